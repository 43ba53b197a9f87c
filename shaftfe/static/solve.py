"""3D static stress and deflection of the balancer shaft on spring-supported bearings.

API
---
``build_model(variant, options, shaft_mesh=None, cache_dir=None) -> StaticModel``
``solve_static(variant, rpm, options=StaticOptions(), ...) -> StaticResult`` (frozen)

Model (issue 4)
---------------
* Linear elasticity on the P2 (or P1) tet mesh of ``shaftfe.solid.mesh``; E, ν of the variant's
  shaft material; mm, N, MPa.
* Bearings: ``shaftfe.fe.supports`` (RBE3 remote point at the seat centre, 2×2 radial spring,
  u_x held at the axial bearing, θ_x held only at a bearing with ``holds_torsion`` (else one
  gauge row whose reaction is checked to be round-off: ``static.model.twist_gauge_block``),
  tilt free unless given; ``rigid_supports`` → remote radial translations held).
* Loads (issue #31): every action of ``shaftfe.model.loads`` (the parts' m e ω² at their
  centroids, the ``[[loads]]``, gravity; ``static.model``), one load vector per pattern. ONE
  factorisation, one solve per pattern (one multi-right-hand-side call with the spin-softening
  columns); each speed (plain factors) or the named load case is Σ factor × pattern solution;
  the stresses are recovered once per pattern and superposed (one rpm² pattern: the
  reference × (rpm/REF_RPM)², as before).

Solve (Woodbury, no dense clique in the sparse matrix)
------------------------------------------------------
B = K + k_p Σ e_i e_iᵀ with six algebraic pin springs on dofs that remove the rigid modes
(k_p = mean diag K) is SPD and factorised once. The supports and the cancelling pins form a
low-rank term U C Uᵀ: columns of U = pin unit vectors, spring rows, hard rows; C⁻¹ =
blockdiag(−I/k_p, C_spring⁻¹, 0 for hard rows: the exact infinite-penalty limit). Then
λ = S⁻¹ Uᵀ B⁻¹ f with the capacitance S = C⁻¹ + Uᵀ B⁻¹ U (small, dense) and u = B⁻¹ (f − U λ).
The rows and columns of S are scaled by diag(C⁻¹ + Uᵀ B⁻¹ U) (a Jacobi scaling of S itself:
soft spring rows are dominated by C⁻¹); cond(S) is reported. The pins cancel exactly: no node is
pinned in the physics. λ holds the support forces: the Woodbury multipliers of every support row
(spring rows: λ = C R u as an equation of the system, hard rows: the Lagrange multipliers), never
recomputed from a seat motion R u that may be ~1e-9 of u (stiff springs).

u is kept as a rigid part Φ a plus an elastic part w (K Φ = 0 analytically, never computed): on
soft springs the rigid motion dwarfs the elastic one and K u would carry its round-off. One step
of iterative refinement with the same factor and capacitance follows (measured on the test
cylinder at k = 1 N/mm: 6.7e-8 → 1.6e-12).

Checks: the supports are tested on the rigid modes BEFORE factorising (``SolverError`` naming the
free motion; the only "missing support" message), and every solve's relative residual
‖K w + Σ Rᵀ λ − f‖ / ‖f‖ and the support-row violation max |R u − C⁻¹ λ| / max |u| must be
≤ ``RESIDUAL_TOL``. Wall-clock seconds go to ``run`` (``StaticResult.run``, summary.json "run"),
never to ``diagnostics``, so two runs on the same inputs give identical diagnostics.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from shaftfe.beam import solve as beam_solve
from shaftfe.beam.solve import check_deflection
from shaftfe.errors import InputError, ShaftfeError, SolverError
from shaftfe.fe import assembly as fem
from shaftfe.fe import recovery, reuse, solvers, supports, surface
from shaftfe.fe.lowrank import LowRankSolver
from shaftfe.fe.pointeval import centroid_tree, interpolate
from shaftfe.fe.surface import SurfaceField
from shaftfe.model.bearing_life import l10h
from shaftfe.model.loads import laws
from shaftfe.model.spin import centroid_rows
from shaftfe.solid.levels import LEVELS
from shaftfe.solid.mesh import warn_unresolved_grooves
from shaftfe.solid.plan import warn_sharp_corners
from shaftfe.static import cache as sc
from shaftfe.static.measured_errors import notch_bars, shoulder_bars
from shaftfe.static.model import (
    REF_RPM,
    StaticModel,
    StaticOptions,
    _patches,
    build_model,
    region_nodes,
)
from shaftfe.static.result import (
    BearingReaction,
    StaticCase,
    StaticResult,
    Station,
    warn_unresolved_fillets,
)
from shaftfe.util.units import omega, rpm2_scale

RESIDUAL_TOL = 1e-8

# --------------------------------------------------------------------------- solve

def _pin_dofs(mesh) -> list[int]:
    """Six dofs that make K + k_p Σ e eᵀ nonsingular: all three translations of a node near
    the left end of the axis, u_y and u_z of one near the right end, and the tangential
    component of the node farthest from the axis."""
    x = mesh.doflocs
    r2 = x[1] ** 2 + x[2] ** 2
    a = int(np.argmin((x[0] - x[0].min()) ** 2 + r2))
    b = int(np.argmin((x[0] - x[0].max()) ** 2 + r2))
    c = int(np.argmax(r2))
    tang = 2 if abs(x[1, c]) >= abs(x[2, c]) else 1
    return [3 * a, 3 * a + 1, 3 * a + 2, 3 * b + 1, 3 * b + 2, 3 * c + tang]


def _modes(mesh):
    x = mesh.doflocs
    center = (0.5 * (x[0].min() + x[0].max()), 0.0, 0.0)
    R = fem.rigid_body_modes(mesh, center)
    R[:, 3:] /= max(0.5 * (x[0].max() - x[0].min()), 1e-9)
    return R


@dataclass(frozen=True, eq=False)
class UnitSolution:
    u: np.ndarray
    lam: list          # per block: support force parameters (C R u or multipliers)
    relres: float
    hard_violation: float
    cond_S: float
    diagnostics: dict  # results only (no timings)
    run: dict = field(default_factory=dict)  # factor_seconds, solve_seconds


def _springs(model: StaticModel) -> str:
    """The bearings' springs by name, softest and stiffest, for a solver failure message."""
    k = {b.bearing: float(np.linalg.eigvalsh(b.C).min()) for b in model.blocks
         if b.C is not None and b.labels == ("u_y", "u_z")}
    if not k:
        return "every support is rigid"
    soft, stiff = min(k, key=k.get), max(k, key=k.get)
    return (f"softest spring: bearing {soft!r} ({k[soft]:.3g} N/mm), stiffest: bearing "
            f"{stiff!r} ({k[stiff]:.3g} N/mm)")


