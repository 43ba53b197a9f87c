"""DIN 743 (2012) shaft strength with nominal stresses: the factors as pure functions, and the
assessment of every notch of the beam model (``shaftfe fatigue --method din743``).

Formulas: DIN 743-1/-2/-3:2012. The standard's text was not at hand; each formula below was
checked against two independent open implementations of it (their equation numbers quoted in
their comments) and reproduces a published exam solution (tests/validation/test_din743.py).

  K1(d_eff)   technological size factor (part 2): case-hardening steel 1 − 0.41 lg(d/16),
              0.6 beyond 150 mm; quenched & tempered σ_B: 1 − 0.26 lg(d/16) (0.67),
              σ_S: 1 − 0.34 lg(d/16) (0.57); 1 up to d_B = 16 mm. d_eff is the diameter that
              governs the heat treatment (DIN 743-2, technological size factor K1; the
              material values of DIN 743-3 hold at d_B): at a shoulder the larger diameter D,
              the section the notch's material was hardened in; at a keyway or a press fit the
              shaft's diameter there (``heat_treatment_diameter``)
  K2(d)       geometric size factor, bending and torsion: 1 − 0.2 lg(d/7.5)/lg 20 (0.8 ≥ 150),
              at the notch's diameter d (the nominal stress's section; DIN 743-2, geometric
              size factor K2): a different diameter from K1's at a shoulder
  K3(d)       size conversion of tabulated β (keyway, press fit): 1 − 0.2 lg β(d_BK)
              lg(d/7.5)/lg 20, at the notch's diameter d
  n           support number 1 + √(G'·mm) 10^−(0.33 + σ_S(d)/712 MPa); hard surface layer
              1 + √(G'·mm) 10^−0.7
  G'          shoulder: 2.3 (1 + φ)/r (tension, bending), 1.15/r (torsion); φ = 1/(4√(t/r) + 2)
              for d/D > 0.67, else 0
  α           shoulder, when no converged value is given: 1 + 1/√(A r/t + 2B r/d (1 + 2r/d)²
              + C (r/t)^z d/D) (A, B, C, z per load)
  groove      round (U) groove, DIN 743-2 tables 2, 3 ("Rundnut"): α of the shoulder's form with
              A, B = 0.22, 1.37 (tension), 0.2, 2.75 (bending), 0.7, 10.3 (torsion), C = 0;
              G' = 2 (1 + φ)/r (tension, bending), 1/r (torsion). Retaining-ring groove
              (DIN 743-2 §4.2.4): β measured at d_BK = 30 mm and R_z 20 (``beta_ring_groove``)
              with ρ* = 10^−(0.514 + 0.00152 σ_S) mm. These constants were read from the open
              implementation named below (its ρ* has a sign slip, "0.00152 − σ_S", corrected
              here to Neuber's form); checked against a hand calculation only
  cross hole  DIN 743-2: α 3 − d_h/d (tension), 3 + 1.4 d_h/d − 2.8 √(d_h/d) (bending),
              2.023 − 1.125 √(d_h/d) (torsion), on the net section (A = πd²/4 − d_h d,
              W = πd³/32 (16) − d_h d²/6); G' 2.3/r, 2.3/r + 2/d, 1.15/r + 2/d (r = d_h/2);
              read from the same open implementation
  β           α/n; keyway β_σ(40 mm) = 3.0 (σ_B(d)/1000)^0.38, β_τ = 0.56 β_σ + 0.1; press fit
              β_σ(40 mm) = 2.7 (σ_B(d)/1000)^0.43, β_τ = 0.65 β_σ (roughness included: K_F = 1)
  K_F         K_Fσ = 1 − 0.22 lg(R_z) (lg(σ_B(d)/20 MPa) − 1), K_Fτ = 0.575 K_Fσ + 0.425
  K_σ         (β/K2 + 1/K_F − 1)/K_V;  σ_WK = σ_W(d_B) K1(d_eff)/K_σ with σ_zdW = 0.4 σ_B,
              σ_bW = 0.5 σ_B, τ_tW = 0.3 σ_B
  ψ           σ_WK/(2 K1 σ_B(d_B) − σ_WK)
  σ_ADK       case 1 (σ_mv constant) or case 2 (σ_mv/σ_a constant), limited by yield
  σ_FK        K1 K2F γ_F σ_S(d_B); K2F 1.2 (bending, torsion; 1.0 in tension and with a hard
              surface layer); γ_F 1.05 / 1.1 / 1.15 for α in [1.5, 2) / [2, 3) / ≥ 3 (tension,
              bending; 1 for torsion and with a hard surface layer)
  S_D, S_F    1/√((σ_zda/σ_zdADK + σ_ba/σ_bADK)² + (τ_ta/τ_tADK)²), the same with maxima and
              the FK values; required S_min = 1.2
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from shaftfe.beam.scf import kt_cross_hole, net_section_moduli

S_MIN = 1.2
D_B = 16.0
D_BK = 40.0
_SHOULDER_ALPHA = {"tension": (0.62, 3.5, 0.0, 0.0), "bending": (0.62, 5.8, 0.2, 3.0),
                   "torsion": (3.4, 19.0, 1.0, 2.0)}
# a round (U) groove, DIN 743-2 table 2 "Rundnut": the same form as the shoulder's, C = 0
_GROOVE_ALPHA = {"tension": (0.22, 1.37, 0.0, 0.0), "bending": (0.2, 2.75, 0.0, 0.0),
                 "torsion": (0.7, 10.3, 0.0, 0.0)}
D_BK_RING = 30.0          # the reference diameter of the ring groove's measured β
RZ_RING = 20.0            # the roughness the ring groove's β was measured at (µm)


def k1(d_eff_mm: float, group: str, strength: str = "ultimate") -> float:
    """Technological size factor of σ_B ("ultimate") or σ_S ("yield")."""
    d = float(d_eff_mm)
    if d <= D_B:
        return 1.0
    if group == "case_hardening_steel":
        return 1.0 - 0.41 * math.log10(d / D_B) if d <= 150.0 else 0.6
    if group == "qt_steel":
        if strength == "ultimate":
            return 1.0 - 0.26 * math.log10(d / D_B) if d <= 300.0 else 0.67
        return 1.0 - 0.34 * math.log10(d / D_B) if d <= 300.0 else 0.57
    raise ValueError(f"DIN 743 size law for group {group!r} is not implemented "
                     "(case_hardening_steel | qt_steel)")


def k2(d_mm: float, load: str = "bending") -> float:
    if load == "tension" or d_mm < 7.5:
        return 1.0
    if d_mm >= 150.0:
        return 0.8
    return 1.0 - 0.2 * math.log10(d_mm / 7.5) / math.log10(20.0)


def k3(d_mm: float, beta_bk: float) -> float:
    if d_mm < 7.5:
        return 1.0
    if d_mm >= 150.0:
        return 1.0 - 0.2 * math.log10(beta_bk)
    return 1.0 - 0.2 * math.log10(beta_bk) * math.log10(d_mm / 7.5) / math.log10(20.0)


def phi(d_mm: float, D_mm: float, r_mm: float) -> float:
    t = 0.5 * (D_mm - d_mm)
    return 1.0 / (4.0 * math.sqrt(t / r_mm) + 2.0) if d_mm / D_mm > 0.67 else 0.0


def gradient_shoulder(d_mm: float, D_mm: float, r_mm: float, load: str) -> float:
    """Related stress gradient G' (1/mm) of a shoulder fillet."""
    if load == "torsion":
        return 1.15 / r_mm
    return 2.3 * (1.0 + phi(d_mm, D_mm, r_mm)) / r_mm


