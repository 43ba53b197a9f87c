"""The result tables the docs quote, computed by the project's own API so they cannot go stale.

    python docs/tables.py            # rewrite the tables in docs/*.md (make tables)
    python docs/tables.py modules    # rewrite the named tables only (here ARCHITECTURE.md's)
    python docs/tables.py --check    # exit 1 if a quoted table differs from a fresh run

Each table sits between ``<!-- table:NAME -->`` and ``<!-- /table -->`` in the file ``TABLES``
names (docs/VALIDATION.md, docs/STUDIES.md, docs/STRENGTH.md, docs/PERFORMANCE.md, and
docs/ARCHITECTURE.md's module index: ``python docs/tables.py modules`` makes that one alone). The
static solutions come from the cache (``shaftfe.static.cache``) when the model is unchanged, so a
second run takes seconds; a cold run solves x2_57 twice at the default level (≈ 30 s).
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"


def fatigue_x2_57() -> str:
    """x2_57, the seed's fatigue settings on loadspectra/rpm.dat, default mesh, both load cases,
    3D and axisymmetric, next to the seed's Ansys result (seed 000 §8.3)."""
    from shaftfe.fatigue.field import evaluate
    from shaftfe.fatigue.run import SEED, read_spectrum
    from shaftfe.fatigue.sn import load_material
    from shaftfe.model.loader import load_variant
    from shaftfe.static import solve as static_solve
    from shaftfe.static.model import StaticOptions, load_case_label
    from shaftfe.util.fmt import big as _big
    from shaftfe.util.paths import DEFAULT_SPECTRUM

    v = load_variant("x2_57")
    history = read_spectrum(str(DEFAULT_SPECTRUM), None, None)
    material = load_material("structural_steel")
    rows = [f"| seed (Ansys) | {SEED['hot_spot']} | {SEED['safety_factor_at_1e7']} | "
            f"{_big(SEED['life_blocks'])} blocks, {_big(SEED['life_hours'])} h, "
            f"{_big(SEED['life_km'])} km |"]
    for seed_case in (True, False):
        ref = static_solve.load_or_solve(v, StaticOptions(level="default",
                                                          seed_load_case=seed_case))
        hs = evaluate(ref, history, material).hot_spot
        rows.append(
            f"| shaftfe, {load_case_label(seed_case)} | {hs.region}, x = {hs.xyz_mm[0]:.1f} mm "
            f"({hs.sigma_eq_ref_MPa:.1f} MPa at {_big(ref.ref_rpm)} rpm) | "
            f"{hs.safety_factor:.3f} | {_big(hs.life_blocks)} blocks, {_big(hs.life_hours)} h, "
            f"{_big(hs.life_km)} km |")
    from shaftfe.axisymmetric.model import AxiOptions
    from shaftfe.axisymmetric.reference import static_reference
    from shaftfe.axisymmetric.solve import solve_axisymmetric
    for seed_case in (True, False):
        ref = static_reference(solve_axisymmetric(
            v, options=AxiOptions(level="default", seed_load_case=seed_case)))
        hs = evaluate(ref, history, material).hot_spot
        rows.append(
            f"| shaftfe `--model axisymmetric`, {load_case_label(seed_case)} | {hs.region}, "
            f"x = {hs.xyz_mm[0]:.1f} mm ({hs.sigma_eq_ref_MPa:.1f} MPa at "
            f"{_big(ref.ref_rpm)} rpm) | {hs.safety_factor:.3f} | {_big(hs.life_blocks)} "
            f"blocks, {_big(hs.life_hours)} h, {_big(hs.life_km)} km |")
    head = ("| | hot spot | safety factor at 10⁷ blocks | life |\n"
            "|---|---|---|---|")
    return head + "\n" + "\n".join(rows)


STUDY_DIR = ROOT / "reports" / "studies" / "x2_tradeoff"
STUDY_FILE = ROOT / "studies" / "x2_tradeoff.toml"


