"""Issue #32: the zoned static solve against the full 3D model, and its speed side by side with
the tree before it (``python benchmarks/bench_zoned.py``; ~6 min on 2 cores; the speed part needs
``SHAFTFE_BASELINE``, a checkout of the tree before the change, else it is left out;
``SHAFTFE_BASELINE_LABEL`` names it in the tables, default "baseline, its default").

Accuracy (in process, x2_57 at 10 000 rpm, all parts, bearing springs, spin softening):
``shaftfe static``'s zoned solve at the default level against the full 3D model at ``default``
and at ``fine`` (``--model solid``): the bearing reactions and the axis deflections at the
stations (the keyways' and the hex socket's effect on the stiffness, which the global model
leaves out), every region's peak (von Mises and max principal) with the model it comes from,
the zones (extent, cuts, dofs, the cut checks, the peaks' change when the cut moves one gap
outward, the time of each phase). Then a keyed Ø20 bar between two cuts in bending and in
torsion (``model.examples.keyed_bar``) at every level against the full 3D model at
the same level and at ``fine``.

Speed (whole processes, ``_timing.process``): ``shaftfe static --variant x2_57`` of this tree
(the zoned solve) and of the baseline (its default, the full 3D model), warm (after one
warm-up, the median of ``RUNS``, A and B in turn) and cold (an empty cache), wall time and peak
memory; and this tree's ``--model solid`` for the same comparison in one tree.

Writes ``reports/benchmarks/zoned.md`` and ``zoned.json``.
"""

from __future__ import annotations

import json
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

from benchmarks._timing import process

RUNS = 7       # warm runs of each command, in turn: this 2-core machine drifts by ±20 % within
               # minutes, so 3 rounds could invert a 15 % difference (measured: 2.02 s against
               # 1.81 s, where a separate run of 10 pairs gave a median ratio of 0.83)
RPM = 10_000.0
HERE = Path(__file__).resolve().parents[1]
OUT = HERE / "reports" / "benchmarks"


def _peaks(case) -> dict:
    return {p.region: (p.von_mises_MPa, p.max_principal_MPa) for p in case.peaks}


def accuracy() -> dict:
    from shaftfe.model.loader import load_variant
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import solve_static
    from shaftfe.zoned.solve import solve_zoned
    v = load_variant("x2_57")
    t = time.perf_counter()
    z = solve_zoned(v, RPM, StaticOptions(), sensitivity=True)
    tz = time.perf_counter() - t
    full = {}
    for lvl in ("default", "fine"):
        t = time.perf_counter()
        s = solve_static(v, [RPM], StaticOptions(level=lvl), beam=False)
        full[lvl] = {"seconds": time.perf_counter() - t, "dofs": s.n_dofs,
                     "peaks": _peaks(s.cases[0]),
                     "bearings": {b.name: (b.Fy_N, b.Fz_N, b.F_radial_N)
                                  for b in s.cases[0].bearings},
                     "stations": {st.name: st.u_mm for st in s.cases[0].stations}}
    zc = z.cases[0]
    return {
        "zoned": {"seconds": tz, "run": z.run,
                  "peaks": {p.region: (p.von_mises_MPa, p.max_principal_MPa, p.model, p.kind)
                            for p in zc.peaks},
                  "bearings": {b.name: (b.Fy_N, b.Fz_N, b.F_radial_N) for b in zc.bearings},
                  "stations": {st.name: st.u_mm for st in zc.stations},
                  "zones": [{"name": q.name, "features": q.features, "x_mm": q.x_mm,
                             "cuts_mm": q.cuts_mm, "nominal_mm": q.nominal_mm,
                             "grown": q.grown, "dofs": q.n_dofs,
                             "cut_checks": [(c.group, c.x_mm, c.vm_diff_rel, c.sxx_diff_rel)
                                            for c in q.cut_checks],
                             "sensitivity": q.sensitivity, "seconds": q.seconds}
                            for q in z.zones],
                  "global": {"nodes": z.global_result.n_nodes,
                             "harmonics": list(z.global_result.harmonics)}},
        "full": full,
        "keyed_bar": keyed_bar_rows(),
    }


