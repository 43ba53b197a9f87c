"""Fatigue figures (PNG): load history, S-N curve, rainflow and damage matrices of a hot spot
(seed 000 Obr. 65, 68, 69) and its Haigh diagram. matplotlib (Agg) is imported inside the
functions, so importing this module costs nothing. Every function returns the written path.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from shaftfe.fatigue.counting import CycleMatrix, Cycles
from shaftfe.fatigue.fkm import mean_stress_factor
from shaftfe.fatigue.kernels import stress_cycles
from shaftfe.fatigue.sn import FatigueMaterial
from shaftfe.util.atomic import atomic_path
from shaftfe.util.figures import log_ticks


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path) -> Path:
    """Write the figure atomically (never a half-written PNG) and close it."""

    path = Path(path)
    try:
        with atomic_path(path) as tmp:
            fig.savefig(tmp, dpi=120, bbox_inches="tight",
                        format=path.suffix.lstrip(".") or None)
    finally:
        fig.clf()
        _plt().close(fig)
    return path


def plot_load_history(history, path) -> Path:
    """rpm and load factor against time (seed Obr. 65 / 88), the load factor (n / ref)² at the
    history's reference speed (pass the fatigue run's history, ``FatigueField.history``, which
    is re-referenced to the static solution's speed)."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(9, 3.5))
    ax.step(history.time_s, history.rpm, where="post", color="tab:blue")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("engine speed [rpm]", color="tab:blue")
    ax2 = ax.twinx()
    ax2.step(history.time_s, history.load_factor, where="post", color="tab:red", alpha=0.4)
    ax2.set_ylabel(f"load factor (n / {history.rpm_ref:,.0f})²".replace(",", " "),
                   color="tab:red")
    ax.set_title(f"{Path(history.source).name}: {history.duration_s:g} s block")
    ax.grid(alpha=0.3)
    return _save(fig, path)


def plot_sn_curve(material: FatigueMaterial, path, kf: float = 1.0) -> Path:
    """The S-N table (points), its log-log interpolation and the treatment beyond the last
    point; ``kf`` < 1 also draws the reduced curve."""
    plt = _plt()
    sn = material.sn
    n = np.logspace(np.log10(sn.cycles[0]), np.log10(sn.cycles[-1]) + 2, 300)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.loglog(sn.cycles, sn.alternating_MPa, "o", color="k", label="card points")
    s = sn.amplitude_at(n)
    ax.loglog(n, s, "-", color="tab:blue", label=f"interpolated ({sn.beyond_last})")
    if sn.beyond_last == "cutoff":
        ax.hlines(sn.endurance_MPa, sn.cycles[-1], n[-1], colors="tab:blue", linestyles="--",
                  label="endurance (no damage below)")
    if kf != 1.0:
        ax.loglog(n, kf * s, "-", color="tab:red", label=f"× kf = {kf:g}")
    log_ticks(ax.xaxis, ax.yaxis)
    ax.set_xlabel("cycles to failure N [-]")
    ax.set_ylabel("alternating stress [MPa] (mean 0)")
    ax.set_title(material.name)
    ax.grid(which="both", alpha=0.3)
    ax.legend()
    return _save(fig, path)


