"""The shaft as a body of revolution under its real loads: options, loads in harmonics, the
bearings' remote points, and the solve of every harmonic needed.

Loads (``model.loads.actions``: every load of the variant as a force and moment about an
axis point, delivered through a surface band):

* a remote load (the default for every action): the band's RBE3 rows (``harmonic.rbe3``, the
  area-weighted least-squares rigid motion of the band) transposed times [F; M]
  (``Rbe3.load``), so F and M are carried exactly and the band stays free to deform (Ansys'
  deformable Remote Force). On a surface of revolution the six rigid modes live in n = 0
  (u_x: an axial force; θ_x: a torque, the kernels' U_θ part of n = 0) and n = 1 (u_y, θ_z in
  the symmetric part; u_z, θ_y in the antisymmetric one): a remote load has no n ≥ 2 part. A
  part's m e ω² acts at its centroid, entering through its seat (group ``load:<part>``); a
  ``[[loads]]`` band that is not a part's seat splits the outline (group ``band:x0:x1``).
* the seed's placement (``seed_load_case``: actions with ``pressed_half``): each part's
  m e ω² as a pressure on the half of its seat opposite its direction (ψ = θ − (angle +
  180°), |ψ| < 90°), uniform or cosine in ψ, p0 from the net force: F = p0 R L · π a_1
  (``kernels.force_per_p0``). Its Fourier series p(ψ) = p0 Σ a_n cos nψ splits into the
  symmetric (cos nθ) and antisymmetric (sin nθ) parts of harmonic n with the factors
  cos n(angle + π) and sin n(angle + π); n = 1 carries the whole net force, n = 0 and n ≥ 2
  are self-equilibrated.
* gravity (``BodyAction``): the body force ρ a of the shaft's own mass (n = 0 for a_x, n = 1
  for a_y, a_z), the parts' weights as remote loads.

Components (``Component``): the actions of one speed-law pattern (``model.loads.pattern_key``)
and one load-case factor name are one right-hand side; every harmonic is factorised once for
all of them, and a speed or a load case is the columns × their factors (``superpose``).

Bearings (``fe.supports``): the RBE3 remote point at the seat-band centre, radial 2×2 spring
(K11, K12, K21, K22) on (u_y, u_z), i.e. on the symmetric and antisymmetric n = 1 parts, which
it couples through K12/K21; tilt spring if given; u_x held at the axial bearing; θ_x held only
at the bearings that hold torsion (``Bearing.holds_torsion``), else at the axial bearing as a
gauge whose reaction vanishes because the torques balance (``model.loads.check_torque_path``;
the solve reports it); ``rigid_supports``: u_y = u_z = 0 at the remote points.

Spin softening (``AxiOptions.spin_softening``, on by default as in 3D): the co-rotating model
of ``shaftfe.model.spin``, in harmonic n = 1 (both parts): each part's mass at its centroid
(the seat's RBE3 rows u_y + d θ_z, a negative spring −m ω²), its tilt matrix on the seat's θ
rows (I_d − I_p and the eccentric centroid's m e² about the axis ⊥ e, which couples the two
parts), and the shaft's own transverse mass by its Ritz projection on Legendre polynomials in
x (``static.model.legendre_ritz``, as in 3D). The response is then not ∝ ω²: a solve serves
one speed only.

Truncation (``AxiOptions.truncation``, the half-seat pressures only): harmonics are added in
order until the two last loaded
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
    BAND_PREFIX,
    AxiLevel,
    axi_level,
    mesh_geometry,
    shaft_geometry,
)
from shaftfe.errors import InputError, SolverError
from shaftfe.model.loads import actions, check_torque_path, law_factor, pattern_key
from shaftfe.model.spin import spinning_parts
from shaftfe.model.validate import validate_variant
from shaftfe.solid.features import (
    ROUND_NOTCH_KINDS,
    bearing_group,
    cuts,
    kind_of,
    seat_group,
)
from shaftfe.solid.plan import prepare
from shaftfe.static.model import DISTRIBUTIONS, legendre_ritz, load_case_label
from shaftfe.util.limits import check_exclude_mm
from shaftfe.util.units import REF_RPM, omega, von_mises

N_MAX = 199


@dataclass(frozen=True)
class AxiOptions:
    level: str | AxiLevel = "default"      # a name of axisymmetric.mesh.AXI_LEVELS or a value
    refine: int = 0                          # uniform refinements of that mesh
    rigid_supports: bool = False
    load_distribution: str = "uniform"       # "uniform" | "cosine"
    seed_load_case: bool = False
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
    if not (isinstance(o.n_max, int) and 1 <= o.n_max <= 999):
        raise InputError("options", "n_max", "1 ... 999", got=o.n_max)
    if not (math.isfinite(o.truncation) and 0 < o.truncation < 1):
        raise InputError("options", "truncation", "0 < truncation < 1", got=o.truncation)
    check_exclude_mm(o.exclude_mm, "--exclude-mm", "exclude_mm")   # ``util.limits``' rule


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
    columns: object = field(default=None, repr=False)    # ``Columns``: per component
    factors: tuple = ()                # the components' factors of these fields


def pressure_loads(variant, sol, distribution: str, rpm: float = REF_RPM) -> list[SeatLoad]:
    """Each loaded attachment's half-seat pressure at ``rpm`` on its seat of the plan ``sol``."""
    seats = {s.name: s for s in sol.seats}
    out = []
    per = kn.force_per_p0(distribution)
    for a in variant.attachments:
        F = a.force_N(rpm)
        if F == 0:
            continue
        st = seats[seat_group(a.name)]
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


