"""`shaftfe report` (issue 7): the whole assessment of a variant as one self-contained HTML page.

One coarse-mesh run (module fixture, ~35-45 s on a loaded 2-core machine: a cold Gmsh mesh, one
static solve, fatigue, Campbell, three PyVista renders, nine plots) serves the content tests; the
bad-input and import tests stop before any computation.
"""

import base64
import io
import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from html.parser import HTMLParser
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PNG = b"\x89PNG\r\n\x1a\n"
VOID = {"meta", "img", "br", "hr", "link", "input", "col", "source", "wbr"}


def _env(tmp: Path) -> dict:
    return {**os.environ, "SHAFTFE_CACHE_DIR": str(tmp / "cache"), "MPLBACKEND": "Agg"}


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("report")
    out = tmp / "rep"
    # the seed's load case, so that the seed figures compare like with like
    # the full 3D model (its volume VTU, its level's error bars); the default, zoned, model's
    # report is tests/test_zoned_cli.py's
    p = subprocess.run([sys.executable, "-m", "shaftfe", "report", "--variant", "x2_57",
                        "--level", "coarse", "--model", "solid", "--seed-load-case", "--out",
                        str(out), "--json"],
                       capture_output=True, text=True, env=_env(tmp), cwd=ROOT)
    assert p.returncode == 0, p.stderr[-3000:]
    return out, p


def test_report_is_written_and_json_matches(run):
    out, p = run
    summary = json.loads((out / "summary.json").read_text())
    assert json.loads(p.stdout) == summary                  # --json prints summary.json
    assert p.stderr == ""                                   # no progress display with --json
    assert (out / "index.html").stat().st_size > 100_000
    assert (out / "x2_57.vtu").stat().st_size > 100_000
    stages = summary["timings_s"]
    for stage in ("balancing", "static (mesh + one solve)", "fatigue", "Campbell"):
        assert stage in stages and stages[stage] >= 0
    assert summary["static"]["level"] == "coarse"
    # one solve: the static stage solved once, the fatigue stage reused it (no second mesh)
    assert summary["sub_timings_s"]["factorisation"] > 0


class _Checker(HTMLParser):
    """Tag balance of the HTML5 page (void elements excepted) and the image sources."""

    def __init__(self):
        super().__init__()
        self.stack, self.errors, self.imgs, self.ids = [], [], [], set()

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "img":
            self.imgs.append(a.get("src", ""))
        if tag not in VOID:
            self.stack.append(tag)

    def handle_startendtag(self, tag, attrs):
        self.handle_starttag(tag, attrs)
        if tag not in VOID:
            self.stack.pop()

    def handle_endtag(self, tag):
        if tag in VOID:
            return
        if not self.stack or self.stack[-1] != tag:
            self.errors.append(f"</{tag}> closes {self.stack[-1:] or 'nothing'}")
        else:
            self.stack.pop()


def test_html_is_well_formed_and_every_image_is_a_png(run):
    out, _ = run
    text = (out / "index.html").read_text(encoding="utf-8")
    ET.fromstring(text.split("\n", 1)[1])          # strict XML well-formedness (after doctype)
    c = _Checker()
    c.feed(text)
    c.close()
    assert not c.errors and not c.stack, (c.errors, c.stack)
    for section in ("summary", "inputs", "balancing", "static", "fatigue", "campbell", "seed",
                    "errors", "timing", "files"):
        assert section in c.ids, section
    # each standard along the shaft, on the page (in "Strength by standard")
    assert {"fig-fkm_along", "fig-din743_along"} <= set(c.ids)
    assert len(c.imgs) >= 14
    for src in c.imgs:
        head, data = src.split(",", 1)
        assert head == "data:image/png;base64"
        png = base64.b64decode(data, validate=True)
        assert png.startswith(PNG) and len(png) > 5_000
    for name in ("von_mises_3d", "displacement_3d", "safety_factor_3d", "balance_forces",
                 "balance_sweep", "deflection", "campbell", "rainflow_matrix", "damage_matrix",
                 "haigh", "load_history", "sn_curve", "fkm_along", "din743_along"):
        f = out / "figures" / f"{name}.png"
        assert f.read_bytes().startswith(PNG) and f.stat().st_size > 5_000, name