def plot_cycle_matrix(matrix: CycleMatrix, path, title: str = "") -> Path:
    """Rainflow (counts) or damage matrix as a range × mean heat map (seed Obr. 68 / 69), each
    occupied cell outlined. Counts: a discrete colour bar of whole numbers (one colour per
    count up to 10, logarithmic bins of whole numbers beyond). Damage: a logarithmic colour
    bar, every label in one format (1e-05, 1e-04 …)."""
    from matplotlib import colors, ticker
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6, 4.5))
    vals = np.asarray(matrix.values, dtype=float)
    v = np.ma.masked_less_equal(vals, 0.0)
    count = matrix.quantity == "count"
    if count:
        norm, ticks, cmap = _count_norm(vals)
        fmt = ticker.FuncFormatter(lambda x, _: f"{x:,.10g}".replace(",", " "))
    else:
        # an infinite damage (a cycle above the static strength: failure in that cycle) is
        # drawn in the colour bar's "over" colour, not put on the scale
        pos = vals[(vals > 0) & np.isfinite(vals)]
        lo = 10.0 ** np.floor(np.log10(pos.min())) if pos.size else 1e-12
        hi = 10.0 ** np.ceil(np.log10(pos.max())) if pos.size else 1.0
        if hi <= lo:
            hi = lo * 10.0
        norm, cmap = colors.LogNorm(lo, hi), plt.get_cmap("viridis").with_extremes(over="red")
        ticks = 10.0 ** np.arange(np.log10(lo), np.log10(hi) + 0.5)
        fmt = ticker.FuncFormatter(lambda x, _: f"{x:.0e}")
    mesh = ax.pcolormesh(matrix.mean_edges, matrix.range_edges, v, cmap=cmap, norm=norm,
                         shading="flat", edgecolors="0.35", linewidth=0.4)
    infinite = not count and bool(np.isinf(vals).any())
    cb = fig.colorbar(mesh, ax=ax, ticks=ticks, format=fmt, extend="max" if infinite else "neither",
                      label="cycles per block" if count else
                      "damage per block [-] (log)" + ("; red: failure in one cycle" if infinite
                                                      else ""))
    cb.minorticks_off()
    unit = f" [{matrix.units}]" if matrix.units else ""
    ax.set_xlabel("mean" + unit)
    ax.set_ylabel("range" + unit)
    ax.set_title(title or f"{matrix.quantity} matrix")
    return _save(fig, path)


def _count_norm(vals: np.ndarray):
    """(norm, ticks, colormap) of a count matrix. Up to ``COUNT_DISCRETE`` cycles per cell:
    one colour per count (per half count when half cycles are left), the ticks at the counts.
    Beyond: logarithmic bins from 1, 2, 5 × 10^k to the next, the ticks on those whole-number
    bounds (a colour then means "from this count up to the next tick")."""
    from matplotlib import colors
    plt = _plt()
    pos = vals[vals > 0]
    top = max(float(pos.max(initial=1.0)), 0.5)
    half = bool(np.any(np.abs(pos - np.round(pos)) > 1e-9))
    if top <= COUNT_DISCRETE:
        step = 0.5 if half else 1.0
        ticks = np.arange(step, np.ceil(top / step) * step + 0.5 * step, step)
        bounds = np.concatenate([ticks - 0.5 * step, [ticks[-1] + 0.5 * step]])
    else:
        k = int(np.ceil(np.log10(top))) + 1
        edges = sorted(m * 10.0 ** e for e in range(k + 1) for m in (1, 2, 5))
        last = next(i for i, e in enumerate(edges) if e > top)
        bounds = np.array(([0.5] if half else []) + edges[: last + 1])
        ticks = bounds
    cmap = plt.get_cmap("viridis", len(bounds) - 1)
    return colors.BoundaryNorm(bounds, cmap.N), ticks, cmap


COUNT_DISCRETE = 10            # up to this many cycles per cell, one colour per count


HAIGH_MAX_POINTS = 20_000


