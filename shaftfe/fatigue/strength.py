"""Strength by standard as an API: ``run_fkm`` (FKM local stresses on the static field) and
``run_din743`` (DIN 743 nominal stresses on the beam model), over the same history and the same
rainflow count as the seed method (``shaftfe.fatigue.run``). ``shaftfe fatigue --method`` is a
thin command over these.

DIN 743 is a fatigue-limit check of one stress cycle: the history's largest rainflow cycle
(the block's lowest to highest speed; all stresses ∝ rpm², so the mean-to-amplitude ratio is
constant: DIN 743 case 2) for S_D, and the highest speed of the history for S_F.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shaftfe.beam.scf import KT_GROOVES, KT_UNDERCUTS, converged_kt, undercut_kt
from shaftfe.beam.solve import beam_at_ref
from shaftfe.errors import InputError
from shaftfe.fatigue import din743, fkm
from shaftfe.fatigue.cards import card_of, load_card, load_surfaces, region_rz
from shaftfe.fatigue.counting import count_cycles
from shaftfe.fatigue.fkm_field import assess_field, k_v_case_hardening
from shaftfe.fatigue.run import load_inputs, resolve_design_life, resolve_model, static_reference
from shaftfe.machine_elements.bearings import EC_DEFAULT, KAPPA_DEFAULT
from shaftfe.model.grooves import UNDERCUTS, undercut_at
from shaftfe.solid.features import fillet_region, groove_region, hole_region
from shaftfe.util.notices import warn
from shaftfe.util.units import REF_RPM


@dataclass(frozen=True)
class StrengthOptions:
    card: str | None = None         # a record of geometry/common/materials.toml; None = the
    #                                 variant's shaft material (the drawing's): ``strength_card``
    rule: str = "modified"          # governing Miner rule (all three are reported)
    consequences: str = "severe"    # FKM j_D: severe | moderate
    inspection: bool = False        # FKM j_D: regular inspections
    damage_sum: float = 0.3         # FKM effective damage sum D_M, steel


def check_options(o: StrengthOptions) -> None:
    if o.rule not in fkm.MINER:
        raise InputError("command line", "--miner", " | ".join(fkm.MINER), got=o.rule)
    if o.consequences not in ("severe", "moderate"):
        raise InputError("command line", "--consequences", "severe | moderate",
                         got=o.consequences)
    if not (math.isfinite(o.damage_sum) and 0.05 <= o.damage_sum <= 1.0):
        raise InputError("command line", "--damage-sum", "a number in [0.05, 1]",
                         got=o.damage_sum)


def strength_options(job) -> StrengthOptions:
    """The standards' options of a ``fatigue.run.FatigueJob`` (the command's names)."""
    return StrengthOptions(card=job.card, rule=job.miner, consequences=job.consequences,
                           inspection=job.inspection, damage_sum=job.damage_sum)


def bearing_options(job) -> tuple[float, float]:
    """(κ, e_C) of the bearings' ISO 281 life over the duty cycle: the job's or the defaults
    (``machine_elements.bearings``), each within the standard's range."""
    kappa = KAPPA_DEFAULT if job.kappa is None else job.kappa
    ec = EC_DEFAULT if job.ec is None else job.ec
    if not (math.isfinite(kappa) and 0.1 <= kappa <= 4.0):
        raise InputError("command line", "--kappa", "a number in [0.1, 4] (ISO 281)", got=kappa)
    if not (math.isfinite(ec) and 0.0 <= ec <= 1.0):
        raise InputError("command line", "--ec", "a number in [0, 1] (ISO 281 Table 13)",
                         got=ec)
    return kappa, ec


def strength_card(variant, opts: StrengthOptions):
    """The strength card an assessment uses: the record named by ``opts.card`` (``--card``) if
    given, else the variant's own shaft material (the drawing's), the same record its FE model
    takes E, ν and density from."""
    if opts.card is not None:
        return load_card(opts.card)
    return card_of(variant.material, f"variant {variant.name}")


