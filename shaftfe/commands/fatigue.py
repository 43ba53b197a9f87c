"""`shaftfe fatigue`: fatigue life and safety factor of the shaft under an engine-speed history.

Replaces the seed's Ansys Fatigue Tool study (SPEC §3). The static reference solution (3D FE at
``shaftfe.static.solve.REF_RPM``) comes from the disk cache of ``shaftfe.static.cache`` when the model
is unchanged, else it is solved once. The history's load factor is re-referenced to the static
solution's speed, every node is evaluated at once (``shaftfe.fatigue.field``), and the command
writes ``fatigue.vtu``, ``summary.json`` and three plots of the hot spot.

Defaults = the seed's settings: von Mises, Soderberg, Ansys "Structural Steel", design life 1e7
blocks, 70 km/h, bearing springs; every part of the variant loads the shaft, as in every other
command (``--seed-load-case``: only the gear + counterweight 1 (F1) and counterweight 2 (Fv2), the
forces the seed applied; the seed's result is printed beside ours only then).

Stdlib only at module level; numpy / scikit-fem / meshio / matplotlib inside the handler.
"""

from __future__ import annotations

import argparse
import json
import math

from shaftfe.errors import InputError

MEAN_STRESS = ("soderberg", "goodman", "gerber", "none")
EQUIVALENT = ("von_mises", "signed_von_mises")
from shaftfe.solid.levels import LEVEL_NAMES as LEVELS

SEED_RPM_REF = 7000.0

# The seed's result (seed 000 §8.3) for the side-by-side comparison.
SEED = {"safety_factor_at_1e7": 0.7, "life_blocks": 25_000.0, "life_hours": 2083.0,
        "life_km": 145_810.0,
        "hot_spot": "fillet at the heavier counterweight (the collar fillet on the "
                    "counterweight-2 side, x ≈ 64.5 mm)",
        "hot_spot_x_mm": 64.5}


def register(sub) -> None:
    p = sub.add_parser(
        "fatigue", help="fatigue life and safety factor under an rpm history (rainflow, Miner)",
        description="Fatigue of the balancer shaft under an engine-speed history: the 3D static "
        "solution (cached) scaled by (rpm/ref)^2, rainflow counting of the load factor, a "
        "mean-stress correction, the S-N curve and Miner's rule at every node. Prints the life "
        "in blocks / hours / km, the safety factor at the design life and the hot spot "
        "(singular points at the bearing and load-patch edges excluded; the unfiltered minimum "
        "shown too). Writes fatigue.vtu, summary.json and rainflow / damage / Haigh plots.")
    p.add_argument("spectrum", help="rpm history: normalised rpm²/ref² (seed rpm.dat), rpm, or "
                   "csv 'time_s,rpm' (see shaftfe.fatigue.history)")
    p.add_argument("--variant", default="x2_57", help="variant name or path (default x2_57)")
    p.add_argument("--ref-rpm", type=float, default=None,
                   help="speed a normalised history is normalised by (default: the file's "
                   "'# reference_rpm' header, else 7000 as the seed)")
    p.add_argument("--sample-rate", type=float, default=None,
                   help="sample rate in Hz of an rpm / normalised file without a header")
    p.add_argument("--mean-stress", default="soderberg",
                   help="soderberg | goodman | gerber | none (default soderberg, as the seed)")
    p.add_argument("--equivalent", default="von_mises",
                   help="von_mises | signed_von_mises (default von_mises, as the seed)")
    p.add_argument("--material", default="structural_steel",
                   help="S-N card in geometry/common/sn_curves.toml: structural_steel (default, "
                   "the seed's Ansys Structural Steel) | 14220")
    p.add_argument("--design-life", type=float, default=1e7,
                   help="design life in blocks (passes of the history), default 1e7")
    p.add_argument("--speed-kmh", type=float, default=70.0,
                   help="average riding speed for the life in km (default 70)")
    p.add_argument("--kf", type=float, default=1.0,
                   help="fatigue strength factor in (0, 1] multiplying the S-N curve (default 1)")
    p.add_argument("--level", default="default", help="mesh level: coarse | default | fine")
    p.add_argument("--exclude-mm", type=float, default=0.0,
                   help="exclude also nodes closer than this to a bearing / load patch edge "
                   "from the filtered hot spot (default 0: one element layer, as shaftfe static)")
    p.add_argument("--seed-load-case", action=argparse.BooleanOptionalAction, default=False,
                   help="load only the seed's forces F1 (gear + counterweight 1) and Fv2 "
                   "(counterweight 2), as the seed did; default off: every part, as every "
                   "command")
    p.add_argument("--cache-dir", default=None,
                   help="cache directory for the mesh and the static solution (default "
                   "$SHAFTFE_CACHE_DIR or ~/.cache/shaftfe)")
    p.add_argument("--json", action="store_true", help="print the summary JSON instead of text")
    p.add_argument("--out", default=None,
                   help="output directory (default reports/<variant>/fatigue)")
    p.set_defaults(handler=run)


