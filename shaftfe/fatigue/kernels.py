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

Spin softening (``beta``, per node, optional): in the co-rotating frame the parts' m ω² u makes
the response slightly nonlinear in λ. Per node the equivalent stress is then modelled as
S(λ) = σ_eq (λ + β λ²) (σ_eq = the linear part, β from a softened and an unsoftened solution at
λ = 1: ``shaftfe.fatigue.field.softening_beta``). S is monotone in λ ≥ 0 (β > −1/2), so the
rainflow cycles of S are those of λ, still counted once, and a cycle (Δλ, λ_m) is exactly the
stress cycle with amplitude |σ_eq| Δλ (1 + 2 β λ_m) / 2 and mean σ_eq (λ_m + β (λ_m² + Δλ²/4))
(``stress_cycles``). β = 0 (or None) is the proportional case above.

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
  With spin softening (β per node; n multiplies the stress history S(λ(t))) D_unit depends on
  β: x*(β) is solved on a grid of β (``BETA_GRID`` quantiles of the nodes' β, plus their
  extremes) and interpolated linearly in β for the field; x* falls monotonically with β (every
  class's amplitude and mean grow with β), so the grid neighbours bracket each node's root.
  A single node is solved on its own β (``shaftfe.fatigue.field.exact_safety`` does so for
  every reported hot spot): exact where the results are reported, interpolated in the VTU.
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
from shaftfe.util import units

VOIGT = ("xx", "yy", "zz", "xy", "yz", "xz")
EQUIVALENT_STRESSES = ("von_mises", "signed_von_mises", "signed_von_mises_hydrostatic")
MEAN_STRESS_THEORIES = ("soderberg", "goodman", "gerber", "none")
SAFETY_FACTOR_MAX = 15.0
SOLVED, CAPPED, FLOORED = 0, 1, 2          # safety-factor status codes
_FLOOR_RATIO = 1e-6                        # lower bracket = n_max · 1e-6
_CHUNK_ELEMENTS = 1 << 20                  # nodes × cycle classes evaluated per chunk
FIELD_BUDGET = 2.0e8      # node × class evaluations of a field before its rest is binned (≈ 5 s)
BIN_MAX = 400             # binned classes: at most BIN_MAX × BIN_MAX range × mean cells
BAND = 0.99               # binned field: nodes in bands of |σ_eq| from x down to BAND · x
BETA_GRID = 33            # softening: roots x*(β) at this many quantiles of the nodes' β
BETA_MIN = -0.4           # softening: S(λ) monotone for λ ≤ 1.25 needs β > −1/(2 · 1.25)


# --- equivalent stress -------------------------------------------------------------------

def _components(sigma) -> np.ndarray:
    s = np.asarray(sigma, dtype=float)
    if s.shape[-1:] != (6,):
        raise InputError("stress field", "sigma", "shape (..., 6): xx, yy, zz, xy, yz, xz",
                         got=s.shape)
    return s


def von_mises(sigma) -> np.ndarray:
    """von Mises of stresses (..., 6) (``shaftfe.util.units.von_mises``, components last)."""
    return units.von_mises(np.moveaxis(_components(sigma), -1, 0))


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


def check_beta(beta, shape) -> np.ndarray | None:
    """The softening coefficients per node (None: proportional loading), finite and > BETA_MIN
    (``S(λ)`` monotone over the speeds a history reaches)."""
    if beta is None:
        return None
    b = np.broadcast_to(np.asarray(beta, dtype=float), shape).ravel()
    if not np.all(np.isfinite(b)) or (b.size and float(b.min()) <= BETA_MIN):
        raise InputError("stress field", "softening beta", f"finite numbers > {BETA_MIN}",
                         got=float(b.min()) if b.size else None)
    return b


def stress_cycles(s, beta, cyc: Cycles) -> tuple[np.ndarray, np.ndarray]:
    """(amplitude, mean) MPa of every class at nodes of linear stress ``s`` (…, 1) and
    softening ``beta`` (same shape or None): |s| Δλ (1 + 2 β λ_m)/2, s (λ_m + β (λ_m² + Δλ²/4))
    (module docstring)."""
    half = cyc.range / 2.0
    if beta is None:
        return np.abs(s) * half, s * cyc.mean
    return (np.abs(s) * half * (1.0 + 2.0 * beta * cyc.mean),
            s * (cyc.mean + beta * (cyc.mean ** 2 + half ** 2)))


def node_stress_cycles(s: float, beta: float, cyc: Cycles) -> Cycles:
    """The cycles of ONE node in MPa (range = 2 × amplitude, mean), for its plots."""
    sa, sm = stress_cycles(float(s), float(beta) if beta else None, cyc)
    return Cycles(2.0 * sa, sm, cyc.count, cyc.closure)


def _damage(s: np.ndarray, cyc: Cycles, material: FatigueMaterial, theory: str,
            kf: float, beta: np.ndarray | None = None) -> np.ndarray:
    """Damage per block of nodes with equivalent reference stress s (1-D) and softening
    ``beta`` (1-D or None), chunked."""
    out = np.empty(s.shape[0])
    step = max(1, _CHUNK_ELEMENTS // max(cyc.n, 1))
    for a in range(0, s.shape[0], step):
        sa, sm = stress_cycles(s[a:a + step, None], None if beta is None
                               else beta[a:a + step, None], cyc)
        sar = mean_stress_correction(sa, sm, theory, yield_MPa=material.yield_MPa,
                                     ultimate_MPa=material.ultimate_MPa)
        out[a:a + step] = miner_damage(sar, cyc.count, material, kf)
    return out


def node_damage(sigma_eq, cycles: Cycles, material: FatigueMaterial,
                theory: str = "soderberg", kf: float = 1.0, *, exact_at=None,
                budget: float = FIELD_BUDGET, info: dict | None = None,
                beta=None) -> np.ndarray:
    """Miner damage per block at every node; ``sigma_eq`` = σ_eq at the reference speed (MPa),
    any shape; returns the same shape. A history without cycles gives 0 (infinite life).
    ``beta``: the nodes' spin-softening coefficients (module docstring), None: proportional.

    A long log has millions of cycle classes, and nodes × classes is then too much to evaluate
    as it stands. Two steps keep it in seconds:

    1. Exact pruning (cutoff S-N curves without "infinite life" damage): σ_ar of a class grows
       with |σ_eq|, so a class below the endurance limit at some node does no damage at any
       node of the same sign with a smaller |σ_eq| (and a β no larger: σ_ar grows with β too).
       The nodes are taken in order of decreasing |σ_eq|, the classes that do no damage at the
       chunk's largest stress and the largest β still to come are dropped (``active_cycles``),
       and once none is left the remaining nodes have no damage. Same result as every class at
       every node.
    2. Banded and binned classes, only when the work left would pass ``budget`` node-class
       evaluations (a history whose every cycle is large: white noise over the whole speed
       range): the nodes ``exact_at`` (the hot-spot candidates, flat indices) are still
       evaluated on every class, the rest of the field as ``_binned_rest`` says. ``info`` (a
       dict, if given) receives what was binned; tests/validation measure the error.
    """
    _check_theory(theory)
    _check_kf(kf)
    s = np.asarray(sigma_eq, dtype=float)
    b = check_beta(beta, s.shape)
    if cycles.n == 0:
        return np.zeros(s.shape)
    flat = s.ravel()
    exact = np.zeros(flat.size, dtype=bool)
    if exact_at is not None:
        exact[np.asarray(exact_at, dtype=np.int64)] = True
    out = np.zeros(flat.size)
    zero = np.flatnonzero(flat == 0)
    if zero.size and not _prunable(material):     # a finite "infinite life": damage even at 0
        out[zero] = _damage(flat[zero], cycles, material, theory, kf,
                            None if b is None else b[zero])
    work = float(zero.size * cycles.n)
    for sign in (1.0, -1.0):
        sel = np.flatnonzero(flat * sign > 0)
        sel = sel[np.argsort(-np.abs(flat[sel]), kind="stable")]
        # the largest β from each position on (pruning must hold for every node still to come)
        b_ahead = (np.maximum.accumulate(b[sel][::-1])[::-1] if b is not None
                   else np.zeros(sel.size))
        cyc, a, pruned_at = cycles, 0, math.inf
        while a < sel.size:
            x = abs(float(flat[sel[a]]))
            if x < 0.95 * pruned_at:        # prune again once |σ_eq| fell by 5 %
                cyc, pruned_at = active_cycles(cyc, sign * x, material, theory, kf,
                                               beta=float(b_ahead[a])), x
            if cyc.n == 0:
                break                       # no class does damage here nor at smaller |σ_eq|
            rest = sel[a:]
            if work + rest.size * cyc.n > budget:
                work += _binned_rest(flat, rest, exact, cyc, budget, material, theory, kf,
                                     out, info, b)
                break
            idx = sel[a:a + max(1, _CHUNK_ELEMENTS // cyc.n)]
            out[idx] = _damage(flat[idx], cyc, material, theory, kf,
                               None if b is None else b[idx])
            work += idx.size * cyc.n
            a += idx.size
    return out.reshape(s.shape)


def _binned_rest(flat, rest, exact, cyc, budget, material, theory, kf, out, info,
                 beta=None) -> float:
    """Step 2 of ``node_damage`` for the nodes ``rest`` (one sign, |σ_eq| descending): exact at
    the ``exact`` ones. The others go in bands of |σ_eq| (from x down to ``BAND`` · x); in a
    band, the classes doing no damage anywhere in it are dropped for good (they do none lower
    down either), the classes whose σ_ar crosses the S-N curve's last point inside the band
    (where the damage jumps) and the most damaging ones are summed exactly, and the rest, above
    that point across the whole band where the damage is a smooth power of σ_ar, on binned
    classes (``binned_cycles``). With softening (``beta``) a band's tests take its extreme β
    (σ_ar grows with β). Returns the node-class evaluations done."""
    def bsub(idx):
        return None if beta is None else beta[idx]
    ex, others = rest[exact[rest]], rest[~exact[rest]]
    work = 0.0
    if ex.size:
        out[ex] = _damage(flat[ex], cyc, material, theory, kf, bsub(ex))
        work += ex.size * cyc.n
    if others.size == 0:
        return work
    per_node = max(128, int(budget // others.size))
    n_classes = cyc.n
    x_abs = np.abs(flat[others])
    b_oth = beta[others] if beta is not None else np.zeros(others.size)
    b_ahead = np.maximum.accumulate(b_oth[::-1])[::-1]
    sign = 1.0 if flat[others[0]] > 0 else -1.0
    cutoff = material.sn.beyond_last == "cutoff"
    n_exact = n_binned = 0
    a = 0
    while a < others.size and cyc.n:
        b = max(a + 1, a + int(np.searchsorted(-x_abs[a:], -BAND * x_abs[a], "right")))
        band = others[a:b]
        above_hi = _above_last_point(cyc, sign * x_abs[a], material, theory, kf,
                                     beta=float(b_ahead[a]))
        if _prunable(material) and not above_hi.all():      # nothing below the band needs them
            cyc = Cycles(cyc.range[above_hi], cyc.mean[above_hi], cyc.count[above_hi],
                         cyc.closure)
            above_hi = above_hi[above_hi]
        if cyc.n == 0:
            break
        smooth = _above_last_point(cyc, sign * x_abs[b - 1], material, theory, kf,
                                   strict=True, beta=float(b_oth[a:b].min())) \
            if cutoff else np.ones(cyc.n, dtype=bool)
        smooth &= above_hi
        exact_idx = np.flatnonzero(~smooth)                 # crossing the last point (or none)
        cand = np.flatnonzero(smooth)
        k = min(per_node // 2, cand.size)
        if k:
            sa_, sm_ = stress_cycles(sign * x_abs[a], float(b_oth[a]), _subset(cyc, cand))
            sar = mean_stress_correction(sa_, sm_, theory, yield_MPa=material.yield_MPa,
                                         ultimate_MPa=material.ultimate_MPa)
            top = cand[np.argpartition(-sar, k - 1)[:k]]
            exact_idx = np.concatenate((exact_idx, top))
            smooth[top] = False
        sub = [_subset(cyc, exact_idx)]
        if smooth.any():
            sub.append(binned_cycles(_subset(cyc, np.flatnonzero(smooth)),
                                     max(16, per_node - sub[0].n)))
        out[band] = sum(_damage(flat[band], c, material, theory, kf, bsub(band))
                        for c in sub if c.n)
        n_exact = max(n_exact, sub[0].n)
        n_binned = max(n_binned, sub[1].n if len(sub) > 1 else 0)
        work += band.size * sum(c.n for c in sub)
        a = b
    if info is not None:
        info.update({"binned_nodes": int(info.get("binned_nodes", 0) + others.size),
                     "classes": int(n_classes), "exact_classes": int(n_exact),
                     "binned_classes": int(n_binned)})
    return work


def _subset(cyc: Cycles, idx: np.ndarray) -> Cycles:
    return Cycles(cyc.range[idx], cyc.mean[idx], cyc.count[idx], cyc.closure)


def binned_cycles(cycles: Cycles, max_classes: int) -> Cycles:
    """The classes on a uniform range × mean grid of at most ``max_classes`` cells (square,
    ≤ ``BIN_MAX`` per side), each cell's cycles replaced by one class at their count-weighted
    centroid with their total count: the damage of a cell's cycles is then met to second order
    in the cell size (first-order errors cancel about the centroid)."""
    n = int(min(BIN_MAX, max(2, math.isqrt(max_classes))))
    r, m, c = cycles.range, cycles.mean, cycles.count
    if cycles.n <= n * n:
        return cycles
    r_hi = float(r.max()) or 1.0
    m_lo, m_hi = float(m.min()), float(m.max())
    ir = np.minimum((r / r_hi * n).astype(np.int64), n - 1)
    im = (np.minimum(((m - m_lo) / (m_hi - m_lo) * n).astype(np.int64), n - 1)
          if m_hi > m_lo else np.zeros(r.size, dtype=np.int64))
    cell = ir * n + im
    w = np.bincount(cell, weights=c, minlength=n * n)
    keep = w > 0
    cr = np.bincount(cell, weights=c * r, minlength=n * n)[keep] / w[keep]
    cm = np.bincount(cell, weights=c * m, minlength=n * n)[keep] / w[keep]
    return Cycles(cr, cm, w[keep], cycles.closure)


def _prunable(material: FatigueMaterial) -> bool:
    sn = material.sn
    return sn.beyond_last == "cutoff" and not math.isfinite(sn.infinite_life_cycles)


def active_cycles(cycles: Cycles, sigma_eq: float, material: FatigueMaterial, theory: str,
                  kf: float, *, beta: float = 0.0) -> Cycles:
    """The classes that do damage at a node of equivalent stress ``sigma_eq`` (MPa, signed)
    and softening ``beta``: with a cutoff S-N curve without "infinite life" damage, those at
    or above the curve's last point (all classes for other curves)."""
    if not _prunable(material) or cycles.n == 0:
        return cycles
    keep = _above_last_point(cycles, sigma_eq, material, theory, kf, beta=beta)
    return cycles if keep.all() else _subset(cycles, np.flatnonzero(keep))


def _above_last_point(cycles: Cycles, sigma_eq: float, material: FatigueMaterial, theory: str,
                      kf: float, *, strict: bool = False, beta: float = 0.0) -> np.ndarray:
    """Per class: σ_ar at ``sigma_eq`` reaches the S-N curve's last point (strictly above it
    with ``strict``), by the very expression ``SNCurve.log_inverse_life`` and ``miner_damage``
    use, so that the classes kept are exactly those the full sum gives damage."""
    sa_, sm_ = stress_cycles(float(sigma_eq), float(beta) if beta else None, cycles)
    sar = mean_stress_correction(sa_, sm_, theory, yield_MPa=material.yield_MPa,
                                 ultimate_MPa=material.ultimate_MPa)
    sa = sar / kf if kf != 1.0 else sar
    with np.errstate(divide="ignore", invalid="ignore"):
        ls = np.log10(sa)
    t0 = material.sn.log_tables()[0][0]
    return ls > t0 if strict else ~(ls < t0)


def cycle_damage(sigma_eq_node: float, cycles: Cycles, material: FatigueMaterial,
                 theory: str = "soderberg", kf: float = 1.0, beta: float = 0.0) -> np.ndarray:
    """Damage per block of each cycle class at ONE node (hot-spot breakdown)."""
    _check_theory(theory)
    _check_kf(kf)
    s = float(sigma_eq_node)
    sa_, sm_ = stress_cycles(s, float(beta) if beta else None, cycles)
    sar = mean_stress_correction(sa_, sm_, theory, yield_MPa=material.yield_MPa,
                                 ultimate_MPa=material.ultimate_MPa)
    return cycles.count * 10.0 ** material.sn.log_inverse_life(sar / kf)


def damage_matrix(sigma_eq_node: float, cycles: Cycles, material: FatigueMaterial,
                  theory: str = "soderberg", kf: float = 1.0, bins=10,
                  beta: float = 0.0) -> CycleMatrix:
    """Damage per block of one node in stress range × mean bins (MPa)."""
    d = cycle_damage(sigma_eq_node, cycles, material, theory, kf, beta)
    sa, sm = stress_cycles(float(sigma_eq_node), float(beta) if beta else None, cycles)
    return _matrix(2.0 * sa, sm, d, bins, "damage", "MPa")


# --- safety factor ----------------------------------------------------------------------------

def safety_factor(sigma_eq, cycles: Cycles, material: FatigueMaterial, design_life: float,
                  theory: str = "soderberg", kf: float = 1.0, *,
                  n_max: float = SAFETY_FACTOR_MAX, rtol: float = 1e-10,
                  method: str = "similarity", beta=None) -> tuple[np.ndarray, np.ndarray]:
    """(n, status) per node: design_life · D(n · σ_eq) = 1, n ≤ n_max (see module docstring).
    ``beta``: spin softening per node (None: proportional; a varying β: roots interpolated
    between β grid roots, exact for a single node).

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
    b = check_beta(beta, shape)
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
            x = _beta_roots(sign, cycles, material, theory, kf, design_life,
                            None if b is None else b[sel])
            with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
                nn = x / np.abs(s[sel])
            n[sel] = np.clip(nn, floor, n_max)
            status[sel] = np.where(nn >= n_max, CAPPED, np.where(nn < floor, FLOORED, SOLVED))
        return n.reshape(shape), status.reshape(shape)

    def fails(idx: np.ndarray, factor: np.ndarray) -> np.ndarray:
        return design_life * _damage(s[idx] * factor, cycles, material, theory, kf,
                                     None if b is None else b[idx]) > 1.0

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


def _beta_roots(sign: float, cycles: Cycles, material: FatigueMaterial, theory: str,
                kf: float, design_life: float, beta) -> np.ndarray | float:
    """x*(β) of ``_unit_roots`` for nodes of one sign: one root without softening or with one
    β; else roots at ``BETA_GRID`` quantiles of β (and its extremes), bisected together, log
    x* interpolated linearly in β (module docstring)."""
    if beta is None or float(beta.min()) == float(beta.max()):
        b0 = 0.0 if beta is None else float(beta[0])
        return float(_unit_roots(sign, cycles, material, theory, kf, design_life,
                                 np.array([b0]))[0])
    grid = np.unique(np.quantile(beta, np.linspace(0.0, 1.0, BETA_GRID)))
    roots = _unit_roots(sign, cycles, material, theory, kf, design_life, grid)
    with np.errstate(divide="ignore"):
        lr = np.log(np.clip(roots, 1e-300, 1e300))
    return np.exp(np.interp(beta, grid, lr))


def _unit_roots(sign: float, cycles: Cycles, material: FatigueMaterial, theory: str,
                kf: float, design_life: float, beta: np.ndarray) -> np.ndarray:
    """Per softening coefficient of ``beta`` (1-D): the x > 0 with design_life · D(sign · x) = 1
    for a node of unit σ_eq and that β (∞: never fails, 0: fails at any stress), bracketed
    and bisected in log x to machine precision; every β's bracket moves in one vectorised
    pass. The classes without damage at the largest x still bracketed and the largest β
    still bisected are dropped as the brackets shrink (exact: σ_ar grows with x and β)."""
    b = np.asarray(beta, dtype=float)
    soft = bool(np.any(b))
    out = np.full(b.size, np.nan)            # NaN: not solved yet

    def fails(x: np.ndarray, idx: np.ndarray, active: Cycles) -> np.ndarray:
        d = _damage(sign * x, active, material, theory, kf, b[idx] if soft else None)
        return design_life * d > 1.0

    def pruned(active: Cycles, idx: np.ndarray) -> Cycles:
        return active_cycles(active, sign * float(hi[idx].max()), material, theory, kf,
                             beta=float(b[idx].max()))

    hi = np.ones(b.size)
    idx = np.arange(b.size)                  # not failing at hi yet: double hi
    while idx.size:
        idx = idx[~fails(hi[idx], idx, cycles)]
        hi[idx] *= 2.0
        never = hi[idx] > 1e300
        out[idx[never]] = math.inf
        idx = idx[~never]
    run = np.flatnonzero(np.isnan(out))
    if not run.size:
        return out
    active = pruned(cycles, run)             # every x tried from here on is <= its hi
    lo = np.where(hi > 1.0, hi / 2.0, 1.0)
    idx = run                                # still failing at lo: halve lo
    while idx.size:
        idx = idx[fails(lo[idx], idx, active)]
        lo[idx] /= 2.0
        zero = lo[idx] < 1e-300
        out[idx[zero]] = 0.0
        idx = idx[~zero]
    run = np.flatnonzero(np.isnan(out))
    for _ in range(200):                     # lo never fails, hi always fails
        mid = np.sqrt(lo[run] * hi[run])
        inside = (lo[run] < mid) & (mid < hi[run])
        run, mid = run[inside], mid[inside]
        if not run.size:
            break
        f = fails(mid, run, active)
        hi[run[f]] = mid[f]
        lo[run[~f]] = mid[~f]
        if f.any():
            active = pruned(active, run)
    left = np.isnan(out)
    out[left] = hi[left]
    return out
