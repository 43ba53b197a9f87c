"""A zone's 3D submodel: the solid on [x0, x1] (``solid.plan.clip``) meshed on its own, its cut
faces driven by the global axisymmetric field, the loads inside the zone applied in it.

Submodeling as Ansys' and Abaqus' practice does it (cut-boundary displacement interpolation):

* every node of a cut face (``end:left`` / ``end:right`` of the clipped plan where the zone does
  not reach the shaft end) takes the global displacement there, the harmonic synthesis at
  (x, r, θ) (``axisymmetric.pointeval.displacement_at``): u_B given, K_II u_I = f_I − K_IB u_B,
  one factorisation of K_II per zone for every speed and case;
* the actions inside the zone (``model.loads.actions`` whose band lies in it: the parts'
  m e ω² at their centroids or, with ``seed_load_case``, their half-seat pressures; the
  ``[[loads]]``) enter as in the full 3D model (``static.model.load_patterns``), × their
  factors at the speed or in the case;
* a bearing inside the zone: the global model's reaction on the shaft, as a remote force on its
  contact band (its tilt spring's moment, zero on every shipped bearing, is left out);
* spin softening: the co-rotating forces the global model applies, as loads: each spinning part
  on a seat in the zone, ω² Σ wᵢ rᵢ (rᵢ · q) with q the seat's remote-point motion
  (``spin.part_rows``) read from the global field on the submodel's seat (its RBE3 rows), and the
  shaft's own mass, ω² ρ u⊥ (the consistent mass times the global transverse field, where the
  global model takes its Ritz projection on Legendre cubics: the difference is below the
  softening's own Ritz error, ``static.model.SHAFT_RITZ_DEGREE``).

The keyway's own effect on the global stiffness (the global model has none) is neglected: the
zoned solve's note measures it against the full 3D model (reactions and deflections).

Stresses: nodal averaging, then the surface recovery (``fe.surface``) on the traction-free faces
(the cut faces are not: they are left out of the recovery, and their edges are patch edges of
the singular-point rule). Peaks per region as in the full 3D model (``fe.recovery.peak``).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from shaftfe.axisymmetric import pointeval
from shaftfe.fe import assembly as fem
from shaftfe.fe import recovery
from shaftfe.model.spin import DEFAULT_PART_MODEL, part_rows, spinning_part
from shaftfe.solid.mesh import build_solid_mesh
from shaftfe.solid.plan import clip
from shaftfe.static.model import load_patterns, mass_times, region_nodes, seat_rows
from shaftfe.util.units import omega, von_mises


@dataclass(frozen=True, eq=False)
class SubModel:
    """A zone's assembled submodel (one factorisation, reused for every speed and case)."""
    zone: object                       # zoned.zones.Zone
    shaft_mesh: object                 # solid.mesh.ShaftMesh of the clipped plan
    variant: object
    options: object                    # static.model.StaticOptions
    cut_groups: tuple[str, ...]        # the mesh groups that are cut faces
    cut_nodes: np.ndarray = field(repr=False)
    cut_dofs: np.ndarray = field(repr=False)
    free_dofs: np.ndarray = field(repr=False)
    K_IB: object = field(repr=False)
    solver: object = field(repr=False)
    patterns: tuple = ()               # static.model.LoadPattern inside the zone
    seats: tuple = ()                  # (R6 (6, ndof), parts) of the spinning parts' seats
    bearings: tuple = ()               # (name, facets, x_mm) of bearings inside the zone
    seconds: dict = field(default_factory=dict)

    @property
    def n_dofs(self) -> int:
        return self.shaft_mesh.n_dofs


@dataclass(frozen=True, eq=False)
class SubField:
    """A submodel's solution at one speed (or case)."""
    u: np.ndarray = field(repr=False)          # (3 N,) interleaved
    stress: np.ndarray = field(repr=False)     # (6, N) recovered
    peaks: tuple = ()                          # fe.recovery.RegionPeak per region
    cut_check: tuple = ()                      # CutCheck per cut face
    seconds: dict = field(default_factory=dict)


@dataclass(frozen=True)
class CutCheck:
    """The submodel's stresses on a cut face against the global model's at the same points
    (the cut-boundary check of submodeling practice): the largest difference of von Mises and
    of σ_xx, relative to the largest global von Mises on the face."""
    group: str
    x_mm: float
    n_nodes: int
    global_vm_max_MPa: float
    vm_diff_rel: float
    sxx_diff_rel: float


