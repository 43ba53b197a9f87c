"""`shaftfe demo`: the main job on the bundled defaults (what `make demo` runs).

Today: the VM 450 balancing study and the x2_57 variant's beam check. It grows into the full
assessment report as the FE stages land.
"""

from __future__ import annotations


def register(sub) -> None:
    p = sub.add_parser("demo", help="run the main job on the bundled defaults")
    p.add_argument("--out", default="reports/demo", help="output folder (default reports/demo)")
    p.set_defaults(handler=run)


def run(args) -> int:
    print("shaftfe demo: nothing to run yet")
    return 0
