"""NumPy kernels of the Fourier-harmonic axisymmetric elements (no Gmsh, no SciPy wrappers).

Body of revolution about x, meridian plane (x, r), angle θ (0 = +y, 90° = +z). A displacement
field is a sum of harmonics n = 0, 1, 2, ... with two parts each (amplitudes on the meridian):

    symmetric      u_x = U_x cos nθ,  u_r = U_r cos nθ,  u_θ =  U_θ sin nθ
    antisymmetric  u_x = V_x sin nθ,  u_r = V_r sin nθ,  u_θ = −V_θ cos nθ

(n = 0: one part, every factor 1: U_x, U_r axisymmetric, U_θ torsion). The antisymmetric part is
the symmetric one turned by 90° about x, so both have the same stiffness. Strains (engineering
shears, order xx, rr, θθ, xr, rθ, xθ) of the symmetric part, with the trig factor shown:

    ε_xx = ∂U_x/∂x                       cos    γ_xr = ∂U_r/∂x + ∂U_x/∂r   cos
    ε_rr = ∂U_r/∂r                       cos    γ_rθ = ∂U_θ/∂r − U_θ/r − n U_r/r   sin
    ε_θθ = (U_r + n U_θ)/r               cos    γ_xθ = ∂U_θ/∂x − n U_x/r          sin

(antisymmetric: normal strains and γ_xr × sin nθ, γ_rθ and γ_xθ × (−cos nθ)). So B = B0 + n B1
and the harmonic stiffness is

    K_n = w_n ∫∫ (B0 + n B1)ᵀ D (B0 + n B1) r dr dx,   w_0 = 2π, w_n = π (n ≥ 1)
        = w_n (K00 + n (K01 + K01ᵀ) + n² K11),

three matrices assembled once for every n. Reference: O. C. Zienkiewicz & R. L. Taylor, The
Finite Element Method, vol. 1 (5th ed.), §10.5 "Axisymmetric solids with non-symmetrical
loading"; E. L. Wilson, "Structural analysis of axisymmetric solids", AIAA J. 3 (1965) 2269.

Elements: 6-node (P2) isoparametric triangles, node order of Gmsh (corners 0, 1, 2, then the
mid-side nodes of edges 01, 12, 20), so the edges on fillet arcs are curved. Boundary edges are
3-node (P2) lines (end, end, middle).
"""

from __future__ import annotations

import numpy as np

# ----------------------------------------------------------------------------- quadrature


def triangle_rule(n: int = 5) -> tuple[np.ndarray, np.ndarray]:
    """Collapsed (Duffy) Gauss rule on the reference triangle (0,0)-(1,0)-(0,1): n² points,
    exact for polynomials of degree 2n − 2 (ξ = a, η = b (1 − a): Gauss–Legendre in a and b,
    Jacobian 1 − a). Returns points (2, n²) and weights (n²) summing to 1/2."""
    g, w = np.polynomial.legendre.leggauss(n)
    g, w = 0.5 * (g + 1.0), 0.5 * w
    a, b = np.meshgrid(g, g, indexing="ij")
    wa, wb = np.meshgrid(w, w, indexing="ij")
    xi, eta = a.ravel(), (b * (1.0 - a)).ravel()
    return np.array([xi, eta]), (wa * wb * (1.0 - a)).ravel()


