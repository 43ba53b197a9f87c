"""Integrals over boundary facets without a volume basis: ``FacetQuadrature``.

A load or a coupling on a face needs, at the face's quadrature points, the position x, the
outward normal n, the area element dA and the values of the facet's nodal shape functions. On
a P2 (P1) tet mesh the trace of the element's basis on a face is the 6-node (3-node) triangle
basis of the face's own nodes, and every other basis function of the element vanishes there,
so all of it follows from the facet's nodes alone: x(ξ) = Σ_a x_a ψ_a(ξ) on the reference
triangle, dA = |∂x/∂ξ₁ × ∂x/∂ξ₂| w, n the unit cross product turned away from the element.

scikit-fem's ``FacetBasis`` gets the same numbers (tests/test_static.py compares them to
round-off) through the element's inverse isoparametric map (a Newton iteration per point) and
the global dof locations of every element; here a face of a few hundred facets costs ~1 ms
instead of ~0.06 s, which the static model pays ~15 times per build.

Node ordering (``facet_nodes``, also used by the surface stress recovery): the face's corners,
then on P2 the mid-side nodes of the edges 0-1, 1-2, 0-2 (the order of scikit-fem's
``ElementTriP2``), turned so that the corners' cross product points out of the solid.
Vector dofs are interleaved (dof 3 n + i), as everywhere in ``shaftfe.fe``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shaftfe.errors import SolverError


@dataclass(frozen=True, eq=False)
class FacetQuadrature:
    """Quadrature data of a set of boundary facets: ``nodes`` (nb, nf) global node numbers,
    ``psi`` (nb, nq) shape-function values at the reference points, ``x`` (3, nf, nq),
    ``n`` (3, nf, nq) outward unit normals, ``dA`` (nf, nq) weights × area element."""
    nodes: np.ndarray
    psi: np.ndarray
    x: np.ndarray
    n: np.ndarray
    dA: np.ndarray
    n_nodes: int

    def vector_load(self, g: np.ndarray) -> np.ndarray:
        """∫ g · v dA for every vector test function v: g (3, nf, nq) → (3 n_nodes,)."""
        out = np.zeros((self.n_nodes, 3))
        w = g * self.dA                                              # (3, nf, nq)
        for a in range(self.psi.shape[0]):
            contrib = w @ self.psi[a]                                # (3, nf)
            for i in range(3):
                out[:, i] += np.bincount(self.nodes[a], weights=contrib[i],
                                         minlength=self.n_nodes)
        return out.ravel()


_EDGES = ((0, 1), (1, 2), (0, 2))     # mid-side nodes 3, 4, 5 of the 6-node triangle


def n_nodes(mesh) -> int:
    """The mesh's nodes (corners and, P2, mid-side nodes)."""
    return int(mesh.doflocs.shape[1])


def is_quadratic(mesh) -> bool:
    """A P2 (10-node) tetrahedral mesh."""
    from skfem import MeshTet2
    return isinstance(mesh, MeshTet2)


def facet_nodes(mesh, facets) -> np.ndarray:
    """(3 or 6, nf) nodes of BOUNDARY facets: the 3 corners, then (P2) the mid-side nodes of the
    edges 01, 12, 02 (matched by their end nodes); ordered so that (x1 − x0) × (x2 − x0)
    points out of the solid (away from the element behind the facet). A facet between two
    elements is refused (ValueError): it has no outside."""
    facets = np.asarray(facets)
    if facets.size and (mesh.f2t[1, facets] != -1).any():
        raise ValueError("facet_nodes: interior facets have no outward side")
    c = mesh.facets[:, facets]
    quad = is_quadratic(mesh)
    out = np.empty((6 if quad else 3, facets.size), dtype=np.int64)
    out[:3] = c
    if quad:
        E = mesh.f2e[:, facets]
        mid = mesh.dofs.edge_dofs[0][E]
        ends = mesh.edges[:, E]
        for k, (a, b) in enumerate(_EDGES):
            for j in range(3):
                hit = (((ends[0, j] == c[a]) & (ends[1, j] == c[b]))
                       | ((ends[0, j] == c[b]) & (ends[1, j] == c[a])))
                out[3 + k, hit] = mid[j, hit]
    p = mesh.p
    inner = p[:, mesh.t[:, mesh.f2t[0, facets]]].mean(axis=1)       # the element behind
    c0, c1, c2 = (p[:, out[i]] for i in range(3))
    flip = np.einsum("cf,cf->f", np.cross(c1 - c0, c2 - c0, axis=0),
                     c0 + c1 + c2 - 3 * inner) < 0
    out[:, flip] = out[[0, 2, 1, 5, 4, 3] if quad else [0, 2, 1]][:, flip]
    return out


def facet_quadrature(mesh, facets, intorder: int | None = None) -> FacetQuadrature:
    """``FacetQuadrature`` of the boundary ``facets`` of a ``MeshTet2`` (order 4 by default) or
    ``MeshTet1`` (order 2): order 4 integrates a product of two P2 traces on a straight facet
    exactly; on a curved one it is the order scikit-fem's facet bases were used with here."""
    from skfem import ElementTriP1, ElementTriP2
    from skfem.quadrature import get_quadrature
    from skfem.refdom import RefTri

    facets = np.asarray(facets)
    quad = is_quadratic(mesh)
    if intorder is None:
        intorder = 4 if quad else 2
    X, W = get_quadrature(RefTri, intorder)                          # (2, nq), (nq,)
    el = ElementTriP2() if quad else ElementTriP1()
    nb = el.doflocs.shape[0]
    basis = [el.lbasis(X, a) for a in range(nb)]
    psi = np.array([b[0] for b in basis])                            # (nb, nq)
    dpsi = np.array([b[1] for b in basis])                           # (nb, 2, nq)
    nodes = facet_nodes(mesh, facets)                                # outward order
    xa = mesh.doflocs[:, nodes]                                      # (3, nb, nf)
    x = np.einsum("iaf,aq->ifq", xa, psi)
    t1 = np.einsum("iaf,aq->ifq", xa, dpsi[:, 0])
    t2 = np.einsum("iaf,aq->ifq", xa, dpsi[:, 1])
    c = np.cross(t1, t2, axis=0)                                     # (3, nf, nq), outward
    area = np.linalg.norm(c, axis=0)
    if not (area > 0).all():
        f = int(facets[np.argmin(area.min(axis=1))])
        raise SolverError(f"boundary facet {f} has a zero or undefined area element: a "
                          "degenerate or tangled facet; remesh")
    n = c / area
    return FacetQuadrature(nodes, psi, x, n, area * W[None, :], n_nodes(mesh))
