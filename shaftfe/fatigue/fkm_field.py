"""The FKM local-stress assessment on the static field (``shaftfe fatigue --method fkm``).

At each named surface region (fillets, keyways, bearing seats) the candidate hot spots are the
region's highest von Mises nodes outside the singular-point exclusion. At each:

1. **Stress profile along the inward normal** (a ``DepthProbe`` of the field). On the 3D field
   the normal is the mean of the adjacent boundary triangles' normals, turned inward by
   locating a point just inside, and the nodal stress field (P2, nodal averages of the
   recovered stress) is interpolated at depths 0…T (``fe.pointeval``); on the axisymmetric
   field the normal is the outline's and the harmonics' nodal stresses are interpolated in the
   meridian mesh and synthesised at the point's angle (``axisymmetric.pointeval``); the zoned
   field takes each point's own model. A least-squares quadratic over the first element depth
   gives the surface slope, and the related stress gradient G = −(dσ/dt)/σ at t = 0; a quadratic
   over ±½ element around the case depth gives the core's stress and gradient there.
2. **Two checks, as the guideline asks for surface-treated parts:** the surface layer (the
   core material's strength, the region's roughness R_z and the case-hardening factor K_V)
   and the core at the case depth (K_R = K_V = 1, its own gradient, the stress there).
3. **Variable amplitude.** The load-factor history is rainflow-counted once (the same count
   as the seed method); each cycle becomes the hot spot's stress cycle (with spin softening
   per node, ``kernels.stress_cycles``), is divided by its own component fatigue strength
   K_AK σ_WK (Haigh F2) and summed on the component S-N curve by the three Miner rules.
4. **Safety and utilisation.** The achieved safety factor is the load factor at which the life
   equals the design life; the degree of utilisation is j_D over it (≤ 1 passes).

Stress kind: von Mises signed by the largest principal stress: for steel (f_W,τ = 0.577) the
guideline's combination of the surface stress components' utilisations is the von Mises form,
and the sign decides the Haigh range of the mean stress.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from shaftfe.fatigue import fkm
from shaftfe.fatigue.cards import StrengthCard, Surfaces, region_rz
from shaftfe.fatigue.counting import count_cycles
from shaftfe.fatigue.field import softening_beta
from shaftfe.fatigue.kernels import signed_von_mises, stress_cycles, von_mises
from shaftfe.fe.pointeval import TetProbe
from shaftfe.solid.features import NOTCH_KINDS, is_notch, kind_of

# the regions FKM assesses: the notches and the bearing seats (ground, press-fitted)
ASSESSED_KINDS = NOTCH_KINDS | {"bearing_seat"}
N_CANDIDATES = 3          # per region and sign: the highest-stress nodes assessed
N_DEPTHS = 32             # profile samples over the whole depth
N_NEAR = 8                # and over the first element and the case-depth window: the fits'
                          # samples whatever the element size against the depth (a fine mesh's
                          # first element holds none of the 32 when h ≪ the case depth)


@dataclass(frozen=True)
class Profile:
    node: int
    xyz_mm: tuple[float, float, float]
    normal: tuple[float, float, float]          # inward unit normal
    h_mm: float                                  # local element size on the surface
    depths_mm: np.ndarray = field(repr=False)
    von_mises: np.ndarray = field(repr=False)    # MPa at the reference speed
    G_surface: float                             # 1/mm
    G_case: float
    case_ratio: float                            # σ(case depth) / σ(surface)
    fit_residual: float                          # rms of the surface fit / σ(surface)


@dataclass(frozen=True)
class Check:
    layer: str                   # surface | core
    depth_mm: float
    sigma_ref_MPa: float         # signed von Mises at the reference speed
    G_per_mm: float
    d_eff_mm: float
    K_d: float
    R_m_MPa: float
    sigma_W_zd_MPa: float
    Rz_um: float
    K_R: float
    n: float
    K_V: float
    K_WK: float
    sigma_WK_MPa: float
    M_sigma: float
    K_AK_largest: float          # of the largest cycle
    sigma_a_largest_MPa: float
    sigma_m_largest_MPa: float
    life_blocks: dict            # rule -> blocks
    safety: dict                 # rule -> achieved safety factor at the design life
    utilisation: dict            # rule -> j_D / safety


@dataclass(frozen=True)
class RegionResult:
    region: str
    node: int
    xyz_mm: tuple[float, float, float]
    notched: bool
    profile: Profile
    surface: Check
    core: Check | None
    s_lin_MPa: float = 0.0       # the node's S0 of S0 (λ + β λ²) (signed von Mises, no softening)
    beta: float = 0.0            # its spin-softening coefficient


@dataclass(frozen=True)
class FkmResult:
    card: StrengthCard
    rule: str                    # the governing Miner rule reported first
    j_D: float
    damage_sum: float
    design_life_blocks: float
    block_seconds: float
    regions: tuple[RegionResult, ...]
    notes: tuple[str, ...] = ()
    cycles: object = field(default=None, repr=False, compare=False)   # counting.Cycles
    # every node assessed (each region's candidates): (node, utilisation, safety) under the
    # governing rule, the worse layer of each (fatigue.vtu's fkm_utilisation, fkm_safety)
    assessed: tuple[tuple[int, float, float], ...] = ()

    @property
    def governing(self) -> tuple[RegionResult, Check]:
        worst = None
        for r in self.regions:
            for c in (r.surface, r.core):
                if c is not None and (worst is None or
                                      c.utilisation[self.rule] > worst[1].utilisation[self.rule]):
                    worst = (r, c)
        return worst


def k_v_case_hardening(d_mm: float, notched: bool) -> float:
    """Surface-treatment factor of case hardening, steel: the lower end of the guideline's
    ranges (FKM Table 4.3.7; DIN 743-2 uses the same lower values): d 8-25 mm notched 1.5,
    unnotched 1.2; 25-40 mm 1.2 / 1.1; beyond 40 mm no credit (1.0)."""
    if d_mm <= 25.0:
        return 1.5 if notched else 1.2
    if d_mm <= 40.0:
        return 1.2 if notched else 1.1
    return 1.0


class DepthProbe(Protocol):
    """Where a stress profile below a surface point of a reference comes from: one per field
    kind, behind this protocol (``fe.pointeval.TetProbe`` for a 3D field; ``axisymmetric.reference.
    SurfaceProbe`` and ``zoned.reference.ZonedProbe`` for the surface references)."""

    def normal(self, node: int) -> tuple[np.ndarray, float]:
        """(inward unit normal (3,), the local element size h in mm) at a surface point."""

    def stress_at(self, node: int, pts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """((k, 6) stress in MPa at the reference speed, found mask (k,)) at the points
        (3, k) below the surface point ``node``."""


def depth_probe(ref):
    """The reference's own profile source (``StaticReference.depth_probe``: the axisymmetric
    and zoned surface references carry one) or the 3D field's (``TetProbe``)."""
    return ref.depth_probe if getattr(ref, "depth_probe", None) is not None else TetProbe(ref)


