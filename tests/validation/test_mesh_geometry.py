"""Validation of the meshed solid against exact geometry (issue 3).

References: the exact volume (cylinders πr²L + fillet spandrel rings by Pappus − keyways by
∫∫ of the cut height over the stadium − hex socket (√3/2)s²d) and the exact face areas from
``shaftfe.solid.plan``; a mesh that reproduces them places every named face where it belongs.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from shaftfe.model.examples import four_step_shaft
from shaftfe.model.variant import Variant


def small_shaft(*, keyway_angle=0.0, load_angle=30.0, hex_end="right",
                full_fillet=False, keyway_radius=0.0) -> Variant:
    """Ø15 | Ø17 (1 mm fillet, 5×3×14 keyway) | Ø22 (fillet, bearing) | Ø17 (seat)."""
    return four_step_shaft(name="small", description="validation shaft",
                           keyway_angle=keyway_angle, cw_angle=load_angle, hub_angle=200.0,
                           hex_end=hex_end, fillet_c=2.5 if full_fillet else 1.0,  # 2.5: whole step
                           keyway_radius=keyway_radius)


def _measure(sm):
    from skfem import Basis, ElementTetP2, FacetBasis, Functional
    one = Functional(lambda w: 1.0 + 0.0 * w.x[0])
    vol = float(one.assemble(Basis(sm.mesh, ElementTetP2())))
    areas = {g: float(one.assemble(FacetBasis(sm.mesh, ElementTetP2(), facets=f)))
             for g, f in sm.mesh.boundaries.items()}
    return vol, areas


# mesh: P2 tets/facets interpolate the curved surfaces; measured volume error ≤ 5.2e-4 and
# face-area error ≤ 2.6e-3 (end faces with the hex socket, x2_57 coarse) over the meshes below
def _check(sm, variant, vol_tol=2e-3, area_tol=5e-3):
    from shaftfe.solid.exact import analytic_volume, expected_areas
    vol, areas = _measure(sm)
    exp = expected_areas(variant)
    assert set(areas) == set(exp)
    assert vol == pytest.approx(analytic_volume(variant), rel=vol_tol)     # mesh (see above)
    for g, a in areas.items():
        assert a == pytest.approx(exp[g], rel=area_tol), g                 # mesh (see above)


def test_default_level_volume_and_areas(tmp_path):
    """Default level, small shaft: volume within 0.2 % of the exact volume, every face group
    within 0.5 % of its exact area, minSICN > Q_CURVED (the P2 repair threshold, see
    tests/test_mesh.py::test_quality_and_positive_jacobians)."""
    from shaftfe.solid.mesh import Q_CURVED, build_mesh
    v = small_shaft()
    sm = build_mesh(v, "default", cache_dir=tmp_path)
    assert sm.min_quality > Q_CURVED
    _check(sm, v)


def test_keyway_straddling_the_load_plane_with_a_bottom_radius(tmp_path):
    """Keyway at 90° to a 0° load: the split plane y = 0 cuts the slot in two; each seat half
    loses exactly half of the opening (exact: ∫ R dψ over the window, round ends by
    quadrature). The keyway's bottom edges are rounded (r1 = 1 mm on a 5 mm wide keyway: its
    fillet meshed at the coarse level's hot-spot size, cheap at this radius): its faces
    (bottom, walls, the fillet's quarter cylinders and tori, ``solid.exact.slot_area``, which
    tests/validation/test_keyway_radius.py checks against OpenCASCADE) are classified as the
    keyway's and meshed where they are (the sharp keyway's closed form reads them 10.6 %
    high: outside the bound; the sharp keyway is the default-level test's and x2_57's).
    Coarse level, same tolerances."""
    from shaftfe.solid.exact import expected_areas
    from shaftfe.solid.mesh import build_mesh
    from shaftfe.solid.plan import prepare
    v = small_shaft(keyway_angle=90.0, load_angle=0.0, keyway_radius=1.0)
    assert [k.rho for k in prepare(v).slots] == [1.0]
    exp = expected_areas(v)
    # exact arithmetic: the same closed form on both halves (measured equal)
    assert exp["load:cw:pressed"] == pytest.approx(exp["load:cw:free"], rel=1e-12)
    _check(build_mesh(v, "coarse", cache_dir=tmp_path), v)


def test_hex_left_and_full_height_fillet(tmp_path):
    """Hex socket in the left end, and a fillet as high as its step (ρ = 2.5 mm): no flat
    shoulder annulus remains (no 'shoulder:c' group); volume and areas as above."""
    from shaftfe.solid.mesh import build_mesh
    v = small_shaft(hex_end="left", full_fillet=True)
    sm = build_mesh(v, "coarse", cache_dir=tmp_path)
    assert "shoulder:c" not in sm.groups and "fillet:c" in sm.groups
    _check(sm, v)


def test_load_angle_200_pressed_side(tmp_path):
    """'hub' force at 200°: the pressed half's facet centroids all satisfy (y, z)·e < 0."""
    from shaftfe.solid.mesh import build_mesh
    sm = build_mesh(small_shaft(), "coarse", cache_dir=tmp_path)
    m = sm.mesh
    e = np.array([math.cos(math.radians(200.0)), math.sin(math.radians(200.0))])
    c = m.p[1:, m.facets[:, m.boundaries["load:hub:pressed"]]].mean(axis=1)
    assert np.all(e @ c < 0)


def _real_variant():
    from shaftfe.model.loader import load_variant
    return load_variant("x2_57")        # a loader regression fails here, it is not skipped


@pytest.mark.slow
def test_x2_57_coarse(tmp_path):
    """The real variant x2_57 at coarse: volume within 0.2 %, areas within 0.5 %,
    minSICN > Q_CURVED (the P2 repair threshold), all groups present."""
    from shaftfe.solid.mesh import Q_CURVED, build_mesh
    v = _real_variant()
    sm = build_mesh(v, "coarse", cache_dir=tmp_path)
    assert sm.min_quality > Q_CURVED
    _check(sm, v)
