"""Export the static/modal model to an Abaqus-format input deck that CalculiX (ccx 2.20) runs.

The deck holds the SAME discrete model as ``shaftfe.static.solve`` (same nodes, same P2 tets, same
nodal load vector, same support rows), so a CalculiX run isolates the solver and the stress
recovery (``benchmarks/bench_calculix.py``).

Contents
--------
* ``*NODE``: mesh node i → id i + 1, coordinates written ``.12e`` (every numeric field
  ≤ 20 characters: ccx reads a number from at most 20 characters, FINDINGS pitfall 9).
* ``*ELEMENT, TYPE=C3D10``: Abaqus / CalculiX 10-node tetrahedron order (CalculiX manual
  §6.2.x "C3D10", Abaqus Analysis User's Manual §28.1.4 "Three-dimensional solid element
  library"): corners 1-4 with the face 1-2-3 seen counter-clockwise from node 4 (positive
  volume), then the mid-side nodes of the edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4. The
  permutation from scikit-fem's P2 numbering is derived from the element's reference node
  coordinates (``TET10_EDGES``), not assumed; negatively oriented tets get corners 2 and 3
  swapped.
* ``*MATERIAL``: ``*ELASTIC`` E, ν and ``*DENSITY`` ρ of the shaft material (mm, N, t/mm³).
* Supports, for every bearing (``shaftfe.fe.supports``): the remote-point rows q = G u of the
  RBE3 coupling enter as linear ``*EQUATION`` s, not as ccx's ``*COUPLING/*DISTRIBUTING``.
  ccx 2.20 does accept the latter (checked on a one-element deck: it becomes one special
  multiple point constraint of its own with its own weighting), but that would be an
  equivalent, not the same, coupling; the equations reproduce our least-squares rows exactly
  (13 significant digits), so the comparison isolates the solver. Every row
  (u_x, u_y, u_z → dofs 1-3 of a reference node A; θ_x, θ_y, θ_z → dofs 1-3 of a node B,
  made only when needed) gets its own dof q: R u − q = 0. Hard rows (axial hold, twist hold,
  rigid radial) hold their q with ``*BOUNDARY``; spring blocks put SPRINGAs on their q; unused
  reference dofs are held. The m rows of a bearing are row-reduced on m pivot dofs of its
  seat (QR with column pivoting) so that each equation has its own dependent dof (the first
  term, coefficient 1) that appears in no other equation: no MPC cascading and no SPC on a
  dependent dof (both restrictions of ccx's ``equations.f``). ccx does not report the forces
  of MPCs, so the reaction of a bearing is printed as the sum of the internal nodal forces of
  its seat nodes (``*NODE PRINT, TOTALS=ONLY``, RF): with no external load on the seat that is
  the force the support exerts on the shaft; for springs also as the ground nodes' RF.
* Springs: C = Σ_k λ_k v_k v_kᵀ (eigen-decomposition, λ_k > 0 for an SPD C) → one
  ``SPRINGA`` per eigenpair, stiffness λ_k, from the reference node to a fixed ground node
  placed at reference + L (0, v_k1, v_k2); a SPRINGA's energy is ½ λ (n·Δu)², n the unit
  vector between its nodes, so the sum is exactly ½ qᵀ C q. (The split diag(K11 − K12,
  K22 − K12) + K12 along (1, 1) also reproduces C but needs a negative spring when K12 < 0 or
  K12 > min(K11, K22); the eigen split never does.)
* ``*CLOAD``: the model's nodal load vector f at ``static.REF_RPM`` (the consistent vector we
  assemble, so both codes see the identical load).
* Steps: ``*STATIC`` (outputs: U and S to the .frd; RF of the ground nodes, U of the
  reference nodes, the summed RF of each seat and integration-point S of a chosen element set
  to the .dat) and/or ``*FREQUENCY`` (n modes; eigenvalues in the .dat).

``build_supports``, ``elimination`` and ``spring_matrix`` give the same support system as
matrices (dependent dofs eliminated the way ccx eliminates MPCs), for our own modal solve in
``benchmarks/bench_calculix.py`` and for the tests.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from shaftfe.fe import assembly as fem

# Abaqus / CalculiX C3D10: mid-side nodes 5..10 on these corner pairs (0-based corners).
TET10_EDGES = ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))
_REF_CORNERS = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
FLOAT_FMT = ".12e"            # at most 19 characters: ccx reads ≤ 20 per numeric field
MAX_LINE = 132                # ccx input lines are at most 132 characters
TERMS_PER_LINE = 4            # *EQUATION terms per data line (ccx reads n/3 terms per line)
SPRING_ARM_MM = 1.0e6         # reference → ground node of a SPRINGA (ccx reports RF along the
                              # deformed spring direction: a long arm makes that exact)
COEF_DROP = 1e-14             # |coefficient| below this × row max is dropped from an equation


def _num(x: float) -> str:
    return format(float(x), FLOAT_FMT)


def skfem_to_abaqus_tet10() -> np.ndarray:
    """Permutation p (10,) with abaqus_node[k] = skfem_element_dofs[p[k]], derived from the
    reference node coordinates of scikit-fem's ``ElementTetP2`` (corners at the unit
    tetrahedron's vertices in the same order as Abaqus' corners 1-4)."""
    from skfem import ElementTetP2
    ref = np.asarray(ElementTetP2().doflocs, dtype=float)
    p = []
    for k in range(4):
        p.append(int(np.argmin(np.abs(ref - _REF_CORNERS[k]).sum(axis=1))))
    for a, b in TET10_EDGES:
        mid = 0.5 * (_REF_CORNERS[a] + _REF_CORNERS[b])
        d = np.abs(ref - mid).sum(axis=1)
        k = int(np.argmin(d))
        if d[k] > 1e-12:                                   # pragma: no cover
            raise ValueError("scikit-fem P2 element has no node at an edge midpoint")
        p.append(k)
    if sorted(p) != list(range(10)):                       # pragma: no cover
        raise ValueError("not a permutation")
    return np.array(p)


def abaqus_connectivity(mesh) -> np.ndarray:
    """(ne, 10) 0-based node numbers of every P2 tet in Abaqus C3D10 order, positively
    oriented (det[x2 − x1, x3 − x1, x4 − x1] > 0 over the corners)."""
    if not fem.is_quadratic(mesh):
        raise ValueError("the CalculiX export needs the P2 (MeshTet2) mesh")
    conn = fem.element_nodes(mesh)[skfem_to_abaqus_tet10()].T.copy()     # (ne, 10)
    x = mesh.doflocs
    c = x[:, conn[:, :4]]                                                 # (3, ne, 4)
    vol = np.einsum("ie,ie->e", c[:, :, 1] - c[:, :, 0],
                    np.cross(c[:, :, 2] - c[:, :, 0], c[:, :, 3] - c[:, :, 0], axis=0))
    neg = vol < 0
    # swap corners 2 and 3 (1-based); edges 1-2 ↔ 3-1 and 2-4 ↔ 3-4 follow, 2-3 stays
    swap = [0, 2, 1, 3, 6, 5, 4, 7, 9, 8]
    conn[neg] = conn[neg][:, swap]
    return conn


# --------------------------------------------------------------------------- supports

@dataclass(frozen=True)
class SpringSplit:
    """C = Σ stiffness_k · direction_k direction_kᵀ (directions in the block's 2-dof plane)."""
    stiffness: tuple[float, ...]
    directions: tuple[tuple[float, float], ...]


def spring_split(C) -> SpringSplit:
    """Eigen-decomposition of an SPD 2×2 spring matrix into positive axial springs."""
    C = np.asarray(C, dtype=float)
    w, V = np.linalg.eigh(0.5 * (C + C.T))
    if w.min() <= 0:
        raise ValueError(f"spring matrix is not positive definite: {C.tolist()}")
    return SpringSplit(tuple(float(a) for a in w),
                       tuple((float(V[0, k]), float(V[1, k])) for k in range(w.size)))


@dataclass(frozen=True, eq=False)
class Equation:
    """Σ coef · u(node, dof) = 0; the first term is the dependent dof (coefficient 1).
    ``nodes`` are 0-based model nodes (reference nodes numbered after the mesh nodes),
    ``dofs`` 1-based (1 = x, 2 = y, 3 = z)."""
    nodes: np.ndarray
    dofs: np.ndarray
    coefs: np.ndarray


@dataclass(frozen=True, eq=False)
class Supports:
    """The support part of the deck, in 0-based model node numbers (reference nodes after the
    mesh nodes, ground nodes after the reference nodes)."""
    equations: tuple[Equation, ...]
    ref_nodes: dict                  # bearing -> (translation node, rotation node or -1)
    ref_xyz: np.ndarray              # (3, n_ref)
    row_dof: dict                    # bearing -> {label: (ref node, dof 1..3)}
    spc: tuple                       # (node, dof) held at 0: hard rows and unused ref dofs
    springs: tuple                   # (ref node, ground node, stiffness)
    ground_xyz: np.ndarray           # (3, n_ground)
    ground_of: dict = field(default_factory=dict)   # bearing -> tuple of ground nodes


_ROW = {"u_x": (0, 1), "u_y": (0, 2), "u_z": (0, 3), "θ_x": (1, 1), "θ_y": (1, 2),
        "θ_z": (1, 3)}


def build_supports(model) -> Supports:
    """Equations, reference nodes, holds and springs for ``model.blocks``.

    Every support row r (a row of the RBE3 matrix G, ``supports.blocks``) gets a dof q_r of a
    reference node of its bearing: the translation rows (u_x, u_y, u_z) dofs 1-3 of node A,
    the rotation rows (θ_x, θ_y, θ_z) dofs 1-3 of node B (created only when needed). The
    equations say R u − q = 0; a hard row holds its q (``*BOUNDARY``), so ccx reports its
    multiplier as the RF of that dof (the force or moment the support exerts on the shaft); a
    spring block puts SPRINGAs between its two q dofs and ground; unused reference dofs are
    held. The m rows of a bearing are row-reduced on m pivot dofs of the seat so that each
    dependent dof (first term, coefficient 1) occurs in one equation only."""
    n = model.shaft_mesh.mesh.doflocs.shape[1]
    loaded = np.nonzero(model.f != 0)[0]
    by_bearing: dict[str, list] = {}
    for blk in model.blocks:
        by_bearing.setdefault(blk.bearing, []).append(blk)
    x_of = {c.name: c.x_mm for c in model.couplings}
    ref_nodes, ref_xyz = _reference_nodes(by_bearing, x_of, n)
    n_ref = len(ref_xyz)
    eqs, springs, spc = [], [], []
    ground_of, ground_xyz, row_dof = {}, [], {}
    used_dep: set[int] = set()
    for name, blks in by_bearing.items():
        R = np.vstack([b.R for b in blks])                       # (mr, ndof)
        labels = [lab for b in blks for lab in b.labels]
        rd = {lab: (ref_nodes[name][_ROW[lab][0]], _ROW[lab][1]) for lab in labels}
        row_dof[name] = rd
        held = set()
        for b in blks:
            if b.C is None:
                held.update(rd[lab] for lab in b.labels)
                continue
            grounds = _add_springs(b, rd, x_of[name], n + n_ref, ground_xyz, springs)
            ground_of[name] = ground_of.get(name, ()) + grounds
        for node in ref_nodes[name]:
            if node < 0:
                continue
            for d in (1, 2, 3):
                if (node, d) in held or (node, d) not in rd.values():
                    spc.append((node, d))
        eqs.extend(_bearing_equations(name, R, [rd[lab] for lab in labels], loaded, used_dep))
    return Supports(tuple(eqs), ref_nodes, np.array(ref_xyz, dtype=float).T.reshape(3, -1),
                    row_dof, tuple(spc), tuple(springs),
                    np.array(ground_xyz, dtype=float).T.reshape(3, -1), ground_of)


def _reference_nodes(by_bearing: dict, x_of: dict, n: int) -> tuple[dict, list]:
    """Reference nodes numbered after the ``n`` mesh nodes: per bearing A, then B if one of
    its rows is a rotation; ``(bearing -> (A, B or -1), coordinates)``."""
    ref_nodes, ref_xyz = {}, []
    nxt = n
    for name, blks in by_bearing.items():
        labels = [lab for b in blks for lab in b.labels]
        a = nxt
        nxt += 1
        ref_xyz.append((x_of[name], 0.0, 0.0))
        b_ = -1
        if any(lab.startswith("θ") for lab in labels):
            b_ = nxt
            nxt += 1
            ref_xyz.append((x_of[name], 0.0, 0.0))
        ref_nodes[name] = (a, b_)
    return ref_nodes, ref_xyz


def _add_springs(blk, rd: dict, x_mm: float, first_ground: int, ground_xyz: list,
                 springs: list) -> tuple[int, ...]:
    """SPRINGAs of a spring block (one per eigenpair of its C) from its reference node to new
    ground nodes (numbered from ``first_ground`` on); appends to ``ground_xyz`` and
    ``springs``, returns the ground nodes."""
    (na, d1), (nb, d2) = rd[blk.labels[0]], rd[blk.labels[1]]
    if na != nb or (d1, d2) != (2, 3):                   # pragma: no cover
        raise ValueError("a spring block must act on dofs 2, 3 of one node")
    split = spring_split(blk.C)
    grounds = []
    for kk, (v1, v2) in zip(split.stiffness, split.directions, strict=True):
        g = first_ground + len(ground_xyz)
        ground_xyz.append((x_mm, SPRING_ARM_MM * v1, SPRING_ARM_MM * v2))
        springs.append((na, g, kk))
        grounds.append(g)
    return tuple(grounds)


def _bearing_equations(name: str, R: np.ndarray, qdofs: list, loaded: np.ndarray,
                       used_dep: set[int]) -> list[Equation]:
    """The equations R u − q = 0 of one bearing (rows R, their q dofs ``qdofs``), row-reduced
    on pivot dofs of the seat that carry no load and are not in ``used_dep`` (updated): each
    pivot is the dependent (first) term of one equation only."""
    from scipy.linalg import qr
    mr = R.shape[0]
    cols = np.nonzero(np.abs(R).max(axis=0) > 0)[0]
    cand = np.setdiff1d(cols, loaded)
    cand = np.array([c for c in cand if int(c) not in used_dep], dtype=np.int64)
    _, _, piv = qr(R[:, cand], mode="economic", pivoting=True)
    piv = cand[piv[:mr]]
    used_dep.update(int(p) for p in piv)
    A = R[:, piv]
    if np.linalg.cond(A) > 1e10:                            # pragma: no cover
        raise ValueError(f"bearing {name!r}: support rows are (nearly) dependent")
    Rn = np.linalg.solve(A, R[:, cols])
    Qn = -np.linalg.inv(A)                                   # coefficients of q
    pos = {int(c): i for i, c in enumerate(cols)}
    eqs = []
    for i in range(mr):
        coef = Rn[i].copy()
        for j, p in enumerate(piv):
            coef[pos[int(p)]] = 1.0 if j == i else 0.0
        scale = max(np.abs(coef).max(), np.abs(Qn[i]).max())
        keep = np.abs(coef) > COEF_DROP * scale
        keep[pos[int(piv[i])]] = False
        d_all = cols[keep]
        nodes = [int(piv[i]) // 3, *(d_all // 3).tolist()]
        dofs = [int(piv[i]) % 3 + 1, *(d_all % 3 + 1).tolist()]
        coefs = [1.0, *coef[keep].tolist()]
        for j, (node, d) in enumerate(qdofs):
            if abs(Qn[i, j]) > COEF_DROP * scale:
                nodes.append(node)
                dofs.append(d)
                coefs.append(float(Qn[i, j]))
        eqs.append(Equation(np.array(nodes), np.array(dofs), np.array(coefs)))
    return eqs


def elimination(n_dofs: int, sup: Supports):
    """Sparse T (n_dofs + 3 n_ref, n_free) with u_full = T u_free: the equations' dependent
    dofs expressed by the independent ones (what ccx does with the MPCs) and the held
    reference dofs removed; also the indices of the free dofs. Reference-node dofs are
    numbered after the mesh dofs (3 per node)."""
    import scipy.sparse as sp
    n_ref = sup.ref_xyz.shape[1]
    N = n_dofs + 3 * n_ref
    dep = np.array([3 * e.nodes[0] + e.dofs[0] - 1 for e in sup.equations], dtype=np.int64)
    held = np.array([3 * nd + d - 1 for nd, d in sup.spc], dtype=np.int64)
    free = np.setdiff1d(np.arange(N), np.concatenate([dep, held]))
    col = np.full(N, -1, dtype=np.int64)
    col[free] = np.arange(free.size)
    rows, cols, vals = [free], [np.arange(free.size)], [np.ones(free.size)]
    for e, d in zip(sup.equations, dep, strict=True):
        g = 3 * e.nodes[1:] + e.dofs[1:] - 1
        c = col[g]
        ok = c >= 0                      # held dofs are zero: their terms drop out
        if np.isin(g[~ok], dep).any():                       # pragma: no cover
            raise ValueError("an equation refers to another equation's dependent dof")
        rows.append(np.full(int(ok.sum()), d))
        cols.append(c[ok])
        vals.append(-e.coefs[1:][ok] / e.coefs[0])
    T = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(N, free.size))
    return T, free


def spring_matrix(n_dofs: int, sup: Supports):
    """Stiffness (N × N, N = n_dofs + 3 n_ref) of the SPRINGAs on the reference dofs, the
    ground nodes held: Σ k n nᵀ with n the unit vector from the reference to the ground node."""
    import scipy.sparse as sp
    n = n_dofs // 3
    n_ref = sup.ref_xyz.shape[1]
    N = n_dofs + 3 * n_ref
    rows, cols, vals = [], [], []
    for rn, g, k in sup.springs:
        d = sup.ground_xyz[:, g - n - n_ref] - sup.ref_xyz[:, rn - n]
        d = d / np.linalg.norm(d)
        idx = 3 * rn + np.arange(3)
        rows.append(np.repeat(idx, 3))
        cols.append(np.tile(idx, 3))
        vals.append((k * np.outer(d, d)).ravel())
    if not rows:
        return sp.csr_matrix((N, N))
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(N, N))


