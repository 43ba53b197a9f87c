"""The 3D static model: options, the assembled model (stiffness, bearing couplings, one load
vector per load pattern) and the mesh's named regions. ``build_model`` validates the variant,
meshes it (or takes a mesh), assembles K, couples the bearings and builds the loads from
``shaftfe.model.loads.actions``. See ``shaftfe.static.solve`` for the solve.

Loads (issue #31): every action (a force F and moment M about (x, 0, 0)) enters as a remote load
on its band's surface facets, f = Rᵀ [F; M] with R the band's RBE3 rows about the action's point
(``fe.assembly.rigid_rows``): F and M are carried exactly and the band stays free to deform
(Ansys' deformable Remote Force). A part's band is its seat's mesh groups ``load:<part>:*``; a
segment seat or a station band is the outer surface's facets that overlap [x0, x1]
(``band_facets``). With ``seed_load_case`` the parts' actions keep the seed's placement: a
pressure on the pressed half seat (``fe.assembly.surface_load``, today's code). Gravity adds the
shaft's own mass (``fe.assembly.body_force_load``). Actions of one pattern
(``model.loads.pattern_key``; one load alone when a load case factors it) sum to ONE load vector
(``LoadPattern``): one right-hand side each, from one factorisation.

Torsion: a bearing holds θ_x only if it declares ``holds_torsion``. With none, the rotation about
the axis is a gauge: one hard row, θ_x of one bearing's seat (``twist_gauge_block``), whose
reaction equals the net applied torque by equilibrium and must be round-off (the loader's
torque-path rule): the solve checks it."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from shaftfe.beam.planes import mesh_hot_axes
from shaftfe.errors import InputError
from shaftfe.fe import assembly as fem
from shaftfe.fe import reuse, supports
from shaftfe.fe.solvers import METHODS
from shaftfe.model import loads as loadmodel
from shaftfe.model.spin import DEFAULT_PART_MODEL, part_rows, spinning_part
from shaftfe.model.validate import validate_variant
from shaftfe.solid.features import (
    OUTLINE_KINDS,
    SEAT_HALVES,
    is_patch,
    kind_of,
    region_of,
    seat_group,
    seat_halves,
)
from shaftfe.solid.levels import MeshLevel, mesh_level
from shaftfe.solid.mesh import build_mesh
from shaftfe.util.limits import check_exclude_mm
from shaftfe.util.units import REF_RPM, omega

DISTRIBUTIONS = ("uniform", "cosine")


LOAD_CASES = {False: "all parts", True: "seed load case (gear + counterweight 1 = F1, "
                                       "counterweight 2 = Fv2)"}


def load_case_label(seed_load_case: bool) -> str:
    """The load case in words, for every table header and summary.json: every part of the
    variant (the default of every command), or the seed's F1 + Fv2 only."""
    return LOAD_CASES[bool(seed_load_case)]


@dataclass(frozen=True)
class StaticOptions:
    level: str | MeshLevel = "default"     # a level name of shaftfe.solid.levels or a MeshLevel
    order: int = 2
    rigid_supports: bool = False
    load_distribution: str = "uniform"     # "uniform" | "cosine"
    body_force: bool = False               # the shaft's own centrifugal load
    seed_load_case: bool = False           # only the parts the seed loaded (gear, CW1, CW2)
    solver: str = "auto"                   # see shaftfe.fe.solvers
    exclude_mm: float = 0.0                # extra band around patch edges for filtered peaks
    spin_softening: bool = True            # co-rotating softening (shaftfe.static.solve.soften)

    @property
    def load_case(self) -> str:
        return load_case_label(self.seed_load_case)


