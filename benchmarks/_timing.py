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


# a small child that runs the command line and reports the peak memory of ITS child: ru_maxrss
# of RUSAGE_CHILDREN is the largest over all children so far, and a process forked from a big
# one starts with the parent's RSS, so the command is measured from this small wrapper
_PEAK = ("import resource, subprocess, sys\n"
         "r = subprocess.run(sys.argv[2:]).returncode\n"
         "kb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss\n"
         "open(sys.argv[1], 'w').write(str(kb))\n"
         "sys.exit(r)\n")


def process(cmd: list[str], cwd: str, env: dict | None = None) -> dict:
    """One whole process of ``cmd`` (in ``cwd``, with ``env`` added to this environment): its
    wall time (``time.perf_counter`` around it), the CPU seconds of the child and its peak
    resident memory (MiB, Linux ``ru_maxrss``: the largest of its processes). Python writes
    and reuses its bytecode (``PYTHONDONTWRITEBYTECODE`` is dropped), as an installed package
    does: without it every run compiles the package's modules again (0.18 s of a warm
    ``shaftfe static``)."""
    import os
    import resource
    import subprocess
    import sys
    import tempfile
    with tempfile.NamedTemporaryFile(suffix=".rss", delete=False) as fh:
        rss = fh.name
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", _PEAK, rss, *cmd], cwd=cwd, check=True,
                   capture_output=True,
                   env={**{k: v for k, v in os.environ.items()
                           if k != "PYTHONDONTWRITEBYTECODE"}, **(env or {})})
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    kb = float(open(rss).read())
    os.unlink(rss)
    return {"wall_s": wall, "cpu_s": (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime),
            "max_rss_MiB": kb / 1024.0}
