"""`shaftfe view`: headless rendering, hot spot, field/component choice, input errors.

The result files are made here: a 40 × 8 × 8 mm bar of quadratic tetrahedra (tetra10, with the
mid-side nodes on the edge midpoints) plus triangle6 face cells carrying ``region`` ids, and
synthetic point fields ``von_mises`` / ``displacement`` / ``stress`` / ``safety_factor``.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

pv = pytest.importorskip("pyvista")

from shaftfe.cli import main  # noqa: E402
from shaftfe.io import render, surface, view  # noqa: E402

TET10_EDGES = ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))


def _tet10_bar():
    """(points, tetra10 connectivity) of a bar x 0..40, y, z -4..4 mm."""
    box = pv.ImageData(dimensions=(11, 3, 3), spacing=(4.0, 4.0, 4.0), origin=(0.0, -4.0, -4.0))
    tet = box.triangulate()
    t4 = tet.cells_dict[pv.CellType.TETRA]
    p = np.asarray(tet.points, float)
    # positive volume (outward faces), as a mesher writes them
    a, b, c, d = (p[t4[:, i]] for i in range(4))
    neg = np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a) < 0
    t4[neg] = t4[neg][:, [1, 0, 2, 3]]
    edges = np.concatenate([np.sort(t4[:, e], axis=1) for e in TET10_EDGES])
    uniq, inv = np.unique(edges, axis=0, return_inverse=True)
    mids = 0.5 * (p[uniq[:, 0]] + p[uniq[:, 1]])
    mid_ids = (len(p) + inv.reshape(-1)).reshape(len(TET10_EDGES), -1).T
    return np.vstack([p, mids]), np.hstack([t4, mid_ids]).astype(np.int64)


def _write_result(path: Path, fields=("von_mises", "displacement", "stress", "safety_factor"),
                  faces: bool = True) -> dict:
    pts, t10 = _tet10_bar()
    cells = {pv.CellType.QUADRATIC_TETRA: t10}
    region_faces = None
    if faces:
        # the x = 0 end face (triangle6 cells taken from the tets' boundary): region 3
        tmp = pv.UnstructuredGrid(cells, pts)
        bnd = surface.boundary(tmp, view.FieldChoice("x", "point", 1, None, "x", "-", "max"),
                            np.zeros(len(pts)))
        conn = bnd.cells_dict[pv.CellType.QUADRATIC_TRIANGLE]
        # exact: grid coordinates (x = 0 stored exactly); isclose's default atol 1e-8
        on_end = np.all(np.isclose(pts[conn[:, :3], 0], 0.0), axis=1)
        region_faces = conn[on_end]
        cells[pv.CellType.QUADRATIC_TRIANGLE] = region_faces
    g = pv.UnstructuredGrid(cells, pts)
    x, y, z = pts.T
    out = {"points": pts}
    # von Mises: smooth, with a unique maximum at a surface node (not at a mid-side node)
    target = int(np.argmin(np.hypot(x - 28.0, np.hypot(y - 4.0, z - 4.0))))
    vm = 50.0 + 2.0 * x + 5.0 * y
    vm[target] = vm.max() + 40.0
    if "von_mises" in fields:
        g.point_data["von_mises"] = vm
        out["von_mises"] = vm
    if "displacement" in fields:
        u = np.column_stack([np.zeros_like(x), 1e-5 * x**2, 2e-6 * x**2])
        g.point_data["displacement"] = u
        out["displacement"] = u
    if "stress" in fields:
        s = np.column_stack([3.0 * y * x, y, z, -x, 0 * x, 0.5 * z])
        g.point_data["stress"] = s
        out["stress"] = s
    if "safety_factor" in fields:
        sf = 3.0 - 0.04 * x + 0.01 * z
        g.point_data["safety_factor"] = sf
        out["safety_factor"] = sf
    if faces:
        region = np.zeros(g.n_cells, dtype=np.int32)
        region[len(t10):] = 3
        g.cell_data["region"] = region
        out["region_faces"] = region_faces
    g.save(path)
    return out


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    d = tmp_path_factory.mktemp("view")
    path = d / "result.vtu"
    data = _write_result(path)
    return path, data


@pytest.fixture
def headless(monkeypatch):
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)


def _image(path: Path) -> np.ndarray:
    import matplotlib.image

    return np.asarray(matplotlib.image.imread(str(path)))[..., :3]


def _clean_env() -> dict:
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY",
                                                              "VTK_DEFAULT_OPENGL_WINDOW")}
    return env


# ---------------------------------------------------------------------------------------------
# rendering


@pytest.mark.slow
def test_screenshot_headless_like_ci(result, tmp_path):
    """A fresh process without DISPLAY (as CI runs it) writes a real, non-uniform PNG."""
    path, data = result
    shot = tmp_path / "shots" / "vm.png"
    cp = subprocess.run([sys.executable, "-m", "shaftfe", "view", str(path), "--screenshot",
                         str(shot), "--window-size", "800x450"],
                        capture_output=True, text=True, env=_clean_env(), timeout=120)
    assert cp.returncode == 0, cp.stderr
    lines = cp.stdout.strip().splitlines()
    assert len(lines) == 1
    line = lines[0]
    assert str(path) in line and "von_mises [MPa]" in line and str(shot) in line
    vm = data["von_mises"]
    assert f"{vm.max():.4g}" in line and f"{vm.min():.4g}" in line
    assert shot.stat().st_size > 10_000
    img = _image(shot)
    assert img.shape == (450, 800, 3)
    assert img.std() > 0.05       # not a blank image (a pixel statistic, not a numerical result)
    assert len(np.unique((img * 255).astype(np.uint8).reshape(-1, 3), axis=0)) > 200
    assert [p.name for p in shot.parent.iterdir()] == ["vm.png"]     # no temporary left


def test_hot_spot_marker_and_colours_visible(result, tmp_path, headless):
    path, _ = result
    shot = tmp_path / "a.png"
    res = render.render(path, screenshot=shot, window_size=(800, 450))
    assert res.off_screen and res.screenshot == str(shot)
    img = _image(shot)
    r, g, b = img[..., 0], img[..., 1], img[..., 2]
    magenta = (r > 0.6) & (b > 0.6) & (g < 0.35)          # the hot-spot sphere, not in jet
    assert magenta.sum() > 20
    red = (r > 0.6) & (g < 0.3) & (b < 0.3)               # jet's hot end on the bar
    # colour classes of rendered pixels (jet's cold end), not a numerical result
    blue = (b > 0.5) & (r < 0.2) & (g < 0.3)
    assert red.sum() > 50 and blue.sum() > 50


def test_default_headless_without_screenshot_writes_next_to_file(tmp_path, headless, capsys):
    path = tmp_path / "only_disp.vtu"
    _write_result(path, fields=("displacement",), faces=False)
    assert main(["view", str(path), "--window-size", "400x300", "--warp", "auto",
                 "--camera", "xy", "--edges"]) == 0
    out = capsys.readouterr().out.strip()
    shot = tmp_path / "only_disp_displacement.png"
    assert shot.is_file() and _image(shot).std() > 0.02     # not blank (pixel statistic)
    assert "displacement magnitude [mm]" in out and "warp x" in out and str(shot) in out


def test_warp_without_displacement_says_so(tmp_path, headless, capsys):
    path = tmp_path / "vm_only.vtu"
    _write_result(path, fields=("von_mises",), faces=False)
    shot = tmp_path / "w.png"
    assert main(["view", str(path), "--warp", "500", "--screenshot", str(shot),
                 "--window-size", "300x200"]) == 0
    err = capsys.readouterr().err
    assert "no 'displacement' field" in err and shot.is_file()


# ---------------------------------------------------------------------------------------------
# pure functions


def test_hot_spot_is_argmax_of_von_mises(result):
    path, data = result
    g = view.load(path)
    ch = view.choose_field(g, None, None)
    assert ch.name == "von_mises" and ch.unit == "MPa"
    hot = view.hot_spot(g, ch)
    i = int(np.argmax(data["von_mises"]))
    assert hot.rule == "max" and hot.index == i
    # exact: float64 written and read back (measured identical); approx/allclose defaults
    assert hot.value == pytest.approx(data["von_mises"][i])
    np.testing.assert_allclose(hot.xyz, data["points"][i])


def test_hot_spot_min_for_safety_factor_and_abs_for_components(result):
    path, data = result
    g = view.load(path)
    sf = view.hot_spot(g, view.choose_field(g, "safety_factor", None))
    assert sf.rule == "min" and sf.index == int(np.argmin(data["safety_factor"]))
    ch = view.choose_field(g, "stress", None)               # default component: xx
    assert ch.component == "xx" and ch.label == "stress xx"
    sxx = data["stress"][:, 0]
    hot = view.hot_spot(g, ch)
    # exact (float64 round trip): approx's default rel 1e-6
    assert hot.rule == "max_abs" and abs(hot.value) == pytest.approx(np.abs(sxx).max())
    yz = view.choose_field(g, "stress", "4")
    assert yz.label == "stress yz"
    mag = view.choose_field(g, "displacement", None)
    assert mag.component == "magnitude"
    # exact arithmetic (float64 round trip, one norm): assert_allclose's default rtol 1e-7
    np.testing.assert_allclose(view.values(g, mag), np.linalg.norm(data["displacement"], axis=1))
    uy = view.choose_field(g, "displacement", "y")
    np.testing.assert_allclose(view.values(g, uy), data["displacement"][:, 1])   # same


def test_non_finite_values_are_skipped_by_the_hot_spot(tmp_path):
    path = tmp_path / "life.vtu"
    _write_result(path, fields=(), faces=False)
    g = pv.read(path)
    life = np.full(g.n_points, np.inf)
    life[7], life[11] = 3.0e4, 2.5e4
    g.point_data["life_blocks"] = life
    g.save(path)
    g = view.load(path)
    hot = view.hot_spot(g, view.choose_field(g, "life_blocks", None))
    assert hot.rule == "min" and hot.index == 11 and hot.value == 2.5e4


def test_region_of_face_cells_is_mapped_onto_the_boundary(result):
    path, data = result
    g = view.load(path)
    ch = view.choose_field(g, "region", None)
    assert ch.association == "cell" and ch.rule == "none" and view.hot_spot(g, ch) is None
    bnd = surface.boundary(g, ch, view.values(g, ch))
    v = np.asarray(bnd.cell_data["_view"])
    conn = bnd.cells_dict[pv.CellType.QUADRATIC_TRIANGLE]
    on_end = np.all(np.isclose(bnd.points[conn[:, :3], 0], 0.0), axis=1)   # exact, as above
    assert on_end.sum() == len(data["region_faces"]) > 0
    assert np.all(v[on_end] == 3) and np.all(v[~on_end] == 0)
    # the boundary of the bar: 2 × (10·2 + 10·2 + 2·2) squares, 2 triangles each
    assert bnd.n_cells == 2 * 2 * (20 + 20 + 4)


def test_default_field_order(tmp_path):
    p1 = tmp_path / "d.vtu"
    _write_result(p1, fields=("displacement", "safety_factor"), faces=True)
    assert view.default_field(view.load(p1)) == "safety_factor"
    p2 = tmp_path / "g.vtu"
    _write_result(p2, fields=(), faces=True)
    assert view.default_field(view.load(p2)) == "region"


def test_units_table():
    assert view.field_unit("von_mises") == "MPa"
    assert view.field_unit("displacement") == "mm"
    assert view.field_unit("life_blocks") == "blocks"
    assert view.field_unit("mode_3_884.34Hz") == "-"
    assert view.field_unit("something_else") == "-"


def test_documented_fields_match_the_table():
    doc = (Path(__file__).resolve().parents[1] / "docs" / "FIELDS.md").read_text()
    rows = {}
    for line in doc.splitlines():
        if line.startswith("| `"):
            cells = [c.strip() for c in line.strip("|").split("|")]
            rows[cells[0].strip("`")] = cells[1]
    for name, (unit, _rule, _what) in view.FIELDS.items():
        assert rows.get(name) == unit, (name, unit, rows.get(name))


# ---------------------------------------------------------------------------------------------
# input errors: one line, exit 2, no screenshot


def _bad_vtu(kind: str, d: Path, good: Path) -> Path:
    if kind == "missing":
        return d / "nothing_here.vtu"
    if kind == "text":
        p = d / "notes.vtu"
        p.write_text("x, y, von_mises\n1, 2, 3\n")
        return p
    if kind == "truncated":
        p = d / "cut.vtu"
        p.write_bytes(good.read_bytes()[:1500])
        return p
    if kind == "polydata":
        p = d / "surf.vtp"
        pv.Sphere().save(p)
        return p
    raise AssertionError(kind)


@pytest.mark.parametrize("kind", ["missing", "text", "truncated", "polydata"])
def test_bad_file_is_one_line_exit_2(result, tmp_path, headless, capsys, kind):
    path = _bad_vtu(kind, tmp_path, result[0])
    shot = tmp_path / "out" / "never.png"
    assert main(["view", str(path), "--screenshot", str(shot)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert str(path) in err and "file" in err and ".vtu" in err
    assert not shot.exists() and not shot.parent.exists()


@pytest.mark.parametrize(("args", "words"), [
    (["--field", "sigma"], ["--field", "'sigma'", "von_mises", "displacement", "stress"]),
    (["--field", "von_mises", "--component", "y"], ["--component", "scalar"]),
    (["--field", "stress", "--component", "magnitude"], ["--component", "xx | yy"]),
    (["--field", "displacement", "--component", "7"], ["--component", "magnitude | x"]),
    (["--window-size", "big"], ["--window-size", "WIDTHxHEIGHT"]),
    (["--warp", "-3"], ["--warp", ">= 0"]),
])
def test_bad_option_is_one_line_exit_2(result, tmp_path, headless, capsys, args, words):
    shot = tmp_path / "never.png"
    assert main(["view", str(result[0]), "--screenshot", str(shot), *args]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    for w in words:
        assert w in err, (w, err)
    assert not shot.exists() and list(tmp_path.iterdir()) == []


def test_help_does_not_import_pyvista():
    code = ("import sys\n"
            "from shaftfe.cli import main\n"
            "for argv in (['--help'], ['view', '--help']):\n"
            "    try:\n"
            "        main(argv)\n"
            "    except SystemExit:\n"
            "        pass\n"
            "bad = [m for m in ('pyvista', 'vtk', 'vtkmodules', 'numpy') if m in sys.modules]\n"
            "print('IMPORTED', bad)\n")
    cp = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                        env=_clean_env(), timeout=60)
    assert cp.returncode == 0, cp.stderr
    assert "RESULT.vtu" in cp.stdout and "--screenshot" in cp.stdout
    assert cp.stdout.strip().splitlines()[-1] == "IMPORTED []"


def test_group_names_from_field_data_or_sidecar(tmp_path):
    path = tmp_path / "result.vtu"
    _write_result(path, fields=("von_mises",), faces=True)
    assert view.group_names(view.load(path), path) == {}
    (tmp_path / "summary.json").write_text(
        '{"vtu": {"file": "result.vtu", "regions": ["bearing:a", "fillet:b", "end:c"]}}')
    assert view.group_names(view.load(path), path) == {1: "bearing:a", 2: "fillet:b",
                                                       3: "end:c"}
    other = tmp_path / "other.vtu"
    other.write_bytes(path.read_bytes())
    assert view.group_names(view.load(other), other) == {}     # the sidecar names result.vtu
    g = pv.read(path)
    g.field_data["region_names"] = np.array(["x", "y", "seat"])
    g.save(other)
    assert view.group_names(view.load(other), other)[3] == "seat"
