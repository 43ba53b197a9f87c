"""`shaftfe demo`: the main job on the bundled defaults (what `make demo` runs).

Runs, on the bundled VM 450 data and the balancer-shaft variant x2_57:
1. the balancing study at the engine's speed (seed 000 §5.4, §8.2.2): forces for the chosen X,
   X2 and the mode-2 sweep over X2 for crank C (X = 31.1 %);
2. the beam check of x2_57 at 10 000 rpm (rigid supports, as Inventor) and 7000 rpm (springs):
   reactions, deflections, nominal and notch stresses, bearing lives (seed 000 §8.2.2);
3. the 3D static solution at 10 000 and 7000 rpm on the bearing springs (seed load case), one
   solve, stored in the static cache;
4. the fatigue life on loadspectra/rpm.dat, reusing that static solution (seed 000 §8.3);
5. the Campbell diagram 0-8000 rpm of the beam model (seed 000 §8.4).
Stages 3-5 are the `shaftfe static`, `fatigue` and `campbell` commands with their outputs in
``--out``/static, /fatigue, /campbell. It grows into the assessment report (issue 7).
"""

from __future__ import annotations

import time


def register(sub) -> None:
    p = sub.add_parser("demo", help="run the main job on the bundled defaults")
    p.add_argument("--out", default="reports/demo", help="output folder (default reports/demo)")
    p.add_argument("--level", default="default", choices=("coarse", "default", "fine"),
                   help="mesh level of the 3D stages (default: default)")
    p.set_defaults(handler=run)


def run(args) -> int:
    import json
    from pathlib import Path

    from shaftfe.commands._common import print_table, write_atomic

    out = Path(args.out)
    summary: dict[str, object] = {}
    t0 = time.perf_counter()
    summary["balancing"] = _balancing(out, print_table)
    summary["beam"] = _beam(out, print_table)
    summary["fe"] = _fe_stages(out, args.level)
    write_atomic(out / "summary.json", json.dumps(summary, indent=2) + "\n")
    print(f"\nshaftfe demo: done in {time.perf_counter() - t0:.2f} s; results in {out}/")
    return 0


def _balancing(out, print_table) -> dict:
    import numpy as np

    from shaftfe.balance import plots, single, sweep
    from shaftfe.balance.engines import load_engine

    engine = load_engine("vm450")
    X_C = 0.311            # crank C (seed 000 §8.2.1)
    res = single.forces(engine, X=X_C, X2=0.57, rpm=engine.rpm)
    m = res.metrics
    print(f"Balancing, {engine.name}: crank C X = 31.1 %, balancer X2 = 57 %, "
          f"{engine.rpm:.0f} rpm, tilt {engine.tilt_deg:g} deg")
    print_table(["metric", "value [N]", "crank angle [deg]"], [
        ["max|Fx|", m.max_abs_fx, m.max_abs_fx_deg],
        ["max|Fy|", m.max_abs_fy, m.max_abs_fy_deg],
        ["RMS|F|", m.rms_f, "-"],
        ["max|F|", m.max_f, m.max_f_deg],
    ])
    sw = sweep.sweep(engine, [X_C], np.arange(0.0, 1.0001, 0.01), rpm=engine.rpm, tilt_deg=0.0)
    mins = sw.minima()
    best = {k: (float(v[0][0]), 100.0 * float(v[1][0])) for k, v in mins.items()}
    print("Sweep over X2 (cylinder frame, seed §8.2.2 fig. 58): minimum of each metric at X2 [%]")
    print_table(["metric", "minimum [N]", "at X2 [%]"],
                [[k, v[0], v[1]] for k, v in best.items()])
    plots.plot_forces(res, out / "balance_forces.png")
    plots.plot_sweep(sw, out / "balance_sweep.png")
    return {"X": X_C, "X2": 0.57, "rpm": engine.rpm, "metrics": m.as_dict(),
            "sweep_minima": {k: {"value_N": v[0], "at_X2_percent": v[1]}
                             for k, v in best.items()}}


def _beam(out, print_table) -> dict:
    """Beam check of x2_57 against the Inventor shaft-module figures (seed 000 §8.2.2)."""
    from shaftfe import beam
    from shaftfe.commands._common import write_atomic
    from shaftfe.commands.beam import plot_results
    from shaftfe.variant import load_variant

    variant = load_variant("x2_57").with_seed_load_case()
    rigid = beam.solve(beam.build_model(variant, rigid_supports=True), [10000.0, 7000.0])
    eb = beam.solve(beam.build_model(variant, rigid_supports=True, shear_deformation=False),
                    [10000.0])[0]
    springs = beam.solve(beam.build_model(variant), [7000.0])[0]
    r10, r7 = rigid
    gear, free = (b.name for b in variant.bearings)
    reac10 = {b.name: b.F_N for b in r10.bearings}
    reac7 = {b.name: b.F_N for b in r7.bearings}
    life7 = {b.name: b.L10h for b in springs.bearings}
    rows = [
        ["reaction gear side, 10 000 rpm [N]", 2689.0, reac10[gear]],
        ["reaction free side, 10 000 rpm [N]", 5921.0, reac10[free]],
        ["reaction gear side, 7000 rpm [N]", 1308.0, reac7[gear]],
        ["reaction free side, 7000 rpm [N]", 2931.0, reac7[free]],
        ["deflection under the gear [mm] (Timoshenko)", 0.063, r10.stations["gear"].u_mm],
        ["deflection under the gear [mm] (Euler-Bernoulli)", 0.063, eb.stations["gear"].u_mm],
        ["max nominal von Mises [MPa]", 263.157, r10.max_sigma_vm_MPa],
        ["L10h free-side bearing, 7000 rpm [h]", 283.4, life7[free]],
    ]
    print("\nBeam check, x2_57, seed load case (rigid supports as Inventor; L10h on springs)")
    print_table(["quantity", "seed", "shaftfe"], rows)
    write_atomic(out / "beam_x2_57.png", plot_results(rigid))
    return {"rows": [{"quantity": q, "seed": a, "shaftfe": b} for q, a, b in rows]}


def _fe_stages(out, level: str) -> dict:
    """3D static, fatigue and Campbell through their commands; returns their exit codes."""
    from pathlib import Path

    from shaftfe.cli import main
    from shaftfe.errors import SolverError

    spectrum = Path(__file__).resolve().parents[2] / "loadspectra" / "rpm.dat"
    stages = {
        "static": ["static", "--variant", "x2_57", "--rpm", "10000,7000", "--seed-load-case",
                   "--level", level, "--out", str(out / "static")],
        "fatigue": ["fatigue", str(spectrum), "--variant", "x2_57", "--level", level,
                    "--out", str(out / "fatigue")],
        "campbell": ["campbell", "0:8000", "--variant", "x2_57", "--out", str(out / "campbell")],
    }
    codes = {}
    for name, argv in stages.items():
        print(f"\n== shaftfe {' '.join(argv)}")
        codes[name] = main(argv)
        if codes[name] != 0:
            raise SolverError(f"demo stage '{name}' failed (exit code {codes[name]})")
    return codes
