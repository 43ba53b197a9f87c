"""Text and JSON of the standards' assessments and of the element checks (shared by
``shaftfe fatigue --method fkm|din743`` and the report's "Strength by standard" section)."""

from __future__ import annotations

import math

import numpy as np

from shaftfe.fatigue import din743 as din
from shaftfe.fatigue import fkm
from shaftfe.fatigue import plots as fp
from shaftfe.fatigue.assess import life_hours
from shaftfe.fatigue.counting import Cycles, _matrix, rainflow_matrix
from shaftfe.fatigue.field import write_ref_vtu
from shaftfe.fatigue.fkm_field import governing_cycles
from shaftfe.fatigue.run import SEED_VARIANT
from shaftfe.machine_elements import bearings, drive, gear, key
from shaftfe.machine_elements.bearings import SEED_POINTS
from shaftfe.model.bearing_life import l10h
from shaftfe.model.mass import mass_properties
from shaftfe.solid.plan import sharp_keyway_edges
from shaftfe.util.atomic import write_atomic
from shaftfe.util.fmt import NO_FINITE_LIFE, big, json_clean, life, life_h_km, life_reason
from shaftfe.util.notices import collected

NONE = "—"        # a value the assessment has not got (nan): printed as this, never as "nan"


def _f(v, fmt=".3g"):
    if isinstance(v, float) and math.isnan(v):
        return NONE
    return "∞" if isinstance(v, float) and math.isinf(v) else format(v, fmt)


def _num(v):
    return float(v) if isinstance(v, (int, float)) and math.isfinite(v) else None


def no_load_cycles(res) -> bool:
    """The history has no load cycles: a constant speed. The rainflow count closes the block as
    one period of a repeating history (``counting``, closure "repeated"), so a constant speed
    counts no cycle at all, not even a start-up/shut-down one (that one is counted only where
    the history holds the start and the stop)."""
    return res.cycles is not None and res.cycles.n == 0


NO_LOAD_CYCLES = ("no load cycles in this history (constant speed; the block is repeated, so "
                  "no start-up/shut-down cycle either): no fatigue damage")


def _g(G: float) -> str:
    """A stress gradient, marked '*' where it is negative (``FKM_G_NOTE``)."""
    return f"{G:.3f}" + ("*" if G < 0 else "")


def _region(name: str, sharp) -> str:
    """A region's name, marked '†' on a sharp-edged keyway (``FKM_KEYWAY_NOTE``)."""
    return name + ("†" if name in sharp else "")


def sharp_keyways(variant) -> frozenset[str]:
    """The regions of the variant's sharp-edged keyways (no bottom radius)."""
    return frozenset(e.region for e in sharp_keyway_edges(variant))


def fkm_rows(res, sharp: frozenset[str]) -> list[list]:
    """The FKM table's rows; with no load cycles the columns of the cycles (K_AK of the largest
    cycle, the safeties, the utilisation, the life) are ``NONE``. ``sharp``: the regions of
    sharp-edged keyways (``sharp_keyways``), marked."""
    quiet = no_load_cycles(res)
    rows = []
    for r in res.regions:
        for c in (r.surface, r.core):
            if c is None:
                continue
            cyc = ([NONE] * 6 if quiet else
                   [_f(c.K_AK_largest, ".3f"), *(_f(c.safety[k]) for k in
                                          ("elementary", "modified", "consistent")),
                    _f(c.utilisation[res.rule]), life(c.life_blocks[res.rule])])
            rows.append([_region(r.region, sharp), c.layer, f"{r.xyz_mm[0]:.2f}",
                         f"{c.sigma_ref_MPa:+.1f}",
                         _g(c.G_per_mm), f"{c.n:.3f}", f"{c.K_d:.3f}", f"{c.R_m_MPa:.0f}",
                         f"{c.sigma_W_zd_MPa:.0f}", f"{c.Rz_um:g}", f"{c.K_R:.3f}",
                         f"{c.K_V:g}", f"{c.K_WK:.3f}", f"{c.sigma_WK_MPa:.0f}",
                         f"{c.M_sigma:.3f}", *cyc])
    return rows


FKM_HEAD = ["region", "layer", "x mm", "±σ_vM@ref MPa", "G 1/mm", "n_σ", "K_d,m", "R_m",
            "σ_W,zd", "R_z µm", "K_R", "K_V", "K_WK", "σ_WK", "M_σ", "K_AK",
            "S elem", "S mod", "S cons", "a (gov.)", "life blocks (gov.)"]
