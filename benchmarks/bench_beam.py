"""Beam model: time per solve against error versus the closed form.

Uniform Ø20 × 200 mm steel shaft, simply supported, central load P: mid-span deflection
P L³/(48 E I) + P L/(4 κ G A) (Timoshenko). Timed: build_model + solve, best of several runs,
for several element lengths; plus the real variant x2_57 if its file and loader exist.
"""

from __future__ import annotations

import math
from pathlib import Path

from benchmarks._timing import best_time


def main() -> None:
    from shaftfe.beam.model import build_model
    from shaftfe.beam.solve import solve
    from shaftfe.model.loads import Load
    from shaftfe.model.variant import Bearing, Material, Segment, Variant

    E, nu, L, d, P = 210_000.0, 0.3, 200.0, 20.0, 1000.0
    G = E / (2 * (1 + nu))
    kappa = 6 * (1 + nu) / (7 + 6 * nu)
    A, I = math.pi * d**2 / 4, math.pi * d**4 / 64  # noqa: E741
    ref = P * L**3 / (48 * E * I) + P * L / (4 * kappa * G * A)
    K0 = ((0.0, 0.0), (0.0, 0.0))
    v = Variant("uniform", "benchmark", (Segment("s", 0.0, L, d),),
                (Bearing("A", "-", 0.0, 0.0, 1e4, 1e4, K0, axial=True),
                 Bearing("B", "-", L, 0.0, 1e4, 1e4, K0)), (),
                Material("steel", E, nu, 7.85e-9, 540.0, 800.0), 0.0,
                loads=(Load("P", "force", L / 2, (L / 2, L / 2), P),))
    print(f"{'case':<28}{'nodes':>7}{'time ms':>10}{'rel. error':>12}")
    for h in (100.0, 10.0, 2.0, 0.5, 0.1):
        def run(h=h):
            m = build_model(v, rigid_supports=True, max_element_mm=h)
            return m, solve(m, 0.0)[0]
        m, r = run()
        i = min(range(m.n_nodes), key=lambda k: abs(m.x[k] - L / 2))
        err = abs(r.uy[i] / ref - 1)
        t = best_time(run, 5 if h < 0.5 else 20)
        print(f"{'uniform SS, h = ' + format(h, 'g') + ' mm':<28}{m.n_nodes:>7}{t * 1e3:>10.3f}"
              f"{err:>12.2e}")

    # a balancer-like stepped shaft (3 steps, coupled springs, 3 attachments), 2 speeds
    from shaftfe.model.variant import Attachment
    Kc = ((35_030.0, 8756.0), (8756.0, 35_030.0))
    bal = Variant("balancer_like", "benchmark",
                  (Segment("a", 0.0, 25.0, 17.0, 1.0), Segment("b", 25.0, 50.0, 22.0, 1.0),
                   Segment("c", 75.0, 35.0, 17.0)),
                  (Bearing("g", "-", 30.0, 10.0, 14_400.0, 9000.0, Kc, axial=True),
                   Bearing("f", "-", 70.0, 10.0, 14_400.0, 9000.0, Kc)),
                  (Attachment("gear", 5.0, 20.0, 0.152, 1.36, 12.0),
                   Attachment("cw1", 5.0, 20.0, 0.125, 22.59, 12.0),
                   Attachment("cw2", 80.0, 105.0, 0.24, 20.23, 92.0, angle_deg=180.0)),
                  Material("steel", E, nu, 7.85e-9, 540.0, 800.0), 0.0,
                  clearance_station_x_mm=50.0)
    for h in (5.0, 1.0):
        def run1(h=h):
            m = build_model(bal, max_element_mm=h)
            return m, solve(m, [10_000.0, 7000.0])
        m, _ = run1()
        t = best_time(run1)
        print(f"{'balancer-like, h = ' + format(h, 'g') + ' mm':<28}{m.n_nodes:>7}"
              f"{t * 1e3:>10.3f}{'-':>12}")

    root = Path(__file__).resolve().parents[1]
    if (root / "geometry" / "x2_57.toml").exists():
        try:
            from shaftfe.model.loader import load_variant
            var = load_variant("x2_57")
        except Exception as exc:   # the loader may not exist yet
            print(f"x2_57: not run ({type(exc).__name__}: {exc})")
            return
        for rigid in (True, False):
            def run2(rigid=rigid):
                m = build_model(var, rigid_supports=rigid)
                return m, solve(m, [10_000.0, 7000.0])
            m, _ = run2()
            t = best_time(run2)
            label = f"x2_57 {'rigid' if rigid else 'springs'}, 2 rpm"
            print(f"{label:<28}{m.n_nodes:>7}{t * 1e3:>10.3f}{'-':>12}")
    else:
        print("x2_57: geometry/x2_57.toml not present, not run")


if __name__ == "__main__":
    main()
