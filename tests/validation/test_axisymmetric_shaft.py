"""The axisymmetric product path on x2_57 and the shoulder-fillet Kt of the harmonic solver.

Sources:
* Statics (lever rule): two bearings without tilt springs make the shaft statically
  determinate, so the reactions follow from the loads alone, whatever the springs: Σ F = 0 and
  Σ M = 0 about a bearing, each part's m e ω² acting at its centroid (the default: a remote
  force and moment through its seat) or at its seat centre (``seed_load_case``: the seed's
  pressure on the half seat, only the seed's three parts). Exact to round-off.
* Peterson's / Roark's shoulder-fillet bending charts (``shaftfe.beam.scf``: W. D. & D. F.
  Pilkey, Peterson's Stress Concentration Factors, 3rd ed., Chart 3.10; Young & Budynas,
  Roark's Formulas, 7th ed., Table 17.1 case 17b) as a sanity band only: the charts are
  photoelastic fits reported to run LOW for shoulders by up to ~24 % (Tipton, Sorem & Rolovic,
  J. Mech. Des. 118 (1996) 321), so the converged FE value must lie in [0.95, 1.30] × chart.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from shaftfe.axisymmetric.model import AxiOptions
from shaftfe.axisymmetric.solve import solve_axisymmetric
from shaftfe.model.loader import load_variant
from shaftfe.static.model import REF_RPM

# round-off: the reactions come from a direct solve whose relative residual is checked ≤ 1e-9
STATICS_TOL = 1e-8


@pytest.fixture(scope="module")
def x2_57(cache):
    v = load_variant("x2_57")
    # the lever rule and ∝ rpm² hold for the loads at the undeformed seats: no spin softening
    return v, solve_axisymmetric(v, [7000.0, REF_RPM],
                                 AxiOptions(level="coarse", spin_softening=False),
                                 cache_dir=cache)


@pytest.mark.parametrize("seed", [False, True], ids=["centroid", "seed_placement"])
def test_reactions_are_the_lever_rule(x2_57, seed, cache):
    v, res = x2_57
    if seed:
        v = v.with_seed_load_case()
        res = solve_axisymmetric(v, REF_RPM, AxiOptions(level="coarse", spin_softening=False,
                                                        seed_load_case=True), cache_dir=cache)
    c = res.case(REF_RPM)
    (a, b) = c.bearings
    Fy = Fz = My = Mz = 0.0
    for at in v.attachments:
        F = at.force_N(REF_RPM)
        ang = math.radians(at.angle_deg)
        x = at.seat_center_mm if seed else at.x_centroid_mm
        Fy += F * math.cos(ang)
        Fz += F * math.sin(ang)
        My += F * math.cos(ang) * (x - a.x_mm)
        Mz += F * math.sin(ang) * (x - a.x_mm)
    L = b.x_mm - a.x_mm
    want_b = (-My / L, -Mz / L)
    want_a = (-Fy - want_b[0], -Fz - want_b[1])
    scale = math.hypot(Fy, Fz)
    for got, want in ((a, want_a), (b, want_b)):
        assert abs(got.Fy_N - want[0]) <= STATICS_TOL * scale
        assert abs(got.Fz_N - want[1]) <= STATICS_TOL * scale
    assert c.equilibrium_residual <= STATICS_TOL


def test_every_rpm_is_the_reference_scaled(x2_57):
    _, res = x2_57
    lo, hi = res.case(7000.0), res.case(REF_RPM)
    s = (7000.0 / REF_RPM) ** 2        # loads ∝ ω²: exact arithmetic up to one rounding
    for p, q in zip(lo.peaks, hi.peaks, strict=True):
        assert p.von_mises_MPa == pytest.approx(q.von_mises_MPa * s, rel=1e-14)


def test_says_what_it_leaves_out(x2_57):
    _, res = x2_57
    feats = {f["feature"] for f in res.omitted}
    assert feats == {"keyway:gear_seat:0", "keyway:cw2_seat:0", "hex_socket"}
    pk = {p.region: p for p in res.case(REF_RPM).peaks}
    assert pk["fillet:collar"].omitted_zone is None            # x ≈ 65: clear of both keyways
    assert pk["fillet:cw2_seat"].omitted_zone == "keyway:cw2_seat:0"


def test_harmonic_truncation_is_stated_and_met(x2_57):
    _, res = x2_57
    assert res.truncation_change < res.options.truncation
    assert res.harmonics[:2] == (0, 1) and all(n % 2 == 1 for n in res.harmonics[1:])


@pytest.mark.parametrize("D, d, r", [(1.5, 1.0, 0.1), (1.2, 1.0, 0.05)])
def test_shoulder_kt_within_the_chart_band(D, d, r):
    from shaftfe.axisymmetric.kt import kt_once
    from shaftfe.beam.scf import kt_shoulder_bending
    res, _ = kt_once(D, d, r, refine=1)
    for fit in ("roark", "peterson"):
        chart = float(kt_shoulder_bending(D, d, r, fit)[0])
        assert 0.95 * chart <= res["bending"].kt <= 1.30 * chart, (fit, chart, res)
    # tension > bending > torsion for a shoulder (every chart family, and Noda-Takase)
    assert res["tension"].kt > res["bending"].kt > res["torsion"].kt > 1.0


def test_cli_axisymmetric_writes_its_files(tmp_path, cache, monkeypatch, capsys):
    from shaftfe.cli import main
    monkeypatch.setenv("SHAFTFE_CACHE_DIR", str(cache))
    out = tmp_path / "axi"
    code = main(["static", "--variant", "x2_57", "--model", "axisymmetric", "--level",
                 "coarse", "--rpm", "7000", "--out", str(out)])
    assert code == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["model"] == "axisymmetric" and (out / "result.vtu").stat().st_size > 0
    assert "zone of influence" in capsys.readouterr().out
    code = main(["static", "--variant", "x2_57", "--model", "axisymmetric", "--order", "1",
                 "--out", str(tmp_path / "bad")])
    err = capsys.readouterr().err
    assert code == 2 and "--order" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "bad").exists()


def test_revolved_vtu_matches_the_axis_deflection(x2_57):
    """The revolved field's points on the axis carry the axis deflection of the result."""
    from shaftfe.axisymmetric.outputs import revolved_fields
    _, res = x2_57
    pts, cells, disp, vm = revolved_fields(res.solution, 1.0, sectors=8)
    on_axis = np.abs(pts[:, 1]) + np.abs(pts[:, 2]) < 1e-12
    from shaftfe.axisymmetric.solve import axis_displacement
    want = axis_displacement(res.solution, pts[on_axis, 0])
    assert np.allclose(disp[on_axis], want, rtol=0, atol=1e-12 * np.abs(want).max())
    assert cells.shape[1] == 6 and np.all(np.isfinite(vm))
