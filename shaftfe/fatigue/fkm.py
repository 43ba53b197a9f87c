"""FKM guideline, linear fatigue assessment with local (elastic) stresses: the factors and the
variable-amplitude damage as pure functions (no I/O; ``shaftfe.fatigue.strength`` applies them
to the FE field).

Source: FKM-Richtlinie "Rechnerischer Festigkeitsnachweis für Maschinenbauteile", 6th ed. (VDMA
2012), chapter 4 (local stresses). Where the guideline text was not at hand the formulas were
checked against published transcriptions: the PragTic help "Size effect" (FKM 2003 table of
K_d,m constants) and the FKM implementation and test data of pyLife (boschresearch/pylife,
``strength/fkm_linear``, "FKM guideline 2012" section numbers); tests/validation reproduces
their published examples. Every factor is returned so that the report prints it.

Material groups (``GROUPS``): the constants of the guideline's tables for the groups this
project needs, and grey cast iron GJL for the guideline's own worked example.

  f_W,σ   σ_W,zd = f_W,σ R_m                      (Table 4.2.1)
  f_W,τ   τ_W,s = f_W,τ σ_W,zd                    (Table 4.2.1)
  a_d, d_N technological size factor K_d,m        (Table 2.2.? / PragTic: FKM 2003)
  a_R, R_m,N,min  roughness factor K_R            (section 4.3.1.4)
  a_G, b_G  support factor n(G)                   (section 4.3.1.3.1)
  a_M, b_M  mean stress sensitivity M_σ           (section 4.4.2)
  K_f~    estimated fatigue notch factor of the design factor
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Group:
    name: str
    f_w_sigma: float
    f_w_tau: float
    a_d: float            # technological size factor constant
    d_eff_n_mm: float     # its reference diameter
    a_r: float            # roughness constant
    rm_n_min_MPa: float
    a_g: float            # support factor constants
    b_g_MPa: float
    a_m: float            # mean stress sensitivity M = a_M 1e-3 R_m + b_M
    b_m: float
    kf_estimate: float    # K_f~ of the design factor


GROUPS = {
    # case-hardening steel (16MnCr5): f_W 0.40; K_d,m: d_eff,N 11 mm, a_d 0.5 ("hardened steel")
    "case_hardening_steel": Group("case-hardening steel", 0.40, 0.577, 0.5, 11.0, 0.22, 400.0,
                                  0.5, 2700.0, 0.35, -0.1, 2.0),
    # quenched and tempered steel (C45 +QT): f_W 0.45, K_d,m: 16 mm, 0.3
    "qt_steel": Group("quenched and tempered steel", 0.45, 0.577, 0.3, 16.0, 0.22, 400.0,
                      0.5, 2700.0, 0.35, -0.1, 2.0),
    # structural steel (Ansys "Structural Steel" is taken as one): f_W 0.45; 40 mm, 0.15
    "structural_steel": Group("structural steel", 0.45, 0.577, 0.15, 40.0, 0.22, 400.0,
                              0.5, 2700.0, 0.35, -0.1, 2.0),
    # grey cast iron (the guideline's example 6.2): f_W 0.34, a_R 0.06, R_m,N,min 100,
    # a_G −0.05, b_G 3200, M = 0.5, K_f~ 1.0; no size law here (d_N → ∞)
    "gjl": Group("grey cast iron GJL", 0.34, 1.0, 0.0, math.inf, 0.06, 100.0,
                 -0.05, 3200.0, 0.0, 0.5, 1.0),
}

# Component S-N curve of steel, normal stress (section 4.4.3): knee and slope
N_KNEE = 1.0e6
K_SLOPE = 5.0
# Safety factor j_D against fatigue, steel, not welded (section 4.5): consequences of failure
# severe / moderate, with / without regular inspection
J_D = {("severe", False): 1.5, ("severe", True): 1.35,
       ("moderate", False): 1.3, ("moderate", True): 1.2}
MINER = ("elementary", "modified", "consistent")


def effective_diameter(y_mm: float, z_mm: float) -> float:
    """d_eff of the technological size factor K_d,m at a surface point of a shaft (local
    stresses): the guideline's table of effective diameters by cross-section form (FKM 2012,
    technological size factor; the 2003 table quoted by PragTic), solid round section:
    d_eff = d in both of its cases (case 1, d_eff = 4V/O, and case 2), with d the diameter of
    the round section through the assessed point, i.e. twice its distance from the axis. On a
    cylinder that is the segment's diameter; on a shoulder fillet the section through the hot
    spot (the collar's at 19° along the 0.6 mm arc: 17.06 mm, the small diameter plus the arc's
    rise). DIN 743 takes its K1 at the shoulder's larger diameter instead
    (``din743.heat_treatment_diameter``): the standards' rules differ, and both are reported."""
    return 2.0 * math.hypot(float(y_mm), float(z_mm))


