"""Pure NumPy fatigue kernels, vectorised over nodes × cycle classes.

Stress components use the order ``VOIGT`` = (xx, yy, zz, xy, yz, xz) in MPa, shape (..., 6).

Equivalent stress (kinds in ``EQUIVALENT_STRESSES``):

* ``von_mises`` (default, as the seed): σ_vM ≥ 0.
* ``signed_von_mises``: σ_vM with the sign of the principal stress of largest magnitude (the
  Ansys Fatigue Tool's "Signed von Mises"); a tie (|σ1| = |σ3|) counts as positive.
* ``signed_von_mises_hydrostatic``: σ_vM with the sign of the hydrostatic stress
  (σxx + σyy + σzz)/3; zero counts as positive.

Proportional loading with a load factor λ(t) ≥ 0 scales every component, so σ_eq(t) =
σ_eq,ref · λ(t) for all three kinds, and a load-factor cycle (range Δλ, mean λ_m) is, at a node,
the stress cycle with amplitude |σ_eq,ref| Δλ / 2 and mean σ_eq,ref λ_m.

Mean-stress theories (``MEAN_STRESS_THEORIES``) give the zero-mean amplitude σ_ar that has the
same life as (σ_a, σ_m) for σ_m ≥ 0:

    soderberg (default, seed 000 §8.3):  σ_ar = σ_a / (1 − σ_m / R_e)      (yield strength)
    goodman:                             σ_ar = σ_a / (1 − σ_m / R_m)      (ultimate strength)
    gerber:                              σ_ar = σ_a / (1 − (σ_m / R_m)²)
    none:                                σ_ar = σ_a

A tensile mean at or beyond the strength (σ_m ≥ R_e or R_m) gives σ_ar = ∞ (static failure,
N = 0). A compressive mean (σ_m < 0, only with a signed equivalent stress) takes no credit:
σ_ar = σ_a for every theory (conservative; the lines are not extended into compression).

The fatigue strength factor ``kf`` (0 < kf ≤ 1; surface finish, size, reliability: the product
of Marin-type factors) multiplies the S-N curve's alternating strengths, as the Ansys Fatigue
Tool's "Fatigue Strength Factor (Kf)" does; equivalently σ_ar / kf is looked up on the curve.

Miner's rule: D = Σ_k n_k / N(σ_ar,k / kf) per block.

Safety factor at a design life L (blocks): the n > 0 with L · D(n · σ) = 1, i.e. the factor by
which the stress (load) could be multiplied so that the design life is exactly consumed (n < 1:
the design life is not reached; the seed's 0.7 at 10⁷ blocks). D(n · σ) increases monotonically
with n, so the root is bracketed and bisected in log n. Two methods, same root:

* ``"similarity"`` (default): every node sees the same cycles scaled by its own σ_eq, and n only
  enters as the product n · σ_eq, so D_node(n) = D_unit(n · |σ_eq|) with one function D_unit per
  sign of σ_eq (a compressive mean is treated differently). The scalar root x* of
  L · D_unit(x) = 1 is bracketed and bisected to machine precision once, and n = x* / |σ_eq|
  for every node — exact, and O(cycles) instead of O(nodes × cycles × iterations).
* ``"bisection"``: a bracketed bisection in log n on all nodes at once (per node, vectorised),
  to the relative tolerance ``rtol``; kept as the general method and as the check of the first.

If L · D(n_max · σ) ≤ 1 (in particular an infinite life, D = 0) the factor is capped at
n_max = ``SAFETY_FACTOR_MAX`` = 15, the cap the Ansys Fatigue Tool uses, and flagged ``CAPPED``.
With the "cutoff" S-N curve D jumps from 0 where the largest cycle reaches the endurance limit;
the bisection then returns that jump. (With the Structural Steel table, whose last point is
1e6 < 10⁷ cycles, n at 10⁷ blocks is therefore set by the largest cycle of the block alone.)
"""

from __future__ import annotations

import math

import numpy as np

from shaftfe.errors import InputError
from shaftfe.fatigue.counting import CycleMatrix, Cycles, _matrix
from shaftfe.fatigue.sn import FatigueMaterial

