"""Converged stress-concentration factors of a shoulder fillet in a stepped round bar, by the
harmonic solver: tension (n = 0), bending (n = 1), torsion (n = 0, u_θ).

Bar: diameter d over 4 d, diameter D over 4 D, fillet radius ρ at the step, free except for
the end loads: a uniform axial traction (tension), a linear one σ_x = k r cos θ (pure bending),
a shear τ_xθ = g r (torsion), equal and opposite on the two ends, so the far field is exact
Saint-Venant (verified: ``tests/validation/test_axisymmetric_exact.py``). Three minimal
point conditions remove the rigid motions without any reaction. Nominal stresses on d:
4P/(πd²), 32M/(πd³), 16T/(πd³) (as Peterson). Kt = the largest principal stress on the fillet
(of the 3D state synthesised over θ, each component with its own trig factor: in bending the
θ-shears are sin θ terms, zero in the bending plane) over the nominal stress (for torsion the
surface state is pure shear, σ1 = τ_max).

Convergence: ``converged`` meshes the bar at one level and refines it uniformly ``levels`` − 1
times (every triangle into four, the fillet kept exact); Richardson extrapolation of the last
three values gives the converged value, the observed order and the error bar |K_∞ − K_finest|
(``richardson``). The peak's position is the angle along the fillet arc from the tangent point
on the smaller diameter.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from shaftfe.axisymmetric import harmonic as hm
from shaftfe.axisymmetric import recovery as rc
from shaftfe.axisymmetric.mesh import (
    AxiLevel,
    Curve,
    MeridianGeometry,
    arc_length_angle,
    mesh_geometry,
)
from shaftfe.axisymmetric.model import AxiOptions
from shaftfe.axisymmetric.solve import solve_axisymmetric
from shaftfe.model.grooves import din471, din509
from shaftfe.solid.features import (
    END_LEFT,
    END_RIGHT,
    fillet_region,
    groove_region,
    shoulder_region,
)
from shaftfe.solid.plan import Groove, _undercut_profile, groove_pieces

# the bar's mesh: fillet elements 0.1 ρ (at 0.2 ρ the first level is still pre-asymptotic:
# measured on D/d 1.5, r/d 0.1, the three levels then spread 5e-3 against 1.6e-4)
LEVEL = AxiLevel("kt", k_far=0.12, k_fillet=0.1, grad=0.25)
LOADS = ("tension", "bending", "torsion")
# the fastest credible observed order: P2 stresses converge as h² (h³ at superconvergent
# points, h⁴ at best for the surface values of smooth fields); beyond, the "order" is noise
P_MAX = 4.0
FILLET = fillet_region("step")      # the bar's fillet (its shoulder segment is "step")
GROOVE = groove_region("bar", 0)    # the grooved bar's groove
UNDERCUT = groove_region("step", 0)  # the undercut bar's DIN 509 undercut
SHAPES = ("step", "groove", "din471", "din509_e", "din509_f")


def stepped_bar(D: float, d: float, rho: float) -> MeridianGeometry:
    r, R = 0.5 * d, 0.5 * D
    L1, L2 = 4 * d, 4 * D
    cur = [Curve((0.0, 0.0), (0.0, r), (END_LEFT,)),
           Curve((0.0, r), (L1 - rho, r), ("surface",)),
           Curve((L1 - rho, r), (L1, r + rho), (FILLET,), (L1 - rho, r + rho), rho)]
    if R - (r + rho) > 1e-9:
        cur.append(Curve((L1, r + rho), (L1, R), (shoulder_region("step"),)))
    cur += [Curve((L1, R), (L1 + L2, R), ("surface",)),
            Curve((L1 + L2, R), (L1 + L2, 0.0), (END_RIGHT,)),
            Curve((L1 + L2, 0.0), (0.0, 0.0), ("axis",))]
    return MeridianGeometry(f"step_{D:g}_{d:g}_{rho:g}", tuple(cur), d,
                            bands=((0.0, L1, d), (L1, L1 + L2, D)))


def grooved_bar(D: float, d: float, rho: float) -> MeridianGeometry:
    """A round bar of diameter D, 8 D long, with a U groove at its middle: bottom diameter d,
    bottom one arc of radius ρ (width 2ρ), straight flanks of height (D − d)/2 − ρ above it
    (issue #33: the groove's Kt; the stepped bar's counterpart)."""
    R, rb, L = 0.5 * D, 0.5 * d, 8.0 * D
    if not 0 < rho <= R - rb + 1e-12:
        raise ValueError(f"a U groove's radius {rho:g} in (0, its depth {R - rb:g}]")
    xa, xb, rc = 0.5 * L - rho, 0.5 * L + rho, rb + rho
    cur = [Curve((0.0, 0.0), (0.0, R), (END_LEFT,)), Curve((0.0, R), (xa, R), ("surface",))]
    if R - rc > 1e-9:
        cur.append(Curve((xa, R), (xa, rc), (GROOVE,)))
    cur += [Curve((xa, rc), (0.5 * L, rb), (GROOVE,), (0.5 * L, rc), rho),
            Curve((0.5 * L, rb), (xb, rc), (GROOVE,), (0.5 * L, rc), rho)]
    if R - rc > 1e-9:
        cur.append(Curve((xb, rc), (xb, R), (GROOVE,)))
    cur += [Curve((xb, R), (L, R), ("surface",)), Curve((L, R), (L, 0.0), (END_RIGHT,)),
            Curve((L, 0.0), (0.0, 0.0), ("axis",))]
    return MeridianGeometry(f"groove_{D:g}_{d:g}_{rho:g}", tuple(cur), d,
                            bands=((0.0, L, D),))


def ring_groove_bar(D: float, rho: float) -> MeridianGeometry:
    """A round bar of diameter D, 8 D long, with DIN 471's retaining-ring groove for D at its
    middle (width m and depth t from ``model.grooves.din471``), flat-bottomed, its two bottom
    corners of radius ρ: the groove's outline as the shaft's (``solid.plan._groove_profile``)."""
    mt = din471(D)
    if mt is None:
        raise ValueError(f"DIN 471 has no groove for diameter {D:g}")
    m, t = mt
    if not 0 < rho <= min(0.5 * m, t):
        raise ValueError(f"a ring groove's corner radius {rho:g} in (0, {min(0.5 * m, t):g}]")
    R, L = 0.5 * D, 8.0 * D
    g = Groove("bar", 0, "din471", R, 0.5 * (L - m), 0.5 * (L + m), t, rho)
    cur = [Curve((0.0, 0.0), (0.0, R), (END_LEFT,)), Curve((0.0, R), (g.x0, R), ("surface",))]
    prev = (g.x0, R)
    for kind_, data in groove_pieces(g)[1:]:
        end = (float(data[0]), float(data[1]))
        cur.append(Curve(prev, end, (GROOVE,), (float(data[2]), float(data[3])), rho)
                   if kind_ == "arc" else Curve(prev, end, (GROOVE,)))
        prev = end
    cur += [Curve(prev, (L, R), ("surface",)), Curve((L, R), (L, 0.0), (END_RIGHT,)),
            Curve((L, 0.0), (0.0, 0.0), ("axis",))]
    return MeridianGeometry(f"din471_{D:g}_{rho:g}", tuple(cur), D - 2.0 * t,
                            bands=((0.0, L, D),))


def undercut_bar(D: float, d: float, kind: str, rho: float | None = None):
    """The stepped bar of ``stepped_bar`` (d over 4 d, D over 4 D) with, instead of the
    fillet, the DIN 509 undercut ``kind`` ("din509_e" | "din509_f") of radius ``rho`` (None:
    the default row for d, ``model.grooves.din509``) in the Ø d at the step, as the shaft's
    outline draws it (``solid.plan``): (geometry, the plan's ``Groove``)."""
    u = din509(d, rho)
    if u is None:
        raise ValueError(f"DIN 509 has no undercut of radius {rho} for diameter {d:g}")
    r, R = 0.5 * d, 0.5 * D
    L1, L2 = 4 * d, 4 * D
    t2 = u.t2 if kind == "din509_f" else 0.0
    g = Groove("step", 0, kind, r, L1 - u.f, L1 + t2, u.t1, u.r, "right", t2)
    if g.r_top >= R:
        raise ValueError(f"the undercut's face top Ø{2 * g.r_top:g} above the step to Ø{D:g}")
    cur = [Curve((0.0, 0.0), (0.0, r), (END_LEFT,))]
    prev = (0.0, r)
    for kind_, data in _undercut_profile(g):
        end = (float(data[0]), float(data[1]))
        groups = ("surface",) if prev == (0.0, r) else (UNDERCUT,)
        cur.append(Curve(prev, end, groups, (float(data[2]), float(data[3])), u.r)
                   if kind_ == "arc" else Curve(prev, end, groups))
        prev = end
    cur += [Curve(prev, (L1, R), (shoulder_region("step"),)),
            Curve((L1, R), (L1 + L2, R), ("surface",)),
            Curve((L1 + L2, R), (L1 + L2, 0.0), (END_RIGHT,)),
            Curve((L1 + L2, 0.0), (0.0, 0.0), ("axis",))]
    geo = MeridianGeometry(f"{kind}_{D:g}_{d:g}_{u.r:g}", tuple(cur), d,
                           bands=((0.0, L1, d), (L1, L1 + L2, D)))
    return geo, g


def _bar(shape: str, D: float, d: float, rho: float):
    """(geometry, the hot region's name, left end radius, right end radius, the diameter of
    the nominal stresses)."""
    if shape == "step":
        return stepped_bar(D, d, rho), FILLET, 0.5 * d, 0.5 * D, d
    if shape == "groove":
        return grooved_bar(D, d, rho), GROOVE, 0.5 * D, 0.5 * D, d
    if shape == "din471":          # D the shaft's diameter (the groove's from DIN 471's row)
        geo = ring_groove_bar(D, rho)            # (its d_ref: the groove's bottom diameter)
        return geo, GROOVE, 0.5 * D, 0.5 * D, geo.d_ref
    if shape in ("din509_e", "din509_f"):       # nominal on the undercut's bottom diameter
        geo, g = undercut_bar(D, d, shape, rho)
        return geo, UNDERCUT, 0.5 * d, 0.5 * D, 2.0 * g.r_bottom
    raise ValueError(f"shape {shape!r}: one of {SHAPES}")


@dataclass(frozen=True)
class KtValue:
    load: str
    kt: float
    angle_deg: float          # along the fillet arc from the small-diameter tangent point (nan:
    #                           an undercut's peak off its arc)


@dataclass(frozen=True, eq=False)
class BarSolution:
    """The stepped bar solved once for the three unit loads on one mesh."""
    geometry: MeridianGeometry
    mesh: object
    surface: rc.Surface
    fillet: np.ndarray        # indices into ``surface.nodes`` on the fillet arc, kinks excluded
    harmonic: dict            # load -> n
    nominal: dict             # load -> nominal stress on d of the unit load
    disp: dict                # load -> displacement vector
    E: float
    nu: float
    hot: str = FILLET         # the notch's region (the fillet's, the groove's)
    # an undercut's other outline nodes (bottom, ramp, wall; kinks excluded): its peak may
    # leave the arc (measured: R1.2 × 0.2 in torsion, 1.6 % above the arc's, on the bottom)
    rest: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0, dtype=int))

    def amplitudes(self, load: str, where: np.ndarray | None = None) -> np.ndarray:
        """(6, k) surface-local stress amplitudes (``recovery.LOCAL``) of ``load`` at the
        surface nodes ``where`` (default: the fillet)."""
        idx = self.fillet if where is None else where
        return self.surface.stress(self.disp[load], self.harmonic[load], self.E,
                                   self.nu)[:, idx]


