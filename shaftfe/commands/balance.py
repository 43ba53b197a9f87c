"""`shaftfe balance ...`: crank-mechanism balancing (SPEC.md §1). Numpy imported in handlers."""

from __future__ import annotations


def register(sub) -> None:
    p = sub.add_parser("balance", help="crank-mechanism shaking forces and balance ratios")
    bsub = p.add_subparsers(dest="balance_command", metavar="SUBCOMMAND")
    p.set_defaults(handler=lambda args: p.print_help() or 2)
    register_single(bsub)
    from shaftfe.commands import balance_multi

    balance_multi.register(bsub)


def register_single(bsub) -> None:
    """forces / sweep / ratios (single cylinder, seed 000 ch. 5 and seed 003)."""
