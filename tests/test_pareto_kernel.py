"""The non-dominated filter of benchmarks/_pareto.py on hand-made points (and its mode pairing).

Reference: Pareto dominance with every objective minimised — a dominates b when a is no worse
in every objective and strictly better in at least one (Deb 2001, Def. 2.5); the front is the
set of points no other point dominates."""

import math

import pytest

from benchmarks._pareto import dominates, fastest_within, pareto_mask, richardson


def test_dominance_definition():
    assert dominates((1, 1), (2, 2))
    assert dominates((1, 2), (2, 2))          # equal in one, better in the other
    assert not dominates((2, 2), (2, 2))      # identical: no strict improvement
    assert not dominates((1, 3), (2, 2))      # trade-off: neither dominates
    assert not dominates((2, 2), (1, 3))
    assert not dominates((3, 3), (1, 1))
    assert not dominates((math.nan, 0), (1, 1))
    with pytest.raises(ValueError):
        dominates((1, 2), (1, 2, 3))


def test_front_two_objectives():
    # (time s, error): a staircase, two dominated points, one duplicate of a front point
    pts = [(1.0, 0.50), (2.0, 0.10), (3.0, 0.20), (4.0, 0.01), (5.0, 0.01), (2.0, 0.10),
           (0.5, 0.90), (10.0, 0.001)]
    assert pareto_mask(pts) == [True, True, False, True, False, True, True, True]


def test_front_three_objectives_and_nan():
    # (time, memory, error): C is slower and less accurate than A but uses less memory
    pts = [(1, 10, 0.1), (2, 20, 0.2), (3, 5, 0.3), (1, 10, math.nan)]
    assert pareto_mask(pts) == [True, False, True, False]


def test_single_and_empty():
    assert pareto_mask([(3.0, 1.0)]) == [True]
    assert pareto_mask([]) == []


def test_richardson_exact_for_pure_power_error():
    # q(h) = q* + c h^p: two levels with ratio r recover q* exactly
    q_star, c, p, h = 100.0, 7.0, 2.0, 0.4
    q_c, q_f = q_star + c * h ** p, q_star + c * (h / 2) ** p
    # exact arithmetic (round-off only: (r^p q_f − q_c)/(r^p − 1), a few eps on O(100) values)
    assert richardson(q_f, q_c, 2.0, p) == pytest.approx(q_star, rel=1e-14)
    with pytest.raises(ValueError):
        richardson(1.0, 2.0, 1.0, 2.0)


def test_fastest_within():
    rows = [{"t": 5, "e": 0.005}, {"t": 2, "e": -0.008}, {"t": 1, "e": 0.2},
            {"t": 0.5, "e": None}]
    assert fastest_within(rows, "e", "t", 0.01) == {"t": 2, "e": -0.008}
    assert fastest_within(rows, "e", "t", 1e-4) is None


def test_pair_modes_by_class_and_order():
    from benchmarks._pareto import pair_modes

    def m(f, fam, wh):
        return {"f0": f, "family": fam, "whirl": wh}
    # model order: B1, T1, F1, B2; reference order: B1, F1, B2, A1 (torsion missing, axial extra)
    mod = [m(100, "lateral", "backward"), m(150, "torsional", "torsional"),
           m(160, "lateral", "forward"), m(300, "lateral", "backward")]
    ref = [m(110, "lateral", "backward"), m(170, "lateral", "forward"),
           m(320, "lateral", "backward"), m(400, "axial", "axial")]
    pairs = {(a["f0"], b["f0"]) for a, b in pair_modes(mod, ref)}
    assert pairs == {(100, 110), (300, 320), (160, 170)}
