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

import functools
import json
import math
from dataclasses import dataclass

import numpy as np

from shaftfe.model.grooves import din509
from shaftfe.util.paths import (
    KT_GROOVES_JSON,
    KT_RING_GROOVES_JSON,
    KT_SHOULDERS_JSON,
    KT_UNDERCUTS_JSON,
    repo_relative,
)

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


# U-notch (circumferential groove) in a circular shaft, nominal stresses on the notch diameter
# d = D − 2h: Roark 7th ed. Table 17.1 case 6a (tension), 6b (bending), 6c (torsion), the same
# C_i form in h/r with two branches (0.25 ≤ h/r ≤ 2, 2 < h/r ≤ 50) and the polynomial in 2h/D.
# (Transcribed from the printed equations as reproduced by eng-calculations.com's Table 17.1
# pages; one transcription, checked against this project's converged Kt of U grooves,
# reports/benchmarks/kt_grooves.json, in tests/validation/test_scf.py.)
_ROARK_U = {
    "tension": (np.array([[0.455, 3.354, -0.769], [3.129, -15.955, 7.404],
                          [-6.909, 29.286, -16.104], [4.325, -16.685, 9.469]]),
                np.array([[0.935, 1.922, 0.004], [0.537, -3.708, 0.040],
                          [-2.538, 3.438, -0.012], [2.066, -1.652, -0.031]])),
    "bending": (np.array([[0.455, 3.354, -0.769], [0.891, -12.721, 4.593],
                          [0.286, 15.481, -6.392], [-0.632, -6.115, 2.568]]),
                np.array([[0.935, 1.922, 0.004], [-0.552, -5.327, 0.086],
                          [0.754, 6.281, -0.121], [-0.138, -2.876, 0.031]])),
    "torsion": (np.array([[1.245, 0.264, 0.491], [-3.030, 3.269, -3.633],
                          [7.199, -11.286, 8.318], [-4.414, 7.753, -5.176]]),
                np.array([[1.651, 0.614, 0.040], [-4.794, -0.314, -0.217],
                          [8.457, -0.962, 0.389], [-4.314, 0.662, -0.212]])),
}
U_NOTCH_RANGE = (0.25, 2.0, 50.0)       # h/r: lower bound, branch switch, upper bound


def kt_u_notch(D: float, h: float, r: float, load: str = "bending") -> KtResult:
    """Kt of a U-notch (a circumferential groove of depth h and bottom radius r) in a shaft of
    diameter D, nominal stresses on d = D − 2h (Roark 7th ed. Table 17.1 cases 6a–6c). Outside
    0.25 ≤ h/r ≤ 50 the nearest branch is evaluated (``in_range`` False, a note says so);
    clamped to Kt ≥ 1."""
    if load not in LOADS:
        raise ValueError(f"unknown Kt load {load!r}; choose one of {LOADS}")
    if not (D > 0 and 0 < h < 0.5 * D and r > 0):
        raise ValueError("a U-notch's Kt needs D > 0, 0 < h < D/2 and r > 0")
    lo, mid, hi = U_NOTCH_RANGE
    hr = h / r
    tab = _ROARK_U[load][0 if hr <= mid else 1]
    C = tab[:, 0] + tab[:, 1] * math.sqrt(hr) + tab[:, 2] * hr
    t = 2.0 * h / D
    kt = max(float(C[0] + C[1] * t + C[2] * t * t + C[3] * t ** 3), 1.0)
    ok = lo <= hr <= hi
    note = "" if ok else f"h/r = {hr:.3g} outside [{lo}, {hi}]: extrapolated"
    return KtResult(kt=kt, in_range=ok, fit="roark U-notch", note=note)


def kt_cross_hole(d: float, dh: float, load: str = "bending") -> KtResult:
    """Kt of a transverse hole of diameter d_h through a shaft of diameter d, nominal stresses
    on the net section (``net_section_moduli``): DIN 743-2's fits of Peterson's charts
    (Pilkey & Pilkey, Peterson's SCF 3rd ed., Charts 4.66–4.68, as DIN 743-2:2012 prints
    them): tension 3 − d_h/d, bending 3 + 1.4 d_h/d − 2.8 √(d_h/d), torsion
    2.023 − 1.125 √(d_h/d) (of the largest shear stress). In range for d_h/d ≤ 0.4 (the
    loader's bound)."""
    if load not in LOADS:
        raise ValueError(f"unknown Kt load {load!r}; choose one of {LOADS}")
    q = dh / d
    kt = {"tension": 3.0 - q, "bending": 3.0 + 1.4 * q - 2.8 * math.sqrt(q),
          "torsion": 2.023 - 1.125 * math.sqrt(q)}[load]
    ok = 0.0 < q <= 0.4
    return KtResult(kt=kt, in_range=ok, fit="DIN 743-2 (Peterson) transverse hole",
                    note="" if ok else f"d_h/d = {q:.3g} outside (0, 0.4]")


