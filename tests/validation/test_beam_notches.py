"""The beam's notches other than shoulders (issue #33): a groove's and a transverse hole's
Kt × nominal, each against the statics of a statically determinate bar written out by hand.

Case: ``model.examples.holed_bar`` (Ø20 × 160, supports at 10 and 150, loads at 40 and 120:
between them M = F · 30 mm in bending, T in torsion, P in tension, by statics), with its
transverse hole at x = 80, or a U groove there instead.

* Nominal stresses: a hole's on the net section (DIN 743-2: A = πd²/4 − d_h d,
  W_b = πd³/32 − d_h d²/6, W_t = πd³/16 − d_h d²/6); a groove's on its bottom diameter.
* Kt: ``beam.scf`` (Roark 7th ed. Table 17.1 cases 6a–6c for the groove; DIN 743-2's fit of
  Peterson's charts for the hole; both checked in tests/validation/test_scf.py).
* Peak: von Mises of the Kt-scaled components; at a hole torsion's peak is the bore's uniaxial
  stress 2 Kt_T τ.

The beam is nodally exact for these loads (point loads, piecewise-constant sections), so the
section forces are exact up to round-off of the solve (1e-9 relative).
"""

from __future__ import annotations

import dataclasses
import math

import pytest

from shaftfe.beam.scf import kt_cross_hole, kt_u_notch, net_section_moduli
from shaftfe.beam.solve import analyse
from shaftfe.model.examples import (
    HOLED_BAR_F_N,
    HOLED_BAR_P_N,
    HOLED_BAR_T_NMM,
    holed_bar,
)
from shaftfe.model.variant import Groove

TOL = 1e-9       # round-off of the beam's solve (its section forces are exact by statics)


def _notch(v):
    (r,) = analyse(v, 0.0)
    (n,) = [n for n in r.notches if n.kind != "shoulder"]
    return r, n


@pytest.mark.parametrize("kind", ["bending", "torsion", "tension"])
def test_cross_hole_peak_on_the_net_section(kind):
    r, n = _notch(holed_bar(kind))
    a, wb, wt = net_section_moduli(20.0, 4.0)
    if kind == "bending":
        nom = HOLED_BAR_F_N * 30.0 / wb
        peak = kt_cross_hole(20.0, 4.0, "bending").kt * nom
    elif kind == "torsion":
        tau = HOLED_BAR_T_NMM / wt
        nom = math.sqrt(3.0) * tau
        peak = 2.0 * kt_cross_hole(20.0, 4.0, "torsion").kt * tau
    else:
        nom = HOLED_BAR_P_N / a
        peak = kt_cross_hole(20.0, 4.0, "tension").kt * nom
    assert (n.kind, n.name, n.x_mm, n.hole_mm) == ("cross_hole", "cross hole bar:0", 80.0, 4.0)
    assert n.sigma_nom_MPa == pytest.approx(nom, rel=TOL)
    assert n.sigma_peak_MPa == pytest.approx(peak, rel=TOL)
    assert r.max_peak_MPa == pytest.approx(peak, rel=TOL) and r.x_max_peak_mm == 80.0
    assert "transverse hole" in n.kt_note


def _table_kt(D: float, d: float, rho: float, load: str) -> float:
    """The converged Kt of a one-arc U groove, read from the committed table itself."""
    import json

    from shaftfe.util.paths import REPO_DIR
    t = json.loads((REPO_DIR / "reports/benchmarks/kt_grooves.json").read_text())
    (row,) = [g for g in t["grooves"] if (g["D_mm"], g["d_mm"]) == (D, d)
              and abs(g["rho_mm"] - rho) < 1e-9]
    return row[load]["kt"]


