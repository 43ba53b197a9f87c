"""A nodal field of a tetrahedral mesh evaluated at arbitrary points (the one implementation:
the static solution's axis deflection and the stress gradient of the FKM assessment use it).

Works on plain arrays so that a cached ``StaticReference`` (node coordinates, scikit-fem-ordered
cells, nodal stresses) needs no scikit-fem mesh object:

* ``corners``: coordinates (3, n) indexable by the cells' first four (corner) node ids;
* ``cells``: (ne, 4 | 10) node ids in scikit-fem's order (``fe.assembly.element_nodes(m).T``);
* ``values``: (n_nodes, ncomp) nodal values.

Each point is located by barycentric coordinates in the straight-sided tet of an element's
corners (candidates: the 16 nearest element centroids) and the P1 / P2 field is evaluated with
the barycentric shape functions. Exact for straight elements and polynomial fields of the
element's degree; the curved boundary elements of a fillet are evaluated as straight, which
moves a point by at most the element's deviation from straight (the mesher's curvature, well
under the element size). Points not found get NaN.
"""

from __future__ import annotations

import numpy as np

N_CANDIDATES = 16


def centroid_tree(corners: np.ndarray, cells: np.ndarray):
    """A k-d tree of the elements' corner centroids (build once per mesh)."""
    from scipy.spatial import cKDTree
    c = np.asarray(cells)[:, :4]
    return cKDTree(np.asarray(corners, dtype=float)[:, c].mean(axis=2).T)


def locate(corners, cells, pts, tree=None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(element id (n,), barycentric coordinates (n, 4), found mask (n,)) of points (3, n)."""
    corners = np.asarray(corners, dtype=float)
    cells = np.asarray(cells)
    pts = np.asarray(pts, dtype=float).reshape(3, -1)
    tree = tree if tree is not None else centroid_tree(corners, cells)
    k = min(N_CANDIDATES, cells.shape[0])
    cand = np.asarray(tree.query(pts.T, k)[1]).reshape(pts.shape[1], k)    # (n, k)
    v = corners[:, cells[cand, :4]]                                       # (3, n, k, 4)
    v = np.moveaxis(v, -1, 1)                                             # (3, 4, n, k)
    T = v[:, 1:] - v[:, :1]                                               # (3, 3, n, k)
    rhs = pts[:, None, :, None] - v[:, 0:1]                               # (3, 1, n, k)
    lam123 = np.linalg.solve(np.moveaxis(T, (0, 1), (-2, -1)),
                             np.moveaxis(rhs, (0, 1), (-2, -1)))[..., 0]  # (n, k, 3)
    lam = np.concatenate([1 - lam123.sum(-1, keepdims=True), lam123], -1)  # (n, k, 4)
    worst = lam.min(-1)
    best = np.argmax(worst, axis=1)
    rows = np.arange(pts.shape[1])
    found = worst[rows, best] >= -1e-9
    return cand[rows, best], lam[rows, best], found


def _p2_edges() -> list[tuple[int, int]]:
    """The corner pairs of scikit-fem's P2 tetrahedron's mid-side nodes, in its dof order."""
    from skfem import ElementTetP2
    ref = np.asarray(ElementTetP2().doflocs, dtype=float)
    refv = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    return [next((a, b) for a in range(4) for b in range(a + 1, 4)
                 if np.allclose(0.5 * (refv[a] + refv[b]), r)) for r in ref[4:]]


def shape_values(L: np.ndarray, nloc: int) -> np.ndarray:
    """(nloc, n) P1 (nloc 4) or P2 (nloc 10) shape functions at barycentric coordinates L."""
    L = np.asarray(L, dtype=float)
    if nloc == 4:
        return L.T.copy()
    if nloc != 10:
        raise ValueError(f"cells of 4 or 10 nodes, got {nloc}")
    N = [L[:, i] * (2 * L[:, i] - 1) for i in range(4)]
    N += [4 * L[:, i] * L[:, j] for i, j in _p2_edges()]
    return np.array(N)


def interpolate(corners, cells, values, pts, tree=None) -> tuple[np.ndarray, np.ndarray]:
    """The nodal ``values`` (n_nodes, ncomp) at points (3, n): ((n, ncomp), found mask)."""
    cells = np.asarray(cells)
    values = np.asarray(values, dtype=float)
    el, L, found = locate(corners, cells, pts, tree)
    N = shape_values(L, cells.shape[1])                                   # (nloc, n)
    V = values[cells[el].T]                                               # (nloc, n, ncomp)
    out = np.einsum("an,anc->nc", N, V)
    out[~found] = np.nan
    return out, found


def surface_normal(ref, node: int) -> tuple[np.ndarray, float]:
    """Inward unit normal and the mean boundary edge length at a surface node: the mean of the
    adjacent boundary triangles' normals, each turned outward by the element it bounds (away
    from that tetrahedron's fourth corner), so that edges and corners (a keyway's floor and
    wall) average correctly."""
    fc = np.asarray(ref.face_cells)
    tris = fc[np.any(fc == node, axis=1)][:, :3]
    if tris.size == 0:
        raise ValueError(f"node {node} is on no boundary face")
    X = np.asarray(ref.xyz, dtype=float)
    corners = np.asarray(ref.cells)[:, :4]
    tets = corners[np.any(np.isin(corners, tris), axis=1)]
    a, b, c = (X[:, tris[:, k]] for k in range(3))
    nrm = np.cross((b - a).T, (c - a).T)                         # (nt, 3)
    nrm /= np.linalg.norm(nrm, axis=1, keepdims=True)
    for j, tri in enumerate(tris):
        own = tets[np.isin(tets, tri).sum(axis=1) == 3]
        if own.size:
            fourth = own[0][~np.isin(own[0], tri)][0]
            if (X[:, fourth] - a[:, j]) @ nrm[j] > 0:
                nrm[j] = -nrm[j]
    n = nrm.sum(axis=0)
    n /= np.linalg.norm(n)
    h = float(np.mean(np.concatenate([np.linalg.norm(b - a, axis=0),
                                      np.linalg.norm(c - b, axis=0),
                                      np.linalg.norm(a - c, axis=0)])))
    return -n, h


class TetProbe:
    """The stress profile source of a 3D field (``fatigue.fkm_field.DepthProbe``): the inward
    normal from the boundary triangles (``surface_normal``) and the P2 nodal stress
    interpolated at interior points (``interpolate``). ``field``: anything with ``xyz`` (3, n),
    ``cells`` (ne, 4 | 10),
    ``face_cells`` (nf, 3 | 6) and ``stress_ref`` (6, n): a 3D ``StaticReference`` or a
    submodel's field."""

    def __init__(self, field):
        self.field = field
        self.stress = np.asarray(field.stress_ref, dtype=float).T
        self.tree = centroid_tree(field.xyz, field.cells)

    def normal(self, node: int) -> tuple[np.ndarray, float]:
        return surface_normal(self.field, node)

    def stress_at(self, node: int, pts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return interpolate(self.field.xyz, self.field.cells, self.stress, pts, self.tree)