# --------------------------------------------------------------------------- deck

@dataclass(frozen=True)
class DeckInfo:
    path: Path
    n_nodes: int                     # all nodes in the deck (mesh + reference + ground)
    n_mesh_nodes: int
    n_elements: int
    n_equations: int
    n_springs: int
    steps: tuple[str, ...]
    ref_nodes: dict                  # bearing -> reference node ids (1-based, deck numbering)
    ground_nodes: dict               # bearing -> ground node ids (1-based)
    rows: dict                       # bearing -> {row label: (reference node id, dof)}
    seat_sets: dict                  # bearing -> node set of its seat (total RF printed)
    load_sum_N: tuple[float, float, float]
    print_elements: int              # elements in the *EL PRINT set (0: none)
    seconds: float


def deck_system(model):
    """The deck's support system as ccx assembles it: ``(T, K_full)`` with K_full the shaft's
    K extended by the reference-node dofs plus the SPRINGAs (``spring_matrix``) and T the
    elimination of the equations and holds (``elimination``); the supported stiffness is
    Tᵀ K_full T, and u_full = T u_free."""
    import scipy.sparse as sp
    sup = build_supports(model)
    nd = model.K.shape[0]
    T, _ = elimination(nd, sup)
    nr = T.shape[0] - nd
    Kf = sp.block_diag([model.K, sp.csr_matrix((nr, nr))], format="csr") \
        + spring_matrix(nd, sup)
    return T, Kf


