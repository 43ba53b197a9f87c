"""Fatigue post-processing of the full default-level static field of x2_57 (issue 5).

Given the static reference solution (``shaftfe.static.solve.load_or_solve``: default mesh level,
seed load case, bearing springs; solved once if the cache is empty — not timed), time (best of
5) ``shaftfe.fatigue.field.evaluate`` on every node with the seed's settings and the rebuilt
rpm.dat: re-referencing the history to the static speed, rainflow counting, von Mises,
Soderberg, Miner damage, life in blocks / h / km, the safety factor at 1e7 blocks, and the
filtered / unfiltered / per-region hot spots. Target ≤ 0.3 s. The ``fatigue.vtu`` write is timed
separately (not part of the target).

Agreement: a plain Python loop over a subset of nodes (its own von Mises, Soderberg, log-log S-N
look-up by bisect, Miner sum, scalar bisection of the safety factor), independent of the NumPy
kernels; the largest relative difference in damage and in safety factor is printed.
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

import numpy as np

from benchmarks._timing import best_of
from shaftfe.fatigue import reference

ROOT = Path(__file__).resolve().parents[1]
SUBSET = 200
TARGET_S = 0.3


def main() -> None:
    from shaftfe.fatigue import count_cycles, load_material
    from shaftfe.fatigue.field import evaluate, write_vtu
    from shaftfe.fatigue.history import read_history
    from shaftfe.model.loader import load_variant
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import load_or_solve

    t = time.perf_counter()
    ref = load_or_solve(load_variant("x2_57"), StaticOptions(level="default",
                                                             seed_load_case=True))
    how = "from cache" if ref.from_cache else "solved"
    print(f"static reference ({how}, {time.perf_counter() - t:.2f} s): {ref.n_nodes} nodes, "
          f"{ref.n_elements} P2 elements, default level, {ref.excluded.size} excluded")
    h = read_history(ROOT / "loadspectra" / "rpm.dat")
    mat = load_material("structural_steel")
    best, ff = best_of(lambda: evaluate(ref, h, mat), repeat=5)
    ok = "OK" if best <= TARGET_S else "OVER TARGET"
    print(f"fatigue field evaluation, {ref.n_nodes} nodes x {ff.result.cycles.n} cycle classes "
          f"({ff.cycles_per_block:g} cycles per block): {best * 1e3:.1f} ms "
          f"(target <= {TARGET_S * 1e3:.0f} ms: {ok})")
    hs = ff.hot_spot
    print(f"hot spot {hs.region} x = {hs.xyz_mm[0]:.2f} mm: SF {hs.safety_factor:.3f} at 1e7, "
          f"life {hs.life_blocks:.4g} blocks = {hs.life_hours:.4g} h = {hs.life_km:.4g} km")

    cyc = count_cycles((h.rpm / ref.ref_rpm) ** 2)
    r = ff.result
    rng = np.random.default_rng(0)
    damaged = np.flatnonzero(r.damage_per_block > 0)
    nodes = np.concatenate([rng.choice(damaged, min(SUBSET // 2, damaged.size), replace=False),
                            rng.choice(ref.n_nodes, SUBSET // 2, replace=False)])
    t = time.perf_counter()
    dd, ds = 0.0, 0.0
    for i in nodes:
        s = reference.von_mises(ref.stress_ref[:, i])
        d = reference.node_damage(s, cyc, mat)
        if d > 0 or r.damage_per_block[i] > 0:
            dd = max(dd, abs(r.damage_per_block[i] - d) / d)
        n = reference.node_safety(s, cyc, mat, 1e7)
        ds = max(ds, abs(r.safety_factor[i] - n) / n)
    t_loop = time.perf_counter() - t
    print(f"per-node Python loop on {nodes.size} nodes ({damaged.size} nodes have damage): "
          f"{t_loop:.2f} s; max relative difference: damage {dd:.1e}, safety factor {ds:.1e}")

    with tempfile.TemporaryDirectory() as d:
        tv, _ = best_of(lambda: write_vtu(ref, ff, Path(d) / "fatigue.vtu"), repeat=3)
    print(f"fatigue.vtu write (not in the target): {tv:.2f} s")


if __name__ == "__main__":
    main()
