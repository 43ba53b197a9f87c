"""Mode-2 balance sweep: time against error vs the seed 000 §5.4 table.

Grid: X = 31 … 40 % (10) × X2 = 0 … 100 % (101) × N angles, parameters A (SPEC.md §1).
Error: largest |min max|F| − seed| over the 10 rows, and whether the X2 of each minimum matches.
"""

from __future__ import annotations

import numpy as np

from benchmarks._timing import best_of
from shaftfe.balance.engines import engine_from_dict
from shaftfe.balance.sweep import sweep

SEED_MAXF = np.array([2219.6, 2163.2, 2113.9, 2075.4, 2038.1, 1994.3, 1937.9, 1904.8, 1873.6,
                      1825.3])
SEED_MAXF_X2 = np.array([57, 57, 57, 57, 57, 56, 56, 56, 56, 55])
SEED_RMS = np.array([1548.0, 1509.5, 1472.1, 1435.9, 1401.1, 1367.7, 1335.8, 1305.6, 1277.1,
                     1250.6])


def _engine():
    return engine_from_dict({
        "crank_radius_mm": 30.2, "rod_length_mm": 110.2, "piston_group_mass_kg": 0.358,
        "bigend_bearing_mass_kg": 0.042, "rod_rot_mass_kg": 0.148953,
        "rod_pos_mass_kg": 0.114447, "tilt_deg": 0.0, "rpm": 6000.0}, "parameters A")



def main() -> None:
    e = _engine()
    X = np.arange(31, 41) / 100
    X2 = np.arange(0, 101) / 100
    print(f"{'sampling':>15} {'angles':>7} {'time [ms]':>10} {'max|F| err [N]':>15} "
          f"{'X2 match':>9} {'RMS err [N]':>12}")
    for sampling, n in (("seed_inclusive", 360), ("period", 360), ("period", 3600),
                        ("period", 36000)):
        t, r = best_of(lambda s=sampling, k=n: sweep(e, X, X2, sampling=s, n=k))
        m = r.minima()
        err = np.max(np.abs(m["max_f"][0] - SEED_MAXF))
        match = int(np.sum(np.round(100 * m["max_f"][1]) == SEED_MAXF_X2))
        rms_err = np.max(np.abs(m["rms_f"][0] - SEED_RMS))
        print(f"{sampling:>15} {r.n_angles:>7} {1000 * t:>10.1f} {err:>15.3f} "
              f"{match:>6}/10 {rms_err:>12.3f}")
    print("(RMS err vs the seed is ~4 N for 'period': the seed's inclusive grid counts TDC twice;"
          " the period RMS is the exact one)")


if __name__ == "__main__":
    main()