def _check(args) -> None:
    if args.mean_stress not in MEAN_STRESS:
        raise InputError("command line", "--mean-stress", " | ".join(MEAN_STRESS),
                         got=args.mean_stress)
    if args.equivalent not in EQUIVALENT:
        raise InputError("command line", "--equivalent", " | ".join(EQUIVALENT),
                         got=args.equivalent)
    if args.level not in LEVELS:
        raise InputError("command line", "--level", " | ".join(LEVELS), got=args.level)
    check_life_settings(args.design_life, args.speed_kmh)
    if not (math.isfinite(args.kf) and 0 < args.kf <= 1):
        raise InputError("command line", "--kf", "a number in (0, 1]", got=args.kf)
    from shaftfe.commands.static import check_exclude_mm
    check_exclude_mm(args.exclude_mm)
    if args.ref_rpm is not None and not (math.isfinite(args.ref_rpm) and args.ref_rpm > 0):
        raise InputError("command line", "--ref-rpm", "a finite speed > 0 (rpm)",
                         got=args.ref_rpm)


def read_spectrum(path: str, ref_rpm: float | None, sample_rate: float | None):
    """The history; a normalised file without a reference (header or option) is taken as
    normalised to 7000 rpm, the seed's reference."""
    from shaftfe.fatigue.history import read_history
    try:
        return read_history(path, rpm_ref=ref_rpm, sample_rate_hz=sample_rate)
    except InputError as exc:
        if ref_rpm is None and exc.field == "reference_rpm":
            return read_history(path, rpm_ref=SEED_RPM_REF, sample_rate_hz=sample_rate)
        raise


SEED_SETTINGS = {"mean_stress": "soderberg", "equivalent": "von_mises",
                 "material": "structural_steel", "design_life": 1e7, "kf": 1.0,
                 "seed_load_case": True}


def seed_applies(args, variant_name: str) -> bool:
    """The seed's x2_57 result is comparable only for variant x2_57, the seed's rpm.dat (same
    bytes) and the seed's settings (``SEED_SETTINGS``)."""
    from pathlib import Path

    from shaftfe.report.assemble import DEFAULT_SPECTRUM
    try:
        same_file = Path(args.spectrum).read_bytes() == DEFAULT_SPECTRUM.read_bytes()
    except OSError:
        same_file = False
    return (variant_name == "x2_57" and same_file
            and all(getattr(args, k) == v for k, v in SEED_SETTINGS.items()))


def _num(v: float):
    return float(v) if math.isfinite(v) else None