def _support_columns(model: StaticModel, P: np.ndarray, kp: float):
    """U = [pins | support rows] and the block-diagonal compliance C⁻¹ (−I/k_p for the pins
    that cancel, the spring compliance, 0 for a hard row)."""
    from scipy.linalg import block_diag
    cols = [P] + [blk.R.T for blk in model.blocks]
    U = np.ascontiguousarray(np.hstack(cols))       # canonical layout: bit-reproducible BLAS
    Cinv = [np.eye(6) * (-1.0 / kp)]
    for blk in model.blocks:
        Cinv.append(np.zeros((blk.R.shape[0],) * 2) if blk.C is None else np.linalg.inv(blk.C))
    return U, block_diag(*Cinv)


def solve_model(model: StaticModel, rhs: np.ndarray | None = None, *,
                tol: float = RESIDUAL_TOL):
    """Solve the supported system for ``rhs`` (default: the model's load at REF_RPM; a 2D array
    (ndof, k) gives a list of k solutions from the same factorisation); a relative residual or
    support-row violation above ``tol`` is a SolverError."""
    m = model.shaft_mesh.mesh
    K = model.K
    free = supports.unrestrained_modes(list(model.blocks), _modes(m))
    if free:
        raise SolverError("the supports leave the shaft free to move: " + "; ".join(free))
    n = K.shape[0]
    pins = _pin_dofs(m)
    kp = float(K.diagonal().mean())
    P = np.zeros((n, 6))
    P[pins, range(6)] = 1.0
    if np.linalg.matrix_rank(P.T @ _modes(m), tol=1e-9) < 6:       # pragma: no cover
        raise SolverError("internal: the pin dofs do not remove the rigid modes")
    t0 = time.perf_counter()
    mat = model.variant.material
    fac = reuse.memo("factor", (reuse.mesh_digest(m), mat.E_MPa, mat.nu, model.options.solver),
                     lambda: solvers.factorize(K, model.options.solver, rigid_modes=_modes(m),
                                               diag_add=(pins, np.full(6, kp))))  # B = K + kp Σ eeᵀ
    t_fac = time.perf_counter() - t0
    U, Cinv = _support_columns(model, P, kp)
    F = model.f if rhs is None else rhs
    F2 = F.reshape(n, -1)
    t1 = time.perf_counter()
    Z = fac.solve(np.column_stack([U, F2]))
    Z, Y = Z[:, :U.shape[1]], Z[:, U.shape[1]:]
    lr = LowRankSolver(fac, U, Cinv, Z=Z,
                       hint=f"check the bearing stiffnesses; {_springs(model)}")
    cond = lr.cond_S              # [B U; Uᵀ −C⁻¹] [u; λ] = [f; g] (pins included in U)

    # u is kept as a rigid part Φ a plus an elastic part w (K Φ = 0 analytically, never
    # computed): with soft springs the rigid motion dwarfs the elastic one and K u would carry
    # its round-off. The support forces are the Woodbury multipliers λ (spring rows: λ = C R u
    # as an equation, not recomputed from a seat motion R u that may be ~1e-9 of u).
    Phi = np.ascontiguousarray(_modes(m))
    Phi_pinv = np.ascontiguousarray(np.linalg.pinv(Phi))
    Us, Cs = U[:, 6:], Cinv[6:, 6:]

    def residuals(f, a, w, lam_s):
        r1 = f - K @ w - Us @ lam_s
        r2 = Cs @ lam_s - (Us.T @ (Phi @ a) + Us.T @ w)
        return r1, r2

    # every right-hand side at once (columns), so that each factor solve is one multi-RHS call
    u0, lam = lr.correct(Y, np.zeros((U.shape[1], Y.shape[1])))
    a = Phi_pinv @ u0
    w = u0 - Phi @ a
    lam_s = lam[6:]
    r1, r2 = residuals(F2, a, w, lam_s)
    fn = np.linalg.norm(F2, axis=0)
    fn_safe = np.where(fn > 0, fn, 1.0)
    relres0 = np.where(fn > 0, np.linalg.norm(r1, axis=0) / fn_safe, 0.0)
    # one step of iterative refinement with the same factor and capacitance
    du, dlam = lr.correct(fac.solve(r1).reshape(r1.shape),
                          np.vstack([np.zeros((6, r1.shape[1])), -r2]))
    da = Phi_pinv @ du
    a, w, lam_s = a + da, w + (du - Phi @ da), lam_s + dlam[6:]
    r1, r2 = residuals(F2, a, w, lam_s)
    u_all = Phi @ a + w
    relres = np.where(fn > 0, np.linalg.norm(r1, axis=0) / fn_safe, 0.0)
    umax = np.abs(u_all).max(axis=0) if u_all.size else np.zeros(F2.shape[1])
    hard = np.abs(r2).max(axis=0) if r2.size else np.zeros(F2.shape[1])
    hard_rel = np.where(umax > 0, hard / np.where(umax > 0, umax, 1.0), 0.0)
    t_sol = time.perf_counter() - t1
    bad = (relres > tol) | (hard_rel > tol)
    if bad.any():
        j = int(np.argmax(bad))
        raise SolverError(f"the linear solve did not converge (relative residual "
                          f"{relres[j]:.2e}, support-row violation {hard_rel[j]:.2e}; limit "
                          f"{tol:g}): check the bearing stiffnesses; {_springs(model)}")
    starts = np.cumsum([0] + [blk.R.shape[0] for blk in model.blocks])
    sols = []
    for j in range(F2.shape[1]):
        lam_blocks = [lam_s[starts[k]:starts[k + 1], j] for k in range(len(model.blocks))]
        diag = {"solver": fac.name, "solver_note": getattr(fac, "note", ""),
                "n_low_rank": int(U.shape[1]),
                "cond_S": cond, "relative_residual": float(relres[j]),
                "hard_violation_rel": float(hard_rel[j]),
                "relative_residual_before_refinement": float(relres0[j]),
                "pin_stiffness": kp}
        run = {"factor_seconds": t_fac, "solve_seconds": t_sol}
        sols.append(UnitSolution(np.ascontiguousarray(u_all[:, j]), lam_blocks,
                                 float(relres[j]), float(hard_rel[j]), cond, diag, run))
    return sols[0] if F.ndim == 1 else sols


