"""Bearing life over the duty cycle (ISO 281:2007): each bearing's radial load follows rpm²
(the loads are centrifugal), so the beam's reaction at one speed gives it at every sample of
the rpm history; the equivalent load and speed, L10h and the modified life L_nm = a1 a_ISO L10
over the spectrum (``model.bearing_life``), in hours and km; and the seed's single points."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shaftfe.beam.solve import beam_at_ref
from shaftfe.model import bearing_life as bl
from shaftfe.util.units import REF_RPM, rpm2_scale

KAPPA_DEFAULT = 1.0    # engine oil ≈ 10 mm²/s at ≈ 100 °C over ν1 ≈ 10 mm²/s (ISO 281, 7000 rpm,
#                        d_m 28.5 mm): κ ≈ 1
EC_DEFAULT = 0.3       # ISO 281 Table 13, d_m < 100 mm: slight (0.5-0.3) to typical (0.3-0.1)
#                        contamination: the boundary, for a splash-lubricated engine bearing
CU_OVER_C0 = 1.0 / 22.0   # ISO 281 Annex B: ball bearings, D_pw ≤ 100 mm: C_u = C0 / 22

# the seed's single points (seed 000 §8.2.2)
SEED_POINTS = ({"bearing": "ZKL 3303", "C_N": 23649.0, "P_N": 2931.0, "rpm": 7000.0,
                "L10h": 1250.7},
               {"bearing": "ZKL 3203", "C_N": None, "P_N": 2931.0, "rpm": 7000.0,
                "L10h": 283.4})


@dataclass(frozen=True)
class BearingDuty:
    name: str
    designation: str
    C_N: float
    C_u_N: float
    P_eq_N: float
    n_eq_rpm: float
    L10h: float
    Lnm_h: float
    Lnm_km: float
    P_max_N: float
    L10h_at_max_rpm: float


def duty(variant, history, kappa: float = KAPPA_DEFAULT, e_c: float = EC_DEFAULT,
         a1: float = 1.0, speed_kmh: float = 70.0, beam=None) -> tuple[BearingDuty, ...]:
    """``beam``: the beam solution at ``util.units.REF_RPM`` if the caller has it."""
    ref_rpm = REF_RPM
    beam = beam if beam is not None else beam_at_ref(variant)
    rpm = np.asarray(history.rpm, dtype=float)
    out = []
    for b, res in zip(variant.bearings, beam.bearings, strict=True):
        P = res.F_N * rpm2_scale(rpm, ref_rpm)
        Peq, neq = bl.duty_cycle(rpm, P, p=b.life_exponent)
        cu = CU_OVER_C0 * b.C0_N
        L10 = bl.l10h(b.C_N, Peq, neq, b.life_exponent)
        Lnm = bl.modified_life_spectrum(b.C_N, cu, rpm, P, kappa, e_c, a1, b.life_exponent)
        imax = int(np.argmax(rpm))
        out.append(BearingDuty(b.name, b.designation, b.C_N, cu, Peq, neq, L10, Lnm,
                               Lnm * speed_kmh if math.isfinite(Lnm) else math.inf,
                               float(P[imax]), bl.l10h(b.C_N, float(P[imax]), float(rpm[imax]),
                                                       b.life_exponent)))
    return tuple(out)
