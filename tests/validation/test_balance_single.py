"""Single-cylinder balancing model against seed 000 (ch. 5, §8.1, appendix 1) and closed forms.

Parameters A (seed 000 §5.2 / §8.1, SPEC.md §1): R = 0.0302 m, T1 = 0.1102 m, m_piston 0.358 kg,
m_bearing 0.042, m_rod_rot 0.148953, m_rod_pos 0.114447, n = 6000 rpm, β = 0.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from shaftfe.balance import kinematics as kin
from shaftfe.balance.engines import engine_from_dict, load_engine
from shaftfe.balance.single import balancer_ratio, crank_ratio, forces
from shaftfe.balance.sweep import sweep
from shaftfe.errors import InputError

PARAMS_A = {
    "crank_radius_mm": 30.2, "rod_length_mm": 110.2, "piston_group_mass_kg": 0.358,
    "bigend_bearing_mass_kg": 0.042, "rod_rot_mass_kg": 0.148953,
    "rod_pos_mass_kg": 0.114447, "tilt_deg": 0.0, "rpm": 6000.0,
}
M_POS = 0.358 + 0.114447
M_ROT = 0.042 + 0.148953
R_M, T1_M = 0.0302, 0.1102

# Seed 000 §5.4, the printed 10 × 8 matrix ("vysledky"), X = 31 … 40 %, X2 step 1 %.
SEED_X = np.arange(31, 41)
SEED_MAXF = [2219.6, 2163.2, 2113.9, 2075.4, 2038.1, 1994.3, 1937.9, 1904.8, 1873.6, 1825.3]
SEED_MAXF_X2 = [57, 57, 57, 57, 57, 56, 56, 56, 56, 55]
SEED_RMS = [1548.0, 1509.5, 1472.1, 1435.9, 1401.1, 1367.7, 1335.8, 1305.6, 1277.1, 1250.6]
SEED_FY_X2 = [68, 67, 66, 65, 64, 63, 62, 61, 60, 59]


def engine_a(**extra):
    return engine_from_dict({**PARAMS_A, **extra}, "parameters A (seed 000 §5.2)")


def amplitude(rpm=6000.0, m_pos=M_POS):
    return m_pos * R_M * float(kin.rad_per_s(rpm)) ** 2


@pytest.fixture(scope="module")
def seed_sweep():
    return sweep(engine_a(), SEED_X / 100, np.arange(0, 101) / 100, sampling="seed_inclusive")


@pytest.fixture(scope="module")
def exact_sweep():
    return sweep(engine_a(), SEED_X / 100, np.arange(0, 101) / 100)


def test_vm450_file_holds_parameters_a():
    """geometry/engines/vm450.toml carries the seed 000 §8.1 values (and β = −10°)."""
    e = load_engine("vm450")
    assert (e.crank_radius_mm, e.rod_length_mm) == (30.2, 110.2)
    assert e.m_pos_kg == pytest.approx(M_POS, abs=1e-12)   # exact arithmetic (sums of masses)
    assert e.m_rot_kg == pytest.approx(M_ROT, abs=1e-12)   # exact arithmetic
    assert e.tilt_deg == -10.0
    assert (e.compensation_mass_kg, e.compensation_radius_mm) == (3.678, 2.739)
    assert (e.balancer_mass_kg, e.balancer_radius_mm) == (0.9473, 8.22)


def test_mode2_table_seed_sampling_max_f(seed_sweep):
    """Seed 000 §5.4 matrix, columns 6 and 8: min max|F| within 0.2 N at the same X2 (1° grid
    0…360° inclusive, X2 step 1 %)."""
    m = seed_sweep.minima()["max_f"]
    # seed printed to 0.1 N (±0.05; measured 0.044 with its own sampling); 0.2 N as in the
    # default-sampling test below, where the seed's 1° grid misses the true peak by ≤ 0.18 N
    np.testing.assert_allclose(m[0], SEED_MAXF, atol=0.2, rtol=0)
    np.testing.assert_array_equal(np.round(100 * m[1], 9), SEED_MAXF_X2)


def test_mode2_table_seed_sampling_rms(seed_sweep):
    """Seed 000 §5.4 matrix, columns 5 and 7: min RMS within 0.1 N, all at X2 = 50 %, with the
    seed's sampling (0…360° inclusive at 1°: TDC counted twice)."""
    m = seed_sweep.minima()["rms_f"]
    # seed printed to 0.1 N: ±0.05 (measured 0.042); 0.1 = one unit of the printed digit
    np.testing.assert_allclose(m[0], SEED_RMS, atol=0.1, rtol=0)
    np.testing.assert_array_equal(np.round(100 * m[1], 9), 50)


