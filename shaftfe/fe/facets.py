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

Node ordering: the face's corners ``mesh.facets`` then, on P2, its edge nodes in the order of
``mesh.f2e`` (edges 0-1, 1-2, 0-2), which is the order of scikit-fem's ``ElementTriP2``.
Vector dofs are interleaved (dof 3 n + i), as everywhere in ``shaftfe.fe``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


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


def facet_quadrature(mesh, facets, intorder: int | None = None) -> FacetQuadrature:
    """``FacetQuadrature`` of the boundary ``facets`` of a ``MeshTet2`` (order 4 by default) or
    ``MeshTet1`` (order 2): order 4 integrates a product of two P2 traces on a straight facet
    exactly; on a curved one it is the order scikit-fem's facet bases were used with here."""
    from skfem import ElementTriP1, ElementTriP2
    from skfem.quadrature import get_quadrature
    from skfem.refdom import RefTri

    from shaftfe.fe.assembly import is_quadratic, n_nodes
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
    nodes = mesh.facets[:, facets]
    if quad:
        nodes = np.vstack([nodes, mesh.dofs.edge_dofs[0][mesh.f2e[:, facets]]])
    xa = mesh.doflocs[:, nodes]                                      # (3, nb, nf)
    x = np.einsum("iaf,aq->ifq", xa, psi)
    t1 = np.einsum("iaf,aq->ifq", xa, dpsi[:, 0])
    t2 = np.einsum("iaf,aq->ifq", xa, dpsi[:, 1])
    c = np.cross(t1, t2, axis=0)                                     # (3, nf, nq)
    area = np.linalg.norm(c, axis=0)
    # outward: away from the corners' centroid of the element behind the facet
    el_of = mesh.f2t[0, facets]
    inward = mesh.p[:, mesh.t[:, el_of]].mean(axis=1) - mesh.p[:, mesh.facets[:, facets]].mean(
        axis=1)                                                      # (3, nf)
    sign = np.where(np.einsum("if,if->f", c.mean(axis=2), inward) > 0, -1.0, 1.0)
    n = c / area * sign[None, :, None]
    return FacetQuadrature(nodes, psi, x, n, area * W[None, :], n_nodes(mesh))
