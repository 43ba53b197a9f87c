"""Supported solve of a ``BeamModel`` and its post-processing per rpm.

Solve
-----
The model is assembled banded, the held dofs are eliminated and the system is factorised once
(banded Cholesky with symmetric Jacobi scaling and one step of iterative refinement) and solved
for every load column of the model (one per speed-law pattern and load name, at the loads'
written magnitudes: the parts' m e ω² at ``REF_RPM``). Every solve is checked by its
componentwise backward error (``RESIDUAL_TOL``) and reports its relative residual and a 1-norm
condition estimate. A speed (``result_at``) or a load case (``result_of_case``) is then the sum
of the columns times their factors (``shaftfe.model.loads.law_factor`` / ``LoadCase.factor``).

Results
-------
Per rpm (``BeamResult``): bearing reactions (vector, magnitude, ISO 281 basic L10h = (C/P)^p 10⁶ /
(60 n)), deflection line and named-station deflections, bending moment/torque at both ends of
every element (jumps at tilt springs are kept), axial force N and torque T there (from the
same element end forces: statics of the axial bearing and of the torque path), nominal bending
stress σ_b = M/W (32 M/(π d³) for a solid section; at a shoulder each side uses its own
diameter, so the maximum is on the smaller one), σ_N = N/A, τ = |T| (D/2)/J (16 T/(π d³)
solid), the combined normal stress of the worst fibre σ = |σ_N| + σ_b (the fibre where bending
adds to the axial stress) and von Mises of (σ, τ) (``shaftfe.util.units.von_mises``), its
maximum and x; at each notch (``beam.model.BeamNotch``) the peak von Mises of
(Kt_b σ_b + Kt_N |σ_N|, Kt_T τ) on the notch's own section: a shoulder's smaller diameter, a
groove's (or an undercut's) bottom diameter, a transverse hole's net section, where torsion's
peak is the bore's uniaxial 2 Kt_T τ (its shear enters as (2/√3) Kt_T τ); a load that is zero
adds nothing, even under an infinite Kt (``shaftfe.beam.scf``: the fits and the converged
tables). Reactions are the forces the supports exert ON the shaft (bearing load = −reaction);
L10h from the radial load.

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
from shaftfe.beam.scf import net_section_moduli
from shaftfe.errors import InputError, SolverError
from shaftfe.model.bearing_life import l10h
from shaftfe.model.loads import law_factor
from shaftfe.util.notices import warn
from shaftfe.util.units import REF_RPM, von_mises

# --------------------------------------------------------------------------- solve

@dataclass(frozen=True, eq=False)
class UnitSolution:
    """Displacements for every load column of the model (``BeamModel.columns``: the loads at
    their written magnitudes); reactions and element end forces in the same columns."""
    model: BeamModel
    u: np.ndarray                 # (ndof, n_col)
    r: np.ndarray                 # (ndof, n_col) support reactions on the shaft, K u − f
    end_forces: np.ndarray        # (n_el, 12, n_col) element end forces (internal, on element)
    relative_residual: float = 0.0   # max over the load columns of ‖K u − F‖/‖F‖ (free dofs)
    backward_error: float = 0.0      # componentwise (Oettli-Prager), checked ≤ RESIDUAL_TOL
    cond_estimate: float = math.nan  # 1-norm condition estimate of the supported K (Hager)


_BAND = 2 * NDOF - 1              # upper bandwidth of the assembled stiffness
RESIDUAL_TOL = 1e-8               # every solve: componentwise backward error below this


def solve_unit(model: BeamModel) -> UnitSolution:
    """Assemble (banded), apply supports, factorise once and solve every load column.

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
    F = model.f
    ncol = F.shape[1]
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
    u = np.zeros((ndof, ncol))
    uf = np.zeros((nf, ncol))
    if ncol:
        uf = d[:, None] * cho_solve_banded((c, False), d[:, None] * F[free])
        uf += d[:, None] * cho_solve_banded((c, False), d[:, None] * (F[free] - Kr @ uf))
    u[free] = uf
    relres, berr, cond = _solve_checks(Kr, d, c, uf, F[free], model.name)
    # element end forces (internal): K_e u_e minus the fixed-end forces of element line loads
    ue = u[dofs]                                            # (ne, 12, 2)
    fe = np.einsum("eij,ejc->eic", ke, ue)
    # reactions: r = K_elastic u − F (= −K_spring u at springs, the held force at held dofs)
    r = np.zeros((ndof, ncol))
    for k in range(ncol):
        r[:, k] = np.bincount(dofs.ravel(), weights=fe[:, :, k].ravel(), minlength=ndof)
    r -= F
    for k in range(ncol):
        if np.any(model.q[k]):
            fe[:, :, k] -= _element_fixed_end_loads(model.L, model.q[k])
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
    if F.shape[1] == 0:
        return 0.0, 0.0, math.nan
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
    Fx_N: float           # axial reaction (the axial bearing)
    L10h: float           # ISO 281 basic rating life from F_N, hours (inf if unloaded, rpm = 0)


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
    sigma_nom_MPa: float      # von Mises nominal on the smaller diameter at the shoulder (a
    #                           groove's bottom diameter, a hole's net section)
    sigma_peak_MPa: float     # von Mises of (Kt_b σ_b + Kt_N |σ_N|, Kt_T τ) (``_peak``)
    kt_tension: float = 1.0
    kt_torsion: float = 1.0
    M_Nmm: float = 0.0        # bending moment on the smaller diameter at the shoulder
    N_N: float = 0.0          # axial force there
    T_Nmm: float = 0.0        # torque there
    undercut: str = ""        # a DIN 509 undercut's kind (``beam.model.BeamNotch.undercut``)
    kind: str = "shoulder"    # ``BeamNotch.kind``: shoulder | groove | ring_groove | cross_hole
    name: str = ""
    hole_mm: float = 0.0


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
    sigma_vm: np.ndarray      # von Mises of (sigma_x, tau)
    max_sigma_vm_MPa: float
    x_max_sigma_vm_mm: float
    notches: tuple[NotchResult, ...]
    max_peak_MPa: float       # max(nominal von Mises, Kt × nominal at the notches)
    x_max_peak_mm: float
    notes: tuple[str, ...] = field(default_factory=tuple)
    relative_residual: float = 0.0    # of the one supported solve (UnitSolution)
    backward_error: float = 0.0       # componentwise backward error of that solve
    cond_estimate: float = math.nan   # 1-norm condition estimate of the supported stiffness
    N: np.ndarray | None = None       # axial force at x_sec, N (tension > 0)
    sigma_N: np.ndarray | None = None     # N / A, MPa
    sigma_x: np.ndarray | None = None     # |σ_N| + σ_b: the worst fibre's normal stress, MPa
    case: str = ""                    # the load case's name ("" = a plain speed)
    torsion_gauge_Nmm: float = 0.0    # torque at the torsion gauge (0 unless a case is unbalanced)

    @property
    def max_deflection_mm(self) -> float:
        return float(self.u.max())

    def max_abs(self, line: str) -> float:
        """max |·| of a line along the shaft ("N", "T", "tau", "sigma_N", ...), 0 if empty."""
        v = getattr(self, line)
        return float(np.abs(v).max()) if v is not None and v.size else 0.0

    def to_dict(self, lines: bool = False) -> dict:
        def fin(v):
            return None if not math.isfinite(v) else v
        d = {
            "variant": self.name, "rpm": self.rpm, "case": self.case,
            "rigid_supports": self.rigid_supports,
            "bearings": [{"name": b.name, "x_mm": b.x_mm, "Fy_N": b.Fy_N, "Fz_N": b.Fz_N,
                          "F_N": b.F_N, "Fx_N": b.Fx_N, "L10h": fin(b.L10h)}
                         for b in self.bearings],
            "stations": {k: {"x_mm": s.x_mm, "uy_mm": s.uy_mm, "uz_mm": s.uz_mm,
                             "u_mm": s.u_mm} for k, s in self.stations.items()},
            "max_deflection_mm": self.max_deflection_mm,
            "max_sigma_vm_nominal_MPa": self.max_sigma_vm_MPa,
            "x_max_sigma_vm_nominal_mm": self.x_max_sigma_vm_mm,
            "max_sigma_vm_with_kt_MPa": fin(self.max_peak_MPa),
            "x_max_sigma_vm_with_kt_mm": self.x_max_peak_mm,
            "notches": [{"x_mm": n.x_mm, "D_mm": n.D_mm, "d_mm": n.d_mm, "r_mm": n.r_mm,
                         "kt": fin(n.kt), "kt_in_range": n.kt_in_range, "kt_note": n.kt_note,
                         "kt_tension": fin(n.kt_tension), "kt_torsion": fin(n.kt_torsion),
                         "M_Nmm": n.M_Nmm, "N_N": n.N_N, "T_Nmm": n.T_Nmm,
                         **({"undercut": n.undercut} if n.undercut else {}),
                         **({"kind": n.kind, "name": n.name} if n.kind != "shoulder" else {}),
                         **({"hole_mm": n.hole_mm} if n.kind == "cross_hole" else {}),
                         "sigma_nom_MPa": n.sigma_nom_MPa, "sigma_peak_MPa": fin(n.sigma_peak_MPa)}
                        for n in self.notches],
            "max_abs_N_N": self.max_abs("N"), "max_abs_T_Nmm": self.max_abs("T"),
            "max_tau_MPa": self.max_abs("tau"), "torsion_gauge_Nmm": self.torsion_gauge_Nmm,
            "notes": list(self.notes),
            "solve": {"relative_residual": self.relative_residual,
                      "backward_error": self.backward_error,
                      "cond_estimate": fin(self.cond_estimate)},
        }
        if lines:
            d["lines"] = {"x_mm": self.x.tolist(), "uy_mm": self.uy.tolist(),
                          "uz_mm": self.uz.tolist(), "x_sec_mm": self.x_sec.tolist(),
                          "M_Nmm": self.M.tolist(), "N_N": self.N.tolist(),
                          "T_Nmm": self.T.tolist(), "sigma_vm_MPa": self.sigma_vm.tolist()}
        return d




