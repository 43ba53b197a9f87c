"""The axisymmetric solution at arbitrary 3D points: the global field a 3D submodel reads on its
cut faces (``shaftfe.zoned``) and compares its stresses with.

A point (x, y, z) is (x, r, θ) with r = √(y² + z²), θ = atan2(z, y) (0 = +y, the convention of
every path). (x, r) is located in the meridian mesh's P2 triangles: candidates are the
``N_CANDIDATES`` nearest triangle centroids, the best by barycentric coordinates of the corner
triangle, then two Newton steps on the element's P2 map (curved fillet elements are curved in
the meridian mesh too). The harmonics' amplitudes are interpolated with the P2 shape functions
and synthesised at θ (``recovery.displacement_at``, ``recovery.synthesize_at``). Exact for the
FE field (it is the field), up to the point location's Newton tolerance (1e-12 of the element).
"""

from __future__ import annotations

from functools import cached_property

import numpy as np

from shaftfe.axisymmetric import kernels as kn
from shaftfe.axisymmetric import recovery as rc

N_CANDIDATES = 12
OUTSIDE_TOL = 1e-6        # barycentric: a point this far outside every triangle is "not found"


def element_tree(mesh):
    """A k-d tree of the meridian triangles' corner centroids (build once per mesh)."""
    from scipy.spatial import cKDTree
    X, R = mesh.xr[0][mesh.tri[:3]], mesh.xr[1][mesh.tri[:3]]
    return cKDTree(np.stack([X.mean(0), R.mean(0)], 1))


def locate(mesh, x: np.ndarray, r: np.ndarray, tree=None):
    """(element (k,), ξ (k,), η (k,), found (k,)) of the meridian points (x, r)."""
    X, R = mesh.xr[0][mesh.tri], mesh.xr[1][mesh.tri]                 # (6, ne)
    tree = tree if tree is not None else element_tree(mesh)
    k = min(N_CANDIDATES, mesh.n_elements)
    cand = np.asarray(tree.query(np.stack([x, r], 1), k)[1]).reshape(x.size, k)
    x0, r0 = X[0][cand], R[0][cand]
    a, b = X[1][cand] - x0, X[2][cand] - x0
    c, d = R[1][cand] - r0, R[2][cand] - r0
    det = a * d - b * c
    px, pr = x[:, None] - x0, r[:, None] - r0
    xi = (d * px - b * pr) / det
    eta = (-c * px + a * pr) / det
    worst = np.minimum(np.minimum(xi, eta), 1.0 - xi - eta)
    best = np.argmax(worst, axis=1)
    rows = np.arange(x.size)
    e = cand[rows, best]
    xi, eta = xi[rows, best], eta[rows, best]
    Xe, Re = X[:, e], R[:, e]                                         # (6, k)
    for _ in range(2):                                                # Newton on the P2 map
        N, dN = kn.tri_p2(xi, eta)
        fx = (N * Xe).sum(0) - x
        fr = (N * Re).sum(0) - r
        J11, J12 = (dN[0] * Xe).sum(0), (dN[1] * Xe).sum(0)
        J21, J22 = (dN[0] * Re).sum(0), (dN[1] * Re).sum(0)
        dj = J11 * J22 - J12 * J21
        xi = xi - (J22 * fx - J12 * fr) / dj
        eta = eta - (-J21 * fx + J11 * fr) / dj
    found = np.minimum(np.minimum(xi, eta), 1.0 - xi - eta) >= -OUTSIDE_TOL
    return e, xi, eta, found


def _cylindrical(xyz: np.ndarray):
    xyz = np.asarray(xyz, dtype=float).reshape(3, -1)
    return xyz[0], np.hypot(xyz[1], xyz[2]), np.arctan2(xyz[2], xyz[1])


def _interpolate(mesh, loc, nodal: np.ndarray) -> np.ndarray:
    """P2 interpolation of nodal values (c, n_nodes) at located points → (c, k)."""
    e, xi, eta, _ = loc
    N, _ = kn.tri_p2(xi, eta)                                          # (6, k)
    return np.einsum("ak,cak->ck", N, nodal[:, mesh.tri[:, e]])


def displacement_at(sol, xyz: np.ndarray, loc=None) -> np.ndarray:
    """(3, k) Cartesian displacement (mm) of the solved model ``sol`` (an ``AxiSolution``) at
    the points ``xyz`` (3, k). ``loc``: the points' ``locate`` result, when reused."""
    x, r, th = _cylindrical(xyz)
    loc = loc if loc is not None else locate(sol.mesh, x, r)
    amps = [(h.n, _interpolate(sol.mesh, loc, h.sym.reshape(-1, 3).T),
             None if h.anti is None else _interpolate(sol.mesh, loc, h.anti.reshape(-1, 3).T))
            for h in sol.harmonics]
    return rc.displacement_at(amps, th)


class StressField:
    """The stress of a solved model ``sol`` at any points, with each harmonic's nodal averages
    (``recovery.nodal_average``) and the element tree made once, when first needed: for many
    calls on one solution (the FKM stress profiles of ``axisymmetric.reference.SurfaceProbe``)."""

    def __init__(self, mesh, amplitudes):
        """``mesh``: anything with the meridian mesh's ``xr``, ``tri`` and ``n_elements``;
        ``amplitudes``: [(n, sym (6, n_nodes), anti (6, n_nodes) | None)] per harmonic."""
        self.mesh = mesh
        self.amplitudes = list(amplitudes)

    @cached_property
    def tree(self):
        """The element tree, made on the first ``at`` (storing or reading the field needs
        none: the seed method never asks, and scipy.spatial is then not imported)."""
        return element_tree(self.mesh)

    @classmethod
    def of(cls, sol) -> StressField:
        """The field of a solved model ``sol`` (an ``AxiSolution``)."""
        E, nu = float(sol.variant.material.E_MPa), float(sol.variant.material.nu)
        return cls(sol.mesh, [(h.n, rc.nodal_average(sol.mesh, h.sym, h.n, E, nu),
                               None if h.anti is None else
                               rc.nodal_average(sol.mesh, h.anti, h.n, E, nu))
                              for h in sol.harmonics])

    def at(self, xyz: np.ndarray, loc=None) -> tuple[np.ndarray, np.ndarray]:
        """((6, k) cylindrical stress (xx, rr, θθ, xr, rθ, θx), found mask (k,)) at the points
        (3, k): the amplitudes interpolated and synthesised at θ. σ_xx and von Mises are the
        Cartesian ones (invariant under the rotation about x)."""
        x, r, th = _cylindrical(xyz)
        loc = loc if loc is not None else locate(self.mesh, x, r, self.tree)
        parts = [(n, _interpolate(self.mesh, loc, sym),
                  None if anti is None else _interpolate(self.mesh, loc, anti))
                 for n, sym, anti in self.amplitudes]
        return rc.synthesize_at(parts, th, rc.CYL_SHEAR), loc[3]

