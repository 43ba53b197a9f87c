"""ISO 281 bearing life and the seed's key and gear checks.

Sources: SKF Rolling bearings catalogue, calculation example 1 (6309, C 55.3 kN, P 10 kN,
3000 r/min: L10 = 169 million revolutions, L10h = 940 h, printed to 3 digits); ISO 281:2007
a_ISO for radial ball bearings (continuity of its three κ ranges, the 50 cap); seed 000
§8.2.2 (3303: 1250.7 h at 2931 N and 7000 rpm; key length 0.126 mm; Inventor's Merritt output
for the gear pair: F_t 16.860, F_r 6.690, F_n 18.139 N, v 32.830 m/s, safety 33.93, printed
to the digits compared).
"""

import math

import numpy as np
import pytest

from shaftfe.machine_elements import drive, gear, key
from shaftfe.model import bearing_life as bl


def test_skf_catalogue_example_basic_life():
    L10 = (55.3 / 10.0) ** 3                                   # million revolutions
    assert round(L10) == 169
    assert round(bl.l10h(55300.0, 10000.0, 3000.0), -1) == 940.0


def test_a_iso_formula_and_ranges():
    # hand value: κ 2.45, e_C C_u/P = 0.8 × 1.34/10, written out
    x = 0.8 * 1.34 / 10
    want = 0.1 * (1 - (2.5671 - 1.9987 / 2.45 ** 0.071739) ** 0.83 * x ** (1 / 3)) ** -9.3
    assert bl.a_iso_ball(2.45, x) == pytest.approx(want, rel=1e-14)
    # the three ranges join: the constants are rounded to 5 digits, so the joins agree to 1e-3
    for k0 in (0.4, 1.0):
        lo, hi = bl.a_iso_ball(k0 * (1 - 1e-12), 0.1), bl.a_iso_ball(k0, 0.1)
        assert lo == pytest.approx(hi, rel=1e-3)
    assert bl.a_iso_ball(4.0, 5.0) == bl.A_ISO_MAX
    assert bl.a_iso_ball(9.0, 0.2) == bl.a_iso_ball(4.0, 0.2)          # κ > 4 taken as 4
    with pytest.raises(ValueError):
        bl.a_iso_ball(0.05, 0.1)


def test_seed_single_points():
    assert round(bl.l10h(23649.0, 2931.0, 7000.0), 1) == 1250.7
    assert round(bl.l10h(14418.0, 2931.0, 7000.0), 1) == 283.4     # C derived from this point


def test_duty_cycle_constant_load_equals_single_point():
    """A constant condition is its own equivalent, exactly; and with a_ISO = 1 (κ, e_C chosen)
    nothing else: two conditions by Miner over revolutions equal the equivalent-load life."""
    P, n = bl.duty_cycle([3000.0] * 4, [2000.0] * 4)
    assert (P, n) == pytest.approx((2000.0, 3000.0), rel=1e-15)
    rpm, load = np.array([2000.0, 6000.0]), np.array([500.0, 4500.0])
    Peq, neq = bl.duty_cycle(rpm, load)
    assert Peq == pytest.approx(((2000 * 500 ** 3 + 6000 * 4500 ** 3) / 8000) ** (1 / 3))
    L_eq = bl.l10h(14418.0, Peq, neq)
    L_sp = bl.modified_life_spectrum(14418.0, 1e-30, rpm, load, kappa=1.0, e_c=0.0)
    a0 = bl.a_iso_ball(1.0, 0.0)            # e_C = 0: a_ISO at its floor, the same per condition
    assert L_sp == pytest.approx(a0 * L_eq, rel=1e-12)


def test_seed_key_and_gear_checks():
    doc = drive.load()
    dr = drive.drive(doc)
    assert dr.alpha_rad_s2 == pytest.approx((9500 - 1200) * 2 * math.pi / 60, rel=1e-15)
    M = drive.torque_Nmm(432.229 + 0.363, dr)
    assert round(M / 1e3, 3) == 0.376
    k = key.check("gear", M, 17.0, doc["keys"])
    assert round(k.length_needed_seed_mm, 3) == 0.126
    assert k.sigma_d_MPa == pytest.approx(120.0, rel=1e-15)
    g = gear.check(375.0, 9500.0, doc["gear_pair"])          # Inventor's input 0.375 N·m
    assert (round(g.F_t_N, 3), round(g.F_r_N, 3), round(g.F_n_N, 3), round(g.v_m_s, 3)) == \
        (16.860, 6.690, 18.139, 32.830)
    assert round(g.safety, 2) == 33.93       # F_all is derived from this value (see the file)
