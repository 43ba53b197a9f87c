"""The 3D static model: options, the assembled model (stiffness, bearing couplings, loads at
REF_RPM) and the mesh's named regions. ``build_model`` validates the variant, meshes it (or takes
a mesh), assembles K and couples the bearings. See ``shaftfe.static.solve`` for the solve."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from shaftfe.errors import InputError
from shaftfe.fe import assembly as fem
from shaftfe.fe import reuse, supports
from shaftfe.model.spin import DEFAULT_PART_MODEL, part_rows, spinning_part
from shaftfe.model.validate import validate_variant
from shaftfe.solid.levels import MeshLevel
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
    hold_twist: str = "all"                # θ_x held at "all" bearings, the "axial" one, "none"
    exclude_mm: float = 0.0                # extra band around patch edges for filtered peaks
    spin_softening: bool = True            # co-rotating softening (shaftfe.static.solve.soften)

    @property
    def load_case(self) -> str:
        return load_case_label(self.seed_load_case)


@dataclass(frozen=True, eq=False)
class StaticModel:
    variant: object
    shaft_mesh: object
    options: StaticOptions
    K: object                             # scipy CSR stiffness
    couplings: tuple
    blocks: tuple
    loads: dict                           # attachment name -> load vector at REF_RPM
    load_force: dict                      # attachment name -> (Fx, Fy, Fz) at REF_RPM
    f: np.ndarray                         # total load vector at REF_RPM
    assembly_seconds: float
    soft: tuple = ()                      # SoftSeat per loaded seat and the shaft (softening)


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
    matrix Ms on polynomials in x. Exact on their span and below Ms in energy elsewhere."""
    from numpy.polynomial import legendre
    xi = (2.0 * x - (x.min() + x.max())) / (x.max() - x.min())
    H = legendre.legvander(xi, degree)                   # (N, degree + 1)
    MH = np.asarray(Ms @ H)
    L = np.linalg.cholesky(H.T @ MH)                     # the Gram Hᵀ Ms H
    return np.linalg.solve(L, MH.T)


def shaft_rows(mesh, density: float, degree: int = SHAFT_RITZ_DEGREE) -> np.ndarray:
    """(2 (degree + 1), ndof) rows B with Bᵀ B the Ritz projection of the shaft's transverse
    mass M_⊥ (∫ ρ (u_y v_y + u_z v_z)) on Φ = P_j(ξ(x)) e_y, P_j(ξ(x)) e_z (``legendre_ritz``):
    it softens the part of the motion outside the basis not at all."""
    from shaftfe.rotordynamics.solid_rotor import mass_and_gyro
    Ms = reuse.memo("scalar_mass", (reuse.mesh_digest(mesh), density),
                    lambda: mass_and_gyro(mesh, density)[0])
    x = mesh.doflocs[0]
    Bs = legendre_ritz(Ms, x, degree)
    B = np.zeros((2 * Bs.shape[0], 3 * x.size))
    B[:Bs.shape[0], 1::3] = Bs
    B[Bs.shape[0]:, 2::3] = Bs
    return B


def spin_seats(variant, mesh, *, part_model: str = DEFAULT_PART_MODEL,
               shaft: bool = True) -> tuple[SoftSeat, ...]:
    """The co-rotating softening terms of ``variant`` on ``mesh``: one per loaded seat (its
    parts, ``shaftfe.model.spin``) and, with ``shaft``, the shaft's own mass (``shaft_rows``)."""
    seats: dict = {}
    for a in variant.attachments:
        groups = [np.asarray(fc) for g, fc in mesh.boundaries.items()
                  if g.startswith(f"load:{a.name}:")]
        if a.mass_kg > 0 and groups:
            key = (a.seat_x_start_mm, a.seat_x_end_mm)
            seats.setdefault(key, (np.concatenate(groups), []))[1].append(
                spinning_part(a, part_model))
    out = []
    for (x0, x1), (facets, parts) in seats.items():
        R6 = fem.rigid_rows(mesh, facets, (0.5 * (x0 + x1), 0.0, 0.0))
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


