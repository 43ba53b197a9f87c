"""The report's options, their checks and its progress stages."""

from __future__ import annotations

import math
from dataclasses import dataclass

from shaftfe.errors import InputError
from shaftfe.rotordynamics.options import DEFAULT_ORDERS, ROTOR_MODELS
from shaftfe.solid.levels import ESTIMATE_PAIR_CHEAP
from shaftfe.util.paths import DEFAULT_SPECTRUM

STAGES = ("inputs", "balancing", "beam check", "static (mesh + one solve)", "fatigue",
          "strength by standard", "Campbell", "VTU", "3D pictures", "plots")


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
    spectrum: str = str(DEFAULT_SPECTRUM)
    engine: str = "vm450"
    level: str = "default"
    design_rpm: tuple[float, ...] = (10_000.0, 7_000.0)   # seed §8.2.2 static check, §8.3 ref
    campbell_step_rpm: float = 500.0
    modes: int = 12
    orders: tuple[float, ...] = DEFAULT_ORDERS
    rotor_model: str = "beam"
    estimate_error: bool = False          # solve a second mesh level (OTHER_LEVEL)
    mean_stress: str = "soderberg"
    material: str = "structural_steel"
    design_life_blocks: float = 1e7
    speed_kmh: float = 70.0
    cache_dir: str | None = None
    pictures: bool = True                 # PyVista renders (off: no VTK import)
    seed_load_case: bool = False          # every part (as every command); True: the seed's F1+Fv2
    model: str = "solid"                  # static model: solid | axisymmetric (static.MODELS)
    spin_softening: bool = True           # the parts' m ω² u (the seed's study had none)
    allow_overspeed: bool = False         # a spectrum above the engine's max_rpm (warned)


CAMPBELL_STEP_MIN_RPM = 10.0     # ≤ 2000 speeds up to the rpm ceiling: seconds, not GiB


def check_options(o: ReportOptions) -> None:
    """Cheap checks of everything the user typed (before any computation or output)."""
    from shaftfe.fatigue.run import check_model_level
    check_model_level(o.model, o.level)
    if o.model == "axisymmetric" and o.estimate_error:
        raise InputError("command line", "--estimate-error", "not with --model axisymmetric "
                         "(its levels' errors are in reports/benchmarks/axisymmetric.md)")
    if o.rotor_model not in ROTOR_MODELS:
        raise InputError("command line", "--rotor-model", " | ".join(ROTOR_MODELS),
                         got=o.rotor_model)
    from shaftfe.util.limits import RPM_CEILING, check_rpm
    if not o.design_rpm:
        raise InputError("command line", "--rpm", "one or more speeds", got="")
    for r in o.design_rpm:
        check_rpm(r, "--rpm", positive=True)
    if not (math.isfinite(o.campbell_step_rpm)
            and CAMPBELL_STEP_MIN_RPM <= o.campbell_step_rpm <= RPM_CEILING):
        raise InputError("command line", "--campbell-step",
                         f"a step in [{CAMPBELL_STEP_MIN_RPM:g}, {RPM_CEILING:g}] rpm (at most "
                         f"{RPM_CEILING / CAMPBELL_STEP_MIN_RPM:.0f} speeds)",
                         got=o.campbell_step_rpm)
    if not (1 <= o.modes <= 50):
        raise InputError("command line", "--modes", "1..50", got=o.modes)
    from shaftfe.fatigue.run import MEAN_STRESS, check_life_settings
    check_life_settings(o.design_life_blocks, o.speed_kmh)
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
