"""Deterministic output (issue 8): two runs of `shaftfe static` on the same inputs give
bit-identical summaries.

Each run is a separate process running the real CLI (`shaftfe static --level coarse --json`)
on a small synthetic stepped shaft with the features that make meshing hard (two 1 mm
shoulder fillets, a keyway, split load seats, two bearings on the seed's coupled springs); the
variant loader is pointed at it in the child, everything else is the shipped code path.

* warm: the test fills the mesh cache; two runs on that cache must write byte-identical
  summary.json and result.vtu files, apart from the run-time entries listed in ``RUN_TIME``
  (wall-clock seconds and whether the mesh came from the cache);
* cold: two runs, each with its own empty SHAFTFE_CACHE_DIR, must agree the same way (Gmsh
  meshing from scratch in two processes);
* the run-time entries should sit in their own block: see ``test_run_time_entries_...``.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

#: entries of summary.json that measure the run, not the result (the top-level ``run`` block)
RUN_TIME = ("factor_seconds", "solve_seconds", "mesh_seconds", "mesh_from_cache",
            "assembly_seconds", "model_seconds", "recovery_seconds", "total_seconds")

_VARIANT = r"""
from shaftfe.model.examples import K_SEED, STEEL
from shaftfe.model.variant import Attachment, Bearing, Keyway, Segment, Variant


def stepped(*_a, **_k):
    kw = (Keyway(5.0, 3.0, 14.0, 14.0, 0.0),)
    segs = (Segment("a", 0.0, 40.0, 17.0, 1.0, keyways=kw),
            Segment("b", 40.0, 20.0, 22.0, 1.0),
            Segment("c", 60.0, 40.0, 17.0, 0.0))
    brg = (Bearing("L", "ZKL 3203", 31.0, 8.0, 14_400.0, 10_000.0, K_SEED, axial=True),
           Bearing("R", "ZKL 3203", 75.0, 8.0, 14_400.0, 10_000.0, K_SEED))
    att = (Attachment("cw", 7.0, 21.0, 0.24, 20.23, 14.0, angle_deg=30.0),
           Attachment("hub", 85.0, 95.0, 0.15, 1.36, 90.0))
    return Variant("stepped", "determinism test shaft", segs, brg, att, STEEL, 0.0)
"""

_CHILD = _VARIANT + r"""
import sys
import shaftfe.model.loader as V
V.load_variant = stepped
from shaftfe.cli import main
sys.exit(main(["static", "--model", "solid", "--variant", "stepped", "--level", "coarse",
               "--rpm", "7000,10000",
               "--json", "--out", sys.argv[1]]))
"""


def run_static(out: Path, cache: Path) -> dict:
    env = {**os.environ, "SHAFTFE_CACHE_DIR": str(cache), "MPLBACKEND": "Agg"}
    p = subprocess.run([sys.executable, "-c", _CHILD, str(out)], capture_output=True,
                       text=True, env=env, cwd=ROOT)
    assert p.returncode == 0, p.stderr
    text = (out / "summary.json").read_text()
    assert json.loads(p.stdout) == json.loads(text)
    return {"summary": text, "vtu": (out / "result.vtu").read_bytes()}


def without_run_time(text: str) -> str:
    """summary.json re-serialised without the ``RUN_TIME`` entries of the ``run`` block."""
    d = json.loads(text)
    for k in RUN_TIME:
        d["run"].pop(k, None)
        assert k not in d["diagnostics"], k
    return json.dumps(d, indent=2)


def differing_paths(a, b, path=()) -> list[tuple]:
    """Key paths whose values differ between two JSON documents."""
    if isinstance(a, dict) and isinstance(b, dict):
        out = []
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                out.append((*path, k))
            else:
                out += differing_paths(a[k], b[k], (*path, k))
        return out
    return [] if a == b else [path]


@pytest.fixture(scope="module")
def warm_runs(tmp_path_factory):
    """The mesh cache is filled here (in this process, the same key as the CLI's), then two
    CLI processes run on it."""
    from shaftfe.solid.mesh import build_mesh
    base = tmp_path_factory.mktemp("det_warm")
    cache = base / "cache"
    ns: dict = {}
    exec(_VARIANT, ns)
    from shaftfe.beam.planes import mesh_hot_axes
    v = ns["stepped"]()
    assert not build_mesh(v, "coarse", 2, cache_dir=cache,
                          hot_axes=mesh_hot_axes(v)).from_cache
    return run_static(base / "run1", cache), run_static(base / "run2", cache)


def test_warm_cache_runs_are_bit_identical(warm_runs):
    """Same inputs, same warm mesh cache, two processes: summary.json identical byte for byte
    once the run-time entries are removed, result.vtu identical byte for byte, and the only
    differing summary entries are the run-time ones."""
    a, b = warm_runs
    assert json.loads(a["summary"])["run"]["mesh_from_cache"] is True
    assert without_run_time(a["summary"]) == without_run_time(b["summary"])
    assert a["vtu"] == b["vtu"]
    diff = differing_paths(json.loads(a["summary"]), json.loads(b["summary"]))
    assert all(p[0] == "run" and p[1] in RUN_TIME for p in diff), diff


def test_cold_mesh_runs_are_bit_identical(warm_runs, tmp_path):
    """A process with its own EMPTY mesh cache meshes from scratch with Gmsh: the same summary
    (apart from the run-time entries) and the same result.vtu as the runs on the cache that
    another process (this one) meshed cold."""
    a, _ = warm_runs
    c = run_static(tmp_path / "cold", tmp_path / "cache_cold")
    assert json.loads(c["summary"])["run"]["mesh_from_cache"] is False
    assert without_run_time(c["summary"]) == without_run_time(a["summary"])
    assert c["vtu"] == a["vtu"]


def test_run_time_entries_live_in_their_own_block(warm_runs):
    """Everything that may differ between two runs on the same inputs sits under a top-level
    "run" key, so a plain byte comparison of the rest is the determinism check."""
    a, b = warm_runs
    diff = differing_paths(json.loads(a["summary"]), json.loads(b["summary"]))
    assert diff and all(p[0] == "run" for p in diff), diff