def plot_haigh(sigma_eq_node: float, cycles: Cycles, material: FatigueMaterial, path,
               theory: str = "soderberg", kf: float = 1.0, beta: float = 0.0) -> Path:
    """Haigh diagram of one node (linear stress ``sigma_eq_node`` = S0, spin softening
    ``beta``): its cycles (σ_m, σ_a), marker area ∝ count, and the chosen mean-stress line
    through the endurance amplitude kf · S_e (the S-N curve's last point)."""
    plt = _plt()
    s = float(sigma_eq_node)
    sa, sm = stress_cycles(s, float(beta) if beta else None, cycles)
    s = s * (1.0 + float(beta))                    # at the reference speed, for the label
    se = kf * material.sn.endurance_MPa
    fig, ax = plt.subplots(figsize=(6, 4.5))
    label = f"cycles at σ_eq,ref = {s:.1f} MPa"
    if sa.size > HAIGH_MAX_POINTS:      # a long log: the largest amplitudes, which do the damage
        keep = np.argpartition(sa, sa.size - HAIGH_MAX_POINTS)[-HAIGH_MAX_POINTS:]
        label += f" (the {HAIGH_MAX_POINTS} largest of {sa.size} classes)"
        sa_p, sm_p, cnt = sa[keep], sm[keep], cycles.count[keep]
    else:
        sa_p, sm_p, cnt = sa, sm, cycles.count
    ax.scatter(sm_p, sa_p, s=20 + 30 * cnt / max(cnt.max(initial=1.0), 1.0), alpha=0.7,
               label=label)
    m = np.linspace(0.0, material.ultimate_MPa, 200)
    lines = {"soderberg": (material.yield_MPa, lambda x: se * (1 - x / material.yield_MPa)),
             "goodman": (material.ultimate_MPa, lambda x: se * (1 - x / material.ultimate_MPa)),
             "gerber": (material.ultimate_MPa,
                        lambda x: se * (1 - (x / material.ultimate_MPa) ** 2)),
             "none": (material.ultimate_MPa, lambda x: np.full_like(x, se))}
    lim, f = lines[theory]
    mm = m[m <= lim]
    ax.plot(mm, f(mm), "r-", label=f"{theory} line (S_e = {se:.1f} MPa)")
    ax.set_xlabel("mean stress σ_m [MPa]")
    ax.set_ylabel("amplitude σ_a [MPa]")
    ax.set_title(f"Haigh diagram, {material.name}")
    ax.set_xlim(min(0.0, float(sm.min(initial=0.0))) * 1.05, material.ultimate_MPa * 1.05)
    ax.set_ylim(0, max(se, float(sa.max(initial=0.0))) * 1.15)
    ax.grid(alpha=0.3)
    ax.legend()
    return _save(fig, path)


def plot_fkm_haigh(gc: dict, path, title: str = "") -> Path:
    """FKM Haigh diagram, overload case F2 (constant stress ratio), of the governing check
    (``fkm_field.governing_cycles``): the component fatigue strength amplitude σ_AK against
    the mean stress, traced ray by ray from ``fkm.mean_stress_factor`` (σ_AK = K_AK σ_WK at
    each ratio σ_m/σ_a: the very factor the assessment divides by), and the assessed cycles
    (σ_m, σ_a) as points (area ∝ count; a long log: its largest amplitudes)."""
    plt = _plt()
    s_wk, M = float(gc["sigma_WK"]), float(gc["M"])
    sa, sm, cnt = (np.asarray(gc[k], dtype=float) for k in ("amplitude", "mean", "count"))
    # rays σ_m/σ_a = cot φ, φ from almost pure tension (mean ≫ amplitude) to pure compression
    phi = np.linspace(0.02, np.pi - 0.02, 2000)
    k_ak = mean_stress_factor(np.sin(phi), np.cos(phi), M)
    amp = k_ak * s_wk
    mean = amp * np.cos(phi) / np.sin(phi)
    fig, ax = plt.subplots(figsize=(7, 4.8))
    ax.plot(mean, amp, "r-", lw=1.8,
            label=f"σ_AK (F2): σ_WK = {s_wk:.0f} MPa, M_σ = {M:.3f}")
    label = f"{cnt.sum():g} cycles per block" + ("" if cnt.size else " (constant speed)")
    big = int(np.argmax(sa)) if sa.size else -1
    m_ak = 0.0
    if big >= 0 and sa[big] > 0:        # the largest cycle's ray to its σ_AK: the margin F2 assumes
        a_ak = float(mean_stress_factor(sa[big], sm[big], M)) * s_wk
        m_ak = a_ak * sm[big] / sa[big]
        ax.plot([0.0, m_ak], [0.0, a_ak], ":", color="tab:blue", lw=1,
                label=f"largest cycle's ray (F2) to σ_AK = {a_ak:.0f} MPa")
        ax.plot([m_ak], [a_ak], "x", color="tab:blue", ms=8)
    if sa.size > HAIGH_MAX_POINTS:
        keep = np.argpartition(sa, sa.size - HAIGH_MAX_POINTS)[-HAIGH_MAX_POINTS:]
        label = f"the {HAIGH_MAX_POINTS} largest of {sa.size} cycle classes"
        sa, sm, cnt = sa[keep], sm[keep], cnt[keep]
    ax.scatter(sm, sa, s=12 + 30 * cnt / max(cnt.max(initial=1.0), 1.0), alpha=0.6,
               color="tab:blue", label=label, zorder=3)
    hi_m = max(float(sm.max(initial=0.0)), s_wk, m_ak) * 1.3
    lo_m = min(float(sm.min(initial=0.0)), -0.5 * s_wk) * 1.6
    ax.set_xlim(lo_m, hi_m)
    ax.set_ylim(0.0, max(float(sa.max(initial=0.0)), s_wk / (1.0 - M) if M < 1 else s_wk)
                * 1.2)
    ax.axvline(0.0, color="0.6", lw=0.8)
    ax.set_xlabel("mean stress σ_m [MPa]")
    ax.set_ylabel("amplitude σ_a [MPa]")
    ax.set_title(title or "FKM Haigh diagram (F2)")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    return _save(fig, path)