def ground_fillets(variant) -> frozenset[str]:
    """The fillets at the end of a bearing seat or next to one (ground with the seat)."""
    segs = variant.segments
    out = set()
    for i, s in enumerate(segs[:-1]):
        if s.fillet_mm > 0 and (s.name.startswith("bearing_seat")
                                or segs[i + 1].name.startswith("bearing_seat")):
            out.add(fillet_region(s.name))
    return frozenset(out)


def run_fkm(job, opts: StrengthOptions, inputs=None, ref=None, progress=None):
    """FKM on the static reference of ``job`` (a ``FatigueJob``: variant, history, mesh level,
    load case); returns (``fkm_field.FkmResult``, inputs, ref). ``progress``: a
    ``util.progress.Progress`` with the stages "static" and "FKM"."""
    from contextlib import nullcontext

    check_options(opts)
    inputs = inputs or load_inputs(job)
    job = resolve_design_life(resolve_model(job), inputs.history,
                              inputs.variant.duty)
    card = strength_card(inputs.variant, opts)
    def stage(name):
        return progress.stage(name) if progress is not None else nullcontext()
    with stage("static"):
        ref = ref or static_reference(inputs.variant, job)
    with stage("FKM"):
        res = assess_field(ref, inputs.history, card, load_surfaces(),
                           ground_fillets=ground_fillets(inputs.variant), rule=opts.rule,
                           j_D=fkm.J_D[(opts.consequences, opts.inspection)],
                           damage_sum=opts.damage_sum, design_life_blocks=job.design_life)
    return res, inputs, ref


# --------------------------------------------------------------------------- DIN 743, beam

@dataclass(frozen=True)
class Din743Row:
    x_mm: float
    result: din743.Result
    stresses: din743.Stresses


@dataclass(frozen=True, eq=False)
class Din743Along:
    """DIN 743 at every cross-section of the shaft (``din743_along``): the unnotched section
    of the local diameter on a grid of ``ALONG_STEP_MM``; the notches are the run's rows."""
    x_mm: np.ndarray
    d_mm: np.ndarray
    S_D: np.ndarray
    S_F: np.ndarray


ALONG_STEP_MM = 0.25       # the cross-sections' spacing (the beam's moment is linear between
#                            its stations: a finer grid adds nothing but points)


@dataclass(frozen=True)
class Din743Run:
    card: object
    ref_rpm: float
    rpm_min: float
    rpm_max: float
    rows: tuple[Din743Row, ...]
    notes: tuple[str, ...]
    along: Din743Along | None = None        # every cross-section (``--plot``), or None

    @property
    def governing(self) -> Din743Row:
        return min(self.rows, key=lambda r: min(r.result.S_D, r.result.S_F))


def section_stresses(beam, x: float, d: float, span: float) -> tuple[float, float, float]:
    """The nominal stresses (σ_zd = 4N/(πd²), σ_b = 32M/(πd³), τ_t = 16T/(πd³)) MPa a notch at
    x of diameter d is judged by: the larger |N|, M, |T| at x − span and x + span (a hub's load
    spread over its seat: the more loaded end). A section load below 1e-9 of the largest
    bending moment (or axial force) is the round-off of an unloaded end: 0."""
    N = beam.N if beam.N is not None else np.zeros_like(beam.M)
    scale = float(np.max(np.abs(beam.M))) or 1.0
    n_scale = max(float(np.max(np.abs(N), initial=0.0)), scale)

    def at(line) -> float:
        return max(abs(float(np.interp(xx, beam.x_sec, line))) for xx in (x - span, x + span))
    n, m, t = at(N), at(beam.M), at(beam.T)
    zd = 4.0 * n / (math.pi * d ** 2) if n > 1e-9 * n_scale else 0.0
    sb = 32.0 * m / (math.pi * d ** 3) if m > 1e-9 * scale else 0.0
    tt = 16.0 * t / (math.pi * d ** 3) if t > 1e-9 * scale else 0.0
    return zd, sb, tt


