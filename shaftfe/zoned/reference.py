"""The zoned solution as the fatigue stage's input: a surface ``StaticReference`` made of the
global model's revolved surface (``axisymmetric.reference``) outside the zones and each 3D
submodel's free surface inside its zone, with the same split the zoned peaks use
(``zoned.solve``): a region whose peak comes from a submodel takes its points from the
submodel, every other region (and the surface within ``CUT_CLEAR_D`` local diameters of a cut)
from the global model.

Points: the global model's outline nodes × 360 angles (1°) and the submodels' free-surface
nodes (the cut faces left out); stresses in Cartesian xx yy zz xy yz xz at the reference speed
(surface-recovered in both); the singular-point rule of each model (``solve.excluded_nodes``
and the seats' θ-edge bands; ``fe.recovery.excluded_nodes`` with the cut faces as patches).
Cells: the revolved outline's triangles and the submodels' facet corners (no volume cells: a
surface field, as ``--model axisymmetric`` gives)."""

from __future__ import annotations

import time

import numpy as np

from shaftfe.axisymmetric.reference import static_reference as axi_reference
from shaftfe.fe import assembly as fem
from shaftfe.fe import recovery
from shaftfe.static.cache import StaticReference
from shaftfe.zoned.solve import CUT_CLEAR_D
from shaftfe.zoned.zones import diameter_at


def _interior(x: np.ndarray, zone, plan) -> np.ndarray:
    """Points of the zone's extent at least ``CUT_CLEAR_D`` local diameters from its cuts."""
    lo = zone.x0 + (CUT_CLEAR_D * diameter_at(plan, zone.x0) if zone.cut_left else -1e-9)
    hi = zone.x1 - (CUT_CLEAR_D * diameter_at(plan, zone.x1) if zone.cut_right else -1e-9)
    return (x >= lo) & (x <= hi)


def zoned_reference(res, seconds: float | None = None) -> StaticReference:
    """The ``StaticReference`` of a ``ZonedResult`` at its first speed (module docstring)."""
    t0 = time.perf_counter()
    plan = res.plan
    g = axi_reference(res.global_result)
    scale = res.cases[0].scale
    from_zone = {p.region for p in res.cases[0].peaks if p.model != "axisymmetric"}
    # the global part: outside every zone's interior, plus the regions it keeps
    keep_g = np.ones(g.n_nodes, dtype=bool)
    for sub, _ in res.fields:
        keep_g &= ~_interior(g.xyz[0], sub.zone, plan)
    for name, ids in g.regions.items():
        if name not in from_zone:
            keep_g[np.asarray(ids, dtype=np.int64)] = True
    parts = [(g.xyz, g.stress_ref, g.regions, g.excluded, g.face_cells, g.face_group,
              g.face_groups, keep_g)]
    for sub, sf in res.fields:
        m = sub.shaft_mesh.mesh
        cut = [np.asarray(m.boundaries[c]) for c in sub.cut_groups]
        surf = fem.face_nodes(m, np.setdiff1d(m.boundary_facets(),
                                              np.concatenate(cut) if cut else []))
        keep = np.zeros(m.doflocs.shape[1], dtype=bool)
        keep[surf] = True
        keep &= _interior(m.doflocs[0], sub.zone, plan)
        for name, ids in sub.regions.items():
            if name not in from_zone:
                keep[ids] = False
        names = tuple(sorted(k for k in m.boundaries if k not in sub.cut_groups))
        fac = np.concatenate([np.asarray(m.boundaries[k]) for k in names])
        gid = np.concatenate([np.full(np.asarray(m.boundaries[k]).size, i, np.int32)
                              for i, k in enumerate(names)])
        tri = m.facets[:, fac].T.astype(np.int64)
        parts.append((m.doflocs, sf.stress * scale, sub.regions, sub.excluded, tri, gid, names,
                      keep))
    return _merge(res, g, parts, seconds, t0)


def _merge(res, g, parts, seconds, t0) -> StaticReference:
    xyz, stress, excl, tris, groups = [], [], [], [], []
    regions: dict[str, list] = {}
    names: list[str] = []
    offset = 0
    for P, S, reg, ex, tri, gid, gnames, keep in parts:
        idx = -np.ones(keep.size, dtype=np.int64)
        idx[keep] = offset + np.arange(int(keep.sum()))
        xyz.append(P[:, keep])
        stress.append(S[:, keep])
        e = idx[np.asarray(ex, dtype=np.int64)]
        excl.append(e[e >= 0])
        for name, ids in reg.items():
            j = idx[np.asarray(ids, dtype=np.int64)]
            j = j[j >= 0]
            if j.size:
                regions.setdefault(name, []).append(j)
        t = idx[tri]
        ok = (t >= 0).all(axis=1)
        tris.append(t[ok])
        for n in gnames:
            if n not in names:
                names.append(n)
        pos = np.array([names.index(n) for n in gnames], dtype=np.int32)
        groups.append(pos[np.asarray(gid, dtype=np.int64)[ok]] if len(gnames)
                      else np.zeros(0, np.int32))
        offset += int(keep.sum())
    stress_all = np.concatenate(stress, axis=1)
    from dataclasses import asdict
    o = res.options
    return StaticReference(
        variant=res.variant, variant_hash=res.variant_hash,
        options={**asdict(o), "model": "zoned", "level": getattr(o.level, "name", o.level),
                 "zones": [z.name for z in res.zones]},
        ref_rpm=float(g.ref_rpm), mesh_key="", key="", stress_ref=stress_all,
        von_mises_ref=recovery.von_mises(stress_all), xyz=np.concatenate(xyz, axis=1),
        excluded=np.unique(np.concatenate(excl)),
        regions={k: np.concatenate(v) for k, v in sorted(regions.items())},
        cells=np.zeros((0, 4), dtype=np.int64), face_cells=np.concatenate(tris),
        face_group=np.concatenate(groups), face_groups=tuple(names),
        n_elements=int(g.n_elements) + sum(s.shaft_mesh.n_elements for s, _ in res.fields),
        solve_seconds=float(res.run.get("total_seconds", 0.0)), from_cache=False,
        seconds=float(seconds or 0.0) + time.perf_counter() - t0,
        notes=(*res.notes, f"zoned model: fatigue on the global model's revolved surface and "
               f"{len(res.fields)} submodels' free surfaces, surface-recovered stresses"),
        relative_residual=g.relative_residual)