def test_mode2_table_seed_sampling_fx_fy(seed_sweep):
    """Seed 000 §5.4 matrix, columns 1-4: min max|Fx| = 0 at X2 = X; min max|Fy| = 1605.1 N at
    X2 = 68 … 59 % (= 99 % − X on the seed's 1° grid, see test_min_max_fy_closed_form)."""
    m = seed_sweep.minima()
    assert np.all(m["max_abs_fx"][0] == 0.0)
    np.testing.assert_array_equal(np.round(100 * m["max_abs_fx"][1], 9), SEED_X)
    np.testing.assert_allclose(m["max_abs_fy"][0], 1605.1, atol=0.05, rtol=0)   # ±½ of 0.1 N
    np.testing.assert_array_equal(np.round(100 * m["max_abs_fy"][1], 9), SEED_FY_X2)


def test_mode2_table_default_sampling(exact_sweep):
    """Default (period, 0.1°) sampling against seed 000 §5.4: the exact period RMS is 1544.0 N at
    X = 31 % (SPEC.md §1: ≈ 0.26 % below the seed's 1548.0 N, which counts TDC twice); the
    max|F| minima stay within 0.2 N of the seed and at the same X2 (largest gap 0.18 N at
    X = 38 %: the seed's 1° grid misses the true peak by that much)."""
    m = exact_sweep.minima()
    # SPEC figure printed to 0.1 N (±0.05; measured 0.0496, on the rounding edge: one unit)
    assert m["rms_f"][0][0] == pytest.approx(1544.0, abs=0.1)
    np.testing.assert_array_equal(np.round(100 * m["rms_f"][1], 9), 50)
    # seed's 1° grid misses the true peak by ≤ 0.18 N (docstring) + its 0.05 N printing
    np.testing.assert_allclose(m["max_f"][0], SEED_MAXF, atol=0.2, rtol=0)
    np.testing.assert_array_equal(np.round(100 * m["max_f"][1], 9), SEED_MAXF_X2)


def test_exact_rms_is_converged():
    """Period RMS of a smooth periodic integrand with the uniform rule converges spectrally:
    360 and 36000 samples agree to 1e-12 (closed-form property of the trapezoid rule), while the
    seed's inclusive grid is ≈ 0.26 % high (SPEC.md §1)."""
    e = engine_a()
    r360 = forces(e, 0.31, 0.50, n=360).metrics.rms_f
    r36k = forces(e, 0.31, 0.50, n=36000).metrics.rms_f
    seed = forces(e, 0.31, 0.50, sampling="seed_inclusive").metrics.rms_f
    # exact arithmetic: the aliased harmonics (order ≥ 360, amplitude ~ (R/T1)^180) are far
    # below round-off (measured 1e-16); was 1e-10
    assert r360 == pytest.approx(r36k, rel=1e-12)
    # SPEC's "≈ 0.26 %" (2 digits, ±0.005 %; measured 0.258 %): 0.02 % = 4× that
    assert seed / r36k - 1 == pytest.approx(0.0026, abs=0.0002)


def test_min_max_fy_closed_form(exact_sweep):
    """min over X2 of max|Fy| = |F_sp(90°)| = A / sqrt(p² − 1), p = T1/R (seed 000 §5.1 at
    α = 90°, where the 1st-order terms vanish), reached at X + X2 = 100 %. The seed's 68 % for
    X = 31 % is a tie on its 1° grid (max|Fy| is the same at X + X2 = 99, 100, 101 %) resolved
    to the first index; finer sampling breaks the tie at X2 = 100 % − X."""
    p = T1_M / R_M
    ref = amplitude() / math.sqrt(p * p - 1.0)
    m = exact_sweep.minima()["max_abs_fy"]
    # exact arithmetic: α = 90° is a sample of the 0.1° grid (measured 4e-16); was 1e-9
    np.testing.assert_allclose(m[0], ref, rtol=1e-12)
    assert ref == pytest.approx(1605.1, abs=0.05)      # seed printed to 0.1 N: ±0.05
    np.testing.assert_array_equal(np.round(100 * m[1], 9), 100 - SEED_X)


