"""ISO 281 basic rating life of a bearing (the one implementation; the beam and the 3D static
model both report it)."""

from __future__ import annotations

import math


def l10h(C_N: float, P_N: float, rpm: float, p: float = 3.0) -> float:
    """Basic rating life in hours, (C/P)^p · 10⁶ / (60 n); infinite without load or speed.
    ``p``: 3 for ball, 10/3 for roller bearings (``Bearing.life_exponent``)."""
    if P_N <= 0 or rpm <= 0:
        return math.inf
    return (C_N / P_N) ** p * 1e6 / (60.0 * rpm)


# ISO 281:2007 modified rating life, radial ball bearings (eqs. for a_ISO by κ range):
# a_ISO = 0.1 [1 − (2.5671 − c / κ^e)^0.83 (e_C C_u / P)^(1/3)]^−9.3, capped at 50
_ISO_BALL = ((0.1, 0.4, 2.2649, 0.054381), (0.4, 1.0, 1.9987, 0.19087),
             (1.0, 4.0, 1.9987, 0.071739))
A_ISO_MAX = 50.0
# a1 for reliability % (ISO 281:2007 Table 12)
A1 = {90.0: 1.0, 95.0: 0.64, 96.0: 0.55, 97.0: 0.47, 98.0: 0.37, 99.0: 0.25}


def a_iso_ball(kappa: float, ec_cu_over_p: float) -> float:
    """Life modification factor of a radial ball bearing. κ above 4 is taken as 4; below 0.1
    the standard gives no value (ValueError)."""
    if not kappa >= 0.1:
        raise ValueError(f"kappa {kappa} < 0.1: outside ISO 281")
    k = min(float(kappa), 4.0)
    c, e = next((c, e) for lo, hi, c, e in _ISO_BALL if lo <= k < hi or (hi == 4.0 and k == 4.0))
    inner = (2.5671 - c / k ** e)
    if inner <= 0:
        return A_ISO_MAX
    base = 1.0 - inner ** 0.83 * max(float(ec_cu_over_p), 0.0) ** (1.0 / 3.0)
    if base <= 0:
        return A_ISO_MAX
    return min(0.1 * base ** -9.3, A_ISO_MAX)


def duty_cycle(rpm, load_N, weights=None, p: float = 3.0) -> tuple[float, float]:
    """Equivalent (load, speed) over operating conditions i (time fractions ``weights``,
    equal if None): n_m = Σ q_i n_i, P = (Σ q_i n_i P_i^p / Σ q_i n_i)^(1/p). A cycle without
    a revolution (the engine at rest throughout) has no equivalent load: (0, 0), whose
    ``l10h`` is infinite (no revolutions, no wear)."""
    import numpy as np
    n = np.asarray(rpm, dtype=float)
    P = np.asarray(load_N, dtype=float)
    q = np.full(n.shape, 1.0 / n.size) if weights is None else \
        np.asarray(weights, float) / np.sum(weights)
    nm = float(np.sum(q * n))
    if not nm > 0:
        return 0.0, 0.0
    return float((np.sum(q * n * P ** p) / nm) ** (1.0 / p)), nm


def modified_life_spectrum(C_N: float, Cu_N: float, rpm, load_N, kappa: float, e_c: float,
                           a1: float = 1.0, p: float = 3.0) -> float:
    """L_nm in hours over the conditions i (equal time each): Palmgren-Miner over the
    revolutions, 1/L = Σ U_i / L_nm,i with U_i the share of revolutions and
    L_nm,i = a1 a_ISO,i (C/P_i)^p 10⁶ revolutions; κ and e_C the same in every condition.
    No revolution at all (the engine at rest): infinite (no wear)."""
    import numpy as np
    n = np.asarray(rpm, dtype=float)
    P = np.asarray(load_N, dtype=float)
    if not n.sum() > 0:
        return math.inf
    u = n / n.sum()
    # a_ISO depends on the load alone here: once per distinct load (a logger's integer rpm
    # repeat: 5 million samples have < 10 000 speeds), the same numbers as per sample
    uP, inv = np.unique(P, return_inverse=True)
    ua = np.array([a_iso_ball(kappa, e_c * Cu_N / Pi) if Pi > 0 else A_ISO_MAX for Pi in uP])
    a = ua[inv.ravel()]
    with np.errstate(divide="ignore"):
        L_rev = np.where(P > 0, a1 * a * (C_N / np.where(P > 0, P, 1.0)) ** p * 1e6, np.inf)
    inv = float(np.sum(u / L_rev))
    if inv == 0:
        return math.inf
    return (1.0 / inv) / (60.0 * float(np.mean(n)))
