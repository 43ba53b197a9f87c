"""Validation of the multi-cylinder balancing model (shaftfe.balance.multi).

References: seed 000 §4.3.1-4.3.5 (twins, I3, I4) and ch. 7 (two-cylinder model); closed forms
derived in the docstrings (primary force of cylinder i: A cos(θ − φ_i) along its axis,
A = m_pos R ω²; couple of a force at axial position z: z e_z × F); the single-cylinder kernel
shaftfe.balance.kinematics (seed 000 §5.1).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from shaftfe.balance import multi
from shaftfe.balance.kinematics import rad_per_s, reciprocating_force, rotate, shaking_forces
from shaftfe.errors import InputError

# Parameters A of seed 000 §5.2 (VM 450): R, T1, m_pos = m_piston + m_rod_pos.
MECH = multi.Mechanism(R=0.0302, T1=0.1102, m_pos=0.358 + 0.114447)
OMEGA = float(rad_per_s(6000.0))
A = MECH.amplitude(OMEGA)
N = multi.DEFAULT_SAMPLES
# exact arithmetic (round-off only): every check below is an exact cancellation or closed
# form evaluated by a real FFT of exact sums; all of them pass at 1e-14 (was 1e-9, and rel=1e-9)
TOL = 1e-12


def single_order(k: int, n: int = N) -> float:
    """Order-k amplitude of ONE cylinder's exact reciprocating force, by its own real FFT."""
    theta = np.arange(n) * (2 * np.pi / n)
    f = reciprocating_force(theta, MECH.m_pos, MECH.R, MECH.T1, OMEGA)
    return float(2 * abs(np.fft.rfft(f)[k]) / n)


def run(cyls, **kw):
    return multi.engine_forces(cyls, MECH, OMEGA, **kw)


# --- single cylinder, harmonic bookkeeping --------------------------------------------------

@pytest.mark.parametrize("phase,tilt,X,X2", [(0.0, 0.0, 0.0, 0.0), (0.0, -10.0, 0.3016, 0.545),
                                             (37.0, 25.0, 0.75, 0.31)])
def test_single_cylinder_equals_kernel(phase, tilt, X, X2):
    """One cylinder through the multi code = kinematics.shaking_forces rotated by β (seed 000
    §5.1 kernel, SPEC §1; X = 30.16 %, X2 = 54.5 %, β = −10° are seed 000 §8.1 values), to 1e-12
    of A, at any TDC phase."""
    r = run((multi.Cylinder(phase_deg=phase, tilt_deg=tilt, X=X, X2=X2),))
    alpha = r.theta - math.radians(phase)
    fx, fy = rotate(*shaking_forces(alpha, MECH.m_pos, MECH.R, MECH.T1, OMEGA, X, X2),
                    math.radians(tilt))
    # exact arithmetic (round-off only; passes at 1e-14)
    assert np.max(np.abs(r.Fx - fx)) <= 1e-12 * A
    assert np.max(np.abs(r.Fy - fy)) <= 1e-12 * A
    assert np.max(r.M) == 0.0  # a single cylinder at the reference position has no couple


def test_first_order_of_exact_kinematics_is_A_and_odd_orders_vanish():
    """Exact slider-crank: y_pos = R cos α + sqrt(T1² − R² sin² α) (seed 000 §5.1); the root is
    a function of cos 2α, so the 1st harmonic of F_sp is exactly A cos α and orders 3, 5 are 0."""
    r = run((multi.Cylinder(),), orders=(1, 2, 3, 5))
    # exact arithmetic (round-off only; passes at 1e-14)
    assert r.force_order(1).amplitude == pytest.approx(A, rel=1e-12)
    assert r.force_order(2).amplitude == pytest.approx(single_order(2), rel=1e-12)
    assert r.force_order(3).amplitude <= 1e-12 * A
    assert r.force_order(5).amplitude <= 1e-12 * A


