"""DIN 509 undercuts (issue #33).

1. **Kt of an undercut at a shoulder** (``axisymmetric.kt.undercut_bar``: the stepped bar of
   the shoulder table, d over 4 d and D over 4 D, with the undercut in the Ø d at the step,
   drawn as the shaft's outline draws it): tension, bending, torsion, converged by three
   uniform refinements and Richardson (``kt.converged``), nominal stresses on the undercut's
   bottom diameter d − 2 t1. Over a grid of d (12, 17, 25, 40 mm: DIN 509's rows over 10 to 18
   and over 18 to 80 mm) and D/d (1.3, 1.6), forms E and F at the default radius, the other
   radii the table gives for d = 25 (form E), and x2_57's Ø17/Ø22 shoulders. Against DIN 743-2's
   α of a shoulder from d − 2 t1 to D with the undercut's radius: how DIN 743 is applied to an
   undercut when no better Kt is at hand. The converged values go into the table DIN 743 reads
   (``reports/benchmarks/kt_undercuts.json``, ``beam.scf.converged_kt``).
2. **x2_57 with DIN 509 E undercuts** in place of its two 0.6 mm span fillets (the gear-side
   bearing seat's right end, the free bearing seat's left end; the rings reach over them to
   the collar's faces): ``shaftfe static`` (the zoned default) warm, its undercut peaks against
   the fillets' they replace, and the full 3D model (``--model solid``, default level) on the
   same shaft: the undercut peaks of an independent discretisation.
3. **The 3D levels on grooves** against the axisymmetric truth (its peaks converged by three
   refinements and Richardson, ``axisymmetric.kt.converged_peaks``, spin softening on in both):
   x2_57 with the undercuts of part 2, and x2_57 with a U groove in the collar (3 wide, 1 deep,
   corner radius 1: ``bench_grooves``' groove), each at coarse, default and fine.

    python -m benchmarks.bench_undercuts     # writes reports/benchmarks/undercuts.md / .json
    python -m benchmarks.bench_undercuts --shaft    # part 2 only, the Kt table kept
    python -m benchmarks.bench_undercuts --levels   # part 3 only
    python -m benchmarks.bench_undercuts --kt       # part 1 only (and the Kt table)
    python -m benchmarks.bench_undercuts --interp   # part 4 only
    python -m benchmarks.bench_undercuts --interp-again   # part 4's interpolation again, its
                                                          # converged values kept

4. **Interpolating the table** (``beam.scf.undercut_kt``, what DIN 743 takes for an undercut
   the table does not hold): converged Kt (as part 1) at points between the grid's, in both
   DIN 509 rows the grid spans twice in d (R0.6 × 0.2 at d 12 and 17, R0.6 × 0.3 at d 25 and
   40), at D/d 1.22 and 1.45, forms E and F, against the interpolation of the committed table.
"""

from __future__ import annotations

import json
import shutil
import statistics
import sys
import tempfile
from pathlib import Path

from benchmarks._timing import process
from shaftfe.util import paths

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "reports" / "benchmarks" / "undercuts"
KT_TABLE = paths.KT_UNDERCUTS_JSON
# (kind, D, d, radius or None for the default row)
GRID = ([(k, round(d * q, 6), d, None) for k in ("din509_e", "din509_f")
         for d in (12.0, 17.0, 25.0, 40.0) for q in (1.3, 1.6)]
        + [("din509_e", 32.5, 25.0, r) for r in (0.8, 1.0, 1.2)]
        + [(k, 22.0, 17.0, None) for k in ("din509_e", "din509_f")]
        # shallow steps (D/d 1.15; form F's face needs the step above its top: not at d 12)
        + [("din509_e", round(d * 1.15, 6), d, None) for d in (12.0, 17.0, 25.0, 40.0)]
        + [("din509_f", round(d * 1.15, 6), d, None) for d in (17.0, 25.0, 40.0)]
        # the other row of d over 3 (10) to 18: R0.4 × 0.2
        + [(k, round(d * 1.3, 6), d, 0.4) for k in ("din509_e", "din509_f")
           for d in (12.0, 17.0)])
RUNS = 3
# part 4: (kind, d, D/d) between the grid's points
INTERP = [(k, d, q) for k in ("din509_e", "din509_f") for d in (14.5, 32.0)
          for q in (1.22, 1.45)]

SEAT_G = 'name = "bearing_seat_gear"'
COLLAR = 'name = "collar"'
SEAT_F = 'name = "bearing_seat_free"'
UNDERCUT = ('[[shaft.segments.grooves]]\nkind = "din509_e"\nside = "{side}"\n'
            'note = "issue #33 benchmark: a DIN 509 E undercut in place of the fillet"\n\n')


