"""Fatigue of the whole static field: per-node life, damage and safety factor, hot spots.

``evaluate(ref, history, material, ...)`` takes a static reference solution (a
``shaftfe.static.cache.StaticReference``: nodal stresses at ``ref.ref_rpm``, coordinates, named
regions, the excluded singular nodes) and a ``shaftfe.fatigue.history.LoadHistory``. The stress at
time t is σ_ref · (rpm(t) / ref_rpm)², so the history is first RE-REFERENCED to the static
solution's speed (``history.with_reference(ref.ref_rpm)``: e.g. the seed's rpm.dat, normalised to
7000 rpm, against the static solve at 10 000 rpm: load factor × (7000 / 10 000)²). Then
``shaftfe.fatigue.assess`` evaluates every node at once (broadcast over nodes × cycle classes, no
Python loop over nodes): equivalent stress, rainflow cycles of the load factor (counted once),
mean-stress correction, S-N curve, Miner damage per block, life in blocks / hours / km and the
safety factor at the design life (exact scalar-root method).

Hot spot = the node of largest damage per block (shortest life); ties (e.g. every node below
the endurance limit: no damage) are broken by the smaller safety factor, then by the larger
|σ_eq|. It is taken
* FILTERED: over the nodes not excluded by the singular-point rule of the static analysis
  (``recovery.excluded_nodes``: one element layer around the edges of the bearing and
  pressed-load patches, where the stress is singular by construction; the seed excluded its
  minimum under a bearing in the same spirit), for the whole shaft and for each named region;
* UNFILTERED: over all nodes, always reported beside it.

The region of the whole-shaft hot spot is the first region containing that node in the order
fillet, keyway, shoulder, seat, others ("-" if the node is on no named face).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from shaftfe.fatigue import kernels
from shaftfe.fatigue.assess import (
    DEFAULT_DESIGN_LIFE_BLOCKS,
    DEFAULT_SPEED_KMH,
    FatigueResult,
    assess,
)
from shaftfe.fatigue.kernels import BETA_MIN, equivalent_stress, von_mises
from shaftfe.fatigue.sn import FatigueMaterial
from shaftfe.io.vtu import write_point_fields
from shaftfe.solid.features import kind_of

# a node on several regions is labelled by the first of its regions' kinds in this order
_KIND_PRIORITY = {"fillet": 0, "groove": 0, "keyway": 1, "cross_hole": 1, "shoulder": 2,
                  "seat": 3, "bearing_seat": 3}


@dataclass(frozen=True)
class HotSpot:
    """One node's fatigue numbers (life ∞ where there is no damage)."""

    region: str                   # region it was searched in, or the whole shaft's label
    regions: tuple[str, ...]      # every region that contains the node
    node: int
    xyz_mm: tuple[float, float, float]
    sigma_eq_ref_MPa: float       # equivalent stress at the static reference speed
    von_mises_ref_MPa: float
    damage_per_block: float
    life_blocks: float
    life_hours: float
    life_km: float
    safety_factor: float
    safety_status: str            # solved | capped | floored
    excluded: bool                # the node is in the singular-point exclusion

    @property
    def infinite_life(self) -> bool:
        return self.damage_per_block == 0.0

    def to_dict(self) -> dict:
        def num(v: float):
            return float(v) if math.isfinite(v) else None
        return {"region": self.region, "regions": list(self.regions), "node": self.node,
                "xyz_mm": list(self.xyz_mm), "sigma_eq_ref_MPa": num(self.sigma_eq_ref_MPa),
                "von_mises_ref_MPa": num(self.von_mises_ref_MPa),
                "damage_per_block": num(self.damage_per_block),
                "life_blocks": num(self.life_blocks), "life_hours": num(self.life_hours),
                "life_km": num(self.life_km), "infinite_life": self.infinite_life,
                "safety_factor": num(self.safety_factor), "safety_status": self.safety_status,
                "excluded": self.excluded}


@dataclass(frozen=True, eq=False)
class FatigueField:
    result: FatigueResult                 # per-node arrays (n_nodes,)
    history: object                       # the LoadHistory re-referenced to ref_rpm
    ref_rpm: float                        # speed of the static solution
    history_rpm_ref: float                # reference of the history as read
    hot_spot: HotSpot                     # filtered (singular-point rule)
    hot_spot_unfiltered: HotSpot
    region_hot_spots: tuple[HotSpot | None, ...] = ()   # filtered, per region (None: all
    region_names: tuple[str, ...] = ()                  # of its nodes are excluded)
    n_nodes: int = 0
    n_excluded: int = 0
    seconds: float = 0.0                  # wall time of the evaluation
    excluded_mask: np.ndarray = field(default=None, repr=False)

    @property
    def cycles_per_block(self) -> float:
        return self.result.cycles.total_count