def solve_bar(D: float, d: float, rho: float, refine: int = 0, level: AxiLevel = LEVEL,
              E: float = 210000.0, nu: float = 0.3, cache_dir=None,
              shape: str = "step") -> BarSolution:
    """The bar of ``stepped_bar`` (``shape`` "groove": ``grooved_bar``; "din509_e" |
    "din509_f": ``undercut_bar``, ρ its radius) under the three end loads of the module
    docstring, the nominal stresses on d (an undercut's: on its bottom diameter)."""
    geo, hot, r, R, d_nom = _bar(shape, D, d, rho)
    mesh = mesh_geometry(geo, level, refine, cache_dir=cache_dir)
    h = hm.assemble(mesh, E, nu, cache_dir=cache_dir)
    left, right = mesh.group_edges(END_LEFT), mesh.group_edges(END_RIGHT)
    S = rc.Surface(mesh)
    # the notch's arcs (a groove's flanks excluded: mapped onto the arc's angle they would sit
    # among its nodes in the peak fit)
    fil = [i for i, c in enumerate(geo.curves) if hot in c.groups and c.center is not None]
    on = np.nonzero(np.isin(S.curve, fil) & ~S.kink)[0]
    rest = np.nonzero(np.isin(S.curve, [i for i, c in enumerate(geo.curves)
                                        if hot in c.groups and c.center is None])
                      & ~S.kink)[0] if hot == UNDERCUT else np.zeros(0, dtype=int)
    ax = mesh.axis_nodes()
    a0, a1 = ax[np.argmin(mesh.xr[0][ax])], ax[np.argmax(mesh.xr[0][ax])]
    far = int(np.argmax(mesh.xr[1]))
    rn = 0.5 * d_nom
    # the left end (radius r) carries the unit field; the right end (radius R) the same
    # resultant. Tension σ_x = 1: P = π r², σ_nom = 4P/(πd²) = r²/rn²; bending σ_x = r cos θ
    # (k = 1): M = π r⁴/4, 32M/(πd³) = r⁴/rn³; torsion τ_xθ = r (g = 1): T = π r⁴/2,
    # 16T/(πd³) = r⁴/rn³ (the stepped bar: r = rn, so 1, r, r)
    cases = {"tension": (0, (lambda x, rr: (1.0, 0.0, 0.0)), (r / R) ** 2, (r / rn) ** 2),
             "bending": (1, (lambda x, rr: (rr, 0.0, 0.0)), (r / R) ** 4, r ** 4 / rn ** 3),
             "torsion": (0, (lambda x, rr: (0.0, 0.0, rr)), (r / R) ** 4, r ** 4 / rn ** 3)}
    pins = {0: [3 * a0, 3 * far + 2], 1: [3 * a0 + 1, 3 * a1 + 1]}
    disp = {}
    for n in (0, 1):                   # one factorisation per harmonic, its loads as columns
        loads = [ld for ld in LOADS if cases[ld][0] == n]
        f = np.column_stack([q * h.traction_vector(right, trac, n)
                             - h.traction_vector(left, trac, n)
                             for trac, q in (cases[ld][1:3] for ld in loads)])
        H = np.zeros((2, h.ndof))
        H[[0, 1], pins[n]] = 1.0
        u = hm.solve(h.K(n), f, h.reduction(n), hard=H).u
        disp.update({ld: u[:, j] for j, ld in enumerate(loads)})
    return BarSolution(geo, mesh, S, on, {ld: c[0] for ld, c in cases.items()},
                       {ld: c[3] for ld, c in cases.items()}, disp, E, nu, hot, rest)


