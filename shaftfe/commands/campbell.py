"""`shaftfe campbell` and `shaftfe modal`: natural frequencies with gyroscopic effects.

Stdlib only at module level; numpy/scipy and matplotlib inside the handlers. A thin command: the
options become a ``shaftfe.rotordynamics.options.RotorOptions`` and
``shaftfe.rotordynamics.analyse.analyse_with_beam`` builds the model chosen by ``--model``
— ``beam`` (Timoshenko beam + rigid disks, milliseconds) or ``solid`` (3D P2 tets of the static
model's mesh at ``--level``, attachments as rigid bodies tied to their seats by ``--coupling``;
``shaftfe.rotordynamics.solid_rotor``) or ``harmonic`` (the round shaft's n = 0, 1 harmonics on
the meridian mesh at ``--level`` with the same bodies; ``harmonic_rotor``) — sweeps the speeds
and checks the reduced sweep against the full-size problem. The solid model's results are
shown next to the beam model's (same variant and options, but no stress stiffening: the beam
has no prestress), and with ``--out`` its mode shapes
at rest are written as ``modes.vtu`` (docs/FIELDS.md, "Mode shapes"). ``--stress-stiffening``
(solid model only, off by default) adds the centrifugal prestress of the shaft body
(``shaftfe.rotordynamics.prestress``); ``--spin-softening`` is refused (a rotating-frame term,
not applicable in the stationary-frame formulation used here).
"""

from __future__ import annotations

import math

from shaftfe.errors import InputError
from shaftfe.rotordynamics.options import (
    COUPLINGS,
    DEFAULT_ORDERS,
    MAX_SPEEDS,
    ROTOR_MODELS,
    RotorOptions,
    check_modes,
    check_options,
)
from shaftfe.solid.levels import LEVEL_NAMES

_SHORT = {"forward": "F", "backward": "B", "torsional": "T", "axial": "A", "undetermined": "?"}


def _common_options(p) -> None:
    from shaftfe.commands._common import add_set_option
    p.add_argument("--variant", default="x2_57", help="variant name (default x2_57)")
    add_set_option(p)
    p.add_argument("--modes", type=int, default=12, help="number of modes (default 12)")
    p.add_argument("--model", choices=ROTOR_MODELS, default="beam",
                   help="rotor model: beam (Timoshenko beam + rigid disks; default), solid "
                   "(3D P2 tets + rigid attachments; shown next to the beam result) or "
                   "harmonic (the round shaft's n = 0, 1 harmonics on its meridian mesh + the "
                   "same rigid attachments; keyways left out)")
    p.add_argument("--level", choices=LEVEL_NAMES, default="coarse",
                   help="solid and harmonic models: mesh level (default coarse)")
    p.add_argument("--coupling", choices=COUPLINGS, default="rigid",
                   help="solid and harmonic models: tie of the attachments to their seats, "
                   "rigid (RBE2-like, "
                   "bonded hub; default) or distributing (RBE3-like, no seat stiffening)")
    p.add_argument("--max-element", type=float, default=5.0, metavar="MM",
                   help="beam model: maximum element length in mm (default 5)")
    p.add_argument("--rigid-supports", action="store_true",
                   help="rigid bearings instead of the bearing spring matrices")
    p.add_argument("--bearing-damping", type=float, default=0.0, metavar="NS_PER_MM",
                   help="isotropic damping of every bearing in N·s/mm (default 0: undamped); "
                   "frequencies are then damped ones")
    p.add_argument("--stress-stiffening", action="store_true",
                   help="solid model: include the geometric stiffness of the shaft's "
                   "centrifugal prestress (default off, like the seed's study)")
    p.add_argument("--spin-softening", action="store_true",
                   help="refused: spin softening is a rotating-frame term, not applicable in "
                   "the stationary frame used here")
    p.add_argument("--verify", action="store_true",
                   help="also solve the full-size quadratic eigenproblem at the highest speed "
                   "and report the largest relative difference")
    p.add_argument("--json", action="store_true", help="print JSON instead of tables")
    p.add_argument("--out", metavar="DIR",
                   help="write the results into DIR (campbell: campbell.png/.csv/.json; "
                   "modal: modal.csv/.json)")