def study_x2_tradeoff() -> str:
    """The showcase study's recommended design (from its committed result table, re-ranked
    here by shaftfe.study.results) next to x2_57 evaluated by the same analyses now; the
    study file's requirements must be x2_57's own values (rounded to 0.1)."""
    import json

    from shaftfe.study import results
    from shaftfe.study.evaluate import evaluate_design
    from shaftfe.study.report import labels
    from shaftfe.study.spec import load_study
    spec = load_study(STUDY_FILE)
    df = results.read_table(STUDY_DIR)
    meta = json.loads((STUDY_DIR / "study.json").read_text())
    if meta["digest"] != spec.digest:
        raise SystemExit(f"{STUDY_DIR} was run on another version of {STUDY_FILE}: re-run "
                         "shaftfe study run studies/x2_tradeoff.toml")
    objs = results.default_objectives(spec)
    i = results.recommend(df, objs, spec.requirements)
    rec = df.iloc[i]
    base = evaluate_design(spec.base, (), spec.analyses)
    for col, _, val in spec.requirements:
        if round(base[col], 1) != val:
            raise SystemExit(f"{STUDY_FILE}: require {col} >= {val} is not x2_57's own value "
                             f"({base[col]:.1f}): update the study file")
    nd = results.non_dominated(df, objs)
    lab = labels(meta["analyses"])             # the fatigue rows name their method and card
    rows = [("X2 [%]", "X2_percent", "{:.1f}"), ("collar fillet [mm]", None, "{:.1f}"),
            ("counterweight outer radii [mm]", None, ""), ("balancer mass [kg]", "mass_kg",
                                                           "{:.3f}"),
            ("engine max\\|F\\| at 6000 rpm [N]", "engine_max_F_N", "{:.0f}"),
            ("engine RMS\\|F\\| at 6000 rpm [N]", "engine_rms_F_N", "{:.0f}"),
            ("collar fillet peak von Mises, 10 000 rpm [MPa]", "stress_fillet:collar_MPa",
             "{:.0f}"),
            (lab["fatigue_sf"], "fatigue_sf", "{:.3f}"), (lab["life_h"], "life_h", "{:.0f}"),
            (lab["life_km"], "life_km", "{:,.0f}"),
            ("L10h, free-side 3203 at 7000 rpm [h]", "L10h_min_h", "{:.0f}"),
            ("first critical speed, beam rotor [rpm]", "critical_rpm", "{:,.0f}")]
    r1 = "attachments.counterweight_1.shape.outer_radius_mm"
    r2 = "attachments.counterweight_2.shape.outer_radius_mm"
    from shaftfe.model.overrides import locate, normalise
    from shaftfe.model.parse import resolve_path, resolved_dict
    merged = resolved_dict(resolve_path(spec.base))

    def base_value(path):
        parent, key, _ = locate(merged, normalise({path: 0.0})[0])
        return float(parent[key])
    out = ["| | x2_57 (the seed's choice) | recommended: design "
           f"{int(rec['design'])} | change |", "|---|---|---|---|"]
    for label, col, fmt in rows:
        if col is None and "fillet" in label:
            a, b = base_value("segments.collar.fillet_mm"), float(rec["segments.collar.fillet_mm"])
            out.append(f"| {label} | {a:.1f} | {b:.1f} | |")
            continue
        if col is None:
            out.append(f"| {label} | {base_value(r1):.2f} / {base_value(r2):.2f} | "
                       f"{rec[r1]:.2f} / {rec[r2]:.2f} | |")
            continue
        a, b = float(base[col]), float(rec[col])
        ch = f"{100 * (b / a - 1):+.1f} %" if a else ""
        out.append(f"| {label} | {fmt.format(a)} | {fmt.format(b)} | {ch} |")
    n_ok = int((df["status"] == "ok").sum())
    out += ["", f"{len(df)} designs: {n_ok} evaluated, "
            f"{int((df['status'] == 'refused').sum())} refused (collar fillet above the "
            f"3203's r_s min 0.6 mm, ISO 582), {sum(nd)} non-dominated, "
            f"{sum(1 for k in range(len(df)) if nd[k] and results.meets(df, spec.requirements)[k])}"
            " of them meeting both requirements."]
    return "\n".join(out)


