"""Synchronous forward whirl of the beam rotor: the co-rotating static (spin softening done
completely) and the full stationary-frame unbalance response it approximates.

Co-rotating static (the beam path's spin softening, ``shaftfe.model.spin``):

    (K − ω² S) u = ω² f₁,    S = M_⊥ᵇ + Σ_parts Tᵀ S_p T

* K: the shaft's Timoshenko stiffness and the bearings' springs (held dofs removed), as in the
  static beam model;
* M_⊥ᵇ: the shaft's consistent transverse mass, with its section's net tilt term: in forward
  synchronous whirl the rotary inertia ρ I (softening) and the gyroscopic ρ I_p = 2 ρ I
  (stiffening) leave +ω² ρ I, i.e. the rotary-inertia matrix with its sign turned
  (``elements.timoshenko_bending_mass`` with −ρ I);
* each part (``SpinningPart``): its mass at the centroid through the rigid link from the seat
  centre's node (v_c = v + d θ_z, w_c = w − d θ_y) and its tilt matrix on (θ_y, θ_z);
* f₁: each part's m e at its centroid (the force at the seat node and the moment d × F).

Full response (stationary frame, for the validation): q = a cos ωt + b sin ωt with the beam
rotor's M, G (``beam_rotor.build_rotor``: disks through the same rigid links) and the bearings
as they are (anisotropic springs allowed): (K − ω² M) a + ω² G b = f_c, (K − ω² M) b − ω² G a
= f_s; at t = 0 each unbalance points along its file angle, as in the static model.

Units: mm, N, t, s; rpm for speeds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shaftfe.beam import elements
from shaftfe.beam import model as beam
from shaftfe.beam.elements import NDOF, RY, RZ, UY, UZ
from shaftfe.errors import SolverError
from shaftfe.model.spin import DEFAULT_PART_MODEL, spinning_parts
from shaftfe.util.units import omega

_XY = np.array([UY, RZ, NDOF + UY, NDOF + RZ])
_XZ = np.array([UZ, RY, NDOF + UZ, NDOF + RY])
_XZ_SIGN = np.array([1.0, -1.0, 1.0, -1.0])


def _link(model: beam.BeamModel, x_seat: float, d: float) -> tuple[np.ndarray, np.ndarray]:
    """(dofs (4,), T (4, 4)): the seat node's (v, w, θ_y, θ_z) and the rigid link to the
    centroid's (v_c, w_c, θ_y, θ_z)."""
    n = beam._node(model.x, x_seat)
    idx = NDOF * n + np.array([UY, UZ, RY, RZ])
    T = np.eye(4)
    T[0, 3] = d
    T[1, 2] = -d
    return idx, T


def _shaft_element_softening(L, model: beam.BeamModel, sec) -> np.ndarray:
    """(n, 12, 12) per unit ω²: the translational consistent mass minus the rotary-inertia
    matrix (module docstring), bending dofs only."""
    phi = 12.0 * model.E * sec.I / (sec.kappa * model.G * sec.A * L ** 2)
    mb = elements.timoshenko_bending_mass(L, model.density * sec.A, -model.density * sec.I,
                                          phi)
    me = np.zeros((L.size, 2 * NDOF, 2 * NDOF))
    me[:, _XY[:, None], _XY[None, :]] = mb
    me[:, _XZ[:, None], _XZ[None, :]] = mb * np.outer(_XZ_SIGN, _XZ_SIGN)
    return me


def shaft_softening(model: beam.BeamModel) -> np.ndarray:
    """Dense M_⊥ᵇ per unit ω² of the shaft (``_shaft_element_softening`` assembled)."""
    me = _shaft_element_softening(model.L, model, model.sections)
    ndof = NDOF * model.n_nodes
    S = np.zeros((ndof, ndof))
    dofs = beam._element_dofs(model.n_elements)
    np.add.at(S, (dofs[:, :, None], dofs[:, None, :]), me)
    return S


def parts_softening(model: beam.BeamModel, parts) -> np.ndarray:
    """Dense Σ Tᵀ S_p T per unit ω² of the parts (``SpinningPart``) on their seat nodes."""
    S = np.zeros((NDOF * model.n_nodes,) * 2)
    for p in parts:
        idx, T = _link(model, p.x_seat_mm, p.d_mm)
        Sp = np.zeros((4, 4))
        Sp[0, 0] = Sp[1, 1] = p.mass_t
        Sp[2:, 2:] = p.tilt
        S[np.ix_(idx, idx)] += T.T @ Sp @ T
    return S


def unbalance_load(model: beam.BeamModel, variant, placement: str = "centroid"
                   ) -> tuple[np.ndarray, np.ndarray]:
    """(f_c, f_s) per unit ω² (N s²): every part's m e at its centroid at t = 0 (along its
    angle) and a quarter turn later, moved to its seat node by the rigid link; ``placement``
    "seat": at the seat centre (the seed's placement, no moment)."""
    fc, fs = np.zeros(NDOF * model.n_nodes), np.zeros(NDOF * model.n_nodes)
    for a in variant.attachments:
        me = a.mass_kg * 1e-3 * a.eccentricity_mm
        if me == 0:
            continue
        xs = 0.5 * (a.seat_x_start_mm + a.seat_x_end_mm)
        idx, T = _link(model, xs, a.x_centroid_mm - xs if placement == "centroid" else 0.0)
        al = math.radians(a.angle_deg)
        for f, ang in ((fc, al), (fs, al + 0.5 * math.pi)):
            f[idx] += T.T @ np.array([me * math.cos(ang), me * math.sin(ang), 0.0, 0.0])
    return fc, fs


