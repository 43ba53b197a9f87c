"""3D static analysis (issue 4): assembly, loads, supports, recovery kernels, scaling, CLI.

Fast checks on coarse meshes; the accuracy checks against beam theory and Kt fits live in
tests/validation/test_static_*.py.
"""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

from shaftfe.errors import InputError, SolverError
from shaftfe.model.examples import STEEL
from shaftfe.model.variant import Attachment, Bearing, Segment, Variant

K_ISO = ((35_030.0, 0.0), (0.0, 35_030.0))
# every check here compares the linear model (loads at the undeformed seats) with statics, beam
# theory or ∝ rpm² scaling: spin_softening=False (its own tests: test_static_spin_softening.py)


def _opts(**kw):
    from shaftfe.static.model import StaticOptions
    return StaticOptions(spin_softening=False, **kw)


def cylinder(angle=0.0, K_left=K_ISO, K_right=K_ISO, axial=True, mass=0.24) -> Variant:
    """Ø20 × 120 mm cylinder, bearings on [5, 15] and [105, 115], one part on [55, 65]."""
    segs = (Segment("s", 0.0, 120.0, 20.0, 0.0),)
    brg = (Bearing("L", "x", 10.0, 10.0, 14_400.0, 10_000.0, K_left, axial=axial),
           Bearing("R", "x", 110.0, 10.0, 14_400.0, 10_000.0, K_right))
    att = (Attachment("w", 55.0, 65.0, mass, 20.0, 60.0, angle_deg=angle),)
    return Variant("cyl", "test cylinder", segs, brg, att, STEEL, 0.0)


def statics_bearing_loads(v, cache, level="default", **opts) -> np.ndarray:
    """Bearing loads (2, 2) [(Fy, Fz) at L, at R] = −reactions, from the applied nodal load
    vector by force and moment equilibrium of a beam on two supports without moment restraint
    (tilt free): the exact statics of the discretised load, independent of the solve."""
    from shaftfe import static
    model = static.build_model(v, _opts(level=level, **opts), cache_dir=cache)
    f = model.f.reshape(-1, 3)
    x, y, z = model.shaft_mesh.mesh.doflocs
    xl, xr = (b.x_center_mm for b in v.bearings)
    # moments about the left bearing centre (z- and −y-components), carried by the right one
    load_r = np.array([(x - xl) @ f[:, 1] - y @ f[:, 0],
                       (x - xl) @ f[:, 2] - z @ f[:, 0]]) / (xr - xl)
    return np.array([f[:, 1:].sum(axis=0) - load_r, load_r])


@pytest.fixture(scope="module")
def base(cache):
    from shaftfe.static.solve import solve_static
    return solve_static(cylinder(), [5000.0, 10000.0], _opts(level="default"),
                        cache_dir=cache, beam=False)


# --------------------------------------------------------------------------- assembly

@pytest.mark.parametrize("order", [1, 2])
def test_vectorised_stiffness_equals_scikit_fem(cache, order):
    """The einsum assembly equals scikit-fem's linear_elasticity form (same weak form) to
    round-off, and annihilates the six rigid-body modes (K R = 0, exact for any mesh)."""
    from shaftfe.fe import assembly as fem
    from shaftfe.solid.mesh import build_mesh
    m = build_mesh(cylinder(), "coarse", order=order, cache_dir=cache).mesh
    K = fem.elasticity_stiffness(m, STEEL.E_MPa, STEEL.nu)
    K2 = fem.elasticity_stiffness_skfem(m, STEEL.E_MPa, STEEL.nu)
    # exact arithmetic (round-off only; measured 5.5e-16)
    assert abs(K - K2).max() <= 1e-12 * abs(K2).max()
    R = fem.rigid_body_modes(m, (60.0, 1.0, -2.0))
    # exact arithmetic: a row of K R sums ~80 terms |K| × |R| ≤ 60 mm: ≤ 80·60·eps ≈ 1e-12
    # of max|K| (measured 3.3e-14); 1e-10 = 100× that
    assert np.abs(K @ R).max() <= 1e-10 * abs(K).max()


def test_rbe3_rows_reproduce_rigid_motions_and_area_means(cache):
    """RBE3 rows: a rigid motion of the seat is returned exactly (definition of the
    least-squares fit), and for a full cylindrical seat the translation row is the area mean
    (1/A)∫u_y dA: for u_y = x² over x ∈ [5, 15] that is (15³ − 5³)/30 (exact integral). The
    tolerance 1e-3 covers the P2 facets' approximation of the cylinder (area error ~1e-4),
    which makes the area weights slightly non-uniform."""
    from shaftfe.fe import assembly as fem
    from shaftfe.solid.mesh import build_mesh
    m = build_mesh(cylinder(), "default", cache_dir=cache).mesh
    G = fem.rigid_rows(m, m.boundaries["bearing:L"], (10.0, 0.0, 0.0))
    # exact arithmetic (a least-squares fit reproduces what it fits; measured 1e-15)
    np.testing.assert_allclose(G @ fem.rigid_body_modes(m, (10.0, 0.0, 0.0)), np.eye(6),
                               atol=1e-10)
    u = np.zeros(3 * m.doflocs.shape[1])
    u[1::3] = m.doflocs[0] ** 2             # u_y = x²: mean over x ∈ [5, 15] is 108.33…
    # mesh: P2 facet area weights (docstring; measured 4e-6)
    assert (G @ u)[1] == pytest.approx((15**3 - 5**3) / 3 / 10, rel=1e-3)


