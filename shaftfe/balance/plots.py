"""Plots of the balancing results (matplotlib Agg, imported inside the functions only).

``plot_forces``: the seed's three views (seed 000 §5.2): Fx, Fy, |F| over the crank angle;
the force vector in polar coordinates; the hodograph Fy(Fx).
``plot_sweep``: mode 1 curves over X2 (seed 000 Fig. 31), or for mode 2 the minima over X and the
X2 at which they occur. Figures are rendered to memory and written atomically.
"""

from __future__ import annotations

import io
from pathlib import Path

from shaftfe.util.atomic import PLOT_SUFFIXES, check_suffix, write_atomic


def _check_path(path: str | Path, option: str = "--plot") -> str:
    """The figure's format from its file name (``util.atomic.check_suffix``: the one rule)."""
    return check_suffix(path, option, PLOT_SUFFIXES).suffix.lower().lstrip(".")


def _save(fig, path: str | Path, fmt: str) -> Path:

    buf = io.BytesIO()
    fig.savefig(buf, format=fmt, dpi=120, bbox_inches="tight")
    return write_atomic(path, buf.getvalue())


def _figure(*args, **kwargs):
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    kwargs.setdefault("layout", "constrained")
    return Figure(*args, **kwargs)


def plot_forces(result, path: str | Path) -> Path:
    """Fx, Fy, |F| vs crank angle; polar |F|; Fy(Fx). ``result`` is a ``single.ForceResult``."""
    import numpy as np

    fmt = _check_path(path)
    fig = _figure(figsize=(14, 4.6))
    ax1 = fig.add_subplot(1, 3, 1)
    a = result.alpha_deg
    ax1.plot(a, result.Fx, label="Fx")
    ax1.plot(a, result.Fy, label="Fy")
    ax1.plot(a, result.F, "k", label="|F|")
    ax1.plot(a, np.hypot(result.Fx_crank, result.Fy_crank), "k:", lw=1,
             label="|F_vk| (crank alone)")
    ax1.set_xlabel("crank angle from TDC [deg]")
    ax1.set_ylabel("force [N]")
    ax1.grid(True, alpha=0.3)
    ax1.legend(fontsize=8)
    ax1.set_title(f"{result.engine}: X = {100 * result.X:.2f} %, X2 = {100 * result.X2:.2f} %, "
                  f"{result.rpm:g} rpm", fontsize=9)
    ax2 = fig.add_subplot(1, 3, 2, projection="polar")
    th = np.arctan2(result.Fy, result.Fx)
    ax2.plot(np.append(th, th[:1]), np.append(result.F, result.F[:1]))
    ax2.set_title("|F| [N] against the force direction (engine frame)", fontsize=9)
    ax3 = fig.add_subplot(1, 3, 3)
    ax3.plot(result.Fx, result.Fy)
    ax3.plot([0], [0], "k+")
    ax3.set_aspect("equal", adjustable="datalim")
    ax3.set_xlabel("Fx [N]")
    ax3.set_ylabel("Fy [N]")
    ax3.grid(True, alpha=0.3)
    ax3.set_title(f"Fy(Fx), tilt {result.tilt_deg:g} deg", fontsize=9)
    return _save(fig, path, fmt)


_LABELS = {"max_abs_fx": "max|Fx|", "max_abs_fy": "max|Fy|", "rms_f": "RMS|F|",
           "max_f": "max|F|"}
_COLORS = {"max_abs_fx": "tab:blue", "max_abs_fy": "tab:green", "rms_f": "tab:red",
           "max_f": "k"}


def plot_sweep(result, path: str | Path) -> Path:
    """Mode 1 (one X): metrics over X2. Mode 2: minima over X and their X2."""
    fmt = _check_path(path)
    if result.X.size == 1:
        fig = _figure(figsize=(7, 4.6))
        ax = fig.add_subplot(1, 1, 1)
        for k, lab in _LABELS.items():
            ax.plot(100 * result.X2, getattr(result, k)[0], color=_COLORS[k], label=lab)
        ax.set_xlabel("X2 [%]")
        ax.set_ylabel("force [N]")
        ax.set_title(f"{result.engine}: X = {100 * result.X[0]:.2f} %, {result.rpm:g} rpm, "
                     f"tilt {result.tilt_deg:g} deg", fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        return _save(fig, path, fmt)
    mins = result.minima()
    fig = _figure(figsize=(12, 4.6))
    ax1 = fig.add_subplot(1, 2, 1)
    ax2 = fig.add_subplot(1, 2, 2)
    for k, lab in _LABELS.items():
        ax1.plot(100 * result.X, mins[k][0], "o-", ms=3, color=_COLORS[k], label=f"min {lab}")
        ax2.plot(100 * result.X, 100 * mins[k][1], "o-", ms=3, color=_COLORS[k],
                 label=f"X2 at min {lab}")
    ax1.set_ylabel("force [N]")
    ax2.set_ylabel("X2 [%]")
    for ax in (ax1, ax2):
        ax.set_xlabel("X [%]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    ax1.set_title(f"{result.engine}: minima over X2, {result.rpm:g} rpm", fontsize=9)
    return _save(fig, path, fmt)


def plot_multi(res, title: str, fmt: str) -> bytes:
    """A multi-cylinder result: forces, force locus, couples and the order spectrum."""
    import io

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    deg = np.degrees(res.theta)
    fig, ax = plt.subplots(2, 2, figsize=(11, 8))
    a = ax[0, 0]
    a.plot(deg, res.Fx, label="Fx")
    a.plot(deg, res.Fy, label="Fy")
    a.plot(deg, res.F, "k", lw=1, label="|F|")
    a.set(xlabel="crank angle [deg]", ylabel="force [N]", title="resultant force")
    a.legend()
    a.grid(alpha=0.3)
    a = ax[0, 1]
    a.plot(res.Fx, res.Fy)
    a.set(xlabel="Fx [N]", ylabel="Fy [N]", title="force locus")
    a.set_aspect("equal", adjustable="datalim")
    a.grid(alpha=0.3)
    a = ax[1, 0]
    a.plot(deg, res.Mx, label="Mx (pitch)")
    a.plot(deg, res.My, label="My (yaw)")
    a.set(xlabel="crank angle [deg]", ylabel="couple [N m]", title="resultant couple")
    a.legend()
    a.grid(alpha=0.3)
    a = ax[1, 1]
    ks = np.array([o.order for o in res.force_orders])
    a.bar(ks - 0.2, [o.amplitude for o in res.force_orders], 0.4, label="|F_k| [N]")
    a2 = a.twinx()
    a2.bar(ks + 0.2, [o.amplitude for o in res.couple_orders], 0.4, color="C1",
           label="|M_k| [N m]")
    a.set(xlabel="order", ylabel="force amplitude [N]", title="orders", xticks=ks)
    a2.set_ylabel("couple amplitude [N m]")
    a.legend(loc="upper left")
    a2.legend(loc="upper right")
    fig.suptitle(title)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format=fmt, dpi=110)
    plt.close(fig)
    return buf.getvalue()
