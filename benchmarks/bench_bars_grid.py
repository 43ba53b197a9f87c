"""The fillet-peak error bars of the 3D levels (issue #30 §5) and of the axisymmetric levels
(issue #32: the zoned solve's and ``--model axisymmetric``'s span fillets), measured over a grid
of shoulders.

Each grid point is a stepped round bar of d = 17 mm (``bench_truth.four_point_bar``: rigid simple
supports, two equal loads 3 D from the shoulder, the shoulder in constant moment) with D/d and
r/d from ``GRID``, plus the three shoulders bench_truth measured first. The SAME ``Variant`` goes
through both paths:

* the truth: ``shaftfe.axisymmetric`` converged by Richardson over refinements 0, 1, 2 of its
  default mesh, with Roache's GCI bar (``axisymmetric.kt.converged_peaks``; the axisymmetric
  path matches an independent implementation to 1e-4);
* the 3D path (``shaftfe.static``, P2 tets) at each mesh level;
* the axisymmetric path (``shaftfe.axisymmetric``) at each of its own levels, refinement 0.
  Its truth is the same method refined (its ``default`` level is refinement 0 of the truth's
  sequence), so the axisymmetric bar is a discretisation error bar of its own method (Roache's
  GCI), not an independent check; the independent check is the 3D path, a different model
  (tetrahedra, another recovery), which meets the same truth within its own bars at ``fine``.

Load kind: bending only. The 3D pipeline's only load is m·e·ω² on the parts' seats (radial
forces); it applies no axial force, so a fillet in tension is never what ``shaftfe static``
reports, and no tension bar is measured or printed.

A fillet the step cannot carry (ρ > (D − d)/2, refused by the variant loader) is replaced by
the largest grid value that fits, 0.9 (D − d)/2 (stated in the table).

The bar of a level is the envelope (min … max) over every measured grid point of
100 (3D − truth) / truth, max principal and von Mises, each widened by the truth's own GCI bar;
it covers the convex hull of the measured points in the (D/d, r/d) plane
(reports/benchmarks/error_bars_shoulders.json; the lookup ``shaftfe.static.solve.truth_bars`` prints
no bar outside it). x2_57's span fillets (reports/benchmarks/truth.json, bench_truth) are then
checked against the grid's bar; for the axisymmetric levels x2_57's two span fillets are solved
here at each level (10 000 rpm, bearing springs, spin softening on and off, as truth.json's
truth) and enter its envelope the same way.

Run in chunks (each solve is cached in ``reports/benchmarks/bars_grid.json``, so a run resumes
where the last stopped): ``python -m benchmarks.bench_bars_grid [--budget S] [--levels a,b]
[--write]``; a chunk starts no new solve after ``--budget`` seconds. When every point of every
level asked is measured, it writes ``bars_grid.md`` and regenerates
``reports/benchmarks/error_bars_shoulders.json`` (``shaftfe.static.measured_errors.
shoulder_bars``); ``--write`` only regenerates them from the cache.
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

from benchmarks import _jsoncache as jsoncache
from shaftfe.util import paths

OUT = Path("reports/benchmarks")
CACHE = OUT / "bars_grid.json"
BARS = paths.SHOULDER_BARS_JSON
TRUTH_JSON = OUT / "truth.json"
RPM = 10_000.0
D_SMALL = 17.0
DD = (1.1, 1.25, 1.5)
RD = (0.02, 0.05, 0.1, 0.15)
FIT = 0.9              # an infeasible r/d is replaced by FIT × (D/d − 1)/2
LEGACY = ((22.0, 17.0, 1.0), (22.0, 17.0, 0.5), (25.0, 17.0, 1.0))   # bench_truth's shoulders
LEVELS = ("coarse", "default", "fine")
AXI_LEVELS = ("coarse", "default", "fine")
LOAD = "bending"
X2_57_FILLETS = ("fillet:collar", "fillet:bearing_seat_gear")


def grid() -> list[tuple[float, float]]:
    """(D/d, r/d) of every grid point (see the module docstring), then the legacy shoulders."""
    pts = []
    for dd in DD:
        fit = round(FIT * (dd - 1) / 2, 6)
        rds = sorted({rd if rd <= (dd - 1) / 2 - 1e-9 else fit for rd in RD})
        pts += [(dd, rd) for rd in rds]
    pts += [(round(D / d, 6), round(r / d, 6)) for D, d, r in LEGACY]
    return pts


def _geometry(dd: float, rd: float) -> tuple[float, float, float]:
    for D, d, r in LEGACY:
        if (round(D / d, 6), round(r / d, 6)) == (dd, rd):
            return D, d, r
    return round(dd * D_SMALL, 6), D_SMALL, round(rd * D_SMALL, 6)


def _key(dd: float, rd: float) -> str:
    return f"{dd:g}/{rd:g}"


def _truth(v) -> dict:
    from shaftfe.axisymmetric.kt import converged_peaks
    t0 = time.perf_counter()
    c = converged_peaks(v, RPM, ["fillet:a"], rigid_supports=True, spin_softening=False)
    return {"max_principal": [c["fillet:a"]["max_principal"]["value"],
                              c["fillet:a"]["max_principal"]["error"]],
            "von_mises": [c["fillet:a"]["von_mises"]["value"],
                          c["fillet:a"]["von_mises"]["error"]],
            "nodes": c["nodes"], "seconds": time.perf_counter() - t0}


def _load() -> dict:
    return jsoncache.load(CACHE)


def _save(data: dict) -> None:
    jsoncache.save(CACHE, data)


def measure(levels, budget: float) -> bool:
    """Solve what the cache lacks until ``budget`` seconds have passed; True when complete."""
    from benchmarks.bench_truth import _solid, four_point_bar
    t_start = time.perf_counter()
    data = _load()
    todo = [(p, None) for p in grid()]
    todo += [(p, lv) for lv in levels for p in grid()]     # every level: the whole grid
    todo += [(p, f"axisymmetric:{lv}") for lv in AXI_LEVELS for p in grid()]
    for (dd, rd), lv in todo:
        rec = data["points"].setdefault(_key(dd, rd), {"D/d": dd, "r/d": rd, "load": LOAD})
        what = "truth" if lv is None else lv
        if what in rec or (what.startswith("axisymmetric:") and
                           what.split(":")[1] in rec.get("axisymmetric", {})):
            continue
        if time.perf_counter() - t_start > budget:
            return False
        D, d, r = _geometry(dd, rd)
        rec["D_d_r_mm"] = [D, d, r]
        v = four_point_bar(D, d, r)
        if lv is None:
            rec["truth"] = _truth(v)
        elif lv.startswith("axisymmetric:"):
            alv = lv.split(":")[1]
            rec.setdefault("axisymmetric", {})[alv] = _axi(v, alv)
            print(f"{_key(dd, rd)} {what}: {rec['axisymmetric'][alv]}", flush=True)
            _save(data)
            continue
        else:
            s1, vm, dofs, dt = _solid(v, lv)
            rec[lv] = {"max_principal": s1, "von_mises": vm, "dofs": dofs, "seconds": dt}
        print(f"{_key(dd, rd)} {what}: {rec[what]}", flush=True)
        _save(data)
    x2 = data.setdefault("x2_57_axisymmetric", {})
    for lv in AXI_LEVELS:
        for soft in (True, False):
            key = f"{lv}|{'on' if soft else 'off'}"
            if key not in x2:
                x2[key] = _axi_x2_57(lv, soft)
                print(f"x2_57 axisymmetric {key}: {x2[key]}", flush=True)
                _save(data)
    return True


def _axi(v, level: str) -> dict:
    """The axisymmetric path's fillet peak of the grid bar at ``level`` (refinement 0), under
    the truth's options (rigid supports, no softening)."""
    from shaftfe.axisymmetric.model import AxiOptions
    from shaftfe.axisymmetric.solve import solve_axisymmetric
    t0 = time.perf_counter()
    res = solve_axisymmetric(v, RPM, AxiOptions(level, rigid_supports=True,
                                                spin_softening=False))
    pk = {p.region: p for p in res.case(RPM).peaks}["fillet:a"]
    return {"max_principal": float(pk.max_principal_MPa), "von_mises": float(pk.von_mises_MPa),
            "nodes": int(res.n_nodes), "seconds": time.perf_counter() - t0}


