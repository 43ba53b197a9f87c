"""`shaftfe fatigue` end to end (issue 5) and the static-solution disk cache.

The x2_57 runs use a coarse static solution shared with tests/validation/test_fatigue_field.py
through a session-wide cache directory; the cache's own checks use a small cylinder.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from shaftfe.cli import main
from shaftfe.model.examples import STEEL
from shaftfe.model.variant import Attachment, Bearing, Segment, Variant

ROOT = Path(__file__).resolve().parents[1]
RPM_DAT = ROOT / "loadspectra" / "rpm.dat"


@pytest.fixture(scope="module")
def cache(tmp_path_factory):
    d = tmp_path_factory.getbasetemp() / "shaftfe-fatigue-cache"
    d.mkdir(exist_ok=True)
    return d


SEED = ("--method", "seed", "--model", "solid")   # the seed method on the 3D model (its cache)


def run(capsys, *argv):
    try:
        rc = main(["fatigue", *SEED, *map(str, argv)] if "--method" not in argv
                  else ["fatigue", *map(str, argv)])
    except SystemExit as exc:          # argparse usage errors
        rc = exc.code
    out = capsys.readouterr()
    return rc, out.out, out.err


@pytest.fixture(scope="module")
def seed_run(cache, tmp_path_factory):
    """The seed's settings (the defaults, and the seed's load case) on the coarse mesh, run
    twice: the second run must take the static solution from the cache."""
    out = tmp_path_factory.mktemp("fatigue-seed")
    import contextlib
    import io
    texts = []
    for _ in range(2):
        buf = io.StringIO()
        with contextlib.redirect_stdout(buf):
            rc = main(["fatigue", *SEED, str(RPM_DAT), "--level", "coarse",
                       "--cache-dir", str(cache),
                       "--seed-load-case", "--out", str(out)])
        assert rc == 0
        texts.append(buf.getvalue())
    return out, texts


def test_seed_run_outputs_and_cache(seed_run):
    """Reference: the interface of issue 5 and docs/FIELDS.md (point data life_blocks,
    damage_per_block, safety_factor, von_mises_ref; cell data region with names in the sidecar
    summary.json). life_km = life_hours × 70 and life_hours = blocks × 300 s / 3600 (seed
    §8.3: 25 000 blocks → 2083 h → 145 810 km) are checked on the printed summary."""
    import meshio
    out, (first, second) = seed_run
    assert "static: solved in" in first or "static: from cache" in first
    assert "static: from cache" in second
    s = json.loads((out / "summary.json").read_text())
    assert s["static"]["notes"] == []                      # the mesh key was predicted: cached
    from shaftfe.fatigue.methods import OUTPUT_FILES
    assert sorted(p.name for p in out.iterdir()) == sorted(OUTPUT_FILES["seed"])
    assert s["warnings"] == []
    res = s["result"]
    # exact arithmetic (round-off only): unit conversions of the same number
    assert res["life_hours"] == pytest.approx(res["life_blocks"] * 300 / 3600, rel=1e-12)
    assert res["life_km"] == pytest.approx(res["life_hours"] * 70, rel=1e-12)
    assert s["inputs"]["seed_load_case"] is True and s["inputs"]["mean_stress"] == "soderberg"
    assert s["history"]["static_ref_rpm"] == 10_000.0 and s["history"]["rpm_ref_of_file"] == 7000
    # rpm.dat gives (7500/7000)² to 12 significant digits (1.14795918367): ≤ 4.4e-12 relative
    # (measured 3.0e-12); 1e-11 = 2× that (was 1e-9)
    assert s["history"]["load_factor_max"] == pytest.approx((7500 / 10_000) ** 2, rel=1e-11)
    for line in ("life:", "safety factor at 1e+07 blocks (= 833 333 h = 58 333 333 km):",
                 "hot spot:", "unfiltered minimum:",
                 "cycles per block:"):
        assert line in second
    m = meshio.read(out / "fatigue.vtu")
    n = s["static"]["n_nodes"]
    for f in ("life_blocks", "damage_per_block", "safety_factor", "von_mises_ref"):
        assert m.point_data[f].shape == (n,)
    life = m.point_data["life_blocks"]
    d = m.point_data["damage_per_block"]
    # exact arithmetic (life = 1/damage, float64 in the .vtu: measured 1.1e-16); was
    # allclose's default rtol 1e-5
    assert np.all(np.isinf(life[d == 0])) and np.allclose(life[d > 0] * d[d > 0], 1.0,
                                                            rtol=1e-12, atol=0.0)
    i = s["hot_spot"]["node"]
    # exact arithmetic: the same float64 in the .vtu and the JSON (measured equal)
    assert m.point_data["safety_factor"][i] == pytest.approx(res["safety_factor"], rel=1e-12)
    assert s["vtu"]["regions"] and max(np.concatenate(
        [c for c in m.cell_data["region"]])) == len(s["vtu"]["regions"])
    for p in s["plots"].values():
        assert (out / p).stat().st_size > 1000


def test_block_twice_halves_blocks_keeps_hours(seed_run, cache, tmp_path, capsys):
    """Reference: Miner's rule on a periodic history — the rainflow cycles of the block played
    twice are exactly twice those of one block (repeated closure), so the damage per (twice as
    long) block doubles: the life in blocks halves and the life in hours is unchanged."""
    out1 = seed_run[0]
    one = json.loads((out1 / "summary.json").read_text())
    lines = RPM_DAT.read_text().splitlines()
    data = [ln for ln in lines if ln.strip() and not ln.startswith("#")]
    head = [ln for ln in lines if ln.startswith("#")]
    f = tmp_path / "twice.dat"
    f.write_text("\n".join(head + data + data) + "\n")
    rc, text, _ = run(capsys, f, "--level", "coarse", "--cache-dir", cache, "--seed-load-case",
                      "--out", tmp_path / "o2", "--json")
    assert rc == 0
    two = json.loads(text)
    assert two["static"]["from_cache"] is True
    assert two["history"]["duration_s"] == 600.0
    assert two["cycles"]["per_block"] == 2 * one["cycles"]["per_block"]
    # exact arithmetic (round-off only): the same cycles twice, Miner sums in another order
    assert two["result"]["life_blocks"] == pytest.approx(one["result"]["life_blocks"] / 2,
                                                         rel=1e-12)
    # exact arithmetic, as above: twice the blocks, each twice as long
    assert two["result"]["life_hours"] == pytest.approx(one["result"]["life_hours"], rel=1e-12)
    assert two["hot_spot"]["node"] == one["hot_spot"]["node"]


def test_constant_rpm_gives_infinite_life(seed_run, cache, tmp_path, capsys):
    """Reference: a constant speed has no load reversal: rainflow counts no cycle, Miner's
    damage is 0 and the life infinite; the safety factor is the cap (15), not a division by
    zero. (The seed's load case: seed_run's static solution, from the cache.)"""
    f = tmp_path / "const.dat"
    f.write_text("# format = rpm\n# sample_rate_hz = 1\n" + "6000\n" * 300)
    out = tmp_path / "o"
    rc, text, err = run(capsys, f, "--level", "coarse", "--seed-load-case", "--cache-dir", cache,
                        "--out", out)
    assert rc == 0, err
    assert "life: infinite" in text and "Traceback" not in err
    assert "cycles per block: 0" in text
    s = json.loads((out / "summary.json").read_text())
    assert s["result"]["life_blocks"] is None and s["result"]["infinite_life"] is True
    assert s["result"]["safety_factor"] == 15.0 and s["result"]["safety_status"] == "capped"


@pytest.mark.parametrize("extra, where", [
    (["--mean-stress", "morrow"], "--mean-stress"),
    (["--design-life", "0"], "--design-life"),
    (["--design-life=-1e7"], "--design-life"),
    (["--design-life", "abc"], "--design-life"),
    (["--design-life", "nan"], "--design-life"),
    (["--kf", "1.5"], "--kf"),
    (["--equivalent", "tresca"], "--equivalent"),
    (["--exclude-mm", "-1"], "--exclude-mm"),
    (["--material", "unobtainium"], "unobtainium"),
    (["--variant", "nope_99"], "nope_99"),
])
def test_bad_options_exit_2_one_line(tmp_path, capsys, extra, where):
    """Reference: the CLI contract — bad input is one line on stderr, exit code 2, no
    traceback and no output written."""
    out = tmp_path / "o"
    rc, text, err = run(capsys, RPM_DAT, "--level", "coarse", "--out", out, *extra)
    assert rc == 2 and text == ""
    assert err.count("\n") == 1 and err.startswith("shaftfe") and "error:" in err
    assert where in err and "Traceback" not in err
    assert not out.exists()


def test_missing_spectrum_exit_2(tmp_path, capsys):
    """Reference: the CLI contract (as above) for a spectrum file that does not exist."""
    out = tmp_path / "o"
    rc, _text, err = run(capsys, tmp_path / "nope.dat", "--out", out)
    assert rc == 2 and err.count("\n") == 1 and "does not exist" in err
    assert not out.exists()


# --------------------------------------------------------------------------- static cache

K_ISO = ((35_030.0, 0.0), (0.0, 35_030.0))


def cylinder() -> Variant:
    """Ø20 × 120 mm cylinder, bearings on [5, 15] and [105, 115], one part on [55, 65]."""
    segs = (Segment("s", 0.0, 120.0, 20.0, 0.0),)
    brg = (Bearing("L", "x", 10.0, 10.0, 14_400.0, 10_000.0, K_ISO, axial=True),
           Bearing("R", "x", 110.0, 10.0, 14_400.0, 10_000.0, K_ISO))
    att = (Attachment("w", 55.0, 65.0, 0.24, 20.0, 60.0, angle_deg=0.0),)
    return Variant("cyl", "test cylinder", segs, brg, att, STEEL, 0.0)


def test_static_cache_roundtrip_corruption_and_key(tmp_path):
    """Reference: the solve itself (``shaftfe.static.solve.solve_static``): a cache hit returns the
    same arrays bit for bit; its singular-point exclusion and regions equal the static
    analysis's (``diagnostics['n_excluded_nodes']``, the node and excluded counts of every
    region peak); the static case at half the speed is the cached field × 1/4; a corrupt or
    truncated file is recomputed; a changed option changes the key."""
    from shaftfe.static.cache import cache_path, from_result
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import load_or_solve, solve_static
    v = cylinder()
    o = StaticOptions(level="coarse", spin_softening=False)      # ∝ rpm² checked below
    a = load_or_solve(v, o, tmp_path)
    assert not a.from_cache and a.notes == ()
    b = load_or_solve(v, o, tmp_path)
    assert b.from_cache and b.key == a.key
    for k in ("stress_ref", "von_mises_ref", "xyz", "excluded", "cells", "face_cells"):
        assert np.array_equal(getattr(a, k), getattr(b, k)), k
    assert {k: v.tolist() for k, v in a.regions.items()} == \
        {k: v.tolist() for k, v in b.regions.items()}

    res = solve_static(v, [10_000.0, 5000.0], o, cache_dir=tmp_path, beam=False)
    r = from_result(res)
    # loads ∝ rpm²: the static API's case at 5000 rpm is the cached field at 10 000 × 1/4
    # (exact arithmetic, round-off only)
    assert res.case(5000.0).peak_von_mises_unfiltered_MPa == pytest.approx(
        0.25 * a.von_mises_ref.max(), rel=1e-12)
    assert r.excluded.size == res.diagnostics["n_excluded_nodes"]
    for p in res.cases[0].peaks:
        nodes = r.regions[p.region]
        assert nodes.size == p.n_nodes
        assert np.setdiff1d(nodes, r.excluded).size == p.n_nodes - p.n_excluded
    np.testing.assert_array_equal(r.stress_ref, a.stress_ref)

    path = cache_path(a.key, tmp_path)
    good = path.read_bytes()
    for bad in (b"not a zip file", good[: len(good) // 2]):
        path.write_bytes(bad)
        c = load_or_solve(v, o, tmp_path)
        assert not c.from_cache
        np.testing.assert_array_equal(c.stress_ref, a.stress_ref)
        assert load_or_solve(v, o, tmp_path).from_cache        # rewritten, readable again
    o2 = StaticOptions(level="coarse", load_distribution="cosine")
    d = load_or_solve(v, o2, tmp_path)
    assert d.key != a.key and not d.from_cache
    # must differ: cosine vs uniform load moves the peak by −0.68 % on this mesh, ≫ round-off;
    # 1e-6 separates a real change from a cache hit with 4 decades either side
    assert not math.isclose(float(d.von_mises_ref.max()), float(a.von_mises_ref.max()),
                            rel_tol=1e-6)


@pytest.mark.parametrize("method", ["fkm", "din743"])
def test_standard_methods_write_their_summary(cache, tmp_path, capsys, method):
    """fkm / din743 on the coarse mesh: summary.json (with "warnings") with the governing
    result, every region or notch, the bearings' duty cycle and the seed's key check (0.126 mm
    by its formula); every file `fatigue --help` names for the method, and nothing else.
    FKM's fatigue.vtu holds the governing utilisation at the governing node (one value)."""
    out = tmp_path / method
    level = ("--level", "coarse") if method == "fkm" else ()     # DIN 743 has no mesh
    rc, text, err = run(capsys, RPM_DAT, "--method", method, *level,
                        "--cache-dir", cache, "--out", out)
    assert rc == 0, err

    def no_inf_nan(c):                   # summary files are strict JSON (allow_nan=False)
        raise AssertionError(f"{c} in summary.json")
    s = json.loads((out / "summary.json").read_text(), parse_constant=no_inf_nan)
    assert s["method"] == method and s["warnings"] == []
    from shaftfe.fatigue.methods import OUTPUT_FILES
    assert sorted(p.name for p in out.iterdir()) == sorted(OUTPUT_FILES[method])
    assert all(f"{out / f}" in text for f in OUTPUT_FILES[method])
    if method == "fkm":
        assert s["governing"]["region"].startswith("fillet:")
        assert {r["region"] for r in s["regions"]} >= {"fillet:collar", "keyway:gear_seat:0"}
        assert 0 < s["governing"]["utilisation"]["modified"] < 10
        import meshio
        import numpy as np
        m = meshio.read(out / "fatigue.vtu")
        u = m.point_data["fkm_utilisation"]
        node = next(r["node"] for r in s["regions"] if r["region"] == s["governing"]["region"])
        # the same float64 written and read back: exact
        assert u[node] == s["governing"]["utilisation"]["modified"] == np.nanmax(u)
        assert np.isfinite(u).sum() == s["vtu"]["assessed_nodes"]
    else:
        assert s["governing"]["S_D"] > 1 and {n["kind"] for n in s["notches"]} == \
            {"shoulder", "keyway", "press_fit"}
    k = s["elements"]["keys"][0]
    assert round(k["length_needed_seed_mm"], 3) == 0.126
    assert "key gear_seat" in text


