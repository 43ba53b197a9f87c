"""Parallel-key check by the seed's method (seed 000 §8.2.2, ČSN 02 2562 keys):
pressure p = 2 (M/d) / (c_ef n_p l h / 2) ≤ σ_d, so the length needed is
l = 2 (M/d) / (c_ef n_p p h / 2); σ_d = 0.6 σ_pt / 1.5."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class KeyCheck:
    name: str
    torque_Nmm: float
    d_mm: float
    sigma_d_MPa: float             # allowable, 0.6 σ_pt / 1.5
    length_needed_mm: float        # at σ_d
    length_needed_seed_mm: float   # at the seed formula's p_d (its 0.126 mm)
    pressure_MPa: float            # with the chosen key length
    safety: float                  # σ_d / p


def length_needed(M_Nmm: float, d_mm: float, p_MPa: float, h_mm: float, c_ef: float = 1.0,
                  n_p: float = 1.0) -> float:
    return 2.0 * (M_Nmm / d_mm) / (c_ef * n_p * p_MPa * h_mm / 2.0)


def pressure(M_Nmm: float, d_mm: float, l_mm: float, h_mm: float, c_ef: float = 1.0,
             n_p: float = 1.0) -> float:
    return 2.0 * (M_Nmm / d_mm) / (c_ef * n_p * l_mm * h_mm / 2.0)


def check(name: str, M_Nmm: float, d_mm: float, keys: dict) -> KeyCheck:
    sd = 0.6 * keys["sigma_pt_MPa"] / 1.5
    h, c, n = keys["height_mm"], keys["c_ef"], keys["n_p"]
    p = pressure(M_Nmm, d_mm, keys["length_mm"], h, c, n)
    return KeyCheck(name, M_Nmm, d_mm, sd, length_needed(M_Nmm, d_mm, sd, h, c, n),
                    length_needed(M_Nmm, d_mm, keys["p_formula_MPa"], h, c, n), p,
                    sd / p if p > 0 else float("inf"))
