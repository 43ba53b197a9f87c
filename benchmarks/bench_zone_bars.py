"""Error bars of the peaks inside the zoned solve's 3D zones (issue #32, deliverable 4: "for
features inside a 3D zone: the full 3D model at ``fine``, and one level finer where it can be
run ... in bending and in torsion"), measured over a grid of keyways and of cross holes.

1. **Keyways with a bottom radius** (``model.examples.keyed_bar``: a bar of diameter d ×
   160 mm, DIN 6885-1's 6 × 3.5 × 16 keyway of shafts over 17 up to 22 mm at x = 80, rigid
   supports, no spin), d and r1/d in ``KEY_GRID`` (b/d 0.333 and 0.273, t1/d 0.194 and
   0.159; r1/d 0.0125 or 0.014 … 0.05), in four-point bending and in torsion: the zoned solve
   at coarse and default against the full 3D model (``--model solid``) at ``fine``. One
   level finer (``finer``: fine's sizes × ``FINER_SCALE``) is run at one point, ``FINER_KEY``
   (Ø22, the largest r1/d); at the smallest r1/d ``fine`` alone has about 1.5 million dofs.
   A sharp keyway (r1 = 0) has no bar: its peak grows with every refinement
   (reports/benchmarks/keyway_edge.md).
2. **Cross holes** (``model.examples.holed_bar``: a Ø20 bar with a transverse hole through
   the axis), d_h/d in ``HOLE_DD``, in tension, four-point bending and torsion: the zoned solve
   at coarse, default and fine against the full 3D model one level finer than ``fine``
   (``finer``), with the full 3D ``fine`` beside it (the reference's own change).

The reference is the issue's: another model (the whole bar in 3D, no cut, no global
axisymmetric model), but the same elements and stress recovery on a finer mesh. So the bar
says how far the zoned solve's zone is from the converged full 3D model: the cut, the global
model and the zone's mesh. It is not an independent check of the 3D elements; those are the
closed forms of tests/validation (Kirsch's hole, Lamé, Saint-Venant) and DIN 743-2's α of a
cross hole (reports/benchmarks/cross_hole.md).

A level's bar is the envelope (min … max) over the grid's points and loads of
100 (zoned − reference) / reference, max principal stress and von Mises, each point's errors
widened by its reference's own change from ``fine`` to ``finer`` where that was run (every
hole; one keyway point: the other keyway points carry no estimate of their reference's own
error, which is likely largest at the smallest r1/d). It applies
(``shaftfe.static.measured_errors.zone_bars``) to a keyway whose (r1/d, b/d) lies in the convex hull
of the measured points and whose t1/b and l/d lie in the measured ranges (one keyway profile,
6 × 3.5 × 16, was measured), or to a cross hole whose d_h/d lies within the measured range,
when every load of the shaft is of one measured kind (bending in the plane through the
feature, as measured; or torsion; or, for a hole, an axial force that stretches its section):
a mix was not measured, nor another bending plane, nor compression. Bending was measured with
the keyway on the tension side; on the compression side its von Mises is the same by
linearity, its max principal stress (then a different point's) was not measured.

    python -m benchmarks.bench_zone_bars [--part keyways|holes] [--write]
        # rows cached in reports/benchmarks/zone_bars.json (a run resumes); --write writes
        # reports/benchmarks/error_bars_zones.json, which shaftfe reads
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

from benchmarks import _jsoncache as jsoncache
from benchmarks import bench_bars_grid as bars_grid
from benchmarks._shaft_files import write_report
from shaftfe.util import paths

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "reports" / "benchmarks" / "zone_bars"
CACHE = OUT.with_suffix(".json")
BARS = paths.ZONE_BARS_JSON
KEY_B, KEY_T1, KEY_L = 6.0, 3.5, 16.0      # mm: model.examples.keyed_bar's keyway
# d (mm; b/d = 6/d, t1/d = 3.5/d) → its r1/d. The smallest r1/d at d = 18 is 0.014, not 0.0125:
# at 0.0125 the full 3D model at fine would have about 1.67 million dofs, above the mesh
# plan's guard (``solid.mesh.KEYWAY_DOFS_MAX``, 1.55 million: about this machine's 24 GiB)
KEY_GRID = {18.0: (0.014, 0.025, 0.05), 22.0: (0.0125, 0.025, 0.05)}
KEY_D = tuple(KEY_GRID)
KEY_LOADS = ("bending", "torsion")
KEY_LEVELS = ("coarse", "default")
FINER_KEY = (22.0, 0.05)               # (d, r1/d) where one level finer than fine fits
HOLE_D = 20.0
HOLE_DD = (0.1, 0.2, 0.3)              # d_h/d
HOLE_LOADS = ("tension", "bending", "torsion")
HOLE_LEVELS = ("coarse", "default", "fine")
FINER_SCALE = 0.7                      # the level finer than fine: its sizes × 0.7
RPM = 1000.0                           # no spin on these bars; the rpm only names the case


def _level(name: str):
    from shaftfe.solid.levels import LEVELS
    return LEVELS["fine"].scaled(FINER_SCALE, "finer") if name == "finer" else LEVELS[name]


def _variant(feature: str, d: float, size: float, load: str):
    from shaftfe.model.examples import holed_bar, keyed_bar
    if feature == "keyway":
        return keyed_bar(load, size, diameter_mm=d)
    return holed_bar(load, size)


def solve_one(feature: str, d: float, size: float, load: str, model: str, level: str,
              cache: str) -> dict:
    """One row: the feature's peak by ``model`` ("zoned" or "solid") at ``level``."""
    import resource
    import time

    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import solve_static
    from shaftfe.zoned.solve import solve_zoned
    v = _variant(feature, d, size, load)
    o = StaticOptions(level=_level(level), rigid_supports=True, spin_softening=False)
    region = "keyway:bar:0" if feature == "keyway" else "cross_hole:bar:0"
    t0 = time.perf_counter()
    if model == "zoned":
        z = solve_zoned(v, RPM, o, cache_dir=cache)
        dofs = sum(zi.n_dofs for zi in z.zones)
        cut = max(max(c.vm_diff_rel, c.sxx_diff_rel) for zi in z.zones for c in zi.cut_checks)
        peaks = z.cases[0].peaks
    else:
        s = solve_static(v, [RPM], o, beam=False, cache_dir=cache)
        dofs, cut, peaks = s.n_dofs, None, s.cases[0].peaks
    secs = time.perf_counter() - t0
    p = {q.region: q for q in peaks}[region]
    return {"dofs": int(dofs), "seconds": secs, "cut_check": cut,
            "peak_MiB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0,
            "von_mises_MPa": p.von_mises_MPa, "max_principal_MPa": p.max_principal_MPa,
            "x_mm": p.xyz_mm[0], "r_mm": math.hypot(*p.xyz_mm[1:])}


