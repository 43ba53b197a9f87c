"""``shaftfe study report DIR``: the result page of a study (index.html beside the tables).

The trade-off the seed's design question is about: the engine's shaking force against the
shaft's fatigue life (or peak stress) against its mass, the non-dominated designs marked and the
recommended one (``shaftfe.study.results.recommend``) starred, with the reasons in words; each
objective against every parameter and against the derived X2; the Spearman sensitivities; the
refused and failed designs with their reasons.
"""

from __future__ import annotations

import base64
import html
import io
import json
import math
from pathlib import Path

from shaftfe.errors import InputError
from shaftfe.fatigue.method_options import methods_of
from shaftfe.model.overrides import locate, normalise
from shaftfe.model.parse import resolve_path, resolved_dict
from shaftfe.study import results
from shaftfe.study.runner import _base_row
from shaftfe.study.spec import OPS
from shaftfe.util.atomic import write_atomic

LABELS = {"engine_max_F_N": "engine max|F| [N]", "engine_rms_F_N": "engine RMS|F| [N]",
          "mass_kg": "balancer mass [kg]",
          "X2_percent": "X2 [%]", "stress_max_MPa": "peak von Mises [MPa]",
          "beam_max_peak_MPa": "beam Kt·nominal peak [MPa]", "L10h_min_h": "L10h (min) [h]",
          "critical_rpm": "1st critical speed [rpm]",
          "critical_margin_percent": "critical speed margin [%]"}
_LOG = ("life_h", "life_km", "life_blocks", "L10h_min_h")


FATIGUE_COLUMNS = {"fatigue_sf": "fatigue safety factor{b}", "life_blocks": "fatigue life{b} "
                   "[blocks]", "life_h": "fatigue life{b} [h]", "life_km": "fatigue life{b} [km]",
                   "fatigue_hot_spot": "fatigue hot spot{b}"}
# the required keys of study.json (runner.study_record writes them all): a record without them
# is not a study's, whatever else it holds
META_KEYS = {"study_file": str, "digest": str, "name": str, "base": str, "parameters": list,
             "objectives": list, "requirements": list, "analyses": dict}


def _method(analyses: dict | None) -> tuple[str, bool]:
    """(the study's fatigue method, whether it takes the study's S-N card: ``--material``)."""
    method = (analyses or {}).get("fatigue_method") or "seed"
    return method, method in methods_of("--material")


def fatigue_basis(analyses: dict | None) -> str:
    """What a study's fatigue numbers are: its method (``analyses.fatigue.method``, by default
    the seed's, ``evaluate.fatigue_row``) on the study's S-N card (the seed's) or the shaft's
    own strength card (the standards), not necessarily the FKM default of ``shaftfe fatigue``;
    the two differ (a safety factor of 0.47 against 2.5 on x2_57)."""
    method, sn = _method(analyses)
    if not sn:
        return f"{method} method, the shaft's own strength card"
    return f"{method} method, S-N card {(analyses or {}).get('material') or 'structural_steel'}"


def fatigue_note(analyses: dict | None) -> str:
    """The sentence that names the study's fatigue numbers and how they differ from the
    fatigue command's default (one quantity, two values: the difference named)."""
    an = analyses or {}
    method, sn = _method(analyses)
    if not sn:
        return (f"Fatigue numbers (safety factor, life): the {method} method on the shaft's own "
                f"strength card, as shaftfe fatigue --method {method} computes them.")
    card = an.get("material") or "structural_steel"
    how = f"{an.get('equivalent') or 'von_mises'}, {an.get('mean_stress') or 'soderberg'}"
    return (f"Fatigue numbers (safety factor, life): the {method} method ({how}) on the S-N "
            f"card {card}, as shaftfe fatigue --method {method} --material {card} computes "
            "them; shaftfe fatigue's default method (FKM, the shaft's own material) gives other "
            "values for the same shaft.")


