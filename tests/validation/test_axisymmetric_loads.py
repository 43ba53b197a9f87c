"""Every load through the axisymmetric path (issue #31 item 3): torque and axial force in
harmonic n = 0 (the torsional u_θ part included), forces, moments and gravity in n = 1, each as
a remote load on its band (RBE3: the band's averaging rows transposed times [F; M]), written as
``[[loads]]`` tables and solved through ``solve_axisymmetric``.

Sources (independent of the method):
* Saint-Venant torsion of a round bar: τ = 16 T/(π d³) on the surface (Timoshenko & Goodier,
  Theory of Elasticity, 3rd ed. 1970, §104); tension σ = F/A; pure bending σ = 32 M/(π d³)
  (Euler-Bernoulli, exact in the Saint-Venant solution of a prismatic bar: ibid. §§ 102-103).
* Statics: a bearing that holds torsion reacts the whole applied torque; balanced torques leave
  nothing on the gauge; the shaft's weight is ρ V g.
* W. D. & D. F. Pilkey, Peterson's Stress Concentration Factors, 3rd ed. (Wiley 2008): Chart
  3.4 (tension of a stepped bar of circular cross section with a shoulder fillet) and Chart
  3.12 (torsion, the same bar), read at D/d = 1.5, r/d = 0.1 (h/r = 2.5) through the
  polynomials printed with the charts: Kt = 1.860 (tension), 1.413 (torsion). Reading
  uncertainty: the charts are photoelastic/early-FE fits of ± a few %, reported to run LOW
  for shoulder fillets by up to ~24 % (Tipton, Sorem & Rolovic, J. Mech. Des. 118 (1996) 321):
  the band [0.95, 1.30] × chart of test_axisymmetric_shaft.py's bending check.
* The project's own converged Kt of the same shoulder (``axisymmetric.kt``: end tractions on a
  bare bar, no bearings, no bands): a second model of the same physics, so the variant path
  (bearings, remote loads, the shaft's mesh) must agree with it to its discretisation.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from shaftfe.axisymmetric import recovery as rc
from shaftfe.axisymmetric.model import AxiOptions
from shaftfe.axisymmetric.solve import solve_axisymmetric
from shaftfe.model.examples import STEEL
from shaftfe.model.loads import read_load_cases, read_loads
from shaftfe.model.variant import Bearing, Segment, Variant

K = ((35_030.0, 0.0), (0.0, 35_030.0))
D_BAR = 20.0


def _variant(segs, loads, cases=(), torsion=True):
    L = segs[-1].x_end_mm
    brg = (Bearing("L", "x", 10.0, 10.0, 1e4, 1e4, K, axial=True, holds_torsion=torsion),
           Bearing("R", "x", L - 10.0, 10.0, 1e4, 1e4, K))
    lds = read_loads(list(loads), "test.toml", segs)
    lc = read_load_cases(list(cases), "test.toml", lds) if cases else ()
    return Variant("loads", "loads test", tuple(segs), brg, (), STEEL, 0.0, loads=lds,
                   load_cases=lc)


BAR = (Segment("a", 0.0, 200.0, D_BAR, 0.0),)


def _mid_surface(res, x0=80.0, x1=120.0):
    """Surface-local stresses (6, k, q) on the outer surface with x in [x0, x1] (≥ 38 mm from
    every band)."""
    sol = res.solution
    S = sol.surface
    x, r = sol.mesh.xr[:, S.nodes]
    idx = np.nonzero((x >= x0) & (x <= x1) & (r > 0.5 * D_BAR - 1e-9))[0]
    from shaftfe.axisymmetric.solve import surface_sigma
    return surface_sigma(sol, idx, rc.theta_grid())


# the far field: the bands' self-equilibrated disturbances decay as e^(−λ x / r) (λ ≈ 2.7 for
# the first axisymmetric end mode of a cylinder) and x ∈ [80, 120] is ≥ 38 mm = 3.8 r from
# every band: e^(−10.3) ≈ 3.5e-5; the Saint-Venant fields (σ_xx linear in y, τ_xθ linear in
# r) lie in the P2 space, so the elements add only round-off. 1e-4 (measured 1.3e-5 tension,
# at x = 120; 1.8e-10 torsion; 8e-12 bending), well inside the bound of 0.5 %
FAR_FIELD = 1e-4


@pytest.fixture(scope="module")
def torsion(cache):
    v = _variant(BAR, [dict(name="T", kind="torque", x_mm=160.0, T_Nmm=1.0e5)])
    return solve_axisymmetric(v, 1000.0, AxiOptions(spin_softening=False), cache_dir=cache)


def test_plain_shaft_torsion(torsion):
    T = 1.0e5
    sig = _mid_surface(torsion)
    tau = 16 * T / (math.pi * D_BAR ** 3)
    # the shear on the surface, τ_tθ (surface-local order tt, θθ, nn, tθ, nθ, nt), uniform
    # in θ (n = 0); its sign follows the outline tangent's orientation: compared in magnitude
    got = np.abs(sig[3])
    assert np.abs(got / tau - 1).max() <= FAR_FIELD, (got.min(), got.max(), tau)
    # the other components vanish (pure shear): relative to τ, at the same bound
    assert np.abs(sig[[0, 1, 2, 4, 5]]).max() <= FAR_FIELD * tau
    # von Mises of the synthesised state: √3 τ (the n = 0 τ_tθ enters the θ synthesis)
    from shaftfe.util.units import von_mises
    assert np.abs(von_mises(sig) / (math.sqrt(3) * tau) - 1).max() <= FAR_FIELD
    # statics: the bearing that holds torsion reacts −T, exactly (round-off of the solve)
    c = torsion.cases[0]
    assert dict(c.torsion_Nmm)["L"] == pytest.approx(-T, rel=1e-9)
    assert c.torque_gauge_relative is None


def test_balanced_torques_leave_the_gauge_unloaded(cache):
    """No bearing holds torsion: T and −T at two stations; the twist is fixed at the axial
    bearing only as a gauge, whose reaction is round-off (Σ T = 0) and the shear between the
    stations is 16 T/(π d³)."""
    T = 1.0e5
    v = _variant(BAR, [dict(name="in", kind="torque", x_mm=40.0, T_Nmm=T),
                       dict(name="out", kind="torque", x_mm=160.0, T_Nmm=-T)], torsion=False)
    res = solve_axisymmetric(v, 1000.0, AxiOptions(spin_softening=False), cache_dir=cache)
    c = res.cases[0]
    # the backward error of the direct solve (≤ 1e-9) bounds the multiplier's share
    assert c.torque_gauge_relative <= 1e-9
    sig = _mid_surface(res)
    assert np.abs(np.abs(sig[3]) / (16 * T / (math.pi * D_BAR ** 3)) - 1).max() <= FAR_FIELD
    assert any("gauge" in n for n in res.notes)


def test_plain_shaft_tension_and_gravity(cache):
    F, g = 2.0e4, 9810.0
    v = _variant(BAR, [dict(name="P", kind="axial_force", x_mm=160.0, F_N=F),
                       dict(name="g", kind="gravity", angle_deg=90.0, g_mm_s2=g)])
    res = solve_axisymmetric(v, 1000.0, AxiOptions(spin_softening=False), cache_dir=cache)
    c = res.cases[0]
    # statics: the axial bearing takes −F; the two bearings (symmetric about x = 100) each
    # take half the weight ρ (π d²/4) L g (the outline is straight: the meshed volume is
    # exact); round-off of the solve (1e-9)
    W = STEEL.density_t_mm3 * math.pi * D_BAR ** 2 / 4 * 200.0 * g
    b = {br.name: br for br in c.bearings}
    assert b["L"].Fx_N == pytest.approx(-F, rel=1e-9)
    for br in c.bearings:
        assert br.Fz_N == pytest.approx(-W / 2, rel=1e-6)   # symmetric bands: mesh symmetry
        assert abs(br.Fy_N) <= 1e-9 * W
    assert c.equilibrium_residual <= 1e-9
    # σ_xx = F/A between the force and the axial bearing: the mean over the θ grid (uniform,
    # 1°) removes the weight's bending stress (a cos θ term, 0.14 MPa = 2e-3 of F/A) exactly
    sig = _mid_surface(res)
    assert np.abs(sig[0].mean(axis=1) / (4 * F / (math.pi * D_BAR ** 2)) - 1).max() <= FAR_FIELD


@pytest.mark.parametrize("angle", [90.0, 0.0, 210.0])
def test_pure_bending_by_end_moments(cache, angle):
    """Moments m = M (0, cos a, sin a) and −m near the two ends: the bearings carry nothing
    (statics) and between them the section moment is −m (the left part's balance), so
    σ_xx = (M_y z − M_z y)/I = M (sin a · y − cos a · z)/I with |σ| = 32 M/(π d³) (beam
    theory); a = 90° is M_z (n = 1 symmetric part), 0° is M_y (the antisymmetric part)."""
    M = 2.0e5
    v = _variant(BAR, [dict(name="ML", kind="moment", x_mm=2.0, width_mm=4.0, M_Nmm=M,
                            angle_deg=angle),
                       dict(name="MR", kind="moment", x_mm=198.0, width_mm=4.0, M_Nmm=-M,
                            angle_deg=angle)])
    res = solve_axisymmetric(v, 1000.0, AxiOptions(spin_softening=False), cache_dir=cache)
    c = res.cases[0]
    for br in c.bearings:          # round-off: 1e-9 of the end moment's force scale M / L
        assert math.hypot(br.Fy_N, br.Fz_N) <= 1e-9 * M / 200.0 * 1e3
    sig = _mid_surface(res)
    nominal = 32 * M / (math.pi * D_BAR ** 3)
    th = rc.theta_grid()
    a = math.radians(angle)
    y, z = 0.5 * D_BAR * np.cos(th), 0.5 * D_BAR * np.sin(th)
    want = M * (math.sin(a) * y - math.cos(a) * z) / (math.pi * D_BAR ** 4 / 64)
    assert np.abs(sig[0] - want[None]).max() <= FAR_FIELD * nominal
    assert np.abs(sig[0]).max() == pytest.approx(nominal, rel=FAR_FIELD)


# ------------------------------------------------------------------- the stepped shaft

STEP = (Segment("small", 0.0, 100.0, 20.0, 2.0), Segment("large", 100.0, 100.0, 30.0, 0.0))
CHART = {"tension": 1.860, "torsion": 1.413}       # Peterson 3rd ed. Charts 3.4 / 3.12
CHART_BAND = (0.95, 1.30)
# the variant's fillet peak against ``kt`` on its own mesh family: two meshes of the same
# shoulder (the shaft's default level, 0.12 ρ on the fillet, against kt's 0.1 ρ refined once)
# and the bands' far disturbance (≥ 78 mm = 7.8 r away); measured 0.13 % (tension) and
# 0.025 % (torsion); bound 0.5 % (kt_reference's level-to-level changes reach 3e-4 at 0.1 ρ)
KT_MESH = 5e-3


@pytest.fixture(scope="module")
def stepped(cache):
    v = _variant(STEP, [dict(name="P", kind="axial_force", x_mm=180.0, width_mm=4.0, F_N=1e4),
                        dict(name="T", kind="torque", x_mm=180.0, width_mm=4.0, T_Nmm=1e5)],
                 cases=[dict(name="tension", rpm=1000.0, factors={"T": 0.0}),
                        dict(name="torsion", rpm=1000.0, factors={"P": 0.0})])
    opts = AxiOptions(spin_softening=False)
    return {c: solve_axisymmetric(v, options=opts, case=c, cache_dir=cache)
            for c in ("tension", "torsion")}


@pytest.mark.parametrize("load", ["tension", "torsion"])
def test_stepped_shaft_kt(stepped, load):
    from shaftfe.axisymmetric.kt import kt_once
    res = stepped[load]
    c = res.cases[0]
    assert c.case == load
    pk = {p.region: p for p in c.peaks}["fillet:small"]
    nominal = 4 * 1e4 / (math.pi * 20.0 ** 2) if load == "tension" else \
        16 * 1e5 / (math.pi * 20.0 ** 3)
    kt = pk.max_principal_MPa / nominal
    ref = kt_once(1.5, 1.0, 0.1, refine=1)[0][load].kt
    assert kt == pytest.approx(ref, rel=KT_MESH), (load, kt, ref)
    lo, hi = CHART_BAND
    assert lo * CHART[load] <= kt <= hi * CHART[load], (load, kt, CHART[load])


def test_constant_loads_do_not_scale_with_speed(cache):
    """A constant torque beside a part's m e ω² (law rpm², at REF_RPM): each speed is the
    columns × its factors, the torque × 1 and the part × (rpm / REF_RPM)² (exact: the same
    columns, one multiplication each; 1e-12 covers the rounding of the products)."""
    from dataclasses import replace

    from shaftfe.model.variant import Attachment
    v = _variant(BAR, [dict(name="T", kind="torque", x_mm=160.0, T_Nmm=1.0e5)])
    v = replace(v, attachments=(Attachment("w", 95.0, 105.0, 1.0, 2.0, 100.0),))
    res = solve_axisymmetric(v, [5000.0, 10000.0], AxiOptions(spin_softening=False),
                             cache_dir=cache)
    lo, hi = res.cases
    assert dict(lo.torsion_Nmm)["L"] == pytest.approx(-1.0e5, rel=1e-9)
    assert dict(hi.torsion_Nmm)["L"] == pytest.approx(-1.0e5, rel=1e-9)
    f_lo, f_hi = dict((n, f) for n, _, f in lo.components), dict(
        (n, f) for n, _, f in hi.components)
    assert f_lo == {"T": 1.0, "parts": 0.25} and f_hi == {"T": 1.0, "parts": 1.0}
    for a, b in zip(lo.bearings, hi.bearings, strict=True):      # forces: the part's only
        assert a.Fy_N == pytest.approx(0.25 * b.Fy_N, rel=1e-12)


def test_an_unknown_load_case_is_refused():
    from shaftfe.errors import InputError
    v = _variant(BAR, [dict(name="T", kind="torque", x_mm=160.0, T_Nmm=1.0e5)])
    with pytest.raises(InputError, match="--case"):
        solve_axisymmetric(v, case="nope")
