"""The study file (TOML, docs/STUDIES.md) read into frozen dataclasses.

    [study]      name, base (a variant name or path), description, max_designs
    [sampling]   method = "grid" | "list" | "lhs"; lhs: samples, seed
    [[parameters]]  path = "segments.collar.fillet_mm" (or paths = [...] moved together),
                    values = [...] (grid) or min / max (+ n for a grid), name (the column)
    [[designs]]  (method = "list") one table per design: {path = value, ...}
    [analyses]   balance, beam, static, fatigue, campbell, bearings: tables of options
    [outputs]    columns (default: all), objectives = ["engine_max_F_N:min", ...]

Every path is a ``--set`` path (``shaftfe.model.overrides``); the paths are checked on the base
variant and every value against its key's own range (``overrides.key_range``) before anything
runs (InputError: one line, exit 2). A design whose combination of values is impossible (a
fillet larger than the bearing corner at its shoulder, a hub wider than its sector) is not bad
input: it is recorded with the loader's one-line reason and the study goes on.
"""

from __future__ import annotations

import hashlib
import json
import math
import operator
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from shaftfe.errors import InputError

METHODS = ("grid", "list", "lhs")
MAX_DESIGNS_DEFAULT = 500          # a larger study needs --yes (or max_designs in the file)
_TOP = {"study", "sampling", "parameters", "designs", "analyses", "outputs"}
ANALYSES = ("balance", "beam", "static", "fatigue", "campbell", "bearings")
# the result columns (shaftfe.study.evaluate): fixed names and per-notch / per-bearing families
FIXED = ("mass_kg", "gamma2_mm", "x_T_mm", "X2_percent", "engine_rpm", "engine_max_F_N",
         "engine_rms_F_N", "beam_max_peak_MPa", "beam_max_deflection_mm", "L10h_min_h",
         "n_dofs", "mesh_key", "stress_max_MPa", "static_max_deflection_mm",
         "fatigue_hot_spot", "fatigue_sf", "life_blocks", "life_h", "life_km", "critical_rpm",
         "critical_margin_percent", "campbell_top_rpm", "variant_hash")
PREFIXES = ("stress_", "L10h_", "beam_F_", "static_F_")
OPS = {">=": operator.ge, "<=": operator.le, ">": operator.gt, "<": operator.lt}
_REQ = re.compile(r"^\s*([A-Za-z0-9_:.\-]+)\s*(>=|<=|>|<)\s*([-+0-9.eE]+)\s*$")


TEXT_COLUMNS = ("mesh_key", "fatigue_hot_spot", "variant_hash")
_NEEDS = {"life_": "fatigue", "fatigue_": "fatigue", "stress_": "static", "static_": "static",
          "n_dofs": "static", "critical_": "campbell", "campbell_": "campbell",
          "beam_": "beam"}


def _needs(col: str) -> str | None:
    """The analysis that produces a result column (None: always there)."""
    return next((a for p, a in _NEEDS.items() if col.startswith(p)), None)


def known_column(name: str) -> bool:
    return name in FIXED or name.startswith(PREFIXES)


def parse_requirement(text: str, src: str = "outputs.require") -> tuple[str, str, float]:
    m = _REQ.match(str(text))
    if not m or not known_column(m.group(1)):
        raise InputError(src, "outputs.require", "\"column >= number\" (or <=, >, <) on a "
                         "result column, e.g. \"life_h >= 2083\"", got=text)
    try:
        return m.group(1), m.group(2), float(m.group(3))
    except ValueError:
        raise InputError(src, "outputs.require", "a number after the operator",
                         got=text) from None




@dataclass(frozen=True)
class Parameter:
    """One axis of the design space: one key, or several keys moved together (``paths``)."""
    name: str
    paths: tuple[str, ...]
    values: tuple[tuple[Any, ...], ...] = ()     # explicit points (grid); one value per path
    low: tuple[float, ...] = ()                  # a range (lhs; grid with n)
    high: tuple[float, ...] = ()
    n: int = 0

    def point(self, u: float) -> tuple[float, ...]:
        """The point at fraction u ∈ [0, 1] of the range (every path linearly together)."""
        return tuple(_tidy(lo + u * (hi - lo)) for lo, hi in zip(self.low, self.high,
                                                                 strict=True))

    def grid(self) -> tuple[tuple[Any, ...], ...]:
        if self.values:
            return self.values
        return tuple(self.point(i / (self.n - 1) if self.n > 1 else 0.0) for i in range(self.n))