def _lines(items, per_line: int) -> list[str]:
    out = []
    for i in range(0, len(items), per_line):
        out.append(",".join(items[i:i + per_line]))
    return out


def write_deck(path, model, *, steps=("static", "frequency"), n_modes: int = 12,
               print_elements=None, f=None) -> DeckInfo:
    """Write the deck for ``model`` (``static.StaticModel``, P2 mesh) to ``path``.

    ``print_elements``: 0-based element numbers whose integration-point stresses go to the
    .dat (``*EL PRINT``); ``f``: load vector (default ``model.f`` at REF_RPM)."""
    import time
    t0 = time.perf_counter()
    path = Path(path)
    m = model.shaft_mesh.mesh
    n = m.doflocs.shape[1]
    conn = abaqus_connectivity(m)
    sup = build_supports(model)
    f = model.f if f is None else np.asarray(f, dtype=float)
    eprint = print_elements is not None and len(print_elements)
    out: list[str] = ["*HEADING", f"shaftfe export: variant {model.variant.name}, "
                      f"mesh {model.shaft_mesh.key[:12]}, {model.shaft_mesh.level}"]
    out.extend(_node_lines(m.doflocs, sup))
    out.extend(_element_lines(conn, sup))
    seat_sets = _seat_sets(model)
    out.extend(_set_lines(m, model.couplings, seat_sets, print_elements if eprint else None))
    out.extend(_material_lines(model.variant.material))
    out.extend(_support_lines(sup, n))
    f3 = f.reshape(-1, 3)
    out.extend(_step_lines(steps, f3, sup, seat_sets, bool(eprint), n_modes))
    for ln in out:
        if len(ln) > MAX_LINE:                              # pragma: no cover
            raise ValueError(f"deck line longer than {MAX_LINE} characters: {ln[:40]}...")
    text = "\n".join(out) + "\n"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    n_ref, n_gr = sup.ref_xyz.shape[1], sup.ground_xyz.shape[1]
    ref_ids = {b: tuple(r + 1 for r in v if r >= 0) for b, v in sup.ref_nodes.items()}
    gr_ids = {b: tuple(g + 1 for g in v) for b, v in sup.ground_of.items()}
    return DeckInfo(path, n + n_ref + n_gr, n, conn.shape[0], len(sup.equations),
                    len(sup.springs), tuple(steps), ref_ids, gr_ids,
                    {b: {lab: (nd + 1, d) for lab, (nd, d) in rd.items()}
                     for b, rd in sup.row_dof.items()}, seat_sets,
                    tuple(float(v) for v in f3.sum(axis=0)),
                    0 if print_elements is None else int(np.unique(print_elements).size),
                    time.perf_counter() - t0)