def test_seed_table_carries_the_computed_numbers(run):
    """Every 'ours' in the comparison is the analysis modules' number, every 'seed' the seed
    module's (not retyped), and the page shows them."""
    from shaftfe.fatigue.run import SEED as FATIGUE
    from shaftfe.report import seed
    from shaftfe.report.html import num

    out, _ = run
    s = json.loads((out / "summary.json").read_text())
    html = (out / "index.html").read_text(encoding="utf-8")

    def row(group, start, unit=None):
        return next(c for c in s["comparisons"] if c["group"] == group
                    and c["quantity"].startswith(start) and unit in (None, c["unit"]))

    cases = {c["rpm"]: c for c in s["static"]["cases"]}
    reac = {b["name"]: b["F_radial_N"] for b in cases[10_000.0]["bearings"]}
    r = row("static", "reaction gear side, 10 000")
    assert r["seed"] == seed.STATIC["reaction_gear_side_10000_N"]
    assert r["ours"] == reac["gear_side"]
    # exact arithmetic (the same formula; measured 0), in % units of O(1)
    assert abs(r["diff_percent"] - 100 * (reac["gear_side"] / r["seed"] - 1)) < 1e-9
    r = row("static", "max reduced")
    assert r["ours"] == cases[10_000.0]["peak_von_mises_MPa"]
    hs = s["fatigue"]["hot_spot"]
    for q, unit, key, seed_key in (
            ("safety factor", "-", "safety_factor", "safety_factor_at_1e7"),
            ("life", "blocks", "life_blocks", "life_blocks"),
            ("life", "h", "life_hours", "life_hours"), ("life", "km", "life_km", "life_km")):
        r = row("fatigue", q, unit)
        assert r["ours"] == hs[key] and r["seed"] == FATIGUE[seed_key]
    f0 = [t["f0_hz"] for t in s["campbell"]["table"]]
    r = row("rotor dynamics", "mode 1 at 0 rpm")
    assert r["ours"] == f0[0] and r["seed"] == seed.CAMPBELL["freq_0rpm_hz"][0]
    assert len([c for c in s["comparisons"] if c["group"] == "rotor dynamics"]) == 13
    for c in s["comparisons"]:
        assert num(c["ours"], 5) in html, c
    # sanity of the physics the table shows: reactions within 3 %, the allowance for the
    # reconstructed geometry (tests/validation/test_static_x2_57.py; measured −0.4 %/+0.8 %)
    for side in ("gear_side", "free_side"):
        r = row("static", f"reaction {side.replace('_', ' ')}, 10 000")
        assert abs(r["diff_percent"]) < 3


