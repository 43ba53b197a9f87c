"""Single-cylinder shaking forces over one revolution and their metrics (seed 000 §5.2-5.4).

Forces are the resultant inertia force the crank mechanism plus a 1:1 counter-rotating balancer
shaft exert on the crankcase, in the engine frame (the cylinder frame turned by the tilt β,
see ``kinematics.rotate``). Metrics over one revolution: max|Fx|, max|Fy|, RMS|F|, max|F|, each
peak with its crank angle.

Sampling (``sampling=``):

* ``"period"`` (default): ``n`` uniform samples over one period without the duplicate end point;
  the RMS is then the exact period RMS (the integrand is smooth and periodic, so the uniform
  rule converges spectrally). Default ``n`` = 3600 (0.1°).
* ``"seed_inclusive"``: 0…360° inclusive, ``n`` steps (default 360, i.e. the seed's 1° grid
  with TDC counted twice). Only to reproduce the seed's table (its RMS is ≈ 0.26 % high).

API units: X, X2 as fractions (0.3016 = 30.16 %), rpm, degrees; forces in N.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from shaftfe.balance import kinematics as kin
from shaftfe.balance.engines import Engine, load_engine
from shaftfe.errors import InputError

Sampling = Literal["period", "seed_inclusive"]
SAMPLINGS: tuple[str, ...] = ("period", "seed_inclusive")
DEFAULT_N = {"period": 3600, "seed_inclusive": 360}
RATIO_RANGE = (0.0, 2.0)   # X, X2 allowed as fractions ([0, 200] %)


def crank_ratio(m_C: float, gamma: float, m_rot: float, m_pos: float, R: float) -> float:
    """X = (m_C γ − m_rot R) / (m_pos R) (seed 000 eq. 2.3.f) as a fraction; γ, R in one unit."""
    return (m_C * gamma - m_rot * R) / (m_pos * R)


def balancer_ratio(m_vh: float, gamma2: float, m_pos: float, R: float) -> float:
    """X2 = m_vh γ2 / (m_pos R) (seed 000 eq. 2.3.h), as a fraction."""
    return m_vh * gamma2 / (m_pos * R)


def sample_angles_deg(sampling: str = "period", n: int | None = None,
                      start_deg: float = 0.0) -> NDArray[np.float64]:
    """Crank angles [deg] of one revolution from ``start_deg`` (see the module docstring)."""
    if sampling not in SAMPLINGS:
        raise InputError("--sampling", "sampling", " or ".join(SAMPLINGS), got=sampling)
    n = DEFAULT_N[sampling] if n is None else int(n)
    if not 4 <= n <= 10_000_000:
        raise InputError("--samples", "samples", "in [4, 10000000]", got=n)
    if sampling == "period":
        return start_deg + np.arange(n) * (360.0 / n)
    return start_deg + np.arange(n + 1) * (360.0 / n)


@dataclass(frozen=True)
class Metrics:
    """Peaks and RMS of one revolution; angles are crank angles in [0, 360) deg from TDC."""

    max_abs_fx: float
    max_abs_fx_deg: float
    max_abs_fy: float
    max_abs_fy_deg: float
    rms_f: float
    max_f: float
    max_f_deg: float

    def as_dict(self) -> dict[str, float]:
        return {k: float(getattr(self, k)) for k in self.__dataclass_fields__}


def metric_arrays(Fx: NDArray, Fy: NDArray, with_index: bool = True) -> dict[str, NDArray]:
    """max|Fx|, max|Fy|, RMS|F|, max|F| (and the sample index of each peak) over the last axis.

    The RMS is the plain mean over the given samples: pass a period without the end point for
    the exact RMS, or the seed's inclusive grid to reproduce the seed.
    """
    F2 = Fx * Fx
    F2 += Fy * Fy
    if not with_index:
        return {"max_abs_fx": np.abs(Fx).max(-1), "max_abs_fy": np.abs(Fy).max(-1),
                "rms_f": np.sqrt(F2.mean(-1)), "max_f": np.sqrt(F2.max(-1))}
    ax, ay = np.abs(Fx), np.abs(Fy)
    ix, iy, iF = ax.argmax(-1), ay.argmax(-1), F2.argmax(-1)
    return {
        "max_abs_fx": np.take_along_axis(ax, ix[..., None], -1)[..., 0], "i_fx": ix,
        "max_abs_fy": np.take_along_axis(ay, iy[..., None], -1)[..., 0], "i_fy": iy,
        "rms_f": np.sqrt(F2.mean(-1)),
        "max_f": np.sqrt(np.take_along_axis(F2, iF[..., None], -1)[..., 0]), "i_f": iF,
    }


@dataclass(frozen=True)
class ForceResult:
    """Shaking forces of one revolution (engine frame) and their metrics."""

    engine: str
    X: float                      # fractions
    X2: float
    rpm: float
    tilt_deg: float
    start_deg: float
    sampling: str
    alpha_deg: NDArray[np.float64]   # crank angle of each sample (from start_deg)
    Fx: NDArray[np.float64]          # total, engine frame [N]
    Fy: NDArray[np.float64]
    Fx_crank: NDArray[np.float64]    # crank mechanism alone (F_vk, no balancer), engine frame
    Fy_crank: NDArray[np.float64]
    first_order_amplitude: float     # A = m_pos R ω² [N]
    metrics: Metrics

    @property
    def F(self) -> NDArray[np.float64]:
        return np.hypot(self.Fx, self.Fy)

    @property
    def Fx_balancer(self) -> NDArray[np.float64]:
        return self.Fx - self.Fx_crank

    @property
    def Fy_balancer(self) -> NDArray[np.float64]:
        return self.Fy - self.Fy_crank

    def summary(self, engine: Engine) -> dict:
        """What ``shaftfe balance forces`` reports (its ``--json``, but the written files'
        paths, which the command adds): the engine, X and X2 in %, the options, A = m_pos R ω²
        in N and the metrics (N, deg)."""
        return {"engine": engine.info(), "X_percent": 100 * self.X,
                "X2_percent": 100 * self.X2, "rpm": self.rpm, "tilt_deg": self.tilt_deg,
                "start_deg": self.start_deg, "sampling": self.sampling,
                "samples": int(self.alpha_deg.size),
                "first_order_amplitude_N": self.first_order_amplitude,
                "metrics": self.metrics.as_dict()}

    @property
    def max_crank_force(self) -> tuple[float, float]:
        """(max |F_vk| N, its crank angle in deg within one turn): the crank mechanism alone."""
        f = np.hypot(self.Fx_crank, self.Fy_crank)
        i = int(f.argmax())
        return float(f[i]), float(self.alpha_deg[i] % 360.0)


def check_ratio(value: float, option: str) -> float:
    lo, hi = RATIO_RANGE
    if not np.isfinite(value) or not lo <= value <= hi:
        raise InputError(option, option.lstrip("-"), f"in [{100 * lo:g}, {100 * hi:g}] %",
                         got=round(100 * float(value), 6))
    return float(value)


def resolve_ratios(engine: Engine, X: float | None, X2: float | None) -> tuple[float, float]:
    """X, X2 (fractions): the given value, else the engine's; X2 defaults to 0 (no balancer)."""
    if X is None:
        X = engine.X
        if X is None:
            raise InputError(engine.source, "compensation_mass_kg",
                             "compensation_mass_kg + compensation_radius_mm, crank parts, "
                             "crank_balance_percent, or X given explicitly (--x)",
                             reason="is missing")
    if X2 is None:
        X2 = engine.X2 if engine.X2 is not None else 0.0
    return check_ratio(X, "--x"), check_ratio(X2, "--x2")


