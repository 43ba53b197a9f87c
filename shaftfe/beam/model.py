"""The stepped Timoshenko beam model of a balancer-shaft variant: discretisation, supports,
loads and the assembled matrices (the fast cross-check of the 3D FE).

Model
-----
* Nodes at every segment boundary, bearing centre and edges, attachment-seat centre and edges,
  the clearance station, the hex-socket bottom, extra point loads; then every interval is cut
  into equal elements no longer than ``max_element_mm``.
* Elements and sections: ``shaftfe.beam.elements`` (6 dof per node, IIE Timoshenko element,
  Cowper κ, exact circle-minus-hexagon section at the hex socket).
* Keyways are ignored in the stiffness (they are local); threads use ``Segment.diameter_mm``
  as given (the variant files model threads at the minor diameter).

Supports
--------
``rigid_supports=True`` (Inventor's shaft module): simple supports v = w = 0 at the bearing
centres, tilt free. Otherwise the 2×2 ``Bearing.K_N_per_mm`` acts on (v, w) at the bearing
centre (coupled y-z) and ``tilt_stiffness_Nmm_per_rad`` on (θ_y, θ_z). In both cases u_x is
held at the bearing with ``axial=True`` (it carries the axial force). Torsion: θ_x is held at
every bearing with ``holds_torsion = true``; where none does, the torques of every load pattern
sum to zero (``shaftfe.model.loads.check_torque_path``) and θ_x is pinned at one bearing
(``torsion_node``) only as a gauge for the free rotation about the axis: its reaction is zero to
round-off, and every result reports it (``BeamResult.torsion_gauge_Nmm``). A system that is not
restrained against every rigid-body motion raises ``SolverError`` naming the free motion
(checked on the rigid-body modes, not by the solver).

Loads
-----
Every load of the variant (``shaftfe.model.loads.actions``: the parts' m e ω², the
``[[loads]]`` forces, moments, torques, axial forces, gear meshes and gravity) is an action: a
force F and a moment M about (x, 0, 0), delivered through a band of the shaft. By default each
action acts at its node x (a point load); with ``spread_loads=True`` its transverse force is a
uniform line load over the band (consistent nodal loads, kept per element for the end forces)
and its axial force and moments are spread over the band's nodes by their tributary lengths.
``seed_placement=True`` keeps the seed's placement of the parts' forces (the seat centre, no
moment): with it every seed number is today's. Gravity's body action loads the shaft's own
mass as a line load ρ A g per element. Actions are grouped into load columns (one per speed-law
pattern ``pattern_key`` and load name, so that a case's per-load factors stay exact), solved
from one factorisation (``shaftfe.beam.solve``) and superposed per speed or load case.

Notches carry their Kt for bending, tension and torsion (``shaftfe.beam.scf``) for the
post-processing: every shoulder (a DIN 509 undercut as the shoulder to its bottom diameter),
every groove (Roark's U-notch fit, a DIN 471 ring groove with its corner radius) and every
transverse hole (the Peterson-chart fit DIN 743-2 prints, nominal stresses on the net
section). Grooves and holes are not in the sections' stiffness (like keyways).

Units: mm, N, MPa, t/mm³. Pure functions; NumPy only.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, replace
from types import MappingProxyType

import numpy as np

from shaftfe.beam.elements import (
    DOF_NAMES,
    NDOF,
    RX,
    RY,
    RZ,
    UX,
    UY,
    UZ,
    Sections,
    element_mass,
    element_stiffness,
    section_properties,
)
from shaftfe.beam.scf import (
    KT_GROOVES,
    KT_RING_GROOVES,
    KtResult,
    converged_kt,
    kt_cross_hole,
    kt_shoulder,
    kt_u_notch,
)
from shaftfe.errors import InputError, SolverError
from shaftfe.model.grooves import UNDERCUTS, undercut_at
from shaftfe.model.loads import actions, check_torque_path, pattern_key
from shaftfe.model.validate import source_of, validate_variant

# a conical segment is cut into elements whose end diameters differ by at most this fraction,
# each with its midpoint's section: the midpoint rule on the flexibility ∫ dx / I(x), I ∝ D⁴,
# errs by about (4 ΔD/D)²/24 ≈ 3e-4 per element at 2 % (tests/validation/test_tapers.py)
TAPER_STEP = 0.02

# --------------------------------------------------------------------------- model

@dataclass(frozen=True)
class LoadColumn:
    """One solved load column: the actions of one speed-law pattern (``pattern_key``) and one
    load name, at their written magnitudes. ``LoadCase.factor(column)`` is its factor in a
    case (the attributes are those it reads); ``torque_abs_Nmm`` = Σ |T| and ``axial_abs_N`` =
    Σ |F_x| applied (the scales below which a torque or an axial force is round-off)."""
    name: str
    scales_with: str
    ref_rpm: float
    channel_ref: float
    torque_abs_Nmm: float = 0.0
    axial_abs_N: float = 0.0

    @property
    def factor_name(self) -> str:
        return self.name


@dataclass(frozen=True)
class Support:
    name: str
    node: int
    x_mm: float
    K_N_per_mm: tuple[tuple[float, float], tuple[float, float]] | None   # None = rigid
    axial: bool
    tilt_Nmm_per_rad: float
    C_N: float
    life_exponent: float
    holds_torsion: bool = False


@dataclass(frozen=True)
class BeamNotch:
    """A notch the beam reports Kt × nominal at: a shoulder (``kind`` "shoulder"; a DIN 509
    undercut is one, ``undercut`` its kind), a circumferential groove ("groove"; "ring_groove"
    a DIN 471 one: D its segment's diameter, d its bottom's, r its corner radius) or a
    transverse hole ("cross_hole": D = d the segment's diameter, ``hole_mm`` the hole's; the
    nominal stresses on the net section)."""
    x_mm: float
    node: int
    D_mm: float
    d_mm: float
    r_mm: float
    kt: float            # bending
    kt_in_range: bool
    kt_fit: str
    kt_note: str
    small_side: str      # "left" | "right": side of the smaller diameter ("": a groove's or
    #                      hole's node inside its segment, both sides judged)
    kt_tension: float = 1.0
    kt_torsion: float = 1.0
    kt_tension_in_range: bool = True
    kt_torsion_in_range: bool = True
    kt_tension_note: str = ""
    kt_torsion_note: str = ""
    # a DIN 509 undercut's kind when it is the shoulder's transition (``model.grooves``): d_mm
    # is then its bottom diameter and r_mm its radius, the shoulder DIN 743-2 assesses it as
    undercut: str = ""
    kind: str = "shoulder"
    hole_mm: float = 0.0
    name: str = ""       # "groove <segment>:<i>", "cross hole <segment>:<i>" ("" a shoulder)


@dataclass(frozen=True, eq=False)
class BeamModel:
    name: str
    x: np.ndarray                  # node coordinates, mm (sorted)
    sections: Sections             # per element
    E: float
    G: float
    nu: float
    density: float                 # t/mm³
    supports: tuple[Support, ...]
    rigid_supports: bool
    torsion_node: int              # the torsion gauge (no bearing holds torsion) or unused
    columns: tuple[LoadColumn, ...]
    f: np.ndarray                  # (ndof, n_col) nodal loads per column, N and N·mm
    q: np.ndarray                  # (n_col, n_el, 2) element line loads in (y, z), N/mm
    stations: MappingProxyType     # name -> node index
    notches: tuple[BeamNotch, ...]
    spread_loads: bool
    seed_placement: bool = False
    notes: tuple[str, ...] = ()
    clearance_mm: float | None = None     # the file's smallest clearance at station "clearance"

    @property
    def n_nodes(self) -> int:
        return self.x.shape[0]

    @property
    def n_elements(self) -> int:
        return self.x.shape[0] - 1

    @property
    def L(self) -> np.ndarray:
        return np.diff(self.x)

    @property
    def torsion_held(self) -> bool:
        """True if a bearing holds torsion (else θ_x is pinned at ``torsion_node`` as a gauge)."""
        return any(s.holds_torsion for s in self.supports)


def _validate(variant, max_element_mm: float, rigid_supports: bool) -> None:
    if not (max_element_mm > 0):
        raise InputError("--max-element", "max_element_mm", "> 0", got=max_element_mm)
    validate_variant(variant, springs=not rigid_supports, typed=False)


def _mesh(key_x: np.ndarray, max_len: float) -> np.ndarray:
    key = np.unique(np.round(key_x, 9))
    # merge points closer than 1e-6 mm
    keep = np.concatenate([[True], np.diff(key) > 1e-6])
    key = key[keep]
    nsub = np.maximum(1, np.ceil(np.diff(key) / max_len - 1e-9).astype(int))
    parts = [np.linspace(a, b, n, endpoint=False) for a, b, n in zip(key[:-1], key[1:], nsub,
                                                                       strict=True)]
    return np.concatenate([*parts, key[-1:]])


def _node(x: np.ndarray, xq: float) -> int:
    i = int(np.argmin(np.abs(x - xq)))
    if abs(x[i] - xq) > 1e-6:
        raise AssertionError(f"no node at x = {xq}")
    return i


def build_model(variant, *, rigid_supports: bool = False, max_element_mm: float = 5.0,
                spread_loads: bool = False, kt_fit: str = "roark",
                shear_deformation: bool = True, seed_placement: bool = False) -> BeamModel:
    """Discretise ``variant`` (a ``shaftfe.model.variant.Variant``) into a Timoshenko beam model
    with every load of the variant (``shaftfe.model.loads.actions``).

    ``shear_deformation=False`` gives the Euler-Bernoulli limit (κ → ∞, Φ = 0), e.g. to
    compare with tools that neglect shear. ``seed_placement=True``: the parts' forces at their
    seat centres with no moment (the seed's placement, ``--seed-load-case``)."""
    _validate(variant, max_element_mm, rigid_supports)
    check_torque_path(variant, source_of(variant))
    acts, body = actions(variant, seed_placement=seed_placement)
    x = _node_positions(variant, max_element_mm, acts)
    sec = _element_sections(variant, x, shear_deformation)
    mat = variant.material
    G = mat.E_MPa / (2.0 * (1.0 + mat.nu))
    supports, torsion_node = _supports(variant, x, rigid_supports)
    columns, f, q = _loads(acts, body, x, sec.A * float(mat.density_t_mm3), spread_loads)
    stations = _stations(variant, x)
    notches = tuple(sorted(_shoulders(variant.segments, x, kt_fit)
                           + _grooves_and_holes(variant.segments, x), key=lambda n: n.x_mm))
    return BeamModel(
        name=variant.name, x=x, sections=sec, E=float(mat.E_MPa), G=float(G), nu=float(mat.nu),
        density=float(mat.density_t_mm3), supports=supports,
        rigid_supports=bool(rigid_supports), torsion_node=torsion_node, columns=columns, f=f,
        q=q, stations=MappingProxyType(stations), notches=notches,
        spread_loads=bool(spread_loads), seed_placement=bool(seed_placement),
        notes=_notes(variant, shear_deformation), clearance_mm=variant.clearance_mm)


def _node_positions(variant, max_element_mm: float, acts) -> np.ndarray:
    """Node coordinates: the key points (segment boundaries, bearing centres and edges, seat
    centres and edges, clearance station, hex-socket bottom, every action's point and band),
    every interval cut into equal elements no longer than ``max_element_mm``."""
    segs = variant.segments
    x0, x1 = segs[0].x_start_mm, segs[-1].x_end_mm
    key = [s.x_start_mm for s in segs] + [x1]
    for b in variant.bearings:
        key += [b.x_center_mm, max(x0, b.x_start_mm), min(x1, b.x_end_mm)]
    for a in variant.attachments:
        key += [a.seat_x_start_mm, a.seat_x_end_mm, 0.5 * (a.seat_x_start_mm + a.seat_x_end_mm)]
    if variant.clearance_station_x_mm is not None:
        key.append(variant.clearance_station_x_mm)
    hs = variant.hex_socket
    if hs is not None:
        key.append(x0 + hs.depth_mm if hs.end == "left" else x1 - hs.depth_mm)
    for s in segs:               # a node at every groove's and hole's centre (its notch)
        key += [g.x_center_mm for g in s.grooves if g.kind not in UNDERCUTS]
        key += [h.x_center_mm for h in s.cross_holes]
    for a in acts:               # on the shaft: checked by the loader (model.loads)
        key += [a.x_mm, *a.band_mm]
    for s in segs:               # a cone: elements whose diameters differ by ≤ TAPER_STEP
        if s.conical:
            n = math.ceil(abs(s.d_right_mm - s.diameter_mm)
                          / (TAPER_STEP * min(s.diameter_mm, s.d_right_mm)))
            key += list(np.linspace(s.x_start_mm, s.x_end_mm, n + 1))
    return _mesh(np.clip(np.asarray(key, dtype=float), x0, x1), max_element_mm)


def _element_sections(variant, x: np.ndarray, shear_deformation: bool) -> Sections:
    """Section of every element: the segment containing the element midpoint, minus the hex
    socket where the midpoint lies inside it; κ = ∞ without shear deformation."""
    segs = variant.segments
    x0, x1 = segs[0].x_start_mm, segs[-1].x_end_mm
    ne = x.size - 1
    xm = 0.5 * (x[:-1] + x[1:])
    bounds = np.array([s.x_start_mm for s in segs] + [x1])
    iseg = np.clip(np.searchsorted(bounds, xm, side="right") - 1, 0, len(segs) - 1)
    D = np.array([s.diameter_mm for s in segs])[iseg]
    for k in np.nonzero([segs[i].conical for i in iseg])[0]:    # a cone: its midpoint's
        D[k] = segs[iseg[k]].diameter_at(xm[k])
    hex_af = np.zeros(ne)
    hs = variant.hex_socket
    if hs is not None:
        inside = xm < x0 + hs.depth_mm if hs.end == "left" else xm > x1 - hs.depth_mm
        hex_af[inside] = hs.across_flats_mm
        if np.any(hex_af >= D):
            raise InputError(source_of(variant), "hex_socket.across_flats_mm",
                             "< the segment diameter", got=hs.across_flats_mm)
    sec = section_properties(D, variant.material.nu, hex_af)
    if not shear_deformation:
        sec = replace(sec, kappa=np.full_like(sec.kappa, np.inf))
    return sec


def _supports(variant, x: np.ndarray, rigid_supports: bool) -> tuple[tuple[Support, ...], int]:
    """One ``Support`` per bearing (springs dropped when ``rigid_supports``) and the torsion
    gauge's node: the first axial bearing, else the first bearing (used only when no bearing
    holds torsion, and by the beam rotor's torsional modes)."""
    supports = []
    for b in variant.bearings:
        supports.append(Support(
            name=b.name, node=_node(x, b.x_center_mm), x_mm=b.x_center_mm,
            K_N_per_mm=None if rigid_supports else tuple(tuple(map(float, r))
                                                          for r in b.K_N_per_mm),
            axial=bool(b.axial),
            tilt_Nmm_per_rad=0.0 if rigid_supports else float(b.tilt_stiffness_Nmm_per_rad),
            C_N=float(b.C_N), life_exponent=float(b.life_exponent),
            holds_torsion=bool(getattr(b, "holds_torsion", False))))
    axial = [s for s in supports if s.axial]
    torsion_node = axial[0].node if axial else (supports[0].node if supports else 0)
    return tuple(supports), torsion_node


def _column_of(item) -> tuple:
    return (pattern_key(item), getattr(item, "factor_name", item.name))


def _tributary(x: np.ndarray, lo: float, hi: float) -> tuple[np.ndarray, np.ndarray]:
    """(nodes, weights summing to 1) of the band [lo, hi]: each node's share of the band's
    length (half of each adjacent element inside it); one node with weight 1 for a point."""
    if hi - lo <= 1e-6:
        return np.array([_node(x, 0.5 * (lo + hi))]), np.ones(1)
    i0, i1 = _node(x, lo), _node(x, hi)
    nodes = np.arange(i0, i1 + 1)
    L = np.diff(x[nodes])
    w = np.zeros(nodes.size)
    w[:-1] += 0.5 * L
    w[1:] += 0.5 * L
    return nodes, w / w.sum()


def _loads(acts, body, x: np.ndarray, rho_A: np.ndarray, spread: bool
           ) -> tuple[tuple[LoadColumn, ...], np.ndarray, np.ndarray]:
    """Load columns, their nodal loads (ndof, n_col) and element line loads (n_col, n_el, 2).

    An action at a point: F and M at its node. Spread (``spread``, a band longer than 1e-6 mm):
    the transverse force as a uniform line load over the band (consistent nodal loads), the
    axial force and the moments over the band's nodes by their tributary lengths. A body
    action (gravity): the line load ρ A a of every element (its transverse part)."""
    keys: dict[tuple, int] = {}
    cols: list[dict] = []
    for item in (*acts, *body):
        k = _column_of(item)
        if k not in keys:
            keys[k] = len(cols)
            cols.append(dict(name=k[1], scales_with=item.scales_with,
                             ref_rpm=float(item.ref_rpm), channel_ref=float(item.channel_ref),
                             torque_abs_Nmm=0.0, axial_abs_N=0.0))
    ndof, ne = NDOF * x.size, x.size - 1
    f = np.zeros((ndof, len(cols)))
    q = np.zeros((len(cols), ne, 2))
    xm = 0.5 * (x[:-1] + x[1:])
    for a in acts:
        c = keys[_column_of(a)]
        cols[c]["torque_abs_Nmm"] += abs(a.M_Nmm[0])
        cols[c]["axial_abs_N"] += abs(a.F_N[0])
        lo, hi = sorted(a.band_mm)
        if spread and hi - lo > 1e-6:
            q[c, (xm > lo) & (xm < hi)] += np.array(a.F_N[1:]) / (hi - lo)
            nodes, w = _tributary(x, lo, hi)
            for dof, v in ((UX, a.F_N[0]), (RX, a.M_Nmm[0]), (RY, a.M_Nmm[1]),
                           (RZ, a.M_Nmm[2])):
                if v:
                    f[NDOF * nodes + dof, c] += v * w
        else:
            n = _node(x, a.x_mm)
            f[NDOF * n + np.array([UX, UY, UZ]), c] += a.F_N
            f[NDOF * n + np.array([RX, RY, RZ]), c] += a.M_Nmm
    for b in body:
        c = keys[_column_of(b)]
        q[c] += rho_A[:, None] * np.array(b.accel_mm_s2[1:])[None, :]
    for c in range(len(cols)):
        f[:, c] += _consistent_line_loads(x, q[c])
    return tuple(LoadColumn(**d) for d in cols), f, q


def _stations(variant, x: np.ndarray) -> dict[str, int]:
    """Named stations -> node: attachment-seat centres, bearing centres, the clearance station."""
    stations: dict[str, int] = {}
    for a in variant.attachments:
        lo, hi = sorted((a.seat_x_start_mm, a.seat_x_end_mm))
        stations[a.name] = _node(x, 0.5 * (lo + hi))
    for b in variant.bearings:
        stations[b.name] = _node(x, b.x_center_mm)
    if variant.clearance_station_x_mm is not None:
        stations["clearance"] = _node(x, variant.clearance_station_x_mm)
    return stations


def _shoulders(segs, x: np.ndarray, kt_fit: str) -> tuple[BeamNotch, ...]:
    """A shoulder's ``BeamNotch`` with its Kt in bending, tension and torsion at every diameter step
    between adjacent segments."""
    shoulders = []
    for i, (s0, s1) in enumerate(itertools.pairwise(segs)):
        if abs(s0.d_right_mm - s1.diameter_mm) < 1e-12:
            continue
        Dm, dm = max(s0.d_right_mm, s1.diameter_mm), min(s0.d_right_mm, s1.diameter_mm)
        rho, kind = s0.fillet_mm, ""
        u = undercut_at(segs, i)
        if u is not None:        # a DIN 509 undercut: the shoulder of its bottom diameter
            g = u[2]
            dm, rho, kind = dm - 2.0 * g.depth_mm, g.radius_mm, g.kind
        k, kn, kt = (kt_shoulder(Dm, dm, rho, kt_fit, load)
                     for load in ("bending", "tension", "torsion"))
        shoulders.append(BeamNotch(
            x_mm=s0.x_end_mm, node=_node(x, s0.x_end_mm), D_mm=Dm, d_mm=dm, r_mm=rho,
            undercut=kind,
            kt=k.kt, kt_in_range=k.in_range, kt_fit=kt_fit, kt_note=k.note,
            small_side="left" if s0.d_right_mm < s1.diameter_mm else "right",
            kt_tension=kn.kt, kt_torsion=kt.kt, kt_tension_in_range=kn.in_range,
            kt_torsion_in_range=kt.in_range, kt_tension_note=kn.note,
            kt_torsion_note=kt.note))
    return tuple(shoulders)


def _groove_kt(D: float, g, table: dict) -> dict:
    """{load: KtResult} of groove ``g`` in a Ø``D`` segment, nominal stresses on its bottom
    diameter: the converged Kt where the committed tables hold it (``table``, the model's one
    read of ``scf.converged_kt``: a one-arc U groove of its D, d, ρ; a DIN 471 groove of its D
    and corner radius), else
    Roark's U-notch fit of its depth and corner radius, which for a flat-bottomed groove is an
    upper bound (the U-notch is the narrowest groove of that radius): it reads above the
    converged Kt of every DIN 471 groove measured (reports/benchmarks/ring_grooves.md), and
    on x2_57's 3 mm wide, 1 deep, R1 collar groove the beam's peak with it is 408.6 MPa where
    the axisymmetric model reads 290.8 at 10 000 rpm (a note says so)."""
    d = D - 2.0 * g.depth_mm
    key = (round(D, 6), round(d, 6), round(g.radius_mm, 6))
    if g.kind == "din471":
        row, src = table.get(("din471", *key)), KT_RING_GROOVES
    elif abs(g.width_mm - 2.0 * g.radius_mm) <= 1e-6:
        row, src = table.get(("groove", *key)), KT_GROOVES
    else:
        row, src = None, ""
    if row is not None:
        return {ld: KtResult(row[ld], True, f"converged ({src})") for ld in row}
    flat = g.width_mm > 2.0 * g.radius_mm + 1e-6
    note = (f"a flat-bottomed {'DIN 471 ' if g.kind == 'din471' else ''}groove taken as the "
            "U-notch of its depth and corner radius, the narrowest groove of that radius: an "
            "upper bound, above its converged Kt (every flat-bottomed DIN 471 groove measured "
            "lies between the shoulder's and the U-notch's fits, reports/benchmarks/"
            "ring_grooves.md)" if flat else "")
    out = {}
    for ld in ("bending", "tension", "torsion"):
        k = kt_u_notch(D, g.depth_mm, g.radius_mm, ld)
        first = note if ld == "bending" else ""        # said once (the bending note)
        out[ld] = replace(k, note="; ".join(n for n in (first, k.note) if n))
    return out


def _grooves_and_holes(segs, x: np.ndarray) -> tuple[BeamNotch, ...]:
    """A ``BeamNotch`` at every groove's centre (a DIN 509 undercut is its shoulder's) with
    its Kt (``_groove_kt``), and at every transverse hole's centre (``scf.kt_cross_hole``)."""
    out = []
    table = converged_kt() if any(s.grooves for s in segs) else {}
    for s in segs:
        D = s.diameter_mm
        for j, g in enumerate(s.grooves):
            if g.kind in UNDERCUTS:
                continue
            k = _groove_kt(D, g, table)
            out.append(_mid_notch(f"groove {s.name}:{j}",
                                  "ring_groove" if g.kind == "din471" else "groove",
                                  g.x_center_mm, x, D, D - 2.0 * g.depth_mm, g.radius_mm, k))
        for j, h in enumerate(s.cross_holes):
            k = {ld: kt_cross_hole(D, h.diameter_mm, ld) for ld in
                 ("bending", "tension", "torsion")}
            out.append(_mid_notch(f"cross hole {s.name}:{j}", "cross_hole", h.x_center_mm, x,
                                  D, D, 0.5 * h.diameter_mm, k, h.diameter_mm))
    return tuple(out)


def _mid_notch(name, kind, x_mm, x, D, d, r, k, hole_mm=0.0) -> BeamNotch:
    b, n, t = k["bending"], k["tension"], k["torsion"]
    return BeamNotch(x_mm=x_mm, node=_node(x, x_mm), D_mm=D, d_mm=d, r_mm=r, kt=b.kt,
                     kt_in_range=b.in_range, kt_fit=b.fit, kt_note=b.note, small_side="",
                     kt_tension=n.kt, kt_torsion=t.kt, kt_tension_in_range=n.in_range,
                     kt_torsion_in_range=t.in_range, kt_tension_note=n.note,
                     kt_torsion_note=t.note, kind=kind, hole_mm=hole_mm, name=name)


def _notes(variant, shear_deformation: bool) -> tuple[str, ...]:
    """The model's simplifications, reported with every result."""
    segs = variant.segments
    notes = ["keyways ignored in the stiffness"] if any(s.keyways for s in segs) else []
    if any(s.cross_holes or any(g.kind not in UNDERCUTS for g in s.grooves) for s in segs):
        notes.append("grooves and transverse holes ignored in the stiffness (their Kt at "
                     "their centres)")
    if not shear_deformation:
        notes.append("Euler-Bernoulli limit: shear deformation off")
    if variant.hex_socket is not None:
        notes.append("hex socket: exact circle-minus-hexagon A and I; J = 2I; kappa from the "
                     "equal-area annulus")
    return tuple(notes)


def _consistent_line_loads(x: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Consistent nodal loads of uniform element line loads q (n_el, 2) in (y, z).

    For the IIE element they equal the Euler-Bernoulli ones (qL/2, ±qL²/12): the integrals of
    its displacement shape functions are L/2 and L/12·L independently of Φ."""
    L = np.diff(x)
    f = np.zeros(NDOF * x.size)
    for c, (dv, dr, sgn) in enumerate(((UY, RZ, 1.0), (UZ, RY, -1.0))):
        qe = q[:, c]
        np.add.at(f, NDOF * np.arange(L.size) + dv, 0.5 * qe * L)
        np.add.at(f, NDOF * np.arange(1, L.size + 1) + dv, 0.5 * qe * L)
        np.add.at(f, NDOF * np.arange(L.size) + dr, sgn * qe * L**2 / 12.0)
        np.add.at(f, NDOF * np.arange(1, L.size + 1) + dr, -sgn * qe * L**2 / 12.0)
    return f


# --------------------------------------------------------------------------- assembly

def _element_dofs(ne: int) -> np.ndarray:
    return (NDOF * np.arange(ne)[:, None] + np.arange(2 * NDOF)[None, :])


def assemble_stiffness(model: BeamModel) -> np.ndarray:
    """Dense free-free elastic stiffness (ndof × ndof), no supports."""
    ke = element_stiffness(model.L, model.E, model.G, model.sections)
    ndof = NDOF * model.n_nodes
    K = np.zeros((ndof, ndof))
    dofs = _element_dofs(model.n_elements)
    np.add.at(K, (dofs[:, :, None], dofs[:, None, :]), ke)
    return K


def _support_terms(model: BeamModel) -> tuple[list[tuple[np.ndarray, np.ndarray]], np.ndarray]:
    """Support springs as a list of (dof indices, small stiffness matrix) and the held dofs."""
    terms = []
    fixed = []
    for s in model.supports:
        b = NDOF * s.node
        if s.K_N_per_mm is None:
            fixed += [b + UY, b + UZ]
        else:
            terms.append((np.array([b + UY, b + UZ]), np.asarray(s.K_N_per_mm, dtype=float)))
        if s.tilt_Nmm_per_rad > 0:
            terms.append((np.array([b + RY, b + RZ]), s.tilt_Nmm_per_rad * np.eye(2)))
        if s.axial:
            fixed.append(b + UX)
        if s.holds_torsion:
            fixed.append(b + RX)
    if model.supports and not model.torsion_held:
        fixed.append(NDOF * model.torsion_node + RX)     # the gauge (Σ T = 0 per pattern)
    return terms, np.unique(np.asarray(fixed, dtype=int))


def assemble_mass(model: BeamModel) -> np.ndarray:
    """Dense consistent mass matrix of the shaft alone (t; attachments not included)."""
    me = element_mass(model.L, model.density, model.G, model.E, model.sections)
    ndof = NDOF * model.n_nodes
    M = np.zeros((ndof, ndof))
    dofs = _element_dofs(model.n_elements)
    np.add.at(M, (dofs[:, :, None], dofs[:, None, :]), me)
    return M


def support_stiffness(model: BeamModel) -> tuple[np.ndarray, np.ndarray]:
    """(K_s, constrained dof indices): dense spring/tilt matrix and the rigidly held dofs."""
    ndof = NDOF * model.n_nodes
    Ks = np.zeros((ndof, ndof))
    terms, fixed = _support_terms(model)
    for idx, k in terms:
        Ks[np.ix_(idx, idx)] += k
    return Ks, fixed


def rigid_body_modes(x: np.ndarray, x_ref: float = 0.0, scale: float = 1.0) -> np.ndarray:
    """(ndof, 6) rigid-body modes: translations x, y, z (unit), torsion (θ_x = 1) and small
    rotations about y and z through ``x_ref`` by θ = 1/``scale`` (so the displacement at distance
    ``scale`` is 1)."""
    n = x.size
    R = np.zeros((NDOF * n, 6))
    idx = NDOF * np.arange(n)
    for k in range(4):
        R[idx + k, k] = 1.0
    th = 1.0 / scale
    R[idx + UZ, 4] = -(x - x_ref) * th     # rotation θ about y: w = −θ x, θ_y = θ
    R[idx + RY, 4] = th
    R[idx + UY, 5] = (x - x_ref) * th      # rotation θ about z: v = θ x, θ_z = θ
    R[idx + RZ, 5] = th
    return R


def check_supports(model: BeamModel) -> None:
    """Raise SolverError if the supports leave a rigid-body motion free (singular system).

    The elastic stiffness of a connected beam is positive definite on the complement of the six
    rigid-body modes, so the supported system is regular iff the supports (springs + held dofs)
    restrain every combination of rigid-body modes."""
    if not model.supports:
        raise SolverError(f"beam model {model.name!r} is singular: it has no bearings")
    terms, fixed = _support_terms(model)
    xm = 0.5 * (model.x[0] + model.x[-1])
    Lr = max(model.x[-1] - model.x[0], 1e-12)
    R = rigid_body_modes(model.x, xm, Lr)
    kref = max([np.abs(k).max() for _, k in terms] + [1.0])
    CR = R[fixed]
    Q = CR.T @ CR
    for idx, k in terms:
        Q += R[idx].T @ k @ R[idx] / kref
    w, V = np.linalg.eigh(0.5 * (Q + Q.T))
    tol = 1e-10 * max(w.max(), 1.0)
    free = [V[:, i] for i in range(6) if w[i] <= tol]
    if free:
        names = []
        for v in free:
            for k in np.argsort(-np.abs(v)):
                if abs(v[k]) > 0.3 and DOF_NAMES[k] not in names:
                    names.append(DOF_NAMES[k])
        raise SolverError(
            f"beam model {model.name!r} is singular: the supports do not restrain "
            f"{', '.join(names)} (need one bearing with axial=True and radial support at two "
            "bearings, or tilt stiffness, in both y and z)")


# --------------------------------------------------------------------------- mass properties
