"""Supported solve of a ``BeamModel`` and its post-processing per rpm.

Solve
-----
The model is assembled banded, the held dofs are eliminated and the system is solved once
(banded Cholesky with symmetric Jacobi scaling and one step of iterative refinement) for two
load cases: the centrifugal loads per unit ω² (rad²/s²) and the static extra loads. Every solve
is checked by its componentwise backward error (``RESIDUAL_TOL``) and reports its relative
residual and a 1-norm condition estimate. Each rpm then scales the unit solution by ω².

Results
-------
Per rpm (``BeamResult``): bearing reactions (vector, magnitude, ISO 281 basic L10h = (C/P)^p 10⁶ /
(60 n)), deflection line and named-station deflections, bending moment/torque at both ends of
every element (jumps at tilt springs are kept), nominal bending stress σ = M/W (32 M/(π d³) for a
solid section; at a shoulder each side uses its own diameter, so the maximum is on the smaller
one), τ = T (D/2)/J (16 T/(π d³) solid), von Mises √(σ² + 3τ²), its maximum and x, and at each
shoulder Kt (``shaftfe.beam.scf``, bending fit) × the nominal von Mises stress on the smaller
diameter at the shoulder (a torsion Kts is not modelled: the seed's loads carry no torque).
Reactions are the forces the supports exert ON the shaft (bearing load = −reaction).

Units: mm, N, MPa, t/mm³; rpm for speeds. Pure functions; SciPy is imported inside the solve.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np

from shaftfe.beam.elements import NDOF, RX, RY, RZ, UX, UY, UZ, element_stiffness
from shaftfe.beam.model import (
    BeamModel,
    _element_dofs,
    _support_terms,
    build_model,
    check_supports,
)
from shaftfe.errors import InputError, SolverError
from shaftfe.model.bearing_life import l10h
from shaftfe.util.units import omega

# --------------------------------------------------------------------------- solve

@dataclass(frozen=True, eq=False)
class UnitSolution:
    """Displacements for the centrifugal loads per unit ω² (column 0) and for the static extra
    loads (column 1); reactions in the same two columns."""
    model: BeamModel
    u: np.ndarray                 # (ndof, 2)
    r: np.ndarray                 # (ndof, 2) support reactions on the shaft, K u − f
    end_forces: np.ndarray        # (n_el, 12, 2) element end forces (internal, on element)
    relative_residual: float = 0.0   # max over the load columns of ‖K u − F‖/‖F‖ (free dofs)
    backward_error: float = 0.0      # componentwise (Oettli-Prager), checked ≤ RESIDUAL_TOL
    cond_estimate: float = math.nan  # 1-norm condition estimate of the supported K (Hager)


_BAND = 2 * NDOF - 1              # upper bandwidth of the assembled stiffness
RESIDUAL_TOL = 1e-8               # every solve: componentwise backward error below this


def solve_unit(model: BeamModel) -> UnitSolution:
    """Assemble (banded), apply supports and solve once for the unit-ω² and static load cases.

    Held dofs are eliminated; the reduced matrix keeps the 11-wide band, so the solve is a
    banded Cholesky factorisation (O(n))."""
    from scipy.linalg import LinAlgError, cho_solve_banded, cholesky_banded

    check_supports(model)
    ndof = NDOF * model.n_nodes
    ke = element_stiffness(model.L, model.E, model.G, model.sections)
    dofs = _element_dofs(model.n_elements)
    terms, fixed = _support_terms(model)
    rows = [np.broadcast_to(dofs[:, :, None], ke.shape).ravel()]
    cols = [np.broadcast_to(dofs[:, None, :], ke.shape).ravel()]
    vals = [ke.ravel()]
    for idx, k in terms:
        rows.append(np.repeat(idx, idx.size))
        cols.append(np.tile(idx, idx.size))
        vals.append(k.ravel())
    rows, cols, vals = (np.concatenate(v) for v in (rows, cols, vals))
    red = np.full(ndof, -1)
    free = np.setdiff1d(np.arange(ndof), fixed)
    red[free] = np.arange(free.size)
    ri, ci = red[rows], red[cols]
    keep = (ri >= 0) & (ci >= 0) & (ci >= ri)
    ri, ci, vals = ri[keep], ci[keep], vals[keep]
    nf = free.size
    ab = np.bincount((_BAND + ri - ci) * nf + ci, weights=vals,
                     minlength=(_BAND + 1) * nf).reshape(_BAND + 1, nf)
    F = np.stack([model.load_unit, model.load_static], axis=1)
    # symmetric Jacobi scaling D K D (translations in N/mm, rotations in N·mm/rad: the scaled
    # matrix has a unit diagonal) and one step of iterative refinement against the unscaled
    # triplets (issue 8: stiffness 1 … 1e12 N/mm)
    d = 1.0 / np.sqrt(ab[_BAND])
    j = np.arange(nf)
    ab = ab * np.stack([d[np.clip(j - (_BAND - b), 0, nf - 1)] for b in range(_BAND + 1)]) * d
    try:
        c = cholesky_banded(ab, lower=False, check_finite=True)
    except LinAlgError as exc:    # pragma: no cover - guarded by check_supports
        raise SolverError(f"beam model {model.name!r}: stiffness not positive definite "
                          f"({exc})") from None
    Kr = _reduced_matrix(ri, ci, vals, nf)
    u = np.zeros((ndof, 2))
    uf = d[:, None] * cho_solve_banded((c, False), d[:, None] * F[free])
    uf += d[:, None] * cho_solve_banded((c, False), d[:, None] * (F[free] - Kr @ uf))
    u[free] = uf
    relres, berr, cond = _solve_checks(Kr, d, c, uf, F[free], model.name)
    # element end forces (internal): K_e u_e minus the fixed-end forces of element line loads
    ue = u[dofs]                                            # (ne, 12, 2)
    fe = np.einsum("eij,ejc->eic", ke, ue)
    # reactions: r = K_elastic u − F (= −K_spring u at springs, the held force at held dofs)
    r = np.stack([np.bincount(dofs.ravel(), weights=fe[:, :, k].ravel(), minlength=ndof)
                  for k in range(2)], axis=1) - F
    if model.spread_loads:
        fe[:, :, 0] -= _element_fixed_end_loads(model.L, model.q_unit)
    return UnitSolution(model=model, u=u, r=r, end_forces=fe, relative_residual=relres,
                        backward_error=berr, cond_estimate=cond)


def _reduced_matrix(ri, ci, vals, nf):
    """The reduced stiffness as a full symmetric CSR matrix from its upper-triangle triplets."""
    import scipy.sparse as sp

    up = sp.csr_matrix((vals, (ri, ci)), shape=(nf, nf))
    return (up + sp.triu(up, 1, format="csr").T).tocsr()


def _solve_checks(K, d, c, u, F, name) -> tuple[float, float, float]:
    """Residual checks of the reduced system K u = F (K rebuilt from its triplets, not from
    the factor), per load column, worst column reported:

    * relative residual ‖K u − F‖₂/‖F‖₂ (reported). Its floor for the exactly rounded u is
      ≈ eps ‖K‖ ‖u‖/‖F‖, which short elements (seat edges 0.5 mm apart: 3e-9) and soft
      supports (rigid motion ≫ bending: 3e-5 at 1 N/mm on a 400 mm shaft) push above 1e-8;
    * componentwise backward error ω = maxᵢ |K u − F|ᵢ / (|K| |u| + |F|)ᵢ (Oettli-Prager; what
      SuperLU calls BERR), scale- and unit-invariant: ~1e-16 for a stable solve. The solve
      fails (SolverError) if ω > ``RESIDUAL_TOL``;
    * Hager's 1-norm estimate of cond₁(K) = ‖K‖₁ ‖K⁻¹‖₁ (``onenormest`` on the solve with the
      factor of D K D, K⁻¹ = D (DKD)⁻¹ D)."""
    from scipy.linalg import cho_solve_banded
    from scipy.sparse.linalg import LinearOperator, onenormest

    nf = K.shape[0]
    fn = np.linalg.norm(F, axis=0)
    r = K @ u - F
    rn = np.linalg.norm(r, axis=0)
    relres = float(max((a / b for a, b in zip(rn, fn, strict=True) if b > 0), default=0.0))
    den = abs(K) @ np.abs(u) + np.abs(F)
    ratio = np.divide(np.abs(r), den, out=np.zeros_like(den), where=den > 0)
    berr = float(ratio.max()) if ratio.size else 0.0
    if not (berr <= RESIDUAL_TOL):
        raise SolverError(f"beam model {name!r}: the linear solve did not converge "
                          f"(backward error {berr:.2e}, relative residual {relres:.2e}; limit "
                          f"{RESIDUAL_TOL:g})")
    cond = math.nan
    if nf >= 2:
        def inv(b):
            b = np.asarray(b, dtype=float)
            dd = d if b.ndim == 1 else d[:, None]
            return dd * cho_solve_banded((c, False), dd * b)
        op = LinearOperator((nf, nf), matvec=inv, rmatvec=inv, matmat=inv, dtype=float)
        cond = float(abs(K).sum(axis=0).max() * onenormest(op))
    return relres, berr, cond


def _element_fixed_end_loads(L: np.ndarray, q: np.ndarray) -> np.ndarray:
    """(n_el, 12) consistent nodal loads of each element's own line load."""
    f = np.zeros((L.size, 2 * NDOF))
    for c, (dv, dr, sgn) in enumerate(((UY, RZ, 1.0), (UZ, RY, -1.0))):
        qe = q[:, c]
        f[:, dv] = f[:, NDOF + dv] = 0.5 * qe * L
        f[:, dr] = sgn * qe * L**2 / 12.0
        f[:, NDOF + dr] = -sgn * qe * L**2 / 12.0
    return f


