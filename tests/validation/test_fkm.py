"""FKM guideline factors against hand calculations and published worked examples.

Sources: FKM-Richtlinie, 6th ed. (2012), ch. 4; the guideline's worked example 6.2 (GJL-250)
and the "IMA FKM training" steel example as published in pyLife's test data
(boschresearch/pylife, tests/strength/fkm_linear/data/FKM/); the K_d,m constants as printed by
the PragTic help ("Size effect", FKM 2003 table). Tolerances: the examples print 3 significant
figures, so a value rounded to the printed digits is compared with half a unit of its last digit.
"""

import math
from fractions import Fraction

import numpy as np
import pytest

from shaftfe.fatigue import fkm

STEEL = fkm.GROUPS["case_hardening_steel"]
GJL = fkm.GROUPS["gjl"]


def test_factors_against_hand_calculation():
    # R_m 1000, R_z 4, G 3.8: each factor by its formula with the numbers written out
    rm = 1000.0
    assert fkm.roughness_factor(4.0, rm, STEEL) == pytest.approx(
        1 - 0.22 * math.log10(4.0) * math.log10(2000 / 400), rel=1e-15)
    assert fkm.support_factor(3.8, rm, STEEL) == pytest.approx(
        1 + 3.8 ** 0.25 * 10 ** -(0.5 + 1000 / 2700), rel=1e-15)
    assert fkm.support_factor(0.5, rm, STEEL) == pytest.approx(
        1 + math.sqrt(0.5) * 10 ** -(0.5 + 1000 / 2700), rel=1e-15)
    assert fkm.support_factor(0.05, rm, STEEL) == pytest.approx(
        1 + 0.05 * 10 ** -(0.5 - 0.5 + 1000 / 2700), rel=1e-15)
    assert fkm.mean_stress_sensitivity(rm, STEEL) == pytest.approx(0.35 - 0.1, rel=1e-15)
    # size factor: 22 mm, hardened steel, d_N 11 mm, a_d 0.5 (PragTic lists the term at the
    # reference, 1 − 0.7686·0.5·lg(11/7.5), as 0.9360: its table truncates to 4 decimals)
    assert 0.9360 <= 1 - 0.7686 * 0.5 * math.log10(11 / 7.5) < 0.9361
    assert fkm.size_factor(22.0, STEEL) == pytest.approx(
        (1 - 0.3843 * math.log10(22 / 7.5)) / (1 - 0.3843 * math.log10(11 / 7.5)), rel=1e-15)
    assert fkm.size_factor(10.0, STEEL) == 1.0


def test_haigh_ranges_and_continuity():
    """K_AK (F2): the four ranges with M = 0.5 at hand-chosen ratios; continuous at R = 0
    (σm/σa = 1) and R = 0.5 (σm/σa = 3) to round-off."""
    M = 0.5
    k = fkm.mean_stress_factor([1.0, 1.0, 1.0, 1.0, 1.0], [-3.0, 0.5, 2.0, 4.0, -1.5], M)
    assert k[0] == pytest.approx(1 / (1 + M * -3.0 / 1.0) if False else 1 / (1 - M))
    assert k[1] == pytest.approx(1 / (1 + 0.5 * M))
    assert k[2] == pytest.approx((1 + M / 3) / (1 + M) / (1 + M / 3 * 2.0))
    assert k[3] == pytest.approx((3 + M) / (3 * (1 + M) ** 2))
    assert k[4] == pytest.approx(1 / (1 - M))            # σmax = −0.5 < 0: range I
    eps = 1e-9
    lo, hi = fkm.mean_stress_factor([1, 1], [1 - eps, 1 + eps], M)
    assert lo == pytest.approx(hi, abs=1e-8)
    lo, hi = fkm.mean_stress_factor([1, 1], [3 - eps, 3 + eps], M)
    assert lo == pytest.approx(hi, abs=1e-8)


def test_fkm_guideline_example_6_2_gjl():
    """FKM guideline example 6.2 (GJL-250, local stresses): R_m 210, R_z 200, G 0.5,
    σa 47, σm 13, K_NL,E 1.05 → σ_W 71, K_R 0.914, n 1.682, K_WK 0.619, K_AK 0.879, σ_AK 101."""
    rm = 210.0
    s_w = GJL.f_w_sigma * rm
    kr = fkm.roughness_factor(200.0, rm, GJL)
    n = fkm.support_factor(0.5, rm, GJL)
    kwk = fkm.design_factor(n, kr, GJL, k_nle=1.05)
    kak = float(fkm.mean_stress_factor(47.0, 13.0, fkm.mean_stress_sensitivity(rm, GJL)))
    assert round(s_w) == 71
    assert kr == pytest.approx(0.914, abs=5e-4)
    assert n == pytest.approx(1.682, abs=5e-4)
    assert kwk == pytest.approx(0.619, abs=5e-4)
    assert kak == pytest.approx(0.879, abs=5e-4)
    assert round(kak * s_w / kwk) == 101


