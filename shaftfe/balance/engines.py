"""Engine data files: ``geometry/engines/<name>.toml`` → a validated, frozen ``Engine``.

Two ways to describe the crank mechanism (SPEC.md §1):

* **lumped** (seed 000): ``piston_group_mass_kg``, ``bigend_bearing_mass_kg`` and the rod
  already split into ``rod_rot_mass_kg`` / ``rod_pos_mass_kg`` (or a whole ``rod_mass_kg`` with
  ``rod_eye_distance_mm`` and ``rod_centroid_from_big_eye_mm``); the crank counterweight as
  ``compensation_mass_kg`` at ``compensation_radius_mm`` (gives X), the balancer shaft as
  ``balancer_mass_kg`` at ``balancer_radius_mm`` (gives X2).
* **parts** (seed 003): crank without pin ``crank_without_pin_mass_kg`` at
  ``crank_without_pin_centroid_mm`` (opposite the pin), pin ``crank_pin_mass_kg`` at the crank
  radius, weighed rod split by its centroid. X then follows from the net static moment
  ``m_r r_r = m_kh r_kh − (m_č + m_or) r``.

X and X2 may also be given directly as ``crank_balance_percent`` / ``balancer_balance_percent``.
Each file has a ``[source]`` table with the provenance of its values.

Units in the files: mm, kg, deg, rpm (in the key names). The ``Engine`` keeps them; ratios X,
X2 are fractions (0.3016 = 30.16 %).
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

from shaftfe.balance.kinematics import split_rod
from shaftfe.errors import InputError
from shaftfe.util.limits import OVERSPEED_HINT, RPM_CEILING
from shaftfe.util.notices import warn
from shaftfe.util.paths import ENGINES_DIR, repo_relative

# key → (allowed text, predicate); all numeric keys the loader understands.
_POS = ("> 0", lambda v: v > 0)
# an engine speed: the one ceiling of every speed (``util.limits.RPM_CEILING``)
_SPEED = (f"in (0, {RPM_CEILING:g}] rpm", lambda v: 0 < v <= RPM_CEILING)
_NONNEG = (">= 0", lambda v: v >= 0)
_KEYS: dict[str, tuple[str, object]] = {
    "crank_radius_mm": _POS,
    "rod_length_mm": _POS,
    "piston_group_mass_kg": _POS,
    "bigend_bearing_mass_kg": _NONNEG,
    "rod_rot_mass_kg": _NONNEG,
    "rod_pos_mass_kg": _NONNEG,
    "rod_mass_kg": _NONNEG,
    "rod_eye_distance_mm": _POS,
    "rod_centroid_from_big_eye_mm": _NONNEG,
    "crank_pin_mass_kg": _NONNEG,
    "crank_without_pin_mass_kg": _NONNEG,
    "crank_without_pin_centroid_mm": _NONNEG,
    "compensation_mass_kg": _NONNEG,
    "compensation_radius_mm": _NONNEG,
    "balancer_mass_kg": _NONNEG,
    "balancer_radius_mm": _NONNEG,
    "crank_balance_percent": ("in [0, 200]", lambda v: 0 <= v <= 200),
    "balancer_balance_percent": ("in [0, 200]", lambda v: 0 <= v <= 200),
    "tilt_deg": ("in [-180, 180]", lambda v: -180 <= v <= 180),
    "idle_rpm": _SPEED,
    "max_rpm": _SPEED,
    "rpm": _SPEED,
}
_TEXT_KEYS = ("name", "description")


@dataclass(frozen=True)
class Engine:
    """One single-cylinder crank mechanism (plus optional balancer shaft), file units."""

    name: str
    source: str                               # file the data came from
    crank_radius_mm: float                    # R (half stroke)
    rod_length_mm: float                      # T1 (eye to eye)
    piston_group_mass_kg: float               # piston + pin + rings + clips
    bigend_bearing_mass_kg: float
    rod_rot_mass_kg: float                    # rod share at the crank pin
    rod_pos_mass_kg: float                    # rod share at the piston pin
    compensation_mass_kg: float | None = None     # crank m_C (lumped description)
    compensation_radius_mm: float | None = None   # γ
    balancer_mass_kg: float | None = None         # m_vh
    balancer_radius_mm: float | None = None       # γ2
    crank_pin_mass_kg: float | None = None        # parts description (seed 003)
    crank_without_pin_mass_kg: float | None = None
    crank_without_pin_centroid_mm: float | None = None
    rod_mass_kg: float | None = None
    rod_eye_distance_mm: float | None = None
    rod_centroid_from_big_eye_mm: float | None = None
    X_given: float | None = None              # fraction, from crank_balance_percent
    X2_given: float | None = None             # fraction, from balancer_balance_percent
    tilt_deg: float = 0.0
    idle_rpm: float | None = None
    max_rpm: float | None = None
    rpm: float = 6000.0
    description: str = ""

    def info(self) -> dict:
        """The engine as the balance commands' ``--json`` states it (mm, kg)."""
        return {"name": self.name, "source": self.source,
                "crank_radius_mm": self.crank_radius_mm, "rod_length_mm": self.rod_length_mm,
                "m_pos_kg": self.m_pos_kg, "m_rot_kg": self.m_rot_kg}

    @property
    def m_pos_kg(self) -> float:
        """Reciprocating mass m_pos = m_piston + m_rod_pos."""
        return self.piston_group_mass_kg + self.rod_pos_mass_kg

    @property
    def m_rot_kg(self) -> float:
        """Rotating mass at the crank pin m_rot = m_bearing + m_rod_rot (pin not included)."""
        return self.bigend_bearing_mass_kg + self.rod_rot_mass_kg

    @property
    def has_parts(self) -> bool:
        return (self.crank_without_pin_mass_kg is not None
                and self.crank_without_pin_centroid_mm is not None
                and self.crank_pin_mass_kg is not None)

    @property
    def crank_static_moment_kg_mm(self) -> float | None:
        """Net crank unbalance beyond the rotating mass [kg·mm], counterweight side positive.

        Lumped: m_C γ − m_rot R. Parts: m_kh r_kh − (m_č + m_or) r (seed 003 eq. 9-11, with the
        big-end bearing, if any, added to the rotating share).
        """
        R = self.crank_radius_mm
        if self.compensation_mass_kg is not None and self.compensation_radius_mm is not None:
            return self.compensation_mass_kg * self.compensation_radius_mm - self.m_rot_kg * R
        if self.has_parts:
            return (self.crank_without_pin_mass_kg * self.crank_without_pin_centroid_mm
                    - (self.crank_pin_mass_kg + self.m_rot_kg) * R)
        return None

    @property
    def X(self) -> float | None:
        """Crank balance ratio as a fraction (given directly, else from the crank masses)."""
        if self.X_given is not None:
            return self.X_given
        s = self.crank_static_moment_kg_mm
        return None if s is None else s / (self.m_pos_kg * self.crank_radius_mm)

    @property
    def X2(self) -> float | None:
        """Balancer balance ratio X2 = m_vh γ2 / (m_pos R) as a fraction (or given directly)."""
        if self.X2_given is not None:
            return self.X2_given
        if self.balancer_mass_kg is None or self.balancer_radius_mm is None:
            return None
        return (self.balancer_mass_kg * self.balancer_radius_mm
                / (self.m_pos_kg * self.crank_radius_mm))


