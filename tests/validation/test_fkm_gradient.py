"""The related stress gradient at a surface point, against closed forms.

A field the elements represent exactly (linear, on P1 tetrahedra) must give its own gradient to
round-off: σ_xx = 100 − 30 (1 − y) on the unit cube has G = 0.3 /mm at the face y = 1. On the
shaft, the 3D fit at the collar fillet is compared with DIN 743-2's closed form for a shoulder
in bending, G' = 2.3 (1 + φ)/r (an approximation of the same quantity; its spread against FE
and photoelastic data is of order 10-20 %, hence the 25 % band)."""

from types import SimpleNamespace

import numpy as np
import pytest

from shaftfe.fatigue.fkm_field import N_NEAR, profile
from shaftfe.fe.pointeval import TetProbe, surface_normal


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
    p = profile(ref, node, TetProbe(ref), case_depth_mm=0.25)
    assert p.G_surface == pytest.approx(0.3, rel=1e-10)
    assert p.case_ratio == pytest.approx((100 - 30 * 0.25) / 100, rel=1e-10)
    assert p.G_case == pytest.approx(30 / (100 - 30 * 0.25), rel=1e-10)


# --- the axisymmetric field's profile (axisymmetric.reference.SurfaceProbe) -------------------

def _axi_probe(mesh, surface, n, u, E, nu, theta):
    """A ``SurfaceProbe`` and a reference-like object (its points) of one harmonic field ``u``
    on ``mesh`` over the angles ``theta``."""
    from shaftfe.axisymmetric.reference import SurfaceProbe
    keep = np.nonzero(~surface.on_axis)[0]
    sol = SimpleNamespace(mesh=mesh, surface=surface,
                          harmonics=[SimpleNamespace(n=n, sym=u, anti=None)],
                          variant=SimpleNamespace(material=SimpleNamespace(E_MPa=E, nu=nu)))
    x, r = mesh.xr[:, surface.nodes[keep]]
    q = theta.size
    xyz = np.stack([np.repeat(x, q), (r[:, None] * np.cos(theta)).ravel(),
                    (r[:, None] * np.sin(theta)).ravel()])
    ref = SimpleNamespace(xyz=xyz, stress_ref=np.full((6, xyz.shape[1]), np.nan))
    return SurfaceProbe(sol, keep, theta), ref, keep