def test_co_and_counter_rotating_split():
    """Single cylinder (SPEC §1 / seed 000 §2.2): X = 50 % leaves A/2 turning against the crank
    (what a 1:1 counter-rotating balancer with X2 = 50 % removes) and nothing turning with it;
    X2 = 50 % alone leaves A/2 turning with the crank. The ellipse of order 1 then is a circle."""
    o = run((multi.Cylinder(X=0.5),)).force_order(1)
    # exact arithmetic (round-off only; passes at 1e-14)
    assert o.co_rotating <= 1e-12 * A
    assert o.counter_rotating == pytest.approx(A / 2, rel=1e-12)
    assert o.minor == pytest.approx(A / 2, rel=1e-12)
    o = run((multi.Cylinder(X2=0.5),)).force_order(1)
    # exact arithmetic (round-off only; passes at 1e-14)
    assert o.counter_rotating <= 1e-12 * A
    assert o.co_rotating == pytest.approx(A / 2, rel=1e-12)
    o = run((multi.Cylinder(X=0.5, X2=0.5),)).force_order(1)
    # exact arithmetic (round-off only; passes at 1e-14)
    assert o.amplitude <= 1e-12 * A


def test_harmonic_orders_of_a_known_ellipse():
    """Closed form: v = a cos kθ + b sin kθ with a ⟂ b has semi-axes |a|, |b|; component
    amplitudes are |a_x|, |b_y| (here a = (0, 3), b = (5, 0), k = 2)."""
    theta = multi.crank_angles(64)
    vx, vy = 5 * np.sin(2 * theta), 3 * np.cos(2 * theta)
    (o,) = multi.harmonic_orders(vx, vy, (2,))
    # exact arithmetic (round-off only) here and in every rel=1e-12 / TOL check of this file
    assert (o.amplitude, o.minor, o.x, o.y) == pytest.approx((5, 3, 5, 3), rel=1e-12)
    assert o.co_rotating + o.counter_rotating == pytest.approx(5, rel=1e-12)


def test_forces_scale_with_rpm_squared():
    """Every term is m R ω² times a function of θ (seed 000 §5.1), so 3000 → 7000 rpm scales
    forces and couples by (7/3)² exactly."""
    cyls = multi.inline([0, 90, 200], [0.08, 0.10], X=[0.3, 0.5, 0.7])  # nothing cancels
    lo = multi.engine_forces(cyls, MECH, float(rad_per_s(3000.0)))
    hi = multi.engine_forces(cyls, MECH, float(rad_per_s(7000.0)))
    s = (7.0 / 3.0) ** 2
    for a, b in ((lo.Fx, hi.Fx), (lo.Fy, hi.Fy), (lo.Mx, hi.Mx), (lo.My, hi.My),
                 (lo.Fx_cyl, hi.Fx_cyl), (lo.Fy_cyl, hi.Fy_cyl)):
        assert np.max(np.abs(b)) > 0.1 * hi.A * 0.08
        # exact arithmetic (round-off only; passes at 1e-14)
        assert np.max(np.abs(s * a - b)) <= 1e-12 * np.max(np.abs(b))
    assert hi.max_force == pytest.approx(s * lo.max_force, rel=1e-12)


# --- inline engines -------------------------------------------------------------------------

def test_i3_120_forces_cancel_and_primary_couple_closed_form():
    """I3, pins 0/120/240°, spacing s (seed 000 §4.3.4: 1st and 2nd order forces balanced,
    significant couples). Closed form (derived; cf. Taylor, The Internal-Combustion Engine in
    Theory and Practice, vol. 2, ch. 8): with z = −s, 0, s about the middle,
    Mx = −Σ z_i A cos(θ − φ_i) = A s [cos θ − cos(θ − 240°)] = −√3 A s sin(θ − 120°), so the
    1st-order couple amplitude is √3 m_pos R ω² s. Order k in general: s·|e^{−ikφ3} − 1|·F_k,
    i.e. √3 s F_2 for order 2 (F_k from the single cylinder's own FFT); order 6 forces add (3 F_6).
    """
    s = 0.08
    r = run(multi.inline([0, 120, 240], s), orders=(1, 2, 4, 6))
    # exact arithmetic (round-off only; passes at 1e-14)
    assert r.force_order(1).amplitude <= TOL * A
    assert r.force_order(2).amplitude <= TOL * A
    assert r.force_order(4).amplitude <= TOL * A
    assert r.force_order(6).amplitude == pytest.approx(3 * single_order(6), rel=1e-12)
    assert r.z_ref_m == pytest.approx(s)       # exact arithmetic: approx's default rel 1e-6
    c1 = r.couple_order(1)
    # exact arithmetic (round-off only; passes at 1e-14)
    assert c1.amplitude == pytest.approx(math.sqrt(3) * A * s, rel=1e-12)
    assert c1.y <= TOL * A * s  # no side force → no yaw couple
    assert r.couple_order(2).amplitude == pytest.approx(math.sqrt(3) * s * single_order(2),
                                                        rel=1e-12)


