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
* spin softening: the co-rotating forces the global model applies, as loads: the parts on each
  seat in the zone, ω² Rᵀ diag(w) R u_g with the full 3D model's softening rows of the seat
  (``static.model.spin_seats``: the parts' centroid and tilt rows on the seat's RBE3 rows) and
  u_g the global field at the submodel's nodes, and the
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
from shaftfe.errors import SolverError
from shaftfe.fe import assembly as fem
from shaftfe.fe import recovery, surface
from shaftfe.fe.solvers import factorize
from shaftfe.solid.features import END_LEFT, END_RIGHT, bearing_group, is_patch
from shaftfe.solid.mesh import build_solid_mesh
from shaftfe.solid.plan import clip
from shaftfe.static.model import load_patterns, mass_times, region_nodes, seat_rows, spin_seats
from shaftfe.util import cachefile, paths
from shaftfe.util.units import omega, von_mises


@dataclass(frozen=True, eq=False)
class SubModel:
    """A zone's assembled submodel (one factorisation, reused for every speed and case)."""
    zone: object                       # zoned.zones.Zone
    shaft_mesh: object                 # solid.mesh.ShaftMesh of the clipped plan
    variant: object
    options: object                    # static.model.StaticOptions
    cut_groups: tuple[str, ...]        # the mesh groups that are cut faces
    cut_dofs: np.ndarray = field(repr=False)      # every cut face's dofs
    free_dofs: np.ndarray = field(repr=False)
    K_IB: object = field(repr=False)                # K[free, cut]
    solver: object = field(repr=False)              # K[free, free] factorised
    floating: object = None                          # FloatingCut of a zone with two cuts
    patterns: tuple = ()               # static.model.LoadPattern inside the zone
    seats: tuple = ()                  # static.model.SoftSeat of the spinning parts' seats
    bearings: tuple = ()               # (name, RBE3 rows (6, ndof)) of bearings inside the zone
    regions: dict = field(default_factory=dict, repr=False)   # region -> node ids (no cuts)
    excluded: np.ndarray = field(default=None, repr=False)    # the singular-point rule's nodes
    free_facets: np.ndarray = field(default=None, repr=False)  # traction-free boundary facets
    seconds: dict = field(default_factory=dict)
    cache_dir: object = None           # where its stiffness and node location are cached

    @property
    def n_dofs(self) -> int:
        return self.shaft_mesh.n_dofs


