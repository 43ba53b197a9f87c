"""``shaftfe study``: the study file, the derived designs, the Dask runner (resume, failures,
retry, a real scheduler and workers), the result tables and the bad-input contract."""

from __future__ import annotations

import json
import os
import shutil
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

from shaftfe.cli import main
from shaftfe.errors import InputError

ROOT = Path(__file__).resolve().parents[1]
BEAM_STUDY = """
[study]
name = "t"
base = "x2_57"
[sampling]
method = "grid"
[[parameters]]
path = "segments.collar.fillet_mm"
values = [0.4, 0.5, 0.6, 0.8]
[[parameters]]
path = "bearing_types.zkl_3203.K_N_per_mm"
values = [[[2.0e4, 0.0], [0.0, 2.0e4]], [[5.0e4, 0.0], [0.0, 5.0e4]]]
[analyses]
beam = true
campbell = { step_rpm = 2000 }
"""


def write(tmp_path, text=BEAM_STUDY, name="s.toml") -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def run_cli(args, capsys):
    rc = main(args)
    out = capsys.readouterr()
    return rc, out.out, out.err


# --------------------------------------------------------------------------- the file

def test_grid_list_lhs(tmp_path):
    from shaftfe.study.sampling import count, designs
    from shaftfe.study.spec import load_study
    s = load_study(write(tmp_path))
    ds = designs(s)
    assert count(s) == len(ds) == 8
    assert ds[0].overrides == (("segments.collar.fillet_mm", 0.4),
                               ("bearing_types.zkl_3203.K_N_per_mm", [[2.0e4, 0.0],
                                                                      [0.0, 2.0e4]]))
    assert ds[1].overrides[0][1] == 0.4 and ds[2].overrides[0][1] == 0.5   # first slowest
    lhs = BEAM_STUDY.replace('method = "grid"', 'method = "lhs"\nsamples = 5\nseed = 3') \
        .replace("values = [0.4, 0.5, 0.6, 0.8]", "min = 0.3\nmax = 0.6") \
        .replace("values = [[[2.0e4, 0.0], [0.0, 2.0e4]], [[5.0e4, 0.0], [0.0, 5.0e4]]]",
                 'path = "materials.14220.E_MPa"\nmin = 2.0e5\nmax = 2.1e5') \
        .replace('path = "bearing_types.zkl_3203.K_N_per_mm"\n', "")
    s = load_study(write(tmp_path, lhs, "l.toml"))
    ds = designs(s)
    assert len(ds) == 5
    assert all(0.3 <= d.overrides[0][1] <= 0.6 for d in ds)
    lst = BEAM_STUDY.split("[[parameters]]")[0].replace('"grid"', '"list"') + """
[[designs]]
"segments.collar.fillet_mm" = 0.5
[[designs]]
segments.collar.fillet_mm = 0.45
[analyses]
beam = true
"""
    s = load_study(write(tmp_path, lst, "list.toml"))
    assert [d.overrides for d in designs(s)] == [(("segments.collar.fillet_mm", 0.5),),
                                                 (("segments.collar.fillet_mm", 0.45),)]


def test_linked_parameter_moves_paths_together(tmp_path):
    from shaftfe.study.sampling import designs
    from shaftfe.study.spec import load_study
    text = BEAM_STUDY.split("[[parameters]]")[0] + """
[[parameters]]
paths = ["attachments.counterweight_1.shape.outer_radius_mm",
         "attachments.counterweight_2.shape.outer_radius_mm"]
min = [30.0, 36.0]
max = [34.0, 40.0]
n = 3
"""
    ds = designs(load_study(write(tmp_path, text)))
    assert [d.overrides[0][1] for d in ds] == [30.0, 32.0, 34.0]      # exact: 30 + k·2
    assert [d.overrides[1][1] for d in ds] == [36.0, 38.0, 40.0]


