"""The shaft as a body of revolution under its real loads: options, loads in harmonics, the
bearings' remote points, and the solve of every harmonic needed.

Loads (the 3D model's, ``static.model``): each attachment's m e ω² at REF_RPM as a pressure on
the half of its seat opposite its direction (ψ = θ − (angle + 180°), |ψ| < 90°), uniform or
cosine in ψ, p0 from the net force: F = p0 R L · π a_1 (``kernels.force_per_p0``). Its Fourier
series p(ψ) = p0 Σ a_n cos nψ splits into the symmetric (cos nθ) and antisymmetric (sin nθ)
parts of harmonic n with the factors cos n(angle + π) and sin n(angle + π). Harmonic n = 1
carries the whole net force; n = 0 and n ≥ 2 are self-equilibrated.

Bearings (``fe.supports``): the RBE3 remote point at the seat-band centre, radial 2×2 spring
(K11, K12, K21, K22) on (u_y, u_z), i.e. on the symmetric and antisymmetric n = 1 parts, which
it couples through K12/K21; tilt spring if given; u_x held at the axial bearing and θ_x at the
bearings of ``hold_twist`` (n = 0); ``rigid_supports``: u_y = u_z = 0 at the remote points.

Truncation (``AxiOptions.truncation``): harmonics are added in order until the two last loaded
ones each change the stress on every fillet and shoulder by less than ``truncation`` × the
largest von Mises stress there (at most ``n_max``). Their series decays geometrically with n
away from a seat (a harmonic n decays over about R/n from its load), so the neglected
remainder is of the size of the last term.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from shaftfe.axisymmetric import harmonic as hm
from shaftfe.axisymmetric import kernels as kn
from shaftfe.axisymmetric import recovery as rc
from shaftfe.axisymmetric.mesh import AxiLevel, axi_level, mesh_geometry, shaft_geometry
from shaftfe.errors import InputError, SolverError
from shaftfe.fe.recovery import von_mises
from shaftfe.fe.supports import HOLD_TWIST
from shaftfe.model.validate import validate_variant
from shaftfe.static.model import DISTRIBUTIONS, REF_RPM, load_case_label

N_MAX = 199


@dataclass(frozen=True)
class AxiOptions:
    level: str | AxiLevel = "default"      # a name of axisymmetric.mesh.AXI_LEVELS or a value
    refine: int = 0                          # uniform refinements of that mesh
    rigid_supports: bool = False
    load_distribution: str = "uniform"       # "uniform" | "cosine"
    seed_load_case: bool = False
    hold_twist: str = "all"
    truncation: float = 1e-4                 # relative stress change of the last harmonics
    n_max: int = N_MAX
    exclude_mm: float = 0.0

    @property
    def load_case(self) -> str:
        return load_case_label(self.seed_load_case)


def check_options(o: AxiOptions) -> None:
    axi_level(o.level)
    if o.load_distribution not in DISTRIBUTIONS:
        raise InputError("--load-distribution", "load_distribution", " | ".join(DISTRIBUTIONS),
                         got=o.load_distribution)
    if o.hold_twist not in HOLD_TWIST:
        raise InputError("options", "hold_twist", " | ".join(HOLD_TWIST), got=o.hold_twist)
    if not (isinstance(o.n_max, int) and 1 <= o.n_max <= 999):
        raise InputError("options", "n_max", "1 ... 999", got=o.n_max)
    if not (math.isfinite(o.truncation) and 0 < o.truncation < 1):
        raise InputError("options", "truncation", "0 < truncation < 1", got=o.truncation)
    if not (math.isfinite(o.exclude_mm) and o.exclude_mm >= 0):
        raise InputError("--exclude-mm", "exclude_mm", ">= 0", got=o.exclude_mm)


@dataclass(frozen=True)
class SeatLoad:
    name: str
    group: str
    angle_deg: float
    force_N: float          # at REF_RPM
    p0_MPa: float
    radius_mm: float


@dataclass(frozen=True, eq=False)
class HarmonicField:
    """The solution of harmonic n: dof amplitudes of the symmetric and antisymmetric parts."""
    n: int
    sym: np.ndarray = field(repr=False)
    anti: np.ndarray | None = field(repr=False)


@dataclass(frozen=True, eq=False)
class AxiSolution:
    """The solved model at REF_RPM (frozen; arrays read-only by convention)."""
    variant: object
    options: AxiOptions
    plan: object                       # solid.plan.Solid
    mesh: object
    harmonics: tuple[HarmonicField, ...]
    loads: tuple[SeatLoad, ...]
    bearings: tuple                    # (name, Rbe3, Bearing)
    reactions: dict                    # name -> (Fx, Fy, Fz, qy, qz) on the shaft at REF_RPM
    surface: object                    # recovery.Surface
    surface_stress: tuple              # (n, sym (6, k), anti (6, k) | None) per harmonic
    n_used: int
    truncation_change: float           # the last loaded harmonic's change, relative
    seconds: dict


def pressure_loads(variant, sol, distribution: str) -> list[SeatLoad]:
    """Each loaded attachment's half-seat pressure at REF_RPM on its seat of the plan ``sol``."""
    seats = {s.name: s for s in sol.seats}
    out = []
    per = kn.force_per_p0(distribution)
    for a in variant.attachments:
        F = a.force_N(REF_RPM)
        if F == 0:
            continue
        st = seats[f"load:{a.name}"]
        p0 = F / (per * st.part.r * (st.x1 - st.x0))
        out.append(SeatLoad(a.name, st.name, float(a.angle_deg), float(F), float(p0),
                            float(st.part.r)))
    return out


