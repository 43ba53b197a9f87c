"""Exact slider-crank kinematics and shaking-force kernels (pure NumPy, SI units inside).

Seed 000 §5.1: crank radius R (half stroke), rod length T1, p = T1/R, crank angle α = ωt from
TDC, z = p² − sin²α:

    y_pos = R (cos α + sqrt(z))
    a_pos = −R ω² [cos α (1 + cos α / sqrt z) + sin²α (cos²α − z) / z^(3/2)]
    F_sp  = −m_pos a_pos                        (inertia force along the cylinder axis)

Balance ratios (SPEC.md §1), cylinder frame (y along the cylinder axis, x across), A = m_pos R ω²:

    Fx = (X2 − X) A sin α,    Fy = F_sp − (X + X2) A cos α

X is the fraction of the 1st-order reciprocating force balanced by the crank, X2 by a 1:1
counter-rotating balancer shaft; the rotating mass is assumed fully balanced by the crank.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from shaftfe.errors import InputError
from shaftfe.util.units import omega


def rad_per_s(rpm: ArrayLike) -> NDArray[np.float64]:
    """Angular speed in rad/s from rpm."""
    return np.asarray(omega(rpm), dtype=float)


def piston_position(alpha: ArrayLike, R: float, T1: float) -> NDArray[np.float64]:
    """Piston-pin distance from the crank axis [same unit as R], α in rad from TDC."""
    a = np.asarray(alpha, dtype=float)
    p = T1 / R
    return R * (np.cos(a) + np.sqrt(p * p - np.sin(a) ** 2))


def piston_acceleration(alpha: ArrayLike, R: float, T1: float, omega: float) -> NDArray[np.float64]:
    """Exact piston acceleration along the cylinder axis (positive away from the crank)."""
    a = np.asarray(alpha, dtype=float)
    p = T1 / R
    s, c = np.sin(a), np.cos(a)
    z = p * p - s * s
    sz = np.sqrt(z)
    return -R * omega**2 * (c * (1.0 + c / sz) + s * s * (c * c - z) / (z * sz))


def reciprocating_force(alpha: ArrayLike, m_pos: float, R: float, T1: float,
                        omega: float) -> NDArray[np.float64]:
    """Inertia force of the reciprocating mass along the cylinder axis, F_sp = −m_pos a_pos."""
    return -m_pos * piston_acceleration(alpha, R, T1, omega)


def shaking_forces(alpha: ArrayLike, m_pos: float, R: float, T1: float, omega: float,
                   X: ArrayLike, X2: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(Fx, Fy) in the cylinder frame for balance ratios X, X2 given as fractions (0.3 = 30 %).

    Broadcasts: pass α with shape (n,) and X, X2 with shapes (..., 1) to get (..., n) arrays,
    which is how the sweeps evaluate every (X, X2) pair without a Python loop.
    """
    a = np.asarray(alpha, dtype=float)
    X = np.asarray(X, dtype=float)
    X2 = np.asarray(X2, dtype=float)
    A = m_pos * R * omega**2
    Fx = (X2 - X) * A * np.sin(a)
    Fy = reciprocating_force(a, m_pos, R, T1, omega) - (X + X2) * A * np.cos(a)
    return Fx, Fy


def rotate(Fx: ArrayLike, Fy: ArrayLike,
           beta: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Rotate a planar vector from the cylinder frame into the engine frame by the tilt β [rad].

    Counter-clockwise rotation (positive β turns the cylinder axis +y towards −x):
    (x, y) → (x cos β − y sin β, x sin β + y cos β).
    """
    c, s = np.cos(beta), np.sin(beta)
    Fx = np.asarray(Fx, dtype=float)
    Fy = np.asarray(Fy, dtype=float)
    return Fx * c - Fy * s, Fx * s + Fy * c


def split_rod(m_rod: float, eye_distance: float, centroid_from_big_eye: float
              ) -> tuple[float, float]:
    """Two-point rod split (seed 003 eq. 7-8): (rotating share, reciprocating share)."""
    if eye_distance <= 0:
        raise InputError("split_rod", "eye_distance", "> 0", got=eye_distance)
    if not 0 <= centroid_from_big_eye <= eye_distance:
        raise InputError("split_rod", "centroid_from_big_eye", f"in [0, {eye_distance:g}]",
                         got=centroid_from_big_eye)
    m_rot = m_rod * (eye_distance - centroid_from_big_eye) / eye_distance
    return m_rot, m_rod - m_rot
