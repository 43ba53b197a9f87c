"""`shaftfe mesh` command group (stub: filled in by its issue)."""

from __future__ import annotations


def register(sub) -> None:
    p = sub.add_parser("mesh", help="(not yet available)")
    p.set_defaults(handler=lambda args: print("shaftfe mesh: not yet available") or 1)