def line_rule(n: int = 5) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre on [0, 1]: points and weights (sum 1)."""
    g, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (g + 1.0), 0.5 * w


# ----------------------------------------------------------------------------- shape functions

TRI_NODES = np.array([[0.0, 1.0, 0.0, 0.5, 0.5, 0.0],
                      [0.0, 0.0, 1.0, 0.0, 0.5, 0.5]])       # (ξ, η) of the 6 nodes


def tri_p2(xi: np.ndarray, eta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """P2 triangle shape functions N (6, q) and their derivatives dN (2, 6, q) in (ξ, η)."""
    L0, L1, L2 = 1.0 - xi - eta, xi, eta
    N = np.array([L0 * (2 * L0 - 1), L1 * (2 * L1 - 1), L2 * (2 * L2 - 1),
                  4 * L0 * L1, 4 * L1 * L2, 4 * L2 * L0])
    z = np.zeros_like(L0)
    dxi = np.array([-(4 * L0 - 1), 4 * L1 - 1, z, 4 * (L0 - L1), 4 * L2, -4 * L2])
    deta = np.array([-(4 * L0 - 1), z, 4 * L2 - 1, -4 * L1, 4 * L1, 4 * (L0 - L2)])
    dN = np.array([dxi, deta])
    return N, dN


def line_p2(s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """P2 line shape functions (end 0, end 1, middle) on s ∈ [0, 1] and dN/ds, each (3, q)."""
    N = np.array([(1 - s) * (1 - 2 * s), s * (2 * s - 1), 4 * s * (1 - s)])
    dN = np.array([4 * s - 3, 4 * s - 1, 4 - 8 * s])
    return N, dN


# ----------------------------------------------------------------------------- material


def elasticity_matrix(E: float, nu: float) -> np.ndarray:
    """Isotropic D (6×6), strains xx, rr, θθ, xr, rθ, xθ with engineering shears."""
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    D = np.zeros((6, 6))
    D[:3, :3] = lam
    D[[0, 1, 2], [0, 1, 2]] += 2 * mu
    D[[3, 4, 5], [3, 4, 5]] = mu
    return D


# ----------------------------------------------------------------------------- geometry


def element_geometry(X: np.ndarray, R: np.ndarray, pts: np.ndarray):
    """Isoparametric map of elements with node coordinates X, R (ne, 6) at reference points
    (2, q): x, r (ne, q), det J (ne, q), N (6, q) and dN/dx, dN/dr (ne, 6, q)."""
    N, dN = tri_p2(pts[0], pts[1])
    x = X @ N
    r = R @ N
    xa, xb = X @ dN[0], X @ dN[1]                  # ∂x/∂ξ, ∂x/∂η
    ra, rb = R @ dN[0], R @ dN[1]
    det = xa * rb - xb * ra
    # inverse Jacobian: ∂ξ/∂x = rb/det, ∂η/∂x = −ra/det, ∂ξ/∂r = −xb/det, ∂η/∂r = xa/det
    Nx = (dN[0][None] * rb[:, None] - dN[1][None] * ra[:, None]) / det[:, None]
    Nr = (-dN[0][None] * xb[:, None] + dN[1][None] * xa[:, None]) / det[:, None]
    return x, r, det, N, Nx, Nr


def strain_operators(N: np.ndarray, Nx: np.ndarray, Nr: np.ndarray, r: np.ndarray):
    """B0, B1 (ne, q, 6, 18) of the module docstring. Where r = 0 (an evaluation point on the
    axis) N/r is replaced by ∂N/∂r: every 1/r term multiplies a combination that the axis
    conditions make vanish on r = 0 (U_r, U_θ at n = 0; U_x and U_r + U_θ at n = 1; all at
    n ≥ 2), so its limit is the radial derivative (l'Hôpital)."""
    ne, _, q = Nx.shape
    Nb = np.broadcast_to(N[None], Nx.shape)
    with np.errstate(divide="ignore", invalid="ignore"):
        Nor = np.where(r[:, None, :] > 0, Nb / r[:, None, :], Nr)
    B0 = np.zeros((ne, q, 6, 18))
    B1 = np.zeros((ne, q, 6, 18))
    T = (0, 2, 1)                                   # (ne, 6, q) -> (ne, q, 6)
    Nx, Nr, Nor = Nx.transpose(T), Nr.transpose(T), Nor.transpose(T)
    ix, ir, it = np.arange(0, 18, 3), np.arange(1, 18, 3), np.arange(2, 18, 3)
    B0[:, :, 0, ix] = Nx
    B0[:, :, 1, ir] = Nr
    B0[:, :, 2, ir] = Nor
    B0[:, :, 3, ix] = Nr
    B0[:, :, 3, ir] = Nx
    B0[:, :, 4, it] = Nr - Nor
    B0[:, :, 5, it] = Nx
    B1[:, :, 2, it] = Nor
    B1[:, :, 4, ir] = -Nor
    B1[:, :, 5, ix] = -Nor
    return B0, B1


def _strain_coefficients() -> tuple[np.ndarray, np.ndarray]:
    """C0, C1 (6 strains, 3 displacement components, 3 functions): B0 and B1 of
    ``strain_operators`` written in the three functions F = (∂N/∂x, ∂N/∂r, N/r) of a node, so
    that B_k[i, 3a + c] = Σ_f C_k[i, c, f] F_f[a]. Read off ``strain_operators`` itself (one
    element per function, that function 1 at node 0 and the others 0), so the strain
    definitions are written once."""
    N = np.zeros((6, 1))
    N[0] = 1.0                                        # N/r = 1 where r = 1, 0 where r = ∞
    Nx, Nr = np.zeros((3, 6, 1)), np.zeros((3, 6, 1))
    Nx[0, 0], Nr[1, 0] = 1.0, 1.0
    r = np.array([[np.inf], [np.inf], [1.0]])
    B0, B1 = strain_operators(N, Nx, Nr, r)           # (3 functions, 1, 6, 18)
    return (np.ascontiguousarray(B0[:, 0, :, :3].transpose(1, 2, 0)),
            np.ascontiguousarray(B1[:, 0, :, :3].transpose(1, 2, 0)))


def stiffness_blocks(X: np.ndarray, R: np.ndarray, D: np.ndarray, order: int = 4):
    """Element matrices K00, K01, K11 (ne, 18, 18) of the module docstring (without w_n).
    Quadrature: ``triangle_rule(order)`` (default 16 points, degree 6: exact for the
    r-weighted products of a straight element's P2 strains with a polynomial stress, so the
    Saint-Venant fields are reproduced to round-off).

    Evaluated through the node functions F = (∂N/∂x, ∂N/∂r, N/r) (``_strain_coefficients``):
    the integrals G_fg[a, b] = ∫ F_f[a] F_g[b] r dA (9 arrays of 6 × 6 per element) once, then
    K_kl[3a + c, 3b + d] = Σ_fg (C_kᵀ D C_l)[c, f, d, g] G_fg[a, b]; the same sums as
    ∫ B_kᵀ D B_l r dA, regrouped (5× fewer operations than the products of the 6 × 18
    strain operators)."""
    pts, w = triangle_rule(order)
    _, r, det, N, Nx, Nr = element_geometry(X, R, pts)
    if np.any(det <= 0):
        raise ValueError("an element of the meridian mesh is inverted (det J <= 0)")
    ne = r.shape[0]
    with np.errstate(divide="ignore", invalid="ignore"):      # r = 0: as strain_operators
        Nor = np.where(r[:, None, :] > 0, N[None] / r[:, None, :], Nr)
    F = np.stack([Nx, Nr, Nor])                                # (3, ne, 6, q)
    wq = det * r * w[None]                                     # (ne, q)
    G = np.einsum("feaq,gebq->fgeab", F * wq[None, :, None, :], F, optimize=True)
    C0, C1 = _strain_coefficients()
    out = []
    for A, B in ((C0, C0), (C0, C1), (C1, C1)):
        E = np.einsum("icf,ij,jdg->cfdg", A, D, B)
        out.append(np.einsum("cfdg,fgeab->eacbd", E, G, optimize=True).reshape(ne, 18, 18))
    return tuple(out)


# ----------------------------------------------------------------------------- boundary


def edge_geometry(X: np.ndarray, R: np.ndarray, s: np.ndarray):
    """P2 boundary edges with node coordinates X, R (m, 3) at parameters s (q): x, r (m, q),
    the length element |dX/ds| (m, q), the unit tangent (2, m, q) and N (3, q)."""
    N, dN = line_p2(s)
    x, r = X @ N, R @ N
    dx, dr = X @ dN, R @ dN
    J = np.hypot(dx, dr)
    return x, r, J, np.array([dx / J, dr / J]), N, dN


def edge_load(X: np.ndarray, R: np.ndarray, traction, order: int = 6) -> np.ndarray:
    """∫ T · N r ds on each edge: (m, 3 nodes, 3 components). ``traction(x, r)`` returns the
    amplitudes (T_x, T_r, T_θ), each broadcastable to (m, q)."""
    s, w = line_rule(order)
    x, r, J, _, N, _ = edge_geometry(X, R, s)
    T = [np.broadcast_to(np.asarray(c, dtype=float), x.shape) for c in traction(x, r)]
    wq = J * r * w[None]
    return np.stack([np.einsum("mq,aq->ma", wq * Tc, N) for Tc in T], axis=-1)


def edge_moments(X: np.ndarray, R: np.ndarray, fields, order: int = 6) -> np.ndarray:
    """∫ φ · N r ds per edge for vector fields φ(x, r) -> (φ_x, φ_r, φ_θ): (k, m, 3, 3); and
    ∫ φ_k · φ_l r ds summed over the edges (k, k) as the second value."""
    s, w = line_rule(order)
    x, r, J, _, N, _ = edge_geometry(X, R, s)
    wq = J * r * w[None]
    phis = [[np.broadcast_to(np.asarray(c, dtype=float), x.shape) for c in f(x, r)]
            for f in fields]
    rows = np.array([np.stack([np.einsum("mq,aq->ma", wq * pc, N) for pc in p], axis=-1)
                     for p in phis])
    k = len(phis)
    gram = np.array([[sum(float((wq * a * b).sum()) for a, b in zip(phis[i], phis[j],
                                                                    strict=True))
                      for j in range(k)] for i in range(k)])
    return rows, gram


def body_load(X: np.ndarray, R: np.ndarray, b, order: int = 4) -> np.ndarray:
    """∫∫ b · N r dr dx on each element for a constant body-force amplitude b = (b_x, b_r,
    b_θ) (N/mm³): (ne, 6 nodes, 3 components), without the harmonic's weight w_n."""
    pts, w = triangle_rule(order)
    _, r, det, N, _, _ = element_geometry(X, R, pts)
    nN = np.einsum("eq,aq->ea", det * r * w[None], N)             # ∫ N r dA (ne, 6)
    return nN[:, :, None] * np.asarray(b, dtype=float)[None, None, :]


# ----------------------------------------------------------------------------- Fourier loads


def half_pressure_coefficients(distribution: str, n_max: int) -> np.ndarray:
    """Fourier cosine coefficients a_n / p0 (n = 0..n_max) of the pressure on the half seat
    about its centre line: p(ψ) = p0 on |ψ| < π/2 (uniform) or p0 cos ψ there (cosine), 0 on
    the other half, p(ψ) = Σ a_n cos nψ. Exact closed forms:
    uniform  a_0 = 1/2, a_n = 2 sin(nπ/2)/(nπ);
    cosine   a_0 = 1/π, a_1 = 1/2, a_n = 2 cos(nπ/2) / (π (1 − n²)) (n ≥ 2)."""
    n = np.arange(n_max + 1, dtype=float)
    a = np.zeros(n_max + 1)
    if distribution == "uniform":
        a[0] = 0.5
        a[1:] = 2 * np.sin(0.5 * np.pi * n[1:]) / (np.pi * n[1:])
    elif distribution == "cosine":
        a[0] = 1 / np.pi
        if n_max >= 1:
            a[1] = 0.5
        a[2:] = 2 * np.cos(0.5 * np.pi * n[2:]) / (np.pi * (1 - n[2:] ** 2))
    else:
        raise ValueError(f"unknown load distribution {distribution!r}")
    a[np.abs(a) < 1e-15] = 0.0
    return a


def force_per_p0(distribution: str) -> float:
    """Net force / (p0 R L) of the half-seat pressure: π a_1 (uniform: 2, cosine: π/2)."""
    return float(np.pi * half_pressure_coefficients(distribution, 1)[1])


# ----------------------------------------------------------------------------- stresses


def nodal_stress_amplitudes(X, R, D, U, n: int):
    """Stress amplitudes (ne, 6 nodes, 6 comps) of harmonic n from element displacement
    amplitudes U (ne, 18), evaluated at each element's own nodes (components xx, rr, θθ, xr,
    rθ, xθ; normal ones and xr carry cos nθ, rθ and xθ sin nθ in the symmetric part)."""
    _, r, _, N, Nx, Nr = element_geometry(X, R, TRI_NODES)
    B0, B1 = strain_operators(N, Nx, Nr, r)
    eps = np.einsum("eqjk,ek->eqj", B0 + n * B1, U)
    return np.einsum("ij,eqj->eqi", D, eps)
