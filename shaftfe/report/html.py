"""Render a ``Report`` as one self-contained HTML page (stdlib only).

Images are embedded as ``data:image/png;base64`` URIs, so ``index.html`` alone is the report
(the same PNGs are also in ``figures/`` beside it, for slides). The markup is HTML5 that is also
well-formed XML (void elements self-closed, only the XML entities), so it can be checked with a
strict parser. Every number is formatted from the ``Report``; nothing is typed in here.
"""

from __future__ import annotations

import base64
import math
from html import escape

from shaftfe import __version__
from shaftfe.fatigue.strength_outputs import elements_lines
from shaftfe.report.seed import VARIANT
from shaftfe.rotordynamics.campbell import whirl_ratio_text
from shaftfe.solid.features import kind_of
from shaftfe.static.result import PEAK_FIT_LABEL  # what a static peak is (one definition)
from shaftfe.util.fmt import NO_FINITE_LIFE, life_reason

CSS = """
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,Arial,sans-serif;margin:0;
 color:#1d2327;background:#f4f5f7;line-height:1.45;font-size:15px}
main{max-width:1180px;margin:0 auto;padding:12px 28px 40px;background:#fff}
header{border-bottom:3px solid #2a5d8f;margin-bottom:8px}
h1{font-size:26px;margin:14px 0 4px}
h2{font-size:20px;margin:30px 0 8px;padding-top:8px;border-top:1px solid #d5d9de;color:#1f4b73}
h3{font-size:16px;margin:18px 0 6px}
p.meta{color:#555;margin:2px 0 10px;font-size:13px}
nav{font-size:13px;margin:6px 0 10px}
nav a{margin-right:12px;color:#2a5d8f;text-decoration:none}
table{border-collapse:collapse;margin:6px 0 12px;font-size:13.5px}
th,td{border:1px solid #d5d9de;padding:3px 8px;vertical-align:top}
th{background:#eef2f6;text-align:left;font-weight:600}
td.n{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
tr.group td{background:#f7f9fb;font-weight:600;color:#1f4b73}
td.good{color:#1d6b2f}td.bad{color:#a12b1f;font-weight:600}
.cards{display:flex;flex-wrap:wrap;gap:10px;margin:10px 0}
.card{border:1px solid #d5d9de;border-radius:6px;padding:8px 12px;min-width:150px;
 background:#fafbfc}
.card .v{font-size:20px;font-weight:600}.card .l{font-size:12px;color:#555;max-width:260px}
.card.good .v{color:#1d6b2f}.card.bad .v{color:#a12b1f}
.warnings{border:2px solid #c77c02;background:#fff6e0;border-radius:6px;padding:8px 14px;
 margin:10px 0}.warnings ul{margin:4px 0 0 18px;padding:0}
figure{margin:10px 0 18px}
figure img{max-width:100%;height:auto;border:1px solid #e1e4e8}
figure.narrow{max-width:720px}
figcaption{font-size:13px;color:#444;margin-top:3px}
.two{display:grid;grid-template-columns:1fr 1fr;gap:14px}
.note{font-size:13px;color:#555}
details{margin:6px 0}summary{cursor:pointer;color:#2a5d8f}
code{font-size:12.5px;background:#f1f3f5;padding:0 3px}
"""


# --------------------------------------------------------------------------- formatting

def num(v, digits: int = 4, unit: str = "", strip: bool = True) -> str:
    """A number with ``digits`` significant digits (trailing zeros stripped), thousands
    separated by a space; below 1e-3 in scientific notation."""
    if v is None:
        return "–"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, str):
        return v
    f = float(v)
    if math.isnan(f):
        return "–"
    if math.isinf(f):
        return "∞"
    if f == 0:
        s = "0"
    elif abs(f) >= 10 ** digits:
        s = f"{f:,.0f}".replace(",", " ")
    elif abs(f) < 1e-3:
        s = f"{f:.{max(digits - 2, 0)}e}"
    else:
        mag = math.floor(math.log10(abs(f)))
        dec = max(0, digits - 1 - mag)
        s = f"{f:,.{dec}f}".replace(",", " ")
        if strip and "." in s:
            s = s.rstrip("0").rstrip(".")
    return f"{s} {unit}".rstrip() if unit else s


def pct(v) -> str:
    if v is None:
        return "–"
    if abs(v) < 0.005:
        return "0.00 %"
    return f"{v:+.2f} %" if abs(v) < 0.995 else f"{v:+.1f} %"


def _e(s) -> str:
    return escape(str(s), quote=True)


def table(headers: list[str], rows: list[list], numeric: set[int] | None = None,
          classes: list[str | None] | None = None) -> str:
    numeric = numeric if numeric is not None else set()
    out = ["<table><thead><tr>"]
    out += [f"<th>{_e(h)}</th>" for h in headers]
    out.append("</tr></thead><tbody>")
    for k, r in enumerate(rows):
        cls = classes[k] if classes else None
        out.append(f'<tr class="{cls}">' if cls else "<tr>")
        if cls == "group":
            out.append(f'<td colspan="{len(headers)}">{_e(r[0])}</td></tr>')
            continue
        for i, c in enumerate(r):
            if isinstance(c, tuple):              # (text, css class)
                out.append(f'<td class="n {c[1]}">{_e(c[0])}</td>')
            elif i in numeric:
                out.append(f'<td class="n">{_e(c)}</td>')
            else:
                out.append(f"<td>{_e(c)}</td>")
        out.append("</tr>")
    out.append("</tbody></table>")
    return "".join(out)


