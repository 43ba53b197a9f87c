"""A keyway with a bottom radius (DIN 6885-1's r1, ``Keyway.bottom_radius_mm``).

* Its peak is a stress, not a value of the mesh: on the keyed Ø20 bar (r1 = 1 mm) in
  four-point bending, the zoned solve at ``coarse`` against the full 3D model at ``fine`` (the
  issue's reference for a 3D zone, #32: committed by benchmarks/bench_keyway_radius.py in
  reports/benchmarks/keyway_radius.json), within the error that benchmark measured at
  ``coarse``, and where that benchmark found it. This is a CONSISTENCY check (the same finite
  elements, a finer mesh of the uncut bar), not an independent validation of the keyway's
  stress: no published keyseat chart at these proportions was at hand.
* The slot's closed-form volume and faces against OpenCASCADE's integration (no mesh): an
  independent reference.
* The plan and the marks: a rounded keyway is no ``SharpKeywayEdge``; a sharp keyway's plan
  hashes as before the radius existed (its meshes stay in the cache).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from shaftfe.model.examples import keyed_bar

BENCH = Path(__file__).resolve().parents[2] / "reports" / "benchmarks" / "keyway_radius.json"


def _bench(rho: float, load: str, model: str, level: str) -> dict:
    rows = json.loads(BENCH.read_text(encoding="utf-8"))["bar"]
    return next(r for r in rows if (r["rho_mm"], r["load"], r["model"], r["level"])
                == (rho, load, model, level))


# the coarse level's error on the bar's keyway peak (r1 1 mm), zoned, against the full 3D model
# at fine: measured −2.65 % in bending (reports/benchmarks/keyway_radius.md), bound 4 %
BOUND = 0.04


def test_a_rounded_keyways_peak_is_a_stress_near_the_full_3d_fine_model(cache):
    """The bar with r1 = 1 mm (r1/d = 0.05: cheap to mesh), bending, zoned, coarse: von Mises
    within BOUND of the full 3D model at ``fine`` (the benchmark's reference row; the sharp
    slot reads −31 % of the r1 0.25 mm reference there: a peak of the mesh). At this radius the
    bottom fillet is no longer the hot spot: the peak sits on the slot's rim at the surface
    (r = 10), over a round end (x 72 … 75 or 85 … 88), where the benchmark's every level put
    it."""
    from shaftfe.static.model import StaticOptions
    from shaftfe.zoned.solve import solve_zoned
    ref = _bench(1.0, "bending", "solid", "fine")["von_mises_MPa"]
    measured = _bench(1.0, "bending", "zoned", "coarse")["von_mises_MPa"] / ref - 1.0
    assert abs(measured) < BOUND                    # the bound holds what was measured
    z = solve_zoned(keyed_bar("bending", 1.0), 1000.0,
                    StaticOptions(level="coarse", rigid_supports=True, spin_softening=False),
                    cache_dir=cache)
    p = {q.region: q for q in z.cases[0].peaks}["keyway:bar:0"]
    assert p.von_mises_MPa == pytest.approx(ref, rel=BOUND)
    x, r = p.xyz_mm[0], math.hypot(*p.xyz_mm[1:])
    assert r >= 9.8
    assert 72.0 - 1e-6 <= x <= 75.0 or 85.0 <= x <= 88.0 + 1e-6


def test_a_rounded_keyway_is_not_marked_sharp_and_a_sharp_one_keeps_its_key():
    from shaftfe.solid.plan import plan_payload, prepare, sharp_keyway_edges
    sharp, round_ = keyed_bar("bending"), keyed_bar("bending", 0.25)
    assert [e.region for e in sharp_keyway_edges(sharp)] == ["keyway:bar:0"]
    assert sharp_keyway_edges(round_) == ()
    # the sharp slot's payload has no radius (the mesh keys of every file stay), the round's has
    assert "rho" not in plan_payload(prepare(sharp))["slots"][0]
    assert plan_payload(prepare(round_))["slots"][0]["rho"] == 0.25


@pytest.mark.parametrize("rho", [0.0, 0.25, 1.0])
def test_the_closed_forms_of_a_rounded_keyway_against_opencascade(rho):
    """``solid.exact.slot_volume`` and ``slot_area`` (closed forms and a 1D quadrature) against
    OpenCASCADE's own integration over the exact CAD solid that the mesher cuts (the slot tool of
    ``solid.occ``, no mesh): a Ø17 × 30 bar with a 5 × 3 × 8 keyway, sharp and rounded. Bounds:
    OCC's own integration, measured within 1.2e-6 (sharp) and 4.3e-6 (rounded) of the closed
    forms on the chip's volume and within 1.6e-6 on the faces' area, neither growing with ρ:
    1e-5. The radius moves both far more: at ρ 0.25 the spandrels are 4.5e-3 of the chip, the
    faces change by 2.4 % (a torus of major radius a in place of a − ρ: by 0.7 %)."""
    import math as m

    import gmsh

    from shaftfe.solid.exact import slot_area, slot_volume
    from shaftfe.solid.mesh import GMSH_LOCK
    from shaftfe.solid.occ import _slot_tool
    from shaftfe.solid.plan import Slot
    k = Slot("s", 0, 8.5, 5.0, 3.0, 8.0, 15.0, m.radians(30.0), rho)
    with GMSH_LOCK:
        gmsh.initialize(readConfigFiles=False, interruptible=False)
        try:
            gmsh.option.setNumber("General.Terminal", 0)
            occ = gmsh.model.occ
            bar = occ.addCylinder(0.0, 0.0, 0.0, 30.0, 0.0, 0.0, 8.5)
            bar2 = occ.addCylinder(0.0, 0.0, 0.0, 30.0, 0.0, 0.0, 8.5)
            (chip,), _ = occ.intersect([(3, bar2)], [(3, _slot_tool(occ, k))])
            removed = occ.getMass(3, chip[1])            # the material the slot takes
            (vol,), _ = occ.cut([(3, bar)], [(3, _slot_tool(occ, k))])
            occ.remove([chip], recursive=True)
            occ.synchronize()
            faces = [s for _, s in gmsh.model.getBoundary([vol], oriented=False)]
            outer = [s for s in faces if gmsh.model.getType(2, s) == "Cylinder"
                     and gmsh.model.getBoundingBox(2, s)[3] - gmsh.model.getBoundingBox(2, s)[0]
                     > 29.0] + [s for s in faces if gmsh.model.getType(2, s) == "Plane" and
                                gmsh.model.getBoundingBox(2, s)[4] > 8.0
                                and gmsh.model.getBoundingBox(2, s)[1] < -8.0]
            assert len(outer) == 3                          # the bar's cylinder and its ends
            slot_faces = sum(occ.getMass(2, s) for s in faces if s not in outer)
        finally:
            gmsh.finalize()
    assert removed == pytest.approx(slot_volume(k), rel=1e-5)
    assert slot_faces == pytest.approx(slot_area(k), rel=1e-5)


def test_the_fillets_dofs_estimate_covers_every_measured_bar():
    """``keyway_fillet_dofs`` (P / (k_fillet² ρ) × KEYWAY_DOFS_PER_CELL) against the keyed bar's
    measured dofs at every level and both radii (the benchmark's full 3D rows): never below
    them (the estimate guards the memory), and within 2 × (it is no loose bound that would
    refuse what runs): an inequality on measured numbers."""
    from shaftfe.solid.levels import LEVELS
    from shaftfe.solid.mesh import keyway_fillet_dofs
    from shaftfe.solid.plan import prepare
    rows = [r for r in json.loads(BENCH.read_text(encoding="utf-8"))["bar"]
            if r["model"] == "solid"]
    assert len(rows) == 12
    for r in rows:
        est = keyway_fillet_dofs(prepare(keyed_bar(r["load"], r["rho_mm"])), LEVELS[r["level"]])
        assert r["dofs"] <= est <= 2.0 * r["dofs"], r



def test_the_guard_lets_the_measured_reference_run():
    """``KEYWAY_DOFS_MAX`` refuses what would not finish, not what was measured to finish: the
    keyed bar's reference row (r1 0.25 mm at fine, 1.44 million dofs, 17.5 GiB; bench_keyway_
    radius) passes the plan's guard, and x2_57 with r1 0.25 mm at fine stays refused."""
    from shaftfe.errors import InputError
    from shaftfe.model.examples import keyed_bar
    from shaftfe.model.loader import load_variant
    from shaftfe.solid.mesh import mesh_plan
    for kind in ("bending", "torsion"):
        mesh_plan(keyed_bar(kind, 0.25), "fine")          # no refusal
    x2 = load_variant("x2_57", ["segments.gear_seat.keyways.0.bottom_radius_mm=0.25",
                                "segments.cw2_seat.keyways.0.bottom_radius_mm=0.25"])
    with pytest.raises(InputError, match="bottom_radius_mm"):
        mesh_plan(x2, "fine")