def test_ima_training_example_steel():
    """'IMA FKM training' (steel, pyLife test data): R_m 473, R_z 25, G 0.172, σa 94.7,
    σm 5.2, K_f~ 2 → σ_W,zd 213, K_R 0.885, n 1.088, K_WK 0.979, K_AK 0.996, σ_AK 216."""
    g = fkm.GROUPS["structural_steel"]
    rm = 473.0
    s_w = 0.45 * rm
    kr = fkm.roughness_factor(25.0, rm, g)
    n = fkm.support_factor(0.172, rm, g)
    kwk = fkm.design_factor(n, kr, g)
    kak = float(fkm.mean_stress_factor(94.7, 5.2, fkm.mean_stress_sensitivity(rm, g)))
    assert round(s_w) == 213
    assert kr == pytest.approx(0.885, abs=5e-4)
    assert n == pytest.approx(1.088, abs=5e-4)
    assert kwk == pytest.approx(0.979, abs=5e-4)
    assert kak == pytest.approx(0.996, abs=5e-4)
    assert int(kak * s_w / kwk) == 216   # printed truncated: 217.4 σ_WK × 0.9964 = 216.6


def test_miner_rules_against_hand_sums():
    """Two classes, s = 1.5 (n 10) and 0.5 (n 1000), k 5, N_D 1e6, D_M 0.3, written out."""
    s, c = np.array([1.5, 0.5]), np.array([10.0, 1000.0])
    d_el = (10 * 1.5 ** 5 + 1000 * 0.5 ** 5) / 1e6
    d_mod = (10 * 1.5 ** 5 + 1000 * 0.5 ** 9) / 1e6
    assert fkm.blocks_to_failure(s, c, "elementary", 0.3) == pytest.approx(0.3 / d_el, rel=1e-14)
    assert fkm.blocks_to_failure(s, c, "modified", 0.3) == pytest.approx(0.3 / d_mod, rel=1e-14)
    # consistent: the limit falls as (1 − D/D_M)^(1/5); the 0.5 class starts at
    # D/D_M = 1 − 0.5^5 = 0.96875: blocks = D_M [0.96875 / r1 + 0.03125 / (r1 + r2)]
    r1, r2 = 10 * 1.5 ** 5 / 1e6, 1000 * 0.5 ** 5 / 1e6
    want = 0.3 * (0.96875 / r1 + 0.03125 / (r1 + r2))
    assert fkm.blocks_to_failure(s, c, "consistent", 0.3) == pytest.approx(want, rel=1e-14)
    # ordering: elementary ≤ consistent, modified ≤ original (no damage below the knee)
    assert fkm.blocks_to_failure(s, c, "elementary", 0.3) < want
    assert fkm.blocks_to_failure(np.array([0.9]), np.array([1e6]), "consistent", 0.3) == math.inf


def test_scale_for_life_inverts_the_life():
    """λ* with life(λ* s) = L: elementary in closed form; the others by bisection to 1e-13,
    checked by recomputing the life (relative 1e-9: the life is a power ≤ 9 of λ). L = 300
    blocks keeps the consistent rule's root where the largest class is above the knee (its
    life is infinite below that)."""
    s, c = np.array([1.2, 0.6, 0.3]), np.array([5.0, 200.0, 4000.0])
    for rule in fkm.MINER:
        lam = fkm.scale_for_life(s, c, rule, 0.3, 300.0)
        assert lam * 1.2 > 1.0
        assert fkm.blocks_to_failure(lam * s, c, rule, 0.3) == pytest.approx(300.0, rel=1e-9)




