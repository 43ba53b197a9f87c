"""The Campbell diagram of a ``CampbellResult`` (``shaftfe.rotordynamics.campbell``):
frequency axis and plot. matplotlib (Agg) only inside ``plot_campbell``.
"""

from __future__ import annotations

import numpy as np

from shaftfe.rotordynamics.campbell import CampbellResult
from shaftfe.rotordynamics.kernels import WHIRL_LABELS

_WHIRL_STYLE = {"forward": ("tab:red", "-"), "backward": ("tab:blue", "--"),
                "torsional": ("tab:green", "-."), "axial": ("tab:purple", ":"),
                "undetermined": ("0.4", "-")}


def campbell_top_hz(res: CampbellResult) -> float:
    """The frequency axis of a Campbell diagram: the excitation region (highest order at the
    top speed) with room above it, and the first two branches (a whirl pair) above it, not the
    10 kHz of the highest mode computed (which squashes the region that matters)."""
    f_max = float(np.max(res.freq_hz))
    f_exc = max(res.orders, default=1.0) * float(res.rpm.max()) / 60.0
    tops = np.sort(np.max(res.freq_hz, axis=0))
    f_pair = float(tops[min(1, tops.size - 1)])
    return min(max(1.5 * f_exc, 1.1 * f_pair), 1.08 * f_max) if f_max > 0 else 1.0


def plot_campbell(res: CampbellResult, title: str = "", fmt: str = "png",
                  f_max_hz: float | None = None) -> bytes:
    """Campbell diagram: frequency [Hz] vs speed [rpm], branches styled by whirl, engine-order
    lines, critical speeds marked. Returns image bytes."""
    import io

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    fig, ax = plt.subplots(figsize=(8, 5.5))
    used = set()
    top = f_max_hz or campbell_top_hz(res)
    for j in range(res.freq_hz.shape[1]):
        c, ls = _WHIRL_STYLE.get(res.branch_whirl[j], _WHIRL_STYLE["undetermined"])
        if np.min(res.freq_hz[:, j]) <= top:            # the legend names what is shown
            used.add(res.branch_whirl[j])
        ax.plot(res.rpm, res.freq_hz[:, j], color=c, ls=ls, marker="o", ms=3, lw=1.2)
        ax.annotate(f"{j + 1}", (res.rpm[-1], res.freq_hz[-1, j]), fontsize=7,
                    xytext=(3, 0), textcoords="offset points", va="center")
    hidden = int(np.sum(np.min(res.freq_hz, axis=0) > top))
    n_line = np.array([res.rpm.min(), res.rpm.max()])
    for k in res.orders:
        ax.plot(n_line, k * n_line / 60.0, color="k", lw=0.8)
        ax.annotate(f"{k:g}×", (n_line[-1], k * n_line[-1] / 60.0), fontsize=8,
                    xytext=(3, 0), textcoords="offset points")
    for c in res.criticals:
        ax.plot([c.rpm], [c.freq_hz], "kX", ms=9)
        ax.annotate(f"{c.rpm:.0f} rpm", (c.rpm, c.freq_hz), fontsize=8, xytext=(4, -10),
                    textcoords="offset points")
    handles = [Line2D([], [], color=_WHIRL_STYLE[w][0], ls=_WHIRL_STYLE[w][1], label=w)
               for w in WHIRL_LABELS if w in used]
    handles.append(Line2D([], [], color="k", lw=0.8, label="excitation k×n/60"))
    if res.criticals:
        handles.append(Line2D([], [], color="k", marker="X", ls="", label="critical speed"))
    ax.legend(handles=handles, fontsize=8, loc="best")
    ax.set_xlabel("speed [rpm]")
    damped = bool(np.nanmax(np.abs(res.zeta), initial=0.0) > 1e-9)
    ax.set_ylabel(f"{'damped ' if damped else ''}natural frequency [Hz]")
    if hidden:
        ax.text(0.01, 0.98, f"{hidden} higher mode{'s' if hidden > 1 else ''} above "
                f"{top:.0f} Hz not shown (up to {np.max(res.freq_hz):.0f} Hz): see the table",
                transform=ax.transAxes, fontsize=8, va="top")
    ax.set_ylim(0, top)
    ax.set_xlim(res.rpm.min(), res.rpm.max() * 1.04 if res.rpm.max() > 0 else 1)
    ax.grid(alpha=0.3)
    ax.set_title(title or "Campbell diagram")
    import textwrap

    fig.text(0.01, 0.01, textwrap.fill(res.statement(), 140), fontsize=7, va="bottom")
    fig.tight_layout(rect=(0.0, 0.06, 1.0, 1.0))
    buf = io.BytesIO()
    fig.savefig(buf, format=fmt, dpi=120)
    plt.close(fig)
    return buf.getvalue()