@dataclass(frozen=True, eq=False)
class LoadPattern:
    """One independent load pattern: the actions that scale together (``model.loads.
    pattern_key``; a load a case factors on its own is a pattern of its own), summed into one
    load vector ``f`` at their written magnitudes: one right-hand side of the solve. A case
    takes it × ``factor`` (``LoadCase.factor`` reads ``factor_name`` and the law)."""
    key: tuple
    scales_with: str
    ref_rpm: float
    channel_ref: float
    factor_name: str                      # the load a case's factor names ("" = none alone)
    names: tuple[str, ...]                # the actions in it
    f: np.ndarray = field(repr=False)
    F_N: tuple[float, float, float] = (0.0, 0.0, 0.0)       # resultant force
    M_Nmm: tuple[float, float, float] = (0.0, 0.0, 0.0)     # resultant moment about 0

    @property
    def name(self) -> str:
        return self.factor_name

    @property
    def label(self) -> str:
        """A readable, unique name of the pattern (summary.json, the cache)."""
        return loadmodel.pattern_label(self.key)

    def factor(self, rpm: float, case=None) -> float:
        """The pattern's factor in ``case`` (a ``LoadCase``), or at the plain speed ``rpm``:
        rpm² loads × (rpm / ref)², constant × 1, channel loads at their ``channel_ref``."""
        if case is not None:
            return case.factor(self)
        return loadmodel.law_factor(self.scales_with, rpm, {}, ref_rpm=self.ref_rpm,
                                    channel_ref=self.channel_ref)


@dataclass(frozen=True, eq=False)
class StaticModel:
    variant: object
    shaft_mesh: object
    options: StaticOptions
    K: object                             # scipy CSR stiffness
    couplings: tuple
    blocks: tuple
    loads: dict                           # action name -> load vector (written magnitude)
    load_force: dict                      # action name -> (Fx, Fy, Fz) (written magnitude)
    f: np.ndarray                         # the plain-speed case's total load at REF_RPM
    assembly_seconds: float
    soft: tuple = ()                      # SoftSeat per loaded seat and the shaft (softening)
    patterns: tuple = ()                  # LoadPattern per independent pattern
    twist_gauge: str = ""                 # no bearing holds torsion: the bearing whose seat
    #                                       θ_x is the gauge (``twist_gauge_block``), else ""


@dataclass(frozen=True, eq=False)
class SoftSeat:
    """One low-rank term of the co-rotating softening (``shaftfe.model.spin``): the negative
    stiffness ω² Rᵀ diag(w) R. A seat: R the rows of its parts' centroid motions and tilts
    (``spin.part_rows`` on the seat's RBE3 rows ``R6`` about the seat centre, the parts on one
    seat summed into at most four rows), ``parts`` the parts on it; the shaft (``parts`` = ()):
    the Ritz rows of its transverse mass (``shaft_rows``)."""
    name: str
    R: np.ndarray                         # (k, ndof)
    w: np.ndarray                         # (k,) per unit ω²: t (translations), t·mm² (tilts)
    R6: np.ndarray | None = None          # (6, ndof) the seat's remote-point rows
    parts: tuple = ()                     # SpinningPart on this seat


# the shaft's transverse mass softening on Legendre polynomials in x of (u_y, u_z): a beam-like
# basis (the transverse motion of a shaft is its axis's deflection up to the section's
# distortion). The degree against the exact solve on coarse x2_57 at 10 000 rpm (error of the
# softening): 1 → 1e-2, 3 → 1.5e-5, 9 → 4e-6 (tests/validation/test_spin_softening_ross.py);
# each degree costs two right-hand sides of the one factorisation
SHAFT_RITZ_DEGREE = 3


def legendre_ritz(Ms, x: np.ndarray, degree: int = SHAFT_RITZ_DEGREE) -> np.ndarray:
    """(degree + 1, N) rows Bs with Bsᵀ Bs = Ms H (Hᵀ Ms H)⁻¹ Hᵀ Ms, H = P_j(ξ(x)) at the nodes
    (Legendre, ξ ∈ [−1, 1] over the nodes' x range): the Ritz projection of a scalar mass
    matrix Ms on polynomials in x. Exact on their span and below Ms in energy elsewhere.
    ``Ms``: the matrix, or a function H ↦ Ms H (``mass_times``: no matrix assembled)."""
    from numpy.polynomial import legendre
    xi = (2.0 * x - (x.min() + x.max())) / (x.max() - x.min())
    H = legendre.legvander(xi, degree)                   # (N, degree + 1)
    MH = np.asarray(Ms(H) if callable(Ms) else Ms @ H)
    L = np.linalg.cholesky(H.T @ MH)                     # the Gram Hᵀ Ms H
    return np.linalg.solve(L, MH.T)