def test_shape_overrides_derive_mass_and_balance():
    """Consistency: the derived [balance] statement equals the loaded design's own mass
    properties (to the 9 digits the derivation writes), and the file's own shape reproduces
    the file's X2 within the loader's tolerance."""
    from shaftfe.model.derive import design_overrides
    from shaftfe.model.loader import load_variant
    from shaftfe.model.mass import balance_ratio, mass_properties
    o = design_overrides("x2_57", {"attachments.counterweight_2.shape.outer_radius_mm": 37.0})
    assert o["attachments.counterweight_2.mass_kg"] < 0.24               # a smaller crescent
    v = load_variant("x2_57", o)
    mp = mass_properties(v)
    assert mp.mass_kg == pytest.approx(o["balance.mass_kg"], rel=1e-8)   # 9 digits written
    assert 100 * balance_ratio(mp, v.balance_target) == pytest.approx(
        o["balance.X2_percent"], rel=1e-8)
    assert v.provenance.source["attachments.counterweight_2.mass_kg"] == "set"
    same = design_overrides("x2_57", {"attachments.counterweight_2.shape.outer_radius_mm":
                                      39.902})
    # the file's X2 (seed: 57 %) from the parts: 57.32 %, within the loader's 2.5 points
    assert abs(same["balance.X2_percent"] - 57.0) < 2.5
    with pytest.raises(InputError, match="follows from the shape"):
        design_overrides("x2_57", {"attachments.counterweight_2.shape.outer_radius_mm": 37.0,
                                   "attachments.counterweight_2.mass_kg": 0.2})


# --------------------------------------------------------------------------- bad input

@pytest.mark.parametrize("edit,match", [
    (("segments.collar.fillet_mm", "segments.colar.fillet_mm"), "nearest: collar"),
    (("values = [0.4, 0.5, 0.6, 0.8]", "values = [0.4, -1.0]"), r"in \[0, 150\] mm"),
    (("bearing_types.zkl_3203.K_N_per_mm", "materials.14220.E_MPa"), "a number"),
    (('method = "grid"', 'method = "grd"'), "grid | list | lhs"),
    (("beam = true", "beem = true"), "nearest|one of"),
])
def test_bad_study_is_one_line_exit_2(tmp_path, capsys, edit, match):
    p = write(tmp_path, BEAM_STUDY.replace(*edit))
    rc, _out, err = run_cli(["study", "run", str(p), "--out", str(tmp_path / "o")], capsys)
    assert rc == 2 and err.count("\n") == 1 and "Traceback" not in err
    assert str(p) in err
    import re
    assert re.search(match, err), err
    assert not (tmp_path / "o").exists()                   # nothing written


def test_too_many_designs_needs_yes(tmp_path, capsys):
    p = write(tmp_path, BEAM_STUDY.replace('name = "t"', 'name = "t"\nmax_designs = 5'))
    rc, _, err = run_cli(["study", "run", str(p), "--out", str(tmp_path / "o")], capsys)
    assert rc == 2 and "at most 5 designs" in err and "--yes" in err


def test_unreachable_scheduler_is_one_line(tmp_path, capsys):
    with socket.socket() as s:                  # a port nobody listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    p = write(tmp_path)
    t0 = time.perf_counter()
    rc, _, err = run_cli(["study", "run", str(p), "--out", str(tmp_path / "o"),
                          "--scheduler", f"tcp://127.0.0.1:{port}"], capsys)
    # a hang guard, not a speed test: the connect timeout is runner.CONNECT_TIMEOUT_S
    assert time.perf_counter() - t0 < 60
    assert rc == 2 and err.count("\n") == 1
    assert "refused the connection" in err and f"port {port}" in err
    assert not (tmp_path / "o").exists()             # nothing left: a later study may use it
    other = write(tmp_path, BEAM_STUDY.replace("0.8]", "0.7]"), "other.toml")
    from shaftfe.study.runner import check_directory
    from shaftfe.study.spec import load_study
    check_directory(tmp_path / "o", load_study(other))   # not "a different study file"


@pytest.mark.parametrize("address,why", [
    ("not a url", "is not a URL"), ("", "is not a URL"),
    ("http://127.0.0.1:8787", "web address"), ("https://127.0.0.1/status", "web address"),
    ("tcp://127.0.0.1:99999", "port is not a number"), ("tcp://127.0.0.1", "host:port"),
    ("foo://127.0.0.1:8786", "schemes tcp"),
])
def test_scheduler_address_says_what_is_wrong(address, why):
    """The address's form is checked before anything is loaded or connected."""
    from shaftfe.study.runner import scheduler_address
    with pytest.raises(InputError, match=why):
        scheduler_address(address)
    assert scheduler_address("127.0.0.1:8786") == ("127.0.0.1", 8786)     # distributed's form
    assert scheduler_address("tcp://localhost:8786") == ("localhost", 8786)


