"""`shaftfe report`: the whole assessment of a variant as one HTML page (issue 7).

Stdlib only at module level; the FE stack is imported by ``shaftfe.report.assemble`` inside the
handler, so ``shaftfe report --help`` stays instant.
"""

from __future__ import annotations

import argparse

from shaftfe.commands._common import add_engine_option


def register(sub) -> None:
    p = sub.add_parser(
        "report", help="run the whole assessment once and write an HTML report",
        description="Balancing at the engine's speed, the static solution at the design "
        "speeds (--model: the zoned model by default, the full 3D one with one solve scaled by "
        "rpm²), fatigue and FKM on the rpm history (reusing that solve, rainflow counted "
        "once) and the Campbell diagram from 0 to the engine's maximum speed, on one mesh and "
        "one model. Writes <out>/index.html (self-contained: images embedded; "
        "also in <out>/figures/), <out>/summary.json and <out>/<variant>.vtu. A progress "
        "display of the stages goes to stderr on a terminal (not with --json).")
    p.add_argument("--variant", default="x2_57", help="variant name or path (default x2_57)")
    p.add_argument("--spectrum", default=None,
                   help="rpm history (default: the variant's [duty] spectrum)")
    add_engine_option(p, "engine file for the balancing section and whose max_rpm bounds the "
                      "rpm history (default: the variant's [duty] engine; none: no balancing, "
                      "the [duty] speed range bounds the history)",
                      "assess an rpm history above the engine's max_rpm (with a warning)")
    p.add_argument("--rpm", default=None, help="design speeds, comma-separated (default: the "
                   "variant's [duty] design_speeds_rpm)")
    p.add_argument("--campbell-range", default=None, metavar="LO:HI",
                   help="speed range of the Campbell sweep in rpm (default: the variant's "
                   "[duty] campbell_range_rpm)")
    p.add_argument("--design-life-h", type=float, default=None, metavar="H",
                   help="design life in hours (default: the variant's [duty] design life)")
    p.add_argument("--material", default=None, metavar="CARD",
                   help="the seed method's S-N card in geometry/common/sn_curves.toml "
                   "(default: the variant's [duty] sn_curve, else the card of the shaft's "
                   "material)")
    p.add_argument("--level", default="default", help="mesh level: coarse | default | fine")
    p.add_argument("--model", default=None,
                   help="static model: zoned (default: the axisymmetric model with 3D zones "
                   "where the shaft is not round) "
                   "| solid (3D P2 tets) | axisymmetric (Fourier harmonics on a meridian mesh; "
                   "keyways and the hex socket left out)")
    p.add_argument("--rotor-model", default="beam",
                   help="rotor model of the Campbell diagram: beam (default) | solid")
    p.add_argument("--campbell-step", type=float, default=500.0, metavar="RPM",
                   help="speed step of the Campbell sweep in rpm (default 500)")
    p.add_argument("--estimate-error", action="store_true",
                   help="with --model solid: solve a second mesh level (coarse for default, "
                   "default for coarse and fine) for a Richardson estimate of the stress and "
                   "deflection errors (default: the measured error of the level from "
                   "reports/benchmarks)")
    p.add_argument("--seed-load-case", action="store_true",
                   help="load only the seed's forces F1 (gear + counterweight 1) and Fv2 "
                   "(counterweight 2), as the seed did (default: every part, as every command)")
    p.add_argument("--spin-softening", action=argparse.BooleanOptionalAction, default=True,
                   help="the parts' m ω² u in the static solution and fatigue (default on)")
    p.add_argument("--no-pictures", action="store_true",
                   help="skip the PyVista 3D pictures")
    p.add_argument("--cache-dir", default=None,
                   help="mesh and static cache directory (default $SHAFTFE_CACHE_DIR or "
                   "~/.cache/shaftfe)")
    p.add_argument("--json", action="store_true",
                   help="print summary.json to stdout instead of the text summary (no "
                   "progress display)")
    p.add_argument("--out", default=None, help="output directory (default reports/<variant>)")
    from shaftfe.commands._common import add_set_option
    add_set_option(p)
    p.set_defaults(handler=run)