def size_factor(d_eff_mm: float, g: Group) -> float:
    """Technological size factor K_d,m = (1 − 0.7686 a_d lg(d/7.5)) / (1 − 0.7686 a_d
    lg(d_N/7.5)) for d_eff > d_eff,N, else 1."""
    if not d_eff_mm > g.d_eff_n_mm:
        return 1.0
    c = 0.7686 * g.a_d
    return (1.0 - c * math.log10(d_eff_mm / 7.5)) / (1.0 - c * math.log10(g.d_eff_n_mm / 7.5))


def support_factor(G_per_mm: float, rm_MPa: float, g: Group) -> float:
    """n_σ(G) (Stieler form): G ≤ 0.1: 1 + G 10^−(a_G − 0.5 + R_m/b_G); 0.1 < G ≤ 1:
    1 + √G 10^−(a_G + R_m/b_G); 1 < G ≤ 100: 1 + G^¼ 10^−(a_G + R_m/b_G). G in 1/mm; a
    negative gradient (stress rising into the material) gives no support (n = 1)."""
    G = float(G_per_mm)
    if not G > 0:
        return 1.0
    e = g.a_g + rm_MPa / g.b_g_MPa
    if G <= 0.1:
        return 1.0 + G * 10.0 ** -(e - 0.5)
    if G <= 1.0:
        return 1.0 + math.sqrt(G) * 10.0 ** -e
    return 1.0 + min(G, 100.0) ** 0.25 * 10.0 ** -e


def roughness_factor(rz_um: float, rm_MPa: float, g: Group) -> float:
    """K_R,σ = 1 − a_R lg(R_z/µm) lg(2 R_m / R_m,N,min); 1 for R_z ≤ 1 µm."""
    if rz_um <= 1.0:
        return 1.0
    return 1.0 - g.a_r * math.log10(rz_um) * math.log10(2.0 * rm_MPa / g.rm_n_min_MPa)


def design_factor(n: float, k_r: float, g: Group, k_v: float = 1.0, k_s: float = 1.0,
                  k_nle: float = 1.0) -> float:
    """K_WK,σ = 1/n [1 + 1/K_f~ (1/K_R − 1)] 1/(K_V K_S K_NL,E)."""
    return (1.0 / n) * (1.0 + (1.0 / g.kf_estimate) * (1.0 / k_r - 1.0)) / (k_v * k_s * k_nle)


def mean_stress_sensitivity(rm_MPa: float, g: Group) -> float:
    """M_σ = a_M 1e-3 R_m/MPa + b_M."""
    return g.a_m * 1e-3 * rm_MPa + g.b_m


def mean_stress_factor(sa, sm, M: float) -> np.ndarray:
    """K_AK of the Haigh diagram for overload case F2 (constant stress ratio R), per cycle:
    I (R > 1, compression): 1/(1 − M); II (R ≤ 0): 1/(1 + M σm/σa); III (0 < R < 0.5):
    (1 + M/3)/(1 + M) / (1 + M/3 σm/σa); IV (R ≥ 0.5): (3 + M)/(3 (1 + M)²)."""
    sa = np.asarray(sa, dtype=float)
    sm = np.asarray(sm, dtype=float)
    r = np.divide(sm, sa, out=np.zeros(np.broadcast(sa, sm).shape), where=sa > 0)
    smax, smin = sm + sa, sm - sa
    out = np.where(smax <= 0, 1.0 / (1.0 - M), 0.0)                        # I (and R = 1)
    two = (smax > 0) & (smin <= 0)
    out = np.where(two, 1.0 / (1.0 + M * r), out)
    # R = smin/smax in (0, 0.5) ⇔ σm/σa in (1, 3)
    three = (smin > 0) & (r < 3.0)
    out = np.where(three, (1.0 + M / 3.0) / (1.0 + M) / (1.0 + M / 3.0 * r), out)
    four = (smin > 0) & (r >= 3.0)
    return np.where(four, (3.0 + M) / (3.0 * (1.0 + M) ** 2), out)


# --------------------------------------------------------------------------- variable amplitude

def class_damage(s, count, rule: str, k: float = K_SLOPE, n_knee: float = N_KNEE) -> np.ndarray:
    """Damage per block of each class of relative amplitude s and count n on the component S-N
    curve: n s^k / N_D at and above the knee; below it n s^(2k−1) / N_D (modified) or
    n s^k / N_D (elementary, and the consistent rule's rate once every class is on). Their sum
    is ``Spectrum.damage``."""
    s = np.asarray(s, dtype=float)
    c = np.asarray(count, dtype=float)
    if rule not in MINER:
        raise ValueError(f"rule {rule!r}: one of {MINER}")
    below = (2 * k - 1) if rule == "modified" else k
    return c * np.where(s >= 1.0, s ** k, s ** below) / n_knee