def _alpha(coef, d_mm: float, D_mm: float, r_mm: float) -> float:
    A, B, C, z = coef
    t = 0.5 * (D_mm - d_mm)
    q = A * r_mm / t + 2.0 * B * r_mm / d_mm * (1.0 + 2.0 * r_mm / d_mm) ** 2 \
        + C * (r_mm / t) ** z * d_mm / D_mm
    return 1.0 + 1.0 / math.sqrt(q)


def alpha_shoulder(d_mm: float, D_mm: float, r_mm: float, load: str) -> float:
    """DIN 743-2's own α of a shoulder fillet (used where no converged Kt is given)."""
    return _alpha(_SHOULDER_ALPHA[load], d_mm, D_mm, r_mm)


def alpha_groove(d_mm: float, D_mm: float, r_mm: float, load: str) -> float:
    """DIN 743-2's α of a round groove (table 2, "Rundnut"): d the groove's bottom diameter,
    D the shaft's, r the groove's radius; valid for r/t ≥ 0.03, d/D ≤ 0.98."""
    return _alpha(_GROOVE_ALPHA[load], d_mm, D_mm, r_mm)


def groove_in_range(notch) -> bool:
    """Is a groove inside the range DIN 743-2 gives its α for (r/t ≥ 0.03, d/D ≤ 0.98)?"""
    t = 0.5 * (notch.D_mm - notch.d_mm)
    return notch.r_mm / t >= 0.03 and notch.d_mm / notch.D_mm <= 0.98