def test_x2_31_gives_3731_at_tdc():
    """Seed 000 §8.1.1 (Fig. 53): X = 30.16 %, X2 = 31 % → max|F| = 3731 N at TDC; closed form
    at TDC: A (1 + R/T1 − X − X2)."""
    r = forces(engine_a(), 0.3016, 0.31).metrics
    assert r.max_f == pytest.approx(3731, abs=0.5)         # seed prints whole newtons: ±0.5
    assert r.max_f_deg == 0.0
    # exact arithmetic (closed form at TDC, a sample)
    assert r.max_f == pytest.approx(amplitude() * (1 + R_M / T1_M - 0.3016 - 0.31), rel=1e-12)


def test_x2_545_gives_2408_at_tdc():
    """Seed 000 §8.1 (Fig. 49): X = 30.16 %, X2 = 54.5 % → max|F| at TDC, exact model 2407.7 N =
    A (1 + R/T1 − X − X2). The seed reports 2390 N read off its plot (SPEC.md §1); our value is
    0.74 % higher, the same ratio as appendix 1's 5437 N vs 5477.5 N (test below)."""
    r = forces(engine_a(), 0.3016, 0.545).metrics
    ref = amplitude() * (1 + R_M / T1_M - 0.3016 - 0.545)
    assert r.max_f == pytest.approx(ref, rel=1e-12)        # exact arithmetic (TDC sample)
    assert r.max_f == pytest.approx(2408, abs=0.5)         # 2407.7 N to whole newtons: ±0.5
    assert r.max_f_deg == 0.0
    # the seed's plot reading is low by appendix 1's ratio 5477.5/5437 − 1 = 0.745 %; 0.76 %
    # = that ratio plus ±0.5 N of the 2390 N reading (measured 0.741 %)
    assert 0 < r.max_f / 2390 - 1 < 0.0076


def test_balance_ratios_from_masses():
    """Seed 000 eq. 2.3.f / 2.3.h with the inputs the seed prints in §8.1-8.2.1 (its equations
    use the rounded m_POS = 0.473, m_ROT = 0.191 kg):
    crank A 3.678 kg × 2.74 mm → 30.17 % (printed 30.16 %: its γ = 2.7397 mm is shown as 2.739);
    crank B 3.40 × 4.85 → 75.06 %; balancer 0.947 × 8.22 → 54.5 %; A4 0.765 × 5.74 → 30.74 %;
    crank C 3.580 × 2.85 mm → 31.1 % (exact masses; the seed prints no equation for C)."""
    R = 30.2
    # printed precision: half a unit of the last digit (0.005 %, 0.05 % for 54.5), except
    # 30.16, whose printed γ is 2.739 for 2.7397 (docstring): 0.01 % (measured 0.009)
    assert 100 * crank_ratio(3.678, 2.74, 0.191, 0.473, R) == pytest.approx(30.16, abs=0.01)
    assert 100 * crank_ratio(3.40, 4.85, 0.191, 0.473, R) == pytest.approx(75.06, abs=0.005)
    assert 100 * balancer_ratio(0.947, 8.22, 0.473, R) == pytest.approx(54.5, abs=0.05)
    assert 100 * balancer_ratio(0.765, 5.74, 0.473, R) == pytest.approx(30.74, abs=0.005)
    assert round(100 * crank_ratio(3.580, 2.85, M_ROT, M_POS, R), 1) == 31.1
    # the engine file route gives the same numbers
    e = engine_a(compensation_mass_kg=3.40, compensation_radius_mm=4.85,
                 balancer_mass_kg=0.765, balancer_radius_mm=5.74)
    # exact arithmetic (round-off only): the same formula by the engine-file route
    assert e.X == pytest.approx(crank_ratio(3.40, 4.85, M_ROT, M_POS, R), rel=1e-14)
    assert e.X2 == pytest.approx(balancer_ratio(0.765, 5.74, M_POS, R), rel=1e-14)


