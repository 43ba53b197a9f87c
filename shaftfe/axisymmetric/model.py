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

Spin softening (``AxiOptions.spin_softening``, on by default as in 3D): the co-rotating model
of ``shaftfe.model.spin``, in harmonic n = 1 (both parts): each part's mass at its centroid
(the seat's RBE3 rows u_y + d θ_z, a negative spring −m ω²), its tilt matrix on the seat's θ
rows (I_d − I_p and the eccentric centroid's m e² about the axis ⊥ e, which couples the two
parts), and the shaft's own transverse mass by its Ritz projection on Legendre polynomials in
x (``static.model.legendre_ritz``, as in 3D). The response is then not ∝ ω²: a solve serves
one speed only.

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

from shaftfe.axisymmetric import harmonic as hm
from shaftfe.axisymmetric import kernels as kn
from shaftfe.axisymmetric import recovery as rc
from shaftfe.axisymmetric.mesh import (
    AxiLevel,
    axi_level,
    mesh_geometry,
    shaft_geometry,
)
from shaftfe.errors import InputError, SolverError
from shaftfe.fe.recovery import von_mises
from shaftfe.fe.supports import HOLD_TWIST
from shaftfe.model.validate import validate_variant
from shaftfe.solid.plan import cut_features
from shaftfe.static.model import DISTRIBUTIONS, load_case_label
from shaftfe.util.units import REF_RPM, omega

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
    # the truncation criterion's fillets: False = those outside the zones of the features the
    # outline leaves out (their peaks are not valid anyway; "use the 3D path there"),
    # True = every fillet (up to n ≈ 23 on x2_57 instead of n = 3)
    converge_all_fillets: bool = False
    # the attachments' m ω² u in the co-rotating frame (see the module docstring); a solve
    # then serves one speed
    spin_softening: bool = True            # the parts' m ω² u (module docstring)
    n_max: int = N_MAX
    exclude_mm: float = 0.0

    @property
    def load_case(self) -> str:
        return load_case_label(self.seed_load_case)

    @property
    def level_name(self) -> str:
        return self.level if isinstance(self.level, str) else self.level.name


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
    force_N: float          # at the solve's speed
    p0_MPa: float


@dataclass(frozen=True, eq=False)
class HarmonicField:
    """The solution of harmonic n: dof amplitudes of the symmetric and antisymmetric parts."""
    n: int
    sym: np.ndarray = field(repr=False)
    anti: np.ndarray | None = field(repr=False)


@dataclass(frozen=True, eq=False)
class AxiSolution:
    """The solved model at ``rpm`` (REF_RPM unless spin softening asks for another speed;
    frozen, arrays read-only by convention)."""
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
    truncation_fillets: tuple          # the fillets the truncation criterion follows
    seconds: dict                      # timings, mesh_from_cache, largest relative_residual
    rpm: float = REF_RPM               # the speed of the loads (and of the spin softening)
    attachment_motion: dict = field(default_factory=dict)   # name -> (q_y, q_z) mm, when
    softening_N_per_mm: dict = field(default_factory=dict)  # spin softening: name -> m ω²


def pressure_loads(variant, sol, distribution: str, rpm: float = REF_RPM) -> list[SeatLoad]:
    """Each loaded attachment's half-seat pressure at ``rpm`` on its seat of the plan ``sol``."""
    seats = {s.name: s for s in sol.seats}
    out = []
    per = kn.force_per_p0(distribution)
    for a in variant.attachments:
        F = a.force_N(rpm)
        if F == 0:
            continue
        st = seats[f"load:{a.name}"]
        p0 = F / (per * st.part.r * (st.x1 - st.x0))
        out.append(SeatLoad(a.name, st.name, float(a.angle_deg), float(F), float(p0)))
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


def solve_model(variant, options: AxiOptions = AxiOptions(), *, rpm: float = REF_RPM,
                cache_dir=None) -> AxiSolution:
    """Mesh, assemble and solve every harmonic the loads at ``rpm`` need (see the module
    docstring)."""
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
    h = hm.assemble(mesh, E, nu, cache_dir=cache_dir)
    loads = pressure_loads(variant, plan, options.load_distribution, rpm)
    omega2 = omega(rpm) ** 2
    soft, centroid = _softening(h, mesh, variant, omega2) if options.spin_softening else ([],
                                                                                        [])
    coeffs = kn.half_pressure_coefficients(options.load_distribution, options.n_max)
    S = rc.Surface(mesh)
    bearings = [(b.name, hm.rbe3(h, mesh.group_edges(f"bearing:{b.name}"), b.x_center_mm), b)
                for b in variant.bearings]
    t_asm = time.perf_counter() - t0 - t_mesh

    fields, stresses = [], []
    # n = 0: axisymmetric part of the pressures; u_x and θ_x held at the bearings
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
    from concurrent.futures import ThreadPoolExecutor
    pool = ThreadPoolExecutor(2)              # two harmonics at a time (SuperLU frees the GIL)
    try:
        p0, p1 = (_pressure_parts(h, mesh, loads, coeffs, n) for n in (0, 1))
        job0 = pool.submit(hm.solve, h.K(0), p0[0], h.reduction(0), hard=np.array(hard))
        job1 = pool.submit(_solve_n1, h, bearings, p1[0], p1[1], options.rigid_supports,
                           soft)
        sol0, (us, ua, reac1, res1) = job0.result(), job1.result()
        relres = [sol0.relres, res1]
        fields.append(HarmonicField(0, sol0.u[:, 0], None))
        stresses.append((0, S.stress(sol0.u[:, 0], 0, E, nu, _sigma_n(S, mesh, p0[2])), None))
        reac = {name: np.zeros(5) for name, _, _ in bearings}
        for (name, lab), lam in zip(hard_lab, sol0.multipliers[:, 0], strict=True):
            if lab == "u_x":
                reac[name][0] = -lam
        fields.append(HarmonicField(1, us, ua))
        stresses.append((1, S.stress(us, 1, E, nu, _sigma_n(S, mesh, p1[2])),
                         S.stress(ua, 1, E, nu, _sigma_n(S, mesh, p1[3]))))
        for name, r in reac1.items():
            reac[name][1:5] = r

        # n ≥ 2: the half-seat pressure patches, until no fillet's peak changes any more
        zones = [] if options.converge_all_fillets else \
            [f["zone_mm"] for f in cut_features(plan)]
        track = _PeakTracker(S, mesh, zones)
        track.add(stresses)
        last: list[float] = []
        n_used, change = 1, 0.0
        todo = [n for n in range(2, options.n_max + 1) if coeffs[n] != 0.0] if loads else []
        done = False
        for k in range(0, len(todo), 2):
            batch = todo[k:k + 2]
            rhs = [_pressure_parts(h, mesh, loads, coeffs, n) for n in batch]
            sols = list(pool.map(lambda a: hm.solve(h.K(a[0]), np.column_stack(a[1][:2]),
                                                    h.reduction(a[0])),
                                 zip(batch, rhs, strict=True)))
            for n, (_, _, sn_s, sn_a), sol in zip(batch, rhs, sols, strict=True):
                relres.append(sol.relres)
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
    finally:
        pool.shutdown()
    if not done:
        if todo and max(last, default=0.0) >= options.truncation:
            raise SolverError(f"the harmonic series did not converge to {options.truncation:g} "
                              f"by n = {options.n_max} (last change {change:.2e}); raise n_max")
    t_all = time.perf_counter() - t0
    secs = {"mesh_seconds": t_mesh, "assembly_seconds": t_asm,
            "solve_seconds": t_all - t_mesh - t_asm, "total_seconds": t_all,
            "mesh_from_cache": mesh.from_cache, "relative_residual": max(relres)}
    motion = {name: (float(row @ us), float(row @ ua)) for name, row, _ in centroid}
    return AxiSolution(variant, options, plan, mesh, tuple(fields), tuple(loads), tuple(bearings),
                       {k: tuple(float(c) for c in v) for k, v in reac.items()}, S,
                       tuple(stresses), n_used, change, track.names, secs, float(rpm), motion,
                       {name: float(k) for name, _, k in centroid})


def _softening(h, mesh, variant, omega2: float):
    """(rows with their (symmetric, antisymmetric) 2×2 stiffness blocks, (name, row, k) whose
    motion × k is the softening force: each part's centroid, and the shaft's mass-weighted mean
    motion × its m ω²) of the co-rotating softening at ω² (module docstring). A seat's tilt
    row ``tz`` reads (θ_z, −θ_y) on the two parts: the tilt matrix T on (θ_y, θ_z) acts there
    as P T Pᵀ, P = [[0, 1], [−1, 0]]."""
    from shaftfe.model.spin import spinning_parts
    from shaftfe.static.model import legendre_ritz
    P = np.array([[0.0, 1.0], [-1.0, 0.0]])
    soft, centroid = [], []
    for p in spinning_parts(variant):
        rb = hm.rbe3(h, mesh.group_edges(f"load:{p.name}"), p.x_seat_mm)
        row = rb.uy + p.d_mm * rb.tz
        soft.append((row, -p.mass_t * omega2 * np.eye(2)))
        soft.append((rb.tz, -omega2 * (P @ p.tilt @ P.T)))
        centroid.append((p.name, row, p.mass_t * omega2))        # t/s² = N/mm
    rho = float(variant.material.density_t_mm3)
    if rho > 0:
        # the 3D mass of the symmetric part, ∫ ρ |u|² dV = ρ π ∫ (U_x² + U_r² + U_θ²) r dr dx; a
        # lateral field u_y = h(x) is U_r = h, U_θ = −h: rows ρ π Ms h on U_r and −ρ π Ms h on
        # U_θ, Gram 2 ρ π hᵀ Ms h (Ms the r-weighted scalar mass of the meridian mesh)
        Ms = _meridian_mass(mesh)
        Bs = legendre_ritz(2.0 * math.pi * rho * Ms, mesh.xr[0])
        B = np.zeros((Bs.shape[0], h.ndof))
        B[:, 1::3], B[:, 2::3] = 0.5 * Bs, -0.5 * Bs
        soft += [(b, -omega2 * np.eye(2)) for b in B]
        m_shaft = 2.0 * math.pi * rho * float(Ms.sum())
        e_y = np.zeros(h.ndof)
        e_y[1::3], e_y[2::3] = 1.0, -1.0
        mean = (B.T @ (B @ e_y)) / m_shaft                     # mass-weighted mean u_y row
        centroid.append(("shaft", mean, m_shaft * omega2))
    return soft, centroid


def _meridian_mass(mesh):
    """∫ N_a N_b r dr dx of the meridian mesh's P2 triangles (sparse N × N)."""
    import scipy.sparse as sp
    pts, w = kn.triangle_rule(4)
    X, R = mesh.xr[0][mesh.tri].T, mesh.xr[1][mesh.tri].T
    _, r, det, N, _, _ = kn.element_geometry(X, R, pts)
    Me = np.einsum("aq,bq,eq->eab", N, N, det * r * w[None])
    rows = np.repeat(mesh.tri.T, 6, axis=1).ravel()
    cols = np.tile(mesh.tri.T, (1, 6)).ravel()
    return sp.csr_matrix((Me.ravel(), (rows, cols)), shape=(mesh.n_nodes,) * 2)


def _solve_n1(h, bearings, fs, fa, rigid: bool, soft=()):
    """Harmonic n = 1, both parts, with ONE factorisation for both.

    Springs: the bearings' 2×2 springs C couple the symmetric (y) and antisymmetric (z) parts.
    With c̄ = (C11 + C22)/2 per bearing, K̃ = K1 + Σ c̄ uyᵀuy (+ the tilt springs, the same in
    both parts) is factorised, and the rest, ΔC = C − c̄ I, is a rank-2-per-bearing term
    U ΔC Uᵀ solved by the Woodbury identity: x = x0 − A0⁻¹U (I + ΔC UᵀA0⁻¹U)⁻¹ ΔC Uᵀ x0.
    Rigid supports: the remote points' u_y held in both parts by multipliers instead.
    ``soft``: (row, 2×2 block on its symmetric and antisymmetric values) of the co-rotating
    softening (``_softening``: negative, or for a disk-like tilt positive, springs) in the same
    low-rank term. The softened system is positive definite exactly when every
    eigenvalue of I + D UᵀA0⁻¹U is positive (A0 and UᵀA0⁻¹U are; determinant lemma): else the
    speed is at or above a critical speed of the softened rotor and a SolverError says so.

    Returns (U_sym, U_anti, {bearing: (F_y, F_z, q_y, q_z)}, the largest backward error of the
    coupled system, ``harmonic.backward_error``)."""
    K1, T1 = h.K(1), h.reduction(1)
    tilt = [(rb.tz[None], np.array([[float(b.tilt_stiffness_Nmm_per_rad)]]))
            for _, rb, b in bearings if float(b.tilt_stiffness_Nmm_per_rad) > 0]
    uy = np.array([rb.uy for _, rb, _ in bearings])                       # (nb, ndof)
    C = [np.asarray(b.K_N_per_mm, dtype=float).reshape(2, 2) for _, _, b in bearings]
    if rigid:
        base, hard, rows, blocks = tilt, uy, [], []
    else:
        cbar = [0.5 * (c[0, 0] + c[1, 1]) for c in C]
        base = [(uy[[k]], np.array([[cbar[k]]])) for k in range(len(C))] + tilt
        hard, rows = None, list(uy)
        blocks = [c - cb * np.eye(2) for c, cb in zip(C, cbar, strict=True)]
    rows += [row for row, _ in soft]
    blocks += [blk for _, blk in soft]
    m = len(blocks)
    rows = np.array(rows).reshape(m, h.ndof)
    sol = hm.solve(K1, np.column_stack([fs, fa, *rows]), T1, springs=base, hard=hard)
    x0s, x0a, Z = sol.u[:, 0], sol.u[:, 1], sol.u[:, 2:]
    mu = sol.multipliers                                       # (n_hard, 2 + m)
    y = np.zeros(2 * m)
    if m:
        G = rows @ Z                                                          # (m, m)
        D = np.zeros((2 * m, 2 * m))
        for k, c in enumerate(blocks):
            D[np.ix_([k, m + k], [k, m + k])] = c
        GG = np.zeros((2 * m, 2 * m))
        GG[:m, :m] = GG[m:, m:] = G
        M = np.eye(2 * m) + D @ GG
        if soft and np.linalg.eigvals(M).real.min() <= 0:
            raise SolverError("spin softening: the speed is at or above a critical speed of "
                              "the softened rotor (the parts' m ω² exceeds what the shaft and "
                              "bearings hold); the static co-rotating solution is not stable")
        y = np.linalg.solve(M, D @ np.concatenate([rows @ x0s, rows @ x0a]))
    us, ua = x0s - Z @ y[:m], x0a - Z @ y[m:]
    # the residual of the coupled system with the factorised matrix of ``hm.solve``:
    # M [x̂; λ] + [Tᵀ (low-rank term); 0] − [Tᵀ f; 0]
    Msys, n_u = sol.matrix, T1.shape[1]
    w = np.asarray(T1.multiply(T1).sum(axis=0)).ravel()        # 1, or 2 on the axis (U_θ = −U_r)
    qs, qa = rows @ us, rows @ ua
    rel, mult = 0.0, []
    for x, f, part in ((us, fs, 0), (ua, fa, 1)):
        extra = np.zeros(h.ndof)
        for k, c in enumerate(blocks):
            extra += (c @ np.array([qs[k], qa[k]]))[part] * rows[k]
        lam = np.zeros(0)
        if hard is not None:
            lam = mu[:, part] - mu[:, 2:] @ y[part * m:(part + 1) * m]
            mult.append(lam)
        z = np.concatenate([(T1.T @ x) / w, lam])
        b = np.concatenate([T1.T @ f, np.zeros(lam.size)])
        r = Msys @ z + np.concatenate([T1.T @ extra, np.zeros(lam.size)]) - b
        rel = max(rel, hm.backward_error(Msys, z, b, r, n_u))
    if not np.all(np.isfinite(us)) or not np.all(np.isfinite(ua)) or rel > 1e-9:
        raise SolverError(f"the n = 1 harmonic solve did not converge (backward error "
                          f"{rel:.2e})")
    reac = {}
    for k, (name, _, _) in enumerate(bearings):
        if rigid:
            reac[name] = (-mult[0][k], -mult[1][k], 0.0, 0.0)
        else:
            q = np.array([qs[k], qa[k]])          # the bearings' rows come first
            F = -C[k] @ q
            reac[name] = (F[0], F[1], q[0], q[1])
    return us, ua, reac, max(rel, sol.relres)


class _PeakTracker:
    """Running θ-synthesis (1° grid) of the surface stress on the fillets outside ``zones``
    (x intervals in mm; every fillet when none is outside); ``add`` returns the largest change
    of such a fillet's peak von Mises stress relative to the largest of their peaks."""

    def __init__(self, surface, mesh, zones=()):
        ids = {}
        for i, c in enumerate(mesh.geometry.curves):
            for g in c.groups:
                if g.startswith("fillet:"):
                    ids.setdefault(g, []).append(i)
        sets = {g: np.nonzero(np.isin(surface.curve, v) & ~surface.kink)[0]
                for g, v in ids.items()}
        x = mesh.xr[0][surface.nodes]

        def clear(nodes) -> bool:
            return not any(((lo <= x[nodes]) & (x[nodes] <= hi)).any() for lo, hi in zones)
        keep = ([g for g, nd in sets.items() if nd.size and clear(nd)]
                or [g for g, nd in sets.items() if nd.size])
        self.names = tuple(keep)
        self.sets = [sets[g] for g in keep]
        self.idx = np.concatenate(self.sets) if self.sets else np.zeros(0, dtype=np.int64)
        self.theta = rc.theta_grid()
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