@dataclass(frozen=True)
class Analyses:
    """What each design computes (``shaftfe.study.evaluate``); defaults in docs/STUDIES.md."""
    engine: str = "vm450"
    X_percent: float | None = None         # None: the seed's crank C (report.seed.CRANK_C_X)
    engine_rpm: float | None = None        # None: the engine file's rpm
    beam: bool = True
    static: bool = False
    static_model: str = "solid"            # solid | zoned (shaftfe.zoned: 3D only in the zones)
    level: str = "coarse"
    spin_softening: bool = True
    seed_load_case: bool = False           # the seed's load model (parts F1, Fv2 at the seat
    #                                        centres) in the beam, static and fatigue rows
    fatigue: bool = False
    fatigue_method: str = "seed"           # by name from fatigue.methods.METHODS
    spectrum: str = ""                     # rpm history, resolved against the study file
    material: str = "structural_steel"
    mean_stress: str = "soderberg"
    equivalent: str = "von_mises"
    design_life: float = 1e7
    speed_kmh: float = 70.0
    campbell: bool = False
    campbell_model: str = "beam"
    campbell_max_rpm: float | None = None  # None: evaluate.CAMPBELL_TOP_RPM
    campbell_step_rpm: float = 250.0
    bearing_rpm: float = 7000.0            # L10h at this speed (the seed's 283.4 h point)

    def options(self) -> dict:
        """The options that change a design's numbers (its cache key), paths as content."""
        from shaftfe.balance.engines import resolve_engine_path
        from shaftfe.util.paths import SN_FILE

        def digest(p) -> str:
            p = Path(p)
            return hashlib.sha256(p.read_bytes()).hexdigest() if p.is_file() else ""
        d = {k: getattr(self, k) for k in self.__dataclass_fields__}
        if d["fatigue_method"] == "seed":     # the only method before the key: the keys of
            del d["fatigue_method"]           # existing studies stay as they were
        if not d["seed_load_case"]:           # likewise
            del d["seed_load_case"]
        if d["static_model"] == "solid":      # likewise
            del d["static_model"]
        d["spectrum"] = digest(self.spectrum) if self.spectrum else ""
        try:
            d["engine_file"] = digest(resolve_engine_path(self.engine))
        except InputError:
            d["engine_file"] = ""                 # refused when a design loads it
        d["sn_curves"] = digest(SN_FILE) if self.fatigue else ""
        return d


@dataclass(frozen=True)
class StudySpec:
    path: str                              # the study file as given
    name: str
    base: str                              # variant name or resolved path
    description: str
    method: str
    parameters: tuple[Parameter, ...]
    samples: int = 0                       # lhs
    seed: int = 0                          # lhs
    designs: tuple[tuple[tuple[str, Any], ...], ...] = ()   # list: ((path, value), ...)
    analyses: Analyses = field(default_factory=Analyses)
    columns: tuple[str, ...] = ()
    objectives: tuple[tuple[str, str], ...] = ()
    requirements: tuple[tuple[str, str, float], ...] = ()
    max_designs: int = MAX_DESIGNS_DEFAULT
    digest: str = ""                       # sha256 of the file's content (a study dir's id)


def _tidy(v: float) -> float:
    return float(f"{v:.10g}")


def _num(t: dict, key: str, src: str, fld: str, default=None, *, lo=None, hi=None,
         integer=False):
    if key not in t:
        return default
    v = t[key]
    ok = isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) \
        and (not integer or float(v).is_integer())
    if ok and lo is not None:
        ok = v >= lo
    if ok and hi is not None:
        ok = v <= hi
    if not ok:
        rng = f"[{lo if lo is not None else '-inf'}, {hi if hi is not None else 'inf'}]"
        raise InputError(src, f"{fld}.{key}", ("an integer" if integer else "a number")
                         + f" in {rng}", got=v)
    return int(v) if integer else float(v)


def _str(t: dict, key: str, src: str, fld: str, default=None, choices=None):
    if key not in t:
        return default
    v = t[key]
    if not isinstance(v, str) or not v or (choices and v not in choices):
        raise InputError(src, f"{fld}.{key}", " | ".join(choices) if choices else
                         "a non-empty string", got=v)
    return v


