"""`shaftfe fatigue`: fatigue life and safety factor of the shaft under an engine-speed history.

Replaces the seed's Ansys Fatigue Tool study (SPEC §3). A thin command: the options become a
``shaftfe.fatigue.run.FatigueJob``, the method named by ``--method`` is taken from the registry
(``shaftfe.fatigue.methods.METHODS``: seed, FKM, DIN 743, ...) and assesses the history, writes
its files (all or none) and gives the lines this module prints. The command never asks which
method it holds.

Stdlib only at module level; numpy / scikit-fem / meshio / matplotlib inside the handler.
"""

from __future__ import annotations

import argparse
import dataclasses

from shaftfe.commands._common import add_engine_option
from shaftfe.solid.levels import LEVEL_NAMES


def register(sub) -> None:
    from shaftfe.fatigue.methods import DEFAULT_METHOD, METHODS
    p = sub.add_parser(
        "fatigue", help="fatigue life and safety factor under an rpm history (rainflow, Miner)",
        description="Fatigue of the balancer shaft under an engine-speed history: the static "
        "solution (--model: zoned by default; the full 3D one cached) scaled by (rpm/ref)^2, "
        "rainflow counting of the load factor, a mean-stress correction, the S-N curve and "
        "Miner's rule at every node. Prints the life in blocks / hours / km, the safety factor "
        "at the design life and the hot spot "
        "(singular points at the bearing and load-patch edges excluded; the unfiltered minimum "
        "shown too). Writes into --out, per method: " + "; ".join(
            f"{n}: {m.files_help}" for n, m in METHODS.items()) + ".")
    from shaftfe.fatigue.method_options import applies_to, help_epilog
    p.epilog = help_epilog()

    def opt(name, help, **kw):               # an option of some methods: default None (given?)
        p.add_argument(name, default=None, help=f"{help} {applies_to(name)}", **kw)
    p.add_argument("--method", default=DEFAULT_METHOD, help=" | ".join(
        f"{n} ({'default: ' if n == DEFAULT_METHOD else ''}{m.title})"
        for n, m in METHODS.items()))
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
    opt("--case", "a [[load_cases]] name of the variant: DIN 743's static check S_F on that "
        "case (its speed, factors and channels), beside the fatigue check")
    opt("--plot", "the safety along the shaft, plotted with its outline, and 'along' in "
        "summary.json: DIN 743's S_D and S_F at every cross-section (the unnotched section, "
        "every 0.25 mm) with each notch's (din743_along.png); FKM's degree of utilisation "
        "at every 1 mm of the surface (the worse of each slice's highest tensile and "
        "compressive node, fkm_along.png)", action="store_true")
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
    opt("--model", "static model: zoned (default: the axisymmetric surface with 3D zones at "
        "the keyways and the hex socket; per-pattern fields for loads not ∝ rpm²) | solid "
        "(3D P2 tets) | axisymmetric "
        "(Fourier harmonics on the revolved surface; keyways and the hex socket left out)")
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
                   help="output directory (default reports/<variant>/<folder>: " + ", ".join(
                       f"{m.out_dir} for {n}" for n, m in METHODS.items()) + ")")
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

    from shaftfe.commands._common import out_name, print_json
    from shaftfe.fatigue.method_options import with_defaults
    from shaftfe.fatigue.methods import AssessmentInputs, get_method
    from shaftfe.fatigue.run import check_job, load_inputs, resolve_model
    from shaftfe.util.atomic import staged_dir
    from shaftfe.util.progress import Progress
    method = get_method(args.method)
    with_defaults(args)                 # an option the method does not use: refused
    job = job_of(args)
    check_job(job)
    method.check(job)
    prog = Progress(["history", *method.stages, "outputs"],
                    enabled=False if args.json else None)
    with prog.stage("history"):
        got = load_inputs(job)
    job = resolve_model(job)
    inputs = AssessmentInputs.one_channel(got.variant, got.history)
    v = inputs.variant
    out = Path(args.out) if args.out else \
        Path("reports") / out_name(v.name, v.overrides) / method.out_dir
    with staged_dir(out, replaces=method.optional_files) as stage:    # every file or none
        result = method.assess(inputs, job, progress=prog)
        with prog.stage("outputs"):
            summary, files = method.write(result, inputs, job, stage)
    if args.json:
        print_json(summary)
        return 0
    for line in method.lines(result, inputs, job, summary, out, files):
        print(line)
    return 0
