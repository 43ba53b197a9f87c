"""Modal analyses of the 3D solid rotor: the reduced basis (``BasisProvider``: shift-invert
Lanczos on one factorisation, cached), the Campbell sweep and single-speed modal analysis, the
full-size quadratic eigenproblem and the check of the sweep against it (method:
``shaftfe.rotordynamics.solid_rotor`` module docstring, "Solution").
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from shaftfe.rotordynamics.campbell import CampbellResult, sweep
from shaftfe.rotordynamics.kernels import TWO_PI, ModalBasis, block_shift_invert
from shaftfe.rotordynamics.options import DEFAULT_ORDERS
from shaftfe.rotordynamics.prestress import Prestress, centrifugal_prestress
from shaftfe.rotordynamics.solid_rotor import SolidRotor
from shaftfe.rotordynamics.solid_solver import ShiftedSolver


class BasisProvider:
    """Lowest undamped modes by block shift-invert Lanczos (``kernels.block_shift_invert``:
    multi-right-hand-side solves, one factorisation), cached: asking for m ≤ the modes already
    computed slices them."""

    def __init__(self, rotor: SolidRotor, solver: ShiftedSolver | None = None,
                 sigma: float | None = None):
        self.rotor = rotor
        self.sigma = -TWO_PI * rotor.options.shift_hz if sigma is None else sigma
        self.solver = solver or ShiftedSolver(rotor, self.sigma, damped=False)
        self._basis: ModalBasis | None = None
        self._prestress: Prestress | None = None
        self.eig_seconds = 0.0

    def prestress(self) -> Prestress:
        """The centrifugal prestress on this provider's factorisation (computed once)."""
        if self._prestress is None:
            self._prestress = centrifugal_prestress(self.rotor, self.solver)
        return self._prestress

    def Kg(self, rotor: SolidRotor | None = None):
        """The speed-squared stiffness K_g if ``rotor``'s (default: this provider's rotor's)
        ``stress_stiffening`` asks for it, else None."""
        on = (rotor or self.rotor).options.stress_stiffening
        return self.prestress().Kg if on else None

    def __call__(self, m: int) -> ModalBasis:
        if self._basis is not None and self._basis.omega.size >= m:
            return ModalBasis(np.ascontiguousarray(self._basis.Phi[:, :m]),
                              self._basis.omega[:m])
        t0 = time.perf_counter()
        r = self.rotor
        # the lowest ⌈2m/3⌉ pairs converged to the kernel's tol, the rest Ritz vectors of the
        # same (richer) Krylov space: ``choose_basis`` asks for 1.5 × the basis it keeps and
        # compares the two, and a Rayleigh-Ritz model on a larger space is never worse
        # (interlacing). Measured on x2_57 coarse (36 pairs): 88 vectors in 11 blocks, 2.9 s,
        # against 74 single-vector solves in eigsh, 8.3 s; the first 24 frequencies agree
        # with fully converged ones to 3e-8, the rest to 4e-6 (benchmarks/bench_rotor_solid.py)
        w2, Phi, _ = block_shift_invert(r.K, r.M, self.solver.solve, m,
                                        shift=self.sigma**2,
                                        n_converged=math.ceil(2 * m / 3),
                                        project=self.solver.project)
        mm = np.einsum("ij,ij->j", Phi, np.asarray(r.M @ Phi))
        Phi = Phi / np.sqrt(mm)
        self._basis = ModalBasis(Phi=Phi, omega=np.sqrt(np.clip(w2, 0.0, None)))
        self.eig_seconds += time.perf_counter() - t0
        return self._basis

    def residuals(self) -> np.ndarray | None:
        """(K + σ² M)⁻¹ Rᵀ of the damped rows (static-like residual vectors for damping)."""
        R = [t.R for t in self.rotor.terms if t.Cd is not None]
        if not R:
            return None
        return self.solver.solve(np.vstack(R).T)