def _order(d: np.ndarray, sf: np.ndarray, s: np.ndarray) -> np.ndarray:
    """Node order, worst first: damage desc, safety factor asc, |σ_eq| desc."""
    return np.lexsort((-np.abs(s), sf, -d))


def worst_node(res: FatigueResult, nodes: np.ndarray | None = None) -> int:
    """Index (into the field) of the worst node among ``nodes`` (all if None); -1 if empty."""
    d, sf, s = res.damage_per_block, res.safety_factor, res.sigma_eq_MPa
    if nodes is None:
        return int(_order(d, sf, s)[0]) if d.size else -1
    nodes = np.asarray(nodes, dtype=np.int64)
    if nodes.size == 0:
        return -1
    return int(nodes[_order(d[nodes], sf[nodes], s[nodes])[0]])


def _label(i: int, regions: dict[str, np.ndarray], member: dict[str, np.ndarray]) -> tuple:
    inside = [name for name in regions if member[name][i]]

    def rank(name: str) -> tuple[int, str]:
        return _KIND_PRIORITY.get(kind_of(name), len(_KIND_PRIORITY)), name
    return tuple(sorted(inside, key=rank))


def _spot(res: FatigueResult, i: int, region: str, regions: tuple, xyz: np.ndarray,
          vm: np.ndarray, excl: np.ndarray) -> HotSpot:
    return HotSpot(
        region=region, regions=regions, node=int(i),
        xyz_mm=tuple(float(c) for c in xyz[:, i]),
        sigma_eq_ref_MPa=float(res.sigma_eq_MPa[i]), von_mises_ref_MPa=float(vm[i]),
        damage_per_block=float(res.damage_per_block[i]),
        life_blocks=float(res.life_blocks[i]), life_hours=float(res.life_hours[i]),
        life_km=float(res.life_km[i]), safety_factor=float(res.safety_factor[i]),
        safety_status=("solved", "capped", "floored")[int(res.safety_status[i])],
        excluded=bool(excl[i]))


def candidates(s_eq: np.ndarray, excluded: np.ndarray, regions: dict) -> np.ndarray:
    """The nodes that can be a hot spot: in the whole field (filtered and not) and in each
    region, the largest positive and the most negative σ_eq. Damage grows with |σ_eq| for a
    given sign (every node sees the same cycles scaled), so the worst node of any node set is
    one of its two extremes; ``kernels.node_damage`` keeps these exact on a long history."""
    keep = np.flatnonzero(~excluded)
    sets = [np.arange(s_eq.size), keep]
    sets += [np.asarray(nodes, dtype=np.int64)[~excluded[np.asarray(nodes, dtype=np.int64)]]
             for nodes in regions.values()]
    out = []
    for nodes in sets:
        if nodes.size:
            v = s_eq[nodes]
            out += [nodes[int(np.argmax(v))], nodes[int(np.argmin(v))]]
    return np.unique(np.asarray(out, dtype=np.int64))


BETA_FLOOR = 1e-3        # nodes below this fraction of the peak |S0| keep β = 0 (no damage)
BETA_LOW_STRESS = 0.01   # a β beyond the model's range is dropped only below this share of the peak
#                          (x2_57, default level, seed loads: one node, at 0.13 % of the peak)