FKM_SIGN_NOTE = ("±σ_vM@ref: signed von Mises stress at the reference speed: the von Mises "
                 "magnitude with the sign of the principal stress of largest magnitude (+ "
                 "tension, − compression; the sign decides the Haigh range of the mean stress), "
                 "at the node FKM assesses (the one of highest utilisation, where the gradient "
                 "and a tensile mean count): a nodal value, so it can differ from `shaftfe "
                 "static`'s peak, the surface fit between the nodes at the most stressed point")
FKM_G_NOTE = ("G* < 0: the von Mises stress rises inward from the surface (the node is not the "
              "peak along its normal); the support factor n_σ(G) gives no credit for it: "
              "n_σ = 1 (FKM: n_σ ≥ 1 only for a stress falling inward)")


FKM_KEYWAY_NOTE = ("† a sharp-edged keyway (no bottom radius is modelled): its local stress "
                   "grows with mesh refinement (reports/benchmarks/keyway_edge.md), so the row "
                   "is a value of the mesh, not a converged assessment; --method din743 "
                   "assesses a keyway by its notch factor")


def fkm_notes(res, sharp: frozenset[str]) -> list[str]:
    """The lines under the FKM table: the sign convention, what a negative gradient does, and
    what a sharp-edged keyway's row is (``sharp``: as ``fkm_rows``)."""
    out = [FKM_SIGN_NOTE]
    if any(c is not None and c.G_per_mm < 0 for r in res.regions for c in (r.surface, r.core)):
        out.append(FKM_G_NOTE)
    if any(r.region in sharp for r in res.regions):
        out.append(FKM_KEYWAY_NOTE)
    return out


def din_rows(run) -> list[list]:
    rows = []
    for w in run.rows:
        r, f = w.result, w.result.factors["bending"]
        rows.append([r.notch.name, f"{w.x_mm:.2f}", r.notch.kind,
                     "-" if math.isnan(f["alpha"]) else f"{f['alpha']:.3f}",
                     "-" if math.isnan(f["n"]) else f"{f['n']:.3f}", f"{f['beta']:.3f}",
                     f"{f['K2']:.3f}", f"{f['K_F']:.3f}", f"{f['K_V']:g}", f"{f['K']:.3f}",
                     f"{r.K1_ultimate:.3f}", f"{f['WK']:.0f}", f"{f['psi']:.3f}",
                     f"{f['ADK']:.0f}", f"{f['FK']:.0f}", f"{w.stresses.b_a:.1f}",
                     f"{w.stresses.b_m:.1f}", _f(r.S_D), _f(r.S_F)])
    return rows


DIN_HEAD = ["notch", "x mm", "kind", "α_σ", "n", "β_σ", "K2", "K_Fσ", "K_V", "K_σ", "K1",
            "σ_bWK", "ψ", "σ_bADK", "σ_bFK", "σ_ba", "σ_bm", "S_D", "S_F"]


def fkm_summary(res, along=None) -> dict:
    """FKM's block of summary.json (``along``: ``fkm_field.FkmAlong`` with ``--plot``)."""
    reg, c = res.governing
    return {"method": "fkm", "card": res.card.name, "rule": res.rule, "j_D": res.j_D,
            "damage_sum": res.damage_sum, "design_life_blocks": res.design_life_blocks,
            "governing": {"region": reg.region, "layer": c.layer,
                          "safety": {k: _num(v) for k, v in c.safety.items()},
                          "utilisation": {k: _num(v) for k, v in c.utilisation.items()},
                          "life_blocks": {k: _num(v) for k, v in c.life_blocks.items()},
                          "life_hours": {k: _num(float(life_hours(v, res.block_seconds)))
                                         for k, v in c.life_blocks.items()},
                          # why a life prints as no finite life (util.fmt), or None
                          "life_reason": life_reason(c.life_blocks[res.rule],
                                                     float(life_hours(c.life_blocks[res.rule],
                                                                      res.block_seconds)))},
            "regions": [{"region": r.region, "node": r.node, "xyz_mm": list(r.xyz_mm),
                         "h_mm": r.profile.h_mm, "fit_rms": _num(r.profile.fit_residual),
                         **{c.layer: {k: (_num(v) if not isinstance(v, dict) else
                                          {a: _num(b) for a, b in v.items()})
                                      for k, v in vars(c).items() if k != "layer"}
                            for c in (r.surface, r.core) if c is not None}}
                        for r in res.regions],
            "no_load_cycles": no_load_cycles(res),
            "notes": list(res.notes) + ([NO_LOAD_CYCLES] if no_load_cycles(res) else []),
            **({"along": _fkm_along(along)} if along is not None else {})}


