"""`shaftfe static --model axisymmetric`: the shaft as a body of revolution, every rpm (or a
named load case) from one solve, each speed the load components × their factors (all ∝ ω²:
the fields once at REF_RPM, scaled), the same outputs as the 3D path (``static.result``):
bearing reactions and L10h, axis deflections at the stations, peaks per region (von Mises and
max principal with their location), the torsion reactions, plus what the model leaves out.

A peak is the maximum over the region's surface nodes and θ of the surface-recovered stress
(``recovery``), located by a parabola through the three best θ samples (1° grid) and the three
best nodes along the outline. Nodes of the boundary edges that touch a seat end (a traction
jump: the singular-point rule of the 3D path) are excluded from the filtered peak; on a loaded
seat the pressure's θ-edges (angle ± 90°) are singular lines too and a band of ±10° around them
is left out of its peak.
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, field

import numpy as np

from shaftfe.axisymmetric import recovery as rc
from shaftfe.axisymmetric.mesh import AXI_LEVELS, BAND_PREFIX, arc_length_angle
from shaftfe.axisymmetric.model import AxiOptions, AxiSolution, solve_model, superpose
from shaftfe.errors import InputError
from shaftfe.fe import reuse
from shaftfe.model.bearing_life import l10h
from shaftfe.solid.features import (
    ROUND_NOTCH_KINDS,
    SEAT_KINDS,
    bearing_group,
    cuts,
    kind_of,
    omitted_entry,
    part_seat_region,
    region_of,
    seat_region,
)
from shaftfe.solid.plan import warn_sharp_corners
from shaftfe.static.measured_errors import notch_bars
from shaftfe.static.result import BearingReaction, Station
from shaftfe.static.solve import _check_rpms
from shaftfe.util.fmt import json_clean
from shaftfe.util.notices import warn
from shaftfe.util.units import REF_RPM, rpm2_scale, von_mises

SEAT_EDGE_BAND_DEG = 10.0


@dataclass(frozen=True)
class AxiPeak:
    region: str
    von_mises_MPa: float
    xyz_mm: tuple[float, float, float]
    theta_deg: float
    max_principal_MPa: float
    max_principal_xyz_mm: tuple[float, float, float]
    fillet_angle_deg: float | None      # along the fillet arc from its start (fillets only)
    n_nodes: int
    n_excluded: int
    omitted_zone: str | None            # the omitted 3D feature whose zone the peak lies in


@dataclass(frozen=True)
class AxiCase:
    rpm: float
    scale: float
    bearings: tuple[BearingReaction, ...]
    stations: tuple[Station, ...]
    max_axis_deflection_mm: float
    peaks: tuple[AxiPeak, ...]
    load_sum_N: tuple[float, float, float]
    reaction_sum_N: tuple[float, float, float]
    equilibrium_residual: float
    case: str = ""                       # the load case's name ("" = a plain speed)
    torsion_Nmm: tuple = ()              # (bearing, its θ_x reaction on the shaft, N·mm)
    torque_gauge_relative: float | None = None   # the gauge's reaction / Σ |applied T|
    components: tuple = ()               # (load name, speed law, factor) of each column


@dataclass(frozen=True, eq=False)
class AxiResult:
    variant: str
    variant_hash: str
    options: AxiOptions
    ref_rpm: float
    n_nodes: int
    n_elements: int
    harmonics: tuple[int, ...]
    truncation_change: float
    omitted: tuple[dict, ...]
    cases: tuple[AxiCase, ...]
    axis_x: np.ndarray = field(repr=False)
    axis_u_ref: np.ndarray = field(repr=False)       # (n, 3) at ref_rpm
    solution: AxiSolution | None = field(default=None, repr=False)
    notes: tuple[str, ...] = ()
    run: dict = field(default_factory=dict)
    # the level's measured error bar (%, low, high) of each span-fillet and groove peak
    # (``truth_bars``) and why such a notch has none
    truth_error_bar_pct: dict = field(default_factory=dict)
    truth_bar_notes: dict = field(default_factory=dict)

    def case(self, rpm: float) -> AxiCase:
        return next(c for c in self.cases if math.isclose(c.rpm, rpm))

    def to_dict(self) -> dict:
        opts = {**asdict(self.options), "level": self.options.level_name}
        return json_clean({
            "model": "axisymmetric", "variant": self.variant, "variant_hash": self.variant_hash,
            "options": opts, "load_case": self.options.load_case, "ref_rpm": self.ref_rpm,
            "mesh": {"nodes": self.n_nodes, "elements": self.n_elements,
                     "dofs_per_harmonic": 3 * self.n_nodes,
                     "harmonics": list(self.harmonics),
                     "truncation": {"tolerance": self.options.truncation,
                                    "last_change": self.truncation_change,
                                    "criterion": "the last two loaded harmonics each change "
                                    "the peak von Mises stress of every fillet outside the "
                                    "omitted features' zones (or of every fillet) by less "
                                    "than the tolerance × the largest of those peaks",
                                    "fillets": list(self.solution.truncation_fillets)
                                    if self.solution is not None else None}},
            "omitted_features": list(self.omitted),
            "cases": [asdict(c) for c in self.cases],
            "truth_error_bar_pct": self.truth_error_bar_pct,
            "truth_bar_notes": self.truth_bar_notes,
            "notes": list(self.notes), "run": self.run,
        })


# ------------------------------------------------------------------------------ helpers


def axis_displacement(sol: AxiSolution, xs) -> np.ndarray:
    """(n, 3) displacement of the axis at ``xs``: u_x from n = 0 (U_x), u_y and u_z from the
    n = 1 parts (U_r on the axis; every other harmonic vanishes there), P2 along the axis."""
    mesh = sol.mesh
    ids = [i for i, c in enumerate(mesh.geometry.curves) if "axis" in c.groups]
    e = mesh.edges[:, np.isin(mesh.edge_curve, ids)]
    x0, x1 = mesh.xr[0][e[0]], mesh.xr[0][e[1]]
    lo, hi = np.minimum(x0, x1), np.maximum(x0, x1)
    f0 = sol.harmonics[0].sym
    f1 = next(h for h in sol.harmonics if h.n == 1)
    out = np.full((len(xs), 3), np.nan)
    for k, x in enumerate(np.asarray(xs, dtype=float)):
        j = np.nonzero((lo - 1e-9 <= x) & (x <= hi + 1e-9))[0]
        if j.size == 0:
            continue
        j = j[0]
        s = (x - x0[j]) / (x1[j] - x0[j])
        N = np.array([(1 - s) * (1 - 2 * s), s * (2 * s - 1), 4 * s * (1 - s)])
        nodes = e[:, j]
        out[k] = [N @ f0[3 * nodes], N @ f1.sym[3 * nodes + 1], N @ f1.anti[3 * nodes + 1]]
    return out


def regions(mesh) -> dict[str, list[int]]:
    """Region name -> outline curve ids, named as the 3D path's regions: each face group, a
    load seat as ``seat:<part>``, a bearing seat as ``seat:bearing:<side>``."""
    out: dict[str, list[int]] = {}
    for i, c in enumerate(mesh.geometry.curves):
        for g in c.groups:
            if g == "axis" or g.startswith(BAND_PREFIX):
                continue
            out.setdefault(region_of(g), []).append(i)
    return out


def excluded_nodes(sol: AxiSolution, exclude_mm: float) -> np.ndarray:
    """Surface-node mask: nodes of boundary edges touching a seat end, and nodes within
    ``exclude_mm`` of one."""
    mesh, S = sol.mesh, sol.surface
    ends = []
    for c in mesh.geometry.curves:
        if any(kind_of(g) in SEAT_KINDS or g.startswith(BAND_PREFIX) for g in c.groups):
            ends += [c.start, c.end]
    mask = np.zeros(S.nodes.size, dtype=bool)
    if not ends:
        return mask
    P = np.array(ends).T
    xr = mesh.xr[:, S.nodes]
    d = np.sqrt(((xr[:, :, None] - P[:, None, :]) ** 2).sum(axis=0)).min(axis=1)
    mark = np.zeros(mesh.n_nodes, dtype=bool)
    mark[S.nodes[d < 1e-9]] = True
    e = mesh.edges
    touch = mark[e].any(axis=0)
    bad = np.zeros(mesh.n_nodes, dtype=bool)
    bad[e[:, touch].ravel()] = True
    mask = bad[S.nodes]
    if exclude_mm > 0:
        mask |= d < exclude_mm
    return mask


def loaded_seat_angles(sol: AxiSolution) -> dict[str, list[float]]:
    """Region name of each loaded seat -> the angles (°) of the forces pressing on it."""
    out: dict[str, list[float]] = {}
    for ld in sol.loads:
        out.setdefault(seat_region(ld.group), []).append(ld.angle_deg)
    return out


def seat_edge_band(theta: np.ndarray, angles) -> np.ndarray:
    """(q,) True where θ (rad) lies within ``SEAT_EDGE_BAND_DEG`` of a half-seat pressure's
    θ-edge (the force angle ± 90°): a singular line of the 3D path's pressure patch too."""
    band = np.zeros(theta.size, dtype=bool)
    deg = np.degrees(theta)
    for a in angles:
        for edge in (a + 90.0, a - 90.0):
            dd = np.abs(np.remainder(deg - edge + 180.0, 360.0) - 180.0)
            band |= dd <= SEAT_EDGE_BAND_DEG
    return band


