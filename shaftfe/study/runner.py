"""Run a study's designs on Dask.distributed, resumably.

``run_study(spec, out_dir, workers=None, scheduler=None)``:

* **Where.** Without ``scheduler`` a ``dask.distributed.LocalCluster`` of worker processes,
  1 thread each (the nanny sets OMP/MKL/OpenBLAS to 1 thread), as many as the cores and the
  free memory allow for the analyses asked (``MEMORY_PER_WORKER``); each worker's memory limit is
  its share of the free memory, so a runaway worker is restarted by its nanny. With
  ``scheduler`` (``tcp://host:8786``) an existing cluster (``dask scheduler`` + ``dask worker``,
  dask-jobqueue, Kubernetes): the workers need shaftfe installed and the study's files.
* **Sharing.** Designs that need the 3D solid are grouped by their mesh key (the solid alone:
  part masses, bearing stiffness, the crank do not change it) and shaft material. Each group's
  mesh is built once (a task of its own; the mesh object goes to the group's tasks), and each
  worker process keeps its last stiffness matrix and factorisation
  (``shaftfe.fe.reuse.keep``): a design of the same solid only adds its loads, springs and
  spin softening (low-rank terms). The group-ordered designs run in one lane per worker
  (each task after the previous one of its lane), so a worker changes solid only where its
  lane crosses from one group to the next. Each 3D design is a task (its row saved as
  soon as it is done); beam-level designs go in chunks (``BEAM_CHUNK``) to keep the
  scheduling overhead per design small.
* **Resume.** Each design's row is written to ``designs/<key>.json`` as soon as it arrives;
  key = sha256 of the base variant's content, the design's overrides, the analysis options,
  the rpm history's content and the package's source. A re-run (after Ctrl-C, a killed worker,
  a lost node) computes only the designs without a row. ``study.json`` records the study
  file's digest: a directory refuses a different study.
* **Failures.** A design the loader refuses, or whose analysis fails, is a row with status and
  reason (``shaftfe.study.evaluate``). A task whose worker died (out of memory, killed) is
  retried once, design by design; a second death is recorded as ``failed``.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import shaftfe
from shaftfe.beam.planes import mesh_hot_axes
from shaftfe.errors import InputError
from shaftfe.fe import reuse
from shaftfe.model.loader import load_variant
from shaftfe.solid.mesh import build_mesh
from shaftfe.study import results, sampling
from shaftfe.study.check import check_study
from shaftfe.study.evaluate import evaluate_design, group_of, load_design
from shaftfe.study.sampling import Design
from shaftfe.study.spec import StudySpec
from shaftfe.util.atomic import write_atomic

MiB = 1024 ** 2
# Resident memory one worker needs (measured as whole processes: the static command's peak RSS
# at each level, README speed table; the beam pipeline ~250 MiB) plus headroom for the mesh
# object in transit: a cap, not a limit on what a design may use.
MEMORY_PER_WORKER = {"beam": 400 * MiB, "coarse": 1200 * MiB, "default": 2000 * MiB,
                     "fine": 5000 * MiB}
BEAM_CHUNK = 25                    # beam-level designs per task
BASE = Design(-1, ())              # the base variant, evaluated beside the designs
STUDY_FORMAT = 1
CONNECT_TIMEOUT_S = 8     # + the command's start (~1 s): the answer comes within 10 s


@dataclass(frozen=True)
class StudyRun:
    out_dir: Path
    rows: tuple[dict, ...]                 # every design, in design order
    computed: int                          # designs evaluated in this run
    reused: int                            # designs whose row was already on disk
    failed: int
    refused: int
    workers: int
    wall_seconds: float
    compute_seconds: float                 # Σ of the designs' own seconds (this run)
    connect_seconds: float = 0.0           # starting / reaching the cluster
    sharing: dict = field(default_factory=dict)   # meshes built, factorisations made/reused


# --------------------------------------------------------------------------- keys and files

# sources that cannot change a design's numbers (scheduling, tables, the page, the CLI)
_NOT_NUMBERS = ("cli.py", "study/runner.py", "study/results.py", "study/report.py",
                "study/sampling.py", "study/__init__.py", "study/check.py")


def source_fingerprint() -> str:
    """sha256 of the package's analysis sources (a code change invalidates cached rows)."""
    root = Path(shaftfe.__file__).parent
    h = hashlib.sha256()
    for p in sorted(root.rglob("*.py")):
        rel = p.relative_to(root).as_posix()
        if (rel.startswith(("commands/", "report/", "io/")) and rel != "report/seed.py") \
                or rel in _NOT_NUMBERS:
            continue
        h.update(rel.encode())
        h.update(p.read_bytes())
    return h.hexdigest()


