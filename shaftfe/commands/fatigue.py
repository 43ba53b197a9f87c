"""`shaftfe fatigue`: fatigue life and safety factor of the shaft under an engine-speed history.

Replaces the seed's Ansys Fatigue Tool study (SPEC §3). A thin command: the options become a
``shaftfe.fatigue.run.FatigueJob``, ``run_fatigue`` does the work, ``shaftfe.fatigue.outputs``
writes fatigue.vtu, summary.json and three plots of the hot spot (all or none), and this module
prints the result.

Stdlib only at module level; numpy / scikit-fem / meshio / matplotlib inside the handler.
"""

from __future__ import annotations

import argparse
import dataclasses
import math

from shaftfe.commands._common import add_engine_option
from shaftfe.solid.levels import LEVEL_NAMES
from shaftfe.util.fmt import design_life, life, lives
from shaftfe.util.units import rpm2_scale


def register(sub) -> None:
    p = sub.add_parser(
        "fatigue", help="fatigue life and safety factor under an rpm history (rainflow, Miner)",
        description="Fatigue of the balancer shaft under an engine-speed history: the 3D static "
        "solution (cached) scaled by (rpm/ref)^2, rainflow counting of the load factor, a "
        "mean-stress correction, the S-N curve and Miner's rule at every node. Prints the life "
        "in blocks / hours / km, the safety factor at the design life and the hot spot "
        "(singular points at the bearing and load-patch edges excluded; the unfiltered minimum "
        "shown too). Writes into --out, per method: fkm: fatigue.vtu (fkm_utilisation, "
        "fkm_safety at the assessed surface nodes), haigh.png (F2, the governing spot's "
        "cycles), rainflow_matrix.png, damage_matrix.png, summary.json; din743: "
        "din743_safety.png (S_D, S_F per notch), summary.json; seed: fatigue.vtu (life, "
        "damage, safety factor at every node), haigh.png, rainflow_matrix.png, "
        "damage_matrix.png, summary.json.")
    from shaftfe.fatigue.method_options import applies_to, help_epilog
    p.epilog = help_epilog()

    def opt(name, help, **kw):               # an option of some methods: default None (given?)
        p.add_argument(name, default=None, help=f"{help} {applies_to(name)}", **kw)
    p.add_argument("--method", default="fkm",
                   help="fkm (default: FKM guideline, local stresses on the 3D field, the "
                   "shaft's real material and surface) | din743 (DIN 743, nominal stresses on "
                   "the beam) | seed (the seed's Ansys-style method: von Mises, Soderberg, "
                   "Structural Steel S-N; exactly as before)")
    opt("--card", "material record in geometry/common/materials.toml whose strengths the "
        "standards use (default: the variant's shaft material, e.g. 14220 = 16MnCr5 case "
        "hardened)")
    opt("--miner", "FKM governing Miner rule: elementary | modified (default, Haibach) | "
        "consistent; all three are printed")
    opt("--consequences", "FKM j_D: severe (default: a broken balancer shaft wrecks the "
        "engine) | moderate")
    opt("--inspection", "FKM j_D with regular inspections (default none)",
        action="store_true")
    opt("--damage-sum", "FKM effective damage sum D_M (default 0.3, steel)", type=float)
    opt("--kappa", "ISO 281 viscosity ratio κ of the bearings (default 1.0)", type=float)
    opt("--ec", "ISO 281 contamination factor e_C (default 0.3)", type=float)
    p.add_argument("spectrum", help="rpm history: normalised rpm²/ref² (seed rpm.dat), rpm, or "
                   "csv 'time_s,rpm' (see shaftfe.fatigue.history)")
    p.add_argument("--variant", default="x2_57", help="variant name or path (default x2_57)")
    add_engine_option(p, "engine file whose max_rpm is the highest speed the history may "
                      "reach (default: the highest speed of the variant's [duty] "
                      "speed_range_rpm)",
                      "assess a history above the engine's max_rpm (with a warning)")
    p.add_argument("--ref-rpm", type=float, default=None,
                   help="speed a normalised history is normalised by (default: the file's "
                   "'# reference_rpm' header, else 7000 as the seed)")
    p.add_argument("--sample-rate", type=float, default=None,
                   help="sample rate in Hz of an rpm / normalised file without a header")
    opt("--mean-stress", "soderberg | goodman | gerber | none (default soderberg, as the seed)")
    opt("--equivalent", "von_mises | signed_von_mises (default von_mises, as the seed)")
    opt("--material", "S-N card in geometry/common/sn_curves.toml, e.g. structural_steel | "
        "14220 | 12050 (default: the variant's [duty] sn_curve, structural_steel for the x2_* "
        "shafts as the seed; else the card of the shaft's material)")
    opt("--design-life-h", "design life in hours of riding (default: the variant's [duty] "
        "design life, 1e7 blocks of the 300 s block = 833 333 h for the x2_* shafts; none "
        "stated: 1e7 blocks with a warning); either form from one pass of the "
        "history to 1e9 blocks and 1e9 h", type=float)
    opt("--design-life", "design life in blocks (passes of the history), the seed's form; "
        "not together with --design-life-h; the same bounds", type=float)
    p.add_argument("--speed-kmh", type=float, default=70.0,
                   help="average riding speed for the life in km (default 70)")
    opt("--kf", "fatigue strength factor in (0, 1] multiplying the S-N curve (default 1)",
        type=float)
    opt("--model", "static model: solid (3D P2 tets, default) | axisymmetric (Fourier "
        "harmonics on the revolved surface; keyways and the hex socket left out; not FKM)")
    opt("--level", "mesh level: " + " | ".join(LEVEL_NAMES)
        + " (axisymmetric: coarse | default | fine; default: default)")
    opt("--exclude-mm", "exclude also nodes closer than this to a bearing / load patch edge "
        "from the filtered hot spot (default 0: one element layer, as shaftfe static)",
        type=float)
    opt("--seed-load-case", "load only the seed's forces F1 (gear + counterweight 1) and Fv2 "
        "(counterweight 2), as the seed did; default off: every part, as every command",
        action=argparse.BooleanOptionalAction)
    opt("--spin-softening", "the parts' m ω² u in the static solution (default on; each "
        "node's stress then follows S0 (λ + β λ²) over the history); the seed had none",
        action=argparse.BooleanOptionalAction)
    p.add_argument("--cache-dir", default=None,
                   help="cache directory for the mesh and the static solution (default "
                   "$SHAFTFE_CACHE_DIR or ~/.cache/shaftfe)")
    p.add_argument("--json", action="store_true", help="print the summary JSON instead of text")
    p.add_argument("--out", default=None,
                   help="output directory (default reports/<variant>/fatigue for seed, "
                   "reports/<variant>/fatigue-<method> for fkm, din743)")
    from shaftfe.commands._common import add_set_option
    add_set_option(p)
    p.set_defaults(handler=run)


