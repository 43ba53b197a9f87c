"""Conical (tapered) segments (issue #33), each path against an independent reference.

* Mass properties of a frustum against its closed forms (Pappus; the polar moment
  π ρ L (r0⁴ + r0³ r1 + r0² r1² + r0 r1³ + r1⁴)/10).
* The meshed solid's volume and face groups (the cone ``taper:<seg>``: π (r0 + r1) × slant)
  against the exact geometry.
* The beam on a shaft with a cone against the unit-load integral with the exact D(x)
  (Timoshenko & Gere; shear by Cowper's κ), as tests/validation/test_beam.py does for steps.
* The rules: nothing cut into a cone, no seat on it, no fillet against it.
"""

from __future__ import annotations

import dataclasses
import itertools
import math

import numpy as np
import pytest
from scipy.integrate import quad

from shaftfe.beam.elements import section_properties
from shaftfe.beam.model import TAPER_STEP, build_model
from shaftfe.beam.solve import solve
from shaftfe.errors import InputError
from shaftfe.model.examples import four_step_shaft
from shaftfe.model.loads import Load
from shaftfe.model.variant import Bearing, Material, Segment, Variant
from shaftfe.solid.plan import prepare

E, NU = 210_000.0, 0.3
G = E / (2 * (1 + NU))
STEEL = Material("steel", E, NU, 7.85e-9, 540.0, 800.0)
RIGID = ((0.0, 0.0), (0.0, 0.0))


def _cone_shaft(d0=15.0, d1=22.0, loads=()) -> Variant:
    """Ø15 × 30 | cone Ø15 → Ø22 × 20 | Ø22 × 40, rigid point supports at x = 5 and 85."""
    segs = (Segment("a", 0.0, 30.0, d0), Segment("cone", 30.0, 20.0, d0, diameter_right_mm=d1),
            Segment("b", 50.0, 40.0, d1))
    brg = tuple(Bearing(f"b{i}", "test", x, 0.0, 1e4, 1e4, RIGID, axial=i == 0)
                for i, x in enumerate((5.0, 85.0)))
    return Variant("cone", "test", segs, brg, (), STEEL, 0.0, loads=tuple(loads))


def test_frustum_mass_properties_against_closed_forms():
    """The shaft body of one cone Ø15 → Ø22 × 20 mm: mass ρ π L (r0² + r0 r1 + r1²)/3, its
    centroid L (r0² + 2 r0 r1 + 3 r1²)/(4 (r0² + r0 r1 + r1²)) from the small end, its polar
    moment ρ π L (r0⁴ + r0³ r1 + r0² r1² + r0 r1³ + r1⁴)/10 (the quadrature is exact for
    these polynomials: round-off, 1e-12)."""
    from shaftfe.model.mass import shaft_body_properties
    v = dataclasses.replace(_cone_shaft(), segments=(
        Segment("cone", 0.0, 20.0, 15.0, diameter_right_mm=22.0),), bearings=())
    rho = STEEL.density_t_mm3 * 1e3
    r0, r1, L = 7.5, 11.0, 20.0
    q = r0 * r0 + r0 * r1 + r1 * r1
    m, mx, _, _, jp, _ = shaft_body_properties(v)
    assert m == pytest.approx(rho * math.pi * L * q / 3.0, rel=1e-12)
    assert mx / m == pytest.approx(L * (r0 ** 2 + 2 * r0 * r1 + 3 * r1 ** 2) / (4 * q),
                                   rel=1e-12)
    assert jp == pytest.approx(rho * math.pi * L * (r0 ** 4 + r0 ** 3 * r1 + r0 ** 2 * r1 ** 2
                                                    + r0 * r1 ** 3 + r1 ** 4) / 10.0,
                               rel=1e-12)


def test_taper_mesh_against_exact_geometry(tmp_path):
    """The four-step shaft with its Ø15 a cone to Ø17 (no step at x = 20), coarse 3D mesh:
    volume and every face group, the cone's included, against the exact values (the
    tolerances of tests/validation/test_mesh_geometry.py: P2 interpolation of curved faces)."""
    from test_mesh_geometry import _check  # (pytest puts this folder on sys.path)

    from shaftfe.solid import features as F
    from shaftfe.solid.mesh import build_mesh
    v = four_step_shaft(taper=True, chamfers=True)
    sm = build_mesh(v, "coarse", cache_dir=tmp_path)
    assert "taper:a" in sm.groups and "shoulder:a" not in sm.groups
    _check(sm, v)
    by = F.by_region(F.features(prepare(v)))       # the cone reads back as its feature
    assert by["taper:a"].kind == F.kind_of("taper:a") == "taper"
    assert by["taper:a"].x_mm == (0.0, 20.0)


