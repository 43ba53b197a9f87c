"""`shaftfe balance forces|sweep|ratios`: output formats and one-line errors (exit 2)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from shaftfe.balance.engines import load_engine
from shaftfe.balance.single import balancer_ratio, crank_ratio, forces


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "shaftfe", "balance", *args],
                          capture_output=True, text=True, timeout=120)


def assert_one_line_error(out: subprocess.CompletedProcess, *needles: str) -> None:
    assert out.returncode == 2, (out.stdout, out.stderr)
    assert "Traceback" not in out.stderr
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1, out.stderr
    for n in needles:
        assert n in lines[0], lines[0]


def test_forces_json_matches_api():
    """`forces --json` reports the API's metrics (seed 000 §8.1 case X 30.16 %, X2 54.5 %)."""
    out = run("forces", "--engine", "vm450", "--x", "30.16", "--x2", "54.5", "--rpm", "6000",
              "--json")
    assert out.returncode == 0, out.stderr
    d = json.loads(out.stdout)
    ref = forces(load_engine("vm450"), 0.3016, 0.545, 6000.0).metrics
    assert d["X_percent"] == pytest.approx(30.16)     # exact up to 30.16 → 0.3016 → %: rel 1e-6
    assert d["tilt_deg"] == -10.0
    for k, v in ref.as_dict().items():
        # exact arithmetic (round-off only): same computation, JSON floats round-trip exactly
        assert d["metrics"][k] == pytest.approx(v, rel=1e-12, abs=1e-12)


def test_mass_overrides_set_the_ratios():
    """--crank-mass-kg/--crank-radius-mm and --balancer-* give X, X2 by seed 000 eq. 2.3.f/h
    (crank B 3.40 kg × 4.85 mm, balancer A4 0.765 kg × 5.74 mm, §8.1.1-8.1.2)."""
    out = run("forces", "--engine", "vm450", "--crank-mass-kg", "3.40", "--crank-radius-mm",
              "4.85", "--balancer-mass-kg", "0.765", "--balancer-radius-mm", "5.74", "--json")
    assert out.returncode == 0, out.stderr
    d = json.loads(out.stdout)
    e = load_engine("vm450")
    R = e.crank_radius_mm
    # exact arithmetic (round-off only): the same formulas on the same inputs
    assert d["X_percent"] == pytest.approx(100 * crank_ratio(3.40, 4.85, e.m_rot_kg, e.m_pos_kg,
                                                             R), rel=1e-12)
    # same: exact arithmetic
    assert d["X2_percent"] == pytest.approx(100 * balancer_ratio(0.765, 5.74, e.m_pos_kg, R),
                                            rel=1e-12)


def test_forces_table_csv_and_plot(tmp_path: Path):
    csv, png = tmp_path / "f.csv", tmp_path / "f.png"
    out = run("forces", "--engine", "vm450", "--x", "30.16", "--x2", "31", "--tilt-deg", "0",
              "--samples", "720", "--csv", str(csv), "--plot", str(png))
    assert out.returncode == 0, out.stderr
    assert "max|F|" in out.stdout and "3 731.4" in out.stdout   # seed 000 §8.1.1: 3731 N
    rows = csv.read_text().strip().splitlines()
    assert rows[0].startswith("alpha_deg,Fx_N,Fy_N,F_N") and len(rows) == 721
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_sweep_mode2_json_csv_plot(tmp_path: Path):
    """Mode 2 on the seed's grid reproduces its X2 column for max|F| (seed 000 §5.4)."""
    csv, png = tmp_path / "s.csv", tmp_path / "s.png"
    out = run("sweep", "--engine", "vm450", "--x", "31:40:1", "--x2", "0:100:1", "--tilt-deg",
              "0", "--sampling", "seed_inclusive", "--json", "--csv", str(csv), "--plot",
              str(png))
    assert out.returncode == 0, out.stderr
    d = json.loads(out.stdout)
    assert d["mode"] == 2 and d["samples"] == 361
    # grid points are integers in % (round-off only in forming them): approx's default 1e-6
    assert d["minima"]["max_f"]["X2_percent"] == pytest.approx([57] * 5 + [56] * 4 + [55])
    assert len(d["grid_N"]["max_f"]) == 10 and len(d["grid_N"]["max_f"][0]) == 101
    rows = csv.read_text().strip().splitlines()
    assert rows[0].split(",")[0] == "X_percent" and len(rows) == 11
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_sweep_mode1_table():
    out = run("sweep", "--engine", "vm450", "--x", "31", "--x2", "0:100:10")
    assert out.returncode == 0, out.stderr
    assert "mode 1" in out.stdout and "minimum over X2" in out.stdout
    assert out.stdout.count("\n") > 11       # one row per X2 value + the minima table


def test_ratios_json():
    """`ratios --engine fe570` gives seed 003's P = 1.03, Pv = 0.529 (§5.4-5.5)."""
    out = run("ratios", "--engine", "fe570", "--json")
    assert out.returncode == 0, out.stderr
    d = json.loads(out.stdout)
    assert d["P_percent"] == pytest.approx(103, abs=0.5)     # seed figure printed to 3 digits
    assert d["Pv_percent"] == pytest.approx(52.9, abs=0.05)  # seed figure printed to 3 digits
    human = run("ratios", "--engine", "fe570")
    assert human.returncode == 0 and "Pv" in human.stdout


@pytest.mark.parametrize(("args", "needles"), [
    (("forces", "--engine", "nosuch"), ("--engine", "vm450", "fe570")),
    (("forces", "--x", "250"), ("--x", "[0, 200]")),
    (("forces", "--x2", "-1"), ("--x2",)),
    (("sweep", "--x", "40:31"), ("--x", "40:31")),
    (("sweep", "--x2", "0:abc"), ("--x2",)),
    (("forces", "--rpm", "-6000"), ("--rpm",)),
    (("forces", "--x", "30", "--crank-mass-kg", "3.6", "--crank-radius-mm", "2.7"), ("--x",)),
    (("forces", "--plot", "out.jpg"), ("--plot", ".png")),
    (("ratios", "--engine", "missing/file.toml"), ("--engine", "does not exist")),
])
def test_bad_input_is_one_line(args, needles):
    assert_one_line_error(run(*args), *needles)


def test_negative_mass_file_writes_nothing(tmp_path: Path):
    """A negative mass in an engine file → one line naming file and field, exit 2, and no
    half-written output."""
    src = Path(load_engine("vm450").source).read_text()
    bad = tmp_path / "bad.toml"
    bad.write_text(src.replace("balancer_mass_kg = 0.9473", "balancer_mass_kg = -0.9473"))
    csv = tmp_path / "out.csv"
    out = run("sweep", "--engine", str(bad), "--x", "31", "--csv", str(csv))
    assert_one_line_error(out, "bad.toml", "balancer_mass_kg", "-0.9473")
    assert not csv.exists()
