"""Command-line interface: a thin layer over the Python API.

Each command group lives in its own module under ``shaftfe.commands`` and exposes
``register(subparsers)``. Those modules import only the standard library at module level; the
numerical stack (numpy for balancing, gmsh / scikit-fem / pyvista / matplotlib for FE work) is
imported inside the handlers, so ``shaftfe --help`` stays instant.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys

from shaftfe import __version__
from shaftfe.errors import ShaftfeError
from shaftfe.util.notices import collecting

# One OpenBLAS thread per process, set before numpy loads OpenBLAS (nothing above imports it; a
# value the user set wins). The commands' dense work is many small products (recoveries, surface
# fits, SuperLU's supernodes), where OpenBLAS's extra thread spins idle and takes the core from
# the zones' PARDISO and the harmonic solves running beside it; the large factorisations are
# PARDISO's, on MKL's own threads. Measured whole processes, warm, paired (A/B wall, medians):
# `static` 0.88, `static --model solid` 0.94, `campbell 0:8000` 0.91, `fatigue` and `demo`
# unchanged within their spread (paired whole-process timings, 2026-12-07, 2 cores).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

# Command modules, in the order they appear in --help.
COMMAND_MODULES = (
    "shaftfe.commands.balance",
    "shaftfe.commands.variant",
    "shaftfe.commands.beam",
    "shaftfe.commands.campbell",
    "shaftfe.commands.mesh",
    "shaftfe.commands.static",
    "shaftfe.commands.fatigue",
    "shaftfe.commands.view",
    "shaftfe.commands.report",
    "shaftfe.commands.study",
    "shaftfe.commands.demo",
)


_ARGV: list[str] = []        # the words being parsed, for the hint in _Parser.error


class _Parser(argparse.ArgumentParser):
    """argparse that reports usage errors as one line with exit code 2 (no usage dump)."""

    def error(self, message: str) -> None:  # type: ignore[override]
        k = next((i for i, a in enumerate(_ARGV) if len(a) > 1 and a[0] == "-"
                  and (a[1].isdigit() or a[1] == ".")), None)
        if k is not None and ("expected one argument" in message or "required" in message
                              or "unrecognized arguments" in message):
            neg = _ARGV[k]
            opt = _ARGV[k - 1] if k and _ARGV[k - 1].startswith("--") else None
            how = f"write {opt}={neg}" if opt else f"put -- before it: -- {neg}"
            message += f" ({neg!r} starts with '-' and reads as an option: {how})"
        self.exit(2, f"{self.prog}: error: {message}\n")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="shaftfe",
        description="Balancer-shaft design and assessment: balancing, beam and 3D FE statics, "
        "fatigue and rotor dynamics.",
    )
    parser.add_argument("--version", action="version", version=f"shaftfe {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for name in COMMAND_MODULES:
        importlib.import_module(name).register(sub)
    return parser


def _interrupt_hook(previous):
    """An unraisable-exception hook that re-delivers a Ctrl-C caught where Python cannot
    raise it (a ``weakref.finalize`` callback, a ``__del__``: it would print "Exception ignored
    ... Traceback ... KeyboardInterrupt" and be lost): the interrupt is re-sent to the main
    thread, so ``main`` reports it in one line. Other exceptions go to the previous hook."""
    def hook(unraisable):
        if isinstance(unraisable.exc_value, KeyboardInterrupt):
            import _thread
            _thread.interrupt_main()
            return
        previous(unraisable)
    return hook


def main(argv: list[str] | None = None) -> int:
    sys.unraisablehook = _interrupt_hook(sys.__unraisablehook__)
    parser = build_parser()
    _ARGV[:] = sys.argv[1:] if argv is None else list(argv)
    args = parser.parse_args(argv)
    if not getattr(args, "handler", None):
        parser.print_help()
        return 0
    try:
        with collecting():
            return int(args.handler(args) or 0)
    except ShaftfeError as exc:
        print(f"shaftfe: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("shaftfe: interrupted (no output written)", file=sys.stderr)
        return 130
    except BrokenPipeError:
        # output piped into `head` and closed early: end quietly, as other CLI tools do
        import os

        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except OSError as exc:
        # a file the run could not read or write after the checks up front (disk full, a path
        # changed meanwhile): one line naming it, as for any other bad input
        where = exc.filename if exc.filename is not None else "file system"
        print(f"shaftfe: error: {where}: {exc.strerror or exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
