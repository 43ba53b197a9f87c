"""The supported solve: one sparse factorisation of B plus a low-rank (Woodbury) correction.

Every 3D model in shaftfe (the static shaft, the solid rotor at each shift) solves

    [ B   U  ] [x]   [f]
    [ Uᵀ −C⁻¹] [λ] = [g]

where B is the sparse FE matrix (made non-singular by pins or a shift), and the columns of U
are the few support rows (a bearing's 6 seat dofs, a body's rigid motion, the pins) with the
block-diagonal compliance C⁻¹ (zero for a rigid row). With Z = B⁻¹ U computed once, the
capacitance S = C⁻¹ + Uᵀ Z is a small dense matrix, and

    λ = S⁻¹ (Uᵀ B⁻¹ f − g),   x = B⁻¹ f − Z λ.

S is scaled by its own diagonal before the LU (Jacobi): a soft spring's row is dominated by
C⁻¹, so scaling by diag(Uᵀ Z) alone would blow cond(S) up; where C⁻¹ and Uᵀ Z nearly cancel
the scale is floored at 1e-3 × |diag(Uᵀ Z)|. cond(S) above 1e13 (≈ 1/(1000 ε): fewer than
three correct digits left in λ) is refused as a singular support system.
"""

from __future__ import annotations

import numpy as np

from shaftfe.errors import SolverError

COND_LIMIT = 1e13
SCALE_FLOOR = 1e-3


class LowRankSolver:
    """The Woodbury correction of one factorisation ``fac`` (``.solve``) by the support
    columns ``U`` with compliance blocks ``Cinv``. ``Z`` = B⁻¹ U when the caller already has
    it (solved together with its first right-hand side), else it is solved here. ``hint`` ends
    the message of a singular support system."""

    def __init__(self, fac, U: np.ndarray, Cinv: np.ndarray, *, Z: np.ndarray | None = None,
                 hint: str = "check the bearing stiffnesses"):
        from scipy.linalg import lu_factor

        self.U = U
        self.Cinv = Cinv
        self.Z = fac.solve(U) if Z is None else Z
        UtZ = U.T @ self.Z
        dS = np.abs(np.diag(Cinv) + np.diag(UtZ))
        dS = np.maximum(dS, SCALE_FLOOR * np.abs(np.diag(UtZ)))
        self.D = 1.0 / np.sqrt(dS)
        S = self.D[:, None] * (Cinv + UtZ) * self.D[None, :]
        self.cond_S = float(np.linalg.cond(S))
        if not np.isfinite(self.cond_S) or self.cond_S > COND_LIMIT:
            raise SolverError(f"the support system is numerically singular (cond(S) = "
                              f"{self.cond_S:.3g}, limit {COND_LIMIT:g}): {hint}")
        self._lu = lu_factor(S)

    def correct(self, y: np.ndarray, g: np.ndarray | None = None
                ) -> tuple[np.ndarray, np.ndarray]:
        """(x, λ) from y = B⁻¹ f (a vector, or one column per right-hand side)."""
        from scipy.linalg import lu_solve

        r = self.U.T @ y
        if g is not None:
            r = r - g
        D = self.D if r.ndim == 1 else self.D[:, None]
        lam = D * lu_solve(self._lu, D * r)
        return y - self.Z @ lam, lam
