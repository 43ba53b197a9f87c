"""`shaftfe demo` (what `make demo` runs) completes on the bundled defaults."""

import json
import subprocess
import sys


def test_demo_runs_and_writes_summary(tmp_path):
    out = subprocess.run([sys.executable, "-m", "shaftfe", "demo", "--out", str(tmp_path)],
                         capture_output=True, text=True, env={"MPLBACKEND": "Agg",
                                                              **__import__("os").environ})
    assert out.returncode == 0, out.stderr
    summary = json.loads((tmp_path / "summary.json").read_text())
    # seed 000 §8.2.2 (fig. 58): for crank C (X = 31.1 %) the max|F| minimum lies at X2 ≈ 57.3 %,
    # i.e. 57 % on a 1 % grid; max|Fx| vanishes at X2 = X = 31 %.
    minima = summary["balancing"]["sweep_minima"]
    assert round(minima["max_f"]["at_X2_percent"], 6) == 57.0
    assert round(minima["max_abs_fx"]["at_X2_percent"], 6) == 31.0
    for name in ("balance_forces.png", "balance_sweep.png"):
        assert (tmp_path / name).stat().st_size > 10_000