def x2_57_undercuts(where: Path) -> Path:
    """A copy of geometry/ in ``where`` whose x2_57 has DIN 509 E undercuts in place of the
    0.6 mm fillets at x = 47 and 64.5 (their fillet_mm 0); the variant file's path."""
    g = where / "geometry"
    shutil.copytree(ROOT / "geometry", g)
    p = g / "common" / "shaft_c.toml"
    s = p.read_text(encoding="utf-8")
    for name, side in ((SEAT_G, "right"), (COLLAR, None), (SEAT_F, "left")):
        a = s.index(name)
        b = s.index("[[shaft.segments]]", a)
        seg = s[a:b]
        if side != "left":
            assert seg.count("fillet_mm = 0.6") == 1
            seg = seg.replace("fillet_mm = 0.6", "fillet_mm = 0.0")
        if side is not None:
            seg += UNDERCUT.format(side=side)
        s = s[:a] + seg + s[b:]
    p.write_text(s, encoding="utf-8")
    return g / "x2_57.toml"


def kt_grid() -> list[dict]:
    import numpy as np

    from shaftfe.axisymmetric import kt
    from shaftfe.fatigue import din743
    rows = []
    with tempfile.TemporaryDirectory() as cache:
        for kind, D, d, rho in GRID:
            geo, g = kt.undercut_bar(D, d, kind, rho)
            c = kt.converged(D, d, g.rho, cache_dir=cache, shape=kind)
            # the peak is the arc's: the largest value on the rest of the outline (bottom,
            # ramp, wall), on the finest level, relative to it
            bar = kt.solve_bar(D, d, g.rho, refine=2, cache_dir=cache, shape=kind)
            rest = np.nonzero(np.isin(bar.surface.curve, [
                i for i, cv in enumerate(geo.curves) if kt.UNDERCUT in cv.groups
                and cv.center is None]) & ~bar.surface.kink)[0]
            db = 2.0 * g.r_bottom
            for ld in kt.LOADS:
                s1 = kt._principal_over_theta(bar.amplitudes(ld, rest), bar.harmonic[ld])
                al = din743.alpha_shoulder(db, D, g.rho, ld)
                k = c[ld]
                rows.append({"kind": kind, "D_mm": D, "d_mm": d, "rho_mm": g.rho,
                             "t1_mm": g.depth, "t2_mm": g.t2, "load": ld, "kt": k["kt"],
                             "bar": k["error"], "order": k["order"],
                             "second_level_rel": k["values"][1] / k["kt"] - 1.0,
                             "angle_deg": k["angle_deg"],
                             "rest_rel": float(s1.max()) / bar.nominal[ld] / k["values"][2],
                             "din743_alpha": al, "din743_rel": al / k["kt"] - 1.0,
                             "seconds": sum(c["seconds"])})
    return rows


def shaft_runs() -> dict:
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        var = x2_57_undercuts(Path(tmp))
        env = {"SHAFTFE_CACHE_DIR": f"{tmp}/cache", "MPLBACKEND": "Agg"}
        for name, variant, model in (("x2_57 zoned", "x2_57", "zoned"),
                                     ("undercuts zoned", str(var), "zoned"),
                                     ("undercuts solid", str(var), "solid")):
            tag = name.replace(" ", "_")
            cmd = [sys.executable, "-m", "shaftfe", "static", "--variant", variant, "--model",
                   model, "--out", f"{tmp}/{tag}"]
            process(cmd, str(ROOT), env)                 # the cache filled
            runs = [process(cmd, str(ROOT), env) for _ in range(RUNS)]
            s = json.loads(Path(f"{tmp}/{tag}/summary.json").read_text())
            peaks = s.get("peaks") or s.get("cases", [{}])[0].get("peaks", [])
            out[name] = {"warm_s": statistics.median(r["wall_s"] for r in runs),
                         "warm_MiB": max(r["max_rss_MiB"] for r in runs),
                         "von_mises_MPa": {p["region"]: p["von_mises_MPa"] for p in peaks}}
    return out