def keyed_bar_rows() -> list[dict]:
    from shaftfe.model.examples import keyed_bar
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import solve_static
    from shaftfe.zoned.solve import solve_zoned
    rows = []
    for kind in ("bending", "torsion"):
        v = keyed_bar(kind)
        ref = {}
        for lvl in ("coarse", "default", "fine"):
            o = StaticOptions(level=lvl, rigid_supports=True, spin_softening=False)
            t = time.perf_counter()
            s = solve_static(v, [1000.0], o, beam=False)
            ts = time.perf_counter() - t
            ref[lvl] = (_peaks(s.cases[0])["keyway:bar:0"][0], ts, s.n_dofs)
        for lvl in ("coarse", "default", "fine"):
            o = StaticOptions(level=lvl, rigid_supports=True, spin_softening=False)
            t = time.perf_counter()
            z = solve_zoned(v, 1000.0, o)
            tz = time.perf_counter() - t
            zp = _peaks(z.cases[0])["keyway:bar:0"][0]
            rows.append({"load": kind, "level": lvl, "zoned_MPa": zp, "zoned_s": tz,
                         "zone_dofs": z.zones[0].n_dofs,
                         "cut_check": max(max(c.vm_diff_rel, c.sxx_diff_rel)
                                          for c in z.zones[0].cut_checks),
                         "solid_same_MPa": ref[lvl][0], "solid_same_s": ref[lvl][1],
                         "solid_dofs": ref[lvl][2], "solid_fine_MPa": ref["fine"][0]})
    return rows


def _shaftfe(tree: str, *args: str) -> list[str]:
    """``shaftfe ARGS`` run from the package of ``tree``."""
    return ["env", f"PYTHONPATH={tree}", "MPLBACKEND=Agg", sys.executable, "-m", "shaftfe",
            *args]


def _static(tree: str, out: str, *extra: str) -> list[str]:
    return _shaftfe(tree, "static", "--variant", "x2_57", "--out", out, *extra)


def _base_label() -> str:
    return os.environ.get("SHAFTFE_BASELINE_LABEL", "baseline, its default")


def commands(here: str, base: str, tmp: str) -> dict:
    """The whole processes timed side by side: what each tree's default gives."""
    rpm = str(HERE / "loadspectra" / "rpm.dat")
    b = _base_label()
    return {
        "static": {"zoned (this tree, default)": _static(here, f"{tmp}/a"),
                   f"{b}": _static(base, f"{tmp}/b"),
                   "full 3D (this tree, --model solid)": _static(here, f"{tmp}/c", "--model",
                                                                 "solid")},
        "fatigue": {"FKM on the zoned model (this tree, default)":
                    _shaftfe(here, "fatigue", rpm, "--out", f"{tmp}/fa"),
                    f"FKM ({b}; static from the cache when warm)":
                    _shaftfe(base, "fatigue", rpm, "--out", f"{tmp}/fb")},
        "demo": {"zoned (this tree, default)": _shaftfe(here, "demo", "--out", f"{tmp}/da"),
                 f"{b}": _shaftfe(base, "demo", "--out", f"{tmp}/db")}}


def speed() -> dict | None:
    base = os.environ.get("SHAFTFE_BASELINE")
    if not base:
        return None
    out: dict = {}
    with tempfile.TemporaryDirectory() as tmp:
        for what, cmds in commands(str(HERE), base, tmp).items():
            out[what] = _time(cmds, tmp, what)
    out["study design"] = study_design(base)
    return out


