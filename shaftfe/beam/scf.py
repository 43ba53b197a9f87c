"""Elastic stress-concentration factors Kt for a stepped round shaft (shoulder fillet) in
bending, tension and torsion.

Nominal stresses on the SMALLER diameter d: σ = 32 M / (π d³) (bending), σ = 4 F / (π d²)
(tension), τ = 16 T / (π d³) (torsion). Geometry: larger diameter D, step height h = (D − d)/2,
fillet radius r. Every fit has the form Kt = C1 + C2 (2h/D) + C3 (2h/D)² + C4 (2h/D)³ with
C_i = a_i + b_i √(h/r) + c_i (h/r).

Tension and torsion (the same two sources as bending; the project's axisymmetric Kt tables,
reports/benchmarks/kt_reference.json, cover tension and torsion too, but only on a grid of D/d
and r/d and at the shipped fillets: they are the FE reference the fits are checked against in
tests/validation/test_scf.py, not a source of the fits):

* ``"roark"``: Roark 7th ed. Table 17.1 case 17a (axial load; 0.25 ≤ h/r ≤ 2 and 2 < h/r ≤ 20)
  and case 17c (torsion; 0.25 ≤ h/r ≤ 4, one branch);
* ``"peterson"``: Pilkey & Pilkey, Peterson's SCF 3rd ed., Chart 3.4 (tension; 0.1 ≤ h/r ≤ 2
  and 2 ≤ h/r ≤ 20) and Chart 3.12 (torsion, Kts = τ_max/τ_nom; 0.25 ≤ h/r ≤ 4), the
  polynomials printed with the charts.

(Transcribed from the printed equations as reproduced by several independent implementations,
which agree digit for digit; the page numbers were not checked here.)

Fits provided (all are curve fits to the same family of photoelastic data, chiefly Leven &
Hartman 1951 and Wilson & White 1973, as charted by Peterson):

``"roark"`` (default)
    Young & Budynas, *Roark's Formulas for Stress and Strain*, 7th ed. (McGraw-Hill 2002),
    Table 17.1, case 17b ("square shoulder with fillet in circular shaft", bending):
    Kt = C1 + C2 (2h/D) + C3 (2h/D)² + C4 (2h/D)³ with C_i = a_i + b_i √(h/r) + c_i (h/r),
    two coefficient sets for 0.25 ≤ h/r ≤ 2 and 2 < h/r ≤ 20. (The page number of the printed
    table was not checked here; the coefficients are as transcribed by several independent
    implementations. Some transcriptions print C4 = −0.790 + 0.417√(h/r) **+** 0.246 h/r
    for the first branch; that sign makes the two branches disagree by up to 0.3 at h/r = 2,
    whereas "−0.246" joins them to within 0.002, so "−" is used.)
``"peterson"``
    W. D. Pilkey & D. F. Pilkey, *Peterson's Stress Concentration Factors*, 3rd ed. (Wiley
    2008), Chart 3.10 (bending of a stepped bar of circular cross section with a shoulder
    fillet), the polynomial printed with the chart (also in Pilkey, *Formulas for Stress,
    Strain, and Structural Matrices*, 2nd ed.): same form, ranges 0.1 ≤ h/r ≤ 2 and
    2 ≤ h/r ≤ 20. Its two branches differ by up to 1.4 % at h/r = 2.
Accuracy. Neither source states a fit error; the two fits of the same data differ by at most
2.5 % (measured over 1.02 ≤ D/d ≤ 3, 0.01 ≤ r/d ≤ 0.3 where both are in range; largest at
shallow steps with large fillets), and both reproduce the chart reading Kt ≈ 1.65 of Shigley 9th
ed. Example 6-6 (D/d = 1.19, r/d = 0.094) within 0.035. (Norton's power-law table of the same
chart was considered and dropped: the transcription available here was not monotonic in D/d
between 1.1 and 1.2, so it could not be trusted.) The charts
themselves are photoelastic and are reported to lie several percent, in places > 20 %, below
converged FE values for shoulder fillets (Tipton et al., Machine Design, Jan 2009; see
FINDINGS pitfall 5). Treat Kt from here as a sanity band, not a precise peak stress.

Outside the range (``KtResult.in_range`` is False and ``note`` says why):
* h/r above the upper bound (sharp fillet): the polynomial is extrapolated (Kt keeps growing
  roughly as √(h/r)); unreliable.
* h/r below the lower bound (fillet large compared with the step): the nearest branch is
  evaluated and the result is clamped to Kt ≥ 1 (the physical limit for a vanishing step).
* r = 0 with a step (sharp corner): Kt = inf (the elastic stress is singular).
* D ≤ d (no step): Kt = 1, in range.
Everything is vectorised over NumPy arrays; no import side effects.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# (a, b, c) for C1..C4, C_i = a + b √(h/r) + c (h/r); rows: C1, C2, C3, C4.
_ROARK_LOW = np.array([[0.927, 1.149, -0.086],
                       [0.015, -3.281, 0.837],
                       [0.847, 1.716, -0.506],
                       [-0.790, 0.417, -0.246]])
_ROARK_HIGH = np.array([[1.225, 0.831, -0.010],
                        [-3.790, 0.958, -0.257],
                        [7.374, -4.834, 0.862],
                        [-3.809, 3.046, -0.595]])
_PETERSON_LOW = np.array([[0.947, 1.206, -0.131],
                          [0.022, -3.405, 0.915],
                          [0.869, 1.777, -0.555],
                          [-0.810, 0.422, -0.260]])
_PETERSON_HIGH = np.array([[1.232, 0.832, -0.008],
                           [-3.813, 0.968, -0.260],
                           [7.423, -4.868, 0.869],
                           [-3.839, 3.070, -0.600]])
# tension: Roark case 17a, Peterson Chart 3.4
_ROARK_N_LOW = np.array([[0.927, 1.149, -0.086],
                         [0.011, -3.029, 0.948],
                         [-0.304, 3.979, -1.737],
                         [0.366, -2.098, 0.875]])
_ROARK_N_HIGH = np.array([[1.225, 0.831, -0.010],
                          [-1.831, -0.318, -0.049],
                          [2.236, -0.522, 0.176],
                          [-0.630, 0.009, -0.117]])
_PETERSON_N_LOW = np.array([[0.926, 1.157, -0.099],
                            [0.012, -3.036, 0.961],
                            [-0.302, 3.977, -1.744],
                            [0.365, -2.098, 0.878]])
_PETERSON_N_HIGH = np.array([[1.200, 0.860, -0.022],
                             [-1.805, -0.346, -0.038],
                             [2.198, -0.486, 0.165],
                             [-0.593, -0.028, -0.106]])
# torsion: Roark case 17c, Peterson Chart 3.12 (one branch each)
_ROARK_T = np.array([[0.953, 0.680, -0.053],
                     [-0.493, -1.820, 0.517],
                     [1.621, 0.908, -0.529],
                     [-1.081, 0.232, 0.065]])
_PETERSON_T = np.array([[0.905, 0.783, -0.075],
                        [-0.437, -1.969, 0.553],
                        [1.557, 1.073, -0.578],
                        [-1.061, 0.171, 0.086]])
LOADS = ("bending", "tension", "torsion")
# (lower bound, branch switch, upper bound) of h/r, per (fit, load)
_RANGES = {("roark", "bending"): (0.25, 2.0, 20.0), ("peterson", "bending"): (0.1, 2.0, 20.0),
           ("roark", "tension"): (0.25, 2.0, 20.0), ("peterson", "tension"): (0.1, 2.0, 20.0),
           ("roark", "torsion"): (0.25, 4.0, 4.0), ("peterson", "torsion"): (0.25, 4.0, 4.0)}
_TABLES = {("roark", "bending"): (_ROARK_LOW, _ROARK_HIGH),
           ("peterson", "bending"): (_PETERSON_LOW, _PETERSON_HIGH),
           ("roark", "tension"): (_ROARK_N_LOW, _ROARK_N_HIGH),
           ("peterson", "tension"): (_PETERSON_N_LOW, _PETERSON_N_HIGH),
           ("roark", "torsion"): (_ROARK_T, _ROARK_T),
           ("peterson", "torsion"): (_PETERSON_T, _PETERSON_T)}

FITS = ("roark", "peterson")


@dataclass(frozen=True)
class KtResult:
    kt: float
    in_range: bool
    fit: str
    note: str = ""


def kt_shoulder_bending(D, d, r, fit: str = "roark"):
    """Kt (array, same shape as the broadcast inputs) for bending of a stepped round shaft.

    D, d: larger and smaller diameter; r: fillet radius (same length unit). Returns
    ``(kt, in_range)`` as NumPy arrays; see the module docstring for the out-of-range policy.
    """
    return kt_shoulder_fit(D, d, r, fit, "bending")


def kt_shoulder_fit(D, d, r, fit: str = "roark", load: str = "bending"):
    """``kt_shoulder_bending`` for any ``load`` of ``LOADS`` (bending, tension, torsion)."""
    if fit not in FITS:
        raise ValueError(f"unknown Kt fit {fit!r}; choose one of {FITS}")
    if load not in LOADS:
        raise ValueError(f"unknown Kt load {load!r}; choose one of {LOADS}")
    D, d, r = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (D, d, r)))
    if np.any(d <= 0) or np.any(r < 0):
        raise ValueError("Kt fit needs d > 0 and r >= 0")
    kt = np.ones(D.shape)
    ok = np.ones(D.shape, dtype=bool)
    step = D > d
    sharp = step & (r == 0)
    kt[sharp] = np.inf
    ok[sharp] = False
    m = step & (r > 0)
    lo, mid, hi = _RANGES[fit, load]
    low_tab, high_tab = _TABLES[fit, load]
    h = 0.5 * (D[m] - d[m])
    hr = h / r[m]
    t = 2.0 * h / D[m]
    s = np.sqrt(hr)
    tab = np.where((hr <= mid)[:, None, None], low_tab[None], high_tab[None])
    C = tab[:, :, 0] + tab[:, :, 1] * s[:, None] + tab[:, :, 2] * hr[:, None]
    val = C[:, 0] + C[:, 1] * t + C[:, 2] * t**2 + C[:, 3] * t**3
    kt[m] = np.maximum(val, 1.0)
    ok[m] = (hr >= lo) & (hr <= hi)
    return kt, ok


def kt_shoulder(D: float, d: float, r: float, fit: str = "roark",
                load: str = "bending") -> KtResult:
    """Scalar convenience wrapper returning a :class:`KtResult` with an explanatory note."""
    kt, ok = kt_shoulder_fit(D, d, r, fit, load)
    kt, ok = float(kt), bool(ok)
    note = ""
    if D > d:
        if r == 0:
            note = "sharp corner (r = 0): elastic Kt is unbounded"
        elif not ok:
            lo, _, hi = _RANGES[fit, load]
            hr = 0.5 * (D - d) / r
            side = "extrapolated (sharp fillet)" if hr > hi else "clamped to >= 1 (large fillet)"
            note = f"h/r = {hr:.3g} outside [{lo}, {hi}]: {side}"
    return KtResult(kt=kt, in_range=ok, fit=fit, note=note)
