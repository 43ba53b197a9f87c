"""The seed method on several load patterns (issue #31): the static reference's per-pattern
stress fields (``StaticReference.patterns``, ``pattern_stress``) with their factor histories,
through the kernels of ``fatigue.channels`` (σ(t) = Σ_k σ_k L_k(t), rainflow of the signed von
Mises per candidate node, the single-channel mean-stress correction, S-N card and Miner sum).

When it runs: the variant has a load that does not scale with rpm² (a constant load, a
history channel such as ``torque_Nm`` or ``alpha_rad_s2``). A variant whose loads are all rpm²
keeps the single-channel path (``fatigue.field``) exactly as before.

Spin softening: the softened reference ``stress_ref`` minus the unsoftened ``stress_linear`` at
the reference speed is taken as a pattern of its own with the factor λ² (λ = (rpm/ref)²), the
rpm² pattern's softening (its base ∝ λ and the softening ∝ ω² ∝ λ). The softening of the other
patterns' responses (a constant load's deflection amplified by ω²) is attributed to it as well:
exact when every load is rpm², and a second-order error otherwise (a small load × a 1-4 %
softening).

Loads fixed in space (a gear mesh's transverse forces, gravity: ``model.loads`` frame
"space") turn once per revolution relative to the shaft. They are assessed at their static
instant (the direction ``angle_deg`` in the shaft's frame); their once-per-revolution reversal
(rotating bending) is NOT counted here. The run warns, naming them.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np

from shaftfe.fatigue import channels
from shaftfe.fatigue.assess import life_hours, life_km
from shaftfe.fatigue.run import finite_or_none
from shaftfe.model.loads import actions, pattern_key
from shaftfe.util.atomic import write_atomic
from shaftfe.util.fmt import life, lives, table_lines
from shaftfe.util.notices import warn
from shaftfe.util.units import rpm2_scale


def needs_channels(ref) -> bool:
    """Whether the reference holds a pattern whose law is not rpm² (the single-channel path
    scales one field by (rpm/ref)²)."""
    return any(p.get("scales_with") != "rpm2" for p in getattr(ref, "patterns", ()))


def pattern_fields(ref, history) -> tuple[tuple[str, ...], np.ndarray, np.ndarray]:
    """(labels, stress_k (K, 6, n), factor histories L (K, T)) of the reference's patterns on
    ``history`` (module docstring: the softening pattern last)."""
    labels, fields, rows = [], [], []
    for p in ref.patterns:
        key = pattern_key(SimpleNamespace(scales_with=p["scales_with"], ref_rpm=p["ref_rpm"],
                                          channel_ref=p["channel_ref"]))
        labels.append(p["key"])
        fields.append(np.asarray(ref.pattern_stress[p["key"]], dtype=float))
        rows.append(channels.channel_factors(history, [key])[0])
    if ref.stress_linear is not None:
        labels.append("spin softening")
        fields.append(np.asarray(ref.stress_ref, float) - np.asarray(ref.stress_linear, float))
        rows.append(rpm2_scale(history.rpm, float(ref.ref_rpm)) ** 2)
    return tuple(labels), np.stack(fields), np.vstack(rows)


@dataclass(frozen=True, eq=False)
class ChannelRun:
    """The seed method on several patterns: the job, its inputs, the candidates' lives
    (``channels.NodeLives``), their region labels and positions, the index of the hot spot
    among them, the patterns assessed, how many nodes passed the bound but were not
    assessed, the loads fixed in space, and the time taken."""
    job: object
    variant: object
    history: object
    material: object
    ref: object
    lives: channels.NodeLives
    regions: tuple[str, ...]
    xyz: np.ndarray
    hot: int
    patterns: tuple[str, ...]
    unassessed: int
    space_fixed: tuple[str, ...]
    seconds: float


def space_fixed_loads(variant) -> tuple[str, ...]:
    """The loads with a transverse part fixed in space (rotating bending, not counted)."""
    acts, body = actions(variant)
    names = [a.name for a in acts if a.frame == "space"
             and any(abs(c) > 0 for c in (*a.F_N[1:], *a.M_Nmm[1:]))]
    names += [b.name for b in body]
    return tuple(dict.fromkeys(names))


def run_channels(job, variant, history, material, ref) -> ChannelRun:
    """Assess the candidates of ``ref`` under ``history`` (``job``: the resolved FatigueJob)."""
    t0 = time.perf_counter()
    labels, sk, L = pattern_fields(ref, history)
    n = sk.shape[2]
    excl = np.zeros(n, dtype=bool)
    excl[np.asarray(ref.excluded, dtype=np.int64)] = True
    regions = dict(sorted(ref.regions.items()))
    nodes, more = channels.candidate_nodes(sk, L, excl, regions)
    nodes = nodes[~excl[nodes]] if (~excl[nodes]).any() else nodes
    lv = channels.assess_nodes(sk, L, nodes, material, design_life_blocks=job.design_life,
                               theory=job.mean_stress, kf=job.kf)
    member = {}
    for name, ids in regions.items():
        for i in np.asarray(ids, dtype=np.int64):
            member.setdefault(int(i), name)
    hot = int(np.lexsort((-lv.peak_MPa, -lv.damage))[0])
    fixed = space_fixed_loads(variant)
    if fixed:
        warn("rotating-bending-not-counted", "fatigue", "loads fixed in space ("
             + ", ".join(fixed) + ") are assessed at their static instant; their reversal once "
             "per revolution (rotating bending) is not counted in this life")
    return ChannelRun(job, variant, history, material, ref, lv,
                      tuple(member.get(int(i), "-") for i in nodes),
                      np.asarray(ref.xyz)[:, nodes], hot, labels, more, fixed,
                      time.perf_counter() - t0)


def summary(run: ChannelRun, files: dict) -> dict:
    """summary.json of a several-pattern run."""
    lv, h = run.lives, run.history

    def row(i):
        d = float(lv.damage[i])
        blocks = 1.0 / d if d > 0 else float("inf")
        hours = float(life_hours(blocks, h.duration_s))
        return {"region": run.regions[i], "xyz_mm": [float(c) for c in run.xyz[:, i]],
                "peak_sigma_eq_MPa": float(lv.peak_MPa[i]),
                "damage_per_block": finite_or_none(d),   # null: static failure (σ_m ≥ R)
                "life_blocks": finite_or_none(blocks),
                "life_hours": finite_or_none(hours),
                "life_km": finite_or_none(float(life_km(hours, run.job.speed_kmh))),
                "safety_factor": finite_or_none(float(lv.safety[i])),
                "cycle_classes": int(lv.n_classes[i])}
    return {"variant": run.variant.name, "method": "seed", "spectrum": str(h.source),
            "channels": list(h.channel_names), "patterns": list(run.patterns),
            "equivalent": channels.MULTI_CHANNEL_EQUIVALENT, "mean_stress": run.job.mean_stress,
            "material": run.material.name, "design_life_blocks": run.job.design_life,
            "hot_spot": row(run.hot), "candidates": [row(i) for i in range(lv.nodes.size)],
            "unassessed_candidates": run.unassessed,
            "candidate_rule": f"the {channels.MAX_CANDIDATES} nodes of largest stress bound "
                              f"above {channels.CANDIDATE_FRACTION:g} × the exact peak of the "
                              "regions' extremes (fatigue.channels)",
            "loads_fixed_in_space_not_cycled": list(run.space_fixed),
            "seconds": run.seconds, "files": files}


def write(run: ChannelRun, out) -> tuple[dict, list[str]]:
    """fatigue.vtu (the assessed nodes as points) and summary.json into ``out``."""
    import json

    import meshio

    lv = run.lives
    pts = np.ascontiguousarray(run.xyz.T)
    cells = [("vertex", np.arange(pts.shape[0]).reshape(-1, 1))]
    with np.errstate(divide="ignore"):
        life = np.where(lv.damage > 0, 1.0 / np.where(lv.damage > 0, lv.damage, 1.0), np.inf)
    data = {"damage_per_block": np.minimum(lv.damage, 1e30), "life_blocks": np.minimum(life, 1e30),
            "safety_factor": np.minimum(lv.safety, 1e30), "peak_sigma_eq_MPa": lv.peak_MPa}
    meshio.write(out / "fatigue.vtu", meshio.Mesh(pts, cells, point_data=data))
    s = summary(run, {"vtu": "fatigue.vtu"})
    write_atomic(out / "summary.json", json.dumps(s, indent=2, allow_nan=False) + "\n")
    return s, ["fatigue.vtu", "summary.json"]


def lines(run: ChannelRun, summary_: dict, out, files) -> list[str]:
    h, lv, job = run.history, run.lives, run.job
    hot = summary_["hot_spot"]
    p = [f"{run.variant.name} fatigue on {len(run.patterns)} load patterns: {h.source} "
         f"({h.n_samples} samples, channels: {', '.join(h.channel_names) or 'rpm only'})",
         "patterns: " + "; ".join(run.patterns),
         f"σ(t) = Σ_k σ_k L_k(t) at {lv.nodes.size} candidate nodes; rainflow of the signed von "
         f"Mises per node; {job.mean_stress}, {run.material.name}, kf {job.kf:g}",
         "",
         "life: " + lives(hot["life_blocks"] if hot["life_blocks"] is not None else
                          float("inf"), hot["life_hours"], hot["life_km"], job.speed_kmh),
         f"safety factor at {job.design_life:g} blocks: "
         + (f"{hot['safety_factor']:.3f}" if hot["safety_factor"] is not None else "∞"),
         f"hot spot: {hot['region']} at x = {hot['xyz_mm'][0]:.2f} mm, peak σ_eq "
         f"{hot['peak_sigma_eq_MPa']:.1f} MPa", ""]
    rows = [[c["region"], f"{c['xyz_mm'][0]:.2f}", f"{c['peak_sigma_eq_MPa']:.1f}",
             life(c["life_blocks"] if c["life_blocks"] is not None else float("inf")),
             f"{c['safety_factor']:.3f}" if c["safety_factor"] is not None else "∞"]
            for c in summary_["candidates"]]
    p += table_lines(["region", "x mm", "peak σ_eq MPa", "life blocks",
                      f"SF @{job.design_life:g}"], rows, title="candidate nodes")
    p.append(f"candidates: {summary_['candidate_rule']}"
             + (f"; {run.unassessed} more nodes passed the bound, not assessed"
                if run.unassessed else ""))
    p.append("\nwrote " + ", ".join(str(out / f) for f in files))
    return p


def warn_rpm2_only(variant, who: str) -> None:
    """``who`` (a method, or the seed method on one field a caller gives it: the report, a
    study) scales one field (or one beam solution) by (rpm/ref)²: the variant's loads of other
    laws are then taken at their reference values and scaled like the rest. Said once, naming
    them (``shaftfe fatigue --method seed`` assesses them per pattern: ``run_channels``)."""
    other = [ld.name for ld in variant.loads if ld.scales_with != "rpm2"]
    if other:
        warn("loads-scaled-as-rpm2", "fatigue", f"{who} scales one stress field by "
             f"(rpm/ref)²: the loads {', '.join(other)} (laws other than rpm2) are taken at "
             "their reference value and scaled with rpm² too; `shaftfe fatigue --method seed` "
             "assesses each load pattern with its own history")