def _pressure_parts(h, mesh, loads, coeffs, n: int):
    """Load vectors (symmetric, antisymmetric) of harmonic n and the normal-traction
    amplitudes σ_nn at the surface nodes (for the surface recovery)."""
    fs, fa = np.zeros(h.ndof), np.zeros(h.ndof)
    sn_s, sn_a = {}, {}
    for ld in loads:
        an = coeffs[n]
        if an == 0.0:
            continue
        phi = math.radians(ld.angle_deg) + math.pi
        edges = mesh.group_edges(ld.group)
        amp = -ld.p0_MPa * an
        cs, sa = amp * math.cos(n * phi), amp * math.sin(n * phi)
        f = h.traction_vector(edges, lambda x, r: (0.0, 1.0, 0.0), n)
        fs += cs * f
        if n > 0:
            fa += sa * f
        sn_s[ld.group] = sn_s.get(ld.group, 0.0) + cs
        sn_a[ld.group] = sn_a.get(ld.group, 0.0) + (sa if n > 0 else 0.0)
    return fs, fa, sn_s, sn_a


def _sigma_n(surface, mesh, by_group: dict) -> np.ndarray:
    """Normal traction amplitude at the surface nodes: the seat's pressure amplitude on its
    nodes, half of it at the seat's end nodes (the pressure jumps there)."""
    out = np.zeros(surface.nodes.size)
    for g, val in by_group.items():
        ids = [i for i, c in enumerate(mesh.geometry.curves) if g in c.groups]
        on = np.isin(surface.curve, ids).astype(float)
        x = mesh.xr[0][surface.nodes]
        c = [mesh.geometry.curves[i] for i in ids]
        ends = np.zeros(surface.nodes.size, dtype=bool)
        for cc in c:
            for p in (cc.start, cc.end):
                ends |= np.isclose(x, p[0], atol=1e-9) & np.isclose(
                    mesh.xr[1][surface.nodes], p[1], atol=1e-9)
        out += val * np.where(ends, 0.5, on)
    return out


