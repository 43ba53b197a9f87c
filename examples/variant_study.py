"""A variant study: every balancer variant in geometry/, side by side.

For each variant: the balancer's mass and balance ratio from its parts, the beam model's
bearing loads and peak notch stress at the engine's top speed, the first natural frequency and
the first once-per-revolution critical speed below the top speed (if any) from the Campbell
sweep of the beam rotor. Beam models only, so the whole study takes a
few seconds; swap in ``shaftfe.solve_static`` for the 3D numbers.

    python examples/variant_study.py
"""

from __future__ import annotations

import sys

import shaftfe

TOP_RPM = 10_000.0          # the seed engine's top speed


def row(name: str) -> list:
    v = shaftfe.load_variant(name)
    mp = shaftfe.mass_properties(v)
    beam = shaftfe.analyse_beam(v, TOP_RPM)[0]
    run = shaftfe.analyse_rotor(v, [1000.0 * i for i in range(11)], 6, verify=False)
    crit = [c for c in run.result.criticals if c.order == 1.0]
    return [name, mp.mass_kg, v.balance_target.X2_percent if v.balance_target else None,
            max(b.F_N for b in beam.bearings), beam.max_peak_MPa,
            float(run.result.freq_hz[0, 0]), crit[0].rpm if crit else None]


def main() -> int:
    head = ["variant", "mass kg", "X2 %", "max bearing N", "peak MPa", "f1 Hz at 0 rpm",
            "1x critical rpm"]
    rows = [row(n) for n in shaftfe.list_variants()]
    print("  ".join(f"{h:>14}" for h in head))
    for r in rows:
        print("  ".join(f"{x:>14}" if isinstance(x, str) else
                        f"{'-':>14}" if x is None else f"{x:14.4g}" for x in r))
    return 0 if rows else 1


if __name__ == "__main__":
    sys.exit(main())
