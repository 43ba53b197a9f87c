"""Which ``shaftfe fatigue`` option belongs to which method: the one table (stdlib only, so the
command's ``--help`` is generated from it without importing numpy). Which method uses which
option is each method's own ``options`` (``fatigue.methods``, the registry).

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
* FKM (``fatigue.fkm_field``): the strength card, its Miner rule, j_D, D_M; on the static
  field of any model (its stress gradient from each field's ``DepthProbe``);
* DIN 743 (``fatigue.strength.run_din743``): the strength card on the beam model: no mesh,
  no static 3D solution, no design life (a fatigue-limit check of the largest cycle);
* DIN 743's safety at every cross-section along the shaft, plotted (``--plot``): a beam
  quantity, so DIN 743's alone;
* both standards also compute the bearings' ISO 281 life (``--kappa``, ``--ec``); the seed
  method does not;
* the 3D / axisymmetric static solution (seed, FKM): ``--model``, ``--level``, ``--exclude-mm``,
  ``--seed-load-case``, ``--spin-softening``, and the design life of a life-based safety factor.

Options of every method (the history, the variant, the engine's speed limit, ``--speed-kmh``,
``--out``, ``--json``, ``--cache-dir``) are not in the table.
"""

from __future__ import annotations

from shaftfe.errors import InputError
from shaftfe.fatigue.methods import DEFAULT_METHOD, METHODS, get_method

__all__ = ["DEFAULT_METHOD", "OPTIONS", "applies_to", "check_method_options", "help_epilog",
           "methods_of", "table", "with_defaults"]

# option -> (argparse dest, default); which methods use it: each method's ``options`` (the
# registry, ``fatigue.methods``), so a new method names its rows in its own module
OPTIONS: dict[str, tuple[str, object]] = {
    "--card": ("card", None),                # None: the variant's shaft material
    "--miner": ("miner", "modified"),
    "--consequences": ("consequences", "severe"),
    "--inspection": ("inspection", False),
    "--damage-sum": ("damage_sum", 0.3),
    "--kappa": ("kappa", None),              # None: machine_elements.bearings.KAPPA_DEFAULT
    "--ec": ("ec", None),                    # None: machine_elements.bearings.EC_DEFAULT
    "--mean-stress": ("mean_stress", "soderberg"),
    "--equivalent": ("equivalent", "von_mises"),
    "--material": ("material", None),        # None: the variant's (sn.variant_card)
    "--kf": ("kf", 1.0),
    "--model": ("model", None),              # None: fatigue.run.resolve_model (zoned)
    "--level": ("level", "default"),
    "--exclude-mm": ("exclude_mm", 0.0),
    "--seed-load-case": ("seed_load_case", False),
    "--spin-softening": ("spin_softening", True),
    "--design-life": ("design_life", None),  # None: run.DEFAULT_DESIGN_LIFE_BLOCKS
    "--design-life-h": ("design_life_h", None),
    "--case": ("case", None),                # a [[load_cases]] name: DIN 743 S_F on it
    "--plot": ("plot", False),               # DIN 743 / FKM at every cross-section, plotted
}


def methods_of(option: str) -> tuple[str, ...]:
    """The registered methods that use ``option``, in the registry's order."""
    return tuple(n for n, m in METHODS.items() if option in m.options)


def table() -> dict[str, tuple[str, object, tuple[str, ...]]]:
    """option -> (dest, default, the methods that use it): the table as the registry makes it
    now (a method registered later, e.g. by a test, is in it)."""
    return {o: (d, v, methods_of(o)) for o, (d, v) in OPTIONS.items()}


def _narrowed(option: str, method: str):
    """(the values ``method`` takes of ``option``, why), where it takes only part of them (a
    method's ``narrowed``); else None."""
    return METHODS[method].narrowed.get(option)


def applies_to(option: str) -> str:
    """'[fkm, din743]': the methods of ``option``, for its help text; a method that takes only
    some of its values names them: '[seed, fkm: solid only]'."""
    def one(m):
        narrow = _narrowed(option, m)
        return m + (f": {' | '.join(narrow[0])} only" if narrow else "")
    return "[" + ", ".join(one(m) for m in methods_of(option)) + "]"


def help_epilog() -> str:
    """The table as the help's closing paragraph: each method and its options."""
    def name(o, m):
        narrow = _narrowed(o, m)
        return f"{o} ({' | '.join(narrow[0])} only)" if narrow else o
    per = [f"{m}: " + " ".join(name(o, m) for o in OPTIONS if o in meth.options)
           for m, meth in METHODS.items()]
    return ("Options by method: " + "; ".join(per) + ". Any other option applies to every "
            "method; an option given that the chosen method does not use is refused.")


def check_method_options(method: str, given: dict[str, object]) -> None:
    """``given``: option -> value of the options typed on the command line (None: not given).
    Refuses an unknown method and any option the method does not use."""
    get_method(method)
    for option, value in given.items():
        if value is None or option not in OPTIONS:
            continue
        methods = methods_of(option)
        if method not in methods:
            raise InputError("command line", option, f"only with --method {' | '.join(methods)}",
                             got=value, reason=f"is not used by --method {method}")
        narrow = _narrowed(option, method)
        if narrow:
            values, why = narrow
            if value not in values:
                others = [m for m in methods if m != method]
                raise InputError("command line", option, f"{' | '.join(values)} with --method "
                                 f"{method} ({why}); {value} with --method "
                                 f"{' | '.join(others)}", got=value)


def with_defaults(args) -> None:
    """Check the options of ``args`` (an argparse namespace, the table's options parsed with
    default None) against ``args.method``, then set each one left out to its default."""
    check_method_options(args.method, {o: getattr(args, d, None)
                                       for o, (d, _) in OPTIONS.items()})
    for dest, default in OPTIONS.values():
        if getattr(args, dest, None) is None:
            setattr(args, dest, default)