def _axi_x2_57(level: str, softening: bool) -> dict:
    """x2_57's span-fillet peaks at the axisymmetric ``level`` under truth.json's options
    (10 000 rpm, bearing springs, all parts, spin softening on or off)."""
    from shaftfe.axisymmetric.model import AxiOptions
    from shaftfe.axisymmetric.solve import solve_axisymmetric
    from shaftfe.model.loader import load_variant
    res = solve_axisymmetric(load_variant("x2_57"), RPM,
                             AxiOptions(level, spin_softening=softening))
    pk = {p.region: p for p in res.case(RPM).peaks}
    return {f: {"max_principal": float(pk[f].max_principal_MPa),
                "von_mises": float(pk[f].von_mises_MPa)} for f in X2_57_FILLETS} | {
        "nodes": int(res.n_nodes)}


def errors(rec: dict, level: str, model: str = "solid") -> dict[str, tuple[float, float, float]]:
    """{quantity: (error %, low %, high %)}: 100 (value − truth) / truth of the 3D (``model``
    "solid") or axisymmetric level and the same widened by the truth's GCI bar."""
    return against_truth(rec[level] if model == "solid" else rec["axisymmetric"][level],
                         rec["truth"])


def against_truth(at: dict, truth: dict) -> dict[str, tuple[float, float, float]]:
    """{quantity: (error %, low %, high %)} of the peaks ``at`` against ``truth`` ({quantity:
    (value, GCI bar)}): 100 (value − truth) / truth, and the same widened by the bar."""
    out = {}
    for q in ("max_principal", "von_mises"):
        t, bar = truth[q]
        val = at[q]
        out[q] = (100 * (val - t) / t, 100 * (val - t - bar) / t, 100 * (val - t + bar) / t)
    return out