# --------------------------------------------------------------------------- post-processing

def probe(mesh, u: np.ndarray, pts: np.ndarray, tree=None) -> tuple[np.ndarray, np.ndarray]:
    """Displacement (n, 3) at points (3, n) and a mask of the points found in the mesh
    (``shaftfe.fe.pointeval.interpolate``: exact for straight elements; the axis stations
    this is used for lie in interior elements, which the mesher leaves straight). Points not
    found get NaN."""
    return interpolate(mesh.p, fem.element_nodes(mesh).T, u.reshape(-1, 3), pts, tree)


def _centroid_tree(mesh):
    return centroid_tree(mesh.p, mesh.t.T)


def axis_deflection(variant, mesh, u: np.ndarray, xs) -> np.ndarray:
    """Displacement (n, 3) of the shaft axis at stations xs: the FE field at (x, 0, 0), or,
    where the axis is not material (hex socket), the mean over 8 points on a ring at 0.8 × the
    local radius (the same for a beam-like field)."""
    xs = np.asarray(xs, dtype=float)
    tree = _centroid_tree(mesh)
    out, ok = probe(mesh, u, np.array([xs, 0 * xs, 0 * xs]), tree)
    for k in np.nonzero(~ok)[0]:
        x = xs[k]
        r = 0.8 * 0.5 * variant.segment_at(x).diameter_at(x)
        a = np.linspace(0, 2 * np.pi, 8, endpoint=False)
        val, ok2 = probe(mesh, u, np.array([np.full(8, x), r * np.cos(a), r * np.sin(a)]), tree)
        out[k] = val[ok2].mean(axis=0) if ok2.any() else np.nan
    return out


@dataclass(frozen=True, eq=False)
class _Recovered:
    """Nodal stresses at REF_RPM (the free surface's from the surface recovery) and the peaks
    per region (at REF_RPM: every case scales them)."""
    stress: np.ndarray
    vm: np.ndarray
    excluded: np.ndarray
    peaks: tuple
    shaft: recovery.RegionPeak
    n_surface: int
    seconds: float


def free_facets(mesh) -> np.ndarray:
    """Boundary facets without a load or a bearing coupling on them (traction-free)."""
    return np.setdiff1d(mesh.boundary_facets(), np.concatenate(_patches(mesh)))


def _stress_field(model: StaticModel, u: np.ndarray):
    """(stress (6, n), surface recovery or None): nodal averaging everywhere, the surface
    recovery's values on the traction-free faces."""
    m, mat = model.shaft_mesh.mesh, model.variant.material
    stress = recovery.nodal_stress(m, u, mat.E_MPa, mat.nu)
    surf = None
    if fem.is_quadratic(m):
        surf = surface.surface_stress(m, u, mat.E_MPa, mat.nu, free_facets(m))
        ok = np.isfinite(surf.stress[0])
        stress[:, surf.nodes[ok]] = surf.stress[:, ok]
    return stress, surf


def _recover(model: StaticModel, u: np.ndarray, options: StaticOptions) -> _Recovered:
    """Nodal averaging everywhere, then the surface recovery (``shaftfe.fe.surface``) on the
    traction-free faces, whose values replace the averaged ones there."""
    t1 = time.perf_counter()
    stress, surf = _stress_field(model, u)
    return _recover_from(model, stress, surf, options, t1)


def _recover_from(model: StaticModel, stress: np.ndarray, surf, options: StaticOptions,
                  t1: float) -> _Recovered:
    """The peaks per region of a recovered field (``_stress_field``)."""
    m = model.shaft_mesh.mesh
    vm = recovery.von_mises(stress)
    excl = recovery.excluded_nodes(m, _patches(m), options.exclude_mm)
    xyz = m.doflocs
    peaks = tuple(recovery.peak(stress, xyz, nodes, excl, name, surf)
                  for name, nodes in sorted(region_nodes(m).items()))
    shaft = recovery.peak(stress, xyz, np.arange(xyz.shape[1]), excl, "shaft", surf)
    n_surf = 0 if surf is None else int(np.isfinite(surf.stress[0]).sum())
    return _Recovered(stress, vm, excl, peaks, shaft, n_surf, time.perf_counter() - t1)


