"""Stresses of the harmonic solution: on the free surface from the displacement trace, in the
interior by nodal averaging, and their synthesis over θ.

Surface recovery (the one the peaks use). On a boundary edge with unit tangent t = (t_x, t_r)
in the meridian plane, the surface strains of harmonic n (symmetric part; trig factors as in
``kernels``) come from the displacement trace alone:

    ε_tt = t_x dU_x/ds + t_r dU_r/ds                         (cos nθ)
    ε_θθ = (U_r + n U_θ) / r                                 (cos nθ)
    γ_tθ = dU_θ/ds − n (t_x U_x + t_r U_r)/r − t_r U_θ / r    (sin nθ)

and the stresses follow from the traction on the face (σ_nn, σ_nt, σ_nθ = the applied traction,
0 on a free face) and Hooke's law in plane stress with that normal stress:

    σ_tt = E/(1 − ν²) (ε_tt + ν ε_θθ) + ν/(1 − ν) σ_nn,   σ_θθ likewise,   σ_tθ = G γ_tθ.

The derivative along the edge is that of the P2 trace (one order better on the surface than the
element's gradient, which also contains the normal derivative). Values at a node shared by two
edges are averaged where the tangent is continuous; at a kink of the outline (a sharp corner,
where the elastic stress may be singular anyway) the nodally averaged stress is used.
Reference for the idea: FINDINGS "nodal averaging vs surface recovery" (Goodier cavity:
+0.005 % against +0.32 % for nodal averaging on the same mesh).

Nodal averaging: each element's stress at its own six nodes, plain mean over the elements of a
node (``kernels.nodal_stress_amplitudes``), the method of the 3D path.

Components. Surface ("local"): tt, θθ, nn, tθ, nθ, nt. Cylindrical ("cyl"): xx, rr, θθ, xr, rθ,
xθ. Types: a component with a θ-shear (tθ, nθ; rθ, xθ) carries sin nθ in the symmetric part,
the others cos nθ; the antisymmetric part carries sin nθ and −cos nθ respectively.
"""

from __future__ import annotations

import numpy as np

from shaftfe.axisymmetric import kernels as kn

LOCAL = ("tt", "θθ", "nn", "tθ", "nθ", "nt")
CYL = ("xx", "rr", "θθ", "xr", "rθ", "xθ")
LOCAL_SHEAR = np.array([False, False, False, True, True, False])
CYL_SHEAR = np.array([False, False, False, False, True, True])
KINK_COS = np.cos(np.radians(10.0))
THETA_STEP_DEG = 1.0        # the θ grid of every peak search (truncation, peaks, fatigue)


def theta_grid() -> np.ndarray:
    """θ = 0°, 1°, …, 359° in rad."""
    return np.radians(np.arange(0.0, 360.0, THETA_STEP_DEG))


def nodal_average(mesh, U: np.ndarray, n: int, E: float, nu: float,
                  elements: np.ndarray | None = None) -> np.ndarray:
    """(6, n_nodes) nodally averaged cylindrical stress amplitudes of harmonic n (only the
    nodes of ``elements`` are valid when a subset of elements is given)."""
    D = kn.elasticity_matrix(E, nu)
    t = mesh.tri if elements is None else mesh.tri[:, elements]
    Ue = U.reshape(-1, 3)[t.T].reshape(t.shape[1], 18)
    s = kn.nodal_stress_amplitudes(mesh.xr[0][t].T, mesh.xr[1][t].T, D, Ue, n)  # (ne,6,6)
    N = mesh.n_nodes
    cnt = np.bincount(t.T.ravel(), minlength=N).astype(float)
    out = np.empty((6, N))
    for c in range(6):
        out[c] = np.bincount(t.T.ravel(), weights=s[:, :, c].ravel(), minlength=N)
    return out / np.maximum(cnt, 1.0)


def cyl_to_local(s: np.ndarray, t: np.ndarray, sign: np.ndarray) -> np.ndarray:
    """Cylindrical amplitudes (6, k) → surface-local ones at boundary nodes with tangent t
    (2, k) and outward normal n = sign · (t_r, −t_x)."""
    nx, nr = sign * t[1], -sign * t[0]
    xx, rr, tt_, xr, rt, xt = s
    s_tt = t[0] ** 2 * xx + t[1] ** 2 * rr + 2 * t[0] * t[1] * xr
    s_nn = nx ** 2 * xx + nr ** 2 * rr + 2 * nx * nr * xr
    s_nt = nx * t[0] * xx + nr * t[1] * rr + (nx * t[1] + nr * t[0]) * xr
    s_tq = t[0] * xt + t[1] * rt
    s_nq = nx * xt + nr * rt
    return np.array([s_tt, tt_, s_nn, s_tq, s_nq, s_nt])