def surface_sigma(sol: AxiSolution, idx: np.ndarray, theta: np.ndarray,
                  shear: np.ndarray = rc.LOCAL_SHEAR) -> np.ndarray:
    """(6, k, q) surface-recovered stress (surface-local components, ``recovery.LOCAL``) at the
    surface nodes ``idx`` (indices into ``sol.surface.nodes``) and angles θ (rad)."""
    parts = [(n, a[:, idx], None if b is None else b[:, idx])
             for n, a, b in sol.surface_stress]
    return rc.synthesize(parts, theta, shear)


def region_peaks(sol: AxiSolution, omitted=()) -> tuple[AxiPeak, ...]:
    """Peaks per region at REF_RPM (see the module docstring)."""
    mesh, S = sol.mesh, sol.surface
    theta = rc.theta_grid()
    excl = excluded_nodes(sol, sol.options.exclude_mm)
    seat_angles = loaded_seat_angles(sol)
    out = []
    for name, ids in sorted(regions(mesh).items()):
        on = np.isin(S.curve, ids)
        idx = np.nonzero(on & ~excl & ~S.on_axis)[0]
        n_all = int((on & ~S.on_axis).sum())
        if idx.size == 0:
            continue
        sig = surface_sigma(sol, idx, theta)                      # (6, k, q)
        vm = von_mises(sig)
        s1 = rc.principal_max_local(sig)
        if name in seat_angles:           # the pressure's θ-edges: singular lines
            keep = ~seat_edge_band(theta, seat_angles[name])
            vm = np.where(keep[None], vm, -np.inf)
            s1 = np.where(keep[None], s1, -np.inf)
        vpk, vloc, vth, fang = _locate(mesh, S, idx, vm, theta)
        ppk, ploc, _, _ = _locate(mesh, S, idx, s1, theta)
        zone = next((f["feature"] for f in omitted
                     if f["zone_mm"][0] <= vloc[0] <= f["zone_mm"][1]), None)
        out.append(AxiPeak(name, vpk, vloc, vth, ppk, ploc, fang, n_all,
                           int(n_all - idx.size), zone))
    return tuple(out)


