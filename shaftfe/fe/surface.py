"""Stress on the free surface of a P2 tet mesh from the displacement trace (issue #12), and peaks
located by a local fit.

Why (measured, reports/benchmarks/truth.md): the nodal average of the elements' own stresses
(``shaftfe.fe.recovery``) is biased on a curved surface. At a shoulder fillet in pure bending its
maximum always lands on a mid-side node, which reads 1.5–2.5 % above the corner nodes around it,
and the peak overshoots the axisymmetric truth by +1…+3 % at the default level and does not
converge monotonically.

Method
------
1. **Traction-free surface stress.** On each free boundary facet (the 6-node curved triangle of
   the tet's face) the P2 trace u(ξ, η) and x(ξ, η) give the covariant tangents a_α = ∂x/∂ξ_α,
   their duals a^α (a^α·a_β = δ), and the surface gradient ∇_s u = ∂u/∂ξ_α ⊗ a^α. Only the
   in-surface strain is used, ε_s = P sym(∇_s u) P with P = I − n nᵀ: it needs no derivative
   normal to the surface, which is the one the volume element gets least accurately. On a
   traction-free face σ·n = 0, so Hooke's law is plane stress in the tangent plane:
   σ = E/(1+ν) ε_s + E ν/(1−ν²) tr(ε_s) P.
2. **Patch recovery on the surface.** These stresses are sampled at the 3 interior Gauss points
   of every facet ((1/6, 1/6), (2/3, 1/6), (1/6, 2/3)) and each Cartesian component is fitted
   by least squares with a quadratic in the node's tangent-plane coordinates over a patch: for a
   corner node the facets around it, for a mid-side node the facets around either end of its
   edge. The fit's value at the node is the recovered stress. (Patches with fewer than 4 facets
   get a linear fit.)
3. **Sharp edges** (the facets' normals at a node differ by more than ``KINK_DEG``) and nodes
   without a free facet keep the nodal average: the elastic stress may be singular there.

Measured on the three pure-bending shoulders against the axisymmetric truth (benchmarks/
bench_truth.py; max principal, coarse / default / fine): 22/17/1 −3.7 / −0.9 / −0.1 %,
22/17/0.5 −2.9 / −0.6 / +0.1 %, 25/17/1 −3.6 / −0.2 / +0.0 % (nodal averaging: −1.9 / +3.4 /
+1.6 %, −1.2 / +1.7 / +1.5 %, −1.1 / +1.1 / +0.9 %). Recovering the facet-node values directly
(no fit) left the mid-side bias at +0.3…+1.4 %; a linear fit over a corner's ring smooths the
peak by −1…−2 % at the corners.

Peaks (``local_peak``): the largest node of a field over a region, then a quadratic fitted to
the field at the nodes of that node's patch, in its tangent plane; where the fit has a maximum
inside the patch, the peak is the fit's value and position there, else the node's value.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from shaftfe.fe.facets import facet_nodes

KINK_DEG = 20.0                       # facets' normals at a node farther apart: a sharp edge
GAUSS3 = np.array([[1 / 6, 1 / 6], [2 / 3, 1 / 6], [1 / 6, 2 / 3]])
_EDGES = ((0, 1), (1, 2), (0, 2))     # mid-side nodes 3, 4, 5 of the 6-node triangle


# --------------------------------------------------------------------------- pure kernels

def hooke_plane_stress(eps: np.ndarray, P: np.ndarray, E: float, nu: float) -> np.ndarray:
    """Voigt stress (k, 6) of plane stress in the tangent planes P = I − n nᵀ (k, 3, 3) from the
    in-plane strain tensors eps (k, 3, 3): σ = E/(1+ν) ε + E ν/(1−ν²) tr(ε) P."""
    tr = np.trace(eps, axis1=1, axis2=2)
    s = E / (1 + nu) * eps + (E * nu / (1 - nu ** 2)) * tr[:, None, None] * P
    return np.stack([s[:, 0, 0], s[:, 1, 1], s[:, 2, 2], s[:, 0, 1], s[:, 1, 2], s[:, 0, 2]], -1)


def tri6_shape(xi: float, eta: float) -> tuple[np.ndarray, np.ndarray]:
    """Values (6,) and (ξ, η) derivatives (6, 2) of the 6-node triangle's shape functions;
    nodes: corners (0,0), (1,0), (0,1), then mid-sides 01, 12, 02."""
    L = np.array([1 - xi - eta, xi, eta])
    dL = np.array([[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]])
    N = np.empty(6)
    dN = np.empty((6, 2))
    for i in range(3):
        N[i] = L[i] * (2 * L[i] - 1)
        dN[i] = (4 * L[i] - 1) * dL[i]
    for k, (a, b) in enumerate(_EDGES):
        N[3 + k] = 4 * L[a] * L[b]
        dN[3 + k] = 4 * (L[a] * dL[b] + L[b] * dL[a])
    return N, dN


def trace_stress(X: np.ndarray, U: np.ndarray, E: float, nu: float, points=GAUSS3):
    """Plane-stress surface stress of 6-node facets at reference points.

    X, U: (3, 6, nf) node coordinates and displacements. Returns the Voigt stress (nf, np, 6)
    (xx, yy, zz, xy, yz, xz), the unit normals (nf, np, 3) (orientation of a_1 × a_2) and the
    points' coordinates (nf, np, 3)."""
    S, nrm, pts = [], [], []
    for xi, eta in points:
        N, dN = tri6_shape(xi, eta)
        a = np.einsum("cnf,nk->fkc", X, dN)                  # covariant tangents (nf, 2, 3)
        du = np.einsum("cnf,nk->fkc", U, dN)
        g = np.einsum("fkc,flc->fkl", a, a)
        dual = np.einsum("fkl,flc->fkc", np.linalg.inv(g), a)
        G = np.einsum("fki,fkj->fij", du, dual)              # ∇_s u, G[i, j] = ∂u_i/∂x_j
        n = np.cross(a[:, 0], a[:, 1])
        n /= np.linalg.norm(n, axis=1)[:, None]
        P = np.eye(3)[None] - n[:, :, None] * n[:, None, :]
        eps = P @ (0.5 * (G + G.transpose(0, 2, 1))) @ P
        S.append(hooke_plane_stress(eps, P, E, nu))
        nrm.append(n)
        pts.append(np.einsum("cnf,n->fc", X, N))
    return np.stack(S, 1), np.stack(nrm, 1), np.stack(pts, 1)