@dataclass(frozen=True)
class Component:
    """One right-hand side: the actions of one speed-law pattern (``model.loads.pattern_key``)
    that one load-case factor scales (``factor_name``: a ``[[loads]]`` name, or "parts" for
    every part's m e ω²), at their written magnitudes (an rpm² load at its ``ref_rpm``). A
    case is Σ factor × component (``LoadCase.factor`` / ``law_factor``); a pattern whose loads
    a case scales alike is one component per load name, all from the same factorisation."""
    pattern: tuple
    factor_name: str
    scales_with: str
    ref_rpm: float
    channel_ref: float
    pressed_half: bool = False          # the seed's half-seat pressures (``pressure_loads``)

    @property
    def name(self) -> str:
        return self.factor_name

    def factor(self, rpm: float, case=None) -> float:
        """This component's factor at a plain speed ``rpm`` (rpm² loads × (rpm/ref)², constant
        × 1, a channel at its channel_ref), or in the load case ``case``."""
        if case is not None:
            return float(case.factor(self))
        return float(law_factor(self.scales_with, rpm, {}, ref_rpm=self.ref_rpm,
                                channel_ref=self.channel_ref))


@dataclass(frozen=True, eq=False)
class Columns:
    """The solution per component (one column each): ``harmonics`` (n, sym (ndof, c_n),
    anti (ndof, c_n) | None, the component index of each column), ``stress`` (n, sym (6, k,
    c_n), anti | None) on ``Surface`` nodes, ``reactions`` name -> (5, c) (Fx, Fy, Fz, q_y,
    q_z on the shaft), ``torsion`` name -> (c,) the θ_x reaction about +x (N·mm) of a bearing
    that holds the twist (or of the gauge), ``load_sum`` (3, c) the applied resultant,
    ``torque_sum`` (c,), ``load_scale`` (c,) Σ (|F| + |M| / L) of the actions (the force
    scale of an equilibrium check when the resultant vanishes: a torque, a couple), ``motion``
    part -> (2, c) the seats' (q_y, q_z) under softening."""
    components: tuple[Component, ...]
    harmonics: tuple
    stress: tuple
    reactions: dict
    torsion: dict
    load_sum: np.ndarray
    torque_sum: np.ndarray
    load_scale: np.ndarray
    motion: dict
    gauge: str | None                   # the bearing whose θ_x row is only a gauge

    def factors(self, rpm: float, case=None) -> np.ndarray:
        return np.array([c.factor(rpm, case) for c in self.components])


def _components(acts, body, pressed: bool) -> list[Component]:
    comps: dict[tuple, Component] = {}
    if pressed:
        comps[(("rpm2", REF_RPM), "parts", True)] = Component(
            ("rpm2", REF_RPM), "parts", "rpm2", REF_RPM, 1.0, True)
    for a in (*acts, *body):
        if getattr(a, "pressed_half", False):
            continue
        nm = getattr(a, "factor_name", a.name)
        k = (pattern_key(a), nm, False)
        comps.setdefault(k, Component(pattern_key(a), nm, a.scales_with, float(a.ref_rpm),
                                      float(a.channel_ref)))
    return list(comps.values())


