"""Shaking forces and couples of engines with several cylinders (seed 000 §4.3, ch. 7).

Frames and conventions
----------------------
Engine frame: ``y`` up (the bisector of a V, the cylinder axis of an upright inline engine),
``x`` across, ``z`` along the crank axis. Each cylinder ``i`` has

* a tilt ``β_i`` (counter-clockwise, as :func:`shaftfe.balance.kinematics.rotate`: positive β
  turns the cylinder axis from +y towards −x),
* a TDC phase ``φ_i``: the engine crank angle θ at which that cylinder is at TDC, so its own
  crank angle is ``α_i = θ − φ_i`` (seed ch. 7 writes ``α_i = α + α0_i`` with ``α0_i = −φ_i``),
* an axial position ``z_i`` along the crank,
* its own compensation ratio ``X_i`` (a counterweight opposite *its* crank pin, fraction of
  ``m_pos R``) and, for completeness, a counter-rotating 1:1 ratio ``X2_i`` (0 for all the
  multi-cylinder layouts here).

Every cylinder's force is the single-cylinder one in its own frame
(``Fx = (X2 − X) A sin α``, ``Fy = F_sp − (X + X2) A cos α``, ``A = m_pos R ω²``, exact
slider-crank ``F_sp``), rotated by ``β_i`` into the engine frame and summed (seed ch. 7). In the
engine frame the crank pin of cylinder ``i`` points along ``(sin(α_i − β_i), cos(α_i − β_i))``:
the crank turns clockwise seen from +z, i.e. towards +x from +y.

Couples: a force ``F_i = (Fx_i, Fy_i, 0)`` acting on the crank axis at ``(0, 0, z_i)`` has the
moment ``z_i e_z × F_i = (−z_i Fy_i, z_i Fx_i, 0)`` about the origin. ``Mx`` (about the
transverse axis) is the pitching couple, ``My`` (about the vertical axis) the yawing couple.
The origin is the mean axial position of the cylinders; the couple only depends on it when the
resultant force is not zero. The seeds' planar model has no couples.

Harmonic orders
---------------
Over one revolution, ``n`` uniform samples ``θ_j = 2π j / n`` (no duplicate end point), the
complex signal ``w = Fx + i Fy`` has Fourier coefficients ``c_m`` (``w = Σ c_m e^{i m θ}``).
Order ``k`` is the sum of a vector turning with the crank (``c_{−k}``, a crank counterweight
can cancel it) and one turning against it (``c_{+k}``, needs a counter-rotating shaft). Its
locus is an ellipse with semi-major axis ``|c_k| + |c_{−k}|`` (the order's amplitude, "max |F_k|")
and semi-minor axis ``||c_k| − |c_{−k}||``. The component amplitudes are ``2 |X_k| / n`` of the
real FFTs of ``Fx`` and ``Fy``.

Twin (seed §4.3.1, ch. 7)
-------------------------
Cylinder 1 tilted ``β1 = δ/2``, cylinder 2 ``β2 = −δ/2``, ``α02 = α01 − δ − ε``
(so ``φ_2 = δ + ε``): crank pin 2 trails pin 1 by ε. With this ``α02`` the counter-rotating
1st order cancels iff ``2δ + ε ≡ 180° (mod 360°)``, i.e. ``ε = 180° − 2δ``. The seed prints
``ε = 2δ − 180°``, which is the same angle modulo 360° only for δ ∈ {0°, 90°, 180°} (its three
worked cases); for other δ the seed's sign belongs to ε measured the other way round, so
:func:`default_epsilon` returns ``180° − 2δ`` (normalised to (−180°, 180°]).

The co-rotating 1st order of the two cylinders is ``(A/2)(p1 + p2)`` (``p_i`` the unit pin
vectors), so a counterweight of ``X_i = 50 %`` opposite *each* pin cancels it for any δ, ε. Their
resultant is ``|p1 + p2|/2 = |cos(ε/2)| = sin δ`` of one cylinder's ``m_pos R`` — that is the
seed's ``X = 100 sin δ %``, which is a crank balance factor "related to one cylinder" (seed
§4.3.1), i.e. the *resultant* counterweight, not a value to put opposite each pin: ``sin δ``
at each pin leaves a 1st-order residual of ``sin δ |1 − 2 sin δ| A`` (one whole cylinder's ``A``
at δ = 90°).

Shared pin (V-twin, both rods on one pin): ε = 0 and the second cylinder's compensation mass is
removed (``X_2 = 0``); the remaining mass at pin 1 is the whole crank counterweight,
``X_1 = 100 %`` by default, which cancels the co-rotating 1st order for any δ and leaves
``A |cos δ|`` counter-rotating (zero at 90°).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from shaftfe.balance.kinematics import rotate, shaking_forces
from shaftfe.errors import InputError

DEFAULT_ORDERS = (1, 2, 4, 6)
DEFAULT_SAMPLES = 720


@dataclass(frozen=True)
class Cylinder:
    """One cylinder of a multi-cylinder engine (angles in degrees, position in metres)."""

    phase_deg: float = 0.0    # engine crank angle θ at which this cylinder is at TDC
    tilt_deg: float = 0.0     # β, counter-clockwise (kinematics.rotate)
    z_m: float = 0.0          # axial position along the crank
    X: float = 0.0            # crank counterweight opposite this pin, fraction of m_pos R
    X2: float = 0.0           # counter-rotating 1:1 balancer share, fraction of m_pos R


@dataclass(frozen=True)
class Mechanism:
    """Crank mechanism shared by all cylinders (SI units)."""

    R: float          # crank radius [m]
    T1: float         # rod length [m]
    m_pos: float      # reciprocating mass per cylinder [kg]

    def amplitude(self, omega: float) -> float:
        """One cylinder's 1st-order reciprocating amplitude A = m_pos R ω² [N]."""
        return self.m_pos * self.R * omega**2


