"""DIN 509 undercuts (issue #33): the standard's rows, the outline's geometry, its exact
volume and areas, the meshed solid, and how DIN 743 assesses it; each against an independent
reference.

* The table (``model.grooves.DIN509``) against the rows of DIN 509:1998's table as read (the
  public excerpt named in the module), the HEIDENHAIN CNC PILOT cycle's default rows.
* The outline against the interpretation written in ``model.grooves`` (15° ramp, flat bottom
  at t1, corner arc tangent to the bottom and to the face or, form F, to a plane t2 into it,
  the 8° wall), checked by hand arithmetic.
* Volume and area (``solid.exact.outline_integrals``, Pappus per piece) against the
  trapezoidal rule on a dense sampling of the outline.
* The meshed solid's face groups against those exact areas (both forms, both sides).
* DIN 743: the undercut's row takes the converged Kt where the committed table holds it, else
  DIN 743-2's shoulder α on the bottom diameter (the formula written out).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from shaftfe.model import grooves
from shaftfe.model.examples import four_step_shaft
from shaftfe.solid.exact import groove_area, groove_volume
from shaftfe.solid.plan import Groove, _undercut_profile, prepare


def test_din509_rows_by_diameter():
    """DIN 509:1998 table (forms E and F): the default row per diameter range, a radius the
    table offers for that diameter, none outside it (exact: table values)."""
    U = grooves.Undercut
    assert grooves.din509(17.0) == U(0.6, 0.2, 2.0, 0.1)          # over 10 to 18
    assert grooves.din509(18.0) == U(0.6, 0.2, 2.0, 0.1)          # "bis 18" includes 18
    assert grooves.din509(18.5) == U(0.6, 0.3, 2.5, 0.2)          # over 18 to 80
    assert grooves.din509(8.0) == U(0.4, 0.2, 2.0, 0.1)           # over 3 to 18
    assert grooves.din509(100.0) == U(1.0, 0.4, 4.0, 0.3)         # over 80
    assert grooves.din509(25.0, 1.2) == U(1.2, 0.2, 2.5, 0.1)     # increased fatigue strength
    assert grooves.din509(60.0, 1.6) == U(1.6, 0.3, 4.0, 0.2)
    assert grooves.din509(60.0, 1.2) is None                      # R1.2 × 0.2: up to 50 only
    assert grooves.din509(1.0) is None and grooves.din509_rows(1.0) == ()
    assert [u.r for u in grooves.din509_rows(25.0)] == [0.6, 0.8, 1.0, 1.2]


def _pieces(kind: str, side: str, d: float = 17.0, rho=None) -> Groove:
    u = grooves.din509(d, rho)
    t2 = u.t2 if kind == "din509_f" else 0.0
    xf = 50.0
    x0, x1 = (xf - u.f, xf + t2) if side == "right" else (xf - t2, xf + u.f)
    return Groove("s", 0, kind, 0.5 * d, x0, x1, u.t1, u.r, side, t2)


@pytest.mark.parametrize("kind", ["din509_e", "din509_f"])
def test_outline_follows_the_interpretation(kind):
    """Side "right" (the face at x = 50 on the right): the ramp rises at 15° to the cylinder at
    f from the face; the bottom lies t1 deep; the arc is tangent to the bottom (its centre above
    its start) and ends tangent to a vertical plane t2 into the face (centre level with its
    end); form F's wall rises from there to the face plane at 8° to it. Side "left" is its
    mirror image about the face (hand arithmetic; 1e-12: round-off)."""
    g = _pieces(kind, "right")
    u = grooves.din509(17.0)
    t2 = u.t2 if kind == "din509_f" else 0.0
    p = _undercut_profile(g)
    (_, a), (_, b), (_, c), (arc, e) = p[:4]
    assert a == pytest.approx((50.0 - u.f, 8.5), abs=1e-12)
    assert math.degrees(math.atan2(a[1] - b[1], b[0] - a[0])) == pytest.approx(15.0, abs=1e-9)
    assert b[1] == c[1] == pytest.approx(8.5 - u.t1, abs=1e-12)
    assert arc == "arc" and e[2] == pytest.approx(c[0], abs=1e-12)           # tangent below
    assert e[3] == pytest.approx(e[1], abs=1e-12) and e[3] - c[1] == pytest.approx(u.r)
    assert e[0] == pytest.approx(50.0 + t2, abs=1e-12)                        # tangent plane
    if t2:
        (_, w) = p[4]
        assert w[0] == pytest.approx(50.0, abs=1e-12) and w[1] == pytest.approx(g.r_top)
        assert math.degrees(math.atan2(e[0] - w[0], w[1] - e[1])) == pytest.approx(8.0)
    else:
        assert len(p) == 4 and e[1] == pytest.approx(g.r_top)
    left = _undercut_profile(_pieces(kind, "left"))
    pts_r = [q[1][:2] for q in p]
    pts_l = [q[1][:2] for q in left]
    mirrored = [(100.0 - x, r) for x, r in reversed(pts_r)]
    assert np.allclose(pts_l, mirrored, atol=1e-12)


@pytest.mark.parametrize("kind,side,d,rho", [("din509_e", "right", 17.0, None),
                                             ("din509_f", "right", 17.0, None),
                                             ("din509_e", "left", 25.0, 1.2),
                                             ("din509_f", "left", 40.0, None)])
def test_undercut_volume_and_area_against_quadrature(kind, side, d, rho):
    """The removed volume against the sharp step, π R² f − ∫ π r² dx along the outline (signed
    by dx: form F's outline turns back in x), and the swept area ∫ 2π r ds, against the
    trapezoidal rule on 20 000 points a piece (error O(h²) ≈ 1e-9 relative: 1e-6)."""
    from test_grooves import dense_outline  # (pytest puts this folder on sys.path)
    g = _pieces(kind, side, d, rho)
    x, r = dense_outline(_undercut_profile(g))
    f = g.x1 - g.x0 - g.t2
    vol = math.pi * g.r ** 2 * f - math.pi * np.sum(0.5 * (r[1:] ** 2 + r[:-1] ** 2)
                                                    * np.diff(x))
    area = np.sum(math.pi * (r[1:] + r[:-1]) * np.hypot(np.diff(x), np.diff(r)))
    assert groove_volume(g) == pytest.approx(vol, rel=1e-6)
    assert groove_area(g) == pytest.approx(area, rel=1e-6)


def _both_undercuts():
    """The four-step shaft with a DIN 509 E undercut on the Ø17's right end (below the Ø22's
    face) and an F undercut on the last Ø17's left end, beside the Ø22's other face (its
    fillet 0; no cross hole), and the Ø22's chamfer at that step."""
    v = four_step_shaft(undercut="din509_e", chamfers=True)
    segs = list(v.segments)
    segs[2] = dataclasses.replace(segs[2], fillet_mm=0.0)
    segs[3] = dataclasses.replace(segs[3], grooves=(
        grooves.din509_groove("din509_f", 17.0, "left", (70.0, 100.0)),))
    return dataclasses.replace(v, segments=tuple(segs))


