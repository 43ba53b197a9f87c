"""Rotor dynamics (beam path): time of a 12-mode × 9-speed Campbell sweep against its error.

Variant x2_57, beam model (5 mm elements), 0-8000 rpm in 1000 rpm steps. Timed: the sweep
(reduced basis with the convergence check, per-speed state-space eigenproblems, MAC tracking,
labels, critical speeds), best of several runs, for the automatic basis and for fixed basis
sizes; error: largest relative difference of the 12 frequencies against the full-size
quadratic eigenproblem at every speed (dense QZ). Also the model assembly time and the time
of the full-size solve itself, for scale. The target is <= 50 ms for the sweep.

The matrices are small (172 dofs, 48 × 48 state matrices): with a multi-threaded BLAS on a
busy 2-core machine the thread synchronisation dominates (10× slower measured), so the same
measurement is repeated in a child process with OPENBLAS_NUM_THREADS=1 and both are printed.
"""

from __future__ import annotations

import math
import time


def _best(fn, repeat: int = 7) -> float:
    best = math.inf
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    return best


def main() -> None:
    import os
    import subprocess
    import sys

    _run(f"BLAS threads: default (OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS')})")
    if os.environ.get("OPENBLAS_NUM_THREADS") != "1":
        env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1",
                   MKL_NUM_THREADS="1")
        code = "import benchmarks.bench_rotor as b; b._run('BLAS threads: 1 (child process)')"
        p = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                           text=True, cwd=os.path.dirname(os.path.dirname(__file__)) or ".")
        print(p.stdout, end="")
        if p.returncode:
            print(p.stderr, end="")


def _run(title: str) -> None:
    import numpy as np

    from shaftfe.model.loader import load_variant
    from shaftfe.rotordynamics import beam_rotor as rotor
    from shaftfe.rotordynamics import kernels as campbell

    v = load_variant("x2_57")
    rpms = np.arange(0.0, 8001.0, 1000.0)
    n = 12
    t_build = _best(lambda: rotor.rotor_from_variant(v))
    r = rotor.rotor_from_variant(v)
    t_full = []
    full = []
    for rpm in rpms:
        t = time.perf_counter()
        s = campbell.full_qep(r.K, r.M, r.G, rpm * math.pi / 30, n)
        t_full.append(time.perf_counter() - t)
        full.append(np.sort(s.imag) / (2 * math.pi))
    full = np.array(full)

    def err(res):
        return float(np.max(np.abs(np.sort(res.freq_hz, axis=1) / full - 1)))

    print(f"-- {title}")
    print(f"x2_57 beam rotor: {r.n_dof} dofs, {len(r.disks)} disks; model build "
          f"{t_build * 1e3:.2f} ms; full-size QEP {np.mean(t_full) * 1e3:.1f} ms per speed")
    print(f"{'case (12 modes x 9 speeds)':<34}{'basis':>7}{'time ms':>10}{'max rel. error':>16}")
    res = rotor.campbell(r, rpms, n)
    t = _best(lambda: rotor.campbell(r, rpms, n))
    print(f"{'automatic basis (tol 1e-6)':<34}{res.basis_size:>7}{t * 1e3:>10.2f}"
          f"{err(res):>16.2e}")
    for m in (14, 18, 24, 36, 54):
        basis = campbell.modal_basis(r.K, r.M, m)
        red = campbell.project(basis, r.G, r.C)

        def fixed(red=red):
            out = []
            for rpm in rpms:
                s, _, _ = campbell.reduced_eig(red, rpm * math.pi / 30)
                out.append(s.imag[:n] / (2 * math.pi))
            return np.array(out)

        f = fixed()
        e = float(np.max(np.abs(np.sort(f, axis=1) / full - 1)))
        tm = _best(lambda red=red, m=m: (campbell.modal_basis(r.K, r.M, m), fixed(red)))
        print(f"{'fixed basis, eigenvalues only':<34}{m:>7}{tm * 1e3:>10.2f}{e:>16.2e}")
    t_cli = _best(lambda: (rotor.rotor_from_variant(v), rotor.campbell(
        rotor.rotor_from_variant(v), rpms, n, orders=(1.0, 2.0))), repeat=3)
    print(f"build + sweep (what `shaftfe campbell 0:8000` computes): {t_cli * 1e3:.1f} ms")


if __name__ == "__main__":
    main()