def _check_options(o: StaticOptions) -> None:
    if o.load_distribution not in DISTRIBUTIONS:
        raise InputError("--load-distribution", "load_distribution", " | ".join(DISTRIBUTIONS),
                         got=o.load_distribution)
    if not (math.isfinite(o.exclude_mm) and o.exclude_mm >= 0):
        raise InputError("--exclude-mm", "exclude_mm", ">= 0", got=o.exclude_mm)
    if o.hold_twist not in supports.HOLD_TWIST:
        raise InputError("options", "hold_twist", " | ".join(supports.HOLD_TWIST),
                         got=o.hold_twist)
    from shaftfe.fe.solvers import METHODS
    if o.solver not in METHODS:
        raise InputError("--solver", "solver", " | ".join(METHODS), got=o.solver)


def build_model(variant, options: StaticOptions = StaticOptions(), *, shaft_mesh=None,
                cache_dir=None) -> StaticModel:
    """Mesh (or take ``shaft_mesh``), assemble K, couple the bearings, build the loads."""
    _check_options(options)
    if options.seed_load_case:
        variant = variant.with_seed_load_case()
    validate_variant(variant, springs=not options.rigid_supports)
    if shaft_mesh is None:
        from shaftfe.beam.planes import mesh_hot_axes
        from shaftfe.solid.mesh import build_mesh
        shaft_mesh = build_mesh(variant, options.level, options.order, cache_dir=cache_dir,
                                hot_axes=mesh_hot_axes(variant))
    m = shaft_mesh.mesh
    mat = variant.material
    t0 = time.perf_counter()
    K = reuse.memo("K", (reuse.mesh_digest(m), mat.E_MPa, mat.nu),
                   lambda: fem.elasticity_stiffness(m, mat.E_MPa, mat.nu))
    couplings = []
    for b in variant.bearings:
        hold = options.hold_twist == "all" or (options.hold_twist == "axial" and b.axial)
        couplings.append(supports.couple_bearing(m, b, rigid=options.rigid_supports,
                                                 hold_twist=hold))
    blocks = tuple(blk for c in couplings for blk in supports.blocks(c))
    loads, forces = {}, {}
    face_cache: dict = {}          # facet bases shared by parts on the same seat
    for a in variant.attachments:
        F = a.force_N(REF_RPM)
        if F == 0:
            continue
        e = _direction(a.angle_deg)
        loads[a.name] = fem.surface_load(m, m.boundaries[f"load:{a.name}:pressed"], F, e,
                                         options.load_distribution, cache=face_cache)
        forces[a.name] = tuple(float(c) for c in F * e)
    if options.body_force:
        w2 = omega(REF_RPM) ** 2
        fb = fem.body_force_load(m, mat.density_t_mm3, w2)
        loads["shaft_body"] = fb
        forces["shaft_body"] = tuple(float(c) for c in fb.reshape(-1, 3).sum(axis=0))
    f = np.zeros(K.shape[0])
    for v in loads.values():
        f += v
    soft = spin_seats(variant, m) if options.spin_softening else ()
    return StaticModel(variant, shaft_mesh, options, K, tuple(couplings), blocks, loads,
                       forces, f, time.perf_counter() - t0, soft)


def region_facets(mesh) -> dict[str, np.ndarray]:
    """Stress regions: each fillet, keyway, shoulder and seat (a split load seat counted once),
    the hex socket and the end faces."""
    groups: dict[str, list] = {}
    for g, f in mesh.boundaries.items():
        if g.startswith("load:"):
            name = "seat:" + g.split(":")[1]
        elif g.startswith("bearing:"):
            name = "seat:" + g
        else:
            name = g
        groups.setdefault(name, []).append(np.asarray(f))
    return {k: np.concatenate(v) for k, v in groups.items()}


def region_nodes(mesh) -> dict[str, np.ndarray]:
    """Region name -> node ids (of ``region_facets``), sorted by name: the regions whose peaks
    ``shaftfe static`` reports and ``shaftfe fatigue`` uses for its hot spots."""
    return {k: fem.face_nodes(mesh, f).astype(np.int64)
            for k, f in sorted(region_facets(mesh).items())}


def _patches(mesh) -> list[np.ndarray]:
    return [np.asarray(f) for g, f in mesh.boundaries.items()
            if g.startswith("bearing:") or g.endswith(":pressed")]