def _station_list(model: StaticModel) -> list[tuple[str, float]]:
    """Seats of the loaded parts, bearing centres and the clearance station."""
    v = model.variant
    stations = [(f"seat:{a.name}", a.seat_center_mm) for a in v.attachments
                if a.name in model.loads]
    stations += [(f"bearing:{c.name}", c.x_mm) for c in model.couplings]
    if v.clearance_station_x_mm is not None:
        stations.append(("clearance", float(v.clearance_station_x_mm)))
    return stations


def _reactions(model: StaticModel, lam: list, f: np.ndarray):
    """Support reactions per bearing (6 components) from the multipliers ``lam`` of a solve
    with the load vector ``f``, Σ loads, Σ reactions and the relative equilibrium residual."""
    reac = {}
    for blk, lb in zip(model.blocks, lam, strict=True):
        r = reac.setdefault(blk.bearing, np.zeros(6))
        for lab, val in zip(blk.labels, lb, strict=True):
            r[supports._DOF[lab]] -= val
    load_sum = f.reshape(-1, 3).sum(axis=0)
    reac_sum = sum((r[:3] for r in reac.values()), np.zeros(3))
    # scale: |Σ loads|, or Σ |nodal loads| when the loads are self-equilibrated (body force)
    scale = max(float(np.linalg.norm(load_sum)),
                1e-6 * float(np.abs(f.reshape(-1, 3)).sum()))
    eq_res = float(np.linalg.norm(reac_sum + load_sum) / scale) if scale > 0 else 0.0
    return reac, load_sum, reac_sum, eq_res


@dataclass(frozen=True, eq=False)
class SpeedSolution:
    """The solution at one speed with its loads scaled by ``scale`` = (rpm / REF_RPM)²: u, the
    support multipliers per block, and the spin-softening force on each part (N)."""
    rpm: float
    scale: float
    u: np.ndarray
    lam: list
    soft_N: dict                      # part -> (F_y, F_z): m ω² ū_c (its centroid's motion);
                                      # "shaft" -> the resultant of the shaft's softening
    extra: np.ndarray | None          # the softening forces as a load vector (ndof) or None


def _soft_terms(model: StaticModel) -> tuple[np.ndarray, np.ndarray]:
    """(R, w): every softening row of the model and its weight per unit ω²."""
    return (np.vstack([sd.R for sd in model.soft]),
            np.concatenate([sd.w for sd in model.soft]))


def _sqrt_psd(C: np.ndarray) -> np.ndarray:
    """C^½ of the symmetric positive semi-definite compliance C = R A⁻¹ Rᵀ (eigenvalues below
    zero by round-off taken as zero)."""
    lam, vec = np.linalg.eigh(0.5 * (C + C.T))
    return (vec * np.sqrt(np.clip(lam, 0.0, None))) @ vec.T


def _softening_failure(model: StaticModel, RW: np.ndarray, rpm: float) -> str:
    """Why the softened system is not positive definite, in numbers the user can check. It
    fails exactly when ω² λ_max ≥ 1, λ_max the largest eigenvalue of C^½ D₁ C^½ (C = R A⁻¹ Rᵀ
    the compliance of the softening rows, D₁ their weights per unit ω²): ω_c = λ_max^-½ is the
    speed this solve implies. A stiffer support lowers C and raises ω_c, so a failure with very
    stiff springs is the solve's conditioning, not the rotor: the message names both the
    implied speed and the springs."""
    _, w = _soft_terms(model)
    Ch = _sqrt_psd(RW)
    lam = float(np.linalg.eigvalsh(Ch @ (w[:, None] * Ch)).max())
    rpm_c = 60.0 / (2.0 * math.pi * math.sqrt(lam)) if lam > 0 else 0.0
    k_max = max((abs(float(k)) for c in model.couplings for row in c.K for k in row),
                default=0.0)
    return (f"spin softening: {rpm:g} rpm is at or above {rpm_c:.0f} rpm, the critical speed "
            "implied by this solve's seat compliance (the parts' m ω² exceeds what the shaft "
            "and bearings hold; the co-rotating static solution does not exist). If "
            f"`shaftfe campbell` finds the rotor's first critical speed far above it, the solve is "
            f"ill-conditioned instead: check the bearing stiffness (largest entry {k_max:.4g} "
            "N/mm) or use --rigid-supports")


def soften(model: StaticModel, base: UnitSolution, unit: list, rpm: float,
           scale: float | None = None) -> SpeedSolution:
    """Spin softening at ``rpm``: the co-rotating static problem done completely (exact on its
    low-rank terms, by a second Woodbury step on the solved system).

    Model (``shaftfe.model.spin``): in the co-rotating frame the rpm² loads act on a rotor
    softened by ω² Σ Rᵀ diag(w) R (``StaticModel.soft``): each seat's parts (mass at the
    centroid through the rigid link from the seat's RBE3 point, tilt inertia I_d − I_p and the
    eccentric centroid's m e² about the axis ⊥ e: the rigid body's exact centrifugal potential)
    and the shaft's own transverse mass M_⊥ by its Ritz projection on Legendre polynomials in x
    (``static.model.shaft_rows``: one factorisation, no second one of K − ω² M_⊥; its error
    against that exact solve is measured in tests/validation/test_spin_softening_ross.py).

    With u₀ the solution for the loads at REF_RPM and W = A⁻¹ Rᵀ (``unit``: the supported
    system's responses to the rows, from the same factorisation), the softened solution for the
    loads × s is u = s u₀ + W μ with μ = D ū, D = ω² diag(w), ū = R u and
    (I − R W D) ū = s R u₀. The softened stiffness A − Rᵀ D R is positive definite exactly when
    I − C^½ D C^½ is (C = R W, symmetric positive semi-definite; D may have negative entries:
    tilt stiffening): else the speed is at or above a critical speed of the softened rotor and
    the static co-rotating solution does not exist (SolverError). The same combination gives
    the multipliers. ``scale``: the factor s on ``base`` (default (rpm / REF_RPM)²; a load
    case passes its superposed base solution Σ factor × pattern solution with s = 1)."""
    s = rpm2_scale(rpm) if scale is None else scale
    if not model.soft or rpm == 0:
        return SpeedSolution(rpm, s, base.u * s, [lb * s for lb in base.lam], {}, None)
    R, w = _soft_terms(model)
    W = np.column_stack([wu.u for wu in unit])
    RW = R @ W
    RW = 0.5 * (RW + RW.T)
    d = omega(rpm) ** 2 * w
    Ch = _sqrt_psd(RW)
    if np.linalg.eigvalsh(np.eye(d.size) - Ch @ (d[:, None] * Ch)).min() <= 0:
        raise SolverError(_softening_failure(model, RW, rpm))
    ubar = np.linalg.solve(np.eye(d.size) - RW * d[None, :], s * (R @ base.u))
    mu = d * ubar
    u = s * base.u + W @ mu
    lam = [s * lb + sum(m_ * wu.lam[k] for m_, wu in zip(mu, unit, strict=True))
           for k, lb in enumerate(base.lam)]
    w2 = omega(rpm) ** 2
    soft_N, j = {}, 0
    for sd in model.soft:
        for p in sd.parts:
            f = p.mass_t * w2 * (centroid_rows(sd.R6, p.d_mm) @ u)
            soft_N[p.name] = (float(f[0]), float(f[1]))
        if not sd.parts:               # the shaft: the resultant of its softening forces
            f = (sd.R.T @ mu[j:j + sd.R.shape[0]]).reshape(-1, 3).sum(axis=0)
            soft_N[sd.name] = (float(f[1]), float(f[2]))
        j += sd.R.shape[0]
    return SpeedSolution(rpm, s, u, lam, soft_N, R.T @ mu)


