"""Circumferential grooves (issue #33).

1. **Kt of a U groove** (``axisymmetric.kt.grooved_bar``, tension, bending, torsion): converged
   by three uniform refinements and Richardson (``kt.converged``), over a grid of grooves in a
   Ø20 bar (d/D 0.8 and 0.9, ρ/t 0.25, 0.5, 1), against DIN 743-2's α ("Rundnut", table 2);
   with the second level's distance to the converged value (the level the validation test
   runs: tests/validation/test_grooves.py).
2. **x2_57 with two grooves**: a U groove in the collar (x = 55.75, 3 wide, 1 deep, corner radius
   1: a 1 mm flat bottom)
   and a DIN 471 ring groove on the gear hub boss (Ø17, x = 27; m 1.1, t 0.4, corner radius
   0.1): whole processes of ``shaftfe static`` (the zoned default) cold (an empty cache) and
   warm (median of 3), peak memory, the groove peaks against ``--model axisymmetric``, and the
   3D zones' dofs.

    python -m benchmarks.bench_grooves     # writes reports/benchmarks/grooves.md / .json
"""

from __future__ import annotations

import json
import statistics
import sys
import tempfile
from pathlib import Path

from benchmarks._shaft_files import write_report, x2_57_with
from benchmarks._timing import process

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "reports" / "benchmarks" / "grooves"
D_BAR = 20.0
# d/D 0.8 and 0.9 (depth t = 2 and 1 mm), ρ/t 0.25, 0.5, 1 (1: the bottom one semicircle)
GRID = [(D_BAR, D_BAR * q, 0.5 * D_BAR * (1 - q) * k) for q in (0.8, 0.9)
        for k in (0.25, 0.5, 1.0)]
# the converged Kt of these grooves go into the table DIN 743 reads (fatigue.standards.
# converged_kt, as the shoulders' kt_reference.json; one-arc grooves only, width 2ρ): the grid
# and a groove of the collar's D, d and ρ
KT_TABLE = ROOT / "reports" / "benchmarks" / "kt_grooves.json"
SHAFT_GROOVES = [(22.0, 20.0, 1.0)]
RUNS = 3

COLLAR_U = ('[[shaft.segments.grooves]]\nkind = "u"\nx_center_mm = 55.75\nwidth_mm = 3.0\n'
            'depth_mm = 1.0\nreconstructed = ["x_center_mm", "width_mm", "depth_mm"]\n'
            'note = "issue #33 benchmark: a U groove in the collar"\n')
BOSS_471 = ('[[shaft.segments.grooves]]\nkind = "din471"\nx_center_mm = 27.0\n'
            'reconstructed = ["x_center_mm"]\n'
            'note = "issue #33 benchmark: a DIN 471 ring groove on the gear hub boss"\n\n')


def kt_grid() -> list[dict]:
    from shaftfe.axisymmetric import kt
    from shaftfe.fatigue import din743
    rows = []
    with tempfile.TemporaryDirectory() as cache:
        for D, d, rho in GRID + SHAFT_GROOVES:
            c = kt.converged(D, d, rho, cache_dir=cache, shape="groove")
            for ld in kt.LOADS:
                al = din743.alpha_groove(d, D, rho, ld)
                k = c[ld]
                rows.append({"D_mm": D, "d_mm": d, "rho_mm": rho, "load": ld, "kt": k["kt"],
                             "bar": k["error"], "order": k["order"],
                             "second_level_rel": k["values"][1] / k["kt"] - 1.0,
                             "angle_deg": k["angle_deg"], "din743_alpha": al,
                             "din743_rel": al / k["kt"] - 1.0, "seconds": sum(c["seconds"])})
    return rows


def shaft_runs() -> dict:
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        var = x2_57_with(Path(tmp), collar=COLLAR_U, boss=BOSS_471)
        for model in ("zoned", "axisymmetric"):
            cmd = [sys.executable, "-m", "shaftfe", "static", "--variant", str(var), "--model",
                   model, "--out", f"{tmp}/{model}"]
            env = {"SHAFTFE_CACHE_DIR": f"{tmp}/cache", "MPLBACKEND": "Agg"}
            cold = process(cmd, str(ROOT), env)
            runs = [process(cmd, str(ROOT), env) for _ in range(RUNS)]
            s = json.loads(Path(f"{tmp}/{model}/summary.json").read_text())
            out[model] = {"cold_s": cold["wall_s"], "cold_MiB": cold["max_rss_MiB"],
                          "warm_s": statistics.median(r["wall_s"] for r in runs),
                          "warm_MiB": max(r["max_rss_MiB"] for r in runs), "summary": s}
    return out