def _locate(mesh, S, idx, val, theta):
    """Peak of val (k, q) over nodes and θ: parabolic in θ, then along the outline."""
    k, q = np.unravel_index(int(np.argmax(val)), val.shape)
    dq, _ = rc.parabola_peak([-1.0, 0.0, 1.0], [val[k, (q - 1) % theta.size], val[k, q],
                                               val[k, (q + 1) % theta.size]])
    th = float(theta[q] + dq * np.radians(rc.THETA_STEP_DEG))
    node = S.nodes[idx[k]]
    x, r = mesh.xr[:, node]
    # neighbours along the outline: the nearest two nodes of the region, one each side
    xr = mesh.xr[:, S.nodes[idx]]
    d = np.hypot(xr[0] - x, xr[1] - r)
    pk = float(val[k, q])
    order = np.argsort(d)
    if order.size >= 3:
        a, b = order[1], order[2]
        ta = (xr[:, a] - [x, r]) @ (xr[:, b] - [x, r])
        if ta < 0:                         # on opposite sides: fit along the outline
            _, pk = rc.parabola_peak([-d[a], 0.0, d[b]], [val[a, q], pk, val[b, q]])
    c = mesh.geometry.curves[int(S.curve[idx[k]])]
    fang = float(arc_length_angle(c, np.array([x]), np.array([r]))[0]) \
        if c.center is not None else None
    loc = (float(x), float(r * math.cos(th)), float(r * math.sin(th)))
    return pk, loc, float(np.degrees(th) % 360.0), fang