def _outwards(errs) -> tuple[float, float]:
    """(min low, max high) of (error, low, high) triples, rounded outwards to 0.01 %."""
    return (math.floor(min(e[1] for e in errs) * 100) / 100,
            math.ceil(max(e[2] for e in errs) * 100) / 100)


def grid_errors(data: dict, level: str, model: str = "solid") -> list[tuple[float, float, float]]:
    return [e for p in grid()
            for e in errors(data["points"][_key(*p)], level, model).values()]


def x2_57_errors(level: str, path: Path = TRUTH_JSON) -> list[tuple[str, str, tuple]]:
    """(fillet, quantity, (error, low, high) %) of x2_57's span fillets at ``level`` in
    bench_truth's truth.json (10 000 rpm, springs, spin softening on and off)."""
    recs = json.loads(Path(path).read_text())["records"]
    out = []
    for r in recs:
        if r["case"].startswith("x2_57") and r["level"] == level:
            t, bar, val = r["truth_MPa"], r["truth_bar_MPa"], r["value_MPa"]
            out.append((r["case"][6:], r["quantity"], (100 * (val - t) / t,
                                                       100 * (val - t - bar) / t,
                                                       100 * (val - t + bar) / t)))
    return out


def x2_57_axi_errors(data: dict, level: str,
                     path: Path = TRUTH_JSON) -> list[tuple[str, str, tuple]]:
    """(fillet, quantity, (error, low, high) %) of x2_57's span fillets at the axisymmetric
    ``level`` against truth.json's truth (spin softening on and off)."""
    recs = json.loads(Path(path).read_text())["records"]
    truth = {(r["case"], r["quantity"]): (r["truth_MPa"], r["truth_bar_MPa"]) for r in recs
             if r["case"].startswith("x2_57")}
    out = []
    for soft in ("on", "off"):
        vals = data["x2_57_axisymmetric"][f"{level}|{soft}"]
        for f in X2_57_FILLETS:
            case = f"x2_57 {f}" + ("" if soft == "on" else " (no softening)")
            for q in ("max_principal", "von_mises"):
                t, bar = truth[(case, q)]
                val = vals[f][q]
                out.append((case[6:], q, (100 * (val - t) / t, 100 * (val - t - bar) / t,
                                          100 * (val - t + bar) / t)))
    return out