def din743_notches(variant, beam, card, surfaces, table: dict) -> list[tuple]:
    """(x, Notch, d for the nominal stress, half-span judged around x) at every shoulder,
    groove, keyway and bearing seat."""
    gf = ground_fillets(variant)
    out = []
    segs = variant.segments
    for nt in beam.notches:
        if nt.kind != "shoulder":       # grooves and holes: from the variant (below)
            continue
        i = next(i for i, s in enumerate(segs) if abs(s.x_end_mm - nt.x_mm) < 1e-6)
        u = undercut_at(segs, i) if nt.undercut else None
        if u is not None:
            # a DIN 509 undercut: its converged Kt (nominal on its bottom diameter) where the
            # table holds it or interpolated between its points (``scf.undercut_kt``), else
            # DIN 743-2's α of the shoulder from its bottom diameter with its radius (the
            # beam's notch), which lies below the converged Kt over the table's grid
            # (reports/benchmarks/undercuts.md)
            k, j, g = u
            name, region = f"undercut {segs[k].name}:{j}", groove_region(segs[k].name, j)
            hit = undercut_kt(g.kind, nt.D_mm, segs[k].diameter_mm, g.radius_mm, table)
            al = hit[0] if hit else None
            src = (f"converged Kt ({KT_UNDERCUTS})" if hit and hit[1] == "table" else
                   f"converged Kt interpolated between the undercuts of {KT_UNDERCUTS} (its "
                   "error between them: reports/benchmarks/undercuts.md §4)" if hit else
                   f"DIN 743-2 formula (a shoulder to the DIN 509 {g.kind[-1].upper()} "
                   f"undercut's bottom diameter with R{g.radius_mm:g}; below the converged Kt, "
                   "reports/benchmarks/undercuts.md)")
            if not al:
                warn("undercut-kt-formula", region, f"DIN 743 takes the shoulder formula for "
                     f"this undercut (D {nt.D_mm:g}, d {segs[k].diameter_mm:g}, "
                     f"R{g.radius_mm:g}: neither in {KT_UNDERCUTS} nor between its points); "
                     "over that table's grid it reads below the converged Kt in every row "
                     "(reports/benchmarks/undercuts.md), so S_D comes out high; outside the "
                     "grid no bound is measured: add the undercut to benchmarks/"
                     "bench_undercuts.py's grid")
        else:
            name, region = f"shoulder {segs[i].name}", fillet_region(segs[i].name)
            al = table.get((round(nt.D_mm, 6), round(nt.d_mm, 6), round(nt.r_mm, 6)))
            src = "converged Kt (reports/benchmarks/kt_reference.json)" if al else \
                "DIN 743-2 formula (no converged Kt for this geometry)"
        out.append((nt.x_mm, din743.Notch(name, "shoulder", nt.d_mm, nt.D_mm, nt.r_mm, al, src,
                                          region_rz(region, surfaces, gf), nt.D_mm),
                    nt.d_mm, 0.0))
    for s in variant.segments:
        for kw in s.keyways:
            # a hub's load is spread over its seat: the keyway is judged at its more loaded
            # end (the beam's point load at the seat centre has no moment there)
            out.append((kw.x_center_mm, din743.Notch(f"keyway {s.name}", "keyway",
                                                     s.diameter_mm, d_eff_mm=s.diameter_mm),
                        s.diameter_mm, 0.5 * kw.length_mm))
        for j, g in enumerate(s.grooves):
            if g.kind in UNDERCUTS:       # assessed as its shoulder (above)
                continue
            # a U groove by its α (DIN 743-2 "Rundnut"); a retaining-ring groove by its
            # measured β (§4.2.4); the nominal stresses on the groove's bottom diameter
            d = s.diameter_mm - 2.0 * g.depth_mm
            kind = "ring_groove" if g.kind == "din471" else "groove"
            # the table's grooves are one arc (width 2ρ, ``axisymmetric.kt.grooved_bar``): a
            # flat-bottomed groove takes the standard's α
            one_arc = abs(g.width_mm - 2.0 * g.radius_mm) <= 1e-6
            al = table.get(("groove", round(s.diameter_mm, 6), round(d, 6),
                            round(g.radius_mm, 6))) if kind == "groove" and one_arc else None
            src = ("DIN 743-2 §4.2.4 β (ring groove)" if kind == "ring_groove" else
                   f"converged Kt ({KT_GROOVES})" if al else
                   "DIN 743-2 formula (round groove; no converged Kt for this geometry)")
            out.append((g.x_center_mm, din743.Notch(
                f"groove {s.name}:{j}", kind, d, s.diameter_mm, g.radius_mm, al, src,
                region_rz(groove_region(s.name, j), surfaces, gf), s.diameter_mm,
                width_mm=g.width_mm), d, 0.0))
        for j, h in enumerate(s.cross_holes):
            # DIN 743-2's α of a transverse hole; the nominal stresses on the net section
            # (din743.net_section_scale)
            out.append((h.x_center_mm, din743.Notch(
                f"cross hole {s.name}:{j}", "cross_hole", s.diameter_mm, s.diameter_mm,
                0.5 * h.diameter_mm, None, "DIN 743-2 formula (transverse hole)",
                region_rz(hole_region(s.name, j), surfaces, gf), s.diameter_mm,
                hole_mm=h.diameter_mm), s.diameter_mm, 0.0))
        if s.name.startswith("bearing_seat"):
            # the hub's edge: the seat's end, or an undercut's opening there (the ring reaches
            # over the undercut and bears on the cylinder only)
            cut = {g.side: g.width_mm for g in s.grooves if g.kind in UNDERCUTS}
            for x in (s.x_start_mm + cut.get("left", 0.0), s.x_end_mm - cut.get("right", 0.0)):
                out.append((x, din743.Notch(f"press fit {s.name} @{x:g}", "press_fit",
                                            s.diameter_mm, d_eff_mm=s.diameter_mm),
                            s.diameter_mm, 0.0))
    return sorted(out, key=lambda r: r[0])