def test_vtu_has_the_documented_fields(run):
    """docs/FIELDS.md: displacement, von_mises, stress (6), safety_factor, life_blocks,
    damage_per_block and the region ids, readable by meshio and PyVista; names in the sidecar."""
    import meshio
    import numpy as np
    import pyvista as pv

    out, _ = run
    s = json.loads((out / "summary.json").read_text())
    m = meshio.read(out / "x2_57.vtu")
    n = m.points.shape[0]
    shapes = {"displacement": (n, 3), "von_mises": (n,), "stress": (n, 6),
              "safety_factor": (n,), "life_blocks": (n,), "damage_per_block": (n,)}
    for name, shape in shapes.items():
        assert m.point_data[name].shape == shape, name
    modes = s["vtu"]["modes"]                      # mode shapes: mode_<k>_<f>Hz, max |u| = 1
    assert len(modes) == len(s["campbell"]["table"])
    mm = meshio.read(out / s["vtu"]["modes_file"])
    assert mm.points.shape == m.points.shape
    for k, (name, row) in enumerate(zip(modes, s["campbell"]["table"], strict=True)):
        assert name == f"mode_{k + 1}_{row['f0_hz']:.2f}Hz"
        u = mm.point_data[name]
        assert u.shape == (n, 3)
        # shapes stored as float32 (eps 6e-8, measured 6e-8): 1e-6 covers the rounded norm
        assert np.linalg.norm(u, axis=1).max() == pytest.approx(1.0, rel=1e-6)
    region = np.concatenate(m.cell_data["region"])
    assert region.min() == 0 and region.max() == len(s["vtu"]["regions"])
    g = pv.read(out / "x2_57.vtu")
    sf = np.asarray(g.point_data["safety_factor"])
    # exact: the same float64 in the .vtu and the JSON (measured equal; approx's default 1e-6)
    assert sf.min() == pytest.approx(s["fatigue"]["hot_spot_unfiltered"]["safety_factor"])
    # the peak is located by a local fit (shaftfe.fe.surface.local_peak) whose polynomial
    # passes through the largest node's value at that node (the same patch fit that recovered
    # it): so the nodal maximum can never exceed it (1e-12: round-off of the same sums, scale
    # (10 000/REF_RPM)² = 1)
    assert np.asarray(g.point_data["von_mises"]).max() <= (
        s["static"]["cases"][0]["peak_von_mises_unfiltered_MPa"] * (1 + 1e-12))


@pytest.mark.parametrize("argv, needle", [
    (["--variant", "nosuch"], "variant"),
    (["--spectrum", "no/such/rpm.dat"], "no/such/rpm.dat"),
    (["--level", "huge"], "--level"),
])
def test_bad_input_is_one_line_and_writes_nothing(tmp_path, argv, needle):
    out = tmp_path / "rep"
    p = subprocess.run([sys.executable, "-m", "shaftfe", "report", *argv, "--out", str(out)],
                       capture_output=True, text=True, env=_env(tmp_path), cwd=ROOT)
    assert p.returncode == 2
    assert "Traceback" not in p.stderr
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0], p.stderr
    assert not (out / "index.html").exists()


def test_report_help_does_not_import_the_fe_stack():
    code = ("import sys, contextlib, io\nfrom shaftfe.cli import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            "    try:\n        main(['report', '--help'])\n    except SystemExit:\n        pass\n"
            "heavy = [m for m in ('gmsh', 'skfem', 'pyvista', 'matplotlib', 'meshio', 'vtk', "
            "'numpy') if m in sys.modules]\nprint('HEAVY', heavy)\n")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert "HEAVY []" in p.stdout, p.stdout + p.stderr


class _Tty(io.StringIO):
    def isatty(self):
        return True


def test_progress_shows_stages_on_a_terminal_only():
    from shaftfe.util.progress import Progress

    tty = _Tty()
    prog = Progress(["a", "b"], stream=tty)
    with prog.stage("a"):
        pass
    with pytest.raises(ValueError), prog.stage("b"):
        raise ValueError
    text = tty.getvalue()
    assert "[1/2] a ..." in text and "[2/2] b" in text and "failed" in text
    assert [n for n, _ in prog.timings] == ["a", "b"]
    quiet = io.StringIO()                         # not a terminal: nothing shown, still timed
    prog = Progress(["a"], stream=quiet)
    with prog.stage("a"):
        pass
    assert quiet.getvalue() == "" and len(prog.timings) == 1
    forced_off = _Tty()                           # --json
    with Progress(["a"], stream=forced_off, enabled=False).stage("a"):
        pass
    assert forced_off.getvalue() == ""


# --------------------------------------------------------------------------- issue 30 §3, §4:
# one value per quantity, the headline's method, the warnings banner, the pictures


def _section(html: str, start: str, end: str) -> str:
    return html[html.index(f'id="{start}"'):html.index(f'id="{end}"')]


