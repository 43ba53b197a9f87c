"""The measured discretisation error of each mesh level, for the report and ``shaftfe fatigue``.

Fillet peaks (issue #12): ``reports/benchmarks/truth.json`` (written by
``benchmarks/bench_truth.py``: x2_57, springs, all parts, 10 000 rpm) holds each level's 3D peak
von Mises stress of the collar and bearing-seat-gear fillets next to the TRUTH, the
axisymmetric path converged by Richardson. (The 3D levels' own Richardson extrapolation, used
before, shares their stress recovery's bias and is not a truth.)

Deflection: ``reports/benchmarks/static.json`` (``benchmarks/bench_static.py``): its
reference q* is the Richardson extrapolation of the P2 default and fine runs with the fillet
size ratio r and p = 3 (a displacement carries no recovery bias).

The report and ``shaftfe fatigue`` quote a level's error, and correct the hot spot's life by
it, only where the benchmark ran on this level's current mesh (``bench_matches``).
"""

from __future__ import annotations

import json
from pathlib import Path

from shaftfe.util.paths import BENCHMARK_JSON, TRUTH_JSON, repo_relative

DOF_MATCH_RTOL = 0.10     # the all-parts load case splits the seats a little differently
_REGIONS = {"collar": "fillet:collar", "bsg": "fillet:bearing_seat_gear"}


def benchmark_errors(level: str, order: int = 2, path: Path = BENCHMARK_JSON,
                     truth_path: Path = TRUTH_JSON) -> dict | None:
    """Relative errors of ``level`` (module docstring): ``collar`` and ``bsg`` against the
    truth, ``defl`` against the deflection benchmark (absent if that file lacks the runs).
    None when the truth file or this level's runs are missing."""
    if order != 2:
        return None
    try:
        recs = json.loads(Path(truth_path).read_text())["records"]
    except (OSError, ValueError, KeyError, TypeError):
        return None
    out = {"source": repo_relative(truth_path), "level": level, "order": order}
    for key, region in _REGIONS.items():
        r = next((r for r in recs if r.get("case") == f"x2_57 {region}"
                  and r.get("level") == level and r.get("quantity") == "von_mises"), None)
        if r is None:
            return None
        out["dofs"] = r.get("dofs")
        out[key] = {"level_value": r["value_MPa"], "reference": r["truth_MPa"],
                    "rel_error": r["value_MPa"] / r["truth_MPa"] - 1.0}
    defl = _deflection_error(level, order, path)
    if defl is not None:
        out["defl"] = defl
    return out


def _deflection_error(level: str, order: int, path: Path) -> dict | None:
    from shaftfe.solid.levels import LEVELS
    try:
        rows = json.loads(Path(path).read_text())
    except (OSError, ValueError):
        return None

    def one(lv, o=2):
        return next((r for r in rows if r.get("level") == lv and r.get("order") == o), None)
    d, f, me = one("default"), one("fine"), one(level, order)
    r = LEVELS["default"].k_fillet / LEVELS["fine"].k_fillet
    if d is None or f is None or me is None or r <= 1:
        return None
    q = f["defl"] + (f["defl"] - d["defl"]) / (r ** 3 - 1.0)
    return {"level_value": me["defl"], "reference": q, "rel_error": me["defl"] / q - 1.0,
            "source": repo_relative(path)}


def bench_matches(bench: dict | None, n_dofs: int, tol: float = DOF_MATCH_RTOL) -> bool:
    """The benchmark was run on this level's current mesh: its dof count within ``tol`` of
    this run's."""
    return bool(bench) and bool(bench.get("dofs")) and abs(bench["dofs"] / n_dofs - 1) <= tol
