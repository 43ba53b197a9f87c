"""The report's options, their checks and its progress stages."""

from __future__ import annotations

import math
from dataclasses import dataclass

from shaftfe.errors import InputError
from shaftfe.fatigue.run import DEFAULT_MODEL, MEAN_STRESS, check_life_settings, check_model_level
from shaftfe.fatigue.sn import variant_card
from shaftfe.rotordynamics.options import DEFAULT_ORDERS, ROTOR_MODELS
from shaftfe.solid.levels import ESTIMATE_PAIR_CHEAP
from shaftfe.static import STATIC_MODELS
from shaftfe.util.limits import RPM_CEILING, check_rpm

# in the order they run; "3D pictures": the wait for what is left of them after the plots
# (they render in a second process from the VTU stage on, ``report.pictures``)
STAGES = ("inputs", "balancing", "beam check", "static (mesh + one solve)", "fatigue",
          "Campbell", "VTU", "strength by standard", "plots", "3D pictures")


ERROR_STAGE = "error estimate (second mesh level)"


# --estimate-error: the second level of the Richardson estimate (the neighbour level; the
# coarser one where there is one, so the estimate costs less than the run itself)
OTHER_LEVEL = ESTIMATE_PAIR_CHEAP


def stages(o) -> tuple[str, ...]:
    """The progress stages of a run with options ``o``."""
    if not o.estimate_error:
        return STAGES
    i = STAGES.index("static (mesh + one solve)") + 1
    return (*STAGES[:i], ERROR_STAGE, *STAGES[i:])


@dataclass(frozen=True)
class ReportOptions:
    variant: str = "x2_57"
    overrides: tuple[str, ...] = ()       # --set PATH=VALUE on the variant (model.overrides)
    # None: the variant's [duty] states it (``with_duty``); nothing defaults to the seed's
    spectrum: str | None = None
    engine: str | None = None             # None with no [duty] engine: no balancing section
    level: str = "default"
    design_rpm: tuple[float, ...] | None = None
    campbell_range_rpm: tuple[float, float] | None = None
    campbell_step_rpm: float = 500.0
    modes: int = 12
    orders: tuple[float, ...] = DEFAULT_ORDERS
    rotor_model: str = "beam"
    estimate_error: bool = False          # solve a second mesh level (OTHER_LEVEL)
    mean_stress: str = "soderberg"
    material: str | None = None           # the seed method's S-N card (sn_curves.toml)
    design_life_blocks: float | None = None
    design_life_h: float | None = None
    speed_kmh: float = 70.0
    cache_dir: str | None = None
    pictures: bool = True                 # PyVista renders (off: no VTK import)
    seed_load_case: bool = False          # every part (as every command); True: the seed's F1+Fv2
    model: str | None = None              # static model: zoned | solid | axisymmetric
    #                                       (static.STATIC_MODELS); None: fatigue.run.
    #                                       DEFAULT_MODEL (zoned)
    spin_softening: bool = True           # the parts' m ω² u (the seed's study had none)
    allow_overspeed: bool = False         # a spectrum above the engine's max_rpm (warned)


# the rotor models the report's Campbell stage builds (``stages.campbell``); the harmonic model
# (``shaftfe campbell --model harmonic``) is not wired into the report yet
REPORT_ROTOR_MODELS = tuple(m for m in ROTOR_MODELS if m != "harmonic")
CAMPBELL_STEP_MIN_RPM = 10.0     # ≤ 2000 speeds up to the rpm ceiling: seconds, not GiB