@dataclass(frozen=True, eq=False)
class FloatingCut:
    """The second cut of a zone with two: its face moves as the global field plus a rigid
    motion q (6), and the global section resultant acts on it (see ``build_submodel``).
    ``pos``: the face's dofs' positions in ``cut_dofs``; Φ (k, 6) its rigid modes about the
    face centre; W = K_II⁻¹ K_IF Φ; S = Φᵀ K_FF Φ − Φᵀ K_FI W (6 × 6); ``K_FI`` = K[face, free]."""
    pos: np.ndarray = field(repr=False)
    Phi: np.ndarray = field(repr=False)
    W: np.ndarray = field(repr=False)
    S: np.ndarray = field(repr=False)
    K_FI: object = field(repr=False)


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
    """The cut-boundary check of submodeling practice, on one cut face: the submodel's stresses
    there against the global field's. Both are recovered on the submodel's own mesh (the
    global displacement interpolated at its nodes, then the same nodal averaging), so the two
    meshes' discretisation cancels and what remains is how far the submodel's solution departs
    from the global one at its cut: the feature's reach. The largest difference of von Mises
    and of σ_xx, relative to the largest global von Mises on the face."""
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
    t0 = time.perf_counter()
    sm = build_solid_mesh(clip(plan, zone.x0, zone.x1), level or options.level, options.order,
                          cache_dir=cache_dir, name=f"{variant.name}:{zone.name}")
    t1 = time.perf_counter()
    m = sm.mesh
    mat = variant.material
    cut_groups = tuple(g for g, on in ((END_LEFT, zone.cut_left), (END_RIGHT, zone.cut_right))
                       if on)
    if not cut_groups:
        # a zone with no cut is the whole shaft: nothing drives it (its rigid motions are free)
        raise SolverError(f"{variant.name}: the 3D zones of the features that are not round "
                          f"({', '.join(f.region for f in zone.features)}) cover the whole "
                          "shaft, so there is no global model to drive them: use --model solid")
    faces = [fem.face_nodes(m, m.boundaries[g]) for g in cut_groups]
    nodes = np.unique(np.concatenate(faces))
    ndof = 3 * m.doflocs.shape[1]
    cut = (3 * nodes[:, None] + np.arange(3)).ravel()
    free = np.setdiff1d(np.arange(ndof), cut)
    K = stiffness(sm, float(mat.E_MPa), float(mat.nu), cache_dir)
    t2 = time.perf_counter()
    rows: dict = {}
    _, _, patterns = load_patterns(variant, m, options, rows, keep=lambda a: _inside(zone, a))
    # the parts' softening terms of the seats in the zone, as the full 3D model makes them (the
    # shaft's own mass is applied point by point instead: ``load_vector``)
    seats = spin_seats(variant, m, shaft=False, rows=rows) if options.spin_softening else ()
    bearings = tuple((b.name, seat_rows(m, np.asarray(m.boundaries[bearing_group(b.name)]),
                                        (float(b.x_center_mm), 0.0, 0.0), rows))
                     for b in variant.bearings if bearing_group(b.name) in m.boundaries)
    K_II, K_IB = fem.partition(K, cut)
    solver = factorize(K_II, options.solver)
    del K_II
    floating = None
    if len(faces) == 2:
        fdofs = (3 * faces[1][:, None] + np.arange(3)).ravel()
        pos = np.searchsorted(cut, fdofs)
        centre = (float(m.doflocs[0, faces[1]].mean()), 0.0, 0.0)
        Phi = fem.rigid_body_modes(m, centre)[fdofs]
        W = np.asarray(solver.solve(np.asarray(K_IB[:, pos] @ Phi)))
        K_F = K[fdofs]
        K_FI = K_F[:, free]
        S = Phi.T @ (K_F[:, fdofs] @ Phi) - Phi.T @ (K_FI @ W)
        floating = FloatingCut(pos, Phi, W, S, K_FI)
    # the singular-point rule's patches: the bearings, the pressed halves and the cut faces (a
    # traction jump at their edges); every other boundary facet is traction-free
    patches = [np.asarray(fc) for g, fc in m.boundaries.items()
               if is_patch(g) or g in cut_groups]
    excluded = recovery.excluded_nodes(m, patches, options.exclude_mm)
    free_facets = np.setdiff1d(m.boundary_facets(), np.concatenate(patches))
    regions = {k: v for k, v in region_nodes(m).items() if k not in cut_groups}
    t3 = time.perf_counter()
    return SubModel(zone, sm, variant, options, cut_groups, cut, free, K_IB, solver, floating,
                    patterns, tuple(seats), bearings, regions, excluded, free_facets,
                    {"mesh_seconds": t1 - t0, "mesh_from_cache": sm.from_cache,
                     "assembly_seconds": t2 - t1, "factor_seconds": t3 - t2}, cache_dir)


def stiffness(sm, E: float, nu: float, cache_dir=None):
    """The submodel's stiffness, cached on disk by its mesh's content key (``zonek-*.npz``):
    loading a zone's K costs a fifth of assembling it (measured 0.05 against 0.25 s on x2_57's
    gear-seat zone)."""
    import hashlib

    key = hashlib.sha256(f"{sm.key}|{E!r}|{nu!r}|elasticity".encode()).hexdigest()
    path = paths.cache_dir(cache_dir) / f"zonek-{key[:24]}.npz"
    return cachefile.cached_csr(path, key, "zone stiffness",
                                lambda: fem.elasticity_stiffness(sm.mesh, E, nu))