@pytest.mark.parametrize("seed", range(4))
def test_scale_for_life_brackets_the_exact_life(seed):
    """λ* of the modified and consistent rules (found between two knees λ_i = 1/(f s_i), then
    bisected) against the lives in exact rational arithmetic (``_exact_lives``, class by
    class): the exact life at λ* (1 − 1e-9) is at least L and at λ* (1 + 1e-9) at most L, a
    step far outside the bisection's 1e-13 and exact to evaluate. Spectra of s = p/64 with
    ties (p drawn with repeats), one of a single class, scaled by f (``Spectrum.scaled``, the
    core's check); targets: the exact lives at three knees (λ* on a knee) and between them,
    below the first knee (the consistent rule's jump) and beyond the last."""
    rng = np.random.default_rng(seed)
    n = 1 if seed == 0 else 25
    p = rng.integers(3, 141, size=n)
    counts = rng.integers(1, 500, size=n)
    f = (Fraction(1), Fraction(1, 3), Fraction(5, 2), Fraction(7, 8))[seed]
    s_exact = [Fraction(int(v), 64) * f for v in p]
    c_exact = [int(v) for v in counts]
    spec = fkm.Spectrum(p / 64.0, counts.astype(float)).scaled(float(f))
    knees = sorted({1 / v for v in s_exact})
    for rule in ("modified", "consistent"):
        targets = {1e-3, 1e9}
        for lam in (knees[0], knees[len(knees) // 2], knees[-1]):
            life = _exact_lives(s_exact, c_exact, lam)[rule]
            if life != math.inf:
                targets |= {float(life), float(life) * 0.7, float(life) * 1.3}
        for L in sorted(targets):
            lam = spec.scale_for_life(rule, 0.3, L)
            lo = _exact_lives(s_exact, c_exact, Fraction(lam) * (1 - Fraction(1, 10 ** 9)))
            hi = _exact_lives(s_exact, c_exact, Fraction(lam) * (1 + Fraction(1, 10 ** 9)))
            assert lo[rule] >= L >= hi[rule], (rule, L, lam)


def _exact_lives(s, c, lam, k=5, n_d=10 ** 6, d_m=Fraction(3, 10)):
    """The three Miner rules in exact rational arithmetic, class by class (FKM ch. 4.4 written
    out): elementary Σ n (λs)^k / N_D, modified (λs)^(2k−1) below the knee, consistent the
    interval sum Σ ΔD / rate with class j switching on at D/D_M = 1 − (λ s_j)^k."""
    x = [lam * v for v in s]
    el = sum(n * v ** k for v, n in zip(x, c, strict=True)) / n_d
    mod = sum(n * (v ** k if v >= 1 else v ** (2 * k - 1)) for v, n in zip(x, c, strict=True))
    out = {"elementary": d_m / el, "modified": d_m / (mod / n_d)}
    if not any(v >= 1 for v in x):
        out["consistent"] = math.inf
        return out
    start = sorted((max(Fraction(0), 1 - v ** k), n * v ** k / n_d)
                   for v, n in zip(x, c, strict=True))
    edges = [st for st, _ in start] + [Fraction(1)]
    blocks, rate = Fraction(0), Fraction(0)
    for j, (_, w) in enumerate(start):
        rate += w
        blocks += (edges[j + 1] - edges[j]) * d_m / rate
    out["consistent"] = blocks
    return out


def test_sorted_spectrum_against_exact_class_sums():
    """``fkm.Spectrum`` (sorted once, prefix sums, a binary search per life) against the
    class-by-class sums in exact rational arithmetic (``_exact_lives``), 40 classes s = p/64
    (p distinct in 3..140: below and above the knee), at λ = 1/2, 1, 3/2 (the bisection of
    the safety factor evaluates such scaled lives). Tolerance 1e-12 relative: the float sums
    have n = 40 positive terms (≤ n eps each way), and a consistent-rule term s_j^k − s_{j+1}^k
    loses at most s/(k Δs) ≤ 140/5 = 28 ulps to cancellation (neighbours ≥ 1/64 apart):
    ≤ 40 · 30 · 1.1e-16 ≈ 1.3e-13."""
    rng = np.random.default_rng(30)
    p = rng.choice(np.arange(3, 141), size=40, replace=False)
    counts = rng.integers(1, 500, size=40)
    s_exact = [Fraction(int(v), 64) for v in p]
    c_exact = [int(n) for n in counts]
    spec = fkm.Spectrum(p / 64.0, counts.astype(float))
    for lam in (Fraction(1, 2), Fraction(1), Fraction(3, 2)):
        want = _exact_lives(s_exact, c_exact, lam)
        for rule in fkm.MINER:
            got = spec.life(rule, 0.3, float(lam))
            if want[rule] == math.inf:
                assert got == math.inf
            else:
                assert got == pytest.approx(float(want[rule]), rel=1e-12), (rule, lam)
        # the per-class damages (the damage matrix) sum to the spectrum's damage
        for rule in ("elementary", "modified"):
            d = fkm.class_damage(float(lam) * p / 64.0, counts, rule).sum()
            assert d == pytest.approx(0.3 / float(want[rule]), rel=1e-12)
    # the core's spectrum: the surface's scaled, no new sort, the same lives
    half = spec.scaled(0.5)
    for rule in fkm.MINER:
        assert half.life(rule, 0.3, 3.0) == spec.life(rule, 0.3, 1.5)
    assert fkm.Spectrum(p / 64.0, counts).scaled(0.0).life("modified", 0.3) == math.inf
    # a hint (another node's order) that kept fewer classes than this spectrum has: every class
    # is still counted (the same lives as without the hint, exactly: the same sort)
    short = fkm.Spectrum(np.where(np.arange(40) < 20, 0.0, p / 64.0), counts).order
    hinted = fkm.Spectrum(p / 64.0, counts, hint=short)
    for rule in fkm.MINER:
        assert hinted.life(rule, 0.3) == spec.life(rule, 0.3), rule