# --------------------------------------------------------------------------- results

@dataclass(frozen=True)
class BearingResult:
    name: str
    x_mm: float
    Fy_N: float           # reaction on the shaft
    Fz_N: float
    F_N: float            # radial magnitude (= bearing load P)
    Fx_N: float
    L10h: float           # ISO 281 basic rating life, hours (inf if unloaded or rpm = 0)


@dataclass(frozen=True)
class StationResult:
    x_mm: float
    uy_mm: float
    uz_mm: float
    u_mm: float


@dataclass(frozen=True)
class NotchResult:
    x_mm: float
    D_mm: float
    d_mm: float
    r_mm: float
    kt: float
    kt_in_range: bool
    kt_note: str
    sigma_nom_MPa: float      # von Mises nominal on the smaller diameter at the shoulder
    sigma_peak_MPa: float     # kt × sigma_nom


@dataclass(frozen=True, eq=False)
class BeamResult:
    name: str
    rpm: float
    rigid_supports: bool
    x: np.ndarray             # nodes, mm
    uy: np.ndarray
    uz: np.ndarray
    u: np.ndarray             # |(uy, uz)|
    stations: MappingProxyType    # name -> StationResult
    bearings: tuple[BearingResult, ...]
    x_sec: np.ndarray         # (2 n_el,) element-end stations: start, end of each element
    d_sec: np.ndarray         # outer diameter at those stations
    My: np.ndarray            # bending moment about y, N·mm
    Mz: np.ndarray
    M: np.ndarray
    T: np.ndarray             # torque, N·mm
    sigma: np.ndarray         # nominal bending stress, MPa
    tau: np.ndarray           # nominal torsional shear stress, MPa
    sigma_vm: np.ndarray      # von Mises of (sigma, tau)
    max_sigma_vm_MPa: float
    x_max_sigma_vm_mm: float
    notches: tuple[NotchResult, ...]
    max_peak_MPa: float       # max(nominal von Mises, Kt × nominal at shoulders)
    x_max_peak_mm: float
    notes: tuple[str, ...] = field(default_factory=tuple)
    relative_residual: float = 0.0    # of the one supported solve (UnitSolution)
    backward_error: float = 0.0       # componentwise backward error of that solve
    cond_estimate: float = math.nan   # 1-norm condition estimate of the supported stiffness

    @property
    def max_deflection_mm(self) -> float:
        return float(self.u.max())

    def to_dict(self, lines: bool = False) -> dict:
        def fin(v):
            return None if not math.isfinite(v) else v
        d = {
            "variant": self.name, "rpm": self.rpm, "rigid_supports": self.rigid_supports,
            "bearings": [{"name": b.name, "x_mm": b.x_mm, "Fy_N": b.Fy_N, "Fz_N": b.Fz_N,
                          "F_N": b.F_N, "L10h": fin(b.L10h)} for b in self.bearings],
            "stations": {k: {"x_mm": s.x_mm, "uy_mm": s.uy_mm, "uz_mm": s.uz_mm,
                             "u_mm": s.u_mm} for k, s in self.stations.items()},
            "max_deflection_mm": self.max_deflection_mm,
            "max_sigma_vm_nominal_MPa": self.max_sigma_vm_MPa,
            "x_max_sigma_vm_nominal_mm": self.x_max_sigma_vm_mm,
            "max_sigma_vm_with_kt_MPa": fin(self.max_peak_MPa),
            "x_max_sigma_vm_with_kt_mm": self.x_max_peak_mm,
            "notches": [{"x_mm": n.x_mm, "D_mm": n.D_mm, "d_mm": n.d_mm, "r_mm": n.r_mm,
                         "kt": fin(n.kt), "kt_in_range": n.kt_in_range, "kt_note": n.kt_note,
                         "sigma_nom_MPa": n.sigma_nom_MPa, "sigma_peak_MPa": fin(n.sigma_peak_MPa)}
                        for n in self.notches],
            "notes": list(self.notes),
            "solve": {"relative_residual": self.relative_residual,
                      "backward_error": self.backward_error,
                      "cond_estimate": fin(self.cond_estimate)},
        }
        if lines:
            d["lines"] = {"x_mm": self.x.tolist(), "uy_mm": self.uy.tolist(),
                          "uz_mm": self.uz.tolist(), "x_sec_mm": self.x_sec.tolist(),
                          "M_Nmm": self.M.tolist(), "sigma_vm_MPa": self.sigma_vm.tolist()}
        return d




