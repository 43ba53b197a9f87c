"""`shaftfe static`: 3D static stress and deflection on spring-supported bearings.

Stdlib only at module level; numpy / scikit-fem / gmsh / meshio / matplotlib inside the handler.
"""

from __future__ import annotations

import argparse
import math

from shaftfe.commands._common import (
    add_engine_option,
    add_set_option,
    check_speeds,
    design_speeds,
    load_variant_from,
    out_name,
    parse_rpm_list,
    print_json,
    print_table,
)
from shaftfe.errors import InputError
from shaftfe.solid.features import SEAT_KINDS, kind_of, segment_of, shoulder_region
from shaftfe.solid.levels import LEVEL_NAMES
from shaftfe.static import STATIC_MODELS
from shaftfe.util.fmt import life

# a 3D zone's field per file (the zoned solve): zone files an earlier run left in the folder
# (another shaft's zones, or another model's run) are removed by every model's run
ZONE_FILES = ("zone_*.vtu",)


def register(sub) -> None:
    p = sub.add_parser(
        "static", help="3D FE static check: stresses, deflections, bearing reactions, L10h",
        description="Static analysis of a balancer-shaft variant in the co-rotating frame. "
        "Default (--model zoned): the shaft as a body of revolution (axisymmetric harmonics) "
        "with 3D P2 submodels only in the zones of the keyways and the hex socket; --model "
        "solid: the full 3D P2 model, described here: every load of the variant (the parts' "
        "m e ω² at their centroids and the [[loads]]) as a remote load on its seat or band, "
        "bearings as RBE3 remote points on 2×2 radial springs (or rigid), θ_x held only where "
        "a bearing holds torsion. One factorisation, one solve per load pattern, each speed or "
        "--case their superposition "
        "(spin softening, on by default: each case exactly by a low-rank update). "
        "Writes result.vtu, summary.json and deflection.png to --out.")
    p.add_argument("--variant", required=True, help="variant name (geometry/<name>.toml) or path")
    p.add_argument("--rpm", default=None,
                   help="speed(s) in rpm, comma-separated (default: the first of the variant's "
                   "[duty] design_speeds_rpm, 10000 for the x2_* shafts), e.g. 7000,10000; "
                   "each at its plain factors (rpm² loads × (rpm/ref)², constant × 1, channel "
                   "loads at their channel_ref)")
    p.add_argument("--case", default=None, metavar="NAME",
                   help="run the variant's [[load_cases]] entry NAME (its rpm and factors) "
                   "instead of --rpm")
    add_engine_option(p)
    p.add_argument("--model", default="zoned", choices=STATIC_MODELS,
                   help="zoned (default): the axisymmetric model of the whole shaft, 3D P2 "
                   "submodels only in the zones of the keyways and the hex socket, driven by "
                   "the global field at their cuts; solid: the full 3D P2 model (the "
                   "reference); axisymmetric: the body of revolution alone (keyways and the "
                   "hex socket left out; says which peaks they affect)")
    p.add_argument("--level", default="default", help="mesh level: " + " | ".join(LEVEL_NAMES))
    p.add_argument("--order", type=int, default=2, help="element order 1 | 2 (default 2)")
    p.add_argument("--rigid-supports", action="store_true",
                   help="Inventor-style rigid supports (remote-point radial translations = 0)")
    p.add_argument("--load-distribution", default="uniform",
                   help="pressure on the pressed half seat: uniform | cosine (default uniform)")
    p.add_argument("--body-force", action="store_true",
                   help="add the shaft's own centrifugal body force (off by default)")
    p.add_argument("--spin-softening", action=argparse.BooleanOptionalAction, default=True,
                   help="each part's m ω² u (the deflected part's centrifugal force in the "
                   "co-rotating frame; on by default: +1.5 %% on the collar fillet at "
                   "10 000 rpm); 3D: every --rpm solved exactly by a low-rank update of one "
                   "factorisation; --model axisymmetric and zoned: one solve per --rpm")
    p.add_argument("--seed-load-case", action="store_true",
                   help="load only the parts the seed loaded (gear, counterweights 1 and 2)")
    p.add_argument("--solver", default="auto",
                   help="auto | superlu | pardiso | amg (default auto: pardiso if installed)")
    p.add_argument("--exclude-mm", type=float, default=0.0, metavar="MM",
                   help="also exclude nodes within MM of a coupling/load patch edge from the "
                   "filtered peaks (default 0: one element layer only)")
    p.add_argument("--estimate-error", action="store_true",
                   help="solve a second mesh level and give a Richardson-type error estimate")
    p.add_argument("--no-beam", action="store_true", help="skip the beam model side by side")
    p.add_argument("--json", action="store_true", help="print the summary JSON instead of tables")
    p.add_argument("--out", default=None,
                   help="output directory (default reports/<variant>/static; with --set "
                   "reports/<variant>_set_<hash>/static)")
    add_set_option(p)
    p.set_defaults(handler=run)