@pytest.mark.parametrize("order", [1, 2])
def test_facet_quadrature_equals_scikit_fem_facet_basis(cache, order):
    """``fe.facets.facet_quadrature`` (facet nodes only) against scikit-fem's ``FacetBasis``
    (the element's inverse isoparametric map, Newton to 1e-12) on a curved seat and a flat end
    face: the same points, outward normals, area weights and load vectors to round-off."""
    from skfem import ElementVector, FacetBasis, LinearForm

    from shaftfe.fe import assembly as fem
    from shaftfe.fe.facets import facet_quadrature
    from shaftfe.solid.mesh import build_mesh
    m = build_mesh(cylinder(), "coarse", order=order, cache_dir=cache).mesh
    ends = m.boundary_facets()[np.abs(m.p[0, m.facets[:, m.boundary_facets()]]).max(axis=0)
                               < 1e-9]
    for facets in (m.boundaries["bearing:L"], m.boundaries["load:w:pressed"], ends):
        fq = facet_quadrature(m, facets)
        fb = FacetBasis(m, ElementVector(fem.scalar_element(m)), facets=facets,
                        mapping=fem.robust_mapping(m), intorder=4 if order == 2 else 2)
        xb = np.asarray(fb.global_coordinates())
        # facet_nodes turns some facets round (outward order), which permutes their points
        # within the facet (the rules are symmetric): compare each facet's points sorted
        ia, ib = (np.lexsort(np.round(x, 6)[::-1], axis=-1) for x in (fq.x, xb))

        def by(a, i):
            return np.take_along_axis(a, i[None] if a.ndim == 3 else i, axis=-1)
        # Newton's 1e-12 stop on the reference coordinates, times |dx/dξ| ≤ 10 mm: ≤ 1e-11 mm
        np.testing.assert_allclose(by(fq.x, ia), by(xb, ib), atol=1e-9)
        # unit normals and area weights: round-off plus the same 1e-12 stop, scaled by the
        # facets' curvature (≤ 1/R on an R ≥ 5 mm seat): 1e-9 leaves ≥ 100×
        np.testing.assert_allclose(by(fq.n, ia), by(np.asarray(fb.normals), ib), atol=1e-9)
        np.testing.assert_allclose(by(fq.dA, ia), by(np.asarray(fb.dx), ib), rtol=1e-9)

        @LinearForm
        def form(v, w):
            return -w.x[2] * v[1] + w.x[1] * v[2] + (w.n[0] + 2.0) * v[0]

        ref = form.assemble(fb)
        g = np.array([fq.n[0] + 2.0, -fq.x[2], fq.x[1]])
        # a sum of ≤ 6 × nq products per entry of the quantities above: the same bound
        np.testing.assert_allclose(fq.vector_load(g), ref, atol=1e-9 * np.abs(ref).max())


@pytest.mark.parametrize("dist", ["uniform", "cosine"])
def test_surface_load_net_force_and_zero_torque(cache, dist):
    """Pressure on the pressed half seat: net force exactly F along e, nothing across it and no
    torque about the axis (statics of the half-cylinder: ∫ −p n dA ∥ e by symmetry)."""
    from shaftfe.fe import assembly as fem
    from shaftfe.solid.mesh import build_mesh
    v = cylinder(angle=37.0)
    m = build_mesh(v, "default", cache_dir=cache).mesh
    e = np.array([0.0, math.cos(math.radians(37.0)), math.sin(math.radians(37.0))])
    f = fem.surface_load(m, m.boundaries["load:w:pressed"], 1234.5, e, dist).reshape(-1, 3)
    # exact arithmetic (normalised to F; measured 1.1e-13 N = 1e-16 F)
    np.testing.assert_allclose(f.sum(axis=0), 1234.5 * e, atol=1e-9)
    x = m.doflocs
    # exact arithmetic: every nodal force ∥ e; torque round-off ~ eps·F·R = 3e-12 N·mm
    # (measured 1.6e-13); 1e-8 N·mm = 1e-12 of F·R
    assert abs((x[1] * f[:, 2] - x[2] * f[:, 1]).sum()) < 1e-8
    # the load sits on the half facing −e (the part's bore bears there); "loaded": above the
    # round-off of a zero entry (1e-9 of the largest)
    loaded = np.abs(f).sum(axis=1) > 1e-9 * np.abs(f).max()
    # exact split: nodes on the plane are off it by the 1e-9 mm coordinate rounding only
    # (measured 6.7e-10 mm)
    assert (x[1:, loaded].T @ e[1:] <= 1e-9).all()