def located(sub: SubModel, mesh):
    """The submodel's nodes located in the global meridian mesh ``mesh``
    (``pointeval.locate``), cached on disk by both meshes' content keys (``zoneloc-*.npz``):
    both meshes are cached by their keys, so the location is too; a warm run then needs no
    k-d tree (its import, scipy.spatial, is 0.2 s of x2_57's warm static run)."""
    import hashlib

    xyz = sub.shaft_mesh.mesh.doflocs
    x, r = xyz[0], np.hypot(xyz[1], xyz[2])
    if not (sub.shaft_mesh.key and mesh.key):
        return pointeval.locate(mesh, x, r)
    key = hashlib.sha256(f"{sub.shaft_mesh.key}|{mesh.key}|locate-1".encode()).hexdigest()
    names = ("e", "xi", "eta", "found")
    z, _ = cachefile.cached(paths.cache_dir(sub.cache_dir) / f"zoneloc-{key[:24]}.npz", key,
                            "zone location",
                            lambda: (dict(zip(names, pointeval.locate(mesh, x, r),
                                              strict=True)), {}))
    return tuple(z[n] for n in names)


def _global_field(sub: SubModel, gsol) -> np.ndarray:
    """(3 N,) the global displacement at every submodel node (interleaved)."""
    return pointeval.displacement_at(gsol, sub.shaft_mesh.mesh.doflocs,
                                     located(sub, gsol.mesh)).T.ravel()


def _bearing_loads(sub: SubModel, gsol) -> np.ndarray:
    """The load vector of the bearings inside the zone: their reactions in ``gsol``."""
    f = np.zeros(3 * sub.shaft_mesh.mesh.doflocs.shape[1])
    for name, R in sub.bearings:
        Fx, Fy, Fz = gsol.reactions[name][:3]
        f += R.T @ np.array([Fx, Fy, Fz, 0.0, 0.0, 0.0])
    return f


def load_vector(sub: SubModel, gsol, rpm: float, case=None, ug=None) -> np.ndarray:
    """The submodel's load vector at the speed ``rpm`` (or in ``case``) for the global
    solution ``gsol`` at that speed: its loads × factors, the bearings' global reactions and
    the spin softening's forces from the global motion."""
    m = sub.shaft_mesh.mesh
    f = _bearing_loads(sub, gsol)
    for p in sub.patterns:
        f += p.factor(rpm, case) * p.f
    if sub.options.spin_softening and gsol.softening_N_per_mm:
        w2 = omega(gsol.rpm) ** 2
        ug = _global_field(sub, gsol) if ug is None else ug
        for seat in sub.seats:                   # ω² Rᵀ diag(w) R u_g (``SoftSeat``)
            f += w2 * (seat.R.T @ (seat.w * (seat.R @ ug)))
        rho = float(sub.variant.material.density_t_mm3)
        if rho > 0:
            U = ug.reshape(-1, 3)[:, 1:]
            MU = mass_times(m, rho, U)
            f[1::3] += w2 * MU[:, 0]
            f[2::3] += w2 * MU[:, 1]
    return f


def solve_speed(sub: SubModel, gsol, rpm: float, case=None) -> SubField:
    """The submodel's field at one speed: cut faces from ``gsol`` (the global solution at
    that speed), loads inside, then stresses, peaks and the cut check."""
    t0 = time.perf_counter()
    m = sub.shaft_mesh.mesh
    mat = sub.variant.material
    ug = _global_field(sub, gsol)
    f = load_vector(sub, gsol, rpm, case, ug)
    u = displace(sub, ug, f)
    t1 = time.perf_counter()
    grad = recovery.node_gradients(m)                 # one for both fields
    stress, averaged, surf = _recover(sub, u, grad)
    peaks = tuple(recovery.peak(stress, m.doflocs, nodes, sub.excluded, name, surf)
                  for name, nodes in sorted(sub.regions.items()))
    stress_g = recovery.nodal_stress(m, ug, mat.E_MPa, mat.nu, grad)
    checks = tuple(cut_check(sub, g, averaged, stress_g) for g in sub.cut_groups)
    t2 = time.perf_counter()
    return SubField(u, stress, peaks, checks, {"solve_seconds": t1 - t0,
                                               "recovery_seconds": t2 - t1})