def _time(cmds: dict, tmp: str, what: str) -> dict:
    """Cold (an empty cache of its own each: no mesh, no solution another command stored) and
    warm (one warm-up, then the median of ``RUNS``, the commands in turn on one cache) of each
    command."""
    out: dict = {}
    for k, (name, cmd) in enumerate(cmds.items()):
        out[name] = {"cold": process(cmd, tmp, {"SHAFTFE_CACHE_DIR": f"{tmp}/cold-{what}-{k}"})}
    env = {"SHAFTFE_CACHE_DIR": f"{tmp}/warm"}
    for cmd in cmds.values():
        process(cmd, tmp, env)                           # warm-up
    runs: dict = {name: [] for name in cmds}
    for _ in range(RUNS):
        for name, cmd in cmds.items():
            runs[name].append(process(cmd, tmp, env))
    for name, rs in runs.items():
        out[name]["warm"] = {"wall_s": statistics.median(r["wall_s"] for r in rs),
                             "max_rss_MiB": max(r["max_rss_MiB"] for r in rs),
                             "all_wall_s": [r["wall_s"] for r in rs]}
    # this tree against the baseline run by run (each pair ran back to back: the ratio holds
    # when the machine's speed drifts between rounds), the median of the pairs
    a, b = list(cmds)[:2]
    out[a]["warm"]["vs_baseline_paired"] = statistics.median(
        x["wall_s"] / y["wall_s"] for x, y in zip(runs[a], runs[b], strict=True))
    return out


STUDY_FILLETS_MM = (0.41, 0.43, 0.47, 0.49)     # a new collar fillet each run: a new solid


def study_design(base: str) -> dict:
    """One study design with a new solid at the ``default`` level (the collar fillet changed:
    a new mesh for the full 3D model; for the zoned one a new meridian mesh, and the zone whose
    cut lies next to the collar where its cut moves with the collar), the seed method's fatigue
    row included, after one design of each (imports, the unchanged zone's mesh), on a cache of
    its own that holds nothing of the measured designs (an earlier run's meshes would make them
    no new solids): ``study.evaluate.evaluate_design`` with ``analyses.static.model`` solid
    (this tree) and zoned (this tree and the baseline), each in a process of its own tree
    (``_DESIGN_SCRIPT``)."""
    import subprocess
    b = _base_label()
    out: dict = {}
    for label, model, tree in (("solid (this tree)", "solid", str(HERE)),
                               ("zoned (this tree)", "zoned", str(HERE)),
                               (f"zoned ({b})", "zoned", base)):
        # shaftfe from ``tree`` (its PYTHONPATH), started outside both trees (the working
        # directory is first on the path); the script imports nothing of benchmarks/ (the
        # baseline's tree has its own)
        code = _DESIGN_SCRIPT.format(rpm=str(HERE / "loadspectra" / "rpm.dat"), model=model,
                                     fillets=STUDY_FILLETS_MM)
        with tempfile.TemporaryDirectory() as cwd:
            p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                               cwd=cwd,
                               env={**os.environ, "PYTHONPATH": tree, "MPLBACKEND": "Agg"})
        if p.returncode:
            raise RuntimeError(f"the study design of {label} failed:\n{p.stderr}")
        out[label] = json.loads(p.stdout.strip().splitlines()[-1])
    return out


_DESIGN_SCRIPT = """
import json, statistics, tempfile, time
from shaftfe.study.evaluate import evaluate_design
from shaftfe.study.spec import Analyses
an = Analyses(static=True, static_model={model!r}, level="default", fatigue=True,
              spectrum={rpm!r})
with tempfile.TemporaryDirectory() as cache:
    evaluate_design("x2_57", {{}}, an, cache_dir=cache)    # warm-up
    times = []
    for r in {fillets!r}:
        t0 = time.perf_counter()
        row = evaluate_design("x2_57", {{"segments.collar.fillet_mm": r}}, an, cache_dir=cache)
        times.append(time.perf_counter() - t0)
        assert row["status"] == "ok", row["error"]
print(json.dumps({{"median_s": statistics.median(times), "all_s": times,
                  "n_dofs": row["n_dofs"], "stress_max_MPa": row["stress_max_MPa"]}}))
"""


def _pct(a: float, b: float) -> str:
    return f"{100 * (a / b - 1):+.2f} %" if b else "-"