def test_every_input_checked_before_the_first_design(tmp_path):
    """Design rules (ISO 582 here) refuse a design and are listed before anything is solved,
    by the parameter and the value the study file gives; an input rule (a unit slip of a
    part's eccentricity) refuses the whole study."""
    from shaftfe.study.check import UNIT_SLIP, _unit_slip, check_study
    from shaftfe.study.sampling import designs
    from shaftfe.study.spec import load_study
    spec = load_study(write(tmp_path))
    checked = check_study(spec, designs(spec))
    assert sorted(checked.refused) == [6, 7]                       # the 0.8 mm fillet
    assert checked.refused[6].startswith("parameter segments.collar.fillet_mm = 0.8 is "
                                         "refused; allowed: <= 0.6 mm")
    [line] = checked.summary()
    assert line.startswith("2 designs refused (6, 7): segments.collar.fillet_mm") \
        and "ISO 582" in line and "--set" not in line
    # the unit-slip bound: x2_57's counterweight_2 has 20.23 mm and 0.24 kg
    from shaftfe.study.sampling import Design
    ok = [Design(0, (("attachments.counterweight_2.eccentricity_mm", 20.23 * 0.8),
                     ("attachments.counterweight_2.mass_kg", 0.24 * 1.25)))]
    _unit_slip(spec, ok)
    # the showcase's counterweights (derived from their shapes) pass the bound
    from shaftfe.model.derive import design_overrides
    show = load_study(ROOT / "studies" / "x2_tradeoff.toml").parameters[0]
    for u in (0.0, 1.0):
        o = design_overrides("x2_57", dict(zip(show.paths, show.point(u), strict=True)))
        _unit_slip(spec, [Design(0, tuple((k, v) for k, v in o.items()
                                         if k.endswith(("mass_kg", "eccentricity_mm"))
                                         and k.startswith("attachments.")))])
    for path, v in (("attachments.counterweight_2.eccentricity_mm", 0.02023),
                    ("attachments.counterweight_2.eccentricity_mm", 20.23 * 10),
                    ("attachments.counterweight_2.mass_kg", 0.24 / (UNIT_SLIP * 1.01))):
        with pytest.raises(InputError, match=f"within {UNIT_SLIP:g}×"):
            _unit_slip(spec, [Design(0, ((path, v),))])


def test_refusal_names_the_study_parameter():
    """A value derived from a parameter (a counterweight's mass from its shape) is named with
    the parameter that gave it, not as a --set the user never wrote nor 'typed in grams'."""
    from shaftfe.study.evaluate import load_design
    from shaftfe.study.spec import refusal
    ov = {"attachments.counterweight_2.shape.outer_radius_mm": 400.0}
    with pytest.raises(InputError) as e:
        load_design("x2_57", ov)
    why, rule = refusal(None, ov, e.value)
    assert why.startswith("attachments.counterweight_2.mass_kg = 43.343 (derived from "
                          "parameter attachments.counterweight_2.shape.outer_radius_mm = 400)")
    assert "--set" not in why and "grams" not in why and "400" not in rule


def test_sharp_corner_refuses_a_fatigue_design_only():
    """A zero fillet at the loaded collar shoulder is a stress singularity: a study that
    assesses fatigue refuses that design (as ``shaftfe fatigue`` refuses the shaft), one that
    does not (beam, balance) still evaluates it. The rule is solid.plan.refuse_sharp_corners."""
    from shaftfe.study.evaluate import load_design
    ov = {"segments.collar.fillet_mm": 0.0}
    v, _ = load_design("x2_57", ov)                      # no fatigue: the design loads
    assert v.segments[[s.name for s in v.segments].index("collar")].fillet_mm == 0.0
    with pytest.raises(InputError, match="sharp corner"):
        load_design("x2_57", ov, fatigue=True)


# --------------------------------------------------------------------------- the runner

@pytest.fixture(scope="module")
def beam_run(tmp_path_factory):
    """One local-cluster run of the beam study (2 workers), shared by the tests below."""
    from shaftfe.study.runner import run_study
    from shaftfe.study.spec import load_study
    d = tmp_path_factory.mktemp("study")
    spec = load_study(write(d))
    return spec, run_study(spec, d / "out", workers=2, progress=False)


