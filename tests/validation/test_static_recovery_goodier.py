"""Stress recovery on a curved surface vs an exact elasticity solution: spherical cavity.

Reference: J. N. Goodier, "Concentration of stress around spherical and cylindrical
inclusions and flaws", J. Appl. Mech. 1 (1933) 39-44 (also Timoshenko & Goodier, Theory of
Elasticity, §136): a spherical cavity in an infinite body under remote uniaxial tension σ0 has
the peak stress σ_max = σ0 (27 − 15ν) / (2 (7 − 5ν)) on its equator (2.045 σ0 for ν = 0.3).

Model: one eighth of a cube of half-width W = 10 a with the cavity at its centre (symmetry
planes x = 0, y = 0, z = 0 held normal), tension σ0 on x = W, P2 tets from Gmsh graded to h ≈
0.1 a on the cavity. The finite cube raises the peak by O((a/W)³) ≈ 0.1 %. The test uses only
the project's stiffness assembly (``fem.elasticity_stiffness``) and stress recovery
(``recovery.nodal_stress``): this is the verification of the surface-recovery method (FINDINGS
pitfall 5), independent of any fit.

Measured (peak σ_xx / σ0 − Goodier): h = 0.2 a (12k dofs) +1.88 %, h = 0.1 a (28k) +0.51 %,
h = 0.05 a (110k) +0.32 % — converging from above towards the finite-cube offset.
"""

from __future__ import annotations

import numpy as np
import pytest

E, NU, A, W, SIGMA0 = 210_000.0, 0.3, 1.0, 10.0, 100.0
KT_GOODIER = (27 - 15 * NU) / (2 * (7 - 5 * NU))


def _mesh(h_near: float, tmp_path):
    import gmsh
    import meshio
    from skfem import MeshTet2

    own = not gmsh.isInitialized()
    if own:
        gmsh.initialize(readConfigFiles=False, interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add("goodier")
        occ = gmsh.model.occ
        box = occ.addBox(0, 0, 0, W, W, W)
        ball = occ.addSphere(0, 0, 0, A)
        occ.cut([(3, box)], [(3, ball)])
        occ.synchronize()
        d = gmsh.model.mesh.field.add("Distance")
        sphere = [t for (dim, t) in gmsh.model.getEntities(2)
                  if abs(np.linalg.norm(gmsh.model.occ.getCenterOfMass(2, t))) < A]
        gmsh.model.mesh.field.setNumbers(d, "SurfacesList", sphere)
        th = gmsh.model.mesh.field.add("Threshold")
        gmsh.model.mesh.field.setNumber(th, "InField", d)
        gmsh.model.mesh.field.setNumber(th, "SizeMin", h_near)
        gmsh.model.mesh.field.setNumber(th, "SizeMax", 2.0)
        gmsh.model.mesh.field.setNumber(th, "DistMin", 0.2 * A)
        gmsh.model.mesh.field.setNumber(th, "DistMax", 6.0 * A)
        gmsh.model.mesh.field.setAsBackgroundMesh(th)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.option.setNumber("Mesh.HighOrderOptimize", 1)
        gmsh.model.addPhysicalGroup(3, [t for _, t in gmsh.model.getEntities(3)])
        gmsh.model.mesh.generate(3)
        path = tmp_path / "goodier.msh"
        gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
        gmsh.write(str(path))
    finally:
        gmsh.model.remove()
        if own:
            gmsh.finalize()
    mm = meshio.read(path)          # meshio reorders Gmsh's tet10 to the VTK order
    t = mm.cells_dict["tetra10"].T
    used = np.unique(t)
    remap = np.full(mm.points.shape[0], -1)
    remap[used] = np.arange(used.size)
    return MeshTet2(np.ascontiguousarray(mm.points[used].T), np.ascontiguousarray(remap[t]))


def _solve(m):
    from scipy.sparse.linalg import spsolve
    from skfem import condense

    from shaftfe.fe import assembly as fem
    from shaftfe.fe.facets import facet_quadrature
    K = fem.elasticity_stiffness(m, E, NU)
    x = m.doflocs
    n = x.shape[1]
    tol = 1e-9     # node selection on the planes x, y, z = 0 and x = W: Gmsh puts them exactly
    fixed = np.concatenate([3 * np.nonzero(np.abs(x[0]) < tol)[0],
                            3 * np.nonzero(np.abs(x[1]) < tol)[0] + 1,
                            3 * np.nonzero(np.abs(x[2]) < tol)[0] + 2])
    bnd = m.boundary_facets()
    right = bnd[np.all(np.abs(m.p[0, m.facets[:, bnd]] - W) < tol, axis=0)]
    fq = facet_quadrature(m, right)
    one = np.ones(fq.dA.shape)
    f = fq.vector_load(np.array([SIGMA0 * one, 0 * one, 0 * one]))      # traction σ0 e_x
    u = np.zeros(3 * n)
    u[np.setdiff1d(np.arange(3 * n), fixed)] = spsolve(*condense(K, f, D=fixed, expand=False))
    return u


@pytest.fixture(scope="module")
def peak(tmp_path_factory):
    from shaftfe.fe import recovery
    m = _mesh(0.1 * A, tmp_path_factory.mktemp("goodier"))
    u = _solve(m)
    s = recovery.nodal_stress(m, u, E, NU)
    x = m.doflocs
    r = np.linalg.norm(x, axis=0)
    on_sphere = np.abs(r - A) < 1e-6      # Gmsh's surface nodes lie on the sphere to ~1e-12
    return float(s[0, on_sphere].max()), m.doflocs.shape[1] * 3


def test_cavity_peak_matches_goodier(peak):
    """Recovered peak σ_xx on the cavity within 1 % of Goodier's 2.045 σ0 (measured +0.51 %
    at h = 0.1 a; the cube adds ~0.1-0.3 %)."""
    smax, _ = peak
    # mesh (h = 0.1 a: measured +0.51 %, converging from above) + the finite cube's O((a/W)³)
    # ≈ 0.1-0.3 % (docstring): 1 % (Goodier's formula evaluated exactly, not the printed 2.045)
    assert smax / SIGMA0 == pytest.approx(KT_GOODIER, rel=0.01)
