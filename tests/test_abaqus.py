"""CalculiX / Abaqus deck export (``shaftfe.io.abaqus``) and result readers (``shaftfe.io.frd``).

No ccx needed (CI has none): the deck is parsed back and checked against the model it came
from; the readers are checked on hand-written fixtures (tests/fixtures/ccx). The side-by-side
run against ccx itself is ``benchmarks/bench_calculix.py``.

References
----------
* C3D10 node numbering: CalculiX CrunchiX User's Manual 2.20 §6.2.4 "Ten-node tetrahedral
  element (C3D10)" and Abaqus Analysis User's Manual §28.1.4 "Three-dimensional solid element
  library": corners 1-4 (face 1-2-3 counter-clockwise seen from node 4), mid-side nodes 5-10 on
  the edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4.
* Numeric fields: ccx reads at most 20 characters per number (``f20.0`` reads in its input
  routines, e.g. equations.f), lines at most 132 characters (FINDINGS pitfall 9).
* ``*EQUATION``: first term = dependent dof, which may not be dependent in a second equation
  (CalculiX manual §7 "*EQUATION"; equations.f stops with "detected on the dependent side of
  two different MPC's").
* SPRINGA: a spring along the line through its two nodes, energy ½ k (n·Δu)² (CalculiX manual
  §6.2 "SPRINGA"); eigenvalues of a symmetric 2×2 matrix in closed form.
* .frd layout: CalculiX GraphiX manual "Result Format" (blocks ended by " -3", " -1" value
  lines with an I10 node number and E12.5 values, " -2" continuation lines).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from shaftfe.model.examples import K_SEED, STEEL
from shaftfe.model.variant import Attachment, Bearing, Segment, Variant

FIX = Path(__file__).parent / "fixtures" / "ccx"


def cylinder(tilt: float = 0.0) -> Variant:
    """Ø20 × 120 mm cylinder on two seed bushings, one 0.24 kg part at e = 20 mm, 30°
    (``tilt``: a tilt spring on the right bearing, N·mm/rad)."""
    segs = (Segment("s", 0.0, 120.0, 20.0, 0.0),)
    brg = (Bearing("L", "x", 10.0, 10.0, 14_400.0, 10_000.0, K_SEED, axial=True),
           Bearing("R", "x", 110.0, 10.0, 14_400.0, 10_000.0, K_SEED,
                   tilt_stiffness_Nmm_per_rad=tilt))
    att = (Attachment("w", 55.0, 65.0, 0.24, 20.0, 60.0, angle_deg=30.0),)
    return Variant("cyl", "test cylinder", segs, brg, att, STEEL, 0.0)


@pytest.fixture(scope="module")
def model(cache):
    from shaftfe.static.model import StaticOptions, build_model
    return build_model(cylinder(), StaticOptions(level="coarse"), cache_dir=cache)


@pytest.fixture(scope="module")
def deck(model, tmp_path_factory):
    from shaftfe.io import abaqus
    path = tmp_path_factory.mktemp("deck") / "cyl.inp"
    info = abaqus.write_deck(path, model, steps=("static", "frequency"),
                             print_elements=[0, 1])
    return info, path.read_text()


def keyword_blocks(text: str) -> dict[str, list[list[str]]]:
    """Deck → {keyword line: [data lines of each occurrence]} (keyword upper-cased)."""
    out: dict[str, list[list[str]]] = {}
    cur = None
    for ln in text.split("\n"):
        if ln.startswith("*"):
            cur = []
            out.setdefault(ln.split(",")[0].strip().upper() + ln[len(ln.split(",")[0]):], [])\
                .append(cur)
        elif cur is not None:
            cur.append(ln)
    return out


def block(blocks, prefix: str) -> list[str]:
    return [ln for k, v in blocks.items() if k.upper().startswith(prefix) for b in v
            for ln in b]


# --------------------------------------------------------------------------- deck form

def test_deck_is_well_formed(deck, model):
    info, text = deck
    lines = text.split("\n")
    assert lines[0] == "*HEADING"
    assert all(len(ln) <= 132 for ln in lines)
    kws = [ln.split(",")[0].upper() for ln in lines if ln.startswith("*")]
    for k in ("*NODE", "*ELEMENT", "*MATERIAL", "*ELASTIC", "*DENSITY", "*SOLID SECTION",
              "*EQUATION", "*BOUNDARY", "*STEP", "*STATIC", "*CLOAD", "*FREQUENCY",
              "*END STEP", "*NODE FILE", "*EL FILE", "*NODE PRINT", "*EL PRINT"):
        assert k in kws, k
    assert kws.count("*STEP") == kws.count("*END STEP") == 2
    # model data (equations) before the first step, as ccx requires
    assert kws.index("*EQUATION") < kws.index("*STEP")
    b = keyword_blocks(text)
    nodes = block(b, "*NODE, NSET")
    ids = [int(ln.split(",")[0]) for ln in nodes]
    assert ids == list(range(1, info.n_nodes + 1))
    els = block(b, "*ELEMENT, TYPE=C3D10")
    assert len(els) == info.n_elements == model.shaft_mesh.n_elements
    assert all(len(ln.split(",")) == 11 for ln in els)
    used = {int(x) for ln in els for x in ln.split(",")[1:]}
    assert used == set(range(1, info.n_mesh_nodes + 1))
    el = block(b, "*ELASTIC")[0].split(",")
    assert float(el[0]) == STEEL.E_MPa and float(el[1]) == STEEL.nu
    assert float(block(b, "*DENSITY")[0]) == STEEL.density_t_mm3
    assert block(b, "*FREQUENCY")[0].strip() == "12"


def test_node_fields_fit_ccx_and_round_trip(deck, model):
    info, text = deck
    nodes = block(keyword_blocks(text), "*NODE, NSET")
    fields = [f for ln in nodes for f in ln.split(",")[1:]]
    assert max(len(f) for f in fields) <= 20                 # ccx: ≤ 20 characters
    xyz = np.array([[float(f) for f in ln.split(",")[1:]] for ln in nodes[:info.n_mesh_nodes]])
    x = model.shaft_mesh.mesh.doflocs.T
    # 13 significant digits written (FLOAT_FMT .12e): ≤ 5e-13 relative per coordinate
    assert np.abs(xyz - x).max() <= 1e-12 * np.abs(x).max()
    nums = re.findall(r"[-+]?\d\.\d+e[-+]\d+", text)
    assert max(len(s) for s in nums) <= 20


# --------------------------------------------------------------------------- C3D10 order

def _check_c3d10(x: np.ndarray, conn: np.ndarray, straight: bool) -> None:
    """Corners positively oriented; mid node k at the midpoint of Abaqus edge k (exactly for
    straight edges, nearest among the element's six edge midpoints for curved ones)."""
    edges = ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))       # nodes 5..10 (manual)
    c = x[:, conn[:, :4]]
    vol = np.einsum("ie,ie->e", c[:, :, 1] - c[:, :, 0],
                    np.cross(c[:, :, 2] - c[:, :, 0], c[:, :, 3] - c[:, :, 0], axis=0))
    assert (vol > 0).all()
    mids = np.array([0.5 * (x[:, conn[:, a]] + x[:, conn[:, b]]) for a, b in edges])
    for k in range(6):
        node = x[:, conn[:, 4 + k]]
        d = np.linalg.norm(mids - node[None], axis=1)                # (6, ne)
        if straight:
            # exact arithmetic (round-off only): midpoints of coordinates of order 1
            assert d[k].max() <= 1e-12
        assert (np.argmin(d, axis=0) == k).all()


