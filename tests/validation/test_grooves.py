"""Circumferential grooves (issue #33): the groove's stress concentration, its DIN 743 factors
and its exact geometry, each against an independent reference.

* Kt of a U groove in a round bar (``axisymmetric.kt.grooved_bar``: the harmonic solver on the
  bar of diameter D with a groove of bottom diameter d and radius ρ, free ends loaded by the
  exact Saint-Venant fields) against DIN 743-2:2012 table 2 ("Rundnut", a Neuber-type fit of
  measured and computed notch factors). Nominal stresses on the groove's bottom diameter.
* DIN 743-2's groove factors, written out by hand (the formulas as the standard prints them).
* The groove's volume and face area against numerical quadrature of its outline.
"""

import math

import numpy as np
import pytest

from shaftfe.axisymmetric import kt
from shaftfe.fatigue import din743 as din
from shaftfe.solid.exact import groove_area, groove_volume
from shaftfe.solid.plan import Groove, _groove_profile

# DIN 743-2's fits are checked here as a chart is: as a band. Neuber-type fits of notch
# factors reproduce the data they were fitted to within several per cent, and the shoulder
# charts are known to lie up to 20 % off converged FE in places (FINDINGS, "On the charts");
# 10 % is the band. What the test can catch: a wrong nominal section, a wrong load, a groove
# meshed with the wrong radius (Kt ∝ ~1/√ρ: a factor 2 in ρ moves Kt by 20-40 %).
CHART_BAND = 0.10
GROOVES = [(22.0, 20.0, 1.0), (20.0, 18.0, 0.5)]      # (D, d, ρ): shallow, sharper


@pytest.mark.parametrize("D,d,rho", GROOVES)
def test_u_groove_kt_within_the_din743_band(D, d, rho, cache):
    """Kt in tension, bending and torsion on the second mesh level (its distance to the
    three-level Richardson value: measured ≤ 3e-4 on these grooves, reports/benchmarks/
    grooves.md) within CHART_BAND of DIN 743-2's α; the peak at the groove's bottom (90° along
    the semicircle from the left flank: the bar and its loads are symmetric about the
    groove's mid-plane, so the peak lies on it; 1° is the peak fit's resolution)."""
    res, _ = kt.kt_once(D, d, rho, refine=1, cache_dir=cache, shape="groove")
    for load in kt.LOADS:
        want = din.alpha_groove(d, D, rho, load)
        assert res[load].kt == pytest.approx(want, rel=CHART_BAND), load
        assert res[load].angle_deg == pytest.approx(90.0, abs=1.0), load


def test_din471_groove_kt_between_the_shoulder_and_the_u_notch_charts(cache):
    """A DIN 471 ring groove on Ø17 (m 1.1, t 0.4, flat-bottomed, corner radius 0.1 mm) on the
    second mesh level (within 0.05 % of the converged value on every ring groove measured,
    reports/benchmarks/ring_grooves.md): its Kt in tension, bending and torsion lies between
    the two published chart fits that bracket a flat-bottomed groove: from below the shoulder
    of the same step and radius (one corner alone; Roark 7th ed. Table 17.1 cases 17a–17c),
    from above the U-notch of the groove's depth and radius (the narrowest groove of that
    radius; Roark's cases 6a–6c). Measured on this groove: the shoulder's fit 7 … 21 % below,
    the U-notch's 28 … 32 % above; over all 13 ring grooves measured the bracket holds with
    ≥ 3 % to spare below and ≥ 20 % above (ring_grooves.md). A groove meshed at twice its
    radius (measured: Kt −19 % in tension at ρ 0.2) falls out below in tension. The peak lies
    on a corner arc (not NaN)."""
    from shaftfe.beam.scf import kt_shoulder, kt_u_notch
    from shaftfe.model.grooves import din471
    _, t = din471(17.0)
    res, _ = kt.kt_once(17.0, 17.0 - 2 * t, 0.1, refine=1, cache_dir=cache, shape="din471")
    for load in kt.LOADS:
        lo = kt_shoulder(17.0, 17.0 - 2 * t, 0.1, "roark", load).kt
        hi = kt_u_notch(17.0, t, 0.1, load).kt
        assert lo < res[load].kt < hi, (load, lo, res[load].kt, hi)
        assert 0.0 <= res[load].angle_deg <= 90.0, load


