"""The 3D static model's loads (issue #31 item 3): every action as a load vector, per pattern.

Cheap checks on the coarse mesh of the test cylinder (tests/test_static.py): the remote load
carries its action's resultant exactly, the seed placement is today's pressure code bit for bit,
a torque is held only by a bearing that declares it, and the twist gauge's reaction is checked.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from shaftfe.errors import SolverError
from shaftfe.fe import assembly as fem
from shaftfe.model import loads as ld
from shaftfe.model.loads import GearGeometry, Load, LoadCase
from shaftfe.static import model as sm
from shaftfe.static.model import StaticOptions
from tests.test_static import cylinder

OPTS = StaticOptions(level="coarse", spin_softening=False)


def _with_loads(v, *loads, cases=()):
    return dataclasses.replace(v, loads=tuple(loads), load_cases=tuple(cases))


LOADS = (
    Load("f", "force", 80.0, (79.0, 81.0), 250.0, 30.0),
    Load("m", "moment", 40.0, (39.0, 41.0), 5.0e3, 120.0),
    Load("ax", "axial_force", 100.0, (99.0, 101.0), -400.0),
    Load("t1", "torque", 30.0, (29.0, 31.0), 1.0e4, scales_with="torque_Nm",
         channel_ref=2.0),
    Load("gear", "gear_mesh", 90.0, (85.0, 95.0), -1.0e4, 200.0, scales_with="torque_Nm",
         channel_ref=2.0, gear=GearGeometry(2.0, 33, 20.0, 15.0, 2.0 * 33 / np.cos(
             np.radians(15.0)))),
    Load("g", "gravity", 60.0, (0.0, 120.0), 9810.0, 270.0),
)


@pytest.fixture(scope="module")
def model(cache):
    # a part whose centroid is 4 mm off its seat centre: a force and a moment
    v = cylinder()
    v = dataclasses.replace(v, attachments=(dataclasses.replace(
        v.attachments[0], x_centroid_mm=64.0),))
    return sm.build_model(_with_loads(v, *LOADS), OPTS, cache_dir=cache)


def test_each_load_vector_carries_its_action_exactly(model):
    """Σ f and Σ (x − x_a) × f of each remote load equal the action's F and M: R Φ = I makes
    Φᵀ Rᵀ [F; M] = [F; M] (round-off of the 6 × 6 solve in ``rigid_rows``: measured ≤ 3e-15
    relative; 1e-10 leaves margin for any BLAS)."""
    m = model.shaft_mesh.mesh
    acts, body = ld.actions(model.variant)
    by_name: dict = {}
    for a in acts:           # a gear mesh is two actions (axial, transverse) at one point
        F0, M0_, _x = by_name.get(a.name, (np.zeros(3), np.zeros(3), a.x_mm))
        by_name[a.name] = (F0 + a.F_N, M0_ + np.asarray(a.M_Nmm), a.x_mm)
    for name, (Fa, Ma, xa) in by_name.items():
        f = model.loads[name]
        F, M0 = sm.resultant(m, f)
        M = M0 - np.cross([xa, 0.0, 0.0], F)                      # about (x_a, 0, 0)
        scale = np.linalg.norm(Fa) + np.linalg.norm(Ma) / 10.0   # N, N·mm / r
        np.testing.assert_allclose(F, Fa, rtol=0, atol=1e-10 * scale, err_msg=name)
        np.testing.assert_allclose(M / 10.0, Ma / 10.0, rtol=0, atol=1e-10 * scale,
                                   err_msg=name)
    # gravity on the shaft's own mass: ρ V g along 270° (−z), V the mesh's volume (the basis
    # functions sum to one: exact up to round-off, 1e-12)
    from skfem import Functional
    vol = Functional(lambda w: 1.0 + 0.0 * w.x[0]).assemble(fem.vector_basis(m))
    mass = model.variant.material.density_t_mm3 * vol
    Fb, _ = sm.resultant(m, model.loads["g:shaft"])
    np.testing.assert_allclose(Fb, [0.0, 0.0, -mass * 9810.0], rtol=1e-12, atol=1e-12)
    # and V is the cylinder's π r² L up to the curved boundary's discretisation (coarse: 0.5 %)
    assert vol == pytest.approx(np.pi * 10.0 ** 2 * 120.0, rel=0.01)
    assert body and body[0].accel_mm_s2[2] == pytest.approx(-9810.0)


def test_patterns_one_per_law_and_the_plain_case(model):
    """One pattern per law (no case factors a load alone here); f = the plain case at REF_RPM:
    rpm² × 1, constant × 1, the channel at its reference × 1."""
    keys = {p.key for p in model.patterns}
    assert keys == {("rpm2", 10000.0), ("constant",), ("torque_Nm", 2.0)}
    # every plain factor at REF_RPM is 1.0: the same sum in the same order, bit for bit
    np.testing.assert_array_equal(model.f, sum(p.f for p in model.patterns))
    # the torques of the channel sum to zero (t1 + gear): no bearing holds torsion, a gauge
    assert model.twist_gauge == "L"               # the axial bearing's seat
    assert sum(1 for b in model.blocks if "θ_x" in b.labels) == 1


def test_case_factors_split_patterns(cache):
    v = _with_loads(cylinder(), *LOADS[:3],
                    cases=(LoadCase("over", 5000.0, (("f", 1.5),)),))
    model = sm.build_model(v, OPTS, cache_dir=cache)
    by = {p.key: p for p in model.patterns}
    assert set(by) == {("rpm2", 10000.0), ("constant",), ("constant", "load", "f")}
    case = v.load_case("over")
    assert by[("constant", "load", "f")].factor(0.0, case) == 1.5
    assert by[("constant",)].factor(0.0, case) == 1.0
    assert by[("rpm2", 10000.0)].factor(0.0, case) == pytest.approx(0.25)


def test_seed_placement_is_todays_pressure_code(cache):
    """--seed-load-case: the parts' vectors are today's ``surface_load`` on the pressed half,
    bit for bit (every seed comparison unchanged)."""
    v = cylinder(angle=30.0)
    v = dataclasses.replace(v, attachments=(dataclasses.replace(
        v.attachments[0], seed_load_case=True, x_centroid_mm=64.0),))
    model = sm.build_model(v, dataclasses.replace(OPTS, seed_load_case=True), cache_dir=cache)
    m = model.shaft_mesh.mesh
    a = v.attachments[0]
    want = fem.surface_load(m, m.boundaries[f"load:{a.name}:pressed"], a.force_N(10000.0),
                            sm._direction(a.angle_deg), "uniform")
    assert np.array_equal(model.loads[a.name], want)
    assert np.array_equal(model.f, want)


def test_torque_held_by_a_declared_bearing(cache):
    """A net torque reacted by the bearing that holds torsion: its reaction is −T (statics
    exact: round-off of the solve, 1e-8 relative) and the other bearing takes none."""
    from shaftfe.static.solve import solve_static
    v = cylinder()
    v = dataclasses.replace(v, attachments=(), bearings=(
        dataclasses.replace(v.bearings[0], holds_torsion=True), v.bearings[1]),
        loads=(Load("t", "torque", 60.0, (59.0, 61.0), 3.0e4),))
    res = solve_static(v, 0.0, OPTS, cache_dir=cache, beam=False)
    b = {r.name: r for r in res.cases[0].bearings}
    assert b["L"].Mx_Nmm == pytest.approx(-3.0e4, rel=1e-8)
    assert b["R"].Mx_Nmm is None
    assert "twist_gauge_torque_rel" not in res.diagnostics


def test_twist_gauge_refuses_a_net_torque(cache):
    """Past the loader's torque-path rule (bypassed here), a net torque on the gauge is a
    SolverError naming the free rotation, not a plausible answer."""
    from shaftfe.static import solve as ss
    v = _with_loads(dataclasses.replace(cylinder(), attachments=()),
                    Load("t", "torque", 60.0, (59.0, 61.0), 3.0e4))
    model = sm.build_model(dataclasses.replace(v, loads=()), OPTS, cache_dir=cache)
    f = sm.remote_load(model.shaft_mesh.mesh, sm.band_facets(model.shaft_mesh.mesh, (59, 61)),
                       (60.0, 0, 0), (0, 0, 0), (3.0e4, 0, 0))
    sol = ss.solve_model(model, f)
    with pytest.raises(SolverError, match="rotation about the shaft axis"):
        ss._twist_gauge_check(model, sol, f)