def job_of(args):
    """The command's options as a ``FatigueJob`` (the fields have the options' names)."""
    from shaftfe.fatigue.run import FatigueJob
    kw = {f.name: getattr(args, f.name) for f in dataclasses.fields(FatigueJob)
          if f.name != "overrides"}
    return FatigueJob(**kw, overrides=tuple(getattr(args, "set", None) or ()))


def run(args) -> int:
    from pathlib import Path

    from shaftfe.commands._common import print_json
    from shaftfe.fatigue.method_options import with_defaults
    from shaftfe.fatigue.outputs import write_outputs
    from shaftfe.fatigue.run import check_job, load_inputs, run_fatigue
    from shaftfe.util.atomic import staged_dir
    from shaftfe.util.progress import Progress
    with_defaults(args)                 # an option the method does not use: refused
    job = job_of(args)
    check_job(job)
    if args.method != "seed":
        from shaftfe.commands.strength import run_standard
        return run_standard(args, job)
    prog = Progress(["history", "static", "rainflow + life", "outputs"],
                    enabled=False if args.json else None)
    with prog.stage("history"):
        inputs = load_inputs(job)
    from shaftfe.commands._common import out_name
    out = Path(args.out) if args.out else \
        Path("reports") / out_name(inputs.variant.name, inputs.variant.overrides) / "fatigue"
    with staged_dir(out) as stage:             # every file or none
        result = run_fatigue(job, inputs, progress=prog)
        with prog.stage("outputs"):
            summary, plots = write_outputs(result, stage)
    if args.json:
        print_json(summary)
        return 0
    _print_result(result, out, plots)
    e = result.level_error
    if e is not None:
        print(f"mesh level {job.level}: its peak stress reads {100 * e['stress_rel_error']:+.1f} "
              f"% against the axisymmetric truth ({e['source']}); with the "
              f"hot-spot stress corrected by that, the life is {_lives_of(e, result)} "
              f"({_pct(e['life_blocks'], result.field.hot_spot.life_blocks)}) and the safety "
              f"factor {e['safety_factor']:.3f}")
    elif job.model == "solid":
        print(f"mesh level {job.level}: no measured error of its peak stress for this shaft and "
              "mesh (measured on x2_57 as shipped: reports/benchmarks/truth.md); no level "
              "correction of the life")
    return 0


def _lives_of(e: dict, result) -> str:
    from shaftfe.fatigue.assess import life_hours
    b = e["life_blocks"]
    return lives(b, None if b is None else float(life_hours(b, result.history.duration_s)))


def _pct(new: float | None, old: float) -> str:
    if new is None or not (math.isfinite(old) and old > 0):
        return "-"
    return f"{100 * (new / old - 1):+.0f} %"