def test_headline_is_the_default_method_named_with_its_verdict(run):
    """The summary cards show the default method of ``shaftfe fatigue`` (FKM), named, with
    its pass/fail; the seed method's safety factor is not a headline card (it stays in
    Strength by standard and the seed comparison)."""
    from shaftfe.fatigue.method_options import DEFAULT_METHOD
    from shaftfe.report.html import num

    out, _ = run
    s = json.loads((out / "summary.json").read_text())
    html = (out / "index.html").read_text(encoding="utf-8")
    head = _section(html, "summary", "inputs")
    assert s["strength"]["default_method"] == DEFAULT_METHOD == "fkm"
    g, rule = s["strength"]["fkm"]["governing"], s["strength"]["fkm"]["rule"]
    u = g["utilisation"][rule]
    verdict = "passes" if u <= 1 else "FAILS"
    assert f"{num(u, 3, strip=False)}: {verdict}" in head
    assert "FKM degree of utilisation" in head and "FKM safety factor" in head
    assert num(g["safety"][rule], 3, strip=False) in head
    seed_sf = num(s["fatigue"]["hot_spot"]["safety_factor"], 3)
    assert seed_sf not in head                            # the seed method is not the headline
    assert seed_sf in _section(html, "strength", "campbell")


def test_one_peak_value_or_the_difference_named(run):
    """The static peak (surface fit) and the largest nodal value (3D picture, ``view``,
    the seed hot spot's stress) are both printed, each named; the load factor's reference
    speed is the same in the fatigue text and the load-history caption."""
    import numpy as np
    import pyvista as pv

    from shaftfe.report.html import PEAK_FIT_LABEL, num

    out, _ = run
    s = json.loads((out / "summary.json").read_text())
    html = (out / "index.html").read_text(encoding="utf-8")
    c0 = s["static"]["cases"][0]
    fit, node = c0["peak_von_mises_MPa"], c0["peak_von_mises_node_MPa"]
    # the local fit passes through the largest node's value (test above): never below it
    # (1e-12: round-off of the same sums)
    assert node <= fit * (1 + 1e-12)
    vm = np.asarray(pv.read(out / "x2_57.vtu").point_data["von_mises"])
    assert node in vm                   # a value of the file (the same float64 written)
    head = _section(html, "summary", "inputs")
    assert f"{num(fit, 4)} MPa" in head and PEAK_FIT_LABEL in head
    assert f"largest nodal value {num(node, 4)} MPa" in head
    i = html.index('id="fig-von_mises_3d"')
    cap = html[html.index("<figcaption>", i):html.index("</figure>", i)]
    assert f"{num(fit, 4)} MPa, is the {PEAK_FIT_LABEL}" in cap
    assert f"{node:.4g} MPa (nodal value)" in cap
    ref = s["fatigue"]["history"]["static_ref_rpm"]
    fat = _section(html, "fatigue", "strength")
    assert f"(n / {num(ref)})²" in fat and f"load factor (n / {ref:g})²" in fat
    for label in ("the node of least seed safety (nodal value)",
                  "the node of highest FKM utilisation"):
        assert label in _section(html, "strength", "campbell")


def test_summary_json_has_the_warnings_of_the_run(run):
    out, _ = run
    s = json.loads((out / "summary.json").read_text())
    assert s["warnings"] == []                 # the bundled variant raises none
    html = (out / "index.html").read_text(encoding="utf-8")
    assert 'id="warnings"' not in html


def test_warnings_banner_and_summary_key():
    """``Report.warnings`` (``notices.collected()`` of the run) goes into summary.json under
    "warnings" and into a banner above the summary, one item per warning, escaped."""
    import dataclasses

    from shaftfe.report import html
    from shaftfe.report.options import ReportOptions
    from shaftfe.report.results import Report

    w = ({"code": "sharp-shoulder", "where": "shoulder:collar", "text": "r = 0 <singular>"},)
    empty = {f.name: {} for f in dataclasses.fields(Report)
             if f.type in ("dict", dict) and f.default is dataclasses.MISSING}
    rep = Report(options=ReportOptions(variant="x2_57", spectrum="rpm.dat"), created_utc="",
                 comparisons=(), errors=(), timings=(), figures=(), warnings=w, **empty)
    assert rep.to_dict()["warnings"] == [w[0]]
    banner = html._banner(rep)
    assert 'id="warnings"' in banner and "1 warning:" in banner
    assert "<b>shoulder:collar</b>: r = 0 &lt;singular&gt;" in banner
    assert html._banner(dataclasses.replace(rep, warnings=())) == ""


