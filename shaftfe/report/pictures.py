"""The report's three PyVista pictures (von Mises, displacement, the seed method's safety
factor), rendered from the run's VTU in a second process while the first one computes the
strength section and draws the plots; before them, that process draws the figures that need
nothing of the solve (the balancing figures: ``Renderer.draw``) while the static model solves,
and the fatigue figures while the rotor solves (the jobs: ``report.drawings``).

A process, not a thread: matplotlib draws holding the interpreter's lock, so in one
interpreter the two would take turns. Measured on x2_57's demo (2-core machine): the pictures
2.8 s and the plots 2.0 s one after the other, and the whole demo 8.2 → 6.9 s warm with them
side by side (``benchmarks/bench_zoned.py`` times the demo). The process starts with the run
(``Renderer``) and imports VTK while the static model solves.

``PictureJob`` carries everything the pictures need (file names, the excluded nodes, the
titles and captions made by the parent), so the second process imports only the renderer.
Where no second process can be started, the pictures are rendered in this one, as before.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from shaftfe.io.render import render, use_offscreen_egl
from shaftfe.io.view import load


@dataclass(frozen=True)
class Shot:
    name: str                 # the PNG's stem under figures/
    field: str                # the VTU's point field
    warp: float | str
    title: str                # the report's figure title
    picture_title: str        # drawn into the picture
    caption: str              # the report's caption (the hot spot's value is added to it)


@dataclass(frozen=True, eq=False)
class PictureJob:
    vtu: str
    fig_dir: str
    excluded: np.ndarray      # the singular-point rule's nodes (not marked as hot spots)
    shots: tuple[Shot, ...]
    window_size: tuple[int, int] = (1000, 520)


def render_all(job: PictureJob) -> tuple[list[tuple[str, str, str]], float]:
    """Render every shot of ``job``: ([(name, title, caption)], seconds)."""
    from pathlib import Path

    t0 = time.perf_counter()
    grid = load(job.vtu)                     # read once for every picture
    out = []
    for s in job.shots:
        res = render(job.vtu, field=s.field, warp=s.warp,
                     screenshot=Path(job.fig_dir) / f"{s.name}.png",
                     window_size=job.window_size, off_screen=True, hot_exclude=job.excluded,
                     zoom="fit", grid=grid, title=s.picture_title)
        caption = s.caption
        if res.hot is not None:
            unit = f" {res.field.unit}" if res.field.unit not in ("-", "id") else ""
            caption += (f" Marked: {res.hot.value:.4g}{unit} (nodal value) at x = "
                        f"{res.hot.xyz[0]:.1f} mm.")
        out.append((s.name, s.title, caption))
    return out, time.perf_counter() - t0


class Job:
    """A job of the second process (a module-level function and its arguments: a figure job of
    ``report.drawings``, which writes files and returns nothing, or ``render_all``):
    ``result`` returns what the function returned there, or runs it here where that process
    could not take the job or died (an error of the job itself is raised as it would be
    here)."""

    def __init__(self, fn, args: tuple, future=None):
        self._fn, self._args, self._future = fn, args, future

    def result(self):
        from concurrent.futures.process import BrokenProcessPool
        if self._future is not None:
            try:
                return self._future.result()
            except BrokenProcessPool:
                pass
        return self._fn(*self._args)


def _warm_up() -> str:
    """Import the renderer (VTK through PyVista: most of the second process's start) before
    the job arrives, off screen as the pictures render."""
    use_offscreen_egl()
    import pyvista
    import pyvista.plotting
    return str(pyvista.__version__)


class Renderer:
    """A second process for the pictures, started (and its renderer imported) when the run
    starts, so that its start-up runs beside the static solve; ``start(job)`` then hands it
    the job. Where no second process can be started, ``start`` renders in this one."""

    def __init__(self) -> None:
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor
        try:
            self._pool = ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn"))
            self._pool.submit(_warm_up)
        except (OSError, RuntimeError, ValueError):  # no second process here
            self._pool = None

    def draw(self, fn, *args) -> Job:
        """Hand the second process a figure job (``report.drawings``: the balancing figures,
        which need nothing of the solve, while the static model solves here; the fatigue
        figures while the rotor solves), run before the pictures; run by ``Job.result`` in
        this process where there is no second one."""
        if self._pool is None:
            return Job(fn, args)
        try:
            return Job(fn, args, self._pool.submit(fn, *args))
        except (OSError, RuntimeError):              # the process is gone: run it here
            return Job(fn, args)

    def start(self, job: PictureJob) -> Job:
        """The pictures' job, the last one: the process ends once it is done."""
        try:
            return self.draw(render_all, job)
        finally:
            if self._pool is not None:
                self._pool.shutdown(wait=False)

    def close(self) -> None:
        """Stop the second process after an error of the run (before the pictures, or while the
        strength section, the plots or the pictures are made): the jobs not started are
        dropped, and a figure it is drawing is waited for, so that no file lands in the output
        folder after the run has removed it (a run writes all its outputs or none)."""
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)


__all__ = ["Job", "PictureJob", "Renderer", "Shot", "render_all"]