def _beam_check(v, rpms: list[float], options: StaticOptions) -> dict:
    """The beam model's answer at every rpm for the side-by-side check; a variant the beam
    cannot model (a ShaftfeError: bad input for the beam, a singular beam system) is reported
    as such, anything else is a bug and propagates."""
    try:
        return {br.rpm: br for br in beam_solve.analyse(
            v, rpms, rigid_supports=options.rigid_supports, spread_loads=True,
            seed_placement=options.seed_load_case)}
    except ShaftfeError as exc:
        return {"error": f"{type(exc).__name__}: {exc}"}


def _finite(v: float) -> float | None:
    return v if math.isfinite(v) else None            # JSON: null for an infinite life


def _bearing_rows(model: StaticModel, reac: dict, u: np.ndarray, r: float, s: float):
    v = model.variant
    bearings = []
    for c in model.couplings:
        rv = reac.get(c.name, np.zeros(6)) * s
        q = c.G @ u * s
        F = float(math.hypot(rv[1], rv[2]))
        b = v.bearing(c.name)
        bearings.append(BearingReaction(c.name, c.x_mm, float(rv[0]), float(rv[1]),
                                        float(rv[2]), F, float(q[1]), float(q[2]),
                                        _finite(l10h(b.C_N, F, r, b.life_exponent)), b.C_N,
                                        b.life_exponent,
                                        float(rv[3]) if c.hold_twist else None))
    return tuple(bearings)


def _load_cross_force(model: StaticModel) -> dict:
    """Per part loaded by a pressure (the seed's placement, ``--seed-load-case``): the nodal
    load's component across its intended direction, relative. A remote load carries its
    force exactly (``static.model.remote_load``): nothing to report."""
    out = {}
    if not model.options.seed_load_case:
        return out
    parts = {a.name for a in model.variant.attachments}
    for nm, F in model.load_force.items():
        if nm not in parts:
            continue
        fv = model.loads[nm].reshape(-1, 3).sum(axis=0)
        e = np.asarray(F) / np.linalg.norm(F)
        out[nm] = float(np.linalg.norm(fv - (fv @ e) * e) / np.linalg.norm(F))
    return out


def _check_rpms(rpm, at_rest_loads: bool = False) -> list[float]:
    """The speeds of a static solve. Rule (issue #30): speeds >= 0, at least one > 0 when every
    load is the parts' (or another rpm²) load, zero at rest: a 0 rpm case beside a positive
    speed is then exactly zero (stated as such by the commands:
    ``shaftfe.beam.solve.AT_REST_NOTE``); a run of nothing but 0 rpm has nothing to solve and
    is refused with one line. ``at_rest_loads``: the variant has loads of another law
    (constant, a channel), which act at rest: 0 rpm alone is then a case."""
    rpms = [float(rpm)] if isinstance(rpm, int | float) else [float(r) for r in rpm]
    if (not rpms or any(not (math.isfinite(r) and r >= 0) for r in rpms)
            or not (at_rest_loads or any(r > 0 for r in rpms))):
        raise InputError("--rpm", "rpm", "speeds >= 0 rpm, at least one > 0 (at 0 rpm the only "
                         "load, the parts' m·e·ω², is zero: there is nothing to solve)", got=rpm)
    return rpms


# the conditions bench_truth measured the bars under (the rest of StaticOptions may vary:
# level, solver, rigid or spring supports, spin softening on or off: both measured)
_BAR_CONDITIONS = {"order": 2, "load_distribution": "uniform", "body_force": False,
                   "seed_load_case": False, "exclude_mm": 0.0}


def truth_bars(variant, options: StaticOptions, peaks, mesh_key: str) -> tuple[dict, dict]:
    """({region: (low, high) %}, {region: why it has none}) for the fillet and groove peaks:
    ``shaftfe.static.measured_errors.notch_bars`` (span fillets and U grooves outside every cut
    feature's zone, inside the measured hulls, in bending) for a named level used as named,
    under the options the bars were measured with (``_BAR_CONDITIONS``), on the pipeline's own
    mesh of the variant (not a mesh the caller built otherwise)."""
    lv = options.level
    name = lv if isinstance(lv, str) else lv.name
    bars = shoulder_bars().bars["solid"]
    if name not in bars or (not isinstance(lv, str) and lv != LEVELS.get(name)):
        return {}, {}
    if any(getattr(options, k) != want for k, want in _BAR_CONDITIONS.items()):
        return {}, {}
    if mesh_key != sc.predicted_mesh_key(variant, options):
        return {}, {}
    return notch_bars(variant, name, peaks, "solid")