def tangent_frames(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit tangents (k, 3) orthogonal to unit normals n (k, 3)."""
    ref = np.where(np.abs(n[:, :1]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]])
    t1 = np.cross(n, ref)
    t1 /= np.linalg.norm(t1, axis=1)[:, None]
    return t1, np.cross(n, t1)


def _basis(a: np.ndarray, b: np.ndarray, quadratic: np.ndarray) -> np.ndarray:
    """(k, p, 6) quadratic monomials 1, a, b, a², ab, b² (the last three zeroed where a linear
    fit is asked for)."""
    q = quadratic[:, None].astype(float)
    one = np.ones_like(a)
    return np.stack([one, a, b, a * a * q, a * b * q, b * b * q], -1)


def weighted_fit(M: np.ndarray, V: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Batched least squares: coefficients (k, 6, c) of min Σ_p w (M c − V)²; the unused
    quadratic columns (all zero) get an identity row so that the system stays regular."""
    Mw = (M * w[..., None]).swapaxes(1, 2)          # (k, 6, p): batched products, not a
    A = Mw @ M                                       # 3-operand einsum (2-3 × its speed)
    unused = np.abs(np.einsum("kii->ki", A)) == 0
    A[unused.nonzero()[0], unused.nonzero()[1], unused.nonzero()[1]] = 1.0
    b = Mw @ V
    return np.linalg.solve(A, b)


# --------------------------------------------------------------------------- mesh helpers

@dataclass(frozen=True, eq=False)
class SurfacePatches:
    """For every recovered node: its patch of facets (padded, ``mask`` marks the real ones),
    its unit normal and whether it lies on a sharp edge."""
    nodes: np.ndarray          # (k,) mesh node numbers
    facets: np.ndarray         # (k, m) indices into the facet list
    mask: np.ndarray           # (k, m)
    normal: np.ndarray         # (k, 3)
    kink: np.ndarray           # (k,) bool
    tri: np.ndarray            # (6, nf) facet nodes


def patches(mesh, facets: np.ndarray) -> SurfacePatches:
    """The recovery patches of every node of the given (free) boundary facets."""
    tri = facet_nodes(mesh, facets)
    nf = tri.shape[1]
    n = mesh.doflocs.shape[1]
    nodes = np.unique(tri)
    loc = np.full(n, -1)
    loc[nodes] = np.arange(nodes.size)
    k = nodes.size
    # normals of every facet at each of its 6 nodes → node normal, kink test
    X = mesh.doflocs[:, tri]
    nn = np.zeros((nf, 6, 3))
    for j, (xi, eta) in enumerate(((0, 0), (1, 0), (0, 1), (.5, 0), (.5, .5), (0, .5))):
        _, dN = tri6_shape(xi, eta)
        a = np.einsum("cnf,nk->fkc", X, dN)
        v = np.cross(a[:, 0], a[:, 1])
        nn[:, j] = v / np.linalg.norm(v, axis=1)[:, None]
    normal = np.zeros((k, 3))
    np.add.at(normal, loc[tri.T.ravel()], nn.reshape(-1, 3))
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    cos_min = np.ones(k)
    np.minimum.at(cos_min, loc[tri.T.ravel()],
                  np.einsum("pc,pc->p", nn.reshape(-1, 3), normal[loc[tri.T.ravel()]]))
    kink = cos_min < np.cos(np.radians(KINK_DEG))
    # patch: corner → facets around it; mid-side → facets around either end of its edge
    corner_inc = sp.csr_matrix((np.ones(3 * nf), (loc[tri[:3].ravel()],
                                                  np.repeat(np.arange(nf)[None], 3, 0).ravel())),
                               shape=(k, nf))
    ends = np.zeros((k, 2), dtype=np.int64)
    ends[:, 0] = ends[:, 1] = np.arange(k)
    for m_, (a, b) in enumerate(_EDGES):
        ends[loc[tri[3 + m_]], 0] = loc[tri[a]]
        ends[loc[tri[3 + m_]], 1] = loc[tri[b]]
    sel = sp.csr_matrix((np.ones(2 * k), (np.repeat(np.arange(k), 2), ends.ravel())),
                        shape=(k, k))
    pm = (sel @ corner_inc).tocsr()
    pm.data[:] = 1.0
    pm.sort_indices()
    cnt = np.diff(pm.indptr)
    width = int(cnt.max())
    pos = np.arange(pm.nnz) - np.repeat(pm.indptr[:-1], cnt)
    F = np.zeros((k, width), dtype=np.int64)
    M = np.zeros((k, width), dtype=bool)
    F[np.repeat(np.arange(k), cnt), pos] = pm.indices
    M[np.repeat(np.arange(k), cnt), pos] = True
    return SurfacePatches(nodes, F, M, normal, kink, tri)


# --------------------------------------------------------------------------- recovery

@dataclass(frozen=True, eq=False)
class SurfaceField:
    """The recovered surface stress and what re-fitting a node's patch needs."""
    nodes: np.ndarray          # (k,) mesh nodes
    stress: np.ndarray         # (6, k) Voigt, NaN on sharp edges
    patches: SurfacePatches
    samples: np.ndarray        # (nf, 3, 6) trace stresses at the facets' Gauss points
    sample_normals: np.ndarray  # (nf, 3, 3)
    sample_points: np.ndarray  # (nf, 3, 3)
    xyz: np.ndarray            # (3, n_nodes) mesh node coordinates


def _fit(f: SurfaceField, sel: np.ndarray):
    """Patch fits of the nodes ``sel`` (indices into f.nodes): coefficients (k, 6, 6) of the
    monomials ``_basis`` per Voigt component, the scale h (k, 1), tangents t1, t2 (k, 3), and
    the number of facets fitted (k,)."""
    pt = f.patches
    F, mask = pt.facets[sel], pt.mask[sel]
    npt = f.samples.shape[1]
    t1, t2 = tangent_frames(pt.normal[sel])
    d = f.sample_points[F] - f.xyz[:, pt.nodes[sel]].T[:, None, None, :]   # (k, m, np, 3)
    # a facet across a fold (its normal > 60° off the node's) never enters a fit
    ok = mask & (np.einsum("kmpc,kc->km", f.sample_normals[F], pt.normal[sel]) / npt > 0.5)
    a = np.einsum("kmpc,kc->kmp", d, t1).reshape(len(sel), -1)
    b = np.einsum("kmpc,kc->kmp", d, t2).reshape(len(sel), -1)
    w = np.repeat(ok, npt, axis=1).astype(float)
    h = np.sqrt((w * (a * a + b * b)).sum(1) / np.maximum(w.sum(1), 1))[:, None]
    h[h == 0] = 1.0
    nfac = ok.sum(1)
    M = _basis(a / h, b / h, nfac >= 4)
    c = weighted_fit(M, f.samples[F].reshape(len(sel), -1, 6), w)
    return c, h, t1, t2, nfac


def surface_stress(mesh, u: np.ndarray, E: float, nu: float, facets: np.ndarray,
                   pt: SurfacePatches | None = None) -> SurfaceField:
    """Recovered stress at the nodes of the free ``facets`` (see the module docstring; nodes on
    a sharp edge get NaN: the caller keeps its nodal average there)."""
    pt = pt if pt is not None else patches(mesh, facets)
    X = mesh.doflocs[:, pt.tri]
    U = np.asarray(u).reshape(-1, 3).T[:, pt.tri]
    S, nrm, P = trace_stress(X, U, E, nu)
    f = SurfaceField(pt.nodes, np.empty((6, 0)), pt, S, nrm, P, mesh.doflocs)
    c, _, _, _, nfac = _fit(f, np.arange(pt.nodes.size))
    out = c[:, 0, :].T.copy()
    out[:, pt.kink | (nfac == 0)] = np.nan
    object.__setattr__(f, "stress", out)
    return f


def local_peak(f: SurfaceField, kind, candidates: np.ndarray
               ) -> tuple[float, tuple[float, float, float]]:
    """Peak of ``kind(stress)`` (von Mises or max principal of Voigt (6, k) stresses) over the
    candidate mesh nodes that the surface recovery covers: the largest node, then the maximum of
    ``kind`` of its patch's fitted polynomial over the disc of its own facets (a 9 × 16 polar
    grid). NaN when no candidate is covered."""
    sel = np.nonzero(np.isin(f.nodes, candidates))[0]
    vals = kind(f.stress[:, sel])
    good = np.isfinite(vals)
    if not good.any():
        return float("nan"), (float("nan"),) * 3
    j = sel[good][int(np.argmax(vals[good]))]
    c, h, t1, t2, _ = _fit(f, np.array([j]))
    pt = f.patches
    own = pt.facets[j][pt.mask[j]]
    i = pt.nodes[j]
    own = own[(pt.tri[:, own] == i).any(axis=0)]
    d = f.xyz[:, np.unique(pt.tri[:, own])].T - f.xyz[:, i]
    R = 0.5 * float(np.max(np.hypot(d @ t1[0], d @ t2[0]))) / float(h[0, 0])
    r, phi = np.meshgrid(np.linspace(0, R, 9), np.radians(np.arange(0, 360, 22.5)))
    a, b = (r * np.cos(phi)).ravel(), (r * np.sin(phi)).ravel()
    M = _basis(a[None], b[None], np.array([True]))[0]            # (g, 6)
    v = kind((M @ c[0]).T)
    g = int(np.argmax(v))
    p = f.xyz[:, i] + h[0, 0] * (a[g] * t1[0] + b[g] * t2[0])
    return float(v[g]), tuple(float(x) for x in p)
