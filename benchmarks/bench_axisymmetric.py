"""The axisymmetric harmonic solver: run time against error, the 3D cross-check, and the
reference Kt tables (issue #11).

Writes ``reports/benchmarks/axisymmetric.md`` (every number quoted in the issue note and the
README comes from here) and ``reports/benchmarks/kt_reference.json`` (the converged Kt of every
shoulder fillet of the four variants and of a generic grid, with error bars: the truth the 3D
tests and benchmarks use).

``python -m benchmarks bench_axisymmetric`` (or ``make bench``). Options via the environment:
``AXI_BENCH_GRID=0`` skips the generic grid (about 3 min on 2 cores).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from benchmarks._timing import best_of

OUT = Path("reports/benchmarks")
VARIANTS = ("x2_31", "x2_42", "x2_50", "x2_57")
GRID_DD = (1.1, 1.2, 1.3, 1.5)
GRID_RD = (0.02, 0.05, 0.1, 0.15)


def _timings(lines: list[str]) -> None:
    from shaftfe.axisymmetric.model import AxiOptions
    from shaftfe.axisymmetric.solve import solve_axisymmetric
    from shaftfe.model.loader import load_variant
    v = load_variant("x2_57")
    lines += ["## Run time (x2_57, every rpm from one solve)", "",
              "| level | meridian nodes | harmonics solved | n max | API warm (best of 3) s | "
              "collar fillet vM MPa | error vs converged |", "|---|---|---|---|---|---|---|"]
    conv = _converged_collar(v)
    for lv in ("coarse", "default", "fine"):
        t, res = best_of(lambda lv=lv: solve_axisymmetric(v, [7000, 10000], AxiOptions(lv)), 3)
        pk = {p.region: p for p in res.case(10000).peaks}["fillet:collar"].von_mises_MPa
        lines.append(f"| {lv} | {res.n_nodes} | {len(res.harmonics)} | {res.harmonics[-1]} | "
                     f"{t:.2f} | {pk:.2f} | {pk / conv['value'] - 1:+.2%} |")
    lines += ["", f"Converged collar fillet (n ≤ 1 carries it to < 1e-5, so the series is cut "
              f"at n = 1 here; Richardson over uniform refinements 0, 1, 2 of 'coarse'): "
              f"{conv['value']:.2f} ± {conv['error']:.2f} MPa ({conv['values']}).", ""]
    # whole process, warm and cold cache
    rows = []
    with tempfile.TemporaryDirectory() as cold:
        for label, env in (("cold cache", {"SHAFTFE_CACHE_DIR": cold}),
                           ("warm cache", {"SHAFTFE_CACHE_DIR": cold})):
            t0 = time.perf_counter()
            subprocess.run([sys.executable, "-m", "shaftfe", "static", "--variant", "x2_57",
                            "--model", "axisymmetric", "--out", str(Path(cold) / "o")],
                           check=True, capture_output=True, env={**os.environ, **env})
            rows.append(f"| {label} | {time.perf_counter() - t0:.2f} |")
    lines += ["`shaftfe static --variant x2_57 --model axisymmetric` as a whole process "
              "(Python start, imports, mesh or cache, solve, VTU and summary):", "",
              "| run | wall s |", "|---|---|", *rows, ""]


def _converged_collar(v) -> dict:
    from shaftfe.axisymmetric.kt import richardson
    from shaftfe.axisymmetric.model import AxiOptions
    from shaftfe.axisymmetric.solve import solve_axisymmetric
    vals = []
    for ref in (0, 1, 2):
        res = solve_axisymmetric(v, 10000, AxiOptions("coarse", refine=ref, n_max=1))
        vals.append({p.region: p for p in res.cases[0].peaks}["fillet:collar"].von_mises_MPa)
    out = richardson(vals)
    out["values"] = [round(x, 3) for x in vals]
    return out


def _cross_check(lines: list[str]) -> None:
    from shaftfe.axisymmetric.model import AxiOptions
    from shaftfe.axisymmetric.solve import solve_axisymmetric
    from shaftfe.model.loader import load_variant
    from shaftfe.static.solve import solve_static
    v = load_variant("x2_57")
    a = solve_axisymmetric(v, 10000, AxiOptions("default")).cases[0]
    s = solve_static(v, 10000, beam=False).cases[0]
    lines += ["## 3D (P2 tets, level default) against axisymmetric (default), x2_57, "
              "10 000 rpm", "", "| quantity | 3D | axisymmetric | 3D − axi |", "|---|---|---|---|"]
    for b3, ba in zip(s.bearings, a.bearings, strict=True):
        lines.append(f"| reaction {b3.name} N | {b3.F_radial_N:.2f} | {ba.F_radial_N:.2f} | "
                     f"{b3.F_radial_N / ba.F_radial_N - 1:+.3%} |")
    st3 = {x.name: x for x in s.stations}
    for x in a.stations:
        if x.name in st3:
            lines.append(f"| deflection {x.name} µm | {st3[x.name].u_mm * 1e3:.2f} | "
                         f"{x.u_mm * 1e3:.2f} | {st3[x.name].u_mm / x.u_mm - 1:+.3%} |")
    p3 = {p.region: p for p in s.peaks}
    for p in a.peaks:
        if p.region.startswith("fillet:") and p.region in p3:
            zone = f" (in the zone of {p.omitted_zone})" if p.omitted_zone else ""
            lines.append(f"| {p.region} vM MPa{zone} | {p3[p.region].von_mises_MPa:.2f} | "
                         f"{p.von_mises_MPa:.2f} | "
                         f"{p3[p.region].von_mises_MPa / p.von_mises_MPa - 1:+.2%} |")
    lines.append("")


def _kt_tables(lines: list[str], grid: bool) -> dict:
    from shaftfe.axisymmetric.kt import converged
    from shaftfe.model.loader import load_variant
    from shaftfe.solid.plan import prepare
    table = {"source": "shaftfe.axisymmetric.kt.converged, 3 uniform refinements, Richardson",
             "nominal": "on d: 4P/(πd²), 32M/(πd³), 16T/(πd³); Kt = max principal / nominal",
             "fillets": [], "grid": []}
    seen = {}
    lines += ["## Converged Kt of the variants' shoulder fillets", "",
              "| variant | fillet | D mm | d mm | ρ mm | Kt tension | Kt bending | Kt torsion | "
              "peak on the arc (bending) ° | time s |", "|---|---|---|---|---|---|---|---|---|---|"]
    for name in VARIANTS:
        sol = prepare(load_variant(name))
        for f in sol.fillets:
            key = (round(2 * f.r_large, 6), round(2 * f.r_small, 6), round(f.rho, 6))
            t0 = time.perf_counter()
            if key not in seen:
                seen[key] = converged(*key)
            r = seen[key]
            dt = time.perf_counter() - t0
            row = {"variant": name, "fillet": f.segment, "D_mm": key[0], "d_mm": key[1],
                   "rho_mm": key[2], **{ld: r[ld] for ld in ("tension", "bending", "torsion")}}
            table["fillets"].append(row)
            lines.append(f"| {name} | {f.segment} | {key[0]:g} | {key[1]:g} | {key[2]:g} | "
                         + " | ".join(f"{r[ld]['kt']:.4f} ± {r[ld]['error']:.1e}"
                                      for ld in ("tension", "bending", "torsion"))
                         + f" | {r['bending']['angle_deg']:.1f} | {dt:.1f} |")
    lines += ["", "(Variants have no grooves; a repeated fillet geometry is computed once: "
              "its time then reads 0.)", ""]
    if grid:
        lines += ["## Generic shoulders (d = 1)", "", "| D/d | r/d | Kt tension | Kt bending | "
                  "Kt torsion | Peterson bending | nodes (finest) | time s |",
                  "|---|---|---|---|---|---|---|---|"]
        from shaftfe.beam.scf import kt_shoulder_bending
        for dd in GRID_DD:
            for rd in GRID_RD:
                if rd > 0.5 * (dd - 1) + 1e-12:
                    continue                      # the fillet would exceed the step
                t0 = time.perf_counter()
                r = converged(dd, 1.0, rd)
                dt = time.perf_counter() - t0
                pet = float(kt_shoulder_bending(dd, 1.0, rd, "peterson")[0])
                table["grid"].append({"D_over_d": dd, "r_over_d": rd,
                                      **{ld: r[ld] for ld in ("tension", "bending",
                                                              "torsion")}})
                lines.append(f"| {dd:g} | {rd:g} | " + " | ".join(
                    f"{r[ld]['kt']:.4f} ± {r[ld]['error']:.1e}"
                    for ld in ("tension", "bending", "torsion"))
                    + f" | {pet:.3f} | {r['nodes'][-1]} | {dt:.1f} |")
        lines.append("")
    return table


def main() -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    lines = ["# Axisymmetric harmonic solver (generated by benchmarks/bench_axisymmetric.py)",
             "", "2-core machine; times are wall-clock seconds.", ""]
    _timings(lines)
    _cross_check(lines)
    table = _kt_tables(lines, grid=os.environ.get("AXI_BENCH_GRID", "1") != "0")
    (OUT / "axisymmetric.md").write_text("\n".join(lines) + "\n")
    (OUT / "kt_reference.json").write_text(json.dumps(table, indent=1) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