def run(args) -> int:
    import time
    from pathlib import Path

    _check(args)
    from shaftfe.fatigue.sn import load_material
    from shaftfe.model.loader import load_variant
    from shaftfe.util.progress import Progress
    prog = Progress(["history", "static", "rainflow + life", "outputs"],
                    enabled=False if args.json else None)
    with prog.stage("history"):
        history = read_spectrum(args.spectrum, args.ref_rpm, args.sample_rate)
    material = load_material(args.material)
    variant = load_variant(args.variant)

    from shaftfe.commands._common import print_json
    from shaftfe.fatigue.field import evaluate
    from shaftfe.static import cache as static_cache
    from shaftfe.static.solve import StaticOptions
    from shaftfe.util.atomic import staged_dir

    extra = {"exclude_mm": args.exclude_mm} if args.exclude_mm > 0 else {}
    opts = StaticOptions(level=args.level, seed_load_case=args.seed_load_case, **extra)
    out = Path(args.out) if args.out else Path("reports") / variant.name / "fatigue"
    with staged_dir(out) as stage:             # every file or none
        with prog.stage("static"):
            ref = static_cache.load_or_solve(variant, opts, args.cache_dir)
        with prog.stage("rainflow + life"):
            t0 = time.perf_counter()
            ff = evaluate(ref, history, material, equivalent=args.equivalent,
                          theory=args.mean_stress, kf=args.kf,
                          design_life_blocks=args.design_life, speed_kmh=args.speed_kmh)
            t_eval = time.perf_counter() - t0
            level_error = level_correction(args, ref, ff, history, material)
        with prog.stage("outputs"):
            summary, plots = _write_outputs(args, history, material, ref, ff, t_eval,
                                            level_error, stage)
    if args.json:
        print_json(summary)
        return 0
    _print_result(args, variant, history, material, ref, ff, t_eval, out, plots)
    if level_error is not None:
        e = level_error
        print(f"mesh level {args.level}: its peak stress reads {100 * e['stress_rel_error']:+.1f} "
              f"% against the static benchmark's converged reference ({e['source']}); with the "
              f"hot-spot stress corrected by that, the life is {_life(e['life_blocks'])} blocks "
              f"({_pct(e['life_blocks'], ff.hot_spot.life_blocks)}) and the safety factor "
              f"{e['safety_factor']:.3f}")
    return 0


def level_correction(args, ref, ff, history, material) -> dict | None:
    """The level's measured peak-stress error (reports/benchmarks/static.json, the same rule as
    the report) and the hot spot's life with the stress corrected by it; None where the
    benchmark does not cover this level's mesh."""
    from shaftfe.report.assemble import benchmark_errors, level_corrected_life
    got = level_corrected_life(ref, ff, history, material, benchmark_errors(args.level),
                               3 * ref.n_nodes,
                               equivalent=args.equivalent, theory=args.mean_stress, kf=args.kf,
                               design_life_blocks=args.design_life, speed_kmh=args.speed_kmh)
    if got is None:
        return None
    meta, corr = got
    return {**meta, **{k: _num(v) for k, v in corr.items()}}


def _pct(new: float | None, old: float) -> str:
    if new is None or not (math.isfinite(old) and old > 0):
        return "-"
    return f"{100 * (new / old - 1):+.0f} %"


