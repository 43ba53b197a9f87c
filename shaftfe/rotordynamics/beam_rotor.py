"""Rotor-dynamics model of the beam path: shaft gyroscopics, rigid disks, bearings, and the
Campbell sweep / single-speed modal analysis (kernels in ``shaftfe.rotordynamics.kernels``).

Equation of motion (stationary frame, spin Ω about +x, constraints eliminated):

    M q̈ + (C + Ω G) q̇ + K q = 0

* K: the shaft's Timoshenko stiffness (``beam.assemble_stiffness``) plus the bearings' 2×2
  radial springs and tilt springs (``beam.support_stiffness``), exactly as in the static beam
  model; held dofs (rigid supports, the axial hold, the torsion hold at ``torsion_node``) are
  removed. Spin softening and stress stiffening are OFF (not modelled).
* M: the shaft's consistent Timoshenko mass with rotary inertia (``beam.assemble_mass``)
  plus rigid disks.
* G: shaft elements — for the Timoshenko (IIE) element the gyroscopic matrix is the skew
  coupling of the two bending planes through twice the rotary-inertia matrix built with the
  polar moment (Nelson, J. Mech. Des. 102 (1980) 793-803; Friswell, Penny, Garvey & Lees,
  *Dynamics of Rotating Machines*, CUP 2010, §5.4-5.5: G_e = skew pairing of the rotary-inertia
  shape-function integral ∫ ρ I_p N_θᵀ N_θ dx). In this code's dofs (θ_z = dv/dx,
  θ_y = −dw/dx; plane dofs of x-z are (w, −θ_y)): G_e[xy, xz] = R S, G_e[xz, xy] = −S R, with
  R the 4×4 rotary-inertia matrix computed with ρ I_p = 2 ρ I and S = diag(1, −1, 1, −1).
  Disks: Id θ̈_y + Ip Ω θ̇_z = M_y and Id θ̈_z − Ip Ω θ̇_y = M_z (dH/dt = M with H ≈ Ip Ω e_x'
  and the tilted axis e_x' ≈ (1, θ_z, −θ_y)).
* C: optional bearing damping, 2×2 per bearing on (v, w) at the bearing node (then the
  frequencies are damped ones).
* Torsion and axial motion are held exactly as in the static beam model (θ_x at the axial
  bearing's node, u_x at the axial bearing; the seed removed the rotation about the axis at
  the bearings): torsional and axial modes are those of the shaft held there.

Disks (attachments) — coupling and its limits
---------------------------------------------
Each attachment is a rigid body connected to ONE shaft node: the node at the centre of its seat
(the part bears on its seat, so a part whose centroid lies outside the seat — counterweight 1,
bolted to the gear, centroid at x = −4 mm, beyond the shaft end — still loads the gear seat).
The offset d = x_centroid − x_node is a rigid link: v_c = v + d θ_z, w_c = w − d θ_y, rotations
equal; the node matrices are Tᵀ M_c T (this adds the m d² tilt inertia and the m d
translation-tilt coupling; G is unchanged because T is the identity on the rotations).
Limits: the part does not stiffen its seat (a 3D bonded model does, and its hub mass sits on a
length, not at one node); the part is treated as axisymmetric about the shaft axis — its mass
centre's eccentricity e is kept only as inertia: polar moment about the shaft axis Ip + m e²,
diametral Id + m e²/2 (the average of the two transverse moments about the shaft axis); the
resulting rotating inertia anisotropy (m e², parametric in the stationary frame) and the
torsion-lateral coupling of an eccentric mass are dropped (unbalance is a forcing, not part of
the free-vibration problem).

Units: mm, N, t, s → rad/s; inputs in kg and kg·mm² are converted (×1e-3). Reports in Hz/rpm.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np

from shaftfe.beam import elements
from shaftfe.beam import model as beam
from shaftfe.beam.elements import NDOF, RX, RY, RZ, UX, UY, UZ
from shaftfe.errors import InputError
from shaftfe.rotordynamics.campbell import CampbellResult, sweep
from shaftfe.rotordynamics.kernels import TWO_PI, Labelling, full_qep, rpm_to_rad_s
from shaftfe.rotordynamics.options import DEFAULT_ORDERS

_S = np.array([1.0, -1.0, 1.0, -1.0])
_XY = np.array([UY, RZ, NDOF + UY, NDOF + RZ])
_XZ = np.array([UZ, RY, NDOF + UZ, NDOF + RY])


# --------------------------------------------------------------------------- elements

def element_gyroscopic(L, rho, E, G, sec: elements.Sections) -> np.ndarray:
    """(n, 12, 12) gyroscopic matrix per unit spin (rad/s) of IIE Timoshenko shaft elements.

    Skew-symmetric; couples the two bending planes through 2× the rotary-inertia matrix with
    the polar area moment I_p = 2 I (exact for the isotropic sections used here)."""
    L = np.asarray(L, dtype=float)
    phi = 12.0 * E * sec.I / (sec.kappa * G * sec.A * L**2)
    R = elements.timoshenko_bending_mass(L, np.zeros_like(L), rho * 2.0 * sec.I, phi)
    g = np.zeros((L.size, 2 * NDOF, 2 * NDOF))
    g[:, _XY[:, None], _XZ[None, :]] = R * _S[None, None, :]
    g[:, _XZ[:, None], _XY[None, :]] = -_S[None, :, None] * R
    return g


def assemble_gyroscopic(model: beam.BeamModel) -> np.ndarray:
    """Dense gyroscopic matrix of the shaft alone (per unit spin, t·mm²·… consistent units)."""
    ge = element_gyroscopic(model.L, model.density, model.E, model.G, model.sections)
    ndof = NDOF * model.n_nodes
    Gm = np.zeros((ndof, ndof))
    dofs = NDOF * np.arange(model.n_elements)[:, None] + np.arange(2 * NDOF)[None, :]
    np.add.at(Gm, (dofs[:, :, None], dofs[:, None, :]), ge)
    return Gm


# --------------------------------------------------------------------------- disks

@dataclass(frozen=True)
class Disk:
    """Rigid, axisymmetric disk: mass (t), polar inertia about the spin axis and diametral
    inertia about a transverse axis through its centroid (t·mm²), centroid at ``x_mm``,
    connected to the node at ``x_node_mm`` by a rigid link."""
    name: str
    x_mm: float
    x_node_mm: float
    mass_t: float
    Ip_t_mm2: float
    Id_t_mm2: float


def disk_matrices(d: Disk) -> tuple[np.ndarray, np.ndarray]:
    """(M, G) 6×6 at the connection node, dofs (u_x, u_y, u_z, θ_x, θ_y, θ_z)."""
    Mc = np.diag([d.mass_t, d.mass_t, d.mass_t, d.Ip_t_mm2, d.Id_t_mm2, d.Id_t_mm2])
    Gc = np.zeros((NDOF, NDOF))
    Gc[RY, RZ] = d.Ip_t_mm2
    Gc[RZ, RY] = -d.Ip_t_mm2
    off = d.x_mm - d.x_node_mm
    T = np.eye(NDOF)
    T[UY, RZ] = off
    T[UZ, RY] = -off
    return T.T @ Mc @ T, T.T @ Gc @ T


def disks_from_variant(variant) -> tuple[Disk, ...]:
    """Every attachment as a rigid axisymmetrised disk on its seat-centre node (kg → t)."""
    out = []
    for a in variant.attachments:
        m = a.mass_kg * 1e-3
        e2 = a.eccentricity_mm**2
        out.append(Disk(name=a.name, x_mm=float(a.x_centroid_mm),
                        x_node_mm=float(a.seat_center_mm), mass_t=m,
                        Ip_t_mm2=a.polar_inertia_kg_mm2 * 1e-3 + m * e2,
                        Id_t_mm2=a.diametral_inertia_kg_mm2 * 1e-3 + 0.5 * m * e2))
    return tuple(out)


def disk_from_geometry(name: str, x_mm: float, outer_d_mm: float, inner_d_mm: float,
                       width_mm: float, density_t_mm3: float,
                       x_node_mm: float | None = None) -> Disk:
    """Annular disk: m = ρ π (D² − d²) w / 4, Ip = m (D² + d²)/8, Id = Ip/2 + m w²/12."""
    m = density_t_mm3 * math.pi * (outer_d_mm**2 - inner_d_mm**2) * width_mm / 4.0
    ip = m * (outer_d_mm**2 + inner_d_mm**2) / 8.0
    return Disk(name, x_mm, x_mm if x_node_mm is None else x_node_mm, m, ip,
                0.5 * ip + m * width_mm**2 / 12.0)


# --------------------------------------------------------------------------- model

@dataclass(frozen=True, eq=False)
class RotorModel:
    """Matrices on the free dofs (held dofs removed) and how to label the modes."""
    name: str
    beam: beam.BeamModel
    disks: tuple[Disk, ...]
    M: np.ndarray
    K: np.ndarray
    G: np.ndarray
    C: np.ndarray | None
    free: np.ndarray                  # free dof indices into the full 6-per-node numbering
    labelling: Labelling
    notes: tuple[str, ...] = field(default_factory=tuple)
    K_support: np.ndarray | None = None   # bearing springs alone (free dofs), for energy shares

    @property
    def n_dof(self) -> int:
        return self.free.size

    def full_vector(self, q: np.ndarray) -> np.ndarray:
        out = np.zeros((NDOF * self.beam.n_nodes, *q.shape[1:]), dtype=q.dtype)
        out[self.free] = q
        return out


def _damping_matrix(c) -> np.ndarray:
    c = np.asarray(c, dtype=float)
    if c.ndim == 0:
        c = c * np.eye(2)
    if c.shape != (2, 2) or not np.all(np.isfinite(c)) or abs(c[0, 1] - c[1, 0]) > 1e-12 * (
            abs(c).max() + 1) or np.any(np.linalg.eigvalsh(c) < -1e-12 * (abs(c).max() + 1)):
        raise InputError("--bearing-damping", "bearing damping",
                         "a scalar >= 0 or a symmetric positive semi-definite 2x2 (N s/mm)",
                         got=c.tolist())
    return c


def build_rotor(model: beam.BeamModel, disks: Sequence[Disk] = (), *,
                bearing_damping=None, extra_fixed: Sequence[int] = (),
                check: bool = True) -> RotorModel:
    """Assemble M, K, G (and C) of a beam model with disks; eliminate the held dofs.

    ``bearing_damping``: None, one value or 2×2 for every bearing (N·s/mm), or a sequence with
    one entry per support. ``extra_fixed``: further dofs (full numbering) held, e.g. a clamp.
    ``check``: refuse a model whose supports leave a rigid-body motion free (free-free models
    for validation pass ``check=False``; their rigid-body modes are then dropped as 0 Hz)."""
    if check:
        beam.check_supports(model)
    K = beam.assemble_stiffness(model)
    Ks, fixed = beam.support_stiffness(model)
    K = K + Ks
    M = beam.assemble_mass(model)
    Gm = assemble_gyroscopic(model)
    x = model.x
    for d in disks:
        if not (d.mass_t >= 0 and d.Ip_t_mm2 >= 0 and d.Id_t_mm2 >= 0):
            raise InputError(f"disk {d.name}", "mass/inertia", ">= 0",
                             got=(d.mass_t, d.Ip_t_mm2, d.Id_t_mm2))
        n = int(np.argmin(np.abs(x - d.x_node_mm)))
        if abs(x[n] - d.x_node_mm) > 1e-6:
            raise InputError(f"disk {d.name}", "x_node_mm", "a node of the beam model",
                             got=d.x_node_mm)
        md, gd = disk_matrices(d)
        idx = NDOF * n + np.arange(NDOF)
        M[np.ix_(idx, idx)] += md
        Gm[np.ix_(idx, idx)] += gd
    C = None
    if bearing_damping is not None:
        sups = model.supports
        nd = np.ndim(bearing_damping)
        if nd == 0 or np.shape(bearing_damping) == (2, 2):
            vals = [bearing_damping] * len(sups)
        elif len(bearing_damping) == len(sups):
            vals = list(bearing_damping)
        else:
            raise InputError("bearing damping", "bearing_damping",
                             f"one value or 2x2, or one per bearing ({len(sups)})",
                             got=np.asarray(bearing_damping).tolist())
        C = np.zeros_like(K)
        for s, c in zip(sups, vals, strict=True):
            idx = NDOF * s.node + np.array([UY, UZ])
            C[np.ix_(idx, idx)] += _damping_matrix(c)
    fixed = np.unique(np.concatenate([np.asarray(fixed, int), np.asarray(extra_fixed, int)]))
    free = np.setdiff1d(np.arange(K.shape[0]), fixed)
    sub = np.ix_(free, free)
    Mf, Kf, Gf = M[sub], K[sub], Gm[sub]
    Cf = None if C is None else C[sub]
    # labelling on the free dofs
    pos = np.full(K.shape[0], -1)
    pos[free] = np.arange(free.size)
    dof_kind = np.tile(np.arange(NDOF), model.n_nodes)
    fk = dof_kind[free]
    groups = MappingProxyType({
        "lateral": np.flatnonzero(np.isin(fk, (UY, UZ, RY, RZ))),
        "torsional": np.flatnonzero(fk == RX),
        "axial": np.flatnonzero(fk == UX)})
    nodes_both = [n for n in range(model.n_nodes)
                  if pos[NDOF * n + UY] >= 0 and pos[NDOF * n + UZ] >= 0]
    py = np.array([pos[NDOF * n + UY] for n in nodes_both], dtype=int)
    pz = np.array([pos[NDOF * n + UZ] for n in nodes_both], dtype=int)
    lab = Labelling(groups=groups, pair_y=py, pair_z=pz, weights=np.diag(Mf).copy())
    notes = ["spin softening and stress stiffening: off",
             "disks: rigid, axisymmetrised (Ip + m e², Id + m e²/2), one node each "
             "(seat centre) with a rigid offset link"]
    if model.supports:
        ax = [sp.x_mm for sp in model.supports if sp.axial]
        notes.append(f"torsion held at x = {model.x[model.torsion_node]:g} mm"
                     + (f", axial motion at x = {ax[0]:g} mm" if ax else "")
                     + " (as in the static beam model): torsional/axial modes are those of "
                     "the shaft held there")
    if C is not None:
        notes.append("bearing damping on: frequencies are damped natural frequencies")
    return RotorModel(name=model.name, beam=model, disks=tuple(disks), M=Mf, K=Kf, G=Gf, C=Cf,
                      free=free, labelling=lab, notes=tuple(notes), K_support=Ks[sub])


def support_energy_share(rotor: RotorModel, vecs: np.ndarray) -> np.ndarray:
    """Share of each mode's strain energy stored in the bearing springs, Re(vᴴ K_s v) /
    Re(vᴴ K v) per column of ``vecs`` (free dofs): near 1 = a bearing mode (the shaft moves
    almost as a rigid body on its springs), near 0 = shaft bending/torsion."""
    if getattr(rotor, "K_support", None) is None:
        return np.zeros(vecs.shape[1])
    num = np.einsum("ij,ij->j", vecs.conj(), rotor.K_support @ vecs).real
    den = np.einsum("ij,ij->j", vecs.conj(), rotor.K @ vecs).real
    return num / den


def rotor_from_variant(variant, *, max_element_mm: float = 5.0, rigid_supports: bool = False,
                       bearing_damping=None) -> RotorModel:
    """Beam rotor model of a balancer-shaft variant: shaft + every attachment as a disk."""
    model = beam.build_model(variant, rigid_supports=rigid_supports,
                             max_element_mm=max_element_mm)
    return build_rotor(model, disks_from_variant(variant), bearing_damping=bearing_damping)


# --------------------------------------------------------------------------- analyses

def campbell(rotor: RotorModel, rpms: Sequence[float], n_modes: int = 12, *,
             orders: Sequence[float] = DEFAULT_ORDERS, tol: float = 1e-6,
             keep_vectors: bool = False) -> CampbellResult:
    """Campbell sweep of the rotor (reduced basis, MAC tracking, whirl labels, criticals)."""
    res = sweep(rotor.K, rotor.M, rotor.G, rpms, n_modes, rotor.labelling, C=rotor.C,
                orders=orders, tol=tol, keep_vectors=keep_vectors)
    from dataclasses import replace

    return replace(res, notes=res.notes + rotor.notes)


def modal(rotor: RotorModel, rpm: float = 0.0, n_modes: int = 12, *,
          keep_vectors: bool = False) -> CampbellResult:
    """Modes at one speed (a one-point sweep)."""
    return campbell(rotor, [rpm], n_modes, keep_vectors=keep_vectors)


@dataclass(frozen=True)
class Verification:
    rpm: float
    freq_reduced_hz: tuple
    freq_full_hz: tuple
    max_rel_diff: float
    n_missed: int = 0         # full-size frequencies below the highest tracked one, unmatched


def speed_index(res: CampbellResult, rpm: float | None = None) -> int:
    """Index of ``rpm`` among the sweep's speeds (default: the highest speed)."""
    if rpm is None:
        return int(np.argmax(res.rpm))
    hits = np.flatnonzero(np.isclose(res.rpm, rpm))
    if hits.size == 0:
        raise InputError("verify", "rpm", "one of the sweep's speeds", got=rpm)
    return int(hits[0])


