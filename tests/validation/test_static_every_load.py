"""The 3D static path with every load (issue #31 items 3 and 8), against independent references.

* Plain shaft in torsion (Saint-Venant; Timoshenko & Goodier, Theory of Elasticity, 3rd ed.
  1970, §104): between the load bands the surface carries τ = 16 T / (π d³).
* Pure bending by two end moments (Euler-Bernoulli / Saint-Venant flexure, ibid. §102): away
  from the load bands σ_x = −M_z y / I, I = π d⁴ / 64.
* A stepped shaft in tension and in torsion through the public API (a variant file written from
  docs/VARIANTS.md with [[loads]] and [[load_cases]]): the fillet's Kt against the project's
  converged axisymmetric Kt (reports/benchmarks/kt_reference.json, ``shaftfe.axisymmetric.kt``:
  another element, mesh and recovery) and against Peterson's charts (Pilkey & Pilkey,
  Peterson's Stress Concentration Factors, 3rd ed. 2008, Chart 3.4 tension and the torsion
  chart of the stepped round bar, by the curve fits printed beside them) as a band.
* Superposition: a case of two patterns equals the sum of the separate solves to round-off.

All on the coarse level, spin softening off (the references are linear statics).
"""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

from shaftfe.model.loads import Load
from shaftfe.static.model import StaticOptions
from shaftfe.static.solve import solve_static

ROOT = Path(__file__).resolve().parents[2]
OPTS = StaticOptions(level="coarse", spin_softening=False)
FINE = StaticOptions(level="fine", spin_softening=False)
# P2 tets reproduce the torsion and bending fields exactly on straight elements; what is left
# is the curved boundary's discretisation and the surface recovery, not the load bands (moving
# them 10 mm further changes nothing: measured): pointwise over the surface nodes the fine
# level of the Ø20 cylinder (9 357 dofs) reads 0.38 % in torsion (default 0.86 %, coarse
# 2.8 %); 0.5 % is the bound
CLOSED_FORM_TOL = 0.005


def _bare_cylinder():
    from tests.test_static import cylinder
    return dataclasses.replace(cylinder(), attachments=())


def _surface_nodes(res, x0, x1, r):
    x = res.mesh.mesh.doflocs
    rr = np.hypot(x[1], x[2])
    return np.nonzero((x[0] >= x0) & (x[0] <= x1) & (rr > r * (1 - 1e-6)))[0]


def test_plain_shaft_torsion_against_saint_venant(cache):
    T, d = 2.0e5, 20.0
    v = dataclasses.replace(_bare_cylinder(), loads=(
        Load("in", "torque", 30.0, (29.0, 31.0), T), Load("out", "torque", 90.0, (89.0, 91.0), -T)))
    res = solve_static(v, 10000.0, FINE, cache_dir=cache, beam=False)
    s = res.pattern_stress[("constant",)]
    x = res.mesh.mesh.doflocs
    ids = _surface_nodes(res, 50.0, 70.0, 0.5 * d)
    th = np.arctan2(x[2, ids], x[1, ids])
    tau = -np.sin(th) * s[3, ids] + np.cos(th) * s[5, ids]       # τ_xθ = −sinθ σ_xy + cosθ σ_xz
    # between the torques the section carries M_x = −T (the part left of a cut holds +T at
    # x = 30; the cut face with normal +x exerts −T): τ_xθ = −16 T / (π d³) on the surface
    ref = -16 * T / (math.pi * d ** 3)
    err = np.abs(tau / ref - 1).max()
    print(f"torsion: max |τ/τ_ref − 1| = {err:.2e} over {ids.size} surface nodes")
    assert ids.size > 20 and err <= CLOSED_FORM_TOL, err
    # the torques sum to zero and no bearing holds torsion: the gauge carries round-off only
    assert res.diagnostics["twist_gauge_torque_rel"] < 1e-8