@pytest.mark.parametrize("kind", ["bending", "torsion"])
@pytest.mark.parametrize("width", [2.0, 3.0])
def test_u_groove_peak_on_its_bottom_diameter(kind, width):
    """A U groove 1 deep with corner radius 1 on the Ø20 bar: one arc (width 2) takes the
    converged Kt of reports/benchmarks/kt_grooves.json, which holds it; flat-bottomed (width
    3) Roark's U-notch fit of its depth and radius."""
    v = holed_bar(kind)
    seg = dataclasses.replace(v.segments[0], cross_holes=(),
                              grooves=(Groove("u", 80.0, width, 1.0, 1.0),))
    r, n = _notch(dataclasses.replace(v, segments=(seg,)))
    d = 18.0
    k = (_table_kt(20.0, d, 1.0, kind) if width == 2.0 else
         kt_u_notch(20.0, 1.0, 1.0, kind).kt)
    if kind == "bending":
        nom = HOLED_BAR_F_N * 30.0 * 32.0 / (math.pi * d ** 3)
        peak = k * nom
    else:
        tau = HOLED_BAR_T_NMM * 16.0 / (math.pi * d ** 3)
        nom, peak = math.sqrt(3.0) * tau, math.sqrt(3.0) * k * tau
    assert (n.kind, n.D_mm, n.d_mm, n.r_mm) == ("groove", 20.0, 18.0, 1.0)
    assert n.sigma_nom_MPa == pytest.approx(nom, rel=TOL)
    assert n.sigma_peak_MPa == pytest.approx(peak, rel=TOL)
    assert ("Kt converged" if width == 2.0 else "Kt roark U-notch") in n.kt_note
    assert "grooves and transverse holes ignored in the stiffness" in " ".join(r.notes)


def test_a_din471_groove_takes_its_converged_kt_or_a_conservative_fit():
    """A DIN 471 groove on the Ø20 bar: at the default corner radius 0.1 the converged Kt of
    reports/benchmarks/kt_ring_grooves.json (read from the file); at 0.15, which the table
    lacks, Roark's U-notch fit, which lies above the converged Kt of every ring groove
    measured (ring_grooves.md), with a note saying so."""
    import json

    from shaftfe.model.grooves import din471
    from shaftfe.util.paths import REPO_DIR
    m, t = din471(20.0)
    rows = json.loads((REPO_DIR / "reports/benchmarks/kt_ring_grooves.json").read_text())
    (row,) = [g for g in rows["ring_grooves"] if g["D_mm"] == 20.0 and g["rho_mm"] == 0.1]
    v = holed_bar("bending")
    for rho, want in ((0.1, row["bending"]["kt"]), (0.15, kt_u_notch(20.0, t, 0.15).kt)):
        seg = dataclasses.replace(v.segments[0], cross_holes=(),
                                  grooves=(Groove("din471", 80.0, m, t, rho),))
        _, n = _notch(dataclasses.replace(v, segments=(seg,)))
        assert n.kind == "ring_groove" and n.kt == pytest.approx(want, rel=1e-12)
        assert n.sigma_peak_MPa == pytest.approx(
            want * HOLED_BAR_F_N * 30.0 * 32.0 / (math.pi * (20.0 - 2 * t) ** 3), rel=TOL)
        assert ("Kt converged" in n.kt_note) == (rho == 0.1)
        assert ("roark U-notch" in n.kt_note and "above its converged Kt" in n.kt_note) \
            == (rho == 0.15)


def test_a_shaft_without_grooves_or_holes_keeps_its_notches_and_json():
    """x2_57 (no grooves, no holes): the beam's notches are its four shoulders, and their JSON
    has exactly the keys, in the order, it had before grooves and holes (a summary stays
    byte-identical)."""
    from shaftfe.model.loader import load_variant
    (r,) = analyse(load_variant("x2_57"), 8000.0)
    assert [n.kind for n in r.notches] == ["shoulder"] * 4
    keys = ["x_mm", "D_mm", "d_mm", "r_mm", "kt", "kt_in_range", "kt_note", "kt_tension",
            "kt_torsion", "M_Nmm", "N_N", "T_Nmm", "sigma_nom_MPa", "sigma_peak_MPa"]
    assert all(list(d) == keys for d in r.to_dict()["notches"])


def test_a_sharp_shoulder_unloaded_in_a_load_has_no_nan_peak():
    """A sharp corner (fillet 0: Kt infinite in every load) in bending only: its peak is
    infinite (null in JSON: the singularity), and the loads it does not carry (tension,
    torsion: zero) add nothing, not ∞ × 0 = NaN."""
    import json

    v = holed_bar("bending")
    a, = v.segments
    segs = (dataclasses.replace(a, length_mm=80.0, cross_holes=()),
            dataclasses.replace(a, name="b", x_start_mm=80.0, length_mm=80.0,
                                diameter_mm=18.0, cross_holes=()))
    (r,) = analyse(dataclasses.replace(v, segments=segs), 0.0)
    (n,) = r.notches
    assert n.kt == math.inf and n.sigma_peak_MPa == math.inf
    assert json.loads(json.dumps(r.to_dict()))["notches"][0]["sigma_peak_MPa"] is None
