"""3D static FE of variant x2_57: run time against error, per mesh level, element order, solver.

Case: x2_57, spring supports (seed bushing), full mass properties, 10 000 rpm. Quantities: the
peak von Mises stress of the collar fillet (the seed's fatigue hot spot) and of the
bearing-seat-gear fillet (both next to a bearing ring), and the max radial deflection.

Reference (a separate refinement study, not the levels themselves): the far field is held
fixed (k_global 0.6, rings and end fillets 0.9 ρ) and ONLY the hot sectors of the two fillets
inside the bearing span are refined (``shaftfe.solid.mesh`` hot-spot field, sector ±20°, plateau
0.4 ρ, grading 0.5; ``REF_BASE``) with k_fillet = 0.3, 0.2, 0.133 (ratio r = 1.5). If
the three values are monotone with a shrinking step: observed order
p = ln((q2 − q1)/(q3 − q2)) / ln r, q* = q3 + (q3 − q2)/(r^p − 1), uncertainty = the spread
between that and the p = 2 extrapolation. Otherwise (the mesh noise of an unstructured mesh
is reached) q* = the mean of the two finest values ± half their difference. Errors in the
table are relative to q*.

Every run is a fresh subprocess (its own time and peak RSS = ``resource.getrusage``
ru_maxrss) with an empty mesh cache, so "mesh" is a real Gmsh build; ``default`` is run a
second time on the cache it wrote ("cached" rows: mesh loaded from disk). Wall time is split
into mesh / assembly / factorisation / solves (the Woodbury columns + load) / recovery (nodal
stress, von Mises, principal, exclusion). SuperLU is not run above 200k dofs (FINDINGS: 183 s
at 233k dofs); AMG-CG is not run (53 s for the 14 right-hand sides at 36k dofs, far slower
than any direct factorisation here). PARDISO is run when ``pypardiso`` imports (the optional
extra ``fast``: the default path never depends on it). The machine is shared: the 1-minute
load average is recorded before and after each run.

Run: ``python -m benchmarks bench_static`` (~15 min on an idle machine). Writes
``reports/benchmarks/static.md``, ``static.json`` (a list of run rows; the report module
reads it) and ``static_reference.json`` (the reference study). ``SHAFTFE_BENCH_NOREF=1`` skips the
k = 0.133 reference run (then the reference is taken from the saved JSON if present).
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "reports" / "benchmarks" / "static.md"          # + static.json: the rows
REF_OUT = ROOT / "reports" / "benchmarks" / "static_reference.json"
RPM = 10_000.0
SUPERLU_MAX_DOFS = 200_000
R_REF = 1.5

_CHILD = r"""
import json, os, resource, sys, time
sys.path.insert(0, {root!r})
level, order, solver, cache, extra = {args!r}
from shaftfe.solid.levels import MeshLevel
if extra:
    level = MeshLevel(level, **extra)
load0 = os.getloadavg()[0]
from shaftfe.static.model import StaticOptions
from shaftfe.static.solve import solve_static
from shaftfe.model.loader import load_variant
v = load_variant("x2_57")
t0 = time.perf_counter()
r = solve_static(v, [{rpm!r}], StaticOptions(level=level, order=order, solver=solver),
                 cache_dir=cache, beam=False)
total = time.perf_counter() - t0
c = r.case({rpm!r})
pk = {{p.region: p for p in c.peaks}}
d = r.diagnostics
t = r.run
out = dict(dofs=r.n_dofs, total=total, mesh=t["mesh_seconds"], assembly=t["assembly_seconds"],
           factor=t["factor_seconds"], solve=t["solve_seconds"], recovery=t["recovery_seconds"],
           cached=bool(t["mesh_from_cache"]), solver=d["solver"], relres=d["relative_residual"],
           defl=c.max_deflection_mm, collar=pk["fillet:collar"].von_mises_MPa,
           bsg=pk["fillet:bearing_seat_gear"].von_mises_MPa,
           collar_xyz=pk["fillet:collar"].xyz_mm,
           end_fillets=max(pk["fillet:thread_m10"].von_mises_MPa,
                           pk["fillet:cw2_seat"].von_mises_MPa),
           min_quality=d["min_quality"],
           rss_MB=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
           load=[load0, os.getloadavg()[0]])