def _named_case(variant, case):
    """The ``LoadCase`` named ``case`` (None: the plain speeds)."""
    if case is None:
        return None
    names = [c.name for c in getattr(variant, "load_cases", ())]
    if case not in names:
        raise InputError("--case", "case", "a [[load_cases]] name of the variant: "
                         + (", ".join(names) or "(it has none)"), got=case)
    return variant.load_case(case)


def _combine(sols: list, phi: list[float]) -> UnitSolution:
    """Σ φ_k × pattern solution k (u and the support multipliers): a case's base solution."""
    if len(sols) == 1:
        s0 = sols[0]
        return UnitSolution(s0.u * phi[0], [lb * phi[0] for lb in s0.lam], s0.relres,
                            s0.hard_violation, s0.cond_S, s0.diagnostics, s0.run)
    u = sum(f * s_.u for f, s_ in zip(phi, sols, strict=True))
    lam = [sum(f * s_.lam[k] for f, s_ in zip(phi, sols, strict=True))
           for k in range(len(sols[0].lam))]
    return UnitSolution(u, lam, max(s_.relres for s_ in sols),
                        max(s_.hard_violation for s_ in sols), sols[0].cond_S,
                        sols[0].diagnostics, sols[0].run)


def _combine_recovered(model: StaticModel, parts: list, phi: list[float],
                       options: StaticOptions) -> _Recovered:
    """A case's stresses and peaks from the per-pattern stress fields (stress, surface fit and
    its trace samples are linear in u): Σ φ_k field_k, then the peaks of the sum."""
    t1 = time.perf_counter()
    stress = sum(f * st for f, (st, _) in zip(phi, parts, strict=True))
    surf = None
    if parts[0][1] is not None:
        s0 = parts[0][1]
        lin = {k: sum(f * getattr(sf, k) for f, (_, sf) in zip(phi, parts, strict=True))
               for k in ("stress", "samples")}
        surf = SurfaceField(s0.nodes, lin["stress"], s0.patches, lin["samples"],
                            s0.sample_normals, s0.sample_points, s0.xyz)
    return _recover_from(model, stress, surf, options, t1)


def _twist_gauge_check(model: StaticModel, sol: UnitSolution, f: np.ndarray,
                       extra: np.ndarray | None = None) -> float:
    """The twist gauge (``static.model.twist_gauge_block``) against the applied torques
    Σ|x × f|ₓ over the nodes. The applied loads ``f`` must have no net torque (the torque-path
    rule); the spin softening's forces ``extra`` may (the centrifugal force on a section whose
    centroid is off the axis: a keyway, the hex socket, an eccentric part displaced sideways;
    the drive reacts it), and the gauge then carries exactly their torque (equilibrium). Both,
    relative to the applied torques, must hold to ``RESIDUAL_TOL``, else a SolverError."""
    k = next(i for i, blk in enumerate(model.blocks)
             if blk.bearing == model.twist_gauge and blk.labels == ("θ_x",))
    x = model.shaft_mesh.mesh.doflocs

    def mx(v):
        v3 = v.reshape(-1, 3)
        return x[1] * v3[:, 2] - x[2] * v3[:, 1]
    tf = mx(f)
    scale = float(np.abs(tf).sum())
    te = 0.0 if extra is None else float(mx(extra).sum())
    scale = max(scale, 0.0 if extra is None else float(np.abs(mx(extra)).sum()))
    net = abs(float(tf.sum()))
    # the gauge's multiplier equals the net applied torque (loads + softening) by equilibrium
    t = float(sol.lam[k][0])
    bal = min(abs(t - (float(tf.sum()) + te)), abs(t + (float(tf.sum()) + te)))
    rel = max(net, bal) / scale if scale > 0 else 0.0
    if rel > RESIDUAL_TOL:
        raise SolverError(f"the free rotation about the shaft axis carries a torque of "
                          f"{abs(t):.4g} N·mm ({rel:.2e} of the applied torques; limit "
                          f"{RESIDUAL_TOL:g}): the torques do not sum to zero and no bearing "
                          "holds torsion")
    return rel