AT_REST_NOTE = ("0 rpm: no load (the only load, the parts' m·e·ω², is zero at rest): every "
                "reaction, deflection and stress is 0 and the bearing life unbounded")
AXIAL_LIFE_NOTE = ("L10h from the radial load only: the bearing's axial load Fx (ISO 281 "
                   "P = X F_r + Y F_a) needs X and Y, which the variant does not give")
# the torsion gauge (no bearing holds torsion) must carry no torque: a case whose torques do
# not balance (a factor on one torque of a pair) is reported, beyond round-off of the inputs
GAUGE_TOL = 1e-9
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


def column_factors(model: BeamModel, rpm: float, case=None) -> np.ndarray:
    """The factor of every load column at a plain speed ``rpm`` (rpm² loads × (rpm/ref)²,
    constant × 1, channel loads at their reference) or in ``case`` (a ``LoadCase``)."""
    if case is not None:
        return np.array([case.factor(c) for c in model.columns])
    return np.array([law_factor(c.scales_with, rpm, {}, ref_rpm=c.ref_rpm,
                                channel_ref=c.channel_ref) for c in model.columns])


def result_at(sol: UnitSolution, rpm: float, case=None) -> BeamResult:
    """Superpose the load columns at ``rpm`` (or in the load case ``case``, at its speed) and
    post-process."""
    m = sol.model
    if case is not None:
        rpm = case.rpm
    coef = column_factors(m, rpm, case)
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
    def line(dof):
        return np.stack([-fe[:, dof], fe[:, NDOF + dof]], 1).ravel()
    My, Mz, T, N = line(RY), line(RZ), line(RX), line(UX)
    # a torque or an axial force below round-off of the applied ones is zero (statics: the
    # load columns' own torques cancel only in the sum)
    for line_, key in ((T, "torque_abs_Nmm"), (N, "axial_abs_N")):
        line_[np.abs(line_) <= GAUGE_TOL * _applied(m, coef, key)] = 0.0
    M = np.hypot(My, Mz)
    x_sec = np.stack([m.x[:-1], m.x[1:]], 1).ravel()
    sec = m.sections
    W, Wt, A = np.repeat(sec.W, 2), np.repeat(sec.Wt, 2), np.repeat(sec.A, 2)
    sigma, sigma_N, tau = M / W, N / A, np.abs(T) / Wt
    sigma_x = np.abs(sigma_N) + sigma
    zero = np.zeros_like(sigma)
    vm = von_mises((sigma_x, zero, zero, tau, zero, zero))
    imax = int(np.argmax(vm))
    notches = []
    for sh in m.notches:
        # the element end on the small-diameter side of a shoulder's node; both sides of a
        # groove's or hole's node (a point load there: the worse)
        ks = ([2 * (sh.node - 1) + 1] if sh.small_side == "left" else [2 * sh.node]
              if sh.small_side == "right" else [2 * (sh.node - 1) + 1, 2 * sh.node])
        nt = max((_notch_at(sh, k, M, N, T, sigma, sigma_N, tau, vm) for k in ks),
                 key=lambda r: r.sigma_peak_MPa)
        notches.append(nt)
    clr = stations.get("clearance")
    where = f"beam, {case.name}" if case is not None else f"beam, {rpm:g} rpm"
    check_deflection(where, float(m.x[-1] - m.x[0]), float(umag.max()),
                     None if clr is None else clr.u_mm, m.clearance_mm)
    gauge = _gauge_torque(m, r, coef, where)
    peak, xpeak = float(vm[imax]), float(x_sec[imax])
    for nt in notches:
        if nt.sigma_peak_MPa > peak:
            peak, xpeak = nt.sigma_peak_MPa, nt.x_mm
    notes = m.notes
    loaded = np.abs(m.f).max(axis=0, initial=0.0) > 0
    if rpm == 0 and not np.any(coef[loaded]):
        notes += (AT_REST_NOTE,)
    if any(b.Fx_N for b in bearings):
        notes += (AXIAL_LIFE_NOTE,)
    return BeamResult(
        name=m.name, rpm=float(rpm), rigid_supports=m.rigid_supports, x=m.x, uy=uy, uz=uz,
        u=umag, stations=MappingProxyType(stations), bearings=tuple(bearings), x_sec=x_sec,
        d_sec=np.repeat(sec.D, 2), My=My, Mz=Mz, M=M, T=T, sigma=sigma, tau=tau, sigma_vm=vm,
        max_sigma_vm_MPa=float(vm[imax]), x_max_sigma_vm_mm=float(x_sec[imax]),
        notches=tuple(notches), max_peak_MPa=peak, x_max_peak_mm=xpeak, notes=notes,
        relative_residual=sol.relative_residual, backward_error=sol.backward_error,
        cond_estimate=sol.cond_estimate, N=N, sigma_N=sigma_N, sigma_x=sigma_x,
        case="" if case is None else case.name, torsion_gauge_Nmm=gauge)


