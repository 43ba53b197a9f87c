"""Gmsh solid + mesh → scikit-fem: groups, node order, quality, cache, CLI (issue 3)."""

from __future__ import annotations

import json
import math
import sys

import numpy as np
import pytest

from shaftfe.errors import InputError
from shaftfe.model.examples import four_step_shaft
from shaftfe.model.variant import Variant


def make_variant(**kwargs) -> Variant:
    """The four-step test shaft (``shaftfe.model.examples``) with a thread end and a washer sharing
    the hub's seat: Ø15 (chamfered end, sharp step up) Ø17 (fillet, keyway) Ø22 (fillet, U
    groove, chamfered step down) Ø17 (a cross hole)."""
    kwargs = {"name": "syn", "description": "synthetic test shaft", "washer": True,
              "thread_end": True, "groove": True, "cross_hole": True, "chamfers": True,
              **kwargs}
    return four_step_shaft(**kwargs)


@pytest.fixture(scope="module")
def coarse(cache):
    from shaftfe.solid.mesh import build_mesh
    return build_mesh(make_variant(), "coarse", cache_dir=cache)


def _integrate_one(mesh, facets=None) -> float:
    from skfem import Basis, ElementTetP1, ElementTetP2, FacetBasis, Functional
    elem = ElementTetP2() if mesh.t.shape[0] == 4 and mesh.doflocs.shape[1] > mesh.p.shape[1] \
        else ElementTetP1()
    one = Functional(lambda w: 1.0 + 0.0 * w.x[0])
    if facets is None:
        return float(one.assemble(Basis(mesh, elem)))
    return float(one.assemble(FacetBasis(mesh, elem, facets=facets)))


def test_groups_exist_and_match_the_solid(coarse):
    """Every named face group of the solid exists, is non-empty, and 'shaft' holds all tets."""
    from shaftfe.solid.exact import expected_areas
    m = coarse.mesh
    assert set(m.boundaries) == set(expected_areas(make_variant()))
    assert set(coarse.groups) == set(m.boundaries) | {"shaft"}
    for g, f in m.boundaries.items():
        assert len(f) > 0, g
        assert np.all(m.f2t[1, f] == -1), f"{g}: interior facets"
    assert np.array_equal(np.sort(m.subdomains["shaft"]), np.arange(m.t.shape[1]))


def test_every_face_group_names_one_feature(coarse):
    """Each face group of the meshed shaft (every kind of feature: fillets, shoulders, a
    keyway, the hex socket, split part seats, a bearing seat, the ends) reads back through the
    one naming table (``solid.features``) to the kind of the feature it belongs to, and every
    feature of the plan has faces in the mesh (issue #32)."""
    from shaftfe.solid import features as F
    from shaftfe.solid.plan import prepare
    by = F.by_region(F.features(prepare(make_variant())))
    seen = {F.region_of(g) for g in coarse.mesh.boundaries}
    assert seen == set(by)
    for g in coarse.mesh.boundaries:
        assert F.kind_of(g) == by[F.region_of(g)].kind, g
    # every kind but a cone's (this shaft's Ø15 steps up; tests/validation/test_tapers.py)
    assert {f.kind for f in by.values()} == set(F.KINDS) - {"taper"}


def test_group_areas_coarse(coarse):
    """Area of each face group (P2 facet quadrature) vs the exact area from
    ``expected_areas``: cylinder 2πRL minus the keyway opening ∫∫ dx ds/√(1−s²/R²), fillet
    ring π²ρ(r+ρ) − 2πρ² (Pappus), annulus π(R²−r²), keyway walls, hex πR² − (√3/2)s² ...;
    within 0.5 %."""
    from shaftfe.solid.exact import expected_areas
    exp = expected_areas(make_variant())
    for g, f in coarse.mesh.boundaries.items():
        a = _integrate_one(coarse.mesh, f)
        # mesh: P2 facets interpolate the curved faces at coarse h ≈ D/2; measured ≤ 1.7e-3
        # (end:right), 5e-3 leaves 3×
        assert a == pytest.approx(exp[g], rel=5e-3), g