VOIGT = ("xx", "yy", "zz", "xy", "yz", "xz")
EQUIVALENT_STRESSES = ("von_mises", "signed_von_mises", "signed_von_mises_hydrostatic")
MEAN_STRESS_THEORIES = ("soderberg", "goodman", "gerber", "none")
SAFETY_FACTOR_MAX = 15.0
SOLVED, CAPPED, FLOORED = 0, 1, 2          # safety-factor status codes
_FLOOR_RATIO = 1e-6                        # lower bracket = n_max · 1e-6
_CHUNK_ELEMENTS = 1 << 20                  # nodes × cycle classes evaluated per chunk


# --- equivalent stress -------------------------------------------------------------------

def _components(sigma) -> np.ndarray:
    s = np.asarray(sigma, dtype=float)
    if s.shape[-1:] != (6,):
        raise InputError("stress field", "sigma", "shape (..., 6): xx, yy, zz, xy, yz, xz",
                         got=s.shape)
    return s


def von_mises(sigma) -> np.ndarray:
    s = _components(sigma)
    xx, yy, zz, xy, yz, xz = (s[..., i] for i in range(6))
    return np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2)
                   + 3.0 * (xy ** 2 + yz ** 2 + xz ** 2))


def principal_stresses(sigma) -> np.ndarray:
    """Principal stresses, ascending, shape (..., 3)."""
    s = _components(sigma)
    t = np.empty((*s.shape[:-1], 3, 3))
    t[..., 0, 0], t[..., 1, 1], t[..., 2, 2] = s[..., 0], s[..., 1], s[..., 2]
    t[..., 0, 1] = t[..., 1, 0] = s[..., 3]
    t[..., 1, 2] = t[..., 2, 1] = s[..., 4]
    t[..., 0, 2] = t[..., 2, 0] = s[..., 5]
    return np.linalg.eigvalsh(t)


def signed_von_mises(sigma, sign_from: str = "principal") -> np.ndarray:
    """σ_vM signed by the largest-magnitude principal stress or by the hydrostatic stress."""
    s = _components(sigma)
    vm = von_mises(s)
    if sign_from == "principal":
        p = principal_stresses(s)
        ref = np.where(np.abs(p[..., 0]) > np.abs(p[..., 2]), p[..., 0], p[..., 2])
    elif sign_from == "hydrostatic":
        ref = s[..., 0] + s[..., 1] + s[..., 2]
    else:
        raise InputError("fatigue options", "sign_from", "principal | hydrostatic",
                         got=sign_from)
    return np.where(ref < 0, -vm, vm)


def equivalent_stress(sigma, kind: str = "von_mises") -> np.ndarray:
    """σ_eq per node from (..., 6) components (see the module docstring for the kinds)."""
    if kind == "von_mises":
        return von_mises(sigma)
    if kind == "signed_von_mises":
        return signed_von_mises(sigma, "principal")
    if kind == "signed_von_mises_hydrostatic":
        return signed_von_mises(sigma, "hydrostatic")
    raise InputError("fatigue options", "equivalent stress", " | ".join(EQUIVALENT_STRESSES),
                     got=kind)


# --- mean stress, S-N, Miner ----------------------------------------------------------------

def _check_theory(theory: str) -> None:
    if theory not in MEAN_STRESS_THEORIES:
        raise InputError("fatigue options", "mean-stress theory",
                         " | ".join(MEAN_STRESS_THEORIES), got=theory)


def _check_kf(kf: float) -> None:
    if not (math.isfinite(kf) and 0 < kf <= 1):
        raise InputError("fatigue options", "kf (fatigue strength factor)", "in (0, 1]", got=kf)