def campbell(rotor: SolidRotor, rpms: Sequence[float], n_modes: int = 12, *,
             orders: Sequence[float] = DEFAULT_ORDERS, tol: float = 1e-6,
             keep_vectors: bool = False,
             provider: BasisProvider | None = None) -> CampbellResult:
    """Campbell sweep of the solid rotor (reduced basis, MAC tracking, labels, criticals);
    with ``options.stress_stiffening`` the reduced stiffness at Ω is diag ω² + Ω² Φᵀ K_g Φ
    (K_g from ``provider.prestress()``, on the basis's factorisation)."""
    prov = provider or BasisProvider(rotor)
    Kg = prov.Kg(rotor)
    res = sweep(rotor.K, rotor.M, rotor.G, rpms, n_modes, rotor.labelling, C=rotor.C,
                orders=orders, tol=tol, keep_vectors=keep_vectors, basis_fn=prov,
                residuals=prov.residuals(), Kg=Kg)
    ss = "stress stiffening: off"
    if Kg is not None:
        ps, top = prov.prestress(), float(np.max(rpms))
        ss = (f"stress stiffening: on (centrifugal prestress of the shaft body, von Mises ≤ "
              f"{ps.max_von_mises(top * TWO_PI / 60.0):.3g} MPa at {top:g} rpm; "
              f"{ps.iterations} refinement steps)")
    return replace(res, notes=res.notes + rotor.notes + (ss,))


def modal(rotor: SolidRotor, rpm: float = 0.0, n_modes: int = 12, *,
          keep_vectors: bool = False, provider: BasisProvider | None = None) -> CampbellResult:
    return campbell(rotor, [rpm], n_modes, keep_vectors=keep_vectors, provider=provider)


def full_qep(rotor: SolidRotor, Omega: float, n_modes: int, *, sigma: float | None = None,
             method: str | None = None, Kg=None):
    """The ``n_modes`` lowest oscillatory eigenvalues (Im s > 0) of the full-size quadratic
    eigenproblem with the hard rows, by shift-invert Arnoldi on the companion pencil
    A − s B, A = [[0, I], [−K, −D]], B = [[I, 0], [0, M]] at the real shift σ: the operator
    (A − σB)⁻¹ B needs one factorisation of K + σ D + σ² M (``ShiftedSolver``). With
    ``stress_stiffening`` K is K + Ω² K_g (``Kg``: the basis's, else computed here, one more
    symmetric factorisation)."""
    from scipy.sparse.linalg import LinearOperator, eigs

    sigma = -TWO_PI * rotor.options.shift_hz if sigma is None else sigma
    if rotor.options.stress_stiffening and Kg is None:
        Kg = centrifugal_prestress(rotor).Kg
    K_extra = None if Kg is None or Omega == 0.0 else (Omega * Omega) * Kg
    sol = ShiftedSolver(rotor, sigma, Omega, method, K_extra)
    n = rotor.n_dof
    M, G = rotor.M, rotor.G
    Cop = rotor.C

    def D(y):
        out = Omega * (G @ y)
        return out + Cop @ y if Cop is not None else out

    def op(y):
        y1, y2 = y[:n], y[n:]
        x1 = -sol.solve(M @ y2 + D(y1) + sigma * (M @ y1))
        return np.concatenate([x1, y1 + sigma * x1])

    k = min(2 * n - 2, 2 * n_modes + 8)
    v0 = np.random.default_rng(0).standard_normal(2 * n)       # reproducible start vector
    mu = eigs(LinearOperator((2 * n, 2 * n), matvec=op, dtype=float), k=k, which="LM",
              return_eigenvectors=False, tol=1e-12, v0=v0)
    s = sigma + 1.0 / mu
    scale = float(np.max(np.abs(s))) if s.size else 1.0
    keep = (np.abs(s) > 1e-6 * scale) & (s.imag > 1e-9 * np.abs(s))
    s = s[keep]
    return s[np.argsort(s.imag)][:n_modes]


def verify(rotor: SolidRotor, res: CampbellResult, rpm: float | None = None,
           provider: BasisProvider | None = None):
    """Full-size quadratic eigenproblem at ``rpm`` (default the top speed of ``res``) against
    the reduced sweep (the same matching as ``shaftfe.rotordynamics.beam_rotor.verify``);
    ``provider``: reuse its prestress (``stress_stiffening``)."""
    from shaftfe.rotordynamics.beam_rotor import compare_with_full, speed_index

    i = speed_index(res, rpm)
    n = res.freq_hz.shape[1]
    Kg = provider.Kg(rotor) if provider is not None else None
    s = full_qep(rotor, float(res.rpm[i]) * TWO_PI / 60.0, n + 6, Kg=Kg)
    return compare_with_full(res, i, s.imag / TWO_PI)


def support_energy_share(rotor: SolidRotor, vecs: np.ndarray) -> np.ndarray:
    num = np.einsum("ij,ij->j", vecs.conj(), rotor.K_support @ vecs).real
    den = np.einsum("ij,ij->j", vecs.conj(), rotor.K @ vecs).real
    return num / den