def mass_times(mesh, density: float, H: np.ndarray) -> np.ndarray:
    """Ms H for the scalar consistent mass Ms = ∫ ρ φ_a φ_b (``fe.assembly.scalar_quadrature``,
    as ``rotordynamics.solid_rotor.mass_and_gyro``) and nodal columns H (N, J),
    element by element without assembling Ms (nor the rotor's gyroscopic matrix): the static
    command needs only these few columns (measured: 0.8 s of assembly saved on x2_57)."""
    phi, _, wdx = fem.scalar_quadrature(mesh)                                 # (nloc, nq), (ne, nq)
    en = fem.element_nodes(mesh)                                              # (nloc, ne)
    Hq = np.einsum("aq,aej->eqj", phi, H[en])                                 # H at the points
    contrib = np.einsum("aq,eqj->eaj", phi, (density * wdx)[:, :, None] * Hq)  # (ne, nloc, J)
    out = np.zeros(H.shape)
    idx = en.T.ravel()
    for j in range(H.shape[1]):
        out[:, j] = np.bincount(idx, weights=contrib[:, :, j].ravel(), minlength=H.shape[0])
    return out


def shaft_rows(mesh, density: float, degree: int = SHAFT_RITZ_DEGREE) -> np.ndarray:
    """(2 (degree + 1), ndof) rows B with Bᵀ B the Ritz projection of the shaft's transverse
    mass M_⊥ (∫ ρ (u_y v_y + u_z v_z)) on Φ = P_j(ξ(x)) e_y, P_j(ξ(x)) e_z (``legendre_ritz``):
    it softens the part of the motion outside the basis not at all."""
    x = mesh.doflocs[0]
    Bs = reuse.memo("shaft_ritz", (reuse.mesh_digest(mesh), density, degree),
                    lambda: legendre_ritz(lambda H: mass_times(mesh, density, H), x, degree))
    B = np.zeros((2 * Bs.shape[0], 3 * x.size))
    B[:Bs.shape[0], 1::3] = Bs
    B[Bs.shape[0]:, 2::3] = Bs
    return B


def spin_seats(variant, mesh, *, part_model: str = DEFAULT_PART_MODEL,
               shaft: bool = True, rows: dict | None = None) -> tuple[SoftSeat, ...]:
    """The co-rotating softening terms of ``variant`` on ``mesh``: one per loaded seat (its
    parts, ``shaftfe.model.spin``) and, with ``shaft``, the shaft's own mass (``shaft_rows``).
    ``rows``: the seats' RBE3 rows already made for the loads (``seat_rows``)."""
    seats: dict = {}
    for a in variant.attachments:
        groups = [np.asarray(fc) for g, fc in mesh.boundaries.items()
                  if g in seat_halves(a.name)]
        if a.mass_kg > 0 and groups:
            key = (a.seat_x_start_mm, a.seat_x_end_mm)
            seats.setdefault(key, (np.concatenate(groups), []))[1].append(
                spinning_part(a, part_model))
    out = []
    for (x0, x1), (facets, parts) in seats.items():
        R6 = seat_rows(mesh, facets, (0.5 * (x0 + x1), 0.0, 0.0), rows)
        # Σ over the parts on the seat as one 4 × 4 matrix on (u_y, u_z, θ_y, θ_z), then its
        # eigenvectors as rows (at most four per seat, whatever the number of parts)
        S4 = np.zeros((4, 4))
        for p in parts:
            S4 += _seat_block(*part_rows(np.eye(6), p))
        lam, vec = np.linalg.eigh(S4)
        keep = np.abs(lam) > 1e-12 * np.abs(lam).max()
        R = vec[:, keep].T @ R6[[1, 2, 4, 5]]
        out.append(SoftSeat("+".join(p.name for p in parts), np.ascontiguousarray(R),
                            lam[keep], np.ascontiguousarray(R6), tuple(parts)))
    if shaft and variant.material.density_t_mm3 > 0:
        out.append(SoftSeat("shaft", shaft_rows(mesh, variant.material.density_t_mm3),
                            np.ones(2 * (SHAFT_RITZ_DEGREE + 1))))
    return tuple(out)


