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

LABELS = {"engine_max_F_N": "engine max|F| [N]", "engine_rms_F_N": "engine RMS|F| [N]",
          "life_h": "fatigue life [h]", "life_km": "fatigue life [km]",
          "fatigue_sf": "fatigue safety factor", "mass_kg": "balancer mass [kg]",
          "X2_percent": "X2 [%]", "stress_max_MPa": "peak von Mises [MPa]",
          "beam_max_peak_MPa": "beam Kt·nominal peak [MPa]", "L10h_min_h": "L10h (min) [h]",
          "critical_rpm": "1st critical speed [rpm]"}
_LOG = ("life_h", "life_km", "life_blocks", "L10h_min_h")


def _label(c: str) -> str:
    return LABELS.get(c, c)


def _png(fig, path: Path | None = None) -> str:
    """The figure as a data URI (the page is one file); also written to ``path`` if given."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, bbox_inches="tight")
    import matplotlib.pyplot as plt
    plt.close(fig)
    if path is not None:
        from shaftfe.util.atomic import write_atomic
        write_atomic(path, buf.getvalue())
    return "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode()


def _fmt(v) -> str:
    if isinstance(v, float):
        if not math.isfinite(v):
            return "—"
        return f"{v:.4g}" if abs(v) < 1e5 else f"{v:.3e}"
    return html.escape(str(v))


def _yscale(ax, col, values) -> None:
    """Lives on a log axis; a life of 0 (failed in the first block) on its linear part."""
    if col in _LOG and (values > 0).any():
        if (values > 0).all():
            ax.set_yscale("log")
        else:
            ax.set_yscale("symlog", linthresh=1.0)


def _tradeoff(df, objs, nd, rec, path: Path, reqs=()):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ok = df["status"] == "ok"
    (cx, _), (cy, _) = objs[0], objs[1]
    cc = objs[2][0] if len(objs) > 2 else None
    fig, ax = plt.subplots(figsize=(7.2, 4.6))
    d = df[ok]
    sc = ax.scatter(d[cx], d[cy], c=d[cc] if cc else None, cmap="viridis", s=36, zorder=2)
    if cc:
        fig.colorbar(sc, ax=ax, label=_label(cc))
    p = df[[bool(m) for m in nd]].sort_values(cx)
    ax.plot(p[cx], p[cy], "o", mfc="none", mec="k", ms=11, zorder=3,
            label="non-dominated")
    if rec is not None:
        r = df.iloc[rec]
        ax.plot([r[cx]], [r[cy]], "*", color="crimson", ms=18, zorder=4, label="recommended")
    for col, op, val in reqs:
        if col == cy:
            ax.axhline(val, color="crimson", ls="--", lw=0.8, label=f"required {op} {val:g}")
        elif col == cx:
            ax.axvline(val, color="crimson", ls="--", lw=0.8, label=f"required {op} {val:g}")
    _yscale(ax, cy, d[cy])
    ax.set_xlabel(_label(cx))
    ax.set_ylabel(_label(cy))
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    return _png(fig, path)


def _against(df, params, objs, nd):
    import matplotlib.pyplot as plt
    xs = [p for p in params if p in df.columns] + (["X2_percent"] if "X2_percent" in df.columns
                                                    and "X2_percent" not in params else [])
    xs = [x for x in xs if df[x].dtype.kind in "if"]
    if not xs:
        return None
    ys = [c for c, _ in objs]
    fig, axes = plt.subplots(len(ys), len(xs), figsize=(3.0 * len(xs) + 0.6, 2.5 * len(ys)),
                             squeeze=False)
    ok = df["status"] == "ok"
    for i, y in enumerate(ys):
        for j, x in enumerate(xs):
            ax = axes[i][j]
            ax.plot(df[ok][x], df[ok][y], ".", color="tab:blue")
            m = [bool(a) for a in nd]
            ax.plot(df[m][x], df[m][y], "o", mfc="none", mec="k")
            _yscale(ax, y, df[ok][y])
            if i == len(ys) - 1:
                ax.set_xlabel(_label(x.rsplit(".", 2)[-2] + "." + x.rsplit(".", 1)[-1]
                                     if x.count(".") > 1 else _label(x)), fontsize=8)
            if j == 0:
                ax.set_ylabel(_label(y), fontsize=8)
            ax.tick_params(labelsize=7)
            ax.grid(alpha=0.3)
    fig.tight_layout()
    return _png(fig)


def write_report(out_dir) -> Path:
    from shaftfe.study import results
    from shaftfe.util.atomic import write_atomic
    out = Path(out_dir)
    sj = out / "study.json"
    if not sj.is_file():
        raise InputError(str(out_dir), "study.json", "a folder written by shaftfe study run",
                         reason="is missing")
    meta = json.loads(sj.read_text())
    run = json.loads((out / "run.json").read_text()) if (out / "run.json").is_file() else {}
    df = results.read_table(out)
    objs = [tuple(o) for o in meta.get("objectives", [])]
    objs = [o for o in objs if o[0] in df.columns]
    reqs = [tuple(r) for r in meta.get("requirements", [])]
    params = meta.get("parameters", [])
    nd = results.non_dominated(df, objs) if objs else [False] * len(df)
    rec = results.recommend(df, objs, reqs) if objs else None
    meets = results.meets(df, reqs)
    n_ok = int((df["status"] == "ok").sum())
    parts = [f"<h1>Study {html.escape(meta.get('name', ''))}</h1>",
             f"<p>{html.escape(meta.get('description', ''))}</p>",
             f"<p>Base variant <b>{html.escape(str(meta.get('base')))}</b>; "
             f"{len(df)} designs: {n_ok} evaluated, "
             f"{int((df['status'] == 'refused').sum())} refused, "
             f"{int((df['status'] == 'failed').sum())} failed. "
             f"Study file: {html.escape(str(meta.get('study_file')))}.</p>"]
    if run:
        parts.append(f"<p>Last run: {run.get('computed')} computed, {run.get('reused')} from "
                     f"earlier runs, {run.get('workers')} workers "
                     f"({html.escape(str(run.get('scheduler')))}), "
                     f"{run.get('wall_seconds', 0):.1f} s wall, "
                     f"{run.get('compute_seconds', 0):.1f} s of design evaluations; meshes "
                     f"built {run.get('sharing', {}).get('meshes_built', 0)}, "
                     f"factorisations {run.get('sharing', {}).get('factor_made', 0)} made / "
                     f"{run.get('sharing', {}).get('factor_reused', 0)} reused.</p>")
    parts.append("<h2>Recommendation</h2>")
    obj_txt = ", ".join(f"{'minimise' if s == 'min' else 'maximise'} {_label(c)}"
                        for c, s in objs)
    req_txt = ", ".join(f"{_label(c)} {op} {v:g}" for c, op, v in reqs) or "none"
    if rec is None:
        parts.append(f"<p>No non-dominated design meets the requirements ({html.escape(req_txt)})"
                     ".</p>")
    else:
        r = df.iloc[rec]
        setting = "; ".join(f"{html.escape(p)} = {_fmt(r[p])}" for p in params if p in df)
        parts.append(
            f"<p><b>Design {int(r['design'])}</b>: {setting}.</p><p>Why: of the "
            f"{sum(nd)} non-dominated designs (objectives: {html.escape(obj_txt)}), "
            f"{sum(1 for i in range(len(df)) if nd[i] and meets[i])} meet the requirements "
            f"({html.escape(req_txt)}); this one is best in the first objective. Its numbers: "
            + ", ".join(f"{_label(c)} {_fmt(r[c])}" for c in
                        dict.fromkeys([c for c, _ in objs] + ["X2_percent", "fatigue_sf",
                                                              "L10h_min_h", "critical_rpm"])
                        if c in df.columns) + ".</p>")
    if len(objs) >= 2 and n_ok:
        parts.append("<h2>Trade-off</h2>")
        uri = _tradeoff(df, objs, nd, rec, out / "tradeoff.png", reqs)
        parts.append(f'<img src="{uri}" alt="trade-off">')
        img = _against(df, params, objs, nd)
        if img:
            parts.append("<h2>Objectives against the parameters</h2>")
            parts.append(f'<img src="{img}" alt="objectives against parameters">')
    outs = [c for c in dict.fromkeys([c for c, _ in objs] + ["X2_percent", "fatigue_sf",
                                                             "L10h_min_h", "stress_max_MPa"])
            if c in df.columns]
    sens = results.sensitivities(df, params, outs)
    if sens and params:
        parts.append("<h2>Sensitivities (Spearman rank correlation over the evaluated designs)"
                     "</h2><table><tr><th>output</th>" + "".join(
                         f"<th>{html.escape(p)}</th>" for p in params) + "</tr>")
        for o, row in sens.items():
            cells = "".join(
                f"<td style='background:rgba({200 if (v or 0) > 0 else 60},{90},"
                f"{60 if (v or 0) > 0 else 200},{abs(v or 0) * 0.5:.2f})'>{_fmt(v)}</td>"
                if v is not None else "<td>—</td>" for v in (row.get(p) for p in params))
            parts.append(f"<tr><td>{html.escape(_label(o))}</td>{cells}</tr>")
        parts.append("</table>")
    cols = ["design"] + [p for p in params if p in df.columns] + [
        c for c in [*outs, "life_km", "critical_margin_percent"] if c in df.columns]
    parts.append("<h2>Designs (evaluated, non-dominated first)</h2><table><tr>" + "".join(
        f"<th>{html.escape(c)}</th>" for c in cols) + "<th>non-dominated</th><th>meets</th></tr>")
    order = sorted((i for i in range(len(df)) if df.iloc[i]["status"] == "ok"),
                   key=lambda i: (not nd[i], int(df.iloc[i]["design"])))
    for i in order:
        r = df.iloc[i]
        star = " ★" if i == rec else ""
        parts.append("<tr>" + "".join(f"<td>{_fmt(r[c])}{star if c == 'design' else ''}</td>"
                                      for c in cols)
                     + f"<td>{'yes' if nd[i] else ''}</td><td>{'yes' if meets[i] else ''}</td>"
                     "</tr>")
    parts.append("</table>")
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
            "max-width:1100px;margin:auto}}table{{border-collapse:collapse;font-size:12px}}"
            "td,th{{border:1px solid #ccc;padding:2px 6px}}</style></head><body>"
            + "\n".join(parts) + "</body></html>\n")
    return write_atomic(out / "index.html", page)
