"""The Campbell sweep of a linear rotor model: the reduced-basis kernels of
``shaftfe.rotordynamics.kernels`` chained over the speeds (steps 1-4 of the method there), the
critical speeds (step 5) and the result (``CampbellResult``: frequencies, damping ratios, whirl
labels, critical speeds; CSV/JSON rows).

Pure functions; NumPy at module level, SciPy inside the kernels.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from shaftfe.errors import InputError, SolverError
from shaftfe.rotordynamics.kernels import (
    TWO_PI,
    Labelling,
    assign,
    choose_basis,
    label_modes,
    reduced_eig,
    rpm_to_rad_s,
)
from shaftfe.rotordynamics.options import DEFAULT_ORDERS


@dataclass(frozen=True)
class CriticalSpeed:
    order: float
    branch: int
    rpm: float
    freq_hz: float
    whirl: str


@dataclass(frozen=True, eq=False)
class CampbellResult:
    """Frequencies per speed (rows) and branch (columns), with labels."""
    rpm: np.ndarray               # (ns,)
    freq_hz: np.ndarray           # (ns, nb) damped natural frequencies
    zeta: np.ndarray              # (ns, nb) damping ratios −Re s/|s|
    whirl: tuple                  # ns tuples of nb labels
    family: tuple                 # ns tuples of nb families
    whirl_ratio: np.ndarray       # (ns, nb)
    mac_min: np.ndarray           # (ns,) smallest tracking MAC into this speed (1 at the first)
    branch_whirl: tuple           # nb labels (most common over the speeds with Ω > 0)
    orders: tuple
    criticals: tuple              # CriticalSpeed, ...
    basis_size: int
    basis_change: float           # relative change of the requested frequencies, basis ×1.5
    n_rigid: int
    n_dof: int
    notes: tuple = field(default_factory=tuple)
    vectors: np.ndarray | None = None   # (ns, n_dof, nb) complex, if kept

    def lowest_frequency_text(self) -> str:
        """The lowest natural frequency at the first speed and, where it differs (a backward
        branch falls with speed), the lowest over the sweep with its speed and whirl: the
        two values side by side, never one for the other."""
        f0 = float(np.min(self.freq_hz[0]))
        i, j = np.unravel_index(int(np.argmin(self.freq_hz)), self.freq_hz.shape)
        out = f"lowest natural frequency {f0:.4g} Hz at {self.rpm[0]:g} rpm"
        if f"{self.freq_hz[i, j]:.4g}" != f"{f0:.4g}":
            out += (f", {self.freq_hz[i, j]:.4g} Hz at {self.rpm[i]:g} rpm "
                    f"({self.whirl[i][j]} whirl, mode {j + 1})")
        return out

    def statement(self) -> str:
        lo, hi = float(self.rpm.min()), float(self.rpm.max())
        orders = ", ".join(f"{k:g}×" for k in self.orders)
        if not self.criticals:
            kmax = max(self.orders)
            return (f"no critical speed in {lo:g}-{hi:g} rpm: no branch of the first "
                    f"{self.freq_hz.shape[1]} modes crosses the {orders} excitation line(s) "
                    f"({self.lowest_frequency_text()}; highest excitation {kmax:g} × "
                    f"{hi:g}/60 = {kmax * hi / 60:.4g} Hz)")
        items = "; ".join(f"{c.rpm:.0f} rpm ({c.order:g}×, mode {c.branch + 1}, {c.whirl}, "
                          f"{c.freq_hz:.4g} Hz)" for c in self.criticals)
        return f"critical speeds in {lo:g}-{hi:g} rpm: {items}"

    def rows(self) -> list[dict]:
        out = []
        for i, n in enumerate(self.rpm):
            for j in range(self.freq_hz.shape[1]):
                out.append({"rpm": float(n), "mode": j + 1, "freq_hz": float(self.freq_hz[i, j]),
                            "whirl": self.whirl[i][j], "family": self.family[i][j],
                            "whirl_ratio": float(self.whirl_ratio[i, j]),
                            "zeta": float(self.zeta[i, j])})
        return out

    def to_dict(self) -> dict:
        return {
            "rpm": self.rpm.tolist(), "freq_hz": self.freq_hz.tolist(),
            "whirl": [list(w) for w in self.whirl], "family": [list(f) for f in self.family],
            "whirl_ratio": self.whirl_ratio.tolist(), "zeta": self.zeta.tolist(),
            "branch_whirl": list(self.branch_whirl), "tracking_mac_min": self.mac_min.tolist(),
            "orders": list(self.orders),
            "critical_speeds": [{"order": c.order, "mode": c.branch + 1, "rpm": c.rpm,
                                 "freq_hz": c.freq_hz, "whirl": c.whirl}
                                for c in self.criticals],
            "statement": self.statement(), "basis_size": self.basis_size,
            "basis_change": self.basis_change, "n_rigid_dropped": self.n_rigid,
            "n_dof": self.n_dof, "notes": list(self.notes)}

    def to_csv(self) -> str:
        lines = ["rpm,mode,freq_hz,whirl,family,whirl_ratio,zeta"]
        for r in self.rows():
            lines.append(f"{r['rpm']:g},{r['mode']},{r['freq_hz']:.9g},{r['whirl']},"
                         f"{r['family']},{r['whirl_ratio']:.6f},{r['zeta']:.6g}")
        return "\n".join(lines) + "\n"


def whirl_ratio_text(ratio: float, family: str) -> str:
    """A whirl ratio as shown in tables: signed for a bending (lateral) mode; "—" with the
    mode's kind otherwise (forward/backward whirl has no meaning for torsion or axial
    motion, whose (u_y, u_z) ratio is an artefact)."""
    return f"{ratio:+.3f}" if family == "lateral" else f"— ({family})"


def sweep(K, M, G, rpms: Sequence[float], n_modes: int, lab: Labelling, *, C=None,
          orders: Sequence[float] = DEFAULT_ORDERS, tol: float = 1e-6, sigma: float = 0.0,
          opinv=None,
          keep_vectors: bool = False, n_extra: int = 6, basis_fn=None,
          residuals=None, Kg=None) -> CampbellResult:
    """Campbell sweep of M q̈ + (C + Ω G) q̇ + (K + Ω² Kg) q = 0 over ``rpms`` (the n lowest
    modes; ``Kg`` optional, e.g. the geometric stiffness of the centrifugal prestress per unit
    Ω²)."""
    n_dof = K.shape[0]
    rpm = _checked_speeds(rpms, n_modes, n_dof)
    Om = rpm_to_rad_s(rpm)
    n_cand = min(n_modes + n_extra, n_dof // 2)
    red, change, n_rigid = choose_basis(K, M, G, C, n_modes, float(Om.max()), tol=tol,
                                        sigma=sigma, opinv=opinv,
                                        m0=max(2 * n_modes, n_cand + 2, n_modes + 6),
                                        basis_fn=basis_fn, residuals=residuals, Kg=Kg)
    Phi = red.basis.Phi
    if lab.transform is not None:          # label on F Φ q: map the basis once, not per speed
        from dataclasses import replace

        Phi_lab, lab = lab.transform @ Phi, replace(lab, transform=None)
    else:
        Phi_lab = Phi
    ns = rpm.size
    nb = n_modes
    freq = np.empty((ns, nb))
    zeta = np.empty((ns, nb))
    ratio = np.empty((ns, nb))
    whirl, family = [], []
    mac_min = np.ones(ns)
    vecs_keep = np.empty((ns, n_dof, nb), complex) if keep_vectors else None
    prev_q = prev_f = None
    for i, w in enumerate(Om):
        s, Q, _ = reduced_eig(red, float(w))
        nc = min(s.size, n_cand)
        if nc < nb:
            raise SolverError(f"Campbell: only {nc} oscillatory modes at {rpm[i]:g} rpm")
        s, Q = s[:nc], Q[:, :nc]
        f = s.imag / TWO_PI
        if prev_q is None:
            pick = np.arange(nb)
        else:
            pick, m_ = assign(prev_q, prev_f, Q, f)
            mac_min[i] = float(m_.min())
        s, Q = s[pick], Q[:, pick]
        fam, wl, r = label_modes(Phi_lab @ Q, lab)
        if w == 0.0:
            # no spin, no whirl sense: a degenerate pair may come out as any (even circular)
            # combination, so lateral modes at rest are "undetermined" with ratio 0
            wl = ["undetermined" if f_ == "lateral" else x for f_, x in zip(fam, wl,
                                                                              strict=True)]
            r = np.where(np.array(fam) == "lateral", 0.0, r)
        freq[i] = s.imag / TWO_PI
        z = -s.real / np.abs(s)
        zeta[i] = np.where(np.abs(z) < 1e-12, 0.0, z)          # round-off of undamped modes
        ratio[i] = np.where(np.abs(r) < 1e-12, 0.0, r)
        whirl.append(tuple(wl))
        family.append(tuple(fam))
        if keep_vectors:
            vecs_keep[i] = Phi @ Q
        prev_q, prev_f = Q, freq[i]
    branch = _branch_whirl(rpm, whirl, nb)
    crit = critical_speeds(rpm, freq, orders, whirl)
    notes = _sweep_notes(rpm, n_rigid, mac_min)
    return CampbellResult(
        rpm=rpm, freq_hz=freq, zeta=zeta, whirl=tuple(whirl), family=tuple(family),
        whirl_ratio=ratio, mac_min=mac_min, branch_whirl=tuple(branch),
        orders=tuple(float(k) for k in orders), criticals=tuple(crit), basis_size=red.m,
        basis_change=change, n_rigid=n_rigid, n_dof=n_dof, notes=tuple(notes),
        vectors=vecs_keep)


def _checked_speeds(rpms, n_modes: int, n_dof: int) -> np.ndarray:
    """The speeds of ``sweep`` as an array [rpm], after its input checks (speeds finite, >= 0
    and strictly increasing; 1 <= ``n_modes`` <= ``n_dof`` // 2)."""
    rpm = np.asarray(rpms, dtype=float)
    if rpm.ndim != 1 or rpm.size == 0 or not np.all(np.isfinite(rpm)) or np.any(rpm < 0):
        raise InputError("campbell", "speeds", "one or more finite speeds >= 0 rpm",
                         got=list(rpms))
    if np.any(np.diff(rpm) <= 0):
        raise InputError("campbell", "speeds", "strictly increasing", got=list(rpms))
    if not (isinstance(n_modes, int) and n_modes >= 1):
        raise InputError("campbell", "modes", "integer >= 1", got=n_modes)
    if n_modes > n_dof // 2:
        raise InputError("campbell", "modes", f"<= {n_dof // 2} for this model", got=n_modes)
    return rpm


def _branch_whirl(rpm: np.ndarray, whirl: list, nb: int) -> list:
    """Each branch's label: the most frequent over the speeds Ω > 0 (the one at rest if the
    sweep has no other speed)."""
    branch = []
    for j in range(nb):
        labs = [whirl[i][j] for i in range(rpm.size) if rpm[i] > 0] or [whirl[0][j]]
        branch.append(max(dict.fromkeys(labs), key=labs.count))
    return branch


def _sweep_notes(rpm: np.ndarray, n_rigid: int, mac_min: np.ndarray) -> list[str]:
    """Notes of a sweep: rigid-body modes dropped, speeds with uncertain tracking."""
    notes = []
    if n_rigid:
        notes.append(f"{n_rigid} rigid-body mode(s) (0 Hz) dropped")
    weak = np.flatnonzero(mac_min < 0.8)
    if weak.size:
        notes.append("mode tracking uncertain (MAC < 0.8) into "
                     + ", ".join(f"{rpm[i]:g}" for i in weak) + " rpm: refine the speed step")
    return notes


def critical_speeds(rpm, freq_hz, orders, whirl=None) -> list[CriticalSpeed]:
    """Crossings of each branch with the k·n/60 lines inside the sweep."""
    rpm = np.asarray(rpm, float)
    out = []
    for k in orders:
        g = freq_hz - k * rpm[:, None] / 60.0          # Hz
        for j in range(freq_hz.shape[1]):
            gj = g[:, j]
            for i in range(rpm.size):
                hit = None
                if gj[i] == 0.0 and freq_hz[i, j] > 0:
                    hit = (rpm[i], i)
                elif i + 1 < rpm.size and gj[i] * gj[i + 1] < 0:
                    t = gj[i] / (gj[i] - gj[i + 1])
                    # label from the nearer speed, never from rest (no whirl sense at Ω = 0)
                    hit = (rpm[i] + t * (rpm[i + 1] - rpm[i]),
                           i + 1 if (t > 0.5 or rpm[i] == 0) else i)
                if hit is not None:
                    n_c, ii = hit
                    out.append(CriticalSpeed(float(k), j, float(n_c), float(k * n_c / 60.0),
                                             whirl[ii][j] if whirl is not None else ""))
    out.sort(key=lambda c: c.rpm)
    return out