def test_appendix1_balancer_force():
    """Seed 000 appendix 1: balancer shaft A.1 force m e ω² = 0.947 · 0.00822 · 628.3² = 3073 N,
    constant over the revolution."""
    rpm = 628.3 * 60 / (2 * math.pi)
    e = engine_a(balancer_mass_kg=0.947, balancer_radius_mm=8.22, crank_balance_percent=30.16)
    r = forces(e, rpm=rpm)
    fb = np.hypot(r.Fx_balancer, r.Fy_balancer)
    assert round(float(fb.max())) == 3073
    np.testing.assert_allclose(fb, 0.947 * 0.00822 * 628.3**2, rtol=1e-12)   # exact arithmetic


def test_appendix1_crank_mechanism_force():
    """Seed 000 appendix 1, max|F_vk| = 5437 N at 6000 rpm (ω = 628.3 rad/s).

    F_vk is the crank mechanism alone (Fig. 48/74: no balancer), which for X = 30.16 % is
    A (1 + R/T1 − X) = 5477.5 N at TDC. The seed's 5437 N is reproduced (5437.6 N, the seed
    truncates as with 30.169 → 30.16 %) only by the piston group alone (0.358 kg, rod shares
    and X set to 0): the inertia force m_piston R ω² (1 + R/T1) at TDC."""
    full = forces(engine_a(), 0.3016, 0.0)
    ref = amplitude() * (1 + R_M / T1_M - 0.3016)
    assert full.metrics.max_f == pytest.approx(ref, rel=1e-12)     # exact arithmetic (TDC)
    assert full.metrics.max_f_deg == 0.0
    np.testing.assert_array_equal(full.Fx_crank, full.Fx)   # X2 = 0: crank alone = total
    piston = engine_a(rod_rot_mass_kg=0.0, rod_pos_mass_kg=0.0, bigend_bearing_mass_kg=0.0)
    r = forces(piston, 0.0, 0.0, rpm=628.3 * 60 / (2 * math.pi)).metrics
    assert math.floor(r.max_f) == 5437
    assert r.max_f_deg == 0.0


def test_infinite_rod_half_and_half_cancels():
    """Seed 000 §5.3 (Fig. 28): X = X2 = 50 % with an 'infinite' rod cancels the 1st order.
    With T1 = 1e6 R the 2nd order left is λ A cos 2α, λ = R/T1 = 1e-6 (series expansion of the
    exact a_pos; the λ³ term is 1e-18): after it, < 1e-12 A remains; Fx is zero."""
    lam = 1e-6
    e = engine_a(rod_length_mm=30.2 / lam)
    r = forces(e, 0.5, 0.5, sampling="period", n=720)
    A = r.first_order_amplitude
    a = np.deg2rad(r.alpha_deg)
    assert np.max(np.abs(r.Fx)) < 1e-12 * A          # exact arithmetic (measured 0)
    # λ³ term 1e-18 A + round-off of the cancelled first order ~eps A (measured 2.8e-16 A);
    # was 1e-9
    assert np.max(np.abs(r.Fy - lam * A * np.cos(2 * a))) < 1e-12 * A
    # max|F| = λ A (1 + O(λ²)) + round-off ~eps A = 2e-10 λA (measured 1.4e-10 λA); was 1e-6
    assert r.metrics.max_f < lam * A * (1 + 1e-8)


def test_infinite_rod_full_crank_balance_moves_force_to_x():
    """Seed 000 §5.2 (Fig. 26): X = 100 %, X2 = 0, infinite rod → the 1st-order force appears
    only across the cylinder: Fx = −A sin α; Fy is the 2nd-order remainder λ A cos 2α only."""
    lam = 1e-6
    r = forces(engine_a(rod_length_mm=30.2 / lam), 1.0, 0.0, n=720)
    A = r.first_order_amplitude
    a = np.deg2rad(r.alpha_deg)
    np.testing.assert_allclose(r.Fx, -A * np.sin(a), rtol=0, atol=1e-12 * A)   # exact (0)
    # as in the test above: λ³ term + round-off, measured 2.8e-16 A; was 1e-9
    assert np.max(np.abs(r.Fy - lam * A * np.cos(2 * a))) < 1e-12 * A