@pytest.mark.parametrize("order", [1, 2])
def test_recovery_patch_test(cache, order):
    """Patch test (Zienkiewicz & Taylor, The FEM vol. 1, §9): a linear displacement field —
    here uniaxial strain ε plus a shear γ — is reproduced exactly by isoparametric P1/P2
    elements, so the recovered nodal stress must be the exact constant σ_xx = E ε (lateral
    contraction −ν ε free), τ_xy = G γ, everywhere, surface nodes included. (A quadratic field
    such as pure bending is NOT exact on curved P2 tets: the validation tests cover it.)"""
    from shaftfe.fe import recovery
    from shaftfe.solid.mesh import build_mesh
    m = build_mesh(cylinder(), "coarse", order=order, cache_dir=cache).mesh
    x, y, z = m.doflocs
    eps, gam, nu, E = 1e-3, 4e-4, STEEL.nu, STEEL.E_MPa
    u = np.column_stack([eps * x + gam * y, -nu * eps * y, -nu * eps * z]).ravel()
    s = recovery.nodal_stress(m, u, E, nu)
    G = E / (2 * (1 + nu))
    # exact for linear fields (patch test): round-off of the gradients on curved P2 tets,
    # measured ≤ 5.9e-14 relative and 3.2e-12 MPa (σ = 210 MPa) in the zero components
    np.testing.assert_allclose(s[0], E * eps, rtol=1e-10)
    np.testing.assert_allclose(s[3], G * gam, rtol=1e-10)
    assert np.abs(s[[1, 2, 4, 5]]).max() < 1e-9
    vm = math.sqrt((E * eps) ** 2 + 3 * (G * gam) ** 2)
    np.testing.assert_allclose(recovery.von_mises(s), vm, rtol=1e-10)     # same reason


def test_partition_equals_slicing():
    """fem.partition against scipy's own slicing (exact: the same entries are copied, none is
    computed), on a random symmetric matrix: the cut holds the first and the last dof, and two
    rows are empty (one cut, one not)."""
    import scipy.sparse as sp

    from shaftfe.fe import assembly as fem
    rng = np.random.default_rng(3)
    A = sp.random(60, 60, density=0.1, random_state=rng, format="csr")
    keep = np.ones(60)
    keep[[7, 12]] = 0.0              # two rows and columns with no entries at all
    D = sp.diags(keep)
    A = (D @ (A + A.T + sp.eye(60)) @ D).tocsr()
    A.eliminate_zeros()
    cut = np.array([0, 5, 6, 7, 31, 59])
    free = np.setdiff1d(np.arange(60), cut)
    K_II, K_IB = fem.partition(A, cut)
    for got, want in ((K_II, A[free][:, free]), (K_IB, A[free][:, cut])):
        assert got.shape == want.shape and got.has_sorted_indices
        assert (got != want).nnz == 0


def test_von_mises_and_principal_kernels():
    """von Mises of uniaxial σ is |σ|, of pure shear τ is √3 τ; principal stresses are the
    eigenvalues (hand-computed: [[2,1,0],[1,2,0],[0,0,5]] → 5, 3, 1)."""
    from shaftfe.fe.recovery import principal, von_mises
    s = np.array([[7.0, 0.0, 0.0], [0, 0, 0], [0, 0, 0], [0, 4.0, 0], [0, 0, 0], [0, 0, 0]])
    # exact arithmetic (round-off only, O(1) values)
    np.testing.assert_allclose(von_mises(s), [7.0, math.sqrt(3) * 4.0, 0.0], atol=1e-12)
    p = principal(np.array([[2.0], [2.0], [5.0], [1.0], [0.0], [0.0]]))
    np.testing.assert_allclose(p[:, 0], [5.0, 3.0, 1.0], atol=1e-12)     # exact arithmetic


# --------------------------------------------------------------------------- solve

def test_every_solve_in_equilibrium(base):
    """Global statics: Σ reactions + Σ loads = 0 (rel. 1e-8) and the full system's relative
    residual ≤ 1e-8, with the load equal to m e ω² (Attachment.force_N) at each rpm."""
    for c in base.cases:
        assert c.equilibrium_residual <= 1e-8      # solver contract (static.RESIDUAL_TOL)
        F = cylinder().attachments[0].force_N(c.rpm)
        # exact arithmetic (loads normalised to m e ω²; measured 1.7e-16 F)
        np.testing.assert_allclose(c.load_sum_N, [0.0, F, 0.0], atol=1e-8 * F)
    assert base.diagnostics["relative_residual"] <= 1e-8     # solver contract (RESIDUAL_TOL)
    # the Jacobi-scaled capacitance is well conditioned (measured 109): 1e8 flags a scaling
    # regression long before the solver's own refusal at 1e13 (eps·cond 2e-8 vs 2e-3)
    assert base.diagnostics["cond_S"] < 1e8