def solve_model(variant, options: AxiOptions = AxiOptions(), *, cache_dir=None) -> AxiSolution:
    """Mesh, assemble and solve every harmonic the loads need (see the module docstring)."""
    t0 = time.perf_counter()
    check_options(options)
    if options.seed_load_case:
        variant = variant.with_seed_load_case()
    validate_variant(variant, springs=not options.rigid_supports)
    from shaftfe.solid.plan import prepare
    plan = prepare(variant)                      # the solid plan: outline, seats, omissions
    mesh = mesh_geometry(shaft_geometry(plan), options.level, options.refine,
                         cache_dir=cache_dir)
    t_mesh = time.perf_counter() - t0
    mat = variant.material
    E, nu = float(mat.E_MPa), float(mat.nu)
    h = hm.assemble(mesh, E, nu)
    loads = pressure_loads(variant, plan, options.load_distribution)
    coeffs = kn.half_pressure_coefficients(options.load_distribution, options.n_max)
    S = rc.Surface(mesh)
    bearings = [(b.name, hm.rbe3(h, mesh.group_edges(f"bearing:{b.name}"), b.x_center_mm), b)
                for b in variant.bearings]
    t_asm = time.perf_counter() - t0 - t_mesh

    fields, stresses = [], []
    # n = 0: axisymmetric part of the pressures; u_x and θ_x held at the bearings
    fs, _, sn_s, _ = _pressure_parts(h, mesh, loads, coeffs, 0)
    hard, hard_lab = [], []
    for name, rb, b in bearings:
        if b.axial:
            hard.append(rb.ux)
            hard_lab.append((name, "u_x"))
        hold = options.hold_twist == "all" or (options.hold_twist == "axial" and b.axial)
        if hold:
            hard.append(rb.tx)
            hard_lab.append((name, "θ_x"))
    if not any(lab == "u_x" for _, lab in hard_lab):
        raise SolverError("the supports leave the shaft free to move: axial translation u_x "
                          "(mark one bearing with axial = true)")
    sol0 = hm.solve(h.K(0), fs, h.reduction(0), hard=np.array(hard))
    fields.append(HarmonicField(0, sol0.u[:, 0], None))
    stresses.append((0, S.stress(sol0.u[:, 0], 0, E, nu, _sigma_n(S, mesh, sn_s)), None))
    reac = {name: np.zeros(5) for name, _, _ in bearings}
    for (name, lab), lam in zip(hard_lab, sol0.multipliers[:, 0], strict=True):
        if lab == "u_x":
            reac[name][0] = -lam

    # n = 1: symmetric and antisymmetric parts coupled by the bearing springs
    fs, fa, sn_s, sn_a = _pressure_parts(h, mesh, loads, coeffs, 1)
    K1, T1 = h.K(1), h.reduction(1)
    K = sp.block_diag([K1, K1], format="csr")
    T = sp.block_diag([T1, T1], format="csr")
    z = np.zeros(h.ndof)
    springs, hard1 = [], []
    for _, rb, b in bearings:
        R = np.array([np.concatenate([rb.uy, z]), np.concatenate([z, rb.uy])])
        if options.rigid_supports:
            hard1 += list(R)
        else:
            springs.append((R, np.asarray(b.K_N_per_mm, dtype=float).reshape(2, 2)))
        tk = float(b.tilt_stiffness_Nmm_per_rad)
        if tk > 0:
            Rt = np.array([np.concatenate([rb.tz, z]), np.concatenate([z, -rb.tz])])
            springs.append((Rt, tk * np.eye(2)))
    sol1 = hm.solve(K, np.concatenate([fs, fa]), T, springs=springs,
                    hard=np.array(hard1) if hard1 else None)
    u1 = sol1.u[:, 0]
    us, ua = u1[:h.ndof], u1[h.ndof:]
    fields.append(HarmonicField(1, us, ua))
    stresses.append((1, S.stress(us, 1, E, nu, _sigma_n(S, mesh, sn_s)),
                     S.stress(ua, 1, E, nu, _sigma_n(S, mesh, sn_a))))
    for k, (name, rb, b) in enumerate(bearings):
        q = np.array([rb.uy @ us, rb.uy @ ua])
        if options.rigid_supports:
            F = -sol1.multipliers[2 * k:2 * k + 2, 0]
        else:
            F = -np.asarray(b.K_N_per_mm, dtype=float).reshape(2, 2) @ q
        reac[name][1:3] = F
        reac[name][3:5] = q

    # n ≥ 2: the half-seat pressure patches, until no fillet's peak changes any more
    track = _PeakTracker(S, mesh)
    track.add(stresses)
    last: list[float] = []
    n_used, change = 1, 0.0
    todo = [n for n in range(2, options.n_max + 1) if coeffs[n] != 0.0] if loads else []
    done = False
    from concurrent.futures import ThreadPoolExecutor
    with ThreadPoolExecutor(2) as pool:       # two harmonics at a time (SuperLU frees the GIL)
        for k in range(0, len(todo), 2):
            batch = todo[k:k + 2]
            rhs = [_pressure_parts(h, mesh, loads, coeffs, n) for n in batch]
            sols = list(pool.map(lambda a: hm.solve(h.K(a[0]), np.column_stack(a[1][:2]),
                                                    h.reduction(a[0])),
                                 zip(batch, rhs, strict=True)))
            for n, (_, _, sn_s, sn_a), sol in zip(batch, rhs, sols, strict=True):
                fields.append(HarmonicField(n, sol.u[:, 0], sol.u[:, 1]))
                ss = S.stress(sol.u[:, 0], n, E, nu, _sigma_n(S, mesh, sn_s))
                sa = S.stress(sol.u[:, 1], n, E, nu, _sigma_n(S, mesh, sn_a))
                stresses.append((n, ss, sa))
                n_used = n
                change = track.add([(n, ss, sa)])
                last = ([*last, change])[-2:]
                if len(last) == 2 and max(last) < options.truncation:
                    done = True
                    break
            if done:
                break
    if not done:
        if todo and max(last, default=0.0) >= options.truncation:
            raise SolverError(f"the harmonic series did not converge to {options.truncation:g} "
                              f"by n = {options.n_max} (last change {change:.2e}); raise n_max")
    t_all = time.perf_counter() - t0
    secs = {"mesh_seconds": t_mesh, "assembly_seconds": t_asm,
            "solve_seconds": t_all - t_mesh - t_asm, "total_seconds": t_all,
            "mesh_from_cache": mesh.from_cache}
    return AxiSolution(variant, options, plan, mesh, tuple(fields), tuple(loads), tuple(bearings),
                       {k: tuple(float(c) for c in v) for k, v in reac.items()}, S,
                       tuple(stresses), n_used, change, secs)