def test_pure_bending_by_end_moments_against_beam_theory(cache):
    M, d = 1.0e5, 20.0
    v = dataclasses.replace(_bare_cylinder(), loads=(
        Load("a", "moment", 30.0, (29.0, 31.0), -M, 90.0),
        Load("b", "moment", 90.0, (89.0, 91.0), M, 90.0)))
    res = solve_static(v, 10000.0, FINE, cache_dir=cache, beam=False)
    s = res.pattern_stress[("constant",)]
    x = res.mesh.mesh.doflocs
    ids = _surface_nodes(res, 50.0, 70.0, 0.5 * d)
    nominal = 32 * M / (math.pi * d ** 3)
    # between the two moments the shaft carries M_z = +M: σ_x = −M y / I
    want = -M * x[1, ids] / (math.pi * d ** 4 / 64)
    err = np.abs(s[0, ids] - want).max() / nominal
    print(f"bending: max |σ_x − M y/I| / (32 M/(π d³)) = {err:.2e} over {ids.size} nodes")
    assert ids.size > 20 and err <= CLOSED_FORM_TOL, err
    # self-equilibrated loads: the bearings carry nothing (round-off of the solve, 1e-8)
    assert max(b.F_radial_N for b in res.cases[0].bearings) < 1e-8 * 2 * M / 60.0


# --------------------------------------------------------------------------- stepped shaft

# the grid shoulder D/d = 1.3, r/d = 0.1 of the reference tables (d = 17 mm)
D, d_, RHO = 22.1, 17.0, 1.7
F_AX, T_TOR = 1000.0, 1.0e4
STEPPED = f"""
[[loads]]
name = "pull_left"
kind = "axial_force"
x_mm = 1.0
F_N = {-F_AX}

[[loads]]
name = "pull_right"
kind = "axial_force"
x_mm = 79.0
F_N = {F_AX}

[[loads]]
name = "twist_left"
kind = "torque"
x_mm = 1.0
T_Nmm = {T_TOR}
scales_with = "torque_Nm"
channel_ref = 10.0

[[loads]]
name = "twist_right"
kind = "torque"
x_mm = 79.0
T_Nmm = {-T_TOR}
scales_with = "torque_Nm"
channel_ref = 10.0

[[load_cases]]
name = "tension"
rpm = 0.0
factors = {{ twist_left = 0.0, twist_right = 0.0 }}

[[load_cases]]
name = "torsion"
rpm = 0.0
factors = {{ pull_left = 0.0, pull_right = 0.0 }}

[[load_cases]]
name = "both"
rpm = 0.0
"""


def _stepped_variant(tmp: Path, loads: str = STEPPED):
    from shaftfe.model.loader import load_variant
    text = (ROOT / "docs/examples/minimal.toml").read_text(encoding="utf-8")
    text = text[:text.index("[[attachments]]")]                 # loads only, no part
    text = text.replace("fillet_mm = 0.5", f"fillet_mm = {RHO}", 1)
    text = text.replace("diameter_mm = 22.0", f"diameter_mm = {D}", 1)
    p = tmp / "stepped.toml"
    p.write_text(text + loads, encoding="utf-8")
    return load_variant(p)


@pytest.fixture(scope="module")
def stepped(cache):
    from shaftfe.fe import reuse
    v = _stepped_variant(cache)
    with reuse.shared():           # one mesh: K and the factorisation made once
        out = {c: solve_static(v, None, OPTS, case=c, cache_dir=cache, beam=False)
               for c in ("tension", "torsion", "both")}
        # separate variants: the tension loads only, the torsion loads only (own solves)
        for name, lds in (("ten", v.loads[:2]), ("tor", v.loads[2:])):
            out[name] = solve_static(dataclasses.replace(v, loads=lds, load_cases=()), 0.0,
                                     OPTS, cache_dir=cache, beam=False)
    return v, out


def _axi_kt(load: str) -> float:
    ref = json.loads((ROOT / "reports/benchmarks/kt_reference.json").read_text())
    row = next(g for g in ref["grid"] if math.isclose(g["D_over_d"], D / d_)
               and math.isclose(g["r_over_d"], RHO / d_))
    return float(row[load]["kt"])