def mean_stress_correction(amplitude, mean, theory: str = "soderberg", *,
                           yield_MPa: float, ultimate_MPa: float) -> np.ndarray:
    """Zero-mean equivalent amplitude σ_ar (MPa) for amplitude σ_a ≥ 0 and mean σ_m."""
    _check_theory(theory)
    sa = np.asarray(amplitude, dtype=float)
    sm = np.asarray(mean, dtype=float)
    if theory == "none":
        return np.broadcast_to(sa, np.broadcast_shapes(sa.shape, sm.shape)).copy()
    pos = np.maximum(sm, 0.0)              # compressive means take no credit
    if theory == "soderberg":
        denom = 1.0 - pos / yield_MPa
    elif theory == "goodman":
        denom = 1.0 - pos / ultimate_MPa
    else:
        denom = 1.0 - np.square(pos / ultimate_MPa)
    sa, denom = np.broadcast_arrays(sa, denom)
    ok = denom > 0
    out = np.where(sa > 0, np.inf, 0.0)      # mean at/above the strength: static failure
    np.divide(sa, denom, out=out, where=ok)
    return out


def miner_damage(sa_eq, count, material: FatigueMaterial, kf: float = 1.0) -> np.ndarray:
    """Σ count / N(σ_ar / kf) over the last axis (Miner's rule)."""
    _check_kf(kf)
    sa = np.asarray(sa_eq, dtype=float)
    inv = np.power(10.0, material.sn.log_inverse_life(sa / kf if kf != 1.0 else sa))
    return inv @ np.asarray(count, dtype=float)