def _seat_block(rows: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Σ w_i r_i r_iᵀ restricted to the seat's (u_y, u_z, θ_y, θ_z) (rows over the 6 rigid
    dofs of its remote point)."""
    r = rows[:, [1, 2, 4, 5]]
    return (r.T * w) @ r


# --------------------------------------------------------------------------- model

def _direction(angle_deg: float) -> np.ndarray:
    a = math.radians(angle_deg)
    return np.array([0.0, math.cos(a), math.sin(a)])


def check_options(o: StaticOptions) -> None:
    """Every rule of the static options, one place for the command line and a caller in
    Python (InputError naming the command line's option)."""
    if o.order not in (1, 2):
        raise InputError("--order", "order", "1 | 2", got=o.order)
    mesh_level(o.level)
    if o.load_distribution not in DISTRIBUTIONS:
        raise InputError("--load-distribution", "load_distribution", " | ".join(DISTRIBUTIONS),
                         got=o.load_distribution)
    check_exclude_mm(o.exclude_mm, "--exclude-mm", "exclude_mm")   # ``util.limits``' rule
    if o.solver not in METHODS:
        raise InputError("--solver", "solver", " | ".join(METHODS), got=o.solver)


def build_model(variant, options: StaticOptions = StaticOptions(), *, shaft_mesh=None,
                cache_dir=None) -> StaticModel:
    """Mesh (or take ``shaft_mesh``), assemble K, couple the bearings, build the loads."""
    check_options(options)
    if options.seed_load_case:
        variant = variant.with_seed_load_case()
    validate_variant(variant, springs=not options.rigid_supports, typed=False)
    if shaft_mesh is None:
        shaft_mesh = build_mesh(variant, options.level, options.order, cache_dir=cache_dir,
                                hot_axes=mesh_hot_axes(variant))
    m = shaft_mesh.mesh
    mat = variant.material
    t0 = time.perf_counter()
    K = reuse.memo("K", (reuse.mesh_digest(m), mat.E_MPa, mat.nu),
                   lambda: fem.elasticity_stiffness(m, mat.E_MPa, mat.nu))
    couplings = [supports.couple_bearing(m, b, rigid=options.rigid_supports,
                                         hold_twist=bool(getattr(b, "holds_torsion", False)))
                 for b in variant.bearings]
    blocks = [blk for c in couplings for blk in supports.blocks(c)]
    gauge = ""
    if couplings and not any(c.hold_twist for c in couplings):
        blocks.append(twist_gauge_block(couplings))
        gauge = blocks[-1].bearing
    blocks = tuple(blocks)
    rows: dict = {}                # the seats' RBE3 rows: the loads' and the softening's
    loads, forces, patterns = load_patterns(variant, m, options, rows)
    f = np.zeros(K.shape[0])
    for p in patterns:
        f += p.factor(REF_RPM) * p.f
    soft = spin_seats(variant, m, rows=rows) if options.spin_softening else ()
    return StaticModel(variant, shaft_mesh, options, K, tuple(couplings), blocks, loads,
                       forces, f, time.perf_counter() - t0, soft, patterns, gauge)


def twist_gauge_block(couplings) -> supports.SupportBlock:
    """The gauge of the free rotation about the axis when no bearing holds torsion: one hard
    row, θ_x of one bearing's seat (its RBE3 row; the axial bearing's, else the first) = 0. It
    fixes the rigid rotation the loads leave undetermined without holding any torque: its
    reaction is the net applied torque (equilibrium), which the torque-path rule makes zero and
    the solve checks to be round-off. A seat's mean rotation, not a pinned node: the nodal
    displacements are those a bearing holding θ_x with no torque gives."""
    c = next((c for c in couplings if c.axial), couplings[0])
    return supports.SupportBlock(c.name, ("θ_x",), c.G[[3]], None)


BAND_NORMAL_MIN = 0.7         # |n · e_r| of an outer cylindrical facet (not a face or chamfer)


def band_facets(mesh, band: tuple[float, float]) -> np.ndarray:
    """The outer surface's boundary facets a station or segment load is delivered through: the
    facets whose axial extent overlaps [x0, x1] (a full ring however narrow the band), with a
    radial normal (|n_r| > ``BAND_NORMAL_MIN``) and outside the feature faces (fillets,
    shoulders, keyways, hex socket, end faces). Empty if there are none."""
    bf = np.asarray(mesh.boundary_facets())
    skip = [np.asarray(f) for g, f in mesh.boundaries.items() if kind_of(g) in OUTLINE_KINDS]
    if skip:
        bf = np.setdiff1d(bf, np.concatenate(skip))
    P = mesh.p[:, mesh.facets[:, bf]]                       # (3, 3 corners, nf)
    x0, x1 = band
    eps = 1e-9 * max(1.0, abs(x1 - x0))
    over = (P[0].max(axis=0) > x0 + eps) & (P[0].min(axis=0) < x1 - eps)
    n = np.cross((P[:, 1] - P[:, 0]).T, (P[:, 2] - P[:, 0]).T).T
    c = P.mean(axis=1)
    rc = np.hypot(c[1], c[2])
    nr = np.abs(n[1] * c[1] + n[2] * c[2]) / np.maximum(np.linalg.norm(n, axis=0) * rc, 1e-300)
    return bf[over & (nr > BAND_NORMAL_MIN)]


def _action_facets(mesh, act) -> np.ndarray:
    """A part's seat groups (its two halves), else the band's outer facets."""
    groups = [np.asarray(f) for g, f in mesh.boundaries.items()
              if act.seat and g in seat_halves(act.seat)]
    if groups:
        return np.concatenate(groups)
    fac = band_facets(mesh, act.band_mm)
    if fac.size == 0:
        raise InputError("loads", f"{act.factor_name}.x_mm", "a band on the shaft's outer "
                         "cylindrical surface (not inside a fillet, keyway or the hex socket)",
                         got=f"[{act.band_mm[0]:g}, {act.band_mm[1]:g}] mm")
    return fac


def seat_rows(mesh, facets, point, cache: dict | None = None) -> np.ndarray:
    """The RBE3 rows (6, ndof) of ``facets`` about ``point`` (``fe.assembly.rigid_rows``), made
    once per (facets, point) in ``cache``: a seat's rows serve its parts' loads and its spin
    softening."""
    key = (np.asarray(facets).tobytes(), tuple(float(c) for c in point))
    R = None if cache is None else cache.get(key)
    if R is None:
        R = fem.rigid_rows(mesh, facets, point)
        if cache is not None:
            cache[key] = R
    return R


def remote_load(mesh, facets, point, F, M, cache: dict | None = None) -> np.ndarray:
    """f = Rᵀ [F; M]: the load vector of a force F and a moment M about ``point`` delivered
    through ``facets`` by their RBE3 rows R (``seat_rows``). R Φ = I, so the resultant of f is
    exactly (F, M) about ``point``; ``cache``: R per (facets, point)."""
    R = seat_rows(mesh, facets, point, cache)
    return R.T @ np.concatenate([np.asarray(F, dtype=float), np.asarray(M, dtype=float)])


def resultant(mesh, f: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(Σ f, Σ x × f about the origin) of a nodal load vector."""
    f3 = f.reshape(-1, 3)
    return f3.sum(axis=0), np.cross(mesh.doflocs.T, f3).sum(axis=0)


def load_patterns(variant, m, options: StaticOptions, rows: dict | None = None, keep=None):
    """({action name: vector}, {action name: force}, patterns): every action of the variant
    (``model.loads.actions``) as a load vector, summed per pattern. ``keep``: a predicate on
    the actions (a 3D submodel takes those inside its zone; the body loads act on its mesh)."""
    acts, body = loadmodel.actions(variant, seed_placement=options.seed_load_case)
    if keep is not None:
        acts = [a for a in acts if keep(a)]
    factored = loadmodel.factored_loads(variant)
    loads, forces = {}, {}
    vec: dict[tuple, np.ndarray] = {}
    meta: dict[tuple, tuple] = {}
    face_cache: dict = {}          # facet bases shared by parts on the same seat
    rows = {} if rows is None else rows

    def add(item, name: str, v: np.ndarray) -> None:
        own = getattr(item, "factor_name", item.name)
        key = loadmodel.solve_pattern(loadmodel.pattern_key(item), own, factored)
        if key not in vec:
            vec[key] = np.zeros_like(v)
            meta[key] = (item.scales_with, float(item.ref_rpm), float(item.channel_ref),
                         own if own in factored else "", [])
        vec[key] += v
        if name not in meta[key][4]:
            meta[key][4].append(name)
        # a load of several actions (a gear mesh: its axial part and its transverse part)
        # is one vector under its name
        loads[name] = loads[name] + v if name in loads else v
        forces[name] = tuple(float(c) for c in loads[name].reshape(-1, 3).sum(axis=0))

    for act in acts:
        if act.pressed_half:        # the seed's placement: today's pressure on the half seat
            a = variant.attachment(act.seat)
            F = a.force_N(REF_RPM)
            v = fem.surface_load(m, m.boundaries[seat_group(a.name, SEAT_HALVES[0])], F,
                                 _direction(a.angle_deg), options.load_distribution,
                                 cache=face_cache)
        else:
            v = remote_load(m, _action_facets(m, act), (act.x_mm, 0.0, 0.0), act.F_N,
                            act.M_Nmm, rows)
        add(act, act.name, v)
    rho = variant.material.density_t_mm3
    for b in body:
        add(b, f"{b.name}:shaft", fem.body_force_load(m, rho, 0.0, accel=b.accel_mm_s2))
    if options.body_force:
        shaft = loadmodel.BodyAction("shaft_body", (0.0, 0.0, 0.0), "rpm2", REF_RPM)
        add(shaft, "shaft_body", fem.body_force_load(m, rho, omega(REF_RPM) ** 2))
    if not vec:                    # nothing loads the shaft: one zero rpm² pattern
        vec[("rpm2", REF_RPM)] = np.zeros(3 * m.doflocs.shape[1])
        meta[("rpm2", REF_RPM)] = ("rpm2", REF_RPM, 1.0, "", [])
    patterns = []
    for key, v in vec.items():
        law, ref, cref, own, names = meta[key]
        F, M = resultant(m, v)
        patterns.append(LoadPattern(key, law, ref, cref, own, tuple(names), v,
                                    tuple(float(c) for c in F), tuple(float(c) for c in M)))
    return loads, forces, tuple(patterns)


def region_facets(mesh) -> dict[str, np.ndarray]:
    """Stress regions: each fillet, keyway, shoulder and seat (a split load seat counted once),
    the hex socket and the end faces."""
    groups: dict[str, list] = {}
    for g, f in mesh.boundaries.items():
        groups.setdefault(region_of(g), []).append(np.asarray(f))
    return {k: np.concatenate(v) for k, v in groups.items()}


def region_nodes(mesh) -> dict[str, np.ndarray]:
    """Region name -> node ids (of ``region_facets``), sorted by name: the regions whose peaks
    ``shaftfe static`` reports and ``shaftfe fatigue`` uses for its hot spots."""
    return {k: fem.face_nodes(mesh, f).astype(np.int64)
            for k, f in sorted(region_facets(mesh).items())}


def _patches(mesh) -> list[np.ndarray]:
    return [np.asarray(f) for g, f in mesh.boundaries.items() if is_patch(g)]