def test_run_time_entries_are_kept_out_of_the_diagnostics(base):
    """Wall-clock seconds and the mesh-cache flag measure the run, not the result: they sit in
    ``StaticResult.run`` (summary.json "run"), never in ``diagnostics`` (issue 8)."""
    run_keys = {"factor_seconds", "solve_seconds", "mesh_seconds", "mesh_from_cache",
                "assembly_seconds", "model_seconds", "recovery_seconds", "total_seconds"}
    assert run_keys <= set(base.run)
    assert not run_keys & set(base.diagnostics)
    d = base.to_dict()
    assert d["run"] == base.run and not run_keys & set(d["diagnostics"])


def test_the_options_refuse_the_band_the_command_line_refuses():
    """One rule for ``--exclude-mm`` (``util.limits.check_exclude_mm``): options built in
    Python meet the command line's bounds, [0, 5] mm."""
    from shaftfe.axisymmetric.model import AxiOptions, check_options
    from shaftfe.static.model import check_options as _check_options
    for bad in (-0.1, 5.5, float("nan")):
        with pytest.raises(InputError, match=r"\[0, 5\] mm"):
            _check_options(_opts(exclude_mm=bad))
        with pytest.raises(InputError, match=r"\[0, 5\] mm"):
            check_options(AxiOptions(exclude_mm=bad))
    _check_options(_opts(exclude_mm=5.0))
    check_options(AxiOptions(exclude_mm=0.0))


@pytest.mark.parametrize("bad,option", [({"order": 3}, "--order"), ({"level": "huge"}, "--level"),
                                        ({"solver": "foo"}, "--solver"),
                                        ({"load_distribution": "x"}, "--load-distribution")])
def test_the_static_options_hold_the_command_lines_rules(bad, option):
    """``static.model.check_options`` is the one set of rules ``shaftfe static`` applies to its
    options (the command builds ``StaticOptions`` and calls it): a caller in Python meets the
    same refusal, naming the command line's option."""
    from shaftfe.static.model import check_options
    with pytest.raises(InputError) as e:
        check_options(_opts(**bad))
    assert e.value.source == option


def test_static_cache_keeps_the_relative_residual(base, cache):
    """The static reference that ``shaftfe fatigue`` reuses carries the solve's relative
    residual, through the disk cache too (reference: the solve's own diagnostics)."""
    from shaftfe.static import cache as static_cache
    from shaftfe.static.solve import load_or_solve
    opts = _opts(level="default")
    ref = static_cache.store(cylinder(), opts, base, cache)
    assert ref.relative_residual == base.diagnostics["relative_residual"] <= 1e-8   # contract
    hit = load_or_solve(cylinder(), opts, cache)
    assert hit.from_cache and hit.relative_residual == ref.relative_residual


def test_surface_load_cache_is_bit_identical(cache):
    """Parts sharing a seat share its facet basis within one model build: the cached load
    vectors equal the uncached ones bit for bit (uniform and cosine, two directions)."""
    from shaftfe.fe import assembly as fem
    from shaftfe.solid.mesh import build_mesh
    m = build_mesh(cylinder(), "default", cache_dir=cache).mesh
    facets = m.boundaries["load:w:pressed"]
    shared: dict = {}
    for dist in ("uniform", "cosine"):
        for ang, F in ((0.0, 100.0), (20.0, 3.5)):
            e = np.array([0.0, math.cos(math.radians(ang)), math.sin(math.radians(ang))])
            ref = fem.surface_load(m, facets, F, e, dist)
            got = fem.surface_load(m, facets, F, e, dist, cache=shared)
            assert np.array_equal(ref, got), (dist, ang)
    assert len(shared) == 1


def test_doubling_rpm_multiplies_stresses_by_four(base):
    """Centrifugal loads are m e ω²: 2× rpm → 4× load → 4× every stress, deflection and
    reaction (linearity)."""
    lo, hi = base.case(5000.0), base.case(10000.0)
    # exact arithmetic (round-off only): one solve scaled by (rpm/REF_RPM)²
    assert hi.peak_von_mises_MPa == pytest.approx(4 * lo.peak_von_mises_MPa, rel=1e-12)
    assert hi.max_deflection_mm == pytest.approx(4 * lo.max_deflection_mm, rel=1e-12)
    for a, b in zip(lo.bearings, hi.bearings, strict=True):
        assert b.F_radial_N == pytest.approx(4 * a.F_radial_N, rel=1e-12)     # exact, as above
        assert b.L10h == pytest.approx(a.L10h / 128, rel=1e-12)   # exact: (1/4)³ and n × 2