def test_groove_factors_by_hand():
    """DIN 743-2 table 2/3 (round groove) and §4.2.4 (ring groove), the numbers written out
    (exact arithmetic: 1e-12)."""
    # α bending of d 16, D 20, r 1: t = 2
    q = 0.2 * 1 / 2 + 2 * 2.75 * (1 / 16) * (1 + 2 / 16) ** 2
    assert din.alpha_groove(16.0, 20.0, 1.0, "bending") == pytest.approx(1 + 1 / math.sqrt(q),
                                                                         rel=1e-12)
    # G' of that groove: φ = 1/(4√(t/r) + 2) (d/D = 0.8 > 0.67)
    ph = 1 / (4 * math.sqrt(2.0) + 2)
    assert din.gradient_groove(16.0, 20.0, 1.0, "bending") == pytest.approx(2 * (1 + ph),
                                                                            rel=1e-12)
    assert din.gradient_groove(16.0, 20.0, 1.0, "torsion") == pytest.approx(1.0, rel=1e-12)
    # ρ* at σ_S = 600 MPa
    rs = 10 ** -(0.514 + 0.00152 * 600)
    assert din.rho_star(600.0) == pytest.approx(rs, rel=1e-12)
    # ring groove t 0.4, r 0.1, m 1.1 (m/t = 2.75 ≥ 1.4: no narrow-groove factor), d = 30 mm
    # (d_BK: K3 cancels)
    b = din.beta_ring_groove(0.4, 0.1, 1.1, 600.0, 30.0)
    assert b["bending"] == pytest.approx(0.9 * (1.14 + 1.08 * math.sqrt(0.4 / (0.1 + 2.9 * rs))),
                                         rel=1e-12)
    assert b["tension"] == pytest.approx(0.9 * (1.27 + 1.17 * math.sqrt(0.4 / (0.1 + 2.9 * rs))),
                                         rel=1e-12)
    assert b["torsion"] == pytest.approx(1.48 + 0.45 * math.sqrt(0.4 / (0.1 + rs)), rel=1e-12)
    # a narrow groove (m/t = 1.0): × 1.08 (m/t)^−0.2 = 1.08, capped at 2.5 in torsion
    n = din.beta_ring_groove(1.0, 0.1, 1.0, 600.0, 30.0)
    assert n["torsion"] == pytest.approx(min(1.08 * (1.48 + 0.45 * math.sqrt(1.0 / (0.1 + rs))),
                                             2.5), rel=1e-12)


def dense_outline(pieces, n: int = 20001):
    """Points (x, r) along an outline (``solid.plan`` pieces, the first one's end the start),
    20 000 a piece: a line's by linear steps, an arc's (the minor one about its centre) by
    equal angles."""
    pts = [tuple(pieces[0][1][:2])]
    for kind, data in pieces[1:]:
        x0, r0 = pts[-1]
        x1, r1 = data[0], data[1]
        if kind == "line":
            t = np.linspace(0, 1, n)[1:]
            pts += list(zip(x0 + t * (x1 - x0), r0 + t * (r1 - r0), strict=True))
        else:
            xc, rc = data[2], data[3]
            a0 = math.atan2(r0 - rc, x0 - xc)
            da = math.remainder(math.atan2(r1 - rc, x1 - xc) - a0, 2 * math.pi)
            t = a0 + da * np.linspace(0, 1, n)[1:]
            rho = math.hypot(x0 - xc, r0 - rc)
            pts += list(zip(xc + rho * np.cos(t), rc + rho * np.sin(t), strict=True))
    return np.array(pts).T


@pytest.mark.parametrize("w,t,rho", [(3.0, 1.0, 1.0), (2.0, 1.5, 1.0), (1.1, 0.4, 0.1),
                                     (4.0, 1.0, 0.5)])
def test_groove_volume_and_area_against_quadrature(w, t, rho):
    """Pappus closed forms against the trapezoidal rule on 20 000 points a piece: the removed
    volume π ∫ (R² − r²) dx (the outline is a function of x between the flanks, the flanks
    add nothing) and the area ∫ 2π r ds (trapezoid error O(h²) ≈ 1e-9 relative: 1e-6)."""
    g = Groove("s", 0, "u", 10.0, 5.0, 5.0 + w, t, rho)
    x, r = dense_outline(_groove_profile(g))
    vol = math.pi * np.trapezoid(g.r ** 2 - r ** 2, x)
    ds = np.hypot(np.diff(x), np.diff(r))
    area = np.sum(2 * math.pi * 0.5 * (r[1:] + r[:-1]) * ds)
    assert groove_volume(g) == pytest.approx(vol, rel=1e-6)
    assert groove_area(g) == pytest.approx(area, rel=1e-6)


