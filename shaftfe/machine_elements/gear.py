"""The balancer drive's spur pair by the seed's method (Autodesk Inventor's Merritt check,
seed 000 §8.2.2 and Obr. 60): tangential force at the operating pitch circle, radial and
normal force at the working pressure angle, pitch-line speed at the reference circle (as
Inventor prints it), and S = F_all / F_t (Inventor 2016 help: F_all = π c_min b_w m μ)."""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class GearCheck:
    torque_Nmm: float          # the drive torque × the torque factor
    alpha_w_deg: float         # working pressure angle
    d_w_mm: float              # operating pitch diameter (ratio 1:1: = a_w)
    F_t_N: float
    F_r_N: float
    F_n_N: float
    v_m_s: float
    safety: float


def check(M_Nmm: float, rpm: float, g: dict) -> GearCheck:
    m, z = g["module_mm"], g["teeth"]
    a = m * z                                       # reference centre distance, z1 = z2
    a_w = g["centre_distance_mm"]
    alpha = math.radians(g["pressure_angle_deg"])
    alpha_w = math.acos(a / a_w * math.cos(alpha))
    T = g["torque_factor"] * M_Nmm
    d_w = a_w                                       # 2 a_w / (1 + u), u = 1
    Ft = 2.0 * T / d_w
    v = math.pi * m * z * rpm / 60000.0
    return GearCheck(T, math.degrees(alpha_w), d_w, Ft, Ft * math.tan(alpha_w),
                     Ft / math.cos(alpha_w), v, g["merritt_allowable_N"] / Ft)
