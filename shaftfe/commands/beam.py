"""`shaftfe beam`: stepped Timoshenko beam model of a variant (fast static cross-check).

Stdlib only at module level; numpy/scipy (shaftfe.beam.model) and matplotlib inside the handler.
"""

from __future__ import annotations

from shaftfe.errors import InputError


def register(sub) -> None:
    p = sub.add_parser(
        "beam", help="Timoshenko beam check of a variant: reactions, deflection, stress, L10h",
        description="Stepped Timoshenko beam model of a balancer-shaft variant: bearing "
        "reactions and L10h, deflection line and at the named stations, nominal von Mises stress "
        "and Kt-based notch estimates at the shoulders (bending, tension, torsion); axial force "
        "and torque along the shaft where the loads carry them. Every load of the variant "
        "(parts' m e ω² at their centroids, [[loads]]) at --rpm (rpm² loads × (rpm/ref)², "
        "constant loads × 1) or in the named --case.")
    p.add_argument("--variant", required=True, help="variant name, e.g. x2_57")
    p.add_argument("--rpm", default=None, help="speed(s) in rpm, comma-separated (default: "
                   "the first of the variant's [duty] design_speeds_rpm), e.g. 10000,7000")
    from shaftfe.commands._common import add_engine_option
    add_engine_option(p)
    p.add_argument("--rigid-supports", action="store_true",
                   help="simple supports at the bearing centres (Inventor shaft module) "
                   "instead of the bearing spring matrices")
    p.add_argument("--max-element", type=float, default=5.0, metavar="MM",
                   help="maximum element length in mm (default 5)")
    p.add_argument("--spread-loads", action="store_true",
                   help="spread each attachment force uniformly over its seat "
                   "(default: point load at the seat centre)")
    p.add_argument("--seed-load-case", action="store_true",
                   help="the seed's load case: only the parts the seed loaded (gear, "
                   "counterweights 1 and 2), each at its seat centre with no moment; default: "
                   "every load, each part's force at its centroid")
    p.add_argument("--case", metavar="NAME[,NAME]",
                   help="solve the variant's [[load_cases]] of these names instead of --rpm")
    p.add_argument("--no-shear", action="store_true",
                   help="Euler-Bernoulli limit (no shear deformation), for comparison")
    p.add_argument("--kt-fit", choices=("roark", "peterson"), default="roark",
                   help="stress-concentration fit for the shoulders (default roark)")
    p.add_argument("--json", action="store_true", help="print JSON instead of tables")
    p.add_argument("--plot", metavar="PATH", help="write a deflection/stress plot (png, pdf, svg)")
    from shaftfe.commands._common import add_set_option
    add_set_option(p)
    p.set_defaults(handler=run)