def test_beam_on_a_cone_against_the_unit_load_integral():
    """Simply supported shaft with a cone, a point load at x = 25 (beside the cone): the
    deflection under it against δ = ∫ M m/(E I) dx + ∫ V v/(κ G A) dx with the exact D(x),
    by scipy quad. The beam cuts the cone into elements whose diameters differ by at most
    TAPER_STEP, each with its midpoint's section: the midpoint rule on 1/I ∝ D⁻⁴ errs by at
    most (20/24) (ΔD/D)² per element, all one way: the bound below."""
    xa, xb, xp, P = 5.0, 85.0, 25.0, 2000.0
    v = _cone_shaft(loads=[Load("p", "force", xp, (xp, xp), P, 0.0)])
    m = build_model(v, rigid_supports=True)
    r = solve(m, 0.0)[0]
    Ra = P * (xb - xp) / (xb - xa)

    def M(x):
        return Ra * (x - xa) - P * max(x - xp, 0.0)

    def V(x):
        return Ra - (P if x > xp else 0.0)

    def D(x):
        return 15.0 + 7.0 * min(max((x - 30.0) / 20.0, 0.0), 1.0)

    def flex(x):
        sec = section_properties(np.array([D(x)]), NU, np.array([0.0]))
        return (M(x) ** 2 / (E * sec.I[0]) + V(x) ** 2 / (sec.kappa[0] * G * sec.A[0])) / P

    delta = sum(quad(flex, lo, hi, epsabs=0, epsrel=1e-13)[0]
                for lo, hi in itertools.pairwise([xa, xp, 30.0, 50.0, xb]))
    got = r.uy[int(np.argmin(np.abs(m.x - xp)))]
    bound = 20.0 / 24.0 * TAPER_STEP ** 2         # the midpoint rule's, see above
    assert got == pytest.approx(delta, rel=bound)
    assert abs(got / delta - 1.0) > 1e-12          # (the cone is approximated, not exact)


def test_rules_of_a_cone():
    """Refused, each naming its field: a keyway in a cone, a chamfer on it, a fillet at a step
    beside it, a bearing on it, a load band on it."""
    from shaftfe.model.variant import Keyway
    v = _cone_shaft()
    cone = v.segments[1]
    for seg, field in ((dataclasses.replace(cone, keyways=(Keyway(5, 3, 8, 40.0),)),
                        "keyways"),
                       (dataclasses.replace(cone, chamfer_right_mm=0.5), "chamfer_right_mm")):
        with pytest.raises(InputError, match=field):
            prepare(dataclasses.replace(v, segments=(v.segments[0], seg, v.segments[2])))
    step = dataclasses.replace(v, segments=(v.segments[0], dataclasses.replace(
        cone, diameter_right_mm=20.0, fillet_mm=0.5), v.segments[2]))
    with pytest.raises(InputError, match=r"segments\[1\].fillet_mm"):
        prepare(step)
    on = dataclasses.replace(v, bearings=(v.bearings[0], dataclasses.replace(
        v.bearings[1], x_center_mm=45.0)))
    with pytest.raises(InputError, match="conical segment 'cone'"):
        prepare(on)
    band = dataclasses.replace(v, loads=(Load("p", "force", 40.0, (38.0, 42.0), 1.0, 0.0),))
    with pytest.raises(InputError, match=r"loads\[0\]"):
        prepare(band)
    # steeper than 30°: Ø15 → Ø40 over 20 mm is 32°
    steep = dataclasses.replace(v, segments=(v.segments[0], dataclasses.replace(
        cone, diameter_right_mm=40.0), dataclasses.replace(v.segments[2], diameter_mm=40.0)))
    with pytest.raises(InputError, match="30°"):
        prepare(steep)


def test_a_cones_concave_kink_is_warned():
    """The cone Ø15 → Ø22 meets the Ø15 at x = 30 without a step: a concave kink (a weak
    singularity), warned with its place; its convex end (x = 50) is not."""
    from shaftfe.util.notices import collecting
    v = _cone_shaft()
    v = dataclasses.replace(v, bearings=tuple(dataclasses.replace(b, width_mm=4.0)
                                              for b in v.bearings))
    with collecting(echo=False) as got:
        prepare(v)
    kinks = [n for n in got if n.code == "taper-kink"]
    assert len(kinks) == 1 and "x = 30 mm" in kinks[0].text


def test_the_meridian_carries_the_cone():
    """The axisymmetric model's outline (``axisymmetric.mesh.shaft_geometry``): one straight
    curve ``taper:a`` from (0, 7.5) to (20, 8.5), and no shoulder at x = 20 (exact)."""
    from shaftfe.axisymmetric.mesh import shaft_geometry
    geo = shaft_geometry(prepare(four_step_shaft(taper=True)))
    cone = [c for c in geo.curves if "taper:a" in c.groups]
    assert len(cone) == 1 and cone[0].center is None
    assert (cone[0].start, cone[0].end) == ((0.0, 7.5), (20.0, 8.5))
    assert not any(g.startswith("shoulder:a") for c in geo.curves for g in c.groups)
