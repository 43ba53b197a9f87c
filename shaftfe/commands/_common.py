"""Small helpers shared by the command modules (stdlib only)."""

from __future__ import annotations

import json
import os
import sys

from shaftfe.errors import InputError
from shaftfe.util.atomic import write_atomic

__all__ = ["add_set_option", "load_variant_from", "out_name", "parse_range", "parse_rpm_list",
           "print_json", "print_table", "write_atomic"]

SET_HELP = ("change one variant key for this run by its dotted path, e.g. "
            "--set segments.collar.fillet_mm=0.5 (repeatable; docs/VARIANTS.md lists the "
            "paths); recorded in the outputs")


def add_set_option(p) -> None:
    """``--set PATH=VALUE`` (repeatable) on a command that loads a variant."""
    p.add_argument("--set", action="append", default=[], metavar="PATH=VALUE", dest="set",
                   help=SET_HELP)


def load_variant_from(args, attr: str = "variant"):
    """The variant named by ``args.<attr>`` with the command line's ``--set`` overrides."""
    from shaftfe.model.loader import load_variant
    return load_variant(getattr(args, attr), tuple(getattr(args, "set", None) or ()))


def out_name(name: str, overrides=()) -> str:
    """The default output folder's name of a run: the variant's name, or with ``--set`` values
    ``<name>_set_<8 hex of them>`` (a run with overrides never overwrites the plain variant's
    outputs). ``overrides``: (path, value) pairs or PATH=VALUE strings."""
    items = sorted(f"{o[0]}={o[1]!r}" if isinstance(o, tuple) else str(o) for o in overrides)
    if not items:
        return name
    import hashlib
    return f"{name}_set_{hashlib.blake2b(chr(10).join(items).encode(), digest_size=4).hexdigest()}"


def parse_range(text: str, option: str, *, lo: float | None = None,
                hi: float | None = None) -> tuple[float, float, float | None]:
    """Parse ``a:b`` or ``a:b:step`` (or a single value ``a``) given for ``option``.

    Returns (start, stop, step) with step None when not given. Reversed ranges, a
    non-positive step and values outside [lo, hi] raise InputError.
    """
    parts = text.split(":")
    allowed = "a, a:b or a:b:step with a <= b, step > 0"
    if lo is not None or hi is not None:
        allowed += f", values in [{lo if lo is not None else '-inf'}, "
        allowed += f"{hi if hi is not None else 'inf'}]"
    try:
        nums = [float(p) for p in parts]
    except ValueError:
        raise InputError("command line", option, allowed, got=text) from None
    if len(nums) not in (1, 2, 3):
        raise InputError("command line", option, allowed, got=text)
    start = nums[0]
    stop = nums[1] if len(nums) >= 2 else nums[0]
    step = nums[2] if len(nums) == 3 else None
    if stop < start or (step is not None and step <= 0):
        raise InputError("command line", option, allowed, got=text)
    for v in (start, stop):
        if (lo is not None and v < lo) or (hi is not None and v > hi):
            raise InputError("command line", option, allowed, got=text)
    return start, stop, step


def add_engine_option(p, engine_help: str | None = None,
                      overspeed_help: str | None = None) -> None:
    """``--engine`` and ``--allow-overspeed`` of a command that assesses operating speeds: the
    engine's max_rpm is the limit (``balance.engines.engine_speed_limit``). Without help texts: a
    command of checking speeds (static, beam), up to ``PROOF_FACTOR`` × max_rpm."""
    from shaftfe.util.limits import PROOF_FACTOR
    p.add_argument("--engine", default=None, help=engine_help or (
        "engine file whose max_rpm bounds --rpm (default: the highest speed of the variant's "
        f"[duty] speed_range_rpm): up to {PROOF_FACTOR:g} × that speed, an overspeed proof "
        "check (the x2_* shafts' 10 000 rpm is 1.05 × the VM 450's 9500)"))
    p.add_argument("--allow-overspeed", action="store_true", help=overspeed_help or (
        f"a --rpm above {PROOF_FACTOR:g} × the engine's max_rpm (with a warning)"))


def check_speeds(rpms, args, variant=None) -> None:
    """The checking speeds against the engine's limit for a proof check
    (``balance.engines.check_operating_speed``): the
    --engine given, else the variant's [duty] speed range."""
    from shaftfe.balance.engines import check_operating_speed
    from shaftfe.util.limits import PROOF_FACTOR
    limit = args.engine or (variant.duty if variant is not None else None)
    check_operating_speed(max(rpms), limit, args.allow_overspeed, "command line",
                          "--rpm", factor=PROOF_FACTOR)


def design_speeds(text: str | None, variant, option: str = "--rpm", *,
                  first: bool = False) -> list[float]:
    """``--rpm`` as typed, else the design speeds the variant's [duty] states (``first``: the
    first of them, the checking speed of ``static`` and ``beam``); neither: one line naming the
    field and the file (nothing defaults to the seed's speeds)."""
    if text is not None:
        return parse_rpm_list(text, option)
    d = variant.duty
    if d is None or not d.design_speeds_rpm:
        src = d.source if d is not None else (variant.source_files or (variant.name,))[0]
        raise InputError(src, "duty.design_speeds_rpm", f"the design speeds in rpm (in the "
                         f"variant's [duty] table, or {option} on the command line)",
                         reason="is not stated")
    return list(d.design_speeds_rpm[:1] if first else d.design_speeds_rpm)


def parse_rpm_list(text: str, option: str = "--rpm") -> list[float]:
    """Parse a comma-separated list of speeds in rpm (``7000,10000``); each finite, in
    [0, limits.RPM_CEILING]; an empty item (``10000,,7000``) is an error."""
    from shaftfe.util.limits import RPM_CEILING
    allowed = (f"comma-separated speeds in rpm, each in [0, {RPM_CEILING:g}] (then at most the "
               "engine's own limit: balance.engines.check_operating_speed)")
    items = [t.strip() for t in text.split(",")]
    try:
        vals = [float(t) for t in items]
    except ValueError:
        raise InputError("command line", option, allowed, got=text) from None
    if not vals or any(not (0 <= v <= RPM_CEILING) for v in vals):
        raise InputError("command line", option, allowed, got=text)
    return vals


def print_json(obj: object) -> None:
    """Print JSON to stdout; a closed pipe (``| head``) ends quietly instead of a traceback."""
    try:
        json.dump(obj, sys.stdout, indent=2, sort_keys=False)
        sys.stdout.write("\n")
        sys.stdout.flush()
    except BrokenPipeError:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())


def print_table(headers: list[str], rows: list[list[object]], title: str | None = None) -> None:
    """Plain fixed-width table for terminals (``util.fmt.table_lines``)."""
    from shaftfe.util.fmt import table_lines
    for line in table_lines(headers, rows, title):
        print(line)
