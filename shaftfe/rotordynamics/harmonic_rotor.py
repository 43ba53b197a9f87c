"""Rotor dynamics of the shaft as a body of revolution: the Fourier-harmonic n = 0 and n = 1
fields of the meridian P2 mesh (``shaftfe.axisymmetric``) with the parts as rigid bodies and
the bearings as springs, in the stationary frame (the 3D solid rotor's equations,
``solid_rotor``, restricted to the harmonics that carry every mode a Campbell diagram follows:
n = 0 axial and torsional, n = 1 bending; n ≥ 2 are ovalisations of the section, far above).

Dofs: q = [n = 0 (U_x, U_r, U_θ); n = 1 symmetric; n = 1 antisymmetric] per meridian node,
with the axis conditions (``harmonic.reduction``), the held rows and, with the rigid coupling,
the parts' seat nodes eliminated (below). The symmetric part carries (u_y, θ_z), the
antisymmetric one (u_z, θ_y) (``axisymmetric.kernels`` conventions).

Matrices (3D energies of the harmonic fields, so the parts' and bearings' terms add directly):

* K: ``Harmonics.K(n)`` (weights 2π, π).
* M: ρ w_n kron(Ms, I₃), Ms = ∫ N_a N_b r dr dx (``axisymmetric.model._meridian_mass``): the
  kinetic energy ½ ∫ ρ |u̇|² dV of cos/sin nθ fields integrates to w_n (2π for n = 0, π for
  n = 1) times the meridian integral.
* G: the solid rotor's G = A − Aᵀ, A = ∫ ρ Nᵀ ∂_θ N dV (``solid_rotor`` docstring), with ∂_θ
  of a vector field in cylindrical components (∂_θ e_r = e_θ, ∂_θ e_θ = −e_r): n = 0:
  ∂_θ u = −U_θ e_r + U_r e_θ, G₀₀ = 2π ρ kron(Ms, 2 Q), Q[r, θ] = −1, Q[θ, r] = 1 (the
  Coriolis coupling of torsion and radial breathing); n = 1: ∂_θ maps the symmetric part to the
  antisymmetric one and back, (A_x, A_r, A_θ) → −(A_x, A_r + A_θ, A_r + A_θ), so
  G_sa = −G_asᵀ = 2 π ρ kron(Ms, P), P = [[1, 0, 0], [0, 1, 1], [0, 1, 1]]. Check: on the
  rigid tilts G[θ_y, θ_z] = 2πρ ∫ r³ dA = I_p, as the solid's (rigid translations: P kills
  (0, 1, −1), no coupling).
* Parts: ``solid_rotor.attachment_bodies``' 6×6 M6, G6 per seat (the parts on one seat, about
  the seat centre), on the body's (u_x, θ_x) in n = 0, (u_y, θ_z) and (u_z, θ_y) in n = 1.
  ``coupling="rigid"`` (the solid's default, RBE2-like): every node of the seat line follows the
  body (n = 0: U = u_x (1, 0, 0) + θ_x (0, 0, r); symmetric: u_y (0, 1, −1) + θ_z (−r, x − c,
  −(x − c)); antisymmetric: u_z (0, 1, −1) + θ_y (r, −(x − c), x − c)), eliminated;
  ``"distributing"`` (RBE3-like): the body moves with the seat's ``harmonic.rbe3`` rows.
* Bearings: ``harmonic.rbe3`` remote points, the 2×2 radial spring on (u_y, u_z) (couples the
  two parts through K12), tilt springs if given, u_x held at the axial bearing and θ_x at every
  bearing (the solid's ``hold_twist="all"``), eliminated exactly (``_eliminate``).

What is not round: the keyways are left out (the outline of
``axisymmetric.mesh.shaft_geometry``); the hex socket's mass is taken out as the bore of equal
area (``_hex_socket_mass``), its stiffness is left out. Both measured against the solid
rotor in benchmarks/bench_harmonic_modes.py.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from shaftfe.errors import InputError
from shaftfe.rotordynamics.kernels import Labelling
from shaftfe.rotordynamics.options import COUPLINGS

P1 = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 1.0], [0.0, 1.0, 1.0]])
Q0 = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])


@dataclass(frozen=True)
class HarmonicOptions:
    level: object = "default"             # a name of axisymmetric.mesh.AXI_LEVELS or an AxiLevel
    coupling: str = "rigid"               # attachments: "rigid" (RBE2) | "distributing" (RBE3)
    rigid_supports: bool = False
    bearing_damping: float = 0.0          # N·s/mm, isotropic, on every bearing's (u_y, u_z)


@dataclass(frozen=True, eq=False)
class HarmonicRotor:
    """Sparse K, M, G on q and the map T (9 N × n_q) to the three harmonic dof vectors."""
    name: str
    variant: object
    mesh: object
    options: HarmonicOptions
    K: object
    M: object
    G: object
    K_support: object
    T: object
    labelling: Labelling
    bodies: tuple = ()
    notes: tuple = field(default_factory=tuple)
    assembly_seconds: float = 0.0
    C: object = None                      # bearing damping (sparse) or None
    damped_rows: object = None            # (r, n_q) the dampers' rows, for residual vectors
    beam = None

    @property
    def n_dof(self) -> int:
        return self.K.shape[0]

    @property
    def disks(self) -> tuple:
        return self.bodies


def _seat_nodes(mesh, groups) -> np.ndarray:
    e = np.concatenate([mesh.group_edges(g) for g in groups])
    return np.unique(mesh.edges[:, e])


def _rigid_fields(x, r, xc, block: int):
    """(3 n, 2) the two rigid motions of ``block`` (0: n = 0 (u_x, θ_x); 1: symmetric (u_y,
    θ_z); 2: antisymmetric (u_z, θ_y)) at nodes (x, r), interleaved (U_x, U_r, U_θ)."""
    n = x.size
    F = np.zeros((n, 3, 2))
    d = x - xc
    if block == 0:
        F[:, 0, 0], F[:, 2, 1] = 1.0, r
    elif block == 1:
        F[:, 1, 0], F[:, 2, 0] = 1.0, -1.0
        F[:, 0, 1], F[:, 1, 1], F[:, 2, 1] = -r, d, -d
    else:
        F[:, 1, 0], F[:, 2, 0] = 1.0, -1.0
        F[:, 0, 1], F[:, 1, 1], F[:, 2, 1] = r, -d, d
    return F.reshape(3 * n, 2)


def _eliminate(H):
    """T (n × (n − h)) with H T = 0 for the h rows H (dense, h × n, full row rank): the h
    pivot dofs (the first columns of a column-pivoted QR of H, a well-conditioned H_P)
    expressed by the other dofs, u_P = −H_P⁻¹ H_F u_F (exact elimination, no penalty)."""
    import scipy.linalg as la
    import scipy.sparse as sp
    h, n = H.shape
    _, _, piv = la.qr(H, mode="economic", pivoting=True)
    P = np.sort(piv[:h])
    F = np.setdiff1d(np.arange(n), P)
    S = -np.linalg.solve(H[:, P], H[:, F])               # u_P = S u_F
    S[np.abs(S) < 1e-14 * np.abs(S).max(initial=0.0)] = 0.0
    Ss = sp.coo_matrix(S)
    rows = np.concatenate([F, P[Ss.row]])
    cols = np.concatenate([np.arange(F.size), Ss.col])
    vals = np.concatenate([np.ones(F.size), Ss.data])
    return sp.csr_matrix((vals, (rows, cols)), shape=(n, F.size))


def build_harmonic_rotor(variant, options: HarmonicOptions = HarmonicOptions(), *,
                         plan_variant=None, support_faces: dict | None = None,
                         cache_dir=None) -> HarmonicRotor:
    """The harmonic rotor of ``variant`` (module docstring). ``plan_variant``: the variant
    whose solid plan gives the outline (default ``variant``; a validation model whose bearing
    sits on an end face); ``support_faces``: bearing name → mesh group (default
    ``bearing:<name>``)."""
    import scipy.sparse as sp

    from shaftfe.axisymmetric import harmonic as hm
    from shaftfe.axisymmetric.mesh import mesh_geometry, shaft_geometry
    from shaftfe.axisymmetric.model import _meridian_mass
    from shaftfe.model.validate import validate_variant
    from shaftfe.rotordynamics import beam_rotor
    from shaftfe.solid.plan import prepare

    if options.coupling not in COUPLINGS:
        raise InputError("--coupling", "coupling", " | ".join(COUPLINGS), got=options.coupling)
    validate_variant(variant, springs=not options.rigid_supports, typed=False)
    t0 = time.perf_counter()
    plan = prepare(plan_variant or variant)
    mesh = mesh_geometry(shaft_geometry(plan), options.level, cache_dir=cache_dir)
    mat = variant.material
    rho = float(mat.density_t_mm3)
    h = hm.assemble(mesh, float(mat.E_MPa), float(mat.nu), cache_dir=cache_dir)
    N = mesh.n_nodes
    n3 = 3 * N
    Ms = _meridian_mass(mesh)
    hole = _hex_socket_mass(variant, plan, mesh)
    if hole is not None:
        Ms = (Ms - hole).tocsr()
    I3 = sp.identity(3, format="csr")
    K = sp.block_diag([h.K(0), h.K(1), h.K(1)], format="csr")
    w0, w1 = hm.weight(0), hm.weight(1)
    M = sp.block_diag([rho * w0 * sp.kron(Ms, I3), rho * w1 * sp.kron(Ms, I3),
                       rho * w1 * sp.kron(Ms, I3)], format="csr")
    Gsa = 2.0 * w1 * rho * sp.kron(Ms, sp.csr_matrix(P1))
    G00 = 2.0 * w0 * rho * sp.kron(Ms, sp.csr_matrix(Q0))
    G = sp.bmat([[G00, None, None], [None, None, Gsa], [None, -Gsa.T, None]], format="csr")

    # the parts: one rigid body per seat (the solid rotor's grouping and 6×6 matrices)
    groups: dict[tuple[float, float], list] = {}
    for a in variant.attachments:
        groups.setdefault((a.seat_x_start_mm, a.seat_x_end_mm), []).append(a)
    disks = {d.name: d for d in beam_rotor.disks_from_variant(variant)}
    bodies = []
    for (x0, x1), parts in groups.items():
        M6, G6 = np.zeros((6, 6)), np.zeros((6, 6))
        for a in parts:
            m6, g6 = beam_rotor.disk_matrices(disks[a.name])
            M6 += m6
            G6 += g6
        names = [f"load:{a.name}" for a in parts]
        if not any(mesh.group_edges(g).size for g in names):
            raise InputError(f"variant {variant.name}", "attachment seats",
                             "a part whose seat is on the shaft's outline", got=names[0])
        bodies.append(("+".join(a.name for a in parts), 0.5 * (x0 + x1), names, M6, G6))

    # q: per block the free dofs (axis conditions; rigid seats' nodes removed) + body dofs
    Ts = [h.reduction(0), h.reduction(1), h.reduction(1)]
    body_cols = []                       # per body: 6 columns of q (u_x, u_y, u_z, θ_x, θ_y, θ_z)
    if options.coupling == "rigid" and bodies:
        slave = np.zeros(N, dtype=bool)
        seat = [_seat_nodes(mesh, b[2]) for b in bodies]
        for nd in seat:
            if slave[nd].any():
                raise InputError(f"variant {variant.name}", "attachment seats",
                                 "seats that share no mesh node", got=variant.name)
            slave[nd] = True
        slave_dofs = np.repeat(slave, 3)
        new = []
        for blk, T in enumerate(Ts):
            T = T.tocsc()
            keep = np.asarray(abs(T[slave_dofs]).sum(axis=0)).ravel() == 0
            T = T[:, keep]
            cols = []
            for (_, xc, _, _, _), nd in zip(bodies, seat, strict=True):
                F = _rigid_fields(mesh.xr[0][nd], mesh.xr[1][nd], xc, blk)
                d = (3 * nd[:, None] + np.arange(3)).ravel()
                cols.append(sp.csr_matrix((F.ravel(), (np.repeat(d, 2), np.tile([0, 1],
                                                                                 d.size))),
                                          shape=(n3, 2)))
            new.append(sp.hstack([T, *cols], format="csr"))
        off = np.cumsum([0] + [t.shape[1] for t in new])
        nb = len(bodies)
        for k in range(nb):
            c0, c1, c2 = (off[b] + new[b].shape[1] - 2 * nb + 2 * k for b in range(3))
            body_cols.append(np.array([c0, c1, c2, c0 + 1, c2 + 1, c1 + 1]))
        Ts = new
    T = sp.block_diag(Ts, format="csr")
    nq = T.shape[1]

    def lift(rows_blocks):
        """rows on the three blocks' full dofs -> a row on the 9 N dofs."""
        out = np.zeros(3 * n3)
        for blk, r in rows_blocks:
            out[blk * n3:(blk + 1) * n3] += r
        return out

    faces = support_faces or {}
    brg = [(b, hm.rbe3(h, mesh.group_edges(faces.get(b.name, f"bearing:{b.name}")),
                       b.x_center_mm)) for b in variant.bearings]
    if not brg:
        raise InputError(f"variant {variant.name}", "bearings", "at least one bearing", got=0)
    hard, springs, dampers = [], [], []
    for b, rb in brg:
        if b.axial:
            hard.append(lift([(0, rb.ux)]))
        hard.append(lift([(0, rb.tx)]))
        R = np.array([lift([(1, rb.uy)]), lift([(2, rb.uy)])])
        if options.rigid_supports:
            hard += list(R)
        else:
            springs.append((R, np.asarray(b.K_N_per_mm, dtype=float).reshape(2, 2)))
        if options.bearing_damping > 0:
            dampers.append(R)
        kt = float(b.tilt_stiffness_Nmm_per_rad)
        if kt > 0:
            springs.append((np.array([lift([(1, rb.tz)]), lift([(2, -rb.tz)])]),
                            kt * np.eye(2)))
    Hq = (sp.csr_matrix(np.array(hard)) @ T).toarray()
    Th = _eliminate(Hq)
    Tq = (T @ Th).tocsr()
    Ksup = sp.csr_matrix((3 * n3, 3 * n3))
    for R, C in springs:
        Rs = sp.csr_matrix(R)
        Ksup = Ksup + Rs.T @ sp.csr_matrix(C) @ Rs
    Kq = (Tq.T @ (K + Ksup) @ Tq).tocsr()
    Mq = Tq.T @ M @ Tq
    Gq = Tq.T @ G @ Tq
    # the bodies' 6 × 6 blocks: on their q columns (rigid) or on the seat's rbe3 rows
    for name, xc, names, M6, G6 in bodies:
        if body_cols:
            k = [b[0] for b in bodies].index(name)
            R6 = sp.csr_matrix((np.ones(6), (np.arange(6), body_cols[k])), shape=(6, nq))
        else:
            e = np.concatenate([mesh.group_edges(g) for g in names])
            rb = hm.rbe3(h, e, xc)
            R6 = sp.csr_matrix(np.array([
                lift([(0, rb.ux)]), lift([(1, rb.uy)]), lift([(2, rb.uy)]),
                lift([(0, rb.tx)]), lift([(2, -rb.tz)]), lift([(1, rb.tz)])])) @ T
        R6 = (R6 @ Th).tocsr()
        Mq = Mq + R6.T @ sp.csr_matrix(M6) @ R6
        Gq = Gq + R6.T @ sp.csr_matrix(G6) @ R6
    Mq, Gq = Mq.tocsr(), Gq.tocsr()
    Gq = (0.5 * (Gq - Gq.T)).tocsr()                      # skew to round-off
    Mq = (0.5 * (Mq + Mq.T)).tocsr()
    Cq = Dr = None
    if dampers:
        Dr = (sp.csr_matrix(np.vstack(dampers)) @ Tq).tocsr()
        Cq = (options.bearing_damping * (Dr.T @ Dr)).tocsr()
    lab = _labelling(n3, M, Tq)
    notes = (f"harmonic rotor: n = 0 and n = 1 fields of the meridian mesh ({options.level}, "
             f"{N} nodes); keyways not modelled, the hex socket's mass as a bore of equal area",
             f"attachments: {len(bodies)} rigid bodies, {options.coupling} coupling")
    return HarmonicRotor(variant.name, variant, mesh, options, Kq, Mq, Gq,
                         (Tq.T @ Ksup @ Tq).tocsr(), Tq, lab,
                         tuple(b[0] for b in bodies), notes, time.perf_counter() - t0, Cq, Dr)