def register(sub) -> None:
    p = sub.add_parser(
        "campbell", help="Campbell diagram with gyroscopic effects and critical speeds",
        description="Natural frequencies of the spinning balancer shaft over a speed range "
        "(reduced modal basis, MAC mode tracking, forward/backward whirl labels) and the "
        "critical speeds where a branch crosses an engine-order line k × rpm/60.")
    p.add_argument("range", metavar="RANGE", nargs="?", default=None,
                   help="speed range in rpm: a:b or a:b:step (e.g. 0:8000; default: the "
                   "variant's [duty] campbell_range_rpm)")
    p.add_argument("--step", type=float, default=1000.0, help="speed step in rpm "
                   "(default 1000; a step given in RANGE wins)")
    default_orders = ",".join(f"{k:g}" for k in DEFAULT_ORDERS)
    p.add_argument("--orders", default=default_orders, help="engine orders for the "
                   f"excitation lines, comma-separated (default {default_orders}, as the "
                   "report and the demo), e.g. 1")
    _common_options(p)
    p.set_defaults(handler=run_campbell)

    q = sub.add_parser(
        "modal", help="natural frequencies and mode labels at one speed",
        description="Natural frequencies (with gyroscopic effects at --rpm) and mode labels "
        "(forward/backward whirl, torsional, axial) of a balancer-shaft variant.")
    q.add_argument("--rpm", type=float, default=0.0, help="spin speed in rpm (default 0)")
    _common_options(q)
    q.set_defaults(handler=run_modal)


# --------------------------------------------------------------------------- parsing

def speeds_from_range(text: str, step: float) -> list[float]:
    from shaftfe.commands._common import parse_range
    from shaftfe.util.limits import RPM_CEILING

    a, b, st = parse_range(text, "RANGE", lo=0.0, hi=RPM_CEILING)
    if not (math.isfinite(a) and math.isfinite(b)):
        raise InputError("command line", "RANGE", "finite speeds", got=text)
    st = step if st is None else st
    if not (math.isfinite(st) and st > 0):
        raise InputError("command line", "--step", "> 0 rpm", got=st)
    if b == a:
        return [a]
    count = (b - a) / st
    if not count + 2 <= MAX_SPEEDS:                # also an overflow to inf (a step of 1e-308)
        raise InputError("command line", "RANGE/--step", f"1 … {MAX_SPEEDS} speeds",
                         got=f"{text} step {st:g}")
    n = math.floor(count + 1e-9)
    out = [a + i * st for i in range(n + 1)]
    if b - out[-1] > 1e-9 * max(1.0, b):
        out.append(b)
    return out


def parse_orders(text: str) -> list[float]:
    allowed = "comma-separated engine orders > 0, e.g. 1,2"
    try:
        vals = [float(t) for t in text.split(",") if t.strip()]
    except ValueError:
        raise InputError("command line", "--orders", allowed, got=text) from None
    if not vals or any(not (math.isfinite(v) and v > 0) for v in vals):
        raise InputError("command line", "--orders", allowed, got=text)
    return sorted(set(vals))


def _check_common(args) -> None:
    check_modes(args.modes)             # before the variant is read (the API's rule)
    if args.spin_softening:
        raise InputError("command line", "--spin-softening", "omit it (its stationary-frame "
                         "counterpart −Ω² A_θ comes with --stress-stiffening)",
                         reason="is not applicable in the stationary frame (rotating-frame "
                         "term)")
    check_options(_options(args))


def _options(args, model: str | None = None) -> RotorOptions:
    return RotorOptions(model=model or args.model, rigid_supports=args.rigid_supports,
                        bearing_damping=args.bearing_damping, max_element_mm=args.max_element,
                        level=args.level, coupling=args.coupling,
                        stress_stiffening=args.stress_stiffening)


def _describe(args, model) -> str:
    sup = "rigid supports" if args.rigid_supports else "bearing springs"
    damp = (f", bearing damping {args.bearing_damping:g} N·s/mm" if args.bearing_damping > 0
            else ", undamped")
    if args.stress_stiffening:
        damp += ", stress stiffening on"
    beam = getattr(model, "beam", None)
    nodes = f"{beam.n_nodes} nodes, " if beam is not None else ""
    disks = getattr(model, "disks", ())
    if args.model == "solid":
        sm = model.shaft_mesh
        return (f"variant {args.variant}: solid model (P{sm.order} tets, level {sm.level}, "
                f"{sm.n_nodes} nodes, {model.n_dof} dofs, {len(disks)} rigid attachment "
                f"bodies, {args.coupling} coupling), {sup}{damp}")
    if args.model == "harmonic":
        m = model.mesh
        return (f"variant {args.variant}: harmonic model (n = 0, 1 on the meridian mesh, level "
                f"{m.level}, {m.n_nodes} nodes, {model.n_dof} dofs, {len(disks)} rigid "
                f"attachment bodies, {args.coupling} coupling; keyways left out), {sup}{damp}")
    return (f"variant {args.variant}: {args.model} model ({nodes}{model.n_dof} dofs, "
            f"{len(disks)} rigid disks), {sup}{damp}")