def truth_bars() -> str:
    """Each 3D and axisymmetric level's fillet error bar against the axisymmetric truth and the
    grid it was measured on (``static.measured_errors.shoulder_bars`` and ``groove_bars``, generated
    by benchmarks/bench_bars_grid.py and bench_groove_bars.py)."""
    from shaftfe.static.measured_errors import groove_bars, shoulder_bars
    sb = shoulder_bars()
    ERROR_BAR_PCT, AXI_ERROR_BAR_PCT = sb.bars["solid"], sb.bars["axisymmetric"]
    LOAD, MEASURED = sb.load, sb.measured

    def pct(x: float) -> str:
        return f"{x:+.2f}".replace("-", "−")

    out = [f"| model | level | error of the fillet peaks against the truth | measured on "
           f"({LOAD}) |", "|---|---|---|---|"]
    dd, rd = [p[0] for p in MEASURED], [p[1] for p in MEASURED]
    where = (f"{len(MEASURED)} shoulders, D/d {min(dd):g}–{max(dd):g}, r/d "
             f"{min(rd):g}–{max(rd):g}")
    for model, bars in (("3D (`--model solid`)", ERROR_BAR_PCT),
                        ("axisymmetric (the zoned solve's global model, `--model "
                         "axisymmetric`)", AXI_ERROR_BAR_PCT)):
        for level, (lo, hi) in bars.items():
            out.append(f"| {model} | `{level}` | {pct(lo)} … {pct(hi)} % | {where} |")
    gb = groove_bars()
    dd, rd = [p[0] for p in gb.measured], [p[1] for p in gb.measured]
    rt = [p[1] / ((p[0] - 1) / 2) for p in gb.measured]
    where = (f"{len(gb.measured)} (D/d, ρ/d) points of U grooves, each at the widths 2ρ and 2 "
             f"× depth where they differ, D/d {min(dd):.3g}–{max(dd):.3g}, corner radius / "
             f"depth {min(rt):.2g}–{max(rt):.2g}")
    for level, (lo, hi) in gb.bars["axisymmetric"].items():
        out.append(f"| axisymmetric, groove peaks | `{level}` | {pct(lo)} … {pct(hi)} % | "
                   f"{where} |")
    from benchmarks.bench_groove_bars import SOLID_CHECK_RHO_MM
    pts = gb.hull("solid") if "solid" in gb.bars else ()
    dd, rd = [p[0] for p in pts] or [0.0], [p[1] for p in pts] or [0.0]
    where = (f"{len(pts)} (D/d, ρ/d) points of the same U grooves (ρ ≥ "
             f"{SOLID_CHECK_RHO_MM:g} mm), both widths, "
             f"D/d {min(dd):.3g}–{max(dd):.3g}, ρ/d {min(rd):.3g}–{max(rd):.3g}")
    for level, (lo, hi) in gb.bars.get("solid", {}).items():
        out.append(f"| 3D (`--model solid`), groove peaks | `{level}` | {pct(lo)} … {pct(hi)} % "
                   f"| {where} |")
    return "\n".join(out)


