"""Shared timing helper for the benchmarks (wall time, best of several runs)."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any


def best_of(fn: Callable[[], Any], repeat: int = 5) -> tuple[float, Any]:
    """Run ``fn`` ``repeat`` times; return (best wall time in s, the last result)."""
    best, out = float("inf"), None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return best, out


def best_time(fn: Callable[[], Any], repeat: int = 5) -> float:
    """Best wall time in s of ``repeat`` runs of ``fn``."""
    return best_of(fn, repeat)[0]