def run(args) -> int:

    from shaftfe.util.atomic import staged_dir

    case = getattr(args, "case", None)
    if case is not None and args.rpm is not None:
        raise InputError("--case", "--rpm", "absent with --case (the case has its own rpm)",
                         got=args.rpm)
    if args.rpm is not None:
        parse_rpm_list(args.rpm)               # a bad --rpm before the variant is read
    variant = load_variant_from(args)
    if case is not None:
        from shaftfe.static.solve import _named_case
        rpms = [_named_case(variant, case).rpm]
    else:
        rpms = design_speeds(args.rpm, variant, first=True)
    check_speeds(rpms, args, variant)
    from shaftfe.static.model import StaticOptions, check_options
    check_options(StaticOptions(level=args.level, order=args.order,
                                load_distribution=args.load_distribution,
                                exclude_mm=args.exclude_mm, solver=args.solver))
    if args.model == "axisymmetric":
        return _run_axisymmetric(args, rpms, variant)
    if args.model == "zoned":
        return _run_zoned(args, rpms, variant)
    from shaftfe.static import cache as static_cache
    from shaftfe.static.solve import solve_static
    from shaftfe.util.units import REF_RPM

    opts = _options(args)
    out = _out(args, variant)
    from shaftfe.util.progress import Progress
    prog = Progress(["mesh + solve", "outputs"], enabled=False if args.json else None)
    with staged_dir(out, replaces=ZONE_FILES) as stage:     # every file or none
        with prog.stage("mesh + solve"):
            # with spin softening `shaftfe fatigue` also needs the unsoftened stress at
            # REF_RPM (its S0 (λ + β λ²)): recovered too when this run can be cached for it
            res = solve_static(variant, None if case else rpms, opts, case=case,
                               beam=not args.no_beam,
                               linear_stress=math.isclose(rpms[0], REF_RPM))
            if args.estimate_error:
                from shaftfe.static.error import with_error_estimate
                res = with_error_estimate(res, variant, opts)
            static_cache.store(variant, opts, res)   # `shaftfe fatigue` reuses it (if it can)
        with prog.stage("outputs"):
            from shaftfe.static.outputs import write_outputs
            summary = write_outputs(args.variant, variant, opts, res, rpms, stage)
    return _report(args, summary, lambda: (_print_overrides(variant),
                                           _print_tables(res, opts, out, _corners(variant),
                                                         _low_grooves(variant, opts))))


def _print_overrides(variant) -> None:
    """One line naming the --set values of this run (nothing without them)."""
    if variant.overrides:
        print("with --set " + ", ".join(f"{p}={v}" for p, v in variant.overrides))


def _report(args, summary: dict, show) -> int:
    """The command's output: summary.json on stdout with --json, else the text tables."""
    if args.json:
        print_json(summary)
    else:
        show()
    return 0