def test_undercut_mesh_against_exact_geometry(tmp_path):
    """Coarse 3D mesh of the four-step shaft with both forms, E on a right end and F on a left
    one (and chamfers: form F's wall is a cone beside the Ø22's chamfer cone, which the faces
    must not swap): volume and every face group against the exact values, the tolerances of
    tests/validation/test_mesh_geometry.py (P2 interpolation of curved faces). One mesh for
    both (the suite's time)."""
    from test_mesh_geometry import _check  # (pytest puts this folder on sys.path)

    from shaftfe.solid.mesh import build_mesh
    v = _both_undercuts()
    sm = build_mesh(v, "coarse", cache_dir=tmp_path)
    for seg in ("b", "d"):
        assert f"groove:{seg}:0" in sm.groups and "fillet:" + seg not in sm.groups
    _check(sm, v)


def test_undercut_rules():
    """The shoulder's fillet must be 0; one undercut per segment end; the face must hold form
    F's recess below the step; the undercut is the shoulder's transition, so no sharp-corner
    warning, and a bearing ring may reach over it to the face (its contact band then ends at
    the undercut)."""
    from shaftfe.errors import InputError
    from shaftfe.solid.plan import sharp_corners
    v = four_step_shaft(undercut="din509_e")
    assert not [c for c in sharp_corners(v) if c.x == 50.0]
    bad = dataclasses.replace(v, segments=(v.segments[0], dataclasses.replace(
        v.segments[1], fillet_mm=1.0), *v.segments[2:]))
    with pytest.raises(InputError, match="fillet_mm"):
        prepare(bad)
    twice = dataclasses.replace(v, segments=(v.segments[0], dataclasses.replace(
        v.segments[1], grooves=v.segments[1].grooves * 2), *v.segments[2:]))
    with pytest.raises(InputError, match="one undercut"):
        prepare(twice)
    # a step Ø17 → Ø19: form F's face top (Ø17 − 0.4 + 1.2 + 2 × 0.1/tan 8° = Ø19.22) is above
    segs = list(four_step_shaft(undercut="din509_f").segments)
    segs[2] = dataclasses.replace(segs[2], diameter_mm=19.0)
    with pytest.raises(InputError, match="face top"):
        prepare(dataclasses.replace(v, segments=tuple(segs)))
    # a ring on [45.5, 50] against the Ø22's face, chamfer 0.3: its band [45.8, 49.7] reaches
    # over the undercut's opening [48, 50]: it bears on [45.8, 48]
    w = dataclasses.replace(v, bearings=(dataclasses.replace(
        v.bearings[0], x_center_mm=47.75, width_mm=4.5, chamfer_mm=0.3),))
    seat = next(s for s in prepare(w).seats if s.name.startswith("bearing"))
    assert (seat.x0, seat.x1) == pytest.approx((45.8, 48.0), abs=1e-12)