def _keys(t: Any, allowed, src: str, fld: str) -> dict:
    if not isinstance(t, dict):
        raise InputError(src, fld, "a table", got=t)
    for k in t:
        if k not in allowed:
            import difflib
            near = difflib.get_close_matches(k, sorted(allowed), n=3, cutoff=0.5)
            raise InputError(src, f"{fld}.{k}", "one of " + ", ".join(near or sorted(allowed)),
                             reason="is not a known key")
    return t


def _parameter(i: int, t: dict, src: str, method: str) -> Parameter:
    fld = f"parameters[{i}]"
    _keys(t, {"name", "path", "paths", "values", "min", "max", "n"}, src, fld)
    if ("path" in t) == ("paths" in t):
        raise InputError(src, f"{fld}.path", "either path = \"a.b.c\" or paths = [...]",
                         reason="is missing" if "path" not in t else "is given twice")
    paths = [t["path"]] if "path" in t else t["paths"]
    if not (isinstance(paths, list) and paths and all(isinstance(p, str) and p for p in paths)):
        raise InputError(src, f"{fld}.paths", "a non-empty list of key paths", got=paths)
    k = len(paths)
    name = _str(t, "name", src, fld, default=paths[0] if k == 1 else "+".join(paths))

    def tup(v, what):
        v = v if k > 1 else [v]
        if not (isinstance(v, list) and len(v) == k):
            raise InputError(src, f"{fld}.{what}", f"{'a list of ' + str(k) if k > 1 else 'one'}"
                             f" value{'s' if k > 1 else ''} (one per path)", got=v)
        return tuple(v)
    if "values" in t:
        vals = t["values"]
        if not (isinstance(vals, list) and vals):
            raise InputError(src, f"{fld}.values", "a non-empty list", got=vals)
        if "min" in t or "max" in t:
            raise InputError(src, f"{fld}.values", "values or min/max, not both",
                             reason="is given with min/max")
        return Parameter(name, tuple(paths), values=tuple(tup(v, "values") for v in vals))
    if "min" not in t or "max" not in t:
        raise InputError(src, f"{fld}.min", "values = [...] or min and max",
                         reason="is missing")
    lo, hi = tup(t["min"], "min"), tup(t["max"], "max")
    for a, what in ((lo, "min"), (hi, "max")):
        if not all(isinstance(x, int | float) and not isinstance(x, bool) and math.isfinite(x)
                   for x in a):
            raise InputError(src, f"{fld}.{what}", "finite numbers", got=list(a))
    n = _num(t, "n", src, fld, default=0, lo=1, hi=10_000, integer=True)
    if method == "grid" and not n:
        raise InputError(src, f"{fld}.n", "an integer >= 1 (grid points on [min, max])",
                         reason="is missing")
    return Parameter(name, tuple(paths), low=tuple(map(float, lo)), high=tuple(map(float, hi)),
                     n=n)


# a key of [analyses.fatigue] -> the `shaftfe fatigue` option it stands for: refused with a
# method that does not use it, by the command's rule (fatigue.method_options)
FATIGUE_KEY_OPTIONS = {"material": "--material", "mean_stress": "--mean-stress",
                       "equivalent": "--equivalent", "design_life_blocks": "--design-life"}


def _fatigue_method(f: dict, src: str) -> str:
    """[analyses.fatigue] method: a name of the registry (default the seed's); a key of an
    option the method does not use is refused."""
    from shaftfe.fatigue.method_options import methods_of
    from shaftfe.fatigue.methods import METHODS
    method = _str(f, "method", src, "analyses.fatigue", "seed", tuple(METHODS))
    for key, option in FATIGUE_KEY_OPTIONS.items():
        if key in f and method not in methods_of(option):
            raise InputError(src, f"analyses.fatigue.{key}",
                             f"only with method = {' | '.join(methods_of(option))}", got=f[key],
                             reason=f"is not used by method {method}")
    return method


