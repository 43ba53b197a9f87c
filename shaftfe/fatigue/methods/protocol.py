"""What every fatigue method answers: ``FatigueMethod``, its inputs and its one result type.

A method (``fatigue.methods.seed``, ``fkm``, ``din743``) is one module holding one object that
answers this protocol; the registry (``fatigue.methods.METHODS``) maps its name to it. The
command ``shaftfe fatigue``, the report and the studies take a method by name from the registry
and never ask which one they hold (as ``rotordynamics.analyse.RotorKind`` for the rotor models).

* ``AssessmentInputs``: the shaft (a ``Variant``) and its load channels. The stress history is a
  sum over channels, σ(t) = Σ_k σ_k L_k(t): each ``LoadChannel`` pairs a stress field at its
  reference with a load-factor history. Today there is ONE channel, "rpm2": the static solution
  at the reference speed and (rpm / ref)²; a method refuses more (``single``) until it combines
  them (the kernel for that is ``fatigue.channels``: per-node rainflow of the signed von Mises
  of Σ_k σ_k L_k(t); a method built on it is one more module). A channel's field
  (the 3D or axisymmetric ``StaticReference``, the beam solution) and its rainflow count may be
  given by a caller that already has them (the report, a study); else the method obtains them
  from its options (the static cache, the beam at ``util.units.REF_RPM``).
* options: ``fatigue.run.FatigueJob``, the command's options by name (each method reads the rows
  of ``fatigue.method_options`` it names in ``options``).
* ``FatigueAssessment``: the method's name, one ``Location`` per assessed place (utilisation,
  safety, damage and life in blocks, hours and km), the governing one, the warnings the
  assessment raised, its notes, and ``detail``: the method's own result for its own tables,
  files and plots (``FatigueRun``, ``FkmDetail``, ``DinDetail``).

Stdlib only: the registry is read by the command's ``--help``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Protocol

from shaftfe.errors import InputError

# the one channel of today: every load of the shaft ∝ rpm², scaled from the static reference
RPM2 = "rpm2"


@dataclass(frozen=True, eq=False)
class LoadChannel:
    """One term σ_k L_k(t) of the stress history."""
    name: str
    history: object                 # fatigue.history.LoadHistory; L_k(t) is its load factor
    #                                 for "rpm2" (a named channel's: channels.channel_factors)
    field: object | None = None     # static.cache.StaticReference (3D or axisymmetric) at its
    #                                 reference speed; None: the method loads or solves it
    beam: object | None = None      # the beam solution at util.units.REF_RPM (DIN 743), or None
    cycles: object | None = None    # rainflow count of ``history`` re-referenced to the field's
    #                                 speed (counting.Cycles), when the caller has counted it


@dataclass(frozen=True, eq=False)
class AssessmentInputs:
    variant: object                 # model.variant.Variant
    channels: tuple[LoadChannel, ...]

    @classmethod
    def one_channel(cls, variant, history, **given) -> AssessmentInputs:
        """Today's inputs: the one "rpm2" channel (``given``: field, beam, cycles)."""
        return cls(variant, (LoadChannel(RPM2, history, **given),))

    @property
    def history(self):
        """The history of the (one) channel: its time axis and speeds."""
        return self.channels[0].history

    def single(self, method: str) -> LoadChannel:
        """The one channel; several are refused (no method combines channels yet)."""
        if len(self.channels) != 1:
            raise InputError("load history", "channels", f"one channel with --method {method}",
                             got=len(self.channels), reason="several load channels are not "
                             "assessed yet")
        return self.channels[0]


@dataclass(frozen=True)
class Location:
    """One assessed place: the method's figures in common units (nan: the method has none)."""
    name: str                       # region (3D field) or notch (beam)
    x_mm: float
    utilisation: float              # ≤ 1 passes: FKM's degree of utilisation a, DIN 743's
    #                                 S_min / min(S_D, S_F), the seed's 1 / safety factor
    safety: float                   # the achieved safety factor (the seed's: stress factor
    #                                 to the design life, capped at kernels.SAFETY_FACTOR_MAX)
    damage_per_block: float         # share of the life used per pass of the history
    life_blocks: float              # inf: no damage; nan: not a life method
    life_hours: float
    life_km: float


@dataclass(frozen=True, eq=False)
class FatigueAssessment:
    method: str
    locations: tuple[Location, ...]
    governing: Location
    warnings: tuple[dict, ...]      # util.notices dicts raised while assessing
    notes: tuple[str, ...]
    detail: object                  # the method's own result (its tables, files, plots)


class FatigueMethod(Protocol):
    name: str                       # the registry key and the --method value
    title: str                      # one line for --help
    options: tuple[str, ...]        # the fatigue.method_options rows the method uses
    narrowed: Mapping               # option -> (the values it takes, why), where not all
    out_dir: str                    # default folder under reports/<variant>/
    files: tuple[str, ...]          # the files ``write`` puts in the folder
    # files ``write`` puts there only with some options: one left by an earlier run into the
    # same folder is removed (``util.atomic.staged_dir``), so the folder holds one run's files
    optional_files: tuple[str, ...]
    files_help: str                 # the files with what they hold, for --help
    stages: tuple[str, ...]         # progress stages of ``assess`` (after "history")

    def check(self, options) -> None: ...
    def assess(self, inputs: AssessmentInputs, options, progress=None) -> FatigueAssessment: ...
    def write(self, result: FatigueAssessment, inputs: AssessmentInputs, options,
              out) -> tuple[dict, list[str]]: ...
    def lines(self, result: FatigueAssessment, inputs: AssessmentInputs, options, summary: dict,
              out, files) -> list[str]: ...


def life_location(name: str, x_mm: float, utilisation: float, safety: float,
                  life_blocks: float, block_seconds: float, speed_kmh: float,
                  damage_per_block: float | None = None) -> Location:
    """A ``Location`` of a life method: hours and km from the blocks (``assess.life_hours``'s
    rule: blocks × block length; km at ``speed_kmh``); the damage per block 1 / life unless
    the method gives its own."""
    b = float(life_blocks)
    h = b * (block_seconds / 3600.0)
    d = (0.0 if b == math.inf else 1.0 / b if b > 0 else math.inf) \
        if damage_per_block is None else float(damage_per_block)
    return Location(name, float(x_mm), float(utilisation), float(safety), d, b, h, h * speed_kmh)