def test_din743_assesses_an_undercut_as_its_table_kt_or_the_shoulder_formula():
    """x2_57's Ø17/Ø22 shoulders with DIN 509 E undercuts: the row is named for the undercut,
    judged on the bottom diameter d − 2 t1, with the converged Kt of
    reports/benchmarks/kt_undercuts.json where it holds (kind, D, d, r); a radius it lacks
    takes DIN 743-2's shoulder α from the bottom diameter (the formula by hand, 1e-12)."""
    from shaftfe.beam.scf import converged_kt
    from shaftfe.beam.solve import beam_at_ref
    from shaftfe.fatigue import din743 as din
    from shaftfe.fatigue.cards import load_surfaces
    from shaftfe.fatigue.strength import din743_notches
    from shaftfe.model.loader import load_variant
    table = converged_kt()
    v = load_variant("x2_57")
    segs = list(v.segments)
    i = [s.name for s in segs].index("bearing_seat_gear")
    segs[i] = dataclasses.replace(segs[i], fillet_mm=0.0, grooves=(
        grooves.din509_groove("din509_e", 17.0, "right", (segs[i].x_start_mm,
                                                            segs[i].x_end_mm)),))
    v = dataclasses.replace(v, segments=tuple(segs))
    rows = {n.name: (x, n, d) for x, n, d, _ in din743_notches(v, beam_at_ref(v), None,
                                                               load_surfaces(), table)}
    x, n, d = rows["undercut bearing_seat_gear:0"]
    assert x == 47.0 and d == pytest.approx(16.6) and n.r_mm == 0.6 and n.D_mm == 22.0
    assert "shoulder bearing_seat_gear" not in rows
    # the press fit's edge: where the ring's contact ends, at the undercut's opening (47 − f)
    assert rows["press fit bearing_seat_gear @45"][0] == 45.0
    key = ("din509_e", 22.0, 17.0, 0.6)
    assert key in table and n.alpha == table[key] and "converged" in n.alpha_source
    # not in the table but between its points (x2_57's D/d 1.294 between 1.15 and 1.3 at d 17):
    # interpolated (``scf.undercut_kt``), no warning
    from shaftfe.beam.scf import undercut_kt
    from shaftfe.util.notices import collecting
    table = {k: a for k, a in table.items() if k != key}
    with collecting(echo=False) as got:
        rows = {n.name: n for _, n, _, _ in din743_notches(v, beam_at_ref(v), None,
                                                           load_surfaces(), table)}
    n = rows["undercut bearing_seat_gear:0"]
    assert got == [] and "interpolated" in n.alpha_source
    assert n.alpha == undercut_kt("din509_e", 22.0, 17.0, 0.6, table)[0]
    # a geometry outside the table's points (none of its form E rows left): the formula
    # (DIN 743-2 table 2, shoulder, bending), said in a warning (it reads below the converged
    # Kt over the table's grid)
    table = {k: a for k, a in table.items() if k[0] != "din509_e"}
    with collecting(echo=False) as got:
        rows = {n.name: n for _, n, _, _ in din743_notches(v, beam_at_ref(v), None,
                                                           load_surfaces(), table)}
    assert [w.code for w in got] == ["undercut-kt-formula"]
    n = rows["undercut bearing_seat_gear:0"]
    assert not n.alpha and "DIN 743-2 formula" in n.alpha_source
    t, r, dd, D = 0.5 * (22.0 - 16.6), 0.6, 16.6, 22.0
    q = 0.62 * r / t + 11.6 * r / dd * (1 + 2 * r / dd) ** 2 + 0.2 * (r / t) ** 3 * dd / D
    assert din.alpha_shoulder(dd, D, r, "bending") == pytest.approx(1 + 1 / math.sqrt(q),
                                                                     rel=1e-12)


def test_interpolated_undercut_kt_against_converged_points_between_the_grid():
    """``scf.undercut_kt`` between the table's points against the converged Kt computed there
    (benchmarks/bench_undercuts.py part 4, reports/benchmarks/undercuts.json "interp": the
    harmonic model, three refinements + Richardson, bars ≤ 2e-4 of Kt): the interpolation of
    the committed table recomputed here, within 1.2 % at every point and load (measured
    −1.11 … +0.46 %: the bound is the measured envelope rounded up, the arithmetic on the same
    committed numbers being exact). At the table's own points it returns them; outside them
    (a D/d below the smallest measured at a bracketing d) None."""
    import json
    from pathlib import Path

    from shaftfe.beam.scf import converged_kt, undercut_kt
    rows = json.loads((Path(__file__).resolve().parents[2] / "reports" / "benchmarks"
                       / "undercuts.json").read_text())["interp"]
    inside = [r for r in rows if r["how"] != "outside"]
    assert len(inside) >= 18
    for r in inside:
        got, how = undercut_kt(r["kind"], r["D_mm"], r["d_mm"], r["rho_mm"])
        assert how == "interpolated"
        assert got[r["load"]] == pytest.approx(r["kt"], rel=0.012), r
    for r in rows:
        if r["how"] == "outside":
            assert undercut_kt(r["kind"], r["D_mm"], r["d_mm"], r["rho_mm"]) is None
    for k, a in converged_kt().items():
        if len(k) == 4 and k[0] in ("din509_e", "din509_f"):
            assert undercut_kt(*k) == (a, "table")