def test_rows_tables_and_refusals(beam_run):
    import pandas as pd
    _spec, run = beam_run
    assert run.computed == 8 and run.reused == 0 and run.workers == 2
    df = pd.read_parquet(run.out_dir / "results.parquet")
    csv = pd.read_csv(run.out_dir / "results.csv")
    assert list(df["design"]) == list(range(8)) and list(csv["design"]) == list(range(8))
    bad = df[df["segments.collar.fillet_mm"] == 0.8]
    assert set(bad["status"]) == {"refused"}                 # ISO 582: r_s min 0.6 mm
    assert all("ISO 582" in e for e in bad["error"])
    ok = df[df["status"] == "ok"]
    assert len(ok) == 6
    for c in ("mass_kg", "X2_percent", "engine_max_F_N", "engine_rms_F_N", "L10h_min_h",
              "critical_rpm", "critical_margin_percent", "seconds"):
        assert ok[c].notna().all(), c
    # a softer bearing lowers the first critical speed (Rayleigh: ω² ∝ stiffness)
    k = ok["bearing_types.zkl_3203.K_N_per_mm"].map(lambda m: m[0][0])
    soft = ok[k == 2e4]["critical_rpm"].to_numpy()
    stiff = ok[k == 5e4]["critical_rpm"].to_numpy()
    assert (soft < stiff).all()


def test_row_equals_a_direct_evaluation(beam_run):
    """The Dask path adds nothing: a design's row is the API's evaluation of it, number for
    number. Same code and inputs; the worker runs BLAS single-threaded (the nanny's
    OMP/MKL/OPENBLAS_NUM_THREADS=1) and this process may not, which reorders the sums of the
    eigen-solve: round-off only (measured 5e-15 relative on the critical speed), bounded by
    1e-10 relative."""
    from shaftfe.study.evaluate import evaluate_design
    spec, run = beam_run
    row = next(r for r in run.rows if r["design"] == 3)
    direct = evaluate_design(spec.base, dict(spec_designs(spec)[3].overrides), spec.analyses)
    for k, v in direct.items():
        if k == "seconds":
            continue
        if isinstance(v, float):
            assert row[k] == pytest.approx(v, rel=1e-10), k
        else:
            assert row[k] == v, k


def spec_designs(spec):
    from shaftfe.study.sampling import designs
    return designs(spec)


def test_resume_computes_only_what_is_missing(beam_run):
    from shaftfe.study.runner import run_study
    spec, run = beam_run
    again = run_study(spec, run.out_dir, workers=1, progress=False)
    assert again.computed == 0 and again.reused == 8            # nothing recomputed
    files = sorted((run.out_dir / "designs").glob("*.json"))
    before = {f.name: f.read_text() for f in files}
    for f in files[:3]:                                          # an interrupted run
        f.unlink()
    third = run_study(spec, run.out_dir, workers=1, progress=False)
    assert third.computed == 3 and third.reused == 5
    untouched = {f.name: f.read_text() for f in files[3:]}
    assert all(before[k] == v for k, v in untouched.items())    # finished rows not rewritten


def test_directory_refuses_another_study(beam_run, tmp_path):
    from shaftfe.study.runner import run_study
    from shaftfe.study.spec import load_study
    _, run = beam_run
    other = load_study(write(tmp_path, BEAM_STUDY.replace("0.8]", "0.7]")))
    with pytest.raises(InputError, match="different study file"):
        run_study(other, run.out_dir, workers=1, progress=False)


def test_report_page(beam_run):
    from shaftfe.study.report import write_report
    _, run = beam_run
    page = write_report(run.out_dir).read_text()
    assert "Recommendation" in page and "Sensitivities" in page
    assert "ISO 582" in page and "data:image/png;base64," in page
    # the base variant, evaluated by the same analyses, is marked on the page
    base = json.loads((run.out_dir / "base.json").read_text())
    assert base["row"]["status"] == "ok" and "x2_57 (base)" in page
    # nothing of the machine it ran on: the study file relative to the folder
    meta = (run.out_dir / "study.json").read_text()
    assert str(run.out_dir.parent) not in meta and str(run.out_dir.parent) not in page
    assert json.loads(meta)["study_file"] == "../s.toml"