@dataclass(frozen=True)
class Order:
    """One harmonic order of a planar vector signal (force in N or couple in N·m)."""

    order: int
    amplitude: float          # semi-major axis of the order's ellipse = max over θ of |v_k|
    minor: float              # semi-minor axis
    x: float                  # amplitude of the x component
    y: float                  # amplitude of the y component
    co_rotating: float        # part turning with the crank
    counter_rotating: float   # part turning against the crank

    def as_dict(self) -> dict[str, float | int]:
        return {"order": self.order, "amplitude": self.amplitude, "minor": self.minor,
                "x": self.x, "y": self.y, "co_rotating": self.co_rotating,
                "counter_rotating": self.counter_rotating}


@dataclass(frozen=True)
class MultiResult:
    """Resultant force and couple over one revolution, and their harmonic orders."""

    theta: NDArray[np.float64] = field(repr=False)     # (n,) engine crank angle [rad]
    Fx: NDArray[np.float64] = field(repr=False)        # (n,) resultant force [N]
    Fy: NDArray[np.float64] = field(repr=False)
    Mx: NDArray[np.float64] = field(repr=False)        # (n,) resultant couple [N·m]
    My: NDArray[np.float64] = field(repr=False)
    Fx_cyl: NDArray[np.float64] = field(repr=False)    # (N, n) per cylinder, engine frame
    Fy_cyl: NDArray[np.float64] = field(repr=False)
    force_orders: tuple[Order, ...]
    couple_orders: tuple[Order, ...]
    A: float                                           # one cylinder's m_pos R ω² [N]
    z_ref_m: float                                     # axial reference of the couple

    @property
    def F(self) -> NDArray[np.float64]:
        return np.hypot(self.Fx, self.Fy)

    @property
    def M(self) -> NDArray[np.float64]:
        return np.hypot(self.Mx, self.My)

    @property
    def max_force(self) -> float:
        return float(self.F.max())

    @property
    def max_couple(self) -> float:
        return float(self.M.max())

    @property
    def max_force_at_deg(self) -> float:
        """The engine crank angle θ [deg, 0 … 360) of the largest resultant force (the first
        sample on a tie)."""
        return math.degrees(self.theta[int(np.argmax(self.F))])

    @property
    def max_couple_at_deg(self) -> float:
        """The engine crank angle θ [deg, 0 … 360) of the largest resultant couple (the first
        sample on a tie)."""
        return math.degrees(self.theta[int(np.argmax(self.M))])

    def force_order(self, k: int) -> Order:
        return _pick(self.force_orders, k)

    def couple_order(self, k: int) -> Order:
        return _pick(self.couple_orders, k)


def _pick(orders: tuple[Order, ...], k: int) -> Order:
    for o in orders:
        if o.order == k:
            return o
    raise KeyError(f"order {k} was not computed")


# the samples per revolution: at least 8 (orders 1..3), at most a million (memory: N × n × 8 B)
MIN_SAMPLES, MAX_SAMPLES = 8, 1_000_000


def check_samples(n: int) -> int:
    """``n`` samples per revolution: a whole number (16 or 16.0) within [MIN_SAMPLES,
    MAX_SAMPLES]."""
    if isinstance(n, bool | np.bool_) or not (
            isinstance(n, int | np.integer | float | np.floating)
            and MIN_SAMPLES <= n <= MAX_SAMPLES and float(n).is_integer()):
        raise InputError("--samples", "samples", f"{MIN_SAMPLES} <= samples <= {MAX_SAMPLES}",
                         got=n)
    return int(n)