def run(args) -> int:
    from shaftfe.commands._common import (
        check_speeds,
        design_speeds,
        load_variant_from,
        parse_rpm_list,
        print_json,
        print_table,
        write_atomic,
    )
    from shaftfe.util.fmt import life
    if args.rpm is not None:
        parse_rpm_list(args.rpm)               # a bad --rpm before the variant is read
    variant = load_variant_from(args)
    rpms = design_speeds(args.rpm, variant, first=True)
    check_speeds(rpms, args, variant)
    from shaftfe.util.limits import check_max_element
    check_max_element(args.max_element)
    plot_fmt = None
    if args.plot:
        from shaftfe.util.atomic import PLOT_SUFFIXES, check_output_file
        plot_fmt = check_output_file(args.plot, "--plot", PLOT_SUFFIXES).suffix[1:].lower()

    from shaftfe.beam.model import build_model
    from shaftfe.beam.solve import solve, solve_cases
    from shaftfe.util.notices import collected

    cases = _cases(variant, args.case)
    if args.seed_load_case:
        variant = variant.with_seed_load_case()
    model = build_model(variant, rigid_supports=args.rigid_supports,
                        max_element_mm=args.max_element, spread_loads=args.spread_loads,
                        kt_fit=args.kt_fit, shear_deformation=not args.no_shear,
                        seed_placement=args.seed_load_case)
    results = solve_cases(model, cases) if cases else solve(model, rpms)

    if args.plot:
        from shaftfe.beam.plots import plot_results
        write_atomic(args.plot, plot_results(results, plot_fmt))
    if args.json:
        print_json({"variant": variant.name, "overrides": variant.overrides_map,
                    "supports": "rigid" if args.rigid_supports else "springs",
                    "load_case": "seed" if args.seed_load_case else "all loads",
                    "shear_deformation": not args.no_shear, "n_nodes": model.n_nodes,
                    "results": [r.to_dict() for r in results], "warnings": collected()})
        return 0
    sup = "rigid simple supports" if args.rigid_supports else "bearing springs"
    kind = "Euler-Bernoulli" if args.no_shear else "Timoshenko"
    case = "seed load case" if args.seed_load_case else "all loads"
    print(f"variant {variant.name}: {kind} beam, {model.n_nodes} nodes, {sup}, {case}, "
          f"loads {'spread over their bands' if args.spread_loads else 'at their points'}")
    for r in results:
        print()
        axial = any(b.Fx_N for b in r.bearings)
        print_table(["bearing", "x mm", "Fy N", "Fz N", "|F| N"] + ["Fx N"] * axial
                    + ["L10h h"],
                    [[b.name, f"{b.x_mm:.2f}", f"{b.Fy_N:.1f}", f"{b.Fz_N:.1f}", f"{b.F_N:.1f}"]
                     + [f"{b.Fx_N:.1f}"] * axial + [life(b.L10h)] for b in r.bearings],
                    title=f"-- {_label(r)}: reactions on the shaft")
        print_table(["station", "x mm", "uy mm", "uz mm", "|u| mm"],
                    [[k, f"{s.x_mm:.2f}", f"{s.uy_mm:.5f}", f"{s.uz_mm:.5f}", f"{s.u_mm:.5f}"]
                     for k, s in r.stations.items()],
                    title="deflection")
        tens, tors = r.max_abs("N") > 0, r.max_abs("T") > 0
        if r.notches:
            mixed = any(n.kind != "shoulder" for n in r.notches)
            print_table(["notch"] * mixed + ["shoulder x mm" if not mixed else "x mm",
                                             "D/d mm", "r mm", "Kt"] + ["Kt_N"] * tens
                        + ["Kt_T"] * tors + ["sigma_nom MPa", "peak MPa", "note"],
                        [[n.name or "shoulder"] * mixed
                         + [f"{n.x_mm:.2f}", f"{n.D_mm:g}/{n.d_mm:g}", f"{n.r_mm:g}",
                          f"{n.kt:.3f}"] + [f"{n.kt_tension:.3f}"] * tens
                         + [f"{n.kt_torsion:.3f}"] * tors
                         + [f"{n.sigma_nom_MPa:.1f}", f"{n.sigma_peak_MPa:.1f}", n.kt_note]
                         for n in r.notches],
                        title="notches (von Mises on the notch's section: a shoulder's "
                        "smaller diameter, a groove's bottom, a hole's net section; nominal "
                        "and with Kt)" if mixed else "shoulders (von Mises on the smaller "
                        "diameter, nominal and with Kt)")
        if tens or tors:
            print(f"axial force max |N| {r.max_abs('N'):.4g} N (max |N/A| "
                  f"{r.max_abs('sigma_N'):.4g} MPa); torque max |T| {r.max_abs('T'):.4g} N·mm "
                  f"(max tau {r.max_abs('tau'):.4g} MPa)")
        for note in r.notes:
            if note not in model.notes:
                print(f"note: {note}")
        print(f"max deflection {r.max_deflection_mm:.4g} mm; max nominal von Mises "
              f"{r.max_sigma_vm_MPa:.4g} MPa at x = {r.x_max_sigma_vm_mm:.4g} mm; with Kt "
              f"{r.max_peak_MPa:.4g} MPa at x = {r.x_max_peak_mm:.4g} mm")
    for note in model.notes:
        print(f"note: {note}")
    if args.plot:
        print(f"wrote {args.plot}")
    return 0


def _label(r) -> str:
    return f"case {r.case} ({r.rpm:g} rpm)" if r.case else f"{r.rpm:g} rpm"


def _cases(variant, names: str | None) -> tuple:
    """The variant's load cases named in ``--case`` (InputError naming the known ones)."""
    if not names:
        return ()
    known = {c.name: c for c in variant.load_cases}
    out = []
    for nm in (n.strip() for n in names.split(",")):
        if nm not in known:
            raise InputError("--case", "--case", "a [[load_cases]] name of the variant: "
                             + (", ".join(known) or "(it has none)"), got=nm)
        out.append(known[nm])
    return tuple(out)