def _recover(sub: SubModel, u: np.ndarray, grad=None):
    """(stress, averaged, surface) of the submodel's displacement ``u``: the nodal stresses
    with the free surface's surface-recovered ones (P2), the averaged nodal stresses alone,
    and the surface recovery (None for P1)."""
    m = sub.shaft_mesh.mesh
    mat = sub.variant.material
    stress = recovery.nodal_stress(m, u, mat.E_MPa, mat.nu, grad)
    averaged = stress.copy()
    surf = None
    if fem.is_quadratic(m):
        surf = surface.surface_stress(m, u, mat.E_MPa, mat.nu, sub.free_facets)
        ok = np.isfinite(surf.stress[0])
        stress[:, surf.nodes[ok]] = surf.stress[:, ok]
    return stress, averaged, surf


def pattern_stress(sub: SubModel, gsol, key: tuple, grad=None) -> np.ndarray:
    """(6, N) the submodel's stress under one load pattern alone (``key``: ``model.loads.
    solve_pattern``) at its written magnitudes, unsoftened: the cut faces from ``gsol`` (the
    global solution of that pattern alone, ``axisymmetric.model.superpose``), the pattern's
    loads inside the zone and the bearings' reactions in ``gsol``. ``grad``: the mesh's
    ``recovery.node_gradients``, when several patterns share it."""
    f = _bearing_loads(sub, gsol)
    for p in sub.patterns:
        if tuple(p.key) == tuple(key):
            f += p.f
    return _recover(sub, displace(sub, _global_field(sub, gsol), f), grad)[0]


def displace(sub: SubModel, ug: np.ndarray, f: np.ndarray) -> np.ndarray:
    """The submodel's displacement for the global field ``ug`` at its nodes and its load
    vector ``f``. One cut: u_B = u_g there, K_II u_I = f_I − K_IB u_B. Two cuts: the first as
    one cut; the second moves as u_g plus a rigid motion q, with the global section resultant
    on it, Φᵀ (K u_g)_F (the force the shaft beyond the cut exerts in the global field,
    recovered on this mesh; exact where the global field is a polynomial of the elements'
    degree: tension, torsion, bending): a zone that is softer than the round shaft (a keyway)
    then carries the global loads, where two displacement-driven cuts would have it carry
    less (measured: −7 … −11 % on a keyway between two cuts in torsion and bending)."""
    u = np.zeros_like(f)
    uB = ug[sub.cut_dofs]
    rhs = f[sub.free_dofs] - sub.K_IB @ uB
    y = np.asarray(sub.solver.solve(rhs))
    fl = sub.floating
    if fl is not None:
        rq = fl.Phi.T @ (fl.K_FI @ ug[sub.free_dofs]) - fl.Phi.T @ (fl.K_FI @ y)
        q = np.linalg.solve(fl.S, rq)
        y = y - fl.W @ q
        uB = uB.copy()
        uB[fl.pos] += fl.Phi @ q
    u[sub.cut_dofs] = uB
    u[sub.free_dofs] = y
    return u


def cut_check(sub: SubModel, group: str, stress: np.ndarray, stress_g: np.ndarray) -> CutCheck:
    """The cut-boundary check of one cut face (``CutCheck``): ``stress`` the submodel's nodal
    stresses, ``stress_g`` the global field's on the same mesh."""
    m = sub.shaft_mesh.mesh
    nodes = fem.face_nodes(m, m.boundaries[group])
    vg, vs = von_mises(stress_g[:, nodes]), von_mises(stress[:, nodes])
    top = max(float(np.max(vg)), 1e-30)
    return CutCheck(group, float(np.mean(m.doflocs[0, nodes])), int(nodes.size), float(top),
                    float(np.max(np.abs(vs - vg)) / top),
                    float(np.max(np.abs(stress[0, nodes] - stress_g[0, nodes])) / top))


def cut_error(checks) -> float:
    """The worst relative difference of a submodel's cut checks."""
    return max((max(c.vm_diff_rel, c.sxx_diff_rel) for c in checks), default=0.0)


__all__ = ["CutCheck", "SubField", "SubModel", "build_submodel", "cut_check", "cut_error",
           "load_vector", "located", "pattern_stress", "solve_speed"]
