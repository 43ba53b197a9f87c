"""Stepped Timoshenko beam model of a balancer-shaft variant: the fast cross-check of the 3D FE.

Model
-----
* Nodes at every segment boundary, bearing centre and edges, attachment-seat centre and edges,
  the clearance station, the hex-socket bottom, extra point loads; then every interval is cut
  into equal elements no longer than ``max_element_mm``.
* 6 dof per node, in this order: u_x (axial), u_y, u_z, θ_x (torsion), θ_y, θ_z. Rotations are
  right-handed about the axes, so θ_z = dv/dx and θ_y = −dw/dx for Euler-Bernoulli kinematics.
* Element: two-node Timoshenko beam with "interdependent interpolation" (IIE; Przemieniecki,
  *Theory of Matrix Structural Analysis*, 1968, §5.6; Friedman & Kosmatka, Comput. Struct.
  47 (1993) 473-481). Its stiffness is the exact flexibility inverse of a uniform Timoshenko
  beam, so nodal displacements are exact for point loads at nodes (and for uniform distributed
  loads with the consistent nodal loads below) on a piecewise-uniform shaft. Φ = 12 EI/(κ G A L²).
* Shear coefficient: Cowper, J. Appl. Mech. 33 (1966) 335-340, Table 1: solid circle
  κ = 6(1+ν)/(7+6ν); hollow circle κ = 6(1+ν)(1+m²)² / [(7+6ν)(1+m²)² + (20+12ν)m²], m = d_i/D.
* Hex socket (``Variant.hex_socket``): the section is the circle minus the regular hexagon of
  across-flats s, with its EXACT area A = πD²/4 − (√3/2)s² and second moment
  I = πD⁴/64 − 5√3 s⁴/144 (a regular hexagon's I is the same about every centroidal axis).
  Torsion constant J = 2I (polar moment; slightly overestimates the Saint-Venant constant of a
  non-circular hole) and κ from Cowper's hollow circle with the equal-area hole diameter.
  Bending stress there uses W = I/(D/2).
* Keyways are ignored in the stiffness (they are local); threads use ``Segment.diameter_mm``
  as given (the variant files model threads at the minor diameter).

Supports
--------
``rigid_supports=True`` (Inventor's shaft module): simple supports v = w = 0 at the bearing
centres, tilt free. Otherwise the 2×2 ``Bearing.K_N_per_mm`` acts on (v, w) at the bearing
centre (coupled y-z) and ``tilt_stiffness_Nmm_per_rad`` on (θ_y, θ_z). In both cases u_x is
held at the bearing with ``axial=True`` and θ_x at that same bearing centre (the seed removes the
rotation about the axis at the bearings; a single torsion hold is enough for a static check and
carries all the torque). A system that is not restrained against every rigid-body motion raises
``SolverError`` naming the free motion (checked on the rigid-body modes, not by the solver).

Loads
-----
Each attachment's centrifugal force m e ω² (``Attachment.force_N``) acts in the direction
``angle_deg`` (0° = +y, 90° = +z) as a point load at the seat centre (default) or, with
``spread_loads=True``, as a uniform line load over the seat (consistent nodal loads). Loads scale
with ω²: the model is solved once per unit ω² (rad²/s²) and scaled for every rpm. Extra static
``PointLoad`` s (forces and a torque) may be added; they do not scale with rpm.

Results
-------
Per rpm (``BeamResult``): bearing reactions (vector, magnitude, ISO 281 basic L10h = (C/P)^p 10⁶ /
(60 n)), deflection line and named-station deflections, bending moment/torque at both ends of
every element (jumps at tilt springs are kept), nominal bending stress σ = M/W (32 M/(π d³) for a
solid section; at a shoulder each side uses its own diameter, so the maximum is on the smaller
one), τ = T (D/2)/J (16 T/(π d³) solid), von Mises √(σ² + 3τ²), its maximum and x, and at each
shoulder Kt (``shaftfe.beam.scf``, bending fit) × the nominal von Mises stress on the smaller
diameter at the shoulder (a torsion Kts is not modelled: the seed's loads carry no torque).
Reactions are the forces the supports exert ON the shaft (bearing load = −reaction).

Units: mm, N, MPa, t/mm³; rpm for speeds. Pure functions; NumPy/SciPy vectorised.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from types import MappingProxyType

import numpy as np

from shaftfe.beam.scf import kt_shoulder
from shaftfe.errors import InputError, SolverError
from shaftfe.model.validate import source_of, validate_variant

NDOF = 6
UX, UY, UZ, RX, RY, RZ = range(NDOF)
DOF_NAMES = ("axial translation (x)", "translation in y", "translation in z",
             "torsion (rotation about x)", "rotation about y", "rotation about z")


# --------------------------------------------------------------------------- sections

def cowper_kappa(nu, m=0.0):
    """Cowper (1966) shear coefficient of a (hollow) circle, m = inner/outer diameter."""
    nu = np.asarray(nu, dtype=float)
    m2 = np.asarray(m, dtype=float) ** 2
    a = (1.0 + m2) ** 2
    return 6.0 * (1.0 + nu) * a / ((7.0 + 6.0 * nu) * a + (20.0 + 12.0 * nu) * m2)


def hexagon_area_inertia(s):
    """Area and centroidal second moment of a regular hexagon with across-flats ``s``."""
    s = np.asarray(s, dtype=float)
    return 0.5 * math.sqrt(3.0) * s**2, 5.0 * math.sqrt(3.0) / 144.0 * s**4


@dataclass(frozen=True, eq=False)
class Sections:
    """Per-element section properties (arrays of length n_elements)."""
    D: np.ndarray        # outer diameter, mm
    A: np.ndarray        # area, mm²
    I: np.ndarray        # second moment (isotropic), mm⁴  # noqa: E741
    J: np.ndarray        # torsion constant, mm⁴
    kappa: np.ndarray    # shear coefficient
    W: np.ndarray        # bending section modulus I/(D/2), mm³
    Wt: np.ndarray       # torsion section modulus J/(D/2), mm³
    hollow: np.ndarray   # bool: hex socket


def section_properties(D, nu: float, hex_af=None) -> Sections:
    """Solid circle of diameter D, or circle minus hexagon (across-flats ``hex_af``, 0 = none)."""
    D = np.asarray(D, dtype=float)
    s = np.zeros_like(D) if hex_af is None else np.broadcast_to(np.asarray(hex_af, float), D.shape)
    A_h, I_h = hexagon_area_inertia(s)
    A = 0.25 * math.pi * D**2 - A_h
    I = math.pi * D**4 / 64.0 - I_h  # noqa: E741
    J = 2.0 * I
    m = np.sqrt(4.0 * A_h / math.pi) / D
    kappa = cowper_kappa(nu, m)
    return Sections(D=D, A=A, I=I, J=J, kappa=kappa, W=I / (0.5 * D), Wt=J / (0.5 * D),
                    hollow=s > 0)


# --------------------------------------------------------------------------- elements

def timoshenko_bending_stiffness(L, EI, kGA):
    """(n, 4, 4) IIE Timoshenko stiffness for one plane, dofs (v1, θ1, v2, θ2), θ = dv/dx."""
    L, EI, kGA = (np.asarray(v, dtype=float) for v in (L, EI, kGA))
    phi = 12.0 * EI / (kGA * L**2)
    c = EI / ((1.0 + phi) * L**3)
    k = np.empty((*L.shape, 4, 4))
    L2 = L**2
    k[..., 0, :] = np.stack([12 + 0 * L, 6 * L, -12 + 0 * L, 6 * L], -1)
    k[..., 1, :] = np.stack([6 * L, (4 + phi) * L2, -6 * L, (2 - phi) * L2], -1)
    k[..., 2, :] = np.stack([-12 + 0 * L, -6 * L, 12 + 0 * L, -6 * L], -1)
    k[..., 3, :] = np.stack([6 * L, (2 - phi) * L2, -6 * L, (4 + phi) * L2], -1)
    return k * c[..., None, None]


# local dof indices (of the 12) for the two bending planes
_XY = np.array([UY, RZ, NDOF + UY, NDOF + RZ])
_XZ = np.array([UZ, RY, NDOF + UZ, NDOF + RY])
_XZ_SIGN = np.array([1.0, -1.0, 1.0, -1.0])   # θ_y = −dw/dx


def element_stiffness(L, E, G, sec: Sections):
    """(n, 12, 12) stiffness of 3D Timoshenko shaft elements (dofs per node: ux uy uz rx ry rz).

    Written per element so that a consistent mass and gyroscopic matrix can be assembled the
    same way later (rotor dynamics)."""
    L = np.asarray(L, dtype=float)
    n = L.shape[0]
    k = np.zeros((n, 2 * NDOF, 2 * NDOF))
    ea = E * sec.A / L
    gj = G * sec.J / L
    for (i, j), sgn in (((UX, UX), 1), ((UX, NDOF + UX), -1), ((NDOF + UX, UX), -1),
                        ((NDOF + UX, NDOF + UX), 1)):
        k[:, i, j] = sgn * ea
    for (i, j), sgn in (((RX, RX), 1), ((RX, NDOF + RX), -1), ((NDOF + RX, RX), -1),
                        ((NDOF + RX, NDOF + RX), 1)):
        k[:, i, j] = sgn * gj
    kb = timoshenko_bending_stiffness(L, E * sec.I, sec.kappa * G * sec.A)
    k[:, _XY[:, None], _XY[None, :]] = kb
    k[:, _XZ[:, None], _XZ[None, :]] = kb * np.outer(_XZ_SIGN, _XZ_SIGN)
    return k


def timoshenko_bending_mass(L, rhoA, rhoI, phi):
    """(n, 4, 4) consistent mass of the IIE Timoshenko element, dofs (v1, θ1, v2, θ2):
    translational + rotary inertia parts (Przemieniecki 1968, §11; Friedman & Kosmatka 1993)."""
    L, rhoA, rhoI, p = (np.asarray(v, dtype=float) for v in (L, rhoA, rhoI, phi))
    p2 = p**2
    ct = rhoA * L / (1.0 + p) ** 2
    t11 = 13 / 35 + 7 * p / 10 + p2 / 3
    t12 = (11 / 210 + 11 * p / 120 + p2 / 24) * L
    t13 = 9 / 70 + 3 * p / 10 + p2 / 6
    t14 = -(13 / 420 + 3 * p / 40 + p2 / 24) * L
    t22 = (1 / 105 + p / 60 + p2 / 120) * L**2
    t24 = -(1 / 140 + p / 60 + p2 / 120) * L**2
    mt = np.stack([np.stack([t11, t12, t13, t14], -1),
                   np.stack([t12, t22, -t14, t24], -1),
                   np.stack([t13, -t14, t11, -t12], -1),
                   np.stack([t14, t24, -t12, t22], -1)], -2) * ct[..., None, None]
    cr = rhoI / ((1.0 + p) ** 2 * L)
    r11 = 6 / 5 + 0 * L
    r12 = (1 / 10 - p / 2) * L
    r22 = (2 / 15 + p / 6 + p2 / 3) * L**2
    r24 = (-1 / 30 - p / 6 + p2 / 6) * L**2
    mr = np.stack([np.stack([r11, r12, -r11, r12], -1),
                   np.stack([r12, r22, -r12, r24], -1),
                   np.stack([-r11, -r12, r11, -r12], -1),
                   np.stack([r12, r24, -r12, r22], -1)], -2) * cr[..., None, None]
    return mt + mr


def element_mass(L, rho, G, E, sec: Sections):
    """(n, 12, 12) consistent mass of the 3D shaft element (axial and torsion linear, bending
    IIE Timoshenko with rotary inertia). Gyroscopic terms are not included (issue 6)."""
    L = np.asarray(L, dtype=float)
    n = L.shape[0]
    m = np.zeros((n, 2 * NDOF, 2 * NDOF))
    for d, c in ((UX, rho * sec.A * L / 6.0), (RX, rho * sec.J * L / 6.0)):
        m[:, d, d] = m[:, NDOF + d, NDOF + d] = 2.0 * c
        m[:, d, NDOF + d] = m[:, NDOF + d, d] = c
    phi = 12.0 * E * sec.I / (sec.kappa * G * sec.A * L**2)
    mb = timoshenko_bending_mass(L, rho * sec.A, rho * sec.I, phi)
    m[:, _XY[:, None], _XY[None, :]] = mb
    m[:, _XZ[:, None], _XZ[None, :]] = mb * np.outer(_XZ_SIGN, _XZ_SIGN)
    return m


# --------------------------------------------------------------------------- model

@dataclass(frozen=True)
class PointLoad:
    """A static point load (does not scale with rpm): forces in N, torque about x in N·mm."""
    x_mm: float
    Fx_N: float = 0.0
    Fy_N: float = 0.0
    Fz_N: float = 0.0
    Mx_Nmm: float = 0.0
    name: str = ""


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


@dataclass(frozen=True)
class Shoulder:
    x_mm: float
    node: int
    D_mm: float
    d_mm: float
    r_mm: float
    kt: float
    kt_in_range: bool
    kt_fit: str
    kt_note: str
    small_side: str      # "left" | "right": side of the smaller diameter


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
    torsion_node: int
    load_unit: np.ndarray          # (ndof,) nodal load per unit ω² (N s²)
    load_static: np.ndarray        # (ndof,) static extra loads
    q_unit: np.ndarray             # (n_el, 2) line load per unit ω² in (y, z), N/mm per rad²/s²
    stations: MappingProxyType     # name -> node index
    shoulders: tuple[Shoulder, ...]
    spread_loads: bool
    notes: tuple[str, ...] = ()

    @property
    def n_nodes(self) -> int:
        return self.x.shape[0]

    @property
    def n_elements(self) -> int:
        return self.x.shape[0] - 1

    @property
    def L(self) -> np.ndarray:
        return np.diff(self.x)


def _validate(variant, max_element_mm: float, rigid_supports: bool) -> None:
    if not (max_element_mm > 0):
        raise InputError("--max-element", "max_element_mm", "> 0", got=max_element_mm)
    validate_variant(variant, springs=not rigid_supports)


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
                extra_loads: Sequence[PointLoad] = (), shear_deformation: bool = True
                ) -> BeamModel:
    """Discretise ``variant`` (a ``shaftfe.model.variant.Variant``) into a Timoshenko beam model.

    ``shear_deformation=False`` gives the Euler-Bernoulli limit (κ → ∞, Φ = 0), e.g. to
    compare with tools that neglect shear."""
    _validate(variant, max_element_mm, rigid_supports)
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
    for p in extra_loads:
        if not (x0 - 1e-9 <= p.x_mm <= x1 + 1e-9):
            raise InputError("extra_loads", "x_mm", f"in [{x0}, {x1}]", got=p.x_mm)
        key.append(p.x_mm)
    x = _mesh(np.clip(np.asarray(key, dtype=float), x0, x1), max_element_mm)
    ne = x.size - 1

    # sections per element (segment containing the element midpoint)
    xm = 0.5 * (x[:-1] + x[1:])
    bounds = np.array([s.x_start_mm for s in segs] + [x1])
    iseg = np.clip(np.searchsorted(bounds, xm, side="right") - 1, 0, len(segs) - 1)
    D = np.array([s.diameter_mm for s in segs])[iseg]
    hex_af = np.zeros(ne)
    if hs is not None:
        inside = xm < x0 + hs.depth_mm if hs.end == "left" else xm > x1 - hs.depth_mm
        hex_af[inside] = hs.across_flats_mm
        if np.any(hex_af >= D):
            raise InputError(source_of(variant), "hex_socket.across_flats_mm",
                             "< the segment diameter", got=hs.across_flats_mm)
    mat = variant.material
    sec = section_properties(D, mat.nu, hex_af)
    if not shear_deformation:
        sec = replace(sec, kappa=np.full_like(sec.kappa, np.inf))
    G = mat.E_MPa / (2.0 * (1.0 + mat.nu))

    # supports
    supports = []
    for b in variant.bearings:
        supports.append(Support(
            name=b.name, node=_node(x, b.x_center_mm), x_mm=b.x_center_mm,
            K_N_per_mm=None if rigid_supports else tuple(tuple(map(float, r))
                                                          for r in b.K_N_per_mm),
            axial=bool(b.axial),
            tilt_Nmm_per_rad=0.0 if rigid_supports else float(b.tilt_stiffness_Nmm_per_rad),
            C_N=float(b.C_N), life_exponent=float(b.life_exponent)))
    axial = [s for s in supports if s.axial]
    torsion_node = axial[0].node if axial else (supports[0].node if supports else 0)

    # loads per unit ω²
    ndof = NDOF * x.size
    f_unit = np.zeros(ndof)
    q_unit = np.zeros((ne, 2))
    stations: dict[str, int] = {}
    for a in variant.attachments:
        f1 = a.mass_kg * a.eccentricity_mm * 1e-3          # N per (rad/s)²
        ang = math.radians(a.angle_deg)
        dirv = np.array([math.cos(ang), math.sin(ang)])
        lo, hi = sorted((a.seat_x_start_mm, a.seat_x_end_mm))
        xc = 0.5 * (lo + hi)
        stations[a.name] = _node(x, xc)
        if spread_loads and hi - lo > 1e-6:
            in_seat = (xm > lo) & (xm < hi)
            q_unit[in_seat] += f1 / (hi - lo) * dirv
        else:
            n = stations[a.name]
            f_unit[NDOF * n + UY] += f1 * dirv[0]
            f_unit[NDOF * n + UZ] += f1 * dirv[1]
    if spread_loads:
        f_unit += _consistent_line_loads(x, q_unit)
    f_static = np.zeros(ndof)
    for p in extra_loads:
        n = _node(x, p.x_mm)
        f_static[NDOF * n + np.array([UX, UY, UZ, RX])] += [p.Fx_N, p.Fy_N, p.Fz_N, p.Mx_Nmm]
    for b in variant.bearings:
        stations[b.name] = _node(x, b.x_center_mm)
    if variant.clearance_station_x_mm is not None:
        stations["clearance"] = _node(x, variant.clearance_station_x_mm)

    # shoulders
    shoulders = []
    for s0, s1 in itertools.pairwise(segs):
        if abs(s0.diameter_mm - s1.diameter_mm) < 1e-12:
            continue
        Dm, dm = max(s0.diameter_mm, s1.diameter_mm), min(s0.diameter_mm, s1.diameter_mm)
        k = kt_shoulder(Dm, dm, s0.fillet_mm, kt_fit)
        shoulders.append(Shoulder(
            x_mm=s0.x_end_mm, node=_node(x, s0.x_end_mm), D_mm=Dm, d_mm=dm, r_mm=s0.fillet_mm,
            kt=k.kt, kt_in_range=k.in_range, kt_fit=kt_fit, kt_note=k.note,
            small_side="left" if s0.diameter_mm < s1.diameter_mm else "right"))

    notes = ["keyways ignored in the stiffness"] if any(s.keyways for s in segs) else []
    if not shear_deformation:
        notes.append("Euler-Bernoulli limit: shear deformation off")
    if hs is not None:
        notes.append("hex socket: exact circle-minus-hexagon A and I; J = 2I; kappa from the "
                     "equal-area annulus")
    return BeamModel(
        name=variant.name, x=x, sections=sec, E=float(mat.E_MPa), G=float(G), nu=float(mat.nu),
        density=float(mat.density_t_mm3), supports=tuple(supports),
        rigid_supports=bool(rigid_supports), torsion_node=torsion_node, load_unit=f_unit,
        load_static=f_static, q_unit=q_unit, stations=MappingProxyType(stations),
        shoulders=tuple(shoulders), spread_loads=bool(spread_loads), notes=tuple(notes))


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


# --------------------------------------------------------------------------- assembly/solve

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
    if model.supports:
        fixed.append(NDOF * model.torsion_node + RX)
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


@dataclass(frozen=True, eq=False)
class UnitSolution:
    """Displacements for the centrifugal loads per unit ω² (column 0) and for the static extra
    loads (column 1); reactions in the same two columns."""
    model: BeamModel
    u: np.ndarray                 # (ndof, 2)
    r: np.ndarray                 # (ndof, 2) support reactions on the shaft, K u − f
    end_forces: np.ndarray        # (n_el, 12, 2) element end forces (internal, on element)
    relative_residual: float = 0.0   # max over the load columns of ‖K u − F‖/‖F‖ (free dofs)
    backward_error: float = 0.0      # componentwise (Oettli-Prager), checked ≤ RESIDUAL_TOL
    cond_estimate: float = math.nan  # 1-norm condition estimate of the supported K (Hager)


_BAND = 2 * NDOF - 1              # upper bandwidth of the assembled stiffness
RESIDUAL_TOL = 1e-8               # every solve: componentwise backward error below this


def solve_unit(model: BeamModel) -> UnitSolution:
    """Assemble (banded), apply supports and solve once for the unit-ω² and static load cases.

    Held dofs are eliminated; the reduced matrix keeps the 11-wide band, so the solve is a
    banded Cholesky factorisation (O(n))."""
    from scipy.linalg import LinAlgError, cho_solve_banded, cholesky_banded

    check_supports(model)
    ndof = NDOF * model.n_nodes
    ke = element_stiffness(model.L, model.E, model.G, model.sections)
    dofs = _element_dofs(model.n_elements)
    terms, fixed = _support_terms(model)
    rows = [np.broadcast_to(dofs[:, :, None], ke.shape).ravel()]
    cols = [np.broadcast_to(dofs[:, None, :], ke.shape).ravel()]
    vals = [ke.ravel()]
    for idx, k in terms:
        rows.append(np.repeat(idx, idx.size))
        cols.append(np.tile(idx, idx.size))
        vals.append(k.ravel())
    rows, cols, vals = (np.concatenate(v) for v in (rows, cols, vals))
    red = np.full(ndof, -1)
    free = np.setdiff1d(np.arange(ndof), fixed)
    red[free] = np.arange(free.size)
    ri, ci = red[rows], red[cols]
    keep = (ri >= 0) & (ci >= 0) & (ci >= ri)
    ri, ci, vals = ri[keep], ci[keep], vals[keep]
    nf = free.size
    ab = np.bincount((_BAND + ri - ci) * nf + ci, weights=vals,
                     minlength=(_BAND + 1) * nf).reshape(_BAND + 1, nf)
    F = np.stack([model.load_unit, model.load_static], axis=1)
    # symmetric Jacobi scaling D K D (translations in N/mm, rotations in N·mm/rad: the scaled
    # matrix has a unit diagonal) and one step of iterative refinement against the unscaled
    # triplets (issue 8: stiffness 1 … 1e12 N/mm)
    d = 1.0 / np.sqrt(ab[_BAND])
    j = np.arange(nf)
    ab = ab * np.stack([d[np.clip(j - (_BAND - b), 0, nf - 1)] for b in range(_BAND + 1)]) * d
    try:
        c = cholesky_banded(ab, lower=False, check_finite=True)
    except LinAlgError as exc:    # pragma: no cover - guarded by check_supports
        raise SolverError(f"beam model {model.name!r}: stiffness not positive definite "
                          f"({exc})") from None
    Kr = _reduced_matrix(ri, ci, vals, nf)
    u = np.zeros((ndof, 2))
    uf = d[:, None] * cho_solve_banded((c, False), d[:, None] * F[free])
    uf += d[:, None] * cho_solve_banded((c, False), d[:, None] * (F[free] - Kr @ uf))
    u[free] = uf
    relres, berr, cond = _solve_checks(Kr, d, c, uf, F[free], model.name)
    # element end forces (internal): K_e u_e minus the fixed-end forces of element line loads
    ue = u[dofs]                                            # (ne, 12, 2)
    fe = np.einsum("eij,ejc->eic", ke, ue)
    # reactions: r = K_elastic u − F (= −K_spring u at springs, the held force at held dofs)
    r = np.stack([np.bincount(dofs.ravel(), weights=fe[:, :, k].ravel(), minlength=ndof)
                  for k in range(2)], axis=1) - F
    if model.spread_loads:
        fe[:, :, 0] -= _element_fixed_end_loads(model.L, model.q_unit)
    return UnitSolution(model=model, u=u, r=r, end_forces=fe, relative_residual=relres,
                        backward_error=berr, cond_estimate=cond)


def _reduced_matrix(ri, ci, vals, nf):
    """The reduced stiffness as a full symmetric CSR matrix from its upper-triangle triplets."""
    import scipy.sparse as sp

    up = sp.csr_matrix((vals, (ri, ci)), shape=(nf, nf))
    return (up + sp.triu(up, 1, format="csr").T).tocsr()


def _solve_checks(K, d, c, u, F, name) -> tuple[float, float, float]:
    """Residual checks of the reduced system K u = F (K rebuilt from its triplets, not from
    the factor), per load column, worst column reported:

    * relative residual ‖K u − F‖₂/‖F‖₂ (reported). Its floor for the exactly rounded u is
      ≈ eps ‖K‖ ‖u‖/‖F‖, which short elements (seat edges 0.5 mm apart: 3e-9) and soft
      supports (rigid motion ≫ bending: 3e-5 at 1 N/mm on a 400 mm shaft) push above 1e-8;
    * componentwise backward error ω = maxᵢ |K u − F|ᵢ / (|K| |u| + |F|)ᵢ (Oettli-Prager; what
      SuperLU calls BERR), scale- and unit-invariant: ~1e-16 for a stable solve. The solve
      fails (SolverError) if ω > ``RESIDUAL_TOL``;
    * Hager's 1-norm estimate of cond₁(K) = ‖K‖₁ ‖K⁻¹‖₁ (``onenormest`` on the solve with the
      factor of D K D, K⁻¹ = D (DKD)⁻¹ D)."""
    from scipy.linalg import cho_solve_banded
    from scipy.sparse.linalg import LinearOperator, onenormest

    nf = K.shape[0]
    fn = np.linalg.norm(F, axis=0)
    r = K @ u - F
    rn = np.linalg.norm(r, axis=0)
    relres = float(max((a / b for a, b in zip(rn, fn, strict=True) if b > 0), default=0.0))
    den = abs(K) @ np.abs(u) + np.abs(F)
    ratio = np.divide(np.abs(r), den, out=np.zeros_like(den), where=den > 0)
    berr = float(ratio.max()) if ratio.size else 0.0
    if not (berr <= RESIDUAL_TOL):
        raise SolverError(f"beam model {name!r}: the linear solve did not converge "
                          f"(backward error {berr:.2e}, relative residual {relres:.2e}; limit "
                          f"{RESIDUAL_TOL:g})")
    cond = math.nan
    if nf >= 2:
        def inv(b):
            b = np.asarray(b, dtype=float)
            dd = d if b.ndim == 1 else d[:, None]
            return dd * cho_solve_banded((c, False), dd * b)
        op = LinearOperator((nf, nf), matvec=inv, rmatvec=inv, matmat=inv, dtype=float)
        cond = float(abs(K).sum(axis=0).max() * onenormest(op))
    return relres, berr, cond


def _element_fixed_end_loads(L: np.ndarray, q: np.ndarray) -> np.ndarray:
    """(n_el, 12) consistent nodal loads of each element's own line load."""
    f = np.zeros((L.size, 2 * NDOF))
    for c, (dv, dr, sgn) in enumerate(((UY, RZ, 1.0), (UZ, RY, -1.0))):
        qe = q[:, c]
        f[:, dv] = f[:, NDOF + dv] = 0.5 * qe * L
        f[:, dr] = sgn * qe * L**2 / 12.0
        f[:, NDOF + dr] = -sgn * qe * L**2 / 12.0
    return f


