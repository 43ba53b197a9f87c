"""Gear-mesh forces of ``shaftfe.model.loads`` against a hand calculation of the nominal forces
at the pitch circle (ISO 6336-1:2019 §5.2, eq. (1)-(3); the same in Shigley/Budynas, 10th ed.,
eq. 13-36 and §13-17: F_t = 2T/d, F_r = F_t tan α_n / cos β, F_a = F_t tan β, d = m_n z / cos β).

Reference values are the closed forms evaluated here by hand (written out), not by the code;
tolerances are round-off of those few operations (1e-12 relative)."""

import math

import pytest

from shaftfe.model.loader import load_variant
from shaftfe.model.loads import GearGeometry, Load, load_actions

RTOL = 1e-12       # a handful of floating-point operations


def test_seed_spur_gear_m2_z33():
    # the seed's driven gear: m 2, z 33, α 20° (seed 000 §8.2), T = 376 N·mm (0.376 N·m)
    # d = 2·33 = 66 mm; F_t = 2·376/66 = 11.393939…; F_r = F_t·tan 20° = 4.14699…
    g = GearGeometry(2.0, 33, 20.0, 0.0, 66.0)
    ft, fr, fa = g.forces(376.0)
    assert ft == pytest.approx(752.0 / 66.0, rel=RTOL)
    assert fr == pytest.approx(752.0 / 66.0 * 0.36397023426620234, rel=RTOL)   # tan 20°
    assert fa == 0.0


def test_helical_gear_forces_and_the_axial_force_moment():
    # m_n 3, z 40, α_n 20°, β 15°: d = 120/cos 15° = 124.2331…, T = 100 N·m
    beta = math.radians(15.0)
    d = 120.0 / 0.9659258262890683                                   # cos 15°
    g = GearGeometry(3.0, 40, 20.0, 15.0, d)
    ft, fr, fa = g.forces(1e5)
    assert ft == pytest.approx(2e5 / d, rel=RTOL)
    assert fr == pytest.approx(2e5 / d * 0.36397023426620234 / 0.9659258262890683, rel=RTOL)
    assert fa == pytest.approx(2e5 / d * 0.2679491924311227, rel=RTOL)       # tan 15°
    # the action at a mesh towards +y (angle 0): contact at (0, r, 0); F_t along +z, F_r along
    # −y, F_a along +x; moments: T about x, and r e_y × F_a e_x = −r F_a e_z
    v = load_variant("x2_57")
    ld = Load("g", "gear_mesh", 11.0, (6.0, 16.0), 1e5, 0.0, gear=g)
    (axial, act), _ = load_actions(ld, v)
    r = d / 2
    # the torque and the axial force turn with the shaft; the rest is fixed in space
    assert axial.frame == "shaft" and act.frame == "space"
    assert axial.F_N == pytest.approx((fa, 0.0, 0.0), rel=RTOL)
    assert axial.M_Nmm == pytest.approx((1e5, 0.0, 0.0), rel=RTOL)
    assert act.F_N == pytest.approx((0.0, -fr, ft), rel=RTOL)
    assert act.M_Nmm[2] == pytest.approx(-r * fa, rel=RTOL)
    assert abs(act.M_Nmm[1]) < 1e-9 * r * fa and act.M_Nmm[0] == 0.0
    assert math.tan(beta) == pytest.approx(0.2679491924311227, rel=RTOL)