def _quad_fit(t: np.ndarray, v: np.ndarray, at: float) -> tuple[float, float, float]:
    """(value, slope, rms residual) at ``at`` of a least-squares quadratic in (t − at)."""
    A = np.stack([np.ones_like(t), t - at, (t - at) ** 2], axis=1)
    c, *_ = np.linalg.lstsq(A, v, rcond=None)
    res = v - A @ c
    return float(c[0]), float(c[1]), float(np.sqrt(np.mean(res ** 2)))


def profile(ref, node: int, probe, case_depth_mm: float | None) -> Profile:
    """The von Mises profile along the inward normal at ``node`` of ``ref`` and its gradients;
    ``probe``: the field's ``DepthProbe`` (``depth_probe(ref)``, made once per reference). The
    profile, its surface value included, is the probe's one field, so that the relative
    gradient −σ'/σ is of one field: on the axisymmetric surface the reference's own stress is
    the surface recovery, which can differ from the interior field's surface value by ~1 %,
    a jump a fit over a 0.05 mm element would read as a gradient."""
    n, h = probe.normal(node)
    x = np.asarray(ref.xyz, dtype=float)[:, node]
    depth = max(2.0 * h, (case_depth_mm or 0.0) + h)
    grids = [np.linspace(0.0, h, N_NEAR + 1), np.linspace(0.0, depth, N_DEPTHS + 1)]
    if case_depth_mm:
        grids.append(case_depth_mm + np.linspace(-0.5 * h, 0.5 * h, N_NEAR + 1))
    t = np.unique(np.concatenate(grids))
    t = t[t >= 0.0]                 # a case depth under ½ element: its window starts at 0
    vals, ok = probe.stress_at(node, x[:, None] + n[:, None] * t[None, :])
    tt, vm = t[ok], von_mises(vals[ok])
    if not ok[0]:        # the surface point itself not located (round-off): its nodal value
        tt = np.concatenate([[0.0], tt])
        vm = np.concatenate([[float(von_mises(np.asarray(ref.stress_ref, float)[:, node]))],
                             vm])
    s0 = float(vm[0])
    near = tt <= h * (1.0 + 1e-9)
    G, rms = 0.0, math.nan
    if near.sum() >= 4 and s0 > 0:
        v0, slope, r = _quad_fit(tt[near], vm[near], 0.0)
        G, rms = -slope / v0, r / s0
    g_case, ratio = G, 1.0
    if case_depth_mm:
        win = np.abs(tt - case_depth_mm) <= 0.5 * h * (1.0 + 1e-9)
        if win.sum() >= 4 and s0 > 0:
            vc, slope_c, _ = _quad_fit(tt[win], vm[win], case_depth_mm)
            ratio = vc / s0
            g_case = -slope_c / vc if vc > 0 else 0.0
    return Profile(int(node), tuple(float(c) for c in x), tuple(float(c) for c in n), h, tt, vm,
                   float(G), float(g_case), float(ratio), float(rms))


