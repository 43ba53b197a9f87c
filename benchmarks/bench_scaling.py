"""Scaling of the 3D pipeline with the number of degrees of freedom (issue 8).

Mesh family: ``shaftfe.model.examples.four_step_shaft`` (its one bearing made axial and given a
tilt stiffness 1e8 N·mm/rad so that it supports the shaft alone) meshed with the "coarse"
level's settings scaled by s (k_global, k_fillet, k_sharp all × s; a benchmark-only ``LEVELS``
entry, mesh.py is not changed). P2, the default solver ("auto": PARDISO if installed, else SuperLU).

Stages, each timed (wall ``perf_counter`` and process CPU ``process_time``, which includes the
~0.5 % of a 10 ms RSS sampler) and with its peak RSS increase (a sampler of
/proc/self/status VmRSS above the RSS at the stage's start, after ``gc.collect()`` and glibc's
``malloc_trim(0)`` hand freed memory back), one fresh process per mesh; the stage's own arrays
that outlive it (K, the factor, M) count in its increase:

* assembly — ``fem.elasticity_stiffness`` (K only);
* supports + loads — the RBE3 rows of every bearing (``supports.couple_bearing``) and the
  surface load of every part (``fem.surface_load``), as ``static.build_model`` makes them;
* factorisation and solves — ``static.solve_model`` (``factor_seconds``; solves = the rest of
  the call: the Woodbury right-hand sides and the small dense capacitance; the memory column is
  the peak of the whole call for both);
* stress recovery — ``recovery.nodal_stress`` + von Mises + principal stresses;
* mass — the P2 consistent mass matrix, assembled here with scikit-fem (quadrature order 4);
* eigen solution — 12 elastic modes (+ the 6 rigid ones of the free shaft) of (K, M) by
  ``rotordynamics.kernels.modal_basis`` with shift-invert at σ = −(2π·100 Hz)² (K − σM is positive
  definite), OPinv from ``solvers.factorize`` of K − σM (its factorisation included);
* mesh — the Gmsh build (cache off), for reference.

Every child runs with MKL_NUM_THREADS=1: on this 2-core machine shared by six sessions MKL's
second thread spins (a one-vector PARDISO solve took 0.19 s with 2 threads and 0.034 s with 1
at 12k dofs, load ≈ 11), which would make the eigen stage measure contention, not the code.

Exponents: least-squares slope of log(CPU time) and log(memory) against log(dofs) over the meshes
with ≥ 20k dofs. Shares at the default level: the same stages for variant x2_57 at level
"default" through ``solve_static`` (its own diagnostics).

Run: ``python -m benchmarks bench_scaling`` (~5-10 min). Writes
``reports/benchmarks/scaling.md``, ``scaling.json`` and ``scaling.png``.
"""

from __future__ import annotations

import json
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "reports" / "benchmarks"
SCALES = (2.0, 1.4, 1.0, 0.7, 0.5, 0.4)
BASE = {"k_global": 0.70, "k_fillet": 0.9, "k_sharp": 5.0, "grad": 1.3}
STAGES = ("mesh", "assembly", "supports+loads", "factorisation", "solves", "recovery", "mass",
          "eigen")