# ------------------------------------------------------------------------------ the API


def _case(sol: AxiSolution, r: float, scale: float, peaks, stations, st_u, ax_u,
          case=None) -> AxiCase:
    """The results at speed ``r`` of the fields of ``sol`` × ``scale`` (``peaks``, station and
    axis displacements of those fields)."""
    cols = sol.columns
    f = np.asarray(sol.factors, dtype=float)
    load_sum = (cols.load_sum @ f) * scale
    for name, (qy, qz) in sol.attachment_motion.items():     # spin softening: m ω² u
        load_sum = load_sum + sol.softening_N_per_mm[name] * np.array([0.0, qy, qz]) * scale
    reac_sum = sum((np.array(rr[:3]) for rr in sol.reactions.values()), np.zeros(3)) * scale
    # relative to the resultant, or where it (nearly) vanishes (torques, couples) to the
    # loads' own size Σ (|F| + |M| / L)
    ref = float(np.linalg.norm(load_sum))
    size = float(np.abs(cols.load_scale * f).sum()) * abs(scale)
    ref = ref if ref > 1e-3 * size else size
    eq = float(np.linalg.norm(load_sum + reac_sum) / ref) if ref > 0 else 0.0
    brs = []
    for name, rb, b in sol.bearings:
        Fx, Fy, Fz, qy, qz = sol.reactions[name]
        F = math.hypot(Fy, Fz) * scale
        life = l10h(b.C_N, F, r, b.life_exponent)
        brs.append(BearingReaction(name, rb.x_mm, Fx * scale, Fy * scale, Fz * scale, F,
                                   qy * scale, qz * scale,
                                   life if math.isfinite(life) else None, b.C_N,
                                   b.life_exponent))
    sts = tuple(Station(nm, float(x), float(u[1] * scale), float(u[2] * scale),
                        float(math.hypot(u[1], u[2]) * scale))
                for (nm, x), u in zip(stations, st_u, strict=True))
    pk = tuple(AxiPeak(p.region, p.von_mises_MPa * scale, p.xyz_mm, p.theta_deg,
                       p.max_principal_MPa * scale, p.max_principal_xyz_mm, p.fillet_angle_deg,
                       p.n_nodes, p.n_excluded, p.omitted_zone) for p in peaks)
    tors = tuple((k, float(t @ f) * scale) for k, t in cols.torsion.items())
    gauge = None
    if cols.gauge is not None:
        applied = float(np.abs(cols.torque_sum * f).sum()) * abs(scale)
        t_g = dict(tors)[cols.gauge]
        gauge = abs(t_g) / applied if applied > 0 else 0.0
    comps = tuple((c.factor_name, c.scales_with, float(x) * scale)
                  for c, x in zip(cols.components, f, strict=True))
    return AxiCase(r, scale, tuple(brs), sts,
                   float(np.nanmax(np.hypot(ax_u[:, 1], ax_u[:, 2])) * scale), pk,
                   tuple(float(c) for c in load_sum), tuple(float(c) for c in reac_sum), eq,
                   "" if case is None else case.name, tors, gauge, comps)


def resolve_case(variant, case):
    """A load case given by name (or as a ``LoadCase``) → the variant's ``LoadCase``."""
    if case is None or not isinstance(case, str):
        return case
    names = [c.name for c in variant.load_cases]
    if case not in names:
        raise InputError("--case", "case", "a [[load_cases]] name of the variant: "
                         + (", ".join(names) or "(it has none)"), got=case)
    return variant.load_case(case)


