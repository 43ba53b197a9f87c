"""The seed's method (seed 000 §8.3, the Ansys Fatigue Tool): an equivalent stress (von Mises),
a mean-stress correction (Soderberg), an S-N card (Structural Steel) and Miner's rule at every
node of the 3D or axisymmetric field (``fatigue.run.run_fatigue``, ``fatigue.field``); files by
``fatigue.outputs``."""

from __future__ import annotations

import math
from types import MappingProxyType

from shaftfe.fatigue.methods.protocol import AssessmentInputs, FatigueAssessment, Location
from shaftfe.solid.features import kind_of


class Seed:
    name = "seed"
    title = ("the seed's Ansys-style method: von Mises, Soderberg, Structural Steel S-N; "
             "exactly as before")
    options = ("--mean-stress", "--equivalent", "--material", "--kf", "--model", "--level",
               "--exclude-mm", "--seed-load-case", "--spin-softening", "--design-life",
               "--design-life-h")
    narrowed = MappingProxyType({})
    out_dir = "fatigue"
    files = ("fatigue.vtu", "haigh.png", "rainflow_matrix.png", "damage_matrix.png",
             "summary.json")
    optional_files = ()
    files_help = ("fatigue.vtu (life, damage, safety factor at every node), haigh.png, "
                  "rainflow_matrix.png, damage_matrix.png, summary.json")
    stages = ("static", "rainflow + life")

    def check(self, options) -> None:
        """Everything the seed method reads is checked by ``run.check_job``."""

    def assess(self, inputs: AssessmentInputs, options, progress=None) -> FatigueAssessment:
        from contextlib import nullcontext

        from shaftfe.fatigue import channel_run as cr
        from shaftfe.fatigue.run import (
            FatigueInputs,
            resolve_design_life,
            run_fatigue,
            sn_material,
            static_reference,
        )
        from shaftfe.util.notices import raised
        ch = inputs.single(self.name)
        material = sn_material(options, inputs.variant)
        with raised() as warned:
            ref = ch.field
            if ref is None and any(ld.scales_with != "rpm2" for ld in inputs.variant.loads):
                # several load patterns: the reference's per-pattern fields (channel_run)
                job = resolve_design_life(options, ch.history, inputs.variant.duty)
                with (progress.stage(self.stages[0]) if progress is not None
                      else nullcontext()):
                    ref = static_reference(inputs.variant, job)
                if cr.needs_channels(ref):
                    with (progress.stage(self.stages[1]) if progress is not None
                          else nullcontext()):
                        crun = cr.run_channels(job, inputs.variant, ch.history, material, ref)
                    lv = crun.lives
                    locs = tuple(_channel_location(crun, i) for i in range(lv.nodes.size))
                    return FatigueAssessment(self.name, locs, locs[crun.hot], tuple(warned),
                                             tuple(ref.notes), crun)
            if ch.field is not None and inputs.variant is not None:     # the report's, a study's
                cr.warn_rpm2_only(inputs.variant, "the seed method on one given field")
            run = run_fatigue(options, FatigueInputs(ch.history, material, inputs.variant),
                              progress, ref=ref)
        ff = run.field
        return FatigueAssessment(self.name, tuple(_location(h) for h in ff.region_hot_spots
                                                  if h is not None), _location(ff.hot_spot),
                                 tuple(warned), tuple(ff.result.notes) + tuple(run.ref.notes),
                                 run)

    def write(self, result, inputs, options, out) -> tuple[dict, list[str]]:
        from shaftfe.fatigue import channel_run as cr
        from shaftfe.fatigue.outputs import write_outputs
        if isinstance(result.detail, cr.ChannelRun):
            return cr.write(result.detail, out)
        summary, plots = write_outputs(result.detail, out)
        return summary, ["fatigue.vtu", *plots.values(), "summary.json"]

    def lines(self, result, inputs, options, summary, out, files) -> list[str]:
        from shaftfe.fatigue import channel_run as cr
        if isinstance(result.detail, cr.ChannelRun):
            return cr.lines(result.detail, summary, out, files)
        return _lines(result.detail, out, summary["plots"])