AT_REST_NOTE = ("0 rpm: no load (the only load, the parts' m·e·ω², is zero at rest): every "
                "reaction, deflection and stress is 0 and the bearing life unbounded")
# small-deflection model: a linear beam (and the linear 3D model) holds while rotations stay
# small. A deflection u over the length L bends the shaft to slopes θ ≈ 3 u / L; at u = 0.02 L,
# θ ≈ 0.06 rad and the neglected second-order terms (1 − cos θ ≈ θ²/2, the axial shortening)
# are 0.2 % of the result: beyond that the linear answer is not the physics
SMALL_DEFLECTION_FRACTION = 0.02


def check_deflection(where: str, length_mm: float, u_max_mm: float,
                     u_clearance_mm: float | None, clearance_mm: float | None) -> None:
    """Rules (issue #30), one for the beam and the 3D model: a deflection above
    SMALL_DEFLECTION_FRACTION × the shaft's length is outside the small-deflection model, and a
    deflection at the clearance station above the clearance the variant file states
    (``shaft.clearance_to_crankshaft_mm``) means the shaft touches the crankshaft, which no model
    here includes: either is a visible warning (the numbers are not a result)."""
    from shaftfe.util.notices import warn
    lim = SMALL_DEFLECTION_FRACTION * length_mm
    if u_max_mm > lim:
        warn("deflection-large", where, f"max deflection {u_max_mm:.4g} mm exceeds "
             f"{SMALL_DEFLECTION_FRACTION:g} × the shaft length ({lim:.3g} mm): outside the "
             "small-deflection (linear) model, the result is not valid (check the bearing "
             "stiffness and the loads)")
    if clearance_mm is not None and u_clearance_mm is not None and u_clearance_mm > clearance_mm:
        warn("deflection-clearance", where, f"deflection {u_clearance_mm:.4g} mm at the "
             f"clearance station exceeds the {clearance_mm:g} mm clearance to the crankshaft "
             "stated in the variant file: the shaft would touch it (contact is not modelled)")


