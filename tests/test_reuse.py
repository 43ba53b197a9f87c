"""Compute once and reuse (brief, issue 8): `shaftfe fatigue` after `shaftfe static` on the same
model reads the static solution from the cache instead of solving again."""

import os
import subprocess
import sys


def test_fatigue_reuses_the_static_solution_of_shaftfe_static(tmp_path):
    env = {**os.environ, "SHAFTFE_CACHE_DIR": str(tmp_path / "cache"), "MPLBACKEND": "Agg"}
    common = ["--variant", "x2_57", "--level", "coarse"]
    st = subprocess.run([sys.executable, "-m", "shaftfe", "static", "--model", "solid", *common,
                         "--seed-load-case",
                         "--out", str(tmp_path / "static")], capture_output=True, text=True,
                        env=env)
    assert st.returncode == 0, st.stderr
    fa = subprocess.run([sys.executable, "-m", "shaftfe", "fatigue", "--method", "seed",
                         "--model", "solid", "loadspectra/rpm.dat",
                         *common, "--seed-load-case", "--out", str(tmp_path / "fatigue")],
                        capture_output=True, text=True, env=env,
                        cwd=os.path.dirname(os.path.dirname(__file__)))
    assert fa.returncode == 0, fa.stderr
    assert "static: from cache" in fa.stdout, fa.stdout
