"""3D static FE: run time against error, per mesh level, element order and solver.

Cases (each run in a fresh subprocess so that time and peak memory are its own):

1. Stepped shaft Ø17/Ø22/Ø17, r = 1 mm fillets (tests/validation/test_static_fillet.py):
   peak max-principal stress in the left fillet as Kt, and max deflection; errors relative to
   the finest P2 run here (the Roark fit is printed for orientation: FE lies 8-14 % above it).
2. Uniform cylinder (tests/validation/test_static_beam.py): deflection under the load against
   Timoshenko beam theory with spring compliance.
3. Variant x2_57 (if it loads), spring supports, 10 000 rpm: cold (empty mesh cache) and cached
   total time of ``solve_static`` and the peak RSS, per solver that imports here.

Run: ``python -m benchmarks bench_static`` (several minutes). Optional solvers: ``pip install
shaftfe[fast]`` (pypardiso) and ``pyamg``.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

_CHILD = r"""
import json, math, resource, sys, time
sys.path.insert(0, {root!r}); sys.path.insert(0, {root!r} + "/tests/validation")
t_import = time.perf_counter()
import numpy as np
from shaftfe.static import StaticOptions, solve_static
case, level, order, solver, cache = {args!r}
out = {{}}
if case == "fillet":
    import test_static_fillet as T
    v = T.stepped()
elif case == "beam":
    import test_static_beam as T
    v = T.shaft()
else:
    from shaftfe.variant import load_variant
    v = load_variant("x2_57")
t0 = time.perf_counter()
r = solve_static(v, [10000.0], StaticOptions(level=level, order=order, solver=solver),
                 cache_dir=cache, beam=False)
out["seconds"] = time.perf_counter() - t0
c = r.case(10000.0)
out.update(dofs=r.n_dofs, max_defl=c.max_deflection_mm, peak_vm=c.peak_von_mises_MPa,
           solver=r.diagnostics["solver"], factor=r.diagnostics["factor_seconds"],
           assembly=r.diagnostics["assembly_seconds"], mesh=r.diagnostics["mesh_seconds"],
           relres=r.diagnostics["relative_residual"])
if case == "fillet":
    out["kt"] = T._kt_fe(r, "fillet:a")
if case == "beam":
    w, _, _ = T.timoshenko(v.attachments[0].force_N(10000.0), np.array([50.0]))
    st = next(s for s in c.stations if s.name == "seat:w")
    out["defl_err"] = st.uy_mm / w[0] - 1
out["rss_MB"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
print("RESULT" + json.dumps(out))
"""


def _run(case, level, order, solver, cache) -> dict | None:
    code = _CHILD.format(root=str(ROOT), args=(case, level, order, solver, str(cache)))
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       timeout=1800)
    for line in p.stdout.splitlines():
        if line.startswith("RESULT"):
            return json.loads(line[6:])
    print(f"   {case} {level} P{order} {solver}: failed: {p.stderr.strip().splitlines()[-1:]}")
    return None


def main() -> None:
    from shaftfe import solvers
    have = [s for s, ok in solvers.available().items() if ok and s != "amg"]
    print(f"solvers timed here: {', '.join(have)} (AMG-CG skipped: 53 s for the 14 right-hand "
          "sides at 36k dofs, far slower than a direct factorisation)")
    from shaftfe.scf import kt_shoulder
    with tempfile.TemporaryDirectory() as tmp:
        cache = Path(tmp)
        print("\n1. stepped shaft, left fillet (Roark Kt = "
              f"{kt_shoulder(22, 17, 1.0).kt:.3f}); errors vs the fine P2 run")
        runs = {}
        for order in (1, 2):
            for level in ("coarse", "default", "fine"):
                runs[(order, level)] = _run("fillet", level, order, "auto", cache)
        ref = runs[(2, "fine")]
        print(f"{'P':>2} {'level':<8}{'dofs':>8}{'time s':>8}{'Kt':>8}{'Kt err':>9}"
              f"{'defl err':>10}{'RSS MB':>8}")
        for (order, level), r in runs.items():
            if r is None or ref is None:
                continue
            print(f"{order:>2} {level:<8}{r['dofs']:>8}{r['seconds']:>8.2f}{r['kt']:>8.3f}"
                  f"{r['kt'] / ref['kt'] - 1:>+9.3%}{r['max_defl'] / ref['max_defl'] - 1:>+10.3%}"
                  f"{r['rss_MB']:>8.0f}")

        print("\n2. uniform cylinder: deflection under the load vs Timoshenko + springs")
        print(f"{'level':<8}{'dofs':>8}{'time s':>8}{'defl err':>10}")
        for level in ("coarse", "default", "fine"):
            r = _run("beam", level, 2, "auto", cache)
            if r:
                print(f"{level:<8}{r['dofs']:>8}{r['seconds']:>8.2f}{r['defl_err']:>+10.3%}")

        print("\n3. x2_57, springs, 10 000 rpm, default level: cold (empty cache) / cached")
        print(f"{'solver':<9}{'dofs':>8}{'cold s':>8}{'cached s':>9}{'mesh s':>8}{'asm s':>7}"
              f"{'factor s':>9}{'relres':>9}{'RSS MB':>8}{'peak vm':>9}{'max defl':>10}")
        for solver in have:
            with tempfile.TemporaryDirectory() as c2:
                cold = _run("x2_57", "default", 2, solver, c2)
                warm = _run("x2_57", "default", 2, solver, c2)
            if cold and warm:
                print(f"{solver:<9}{warm['dofs']:>8}{cold['seconds']:>8.2f}{warm['seconds']:>9.2f}"
                      f"{cold['mesh']:>8.2f}{warm['assembly']:>7.2f}{warm['factor']:>9.2f}"
                      f"{warm['relres']:>9.1e}{warm['rss_MB']:>8.0f}{warm['peak_vm']:>9.1f}"
                      f"{warm['max_defl']:>10.4f}")


if __name__ == "__main__":
    main()