def plot_din743_safeties(rows: list[dict], s_min: float, path, title: str = "") -> Path:
    """DIN 743 per notch: the fatigue safety S_D and the yield safety S_F (bars, log scale;
    an infinite value drawn at the axis end and marked ∞) against the minimum S_min."""
    plt = _plt()
    names = [r["name"] if "@" in r["name"] else f"{r['name']} @{r['x_mm']:g}" for r in rows]
    vals = {k: np.array([np.inf if r[k] is None else r[k] for r in rows], dtype=float)
            for k in ("S_D", "S_F")}
    finite = np.concatenate([v[np.isfinite(v)] for v in vals.values()] + [[s_min]])
    top = float(finite.max()) * 3.0
    fig, ax = plt.subplots(figsize=(8, 0.45 * len(rows) + 1.6))
    y = np.arange(len(rows))
    for off, (k, color) in zip((-0.2, 0.2), (("S_D", "tab:blue"), ("S_F", "tab:orange")),
                               strict=True):
        v = vals[k]
        ax.barh(y + off, np.where(np.isfinite(v), v, top), height=0.38, color=color,
                label={"S_D": "S_D (fatigue)", "S_F": "S_F (yield)"}[k])
        for yy, vv in zip(y + off, v, strict=True):
            ax.text(min(vv, top) * 1.05, yy, "∞" if not np.isfinite(vv) else f"{vv:.2f}",
                    va="center", fontsize=7)
    ax.axvline(s_min, color="r", lw=1.5, label=f"S_min = {s_min:g}")
    ax.set_xscale("log")
    log_ticks(ax.xaxis)
    ax.set_xlim(min(0.5, float(finite.min()) * 0.8), top * 2.0)
    ax.set_yticks(y, names, fontsize=8)
    worst = int(np.argmin(np.minimum(vals["S_D"], vals["S_F"])))
    ax.get_yticklabels()[worst].set_fontweight("bold")        # the governing notch
    ax.invert_yaxis()
    ax.set_xlabel("safety [-] (log scale); bold: the governing notch")
    ax.set_title(title or "DIN 743 safeties per notch")
    ax.grid(axis="x", which="both", alpha=0.3)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=3, fontsize=8)
    return _save(fig, path)