def solve_static(variant, rpm=None, options: StaticOptions = StaticOptions(), *,
                 case: str | None = None, shaft_mesh=None, cache_dir=None, beam: bool = True,
                 linear_stress: bool = False) -> StaticResult:
    """One factorisation, one solve per load pattern (``StaticModel.patterns``), and every
    reported case the superposition Σ factor × pattern solution: each speed of ``rpm`` (a
    number or a sequence; default REF_RPM) at its plain factors (rpm² loads × (rpm / ref)²,
    constant × 1, channel loads at their reference), or the load case named ``case`` (its rpm
    and factors; ``rpm`` then None or that rpm). With spin softening each case is softened
    exactly (``soften`` on the case's base solution) and the reference is the first case
    (positive speed); ``linear_stress`` then also recovers the unsoftened per-pattern stresses
    (``StaticResult.pattern_stress``; ``stress_linear_ref``: fatigue's per-node softening
    model). Without softening the reference is REF_RPM when every load is rpm², else the first
    case. Stresses are recovered once per pattern and superposed (one pattern: scaled)."""
    t_all = time.perf_counter()
    lc = _named_case(variant, case)
    if lc is not None:
        if rpm is not None and [float(r) for r in np.atleast_1d(rpm)] != [lc.rpm]:
            raise InputError("--rpm", "rpm", f"absent with --case (case {lc.name!r} runs at "
                             f"{lc.rpm:g} rpm)", got=rpm)
        rpm = lc.rpm
    only_rpm2 = set(laws(variant)) <= {"rpm2"}
    rpms = _check_rpms(REF_RPM if rpm is None else rpm, at_rest_loads=not only_rpm2)
    warn_sharp_corners(variant)          # a fillet 0 at a loaded shoulder: not a stress there
    warn_unresolved_grooves(variant, options.level)      # a groove's peak the mesh reads low
    t0 = time.perf_counter()
    model = build_model(variant, options, shaft_mesh=shaft_mesh, cache_dir=cache_dir)
    v, sm = model.variant, model.shaft_mesh
    m = sm.mesh
    t_model = time.perf_counter() - t0
    pats = model.patterns
    n_p = len(pats)
    scaled = n_p == 1 and pats[0].scales_with == "rpm2" and lc is None
    soft_on = bool(model.soft) and any(r > 0 for r in rpms)
    cols = [p.f for p in pats]
    if soft_on:
        cols += list(_soft_terms(model)[0])
    sols = solve_model(model, np.column_stack(cols))
    psol, unit = sols[:n_p], sols[n_p:]
    phis = {r: [p.factor(r, lc) for p in pats] for r in dict.fromkeys(rpms)}
    speeds = {r: soften(model, _combine(psol, phis[r]), unit, r, scale=1.0) for r in phis}
    if soft_on:
        ref_rpm = next(r for r in rpms if r > 0)
    else:
        ref_rpm = REF_RPM if scaled else rpms[0]
    ref = speeds[ref_rpm] if ref_rpm in speeds else soften(
        model, _combine(psol, [p.factor(ref_rpm) for p in pats]), unit, ref_rpm, scale=1.0)
    u = ref.u
    # stress per pattern (unsoftened, at its written magnitude): free without softening (the
    # cases superpose them), one field each with softening when asked (linear_stress)
    pfields = ([_stress_field(model, s_.u) for s_ in psol]
               if (not soft_on and not scaled and n_p > 1) or (soft_on and linear_stress)
               else None)
    if soft_on:
        recs = {r: _recover(model, sp_.u, options) for r, sp_ in speeds.items()}
        rec = recs[ref_rpm]
    elif scaled or n_p == 1:
        # one pattern: one recovery at the reference, the cases by its factor (peaks × φ
        # only for φ >= 0: a negative factor flips the principal stresses)
        rec = _recover(model, u, options)
        k_ref = pats[0].factor(ref_rpm, None if scaled else lc)
        recs = {r: (rec, phis[r][0] / k_ref) if k_ref and phis[r][0] / k_ref >= 0
                else (_recover(model, sp_.u, options), 1.0) for r, sp_ in speeds.items()}
        if pfields is None and not soft_on:
            pfields = [(rec.stress / k_ref, None)] if k_ref else [_stress_field(model, psol[0].u)]
    else:
        recs = {r: _combine_recovered(model, pfields, phis[r], options) for r in speeds}
        rec = recs[ref_rpm] if ref_rpm in recs else _combine_recovered(
            model, pfields, [p.factor(ref_rpm) for p in pats], options)
    xyz = m.doflocs
    stations = _station_list(model)
    x0, x1 = float(xyz[0].min()), float(xyz[0].max())
    ax_x = np.linspace(x0 + 1e-6, x1 - 1e-6, 121)
    beam_res = {}
    if beam and lc is not None:
        # the beam model takes plain speeds, not a case's factors: no side by side
        beam_res = {"error": f"no beam side by side for load case {lc.name!r} (the beam model "
                             "takes plain speeds)"}
    elif beam:
        beam_res = _beam_check(v, rpms, options)

    ax_u_ref = axis_deflection(v, m, u, ax_x)
    gauge_rel = 0.0
    cases = []
    for r in rpms:
        sp_ = speeds[r]
        ur = sp_.u
        rc_, f_ = recs[r] if isinstance(recs[r], tuple) else (recs[r], 1.0)
        st_u = axis_deflection(v, m, ur, [q[1] for q in stations])
        ax_u = axis_deflection(v, m, ur, ax_x)
        radial = np.hypot(ur[1::3], ur[2::3])
        imax = int(np.argmax(radial))
        f_l = sum(f * p.f for f, p in zip(phis[r], pats, strict=True))
        f_r = f_l + (0.0 if sp_.extra is None else sp_.extra)
        reac, load_sum, reac_sum, eq_res = _reactions(model, sp_.lam, f_r)
        if model.twist_gauge:
            gauge_rel = max(gauge_rel, _twist_gauge_check(model, sp_, f_l, sp_.extra))
        sts = tuple(Station(nm, float(x), float(uu[1]), float(uu[2]),
                            float(math.hypot(uu[1], uu[2])))
                    for (nm, x), uu in zip(stations, st_u, strict=True))
        clr = next((st.u_mm for st in sts if st.name == "clearance"), None)
        check_deflection(f"static, {r:g} rpm", x1 - x0, float(radial[imax]), clr,
                         v.clearance_mm)
        g = rc_.shaft.scaled(f_)
        bm = None
        if "error" in beam_res:
            bm = {"error": beam_res["error"]}
        elif r in beam_res:
            bm = _beam_summary(beam_res[r])
        cases.append(StaticCase(
            rpm=r, scale=rpm2_scale(r, ref_rpm) if ref_rpm > 0 else 1.0,
            bearings=_bearing_rows(model, reac, ur, r, 1.0),
            stations=sts, max_deflection_mm=float(radial[imax]),
            max_deflection_xyz_mm=tuple(float(c) for c in xyz[:, imax]),
            max_axis_deflection_mm=float(np.hypot(ax_u[:, 1], ax_u[:, 2]).max()),
            peaks=tuple(p.scaled(f_) for p in rc_.peaks), peak_von_mises_MPa=g.von_mises_MPa,
            peak_von_mises_xyz_mm=g.xyz_mm,
            peak_von_mises_unfiltered_MPa=g.von_mises_unfiltered_MPa,
            peak_von_mises_unfiltered_xyz_mm=g.xyz_unfiltered_mm,
            load_sum_N=tuple(float(c) for c in load_sum),
            reaction_sum_N=tuple(float(c) for c in reac_sum),
            equilibrium_residual=eq_res, beam=bm, spin_softening_N=sp_.soft_N or None,
            case=lc.name if lc is not None else "",
            factors={p.label: float(f) for p, f in zip(pats, phis[r], strict=True)}))

    diag = dict(psol[0].diagnostics)
    diag.update(relative_residual=max(s_.relres for s_ in psol),
                hard_violation_rel=max(s_.hard_violation for s_ in psol),
                relative_residual_before_refinement=max(
                    s_.diagnostics["relative_residual_before_refinement"] for s_ in psol),
                n_load_patterns=n_p)
    diag.update(min_quality=sm.min_quality, n_excluded_nodes=int(rec.excluded.size),
                n_surface_recovered_nodes=rec.n_surface)
    if model.twist_gauge:
        diag["twist_gauge_torque_rel"] = gauge_rel
    cross = _load_cross_force(model)
    if cross:
        diag["load_cross_force_rel"] = cross
    run = dict(psol[0].run)
    run.update(mesh_seconds=sm.build_seconds, mesh_from_cache=sm.from_cache,
               assembly_seconds=model.assembly_seconds, model_seconds=t_model,
               recovery_seconds=rec.seconds)
    bars, bar_notes = truth_bars(v, options, rec.peaks, sm.key)
    unresolved = warn_unresolved_fillets({pk.region: pk.von_mises_MPa for pk in rec.peaks})
    from types import MappingProxyType
    p_u = MappingProxyType({p.key: s_.u for p, s_ in zip(pats, psol, strict=True)})
    p_s = MappingProxyType({} if pfields is None else {
        p.key: st for p, (st, _) in zip(pats, pfields, strict=True)})
    lin_ref = None
    if soft_on and linear_stress:
        lin_ref = sum(p.factor(ref_rpm, lc) * p_s[p.key] for p in pats)
    res = StaticResult(
        variant=v.name, variant_hash=v.content_hash, options=options, ref_rpm=ref_rpm,
        n_nodes=sm.n_nodes, n_elements=sm.n_elements, n_dofs=3 * sm.n_nodes, mesh_key=sm.key,
        u_ref=u, stress_ref=rec.stress, von_mises_ref=rec.vm, axis_x=ax_x, axis_u_ref=ax_u_ref,
        cases=tuple(cases), diagnostics=diag, notes=(), mesh=sm, run=run,
        truth_error_bar_pct=bars, truth_bar_notes=bar_notes, unresolved_fillets=unresolved,
        stress_linear_ref=lin_ref, case_name=lc.name if lc is not None else "",
        patterns=tuple(_pattern_info(p) for p in pats), pattern_u=p_u, pattern_stress=p_s)
    res.run["total_seconds"] = time.perf_counter() - t_all
    return res