def zone_bars() -> str:
    """The zoned solve's bars of the peaks inside its 3D zones, per feature and level, the grid
    they were measured on (``static.measured_errors.zone_feature_bars``, generated by
    benchmarks/bench_zone_bars.py), and the keyed Ø20 bar that the grid did not hold
    (benchmarks/bench_keyway_radius.py) against the bar the lookup gives it."""
    import json
    from types import SimpleNamespace

    from shaftfe.model.examples import keyed_bar
    from shaftfe.solid.plan import prepare
    from shaftfe.static.measured_errors import zone_bars as lookup
    from shaftfe.static.measured_errors import zone_feature_bars

    def pct(x: float) -> str:
        return f"{x:+.2f}".replace("-", "−")

    zb = zone_feature_bars()
    out = ["| feature in a 3D zone | zoned level | error of its peak against the full 3D model "
           "at a finer level | measured on |", "|---|---|---|---|"]
    k = zb.get("keyway")
    if k:
        rd, bd = [p[0] for p in k["measured"]], [p[1] for p in k["measured"]]
        where = (f"{len(k['measured'])} keyways 6 × 3.5 × 16 (DIN 6885-1; t1/b "
                 f"{k['t1_over_b'][0]:.3g}, l/d {k['l_over_d'][0]:.3g}–{k['l_over_d'][1]:.3g}) "
                 f"in bars of b/d {min(bd):.3g}–{max(bd):.3g}, r1/d {min(rd):g}–{max(rd):g}; "
                 f"{', '.join(k['loads'])}; reference: `fine`")
        for level, (lo, hi) in k["bars"]["zoned"].items():
            out.append(f"| rounded keyway | `{level}` | {pct(lo)} … {pct(hi)} % | {where} |")
    h = zb.get("cross_hole")
    if h:
        dd = [p[0] for p in h["measured"]]
        where = (f"{len(dd)} cross holes in a Ø20 bar, d_h/d {min(dd):g}–{max(dd):g}; "
                 f"{', '.join(h['loads'])}; reference: `fine` × 0.7")
        for level, (lo, hi) in h["bars"]["zoned"].items():
            out.append(f"| cross hole | `{level}` | {pct(lo)} … {pct(hi)} % | {where} |")
    if not k:
        return "\n".join(out)
    rows = json.loads((ROOT / "reports" / "benchmarks" / "keyway_radius.json")
                      .read_text())["bar"]
    ref = {(r["rho_mm"], r["load"]): r for r in rows
           if r["model"] == "solid" and r["level"] == "fine"}
    out += ["", "| not in the grid: the keyed Ø20 bar (b/d 0.3) | zoned level | its error "
            "against the full 3D model at `fine` | the bar the lookup gives it | inside |",
            "|---|---|---|---|---|"]
    key = "keyway:bar:0"
    for r in rows:
        if r["model"] != "zoned" or r["level"] not in k["bars"]["zoned"]:
            continue
        v = keyed_bar(r["load"], r["rho_mm"])
        bars, notes = lookup(v, prepare(v), r["level"], [SimpleNamespace(region=key)])
        d = v.segments[0].diameter_mm
        t = ref[(r["rho_mm"], r["load"])]
        es = [100.0 * (r[q] / t[q] - 1.0) for q in ("von_mises_MPa", "max_principal_MPa")]
        if key in bars:
            lo, hi = bars[key]
            bar = f"{pct(lo)} … {pct(hi)} %"      # rounded outwards when written: no margin
            inside = "yes" if all(lo <= e <= hi for e in es) else "NO"
        else:
            why = notes[key]
            bar = "none: " + ("its geometry outside the grid" if "convex hull" in why
                              else why.split(" (")[0])
            inside = "-"
        out.append(f"| r1 {r['rho_mm']:g} mm (r1/d {r['rho_mm'] / d:g}), {r['load']} | "
                   f"`{r['level']}` | von Mises {pct(es[0])} %, max principal {pct(es[1])} % | "
                   f"{bar} | {inside} |")
    return "\n".join(out)


def groove_truth_check() -> str:
    """The groove bars' truth against the full 3D model at ``fine``, over the grid
    (benchmarks/bench_groove_bars.py: reports/benchmarks/groove_bars.json)."""
    import json
    import sys
    sys.path.insert(0, str(ROOT))
    from benchmarks import bench_groove_bars as g
    data = json.loads((ROOT / "reports" / "benchmarks" / "groove_bars.json").read_text())
    se = g.solid_errors(data)
    dofs = [rec["solid_fine"]["dofs"] for _, rec in g.checked(data)]
    return ("| independent check of the groove truth | grooves | 3D dofs | 3D fine − truth |\n"
            "|---|---|---|---|\n"
            f"| full 3D model, `fine` (P2 tetrahedra, its own recovery) | "
            f"{len(dofs)} of {len(g.grid())} (ρ ≥ {g.SOLID_CHECK_RHO_MM:g} mm) | "
            f"{min(dofs)}–{max(dofs)} | {min(se):+.3f} … {max(se):+.3f} % |")


