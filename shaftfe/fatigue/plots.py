"""Fatigue figures (PNG): load history, S-N curve, rainflow and damage matrices of a hot spot
(seed 000 Obr. 65, 68, 69) and its Haigh diagram. matplotlib (Agg) is imported inside the
functions, so importing this module costs nothing. Every function returns the written path.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from shaftfe.fatigue.counting import CycleMatrix, Cycles
from shaftfe.fatigue.sn import FatigueMaterial


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path) -> Path:
    """Write the figure atomically (never a half-written PNG) and close it."""
    from shaftfe.util.atomic import atomic_path

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
    """rpm and load factor against time (seed Obr. 65 / 88)."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(9, 3.5))
    ax.step(history.time_s, history.rpm, where="post", color="tab:blue")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("engine speed [rpm]", color="tab:blue")
    ax2 = ax.twinx()
    ax2.step(history.time_s, history.load_factor, where="post", color="tab:red", alpha=0.4)
    ax2.set_ylabel(f"load factor (rpm/{history.rpm_ref:g})²", color="tab:red")
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
    ax.set_xlabel("cycles to failure N [-]")
    ax.set_ylabel("alternating stress [MPa] (mean 0)")
    ax.set_title(material.name)
    ax.grid(which="both", alpha=0.3)
    ax.legend()
    return _save(fig, path)


def plot_cycle_matrix(matrix: CycleMatrix, path, title: str = "") -> Path:
    """Rainflow (counts) or damage matrix as a range × mean heat map (seed Obr. 68 / 69)."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6, 4.5))
    v = np.ma.masked_equal(matrix.values, 0.0)
    mesh = ax.pcolormesh(matrix.mean_edges, matrix.range_edges, v, cmap="viridis",
                         shading="flat")
    count = matrix.quantity == "count"
    fig.colorbar(mesh, ax=ax, label=("cycles per block" if count else "damage per block [-]"),
                 format=None if count else "%.2g")
    unit = f" [{matrix.units}]" if matrix.units else ""
    ax.set_xlabel("mean" + unit)
    ax.set_ylabel("range" + unit)
    ax.set_title(title or f"{matrix.quantity} matrix")
    return _save(fig, path)


HAIGH_MAX_POINTS = 20_000


def plot_haigh(sigma_eq_node: float, cycles: Cycles, material: FatigueMaterial, path,
               theory: str = "soderberg", kf: float = 1.0, beta: float = 0.0) -> Path:
    """Haigh diagram of one node (linear stress ``sigma_eq_node`` = S0, spin softening
    ``beta``): its cycles (σ_m, σ_a), marker area ∝ count, and the chosen mean-stress line
    through the endurance amplitude kf · S_e (the S-N curve's last point)."""
    from shaftfe.fatigue.kernels import stress_cycles
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