def _analyses(t: dict, src: str, base_dir: Path) -> Analyses:
    from shaftfe.fatigue.kernels import EQUIVALENT_STRESSES, MEAN_STRESS_THEORIES
    from shaftfe.solid.levels import LEVEL_NAMES
    _keys(t, set(ANALYSES), src, "analyses")
    kw: dict[str, Any] = {}

    def sub(name: str, allowed: set) -> dict | None:
        v = t.get(name, False)
        if v is False:
            return None
        if v is True:
            return {}
        return _keys(v, allowed, src, f"analyses.{name}")
    if (b := sub("balance", {"engine", "X_percent", "rpm"})) is not None:
        kw["engine"] = _str(b, "engine", src, "analyses.balance", "vm450")
        kw["X_percent"] = _num(b, "X_percent", src, "analyses.balance", None, lo=0, hi=200)
        kw["engine_rpm"] = _num(b, "rpm", src, "analyses.balance", None, lo=1, hi=20_000)
    kw["beam"] = sub("beam", set()) is not None if "beam" in t else True
    if (s := sub("static", {"model", "level", "spin_softening", "seed_load_case"})) is not None:
        # the full 3D solid or the zoned model (its global axisymmetric model gives the
        # reactions, its zones the keyways' peaks); the axisymmetric model alone has no
        # keyway peaks for the row
        kw["static_model"] = _str(s, "model", src, "analyses.static", "solid",
                                  ("solid", "zoned"))
        kw.update(static=True,
                  level=_str(s, "level", src, "analyses.static", "coarse", LEVEL_NAMES))
        sp = s.get("spin_softening", True)
        if not isinstance(sp, bool):
            raise InputError(src, "analyses.static.spin_softening", "true | false", got=sp)
        kw["spin_softening"] = sp
        slc = s.get("seed_load_case", False)
        if not isinstance(slc, bool):
            raise InputError(src, "analyses.static.seed_load_case", "true | false", got=slc)
        kw["seed_load_case"] = slc
    if (f := sub("fatigue", {"method", "spectrum", "material", "mean_stress", "equivalent",
                             "design_life_blocks", "speed_kmh"})) is not None:
        if "static" not in kw:
            raise InputError(src, "analyses.fatigue", "with [analyses.static] (fatigue scales "
                             "the static stress field)", reason="needs the static analysis")
        spec = _str(f, "spectrum", src, "analyses.fatigue")
        if spec is None:
            raise InputError(src, "analyses.fatigue.spectrum", "an rpm history file",
                             reason="is missing")
        p = Path(spec) if Path(spec).is_absolute() else (base_dir / spec)
        if not p.is_file():
            raise InputError(src, "analyses.fatigue.spectrum", "an existing file (relative to "
                             "the study file)", got=spec)
        kw.update(fatigue=True, spectrum=str(p.resolve()),
                  fatigue_method=_fatigue_method(f, src),
                  material=_str(f, "material", src, "analyses.fatigue", "structural_steel"),
                  mean_stress=_str(f, "mean_stress", src, "analyses.fatigue", "soderberg",
                                   MEAN_STRESS_THEORIES),
                  equivalent=_str(f, "equivalent", src, "analyses.fatigue", "von_mises",
                                  EQUIVALENT_STRESSES[:2]),
                  design_life=_num(f, "design_life_blocks", src, "analyses.fatigue", 1e7,
                                   lo=1, hi=1e12),
                  speed_kmh=_num(f, "speed_kmh", src, "analyses.fatigue", 70.0, lo=1, hi=400))
    if (c := sub("campbell", {"model", "max_rpm", "step_rpm"})) is not None:
        kw.update(campbell=True,
                  campbell_model=_str(c, "model", src, "analyses.campbell", "beam", ("beam",)),
                  campbell_max_rpm=_num(c, "max_rpm", src, "analyses.campbell", None, lo=100,
                                        hi=60_000),
                  campbell_step_rpm=_num(c, "step_rpm", src, "analyses.campbell", 250.0,
                                         lo=1, hi=5000))
    if (br := sub("bearings", {"rpm"})) is not None:
        kw["bearing_rpm"] = _num(br, "rpm", src, "analyses.bearings", 7000.0, lo=1, hi=20_000)
    return Analyses(**kw)