def zoned_speed() -> str:
    """``shaftfe static`` zoned against the full 3D model: whole processes side by side and
    the keyway peaks against the full 3D fine model (benchmarks/bench_zoned.py)."""
    import json
    d = json.loads((ROOT / "reports" / "benchmarks" / "zoned.json").read_text())
    acc, spd = d["accuracy"], d["speed"] or {}
    z, fine = acc["zoned"], acc["full"]["fine"]
    dofs = {"zoned (this tree, default)": sum(q["dofs"] for q in z["zones"]),
            "full 3D (this tree, --model solid)": acc["full"]["default"]["dofs"]}
    out = ["| command | model | warm s | paired / baseline | cold s | peak MiB (warm) | "
           "3D dofs |", "|---|---|---|---|---|---|---|"]
    what = {"static": "`shaftfe static --variant x2_57`", "fatigue": "`shaftfe fatigue "
            "loadspectra/rpm.dat`", "demo": "`make demo`"}
    for key, label in what.items():
        for name, r in spd.get(key, {}).items():
            pr = r["warm"].get("vs_baseline_paired")
            out.append(f"| {label} | {name} | {r['warm']['wall_s']:.2f} | "
                       f"{'-' if pr is None else f'{pr:.3f}'} | "
                       f"{r['cold']['wall_s']:.2f} | {r['warm']['max_rss_MiB']:.0f} | "
                       f"{dofs.get(name, '-') if key == 'static' else '-'} |")
    for model, r in spd.get("study design", {}).items():
        out.append(f"| a study design, new solid, `default` (warm process) | {model} | "
                   f"{r['median_s']:.2f} | - | - | - | {r['n_dofs']} |")
    out += ["", "| peak (von Mises) | zoned MPa | full 3D fine MPa | difference |",
            "|---|---|---|---|"]
    for reg, (vm, _, model, kind) in z["peaks"].items():
        if kind in ("keyway", "hex_socket") or (kind == "fillet" and model == "axisymmetric"):
            f = fine["peaks"][reg][0]
            out.append(f"| {reg} ({model}) | {vm:.2f} | {f:.2f} | {100 * (vm / f - 1):+.2f} % |")
    return "\n".join(out)


def fkm_gradient() -> str:
    """FKM's stress gradient at x2_57's span fillets by model and level against the finest
    axisymmetric value, and what it does to n_σ (benchmarks/bench_fkm_gradient.py)."""
    import json
    d = json.loads((ROOT / "reports" / "benchmarks" / "fkm_gradient.json").read_text())
    x = d["x2_57"]
    regs = list(x["converged"])
    out = ["| model, level | " + " | ".join(f"`{r}` G /mm (error)" for r in regs)
           + " | n_σ error |", "|---|" + "---|" * (len(regs) + 1)]
    from shaftfe.fatigue import fkm
    from shaftfe.fatigue.strength import StrengthOptions, strength_card
    from shaftfe.model.loader import load_variant
    g = fkm.GROUPS[strength_card(load_variant("x2_57"), StrengthOptions()).group]
    for r in x["rows"]:
        if r["level"] not in ("coarse", "default", "fine"):
            continue
        cells, dn = [], []
        for reg in regs:
            G, ref = r["fillets"][reg]["G"], x["converged"][reg]["value"]
            cells.append(f"{G:.2f} ({100 * (G / ref - 1):+.0f} %)")
            dn.append(100 * (r["fillets"][reg]["n_sigma"]
                             / fkm.support_factor(ref, x["rm_MPa"], g) - 1))
        out.append(f"| {r['model']}, `{r['level']}` | " + " | ".join(cells)
                   + f" | {min(dn):+.2f} … {max(dn):+.2f} % |")
    ref = ", ".join(f"{x['converged'][r]['value']:.2f} ± {x['converged'][r]['error']:.2f}"
                    for r in regs)
    out.append(f"\nReference: the axisymmetric `fine` level refined twice ({ref} /mm): a "
               "convergence measure of the discretisation, not an independent validation; "
               "that is tests/validation/test_fkm_gradient.py (exact on the Saint-Venant bar, "
               "DIN 743-2's shoulder formula as a 25 % band).")
    return "\n".join(out)


# table name -> (the file that quotes it, the function that computes it)
def groove_kt_fits() -> str:
    """The chart fits against the converged Kt of grooves: the ranges of
    reports/benchmarks/ring_grooves.json (benchmarks/bench_ring_grooves.py)."""
    import json
    d = json.loads((ROOT / "reports" / "benchmarks" / "ring_grooves.json").read_text(
        encoding="utf-8"))

    def span(rows, key) -> str:
        v = [100 * r[key] for r in rows]
        return f"{min(v):+.1f} … {max(v):+.1f} %"
    ring, u = d["ring"], d["u"]
    n_ring = len({(r["D_mm"], r["rho_mm"]) for r in ring})
    n_u = len({(r["D_mm"], r["d_mm"], r["rho_mm"]) for r in u})
    return "\n".join([
        "| grooves (tension, bending, torsion) | Roark shoulder fit | Roark U-notch fit | "
        "DIN 743-2 α (round groove) |", "|---|---|---|---|",
        f"| {n_u} U grooves (`kt_grooves.json`) | - | {span(u, 'roark_rel')} | "
        f"{span(u, 'din743_rel')} |",
        f"| {n_ring} DIN 471 grooves (`kt_ring_grooves.json`) | {span(ring, 'shoulder_rel')} | "
        f"{span(ring, 'roark_rel')} | {span(ring, 'din743_rel')} |"])