def fillet_peak(bar: BarSolution, values: np.ndarray) -> tuple[float, float]:
    """(peak, angle along the arc °) of ``values`` at the notch's arc nodes (``_arc_peak``):
    on the fillet from its small-diameter tangent point, in a U groove from its left flank
    (its two arcs share one centre); a flat-bottomed groove's corners (two centres) each on
    its own, the larger peak (its angle on that corner's arc)."""
    idx = [i for i, c in enumerate(bar.geometry.curves)
           if bar.hot in c.groups and c.center is not None]
    by_centre: dict = {}
    for i in idx:
        by_centre.setdefault(bar.geometry.curves[i].center, []).append(i)
    best = (-math.inf, math.nan)
    for arcs in by_centre.values():
        first, last = bar.geometry.curves[arcs[0]], bar.geometry.curves[arcs[-1]]
        c = Curve(first.start, last.end, first.groups, first.center, first.size)
        on = np.isin(bar.surface.curve[bar.fillet], arcs)
        pk = _arc_peak(c, bar.mesh.xr[:, bar.surface.nodes[bar.fillet[on]]], values[on])
        best = max(best, pk)
    return best


def kt_once(D: float, d: float, rho: float, refine: int = 0, level: AxiLevel = LEVEL,
            E: float = 210000.0, nu: float = 0.3, cache_dir=None, shape: str = "step"):
    """Kt in tension, bending and torsion on one mesh: ({load: KtValue}, nodes)."""
    bar = solve_bar(D, d, rho, refine, level, E, nu, cache_dir, shape)
    out = {}
    for load in LOADS:
        s1 = _principal_over_theta(bar.amplitudes(load), bar.harmonic[load])
        kt_val, ang_val = fillet_peak(bar, s1)
        if bar.rest.size:           # an undercut's peak off its arc: the largest node there
            s_rest = _principal_over_theta(bar.amplitudes(load, bar.rest), bar.harmonic[load])
            if s_rest.max() > kt_val:
                kt_val, ang_val = float(s_rest.max()), math.nan
        out[load] = KtValue(load, kt_val / bar.nominal[load], ang_val)
    return out, bar.mesh.n_nodes