def test_reactions_statics_and_l10h(base, cache):
    """Reactions equal the statics of the applied load (two supports, tilt free), ≈ F/2 each
    for the symmetric case; L10h = (C/P)³ 10⁶ / (60 n) (ISO 281 basic rating life)."""
    c = base.case(10000.0)
    P = statics_bearing_loads(cylinder(), cache)
    F = cylinder().attachments[0].force_N(10000.0)
    for b, p in zip(c.bearings, P, strict=True):
        # statics exact: round-off only (measured 4.8e-14 F; PARDISO/SuperLU alike)
        np.testing.assert_allclose([-b.Fy_N, -b.Fz_N], p, rtol=1e-9, atol=1e-9 * F)
        # load centroid ≈ x = 60: exact for a seat mesh symmetric about 60, else off by the
        # P2 facet weights' error (~1e-4, as the RBE3 test); measured 1e-13
        assert b.F_radial_N == pytest.approx(F / 2, rel=1e-3)
        # exact arithmetic (the same formula)
        assert b.L10h == pytest.approx((14_400.0 / b.F_radial_N) ** 3 * 1e6 / 600_000.0,
                                       rel=1e-12)


def test_rotating_the_load_rotates_the_response(cache):
    """Isotropic springs: turning the eccentricity by 37° turns the reactions (statics of the
    load, to 1e-9) and the deflection vector at the seat (axisymmetric structure; the two
    meshes differ — each is split on its own load plane — so magnitude to 0.5 %, angle 0.3°)."""
    from shaftfe.static.solve import solve_static
    v = cylinder(angle=37.0)
    r0 = solve_static(cylinder(), [10000.0], _opts(level="fine"), cache_dir=cache,
                      beam=False)
    r = solve_static(v, [10000.0], _opts(level="fine"), cache_dir=cache, beam=False)
    a, b = r0.case(10000.0), r.case(10000.0)
    P = statics_bearing_loads(v, cache, level="fine")
    for b1, p in zip(b.bearings, P, strict=True):
        # statics exact: round-off only (measured 1.9e-13)
        np.testing.assert_allclose([-b1.Fy_N, -b1.Fz_N], p, rtol=1e-9)
        # exact arithmetic: every nodal force is ∥ e, so the statics reaction is too
        # (measured 7e-15°); was abs 1e-2
        assert math.degrees(math.atan2(p[1], p[0])) == pytest.approx(37.0, abs=1e-10)
    s0, s1 = a.stations[0], b.stations[0]
    # mesh: two different fine meshes, each within the fine level's deflection error (0.22 %,
    # the two-level estimate of test_error_estimate_from_two_levels): |Δu| ≤ 0.45 %, and a
    # 0.45 % transverse error turns the vector by ≤ 0.26°; measured 1e-4 and 6e-5°
    assert s1.u_mm == pytest.approx(s0.u_mm, rel=5e-3)
    assert math.degrees(math.atan2(s1.uz_mm, s1.uy_mm)) == pytest.approx(37.0, abs=0.3)
    # mesh: a nodal peak converges more slowly than the deflection (measured 0.86 %)
    assert b.peak_von_mises_MPa == pytest.approx(a.peak_von_mises_MPa, rel=0.05)


def test_coupled_spring_gives_closed_form_remote_displacement(cache):
    """K12 ≠ 0: the remote point (measured from the displacement field through the RBE3 rows)
    moves by K_b⁻¹ P, P the bearing load from statics — including the component across the
    load that K12 creates."""
    from shaftfe.static.solve import solve_static
    Kc = ((35_030.0, 8_756.0), (8_756.0, 35_030.0))
    v = cylinder(K_left=Kc, K_right=Kc)
    r = solve_static(v, [10000.0], _opts(level="default"), cache_dir=cache, beam=False)
    P = statics_bearing_loads(v, cache)
    for b, p in zip(r.cases[0].bearings, P, strict=True):
        q = np.linalg.solve(np.array(Kc), p)
        # spring law exact (λ = C R u is an equation of the solve): round-off only, measured
        # 3.3e-13; cond(Kc) = 1.7 adds nothing
        np.testing.assert_allclose([b.uy_mm, b.uz_mm], q, rtol=1e-8)
        assert b.uz_mm < -0.2 * b.uy_mm < 0     # K12 moves it across: K⁻¹ gives −0.25 uy


