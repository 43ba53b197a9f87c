"""Which ``shaftfe fatigue`` option belongs to which method: the one table (stdlib only, so the
command's ``--help`` is generated from it without importing numpy).

An option the chosen method does not use would be dropped without a word (``--card`` with the
seed method, whose S-N card is ``--material``; ``--model axisymmetric`` with DIN 743, which
works on the beam), so a result would look as if the option had been applied. The rule: an
option given on the command line that the chosen method does not use is refused, in one line
naming the methods it applies to (``check_method_options``). The command registers these
options with ``default=None`` so that "given" can be told from "left at its default" (even
``--card 14220``, the shaft's own material, is refused with ``--method seed``), then fills the
defaults from this table (``with_defaults``).

Why each option belongs where:

* the seed method (``fatigue.run``): von Mises / Soderberg / S-N card with Miner, on the 3D or
  axisymmetric field: ``--mean-stress``, ``--equivalent``, ``--material`` (S-N card), ``--kf``;
* FKM (``fatigue.fkm_field``): the strength card, its Miner rule, j_D, D_M; on the 3D field;
* DIN 743 (``fatigue.standards.run_din743``): the strength card on the beam model: no mesh,
  no static 3D solution, no design life (a fatigue-limit check of the largest cycle);
* both standards also compute the bearings' ISO 281 life (``--kappa``, ``--ec``); the seed
  method does not;
* the 3D / axisymmetric static solution (seed, FKM): ``--model``, ``--level``, ``--exclude-mm``,
  ``--seed-load-case``, ``--spin-softening``, and the design life of a life-based safety factor.

Options of every method (the history, the variant, the engine's speed limit, ``--speed-kmh``,
``--out``, ``--json``, ``--cache-dir``) are not in the table.
"""

from __future__ import annotations

from shaftfe.errors import InputError

METHODS = ("fkm", "din743", "seed")
DEFAULT_METHOD = "fkm"

SEED, FKM, DIN = ("seed",), ("fkm",), ("din743",)
FIELD = ("seed", "fkm")              # the methods that use the static 3D (or axisymmetric) field
STANDARDS = ("fkm", "din743")

# option -> (argparse dest, default, the methods that use it)
METHOD_OPTIONS: dict[str, tuple[str, object, tuple[str, ...]]] = {
    "--card": ("card", None, STANDARDS),            # None: the variant's shaft material
    "--miner": ("miner", "modified", FKM),
    "--consequences": ("consequences", "severe", FKM),
    "--inspection": ("inspection", False, FKM),
    "--damage-sum": ("damage_sum", 0.3, FKM),
    "--kappa": ("kappa", None, STANDARDS),          # None: elements.bearings.KAPPA_DEFAULT
    "--ec": ("ec", None, STANDARDS),                # None: elements.bearings.EC_DEFAULT
    "--mean-stress": ("mean_stress", "soderberg", SEED),
    "--equivalent": ("equivalent", "von_mises", SEED),
    "--material": ("material", None, SEED),         # None: the variant's (sn.variant_card)
    "--kf": ("kf", 1.0, SEED),
    "--model": ("model", "solid", FIELD),
    "--level": ("level", "default", FIELD),
    "--exclude-mm": ("exclude_mm", 0.0, FIELD),
    "--seed-load-case": ("seed_load_case", False, FIELD),
    "--spin-softening": ("spin_softening", True, FIELD),
    "--design-life": ("design_life", None, FIELD),  # None: run.DEFAULT_DESIGN_LIFE_BLOCKS
    "--design-life-h": ("design_life_h", None, FIELD),
}

# option -> method -> (the values that method takes, why): where a method takes only part of an
# option's values (FKM's stress gradient is taken along the normal of the 3D field: the
# axisymmetric model's revolved surface has no element layer to take it in)
METHOD_VALUES: dict[str, dict[str, tuple[tuple[str, ...], str]]] = {
    "--model": {"fkm": (("solid",), "the FKM stress gradient is taken on the 3D field")},
}


def applies_to(option: str) -> str:
    """'[fkm, din743]': the methods of ``option``, for its help text; a method that takes only
    some of its values names them: '[seed, fkm: solid only]'."""
    narrow = METHOD_VALUES.get(option, {})
    return "[" + ", ".join(m + (f": {' | '.join(narrow[m][0])} only" if m in narrow else "")
                           for m in METHOD_OPTIONS[option][2]) + "]"


def help_epilog() -> str:
    """The table as the help's closing paragraph: each method and its options."""
    def name(o, m):
        narrow = METHOD_VALUES.get(o, {}).get(m)
        return f"{o} ({' | '.join(narrow[0])} only)" if narrow else o
    per = [f"{m}: " + " ".join(name(o, m) for o, (_, _, ms) in METHOD_OPTIONS.items() if m in ms)
           for m in METHODS]
    return ("Options by method: " + "; ".join(per) + ". Any other option applies to every "
            "method; an option given that the chosen method does not use is refused.")


def check_method_options(method: str, given: dict[str, object]) -> None:
    """``given``: option -> value of the options typed on the command line (None: not given).
    Refuses an unknown method and any option the method does not use."""
    if method not in METHODS:
        raise InputError("command line", "--method", " | ".join(METHODS), got=method)
    for option, value in given.items():
        if value is None or option not in METHOD_OPTIONS:
            continue
        methods = METHOD_OPTIONS[option][2]
        if method not in methods:
            raise InputError("command line", option, f"only with --method {' | '.join(methods)}",
                             got=value, reason=f"is not used by --method {method}")
        if method in METHOD_VALUES.get(option, {}):
            values, why = METHOD_VALUES[option][method]
            if value not in values:
                others = [m for m in methods if m != method]
                raise InputError("command line", option, f"{' | '.join(values)} with --method "
                                 f"{method} ({why}); {value} with --method "
                                 f"{' | '.join(others)}", got=value)


def with_defaults(args) -> None:
    """Check the options of ``args`` (an argparse namespace, the table's options parsed with
    default None) against ``args.method``, then set each one left out to its default."""
    check_method_options(args.method, {o: getattr(args, d, None)
                                       for o, (d, _, _) in METHOD_OPTIONS.items()})
    for dest, default, _ in METHOD_OPTIONS.values():
        if getattr(args, dest, None) is None:
            setattr(args, dest, default)
