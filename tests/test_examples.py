"""The two scripts in examples/ run on the public API (shaftfe/__init__.py) and succeed.

custom_shaft.py exits 1 unless its 3D bearing reactions balance the part's force m e ω² to the
solver's residual contract (1e-8, shaftfe.static.solve.RESIDUAL_TOL);
variant_study.py prints one row per variant file.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _run(script: str, tmp_path) -> str:
    env = dict(os.environ, MPLBACKEND="Agg", SHAFTFE_CACHE_DIR=str(tmp_path / "cache"))
    p = subprocess.run([sys.executable, str(ROOT / "examples" / script)], cwd=ROOT, env=env,
                       capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stdout + p.stderr
    return p.stdout


@pytest.mark.slow
def test_custom_shaft_example_matches_statics(tmp_path):
    out = _run("custom_shaft.py", tmp_path)
    assert "force balance of the reactions" in out


def test_variant_study_example_lists_every_variant(tmp_path):
    from shaftfe import list_variants
    out = _run("variant_study.py", tmp_path)
    for name in list_variants():
        assert name in out