def test_c3d10_order_on_straight_mesh_with_inverted_tets():
    from skfem import MeshTet1, MeshTet2

    from shaftfe.io import abaqus
    m1 = MeshTet1().refined(1)
    t = m1.t.copy()
    t[[1, 2], ::2] = t[[2, 1], ::2]                 # every other tet negatively oriented
    m2 = MeshTet2.from_mesh(MeshTet1(m1.p, t))
    conn = abaqus.abaqus_connectivity(m2)
    _check_c3d10(m2.doflocs, conn, straight=True)
    # the same node sets as scikit-fem's elements (a permutation, nothing lost)
    assert (np.sort(conn, axis=1) == np.sort(m2.dofs.element_dofs.T, axis=1)).all()


def test_c3d10_order_in_the_written_deck(deck, model):
    _info, text = deck
    els = block(keyword_blocks(text), "*ELEMENT, TYPE=C3D10")
    conn = np.array([[int(v) for v in ln.split(",")[1:]] for ln in els]) - 1
    _check_c3d10(model.shaft_mesh.mesh.doflocs, conn, straight=False)


# --------------------------------------------------------------------------- loads

def test_cload_sum_is_the_resultant_m_e_omega2(deck, model):
    from shaftfe.static.model import REF_RPM
    _info, text = deck
    loads = block(keyword_blocks(text), "*CLOAD")
    F = np.zeros(3)
    for ln in loads:
        node, dof, val = ln.split(",")
        F[int(dof) - 1] += float(val)
    # independent closed form: m e ω² along 30° in the y-z plane
    w = REF_RPM * 2 * math.pi / 60
    Fref = 0.24 * 20e-3 * w ** 2 * np.array([0.0, math.cos(math.pi / 6), math.sin(math.pi / 6)])
    # 13 written digits: ≤ 5e-13 Σ|f_i| = 1e-12 ‖F‖ (Σ|f_i| ≈ 2 ‖F‖ on the coarse mesh; the
    # assembled resultant itself is exact to 2e-16); measured 2.4e-14; 1e-11 = 10× the bound
    assert np.abs(F - Fref).max() <= 1e-11 * np.linalg.norm(Fref)
    # node by node the same vector we assemble (to the 13 written digits)
    f = np.zeros_like(model.f)
    for ln in loads:
        node, dof, val = ln.split(",")
        f[3 * (int(node) - 1) + int(dof) - 1] = float(val)
    assert np.abs(f - model.f).max() <= 1e-12 * np.abs(model.f).max()   # ≤ 5e-13 per value