def _inside(zone, act) -> bool:
    a, b = act.band_mm
    return zone.x0 - 1e-9 <= a and b <= zone.x1 + 1e-9


def build_submodel(variant, plan, zone, options, *, level=None, cache_dir=None) -> SubModel:
    """Mesh, assemble and factorise the submodel of ``zone`` (``plan``: the whole shaft's mesh
    plan, ``solid.mesh.mesh_plan``, so the zone keeps the whole model's hot-spot sizing)."""
    from shaftfe.fe.solvers import factorize
    t0 = time.perf_counter()
    sm = build_solid_mesh(clip(plan, zone.x0, zone.x1), level or options.level, options.order,
                          cache_dir=cache_dir, name=f"{variant.name}:{zone.name}")
    t1 = time.perf_counter()
    m = sm.mesh
    mat = variant.material
    cut_groups = tuple(g for g, on in (("end:left", zone.cut_left), ("end:right", zone.cut_right))
                       if on)
    nodes = np.unique(np.concatenate([fem.face_nodes(m, m.boundaries[g]) for g in cut_groups]))
    ndof = 3 * m.doflocs.shape[1]
    cut = (3 * nodes[:, None] + np.arange(3)).ravel()
    free = np.setdiff1d(np.arange(ndof), cut)
    K = _stiffness(sm, float(mat.E_MPa), float(mat.nu), cache_dir)
    t2 = time.perf_counter()
    rows: dict = {}
    _, _, patterns = load_patterns(variant, m, options, rows, keep=lambda a: _inside(zone, a))
    seats = []
    if options.spin_softening:
        by_seat: dict = {}
        for a in variant.attachments:
            groups = [np.asarray(f) for g, f in m.boundaries.items()
                      if g.startswith(f"load:{a.name}:")]
            if a.mass_kg > 0 and groups:
                key = (a.seat_x_start_mm, a.seat_x_end_mm)
                by_seat.setdefault(key, (np.concatenate(groups), []))[1].append(
                    spinning_part(a, DEFAULT_PART_MODEL))
        for (x0, x1), (facets, parts) in by_seat.items():
            seats.append((seat_rows(m, facets, (0.5 * (x0 + x1), 0.0, 0.0), rows),
                          tuple(parts)))
    bearings = tuple((b.name, np.asarray(m.boundaries[f"bearing:{b.name}"]),
                      float(b.x_center_mm)) for b in variant.bearings
                     if f"bearing:{b.name}" in m.boundaries)
    solver = factorize(K[free][:, free], options.solver)
    t3 = time.perf_counter()
    return SubModel(zone, sm, variant, options, cut_groups, nodes, cut, free,
                    K[free][:, cut], solver, patterns, tuple(seats), bearings,
                    {"mesh_seconds": t1 - t0, "mesh_from_cache": sm.from_cache,
                     "assembly_seconds": t2 - t1, "factor_seconds": t3 - t2})


def _stiffness(sm, E: float, nu: float, cache_dir=None):
    """The submodel's stiffness, cached on disk by its mesh's content key (``zonek-*.npz``):
    loading a zone's K costs a fifth of assembling it (measured 0.05 against 0.25 s on x2_57's
    gear-seat zone)."""
    import hashlib

    from shaftfe.util import cachefile, paths
    key = hashlib.sha256(f"{sm.key}|{E!r}|{nu!r}|elasticity".encode()).hexdigest()
    path = paths.cache_dir(cache_dir) / f"zonek-{key[:24]}.npz"
    return cachefile.cached_csr(path, key, "zone stiffness",
                                lambda: fem.elasticity_stiffness(sm.mesh, E, nu))


def _global_field(sub: SubModel, gsol) -> np.ndarray:
    """(3 N,) the global displacement at every submodel node (interleaved)."""
    return pointeval.displacement_at(gsol, sub.shaft_mesh.mesh.doflocs).T.ravel()


