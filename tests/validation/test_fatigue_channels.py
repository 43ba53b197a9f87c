"""Fatigue under several load channels (``shaftfe.fatigue.channels``).

* One channel reproduces the single-channel path (``kernels.node_damage`` / ``safety_factor``
  on cycles of λ counted once) — the same arithmetic up to the rounding of σ·λ, so 1e-12.
* Two channels: a node under a constant mean stress plus a fully reversed one, against Miner's
  rule by hand (Basquin curve, Goodman): the independent closed form of the counted cycles.
* The candidate bound: no node outside the candidates has a larger peak than the
  candidates' largest (the triangle inequality of the von Mises norm).
"""

import math

import numpy as np
import pytest

from shaftfe.fatigue import channels, counting, kernels
from shaftfe.fatigue.history import from_rpm
from shaftfe.fatigue.sn import FatigueMaterial, SNCurve, load_material

STEEL = load_material("structural_steel")
BASQUIN = FatigueMaterial("basquin", 490.0, 740.0,
                          SNCurve((1e3, 1e6), (296.0 * 1000 ** 0.2, 296.0), "cutoff"))


def _fields(rng, n=40):
    s = rng.normal(0.0, 150.0, size=(6, n))
    s[:, 0] = [400.0, 0, 0, 30.0, 0, 0]           # a tension-dominated node
    return s


@pytest.mark.parametrize("kind", ["von_mises", "signed_von_mises"])
def test_one_channel_equals_the_single_channel_result(kind):
    rng = np.random.default_rng(1)
    s = _fields(rng)
    lam = rng.uniform(0.05, 1.2, 3000) ** 2            # a load factor ≥ 0 (rpm²-like)
    cyc = counting.count_cycles(lam)
    s_eq = kernels.equivalent_stress(s.T, kind)
    d_ref = kernels.node_damage(s_eq, cyc, STEEL, "goodman")
    n_ref, _ = kernels.safety_factor(s_eq, cyc, STEEL, 1e6, "goodman")
    got = channels.assess_nodes(s[None], lam[None], np.arange(s.shape[1]), STEEL,
                                design_life_blocks=1e6, theory="goodman", kind=kind)
    # same cycles scaled by σ_eq; the products σ·λ round once: 1e-12 relative
    np.testing.assert_allclose(got.damage, d_ref, rtol=1e-12, atol=0)
    np.testing.assert_allclose(got.safety, n_ref, rtol=1e-9)     # bisection to rtol 1e-10


def test_two_channels_against_miner_by_hand():
    # node: σ_xx = 100 L1 + 300 L2, L1 ≡ 1 (constant), L2 = ±1 alternating 1000 times:
    # one cycle class per reversal pair: σ_a = 300, σ_m = 100, count 1000 (closure 'repeated')
    sk = np.zeros((2, 6, 1))
    sk[0, 0, 0], sk[1, 0, 0] = 100.0, 300.0
    L = np.vstack([np.ones(2000), np.tile([1.0, -1.0], 1000)])
    got = channels.assess_nodes(sk, L, [0], BASQUIN, design_life_blocks=1.0, theory="goodman")
    sar = 300.0 / (1.0 - 100.0 / 740.0)               # Goodman, R_m = 740 MPa
    # Basquin through (1e3, 296·1000^0.2) and (1e6, 296): N = 1e6 (296 / σ)^(1/0.2·…)
    k = math.log(1e6 / 1e3) / math.log(296.0 * 1000 ** 0.2 / 296.0)
    N = 1e6 * (296.0 / sar) ** k
    if sar < 296.0:
        pytest.fail("the hand case must lie on the finite-life branch")
    assert got.damage[0] == pytest.approx(1000.0 / N, rel=1e-12)
    assert got.peak_MPa[0] == 400.0


def test_candidates_hold_every_possible_hot_spot():
    rng = np.random.default_rng(3)
    sk = rng.normal(0.0, 100.0, size=(2, 6, 300))
    h = from_rpm(rng.uniform(1000, 9000, 500), sample_rate_hz=10.0, rpm_ref=7000.0)
    L = np.vstack([h.load_factor, np.sin(np.arange(500) / 7.0)])
    cand, more = channels.candidate_nodes(sk, L, np.zeros(300, bool), {})
    s_t = channels.equivalent_histories(sk, L, np.arange(300))
    peaks = np.abs(s_t).max(axis=1)
    # the hot spot by peak is a candidate; every non-candidate is below the fraction of the best
    assert int(np.argmax(peaks)) in set(cand.tolist())
    out = np.setdiff1d(np.arange(300), cand)
    if more == 0:
        assert peaks[out].max(initial=0) < channels.CANDIDATE_FRACTION * peaks[cand].max()


def test_one_pattern_fe_field_equals_the_single_channel_path(tmp_path):
    """x2_57 (every load rpm²; coarse; spin softening off, so the response is proportional):
    the several-pattern path on its one pattern gives, at each candidate node, the damage and
    safety factor of the single-channel path (cycles of λ counted once, scaled by σ_eq) — the
    same arithmetic up to the rounding of σ·λ: 1e-12 on damage, 1e-9 on the bisected factor."""
    from shaftfe.fatigue import channel_run
    from shaftfe.fatigue.history import read_history
    from shaftfe.fatigue.run import FatigueJob, resolve_design_life, static_reference
    from shaftfe.model.loader import load_variant
    from shaftfe.util.paths import DEFAULT_SPECTRUM

    v = load_variant("x2_57")
    h = read_history(DEFAULT_SPECTRUM)
    job = resolve_design_life(FatigueJob(spectrum="rpm.dat", level="coarse", model="solid",
                                         spin_softening=False, equivalent="signed_von_mises",
                                         design_life=1e4), h, v.duty)
    ref = static_reference(v, job)           # the 3D model's: its per-pattern fields
    assert [p["scales_with"] for p in ref.patterns] == ["rpm2"] and ref.stress_linear is None
    run = channel_run.run_channels(job, v, h, STEEL, ref)
    hr = h.with_reference(ref.ref_rpm)
    cyc = counting.count_cycles(hr.load_factor)
    s_eq = kernels.equivalent_stress(np.asarray(ref.stress_ref).T[run.lives.nodes],
                                     "signed_von_mises")
    d = kernels.node_damage(s_eq, cyc, STEEL, "soderberg")
    n, _ = kernels.safety_factor(s_eq, cyc, STEEL, 1e4, "soderberg")
    np.testing.assert_allclose(run.lives.damage, d, rtol=1e-12, atol=0)
    np.testing.assert_allclose(run.lives.safety, n, rtol=1e-9)