print("RESULT" + json.dumps(out))
"""


REF_BASE = {"k_global": 0.60, "k_ring": 0.9, "k_fillet_end": 0.9, "k_sharp": 4.0, "grad": 1.0,
            "grad_hot": 0.5, "d_hot": 0.4, "sector_deg": 20.0}
REF_K = (0.3, 0.2, 0.133)


def ref_settings(k: float) -> dict:
    """The reference family: far field fixed, hot sectors refined (see the module docstring)."""
    return dict(REF_BASE, k_fillet=k)


def _run(level: str, order: int, solver: str, extra: dict | None = None,
         cache: str | None = None) -> dict | None:
    with tempfile.TemporaryDirectory() as tmp:
        code = _CHILD.format(root=str(ROOT), args=(level, order, solver, cache or tmp, extra),
                             rpm=RPM)
        p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           timeout=3600, env=os.environ.copy())
    for line in p.stdout.splitlines():
        if line.startswith("RESULT"):
            return json.loads(line[6:])
    print(f"   {level} P{order} {solver}: failed: {p.stderr.strip().splitlines()[-1:]}")
    return None


def richardson3(q1: float, q2: float, q3: float, r: float) -> dict:
    """Three-level Richardson extrapolation with the observed order (see the docstring).

    If the last step is not smaller than the one before and of the same sign (the sequence is
    not in the asymptotic range, or has reached the mesh noise), no extrapolation is made:
    q* = the mean of the two finest values, uncertainty = half their difference
    (``method`` says which)."""
    d1, d2 = q2 - q1, q3 - q2
    out = {"values": [q1, q2, q3], "monotone": d1 * d2 > 0 and abs(d2) < abs(d1)}
    q2nd = q3 + d2 / (r ** 2 - 1.0)
    if out["monotone"]:
        p = math.log(d1 / d2) / math.log(r)
        qp = q3 + d2 / (r ** p - 1.0)
        out.update(order=p, extrapolated=qp, extrapolated_p2=q2nd, uncertainty=abs(qp - q2nd),
                   method="richardson")
    else:
        out.update(order=float("nan"), extrapolated=0.5 * (q2 + q3), extrapolated_p2=q2nd,
                   uncertainty=0.5 * abs(d2), method="plateau")
    return out


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


def _show(r: dict) -> None:
    print(f"  {r['level']:<9} P{r['order']} {r['solver']:<8}{' cached' if r['cached'] else ''}"
          f" {r['dofs']:>7} dofs {r['total']:7.1f} s  collar {r['collar']:.1f}  bsg "
          f"{r['bsg']:.1f} MPa  defl {r['defl']:.5f} mm  RSS {r['rss_MB']:.0f} MB  load "
          f"{r['load'][0]:.1f}/{r['load'][1]:.1f}", flush=True)


def main() -> None:
    from shaftfe.fe import solvers
    have = [s for s in ("pardiso", "superlu") if solvers.available()[s]]
    print(f"solvers: {', '.join(have)}; AMG-CG not run (see the module docstring)")
    rows: list[dict] = []
    plan = [(lv, 2) for lv in ("coarse", "default", "fine")] + \
        [(lv, 1) for lv in ("coarse", "default")]
    only = os.environ.get("SHAFTFE_BENCH_ONLY")        # e.g. "coarse,default": rerun these,
    if only:                                          # keep the other saved rows
        keep = set(only.split(","))
        plan = [(lv, o) for lv, o in plan if lv in keep]
        rows = [r for r in _load_rows(OUT.with_suffix(".json")) if r["level"] not in keep]
    for level, order in plan:
        big = False
        for solver in have:                                     # PARDISO first
            if solver == "superlu" and big:
                print(f"  {level:<9} P{order} superlu: not run (> {SUPERLU_MAX_DOFS} dofs)")
                continue
            with tempfile.TemporaryDirectory() as cache:
                runs = [_run(level, order, solver, cache=cache)]
                if level == "default" and order == 2:
                    runs.append(_run(level, order, solver, cache=cache))   # mesh cached
            for r in runs:
                if r is None:
                    continue
                big = r["dofs"] > SUPERLU_MAX_DOFS
                r.update(level=level, order=order)
                rows.append(r)
                _show(r)
    # reference family
    for k in REF_K:
        name = f"ref-k{k:g}"
        if (k < 0.2 and os.environ.get("SHAFTFE_BENCH_NOREF")) or only:
            continue
        r = _run(name, 2, have[0], ref_settings(k))
        if r is not None:
            r.update(level=name, order=2)
            rows.append(r)
            _show(r)
    if os.environ.get("SHAFTFE_BENCH_NOREF") and not only and OUT.with_suffix(".json").exists():
        rows += [r for r in _load_rows(OUT.with_suffix(".json")) if r["level"] == "ref-k0.133"]
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.with_suffix(".json").write_text(json.dumps(rows, indent=1))
    write(rows)


def _load_rows(path: Path) -> list[dict]:
    """Rows of a saved benchmark JSON: a list of rows, or {"rows": [...]}."""
    data = json.loads(path.read_text())
    return data["rows"] if isinstance(data, dict) else data


def _one(rows, level, order=2, cached=False):
    return next((r for r in rows if r["level"] == level and r["order"] == order
                 and r["cached"] == cached), None)


def write(rows: list[dict]) -> None:
    from shaftfe.solid.levels import LEVELS
    series = [_one(rows, f"ref-k{k:g}") for k in REF_K]
    if any(s is None for s in series):
        print("reference series incomplete: no report")
        return
    ref = {k: richardson3(*(s[k] for s in series), R_REF) for k in ("collar", "bsg", "defl")}
    q = {k: v["extrapolated"] for k, v in ref.items()}
    for r in rows:
        for k in ("collar", "bsg", "defl"):
            r[f"e_{k}"] = r[k] / q[k] - 1.0
        r["e_peak"] = max(abs(r["e_collar"]), abs(r["e_bsg"]))
    OUT.with_suffix(".json").write_text(json.dumps(rows, indent=1))        # a list of rows
    REF_OUT.write_text(json.dumps({"reference": ref, "ref_base": REF_BASE, "ref_k": REF_K,
                                   "levels": {k: lv.settings() for k, lv in LEVELS.items()}},
                              indent=1))
    main_rows = [r for r in rows if not r["level"].startswith("ref-")]
    front = pareto(main_rows, "e_peak")

    def rs(k):
        v = ref[k]
        vals = " / ".join(f"{x:.5g}" for x in v["values"])
        if v["method"] == "richardson":
            return (f"{vals} → observed order {v['order']:.2f}, q* = {v['extrapolated']:.5g} "
                    f"(p = 2: {v['extrapolated_p2']:.5g}; uncertainty "
                    f"±{v['uncertainty']:.2g})")
        return (f"{vals} → the last step reverses or does not shrink (mesh noise reached): "
                f"q* = mean of the two finest = {v['extrapolated']:.5g} ± "
                f"{v['uncertainty']:.2g} (no extrapolation)")
    L = ["# Static FE benchmark: run time against error (x2_57, springs, 10 000 rpm)", "",
         "Generated by `python -m benchmarks bench_static` (benchmarks/bench_static.py). "
         "Machine: 2 cores, shared with other jobs: `load` is the 1-minute load average "
         "before/after each run (a load above 2 inflates every time). Each run is a fresh "
         "process with an empty mesh cache, except the rows marked cached.", "",
         "## Reference", "",
         "Far field fixed, only the hot sectors of the two span fillets refined, k_fillet = "
         "0.3 / 0.2 / 0.133 (ratio 1.5), three-level Richardson with the observed order:", "",
         f"- collar fillet (MPa): {rs('collar')}",
         f"- bearing-seat-gear fillet (MPa): {rs('bsg')}",
         f"- max deflection (mm): {rs('defl')}", "",
         "Independent checks of the recovery behind these numbers: Goodier's spherical cavity "
         "(tests/validation/test_static_recovery_goodier.py, +0.3…0.5 % at h = 0.05…0.1 a) "
         "and the stepped-shaft fillet against the Roark/Peterson Kt fits "
         "(tests/validation/test_static_fillet.py).", "",
         "## Runs", "",
         "| level | P | solver | dofs | total s | mesh | asm | factor | solves | recovery "
         "| RSS MB | load | collar MPa | err | bsg MPa | err | defl mm | err | Pareto |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        i = next((j for j, m in enumerate(main_rows) if m is r), None)
        name = r["level"] + (" (cached)" if r["cached"] else "")
        L.append(f"| {name} | {r['order']} | {r['solver']} | {r['dofs']} | "
                 f"{r['total']:.1f} | {r['mesh']:.1f} | {r['assembly']:.1f} | "
                 f"{r['factor']:.1f} | {r['solve']:.1f} | {r['recovery']:.1f} | "
                 f"{r['rss_MB']:.0f} | {r['load'][0]:.1f}/{r['load'][1]:.1f} | "
                 f"{r['collar']:.1f} | {r['e_collar']:+.1%} | {r['bsg']:.1f} | "
                 f"{r['e_bsg']:+.1%} | {r['defl']:.5f} | {r['e_defl']:+.2%} | "
                 f"{'yes' if i in front else ''} |")
    L += ["", "Pareto = not dominated in (total time, worst of the two fillet-peak errors); the "
          "reference runs are not candidates.", "", "## Levels (shaftfe.solid.levels.LEVELS)", ""]
    for lv, cfg in LEVELS.items():
        L.append(f"- `{lv}`: " + ", ".join(f"{k} {v:g}" for k, v in cfg.items()))
    L += ["", "## Findings", ""]
    for r in main_rows:
        if r["order"] == 2 and not r["cached"] and r["solver"] == rows[0]["solver"]:
            L.append(f"- P2 {r['level']}: {r['dofs']} dofs, worst fillet-peak error "
                     f"{r['e_peak']:.1%} ({r['e_collar']:+.1%} collar, {r['e_bsg']:+.1%} "
                     f"bearing-seat-gear); max deflection {r['e_defl']:+.2%}; {r['total']:.1f} s "
                     f"cold at load {r['load'][0]:.1f}. 1 % target "
                     f"{'met' if r['e_peak'] <= 0.01 else 'NOT met'}.")
    for r in main_rows:
        if r["level"] == "default" and r["order"] == 2 and r["cached"]:
            L.append(f"- P2 default, mesh cached, {r['solver']}: {r['total']:.1f} s "
                     f"(load {r['load'][0]:.1f}); peak RSS {r['rss_MB']:.0f} MB.")
    fronts = sorted({(main_rows[i]["level"], main_rows[i]["order"], main_rows[i]["solver"])
                     for i in front})
    L.append("- On the Pareto front: " + ", ".join(f"{lv} P{o} {sv}" for lv, o, sv in fronts)
             + ".")
    L.append("- P1 tets under-predict the fillet peaks by tens of percent: not usable for "
             "stress; deflection within a few percent.")
    for r in rows:
        if r.get("note"):
            L.append(f"- {r['level']}: {r['note']}.")
    L += ["", "## Why these levels", "",
          "- The peak fillet stress depends on the element size AT the hot spot: with the far "
          "field fixed, refining only the hot sectors moves the collar peak 484 (k_fillet "
          "0.45, an exploratory run) → 501 → 505 → 504 MPa (0.3 → 0.133), while the "
          "deflection does not move in the 5th "
          "digit. The old levels refined the whole ring of every fillet at 0.9 ρ (default "
          "-8 to -9 % at 94k dofs): the hot-spot field buys 16x less error for 1.8x the dofs.",
          "- The plateau depth and the grading matter as much as k_fillet: k_fillet 0.3 with a "
          "0.25 ρ plateau and slope 1.0 gave -2.5 % (90-102k dofs), with 0.4 ρ and 0.5 it gives "
          "-0.5 % (the default). Sectors of ±10° suffice (the peak sits within 2° of the load "
          "plane); ±20° is kept for the reference.",
          "- `default` is the cheapest setting measured that meets the 1 % error target; "
          "`coarse` is the fast preview (≈ -4 %), `fine` is reference-grade (≤ 0.4 %).",
          "- Fillet rings and end fillets stay at 0.9 ρ: at 1.2-1.5 ρ one nearly flat curved "
          "tet gave a spurious 699 MPa peak on a ring and an end fillet's area was 0.7 % off.",
          "- Not met on this machine: 5 s cold / 2 s cached / 1.5 GB for `default` (see the "
          "rows: the factorisation and assembly of 170k dofs alone exceed 2 s; SuperLU needs "
          "2.6 GB)."]
    OUT.write_text("\n".join(L) + "\n")
    print(f"wrote {OUT}")


def rewrite(extra: str | None = None) -> None:
    """Regenerate the markdown from the saved rows (reports/benchmarks/static.json), adding the
    rows of another JSON file of the same form (e.g. a separately run reference level)."""
    rows = _load_rows(OUT.with_suffix(".json"))
    if extra:
        rows += _load_rows(Path(extra))
    write(rows)


if __name__ == "__main__":
    main()
