"""The groove-peak error bars of the axisymmetric levels (issue #33: the zoned solve's and
``--model axisymmetric``'s circumferential grooves) and of the 3D levels (``--model solid``),
measured over a grid of U grooves.

Each grid point is a round bar of D = 20 mm with one U groove in the middle of a four-point
bend (``grooved_bar``: rigid simple supports, two equal loads 3 D from the groove, the groove in
constant moment): depth t = (D − d)/2 with d/D in ``DD``, bottom corner radius ρ = k t with k in
``K``, and two widths, the extremes a U groove of that t and ρ spans here: w = 2 t (a flat bottom
2 (t − ρ) long) and w = 2 ρ (a round bottom and straight flanks; the same groove when ρ = t).

* the truth: ``shaftfe.axisymmetric`` converged by Richardson over refinements 0, 1, 2 of its
  default mesh, with Roache's GCI bar (``axisymmetric.kt.converged_peaks``, as the shoulders'
  truth in bench_bars_grid; the method matches an independent implementation to 1e-4);
* the axisymmetric path at each of its levels, refinement 0;
* the full 3D model at ``fine`` (another model: tetrahedra, its own recovery), the independent
  check of the truth; and at ``coarse`` and ``default`` too on the same grooves (ρ ≥
  ``SOLID_CHECK_RHO_MM``): the 3D levels' groove bars, on those grooves' own hull, with
  x2_57's collar groove at every 3D level as their check where they were not measured.

And x2_57 with a full round U groove in the collar (x = 55.75, 2 wide, 1 deep, corner radius
1; D/d 22/20, ρ/d 0.05: inside the grid's hull, not a grid point), 10 000 rpm, bearing springs,
all parts, spin softening on and off, against its own truth (the same Richardson): the shaft's
supports and softening, as the shoulders' bars hold x2_57's fillets.

The truth is the same method refined, so the bar is a discretisation error bar of the
axisymmetric model (Roache's GCI), not an independent check; the independent checks of the
groove peaks are DIN 743-2's α (reports/benchmarks/grooves.md: −7.0 … +2.9 % over a grid of
the same grooves) and the 3D path of tests/validation/test_grooves.py.

Load kind: bending only (the bars are printed only for a shaft whose every load bends it,
``static.measured_errors.bending_only``).

The bar of a level is the envelope (min … max) over every grid point of 100 (value − truth) /
truth, max principal and von Mises, each widened by the truth's own GCI bar. It covers a groove
whose (D/d, ρ/d) lies in the convex hull of the measured points and whose width lies between
the two measured widths, 2 ρ … 2 t (reports/benchmarks/error_bars_grooves.json; the lookup
``shaftfe.static.measured_errors.notch_bars`` prints no bar elsewhere: a DIN 471 ring groove's
0.1 mm corners, a DIN 509 undercut at a shoulder).

    python -m benchmarks.bench_groove_bars [--write]   # reports/benchmarks/groove_bars.md / .json
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from benchmarks import _jsoncache as jsoncache
from benchmarks import bench_bars_grid as bars_grid
from shaftfe.util import paths

OUT = Path("reports/benchmarks")
CACHE = OUT / "groove_bars.json"
BARS = paths.GROOVE_BARS_JSON
RPM = 10_000.0
D_BAR = 20.0
DD = (0.8, 0.9, 0.95)          # d/D
K = (0.25, 0.5, 1.0)           # ρ/t
WIDTHS = ("2t", "2rho")
AXI_LEVELS = ("coarse", "default", "fine")
LOAD = "bending"
REGION = "groove:a:0"
# the 3D check only where its fine mesh fits this 24 GiB machine: ρ 0.5 mm took 430 497 dofs and
# 46 s; ρ 0.25 mm passed 9 GiB still meshing (the corner ring's dofs grow as 1/ρ²)
SOLID_CHECK_RHO_MM = 0.5
# the 3D levels whose groove bars are measured on those grooves (fine: the check above)
SOLID_LEVELS = ("coarse", "default", "fine")
X2_57_GROOVE = (55.75, 2.0, 1.0, 1.0)      # x, width, depth, radius: a full round U
X2_57_REGION = "groove:collar:0"


def grid() -> list[tuple[float, float, str]]:
    """(d/D, ρ/t, width rule) of every grid point; the w = 2ρ groove only where ρ < t."""
    return [(q, k, w) for q in DD for k in K for w in WIDTHS if not (w == "2rho" and k == 1.0)]


def geometry(q: float, k: float, w: str) -> tuple[float, float, float, float]:
    """(D, t, ρ, width) in mm of a grid point."""
    t = round(0.5 * D_BAR * (1.0 - q), 9)
    rho = round(k * t, 9)
    return D_BAR, t, rho, round(2.0 * (t if w == "2t" else rho), 9)


def grooved_bar(D: float, t: float, rho: float, width: float):
    """The Variant of one grid point (see the module docstring): supports (seat centres) 30 mm
    outside the loads, load seats 10 mm wide, 1 kg at e = 1 mm each (F = 1097 N at 10 000 rpm)."""
    from shaftfe.model.examples import STEEL
    from shaftfe.model.variant import Attachment, Bearing, Groove, Segment, Variant
    a = 3.0 * D                                  # load to groove centre
    half = a + 40.0
    segs = (Segment("a", 0.0, 2 * half, D, 0.0,
                    grooves=(Groove("u", half, width, t, rho),)),)
    K_ = ((1e5, 0.0), (0.0, 1e5))                # unused: rigid supports
    brg = (Bearing("L", "x", 10.0, 10.0, 1e5, 1e5, K_, axial=True),
           Bearing("R", "x", 2 * half - 10.0, 10.0, 1e5, 1e5, K_))
    att = (Attachment("p", half - a - 5.0, half - a + 5.0, 1.0, 1.0, half - a),
           Attachment("q", half + a - 5.0, half + a + 5.0, 1.0, 1.0, half + a))
    return Variant(f"4pb_groove_{D:g}_{t:g}_{rho:g}_{width:g}",
                   "four-point bending of a U groove", segs, brg, att, STEEL, 0.0)


def x2_57_grooved(groove=X2_57_GROOVE, segment: str = "collar", loads=None):
    """x2_57 with one U groove ``groove`` = (x, width, depth, corner radius) mm on ``segment``
    (default: the collar's, ``X2_57_GROOVE``), and ``loads`` instead of its own if given."""
    from dataclasses import replace

    from shaftfe.model.loader import load_variant
    from shaftfe.model.variant import Groove
    v = load_variant("x2_57")
    g = Groove("u", *groove)
    segs = tuple(replace(s, grooves=(g,)) if s.name == segment else s for s in v.segments)
    return replace(v, segments=segs, **({} if loads is None else {"loads": loads}))


def _x2_57(level: str | None, softening: bool) -> dict:
    """x2_57's collar groove at the axisymmetric ``level`` (None: its truth), 10 000 rpm,
    bearing springs, spin softening on or off."""
    from shaftfe.axisymmetric.kt import converged_peaks
    from shaftfe.axisymmetric.model import AxiOptions
    from shaftfe.axisymmetric.solve import solve_axisymmetric
    v = x2_57_grooved()
    if level is None:
        c = converged_peaks(v, RPM, [X2_57_REGION], spin_softening=softening)
        return {q: [c[X2_57_REGION][q]["value"], c[X2_57_REGION][q]["error"]]
                for q in ("max_principal", "von_mises")} | {"nodes": c["nodes"]}
    res = solve_axisymmetric(v, RPM, AxiOptions(level, spin_softening=softening))
    pk = {p.region: p for p in res.case(RPM).peaks}[X2_57_REGION]
    return {"max_principal": float(pk.max_principal_MPa), "von_mises": float(pk.von_mises_MPa),
            "nodes": int(res.n_nodes)}


def _key(q: float, k: float, w: str) -> str:
    return f"{q:g}/{k:g}/{w}"


def _truth(v) -> dict:
    from shaftfe.axisymmetric.kt import converged_peaks
    t0 = time.perf_counter()
    c = converged_peaks(v, RPM, [REGION], rigid_supports=True, spin_softening=False)
    return {q: [c[REGION][q]["value"], c[REGION][q]["error"]]
            for q in ("max_principal", "von_mises")} | {
        "nodes": c["nodes"], "seconds": time.perf_counter() - t0}


def _axi(v, level: str) -> dict:
    """The groove's peak at the axisymmetric ``level`` (refinement 0), under the truth's
    options (rigid supports, no softening)."""
    from shaftfe.axisymmetric.model import AxiOptions
    from shaftfe.axisymmetric.solve import solve_axisymmetric
    t0 = time.perf_counter()
    res = solve_axisymmetric(v, RPM, AxiOptions(level, rigid_supports=True,
                                                spin_softening=False))
    pk = {p.region: p for p in res.case(RPM).peaks}[REGION]
    return {"max_principal": float(pk.max_principal_MPa), "von_mises": float(pk.von_mises_MPa),
            "nodes": int(res.n_nodes), "seconds": time.perf_counter() - t0}


def _solid_fine(v) -> dict:
    """The groove's peak by the full 3D model at ``fine`` (tetrahedra, another recovery: a
    different model from the truth's), under the truth's options: the independent check of
    the truth."""
    return _solid(v, "fine")


def _solid(v, level: str, region: str = REGION, rigid: bool = True,
           softening: bool = False) -> dict:
    """The groove's peak by the full 3D model at ``level`` (the truth's options by default:
    rigid supports, no softening)."""
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import solve_static
    t0 = time.perf_counter()
    res = solve_static(v, [RPM], StaticOptions(level=level, rigid_supports=rigid,
                                               spin_softening=softening), beam=False)
    pk = {p.region: p for p in res.case(RPM).peaks}[region]
    return {"max_principal": float(pk.max_principal_MPa), "von_mises": float(pk.von_mises_MPa),
            "dofs": int(res.n_dofs), "seconds": time.perf_counter() - t0}


def checked(data: dict) -> list[tuple[tuple, dict]]:
    """(grid point, record) of the grooves the 3D model checked (ρ ≥ SOLID_CHECK_RHO_MM)."""
    return [(p, data["points"][_key(*p)]) for p in grid()
            if geometry(*p)[2] >= SOLID_CHECK_RHO_MM]


def solid_errors(data: dict) -> list[float]:
    """100 (3D fine − truth) / truth over the checked grooves, both quantities."""
    return [100 * (rec["solid_fine"][q] / rec["truth"][q][0] - 1) for _, rec in checked(data)
            for q in ("max_principal", "von_mises")]


def solid_at(rec: dict, level: str) -> dict:
    """A checked groove's (or x2_57's) 3D peak at ``level``."""
    return rec["solid_fine"] if level == "fine" else rec["solid"][level]


def solid_grid_errors(data: dict, level: str) -> list[tuple[float, float, float]]:
    """The 3D ``level``'s (error, low, high) % on every checked groove (ρ ≥ 0.5 mm)."""
    return [e for _, rec in checked(data)
            for e in bars_grid.against_truth(solid_at(rec, level), rec["truth"]).values()]


def solid_envelope(data: dict, level: str) -> tuple[float, float]:
    """The 3D level's groove bar: the envelope over the checked grooves."""
    return _outwards(solid_grid_errors(data, level))


def solid_measured_points(data: dict) -> list[tuple[float, float]]:
    """(D/d, ρ/d) of the checked grooves, each once: the 3D bars' hull."""
    return measured_points([p for p, _ in checked(data)])


def x2_57_solid_errors(data: dict, level: str) -> list[tuple[str, tuple[float, float, float]]]:
    """(softening, (error, low, high) %) of x2_57's collar groove by the 3D ``level``."""
    return [(soft, e) for soft in ("on", "off")
            for e in bars_grid.against_truth(data["x2_57"][soft]["solid"][level],
                                             data["x2_57"][soft]["truth"]).values()]


def _load() -> dict:
    return jsoncache.load(CACHE)


def _save(data: dict) -> None:
    jsoncache.save(CACHE, data)


def measure() -> dict:
    """Solve what the cache lacks (each solve is kept, so a run resumes where the last one
    stopped)."""
    data = _load()
    for q, k, w in grid():
        rec = data["points"].setdefault(_key(q, k, w), {"d/D": q, "rho/t": k, "width": w})
        D, t, rho, width = geometry(q, k, w)
        rec["D_t_rho_w_mm"] = [D, t, rho, width]
        v = grooved_bar(D, t, rho, width)
        if "truth" not in rec:
            rec["truth"] = _truth(v)
            print(f"{_key(q, k, w)} truth: {rec['truth']}", flush=True)
            _save(data)
        for lv in AXI_LEVELS:
            if lv not in rec.setdefault("axisymmetric", {}):
                rec["axisymmetric"][lv] = _axi(v, lv)
                print(f"{_key(q, k, w)} {lv}: {rec['axisymmetric'][lv]}", flush=True)
                _save(data)
        if "solid_fine" not in rec and rho >= SOLID_CHECK_RHO_MM:
            rec["solid_fine"] = _solid_fine(v)
            print(f"{_key(q, k, w)} 3D fine: {rec['solid_fine']}", flush=True)
            _save(data)
        for lv in SOLID_LEVELS[:-1] if rho >= SOLID_CHECK_RHO_MM else ():
            if lv not in rec.setdefault("solid", {}):
                rec["solid"][lv] = _solid(v, lv)
                print(f"{_key(q, k, w)} 3D {lv}: {rec['solid'][lv]}", flush=True)
                _save(data)
    for soft in ("on", "off"):
        rec = data.setdefault("x2_57", {}).setdefault(soft, {})
        for lv in ("truth", *AXI_LEVELS):
            if lv == "truth" and "truth" not in rec:
                rec["truth"] = _x2_57(None, soft == "on")
            elif lv != "truth" and lv not in rec.setdefault("axisymmetric", {}):
                rec["axisymmetric"][lv] = _x2_57(lv, soft == "on")
            else:
                continue
            print(f"x2_57 {soft} {lv}: done", flush=True)
            _save(data)
        for lv in SOLID_LEVELS:
            if lv not in rec.setdefault("solid", {}):
                rec["solid"][lv] = _solid(x2_57_grooved(), lv, X2_57_REGION, rigid=False,
                                          softening=soft == "on")
                print(f"x2_57 {soft} 3D {lv}: {rec['solid'][lv]}", flush=True)
                _save(data)
    return data


def errors(rec: dict, level: str) -> dict[str, tuple[float, float, float]]:
    """{quantity: (error %, low %, high %)}: 100 (value − truth) / truth at the axisymmetric
    ``level``, and the same widened by the truth's GCI bar (the shoulders' rule: a record of
    the same layout)."""
    return bars_grid.errors(rec, level, "axisymmetric")


_outwards = bars_grid._outwards          # the envelope, rounded outwards to 0.01 %


def grid_errors(data: dict, level: str) -> list[tuple[float, float, float]]:
    return [e for p in grid() for e in errors(data["points"][_key(*p)], level).values()]


def x2_57_errors(data: dict, level: str) -> list[tuple[str, str, tuple[float, float, float]]]:
    """(softening, quantity, (error, low, high) %) of x2_57's collar groove at ``level``."""
    return [(soft, q, e) for soft in ("on", "off")
            for q, e in errors(data["x2_57"][soft], level).items()]


def envelope(data: dict, level: str) -> tuple[float, float]:
    """The bar of ``level``: (low, high) % over the grid and x2_57's collar groove."""
    return _outwards(grid_errors(data, level) + [e for *_, e in x2_57_errors(data, level)])


def measured_points(points=None) -> list[tuple[float, float]]:
    """(D/d, ρ/d) of the grid's ``points`` (all by default), each once (both widths are
    measured at every one)."""
    out = []
    for q, k, _ in grid() if points is None else points:
        D, t, rho, _ = geometry(q, k, "2t")
        p = (round(D / (D - 2 * t), 6), round(rho / (D - 2 * t), 6))
        if p not in out:
            out.append(p)
    return out


def write(data: dict) -> dict:
    bars = {lv: envelope(data, lv) for lv in AXI_LEVELS}
    lines = ["# The axisymmetric levels' groove error bars over a grid of U grooves", "",
             "(generated by benchmarks/bench_groove_bars.py; 2-core machine shared with other "
             "jobs, wall-clock seconds)", "",
             f"Four-point bending of a Ø{D_BAR:g} bar with one U groove in constant moment, "
             "rigid simple supports; depth t = (D − d)/2, bottom corner radius ρ, width 2t (a "
             "flat bottom) or 2ρ (straight flanks). Truth: the axisymmetric model converged by "
             "Richardson over refinements 0, 1, 2 of its default mesh, ± its GCI bar; the "
             "levels: refinement 0. Error = 100 (level − truth) / truth. The truth is this "
             "method refined, so the bar is a discretisation error bar of the axisymmetric "
             "model, not an independent check (that is DIN 743-2's α in grooves.md and the 3D "
             "path of tests/validation/test_grooves.py).", "",
             "| d/D | ρ/t | width | D/t/ρ/w mm | truth max principal MPa | truth von Mises MPa "
             "| level | meridian nodes | s | error max principal | error von Mises |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for q, k, w in grid():
        rec = data["points"][_key(q, k, w)]
        D, t, rho, width = rec["D_t_rho_w_mm"]
        tr = rec["truth"]
        for lv in AXI_LEVELS:
            a = rec["axisymmetric"][lv]
            e = errors(rec, lv)
            lines.append(
                f"| {q:g} | {k:g} | {w} | {D:g}/{t:g}/{rho:g}/{width:g} | "
                f"{tr['max_principal'][0]:.3f} ± {tr['max_principal'][1]:.3f} | "
                f"{tr['von_mises'][0]:.3f} ± {tr['von_mises'][1]:.3f} | {lv} | {a['nodes']} | "
                f"{a['seconds']:.2f} | {e['max_principal'][0]:+.3f} % | "
                f"{e['von_mises'][0]:+.3f} % |")
    lines += ["", "## x2_57's collar groove against the grid", "",
              f"x2_57 with a U groove in the collar (x, width, depth, radius = {X2_57_GROOVE} "
              "mm; D/d 22/20, ρ/d 0.05, inside the grid's hull), 10 000 rpm, bearing springs, "
              "all parts, against its own truth (the same Richardson), checked against the "
              "grid's own envelope:", "",
              "| spin softening | level | quantity | error | inside the grid's envelope |",
              "|---|---|---|---|---|"]
    for lv in AXI_LEVELS:
        lo, hi = _outwards(grid_errors(data, lv))
        lines += [f"| {soft} | {lv} | {q} | {e[0]:+.3f} % | "
                  f"{'yes' if lo <= e[0] <= hi else 'NO'} |" for soft, q, e in
                  x2_57_errors(data, lv)]
    lines += ["", "## Bar per level (bending; what `shaftfe static` prints beside a groove peak "
              "of the axisymmetric model inside the measured grid)", "",
              "Each error widened by the truth's GCI bar; the envelope over the grid; written to "
              "reports/benchmarks/error_bars_grooves.json.", "",
              "| axisymmetric level | grid points | grid envelope | bar (grid and x2_57) |",
              "|---|---|---|---|"]
    for lv, (lo, hi) in bars.items():
        g_lo, g_hi = _outwards(grid_errors(data, lv))
        lines.append(f"| {lv} | {len(grid())} | {g_lo:+.2f} … {g_hi:+.2f} % | "
                     f"{lo:+.2f} … {hi:+.2f} % |")
    tsecs = sum(data["points"][_key(*p)]["truth"]["seconds"] for p in grid())
    lines += ["", f"Truth: {len(grid())} grooves, {tsecs:.0f} s in all."]
    se = solid_errors(data)
    lines += ["", "## The truth against an independent model", "",
              "The full 3D model (P2 tetrahedra, its own surface recovery) at `fine` on every "
              f"grid groove with ρ ≥ {SOLID_CHECK_RHO_MM:g} mm ({len(checked(data))} of "
              f"{len(grid())}: a smaller ρ's fine 3D mesh does not fit this machine), under the "
              "truth's options: 100 (3D − truth) / truth, max principal and von Mises, "
              f"{min(se):+.3f} … {max(se):+.3f} % (the 3D level's own discretisation "
              "included). What the bars above claim is the axisymmetric level's distance to its "
              "own converged value; that value is confirmed by a different model to this band, "
              "no closer.", "",
              "| d/D | ρ/t | width | 3D dofs | 3D s | max principal | von Mises |",
              "|---|---|---|---|---|---|---|"]
    for (q, k, w), rec in checked(data):
        sf, tr = rec["solid_fine"], rec["truth"]
        lines.append(f"| {q:g} | {k:g} | {w} | {sf['dofs']} | {sf['seconds']:.1f} | "
                     f"{100 * (sf['max_principal'] / tr['max_principal'][0] - 1):+.3f} % | "
                     f"{100 * (sf['von_mises'] / tr['von_mises'][0] - 1):+.3f} % |")
    solid = {lv: solid_envelope(data, lv) for lv in SOLID_LEVELS}
    lines += ["", "## The 3D levels' groove bars (`--model solid`)", "",
              f"The full 3D model at each level on the same {len(checked(data))} grooves (ρ ≥ "
              f"{SOLID_CHECK_RHO_MM:g} mm: {len(solid_measured_points(data))} (D/d, ρ/d) "
              "points), against the truth, each error widened by the truth's GCI bar: an "
              "independent model judged by the converged axisymmetric one. Written to "
              "reports/benchmarks/error_bars_grooves.json (`solid`, on these points' hull); "
              "x2_57's collar groove (not in the envelope: bearing springs, spin softening on "
              "and off, against its own truth) checks it where it was not measured.", "",
              "| 3D level | grooves | bar | x2_57's collar groove (errors) | inside |",
              "|---|---|---|---|---|"]
    for lv, (lo, hi) in solid.items():
        es = [e[0] for _, e in x2_57_solid_errors(data, lv)]
        x2 = ", ".join(f"{e:+.3f} %" for e in es)
        inside = "yes" if all(lo <= e <= hi for e in es) else "NO"
        lines.append(f"| {lv} | {len(checked(data))} | {lo:+.2f} … {hi:+.2f} % | {x2} | "
                     f"{inside} |")
    (OUT / "groove_bars.md").write_text("\n".join(lines) + "\n")
    _write_module(bars, measured_points(), solid, solid_measured_points(data))
    print("\n".join(lines))
    return bars


def _write_module(bars: dict, points, solid: dict, solid_points) -> None:
    from shaftfe.static.measured_errors import write_bars
    write_bars(BARS, "benchmarks/bench_groove_bars.py", LOAD,
               {"axisymmetric": bars, "solid": solid}, points, {"solid": solid_points})


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(prog="bench_groove_bars")
    ap.add_argument("--write", action="store_true", help="only write the outputs from the cache")
    a = ap.parse_args(argv if argv is not None else [])
    write(_load() if a.write else measure())


if __name__ == "__main__":
    import sys
    main(sys.argv[1:])