def test_colour_bar_ticks_are_round_and_one_is_yellow():
    """safety_factor_3d / von_mises_3d: the colour range widened to round ticks (no 0.4722 /
    1.104 …); the safety factor's map is yellow exactly at 1, red below, green above."""
    from matplotlib import colormaps

    from shaftfe.io.render import _tick_format, nice_range, safety_colormap

    assert nice_range(0.101, 497.2) == (0.0, 500.0, 6)
    lo, hi, n = nice_range(0.4671, 2.9)
    assert (lo, hi) == (0.0, 3.0) and _tick_format((hi - lo) / (n - 1)) == "%.1f"
    assert _tick_format(100.0) == "%.0f" and _tick_format(0.25) == "%.2f"
    cm = safety_colormap(0.0, 3.0, n=301)          # entry k is the colour of 0.01 k
    # exact: the same RdYlGn lookup at its middle (0.5) as at the value 1.0 (entry 100)
    assert cm(100 / 300) == colormaps["RdYlGn"](0.5)
    r, g, _, _ = cm(0.0)
    assert r > 0.6 > g                                # red below 1
    r, g, _, _ = cm(1.0)
    assert g > 0.3 > r                                # green at the top of the scale


def test_count_matrix_has_a_discrete_integer_colour_bar(tmp_path):
    """rainflow_matrix.png: whole-number ticks, one colour per count up to 10, logarithmic
    whole-number bins beyond; damage_matrix.png: one label format (powers of ten)."""
    import numpy as np

    from shaftfe.fatigue.counting import CycleMatrix
    from shaftfe.fatigue.plots import _count_norm, plot_cycle_matrix

    norm, ticks, cmap = _count_norm(np.array([[0.0, 1.0], [3.0, 2.0]]))
    assert list(ticks) == [1, 2, 3] and cmap.N == 3
    assert [int(norm(v)) for v in (1, 2, 3)] == [0, 1, 2]      # one colour per count
    norm, ticks, _ = _count_norm(np.array([[1.0, 37.0], [0.0, 130.0]]))
    assert list(ticks) == [1, 2, 5, 10, 20, 50, 100, 200]
    assert all(float(t).is_integer() for t in ticks)
    norm, ticks, _ = _count_norm(np.array([[0.5, 1.5]]))       # half cycles left
    assert list(ticks) == [0.5, 1.0, 1.5]
    e = np.linspace(0.0, 100.0, 3)
    path = plot_cycle_matrix(CycleMatrix(e, e, np.array([[1.7e-4, 0.0], [7.5e-5, 2e-6]]),
                                         "damage", "MPa"), tmp_path / "d.png")
    assert path.read_bytes().startswith(PNG)


def test_load_plane_is_signed_and_follows_the_bending():
    """deflection.png: the deflection is projected on the plane the axis bends in, signed, so
    a line through zero (a rigid tilt on the springs) is not folded into a kink."""
    import numpy as np

    from shaftfe.io.vtu import load_plane

    x = np.linspace(-1.0, 1.0, 11)
    d = np.array([0.6, -0.8])                       # a tilt through zero in that plane
    n = load_plane(x * d[0], x * d[1])
    # exact up to the eigen-solver's round-off (unit vectors, O(1e-16))
    assert abs(abs(n @ d) - 1.0) < 1e-12
    signed = np.column_stack([x * d[0], x * d[1]]) @ n
    assert np.all(np.diff(signed) > 0) or np.all(np.diff(signed) < 0)   # no fold at 0
    n2 = load_plane(-(x ** 2 + 0.1) * d[0], -(x ** 2 + 0.1) * d[1])
    assert n2 @ d < 0                               # the largest deflection is positive


