"""Assembly and solution of the harmonic problems on one meridian mesh.

``Harmonics(mesh, E, nu)`` assembles the three matrices K00, K01 + K01ᵀ, K11 once
(``kernels``); ``K(n)`` is then a linear combination. Dofs: (U_x, U_r, U_θ) per node,
interleaved. Axis conditions (regularity of the 3D field on r = 0), applied by elimination
(``reduction``): n = 0: U_r = U_θ = 0; n = 1: U_x = 0 and U_θ = −U_r (a lateral translation is
U_r = −U_θ); n ≥ 2: U_x = U_r = U_θ = 0.

``solve(K, F, springs, hard, T)`` solves one (coupled) harmonic system with springs (rows R, a
k×k stiffness C: energy ½ (R u)ᵀ C (R u)) and hard rows H u = 0 (Lagrange multipliers) by a
sparse LU of the saddle-point matrix, one factorisation for all right-hand sides.

``Rbe3`` gives the remote-point rows of a seat (the area-weighted least-squares rigid motion of
the seat face, as ``fe.assembly.rigid_rows`` does in 3D): on a full surface of revolution the six
rigid modes split by harmonic: u_x and θ_x live in n = 0, (u_y, θ_z) in the symmetric n = 1
part and (u_z, θ_y) in the antisymmetric one with the same rows (θ_y = −θ_z's functional).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from shaftfe.axisymmetric import kernels as kn
from shaftfe.errors import SolverError
from shaftfe.fe import reuse
from shaftfe.util import cachefile, paths

CHUNK = 4000                # elements per assembly block (memory ~ CHUNK × 25 × 6 × 18 × 8 B × 4)


def weight(n: int) -> float:
    """∫ cos² nθ dθ over a revolution (2π for n = 0, π otherwise)."""
    return 2 * math.pi if n == 0 else math.pi


@dataclass(frozen=True, eq=False)
class Harmonics:
    mesh: object
    E: float
    nu: float
    K00: sp.csr_matrix = field(repr=False)
    K01: sp.csr_matrix = field(repr=False)     # K01 + K01ᵀ
    K11: sp.csr_matrix = field(repr=False)
    seconds: float = 0.0

    @property
    def ndof(self) -> int:
        return 3 * self.mesh.n_nodes

    def K(self, n: int) -> sp.csr_matrix:
        a, b, c = self.K00, self.K01, self.K11
        w = weight(n)
        if (a.indptr is b.indptr is c.indptr) or (
                np.array_equal(a.indptr, b.indptr) and np.array_equal(a.indptr, c.indptr)
                and np.array_equal(a.indices, b.indices)
                and np.array_equal(a.indices, c.indices)):     # one pattern: combine the data
            return sp.csr_matrix((w * (a.data + n * b.data + (n * n) * c.data),
                                  a.indices.copy(), a.indptr.copy()), shape=a.shape)
        return (w * (a + n * b + (n * n) * c)).tocsr()

    def reduction(self, n: int) -> sp.csr_matrix:
        """T (ndof × nred): u = T û with the axis conditions of harmonic n built in."""
        N = self.mesh.n_nodes
        axis = np.zeros(N, dtype=bool)
        axis[self.mesh.axis_nodes()] = True
        keep = np.ones((N, 3), dtype=bool)
        if n == 0:
            keep[axis, 1:] = False
        elif n == 1:
            keep[axis, 0] = False
            keep[axis, 2] = False               # U_θ = −U_r: a slave of U_r
        else:
            keep[axis] = False
        cols = -np.ones(3 * N, dtype=np.int64)
        kept = np.nonzero(keep.ravel())[0]
        cols[kept] = np.arange(kept.size)
        rows, cc, vals = list(kept), list(cols[kept]), [1.0] * kept.size
        if n == 1:
            ax = np.nonzero(axis)[0]
            rows += list(3 * ax + 2)
            cc += list(cols[3 * ax + 1])
            vals += [-1.0] * ax.size
        return sp.csr_matrix((vals, (rows, cc)), shape=(3 * N, kept.size))

    # ------------------------------------------------------------------ boundary terms

    def edge_coords(self, edge_ids: np.ndarray):
        m = self.mesh
        e = m.edges[:, edge_ids]
        return e, m.xr[0][e].T, m.xr[1][e].T

    def traction_vector(self, edge_ids, traction, n: int) -> np.ndarray:
        """Load vector (ndof,) of a traction with amplitudes ``traction(x, r)`` -> (T_x, T_r,
        T_θ) on the edges, for harmonic n (the weight w_n included)."""
        f = np.zeros(self.ndof)
        if len(edge_ids) == 0:
            return f
        e, X, R = self.edge_coords(np.asarray(edge_ids))
        fe = kn.edge_load(X, R, traction)               # (m, 3, 3)
        for c in range(3):
            np.add.at(f, 3 * e.T.ravel() + c, fe[:, :, c].ravel())
        return weight(n) * f


    def body_vector(self, b, n: int) -> np.ndarray:
        """Load vector (ndof,) of a constant body-force amplitude b = (b_x, b_r, b_θ) (N/mm³)
        over the whole meridian, harmonic n (the weight w_n included)."""
        m = self.mesh
        fe = kn.body_load(m.xr[0][m.tri].T, m.xr[1][m.tri].T, b)        # (ne, 6, 3)
        f = np.zeros(self.ndof)
        for c in range(3):
            np.add.at(f, 3 * m.tri.T.ravel() + c, fe[:, :, c].ravel())
        return weight(n) * f


ASSEMBLY_CACHE_FORMAT = 1


def assembly_key(mesh, E: float, nu: float) -> str:
    """Content key of the assembled matrices: the mesh's key, E, ν and the source of the
    element kernels and of this module (a change of the code is never served stale)."""
    import hashlib
    import json
    from pathlib import Path
    src = hashlib.sha256()
    for mod in (kn.__file__, __file__):
        src.update(Path(mod).read_bytes())
    for a in (mesh.xr, mesh.tri):          # the arrays themselves: a regenerated mesh that
        src.update(np.ascontiguousarray(a).tobytes())   # numbers its nodes differently misses
    text = json.dumps({"mesh": mesh.key, "E": repr(float(E)), "nu": repr(float(nu)),
                       "code": src.hexdigest(), "format": ASSEMBLY_CACHE_FORMAT})
    return hashlib.sha256(text.encode()).hexdigest()


def assemble(mesh, E: float, nu: float, *, cache_dir=None, use_cache: bool = True) -> Harmonics:
    """K00, K01 + K01ᵀ, K11 of ``mesh``. Cached as ``axik-<key>.npz`` (one sparsity pattern,
    three data arrays; ``util.cachefile``) when the mesh has a content key (a mesh from
    ``mesh.mesh_geometry``): loading costs a fifth of assembling. Inside ``fe.reuse``'s scope
    (several speeds with spin softening, fatigue's unsoftened solve, a study's designs) the
    matrices of one key are made or loaded once and shared."""
    if use_cache and mesh.key and reuse.active():
        key = assembly_key(mesh, E, nu)
        return reuse.memo("axisymmetric assembly", (key,),
                          lambda: _assemble(mesh, E, nu, key, cache_dir))
    return _assemble(mesh, E, nu, assembly_key(mesh, E, nu) if use_cache and mesh.key
                     else None, cache_dir)


def _assemble(mesh, E: float, nu: float, key: str | None, cache_dir) -> Harmonics:
    """``assemble``: from the cache file of ``key`` when there is one, else assembled (and
    saved under ``key``; None: no cache)."""
    import time
    from pathlib import Path

    t0 = time.perf_counter()
    N = mesh.n_nodes
    shape = (3 * N, 3 * N)
    path = None
    if key is not None:
        path = Path(paths.cache_dir(cache_dir)) / f"axik-{key[:24]}.npz"
        if path.exists():
            got = cachefile.load(path, key, "axisymmetric assembly")
            if got is not None:
                z, _ = got
                mats = [sp.csr_matrix((z[k], z["indices"], z["indptr"]), shape=shape,
                                      copy=False) for k in ("K00", "K01", "K11")]
                return Harmonics(mesh, E, nu, *mats, seconds=time.perf_counter() - t0)
    D = kn.elasticity_matrix(E, nu)
    parts = [[], [], []]
    dof = (3 * mesh.tri.T[:, :, None] + np.arange(3)).reshape(-1, 18)     # (ne, 18)
    for a in range(0, mesh.n_elements, CHUNK):
        t = mesh.tri[:, a:a + CHUNK]
        K00, K01, K11 = kn.stiffness_blocks(mesh.xr[0][t].T, mesh.xr[1][t].T, D)
        parts[0].append(K00.ravel())
        parts[1].append((K01 + K01.transpose(0, 2, 1)).ravel())
        parts[2].append(K11.ravel())
    rows = np.repeat(dof, 18, axis=1).ravel()
    cols = np.tile(dof, (1, 18)).ravel()
    mats = [sp.csr_matrix((np.concatenate(p), (rows, cols)), shape=shape) for p in parts]
    same = all(np.array_equal(m.indptr, mats[0].indptr)
               and np.array_equal(m.indices, mats[0].indices) for m in mats[1:])
    if same:                               # one pattern held once, as when loaded
        mats = [mats[0]] + [sp.csr_matrix((m.data, mats[0].indices, mats[0].indptr),
                                          shape=shape, copy=False) for m in mats[1:]]
    if path is not None and same:          # one pattern (the same rows and columns summed)
        try:
            cachefile.save(path, {"indptr": mats[0].indptr, "indices": mats[0].indices,
                                  "K00": mats[0].data, "K01": mats[1].data,
                                  "K11": mats[2].data},
                           {"key": key, "format": ASSEMBLY_CACHE_FORMAT})
        except OSError:
            pass                           # a read-only cache only costs the write
    return Harmonics(mesh, E, nu, *mats, seconds=time.perf_counter() - t0)


# ---------------------------------------------------------------------- remote points


@dataclass(frozen=True, eq=False)
class Rbe3:
    """Remote-point rows of one seat (functionals on one harmonic's dof vector):
    ``ux``, ``tx`` on n = 0; ``uy``, ``tz`` on the symmetric n = 1 part (the antisymmetric part
    gives u_z = ``uy`` · V and θ_y = −``tz`` · V)."""
    x_mm: float
    ux: np.ndarray
    tx: np.ndarray
    uy: np.ndarray
    tz: np.ndarray

    def load(self, F, M) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Nodal forces of a remote load: force F (N) and moment M (N·mm) about (x_mm, 0, 0)
        through this band, as the transpose of its averaging rows times [F; M] (RBE3: F and M
        carried exactly, the band free to deform): (n = 0, n = 1 symmetric, n = 1
        antisymmetric); u_z = ``uy`` · V and θ_y = −``tz`` · V in the antisymmetric part."""
        return (F[0] * self.ux + M[0] * self.tx, F[1] * self.uy + M[2] * self.tz,
                F[2] * self.uy - M[1] * self.tz)


def rbe3(h: Harmonics, edge_ids, x_c: float) -> Rbe3:
    """Least-squares rigid motion of the seat (area inner product), per harmonic part."""
    e, X, R = h.edge_coords(np.asarray(edge_ids))

    def scatter(rows):
        out = np.zeros((rows.shape[0], h.ndof))
        for k in range(rows.shape[0]):
            for c in range(3):
                np.add.at(out[k], 3 * e.T.ravel() + c, rows[k, :, :, c].ravel())
        return out

    zero, one = 0.0, 1.0
    # n = 0: u_x mode (1, 0, 0); θ_x mode (0, 0, r)  (Gram diagonal: they do not couple)
    rows0, g0 = kn.edge_moments(X, R, [lambda x, r: (one, zero, zero),
                                       lambda x, r: (zero, zero, r)])
    r0 = scatter(rows0)
    ux, tx = r0[0] / g0[0, 0], r0[1] / g0[1, 1]
    # n = 1 symmetric: u_y mode amplitudes (0, 1, −1); θ_z mode (−r, x − c, −(x − c))
    rows1, g1 = kn.edge_moments(X, R, [lambda x, r: (zero, one, -one),
                                       lambda x, r: (-r, x - x_c, -(x - x_c))])
    r1 = np.linalg.solve(g1, scatter(rows1))
    return Rbe3(float(x_c), ux, tx, r1[0], r1[1])


# ---------------------------------------------------------------------- the solve


@dataclass(frozen=True, eq=False)
class Solution:
    u: np.ndarray                 # (ndof, nrhs) full dof vectors
    multipliers: np.ndarray       # (n_hard, nrhs): forces of the hard rows (on the rows' sense)
    relres: float                 # the largest backward error (``backward_error``)
    matrix: sp.spmatrix = field(default=None, repr=False)   # the factorised (saddle) matrix


def _norm(A) -> float:
    return float(abs(A).sum(axis=1).max()) if A.shape[0] and A.shape[1] else 0.0


def _amax(a) -> float:
    return float(np.abs(a).max()) if np.size(a) else 0.0


def backward_error(M, z: np.ndarray, b: np.ndarray, r: np.ndarray, n_u: int | None = None
                   ) -> float:
    """Normwise backward error of r = M z − b, block by block when z = [u; μ] stacks n_u
    displacements (mm) and multipliers (N) of a saddle point [[A, Hᵀ], [H, 0]]: the
    equilibrium rows ‖r_u‖ / (‖A‖ ‖u‖ + ‖Hᵀ‖ ‖μ‖ + ‖b_u‖), the constraint rows
    ‖r_c‖ / (‖H‖ ‖u‖) (∞-norms), the larger of the two (Higham, Accuracy and Stability of
    Numerical Algorithms, 2nd ed., Thm. 7.1, applied per block so that mm and N do not mix).
    A stable direct solve keeps it at O(eps) whatever the conditioning; ‖r‖ / ‖b‖ alone does
    not: a rigid motion on soft springs makes ‖A‖ ‖u‖ ≫ ‖b‖, and the residual's own rounding
    then exceeds any fixed bound. (Columns are checked together.)"""
    M = sp.csr_matrix(M)
    n = M.shape[0]
    n_u = n if n_u is None else n_u
    u, mu = z[:n_u], z[n_u:]
    A, Ht = M[:n_u, :n_u], M[:n_u, n_u:]
    den = _norm(A) * _amax(u) + _norm(Ht) * _amax(mu) + _amax(b[:n_u])
    err = _amax(r[:n_u]) / den if den > 0 else 0.0
    if n_u < n:
        dc = _norm(M[n_u:, :n_u]) * _amax(u) + _amax(b[n_u:])
        err = max(err, _amax(r[n_u:]) / dc if dc > 0 else 0.0)
    return err


def _matrix_key(M: sp.spmatrix, spd: bool) -> tuple:
    """The content of the CSC matrix ``M`` and how it is factorised, hashed (a few ms at
    x2_57's default: 0.3–0.6 million entries): the key of its factorisation in ``fe.reuse``."""
    import hashlib
    M = sp.csc_matrix(M)
    h = hashlib.sha256(f"{M.shape}|{spd}|{M.has_sorted_indices}|{M.dtype}|"
                       f"{M.indices.dtype}".encode())
    for a in (M.indptr, M.indices, M.data):
        h.update(np.ascontiguousarray(a).tobytes())
    return (h.hexdigest(),)


def solve(K: sp.spmatrix, F: np.ndarray, T: sp.spmatrix, springs=(), hard=None, *,
          keep: str | None = None) -> Solution:
    """Minimise ½ uᵀ K u + ½ Σ (R u)ᵀ C (R u) − uᵀ F with u = T û and H u = 0.

    ``springs``: (R (k × ndof), C (k × k)); ``hard``: H (h × ndof) or None. The saddle-point
    matrix [[Tᵀ(K + Σ RᵀCR)T, (H T)ᵀ], [H T, 0]] is factorised once (SuperLU), one step of
    iterative refinement follows; the blockwise normwise backward error of every right-hand side
    (``backward_error``) is checked (1e-9, SolverError beyond: also what a singular system
    without pivoting gives)."""
    from scipy.sparse.linalg import splu
    F = np.atleast_2d(np.asarray(F, dtype=float).T).T
    A = K
    for R, C in springs:
        Rs = sp.csr_matrix(R)
        A = A + Rs.T @ sp.csr_matrix(np.asarray(C, dtype=float)) @ Rs
    Ar = (T.T @ A @ T).tocsc()
    nh = 0 if hard is None else hard.shape[0]
    if nh:
        Hr = sp.csr_matrix(hard) @ T
        M = sp.bmat([[Ar, Hr.T], [Hr, None]], format="csc")
    else:
        M = Ar
    rhs = np.vstack([T.T @ F, np.zeros((nh, F.shape[1]))])
    spd = not nh and all(np.array_equal(np.asarray(C), np.asarray(C).T) for _, C in springs)

    def factorise():
        try:
            # symmetric positive definite (no hard rows, symmetric springs): a symmetric
            # ordering and no pivoting (stable for SPD; measured 20 % faster and 30 % less fill
            # than COLAMD on x2_57); a saddle point (zero diagonal block) or a non-symmetric
            # spring keeps COLAMD with partial pivoting
            return splu(M, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                        options={"SymmetricMode": True}) if spd else \
                splu(M, permc_spec="COLAMD")
        except RuntimeError as exc:
            raise SolverError(f"the harmonic system is singular ({exc}): a rigid motion is not "
                              "held by the supports") from None
    # ``keep``: the kind under which ``fe.reuse`` shares this factorisation inside its scope
    # (a second speed with spin softening, a low-rank term, and fatigue's unsoftened solve
    # then factorise nothing again; the same factor, so the same bits)
    lu = reuse.memo(keep, _matrix_key(M, spd), factorise) if keep and reuse.active() \
        else factorise()
    z = lu.solve(rhs)
    z += lu.solve(rhs - M @ z)       # one step of iterative refinement (soft springs: a
    res = M @ z - rhs                # rigid motion on them makes the system ill-conditioned)
    relres = backward_error(M, z, rhs, res, Ar.shape[0])
    if not np.all(np.isfinite(z)) or relres > 1e-9:
        raise SolverError(f"the harmonic solve did not converge (relative residual "
                          f"{relres:.2e}): a rigid motion may not be held by the supports")
    u = T @ z[:Ar.shape[0]]
    return Solution(u, z[Ar.shape[0]:], relres, M)