def figure(report, name: str, narrow: bool = False) -> str:
    f = report.figure(name)
    if f is None:
        return ""
    data = base64.b64encode(f.png).decode("ascii")
    cls = ' class="narrow"' if narrow else ""
    return (f'<figure id="fig-{_e(f.name)}"{cls}><img src="data:image/png;base64,{data}" '
            f'alt="{_e(f.title)}"/><figcaption><b>{_e(f.title)}.</b> {_e(f.caption)} '
            f"(<code>figures/{_e(f.name)}.png</code>)</figcaption></figure>")


def card(value: str, label: str, cls: str = "") -> str:
    c = f"card {cls}".strip()
    return (f'<div class="{c}"><div class="v">{_e(value)}</div>'
            f'<div class="l">{_e(label)}</div></div>')


def life(blocks, hours=None) -> str:
    """A fatigue life an engineer can read: blocks and hours, or "no finite life at this load"
    with its reason (``util.fmt``: infinite, or beyond 10⁹ blocks or hours)."""
    why = life_reason(blocks, *(() if hours is None else (hours,)))
    if why:
        return f"{NO_FINITE_LIFE} ({why})"
    return num(blocks, 3, "blocks") + (f" = {num(hours, 3, 'h')}" if hours is not None else "")


def headline(r) -> dict:
    """The verdict of the default fatigue method (``strength.default_method``, FKM; DIN 743 where
    FKM has no field, i.e. the axisymmetric model): method, safety, utilisation, life, passes."""
    s = r.strength or {}
    if "fkm" in s:
        f = s["fkm"]
        g, rule = f["governing"], f["rule"]
        u = g["utilisation"][rule]
        return {"method": "FKM", "what": f"FKM local stress, card {f['card']}, Miner {rule}, "
                f"j_D {num(f['j_D'])}, {g['region']} ({g['layer']})",
                "safety": g["safety"][rule], "utilisation": u,
                "life_blocks": g["life_blocks"][rule], "life_hours": g["life_hours"][rule],
                "passes": u is not None and u <= 1.0}
    if "din743" in s:
        d = s["din743"]
        g = d["governing"]
        u = d["S_min"] / g["S_D"] if g["S_D"] else None
        return {"method": "DIN 743", "what": f"DIN 743 nominal stress, card {d['card']}, "
                f"{g['notch']}, S_min {num(d['S_min'])}", "safety": g["S_D"], "utilisation": u,
                "life_blocks": None, "life_hours": None, "passes": u is not None and u <= 1.0}
    return {}


def _banner(r) -> str:
    """The run's warnings (``shaftfe.util.notices``) above everything else."""
    if not r.warnings:
        return ""
    items = "".join(f"<li><b>{_e(w['where'])}</b>: {_e(w['text'])}</li>" for w in r.warnings)
    return (f'<div class="warnings" id="warnings"><b>{len(r.warnings)} warning'
            f'{"s" if len(r.warnings) != 1 else ""}: results outside the model\'s range</b>'
            f"<ul>{items}</ul></div>")


# --------------------------------------------------------------------------- sections

def _summary(r) -> str:
    st, camp = r.static, r.campbell
    c0 = st["cases"][0]
    worst_b = max(st["cases"][-1]["bearings"], key=lambda b: b["F_radial_N"])
    h = headline(r)
    low, i_low = min((min(row), i) for i, row in enumerate(camp["freq_hz"]))
    cards = []
    if h:
        ok = "passes" if h["passes"] else "FAILS"
        cards += [
            card(f"{num(h['utilisation'], 3, strip=False)}: {ok}",
                 f"{h['method']} degree of utilisation (≤ 1 passes), the default method of "
                 f"shaftfe fatigue; {h['what']}", "good" if h["passes"] else "bad"),
            card(num(h["safety"], 3, strip=False), f"{h['method']} safety factor"),
        ]
        if h["method"] == "FKM":
            cards.append(card(life(h["life_blocks"], h["life_hours"]),
                              f"FKM life at {num(r.fatigue['settings']['design_life_blocks'])}"
                              " blocks design life"))
    nodal = c0.get("peak_von_mises_node_MPa")
    cards += [
        card(num(c0["peak_von_mises_MPa"], 4, "MPa"),
             f"peak von Mises, {num(c0['rpm'])} rpm ({c0['peak_region']}), "
             + PEAK_FIT_LABEL + (f"; largest nodal value {num(nodal, 4)} MPa" if nodal else "")),
        card(num(worst_b["L10h"], 4, "h"),
             f"L10h {worst_b['name'].replace('_', ' ')}, {num(st['cases'][-1]['rpm'])} rpm"),
        card(num(camp["table"][0]["f0_hz"], 4, "Hz"),
             f"lowest natural frequency at 0 rpm; the lowest over the sweep, "
             f"{num(low, 4, 'Hz')}, is at {num(camp['rpm'][i_low])} rpm"),
        card(str(len(camp["criticals"])),
             f"critical speeds in {num(camp['rpm'][0])} to {num(camp['rpm'][-1])} rpm"),
    ]
    return ('<h2 id="summary">Summary</h2><div class="cards">' + "".join(cards) + "</div>"
            f'<p class="note">The seed method ({_e(r.fatigue["settings"]["material"])} S-N card, '
            f'{_e(r.fatigue["settings"]["mean_stress"])}) is in '
            '<a href="#strength">Strength by standard</a>'
            + (" and the seed comparison" if r.comparisons else "") + ".</p>"
            f'<p class="note">{_e(camp["statement"])}.</p>')




