"""Section properties and two-node Timoshenko shaft elements of the stepped beam model.

Degrees of freedom
------------------
6 dof per node, in this order: u_x (axial), u_y, u_z, θ_x (torsion), θ_y, θ_z. Rotations are
right-handed about the axes, so θ_z = dv/dx and θ_y = −dw/dx for Euler-Bernoulli kinematics.

Element
-------
Two-node Timoshenko beam with "interdependent interpolation" (IIE; Przemieniecki, *Theory of
Matrix Structural Analysis*, 1968, §5.6; Friedman & Kosmatka, Comput. Struct. 47 (1993)
473-481). Its stiffness is the exact flexibility inverse of a uniform Timoshenko beam, so nodal
displacements are exact for point loads at nodes (and for uniform distributed loads with the
consistent nodal loads of ``shaftfe.beam.model``) on a piecewise-uniform shaft.
Φ = 12 EI/(κ G A L²). The consistent mass has translational and rotary-inertia parts
(Przemieniecki 1968, §11; Friedman & Kosmatka 1993).

Sections
--------
* Shear coefficient: Cowper, J. Appl. Mech. 33 (1966) 335-340, Table 1: solid circle
  κ = 6(1+ν)/(7+6ν); hollow circle κ = 6(1+ν)(1+m²)² / [(7+6ν)(1+m²)² + (20+12ν)m²], m = d_i/D.
* Hex socket (``Variant.hex_socket``): the section is the circle minus the regular hexagon of
  across-flats s, with its EXACT area A = πD²/4 − (√3/2)s² and second moment
  I = πD⁴/64 − 5√3 s⁴/144 (a regular hexagon's I is the same about every centroidal axis).
  Torsion constant J = 2I (polar moment; slightly overestimates the Saint-Venant constant of a
  non-circular hole) and κ from Cowper's hollow circle with the equal-area hole diameter.
  Bending stress there uses W = I/(D/2).

Units: mm, N, MPa, t/mm³. Pure NumPy, vectorised over elements.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

NDOF = 6
UX, UY, UZ, RX, RY, RZ = range(NDOF)
DOF_NAMES = ("axial translation (x)", "translation in y", "translation in z",
             "torsion (rotation about x)", "rotation about y", "rotation about z")


# --------------------------------------------------------------------------- sections

def cowper_kappa(nu, m=0.0):
    """Cowper (1966) shear coefficient of a (hollow) circle, m = inner/outer diameter."""
    nu = np.asarray(nu, dtype=float)
    m2 = np.asarray(m, dtype=float) ** 2
    a = (1.0 + m2) ** 2
    return 6.0 * (1.0 + nu) * a / ((7.0 + 6.0 * nu) * a + (20.0 + 12.0 * nu) * m2)


def hexagon_area_inertia(s):
    """Area and centroidal second moment of a regular hexagon with across-flats ``s``."""
    s = np.asarray(s, dtype=float)
    return 0.5 * math.sqrt(3.0) * s**2, 5.0 * math.sqrt(3.0) / 144.0 * s**4


@dataclass(frozen=True, eq=False)
class Sections:
    """Per-element section properties (arrays of length n_elements)."""
    D: np.ndarray        # outer diameter, mm
    A: np.ndarray        # area, mm²
    I: np.ndarray        # second moment (isotropic), mm⁴  # noqa: E741
    J: np.ndarray        # torsion constant, mm⁴
    kappa: np.ndarray    # shear coefficient
    W: np.ndarray        # bending section modulus I/(D/2), mm³
    Wt: np.ndarray       # torsion section modulus J/(D/2), mm³
    hollow: np.ndarray   # bool: hex socket


def section_properties(D, nu: float, hex_af=None) -> Sections:
    """Solid circle of diameter D, or circle minus hexagon (across-flats ``hex_af``, 0 = none)."""
    D = np.asarray(D, dtype=float)
    s = np.zeros_like(D) if hex_af is None else np.broadcast_to(np.asarray(hex_af, float), D.shape)
    A_h, I_h = hexagon_area_inertia(s)
    A = 0.25 * math.pi * D**2 - A_h
    I = math.pi * D**4 / 64.0 - I_h  # noqa: E741
    J = 2.0 * I
    m = np.sqrt(4.0 * A_h / math.pi) / D
    kappa = cowper_kappa(nu, m)
    return Sections(D=D, A=A, I=I, J=J, kappa=kappa, W=I / (0.5 * D), Wt=J / (0.5 * D),
                    hollow=s > 0)


# --------------------------------------------------------------------------- elements

def timoshenko_bending_stiffness(L, EI, kGA):
    """(n, 4, 4) IIE Timoshenko stiffness for one plane, dofs (v1, θ1, v2, θ2), θ = dv/dx."""
    L, EI, kGA = (np.asarray(v, dtype=float) for v in (L, EI, kGA))
    phi = 12.0 * EI / (kGA * L**2)
    c = EI / ((1.0 + phi) * L**3)
    k = np.empty((*L.shape, 4, 4))
    L2 = L**2
    k[..., 0, :] = np.stack([12 + 0 * L, 6 * L, -12 + 0 * L, 6 * L], -1)
    k[..., 1, :] = np.stack([6 * L, (4 + phi) * L2, -6 * L, (2 - phi) * L2], -1)
    k[..., 2, :] = np.stack([-12 + 0 * L, -6 * L, 12 + 0 * L, -6 * L], -1)
    k[..., 3, :] = np.stack([6 * L, (2 - phi) * L2, -6 * L, (4 + phi) * L2], -1)
    return k * c[..., None, None]


# local dof indices (of the 12) for the two bending planes
_XY = np.array([UY, RZ, NDOF + UY, NDOF + RZ])
_XZ = np.array([UZ, RY, NDOF + UZ, NDOF + RY])
_XZ_SIGN = np.array([1.0, -1.0, 1.0, -1.0])   # θ_y = −dw/dx


def element_stiffness(L, E, G, sec: Sections):
    """(n, 12, 12) stiffness of 3D Timoshenko shaft elements (dofs per node: ux uy uz rx ry rz).

    Written per element so that a consistent mass and gyroscopic matrix can be assembled the
    same way later (rotor dynamics)."""
    L = np.asarray(L, dtype=float)
    n = L.shape[0]
    k = np.zeros((n, 2 * NDOF, 2 * NDOF))
    ea = E * sec.A / L
    gj = G * sec.J / L
    for (i, j), sgn in (((UX, UX), 1), ((UX, NDOF + UX), -1), ((NDOF + UX, UX), -1),
                        ((NDOF + UX, NDOF + UX), 1)):
        k[:, i, j] = sgn * ea
    for (i, j), sgn in (((RX, RX), 1), ((RX, NDOF + RX), -1), ((NDOF + RX, RX), -1),
                        ((NDOF + RX, NDOF + RX), 1)):
        k[:, i, j] = sgn * gj
    kb = timoshenko_bending_stiffness(L, E * sec.I, sec.kappa * G * sec.A)
    k[:, _XY[:, None], _XY[None, :]] = kb
    k[:, _XZ[:, None], _XZ[None, :]] = kb * np.outer(_XZ_SIGN, _XZ_SIGN)
    return k


def timoshenko_bending_mass(L, rhoA, rhoI, phi):
    """(n, 4, 4) consistent mass of the IIE Timoshenko element, dofs (v1, θ1, v2, θ2):
    translational + rotary inertia parts (Przemieniecki 1968, §11; Friedman & Kosmatka 1993)."""
    L, rhoA, rhoI, p = (np.asarray(v, dtype=float) for v in (L, rhoA, rhoI, phi))
    p2 = p**2
    ct = rhoA * L / (1.0 + p) ** 2
    t11 = 13 / 35 + 7 * p / 10 + p2 / 3
    t12 = (11 / 210 + 11 * p / 120 + p2 / 24) * L
    t13 = 9 / 70 + 3 * p / 10 + p2 / 6
    t14 = -(13 / 420 + 3 * p / 40 + p2 / 24) * L
    t22 = (1 / 105 + p / 60 + p2 / 120) * L**2
    t24 = -(1 / 140 + p / 60 + p2 / 120) * L**2
    mt = np.stack([np.stack([t11, t12, t13, t14], -1),
                   np.stack([t12, t22, -t14, t24], -1),
                   np.stack([t13, -t14, t11, -t12], -1),
                   np.stack([t14, t24, -t12, t22], -1)], -2) * ct[..., None, None]
    cr = rhoI / ((1.0 + p) ** 2 * L)
    r11 = 6 / 5 + 0 * L
    r12 = (1 / 10 - p / 2) * L
    r22 = (2 / 15 + p / 6 + p2 / 3) * L**2
    r24 = (-1 / 30 - p / 6 + p2 / 6) * L**2
    mr = np.stack([np.stack([r11, r12, -r11, r12], -1),
                   np.stack([r12, r22, -r12, r24], -1),
                   np.stack([-r11, -r12, r11, -r12], -1),
                   np.stack([r12, r24, -r12, r22], -1)], -2) * cr[..., None, None]
    return mt + mr


def element_mass(L, rho, G, E, sec: Sections):
    """(n, 12, 12) consistent mass of the 3D shaft element (axial and torsion linear, bending
    IIE Timoshenko with rotary inertia). Gyroscopic terms are not included (issue 6)."""
    L = np.asarray(L, dtype=float)
    n = L.shape[0]
    m = np.zeros((n, 2 * NDOF, 2 * NDOF))
    for d, c in ((UX, rho * sec.A * L / 6.0), (RX, rho * sec.J * L / 6.0)):
        m[:, d, d] = m[:, NDOF + d, NDOF + d] = 2.0 * c
        m[:, d, NDOF + d] = m[:, NDOF + d, d] = c
    phi = 12.0 * E * sec.I / (sec.kappa * G * sec.A * L**2)
    mb = timoshenko_bending_mass(L, rho * sec.A, rho * sec.I, phi)
    m[:, _XY[:, None], _XY[None, :]] = mb
    m[:, _XZ[:, None], _XZ[None, :]] = mb * np.outer(_XZ_SIGN, _XZ_SIGN)
    return m