def softening_beta(s_soft, s_lin) -> np.ndarray:
    """β per node of S(λ) = S0 (λ + β λ²) from the equivalent stress with spin softening
    (``s_soft``) and without it (``s_lin = S0``), both at the reference speed (λ = 1):
    β = s_soft / s_lin − 1, exact at λ = 0 (slope) and at λ = 1. The model's error elsewhere is
    the softened response's cubic term, (ρ λ)² of the stress with ρ = m ω² / k the
    softening ratio (≈ 1.5 % at 10 000 rpm on x2_57: ≈ 2e-4; tests/validation measures it
    against an exact solve per speed). Nodes below ``BETA_FLOOR`` of the peak |S0|, or whose
    equivalent stress changes sign (a signed kind near zero), keep β = 0: their stress is
    negligible, and a ratio of two near-zero numbers is not a coefficient."""
    s1 = np.asarray(s_soft, dtype=float)
    s0 = np.asarray(s_lin, dtype=float)
    peak = float(np.abs(s0).max(initial=0.0))
    big = np.abs(s0) > BETA_FLOOR * peak
    ok = big & (s0 * s1 > 0)
    beta = np.zeros(s0.shape)
    np.divide(s1, s0, out=beta, where=ok)
    beta = np.where(ok, beta - 1.0, 0.0)
    # the completed co-rotating model (model.spin) also stiffens (a part's tilt inertia): at a
    # node where the softened stress falls far below the linear one the one-coefficient model
    # S0 (λ + β λ²) stops being monotone (β ≤ kernels.BETA_MIN). Such nodes are low-stressed
    # (BETA_LOW_STRESS); they keep β = 0, their linear
    # stress, and a node above that share is refused by kernels.check_beta as before
    low = (beta <= BETA_MIN) & (np.abs(s0) < BETA_LOW_STRESS * peak)
    return np.where(low, 0.0, beta)


def evaluate_arrays(stress_ref, history, material: FatigueMaterial, *, ref_rpm: float,
                    xyz, regions: dict | None = None, excluded=None,
                    equivalent: str = "von_mises", theory: str = "soderberg", kf: float = 1.0,
                    design_life_blocks: float = DEFAULT_DESIGN_LIFE_BLOCKS,
                    speed_kmh: float = DEFAULT_SPEED_KMH,
                    stress_linear=None) -> FatigueField:
    """The field evaluation on plain arrays: ``stress_ref`` (6, n) MPa at ``ref_rpm``, ``xyz``
    (3, n), ``regions`` name -> node ids, ``excluded`` node ids (see the module docstring).
    ``stress_linear``: with spin softening, the unsoftened stress at ``ref_rpm`` (``stress_ref``
    is then the softened one): each node's stress follows S0 (λ + β λ²) (``softening_beta``,
    ``kernels``)."""
    t0 = time.perf_counter()
    s = np.asarray(stress_ref, dtype=float)
    xyz = np.asarray(xyz, dtype=float)
    n = s.shape[1]
    h = history if math.isclose(history.rpm_ref, ref_rpm, rel_tol=1e-15) \
        else history.with_reference(ref_rpm)
    excl = np.zeros(n, dtype=bool)
    if excluded is not None:
        excl[np.asarray(excluded, dtype=np.int64)] = True
    regions = dict(sorted((regions or {}).items()))
    s_eq = equivalent_stress(s.T, equivalent)
    beta = None
    if stress_linear is not None:
        beta = softening_beta(s_eq, equivalent_stress(np.asarray(stress_linear, float).T,
                                                      equivalent))
    cand = candidates(s_eq, excl, regions)
    res = assess(s.T, h, material, equivalent=equivalent, theory=theory, kf=kf,
                 design_life_blocks=design_life_blocks, speed_kmh=speed_kmh, exact_at=cand,
                 sigma_eq=s_eq, beta=beta)
    vm = res.sigma_eq_MPa if equivalent == "von_mises" else von_mises(s.T)
    member = {}
    for name, nodes in regions.items():
        mk = np.zeros(n, dtype=bool)
        mk[np.asarray(nodes, dtype=np.int64)] = True
        member[name] = mk
    def exact(nodes: np.ndarray) -> np.ndarray:
        """On a long history only the candidates are exact; the worst node of any set is one
        of them (see ``candidates``), so the search keeps to them."""
        return nodes if res.exact_nodes is None else np.intersect1d(nodes, res.exact_nodes)

    keep = np.flatnonzero(~excl)
    i_f = worst_node(res, exact(keep))
    i_u = worst_node(res, exact(np.arange(n)))
    if i_f < 0:                                    # everything excluded: fall back, say so
        i_f = i_u
    worst = [worst_node(res, exact(np.asarray(nodes, dtype=np.int64)[
        ~excl[np.asarray(nodes, dtype=np.int64)]])) for nodes in regions.values()]
    if beta is not None:          # the reported nodes' safety factors on their own β, exactly
        exact_safety(res, [i for i in (i_f, i_u, *worst) if i >= 0], beta, material,
                     theory=theory, kf=kf, design_life_blocks=design_life_blocks)
    lab_f, lab_u = _label(i_f, regions, member), _label(i_u, regions, member)
    spot_f = _spot(res, i_f, lab_f[0] if lab_f else "-", lab_f, xyz, vm, excl)
    spot_u = _spot(res, i_u, lab_u[0] if lab_u else "-", lab_u, xyz, vm, excl)
    per_region = []
    for name, i in zip(regions, worst, strict=True):
        per_region.append(None if i < 0 else
                          _spot(res, i, name, _label(i, regions, member), xyz, vm, excl))
    return FatigueField(res, h, float(ref_rpm), float(history.rpm_ref), spot_f, spot_u,
                        tuple(per_region), tuple(regions), n, int(excl.sum()),
                        time.perf_counter() - t0, excl)