def gradient_groove(d_mm: float, D_mm: float, r_mm: float, load: str) -> float:
    """Related stress gradient G' (1/mm) of a round groove (DIN 743-2 table 3): 2 (1 + φ)/r
    in tension and bending, 1/r in torsion."""
    if load == "torsion":
        return 1.0 / r_mm
    return 2.0 * (1.0 + phi(d_mm, D_mm, r_mm)) / r_mm


def alpha_cross_hole(d_mm: float, dh_mm: float, load: str) -> float:
    """DIN 743-2's α of a transverse hole of diameter d_h through a shaft of diameter d
    (nominal stresses on the net section, ``net_section_scale``): ``beam.scf.kt_cross_hole``
    (tension 3 − d_h/d, bending 3 + 1.4 d_h/d − 2.8 √(d_h/d), torsion 2.023 − 1.125 √(d_h/d),
    of the largest shear stress)."""
    return kt_cross_hole(d_mm, dh_mm, load).kt


def gradient_cross_hole(d_mm: float, dh_mm: float, load: str) -> float:
    """G' (1/mm) at a transverse hole of radius r = d_h/2 (DIN 743-2): 2.3/r in tension,
    2.3/r + 2/d in bending, 1.15/r + 2/d in torsion."""
    r = 0.5 * dh_mm
    return {"tension": 2.3 / r, "bending": 2.3 / r + 2.0 / d_mm,
            "torsion": 1.15 / r + 2.0 / d_mm}[load]


def net_section_scale(notch) -> tuple[float, float, float]:
    """(tension, bending, torsion) factors from the full round section's nominal stresses to
    the notch's own: 1 except at a transverse hole, whose section loses d_h d (area) and
    d_h d²/6 (both moduli; ``beam.scf.net_section_moduli``, DIN 743-2)."""
    if notch.kind != "cross_hole":
        return 1.0, 1.0, 1.0
    d = notch.d_mm
    full = (math.pi * d * d / 4, math.pi * d ** 3 / 32, math.pi * d ** 3 / 16)
    return tuple(f / n for f, n in zip(full, net_section_moduli(d, notch.hole_mm),
                                       strict=True))


def rho_star(sigma_s_d_MPa: float) -> float:
    """Neuber's substitute micro-support length ρ* (mm) of steel, 10^−(0.514 + 0.00152 σ_S)
    (DIN 743-2 §4.2.4, the ring groove's fictitious radius)."""
    return 10.0 ** -(0.514 + 0.00152 * sigma_s_d_MPa)


def beta_ring_groove(t_mm: float, r_mm: float, m_mm: float, sigma_s_d_MPa: float,
                     d_mm: float) -> dict[str, float]:
    """β per load of a retaining-ring (rectangular) groove at diameter d (DIN 743-2 §4.2.4),
    measured at d_BK = 30 mm: tension 0.9 (1.27 + 1.17 √(t/r_f)), bending
    0.9 (1.14 + 1.08 √(t/r_f)), both ≤ 4 with r_f = r + 2.9 ρ*; torsion 1.48 + 0.45 √(t/r_f)
    ≤ 2.5 with r_f = r + ρ*; each × 1.08 (m/t)^−0.2 for a narrow groove (m/t < 1.4), then
    converted to d by K3."""
    rs = rho_star(sigma_s_d_MPa)
    q_n, q_t = math.sqrt(t_mm / (r_mm + 2.9 * rs)), math.sqrt(t_mm / (r_mm + rs))
    raw = {"tension": (0.9 * (1.27 + 1.17 * q_n), 4.0), "bending": (0.9 * (1.14 + 1.08 * q_n), 4.0),
           "torsion": (1.48 + 0.45 * q_t, 2.5)}
    narrow = 1.08 * (m_mm / t_mm) ** -0.2 if m_mm / t_mm < 1.4 else 1.0
    out = {}
    for load, (b, cap) in raw.items():
        b = min(min(b, cap) * narrow, cap)
        out[load] = b * k3(D_BK_RING, b) / k3(d_mm, b)
    return out


def support_number(G_per_mm: float, sigma_s_d_MPa: float, hard_layer: bool) -> float:
    e = 0.7 if hard_layer else 0.33 + sigma_s_d_MPa / 712.0
    return 1.0 + math.sqrt(G_per_mm) * 10.0 ** -e