METHOD = Seed()


def _location(h) -> Location:
    """A hot spot (``field.HotSpot``) as a ``Location``: utilisation 1 / safety factor (the
    stress factor to the design life)."""
    sf = h.safety_factor
    return Location(h.region, h.xyz_mm[0], 1.0 / sf if sf > 0 else math.inf, sf,
                    h.damage_per_block, h.life_blocks, h.life_hours, h.life_km)


def _channel_location(run, i: int) -> Location:
    """A candidate node of a several-pattern run as a ``Location``."""
    from shaftfe.fatigue.assess import life_hours, life_km
    d = float(run.lives.damage[i])
    blocks = 1.0 / d if d > 0 else math.inf
    hours = float(life_hours(blocks, run.history.duration_s))
    sf = float(run.lives.safety[i])
    return Location(run.regions[i], float(run.xyz[0, i]), 1.0 / sf if sf > 0 else math.inf,
                    sf, d, blocks, hours, float(life_km(hours, run.job.speed_kmh)))


def _lines(run, out, plots) -> list[str]:
    """The text of ``shaftfe fatigue --method seed`` (was the command's print)."""
    from shaftfe.static.model import load_case_label
    from shaftfe.util.fmt import design_life, life, lives, table_lines
    from shaftfe.util.units import rpm2_scale
    args, variant, history, material, ref, ff = (run.job, run.variant, run.history,
                                                 run.material, run.ref, run.field)
    t_eval = run.eval_seconds
    r = ff.result
    hot, raw = ff.hot_spot, ff.hot_spot_unfiltered
    s_hot = hot.sigma_eq_ref_MPa
    lf = ff.history.load_factor
    vtu = out / "fatigue.vtu"
    p = []
    p.append(f"{variant.name} fatigue: {history.source} ({history.n_samples} samples, "
             f"{history.duration_s:g} s block, rpm {history.rpm.min():.0f}-"
             f"{history.rpm.max():.0f}, file reference {history.rpm_ref:g} rpm)")
    how = f"{'read from the cache' if ref.from_cache else 'solved'} in {ref.seconds:.1f} s"
    if args.model == "axisymmetric":
        p.append(f"static: axisymmetric, {how} ({ref.ref_rpm:g} rpm, harmonics n = "
                 f"0..{ref.options['harmonics'][-1]}, {args.level}; {ref.n_nodes} surface "
                 "points)")
    elif args.model == "zoned":
        p.append(f"static: zoned (the axisymmetric global model and {len(ref.options['zones'])} "
                 f"3D zones), {how} ({ref.ref_rpm:g} rpm, {args.level}; {ref.n_nodes} surface "
                 "points)")
    elif ref.from_cache:
        p.append(f"static: from cache ({ref.seconds:.2f} s; solved at {ref.ref_rpm:g} rpm, "
                 f"{ref.n_nodes} nodes, P2 {args.level})")
    else:
        p.append(f"static: solved in {ref.seconds:.1f} s ({ref.ref_rpm:g} rpm, {ref.n_nodes} "
                 f"nodes, P2 {args.level})")
    p.append(f"load factor = (rpm / {ff.ref_rpm:g})^2 in [{lf.min():.4g}, {lf.max():.4g}]; "
             f"{args.equivalent}, {args.mean_stress}, {material.name}, kf {args.kf:g}, "
             f"load case: {load_case_label(args.seed_load_case)}, "
             "bearing springs")
    p.append(f"cycles per block: {r.cycles.total_count:g} ({r.cycles.n} distinct range/mean "
             f"classes, rainflow of the repeated block); evaluated {ff.n_nodes} nodes in "
             f"{t_eval:.3f} s")
    p.append("")
    if hot.infinite_life:
        why = ("the history has no load cycles (constant speed)" if r.cycles.n == 0 else
               "every cycle is below the endurance limit")
        p.append(f"life: infinite ({why}): no fatigue damage")
    elif not math.isfinite(hot.damage_per_block):
        p.append(f"life: 0 blocks (static failure: a cycle's mean stress reaches the "
                 f"{'yield' if args.mean_stress == 'soderberg' else 'ultimate'} strength)")
    else:
        p.append(f"life: {lives(hot.life_blocks, hot.life_hours, hot.life_km, args.speed_kmh)}")
    cap = " (capped: life at this load factor >= design life)" \
        if hot.safety_status == "capped" else ""
    p.append(f"safety factor at "
             f"{design_life(args.design_life, history.duration_s, args.speed_kmh)}"
             f": {hot.safety_factor:.3f}{cap}")
    p.append(f"hot spot: {hot.region} at x y z = {_xyz(hot.xyz_mm)} mm, "
             f"sigma_eq = {s_hot:.1f} MPa at {ref.ref_rpm:g} rpm"
             + (f" = {s_hot * rpm2_scale(history.rpm_ref, ref.ref_rpm):.1f} MPa at "
                f"{history.rpm_ref:g} rpm" if history.rpm_ref != ref.ref_rpm else "")
             + " "
             f"(singular points excluded: {ff.n_excluded} nodes)")
    p.append(f"unfiltered minimum: {raw.region} at x y z = {_xyz(raw.xyz_mm)} mm, life "
             f"{lives(raw.life_blocks, raw.life_hours)}, safety factor "
             f"{raw.safety_factor:.3g}{' (a singular point, excluded)' if raw.excluded else ''}")
    p.append("")
    rows = [[h.region, h.xyz_mm[0], h.sigma_eq_ref_MPa, life(h.life_blocks), h.safety_factor]
            for h in ff.region_hot_spots if h is not None and kind_of(h.region) != "end"]
    p += table_lines(["region", "x mm", f"sigma_eq MPa @{ref.ref_rpm:g}", "life blocks",
                      f"SF @{args.design_life:g}"], rows, title="per region (filtered)")
    from shaftfe.fatigue.run import SEED, seed_applies
    if seed_applies(args, variant.name):
        p.append("")
        p.append(f"seed (Ansys, seed 000 §8.3): safety factor {SEED['safety_factor_at_1e7']} "
                 "at 1e7, life 25 000 blocks (2083 h, 145 810 km), hot spot: "
                 f"{SEED['hot_spot']}")
    for n in list(r.notes) + list(ref.notes):
        p.append(f"note: {n}")
    p.append(f"\nwrote {vtu}, {out / 'summary.json'}, "
             + ", ".join(str(out / v) for v in plots.values()))
    e = run.level_error
    if e is not None:
        p.append(f"mesh level {args.level}: its peak stress reads "
                 f"{100 * e['stress_rel_error']:+.1f} % against the axisymmetric truth "
                 f"({e['source']}); with the hot-spot stress corrected by that, the life is "
                 f"{_lives_of(e, run)} ({_pct(e['life_blocks'], hot.life_blocks)}) and the "
                 f"safety factor {e['safety_factor']:.3f}")
    elif args.model == "solid":
        p.append(f"mesh level {args.level}: no measured error of its peak stress for this "
                 "shaft and mesh (measured on x2_57 as shipped: reports/benchmarks/truth.md); "
                 "no level correction of the life")
    return p


def _lives_of(e: dict, run) -> str:
    from shaftfe.fatigue.assess import life_hours
    from shaftfe.util.fmt import lives
    b = e["life_blocks"]
    return lives(b, None if b is None else float(life_hours(b, run.history.duration_s)))


def _pct(new: float | None, old: float) -> str:
    if new is None or not (math.isfinite(old) and old > 0):
        return "-"
    return f"{100 * (new / old - 1):+.0f} %"


def _xyz(p) -> str:
    return " ".join(f"{c:.2f}" for c in p)