def load_study(path: str | Path) -> StudySpec:
    """Read and check a study file (InputError naming the file and the field)."""
    p = Path(path)
    src = str(path)
    try:
        raw = p.read_bytes()
        t = tomllib.loads(raw.decode("utf-8"))
    except FileNotFoundError:
        raise InputError(src, "file", "an existing study file (TOML)",
                         reason="does not exist") from None
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise InputError(src, "file", "a readable TOML file",
                         reason=f"cannot be read ({str(exc).splitlines()[0]})") from None
    _keys(t, _TOP, src, "top level")
    st = _keys(t.get("study", {}), {"name", "base", "description", "max_designs"}, src,
               "study")
    name = _str(st, "name", src, "study", p.stem)
    if not re.fullmatch(r"[A-Za-z0-9_][A-Za-z0-9_.+-]*", name):
        raise InputError(src, "study.name", "letters, digits, _ . + - (a folder name)",
                         got=name)
    desc = st.get("description", "")
    if not isinstance(desc, str):
        raise InputError(src, "study.description", "a string", got=desc)
    base = _str(st, "base", src, "study")
    if base is None:
        raise InputError(src, "study.base", "a variant name or file", reason="is missing")
    bp = p.parent / base
    if base.endswith(".toml") and not Path(base).is_absolute() and bp.is_file():
        base = str(bp.resolve())
    sm = _keys(t.get("sampling", {}), {"method", "samples", "seed"}, src, "sampling")
    method = _str(sm, "method", src, "sampling", "grid", METHODS)
    samples = _num(sm, "samples", src, "sampling", 0, lo=1, hi=1_000_000, integer=True)
    seed = _num(sm, "seed", src, "sampling", 0, lo=0, hi=2**32 - 1, integer=True)
    if method == "lhs" and not samples:
        raise InputError(src, "sampling.samples", "an integer >= 1 (the Latin hypercube's "
                         "size)", reason="is missing")
    plist = t.get("parameters", [])
    if not isinstance(plist, list):
        raise InputError(src, "parameters", "[[parameters]] tables", got=plist)
    params = tuple(_parameter(i, _keys(q, {"name", "path", "paths", "values", "min", "max",
                                           "n"}, src, f"parameters[{i}]"), src, method)
                   for i, q in enumerate(plist))
    if method == "lhs" and any(q.values for q in params):
        raise InputError(src, "parameters", "min/max ranges for a Latin hypercube",
                         reason="has a parameter with values")
    designs: tuple = ()
    if method == "list":
        dl = t.get("designs")
        if not (isinstance(dl, list) and dl and all(isinstance(d, dict) and d for d in dl)):
            raise InputError(src, "designs", "[[designs]] tables of path = value (method = "
                             "\"list\")", reason="is missing")
        designs = tuple(tuple(sorted(_flatten(d).items())) for d in dl)
    elif "designs" in t:
        raise InputError(src, "designs", "only with sampling.method = \"list\"",
                         reason="is given")
    if method != "list" and not params:
        raise InputError(src, "parameters", "at least one [[parameters]] table",
                         reason="is missing")
    names = [q.name for q in params]
    if len(set(names)) != len(names):
        raise InputError(src, "parameters", "distinct names", got=names)
    an = _analyses(t.get("analyses", {}), src, p.parent)
    out = _keys(t.get("outputs", {}), {"columns", "objectives", "require"}, src, "outputs")
    cols = out.get("columns", [])
    if not (isinstance(cols, list) and all(isinstance(c, str) and known_column(c)
                                           for c in cols)):
        raise InputError(src, "outputs.columns", "a list of result columns: " + ", ".join(FIXED)
                         + " or " + ", ".join(p + "…" for p in PREFIXES), got=cols)
    objs = []
    for o in out.get("objectives", []):
        col, _, sense = str(o).partition(":")
        if sense not in ("min", "max") or not known_column(col):
            raise InputError(src, "outputs.objectives", "\"column:min\" or \"column:max\" on a "
                             "result column, e.g. \"engine_max_F_N:min\"", got=o)
        objs.append((col, sense))
    reqs = out.get("require", [])
    if not isinstance(reqs, list):
        raise InputError(src, "outputs.require", "a list of \"column >= number\"", got=reqs)
    reqs = tuple(parse_requirement(r, src) for r in reqs)
    for col in [c for c, _ in objs] + [c for c, _, _ in reqs]:
        need = _needs(col)
        if col in TEXT_COLUMNS:
            raise InputError(src, "outputs", "objectives and requirements on a numeric column",
                             got=col)
        if need and not getattr(an, need):
            raise InputError(src, "outputs", f"[analyses.{need}] for the column {col}",
                             got=col, reason="is not computed")
    maxd = _num(st, "max_designs", src, "study", MAX_DESIGNS_DEFAULT, lo=1, hi=10_000_000,
                integer=True)
    digest = hashlib.sha256(json.dumps(t, sort_keys=True, default=str).encode()).hexdigest()
    return StudySpec(path=src, name=name, base=base, description=desc,
                     method=method, parameters=params, samples=samples, seed=seed,
                     designs=designs, analyses=an, columns=tuple(cols),
                     objectives=tuple(objs), requirements=reqs, max_designs=maxd, digest=digest)