def test_numbers_and_life_axis_on_the_page():
    """Speeds readable (40,235 rpm, not 4.024e+04); lives on a log axis with 0 and ∞ on
    marked edges a decade beyond the finite ones (exact: the edges are lo/10 and hi·10)."""
    from shaftfe.study.report import _fmt, _placed
    assert _fmt(40235.4) == "40,235" and _fmt(0.49531) == "0.4953" and _fmt(272.5) == "272.5"
    assert _fmt(float("inf")) == "∞" and _fmt(float("nan")) == "—"
    assert _fmt(2.68e9) == "2.680·10<sup>9</sup>"
    v, edges = _placed("life_h", [0.0, 0.8, 50.0, float("inf")])
    assert list(v) == [0.08, 0.8, 50.0, 500.0] and sorted(edges.values()) == [0.08, 500.0]
    v, edges = _placed("engine_max_F_N", [1.0, 2.0])
    assert list(v) == [1.0, 2.0] and edges == {}


@pytest.mark.parametrize("sense,word", [("min", "lowest"), ("max", "highest")])
def test_recommendation_text_is_true_of_the_table(sense, word):
    """The page's claim about the recommended design holds in the table: among the
    non-dominated designs that meet the requirements it is the best in the first objective
    by that objective's sense; a better one that misses a requirement is named with why."""
    import pandas as pd

    from shaftfe.study import results
    from shaftfe.study.report import recommendation
    f = [100.0, 200.0, 300.0, 400.0]
    life = [5.0, 50.0, 80.0, 120.0] if sense == "min" else [120.0, 80.0, 50.0, 5.0]
    df = pd.DataFrame({"design": [0, 1, 2, 3], "status": ["ok"] * 4,
                       "engine_max_F_N": f, "life_h": life})
    objs = [("engine_max_F_N", sense), ("life_h", "max")]
    reqs = [("life_h", ">=", 10.0)]
    nd, meets = results.non_dominated(df, objs), results.meets(df, reqs)
    rec = results.recommend(df, objs, reqs)
    cand = [i for i in range(4) if nd[i] and meets[i]]
    best = (min if sense == "min" else max)(cand, key=lambda i: f[i])
    assert rec == best
    text = recommendation(df, objs, reqs, nd, meets, rec, [])
    assert f"has the {word} engine max|F| [N]: {f[rec]:g}" in text
    missed = 0 if sense == "min" else 3                # the better design without the life
    assert (f"design {missed}, {f[missed]:g}: fatigue life (seed method, S-N card "
            "structural_steel) [h] 5 (required &gt;= 10)") in text


def test_dead_worker_is_retried_once_then_recorded(tmp_path):
    """The retry logic with a stand-in for distributed's futures: a task that dies is
    resubmitted design by design once; a design whose retry dies too is recorded failed."""
    from shaftfe.study import runner
    from shaftfe.study.sampling import designs
    from shaftfe.study.spec import load_study
    spec = load_study(write(tmp_path))
    ds = designs(spec)[:3]
    todo = [(f"k{i}", d) for i, d in enumerate(ds)]

    class Fut:
        status = "finished"

        def __init__(self, items, dies):
            self.items, self.dies = items, dies

        def result(self):
            if self.dies:
                raise RuntimeError("KilledWorker: worker died")
            return [(k, {"status": "ok", "error": "", "seconds": 1.0}) for k, _ in self.items]

        def release(self):
            pass

    calls = []

    class Client:
        def submit(self, fn, base, items, *a, **k):
            calls.append([key for key, _ in items])
            # the first (3-design) task dies; on retry design k1 dies again
            return Fut(items, dies=len(calls) == 1 or [key for key, _ in items] == ["k1"])

    class Completed:
        def __init__(self, fs):
            self.q = list(fs)

        def __iter__(self):
            while self.q:
                yield self.q.pop(0)

        def add(self, f):
            self.q.append(f)

    ddir = tmp_path / "designs"
    ddir.mkdir()
    sharing = {"meshes_built": 0, "factor_made": 0, "factor_reused": 0}
    n, _ = runner._execute(Client(), spec, todo, 1, ddir, runner.Bar(3, 0, enabled=False),
                           sharing, as_completed=Completed)
    assert calls == [["k0", "k1", "k2"], ["k0"], ["k1"], ["k2"]]      # once, one by one
    rows = {k: json.loads((ddir / f"{k}.json").read_text()) for k in ("k0", "k1", "k2")}
    assert rows["k0"]["status"] == rows["k2"]["status"] == "ok"
    assert rows["k1"]["status"] == "failed" and "twice" in rows["k1"]["error"]
    assert n == 3


