"""The typed load model (``shaftfe.model.loads``): reading, the torque-path rule, speed laws and
load-case factors, and the parts' forces at their centroids (statics of the actions)."""

import dataclasses

import pytest

from shaftfe.errors import InputError
from shaftfe.model import loads as ld
from shaftfe.model.loader import load_variant
from shaftfe.model.validate import validate_variant
from shaftfe.util.units import REF_RPM


@pytest.fixture(scope="module")
def x2():
    return load_variant("x2_57")


def _load(**kw):
    base = dict(name="t", kind="torque", x_mm=50.0, value=376.0)
    base.update(kw)
    base["band_mm"] = (base["x_mm"] - 1.0, base["x_mm"] + 1.0)
    return ld.Load(**base)


def test_parts_act_at_their_centroids_seed_placement_at_the_seat(x2):
    # the action's moment about the seat centre is (x_c - x_seat) e_x × F: exact statics
    acts = ld.attachment_actions(x2)
    seed = ld.attachment_actions(x2, seed_placement=True)
    for a, s in zip(acts, seed, strict=True):
        part = x2.attachment(a.name)
        dx = part.x_centroid_mm - part.seat_center_mm
        assert a.F_N == s.F_N and a.scales_with == "rpm2" and a.ref_rpm == REF_RPM
        assert a.M_Nmm == pytest.approx((0.0, -dx * a.F_N[2], dx * a.F_N[1]), abs=1e-9)
        assert s.M_Nmm == (0.0, 0.0, 0.0) and s.pressed_half and not a.pressed_half
    cw1 = next(a for a in acts if a.name == "counterweight_1")
    assert cw1.M_Nmm[2] != 0.0          # its centroid lies 15 mm outboard of its seat centre


def test_a_torque_must_have_a_path(x2):
    v = dataclasses.replace(x2, loads=(_load(),))
    with pytest.raises(InputError, match="rotation about the shaft axis free"):
        validate_variant(v)
    # balanced by a second torque of the same law: accepted
    validate_variant(dataclasses.replace(x2, loads=(_load(), _load(name="u", value=-376.0,
                                                                   x_mm=100.0))))
    # balanced only across two laws: the sum moves with speed, refused
    with pytest.raises(InputError, match="'rpm2'"):
        validate_variant(dataclasses.replace(x2, loads=(
            _load(), _load(name="u", value=-376.0, scales_with="rpm2"))))
    # a support that holds torsion reacts it
    b0 = dataclasses.replace(x2.bearings[0], holds_torsion=True)
    validate_variant(dataclasses.replace(x2, loads=(_load(),),
                                         bearings=(b0, *x2.bearings[1:])))


def test_speed_laws_and_case_factors():
    f = _load(kind="force", value=10.0, scales_with="rpm2", ref_rpm=5000.0)
    c = _load(kind="force", value=10.0, scales_with="torque_Nm", channel_ref=0.5)
    case = ld.LoadCase("x", 10_000.0, factors=(("t", 1.5),), channels=(("torque_Nm", 2.0),))
    assert case.factor(f) == 1.5 * 4.0                       # (10000 / 5000)² exactly
    assert case.factor(c) == 1.5 * 4.0                       # 2.0 / 0.5 exactly
    assert ld.LoadCase("y", 0.0).factor(c) == 1.0            # a channel not given: its ref


def test_loads_read_from_the_file_and_set():
    # geometry/examples/x2_57_driven.toml (the file docs/VARIANTS.md shows): read, set, refused
    p = ld_path("x2_57_driven.toml")
    v = load_variant(p)
    assert [x.name for x in v.loads] == ["mesh_pump", "pump", "mesh_run_up", "inertia_cw2"]
    assert v.loads[0].gear.pitch_diameter_mm == 66.0 and v.loads[0].band_mm == (6.0, 16.0)
    assert ld.channels(v) == ("alpha_rad_s2",)
    run_up = v.load_case("run_up")
    assert run_up.factor(v.loads[2]) == 1.0 and run_up.factor(v.loads[0]) == (9500 / 9500) ** 2
    w = load_variant(p, {"loads.pump.T_Nmm": -80.0, "loads.mesh_pump.T_Nmm": 80.0})
    assert w.loads[1].value == -80.0 and w.content_hash != v.content_hash
    with pytest.raises(InputError, match="rotation about the shaft axis free"):
        load_variant(p, {"loads.pump.T_Nmm": -80.0})


def test_the_driven_example_variant_carries_the_drive_loads():
    # geometry/examples/x2_57_driven.toml: x2_57 + the drive loads, named by itself
    v = load_variant(ld_path("x2_57_driven.toml"))
    base = load_variant("x2_57")
    assert v.name == "x2_57_driven" and v.attachments == base.attachments
    acts, _ = ld.actions(v)
    for law in ("rpm2", "alpha_rad_s2"):              # the torques balance per law exactly
        assert sum(a.torque_Nmm for a in acts if a.scales_with == law) == 0.0
    assert v.provenance.source["loads.mesh_pump.T_Nmm"] == "reconstructed"
    assert v.with_seed_load_case().loads == ()


def test_angular_acceleration_channel_of_a_linear_run_up():
    # rpm rising linearly 1200 → 9500 in 1 s (the seed's run-up): dω/dt = 869.2 rad/s²
    # (seed 000 §8.2.2); np.gradient is exact on a linear function: round-off only
    import numpy as np

    from shaftfe.fatigue.history import from_rpm
    h = from_rpm(np.linspace(1200.0, 9500.0, 101), sample_rate_hz=100.0)
    a = h.channel("alpha_rad_s2")
    np.testing.assert_allclose(a, (9500.0 - 1200.0) * 2 * np.pi / 60.0, rtol=1e-12)
    assert abs(a[0] - 869.2) < 0.05                   # the seed's rounded figure


def ld_path(name: str):
    from shaftfe.util.paths import GEOMETRY_DIR
    return GEOMETRY_DIR / "examples" / name
