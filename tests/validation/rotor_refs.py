"""Closed-form and exact reference solutions for the rotor-dynamics validation tests (shared by
the beam and the 3D solid rotor tests; the sources are named in each function).

* Timoshenko beam (Timoshenko, Phil. Mag. 41 (1921) 744; shear coefficient Cowper 1966):
  free-free frequencies from the exact transfer matrix of the uniform beam (Pestel & Leckie,
  *Matrix Methods in Elastomechanics*, 1963), roots of the 2×2 boundary determinant.
* Pinned-pinned spinning Timoshenko shaft (Eshleman & Eubanks, J. Eng. Ind. 91 (1969)
  1180-1188).
* Rigid disk on a massless Euler-Bernoulli cantilever (overhung-disk gyroscopic model;
  Friswell et al., *Dynamics of Rotating Machines*, 2010, §3.6; Vance 1988, §2).
* Uniform rods: axial f_n = n c/(2L), c = √(E/ρ); torsion c_t = √(G/ρ) (free-free);
  fixed-free (2n−1) c/(4L); fixed-fixed n c/(2L) (Rao, *Mechanical Vibrations*, §8.4-8.5).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.linalg import expm
from scipy.optimize import brentq

E, NU, RHO = 210_000.0, 0.3, 7.85e-9
G = E / (2 * (1 + NU))
KAPPA = 6 * (1 + NU) / (7 + 6 * NU)


def rod_speed(modulus: float, rho: float = RHO) -> float:
    """Wave speed √(modulus/ρ) in mm/s (E: axial, G: torsion)."""
    return math.sqrt(modulus / rho)


def timoshenko_free_free(L, D, n_roots, f_max):
    """Exact Timoshenko free-free bending frequencies (Hz) by the transfer matrix."""
    A, I = math.pi * D**2 / 4, math.pi * D**4 / 64  # noqa: E741
    kga, ei = KAPPA * G * A, E * I

    def det(f):
        w2 = (2 * math.pi * f) ** 2
        Amat = np.array([[0, 1, 0, 1 / kga], [0, 0, 1 / ei, 0], [0, -RHO * I * w2, 0, -1],
                         [-RHO * A * w2, 0, 0, 0]])
        T = expm(Amat * L)
        return np.linalg.det(T[2:4, 0:2])

    grid = np.linspace(1.0, f_max, 4000)
    vals = np.array([det(f) for f in grid])
    roots = []
    for a, b, va, vb in zip(grid[:-1], grid[1:], vals[:-1], vals[1:], strict=True):
        if va * vb < 0:
            # to round-off: brentq's rtol floor is 4 eps ≈ 9e-16; 1e-14 and 1e-12 Hz are far
            # below the 1e-6…1e-4 tolerances the tests use against these roots
            roots.append(brentq(det, a, b, xtol=1e-12, rtol=1e-14))
    return np.array(roots[:n_roots])


def pinned_whirl(L, D, n, Omega):
    """(forward, backward) whirl frequencies in Hz of mode n of a pinned-pinned spinning
    Timoshenko shaft (Eshleman & Eubanks 1969)."""
    A, I = math.pi * D**2 / 4, math.pi * D**4 / 64  # noqa: E741
    k = n * math.pi / L
    a, b, c = KAPPA * G * A * k**2, E * I * k**2 + KAPPA * G * A, KAPPA * G * A * k
    p = np.polysub(np.polymul([-RHO * A, 0.0, a], [-RHO * I, 2 * RHO * I * Omega, b]), [c**2])
    r = np.roots(p)
    # real roots: np.roots (companion eigenvalues) leaves spurious imaginary parts ~ eps ×
    # the root's condition; 1e-8 keeps them and drops genuinely complex pairs (|Im| ~ |r|)
    r = r[np.abs(r.imag) < 1e-8 * np.abs(r)].real
    return min(r[r > 0]) / (2 * math.pi), -max(r[r < 0]) / (2 * math.pi)


def overhung_closed_form(L, D, m, Ip, Id, offset, Omega):
    """(forward, backward) lowest whirl frequencies (Hz) of a rigid disk whose centroid sits
    ``offset`` beyond the tip of a massless Euler-Bernoulli cantilever of length L."""
    I = math.pi * D**4 / 64  # noqa: E741
    a = L + offset
    # flexibility of the disk centre (force P and moment at the rigid extension)
    F = np.array([[L**3 / 3 + offset * L**2 + offset**2 * L, L**2 / 2 + offset * L],
                  [L**2 / 2 + offset * L, L]]) / (E * I)
    assert a > 0
    Kc = np.linalg.inv(F)
    k11, k12, k22 = Kc[0, 0], Kc[0, 1], Kc[1, 1]
    # (k11 − m ω²)(k22 − Id ω² + Ip Ω ω) − k12² = 0, ω signed
    p = np.polysub(np.polymul([-m, 0.0, k11], [-Id, Ip * Omega, k22]), [k12**2])
    r = np.roots(p)
    r = r[np.abs(r.imag) < 1e-8 * np.abs(r)].real       # real roots, as in pinned_whirl
    return min(r[r > 0]) / (2 * math.pi), -max(r[r < 0]) / (2 * math.pi)


# Friswell et al. (2010) Example 5.9.9, overhung rotor: shaft 1.5 m × Ø50 mm, bearings
# 10 MN/m at 0 and 1.0 m, disk Ø350 × 70 mm at the free end (1.5 m). Reference numbers (rad/s):
# the ROSS regression values for this example (petrobras/ross, same source as above).
ROSS_599 = {0.0: [90.14, 90.14, 630.73, 630.73, 830.43, 830.43],
            4000.0: [76.19, 103.91, 565.99, 634.23, 647.75, 1174.2]}


EF_599, GF_599, RHO_599 = 211e3, 81.2e3, 7.81e-9      # Friswell et al. (2010) Example 5.9.9


def friswell_599_variants():
    """(model, outline) variants of Example 5.9.9: shaft 1.5 m × Ø50 mm, bearings 10 MN/m at
    x = 0 (on the end face: the outline variant leaves it out, the model's bearing ``a`` is
    tied to ``end:left``) and 1.0 m (10 mm seat), disk Ø350 × 70 mm (bore 50) as a rigid
    attachment on the last 10 mm, centroid at 1.5 m."""
    from shaftfe.model.variant import Attachment, Bearing, Material, Segment, Variant
    from shaftfe.rotordynamics import beam_rotor as rotor

    mat = Material("friswell", EF_599, EF_599 / (2 * GF_599) - 1.0, RHO_599, 1.0, 1.0)
    d = rotor.disk_from_geometry("d", 1500.0, 350.0, 50.0, 70.0, RHO_599)
    att = (Attachment("disk", 1490.0, 1500.0, d.mass_t * 1e3, 0.0, 1500.0,
                      polar_inertia_kg_mm2=d.Ip_t_mm2 * 1e3,
                      diametral_inertia_kg_mm2=d.Id_t_mm2 * 1e3),)
    K = ((10_000.0, 0.0), (0.0, 10_000.0))
    a = Bearing("a", "test", 0.0, 0.0, 1.0, 1.0, K, axial=True)
    b = Bearing("b", "test", 1000.0, 10.0, 1.0, 1.0, K)
    seg = (Segment("s", 0.0, 1500.0, 50.0),)
    return (Variant("f599", "Friswell 5.9.9", seg, (a, b), att, mat, 0.0),
            Variant("f599", "mesh", seg, (b,), att, mat, 0.0))