def solve_axisymmetric(variant, rpm=REF_RPM, options: AxiOptions = AxiOptions(), *,
                       cache_dir=None, case=None) -> AxiResult:
    """Every speed in ``rpm`` (or the load case ``case``, a name or a ``LoadCase``, at its own
    speed) from one solve: one factorisation per harmonic and one column per load component
    (``model.Component``), each speed's fields the columns × that speed's factors. Loads all
    ∝ rpm² (every shipped variant): solved once at REF_RPM, results × (rpm / REF_RPM)². With
    ``options.spin_softening`` the response is not ∝ rpm²: each speed is solved at it (one
    solve each, on the same cached mesh), the fields are the first speed's."""
    from dataclasses import replace

    t0 = time.perf_counter()
    case = resolve_case(variant, case)
    rpms = _check_rpms(case.rpm if case is not None else rpm)
    warn_sharp_corners(variant)          # a fillet 0 at a loaded shoulder: not a stress there
    if options.spin_softening and len(rpms) > 1:
        # the fields are the first positive speed's; a 0 rpm case (no load, no softening) is
        # the linear solve's exact zero
        r0 = next(r for r in rpms if r > 0)
        with reuse.shared():             # one factorisation per harmonic for every speed
            parts = [solve_axisymmetric(variant, r, options, cache_dir=cache_dir) if r > 0
                     else solve_axisymmetric(variant, [r, r0],
                                             replace(options, spin_softening=False),
                                             cache_dir=cache_dir) for r in rpms]
        cases = tuple(replace(p.case(r), scale=(r / r0) ** 2)
                      for p, r in zip(parts, rpms, strict=True))
        first = parts[rpms.index(r0)]
        run = {**first.run, "total_seconds": time.perf_counter() - t0}
        return replace(first, cases=cases, run=run)
    ref_rpm = rpms[0] if options.spin_softening else REF_RPM
    sol = solve_model(variant, options, rpm=ref_rpm, cache_dir=cache_dir, case=case)
    v = sol.variant
    t1 = time.perf_counter()
    omitted = tuple(omitted_entry(f) for f in cuts(sol.plan))
    stations = [(part_seat_region(a.name), a.seat_center_mm) for a in v.attachments
                if a.force_N(REF_RPM) != 0]
    stations += [(f"load:{ld.name}", ld.x_mm) for ld in getattr(v, "loads", ())
                 if ld.kind != "gravity"]
    stations += [(bearing_group(name), rb.x_mm) for name, rb, _ in sol.bearings]
    if v.clearance_station_x_mm is not None:
        stations.append(("clearance", float(v.clearance_station_x_mm)))
    x0, x1 = float(sol.mesh.xr[0].min()), float(sol.mesh.xr[0].max())
    ax_x = np.linspace(x0, x1, 121)
    # all ∝ rpm² (or one case, or softening: one speed): the fields once, scaled per speed
    proportional = case is not None or options.spin_softening or all(
        c.scales_with == "rpm2" for c in sol.columns.components)
    cases, first = [], None
    for r in rpms:
        if proportional:
            at, s = sol, (1.0 if options.spin_softening or case is not None
                          else rpm2_scale(r, ref_rpm))
        else:                            # constant and channel loads: the columns per speed
            at, s = superpose(sol, sol.columns.factors(r)), 1.0
        if first is None or not proportional:
            peaks = region_peaks(at, omitted)
            st_u = axis_displacement(at, [x for _, x in stations])
            ax_u = axis_displacement(at, ax_x)
            first = first or (at, ax_u)
        cases.append(_case(at, r, s, peaks, stations, st_u, ax_u, case))
    sol, ax_u = first
    notes = [f"{f['feature']} is not modelled (a body of revolution); peaks with x in "
             f"[{f['zone_mm'][0]:g}, {f['zone_mm'][1]:g}] mm lie in its zone of influence: "
             "use the 3D path there" for f in omitted]
    notes.append("threads are plain cylinders at their modelled diameter (as in the 3D path)")
    others = sorted(p.region for p in cases[0].peaks if kind_of(p.region) in ROUND_NOTCH_KINDS
                    and p.region not in sol.truncation_fillets)
    if others and sol.loads:
        notes.append(f"harmonic series cut at n = {sol.n_used} when the fillets "
                     f"{', '.join(sol.truncation_fillets)} had converged to "
                     f"{options.truncation:g}; the peaks of {', '.join(others)} (in the zone of "
                     "an omitted feature) are not converged in n (AxiOptions("
                     "converge_all_fillets=True) includes them)")
    notes += _load_notes(sol, cases)
    run = dict(sol.seconds)
    run["post_seconds"] = time.perf_counter() - t1
    run["total_seconds"] = time.perf_counter() - t0
    if options.spin_softening:
        notes.append(f"spin softening included: each attachment's m ω² u at {ref_rpm:g} rpm "
                     "(its seat's translation; its tilt left out)")
    bars, bar_notes = truth_bars(v, options, cases[0].peaks)
    # the fields kept (``solution``, the axis) are the first speed's where the loads are not
    # all ∝ rpm²: that speed is the result's reference, as its fatigue reference says
    return AxiResult(v.name, v.content_hash, options, ref_rpm if proportional else rpms[0],
                     sol.mesh.n_nodes,
                     sol.mesh.n_elements, tuple(h.n for h in sol.harmonics),
                     sol.truncation_change, omitted, tuple(cases), ax_x, ax_u, sol,
                     tuple(notes), run, bars, bar_notes)


