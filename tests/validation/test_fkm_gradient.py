"""The related stress gradient at a surface point, against closed forms.

A field the elements represent exactly (linear, on P1 tetrahedra) must give its own gradient to
round-off: σ_xx = 100 − 30 (1 − y) on the unit cube has G = 0.3 /mm at the face y = 1. On the
shaft, the 3D fit at the collar fillet is compared with DIN 743-2's closed form for a shoulder
in bending, G' = 2.3 (1 + φ)/r (an approximation of the same quantity; its spread against FE
and photoelastic data is of order 10-20 %, hence the 25 % band)."""

from types import SimpleNamespace

import numpy as np
import pytest

from shaftfe.fatigue.fkm_field import profile, surface_normal
from shaftfe.fe.pointeval import centroid_tree


def _cube():
    from skfem import MeshTet
    m = MeshTet.init_tensor(*(np.linspace(0, 1, 6),) * 3)
    x, y = m.p[0], m.p[1]
    s = np.zeros((6, m.p.shape[1]))
    s[0] = 100.0 - 30.0 * (1.0 - y) + 0.0 * x
    return SimpleNamespace(xyz=m.p, cells=m.t.T, face_cells=m.facets[:, m.boundary_facets()].T,
                           stress_ref=s)


def test_linear_field_gradient_is_exact():
    ref = _cube()
    node = int(np.flatnonzero((np.abs(ref.xyz[1] - 1) < 1e-12) & (np.abs(ref.xyz[0] - 0.4) < 1e-12)
                              & (np.abs(ref.xyz[2] - 0.6) < 1e-12))[0])
    d, _h = surface_normal(ref, node)
    assert d == pytest.approx([0.0, -1.0, 0.0], abs=1e-12)
    p = profile(ref, node, centroid_tree(ref.xyz, ref.cells), case_depth_mm=0.25)
    assert p.G_surface == pytest.approx(0.3, rel=1e-10)
    assert p.case_ratio == pytest.approx((100 - 30 * 0.25) / 100, rel=1e-10)
    assert p.G_case == pytest.approx(30 / (100 - 30 * 0.25), rel=1e-10)