def _notch_at(sh, k: int, M, N, T, sigma, sigma_N, tau, vm) -> NotchResult:
    """The notch ``sh`` judged at element end ``k``: the nominal stresses on its own section
    (a shoulder's smaller diameter, an undercut's or a groove's bottom diameter, a hole's net
    section, ``scf.net_section_moduli``) and the peak ``_peak``."""
    sb, sn, tt, nom = sigma[k], sigma_N[k], tau[k], vm[k]
    if sh.kind == "cross_hole":
        a, wb, wt = net_section_moduli(sh.d_mm, sh.hole_mm)
        sb, sn, tt = M[k] / wb, N[k] / a, abs(T[k]) / wt
    elif sh.undercut or sh.kind != "shoulder":      # on the bottom diameter
        d = sh.d_mm
        sb, sn, tt = (32.0 * M[k] / (np.pi * d ** 3), 4.0 * N[k] / (np.pi * d ** 2),
                      16.0 * abs(T[k]) / (np.pi * d ** 3))
    if sh.undercut or sh.kind != "shoulder":        # the element's own is the full section's
        nom = von_mises((abs(sn) + sb, 0.0, 0.0, tt, 0.0, 0.0))
    return NotchResult(sh.x_mm, sh.D_mm, sh.d_mm, sh.r_mm, sh.kt, sh.kt_in_range,
                       _kt_note(sh, sn, tt), float(nom), float(_peak(sh, sb, sn, tt)),
                       sh.kt_tension, sh.kt_torsion, float(M[k]), float(N[k]), float(T[k]),
                       sh.undercut, sh.kind, sh.name, sh.hole_mm)