def _hex_socket_mass(variant, plan, mesh):
    """The hex socket's share of ``_meridian_mass`` (the local correction of its mass: the
    socket as the bore of equal area, the beam's and the ROSS model's idealisation), or None:
    ∫ N_a N_b r dr dx over r < r_eq, x within the depth, by the same order-4 quadrature with
    the integrand masked at the points, scaled to the exact area × depth (a quadrature of a
    discontinuous integrand). The polar inertia of the bore of equal area is that of the
    hexagon within 1 % (m r²/2 against 5 m s²/36). Its stiffness is left out: on x2_57 the
    socket lies inside the rigidly tied seats of the lock nut and counterweight 2."""
    import scipy.sparse as sp

    from shaftfe.axisymmetric import kernels as kn
    from shaftfe.beam.elements import hexagon_area_inertia
    hs = variant.hex_socket
    if hs is None:
        return None
    area = float(hexagon_area_inertia(hs.across_flats_mm)[0])
    r_eq, t = math.sqrt(area / math.pi), float(hs.depth_mm)
    x0, x1 = ((plan.x_right - t, plan.x_right) if hs.end == "right"
              else (plan.x_left, plan.x_left + t))
    pts, w = kn.triangle_rule(4)
    X, R = mesh.xr[0][mesh.tri].T, mesh.xr[1][mesh.tri].T
    x, r, det, N, _, _ = kn.element_geometry(X, R, pts)
    inside = (r < r_eq) & (x > x0) & (x < x1)
    wq = det * r * w[None] * inside
    vol = 2.0 * math.pi * float(wq.sum())
    if vol <= 0:
        return None
    Me = np.einsum("aq,bq,eq->eab", N, N, wq) * (area * t / vol)
    rows = np.repeat(mesh.tri.T, 6, axis=1).ravel()
    cols = np.tile(mesh.tri.T, (1, 6)).ravel()
    return sp.csr_matrix((Me.ravel(), (rows, cols)), shape=(mesh.n_nodes,) * 2)