def test_view_names_the_fitted_peak_of_the_sidecar(tmp_path):
    """``shaftfe view result.vtu`` prints the nodal maximum; the run's summary.json prints the
    surface-fit peak; view names that value and the difference beside its own."""
    from shaftfe.io import view

    ch = view.FieldChoice("von_mises", "point", 1, None, "von_mises", "MPa", "max")
    vtu = tmp_path / "result.vtu"
    (tmp_path / "summary.json").write_text(json.dumps(
        {"vtu": {"file": "result.vtu", "rpm": 10000.0},
         "cases": [{"rpm": 10000.0, "peak_von_mises_MPa": 509.21},
                   {"rpm": 7000.0, "peak_von_mises_MPa": 249.5}]}))
    assert view.fitted_peak(vtu, ch) == 509.21
    assert view.fitted_peak(tmp_path / "other.vtu", ch) is None     # another file's summary
    sf = view.FieldChoice("safety_factor", "point", 1, None, "safety_factor", "-", "min")
    assert view.fitted_peak(vtu, sf) is None


def test_life_error_row_when_the_hot_spot_fails_in_the_first_block():
    """An allowed overspeed can put a cycle above the static strength: the hot spot's life is
    0 blocks. The error table's life row then says so instead of dividing by zero (the report
    crashed with ZeroDivisionError: issue #30 review)."""
    from shaftfe.report.comparisons import _check_rows
    static = {"cases": [{"rpm": 10000.0, "bearings": [], "beam_springs": {}}],
              "relative_residual": 1e-12, "solver": "pardiso"}
    rows = _check_rows(static, static["cases"][0], {"hot_spot": {"life_blocks": 0.0}},
                       {"life_blocks": 0.0, "safety_factor": 0.06, "factor": 1.01},
                       {"table": [{"f0_hz": 481.1}], "verify": {"max_rel_diff": 1e-9,
                                                                 "rpm": 0.0},
                        "basis_change": 1e-9, "description": "beam rotor"})
    life = next(r for r in rows if r.quantity == "fatigue life at the hot spot")
    assert "fails in the first block" in life.error


def test_pictures_render_here_when_no_second_process_can(monkeypatch):
    """``report.pictures``: where the second process cannot start (``Renderer``) or dies
    (BrokenProcessPool), the pictures (and the figure jobs handed to it: one ``Job``) are made
    in this process; an error of the rendering itself is raised, not hidden."""
    import concurrent.futures
    from concurrent.futures.process import BrokenProcessPool

    import numpy as np

    from shaftfe.report import pictures
    job = pictures.PictureJob("x.vtu", "figures", np.zeros(0, dtype=int), ())
    here = ([("von_mises_3d", "t", "c")], 0.5)
    monkeypatch.setattr(pictures, "render_all", lambda j: here if j is job else None)

    class Broken:
        def result(self):
            raise BrokenProcessPool("killed")

    class Failing:
        def result(self):
            raise ValueError("no such field")

    assert pictures.Job(pictures.render_all, (job,), Broken()).result() is here
    with pytest.raises(ValueError, match="no such field"):
        pictures.Job(pictures.render_all, (job,), Failing()).result()

    def refuse(*a, **k):
        raise OSError("no processes here")
    monkeypatch.setattr(concurrent.futures, "ProcessPoolExecutor", refuse)
    assert pictures.Renderer().start(job).result() is here

    # a figure job (``Renderer.draw``): drawn here without a second process or when it died,
    # its own error raised
    drawn = []
    pictures.Renderer().draw(drawn.append, "balance").result()
    pictures.Job(drawn.append, ("again",), Broken()).result()
    assert drawn == ["balance", "again"]
    with pytest.raises(ValueError, match="no such field"):
        pictures.Job(drawn.append, ("never",), Failing()).result()
    assert drawn == ["balance", "again"]