def compare_with_full(res: CampbellResult, i: int, freq_full_hz: np.ndarray) -> Verification:
    """The reduced sweep's frequencies at speed index ``i`` against the full-size ones: each
    tracked frequency against the nearest full-size one (the tracked branches are the n lowest
    at the first speed, not necessarily the n lowest at this one); full-size frequencies below
    the highest tracked one that match none are counted as missed."""
    f_all = np.asarray(freq_full_hz, dtype=float)
    f_red = np.sort(res.freq_hz[i])
    f_full = f_all[np.argmin(np.abs(f_all[None, :] - f_red[:, None]), axis=1)]
    diff = float(np.max(np.abs(f_red - f_full) / f_full))
    below = f_all[f_all <= f_red.max() * (1 + 1e-6)]
    matched = np.min(np.abs(below[:, None] - f_red[None, :]) / below[:, None], axis=1) < 1e-3
    return Verification(float(res.rpm[i]), tuple(f_red.tolist()), tuple(f_full.tolist()), diff,
                        int(np.count_nonzero(~matched)))


def verify(rotor: RotorModel, res: CampbellResult, rpm: float | None = None) -> Verification:
    """Full-size quadratic eigenproblem at ``rpm`` (default the highest speed of ``res``)
    against the reduced sweep's sorted frequencies at that speed."""
    i = speed_index(res, rpm)
    n = res.freq_hz.shape[1]
    s = full_qep(rotor.K, rotor.M, rotor.G, float(rpm_to_rad_s(res.rpm[i])), n + 6, C=rotor.C)
    return compare_with_full(res, i, s.imag / TWO_PI)
