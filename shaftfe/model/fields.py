"""Field readers of the variant files: one TOML value at a time, checked, with the file and
the field named in every error (``InputError(file, field, allowed, got)``), plausibility bounds
that catch unit mistakes, and the provenance bookkeeping (which file defined what, and whether
it is seed, reconstructed, derived or standard)."""

from __future__ import annotations

import math
from typing import Any

from shaftfe.errors import InputError
from shaftfe.model.variant import SOURCES

PROV_KEYS = {*SOURCES, "note"}


class Ctx:
    """File bookkeeping: which file defined which top-level item (for error messages)."""

    def __init__(self) -> None:
        self.origin: dict[str, str] = {}
        self.files: list[str] = []
        self.source: dict[str, str] = {}
        self.note: dict[str, str] = {}

    def file_of(self, key: str, default: str) -> str:
        return self.origin.get(key, default)



def is_num(x: Any) -> bool:
    return isinstance(x, int | float) and not isinstance(x, bool)


def is_numeric_value(x: Any) -> bool:
    if is_num(x):
        return True
    if isinstance(x, list) and x:
        return all(is_numeric_value(e) for e in x)
    return False


def table(val: Any, src: str, fld: str) -> dict:
    if not isinstance(val, dict):
        raise InputError(src, fld, "a table", got=type(val).__name__)
    return val


def check_keys(t: dict, allowed: set[str], src: str, fld: str) -> None:
    for k in t:
        if k not in allowed and k not in PROV_KEYS:
            raise InputError(src, f"{fld}.{k}", "one of " + ", ".join(sorted(allowed)),
                             reason="is not a known field")


def num(t: dict, key: str, src: str, fld: str, *, default: float | None = None,
         required: bool = True) -> float | None:
    if key not in t:
        if required and default is None:
            raise InputError(src, f"{fld}.{key}", "a number", reason="is missing")
        return default
    v = t[key]
    if not is_num(v) or not math.isfinite(float(v)):
        raise InputError(src, f"{fld}.{key}", "a finite number", got=v)
    return float(v)


def text(t: dict, key: str, src: str, fld: str, default: str | None = None) -> str:
    if key not in t:
        if default is None:
            raise InputError(src, f"{fld}.{key}", "a string", reason="is missing")
        return default
    v = t[key]
    if not isinstance(v, str) or not v:
        raise InputError(src, f"{fld}.{key}", "a non-empty string", got=v)
    return v


def need(ok: bool, src: str, fld: str, allowed: str, got: Any) -> None:
    if not ok:
        raise InputError(src, fld, allowed, got=got)


# Plausibility bounds for a balancer shaft of a motorcycle engine (mm, kg, N, MPa). They are far
# wider than any real design and exist to catch a value typed in the wrong unit, which passes a
# type check and then gives nonsense (a Ø 0.022 "mm" collar meshed for 10 minutes at 3.8 GB).
PLAUSIBLE = {              # kind: (low, high, unit, the unit a value below `low` was typed in)
    "diameter_mm": (2.0, 300.0, "mm", "metres"),
    "length_mm": (0.2, 2000.0, "mm", "metres"),
    "mass_kg": (1e-5, 20.0, "kg", "tonnes"),
    "eccentricity_mm": (0.0, 300.0, "mm", "metres"),
    "E_MPa": (1e4, 1e6, "MPa", "GPa"),
    "strength_MPa": (10.0, 5000.0, "MPa", "GPa"),
    "C_N": (100.0, 1e7, "N", "kN"),
    "K_N_per_mm": (10.0, 1e9, "N/mm", "kN/mm"),
}
ABOVE_HINT = {"mass_kg": "grams", "eccentricity_mm": "µm", "diameter_mm": "µm",
               "length_mm": "µm", "E_MPa": "Pa", "strength_MPa": "Pa", "K_N_per_mm": "N/m"}


FILLET_MIN_MM = 0.05


