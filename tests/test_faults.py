"""Faults lose nothing: damaged cache entries are found by their checksum and rebuilt with a
one-line notice, two processes building one entry leave a valid entry, and an interrupted run
(Ctrl-C) or a failing one leaves no partial output."""

from __future__ import annotations

import io
import json
import os
import signal
import subprocess
import sys
import time
import zipfile
from pathlib import Path

import numpy as np
import pytest

from shaftfe.util import cachefile
from shaftfe.util.atomic import staged_dir


def _rewrite_member(path: Path, name: str, array: np.ndarray) -> None:
    """Replace one array of an .npz with ``array``, keeping every other member (and the stored
    checksum) as it was: a valid zip whose content no longer matches its checksum."""
    members = {}
    with zipfile.ZipFile(path) as z:
        for info in z.infolist():
            members[info.filename] = z.read(info.filename)
    buf = io.BytesIO()
    np.save(buf, array)
    members[f"{name}.npy"] = buf.getvalue()
    with zipfile.ZipFile(path, "w") as z:
        for k, v in members.items():
            z.writestr(k, v)


def test_cache_entry_checksum_detects_changed_content(tmp_path, capsys):
    path = tmp_path / "entry.npz"
    arrays = {"a": np.arange(10.0), "b": np.eye(3, dtype=np.int32)}
    cachefile.save(path, arrays, {"key": "k1"})
    got = cachefile.load(path, "k1", "test")
    assert got is not None
    assert all(np.array_equal(got[0][n], arrays[n]) for n in arrays)
    assert capsys.readouterr().err == ""
    _rewrite_member(path, "a", np.arange(10.0) + 1e-12)     # a flipped low bit, valid zip
    assert cachefile.load(path, "k1", "test") is None
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "checksum mismatch" in err[0] and "entry.npz" in err[0]