def _inputs(r) -> str:
    i, o, p = r.inputs, r.options, r.provenance
    rows = [["variant", f"{i['variant']}: {i['description']}"],
            ["files", ", ".join(i["files"])],
            ["content hash", i["content_hash"][:16] + "…"],
            ["overrides (--set)", ", ".join(f"{k} = {v}" for k, v in
                                            i.get("overrides", {}).items()) or "none"],
            ["shaft", f"length {num(i['length_mm'])} mm, {i['material']}, E "
                      f"{num(i['E_MPa'])} MPa, ν {num(i['nu'], 3)}"],
            ["engine", f"{i['engine']} ({i['engine_file']})" if i["engine"]
             else "none (the variant's [duty] names none: no balancing)"],
            ["rpm history", i["spectrum"]],
            ["design speeds", ", ".join(f"{num(x)} rpm" for x in i["design_rpm"])],
            ["Campbell range", f"{num(i['campbell_range_rpm'][0])} to "
                               f"{num(i['campbell_range_rpm'][1])} rpm, step "
                               f"{num(o.campbell_step_rpm)} rpm, {o.modes} modes, orders "
                               + ", ".join(f"{k:g}×" for k in o.orders)],
            _mesh_row(r.static),
            ["supports / load case", f"{r.static['supports']}; {r.static['load_case']}"]]
    s = '<h2 id="inputs">Inputs and what is reconstructed</h2>'
    s += table(["input", "value"], rows)
    s += "<h3>Bearings and parts</h3>"
    s += table(["bearing", "type", "x [mm]", "C [N]", "K11 / K12 [N/mm]", "axial"],
               [[b["name"], b["designation"], num(b["x_mm"]), num(b["C_N"], 5),
                 f"{num(b['K_N_per_mm'][0][0], 5)} / {num(b['K_N_per_mm'][0][1], 5)}",
                 num(b["axial"])] for b in i["bearings"]], numeric={2, 3})
    rpms = i["design_rpm"]
    slc = any(a["seed_load_case"] for a in i["attachments"])   # the column where it means one
    s += table(["part", "m [kg]", "e [mm]", "seat x [mm]"]
               + (["loads the shaft (seed case)"] if slc else [])
               + [f"m e ω² at {num(x)} rpm [N]" for x in rpms],
               [[a["name"], num(a["mass_kg"], 4), num(a["eccentricity_mm"], 4),
                 num(a["x_mm"])] + ([num(a["seed_load_case"])] if slc else [])
                + [num(a["force_N"][f"{x:g}"], 4) for x in rpms] for a in i["attachments"]],
               numeric={1, 2, 3, *range(4 + slc, 4 + slc + len(rpms))})
    if i.get("spectrum_comments"):
        s += (f"<p class=\"note\">The rpm history <code>{_e(i['spectrum'])}</code> says of "
              f"itself: “{_e(' '.join(i['spectrum_comments']))}”</p>")
    counts = ", ".join(f"{n} {t}" for t, n in sorted(p["counts"].items()))
    s += ("<h3>Provenance of the drawing parameters</h3>"
          f"<p>Every numeric value of the variant files is tagged: {_e(counts)}."
          + (" The drawings' dimensions did not survive in the seed, so the geometry is "
             "reconstructed to reproduce the seed's facts; "
             f"<code>{_e(p['document'])}</code> says how each value was fitted and to what."
             if p.get("seed_geometry") else "") + "</p>"
          f"<details><summary>the {len(p['reconstructed'])} reconstructed values</summary>"
          f"<p class=\"note\">{_e(', '.join(p['reconstructed']))}</p></details>")
    return s


