"""FKM against the seed method on a long rpm log (issue 30 §2): `shaftfe fatigue --method fkm`
must take no longer than `--method seed` (±20 %) on the same history, counted once.

History (generated here, seeded): 5 million samples at 100 Hz (13.9 h), every sample drawn
uniformly from 1200-9000 rpm and rounded to whole rpm as a logger records them: every sample is
a reversal, about 1.5 million distinct rainflow classes, the hardest case for every
per-class evaluation. Mesh level coarse, x2_57, the static solution from the cache (solved
first, not timed).

Both methods are run as whole processes (wall and CPU time of the process, peak RSS) in two
trees side by side, in one run: BEFORE (``git worktree`` of ``BENCH_BEFORE``, default ``main``,
its own code imported) and this tree. A run still going after ``TIMEOUT_S`` is stopped and
reported as "> TIMEOUT_S" (main's FKM: the classes were summed again for every step of every
safety-factor bisection, hours on this history).

Accuracy (the FKM numbers must not change beyond round-off: FKM evaluates every class, no
binning): (1) main and this tree on the seed's rpm.dat and on a 20 000-sample prefix of the
history (main's FKM finishes on it): the largest relative difference of any number in the
summaries; (2) on the full history, this tree's governing check against a direct evaluation of
every class (``reference_life``: the Miner sums written out class by class, the consistent
rule's interval sum as a loop), lives at the computed safety factor: they must be the design
life (or, for the consistent rule, λ* is the load at which its life jumps from ∞: the largest
cycle at the knee).
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "reports" / "benchmarks" / "fkm_speed.md"
N_SAMPLES = int(os.environ.get("BENCH_FKM_SAMPLES", 5_000_000))   # smaller: a dry run
RATE_HZ = 100.0
RPM_RANGE = (1200.0, 9000.0)
PREFIX = min(20_000, N_SAMPLES)
TIMEOUT_S = 300.0
BEFORE = os.environ.get("BENCH_BEFORE", "main")


def history(n: int = N_SAMPLES, seed: int = 30) -> np.ndarray:
    """Uniform random whole rpm in RPM_RANGE, ``n`` samples."""
    rng = np.random.default_rng(seed)
    lo, hi = RPM_RANGE
    return np.round(lo + (hi - lo) * rng.random(n))


def write(path: Path, rpm: np.ndarray) -> Path:
    with open(path, "w") as f:
        f.write(f"# format = rpm\n# sample_rate_hz = {RATE_HZ:g}\n")
        np.savetxt(f, rpm, fmt="%.0f")
    return path


def run(tree: Path, spectrum: Path, method: str, out: Path, timeout: float = TIMEOUT_S):
    """One `shaftfe fatigue` process of ``tree``: (wall s, CPU s, peak RSS MiB, summary dict
    or None when stopped at ``timeout``); CPU and RSS of that process (os.wait4 on its pid)."""
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=str(tree))
    out.mkdir(parents=True, exist_ok=True)
    log = out.parent / f"{out.name}.json.txt"
    t0 = time.perf_counter()
    with open(log, "w") as f:
        p = subprocess.Popen([sys.executable, "-m", "shaftfe", "fatigue", str(spectrum),
                              "--method", method, "--level", "coarse", "--out", str(out),
                              "--json"], cwd=tree, env=env, stdout=f,
                             stderr=subprocess.DEVNULL)
        while True:
            pid, status, ru = os.wait4(p.pid, os.WNOHANG)
            if pid:
                break
            if time.perf_counter() - t0 > timeout:
                p.kill()                          # our own child, by its handle
                os.wait4(p.pid, 0)
                p.returncode = -9
                return time.perf_counter() - t0, math.nan, math.nan, None
            time.sleep(0.1)
    wall = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    if p.returncode != 0:
        raise RuntimeError(f"{tree}: fatigue --method {method} {spectrum} failed "
                           f"({p.returncode})")
    return (wall, ru.ru_utime + ru.ru_stime, ru.ru_maxrss / 1024,
            json.loads(log.read_text()))


def max_rel_diff(a, b, path: str = "") -> tuple[float, str]:
    """Largest relative difference of the numbers of two JSON trees (inf: a structural or
    non-numeric difference), and where."""
    if isinstance(a, dict) and isinstance(b, dict):
        return max([max_rel_diff(a[k], b.get(k), f"{path}.{k}") for k in a
                    if k not in ("timing", "seconds", "from_cache")] or [(0.0, path)])
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        return max([max_rel_diff(x, y, f"{path}[{i}]") for i, (x, y) in
                    enumerate(zip(a, b, strict=True))] or [(0.0, path)])
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and \
            not isinstance(a, bool):
        if a == b:
            return 0.0, path
        return abs(b - a) / max(abs(a), abs(b)), path
    return (0.0, path) if a == b else (math.inf, path)


def compare(before: dict, after: dict) -> tuple[float, str]:
    """The FKM result blocks (governing, regions) of two summaries."""
    return max(max_rel_diff(before[k], after[k], k) for k in ("governing", "regions"))


def reference_life(s: np.ndarray, c: np.ndarray, rule: str, damage_sum: float,
                   k: float = 5.0, n_d: float = 1e6) -> float:
    """Blocks to D_M under one Miner rule, every class summed directly (FKM ch. 4.4):
    elementary Σ n s^k / N_D; modified s^(2k−1) below the knee; consistent: the classes
    switch on at D/D_M = 1 − s^k in turn, blocks = D_M Σ ΔD/rate over the intervals (a loop)."""
    keep = (s > 0) & (c > 0)
    s, c = s[keep], c[keep]
    if rule == "elementary":
        return damage_sum / (float(np.sum(c * s ** k)) / n_d)
    if rule == "modified":
        return damage_sum / (float(np.sum(np.where(s >= 1, c * s ** k,
                                                   c * s ** (2 * k - 1)))) / n_d)
    if not np.any(s >= 1):
        return math.inf
    start = np.where(s >= 1, 0.0, 1.0 - s ** k)
    o = np.argsort(start, kind="stable")
    w = (c * s ** k / n_d)[o].tolist()
    edges = np.append(start[o], 1.0).tolist()
    blocks, rate = 0.0, 0.0
    for j, wj in enumerate(w):
        rate += wj
        blocks += (edges[j + 1] - edges[j]) * damage_sum / rate
    return blocks


def check_long(spectrum: Path) -> dict:
    """This tree's FKM on the full history: the governing check's lives at its own safety
    factor λ* (each rule), by ``reference_life``: relative distance to the design life."""
    from shaftfe.fatigue import strength as sd
    from shaftfe.fatigue.fkm_field import governing_cycles
    from shaftfe.fatigue.run import FatigueJob
    job = FatigueJob(spectrum=str(spectrum), level="coarse", model="solid")
    res, _, _ = sd.run_fkm(job, sd.StrengthOptions())
    reg, chk = res.governing
    gc = governing_cycles(res)
    out = {"classes": int(res.cycles.n), "region": reg.region, "layer": chk.layer}
    for rule in ("elementary", "modified", "consistent"):
        lam = chk.safety[rule]
        life_at = reference_life(lam * gc["s"], gc["count"], rule, res.damage_sum)
        life_1 = reference_life(gc["s"], gc["count"], rule, res.damage_sum)
        # the consistent rule's life jumps from ∞ to finite where the largest cycle reaches
        # the knee; λ* is that jump when the life there is already below the design life
        jump = rule == "consistent" and life_at < res.design_life_blocks
        out[rule] = {"safety": lam, "jump": jump,
                     "life_at_safety_rel_err": abs(lam * float(gc["s"].max()) - 1.0) if jump
                     else abs(life_at / res.design_life_blocks - 1.0),
                     "life_rel_err": abs(chk.life_blocks[rule] / life_1 - 1.0)
                     if math.isfinite(life_1) else 0.0}
    return out


def main() -> None:
    rows, acc = [], {}
    with tempfile.TemporaryDirectory(prefix="bench-fkm-") as tmp:
        tmp = Path(tmp)
        old = tmp / "before"
        subprocess.run(["git", "worktree", "add", "--detach", "-q", str(old), BEFORE],
                       cwd=ROOT, check=True)
        try:
            rpm = history()
            long_f = write(tmp / "uniform_5M.dat", rpm)
            pre_f = write(tmp / f"uniform_{PREFIX}.dat", rpm[:PREFIX])
            rpm_dat = ROOT / "loadspectra" / "rpm.dat"
            run(ROOT, rpm_dat, "seed", tmp / "warm")       # the static solution into the cache
            for name, f in (("rpm.dat", rpm_dat), (f"prefix {PREFIX:,}", pre_f)):
                a = run(old, f, "fkm", tmp / "a")[3]
                b = run(ROOT, f, "fkm", tmp / "b")[3]
                acc[name] = compare(a, b)
            for tree, label in ((old, f"before ({BEFORE})"), (ROOT, "after (this tree)")):
                for method in ("seed", "fkm"):
                    wall, cpu, rss, s = run(tree, long_f, method, tmp / f"o-{label}-{method}")
                    rows.append({"tree": label, "method": method, "wall_s": wall,
                                 "cpu_s": cpu, "rss_mib": rss, "finished": s is not None})
                    print(f"{label} {method}: {wall:.1f} s"
                          + ("" if s is not None else " (stopped)"), flush=True)
        finally:
            subprocess.run(["git", "worktree", "remove", "--force", str(old)], cwd=ROOT)
        long_chk = check_long(long_f)
    after = {r["method"]: r for r in rows if r["tree"].startswith("after")}
    data = {"rows": rows, "accuracy": {k: list(v) for k, v in acc.items()}, "long": long_chk,
            "fkm_over_seed": after["fkm"]["wall_s"] / after["seed"]["wall_s"]}
    from shaftfe.util.atomic import write_atomic
    write_atomic(OUT.with_suffix(".json"), json.dumps(data, indent=1) + "\n")
    write_report(data)


def write_report(data: dict) -> None:
    """fkm_speed.md from the measurements (``python -m benchmarks.bench_fkm_speed report``
    re-renders it from fkm_speed.json)."""
    from shaftfe.util.atomic import write_atomic
    rows, acc, long_chk, ratio = (data["rows"], data["accuracy"], data["long"],
                                  data["fkm_over_seed"])

    def t(r):
        return f"{r['wall_s']:.1f}" if r["finished"] else f"> {TIMEOUT_S:.0f} (stopped)"
    lines = ["# FKM against the seed method on a 5-million-sample log", "",
             "Written by `python -m benchmarks bench_fkm_speed` (see its docstring). Whole "
             f"`shaftfe fatigue` processes, x2_57, `--level coarse`, static solution cached; "
             f"{N_SAMPLES:,} samples at {RATE_HZ:g} Hz, uniform {RPM_RANGE[0]:.0f}-"
             f"{RPM_RANGE[1]:.0f} rpm (whole rpm), {long_chk['classes']:,} rainflow classes; "
             "2-core machine shared with other jobs.", "",
             "| tree | method | wall s | CPU s | peak RSS MiB |",
             "|---|---|---|---|---|"]
    for r in rows:
        cpu = "-" if not r["finished"] else f"{r['cpu_s']:.1f}"
        rss = "-" if not r["finished"] else f"{r['rss_mib']:.0f}"
        lines.append(f"| {r['tree']} | {r['method']} | {t(r)} | {cpu} | {rss} |")
    lines += ["", f"After: fkm / seed wall time = {ratio:.2f} (target ≤ 1.2).", "",
              "FKM numbers, main against this tree (every number of the governing and region "
              "blocks, largest relative difference; FKM sums every class, no binning, so "
              "only the summation order differs):", ""]
    for name, (d, where) in acc.items():
        lines.append(f"- {name}: {d:.1e} (at `{where}`)")
    lines += ["", f"Full history, governing check {long_chk['region']} ({long_chk['layer']}) "
              "against a direct class-by-class evaluation (`reference_life`):", ""]
    for rule in ("elementary", "modified", "consistent"):
        c = long_chk[rule]
        at = ("the jump (life ∞ below it): largest cycle's λ* s / knee − 1 = " if c["jump"]
              else "life at it / design life − 1 = ")
        one = ("∞ at λ = 1 (no cycle reaches the knee below λ* > 1), as the direct sum"
               if c["jump"] and c["safety"] > 1 else
               f"life at λ = 1 against the direct sum: {c['life_rel_err']:.1e}")
        lines.append(f"- {rule}: safety {c['safety']:.6g}; {at}"
                     f"{c['life_at_safety_rel_err']:.1e}; {one}")
    lines.append("")
    write_atomic(OUT, "\n".join(lines))
    print(f"wrote {OUT}")


if __name__ == "__main__":
    if sys.argv[1:] == ["report"]:
        write_report(json.loads(OUT.with_suffix(".json").read_text()))
    else:
        main()
