"""Mesh benchmark: per level, size, quality, cold vs cached time and volume error.

Run: ``python -m benchmarks bench_mesh`` (or ``python benchmarks/bench_mesh.py``).
Meshes the real variant x2_57 when ``load_variant`` can load it, and always a small synthetic
shaft (Ø15/17/22/17, 1 mm fillets, one keyway, a hex socket). The cache goes to a temporary
directory, so "cold" is a real Gmsh build and "cached" a load of the npz just written.
Volume error = meshed P2 volume / exact volume (shaftfe.solid.exact.analytic_volume) − 1.
"""

from __future__ import annotations

import sys
import tempfile
import time


def _synthetic():
    from shaftfe.model.examples import four_step_shaft
    return four_step_shaft(name="synthetic", description="benchmark shaft")


def _variants():
    out = []
    try:
        from shaftfe.model.loader import load_variant
        out.append(load_variant("x2_57"))
    except Exception as exc:       # loader or file not there yet
        print(f"(x2_57 skipped: {exc})")
    out.append(_synthetic())
    return out


def _volume(mesh) -> float:
    from skfem import Basis, ElementTetP2, Functional
    one = Functional(lambda w: 1.0 + 0.0 * w.x[0])
    return float(one.assemble(Basis(mesh, ElementTetP2())))


def main(levels=("coarse", "default", "fine")) -> list[dict]:
    from shaftfe.commands._common import print_table
    from shaftfe.solid.exact import analytic_volume
    from shaftfe.solid.mesh import build_mesh
    rows, records = [], []
    with tempfile.TemporaryDirectory(prefix="shaftfe-bench-") as cache:
        for v in _variants():
            exact = analytic_volume(v)
            for level in levels:
                cold = build_mesh(v, level, cache_dir=cache)
                t = time.perf_counter()
                hot = build_mesh(v, level, cache_dir=cache)
                t_hot = time.perf_counter() - t
                assert hot.from_cache and not cold.from_cache
                err = _volume(cold.mesh) / exact - 1.0
                rec = {"variant": v.name, "level": level, "nodes": cold.n_nodes,
                       "elements": cold.n_elements, "dofs": cold.n_dofs,
                       "min_sicn": cold.min_quality, "cold_s": cold.build_seconds,
                       "cached_s": t_hot, "vol_err": err}
                records.append(rec)
                rows.append([v.name, level, cold.n_nodes, cold.n_elements, cold.n_dofs,
                             f"{cold.min_quality:.3f}", f"{cold.build_seconds:.2f}",
                             f"{t_hot:.3f}", f"{err:+.2e}"])
                sys.stdout.flush()
    print_table(["variant", "level", "nodes", "tets", "dofs", "minSICN", "cold s", "cached s",
                 "vol err"], rows, title="mesh (P2, 1 thread; cold includes the first skfem "
                 "import in the first row)")
    return records


if __name__ == "__main__":
    main()