def write(acc: dict, spd: dict | None) -> str:
    z, f = acc["zoned"], acc["full"]
    lines = ["# The zoned static solve against the full 3D model (issue #32)", "",
             "(generated by benchmarks/bench_zoned.py; 2-core machine shared with other jobs, "
             "wall-clock seconds)", "",
             f"## x2_57 at {RPM:g} rpm, all parts, bearing springs, spin softening", "",
             f"Zoned: the axisymmetric global model ({z['global']['nodes']} meridian nodes, "
             f"harmonics {z['global']['harmonics']}) and {len(z['zones'])} 3D submodels at "
             f"`default`, {z['seconds']:.2f} s in process (with the sensitivity solves). Full "
             f"3D: `default` {f['default']['dofs']} dofs, {f['default']['seconds']:.1f} s; "
             f"`fine` {f['fine']['dofs']} dofs, {f['fine']['seconds']:.1f} s.", "",
             "### Zones", "",
             "| zone | features | nominal zone mm | extent mm | cuts mm | grown | dofs | cut "
             "check (vM / σxx) | peak change, cut one gap out | mesh s | assembly s | factor s "
             "| solve s | recovery s |", "|" + "---|" * 14]
    for q in z["zones"]:
        cc = "; ".join(f"{g} x {x:g}: {100 * a:.2f} / {100 * b:.2f} %"
                       for g, x, a, b in q["cut_checks"])
        sens = q["sensitivity"] or {}
        sv = ", ".join(f"{k} {100 * v:+.2f} %" for k, v in sens.items() if k != "cuts_mm")
        sv = f"to {sens.get('cuts_mm')}: {sv}" if sens else "-"
        s = q["seconds"]
        lines.append(f"| {q['name']} | {', '.join(q['features'])} | {q['nominal_mm'][0]:g} … "
                     f"{q['nominal_mm'][1]:g} | {q['x_mm'][0]:g} … {q['x_mm'][1]:g} | "
                     f"{', '.join(f'{x:g}' for x in q['cuts_mm'])} | {q['grown']} | "
                     f"{q['dofs']} | {cc} | {sv} | {s['mesh_seconds']:.2f} | "
                     f"{s['assembly_seconds']:.2f} | {s['factor_seconds']:.2f} | "
                     f"{s['solve_seconds']:.2f} | {s['recovery_seconds']:.2f} |")
    r = z["run"]
    lines += ["", f"Phases of the whole zoned solve: plan {r['plan_seconds']:.2f} s, global "
              f"{r['global_seconds']:.2f} s, zones {r['zones_seconds']:.2f} s (with the "
              "sensitivity solves).", "", "### Reactions and deflections (the keyways' and the "
              "hex socket's effect on the stiffness)", "",
              "| quantity | zoned (global model) | full 3D default | diff | full 3D fine | diff |",
              "|---|---|---|---|---|---|"]
    for name, (_, _, F) in z["bearings"].items():
        d, fi = f["default"]["bearings"][name][2], f["fine"]["bearings"][name][2]
        lines.append(f"| bearing {name} \\|F\\| N | {F:.2f} | {d:.2f} | {_pct(F, d)} | "
                     f"{fi:.2f} | {_pct(F, fi)} |")
    for name, u in z["stations"].items():
        d, fi = f["default"]["stations"].get(name), f["fine"]["stations"].get(name)
        if d is None:
            continue
        lines.append(f"| deflection {name} µm | {1e3 * u:.3f} | {1e3 * d:.3f} | {_pct(u, d)} | "
                     f"{1e3 * fi:.3f} | {_pct(u, fi)} |")
    lines += ["", "### Peaks", "",
              "| region | kind | from | zoned vM MPa | full default | diff | full fine | diff "
              "| zoned max principal | full default | full fine |", "|" + "---|" * 11]
    for reg, (vm, p1, model, kind) in z["peaks"].items():
        d, fi = f["default"]["peaks"].get(reg), f["fine"]["peaks"].get(reg)
        if d is None or fi is None:
            continue
        lines.append(f"| {reg} | {kind} | {model} | {vm:.2f} | {d[0]:.2f} | {_pct(vm, d[0])} | "
                     f"{fi[0]:.2f} | {_pct(vm, fi[0])} | {p1:.2f} | {d[1]:.2f} | {fi[1]:.2f} |")
    lines += ["", "## A keyed Ø20 bar between two cuts (tests/validation/test_zoned.py)", "",
              "| load | level | zoned keyway vM MPa | zone dofs | zoned s | cut check | full 3D "
              "same level | diff | full 3D dofs | full 3D s | full 3D fine | diff |",
              "|" + "---|" * 12]
    for row in acc["keyed_bar"]:
        lines.append(f"| {row['load']} | {row['level']} | {row['zoned_MPa']:.2f} | "
                     f"{row['zone_dofs']} | {row['zoned_s']:.2f} | "
                     f"{100 * row['cut_check']:.2f} % | {row['solid_same_MPa']:.2f} | "
                     f"{_pct(row['zoned_MPa'], row['solid_same_MPa'])} | {row['solid_dofs']} | "
                     f"{row['solid_same_s']:.2f} | {row['solid_fine_MPa']:.2f} | "
                     f"{_pct(row['zoned_MPa'], row['solid_fine_MPa'])} |")
    if spd:
        title = {"static": "`shaftfe static --variant x2_57`",
                 "fatigue": "`shaftfe fatigue loadspectra/rpm.dat` (FKM, the default method)",
                 "demo": "`shaftfe demo` (`make demo`)"}
        for what, rows in spd.items():
            if what not in title:
                continue
            lines += ["", f"## {title[what]}: whole processes, side by side", "",
                      f"Warm: the median of {RUNS} runs after one warm-up, the commands in "
                      "turn on one warm cache (paired: the median over the rounds of this "
                      "tree's run / the baseline's run of the same round); cold: an empty "
                      "cache (every mesh made).", "",
                      "| command | warm s | warm runs s | paired / baseline | warm peak MiB | "
                      "cold s | cold peak MiB |", "|---|---|---|---|---|---|---|"]
            for name, d in rows.items():
                w, c = d["warm"], d["cold"]
                pr = w.get("vs_baseline_paired")
                lines.append(f"| {name} | {w['wall_s']:.2f} | "
                             f"{', '.join(f'{x:.2f}' for x in w['all_wall_s'])} | "
                             f"{'-' if pr is None else f'{pr:.3f}'} | "
                             f"{w['max_rss_MiB']:.0f} | {c['wall_s']:.2f} | "
                             f"{c['max_rss_MiB']:.0f} |")
        sd = spd.get("study design")
        if sd:
            lines += ["", "## A study design with a new solid at `default` (in process)", "",
                      "The collar fillet changed each run "
                      f"({', '.join(f'{r:g}' for r in STUDY_FILLETS_MM)} mm), the seed "
                      "method's fatigue row included, after one design of each model, on a "
                      "cache of its own that holds none of the measured designs (a new solid "
                      "each: the meridian mesh anew; a zone whose cut moves with the collar "
                      "anew), each tree in a process of its own.", "",
                      "| analyses.static.model (tree) | median s | runs s | dofs | stress_max "
                      "MPa |",
                      "|---|---|---|---|---|"]
            for model, d in sd.items():
                lines.append(f"| {model} | {d['median_s']:.2f} | "
                             f"{', '.join(f'{x:.2f}' for x in d['all_s'])} | {d['n_dofs']} | "
                             f"{d['stress_max_MPa']:.2f} |")
    else:
        lines += ["", "(speed part left out: SHAFTFE_BASELINE not set)"]
    return "\n".join(lines) + "\n"


def main() -> None:
    """``--speed-only``: keep the accuracy part of the last zoned.json and re-time."""
    if "--speed-only" in sys.argv and (OUT / "zoned.json").exists():
        acc = json.loads((OUT / "zoned.json").read_text())["accuracy"]
    else:
        acc = accuracy()
    spd = speed()
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "zoned.json").write_text(json.dumps({"accuracy": acc, "speed": spd}, indent=1,
                                               default=str) + "\n")
    (OUT / "zoned.md").write_text(write(acc, spd))
    print((OUT / "zoned.md").read_text())


if __name__ == "__main__":
    main()
