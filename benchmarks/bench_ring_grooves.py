"""DIN 471 retaining-ring grooves and U grooves: converged Kt against the published charts
(issue #33, deliverable 4).

1. **Kt of a DIN 471 ring groove** (``axisymmetric.kt.ring_groove_bar``: a round bar of the
   groove's shaft diameter D, 8 D long, the groove at its middle with DIN 471's width m and depth
   t for D, flat-bottomed, its two corners of radius ρ; the outline the shaft's), tension,
   bending, torsion, converged by three uniform refinements and Richardson
   (``kt.converged``), nominal stresses on the groove's bottom diameter. Over DIN 471's rows
   at the default corner radius 0.1 mm (D 10 … 40; rows from 20 mm are reconstructed, see
   ``model.grooves``) and the larger radii a drawing may give (0.2, 0.3 mm at D 17 and 30).
   Against the published chart fits that bracket a flat-bottomed groove: from below a
   shoulder fillet of the same step and radius (one corner alone: Roark 7th ed. Table 17.1
   cases 17a–17c, ``beam.scf.kt_shoulder``), from above a U-notch of the groove's depth and
   corner radius (the narrowest groove of that radius: Roark's cases 6a–6c,
   ``beam.scf.kt_u_notch``); and DIN 743-2's round-groove α ("Rundnut",
   ``fatigue.din743.alpha_groove``). The converged values go into the table the beam reads
   for a DIN 471 groove (``reports/benchmarks/kt_ring_grooves.json``,
   ``beam.scf.converged_kt``).
2. **Roark's U-notch fit and DIN 743-2's α on the U grooves** of
   ``reports/benchmarks/kt_grooves.json`` (``bench_grooves``' converged table, read, not
   re-solved).

3. **The 3D model on a DIN 471 groove**: x2_57 with ``bench_grooves``' groove on the gear hub
   boss (Ø17, corner radius 0.1), ``solve_static`` (the full 3D model) at each level against
   the axisymmetric model's converged peak (three refinements, Richardson): what the 3D mesh
   reads where it cannot resolve the corner (``solid.mesh.unresolved_grooves``, the warning
   ``groove-unresolved``).

    python -m benchmarks.bench_ring_grooves   # writes reports/benchmarks/ring_grooves.md / .json
    python -m benchmarks.bench_ring_grooves --report   # the page again from the .json
    python -m benchmarks.bench_ring_grooves --solid    # part 3 only, the rest kept
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

from benchmarks._shaft_files import write_kt_table, write_report
from shaftfe.util import paths

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "reports" / "benchmarks" / "ring_grooves"
U_TABLE = paths.KT_GROOVES_JSON
KT_TABLE = paths.KT_RING_GROOVES_JSON
# (D, corner radius): DIN 471's rows at the default 0.1 mm, and larger radii at D 17 and 30
GRID = ([(D, 0.1) for D in (10.0, 12.0, 15.0, 17.0, 20.0, 25.0, 30.0, 35.0, 40.0)]
        + [(D, r) for D in (17.0, 30.0) for r in (0.2, 0.3)])


def _fits(D: float, d: float, rho: float, load: str) -> tuple[float, float, bool]:
    """(Roark's U-notch Kt, DIN 743-2's α, Roark in its h/r range) for depth (D − d)/2."""
    from shaftfe.beam.scf import kt_u_notch
    from shaftfe.fatigue import din743
    r = kt_u_notch(D, 0.5 * (D - d), rho, load)
    return r.kt, din743.alpha_groove(d, D, rho, load), r.in_range


def ring_grid() -> list[dict]:
    from shaftfe.axisymmetric import kt
    from shaftfe.model.grooves import din471
    rows = []
    with tempfile.TemporaryDirectory() as cache:
        for D, rho in GRID:
            m, t = din471(D)
            d = D - 2.0 * t
            c = kt.converged(D, d, rho, cache_dir=cache, shape="din471")
            for ld in kt.LOADS:
                k = c[ld]
                roark, alpha, ok = _fits(D, d, rho, ld)
                rows.append({"D_mm": D, "d_mm": d, "m_mm": m, "t_mm": t, "rho_mm": rho,
                             "load": ld, "kt": k["kt"], "bar": k["error"], "order": k["order"],
                             "second_level_rel": k["values"][1] / k["kt"] - 1.0,
                             "roark": roark, "roark_rel": roark / k["kt"] - 1.0,
                             "roark_in_range": ok, "din743_alpha": alpha,
                             "din743_rel": alpha / k["kt"] - 1.0,
                             "nodes": c["nodes"][-1], "seconds": sum(c["seconds"])})
    return rows


def u_rows() -> list[dict]:
    rows = []
    for g in json.loads(U_TABLE.read_text(encoding="utf-8"))["grooves"]:
        D, d, rho = g["D_mm"], g["d_mm"], g["rho_mm"]
        for ld in ("tension", "bending", "torsion"):
            roark, alpha, ok = _fits(D, d, rho, ld)
            k = g[ld]["kt"]
            rows.append({"D_mm": D, "d_mm": d, "rho_mm": rho, "load": ld, "kt": k,
                         "bar": g[ld]["bar"], "roark_rel": roark / k - 1.0,
                         "roark_in_range": ok, "din743_rel": alpha / k - 1.0})
    return rows


def _span(rows, key) -> str:
    v = [100 * r[key] for r in rows]
    return f"{min(v):+.1f} … {max(v):+.1f} %"


def shoulder_rel(r: dict) -> float:
    """Roark's shoulder fit (one corner alone) of the groove's step and radius against the
    converged Kt."""
    from shaftfe.beam.scf import kt_shoulder
    return kt_shoulder(r["D_mm"], r["d_mm"], r["rho_mm"], "roark", r["load"]).kt / r["kt"] - 1


def solid_runs() -> list[dict]:
    """Part 3: the groove's von Mises and max principal peak per 3D level against the
    axisymmetric model converged."""
    import time

    from benchmarks._shaft_files import x2_57_with
    from benchmarks.bench_grooves import BOSS_471
    from shaftfe.axisymmetric.kt import converged_peaks
    from shaftfe.model.loader import load_variant
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import solve_static
    rpm, region = 10_000.0, "groove:gear_hub_boss:0"
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        v = load_variant(str(x2_57_with(Path(tmp), boss=BOSS_471)))
        truth = converged_peaks(v, rpm, [region])[region]
        for lv in ("coarse", "default"):
            t0 = time.perf_counter()
            res = solve_static(v, [rpm], StaticOptions(level=lv), beam=False,
                               cache_dir=Path(tmp) / "cache")
            dt = time.perf_counter() - t0
            pk = {p.region: p for p in res.case(rpm).peaks}[region]
            for q, val in (("von_mises", pk.von_mises_MPa),
                           ("max_principal", pk.max_principal_MPa)):
                rows.append({"level": lv, "quantity": q, "truth": truth[q]["value"],
                             "truth_bar": truth[q]["error"], "solid": float(val),
                             "rel": float(val) / truth[q]["value"] - 1.0,
                             "dofs": int(res.n_dofs), "seconds": dt})
                print(rows[-1], flush=True)
    return rows


def main(argv: list[str]) -> None:
    old = (json.loads(OUT.with_suffix(".json").read_text(encoding="utf-8"))
           if OUT.with_suffix(".json").exists() else {})
    if "--report" in argv or "--solid" in argv:
        ring = old["ring"]
    else:
        ring = ring_grid()
    solid = solid_runs() if "--solid" in argv or "--report" not in argv else old.get("solid", [])
    u = u_rows()
    for r in ring:
        r["shoulder_rel"] = shoulder_rel(r)
    write_kt_table(KT_TABLE, ring, ("D_mm", "d_mm", "m_mm", "rho_mm"),
                   "benchmarks/bench_ring_grooves.py: DIN 471 grooves in a round bar, three "
                   "refinements + Richardson; nominal stresses on the groove's bottom diameter",
                   "ring_grooves")
    lines = ["# Ring grooves (DIN 471) and U grooves: converged Kt against Roark's and DIN 743's "
             "fits", "", "(generated by benchmarks/bench_ring_grooves.py)", "",
             "## 1. DIN 471 ring grooves", "",
             "A round bar of the shaft's diameter D with the groove (width m, depth t from DIN "
             "471's row for D; flat bottom; corner radius ρ). Converged: three uniform "
             "refinements of the harmonic model and Richardson (`axisymmetric.kt.converged`), "
             "± its grid-convergence bar; nominal stresses on d = D − 2t. The fits take the "
             "groove as a U-notch of depth t and radius ρ: Roark 7th ed. Table 17.1 cases "
             "6a–6c (the beam's Kt, `beam.scf.kt_u_notch`; its range 0.25 ≤ t/ρ ≤ 50) and "
             "DIN 743-2's α of a round groove; and from below the shoulder of the same step "
             "and radius (one corner alone; Roark's cases 17a–17c). Rows from D 20 mm use "
             "DIN 471 dimensions that are reconstructed (`model.grooves`).", "",
             "| D mm | m × t mm | ρ mm | load | Kt converged | ± bar | second level | "
             "Roark shoulder vs FE | Roark U-notch vs FE | DIN 743 α vs FE | nodes (finest) "
             "| s |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in ring:
        lines.append(f"| {r['D_mm']:g} | {r['m_mm']:g} × {r['t_mm']:.3g} | {r['rho_mm']:g} | "
                     f"{r['load']} | {r['kt']:.4f} | {r['bar']:.1e} | "
                     f"{100 * r['second_level_rel']:+.3f} % | {100 * r['shoulder_rel']:+.1f} % | "
                     f"{100 * r['roark_rel']:+.1f} %"
                     f"{'' if r['roark_in_range'] else ' (out of range)'} | "
                     f"{100 * r['din743_rel']:+.1f} % | {r['nodes']} | {r['seconds']:.1f} |")
    bars = [r["bar"] / r["kt"] for r in ring]
    inside = all(r["shoulder_rel"] < 0 < r["roark_rel"] for r in ring)
    lines += ["", f"Over the {len(GRID)} grooves × 3 loads: Roark's shoulder fit "
              f"{_span(ring, 'shoulder_rel')}, its U-notch fit {_span(ring, 'roark_rel')}, "
              f"DIN 743-2's α {_span(ring, 'din743_rel')} from the "
              f"converged Kt; the converged bars ≤ {100 * max(bars):.3f} % of Kt; the second "
              f"level within {100 * max(abs(r['second_level_rel']) for r in ring):.3f} %. "
              + ("Every converged Kt lies between the shoulder's and the U-notch's fits."
                 if inside else "NOT every converged Kt lies between the shoulder's and the "
                 "U-notch's fits."), "",
              "## 2. U grooves (the converged table of bench_grooves)", "",
              "| D mm | d mm | ρ mm | load | Kt converged | Roark U-notch vs FE | "
              "DIN 743 α vs FE |", "|---|---|---|---|---|---|---|"]
    for r in u:
        lines.append(f"| {r['D_mm']:g} | {r['d_mm']:g} | {r['rho_mm']:.3g} | {r['load']} | "
                     f"{r['kt']:.4f} | {100 * r['roark_rel']:+.1f} % | "
                     f"{100 * r['din743_rel']:+.1f} % |")
    lines += ["", f"Roark's U-notch fit {_span(u, 'roark_rel')}, DIN 743-2's α "
              f"{_span(u, 'din743_rel')} from the converged Kt of the U grooves."]
    if solid:
        lines += ["", "## 3. The full 3D model on a DIN 471 groove", "",
                  "x2_57 with a DIN 471 groove on the gear hub boss (Ø17, m 1.1, t 0.4, corner "
                  "radius 0.1), 10 000 rpm, bearing springs, spin softening: `solve_static` "
                  "against the axisymmetric model converged (three refinements, Richardson). "
                  "The 3D levels do not resolve a 0.1 mm corner (`solid.mesh."
                  "unresolved_grooves`; the run warns `groove-unresolved`).", "",
                  "| level | quantity | axisymmetric converged MPa | 3D MPa | error | 3D dofs | "
                  "3D s |", "|---|---|---|---|---|---|---|"]
        for r in solid:
            lines.append(f"| {r['level']} | {r['quantity'].replace('_', ' ')} | "
                         f"{r['truth']:.2f} ± {r['truth_bar']:.2f} | {r['solid']:.2f} | "
                         f"{100 * r['rel']:+.1f} % | {r['dofs']} | {r['seconds']:.1f} |")
    write_report(OUT, lines, {"ring": ring, "u": u, "solid": solid})


if __name__ == "__main__":
    main(sys.argv[1:])
