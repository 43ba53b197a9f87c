"""`shaftfe beam`: stepped Timoshenko beam model of a variant (stub)."""

from __future__ import annotations


def register(sub) -> None:
    p = sub.add_parser("beam", help="(not yet available)")
    p.set_defaults(handler=lambda args: print("shaftfe beam: not yet available") or 1)
