"""Per-pattern stress fields of the axisymmetric and zoned fatigue references (issue #32): a
variant with a load whose law is not rpm² is assessed by the seed method pattern by pattern
(``fatigue.channel_run``), so these references hold each pattern's unsoftened stress, as the
full 3D model's does, and the zoned model is the default for every variant.

The bar: Ø20 × 300 mm, a 6 × 3.5 × 16 keyway at x = 150 (a 3D zone, 122 … 178 mm), bearings at
10 and 290 mm; three patterns: four-point bending (F at 60 and 240 mm, constant), a torque
between the same bands (+T at 60, −T at 240) that follows the channel ``alpha_rad_s2``, and a
force inside the zone (x = 170, ∝ rpm²) that a load case factors on its own (so it is a pattern
of its own, ``model.loads.solve_pattern``).

References:
* closed forms (Saint-Venant, e.g. Roark's Formulas for Stress and Strain, 7th ed., §8.1 and
  table 10.1 case 1): between the load bands the bending moment is M = F · 50 mm, so the
  surface's largest |σ_xx| = 32 M / (π d³); the torsion pattern's surface shear
  √(σ_xy² + σ_xz²) = 16 T / (π d³) at every angle. Checked on the global model's part of the
  surface at x = 95 … 118 mm, at least 1.65 d from the bands' edges and 1.2 d from the slot
  (Saint-Venant's end effects of the bands and the keyway's disturbance decay within about one
  diameter);
* superposition (exact arithmetic up to rounding): Σ_k factor_k × pattern_k is the total
  unsoftened stress at every point, the zone's points included: each submodel's pattern field
  is its own solve on the same factorisation (cut displacement, the pattern's loads inside);
* the patterns are named as the full 3D model names them (its own load patterns, built from the
  same variant on its mesh);
* with spin softening, the reference's patterns are those of the unsoftened solve (the columns
  of a softened solve are softened).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from shaftfe.model.examples import K_SEED, STEEL
from shaftfe.model.loads import Load, LoadCase, law_factor
from shaftfe.model.variant import Bearing, Keyway, Segment, Variant

D = 20.0
F_N = 1000.0
T_NMM = 40_000.0
M_NMM = F_N * 50.0        # between the bands: the support reaction F × (60 − 10) mm


def _bar() -> Variant:
    kw = (Keyway(6.0, 3.5, 16.0, 150.0, 0.0),)
    segs = (Segment("bar", 0.0, 300.0, D, 0.0, keyways=kw),)
    brg = (Bearing("L", "x", 10.0, 10.0, 14_400.0, 10_000.0, K_SEED, axial=True),
           Bearing("R", "x", 290.0, 10.0, 14_400.0, 10_000.0, K_SEED))
    loads = (Load("p1", "force", 60.0, (58.0, 62.0), F_N, 0.0),
             Load("p2", "force", 240.0, (238.0, 242.0), F_N, 0.0),
             Load("t1", "torque", 60.0, (58.0, 62.0), T_NMM, scales_with="alpha_rad_s2",
                  channel_ref=100.0),
             Load("t2", "torque", 240.0, (238.0, 242.0), -T_NMM, scales_with="alpha_rad_s2",
                  channel_ref=100.0),
             Load("p3", "force", 170.0, (168.0, 172.0), 500.0, 90.0, scales_with="rpm2",
                  ref_rpm=10_000.0))
    return Variant("three_patterns", "keyed bar, bending, a torque channel, a load in the zone",
                   segs, brg, (), STEEL, 0.0, loads=loads,
                   load_cases=(LoadCase("over", 10_000.0, (("p3", 1.5),)),))


@pytest.fixture(scope="module")
def refs(cache):
    from shaftfe.fatigue.run import surface_model
    out = {}
    for model in ("axisymmetric", "zoned"):
        opts, solve, reference = surface_model(model, level="coarse", seed_load_case=False,
                                               spin_softening=False)
        out[model] = reference(solve(_bar(), 1000.0, opts, cache_dir=cache))
    return out


def _pattern(ref, law: str):
    p = next(p for p in ref.patterns if p["scales_with"] == law)
    return p, np.asarray(ref.pattern_stress[p["key"]])


@pytest.mark.parametrize("model", ["axisymmetric", "zoned"])
def test_each_pattern_alone_is_the_closed_form_between_the_bands(refs, model):
    """Bending: the largest |σ_xx| of each slice = 32 M / (π d³); torsion: the surface shear
    = 16 T / (π d³) at every angle (module docstring). Bound 1e-5: the axisymmetric P2
    meridian elements carry a stress linear in r exactly, so what is left is the band loads'
    and the keyway's decayed end effects at 1.75 d and 1.6 d (measured: 4.8e-7 bending,
    2e-9 torsion, both models), a property of the mesh, not of the machine's rounding."""
    ref = refs[model]
    assert {p["scales_with"] for p in ref.patterns} == {"constant", "alpha_rad_s2", "rpm2"}
    x = ref.xyz[0]
    r = np.hypot(ref.xyz[1], ref.xyz[2])
    on = (x > 95.0) & (x < 118.0) & (r > 0.999 * D / 2)
    assert on.sum() > 360
    _, sb = _pattern(ref, "constant")
    _, st = _pattern(ref, "alpha_rad_s2")
    bend = 32.0 * M_NMM / (math.pi * D ** 3)
    shear = 16.0 * T_NMM / (math.pi * D ** 3)
    for xs in np.unique(np.round(x[on], 6)):
        sl = on & np.isclose(x, xs)
        assert np.abs(sb[0, sl]).max() == pytest.approx(bend, rel=1e-5)
    tau = np.hypot(st[3, on], st[5, on])
    np.testing.assert_allclose(tau, shear, rtol=1e-5)
    # each pattern alone: the torque adds no σ_xx, the bending no shear about the axis
    assert np.abs(st[0, on]).max() < 1e-5 * shear
    assert np.abs(np.hypot(sb[3, on], sb[5, on])).max() < 1e-5 * bend