def _key(feature, d, size, load, model, level) -> str:
    return f"{feature}|{d:g}|{size:.6g}|{load}|{model}|{level}"


def _plan(part: str) -> list[tuple]:
    rows = []
    if part in ("all", "holes"):
        for dd in HOLE_DD:
            for load in HOLE_LOADS:
                for lv in HOLE_LEVELS:
                    rows.append(("cross_hole", HOLE_D, dd * HOLE_D, load, "zoned", lv))
                rows += [("cross_hole", HOLE_D, dd * HOLE_D, load, "solid", "fine"),
                         ("cross_hole", HOLE_D, dd * HOLE_D, load, "solid", "finer")]
    if part in ("all", "keyways"):
        for d, rds in KEY_GRID.items():
            for rd in rds:
                for load in KEY_LOADS:
                    for lv in KEY_LEVELS:
                        rows.append(("keyway", d, rd * d, load, "zoned", lv))
                    rows.append(("keyway", d, rd * d, load, "solid", "fine"))
                    if (d, rd) == FINER_KEY:
                        rows.append(("keyway", d, rd * d, load, "solid", "finer"))
    return rows


def measure(part: str) -> dict:
    """Run every row of ``part`` not in the cache, each in its own process (its peak memory
    its own; meshes shared through one cache folder), and return the cache."""
    data = jsoncache.load(CACHE)
    with tempfile.TemporaryDirectory() as cache:
        for row in _plan(part):
            k = _key(*row)
            if k in data["points"]:
                continue
            cmd = [sys.executable, "-m", "benchmarks.bench_zone_bars", "--one",
                   json.dumps([*row, cache])]
            out = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
            if out.returncode != 0:
                print(f"{k}: failed\n{out.stderr[-2000:]}", file=sys.stderr)
                continue
            data["points"][k] = json.loads(out.stdout.strip().splitlines()[-1])
            print(k, data["points"][k], flush=True)
            jsoncache.save(CACHE, data)
    return data