def solid_levels() -> list[dict]:
    """Part 3: each groove's von Mises and max principal peak per 3D level against the
    converged axisymmetric one."""
    import time

    from benchmarks._shaft_files import x2_57_with
    from benchmarks.bench_grooves import COLLAR_U
    from shaftfe.axisymmetric.kt import converged_peaks
    from shaftfe.model.loader import load_variant
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import solve_static
    rpm = 10_000.0
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        cases = (("undercuts E", x2_57_undercuts(Path(tmp) / "u"),
                  ["groove:bearing_seat_gear:0", "groove:bearing_seat_free:0"]),
                 ("U groove", x2_57_with(Path(tmp) / "g", collar=COLLAR_U),
                  ["groove:collar:0"]))
        for name, path, regions in cases:
            v = load_variant(str(path))
            truth = converged_peaks(v, rpm, regions)
            for lv in ("coarse", "default", "fine"):
                t0 = time.perf_counter()
                res = solve_static(v, [rpm], StaticOptions(level=lv), beam=False,
                                   cache_dir=Path(tmp) / "cache")
                dt = time.perf_counter() - t0
                pk = {p.region: p for p in res.case(rpm).peaks}
                for r in regions:
                    for q, val in (("von_mises", pk[r].von_mises_MPa),
                                   ("max_principal", pk[r].max_principal_MPa)):
                        t = truth[r][q]
                        rows.append({"case": name, "region": r, "quantity": q, "level": lv,
                                     "truth": t["value"], "truth_bar": t["error"],
                                     "solid": float(val), "rel": float(val) / t["value"] - 1,
                                     "dofs": int(res.n_dofs), "seconds": dt})
                        print(rows[-1], flush=True)
    return rows


def interp_check(prev=()) -> list[dict]:
    """Part 4: the converged Kt at ``INTERP`` against ``beam.scf.undercut_kt``'s interpolation
    of the committed table (``prev``: earlier rows whose converged Kt is taken, not solved
    again: ``--interp-again``)."""
    from shaftfe.axisymmetric import kt
    from shaftfe.beam.scf import undercut_kt
    rows = []
    with tempfile.TemporaryDirectory() as cache:
        for kind, d, q in INTERP:
            D = round(d * q, 6)
            _, g = kt.undercut_bar(D, d, kind, None)
            hit = undercut_kt(kind, D, d, g.rho)
            if hit is None:       # outside the measured points (form F: no D/d 1.15 at d 12)
                rows += [{"kind": kind, "D_mm": D, "d_mm": d, "rho_mm": g.rho,
                          "t1_mm": g.depth, "load": ld, "how": "outside"} for ld in kt.LOADS]
                continue
            got, how = hit
            old = {r["load"]: {"kt": r["kt"], "error": r["bar"]} for r in prev
                   if (r["kind"], r["D_mm"], r["d_mm"]) == (kind, D, d) and "kt" in r}
            c = old if len(old) == 3 else kt.converged(D, d, g.rho, cache_dir=cache,
                                                        shape=kind)
            for ld in kt.LOADS:
                rows.append({"kind": kind, "D_mm": D, "d_mm": d, "rho_mm": g.rho,
                             "t1_mm": g.depth, "load": ld, "kt": c[ld]["kt"],
                             "bar": c[ld]["error"], "interpolated": got[ld], "how": how,
                             "rel": got[ld] / c[ld]["kt"] - 1.0})
                print(rows[-1], flush=True)
    return rows


def _angle(a: float) -> str:
    return "off the arc" if a != a else f"{a:.1f}"


def main() -> None:
    if "--kt" in sys.argv:              # part 1 only (the table), parts 2 and 3 kept
        data = json.loads(OUT.with_suffix(".json").read_text(encoding="utf-8"))
        data["kt"] = kt_grid()
        write_table(data["kt"])
        OUT.with_suffix(".json").write_text(json.dumps(data, indent=1) + "\n",
                                            encoding="utf-8")
        render(data)
        return
    if {"--interp", "--interp-again"} & set(sys.argv):     # part 4 only, the rest kept
        data = json.loads(OUT.with_suffix(".json").read_text(encoding="utf-8"))
        data["interp"] = interp_check(data.get("interp", ()) if "--interp-again" in sys.argv
                                      else ())
        OUT.with_suffix(".json").write_text(json.dumps(data, indent=1) + "\n",
                                            encoding="utf-8")
        render(data)
        return
    if {"--render", "--shaft", "--levels"} & set(sys.argv):
        # the page again from the committed numbers (--shaft, --levels: that part measured)
        data = json.loads(OUT.with_suffix(".json").read_text(encoding="utf-8"))
        if "--shaft" in sys.argv:
            data["shaft"] = shaft_runs()
        if "--levels" in sys.argv:
            data["levels"] = solid_levels()
        if {"--shaft", "--levels"} & set(sys.argv):
            OUT.with_suffix(".json").write_text(json.dumps(data, indent=1) + "\n",
                                                encoding="utf-8")
        render(data)
        return
    rows = kt_grid()
    write_table(rows)
    data = {"kt": rows, "shaft": shaft_runs(), "levels": solid_levels(),
            "interp": interp_check()}
    OUT.with_suffix(".json").write_text(json.dumps(data, indent=1) + "\n", encoding="utf-8")
    render(data)