# --------------------------------------------------------------------------- handlers

def _solve(args, rpms, orders, keep_vectors=False):
    """The variant, and ``rotordynamics.analyse.analyse_with_beam`` on it."""
    from shaftfe.commands._common import load_variant_from
    from shaftfe.rotordynamics.analyse import analyse_with_beam

    variant = load_variant_from(args)
    run, beam_res = analyse_with_beam(variant, rpms, args.modes, orders=orders,
                                      options=_options(args), keep_vectors=keep_vectors,
                                      verify=args.verify)
    return run, beam_res, variant


def _payload(args, variant, run, beam_res=None) -> dict:
    from shaftfe.rotordynamics.analyse import summary
    return summary(args.variant, variant, _options(args), run, beam_res)


def _print_side_by_side(res, beam_res, stiffened: bool = False) -> None:
    from shaftfe.commands._common import print_table

    rows = []
    from shaftfe.rotordynamics.analyse import side_by_side
    for r in side_by_side(res, beam_res):
        beam = "—" if r["beam_hz"] is None else (
            f"{r['beam_hz']:.1f} {_SHORT[r['beam_whirl']]} (mode {r['beam_mode']})")
        diff = "—" if r["solid_over_beam"] is None else f"{100 * (r['solid_over_beam'] - 1):+.1f}"
        rows.append([r["mode"], f"{r['rpm']:g}", r["family"],
                     f"{r['solid_hz']:.1f} {_SHORT[r['solid_whirl']]}", beam, diff])
    print_table(["mode", "rpm", "family", "3D solid Hz", "beam Hz", "3D vs beam %"], rows,
                title="3D solid model next to the beam model (same variant and bearings; each "
                "3D mode against the beam mode of the same family and rank; torsion is held at "
                "both bearings in 3D, at one node in the beam"
                + ("; the beam without the 3D model's stress stiffening: it has no prestress"
                   if stiffened else "") + ")")


def _print_tables(args, model, res, ver) -> None:
    from shaftfe.commands._common import print_table

    print(_describe(args, model))
    nb = res.freq_hz.shape[1]
    rows = []
    for i, n in enumerate(res.rpm):
        rows.append([f"{n:g}"] + [f"{res.freq_hz[i, j]:.1f} {_SHORT[res.whirl[i][j]]}"
                                  for j in range(nb)])
    print_table(["rpm"] + [f"mode {j + 1}" for j in range(nb)], rows,
                title="damped natural frequencies [Hz] (F forward, B backward, T torsional, "
                "A axial, ? undetermined/planar)")
    print(f"branch whirl: {', '.join(f'{j + 1} {w}' for j, w in enumerate(res.branch_whirl))}")
    print(res.statement())
    print(f"reduced basis: {res.basis_size} modes of {res.n_dof} dofs; requested frequencies "
          f"change {res.basis_change:.1e} (relative) when the basis grows ×1.5")
    if ver is not None:
        print(f"verify: full-size quadratic eigenproblem at {ver.rpm:g} rpm, largest relative "
              f"difference {ver.max_rel_diff:.2e}, full-size modes missed by the tracking: "
              f"{ver.n_missed}")
    for note in res.notes:
        print(f"note: {note}")


def _staged(out):
    """``atomic.staged_dir`` for an optional ``--out`` (yields None without one)."""
    from contextlib import nullcontext

    from shaftfe.util.atomic import staged_dir
    return staged_dir(out) if out else nullcontext(None)


def _duty_range(args) -> str:
    """RANGE from the variant's [duty] campbell_range_rpm; neither: one line naming both."""
    from shaftfe.commands._common import load_variant_from
    v = load_variant_from(args)
    d = v.duty
    if d is None or d.campbell_range_rpm is None:
        src = d.source if d is not None else (v.source_files or (v.name,))[0]
        raise InputError(src, "duty.campbell_range_rpm", "the Campbell range [low, high] in "
                         "rpm (in the variant's [duty] table, or RANGE on the command line)",
                         reason="is not stated")
    lo, hi = d.campbell_range_rpm
    return f"{lo:g}:{hi:g}"