def _balancing(r) -> str:
    b = r.balancing
    if b is None:
        return ""
    m = b["metrics"]
    s = ('<h2 id="balancing">Balancing</h2>'
         f"<p>{_e(b['engine'])} at {num(b['rpm'])} rpm (tilt {num(b['tilt_deg'])}°), "
         f"crank X = {num(b['X_percent'], 3)} %, balancer X2 = {num(b['X2_percent'], 4)} % "
         "(this variant's mass properties), first-order amplitude m_pos R ω² = "
         f"{num(b['first_order_amplitude_N'], 4)} N.</p>")
    s += table(["metric (engine frame)", "value [N]", "crank angle [°]"],
               [["max|Fx|", num(m["max_abs_fx"], 5), num(m["max_abs_fx_deg"], 4)],
                ["max|Fy|", num(m["max_abs_fy"], 5), num(m["max_abs_fy_deg"], 4)],
                ["RMS|F|", num(m["rms_f"], 5), "–"],
                ["max|F|", num(m["max_f"], 5), num(m["max_f_deg"], 4)]], numeric={1, 2})
    sm = b["sweep_minima"]
    labels = {"max_abs_fx": "max|Fx|", "max_abs_fy": "max|Fy|", "rms_f": "RMS|F|",
              "max_f": "max|F|"}
    s += table(["metric, minimum over X2 (crank C, cylinder frame)", "minimum [N]",
                "at X2 [%]"],
               [[labels.get(k, k), num(v["value_N"], 5), num(v["at_X2_percent"], 3)]
                for k, v in sm.items()], numeric={1, 2})
    s += figure(r, "balance_forces") + figure(r, "balance_sweep", narrow=True)
    return s


def _mesh_row(st: dict) -> list[str]:
    if st.get("model") == "zoned":
        return ["meshes", f"meridian P2 {st['global_level']}, {num(st['n_nodes'])} nodes, "
                f"harmonics n = {', '.join(str(n) for n in st['harmonics'])}; "
                + "; ".join(f"3D zone {z['name']}: P2 {st['level']}, {num(z['n_dofs'])} dofs"
                            for z in st["zones"])]
    if st.get("model") == "axisymmetric":
        return ["meridian mesh", f"P2 {st['level']}, {num(st['n_nodes'])} nodes, "
                f"{num(st['n_elements'])} triangles, harmonics n = "
                f"{', '.join(str(n) for n in st['harmonics'])} ({num(st['n_dofs'])} dofs in "
                "all)"]
    return ["3D mesh", f"P{st['order']} {st['level']}, {num(st['n_nodes'])} nodes, "
            f"{num(st['n_elements'])} tets, {num(st['n_dofs'])} dofs"]


