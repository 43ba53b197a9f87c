"""Bearing supports as the reference study modelled them (seed 000 §8.3, Ansys "bushing").

Each bearing is a remote point at the centre of its seat (x = seat centre, on the axis), tied
to the seat face ``bearing:<name>`` by a distributing (RBE3-type) coupling: the remote point's six
motions q = (u_x, u_y, u_z, θ_x, θ_y, θ_z) are the area-weighted least-squares rigid motion of the
seat face, q = G u (``fe.assembly.rigid_rows``). The coupling itself adds no stiffness; it only
spreads the support force over the seat. From the remote point to ground:

* radial: a 2×2 spring on (u_y, u_z) with ``Bearing.K_N_per_mm`` (K11, K12, K21, K22); with
  ``rigid=True`` (Inventor-style) u_y = u_z = 0 instead (hard constraint);
* axial: u_x = 0 at every bearing with ``axial=True`` (hard);
* rotation about the shaft axis: θ_x = 0 (hard) at a bearing coupled with ``hold_twist``: in the
  3D static path the bearings that declare ``holds_torsion`` (else one gauge row that carries
  no torque: ``shaftfe.static.model.twist_gauge_block``); the seed removed it at both;
* tilt (θ_y, θ_z): free, unless ``tilt_stiffness_Nmm_per_rad`` > 0 (isotropic tilt spring).

The supports enter the solve as a low-rank term Σ Gᵀ C G (springs) plus hard rows H u = 0
(``SupportBlock``), never assembled into the sparse matrix (it would be a dense clique).

``unrestrained_modes`` checks, before any factorisation, which rigid-body motions of the shaft
the supports do not hold: the 6×6 support stiffness on the rigid modes (hard rows counting as
infinitely stiff) must be positive definite. A (near-)zero direction is named, e.g. "axial
translation u_x": a solver is never trusted to find it (FINDINGS pitfall 8).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shaftfe.fe import assembly as fem
from shaftfe.solid.features import bearing_group

HOLD_TWIST = ("all", "axial", "none")   # bearings that hold θ_x: every one, the axial one, none

MODE_NAMES = ("axial translation u_x", "translation u_y", "translation u_z",
              "rotation about the shaft axis θ_x", "tilt θ_y", "tilt θ_z")
MODE_HINTS = ("mark one bearing with axial = true",
              "add a bearing (radial support)", "add a bearing (radial support)",
              "hold the rotation about the shaft axis at a bearing",
              "add a second bearing or a tilt stiffness",
              "add a second bearing or a tilt stiffness")


@dataclass(frozen=True, eq=False)
class BearingCoupling:
    """One bearing: its seat, remote point and support law."""
    name: str
    x_mm: float                   # remote point (seat centre on the axis)
    facets: np.ndarray
    G: np.ndarray                 # (6, ndof) remote-point rows: q = G u
    K: np.ndarray                 # (2, 2) radial stiffness N/mm on (u_y, u_z)
    tilt_k: float                 # N·mm/rad on θ_y and θ_z (0 = free)
    axial: bool
    hold_twist: bool
    rigid: bool


@dataclass(frozen=True, eq=False)
class SupportBlock:
    """Rows R (m, ndof) of one support term. ``C`` is the m×m spring stiffness (energy
    ½ (R u)ᵀ C (R u)); ``C is None`` means hard rows R u = 0 (infinite stiffness)."""
    bearing: str
    labels: tuple[str, ...]        # "u_y", "u_z", "θ_x", ...
    R: np.ndarray
    C: np.ndarray | None


_DOF = {"u_x": 0, "u_y": 1, "u_z": 2, "θ_x": 3, "θ_y": 4, "θ_z": 5}


def couple_bearing(mesh, bearing, *, rigid: bool = False, hold_twist: bool = True,
                   group: str | None = None) -> BearingCoupling:
    """Build the RBE3 coupling of ``bearing`` (a ``variant.Bearing``) on its seat group."""
    group = group or bearing_group(bearing.name)
    facets = np.asarray(mesh.boundaries[group])
    x = float(bearing.x_center_mm)
    G = fem.rigid_rows(mesh, facets, (x, 0.0, 0.0))
    K = np.asarray(bearing.K_N_per_mm, dtype=float).reshape(2, 2)
    return BearingCoupling(bearing.name, x, facets, G, K,
                           float(bearing.tilt_stiffness_Nmm_per_rad), bool(bearing.axial),
                           hold_twist, rigid)


def blocks(c: BearingCoupling) -> list[SupportBlock]:
    """The support terms of one bearing (springs and hard rows)."""
    out: list[SupportBlock] = []
    hard = []
    if c.rigid:
        hard += ["u_y", "u_z"]
    else:
        out.append(SupportBlock(c.name, ("u_y", "u_z"), c.G[[1, 2]], c.K))
    if c.tilt_k > 0:
        out.append(SupportBlock(c.name, ("θ_y", "θ_z"), c.G[[4, 5]], c.tilt_k * np.eye(2)))
    if c.axial:
        hard.append("u_x")
    if c.hold_twist:
        hard.append("θ_x")
    if hard:
        out.append(SupportBlock(c.name, tuple(hard), c.G[[_DOF[h] for h in hard]], None))
    return out


def unrestrained_modes(block_list: list[SupportBlock], modes: np.ndarray,
                       rtol: float = 1e-9) -> list[str]:
    """Names of the rigid motions the supports leave free.

    ``modes`` (ndof, 6): rigid modes about a point on the axis, with the rotations scaled by a
    length so that all six produce displacements of similar size. The supports' stiffness on
    the modes is Kr = Σ (R Φ)ᵀ C (R Φ) over springs, and hard rows restrict the admissible
    modes to the null space N of H Φ; a free motion is a direction of N where Nᵀ Kr N vanishes
    (relative to the largest spring stiffness)."""
    Kr = np.zeros((6, 6))
    H = [np.zeros((0, 6))]
    scale = 0.0
    for b in block_list:
        RP = b.R @ modes
        if b.C is None:
            H.append(RP / np.maximum(np.abs(RP).max(axis=1, keepdims=True), 1e-300))
        else:
            Kr += RP.T @ b.C @ RP
            scale = max(scale, float(np.abs(b.C).max()))
    Hm = np.vstack(H)
    if Hm.shape[0]:
        _, s, vt = np.linalg.svd(Hm)
        rank = int((s > 1e-8 * max(s.max(initial=0.0), 1.0)).sum())
        N = vt[rank:].T
    else:
        N = np.eye(6)
    if N.shape[1] == 0:
        return []
    w, V = np.linalg.eigh(N.T @ Kr @ N)
    free = []
    for k in np.nonzero(w <= rtol * max(scale, 1e-300))[0]:
        vec = N @ V[:, k]
        j = int(np.argmax(np.abs(vec)))
        name = f"{MODE_NAMES[j]} ({MODE_HINTS[j]})"
        if name not in free:
            free.append(name)
    return free
