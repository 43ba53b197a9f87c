"""Solves with the 3D solid rotor's shifted matrix (``ShiftedSolver``): one sparse
factorisation per shift and a low-rank Woodbury correction for the support terms and the
hard rows (method: ``shaftfe.rotordynamics.solid_rotor`` module docstring, "Solution").
"""

from __future__ import annotations

import time

import numpy as np

from shaftfe.fe.lowrank import LowRankSolver
from shaftfe.rotordynamics.solid_rotor import SolidRotor


class ShiftedSolver:
    """Solves (K_tot + σ D + σ² M) x = b with the hard rows H x = 0 (D = C + Ω G), by one
    sparse factorisation of B = K + σ Ω G + σ² M (+ σ C of nothing: damping is low rank)
    and a Woodbury correction with the support terms. ``K_extra``: a sparse stiffness added
    to K (the prestress Ω² K_g of ``full_qep``). ``damped=False``: D = Ω G only, so that at
    Ω = 0 the solve is exactly (K + σ² M)⁻¹ (the undamped modal basis and its residual
    vectors)."""

    def __init__(self, rotor: SolidRotor, sigma: float, Omega: float = 0.0,
                 method: str | None = None, K_extra=None, damped: bool = True):
        from shaftfe.fe import solvers

        t0 = time.perf_counter()
        B = (rotor.K_sparse + (sigma * sigma) * rotor.M_sparse).tocsr()
        if K_extra is not None:
            B = (B + K_extra).tocsr()
        method = rotor.options.solver if method is None else method
        if Omega != 0.0 and sigma != 0.0:
            B = (B + (sigma * Omega) * rotor.G_sparse).tocsr()
            self._fac = solvers.factorize_unsymmetric(B, method)
        else:
            self._fac = solvers.factorize(B, _auto_method(method))
        self.name = self._fac.name
        self.factor_seconds = time.perf_counter() - t0
        U, Cinv = [], []
        if sigma != 0.0:
            for b in rotor.body_terms:          # σ² M_b + σ Ω G_b on the body's rows
                U.append(b.R.T)
                Cinv.append(np.linalg.inv(sigma * sigma * b.M6 + sigma * Omega * b.G6))
        for t in rotor.terms:
            U.append(t.R.T)
            r = t.R.shape[0]
            if t.C is None:
                Cinv.append(np.zeros((r, r)))
            else:
                Ct = t.C + (sigma * t.Cd if t.Cd is not None and damped else 0.0)
                Cinv.append(np.linalg.inv(Ct))
        self.n = B.shape[0]
        self.n_solves = 0
        if U:
            from scipy.linalg import block_diag

            self._lr = LowRankSolver(self._fac, np.hstack(U), block_diag(*Cinv),
                                     hint="a support is missing or redundant")
            self.cond_S = self._lr.cond_S
        else:
            self._lr = None
            self.cond_S = 1.0
        hard = [t.R for t in rotor.terms if t.C is None]
        self._hard_Q = np.linalg.qr(np.vstack(hard).T)[0] if hard else None
        self.seconds = time.perf_counter() - t0

    def project(self, X):
        """X projected (Euclidean) on the null space of the hard rows H: X − Q Qᵀ X, Q an
        orthonormal basis of range Hᵀ. Every solve's result lies there already; this removes
        the rounding a Gram-Schmidt remainder carries out of it (``kernels.block_shift_invert``)."""
        if self._hard_Q is None:
            return X
        Q = self._hard_Q
        return X - Q @ (Q.T @ X)

    def solve(self, b):
        b = np.asarray(b)
        if np.iscomplexobj(b):
            return self.solve(b.real) + 1j * self.solve(b.imag)
        self.n_solves += 1 if b.ndim == 1 else b.shape[1]
        y = self._fac.solve(b)
        if self._lr is None:
            return y
        return self._lr.correct(y.reshape(self.n, -1))[0].reshape(y.shape)


def _auto_method(method: str) -> str:
    """``auto`` for the symmetric factorisation: PARDISO when installed, else SuperLU. The
    basis is solved in blocks (``kernels.block_shift_invert``), where a multi-right-hand-side
    solve costs little more than one, so PARDISO's faster factorisation wins (x2_57 coarse,
    84k dofs: 1.5 s against SuperLU's 4.6 s; reports/benchmarks/rotor_solid.md). A matrix
    made indefinite by a compressive prestress falls back to PARDISO's symmetric indefinite
    factorisation (``solvers._Pardiso``)."""
    if method != "auto":
        return method
    from shaftfe.fe import solvers
    return "pardiso" if solvers.available()["pardiso"] else "superlu"
