"""`shaftfe balance twin|inline`: several cylinders (seed 000 §4.3, ch. 7). Stub."""

from __future__ import annotations


def register(bsub) -> None:
    """Add the multi-cylinder subcommands to the `balance` group."""