# --------------------------------------------------------------------------- results

@dataclass(frozen=True)
class BearingResult:
    name: str
    x_mm: float
    Fy_N: float           # reaction on the shaft
    Fz_N: float
    F_N: float            # radial magnitude (= bearing load P)
    Fx_N: float
    L10h: float           # ISO 281 basic rating life, hours (inf if unloaded or rpm = 0)


@dataclass(frozen=True)
class StationResult:
    x_mm: float
    uy_mm: float
    uz_mm: float
    u_mm: float


@dataclass(frozen=True)
class NotchResult:
    x_mm: float
    D_mm: float
    d_mm: float
    r_mm: float
    kt: float
    kt_in_range: bool
    kt_note: str
    sigma_nom_MPa: float      # von Mises nominal on the smaller diameter at the shoulder
    sigma_peak_MPa: float     # kt × sigma_nom


@dataclass(frozen=True, eq=False)
class BeamResult:
    name: str
    rpm: float
    rigid_supports: bool
    x: np.ndarray             # nodes, mm
    uy: np.ndarray
    uz: np.ndarray
    u: np.ndarray             # |(uy, uz)|
    stations: MappingProxyType    # name -> StationResult
    bearings: tuple[BearingResult, ...]
    x_sec: np.ndarray         # (2 n_el,) element-end stations: start, end of each element
    d_sec: np.ndarray         # outer diameter at those stations
    My: np.ndarray            # bending moment about y, N·mm
    Mz: np.ndarray
    M: np.ndarray
    T: np.ndarray             # torque, N·mm
    sigma: np.ndarray         # nominal bending stress, MPa
    tau: np.ndarray           # nominal torsional shear stress, MPa
    sigma_vm: np.ndarray      # von Mises of (sigma, tau)
    max_sigma_vm_MPa: float
    x_max_sigma_vm_mm: float
    notches: tuple[NotchResult, ...]
    max_peak_MPa: float       # max(nominal von Mises, Kt × nominal at shoulders)
    x_max_peak_mm: float
    notes: tuple[str, ...] = field(default_factory=tuple)
    relative_residual: float = 0.0    # of the one supported solve (UnitSolution)
    backward_error: float = 0.0       # componentwise backward error of that solve
    cond_estimate: float = math.nan   # 1-norm condition estimate of the supported stiffness

    @property
    def max_deflection_mm(self) -> float:
        return float(self.u.max())

    def to_dict(self, lines: bool = False) -> dict:
        def fin(v):
            return None if not math.isfinite(v) else v
        d = {
            "variant": self.name, "rpm": self.rpm, "rigid_supports": self.rigid_supports,
            "bearings": [{"name": b.name, "x_mm": b.x_mm, "Fy_N": b.Fy_N, "Fz_N": b.Fz_N,
                          "F_N": b.F_N, "L10h": fin(b.L10h)} for b in self.bearings],
            "stations": {k: {"x_mm": s.x_mm, "uy_mm": s.uy_mm, "uz_mm": s.uz_mm,
                             "u_mm": s.u_mm} for k, s in self.stations.items()},
            "max_deflection_mm": self.max_deflection_mm,
            "max_sigma_vm_nominal_MPa": self.max_sigma_vm_MPa,
            "x_max_sigma_vm_nominal_mm": self.x_max_sigma_vm_mm,
            "max_sigma_vm_with_kt_MPa": fin(self.max_peak_MPa),
            "x_max_sigma_vm_with_kt_mm": self.x_max_peak_mm,
            "notches": [{"x_mm": n.x_mm, "D_mm": n.D_mm, "d_mm": n.d_mm, "r_mm": n.r_mm,
                         "kt": fin(n.kt), "kt_in_range": n.kt_in_range, "kt_note": n.kt_note,
                         "sigma_nom_MPa": n.sigma_nom_MPa, "sigma_peak_MPa": fin(n.sigma_peak_MPa)}
                        for n in self.notches],
            "notes": list(self.notes),
            "solve": {"relative_residual": self.relative_residual,
                      "backward_error": self.backward_error,
                      "cond_estimate": fin(self.cond_estimate)},
        }
        if lines:
            d["lines"] = {"x_mm": self.x.tolist(), "uy_mm": self.uy.tolist(),
                          "uz_mm": self.uz.tolist(), "x_sec_mm": self.x_sec.tolist(),
                          "M_Nmm": self.M.tolist(), "sigma_vm_MPa": self.sigma_vm.tolist()}
        return d