def _fkm_along(along) -> dict:
    u = np.asarray(along.utilisation, dtype=float)
    i = int(np.nanargmax(u)) if np.isfinite(u).any() else None
    return {"x_mm": [float(x) for x in along.x_mm],
            "utilisation": [_num(float(v)) for v in u],
            "safety": [_num(float(s)) for s in along.safety], "region": list(along.region),
            "governing": None if i is None else {
                "x_mm": float(along.x_mm[i]), "utilisation": _num(float(u[i])),
                "region": along.region[i]}}


def plot_fkm_along(summary: dict, variant, path) -> None:
    """FKM's degree of utilisation along the shaft (``summary``: the FKM summary with
    "along"), each region's governing node marked, the shaft's outline below."""
    x = np.asarray(summary["along"]["x_mm"], dtype=float)
    fp.plot_fkm_along(summary["along"], summary["regions"], summary["rule"],
                      shaft_diameters(variant, x), path,
                      title=f"FKM degree of utilisation along the shaft, card "
                      f"{summary['card']}, j_D {summary['j_D']:g}")


def shaft_diameters(variant, x) -> np.ndarray:
    """The shaft's outer diameter at each x (``Variant.segment_at``; a cone's linear)."""
    return np.array([variant.segment_at(float(xx)).diameter_at(float(xx)) for xx in x],
                    dtype=float)


def din_summary(run) -> dict:
    g = run.governing
    return {"method": "din743", "card": run.card.name, "S_min": din.S_MIN,
            "cycle_rpm": [run.rpm_min, run.rpm_max],
            "governing": {"notch": g.result.notch.name, "x_mm": g.x_mm,
                          "S_D": _num(g.result.S_D), "S_F": _num(g.result.S_F)},
            "notches": [{"name": w.result.notch.name, "x_mm": w.x_mm,
                         "kind": w.result.notch.kind, "alpha_source": w.result.notch.alpha_source,
                         "d_eff_K1_mm": din.heat_treatment_diameter(w.result.notch),
                         "d_K2_mm": w.result.notch.d_mm,
                         "S_D": _num(w.result.S_D), "S_F": _num(w.result.S_F),
                         "stresses_MPa": {k: _num(v) for k, v in vars(w.stresses).items()},
                         "factors": {ld: {k: _num(v) for k, v in f.items()}
                                     for ld, f in w.result.factors.items()}}
                        for w in run.rows],
            "notes": list(run.notes),
            **({"along": {"x_mm": [float(x) for x in run.along.x_mm],
                          "d_mm": [float(d) for d in run.along.d_mm],
                          "S_D": [_num(float(v)) for v in run.along.S_D],
                          "S_F": [_num(float(v)) for v in run.along.S_F],
                          "governing_unnotched": _along_min(run.along)}}
               if run.along is not None else {})}


def _along_min(along) -> dict:
    """The lowest safety of an unnotched section and where."""
    import numpy as np
    s = np.minimum(along.S_D, along.S_F)
    i = int(np.argmin(s))
    return {"x_mm": float(along.x_mm[i]), "S_D": _num(float(along.S_D[i])),
            "S_F": _num(float(along.S_F[i]))}


def elements_summary(bearings, keys, gear_chk, kappa: float, e_c: float, *,
                     seed: bool = True) -> dict:
    """The element checks' summary; ``seed``: with the seed's single-point bearing lives
    (only for the seed's shaft); ``gear_chk`` None: no gear pair (the block is None)."""
    seed_rows = []
    for s in SEED_POINTS if seed else ():
        C = s["C_N"] if s["C_N"] else next(b.C_N for b in bearings)
        seed_rows.append({**s, "C_N": C, "ours_L10h": l10h(C, s["P_N"], s["rpm"])})
    return {"bearings": {"kappa": kappa, "e_C": e_c,
                         "duty_cycle": [{k: _num(v) if isinstance(v, float) else v
                                         for k, v in vars(b).items()} for b in bearings],
                         "seed_points": seed_rows},
            "keys": [{k: _num(v) if isinstance(v, float) else v for k, v in vars(k_).items()}
                     for k_ in keys],
            "gear": {k: _num(v) for k, v in vars(gear_chk).items()}
            if gear_chk is not None else None}


