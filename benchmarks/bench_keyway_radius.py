"""A keyway with a bottom radius (DIN 6885-1's r1, ``bottom_radius_mm``) has a converged peak:
its error per mesh level, and what it costs.

1. The keyed Ø20 bar (``model.examples.keyed_bar``: a 6 × 3.5 × 16 keyway, r1 = 0.25 mm, rigid
   supports, no spin) in four-point bending and in torsion: the full 3D model (``--model
   solid``) at coarse, default and fine, and the zoned solve at coarse and default. The
   reference is the full 3D model at ``fine`` (the issue's, #32). One level finer could not be
   run here: ``fine`` has 1.44 million dofs on this bar and took most of the machine's 24 GiB.
2. x2_57 at 10 000 rpm with r1 = 0.25 mm on both keyways (``--set``): the zoned solve at
   default against the full 3D model at default, every keyway-zone peak; and the cost of the
   radius (the zoned solve of the sharp-edged file beside it, warm).

    python -m benchmarks.bench_keyway_radius [--resume]
        # writes reports/benchmarks/keyway_radius.md / .json; --resume keeps the rows an
        # interrupted run left in keyway_radius.partial.json and runs the rest
"""

from __future__ import annotations

import json
import math
import resource
import sys
import tempfile
import time
from pathlib import Path

from benchmarks._shaft_files import write_report

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "reports" / "benchmarks" / "keyway_radius"
RHO = 0.25                                  # mm, the bar's and x2_57's keyways' r1 here
BAR_RHOS = (RHO, 1.0)                       # the bar's: 1 mm, cheap, is the suite's case
RPM = 10_000.0
X2_SET = {f"segments.{s}.keyways.0.bottom_radius_mm": RHO for s in ("gear_seat", "cw2_seat")}


def _levels():
    from shaftfe.solid.levels import LEVELS
    return {k: LEVELS[k] for k in ("coarse", "default", "fine")}


DONE: list[dict] = []                      # rows of an interrupted run (--resume)


def _done(**key) -> dict | None:
    return next((r for r in DONE if all(r.get(k) == v for k, v in key.items())), None)


def _keep(rows: list[dict], row: dict) -> None:
    """Append a row and write what has been measured so far (a long run leaves its part)."""
    rows.append(row)
    OUT.with_suffix(".partial.json").write_text(json.dumps(rows, indent=1), encoding="utf-8")


def _peak(p) -> dict:
    return {"von_mises_MPa": p.von_mises_MPa, "max_principal_MPa": p.max_principal_MPa,
            "x_mm": p.xyz_mm[0], "r_mm": math.hypot(*p.xyz_mm[1:])}


def _bar(cache: str) -> list[dict]:
    from shaftfe.model.examples import keyed_bar
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import solve_static
    from shaftfe.zoned.solve import solve_zoned
    rows: list[dict] = []
    for rho, (name, lvl) in ((rho, nl) for rho in BAR_RHOS for nl in _levels().items()):
        for kind in ("bending", "torsion"):
            v = keyed_bar(kind, rho)
            o = StaticOptions(level=lvl, rigid_supports=True, spin_softening=False)
            old = _done(rho_mm=rho, load=kind, model="solid", level=name)
            if old is None:
                t0 = time.perf_counter()
                s = solve_static(v, [1000.0], o, beam=False, cache_dir=cache)
                secs = time.perf_counter() - t0
                p = {q.region: q for q in s.cases[0].peaks}["keyway:bar:0"]
                old = {"rho_mm": rho, "load": kind, "model": "solid", "level": name,
                       "dofs": s.n_dofs, "seconds": secs, **_peak(p)}
            _keep(rows, old)
            if name == "fine":
                continue
            old = _done(rho_mm=rho, load=kind, model="zoned", level=name)
            if old is None:
                t0 = time.perf_counter()
                z = solve_zoned(v, 1000.0, o, cache_dir=cache)
                secs = time.perf_counter() - t0
                p = {q.region: q for q in z.cases[0].peaks}["keyway:bar:0"]
                old = {"rho_mm": rho, "load": kind, "model": "zoned", "level": name,
                       "dofs": sum(zi.n_dofs for zi in z.zones), "seconds": secs,
                       "cut_check": max(max(c.vm_diff_rel, c.sxx_diff_rel)
                                        for zi in z.zones for c in zi.cut_checks), **_peak(p)}
            _keep(rows, old)
    return rows


def _x2_57(cache: str) -> list[dict]:
    from shaftfe.model.loader import load_variant
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import solve_static
    from shaftfe.zoned.solve import solve_zoned
    lvl = _levels()["default"]
    out: list[dict] = []
    for label, sets in (("r1 0.25", X2_SET), ("sharp", {})):
        v = load_variant("x2_57", sets)
        for _ in range(2):                  # the second run: warm (meshes and factors cached)
            t0 = time.perf_counter()
            z = solve_zoned(v, RPM, StaticOptions(level=lvl), cache_dir=cache)
            secs = time.perf_counter() - t0
        for p in z.cases[0].peaks:
            if p.model.startswith("zone:"):
                out.append({"keyways": label, "model": "zoned", "level": "default",
                            "region": p.region, "dofs": sum(zi.n_dofs for zi in z.zones),
                            "seconds_warm": secs, **_peak(p)})
    v = load_variant("x2_57", X2_SET)
    t0 = time.perf_counter()
    s = solve_static(v, [RPM], StaticOptions(level=lvl), beam=False, cache_dir=cache)
    secs = time.perf_counter() - t0
    for p in s.cases[0].peaks:
        out.append({"keyways": "r1 0.25", "model": "solid", "level": "default",
                    "region": p.region, "dofs": s.n_dofs, "seconds_cold": secs, **_peak(p)})
    return out