def check(layer: str, depth: float, s_cycles: tuple[np.ndarray, np.ndarray], count,
          sigma_ref: float, G: float, d_eff: float, card: StrengthCard, rz: float,
          k_v: float, *, rules, j_D: float, damage_sum: float, design_life: float,
          hint=None, under: tuple | None = None) -> tuple[Check, fkm.Spectrum]:
    """One layer's check and its spectrum of relative amplitudes σ_a / (K_AK σ_WK) (sorted
    once, ``fkm.Spectrum``; ``hint``: another node's order). ``under`` = (the surface's
    spectrum, its σ_WK, r): the core's cycles are the surface's × r (K_AK and M unchanged:
    the same ratio σ_m/σ_a and the same d_eff), so its spectrum is the surface's scaled by
    r σ_WK,surface / σ_WK,core, without a second pass over the classes."""
    g = fkm.GROUPS[card.group]
    K_d = fkm.size_factor(d_eff, g)
    R_m = K_d * card.rm_n_MPa
    s_wzd = g.f_w_sigma * R_m
    K_R = fkm.roughness_factor(rz, R_m, g)
    n = fkm.support_factor(G, R_m, g)
    K_WK = fkm.design_factor(n, K_R, g, k_v)
    s_wk = s_wzd / K_WK
    M = fkm.mean_stress_sensitivity(R_m, g)
    sa, sm = s_cycles
    if under is None:
        k_ak = fkm.mean_stress_factor(sa, sm, M)
        spec = fkm.Spectrum(sa / (k_ak * s_wk), count, hint=hint)
    else:
        base, s_wk_base, r = under
        spec = base.scaled(r * s_wk_base / s_wk)
    life, safety, util = {}, {}, {}
    for rule in rules:
        life[rule] = spec.life(rule, damage_sum)
        safety[rule] = spec.scale_for_life(rule, damage_sum, design_life)
        util[rule] = j_D / safety[rule] if safety[rule] > 0 else math.inf
    i = int(np.argmax(sa)) if sa.size else 0
    k_ak_i = float(fkm.mean_stress_factor(sa[i], sm[i], M)) if sa.size else math.nan
    return (Check(layer, depth, sigma_ref, G, d_eff, K_d, R_m, s_wzd, rz, K_R, n, k_v, K_WK,
                  s_wk, M, k_ak_i, float(sa[i]) if sa.size else 0.0,
                  float(sm[i]) if sa.size else 0.0, life, safety, util), spec)


