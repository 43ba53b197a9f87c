"""Finite-element assembly for 3D linear elasticity on the shaft mesh (scikit-fem).

Everything here works on a scikit-fem ``MeshTet2`` (P2, the default) or ``MeshTet1`` in mm,
with vector dofs interleaved per node: dof ``3 n + i`` is component i (x, y, z) of node n
(scikit-fem's ``ElementVector`` numbering; ``nodal_dofs`` of a P2 basis holds only the corner
nodes, so never sum loads over it — FINDINGS pitfall 2).

Pieces
------
* ``elasticity_stiffness``: K = ∫ σ(u) : ε(v) dx, with σ = λ tr ε I + 2 μ ε. The element matrices
  are built with one batched matrix product of the weighted basis gradients (NumPy ``matmul``)
  and summed as 3×3 node blocks on the mesh's node pattern (``node_pattern``, computed once per
  mesh from the node adjacency, instead of SciPy's COO → CSR duplicate sort);
  ``elasticity_stiffness_skfem`` is the plain scikit-fem form it is tested
  against (they agree to round-off). P2 gradients are linear, so the integrand is quadratic and
  ``intorder=2`` integrates it exactly on straight tets (curved P2 tets: the same rule scikit-fem
  uses by default for this element).
* ``surface_load``: the load vector of a pressure on a named face group, uniform or
  cosine-distributed about a direction, scaled so that its net force is exactly the given force
  (face integrals from the facets' own nodes: ``shaftfe.fe.facets``).
* ``rigid_rows``: the six rows that give a face's RBE3 remote-point motion (least-squares rigid
  fit to the face displacements with area weighting); see ``shaftfe.fe.supports``.
* ``body_force_load``: the centrifugal body force ρ ω² (0, y, z) of the shaft itself, and a
  uniform acceleration's ρ a (gravity).
* ``rigid_body_modes``: the six rigid motions sampled at the nodes.
"""

from __future__ import annotations

import threading

import numpy as np
import scipy.sparse as sp

from shaftfe.errors import SolverError
from shaftfe.fe.facets import facet_quadrature, is_quadratic, n_nodes

ASSEMBLY_CHUNK = 4096     # elements per block of element matrices in elasticity_stiffness


def lame(E: float, nu: float) -> tuple[float, float]:
    """Lamé parameters (λ, μ) of an isotropic material."""
    return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))


def scalar_element(mesh):
    """P2 for a ``MeshTet2``, P1 for a ``MeshTet1``."""
    from skfem import ElementTetP1, ElementTetP2, MeshTet2
    return ElementTetP2() if isinstance(mesh, MeshTet2) else ElementTetP1()


def vector_basis(mesh, intorder: int | None = None):
    from skfem import Basis, ElementVector
    if intorder is None:
        intorder = 2 if is_quadratic(mesh) else 1
    return Basis(mesh, ElementVector(scalar_element(mesh)), intorder=intorder)


# --------------------------------------------------------------------------- stiffness

def physical_gradients(mesh, intorder: int | None = None):
    """Gradients of the nodal basis functions at the quadrature points of every element,
    (ne, nq, nloc, 3), and the integration weights w_q |det J| (ne, nq), computed directly with
    NumPy for the isoparametric map x(ξ) = Σ_a x_a φ_a(ξ): J = Σ_a x_a ⊗ ∇_ξ φ_a,
    ∇φ_a = J⁻ᵀ ∇_ξ φ_a. The same quantities as a scikit-fem ``Basis`` (tested), without its
    per-function Python loop over the mapping."""
    from skfem.quadrature import get_quadrature
    if intorder is None:
        intorder = 2 if is_quadratic(mesh) else 1
    X, W = get_quadrature(mesh.refdom, intorder)                   # (3, nq), (nq,)
    dN, det = gradients_at(mesh, X)
    return dN, det * W[None, :]


