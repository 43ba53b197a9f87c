"""Strength cards and surface roughness for the standards' assessments, read into frozen
dataclasses; every bad value is one ``InputError`` naming the file and the field.

A card is a view of ONE material record (``geometry/common/materials.toml``, ``[materials.NAME]``:
the same record that gives the FE model its E, ν and density and the seed method's S-N card its
strengths): ``card_of(variant.material)`` for the shaft's own material, ``load_card(NAME)`` for
a record named on the command line. The surfaces' roughness stays in
``geometry/common/strength.toml``."""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

from shaftfe.errors import InputError
from shaftfe.fatigue import fkm
from shaftfe.model.parse import material_record
from shaftfe.solid.features import kind_of
from shaftfe.util.paths import COMMON_DIR

CARDS_FILE = COMMON_DIR / "strength.toml"        # the surfaces
MATERIALS_FILE = COMMON_DIR / "materials.toml"   # the material records


@dataclass(frozen=True)
class StrengthCard:
    name: str
    description: str
    group: str                     # key of fkm.GROUPS
    rm_n_MPa: float                # at the standard's reference diameter
    rp_n_MPa: float
    case_hardness_HRC: float | None
    case_depth_mm: float | None

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


def card_of(material, source: str = "the variant's materials") -> StrengthCard:
    """The strength card of a material record (``model.variant.Material``); a record without a
    standard material group is refused (it cannot be assessed by FKM or DIN 743)."""
    if material.group not in fkm.GROUPS:
        raise InputError(source, f"materials.{material.name}.group",
                         " | ".join(k for k in fkm.GROUPS if k != "gjl")
                         + " (a material the standards can assess)", got=material.group or None)
    return StrengthCard(material.name, material.description, material.group,
                        material.ultimate_MPa, material.yield_MPa, material.case_hardness_HRC,
                        material.case_depth_mm)


def load_card(name: str, path: str | Path = MATERIALS_FILE) -> StrengthCard:
    """The card of record ``[materials.NAME]`` in ``path``."""
    return card_of(material_record(name, path), str(path))


def load_surfaces(path: str | Path = CARDS_FILE) -> Surfaces:
    path = Path(path)
    src = str(path)
    t = _read(path).get("surfaces", {})
    return Surfaces(*(_num(t, k, src, "surfaces", 0.1, 400.0)
                      for k in ("seat_Rz_um", "fillet_Rz_um", "keyway_Rz_um", "turned_Rz_um")))


def region_rz(region: str, surf: Surfaces, ground_fillets: frozenset[str]) -> float:
    """R_z of a named surface region: bearing seats and the fillets next to them ground,
    keyways milled, the rest finish-turned."""
    kind = kind_of(region)
    if kind == "bearing_seat":
        return surf.seat_rz_um
    if kind == "keyway":
        return surf.keyway_rz_um
    if region in ground_fillets:
        return surf.fillet_rz_um
    return surf.turned_rz_um