def design_key(base_hash: str, design: Design, options: dict, code: str) -> str:
    payload = {"format": STUDY_FORMAT, "base": base_hash, "set": list(design.overrides),
               "analyses": options, "code": code}
    return hashlib.sha256(json.dumps(payload, sort_keys=True, default=repr).encode()
                          ).hexdigest()[:32]


def _write_json(path: Path, obj) -> None:
    """A row or the study's record (an infinite life stays ``Infinity``: Python's JSON reads
    it back; these files are the study's own cache, the tables are what others read)."""
    write_atomic(path, json.dumps(obj, indent=1, default=str) + "\n")


def _finished(path: Path) -> bool:
    """A design row on disk that a resumed run keeps (not a cluster failure)."""
    if not path.is_file():
        return False
    try:
        return not json.loads(path.read_text()).get("cluster_failure", False)
    except (OSError, ValueError):
        return False


def _cluster_error(exc: BaseException) -> bool:
    """A task lost to the cluster (a dead worker, a cancelled future, a lost connection)."""
    names = {t.__name__ for t in type(exc).__mro__}
    return bool(names & {"KilledWorker", "CancelledError", "FutureCancelledError",
                         "CommClosedError", "OSError", "TimeoutError"})


def check_directory(out_dir: Path, spec: StudySpec) -> None:
    """A study directory belongs to one study file (its content digest)."""
    sj = out_dir / "study.json"
    if not sj.is_file():
        if out_dir.exists() and any(out_dir.iterdir()):
            raise InputError(str(out_dir), "--out", "an empty directory or one made by "
                             "shaftfe study run", reason="holds other files")
        return
    try:
        meta = json.loads(sj.read_text())
        old = meta.get("digest") if isinstance(meta, dict) else None
    except (OSError, ValueError):
        meta = old = None
    if not isinstance(old, str):
        raise InputError(str(out_dir), "study.json", "the record shaftfe study run writes "
                         "(delete the folder, or choose another --out)",
                         reason="is damaged (not the JSON record of a study)")
    if old != spec.digest:
        raise InputError(str(out_dir), "study.json", f"the study it was made for ("
                         f"{meta.get('study_file', '?')}), or another --out", got=spec.path,
                         reason="belongs to a different study file")


# --------------------------------------------------------------------------- worker tasks

def build_group_mesh(base: str, overrides, level: str):
    """The mesh of a group's solid (one per group, built on a worker; cached on its disk)."""
    v, _ = load_design(base, overrides)
    return build_mesh(v, level, 2, hot_axes=mesh_hot_axes(v))


def evaluate_task(base: str, items, analyses, shaft_mesh=None,
                  after=None) -> list[tuple[str, dict]]:
    """Evaluate (key, overrides) items in order. The worker process keeps its last stiffness
    matrix and factorisation (``reuse.keep``), so consecutive designs of one solid share them
    whichever task they arrive in; the counts this task added ride on its first row.
    ``after``: the previous task of the same lane (only orders the two)."""
    from contextlib import nullcontext

    try:
        from distributed import get_worker
        single = get_worker().state.nthreads == 1
    except (ImportError, ValueError, AttributeError):
        single = False
    # a worker with several threads runs designs side by side: no shared factorisation there
    # (one solver handle is not thread-safe), only within this task
    ctx = nullcontext(reuse.keep()) if single else reuse.shared()
    out = []
    with ctx as stats:
        made0, reused0 = dict(stats["made"]), dict(stats["reused"])
        for key, overrides in items:
            out.append((key, evaluate_design(base, overrides, analyses,
                                             shaft_mesh=shaft_mesh)))
    if out:
        out[0][1]["_sharing"] = {
            "made": {k: v - made0.get(k, 0) for k, v in stats["made"].items()},
            "reused": {k: v - reused0.get(k, 0) for k, v in stats["reused"].items()}}
    return out


# --------------------------------------------------------------------------- planning

