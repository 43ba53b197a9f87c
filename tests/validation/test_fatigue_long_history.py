"""Long histories (a 100 Hz data-logger trace of hours): the fast counting and evaluation paths
give the same numbers as the straightforward ones.

References: the ``rainflow`` package (PyPI, ASTM E1049-85 §5.4.4) as the independent peer of our
reversal filter and three-point detector; ``numpy.unique(axis=0)`` for the merge of equal
classes; the full nodes × classes damage sum for the pruned field evaluation.
"""

from __future__ import annotations

import numpy as np
import pytest
import rainflow

from shaftfe.fatigue import kernels
from shaftfe.fatigue.counting import count_cycles, extract, merge, reversals
from shaftfe.fatigue.sn import load_material


def _series(rng, n):
    """Random series with plateaus (rounded values) and with random lengths, the edge cases of
    the reversal filter (0, 1, 2 samples, constant runs)."""
    return np.round(rng.random(n) * rng.integers(1, 8), 1)


def test_reversals_are_those_of_the_rainflow_package():
    rng = np.random.default_rng(11)
    for _ in range(2000):
        y = _series(rng, int(rng.integers(0, 60)))
        ours = reversals(y)
        peer = np.array([x for _, x in rainflow.reversals(y.tolist())])
        np.testing.assert_array_equal(ours, peer)    # exact: values are copied, not computed


@pytest.mark.parametrize("closure", ["half", "repeated"])
def test_cycles_are_those_of_the_rainflow_package(closure):
    rng = np.random.default_rng(12)
    for _ in range(500):
        y = _series(rng, int(rng.integers(0, 120)))
        ours = extract(y, closure)
        if y.size < 2 or y.max() == y.min():
            assert ours.shape == (0, 3)
            continue
        if closure == "repeated":          # the closure's rotation, as extract documents it
            i = int(np.argmax(y))
            y = np.concatenate((y[i:], y[:i], y[i:i + 1]))
        peer = np.array([(r, m, c) for r, m, c, _, _ in rainflow.extract_cycles(y.tolist())
                         if r > 0]).reshape(-1, 3)
        # exact: range |a - b| and mean (a + b)/2 of the same two stored values, same order
        np.testing.assert_array_equal(ours, peer)


def test_merge_equals_numpy_unique_rows():
    rng = np.random.default_rng(13)
    raw = np.column_stack((np.round(rng.random(5000), 2), np.round(rng.random(5000), 2),
                           rng.choice([0.5, 1.0], 5000)))
    cyc = merge(raw, "half")
    keys, inv = np.unique(raw[:, :2], axis=0, return_inverse=True)
    counts = np.bincount(inv.ravel(), weights=raw[:, 2])
    np.testing.assert_array_equal(cyc.range, keys[:, 0])      # exact: the same sort
    np.testing.assert_array_equal(cyc.mean, keys[:, 1])
    np.testing.assert_array_equal(cyc.count, counts)          # exact: sums of 0.5 and 1


@pytest.mark.parametrize("theory", ["soderberg", "goodman", "gerber", "none"])
def test_pruned_field_damage_equals_the_full_sum(theory):
    """node_damage drops, per chunk of nodes in decreasing |σ_eq|, the classes below the
    endurance limit; the full sum over every class at every node is the reference."""
    rng = np.random.default_rng(14)
    lf = ((3000 + 4000 * rng.random(20_000)) / 7000) ** 2
    cyc = count_cycles(lf)
    sigma = np.concatenate((rng.random(1500) * 600, -rng.random(500) * 300, [0.0]))
    mat = load_material("structural_steel")
    kf = 0.8
    full = kernels._damage(sigma, cyc, mat, theory, kf)
    fast = kernels.node_damage(sigma, cyc, mat, theory, kf)
    np.testing.assert_array_equal(fast == 0, full == 0)        # same nodes without damage
    np.testing.assert_array_equal(np.isinf(fast), np.isinf(full))
    ok = np.isfinite(full) & (full > 0)
    # the same terms summed, minus exact zeros: only the summation order differs, so the
    # difference is round-off of a sum of C positive terms, <= C * eps relative (C = classes)
    assert np.max(np.abs(fast[ok] - full[ok]) / full[ok]) <= cyc.n * np.finfo(float).eps


def test_safety_factor_with_pruning_equals_the_bisection_on_all_nodes():
    """The scalar root with classes pruned at the upper bracket against the per-node bisection
    on every class (kernels.safety_factor method="bisection")."""
    rng = np.random.default_rng(15)
    lf = ((3000 + 4000 * rng.random(5000)) / 7000) ** 2
    cyc = count_cycles(lf)
    sigma = rng.random(40) * 400 + 50
    mat = load_material("structural_steel")
    n_sim, st_sim = kernels.safety_factor(sigma, cyc, mat, 1e7, method="similarity")
    n_bis, st_bis = kernels.safety_factor(sigma, cyc, mat, 1e7, method="bisection", rtol=1e-12)
    np.testing.assert_array_equal(st_sim, st_bis)
    # the bisection stops at rtol = 1e-12 in log n; the similarity root is exact to round-off
    np.testing.assert_allclose(n_sim, n_bis, rtol=2e-12)


def test_binned_field_keeps_the_candidates_exact_and_the_rest_close():
    """A history whose every cycle is large (white noise over the whole speed range) with the
    work budget set low, so that the field goes to binned classes: the candidate nodes (the
    hot spots) equal the full sum; the others are within the binning bound.

    Bound: a cell's cycles are replaced by their count-weighted centroid, so the first-order
    error cancels and what is left is ½ f''·var per class, relative (k² δ²)/24 for a damage
    ∝ σ_ar^k over a cell of relative width δ; k = 18 bounds the effective exponent of this
    S-N table with Soderberg (measured −17.8, issue 18), δ = 1/√(binned classes) per axis.
    Binned classes are those well above the endurance limit in the node's stress band, where
    the damage is such a smooth power; the classes crossing the limit are summed exactly, so
    the bound holds at every node, also those near the limit."""
    rng = np.random.default_rng(16)
    lf = ((1500 + 8000 * rng.random(20_000)) / 10_000) ** 2
    cyc = count_cycles(lf)
    mat = load_material("structural_steel")
    sigma = np.sort(rng.random(1000) * 400)
    cand = [999, 500]
    full = kernels._damage(sigma, cyc, mat, "soderberg", 1.0)
    info: dict = {}
    budget = 600.0 * sigma.size                 # 300 exact + ≤ 300 binned classes a node
    fast = kernels.node_damage(sigma, cyc, mat, "soderberg", 1.0, exact_at=cand,
                               budget=budget, info=info)
    assert info["binned_nodes"] == sigma.size - len(cand) and info["binned_classes"] <= 300
    # candidates: the same sum minus exact zeros, round-off only (<= C eps, C = classes)
    np.testing.assert_allclose(fast[cand], full[cand], rtol=cyc.n * np.finfo(float).eps)
    big = np.isfinite(full) & (full > 0)
    np.testing.assert_array_equal(fast == 0, full == 0)
    delta = 1.0 / np.sqrt(info["binned_classes"])
    bound = 18.0 ** 2 * delta ** 2 / 24.0
    rel = np.abs(fast[big] - full[big]) / full[big]
    assert rel.max() <= bound, (rel.max(), bound)