def _peak(sh, sb: float, sn: float, tt: float) -> float:
    """von Mises of (Kt_b σ_b + Kt_N |σ_N|, Kt_T τ): each load's peak added as if at one
    point (conservative where they are not). A load that is zero contributes nothing, also
    where its Kt is infinite (a sharp corner). At a transverse hole torsion's peak is the
    bore's uniaxial stress 2 τ_max = 2 Kt_T τ (Kt_T of the largest shear stress), so its
    shear enters as (2/√3) Kt_T τ."""
    def part(kt: float, s: float) -> float:
        return kt * s if s else 0.0
    shear = part(sh.kt_torsion, tt) * (2.0 / math.sqrt(3.0) if sh.kind == "cross_hole" else 1)
    return von_mises((part(sh.kt, sb) + part(sh.kt_tension, abs(sn)), 0.0, 0.0, shear, 0.0,
                      0.0))


def _kt_note(sh, sigma_N: float, tau: float) -> str:
    """The shoulder's Kt notes of the loads it carries (bending always; tension and torsion
    where they are non-zero)."""
    out = [sh.kt_note] if sh.kt_note else []
    if sh.kind != "shoulder":
        out.insert(0, f"{sh.name}: Kt {sh.kt_fit}")
    if sh.undercut:
        out.insert(0, f"DIN 509 {sh.undercut[-1].upper()} undercut: Kt of a shoulder to its "
                   f"bottom Ø{sh.d_mm:g} with its radius {sh.r_mm:g}")
    if sigma_N and sh.kt_tension_note:
        out.append(f"tension: {sh.kt_tension_note}")
    if tau and sh.kt_torsion_note:
        out.append(f"torsion: {sh.kt_torsion_note}")
    return "; ".join(out)


