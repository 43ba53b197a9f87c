"""The axisymmetric model as the input of fatigue and of the report (``--model axisymmetric``),
its n = 1 spring coupling and its harmonic truncation.

Sources:
* The rotation of surface-local stresses to x y z (``reference.local_to_cartesian``): on the
  exact Saint-Venant fields in ``test_axisymmetric_exact``, and here against the direct
  rotation of a cylindrical tensor about the x axis on surfaces of any meridian tangent.
* The n = 1 spring coupling solved by the Woodbury identity against the same equations solved
  directly as one coupled system (the formulation of the 3D path: one matrix, the 2×2 spring
  blocks inside it).
* The element matrices (``kernels.stiffness_blocks``, summed through the node functions
  ∂N/∂x, ∂N/∂r, N/r) against their definition, the quadrature of B_kᵀ D B_l r written out from
  the strain operators (Zienkiewicz & Taylor vol. 1, §10.5), on elements off and on the axis.
* The fatigue hot spot against the static peak: the same surface stress sampled at the points
  of the revolved surface, so the sampled maximum is below the located peak by at most the
  drop of a parabola over half a node spacing (bound below).
"""

from __future__ import annotations

import json
import math
from types import SimpleNamespace

import numpy as np
import pytest
import scipy.sparse as sp

from shaftfe.axisymmetric import harmonic as hm
from shaftfe.axisymmetric import kernels as kn
from shaftfe.axisymmetric import recovery as rc
from shaftfe.axisymmetric.mesh import (
    AxiLevel,
    cylinder_geometry,
    mesh_geometry,
)
from shaftfe.axisymmetric.model import AxiOptions, _solve_n1
from shaftfe.axisymmetric.reference import local_to_cartesian, static_reference
from shaftfe.axisymmetric.solve import solve_axisymmetric
from shaftfe.model.loader import load_variant
from shaftfe.static.model import REF_RPM

E, NU = 210000.0, 0.3
# round-off: as ``test_axisymmetric_exact.ROUNDOFF`` (cond ≈ 1e4 of the bar's stiffness on its
# elastic modes, × eps, with room for the recovery's sums); the rotation adds a few flops
ROUNDOFF = 1e-10
EPS = np.finfo(float).eps
# the coupled n = 1 system of the Woodbury test (778 reduced unknowns): 2-norm condition number
# measured 7.2e4 (numpy.linalg.cond of the dense reduced matrix)
COND = 7.2e4


def _bar(R=5.0, L=40.0):
    return mesh_geometry(cylinder_geometry(R, L), AxiLevel("t", 0.3, 0.3, 0.3),
                         use_cache=False)


@pytest.fixture(scope="module")
def bar():
    m = _bar()
    return m, hm.assemble(m, E, NU, use_cache=False)


def test_local_to_cartesian_on_tilted_surfaces():
    """Random stress tensors given in cylindrical components (x, r, θ) on surfaces of any
    meridian tangent: ``recovery.cyl_to_local`` then ``local_to_cartesian`` equals the direct
    rotation of the cylindrical tensor about the x axis (σ_yy = σ_rr c² + σ_θθ s² − 2σ_rθ cs,
    …; rounding only: 1e-12 of the largest component)."""
    rng = np.random.default_rng(7)
    k, q = 40, 12
    cyl = rng.normal(size=(6, k))
    phi = rng.uniform(0, 2 * np.pi, k)
    t = np.array([np.cos(phi), np.sin(phi)])
    sign = rng.choice([-1.0, 1.0], k)
    theta = rng.uniform(0, 2 * np.pi, q)
    loc = rc.cyl_to_local(cyl, t, sign)
    got = local_to_cartesian(np.repeat(loc[:, :, None], q, axis=2), t, sign, theta)
    xx, rr, qq, xr, rq, xq = (c[:, None] for c in cyl)
    c, s = np.cos(theta)[None], np.sin(theta)[None]
    want = np.array([xx + 0 * c, rr * c * c + qq * s * s - 2 * rq * c * s,
                     rr * s * s + qq * c * c + 2 * rq * c * s, xr * c - xq * s,
                     (rr - qq) * c * s + rq * (c * c - s * s), xr * s + xq * c])
    assert np.abs(got - want).max() <= 1e-12 * np.abs(cyl).max()