def _band_group(a, plan) -> str:
    """The mesh group a remote action is delivered through: its part's seat, else its band."""
    seats = {st.name: st for st in plan.seats}
    st = seats.get(seat_group(a.seat))
    if st is not None and np.allclose((st.x0, st.x1), a.band_mm, atol=1e-6):
        return st.name
    return f"{BAND_PREFIX}{a.band_mm[0]:.6g}:{a.band_mm[1]:.6g}"


def load_bands(variant, plan, seed_placement: bool) -> tuple:
    """(group, x0, x1) of every remote action's band that is not a part's seat (for
    ``mesh.shaft_geometry``)."""
    acts, _ = actions(variant, seed_placement=seed_placement)
    out = {}
    for a in acts:
        if a.pressed_half:
            continue
        g = _band_group(a, plan)
        if g.startswith(BAND_PREFIX):
            out[g] = (g, float(a.band_mm[0]), float(a.band_mm[1]))
    return tuple(out.values())


def _right_hand_sides(h, mesh, plan, variant, comps, acts, body, pressure, coeffs):
    """(f0 (ndof, c), f1s, f1a, load_sum (3, c), torque_sum (c,), load_scale (c,), the
    pressure's σ_nn amplitudes per part (n = 0, n = 1 sym, n = 1 anti) for the pressed
    column)."""
    c = len(comps)
    index = {(co.pattern, co.factor_name, co.pressed_half): i for i, co in enumerate(comps)}
    f0, f1s, f1a = (np.zeros((h.ndof, c)) for _ in range(3))
    load_sum, torque_sum, scale = np.zeros((3, c)), np.zeros(c), np.zeros(c)
    length = float(plan.length)
    sn = ({}, {}, {})
    if pressure:
        j = index[(("rpm2", REF_RPM), "parts", True)]
        p0, p1 = (_pressure_parts(h, mesh, pressure, coeffs, n) for n in (0, 1))
        f0[:, j], f1s[:, j], f1a[:, j] = p0[0], p1[0], p1[1]
        sn = (p0[2], p1[2], p1[3])
        for ld in pressure:
            a = math.radians(ld.angle_deg)
            load_sum[:, j] += ld.force_N * np.array([0.0, math.cos(a), math.sin(a)])
            scale[j] += abs(ld.force_N)
    rows: dict = {}
    for a in acts:
        if a.pressed_half:
            continue
        j = index[(pattern_key(a), a.factor_name, False)]
        g = _band_group(a, plan)
        edges = mesh.group_edges(g)
        if len(edges) == 0:
            raise InputError("loads", f"{a.name}.band", "a band on the shaft's outline",
                             got=a.band_mm)
        rb = rows.get((g, a.x_mm))
        if rb is None:
            rb = rows[(g, a.x_mm)] = hm.rbe3(h, edges, a.x_mm)
        l0, ls, la = rb.load(a.F_N, a.M_Nmm)
        f0[:, j] += l0
        f1s[:, j] += ls
        f1a[:, j] += la
        load_sum[:, j] += a.F_N
        torque_sum[j] += a.M_Nmm[0]
        scale[j] += float(np.linalg.norm(a.F_N) + np.linalg.norm(a.M_Nmm) / length)
    if body:
        rho = float(variant.material.density_t_mm3)
        unit0 = h.body_vector((1.0, 0.0, 0.0), 0)
        unit1 = h.body_vector((0.0, 1.0, -1.0), 1)            # u_y (sym) / u_z (anti) mode
        mass = rho * float(unit0[0::3].sum())                 # 2π ∫ ρ r dA
        for b in body:
            j = index[(pattern_key(b), b.name, False)]
            ax, ay, az = b.accel_mm_s2
            f0[:, j] += rho * ax * unit0
            f1s[:, j] += rho * ay * unit1
            f1a[:, j] += rho * az * unit1
            load_sum[:, j] += mass * np.array([ax, ay, az])
            scale[j] += mass * float(np.linalg.norm(b.accel_mm_s2))
    return f0, f1s, f1a, load_sum, torque_sum, scale, sn