def beta_keyway(sigma_b_d_MPa: float, d_mm: float) -> tuple[float, float]:
    """(β_σ, β_τ) of a parallel-key seat at diameter d."""
    b40 = 3.0 * (sigma_b_d_MPa / 1000.0) ** 0.38
    bs = b40 * k3(D_BK, b40) / k3(d_mm, b40)
    t40 = 0.56 * b40 + 0.1
    bt = t40 * k3(D_BK, t40) / k3(d_mm, t40)
    return bs, bt


def beta_press_fit(sigma_b_d_MPa: float, d_mm: float) -> tuple[float, float]:
    b40 = 2.7 * (sigma_b_d_MPa / 1000.0) ** 0.43
    bs = b40 * k3(D_BK, b40) / k3(d_mm, b40)
    t40 = 0.65 * b40
    bt = t40 * k3(D_BK, t40) / k3(d_mm, t40)
    return bs, bt


def roughness(rz_um: float, sigma_b_d_MPa: float) -> tuple[float, float]:
    """(K_Fσ, K_Fτ)."""
    kf = 1.0 - 0.22 * math.log10(rz_um) * (math.log10(sigma_b_d_MPa / 20.0) - 1.0) \
        if rz_um > 1.0 else 1.0
    return kf, 0.575 * kf + 0.425


def gamma_f(alpha: float, load: str, hard_layer: bool) -> float:
    if load == "torsion" or hard_layer or alpha < 1.5:
        return 1.0
    return 1.05 if alpha < 2.0 else 1.1 if alpha < 3.0 else 1.15


def k2f(load: str, hard_layer: bool) -> float:
    return 1.0 if (load == "tension" or hard_layer) else 1.2


def amplitude_strength(s_wk: float, psi: float, s_fk: float, s_mv: float, s_a: float,
                       case: int) -> float:
    """σ_ADK (or τ_ADK with τ_mv) for case 1 (mean constant) or 2 (mean/amplitude constant)."""
    if case == 1:
        if s_mv <= (s_fk - s_wk) / (1.0 - psi):
            return s_wk - psi * s_mv
        return s_fk - s_mv
    ratio = s_mv / s_a if s_a > 0 else math.inf
    if ratio <= (s_fk - s_wk) / (s_wk - psi * s_fk):
        return s_wk / (1.0 + psi * ratio)
    return s_fk / (1.0 + ratio)


@dataclass(frozen=True)
class Notch:
    """A notch: kind shoulder | groove (a round U groove) | ring_groove (a retaining-ring
    groove) | cross_hole | keyway | press_fit, or plain (an unnotched section: α = β = 1);
    diameters (d at the notch, D the shaft's beside it), radius, a groove's width, a hole's
    diameter, and α per load where known (None → DIN 743's formula)."""
    name: str
    kind: str
    d_mm: float
    D_mm: float = 0.0
    r_mm: float = 0.0
    alpha: dict | None = None           # load -> α (tension, bending, torsion)
    alpha_source: str = ""
    rz_um: float = 1.0
    d_eff_mm: float = 0.0               # heat-treatment diameter for K1 (0: the default,
    #                                     ``heat_treatment_diameter``)
    width_mm: float = 0.0               # a ring groove's width m
    hole_mm: float = 0.0                # a transverse hole's diameter d_h


@dataclass(frozen=True)
class Stresses:
    """Nominal stresses, MPa: amplitudes, means and maxima per load."""
    zd_a: float = 0.0
    zd_m: float = 0.0
    b_a: float = 0.0
    b_m: float = 0.0
    t_a: float = 0.0
    t_m: float = 0.0

    def maxima(self) -> tuple[float, float, float]:
        return (abs(self.zd_m) + self.zd_a, abs(self.b_m) + self.b_a,
                abs(self.t_m) + self.t_a)


@dataclass(frozen=True)
class Result:
    notch: Notch
    factors: dict              # load -> {alpha, G, n, beta, K2, K_F, K_V, K, WK, psi, ADK, FK}
    K1_ultimate: float
    K1_yield: float
    sigma_B_d: float
    sigma_S_d: float
    sigma_mv: float
    S_D: float
    S_F: float


def heat_treatment_diameter(notch: Notch) -> float:
    """d_eff of K1 (see the module docstring): the notch's own ``d_eff_mm`` if set, else D at
    a shoulder and d elsewhere."""
    return notch.d_eff_mm or (notch.D_mm or notch.d_mm)


