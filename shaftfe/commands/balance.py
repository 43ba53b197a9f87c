"""`shaftfe balance ...`: crank-mechanism balancing (SPEC.md §1). Numpy imported in handlers.

Single cylinder (this module): ``forces``, ``sweep``, ``ratios``. Ratios X, X2 are percent on
the command line (fractions in the Python API).
"""

from __future__ import annotations

import math

from shaftfe.errors import InputError


def register(sub) -> None:
    p = sub.add_parser("balance", help="crank-mechanism shaking forces and balance ratios")
    bsub = p.add_subparsers(dest="balance_command", metavar="SUBCOMMAND")
    p.set_defaults(handler=lambda args: p.print_help() or 2)
    register_single(bsub)
    from shaftfe.commands import balance_multi

    balance_multi.register(bsub)


def register_single(bsub) -> None:
    """forces / sweep / ratios (single cylinder, seed 000 ch. 5 and seed 003)."""
    f = bsub.add_parser("forces", help="shaking forces over one revolution and their peaks")
    _engine_opts(f)
    f.add_argument("--x", type=float, metavar="PCT",
                   help="crank balance ratio X [%%] (default: from the engine file)")
    f.add_argument("--x2", type=float, metavar="PCT",
                   help="balancer balance ratio X2 [%%] (default: from the engine file, else 0)")
    f.add_argument("--start-deg", type=float, default=0.0, metavar="DEG",
                   help="crank angle of the first sample, from TDC (default 0)")
    f.add_argument("--csv", metavar="PATH", help="write angle, Fx, Fy, |F| samples as CSV")
    f.add_argument("--plot", metavar="PATH",
                   help="force components, polar |F| and Fy(Fx) (.png/.pdf/.svg)")
    f.set_defaults(handler=_forces)

    s = bsub.add_parser("sweep", help="metrics over an X2 range (mode 1) or X and X2 ranges "
                        "(mode 2: per X the minimum of each metric and its X2)")
    _engine_opts(s)
    s.add_argument("--x", metavar="RANGE",
                   help="X [%%]: a value (mode 1) or a:b[:step] (mode 2, step default 1); "
                   "default: from the engine file")
    s.add_argument("--x2", metavar="RANGE", default="0:100:1",
                   help="X2 range a:b[:step] [%%] (default 0:100:1)")
    s.add_argument("--csv", metavar="PATH",
                   help="mode 1: the curves over X2; mode 2: the table of minima")
    s.add_argument("--plot", metavar="PATH", help="sweep curves (.png/.pdf/.svg)")
    s.set_defaults(handler=_sweep)

    r = bsub.add_parser("ratios", help="balance ratios P = X + X2 and Pv = X2/X from parts "
                        "(seed 003)")
    r.add_argument("--engine", default="vm450", metavar="NAME|PATH",
                   help="engine name in geometry/engines or a .toml path (default vm450)")
    r.add_argument("--json", action="store_true", help="machine-readable output")
    r.set_defaults(handler=_ratios)


def _engine_opts(p) -> None:
    p.add_argument("--engine", default="vm450", metavar="NAME|PATH",
                   help="engine name in geometry/engines or a .toml path (default vm450)")
    p.add_argument("--rpm", type=float, help="crank speed [rpm] (default: the file's rpm)")
    p.add_argument("--tilt-deg", type=float, metavar="DEG",
                   help="cylinder tilt beta [deg] (default: the file's tilt_deg; 0 = metrics in "
                   "the cylinder frame, as in the seed's sweep table)")
    p.add_argument("--crank-mass-kg", type=float, metavar="KG",
                   help="override: crank compensation mass m_C (with --crank-radius-mm)")
    p.add_argument("--crank-radius-mm", type=float, metavar="MM", help="override: its radius")
    p.add_argument("--balancer-mass-kg", type=float, metavar="KG",
                   help="override: balancer mass m_vh (with --balancer-radius-mm)")
    p.add_argument("--balancer-radius-mm", type=float, metavar="MM",
                   help="override: its eccentricity gamma2")
    p.add_argument("--sampling", choices=("period", "seed_inclusive"), default="period",
                   help="period: N samples without the end point, exact RMS (default); "
                   "seed_inclusive: 0..360 deg inclusive like the seed's script")
    p.add_argument("--samples", type=int, metavar="N",
                   help="angle steps per revolution (default 3600 period, 360 seed_inclusive)")
    p.add_argument("--json", action="store_true", help="machine-readable output")


# ----------------------------------------------------------------------------- helpers
def _finite(value, option: str, allowed: str, ok) -> None:
    if value is not None and (not math.isfinite(value) or not ok(value)):
        raise InputError(option, option.lstrip("-"), allowed, got=value)


