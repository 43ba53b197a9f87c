"""The measured discretisation error of each mesh level, from the static benchmark.

``reports/benchmarks/static.json`` (written by ``benchmarks/bench_static.py``: x2_57, springs,
all parts, 10 000 rpm) holds the peak fillet stresses and the deflection of every level; its
reference q* is the Richardson extrapolation of the P2 default and fine runs with the fillet
size ratio r and p = 2 for stress, 3 for deflection (the benchmark's own rule). The report and
``shaftfe fatigue`` quote a level's error against it, and correct the hot spot's life by it,
only where the benchmark ran on this level's current mesh (``bench_matches``).
"""

from __future__ import annotations

import json
from pathlib import Path

from shaftfe.util.paths import BENCHMARK_JSON, repo_relative

DOF_MATCH_RTOL = 0.10     # the all-parts load case splits the seats a little differently


def benchmark_errors(level: str, order: int = 2, path: Path = BENCHMARK_JSON) -> dict | None:
    """Relative errors of ``level`` against the benchmark's reference (module docstring).
    None when the file or the runs are missing."""
    from shaftfe.solid.levels import LEVELS
    try:
        rows = json.loads(Path(path).read_text())
    except (OSError, ValueError):
        return None

    def one(lv):
        return next((r for r in rows if r.get("level") == lv and r.get("order") == 2), None)
    d, f, me = one("default"), one("fine"), next(
        (r for r in rows if r.get("level") == level and r.get("order") == order), None)
    if d is None or f is None or me is None:
        return None
    r = LEVELS["default"].k_fillet / LEVELS["fine"].k_fillet
    if r <= 1:
        return None
    out = {"source": repo_relative(path), "level": level, "order": order, "dofs": me.get("dofs")}
    for k, p in (("collar", 2), ("bsg", 2), ("defl", 3)):
        q = f[k] + (f[k] - d[k]) / (r ** p - 1.0)
        out[k] = {"level_value": me[k], "reference": q, "rel_error": me[k] / q - 1.0}
    return out


def bench_matches(bench: dict | None, n_dofs: int, tol: float = DOF_MATCH_RTOL) -> bool:
    """The benchmark was run on this level's current mesh: its dof count within ``tol`` of
    this run's."""
    return bool(bench) and bool(bench.get("dofs")) and abs(bench["dofs"] / n_dofs - 1) <= tol