def test_din743_plot_gives_the_safety_along_the_shaft(tmp_path, capsys):
    """``--method din743 --plot``: din743_along.png beside the method's files, and the safety
    of the unnotched section at every cross-section in summary.json, the shaft's whole length
    every 0.25 mm. S_F in the collar by hand (DIN 743-1/-2, an unnotched section: α = 1 so
    γ_F = 1; K2F = 1.2 in bending and torsion, 1.0 with a hard surface layer as the case
    hardened 14220 has): S_F = 1/√((σ_b,max/σ_bFK)² + (τ_max/τ_tFK)²),
    σ_bFK = K1(d) · K2F · R_p, τ_tFK = σ_bFK/√3, the nominal stresses from the beam's moment
    and torque at x × the cycle's highest load factor (exact arithmetic: 1e-9). A run without
    ``--plot`` into the same folder leaves no din743_along.png there (the earlier run's would
    sit beside a summary without "along"). ``--plot`` with another method is refused."""
    import numpy as np

    from shaftfe.beam.solve import beam_at_ref
    from shaftfe.fatigue import din743 as din
    from shaftfe.fatigue.strength import StrengthOptions, din743_card
    from shaftfe.model.loader import load_variant
    out = tmp_path / "d"
    rc, text, err = run(capsys, RPM_DAT, "--method", "din743", "--plot", "--out", out)
    assert rc == 0, err
    assert (out / "din743_along.png").stat().st_size > 0
    assert "along the shaft" in text
    s = json.loads((out / "summary.json").read_text())
    a = s["along"]
    x = np.array(a["x_mm"])
    assert x[0] == 0.0 and x[-1] == pytest.approx(114.0) and np.diff(x).max() <= 0.25 + 1e-9
    v = load_variant("x2_57")
    card = din743_card(v, StrengthOptions())
    beam = beam_at_ref(v)
    hi = (s["cycle_rpm"][1] / 10_000.0) ** 2
    for i in np.flatnonzero((x > 50) & (x < 60))[::8]:
        d = a["d_mm"][i]
        sb = 32 * abs(np.interp(x[i], beam.x_sec, beam.M)) / (math.pi * d ** 3) * hi
        tt = 16 * abs(np.interp(x[i], beam.x_sec, beam.T)) / (math.pi * d ** 3) * hi
        fk = din.k1(d, card.group, "yield") * (1.0 if card.case_hardened else 1.2) \
            * card.rp_n_MPa
        want = 1 / math.hypot(sb / fk, tt / (fk / math.sqrt(3)))
        assert a["S_F"][i] == pytest.approx(want, rel=1e-9)
    (out / "mine.png").write_bytes(b"x")                 # a user's file is not the run's
    rc, _, err = run(capsys, RPM_DAT, "--method", "din743", "--out", out)
    assert rc == 0, err
    assert not (out / "din743_along.png").exists() and (out / "mine.png").exists()
    assert "along" not in json.loads((out / "summary.json").read_text())
    rc, _, err = run(capsys, RPM_DAT, "--method", "seed", "--plot", "--out", tmp_path / "s")
    assert rc == 2 and "--plot" in err and "din743" in err