def _group_key(base: str, design: Design, level: str) -> tuple:
    """``group_of`` a design, or ("refused",) if it cannot be loaded."""
    try:
        v, _ = load_design(base, design.overrides)
        return group_of(v, level)
    except Exception:                       # the evaluation records why, one design alone
        return ("refused",)


def plan_tasks(spec: StudySpec, todo: list[tuple[str, Design]], known=None):
    """[(mesh group or None, [(key, overrides), ...]), ...] in group order. A 3D design is a
    task of its own (its row is saved the moment it is done: an interruption loses at most
    the designs in progress); beam-level designs go ``BEAM_CHUNK`` to a task. ``known``:
    design number → group, as ``shaftfe.study.check`` found them (else loaded here)."""
    if not spec.analyses.static:
        items = [(k, d.overrides) for k, d in todo]
        return [(None, items[i:i + BEAM_CHUNK]) for i in range(0, len(items), BEAM_CHUNK)]
    if spec.analyses.static_model == "zoned":    # no shared solid: each zone meshes (and
        return [(None, [(k, d.overrides)]) for k, d in todo]    # caches) its own clip
    groups: dict[tuple, list] = {}
    for k, d in todo:
        g = (known or {}).get(d.number) or _group_key(spec.base, d, spec.analyses.level)
        groups.setdefault(g, []).append((k, d))
    return [(None if g == ("refused",) else g, [(k, d.overrides)])
            for g, members in groups.items() for k, d in members]


# --------------------------------------------------------------------------- cluster