def test_seat_halves_are_exact_halves(coarse):
    """A seat without a keyway splits into two halves of exactly πRL each (R = 8.5,
    L = 10 → 267.04 mm²); the pressed/free difference is below 0.1 % of a half."""
    m = coarse.mesh
    half = math.pi * 8.5 * 10.0
    p = _integrate_one(m, m.boundaries["load:hub:pressed"])
    f = _integrate_one(m, m.boundaries["load:hub:free"])
    # mesh (P2 surface error, as test_group_areas_coarse): measured 1.0e-4 and 3.8e-5
    assert p == pytest.approx(half, rel=5e-3)
    assert f == pytest.approx(half, rel=5e-3)
    assert abs(p - f) < 1e-3 * half       # the two halves' mesh errors: measured 6.5e-5


def test_attachments_on_one_seat_share_faces(coarse):
    """'hub' and 'washer' have the same seat interval and angle → the same facets."""
    b = coarse.mesh.boundaries
    for side in ("pressed", "free"):
        assert np.array_equal(b[f"load:hub:{side}"], b[f"load:washer:{side}"])


@pytest.mark.parametrize("name,angle", [("cw", 30.0), ("hub", 0.0)])
def test_pressed_half_lies_on_minus_e_side(coarse, name, angle):
    """Every pressed facet's corners satisfy (y, z)·e ≤ 0 for the force direction
    e = (cos α, sin α); every free facet's corners satisfy (y, z)·e ≥ 0 (1e-9 mm)."""
    m = coarse.mesh
    e = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
    for side, sign in (("pressed", -1.0), ("free", 1.0)):
        pts = m.p[1:, m.facets[:, m.boundaries[f"load:{name}:{side}"]].ravel()]
        # exact split: nodes on the dividing plane are off it by the 1e-9 mm rounding of the
        # coordinates only (≤ 0.7e-9 mm; measured 8.4e-11)
        assert np.all(sign * (e @ pts) >= -1e-9), side


def test_tet10_midside_nodes(coarse):
    """Mid-side node order (FINDINGS pitfall 1). Reference: an edge node sits at its chord's
    midpoint unless Gmsh moved it: the HighOrder optimiser moves some interior ones (up to
    17 % of the edge length ℓ measured at coarse) and boundary ones follow the curved surface
    (≤ 20 % of ℓ measured). Checks: (1) in every tet, each edge node that sits exactly at an edge
    midpoint of that tet (1e-8 mm) sits at its OWN edge's midpoint (a swapped pair would
    sit at another edge's midpoint); (2) every node is within 0.25 ℓ of its midpoint; (3) at
    least half of the interior edges are straight (midpoint to 1e-8 mm; coordinates are
    rounded to 1e-9 mm)."""
    m = coarse.mesh
    p, x = m.p, m.doflocs
    pairs = [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)]
    mids = np.stack([0.5 * (p[:, m.t[i]] + p[:, m.t[j]]) for i, j in pairs])  # 6 × 3 × nel
    nodes = x[:, m.dofs.element_dofs[4:]].transpose(1, 0, 2)                  # 6 × 3 × nel
    dist = np.linalg.norm(nodes[:, None] - mids[None, :], axis=2)            # 6 × 6 × nel
    # exact, not "nearest": a node the optimiser moved may come nearer another edge's midpoint
    # on a flat tet (seen run to run), but no straight-edge node may sit at another midpoint
    # "exactly at a midpoint": coordinates rounded to 1e-9 mm put a straight-edge node ≤ √3
    # × 1e-9 mm off; 1e-8 mm ≪ any optimiser move (a fraction of ℓ ~ mm)
    at_a_mid = dist.min(axis=1) < 1e-8                                       # 6 × nel
    assert np.all(at_a_mid.mean(axis=1) > 0.25)     # every local edge slot is well tested
    assert np.all(np.argmin(dist, axis=1)[at_a_mid] == np.broadcast_to(
        np.arange(6)[:, None], at_a_mid.shape)[at_a_mid])
    edofs = m.dofs.edge_dofs[0]
    a, b = m.edges
    dev = np.linalg.norm(x[:, edofs] - 0.5 * (p[:, a] + p[:, b]), axis=0)
    ell = np.linalg.norm(p[:, a] - p[:, b], axis=0)
    on_bnd = np.zeros(m.edges.shape[1], dtype=bool)
    on_bnd[m.boundary_edges()] = True
    assert np.all(dev <= 0.25 * ell)      # measured ≤ 17 % (interior) / 20 % (boundary) of ℓ
    assert np.mean(dev[~on_bnd] < 1e-8) >= 0.5    # 1e-8 mm: as at_a_mid above
    # and the element → edge-dof table follows scikit-fem's edge order (0,1),(1,2),(0,2),...
    t2e = m.t2e
    for k, (i, j) in enumerate([(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)]):
        e = t2e[k]
        assert np.array_equal(np.sort(m.edges[:, e], axis=0), np.sort(m.t[[i, j]], axis=0))