def test_element_matrices_are_their_definition():
    """K00, K01, K11 equal Σ_q w_q det J r B_kᵀ D B_l (the definition, from the strain
    operators) on random curved P2 elements, three of them with an edge on the axis (r = 0 at
    two nodes). Tolerance: the same products summed in another order, each term bounded by
    |K|; 1e-12 of the largest entry leaves ~1000× over double round-off (measured 7e-16). A
    wrong coefficient gives errors of order 1."""
    rng = np.random.default_rng(7)
    ne = 40
    c = np.stack([rng.uniform(0, 50, ne), rng.uniform(0.5, 10, ne)], 1)
    c[:3, 1] = 0.0                                      # the first three on the axis
    v1 = np.stack([rng.uniform(0.5, 1.5, ne), np.zeros(ne)], 1)
    v2 = np.stack([rng.uniform(-0.3, 0.3, ne), rng.uniform(0.5, 1.5, ne)], 1)
    p0, p1, p2 = c, c + v1, c + v2

    def mid(a, b):
        bow = rng.normal(0.0, 0.02, a.shape)
        bow[:3] = 0.0 if a is p0 and b is p1 else bow[:3]   # the axis edge stays straight
        return 0.5 * (a + b) + bow
    pts = np.stack([p0, p1, p2, mid(p0, p1), mid(p1, p2), mid(p2, p0)], 1)
    X, R = pts[:, :, 0], pts[:, :, 1]
    D = kn.elasticity_matrix(E, NU)
    q, w = kn.triangle_rule(4)
    _, r, det, N, Nx, Nr = kn.element_geometry(X, R, q)
    B0, B1 = kn.strain_operators(N, Nx, Nr, r)
    wq = det * r * w[None]
    for got, (Bk, Bl) in zip(kn.stiffness_blocks(X, R, D), ((B0, B0), (B0, B1), (B1, B1)),
                             strict=True):
        want = np.einsum("eq,eqia,ij,eqjb->eab", wq, Bk, D, Bl)
        assert np.abs(got - want).max() <= 1e-12 * np.abs(want).max()


def test_woodbury_n1_equals_the_coupled_system(bar):
    """Two seats on anisotropic, cross-coupled springs (K12 ≠ 0, K11 ≠ K22) and a tilt
    spring: the Woodbury solve equals the direct solve of the coupled 2·ndof system."""
    m, h = bar
    surf = m.group_edges("surface")
    xe = m.xr[0][m.edges[2, surf]]
    seats = [surf[xe < 6.0], surf[xe > 34.0]]
    Ks = [np.array([[4.0e4, 1.5e4], [1.2e4, 9.0e4]]), np.array([[2.0e5, -3.0e4],
                                                                [-3.0e4, 6.0e4]])]
    bearings = []
    for k, (e, K) in enumerate(zip(seats, Ks, strict=True)):
        rb = hm.rbe3(h, e, float(m.xr[0][m.edges[2, e]].mean()))
        bearings.append((f"b{k}", rb, SimpleNamespace(K_N_per_mm=K,
                                                      tilt_stiffness_Nmm_per_rad=2.0e6 * k)))
    mid = surf[(xe > 15.0) & (xe < 25.0)]
    fs = h.traction_vector(mid, lambda x, r: (0.0, 1.0, 0.0), 1)
    fa = 0.3 * fs
    us, ua, reac, _ = _solve_n1(h, bearings, fs, fa, rigid=False)
    # the direct formulation: one coupled system
    K1, T1 = h.K(1), h.reduction(1)
    z = np.zeros(h.ndof)
    springs = []
    for _, rb, b in bearings:
        springs.append((np.array([np.concatenate([rb.uy, z]), np.concatenate([z, rb.uy])]),
                        b.K_N_per_mm))
        if b.tilt_stiffness_Nmm_per_rad > 0:
            springs.append((np.array([np.concatenate([rb.tz, z]),
                                      np.concatenate([z, -rb.tz])]),
                            b.tilt_stiffness_Nmm_per_rad * np.eye(2)))
    ref = hm.solve(sp.block_diag([K1, K1], format="csr"), np.concatenate([fs, fa]),
                   sp.block_diag([T1, T1], format="csr"), springs=springs).u[:, 0]
    scale = np.abs(ref).max()
    # both are backward-stable direct solves of the same equations (the SPD K̃ without
    # pivoting, growth 1; the non-symmetric reference with partial pivoting): each forward
    # error is ≲ c · COND · eps with c a modest function of the 778 unknowns; 1e3 (see COND).
    # Measured 3e-15 relative.
    assert np.abs(np.concatenate([us, ua]) - ref).max() <= 1e3 * COND * EPS * scale
    for name, rb, b in bearings:
        q = np.array([rb.uy @ ref[:h.ndof], rb.uy @ ref[h.ndof:]])
        F = -b.K_N_per_mm @ q
        assert np.allclose(reac[name][:2], F, rtol=0, atol=1e3 * COND * EPS * np.abs(F).max())


