"""`shaftfe static` runs the zoned solve by default (issue #32): its files, its summary and the
--model choices beside it."""

from __future__ import annotations

import json
import math

import pytest


@pytest.fixture(scope="module")
def zoned_run(tmp_path_factory, cache):
    import os

    from shaftfe.cli import main
    out = tmp_path_factory.mktemp("zoned") / "o"
    old = os.environ.get("SHAFTFE_CACHE_DIR")
    os.environ["SHAFTFE_CACHE_DIR"] = str(cache)
    try:
        rc = main(["static", "--variant", "x2_57", "--level", "coarse", "--json",
                   "--out", str(out)])
    finally:
        if old is None:
            os.environ.pop("SHAFTFE_CACHE_DIR")
        else:
            os.environ["SHAFTFE_CACHE_DIR"] = old
    return rc, out


def test_the_default_static_model_is_zoned_and_writes_every_file(zoned_run):
    import meshio
    rc, out = zoned_run
    assert rc == 0
    assert {p.name for p in out.iterdir()} == {"result.vtu", "zone_1.vtu", "zone_2.vtu",
                                               "summary.json"}
    s = json.loads((out / "summary.json").read_text())
    assert s["model"] == "zoned" and s["inputs"]["model"] == "zoned"
    assert [z["features"] for z in s["zones"]] == [["keyway:gear_seat:0"],
                                                   ["keyway:cw2_seat:0", "hex_socket"]]
    assert [z["file"] for z in s["vtu"]["zones"]] == ["zone_1.vtu", "zone_2.vtu"]
    models = {p["region"]: p["model"] for p in s["cases"][0]["peaks"]}
    assert models["keyway:gear_seat:0"] == "zone:keyway:gear_seat:0"
    assert models["fillet:collar"] == "axisymmetric"      # the span fillets: the global model
    # their bars: the global model's level (axisymmetric default, whatever the zones' level);
    # the zones' peaks: x2_57's keyways are sharp, so none (their reason is in truth_bar_notes)
    from shaftfe.static.measured_errors import shoulder_bars
    assert s["truth_error_bar_pct"] == {f: list(shoulder_bars().bars["axisymmetric"]["default"])
                                        for f in ("fillet:collar", "fillet:bearing_seat_gear")}
    assert all("sharp-edged" in s["truth_bar_notes"][k]
               for k in ("keyway:gear_seat:0", "keyway:cw2_seat:0"))
    z = meshio.read(out / "zone_1.vtu")
    assert z.point_data["stress"].shape == (z.points.shape[0], 6)
    g = meshio.read(out / "result.vtu")
    assert set(g.point_data) == {"displacement_mm", "von_mises_MPa"}


def test_a_run_into_the_folder_of_a_zoned_one_leaves_no_zone_files(zoned_run, tmp_path,
                                                                    cache, monkeypatch):
    """An axisymmetric run into a copy of the zoned run's folder: the earlier run's zone files
    go (they would sit beside a summary without zones); its own files replace the others."""
    import shutil

    from shaftfe.cli import main
    out = tmp_path / "o"
    shutil.copytree(zoned_run[1], out)
    monkeypatch.setenv("SHAFTFE_CACHE_DIR", str(cache))
    assert main(["static", "--variant", "x2_57", "--model", "axisymmetric", "--level",
                 "coarse", "--json", "--out", str(out)]) == 0
    assert not list(out.glob("zone_*.vtu"))
    assert json.loads((out / "summary.json").read_text())["model"] == "axisymmetric"