def plot_din743_along(along: dict, notches: list[dict], s_min: float, path,
                      title: str = "") -> Path:
    """DIN 743 along the shaft: S_D and S_F of the unnotched section at every cross-section
    (lines, log scale), each notch's S_D and S_F (markers, named), S_min, and the shaft's
    outline below (the sections' diameters ``along["d_mm"]``). A section without stress
    (safety ∞) is drawn at the top of the axis."""
    plt = _plt()
    x = np.asarray(along["x_mm"], dtype=float)
    vals = {k: np.array([np.inf if v is None else v for v in along[k]], dtype=float)
            for k in ("S_D", "S_F")}
    pts = {k: np.array([np.inf if n[k] is None else n[k] for n in notches], dtype=float)
           for k in ("S_D", "S_F")}
    finite = np.concatenate([v[np.isfinite(v)] for v in (*vals.values(), *pts.values())]
                            + [np.array([s_min])])
    lo, top = max(float(finite.min()) * 0.7, 1e-2), min(float(finite.max()) * 1.5, 1e3)
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(10, 5.6), sharex=True,
                                  gridspec_kw={"height_ratios": [4, 1]})
    # where the yield limit bounds the amplitude (DIN 743 case 2), S_D = S_F: S_D dashed on top
    for k, color, label, ls in (("S_F", "tab:orange", "S_F (yield), unnotched section", "-"),
                                ("S_D", "tab:blue", "S_D (fatigue), unnotched section", "--")):
        ax.plot(x, np.minimum(vals[k], top), color=color, lw=1.2, ls=ls, label=label)
    nx = np.array([n["x_mm"] for n in notches], dtype=float)
    for k, color, mk in (("S_D", "tab:blue", "o"), ("S_F", "tab:orange", "^")):
        ax.scatter(nx, np.minimum(pts[k], top), color=color, marker=mk, zorder=3, s=28,
                   edgecolors="k", linewidths=0.5, label=f"{k} at a notch")
    for n, xx, yy in zip(notches, nx, np.minimum(pts["S_D"], pts["S_F"]), strict=True):
        ax.annotate(n["name"], (xx, min(yy, top)), textcoords="offset points", xytext=(2, -9),
                    fontsize=6, rotation=-35, ha="left", va="top")
    ax.axhline(s_min, color="r", lw=1.2, label=f"S_min = {s_min:g}")
    ax.set_yscale("log")
    log_ticks(ax.yaxis)
    ax.set_ylim(lo, top * 1.05)
    ax.set_ylabel("safety [-] (log scale)")
    ax.grid(which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=3, loc="upper center")
    ax.set_title(title or "DIN 743 safety along the shaft")
    _outline_panel(ax2, x, along["d_mm"], nx)
    return _save(fig, path)


def _outline_panel(ax, x, d_mm, marks) -> None:
    """The shaft's outline (diameters ``d_mm`` at ``x``) below an along-the-shaft plot, the
    x of each of ``marks`` dotted."""
    r = 0.5 * np.asarray(d_mm, dtype=float)
    ax.fill_between(x, -r, r, color="0.75", edgecolor="0.3", lw=0.6)
    for xx in marks:
        ax.axvline(xx, color="k", lw=0.5, ls=":")
    ax.set_ylabel("Ø mm")
    ax.set_xlabel("x [mm]")


def plot_fkm_along(along: dict, regions: list[dict], rule: str, d_mm, path,
                   title: str = "") -> Path:
    """FKM along the shaft: the degree of utilisation at every cross-section (``along``: the
    summary's, a line), each assessed region's governing node (``regions``: the summary's, the
    worse layer, named markers), the limit 1, and the shaft's outline ``d_mm`` at
    ``along["x_mm"]`` below."""
    plt = _plt()
    x = np.asarray(along["x_mm"], dtype=float)
    u = np.array([np.nan if v is None else v for v in along["utilisation"]], dtype=float)

    def worse(r) -> float:
        vals = [r[k]["utilisation"][rule] for k in ("surface", "core") if k in r]
        vals = [np.inf if v is None else v for v in vals]
        return max(vals)
    rx = np.array([r["xyz_mm"][0] for r in regions], dtype=float)
    ru = np.array([worse(r) for r in regions], dtype=float)
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(10, 5.6), sharex=True,
                                  gridspec_kw={"height_ratios": [4, 1]})
    ax.plot(x, u, color="tab:blue", lw=1.2, label="every 1 mm of the surface")
    ax.scatter(rx, ru, color="tab:red", marker="o", zorder=3, s=28, edgecolors="k",
               linewidths=0.5, label="a region's hot spot")
    for r, xx, yy in zip(regions, rx, ru, strict=True):
        ax.annotate(r["region"], (xx, yy), textcoords="offset points", xytext=(2, 4),
                    fontsize=6, rotation=35, ha="left", va="bottom")
    ax.axhline(1.0, color="r", lw=1.2, label="limit 1 (passes below)")
    top = float(np.nanmax(np.concatenate([u, ru[np.isfinite(ru)], [1.0]])))
    ax.set_ylim(0.0, 1.25 * top)
    ax.set_ylabel(f"degree of utilisation [-] ({rule} Miner)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=3, loc="upper center")
    ax.set_title(title or "FKM degree of utilisation along the shaft")
    _outline_panel(ax2, x, d_mm, rx)
    return _save(fig, path)