_CHILD = r"""
import ctypes, gc, json, math, sys, threading, time
sys.path.insert(0, {root!r})
import numpy as np
scale = {scale!r}


class RSS:
    def __init__(self):
        self.peak = 0
        self.run = True
        threading.Thread(target=self._loop, daemon=True).start()

    @staticmethod
    def now():
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) * 1024
        return 0

    def _loop(self):
        while self.run:
            self.peak = max(self.peak, self.now())
            time.sleep(0.01)

    def stage(self, fn):
        gc.collect()
        ctypes.CDLL("libc.so.6").malloc_trim(0)     # freed memory back to the OS first
        base = self.now()
        self.peak = base
        t, c = time.perf_counter(), time.process_time()
        out = fn()
        dt, dc = time.perf_counter() - t, time.process_time() - c
        time.sleep(0.005)
        self.cpu = dc
        return out, dt, max(self.peak - base, 0)


rss = RSS()
import dataclasses
from shaftfe.model import examples
from shaftfe.fe import assembly as fem
from shaftfe.solid import mesh
from shaftfe.fe import recovery
from shaftfe.fe import solvers
from shaftfe.static.model import StaticOptions, build_model
from shaftfe.static.solve import solve_model
from shaftfe.rotordynamics.kernels import modal_basis
base = {base!r}
from shaftfe.solid.levels import MeshLevel
level = MeshLevel("scaling", **{{k: (v * scale if k != "grad" else v) for k, v in base.items()}})
v = examples.four_step_shaft()
v = dataclasses.replace(v, bearings=tuple(dataclasses.replace(b, tilt_stiffness_Nmm_per_rad=1e8,
                                                              axial=True)
                                          for b in v.bearings))
res = {{}}
sm, t, m = rss.stage(lambda: mesh.build_mesh(v, level, 2, use_cache=False))
res["mesh"] = (t, m, rss.cpu)
res["dofs"] = sm.n_dofs
mat = v.material
K, t, m = rss.stage(lambda: fem.elasticity_stiffness(sm.mesh, mat.E_MPa, mat.nu))
res["assembly"] = (t, m, rss.cpu)
from shaftfe.fe import supports
from shaftfe.static.model import REF_RPM, _direction

def supports_and_loads():
    cs = [supports.couple_bearing(sm.mesh, b) for b in v.bearings]
    fs = [fem.surface_load(sm.mesh, sm.mesh.boundaries[f"load:{{a.name}}:pressed"],
                           a.force_N(REF_RPM), _direction(a.angle_deg)) for a in v.attachments]
    return cs, fs
_, t, m = rss.stage(supports_and_loads)
res["supports+loads"] = (t, m, rss.cpu)
model = build_model(v, StaticOptions(level=level), shaft_mesh=sm)
sol, t, m = rss.stage(lambda: solve_model(model))
d = {{**sol.diagnostics, **sol.run}}
res["factorisation"] = (d["factor_seconds"], m, rss.cpu * d["factor_seconds"] / t)
res["solves"] = (t - d["factor_seconds"], m, rss.cpu * (1 - d["factor_seconds"] / t))
res["solver"] = d["solver"]
res["relres"] = d["relative_residual"]

def rec():
    s = recovery.nodal_stress(sm.mesh, sol.u, mat.E_MPa, mat.nu)
    return recovery.von_mises(s), recovery.principal(s)
_, t, m = rss.stage(rec)
res["recovery"] = (t, m, rss.cpu)

def mass_matrix():
    from skfem import BilinearForm
    rho = mat.density_t_mm3
    @BilinearForm
    def mass(u, w, p):
        return rho * (u[0] * w[0] + u[1] * w[1] + u[2] * w[2])
    return mass.assemble(fem.vector_basis(sm.mesh, 4)).tocsr()
M, t, m = rss.stage(mass_matrix)
res["mass"] = (t, m, rss.cpu)

def eig():
    sigma = -(2 * math.pi * 100.0) ** 2
    from scipy.sparse.linalg import LinearOperator
    fac = solvers.factorize((K - sigma * M).tocsr(), "auto")
    op = LinearOperator(K.shape, matvec=fac.solve, dtype=float)
    b = modal_basis(K, M, 18, sigma=sigma, opinv=op)
    return b.omega
om, t, m = rss.stage(eig)
res["eigen"] = (t, m, rss.cpu)
res["f_hz"] = [float(x) for x in om / (2 * math.pi)]
rss.run = False
print("RESULT " + json.dumps(res))
"""

_CHILD_DEFAULT = r"""
import json, sys
sys.path.insert(0, {root!r})
from shaftfe.static.model import StaticOptions
from shaftfe.static.solve import solve_static
from shaftfe.model.loader import load_variant
r = solve_static(load_variant("x2_57"), [10000.0], StaticOptions(level="default"),
                 cache_dir={cache!r}, beam=False)
d = {{**r.diagnostics, **r.run}}
d["dofs"] = r.n_dofs
print("RESULT " + json.dumps({{k: v for k, v in d.items() if isinstance(v, (int, float, str))}}))
"""


def _run(code: str) -> dict:
    import os
    env = {**os.environ, "MKL_NUM_THREADS": "1"}
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    line = next((x for x in p.stdout.splitlines() if x.startswith("RESULT ")), None)
    if p.returncode != 0 or line is None:
        raise RuntimeError(p.stderr[-2000:])
    return json.loads(line[7:])


def fit(x, y) -> float:
    import numpy as np
    x, y = np.asarray(x, float), np.asarray(y, float)
    ok = (x >= 20_000) & (y > 0)
    if ok.sum() < 2:
        return float("nan")
    return float(np.polyfit(np.log(x[ok]), np.log(y[ok]), 1)[0])