def assess(notch: Notch, st: Stresses, rm_n: float, rp_n: float, group: str, *,
           k_v: float = 1.0, hard_layer: bool = False, case: int = 2) -> Result:
    d_eff = heat_treatment_diameter(notch)
    K1B, K1S = k1(d_eff, group, "ultimate"), k1(d_eff, group, "yield")
    sB, sS = K1B * rm_n, K1S * rp_n
    W = {"tension": 0.4 * rm_n, "bending": 0.5 * rm_n, "torsion": 0.3 * rm_n}
    loads = {"tension": (st.zd_a, st.zd_m), "bending": (st.b_a, st.b_m),
             "torsion": (st.t_a, st.t_m)}
    s_mv = math.sqrt((st.zd_m + st.b_m) ** 2 + 3.0 * st.t_m ** 2)
    if notch.kind == "keyway":
        bs, bt = beta_keyway(sB, notch.d_mm)
    elif notch.kind == "press_fit":
        bs, bt = beta_press_fit(sB, notch.d_mm)
    elif notch.kind == "ring_groove":
        ring = beta_ring_groove(0.5 * (notch.D_mm - notch.d_mm), notch.r_mm, notch.width_mm,
                                sS, notch.d_mm)
    f = {}
    for load, (a, _m) in loads.items():
        shear = load == "torsion"
        kF = roughness(notch.rz_um, sB)[1 if shear else 0]
        if notch.kind == "plain":
            # an unnotched section: no stress concentration (α = β = 1, no support effect)
            al, G, n, beta = 1.0, 0.0, 1.0, 1.0
        elif notch.kind in ("shoulder", "groove", "cross_hole"):
            if notch.kind == "cross_hole":
                al = (notch.alpha or {}).get(load) or alpha_cross_hole(notch.d_mm,
                                                                       notch.hole_mm, load)
                G = gradient_cross_hole(notch.d_mm, notch.hole_mm, load)
            else:
                formula, grad = ((alpha_shoulder, gradient_shoulder)
                                 if notch.kind == "shoulder" else (alpha_groove, gradient_groove))
                al = (notch.alpha or {}).get(load) or formula(notch.d_mm, notch.D_mm,
                                                              notch.r_mm, load)
                G = grad(notch.d_mm, notch.D_mm, notch.r_mm, load)
            n = min(support_number(G, sS, hard_layer), al)
            beta = al / n
        elif notch.kind == "ring_groove":
            # β measured on grooves turned to R_z 20: K_F relative to that roughness
            al, G, n = math.nan, math.nan, math.nan
            # (capped at 1: a surface finer than the test pieces' is given no credit)
            kF = min(kF / roughness(RZ_RING, sB)[1 if shear else 0], 1.0)
            beta = ring[load]
        else:
            al, G, n, kF = math.nan, math.nan, math.nan, 1.0
            beta = bt if shear else bs
        K2 = k2(notch.d_mm, load)
        K = (beta / K2 + 1.0 / kF - 1.0) / k_v
        wk = W[load] * K1B / K
        psi = wk / (2.0 * K1B * rm_n - wk)
        # γ_F raises the yield limit of a circumferential notch only (DIN 743-1): not at a
        # transverse hole (nor a keyway or a press fit, whose α is not known)
        circ = al == al and notch.kind != "cross_hole"
        fk = K1S * k2f(load, hard_layer) * gamma_f(al if circ else 1.0, load, hard_layer) * rp_n
        if shear:
            fk /= math.sqrt(3.0)
        mv = s_mv / math.sqrt(3.0) if shear else s_mv
        adk = amplitude_strength(wk, psi, fk, mv, a, case)
        f[load] = {"alpha": al, "G": G, "n": n, "beta": beta, "K2": K2, "K_F": kF,
                   "K_V": k_v, "K": K, "WK": wk, "psi": psi, "ADK": adk, "FK": fk}
    def ratio(x: float, load: str, key: str) -> float:
        return x / f[load][key] if x else 0.0
    a_n = ratio(st.zd_a, "tension", "ADK") + ratio(st.b_a, "bending", "ADK")
    a_t = ratio(st.t_a, "torsion", "ADK")
    sd = 1.0 / math.hypot(a_n, a_t) if (a_n or a_t) else math.inf
    mz, mb, mt = st.maxima()
    f_n = ratio(mz, "tension", "FK") + ratio(mb, "bending", "FK")
    f_t = ratio(mt, "torsion", "FK")
    sf = 1.0 / math.hypot(f_n, f_t) if (f_n or f_t) else math.inf
    return Result(notch, f, K1B, K1S, sB, sS, s_mv, sd, sf)
