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


def test_a_second_axisymmetric_solve_of_the_same_shaft_factorises_nothing(monkeypatch):
    """``axisymmetric.harmonic.solve`` keeps the factorisations of the last systems by their
    matrix's content: x2_57 with spin softening at 7000 rpm after 10 000 rpm (the softening is
    a low-rank term: the factorised matrices are the same) calls SuperLU's factorisation no
    more, and its fields are those of a solve with the kept factors cleared, bit for bit (the
    same matrix, the same factor)."""
    import numpy as np
    import scipy.sparse.linalg as sla

    from shaftfe.axisymmetric import harmonic as hm
    from shaftfe.axisymmetric.model import AxiOptions
    from shaftfe.axisymmetric.solve import solve_axisymmetric
    from shaftfe.model.loader import load_variant
    v = load_variant("x2_57")
    opts = AxiOptions(level="coarse")
    solve_axisymmetric(v, 10000.0, opts)
    calls = []
    real = sla.splu

    def counting(*a, **k):
        calls.append(1)
        return real(*a, **k)
    monkeypatch.setattr(sla, "splu", counting)
    kept = solve_axisymmetric(v, 7000.0, opts)
    assert not calls
    hm.clear_factors()
    fresh = solve_axisymmetric(v, 7000.0, opts)
    assert len(calls) >= 2                    # n = 0 and n = 1 factorised again
    for a, b in zip(kept.solution.harmonics, fresh.solution.harmonics, strict=True):
        assert np.array_equal(a.sym, b.sym)
        assert (a.anti is None and b.anti is None) or np.array_equal(a.anti, b.anti)
    assert kept.cases[0].peaks == fresh.cases[0].peaks