def check_orders(orders: Sequence[int], n: int) -> list[int]:
    """The harmonic orders ``orders`` (as given: their order and repeats kept) if ``n`` samples
    per revolution resolve each (an integer, 1 <= k < n/2)."""
    hi = math.ceil(n / 2) - 1
    out = []
    for k in orders:
        if isinstance(k, bool) or not (isinstance(k, int | np.integer | float | np.floating)
                                       and 1 <= k <= hi and float(k).is_integer()):
            raise InputError("--orders", "orders", f"integers in [1, {hi}]", got=k)
        out.append(int(k))
    return out


def mechanism(radius_mm: float, rod_mm: float, m_pos_kg: float) -> Mechanism:
    """The crank mechanism from its data in mm and kg (finite, > 0, the rod longer than the
    crank radius), in the SI units the kernels take."""
    for opt, v in (("--radius-mm", radius_mm), ("--rod-mm", rod_mm), ("--m-pos-kg", m_pos_kg)):
        if not (math.isfinite(v) and v > 0):
            raise InputError(opt, opt.lstrip("-"), "> 0", got=v)
    if rod_mm <= radius_mm:
        raise InputError("--rod-mm/--radius-mm", "rod length", f"> crank radius {radius_mm:g} "
                         "mm", got=rod_mm)
    return Mechanism(R=radius_mm / 1000.0, T1=rod_mm / 1000.0, m_pos=m_pos_kg)


def crank_angles(n: int = DEFAULT_SAMPLES) -> NDArray[np.float64]:
    """n uniform crank angles over one revolution, 0 included, 2π excluded."""
    n = check_samples(n)
    return np.arange(n) * (2.0 * np.pi / n)