def gradients_at(mesh, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Physical gradients (ne, nq, nloc, 3) of the nodal basis functions at the reference
    points X (3, nq) of every element, and det J (ne, nq) there; an element with det J ≤ 0 at
    one of the points (tangled or inverted) is a one-line SolverError naming it."""
    e = scalar_element(mesh)
    dref = np.array([e.lbasis(X, a)[1] for a in range(e.doflocs.shape[0])])  # (nloc, 3, nq)
    nloc, nq = dref.shape[0], dref.shape[2]
    xe = np.ascontiguousarray(mesh.doflocs[:, element_nodes(mesh)].transpose(2, 0, 1))
    J = (xe @ dref.reshape(nloc, 3 * nq)).reshape(-1, 3, 3, nq)   # J[e, i, j, q] = ∂x_i/∂ξ_j
    # J⁻¹ by cofactors, component arrays (ne, nq): faster than batched LAPACK on 3 × 3
    C = np.empty_like(J)                                           # C[e, j, i] = cof(J)[i, j]
    for i in range(3):
        i1, i2 = (i + 1) % 3, (i + 2) % 3
        for j in range(3):
            j1, j2 = (j + 1) % 3, (j + 2) % 3
            C[:, j, i] = J[:, i1, j1] * J[:, i2, j2] - J[:, i1, j2] * J[:, i2, j1]
    det = np.einsum("eiq,eiq->eq", J[:, 0], C[:, :, 0])           # Σ_j J[0, j] cof[0, j]
    if not det.size or not (det.min() > 0):
        _refuse_bad_elements(mesh, det)
    with np.errstate(all="ignore"):
        Jinv = C / det[:, None, None, :]                           # Jinv[e, j, i, q]
    # ∇φ_a = J⁻ᵀ ∇_ξ φ_a: dN[e, q, a, i] = Σ_j Jinv[e, j, i, q] dref[a, j, q]
    dN = np.empty((J.shape[0], nq, nloc, 3))
    for q in range(nq):                                            # (a, j) @ (e, j, i)
        np.matmul(dref[:, :, q], Jinv[..., q], out=dN[:, q])
    return dN, det


def _refuse_bad_elements(mesh, det: np.ndarray) -> None:
    """One-line ``SolverError`` naming the worst element with det J ≤ 0 (or not finite) at a
    quadrature point: a tangled or inverted element would otherwise be integrated with |det J|
    and give a plausible-looking but wrong result."""
    if not det.size:
        raise SolverError("the mesh has no elements")
    worst = np.where(np.isfinite(det), det, -np.inf).min(axis=1)
    bad = np.nonzero(~(worst > 0))[0]
    e = int(bad[np.argmin(worst[bad])])
    c = mesh.p[:, mesh.t[:, e]].mean(axis=1)
    raise SolverError(f"element {e} (centroid {c[0]:.3f}, {c[1]:.3f}, {c[2]:.3f} mm) is tangled "
                      f"or inverted: det J = {worst[e]:.3g} <= 0 at a quadrature point "
                      f"({bad.size} such element(s)); remesh or fix the mesh")


def elasticity_stiffness(mesh, E: float, nu: float) -> sp.csr_matrix:
    """K = ∫ (λ div u div v + 2 μ ε(u):ε(v)) dx, vectorised: with T[(a,i),(b,j)] =
    Σ_q w_q ∂_i φ_a ∂_j φ_b (one batched matrix product per element),
    K_e[(a,i),(b,j)] = λ T[(a,i),(b,j)] + μ T[(a,j),(b,i)] + μ δ_ij Σ_k T[(a,k),(b,k)]."""
    lam, mu = lame(E, nu)
    dN, wdx = physical_gradients(mesh)                            # (ne, nq, nloc, 3), (ne, nq)
    ne, nq, nloc, _ = dN.shape
    G = dN * np.sqrt(wdx)[:, :, None, None]                       # weights split over both
    del dN
    Gm = G.reshape(ne, nq, 3 * nloc)                              # column a*3 + i
    # element matrices as 3×3 node blocks Kb[e, a, b, i, j], written chunk by chunk into one
    # array: the temporaries stay small (peak memory of the whole assembly −0.4 GB at 145k dofs)
    Kb = np.empty((ne, nloc, nloc, 3, 3))
    for s in range(0, ne, ASSEMBLY_CHUNK):
        g = Gm[s:s + ASSEMBLY_CHUNK]
        T = np.matmul(g.transpose(0, 2, 1), g).reshape(-1, nloc, 3, nloc, 3)   # e a i b j
        lap = np.einsum("eaibi->eab", T)                           # ∇φ_a · ∇φ_b
        Tb = T.transpose(0, 1, 3, 2, 4)                            # e a b i j
        k = Kb[s:s + ASSEMBLY_CHUNK]
        np.multiply(Tb, lam, out=k)                                # λ T[(a,i),(b,j)]
        k += mu * Tb.transpose(0, 1, 2, 4, 3)                      # μ T[(a,j),(b,i)]
        for i in range(3):
            k[:, :, :, i, i] += mu * lap
    return assemble_blocks(mesh, Kb, 3)


# --------------------------------------------------------------------------- sparse pattern

_PATTERNS: dict = {}      # id(mesh) -> (weakref to the mesh, pattern): one pattern per mesh
_PATTERNS_LOCK = threading.Lock()   # the zoned solve assembles in a worker thread too


def node_pattern(mesh):
    """The node-to-node sparsity pattern of the mesh's elements, computed once per mesh object:
    ``(where, indptr, indices)`` with ``where[e*nloc*nloc + a*nloc + b]`` the position in the
    CSR node pattern (rows sorted, columns sorted) of the pair (node a, node b) of element e.
    Replaces SciPy's COO → CSR conversion with duplicate summing (a sort of every row: 1.7 s of
    the 2.3 s stiffness assembly on x2_57 default) by the node adjacency EᵀE of the
    element-node incidence E and one ``searchsorted`` (0.26 s), shared by the stiffness and the
    mass matrices of one mesh."""
    import weakref
    with _PATTERNS_LOCK:
        hit = _PATTERNS.get(id(mesh))
    if hit is not None and hit[0]() is mesh:
        return hit[1]
    ed = element_nodes(mesh).T                                      # (ne, nloc)
    nl = ed.shape[1]
    nn = n_nodes(mesh)
    ne = ed.shape[0]
    E = sp.csr_matrix((np.ones(ed.size), ed.ravel(), np.arange(0, ed.size + 1, nl)),
                      shape=(ne, nn))                               # element-node incidence
    A = (E.T @ E).tocsr()                                           # node adjacency
    A.sort_indices()
    keys = np.repeat(np.arange(nn, dtype=np.int64) * nn, np.diff(A.indptr)) + A.indices
    pairs = (np.repeat(ed.astype(np.int64), nl, axis=1) * nn + np.tile(ed, (1, nl))).ravel()
    where = np.searchsorted(keys, pairs)
    if keys.size < 2**31:
        where = where.astype(np.int32)                              # −14 MB at 170k dofs
    pattern = (where, A.indptr.astype(np.int64),
               A.indices.astype(np.int32))
    with _PATTERNS_LOCK:
        for key in [k for k, (ref, _) in _PATTERNS.items() if ref() is None]:
            del _PATTERNS[key]
        _PATTERNS[id(mesh)] = (weakref.ref(mesh), pattern)
    return pattern


def assemble_blocks(mesh, blocks: np.ndarray, d: int) -> sp.csr_matrix:
    """Sum element matrices given as node blocks ``blocks[e, a, b]`` (each d × d, or scalars for
    d = 1) into a CSR matrix of size d·N (dof d n + i = component i of node n), canonical
    format (sorted columns, no duplicates)."""
    where, indptr, indices = node_pattern(mesh)
    nu, nn = indices.size, indptr.size - 1
    flat = blocks.reshape(where.size, d * d)
    data = np.empty((nu, d * d))
    for j in range(d * d):                                          # bincount sums in order:
        data[:, j] = np.bincount(where, weights=flat[:, j], minlength=nu)   # deterministic
    if d == 1:
        return sp.csr_matrix((data[:, 0], indices, indptr), shape=(nn, nn))
    return sp.bsr_matrix((data.reshape(nu, d, d), indices, indptr),
                         shape=(d * nn, d * nn)).tocsr()


def partition(K: sp.csr_matrix, cut: np.ndarray) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """(K_II, K_IB) of the square CSR matrix K split into the dofs ``cut`` (B, sorted, unique)
    and the rest (I, in their order): one pass over K's arrays, none of the row-permuted and
    row-block copies that slicing makes (measured on x2_57's 32k-dof zone: the same blocks,
    two 28 MB copies fewer while the zones factorise side by side)."""
    n = K.shape[0]
    inner = np.ones(n, dtype=bool)
    inner[cut] = False
    pos_i = np.cumsum(inner) - 1                       # old dof -> its place in I (or B)
    pos_b = np.cumsum(~inner) - 1
    rows = np.repeat(np.arange(n, dtype=K.indices.dtype), np.diff(K.indptr))
    row_in = inner[rows]
    col_in = inner[K.indices]
    ni, nb = n - len(cut), len(cut)
    out = []
    for keep, pos, ncol in ((row_in & col_in, pos_i, ni), (row_in & ~col_in, pos_b, nb)):
        indptr = np.zeros(ni + 1, dtype=K.indptr.dtype)
        np.cumsum(np.bincount(pos_i[rows[keep]], minlength=ni), out=indptr[1:])
        out.append(sp.csr_matrix((K.data[keep], pos[K.indices[keep]].astype(K.indices.dtype),
                                  indptr), shape=(ni, ncol)))
    return out[0], out[1]


def elasticity_stiffness_skfem(mesh, E: float, nu: float) -> sp.csr_matrix:
    """The same matrix through scikit-fem's ``linear_elasticity`` form (reference)."""
    from skfem.models.elasticity import linear_elasticity
    return linear_elasticity(*lame(E, nu)).assemble(vector_basis(mesh)).tocsr()