def _start_stop(sigma: float, c: Check) -> float:
    """Relative amplitude σ_a / (K_AK σ_WK) of the cycle 0 → ``sigma`` (σ_a = |σ|/2, σ_m = σ/2)
    in the check ``c``'s strengths: a history-free measure of how hard a node would be loaded."""
    sa, sm = 0.5 * abs(sigma), 0.5 * sigma
    return float(sa / (fkm.mean_stress_factor(sa, sm, c.M_sigma) * c.sigma_WK_MPa))


def assess_field(ref, history, card: StrengthCard, surfaces: Surfaces, *,
                 ground_fillets: frozenset[str], rule: str = "modified", j_D: float = 1.5,
                 damage_sum: float = 0.3, design_life_blocks: float = 1e7,
                 cycles=None) -> FkmResult:
    """Every region of the ``ASSESSED_KINDS`` of the static reference ``ref`` under ``history``.
    ``cycles``: the rainflow count of ``history`` re-referenced to ``ref.ref_rpm`` where the
    caller has it (the seed method's, ``FatigueField.result.cycles``): counted once."""
    h = history.with_reference(ref.ref_rpm)
    if cycles is None:
        cyc = count_cycles(h.load_factor)
    else:
        cyc = cycles
    S = np.asarray(ref.stress_ref, dtype=float)
    signed = signed_von_mises(S.T)
    excluded = np.zeros(signed.size, dtype=bool)
    excluded[np.asarray(ref.excluded, dtype=np.int64)] = True
    probe = depth_probe(ref)
    rules = fkm.MINER
    out, notes, hints, assessed = [], [], {}, []   # hints: the last spectrum's order, per sign
    node = _NodeAssessment(ref, cyc, card, probe, S, dict(rules=rules, j_D=j_D,
                                                          damage_sum=damage_sum,
                                                          design_life=design_life_blocks), rule)
    for name in sorted(ref.regions):
        if kind_of(name) not in ASSESSED_KINDS:
            continue
        nodes = np.asarray(ref.regions[name], dtype=np.int64)
        nodes = nodes[~excluded[nodes]]
        if nodes.size == 0:
            notes.append(f"{name}: every node is in the singular-point exclusion")
            continue
        sv = signed[nodes]              # the highest tensile and the highest compressive
        cand = np.unique(np.concatenate([nodes[np.argsort(-sv)[:N_CANDIDATES]],
                                         nodes[np.argsort(sv)[:N_CANDIDATES]]]))
        rz = region_rz(name, surfaces, ground_fillets)
        best = None
        for i in cand:
            res, u, s_min = node(name, int(i), rz, hints)
            surf, s_soft = res.surface, res.surface.sigma_ref_MPa
            assessed.append((int(i), u, s_min))
            # the worst node; among equal utilisations (a history without load cycles: all 0)
            # the one a start-stop cycle 0 → its reference stress would load most (relative
            # amplitude, F2 Haigh: tension counts more than compression), so that the hot spot
            # stays where a load cycle would put it
            key = (u, _start_stop(s_soft, surf))
            if best is None or key > best[0]:
                best = (key, res)
        out.append(best[1])
    return FkmResult(card, rule, j_D, damage_sum, float(design_life_blocks), float(h.duration_s),
                     tuple(out), tuple(notes), cyc, tuple(assessed))