def _run_axisymmetric(args, rpms, variant) -> int:

    from shaftfe.axisymmetric.model import AxiOptions
    from shaftfe.axisymmetric.outputs import write_outputs
    from shaftfe.axisymmetric.solve import solve_axisymmetric
    from shaftfe.util.atomic import staged_dir
    for flag, bad in (("--order", args.order != 2), ("--body-force", args.body_force),
                      ("--estimate-error", args.estimate_error),
                      ("--solver", args.solver != "auto")):
        if bad:
            raise InputError(flag, flag, "not with --model axisymmetric (P2 harmonics, SuperLU, "
                             "no body force; the reference tables give its error)")
    opts = AxiOptions(level=args.level, rigid_supports=args.rigid_supports,
                      load_distribution=args.load_distribution,
                      seed_load_case=args.seed_load_case, exclude_mm=args.exclude_mm,
                      spin_softening=args.spin_softening)
    out = _out(args, variant)
    with staged_dir(out, replaces=ZONE_FILES) as stage:     # both files or none
        res = solve_axisymmetric(variant, rpms, opts, case=getattr(args, "case", None))
        summary = write_outputs(args.variant, variant, opts, res, rpms, stage)
    return _report(args, summary, lambda: (_print_overrides(variant),
                                           _print_axi(res, opts, out, _shoulders(variant))))


def _options(args):
    """The 3D options of the command line (the full 3D model's and the zoned one's)."""
    from shaftfe.static.model import StaticOptions
    return StaticOptions(level=args.level, order=args.order, rigid_supports=args.rigid_supports,
                         load_distribution=args.load_distribution, body_force=args.body_force,
                         seed_load_case=args.seed_load_case, solver=args.solver,
                         exclude_mm=args.exclude_mm, spin_softening=args.spin_softening)


def _out(args, variant):
    """--out, else reports/<variant>[_set_<hash>]/static."""
    from pathlib import Path
    return Path(args.out) if args.out else \
        Path("reports") / out_name(variant.name, variant.overrides) / "static"


def _run_zoned(args, rpms, variant) -> int:

    from shaftfe.util.atomic import staged_dir
    from shaftfe.zoned.outputs import write_outputs
    from shaftfe.zoned.solve import solve_zoned
    for flag, bad in (("--estimate-error", args.estimate_error),
                      ("--body-force", args.body_force)):
        if bad:
            raise InputError(flag, flag, "not with --model zoned (the default): use "
                             "--model solid")
    opts = _options(args)
    out = _out(args, variant)
    case = getattr(args, "case", None)
    with staged_dir(out, replaces=ZONE_FILES) as stage:     # every file or none
        res = solve_zoned(variant, rpms, opts, case=case)
        summary = write_outputs(args.variant, variant, opts, res, rpms, stage)
    return _report(args, summary, lambda: (_print_overrides(variant),
                                           _print_zoned(res, opts, out, _corners(variant))))


def _print_zoned(res, opts, out, corners=()) -> None:
    from shaftfe.solid.plan import SharpKeywayEdge, sharp_mark
    g = res.global_result
    print(f"variant {res.variant}: zoned — axisymmetric global ({g.n_nodes} meridian nodes, "
          f"harmonics n = 0..{g.harmonics[-1]}) + {len(res.zones)} 3D P{opts.order} submodel"
          f"{'s' if len(res.zones) != 1 else ''} at {opts.level} "
          f"({sum(z.n_dofs for z in res.zones)} dofs), "
          f"{'rigid supports' if opts.rigid_supports else 'bearing springs'}, "
          f"{res.run['total_seconds']:.2f} s")
    print(f"load case: {opts.load_case}")
    print_table(["zone", "features", "x mm", "cut at mm", "dofs", "cut check %", "grown"],
                [[z.name, ", ".join(z.features), f"{z.x_mm[0]:g} … {z.x_mm[1]:g}",
                  ", ".join(f"{x:g}" for x in z.cuts_mm) or "-", z.n_dofs,
                  max((100 * max(c.vm_diff_rel, c.sxx_diff_rel) for c in z.cut_checks),
                      default=0.0), z.grown] for z in res.zones])
    for c in res.cases:
        print()
        print_table(["bearing", "x mm", "|F| N", "L10h h"],
                    [[b.name, b.x_mm, b.F_radial_N, life(b.L10h)] for b in c.bearings],
                    title=f"{c.rpm:g} rpm, " + (f"case {c.case!r}" if c.case else
                                                opts.load_case) + ": bearing reactions "
                    "(global model)")
        _at_rest(c.rpm)
        print(f"equilibrium residual {c.equilibrium_residual:.1e}")
        print_table(["station", "x mm", "deflection µm"],
                    [r[:3] for r in _station_rows(c.stations, {})])
        rows = [[p.region, p.model, p.von_mises_MPa, p.max_principal_MPa, p.xyz_mm[0],
                 _bar(res.truth_error_bar_pct, p.region),
                 sharp_mark(corners if p.model != "axisymmetric" else
                            [c for c in corners if not isinstance(c, SharpKeywayEdge)],
                            p.xyz_mm)]
                for p in c.peaks if p.kind not in ("end", "seat", "bearing_seat")
                and p.region != "surface"]
        print_table(["region", "model", "von Mises MPa", "max principal MPa", "x mm",
                     "error vs truth %", "note"], rows)
    _print_bar_notes(res, f"the axisymmetric {res.axi_level} level's", zoned=True)
    for n in res.notes:
        print(f"note: {n}")
    print(f"\nwrote {out / 'result.vtu'}, the zones' zone_*.vtu, {out / 'summary.json'}")