# --------------------------------------------------------------------------- faces

def robust_mapping(mesh):
    """The mesh's reference mapping; for curved (P2) meshes an isoparametric mapping whose
    inverse (Newton, used by facet bases and probes) starts at the element centroid and does
    not clip the iterate to the unit cube. scikit-fem 12's clipped iteration stalls on strongly
    curved tets of a coarse cylinder mesh ("Newton iteration didn't converge")."""
    if not is_quadratic(mesh):
        return mesh.mapping()
    from skfem.mapping import MappingIsoparametric

    class _Mapping(MappingIsoparametric):
        def invF(self, x, tind=None, newton_max_iters=50, newton_tol=1e-12):
            # elements where Newton does not converge (a probe point far outside a curved
            # candidate element) get NaN, which every "inside" test rejects
            X = np.zeros(x.shape) + 0.25
            with np.errstate(all="ignore"):
                for _ in range(newton_max_iters):
                    dX = np.einsum("ijkl,jkl->ikl", self.invDF(X, tind), x - self.F(X, tind))
                    X = X + dX
                    done = np.linalg.norm(dX, 1, (0, 2)) < newton_tol
                    if done.all():
                        return X
            X[:, ~done, :] = np.nan
            return X

    return _Mapping(mesh, mesh.elem(), mesh.bndelem)


