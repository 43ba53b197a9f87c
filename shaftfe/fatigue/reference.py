"""A scalar, loop-based fatigue evaluation of ONE node: the independent reference that the
vectorised kernels (``shaftfe.fatigue.kernels``, ``field``) are checked against in the tests and
the benchmark. It calls none of those kernels: its own von Mises, log-log S-N look-up by bisect,
Soderberg correction, Miner sum and scalar bisection of the safety factor. Slow by design."""

from __future__ import annotations

import bisect
import math

import numpy as np

from shaftfe.util import units


def von_mises(s) -> float:
    return float(units.von_mises(np.asarray(s, dtype=float)))


def log_life(sa: float, material) -> float:
    """log10 N(S_a) by hand: log-log interpolation of the card, first segment extended upwards,
    no damage below the last point (cutoff)."""
    ls = [math.log10(v) for v in material.sn.alternating_MPa]     # descending
    ln = [math.log10(v) for v in material.sn.cycles]              # ascending
    x = math.log10(sa)
    if x < ls[-1]:
        return math.inf
    if x >= ls[0]:
        k = 0
    else:
        neg = [-v for v in ls]                                    # ascending
        k = bisect.bisect_right(neg, -x) - 1
        k = min(k, len(ls) - 2)
    t = (x - ls[k]) / (ls[k + 1] - ls[k])
    return ln[k] + t * (ln[k + 1] - ln[k])


def node_damage(sigma: float, cycles, material, beta: float = 0.0) -> float:
    """Miner damage per block of ONE node, a plain loop over the cycles: amplitude σ Δλ/2, mean
    σ λ_m, Soderberg σ_a / (1 − σ_m / R_e), 1 / N from ``log_life``. With spin softening
    (``beta``) the stress at load factor λ is σ (λ + β λ²), evaluated at the cycle's two
    extremes λ_m ± Δλ/2 (not by the kernels' closed form)."""
    d = 0.0
    for r, m, c in zip(cycles.range, cycles.mean, cycles.count, strict=True):
        hi, lo = m + r / 2.0, m - r / 2.0
        s_hi, s_lo = sigma * (hi + beta * hi * hi), sigma * (lo + beta * lo * lo)
        sa, sm = abs(s_hi - s_lo) / 2.0, (s_hi + s_lo) / 2.0
        denom = 1.0 - max(sm, 0.0) / material.yield_MPa
        if sa == 0.0:
            continue
        if denom <= 0.0:
            return math.inf
        ll = log_life(sa / denom, material)
        if math.isfinite(ll):
            d += c * 10.0 ** (-ll)
    return d


def node_safety(sigma: float, cycles, material, life: float, n_max: float = 15.0,
                beta: float = 0.0) -> float:
    """n with life · D(n σ) = 1 by a scalar bisection in log n until lo and hi are adjacent
    floats (D is monotone in n)."""
    if life * node_damage(n_max * sigma, cycles, material, beta) <= 1.0:
        return n_max
    lo, hi = n_max * 1e-6, n_max
    while True:
        mid = math.sqrt(lo * hi)
        if not lo < mid < hi:
            return hi
        if life * node_damage(mid * sigma, cycles, material, beta) > 1.0:
            hi = mid
        else:
            lo = mid