def known_engines(directory: Path = ENGINES_DIR) -> list[str]:
    return sorted(p.stem for p in Path(directory).glob("*.toml"))


def resolve_engine_path(name_or_path: str | Path, directory: Path = ENGINES_DIR) -> Path:
    text = str(name_or_path)
    p = Path(text)
    if text.endswith(".toml") or p.parent != Path("."):
        if not p.is_file():
            raise InputError("--engine", "engine file", "an existing .toml file", got=text,
                             reason="does not exist")
        return p
    cand = Path(directory) / f"{text.lower()}.toml"
    if not cand.is_file():
        known = ", ".join(known_engines(directory)) or "(none)"
        raise InputError("--engine", "engine", f"one of {known} or a path to a .toml file",
                         got=text, reason="is not a known engine")
    return cand


def load_engine(name_or_path: str | Path, directory: Path = ENGINES_DIR) -> Engine:
    """Read and validate an engine file; bad data → ``InputError`` naming file and field."""
    path = resolve_engine_path(name_or_path, directory)
    src = str(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(src, "file", "a readable UTF-8 TOML file", reason=f"unreadable ({exc})") \
            from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError(src, "file", "valid TOML", reason=f"is not valid TOML ({exc})") from None
    return engine_from_dict(data, src, default_name=path.stem)


def _numbers(data: dict, source: str) -> dict[str, float]:
    """Every numeric key of an engine table, checked against ``_KEYS``."""
    vals: dict[str, float] = {}
    for key, value in data.items():
        if key == "source" or key in _TEXT_KEYS:
            continue
        if key not in _KEYS:
            raise InputError(source, key, "one of " + ", ".join(sorted(_KEYS)), reason="is unknown")
        allowed, ok = _KEYS[key]
        if (isinstance(value, bool) or not isinstance(value, int | float)
                or not math.isfinite(value)):
            raise InputError(source, key, f"a finite number {allowed}", got=value)
        if not ok(value):  # type: ignore[operator]
            raise InputError(source, key, allowed, got=value)
        vals[key] = float(value)
    return vals


def _need(vals: dict[str, float], source: str, key: str, why: str) -> float:
    if key not in vals:
        raise InputError(source, key, f"a number ({why})", reason="is missing")
    return vals[key]


def _rod_split(vals: dict[str, float], source: str) -> tuple[float, float]:
    """The rod's rotating and reciprocating masses: given, or split from the weighed rod
    (seed 003 eq. 7-8)."""
    if "rod_rot_mass_kg" in vals or "rod_pos_mass_kg" in vals:
        return (_need(vals, source, "rod_rot_mass_kg", "given with rod_pos_mass_kg"),
                _need(vals, source, "rod_pos_mass_kg", "given with rod_rot_mass_kg"))
    if "rod_mass_kg" in vals:

        ell = _need(vals, source, "rod_eye_distance_mm", "needed to split rod_mass_kg")
        l1 = _need(vals, source, "rod_centroid_from_big_eye_mm", "needed to split rod_mass_kg")
        if l1 > ell:
            raise InputError(source, "rod_centroid_from_big_eye_mm",
                             f"<= rod_eye_distance_mm = {ell:g}", got=l1)
        return split_rod(vals["rod_mass_kg"], ell, l1)
    raise InputError(source, "rod_rot_mass_kg",
                     "rod_rot_mass_kg + rod_pos_mass_kg, or rod_mass_kg + "
                     "rod_eye_distance_mm + rod_centroid_from_big_eye_mm", reason="is missing")


def _check_pairs(vals: dict[str, float], source: str) -> None:
    """Masses given with their radius, the crank pin with the crank, idle ≤ max rpm."""
    for a, b in (("compensation_mass_kg", "compensation_radius_mm"),
                 ("balancer_mass_kg", "balancer_radius_mm"),
                 ("crank_without_pin_mass_kg", "crank_without_pin_centroid_mm")):
        if (a in vals) != (b in vals):
            missing = b if a in vals else a
            raise InputError(source, missing, f"given together with {a if a != missing else b}",
                             reason="is missing")
    if "crank_without_pin_mass_kg" in vals and "crank_pin_mass_kg" not in vals:
        raise InputError(source, "crank_pin_mass_kg", "given with crank_without_pin_mass_kg",
                         reason="is missing")
    if "idle_rpm" in vals and "max_rpm" in vals and vals["idle_rpm"] > vals["max_rpm"]:
        raise InputError(source, "idle_rpm", f"<= max_rpm = {vals['max_rpm']:g}",
                         got=vals["idle_rpm"])


def engine_from_dict(data: dict, source: str, default_name: str = "engine") -> Engine:
    """Validate a parsed engine table (see the module docstring) and build an ``Engine``."""
    vals = _numbers(data, source)
    R = _need(vals, source, "crank_radius_mm", "crank radius")
    piston = _need(vals, source, "piston_group_mass_kg", "reciprocating mass")
    rod_rot, rod_pos = _rod_split(vals, source)
    T1 = vals.get("rod_length_mm", vals.get("rod_eye_distance_mm"))
    if T1 is None:
        raise InputError(source, "rod_length_mm", "a number > crank_radius_mm", reason="is missing")
    if T1 <= R:
        raise InputError(source, "rod_length_mm", f"> crank_radius_mm = {R:g}", got=T1)
    _check_pairs(vals, source)
    name = data.get("name", default_name)
    pct = vals.get("crank_balance_percent")
    pct2 = vals.get("balancer_balance_percent")
    eng = Engine(
        name=str(name), source=source, crank_radius_mm=R, rod_length_mm=T1,
        piston_group_mass_kg=piston,
        bigend_bearing_mass_kg=vals.get("bigend_bearing_mass_kg", 0.0),
        rod_rot_mass_kg=rod_rot, rod_pos_mass_kg=rod_pos,
        compensation_mass_kg=vals.get("compensation_mass_kg"),
        compensation_radius_mm=vals.get("compensation_radius_mm"),
        balancer_mass_kg=vals.get("balancer_mass_kg"),
        balancer_radius_mm=vals.get("balancer_radius_mm"),
        crank_pin_mass_kg=vals.get("crank_pin_mass_kg"),
        crank_without_pin_mass_kg=vals.get("crank_without_pin_mass_kg"),
        crank_without_pin_centroid_mm=vals.get("crank_without_pin_centroid_mm"),
        rod_mass_kg=vals.get("rod_mass_kg"),
        rod_eye_distance_mm=vals.get("rod_eye_distance_mm"),
        rod_centroid_from_big_eye_mm=vals.get("rod_centroid_from_big_eye_mm"),
        X_given=None if pct is None else pct / 100.0,
        X2_given=None if pct2 is None else pct2 / 100.0,
        tilt_deg=vals.get("tilt_deg", 0.0), idle_rpm=vals.get("idle_rpm"),
        max_rpm=vals.get("max_rpm"), rpm=vals.get("rpm", 6000.0),
        description=str(data.get("description", "")),
    )
    if eng.X is not None and not -2.0 <= eng.X <= 2.0:
        field = ("compensation_mass_kg" if "compensation_mass_kg" in vals
                 else "crank_without_pin_mass_kg")
        raise InputError(source, field,
                         "masses giving a crank balance ratio X in [-200, 200] %",
                         got=round(100 * eng.X, 2))
    return eng


# --------------------------------------------------------------------------- the engine's limit
# A stress or life assessment at operating speeds (a fatigue history, the report's spectrum,
# ``static --rpm``, ``beam --rpm``) is bounded by the engine's ``max_rpm``, below the absolute
# ``util.limits.RPM_CEILING`` (the module docstring of ``util.limits`` says why each bound).

DEFAULT_ENGINE = "vm450"     # the x2_* balancer shafts' engine (``util.limits``' docstring)


def engine_speed_limit(engine=DEFAULT_ENGINE) -> tuple[float, str]:
    """(the engine's max_rpm, where it comes from); an engine file without max_rpm: the
    absolute ``RPM_CEILING``. ``engine`` is an engine name or file, or a variant's duty
    (``model.variant.Duty``: the highest speed of its speed range), or None (no engine and no
    duty: ``RPM_CEILING``)."""
    if engine is None:
        return RPM_CEILING, "shaftfe.util.limits.RPM_CEILING (no engine, no [duty] speed range)"
    if hasattr(engine, "speed_limit"):
        return engine.speed_limit()
    e = load_engine(engine)
    if e.max_rpm is None:
        return RPM_CEILING, (f"shaftfe.util.limits.RPM_CEILING ({repo_relative(e.source)} "
                             "gives no max_rpm)")
    return float(e.max_rpm), f"max_rpm of {e.name} in {repo_relative(e.source)}"


def check_operating_speed(rpm: float, engine: str, allow_overspeed: bool, source: str,
                          what: str, *, factor: float = 1.0, hint: str = OVERSPEED_HINT) -> None:
    """``rpm``, the highest speed of an assessment, against ``factor`` × the engine's max_rpm
    (1: an operating history; ``PROOF_FACTOR``: a proof check): above it, refused unless
    ``allow_overspeed``, then assessed with a visible warning. ``hint``: how the caller's user
    goes past it (the commands' option; a caller without one says so)."""
    max_rpm, where = engine_speed_limit(engine)
    limit = min(factor * max_rpm, RPM_CEILING)
    if rpm <= limit:
        return
    bound = f"{limit:g} rpm, the {where}" if factor == 1 else \
        f"{limit:g} rpm = {factor:g} × the {where} ({max_rpm:g} rpm: an overspeed proof check)"
    if not allow_overspeed:
        raise InputError(source, what, f"at most {bound}{hint}", got=float(rpm),
                         reason="is above the engine's maximum speed")
    warn("overspeed", source, f"{what} = {rpm:g} rpm is above {bound}: assessed as asked "
         "(--allow-overspeed); the engine does not run there, so a life at it is not an "
         "operating life")