def l10h(C_N: float, P_N: float, rpm: float, p: float = 3.0) -> float:
    """ISO 281 basic rating life in hours: (C/P)^p · 10⁶ / (60 n)."""
    if P_N <= 0 or rpm <= 0:
        return math.inf
    return (C_N / P_N) ** p * 1e6 / (60.0 * rpm)


def omega(rpm: float) -> float:
    return rpm * 2.0 * math.pi / 60.0


def result_at(sol: UnitSolution, rpm: float) -> BeamResult:
    """Scale the unit solution to ``rpm`` (centrifugal loads ∝ ω²) and post-process."""
    m = sol.model
    w2 = omega(rpm) ** 2
    coef = np.array([w2, 1.0])
    u = sol.u @ coef
    r = sol.r @ coef
    fe = sol.end_forces @ coef                                  # (ne, 12)
    uy, uz = u[UY::NDOF], u[UZ::NDOF]
    umag = np.hypot(uy, uz)
    stations = {k: StationResult(float(m.x[i]), float(uy[i]), float(uz[i]), float(umag[i]))
                for k, i in m.stations.items()}
    bearings = []
    for s in m.supports:
        b = NDOF * s.node
        Fy, Fz, Fx = float(r[b + UY]), float(r[b + UZ]), float(r[b + UX]) if s.axial else 0.0
        F = math.hypot(Fy, Fz)
        bearings.append(BearingResult(s.name, s.x_mm, Fy, Fz, F, Fx,
                                      l10h(s.C_N, F, rpm, s.life_exponent)))
    # internal resultants at element ends: start = −f(start), end = +f(end)
    My = np.stack([-fe[:, RY], fe[:, NDOF + RY]], 1).ravel()
    Mz = np.stack([-fe[:, RZ], fe[:, NDOF + RZ]], 1).ravel()
    T = np.stack([-fe[:, RX], fe[:, NDOF + RX]], 1).ravel()
    M = np.hypot(My, Mz)
    x_sec = np.stack([m.x[:-1], m.x[1:]], 1).ravel()
    sec = m.sections
    W = np.repeat(sec.W, 2)
    Wt = np.repeat(sec.Wt, 2)
    sigma = M / W
    tau = np.abs(T) / Wt
    vm = np.sqrt(sigma**2 + 3.0 * tau**2)
    imax = int(np.argmax(vm))
    notches = []
    for sh in m.shoulders:
        # element on the small-diameter side of the shoulder node
        e = sh.node - 1 if sh.small_side == "left" else sh.node
        k = 2 * e + (1 if sh.small_side == "left" else 0)
        s_nom = float(vm[k])
        notches.append(NotchResult(sh.x_mm, sh.D_mm, sh.d_mm, sh.r_mm, sh.kt, sh.kt_in_range,
                                   sh.kt_note, s_nom, sh.kt * s_nom))
    peak, xpeak = float(vm[imax]), float(x_sec[imax])
    for nt in notches:
        if nt.sigma_peak_MPa > peak:
            peak, xpeak = nt.sigma_peak_MPa, nt.x_mm
    return BeamResult(
        name=m.name, rpm=float(rpm), rigid_supports=m.rigid_supports, x=m.x, uy=uy, uz=uz,
        u=umag, stations=MappingProxyType(stations), bearings=tuple(bearings), x_sec=x_sec,
        d_sec=np.repeat(sec.D, 2), My=My, Mz=Mz, M=M, T=T, sigma=sigma, tau=tau, sigma_vm=vm,
        max_sigma_vm_MPa=float(vm[imax]), x_max_sigma_vm_mm=float(x_sec[imax]),
        notches=tuple(notches), max_peak_MPa=peak, x_max_peak_mm=xpeak, notes=m.notes,
        relative_residual=sol.relative_residual, backward_error=sol.backward_error,
        cond_estimate=sol.cond_estimate)