def _load(args):
    """Engine from --engine with the mass/radius overrides applied and validated."""
    import dataclasses

    from shaftfe.balance.engines import load_engine

    if args.rpm is not None:
        from shaftfe.util.limits import check_rpm
        check_rpm(args.rpm, "--rpm", positive=True)
    _finite(args.tilt_deg, "--tilt-deg", "in [-180, 180]", lambda v: -180 <= v <= 180)
    eng = load_engine(args.engine)
    for m_opt, r_opt, m_field, r_field in (
            ("--crank-mass-kg", "--crank-radius-mm", "compensation_mass_kg",
             "compensation_radius_mm"),
            ("--balancer-mass-kg", "--balancer-radius-mm", "balancer_mass_kg",
             "balancer_radius_mm")):
        m = getattr(args, m_opt[2:].replace("-", "_"))
        r = getattr(args, r_opt[2:].replace("-", "_"))
        if m is None and r is None:
            continue
        if m is None or r is None:
            missing = m_opt if m is None else r_opt
            raise InputError(missing, missing.lstrip("-"),
                             f"given together with {r_opt if m is None else m_opt}",
                             reason="is missing")
        _finite(m, m_opt, ">= 0", lambda v: v >= 0)
        _finite(r, r_opt, ">= 0", lambda v: v >= 0)
        kw = {m_field: m, r_field: r}
        if m_field == "compensation_mass_kg":
            kw["X_given"] = None
        else:
            kw["X2_given"] = None
        eng = dataclasses.replace(eng, **kw)
    return eng


def _ratio_arg(value: float | None, option: str, conflicts: bool) -> float | None:
    if value is None:
        return None
    if conflicts:
        other = "--crank-mass-kg" if option == "--x" else "--balancer-mass-kg"
        raise InputError(option, option.lstrip("-"), f"either {option} or {other}, not both",
                         got=value)
    _finite(value, option, "in [0, 200] %", lambda v: 0 <= v <= 200)
    return value / 100.0


def _csv(path: str, header: list[str], rows) -> None:
    from shaftfe.commands._common import write_atomic

    lines = [",".join(header)]
    lines += [",".join(f"{v:.10g}" for v in row) for row in rows]
    write_atomic(path, "\n".join(lines) + "\n")


def _check_out(path: str | None, option: str, suffixes: tuple[str, ...] | None = None) -> None:
    """``util.atomic.check_output_file`` (``suffixes``: a figure's by default)."""
    from shaftfe.util.atomic import PLOT_SUFFIXES, check_output_file
    check_output_file(path, option, PLOT_SUFFIXES if suffixes is None else suffixes)


# ----------------------------------------------------------------------------- handlers
def _forces(args) -> int:
    from shaftfe.balance.single import forces
    from shaftfe.commands._common import print_json, print_table

    _check_out(args.plot, "--plot")
    _check_out(args.csv, "--csv", (".csv",))
    _finite(args.start_deg, "--start-deg", "a finite angle", lambda v: True)
    X = _ratio_arg(args.x, "--x", args.crank_mass_kg is not None)
    X2 = _ratio_arg(args.x2, "--x2", args.balancer_mass_kg is not None)
    eng = _load(args)
    res = forces(eng, X, X2, args.rpm, tilt_deg=args.tilt_deg, start_deg=args.start_deg,
                 sampling=args.sampling, n=args.samples)
    m = res.metrics
    if args.plot:                   # the plot first: it is the step that can still fail
        from shaftfe.balance.plots import plot_forces

        plot_forces(res, args.plot)
    if args.csv:
        import numpy as np

        _csv(args.csv, ["alpha_deg", "Fx_N", "Fy_N", "F_N", "Fx_crank_N", "Fy_crank_N"],
             np.column_stack([res.alpha_deg, res.Fx, res.Fy, res.F, res.Fx_crank,
                              res.Fy_crank]))
    if args.json:
        print_json({**res.summary(eng), "csv": args.csv, "plot": args.plot})
        return 0
    print(f"{eng.name} ({eng.source}): X = {100 * res.X:.2f} %, X2 = {100 * res.X2:.2f} %, "
          f"{res.rpm:g} rpm, tilt {res.tilt_deg:g} deg, m_pos = {eng.m_pos_kg:.6g} kg, "
          f"m_rot = {eng.m_rot_kg:.6g} kg, A = m_pos R w^2 = {res.first_order_amplitude:.1f} N")
    fvk, fvk_deg = res.max_crank_force
    print_table(["metric", "value [N]", "at crank angle [deg]"], [
        ["max|Fx|", round(m.max_abs_fx, 1), round(m.max_abs_fx_deg, 2)],
        ["max|Fy|", round(m.max_abs_fy, 1), round(m.max_abs_fy_deg, 2)],
        ["RMS|F|", round(m.rms_f, 1), "-"],
        ["max|F|", round(m.max_f, 1), round(m.max_f_deg, 2)],
        ["max|F_vk| (crank alone)", round(fvk, 1), round(fvk_deg, 2)],
        ["balancer force X2*A", round(res.X2 * res.first_order_amplitude, 1), "-"],
    ])
    for what, path in (("samples", args.csv), ("plot", args.plot)):
        if path:
            print(f"{what} written to {path}")
    return 0