def test_quality_and_positive_jacobians(coarse):
    """Min Gmsh minSICN of the curved tets > ``Q_CURVED`` (the repair threshold of
    ``mesh._untangle``; it was 0.2 with Gmsh's non-deterministic HighOrder optimiser, and
    pulling curved nodes towards their chords until 0.2 made coarse meshes of round shafts
    measurably less accurate: a Ø20 cylinder's deflection moved 2.3 % between default and
    fine), and det J of the curved P2 map is positive at every 4th-order quadrature point of
    every tet (no inverted elements)."""
    from skfem.quadrature import get_quadrature
    from skfem.refdom import RefTet

    from shaftfe.solid.mesh import Q_CURVED
    assert coarse.min_quality > Q_CURVED
    X, _ = get_quadrature(RefTet, 4)
    det = coarse.mesh._mapping().detDF(X)
    assert det.shape[0] == coarse.n_elements
    assert np.all(det > 0)


def test_chamfered_ring_contact_band_must_clear_the_fillet():
    """A ring's contact band (ring minus its chamfer at each end) must lie on straight seat:
    a ring abutting the 1 mm fillet at x = 70 with a 0.5 mm chamfer would bear on the fillet
    (InputError naming the bearing); with a 1.5 mm chamfer the coupling face is the band
    [x_face + 1.5, x_end − 1.5] and its exact area is 2π R (w − 2 c)."""
    import dataclasses
    import math

    from shaftfe.solid.exact import expected_areas
    from shaftfe.solid.plan import prepare
    v = make_variant(bearing=(74.0, 8.0), cross_hole=False)   # ring [70, 78] on Ø17 at the step
    v = dataclasses.replace(v, bearings=(dataclasses.replace(v.bearings[0], chamfer_mm=0.5),))
    with pytest.raises(InputError) as exc:
        prepare(v)
    assert "bearings[0].seat" in str(exc.value) and "fillet" in str(exc.value)
    v = dataclasses.replace(v, bearings=(dataclasses.replace(v.bearings[0], chamfer_mm=1.5),))
    st = next(s for s in prepare(v).seats if s.name == "bearing:mid")
    # exact arithmetic (round-off only): approx's default rel 1e-6
    assert (st.x0, st.x1) == pytest.approx((71.5, 76.5))
    assert expected_areas(v)["bearing:mid"] == pytest.approx(2 * math.pi * 8.5 * 5.0)


@pytest.mark.parametrize("kwargs,field", [
    ({"fillet_b": 3.0}, "segments[1].fillet_mm"),           # step 17→22 is 2.5 mm high
    ({"keyway_x": 47.0}, "keyways[0].x_center_mm"),         # slot runs into the fillet
    ({"bearing": (69.0, 8.0)}, "bearings[0].seat"),         # straddles the Ø22/Ø17 step
    ({"cw_seat": (30.0, 40.0)}, "attachments[0].seat_x"),   # cuts through the keyway
])
def test_bad_variant_fails_before_gmsh(monkeypatch, kwargs, field):
    """A bad variant raises InputError naming the field, with gmsh made unimportable."""
    from shaftfe.solid.mesh import build_mesh
    monkeypatch.setitem(sys.modules, "gmsh", None)
    with pytest.raises(InputError) as exc:
        build_mesh(make_variant(**kwargs), "coarse", use_cache=False)
    assert field in str(exc.value)
    assert "\n" not in str(exc.value)


def test_bad_level_and_order():
    """Unknown level / order → InputError listing the allowed values."""
    from shaftfe.solid.mesh import build_mesh
    with pytest.raises(InputError, match="coarse"):
        build_mesh(make_variant(), "medium")
    with pytest.raises(InputError, match=r"1 \| 2"):
        build_mesh(make_variant(), "coarse", order=3)


