"""Where shaftfe finds its data and keeps its caches: the one home of every path.

The data ship with the source tree (an editable install or a clone): ``geometry/`` holds the
variants, the common tables (materials, bearing types, parts, S-N curves) and the engines;
``loadspectra/`` the rpm logs; ``reports/benchmarks/`` the measured run-time/error table that
the report quotes. The mesh and static caches live in ``cache_dir`` if given, else
``$SHAFTFE_CACHE_DIR``, else ``~/.cache/shaftfe``.
"""

from __future__ import annotations

import os
from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parent.parent       # shaftfe/
REPO_DIR = PACKAGE_DIR.parent                                # the source tree
GEOMETRY_DIR = REPO_DIR / "geometry"
COMMON_DIR = GEOMETRY_DIR / "common"
ENGINES_DIR = GEOMETRY_DIR / "engines"
SN_FILE = COMMON_DIR / "sn_curves.toml"
LOADSPECTRA_DIR = REPO_DIR / "loadspectra"
DEFAULT_SPECTRUM = LOADSPECTRA_DIR / "rpm.dat"
BENCHMARKS_DIR = REPO_DIR / "reports" / "benchmarks"    # the measured tables the package reads
BENCHMARK_JSON = BENCHMARKS_DIR / "static.json"
TRUTH_JSON = BENCHMARKS_DIR / "truth.json"
# the converged Kt tables (the axisymmetric model, 3 uniform refinements and Richardson), each
# written by its benchmark: shoulders, U grooves, DIN 509 undercuts, DIN 471 ring grooves
KT_SHOULDERS_JSON, KT_GROOVES_JSON, KT_UNDERCUTS_JSON, KT_RING_GROOVES_JSON = (
    BENCHMARKS_DIR / f"kt_{name}.json" for name in ("reference", "grooves", "undercuts",
                                                     "ring_grooves"))
CACHE_ENV = "SHAFTFE_CACHE_DIR"


def cache_dir(explicit: str | os.PathLike | None = None) -> Path:
    """The mesh and static cache directory (see the module docstring)."""
    if explicit is not None:
        return Path(explicit)
    env = os.environ.get(CACHE_ENV)
    return Path(env) if env else Path.home() / ".cache" / "shaftfe"


def repo_relative(path: str | os.PathLike) -> str:
    """``path`` relative to the source tree when it lies inside it, else as given."""
    try:
        p = Path(path).resolve()
    except OSError:
        return str(path)
    return str(p.relative_to(REPO_DIR)) if p.is_relative_to(REPO_DIR) else str(path)