def _h(v) -> str:
    """A bearing life in hours: '1 251 h', or no finite life above 1e9 h (util.fmt)."""
    return NO_FINITE_LIFE if life_reason(v) else f"{big(v)} h"


def elements_lines(el: dict, speed_kmh: float) -> list[str]:
    b = el["bearings"]
    out = [f"bearings, ISO 281 over the rpm history (κ {b['kappa']:g}, e_C {b['e_C']:g}, "
           "C_u = C0/22, loads ∝ rpm²):"]
    for d in b["duty_cycle"]:
        out.append(f"  {d['name']} {d['designation']}: P_eq {d['P_eq_N']:.0f} N at n_eq "
                   f"{d['n_eq_rpm']:.0f} rpm; L10h {_h(d['L10h'])}; L_nm "
                   f"{life_h_km(d['Lnm_h'], d['Lnm_km'], speed_kmh)}")
    for s in b["seed_points"]:
        out.append(f"  seed single point {s['bearing']} (C {s['C_N']:.0f} N, P {s['P_N']:.0f} "
                   f"N, {s['rpm']:.0f} rpm): L10h {s['ours_L10h']:.1f} h (seed {s['L10h']} h)")
    for k in el["keys"]:
        out.append(f"key {k['name']} (Ø{k['d_mm']:g}, M {k['torque_Nmm'] / 1e3:.3f} N·m): "
                   f"length needed {k['length_needed_seed_mm']:.3f} mm by the seed's formula "
                   f"(seed 0.126), {k['length_needed_mm']:.3f} mm at σ_d "
                   f"{k['sigma_d_MPa']:.0f} MPa; 5×5×8: p {k['pressure_MPa']:.2f} MPa, "
                   f"safety {k['safety']:.1f}")
    g = el["gear"]
    if g is None:
        return out
    out.append(f"gear pair (Merritt as Inventor, 9500 rpm, 1.5× torque {g['torque_Nmm'] / 1e3:.4f} "
               f"N·m): F_t {g['F_t_N']:.3f} N, F_r {g['F_r_N']:.3f} N, F_n {g['F_n_N']:.3f} N, "
               f"v {g['v_m_s']:.3f} m/s, safety {g['safety']:.2f} (seed 33.93)")
    return out


def compute_elements(variant, history, kappa: float, e_c: float, speed_kmh: float,
                     beam=None) -> dict:
    """Bearings over the duty cycle, the keys and the gear pair of ``variant`` (``beam``: the
    beam solution at ``util.units.REF_RPM`` when the caller has one). Each check runs only
    where its element is: the keys where a segment has a keyway, the gear pair where the
    variant has a part named "gear"; both need the drive's data, the element-check file its
    [duty] names (``elements``; none: no key or gear check). The seed's single-point bearing
    lives stand beside ours for the seed's shaft only."""
    elements = variant.duty.elements if variant.duty is not None else None
    seed = variant.name == SEED_VARIANT
    duty = bearings.duty(variant, history, kappa, e_c, speed_kmh=speed_kmh, beam=beam)
    if elements is None:
        return elements_summary(duty, [], None, kappa, e_c, seed=seed)
    doc = drive.load(elements)
    dr = drive.drive(doc)
    mp = mass_properties(variant)
    M_all = drive.torque_Nmm(mp.polar_inertia_kg_mm2 + dr.pump_inertia_kg_mm2, dr)
    cw2 = next((a for a in variant.attachments if a.name == "counterweight_2"), None)
    keys = []
    for s in variant.segments:
        if s.keyways:
            if s.name == "gear_seat" or cw2 is None:
                M = M_all
            else:
                M = drive.torque_Nmm(cw2.polar_inertia_kg_mm2
                                     + cw2.mass_kg * cw2.eccentricity_mm ** 2, dr)
            keys.append(key.check(s.name, M, s.diameter_mm, doc["keys"]))
    has_gear = any(a.name == "gear" for a in variant.attachments)
    g = gear.check(M_all, dr.max_rpm, doc["gear_pair"]) if has_gear else None
    return elements_summary(duty, keys, g, kappa, e_c, seed=seed)


