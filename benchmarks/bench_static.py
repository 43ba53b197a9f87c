"""3D static FE of variant x2_57: run time against error, per mesh level, element order, solver.

Case: x2_57, spring supports (seed bushing), full mass properties, 10 000 rpm. Quantities: the
peak von Mises stress of the collar fillet (the seed's fatigue hot spot) and of the
bearing-seat-gear fillet (both next to a bearing ring), and the max radial deflection.

Reference: Richardson extrapolation of the two finest P2 runs (levels default and fine, fillet
element size ratio r = k_fillet(default)/k_fillet(fine) = 2; assumed orders p = 2 for the
recovered stress, p = 3 for the displacement): q* = q_fine + (q_fine − q_default)/(r^p − 1).
The errors in the table are relative to q*; the "vs fine" column is relative to the finest run.

Every run is a fresh subprocess (its own time and peak RSS = ``resource.getrusage``
ru_maxrss) with an empty mesh cache, so "mesh" is a real Gmsh build. Wall time is split into
mesh / assembly / factorisation / solves (the Woodbury columns + load) / recovery (nodal
stress, von Mises, principal, exclusion). SuperLU is not run above 200k dofs (FINDINGS: 183 s
at 233k dofs, minutes and GB beyond); AMG-CG is not run (53 s for the 14 right-hand sides at
36k dofs, far slower than any direct factorisation here). PARDISO is run when ``pypardiso``
imports (a private install: the default path never depends on it).

Run: ``python -m benchmarks bench_static`` (~10 min). Writes ``reports/benchmarks/static.md``.
Extra levels for the local-refinement study: ``SHAFTFE_BENCH_EXTRA=1``.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "reports" / "benchmarks" / "static.md"
RPM = 10_000.0
SUPERLU_MAX_DOFS = 200_000

# extra mesh settings (not LEVELS): the default global size with a finer fillet size
EXTRA = {
    "g0.7-f0.45": {"k_global": 0.70, "k_fillet": 0.45, "k_sharp": 5.0, "grad": 1.3},
    "g0.6-f0.45": {"k_global": 0.60, "k_fillet": 0.45, "k_sharp": 4.0, "grad": 1.0},
}

_CHILD = r"""
import json, resource, sys, time
sys.path.insert(0, {root!r})
level, order, solver, cache, extra = {args!r}
from shaftfe.mesh import LEVELS
if extra:
    LEVELS[level] = extra
from shaftfe.static import StaticOptions, solve_static
from shaftfe.variant import load_variant
v = load_variant("x2_57")
t0 = time.perf_counter()
r = solve_static(v, [{rpm!r}], StaticOptions(level=level, order=order, solver=solver),
                 cache_dir=cache, beam=False)
total = time.perf_counter() - t0
c = r.case({rpm!r})
pk = {{p.region: p for p in c.peaks}}
d = r.diagnostics
out = dict(dofs=r.n_dofs, total=total, mesh=d["mesh_seconds"], assembly=d["assembly_seconds"],
           factor=d["factor_seconds"], solve=d["solve_seconds"], recovery=d["recovery_seconds"],
           solver=d["solver"], relres=d["relative_residual"], defl=c.max_deflection_mm,
           collar=pk["fillet:collar"].von_mises_MPa,
           bsg=pk["fillet:bearing_seat_gear"].von_mises_MPa,
           excluded=pk["fillet:collar"].n_excluded + pk["fillet:bearing_seat_gear"].n_excluded,
           rss_MB=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)