def forces(engine: Engine | str, X: float | None = None, X2: float | None = None,
           rpm: float | None = None, *, tilt_deg: float | None = None, start_deg: float = 0.0,
           sampling: Sampling = "period", n: int | None = None) -> ForceResult:
    """Shaking forces of ``engine`` over one revolution (seed 000 §5.1-5.3).

    ``engine`` is an ``Engine`` or a name/path for ``load_engine``. X, X2 are fractions (None →
    from the engine file); rpm None → the file's ``rpm``; tilt None → the file's ``tilt_deg``
    (metrics are in the engine frame; tilt 0 gives the cylinder frame the seed's §5.4 table
    uses). Exact slider-crank kinematics.
    """
    if not isinstance(engine, Engine):
        engine = load_engine(engine)
    X, X2 = resolve_ratios(engine, X, X2)
    rpm = engine.rpm if rpm is None else float(rpm)
    if not np.isfinite(rpm) or rpm <= 0:
        raise InputError("--rpm", "rpm", "> 0", got=rpm)
    tilt = engine.tilt_deg if tilt_deg is None else float(tilt_deg)
    if not np.isfinite(start_deg):
        raise InputError("--start-deg", "start_deg", "a finite angle", got=start_deg)
    alpha_deg = sample_angles_deg(sampling, n, start_deg)
    alpha = np.deg2rad(alpha_deg)
    R, T1 = engine.crank_radius_mm / 1000.0, engine.rod_length_mm / 1000.0
    omega = float(kin.rad_per_s(rpm))
    m_pos = engine.m_pos_kg
    # row 0: crank + balancer; row 1: crank mechanism alone (F_vk, X2 = 0)
    fx, fy = kin.shaking_forces(alpha, m_pos, R, T1, omega, np.array([[X], [X]]),
                                np.array([[X2], [0.0]]))
    beta = np.deg2rad(tilt)
    fx, fy = kin.rotate(fx, fy, beta)
    m = metric_arrays(fx[0], fy[0])
    ang = np.mod(alpha_deg, 360.0)
    metrics = Metrics(
        max_abs_fx=float(m["max_abs_fx"]), max_abs_fx_deg=float(ang[m["i_fx"]]),
        max_abs_fy=float(m["max_abs_fy"]), max_abs_fy_deg=float(ang[m["i_fy"]]),
        rms_f=float(m["rms_f"]), max_f=float(m["max_f"]), max_f_deg=float(ang[m["i_f"]]),
    )
    return ForceResult(
        engine=engine.name, X=X, X2=X2, rpm=rpm, tilt_deg=tilt, start_deg=float(start_deg),
        sampling=sampling, alpha_deg=alpha_deg, Fx=fx[0], Fy=fy[0], Fx_crank=fx[1],
        Fy_crank=fy[1], first_order_amplitude=m_pos * R * omega**2, metrics=metrics,
    )