def _static(r) -> str:
    st = r.static
    if st.get("model") == "zoned":
        zones = "; ".join(
            f"{_e(z['name'])} (x {num(z['x_mm'][0])} to {num(z['x_mm'][1])} mm, "
            f"{num(z['n_dofs'])} dofs, cut check {num(z['cut_check_percent'], 2)} %)"
            for z in st["zones"])
        head = (f"<p>Zoned solve at each design speed: the shaft as a body of revolution "
                f"(Fourier harmonics n = 0 … {st['harmonics'][-1]} on a P2 meridian mesh, "
                f"{st['global_level']}, {_e(st['solver'])}) gives the reactions, deflections "
                "and every round notch; a 3D P2 submodel in each zone where the shaft is not "
                f"round, driven at its cuts by the global field: {_e(zones)}. The cut check "
                "compares the submodel's stresses at its cut with the global ones (a zone grows "
                "while it exceeds 10 %). The keyways' and hex socket's effect on the stiffness "
                f"is not in the global model. {_e(st['supports'])}; {_e(st['load_case'])}. "
                "Peaks are located on the surface-recovered stress; the seat ends and the "
                "pressure edges are left out.</p>")
    elif st.get("model") == "axisymmetric":
        omitted = ", ".join(f"{f['feature']} (x {num(f['zone_mm'][0])} to "
                            f"{num(f['zone_mm'][1])} mm)" for f in st["omitted_features"])
        head = (f"<p>One axisymmetric solve at {num(st['ref_rpm'])} rpm: the shaft as a body "
                f"of revolution in Fourier harmonics n = 0 … {st['harmonics'][-1]} on a P2 "
                f"meridian mesh ({st['level']}, {num(st['n_dofs'])} dofs in all, "
                f"{_e(st['solver'])}, relative residual {st['relative_residual']:.1e}); every "
                f"speed is that solution × (n / {num(st['ref_rpm'])})². {_e(st['supports'])}; "
                f"{_e(st['load_case'])}. Left out: {_e(omitted)}; a peak in such a zone needs "
                "the 3D model. Peaks are located on the surface-recovered stress; the seat "
                "ends and the pressure edges are left out.</p>")
    else:
        head = (f"<p>One 3D solve at {num(st['ref_rpm'])} rpm (P{st['order']} {st['level']}, "
                f"{num(st['n_dofs'])} dofs, solver {_e(st['solver'])}, relative residual "
                f"{st['relative_residual']:.1e}); every speed is that solution × (n / "
                f"{num(st['ref_rpm'])})². {_e(st['supports'])}; {_e(st['load_case'])}. Peaks "
                f"exclude {num(st['n_excluded_nodes'])} singular nodes (one element layer at "
                "the edges of the bearing couplings and load patches; the unfiltered value is "
                "shown beside).</p>")
    s = '<h2 id="static">Static: stress, deflection, reactions</h2>' + head
    s += '<div class="two">' + figure(r, "von_mises_3d") + figure(r, "displacement_3d") + "</div>"
    s += figure(r, "deflection", narrow=True)
    s += "<h3>Bearing reactions and lives (ISO 281 basic, p = 3)</h3>"
    rows = []
    for c in st["cases"]:
        beam = {b["name"]: b for b in c["beam_springs"].get("bearings", [])}
        for b in c["bearings"]:
            bb = beam.get(b["name"], {})
            rows.append([num(c["rpm"]), b["name"], num(b["x_mm"]), num(b["F_radial_N"], 5),
                         num(bb.get("F_N"), 5), num(b["C_N"], 5), num(b["L10h"], 4),
                         num(b["uy_mm"] * 1e3, 4)])
    s += table(["speed [rpm]", "bearing", "x [mm]",
                f"radial load, {_LOAD_MODEL.get(st.get('model'), '3D')} FE [N]",
                "radial load, beam [N]", "C [N]", "L10h [h]", "bearing u_y [µm]"], rows,
               numeric={0, 2, 3, 4, 5, 6, 7})
    s += "<h3>Deflections</h3>"
    rows = []
    for c in st["cases"]:
        for x in c["stations"]:
            rows.append([num(c["rpm"]), x["name"], num(x["x_mm"]), num(x["u_mm"] * 1e3, 4)])
        for k, v in c["relative_deflection_mm"].items():
            rows.append([num(c["rpm"]), f"{k}, relative to the bearing line", "–",
                         num(v * 1e3, 4)])
        rows.append([num(c["rpm"]), "max nodal |u_yz|", num(c["max_deflection_xyz_mm"][0]),
                     num(c["max_deflection_mm"] * 1e3, 4)])
    s += table(["speed [rpm]", "station", "x [mm]", "deflection [µm]"], rows,
               numeric={0, 2, 3})
    c0 = st["cases"][0]
    s += f"<h3>Peak von Mises stress per region, {num(c0['rpm'])} rpm</h3>"
    bars = st.get("truth_error_bar_pct") or {}
    rows = [[p["region"], num(p["von_mises_MPa"], 4), num(p["xyz_mm"][0]),
             num(p["von_mises_unfiltered_MPa"], 4),
             f"{bars[p['region']][0]:+.2f} … {bars[p['region']][1]:+.2f}"
             if p["region"] in bars else "–"]
            for p in sorted(c0["peaks"], key=lambda p: -(p["von_mises_MPa"] or 0))
            if kind_of(p["region"]) != "end"]
    s += table(["region", "von Mises [MPa]", "x [mm]", "unfiltered [MPa]",
                "error vs truth [%]"], rows, numeric={1, 2, 3})
    why = st.get("truth_bar_notes") or {}
    if bars or why:
        whose = (f"the 3D {st['level']} level's" if st["model"] == "solid" else
                 f"the axisymmetric {st.get('global_level', st['level'])} level's (its own "
                 "method refined: a discretisation bar)")
        what, grids = ("span fillet's or groove's peak", "grids of shoulders and of U "
                       "grooves (reports/benchmarks/bars_grid.md, groove_bars.md)")
        s += (f"<p>error vs truth: {escape(whose)} measured error of a {what} against the "
              f"converged axisymmetric solution over {grids} in bending; none where it was "
              "not measured.</p>")
        if any(kind_of(r) in ("keyway", "cross_hole") for r in bars):
            s += ("<p>A 3D zone's rounded keyway or cross hole: the zone level's measured error "
                  "against the full 3D model at a finer level (keyways: fine; cross holes: fine "
                  "× 0.7), over a grid of keyways and one of cross holes "
                  "(reports/benchmarks/zone_bars.md).</p>")
        if why:
            s += "<ul>" + "".join(f"<li>{escape(r)}: {escape(w)}</li>"
                                  for r, w in why.items()) + "</ul>"
    return s