print("RESULT" + json.dumps(out))
"""


def _run(level: str, order: int, solver: str, extra: dict | None = None) -> dict | None:
    with tempfile.TemporaryDirectory() as cache:
        code = _CHILD.format(root=str(ROOT), args=(level, order, solver, cache, extra),
                             rpm=RPM)
        p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           timeout=3600, env=os.environ.copy())
    for line in p.stdout.splitlines():
        if line.startswith("RESULT"):
            return json.loads(line[6:])
    print(f"   {level} P{order} {solver}: failed: {p.stderr.strip().splitlines()[-1:]}")
    return None


def richardson(q_fine: float, q_coarse: float, r: float, p: float) -> float:
    return q_fine + (q_fine - q_coarse) / (r ** p - 1.0)


def pareto(rows: list[dict], key: str) -> set[int]:
    """Indices of the rows not dominated in (total time, |error of key|)."""
    out = set()
    for i, a in enumerate(rows):
        dom = any(b["total"] <= a["total"] and abs(b[key]) <= abs(a[key])
                  and (b["total"] < a["total"] or abs(b[key]) < abs(a[key]))
                  for j, b in enumerate(rows) if j != i)
        if not dom:
            out.add(i)
    return out


def main() -> None:
    from shaftfe import solvers
    from shaftfe.mesh import LEVELS
    have = [s for s in ("superlu", "pardiso") if solvers.available()[s]]
    print(f"solvers: {', '.join(have)}; AMG-CG not run (see the module docstring)")
    plan = [(lv, o) for o in (2, 1) for lv in ("coarse", "default", "fine")]
    if os.environ.get("SHAFTFE_BENCH_EXTRA"):
        plan += [(lv, 2) for lv in EXTRA]
    rows = []
    for level, order in plan:
        big = False
        for solver in sorted(have, key=lambda s: s != "pardiso"):   # PARDISO first
            if solver == "superlu" and big:
                print(f"  {level:<11} P{order} superlu: not run (> {SUPERLU_MAX_DOFS} dofs)")
                continue
            r = _run(level, order, solver, EXTRA.get(level))
            if r is None:
                continue
            big = r["dofs"] > SUPERLU_MAX_DOFS
            r.update(level=level, order=order)
            rows.append(r)
            print(f"  {level:<11} P{order} {r['solver']:<8} {r['dofs']:>7} dofs "
                  f"{r['total']:7.1f} s  collar {r['collar']:.1f}  bsg {r['bsg']:.1f} MPa  "
                  f"defl {r['defl']:.5f} mm  RSS {r['rss_MB']:.0f} MB", flush=True)
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.with_suffix(".json").write_text(json.dumps(rows, indent=1))
    write(rows, LEVELS)


def _one(rows, level, order):
    return next((r for r in rows if r["level"] == level and r["order"] == order), None)


def write(rows: list[dict], levels: dict) -> None:
    d, f = _one(rows, "default", 2), _one(rows, "fine", 2)
    if d is None or f is None:
        print("no default/fine P2 runs: no reference, no report")
        return
    rs = levels["default"]["k_fillet"] / levels["fine"]["k_fillet"]
    ref = {k: richardson(f[k], d[k], rs, 2) for k in ("collar", "bsg")}
    ref["defl"] = richardson(f["defl"], d["defl"], rs, 3)
    for r in rows:
        for k in ("collar", "bsg", "defl"):
            r[f"e_{k}"] = r[k] / ref[k] - 1.0
            r[f"ef_{k}"] = r[k] / f[k] - 1.0
        r["e_peak"] = max(abs(r["e_collar"]), abs(r["e_bsg"]))
    front = pareto(rows, "e_peak")
    L = ["# Static FE benchmark: run time against error (x2_57, springs, 10 000 rpm)", "",
         "Generated by `python -m benchmarks bench_static` (benchmarks/bench_static.py). "
         "Machine: 2 cores. Each run is a fresh process with an empty mesh cache.", "",
         "Reference q*: Richardson extrapolation of the P2 default and fine runs "
         f"(fillet element size ratio r = {rs:g}; p = 2 for stress, 3 for deflection): "
         f"collar fillet {ref['collar']:.1f} MPa, bearing-seat-gear fillet {ref['bsg']:.1f} "
         f"MPa, max deflection {ref['defl']:.5f} mm. 'vs fine' = relative to the fine P2 run.",
         "", "| level | P | solver | dofs | total s | mesh | asm | factor | solves | recovery "
         "| RSS MB | collar MPa | err | bsg MPa | err | defl mm | err | Pareto |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for i, r in enumerate(rows):
        L.append(f"| {r['level']} | {r['order']} | {r['solver']} | {r['dofs']} | "
                 f"{r['total']:.1f} | {r['mesh']:.1f} | {r['assembly']:.1f} | "
                 f"{r['factor']:.1f} | {r['solve']:.1f} | {r['recovery']:.1f} | "
                 f"{r['rss_MB']:.0f} | {r['collar']:.1f} | {r['e_collar']:+.1%} | "
                 f"{r['bsg']:.1f} | {r['e_bsg']:+.1%} | {r['defl']:.5f} | "
                 f"{r['e_defl']:+.2%} | {'yes' if i in front else ''} |")
    L += ["", "Pareto = not dominated in (total time, worst of the two fillet-peak errors).", ""]
    L += ["## Findings", ""]
    for r in rows:
        if r["level"] in ("coarse", "default") and r["order"] == 2 and r["solver"] == "pardiso":
            L.append(f"- P2 {r['level']}: worst fillet-peak error {r['e_peak']:.1%} vs q* "
                     f"({r['e_collar']:+.1%} collar, {r['e_bsg']:+.1%} bearing-seat-gear); max "
                     f"deflection {r['e_defl']:+.2%}. The 1 % peak-stress target is "
                     f"{'met' if r['e_peak'] <= 0.01 else 'NOT met'}.")
    fronts = sorted({(rows[i]["level"], rows[i]["order"], rows[i]["solver"]) for i in front})
    L.append("- On the Pareto front: " + ", ".join(f"{lv} P{o} {sv}" for lv, o, sv in fronts)
             + ".")
    L.append("- The two solvers give the same numbers to the printed digits (same mesh); "
             "PARDISO is faster per factorisation, SuperLU is the dependency-free default.")
    L.append("- P1 tets under-predict the fillet peaks by 25-45 % even at the fine level: not "
             "usable for stress (deflection within 2-6 %); P1 is on the front only as the "
             "fastest point.")
    L += ["", "## Recommendation (from the numbers above, 2026-11-21 run)", "",
          "- Keep `default` P2 as the default level: reactions and deflection are converged "
          "(max deflection within 0.1 % of q* at every P2 level) and a cold run takes 9-15 s "
          "(PARDISO / SuperLU; ~4 s of it is Gmsh, cached afterwards).",
          "- Its fillet peaks are 8-9 % below q* (coarse 9-10.5 %): no level meets a 1 % "
          "peak-stress error, and `coarse` does not. The fillet element size decides it: "
          "coarse and default share k_fillet = 0.9 and differ by 1.5 %, the k_fillet = 0.45 "
          "meshes are within 1.4-5 %.",
          "- For fillet peaks (the fatigue hot spot) use `fine` (-2 %, 81 s with PARDISO, "
          "6.6 GB; SuperLU not practical at 595k dofs) or, cheaper, the default global size with "
          "k_fillet = 0.45 (g0.7-f0.45: 272k dofs, 38 s, -3 to -5 %). LEVELS is NOT changed: "
          "the reference itself is uncertain by ~1-2 % (g0.6-f0.45 gives 468.7 MPa on the "
          "bearing-seat-gear fillet, above fine's 464.5: not monotone at that level of detail), "
          "so a 1 % claim cannot be backed; a four-level study with k_fillet 0.3 (~1M dofs) "
          "would be needed first.",
          "- Solver: PARDISO where `pypardiso` is installed (factorisation 1.2 s vs 7.1 s at "
          "94k dofs), SuperLU otherwise; AMG-CG not competitive here.",
          "- Not measured: a coarser local size on the thread-end fillets (ρ = 0.4 mm, 28-40 "
          "MPa). The default is not slow; its error, not its time, is the problem."]
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text("\n".join(L) + "\n")
    print(f"wrote {OUT}")


def rewrite() -> None:
    """Regenerate the markdown from the saved rows (reports/benchmarks/static.json)."""
    from shaftfe.mesh import LEVELS
    write(json.loads(OUT.with_suffix(".json").read_text()), LEVELS)


if __name__ == "__main__":
    main()
