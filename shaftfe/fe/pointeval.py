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