def check_options(o: ReportOptions) -> None:
    """Cheap checks of everything the user typed (before any computation or output)."""
    check_model_level(o.model or DEFAULT_MODEL, o.level, STATIC_MODELS)
    if o.model != "solid" and o.estimate_error:
        raise InputError("command line", "--estimate-error", "with --model solid (the "
                         "axisymmetric levels' errors are in reports/benchmarks/"
                         "axisymmetric.md, the zoned model's in zoned.md)",
                         got=o.model or f"{DEFAULT_MODEL} (the default)")
    if o.rotor_model not in REPORT_ROTOR_MODELS:
        raise InputError("command line", "--rotor-model", " | ".join(REPORT_ROTOR_MODELS),
                         got=o.rotor_model)
    if o.design_rpm is not None and not o.design_rpm:
        raise InputError("command line", "--rpm", "one or more speeds", got="")
    for r in o.design_rpm or ():
        check_rpm(r, "--rpm", positive=True)
    if o.campbell_range_rpm is not None:
        lo, hi = o.campbell_range_rpm
        if not (math.isfinite(lo) and math.isfinite(hi) and 0 <= lo < hi <= RPM_CEILING):
            raise InputError("command line", "--campbell-range",
                             f"LO:HI with 0 <= LO < HI <= {RPM_CEILING:g} rpm",
                             got=f"{lo:g}:{hi:g}")
    if not (math.isfinite(o.campbell_step_rpm)
            and CAMPBELL_STEP_MIN_RPM <= o.campbell_step_rpm <= RPM_CEILING):
        raise InputError("command line", "--campbell-step",
                         f"a step in [{CAMPBELL_STEP_MIN_RPM:g}, {RPM_CEILING:g}] rpm (at most "
                         f"{RPM_CEILING / CAMPBELL_STEP_MIN_RPM:.0f} speeds)",
                         got=o.campbell_step_rpm)
    if not (1 <= o.modes <= 50):
        raise InputError("command line", "--modes", "1..50", got=o.modes)
    check_life_settings(o.design_life_blocks, o.speed_kmh, o.design_life_h)
    if o.mean_stress not in MEAN_STRESS:
        raise InputError("command line", "--mean-stress", " | ".join(MEAN_STRESS),
                         got=o.mean_stress)
    if o.rotor_model == "solid" and not solid_rotor_available():
        raise InputError("command line", "--rotor-model",
                         "beam (the 3D solid rotor model is not available yet)", got="solid")


def solid_rotor_available() -> bool:
    """True when the 3D solid rotor model (``shaftfe.rotordynamics.solid_rotor``) is installed."""
    import importlib.util
    return importlib.util.find_spec("shaftfe.rotordynamics.solid_rotor") is not None


def with_duty(o: ReportOptions, variant) -> ReportOptions:
    """``o`` with every duty value it leaves open taken from the variant's [duty]
    (``model.variant.Duty``); a value neither states is one line naming the field, the file and
    the option. The engine and the element checks' data are optional (no engine: no balancing
    section; no element data: no key and gear-pair checks)."""
    import dataclasses

    d = variant.duty
    where = variant.source_files[0] if variant.source_files else variant.name
    src = d.source if d is not None else where

    def need(value, field: str, option: str, what: str):
        if value is None:
            raise InputError(src, f"duty.{field}", f"{what} (in the variant's [duty] table, "
                             f"or {option} on the command line)", reason="is not stated")
        return value

    life_h = o.design_life_h if o.design_life_blocks is None else None
    life_b = o.design_life_blocks
    if life_b is None and life_h is None and d is not None:
        life_b, life_h = d.design_life_blocks, d.design_life_h
    if life_b is None:
        need(life_h, "design_life_h", "--design-life-h", "a design life in hours")
    return dataclasses.replace(
        o,
        spectrum=o.spectrum or need(d and d.spectrum, "spectrum", "--spectrum",
                                    "an rpm history file"),
        engine=o.engine or (d.engine if d is not None else None),
        design_rpm=o.design_rpm or need((d and d.design_speeds_rpm) or None,
                                        "design_speeds_rpm", "--rpm", "the design speeds"),
        campbell_range_rpm=o.campbell_range_rpm or need(
            d and d.campbell_range_rpm, "campbell_range_rpm", "--campbell-range",
            "the Campbell range [low, high] in rpm"),
        material=o.material or variant_card(variant),
        design_life_blocks=life_b, design_life_h=life_h)