def test_rigid_supports_hold_remote_points(cache):
    """--rigid-supports: the remote points do not move; the reactions are the statics."""
    from shaftfe.static.solve import solve_static
    r = solve_static(cylinder(), [10000.0], _opts(level="default", rigid_supports=True),
                     cache_dir=cache, beam=False)
    P = statics_bearing_loads(cylinder(), cache, rigid_supports=True)
    for b, p in zip(r.cases[0].bearings, P, strict=True):
        # hard rows R u = 0 (exact Lagrange multipliers): round-off only, ~eps × max|u| =
        # 0.07 mm → 1.6e-17 mm (measured 1e-17); 1e-12 mm = 1.4e-11 of max|u|
        assert abs(b.uy_mm) < 1e-12 and abs(b.uz_mm) < 1e-12
        # statics exact: round-off only (measured 2.5e-10 N absolute on a ~3 kN reaction
        # whose Fz part is ~0: hence atol)
        np.testing.assert_allclose([-b.Fy_N, -b.Fz_N], p, rtol=1e-9, atol=1e-6)


@pytest.mark.parametrize("what,expect", [
    ("axial", "axial translation"),
    ("one_bearing", "tilt"),
])
def test_missing_support_is_named(cache, what, expect):
    """A support set that leaves a rigid motion free raises SolverError naming it, before any
    solver can return garbage (FINDINGS pitfall 8)."""
    from shaftfe.static.solve import solve_static
    v, opts = cylinder(), _opts(level="default")
    if what == "axial":
        v = cylinder(axial=False)
    elif what == "one_bearing":
        v = dataclasses.replace(v, bearings=v.bearings[:1])
    with pytest.raises(SolverError, match=expect):
        solve_static(v, 10000.0, opts, cache_dir=cache, beam=False)


def test_single_bearing_with_tilt_spring(cache):
    """One bearing with a tilt stiffness k_t carries the part as a cantilever: by statics the
    remote point takes the force F (u_y = F/k) and the moment F·(x_load − x_b) about z
    (θ_z = F (x_load − x_b) / k_t, the load acting at its seat centroid)."""
    from shaftfe import static
    k_t = 5e7
    v = cylinder()
    v = dataclasses.replace(v, bearings=(dataclasses.replace(
        v.bearings[0], tilt_stiffness_Nmm_per_rad=k_t),))
    model = static.build_model(v, _opts(level="default"), cache_dir=cache)
    sol = static.solve_model(model)
    f = model.f.reshape(-1, 3)
    x, y = model.shaft_mesh.mesh.doflocs[:2]
    F = f[:, 1].sum()
    Mz = (x - 10.0) @ f[:, 1] - y @ f[:, 0]                # moment about the bearing centre
    q = model.couplings[0].G @ sol.u
    # spring law exact: round-off only (measured 1.1e-14 and 2.9e-14)
    assert q[1] == pytest.approx(F / 35_030.0, rel=1e-8)
    assert q[5] == pytest.approx(Mz / k_t, rel=1e-8)
    # load centroid ≈ x = 60 (as in test_reactions_statics_and_l10h; measured exact)
    assert Mz == pytest.approx(F * 50.0, rel=1e-3)


def test_exclusion_band(cache):
    """--exclude-mm: the filtered peaks skip every node within the band of a patch edge (and
    still the element layer); the unfiltered peak is unchanged."""
    from scipy.spatial import cKDTree

    from shaftfe.fe import recovery
    from shaftfe.solid.mesh import build_mesh
    m = build_mesh(cylinder(), "default", cache_dir=cache).mesh
    patches = [np.asarray(f) for g, f in m.boundaries.items()
               if g.startswith("bearing:") or g.endswith(":pressed")]
    layer = recovery.excluded_nodes(m, patches)
    band = recovery.excluded_nodes(m, patches, 12.0)
    assert np.isin(layer, band).all() and band.size > layer.size
    edge = np.unique(np.concatenate([recovery.patch_edge_nodes(m, p) for p in patches]))
    d, _ = cKDTree(m.doflocs[:, edge].T).query(m.doflocs.T)
    assert np.isin(np.nonzero(d < 12.0)[0], band).all()
    assert (d[np.setdiff1d(band, layer)] < 12.0).all()


def test_bad_spring_matrix_is_input_error(cache):
    """A non-positive-definite 2×2 bearing stiffness is rejected as input."""
    from shaftfe.static.solve import solve_static
    bad = ((1000.0, 2000.0), (2000.0, 1000.0))
    with pytest.raises(InputError, match="K_N_per_mm"):
        solve_static(cylinder(K_left=bad), 10000.0, _opts(level="default"),
                     cache_dir=cache, beam=False)