def test_richardson_gci():
    """Roache's GCI (``kt.richardson``): exact extrapolation of a pure power-law error (exact
    arithmetic up to a few roundings: 1e-12 on the order and the value), the 1.25 safety
    factor on its bar; an
    oscillating sequence claims no order and gets |K2 − K1|."""
    from shaftfe.axisymmetric.kt import richardson
    k_inf, c = 2.5, 0.04
    r = richardson([k_inf + c * h ** 2 for h in (1.0, 0.5, 0.25)])
    assert r["order"] == pytest.approx(2.0, rel=1e-12)
    assert r["value"] == pytest.approx(k_inf, rel=1e-12)
    # the bar is a difference of close numbers: relative rounding ≈ eps · K / ΔK ≈ 1e-13
    assert r["error"] == pytest.approx(1.25 * c * 0.25 ** 2, rel=1e-9)
    r = richardson([2.0, 2.1, 2.05])
    assert r["order"] is None and r["value"] == 2.05 and r["error"] == pytest.approx(0.05)


@pytest.fixture(scope="module")
def coarse(cache):
    v = load_variant("x2_57")
    return v, solve_axisymmetric(v, REF_RPM, AxiOptions(level="coarse"), cache_dir=cache)


def test_truncation_follows_the_valid_fillets(coarse, cache):
    """The default cut follows the fillets outside the omitted features' zones; cutting there
    changes them by less than the tolerance (against the series run until every fillet has
    converged), and the others are named in a note."""
    # the half-seat pressure patches (the seed's placement) are what needs n ≥ 2; the default
    # remote loads have n = 0, 1 only
    v = load_variant("x2_57")
    res = solve_axisymmetric(v, REF_RPM, AxiOptions(level="coarse", seed_load_case=True),
                             cache_dir=cache)
    full = solve_axisymmetric(v, REF_RPM, AxiOptions(level="coarse", converge_all_fillets=True,
                                                     seed_load_case=True), cache_dir=cache)
    crit = res.solution.truncation_fillets
    assert set(crit) == {"fillet:collar", "fillet:bearing_seat_gear"}
    assert len(res.harmonics) < len(full.harmonics)
    a = {p.region: p.von_mises_MPa for p in res.cases[0].peaks}
    b = {p.region: p.von_mises_MPa for p in full.cases[0].peaks}
    top = max(b[f] for f in crit)
    for f in crit:
        # the criterion bounds only the last two increments; the series' decay (the pressure
        # coefficients ∝ 1/n, each harmonic's reach ∝ e^(−n x / r)) makes the whole tail
        # smaller, and this checks it at the criterion's own tolerance, 1e-4 of the largest
        # peak (measured tails 8e-6 and 2e-7 of it)
        assert abs(a[f] - b[f]) <= res.options.truncation * top, f
    assert any("not converged in n" in n and "fillet:cw2_seat" in n for n in res.notes)