@dataclass(frozen=True, eq=False)
class SyncResult:
    """The response at t = 0 (full dofs: ``u``; a quarter turn later ``b``, stationary frame
    only), the bearings' |reaction| then, and the collar-type section moments."""
    rpm: float
    u: np.ndarray
    b: np.ndarray | None          # None: the co-rotating static
    bearings_N: dict              # name -> |reaction| at t = 0
    model: beam.BeamModel

    def moment_Nmm(self, x_mm: float) -> float:
        """|M| at the node at x, at the end of the element left of it: the element's end force
        K_e u_e minus its own inertia (co-rotating: ω² S_e u_e; stationary: ω² (M_e a − G_e b))."""
        m = self.model
        e = beam._node(m.x, x_mm) - 1
        sec = _slice(m.sections, e)
        L = m.L[e:e + 1]
        idx = NDOF * e + np.arange(2 * NDOF)
        w2 = omega(self.rpm) ** 2
        f = elements.element_stiffness(L, m.E, m.G, sec)[0] @ self.u[idx]
        if self.b is None:
            f = f - w2 * _shaft_element_softening(L, m, sec)[0] @ self.u[idx]
        else:
            from shaftfe.rotordynamics.beam_rotor import element_gyroscopic
            f = (f - w2 * elements.element_mass(L, m.density, m.G, m.E, sec)[0] @ self.u[idx]
                 + w2 * element_gyroscopic(L, m.density, m.E, m.G, sec)[0] @ self.b[idx])
        return float(math.hypot(f[NDOF + RY], f[NDOF + RZ]))


def _slice(sec, e):
    from dataclasses import fields, replace
    return replace(sec, **{f.name: getattr(sec, f.name)[e:e + 1] for f in fields(sec)})


def _bearing_forces(model: beam.BeamModel, u: np.ndarray) -> dict:
    out = {}
    for s in model.supports:
        b = NDOF * s.node
        k = np.asarray(s.K_N_per_mm, dtype=float)
        out[s.name] = float(np.linalg.norm(k @ u[[b + UY, b + UZ]]))
    return out


def corotating_static(variant, rpm: float, *, part_model: str = DEFAULT_PART_MODEL,
                      shaft: bool = True, parts: bool = True, max_element_mm: float = 5.0,
                      placement: str = "centroid") -> SyncResult:
    """The co-rotating static at ``rpm`` (module docstring); ``shaft``/``parts`` False leave
    out their softening (both False: the unsoftened solution at ``rpm``); ``placement`` of the
    unbalance loads as ``unbalance_load``."""
    model = beam.build_model(variant, max_element_mm=max_element_mm)
    K = beam.assemble_stiffness(model) + beam.support_stiffness(model)[0]
    fixed = beam.support_stiffness(model)[1]
    S = np.zeros_like(K)
    if shaft:
        S += shaft_softening(model)
    if parts:
        S += parts_softening(model, spinning_parts(variant, part_model))
    w2 = omega(rpm) ** 2
    fc, _ = unbalance_load(model, variant, placement)
    free = np.setdiff1d(np.arange(K.shape[0]), fixed)
    A = (K - w2 * S)[np.ix_(free, free)]
    try:                           # positive definite below the softened rotor's first critical
        c = np.linalg.cholesky(0.5 * (A + A.T))
    except np.linalg.LinAlgError:
        raise SolverError(f"spin softening (beam): {rpm:g} rpm is at or above a critical speed "
                          "of the softened rotor; the co-rotating static solution does not "
                          "exist") from None
    u = np.zeros(K.shape[0])
    u[free] = np.linalg.solve(c.T, np.linalg.solve(c, fc[free] * w2))
    return SyncResult(rpm, u, None, _bearing_forces(model, u), model)


def stationary_response(variant, rpm: float, *, part_model: str = "own_inertia",
                        max_element_mm: float = 5.0) -> SyncResult:
    """The full synchronous unbalance response (stationary frame, module docstring) at t = 0,
    undamped, disks with the axisymmetric inertias of ``part_model`` ("own_inertia" or
    "axisymmetrised": a disk cannot take the anisotropic rigid-body term)."""
    from shaftfe.rotordynamics.beam_rotor import Disk, build_rotor
    model = beam.build_model(variant, max_element_mm=max_element_mm)
    disks = []
    for p, a in zip(spinning_parts(variant, part_model),
                    [a for a in variant.attachments if a.mass_kg > 0], strict=True):
        ip = a.polar_inertia_kg_mm2 * 1e-3 + (p.mass_t * a.eccentricity_mm ** 2
                                              if part_model == "axisymmetrised" else 0.0)
        id_ = float(p.tilt[0, 0]) + ip
        disks.append(Disk(p.name, p.x_seat_mm + p.d_mm, p.x_seat_mm, p.mass_t, ip, id_))
    rot = build_rotor(model, disks)
    fc, fs = unbalance_load(model, variant)
    W = omega(rpm)
    w2 = W * W
    A = rot.K - w2 * rot.M
    B = w2 * rot.G
    n = rot.n_dof
    big = np.block([[A, B], [-B, A]])
    ab = np.linalg.solve(big, np.concatenate([fc[rot.free], fs[rot.free]]) * w2)
    u = rot.full_vector(ab[:n])
    return SyncResult(rpm, u, rot.full_vector(ab[n:]), _bearing_forces(model, u), model)