FKM_FIELDS = ("fkm_utilisation", "fkm_safety", "von_mises_ref")


def write_fkm_files(res, ref, out) -> tuple[dict, dict]:
    """FKM's files into ``out``: fatigue.vtu (``FKM_FIELDS``: the degree of utilisation and the
    achieved safety under the governing rule, the worse layer, at every surface node it
    assessed, NaN elsewhere; docs/FIELDS.md) and, of the governing check, the Haigh diagram
    (F2) with its cycles, the rainflow matrix and the damage matrix. Returns (the summary's
    "vtu" block, plot name -> file)."""
    import numpy as np

    n = int(ref.n_nodes)
    util, safety = np.full(n, np.nan), np.full(n, np.nan)
    for node, u, s in res.assessed:
        util[node], safety[node] = u, s
    write_ref_vtu(ref, out / "fatigue.vtu", {"fkm_utilisation": util, "fkm_safety": safety,
                                             "von_mises_ref": ref.von_mises_ref})
    gc = governing_cycles(res)
    where = f"{gc['region']} ({gc['layer']}), x = {gc['x_mm']:.1f} mm"
    fp.plot_fkm_haigh(gc, out / "haigh.png",
                      title=f"FKM Haigh diagram (F2), governing spot\n{where}")
    cyc = Cycles(2.0 * gc["amplitude"], gc["mean"], gc["count"], res.cycles.closure)
    fp.plot_cycle_matrix(rainflow_matrix(cyc, units="MPa"), out / "rainflow_matrix.png",
                         title=f"rainflow matrix per block\n{where}")
    rule = res.rule if res.rule != "consistent" else "elementary"
    d = fkm.class_damage(gc["s"], gc["count"], rule)
    fp.plot_cycle_matrix(_matrix(cyc.range, cyc.mean, d / res.damage_sum, 10, "damage", "MPa"),
                         out / "damage_matrix.png",
                         title=f"FKM damage per block / D_M ({rule} Miner)\n{where}")
    vtu = {"file": "fatigue.vtu", "regions": list(ref.face_groups),
           "point_data": list(FKM_FIELDS), "von_mises_ref_rpm": ref.ref_rpm,
           "assessed_nodes": len(res.assessed),
           "note": f"fkm_utilisation and fkm_safety ({res.rule} Miner, the worse of surface "
                   "and core) at the surface nodes FKM assessed (each region's highest "
                   "tensile and compressive nodes outside the singular-point exclusion), NaN "
                   "elsewhere"}
    return vtu, {"haigh": "haigh.png", "rainflow_matrix": "rainflow_matrix.png",
                 "damage_matrix": "damage_matrix.png"}


def plot_din_along(summary: dict, path) -> None:
    """DIN 743's safety along the shaft (``summary``: ``din_summary`` with "along")."""
    fp.plot_din743_along(summary["along"], summary["notches"], summary["S_min"], path,
                         title=f"DIN 743 safety along the shaft, card {summary['card']}")


def write_din_files(summary: dict, out) -> dict:
    """DIN 743's plots into ``out``: S_D and S_F per notch against S_min; with the safety at
    every cross-section in the summary (``--plot``), the safety along the shaft too."""
    fp.plot_din743_safeties(summary["notches"], summary["S_min"], out / "din743_safety.png",
                            title=f"DIN 743 safeties per notch, card {summary['card']}")
    files = {"din743_safety": "din743_safety.png"}
    if summary.get("along"):
        plot_din_along(summary, out / "din743_along.png")
        files["din743_along"] = "din743_along.png"
    return files


def write_outputs(summary: dict, out) -> tuple[dict, list[str]]:
    """summary.json of ``shaftfe fatigue --method fkm | din743`` into the (staged) directory
    ``out``, the last file, with the run's warnings (``util.notices.collected``); ``summary``
    names the files written before it ("vtu", "plots"). Returns the summary written and the
    file names."""
    import json

    summary = {**summary, "warnings": collected()}
    summary = json_clean(summary)         # JSON has no inf: null with the reason beside
    write_atomic(out / "summary.json", json.dumps(summary, indent=1, allow_nan=False) + "\n")
    files = ([summary["vtu"]["file"]] if "vtu" in summary else []) + \
        list(summary["plots"].values()) + ["summary.json"]
    return summary, files