def test_fatigue_reference_carries_the_static_peaks(coarse):
    """The fatigue input (the revolved surface) holds the same stresses as the peaks: its
    largest filtered von Mises on the collar fillet is the located peak up to the sampling."""
    _, res = coarse
    ref = static_reference(res)
    assert ref.stress_ref.shape == (6, ref.n_nodes) and ref.cells.shape[0] == 0
    keep = np.ones(ref.n_nodes, dtype=bool)
    keep[ref.excluded] = False
    nodes = ref.regions["fillet:collar"]
    sampled = float(ref.von_mises_ref[nodes[keep[nodes]]].max())
    peak = {p.region: p for p in res.cases[0].peaks}["fillet:collar"].von_mises_MPa
    # the peak's value is the parabola along the outline through the best node (on the same
    # 1° θ sample as these points); P2 outline nodes are h/2 apart, so the vertex is within
    # h/4 of a node and the parabola drops by ½|σ''|(h/4)² there. Fillet element size
    # h ≤ 0.3 ρ at coarse (k_fillet); along the collar fillet |σ''| ≈ 4.7 σ_peak/ρ² (measured
    # from the node values on the default mesh: the peak is sharp, on a scale of ρ/2), so with
    # 5: drop ≤ σ_peak · 5 · 0.3²/32 = 1.4 % of the peak. Measured 0.31 % (coarse).
    assert peak * (1 - 0.0141) <= sampled <= peak * (1 + 1e-12)
    # Cartesian components: von Mises is invariant under the rotation (rounding only: the
    # rotation is a few flops per component, 1e-12 of the peak)
    from shaftfe.axisymmetric.solve import surface_sigma
    from shaftfe.fe.recovery import von_mises
    S = res.solution.surface
    keep_nodes = np.nonzero(~S.on_axis)[0]
    theta = np.radians(np.arange(0.0, 360.0, 1.0))
    local = von_mises(surface_sigma(res.solution, keep_nodes, theta)).ravel()
    assert np.abs(von_mises(ref.stress_ref) - local).max() <= 1e-12 * peak


def test_fatigue_cli_axisymmetric(tmp_path, cache, monkeypatch, capsys):
    from shaftfe.cli import main
    from shaftfe.util.paths import DEFAULT_SPECTRUM
    monkeypatch.setenv("SHAFTFE_CACHE_DIR", str(cache))
    monkeypatch.setenv("MPLBACKEND", "Agg")
    out = tmp_path / "fat"
    code = main(["fatigue", "--method", "seed", str(DEFAULT_SPECTRUM),
                 "--model", "axisymmetric", "--level",
                 "coarse", "--seed-load-case", "--out", str(out), "--json"])
    assert code == 0
    s = json.loads(capsys.readouterr().out)
    assert s["inputs"]["model"] == "axisymmetric"
    assert s["hot_spot"]["region"] == "fillet:collar"       # the seed's hot spot (§8.3)
    assert abs(s["hot_spot"]["xyz_mm"][0] - 64.5) < 1.0
    assert (out / "fatigue.vtu").stat().st_size > 0
    code = main(["fatigue", "--method", "seed", str(DEFAULT_SPECTRUM),
                 "--model", "axisymmetric", "--level",
                 "medium", "--out", str(tmp_path / "bad")])
    err = capsys.readouterr().err
    assert code == 2 and "--level" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "bad").exists()


def test_report_axisymmetric(tmp_path, cache, monkeypatch):
    """``shaftfe report --model axisymmetric``: the page, summary and VTU of the revolved
    surface, with the static and fatigue fields on the same points."""
    import meshio

    from shaftfe.commands.report import make_report
    from shaftfe.report.options import ReportOptions
    monkeypatch.setenv("MPLBACKEND", "Agg")
    out = tmp_path / "rep"
    make_report(ReportOptions(level="coarse", model="axisymmetric", pictures=False,
                              seed_load_case=True, cache_dir=str(cache)), out, json_out=True)
    s = json.loads((out / "summary.json").read_text())
    assert s["static"]["model"] == "axisymmetric"
    c0 = s["static"]["cases"][0]
    assert c0["peak_region"] == "fillet:collar"
    m = meshio.read(out / "x2_57.vtu")
    n = m.points.shape[0]
    assert m.cells[0].type == "triangle"
    for name in ("displacement", "von_mises", "stress", "safety_factor", "life_blocks"):
        assert m.point_data[name].shape[0] == n
    # the VTU at the first design speed (10 000 rpm = REF_RPM, scale 1) holds the fatigue hot
    # spot's von Mises at its node: the same float64 (exact)
    hs = s["fatigue"]["hot_spot"]
    assert m.point_data["von_mises"][hs["node"]] == hs["von_mises_ref_MPa"]
    html = (out / "index.html").read_text()
    assert "axisymmetric" in html and "revolved surface" in html
    assert math.isfinite(s["fatigue"]["hot_spot"]["safety_factor"])


