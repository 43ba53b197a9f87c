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


FAST_OR_REFUSE = {
    # valid files: the C-speed reader must give the line reader's history, bit for bit
    "norm.dat": "# reference_rpm = 7000\n# sample_rate_hz = 2\n0.5\n0.25\n1.0\n",
    "crlf.dat": "# reference_rpm = 7000\r\n0.5\r\n0.6\r\n",
    "rpm.dat": "# format = rpm\n# sample_rate_hz = 100\n3000\n3100\n2900.5\n",
    "auto_rpm.txt": "# sample_rate_hz = 10\n3000\n4000\n",
    "log.csv": "# a logger\ntime_s,rpm\n0,1000\n0.5,2000\n1.5,1500\n",
    "blank_lines.dat": "# reference_rpm = 7000\n\n0.5\n\n0.6\n",
    # files the line reader refuses: the fast one must not read them into something else
    "csv_header_no_table.dat": "# format = csv\n1000\n2000\n",
    "two_numbers_a_line.dat": "# reference_rpm = 7000\n0.5 0.7 0.9\n",
    "form_feed_in_header.dat": "# note\f# sample_rate_hz = 10\n0.5\n0.6\n",
    "underscore_in_header.dat": "# reference_rpm = 7000\n# sample_rate_hz = 1_0\n0.5\n",
    "comment_between_data.dat": "# reference_rpm = 7000\n0.5\n# pause\n0.6\n",
    "unicode_digit.dat": "# reference_rpm = 7000\n0.5\n\u0663\n",
}


@pytest.mark.parametrize("name", sorted(FAST_OR_REFUSE))
def test_fast_reader_agrees_with_the_line_reader_or_steps_aside(name):
    from shaftfe.errors import InputError
    from shaftfe.fatigue.history import _read_fast, _read_lines
    text = FAST_OR_REFUSE[name]
    fast = _read_fast(name, text, None, None, None)
    try:
        slow = _read_lines(name, text, None, None, None)
    except InputError:
        assert fast is None            # refused by the line reader: the fast one stepped aside
        return
    if name == "comment_between_data.dat":   # valid, but left to the line reader by design
        assert fast is None
        return
    assert fast is not None, "a plain valid file must take the fast path"
    for f in ("time_s", "rpm", "load_factor"):
        np.testing.assert_array_equal(getattr(fast, f), getattr(slow, f))   # same arithmetic
    assert (fast.format, fast.rpm_ref, fast.duration_s) == (slow.format, slow.rpm_ref,
                                                            slow.duration_s)


@pytest.mark.parametrize("budget", [kernels.FIELD_BUDGET, 2.0e5])
def test_finite_infinite_life_damage_is_kept_everywhere(budget):
    """The Ansys-style card (cutoff with "Infinite Life" = 1e9 cycles: a class below the curve
    still does 1e-9 per cycle) cannot be pruned: a node with σ_eq = 0 has damage Σn / 1e9, and
    the banded path must sum the classes on both sides of that step exactly (binning across
    the step gave 27 %). Reference: the full sum."""
    rng = np.random.default_rng(17)
    lf = ((1500 + 8000 * rng.random(5000)) / 10_000) ** 2
    cyc = count_cycles(lf)
    mat = load_material("structural_steel", infinite_life_cycles=1e9)
    sigma = np.concatenate(([0.0], np.sort(rng.random(300) * 400)))
    full = kernels._damage(sigma, cyc, mat, "soderberg", 1.0)
    fast = kernels.node_damage(sigma, cyc, mat, "soderberg", 1.0, exact_at=[300],
                               budget=budget)
    # exact sum at σ = 0 (the same terms, count / 1e9); elsewhere the binned bound of
    # test_binned_field_keeps_the_candidates_exact_and_the_rest_close with ≤ 300 binned
    # classes (18² δ² / 24 with δ = 1/√300), or round-off (C eps) when nothing is binned
    assert fast[0] == pytest.approx(full[0], rel=cyc.n * np.finfo(float).eps) and fast[0] > 0
    ok = np.isfinite(full)
    bound = 18.0 ** 2 / 300 / 24.0 if budget < 1e6 else cyc.n * np.finfo(float).eps
    assert np.max(np.abs(fast[ok] - full[ok]) / full[ok]) <= bound
