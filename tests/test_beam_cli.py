"""CLI `shaftfe beam`: output, options, errors (exit 2, one line, no half-written file)."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

import shaftfe.model.loader as variant_mod
from shaftfe.cli import main
from shaftfe.model.variant import Attachment, Bearing, Duty, Material, Segment, Variant

ROOT = Path(__file__).resolve().parents[1]
K = ((35_030.0, 8756.0), (8756.0, 35_030.0))


def _fake_variant(n_bearings: int = 2) -> Variant:
    segs = (Segment("a", 0.0, 25.0, 17.0, 1.0), Segment("b", 25.0, 50.0, 22.0, 1.0),
            Segment("c", 75.0, 35.0, 17.0))
    brgs = (Bearing("gear_side", "3203", 30.0, 10.0, 14_400.0, 9000.0, K, axial=True),
            Bearing("free_side", "3203", 70.0, 10.0, 14_400.0, 9000.0, K))[:n_bearings]
    atts = (Attachment("gear", 5.0, 20.0, 0.152, 1.36, 12.0),
            Attachment("cw2", 80.0, 105.0, 0.24, 20.23, 92.0, angle_deg=180.0))
    return Variant("fake", "test", segs, brgs, atts,
                   Material("14220", 210_000.0, 0.3, 7.85e-9, 540.0, 800.0), 0.0,
                   clearance_station_x_mm=50.0,
                   duty=Duty("fake", (1200.0, 9500.0), design_speeds_rpm=(10_000.0,)))


@pytest.fixture
def fake_loader(monkeypatch):
    def load(name, overrides=()):
        return _fake_variant(1 if name == "one_bearing" else 2)
    monkeypatch.setattr(variant_mod, "load_variant", load, raising=False)


def test_json_two_speeds_and_equilibrium(fake_loader, capsys):
    """Reactions balance the centrifugal loads m e ω² (statics) and the 7000 rpm forces are
    (7000/10000)² of the 10 000 rpm ones."""
    assert main(["beam", "--variant", "fake", "--rpm", "10000,7000", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    r10, r7 = out["results"]
    w = 10_000 * 2 * math.pi / 60
    Fy = 0.152 * 1.36e-3 * w**2 - 0.24 * 20.23e-3 * w**2
    # statics up to the rounding of the reaction recovery K u − F: ≤ eps Σ|K||u| ≈ 3e-11 |F|
    # here (measured 3.8e-14); 1e-9 = 35× that
    assert sum(b["Fy_N"] for b in r10["bearings"]) == pytest.approx(-Fy, rel=1e-9)
    for b10, b7 in zip(r10["bearings"], r7["bearings"], strict=True):
        # exact arithmetic (round-off only): one unit solve scaled by ω², (7/10)² = 0.49
        assert b7["F_N"] == pytest.approx(b10["F_N"] * 0.49, rel=1e-12)
    assert set(r10["stations"]) >= {"gear", "cw2", "clearance", "gear_side", "free_side"}
    assert len(r10["notches"]) == 2


def test_table_output_and_plot(fake_loader, capsys, tmp_path):
    png = tmp_path / "out" / "beam.png"
    assert main(["beam", "--variant", "fake", "--rigid-supports", "--plot", str(png)]) == 0
    text = capsys.readouterr().out
    assert "reactions" in text and "L10h" in text and "Kt" in text
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_singular_model_is_one_line_exit_2(fake_loader, capsys, tmp_path):
    png = tmp_path / "x.png"
    assert main(["beam", "--variant", "one_bearing", "--plot", str(png)]) == 2
    err = capsys.readouterr().err
    assert "singular" in err and len(err.strip().splitlines()) == 1
    assert not png.exists()


@pytest.mark.parametrize("argv", [["--rpm", "abc"], ["--rpm", "-5"], ["--plot", "out.txt"],
                                  ["--max-element", "0"]])
def test_bad_options_exit_2_one_line(argv, tmp_path):
    out = subprocess.run([sys.executable, "-m", "shaftfe", "beam", "--variant", "x2_57", *argv],
                         capture_output=True, text=True, cwd=tmp_path)
    assert out.returncode == 2
    assert "Traceback" not in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "out.txt").exists()


def _real_variant_available() -> bool:
    return (ROOT / "geometry" / "x2_57.toml").exists() and hasattr(variant_mod, "load_variant")


@pytest.mark.skipif(not _real_variant_available(),
                    reason="geometry/x2_57.toml or shaftfe.model.loader.load_variant "
                           "not present yet")
def test_real_variant_x2_57_runs():
    """End-to-end on the real variant file: two bearings, reactions balance the attachments'
    m e ω² (statics), finite stresses."""
    out = subprocess.run([sys.executable, "-m", "shaftfe", "beam", "--variant", "x2_57",
                          "--rigid-supports", "--json"], capture_output=True, text=True,
                         cwd=ROOT)
    assert out.returncode == 0, out.stderr
    res = json.loads(out.stdout)["results"][0]
    v = variant_mod.load_variant("x2_57")
    Fy = sum(a.force_N(10_000) * math.cos(math.radians(a.angle_deg)) for a in v.attachments)
    Fz = sum(a.force_N(10_000) * math.sin(math.radians(a.angle_deg)) for a in v.attachments)
    scale = max(a.force_N(10_000) for a in v.attachments)
    # statics up to the rounding of the recovery K u − F: ≤ eps Σ|K||u| ≈ 3e-12 of the largest
    # attachment force (measured 1.4e-14); 1e-9 leaves 300×
    assert abs(sum(b["Fy_N"] for b in res["bearings"]) + Fy) < 1e-9 * scale
    assert abs(sum(b["Fz_N"] for b in res["bearings"]) + Fz) < 1e-9 * scale
    assert math.isfinite(res["max_sigma_vm_nominal_MPa"])


def test_axial_force_and_torque_printed_where_they_act(capsys):
    """issue #31 (beam): a variant with torques and an axial force (the Shigley Example 7-2
    file: a torque between the gears, none axial) prints the torque line and the shoulders'
    torsion Kt; the seed's variant (no torque, no axial force) prints neither. JSON carries
    max |T|, max |N|, τ and the gauge torque (zero: the file's torques balance)."""
    data = str(ROOT / "tests/validation/data/shigley_ex7_2.toml")
    # the file states no [duty]: the speed on the command line (its loads are constant)
    assert main(["beam", "--variant", data, "--rigid-supports", "--rpm", "1000"]) == 0
    out = capsys.readouterr().out
    assert "torque max |T| 3.661e+05 N·mm" in out and "Kt_T" in out and "Kt_N" not in out
    assert main(["beam", "--variant", data, "--rigid-supports", "--rpm", "1000", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)["results"][0]
    # 3240 lbf·in (the book's torque): exact unit conversion, round-off of the statics only
    assert r["max_abs_T_Nmm"] == pytest.approx(3240 * 4.4482216152605 * 25.4, rel=1e-9)
    assert r["max_abs_N_N"] == 0.0 and r["max_tau_MPa"] > 0
    assert abs(r["torsion_gauge_Nmm"]) <= 1e-9 * r["max_abs_T_Nmm"]  # balanced: round-off
    assert main(["beam", "--variant", "x2_57"]) == 0
    out = capsys.readouterr().out
    assert "torque max" not in out and "Kt_T" not in out