def blocks_to_failure(s, count, rule: str, damage_sum: float, k: float = K_SLOPE,
                      n_knee: float = N_KNEE) -> float:
    """Blocks until the damage reaches the effective damage sum D_M.

    Elementary and modified: D_M / (damage per block).
    Consistent (Haibach's "konsequente Miner-Regel"): the fatigue limit falls as damage
    accumulates, σ_D(D) = σ_D (1 − D/D_M)^(1/k), and a cycle damages only while it is above
    it, by (s^k)/N_D. A cycle of relative amplitude s < 1 becomes damaging once
    D/D_M ≥ 1 − s^k; the damage rate per block is piecewise constant between those
    thresholds, so the number of blocks is the exact sum Σ ΔD / rate over the intervals
    (``Spectrum.life``). Infinite if no cycle reaches the fatigue limit: the limit then never
    starts to fall."""
    if rule not in MINER:
        raise ValueError(f"rule {rule!r}: one of {MINER}")
    return Spectrum(s, count, k, n_knee).life(rule, damage_sum)


def scale_for_life(s, count, rule: str, damage_sum: float, blocks: float,
                   k: float = K_SLOPE, n_knee: float = N_KNEE) -> float:
    """The factor λ on every amplitude (the load; with a constant stress ratio the mean
    stress factors do not change) at which the life is exactly ``blocks``
    (``Spectrum.scale_for_life``)."""
    return Spectrum(s, count, k, n_knee).scale_for_life(rule, damage_sum, blocks)


