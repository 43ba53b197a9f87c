"""Operating limits every command shares (stdlib only, so the CLI can check before importing).

``RPM_CEILING``: the one ceiling on an engine or balancer-shaft speed, for every command and
every input file. 20 000 rpm is above the red line of any motorcycle engine (the seed's VM 450
turns at most 10 000 rpm); a larger number is a typing or unit mistake (rad/s, or rpm²), and at
1e9 rpm the FE answer would be 10^12 MPa of nonsense.

The engine's own limit. ``RPM_CEILING`` is the absolute bound of any speed; a stress or life
assessment at operating speeds (a fatigue history, the report's spectrum, ``static --rpm``,
``beam --rpm``) is bounded by the engine's ``max_rpm`` (``geometry/engines/<engine>.toml``;
the x2_* balancer shafts are the VM 450's: their [balance] m_pos 0.473 kg and R 30.2 mm are its
crank's, seed 000 §8.1), ``balance.engines.engine_speed_limit``. A history above it is refused
unless the user allows the overspeed (``--allow-overspeed``), then assessed with a warning
(``balance.engines.check_operating_speed``): a spectrum at
19 999 rpm gave a 7 h life for an engine that never turns above 9500. The single checking
speeds of ``static`` / ``beam --rpm`` may go up to ``PROOF_FACTOR`` × max_rpm: an overspeed
(proof) check of the rotor's strength, as the seed's own static check at 10 000 rpm (5 % above
the VM 450's 9500) and the 110-120 % overspeed tests of rotating machinery (API 617 runs its
rotors at 110 % of the maximum continuous speed); above that the same refusal and option.
``campbell`` is not
bounded by it (a sweep past the maximum speed shows the margin to the next critical speed).

``BEAM_ELEMENT_MIN_MM``: the shortest beam element a user may ask for with ``--max-element``; a
150 mm shaft then has at most about 1500 elements (the default is 5 mm), while 1e-6 mm would
ask for 10^8 elements and tens of GiB.

``EXCLUDE_MM_MAX``: the widest band around bearing and load-patch edges that the filtered hot
spot of ``static`` and ``fatigue`` may leave out (``--exclude-mm``).
"""

from __future__ import annotations

import math

from shaftfe.errors import InputError

RPM_CEILING = 20_000.0
BEAM_ELEMENT_MIN_MM = 0.1
EXCLUDE_MM_MAX = 5.0     # a band around patch edges; wider would exclude whole short segments


def check_rpm(v: float, option: str, source: str = "command line", *,
              positive: bool = False) -> float:
    """A speed in rpm: finite, in [0, RPM_CEILING] (or (0, …] with ``positive``)."""
    lo = "(0" if positive else "[0"
    if not (math.isfinite(v) and (v > 0 if positive else v >= 0) and v <= RPM_CEILING):
        raise InputError(source, option, f"a speed in {lo}, {RPM_CEILING:g}] rpm", got=v)
    return float(v)


def check_max_element(v: float, option: str = "--max-element") -> float:
    if not (math.isfinite(v) and v >= BEAM_ELEMENT_MIN_MM):
        raise InputError("command line", option, f">= {BEAM_ELEMENT_MIN_MM:g} mm (a beam "
                         "element length)", got=v)
    return float(v)


def check_exclude_mm(v: float, source: str = "command line", field: str = "--exclude-mm") -> None:
    """``--exclude-mm`` of static and fatigue: a finite band in [0, EXCLUDE_MM_MAX] mm
    (``source``, ``field``: where the value came from; the options classes name theirs)."""
    if not (math.isfinite(v) and 0 <= v <= EXCLUDE_MM_MAX):
        raise InputError(source, field, f"a band in [0, {EXCLUDE_MM_MAX:g}] mm", got=v)


PROOF_FACTOR = 1.2           # static / beam checking speeds: up to 1.2 × max_rpm (docstring)
OVERSPEED_HINT = "; --allow-overspeed to assess it anyway"
