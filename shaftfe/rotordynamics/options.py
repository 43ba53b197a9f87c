"""The rotor analysis's options (stdlib only: the CLI reads the choices without numpy)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from shaftfe.errors import InputError

ROTOR_MODELS = ("beam", "solid", "harmonic")
COUPLINGS = ("rigid", "distributing")     # solid model: RBE2-like (bonded) | RBE3-like
# The excitation (engine) orders of a Campbell diagram's lines k × n/60, n the shaft's speed:
# 1× (the shaft's own unbalance: the counterweights' m e ω², the only load modelled) and 2×
# (its second harmonic). ONE default for the API (``analyse``, ``campbell.sweep``), the
# ``campbell`` command, the report and the demo.
DEFAULT_ORDERS: tuple[float, ...] = (1.0, 2.0)
# The separation margin drawn around each excitation line of the Campbell diagram, ±10 % of
# the excitation frequency: a design-practice parameter, not a standard's requirement. API 684
# / API 617 derive the required margin from the amplification factor of a damped unbalance
# response, which this undamped sweep does not compute; a branch inside the band is a critical
# speed close enough to the excitation to need that response analysis.
SEPARATION_MARGIN = 0.10
# the size of a sweep: the modes per speed (the reduced basis grows with them), and the speeds a
# command line's RANGE/--step may ask (a Campbell diagram's resolution far past any plot's; a
# study sets its own step, ``study.spec``)
MAX_SPEEDS = 2001
MAX_MODES = 200


@dataclass(frozen=True)
class RotorOptions:
    model: str = "beam"                   # "beam" | "solid" | "harmonic"
    rigid_supports: bool = False
    bearing_damping: float = 0.0          # N·s/mm, isotropic, on every bearing (0: undamped)
    max_element_mm: float = 5.0           # beam elements
    level: object = "coarse"              # solid: mesh level (name or MeshLevel);
    #                                       harmonic: meridian level name
    coupling: str = "rigid"               # solid, harmonic: "rigid" | "distributing"
    stress_stiffening: bool = False       # solid: centrifugal prestress
    cache_dir: object = None


def check_modes(n_modes: int) -> None:
    """The modes of a sweep: 1 … MAX_MODES (the model's own bound, half its dofs, is
    ``analyse``'s)."""
    if isinstance(n_modes, bool) or not (isinstance(n_modes, int) and 1 <= n_modes <= MAX_MODES):
        raise InputError("command line", "--modes", f"1..{MAX_MODES}", got=n_modes)


def check_options(o: RotorOptions) -> None:
    """The rules of an analysis, whoever asks (the CLI names the same options)."""
    from shaftfe.util.limits import check_max_element
    if o.model not in ROTOR_MODELS:
        raise InputError("command line", "--model", " | ".join(ROTOR_MODELS), got=o.model)
    check_max_element(o.max_element_mm)
    if not (math.isfinite(o.bearing_damping) and o.bearing_damping >= 0):
        raise InputError("command line", "--bearing-damping", ">= 0 N s/mm",
                         got=o.bearing_damping)
    if o.coupling not in COUPLINGS:
        raise InputError("--coupling", "coupling", " | ".join(COUPLINGS), got=o.coupling)
    if o.stress_stiffening and o.model != "solid":
        raise InputError("command line", f"--stress-stiffening with --model {o.model}",
                         "--stress-stiffening with --model solid",
                         reason="is not available (the prestress is modelled only in the 3D "
                         "solid rotor)")