def _peterson(load: str) -> float:
    """Kt of the curve fits beside Peterson's charts (Pilkey & Pilkey 2008, stepped round bar
    with shoulder fillet; t = (D − d)/2, fits for 2 ≤ t/r ≤ 20 (tension), 0.25 ≤ t/r ≤ 4
    (torsion)): Kt = C1 + C2 (2t/D) + C3 (2t/D)² + C4 (2t/D)³."""
    t = 0.5 * (D - d_)
    q, s, a = t / RHO, math.sqrt(t / RHO), 2 * t / D
    if load == "tension":
        c = (1.200 + 0.860 * s - 0.022 * q, -1.805 - 0.346 * s - 0.038 * q,
             2.198 - 0.486 * s + 0.165 * q, -0.593 - 0.028 * s - 0.106 * q)
    else:
        c = (0.905 + 0.783 * s - 0.075 * q, -0.437 - 1.969 * s + 0.553 * q,
             1.557 + 1.073 * s - 0.578 * q, -1.061 + 0.171 * s + 0.086 * q)
    return c[0] + c[1] * a + c[2] * a ** 2 + c[3] * a ** 3


@pytest.mark.parametrize("load", ["tension", "torsion"])
def test_stepped_shaft_fillet_kt(stepped, load):
    _, out = stepped
    res = out[load]
    peak = {p.region: p for p in res.cases[0].peaks}["fillet:left_seat"]
    nominal = (4 * F_AX / (math.pi * d_ ** 2) if load == "tension"
               else 16 * T_TOR / (math.pi * d_ ** 3))
    kt3d = peak.max_principal_MPa / nominal
    axi = _axi_kt(load)
    err = kt3d / axi - 1
    from shaftfe.static.measured_errors import shoulder_bars
    ERROR_BAR_PCT = shoulder_bars().bars["solid"]
    print(f"{load}: Kt 3D {kt3d:.4f}, axisymmetric {axi:.4f} ({100 * err:+.2f} %), "
          f"Peterson fit {_peterson(load):.4f}; coarse bending bar {ERROR_BAR_PCT['coarse']}")
    # the bars were measured in bending: a run in tension or torsion prints none, and says why
    assert "fillet:left_seat" not in res.truth_error_bar_pct
    assert "measured in bending" in res.truth_bar_notes["fillet:left_seat"]
    # the coarse level's bending bar (static.measured_errors.shoulder_bars: the envelope of its
    # measured error against the axisymmetric truth over a grid of shoulders: −4.39 … −1.62 %);
    # tension and torsion load the same fillet with no steeper a gradient than bending, so
    # their error stays within the bar's magnitude (measured −3.31 % tension, −0.29 % torsion)
    lo, hi = ERROR_BAR_PCT["coarse"]
    assert abs(err) <= max(abs(lo), abs(hi)) / 100, (load, kt3d, axi, (lo, hi))
    kp = _peterson(load)
    if load == "tension":
        # Peterson's tension and bending charts read low at small r/d (Tipton, Sorem & Rolovic,
        # J. Mech. Des. 118, 1996: by up to 40 %): a band [chart, 1.4 × chart]
        assert kp <= kt3d <= 1.4 * kp, (kt3d, kp)
    else:
        # the torsion fit (t/r = 4.17, 4 % beyond its range 4) and the chart's reading: ± 6 %
        assert abs(kt3d / kp - 1) <= 0.06, (kt3d, kp)


def test_case_of_two_patterns_is_the_sum_of_separate_solves(stepped):
    _, out = stepped
    both, r1, r2 = out["both"], out["ten"], out["tor"]
    assert len(both.patterns) == 4            # each load factored alone by a case: 4 patterns
    assert len(r1.patterns) == 1 and len(r2.patterns) == 1
    # linear superposition with the same factorisation: round-off of the solve (relative
    # residual ≤ 1e-8 checked; measured ~1e-13)
    scale = np.abs(both.u_ref).max()
    assert np.abs(both.u_ref - r1.u_ref - r2.u_ref).max() <= 1e-9 * scale
    sc = np.abs(both.stress_ref).max()
    assert np.abs(both.stress_ref - r1.stress_ref - r2.stress_ref).max() <= 1e-9 * sc
    pk = {p.region: p.max_principal_MPa for p in both.cases[0].peaks}
    assert pk["fillet:left_seat"] > 0