def notch_stresses(beam, x: float, notch, d: float, span: float) -> tuple[float, float, float]:
    """The nominal stresses a notch is judged by: ``section_stresses`` on the full round
    section, times the notch's own section's factors (a transverse hole's net section,
    ``din743.net_section_scale``)."""
    return tuple(v * k for v, k in zip(section_stresses(beam, x, d, span),
                                       din743.net_section_scale(notch), strict=True))


def _stresses(zd: float, sb: float, tt: float, lo: float, hi: float) -> din743.Stresses:
    """The cycle lo → hi (load factors) of the nominal stresses at the reference speed."""
    a, m = (hi - lo) / 2, (hi + lo) / 2
    return din743.Stresses(zd_a=zd * a, zd_m=zd * m, b_a=sb * a, b_m=sb * m, t_a=tt * a,
                           t_m=tt * m)


def din743_along(variant, beam, card, surfaces, lo: float, hi: float,
                 step_mm: float = ALONG_STEP_MM) -> Din743Along:
    """S_D and S_F of the unnotched section at every cross-section x (step ``step_mm``, and
    each segment's ends): DIN 743 with α = β = 1, the local diameter for K1, K2 and the
    nominal stresses, the turned (or a bearing seat's ground) surface for K_F, K_V of an
    unnotched case-hardened section. The load cycle lo → hi is the notches' (``run_din743``)."""
    xs, ds, rzs = [], [], []
    for s in variant.segments:
        n = max(2, math.ceil(s.length_mm / step_mm) + 1)
        xs.append(np.linspace(s.x_start_mm, s.x_end_mm, n))
        ds.append(s.diameter_at(xs[-1]))         # (linear along a cone)
        rzs.append(np.full(n, surfaces.seat_rz_um if s.name.startswith("bearing_seat")
                           else surfaces.turned_rz_um))
    x, d, rz_all = np.concatenate(xs), np.concatenate(ds), np.concatenate(rzs)
    sd, sf = np.empty(x.size), np.empty(x.size)
    for i, (xi, di, rz) in enumerate(zip(x, d, rz_all, strict=True)):
        kv = k_v_case_hardening(di, False) if card.case_hardened else 1.0
        notch = din743.Notch("plain", "plain", float(di), rz_um=float(rz), d_eff_mm=float(di))
        res = din743.assess(notch, _stresses(*section_stresses(beam, xi, di, 0.0), lo, hi),
                            card.rm_n_MPa, card.rp_n_MPa, card.group, k_v=kv,
                            hard_layer=card.case_hardened, case=2)
        sd[i], sf[i] = res.S_D, res.S_F
    return Din743Along(x, d, sd, sf)