def _fatigue(r) -> str:
    f = r.fatigue
    h, hs, raw = f["history"], f["hot_spot"], f["hot_spot_unfiltered"]
    st = f["settings"]
    s = ('<h2 id="fatigue">Fatigue</h2>'
         f"<p>{_e(h['source'])}: {num(h['samples'])} samples, {num(h['duration_s'])} s per "
         f"block, {num(h['rpm_min'])}-{num(h['rpm_max'])} rpm. The same static solution × load "
         f"factor (n / {num(h['static_ref_rpm'])})² (range {num(h['load_factor_min'], 3)}-"
         f"{num(h['load_factor_max'], 3)}); rainflow counted once ({num(f['cycles_per_block'])} "
         f"cycles per block, {f['cycle_classes']} classes, {_e(f['closure'])} block); "
         f"{_e(st['equivalent'])}, {_e(st['mean_stress'])}, {_e(st['material'])} (yield "
         f"{num(st['yield_MPa'])} MPa, endurance {num(st['endurance_MPa'], 4)} MPa), Miner. "
         f"Hot spot: {_e(hs['region'])} at x = {num(hs['xyz_mm'][0])} mm, σ_eq = "
         f"{num(hs['sigma_eq_ref_MPa'], 4)} MPa at {num(h['static_ref_rpm'])} rpm.</p>")
    rows = [["hot spot (singular points excluded)", num(hs["life_blocks"], 4),
             num(hs["life_hours"], 4), num(hs["life_km"], 4), num(hs["safety_factor"], 3)],
            [f"unfiltered minimum ({raw['region']}, x = {num(raw['xyz_mm'][0])} mm"
             f"{', excluded' if raw['excluded'] else ''})", num(raw["life_blocks"], 4),
             num(raw["life_hours"], 4), num(raw["life_km"], 4), num(raw["safety_factor"], 3)]]
    lc = f.get("life_if_peak_corrected")
    if lc:
        rows.append([f"hot spot, stress × {lc['factor']:.4f} (estimated mesh error removed)",
                     num(lc["life_blocks"], 4), num(lc["life_hours"], 4),
                     num(lc["life_km"], 4), num(lc["safety_factor"], 3)])
    s += table(["", "life [blocks]", "life [h]", f"life [km] at {num(st['speed_kmh'])} km/h",
                f"safety factor at {num(st['design_life_blocks'])} blocks [-]"], rows,
               numeric={1, 2, 3, 4})
    s += '<div class="two">' + figure(r, "safety_factor_3d") + figure(r, "load_history") + "</div>"
    s += ('<div class="two">' + figure(r, "rainflow_matrix") + figure(r, "damage_matrix")
          + "</div>")
    s += '<div class="two">' + figure(r, "haigh") + figure(r, "sn_curve") + "</div>"
    s += "<h3>Per region (singular points excluded)</h3>"
    s += table(["region", "x [mm]", "σ_eq at ref [MPa]", "life [blocks]", "safety factor [-]"],
               [[x["region"], num(x["xyz_mm"][0]), num(x["sigma_eq_ref_MPa"], 4),
                 num(x["life_blocks"], 4), num(x["safety_factor"], 3)]
                for x in sorted(f["regions"], key=lambda x: x["safety_factor"] or 0)],
               numeric={1, 2, 3, 4})
    return s


def _campbell(r) -> str:
    c = r.campbell
    s = ('<h2 id="campbell">Rotor dynamics: Campbell diagram</h2>'
         f"<p>{_e(c['description'])}; {num(c['n_dof'])} dofs; {len(c['rpm'])} speeds from "
         f"{num(c['rpm'][0])} to {num(c['rpm'][-1])} rpm; reduced basis of {c['basis_size']} "
         f"modes; smallest tracking MAC {c['tracking_mac_min']:.3f}. {_e(c['statement'])}.</p>")
    s += figure(r, "campbell")
    top = num(c["rpm"][-1])
    s += table(["mode", "f at 0 rpm [Hz]", f"f at {top} rpm [Hz]", "whirl", "family",
                f"whirl ratio at {top} rpm [-]", "bearing strain-energy share at 0 rpm [-]"],
               [[t["mode"], num(t["f0_hz"], 5), num(t["f_top_hz"], 5), t["whirl"], t["family"],
                 whirl_ratio_text(t["whirl_ratio_top"], t["family"]),
                 num(t["bearing_energy_share"], 3) if t["bearing_energy_share"] >= 1e-3
                 else "< 0.001"]
                for t in c["table"]], numeric={0, 1, 2, 5, 6})
    if c["criticals"]:
        s += table(["order", "mode", "critical speed [rpm]", "frequency [Hz]", "whirl"],
                   [[f"{k['order']:g}×", k["mode"], num(k["rpm"], 5), num(k["freq_hz"], 5),
                     k["whirl"]] for k in c["criticals"]], numeric={1, 2, 3})
    return s


def _comparison(r) -> str:
    if not r.comparisons:                     # a shaft that is not the seed's
        return ""
    s = ('<h2 id="seed">Seed figures next to ours</h2><p class="note">Seed figures from '
         "<code>shaftfe/report/seed.py</code> (and the variant file's seed-tagged balance "
         "table); ours from this run. Difference = ours / seed − 1.</p>")
    if not r.static.get("load_case", "").startswith("seed"):
        s += ('<p class="note"><b>Load case:</b> this run loads every part of the variant '
              "(the default of every command), while the seed's static and fatigue figures "
              "load only F1 (gear + counterweight 1) and Fv2 (counterweight 2): the screws, "
              "keys, nuts and washers it left out shift the reactions and stresses. Run "
              "<code>shaftfe report --seed-load-case</code> (what <code>shaftfe demo</code> "
              "does) to compare like with like.</p>")
    rows, classes = [], []
    group = model = None
    for c in r.comparisons:
        if c.group != group:
            group, model = c.group, None
            rows.append([group])
            classes.append("group")
        d = c.diff_percent
        cls = "" if d is None else ("good" if abs(d) <= 5 else "bad")
        how = "same as above" if c.model == model else c.model
        model = c.model
        rows.append([c.quantity, c.unit, num(c.seed, 5), num(c.ours, 5), (pct(d), cls),
                     how + (f"; {c.note}" if c.note else "")])
        classes.append(None)
    s += table(["quantity", "unit", "seed", "shaftfe", "difference", "how ours was computed"],
               rows, numeric={2, 3}, classes=classes)
    if r.inputs["variant"] != VARIANT:
        s += (f'<p class="note">The seed\'s static, fatigue and rotor-dynamics figures are of '
              f"variant {_e(VARIANT)}; for {_e(r.inputs['variant'])} only the balancing and "
              "the variant's own balance table are compared.</p>")
    s += ('<p class="note">Green: within 5 %; red: more. Why the large ones differ (stress '
          "with and without the notch, the reconstructed fillet radius, the invented part of "
          "the rpm history, the beam rotor model against the seed's 3D Ansys model): "
          "docs/VALIDATION.md.</p>")
    return s