def _principal_over_theta(amp: np.ndarray, n: int) -> np.ndarray:
    """Largest principal stress over θ at each node of the harmonic-n surface amplitudes
    ``amp`` (6, k), LOCAL order: the 3D state synthesised on ``recovery.theta_grid`` with each
    component's trig factor (``recovery.synthesize``, as the product path does), then the
    maximum over θ. The θ-shear amplitudes (tθ, nθ) carry sin nθ: in bending (n = 1) they vanish
    in the bending plane θ = 0, where the peak is (the symmetry plane; measured: the maximum over
    the grid is at θ = 0 on every shoulder of kt_reference). Taking the principal stress of the
    raw amplitudes instead adds the tθ amplitude (up to 7 % of the nominal stress on the fillet)
    as if it acted at θ = 0: +0.04…+0.25 % on Kt in bending (issue #30 §5)."""
    th = rc.theta_grid()[:1] if n == 0 else rc.theta_grid()
    return rc.principal_max_local(rc.synthesize([(n, amp, None)], th, rc.LOCAL_SHEAR)).max(axis=-1)


def _arc_peak(c: Curve, xr: np.ndarray, val: np.ndarray) -> tuple[float, float]:
    """Peak of ``val`` at points ``xr`` on arc ``c`` in the arc angle: ``recovery.parabola_peak``
    through the largest value and its two neighbours (the nodes are P2 nodes of the outline,
    so the recovered stress is piecewise quadratic along the arc)."""
    ang = arc_length_angle(c, xr[0], xr[1])
    o = np.argsort(ang)
    a, v = ang[o], val[o]
    j = int(np.argmax(v))
    if 0 < j < v.size - 1:
        x, y = rc.parabola_peak(a[j - 1:j + 2], v[j - 1:j + 2])
        return y, x
    return float(v[j]), float(a[j])