def solve_model(variant, options: AxiOptions = AxiOptions(), *, rpm: float = REF_RPM,
                cache_dir=None, case=None) -> AxiSolution:
    """Mesh, assemble and solve every harmonic the loads need (see the module docstring):
    one factorisation per harmonic, one column per load component (``Component``); the
    solution's fields are the components superposed at ``rpm`` (or in the load case
    ``case``), and ``columns`` keeps them apart for other speeds and cases."""
    t0 = time.perf_counter()
    check_options(options)
    if options.seed_load_case:
        variant = variant.with_seed_load_case()
    validate_variant(variant, springs=not options.rigid_supports, typed=False)
    check_torque_path(variant)
    plan = prepare(variant)                      # the solid plan: outline, seats, omissions
    acts, body = actions(variant, seed_placement=options.seed_load_case)
    mesh = mesh_geometry(shaft_geometry(plan, load_bands(variant, plan, options.seed_load_case)),
                         options.level, options.refine, cache_dir=cache_dir)
    t_mesh = time.perf_counter() - t0
    mat = variant.material
    E, nu = float(mat.E_MPa), float(mat.nu)
    h = hm.assemble(mesh, E, nu, cache_dir=cache_dir)
    pressed = any(a.pressed_half for a in acts)
    # the seed's placement: today's half-seat pressures, their column at REF_RPM
    loads = pressure_loads(variant, plan, options.load_distribution, REF_RPM) if pressed else []
    comps = _components(acts, body, bool(loads))
    omega2 = omega(rpm) ** 2
    soft, centroid = _softening(h, mesh, variant, omega2) if options.spin_softening else ([],
                                                                                        [])
    coeffs = kn.half_pressure_coefficients(options.load_distribution, options.n_max)
    S = rc.Surface(mesh)
    bearings = [(b.name, hm.rbe3(h, mesh.group_edges(bearing_group(b.name)), b.x_center_mm), b)
                for b in variant.bearings]
    f0, f1s, f1a, load_sum, torque_sum, load_scale, sn = _right_hand_sides(
        h, mesh, plan, variant, comps, acts, body, loads, coeffs)
    nc = len(comps)
    fac = np.array([c.factor(rpm, case) for c in comps])
    t_asm = time.perf_counter() - t0 - t_mesh

    # n = 0: u_x held at the axial bearing; θ_x where a bearing holds torsion, else one gauge
    # row (the axial bearing's) that carries Σ T = 0 (``check_torque_path``)
    hard, hard_lab = [], []
    for name, rb, b in bearings:
        if b.axial:
            hard.append(rb.ux)
            hard_lab.append((name, "u_x"))
        if b.holds_torsion:
            hard.append(rb.tx)
            hard_lab.append((name, "θ_x"))
    if not any(lab == "u_x" for _, lab in hard_lab):
        raise SolverError("the supports leave the shaft free to move: axial translation u_x "
                          "(mark one bearing with axial = true)")
    gauge = None
    if not any(lab == "θ_x" for _, lab in hard_lab):
        gauge = next(name for name, _, b in bearings if b.axial)
        hard.append(next(rb.tx for name, rb, _ in bearings if name == gauge))
        hard_lab.append((gauge, "θ_x"))
    from concurrent.futures import ThreadPoolExecutor
    pool = ThreadPoolExecutor(2)              # two harmonics at a time (SuperLU frees the GIL)
    cols_h, cols_s = [], []
    all_idx = np.arange(nc)
    try:
        job0 = pool.submit(hm.solve, h.K(0), f0, h.reduction(0), hard=np.array(hard),
                           keep="harmonic n=0")
        job1 = pool.submit(_solve_n1, h, bearings, f1s, f1a, options.rigid_supports, soft)
        sol0, (us, ua, reac1, res1) = job0.result(), job1.result()
        relres = [sol0.relres, res1]
        pj = [i for i, c in enumerate(comps) if c.pressed_half]

        def sigma(group_vals, j):
            return _sigma_n(S, mesh, group_vals) if j in pj else None
        cols_h.append((0, sol0.u, None, all_idx))
        cols_s.append((0, np.stack([S.stress(sol0.u[:, j], 0, E, nu, sigma(sn[0], j))
                                    for j in range(nc)], -1), None))
        reac = {name: np.zeros((5, nc)) for name, _, _ in bearings}
        tors = {}
        for (name, lab), lam in zip(hard_lab, sol0.multipliers, strict=True):
            if lab == "u_x":
                reac[name][0] = -lam
            else:
                tors[name] = -lam
        cols_h.append((1, us, ua, all_idx))
        cols_s.append((1, np.stack([S.stress(us[:, j], 1, E, nu, sigma(sn[1], j))
                                    for j in range(nc)], -1),
                       np.stack([S.stress(ua[:, j], 1, E, nu, sigma(sn[2], j))
                                 for j in range(nc)], -1)))
        for name, r in reac1.items():
            reac[name][1:5] = r

        # n ≥ 2: the half-seat pressure patches (the seed's placement), until no fillet's
        # peak changes any more; the remote loads have no n ≥ 2 part (a band's rigid rows)
        zones = [] if options.converge_all_fillets else \
            [f.zone_mm for f in cuts(plan)]
        track = _PeakTracker(S, mesh, zones)
        track.add([(n, a @ fac, None if b is None else b @ fac) for n, a, b in cols_s])
        last: list[float] = []
        n_used, change = 1, 0.0
        todo = [n for n in range(2, options.n_max + 1) if coeffs[n] != 0.0] if loads else []
        jp = np.array(pj, dtype=np.int64)
        done = False
        for k in range(0, len(todo), 2):
            batch = todo[k:k + 2]
            rhs = [_pressure_parts(h, mesh, loads, coeffs, n) for n in batch]
            sols = list(pool.map(lambda a: hm.solve(h.K(a[0]), np.column_stack(a[1][:2]),
                                                    h.reduction(a[0])),
                                 zip(batch, rhs, strict=True)))
            for n, (_, _, sn_s, sn_a), sol in zip(batch, rhs, sols, strict=True):
                relres.append(sol.relres)
                cols_h.append((n, sol.u[:, :1], sol.u[:, 1:2], jp))
                ss = S.stress(sol.u[:, 0], n, E, nu, _sigma_n(S, mesh, sn_s))
                sa = S.stress(sol.u[:, 1], n, E, nu, _sigma_n(S, mesh, sn_a))
                cols_s.append((n, ss[..., None], sa[..., None]))
                n_used = n
                change = track.add([(n, ss * fac[jp[0]], sa * fac[jp[0]])])
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
    motion = {name: np.array([row @ us, row @ ua]) for name, row, _ in centroid}
    cols = Columns(tuple(comps), tuple(cols_h), tuple(cols_s), reac, tors, load_sum,
                   torque_sum, load_scale, motion, gauge)
    base = AxiSolution(variant, options, plan, mesh, (), tuple(loads), tuple(bearings), {}, S,
                       (), n_used, change, track.names, secs, float(rpm), {},
                       {name: float(k) for name, _, k in centroid}, cols)
    return superpose(base, fac)