def test_i3_middle_pin_180_trades_couples_for_force():
    """I3 with the outer pins together and the middle one at 180° (seed 000 §4.3.4: no couple,
    1st order balanced only to 2/3, 2nd orders of all cylinders add). Closed form: phasor sums
    2 − 1 = 1 (order 1) and 2 + 1 = 3 (even orders) of the single-cylinder amplitudes; the
    outer cylinders are equal and symmetric about the middle → zero couple about it."""
    s = 0.08
    r = run(multi.inline([0, 180, 0], s), orders=(1, 2, 4))
    residual = r.force_order(1).amplitude
    # exact arithmetic (round-off only; passes at 1e-14)
    assert residual == pytest.approx(A, rel=1e-12)
    assert 1 - residual / (3 * A) == pytest.approx(2 / 3, rel=1e-12)  # "2/3 balanced"
    assert r.force_order(2).amplitude == pytest.approx(3 * single_order(2), rel=1e-12)
    assert r.force_order(4).amplitude == pytest.approx(3 * single_order(4), rel=1e-12)
    assert r.max_couple <= TOL * A * s


def test_flat_plane_i4():
    """Flat-plane I4, pins 0/180/180/0 (seed 000 §4.3.5: 1st order and couples balanced, the
    2nd orders of the pistons add). Order 2 and 4 = 4× one cylinder's exact amplitude (its own
    FFT), not just λ m R ω²; mirror symmetry about the middle → zero couple."""
    s = 0.085
    r = run(multi.inline([0, 180, 180, 0], s), orders=(1, 2, 4))
    # exact arithmetic (round-off only; passes at 1e-14)
    assert r.force_order(1).amplitude <= TOL * A
    assert r.couple_order(1).amplitude <= TOL * A * s
    assert r.max_couple <= TOL * A * s
    f2 = r.force_order(2)
    # exact arithmetic (round-off only; passes at 1e-14)
    assert f2.amplitude == pytest.approx(4 * single_order(2), rel=1e-12)
    assert f2.x <= TOL * A  # along the cylinder axes
    assert r.force_order(4).amplitude == pytest.approx(4 * single_order(4), rel=1e-12)
    # Exact vs λ m R ω²: binomial expansion of sqrt(1 − λ² sin² α) gives the harmonic
    # coefficients of F_sp / A: order 2 = λ + λ³/4 + 15λ⁵/128 + 35λ⁷/512 + O(λ⁹),
    # order 4 = λ³/4 + 3λ⁵/16 + O(λ⁷) (classical series, e.g. Den Hartog, Mechanical Vibrations).
    lam = MECH.R / MECH.T1
    series2 = lam + lam**3 / 4 + 15 * lam**5 / 128 + 35 * lam**7 / 512
    # truncated series: the first omitted term is O(λ⁹) (λ = 0.274: 9e-6)
    assert f2.amplitude / (4 * A) == pytest.approx(series2, abs=lam**9)
    # λ m R ω² alone is low by λ²/4 + 15λ⁴/128 + … = 1.94 % here (series above): > 1.9 %
    assert f2.amplitude / (4 * lam * A) - 1 > 0.019
    series4 = lam**3 / 4 + 3 * lam**5 / 16
    # truncated series: first omitted term O(λ⁷) (5e-5)
    assert r.force_order(4).amplitude / (4 * A) == pytest.approx(series4, abs=lam**7)