def write_table(rows: list[dict]) -> None:
    """The converged Kt table DIN 743 reads (``beam.scf.converged_kt``)."""
    from benchmarks._shaft_files import write_kt_table
    write_kt_table(KT_TABLE, rows, ("kind", "D_mm", "d_mm", "rho_mm"),
                   "benchmarks/bench_undercuts.py: DIN 509 undercuts at the step of a round "
                   "bar, three refinements + Richardson; nominal stresses on the bottom "
                   "diameter", "undercuts")


def render(data: dict) -> None:
    rows, runs = data["kt"], data["shaft"]
    lines = ["# DIN 509 undercuts: Kt against DIN 743-2, and x2_57 with undercuts", "",
             "(generated by benchmarks/bench_undercuts.py)", "",
             "## 1. Kt of an undercut at the step of a round bar", "",
             "Nominal stresses on the undercut's bottom diameter d − 2 t1. Converged: three "
             "uniform refinements of the harmonic model and Richardson (`axisymmetric.kt."
             "converged`), ± its grid-convergence bar. The outline as `solid.plan` draws it "
             "(`model.grooves`: the geometry's interpretation). The peak is on the corner arc, "
             "at the angle given from the arc's tangent point on the bottom (90° = on the "
             "face); `rest` is the largest value elsewhere on the undercut's outline (bottom, "
             "ramp, wall) over the arc's peak, on the finest level; where it is above 1 the "
             "peak is off the arc and Kt is that value.", "",
             "DIN 743-2's α is that of a shoulder from d − 2 t1 to D with the undercut's "
             "radius: how the standard is applied to an undercut without a better Kt.", "",
             "| form | D/d | d mm | R × t1 (t2) | load | Kt converged | ± bar | second level | "
             "peak at ° | rest | DIN 743 α | DIN 743 vs FE |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        t2 = f" ({r['t2_mm']:g})" if r["t2_mm"] else ""
        lines.append(f"| {r['kind'][-1].upper()} | {r['D_mm'] / r['d_mm']:.3f} | "
                     f"{r['d_mm']:g} | R{r['rho_mm']:g} × {r['t1_mm']:g}{t2} | {r['load']} | "
                     f"{r['kt']:.4f} | {r['bar']:.1e} | {100 * r['second_level_rel']:+.3f} % | "
                     f"{_angle(r['angle_deg'])} | {r['rest_rel']:.3f} | {r['din743_alpha']:.3f} | "
                     f"{100 * r['din743_rel']:+.1f} % |")
    rel = [r["din743_rel"] for r in rows]
    sec = [abs(r["second_level_rel"]) for r in rows]
    off = [r for r in rows if r["angle_deg"] != r["angle_deg"]]
    on = [r for r in rows if r["angle_deg"] == r["angle_deg"]]
    bars = [r["bar"] / r["kt"] for r in on]
    lines += ["", f"- DIN 743-2's shoulder α on the bottom diameter against the converged Kt: "
              f"{100 * min(rel):+.1f} … {100 * max(rel):+.1f} % over the grid: it "
              "underestimates an undercut's notch effect. DIN 743 therefore takes the "
              "converged Kt of this table where it holds the undercut, and the formula "
              "otherwise, with a warning.",
              f"- Peaks on the corner arc ({len(on)} of {len(rows)}): bars ≤ "
              f"{100 * max(bars):.3f} % of Kt; the second level within "
              f"{100 * max(abs(r['second_level_rel']) for r in on):.3f} % of the converged "
              "value.",
              *(f"- Off the arc ({r['kind'][-1].upper()} R{r['rho_mm']:g} × {r['t1_mm']:g}, "
                f"d {r['d_mm']:g}, {r['load']}): the peak sits where the arc meets the bottom; "
                "the largest nodal value there converges without an order (no fit between "
                f"nodes): bar {100 * r['bar'] / r['kt']:.1f} %." for r in off),
              f"- Over all rows the second level lies within {100 * max(sec):.3f} % of the "
              "converged value.", ""]
    p0, pz, ps = (runs[k]["von_mises_MPa"] for k in ("x2_57 zoned", "undercuts zoned",
                                                      "undercuts solid"))
    lines += ["## 2. x2_57 with DIN 509 E undercuts in place of the span fillets", "",
              "Whole processes of `shaftfe static`, warm (median of "
              f"{RUNS} runs, the cache filled by a first run).", "",
              "| run | warm s | warm MiB |", "|---|---|---|"]
    for m, r in runs.items():
        lines.append(f"| {m} | {r['warm_s']:.2f} | {r['warm_MiB']:.0f} |")
    lines += ["", "| shoulder | x2_57: fillet R0.6, von Mises MPa | undercut R0.6 × 0.2, zoned "
              "(axisymmetric) | undercut, full 3D default | 3D / axisymmetric |",
              "|---|---|---|---|---|"]
    for fil, und in (("fillet:bearing_seat_gear", "groove:bearing_seat_gear:0"),
                     ("fillet:collar", "groove:bearing_seat_free:0")):
        a, b, c = (p[k] for p, k in ((p0, fil), (pz, und), (ps, und)))
        lines.append(f"| {fil.split(':')[1]} | {a:.1f} | {b:.1f} ({b / a - 1:+.1%}) | "
                     f"{c:.1f} | {c / b - 1:+.2%} |")
    lines += _levels_lines(data.get("levels", []))
    lines += _interp_lines(data.get("interp", []))
    lines += ["", "The full 3D model sizes a groove's corner arcs as a span fillet's (the hot-spot "
              "field, `solid.mesh`); before that, its default level read the undercuts 15 % "
              "low (0.54 mm elements on a 0.6 mm radius)."]
    (OUT.with_suffix(".md")).write_text("\n".join(lines) + "\n", encoding="utf-8")
    print("\n".join(lines))


def _levels_lines(rows: list[dict]) -> list[str]:
    if not rows:
        return []
    out = ["", "## 3. The 3D levels on grooves against the axisymmetric truth", "",
           "Truth: the axisymmetric model converged over three refinements, Richardson, its "
           "bar; spin softening on in both; 10 000 rpm, bearing springs.", "",
           "| case | groove | quantity | truth MPa | level | 3D dofs | 3D s | 3D MPa | error |",
           "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['case']} | {r['region']} | {r['quantity'].replace('_', ' ')} | "
                   f"{r['truth']:.2f} ± {r['truth_bar']:.2f} | {r['level']} | {r['dofs']} | "
                   f"{r['seconds']:.1f} | {r['solid']:.2f} | {100 * r['rel']:+.2f} % |")
    out.append("")
    for lv in ("coarse", "default", "fine"):
        e = [r["rel"] for r in rows if r["level"] == lv]
        out.append(f"- {lv}: {100 * min(e):+.2f} … {100 * max(e):+.2f} % over these grooves "
                   "(three grooves on one shaft: a measurement, not an error bar for others)")
    return out


def _interp_lines(rows: list[dict]) -> list[str]:
    if not rows:
        return []
    out = ["", "## 4. The table interpolated between its points", "",
           "What DIN 743 takes for an undercut the table does not hold (`beam.scf.undercut_kt`): "
           "at each measured d of the same DIN 509 row the parabola through the three nearest "
           "D/d (linear between two), then linear in d between the two that bracket it; none "
           "outside. Against the converged Kt (as §1) at points between the grid's.", "",
           "| form | d mm | D/d | r × t1 mm | load | Kt converged | ± bar | interpolated | "
           "error |", "|---|---|---|---|---|---|---|---|---|"]
    outside = sorted({(r["kind"][-1].upper(), r["d_mm"], round(r["D_mm"] / r["d_mm"], 2))
                      for r in rows if r["how"] == "outside"})
    rows = [r for r in rows if r["how"] != "outside"]
    for r in rows:
        out.append(f"| {r['kind'][-1].upper()} | {r['d_mm']:g} | {r['D_mm'] / r['d_mm']:.2f} | "
                   f"{r['rho_mm']:g} × {r['t1_mm']:g} | {r['load']} | {r['kt']:.4f} | "
                   f"{r['bar']:.1e} | {r['interpolated']:.4f} | {100 * r['rel']:+.2f} % |")
    e = [100 * r["rel"] for r in rows]
    out += ["", f"Interpolation error {min(e):+.2f} … {max(e):+.2f} % at these "
            f"{len(rows) // 3} points × 3 loads (a measurement between the grid's points; no "
            "bar is claimed beyond them). Negative: the interpolation reads low, so S_D comes "
            "out that much high."]
    if outside:
        out.append("Outside the measured points (no interpolation; DIN 743 takes the formula "
                   "with its warning): " + ", ".join(f"{k} d {d:g} D/d {q:g}"
                                                    for k, d, q in outside) + ".")
    return out


if __name__ == "__main__":
    main()
