"""Elastic stress-concentration factors Kt for a stepped round shaft (shoulder fillet) in bending.

Nominal stress: σ_nom = 32 M / (π d³) on the SMALLER diameter d. Geometry: larger diameter D,
step height h = (D − d)/2, fillet radius r.

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
# (lower bound, branch switch, upper bound) of h/r
_RANGES = {"roark": (0.25, 2.0, 20.0), "peterson": (0.1, 2.0, 20.0)}
_TABLES = {"roark": (_ROARK_LOW, _ROARK_HIGH), "peterson": (_PETERSON_LOW, _PETERSON_HIGH)}

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
    if fit not in FITS:
        raise ValueError(f"unknown Kt fit {fit!r}; choose one of {FITS}")
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
    lo, mid, hi = _RANGES[fit]
    low_tab, high_tab = _TABLES[fit]
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


def kt_shoulder(D: float, d: float, r: float, fit: str = "roark") -> KtResult:
    """Scalar convenience wrapper returning a :class:`KtResult` with an explanatory note."""
    kt, ok = kt_shoulder_bending(D, d, r, fit)
    kt, ok = float(kt), bool(ok)
    note = ""
    if D > d:
        if r == 0:
            note = "sharp corner (r = 0): elastic Kt is unbounded"
        elif not ok:
            lo, _, hi = _RANGES[fit]
            hr = 0.5 * (D - d) / r
            side = "extrapolated (sharp fillet)" if hr > hi else "clamped to >= 1 (large fillet)"
            note = f"h/r = {hr:.3g} outside [{lo}, {hi}]: {side}"
    return KtResult(kt=kt, in_range=ok, fit=fit, note=note)