@pytest.mark.parametrize("case", ["tension", "bending", "torsion"])
def test_axisymmetric_profile_of_saint_venant_fields_is_exact(case):
    """Saint-Venant bar (Timoshenko & Goodier, Theory of Elasticity, 3rd ed. 1970, ch. 10-11;
    the field is inside the P2 space, ``test_axisymmetric_exact``): at the surface r = R, θ = 0
    the von Mises stress falls inward as r in bending (σ_xx = k y) and torsion (τ = g r), so
    G = 1/R, and is uniform in tension, G = 0. Round-off bound: the nodal stresses are exact to
    1e-10 of the scale (``test_axisymmetric_exact.ROUNDOFF``), the interpolation and the
    quadratic fit of a linear profile are exact, and the fit's slope over the first element
    (h = 2.9 mm, the outline's edge here) divides that by h/R > 0.5: 1e-8 leaves 50×."""
    from shaftfe.axisymmetric import harmonic as hm
    from shaftfe.axisymmetric import recovery as rc
    from shaftfe.axisymmetric.mesh import AxiLevel, cylinder_geometry, mesh_geometry
    E, nu, R, L = 210000.0, 0.3, 5.0, 40.0
    m = mesh_geometry(cylinder_geometry(R, L), AxiLevel("t", 0.3, 0.3, 0.3), use_cache=False)
    h = hm.assemble(m, E, nu, use_cache=False)
    left, right = m.group_edges("end:left"), m.group_edges("end:right")
    ax = m.axis_nodes()
    a0, a1 = ax[np.argmin(m.xr[0][ax])], ax[np.argmax(m.xr[0][ax])]
    far = int(np.argmax(m.xr[1]))
    n, tr, pins = {"tension": (0, lambda x, r: (100.0, 0, 0), [3 * a0, 3 * far + 2]),
                   "bending": (1, lambda x, r: (10.0 * r, 0, 0), [3 * a0 + 1, 3 * a1 + 1]),
                   "torsion": (0, lambda x, r: (0, 0, 10.0 * r), [3 * a0, 3 * far + 2])}[case]
    H = np.zeros((2, h.ndof))
    H[[0, 1], pins] = 1.0
    f = h.traction_vector(right, tr, n) - h.traction_vector(left, tr, n)
    u = hm.solve(h.K(n), f, h.reduction(n), hard=H).u[:, 0]
    S = rc.Surface(m)
    probe, ref, keep = _axi_probe(m, S, n, u, E, nu, np.array([0.0, 0.5 * np.pi]))
    x, r = m.xr[:, S.nodes[keep]]
    j = int(np.argmin(np.abs(x - 0.5 * L) + np.abs(r - R)))     # mid-length, on the surface
    nrm, _ = probe.normal(2 * j)
    assert nrm == pytest.approx([0.0, -1.0, 0.0], abs=1e-12)    # θ = 0: inward is −y
    assert probe.normal(2 * j + 1)[0] == pytest.approx([0.0, 0.0, -1.0], abs=1e-12)
    p = profile(ref, 2 * j, probe, case_depth_mm=1.0)
    # the profile was sampled and fitted (G = 0 in tension is the field's, not a fallback)
    assert p.depths_mm.size >= N_NEAR + 1 and np.isfinite(p.fit_residual)
    assert p.von_mises[0] == pytest.approx(100.0 if case == "tension" else (
        10.0 * R * (3 ** 0.5 if case == "torsion" else 1.0)), rel=1e-8)
    want = 0.0 if case == "tension" else 1.0 / R
    assert p.G_surface == pytest.approx(want, abs=1e-8)
    assert p.case_ratio == pytest.approx(1.0 if case == "tension" else (R - 1.0) / R, rel=1e-8)


@pytest.mark.parametrize("load", ["bending", "torsion"])
def test_axisymmetric_shoulder_gradient_against_din743(load):
    """A stepped bar D 22 / d 17 / r 0.6 (x2_57's span fillets) at the Kt tables' mesh
    (``axisymmetric.kt.solve_bar``), the fillet's hot spot: G against DIN 743-2 (2012), the
    related gradient of a shoulder, G' = 2.3 (1 + φ)/r in bending, 1.15/r in torsion
    (``din743.gradient_shoulder``), an empirical fit whose spread against FE and photoelastic
    data is of order 10-20 %: a 25 % band (it catches a wrong normal, a wrong depth scale or
    a surface value from another field, each a factor of order 2 or a sign). Measured: bending
    +7.3 %, torsion −11.2 % (refine 0); one and two uniform refinements give bending +14.9 /
    +18.4 % and torsion −9.2 / −8.1 %: G converges at first order (the P2 stress's
    derivative), to about 5.1 and 1.78 /mm."""
    from shaftfe.axisymmetric.kt import solve_bar
    from shaftfe.fatigue.din743 import gradient_shoulder
    from shaftfe.fatigue.kernels import von_mises
    D, d, rho = 22.0, 17.0, 0.6
    b = solve_bar(D, d, rho)
    probe, ref, keep = _axi_probe(b.mesh, b.surface, b.harmonic[load], b.disp[load], b.E,
                                  b.nu, np.array([0.0]))
    fil = b.surface.nodes[b.fillet]
    x, r = b.mesh.xr[:, fil]
    s, _ = probe.field.at(np.stack([x, r, 0.0 * x]))
    j = int(np.searchsorted(b.surface.nodes[keep], fil[np.argmax(von_mises(s.T))]))
    G = profile(ref, j, probe, None).G_surface
    assert G == pytest.approx(gradient_shoulder(d, D, rho, load), rel=0.25)