def _node_lines(x: np.ndarray, sup: Supports) -> list[str]:
    """``*NODE`` blocks: the mesh nodes (NSHAFT), then the reference (NREF) and ground
    (NGROUND) nodes numbered after them."""
    n = x.shape[1]
    n_ref = sup.ref_xyz.shape[1]
    out = ["*NODE, NSET=NSHAFT"]
    ids = np.arange(1, n + 1)
    out.extend(f"{i},{_num(a)},{_num(b)},{_num(c)}" for i, a, b, c in zip(ids, *x, strict=True))
    if n_ref:
        out.append("*NODE, NSET=NREF")
        out.extend(f"{n + 1 + k},{_num(a)},{_num(b)},{_num(c)}"
                   for k, (a, b, c) in enumerate(sup.ref_xyz.T))
    if sup.ground_xyz.shape[1]:
        out.append("*NODE, NSET=NGROUND")
        out.extend(f"{n + n_ref + 1 + k},{_num(a)},{_num(b)},{_num(c)}"
                   for k, (a, b, c) in enumerate(sup.ground_xyz.T))
    return out


def _element_lines(conn: np.ndarray, sup: Supports) -> list[str]:
    """The C3D10 elements (ELSET SHAFT), then one SPRINGA element and ``*SPRING`` per spring
    (ELSET SPR<k>), numbered after the tets."""
    out = ["*ELEMENT, TYPE=C3D10, ELSET=SHAFT"]
    out.extend(f"{e + 1}," + ",".join(map(str, row)) for e, row in enumerate(conn + 1))
    ne = conn.shape[0]
    for k, (rn, g, kk) in enumerate(sup.springs):
        eid = ne + 1 + k
        out.append(f"*ELEMENT, TYPE=SPRINGA, ELSET=SPR{k + 1}")
        out.append(f"{eid},{rn + 1},{g + 1}")
        out.append(f"*SPRING, ELSET=SPR{k + 1}")
        out.append("")                                   # no dof line for SPRINGA
        out.append(_num(kk))
    return out