def keyway_radius() -> str:
    """A rounded keyway's peak per level against the full 3D model at fine, and its cost:
    reports/benchmarks/keyway_radius.json (benchmarks/bench_keyway_radius.py)."""
    import json
    d = json.loads((ROOT / "reports" / "benchmarks" / "keyway_radius.json").read_text(
        encoding="utf-8"))
    bar = d["bar"]
    out = ["| keyed Ø20 bar, r1 mm | model | level | dofs | s (bending, mesh made) | bending vM "
           "vs full 3D fine | torsion vM vs full 3D fine |", "|---|---|---|---|---|---|---|"]
    for rho in sorted({r["rho_mm"] for r in bar}):
        ref = {r["load"]: r for r in bar
               if (r["rho_mm"], r["model"], r["level"]) == (rho, "solid", "fine")}
        for model in ("solid", "zoned"):
            for level in ("coarse", "default", "fine"):
                rows = {r["load"]: r for r in bar
                        if (r["rho_mm"], r["model"], r["level"]) == (rho, model, level)}
                if not rows:
                    continue
                diff = {k: 100 * (rows[k]["von_mises_MPa"] / ref[k]["von_mises_MPa"] - 1)
                        for k in rows}
                b = rows["bending"]
                out.append(f"| {rho:g} | {'full 3D' if model == 'solid' else 'zoned'} | "
                           f"{level} | {b['dofs']} | {b['seconds']:.1f} | "
                           f"{diff['bending']:+.2f} % | {diff['torsion']:+.2f} % |")
    x2 = d["x2_57"]
    z = {r["keyways"]: r for r in x2 if r["model"] == "zoned"}
    out += ["", f"x2_57 zoned at `default`, warm in process: sharp-edged keyways "
            f"{z['sharp']['dofs']} zone dofs, {z['sharp']['seconds_warm']:.1f} s; with r1 "
            f"{d['rho_mm']:g} mm {z['r1 0.25']['dofs']} zone dofs, "
            f"{z['r1 0.25']['seconds_warm']:.1f} s."]
    return "\n".join(out)


# The pipeline's order, lowest first: a module imports only modules of its own package or of
# packages before its own, but the arrows docs/ARCHITECTURE.md names with their reasons
# (tests/test_architecture.py checks the import graph against it; "shaftfe" is the package's
# face, its version and a lazy table). The floors of ARCHITECTURE.md's module index.
PIPELINE = ("errors", "shaftfe", "util", "balance", "model", "solid", "fe", "beam",
            "machine_elements", "io", "static", "axisymmetric", "zoned", "rotordynamics",
            "fatigue", "report", "study", "commands", "cli", "__main__")


# words ending in a full stop that do not end a sentence (first-sentence cuts of docstrings)
ABBREVIATIONS = {"e.g", "i.e", "vs", "ch", "obr", "eq", "fig", "vol", "no", "cf", "al",
                 "approx", "ref", "sec", "tab"}


def _first_sentence(doc: str, limit: int = 220) -> str:
    """A docstring's first sentence, on one line (cut at ``limit`` characters)."""
    text = " ".join(doc.split("\n\n", 1)[0].split())
    for m in re.finditer(r"\.(\s|$)", text):
        word = re.search(r"(\S+)$", text[:m.start()])
        token = word.group(1).lstrip("([\"'").lower() if word else ""
        if token in ABBREVIATIONS or re.fullmatch(r"§\d+", token):
            continue                                   # "ch. 7", "(e.g. 1", "Fig. 3", "§5."
        if text[:m.start()].count("``") % 2 == 0:      # not inside a ``literal``
            text = text[:m.start() + 1]
            break
    if len(text) <= limit:
        return text
    cut = text[:limit].rsplit(" ", 1)[0]                               # at a word,
    if cut.count("``") % 2:                                           # not in a ``literal``
        cut = cut[:cut.rindex("``")].rstrip()
    return cut.rstrip(",;:(") + " …"


