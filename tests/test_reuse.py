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
    """Inside a ``fe.reuse`` scope the axisymmetric model's n = 0 and n = 1 factorisations are
    kept by their matrix's content: x2_57 with spin softening at 7000 rpm after 10 000 rpm (the
    softening is a low-rank term: the factorised matrices are the same) calls SuperLU's
    factorisation no more (nor assembles), and its fields are those of a solve outside the
    scope, which factorises again, bit for bit (the same matrix, the same factor)."""
    import numpy as np
    import scipy.sparse.linalg as sla

    from shaftfe.axisymmetric.model import AxiOptions
    from shaftfe.axisymmetric.solve import solve_axisymmetric
    from shaftfe.fe import reuse
    from shaftfe.model.loader import load_variant
    v = load_variant("x2_57")
    opts = AxiOptions(level="coarse")
    calls = []
    real = sla.splu

    def counting(*a, **k):
        calls.append(1)
        return real(*a, **k)
    monkeypatch.setattr(sla, "splu", counting)
    with reuse.shared() as stats:
        solve_axisymmetric(v, 10000.0, opts)
        made = len(calls)
        kept = solve_axisymmetric(v, 7000.0, opts)
    assert made >= 2 and len(calls) == made                 # n = 0 and n = 1, once
    # the assembled matrices too (made or loaded once: ``axisymmetric.harmonic.assemble``)
    assert stats["reused"] == {"harmonic n=0": 1, "harmonic n=1": 1,
                               "axisymmetric assembly": 1}
    fresh = solve_axisymmetric(v, 7000.0, opts)              # no scope: factorised again
    assert len(calls) == 2 * made
    for a, b in zip(kept.solution.harmonics, fresh.solution.harmonics, strict=True):
        assert np.array_equal(a.sym, b.sym)
        assert (a.anti is None and b.anti is None) or np.array_equal(a.anti, b.anti)
    assert kept.cases[0].peaks == fresh.cases[0].peaks