def cylinder_forces(theta: NDArray[np.float64], cylinders: Sequence[Cylinder], mech: Mechanism,
                    omega: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(Fx, Fy) of every cylinder in the engine frame, shape (N, n), no loop over angles."""
    phase = np.radians([c.phase_deg for c in cylinders])[:, None]
    beta = np.radians([c.tilt_deg for c in cylinders])[:, None]
    X = np.array([c.X for c in cylinders], dtype=float)[:, None]
    X2 = np.array([c.X2 for c in cylinders], dtype=float)[:, None]
    alpha = np.asarray(theta, dtype=float)[None, :] - phase
    fx, fy = shaking_forces(alpha, mech.m_pos, mech.R, mech.T1, omega, X, X2)
    return rotate(fx, fy, beta)


def harmonic_orders(vx: NDArray[np.float64], vy: NDArray[np.float64],
                    orders: Sequence[int] = DEFAULT_ORDERS) -> tuple[Order, ...]:
    """Split a planar vector signal sampled uniformly over one revolution into orders."""
    vx = np.asarray(vx, dtype=float)
    vy = np.asarray(vy, dtype=float)
    n = vx.shape[-1]
    orders = check_orders(orders, n)
    c = np.fft.fft(vx + 1j * vy) / n
    cx = np.fft.rfft(vx) / n
    cy = np.fft.rfft(vy) / n
    out = []
    for k in orders:
        counter, co = abs(c[k]), abs(c[-k])
        out.append(Order(order=int(k), amplitude=float(counter + co),
                         minor=float(abs(counter - co)), x=float(2 * abs(cx[k])),
                         y=float(2 * abs(cy[k])), co_rotating=float(co),
                         counter_rotating=float(counter)))
    return tuple(out)


def engine_forces(cylinders: Sequence[Cylinder], mech: Mechanism, omega: float, *,
                  samples: int = DEFAULT_SAMPLES,
                  orders: Sequence[int] = DEFAULT_ORDERS) -> MultiResult:
    """Resultant shaking force and couple of ``cylinders`` over one revolution."""
    if not cylinders:
        raise InputError("cylinders", "number of cylinders", ">= 1", got=0)
    theta = crank_angles(samples)
    fx, fy = cylinder_forces(theta, cylinders, mech, omega)
    z = np.array([c.z_m for c in cylinders], dtype=float)
    z_ref = float(z.mean())
    dz = (z - z_ref)[:, None]
    Fx, Fy = fx.sum(axis=0), fy.sum(axis=0)
    Mx, My = -(dz * fy).sum(axis=0), (dz * fx).sum(axis=0)
    return MultiResult(theta=theta, Fx=Fx, Fy=Fy, Mx=Mx, My=My, Fx_cyl=fx, Fy_cyl=fy,
                       force_orders=harmonic_orders(Fx, Fy, orders),
                       couple_orders=harmonic_orders(Mx, My, orders),
                       A=mech.amplitude(omega), z_ref_m=z_ref)


# --- layouts -------------------------------------------------------------------------------

def twin_layout(cylinders: Sequence[Cylinder], delta_deg: float, *, shared_pin: bool,
                offset_mm: float) -> dict:
    """The twin's layout as the summary states it: δ, the ε the cylinders were built with
    (read off them, normalised to (−180°, 180°]), the pin arrangement, the offset and the
    resultant crank counterweight (% of one cylinder's m_pos R). ``delta_deg``,
    ``shared_pin`` and ``offset_mm`` must be the ones ``twin`` built ``cylinders`` with."""
    return {"delta_deg": delta_deg, "epsilon_deg": _wrap180(cylinders[1].phase_deg - delta_deg),
            "shared_pin": bool(shared_pin), "offset_mm": offset_mm,
            "resultant_counterweight_pct": 100.0 * resultant_counterweight(cylinders)}


def inline_layout(pins_deg: Sequence[float], res: MultiResult) -> dict:
    """The inline engine's layout as the summary states it: the pins and the couple's axial
    reference (mm)."""
    return {"pins_deg": list(pins_deg), "z_ref_mm": 1000.0 * res.z_ref_m}


def summary(command: str, engine: str, rpm: float, mech: Mechanism, omega: float,
            cylinders: Sequence[Cylinder], res: MultiResult, layout: dict) -> dict:
    """What ``shaftfe balance twin | inline`` reports (its ``--json``, but the plot's path,
    which the command adds), in the report's units (rpm, rad/s, mm, kg, N, N·m, deg, %);
    ``omega`` is the engine's ω at ``rpm`` (``util.units.omega``)."""
    return {
        "command": f"balance {command}",
        "engine": engine, "rpm": rpm, "omega_rad_s": omega,
        "R_mm": 1000.0 * mech.R, "T1_mm": 1000.0 * mech.T1, "m_pos_kg": mech.m_pos,
        "A_N": res.A, "samples": int(res.theta.size),
        **layout,
        "cylinders": [{"phase_deg": c.phase_deg, "tilt_deg": c.tilt_deg,
                       "z_mm": 1000.0 * c.z_m, "X_pct": 100.0 * c.X} for c in cylinders],
        "max_force_N": res.max_force, "max_force_at_deg": res.max_force_at_deg,
        "max_couple_Nm": res.max_couple, "max_couple_at_deg": res.max_couple_at_deg,
        "force_orders": [o.as_dict() for o in res.force_orders],
        "couple_orders": [o.as_dict() for o in res.couple_orders],
    }


def _wrap180(deg: float) -> float:
    """Angle in (−180, 180]."""
    w = math.fmod(deg, 360.0)
    if w > 180.0:
        w -= 360.0
    elif w <= -180.0:
        w += 360.0
    return w


def default_epsilon(delta_deg: float) -> float:
    """Crank-pin offset ε that cancels the 1st order of a twin with α02 = α01 − δ − ε.

    ``ε = 180° − 2δ`` (normalised to (−180°, 180°]); equals the seed's printed
    ``2δ − 180°`` modulo 360° for δ = 0°, 90°, 180° (see the module docstring).
    """
    return _wrap180(180.0 - 2.0 * delta_deg)


def resultant_counterweight(cylinders: Sequence[Cylinder]) -> float:
    """|Σ X_i p_i| at θ = 0: the crank's resultant counterweight as a fraction of one m_pos R."""
    ang = np.radians([c.phase_deg + c.tilt_deg for c in cylinders])  # pin angle = −(φ + β)
    X = np.array([c.X for c in cylinders], dtype=float)
    return float(abs(np.sum(X * np.exp(-1j * ang))))


def twin(delta_deg: float, epsilon_deg: float | None = None, *, shared_pin: bool = False,
         X: Sequence[float] | float | None = None, offset_m: float = 0.0) -> tuple[Cylinder, ...]:
    """Two cylinders at δ with pin offset ε (seed ch. 7); X as fraction(s) of m_pos R.

    ``X`` None → 50 % opposite each pin (resultant = sin δ, the seed's X) or, with
    ``shared_pin``, one 100 % mass at the shared pin and none for cylinder 2. A single number
    applies to every compensation mass present; a pair gives (X_1, X_2) (not with a shared
    pin, which has one mass only). ``offset_m``: axial distance between the two cylinders
    (0 = the seed's planar model).
    """
    if not (math.isfinite(delta_deg) and 0.0 <= delta_deg <= 180.0):
        raise InputError("--delta", "delta", "0 <= delta <= 180 deg", got=delta_deg)
    if shared_pin:
        if epsilon_deg is not None and _wrap180(epsilon_deg) != 0.0:
            raise InputError("--epsilon", "epsilon", "0 (or omitted) with --shared-pin",
                             got=epsilon_deg)
        eps = 0.0
    elif epsilon_deg is None:
        eps = default_epsilon(delta_deg)
    else:
        if not math.isfinite(epsilon_deg) or abs(epsilon_deg) > 360.0:
            raise InputError("--epsilon", "epsilon", "-360 <= epsilon <= 360 deg",
                             got=epsilon_deg)
        eps = float(epsilon_deg)
    if not (math.isfinite(offset_m) and offset_m >= 0.0):
        raise InputError("--offset-mm", "offset", ">= 0 mm", got=1000.0 * offset_m)

    if X is None:
        xs = (1.0, 0.0) if shared_pin else (0.5, 0.5)
    else:
        vals = [float(X)] if np.isscalar(X) else [float(v) for v in X]  # type: ignore[arg-type]
        if shared_pin and len(vals) != 1:
            raise InputError("--x", "x", "one value with --shared-pin (one compensation mass)",
                             got=",".join(f"{100 * v:g}" for v in vals))
        if len(vals) not in (1, 2):
            raise InputError("--x", "x", "one value or two (cylinder 1, cylinder 2)",
                             got=",".join(f"{100 * v:g}" for v in vals))
        _check_x(vals)
        xs = (vals[0], 0.0) if shared_pin else (vals[0], vals[-1])
    return (
        Cylinder(phase_deg=0.0, tilt_deg=delta_deg / 2.0, z_m=-offset_m / 2.0 + 0.0, X=xs[0]),
        Cylinder(phase_deg=delta_deg + eps, tilt_deg=0.0 - delta_deg / 2.0, z_m=offset_m / 2.0,
                 X=xs[1]),
    )


def inline(pins_deg: Sequence[float], spacing_m: Sequence[float] | float,
           X: Sequence[float] | float | None = None) -> tuple[Cylinder, ...]:
    """Upright inline engine: TDC phases (crank-pin angles) and axial spacing(s).

    ``spacing_m``: one value (equal spacing) or N − 1 gaps between neighbouring cylinders.
    ``X``: None (no counterweights), one fraction for all, or one per cylinder.
    """
    pins = [float(p) for p in pins_deg]
    n = len(pins)
    if n < 1 or not all(math.isfinite(p) and -360.0 <= p <= 360.0 for p in pins):
        raise InputError("--pins", "pins", "one or more angles in [-360, 360] deg",
                         got=",".join(f"{p:g}" for p in pins))
    gaps = [float(spacing_m)] * (n - 1) if np.isscalar(spacing_m) else \
        [float(s) for s in spacing_m]  # type: ignore[union-attr]
    if len(gaps) != max(n - 1, 0) and not (n == 1 and len(gaps) <= 1):
        raise InputError("--spacing-mm", "spacing", f"1 value or {n - 1} values (N - 1 gaps "
                         f"for {n} cylinders)", got=len(gaps), reason="has the wrong count")
    given = [float(spacing_m)] if np.isscalar(spacing_m) else gaps
    if not all(math.isfinite(g) and g >= 0.0 for g in given):      # every gap given
        raise InputError("--spacing-mm", "spacing", "gaps >= 0 mm",
                         got=",".join(f"{1000.0 * g:g}" for g in given))
    gaps = gaps[: max(n - 1, 0)]
    z = np.concatenate([[0.0], np.cumsum(gaps)]) if gaps else np.zeros(1)
    if X is None:
        xs = [0.0] * n
    else:
        xs = [float(X)] * n if np.isscalar(X) else [float(v) for v in X]  # type: ignore[union-attr]
        if len(xs) != n:
            raise InputError("--x", "x", f"1 value or {n} values (one per cylinder)",
                             got=len(xs), reason="has the wrong count")
        _check_x(xs)
    return tuple(Cylinder(phase_deg=p, tilt_deg=0.0, z_m=float(zi), X=x)
                 for p, zi, x in zip(pins, z, xs, strict=True))


def _check_x(vals: Sequence[float]) -> None:
    for v in vals:
        if not (math.isfinite(v) and -2.0 <= v <= 2.0):
            raise InputError("--x", "x", "-200 <= X <= 200 %", got=round(100 * v, 6))