def truth_bars(variant, options: AxiOptions, peaks) -> tuple[dict, dict]:
    """({region: (low, high) %}, {region: why it has none}) of the span-fillet and groove peaks: the
    axisymmetric level's bar measured over the grid of shoulders and the grid of U grooves
    (``shaftfe.static.measured_errors.notch_bars``, ``shoulder_bars``, ``groove_bars``: its own
    method refined, a discretisation error bar) for a named level used as named at refinement 0,
    under the options the bars were measured with (the uniform placement of the parts' loads,
    every peak node kept, the default harmonic truncation); supports rigid or springs and spin
    softening on or off were both measured (x2_57). ``converge_all_fillets`` is free: it only
    adds harmonics, which change a span fillet's peak by less than the truncation tolerance
    (1e-4 of the largest peak)."""
    name, d = options.level_name, AxiOptions()
    if not isinstance(options.level, str) and options.level != AXI_LEVELS.get(name):
        return {}, {}
    if (options.refine, options.load_distribution, options.seed_load_case, options.exclude_mm,
            options.truncation, options.n_max) != (0, d.load_distribution, False, 0.0,
                                                   d.truncation, d.n_max):
        return {}, {}
    return notch_bars(variant, name, peaks, "axisymmetric")


GAUGE_TOL = 1e-9     # relative: Σ T = 0 per law to round-off (``model.loads.TORQUE_TOL``)


def _load_notes(sol: AxiSolution, cases) -> list[str]:
    """How the loads enter (the placement, the twist's support) and the torsion gauge's
    check: its reaction must vanish against the applied torques (a warning if it does not)."""
    cols = sol.columns
    out = []
    if not sol.options.seed_load_case and any(a.force_N(REF_RPM) for a in
                                              sol.variant.attachments):
        out.append("each part's m e ω² acts at its centroid, through its seat as a remote "
                   "force and moment (RBE3); --seed-load-case: the seed's half-seat pressure")
    if np.any(cols.torque_sum):
        if cols.gauge is None:
            held = ", ".join(cols.torsion)
            out.append(f"torsion held by the bearings that hold it ({held})")
        else:
            worst = max((c.torque_gauge_relative or 0.0) for c in cases)
            out.append(f"no bearing holds torsion: the twist is fixed at {cols.gauge} only as a "
                       f"gauge; its reaction is {worst:.1e} of the applied torques (Σ T = 0)")
            if worst > GAUGE_TOL:
                warn("torque-gauge", f"axisymmetric {cols.gauge}", f"the gauge holding the "
                     f"twist carries {worst:.2e} of the applied torques: the case's factors "
                     "leave a net torque that no support holds")
    return out
