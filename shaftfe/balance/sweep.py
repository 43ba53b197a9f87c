"""Balance-ratio sweeps (seed 000 §5.4): metrics over an X2 range for one X or an X range.

Mode 1: fixed X → max|Fx|, max|Fy|, RMS|F|, max|F| as curves over X2.
Mode 2: X range too → for each X the minimum of each metric and the X2 where it occurs (the
seed's a × 8 matrix, ``SweepResult.seed_matrix``). Ties resolve to the lowest X2, as Matlab's
``min`` does.

Everything is evaluated on the (X, X2, angle) grid by broadcasting; the slider-crank term is
computed once per angle. Large grids are processed in blocks of X rows to bound memory.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from shaftfe.balance import kinematics as kin
from shaftfe.balance.engines import Engine, load_engine
from shaftfe.balance.single import (
    RATIO_RANGE,
    Sampling,
    metric_arrays,
    sample_angles_deg,
)
from shaftfe.errors import InputError

METRICS = ("max_abs_fx", "max_abs_fy", "rms_f", "max_f")
_BLOCK = 400_000     # grid points (X2 × angle) per block (cache-sized: ~3 MB arrays)


def percent_grid(start: float, stop: float, step: float | None, option: str
                 ) -> NDArray[np.float64]:
    """start, start+step, … ≤ stop (percent); a single value when step is None and start = stop."""
    lo, hi = 100 * RATIO_RANGE[0], 100 * RATIO_RANGE[1]
    allowed = f"a:b[:step] with {lo:g} <= a <= b <= {hi:g} %, step > 0"
    if not (lo <= start <= stop <= hi):
        raise InputError(option, option.lstrip("-"), allowed, got=f"{start:g}:{stop:g}")
    if step is None:
        step = 1.0
    if step <= 0:
        raise InputError(option, option.lstrip("-"), allowed, got=step)
    n = int(np.floor((stop - start) / step + 1e-9)) + 1
    if n > 100_000:
        raise InputError(option, option.lstrip("-"), "at most 100000 values", got=n)
    return np.round(start + step * np.arange(n), 10)


@dataclass(frozen=True)
class SweepResult:
    """Metrics on the (X, X2) grid; X, X2 as fractions, forces in N (engine frame)."""

    engine: str
    rpm: float
    tilt_deg: float
    sampling: str
    n_angles: int
    X: NDArray[np.float64]           # (a,)
    X2: NDArray[np.float64]          # (b,)
    max_abs_fx: NDArray[np.float64]  # (a, b)
    max_abs_fy: NDArray[np.float64]
    rms_f: NDArray[np.float64]
    max_f: NDArray[np.float64]

    def minima(self) -> dict[str, tuple[NDArray[np.float64], NDArray[np.float64]]]:
        """metric → (minimum over X2 for each X, X2 fraction at that minimum)."""
        out = {}
        for k in METRICS:
            v = getattr(self, k)
            i = v.argmin(axis=1)
            out[k] = (v[np.arange(v.shape[0]), i], self.X2[i])
        return out

    @property
    def mode(self) -> int:
        """1: one X (a sweep over X2), 2: a grid of X and X2 (the minima over X2 per X)."""
        return 1 if self.X.size == 1 else 2

    def summary(self, engine) -> dict:
        """What ``shaftfe balance sweep`` reports (its ``--json``, but the written files'
        paths, which the command adds): X and X2 in %, each metric's minimum over X2 per X
        (N, and the X2 in % where it lies) and the whole grid (N)."""
        mins = self.minima()
        return {"engine": engine.info(), "mode": self.mode, "rpm": self.rpm,
                "tilt_deg": self.tilt_deg, "sampling": self.sampling, "samples": self.n_angles,
                "X_percent": (100 * self.X).tolist(), "X2_percent": (100 * self.X2).tolist(),
                "minima": {k: {"value_N": mins[k][0].tolist(),
                               "X2_percent": (100 * mins[k][1]).tolist()} for k in METRICS},
                "grid_N": {k: getattr(self, k).tolist() for k in METRICS}}

    def seed_matrix(self) -> NDArray[np.float64]:
        """The seed's a × 8 matrix: min max|Fx|, min max|Fy|, X2 [%] of each, min RMS,
        min max|F|, X2 [%] of each (seed 000 §5.4, column order as printed there)."""
        m = self.minima()
        return np.column_stack([
            m["max_abs_fx"][0], m["max_abs_fy"][0], 100 * m["max_abs_fx"][1],
            100 * m["max_abs_fy"][1], m["rms_f"][0], m["max_f"][0], 100 * m["rms_f"][1],
            100 * m["max_f"][1],
        ])


def sweep(engine: Engine | str, X: NDArray | list[float] | float, X2: NDArray | list[float],
          rpm: float | None = None, *, tilt_deg: float | None = None,
          sampling: Sampling = "period", n: int | None = None) -> SweepResult:
    """Metrics for every (X, X2) pair (fractions); one X = mode 1, several = mode 2.

    ``engine`` is an ``Engine`` or a name/path; metrics are in the engine frame (tilt from the
    file unless ``tilt_deg`` is given; 0 = cylinder frame, as in the seed's §5.4 table).
    """
    if not isinstance(engine, Engine):
        engine = load_engine(engine)
    Xa = np.atleast_1d(np.asarray(X, dtype=float))
    X2a = np.atleast_1d(np.asarray(X2, dtype=float))
    lo, hi = RATIO_RANGE
    for arr, opt in ((Xa, "--x"), (X2a, "--x2")):
        if arr.ndim != 1 or arr.size == 0:
            raise InputError(opt, opt.lstrip("-"), "a non-empty 1-D list of ratios", got=arr.shape)
        bad = arr[~((arr >= lo) & (arr <= hi))]
        if bad.size:
            raise InputError(opt, opt.lstrip("-"), f"in [{100 * lo:g}, {100 * hi:g}] %",
                             got=float(100 * bad[0]))
    rpm = engine.rpm if rpm is None else float(rpm)
    if not np.isfinite(rpm) or rpm <= 0:
        raise InputError("--rpm", "rpm", "> 0", got=rpm)
    tilt = engine.tilt_deg if tilt_deg is None else float(tilt_deg)
    alpha = np.deg2rad(sample_angles_deg(sampling, n))
    R, T1 = engine.crank_radius_mm / 1000.0, engine.rod_length_mm / 1000.0
    omega = float(kin.rad_per_s(rpm))
    m_pos = engine.m_pos_kg
    A = m_pos * R * omega**2
    s, c = np.sin(alpha), np.cos(alpha)
    f_sp = kin.reciprocating_force(alpha, m_pos, R, T1, omega)        # (n,), once
    beta = np.deg2rad(tilt)
    cb, sb = np.cos(beta), np.sin(beta)

    out = {k: np.empty((Xa.size, X2a.size)) for k in METRICS}
    cols = max(1, min(X2a.size, _BLOCK // alpha.size))         # blocks of (X, X2), not angles
    rows = max(1, _BLOCK // (cols * alpha.size))
    for r0 in range(0, Xa.size, rows):
        x = Xa[r0:r0 + rows, None, None]
        for c0 in range(0, X2a.size, cols):
            x2 = X2a[None, c0:c0 + cols, None]
            fx = ((x2 - x) * A) * s                                     # (rows, cols, n)
            fy = f_sp - ((x + x2) * A) * c
            if beta != 0.0:
                fx, fy = fx * cb - fy * sb, fx * sb + fy * cb
            m = metric_arrays(fx, fy, with_index=False)
            for k in METRICS:
                out[k][r0:r0 + rows, c0:c0 + cols] = m[k]
    return SweepResult(engine=engine.name, rpm=rpm, tilt_deg=tilt, sampling=sampling,
                       n_angles=int(alpha.size), X=Xa, X2=X2a, **out)