class _PeakTracker:
    """Running θ-synthesis (1° grid) of the surface stress on every fillet; ``add`` returns the
    largest change of a fillet's peak von Mises stress relative to the largest fillet peak."""

    def __init__(self, surface, mesh):
        ids = {}
        for i, c in enumerate(mesh.geometry.curves):
            for g in c.groups:
                if g.startswith("fillet:"):
                    ids.setdefault(g, []).append(i)
        self.sets = [np.nonzero(np.isin(surface.curve, v) & ~surface.kink)[0]
                     for v in ids.values()]
        self.idx = np.concatenate(self.sets) if self.sets else np.zeros(0, dtype=np.int64)
        self.theta = np.radians(np.arange(0.0, 360.0, 1.0))
        self.sum = np.zeros((6, self.idx.size, self.theta.size))
        self.peaks = np.zeros(len(self.sets))

    def add(self, parts) -> float:
        if self.idx.size == 0:
            return 0.0
        sub = [(n, s[:, self.idx], None if a is None else a[:, self.idx]) for n, s, a in parts]
        self.sum += rc.synthesize(sub, self.theta, rc.LOCAL_SHEAR)
        vm = von_mises(self.sum).max(axis=1)
        new, k = [], 0
        for st in self.sets:
            new.append(float(vm[k:k + st.size].max()))
            k += st.size
        new = np.array(new)
        top = float(new.max())
        change = float(np.abs(new - self.peaks).max() / top) if top > 0 else 0.0
        self.peaks = new
        return change
