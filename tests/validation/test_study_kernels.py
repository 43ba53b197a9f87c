"""The numerical pieces of ``shaftfe study`` against independent references.

* Plate-shape mass properties (shaftfe.model.shapes) against a midpoint-rule quadrature of the
  same plate in polar coordinates (an independent evaluation of ∫ρ dV, ∫ρ y dV, ∫ρ r² dV), and
  against the seed's counterweight figures in geometry/x2_57.toml (seed 000 §8.2.2: 0.125 kg at
  22.59 mm, 0.24 kg at 20.23 mm; inertias stated to 6 digits in the file).
* Latin hypercube (McKay, Beckman & Conover, Technometrics 21 (1979) 239): every stratum of
  every coordinate holds exactly one point.
* Non-dominated set: the definition applied by brute force on random points.
* Spearman's ρ against scipy.stats.spearmanr (a peer implementation).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from shaftfe.model.shapes import shape_mass_properties

RHO = 7.85e-9           # t/mm³ (the files' steel)
CW1 = dict(kind="annular_sector", thickness_mm=20.0, inner_radius_mm=12.0,
           outer_radius_mm=34.3565, half_angle_deg=44.0169)
CW2 = dict(kind="hub_ring_plus_annular_sector", thickness_mm=25.0, hub_outer_radius_mm=12.0,
           inner_radius_mm=29.542, outer_radius_mm=39.902, half_angle_deg=79.4409)


def quadrature(shape: dict, seat_r: float, n: int = 1500) -> dict:
    """Midpoint rule in (r, θ) over the plate (kg, mm): error O(h²) ≈ 1e-7 relative here."""
    rho = RHO * 1e3
    t = shape["thickness_mm"]
    pieces = [(shape["inner_radius_mm"], shape["outer_radius_mm"],
               math.radians(shape["half_angle_deg"]))]
    if shape["kind"] == "hub_ring_plus_annular_sector":
        pieces.append((seat_r, shape["hub_outer_radius_mm"], math.pi))
    m = me = J = 0.0
    for r0, r1, a in pieces:
        r = r0 + (np.arange(n) + 0.5) * (r1 - r0) / n
        th = -a + (np.arange(n) + 0.5) * 2 * a / n
        dA = np.outer(r, np.ones(n)) * (r1 - r0) / n * 2 * a / n
        y = np.outer(r, np.cos(th))
        m += rho * t * dA.sum()
        me += rho * t * (y * dA).sum()
        J += rho * t * (np.outer(r ** 2, np.ones(n)) * dA).sum()
    e = me / m
    polar = J - m * e * e
    return {"mass_kg": m, "eccentricity_mm": e, "polar_inertia_kg_mm2": polar,
            "diametral_inertia_kg_mm2": polar / 2 + m * t * t / 12}


@pytest.mark.parametrize("shape", [CW1, CW2], ids=["sector", "hub+sector"])
def test_shape_against_quadrature(shape):
    got = shape_mass_properties(shape, RHO, 8.5)
    ref = quadrature(shape, 8.5)
    for k, v in ref.items():
        # midpoint rule, 1500² cells: relative error ≤ (h/L)² / 24 ≈ 2e-8 per integral; the
        # polar inertia is a difference J − m e² that amplifies it ~3×: 1e-6 bounds both
        assert got[k] == pytest.approx(v, rel=1e-6), k


@pytest.mark.parametrize("shape,ref", [
    (CW1, {"mass_kg": 0.125, "eccentricity_mm": 22.59, "polar_inertia_kg_mm2": 18.9844,
           "diametral_inertia_kg_mm2": 13.6589}),
    (CW2, {"mass_kg": 0.24, "eccentricity_mm": 20.23, "polar_inertia_kg_mm2": 147.83,
           "diametral_inertia_kg_mm2": 86.4152})], ids=["cw1", "cw2"])
def test_shape_reproduces_the_files_counterweights(shape, ref):
    got = shape_mass_properties(shape, RHO, 8.5)
    for k, v in ref.items():
        # the file states the shape's radii and angle to 6 significant digits (fitted to the
        # seed's m and e): their rounding moves m e by ≤ 2e-5 relative; 5e-5 bounds it
        assert got[k] == pytest.approx(v, rel=5e-5), k


def test_lhs_one_point_per_stratum():
    from shaftfe.study.sampling import lhs_unit
    for n, d, seed in ((1, 1, 0), (7, 3, 1), (100, 5, 42)):
        u = lhs_unit(n, d, seed)
        assert u.shape == (n, d) and (u >= 0).all() and (u < 1).all()
        for j in range(d):
            assert sorted(np.floor(u[:, j] * n).astype(int)) == list(range(n))  # exact
    assert np.array_equal(lhs_unit(10, 2, 3), lhs_unit(10, 2, 3))        # seeded
    assert not np.array_equal(lhs_unit(10, 2, 3), lhs_unit(10, 2, 4))


def test_non_dominated_brute_force():
    import pandas as pd

    from shaftfe.study.results import non_dominated
    rng = np.random.default_rng(5)
    pts = rng.integers(0, 6, size=(60, 3)).astype(float)     # ties on purpose
    df = pd.DataFrame({"status": ["ok"] * 60, "a": pts[:, 0], "b": pts[:, 1],
                       "c": pts[:, 2]})
    df.loc[3, "status"] = "failed"
    got = non_dominated(df, [("a", "min"), ("b", "max"), ("c", "min")])
    s = pts * np.array([1, -1, 1])
    for i in range(60):
        dominated = any(j != i and j != 3 and (s[j] <= s[i]).all() and (s[j] < s[i]).any()
                        for j in range(60))
        assert got[i] == (i != 3 and not dominated)


def test_spearman_against_scipy():
    import pandas as pd
    from scipy.stats import spearmanr

    from shaftfe.study.results import sensitivities
    rng = np.random.default_rng(9)
    x = rng.random(40)
    y = np.exp(3 * x) + 0.3 * rng.random(40)
    x[5] = x[6]                                               # a tie
    df = pd.DataFrame({"status": ["ok"] * 40, "p": x, "o": y})
    got = sensitivities(df, ["p"], ["o"])["o"]["p"]
    assert got == pytest.approx(spearmanr(x, y).statistic, abs=1e-12)   # round-off only