class _NodeAssessment:
    """One surface node's FKM assessment (its stress cycles with spin softening, its profile,
    the surface and core checks) on one reference and count: ``__call__(region, node, rz,
    hints)`` -> (RegionResult, utilisation, safety) under ``rule``, the worse layer's."""

    def __init__(self, ref, cyc, card, probe, S, common: dict, rule: str):
        self.ref, self.cyc, self.card, self.probe, self.common, self.rule = \
            ref, cyc, card, probe, common, rule
        self.S = S
        self.linear = (None if ref.stress_linear is None else
                       np.asarray(ref.stress_linear, float))
        self.xyz = np.asarray(ref.xyz, float)

    def __call__(self, name: str, i: int, rz: float, hints: dict):
        card, cyc, common = self.card, self.cyc, self.common
        s_soft = float(signed_von_mises(self.S[:, i]))
        beta, s_lin = 0.0, s_soft
        if self.linear is not None:
            s_lin = float(signed_von_mises(self.linear[:, i]))
            beta = float(softening_beta(np.array([s_soft]), np.array([s_lin]))[0])
        sa, sm = stress_cycles(s_lin, beta if beta else None, cyc)
        prof = profile(self.ref, i, self.probe, card.case_depth_mm)
        x = self.xyz[:, i]
        d_eff = fkm.effective_diameter(x[1], x[2])
        notched = is_notch(name)
        kv = k_v_case_hardening(d_eff, notched) if card.case_hardened else 1.0
        sign = s_lin >= 0
        surf, spec = check("surface", 0.0, (sa, sm), cyc.count, s_soft, prof.G_surface,
                           d_eff, card, rz, kv, hint=hints.get(sign), **common)
        hints[sign] = spec.order
        core = None
        if card.case_hardened:
            r = prof.case_ratio
            core, _ = check("core", card.case_depth_mm, (r * sa, r * sm), cyc.count,
                            r * s_soft, prof.G_case, d_eff, card, 1.0, 1.0,
                            under=(spec, surf.sigma_WK_MPa, r), **common)
        res = RegionResult(name, i, tuple(float(c) for c in x), notched, prof, surf, core,
                           s_lin, beta)
        rule = self.rule
        u = max(surf.utilisation[rule], core.utilisation[rule] if core else 0.0)
        return res, u, min(surf.safety[rule], core.safety[rule] if core else math.inf)


@dataclass(frozen=True, eq=False)
class FkmAlong:
    """FKM at every cross-section of the shaft (``assess_along``): per axial bin of
    ``ALONG_STEP_MM`` the worse of its highest tensile and highest compressive surface node
    (outside the singular-point exclusion), its utilisation and safety under the governing
    rule (the worse layer) and the region it lies in ("surface": none); a slice whose surface
    nodes all lie in the exclusion (a bearing's or a load patch's edges): NaN, region
    "excluded"; a slice without a surface node (a coarse surface's rings can lie further
    apart than a slice) is left out."""
    x_mm: np.ndarray
    utilisation: np.ndarray
    safety: np.ndarray
    region: tuple[str, ...]


ALONG_STEP_MM = 1.0      # FKM's cross-sections (each bin: two nodes with a stress profile)