def _labelling(n3: int, M, Tq) -> Labelling:
    """Families on the harmonic dofs: n = 0 (U_x, U_r) axial, n = 0 U_θ torsional, n = 1
    lateral; whirl pairs: U_r of the symmetric (u_y) and antisymmetric (u_z) parts."""
    from types import MappingProxyType
    comp = np.tile(np.arange(3), n3 // 3)
    b0 = np.arange(n3)
    groups = MappingProxyType({"axial": b0[comp != 2], "torsional": b0[comp == 2],
                               "lateral": np.arange(n3, 3 * n3)})
    return Labelling(groups=groups, pair_y=n3 + b0[comp == 1], pair_z=2 * n3 + b0[comp == 1],
                     weights=np.asarray(M.diagonal()), transform=Tq)


def campbell(rotor: HarmonicRotor, rpms, n_modes: int = 12, **kw):
    """The Campbell sweep of the harmonic rotor (``campbell.sweep`` on its sparse matrices)."""
    from shaftfe.rotordynamics.campbell import sweep
    res = None
    if rotor.damped_rows is not None:       # the dampers' static residual vectors K⁻¹ Rᵀ
        from scipy.sparse.linalg import splu
        res = splu(rotor.K.tocsc()).solve(rotor.damped_rows.T.toarray())
    from dataclasses import replace
    out = sweep(rotor.K, rotor.M, rotor.G, rpms, n_modes, rotor.labelling, C=rotor.C,
                residuals=res, **kw)
    return replace(out, notes=out.notes + rotor.notes)