def exact_safety(res: FatigueResult, nodes, beta, material: FatigueMaterial, *, theory: str,
                 kf: float, design_life_blocks: float) -> None:
    """Re-solve the safety factor of ``nodes`` each on its own β (the field's are interpolated
    between β grid roots, ``kernels.safety_factor``) into ``res``'s arrays."""
    s0 = res.sigma_eq_MPa / (1.0 + beta)
    for i in dict.fromkeys(int(k) for k in nodes):
        n, st = kernels.safety_factor(s0[[i]], res.cycles, material, design_life_blocks,
                                      theory, kf, beta=beta[[i]])
        res.safety_factor[i], res.safety_status[i] = n[0], st[0]


def evaluate(ref, history, material: FatigueMaterial, **settings) -> FatigueField:
    """``evaluate_arrays`` on a ``shaftfe.static.cache.StaticReference``."""
    return evaluate_arrays(ref.stress_ref, history, material, ref_rpm=ref.ref_rpm, xyz=ref.xyz,
                           regions=ref.regions, excluded=ref.excluded,
                           stress_linear=getattr(ref, "stress_linear", None), **settings)


def hot_spot_with_factor(ref, ff: FatigueField, history, material: FatigueMaterial,
                         factor: float, **settings) -> dict:
    """The hot spot's life and safety factor with its stress × ``factor`` (one node: cheap):
    what the life becomes if the peak stress is corrected by a level's measured error."""
    i = ff.hot_spot.node
    s = np.asarray(ref.stress_ref)[:, [i]] * factor
    lin = getattr(ref, "stress_linear", None)
    f2 = evaluate_arrays(s, history, material, ref_rpm=ref.ref_rpm,
                         xyz=np.asarray(ref.xyz)[:, [i]],
                         stress_linear=None if lin is None else np.asarray(lin)[:, [i]] * factor,
                         **settings)
    h = f2.hot_spot
    return {"factor": factor, "life_blocks": h.life_blocks, "life_hours": h.life_hours,
            "life_km": h.life_km, "safety_factor": h.safety_factor}


def write_vtu(ref, ff: FatigueField, path) -> object:
    """``fatigue.vtu``: the mesh of ``ref`` with point data ``life_blocks`` (inf = no damage),
    ``damage_per_block``, ``safety_factor`` and ``von_mises_ref`` (MPa at ``ref.ref_rpm``) and
    cell data ``region`` (0 = volume, k ≥ 1 = face group ``ref.face_groups[k − 1]``), as in
    docs/FIELDS.md. Written atomically."""
    r = ff.result
    return write_ref_vtu(ref, path, {
        "life_blocks": np.asarray(r.life_blocks, dtype=float),
        "damage_per_block": np.asarray(r.damage_per_block, dtype=float),
        "safety_factor": np.asarray(r.safety_factor, dtype=float),
        "von_mises_ref": np.asarray(ref.von_mises_ref, dtype=float)})


def write_ref_vtu(ref, path, point_data: dict) -> object:
    """The mesh of the static reference ``ref`` (volume cells, then the face groups' triangles,
    cell data ``region``) with ``point_data``, written atomically (every fatigue method's
    fatigue.vtu)."""
    quad = ref.cells.shape[1] == 10
    cells, region = [], []
    if ref.cells.shape[0]:             # none for a surface-only field (axisymmetric model)
        cells.append(("tetra10" if quad else "tetra", np.asarray(ref.cells, dtype=np.int64)))
        region.append(np.zeros(ref.cells.shape[0], dtype=np.int32))
    if ref.face_cells.shape[0]:
        cells.append(("triangle6" if quad else "triangle",
                      np.asarray(ref.face_cells, dtype=np.int64)))
        region.append(np.asarray(ref.face_group, dtype=np.int32) + 1)
    write_point_fields(np.asarray(ref.xyz).T, cells, region, path, point_data)
    return path