def richardson(values) -> dict:
    """Extrapolation and error bar of the last three values of a sequence refined by 2 each
    time, by Roache's grid convergence index (P. J. Roache, "Quantification of uncertainty in
    computational fluid dynamics", Annu. Rev. Fluid Mech. 29 (1997) 123; ASME V&V 20-2009 §2-4):

    * monotone with an observed order p = log2(|K1 − K0| / |K2 − K1|) in [1, P_MAX]:
      K_∞ = K2 + (K2 − K1)/(2^p − 1), bar = 1.25 |K_∞ − K2| (safety factor 1.25 of a
      three-grid study);
    * otherwise (oscillating, or p outside [1, P_MAX]: slower than first order, or faster than a
      P2 surface stress can converge, i.e. a difference small by cancellation, not a rate):
      no order is claimed, K_∞ = K2 and bar = 3 |K2 − K1| / (2^2 − 1) = |K2 − K1| (safety
      factor 3 with the formal order 2 of P2 stresses).

    The bar is that of the returned value."""
    k0, k1, k2 = values[-3:]
    d1, d2 = k1 - k0, k2 - k1
    if d1 != 0 and d2 != 0 and d1 * d2 > 0 and abs(d1) > abs(d2):
        p = math.log2(abs(d1) / abs(d2))
        if 1.0 <= p <= P_MAX:
            kinf = k2 + d2 / (2 ** p - 1)
            return {"value": kinf, "error": 1.25 * abs(kinf - k2), "order": p, "finest": k2}
    return {"value": k2, "error": abs(d2), "order": None, "finest": k2}