def superpose(sol: AxiSolution, factors) -> AxiSolution:
    """``sol`` with its fields, reactions and seat motions the components' columns × factors
    (``Columns.factors(rpm, case)``)."""
    from dataclasses import replace
    c = sol.columns
    f = np.asarray(factors, dtype=float)
    harm = tuple(HarmonicField(n, s @ f[i], None if a is None else a @ f[i])
                 for n, s, a, i in c.harmonics)
    idx = {n: i for n, _, _, i in c.harmonics}
    stress = tuple((n, s @ f[idx[n]], None if a is None else a @ f[idx[n]])
                   for n, s, a in c.stress)
    reac = {k: tuple(float(v) for v in r @ f) for k, r in c.reactions.items()}
    motion = {k: tuple(float(v) for v in m @ f) for k, m in c.motion.items()}
    return replace(sol, harmonics=harm, surface_stress=stress, reactions=reac,
                   attachment_motion=motion, factors=tuple(float(x) for x in f))


def _softening(h, mesh, variant, omega2: float):
    """(rows with their (symmetric, antisymmetric) 2×2 stiffness blocks, (name, row, k) whose
    motion × k is the softening force: each part's centroid, and the shaft's mass-weighted mean
    motion × its m ω²) of the co-rotating softening at ω² (module docstring). A seat's tilt
    row ``tz`` reads (θ_z, −θ_y) on the two parts: the tilt matrix T on (θ_y, θ_z) acts there
    as P T Pᵀ, P = [[0, 1], [−1, 0]]."""
    P = np.array([[0.0, 1.0], [-1.0, 0.0]])
    soft, centroid = [], []
    for p in spinning_parts(variant):
        rb = hm.rbe3(h, mesh.group_edges(seat_group(p.name)), p.x_seat_mm)
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
    """Harmonic n = 1, both parts, with ONE factorisation for both and every column of
    ``fs``, ``fa`` (ndof, c).

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

    Returns (U_sym, U_anti (ndof, c), {bearing: (4, c) F_y, F_z, q_y, q_z}, the largest backward
    error of the coupled system, ``harmonic.backward_error``); vectors for vector loads."""
    vec = np.ndim(fs) == 1                  # one load: vectors in, vectors out
    fs, fa = np.atleast_2d(fs.T).T, np.atleast_2d(fa.T).T
    nc = fs.shape[1]
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
    sol = hm.solve(K1, np.column_stack([fs, fa, *rows]), T1, springs=base, hard=hard,
                   keep="harmonic n=1")
    x0s, x0a, Z = sol.u[:, :nc], sol.u[:, nc:2 * nc], sol.u[:, 2 * nc:]
    mu = sol.multipliers                                       # (n_hard, 2 c + m)
    y = np.zeros((2 * m, nc))
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
        y = np.linalg.solve(M, D @ np.vstack([rows @ x0s, rows @ x0a]))      # (2m, c)
    us, ua = x0s - Z @ y[:m], x0a - Z @ y[m:]
    # the residual of the coupled system with the factorised matrix of ``hm.solve``:
    # M [x̂; λ] + [Tᵀ (low-rank term); 0] − [Tᵀ f; 0]
    Msys, n_u = sol.matrix, T1.shape[1]
    w = np.asarray(T1.multiply(T1).sum(axis=0)).ravel()        # 1, or 2 on the axis (U_θ = −U_r)
    qs, qa = rows @ us, rows @ ua                                            # (m, c)
    rel, mult = 0.0, [[], []]
    for part, (x, f) in enumerate(((us, fs), (ua, fa))):
        extra = np.zeros((h.ndof, nc))
        for k, c in enumerate(blocks):
            extra += np.outer(rows[k], (c @ np.vstack([qs[k], qa[k]]))[part])
        lam = np.zeros((0, nc))
        if hard is not None:
            lam = mu[:, part * nc:(part + 1) * nc] - mu[:, 2 * nc:] @ y[part * m:(part + 1) * m]
            mult[part] = lam
        z = np.vstack([(T1.T @ x) / w[:, None], lam])
        b = np.vstack([T1.T @ f, np.zeros(lam.shape)])
        r = Msys @ z + np.vstack([T1.T @ extra, np.zeros(lam.shape)]) - b
        rel = max(rel, hm.backward_error(Msys, z, b, r, n_u))
    if not np.all(np.isfinite(us)) or not np.all(np.isfinite(ua)) or rel > 1e-9:
        raise SolverError(f"the n = 1 harmonic solve did not converge (backward error "
                          f"{rel:.2e})")
    reac = {}
    for k, (name, _, _) in enumerate(bearings):
        if rigid:
            reac[name] = np.array([-mult[0][k], -mult[1][k], np.zeros(nc), np.zeros(nc)])
        else:
            q = np.vstack([qs[k], qa[k]])          # the bearings' rows come first
            F = -C[k] @ q
            reac[name] = np.array([F[0], F[1], q[0], q[1]])
    if vec:
        us, ua, reac = us[:, 0], ua[:, 0], {k: r[:, 0] for k, r in reac.items()}
    return us, ua, reac, max(rel, sol.relres)


class _PeakTracker:
    """Running θ-synthesis (1° grid) of the surface stress on the fillets outside ``zones``
    (x intervals in mm; every fillet when none is outside); ``add`` returns the largest change
    of such a fillet's peak von Mises stress relative to the largest of their peaks."""

    def __init__(self, surface, mesh, zones=()):
        ids = {}
        for i, c in enumerate(mesh.geometry.curves):
            for g in c.groups:
                if kind_of(g) in ROUND_NOTCH_KINDS:
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