def _seat_sets(model) -> dict[str, str]:
    """Bearing -> name of the node set of its seat (``SEAT_<NAME>``)."""
    return {c.name: "SEAT_" + "".join(ch if ch.isalnum() else "_" for ch in c.name.upper())
            for c in model.couplings}


def _set_lines(mesh, couplings, seat_sets: dict, print_elements) -> list[str]:
    """``*NSET`` of every seat and, when ``print_elements`` is given, ``*ELSET`` EPRINT."""
    out = []
    for c in couplings:
        out.append(f"*NSET, NSET={seat_sets[c.name]}")
        out.extend(_lines([str(int(i) + 1) for i in fem.face_nodes(mesh, c.facets)], 16))
    if print_elements is not None:
        out.append("*ELSET, ELSET=EPRINT")
        out.extend(_lines([str(int(e) + 1) for e in np.unique(print_elements)], 16))
    return out


def _material_lines(mat) -> list[str]:
    """``*MATERIAL`` (E, ν, ρ) and the ``*SOLID SECTION`` of the shaft that uses it."""
    name = mat.name.upper().replace(' ', '_')[:70] or 'STEEL'
    return [f"*MATERIAL, NAME={name}", "*ELASTIC", f"{_num(mat.E_MPa)},{_num(mat.nu)}",
            "*DENSITY", _num(mat.density_t_mm3),
            f"*SOLID SECTION, ELSET=SHAFT, MATERIAL={name}"]