def _print_result(run, out, plots) -> None:
    from shaftfe.commands._common import print_table
    from shaftfe.static.model import load_case_label
    args, variant, history, material, ref, ff = (run.job, run.variant, run.history,
                                                 run.material, run.ref, run.field)
    t_eval = run.eval_seconds
    r = ff.result
    hot, raw = ff.hot_spot, ff.hot_spot_unfiltered
    s_hot = hot.sigma_eq_ref_MPa
    lf = ff.history.load_factor
    vtu = out / "fatigue.vtu"
    print(f"{variant.name} fatigue: {history.source} ({history.n_samples} samples, "
          f"{history.duration_s:g} s block, rpm {history.rpm.min():.0f}-{history.rpm.max():.0f}, "
          f"file reference {history.rpm_ref:g} rpm)")
    if args.model == "axisymmetric":
        print(f"static: axisymmetric, solved in {ref.seconds:.1f} s ({ref.ref_rpm:g} rpm, "
              f"harmonics n = 0..{ref.options['harmonics'][-1]}, {args.level}; "
              f"{ref.n_nodes} surface points)")
    elif ref.from_cache:
        print(f"static: from cache ({ref.seconds:.2f} s; solved at {ref.ref_rpm:g} rpm, "
              f"{ref.n_nodes} nodes, P2 {args.level})")
    else:
        print(f"static: solved in {ref.seconds:.1f} s ({ref.ref_rpm:g} rpm, {ref.n_nodes} "
              f"nodes, P2 {args.level})")
    print(f"load factor = (rpm / {ff.ref_rpm:g})^2 in [{lf.min():.4g}, {lf.max():.4g}]; "
          f"{args.equivalent}, {args.mean_stress}, {material.name}, kf {args.kf:g}, "
          f"load case: {load_case_label(args.seed_load_case)}, "
          "bearing springs")
    print(f"cycles per block: {r.cycles.total_count:g} ({r.cycles.n} distinct range/mean "
          f"classes, rainflow of the repeated block); evaluated {ff.n_nodes} nodes in "
          f"{t_eval:.3f} s")
    print()
    if hot.infinite_life:
        why = ("the history has no load cycles (constant speed)" if r.cycles.n == 0 else
               "every cycle is below the endurance limit")
        print(f"life: infinite ({why}): no fatigue damage")
    elif not math.isfinite(hot.damage_per_block):
        print(f"life: 0 blocks (static failure: a cycle's mean stress reaches the "
              f"{'yield' if args.mean_stress == 'soderberg' else 'ultimate'} strength)")
    else:
        print(f"life: {lives(hot.life_blocks, hot.life_hours, hot.life_km, args.speed_kmh)}")
    cap = " (capped: life at this load factor >= design life)" \
        if hot.safety_status == "capped" else ""
    print(f"safety factor at {design_life(args.design_life, history.duration_s, args.speed_kmh)}"
          f": {hot.safety_factor:.3f}{cap}")
    print(f"hot spot: {hot.region} at x y z = {_xyz(hot.xyz_mm)} mm, "
          f"sigma_eq = {s_hot:.1f} MPa at {ref.ref_rpm:g} rpm"
          + (f" = {s_hot * rpm2_scale(history.rpm_ref, ref.ref_rpm):.1f} MPa at "
             f"{history.rpm_ref:g} rpm" if history.rpm_ref != ref.ref_rpm else "")
          + " "
          f"(singular points excluded: {ff.n_excluded} nodes)")
    print(f"unfiltered minimum: {raw.region} at x y z = {_xyz(raw.xyz_mm)} mm, life "
          f"{lives(raw.life_blocks, raw.life_hours)}, safety factor {raw.safety_factor:.3g}"
          f"{' (a singular point, excluded)' if raw.excluded else ''}")
    print()
    rows = [[h.region, h.xyz_mm[0], h.sigma_eq_ref_MPa, life(h.life_blocks), h.safety_factor]
            for h in ff.region_hot_spots if h is not None and not h.region.startswith("end:")]
    print_table(["region", "x mm", f"sigma_eq MPa @{ref.ref_rpm:g}", "life blocks",
                 f"SF @{args.design_life:g}"], rows, title="per region (filtered)")
    from shaftfe.fatigue.run import SEED, seed_applies
    if seed_applies(args, variant.name):
        print()
        print(f"seed (Ansys, seed 000 §8.3): safety factor {SEED['safety_factor_at_1e7']} at "
              f"1e7, life 25 000 blocks (2083 h, 145 810 km), hot spot: {SEED['hot_spot']}")
    for n in list(r.notes) + list(ref.notes):
        print(f"note: {n}")
    print(f"\nwrote {vtu}, {out / 'summary.json'}, "
          + ", ".join(str(out / v) for v in plots.values()))


def _xyz(p) -> str:
    return " ".join(f"{c:.2f}" for c in p)