def _rows(data: dict) -> list[dict]:
    out = []
    for k, r in data["points"].items():
        feature, d, size, load, model, level = k.split("|")
        out.append({"feature": feature, "d": float(d), "size": float(size), "load": load,
                    "model": model, "level": level, **r})
    return out


def _ref_level(feature: str) -> str:
    return "fine" if feature == "keyway" else "finer"


def _solid(rows: list[dict], level: str) -> dict:
    return {(r["feature"], r["d"], r["size"], r["load"]): r for r in rows
            if r["model"] == "solid" and r["level"] == level}


def reference_change(rows: list[dict]) -> dict:
    """{(feature, d, size, load): %} the full 3D model's own change from ``fine`` to
    ``finer``, max over von Mises and max principal, relative to ``finer``, where both were
    run: the reference's own error, by which a point's errors are widened."""
    fine, finer = _solid(rows, "fine"), _solid(rows, "finer")
    return {k: max(100.0 * abs(fine[k][q] / t[q] - 1.0)
                   for q in ("von_mises_MPa", "max_principal_MPa"))
            for k, t in finer.items() if k in fine}


def errors(rows: list[dict]) -> list[dict]:
    """Each zoned row's % error against its reference row (vm and max principal), and the
    reference's own change where it was measured (``reference_change``, else 0)."""
    fine, finer = _solid(rows, "fine"), _solid(rows, "finer")
    ref = {k: r for k, r in (*fine.items(), *finer.items()) if r["level"] == _ref_level(k[0])}
    change = reference_change(rows)
    out = []
    for r in rows:
        k = (r["feature"], r["d"], r["size"], r["load"])
        t = ref.get(k)
        if r["model"] != "zoned" or t is None:
            continue
        out.append({**r, "err_vm": 100.0 * (r["von_mises_MPa"] / t["von_mises_MPa"] - 1.0),
                    "err_mp": 100.0 * (r["max_principal_MPa"] / t["max_principal_MPa"] - 1.0),
                    "ref_change": change.get(k, 0.0)})
    return out


def bars(rows: list[dict]) -> dict:
    """{feature: {"bars": {"zoned": {level: (lo, hi)}}, "measured": ..., "loads": ...}}."""
    errs = errors(rows)
    out: dict = {}
    for feature, levels, loads in (("keyway", KEY_LEVELS, KEY_LOADS),
                                   ("cross_hole", HOLE_LEVELS, HOLE_LOADS)):
        mine = [e for e in errs if e["feature"] == feature]
        if not mine:
            continue
        by = {}
        for lv in levels:
            es = [(x - e["ref_change"], x + e["ref_change"]) for e in mine if e["level"] == lv
                  for x in (e["err_vm"], e["err_mp"])]
            if es:
                by[lv] = (min(a for a, _ in es), max(b for _, b in es))
        if feature == "keyway":
            measured = sorted({(round(e["size"] / e["d"], 6), round(KEY_B / e["d"], 6))
                               for e in mine})
            ld = [KEY_L / e["d"] for e in mine]
            extra = {"t1_over_b": [round(KEY_T1 / KEY_B, 6)] * 2,
                     "l_over_d": [round(min(ld), 6), round(max(ld), 6)]}
        else:
            measured = sorted({(round(e["size"] / e["d"], 6), 0.0) for e in mine})
            extra = {}
        out[feature] = {"bars": {"zoned": by}, "measured": measured,
                        "loads": [lo for lo in loads if any(e["load"] == lo for e in mine)],
                        "cut_check_max": math.ceil(1e4 * max(e["cut_check"] for e in mine))
                        / 1e4, **extra}
    return out


def _pct(x: float) -> str:
    return f"{x:+.2f} %"


