"""`shaftfe campbell` and `shaftfe modal`: natural frequencies with gyroscopic effects.

Stdlib only at module level; numpy/scipy (shaftfe.rotor, shaftfe.campbell) and matplotlib
inside the handlers. The model is chosen by ``--model``: today only ``beam`` (Timoshenko beam
+ rigid disks); a 3D ``solid`` builder plugs into ``_MODEL_BUILDERS`` with the same contract:
``builder(args)`` returns an object like ``shaftfe.rotor.RotorModel`` — M, K, G, C (dense or
sparse, free dofs), ``labelling`` (``shaftfe.campbell.Labelling``), ``notes``, ``n_dof`` and
optionally ``K_support`` (bearing springs, for the energy shares), ``beam``/``disks`` (only
for the description line) — and then remove the "solid" refusal in ``_check_common``.
"""

from __future__ import annotations

import math

from shaftfe.errors import InputError

_MAX_SPEEDS = 2001
_MAX_MODES = 200
_SHORT = {"forward": "F", "backward": "B", "torsional": "T", "axial": "A", "undetermined": "?"}


def _common_options(p) -> None:
    p.add_argument("--variant", default="x2_57", help="variant name (default x2_57)")
    p.add_argument("--modes", type=int, default=12, help="number of modes (default 12)")
    p.add_argument("--model", choices=("beam", "solid"), default="beam",
                   help="rotor model: beam (Timoshenko beam + rigid disks; default) or solid "
                   "(3D FE, not available yet)")
    p.add_argument("--max-element", type=float, default=5.0, metavar="MM",
                   help="beam model: maximum element length in mm (default 5)")
    p.add_argument("--rigid-supports", action="store_true",
                   help="rigid bearings instead of the bearing spring matrices")
    p.add_argument("--bearing-damping", type=float, default=0.0, metavar="NS_PER_MM",
                   help="isotropic damping of every bearing in N·s/mm (default 0: undamped); "
                   "frequencies are then damped ones")
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
    p.add_argument("range", metavar="RANGE",
                   help="speed range in rpm: a:b or a:b:step (e.g. 0:8000)")
    p.add_argument("--step", type=float, default=1000.0, help="speed step in rpm "
                   "(default 1000; a step given in RANGE wins)")
    p.add_argument("--orders", default="1", help="engine orders for the excitation lines, "
                   "comma-separated (default 1), e.g. 1,2")
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

    a, b, st = parse_range(text, "RANGE", lo=0.0)
    if not (math.isfinite(a) and math.isfinite(b)):
        raise InputError("command line", "RANGE", "finite speeds", got=text)
    st = step if st is None else st
    if not (math.isfinite(st) and st > 0):
        raise InputError("command line", "--step", "> 0 rpm", got=st)
    if b == a:
        return [a]
    n = math.floor((b - a) / st + 1e-9)
    if n + 2 > _MAX_SPEEDS:
        raise InputError("command line", "RANGE/--step", f"at most {_MAX_SPEEDS} speeds",
                         got=f"{text} step {st:g}")
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
    if args.model == "solid":
        raise InputError("command line", "--model", "beam (the 3D solid rotor model is not "
                         "available yet)", got="solid")
    if not (1 <= args.modes <= _MAX_MODES):
        raise InputError("command line", "--modes", f"1..{_MAX_MODES}", got=args.modes)
    if not (math.isfinite(args.max_element) and args.max_element > 0):
        raise InputError("command line", "--max-element", "> 0 mm", got=args.max_element)
    if not (math.isfinite(args.bearing_damping) and args.bearing_damping >= 0):
        raise InputError("command line", "--bearing-damping", ">= 0 N s/mm",
                         got=args.bearing_damping)


# --------------------------------------------------------------------------- models

def _beam_rotor(args):
    from shaftfe import rotor
    from shaftfe.variant import load_variant

    variant = load_variant(args.variant)
    return rotor.rotor_from_variant(
        variant, max_element_mm=args.max_element, rigid_supports=args.rigid_supports,
        bearing_damping=args.bearing_damping if args.bearing_damping > 0 else None)


_MODEL_BUILDERS = {"beam": _beam_rotor}


