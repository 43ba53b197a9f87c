"""Model-independent rotor-dynamics kernels: reduced modal basis, projection, reduced and
full-size quadratic eigenproblems, MAC tracking, whirl labels.

The Campbell sweep that chains them (and the critical speeds, step 5 below) is
``shaftfe.rotordynamics.campbell``; the Campbell plot is ``shaftfe.rotordynamics.plots``.

Works on any linear rotor model written in the stationary frame,

    M q̈ + (C + Ω G) q̇ + K q = 0,        G = −Gᵀ (gyroscopic matrix per unit spin speed),

given as dense or SciPy-sparse matrices on the free dofs (constraints already eliminated).
Units are the caller's; with K in N/mm and M in t, eigenvalues come out in rad/s.

Method
------
1. Reduced basis (once): the ``m`` lowest undamped modes Φ of (K, M), mass-normalised
   (Φᵀ M Φ = I, Φᵀ K Φ = diag ω²). Small dense models: ``scipy.linalg.eigh`` on a subset; large
   sparse ones: shift-invert Lanczos (``eigsh``, σ = ``sigma``; an ``OPinv`` built from a
   sparse Cholesky factor can be passed in). ``m`` starts at max(2 n, n + 8) for ``n`` requested
   modes and grows (×1.5) until the requested damped frequencies at the top speed change by
   less than ``tol`` (relative) between the chosen basis and the next larger one (this change
   is an estimate of the truncation error, measured 1-4× below the true error). With
   damping, the static residual vectors K⁻¹ C_j of the damped dofs are added (Rayleigh-Ritz):
   undamped modes alone converge slowly for damped modes (measured: a 196-dof rotor with
   1 N·s/mm bearings needed the full space without them, 24 modes + 4 residuals with them).
   The basis suits light damping; heavily damped (near-critical) modes need ``full_qep``.
2. Per speed: the projected quadratic eigenproblem s² I + s (C_r + Ω G_r) + diag ω² = 0 as a
   2m × 2m state-space eigenproblem (dense ``eig``). Eigenvalues s = −ζ|s| ± i ω_d; the damped
   natural frequency is ω_d = Im s > 0 (for C = 0 the undamped whirl frequency). Eigenvalues
   with |s| below ``1e-4 × ω_max`` of the basis are rigid-body modes and are dropped (counted).
   Optional speed-squared stiffness ``Kg`` (symmetric, e.g. the geometric stiffness of the
   centrifugal prestress, K_σ(Ω) = Ω² K_g): projected once, K_g,r = Φᵀ K_g Φ, and the reduced
   stiffness at speed Ω is diag ω² + Ω² K_g,r (without ``Kg`` the code path is unchanged).
3. Tracking: branches start from the n lowest modes at the first speed; at each next speed
   the candidates (n + 6 lowest) are assigned to the branches by maximising the modal
   assurance criterion MAC = |aᴴb|² / (aᴴa · bᴴb) of the reduced (modal-coordinate, hence
   mass-weighted) eigenvectors (Hungarian assignment, ``linear_sum_assignment``), with a small
   frequency-proximity tie-breaker. Within a degenerate cluster (equal frequencies, e.g. the
   pairs at Ω = 0 on isotropic bearings, where any combination of the pair is a mode) the MAC
   with the cluster's subspace is used and the cluster is handed out in frequency order. A
   smallest MAC below 0.8 into some speed is reported in the notes (refine the step).
4. Labels: the caller gives dof groups (e.g. lateral / torsional / axial) and pairs of lateral
   dofs (y, z). A mode belongs to the group holding more than half of its diag(M)-weighted
   squared amplitude ("mixed" otherwise). For lateral modes the whirl ratio

       r = −2 Σ Im(conj(y_k) z_k) / Σ (|y_k|² + |z_k|²)     (eigenvalue with Im s > 0)

   is +1 for a circular forward orbit (same sense as the spin about +x: from +y towards +z),
   −1 for a circular backward one and 0 for a straight-line (planar) orbit. |r| < ``whirl_tol``
   → "undetermined" (planar or mixed orbit, e.g. at Ω = 0 or with strongly anisotropic
   bearings). Labels: forward / backward / torsional / axial / undetermined. A branch's label
   is the most frequent one over the speeds Ω > 0. For a 3D solid model pass all nodes'
   (u_y, u_z) as the pairs: a torsion mode has r = 0 there (u_y, u_z in phase), so torsion vs
   planar bending must come from the groups (e.g. projections), not from r. At Ω = 0 the whirl
   sense is undefined: lateral modes at rest are "undetermined" (ratio 0).
5. Critical speeds: where a branch's frequency f(n) crosses the excitation line k·n/60 (k =
   engine order) between two speeds of the sweep (sign change of f − k n/60, linear
   interpolation; a branch touching the line at a grid speed counts too). The whirl label of
   a crossing is that of the nearer grid speed (never the one at rest).

Full-size check (``full_qep``): the same quadratic eigenproblem without reduction, as the
companion pencil A − s B, A = [[0, I], [−K, −D]], B = [[I, 0], [0, M]]; dense ``eig`` for small
models (the pencil balanced by s = w0 ŝ, w0² = max|K|/max|M|), otherwise shift-invert Arnoldi on
(A − σB)⁻¹B, which needs only a factorisation of K + σD + σ²M.

Pure functions; NumPy at module level, SciPy inside the functions.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from shaftfe.errors import InputError, SolverError
from shaftfe.util.units import omega

TWO_PI = 2.0 * math.pi
WHIRL_LABELS = ("forward", "backward", "torsional", "axial", "undetermined")
_DENSE_LIMIT = 2000          # dofs: dense symmetric eigen solver (basis) below, sparse above
_DENSE_QEP_LIMIT = 300       # dofs: dense QZ for the full-size check below, shift-invert above


def rpm_to_rad_s(rpm):
    return np.asarray(omega(rpm), dtype=float)


def _is_sparse(A) -> bool:
    import scipy.sparse as sp

    return sp.issparse(A)


# --------------------------------------------------------------------------- reduced basis

@dataclass(frozen=True, eq=False)
class ModalBasis:
    """Mass-normalised undamped modes of (K, M): Φ (n_dof, m), ω (m,) in rad/s."""
    Phi: np.ndarray
    omega: np.ndarray


def modal_basis(K, M, m: int, *, sigma: float = 0.0, opinv=None) -> ModalBasis:
    """The ``m`` lowest undamped modes of (K, M), mass-normalised."""
    n = K.shape[0]
    if not (1 <= m <= n):
        raise InputError("modal basis", "size", f"1..{n}", got=m)
    if not _is_sparse(K) and not _is_sparse(M) and n <= _DENSE_LIMIT:
        from scipy.linalg import LinAlgError, eigh

        Kd, Md = np.asarray(K), np.asarray(M)
        try:
            # A supported rotor has K positive definite: solve the inverted pencil M φ = μ K φ
            # (ω² = 1/μ), whose absolute error eps·μ_max is relative to the LOWEST modes. The
            # direct pencil's error is eps·ω_max², which a 1e12 N/mm bearing makes ~1e18.
            w2, Phi = _inverted_pencil(Kd, Md, m)
        except LinAlgError:
            try:                                   # free-free: K singular, use (K, M)
                w2, Phi = eigh(Kd, Md, subset_by_index=[0, m - 1])
            except LinAlgError as exc:
                raise SolverError("modal basis: mass matrix not positive definite "
                                  f"({exc})") from None
    else:
        import scipy.sparse as sp
        from scipy.sparse.linalg import eigsh

        Ks, Ms = sp.csc_matrix(K), sp.csc_matrix(M)
        k = min(m, n - 1)
        v0 = np.random.default_rng(0).standard_normal(n)   # reproducible (ARPACK's is random)
        w2, Phi = eigsh(Ks, k=k, M=Ms, sigma=sigma, which="LM", OPinv=opinv, v0=v0)
        order = np.argsort(w2)
        w2, Phi = w2[order], Phi[:, order]
    # mass-normalise (eigh already does; eigsh does too, but be explicit and cheap)
    mm = np.einsum("ij,ij->j", Phi, M @ Phi)
    Phi = Phi / np.sqrt(mm)
    omega = np.sqrt(np.clip(w2, 0.0, None))
    return ModalBasis(Phi=Phi, omega=omega)


def _m_orthonormal(X, V, MV, M, drop: float = 1e-10, project=None):
    """X made M-orthonormal and M-orthogonal to the M-orthonormal V (MV = M V): two passes of
    block classical Gram-Schmidt, then two passes of normalisation by the eigen-decomposition
    of the block's Gram matrix (one pass leaves ~ε·g_max/g_min of M-orthonormality; the second
    brings it to ~ε, as CholeskyQR2 does). Dropped: directions whose M-norm² is below ``drop``
    of the block's largest after the projection (the block is rank-deficient), and all of
    them when that largest is below (1e-12)² of the block's M-norm² before it (the block was
    in span V: the space is invariant). Not relative to the norms before the projection
    direction by direction: a Krylov block loses most of its norm to the converged directions
    by design (measured: that rule dropped one direction per block on x2_57 and forced a
    restart). ``project``: a map onto the constrained space (``block_shift_invert``), applied
    after each Gram-Schmidt pass (then M X is recomputed). Returns (X, M X)."""
    MX = M @ X
    g0 = float(np.max(np.einsum("ij,ij->j", X, MX))) if X.size else 0.0
    for _ in range(2):
        if V.shape[1]:
            C = MV.T @ X
            X = X - V @ C
            MX = MX - MV @ C
        if project is not None:
            X = project(X)
    if project is not None:
        MX = M @ X
    for k in range(2):
        G = X.T @ MX
        g, Q = np.linalg.eigh(0.5 * (G + G.T))
        top = float(g.max()) if g.size else 0.0
        if k == 0 and not top > 1e-24 * g0:
            return X[:, :0], MX[:, :0]
        keep = g > (drop * top if k == 0 else 0.0)
        Q = Q[:, keep] / np.sqrt(g[keep])
        X, MX = X @ Q, MX @ Q
    return X, MX


def block_shift_invert(K, M, solve, m: int, *, shift: float, block: int | None = None,
                       tol: float = 1e-6, max_dim: int | None = None, seed: int = 0,
                       max_restarts: int = 20, n_converged: int | None = None,
                       project=None):
    """The ``m`` lowest eigenpairs of K φ = ω² M φ by block shift-invert Lanczos with full
    M-reorthogonalisation and thick restarts: the Krylov space of S = (K + shift M)⁻¹ M grows
    by blocks, each block one multi-right-hand-side call ``solve(B)`` (B of shape (n, b)), so
    that a direct solver streams its factor once per block, not once per vector (ARPACK's
    ``eigsh`` asks for one vector at a time). ``solve`` may carry constraints (hard rows
    H q = 0): its results then span the constrained space, and so does every basis vector in
    exact arithmetic. Not in floating point: a new direction is the small remainder of a
    block after the Gram-Schmidt against V (a restart's residual S φ − θ φ is ~tol·θ of its
    terms), so normalising it multiplies the rounding of V's own constraint violation by
    1/remainder at every step. K (the Rayleigh-Ritz matrix) does not hold the hard rows, so a
    violating direction (e.g. a rigid twist the bearings hold) has no stiffness: it comes out
    as a spurious ω² ≈ 0 Ritz value and pollutes the restarts (measured on a two-disc solid
    rotor: |H V| grew ×3 per restart, 7e-7 → 350, and 36 modes never converged). Pass
    ``project`` (a map of a block onto the constrained space, e.g. the Euclidean projector
    on null H) to remove it after every Gram-Schmidt pass: the violation then stays at
    rounding level.

    Rayleigh-Ritz on K in the M-orthonormal basis V gives ω² and φ (so Φᵀ K Φ = diag ω² and
    Φᵀ M Φ = I hold to rounding whatever the convergence: a reduced model on Φ is a
    Rayleigh-Ritz model). The residual of a Ritz pair for S, ‖S φ − θ φ‖_M / θ
    (θ = 1/(ω² + shift)), comes exactly from S V, kept block by block (no extra solve), and
    must fall below ``tol`` for all m pairs; ω² is then in error by ~tol² relative (Rayleigh
    quotient). tol 1e-6: the residual floor of the solves is ~1e-7 on the higher modes of
    x2_57's rotor (measured), so a tighter tol can stall. Restart: the m + b lowest Ritz
    vectors (and their S images: S is linear) are kept, and the next block is the residual
    directions of the least converged pairs.
    Returns (ω² ascending (m,), Φ M-orthonormal (n, m), number of vectors solved)."""
    n = K.shape[0]
    b = block or max(4, min(16, math.ceil(m / 4)))
    # a restart keeps m + b vectors and must add a block of b: a smaller max_dim would
    # overflow the buffers (measured: m 36, b 9, max_dim 44 stopped with a broadcast error)
    d_max = max(max_dim or (2 * m + b), m + 2 * b)
    cap = d_max + b
    nc = m if n_converged is None else min(m, n_converged)
    V, MV, SV, KV = (np.empty((n, cap)) for _ in range(4))   # filled column by column
    rng = np.random.default_rng(seed)
    X = solve(M @ rng.standard_normal((n, b)))          # in the constrained space
    n_solved = b
    d = 0
    X, MX = _m_orthonormal(X, V[:, :0], MV[:, :0], M, project=project)
    res = np.full(m, np.inf)
    for _restart in range(max_restarts + 1):
        while True:
            k = X.shape[1]
            SX = solve(MX)
            n_solved += k
            V[:, d:d + k], MV[:, d:d + k], SV[:, d:d + k] = X, MX, SX
            KV[:, d:d + k] = K @ X
            d += k
            if d >= d_max:
                break
            X, MX = _m_orthonormal(SX, V[:, :d], MV[:, :d], M, project=project)
            if X.shape[1] == 0:                           # the space is invariant
                break
        A = V[:, :d].T @ KV[:, :d]
        w2, Y = np.linalg.eigh(0.5 * (A + A.T))             # V is M-orthonormal
        if w2.size < m:
            raise SolverError(f"block Lanczos: the space closed at {d} vectors, fewer than "
                              f"the {m} modes asked for")
        theta = 1.0 / (w2[:m] + shift)
        Phi = V[:, :d] @ Y[:, :m]
        R = SV[:, :d] @ Y[:, :m] - Phi * theta             # S φ − θ φ
        res = np.sqrt(np.abs(np.einsum("ij,ij->j", R, M @ R))) / np.abs(theta)
        if np.all(res[:nc] <= tol):
            return w2[:m], Phi, n_solved
        p = min(d, m + b)
        for buf in (V, MV, SV, KV):
            buf[:, :p] = buf[:, :d] @ Y[:, :p]
        d = p
        bad = np.argsort(-res[:nc])[:b]
        X, MX = _m_orthonormal(R[:, bad], V[:, :d], MV[:, :d], M, project=project)
        if X.shape[1] == 0:
            raise SolverError("block Lanczos: no new direction to restart with")
    raise SolverError(f"block Lanczos: {m} modes not converged to {tol:g} after "
                      f"{max_restarts} restarts (residuals up to {res.max():.2e})")


def _inverted_pencil(K: np.ndarray, M: np.ndarray, m: int):
    """The m lowest (ω², φ) of K φ = ω² M φ from M φ = μ K φ; raises LinAlgError when K is not
    positive definite (Cholesky of K fails, or a μ ≤ 0 would mean ω² ≤ 0)."""
    from scipy.linalg import LinAlgError, cho_factor, eigh

    cho_factor(K, check_finite=True)               # LinAlgError unless K is positive definite
    n = K.shape[0]
    mu, Phi = eigh(M, K, subset_by_index=[n - m, n - 1])
    if not np.all(mu > 0):
        raise LinAlgError("K not positive definite")
    return 1.0 / mu[::-1], Phi[:, ::-1]


@dataclass(frozen=True, eq=False)
class Reduced:
    """Projected matrices in the basis: K_r = diag ω², M_r = I, G_r, C_r (m × m); ``Kg`` the
    projected speed-squared stiffness Φᵀ K_g Φ (None: none), K_r(Ω) = diag ω² + Ω² Kg."""
    basis: ModalBasis
    G: np.ndarray
    C: np.ndarray
    Kg: np.ndarray | None = None

    @property
    def m(self) -> int:
        return self.basis.omega.size


def project(basis: ModalBasis, G=None, C=None, m: int | None = None, Kg=None) -> Reduced:
    Phi = basis.Phi if m is None else basis.Phi[:, :m]
    Phi = np.ascontiguousarray(Phi)        # a column slice would make matmul skip BLAS
    om = basis.omega if m is None else basis.omega[:m]
    k = Phi.shape[1]
    Gr = np.zeros((k, k)) if G is None else Phi.T @ (G @ Phi)
    Cr = np.zeros((k, k)) if C is None else Phi.T @ (C @ Phi)
    Kgr = None
    if Kg is not None:
        Kgr = Phi.T @ (Kg @ Phi)
        Kgr = 0.5 * (Kgr + Kgr.T)
    return Reduced(ModalBasis(Phi, om), 0.5 * (Gr - Gr.T), 0.5 * (Cr + Cr.T), Kgr)


def reduced_eig(red: Reduced, Omega: float, rigid_tol: float = 1e-4):
    """Eigenvalues s (Im s > 0, sorted by Im s) and reduced eigenvectors (m, k) at spin Ω
    [rad/s]; also the number of dropped rigid-body eigenvalues."""
    from scipy.linalg import eig

    m = red.m
    w2 = red.basis.omega**2
    A = np.zeros((2 * m, 2 * m))
    A[:m, m:] = np.eye(m)
    A[m:, :m] = -np.diag(w2)
    if red.Kg is not None:
        A[m:, :m] -= (Omega * Omega) * red.Kg
    A[m:, m:] = -(red.C + Omega * red.G)
    s, V = eig(A)
    return _select(s, V[:m], rigid_tol * max(float(red.basis.omega.max()), 1.0))


def _select(s, V, abs_tol):
    """Keep oscillatory eigenvalues with Im s > 0, drop rigid ones, sort by Im s."""
    rigid = np.abs(s) < abs_tol
    keep = (~rigid) & (s.imag > 1e-9 * np.abs(s))
    order = np.argsort(s.imag[keep])
    idx = np.flatnonzero(keep)[order]
    n_rigid = int(np.count_nonzero(rigid)) // 2 if np.any(rigid) else 0
    return s[idx], V[:, idx], n_rigid


def ritz(K, M, V: np.ndarray) -> ModalBasis:
    """Rayleigh-Ritz on span(V): mass-normalised modes of the projected (K, M)."""
    from scipy.linalg import eigh, qr

    Q, _ = qr(V, mode="economic")
    Kr = Q.T @ (K @ Q)
    Mr = Q.T @ (M @ Q)
    w2, X = eigh(0.5 * (Kr + Kr.T), 0.5 * (Mr + Mr.T))
    return ModalBasis(Phi=Q @ X, omega=np.sqrt(np.clip(w2, 0.0, None)))


def damper_residuals(K, C) -> np.ndarray | None:
    """Static residual vectors K⁻¹ C_j of the damped dofs j (None without damping or if K is
    singular). Added to the undamped modes they let a small basis represent the local
    deformation at the dampers (modal truncation alone converges slowly for damped modes)."""
    if C is None:
        return None
    import scipy.sparse as sp

    Cc = sp.csc_matrix(C)
    cols = np.flatnonzero(np.diff(Cc.indptr) > 0)
    if cols.size == 0:
        return None
    F = Cc[:, cols].toarray()
    try:
        if _is_sparse(K):
            from scipy.sparse.linalg import splu

            R = splu(sp.csc_matrix(K)).solve(F)
        else:
            from scipy.linalg import cho_factor, cho_solve

            R = cho_solve(cho_factor(np.asarray(K)), F)
    except (np.linalg.LinAlgError, RuntimeError, ValueError):
        return None
    return R if np.all(np.isfinite(R)) else None


def choose_basis(K, M, G, C, n_modes: int, Omega_max: float, *, tol: float = 1e-6,
                 sigma: float = 0.0, opinv=None, m0: int | None = None, basis_fn=None,
                 residuals=None, Kg=None):
    """Basis size whose requested damped frequencies at Ω_max change < ``tol`` (relative)
    when the basis grows by ×1.5 (with the speed-squared stiffness Ω_max² ``Kg``, if any).
    With damping, the damped dofs' static residual vectors K⁻¹ C_j are added to the modes
    (Rayleigh-Ritz). Returns (Reduced for the chosen size, measured change, number of
    rigid-body eigenvalues dropped).

    Large models (``shaftfe.rotordynamics.solid_rotor``): ``basis_fn(m)`` returns the ``m`` lowest
    mass-normalised modes (a cached shift-invert solver) instead of ``modal_basis``, and
    ``residuals`` the damping residual vectors instead of ``damper_residuals``; K may then
    be a LinearOperator (only K @ X is used)."""
    n = K.shape[0]
    m = min(n, m0 if m0 else max(2 * n_modes, n_modes + 6))
    R = damper_residuals(K, C) if residuals is None else residuals
    nr_extra = 0 if R is None else R.shape[1]
    while True:
        m_big = min(n, max(m + 4, math.ceil(1.5 * m)))
        basis = (modal_basis(K, M, m_big, sigma=sigma, opinv=opinv) if basis_fn is None
                 else basis_fn(m_big))
        if R is not None and m_big + nr_extra < n:
            big = ritz(K, M, np.hstack([basis.Phi, R]))
            small = ritz(K, M, np.hstack([basis.Phi[:, :m], R]))
            red_big, red = project(big, G, C, Kg=Kg), project(small, G, C, Kg=Kg)
        else:
            red_big = project(basis, G, C, Kg=Kg)
            red = Reduced(ModalBasis(np.ascontiguousarray(basis.Phi[:, :m]),  # a sub-block
                                     basis.omega[:m]),
                          red_big.G[:m, :m], red_big.C[:m, :m],
                          None if red_big.Kg is None else red_big.Kg[:m, :m])
        s1, _, nr = reduced_eig(red, Omega_max)
        s2, _, _ = reduced_eig(red_big, Omega_max)
        k = min(n_modes, s1.size, s2.size)
        if k == 0:
            raise SolverError("Campbell: the model has no oscillatory modes")
        change = float(np.max(np.abs(s1.imag[:k] - s2.imag[:k]) / s2.imag[:k]))
        if change < tol or m_big == n:
            if m_big == n:           # the big basis is the full space: use it, exact
                return red_big, 0.0, nr
            return red, change, nr
        m = m_big


# --------------------------------------------------------------------------- tracking & labels

def mac(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """Modal assurance criterion between the columns of A and B (complex allowed)."""
    num = np.abs(A.conj().T @ B) ** 2
    na = np.einsum("ij,ij->j", A.conj(), A).real
    nb = np.einsum("ij,ij->j", B.conj(), B).real
    return num / np.outer(na, nb)


def assign(prev_vecs, prev_f, cand_vecs, cand_f):
    """Indices into the candidates for each previous branch (MAC with a frequency
    tie-breaker)."""
    from scipy.optimize import linear_sum_assignment

    Mc = mac(prev_vecs, cand_vecs)
    df = np.abs(prev_f[:, None] - cand_f[None, :]) / np.maximum(prev_f[:, None], 1e-30)
    cost = -Mc + 1e-3 * df
    # degenerate clusters (equal frequencies, e.g. isotropic pairs at rest): any combination
    # of the cluster is a mode, so use the subspace MAC and hand the cluster's candidates out
    # in frequency order (lower branch index -> lower frequency)
    order = np.argsort(prev_f)
    fs = prev_f[order]
    start = 0
    fscale = max(float(np.max(np.abs(cand_f))), 1e-30)
    for k in range(1, fs.size + 1):
        if k == fs.size or fs[k] - fs[k - 1] > 1e-7 * max(abs(fs[k]), 1e-30):
            cl = np.sort(order[start:k])
            if cl.size > 1:
                Qc, _ = np.linalg.qr(prev_vecs[:, cl])
                num = np.sum(np.abs(Qc.conj().T @ cand_vecs) ** 2, axis=0)
                den = np.einsum("ij,ij->j", cand_vecs.conj(), cand_vecs).real
                smac = num / den
                for rank, b in enumerate(cl):
                    Mc[b] = smac
                    cost[b] = -smac + 1e-3 * df[b] - 1e-6 * rank * cand_f / fscale
            start = k
    rows, cols = linear_sum_assignment(cost)
    out = np.empty(prev_vecs.shape[1], dtype=int)
    out[rows] = cols
    return out, Mc[rows, cols]


def whirl_ratio(vecs: np.ndarray, iy: np.ndarray, iz: np.ndarray) -> np.ndarray:
    """r = −2 Σ Im(conj(y) z) / Σ(|y|² + |z|²) per column (eigenvalue with Im s > 0):
    +1 circular forward, −1 circular backward, 0 planar."""
    y, z = vecs[iy], vecs[iz]
    num = -2.0 * np.sum(np.imag(np.conj(y) * z), axis=0)
    den = np.sum(np.abs(y) ** 2 + np.abs(z) ** 2, axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(den > 0, num / np.where(den > 0, den, 1.0), 0.0)


@dataclass(frozen=True, eq=False)
class Labelling:
    """How to label the modes of a model: dof groups (name → indices into the free dofs; the
    group named "lateral" gets forward/backward), the lateral (y, z) dof pairs for the whirl
    ratio (translations), and optional alternative pairs with the z sign (e.g. tilts
    (θ_z, −θ_y)) used when the first pairs carry no motion; weights = diag(M). With
    ``transform`` (a matrix F, e.g. the beam-like section motions of a 3D solid), the labels
    are computed on F v instead of v, and groups, pairs and weights refer to F's rows."""
    groups: Mapping[str, np.ndarray]
    pair_y: np.ndarray
    pair_z: np.ndarray
    weights: np.ndarray | None = None
    whirl_tol: float = 0.05
    transform: object | None = None     # (n_feat, n_dof) map applied to the vectors first


