"""The report's figure jobs that the second process draws (``report.pictures.Renderer.draw``):
each a module-level function of small, picklable inputs that writes its PNGs and returns
nothing. They live apart from ``report.assemble`` so that the second process, which imports
this module to run them, does not import the whole pipeline (0.1 s and 250 modules here,
against 0.4 s and 570 for ``report.assemble``).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from shaftfe.balance import plots
from shaftfe.fatigue import kernels
from shaftfe.fatigue import plots as fatigue_plots
from shaftfe.fatigue.counting import rainflow_matrix


def draw_balance(fres, sw, fig_dir) -> None:
    """The balancing figures' files (in the pictures' process when there is one)."""
    plots.plot_forces(fres, Path(fig_dir) / "balance_forces.png")
    plots.plot_sweep(sw, Path(fig_dir) / "balance_sweep.png")


@dataclass(frozen=True)
class FatigueFigures:
    """What the fatigue figures need of the run (``draw_fatigue``; small enough to hand to the
    second process): the fatigue history, the hot spot's S0 and softening β and its label, the
    rainflow cycles, the S-N card and the mean-stress rule."""
    history: object
    s0: float
    beta: float
    label: str
    cycles: object
    material: object
    mean_stress: str
    fig_dir: Path


def draw_fatigue(f: FatigueFigures) -> None:
    """The fatigue figures' files (in the pictures' process when there is one): the load
    history, the hot spot's rainflow and damage matrices, its Haigh diagram and the S-N
    curve."""
    fatigue_plots.plot_load_history(f.history, f.fig_dir / "load_history.png")
    fatigue_plots.plot_cycle_matrix(
        rainflow_matrix(kernels.node_stress_cycles(f.s0, f.beta, f.cycles), units="MPa"),
        f.fig_dir / "rainflow_matrix.png",
        title=f"rainflow matrix per block, hot spot {f.label}")
    fatigue_plots.plot_cycle_matrix(
        kernels.damage_matrix(f.s0, f.cycles, f.material, f.mean_stress, 1.0, beta=f.beta),
        f.fig_dir / "damage_matrix.png", title=f"damage matrix per block, hot spot {f.label}")
    fatigue_plots.plot_haigh(f.s0, f.cycles, f.material, f.fig_dir / "haigh.png",
                             f.mean_stress, 1.0, f.beta)
    fatigue_plots.plot_sn_curve(f.material, f.fig_dir / "sn_curve.png")



__all__ = ["FatigueFigures", "draw_balance", "draw_fatigue"]