def size_diameters_note(rows) -> str:
    """The diameters DIN 743's size factors take at each shoulder, against FKM's rule."""
    sh = [(r.result.notch.name, din743.heat_treatment_diameter(r.result.notch),
           r.result.notch.d_mm) for r in rows if r.result.notch.kind == "shoulder"]
    each = "; ".join(f"{n}: K1 at {D:g} mm, K2 at {d:g} mm" for n, D, d in sh)
    return ("size factors: DIN 743-2 takes the technological K1 at the heat-treatment diameter "
            "(the larger diameter D at a shoulder) and the geometric K2 (and K3) at the notch "
            f"diameter d ({each}); FKM takes its K_d,m at the diameter of the round section "
            "through its hot spot (about d on a fillet): the two standards' rules differ")


def din743_card(variant, opts: StrengthOptions):
    """``strength_card``, refused unless DIN 743 has a law for its group (case-hardening and
    quenched-and-tempered steels here)."""
    card = strength_card(variant, opts)
    if card.group not in ("case_hardening_steel", "qt_steel"):
        raise InputError("geometry/common/materials.toml", f"materials.{card.name}.group",
                         "case_hardening_steel | qt_steel for DIN 743", got=card.group)
    return card


def run_din743(job, opts: StrengthOptions, inputs=None, beam=None) -> Din743Run:
    check_options(opts)
    inputs = inputs or load_inputs(job)
    card = din743_card(inputs.variant, opts)
    ref_rpm = REF_RPM
    beam = beam if beam is not None else beam_at_ref(inputs.variant)
    h = inputs.history.with_reference(ref_rpm)
    cyc = count_cycles(h.load_factor)
    lo, hi = float(h.load_factor.min()), float(h.load_factor.max())
    if cyc.n:                              # the largest cycle of the repeated block
        k = int(np.argmax(cyc.range))
        lo, hi = float(cyc.minimum[k]), float(cyc.maximum[k])
    rows, notes = [], []
    table = converged_kt()
    surfaces = load_surfaces()
    for x, notch, d, span in din743_notches(inputs.variant, beam, card, surfaces, table):
        st = _stresses(*notch_stresses(beam, x, notch, d, span), lo, hi)
        kv = k_v_case_hardening(notch.d_mm, True) if card.case_hardened else 1.0
        res = din743.assess(notch, st, card.rm_n_MPa, card.rp_n_MPa, card.group, k_v=kv,
                            hard_layer=card.case_hardened, case=2)
        rows.append(Din743Row(x, res, st))
    notes.append(size_diameters_note(rows))
    out = [r.result.notch.name for r in rows if r.result.notch.kind == "groove"
           and not r.result.notch.alpha and not din743.groove_in_range(r.result.notch)]
    if out:
        notes.append("outside the range of DIN 743-2's groove formula (r/t ≥ 0.03, d/D ≤ "
                     f"0.98): {', '.join(out)}; its α is extrapolated there")
    rpm = h.rpm_ref * math.sqrt(hi), h.rpm_ref * math.sqrt(lo)
    along = (din743_along(inputs.variant, beam, card, surfaces, lo, hi)
             if getattr(job, "plot", False) else None)
    return Din743Run(card, ref_rpm, rpm[1], rpm[0], tuple(rows), tuple(notes), along)