def _mass_on_springs(k, angle_deg: float = 0.0):
    """Ø20 × 100 steel shaft on two equal springs at x = 10 and 90 (k: a stiffness in N/mm, or
    a 2×2 matrix), one 1 kg part at mid-span with e = 2 mm: the classic mass on springs, the
    shaft a third spring in series, made massless (density 0) so that its own spin softening
    stays out of this reference (validated in test_spin_softening_ross.py)."""
    from dataclasses import replace

    from shaftfe.model.examples import STEEL
    from shaftfe.model.variant import Attachment, Bearing, Segment, Variant
    K = ((k, 0.0), (0.0, k)) if np.isscalar(k) else tuple(map(tuple, k))
    brg = (Bearing("L", "x", 10.0, 10.0, 1e4, 1e4, K, axial=True),
           Bearing("R", "x", 90.0, 10.0, 1e4, 1e4, K))
    att = (Attachment("w", 45.0, 55.0, 1.0, 2.0, 50.0, angle_deg=angle_deg),)
    return Variant("spin", "mass on springs", (Segment("a", 0.0, 100.0, 20.0, 0.0),), brg, att,
                   replace(STEEL, density_t_mm3=0.0), 0.0)


def test_spin_softening_is_the_mass_on_springs(tmp_path):
    """u = m e ω² / (k_eff − m ω²): the equilibrium k_eff u = m ω² (e + u) of a mass on a
    spring in the co-rotating frame (the undamped Jeffcott rotor's synchronous response below
    its critical speed), with k_eff the two bearing springs in parallel in series with the
    shaft at mid-span (Timoshenko beam: L³/(48 E I) + L/(4 κ G A), κ = 6(1 + ν)/(7 + 6ν) for
    a solid circle, Cowper 1966)."""
    v = _mass_on_springs(100.0)
    m, e, k = 1.0, 2.0, 100.0
    c_shaft = _shaft_compliance(v)
    w2 = 50e3 / m                              # m ω² = 50 N/mm: 2k − m ω² = 150 = ¾ of 2k
    rpm = math.sqrt(w2) * 60 / (2 * math.pi)
    res = solve_axisymmetric(v, rpm, AxiOptions(spin_softening=True), cache_dir=tmp_path)
    q = res.solution.attachment_motion["w"][0]
    k_eff = 1.0 / (1.0 / (2 * k) + c_shaft)
    mw2 = m * w2 * 1e-3
    want = m * e * 1e-3 * w2 / (k_eff - mw2)
    # the beam model of the shaft's share of the compliance (δ = 2k c_shaft = 1.5e-3 of it)
    # misses the local seat deformation and the load's distribution; allowing 10 % of that
    # share, amplified by 2k/(2k − mω²) = 1.33: 2.0e-4 (measured −8.7e-5)
    delta, amp = 2 * k * c_shaft, 2 * k / (2 * k - mw2)
    assert abs(q / want - 1) <= 0.1 * delta * amp
    # without softening the same shaft gives the unamplified deflection
    plain = solve_axisymmetric(v, rpm, AxiOptions(spin_softening=False), cache_dir=tmp_path)
    u0 = {s.name: s for s in plain.cases[0].stations}["seat:w"].uy_mm
    assert abs(u0 / (m * e * 1e-3 * w2 / k_eff) - 1) <= 0.1 * delta
    # the reactions balance the load and the softening force m ω² u: the direct solve's
    # backward error (≤ 1e-9) times the rigid translation's share of the reactions
    assert res.cases[0].equilibrium_residual <= 1e-8


def _shaft_compliance(v) -> float:
    """Mid-span compliance of the 80 mm bearing span, Timoshenko beam (Cowper's κ)."""
    E, nu, d, L = v.material.E_MPa, v.material.nu, 20.0, 80.0
    inertia, area = math.pi * d ** 4 / 64, math.pi * d ** 2 / 4
    kap = 6 * (1 + nu) / (7 + 6 * nu)
    return L ** 3 / (48 * E * inertia) + L / (4 * kap * E / (2 * (1 + nu)) * area)