def _errors(r) -> str:
    s = '<h2 id="errors">Error estimate of each FE quantity</h2>'
    s += table(["quantity", "value", "unit", "estimated error", "how"],
               [[e.quantity, num(e.value, 5), e.unit, e.error, e.method] for e in r.errors],
               numeric={1})
    return s


def _timing(r) -> str:
    total = sum(t for _, t in r.timings)
    s = '<h2 id="timing">Run time</h2>'
    s += table(["stage", "wall time [s]", "share [%]"],
               [[n, f"{t:.2f}", f"{100 * t / total:.0f}" if total else "–"]
                for n, t in r.timings] + [["total", f"{total:.2f}", "100"]], numeric={1, 2})
    sub = r.sub_timings
    rows = [[k, "yes" if v else "no"] if isinstance(v, bool) else [k, num(v, 3)]
            for k, v in sub.items()]
    s += "<h3>Inside the static and fatigue stages [s]</h3>"
    s += table(["step", "wall time [s]"], rows, numeric={1})
    m = r.machine
    load = m.get("load_average_1_5_15")
    s += (f'<p class="note">Machine: {m.get("cpus")} CPUs, {_e(m.get("platform"))}, Python '
          f"{_e(m.get('python'))}; load average at the start "
          f"{', '.join(f'{x:.2f}' for x in load) if load else '–'} (1, 5, 15 min).</p>")
    return s


_LOAD_MODEL = {"axisymmetric": "axisymmetric", "zoned": "zoned (axisymmetric global)"}


def _files(r) -> str:
    f = r.files
    s = ('<h2 id="files">Result files</h2>'
         f"<p><code>{_e(f['vtu'])}</code>: "
         + {"axisymmetric": "the revolved surface of the axisymmetric model (triangles; no "
                            "volume)",
            "zoned": "the zoned model's surface (the axisymmetric model's revolved surface, "
                     "the 3D zones' free surfaces; triangles, no volume)"}.get(
                r.static.get("model"), "the 3D mesh")
         + " with point data <code>displacement</code> "
         "[mm], <code>von_mises</code>, <code>max_principal</code>, <code>stress</code> (xx, yy, "
         f"zz, xy, yz, xz) [MPa] at {num(f['vtu_rpm'])} rpm, and <code>safety_factor</code> [-], "
         "<code>life_blocks</code> [blocks], <code>damage_per_block</code> [-] of the fatigue "
         "study; cell data <code>region</code> (0 volume, k = regions[k − 1] in "
         "<code>summary.json</code>)"
         + (f". <code>{_e(f['modes_vtu'])}</code>: the mode shapes of the Campbell model at "
            f"{num(f['mode_rpm'])} rpm as <code>mode_k_fHz</code> [-]"
            + (f" (e.g. <code>{_e(f['mode_fields'][0])}</code>)" if f.get("mode_fields")
               else "") + f", {_e(f['mode_note'])}" if f.get("modes_vtu") else "")
         + ". Open them in ParaView or with "
         f"<code>shaftfe view {_e(f['vtu'])} --field safety_factor</code>; field names and "
         "units: docs/FIELDS.md. <code>summary.json</code>: every number of this page.</p>")
    return s


def _notes(r) -> str:
    notes = list(r.notes) + list(r.static.get("notes", [])) + list(r.fatigue.get("notes", [])) \
        + list(r.campbell.get("notes", []))
    notes = list(dict.fromkeys(notes))
    if not notes:
        return ""
    return ('<h2 id="notes">Notes</h2><ul>' + "".join(f"<li>{_e(n)}</li>" for n in notes)
            + "</ul>")


SECTIONS = (("summary", "Summary"), ("inputs", "Inputs"), ("balancing", "Balancing"),
            ("static", "Static"), ("fatigue", "Fatigue"), ("strength", "Strength by standard"),
            ("campbell", "Campbell"),
            ("seed", "Seed vs ours"), ("errors", "Errors"), ("timing", "Run time"),
            ("files", "Files"))