def test_the_zoned_fatigue_reference_is_the_global_surface_plus_the_zones(cache):
    """``zoned.reference``: the regions the zoned peaks take from the global model hold the
    global model's surface points and stresses exactly (the same field: the axisymmetric
    reference of the same options, compared point by point, exact arithmetic); the zones'
    regions hold the submodels' surface nodes, whose largest nodal von Mises lies within 5 %
    below the zoned static peak of each keyway (the peak is fitted between the nodes; the hex
    socket's fit reaches past its corner edges, 21.2 against 12.8 MPa nodal, and is not
    compared)."""
    import numpy as np

    from shaftfe.axisymmetric.model import AxiOptions
    from shaftfe.axisymmetric.reference import static_reference
    from shaftfe.axisymmetric.solve import solve_axisymmetric
    from shaftfe.model.loader import load_variant
    from shaftfe.static.model import StaticOptions
    from shaftfe.zoned.reference import zoned_reference
    from shaftfe.zoned.solve import solve_zoned
    v = load_variant("x2_57")
    res = solve_zoned(v, 10_000.0, StaticOptions(level="coarse", spin_softening=False),
                      cache_dir=cache)
    ref = zoned_reference(res)
    axi = static_reference(solve_axisymmetric(v, 10_000.0, AxiOptions(spin_softening=False),
                                              cache_dir=cache))
    for region in ("fillet:collar", "fillet:bearing_seat_gear"):
        a = np.asarray(ref.regions[region])
        b = np.asarray(axi.regions[region])
        order_a = np.lexsort(ref.xyz[:, a])
        order_b = np.lexsort(axi.xyz[:, b])
        assert np.array_equal(ref.xyz[:, a][:, order_a], axi.xyz[:, b][:, order_b])
        assert np.array_equal(ref.stress_ref[:, a][:, order_a], axi.stress_ref[:, b][:, order_b])
    peaks = {p.region: p for p in res.cases[0].peaks}
    for region in ("keyway:gear_seat:0", "keyway:cw2_seat:0"):
        ids = np.asarray(ref.regions[region])
        nodal = float(ref.von_mises_ref[np.setdiff1d(ids, ref.excluded)].max())
        assert 0.95 * peaks[region].von_mises_MPa <= nodal <= peaks[region].von_mises_MPa * 1.001