def axi_envelope(data: dict, level: str, path: Path = TRUTH_JSON) -> tuple[float, float]:
    """The axisymmetric ``level``'s bar: (low, high) % over the grid and x2_57's span fillets."""
    return _outwards(grid_errors(data, level, "axisymmetric")
                     + [e for *_, e in x2_57_axi_errors(data, level, path)])


def envelope(data: dict, level: str, path: Path = TRUTH_JSON) -> tuple[float, float]:
    """The bar of ``level``: (low, high) % over its grid points and x2_57's span fillets (both
    inside the grid's hull, against the same truth), rounded outwards to 0.01 %."""
    return _outwards(grid_errors(data, level) + [e for *_, e in x2_57_errors(level, path)])


def write(data: dict, levels) -> dict:
    """bars_grid.md and the generated module from the cache."""
    bars = {lv: envelope(data, lv) for lv in levels}
    grid_only = {lv: _outwards(grid_errors(data, lv)) for lv in levels}
    lines = ["# The 3D levels' fillet error bars over a grid of shoulders", "",
             "(generated by benchmarks/bench_bars_grid.py; 2-core machine shared with other "
             "jobs, wall-clock seconds)", "",
             "Four-point bending of a stepped bar, d = 17 mm, rigid simple supports, the "
             "shoulder in constant moment; the same Variant through both paths. Truth: "
             "axisymmetric, Richardson over refinements 0, 1, 2, GCI bar. Error = 100 (3D − "
             "truth) / truth. Points marked * replace an r/d the step cannot carry "
             f"(> (D/d − 1)/2) by {FIT} (D/d − 1)/2; † are bench_truth's shoulders.", "",
             "| D/d | r/d | D/d/ρ mm | truth max principal MPa | truth von Mises MPa | truth s "
             "| level | 3D dofs | 3D s | error max principal | error von Mises |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    legacy = {(round(D / d, 6), round(r / d, 6)) for D, d, r in LEGACY}
    for dd, rd in grid():
        rec = data["points"][_key(dd, rd)]
        mark = "†" if (dd, rd) in legacy else ("*" if rd not in RD else "")
        D, d, r = rec["D_d_r_mm"]
        t = rec["truth"]
        for lv in levels:
            if lv not in rec:
                continue
            e = errors(rec, lv)
            lines.append(
                f"| {dd:g} | {rd:g}{mark} | {D:g}/{d:g}/{r:g} | "
                f"{t['max_principal'][0]:.3f} ± {t['max_principal'][1]:.3f} | "
                f"{t['von_mises'][0]:.3f} ± {t['von_mises'][1]:.3f} | {t['seconds']:.1f} | "
                f"{lv} | {rec[lv]['dofs']} | {rec[lv]['seconds']:.1f} | "
                f"{e['max_principal'][0]:+.2f} % | {e['von_mises'][0]:+.2f} % |")
    lines += ["", "## x2_57's span fillets against the grid", "",
              "x2_57's collar and bearing-seat-gear fillets (D/d 22/17 = 1.294, r/d 0.6/17 = "
              "0.035) lie inside the measured hull; their errors against the same truth "
              "(reports/benchmarks/truth.md: 10 000 rpm, bearing springs, spin softening on and "
              "off), checked against the grid's own envelope:", "",
              "| fillet | level | quantity | error | inside the grid's envelope |",
              "|---|---|---|---|---|"]
    for lv in levels:
        lo, hi = grid_only[lv]
        lines += [f"| {c} | {lv} | {q} | {e[0]:+.2f} % | "
                  f"{'yes' if lo <= e[0] <= hi else 'NO'} |" for c, q, e in x2_57_errors(lv)]
    lines += ["", "## Bar per level (bending; what `shaftfe static` prints beside a fillet peak "
              "inside the measured hull)", "",
              "Each error widened by the truth's GCI bar; the bar is the envelope over the grid "
              "and x2_57's fillets (measured inside the hull against the same truth, so what "
              "is printed covers every measurement there); written to "
              "reports/benchmarks/error_bars_shoulders.json.", "",
              "| level | grid points | grid envelope | bar (grid and x2_57) | 3D seconds (sum) |",
              "|---|---|---|---|---|"]
    for lv, (lo, hi) in bars.items():
        pts = grid()
        secs = sum(data["points"][_key(*p)][lv]["seconds"] for p in pts)
        g_lo, g_hi = grid_only[lv]
        lines.append(f"| {lv} | {len(pts)} | {g_lo:+.2f} … {g_hi:+.2f} % | "
                     f"{lo:+.2f} … {hi:+.2f} % | {secs:.0f} |")
    tsecs = sum(data["points"][_key(*p)]["truth"]["seconds"] for p in grid())
    lines += ["", f"Truth: {len(grid())} points, {tsecs:.0f} s in all."]
    axi_bars = {lv: axi_envelope(data, lv) for lv in AXI_LEVELS}
    lines += _axi_lines(data, axi_bars)
    (OUT / "bars_grid.md").write_text("\n".join(lines) + "\n")
    _write_module(bars, grid(), axi_bars)
    print("\n".join(lines))
    return bars


def _axi_lines(data: dict, axi_bars: dict) -> list[str]:
    """The axisymmetric levels' section of bars_grid.md."""
    lines = ["", "## The axisymmetric levels (the zoned solve's and --model axisymmetric's span "
             "fillets)", "",
             "The same bars and truth, solved by `shaftfe.axisymmetric` at each of its levels "
             "(refinement 0; rigid supports, no softening). The truth is this method refined "
             "(the `default` level is refinement 0 of its sequence), so this is the "
             "discretisation error of the axisymmetric model (Roache's GCI), not an "
             "independent check; the independent check of the truth is the 3D path above, a "
             "different model, within its own bars at `fine`.", "",
             "| D/d | r/d | level | meridian nodes | s | error max principal | "
             "error von Mises |", "|---|---|---|---|---|---|---|"]
    for dd, rd in grid():
        rec = data["points"][_key(dd, rd)]
        for lv in AXI_LEVELS:
            a = rec["axisymmetric"][lv]
            e = errors(rec, lv, "axisymmetric")
            lines.append(f"| {dd:g} | {rd:g} | {lv} | {a['nodes']} | {a['seconds']:.2f} | "
                         f"{e['max_principal'][0]:+.3f} % | {e['von_mises'][0]:+.3f} % |")
    lines += ["", "x2_57's span fillets at each axisymmetric level against truth.json's truth "
              "(10 000 rpm, bearing springs, all parts):", "",
              "| fillet | level | quantity | error | inside the grid's envelope |",
              "|---|---|---|---|---|"]
    for lv in AXI_LEVELS:
        lo, hi = _outwards(grid_errors(data, lv, "axisymmetric"))
        lines += [f"| {c} | {lv} | {q} | {e[0]:+.3f} % | "
                  f"{'yes' if lo <= e[0] <= hi else 'NO'} |"
                  for c, q, e in x2_57_axi_errors(data, lv)]
    lines += ["", "| axisymmetric level | grid envelope | bar (grid and x2_57) |", "|---|---|---|"]
    for lv, (lo, hi) in axi_bars.items():
        g_lo, g_hi = _outwards(grid_errors(data, lv, "axisymmetric"))
        lines.append(f"| {lv} | {g_lo:+.2f} … {g_hi:+.2f} % | {lo:+.2f} … {hi:+.2f} % |")
    return lines


def _write_module(bars: dict, points, axi_bars: dict) -> None:
    from shaftfe.static.measured_errors import write_bars
    write_bars(BARS, "benchmarks/bench_bars_grid.py", LOAD,
               {"solid": bars, "axisymmetric": axi_bars}, points)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(prog="bench_bars_grid")
    ap.add_argument("--budget", type=float, default=math.inf,
                    help="start no new solve after this many seconds")
    ap.add_argument("--levels", default=",".join(LEVELS))
    ap.add_argument("--write", action="store_true", help="only write the outputs from the cache")
    a = ap.parse_args(argv if argv is not None else [])
    levels = tuple(a.levels.split(","))
    if a.write or measure(levels, a.budget):
        write(_load(), levels)
    else:
        print("bench_bars_grid: budget reached; run again to resume", flush=True)


if __name__ == "__main__":
    import sys
    main(sys.argv[1:])