def _damage(s: np.ndarray, cyc: Cycles, material: FatigueMaterial, theory: str,
            kf: float) -> np.ndarray:
    """Damage per block of nodes with equivalent reference stress s (1-D), chunked."""
    out = np.empty(s.shape[0])
    half = cyc.range / 2.0
    step = max(1, _CHUNK_ELEMENTS // max(cyc.n, 1))
    for a in range(0, s.shape[0], step):
        sc = s[a:a + step, None]
        sar = mean_stress_correction(np.abs(sc) * half, sc * cyc.mean, theory,
                                     yield_MPa=material.yield_MPa,
                                     ultimate_MPa=material.ultimate_MPa)
        out[a:a + step] = miner_damage(sar, cyc.count, material, kf)
    return out


def node_damage(sigma_eq, cycles: Cycles, material: FatigueMaterial,
                theory: str = "soderberg", kf: float = 1.0) -> np.ndarray:
    """Miner damage per block at every node; ``sigma_eq`` = σ_eq at the reference speed (MPa),
    any shape; returns the same shape. A history without cycles gives 0 (infinite life)."""
    _check_theory(theory)
    _check_kf(kf)
    s = np.asarray(sigma_eq, dtype=float)
    if cycles.n == 0:
        return np.zeros(s.shape)
    return _damage(s.ravel(), cycles, material, theory, kf).reshape(s.shape)


def cycle_damage(sigma_eq_node: float, cycles: Cycles, material: FatigueMaterial,
                 theory: str = "soderberg", kf: float = 1.0) -> np.ndarray:
    """Damage per block of each cycle class at ONE node (hot-spot breakdown)."""
    _check_theory(theory)
    _check_kf(kf)
    s = float(sigma_eq_node)
    sar = mean_stress_correction(abs(s) * cycles.range / 2.0, s * cycles.mean, theory,
                                 yield_MPa=material.yield_MPa,
                                 ultimate_MPa=material.ultimate_MPa)
    return cycles.count * 10.0 ** material.sn.log_inverse_life(sar / kf)


def damage_matrix(sigma_eq_node: float, cycles: Cycles, material: FatigueMaterial,
                  theory: str = "soderberg", kf: float = 1.0, bins=10) -> CycleMatrix:
    """Damage per block of one node in stress range × mean bins (MPa)."""
    d = cycle_damage(sigma_eq_node, cycles, material, theory, kf)
    s = float(sigma_eq_node)
    return _matrix(cycles.range * abs(s), cycles.mean * s, d, bins, "damage", "MPa")


# --- safety factor ----------------------------------------------------------------------------

def safety_factor(sigma_eq, cycles: Cycles, material: FatigueMaterial, design_life: float,
                  theory: str = "soderberg", kf: float = 1.0, *,
                  n_max: float = SAFETY_FACTOR_MAX, rtol: float = 1e-10,
                  method: str = "similarity") -> tuple[np.ndarray, np.ndarray]:
    """(n, status) per node: design_life · D(n · σ_eq) = 1, n ≤ n_max (see module docstring).

    status: SOLVED, CAPPED (n = n_max: life at n_max ≥ design life, incl. infinite life) or
    FLOORED (n < n_max · 1e-6: reported as that floor; a static failure in practice)."""
    _check_theory(theory)
    _check_kf(kf)
    if not (math.isfinite(design_life) and design_life > 0):
        raise InputError("fatigue options", "design life", "a finite number > 0 (blocks)",
                         got=design_life)
    if not (math.isfinite(n_max) and n_max > 0):
        raise InputError("fatigue options", "n_max", "a finite number > 0", got=n_max)
    if not (0 < rtol < 1e-2):
        raise InputError("fatigue options", "rtol", "in (0, 0.01)", got=rtol)
    if method not in ("similarity", "bisection"):
        raise InputError("fatigue options", "safety-factor method", "similarity | bisection",
                         got=method)
    s = np.asarray(sigma_eq, dtype=float)
    shape = s.shape
    s = s.ravel()
    n = np.full(s.shape, float(n_max))
    status = np.full(s.shape, CAPPED, dtype=np.int8)
    if cycles.n == 0 or s.size == 0:
        return n.reshape(shape), status.reshape(shape)
    floor = n_max * _FLOOR_RATIO
    if method == "similarity":
        for sign in (1.0, -1.0):
            sel = np.flatnonzero(s > 0) if sign > 0 else np.flatnonzero(s < 0)
            if sel.size == 0:
                continue
            x = _unit_root(sign, cycles, material, theory, kf, design_life)
            with np.errstate(divide="ignore", over="ignore"):
                nn = x / np.abs(s[sel])
            n[sel] = np.clip(nn, floor, n_max)
            status[sel] = np.where(nn >= n_max, CAPPED, np.where(nn < floor, FLOORED, SOLVED))
        return n.reshape(shape), status.reshape(shape)

    def fails(idx: np.ndarray, factor: np.ndarray) -> np.ndarray:
        return design_life * _damage(s[idx] * factor, cycles, material, theory, kf) > 1.0

    idx = np.flatnonzero(fails(np.arange(s.size), n))   # n* < n_max: solve; others capped
    lo = np.full(idx.size, floor)
    below = fails(idx, lo)                                # fails even at the floor
    n[idx[below]] = floor
    status[idx[below]] = FLOORED
    idx, lo = idx[~below], lo[~below]
    status[idx] = SOLVED
    hi = np.full(idx.size, float(n_max))
    iters = math.ceil(math.log2(math.log(n_max / floor) / math.log1p(rtol)))
    for _ in range(iters):
        mid = np.sqrt(lo * hi)
        f = fails(idx, mid)
        lo = np.where(f, lo, mid)
        hi = np.where(f, mid, hi)
    n[idx] = np.sqrt(lo * hi)
    return n.reshape(shape), status.reshape(shape)


def _unit_root(sign: float, cycles: Cycles, material: FatigueMaterial, theory: str,
               kf: float, design_life: float) -> float:
    """x > 0 with design_life · D(sign · x) = 1 for a node of unit σ_eq (∞: never fails,
    0: fails at any stress), bracketed and bisected in log x to machine precision."""

    def fails(x: float) -> bool:
        d = _damage(np.array([sign * x]), cycles, material, theory, kf)[0]
        return bool(design_life * d > 1.0)

    hi = 1.0
    while not fails(hi):
        hi *= 2.0
        if hi > 1e300:
            return math.inf
    lo = hi / 2.0 if hi > 1.0 else 1.0
    while fails(lo):
        lo /= 2.0
        if lo < 1e-300:
            return 0.0
    for _ in range(200):                  # lo never fails, hi always fails
        mid = math.sqrt(lo * hi)
        if not lo < mid < hi:
            break
        if fails(mid):
            hi = mid
        else:
            lo = mid
    return hi