def _flatten(d: dict, prefix: str = "") -> dict:
    """A [[designs]] table: quoted dotted keys ("a.b" = 1) or nested tables (a.b = 1)."""
    out = {}
    for k, v in d.items():
        key = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(_flatten(v, key + "."))
        else:
            out[key] = v
    return out


MAX_WITH_YES = 10_000_000          # designs in one study even with --yes (the table's size)


def check_count(spec: StudySpec, n: int, *, yes: bool = False) -> None:
    """Too many designs (``n``, counted before they are made) without ``yes``, or at all."""
    if n > MAX_WITH_YES:
        raise InputError(spec.path, "sampling", f"at most {MAX_WITH_YES:,} designs in one "
                         "study (split it)", got=n, reason="asks for more designs")
    if n > spec.max_designs and not yes:
        raise InputError(spec.path, "sampling", f"at most {spec.max_designs} designs "
                         "(study.max_designs) without --yes", got=n,
                         reason="asks for more designs")


def check_designs(spec: StudySpec, designs) -> None:
    """Bad input before anything runs: a path the base variant does not have (nearest names
    listed), a value of the wrong kind or outside its key's own range
    (``shaftfe.model.fields.key_range``). InputError naming the study file."""
    import copy

    from shaftfe.model import overrides as ov
    from shaftfe.model.fields import is_num, key_range
    from shaftfe.model.parse import resolve_path, resolved_dict
    merged = resolved_dict(resolve_path(spec.base))
    seen: set[tuple[str, str]] = set()
    for d in designs:
        for path, value in d.overrides:
            where = f"parameter {path}"
            kind = type(value).__name__ if not is_num(value) else "number"
            if (path, kind) not in seen:                 # every kind of value once per path
                seen.add((path, kind))
                try:
                    ov.apply(copy.deepcopy(merged), ov.normalise({path: value}))
                except InputError as exc:
                    raise InputError(spec.path, where, exc.allowed, reason=(
                        f"does not fit the base variant ({exc.field} = {exc.got!r})")) from None
            rng = key_range(path)
            if rng is not None and is_num(value):
                lo, hi, unit = rng
                if not (math.isfinite(value) and lo <= value <= hi):
                    raise InputError(spec.path, where, f"in [{lo:g}, {hi:g}] {unit} (the "
                                     "key's range, docs/VARIANTS.md)", got=value)


# ------------------------------------------------- a design's refusal in the study's terms

def _shown(v) -> str:
    return f"{v:g}" if isinstance(v, float) else repr(v)


def parameter_of(spec: StudySpec, path: str) -> str:
    """How the study file names the parameter that sets ``path``."""
    for q in spec.parameters:
        if path in q.paths:
            return f"parameter '{q.name}'" if q.name != path else f"parameter {path}"
    return f"parameter {path}"


_HINTS = (" (typed in grams?)", " (typed in metres?)", " (typed in µm?)", " (typed in tonnes?)")


def refusal(spec: StudySpec | None, overrides, exc: InputError) -> tuple[str, str]:
    """(reason, rule) of the loader's refusal of a design, in the study's terms: a key the
    study set is named as its parameter with the value the file gives; a key derived from the
    parameters (a counterweight's mass from its shape, the [balance] statement) as derived from
    them (no "typed in grams?": nobody typed it). ``rule``: the reason without the design's
    values (designs refused by one rule are listed together)."""
    ov = dict(overrides)
    src = str(exc.source)
    allowed = str(exc.allowed)
    for h in _HINTS:
        allowed = allowed.replace(h, "")
    rule = f"{exc.field}: allowed {allowed}"
    path = src[len("--set "):].split("=", 1)[0] if src.startswith("--set ") else None
    if path in ov:
        name = parameter_of(spec, path) if spec else f"parameter {path}"
        what = "" if exc.field == path else f" ({exc.field} = {exc.got!r})"
        return f"{name} = {_shown(ov[path])}{what} is refused; allowed: {exc.allowed}", rule
    part = path.split(".")[1] if path and path.startswith("attachments.") else None
    causes = [p for p in ov if part and p.startswith(f"attachments.{part}.shape.")] or list(ov)

    def label(p: str) -> str:
        name = parameter_of(spec, p) if spec else f"parameter {p}"
        return name if name.endswith(p) else f"{name} ({p})"
    given = ", ".join(f"{label(p)} = {_shown(ov[p])}" for p in causes)
    return (f"{exc.field} = {_shown(exc.got)} (derived from {given}) is refused; allowed: "
            f"{allowed}"), rule