def assess_along(ref, surfaces: Surfaces, res: FkmResult, *, ground_fillets: frozenset[str],
                 step_mm: float = ALONG_STEP_MM) -> FkmAlong:
    """FKM at every cross-section: the surface nodes (the reference's face triangles') in
    bins of ``step_mm`` along x, each bin judged by its highest tensile and highest
    compressive node as ``assess_field`` judges a region's candidates (the same count, card,
    j_D, rule, design life and Miner sum as ``res``), and by the nodes ``res`` assessed in it
    (its regions' candidates: so no slice reads below a hot spot in it); the worst kept (among
    equal utilisations, as ``assess_field``: the one a start-stop cycle loads most). A node's
    roughness and K_V are its region's (notches first, then the seats; the rest turned)."""
    S = np.asarray(ref.stress_ref, dtype=float)
    signed = signed_von_mises(S.T)
    surf = np.unique(np.asarray(ref.face_cells, dtype=np.int64))
    excluded = np.zeros(signed.size, dtype=bool)
    excluded[np.asarray(ref.excluded, dtype=np.int64)] = True
    region = np.full(signed.size, "surface", dtype=object)
    # the seats first, the notches over them (a fillet's node beside a seat is the fillet's)
    for name in sorted(ref.regions, key=lambda n: (is_notch(n), n)):
        if kind_of(name) in ASSESSED_KINDS:
            region[np.asarray(ref.regions[name], dtype=np.int64)] = name
    x = np.asarray(ref.xyz, float)[0, surf]
    lo, hi = float(x.min()), float(x.max())
    nb = max(1, math.ceil((hi - lo) / step_mm))
    b = np.minimum(((x - lo) / step_mm).astype(np.int64), nb - 1)
    node = _NodeAssessment(ref, res.cycles, res.card, depth_probe(ref),
                           S, dict(rules=fkm.MINER, j_D=res.j_D, damage_sum=res.damage_sum,
                                   design_life=res.design_life_blocks), res.rule)
    xs, us, ss, names, hints = [], [], [], [], {}
    ax = np.asarray(ref.xyz, float)[0]
    own = {r.node: r.region for r in res.regions}
    done: dict = {}                                  # slice -> [(u, safety, region)] of res's
    for i, u, sf in res.assessed:
        k = min(max(int((ax[i] - lo) / step_mm), 0), nb - 1)
        done.setdefault(k, []).append((u, sf, own.get(i, str(region[i]))))
    order = np.argsort(b, kind="stable")
    starts = np.searchsorted(b[order], np.arange(nb + 1))
    for k in range(nb):
        idx = surf[order[starts[k]:starts[k + 1]]]
        if idx.size == 0:
            continue
        xs.append(lo + (k + 0.5) * step_mm)
        idx = idx[~excluded[idx]]
        if idx.size == 0:
            us.append(math.nan)
            ss.append(math.nan)
            names.append("excluded")
            continue
        sv = signed[idx]
        worst = None
        for i in sorted({int(idx[np.argmax(sv)]), int(idx[np.argmin(sv)])}):
            name = str(region[i])
            r, u, sf = node(name, i, region_rz(name, surfaces, ground_fillets), hints)
            key = (u, _start_stop(r.surface.sigma_ref_MPa, r.surface))
            if worst is None or key > worst[0]:
                worst = (key, sf, name)
        (u, _), sf, name = worst
        for u_r, sf_r, name_r in done.get(k, ()):
            if u_r > u:
                u, sf, name = u_r, sf_r, name_r
        us.append(u)
        ss.append(sf)
        names.append(name)
    return FkmAlong(np.array(xs), np.array(us), np.array(ss), tuple(names))


def governing_cycles(res: FkmResult) -> dict:
    """The governing check's stress cycles and strengths, for its plots: amplitude and mean
    (MPa, the layer's: the core's are the surface's × r), count, K_AK per cycle, σ_WK, M and
    the relative amplitudes s = σ_a / (K_AK σ_WK)."""
    reg, c = res.governing
    cyc = res.cycles
    sa, sm = stress_cycles(reg.s_lin_MPa, reg.beta if reg.beta else None, cyc)
    if c.layer == "core":
        r = reg.profile.case_ratio
        sa, sm = r * sa, r * sm
    k_ak = fkm.mean_stress_factor(sa, sm, c.M_sigma)
    return {"region": reg.region, "layer": c.layer, "x_mm": reg.xyz_mm[0], "amplitude": sa,
            "mean": sm, "count": cyc.count, "K_AK": k_ak, "sigma_WK": c.sigma_WK_MPa,
            "M": c.M_sigma, "s": sa / (k_ak * c.sigma_WK_MPa)}
