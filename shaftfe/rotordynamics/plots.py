"""The Campbell diagram of a ``CampbellResult`` (``shaftfe.rotordynamics.campbell``):
frequency axis and plot. matplotlib (Agg) only inside ``plot_campbell``.
"""

from __future__ import annotations

import numpy as np

from shaftfe.rotordynamics.campbell import CampbellResult
from shaftfe.rotordynamics.kernels import WHIRL_LABELS
from shaftfe.rotordynamics.options import SEPARATION_MARGIN
from shaftfe.util.figures import log_ticks

_WHIRL_STYLE = {"forward": ("tab:red", "-"), "backward": ("tab:blue", "--"),
                "torsional": ("tab:green", "-."), "axial": ("tab:purple", ":"),
                "undetermined": ("0.4", "-")}


def campbell_limits_hz(res: CampbellResult) -> tuple[float, float]:
    """The logarithmic frequency axis of a Campbell diagram: every computed branch (up to the
    highest mode, with room above) and the excitation region (from half the lowest branch or
    a tenth of the highest excitation, whichever is lower: the excitation lines enter the
    plot well below the branches they could cross)."""
    f = res.freq_hz[res.freq_hz > 0]
    f_exc = max(res.orders, default=1.0) * float(res.rpm.max()) / 60.0
    if f.size == 0:
        return 1.0, max(10.0, 2.0 * f_exc)
    lo = 0.5 * float(f.min())
    if f_exc > 0:
        lo = min(lo, 0.1 * f_exc)
    return lo, 1.3 * float(f.max())


def _merged_labels(ax, x: float, ys: np.ndarray, min_px: float = 9.0) -> list[tuple]:
    """Branch numbers at the right end, merged where they would overlap (closer than
    ``min_px`` on the screen): [(y, "1, 2"), …]."""
    pix = ax.transData.transform(np.column_stack([np.full(ys.size, x), ys]))[:, 1]
    order = np.argsort(pix)
    groups: list[list[int]] = []
    for j in order:
        if groups and pix[j] - pix[groups[-1][-1]] < min_px:
            groups[-1].append(int(j))
        else:
            groups.append([int(j)])
    return [(float(np.exp(np.mean(np.log(ys[g])))), ", ".join(str(j + 1) for j in sorted(g)))
            for g in groups]


def _critical_labels(ax, criticals, dx_px: float = 70.0, dy_px: float = 18.0) -> list:
    """One label per cluster of critical-speed markers (closer than ``dx_px`` × ``dy_px`` on
    the screen, in speed order): [((rpm, Hz) of the cluster's first, "41022, 44391 rpm")]."""
    if not criticals:
        return []
    pts = sorted(criticals, key=lambda c: c.rpm)
    pix = ax.transData.transform([(c.rpm, c.freq_hz) for c in pts])
    groups: list[list[int]] = [[0]]
    for k in range(1, len(pts)):
        a = pix[groups[-1][0]]
        if abs(pix[k, 0] - a[0]) < dx_px and abs(pix[k, 1] - a[1]) < dy_px:
            groups[-1].append(k)
        else:
            groups.append([k])
    return [((pts[g[0]].rpm, max(pts[k].freq_hz for k in g)),
             ", ".join(f"{pts[k].rpm:.0f}" for k in g) + " rpm") for g in groups]


def plot_campbell(res: CampbellResult, title: str = "", fmt: str = "png") -> bytes:
    """Campbell diagram: every computed branch (frequency [Hz], log axis, against speed [rpm]),
    styled by whirl, the excitation lines k·n/60 with the ±``SEPARATION_MARGIN`` band around
    each, critical speeds marked; legend and statement outside the plot area. Returns image
    bytes."""
    import io
    import textwrap

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    fig, ax = plt.subplots(figsize=(10, 6))
    lo, hi = campbell_limits_hz(res)
    x_max = float(res.rpm.max())
    ax.set_yscale("log")
    log_ticks(ax.yaxis)
    ax.set_ylim(lo, hi)
    ax.set_xlim(float(res.rpm.min()), x_max * 1.07 if x_max > 0 else 1.0)
    used = set()
    for j in range(res.freq_hz.shape[1]):
        c, ls = _WHIRL_STYLE.get(res.branch_whirl[j], _WHIRL_STYLE["undetermined"])
        used.add(res.branch_whirl[j])
        ax.plot(res.rpm, res.freq_hz[:, j], color=c, ls=ls, marker="o", ms=2.5, lw=1.1)
    n_line = np.linspace(float(res.rpm.min()), x_max, 200)
    for k in res.orders:
        f_line = k * n_line / 60.0
        ax.fill_between(n_line, f_line * (1 - SEPARATION_MARGIN),
                        f_line * (1 + SEPARATION_MARGIN), color="0.5", alpha=0.18, lw=0)
        ax.plot(n_line, f_line, color="k", lw=0.9)
        # the order's name on its line inside the plot (the right edge holds the branch
        # numbers), on a white box
        i = int(0.8 * (n_line.size - 1))
        ax.annotate(f"{k:g}×", (n_line[i], f_line[i]), fontsize=8, ha="right", va="bottom",
                    xytext=(-3, 3), textcoords="offset points",
                    bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none",
                          "alpha": 0.8})
    fig.canvas.draw()                      # the limits are final: label positions in pixels
    for y, text in _merged_labels(ax, x_max, res.freq_hz[-1]):
        ax.annotate(text, (x_max, y), fontsize=7, xytext=(4, 0), textcoords="offset points",
                    va="center")
    for c in res.criticals:
        ax.plot([c.rpm], [c.freq_hz], "kX", ms=8)
    for (x, y), text in _critical_labels(ax, res.criticals):
        right = x > 0.7 * x_max                    # keep clear of the branch numbers
        ax.annotate(text, (x, y), fontsize=7, xytext=(-30 if right else -4, 7),
                    textcoords="offset points", ha="right" if right else "left",
                    bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none",
                          "alpha": 0.8})
    handles = [Line2D([], [], color=_WHIRL_STYLE[w][0], ls=_WHIRL_STYLE[w][1], label=w)
               for w in WHIRL_LABELS if w in used]
    handles.append(Line2D([], [], color="k", lw=0.9, label="excitation k×n/60"))
    handles.append(Patch(color="0.5", alpha=0.3,
                         label=f"±{100 * SEPARATION_MARGIN:g} % separation margin"))
    if res.criticals:
        handles.append(Line2D([], [], color="k", marker="X", ls="", label="critical speed"))
    ax.legend(handles=handles, fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0),
              borderaxespad=0.0)
    ax.set_xlabel("speed [rpm]")
    damped = bool(np.nanmax(np.abs(res.zeta), initial=0.0) > 1e-9)
    ax.set_ylabel(f"{'damped ' if damped else ''}natural frequency [Hz] (log)")
    ax.grid(alpha=0.3, which="both")
    ax.set_title(title or "Campbell diagram")
    fig.text(0.01, 0.01, textwrap.fill(
        f"{res.statement()}. Branch numbers at the right: mode numbers of the table. Band: "
        f"±{100 * SEPARATION_MARGIN:g} % of each excitation frequency (design-practice margin; "
        "API 684/617 derive it from a damped response's amplification factor).", 150),
        fontsize=7, va="bottom")
    fig.tight_layout(rect=(0.0, 0.07, 1.0, 1.0))
    buf = io.BytesIO()
    fig.savefig(buf, format=fmt, dpi=120)
    plt.close(fig)
    return buf.getvalue()