def test_cache_hit_returns_identical_mesh(coarse, cache):
    """A second call loads the npz (from_cache) and returns the same arrays and groups."""
    from shaftfe.solid.mesh import build_mesh
    again = build_mesh(make_variant(), "coarse", cache_dir=cache)
    assert not coarse.from_cache and again.from_cache
    assert again.key == coarse.key
    assert np.array_equal(again.mesh.doflocs, coarse.mesh.doflocs)
    assert np.array_equal(again.mesh.t, coarse.mesh.t)
    assert again.groups == coarse.groups
    for g in coarse.mesh.boundaries:
        assert np.array_equal(again.mesh.boundaries[g], coarse.mesh.boundaries[g])
    assert again.min_quality == coarse.min_quality


def test_cached_topology_is_scikit_fems_own(coarse, cache, tmp_path):
    """The facets, edges and their maps kept in a cache entry (``solid.mesh.TOPOLOGY``) equal
    what scikit-fem derives from t on a mesh built without them (exact: the same integer
    arrays); an entry written without them gets them on its first load."""
    import shutil

    from skfem import MeshTet2

    from shaftfe.solid.mesh import TOPOLOGY, build_mesh, cache_path
    again = build_mesh(make_variant(), "coarse", cache_dir=cache)
    assert again.from_cache
    m = again.mesh
    bare = MeshTet2(m.doflocs, m.t)                   # scikit-fem derives everything itself
    for name in TOPOLOGY:
        assert hasattr(m, f"_{name}"), name           # loaded, not derived
        assert np.array_equal(getattr(m, name), getattr(bare, name)), name
    assert np.array_equal(m.boundary_facets(), bare.boundary_facets())
    # an entry without topology (as written before it was kept): loaded, then completed
    from shaftfe.solid import mesh as sm
    path = cache_path(again.key, tmp_path)
    shutil.copy(cache_path(again.key, cache), path)
    data = sm._load(path, again.key)
    data["topology"] = {}
    sm._save(path, data)
    assert sm._load(path, again.key)["topology"] == {}
    old = build_mesh(make_variant(), "coarse", cache_dir=tmp_path)
    assert old.from_cache and set(sm._load(path, again.key)["topology"]) == set(TOPOLOGY)
    assert np.array_equal(old.mesh.facets, bare.facets)


def test_key_depends_on_geometry_not_on_name():
    """The cache key changes with the seat angle and the level, not with the variant name."""
    from shaftfe.solid.mesh import mesh_key
    from shaftfe.solid.plan import prepare
    k = mesh_key(prepare(make_variant()), "coarse", 2, "4.15")
    assert k == mesh_key(prepare(make_variant(name="other")), "coarse", 2, "4.15")
    assert k != mesh_key(prepare(make_variant(cw_angle=31.0)), "coarse", 2, "4.15")
    assert k != mesh_key(prepare(make_variant()), "default", 2, "4.15")
    assert k != mesh_key(prepare(make_variant()), "coarse", 1, "4.15")
    assert k != mesh_key(prepare(make_variant()), "coarse", 2, "4.14")


def gmsh_version():
    from shaftfe.solid import mesh
    return mesh.gmsh_version()


def test_cache_dir_from_environment(monkeypatch, tmp_path):
    """Without cache_dir the cache goes to $SHAFTFE_CACHE_DIR."""
    from shaftfe.solid.mesh import cache_path
    monkeypatch.setenv("SHAFTFE_CACHE_DIR", str(tmp_path))
    assert cache_path("ab" * 32).parent == tmp_path


def test_meshing_is_deterministic():
    """Two cold builds of the same input IN ONE PROCESS give the same mesh bit for bit (1
    thread); across processes see the next test."""
    from shaftfe.solid.mesh import build_mesh
    v = make_variant(hex_socket=False, groove=False, cross_hole=False)
    a = build_mesh(v, "coarse", use_cache=False)
    b = build_mesh(v, "coarse", use_cache=False)
    assert a.mesh.doflocs.tobytes() == b.mesh.doflocs.tobytes()
    assert a.mesh.t.tobytes() == b.mesh.t.tobytes()
    for g in a.mesh.boundaries:
        assert np.array_equal(a.mesh.boundaries[g], b.mesh.boundaries[g])


_CHILD_BUILD = (
    "from shaftfe.model.examples import four_step_shaft\n"
    "from shaftfe.solid.mesh import build_mesh\n"
    "v = four_step_shaft(name='syn', description='synthetic test shaft', washer=True, "
    "thread_end=True, hex_socket=False)\n"
    "build_mesh(v, 'coarse')\n")


