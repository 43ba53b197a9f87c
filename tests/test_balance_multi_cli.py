"""CLI tests for `shaftfe balance twin|inline` (run as a subprocess, like a user would)."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import pytest


def shaftfe(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "shaftfe", "balance", *args],
                          capture_output=True, text=True, timeout=120)


def test_twin_table():
    r = shaftfe("twin", "--engine", "vm450", "--delta", "90", "--rpm", "6000")
    assert r.returncode == 0, r.stderr
    assert "max |F|" in r.stdout and "order" in r.stdout and "co-rot" in r.stdout
    assert "delta 90 deg, epsilon 0 deg" in r.stdout
    assert r.stderr == ""


def test_twin_json_cancels_first_order():
    """90° V2 with the default ε and counterweights (seed 000 §4.3.1): 1st order ≤ 1e-12 A."""
    r = shaftfe("twin", "--engine", "vm450", "--delta", "90", "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    # exact up to round-off (100 % by construction): approx's default rel 1e-6
    assert d["epsilon_deg"] == 0.0 and d["resultant_counterweight_pct"] == pytest.approx(100.0)
    f1 = next(o for o in d["force_orders"] if o["order"] == 1)
    # exact cancellation (round-off only: measured 1.2e-16 A); was 1e-9
    assert f1["amplitude"] <= 1e-12 * d["A_N"]
    assert [c["X_pct"] for c in d["cylinders"]] == [50.0, 50.0]


def test_twin_shared_pin_json():
    """Shared pin: one 100 % mass, cylinder 2's removed (seed 000 ch. 7)."""
    r = shaftfe("twin", "--delta", "90", "--shared-pin", "--json", "--rpm", "3000")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert [c["X_pct"] for c in d["cylinders"]] == [100.0, 0.0]
    assert d["rpm"] == 3000.0
    # exact cancellation (round-off only: measured 1.6e-16 A); was 1e-9
    assert d["force_orders"][0]["amplitude"] <= 1e-12 * d["A_N"]


def test_inline_i3_json_couple():
    """I3 120°, 80 mm: 1st-order couple √3 m_pos R ω² s (closed form, see the validation test),
    from the JSON's own A_N."""
    r = shaftfe("inline", "--engine", "vm450", "--pins", "0,120,240", "--spacing-mm", "80",
                "--json", "--orders", "1,2")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    c1 = d["couple_orders"][0]
    assert c1["order"] == 1
    # exact arithmetic (round-off only: measured 2e-16 relative, 4e-16 A); were 1e-9
    assert c1["amplitude"] == pytest.approx(math.sqrt(3) * d["A_N"] * 0.080, rel=1e-12)
    assert d["force_orders"][0]["amplitude"] <= 1e-12 * d["A_N"]
    assert d["z_ref_mm"] == pytest.approx(80.0)      # exact (the pin spacing): default rel 1e-6


def test_inline_table_and_plot(tmp_path):
    out = tmp_path / "sub" / "i4.png"
    r = shaftfe("inline", "--pins", "0,180,180,0", "--spacing-mm", "70,90,70", "--plot", str(out))
    assert r.returncode == 0, r.stderr
    assert "4 cylinders inline" in r.stdout and f"wrote {out}" in r.stdout
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert not list(out.parent.glob(".*.tmp"))


@pytest.mark.parametrize("args,needle", [
    (["twin", "--delta", "200"], "--delta"),
    (["twin", "--delta", "-5"], "--delta"),
    (["twin", "--delta", "abc"], "--delta"),
    (["twin", "--delta", "60", "--shared-pin", "--epsilon", "30"], "--epsilon"),
    (["twin", "--delta", "60", "--x", "50,50,50"], "--x"),
    (["twin", "--delta", "60", "--x", "50,,50"], "--x"),
    (["twin", "--delta", "60", "--rpm", "-100"], "--rpm"),
    # the one speed ceiling of every command (util.limits.RPM_CEILING, 20 000 rpm)
    (["twin", "--delta", "60", "--rpm", "50000"], "(0, 20000] rpm"),
    (["twin", "--delta", "60", "--engine", "nosuch"], "--engine"),
    (["twin", "--delta", "60", "--plot", "out.txt"], "--plot"),
    (["inline", "--pins", "0,120,240", "--spacing-mm", "80,80,80"], "--spacing-mm"),
    (["inline", "--pins", "0,12o,240", "--spacing-mm", "80"], "--pins"),
    (["inline", "--pins", "0,120,240", "--spacing-mm", "80", "--x", "10,20"], "--x"),
    (["inline", "--pins", "0,120,240", "--spacing-mm", "80", "--orders", "0,2"], "--orders"),
    (["inline", "--pins", "0,120,240"], "--spacing-mm"),
])
def test_bad_input_one_line_exit_2(args, needle, tmp_path):
    plot = tmp_path / "never.png"
    r = shaftfe(*args, "--plot", str(plot)) if "--plot" not in args else shaftfe(*args)
    assert r.returncode == 2
    assert r.stdout == ""
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, r.stderr
    assert "Traceback" not in r.stderr and needle in lines[0]
    assert not plot.exists()


def test_the_mechanism_rules_serve_api_callers_as_before():
    """balance.multi's rules (issue #34: the command only applies them) keep what an API
    caller got: the orders as asked (order and repeats), a whole float sample count; and
    refuse what the command refused: a negative gap even with one cylinder."""
    import numpy as np

    from shaftfe.balance import multi
    from shaftfe.errors import InputError
    theta = multi.crank_angles(16.0)                       # a whole number, given as a float
    assert theta.size == 16
    x, y = np.cos(theta), np.sin(3 * theta)
    assert [o.order for o in multi.harmonic_orders(x, y, (3, 1, 2, 1))] == [3, 1, 2, 1]
    assert multi.harmonic_orders(x, y, ()) == ()
    with pytest.raises(InputError, match="integers in"):
        multi.harmonic_orders(x, y, (2.5,))
    with pytest.raises(InputError, match="gaps >= 0 mm"):
        multi.inline([0.0], -0.08)