# A key's own range, whatever the other keys say (a study's values are checked against it
# before anything runs): the plausibility kinds above by key name, and the signs the loader
# asks of the rest. Rules that tie a key to others (a fillet under the bearing corner at its
# shoulder, a step taller than its fillet, the balance statement) are the design's, checked
# when the design is loaded.
_RANGE_OF_KEY = {"diameter_mm": "diameter_mm", "bore_mm": "diameter_mm",
                 "outer_diameter_mm": "diameter_mm", "length_mm": "length_mm",
                 "width_mm": "length_mm", "mass_kg": "mass_kg",
                 "eccentricity_mm": "eccentricity_mm", "E_MPa": "E_MPa",
                 "yield_MPa": "strength_MPa", "ultimate_MPa": "strength_MPa", "C_N": "C_N",
                 "C0_N": "C_N", "K_N_per_mm": "K_N_per_mm"}


def key_range(path: str) -> tuple[float, float, str] | None:
    """(low, high, unit) of the number at ``path`` (a ``--set`` path) on its own, or None."""
    key = path.rsplit(".", 1)[-1]
    if key in _RANGE_OF_KEY:
        lo, hi, unit, _ = PLAUSIBLE[_RANGE_OF_KEY[key]]
        return lo, hi, unit
    if key == "fillet_mm":
        return 0.0, PLAUSIBLE["diameter_mm"][1] / 2, "mm (0 = sharp, else >= "\
            f"{FILLET_MIN_MM:g})"
    if key == "nu":
        return 0.0, 0.5, "(Poisson's ratio)"
    if key == "density_t_mm3":
        return 1e-10, 1e-7, "t/mm³"
    if ".shape." in path and key.endswith(("_mm", "_deg")):
        return 0.0, 180.0 if key.endswith("_deg") else PLAUSIBLE["length_mm"][1], \
            "deg" if key.endswith("_deg") else "mm"
    return None


class ImplausibleValue(InputError):
    """A value outside its key's plausible range (``plausible``): a unit slip, not a design
    choice (``shaftfe study`` refuses the whole study for it, not one design)."""


def plausible(v: float, kind: str, src: str, fld: str) -> None:
    """``v`` within ``PLAUSIBLE[kind]``; else an error with a hint at the likely unit."""
    lo, hi, unit, below = PLAUSIBLE[kind]
    if lo <= v <= hi:
        return
    hint = ""
    if 0 < v < lo:
        hint = f" (typed in {below}?)"
    elif v > hi and kind in ABOVE_HINT:
        hint = f" (typed in {ABOVE_HINT[kind]}?)"
    raise ImplausibleValue(src, fld, f"a plausible value in [{lo:g}, {hi:g}] {unit}{hint}",
                           got=v)


def provenance(t: dict, src: str, fld: str, path: str, ctx: Ctx) -> None:
    """Every numeric key of table ``t`` must be in exactly one of the lists seed / reconstructed
    / derived / standard; record them under ``path``."""
    numeric = {k for k, v in t.items() if k not in PROV_KEYS and is_numeric_value(v)}
    seen: dict[str, str] = {}
    for s in SOURCES:
        lst = t.get(s, [])
        if not isinstance(lst, list) or not all(isinstance(e, str) for e in lst):
            raise InputError(src, f"{fld}.{s}", "a list of key names", got=lst)
        for k in lst:
            if k not in t:
                raise InputError(src, f"{fld}.{k}", f"a number (it is listed in '{s}')",
                                 reason="is missing")
            if k not in numeric:
                raise InputError(src, f"{fld}.{k}", "a number or a list of numbers",
                                 got=t[k])
            if k in seen:
                raise InputError(src, f"{fld}.{k}", "listed in exactly one provenance list",
                                 reason=f"is listed in both '{seen[k]}' and '{s}'")
            seen[k] = s
    for k in sorted(numeric - set(seen)):
        raise InputError(src, f"{fld}.{k}",
                         "listed in one of seed / reconstructed / derived / standard",
                         reason="has no provenance")
    for k, s in seen.items():
        ctx.source[f"{path}.{k}"] = s
    note = t.get("note")
    if note is not None:
        if not isinstance(note, str):
            raise InputError(src, f"{fld}.note", "a string", got=note)
        ctx.note[path] = note