def test_spin_softening_anisotropic_bearings_off_axis(tmp_path):
    """The same closed form in 2D: K12 ≠ 0, K11 ≠ K22 and a load at 30°, so both n = 1 parts
    and the bearings' Woodbury term carry it: u = (K_eff − m ω² I)⁻¹ F d with
    K_eff = ((2K)⁻¹ + c_shaft I)⁻¹."""
    Kb = np.array([[100.0, 30.0], [30.0, 150.0]])
    v = _mass_on_springs(Kb, 30.0)
    w2 = 50e3
    rpm = math.sqrt(w2) * 60 / (2 * math.pi)
    res = solve_axisymmetric(v, rpm, AxiOptions(spin_softening=True), cache_dir=tmp_path)
    q = np.array(res.solution.attachment_motion["w"])
    c_shaft = _shaft_compliance(v)
    K_eff = np.linalg.inv(np.linalg.inv(2 * Kb) + c_shaft * np.eye(2))
    mw2, F = w2 * 1e-3, 2e-3 * w2
    d = np.array([math.cos(math.radians(30.0)), math.sin(math.radians(30.0))])
    want = np.linalg.solve(K_eff - mw2 * np.eye(2), F * d)
    # as the isotropic case: 10 % of the shaft's compliance share (c_shaft · λmax(2K)),
    # amplified at most by λmax(K_eff)/(λmin(K_eff) − m ω²): 6.6e-4 (measured 9.0e-5)
    lam = np.linalg.eigvalsh(K_eff)
    bound = 0.1 * c_shaft * np.linalg.eigvalsh(2 * Kb).max() * lam.max() / (lam.min() - mw2)
    assert np.abs(q - want).max() <= bound * np.abs(want).max()
    assert res.cases[0].equilibrium_residual <= 1e-8


def test_spin_softening_rigid_supports_are_the_stiff_spring_limit(tmp_path):
    """The rigid-support branch (multipliers) against the spring branch with k = 1e8 N/mm:
    they differ by the springs' share of the compliance, (1/c_shaft)/(2k) = 6.8e-4, amplified
    by k_shaft/(k_shaft − m ω²) = 1.04; allowing 4× for the seats' distribution: 2.8e-3
    (measured 7.4e-4). The reactions, from the multipliers, close the equilibrium."""
    w2 = 5e6                                   # m ω² = 5000 N/mm, 4 % of the shaft's stiffness
    rpm = math.sqrt(w2) * 60 / (2 * math.pi)
    opts = AxiOptions(spin_softening=True)
    rigid = solve_axisymmetric(_mass_on_springs(100.0), rpm,
                               AxiOptions(spin_softening=True, rigid_supports=True),
                               cache_dir=tmp_path)
    k = 1e8
    stiff = solve_axisymmetric(_mass_on_springs(k), rpm, opts, cache_dir=tmp_path)
    ks = 1.0 / _shaft_compliance(stiff.solution.variant)
    bound = 4 * ks / (2 * k) * ks / (ks - w2 * 1e-3)
    qr = rigid.solution.attachment_motion["w"][0]
    qs = stiff.solution.attachment_motion["w"][0]
    assert abs(qs / qr - 1) <= bound
    for a, b in zip(rigid.cases[0].bearings, stiff.cases[0].bearings, strict=True):
        assert abs(b.F_radial_N / a.F_radial_N - 1) <= bound
    assert rigid.cases[0].equilibrium_residual <= 1e-8


def test_spin_softening_refuses_a_supercritical_speed(tmp_path):
    """m ω² = 300 N/mm > 2k = 200 N/mm: the softened rotor is past its critical speed."""
    from shaftfe.errors import SolverError
    rpm = math.sqrt(3e5) * 60 / (2 * math.pi)
    with pytest.raises(SolverError, match="critical speed"):
        solve_axisymmetric(_mass_on_springs(100.0), rpm, AxiOptions(spin_softening=True),
                           cache_dir=tmp_path)


def test_spin_softening_solves_each_speed(tmp_path):
    """Several speeds with softening: one solve per speed (the response is not ∝ rpm²), each
    case the very case of a solve at that speed alone (the same arithmetic: exact)."""
    v = _mass_on_springs(100.0)
    speeds = (1500.0, 2000.0)                  # below the softened critical speed (≈ 4270 rpm)
    both = solve_axisymmetric(v, list(speeds), AxiOptions(spin_softening=True),
                              cache_dir=tmp_path)
    for r, case in zip(speeds, both.cases, strict=True):
        alone = solve_axisymmetric(v, r, AxiOptions(spin_softening=True), cache_dir=tmp_path)
        assert case.rpm == r
        assert [b.F_radial_N for b in case.bearings] == \
            [b.F_radial_N for b in alone.cases[0].bearings]
        assert [p.von_mises_MPa for p in case.peaks] == \
            [p.von_mises_MPa for p in alone.cases[0].peaks]
