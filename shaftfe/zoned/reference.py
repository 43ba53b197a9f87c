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
surface field, as ``--model axisymmetric`` gives). FKM's stress profile below a point comes from
the point's own model (``ZonedProbe``)."""

from __future__ import annotations

import time
from dataclasses import replace
from functools import cached_property

import numpy as np

from shaftfe.axisymmetric.reference import SurfaceProbe, pattern_views
from shaftfe.axisymmetric.reference import static_reference as axi_reference
from shaftfe.axisymmetric.reference import surface_displacement as axi_displacement
from shaftfe.fe import assembly as fem
from shaftfe.fe import recovery
from shaftfe.fe.pointeval import TetProbe
from shaftfe.static.cache import StaticReference, facet_cells
from shaftfe.zoned.solve import CUT_CLEAR_D
from shaftfe.zoned.submodel import pattern_stress
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
    views = pattern_views(res.global_result)        # once, for the global and the zones
    g = axi_reference(res.global_result, views=views)
    # the submodels' fields are at the speed the global model's reference is at (``solve_zoned``
    # solves a zone at the global solution's own speed, rpm_f): no scaling
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
    probes = [g.depth_probe]
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
        parts.append((m.doflocs, sf.stress, sub.regions, sub.excluded, tri, gid, names,
                      keep))
        probes.append(_ZoneField(m, sf.stress))
    ref = _merge(res, g, parts, seconds, t0)
    keeps = [p[-1] for p in parts]
    return replace(ref, depth_probe=ZonedProbe(keeps, probes), patterns=g.patterns,
                   pattern_stress=_pattern_stress(res, g, keeps, views[1]))


def _pattern_stress(res, g, keeps, views) -> dict:
    """{label: stress} of each load pattern on the merged points, where the global reference
    has them (``views``: ``axisymmetric.reference.pattern_views``): the global model's outside
    the zones, each submodel's solved for the pattern alone inside (``submodel.
    pattern_stress``, on its factorised stiffness, one gradient operator per zone)."""
    if not g.pattern_stress:
        return {}
    grads = [recovery.node_gradients(sub.shaft_mesh.mesh) for sub, _ in res.fields]
    out = {}
    for key, info, view in views:
        parts = [g.pattern_stress[info["key"]]]
        parts += [pattern_stress(sub, view, key, grad)
                  for (sub, _), grad in zip(res.fields, grads, strict=True)]
        out[info["key"]] = np.concatenate([S[:, k] for S, k in zip(parts, keeps, strict=True)],
                                          axis=1)
    return out


class _ZoneField:
    """A submodel's volume field as ``fatigue.fkm_field.TetProbe`` reads it (its own points,
    P2 cells, boundary triangles and nodal stress), made only when FKM asks for a profile."""

    def __init__(self, mesh=None, stress: np.ndarray | None = None, field=None):
        self.mesh, self.stress = mesh, stress
        if field is not None:             # read from the surface cache: the arrays as they are
            self.__dict__["field"] = field

    @cached_property
    def field(self):
        from types import SimpleNamespace

        m = self.mesh
        return SimpleNamespace(xyz=m.doflocs, stress_ref=self.stress,
                               cells=fem.element_nodes(m).T.astype(np.int64),
                               face_cells=facet_cells(m)[0])

    @cached_property
    def probe(self):
        return TetProbe(self.field)


class ZonedProbe:
    """FKM's stress profile below a point of the zoned reference (``fatigue.fkm_field.
    DepthProbe``): each point asks the model it came from, the global model's revolved surface
    (``axisymmetric.reference.SurfaceProbe``, exact from the harmonic field) or its submodel's
    3D field (``TetProbe``: the volume below a keyway is the submodel's). ``keeps``: each
    part's mask of the points it gave, in the merged order (``_merge``)."""

    def __init__(self, keeps, probes):
        self.sizes = tuple(int(k.size) for k in keeps)      # each part's own point count
        self.owner = np.concatenate([np.full(int(k.sum()), i) for i, k in enumerate(keeps)])
        self.local = np.concatenate([np.flatnonzero(k) for k in keeps])
        self.probes = probes

    def _of(self, node: int):
        p = self.probes[self.owner[node]]
        return (p.probe if isinstance(p, _ZoneField) else p), int(self.local[node])

    def arrays(self) -> dict[str, np.ndarray]:
        """Everything ``from_arrays`` needs (the surface-reference cache, ``fatigue.
        surface_cache``): the points' origin, the global probe's arrays, each zone's volume
        field (points, P2 cells, boundary triangles, nodal stress)."""
        out = {"owner": self.owner, "local": self.local, "sizes": np.array(self.sizes)}
        out.update({f"g_{k}": v for k, v in self.probes[0].arrays().items()})
        for i, z in enumerate(self.probes[1:], start=1):
            f = z.field
            out.update({f"z{i}_xyz": f.xyz, f"z{i}_cells": f.cells,
                        f"z{i}_face_cells": f.face_cells, f"z{i}_stress": f.stress_ref})
        return out

    @classmethod
    def from_arrays(cls, a: dict) -> ZonedProbe:
        from types import SimpleNamespace

        self = cls.__new__(cls)
        self.owner, self.local = a["owner"], a["local"]
        self.sizes = tuple(int(s) for s in a["sizes"])
        self.probes = [SurfaceProbe.from_arrays({k[2:]: v for k, v in a.items()
                                                 if k.startswith("g_")})]
        for i in range(1, len(self.sizes)):       # each TetProbe made when FKM first asks
            self.probes.append(_ZoneField(field=SimpleNamespace(
                xyz=a[f"z{i}_xyz"], cells=a[f"z{i}_cells"], face_cells=a[f"z{i}_face_cells"],
                stress_ref=a[f"z{i}_stress"])))
        return self

    def normal(self, node: int) -> tuple[np.ndarray, float]:
        p, j = self._of(node)
        return p.normal(j)

    def stress_at(self, node: int, pts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        p, j = self._of(node)
        return p.stress_at(j, pts)


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


def surface_displacement(res, ref) -> np.ndarray:
    """(n, 3) Cartesian displacement in mm at the points of ``ref`` (= ``zoned_reference(res)``)
    at its speed: the global model's on its revolved surface (``axisymmetric.reference.
    surface_displacement``), each submodel's own nodal values in its zone."""
    from types import SimpleNamespace

    p = ref.depth_probe
    out = np.empty((ref.n_nodes, 3))
    on = p.owner == 0
    g = axi_displacement(res.global_result, SimpleNamespace(n_nodes=p.sizes[0]))
    out[on] = g[p.local[on]]
    for k, (_, sf) in enumerate(res.fields, start=1):
        on = p.owner == k
        out[on] = sf.u.reshape(-1, 3)[p.local[on]]
    return out