@pytest.mark.parametrize("model", ["axisymmetric", "zoned"])
def test_the_patterns_add_up_to_the_unsoftened_field(refs, model):
    """Σ_k factor_k(ref speed) × pattern_k = the reference's own stress at every point, the
    zone's included (exact up to rounding: the same factorisations; 1e-9 of the largest
    stress); the zone's own load is in its pattern there."""
    ref = refs[model]
    if model == "zoned":
        zone = ref.depth_probe.owner > 0
        assert zone.any()
        p3 = np.asarray(ref.pattern_stress["rpm2:10000:load:p3"])
        assert np.abs(p3[:, zone]).max() > 0.01 * np.abs(p3).max()
    total = sum(law_factor(p["scales_with"], ref.ref_rpm, {}, ref_rpm=p["ref_rpm"],
                           channel_ref=p["channel_ref"])
                * np.asarray(ref.pattern_stress[p["key"]]) for p in ref.patterns)
    scale = np.abs(ref.stress_ref).max()
    assert np.abs(total - ref.stress_ref).max() <= 1e-9 * scale


def test_a_softened_reference_holds_the_unsoftened_patterns(cache):
    """With spin softening the reference's patterns are the unsoftened solve's (its columns;
    a softened solve's are softened): the same arrays."""
    from shaftfe.fatigue.run import surface_model, surface_reference
    v = _bar()
    opts, solve, reference = surface_model("zoned", level="coarse", seed_load_case=False,
                                           spin_softening=True)
    soft = surface_reference(lambda o: reference(solve(v, 1000.0, o, cache_dir=cache)), opts)
    _, _, reference2 = surface_model("zoned", level="coarse", seed_load_case=False,
                                     spin_softening=False)
    from dataclasses import replace
    lin = reference2(solve(v, 1000.0, replace(opts, spin_softening=False), cache_dir=cache))
    assert soft.patterns == lin.patterns and soft.pattern_stress.keys() == lin.pattern_stress.keys()
    for k in lin.pattern_stress:
        np.testing.assert_array_equal(soft.pattern_stress[k], lin.pattern_stress[k])


def test_the_patterns_are_named_as_the_full_3d_model_names_them(refs, cache):
    """The same variant through the full 3D model (its ``static.model.LoadPattern`` keys, the
    load case's factored load split off): the same labels and laws."""
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import load_or_solve
    solid = load_or_solve(_bar(), StaticOptions(level="coarse", spin_softening=False), cache)
    want = {(p["key"], p["scales_with"]) for p in solid.patterns}
    assert "rpm2:10000:load:p3" in {k for k, _ in want}
    for model in ("axisymmetric", "zoned"):
        assert {(p["key"], p["scales_with"]) for p in refs[model].patterns} == want


def test_the_patterns_round_trip_through_the_surface_cache(refs, tmp_path):
    """One file an entry (``fatigue.surface_cache``): the patterns and their fields come back
    bit for bit (.npz keeps the arrays unchanged), the probe beside them."""
    from shaftfe.fatigue import surface_cache
    from shaftfe.static.model import StaticOptions
    opts = StaticOptions(level="coarse", spin_softening=False)
    ref = refs["zoned"]
    surface_cache.store(ref, "zoned", _bar(), opts, tmp_path)
    got = surface_cache.load("zoned", _bar(), opts, ref.ref_rpm, tmp_path)
    assert got is not None and got.from_cache
    assert len(list(tmp_path.glob("surface-*.npz"))) == 1
    assert got.patterns == ref.patterns
    for k, v in ref.pattern_stress.items():
        np.testing.assert_array_equal(got.pattern_stress[k], v)
    assert type(got.depth_probe).__name__ == "ZonedProbe"