def _describe(args, model) -> str:
    sup = "rigid supports" if args.rigid_supports else "bearing springs"
    damp = (f", bearing damping {args.bearing_damping:g} N·s/mm" if args.bearing_damping > 0
            else ", undamped")
    beam = getattr(model, "beam", None)
    nodes = f"{beam.n_nodes} nodes, " if beam is not None else ""
    disks = getattr(model, "disks", ())
    return (f"variant {args.variant}: {args.model} model ({nodes}{model.n_dof} dofs, "
            f"{len(disks)} rigid disks), {sup}{damp}")


# --------------------------------------------------------------------------- handlers

def _solve(args, rpms, orders, keep_vectors=False):
    from shaftfe import rotor

    model = _MODEL_BUILDERS[args.model](args)
    n_max = model.n_dof // 2
    if args.modes > n_max:
        raise InputError("command line", "--modes", f"1..{n_max} for this model", got=args.modes)
    res = rotor.campbell(model, rpms, args.modes, orders=orders, keep_vectors=keep_vectors)
    ver = rotor.verify(model, res) if args.verify else None
    return model, res, ver


def _payload(args, model, res, ver) -> dict:
    d = {"variant": args.variant, "model": args.model, "n_dof": model.n_dof,
         "supports": "rigid" if args.rigid_supports else "springs",
         "bearing_damping_Ns_per_mm": args.bearing_damping, "result": res.to_dict()}
    if ver is not None:
        d["verify"] = {"rpm": ver.rpm, "freq_reduced_hz": list(ver.freq_reduced_hz),
                       "freq_full_hz": list(ver.freq_full_hz),
                       "max_rel_diff": ver.max_rel_diff, "n_missed": ver.n_missed}
    return d


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


def run_campbell(args) -> int:
    from shaftfe.commands._common import print_json, write_atomic

    rpms = speeds_from_range(args.range, args.step)
    orders = parse_orders(args.orders)
    _check_common(args)
    model, res, ver = _solve(args, rpms, orders)
    if args.out:
        import json
        from pathlib import Path

        from shaftfe.campbell import plot_campbell

        title = f"{args.variant}: Campbell diagram ({args.model} model)"
        png = plot_campbell(res, title=title)
        js = json.dumps(_payload(args, model, res, ver), indent=2)
        csv = res.to_csv()
        out = Path(args.out)
        for name, data in (("campbell.png", png), ("campbell.csv", csv),
                           ("campbell.json", js + "\n")):
            write_atomic(out / name, data)
    if args.json:
        print_json(_payload(args, model, res, ver))
    else:
        _print_tables(args, model, res, ver)
        if args.out:
            print(f"wrote {args.out}/campbell.png, campbell.csv, campbell.json")
    return 0


def run_modal(args) -> int:
    from shaftfe.commands._common import print_json, print_table, write_atomic

    if not (math.isfinite(args.rpm) and args.rpm >= 0):
        raise InputError("command line", "--rpm", ">= 0", got=args.rpm)
    _check_common(args)
    from shaftfe.rotor import support_energy_share

    model, res, ver = _solve(args, [args.rpm], [1.0], keep_vectors=True)
    share = support_energy_share(model, res.vectors[0])
    payload = _payload(args, model, res, ver)
    payload["bearing_energy_share"] = share.tolist()
    if args.out:
        import json
        from pathlib import Path

        out = Path(args.out)
        write_atomic(out / "modal.csv", res.to_csv())
        write_atomic(out / "modal.json", json.dumps(payload, indent=2) + "\n")
    if args.json:
        print_json(payload)
        return 0
    print(_describe(args, model))
    print_table(["mode", "f Hz", "f·60 rpm", "family", "whirl", "whirl ratio", "zeta",
                 "bearing energy"],
                [[j + 1, f"{res.freq_hz[0, j]:.2f}", f"{res.freq_hz[0, j] * 60:.0f}",
                  res.family[0][j], res.whirl[0][j], f"{res.whirl_ratio[0, j]:+.3f}",
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
    if args.out:
        print(f"wrote {args.out}/modal.csv, modal.json")
    return 0