def _pattern_info(p) -> dict:
    """A load pattern for summary.json: its label, law, references and loads, and its
    resultant at the written magnitudes."""
    return {"key": p.label, "scales_with": p.scales_with, "ref_rpm": p.ref_rpm,
            "channel_ref": p.channel_ref, "factor_name": p.factor_name, "loads": list(p.names),
            "F_N": list(p.F_N), "M_Nmm": list(p.M_Nmm)}


def _beam_summary(br) -> dict:
    return {"bearings": [{"name": b.name, "F_N": b.F_N, "Fy_N": b.Fy_N, "Fz_N": b.Fz_N,
                          "L10h": b.L10h if math.isfinite(b.L10h) else None}
                         for b in br.bearings],
            "stations": {k: s.u_mm for k, s in br.stations.items()},
            "max_deflection_mm": br.max_deflection_mm,
            "max_sigma_vm_nominal_MPa": br.max_sigma_vm_MPa,
            "max_sigma_vm_with_kt_MPa": br.max_peak_MPa
            if math.isfinite(br.max_peak_MPa) else None,
            "x_line_mm": br.x.tolist(), "u_line_mm": br.u.tolist(),
            "uy_line_mm": br.uy.tolist(), "uz_line_mm": br.uz.tolist()}


def load_or_solve(variant, options=None, cache_dir=None, *, use_cache: bool = True,
                  solve_kwargs: dict | None = None) -> sc.StaticReference:
    """The static reference solution of ``variant`` with ``options`` (``StaticOptions``), read
    from the cache when the key matches, else solved (and stored). ``cache_dir`` is used for the
    mesh cache too."""
    t0 = time.perf_counter()
    warn_sharp_corners(variant)          # a cached solution says it as a fresh one would
    options = options if options is not None else StaticOptions()
    warn_unresolved_grooves(variant, options.level)
    mkey = sc.predicted_mesh_key(variant, options)
    key = sc.static_key(variant, options, mkey, REF_RPM)
    path = sc.cache_path(key, cache_dir)
    if use_cache and path.exists():
        ref = sc._load(path, key, variant.name, t0)
        if ref is not None:
            # as a fresh solve would say it (on the nodal values the cache holds)
            warn_unresolved_fillets(sc.region_peaks(ref), "largest nodal values")
            return ref
    res = solve_static(variant, REF_RPM, options, cache_dir=cache_dir, beam=False,
                       linear_stress=True, **(solve_kwargs or {}))
    if use_cache:
        ref = sc.store(variant, options, res, cache_dir)
    else:
        ref = sc.from_result(res, key)
    return replace(ref, seconds=time.perf_counter() - t0)