def _write_outputs(args, history, material, ref, ff, t_eval, level_error, out):
    from shaftfe.commands._common import package_versions, write_atomic
    from shaftfe.fatigue import kernels
    from shaftfe.fatigue import plots as fatigue_plots
    from shaftfe.fatigue.counting import rainflow_matrix
    from shaftfe.fatigue.field import write_vtu
    from shaftfe.static.solve import load_case_label
    from shaftfe.util.atomic import atomic_path
    r = ff.result
    hot, raw = ff.hot_spot, ff.hot_spot_unfiltered
    vtu = out / "fatigue.vtu"
    write_vtu(ref, ff, vtu)
    s_hot = hot.sigma_eq_ref_MPa
    plots = {}
    lbl = f"{hot.region} x = {hot.xyz_mm[0]:.1f} mm"
    with atomic_path(out / "rainflow_matrix.png") as tmp:
        fatigue_plots.plot_cycle_matrix(
            rainflow_matrix(r.cycles, scale=s_hot if s_hot != 0 else 1.0), tmp,
            title=f"rainflow matrix per block\nhot spot {lbl}")
    plots["rainflow_matrix"] = "rainflow_matrix.png"
    with atomic_path(out / "damage_matrix.png") as tmp:
        fatigue_plots.plot_cycle_matrix(
            kernels.damage_matrix(s_hot, r.cycles, material, args.mean_stress, args.kf), tmp,
            title=f"damage matrix per block\nhot spot {lbl}")
    plots["damage_matrix"] = "damage_matrix.png"
    with atomic_path(out / "haigh.png") as tmp:
        fatigue_plots.plot_haigh(s_hot, r.cycles, material, tmp, args.mean_stress, args.kf)
    plots["haigh"] = "haigh.png"

    lf = ff.history.load_factor
    static_info = {
        "from_cache": ref.from_cache, "seconds": ref.seconds,
        "solve_seconds": ref.solve_seconds, "ref_rpm": ref.ref_rpm, "cache_key": ref.key,
        "relative_residual": ref.relative_residual,
        "mesh_key": ref.mesh_key, "variant_hash": ref.variant_hash, "options": ref.options,
        "n_nodes": ref.n_nodes, "n_elements": ref.n_elements, "n_excluded_nodes": ff.n_excluded,
        "notes": list(ref.notes)}
    summary = {
        "inputs": {"spectrum": str(args.spectrum), "variant": args.variant,
                   "ref_rpm": args.ref_rpm, "sample_rate_hz": args.sample_rate,
                   "mean_stress": args.mean_stress, "equivalent": args.equivalent,
                   "material": args.material, "design_life_blocks": args.design_life,
                   "speed_kmh": args.speed_kmh, "kf": args.kf, "level": args.level,
                   "seed_load_case": args.seed_load_case,
                   "load_case": load_case_label(args.seed_load_case),
                   "exclude_mm": args.exclude_mm,
                   "supports": "bearing springs (2x2 radial stiffness)"},
        "versions": package_versions("matplotlib"),
        "history": {"source": history.source, "format": history.format,
                    "samples": history.n_samples, "duration_s": history.duration_s,
                    "rpm_min": float(history.rpm.min()), "rpm_max": float(history.rpm.max()),
                    "rpm_ref_of_file": history.rpm_ref, "static_ref_rpm": ff.ref_rpm,
                    "load_factor_min": float(lf.min()), "load_factor_max": float(lf.max()),
                    "note": "load factor = (rpm / static_ref_rpm)^2 multiplies the static "
                            "stresses at static_ref_rpm"},
        "static": static_info,
        "cycles": {"per_block": r.cycles.total_count, "classes": r.cycles.n,
                   "closure": r.cycles.closure},
        "result": {"life_blocks": _num(hot.life_blocks), "life_hours": _num(hot.life_hours),
                   "life_km": _num(hot.life_km), "infinite_life": hot.infinite_life,
                   "damage_per_block": _num(hot.damage_per_block),
                   "safety_factor": hot.safety_factor, "safety_status": hot.safety_status,
                   "design_life_blocks": args.design_life,
                   "safety_factor_cap": kernels.SAFETY_FACTOR_MAX,
                   "min_safety_factor_filtered": float(r.safety_factor[~ff.excluded_mask].min())
                   if (~ff.excluded_mask).any() else None,
                   "min_safety_factor_unfiltered": float(r.safety_factor.min())},
        "hot_spot": hot.to_dict(),
        "hot_spot_unfiltered": raw.to_dict(),
        "regions": [h.to_dict() for h in ff.region_hot_spots if h is not None],
        "seed": SEED if seed_applies(args, ref.variant) else None,
        "notes": list(r.notes) + list(ref.notes),
        "vtu": {"file": vtu.name, "regions": list(ref.face_groups),
                "point_data": ["life_blocks", "damage_per_block", "safety_factor",
                               "von_mises_ref"],
                "von_mises_ref_rpm": ref.ref_rpm,
                "note": "life_blocks = inf where there is no damage; von_mises_ref at "
                        "von_mises_ref_rpm"},
        "plots": plots,
        "timing": {"fatigue_seconds": t_eval},
        "level_error": level_error,
    }
    text = json.dumps(summary, indent=2, allow_nan=False)
    write_atomic(out / "summary.json", text + "\n")
    return summary, plots