def load_vector(sub: SubModel, gsol, rpm: float, case=None, ug=None) -> np.ndarray:
    """The submodel's load vector at the speed ``rpm`` (or in ``case``) for the global
    solution ``gsol`` at that speed: its loads × factors, the bearings' global reactions and
    the spin softening's forces from the global motion."""
    m = sub.shaft_mesh.mesh
    f = np.zeros(3 * m.doflocs.shape[1])
    for p in sub.patterns:
        f += p.factor(rpm, case) * p.f
    for name, facets, x in sub.bearings:
        Fx, Fy, Fz = gsol.reactions[name][:3]
        f += seat_rows(m, facets, (x, 0.0, 0.0)).T @ np.array([Fx, Fy, Fz, 0.0, 0.0, 0.0])
    if sub.options.spin_softening and gsol.softening_N_per_mm:
        w2 = omega(gsol.rpm) ** 2
        ug = _global_field(sub, gsol) if ug is None else ug
        for R6, parts in sub.seats:
            q6 = R6 @ ug
            g6 = np.zeros(6)
            for p in parts:
                rows, w = part_rows(np.eye(6), p)
                g6 += (rows.T * w) @ (rows @ q6)
            f += R6.T @ (w2 * g6)
        rho = float(sub.variant.material.density_t_mm3)
        if rho > 0:
            U = ug.reshape(-1, 3)[:, 1:]
            MU = mass_times(m, rho, U)
            f[1::3] += w2 * MU[:, 0]
            f[2::3] += w2 * MU[:, 1]
    return f


def _free_facets(sub: SubModel) -> np.ndarray:
    m = sub.shaft_mesh.mesh
    skip = [np.asarray(f) for g, f in m.boundaries.items()
            if g.startswith("bearing:") or g.endswith(":pressed") or g in sub.cut_groups]
    return np.setdiff1d(m.boundary_facets(), np.concatenate(skip))


def solve_speed(sub: SubModel, gsol, rpm: float, case=None) -> SubField:
    """The submodel's field at one speed: cut faces from ``gsol`` (the global solution at
    that speed), loads inside, then stresses, peaks and the cut check."""
    from shaftfe.fe import surface
    t0 = time.perf_counter()
    m = sub.shaft_mesh.mesh
    mat = sub.variant.material
    ug = _global_field(sub, gsol)
    f = load_vector(sub, gsol, rpm, case, ug)
    u = np.zeros_like(f)
    uB = ug[sub.cut_dofs]
    u[sub.cut_dofs] = uB
    u[sub.free_dofs] = sub.solver.solve(f[sub.free_dofs] - sub.K_IB @ uB)
    t1 = time.perf_counter()
    stress = recovery.nodal_stress(m, u, mat.E_MPa, mat.nu)
    averaged = stress.copy()
    surf = None
    if fem.is_quadratic(m):
        surf = surface.surface_stress(m, u, mat.E_MPa, mat.nu, _free_facets(sub))
        ok = np.isfinite(surf.stress[0])
        stress[:, surf.nodes[ok]] = surf.stress[:, ok]
    patches = [np.asarray(fc) for g, fc in m.boundaries.items()
               if g.startswith("bearing:") or g.endswith(":pressed") or g in sub.cut_groups]
    excl = recovery.excluded_nodes(m, patches, sub.options.exclude_mm)
    regions = {k: v for k, v in region_nodes(m).items() if k not in sub.cut_groups}
    peaks = tuple(recovery.peak(stress, m.doflocs, nodes, excl, name, surf)
                  for name, nodes in sorted(regions.items()))
    checks = tuple(cut_check(sub, g, averaged, gsol) for g in sub.cut_groups)
    t2 = time.perf_counter()
    return SubField(u, stress, peaks, checks, {"solve_seconds": t1 - t0,
                                               "recovery_seconds": t2 - t1})


def cut_check(sub: SubModel, group: str, stress: np.ndarray, gsol) -> CutCheck:
    """The cut-boundary check of one cut face (``CutCheck``)."""
    m = sub.shaft_mesh.mesh
    nodes = fem.face_nodes(m, m.boundaries[group])
    xyz = m.doflocs[:, nodes]
    sg = pointeval.stress_at(gsol, xyz)
    vg, vs = von_mises(sg), von_mises(stress[:, nodes])
    top = max(float(np.max(vg)), 1e-30)
    return CutCheck(group, float(np.mean(xyz[0])), int(nodes.size), float(np.max(vg)),
                    float(np.max(np.abs(vs - vg)) / top),
                    float(np.max(np.abs(stress[0, nodes] - sg[0])) / top))


def cut_error(checks) -> float:
    """The worst relative difference of a submodel's cut checks."""
    return max((max(c.vm_diff_rel, c.sxx_diff_rel) for c in checks), default=0.0)


__all__ = ["CutCheck", "SubField", "SubModel", "build_submodel", "cut_check", "cut_error",
           "load_vector", "solve_speed"]