def _strength(r) -> str:
    """Three methods side by side, the bearings over the duty cycle, keys and gears."""
    s = r.strength
    if not s:
        return ""
    fat = r.fatigue["hot_spot"]
    ref = num(r.fatigue["history"]["static_ref_rpm"])
    st = r.fatigue["settings"]
    rows = [(f"seed (Ansys-style: von Mises, {_e(st['mean_stress'])}, S-N card "
             f"{_e(st['material'])})",
             num(fat["safety_factor"], 3, strip=False), "-",
             life(fat["life_blocks"], fat["life_hours"]),
             f"{num(fat['sigma_eq_ref_MPa'], 4)} at x = {num(fat['xyz_mm'][0])} mm: the node of "
             "least seed safety (nodal value)")]
    if "fkm" in s:
        g = s["fkm"]["governing"]
        rule = s["fkm"]["rule"]
        gr = next((x for x in s["fkm"]["regions"] if x["region"] == g["region"]), None)
        hot = (f"{num(gr[g['layer']]['sigma_ref_MPa'], 4)} at x = {num(gr['xyz_mm'][0])} mm: the "
               "node of highest FKM utilisation (nodal signed von Mises: the stress gradient and a "
               "tensile mean count, so not always the node of the largest stress)") if gr else "–"
        rows.append((f"FKM local, card {_e(s['fkm']['card'])} ({_e(g['region'])}, {g['layer']}; "
                     f"Miner {rule}; j_D {num(s['fkm']['j_D'])}) — the default",
                     num(g["safety"][rule], 3, strip=False),
                     num(g["utilisation"][rule], 3, strip=False),
                     life(g["life_blocks"][rule], g["life_hours"][rule]), hot))
    d, s_min = s["din743"]["governing"], s["din743"]["S_min"]
    rows.append((f"DIN 743 nominal, beam ({_e(d['notch'])}; S_min {num(s_min)})", num(d["S_D"], 3),
                 num(s_min / d["S_D"], 3) if d["S_D"] else "-", "fatigue limit (no life)",
                 "nominal beam stress × notch factors"))
    c0 = r.static["cases"][0]
    html = ('<h2 id="strength">Strength by standard</h2>'
            "<p>The default of <code>shaftfe fatigue</code> is <b>FKM</b>: it judges the local "
            "stress of the static field with the shaft's own material (card "
            f"{_e(s['din743']['card'])}), surface and stress gradient, as an FE user signs a "
            f"shaft. The seed method takes the S-N card {_e(st['material'])} (yield "
            f"{num(st['yield_MPa'])} MPa) with its {_e(st['mean_stress'])} correction; DIN 743 "
            "judges nominal beam "
            "stresses with tabulated notch factors at the fatigue limit of one cycle (the "
            "history's largest), so it gives no life. They differ because they judge different "
            "materials and different stresses, not because one is wrong.</p>"
            f'<p class="note">One stress field, three readings of its peak at {ref} rpm: the '
            f"static peak {num(c0['peak_von_mises_MPa'], 4)} MPa is the {PEAK_FIT_LABEL} "
            "(largest nodal value "
            f"{num(c0.get('peak_von_mises_node_MPa'), 4)} MPa); each method below reads the "
            "nodal value at its own hot spot. All include spin softening when it is on.</p>"
            "<table><tr><th>method</th><th>safety factor</th><th>degree of utilisation</th>"
            f"<th>life</th><th>hot-spot stress at {ref} rpm [MPa]</th></tr>"
            + "".join(f"<tr><td>{a}</td><td>{b}</td><td>{c}</td><td>{e}</td><td>{_e(h)}</td>"
                      "</tr>" for a, b, c, e, h in rows) + "</table>")
    # each standard at every cross-section of the shaft (``shaftfe fatigue --plot``'s)
    html += figure(r, "fkm_along") + figure(r, "din743_along")
    el = s["elements"]
    what = "Bearings (ISO 281)" + (", keys" if el.get("keys") else "") + \
        (" and gear pair" if el.get("gear") else "")
    html += f"<h3>{what}</h3><ul>" + "".join(
        f"<li>{_e(line.strip())}</li>" for line in
        elements_lines(s["elements"], r.fatigue["settings"]["speed_kmh"])) + "</ul>"
    return html


def render(report) -> str:
    r = report
    title = f"shaftfe assessment: {r.inputs['variant']}"
    nav = "".join(f'<a href="#{k}">{_e(v)}</a>' for k, v in SECTIONS
                  if not (k == "seed" and not r.comparisons)
                  and not (k == "balancing" and r.balancing is None)
                  and not (k == "strength" and not r.strength))
    body = "".join([
        "<header>", f"<h1>{_e(title)}</h1>",
        f'<p class="meta">{_e(r.inputs["description"])} · {_e(r.created_utc)} · shaftfe '
        f"{_e(__version__)} · total run time {sum(t for _, t in r.timings):.1f} s</p>",
        "</header>", _banner(r), f"<nav>{nav}</nav>",
        _summary(r), _inputs(r), _balancing(r), _static(r), _fatigue(r), _strength(r), _campbell(r),
        _comparison(r), _errors(r), _timing(r), _files(r), _notes(r)])
    return ("<!DOCTYPE html>\n"
            '<html lang="en" xmlns="http://www.w3.org/1999/xhtml"><head><meta charset="utf-8"/>'
            '<meta name="viewport" content="width=device-width, initial-scale=1"/>'
            f"<title>{_e(title)}</title><style>{CSS}</style></head>"
            f"<body><main>{body}</main></body></html>\n")