def labels(analyses: dict | None = None) -> dict[str, str]:
    """Column → label; the fatigue columns name their method and material card."""
    b = f" ({fatigue_basis(analyses)})"
    return {**LABELS, **{c: t.format(b=b) for c, t in FATIGUE_COLUMNS.items()}}


def _label(c: str, lab: dict | None = None) -> str:
    return (lab or labels()).get(c, c)


def _axis(c: str, lab: dict | None = None) -> str:
    """A label on a plot axis: the basis in parentheses on its own line (a long one would
    run past the axis)."""
    return _label(c, lab).replace(" (", "\n(", 1)


def _png(fig, path: Path | None = None) -> str:
    """The figure as a data URI (the page is one file); also written to ``path`` if given."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, bbox_inches="tight")
    import matplotlib.pyplot as plt
    plt.close(fig)
    if path is not None:
        write_atomic(path, buf.getvalue())
    return "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode()


def _fmt(v) -> str:
    """A table cell: 4 significant digits below 1000, whole numbers with thousands
    separators up to 10⁹ (40,235 rpm, not 4.024e+04), powers of ten beyond."""
    if isinstance(v, float | int) and not isinstance(v, bool):
        v = float(v)
        if math.isnan(v):
            return "—"
        if math.isinf(v):
            return "∞" if v > 0 else "−∞"
        if abs(v) >= 1e9:
            m, e = f"{v:.3e}".split("e")
            return f"{m}·10<sup>{int(e)}</sup>"
        return f"{v:,.0f}" if abs(v) >= 1000 else f"{v:.4g}"
    return html.escape(str(v))


def _short(path: str) -> str:
    """A parameter path as an axis label: the part and the key, without the table names
    (attachments.counterweight_1.shape.outer_radius_mm → counterweight_1 outer_radius_mm)."""
    parts = [p for p in path.split(".") if p not in ("attachments", "segments", "shape",
                                                     "bearing_types", "materials", "shaft")]
    return " ".join(parts[-2:]) if len(parts) > 1 else path


def _placed(col, values):
    """(values on the axis, edges): a life (positive, on a log axis) of 0 (fails in the first
    block) is drawn at a marked bottom edge and an infinite one (no finite life) at a marked
    top edge, a decade beyond the finite values; other columns as they are."""
    import numpy as np
    v = np.asarray(values, dtype=float)
    if col not in _LOG:
        return v, {}
    fin = v[np.isfinite(v) & (v > 0)]
    lo, hi = (fin.min(), fin.max()) if fin.size else (1.0, 1.0)
    out, edges = v.copy(), {}
    if (v <= 0).any():
        edges["life 0 (fails in the first block): drawn on this line"] = lo / 10
        out[v <= 0] = lo / 10
    if np.isposinf(v).any():
        edges["∞ (no finite life): drawn on this line"] = hi * 10
        out[np.isposinf(v)] = hi * 10
    return out, edges


def _yaxis(ax, col, edges) -> None:
    """A life on a log axis with plain numbers (0.5, 20, 3,000 h); the edges marked."""
    from matplotlib.ticker import FuncFormatter, MaxNLocator
    ax.xaxis.set_major_locator(MaxNLocator(5))
    if col in _LOG:
        ax.set_yscale("log")
        plain = FuncFormatter(lambda y, _: f"{y:,.0f}" if y >= 1 else f"{y:g}")
        ax.yaxis.set_major_formatter(plain)
        ax.yaxis.set_minor_formatter(plain if _decades(ax) < 1.5 else FuncFormatter(""
                                                                                   .format))
    for text, y in edges.items():
        ax.axhline(y, color="0.4", ls=":", lw=0.8)
        ax.annotate(text, (0.005, y), xycoords=("axes fraction", "data"), fontsize=7,
                    color="0.3", va="bottom")


def _decades(ax) -> float:
    lo, hi = ax.get_ylim()
    return math.log10(hi / lo) if lo > 0 and hi > lo else 0.0


def _tradeoff(df, objs, nd, rec, path: Path, reqs=(), base=None, base_name="base", lab=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ok = df["status"] == "ok"
    (cx, _), (cy, _) = objs[0], objs[1]
    cc = objs[2][0] if len(objs) > 2 else None
    fig, ax = plt.subplots(figsize=(7.6, 4.6), layout="constrained")
    d = df[ok]
    y_all, edges = _placed(cy, df[cy])
    sc = ax.scatter(d[cx], y_all[ok.to_numpy()], c=d[cc] if cc else None, cmap="viridis", s=36,
                    zorder=2)
    if cc:
        fig.colorbar(sc, ax=ax, label=_axis(cc, lab))
    m = [bool(x) for x in nd]
    ax.plot(df[m][cx], y_all[m], "o", mfc="none", mec="k", ms=11, zorder=3,
            label="non-dominated")
    if rec is not None:
        ax.plot([df.iloc[rec][cx]], [y_all[rec]], "*", color="crimson", ms=18, zorder=4,
                label="recommended")
    if base is not None and cx in base and cy in base:
        by = _placed(cy, [base[cy], *d[cy]])[0][0]
        ax.plot([base[cx]], [by], "D", color="darkorange", mec="k", ms=9, zorder=5,
                label=f"{base_name} (the base)")
    for col, op, val in reqs:
        if col == cy:
            ax.axhline(val, color="crimson", ls="--", lw=0.8, label=f"required {op} {val:g}")
        elif col == cx:
            ax.axvline(val, color="crimson", ls="--", lw=0.8, label=f"required {op} {val:g}")
    _yaxis(ax, cy, edges)
    ax.set_xlabel(_axis(cx, lab))
    ax.set_ylabel(_axis(cy, lab))
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    return _png(fig, path)


def _against(df, groups, objs, nd, base=None, lab=None):
    """Each objective against each parameter (one column per parameter: paths moved
    together share it, labelled by the first) and against the derived X2."""
    import matplotlib.pyplot as plt
    xs = [(paths[0], f"{name}: {_short(paths[0])}" if name != paths[0] else _short(paths[0]))
          for name, paths in groups if paths[0] in df.columns]
    if "X2_percent" in df.columns and all(x != "X2_percent" for x, _ in xs):
        xs.append(("X2_percent", _label("X2_percent", lab)))
    xs = [(x, xl) for x, xl in xs if df[x].dtype.kind in "if"]
    if not xs:
        return None
    ys = [c for c, _ in objs]
    fig, axes = plt.subplots(len(ys), len(xs), figsize=(3.1 * len(xs) + 0.8, 2.5 * len(ys)),
                             squeeze=False, layout="constrained")
    ok = (df["status"] == "ok").to_numpy()
    m = [bool(a) for a in nd]
    for i, y in enumerate(ys):
        yv, edges = _placed(y, df[y])
        for j, (x, xl) in enumerate(xs):
            ax = axes[i][j]
            ax.plot(df[x][ok], yv[ok], ".", color="tab:blue")
            ax.plot(df[x][m], yv[m], "o", mfc="none", mec="k")
            if base is not None and x in base and y in base:
                ax.plot([base[x]], [_placed(y, [base[y], *list(df[y][ok])])[0][0]], "D",
                        color="darkorange", mec="k", ms=6)
            _yaxis(ax, y, edges)
            if i == len(ys) - 1:
                ax.set_xlabel(xl, fontsize=8)
            if j == 0:
                ax.set_ylabel(_axis(y, lab), fontsize=8)
            ax.tick_params(labelsize=7)
            ax.grid(alpha=0.3)
    return _png(fig)


def read_meta(out: Path) -> dict:
    """The folder's study.json; InputError (one line) for a folder that is not a study's."""
    what = "a folder written by shaftfe study run"
    if not out.is_dir():
        raise InputError(str(out), "folder", what, reason="is a file, not a study folder"
                         if out.is_file() else "does not exist" if not out.exists() else
                         "is not a folder")
    sj = out / "study.json"
    if not sj.is_file():
        raise InputError(str(out), "study.json", what, reason="is missing: this is not a "
                         "study folder, or its run was refused before it started")
    try:
        meta = json.loads(sj.read_text())
    except (OSError, ValueError, UnicodeDecodeError):
        meta = None
    fix = "(run the study again into a new --out)"
    if not isinstance(meta, dict):
        raise InputError(str(out), "study.json", f"the record shaftfe study run writes {fix}",
                         reason="is damaged")
    lacking = [k for k, t in META_KEYS.items() if not isinstance(meta.get(k), t)]
    if lacking:
        raise InputError(str(out), "study.json", f"the record shaftfe study run writes, with "
                         f"{', '.join(META_KEYS)} {fix}", reason="is damaged (no valid "
                         f"{', '.join(lacking)})")
    return meta


def write_report(out_dir) -> Path:
    out = Path(out_dir)
    meta = read_meta(out)
    try:
        run = json.loads((out / "run.json").read_text())
    except (OSError, ValueError):
        run = {}                               # the last run's counts: optional
    run = run if isinstance(run, dict) else {}
    df = results.read_table(out)
    objs = [tuple(o) for o in meta.get("objectives", [])]
    objs = [o for o in objs if o[0] in df.columns]
    reqs = [tuple(r) for r in meta.get("requirements", [])]
    params = meta.get("parameters", [])
    groups = [(g[0], list(g[1])) for g in meta.get("parameter_groups", [])] or \
        [(p, [p]) for p in params]
    nd = results.non_dominated(df, objs) if objs else [False] * len(df)
    rec = results.recommend(df, objs, reqs) if objs else None
    meets = results.meets(df, reqs)
    base, base_name = _base(out, meta, params)
    lab = labels(meta.get("analyses"))
    n_ok = int((df["status"] == "ok").sum())
    parts = [f"<h1>Study {html.escape(meta.get('name', ''))}</h1>",
             f"<p>{html.escape(meta.get('description', ''))}</p>",
             f"<p>Base variant <b>{html.escape(base_name)}</b>; "
             f"{len(df)} designs: {n_ok} evaluated, "
             f"{int((df['status'] == 'refused').sum())} refused, "
             f"{int((df['status'] == 'failed').sum())} failed. "
             f"Study file: {html.escape(str(meta.get('study_file')))} (relative to this "
             "folder).</p>"]
    if run:
        sh = run.get("sharing", {})
        parts.append(f"<p>Last run: {run.get('computed')} computed, {run.get('reused')} from "
                     f"earlier runs, {run.get('workers')} workers "
                     f"({html.escape(str(run.get('scheduler')))}), "
                     f"{run.get('wall_seconds', 0):.1f} s wall, "
                     f"{run.get('compute_seconds', 0):.1f} s of design evaluations; meshes "
                     f"built {sh.get('meshes_built', 0)}, factorisations "
                     f"{sh.get('factor_made', 0)} made / {sh.get('factor_reused', 0)} "
                     "reused.</p>")
    if any(c in df.columns for c in FATIGUE_COLUMNS):
        parts.append(f"<p>{html.escape(fatigue_note(meta.get('analyses')))}</p>")
    parts.append("<h2>Recommendation</h2>")
    parts.append(recommendation(df, objs, reqs, nd, meets, rec, params, lab))
    if len(objs) >= 2 and n_ok:
        parts.append("<h2>Trade-off</h2>")
        uri = _tradeoff(df, objs, nd, rec, out / "tradeoff.png", reqs, base, base_name, lab)
        parts.append(f'<img src="{uri}" alt="trade-off">')
        img = _against(df, groups, objs, nd, base, lab)
        if img:
            parts.append("<h2>Objectives against the parameters</h2>")
            parts.append(f'<img src="{img}" alt="objectives against parameters">')
    outs = [c for c in dict.fromkeys([c for c, _ in objs] + ["X2_percent", "fatigue_sf",
                                                             "L10h_min_h", "stress_max_MPa"])
            if c in df.columns]
    sens = results.sensitivities(df, params, outs)

    def head(c):                          # a short header, the full path on hover
        return (f"<th title='{html.escape(c)}'>"
                f"{html.escape(_short(c) if c in params else _label(c, lab))}</th>")
    if sens and params:
        parts.append("<h2>Sensitivities (Spearman rank correlation over the evaluated designs)"
                     "</h2><div class='wide'><table><tr><th>output</th>"
                     + "".join(head(p) for p in params) + "</tr>")
        for o, row in sens.items():
            cells = "".join(
                f"<td style='background:rgba({200 if (v or 0) > 0 else 60},{90},"
                f"{60 if (v or 0) > 0 else 200},{abs(v or 0) * 0.5:.2f})'>{_fmt(v)}</td>"
                if v is not None else "<td>—</td>" for v in (row.get(p) for p in params))
            parts.append(f"<tr><td>{html.escape(_label(o, lab))}</td>{cells}</tr>")
        parts.append("</table></div>")
    cols = ["design"] + [p for p in params if p in df.columns] + [
        c for c in [*outs, "life_km", "critical_margin_percent"] if c in df.columns]
    parts.append("<h2>Designs (evaluated, non-dominated first)</h2><div class='wide'><table>"
                 "<tr>" + "".join(head(c) for c in cols)
                 + "<th>non-dominated</th><th>meets</th></tr>")
    if base is not None:
        parts.append(f"<tr class='base'><td>{html.escape(base_name)} (base)</td>" + "".join(
            f"<td>{_fmt(base.get(c)) if base.get(c) is not None else ''}</td>"
            for c in cols[1:]) + "<td></td><td>"
            + ("yes" if all(_ok(base.get(c), op, v) for c, op, v in reqs) else "")
            + "</td></tr>")
    order = sorted((i for i in range(len(df)) if df.iloc[i]["status"] == "ok"),
                   key=lambda i: (not nd[i], int(df.iloc[i]["design"])))
    for i in order:
        r = df.iloc[i]
        star = " ★" if i == rec else ""
        parts.append("<tr>" + "".join(f"<td>{_fmt(r[c])}{star if c == 'design' else ''}</td>"
                                      for c in cols)
                     + f"<td>{'yes' if nd[i] else ''}</td><td>{'yes' if meets[i] else ''}</td>"
                     "</tr>")
    parts.append("</table></div>")
    bad = df[df["status"] != "ok"]
    if len(bad):
        parts.append("<h2>Refused and failed designs</h2><table><tr><th>status</th><th>reason"
                     "</th><th>designs</th></tr>")
        for (st, err), g in bad.groupby(["status", "error"]):
            parts.append(f"<tr><td>{st}</td><td>{html.escape(str(err))}</td><td>"
                         + ", ".join(str(int(d)) for d in g["design"]) + "</td></tr>")
        parts.append("</table>")
    page = ("<!doctype html><html><head><meta charset='utf-8'><title>shaftfe study "
            f"{html.escape(meta.get('name', ''))}</title><style>body{{font-family:sans-serif;"
            "max-width:1100px;margin:auto;padding:0 8px}}img{{max-width:100%;height:auto}}"
            ".wide{{overflow-x:auto;max-width:100%}}"
            "table{{border-collapse:collapse;font-size:12px}}"
            "td,th{{border:1px solid #ccc;padding:2px 6px}}"
            "th{{max-width:7.5em;overflow-wrap:anywhere;font-weight:600}}"
            "tr.base td{{background:#fff1dc}}</style></head><body>"
            + "\n".join(parts) + "</body></html>\n")
    return write_atomic(out / "index.html", page)


def _ok(v, op, val) -> bool:
    return v is not None and not (isinstance(v, float) and math.isnan(v)) and \
        OPS[op](float(v), val)


def _base(out: Path, meta: dict, params) -> tuple[dict | None, str]:
    """The base variant's row (``base.json``, the same analyses) with its own values of the
    parameters, and its name; (None, name) if the folder has none."""
    name = str(meta.get("base", "base"))
    name = Path(name).stem if name.endswith(".toml") else name
    row = _base_row(out, meta.get("base_key"))
    if row is None or row.get("status") != "ok":
        return None, name
    row = dict(row)
    try:
        b = str(meta.get("base"))
        merged = resolved_dict(resolve_path(out / b if b.endswith(".toml") else b))
        for p in params:
            parent, key, _ = locate(merged, normalise({p: 0.0})[0])
            row[p] = parent[key]
    except (InputError, KeyError, TypeError, IndexError):
        pass                                   # the base's values are not shown then
    return row, name


def recommendation(df, objs, reqs, nd, meets, rec, params, lab=None) -> str:
    """The recommendation in words, each claim true of the table: the candidates (the
    non-dominated designs meeting every requirement), the recommended one's rank in the first
    objective among them (lowest / highest by its sense), the next candidate, and the designs
    better in that objective that a requirement rules out."""
    obj_txt = ", ".join(f"{'minimise' if s == 'min' else 'maximise'} {_label(c, lab)}"
                        for c, s in objs)
    req_txt = ", ".join(f"{_label(c, lab)} {op} {v:g}" for c, op, v in reqs) or "none"
    cand = [i for i in range(len(df)) if nd[i] and meets[i]]
    if rec is None:
        return (f"<p>No non-dominated design meets the requirements ({html.escape(req_txt)})"
                ".</p>")
    r = df.iloc[rec]
    c1, s1 = objs[0]
    sign = 1.0 if s1 == "min" else -1.0
    word = "lowest" if s1 == "min" else "highest"
    others = sorted((i for i in cand if i != rec), key=lambda i: sign * float(df.iloc[i][c1]))
    nxt = (f"; the next: design {int(df.iloc[others[0]]['design'])}, "
           f"{_fmt(df.iloc[others[0]][c1])}" if others else "")
    better = [i for i in range(len(df)) if df.iloc[i]["status"] == "ok" and not meets[i]
              and nd[i] and sign * float(df.iloc[i][c1]) < sign * float(r[c1])]
    ruled = ""
    if better:
        def fails(i):
            return ", ".join(f"{_label(c, lab)} {_fmt(df.iloc[i][c])} (required {op} {v:g})"
                             for c, op, v in reqs if not _ok(df.iloc[i][c], op, v))
        ruled = (" A " + ("lower" if s1 == "min" else "higher") + f" {_label(c1, lab)} is only "
                 "reached by non-dominated designs that miss a requirement: " + "; ".join(
                     f"design {int(df.iloc[i]['design'])}, {_fmt(df.iloc[i][c1])}: "
                     f"{fails(i)}" for i in better[:4]) + ".")
    setting = "; ".join(f"{html.escape(p)} = {_fmt(r[p])}" for p in params if p in df)
    return (f"<p><b>Design {int(r['design'])}</b>: {setting}.</p><p>Why: of the {sum(nd)} "
            f"non-dominated designs (objectives: {html.escape(obj_txt)}), {len(cand)} meet "
            f"the requirements ({html.escape(req_txt)}). Of these, this one has the {word} "
            f"{html.escape(_label(c1, lab))}: {_fmt(r[c1])}{nxt}.{html.escape(ruled)} Its numbers: "
            + ", ".join(f"{_label(c, lab)} {_fmt(r[c])}" for c in
                        dict.fromkeys([c for c, _ in objs] + ["X2_percent", "fatigue_sf",
                                                              "L10h_min_h", "critical_rpm"])
                        if c in df.columns) + ".</p>")