def result_at(sol: UnitSolution, rpm: float) -> BeamResult:
    """Scale the unit solution to ``rpm`` (centrifugal loads ∝ ω²) and post-process."""
    m = sol.model
    w2 = omega(rpm) ** 2
    coef = np.array([w2, 1.0])
    u = sol.u @ coef
    r = sol.r @ coef
    fe = sol.end_forces @ coef                                  # (ne, 12)
    uy, uz = u[UY::NDOF], u[UZ::NDOF]
    umag = np.hypot(uy, uz)
    stations = {k: StationResult(float(m.x[i]), float(uy[i]), float(uz[i]), float(umag[i]))
                for k, i in m.stations.items()}
    bearings = []
    for s in m.supports:
        b = NDOF * s.node
        Fy, Fz, Fx = float(r[b + UY]), float(r[b + UZ]), float(r[b + UX]) if s.axial else 0.0
        F = math.hypot(Fy, Fz)
        bearings.append(BearingResult(s.name, s.x_mm, Fy, Fz, F, Fx,
                                      l10h(s.C_N, F, rpm, s.life_exponent)))
    # internal resultants at element ends: start = −f(start), end = +f(end)
    My = np.stack([-fe[:, RY], fe[:, NDOF + RY]], 1).ravel()
    Mz = np.stack([-fe[:, RZ], fe[:, NDOF + RZ]], 1).ravel()
    T = np.stack([-fe[:, RX], fe[:, NDOF + RX]], 1).ravel()
    M = np.hypot(My, Mz)
    x_sec = np.stack([m.x[:-1], m.x[1:]], 1).ravel()
    sec = m.sections
    W = np.repeat(sec.W, 2)
    Wt = np.repeat(sec.Wt, 2)
    sigma = M / W
    tau = np.abs(T) / Wt
    vm = np.sqrt(sigma**2 + 3.0 * tau**2)
    imax = int(np.argmax(vm))
    notches = []
    for sh in m.shoulders:
        # element on the small-diameter side of the shoulder node
        e = sh.node - 1 if sh.small_side == "left" else sh.node
        k = 2 * e + (1 if sh.small_side == "left" else 0)
        s_nom = float(vm[k])
        notches.append(NotchResult(sh.x_mm, sh.D_mm, sh.d_mm, sh.r_mm, sh.kt, sh.kt_in_range,
                                   sh.kt_note, s_nom, sh.kt * s_nom))
    clr = stations.get("clearance")
    check_deflection(f"beam, {rpm:g} rpm", float(m.x[-1] - m.x[0]), float(umag.max()),
                     None if clr is None else clr.u_mm, m.clearance_mm)
    peak, xpeak = float(vm[imax]), float(x_sec[imax])
    for nt in notches:
        if nt.sigma_peak_MPa > peak:
            peak, xpeak = nt.sigma_peak_MPa, nt.x_mm
    return BeamResult(
        name=m.name, rpm=float(rpm), rigid_supports=m.rigid_supports, x=m.x, uy=uy, uz=uz,
        u=umag, stations=MappingProxyType(stations), bearings=tuple(bearings), x_sec=x_sec,
        d_sec=np.repeat(sec.D, 2), My=My, Mz=Mz, M=M, T=T, sigma=sigma, tau=tau, sigma_vm=vm,
        max_sigma_vm_MPa=float(vm[imax]), x_max_sigma_vm_mm=float(x_sec[imax]),
        notches=tuple(notches), max_peak_MPa=peak, x_max_peak_mm=xpeak,
        notes=m.notes + ((AT_REST_NOTE,) if rpm == 0 else ()),
        relative_residual=sol.relative_residual, backward_error=sol.backward_error,
        cond_estimate=sol.cond_estimate)


def solve(model: BeamModel, rpm: float | Sequence[float]) -> tuple[BeamResult, ...]:
    """Solve once and return one ``BeamResult`` per rpm."""
    rpms = [rpm] if isinstance(rpm, (int, float)) else list(rpm)
    for v in rpms:
        if not (math.isfinite(v) and v >= 0):
            raise InputError("--rpm", "rpm", ">= 0", got=v)
    sol = solve_unit(model)
    return tuple(result_at(sol, v) for v in rpms)


def analyse(variant, rpm: float | Sequence[float], **options) -> tuple[BeamResult, ...]:
    """``build_model`` + ``solve`` in one call (options as for ``build_model``)."""
    return solve(build_model(variant, **options), rpm)