def _print_result(args, variant, history, material, ref, ff, t_eval, out, plots) -> None:
    from shaftfe.commands._common import print_table
    from shaftfe.static.solve import load_case_label
    r = ff.result
    hot, raw = ff.hot_spot, ff.hot_spot_unfiltered
    s_hot = hot.sigma_eq_ref_MPa
    lf = ff.history.load_factor
    vtu = out / "fatigue.vtu"
    print(f"{variant.name} fatigue: {history.source} ({history.n_samples} samples, "
          f"{history.duration_s:g} s block, rpm {history.rpm.min():.0f}-{history.rpm.max():.0f}, "
          f"file reference {history.rpm_ref:g} rpm)")
    if ref.from_cache:
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
        print(f"life: {_big(hot.life_blocks)} blocks = {_big(hot.life_hours)} h = "
              f"{_big(hot.life_km)} km at {args.speed_kmh:g} km/h")
    cap = " (capped: life at this load factor >= design life)" \
        if hot.safety_status == "capped" else ""
    print(f"safety factor at {args.design_life:g} blocks: {hot.safety_factor:.3f}{cap}")
    print(f"hot spot: {hot.region} at x y z = {_xyz(hot.xyz_mm)} mm, "
          f"sigma_eq = {s_hot:.1f} MPa at {ref.ref_rpm:g} rpm"
          + (f" = {s_hot * (history.rpm_ref / ref.ref_rpm) ** 2:.1f} MPa at "
             f"{history.rpm_ref:g} rpm" if history.rpm_ref != ref.ref_rpm else "")
          + " "
          f"(singular points excluded: {ff.n_excluded} nodes)")
    print(f"unfiltered minimum: {raw.region} at x y z = {_xyz(raw.xyz_mm)} mm, life "
          f"{_life(raw.life_blocks)} blocks, safety factor {raw.safety_factor:.3g}"
          f"{' (a singular point, excluded)' if raw.excluded else ''}")
    print()
    rows = [[h.region, h.xyz_mm[0], h.sigma_eq_ref_MPa, _life(h.life_blocks), h.safety_factor]
            for h in ff.region_hot_spots if h is not None and not h.region.startswith("end:")]
    print_table(["region", "x mm", f"sigma_eq MPa @{ref.ref_rpm:g}", "life blocks",
                 f"SF @{args.design_life:g}"], rows, title="per region (filtered)")
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


def _big(v: float) -> str:
    """Thousands with a space (25 000), small values with 3 significant digits."""
    return f"{v:,.0f}".replace(",", " ") if abs(v) >= 1000 else f"{v:.3g}"


def _life(v: float | None) -> str:
    return "inf" if v is None or not math.isfinite(v) else f"{v:.4g}"


def check_life_settings(design_life: float, speed_kmh: float) -> None:
    """The design life (blocks) and the speed that turns hours into km: finite and > 0
    (shared by ``shaftfe fatigue`` and ``shaftfe report``)."""
    if not (math.isfinite(design_life) and design_life > 0):
        raise InputError("command line", "--design-life", "a finite number > 0 (blocks)",
                         got=design_life)
    if not (math.isfinite(speed_kmh) and speed_kmh > 0):
        raise InputError("command line", "--speed-kmh", "a finite number > 0 (km/h)",
                         got=speed_kmh)
