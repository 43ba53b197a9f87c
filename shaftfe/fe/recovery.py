"""Stress recovery at the mesh nodes, von Mises and principal stresses, region peaks.

On the traction-free surface the static path replaces these nodal averages by the surface
recovery of ``shaftfe.fe.surface`` (issue #12: the nodal average is biased high there by
+1…+3 % at a fillet, measured against the axisymmetric truth); the averages below remain the
field inside the solid and on loaded or coupled faces.

Method (chosen and why)
-----------------------
Per-element evaluation and nodal averaging, as CalculiX does: the P2 displacement of each
element is differentiated AT THE ELEMENT'S OWN 10 NODES (corner and mid-side), Hooke's law gives
the stress there, and each mesh node takes the plain mean of the values of the elements that
share it. The P2 stress is linear in each element, so the element-node values are the exact
linear extension of the element's stress to its surface; averaging removes the inter-element
jump, which is O(h²) for a smooth solution, so the surface values converge at the rate of the
stress itself and need no global solve. L2 projection (a global mass-matrix solve) smears the
peak over the support of the basis functions and was seen to move non-monotonically on refinement
(FINDINGS pitfall 5); unaveraged corner values blow up on single poor elements. Superconvergent
patch recovery needs interior patches, which do not exist at a surface node. The method is
verified by tests: exact for a linear stress field (pure bending of a cylinder) and against a
beam's M c/I.

Components are stored in the order ``STRESS_COMPONENTS`` = (xx, yy, zz, xy, yz, xz), in MPa.

Singular points
---------------
Points that are singular BY CONSTRUCTION are the edges of the loaded and coupled patches (the
circles and lines where a pressure or the RBE3 seat coupling starts or ends: a traction jump).
Rule: a node is excluded from the filtered peaks if it belongs to an element that has a node ON
such a patch edge (one element layer either side). The unfiltered peak is always reported too.

Limit of the rule: a patch edge that coincides with a fillet's tangent line puts the fillet's
peak inside the excluded element layer, and the filtered peak then grows with refinement as the
layer shrinks (measured on x2_57 before the bearings had chamfers: collar fillet 246 → 474 MPa,
default → fine). The geometry now prevents it: a bearing's coupling face is the ring's contact
band (``Bearing.chamfer_mm`` off each end, ``shaftfe.solid.plan`` rejects a band that reaches into a
fillet), so on x2_57 the two fillets next to the bearings lose no node to the rule and converge
monotonically under refinement of their hot spots (reports/benchmarks/static.md: a three-level
study with observed order ≈ 3 and the default level within ~1 % of the extrapolated value).
``StaticOptions.exclude_mm`` (CLI ``--exclude-mm``) still adds a
band of fixed width around every patch edge for a filtered peak that is mesh-independent where a
patch edge does sit next to a stress raiser.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shaftfe.fe import assembly as fem
from shaftfe.fe.surface import local_peak
from shaftfe.util.units import von_mises

STRESS_COMPONENTS = ("xx", "yy", "zz", "xy", "yz", "xz")


# --------------------------------------------------------------------------- pure kernels



def tensor(s: np.ndarray) -> np.ndarray:
    """(6, n) Voigt → (n, 3, 3) symmetric tensors."""
    xx, yy, zz, xy, yz, xz = s
    return np.stack([np.stack([xx, xy, xz], -1), np.stack([xy, yy, yz], -1),
                     np.stack([xz, yz, zz], -1)], -2)


def principal(s: np.ndarray) -> np.ndarray:
    """Principal stresses (3, n), largest first, of Voigt stresses s (6, n)."""
    return np.linalg.eigvalsh(tensor(np.asarray(s)))[:, ::-1].T


def hooke(grad: np.ndarray, E: float, nu: float) -> np.ndarray:
    """Voigt stress (6, ...) from displacement gradients grad[i, j] = ∂u_i/∂x_j (3, 3, ...)."""
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    tr = grad[0, 0] + grad[1, 1] + grad[2, 2]
    return np.array([lam * tr + 2 * mu * grad[0, 0], lam * tr + 2 * mu * grad[1, 1],
                     lam * tr + 2 * mu * grad[2, 2], mu * (grad[0, 1] + grad[1, 0]),
                     mu * (grad[1, 2] + grad[2, 1]), mu * (grad[0, 2] + grad[2, 0])])


# --------------------------------------------------------------------------- recovery

def node_gradients(mesh):
    """(∂φ at every element's own nodes (ne, nloc, nloc, 3), the node numbers (nloc, ne)): what
    ``element_node_stress`` needs of the mesh, computed once for several fields on it."""
    e = fem.scalar_element(mesh)
    X = np.asarray(e.doflocs, dtype=float).T                # reference node coordinates
    dN, _ = fem.gradients_at(mesh, X)                        # (ne, nq, nloc, 3), q = nodes
    return dN, fem.element_nodes(mesh)                       # nodes (nloc, ne)


def element_node_stress(mesh, u: np.ndarray, E: float, nu: float, grad=None):
    """Stress (6, nloc, ne) of every element evaluated at its own nodes, and the node numbers
    (nloc, ne). ``grad``: ``node_gradients(mesh)``, when it is reused."""
    dN, nodes = grad if grad is not None else node_gradients(mesh)
    U = u.reshape(-1, 3)[nodes.T].transpose(0, 2, 1)          # (ne, 3, nloc): U[e, i, a]
    # grad[e, q, i, j] = Σ_a U[e, i, a] ∂_j φ_a(x_q), as (i, j, e, q) for hooke
    g = np.matmul(U[:, None], dN).transpose(2, 3, 0, 1)
    s = hooke(g, E, nu)                                      # (6, ne, nloc)
    return np.transpose(s, (0, 2, 1)), nodes


def nodal_stress(mesh, u: np.ndarray, E: float, nu: float, grad=None) -> np.ndarray:
    """Averaged nodal stress (6, n_nodes), see the module docstring (``grad``:
    ``node_gradients(mesh)``, when it is reused)."""
    s, nodes = element_node_stress(mesh, u, E, nu, grad)
    return average_to_nodes(mesh, s, nodes)


def average_to_nodes(mesh, s: np.ndarray, nodes: np.ndarray) -> np.ndarray:
    """Plain average over the elements sharing each node of per-element nodal values
    ``s`` (6, nloc, ne) at ``nodes`` (nloc, ne): (6, n_nodes)."""
    n = mesh.doflocs.shape[1]
    cnt = np.bincount(nodes.ravel(), minlength=n).astype(float)
    out = np.empty((6, n))
    for c in range(6):
        out[c] = np.bincount(nodes.ravel(), weights=s[c].ravel(), minlength=n)
    return out / np.maximum(cnt, 1.0)


# --------------------------------------------------------------------------- regions

def patch_edge_nodes(mesh, patch_facets: np.ndarray) -> np.ndarray:
    """Nodes on the boundary curve of a face patch: nodes shared by a patch facet and a
    boundary facet outside the patch."""
    boundary = mesh.boundary_facets()
    outside = np.setdiff1d(boundary, patch_facets)
    return np.intersect1d(fem.face_nodes(mesh, patch_facets), fem.face_nodes(mesh, outside))


def excluded_nodes(mesh, patches: list[np.ndarray], distance_mm: float = 0.0) -> np.ndarray:
    """Nodes of every element that touches a patch edge (the singular-point rule) and, with
    ``distance_mm`` > 0, also every node closer than that to a patch-edge node (a
    mesh-independent band, so that the filtered peak converges under refinement)."""
    edge = np.unique(np.concatenate([patch_edge_nodes(mesh, p) for p in patches])) \
        if patches else np.zeros(0, dtype=np.int64)
    ed = fem.element_nodes(mesh)
    mark = np.zeros(mesh.doflocs.shape[1], dtype=bool)
    mark[edge] = True
    touch = mark[ed].any(axis=0)
    out = np.unique(ed[:, touch])
    if distance_mm > 0 and edge.size:
        from scipy.spatial import cKDTree
        d, _ = cKDTree(mesh.doflocs[:, edge].T).query(mesh.doflocs.T)
        out = np.union1d(out, np.nonzero(d < distance_mm)[0])
    return out


@dataclass(frozen=True)
class RegionPeak:
    """A region's peaks: von Mises and max principal stress, each located on its own (on the
    free surface by the local fit of ``shaftfe.fe.surface.local_peak``, elsewhere the largest
    node). "Filtered": the singular-point rule applied."""
    region: str
    von_mises_MPa: float            # filtered
    xyz_mm: tuple[float, float, float]
    max_principal_MPa: float        # filtered, located on its own
    max_principal_xyz_mm: tuple[float, float, float]
    von_mises_unfiltered_MPa: float
    xyz_unfiltered_mm: tuple[float, float, float]
    n_nodes: int
    n_excluded: int

    def scaled(self, s: float) -> RegionPeak:
        """The same peaks with every stress × s (s ≥ 0: the loads scaled)."""
        from dataclasses import replace
        return replace(self, von_mises_MPa=self.von_mises_MPa * s,
                       max_principal_MPa=self.max_principal_MPa * s,
                       von_mises_unfiltered_MPa=self.von_mises_unfiltered_MPa * s)


_NAN3 = (float("nan"),) * 3


def _field_peak(kind, stress: np.ndarray, xyz: np.ndarray, nodes: np.ndarray, surf):
    """Peak of kind(stress) over ``nodes``: the local fit where the surface recovery covers a
    node, the largest node elsewhere; the larger of the two."""
    if nodes.size == 0:
        return float("nan"), _NAN3
    best, where = float("-inf"), _NAN3
    rest = nodes
    if surf is not None:
        ok = surf.nodes[np.isfinite(surf.stress[0])]
        cov = np.intersect1d(nodes, ok)
        rest = np.setdiff1d(nodes, cov)
        if cov.size:
            best, where = local_peak(surf, kind, cov)
    if rest.size:
        v = kind(stress[:, rest])
        i = int(np.argmax(v))
        if v[i] > best:
            best, where = float(v[i]), tuple(float(c) for c in xyz[:, rest[i]])
    return best, where


def max_principal(s: np.ndarray) -> np.ndarray:
    """The largest principal stress of Voigt stresses s (6, n)."""
    return principal(s)[0]


def peak(stress: np.ndarray, xyz: np.ndarray, nodes: np.ndarray, excluded: np.ndarray,
         region: str, surf=None) -> RegionPeak:
    """The peaks of ``stress`` (6, n_nodes) over ``nodes`` with and without the ``excluded``
    nodes; ``surf`` (a ``shaftfe.fe.surface.SurfaceField``) locates peaks on the free surface by
    its local fit."""
    keep = np.setdiff1d(nodes, excluded)
    v, loc = _field_peak(von_mises, stress, xyz, keep, surf)
    p1, loc1 = _field_peak(max_principal, stress, xyz, keep, surf)
    vu, locu = _field_peak(von_mises, stress, xyz, nodes, surf)
    return RegionPeak(region, v, loc, p1, loc1, vu, locu, int(nodes.size),
                      int(nodes.size - keep.size))
