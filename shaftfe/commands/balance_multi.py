"""`shaftfe balance twin|inline`: several cylinders (seed 000 §4.3, ch. 7; SPEC.md §1).

Every cylinder gets the engine file's R, T1 and m_pos; the file's X, X2 and tilt_deg (a
single-cylinder crank, balancer and installation angle) are not used: the engine frame has the
V bisector (or the inline cylinders) vertical, and the counterweights follow the layout (see
``shaftfe.balance.multi``).

Stdlib only at module level; numpy and matplotlib are imported inside the handlers.
"""

from __future__ import annotations

import argparse
import math

from shaftfe.commands._common import print_json, print_table, write_atomic
from shaftfe.errors import InputError
from shaftfe.util import units
from shaftfe.util.limits import check_rpm


def register(bsub) -> None:
    """Add the multi-cylinder subcommands to the `balance` group."""
    t = bsub.add_parser(
        "twin", help="two-cylinder engine (V, inline, boxer): resultant force by order",
        description="Two cylinders at an angle delta with crank-pin offset epsilon (seed 000 "
        "ch. 7): cylinder 1 tilted delta/2, cylinder 2 -delta/2, alpha02 = alpha01 - delta - "
        "epsilon. Defaults cancel the 1st order: epsilon = 180 - 2 delta, a 50 %% "
        "counterweight opposite each pin (resultant 100 sin(delta) %% of one cylinder, the "
        "seed's X); --shared-pin: one pin, one 100 %% counterweight.")
    _common_args(t)
    t.add_argument("--delta", type=float, required=True, metavar="DEG",
                   help="angle between the cylinders, 0 (inline) .. 180 (boxer)")
    t.add_argument("--epsilon", type=float, default=None, metavar="DEG",
                   help="crank-pin offset, pin 2 trailing pin 1 (default 180 - 2 delta)")
    t.add_argument("--shared-pin", action="store_true",
                   help="both rods on one pin: epsilon = 0, cylinder 2's counterweight removed")
    t.add_argument("--x", default=None, metavar="PCT[,PCT]",
                   help="counterweight opposite each pin in %% of m_pos R: one value for both "
                   "or 'X1,X2' (default 50,50; with --shared-pin one value, default 100)")
    t.add_argument("--offset-mm", type=float, default=0.0, metavar="MM",
                   help="axial distance between the two cylinders for the couple (default 0)")
    t.set_defaults(handler=_run_twin)

    i = bsub.add_parser(
        "inline", help="N-cylinder inline engine: resultant force and couple by order",
        description="Upright inline engine: crank-pin (TDC) angles and axial spacing; reports "
        "the resultant force and the couple about the transverse (Mx, pitch) and vertical "
        "(My, yaw) axes through the middle of the cylinder row, split into orders by FFT.")
    _common_args(i)
    i.add_argument("--pins", required=True, metavar="DEG,DEG,...",
                   help="crank angle at which each cylinder is at TDC, e.g. 0,120,240")
    i.add_argument("--spacing-mm", required=True, metavar="MM[,MM...]",
                   help="cylinder spacing: one value (equal) or N-1 gaps")
    i.add_argument("--x", default=None, metavar="PCT[,PCT...]",
                   help="counterweight opposite each pin in %% of m_pos R: one value or one "
                   "per cylinder (default 0)")
    i.set_defaults(handler=_run_inline)


def _common_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("--engine", default="vm450",
                   help="engine file name under geometry/engines/ or a path (default vm450); "
                   "supplies R, T1, m_pos and the default rpm for every cylinder")
    p.add_argument("--radius-mm", type=float, default=None, help="override crank radius R")
    p.add_argument("--rod-mm", type=float, default=None, help="override rod length T1")
    p.add_argument("--m-pos-kg", type=float, default=None,
                   help="override the reciprocating mass per cylinder")
    p.add_argument("--rpm", type=float, default=None, help="speed (default: the engine's rpm)")
    p.add_argument("--samples", type=int, default=720,
                   help="samples per revolution for the FFT (default 720)")
    p.add_argument("--orders", default="1,2,4,6", metavar="K,K,...",
                   help="harmonic orders to report (default 1,2,4,6)")
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")
    p.add_argument("--plot", default=None, metavar="PATH",
                   help="write a figure (.png, .pdf or .svg)")


# --- parsing helpers ------------------------------------------------------------------------

def parse_floats(text: str, option: str) -> list[float]:
    """'a,b,c' → floats; anything malformed → InputError naming the option."""
    allowed = "comma-separated finite numbers, e.g. 0,120,240"
    parts = [s.strip() for s in str(text).split(",")]
    try:
        vals = [float(s) for s in parts]
    except ValueError:
        raise InputError(option, option.lstrip("-"), allowed, got=text) from None
    if not vals or not all(math.isfinite(v) for v in vals):
        raise InputError(option, option.lstrip("-"), allowed, got=text)
    return vals


def _parse_orders(text: str, samples: int) -> list[int]:
    """'1,2,4' → the orders (their range: ``balance.multi.check_orders``)."""
    from shaftfe.balance.multi import check_orders
    try:
        ks = [int(s.strip()) for s in str(text).split(",")]
    except ValueError:
        raise InputError("--orders", "orders", "comma-separated integers", got=text) from None
    return sorted(set(check_orders(ks, samples)))


