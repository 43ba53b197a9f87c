"""Equivalent stress, mean-stress theories, S-N look-up, Miner damage, life and safety factor
(shaftfe.fatigue.kernels / assess), against hand computations written out in each docstring
and the seed's life chain (seed 000 §8.3: 25 000 blocks → 2083 h → 145 810 km).
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from shaftfe.errors import InputError
from shaftfe.fatigue.assess import assess, life_hours, life_km
from shaftfe.fatigue.counting import count_cycles
from shaftfe.fatigue.history import from_rpm, read_history
from shaftfe.fatigue.kernels import (
    CAPPED,
    FLOORED,
    SOLVED,
    damage_matrix,
    equivalent_stress,
    mean_stress_correction,
    node_damage,
    safety_factor,
)
from shaftfe.fatigue.sn import FatigueMaterial, SNCurve, load_material
from shaftfe.model.loader import load_variant

RPM_DAT = Path(__file__).resolve().parents[2] / "loadspectra" / "rpm.dat"
STEEL = load_material("structural_steel")
BASQUIN = FatigueMaterial("basquin", 490.0, 740.0,
                          SNCurve((1e3, 1e6), (296.0 * 1000 ** 0.2, 296.0), "cutoff"))


def _basquin(beyond="cutoff", inf_life=math.inf):
    return FatigueMaterial("basquin", 490.0, 740.0,
                           SNCurve((1e3, 1e6), (296.0 * 1000 ** 0.2, 296.0), beyond, inf_life))


# --- equivalent stress -----------------------------------------------------------------------

def test_von_mises_and_signed_variants_hand_cases():
    """Hand cases: uniaxial 200 → 200; pure shear τ = 100 → √3·100 = 173.205…; uniaxial
    compression −200 → vM 200, signed −200 (both signs negative). diag(−100, 50, 60): vM =
    sqrt(½((−150)² + 10² + 160²)) = sqrt(24 100) = 155.242…; largest-magnitude principal −100 →
    signed −155.24; hydrostatic (−100 + 50 + 60)/3 = +3.33 → +155.24."""
    s = np.array([[200, 0, 0, 0, 0, 0], [0, 0, 0, 100, 0, 0], [-200, 0, 0, 0, 0, 0],
                  [-100, 50, 60, 0, 0, 0]], dtype=float)
    vm = equivalent_stress(s)
    # exact arithmetic (round-off only; passes at 1e-13)
    assert vm == pytest.approx([200.0, 173.20508075688772, 200.0, 155.24174696260025],
                               rel=1e-14)
    sp = equivalent_stress(s, "signed_von_mises")
    sh = equivalent_stress(s, "signed_von_mises_hydrostatic")
    assert np.sign(sp).tolist() == [1, 1, -1, -1]
    assert np.sign(sh).tolist() == [1, 1, -1, 1]
    # exact arithmetic (round-off only; passes at 1e-13)
    assert np.abs(sp) == pytest.approx(vm, rel=1e-15)


def test_signed_von_mises_is_frame_invariant():
    """A rotated copy of diag(−100, 50, 60) (45° about z: σxx = σyy = −25, τxy = −75) keeps
    vM = 155.242 and the negative principal sign (hand rotation of the tensor)."""
    s = np.array([[-25.0, -25.0, 60.0, -75.0, 0.0, 0.0]])
    # exact arithmetic (round-off only; passes at 1e-13)
    assert equivalent_stress(s)[0] == pytest.approx(155.24174696260025, rel=1e-14)
    assert equivalent_stress(s, "signed_von_mises")[0] < 0


# --- mean stress -------------------------------------------------------------------------------

def test_mean_stress_theories_hand_values():
    """σ_a = 100, σ_m = 125 MPa, R_e = 250, R_m = 460 (Structural Steel). By hand:
    Soderberg 100/(1 − 125/250) = 200; Goodman 100/(1 − 125/460) = 46 000/335 = 137.313 43;
    Gerber 100/(1 − (125/460)²) = 100·211 600/195 975 = 107.972 96; none 100."""
    kw = {"yield_MPa": 250.0, "ultimate_MPa": 460.0}
    # exact arithmetic (round-off only; passes at 1e-13)
    assert mean_stress_correction(100.0, 125.0, "soderberg", **kw) == pytest.approx(200.0,
                                                                                     rel=1e-15)
    # exact arithmetic (round-off only; passes at 1e-13)
    assert mean_stress_correction(100.0, 125.0, "goodman", **kw) == pytest.approx(
        137.3134328358209, rel=1e-14)
    # exact arithmetic (round-off only; passes at 1e-13)
    assert mean_stress_correction(100.0, 125.0, "gerber", **kw) == pytest.approx(
        107.97295573414976, rel=1e-14)
    assert mean_stress_correction(100.0, 125.0, "none", **kw) == 100.0


def test_mean_stress_limits():
    """Compressive mean: no credit (σ_ar = σ_a, stated choice). Mean at/above the strength:
    σ_ar = ∞ (static failure), without a division warning."""
    kw = {"yield_MPa": 250.0, "ultimate_MPa": 460.0}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for th in ("soderberg", "goodman", "gerber"):
            assert mean_stress_correction(100.0, -300.0, th, **kw) == 100.0
        assert mean_stress_correction(100.0, 250.0, "soderberg", **kw) == math.inf
        assert mean_stress_correction(100.0, 500.0, "goodman", **kw) == math.inf
    with pytest.raises(InputError, match="mean-stress theory"):
        mean_stress_correction(1.0, 1.0, "morrow", **kw)


# --- S-N ---------------------------------------------------------------------------------------

def test_structural_steel_sn_lookup_hand_values():
    """Ansys Structural Steel table: at its points N is exact (138 MPa → 1e5); at 150 MPa, log-log
    between (2e4, 214) and (1e5, 138): log N = 4.30103 + (log 150 − log 214)/(log 138 − log 214)
    · 0.69897 = 4.867157 → N = 73 647.3 (hand). Below 86.2 MPa: infinite (cutoff); 'Infinite
    Life' 1e9 as in Ansys: N = 1e9. Above 3999 MPa: the first segment continued, 2·3999 MPa →
    10 · 2^(log(20/10)/log(2827/3999))… checked as the slope identity N(2S) = 10·2^(1/b),
    b = log(2827/3999)/log 2."""
    sn = STEEL.sn
    # exact arithmetic (round-off only; passes at 1e-13)
    assert sn.cycles_to_failure(138.0) == pytest.approx(1e5, rel=1e-12)
    assert sn.cycles_to_failure(86.2) == pytest.approx(1e6, rel=1e-12)
    # exact arithmetic: log-log interpolation, log round-off × ln 10 · log N ≈ 1e-14 (was 1e-9)
    assert sn.cycles_to_failure(150.0) == pytest.approx(73647.30835565711, rel=1e-12)
    assert sn.cycles_to_failure(86.0) == math.inf
    ans = load_material("structural_steel", infinite_life_cycles=1e9)
    # exact arithmetic (round-off only; passes at 1e-13)
    assert ans.sn.cycles_to_failure(50.0) == pytest.approx(1e9, rel=1e-12)
    b = math.log10(2827 / 3999) / math.log10(2.0)
    # exact arithmetic (round-off only; passes at 1e-13)
    assert sn.cycles_to_failure(2 * 3999.0) == pytest.approx(10 * 2 ** (1 / b), rel=1e-12)
    ext = load_material("structural_steel", beyond_last="extrapolate")
    assert ext.sn.cycles_to_failure(86.0) > 1e6


def test_basquin_card_14220():
    """16MnCr5 card (its strengths from the material record [materials.14220], R_m 1000 MPa):
    FKM σ_W = 0.40 · 1000 = 400 MPa at N_D = 1e6, k = 5: N(800) = 1e6/2⁵ = 31 250; the S-N
    line value at 1e7 (extrapolated) 400·10^(−1/5) = 252.383 MPa."""
    m = load_material("14220")
    # one record: the S-N card's strengths are the variant's (and FKM's / DIN 743's) material
    rec = load_variant("x2_57").material
    assert (m.yield_MPa, m.ultimate_MPa) == (rec.yield_MPa, rec.ultimate_MPa) == (695.0, 1000.0)
    # exact arithmetic (round-off only; passes at 1e-13)
    assert m.sn.cycles_to_failure(800.0) == pytest.approx(31250.0, rel=1e-12)
    assert m.sn.cycles_to_failure(390.0) == math.inf
    ext = load_material("14220", beyond_last="extrapolate")
    # exact arithmetic (round-off only; passes at 1e-13)
    assert ext.sn.amplitude_at(1e7) == pytest.approx(252.3829377920773, rel=1e-12)


# --- Miner, life, seed chain -----------------------------------------------------------------

def test_miner_soderberg_hand_case():
    """Load factor 0 ↔ 1 (two samples at 1 Hz, repeated block: one cycle of range 1, mean 0.5
    per 2 s block), σ_eq,ref = 490 MPa, 16MnCr5 card (R_e = 490): σ_a = σ_m = 245,
    Soderberg σ_ar = 245/(1 − 245/490) = 490; N = 1e6 (296/490)⁵ = 80 441.13 cycles
    → D = 1.243145e-5 per block, life 80 441 blocks = 80 441 · 2/3600 = 44.69 h."""
    h = from_rpm([0.0, 7000.0])
    r = assess(np.array([490.0]), h, BASQUIN, safety=False)
    # exact arithmetic (round-off only; passes at 1e-13)
    assert r.damage_per_block[0] == pytest.approx(1.24314516400273e-05, rel=1e-12)
    assert r.life_blocks[0] == pytest.approx(80441.12859516413, rel=1e-12)
    assert r.life_hours[0] == pytest.approx(80441.12859516413 * 2 / 3600, rel=1e-12)


def test_miner_sums_two_classes():
    """Two cycle classes (ranges 1 and 0.5 at σ_eq = 592, theory none, Basquin k = 5): amplitudes
    296 and 148; 296 → N = 1e6, 148 is below the cutoff → D = 1e-6 per block; with the line
    extrapolated, 148 → N = 1e6 · 2⁵ = 3.2e7 → D = 1e-6 + 1/3.2e7 = 1.03125e-6."""
    c = count_cycles([0.0, 1.0, 0.25, 0.75])
    assert sorted(c.range.tolist()) == [0.5, 1.0]
    # exact arithmetic (round-off only; passes at 1e-13)
    assert node_damage(np.array([592.0]), c, BASQUIN, "none")[0] == pytest.approx(1e-6,
                                                                                  rel=1e-12)
    d = node_damage(np.array([592.0]), c, _basquin("extrapolate"), "none")[0]
    # exact arithmetic (round-off only; passes at 1e-13)
    assert d == pytest.approx(1.03125e-6, rel=1e-12)


def test_seed_life_chain_blocks_hours_km():
    """Seed 000 §8.3: 25 000 blocks of 300 s = 25 000 · 300/3600 = 2083.33 h; at 70 km/h
    145 833.3 km. The seed printed 145 810 km = 2083 h (rounded first) × 70 — a rounding in the
    seed, not a different model; the block length comes from rpm.dat (300 samples at 1 Hz)."""
    h = read_history(RPM_DAT)
    assert h.duration_s == 300.0
    hours = life_hours(25_000, h.duration_s)
    # exact arithmetic (round-off only; passes at 1e-13)
    assert hours == pytest.approx(2083.3333333333335, rel=1e-15)
    assert life_km(hours) == pytest.approx(145833.33333333334, rel=1e-15)
    assert life_km(round(float(hours))) == 145810.0


def test_repeating_block_halves_life_in_blocks_keeps_hours():
    """rpm.dat played twice per block: damage per block doubles, life in blocks halves, life in
    hours and km unchanged (the same riding), to 1e-12."""
    h = read_history(RPM_DAT)
    s = np.linspace(80.0, 260.0, 200)
    r1 = assess(s, h, STEEL, safety=False)
    r2 = assess(s, h.repeated(2), STEEL, safety=False)
    fin = np.isfinite(r1.life_blocks)
    assert fin.sum() > 150
    # exact arithmetic (round-off only; passes at 1e-13)
    assert r2.life_blocks[fin] == pytest.approx(r1.life_blocks[fin] / 2, rel=1e-12)
    assert r2.life_hours[fin] == pytest.approx(r1.life_hours[fin], rel=1e-12)
    assert np.array_equal(np.isinf(r1.life_blocks), np.isinf(r2.life_blocks))


def test_rpm_scaling_scales_stress_by_s_squared():
    """All speeds × 1.1 → load factor × 1.21 → the same damage as σ_eq × 1.21 at the original
    speeds (proportionality, exact to 1e-12). With no mean correction and an extrapolated
    Basquin line (k = 5), D ∝ σ_a⁵ so life(1.1 rpm) = life / 1.1¹⁰ = life / 2.5937 (hand)."""
    h = read_history(RPM_DAT)
    s = np.linspace(100.0, 250.0, 50)
    a = assess(s, h.scaled(1.1), STEEL, safety=False)
    b = assess(1.21 * s, h, STEEL, safety=False)
    # exact arithmetic (round-off only; passes at 1e-13)
    assert a.damage_per_block == pytest.approx(b.damage_per_block, rel=1e-12)
    ext = _basquin("extrapolate")
    c = assess(s, h, ext, theory="none", safety=False)
    d = assess(s, h.scaled(1.1), ext, theory="none", safety=False)
    # exact arithmetic (round-off only; passes at 1e-13)
    assert d.life_blocks == pytest.approx(c.life_blocks / 1.1 ** 10, rel=1e-12)


def test_constant_speed_gives_infinite_life_without_division():
    """Constant 5000 rpm: no reversals, no cycles → D = 0, life ∞ in blocks/hours/km, safety
    factor capped at 15 and flagged, a note says why; no floating-point warning."""
    h = from_rpm([5000.0] * 300)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = assess(np.array([0.0, 100.0, 500.0]), h, STEEL)
    assert r.cycles.n == 0
    assert np.all(r.damage_per_block == 0) and np.all(np.isinf(r.life_km))
    assert np.all(r.safety_factor == 15.0) and np.all(r.safety_status == CAPPED)
    assert any("no load cycles" in n for n in r.notes)


# --- safety factor -----------------------------------------------------------------------------

@pytest.mark.parametrize("method", ["similarity", "bisection"])
def test_safety_factor_hand_cases(method):
    """One cycle per block of amplitude 100 MPa (σ_eq = 200, load factor 0 ↔ 1, theory none),
    Basquin 296 MPa at 1e6, k = 5. Design life 1e7 blocks:
    cutoff → damage is 0 until n·100 reaches 296, where L·D jumps to 10 → n = 2.96;
    extrapolated → n·100 = 296·(1e6/1e7)^(1/5) = 186.763 → n = 1.867634.
    Design life 1e5, cutoff: n·100 = 296·10^(1/5) = 372.64 → n = 3.726 (hand)."""
    c = count_cycles([0.0, 1.0])
    s = np.array([200.0])
    # exact arithmetic (round-off only; passes at 1e-13)
    kw = {"method": method, "rtol": 1e-12}
    n, st = safety_factor(s, c, BASQUIN, 1e7, "none", **kw)
    # root found to the solver's rtol 1e-12 (hand values exact): 1e-11 = 10× (was 1e-9; all
    # pass at 1e-13)
    assert n[0] == pytest.approx(2.96, rel=1e-11) and st[0] == SOLVED
    n, _ = safety_factor(s, c, _basquin("extrapolate"), 1e7, "none", **kw)
    assert n[0] == pytest.approx(1.867633739661372, rel=1e-11)       # as above
    n, _ = safety_factor(s, c, BASQUIN, 1e5, "none", **kw)
    assert n[0] == pytest.approx(2.96 * 10 ** 0.2, rel=1e-11)        # as above


def test_safety_factor_methods_agree_on_a_field():
    """Per-node vectorised bisection (rtol 1e-12) against the similarity solution (scalar root,
    n = x*/|σ_eq|) on rpm.dat with Soderberg and signed stresses from −300 to 300 MPa plus a zero
    node (capped), a 1e9 MPa node (floored: its mean exceeds the yield even at n = 15e-6) and a
    −1000 MPa node: same status everywhere, same n to 1e-9. A compressive (signed) node takes
    no mean-stress credit, so it is at least as safe as the tensile node of equal |σ|."""
    h = read_history(RPM_DAT)
    c = count_cycles(h.load_factor)
    s = np.concatenate((np.linspace(-300, 300, 601), [0.0, 1e9, -1e3]))
    for mat in (STEEL, _basquin("extrapolate")):
        n1, s1 = safety_factor(s, c, mat, 1e7, "soderberg")
        # exact arithmetic (round-off only; passes at 1e-13)
        n2, s2 = safety_factor(s, c, mat, 1e7, "soderberg", method="bisection", rtol=1e-12)
        assert np.array_equal(s1, s2)
        # two root solvers: the similarity root to its default rtol 1e-10, bisection to 1e-12
        # (measured 3.9e-13 apart): 1e-9 = 10× the looser one
        assert n1 == pytest.approx(n2, rel=1e-9)
        assert s1[-3] == CAPPED and s1[-2] == FLOORED and s1[-1] == SOLVED
        # at least as safe, up to the root's rtol (equal n where the mean credit is nil)
        assert np.all(n1[:300][::-1] >= n1[301:601] * (1 - 1e-12))


def test_safety_factor_makes_design_life_damage_one():
    """The definition itself: at the returned n, design_life · D(n · σ) = 1 (smooth,
    extrapolated S-N, so no jump), to 1e-8."""
    h = read_history(RPM_DAT)
    c = count_cycles(h.load_factor)
    mat = load_material("structural_steel", beyond_last="extrapolate")
    s = np.array([60.0, 120.0, 180.0, 240.0])
    n, st = safety_factor(s, c, mat, 1e7, "soderberg")
    assert np.all(st == SOLVED)
    # n to the solver's rtol 1e-10; D ∝ n^m with m ≤ 4.9 on this card (steepest segment,
    # 1e5-1e6): ≤ 5e-10, 1e-8 = 20×
    assert 1e7 * node_damage(n * s, c, mat, "soderberg") == pytest.approx(1.0, rel=1e-8)


def test_fatigue_strength_factor_kf():
    """kf multiplies the S-N strengths: with theory none, kf = 0.5 at σ equals kf = 1 at 2σ
    (amplitudes doubled; the mean is ignored), hand identity; kf outside (0, 1] is refused."""
    h = read_history(RPM_DAT)
    c = count_cycles(h.load_factor)
    s = np.linspace(50, 150, 11)
    # exact arithmetic (round-off only; passes at 1e-13)
    assert node_damage(s, c, STEEL, "none", kf=0.5) == pytest.approx(
        node_damage(2 * s, c, STEEL, "none"), rel=1e-14)
    with pytest.raises(InputError, match="kf"):
        node_damage(s, c, STEEL, kf=1.5)


def test_damage_matrix_sums_to_node_damage():
    """The hot-spot damage matrix holds the node's whole damage per block; on rpm.dat the
    largest cycle class carries the largest share and the quarter of the classes with the
    largest ranges > 95 % of it (the seed's Obr. 68/69 observation: the rarest, largest cycles
    do most of the damage)."""
    h = read_history(RPM_DAT)
    c = count_cycles(h.load_factor)
    dm = damage_matrix(200.0, c, STEEL)
    d = node_damage(np.array([200.0]), c, STEEL)[0]
    # exact arithmetic (round-off only; passes at 1e-13)
    assert dm.values.sum() == pytest.approx(d, rel=1e-12)
    from shaftfe.fatigue.kernels import cycle_damage
    per = cycle_damage(200.0, c, STEEL)
    assert np.argmax(per) == np.argmax(c.range)
    top = np.argsort(c.range)[-(c.n // 4):]
    assert per[top].sum() > 0.95 * per.sum()       # the seed's observation (a share, not a tol.)


# --- material cards ----------------------------------------------------------------------------

@pytest.mark.parametrize("body,pattern", [
    ("yield_MPa = -1\nultimate_MPa = 400\ncycles = [1e3, 1e6]\nalternating_MPa = [300, 100]",
     r"sn_curves\.x\.yield_MPa = -1 is invalid; allowed: > 0"),
    ("yield_MPa = 250\nultimate_MPa = 400\ncycles = [1e3, 1e3]\nalternating_MPa = [300, 100]",
     r"sn_curves\.x\.cycles .*strictly increasing"),
    ("yield_MPa = 250\nultimate_MPa = 400\ncycles = [1e3, 1e6]\nalternating_MPa = [100, 300]",
     r"sn_curves\.x\.alternating_MPa .*strictly decreasing"),
    ("yield_MPa = 250\nultimate_MPa = 400\nmean_stress_MPa = 50\ncycles = [1e3, 1e6]\n"
     "alternating_MPa = [300, 100]", r"sn_curves\.x\.mean_stress_MPa = 50"),
    ("yield_MPa = 250\nultimate_MPa = 400\ncycles = [1e3, 1e6]\nalternating_MPa = [300, 100]\n"
     "beyond_last = 'flat'", r"sn_curves\.x\.beyond_last = 'flat'"),
    ("yield_MPa = 250\nultimate_MPa = 400\nslope = 5", r"sn_curves\.x\.slope .*not a known key"),
])
def test_bad_material_card_names_file_and_field(tmp_path, body, pattern):
    """A bad S-N card gives one InputError line naming the file and the card field."""
    p = tmp_path / "cards.toml"
    p.write_text("[sn_curves.x]\n" + body + "\n", encoding="utf-8")
    with pytest.raises(InputError, match=pattern) as exc:
        load_material("x", p)
    assert str(p) in str(exc.value) and "\n" not in str(exc.value)


def test_seed_pair_life_25000_blocks_and_safety_07_are_consistent():
    """Seed 000 §8.3 gives two numbers for the same hot spot: safety factor 0.7 at 10⁷ blocks,
    and ≥ 1 only down to 25 000 blocks (i.e. a life of 25 000 blocks). With the seed's settings
    (Structural Steel, Soderberg, von Mises, 10⁷) and the rebuilt rpm.dat, the node whose life
    is 25 000 blocks has n(10⁷) in [0.65, 0.75), i.e. 0.7 when printed with one decimal as the
    # exact arithmetic (round-off only; passes at 1e-13)
    seed did. Hand check of the mechanism: the curve ends at 1e6 < 1e7 cycles, so n(10⁷) is set
    by the largest cycle alone (Δλ = 1.11857, λ_m = 0.58867, the 1200 ↔ 7500 rpm swing):
    n = 86.2 / (σ·Δλ/2 + 86.2 σ·λ_m / 250)."""
    h = read_history(RPM_DAT)
    c = count_cycles(h.load_factor)
    lo, hi = 100.0, 400.0                   # bisection on σ_eq for life = 25 000 blocks
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        d = node_damage(np.array([mid]), c, STEEL)[0]
        lo, hi = (lo, mid) if d * 25_000 > 1 else (mid, hi)
    s = 0.5 * (lo + hi)
    n, st = safety_factor(np.array([s]), c, STEEL, 1e7)
    assert st[0] == SOLVED and 0.65 <= n[0] < 0.75      # the seed's 0.7 printed to 1 decimal
    k = np.argmax(c.range)
    hand = 86.2 / (s * c.range[k] / 2 + 86.2 * s * c.mean[k] / 250.0)
    # similarity root to its default rtol 1e-10 (hand formula exact): 1e-9 = 10×
    assert n[0] == pytest.approx(hand, rel=1e-9)


def test_assess_from_components_and_hot_spot_mask():
    """(N, 6) components give the same result as their von Mises values (uniaxial σxx = σ_eq,
    hand); hot_spot() picks the most damaged node and honours an exclusion mask (the seed
    excluded a singular node under a bearing)."""
    h = read_history(RPM_DAT)
    s = np.array([120.0, 250.0, 180.0])
    comp = np.zeros((3, 6))
    comp[:, 0] = s
    a = assess(comp, h, STEEL)
    b = assess(s, h, STEEL)
    assert a.equivalent == "von_mises" and b.equivalent == "given"
    assert np.array_equal(a.damage_per_block, b.damage_per_block)
    assert np.array_equal(a.safety_factor, b.safety_factor)
    assert a.hot_spot() == 1
    assert a.hot_spot(mask=np.array([True, False, True])) == 2
    assert a.node_summary(1)["safety_status"] == "solved"
