"""Validation of the stepped Timoshenko beam model (shaftfe.beam.model) against closed forms.

Closed forms used (each test names its own):
* Timoshenko & Gere, *Mechanics of Materials* / Gere & Goodno: simply supported beam with a
  central point load, bending part P L³/(48 E I); beam with an overhang by superposition;
  cantilever P L³/(3 E I).
* Shear deflection by the unit-load (Castigliano) method with shear energy V²/(2 κ G A)
  (Timoshenko & Goodier; Cowper 1966 for κ): ∫ V v /(κ G A) dx.
* Cowper, J. Appl. Mech. 33 (1966) 335, Table 1: κ solid circle 6(1+ν)/(7+6ν), thin-walled
  round tube 2(1+ν)/(4+3ν).
* ISO 281 basic rating life and the seed's own number (SPEC §2: 3303, C = 23 649 N, P = 2931 N,
  7000 rpm → 1250.7 h).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import quad

from shaftfe.beam.elements import (
    NDOF,
    RX,
    RZ,
    UY,
    cowper_kappa,
    hexagon_area_inertia,
    section_properties,
)
from shaftfe.beam.model import (
    assemble_mass,
    assemble_stiffness,
    build_model,
    rigid_body_modes,
    support_stiffness,
)
from shaftfe.beam.solve import solve, solve_unit
from shaftfe.errors import InputError, SolverError
from shaftfe.model.bearing_life import l10h
from shaftfe.model.loads import Load
from shaftfe.model.variant import Attachment, Bearing, HexSocket, Material, Segment, Variant

E, NU = 210_000.0, 0.3
G = E / (2 * (1 + NU))
KAPPA = 6 * (1 + NU) / (7 + 6 * NU)
STEEL = Material("steel", E, NU, 7.85e-9, 540.0, 800.0)
RIGID = ((0.0, 0.0), (0.0, 0.0))


def make_variant(segments, bearings, attachments=(), hex_socket=None, clearance=None,
                 name="t"):
    """segments: [(length, diameter, fillet_right)], bearings: [(x, K, axial, tilt, C,
    holds_torsion)]."""
    segs, x = [], 0.0
    for i, (length, dia, *rest) in enumerate(segments):
        segs.append(Segment(f"s{i}", x, length, dia, fillet_mm=rest[0] if rest else 0.0))
        x += length
    brgs = []
    for i, (xb, K, *rest) in enumerate(bearings):
        axial = rest[0] if len(rest) > 0 else (i == 0)
        tilt = rest[1] if len(rest) > 1 else 0.0
        C = rest[2] if len(rest) > 2 else 10_000.0
        brgs.append(Bearing(f"b{i}", "test", xb, 0.0, C, C, K, axial=axial,
                            tilt_stiffness_Nmm_per_rad=tilt,
                            holds_torsion=rest[3] if len(rest) > 3 else False))
    return Variant(name, "test", tuple(segs), tuple(brgs), tuple(attachments), STEEL, 0.0,
                   hex_socket=hex_socket, clearance_station_x_mm=clearance)


def props(d):
    return math.pi * d**2 / 4, math.pi * d**4 / 64


def node(model, x):
    i = int(np.argmin(np.abs(model.x - x)))
    assert abs(model.x[i] - x) < 1e-9       # nodes are placed at x (round-off of mm sums only)
    return i


def point(x, Fy=0.0, Fz=0.0, Mx=0.0, Fx=0.0):
    """Point loads at x (the load model's ``[[loads]]`` entries, constant law, no band): a
    force in y, one in z, a torque about x and an axial force."""
    out = []
    for kind, val, ang in (("force", Fy, 0.0), ("force", Fz, 90.0), ("torque", Mx, 0.0),
                           ("axial_force", Fx, 0.0)):
        if val:
            out.append(Load(f"{kind}@{x:g}/{ang:g}", kind, x, (x, x), val, ang))
    return out


def one(v, rpm=0.0, loads=(), **kw):
    """Build and solve ``v`` with the extra point ``loads`` (lists from ``point``)."""
    if loads:
        v = replace(v, loads=tuple(ld for grp in loads for ld in grp))
    m = build_model(v, **kw)
    return m, solve(m, rpm)[0]


# EXACT: the closed forms below are reproduced exactly by the IIE element (exact for nodal
# point loads; nodal values exact for consistent uniform loads), so what is left is round-off.
# Its componentwise bound eps·‖|K⁻¹|(|K||u| + |F|)‖∞/‖u‖∞ (Skeel) is ≤ 1.3e-11 for every model
# in this file (1.2e-10 for the Euler-Bernoulli one), the rounding of the recovered forces
# eps·max(|K||u|)/max|F| ≤ 2.7e-11; the normwise eps·cond₁ (≤ 3.5e-9, cond₁ ≤ 1.6e7) overstates
# both. Every check passes at 1e-12 on OpenBLAS SkylakeX and Prescott kernels. Hence rel 1e-9
# (≥ 75× the bound; the displacement checks were rel 1e-6 before).
EXACT = 1e-9


# ----------------------------------------------------------------------------- sections

def test_cowper_kappa_solid_and_thin_tube_limit():
    """Cowper (1966) Table 1: solid circle 6(1+ν)/(7+6ν) = 0.886364 for ν = 0.3 (printed in
    the table's numeric column as 0.886), and the hollow-circle formula must reduce to the thin
    tube entry 2(1+ν)/(4+3ν) as m → 1."""
    # exact arithmetic (round-off only) for both forms
    assert cowper_kappa(0.3) == pytest.approx(0.8863636363636364, rel=1e-12)
    for nu in (0.0, 0.25, 0.3, 0.45):
        # exact arithmetic (round-off only)
        assert cowper_kappa(nu, 1.0) == pytest.approx(2 * (1 + nu) / (4 + 3 * nu), rel=1e-12)


def _polygon_inertia(pts):
    """Second moment about the x axis of a polygon by the shoelace formula (Green's theorem)."""
    x, y = pts[:, 0], pts[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    cr = x * y1 - x1 * y
    return 0.5 * cr.sum(), (cr * (y**2 + y * y1 + y1**2)).sum() / 12.0


def test_hexagon_section_matches_polygon_integration():
    """Hexagon area and I against an independent polygon (Green's theorem) integration, in two
    orientations (a regular hexagon's I is orientation-independent)."""
    s = 8.0
    a = s / math.sqrt(3)
    for phase in (0.0, 0.3, math.pi / 6):
        ang = phase + np.arange(6) * math.pi / 3
        area, Ix = _polygon_inertia(np.column_stack([a * np.cos(ang), a * np.sin(ang)]))
        A_h, I_h = hexagon_area_inertia(s)
        # exact arithmetic (closed form vs exact polygon integration, round-off only)
        assert A_h == pytest.approx(area, rel=1e-12)
        assert I_h == pytest.approx(Ix, rel=1e-12)


def test_element_stiffness_annihilates_rigid_body_modes_and_is_symmetric():
    """A free-free beam has exactly six zero-energy modes (three translations, three small
    rotations); the assembled elastic stiffness must map them to zero and be symmetric."""
    v = make_variant([(30, 20), (40, 25), (30, 15)], [(10, RIGID), (90, RIGID)])
    m = build_model(v, max_element_mm=6, rigid_supports=True)   # K_N_per_mm unused
    K = assemble_stiffness(m)
    R = rigid_body_modes(m.x, 50.0, 100.0)
    # exact arithmetic (round-off only: measured 8e-17 and 0)
    assert np.abs(K @ R).max() < 1e-9 * np.abs(K).max()
    assert np.abs(K - K.T).max() < 1e-9 * np.abs(K).max()
    w = np.linalg.eigvalsh(K)
    # the six rigid eigenvalues are round-off (≤ 6e-17 w_max), the first elastic one 1.4e-5
    # w_max: 1e-9 separates them by 4 decades either side
    assert np.sum(w < 1e-9 * w.max()) == 6


# ----------------------------------------------------------------------------- statics

@pytest.mark.parametrize("max_el", [1000.0, 7.0])
def test_simply_supported_central_load(max_el):
    """Simply supported uniform shaft, central point load P (Gere & Goodno, Table of beam
    deflections, case "simple beam, load at midpoint"): δ_mid = P L³/(48 E I) + P L/(4 κ G A)
    (the second term by the unit-load method with shear energy), reactions P/2, M_max = P L/4,
    σ = 32 M/(π d³)."""
    L, d, P = 200.0, 20.0, 1234.0
    A, Ia = props(d)
    v = make_variant([(L, d)], [(0.0, RIGID), (L, RIGID)])
    m, r = one(v, rigid_supports=True, max_element_mm=max_el,
               loads=[point(L / 2, Fy=P)])
    ref = P * L**3 / (48 * E * Ia) + P * L / (4 * KAPPA * G * A)
    # exact element: round-off only (EXACT, see its definition)
    assert r.uy[node(m, L / 2)] == pytest.approx(ref, rel=EXACT)
    assert np.abs(r.uz).max() == 0.0
    for b in r.bearings:
        # exact element: round-off only (EXACT, see its definition)
        assert b.Fy_N == pytest.approx(-P / 2, rel=EXACT)
        assert b.F_N == pytest.approx(P / 2, rel=EXACT)
    assert r.M.max() == pytest.approx(P * L / 4, rel=EXACT)
    assert r.max_sigma_vm_MPa == pytest.approx(32 * P * L / 4 / (math.pi * d**3), rel=EXACT)
    assert r.x_max_sigma_vm_mm == pytest.approx(L / 2)     # a node: exact (default rel 1e-6)


def test_overhang_tip_load():
    """Beam with an overhang (supports at 0 and L, load P at the free end x = L + a). Gere &
    Goodno, beam with overhang by superposition: bending tip deflection P a² (L + a)/(3 E I);
    reactions R_A = −P a/L, R_B = P (L + a)/L; shear deflection (unit-load method, V = P on the
    overhang and P a/L in the span) P a (L + a)/(L κ G A)."""
    L, a, d, P = 150.0, 60.0, 18.0, 800.0
    A, Ia = props(d)
    v = make_variant([(L + a, d)], [(0.0, RIGID), (L, RIGID)])
    _, r = one(v, rigid_supports=True, max_element_mm=5,
               loads=[point(L + a, Fz=P)])
    ref = P * a**2 * (L + a) / (3 * E * Ia) + P * a * (L + a) / (L * KAPPA * G * A)
    # exact element: round-off only (EXACT, see its definition)
    assert r.uz[-1] == pytest.approx(ref, rel=EXACT)
    # reactions on the shaft: A pulls along +z (a/L P), B pushes back −(L+a)/L P
    assert r.bearings[0].Fz_N == pytest.approx(P * a / L, rel=EXACT)
    assert r.bearings[1].Fz_N == pytest.approx(-P * (L + a) / L, rel=EXACT)
    assert r.M.max() == pytest.approx(P * a, rel=EXACT)


def test_cantilever_on_radial_and_tilt_springs():
    """A single bearing at x = 0 with radial spring k and tilt spring k_t, tip load P at L:
    δ = P L³/(3 E I) + P L/(κ G A) (Timoshenko cantilever) + P/k + P L²/k_t (rigid-body motion
    of the elastic clamp, superposition)."""
    L, d, P, k, kt = 120.0, 16.0, 500.0, 20_000.0, 3.0e7
    A, Ia = props(d)
    v = make_variant([(L, d)], [(0.0, ((k, 0.0), (0.0, k)), True, kt)])
    _, r = one(v, max_element_mm=10, loads=[point(L, Fy=P)])
    ref = P * L**3 / (3 * E * Ia) + P * L / (KAPPA * G * A) + P / k + P * L**2 / kt
    # exact element: round-off only (EXACT, see its definition)
    assert r.uy[-1] == pytest.approx(ref, rel=EXACT)
    assert r.bearings[0].Fy_N == pytest.approx(-P, rel=EXACT)


def test_simply_supported_on_unequal_springs():
    """Central load on springs k1, k2: the rigid-support result plus the support displacements
    R/k interpolated linearly (lever rule) to mid-span: + (P/2/k1 + P/2/k2)/2."""
    L, d, P, k1, k2 = 200.0, 20.0, 1000.0, 35_030.0, 12_000.0
    A, Ia = props(d)
    v = make_variant([(L, d)], [(0.0, ((k1, 0), (0, k1))), (L, ((k2, 0), (0, k2)))])
    m, r = one(v, max_element_mm=8, loads=[point(L / 2, Fy=P)])
    rigid = P * L**3 / (48 * E * Ia) + P * L / (4 * KAPPA * G * A)
    ref = rigid + 0.5 * (P / 2 / k1 + P / 2 / k2)
    # exact element: round-off only (EXACT, see its definition)
    assert r.uy[node(m, L / 2)] == pytest.approx(ref, rel=EXACT)
    assert r.uy[0] == pytest.approx(P / 2 / k1, rel=EXACT)
    assert r.uy[-1] == pytest.approx(P / 2 / k2, rel=EXACT)


def test_overhang_on_springs_lever_rule():
    """Overhang beam on springs: tip = rigid-support tip deflection + rigid-body line through the
    support displacements δ_A = R_A/k1, δ_B = R_B/k2 evaluated at L + a (lever rule)."""
    L, a, d, P, k1, k2 = 150.0, 60.0, 18.0, 800.0, 30_000.0, 50_000.0
    A, Ia = props(d)
    v = make_variant([(L + a, d)], [(0.0, ((k1, 0), (0, k1))), (L, ((k2, 0), (0, k2)))])
    _, r = one(v, max_element_mm=5, loads=[point(L + a, Fy=P)])
    tip_rigid = P * a**2 * (L + a) / (3 * E * Ia) + P * a * (L + a) / (L * KAPPA * G * A)
    dA = -P * a / L / k1            # bearing A is pulled away from the load (−y)
    dB = P * (L + a) / L / k2
    ref = tip_rigid + dA + (dB - dA) * (L + a) / L
    # exact element: round-off only (EXACT, see its definition)
    assert r.uy[-1] == pytest.approx(ref, rel=EXACT)


def test_coupled_spring_support_displacement_is_K_inverse_R():
    """Coupled bearing stiffness (seed 000 §8.3: K11 = K22 = 35 030, K12 = 8756 N/mm): the beam
    is statically determinate, so the bearing loads follow the lever rule independently of K and
    each bearing centre moves by K⁻¹ × (load on the bearing), including the cross-coupled part;
    mid-span = rigid-support deflection + mean of the two support displacement vectors."""
    Kc = ((35_030.0, 8756.0), (8756.0, 35_030.0))
    L, d, P, xp, ang = 180.0, 20.0, 2000.0, 70.0, math.radians(30)
    v = make_variant([(L, d)], [(0.0, Kc), (L, Kc)])
    Py, Pz = P * math.cos(ang), P * math.sin(ang)
    m, r = one(v, max_element_mm=6, loads=[point(xp, Fy=Py, Fz=Pz)])
    load_on = {0: np.array([Py, Pz]) * (L - xp) / L, 1: np.array([Py, Pz]) * xp / L}
    Kinv = np.linalg.inv(np.array(Kc))
    for i, b in enumerate(r.bearings):
        # exact element: round-off only (EXACT, see its definition)
        assert np.allclose([b.Fy_N, b.Fz_N], -load_on[i], rtol=EXACT, atol=EXACT * P)
        n = node(m, b.x_mm)
        disp = np.array([r.uy[n], r.uz[n]])
        # exact element: round-off only (EXACT, see its definition)
        assert np.allclose(disp, Kinv @ load_on[i], rtol=EXACT)
    # a pure y load still moves the supports in z through K12
    m2, ry = one(v, max_element_mm=6, loads=[point(L / 2, Fy=P)])
    A, Ia = props(d)
    rigid = P * L**3 / (48 * E * Ia) + P * L / (4 * KAPPA * G * A)
    sup = Kinv @ np.array([P / 2, 0.0])
    n = node(m2, L / 2)
    # exact element: round-off only (EXACT, see its definition)
    assert ry.uy[n] == pytest.approx(rigid + sup[0], rel=EXACT)
    assert ry.uz[n] == pytest.approx(sup[1], rel=EXACT)
    assert sup[1] < 0


def test_stepped_hollow_shaft_against_unit_load_integral():
    """Stepped shaft with a hex socket, simply supported, point load: deflection under the load
    from the unit-load method δ = ∫ M m/(E I) dx + ∫ V v/(κ G A) dx, integrated piecewise with
    scipy quad over the segment pieces (independent of the element formulation); the section
    properties come from the separately validated hexagon/Cowper formulas. Also checks the
    nominal stress at the shoulder on the smaller diameter: σ = 32 M(x_s)/(π d³)."""
    segs = [(25.0, 15.0, 1.0), (40.0, 22.0, 1.0), (35.0, 17.0, 0.5), (30.0, 12.0)]
    hs = HexSocket("left", 8.0, 10.0)
    xa, xb, xp, P = 5.0, 110.0, 45.0, 3000.0
    v = make_variant(segs, [(xa, RIGID), (xb, RIGID)], hex_socket=hs)
    m, r = one(v, rigid_supports=True, max_element_mm=4,
               loads=[point(xp, Fy=P)])
    span = xb - xa
    Ra = P * (xb - xp) / span

    def M(x):
        return Ra * (x - xa) - P * max(x - xp, 0.0) if xa <= x <= xb else 0.0

    def V(x):
        return (Ra - (P if x > xp else 0.0)) if xa <= x <= xb else 0.0

    def m1(x):   # unit load at xp
        return M(x) / P

    def v1(x):
        return V(x) / P

    bounds = [0.0, 10.0, 25.0, 65.0, 100.0, 130.0]
    cuts = sorted({*bounds, xa, xb, xp})
    delta = 0.0
    for lo, hi in itertools.pairwise(cuts):
        xm = 0.5 * (lo + hi)
        dia = next(sd for (sl, sd, *_), x0 in zip(segs, [0, 25, 65, 100], strict=True)
                   if x0 <= xm < x0 + sl)
        sec = section_properties(np.array([dia]), NU, np.array([8.0 if xm < 10 else 0.0]))
        EI, kGA = E * sec.I[0], sec.kappa[0] * G * sec.A[0]
        delta += quad(lambda x, EI=EI, kGA=kGA: M(x) * m1(x) / EI + V(x) * v1(x) / kGA,
                      lo, hi, epsabs=0, epsrel=1e-13)[0]   # reference to ~round-off
    # exact element: round-off only (EXACT, see its definition)
    assert r.uy[node(m, xp)] == pytest.approx(delta, rel=EXACT)
    # shoulder at x = 65 (22 -> 17): nominal stress on d = 17
    nt = next(n for n in r.notches if n.x_mm == 65.0)
    assert nt.d_mm == 17.0
    # exact element: round-off only (EXACT, see its definition)
    assert nt.sigma_nom_MPa == pytest.approx(32 * abs(M(65.0)) / (math.pi * 17.0**3), rel=EXACT)
    assert nt.sigma_peak_MPa == pytest.approx(nt.kt * nt.sigma_nom_MPa, rel=1e-12)  # exact


def test_uniform_line_load_spread_over_seat():
    """Uniform load over the whole span (an attachment whose seat spans the bearings, spread):
    δ_mid = 5 q L⁴/(384 E I) + q L²/(8 κ G A) (Gere & Goodno + unit-load shear term), reactions
    q L/2, M_max = q L²/8 (at a node: mid-span)."""
    L, d = 200.0, 20.0
    A, Ia = props(d)
    att = Attachment("cw", 0.0, L, 0.5, 10.0, L / 2)
    v = make_variant([(L, d)], [(0.0, RIGID), (L, RIGID)], attachments=[att])
    rpm = 6000.0
    m, r = one(v, rpm, rigid_supports=True, max_element_mm=5, spread_loads=True)
    W = att.force_N(rpm)
    q = W / L
    ref = 5 * q * L**4 / (384 * E * Ia) + q * L**2 / (8 * KAPPA * G * A)
    # exact element: round-off only (EXACT, see its definition)
    assert r.uy[node(m, L / 2)] == pytest.approx(ref, rel=EXACT)
    assert r.bearings[0].F_N == pytest.approx(W / 2, rel=EXACT)
    assert r.M.max() == pytest.approx(q * L**2 / 8, rel=EXACT)


@pytest.mark.parametrize("seed", [False, True])
def test_equilibrium_with_several_loads_and_coupled_springs(seed):
    """Static equilibrium (Newton): Σ reactions + Σ applied loads = 0 in y and z, and the moment
    about x = 0 also balances, to 1e-10 relative: with each part's force at its centroid (the
    default: issue #31) or at its seat centre (``seed_placement``, the seed's model)."""
    Kc = ((35_030.0, 8756.0), (8756.0, 35_030.0))
    atts = [Attachment("gear", 5, 20, 0.152, 1.36, 12, angle_deg=0.0),
            Attachment("cw1", 5, 20, 0.125, 22.59, 12, angle_deg=10.0),
            Attachment("cw2", 80, 105, 0.24, 20.23, 92, angle_deg=200.0)]
    v = make_variant([(25, 17, 1), (50, 22, 1), (35, 17)], [(30, Kc), (70, Kc)],
                     attachments=atts)
    _, r = one(v, 10_000.0, max_element_mm=3, seed_placement=seed)
    Fy = sum(a.force_N(10_000) * math.cos(math.radians(a.angle_deg)) for a in atts)
    Fz = sum(a.force_N(10_000) * math.sin(math.radians(a.angle_deg)) for a in atts)
    My = sum(a.force_N(10_000) * math.cos(math.radians(a.angle_deg))
             * (a.seat_center_mm if seed else a.x_centroid_mm) for a in atts)
    scale = max(a.force_N(10_000) for a in atts)
    # statics: round-off of the recovered forces, eps·max(|K||u|)/max|F| = 2.5e-12 for this
    # model (see EXACT); 1e-10 = 40× that
    assert abs(sum(b.Fy_N for b in r.bearings) + Fy) < 1e-10 * scale
    assert abs(sum(b.Fz_N for b in r.bearings) + Fz) < 1e-10 * scale
    assert abs(sum(b.Fy_N * b.x_mm for b in r.bearings) + My) < 1e-10 * scale * 100


def _balancer_like(angle_shift=0.0, K=((30_000.0, 0.0), (0.0, 30_000.0)), tilt=0.0):
    atts = [Attachment("gear", 5, 20, 0.152, 1.36, 12, angle_deg=0.0 + angle_shift),
            Attachment("cw1", 5, 20, 0.125, 22.59, 12, angle_deg=35.0 + angle_shift),
            Attachment("cw2", 80, 105, 0.24, 20.23, 92, angle_deg=190.0 + angle_shift)]
    return make_variant([(25, 17, 1), (50, 22, 1), (35, 17)],
                        [(30, K, True, tilt), (70, K, False, tilt)], attachments=atts,
                        clearance=50.0)


def test_rotating_load_directions_rotates_the_response():
    """Isotropic supports: rotating every attachment angle by φ rotates reactions and deflection
    vectors by φ (rotational symmetry of an axisymmetric shaft) and leaves magnitudes unchanged."""
    phi = 47.0
    c, s = math.cos(math.radians(phi)), math.sin(math.radians(phi))
    rot = np.array([[c, -s], [s, c]])
    for K, tilt in ((((30_000.0, 0.0), (0.0, 30_000.0)), 1e6), (RIGID, 0.0)):
        rigid = K is RIGID
        _, r0 = one(_balancer_like(0.0, K, tilt), 8000.0, rigid_supports=rigid)
        _, r1 = one(_balancer_like(phi, K, tilt), 8000.0, rigid_supports=rigid)
        for b0, b1 in zip(r0.bearings, r1.bearings, strict=True):
            # exact rotational symmetry: round-off only (EXACT, see its definition)
            assert np.allclose(rot @ [b0.Fy_N, b0.Fz_N], [b1.Fy_N, b1.Fz_N], rtol=0,
                               atol=EXACT * b0.F_N)
        u0 = rot @ np.vstack([r0.uy, r0.uz])
        # exact rotational symmetry: round-off only (EXACT, see its definition)
        assert np.allclose(u0, np.vstack([r1.uy, r1.uz]), rtol=0, atol=EXACT * r0.u.max())
        assert np.allclose(r0.sigma_vm, r1.sigma_vm, rtol=EXACT)


def test_doubling_rpm_quadruples_forces_and_stresses():
    """Centrifugal loads m e ω² (Attachment.force_N): doubling rpm gives exactly 4× forces,
    deflections and stresses (linear model), and L10h scales by 1/(2·4^p)."""
    m = build_model(_balancer_like())
    r1, r2 = solve(m, [5000.0, 10_000.0])
    for b1, b2 in zip(r1.bearings, r2.bearings, strict=True):
        # exact arithmetic (round-off only): one unit solve scaled by ω²
        assert b2.F_N == pytest.approx(4 * b1.F_N, rel=1e-12)
        assert b2.L10h == pytest.approx(b1.L10h / (2 * 4**3), rel=1e-12)
    # exact arithmetic (round-off only), as above
    assert np.allclose(r2.u, 4 * r1.u, rtol=1e-12)
    assert np.allclose(r2.sigma_vm, 4 * r1.sigma_vm, rtol=1e-12)
    assert r2.max_peak_MPa == pytest.approx(4 * r1.max_peak_MPa, rel=1e-12)
    assert r2.stations["clearance"].u_mm == pytest.approx(4 * r1.stations["clearance"].u_mm,
                                                          rel=1e-12)


def test_attachment_force_is_m_e_omega_squared():
    """Single attachment at mid-span on rigid supports: each reaction equals m e ω²/2 with
    ω = 2π n/60 (seed table: 0.24 kg × 20.23 mm at 10 000 rpm = 5324 N)."""
    att = Attachment("cw2", 90, 110, 0.24, 20.23, 100, angle_deg=90.0)
    v = make_variant([(200, 20)], [(0.0, RIGID), (200.0, RIGID)], attachments=[att])
    _, r = one(v, 10_000.0, rigid_supports=True)
    F = 0.24 * 20.23e-3 * (10_000 * 2 * math.pi / 60) ** 2
    assert F == pytest.approx(5324, abs=0.5)   # seed 000 §8.2 load table
    assert r.bearings[0].Fz_N == pytest.approx(-F / 2, rel=EXACT)
    assert r.bearings[0].Fy_N == pytest.approx(0.0, abs=EXACT * F)   # EXACT (0 by symmetry)


def test_torque_gives_tau_and_von_mises():
    """Torque T applied at the free end and held at the axial bearing (``holds_torsion``):
    τ = 16 T/(π d³) between them, σ_vm = √(σ² + 3τ²) (von Mises for bending + torsion)."""
    L, d, T, P = 200.0, 20.0, 40_000.0, 1000.0
    v = make_variant([(L, d)], [(0.0, RIGID, True, 0.0, 10_000.0, True),
                                (150.0, RIGID, False)])
    m, r = one(v, rigid_supports=True, max_element_mm=10,
               loads=[point(100.0, Fy=P), point(L, Mx=T)])
    tau = 16 * T / (math.pi * d**3)
    inside = r.x_sec < 200.0
    # exact element: round-off only (EXACT, see its definition)
    assert np.allclose(r.tau[inside], tau, rtol=EXACT)
    sig = r.sigma
    assert np.allclose(r.sigma_vm, np.sqrt(sig**2 + 3 * r.tau**2), rtol=1e-12)   # exact
    # rotation of the free end = T L/(G J)
    Ip = math.pi * d**4 / 32
    assert r.x[-1] == L
    u = solve_unit(m).u.sum(axis=1)          # every load column at factor 1
    # exact element: round-off only (EXACT, see its definition)
    assert u[NDOF * (m.n_nodes - 1) + RX] == pytest.approx(T * L / (G * Ip), rel=EXACT)


def test_l10h_reproduces_seed_value():
    """ISO 281 basic life (C/P)^3 10⁶/(60 n): seed 000 §8.2, bearing 3303 (C = 23 649 N) with
    P = 2931 N at 7000 rpm → 1250.7 h (seed, 5 significant digits)."""
    # seed's 5 digits: ±0.05 (ours 1250.667); 0.1 = one unit of the printed digit
    assert l10h(23_649.0, 2931.0, 7000.0, 3.0) == pytest.approx(1250.7, abs=0.1)
    assert math.isinf(l10h(23_649.0, 0.0, 7000.0))


def test_shaft_mass_uniform_cylinder_minus_hexagon():
    """Mass of a Ø20 × 100 steel cylinder ρ π d² L/4 minus a hex socket s = 8, depth 10 with
    area (√3/2) s² (regular hexagon), from the one mass implementation
    (shaftfe.model.mass)."""
    from shaftfe.model.mass import mass_properties
    v = make_variant([(100.0, 20.0)], [(0.0, RIGID), (100.0, RIGID)],
                     hex_socket=HexSocket("right", 8.0, 10.0))
    vol = math.pi * 20**2 / 4 * 100 - math.sqrt(3) / 2 * 64 * 10
    # exact arithmetic: the same closed form in a different order of operations (round-off)
    assert mass_properties(v).shaft_mass_kg == pytest.approx(vol * 7.85e-9 * 1e3, rel=1e-12)


# ----------------------------------------------------------------------------- singularity

def test_singular_supports_raise_solver_error():
    """Missing supports must be detected before solving (FINDINGS pitfall 8) and named."""
    k = ((30_000.0, 0.0), (0.0, 30_000.0))
    one_bearing = make_variant([(100, 20)], [(10.0, k, True)])
    with pytest.raises(SolverError, match="rotation about"):
        solve(build_model(one_bearing), 1000.0)
    no_axial = make_variant([(100, 20)], [(10.0, k, False), (90.0, k, False)])
    with pytest.raises(SolverError, match="axial"):
        solve(build_model(no_axial), 1000.0)
    # a bearing without stiffness in z is refused as input (shaftfe.model.validate: one rule
    # for the beam and the 3D model), naming the field, before any matrix is built
    y_only = ((30_000.0, 0.0), (0.0, 0.0))
    no_z = make_variant([(100, 20)], [(10.0, y_only, True), (90.0, y_only, False)])
    with pytest.raises(InputError, match="K_N_per_mm"):
        build_model(no_z)
    none = make_variant([(100, 20)], [])
    with pytest.raises(SolverError, match="no bearings"):
        solve(build_model(none), 1000.0)
    # the same one-bearing model is regular once the bearing has tilt stiffness
    tilted = make_variant([(100, 20)], [(10.0, k, True, 1e7)])
    solve(build_model(tilted), 1000.0)


def test_bad_input_raises_input_error():
    """Negative spring matrix, bearing outside the shaft, bad element length, negative rpm."""
    with pytest.raises(InputError):
        build_model(make_variant([(100, 20)], [(10.0, ((-1.0, 0.0), (0.0, 1.0)))]))
    with pytest.raises(InputError):
        build_model(make_variant([(100, 20)], [(120.0, RIGID)]))
    v = make_variant([(100, 20)], [(0.0, RIGID), (100.0, RIGID)])
    with pytest.raises(InputError):
        build_model(v, max_element_mm=0.0)
    with pytest.raises(InputError):
        solve(build_model(v, rigid_supports=True), -5.0)


# ----------------------------------------------------------------------------- mass matrix

def test_consistent_mass_rigid_body_mass_and_inertia():
    """The consistent mass must reproduce the rigid-body inertia of a stepped shaft: mass
    Σ ρ A L for each translation, and Σ ρ J L (polar) for torsion (exact integrals)."""
    v = make_variant([(30, 20), (40, 25), (30, 15)], [(10, RIGID), (90, RIGID)])
    m = build_model(v, max_element_mm=6, rigid_supports=True)   # K_N_per_mm unused
    M = assemble_mass(m)
    R = rigid_body_modes(m.x, 0.0, 1.0)
    rho = STEEL.density_t_mm3
    mass = rho * math.pi / 4 * (20**2 * 30 + 25**2 * 40 + 15**2 * 30)
    Jp = rho * math.pi / 32 * (20**4 * 30 + 25**4 * 40 + 15**4 * 30)
    G_ = R.T @ M @ R
    for k in range(3):
        # exact arithmetic: the consistent mass integrates rigid motions exactly
        assert G_[k, k] == pytest.approx(mass, rel=1e-12)
    assert G_[3, 3] == pytest.approx(Jp, rel=1e-12)      # exact arithmetic, as above


def _ss_frequencies_sq(L, d, h):
    from scipy.linalg import eigh

    v = make_variant([(L, d)], [(0.0, RIGID), (L, RIGID)])
    m = build_model(v, rigid_supports=True, max_element_mm=h)
    K = assemble_stiffness(m)
    M = assemble_mass(m)
    _, fixed = support_stiffness(m)
    # keep only the y-plane bending dofs (v, θ_z) of the free nodes
    dofs = np.arange(K.shape[0])
    plane = np.isin(dofs % NDOF, [UY, RZ]) & ~np.isin(dofs, fixed)
    return eigh(K[np.ix_(plane, plane)], M[np.ix_(plane, plane)], eigvals_only=True,
                subset_by_index=[0, 2])


def test_simply_supported_timoshenko_frequencies():
    """Simply supported uniform Timoshenko beam: for k = nπ/L the exact natural frequencies are
    the roots of  ρI·ρA/(κGA) ω⁴ − [ρA + ρI k² + EI ρA k²/(κGA)] ω² + EI k⁴ = 0 (Timoshenko
    1921; Han, Benaroya & Wei, J. Sound Vib. 225 (1999) 935, hinged-hinged case; lower root
    taken in the cancellation-free form 2c/(b + √(b² − 4ac))). Stubby shaft (L/d = 6) so that
    shear and rotary inertia matter (mode 1 is 6 % below Euler-Bernoulli). The IIE consistent
    mass tends to linear interpolation as Φ ∝ 1/h² grows, so the frequencies converge as O(h²)
    from above (measured: mode-1 error 1.07e-5 at h = 2 mm, 2.66e-6 at h = 1 mm)."""
    L, d = 120.0, 20.0
    rho = STEEL.density_t_mm3
    A, Ia = props(d)
    exact = []
    for n in (1, 2, 3):
        k = n * math.pi / L
        a = rho * Ia * rho * A / (KAPPA * G * A)
        b = rho * A + rho * Ia * k**2 + E * Ia * rho * A * k**2 / (KAPPA * G * A)
        c = E * Ia * k**4
        exact.append(2 * c / (b + math.sqrt(b * b - 4 * a * c)))
    exact = np.array(exact)
    e2 = _ss_frequencies_sq(L, d, 2.0) / exact - 1
    e1 = _ss_frequencies_sq(L, d, 1.0) / exact - 1
    assert np.all(e1 > 0) and np.all(e2 > e1)
    assert e1[0] < 1e-5             # mesh: O(h²), measured 2.66e-6 at h = 1 mm (docstring)
    # second-order convergence: the O(h⁴) term moves the ratio by 0.0025 (measured 4.0025)
    assert np.all(np.abs(e2 / e1 - 4.0) < 0.1)
    eb1 = E * Ia * (math.pi / L) ** 4 / (rho * A)
    assert exact[0] < 0.95 * eb1     # shear + rotary inertia: 6.2 % below Euler-Bernoulli


def test_euler_bernoulli_limit():
    """shear_deformation=False: simply supported central load gives exactly P L³/(48 E I)
    (Euler-Bernoulli, Gere & Goodno) and an overhang tip P a² (L + a)/(3 E I)."""
    L, a, d, P = 150.0, 60.0, 18.0, 800.0
    _, Ia = props(d)
    v = make_variant([(L + a, d)], [(0.0, RIGID), (L, RIGID)])
    m, r = one(v, rigid_supports=True, max_element_mm=5, shear_deformation=False,
               loads=[point(L / 2, Fy=P), point(L + a, Fz=P)])
    # exact element: round-off only, Skeel bound 1.2e-10 here (κ → ∞ stiffens the shear
    # terms): 10 × EXACT leaves 80× (was rel 1e-6)
    assert r.uy[node(m, L / 2)] == pytest.approx(P * L**3 / (48 * E * Ia), rel=10 * EXACT)
    assert r.uz[-1] == pytest.approx(P * a**2 * (L + a) / (3 * E * Ia), rel=10 * EXACT)
