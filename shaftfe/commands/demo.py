"""`shaftfe demo`: the main job on the bundled defaults (what `make demo` runs).

The demo IS the assessment report of the default variant in the seed's load case
(``shaftfe report --variant x2_57 --seed-load-case``): balancing of the VM 450 at its speed
(crank C, X = 31.1 %, with the variant's X2), the beam check against the Inventor figures, the
static solve (the zoned model: axisymmetric with 3D zones at the keyways and the hex socket) at
10 000 and 7000 rpm (bearing springs; the seed's F1 + Fv2, so that every seed
figure is compared like with like: the one command that does not load every part by default,
and its output says so), the fatigue life on ``loadspectra/rpm.dat`` reusing that solve, and the
Campbell diagram from 0 to the engine's maximum speed; the seed figures next to ours. It writes
``<out>/index.html`` (self-contained), ``summary.json``, the VTU and the figures, and prints where
the report is. See ``shaftfe.commands.report`` and ``shaftfe.report``.
"""

from __future__ import annotations

from shaftfe.solid.levels import LEVEL_NAMES

DEFAULT_VARIANT = "x2_57"


def register(sub) -> None:
    p = sub.add_parser("demo", help="run the main job on the bundled defaults (the report of "
                       f"{DEFAULT_VARIANT})",
                       description="The assessment report of the default variant "
                       f"{DEFAULT_VARIANT} on the bundled engine and rpm history, in the seed's "
                       f"load case (= shaftfe report --variant {DEFAULT_VARIANT} "
                       "--seed-load-case --no-spin-softening): the reproduction of the seed "
                       "study.")
    p.add_argument("--out", default=f"reports/{DEFAULT_VARIANT}",
                   help=f"output folder (default reports/{DEFAULT_VARIANT})")
    p.add_argument("--level", default="default", choices=LEVEL_NAMES,
                   help="mesh level of the 3D stages (default: default)")
    p.add_argument("--json", action="store_true", help="print summary.json instead of text")
    p.set_defaults(handler=run)


def run(args) -> int:
    from shaftfe.commands import report
    from shaftfe.model.loader import load_variant
    from shaftfe.report.options import ReportOptions, with_duty

    # the seed's study as it was made: its load case, no spin softening (its Ansys static),
    # and its duty (the variant's [duty]: the seed's speeds, rpm.dat, VM 450)
    options = with_duty(ReportOptions(variant=DEFAULT_VARIANT, level=args.level,
                                      seed_load_case=True, spin_softening=False),
                        load_variant(DEFAULT_VARIANT))
    return report.make_report(options, args.out, json_out=args.json)