def main() -> None:
    import tempfile
    load0 = subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    runs = []
    for s in SCALES:
        t = time.perf_counter()
        r = _run(_CHILD.format(root=str(ROOT), scale=s, base=BASE))
        r["scale"] = s
        runs.append(r)
        print(f"scale {s}: {r['dofs']} dofs, {time.perf_counter() - t:.0f} s", flush=True)
    with tempfile.TemporaryDirectory() as cache:
        _run(_CHILD_DEFAULT.format(root=str(ROOT), cache=cache))          # mesh into the cache
        dflt = _run(_CHILD_DEFAULT.format(root=str(ROOT), cache=cache))   # warm: stage times
    load1 = subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    runs.sort(key=lambda r: r["dofs"])
    dofs = [r["dofs"] for r in runs]
    expo = {s: (fit(dofs, [r[s][2] for r in runs]), fit(dofs, [r[s][1] for r in runs]),
                fit(dofs, [r[s][0] for r in runs])) for s in STAGES}
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "scaling.json").write_text(json.dumps({"runs": runs, "exponents": expo,
                                                  "default_x2_57": dflt}, indent=1))
    _plot(runs, expo)
    lines = ["# Scaling with degrees of freedom (issue 8)", "",
             "Generated by `python -m benchmarks bench_scaling`; method in the module "
             "docstring. Load (uptime) before: `" + load0 + "`; after: `" + load1 + "` "
             "(2 shared cores: times are indicative, exponents more robust than seconds).", "",
             "## Time per stage: CPU s (wall s), and peak RSS increase (MB)", "",
             "CPU time of the process (one MKL thread, so ≈ the work done) is what the "
             "exponents are fitted to: wall time on the shared machine also measures the other "
             "sessions. Factorisation/solves CPU is the call's CPU split in the wall-time ratio.",
             ""]
    head = ["dofs", *STAGES, "solver", "relres"]
    lines += ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in runs:
        lines.append("| " + " | ".join([str(r["dofs"])]
                                       + [f"{r[s][2]:.2f} ({r[s][0]:.2f})" for s in STAGES]
                                       + [r["solver"], f"{r['relres']:.1e}"]) + " |")
    lines += ["", "| dofs | " + " | ".join(f"{s} MB" for s in STAGES) + " |",
              "|" + "---|" * (len(STAGES) + 1)]
    for r in runs:
        lines.append("| " + " | ".join([str(r["dofs"])]
                                       + [f"{r[s][1] / 2**20:.0f}" for s in STAGES]) + " |")
    lines += ["", "## Fitted exponents (CPU time ∝ dofs^a, memory ∝ dofs^b, meshes ≥ 20k dofs)",
              "", "| stage | a (CPU time) | b (memory) | a (wall, noisy) |", "|---|---|---|---|"]
    for s in STAGES:
        lines.append(f"| {s} | {expo[s][0]:.2f} | {expo[s][1]:.2f} | {expo[s][2]:.2f} |")
    tot = sum(dflt.get(k, 0.0) for k in ("assembly_seconds", "factor_seconds", "solve_seconds",
                                          "recovery_seconds"))
    post = dflt["total_seconds"] - dflt["model_seconds"] - dflt["factor_seconds"] \
        - dflt["solve_seconds"] - dflt["recovery_seconds"]
    share = {"mesh (cache hit)": dflt["mesh_seconds"],
             "assembly + supports + loads": dflt["assembly_seconds"],
             "factorisation": dflt["factor_seconds"], "solves": dflt["solve_seconds"],
             "recovery": dflt["recovery_seconds"],
             "post-processing (stations, peaks, axis line)": post}
    total = dflt["total_seconds"]
    lines += ["", f"## Shares at the default level: x2_57, {dflt['dofs']} dofs, solver "
              f"{dflt['solver']}, warm mesh cache, `solve_static` diagnostics", "",
              "| stage | s | share |", "|---|---|---|"]
    for k, v in share.items():
        lines.append(f"| {k} | {v:.2f} | {v / total:.0%} |")
    lines.append(f"| total | {total:.2f} | 100% |")
    big = max((k for k in share if k not in ("factorisation", "solves")), key=share.get)
    lines += ["", f"Largest stage besides the linear solve at the default level: **{big}** "
              f"({share[big]:.1f} s of {total:.1f} s; the four stages timed in both: "
              f"{tot:.1f} s).", "", "![scaling](scaling.png)", ""]
    (OUT / "scaling.md").write_text("\n".join(lines))
    print(f"wrote {OUT / 'scaling.md'}")


def _plot(runs, expo) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.5))
    x = [r["dofs"] for r in runs]
    for s in STAGES:
        ax[0].loglog(x, [max(r[s][2], 1e-4) for r in runs], "o-",
                     label=f"{s} (a = {expo[s][0]:.2f})")
        ax[1].loglog(x, [max(r[s][1] / 2**20, 0.1) for r in runs], "o-",
                     label=f"{s} (b = {expo[s][1]:.2f})")
    ax[0].set(xlabel="dofs", ylabel="CPU time s (1 MKL thread)", title="time per stage")
    ax[1].set(xlabel="dofs", ylabel="peak RSS increase MB", title="memory per stage")
    for a in ax:
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(OUT / "scaling.png", dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    main()