def modules() -> str:
    """docs/ARCHITECTURE.md's module index: every module of shaftfe, package by package from
    the top of ``PIPELINE`` down, with its docstring's first sentence (the docstrings are the
    description: a new module is listed when the index is made again)."""
    import ast
    pkg = ROOT / "shaftfe"
    groups: dict[str, list[tuple[str, str]]] = {}
    for p in sorted(pkg.rglob("*.py")):
        rel = p.relative_to(pkg)
        top = rel.parts[0] if len(rel.parts) > 1 else \
            ("shaftfe" if rel.stem == "__init__" else rel.stem)
        name = ".".join(rel.with_suffix("").parts)
        if name.endswith("__init__") and name != "__init__":
            continue                      # a package's face: its modules speak for it
        doc = ast.get_docstring(ast.parse(p.read_text(encoding="utf-8"))) or ""
        groups.setdefault(top, []).append((name if name != "__init__" else "shaftfe",
                                           _first_sentence(doc) if doc else "(no docstring)"))
    out = []
    for floor, top in sorted(enumerate(PIPELINE, 1), reverse=True):
        if top not in groups:
            raise SystemExit(f"docs/tables.py: the package {top!r} of PIPELINE has no module")
        where = f"`{top}/`" if (pkg / top).is_dir() else f"`{top}`"
        out.append(f"**floor {floor}: {where}**")
        out.append("")
        out += [f"- `{n}`: {d}" for n, d in groups.pop(top)]
        out.append("")
    if groups:
        raise SystemExit("docs/tables.py: packages not in PIPELINE: " + ", ".join(sorted(groups)))
    return "\n".join(out).rstrip() + "\n"


TABLES = {"fatigue-x2_57": (DOCS / "VALIDATION.md", fatigue_x2_57),
          "modules": (DOCS / "ARCHITECTURE.md", modules),
          "truth-bars": (DOCS / "VALIDATION.md", truth_bars),
          "groove-truth-check": (DOCS / "VALIDATION.md", groove_truth_check),
          "zone-bars": (DOCS / "VALIDATION.md", zone_bars),
          "study-x2_tradeoff": (DOCS / "STUDIES.md", study_x2_tradeoff),
          "zoned-speed": (DOCS / "PERFORMANCE.md", zoned_speed),
          "fkm-gradient": (DOCS / "STRENGTH.md", fkm_gradient),
          "groove-kt-fits": (DOCS / "STRENGTH.md", groove_kt_fits),
          "keyway-radius": (DOCS / "PERFORMANCE.md", keyway_radius)}


def render(path: Path, text: str, names=None) -> str:
    """``text`` (the content of ``path``) with each of its tables recomputed (those of
    ``names`` only, where given)."""
    for name, (where, make) in TABLES.items():
        if where != path or (names and name not in names):
            continue
        # the body up to the FIRST closing marker (an empty block too)
        pat = re.compile(rf"(<!-- table:{re.escape(name)} -->\n)(?:.*?)(<!-- /table -->)",
                         re.S)
        if not pat.search(text):
            raise SystemExit(f"{path.name}: marker <!-- table:{name} --> not found")
        body = make()
        text = pat.sub(lambda m, b=body: m.group(1) + b + "\n" + m.group(2), text)
    return text


def main(argv: list[str]) -> int:
    """``[NAME ...] [--check]``: every table, or the named ones (e.g. ``modules``)."""
    names = {a for a in argv if not a.startswith("-")}
    unknown = names - set(TABLES)
    if unknown:
        raise SystemExit(f"docs/tables.py: no table {', '.join(sorted(unknown))}; the tables: "
                         + ", ".join(TABLES))
    status = 0
    for path in sorted({where for name, (where, _) in TABLES.items()
                        if not names or name in names}):
        rel = path.relative_to(ROOT)
        old = path.read_text(encoding="utf-8")
        new = render(path, old, names)
        if "--check" in argv:
            if new != old:
                print(f"{rel}: the result tables are stale; run `make tables`", file=sys.stderr)
                status = 1
            else:
                print(f"{rel}: result tables are current")
        elif new != old:
            from shaftfe.util.atomic import write_atomic
            write_atomic(path, new)
            print(f"{rel}: tables rewritten")
        else:
            print(f"{rel}: tables already current")
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
