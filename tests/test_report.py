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
    p = subprocess.run([sys.executable, "-m", "shaftfe", "report", "--variant", "x2_57",
                        "--level", "coarse", "--seed-load-case", "--out", str(out), "--json"],
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
    assert len(c.imgs) >= 12
    for src in c.imgs:
        head, data = src.split(",", 1)
        assert head == "data:image/png;base64"
        png = base64.b64decode(data, validate=True)
        assert png.startswith(PNG) and len(png) > 5_000
    for name in ("von_mises_3d", "displacement_3d", "safety_factor_3d", "balance_forces",
                 "balance_sweep", "deflection", "campbell", "rainflow_matrix", "damage_matrix",
                 "haigh", "load_history", "sn_curve"):
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