def test_inline_spacing_list_and_reference_point():
    """Unequal gaps: the couple is taken about the mean cylinder position (module docstring);
    for a single-plane check, I2 360° (pins 0/0) with gap g has zero couple about its middle and
    a 180° I2 has the primary couple A g (closed form: (g/2)·A cos θ·2)."""
    g = 0.07
    r = run(multi.inline([0, 180], [g]), orders=(1,))
    # exact arithmetic (round-off only; passes at 1e-14)
    assert r.couple_order(1).amplitude == pytest.approx(A * g, rel=1e-12)
    assert r.force_order(1).amplitude <= TOL * A
    r = run(multi.inline([0, 0], g), orders=(1,))
    # exact arithmetic (round-off only; passes at 1e-14)
    assert r.max_couple <= TOL * A * g
    r = run(multi.inline([0, 120, 240], [0.08, 0.10]))
    assert r.z_ref_m == pytest.approx((0 + 0.08 + 0.18) / 3)     # exact: default rel 1e-6


# --- twins (seed 000 §4.3.1-4.3.3, ch. 7) ---------------------------------------------------

@pytest.mark.parametrize("delta", [0.0, 90.0, 180.0])
def test_seed_twins_cancel_first_order(delta):
    """180° I2 (δ = 0), 90° V2, boxer (δ = 180) with the default ε and counterweights (seed 000
    §4.3.1-4.3.3, ch. 7.1): residual 1st order ≤ 1e-12 A. The default ε equals the seed's
    2δ − 180° modulo 360° for these three δ."""
    cyls = multi.twin(delta)
    eps = cyls[1].phase_deg - delta
    # exact arithmetic: the angle is a multiple of 360° (cos = 1 up to one rounding)
    assert math.isclose(math.cos(math.radians(eps - (2 * delta - 180))), 1.0, abs_tol=1e-15)
    r = run(cyls)
    # exact arithmetic (round-off only; passes at 1e-14)
    assert r.force_order(1).amplitude <= TOL * A
    assert multi.resultant_counterweight(cyls) == pytest.approx(math.sin(math.radians(delta)),
                                                                abs=1e-12)


def test_v90_shared_pin_one_full_counterweight():
    """90° V2 with a shared pin and one 100 % compensation mass (seed 000 §4.3.1, ch. 7: the
    second compensation mass is dropped): 1st order cancelled. Seed §4.3.1: the 2nd-order
    resultant is 1.4 (= √2) times one cylinder's and acts across the bisector (x)."""
    cyls = multi.twin(90.0, shared_pin=True)
    assert (cyls[0].X, cyls[1].X) == (1.0, 0.0)
    r = run(cyls)
    # exact arithmetic (round-off only; passes at 1e-14)
    assert r.force_order(1).amplitude <= TOL * A
    f2 = r.force_order(2)
    # exact arithmetic (round-off only; passes at 1e-14)
    assert f2.amplitude == pytest.approx(math.sqrt(2) * single_order(2), rel=1e-12)
    assert f2.y <= TOL * A
    # two 50 % masses on coincident pins (ε = 0) are the same crank: identical forces
    r2 = run(multi.twin(90.0))
    # exact arithmetic (round-off only; passes at 1e-14)
    assert np.max(np.abs(r.Fx - r2.Fx)) + np.max(np.abs(r.Fy - r2.Fy)) <= 1e-12 * A


def test_i2_360_is_a_single_cylinder_with_double_masses():
    """Seed 000 §4.3.2: the 360° I2 (δ = 0, ε = 0) behaves like a single cylinder with twice
    the masses: forces = 2 × kernel(X)."""
    X = 0.4
    r = run(multi.twin(0.0, 0.0, X=X))
    fx, fy = shaking_forces(r.theta, MECH.m_pos, MECH.R, MECH.T1, OMEGA, X, 0.0)
    # exact arithmetic (round-off only; passes at 1e-14)
    assert np.max(np.abs(r.Fx - 2 * fx)) <= 1e-12 * A
    assert np.max(np.abs(r.Fy - 2 * fy)) <= 1e-12 * A