class Spectrum:
    """One block of cycles as relative amplitudes s_i = σ_a,i / σ_AK,i with counts n_i,
    sorted by s descending once, with prefix sums, so that the life under every Miner rule at
    any load factor λ (amplitudes λ s_i) costs a binary search, not a pass over the classes:
    a long log has a million classes and the safety factor needs ~50 lives per check.

    With m(λ) = #{λ s_i ≥ 1} (the classes at or above the knee), A_j = Σ_{i≤j} n_i s_i^k
    (prefix) and B_j = Σ_{i≥j} n_i s_i^(2k−1) (suffix):
      elementary: D(λ) = λ^k A_{n−1} / N_D;
      modified:   D(λ) = (λ^k A_{m−1} + λ^(2k−1) B_m) / N_D;
      consistent: classes switch on in the order of s (class j at D/D_M = 1 − (λ s_j)^k), the
        rate once 0..j are on is λ^k A_j / N_D, so the sum Σ ΔD / rate over the intervals is
        blocks = D_M N_D [(λ^−k − s_m^k) / A_{m−1} + T_m], T_m = Σ_{j≥m} (s_j^k − s_{j+1}^k) / A_j
        (s_n = 0), infinite for m = 0.
    The same sums as the class-by-class evaluation, in another order (round-off only:
    tests/validation/test_fkm.py checks the two). ``factor`` scales every s (a check whose
    cycles are this one's times a constant: the core under its surface) without a new sort;
    ``hint``: an order that nearly sorts s (another node's), which the stable sort exploits."""

    def __init__(self, s, count, k: float = K_SLOPE, n_knee: float = N_KNEE, hint=None,
                 factor: float = 1.0):
        s = np.asarray(s, dtype=float).ravel()
        c = np.asarray(count, dtype=float).ravel()
        keep = (s > 0) & (c > 0)
        o = np.flatnonzero(keep) if hint is None else hint[keep[hint]]
        if o.size != np.count_nonzero(keep):        # the hint's node kept fewer classes
            o = np.flatnonzero(keep)
        o = o[np.argsort(-s[o], kind="stable")]
        self.order, self.k, self.n_knee = o, float(k), float(n_knee)
        self.s = s[o]
        self._neg = -self.s
        c = c[o]
        sk = self.s ** k
        self.A = np.cumsum(c * sk)
        self.B = np.append(np.cumsum((c * self.s ** (2 * k - 1))[::-1])[::-1], 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            d = (sk - np.append(sk[1:], 0.0)) / self.A
        self.T = np.append(np.cumsum(d[::-1])[::-1], 0.0)
        self.sk = np.append(sk, 0.0)
        self.factor = float(factor)
        if not (math.isfinite(self.factor) and self.factor >= 0):
            raise ValueError(f"factor {factor!r}: a finite number >= 0")

    def scaled(self, factor: float) -> Spectrum:
        """The same classes with every s × ``factor`` (shares the arrays)."""
        out = object.__new__(Spectrum)
        out.__dict__.update(self.__dict__)
        out.factor = self.factor * float(factor)
        return out

    @property
    def n(self) -> int:
        """Number of classes that do damage at some load (0: none, or every s scaled to 0)."""
        return int(self.s.size) if self.factor > 0 else 0

    def damage(self, rule: str, lam: float = 1.0) -> float:
        """Damage per block at load factor ``lam`` (elementary, modified)."""
        if self.n == 0:
            return 0.0
        if rule == "elementary":
            lam = lam * self.factor
            return float(lam ** self.k * self.A[-1] / self.n_knee)
        if rule == "modified":
            return self._damage_at(self._m(lam * self.factor))(lam)
        raise ValueError(f"rule {rule!r}: elementary | modified (consistent: life)")

    def _m(self, lam: float) -> int:
        """#{s_i ≥ 1/lam} (at or above the knee): a binary search, s being descending."""
        return int(np.searchsorted(self._neg, -1.0 / lam, side="right")) if lam > 0 else 0

    def life(self, rule: str, damage_sum: float, lam: float = 1.0) -> float:
        """Blocks until the damage reaches D_M at load factor ``lam`` (class docstring)."""
        if self.n == 0:
            return math.inf
        if rule == "elementary":
            d = self.damage(rule, lam)
            return damage_sum / d if d > 0 else math.inf
        return self._life_at(rule, damage_sum, self._m(lam * self.factor))(lam)

    def scale_for_life(self, rule: str, damage_sum: float, blocks: float) -> float:
        """The load factor λ at which the life is exactly ``blocks``: elementary
        λ = (life/blocks)^(1/k) in closed form, the other rules by bisection in log λ (their
        life falls monotonically with λ). The consistent rule's life is infinite until the
        largest cycle reaches the knee and finite from there: where that jump already passes
        the design life, λ* is the jump (the load at which damage starts at all; returned
        just below it, where the life is still infinite).

        The bisection runs between two neighbouring knees λ_i = 1 / (factor s_i), where m(λ)
        is constant: a binary search over the knees finds them (O(log n) lives, each a binary
        search itself), and the life between them is a closed expression of λ evaluated in
        plain floats (``_life_at``)."""
        if self.n == 0:
            return math.inf
        life1 = self.life(rule, damage_sum)
        if rule == "elementary":
            return (life1 / blocks) ** (1.0 / self.k)
        lo, hi = 1e-6, 1e6
        if self.life(rule, damage_sum, hi) - blocks > 0:
            return hi
        # the knees strictly inside (lo, hi): s_i in (1 / (hi f), 1 / (lo f)), s descending
        f = self.factor
        i0 = int(np.searchsorted(self._neg, -1.0 / (lo * f), side="right"))
        i1 = int(np.searchsorted(self._neg, -1.0 / (hi * f), side="left"))
        a, b = i0, i1                 # the first knee i in [i0, i1) whose life is ≤ blocks
        while a < b:
            mid = (a + b) // 2
            if self.life(rule, damage_sum, 1.0 / (f * float(self.s[mid]))) - blocks <= 0:
                b = mid
            else:
                a = mid + 1
        if a < i1:
            hi = 1.0 / (f * float(self.s[a]))
        if a > i0:
            lo = 1.0 / (f * float(self.s[a - 1]))
        life = self._life_at(rule, damage_sum, self._m(math.sqrt(lo * hi) * f))
        for _ in range(200):
            mid = math.sqrt(lo * hi)
            if life(mid) - blocks > 0:
                lo = mid
            else:
                hi = mid
            if hi / lo - 1.0 < 1e-13:
                break
        return math.sqrt(lo * hi)

    def _damage_at(self, m: int):
        """λ ↦ the modified rule's damage per block at λ, for m(λ) = ``m`` (class docstring),
        in plain floats: ``damage`` and, between two knees, ``scale_for_life``'s bisection."""
        k, f, nk = self.k, self.factor, self.n_knee
        a, b = (float(self.A[m - 1]) if m else 0.0), float(self.B[m])

        def damage(lam: float) -> float:
            lam = lam * f
            top = lam ** k * a if m else 0.0
            return (top + lam ** (2 * k - 1) * b) / nk
        return damage

    def _life_at(self, rule: str, damage_sum: float, m: int):
        """λ ↦ ``life`` (modified, consistent) at λ for m(λ) = ``m``: the one expression of
        the life, which ``life`` evaluates at its own m and ``scale_for_life`` bisects between
        two knees."""
        if rule == "modified":
            damage = self._damage_at(m)

            def life(lam: float) -> float:
                d = damage(lam)
                return damage_sum / d if d > 0 else math.inf
            return life
        if rule != "consistent":
            raise ValueError(f"rule {rule!r}: one of {MINER}")
        if m == 0:
            return lambda lam: math.inf  # nothing above the fatigue limit: no damage ever starts
        k, f, nk = self.k, self.factor, self.n_knee
        a, skm, t = float(self.A[m - 1]), float(self.sk[m]), float(self.T[m])
        return lambda lam: damage_sum * nk * (((lam * f) ** -k - skm) / a + t)