def default_workers(spec: StudySpec) -> tuple[int, int]:
    """(workers, memory limit per worker in bytes) for a LocalCluster on this machine."""
    import psutil
    need = MEMORY_PER_WORKER[spec.analyses.level if spec.analyses.static else "beam"]
    avail = psutil.virtual_memory().available
    cores = os.cpu_count() or 1
    n = max(1, min(cores, avail // need))
    return int(n), int(avail // n)


SCHEMES = ("tcp", "tls", "ws", "wss", "ucx", "inproc")


def scheduler_address(scheduler: str) -> tuple[str, int | None]:
    """(host, port) of a scheduler address as distributed reads it (``tcp://host:8786`` or
    ``host:8786``); InputError saying why it is not one."""
    from urllib.parse import urlsplit

    def bad(why: str):
        return InputError("--scheduler", "address", "a Dask scheduler address, e.g. "
                          "tcp://host:8786", got=scheduler, reason=why)
    s = str(scheduler).strip()
    if not s or any(c.isspace() for c in s):
        raise bad("is not a URL")
    scheme, sep, _ = s.partition("://")
    if not sep:
        scheme, s = "tcp", "tcp://" + s
    if scheme in ("http", "https"):
        raise bad("is a web address (the dashboard's?), not the scheduler's: a scheduler "
                  "listens on tcp://host:8786")
    if scheme not in SCHEMES:
        raise bad(f"is not a URL with one of the schemes {', '.join(SCHEMES)}")
    if scheme in ("ucx", "inproc"):
        return "", None                       # no socket to probe
    try:
        u = urlsplit(s)
        port = u.port
    except ValueError:
        raise bad("is not a URL (its port is not a number in [0, 65535])") from None
    if not u.hostname or port is None or u.path not in ("", "/"):
        raise bad("is not a URL of the form scheme://host:port")
    return u.hostname, port


def probe(scheduler: str, timeout: float = CONNECT_TIMEOUT_S) -> None:
    """Reach the scheduler's host and port (one TCP connection, closed at once): InputError
    saying what happened: not a URL, a refused connection, no answer, no route."""
    import socket
    host, port = scheduler_address(scheduler)
    if port is None:
        return

    def bad(why: str):
        return InputError("--scheduler", "address", "a reachable Dask scheduler, e.g. "
                          "tcp://host:8786", got=scheduler, reason=why)
    try:
        with socket.create_connection((host, port), timeout=timeout):
            pass
    except ConnectionRefusedError:
        raise bad(f"refused the connection (nothing listens on port {port} of {host})") \
            from None
    except TimeoutError:                      # socket.timeout is TimeoutError (3.10+)
        raise bad(f"did not answer within {timeout:g} s (unreachable: a wrong address or a "
                  "firewall)") from None
    except socket.gaierror as exc:
        raise bad(f"names a host that cannot be resolved ({exc.strerror})") from None
    except OSError as exc:                    # no route, network unreachable, …
        raise bad(f"is unreachable ({exc.strerror or type(exc).__name__})") from None


def connect(scheduler: str | None, workers: int | None, spec: StudySpec):
    """(client, cluster or None, n_workers)."""
    import logging

    import dask
    from distributed import Client, LocalCluster
    if scheduler is not None:             # an empty address is refused, not a local cluster
        probe(scheduler)
        try:
            client = Client(scheduler, timeout=f"{CONNECT_TIMEOUT_S}s")
        except Exception as exc:          # the port answers, but not as a Dask scheduler
            # (a service answering garbage: distributed raises MemoryError, TypeError, …
            # while reading its handshake)
            raise InputError("--scheduler", "address", "a reachable Dask scheduler, e.g. "
                             "tcp://host:8786", got=scheduler,
                             reason="answers but is not a Dask scheduler (no handshake "
                             f"within {CONNECT_TIMEOUT_S} s: {type(exc).__name__})") from None
        n = len(client.scheduler_info().get("workers", {}))
        if n == 0:
            try:
                client.wait_for_workers(1, timeout=60)
            except TimeoutError:
                client.close()
                raise InputError("--scheduler", "address", "a scheduler with workers",
                                 got=scheduler, reason="has no workers after 60 s") from None
            n = len(client.scheduler_info().get("workers", {}))
        return client, None, n
    n_auto, mem = default_workers(spec)
    n = workers or n_auto
    # our own retry (once, design by design) replaces the scheduler's
    dask.config.set({"distributed.scheduler.allowed-failures": 0,
                     "distributed.worker.daemon": False})
    cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                           memory_limit=mem if workers is None else None,
                           dashboard_address=None, silence_logs=logging.CRITICAL)
    return Client(cluster), cluster, n


# --------------------------------------------------------------------------- progress

class Bar:
    """``[#####-----] 12/45 designs  2 failed  ETA 1 min 20 s`` on a terminal (stderr)."""

    def __init__(self, total: int, done: int, stream=None, enabled: bool | None = None):
        self.stream = stream or sys.stderr
        self.enabled = (self.stream.isatty() if enabled is None else enabled)
        self.total, self.done, self.start_done = total, done, done
        self.failed = 0
        self.t0 = time.perf_counter()

    def update(self, n: int = 1, failed: int = 0) -> None:
        self.done += n
        self.failed += failed
        if not self.enabled:
            return
        width = 30
        frac = self.done / self.total if self.total else 1.0
        fill = int(width * frac)
        rate = (self.done - self.start_done) / max(time.perf_counter() - self.t0, 1e-9)
        left = (self.total - self.done) / rate if rate > 0 else math.inf
        eta = "" if not math.isfinite(left) else f"  ETA {_hms(left)}"
        fail = f"  {self.failed} failed" if self.failed else ""
        self.stream.write(f"\r\x1b[K[{'#' * fill}{'-' * (width - fill)}] {self.done}/"
                          f"{self.total} designs{fail}{eta}")
        self.stream.flush()

    def close(self) -> None:
        if self.enabled:
            self.stream.write("\n")
            self.stream.flush()


def _hms(s: float) -> str:
    s = round(s)
    if s < 60:
        return f"{s} s"
    m, s = divmod(s, 60)
    if m < 60:
        return f"{m} min {s:02d} s"
    h, m = divmod(m, 60)
    return f"{h} h {m:02d} min"


# --------------------------------------------------------------------------- run

def run_study(spec: StudySpec, out_dir, *, workers: int | None = None,
              scheduler: str | None = None, progress: bool | None = None,
              checked=None, announce=None) -> StudyRun:
    """Evaluate every design without a row in ``out_dir``; write the result tables.

    Every input is checked first (``shaftfe.study.check``; ``checked``: its result if the
    caller has it) and the cluster is reached before anything is written: a refused study or
    an unreachable scheduler leaves a fresh ``out_dir`` as it was (not created).
    ``announce(checked)``: called once the cluster is reached, before the first design runs
    (the command lists the refused designs there)."""
    t_all = time.perf_counter()
    out = Path(out_dir)
    if scheduler is not None:                      # '' is an address given, and refused
        scheduler_address(scheduler)               # its form, before any design is loaded
    designs = sampling.designs(spec)
    if checked is None:
        checked = check_study(spec, designs)       # every input, before anything runs
    check_directory(out, spec)
    base_hash = load_variant(spec.base).content_hash
    options = spec.analyses.options()
    code = source_fingerprint()
    keys = [design_key(base_hash, d, options, code) for d in designs]
    ddir = out / "designs"
    done = {k for k in keys if _finished(ddir / f"{k}.json")}
    todo = [(k, d) for k, d in zip(keys, designs, strict=True) if k not in done]
    todo = list({k: (k, d) for k, d in todo}.values())          # equal designs once
    refused = [(k, d) for k, d in todo if d.number in checked.refused]
    todo = [(k, d) for k, d in todo if d.number not in checked.refused]
    reused = len(designs) - len(todo) - len(refused)
    # the base variant itself, by the same analyses: the reference the page marks
    base_key = design_key(base_hash, BASE, options, code)
    base_todo = not _base_row(out, base_key)
    if base_todo:
        todo.append((base_key, BASE))
    computed = compute_s = 0
    sharing: dict = {"meshes_built": 0, "factor_made": 0, "factor_reused": 0}
    n_workers = 0
    t_conn = 0.0
    client = cluster = None
    if todo:                                  # reach the cluster before writing anything
        t0 = time.perf_counter()
        client, cluster, n_workers = connect(scheduler, workers, spec)
        t_conn = time.perf_counter() - t0
    if announce is not None:
        announce(checked)
    try:
        ddir.mkdir(parents=True, exist_ok=True)
        _write_json(out / "study.json", study_record(spec, out, len(designs), base_key))
        for k, d in refused:                  # the loader's refusal, found by the check
            _write_json(ddir / f"{k}.json", {"status": "refused", "error":
                                             checked.refused[d.number], "seconds": 0.0})
            computed += 1
        if todo:
            bar = Bar(len(designs) + base_todo, len(designs) + base_todo - len(todo),
                      enabled=progress)
            try:
                c, compute_s = _execute(client, spec, todo, n_workers, ddir, bar, sharing,
                                        groups=checked.groups)
                computed += c - base_todo
            finally:
                bar.close()
            b = ddir / f"{base_key}.json"
            if b.is_file():                   # kept beside the designs, not among them
                _write_json(out / "base.json", {"key": base_key,
                                                "row": json.loads(b.read_text())})
                b.unlink()
    finally:
        if client is not None:
            client.close()
        if cluster is not None:
            cluster.close()
    rows = []
    for k, d in zip(keys, designs, strict=True):
        row = json.loads((ddir / f"{k}.json").read_text())
        rows.append(results.row_with_inputs(d, k, row))
    results.write_tables(out, spec, rows)
    run = StudyRun(out, tuple(rows), computed, reused, sum(
        r["status"] == "failed" for r in rows), sum(r["status"] == "refused" for r in rows),
        n_workers, time.perf_counter() - t_all, compute_s, connect_seconds=t_conn,
        sharing=sharing)
    _write_json(out / "run.json", {
        "designs": len(designs), "computed": run.computed, "reused": run.reused,
        "failed": run.failed, "refused": run.refused, "workers": run.workers,
        "wall_seconds": run.wall_seconds, "compute_seconds": run.compute_seconds,
        "connect_seconds": run.connect_seconds,
        "sharing": sharing, "scheduler": scheduler or "LocalCluster"})
    return run


def study_record(spec: StudySpec, out: Path, n_designs: int, base_key: str) -> dict:
    """What study.json holds: the study file (relative to the folder) and its digest, the
    parameters, objectives, requirements and analysis options, the base row's key."""
    return {"study_file": _shown_path(spec.path, out), "digest": spec.digest,
            "name": spec.name, "base": _shown_path(spec.base, out)
            if spec.base.endswith(".toml") else spec.base,
            "designs": n_designs, "base_key": base_key, "description": spec.description,
            "parameters": list(sampling.paths(spec)),
            "parameter_groups": [[q.name, list(q.paths)] for q in spec.parameters],
            "objectives": [list(o) for o in results.default_objectives(spec)],
            "requirements": [list(r) for r in spec.requirements],
            "analyses": spec.analyses.options(), "format": STUDY_FORMAT}


def _base_row(out: Path, key: str | None = None) -> dict | None:
    """The base variant's row (``base.json``; of this code and these options if ``key``)."""
    try:
        b = json.loads((Path(out) / "base.json").read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(b, dict) or (key is not None and b.get("key") != key):
        return None
    row = b.get("row")
    return row if isinstance(row, dict) and not row.get("cluster_failure") else None


def _shown_path(path: str, out: Path) -> str:
    """A file the study names, as written into the folder: relative to the folder (so a
    committed study folder holds no path of the machine it ran on), absolute only when it
    lies on another drive."""
    p = Path(path).resolve()
    try:
        return os.path.relpath(p, out.resolve())
    except ValueError:
        return str(p)


def _execute(client, spec, todo, n_workers, ddir: Path, bar: Bar, sharing: dict,
             as_completed=None, groups=None):
    """Submit the planned tasks, write each row as it arrives, retry a dead task once design
    by design (``as_completed``: distributed's, or a stand-in with the same protocol)."""
    if as_completed is None:
        from distributed import as_completed
    tasks = plan_tasks(spec, todo, groups)
    meshes: dict = {}
    futures = {}
    # 3D designs run in one lane per worker: contiguous runs of the group-ordered tasks, each
    # task after the previous one of its lane (a dependency, so dask keeps a lane on one
    # worker, in order): a worker changes solid only where its lane crosses a group boundary,
    # and keeps reusing its factorisation in between
    # (designs the loader refuses need no solid: they run unchained, first)
    tasks = [t for t in tasks if t[0] is None] + [t for t in tasks if t[0] is not None]
    n_free = sum(t[0] is None for t in tasks)
    n_3d = len(tasks) - n_free
    n_lanes = max(1, min(n_workers, n_3d))
    lane_start = {n_free + round(i * n_3d / n_lanes) for i in range(n_lanes)}
    prev = None
    pending: dict = {}                   # mesh group → its tasks not yet done
    for i, (g, items) in enumerate(tasks):
        mesh_f = None
        if g is not None:
            pending[g] = pending.get(g, 0) + 1
            if g not in meshes:
                meshes[g] = client.submit(build_group_mesh, spec.base, dict(items[0][1]),
                                          spec.analyses.level, pure=False)
                sharing["meshes_built"] += 1
            mesh_f = meshes[g]
        after = None if (g is None or i in lane_start) else prev
        f = client.submit(evaluate_task, spec.base, items, spec.analyses, mesh_f, after,
                          pure=False)
        prev = f
        futures[f] = (items, mesh_f, 0, g)
    computed, compute_s = 0, 0.0
    ac = as_completed(list(futures))
    for f in ac:
        items, mesh_f, tries, grp = futures.pop(f)
        try:
            pairs = f.result()
        except Exception as exc:             # the worker died (memory, killed) or the task
            mesh_failed = mesh_f is not None and mesh_f.status == "error"
            if tries == 0 and not mesh_failed:   # raised: once more, one design per task
                for it in items:
                    r = client.submit(evaluate_task, spec.base, [it], spec.analyses, mesh_f,
                                      None, pure=False)
                    futures[r] = ([it], mesh_f, 1, grp)
                    if grp is not None:
                        pending[grp] += 1
                    ac.add(r)
                _done_with(grp, pending, meshes)
                continue
            msg = " ".join(str(exc).split())[:300] or type(exc).__name__
            why = (f"the mesh could not be built: {msg}" if mesh_failed else
                   f"{type(exc).__name__} twice (the worker died or the task raised): {msg}")
            # recorded, and computed again by the next run (the cluster failed, not the design;
            # a mesh that raised is the design's own failure)
            pairs = [(k, {"status": "failed", "error": why, "seconds": 0.0,
                          "cluster_failure": not mesh_failed or _cluster_error(exc)})
                     for k, _ in items]
        for k, row in pairs:
            sh = row.pop("_sharing", None)
            if sh:
                sharing["factor_made"] += sh["made"].get("factor", 0)
                sharing["factor_reused"] += sh["reused"].get("factor", 0)
            _write_json(ddir / f"{k}.json", row)
            computed += 1
            compute_s += float(row.get("seconds", 0.0))
            bar.update(1, failed=int(row["status"] != "ok"))
        f.release()
        _done_with(grp, pending, meshes)
    return computed, compute_s


def _done_with(grp, pending: dict, meshes: dict) -> None:
    """One task of mesh group ``grp`` finished: after its last, let the cluster free the mesh
    (a study over a fillet radius has as many meshes as designs)."""
    if grp is None:
        return
    pending[grp] -= 1
    if pending[grp] == 0 and grp in meshes:
        meshes.pop(grp).release()