def _pct(a: float, b: float) -> str:
    return f"{100.0 * (a / b - 1.0):+.2f} %"


def _bar_lines(rows: list[dict]) -> list[str]:
    out = ["## 1. The keyed Ø20 bar", "",
           "| r1 mm | load | model | level | dofs | s | von Mises MPa | vs full fine | max "
           "principal MPa | vs full fine | at x mm | at r mm | cut check |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for rho in BAR_RHOS:
        for load in ("bending", "torsion"):
            ref = next(r for r in rows if (r["rho_mm"], r["load"], r["model"], r["level"])
                       == (rho, load, "solid", "fine"))
            for r in rows:
                if (r["rho_mm"], r["load"]) != (rho, load):
                    continue
                cut = f"{100 * r['cut_check']:.2f} %" if "cut_check" in r else "-"
                out.append(f"| {rho:g} | {load} | {r['model']} | {r['level']} | {r['dofs']} | "
                           f"{r['seconds']:.1f} | {r['von_mises_MPa']:.2f} | "
                           f"{_pct(r['von_mises_MPa'], ref['von_mises_MPa'])} | "
                           f"{r['max_principal_MPa']:.2f} | "
                           f"{_pct(r['max_principal_MPa'], ref['max_principal_MPa'])} | "
                           f"{r['x_mm']:.2f} | {r['r_mm']:.2f} | {cut} |")
    out += ["", "r1/d = 0.0125 and 0.05. The slot spans x 72 … 88 mm, its bottom plane at r = "
            "6.5 mm. Nominal stresses on the full section: bending 32 M / (π d³) = 38.20 MPa "
            "(M = 30 000 N mm), torsion 16 T / (π d³) = 31.83 MPa (T = 50 000 N mm).", ""]
    return out


def _x2_lines(rows: list[dict]) -> list[str]:
    zr = [r for r in rows if r["model"] == "zoned" and r["keyways"] == "r1 0.25"]
    sharp = [r for r in rows if r["model"] == "zoned" and r["keyways"] == "sharp"]
    solid = {r["region"]: r for r in rows if r["model"] == "solid"}
    out = ["## 2. x2_57 at 10 000 rpm, r1 = 0.25 mm on both keyways", "",
           f"Zoned at `default`: {zr[0]['dofs']} zone dofs, {zr[0]['seconds_warm']:.1f} s warm "
           f"in process (the sharp-edged file: {sharp[0]['dofs']} dofs, "
           f"{sharp[0]['seconds_warm']:.1f} s). Full 3D at `default`: "
           f"{next(iter(solid.values()))['dofs']} dofs, "
           f"{next(iter(solid.values()))['seconds_cold']:.1f} s with its mesh made. (Full 3D "
           "at `fine` could not be run: on the bar alone it had 1.44 million dofs.)", "",
           "| region | zoned vM MPa | full 3D default | diff | zoned max principal | full 3D "
           "default | diff |", "|---|---|---|---|---|---|---|"]
    for r in zr:
        d = solid.get(r["region"])
        if d is None:
            continue
        out.append(f"| {r['region']} | {r['von_mises_MPa']:.2f} | {d['von_mises_MPa']:.2f} | "
                   f"{_pct(r['von_mises_MPa'], d['von_mises_MPa'])} | "
                   f"{r['max_principal_MPa']:.2f} | {d['max_principal_MPa']:.2f} | "
                   f"{_pct(r['max_principal_MPa'], d['max_principal_MPa'])} |")
    return out


def main() -> None:
    part, whole = OUT.with_suffix(".partial.json"), OUT.with_suffix(".json")
    x2 = None
    if "--resume" in sys.argv[1:]:
        if part.exists():
            DONE.extend(json.loads(part.read_text(encoding="utf-8")))
        elif whole.exists():                # a finished run's rows, x2_57's part kept whole
            old = json.loads(whole.read_text(encoding="utf-8"))
            DONE.extend(old["bar"])
            x2 = old["x2_57"]
        for r in DONE:
            r.setdefault("rho_mm", RHO)     # (rows of the first run, before BAR_RHOS)
    with tempfile.TemporaryDirectory() as cache:
        bar = _bar(cache)
        if x2 is None:
            x2 = _x2_57(cache)
    peak_mib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    memory = (f"peak memory of the run {peak_mib:.0f} MiB" if not DONE else
              "resumed: the rows of the earlier runs kept, and their peak memory not measured")
    OUT.with_suffix(".json").write_text(json.dumps({"bar": bar, "x2_57": x2, "rho_mm": RHO},
                                                   indent=1), encoding="utf-8")
    lines = ["# A keyway with a bottom radius: its converged peak, per level, and its cost",
             "", "(generated by benchmarks/bench_keyway_radius.py; 2-core machine, wall-clock "
             "seconds in process, with an empty cache (each bar row makes its mesh); "
             f"{memory})", "", *_bar_lines(bar), *_x2_lines(x2)]
    write_report(OUT, lines)
    part.unlink(missing_ok=True)


if __name__ == "__main__":
    main()