def solve(model: BeamModel, rpm: float | Sequence[float]) -> tuple[BeamResult, ...]:
    """Solve once and return one ``BeamResult`` per rpm."""
    rpms = [rpm] if isinstance(rpm, (int, float)) else list(rpm)
    for v in rpms:
        if not (math.isfinite(v) and v >= 0):
            raise InputError("--rpm", "rpm", ">= 0", got=v)
    sol = solve_unit(model)
    return tuple(result_at(sol, v) for v in rpms)


def analyse(variant, rpm: float | Sequence[float], **options) -> tuple[BeamResult, ...]:
    """``build_model`` + ``solve`` in one call (options as for ``build_model``)."""
    return solve(build_model(variant, **options), rpm)


# --------------------------------------------------------------------------- mass properties

def shaft_volume_mm3(variant) -> float:
    """Volume of the stepped shaft from its segments minus the hex socket (fillets, keyways and
    threads ignored)."""
    v = sum(0.25 * math.pi * s.diameter_mm**2 * s.length_mm for s in variant.segments)
    if variant.hex_socket is not None:
        v -= float(hexagon_area_inertia(variant.hex_socket.across_flats_mm)[0]) \
            * variant.hex_socket.depth_mm
    return v


def shaft_mass_kg(variant) -> float:
    """Shaft mass in kg (density in t/mm³ → ×1000 kg/t)."""
    return shaft_volume_mm3(variant) * variant.material.density_t_mm3 * 1e3