def test_cold_builds_are_identical_across_processes(tmp_path):
    """Two cold builds of the same P2 mesh in two separate processes, each with its own empty
    cache ($SHAFTFE_CACHE_DIR), write the same node coordinates, connectivity and face groups
    bit for bit. Reference: the exact equality of the arrays (no tolerance). Before
    ``shaftfe.solid.mesh._untangle`` replaced Gmsh's HighOrder optimiser this failed: ~40 % of the
    curved mid-side nodes moved from one process to the next (3477 of 9020 nodes, up to
    0.027 mm, issue 3 note), because the optimiser's result depends on pointer order (it was
    reproducible with address-space randomisation off, ``setarch -R``)."""
    import os
    import subprocess
    procs = []
    for i in (0, 1):
        env = {**os.environ, "SHAFTFE_CACHE_DIR": str(tmp_path / f"c{i}")}
        procs.append(subprocess.Popen([sys.executable, "-c", _CHILD_BUILD], env=env,
                                      stderr=subprocess.PIPE, text=True))
    for p in procs:
        _, err = p.communicate(timeout=600)
        assert p.returncode == 0, err
    files = [sorted((tmp_path / f"c{i}").glob("mesh-*.npz")) for i in (0, 1)]
    assert len(files[0]) == len(files[1]) == 1
    assert files[0][0].name == files[1][0].name               # same cache key
    with np.load(files[0][0]) as a, np.load(files[1][0]) as b:
        assert set(a.files) == set(b.files)
        for k in a.files:
            if k != "meta":
                assert a[k].tobytes() == b[k].tobytes(), k
        ma = json.loads(a["meta"].tobytes().decode())
        mb = json.loads(b["meta"].tobytes().decode())
        assert ma["min_sicn"] == mb["min_sicn"]
        assert ma["boundaries"] == mb["boundaries"]


def test_order_one_volume(tmp_path):
    """P1 tets (MeshTet1): the quadrature volume equals Σ|det[p1−p0, p2−p0, p3−p0]|/6 of the
    tets (1e-12), and lies below the exact volume by the chord deficit, which is at most that
    of a regular 7-gon, 1 − 7 sin(2π/7)/(2π) = 12.9 % (coarse: h = D/2 → ≥ 7 chords around)."""
    from skfem import MeshTet1

    from benchmarks.bench_truth import four_point_bar
    from shaftfe.solid.exact import analytic_volume
    from shaftfe.solid.mesh import build_mesh
    v = four_point_bar(22.0, 17.0, 1.0)     # the P1 path needs no features: a stepped bar
    sm = build_mesh(v, "coarse", order=1, cache_dir=tmp_path)
    m = sm.mesh
    assert isinstance(m, MeshTet1) and sm.order == 1
    vol = _integrate_one(m)
    p = m.p[:, m.t]
    det = np.linalg.det(np.stack([p[:, 1] - p[:, 0], p[:, 2] - p[:, 0], p[:, 3] - p[:, 0]],
                                 axis=-1).transpose(1, 0, 2))
    # exact arithmetic (round-off only): P1 quadrature of 1 is the tet volume
    assert vol == pytest.approx(np.abs(det).sum() / 6.0, rel=1e-12)
    deficit = 1.0 - vol / analytic_volume(v)
    # geometric bound (docstring): the chord deficit of a regular 7-gon, 12.9 %
    assert 0.0 < deficit < 1.0 - 7.0 * math.sin(2 * math.pi / 7) / (2 * math.pi)


def test_cli_mesh_json_and_vtu(monkeypatch, tmp_path, capsys, coarse, cache):
    """`shaftfe mesh --json --out x.vtu` prints the summary and writes a VTU whose tetra10
    count equals the element count and whose triangles carry the group ids (the module's
    coarse mesh, read from its cache: the command's mesh key is the fixture's)."""
    import meshio

    import shaftfe.model.loader
    from shaftfe.cli import main
    monkeypatch.setattr(shaftfe.model.loader, "load_variant",
                        lambda name, overrides=(): make_variant(name=name),
                        raising=False)
    out = tmp_path / "syn.vtu"
    rc = main(["mesh", "--variant", "syn", "--level", "coarse", "--cache-dir",
               str(cache), "--out", str(out), "--json"])
    assert rc == 0
    s = json.loads(capsys.readouterr().out)
    from shaftfe.solid.mesh import Q_CURVED
    assert s["from_cache"] is True and coarse.key.startswith(s["key"])
    assert s["nodes"] > 0 and s["min_quality_minSICN"] > Q_CURVED
    m = meshio.read(out)
    assert m.cells_dict["tetra10"].shape[0] == s["elements"]
    ids = np.concatenate(m.cell_data["group"])
    assert set(np.unique(ids)) == set(range(len(s["groups"])))   # 0 = volume, 1.. = faces
    rc = main(["mesh", "--variant", "syn", "--level", "coarse", "--cache-dir",
               str(cache), "--out", str(tmp_path / "syn.msh")])
    assert rc == 0
    assert "from cache" in capsys.readouterr().out
    assert meshio.read(tmp_path / "syn.msh").cells_dict["tetra10"].shape[0] == s["elements"]


