"""Identical results before and after a change that must not change any (the restructuring of
issue 14): summary.json of `static`, `fatigue`, `campbell`, `campbell --model solid --level
coarse` and `report` on x2_57, with the run-time blocks left out, byte for byte.

    python -m benchmarks.identical_results against COMMIT  # record COMMIT and this tree, compare
    python -m benchmarks.identical_results record DIR      # run the five commands into DIR
    python -m benchmarks.identical_results compare A B     # exit 1 if any summary differs

``against`` (``make identical BEFORE=<commit>``) checks COMMIT out into a temporary git
worktree, records it there (``python -m shaftfe`` run inside that checkout imports its own
code, with this environment's packages), records this tree, compares, and removes the worktree. The
mesh and static caches are bypassed by a fresh SHAFTFE_CACHE_DIR inside DIR,
so each record solves everything. Left out of the comparison, because they measure the run and
not the result: ``run``, ``timing``, ``timings(_s)``, ``sub_timings(_s)``, ``machine``,
``created_utc`` and every key named ``seconds``, ``*_seconds``, ``from_cache`` or
``mesh_from_cache``; and ``cache_key``, the static cache's key, which hashes the source code of
the static modules (``shaftfe.util.cachefile.code_fingerprint`` of
``static.cache.FINGERPRINT_MODULES``) so that any edit of that code
invalidates the cache: it changes with every code change by design and says nothing of the
result (the mesh key and the variant hash, which do describe the model, stay compared).
The checkout's own path (the default spectrum of ``report`` is an absolute path) is written as
``<repo>``, so records made in two checkouts (a worktree of the old commit) compare.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RUNS = {   # name -> (argv after `shaftfe`, the summary file inside --out)
    "static": (["static", "--variant", "x2_57"], "summary.json"),
    "fatigue": (["fatigue", "loadspectra/rpm.dat", "--variant", "x2_57"], "summary.json"),
    "campbell": (["campbell", "0:8000", "--variant", "x2_57"], "campbell.json"),
    "campbell_solid": (["campbell", "0:8000", "--variant", "x2_57", "--model", "solid",
                        "--level", "coarse"], "campbell.json"),
    "report": (["report", "--variant", "x2_57"], "summary.json"),
}
RUNTIME_KEYS = {"run", "timing", "timings", "timings_s", "sub_timings", "sub_timings_s",
                "machine", "seconds", "from_cache", "mesh_from_cache", "created_utc",
                "cache_key"}


def normalise(obj):
    """The summary without its run-time keys (see the module docstring)."""
    if isinstance(obj, dict):
        return {k: normalise(v) for k, v in obj.items()
                if k not in RUNTIME_KEYS and not k.endswith("_seconds")}
    if isinstance(obj, list):
        return [normalise(v) for v in obj]
    return obj


def write_normalised(summary: Path, dest: Path, root: Path = ROOT) -> None:
    data = normalise(json.loads(summary.read_text(encoding="utf-8")))
    text = json.dumps(data, indent=1, sort_keys=True) + "\n"
    dest.write_text(text.replace(str(root), "<repo>"), encoding="utf-8")


def record(out: Path, root: Path = ROOT) -> None:
    """Run the five commands of the checkout ``root`` into ``out`` (fresh caches)."""
    out.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, MPLBACKEND="Agg", SHAFTFE_CACHE_DIR=str(out / "cache"))
    for name, (argv, summary) in RUNS.items():
        run_dir = out / "runs" / name
        p = subprocess.run([sys.executable, "-m", "shaftfe", *argv, "--out", str(run_dir)],
                           cwd=root, env=env, capture_output=True, text=True)
        if p.returncode != 0:
            raise SystemExit(f"{name}: shaftfe exited {p.returncode}: {p.stderr.strip()}")
        write_normalised(run_dir / summary, out / f"{name}.json", root)
        print(f"recorded {name}")


def compare(a: Path, b: Path) -> int:
    bad = 0
    for name in RUNS:
        x, y = (a / f"{name}.json").read_bytes(), (b / f"{name}.json").read_bytes()
        if x == y:
            print(f"{name}: identical ({len(x)} bytes)")
            continue
        bad += 1
        lx, ly = x.decode().splitlines(), y.decode().splitlines()
        i = next((k for k, (p, q) in enumerate(zip(lx, ly, strict=False)) if p != q),
                 min(len(lx), len(ly)))
        print(f"{name}: DIFFERS at line {i + 1}:\n  {lx[i] if i < len(lx) else '<end>'}\n  "
              f"{ly[i] if i < len(ly) else '<end>'}")
    return 1 if bad else 0


def against(commit: str) -> int:
    """Record ``commit`` (a temporary worktree) and this tree, and compare."""
    import tempfile
    with tempfile.TemporaryDirectory(prefix="identical-") as tmp:
        old = Path(tmp) / "checkout"
        subprocess.run(["git", "worktree", "add", "--detach", "-q", str(old), commit],
                       cwd=ROOT, check=True)
        try:
            record(Path(tmp) / "before", old.resolve())
            record(Path(tmp) / "after", ROOT)
            return compare(Path(tmp) / "before", Path(tmp) / "after")
        finally:
            subprocess.run(["git", "worktree", "remove", "--force", str(old)], cwd=ROOT)


def main(argv: list[str]) -> int:
    if len(argv) == 2 and argv[0] == "against":
        return against(argv[1])
    if len(argv) == 2 and argv[0] == "record":
        record(Path(argv[1]))
        return 0
    if len(argv) == 3 and argv[0] == "compare":
        return compare(Path(argv[1]), Path(argv[2]))
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