def net_section_moduli(d: float, dh: float) -> tuple[float, float, float]:
    """(A, W_b, W_t) of a round section of diameter d through a transverse hole d_h
    (DIN 743-2): A = πd²/4 − d_h d, W_b = πd³/32 − d_h d²/6, W_t = πd³/16 − d_h d²/6."""
    return (math.pi * d * d / 4 - dh * d, math.pi * d ** 3 / 32 - dh * d * d / 6,
            math.pi * d ** 3 / 16 - dh * d * d / 6)


# the committed tables of converged Kt (``util.paths``), as the messages name them
KT_TABLE = repo_relative(KT_SHOULDERS_JSON)
KT_GROOVES = repo_relative(KT_GROOVES_JSON)
KT_UNDERCUTS = repo_relative(KT_UNDERCUTS_JSON)
KT_RING_GROOVES = repo_relative(KT_RING_GROOVES_JSON)


def converged_kt() -> dict:
    """(D, d, ρ) rounded to 1e-6 mm -> {load: α} from the committed tables of converged Kt:
    the shoulders' (``benchmarks/bench_axisymmetric.py``), keyed ("groove", D, d, ρ) the
    one-arc U grooves' (``benchmarks/bench_grooves.py``), keyed ("din471", D, d, ρ) the DIN 471
    ring grooves' (``benchmarks/bench_ring_grooves.py``; d the bottom diameter) and keyed
    (kind, D, d, r) the DIN 509 undercuts' (d the shaft's, the nominal stresses on the
    undercut's bottom diameter; ``benchmarks/bench_undercuts.py``). The files are read once
    per process; each call returns its own copy."""
    return {k: dict(v) for k, v in _tables()}


def undercut_kt(kind: str, D: float, d: float, r: float, table: dict | None = None):
    """{load: Kt} of the DIN 509 undercut ``kind`` of radius ``r`` in a Ø``d`` at a step to
    Ø``D`` (nominal stresses on its bottom diameter) from the converged table
    (``converged_kt``, or ``table``): the entry itself, else interpolated between the measured
    undercuts of the same DIN 509 row (the same r, t1, f, t2): in D/d at each measured d (the
    parabola through the three nearest D/d, points closer than 0.02 merged; linear between
    two), then linear in d between the two measured d that bracket it. None outside the
    measured points' range (no extrapolation). The interpolation's error, measured at points
    between the grid's: reports/benchmarks/undercuts.md §4 (Kt is concave in D/d: a linear
    interpolation read 0.7-1.8 % low there). Returns (values, "table" | "interpolated") or
    None."""
    table = converged_kt() if table is None else table
    exact = table.get((kind, round(D, 6), round(d, 6), round(r, 6)))
    if exact:
        return exact, "table"
    row = din509(d, r)
    if row is None:
        return None
    pts: dict = {}
    for k, v in table.items():
        if len(k) == 4 and k[0] == kind and abs(k[3] - r) <= 1e-9 and din509(k[2], r) == row:
            pts.setdefault(k[2], []).append((k[1] / k[2], v))
    q = D / d
    below = [x for x in pts if x <= d]
    above = [x for x in pts if x >= d]
    if not below or not above:
        return None
    d0, d1 = max(below), min(above)
    at = []
    for dd in dict.fromkeys((d0, d1)):
        qs = []
        for p in sorted(pts[dd], key=lambda p: p[0]):
            if not qs or p[0] - qs[-1][0] >= 0.02:
                qs.append(p)
        qq = np.array([p[0] for p in qs])
        if len(qs) < 2 or not qq[0] - 1e-9 <= q <= qq[-1] + 1e-9:
            return None
        near = np.sort(np.argsort(np.abs(qq - q), kind="stable")[:3])
        at.append({ld: _through(qq[near], np.array([qs[i][1][ld] for i in near]), q)
                   for ld in LOADS})
    if len(at) == 1:
        return at[0], "interpolated"
    w = (d - d0) / (d1 - d0)
    return {ld: (1 - w) * at[0][ld] + w * at[1][ld] for ld in LOADS}, "interpolated"


def _through(x: np.ndarray, y: np.ndarray, at: float) -> float:
    """The polynomial through the 2 or 3 points (x, y) at ``at`` (Lagrange)."""
    out = 0.0
    for i in range(x.size):
        w = 1.0
        for j in range(x.size):
            if j != i:
                w *= (at - x[j]) / (x[i] - x[j])
        out += w * y[i]
    return float(out)


@functools.cache
def _tables() -> tuple:
    out = []
    for path, rows in ((KT_SHOULDERS_JSON, "fillets"), (KT_GROOVES_JSON, "grooves"),
                       (KT_UNDERCUTS_JSON, "undercuts"), (KT_RING_GROOVES_JSON, "ring_grooves")):
        try:
            t = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            continue
        tag = {"fillets": lambda r: (), "grooves": lambda r: ("groove",),
               "undercuts": lambda r: (r["kind"],),
               "ring_grooves": lambda r: ("din471",)}[rows]
        out += [((*tag(r), round(r["D_mm"], 6), round(r["d_mm"], 6), round(r["rho_mm"], 6)),
                 tuple((ld, r[ld]["kt"]) for ld in ("tension", "bending", "torsion")))
                for r in t.get(rows, [])]
    return tuple(out)


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