class Surface:
    """The boundary nodes where surface stresses are recovered (every outline node off the
    axis), with their tangent, outward normal side and kink flag."""

    def __init__(self, mesh):
        self.mesh = mesh
        axis_ids = [i for i, c in enumerate(mesh.geometry.curves) if "axis" in c.groups]
        keep = ~np.isin(mesh.edge_curve, axis_ids)
        self.edge_ids = np.nonzero(keep)[0]
        e = mesh.edges[:, self.edge_ids]                      # (3, m)
        X, R = mesh.xr[0][e].T, mesh.xr[1][e].T
        s = np.array([0.0, 1.0, 0.5])
        _, _, J, t, _, dN = kn.edge_geometry(X, R, s)           # J (m, 3), t (2, m, 3)
        self.J, self.t, self.dN = J, t, dN
        self.e = e
        nodes = e.T.ravel()                                     # (m*3,) edge-local order
        uniq, inv = np.unique(nodes, return_inverse=True)
        r = mesh.xr[1][uniq]
        self.on_axis = r <= 1e-9 * max(1.0, float(mesh.xr[1].max()))
        self.nodes, self.inv = uniq, inv
        tt = t.transpose(1, 2, 0).reshape(-1, 2)                # (m*3, 2)
        cnt = np.bincount(inv, minlength=uniq.size)
        tmean = np.stack([np.bincount(inv, weights=tt[:, c], minlength=uniq.size)
                          for c in range(2)]) / cnt
        # smooth where every entry's tangent agrees with the mean direction
        nrm = np.linalg.norm(tmean, axis=0)
        dots = (tt.T * (tmean / np.maximum(nrm, 1e-300))[:, inv]).sum(axis=0)
        worst = np.full(uniq.size, 1.0)
        np.minimum.at(worst, inv, dots)
        self.kink = (worst < KINK_COS) | self.on_axis
        self.tangent = tmean / np.maximum(nrm, 1e-300)
        sign_e = np.repeat(mesh.edge_sign[self.edge_ids], 3)
        sg = np.bincount(inv, weights=sign_e, minlength=uniq.size)
        self.sign = np.where(sg >= 0, 1.0, -1.0)
        self.curve = np.zeros(uniq.size, dtype=np.int64)
        self.curve[inv] = np.repeat(mesh.edge_curve[self.edge_ids], 3)
        self.count = cnt
        kn_nodes = self.nodes[self.kink]
        self.kink_elements = np.nonzero(np.isin(mesh.tri, kn_nodes).any(axis=0))[0]

    def stress(self, U: np.ndarray, n: int, E: float, nu: float, sigma_n=None,
               averaged: np.ndarray | None = None) -> np.ndarray:
        """(6, k) surface-local stress amplitudes (LOCAL order) of harmonic n at ``nodes``.
        ``sigma_n`` (k,): the applied normal traction amplitude (−pressure) at the nodes;
        ``averaged`` (6, n_nodes): the nodally averaged cylindrical amplitudes used at kinks
        (computed if not given)."""
        mesh = self.mesh
        e = self.e
        Ux, Ur, Ut = (U[3 * e + c] for c in range(3))             # (3, m) each
        xr = mesh.xr
        r = xr[1][e]
        d = [np.einsum("am,ak->mk", comp, self.dN) / self.J for comp in (Ux, Ur, Ut)]
        tx, tr = self.t                                          # (m, 3)
        UxN, UrN, UtN = Ux.T, Ur.T, Ut.T                          # (m, 3)
        with np.errstate(divide="ignore", invalid="ignore"):
            e_tt = tx * d[0] + tr * d[1]
            e_qq = (UrN + n * UtN) / r.T
            g_tq = d[2] - n * (tx * UxN + tr * UrN) / r.T - tr * UtN / r.T
        k = self.nodes.size
        vals = []
        for a in (e_tt, e_qq, g_tq):
            v = a.ravel()
            v = np.where(np.isfinite(v), v, 0.0)
            vals.append(np.bincount(self.inv, weights=v, minlength=k) / self.count)
        e_tt, e_qq, g_tq = vals
        sn = np.zeros(k) if sigma_n is None else np.asarray(sigma_n, dtype=float)
        Ep = E / (1 - nu * nu)
        G = E / (2 * (1 + nu))
        out = np.zeros((6, k))
        out[0] = Ep * (e_tt + nu * e_qq) + nu / (1 - nu) * sn
        out[1] = Ep * (e_qq + nu * e_tt) + nu / (1 - nu) * sn
        out[2] = sn
        out[3] = G * g_tq
        if self.kink.any():
            avg = averaged if averaged is not None else nodal_average(
                mesh, U, n, E, nu, self.kink_elements)
            ks = np.nonzero(self.kink)[0]
            loc = cyl_to_local(avg[:, self.nodes[ks]], self.tangent[:, ks], self.sign[ks])
            out[:, ks] = loc
        return out


# ------------------------------------------------------------------------------ synthesis


