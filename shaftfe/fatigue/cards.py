"""Strength cards and surface roughness for the standards' assessments
(``geometry/common/strength.toml``), read into frozen dataclasses; every bad value is one
``InputError`` naming the file and the field."""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

from shaftfe.errors import InputError
from shaftfe.fatigue import fkm
from shaftfe.util.paths import COMMON_DIR

CARDS_FILE = COMMON_DIR / "strength.toml"
_TAGS = ("seed", "standard", "reconstructed", "derived")


@dataclass(frozen=True)
class StrengthCard:
    name: str
    description: str
    group: str                     # key of fkm.GROUPS
    rm_n_MPa: float                # at the standard's reference diameter
    rp_n_MPa: float
    case_hardness_HRC: float | None
    case_depth_mm: float | None
    tags: tuple[tuple[str, str], ...]      # (key, provenance)

    @property
    def case_hardened(self) -> bool:
        return self.case_depth_mm is not None


@dataclass(frozen=True)
class Surfaces:
    seat_rz_um: float
    fillet_rz_um: float
    keyway_rz_um: float
    turned_rz_um: float


def _read(path: Path) -> dict:
    try:
        return tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise InputError(str(path), "file", "a readable TOML file", reason=str(exc)) from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError(str(path), "file", "valid TOML", reason=str(exc)) from None


def _num(t: dict, key: str, src: str, fld: str, lo: float, hi: float,
         optional: bool = False) -> float | None:
    v = t.get(key)
    if v is None and optional:
        return None
    ok = isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) \
        and lo <= v <= hi
    if not ok:
        raise InputError(src, f"{fld}.{key}", f"a number in [{lo:g}, {hi:g}]", got=v)
    return float(v)


def load_card(name: str, path: str | Path = CARDS_FILE) -> StrengthCard:
    path = Path(path)
    src = str(path)
    cards = _read(path).get("cards", {})
    if name not in cards:
        raise InputError(src, "cards", " | ".join(sorted(cards)) or "a [cards.NAME] table",
                         got=name)
    t, fld = cards[name], f"cards.{name}"
    group = t.get("group")
    if group not in fkm.GROUPS:
        raise InputError(src, f"{fld}.group", " | ".join(k for k in fkm.GROUPS if k != "gjl"),
                         got=group)
    rm = _num(t, "Rm_N_MPa", src, fld, 200.0, 2500.0)
    rp = _num(t, "Rp_N_MPa", src, fld, 100.0, rm)
    hrc = _num(t, "case_hardness_HRC", src, fld, 20.0, 70.0, optional=True)
    depth = _num(t, "case_depth_mm", src, fld, 0.05, 5.0, optional=True)
    tags = tuple((k, tag) for tag in _TAGS for k in t.get(tag, []))
    return StrengthCard(name, str(t.get("description", "")), group, rm, rp, hrc, depth, tags)


def load_surfaces(path: str | Path = CARDS_FILE) -> Surfaces:
    path = Path(path)
    src = str(path)
    t = _read(path).get("surfaces", {})
    return Surfaces(*(_num(t, k, src, "surfaces", 0.1, 400.0)
                      for k in ("seat_Rz_um", "fillet_Rz_um", "keyway_Rz_um", "turned_Rz_um")))


def region_rz(region: str, surf: Surfaces, ground_fillets: frozenset[str]) -> float:
    """R_z of a named surface region: bearing seats and the fillets next to them ground,
    keyways milled, the rest finish-turned."""
    if region.startswith("seat:bearing"):
        return surf.seat_rz_um
    if region.startswith("keyway:"):
        return surf.keyway_rz_um
    if region in ground_fillets:
        return surf.fillet_rz_um
    return surf.turned_rz_um