def _support_lines(sup: Supports, n: int) -> list[str]:
    """``*EQUATION`` (the support rows) and ``*BOUNDARY`` (held dofs, ground nodes)."""
    out = []
    if sup.equations:
        out.append("*EQUATION")
        for e in sup.equations:
            out.append(str(len(e.coefs)))
            terms = [f"{nd + 1},{d},{_num(c)}" for nd, d, c in
                     zip(e.nodes, e.dofs, e.coefs, strict=True)]
            out.extend(_lines(terms, TERMS_PER_LINE))
    out.append("*BOUNDARY")
    out.extend(f"{nd + 1},{d},{d}" for nd, d in sup.spc)
    n_ref = sup.ref_xyz.shape[1]
    out.extend(f"{n + n_ref + 1 + k},1,3" for k in range(sup.ground_xyz.shape[1]))
    return out


def _step_lines(steps, f3: np.ndarray, sup: Supports, seat_sets: dict, eprint: bool,
                n_modes: int) -> list[str]:
    """One ``*STEP`` per entry of ``steps``: ``static`` (``*CLOAD`` f3 (n, 3) and the outputs)
    or ``frequency`` (``n_modes`` modes)."""
    nz = np.nonzero(f3)
    cload = [f"{i + 1},{d + 1},{_num(f3[i, d])}" for i, d in zip(*nz, strict=True)]
    out = []
    for s in steps:
        out.append("*STEP")
        if s == "static":
            out.extend(["*STATIC", "*CLOAD", *cload, "*NODE FILE", "U", "*EL FILE", "S"])
            if sup.ground_xyz.shape[1]:
                out.extend(["*NODE PRINT, NSET=NGROUND", "RF"])
            if sup.ref_xyz.shape[1]:
                out.extend(["*NODE PRINT, NSET=NREF", "U"])
            for nm in seat_sets.values():
                # internal nodal forces summed over the seat = the support's force on the shaft
                out.extend([f"*NODE PRINT, NSET={nm}, TOTALS=ONLY", "RF"])
            if eprint:
                out.extend(["*EL PRINT, ELSET=EPRINT", "S"])
        elif s == "frequency":
            out.extend(["*FREQUENCY", str(int(n_modes))])
        else:
            raise ValueError(f"unknown step {s!r}")
        out.append("*END STEP")
    return out


def mid_node_offsets(mesh, conn: np.ndarray | None = None) -> np.ndarray:
    """(ne, 6) distance of each Abaqus mid-side node from the midpoint of its corner pair
    (0 for a straight edge; a curved boundary edge moves its node off the chord)."""
    conn = abaqus_connectivity(mesh) if conn is None else conn
    x = mesh.doflocs
    d = []
    for k, (a, b) in enumerate(TET10_EDGES):
        mid = 0.5 * (x[:, conn[:, a]] + x[:, conn[:, b]])
        d.append(np.linalg.norm(x[:, conn[:, 4 + k]] - mid, axis=0))
    return np.array(d).T