@pytest.mark.slow
def test_real_scheduler_and_two_workers(tmp_path):
    """`dask scheduler` and two `dask worker` processes on localhost, the study through the
    CLI's --scheduler: every design computed by those workers."""
    dask = shutil.which("dask", path=os.path.dirname(sys.executable))
    assert dask, "the dask CLI comes with dask[distributed]"
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    addr = f"tcp://127.0.0.1:{port}"
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    log = open(tmp_path / "cluster.log", "w")
    procs = [subprocess.Popen([dask, "scheduler", "--host", "127.0.0.1", "--port", str(port),
                               "--no-dashboard"], stdout=log, stderr=log, env=env)]
    try:
        for i in range(2):
            procs.append(subprocess.Popen(
                [dask, "worker", addr, "--nthreads", "1", "--nworkers", "1", "--name",
                 f"w{i}", "--no-dashboard", "--memory-limit", "1GiB"],
                stdout=log, stderr=log, env=env))
        from distributed import Client
        with Client(addr, timeout="30s") as c:
            c.wait_for_workers(2, timeout=60)
        p = write(tmp_path)
        out = tmp_path / "o"
        r = subprocess.run([sys.executable, "-m", "shaftfe", "study", "run", str(p), "--out",
                            str(out), "--scheduler", addr], capture_output=True, text=True,
                           env=env, timeout=600)
        assert r.returncode == 0, r.stderr
        run = json.loads((out / "run.json").read_text())
        assert run["workers"] == 2 and run["computed"] == 8 and run["scheduler"] == addr
        assert (out / "results.parquet").is_file() and (out / "index.html").is_file()
    finally:
        for pr in reversed(procs):
            pr.terminate()
        for pr in procs:
            try:
                pr.wait(timeout=20)
            except subprocess.TimeoutExpired:
                pr.kill()
        log.close()


def test_docs_quote_the_code():
    """docs/STUDIES.md states the defaults the code has."""
    from shaftfe.study.evaluate import CAMPBELL_TOP_RPM
    from shaftfe.study.runner import CONNECT_TIMEOUT_S, MEMORY_PER_WORKER, MiB
    from shaftfe.study.spec import MAX_DESIGNS_DEFAULT, Analyses
    text = (ROOT / "docs" / "STUDIES.md").read_text()
    assert f"(default {MAX_DESIGNS_DEFAULT})" in text
    assert f"max_rpm (default {CAMPBELL_TOP_RPM:,.0f}".replace(",", " ") in text
    assert f"step_rpm (default {Analyses().campbell_step_rpm:g})" in text
    assert f"within {CONNECT_TIMEOUT_S} s" in text
    from shaftfe.study.check import UNIT_SLIP
    assert f"within {UNIT_SLIP:g}× of the base" in text
    gib = {k: v / MiB for k, v in MEMORY_PER_WORKER.items()}
    assert (f"beam {gib['beam']:.0f} MiB, coarse 3D {gib['coarse'] / 1024:.1f} GiB, default "
            f"{gib['default'] / 1024:.0f} GiB, fine {gib['fine'] / 1024:.0f} GiB") in text


def test_any_override_rederives_the_balance_statement():
    """Turning a counterweight moves X2 (|Σ m e| shrinks); the design loads because the
    statement follows the parts (it was refused when only masses re-derived it)."""
    from shaftfe.model.derive import design_overrides
    from shaftfe.model.loader import load_variant
    o = design_overrides("x2_57", {"attachments.counterweight_1.angle_deg": 90.0})
    v = load_variant("x2_57", o)
    assert o["balance.X2_percent"] < 50.0          # 57 % with both counterweights in line
    assert v.balance_target.X2_percent == o["balance.X2_percent"]


def test_infinite_life_ranks_best():
    import pandas as pd

    from shaftfe.study.results import meets, non_dominated
    df = pd.DataFrame({"status": ["ok", "ok"], "life_h": [float("inf"), 10.0],
                       "engine_max_F_N": [100.0, 100.0]})
    assert non_dominated(df, [("engine_max_F_N", "min"), ("life_h", "max")]) == [True, False]
    assert meets(df, [("life_h", ">=", 100.0)]) == [True, False]


