"""Inputs of the element checks (``geometry/common/elements.toml``) and the drive torque."""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass

from shaftfe.errors import InputError
from shaftfe.util.paths import COMMON_DIR
from shaftfe.util.units import omega

ELEMENTS_FILE = COMMON_DIR / "elements.toml"


@dataclass(frozen=True)
class Drive:
    idle_rpm: float
    max_rpm: float
    run_up_s: float
    pump_inertia_kg_mm2: float

    @property
    def alpha_rad_s2(self) -> float:
        """Angular acceleration from idle to the maximum speed in the run-up time."""
        return omega(self.max_rpm - self.idle_rpm) / self.run_up_s


def load(path=ELEMENTS_FILE) -> dict:
    src = str(path)
    try:
        doc = tomllib.loads(open(path, encoding="utf-8").read())
    except (OSError, tomllib.TOMLDecodeError) as exc:
        raise InputError(src, "file", "a readable TOML file", reason=str(exc)) from None
    out = {}
    for table in ("drive", "keys", "gear_pair"):
        t = doc.get(table)
        if not isinstance(t, dict):
            raise InputError(src, table, f"a [{table}] table", got=t)
        vals = {}
        for k, v in t.items():
            if k in ("seed", "derived", "reconstructed", "standard", "note"):
                continue
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) \
                    or v <= 0:
                raise InputError(src, f"{table}.{k}", "a finite number > 0", got=v)
            vals[k] = float(v)
        out[table] = vals
    return out


def drive(doc: dict) -> Drive:
    d = doc["drive"]
    return Drive(d["idle_rpm"], d["max_rpm"], d["run_up_s"], d["pump_inertia_kg_mm2"])


def torque_Nmm(inertia_kg_mm2: float, dr: Drive) -> float:
    """M = I α; kg·mm² × rad/s² = 1e-6 kg·m²/s² = 1e-3 N·mm."""
    return inertia_kg_mm2 * dr.alpha_rad_s2 * 1e-3