def _sweep(args) -> int:
    import numpy as np

    from shaftfe.balance.sweep import METRICS, percent_grid, sweep
    from shaftfe.commands._common import parse_range, print_json, print_table

    _check_out(args.plot, "--plot")
    _check_out(args.csv, "--csv", (".csv",))
    x2 = percent_grid(*parse_range(args.x2, "--x2", lo=0, hi=200), "--x2")
    if args.x is not None:
        if args.crank_mass_kg is not None:
            raise InputError("--x", "x", "either --x or --crank-mass-kg, not both", got=args.x)
        x = percent_grid(*parse_range(args.x, "--x", lo=0, hi=200), "--x")
        eng = _load(args)
    else:
        eng = _load(args)
        if eng.X is None:
            raise InputError(eng.source, "compensation_mass_kg",
                             "crank data in the file or --x", reason="is missing")
        _finite(100 * eng.X, "--x", "in [0, 200] % (X from the engine file)",
                lambda v: 0 <= v <= 200)
        x = np.array([100 * eng.X])
    res = sweep(eng, x / 100, x2 / 100, args.rpm, tilt_deg=args.tilt_deg,
                sampling=args.sampling, n=args.samples)
    mode = res.mode
    mins = res.minima()
    names = {"max_abs_fx": "max|Fx|", "max_abs_fy": "max|Fy|", "rms_f": "RMS|F|",
             "max_f": "max|F|"}
    if args.plot:                   # the plot first: it is the step that can still fail
        from shaftfe.balance.plots import plot_sweep

        plot_sweep(res, args.plot)
    if args.csv:
        if mode == 1:
            _csv(args.csv, ["X2_percent", *[f"{k}_N" for k in METRICS]],
                 np.column_stack([100 * res.X2, *[getattr(res, k)[0] for k in METRICS]]))
        else:
            cols = [100 * res.X]
            for k in METRICS:
                cols += [mins[k][0], 100 * mins[k][1]]
            _csv(args.csv, ["X_percent", *[h for k in METRICS
                                           for h in (f"min_{k}_N", f"X2_at_min_{k}_percent")]],
                 np.column_stack(cols))
    if args.json:
        print_json({**res.summary(eng), "csv": args.csv, "plot": args.plot})
        return 0
    print(f"{eng.name}: mode {mode}, {res.rpm:g} rpm, tilt {res.tilt_deg:g} deg, "
          f"{res.sampling} sampling with {res.n_angles} angles, "
          f"X2 {100 * res.X2[0]:g}..{100 * res.X2[-1]:g} % ({res.X2.size} values)")
    if mode == 1:
        print_table(["X2 [%]", *[f"{names[k]} [N]" for k in METRICS]],
                    [[round(100 * v, 4), *[round(float(getattr(res, k)[0, j]), 1)
                                           for k in METRICS]]
                     for j, v in enumerate(res.X2)])
        print()
    print_table(["X [%]", *[f"min {names[k]} [N] @ X2 [%]" for k in METRICS]],
                [[round(100 * xv, 4), *[f"{mins[k][0][i]:.1f} @ {100 * mins[k][1][i]:g}"
                                        for k in METRICS]] for i, xv in enumerate(res.X)],
                title="minimum over X2 of each metric:")
    for what, path in (("table", args.csv), ("plot", args.plot)):
        if path:
            print(f"{what} written to {path}")
    return 0


def _ratios(args) -> int:
    from shaftfe.balance.engines import load_engine
    from shaftfe.balance.parts import ratios
    from shaftfe.commands._common import print_json, print_table

    eng = load_engine(args.engine)
    r = ratios(eng)
    if args.json:
        print_json(r.summary(eng.source))
        return 0
    rows = [["rod rotating share m_or (+ bearing) [g]", round(1000 * r.m_rod_rot_kg, 2)],
            ["rod reciprocating share m_op [g]", round(1000 * r.m_rod_pos_kg, 2)],
            ["reciprocating mass m_p + m_op [g]", round(1000 * r.m_pos_kg, 2)]]
    if r.m_r_kg is not None:
        rows += [["crank rotating mass m_r [g]", round(1000 * r.m_r_kg, 2)],
                 ["its centroid r_r [mm]", round(r.r_r_mm, 3)]]
    rows += [["crank static moment [kg mm]", round(r.crank_moment_kg_mm, 4)],
             ["balancer static moment [kg mm]", round(r.balancer_moment_kg_mm, 4)],
             ["X (crank) [%]", round(100 * r.X, 2)],
             ["X2 (balancer) [%]", round(100 * r.X2, 2)],
             ["P = X + X2 [%]", round(100 * r.P, 2)],
             ["Pv = X2 / X [%]", "-" if r.Pv is None else round(100 * r.Pv, 2)]]
    print_table(["quantity", "value"], rows, title=f"{eng.name} ({eng.source})")
    return 0