def _print_axi(res, opts, out, corners=()) -> None:
    from shaftfe.solid.plan import sharp_mark
    print(f"variant {res.variant}: axisymmetric (Fourier harmonics n = 0..{res.harmonics[-1]}, "
          f"{len(res.harmonics)} solved), {opts.level}, {res.n_nodes} meridian nodes, "
          f"{'rigid supports' if opts.rigid_supports else 'bearing springs'}, "
          f"{res.run['total_seconds']:.2f} s")
    print(f"load case: {opts.load_case}")
    if opts.spin_softening:
        print("spin softening: on (the FE columns); the beam columns are without it")
    for c in res.cases:
        print()
        print_table(["bearing", "x mm", "|F| N", "L10h h"],
                    [[b.name, b.x_mm, b.F_radial_N, life(b.L10h)] for b in c.bearings],
                    title=f"{c.rpm:g} rpm, {opts.load_case}: bearing reactions")
        _at_rest(c.rpm)
        print(f"equilibrium residual {c.equilibrium_residual:.1e}")
        print_table(["station", "x mm", "deflection µm"],
                    [r[:3] for r in _station_rows(c.stations, {})])
        rows = [[p.region, p.von_mises_MPa, p.max_principal_MPa, p.xyz_mm[0], p.theta_deg,
                 "-" if p.fillet_angle_deg is None else p.fillet_angle_deg,
                 _bar(res.truth_error_bar_pct, p.region),
                 p.omitted_zone or "", sharp_mark(corners, p.xyz_mm)]
                for p in c.peaks if kind_of(p.region) not in SEAT_KINDS | {"end"}]
        print_table(["region", "von Mises MPa", "max principal MPa", "x mm", "θ deg",
                     "on fillet deg", "error vs truth %", "in the zone of", "note"], rows)
    _print_bar_notes(res, f"this axisymmetric level's ({opts.level_name})")
    for n in res.notes:
        print(f"note: {n}")
    print(f"\nwrote {out / 'result.vtu'}, {out / 'summary.json'}")


def _bar(bars: dict, region: str) -> str:
    """A peak's measured error bar as printed ("-" where none was measured)."""
    return f"{bars[region][0]:+.2f} … {bars[region][1]:+.2f}" if region in bars else "-"


def _print_bar_notes(res, whose: str, zoned: bool = False) -> None:
    """What the "error vs truth" column means, and why a notch has no bar."""
    if not (res.truth_error_bar_pct or res.truth_bar_notes):
        return
    print(f"error vs truth: {whose} measured error of span-fillet and groove peaks (von Mises "
          "and max principal) against the converged axisymmetric solution over a grid of "
          "shoulders and one of U grooves in bending (its own method refined: a discretisation "
          "bar; reports/benchmarks/bars_grid.md, groove_bars.md); none where it was not "
          "measured (end fillets, undercuts, a zone's other peaks, other options than the "
          "measured ones, a notch outside the measured grid, a fillet or groove under an axial "
          "force or torque)")
    if zoned and any(kind_of(r) in ("keyway", "cross_hole") for r in res.truth_error_bar_pct):
        print("  a zone's rounded keyway or cross hole: the zone level's measured error against "
              "the full 3D model at a finer level (keyways: fine; cross holes: fine × 0.7) over "
              "a grid of keyways and one of cross holes (reports/benchmarks/zone_bars.md)")
    for region, why in res.truth_bar_notes.items():
        print(f"  {region}: {why}")