def test_error_estimate_from_two_levels(cache):
    """--estimate-error: a second level is solved and the Richardson-type numbers are
    consistent: extrapolated = fine + (fine − coarse)/(r^p − 1), error = |that difference|."""
    from shaftfe.static.error import with_error_estimate
    from shaftfe.static.solve import solve_static
    opts = _opts(level="default")
    r = with_error_estimate(solve_static(cylinder(), [10000.0], opts, cache_dir=cache,
                                         beam=False), cylinder(), opts, cache)
    ee = r.error_estimate
    assert ee["levels"] == ["fine", "default"]
    d = ee["cases"][0]["max_deflection"]
    k = ee["ratio_deflection"] ** ee["order_deflection"] - 1
    # exact arithmetic (the same formulas; measured equal): approx's default rel 1e-6
    assert d["extrapolated"] == pytest.approx(d["fine"] + (d["fine"] - d["coarse"]) / k)
    assert d["error_fine"] == pytest.approx(abs(d["fine"] - d["coarse"]) / k)
    assert d["coarse"] == pytest.approx(r.cases[0].max_deflection_mm, rel=1e-12)   # exact
    # mesh: the fine level's estimated deflection error (measured 0.22 %) is below 1 %
    assert d["rel_error_fine"] < 0.01


def test_body_force_resultant(cache):
    """The shaft's own centrifugal force ρ ω² (0, y, z): its net force is ρ ω² times the first
    moment of the meshed volume (∫ y dV, ∫ z dV — zero for the exact cylinder, O(h³) for the
    curved P2 mesh), computed here by an independent scikit-fem Functional; the run stays in
    equilibrium and the body force adds stress."""
    from skfem import Basis, ElementTetP2, Functional

    from shaftfe.static.solve import solve_static
    a = solve_static(cylinder(), [10000.0], _opts(level="default"), cache_dir=cache,
                     beam=False)
    b = solve_static(cylinder(), [10000.0], _opts(level="default", body_force=True),
                     cache_dir=cache, beam=False)
    m = b.mesh.mesh
    basis = Basis(m, ElementTetP2(), intorder=4)
    qy = Functional(lambda w: w.x[1]).assemble(basis)
    qz = Functional(lambda w: w.x[2]).assemble(basis)
    w2 = (10000.0 * 2 * math.pi / 60) ** 2
    F = cylinder().attachments[0].force_N(10000.0)
    expect = [0.0, F + STEEL.density_t_mm3 * w2 * qy, STEEL.density_t_mm3 * w2 * qz]
    # quadrature: the body-force load and this Functional integrate the same P2 geometry
    # (degree-5 integrand; intorder 4 vs 6 move ρω²∫y dV by 3e-12 relative): measured
    # 1e-15 F; 1e-9 covers the quadrature order with 300× margin
    np.testing.assert_allclose(b.cases[0].load_sum_N, expect, rtol=1e-9, atol=1e-9 * F)
    assert b.cases[0].equilibrium_residual <= 1e-8    # solver contract (RESIDUAL_TOL)
    # must differ: body-force stress scale ρ ω² R² ≈ 0.9 MPa (measured max change 1.7 MPa)
    assert np.abs(b.stress_ref - a.stress_ref).max() > 0.1


# --------------------------------------------------------------------------- CLI

def test_cli_writes_vtu_summary_plot(tmp_path, cache, monkeypatch, capsys):
    """`shaftfe static` writes result.vtu (documented fields), summary.json and the plot;
    bad input exits 2 with one line and writes nothing."""
    import meshio

    import shaftfe.model.loader
    from shaftfe.cli import main
    monkeypatch.setenv("SHAFTFE_CACHE_DIR", str(cache))
    monkeypatch.setattr(shaftfe.model.loader, "load_variant",
                        lambda name, overrides=(): cylinder())
    out = tmp_path / "o"
    rc = main(["static", "--model", "solid", "--variant", "cyl", "--rpm", "7000,10000",
               "--level", "default", "--out", str(out)])
    assert rc == 0
    assert "bearing" in capsys.readouterr().out
    m = meshio.read(out / "result.vtu")
    assert m.point_data["stress"].shape == (m.points.shape[0], 6)
    assert m.point_data["displacement"].shape == (m.points.shape[0], 3)
    assert "von_mises" in m.point_data and "region" in m.cell_data
    s = json.loads((out / "summary.json").read_text())
    assert [c["rpm"] for c in s["cases"]] == [7000.0, 10000.0]
    assert s["vtu"]["stress_components"] == ["xx", "yy", "zz", "xy", "yz", "xz"]
    assert s["cases"][1]["equilibrium_residual"] <= 1e-8    # solver contract (RESIDUAL_TOL)
    assert (out / "deflection.png").stat().st_size > 1000
    bad = tmp_path / "bad"
    assert main(["static", "--variant", "cyl", "--rpm", "-3", "--out", str(bad)]) == 2
    assert "error" in capsys.readouterr().err
    assert not bad.exists()
    assert main(["static", "--variant", "cyl", "--level", "huge", "--out", str(bad)]) == 2
    assert not bad.exists()


# ---------------------------------------------------------------- issue #30, b-static-variant

