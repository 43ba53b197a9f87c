"""Transverse (cross) holes (issue #33).

1. **Kt of a cross hole** in a Ø20 bar (``model.examples.holed_bar``: a Ø4 hole, d_h/d = 0.2),
   tension, four-point bending and torsion, by the zoned solve (the hole in a 3D zone) at the
   three mesh levels, against DIN 743-2's α (a fit of Peterson's charts); the zone's dofs and
   the solve's time (a warm mesh cache).
2. **x2_57 with a cross hole and a ring groove**: a Ø3 hole through the gear hub boss
   (x = 22, at 90°) and a DIN 471 groove in the collar (Ø22, x = 60): whole processes of
   ``shaftfe static`` (the zoned default) cold and warm (median of 3), peak memory, the zones'
   dofs and the two notches' peaks.

    python -m benchmarks.bench_cross_hole     # writes reports/benchmarks/cross_hole.md / .json
"""

from __future__ import annotations

import json
import math
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

from benchmarks._timing import process

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "reports" / "benchmarks" / "cross_hole"
LEVELS = ("coarse", "default", "fine")
LOADS = ("tension", "bending", "torsion")
RUNS = 3
D, DH = 20.0, 4.0

HOLE = ('[[shaft.segments.cross_holes]]\ndiameter_mm = 3.0\nx_center_mm = 22.0\n'
        'angle_deg = 90.0\nreconstructed = ["diameter_mm", "x_center_mm", "angle_deg"]\n'
        'note = "issue #33 benchmark: an oil hole through the gear hub boss"\n\n')
RING = ('[[shaft.segments.grooves]]\nkind = "din471"\nx_center_mm = 60.0\n'
        'reconstructed = ["x_center_mm"]\n'
        'note = "issue #33 benchmark: a DIN 471 ring groove in the collar"\n')


def holed_geometry(where: Path) -> Path:
    """A copy of geometry/ whose x2_57 has the hole and the ring groove; the variant's path."""
    g = where / "geometry"
    shutil.copytree(ROOT / "geometry", g)
    p = g / "common" / "shaft_c.toml"
    s = p.read_text(encoding="utf-8")
    end = 'spot (§8.3)."""\n'
    assert s.count(end) == 1
    s = s.replace(end, end + RING)
    i = s.index('name = "gear_hub_boss"')
    j = s.index("[[shaft.segments]]", i)
    p.write_text(s[:j] + HOLE + s[j:], encoding="utf-8")
    return g / "x2_57.toml"


def kt_rows() -> list[dict]:
    from shaftfe.fatigue import din743 as din
    from shaftfe.model.examples import HOLED_BAR_F_N, HOLED_BAR_P_N, HOLED_BAR_T_NMM, holed_bar
    from shaftfe.static.model import StaticOptions
    from shaftfe.zoned.solve import solve_zoned
    n = din.Notch("hole", "cross_hole", D, D, 0.5 * DH, hole_mm=DH)
    scale = dict(zip(LOADS, din.net_section_scale(n), strict=True))
    full = {"tension": HOLED_BAR_P_N / (math.pi * D * D / 4),
            "bending": HOLED_BAR_F_N * 30.0 / (math.pi * D ** 3 / 32),
            "torsion": HOLED_BAR_T_NMM / (math.pi * D ** 3 / 16)}
    rows = []
    with tempfile.TemporaryDirectory() as cache:
        for load in LOADS:
            for level in LEVELS:
                o = StaticOptions(level=level, spin_softening=False)
                solve_zoned(holed_bar(load), 1000.0, o, cache_dir=cache)    # meshes made
                t0 = time.perf_counter()
                z = solve_zoned(holed_bar(load), 1000.0, o, cache_dir=cache)
                secs = time.perf_counter() - t0
                p = {q.region: q for q in z.cases[0].peaks}["cross_hole:bar:0"]
                kt = p.max_principal_MPa / (full[load] * scale[load]) / (
                    2.0 if load == "torsion" else 1.0)
                al = din.alpha_cross_hole(D, DH, load)
                rows.append({"load": load, "level": level, "kt": kt, "din743_alpha": al,
                             "rel": kt / al - 1.0, "zone_dofs": sum(zi.n_dofs for zi in z.zones),
                             "seconds": secs, "xyz_mm": list(p.max_principal_xyz_mm)})
    return rows