def synthesize(parts, theta: np.ndarray, shear: np.ndarray) -> np.ndarray:
    """Σ over harmonics of amplitudes × trig factors: ``parts`` = [(n, sym (6, k), anti (6, k)
    or None)], θ (q,) in rad → (6, k, q)."""
    return synthesize_at([(n, s[:, :, None], None if a is None else a[:, :, None])
                          for n, s, a in parts], np.asarray(theta)[None, :], shear)


def synthesize_at(parts, theta: np.ndarray, shear: np.ndarray) -> np.ndarray:
    """The same sum with amplitudes (6, *shape) and angles θ broadcastable to ``shape``: one
    angle per point (a 3D point at θ = atan2(z, y)) or a grid (amplitudes (6, k, 1), θ (1, q))."""
    theta = np.asarray(theta, dtype=float)
    sh = shear.reshape((6, *(1,) * theta.ndim))
    out = 0.0
    for n, sym, anti in parts:
        if n == 0:
            out = out + sym
            continue
        c, s = np.cos(n * theta)[None], np.sin(n * theta)[None]
        out = out + sym * np.where(sh, s, c)
        if anti is not None:
            out = out + anti * np.where(sh, -c, s)
    return out * np.ones((1, *theta.shape))


def parabola_peak(x, y) -> tuple[float, float]:
    """The peak of the parabola through three points (x sorted, the middle one the largest
    sample): its vertex, kept within [x0, x2], and the parabola's value there; the middle point
    itself where the parabola is not concave or a value is not finite. The one peak locator
    of the surface stresses (in θ, along the outline, along a fillet arc)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    if not np.all(np.isfinite(y)):             # a neighbour left out (−inf): no fit
        return float(x[1]), float(y[1])
    c2, c1, c0 = np.linalg.solve(np.vander(x, 3), y)
    if not c2 < 0:
        return float(x[1]), float(y[1])
    xv = float(np.clip(-c1 / (2 * c2), x[0], x[2]))
    return xv, float((c2 * xv + c1) * xv + c0)


def displacement(harmonics, nodes: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """(3, k, q) Cartesian displacement (x, y, z) at ``nodes`` and angles θ (rad)
    (``displacement_at`` on the grid nodes × θ)."""
    amps = [(h.n, h.sym.reshape(-1, 3)[nodes].T[:, :, None],
             None if h.anti is None else h.anti.reshape(-1, 3)[nodes].T[:, :, None])
            for h in harmonics]
    return displacement_at(amps, np.asarray(theta)[None, :])


def displacement_at(amps, theta: np.ndarray) -> np.ndarray:
    """(3, *shape) Cartesian displacement from each harmonic's amplitudes (U_x, U_r, U_θ)
    (3, *shape) of its symmetric and antisymmetric parts, ``amps`` = [(n, sym, anti | None)],
    at angles θ broadcastable to ``shape`` (``kernels``: U_x, U_r ∝ cos nθ, U_θ ∝ sin nθ in the
    symmetric part, every component × 1 for n = 0; sin nθ and −cos nθ in the antisymmetric
    part), u_r and u_θ rotated to y, z."""
    theta = np.asarray(theta, dtype=float)
    ux = ur = ut = 0.0
    for n, U, V in amps:
        c, s = np.cos(n * theta), np.sin(n * theta)
        ux = ux + U[0] * c
        ur = ur + U[1] * c
        ut = ut + U[2] * (s if n else 1.0)        # n = 0: torsion, u_θ = U_θ
        if V is not None:
            ux = ux + V[0] * s
            ur = ur + V[1] * s
            ut = ut - V[2] * c
    c, s = np.cos(theta), np.sin(theta)
    one = np.ones(theta.shape)
    return np.stack([ux * one, ur * c - ut * s, ur * s + ut * c])


def principal_max_local(s: np.ndarray) -> np.ndarray:
    """Largest principal stress of (6, ...) tensors in either order here (three normal
    stresses a, b, c, then the shears ab, bc, ca: tt, θθ, nn, tθ, θn, nt or xx, rr, θθ, xr, rθ,
    θx). Closed form (the trigonometric solution of the characteristic cubic), not
    ``fe.recovery.principal``'s eigvalsh: the peaks evaluate ~10⁶ tensors (nodes × θ grid)."""
    a, b, c, ab, bc, ac = s
    q = (a + b + c) / 3.0
    p1 = ab * ab + bc * bc + ac * ac
    p2 = (a - q) ** 2 + (b - q) ** 2 + (c - q) ** 2 + 2 * p1
    p = np.sqrt(p2 / 6.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        B = [(a - q) / p, (b - q) / p, (c - q) / p, ab / p, bc / p, ac / p]
        detB = (B[0] * (B[1] * B[2] - B[4] * B[4]) - B[3] * (B[3] * B[2] - B[4] * B[5])
                + B[5] * (B[3] * B[4] - B[1] * B[5]))
        phi = np.arccos(np.clip(detB / 2.0, -1.0, 1.0)) / 3.0
    out = q + 2 * p * np.cos(phi)
    return np.where(p > 0, out, q)