def test_fatigue_seed_method_runs_on_the_zoned_field(tmp_path, cache, monkeypatch):
    """`shaftfe fatigue --method seed --model zoned`: the hot spot is a span fillet of the
    global model."""
    from shaftfe.cli import main
    from shaftfe.util.paths import GEOMETRY_DIR
    monkeypatch.setenv("SHAFTFE_CACHE_DIR", str(cache))
    rpm = str(GEOMETRY_DIR.parent / "loadspectra" / "rpm.dat")
    out = tmp_path / "f"
    assert main(["fatigue", rpm, "--method", "seed", "--model", "zoned", "--level", "coarse",
                 "--no-spin-softening", "--json", "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["static"]["options"]["model"] == "zoned"
    assert s["hot_spot"]["region"].startswith("fillet:")


def test_fkm_on_the_zoned_field_takes_each_points_own_model(tmp_path, cache, monkeypatch):
    """`shaftfe fatigue --method fkm --model zoned`: every assessed region has a hot spot and a
    finite gradient; a region of the global model is assessed at the same node, with the same
    gradient (exact arithmetic: the same harmonic field and the same profile points) as
    `--model axisymmetric` gives; the keyways' come from their 3D submodels."""
    from shaftfe.cli import main
    from shaftfe.util.paths import GEOMETRY_DIR
    monkeypatch.setenv("SHAFTFE_CACHE_DIR", str(cache))
    rpm = str(GEOMETRY_DIR.parent / "loadspectra" / "rpm.dat")
    runs = {}
    # the zoned global model is the axisymmetric one at its default level, whatever the zones'
    for model, level in (("zoned", "coarse"), ("axisymmetric", "default")):
        out = tmp_path / model
        assert main(["fatigue", rpm, "--method", "fkm", "--model", model, "--level", level,
                     "--no-spin-softening", "--json", "--out", str(out)]) == 0
        s = json.loads((out / "summary.json").read_text())
        runs[model] = {r["region"]: r for r in s["regions"]}
    z, a = runs["zoned"], runs["axisymmetric"]
    assert {"keyway:gear_seat:0", "keyway:cw2_seat:0"} <= set(z)
    for r in z.values():            # every region's profile was fitted (no G = 0 fallback)
        assert r["fit_rms"] is not None and math.isfinite(r["fit_rms"])
    for name in ("keyway:gear_seat:0", "keyway:cw2_seat:0"):    # from the zones' 3D fields
        assert z[name]["surface"]["G_per_mm"] > 0
    for name in ("fillet:bearing_seat_gear", "fillet:collar"):
        assert z[name]["surface"]["sigma_ref_MPa"] == a[name]["surface"]["sigma_ref_MPa"]
        assert z[name]["surface"]["G_per_mm"] == pytest.approx(a[name]["surface"]["G_per_mm"],
                                                               rel=1e-12)
        assert z[name]["surface"]["G_per_mm"] > 1.0       # a fillet's steep fall inward


def test_a_cut_check_that_never_passes_is_warned(cache, monkeypatch):
    """A zone whose cut check still fails when it can grow no further is not silently taken:
    a visible warning names the zone (forced here by a bound no cut meets, and no growth)."""
    import shaftfe.zoned.solve as zs
    from shaftfe.model.examples import keyed_bar
    from shaftfe.static.model import StaticOptions
    from shaftfe.util.notices import collected, collecting
    monkeypatch.setattr(zs, "CUT_TOL", 1e-9)
    monkeypatch.setattr(zs, "MAX_GROW", 0)
    with collecting(echo=False):
        zs.solve_zoned(keyed_bar("torsion"), 1000.0,
                       StaticOptions(level="coarse", rigid_supports=True, spin_softening=False),
                       cache_dir=cache)
        warned = [w for w in collected() if w["code"] == "cut-check"]
    assert warned and "zone:keyway:bar:0" in warned[0]["where"]


def test_the_report_on_the_zoned_model(tmp_path, cache, monkeypatch):
    """`shaftfe report --model zoned`: the static section, fatigue and FKM on the zoned field;
    one quantity, one value: the report's static peaks are those `shaftfe static` (zoned, the
    same options) prints, and its VTU carries the static and fatigue fields on the zoned
    surface's points."""
    import meshio

    from shaftfe.cli import main
    from shaftfe.util.paths import GEOMETRY_DIR
    monkeypatch.setenv("SHAFTFE_CACHE_DIR", str(cache))
    for f in cache.glob("surface-*"):               # the report's own entry is looked for below
        f.unlink()
    out = tmp_path / "rep"
    assert main(["report", "--variant", "x2_57", "--level", "coarse", "--model", "zoned",
                 "--no-pictures", "--no-spin-softening", "--json", "--out", str(out)]) == 0
    # compute once: `shaftfe fatigue` on the same model reads the report's surface reference
    assert len(list(cache.glob("surface-*.npz"))) == 1
    rpm = str(GEOMETRY_DIR.parent / "loadspectra" / "rpm.dat")
    assert main(["fatigue", rpm, "--level", "coarse", "--no-spin-softening", "--method",
                 "seed", "--json", "--out", str(tmp_path / "fat")]) == 0
    assert json.loads((tmp_path / "fat" / "summary.json").read_text())["static"]["from_cache"]
    s = json.loads((out / "summary.json").read_text())
    st = s["static"]
    assert st["model"] == "zoned" and [z["name"] for z in st["zones"]]
    assert "fkm" in s["strength"] and s["strength"]["fkm"]["regions"]
    assert main(["static", "--variant", "x2_57", "--level", "coarse", "--no-spin-softening",
                 "--json", "--out", str(tmp_path / "st")]) == 0
    z = json.loads((tmp_path / "st" / "summary.json").read_text())
    zc = {c["rpm"]: c for c in z["cases"]}
    both = [c for c in st["cases"] if c["rpm"] in zc]
    assert both
    for c in both:
        want = {p["region"]: p["von_mises_MPa"] for p in zc[c["rpm"]]["peaks"]}
        assert {p["region"]: p["von_mises_MPa"] for p in c["peaks"]} == want
    m = meshio.read(out / "x2_57.vtu")
    for name in ("displacement", "von_mises", "stress", "safety_factor", "life_blocks"):
        assert name in m.point_data, name
    html = (out / "index.html").read_text(encoding="utf-8")
    assert "Zoned solve" in html


@pytest.mark.parametrize("model", ["axisymmetric", "zoned"])
def test_a_surface_reference_at_a_design_speed_has_its_linear_stress_at_that_speed(
        model, cache, monkeypatch):
    """The report solves at the design speeds (6000 rpm here) with spin softening and the
    unsoftened field once more: the two must be at one speed, or fatigue's softening
    coefficient β = S_soft/S_lin − 1 reads (6000/10 000)² − 1 = −0.64 (the unsoftened solve
    keeps its own reference speed). Bound: the softening at 6000 rpm is (0.6)² of x2_57's
    ≈ 1.5 % at 10 000 rpm (fatigue.field.softening_beta); 5 % leaves room for the parts'
    tilt terms, far from −0.64."""
    import numpy as np

    from shaftfe.fatigue.field import softening_beta
    from shaftfe.model.loader import load_variant
    from shaftfe.report.assemble import _surface_static
    from shaftfe.report.options import ReportOptions
    from shaftfe.static.cache import kept_nodes
    from shaftfe.util.progress import Progress
    monkeypatch.setenv("SHAFTFE_CACHE_DIR", str(cache))
    o = ReportOptions(variant="x2_57", level="coarse", model=model, design_rpm=(6000.0,))
    _, ref = _surface_static(o, load_variant("x2_57"), Progress((), enabled=False))
    assert ref.ref_rpm == 6000.0
    vm = np.asarray(ref.von_mises_ref)
    lin = np.sqrt(0.5 * ((ref.stress_linear[0] - ref.stress_linear[1]) ** 2
                         + (ref.stress_linear[1] - ref.stress_linear[2]) ** 2
                         + (ref.stress_linear[2] - ref.stress_linear[0]) ** 2)
                  + 3 * (ref.stress_linear[3:] ** 2).sum(axis=0))
    keep = kept_nodes(ref) & (vm > 0.1 * vm.max())
    beta = softening_beta(vm[keep], lin[keep])
    assert np.abs(beta).max() < 0.05


def test_the_surface_reference_is_read_back_from_its_cache(tmp_path, cache, monkeypatch):
    """`shaftfe fatigue` on the zoned model keeps its surface reference and FKM's field below
    it (``fatigue.surface_cache``): a second run reads them and assesses to the same bits
    (exact: the arrays round-trip through .npz unchanged), a changed option solves again."""
    from shaftfe.cli import main
    from shaftfe.util.paths import GEOMETRY_DIR
    monkeypatch.setenv("SHAFTFE_CACHE_DIR", str(tmp_path / "c"))
    import shutil
    shutil.copytree(cache, tmp_path / "c",                 # the meshes, not the references
                    ignore=shutil.ignore_patterns("surface-*"))
    rpm = str(GEOMETRY_DIR.parent / "loadspectra" / "rpm.dat")
    got = []
    for k in range(2):
        out = tmp_path / f"f{k}"
        assert main(["fatigue", rpm, "--level", "coarse", "--no-spin-softening", "--json",
                     "--out", str(out)]) == 0
        got.append(json.loads((out / "summary.json").read_text()))
    assert [g["static"]["from_cache"] for g in got] == [False, True]
    assert got[0]["static"]["model"] == "zoned"
    assert got[0]["regions"] == got[1]["regions"]
    assert len(list((tmp_path / "c").glob("surface-*.npz"))) == 1      # one file an entry
    assert main(["fatigue", rpm, "--level", "coarse", "--json", "--out",
                 str(tmp_path / "f2")]) == 0                   # spin softening: a new entry
    assert len(list((tmp_path / "c").glob("surface-*.npz"))) == 2


def test_zones_covering_the_whole_shaft_are_refused_in_one_clear_error(tmp_path):
    """A short shaft whose cut features' zones grow over its whole length leaves no global
    model to drive them (no cut): a SolverError naming the features and --model solid, not a
    crash (it was a ValueError from numpy)."""
    import dataclasses

    from shaftfe.errors import SolverError
    from shaftfe.model.examples import K_SEED, four_step_shaft
    from shaftfe.model.variant import Bearing
    from shaftfe.static.model import StaticOptions
    from shaftfe.zoned.solve import solve_zoned
    v = four_step_shaft(washer=True, thread_end=True)
    v = dataclasses.replace(v, bearings=(dataclasses.replace(v.bearings[0], axial=True),
                                         Bearing("b2", "x", 10.0, 6.0, 14_400.0, 10_000.0,
                                                 K_SEED)))
    with pytest.raises(SolverError, match=r"cover the whole shaft.*--model solid"):
        solve_zoned(v, 10_000.0, StaticOptions(level="coarse"), cache_dir=tmp_path)


def test_the_zoned_solve_reads_its_bending_planes_from_the_cache(tmp_path, monkeypatch):
    """``beam.planes.mesh_hot_axes(use_cache=True)`` (the zoned solve's): the first call
    solves the beam and writes the axes, a second call reads them (no beam solve: the solver
    is made to fail) bit for bit (JSON keeps every bit of a float: exact equality); another
    variant (a --set of a fillet) is another key; without the cache nothing is written."""
    from shaftfe.beam import planes
    from shaftfe.model.loader import load_variant
    v = load_variant("x2_57")
    plain = planes.mesh_hot_axes(v)
    assert not list(tmp_path.glob("axes-*.json"))
    first = planes.mesh_hot_axes(v, cache_dir=tmp_path, use_cache=True)
    assert first == plain and len(list(tmp_path.glob("axes-*.json"))) == 1

    def no_solve(variant):
        raise AssertionError("the beam was solved again")
    monkeypatch.setattr(planes, "_mesh_hot_axes", no_solve)
    assert planes.mesh_hot_axes(v, cache_dir=tmp_path, use_cache=True) == plain
    other = load_variant("x2_57", ["segments.collar.fillet_mm=0.5"])
    with pytest.raises(AssertionError, match="solved again"):
        planes.mesh_hot_axes(other, cache_dir=tmp_path, use_cache=True)


def test_the_cached_bending_planes_keep_the_beam_solves_warnings(tmp_path, monkeypatch):
    """The beam solve behind the bending planes warns (its deflection beyond the linear range,
    the clearance, the torques: in the zoned default the only deflection check): a warm run
    reads the planes from the cache and raises the same warnings again, so summary.json holds
    them whether the cache was cold or warm."""
    from shaftfe.beam import planes
    from shaftfe.model.loader import load_variant
    from shaftfe.util.notices import collecting, raised, warn
    v = load_variant("x2_57")
    plain = planes.mesh_hot_axes(v)

    def warning(variant):
        warn("deflection-large", "beam, 10000 rpm", "max deflection beyond the linear range")
        return plain

    def no_solve(variant):
        raise AssertionError("the beam was solved again")
    with collecting(echo=False):
        monkeypatch.setattr(planes, "_mesh_hot_axes", warning)
        with raised() as cold:
            assert planes.mesh_hot_axes(v, cache_dir=tmp_path, use_cache=True) == plain
        monkeypatch.setattr(planes, "_mesh_hot_axes", no_solve)
    with collecting(echo=False):
        with raised() as warm:
            assert planes.mesh_hot_axes(v, cache_dir=tmp_path, use_cache=True) == plain
    assert cold == warm == [{"code": "deflection-large", "where": "beam, 10000 rpm",
                             "text": "max deflection beyond the linear range"}]


def test_a_notch_in_a_solved_zone_says_why_it_has_no_bar():
    """``zoned.solve.zone_filtered``: a notch whose faces reach into a solved zone loses its
    bar, and a note it had (no bar for its geometry) too, for the zone's reason; one outside
    keeps its bar or note; a notch the global model does not report keeps neither."""
    from shaftfe.zoned.solve import zone_filtered
    bars = {"fillet:a": (-0.3, 0.2), "fillet:b": (-0.3, 0.2), "fillet:z": (-0.3, 0.2)}
    notes = {"groove:c:0": "no measured bar for this groove", "groove:d:0": "no bar (load)"}
    kept, why = zone_filtered(bars, notes, {"fillet:a", "fillet:b", "groove:c:0", "groove:d:0"},
                              {"fillet:b": "zone:k", "groove:d:0": "zone:k"})
    assert kept == {"fillet:a": (-0.3, 0.2)}
    assert why["groove:c:0"] == "no measured bar for this groove"
    assert "3D zone zone:k" in why["fillet:b"] and "3D zone zone:k" in why["groove:d:0"]
    assert "fillet:z" not in kept and "fillet:z" not in why