@pytest.mark.parametrize("delta", [30.0, 52.0, 60.0, 120.0])
def test_general_delta_default_and_seed_printed_epsilon(delta):
    """Derived in multi's docstring: with α02 = α01 − δ − ε the counter-rotating 1st order is
    (A/2)|1 + e^{i(2δ + ε)}| = A|cos((2δ + ε)/2)|. Default ε = 180° − 2δ cancels it; the seed's
    printed ε = 2δ − 180° leaves A|sin 2δ| unless δ ∈ {0, 90, 180}. The default counterweights
    (50 % per pin) give the resultant sin δ of one cylinder (the seed's X = 100 sin δ %)."""
    r = run(multi.twin(delta))
    # exact arithmetic (round-off only; passes at 1e-14)
    assert r.force_order(1).amplitude <= TOL * A
    assert multi.resultant_counterweight(multi.twin(delta)) == pytest.approx(
        math.sin(math.radians(delta)), rel=1e-12)
    o = run(multi.twin(delta, 2 * delta - 180)).force_order(1)
    # exact arithmetic (round-off only; passes at 1e-14)
    assert o.counter_rotating == pytest.approx(A * abs(math.sin(math.radians(2 * delta))),
                                               rel=1e-12)
    # exact arithmetic (round-off only; passes at 1e-14)
    assert o.co_rotating <= TOL * A


@pytest.mark.parametrize("delta", [45.0, 60.0, 90.0])
def test_literal_per_pin_sin_delta_and_shared_pin_residuals(delta):
    """Closed forms (multi docstring): X = sin δ opposite EACH pin leaves a co-rotating
    (A/2)|1 − 2 sin δ|·|p1 + p2| = A sin δ |1 − 2 sin δ|; a shared pin with one 100 % mass leaves
    only A |cos δ| counter-rotating (seed §4.3.1: below 90° a shared pin cannot be fully
    balanced without a balancer shaft)."""
    sd = math.sin(math.radians(delta))
    o = run(multi.twin(delta, X=sd)).force_order(1)
    # exact arithmetic (round-off only; passes at 1e-14)
    assert o.co_rotating == pytest.approx(A * sd * abs(1 - 2 * sd), rel=1e-12)
    o = run(multi.twin(delta, shared_pin=True)).force_order(1)
    # exact arithmetic (round-off only; passes at 1e-14)
    assert o.co_rotating <= TOL * A
    assert o.counter_rotating == pytest.approx(A * abs(math.cos(math.radians(delta))), abs=TOL * A)


def test_twin_offset_gives_the_i2_couple():
    """180° I2 with the cylinders e apart (seed §4.3.2: first order balanced 'at the cost of a
    rocking couple on the arm e'): 1st-order couple A e with X = 0 (closed form
    (e/2)·A cos θ·2); with 50 % per pin the co-rotating half is cancelled → A e / 2."""
    e = 0.09
    r = run(multi.twin(0.0, X=0.0, offset_m=e))
    # exact arithmetic (round-off only; passes at 1e-14)
    assert r.couple_order(1).amplitude == pytest.approx(A * e, rel=1e-12)
    r = run(multi.twin(0.0, offset_m=e))
    c = r.couple_order(1)
    # exact arithmetic (round-off only; passes at 1e-14)
    assert c.amplitude == pytest.approx(A * e / 2, rel=1e-12)
    assert c.co_rotating <= TOL * A * e


# --- input validation -----------------------------------------------------------------------

@pytest.mark.parametrize("call", [
    lambda: multi.twin(181.0),
    lambda: multi.twin(-1.0),
    lambda: multi.twin(float("nan")),
    lambda: multi.twin(60.0, 30.0, shared_pin=True),
    lambda: multi.twin(60.0, shared_pin=True, X=[1.0, 0.5]),
    lambda: multi.twin(60.0, X=[0.5, 0.5, 0.5]),
    lambda: multi.twin(60.0, X=3.0),
    lambda: multi.inline([0, 120, 240], [0.08]),
    lambda: multi.inline([0, 120, 240], [0.08, -0.1]),
    lambda: multi.inline([0, 120, 240], 0.08, X=[0.5, 0.5]),
    lambda: multi.inline([], 0.08),
    lambda: multi.engine_forces(multi.inline([0], 0.0), MECH, OMEGA, orders=(400,)),
    lambda: multi.engine_forces(multi.inline([0], 0.0), MECH, OMEGA, samples=4),
])
def test_bad_layout_raises_input_error(call):
    with pytest.raises(InputError):
        call()
