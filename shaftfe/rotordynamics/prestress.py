"""Centrifugal prestress of the 3D solid shaft (option ``SolidOptions.stress_stiffening``):
the static displacement under the shaft's own body force per unit Ω², the stresses at the
quadrature points, the geometric stiffness K_σ,1 and the convective term A_θ, and
K_g = K_σ,1 − A_θ (theory: ``shaftfe.rotordynamics.solid_rotor`` module docstring,
"Centrifugal prestress"). scikit-fem inside the functions.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from shaftfe.errors import SolverError
from shaftfe.rotordynamics.kernels import TWO_PI
from shaftfe.rotordynamics.solid_rotor import SolidRotor, vector_matrix
from shaftfe.rotordynamics.solid_solver import ShiftedSolver


def geometric_order(mesh) -> int:
    """Quadrature order of the geometric stiffness: σ⁰ ∂φ_a ∂φ_b is cubic on a straight P2
    tet (each factor linear), constant on P1."""
    from shaftfe.fe import assembly as fem
    return 3 if fem.is_quadratic(mesh) else 1


def quadrature_stress(mesh, u: np.ndarray, E: float, nu: float,
                      intorder: int | None = None) -> np.ndarray:
    """σ = λ tr ε I + 2 μ ε at the quadrature points (ne, nq, 3, 3) of the displacement u
    (mesh dofs, interleaved), ε = sym ∇u, ∂_j u_i = Σ_a u_ai ∂_j φ_a."""
    from shaftfe.fe import assembly as fem

    intorder = geometric_order(mesh) if intorder is None else intorder
    dN, _ = fem.physical_gradients(mesh, intorder)                 # (ne, nq, nloc, 3)
    ue = np.asarray(u, float).reshape(-1, 3)[fem.element_nodes(mesh).T]   # (ne, nloc, 3)
    grad = np.einsum("eai,eqaj->eqij", ue, dN)                     # ∂_j u_i
    eps = 0.5 * (grad + grad.transpose(0, 1, 3, 2))
    lam, mu = fem.lame(E, nu)
    tr = np.trace(eps, axis1=2, axis2=3)
    return 2.0 * mu * eps + (lam * tr)[:, :, None, None] * np.eye(3)


def geometric_stiffness(mesh, stress: np.ndarray, intorder: int | None = None):
    """Scalar geometric (initial-stress) stiffness (S_σ)_ab = ∫ σ⁰_ij ∂_i φ_a ∂_j φ_b dV
    (N × N sparse CSR) of a prestress given at the quadrature points of order ``intorder``
    (default ``geometric_order``): shape (ne, nq, 3, 3), or anything that broadcasts to it
    (a constant 3 × 3 tensor). The vector matrix is ``vector_matrix(S_σ)``."""
    from shaftfe.fe import assembly as fem

    intorder = geometric_order(mesh) if intorder is None else intorder
    dN, wdx = fem.physical_gradients(mesh, intorder)                 # (ne, nq, nloc, 3)
    S = np.broadcast_to(np.asarray(stress, float), (*dN.shape[:2], 3, 3))
    sdN = np.einsum("eqij,eqbj->eqbi", S * wdx[:, :, None, None], dN)    # w σ⁰ ∂φ_b
    Ke = np.einsum("eqai,eqbi->eab", dN, sdN)
    return fem.assemble_blocks(mesh, Ke, 1)


def convective_matrix(mesh, density: float):
    """Scalar A_θ = ∫ ρ ∂_θ φ_a ∂_θ φ_b dV, ∂_θ = −z ∂_y + y ∂_z (order 4: exact on straight
    P2 tets), the companion of the prestress in the stationary frame (``solid_rotor``
    module docstring)."""
    from skfem.quadrature import get_quadrature

    from shaftfe.fe import assembly as fem

    order = 4 if fem.is_quadratic(mesh) else 2
    e = fem.scalar_element(mesh)
    X, _ = get_quadrature(mesh.refdom, order)
    phi = np.array([e.lbasis(X, a)[0] for a in range(e.doflocs.shape[0])])   # (nloc, nq)
    dN, wdx = fem.physical_gradients(mesh, order)
    xq = np.einsum("iae,aq->eqi", mesh.doflocs[:, fem.element_nodes(mesh)], phi)
    dth = -xq[:, :, 2:3] * dN[..., 1] + xq[:, :, 1:2] * dN[..., 2]             # (ne, nq, nloc)
    Ae = np.einsum("eqa,eqb->eab", dth * (density * wdx)[:, :, None], dth)
    return fem.assemble_blocks(mesh, Ae, 1)


@dataclass(frozen=True, eq=False)
class Prestress:
    """Centrifugal prestress of the shaft body per unit Ω² (Ω_ref = 1 rad/s): displacement
    ``u`` (mesh dofs), stress at the quadrature points (ne, nq, 3, 3) of ``intorder``, and
    ``Kg`` = K_σ,1 − A_θ on q (sparse), so that the stiffness at Ω is K + Ω² Kg."""
    u: np.ndarray
    stress: np.ndarray
    intorder: int
    Kg: object
    iterations: int
    seconds: float

    def max_von_mises(self, Omega: float) -> float:
        """Largest von Mises stress [MPa] at the quadrature points at spin Ω [rad/s]."""
        s = self.stress
        dev = s - (np.trace(s, axis1=2, axis2=3) / 3.0)[:, :, None, None] * np.eye(3)
        return float(Omega**2 * np.sqrt(1.5 * np.einsum("eqij,eqij->eq", dev, dev)).max())


def centrifugal_displacement(rotor: SolidRotor, solver: ShiftedSolver, *, tol: float = 1e-8,
                             max_iter: int = 60) -> tuple[np.ndarray, int]:
    """Static displacement q of the supported rotor under the shaft's body force at
    Ω = 1 rad/s, by iterative refinement on ``solver`` = (K_tot + σ² M)⁻¹ (hard rows kept):
    q ← q + Δq, Δq = solver(f − K_tot q), until the energy norm of the change of the step,
    ‖Δq_k − Δq_(k−1)‖_K, is < ``tol`` ‖q‖_K. (The elastic part of Δq falls by σ²/(ω² + σ²)
    per step; on a free model the load's rigid-body part, the mesh's tiny net force, adds
    the same strain-free motion every step and drops out of the difference.)"""
    from shaftfe.fe import assembly as fem

    m = rotor.shaft_mesh.mesh
    f = fem.body_force_load(m, rotor.variant.material.density_t_mm3, 1.0)
    if rotor.T is not None:
        f = rotor.T.T @ f
    K = rotor.K
    q = np.zeros_like(f)
    r, dq_old = f, 0.0
    for it in range(1, max_iter + 1):
        dq = solver.solve(r)
        q = q + dq
        Kq = K @ q
        r = f - Kq
        d = dq - dq_old
        dq_old = dq
        if abs(float(d @ (K @ d))) <= tol**2 * abs(float(q @ Kq)):
            return q, it
    raise SolverError(f"centrifugal prestress: the refinement did not converge in {max_iter} "
                      f"steps (shift {rotor.options.shift_hz:g} Hz too high for the lowest "
                      "mode?)")


def centrifugal_prestress(rotor: SolidRotor, solver: ShiftedSolver | None = None) -> Prestress:
    """Prestress of the shaft body per unit Ω² and its stiffness Kg = K_σ,1 − A_θ on q
    (``solid_rotor`` module docstring); ``solver``: the basis's factorisation (a new one at the
    rotor's shift if None)."""
    t0 = time.perf_counter()
    if solver is None:
        solver = ShiftedSolver(rotor, -TWO_PI * rotor.options.shift_hz)
    q, it = centrifugal_displacement(rotor, solver)
    m = rotor.shaft_mesh.mesh
    mat = rotor.variant.material
    u = rotor.mesh_vector(q)
    order = geometric_order(m)
    stress = quadrature_stress(m, u, mat.E_MPa, mat.nu, order)
    Kg = vector_matrix(geometric_stiffness(m, stress, order)
                       - convective_matrix(m, mat.density_t_mm3))
    if rotor.T is not None:
        Kg = (rotor.T.T @ Kg @ rotor.T).tocsr()
    return Prestress(u, stress, order, Kg, it, time.perf_counter() - t0)