def _at_rest(rpm: float) -> None:
    """A 0 rpm case is exactly zero: say so once above its tables."""
    if rpm == 0:
        from shaftfe.beam.solve import AT_REST_NOTE
        print(f"note: {AT_REST_NOTE}")


def _shoulders(variant) -> tuple:
    """The sharp shoulder corners alone (the axisymmetric model has no keyway)."""
    from shaftfe.solid.plan import sharp_corners
    return sharp_corners(variant)


def _corners(variant) -> tuple:
    """What a printed peak may sit on and be no converged stress: the sharp shoulder corners
    and the keyways' sharp bottom edges (``solid.plan.sharp_mark``)."""
    from shaftfe.solid.plan import sharp_corners, sharp_keyway_edges
    return (*sharp_corners(variant), *sharp_keyway_edges(variant))


def _low_grooves(variant, opts) -> frozenset[str]:
    """The regions of the grooves the 3D mesh does not resolve (their peaks read low;
    ``solid.mesh.unresolved_grooves``, warned by the solve)."""
    from shaftfe.solid.features import groove_region
    from shaftfe.solid.mesh import unresolved_grooves
    return frozenset(groove_region(g.segment, g.index)
                     for g in unresolved_grooves(variant, opts.level))


def _whole_mark(corners) -> str:
    """The whole-shaft peak's mark: not the shaft's maximum when a corner is singular (a
    sharp shoulder: unbounded; a keyway edge only marks a peak on it)."""
    from shaftfe.solid.plan import SharpCorner
    corners = [c for c in corners if isinstance(c, SharpCorner)]
    if not corners:
        return ""
    return "not bounded: sharp corner " + ", ".join(c.region for c in corners)