def test_help_names_every_file_of_each_method(capsys):
    """`fatigue --help` tells the truth per method: every file a method writes
    (``fatigue.methods.OUTPUT_FILES``, which the runs above check against the folder) is named
    in the method's clause of the description."""
    from shaftfe.fatigue.methods import OUTPUT_FILES
    with pytest.raises(SystemExit):
        main(["fatigue", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    clause = text.split("Writes into --out, per method:")[1]
    parts = {m: clause.split(f"{m}:")[1] for m in OUTPUT_FILES}
    for method, files in OUTPUT_FILES.items():
        own = parts[method].split(";")[0]
        for f in files:
            assert f in own, (method, f)


def test_overspeed_allowed_is_assessed_with_a_warning_and_the_design_life_in_hours(
        seed_run, cache, tmp_path, capsys):
    """A history reaching 19 999 rpm (above the VM 450's max_rpm 9500) is refused without
    --allow-overspeed (tests/test_bad_input.py); with it, it is assessed, the warning is printed
    on stderr and written into summary.json. The design life given in hours becomes blocks of
    the history: 1000 h of a 4 s block = 900 000 blocks (3.6e6 / 4: exact in binary). (The
    seed's load case: seed_run's static solution, from the cache.)"""
    spec = tmp_path / "over.dat"
    spec.write_text("# format = rpm\n# sample_rate_hz = 1\n3000\n19999\n3000\n8000\n")
    out = tmp_path / "o"
    rc, text, err = run(capsys, spec, "--level", "coarse", "--seed-load-case", "--cache-dir",
                        cache, "--allow-overspeed", "--design-life-h", "1000", "--out", out)
    assert rc == 0, err
    assert "shaftfe: warning:" in err and "19999" in err and "9500" in err
    s = json.loads((out / "summary.json").read_text())
    assert [w["code"] for w in s["warnings"]] == ["overspeed"]
    assert s["result"]["design_life_blocks"] == 900_000.0
    assert "safety factor at 900000 blocks (= 1 000 h = 70 000 km):" in text


# --- slice f2-fatigue-fixes (issue #30 review of `shaftfe fatigue`) ---------------------------

def test_fkm_on_a_constant_speed_says_no_load_cycles_at_the_loaded_hot_spots(cache, tmp_path,
                                                                              capsys):
    """Reference: a constant speed has no load reversal, and the repeated-block closure adds
    no start-stop cycle: rainflow counts nothing, FKM's damage is 0. The table printed 'nan'
    (K_AK) and '∞' (safeties) and moved the hot spots (every utilisation 0: the first
    candidate won); now it prints '—', says so once, and each region's hot spot is the node
    a start-stop history (0 → 3000 rpm) governs by (same node, same signed stress)."""
    f = tmp_path / "const.dat"
    f.write_text("# format = rpm\n# sample_rate_hz = 10\n" + "3000\n" * 100)
    rc, text, err = run(capsys, f, "--method", "fkm", "--level", "coarse", "--cache-dir", cache,
                        "--out", tmp_path / "c")
    assert rc == 0, err
    assert "nan" not in text and "governing: none: no load cycles in this history" in text
    assert "∞" not in text.split("governing:")[0]
    const = json.loads((tmp_path / "c" / "summary.json").read_text())
    assert const["no_load_cycles"] is True
    # the loaded comparison: start-stop cycles 0 → 3000 rpm, the cycle the tie rule stands in
    # for (rpm.dat's cycles run from idle, not from rest, and may rank two nodes of a region
    # with nearly equal stresses the other way)
    g = tmp_path / "start_stop.dat"
    g.write_text("# format = rpm\n# sample_rate_hz = 10\n" + "0\n3000\n" * 50)
    rc, _, err = run(capsys, g, "--method", "fkm", "--level", "coarse", "--cache-dir",
                     cache, "--out", tmp_path / "r")
    assert rc == 0, err
    loaded = json.loads((tmp_path / "r" / "summary.json").read_text())
    assert loaded["no_load_cycles"] is False
    # the choice among a region's candidates is discrete: the same node, exactly — except in
    # the gear seat's keyway, where with the parts at their centroids (issue #31) two nodes of
    # nearly equal stress swap: the tie rule (a start-stop cycle from the softened 10 000 rpm
    # reference) picks 4999, the 0 → 3000 rpm cycles 5037 (measured; open)
    near_tie = {"keyway:gear_seat:0"}
    assert {r["region"]: r["node"] for r in const["regions"] if r["region"] not in near_tie} \
        == {r["region"]: r["node"] for r in loaded["regions"] if r["region"] not in near_tie}


def test_fkm_plot_gives_the_utilisation_along_the_shaft(cache, tmp_path, capsys):
    """``--method fkm --plot`` on the coarse mesh: fkm_along.png beside FKM's files, and the
    degree of utilisation of every 1 mm slice of the surface in summary.json, over the shaft's
    whole length. What the slicing guarantees, checked against the static reference itself
    (FKM's factors are validated in tests/validation/test_fkm.py): a slice is listed where the
    surface has a node in it, and has no value (null, "excluded") exactly where every such
    node is in the singular-point exclusion; a slice reads at least every hot spot the
    regions' own assessment found in it, so the slice of the governing hot spot reads the
    governing utilisation or more."""
    import numpy as np

    from shaftfe.fatigue.run import FatigueJob, static_reference
    from shaftfe.model.loader import load_variant
    out = tmp_path / "f"
    rc, text, err = run(capsys, RPM_DAT, "--method", "fkm", "--level", "coarse", "--plot",
                        "--cache-dir", cache, "--out", out)
    assert rc == 0, err
    assert (out / "fkm_along.png").stat().st_size > 0 and "fkm_along.png" in text
    s = json.loads((out / "summary.json").read_text())
    a = s["along"]
    x, u = np.array(a["x_mm"]), np.array(a["utilisation"], dtype=float)
    ref = static_reference(load_variant("x2_57"), FatigueJob(spectrum=str(RPM_DAT),
                                                             level="coarse", cache_dir=str(cache)))
    assert ref.from_cache                                   # the run's own reference
    surf = np.unique(ref.face_cells)
    xs = ref.xyz[0, surf]
    lo = xs.min()
    k = np.minimum(((xs - lo) / 1.0).astype(int), int(np.ceil(xs.max() - lo)) - 1)
    excl = np.isin(surf, ref.excluded)
    want = sorted(set(k.tolist()))
    assert np.allclose(x, lo + np.array(want) + 0.5) and len(a["region"]) == x.size
    gap = [not np.any(~excl[k == j]) for j in want]
    assert list(np.isnan(u)) == gap and any(gap)
    assert [a["region"][i] for i in np.flatnonzero(gap)] == ["excluded"] * sum(gap)
    for r in s["regions"]:                       # each region's hot spot: its slice reads it
        j = int(np.flatnonzero(np.isclose(x, lo + np.floor(r["xyz_mm"][0] - lo) + 0.5))[0])
        worse = max(r[lay]["utilisation"]["modified"] for lay in ("surface", "core") if lay in r)
        assert u[j] >= worse
    g = s["governing"]["utilisation"]["modified"]
    assert a["governing"]["utilisation"] == np.nanmax(u) >= g
    rc, _, err = run(capsys, RPM_DAT, "--method", "fkm", "--level", "coarse", "--cache-dir",
                     cache, "--out", out)
    assert rc == 0, err
    assert not (out / "fkm_along.png").exists() and "along" not in json.loads(
        (out / "summary.json").read_text())