def run_campbell(args) -> int:
    from shaftfe.commands._common import print_json, write_atomic

    if args.range is not None:
        speeds_from_range(args.range, args.step)     # a bad RANGE before the variant is read
    rpms = speeds_from_range(args.range or _duty_range(args), args.step)
    orders = parse_orders(args.orders)
    _check_common(args)
    vtu = None
    from shaftfe.util.progress import Progress
    prog = Progress(["model + sweep", "outputs"], enabled=False if args.json else None)
    with _staged(args.out) as out:                   # every file or none
        with prog.stage("model + sweep"):
            run, beam_res, variant = _solve(args, rpms, orders)
            model, res, ver = run.model, run.result, run.verification
        if out is not None:
            import json

            from shaftfe.rotordynamics.plots import plot_campbell

            title = f"{variant.name}: Campbell diagram ({args.model} model)"
            png = plot_campbell(res, title=title)
            js = json.dumps(_payload(args, variant, run, beam_res), indent=2)
            csv = res.to_csv()
            for name, data in (("campbell.png", png), ("campbell.csv", csv),
                               ("campbell.json", js + "\n")):
                write_atomic(out / name, data)
            from shaftfe.rotordynamics.analyse import write_rest_modes
            vtu = "modes.vtu" if write_rest_modes(run, args.modes, out / "modes.vtu") else None
    if args.json:
        print_json(_payload(args, variant, run, beam_res))
    else:
        _print_tables(args, model, res, ver)
        if beam_res is not None:
            _print_side_by_side(res, beam_res, args.stress_stiffening)
        if args.out:
            print(f"wrote {args.out}/campbell.png, campbell.csv, campbell.json"
                  + (f", {vtu}" if vtu else ""))
    return 0


def run_modal(args) -> int:
    from shaftfe.commands._common import print_json, print_table, write_atomic
    from shaftfe.rotordynamics.campbell import whirl_ratio_text
    from shaftfe.util.limits import check_rpm
    check_rpm(args.rpm, "--rpm")
    _check_common(args)
    files = "modal.csv, modal.json"
    with _staged(args.out) as out:                   # every file or none
        run, beam_res, variant = _solve(args, [args.rpm], [1.0], keep_vectors=True)
        model, res, ver = run.model, run.result, run.verification
        share = run.support_energy_share(0)
        payload = _payload(args, variant, run, beam_res)
        payload["bearing_energy_share"] = share.tolist()
        if out is not None:
            import json

            write_atomic(out / "modal.csv", res.to_csv())
            write_atomic(out / "modal.json", json.dumps(payload, indent=2) + "\n")
            if args.model == "solid":
                from shaftfe.rotordynamics.modes_vtu import write_modes_vtu

                write_modes_vtu(model, res, out / "modes.vtu")
                files += ", modes.vtu"
    if args.json:
        print_json(payload)
        return 0
    print(_describe(args, model))
    print_table(["mode", "f Hz", "f·60 rpm", "family", "whirl", "whirl ratio", "zeta",
                 "bearing energy"],
                [[j + 1, f"{res.freq_hz[0, j]:.2f}", f"{res.freq_hz[0, j] * 60:.0f}",
                  res.family[0][j], res.whirl[0][j],
                  whirl_ratio_text(res.whirl_ratio[0, j], res.family[0][j]),
                  f"{res.zeta[0, j]:.3g}", f"{share[j]:.2f}"]
                 for j in range(res.freq_hz.shape[1])],
                title=f"modes at {args.rpm:g} rpm (bearing energy: share of the mode's strain "
                "energy in the bearing springs)")
    print(f"reduced basis: {res.basis_size} modes of {res.n_dof} dofs")
    if ver is not None:
        print(f"verify: full-size quadratic eigenproblem, largest relative difference "
              f"{ver.max_rel_diff:.2e}, modes missed: {ver.n_missed}")
    for note in res.notes:
        print(f"note: {note}")
    if beam_res is not None:
        _print_side_by_side(res, beam_res, args.stress_stiffening)
    if args.out:
        print(f"wrote {args.out}/{files}")
    return 0
