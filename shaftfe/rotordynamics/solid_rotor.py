"""Rotor dynamics of the 3D solid shaft (P2 tets): mass, gyroscopics, rigid attachments,
bearings, and the Campbell sweep in a reduced modal basis (kernels in
``shaftfe.rotordynamics.kernels``).

This module builds the model (``build_solid_rotor``: matrices, attachment bodies, support
terms); its docstring documents the whole solid rotor path, whose code is split by stage in
``shaftfe.rotordynamics``: ``solid_solver`` (``ShiftedSolver``: the shifted factorisation with
the support terms), ``prestress`` (centrifugal prestress, K_g), ``solid_modal``
(``BasisProvider``, ``campbell``, ``modal``, ``full_qep``, ``verify``) and ``modes_vtu`` (mode
shapes as VTU).

Equation of motion (stationary frame, spin Ω about +x):

    M q̈ + (C + Ω G) q̇ + K q = 0,      with hard rows H q = 0 (held motions).

Matrices
--------
* K: linear elasticity of the shaft (``fe.assembly.elasticity_stiffness``, E, ν of the
  variant's shaft material). Stress stiffening: an option, OFF by default like the seed's study
  (section "Centrifugal prestress" below). Spin softening: not applicable in the stationary frame
  (a rotating-frame term; below).
* M: consistent mass ∫ ρ Nᵀ N dV of the P2 solid (quadrature of order 4: exact for straight
  tets), ρ of the shaft material.
* G: gyroscopic (Coriolis) matrix of the solid in the stationary frame, for an axisymmetric
  rotor. Derivation: describe the displacement u(x, t) (inertial components) at the spatial
  point x that the material occupies at rest; material flows through x with the velocity
  Ω w(x), w = e_x × x = (0, −z, y). A particle's position is x + u(x, t), its velocity
  ṗ = Ω w + ∂u/∂t + Ω ∂u/∂θ with ∂u/∂θ = (∇u) w = −z ∂u/∂y + y ∂u/∂z. The kinetic energy
  ½ ∫ ρ |ṗ|² dV has the cross term Ω ∫ ρ u̇ · ∂u/∂θ dV = Ω q̇ᵀ A q with
  A = ∫ ρ Nᵀ (∂N/∂θ) dV; Lagrange's equations turn it into Ω (A − Aᵀ) q̇, so

      G = A − Aᵀ = kron(S − Sᵀ, I₃),   S_ab = ∫ ρ φ_a (−z ∂_y φ_b + y ∂_z φ_b) dV

  (each Cartesian component couples with itself; for an axisymmetric body S is already
  skew, ∫ φ_a ∂_θ φ_b = −∫ φ_b ∂_θ φ_a, so G = 2A = 2 ∫ ρ Nᵀ ∂_θ N dV). The Ω² terms of the
  same expansion (½ Ω² ∫ ρ |∂u/∂θ|²) are of the order of the centrifugal geometric terms and
  are dropped with them, or kept with them (option ``stress_stiffening``, below). Check:
  projected on the rigid tilts of a body, G gives G[θ_y, θ_z] = ∫ ρ (y² + z²) dV = I_p, the
  rigid-disk gyroscopic term of ``shaftfe.rotordynamics.beam_rotor`` (tested). Not valid for a
  non-axisymmetric body (keyways, the hex socket: small, their mass is < 1 % of the shaft).
* Bearings: ``shaftfe.fe.supports`` exactly as in the static model (RBE3 remote point at the seat
  centre, 2×2 radial spring, θ_x held at every bearing ("all") and u_x at the axial one as
  hard rows, tilt free); optional isotropic damping c on the remote point's (u_y, u_z).
* Attachments (gear, counterweights, nuts, …): every part is a rigid body with its mass,
  centroid offset and inertia (``beam_rotor.disks_from_variant``: axisymmetrised Ip + m e²,
  Id + m e²/2; polar inertia → gyroscopic block G[θ_y, θ_z] = Ip). Parts on the same seat form
  one body at the seat centre. Tie to the seat faces (``load:<part>:pressed|free``):

  - ``coupling="rigid"`` (default; RBE2-like, kinematic): every node of the seat faces follows
    the body, u_i = u_m + θ_m × (x_i − x_m) (master-slave elimination, q = [free nodes,
    6 dofs per body]). It stiffens the seat like a bonded hub: a press-fitted and keyed hub
    (gear hub, counterweight hub, nuts clamped on the thread) is much stiffer than the Ø17
    shaft under it (hub ring Ø24/Ø17: 3× the shaft's EI), and the seed's Ansys model bonded
    the parts' solids to the shaft.
  - ``coupling="distributing"`` (RBE3-like): the body follows the area-weighted least-squares
    rigid motion of the seat; adds no stiffness (a loose or very soft hub). Mass and
    gyroscopic blocks Rᵀ M_b R on the seat dofs (sparse, one clique per seat).

Centrifugal prestress (option ``stress_stiffening``, default off)
----------------------------------------------------------------
Equation with the option: M q̈ + (C + Ω G) q̇ + (K + Ω² K_g) q = 0, K_g = K_σ,1 − A_θ:

* K_σ,1: geometric (initial-stress) stiffness of the shaft body's centrifugal prestress σ⁰
  at Ω = 1 rad/s, the second variation of ½ ∫ σ⁰_ij ∂_i u_k ∂_j u_k dV (the nonlinear part
  of the Green strain under σ⁰); the same scalar matrix on each component:

      K_σ = kron(S_σ, I₃),   (S_σ)_ab = ∫ σ⁰_ij ∂_i φ_a ∂_j φ_b dV      (``geometric_stiffness``)

  σ⁰ = λ tr ε I + 2 μ ε from the displacement gradient at the quadrature points
  (``quadrature_stress``; order 3, exact on straight P2 tets: σ⁰ and ∂φ are linear) of the
  static solution of the SUPPORTED rotor under the shaft's own body force ρ Ω² (0, y, z)
  (``fe.assembly.body_force_load``). σ⁰ ∝ Ω²: solved once at Ω_ref = 1 rad/s, K_σ(Ω) = Ω² K_σ,1.
* A_θ = kron(∫ ρ ∂_θ φ_a ∂_θ φ_b dV, I₃) (``convective_matrix``): the Ω² term
  ½ Ω² ∫ ρ |∂u/∂θ|² of the kinetic energy above (L = T − V: a stiffness −Ω² A_θ). It
  belongs to the same order as K_σ and must come with it: on a rigid tilt θ_y both give
  Ω² I_p/2 θ_y² (K_σ by the virial identity ∫ σ⁰ dV = ∫ x ⊗ ρ Ω² x_⊥ dV = Ω² diag(0, I_p/2,
  I_p/2) of a traction-free body; A_θ since ∂u/∂θ = y θ_y e_x), so they cancel and a
  spinning rigid body keeps the classical gyroscopic equations without Ω² stiffness; for the
  bending of a slender shaft they cancel to leading order too (the section integral of σ⁰_yy
  is ρ Ω² I, that of ρ |∂u/∂θ|² is ρ I v'², v the deflection). K_σ alone would stiffen a
  spinning rigid rotor's tilt by Ω² I_p/2 (tested in tests/validation/test_stress_stiffening).

Only the shaft body's prestress: the attachments are rigid bodies (no strain); their
eccentric centroids' centrifugal loads rotate with the shaft, a co-rotating unbalance, not
an axisymmetric prestress, and are left out. K_g is projected ONCE on the basis and added as
Ω² Φᵀ K_g Φ to the reduced stiffness at every speed (``campbell.sweep(Kg=…)``); ``full_qep``
adds Ω² K_g to K (the ``--verify`` path). The basis stays the modes at rest (the growth test
at the top speed includes Ω² K_g). Static solve without a second factorisation: iterative
refinement on the basis's factorisation, u ← u + (K_tot + σ² M)⁻¹ (f − K_tot u) with the
Woodbury support terms (hard rows kept); the error contracts by σ²/(ω₁² + σ²) per step
(≈ 0.01 on x2_57); the rigid-body part of a free model's load only adds strain-free motion.

Verified (tests/validation/test_stress_stiffening.py): prescribed σ_xx = T/A on the pinned
cylinder, f(T)/f(0) of bending modes 1-2 within 0.06 % of the pinned Timoshenko beam under
axial load (+21 % tension, −27 % compression); the centrifugal stresses of a free spinning
long cylinder within 1.8 % of the peak of Timoshenko & Goodier's solution (rms 0.6 %); the
virial identity on the rigid tilts (K_σ = A_θ = Ω² I_p/2 within 0.1 %, K_g < 1e-3 I_p);
reduced vs full with K_g < 1e-5. x2_57 coarse at 8000 rpm: von Mises of the prestress
≤ 0.51 MPa, the 12 frequencies change ≤ 3.1e-5 (K_σ alone: ≤ 6.5e-5): off by default.

Spin softening: NOT applicable in the stationary frame. It is the term −Ω² M_⊥ (M_⊥ the mass
of the displacements normal to the spin axis) of the ROTATING-frame equations
M ẍ + 2 Ω G_c ẋ + (K + K_σ − Ω² M_⊥) x = 0; in the stationary-frame formulation used here
(axisymmetric rotor) the rotating frame's Coriolis and spin-softening terms become Ω G and
−Ω² A_θ (above), and adding −Ω² M_⊥ as well would be wrong. (Ansys likewise applies spin
softening only with a rotating reference frame, not with stationary-frame Coriolis.)

Solution
--------
The bearing springs and the hard rows are never assembled into the sparse matrix (dense
cliques); they enter every solve as a low-rank Woodbury term (as in ``shaftfe.static.solve``):
B = K + σ Ω G + σ² M (sparse, SPD at Ω = 0) is factorised ONCE per shift σ, and
(B + U C Uᵀ)⁻¹ with hard rows (C⁻¹ = 0, the exact infinite-stiffness limit) costs one small
dense capacitance solve per right-hand side. Shift σ = −2π f_s (real, f_s = ``shift_hz``): at
Ω = 0 the matrix is K + (2π f_s)² M, positive definite even for a free-free model.

1. Basis (once): the lowest undamped modes by shift-invert Lanczos (``eigsh``, OPinv = the
   Woodbury operator with hard rows, so the modes satisfy H q = 0), mass-normalised; cached
   and reused when the basis grows.
2. Per speed: ``shaftfe.rotordynamics.campbell.sweep`` (projected quadratic eigenproblem, MAC
   tracking, whirl labels, critical speeds), basis size chosen by the convergence test there.
3. ``verify``: the full-size quadratic eigenproblem at the top speed (shift-invert Arnoldi on
   the companion linearisation, one nonsymmetric factorisation of K + σ(C + ΩG) + σ² M with
   the same low-rank terms).

Labels: each mode is mapped to beam-like section motions (least-squares rigid motion of x
slices, with diag(M) weights, plus the attachment bodies): u_x → axial, θ_x → torsional,
(u_y, u_z, θ_y, θ_z) → lateral; the whirl ratio uses the sections' (u_y, u_z) and
(θ_z, −θ_y) pairs (``kernels.Labelling.transform``).

Units: mm, N, t, s. Heavy imports (scikit-fem) inside functions.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np

from shaftfe.errors import InputError
from shaftfe.rotordynamics.kernels import Labelling
from shaftfe.rotordynamics.options import COUPLINGS
from shaftfe.solid.features import seat_halves


@dataclass(frozen=True)
class SolidOptions:
    level: str = "coarse"
    order: int = 2
    coupling: str = "rigid"               # attachments: "rigid" (RBE2) | "distributing" (RBE3)
    rigid_supports: bool = False
    bearing_damping: float = 0.0          # N·s/mm, isotropic, on every bearing
    hold_twist: str = "all"               # θ_x held at "all" bearings | "axial" | "none"
    solver: str = "auto"                  # shaftfe.fe.solvers for the symmetric factorisation
    shift_hz: float = 50.0                # σ = −2π shift_hz
    stress_stiffening: bool = False       # centrifugal prestress Ω² K_g (module docstring)


# --------------------------------------------------------------------------- matrices

def mass_and_gyro(mesh, density: float):
    """Scalar consistent mass Ms = ∫ ρ φ_a φ_b and S = ∫ ρ φ_a ∂_θ φ_b (N × N sparse CSR,
    N = nodes), by order-4 quadrature (exact on straight P2 tets)."""
    from shaftfe.fe import assembly as fem

    phi, dN, wdx = fem.scalar_quadrature(mesh)        # (nloc, nq), (ne,nq,nloc,3), (ne, nq)
    en = fem.element_nodes(mesh)                                               # (nloc, ne)
    xq = np.einsum("iae,aq->eqi", mesh.doflocs[:, en], phi)                    # (ne, nq, 3)
    pw = phi.T[None, :, :] * (density * wdx)[:, :, None]                       # (ne, nq, nloc)
    Me = np.einsum("eqa,bq->eab", pw, phi)
    dth = -xq[:, :, 2:3] * dN[..., 1] + xq[:, :, 1:2] * dN[..., 2]             # (ne, nq, nloc)
    Se = np.einsum("eqa,eqb->eab", pw, dth)
    return fem.assemble_blocks(mesh, Me, 1), fem.assemble_blocks(mesh, Se, 1)


def vector_matrix(Ss):
    """kron(Ss, I₃): the scalar matrix acting on each interleaved component."""
    import scipy.sparse as sp
    return sp.kron(Ss, sp.identity(3), format="csr")


def _rigid_T(points: np.ndarray, center: np.ndarray) -> np.ndarray:
    """(3 n, 6) rigid motions (u, θ) about ``center`` sampled at points (3, n), interleaved."""
    r = points - center[:, None]
    n = points.shape[1]
    T = np.zeros((n, 3, 6))
    T[:, 0, 0] = T[:, 1, 1] = T[:, 2, 2] = 1.0
    T[:, 1, 3], T[:, 2, 3] = -r[2], r[1]          # rotation about x
    T[:, 0, 4], T[:, 2, 4] = r[2], -r[0]          # about y
    T[:, 0, 5], T[:, 1, 5] = -r[1], r[0]          # about z
    return T.reshape(3 * n, 6)


@dataclass(frozen=True, eq=False)
class Body:
    """A rigid attachment body: the parts on one seat, reference point at the seat centre."""
    name: str                     # "gear+screws_cw1+…"
    x_mm: float
    facets: np.ndarray
    M6: np.ndarray                # 6×6 mass at the reference point (u, θ)
    G6: np.ndarray                # 6×6 gyroscopic per unit spin
    mass_t: float


def attachment_bodies(variant, mesh) -> list[Body]:
    from shaftfe.rotordynamics import beam_rotor as rotor

    disks = {d.name: d for d in rotor.disks_from_variant(variant)}
    groups: dict[tuple[float, float], list] = {}
    for a in variant.attachments:
        groups.setdefault((a.seat_x_start_mm, a.seat_x_end_mm), []).append(a)
    out = []
    for (x0, x1), parts in groups.items():
        fac = []
        for a in parts:
            for g in seat_halves(a.name):
                if g not in mesh.boundaries:
                    raise InputError(f"variant {variant.name}", f"attachment {a.name!r}",
                                     "a part whose seat is a named face group of the mesh",
                                     got=g, reason="has no face group")
                fac.append(np.asarray(mesh.boundaries[g]))
        M6, G6 = np.zeros((6, 6)), np.zeros((6, 6))
        for a in parts:
            m6, g6 = rotor.disk_matrices(disks[a.name])
            M6 += m6
            G6 += g6
        out.append(Body("+".join(a.name for a in parts), 0.5 * (x0 + x1),
                        np.unique(np.concatenate(fac)), M6, G6,
                        float(sum(disks[a.name].mass_t for a in parts))))
    return out


# --------------------------------------------------------------------------- model

@dataclass(frozen=True, eq=False)
class LowRank:
    """One support term on rows R (r × n_dof) of q: a spring C (r × r; None = hard rows
    R q = 0) and an optional damping Cd (r × r)."""
    bearing: str
    labels: tuple
    R: np.ndarray
    C: np.ndarray | None
    Cd: np.ndarray | None = None


@dataclass(frozen=True, eq=False)
class BodyTerm:
    """A rigid body on a distributing coupling: its motion is R q (6 × n_dof rows), its mass
    and gyroscopic matrices enter as Rᵀ M6 R and Rᵀ G6 R (never assembled: a dense clique of
    the seat dofs)."""
    name: str
    R: np.ndarray
    M6: np.ndarray
    G6: np.ndarray


@dataclass(frozen=True, eq=False)
class SolidRotor:
    """Matrices on q (mesh dofs, or free mesh dofs + 6 per rigid body) and the support terms.

    ``K``, ``C``, ``K_support`` (and ``M``, ``G`` with a distributing coupling) are
    LinearOperators (sparse part + low-rank terms); ``K_sparse``, ``M_sparse``, ``G_sparse``
    are SciPy sparse. ``T`` maps q to the mesh dofs (None: identity). Hard rows are in
    ``terms`` with ``C is None``."""
    name: str
    variant: object
    shaft_mesh: object
    options: SolidOptions
    K_sparse: object
    M_sparse: object
    G_sparse: object
    terms: tuple
    T: object | None
    bodies: tuple
    labelling: Labelling
    body_terms: tuple = ()
    notes: tuple = field(default_factory=tuple)
    assembly_seconds: float = 0.0
    beam: object = None           # (for the CLI description line) no beam model here

    @property
    def n_dof(self) -> int:
        return self.K_sparse.shape[0]

    @property
    def disks(self) -> tuple:
        return self.bodies

    def _op(self, which: str):
        from scipy.sparse.linalg import LinearOperator

        n = self.n_dof
        base = {"K": self.K_sparse, "M": self.M_sparse, "G": self.G_sparse}.get(which)
        if which in ("M", "G"):
            terms = [(b.R, b.M6 if which == "M" else b.G6) for b in self.body_terms]
        else:
            terms = [(t.R, t.C if which in ("K", "Ks") else t.Cd) for t in self.terms]
        terms = [(R, C) for R, C in terms if C is not None]

        def mv(x):
            x = np.asarray(x)
            y = base @ x if base is not None else np.zeros(x.shape, dtype=np.result_type(
                x, float))
            for R, C in terms:
                y = y + R.T @ (C @ (R @ x))
            return y
        return LinearOperator((n, n), matvec=mv, matmat=mv, rmatvec=mv, dtype=float)

    @property
    def K(self):
        return self._op("K")

    @property
    def M(self):
        return self._op("M") if self.body_terms else self.M_sparse

    @property
    def G(self):
        return self._op("G") if self.body_terms else self.G_sparse

    @property
    def K_support(self):
        return self._op("Ks")

    @property
    def C(self):
        return self._op("C") if any(t.Cd is not None for t in self.terms) else None

    def mesh_vector(self, q: np.ndarray) -> np.ndarray:
        return q if self.T is None else self.T @ q

def _check_options(o: SolidOptions) -> None:
    if o.coupling not in COUPLINGS:
        raise InputError("--coupling", "coupling", " | ".join(COUPLINGS), got=o.coupling)
    from shaftfe.fe.supports import HOLD_TWIST
    if o.hold_twist not in HOLD_TWIST:
        raise InputError("options", "hold_twist", " | ".join(HOLD_TWIST), got=o.hold_twist)
    if not (math.isfinite(o.bearing_damping) and o.bearing_damping >= 0):
        raise InputError("--bearing-damping", "bearing damping", ">= 0 N s/mm",
                         got=o.bearing_damping)
    if not (math.isfinite(o.shift_hz) and o.shift_hz > 0):
        raise InputError("options", "shift_hz", "> 0 Hz", got=o.shift_hz)
    from shaftfe.fe.solvers import METHODS
    if o.solver not in METHODS:
        raise InputError("--solver", "solver", " | ".join(METHODS), got=o.solver)


def build_solid_rotor(variant, options: SolidOptions = SolidOptions(), *, shaft_mesh=None,
                      support_faces: dict | None = None, supported: bool = True,
                      attachments: bool = True, cache_dir=None) -> SolidRotor:
    """Assemble the solid rotor of ``variant`` (mesh built at ``options.level`` unless given).

    ``support_faces``: bearing name → face group (default ``bearing:<name>``; e.g. an end face
    for a validation model). ``supported=False``: no bearings (free-free validation models).
    ``attachments=False``: the bare shaft."""
    from shaftfe.fe import assembly as fem
    from shaftfe.model.validate import validate_variant

    _check_options(options)
    validate_variant(variant, springs=supported and not options.rigid_supports,
                     typed=False)
    if shaft_mesh is None:
        from shaftfe.beam.planes import mesh_hot_axes
        from shaftfe.solid.mesh import build_mesh
        shaft_mesh = build_mesh(variant, options.level, options.order, cache_dir=cache_dir,
                                hot_axes=mesh_hot_axes(variant))
    m = shaft_mesh.mesh
    mat = variant.material
    t0 = time.perf_counter()
    K = fem.elasticity_stiffness(m, mat.E_MPa, mat.nu)
    Ms, Ss = mass_and_gyro(m, mat.density_t_mm3)
    M = vector_matrix(Ms)
    G = vector_matrix(Ss - Ss.T)
    bodies = attachment_bodies(variant, m) if attachments else []
    notes = ["spin softening: not applicable in the stationary frame (rotating-frame term)"]
    T = None
    body_rows = []          # (6, n_q) rows giving each body's motion, for the labels
    body_terms = []         # distributing coupling: low-rank mass/gyroscopic terms
    if bodies and options.coupling == "rigid":
        T, K, M, G, body_rows = _tie_rigidly(variant, m, bodies, K, M, G)
        notes.append(f"attachments: {len(bodies)} rigid bodies tied rigidly (RBE2-like) to "
                     "their seat faces (stiffen the seats like bonded hubs)")
    elif bodies:
        body_terms, body_rows = _distributing_bodies(m, bodies)
        notes.append(f"attachments: {len(bodies)} rigid bodies on distributing (RBE3-like) "
                     "couplings to their seat faces (no seat stiffening)")
    terms = []
    if supported:
        terms = _support_terms(variant, m, options, T, support_faces)
        if options.bearing_damping > 0:
            notes.append("bearing damping on: frequencies are damped natural frequencies")
        notes.append(f"bearings: RBE3 remote points, θ_x held at {options.hold_twist} "
                     "bearing(s), u_x at the axial one (as in the static 3D model)")
    K = K.tocsr()
    lab = _labelling(m, Ms, T, body_rows, bodies, M)
    return SolidRotor(variant.name, variant, shaft_mesh, options, K, M, G, tuple(terms), T,
                      tuple(bodies), lab, tuple(body_terms), tuple(notes),
                      time.perf_counter() - t0)


def _tie_rigidly(variant, m, bodies: list[Body], K, M, G):
    """Rigid (RBE2-like) coupling: every seat node follows its body (master-slave elimination,
    q = [free nodes, 6 dofs per body]). Returns the map T (mesh dofs × q), K, M, G on q (with
    the bodies' mass and gyroscopic blocks) and each body's (6, n_q) motion rows."""
    import scipy.sparse as sp

    from shaftfe.fe import assembly as fem

    N3 = K.shape[0]
    body_rows = []
    slave_of = np.full(N3 // 3, -1)
    for k, b in enumerate(bodies):
        nodes = fem.face_nodes(m, b.facets)
        if np.any(slave_of[nodes] >= 0):
            raise InputError(f"variant {variant.name}", "attachment seats",
                             "seats that share no mesh node", got=b.name)
        slave_of[nodes] = k
    keep = np.flatnonzero(slave_of < 0)
    keep_dofs = (3 * keep[:, None] + np.arange(3)).ravel()
    n_q = keep_dofs.size + 6 * len(bodies)
    rows, cols, vals = [keep_dofs], [np.arange(keep_dofs.size)], [np.ones(keep_dofs.size)]
    for k, b in enumerate(bodies):
        nodes = np.flatnonzero(slave_of == k)
        Tn = _rigid_T(m.doflocs[:, nodes], np.array([b.x_mm, 0.0, 0.0]))   # (3n, 6)
        d = (3 * nodes[:, None] + np.arange(3)).ravel()
        c0 = keep_dofs.size + 6 * k
        rows.append(np.repeat(d, 6))
        cols.append(np.tile(c0 + np.arange(6), d.size))
        vals.append(Tn.ravel())
    T = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(N3, n_q))
    Tt = T.T.tocsr()
    K = (Tt @ K @ T).tocsr()
    # the bodies' own 6 × 6 mass and gyroscopic blocks on their q rows, added as one sparse
    # matrix each (a LIL round trip of the whole matrix cost 0.8 s at 84k dofs)
    ri, ci, mv, gv = [], [], [], []
    for k, b in enumerate(bodies):
        idx = keep_dofs.size + 6 * k + np.arange(6)
        ri.append(np.repeat(idx, 6))
        ci.append(np.tile(idx, 6))
        mv.append(np.asarray(b.M6, dtype=float).ravel())
        gv.append(np.asarray(b.G6, dtype=float).ravel())
        Rb = np.zeros((6, n_q))
        Rb[:, idx] = np.eye(6)
        body_rows.append(Rb)
    M = (Tt @ M @ T).tocsr()
    G = (Tt @ G @ T).tocsr()
    if bodies:
        r_, c_ = np.concatenate(ri), np.concatenate(ci)
        M = (M + sp.csr_matrix((np.concatenate(mv), (r_, c_)), shape=M.shape)).tocsr()
        G = (G + sp.csr_matrix((np.concatenate(gv), (r_, c_)), shape=G.shape)).tocsr()
    return T, K, M, G, body_rows


def _distributing_bodies(m, bodies: list[Body]) -> tuple[list[BodyTerm], list[np.ndarray]]:
    """Distributing (RBE3-like) coupling: each body moves with its seat's area-weighted rigid
    fit R q; returns its low-rank mass/gyroscopic terms and its (6, n_dof) motion rows."""
    from shaftfe.fe import assembly as fem

    body_terms, body_rows = [], []
    for b in bodies:
        R6 = fem.rigid_rows(m, b.facets, (b.x_mm, 0.0, 0.0))
        R6[np.abs(R6) < 1e-14 * np.abs(R6).max()] = 0.0
        body_terms.append(BodyTerm(b.name, R6, b.M6, b.G6))
        body_rows.append(R6)
    return body_terms, body_rows


def _support_terms(variant, m, options: SolidOptions, T,
                   support_faces: dict | None) -> list[LowRank]:
    """The bearings' low-rank terms on q (``shaftfe.fe.supports``: RBE3 remote point, springs
    or hard rows, θ_x held as ``options.hold_twist`` says; damping on the remote point's
    (u_y, u_z)), mapped through T when the attachments are tied rigidly."""
    from shaftfe.fe import supports

    if not variant.bearings:
        raise InputError(f"variant {variant.name}", "bearings", "at least one bearing",
                         got=0)
    terms = []
    for brg in variant.bearings:
        hold = options.hold_twist == "all" or (options.hold_twist == "axial" and brg.axial)
        grp = (support_faces or {}).get(brg.name)
        c = supports.couple_bearing(m, brg, rigid=options.rigid_supports, hold_twist=hold,
                                    group=grp)
        for blk in supports.blocks(c):
            R = blk.R if T is None else np.asarray((T.T @ blk.R.T).T)
            Cd = None
            if blk.C is not None and blk.labels == ("u_y", "u_z") \
                    and options.bearing_damping > 0:
                Cd = options.bearing_damping * np.eye(2)
            terms.append(LowRank(blk.bearing, blk.labels, R,
                                 None if blk.C is None else np.asarray(blk.C, float), Cd))
    return terms


def _labelling(mesh, Ms, T, body_rows, bodies, M) -> Labelling:
    """Section motions of x slices (least-squares rigid fit, diag(M) weights) + bodies."""
    import scipy.sparse as sp

    x = mesh.doflocs
    w = np.asarray(Ms.diagonal())
    x0, x1 = float(x[0].min()), float(x[0].max())
    n_sl = int(min(40, max(8, round((x1 - x0) / 5.0))))
    edges = np.linspace(x0, x1, n_sl + 1)
    sl = np.clip(np.searchsorted(edges, x[0], side="right") - 1, 0, n_sl - 1)
    wts = []

    def add_feature_rows(F, mass, J):
        """F (6, ·) rows (u_x, u_y, u_z, θ_x, θ_y, θ_z) → features u_x, u_y, u_z, ρ_p θ_x,
        ρ_t θ_z, −ρ_t θ_y; weights = mass."""
        rp = math.sqrt(max(J[3, 3], 0.0) / mass) if mass > 0 else 1.0
        rt = math.sqrt(max(0.5 * (J[4, 4] + J[5, 5]), 0.0) / mass) if mass > 0 else 1.0
        feats = [F[0], F[1], F[2], rp * F[3], rt * F[5], -rt * F[4]]
        out = []
        for f in feats:
            out.append(f)
            wts.append(mass)
        return out

    blocks = []
    for s in range(n_sl):
        nodes = np.flatnonzero(sl == s)
        if nodes.size < 4:
            continue
        xc = np.array([0.5 * (edges[s] + edges[s + 1]), 0.0, 0.0])
        Phi = _rigid_T(x[:, nodes], xc)                       # (3n, 6)
        W = np.repeat(w[nodes], 3)
        J = Phi.T @ (W[:, None] * Phi)
        try:
            P = np.linalg.solve(J, Phi.T * W[None, :])        # (6, 3n)
        except np.linalg.LinAlgError:
            continue
        d = (3 * nodes[:, None] + np.arange(3)).ravel()
        F = sp.csr_matrix((P.ravel(), (np.repeat(np.arange(6), d.size), np.tile(d, 6))),
                          shape=(6, x.shape[1] * 3))
        if T is not None:
            F = F @ T
        blocks.extend(add_feature_rows([F[i] for i in range(6)], float(W.sum() / 3), J))
    for Rb, b in zip(body_rows, bodies, strict=True):
        Rb = sp.csr_matrix(Rb)
        blocks.extend(add_feature_rows([Rb[i] for i in range(6)], b.mass_t, b.M6))
    Tr = sp.vstack(blocks).tocsr()
    nf = Tr.shape[0]
    kind = np.tile(np.arange(6), nf // 6)
    groups = MappingProxyType({"axial": np.flatnonzero(kind == 0),
                               "torsional": np.flatnonzero(kind == 3),
                               "lateral": np.flatnonzero(np.isin(kind, (1, 2, 4, 5)))})
    py = np.concatenate([np.flatnonzero(kind == 1), np.flatnonzero(kind == 4)])
    pz = np.concatenate([np.flatnonzero(kind == 2), np.flatnonzero(kind == 5)])
    return Labelling(groups=groups, pair_y=py, pair_z=pz, weights=np.array(wts),
                     transform=Tr)