def scalar_quadrature(mesh):
    """(φ (nloc, nq), ∇φ (ne, nq, nloc, 3), w |det J| (ne, nq)) of the scalar nodal basis at
    the quadrature points (order 4 on P2: exact for a mass on straight P2 tets, 2 on P1): the
    one quadrature of the scalar mass (``rotordynamics.solid_rotor.mass_and_gyro``,
    ``static.model.mass_times``)."""
    from skfem.quadrature import get_quadrature
    order = 4 if is_quadratic(mesh) else 2
    e = scalar_element(mesh)
    X, _ = get_quadrature(mesh.refdom, order)
    phi = np.array([e.lbasis(X, a)[0] for a in range(e.doflocs.shape[0])])
    dN, wdx = physical_gradients(mesh, order)
    return phi, dN, wdx


def element_nodes(mesh) -> np.ndarray:
    """(nloc, ne) node numbers of every element (10 for P2, 4 for P1) in scikit-fem order."""
    return mesh.dofs.element_dofs if is_quadratic(mesh) else mesh.t


def face_nodes(mesh, facets) -> np.ndarray:
    """All nodes (corners and, for P2, mid-side nodes) of the given facets."""
    facets = np.asarray(facets)
    corners = mesh.facets[:, facets].ravel()
    if not is_quadratic(mesh):
        return np.unique(corners)
    mids = mesh.dofs.edge_dofs[0][mesh.f2e[:, facets]].ravel()
    return np.unique(np.concatenate([corners, mids]))


def _rigid_field(x, k: int, center):
    """Rigid mode k (0-2 translations x, y, z; 3-5 rotations about x, y, z through ``center``)
    evaluated at points x (3, ...), as a (3, ...) array."""
    z0 = np.zeros_like(x[0])
    if k < 3:
        out = [z0, z0, z0]
        out[k] = z0 + 1.0
        return np.array(out)
    r = [x[i] - center[i] for i in range(3)]
    if k == 3:
        return np.array([z0, -r[2], r[1]])
    if k == 4:
        return np.array([r[2], z0, -r[0]])
    return np.array([-r[1], r[0], z0])


def rigid_rows(mesh, facets, center) -> np.ndarray:
    """(6, ndof) rows giving the RBE3 remote-point motion of a face about ``center``:
    q = (Φᵀ W Φ)⁻¹ Φᵀ W u, with Φ the six rigid modes and W the surface (area) inner product,
    i.e. the area-weighted least-squares rigid motion of the face. For a full cylindrical seat
    centred on the axis the translation rows are the area means (1/A) ∫ u_y dA etc. and the
    twist row is ∫ (y u_z − z u_y) dA / ∫ (y² + z²) dA. A rigid motion of the face is
    reproduced exactly; the coupling adds no stiffness of its own."""
    fq = facet_quadrature(mesh, facets)
    center = np.asarray(center, dtype=float)
    rows = [fq.vector_load(_rigid_field(fq.x, k, center)) for k in range(6)]
    R = np.array(rows)                                  # (6, ndof): ∫ φ_k · v dA
    modes = rigid_body_modes(mesh, center)              # (ndof, 6), exact in the FE space
    M = R @ modes                                       # ∫ φ_k · φ_l dA
    return np.linalg.solve(M, R)


