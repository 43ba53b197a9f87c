"""The rotating frame for the rpm² loads: what each spinning part adds to the co-rotating static
problem (one model, used by the 3D, beam and axisymmetric paths).

In the frame that turns with the shaft at ω, the synchronous forward whirl of an unbalanced
rotor on isotropic supports is a static problem: the centrifugal field ρ ω² (y, z) is a load on
the undeformed rotor (the unbalance, m e ω² at each part's centroid) plus a negative stiffness
on its motion (spin softening). For a rigid part the centrifugal potential is exact:

    V = −½ ω² ∫ρ (y² + z²) dV = −½ ω² [ m |e + ū_c|² + I_xx(θ) ]

with ū_c the motion of the part's centroid and I_xx(θ) the part's moment of inertia about the
spin-parallel axis through its centroid once tilted by θ. To second order in the seat's motion
(translation u, tilt θ = (θ_y, θ_z) of the seat's remote point at x_seat):

* the part's mass at its CENTROID: ū_c = u + θ × (d, e, 0), d = x_c − x_seat, whose transverse
  part is (u_y + d θ_z, u_z − d θ_y): a negative spring −m ω² there (this carries the m d²
  tilt inertia and the translation-tilt coupling of the offset centroid);
* its own tilt inertia: I_xx(θ) = I_p + (I_d − I_p)(θ_y² + θ_z²), I_d, I_p about its own
  centroid (as the variant file gives them): a tilt spring −(I_d − I_p) ω² on the seat's
  rotation, stiffening for a disk (I_p > I_d: the gyroscopic stiffening of forward
  synchronous whirl seen from the rotating frame);
* the eccentric centroid's own second-order term: tilting about the axis n ⊥ e (in the y-z
  plane) swings the centroid toward the spin axis, m |e + ū_c|² loses m e² θ_n²: a tilt spring
  −m e² ω² about n only. This is the chosen model ("exact rigid body"): for x2_57's
  counterweights m e² (64 and 98 kg·mm²) is 12 and 1.6 times |I_d − I_p|, so dropping it
  ("own inertia": A) or averaging it over the two planes as the beam rotor's Campbell disks do
  (I_p + m e², I_d + m e²/2: "axisymmetrised": B, the form a rotordynamics code with
  axisymmetric disks can take) changes the increments by as much as the softening itself. In
  the co-rotating frame the part is at rest, so the anisotropic form is as exact as the
  isotropic ones; in the stationary frame it is a parametric (time-varying) term, which is why
  Campbell diagrams average it (B).

A twist θ_x about the spin axis leaves V unchanged (a rotation about the axis keeps every
radius): no term. The shaft's own mass softens by −ω² M_⊥ (its consistent mass on the
transverse displacements; the paths say how they take it).

Limits: exact for isotropic supports. With anisotropic bearings (x2_57's K_yz ≠ 0) the
bearings turn in the co-rotating frame and the true response has a backward (2ω) part the
static model leaves out: measured against the full stationary-frame response in
tests/validation/test_spin_softening_ross.py.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

PART_MODELS = ("rigid_body", "own_inertia", "axisymmetrised", "seat_mass")
DEFAULT_PART_MODEL = "rigid_body"


@dataclass(frozen=True)
class SpinningPart:
    """A part's co-rotating softening per unit ω²: its mass (t) at the centroid offset
    ``d_mm`` = x_c − x_seat from its seat's remote point, and the 2×2 tilt matrix (t·mm²) on the
    seat's (θ_y, θ_z): the negative tilt stiffness is ω² × ``tilt``."""
    name: str
    x_seat_mm: float
    d_mm: float
    mass_t: float
    tilt: np.ndarray            # (2, 2) symmetric, t·mm²; may be indefinite (stiffening)


def spinning_part(a, model: str = DEFAULT_PART_MODEL) -> SpinningPart:
    """The softening of attachment ``a`` (``shaftfe.model.variant.Attachment``) under the part
    model ``model`` (module docstring): ``rigid_body`` (chosen), ``own_inertia`` (drops the
    eccentric centroid's m e²), ``axisymmetrised`` (its plane average, as a Campbell disk)."""
    if model not in PART_MODELS:
        raise ValueError(f"part model {model!r} not in {PART_MODELS}")
    m = a.mass_kg * 1e-3
    ip, id_ = a.polar_inertia_kg_mm2 * 1e-3, a.diametral_inertia_kg_mm2 * 1e-3
    me2 = m * a.eccentricity_mm ** 2
    tilt = (id_ - ip) * np.eye(2)
    if model == "rigid_body":
        al = math.radians(a.angle_deg)
        n = np.array([-math.sin(al), math.cos(al)])       # (θ_y, θ_z) axis ⊥ e in the y-z plane
        tilt = tilt - me2 * np.outer(n, n)
    elif model == "axisymmetrised":
        tilt = tilt - 0.5 * me2 * np.eye(2)
    xs = 0.5 * (a.seat_x_start_mm + a.seat_x_end_mm)
    if model == "seat_mass":
        return SpinningPart(a.name, float(xs), 0.0, m, np.zeros((2, 2)))
    return SpinningPart(a.name, float(xs), float(a.x_centroid_mm - xs), m, tilt)


def spinning_parts(variant, model: str = DEFAULT_PART_MODEL) -> tuple[SpinningPart, ...]:
    """Every attachment with mass (the parts that spin with the shaft)."""
    return tuple(spinning_part(a, model) for a in variant.attachments if a.mass_kg > 0)


def centroid_rows(R6: np.ndarray, d_mm: float) -> np.ndarray:
    """(2, n) rows of the centroid's transverse motion (u_y + d θ_z, u_z − d θ_y) from the six
    rigid rows (u_x, u_y, u_z, θ_x, θ_y, θ_z) of the seat's remote point."""
    return np.vstack([R6[1] + d_mm * R6[5], R6[2] - d_mm * R6[4]])


def part_rows(R6: np.ndarray, part: SpinningPart) -> tuple[np.ndarray, np.ndarray]:
    """(rows (k, n), weights (k,)) of a part's softening per unit ω² as Σ w_i r_i r_iᵀ: the
    centroid's two translation rows with weight m, and the tilt rows (θ_y, θ_z) rotated onto
    the tilt matrix's eigenvectors with its eigenvalues as weights (zero weights dropped)."""
    lam, vec = np.linalg.eigh(part.tilt)
    tilt_rows = vec.T @ R6[[4, 5]]
    keep = np.abs(lam) > 0
    rows = np.vstack([centroid_rows(R6, part.d_mm), tilt_rows[keep]])
    return rows, np.concatenate([[part.mass_t, part.mass_t], lam[keep]])