def test_din743_takes_the_converged_kt_only_for_a_one_arc_groove():
    """``fatigue.strength.din743_notches``: a U groove whose D, d, ρ the committed table holds
    AND whose bottom is one arc (width 2ρ, the table's bar, ``kt.grooved_bar``) takes the
    converged Kt; the same D, d, ρ with a flat bottom (width 3) takes DIN 743-2's formula; the
    row names its source either way."""
    import dataclasses

    from shaftfe.beam.scf import converged_kt
    from shaftfe.beam.solve import beam_at_ref
    from shaftfe.fatigue.cards import load_surfaces
    from shaftfe.fatigue.strength import din743_notches
    from shaftfe.model.examples import holed_bar
    from shaftfe.model.variant import Groove
    table = converged_kt()
    key = ("groove", 22.0, 20.0, 1.0)
    assert key in table                      # reports/benchmarks/kt_grooves.json holds it
    for width, want in ((2.0, "converged Kt"), (3.0, "DIN 743-2 formula")):
        v = holed_bar("bending")             # a Ø22 bar on two bearings, the groove at x = 80
        seg = dataclasses.replace(v.segments[0], diameter_mm=22.0, cross_holes=(),
                                  grooves=(Groove("u", 80.0, width, 1.0, 1.0),))
        v = dataclasses.replace(v, segments=(seg,))
        rows = [r for r in din743_notches(v, beam_at_ref(v), None, load_surfaces(), table)
                if r[1].kind == "groove"]
        assert len(rows) == 1 and rows[0][1].alpha_source.startswith(want), width
        assert (rows[0][1].alpha == table[key]) == (width == 2.0)


def test_a_notch_under_a_load_band_is_refused():
    """A groove under a ``[[loads]]`` band would be loaded by the axisymmetric model (the band
    covers its faces) and not by the 3D one: refused, naming the load (solid.plan)."""
    import dataclasses

    from shaftfe.errors import InputError
    from shaftfe.model.examples import four_step_shaft
    from shaftfe.model.loads import Load
    from shaftfe.solid.plan import prepare
    v = four_step_shaft(groove=True)
    v = dataclasses.replace(v, loads=(Load("push", "force", 53.0, (51.0, 55.0), 100.0, 0.0),))
    with pytest.raises(InputError, match="push"):
        prepare(v)


def test_a_din471_groove_from_a_reconstructed_table_row_is_warned():
    """DIN 471's rows from 20 mm on were reconstructed (``model.grooves``): a din471 groove of
    that size says so in a warning; one from the read rows (Ø17) does not."""
    import dataclasses

    from shaftfe.model.examples import holed_bar
    from shaftfe.model.grooves import din471
    from shaftfe.model.variant import Groove
    from shaftfe.solid.plan import prepare
    from shaftfe.util.notices import collecting
    for dia, warned in ((22.0, True), (17.0, False)):
        m, t = din471(dia)
        v = holed_bar("bending")
        seg = dataclasses.replace(v.segments[0], diameter_mm=dia, cross_holes=(),
                                  grooves=(Groove("din471", 80.0, m, t, 0.1),))
        with collecting(echo=False) as got:
            prepare(dataclasses.replace(v, segments=(seg,)))
        assert any(n.code == "din471-reconstructed" for n in got) == warned, dia


def test_a_groove_the_3d_mesh_does_not_resolve_is_warned():
    """The full 3D model refines a groove's corner arcs only down to
    ``solid.mesh.GROOVE_HOT_MIN_MM`` elements: a DIN 471 groove's 0.1 mm corners are not
    resolved at any level, and its 3D peak reads low (measured: reports/benchmarks/
    ring_grooves.md §3), so each run of the 3D model warns ``groove-unresolved`` naming the
    groove; a U groove of radius 0.8 is resolved at the levels with the hot-spot field (no
    warning). No mesh is built: the rule is the size field's."""
    import dataclasses

    from shaftfe.model.examples import four_step_shaft
    from shaftfe.model.grooves import din471
    from shaftfe.model.variant import Groove
    from shaftfe.solid.mesh import unresolved_grooves, warn_unresolved_grooves
    from shaftfe.util.notices import collecting
    v = four_step_shaft(groove=True)
    assert unresolved_grooves(v, "default") == ()
    m, t = din471(22.0)
    segs = list(v.segments)
    i = next(k for k, s in enumerate(segs) if s.grooves)
    segs[i] = dataclasses.replace(segs[i], grooves=(Groove("din471", 53.0, m, t, 0.1),))
    ring = dataclasses.replace(v, segments=tuple(segs))
    for level in ("coarse", "default", "fine"):
        (g,) = unresolved_grooves(ring, level)
        assert g.rho == 0.1
    with collecting(echo=False) as got:
        warn_unresolved_grooves(ring, "default")
    (w,) = [w for w in got if w.code == "groove-unresolved"]     # (Ø22's row: reconstructed)
    assert w.where == "groove:c:0" and "0.1 mm" in w.text and "axisymmetric" in w.text
    # and `shaftfe static --model solid` marks that groove's row in its peak table
    from types import SimpleNamespace

    from shaftfe.commands.static import _low_grooves
    assert _low_grooves(ring, SimpleNamespace(level="default")) == {"groove:c:0"}
    assert _low_grooves(v, SimpleNamespace(level="default")) == set()
