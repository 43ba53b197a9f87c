"""A transverse (cross) hole (issue #33): the zoned solve's 3D zone around it against the
published stress concentration, and the hole's exact geometry against the mesh.

Case: ``model.examples.holed_bar``, a Ø20 bar with a Ø4 hole (d_h/d = 0.2) at x = 80 mm, loaded
between x = 40 and 120 mm in tension (P = 10 kN), four-point bending (M = F · 30 mm) and torsion
(T = 50 N·m); the hole lies in a 3D zone, the rest is the axisymmetric global model.

Reference: DIN 743-2:2012's α of a transverse hole (3 − d_h/d; 3 + 1.4 d_h/d − 2.8 √(d_h/d);
2.023 − 1.125 √(d_h/d)), nominal stresses on the net section (A = πd²/4 − d_h d,
W_b = πd³/32 − d_h d²/6, W_t = πd³/16 − d_h d²/6): a fit of Peterson's charts of a round
bar with a transverse hole (Peterson's Stress Concentration Factors, 3rd ed., charts 4.66-4.70,
photoelastic and strain-gauge data), which is why it is a band, not a value.
"""

import math

import pytest

from shaftfe.fatigue import din743 as din
from shaftfe.model.examples import (
    HOLED_BAR_F_N,
    HOLED_BAR_P_N,
    HOLED_BAR_T_NMM,
    holed_bar,
)

# the charts' band: Peterson's transverse-hole data scatter by about ±10 % about the curves
# DIN 743 fits (and FINDINGS "On the charts": chart fits lie up to 20 % from converged FE for
# shoulders). Measured (reports/benchmarks/cross_hole.md): tension −9.3 / −7.3 %, bending
# −2.8 / +1.7 %, torsion +7.0 / +8.0 % at coarse / default. What the test catches: the
# hole missing or meshed wrong (Kt 1), a wrong net section (±25 %), the peak taken from the
# global model that has no hole.
CHART_BAND = 0.10
D, DH = 20.0, 4.0


def _nominal(load: str) -> float:
    """The net section's nominal stress (τ in torsion)."""
    n = din.Notch("hole", "cross_hole", D, D, 0.5 * DH, hole_mm=DH)
    k = dict(zip(("tension", "bending", "torsion"), din.net_section_scale(n), strict=True))
    full = {"tension": HOLED_BAR_P_N / (math.pi * D * D / 4),
            "bending": HOLED_BAR_F_N * 30.0 / (math.pi * D ** 3 / 32),
            "torsion": HOLED_BAR_T_NMM / (math.pi * D ** 3 / 16)}
    return full[load] * k[load]


@pytest.mark.parametrize("level", ["coarse", "default"])
@pytest.mark.parametrize("load", ["tension", "bending", "torsion"])
def test_cross_hole_kt_within_the_chart_band(load, level, cache):
    """Kt = σ1,max / σ_nom (torsion: τ_max / τ_nom with τ_max = σ1/2, the hole's edge and bore
    being a free surface in a uniaxial state) within CHART_BAND of DIN 743-2's α, at two mesh
    levels; the peak lies on the hole (its region) at the shaft's surface or in its bore."""
    from shaftfe.static.model import StaticOptions
    from shaftfe.zoned.solve import solve_zoned
    z = solve_zoned(holed_bar(load), 1000.0, StaticOptions(level=level, spin_softening=False),
                    cache_dir=cache)
    assert [zn.name for zn in z.zones] == ["zone:cross_hole:bar:0"]
    p = {q.region: q for q in z.cases[0].peaks}["cross_hole:bar:0"]
    assert p.model == "zone:cross_hole:bar:0"
    kt = p.max_principal_MPa / _nominal(load) / (2.0 if load == "torsion" else 1.0)
    assert kt == pytest.approx(din.alpha_cross_hole(D, DH, load), rel=CHART_BAND)
    x, _, zz = p.max_principal_xyz_mm
    # on the hole's wall: its distance from the hole's axis (x = 80, along y) is its radius
    # (the P2 surface's chord error at the peak node, < 2 % of a)
    assert math.hypot(x - 80.0, zz) == pytest.approx(0.5 * DH, rel=0.02)