@pytest.mark.slow
def test_reused_factorisation_gives_the_standalone_answer():
    """Two designs of one solid (a part's mass differs; the four-point-bent bar of
    benchmarks.bench_truth, a study's design in miniature): the second, solved on the
    first's K and factorisation (fe.reuse), against its own standalone solve. The same
    matrix factorised again: equal to round-off (BLAS thread scheduling only, 1e-12). The
    shaft's scalar mass (its spin softening, ``static.model.shaft_rows``) is reused too."""
    import dataclasses

    from benchmarks.bench_truth import four_point_bar
    from shaftfe.fe import reuse
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import solve_static
    opts = StaticOptions(level="coarse")
    base = four_point_bar(22.0, 17.0, 1.0)

    def design(mass_kg):
        p, q = base.attachments
        return dataclasses.replace(base, attachments=(p, dataclasses.replace(q,
                                                                             mass_kg=mass_kg)))
    v1, v2 = design(1.0), design(1.3)
    with reuse.shared() as stats:
        solve_static(v1, 10000, opts, beam=False)
        shared = solve_static(v2, 10000, opts, beam=False)
    once = {"K": 1, "factor": 1, "shaft_ritz": 1}           # the shaft mass's Ritz rows
    assert stats["made"] == once and stats["reused"] == once
    alone = solve_static(v2, 10000, opts, beam=False)
    assert shared.mesh_key == alone.mesh_key
    for a, b in zip(shared.cases[0].peaks, alone.cases[0].peaks, strict=True):
        # (a bearing seat wholly inside the singular-point exclusion has no peak: NaN in both)
        assert a.von_mises_MPa == pytest.approx(b.von_mises_MPa, rel=1e-12, nan_ok=True), \
            a.region
    assert [x.F_radial_N for x in shared.cases[0].bearings] == pytest.approx(
        [x.F_radial_N for x in alone.cases[0].bearings], rel=1e-12)


def test_failed_designs_exit_1(tmp_path, capsys, monkeypatch):
    """A run with failed designs is not a finished study: exit 1 and one line saying how many
    (the runner itself is the beam_run fixture's; here only the command's ending)."""
    from shaftfe.study import runner
    p = write(tmp_path)
    rows = ({"design": 0, "status": "failed", "error": "SolverError: x"},)

    def fake(spec, out, **kw):                # the runner checks the study, then announces
        from shaftfe.study import sampling
        from shaftfe.study.check import check_study
        kw["announce"](check_study(spec, sampling.designs(spec)))
        return runner.StudyRun(Path(out), rows, 1, 0, 1, 0, 1, 0.1, 0.1)
    monkeypatch.setattr(runner, "run_study", fake)
    rc, _out, err = run_cli(["study", "run", str(p), "--out", str(tmp_path / "o"),
                            "--no-report"], capsys)
    assert rc == 1
    assert err.splitlines()[0].startswith("shaftfe: 2 designs refused (6, 7)")  # before solving
    assert "1 of 1 designs failed" in err.splitlines()[-1]


# --------------------------------------------------------------------------- issue #30, s2
SHOWCASE = ROOT / "reports" / "studies" / "x2_tradeoff"


@pytest.mark.parametrize("drop", ["all", "study_file", "analyses"])
def test_study_json_without_its_keys_is_damaged(tmp_path, drop):
    """A study.json that is valid JSON but lacks a key the study run writes is refused as
    damaged, naming the key, before anything is read or written (it gave "Base variant base
    ... Study file: None" and overwrote index.html)."""
    from shaftfe.study.report import META_KEYS, read_meta, write_report
    out = tmp_path / "s"
    shutil.copytree(SHOWCASE, out, ignore=shutil.ignore_patterns("designs"))
    meta = json.loads((out / "study.json").read_text())
    assert set(META_KEYS) <= set(meta) and read_meta(out) == meta   # the showcase is whole
    meta = {} if drop == "all" else {k: v for k, v in meta.items() if k != drop}
    (out / "study.json").write_text(json.dumps(meta))
    page = (out / "index.html").read_bytes()
    with pytest.raises(InputError, match="study.json is damaged .no valid .*"
                       + ("study_file" if drop != "analyses" else "analyses")):
        write_report(out)
    assert (out / "index.html").read_bytes() == page


def test_report_on_a_file_says_it_is_a_file(tmp_path):
    from shaftfe.study.report import read_meta
    f = write(tmp_path)
    with pytest.raises(InputError, match="is a file, not a study folder"):
        read_meta(f)
    with pytest.raises(InputError, match="does not exist"):
        read_meta(tmp_path / "nothing")