def label_modes(vecs: np.ndarray, lab: Labelling):
    """(family per column, whirl label per column, whirl ratio per column)."""
    if lab.transform is not None:
        vecs = lab.transform @ vecs
    w = np.ones(vecs.shape[0]) if lab.weights is None else lab.weights
    e = (np.abs(vecs) ** 2) * w[:, None]
    tot = e.sum(axis=0)
    fam, whirl = [], []
    r = whirl_ratio(vecs, lab.pair_y, lab.pair_z)
    fracs = {g: e[np.asarray(idx, dtype=int)].sum(axis=0) / np.where(tot > 0, tot, 1.0)
             for g, idx in lab.groups.items()}
    for j in range(vecs.shape[1]):
        best = max(fracs, key=lambda g: fracs[g][j]) if fracs else "mixed"
        f = best if fracs and fracs[best][j] > 0.5 else "mixed"
        fam.append(f)
        if f == "lateral":
            whirl.append("forward" if r[j] >= lab.whirl_tol else
                         "backward" if r[j] <= -lab.whirl_tol else "undetermined")
        elif f in ("torsional", "axial"):
            whirl.append(f)
        else:
            whirl.append("undetermined")
    return fam, whirl, r


# --------------------------------------------------------------------------- full-size check

def full_qep(K, M, G, Omega: float, n_modes: int, *, C=None, sigma: float = 0.0):
    """The ``n_modes`` lowest oscillatory eigenvalues (Im s > 0) of the full quadratic
    eigenproblem at spin Ω [rad/s], without reduction."""
    n = K.shape[0]
    D = Omega * G if C is None else C + Omega * G
    if not _is_sparse(K) and n <= _DENSE_QEP_LIMIT:
        from scipy.linalg import eig

        Kd, Md, Dd = (np.asarray(X.toarray() if _is_sparse(X) else X, float) for X in (K, M, D))
        # balance the pencil: s = w0 ŝ with w0² = |K|/|M| (K ~ 1e5 N/mm, M ~ 1e-9 t otherwise)
        w0 = math.sqrt(np.abs(Kd).max() / np.abs(Md).max())
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-Kd / w0**2, -Dd / w0]])
        B = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), Md]])
        s = w0 * eig(A, B, right=False)
        s = s[np.isfinite(s)]
    else:
        import scipy.sparse as sp
        from scipy.sparse.linalg import LinearOperator, eigs, splu

        Ks, Ms, Ds = (sp.csc_matrix(X) for X in (K, M, D))
        lu = splu((Ks + sigma * Ds + sigma**2 * Ms).tocsc())

        def op(y):
            y1, y2 = y[:n], y[n:]
            rhs = Ms @ y2 + Ds @ y1 + sigma * (Ms @ y1)
            x1 = -lu.solve(np.asarray(rhs, dtype=lu.L.dtype) if not np.iscomplexobj(rhs)
                           else rhs)
            return np.concatenate([x1, y1 + sigma * x1])

        k = min(2 * n - 2, 2 * n_modes + 8)
        v0 = np.random.default_rng(0).standard_normal(2 * n)   # reproducible (ARPACK's
        mu = eigs(LinearOperator((2 * n, 2 * n), matvec=op, dtype=float), k=k,  # own is random)
                  which="LM", return_eigenvectors=False, v0=v0)
        s = sigma + 1.0 / mu
    om_scale = float(np.max(np.abs(s))) if s.size else 1.0
    keep = (np.abs(s) > 1e-9 * om_scale) & (s.imag > 1e-9 * np.abs(s))
    s = s[keep]
    s = s[np.argsort(s.imag)]
    return s[:n_modes]
