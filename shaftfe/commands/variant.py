"""`shaftfe variant` command group (stub: filled in by its issue)."""

from __future__ import annotations


def register(sub) -> None:
    p = sub.add_parser("variant", help="(not yet available)")
    p.set_defaults(handler=lambda args: print("shaftfe variant: not yet available") or 1)