def rigid_body_modes(mesh, center=(0.0, 0.0, 0.0)) -> np.ndarray:
    """(ndof, 6) nodal values of the rigid modes (translations x, y, z; rotations about x, y, z
    through ``center``), interleaved dofs."""
    x = mesh.doflocs
    out = np.empty((3 * x.shape[1], 6))
    for k in range(6):
        out[:, k] = _rigid_field(x, k, np.asarray(center, dtype=float)).T.ravel()
    return out


def surface_load(mesh, facets, force, direction, distribution: str = "uniform",
                 cache: dict | None = None) -> np.ndarray:
    """Load vector of a pressure on a face whose net force is exactly ``force`` along
    ``direction`` (a unit vector in the y–z plane).

    The pressure acts along the inward normal −n: p = p0 (uniform) or p = p0 max(0, −n·e)
    (cosine distribution about the direction e). p0 is found from the discrete net force, so
    Σ f · e = force to round-off whatever the mesh; the small force across e and torque about
    the axis that the discretised surface leaves are then removed exactly (see below).

    ``cache``: a dict shared by the calls of ONE model build (same mesh); the facet basis, the
    correction vectors and (uniform) the unscaled pressure vector are reused for a facet set
    seen before (several parts on one seat): the same numbers, bit for bit."""
    e = np.asarray(direction, dtype=float)
    facets = np.asarray(facets)
    key = (facets.dtype.str, facets.tobytes())
    hit = cache.get(key) if cache is not None else None
    if hit is None:
        hit = {"fq": facet_quadrature(mesh, facets)}
        if cache is not None:
            cache[key] = hit
    fq = hit["fq"]
    if distribution == "uniform":
        p = np.ones(fq.dA.shape)
    elif distribution == "cosine":
        p = np.maximum(0.0, -np.einsum("i,i...->...", e, fq.n))
    else:  # pragma: no cover - validated by the caller
        raise ValueError(f"unknown load distribution {distribution!r}")

    pkey = "uniform" if distribution == "uniform" else (distribution, e.tobytes())
    if pkey not in hit:
        hit[pkey] = fq.vector_load(-p * fq.n)                       # ∫ −p n · v dA
    f = hit[pkey].copy()
    net = f.reshape(-1, 3).sum(axis=0) @ e
    if not net > 0:
        raise ValueError("the loaded face gives no force along the load direction")
    f *= force / net

    # The discretised surface leaves a force across e (also along x) and a torque about the axis
    # of order (h/r)² × force. Remove them with a small uniform traction (x, y, z) and a uniform
    # shear (−z, y) on the same face: the net load is exactly ``force`` along e, zero torque.
    x = mesh.doflocs

    def resultant(g):
        g3 = g.reshape(-1, 3)
        return np.array([g3[:, 0].sum(), g3[:, 1].sum(), g3[:, 2].sum(),
                         (x[1] * g3[:, 2] - x[2] * g3[:, 1]).sum()])
    if "corr" not in hit:
        one, zero = np.ones(fq.dA.shape), np.zeros(fq.dA.shape)
        hit["corr"] = [fq.vector_load(np.array(g)) for g in
                       ((one, zero, zero), (zero, one, zero), (zero, zero, one),
                        (zero, -fq.x[2], fq.x[1]))]                # traction x, y, z; twist
    corr = hit["corr"]
    M = np.column_stack([resultant(g) for g in corr])
    target = np.array([0.0, force * e[1], force * e[2], 0.0])
    coef = np.linalg.solve(M, target - resultant(f))
    return f + sum(c * g for c, g in zip(coef, corr, strict=True))


def body_force_load(mesh, density: float, omega2: float, accel=None) -> np.ndarray:
    """Body force of the shaft's own mass in the co-rotating frame: the centrifugal
    ∫ ρ ω² (0, y, z) · v dx, plus ∫ ρ a · v dx of a uniform acceleration ``accel`` (mm/s², e.g.
    gravity) when given."""
    from skfem import LinearForm
    a = None if accel is None else np.asarray(accel, dtype=float)

    @LinearForm
    def body(v, w):
        out = density * omega2 * (w.x[1] * v[1] + w.x[2] * v[2])
        if a is not None:
            out = out + density * (a[0] * v[0] + a[1] * v[1] + a[2] * v[2])
        return out

    return body.assemble(vector_basis(mesh, 4 if is_quadratic(mesh) else 2))