def test_forces_scale_with_rpm_squared():
    """F ∝ ω² exactly (every term of seed 000 §5.1 carries ω²)."""
    e = engine_a()
    a = forces(e, 0.3016, 0.545, rpm=3000.0)
    b = forces(e, 0.3016, 0.545, rpm=9000.0)
    # exact arithmetic (round-off only: measured 4.5e-12 N on 5.4 kN; atol for zero crossings)
    np.testing.assert_allclose(b.Fx, 9 * a.Fx, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(b.Fy, 9 * a.Fy, rtol=1e-12, atol=1e-9)
    assert b.metrics.rms_f == pytest.approx(9 * a.metrics.rms_f, rel=1e-12)


def test_tilt_rotates_the_vector():
    """Seed 000 §5.1 (Fig. 21): the tilt β only rotates the force vector: |F| unchanged, the
    components rotate by β; β = 90° maps the cylinder axis (+y) onto −x."""
    e = engine_a()
    r0 = forces(e, 0.3016, 0.545, tilt_deg=0.0)
    for beta in (-10.0, 37.0, 90.0):
        rb = forces(e, 0.3016, 0.545, tilt_deg=beta)
        c, s = math.cos(math.radians(beta)), math.sin(math.radians(beta))
        # exact arithmetic (round-off only, forces ~3 kN: 1e-9 N = 3e-13 relative; measured
        # 0 and 3e-16 relative)
        np.testing.assert_allclose(rb.Fx, c * r0.Fx - s * r0.Fy, rtol=0, atol=1e-9)
        np.testing.assert_allclose(rb.Fy, s * r0.Fx + c * r0.Fy, rtol=0, atol=1e-9)
        np.testing.assert_allclose(rb.F, r0.F, rtol=1e-13)
    r90 = forces(e, 0.3016, 0.545, tilt_deg=90.0)
    np.testing.assert_allclose(r90.Fx, -r0.Fy, rtol=0, atol=1e-9)      # exact arithmetic


def test_start_angle_shifts_samples():
    """The start angle α0 (seed 000 §5 input α) only shifts the samples of the periodic force."""
    e = engine_a()
    r0 = forces(e, 0.3016, 0.545, n=360)
    r30 = forces(e, 0.3016, 0.545, n=360, start_deg=30.0)
    # exact arithmetic: the same angles up to the rounding of α0 + k° (measured 2.7e-12 N)
    np.testing.assert_allclose(r30.Fy, np.roll(r0.Fy, -30), rtol=0, atol=1e-9)
    assert r30.metrics.max_f_deg == 0.0      # the TDC peak is still reported at 0°
    assert r30.metrics.rms_f == pytest.approx(r0.metrics.rms_f, rel=1e-12)   # exact arithmetic


def test_sweep_equals_single_evaluation():
    """The broadcast sweep and the single-point forces() give identical metrics (same kernel,
    seed 000 §5.4 loop replaced by broadcasting), also with a tilt."""
    e = engine_a(tilt_deg=-10.0)
    sw = sweep(e, [0.3016, 0.75], [0.31, 0.545], n=720)
    for i, x in enumerate((0.3016, 0.75)):
        for j, x2 in enumerate((0.31, 0.545)):
            m = forces(e, x, x2, n=720).metrics
            for k in ("max_abs_fx", "max_abs_fy", "rms_f", "max_f"):
                # exact arithmetic (same kernel, broadcast)
                assert getattr(sw, k)[i, j] == pytest.approx(getattr(m, k), rel=1e-12)


def test_bad_engine_files(tmp_path: Path):
    """Engine-file validation: negative mass, unknown key, rod shorter than the crank, unknown
    engine → InputError naming the file (or option) and the field."""
    base = "\n".join(f"{k} = {v}" for k, v in PARAMS_A.items())
    f = tmp_path / "neg.toml"
    f.write_text(base.replace("piston_group_mass_kg = 0.358", "piston_group_mass_kg = -0.358"))
    with pytest.raises(InputError, match=r"neg\.toml: piston_group_mass_kg = -0\.358"):
        load_engine(f)
    f.write_text(base + "\nbalancer_mas_kg = 1.0\n")
    with pytest.raises(InputError, match="balancer_mas_kg"):
        load_engine(f)
    f.write_text(base.replace("rod_length_mm = 110.2", "rod_length_mm = 20.0"))
    with pytest.raises(InputError, match=r"rod_length_mm = 20\.0"):
        load_engine(f)
    with pytest.raises(InputError, match="vm450"):
        load_engine("no_such_engine")
    with pytest.raises(InputError, match="--x"):
        forces(engine_a(), 2.5, 0.0)