def _applied(m: BeamModel, coef: np.ndarray, key: str) -> float:
    """Σ over the load columns of |factor| × the column's applied Σ|T| or Σ|F_x| (``key``)."""
    return float(np.abs(coef) @ np.array([getattr(c, key) for c in m.columns]))


def _gauge_torque(m: BeamModel, r: np.ndarray, coef: np.ndarray, where: str) -> float:
    """The torque the torsion gauge carries (0 when a bearing holds torsion). Zero to
    round-off when the torques balance; else a visible warning (the case's torques do not)."""
    if m.torsion_held or not m.supports:
        return 0.0
    t = float(r[NDOF * m.torsion_node + RX])
    if abs(t) > GAUGE_TOL * max(_applied(m, coef, "torque_abs_Nmm"), 1.0):
        warn("torque-unbalanced", where, f"the applied torques do not balance (net "
             f"{-t:.4g} N·mm) and no bearing holds torsion: the beam holds the twist at "
             f"x = {m.x[m.torsion_node]:g} mm to solve, which is not physical (declare "
             "holds_torsion on the bearing that reacts it, or balance the case's factors)")
    return t


def solve_cases(model: BeamModel, cases) -> tuple[BeamResult, ...]:
    """Solve once and return one ``BeamResult`` per load case (``LoadCase``)."""
    sol = solve_unit(model)
    return tuple(result_at(sol, c.rpm, c) for c in cases)


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


def beam_at_ref(variant) -> BeamResult:
    """The beam solution at ``util.units.REF_RPM`` (DIN 743's and the bearings' input)."""
    return analyse(variant, REF_RPM)[0]