def test_cross_hole_geometry_against_the_mesh(cache):
    """The hole's wall area and the shaft's volume on the default mesh against the closed
    forms (``solid.exact.hole_area``, ``hole_volume``: quadratures of the cylinders'
    intersection); the P2 facets' chord error at the default size (0.3 a on the bore):
    measured −4.7e-6 (area) and −2.7e-4 (volume: the whole bar's curved surface), bound
    2e-3."""
    from skfem import Basis, ElementTetP2, FacetBasis, Functional

    from shaftfe.solid.exact import analytic_volume, expected_areas
    from shaftfe.solid.mesh import build_mesh
    v = holed_bar("bending")
    m = build_mesh(v, "default", cache_dir=cache).mesh
    one = Functional(lambda w: 1.0 + 0.0 * w.x[0])
    vol = float(one.assemble(Basis(m, ElementTetP2())))
    area = float(one.assemble(FacetBasis(m, ElementTetP2(),
                                         facets=m.boundaries["cross_hole:bar:0"])))
    assert vol == pytest.approx(analytic_volume(v), rel=2e-3)
    assert area == pytest.approx(expected_areas(v)["cross_hole:bar:0"], rel=2e-3)


def test_din743_cross_hole_factors_by_hand():
    """DIN 743-2's transverse hole written out (exact arithmetic: 1e-12): α per load, G', and
    the net section's factors over the full section's nominal stresses."""
    q = DH / D
    assert din.alpha_cross_hole(D, DH, "tension") == pytest.approx(3 - q, rel=1e-12)
    assert din.alpha_cross_hole(D, DH, "bending") == pytest.approx(
        3 + 1.4 * q - 2.8 * math.sqrt(q), rel=1e-12)
    assert din.alpha_cross_hole(D, DH, "torsion") == pytest.approx(
        2.023 - 1.125 * math.sqrt(q), rel=1e-12)
    r = DH / 2
    assert din.gradient_cross_hole(D, DH, "bending") == pytest.approx(2.3 / r + 2 / D,
                                                                      rel=1e-12)
    assert din.gradient_cross_hole(D, DH, "torsion") == pytest.approx(1.15 / r + 2 / D,
                                                                      rel=1e-12)
    n = din.Notch("hole", "cross_hole", D, D, r, hole_mm=DH)
    a, wb, wt = math.pi * D * D / 4, math.pi * D ** 3 / 32, math.pi * D ** 3 / 16
    assert din.net_section_scale(n) == pytest.approx(
        (a / (a - DH * D), wb / (wb - DH * D * D / 6), wt / (wt - DH * D * D / 6)), rel=1e-12)
    assert din.net_section_scale(din.Notch("s", "shoulder", 17.0, 22.0, 0.6)) == (1, 1, 1)


def test_din743_assesses_the_hole_on_its_net_section():
    """``fatigue.strength.din743_notches`` + ``run_din743``: the holed bar's hole is a row
    whose nominal bending amplitude is the beam's section stress at x = 80 times the net
    section's factor (exact arithmetic)."""
    from shaftfe.beam.solve import beam_at_ref
    from shaftfe.fatigue.cards import load_surfaces
    from shaftfe.fatigue.strength import din743_notches, section_stresses
    v = holed_bar("bending")
    beam = beam_at_ref(v)
    rows = din743_notches(v, beam, None, load_surfaces(), {})
    (x, notch, d, span), = [r for r in rows if r[1].kind == "cross_hole"]
    assert (x, d, span, notch.hole_mm) == (80.0, D, 0.0, DH)
    sb = section_stresses(beam, x, d, span)[1]
    assert sb * din.net_section_scale(notch)[1] == pytest.approx(
        32 * HOLED_BAR_F_N * 30.0 / (math.pi * D ** 3) * (math.pi * D ** 3 / 32)
        / (math.pi * D ** 3 / 32 - DH * D * D / 6), rel=1e-9)