@pytest.mark.parametrize("damage", ["truncate", "garbage", "content"])
def test_damaged_mesh_cache_is_rebuilt_with_a_notice(tmp_path, damage, capfd):
    from benchmarks.bench_truth import four_point_bar
    from shaftfe.solid.mesh import build_mesh, cache_path
    v = four_point_bar(22.0, 17.0, 1.0)      # the cache's handling needs no features: a bar
    first = build_mesh(v, "coarse", order=1, cache_dir=tmp_path)
    path = cache_path(first.key, tmp_path)
    capfd.readouterr()
    if damage == "truncate":
        path.write_bytes(path.read_bytes()[: path.stat().st_size // 2])
    elif damage == "garbage":
        path.write_bytes(b"\x00" * 1000)
    else:
        _rewrite_member(path, "doflocs", np.asarray(first.mesh.p) * 1.0001)
    again = build_mesh(v, "coarse", order=1, cache_dir=tmp_path)
    err = capfd.readouterr().err.strip().splitlines()
    assert not again.from_cache
    assert len(err) == 1 and "mesh cache entry" in err[0] and "rebuilding" in err[0]
    assert np.array_equal(again.mesh.t, first.mesh.t)          # rebuilt, not the damaged one
    assert np.array_equal(again.mesh.p, first.mesh.p)
    assert build_mesh(v, "coarse", order=1, cache_dir=tmp_path).from_cache   # and stored


def test_damaged_static_cache_is_recomputed_with_a_notice(tmp_path, capfd):
    """The static reference store: a valid entry reads back; one whose stresses were changed
    after writing fails its checksum and is recomputed (None → solve)."""
    from shaftfe.static.cache import StaticReference, _load, _save
    n = 20
    ref = StaticReference(
        variant="v", variant_hash="h", options={}, ref_rpm=10_000.0, mesh_key="m", key="K",
        stress_ref=np.ones((6, n)), von_mises_ref=np.ones(n), xyz=np.zeros((3, n)),
        excluded=np.arange(2), regions={"fillet:a": np.arange(5)},
        cells=np.zeros((1, 4), dtype=np.int64), face_cells=np.zeros((0, 3), dtype=np.int64),
        face_group=np.zeros(0, dtype=np.int32), face_groups=(), n_elements=1,
        solve_seconds=1.0, from_cache=False, seconds=0.0)
    path = tmp_path / "static.npz"
    _save(path, ref)
    assert _load(path, "K", "v", time.perf_counter()) is not None
    _rewrite_member(path, "stress_ref", np.full((6, n), 2.0))
    capfd.readouterr()
    assert _load(path, "K", "v", time.perf_counter()) is None
    err = capfd.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "static cache entry" in err[0]


def _default_sigint() -> None:
    """In the child before it runs Python: SIGINT back to its default. A process started with
    SIGINT ignored (a pytest-xdist worker, a `nohup` job) passes that on, and Python then installs
    no KeyboardInterrupt handler, so the ctrl-c test would interrupt nothing."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _shaftfe(*args, cache=None, **kw):
    env = dict(os.environ, MPLBACKEND="Agg")
    if cache is not None:
        env["SHAFTFE_CACHE_DIR"] = str(cache)
    return subprocess.Popen([sys.executable, "-m", "shaftfe", *args], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=env, **kw)


def test_two_processes_building_one_mesh_entry_leave_a_valid_entry(tmp_path):
    from shaftfe.model.loader import load_variant
    from shaftfe.solid.mesh import build_mesh, cache_path
    procs = [_shaftfe("mesh", "--variant", "x2_57", "--level", "coarse", "--order", "1",
                      "--cache-dir", str(tmp_path), "--json") for _ in range(2)]
    outs = [p.communicate(timeout=300) for p in procs]
    assert [p.returncode for p in procs] == [0, 0], [o[1] for o in outs]
    keys = {json.loads(o[0])["key"] for o in outs}
    assert len(keys) == 1
    entries = list(tmp_path.glob("mesh-*.npz"))
    assert len(entries) == 1 and not list(tmp_path.glob(".*"))    # no temporary left behind
    m = build_mesh(load_variant("x2_57"), "coarse", order=1, cache_dir=tmp_path)
    assert m.from_cache and m.key.startswith(keys.pop())
    assert cache_path(m.key, tmp_path) == entries[0]


def test_staged_outputs_are_all_or_nothing(tmp_path):
    out = tmp_path / "run"
    with pytest.raises(KeyboardInterrupt), staged_dir(out) as stage:
        (stage / "a.txt").write_text("a")
        raise KeyboardInterrupt
    assert not out.exists() and list(tmp_path.iterdir()) == []     # nor a staging directory
    out.mkdir()
    (out / "old.txt").write_text("old")
    with pytest.raises(RuntimeError), staged_dir(out) as stage:
        (stage / "old.txt").write_text("new")
        raise RuntimeError("a failing solve")
    assert (out / "old.txt").read_text() == "old" and sorted(os.listdir(out)) == ["old.txt"]
    with staged_dir(out) as stage:
        assert stage.parent == out      # inside an existing out: its file system, its rights
        (stage / "old.txt").write_text("new")
        (stage / "sub").mkdir()
        (stage / "sub" / "b.txt").write_text("b")
    assert (out / "old.txt").read_text() == "new" and (out / "sub" / "b.txt").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]


def test_a_run_removes_the_optional_files_an_earlier_run_left(tmp_path):
    """``replaces``: files matching the patterns that this run did not write are an earlier
    run's (a plot an option asked for, another shaft's 3D zones) and go; this run's files and
    files matching no pattern stay; a failed run removes nothing."""
    out = tmp_path / "run"
    out.mkdir()
    for name in ("zone_a.vtu", "zone_b.vtu", "along.png", "mine.txt"):
        (out / name).write_text("old")
    with pytest.raises(RuntimeError), staged_dir(out, replaces=("zone_*.vtu",)) as stage:
        (stage / "zone_a.vtu").write_text("new")
        raise RuntimeError("a failing solve")
    assert sorted(os.listdir(out)) == ["along.png", "mine.txt", "zone_a.vtu", "zone_b.vtu"]
    with staged_dir(out, replaces=("zone_*.vtu", "along.png")) as stage:
        (stage / "zone_a.vtu").write_text("new")
    assert sorted(os.listdir(out)) == ["mine.txt", "zone_a.vtu"]
    assert (out / "zone_a.vtu").read_text() == "new"


def test_ctrl_c_at_any_stage_leaves_no_partial_output(tmp_path):
    """SIGINT to `shaftfe static` (the zoned default, coarse) at several moments of a run
    (import, meshing, solve, writing): the --out directory is either absent or complete, never
    partial, and no staging directory is left. Delays spread over one cold coarse run (about
    2-4 s on 2 cores: the meridian mesh, two zone meshes, the solves, four files): during the
    imports, the meshing and solve, and near the writing."""
    complete = {"result.vtu", "summary.json", "zone_1.vtu", "zone_2.vtu"}
    seen_interrupted = 0
    for k, delay in enumerate((0.3, 1.5, 3.0)):
        out = tmp_path / f"out{k}"
        p = _shaftfe("static", "--variant", "x2_57", "--level", "coarse",
                     "--out", str(out), cache=tmp_path / "cache", preexec_fn=_default_sigint)
        time.sleep(delay)
        p.send_signal(signal.SIGINT)
        _, err = p.communicate(timeout=300)
        assert p.returncode in (0, 130, -signal.SIGINT), err
        assert "Traceback" not in err
        if p.returncode != 0:
            seen_interrupted += 1
        # absent, or complete (an interrupt after the files were moved in, while printing)
        assert not out.exists() or set(os.listdir(out)) == complete
        assert not [q for q in tmp_path.iterdir() if ".staging-" in q.name]
    assert seen_interrupted >= 1