def _setup(args):
    """Mechanism, omega, rpm, engine label, orders — all validated before any output (their
    rules: ``balance.multi``)."""
    from shaftfe.balance.multi import check_samples, mechanism

    check_samples(args.samples)
    orders = _parse_orders(args.orders, args.samples)
    from shaftfe.util.atomic import PLOT_SUFFIXES, check_output_file
    check_output_file(args.plot, "--plot", PLOT_SUFFIXES)
    from shaftfe.balance.engines import load_engine

    eng = load_engine(args.engine)
    R = args.radius_mm if args.radius_mm is not None else eng.crank_radius_mm
    T1 = args.rod_mm if args.rod_mm is not None else eng.rod_length_mm
    m_pos = args.m_pos_kg if args.m_pos_kg is not None else eng.m_pos_kg
    if args.rpm is not None:
        check_rpm(args.rpm, "--rpm", positive=True)    # the one speed ceiling (``util.limits``)
    rpm = args.rpm if args.rpm is not None else eng.rpm
    label = eng.name
    mech = mechanism(R, T1, m_pos)
    omega = units.omega(rpm)
    return mech, omega, rpm, label, orders


# --- handlers -------------------------------------------------------------------------------

def _run_twin(args) -> int:
    from shaftfe.balance import multi

    mech, omega, rpm, label, orders = _setup(args)
    X = None if args.x is None else [v / 100.0 for v in parse_floats(args.x, "--x")]
    if X is not None and len(X) == 1:
        X = X[0]
    offset = args.offset_mm
    cyls = multi.twin(args.delta, args.epsilon, shared_pin=args.shared_pin, X=X,
                      offset_m=offset / 1000.0)
    res = multi.engine_forces(cyls, mech, omega, samples=args.samples, orders=orders)
    layout = multi.twin_layout(cyls, args.delta, shared_pin=args.shared_pin, offset_mm=offset)
    head = (f"layout: delta {args.delta:g} deg, epsilon {layout['epsilon_deg']:g} deg, "
            f"{'shared pin' if args.shared_pin else 'two pins'}, resultant crank counterweight "
            f"{layout['resultant_counterweight_pct']:.2f} % of one cylinder's m_pos R")
    return _report(args, "twin", label, rpm, mech, omega, cyls, res, layout, head)


def _run_inline(args) -> int:
    from shaftfe.balance import multi

    mech, omega, rpm, label, orders = _setup(args)
    pins = parse_floats(args.pins, "--pins")
    spacing = [s / 1000.0 for s in parse_floats(args.spacing_mm, "--spacing-mm")]
    X = None if args.x is None else [v / 100.0 for v in parse_floats(args.x, "--x")]
    if X is not None and len(X) == 1:
        X = X[0]
    cyls = multi.inline(pins, spacing[0] if len(spacing) == 1 else spacing, X=X)
    res = multi.engine_forces(cyls, mech, omega, samples=args.samples, orders=orders)
    layout = multi.inline_layout(pins, res)
    head = (f"layout: {len(cyls)} cylinders inline, pins {','.join(f'{p:g}' for p in pins)} "
            f"deg; couple about z = {1000.0 * res.z_ref_m:g} mm (middle of the row)")
    return _report(args, "inline", label, rpm, mech, omega, cyls, res, layout, head)


def _report(args, command, label, rpm, mech, omega, cyls, res, layout, head) -> int:
    from shaftfe.balance.multi import summary

    data = summary(command, label, rpm, mech, omega, cyls, res, layout)
    from shaftfe.balance.plots import plot_multi
    png = plot_multi(res, f"balance {command}: {label}, {rpm:g} rpm",
                args.plot.rsplit(".", 1)[-1].lower()) if args.plot else None
    if png is not None:
        write_atomic(args.plot, png)
        data["plot"] = str(args.plot)
    if args.json:
        print_json(data)
        return 0
    print(f"balance {command}: engine {label} (R {1000 * mech.R:g} mm, T1 {1000 * mech.T1:g} mm,"
          f" m_pos {mech.m_pos:.4g} kg per cylinder), {rpm:g} rpm, "
          f"A = m_pos R w^2 = {res.A:.1f} N")
    print(head)
    print_table(["cyl", "TDC at [deg]", "tilt [deg]", "z [mm]", "X [%]"],
                [[n + 1, c.phase_deg, c.tilt_deg, 1000.0 * c.z_m, 100.0 * c.X]
                 for n, c in enumerate(cyls)])
    print(f"max |F| = {res.max_force:.1f} N at {data['max_force_at_deg']:g} deg; "
          f"max |M| = {res.max_couple:.2f} N*m at {data['max_couple_at_deg']:g} deg")
    print_table(["order", "|F| [N]", "|F|/A", "co-rot [N]", "counter [N]", "Fx [N]", "Fy [N]",
                 "|M| [N*m]", "Mx [N*m]", "My [N*m]"],
                [[f.order, f.amplitude, f"{f.amplitude / res.A:.4g}", f.co_rotating,
                  f.counter_rotating, f.x, f.y, m.amplitude, m.x, m.y]
                 for f, m in zip(res.force_orders, res.couple_orders, strict=True)],
                title="orders (amplitude = semi-major axis of the order's ellipse; co-rot turns "
                "with the crank, counter against it; Mx pitch, My yaw):")
    if png is not None:
        print(f"wrote {args.plot}")
    return 0
