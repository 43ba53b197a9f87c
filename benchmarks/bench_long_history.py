"""Long rpm histories: `shaftfe fatigue` on data-logger traces of up to 5 million samples (14 h at
100 Hz), whole process, against the same history's life from the straightforward path.

Histories (seeded, written to a temporary folder, rpm format, 100 Hz, integer rpm as a logger
records them):
* ``riding``: a speed wandering between 1200 and 9500 rpm (an Ornstein-Uhlenbeck process around
  a slowly varying set speed) with ±20 rpm sensor noise: 1.5 million cycles per 5 million samples.
* ``white``: every sample drawn anew over 1500-9500 rpm; every cycle is large, so every node
  does damage in every class: the worst case of the nodes × classes evaluation.

The whole x2_57 default field (every part loaded) is evaluated; the static solution is cached first
(not timed). Reported: wall and CPU time of the process, peak RSS, cycles and distinct classes,
and the hot spot's life. Check: the life of a 100 000-sample prefix of each history from
``shaftfe.fatigue`` equals the life from a direct evaluation of every class at the hot-spot node
(``kernels._damage``, no pruning) to round-off.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "reports" / "benchmarks" / "long_history.md"
SIZES = {"riding": (100_000, 1_000_000, 5_000_000),
         "white": (100_000, 1_000_000)}       # white 5 M: ≈ 40 s, left out


def history(kind: str, n: int, seed: int = 7) -> np.ndarray:
    rng = np.random.default_rng(seed)
    if kind == "white":
        return np.round(1500 + 8000 * rng.random(n))
    from scipy.signal import lfilter
    dt = 0.01
    target = 4000 + 2500 * np.sin(np.arange(n) * dt / 60.0)
    a = np.exp(-dt / 2.0)
    x = lfilter([1 - a], [1, -a], target + 3000 * rng.standard_normal(n))
    return np.clip(np.round(x + 20 * rng.standard_normal(n)), 1200, 9500)


def write(path: Path, rpm: np.ndarray) -> None:
    with open(path, "w") as f:
        f.write("# format = rpm\n# sample_rate_hz = 100\n")
        np.savetxt(f, rpm, fmt="%.0f")


def run(path: Path, out: Path, env: dict) -> dict:
    """One `shaftfe fatigue` process; its own CPU time and peak RSS (os.wait4 on its pid)."""
    t0 = time.perf_counter()
    p = subprocess.Popen([sys.executable, "-m", "shaftfe", "fatigue", str(path), "--out",
                          str(out), "--json"], stdout=subprocess.PIPE, text=True, env=env)
    text = p.stdout.read()
    _, status, ru = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    if p.returncode != 0:
        raise RuntimeError(f"shaftfe fatigue {path} failed ({p.returncode})")
    s = json.loads(text)
    return {"wall_s": wall, "cpu_s": ru.ru_utime + ru.ru_stime, "rss_mib": ru.ru_maxrss / 1024,
            "cycles": s["cycles"]["per_block"], "classes": s["cycles"]["classes"],
            "life_blocks": s["result"]["life_blocks"], "eval_s": s["timing"]["fatigue_seconds"],
            "nodes": s["static"]["n_nodes"]}


def check_prefix(kind: str) -> float:
    """Largest relative difference of the damage over every 10th node of the field, 100 000-
    sample prefix: the field evaluation (pruned, banded where the budget says so) against the
    full sum over every class at those nodes (``kernels._damage``)."""
    from shaftfe.fatigue import kernels
    from shaftfe.fatigue.field import evaluate
    from shaftfe.fatigue.history import from_rpm
    from shaftfe.fatigue.sn import load_material
    from shaftfe.model.loader import load_variant
    from shaftfe.static import solve as static_solve
    from shaftfe.static.model import StaticOptions
    ref = static_solve.load_or_solve(load_variant("x2_57"), StaticOptions())
    h = from_rpm(history(kind, 100_000), sample_rate_hz=100.0)
    mat = load_material("structural_steel")
    ff = evaluate(ref, h, mat)
    nodes = np.arange(0, ff.n_nodes, 10)
    full = kernels._damage(ff.result.sigma_eq_MPa[nodes], ff.result.cycles, mat, "soderberg",
                           1.0)
    got = ff.result.damage_per_block[nodes]
    ok = np.isfinite(full) & (full > 0)
    if not (np.array_equal(np.isinf(full), np.isinf(got)) and np.array_equal(full == 0,
                                                                             got == 0)):
        return float("inf")
    return float(np.max(np.abs(got[ok] / full[ok] - 1.0))) if ok.any() else 0.0


def main() -> None:
    env = dict(os.environ, MPLBACKEND="Agg")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        write(tmp / "warm.dat", history("riding", 1000))
        run(tmp / "warm.dat", tmp / "o", env)             # the static solution into the cache
        for kind, sizes in SIZES.items():
            for n in sizes:
                f = tmp / f"{kind}_{n}.dat"
                write(f, history(kind, n))
                r = run(f, tmp / f"o_{kind}_{n}", env)
                rows.append({"kind": kind, "samples": n, **r})
                print(f"{kind:7s} {n:>9,d} samples: {r['wall_s']:.1f} s wall, "
                      f"{r['cpu_s']:.1f} s CPU, {r['rss_mib']:.0f} MiB, {r['classes']} classes")
    checks = {k: check_prefix(k) for k in ("riding", "white")}
    lines = ["# Long rpm histories: `shaftfe fatigue` run time", "",
             "Written by `python -m benchmarks bench_long_history` (see its docstring). Whole "
             f"process, x2_57 default field ({rows[0]['nodes']:,} nodes, every part loaded), "
             "static solution cached, 2-core machine. White noise of 5 million samples is left "
             "out (≈ 40 s).", "",
             "| history | samples | cycles / block | classes | wall s | CPU s | of it evaluation s "
             "| peak RSS MiB | life blocks |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        life = "inf" if r["life_blocks"] is None else f"{r['life_blocks']:.4g}"
        lines.append(f"| {r['kind']} | {r['samples']:,} | {r['cycles']:,.0f} | {r['classes']:,} "
                     f"| {r['wall_s']:.1f} | {r['cpu_s']:.1f} | {r['eval_s']:.1f} | "
                     f"{r['rss_mib']:.0f} | {life} |")
    lines += ["", "Check, 100 000-sample prefix: damage of the field evaluation at every 10th "
              "node against the full sum over every class, largest relative difference: "
              + ", ".join(f"{k} {v:.1e}" for k, v in checks.items()) + ".", ""]
    from shaftfe.util.atomic import write_atomic
    write_atomic(OUT, "\n".join(lines))
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