def test_cli_bad_out_suffix_exit_2(monkeypatch, capsys):
    """A wrong --out suffix is one error line and exit code 2 (before any meshing)."""
    import shaftfe.model.loader
    from shaftfe.cli import main
    monkeypatch.setattr(shaftfe.model.loader, "load_variant",
                        lambda name, overrides=(): make_variant(name=name),
                        raising=False)
    assert main(["mesh", "--variant", "syn", "--out", "x.stl"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and ".vtu" in err


def test_exact_formulas_against_quadrature():
    """The closed forms in shaftfe.solid.plan vs independent 2D quadrature: the fillet ring volume
    ∫∫ 2πr dA over the spandrel, its area ∫ 2πr ds over the arc, and the keyway volume
    ∫∫ (√(R²−s²) − (R−t)) over the stadium (scipy dblquad)."""
    from scipy.integrate import dblquad, quad

    from shaftfe.solid.exact import fillet_area, fillet_volume, slot_volume
    from shaftfe.solid.plan import Fillet, Slot
    f = Fillet("b", 50.0, 8.5, 11.0, 1.5, -1)
    rho, r0 = f.rho, f.r_small
    # spandrel: u ∈ [0, ρ] from the shoulder, v ∈ [0, ρ − √(ρ² − (ρ−u)²)] above the cylinder
    vol, _ = dblquad(lambda v, u: 2 * math.pi * (r0 + v), 0, rho, 0,
                     lambda u: rho - math.sqrt(rho**2 - (rho - u) ** 2))
    # dblquad's default tolerance 1.5e-8 (its error estimate here 4.7e-10; measured 2e-16)
    assert fillet_volume(f) == pytest.approx(vol, rel=1e-9)
    area, _ = quad(lambda p: 2 * math.pi * (r0 + rho - rho * math.cos(p)) * rho, 0, math.pi / 2)
    # smooth 1D integrand: quad converges to round-off (estimate 1.1e-14, measured 2e-16)
    assert fillet_area(f) == pytest.approx(area, rel=1e-12)
    k = Slot("b", 0, 8.5, 5.0, 3.0, 14.0, 35.0, 0.0)
    a = 2.5
    kv, _ = dblquad(lambda s, x: math.sqrt(8.5**2 - s * s) - 5.5, -7.0, 7.0,
                    lambda x: -math.sqrt(max(a * a - max(abs(x) - 4.5, 0) ** 2, 0)),
                    lambda x: math.sqrt(max(a * a - max(abs(x) - 4.5, 0) ** 2, 0)),
                    epsabs=1e-11)      # 1e-11 mm³ absolute: ≪ the 1e-8 relative check below
    # √ singularities at the stadium ends limit dblquad: estimate 2.4e-11, measured 2.9e-11
    # relative; 1e-8 leaves 300× for other QUADPACK builds
    assert slot_volume(k) == pytest.approx(kv, rel=1e-8)


def test_a_mesh_file_suffix_in_capitals_is_written_as_its_format(tmp_path):
    """``mesh --out m.MSH``: the suffix rule takes any case (util.atomic.check_suffix), and so
    does the writer (it wrote .MSH through the VTU writer, which refused it with a traceback)."""
    from types import SimpleNamespace

    import meshio
    import skfem

    from shaftfe.io.vtu import write_mesh
    m = skfem.MeshTet()
    p = write_mesh(SimpleNamespace(mesh=m, order=1, groups=()), tmp_path / "m.MSH")
    assert meshio.read(p, file_format="gmsh").cells_dict["tetra"].shape[0] == m.t.shape[1]