def test_fatigue_numbers_name_their_method_and_card(tmp_path):
    """The study's fatigue numbers are the seed method's on the study's S-N card (not
    `shaftfe fatigue`'s FKM default): every label on the page says so, the page says how they
    differ, and the numbers in the table are the committed table's, unchanged."""
    import pandas as pd

    from shaftfe.study.report import labels, write_report
    lab = labels({"material": "14220"})
    assert lab["fatigue_sf"] == "fatigue safety factor (seed method, S-N card 14220)"
    assert lab["life_h"] == "fatigue life (seed method, S-N card 14220) [h]"
    out = tmp_path / "s"
    shutil.copytree(SHOWCASE, out, ignore=shutil.ignore_patterns("designs"))
    page = write_report(out).read_text()
    basis = "(seed method, S-N card structural_steel)"
    assert f"fatigue safety factor {basis}" in page and f"fatigue life {basis} [h]" in page
    assert "fatigue safety factor</th>" not in page and "fatigue life [h]" not in page
    assert "shaftfe fatigue --method seed --material structural_steel" in page
    assert "default method (FKM" in page
    shown = pd.read_csv(SHOWCASE / "results.csv")
    assert pd.read_csv(out / "results.csv").equals(shown)


def test_a_zoned_design_row_is_the_zoned_solve_and_needs_no_shared_solid(cache, monkeypatch):
    """``analyses.static.model = "zoned"``: a design's static columns are `shaftfe static`'s
    (the zoned solve, the same options) number for number (the same code and inputs: exact),
    its fatigue row is the seed method on the zoned surface reference, and the planner gives
    every design a task of its own with no shared 3D mesh to build."""
    from shaftfe.model.loader import load_variant
    from shaftfe.static.model import StaticOptions
    from shaftfe.study.evaluate import evaluate_design
    from shaftfe.study.runner import plan_tasks
    from shaftfe.study.spec import Analyses
    from shaftfe.zoned.solve import solve_zoned
    monkeypatch.setenv("SHAFTFE_CACHE_DIR", str(cache))
    an = Analyses(static=True, static_model="zoned", level="coarse", spin_softening=False,
                  fatigue=True, spectrum=str(ROOT / "loadspectra" / "rpm.dat"))
    row = evaluate_design("x2_57", {}, an)
    assert row["status"] == "ok", row["error"]
    res = solve_zoned(load_variant("x2_57"), [10000.0, 7000.0],
                      StaticOptions(level="coarse", spin_softening=False))
    peaks = {p.region: p.von_mises_MPa for p in res.cases[0].peaks}
    for region in ("keyway:gear_seat:0", "keyway:cw2_seat:0", "fillet:bearing_seat_gear"):
        assert row[f"stress_{region}_MPa"] == peaks[region]
    assert row["static_max_deflection_mm"] == res.cases[0].max_axis_deflection_mm
    for b in res.case(7000.0).bearings:       # the bearing speed's columns (L10h at 7000 rpm)
        assert row[f"static_F_{b.name}_N"] == b.F_radial_N and row[f"L10h_{b.name}_h"] == b.L10h
    assert row["fatigue_hot_spot"].startswith("fillet:")
    g = res.global_result                  # the global model's dofs and the zones' together
    assert row["n_dofs"] == 3 * g.n_nodes * len(g.harmonics) + sum(z.n_dofs for z in res.zones)
    # with spin softening the fatigue row takes one more (unsoftened) zoned solve on the same
    # points: the design evaluates, and its static columns are the softened solve's
    import dataclasses
    soft = evaluate_design("x2_57", {}, dataclasses.replace(an, spin_softening=True))
    assert soft["status"] == "ok", soft["error"]
    assert soft["fatigue_hot_spot"].startswith("fillet:") and soft["fatigue_sf"] > 0
    assert soft["stress_max_MPa"] > row["stress_max_MPa"]     # softening adds deflection
    # its bearing columns: the softened zoned solve's at 7000 rpm (exact: the same global solve)
    sres = solve_zoned(load_variant("x2_57"), [10000.0, 7000.0],
                       StaticOptions(level="coarse", spin_softening=True))
    for b in sres.case(7000.0).bearings:
        assert soft[f"static_F_{b.name}_N"] == b.F_radial_N
        assert soft[f"L10h_{b.name}_h"] == b.L10h
    assert "static_model" in an.options() and "static_model" not in Analyses().options()
    from types import SimpleNamespace
    todo = [(f"d{i}", SimpleNamespace(overrides={}, number=i)) for i in range(3)]
    tasks = plan_tasks(SimpleNamespace(analyses=an, base="x2_57"), todo)
    assert [g for g, _ in tasks] == [None, None, None]