# --------------------------------------------------------------------------- springs

@pytest.mark.parametrize("K", [K_SEED, ((1.0e4, 2.0e4), (2.0e4, 9.0e4)),
                               ((5.0e3, -1.2e3), (-1.2e3, 7.0e3))])
def test_spring_split_reproduces_k_with_positive_springs(K):
    from shaftfe.io import abaqus
    a, b, d = K[0][0], K[0][1], K[1][1]
    s = abaqus.spring_split(K)
    # closed-form eigenvalues of [[a, b], [b, d]]
    m, r = 0.5 * (a + d), math.hypot(0.5 * (a - d), b)
    # symmetric eigensolver: error ≤ few eps ‖K‖, ≤ 4e-15 relative to the smaller eigenvalue
    # (case 2: ‖K‖/λ_min = 18); 1e-13 leaves 25×
    assert sorted(s.stiffness) == pytest.approx([m - r, m + r], rel=1e-13)
    assert min(s.stiffness) > 0           # (the diag(K11-K12, K22-K12) split is negative for #2)
    rec = sum(k * np.outer(v, v) for k, v in zip(s.stiffness, s.directions, strict=True))
    # exact arithmetic (round-off only): Σ λ v vᵀ of an orthonormal eigenbasis, ‖K‖/|a| ≤ 10
    assert np.abs(rec - np.array(K)).max() <= 1e-12 * abs(a)
    if K == K_SEED:                       # K11 ± K12 along (1, ±1)/√2
        # exact arithmetic: eps ‖K‖/λ_min = 4e-16 (‖K‖/λ_min = 1.7)
        assert sorted(s.stiffness) == pytest.approx([35_030 - 8_756, 35_030 + 8_756], rel=1e-14)