def report(data: dict) -> list[str]:
    rows = _rows(data)
    lines = ["# Error bars of the peaks inside the zoned solve's 3D zones", "",
             "(generated by benchmarks/bench_zone_bars.py; 2-core machine; each row a process "
             "of its own, wall-clock seconds in process, meshes shared between a geometry's "
             "rows)", ""]
    for feature, title, ref in (
            ("keyway", "## 1. Keyways with a bottom radius (6 × 3.5 × 16, DIN 6885-1)",
             "fine"),
            ("cross_hole", f"## 2. Cross holes through a Ø{HOLE_D:g} bar", "finer")):
        mine = [r for r in rows if r["feature"] == feature]
        if not mine:
            continue
        lines += [title, "", f"Reference: the full 3D model at `{ref}`. vs ref: 100 (value − "
                  "reference) / reference.", "",
                  "| d mm | r1 or d_h mm | load | model | level | dofs | s | MiB | von Mises MPa"
                  " | vs ref | max principal MPa | vs ref | at x mm | at r mm | cut check |",
                  "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
        order = {"coarse": 0, "default": 1, "fine": 2, "finer": 3}
        mine.sort(key=lambda r: (r["d"], r["size"], r["load"], r["model"] == "solid",
                                 order[r["level"]]))
        refs = {(r["d"], r["size"], r["load"]): r for r in mine
                if r["model"] == "solid" and r["level"] == ref}
        for r in mine:
            t = refs.get((r["d"], r["size"], r["load"]))
            ev = _pct(100 * (r["von_mises_MPa"] / t["von_mises_MPa"] - 1)) if t else "-"
            ep = _pct(100 * (r["max_principal_MPa"] / t["max_principal_MPa"] - 1)) if t else "-"
            cut = f"{100 * r['cut_check']:.2f} %" if r["cut_check"] is not None else "-"
            lines.append(f"| {r['d']:g} | {r['size']:.4g} | {r['load']} | {r['model']} | "
                         f"{r['level']} | {r['dofs']} | {r['seconds']:.1f} | "
                         f"{r['peak_MiB']:.0f} | {r['von_mises_MPa']:.2f} | {ev} | "
                         f"{r['max_principal_MPa']:.2f} | {ep} | {r['x_mm']:.2f} | "
                         f"{r['r_mm']:.2f} | {cut} |")
        lines.append("")
        change = {k: c for k, c in reference_change(rows).items() if k[0] == feature}
        if change:
            worst = max(change, key=change.get)
            lines += [f"The reference's own change from `fine` to `finer` (fine's sizes × "
                      f"{FINER_SCALE:g}), max of von Mises and max principal: measured at "
                      f"{len(change)} of the grid's {len(refs)} points, at most "
                      f"{change[worst]:.2f} % (d {worst[1]:g}, size {worst[2]:.4g}, "
                      f"{worst[3]}). Each point's errors are widened by it where it was "
                      "measured.", ""]
        b = bars(rows).get(feature)
        if b:
            lines += [f"Bars (the envelope over {len(b['measured'])} geometries and the loads "
                      f"{', '.join(b['loads'])}, von Mises and max principal, each widened by "
                      "its reference's own change where measured):", ""]
            lines += [f"- zoned `{lv}`: {_pct(a)} … {_pct(z)} (rounded outwards, as written)"
                      for lv, (lo, hi) in b["bars"]["zoned"].items()
                      for a, z in [outwards(lo, hi)]]
            lines.append("")
    return lines


def outwards(lo: float, hi: float) -> tuple[float, float]:
    """(lo, hi) rounded outwards to 0.01 % (``bench_bars_grid._outwards``, the shoulders' and
    grooves' rule): the bar written holds every measured error (and a zero is written +0.0)."""
    a, b = bars_grid._outwards([(0.0, lo, hi)])
    return a + 0.0, b + 0.0


def write_bars(data: dict) -> None:
    import datetime
    when = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M UTC")
    b = bars(_rows(data))
    for f in b.values():
        f["bars"] = {m: {lv: list(outwards(lo, hi)) for lv, (lo, hi) in by.items()}
                     for m, by in f["bars"].items()}
        f["measured"] = [list(p) for p in f["measured"]]
    BARS.write_text(json.dumps({"source": f"benchmarks/bench_zone_bars.py on {when}", **b},
                               indent=1) + "\n", encoding="utf-8")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--part", choices=("all", "keyways", "holes"), default="all")
    ap.add_argument("--write", action="store_true")
    ap.add_argument("--one", help=argparse.SUPPRESS)
    a = ap.parse_args(argv if argv is not None else [])
    if a.one:
        feature, d, size, load, model, level, cache = json.loads(a.one)
        print(json.dumps(solve_one(feature, d, size, load, model, level, cache)))
        return
    data = measure(a.part)
    write_report(OUT, report(data))
    if a.write:
        missing = [_key(*r) for r in _plan("all") if _key(*r) not in data["points"]]
        if missing:
            raise SystemExit(f"not written: {len(missing)} rows of the grid are missing "
                             f"(first: {missing[0]}); run again to resume")
        write_bars(data)


if __name__ == "__main__":
    main(sys.argv[1:])