def _peaks(summary: dict) -> dict:
    """region -> (von Mises, max principal, x, source) from a static summary.json."""
    rows = summary.get("peaks") or summary.get("cases", [{}])[0].get("peaks", [])
    return {p["region"]: p for p in rows}


def main() -> None:
    rows = kt_grid()
    table: dict = {}
    for r in rows:
        key = (r["D_mm"], r["d_mm"], r["rho_mm"])
        table.setdefault(key, {"D_mm": r["D_mm"], "d_mm": r["d_mm"], "rho_mm": r["rho_mm"]})
        table[key][r["load"]] = {"kt": r["kt"], "bar": r["bar"]}
    KT_TABLE.write_text(json.dumps({"source": "benchmarks/bench_grooves.py: U grooves in a "
                                    "round bar, three refinements + Richardson",
                                    "grooves": list(table.values())}, indent=1) + "\n",
                        encoding="utf-8")
    runs = shaft_runs()
    OUT.with_suffix(".json").write_text(json.dumps({"kt": rows, "shaft": {
        m: {k: v for k, v in r.items() if k != "summary"} for m, r in runs.items()}},
        indent=1), encoding="utf-8")
    lines = ["# Circumferential grooves: Kt against DIN 743-2, and a shaft with two grooves", "",
             "(generated by benchmarks/bench_grooves.py)", "",
             "## 1. Kt of a U groove in a round bar, nominal stress on d", "",
             "The grid in a Ø20 bar, and the collar groove of part 2 (Ø22).", "",
             "Converged: three uniform refinements of the harmonic model, Richardson "
             "(`axisymmetric.kt.converged`); ± its grid-convergence bar. DIN 743-2:2012 "
             "table 2 (\"Rundnut\"): a Neuber-type fit, the independent reference here.", "",
             "| D mm | d/D | ρ/d | load | Kt converged | ± bar | second level vs converged | "
             "DIN 743 α | DIN 743 vs FE | peak at ° (90 = bottom) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['D_mm']:g} | {r['d_mm'] / r['D_mm']:.2f} | "
                     f"{r['rho_mm'] / r['d_mm']:.3f} | "
                     f"{r['load']} | {r['kt']:.4f} | {r['bar']:.1e} | "
                     f"{100 * r['second_level_rel']:+.3f} % | {r['din743_alpha']:.3f} | "
                     f"{100 * r['din743_rel']:+.1f} % | {r['angle_deg']:.1f} |")
    rel = [r["din743_rel"] for r in rows]
    sec = [abs(r["second_level_rel"]) for r in rows]
    lines += ["", f"DIN 743-2's α against the converged Kt: {100 * min(rel):+.1f} … "
              f"{100 * max(rel):+.1f} % over the grid; the second mesh level within "
              f"{100 * max(sec):.3f} % of the converged value.", ""]
    z, a = runs["zoned"], runs["axisymmetric"]
    pz, pa = _peaks(z["summary"]), _peaks(a["summary"])
    lines += ["## 2. x2_57 with a U groove (collar) and a DIN 471 groove (gear hub boss)", "",
              "Whole processes of `shaftfe static --variant <x2_57 + grooves>`; cold: an empty "
              f"cache; warm: the median of {RUNS} runs.", "",
              "| model | cold s | cold MiB | warm s | warm MiB |", "|---|---|---|---|---|"]
    for m, r in runs.items():
        lines.append(f"| {m} | {r['cold_s']:.2f} | {r['cold_MiB']:.0f} | {r['warm_s']:.2f} | "
                     f"{r['warm_MiB']:.0f} |")
    zones = z["summary"].get("zones", [])
    if zones:
        lines += ["", "zones: " + "; ".join(
            f"{zi.get('name')} {zi.get('n_dofs')} dofs" for zi in zones)]
    lines += ["", "| groove | zoned: von Mises MPa (source) | axisymmetric: von Mises MPa | "
              "zoned / axisymmetric |", "|---|---|---|---|"]
    for g in sorted(k for k in pa if k.startswith("groove:")):
        vz, va = pz[g]["von_mises_MPa"], pa[g]["von_mises_MPa"]
        lines.append(f"| {g} | {vz:.2f} ({pz[g].get('model', '')}) | {va:.2f} | "
                     f"{vz / va - 1:+.1%} |")
    lines += ["", "A groove is the axisymmetric model's in every case: inside a keyway's 3D zone "
              "the zone meshes it only for its geometry (no smaller than its depth), and "
              "its peak and fatigue field come from the global model, which meshes its "
              "radius; the run warns (`groove-in-zone`) that the keyway's own field at "
              "the groove is left out."]
    write_report(OUT, lines)


if __name__ == "__main__":
    main()