def test_deck_springs_assemble_to_the_bearing_matrix(deck, model):
    """Parse SPRINGA elements, their stiffness and node coordinates back from the deck and
    assemble Σ k n nᵀ on each reference node: the (y, z) block must be the bearing's K."""
    info, text = deck
    b = keyword_blocks(text)
    xyz = {int(ln.split(",")[0]): np.array([float(v) for v in ln.split(",")[1:]])
           for ln in block(b, "*NODE, NSET")}
    spring_el = {}
    for k, occ in b.items():
        m = re.match(r"\*ELEMENT, TYPE=SPRINGA, ELSET=(\w+)", k)
        if m:
            _, n1, n2 = occ[0][0].split(",")
            spring_el[m.group(1)] = (int(n1), int(n2))
    stiff = {}
    for k, occ in b.items():
        m = re.match(r"\*SPRING, ELSET=(\w+)", k)
        if m:
            assert occ[0][0] == ""                               # SPRINGA: no dof line
            stiff[m.group(1)] = float(occ[0][1])
    assert set(spring_el) == set(stiff) and len(stiff) == info.n_springs == 4
    Kref: dict[int, np.ndarray] = {}
    for name, (n1, n2) in spring_el.items():
        n = xyz[n2] - xyz[n1]
        n /= np.linalg.norm(n)
        Kref[n1] = Kref.get(n1, np.zeros((3, 3))) + stiff[name] * np.outer(n, n)
    for brg in ("L", "R"):
        ref = info.rows[brg]["u_y"][0]
        assert info.rows[brg]["u_z"] == (ref, 3)
        # round-off only (≈ 3e-14 relative to K ≈ 3.5e4 N/mm; measured 7e-12 N/mm): the seed's
        # directions (1, ±1)/√2 round identically in both written components (normalisation
        # restores them) and its eigenvalues K11 ± K12 are integers, exact in 13 digits
        assert np.abs(Kref[ref][1:, 1:] - np.array(K_SEED)).max() <= 1e-9
        assert np.abs(Kref[ref][0]).max() <= 1e-9     # nothing axial: exact (same x), measured 0
        # ground nodes are held in all three directions
    bnd = block(b, "*BOUNDARY")
    held = {(int(ln.split(",")[0]), int(ln.split(",")[1]), int(ln.split(",")[2])) for ln in bnd}
    for g in (n2 for _, n2 in spring_el.values()):
        assert (g, 1, 3) in held


# --------------------------------------------------------------------------- equations

def parse_equations(text: str) -> list[list[tuple[int, int, float]]]:
    lines = block(keyword_blocks(text), "*EQUATION")
    out, i = [], 0
    while i < len(lines) and lines[i].strip():
        nterm = int(lines[i])
        i += 1
        terms: list[tuple[int, int, float]] = []
        while len(terms) < nterm:
            f = lines[i].split(",")
            assert len(f) % 3 == 0 and len(f) // 3 <= 4
            terms += [(int(f[j]), int(f[j + 1]), float(f[j + 2])) for j in range(0, len(f), 3)]
            i += 1
        out.append(terms)
    return out


def test_equations_reproduce_the_rbe3_rows(deck, model):
    """Each bearing's equations E satisfy E = A⁻¹ [G_rows, −I] for an invertible A (row
    reduction of 'G_rows u − q = 0'): recover A = −(E_q)⁻¹ and check A E_u = G_rows. Every
    dependent dof is dependent once and appears in no other equation."""
    info, text = deck
    eqs = parse_equations(text)
    assert len(eqs) == info.n_equations
    n = info.n_mesh_nodes
    deps = [(t[0][0], t[0][1]) for t in eqs]
    assert all(t[0][2] == 1.0 for t in eqs)
    assert len(set(deps)) == len(deps)
    others = {(nd, d) for t in eqs for nd, d, _ in t[1:]}
    assert not (set(deps) & others)
    for c in model.couplings:
        rows = info.rows[c.name]                     # label -> (reference node, dof)
        labels = list(rows)
        G = np.vstack([blk.R for blk in model.blocks if blk.bearing == c.name])
        blabels = [lab for blk in model.blocks if blk.bearing == c.name for lab in blk.labels]
        G = G[[blabels.index(lab) for lab in labels]]
        qpos = {rows[lab]: j for j, lab in enumerate(labels)}
        mine = [t for t in eqs if any((nd, d) in qpos for nd, d, _ in t)]
        assert len(mine) == len(labels)
        Eu = np.zeros((len(mine), 3 * n))
        Eq = np.zeros((len(mine), len(labels)))
        for i, t in enumerate(mine):
            for nd, d, cf in t:
                if (nd, d) in qpos:
                    Eq[i, qpos[(nd, d)]] = cf
                else:
                    Eu[i, 3 * (nd - 1) + d - 1] = cf
        A = -np.linalg.inv(Eq)
        # 13 written digits (5e-13) × cond(Eq) ≈ 10 × a few terms ≈ 1e-11; measured 3.7e-13
        assert np.abs(A @ Eu - G).max() <= 1e-10 * np.abs(G).max()