def converged(D: float, d: float, rho: float, levels: int = 3, level: AxiLevel = LEVEL,
              cache_dir=None, shape: str = "step") -> dict:
    """{load: {"kt", "error", "order", "angle_deg", "values"}} from ``levels`` uniform
    refinements (≥ 3) of the stepped bar (``shape`` "groove": the grooved bar)."""
    import time
    vals = {ld: [] for ld in LOADS}
    angles = {}
    nodes, secs = [], []
    for ref in range(levels):
        t0 = time.perf_counter()
        res, nn = kt_once(D, d, rho, ref, level, cache_dir=cache_dir, shape=shape)
        secs.append(time.perf_counter() - t0)
        nodes.append(nn)
        for ld in LOADS:
            vals[ld].append(res[ld].kt)
            angles[ld] = res[ld].angle_deg
    out = {}
    for ld in LOADS:
        rich = richardson(vals[ld])
        out[ld] = {"kt": rich["value"], "error": rich["error"], "order": rich["order"],
                   "angle_deg": angles[ld], "values": vals[ld]}
    out["nodes"] = nodes
    out["seconds"] = secs
    return out


def converged_peaks(variant, rpm: float, regions, level="default", levels: int = 3,
                    **options) -> dict:
    """The shaft's (or any variant's) region peaks converged like the Kt values: the
    axisymmetric solve at ``levels`` uniform refinements of ``level`` (``AxiOptions`` fields in
    ``options``), ``richardson`` of each region's von Mises and max principal peak:
    {region: {"von_mises": …, "max_principal": …}, "nodes": [...]}, each with its "values"."""
    vals = {r: {"von_mises": [], "max_principal": []} for r in regions}
    nodes = []
    for ref in range(levels):
        res = solve_axisymmetric(variant, rpm, AxiOptions(level, refine=ref, **options))
        pk = {p.region: p for p in res.case(rpm).peaks}
        for r in regions:
            vals[r]["von_mises"].append(pk[r].von_mises_MPa)
            vals[r]["max_principal"].append(pk[r].max_principal_MPa)
        nodes.append(res.n_nodes)
    out: dict = {"nodes": nodes}
    for r in regions:
        out[r] = {q: {**richardson(v), "values": [round(x, 3) for x in v]}
                  for q, v in vals[r].items()}
    return out