def _print_tables(res, opts, out, corners=(), low=frozenset()) -> None:
    from shaftfe.solid.plan import sharp_mark
    from shaftfe.static.result import PEAK_FIT_LABEL
    d = res.diagnostics
    print(f"variant {res.variant}: P{opts.order} {opts.level}, {res.n_dofs} dofs, "
          f"{'rigid supports' if opts.rigid_supports else 'bearing springs'}, solver "
          f"{d['solver']}, {res.run['total_seconds']:.1f} s")
    print(f"load case: {opts.load_case}" + (f"; case {res.case_name!r}" if res.case_name
                                             else ""))
    print("load patterns (one solve each): " + ", ".join(
        f"{p['key']} ({', '.join(p['loads']) or 'none'})" for p in res.patterns))
    if "twist_gauge_torque_rel" in d:
        print(f"torsion: no bearing holds torsion; the rotation about the axis is a gauge whose "
              f"reaction is {d['twist_gauge_torque_rel']:.1e} of the applied torques")
    for c in res.cases:
        print()
        rows = []
        beam_b = {b["name"]: b for b in (c.beam or {}).get("bearings", [])}
        torque = any(b.Mx_Nmm is not None for b in c.bearings)
        for b in c.bearings:
            bb = beam_b.get(b.name, {})
            rows.append([b.name, b.x_mm, b.F_radial_N, bb.get("F_N", "-"),
                         life(b.L10h), life(bb.get("L10h")) if bb else "-"]
                        + ([b.Fx_N, "-" if b.Mx_Nmm is None else b.Mx_Nmm] if torque else []))
        title = f"{c.rpm:g} rpm, " + (f"case {c.case!r}" if c.case else opts.load_case)
        print_table(["bearing", "x mm", "|F| N (FE)", "|F| N (beam)", "L10h h (FE)",
                     "L10h h (beam)"] + (["Fx N", "torque N·mm"] if torque else []), rows,
                    title=f"{title}: bearing reactions")
        if (c.beam or {}).get("error"):
            print(f"beam: {c.beam['error']}")
        _at_rest(c.rpm if all(p["scales_with"] == "rpm2" for p in res.patterns) else None)
        print(f"equilibrium residual {c.equilibrium_residual:.1e}")
        beam_st = (c.beam or {}).get("stations", {})
        rows = _station_rows(c.stations, beam_st)
        rows.append(["max (nodal |u_yz|)", c.max_deflection_xyz_mm[0], c.max_deflection_mm * 1e3,
                     (c.beam or {}).get("max_deflection_mm", float("nan")) * 1e3
                     if (c.beam or {}).get("max_deflection_mm") is not None else "-"])
        print_table(["station", "x mm", "deflection µm (FE)", "µm (beam)"], rows)
        bars = res.truth_error_bar_pct
        unresolved = {*res.unresolved_fillets,
                      *(shoulder_region(segment_of(r)) for r in res.unresolved_fillets)}
        rows = [[p.region, p.von_mises_MPa, p.max_principal_MPa, p.xyz_mm[0],
                 p.von_mises_unfiltered_MPa, _bar(bars, p.region),
                 "fillet not resolved: not a stress" if p.region in unresolved
                 else "groove not resolved: reads low (see its warning)" if p.region in low
                 else sharp_mark(corners, p.xyz_mm)]
                for p in c.peaks if kind_of(p.region) != "end"]
        rows.append(["whole shaft", c.peak_von_mises_MPa, "-", c.peak_von_mises_xyz_mm[0],
                     c.peak_von_mises_unfiltered_MPa, "-",
                     _whole_mark(corners) or sharp_mark(corners, c.peak_von_mises_xyz_mm)
                     or ("not bounded: a fillet not resolved" if unresolved else "")])
        print_table(["region", "von Mises MPa", "max principal MPa", "x mm",
                     "unfiltered MPa", "error vs truth %", "note"], rows)
        print(f"peaks: the {PEAK_FIT_LABEL} (result.vtu, `shaftfe view` and the pictures hold "
              "nodal values, which can read slightly lower)")
    if res.truth_error_bar_pct or res.truth_bar_notes:
        print("error vs truth: this level's measured error of fillet and groove peaks (von "
              "Mises and max principal) against the converged axisymmetric solution over a grid "
              "of shoulders and one of U grooves (reports/benchmarks/bars_grid.md, "
              "groove_bars.md); none where it was not measured (end fillets, undercuts, notches "
              "in a keyway's, cross hole's or hex socket's zone, other options than the "
              "measured ones, a notch's geometry outside the measured grid, an axial force or "
              "torque)")
    for region, why in res.truth_bar_notes.items():
        print(f"  {region}: {why}")
    if res.error_estimate:
        ee = res.error_estimate
        print(f"\nerror estimate (levels {ee['levels'][0]} vs {ee['levels'][1]}, "
              f"Richardson-type):")
        for c in ee["cases"]:
            for key, unit in (("peak_von_mises", "MPa"), ("max_deflection", "mm")):
                e = c[key]
                if e:
                    print(f"  {c['rpm']:g} rpm {key}: {e['fine']:.4g} {unit} ± "
                          f"{e['error_fine']:.2g} (extrapolated {e['extrapolated']:.4g})")
    print(f"\nwrote {out / 'result.vtu'}, {out / 'summary.json'}, {out / 'deflection.png'}")


def _station_rows(stations, beam_st: dict) -> list[list]:
    """One row per position: stations at the same x (the gear and counterweight 1 share a
    seat) are one row with both names."""
    rows: dict[float, list] = {}
    for s in stations:
        key = round(s.x_mm, 6)
        if key in rows:
            rows[key][0] += f" + {s.name}"
        else:
            rows[key] = [s.name, s.x_mm, s.u_mm * 1e3, _beam_station(beam_st, s.name)]
    return list(rows.values())


def _beam_station(st: dict, name: str) -> object:
    key = name.split(":", 1)[1] if ":" in name else name
    v = st.get(key, st.get(name))
    return v * 1e3 if isinstance(v, float) else "-"