def options_from_args(args):
    from shaftfe.commands._common import parse_range, parse_rpm_list
    from shaftfe.report.options import ReportOptions
    from shaftfe.util.limits import RPM_CEILING

    camp = None
    if args.campbell_range is not None:
        lo, hi, _ = parse_range(args.campbell_range, "--campbell-range", lo=0.0, hi=RPM_CEILING)
        camp = (lo, hi)
    return ReportOptions(
        variant=args.variant, spectrum=args.spectrum,
        engine=args.engine, campbell_range_rpm=camp, design_life_h=args.design_life_h,
        design_rpm=tuple(parse_rpm_list(args.rpm)) if args.rpm is not None else None,
        material=args.material, level=args.level, rotor_model=args.rotor_model,
        campbell_step_rpm=args.campbell_step, estimate_error=args.estimate_error,
        cache_dir=args.cache_dir, pictures=not args.no_pictures,
        seed_load_case=args.seed_load_case, model=args.model,
        spin_softening=args.spin_softening, allow_overspeed=args.allow_overspeed,
        overrides=tuple(getattr(args, "set", None) or ()))


def run(args) -> int:
    return make_report(options_from_args(args), args.out, json_out=args.json)


def make_report(options, out=None, *, json_out: bool = False, progress=None) -> int:
    """Run, write and tell where the report is (the handler of ``report`` and ``demo``)."""
    import json
    import sys
    from pathlib import Path

    from shaftfe import report as report_pkg
    from shaftfe.commands._common import print_json
    from shaftfe.report import assemble
    from shaftfe.report.options import check_options, stages
    from shaftfe.util.atomic import staged_dir
    from shaftfe.util.progress import Progress

    check_options(options)
    from shaftfe.commands._common import out_name
    variant_name = out_name(Path(options.variant).stem, options.overrides)
    out = Path(out) if out else Path("reports") / variant_name
    prog = progress or Progress(stages(options), enabled=False if json_out else None)
    with staged_dir(out) as stage:              # every file of the report or none
        rep = assemble.run_report(options, stage, prog)
        report_pkg.write(rep, stage)
    page = out / "index.html"
    if json_out:
        print_json(json.loads((out / "summary.json").read_text()))
        return 0
    prog.done(f"shaftfe report: {page}")
    _print_summary(rep, page)
    sys.stdout.flush()
    return 0


def _short(text: str, width: int = 48) -> str:
    """The model column of the text summary: two rows of one quantity (3D FE and beam) are
    told apart by it."""
    return text if len(text) <= width else text[:width - 1] + "…"


def _print_summary(rep, page) -> None:
    from shaftfe.commands._common import print_table
    from shaftfe.report.html import PEAK_FIT_LABEL, headline, life, num, pct

    st, fat = rep.static, rep.fatigue
    hs = fat["hot_spot"]
    c0 = st["cases"][0]
    node = c0.get("peak_von_mises_node_MPa")
    print(f"{rep.inputs['variant']}: {rep.inputs['description']}")
    print(f"load case: {st['load_case']}")
    print(f"static {st['model_label']} ({num(st['n_dofs'])} dofs): peak von Mises "
          f"{num(c0['peak_von_mises_MPa'], 4)} MPa at {num(c0['rpm'])} rpm ({c0['peak_region']}; "
          f"{PEAK_FIT_LABEL}" + (f", largest nodal value {num(node, 4)} MPa" if node else "")
          + ")")
    h = headline(rep)
    if h:
        print(f"fatigue, {h['method']} (the default method): degree of utilisation "
              f"{num(h['utilisation'], 3, strip=False)} "
              f"({'passes' if h['passes'] else 'FAILS'}), safety "
              f"{num(h['safety'], 3, strip=False)}"
              + (f"; life: {life(h['life_blocks'], h['life_hours'])}"
                 if h["method"] == "FKM" else "") + f"; {h['what']}")
    print(f"fatigue, seed method ({fat['settings']['mean_stress']}, "
          f"{fat['settings']['material']}): life {num(hs['life_blocks'], 4)} blocks = "
          f"{num(hs['life_hours'], 4)} h = {num(hs['life_km'], 4)} km; safety factor "
          f"{num(hs['safety_factor'], 3)} at {num(fat['settings']['design_life_blocks'])} blocks; "
          f"hot spot {hs['region']}")
    print(f"Campbell: {rep.campbell['statement']}")
    rows = [[c.quantity, c.unit, num(c.seed, 5), num(c.ours, 5), pct(c.diff_percent),
             _short(c.model)] for c in rep.comparisons if c.group in ("static", "fatigue")]
    if rows:                                  # the seed's shaft only
        print()
        print_table(["quantity", "unit", "seed", "shaftfe", "diff", "shaftfe model"], rows,
                    title="seed figures next to ours (all of them in the report)")
    print()
    print("run time: " + ", ".join(f"{n} {t:.1f} s" for n, t in rep.timings)
          + f"; total {sum(t for _, t in rep.timings):.1f} s")
    print(f"\nreport: {page}")