def shaft_runs() -> dict:
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        var = holed_geometry(Path(tmp))
        cmd = [sys.executable, "-m", "shaftfe", "static", "--variant", str(var), "--out",
               f"{tmp}/zoned"]
        env = {"SHAFTFE_CACHE_DIR": f"{tmp}/cache", "MPLBACKEND": "Agg"}
        cold = process(cmd, str(ROOT), env)
        runs = [process(cmd, str(ROOT), env) for _ in range(RUNS)]
        s = json.loads(Path(f"{tmp}/zoned/summary.json").read_text())
        out = {"cold_s": cold["wall_s"], "cold_MiB": cold["max_rss_MiB"],
               "warm_s": statistics.median(r["wall_s"] for r in runs),
               "warm_MiB": max(r["max_rss_MiB"] for r in runs),
               "zones": [{"name": z["name"], "x_mm": z["x_mm"], "n_dofs": z["n_dofs"]}
                         for z in s["zones"]],
               "peaks": {p["region"]: {"von_mises_MPa": p["von_mises_MPa"],
                                       "max_principal_MPa": p["max_principal_MPa"],
                                       "model": p.get("model", "")}
                         for p in s["cases"][0]["peaks"]
                         if p["region"].startswith(("cross_hole:", "groove:"))},
               "warnings": s["warnings"]}
    return out


def main() -> None:
    rows = kt_rows()
    shaft = shaft_runs()
    OUT.with_suffix(".json").write_text(json.dumps({"kt": rows, "shaft": shaft}, indent=1)
                                        + "\n", encoding="utf-8")
    lines = ["# Cross holes: Kt against DIN 743-2, and a shaft with a hole and a ring groove", "",
             "(generated by benchmarks/bench_cross_hole.py)", "",
             f"## 1. A Ø{DH:g} hole through a Ø{D:g} bar (d_h/d = {DH / D:g}), the zoned solve",
             "", "Kt = σ1,max / σ_nom on the net section (torsion: τ_max = σ1/2 at the free "
             "hole edge, over τ_nom); DIN 743-2:2012's α of a transverse hole, a fit of "
             "Peterson's charts; time: the zoned solve with its meshes cached.", "",
             "| load | level | Kt | DIN 743 α | Kt vs α | zone dofs | s | peak at (x, y, z) mm |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        x, y, z = r["xyz_mm"]
        lines.append(f"| {r['load']} | {r['level']} | {r['kt']:.4f} | {r['din743_alpha']:.4f} | "
                     f"{100 * r['rel']:+.1f} % | {r['zone_dofs']} | {r['seconds']:.2f} | "
                     f"({x:.2f}, {y:.2f}, {z:.2f}) |")
    lines += ["", "## 2. x2_57 with a Ø3 cross hole (gear hub boss, x = 22) and a DIN 471 "
              "groove (collar, x = 60)", "",
              "Whole processes of `shaftfe static --variant <x2_57 + hole + groove>` (the zoned "
              f"default); cold: an empty cache; warm: the median of {RUNS} runs.", "",
              "| cold s | cold MiB | warm s | warm MiB |", "|---|---|---|---|",
              f"| {shaft['cold_s']:.2f} | {shaft['cold_MiB']:.0f} | {shaft['warm_s']:.2f} | "
              f"{shaft['warm_MiB']:.0f} |", "",
              "zones: " + "; ".join(f"{z['name']} x {z['x_mm'][0]:g} … {z['x_mm'][1]:g} mm, "
                                    f"{z['n_dofs']} dofs" for z in shaft["zones"]), "",
              "| notch | von Mises MPa | max principal MPa | from |", "|---|---|---|---|"]
    for reg, p in sorted(shaft["peaks"].items()):
        lines.append(f"| {reg} | {p['von_mises_MPa']:.2f} | {p['max_principal_MPa']:.2f} | "
                     f"{p['model']} |")
    if shaft["warnings"]:
        lines += ["", "warnings: " + "; ".join(str(w) for w in shaft["warnings"])]
    OUT.with_suffix(".md").write_text("\n".join(lines) + "\n", encoding="utf-8")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