@pytest.mark.parametrize("case", ["springs", "rigid", "tilt spring"])
def test_eliminated_system_gives_our_static_solution(model, cache, case):
    """The deck's support system (equations + springs + holds), solved by elimination the way
    ccx treats MPCs, reproduces shaftfe.static.solve's Woodbury solution (springs; rigid radial
    holds; a tilt spring, which puts SPRINGAs on the rotation reference node)."""
    from scipy.sparse.linalg import spsolve

    from shaftfe.io import abaqus
    from shaftfe.static.model import StaticOptions, build_model
    from shaftfe.static.solve import solve_model
    if case == "rigid":
        model = build_model(cylinder(), StaticOptions(level="coarse", rigid_supports=True),
                            shaft_mesh=model.shaft_mesh)
    elif case == "tilt spring":
        model = build_model(cylinder(tilt=2.0e7), StaticOptions(level="coarse"),
                            shaft_mesh=model.shaft_mesh)
        assert any(lab == "θ_y" for blk in model.blocks for lab in blk.labels)
    T, Kf = abaqus.deck_system(model)
    nd = model.K.shape[0]
    nr = T.shape[0] - nd
    f = np.concatenate([model.f, np.zeros(nr)])
    u = T @ spsolve((T.T @ Kf @ T).tocsc(), T.T @ f)
    ref = solve_model(model).u
    # round-off only: eps × the Skeel condition ‖|A⁻¹|(|A||q| + |b|)‖/‖q‖ of the eliminated
    # system A = Tᵀ K T, 4e4 (rigid) … 4e5 (tilt spring), ≈ 1e-10; 1e-8 = 100× that. (The
    # normwise eps·cond₁(A), up to 7e-7 here, is not scale invariant: the tilt spring's
    # N·mm/rad rows inflate it.) Measured ≤ 1.5e-11 for PARDISO and SuperLU.
    assert np.abs(u[:nd] - ref).max() <= 1e-8 * np.abs(ref).max()


# --------------------------------------------------------------------------- readers

def test_frd_reader_on_fixture():
    from shaftfe.io import frd
    r = frd.read_frd(FIX / "small.frd")
    assert r.node_ids.tolist() == [1, 2, 3, 12345]
    assert r.coords[2].tolist() == [0.0, -3.0, 0.0]
    d = r.result("DISP")
    assert d.components == ("D1", "D2", "D3") and d.step == 1 and d.time == 1.0
    assert d.values[1].tolist() == [-1.5e-2, -3.25e-1, 2.0]              # touching numbers
    assert d.values[2].tolist() == [-3.0, -3.0, -3.0]
    assert d.values[3].tolist() == [4.0e-5, 0.0, -7.5]
    s = r.result("STRESS")
    assert s.components == ("SXX", "SYY", "SZZ", "SXY", "SYZ", "SZX")
    assert s.values[0].tolist() == [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]        # -1 + -2 lines
    assert s.values[1].tolist() == [-100.0, -3.0, 0.5, -3.5, 0.0, 12.0]
    assert s.nodes.tolist() == [1, 2, 3, 12345]
    with pytest.raises(KeyError):
        r.result("TEMP")


def test_dat_reader_on_fixture():
    from shaftfe.io import frd
    d = frd.read_dat(FIX / "small.dat")
    g = d.table("forces", "NGROUND")
    assert g.columns == ("node", "fx", "fy", "fz")
    assert g.keys[:, 0].tolist() == [21, 22]
    assert g.values[0].tolist() == [-1.0, 2500.0, -3.0e-3]
    t = d.table("total force", "SEAT_A")
    assert t.keys.shape == (1, 0) and t.values[0].tolist() == [-4.263812e-10, -3.260519e3,
                                                                5.170837e-05]
    s = d.table("stresses", "EPRINT")
    assert s.columns[2:] == ("sxx", "syy", "szz", "sxy", "sxz", "syz")   # .dat shear order
    assert s.keys.tolist() == [[7, 1], [7, 2]]
    assert s.values[1].tolist() == [-1.0, -2.0, -3.0, -4.0, -5.0, -6.0]
    assert d.frequencies_hz.tolist() == [1000.0, 2000.0]
    assert d.eigenvalues.shape == (2, 4)