def test_zero_rpm_is_refused_before_any_mesh():
    """At 0 rpm the only load (m e ω²) is zero: a static run of nothing but 0 rpm is refused
    with one line (it raised a ValueError in the spin-softening step); a 0 rpm case beside a
    positive speed is exact zeros (tests/test_stability.py), stated by the commands as the beam
    states its own."""
    from shaftfe.beam.solve import AT_REST_NOTE, analyse
    from shaftfe.static.solve import solve_static
    for rpm in (0.0, [0.0, 0.0]):
        with pytest.raises(InputError, match=r"at least one > 0"):
            solve_static(cylinder(), rpm, _opts(level="coarse"))
    r = analyse(cylinder(), 0.0)[0]
    assert AT_REST_NOTE in r.notes and r.max_deflection_mm == 0.0 and r.max_peak_MPa == 0.0


def test_sharp_corner_rule_one_place():
    """solid.plan.sharp_corners: a fillet 0 at a shoulder with forces on both sides is a
    singular corner (warned, marked, refused by fatigue); a step beyond every force carries no
    moment and is not one."""
    import warnings

    from shaftfe.model.loader import load_variant
    from shaftfe.solid.plan import (
        refuse_sharp_corners,
        sharp_corners,
        sharp_mark,
        warn_sharp_corners,
    )
    from shaftfe.util.notices import ShaftfeWarning
    v = load_variant("x2_57", {"segments.collar.fillet_mm": 0.0})
    (c,) = sharp_corners(v)
    assert (c.region, c.x, c.r_small, c.zone_mm) == ("shoulder:collar", 64.5, 8.5, 2.5)
    assert sharp_mark((c,), (64.5, 0.0, 8.5)) and not sharp_mark((c,), (46.6, 8.5, 0.0))
    assert sharp_corners(load_variant("x2_57", {"segments.thread_m10.fillet_mm": 0.0})) == ()
    assert sharp_corners(load_variant("x2_57")) == ()
    with pytest.warns(ShaftfeWarning, match="stress singularity"):
        warn_sharp_corners(v)
    with pytest.raises(InputError, match=r"--set segments\.collar\.fillet_mm=0\.0.*sharp corner"):
        refuse_sharp_corners(v, "a fatigue check")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        refuse_sharp_corners(load_variant("x2_57"), "a fatigue check")


def test_deflection_beyond_the_model_or_the_clearance_is_warned():
    """A deflection above 2 % of the length (small-deflection model) or above the file's
    clearance at its station is warned (beam and 3D share check_deflection): x2_57 at the rpm
    ceiling, 20 000 rpm, with the seed's placement (parts at their seat centres) moves 1.49 mm
    at the clearance station (4 × its 0.371 mm at 10 000, loads ∝ rpm²) against the 1.4 mm
    stated (with the parts at their centroids, the default since issue #31: 0.95 mm, not
    warned); at 10 000 rpm nothing is warned. The audit's 254.6 mm (a stiffness 1000 × too soft,
    now refused) is 2.2 × the shaft's length."""
    import warnings

    from shaftfe.beam.solve import analyse, check_deflection
    from shaftfe.model.loader import load_variant
    from shaftfe.util.notices import ShaftfeWarning
    with pytest.warns(ShaftfeWarning, match="small-deflection"):
        check_deflection("test", 114.0, 254.6, None, None)
    with pytest.warns(ShaftfeWarning, match="clearance to the crankshaft"):
        analyse(load_variant("x2_57"), 20000.0, seed_placement=True)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        analyse(load_variant("x2_57"), 10000.0)
        check_deflection("test", 114.0, 0.02 * 114.0, 1.4, 1.4)     # at the bounds: allowed


def test_a_shoulder_face_above_its_fillet_means_the_fillet_is_not_resolved():
    """static.result.unresolved_fillets: a resolved fillet carries its step's peak, so a
    shoulder face reading more than 2 × its own fillet (the review's 0.05 mm collar fillet at
    the coarse level: face 350 281 MPa, fillet 1 312 MPa) flags the fillet; a face below it, or
    a little above a lightly loaded end fillet beside a loaded seat (x2_57's cw2_seat at the
    coarse level: 27.55 and 25.42 MPa), does not. Exact comparisons of given numbers."""
    from shaftfe.static.result import unresolved_fillets
    assert list(unresolved_fillets({"fillet:collar": 1312.0,
                                    "shoulder:collar": 350281.0})) == ["fillet:collar"]
    assert unresolved_fillets({"fillet:collar": 503.0, "shoulder:collar": 227.0}) == {}
    assert unresolved_fillets({"fillet:cw2_seat": 25.42, "shoulder:cw2_seat": 27.55}) == {}
    assert unresolved_fillets({"shoulder:collar": 227.0}) == {}    # a sharp step: its own rule
