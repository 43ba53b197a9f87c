"""The seed's figures next to ours (``comparisons``) and the error estimate of every number the
report states (``error_estimates``)."""

from __future__ import annotations

from shaftfe.report.options import OTHER_LEVEL
from shaftfe.report.results import Comparison, ErrorEstimate
from shaftfe.solid.features import ROUND_NOTCH_KINDS, kind_of
from shaftfe.static.measured_errors import MEASURED_FILLETS, bench_matches


def _richardson_rows(c0: dict, ee: dict) -> list[ErrorEstimate]:
    """From --estimate-error: this run against the extrapolation from two levels."""
    out = []
    how = (f"Richardson from this run and a second solve on the other level (levels "
           f"{ee['levels'][0]} / {ee['levels'][1]}, {ee['dofs'][0]} / {ee['dofs'][1]} dofs; "
           "--estimate-error); an estimate, not a bound")
    ec = ee["cases"][0]
    items = [(f"peak von Mises, {c0['rpm']:g} rpm", c0["peak_von_mises_MPa"], "MPa",
              ec["peak_von_mises"]),
             (f"max deflection, {c0['rpm']:g} rpm", c0["max_deflection_mm"], "mm",
              ec["max_deflection"])]
    mine = {p["region"]: p["von_mises_MPa"] for p in c0["peaks"]}
    items += [(f"{region} peak, {c0['rpm']:g} rpm", mine.get(region), "MPa", e)
              for region, e in sorted(ec["region_peaks"].items())
              if kind_of(region) in ROUND_NOTCH_KINDS]
    for label, val, unit, e in items:
        if e and val and e["extrapolated"]:
            rel = val / e["extrapolated"] - 1.0
            out.append(ErrorEstimate(
                label, val, unit,
                f"{100 * rel:+.2f} % against the extrapolated {e['extrapolated']:.5g} {unit}",
                how))
    return out


def _benchmark_rows(report_static: dict, c0: dict, bench: dict | None) -> list[ErrorEstimate]:
    """From the static benchmark's measured error of this level (or why there is none)."""
    out = []
    if bench and not bench_matches(bench, report_static["n_dofs"]):
        out.append(ErrorEstimate(
            "peak von Mises", c0["peak_von_mises_MPa"], "MPa", "not estimated in this run",
            f"the benchmark ({bench['source']}) was run on a {bench['level']} mesh of "
            f"{bench.get('dofs')} dofs, this run has {report_static['n_dofs']}: the mesh levels "
            "changed since (re-run `make bench`); `shaftfe report --model solid "
            "--estimate-error` adds a Richardson estimate from a second solve on the "
            f"{OTHER_LEVEL[report_static['level']]} level"))
    elif bench:
        mesh_note = (f"; benchmark mesh {bench.get('dofs')} dofs, this run "
                     f"{report_static['n_dofs']}")
        for key, label in (("collar", "collar fillet peak"),
                           ("bsg", "bearing-seat-gear fillet peak")):
            region = MEASURED_FILLETS[key]
            pk = next((p for p in c0["peaks"] if p["region"] == region), None)
            val = pk["von_mises_MPa"] if pk else None
            rel = bench[key]["rel_error"]
            extra = (f"; corrected ≈ {val / (1 + rel):.4g} MPa" if val else "")
            out.append(ErrorEstimate(
                f"{label}, {c0['rpm']:g} rpm", val, "MPa",
                f"{100 * rel:+.1f} % (reads low){extra}",
                f"benchmark ({bench['source']}, level {bench['level']} P2 against the "
                "axisymmetric truth converged by Richardson; all-parts load case; no second "
                f"solve in this run{mesh_note})"))
        if "defl" in bench:
            rel = bench["defl"]["rel_error"]
            out.append(ErrorEstimate(
                f"max deflection, {c0['rpm']:g} rpm", c0["max_deflection_mm"], "mm",
                f"{100 * rel:+.2f} %", f"benchmark ({bench['defl']['source']}: against the "
                "Richardson extrapolation of default and fine)"))
    else:
        out.append(ErrorEstimate("peak von Mises", c0["peak_von_mises_MPa"], "MPa",
                                 "not estimated in this run",
                                 "no measured error for this shaft (the level's fillet errors "
                                 "were measured on x2_57 as shipped, "
                                 "reports/benchmarks/truth.md); `shaftfe report "
                                 "--model solid --estimate-error` adds a Richardson "
                                 "estimate from a second mesh level"))
    return out


def _check_rows(report_static: dict, c0: dict, ff_out: dict, scaled: dict | None,
                camp: dict, seed: bool = True) -> list[ErrorEstimate]:
    """Reactions against the beam, the linear solve, the corrected life, the reduced basis."""
    import math as _m
    out = []
    b = {x["name"]: x["F_radial_N"] for x in c0["bearings"]}
    bb = {x["name"]: x["F_N"] for x in c0["beam_springs"].get("bearings", [])}
    if bb:
        d = max(abs(b[k] / bb[k] - 1) for k in b if bb.get(k))
        out.append(ErrorEstimate(
            f"bearing reactions, {c0['rpm']:g} rpm", max(b.values()), "N",
            f"{100 * d:.2g} % from the beam model; equilibrium residual "
            f"{c0['equilibrium_residual']:.1e}",
            "two supports with free tilt: the reactions are statically determinate, so 3D FE "
            "and beam must agree"))
    out.append(ErrorEstimate("linear solve", None, "-",
                             f"relative residual {report_static['relative_residual']:.1e}",
                             f"{report_static['solver']}; the run fails above "
                             + ("1e-9" if report_static.get("model") in ("axisymmetric",
                                                                          "zoned")
                                else "1e-8")))
    hs = ff_out["hot_spot"]
    if scaled is not None and hs["life_blocks"] is not None:
        lb = scaled["life_blocks"]
        out.append(ErrorEstimate(
            "fatigue life at the hot spot", hs["life_blocks"], "blocks",
            f"≈ {f'{lb:,.0f}'.replace(',', ' ')} blocks "
            f"({100 * (lb / hs['life_blocks'] - 1):+.0f} %), safety factor "
            f"{scaled['safety_factor']:.3f}, if the hot-spot stress is corrected by "
            f"×{scaled['factor']:.4f}"
            if _m.isfinite(lb) and hs["life_blocks"] > 0
            else ("infinite after correction" if not _m.isfinite(lb)
                  else "0 blocks: fails in the first block, corrected or not"),
            "the same S-N evaluation at the hot spot with the stress corrected by the estimated "
            "error of the peak above (life ∝ σ^-k: a few % of stress is tens of % of life)"))
    out.append(ErrorEstimate(
        "natural frequencies (reduced basis)", camp["table"][0]["f0_hz"], "Hz",
        f"{camp['verify']['max_rel_diff']:.1e} vs the full-size problem at "
        f"{camp['verify']['rpm']:g} rpm; basis change {camp['basis_change']:.1e}",
        f"{camp['description']}"
        + ("; model error vs the seed's 3D Ansys model is not covered (see the comparison)"
           if seed else "")))
    return out


# where the surface models' peak errors were measured (no bar is printed from them in a run)
_PEAK_ERRORS_MEASURED = {
    "axisymmetric": "axisymmetric model: each level's error against its Richardson-converged "
                    "value (three uniform refinements) and its cross-check with the 3D model "
                    "are in reports/benchmarks/axisymmetric.md (`make bench`)",
    "zoned": "zoned model: every peak against the full 3D model at default and fine, and the "
             "cut checks, in reports/benchmarks/zoned.md (`make bench`); no bar is printed "
             "(the 3D levels' bars were measured on whole-shaft meshes)"}


def error_estimates(report_static: dict, res, ff_out: dict, scaled: dict | None,
                    bench: dict | None, camp: dict, beam_check: dict, *,
                    seed: bool = True) -> list[ErrorEstimate]:
    """How far each stated number may be from the truth, and how that is known (``seed``:
    the variant the seed's studies were of, whose rotor model the comparison judges)."""
    c0 = report_static["cases"][0]
    ee = getattr(res, "error_estimate", None)
    where = _PEAK_ERRORS_MEASURED.get(report_static.get("model"))
    if where:
        head = [ErrorEstimate("peak von Mises", c0["peak_von_mises_MPa"], "MPa",
                              "not estimated in this run", where)]
    else:
        head = _richardson_rows(c0, ee) if ee else _benchmark_rows(report_static, c0, bench)
    return head + _check_rows(report_static, c0, ff_out, scaled, camp, seed)


def _balancing_rows(bal: dict, B: dict) -> list[Comparison]:
    """Seed 000 §5.4 and appendix 1."""
    rows: list[Comparison] = []
    add = rows.append
    m2 = bal["seed_row"]["minima"]
    grp = "balancing"
    model = (f"{bal['engine']}, X = {bal['seed_row']['X_percent']:g} %, "
             f"{bal['seed_row']['rpm']:g} rpm, cylinder frame, 3600 angles/rev")
    add(Comparison(grp, "min over X2 of max|F|", "N", B["min_max_f_N"],
                   m2["max_f"]["value_N"], model))
    add(Comparison(grp, "X2 at min max|F|", "%", B["min_max_f_at_X2_percent"],
                   m2["max_f"]["at_X2_percent"], model + ", 1 % grid"))
    add(Comparison(grp, "min over X2 of RMS|F|", "N", B["min_rms_f_N"],
                   m2["rms_f"]["value_N"], model,
                   "exact period RMS; the seed counted TDC twice (+0.26 %)"))
    add(Comparison(grp, "X2 at min RMS|F|", "%", B["min_rms_f_at_X2_percent"],
                   m2["rms_f"]["at_X2_percent"], model))
    add(Comparison(grp, "min over X2 of max|Fy|", "N", B["min_max_fy_N"],
                   m2["max_abs_fy"]["value_N"], model))
    if bal["balancer_force_A1_N"] is not None:
        add(Comparison(grp, "balancer force of shaft A.1, 6000 rpm", "N",
                       B["balancer_force_A1_N"], bal["balancer_force_A1_N"],
                       "m_vh γ2 ω² from the engine file"))
    return rows


def _variant_rows(bal: dict, variant) -> list[Comparison]:
    """Seed 000 §8.2.2 table, from the variant file's seed-tagged balance table."""
    rows: list[Comparison] = []
    add = rows.append
    tgt = variant.balance_target
    mp = bal["mass_properties"]
    if tgt is not None:
        grp = f"variant {variant.name}"
        mdl = "shaft body + every part of the variant files"
        add(Comparison(grp, "whole balancer mass", "kg", tgt.mass_kg, mp["mass_kg"], mdl))
        add(Comparison(grp, "eccentricity γ2", "mm", tgt.gamma2_mm, mp["gamma2_mm"], mdl))
        add(Comparison(grp, "axial centroid x_T", "mm", tgt.x_T_mm, mp["x_T_mm"], mdl))
        add(Comparison(grp, "balance ratio X2", "%", tgt.X2_percent, bal["X2_percent"],
                       "m γ2 / (m_pos R)"))
    return rows


def _load_rows(variant, S: dict, parts: tuple[str, str, str]) -> list[Comparison]:
    """The seed's part forces (seed 000 §8.2.2), where the variant has the seed's parts."""
    rows: list[Comparison] = []
    add = rows.append
    grp = "loads"
    att = {a.name: a for a in variant.attachments}
    if set(parts) <= att.keys():
        g, c1, c2 = (att[n] for n in parts)
        mdl = "m e ω² of the seed's masses and eccentricities"
        add(Comparison(grp, "gear, 10 000 rpm", "N", S["force_gear_10000_N"],
                       g.force_N(10_000), mdl))
        add(Comparison(grp, "counterweight 1, 10 000 rpm", "N", S["force_cw1_10000_N"],
                       c1.force_N(10_000), mdl))
        add(Comparison(grp, "counterweight 2, 10 000 rpm", "N", S["force_cw2_10000_N"],
                       c2.force_N(10_000), mdl))
        add(Comparison(grp, "F1 = gear + counterweight 1, 7000 rpm", "N", S["force_F1_7000_N"],
                       g.force_N(7_000) + c1.force_N(7_000), mdl))
        add(Comparison(grp, "Fv2 = counterweight 2, 7000 rpm", "N", S["force_cw2_7000_N"],
                       c2.force_N(7_000), mdl))
    return rows


def _static_rows(st: dict, beam_check: dict, variant, S: dict) -> list[Comparison]:
    """Reactions, deflections, peak stress and L10h (seed 000 §8.2.2, Inventor / Ansys)."""
    rows: list[Comparison] = []
    add = rows.append
    grp = "static"
    cases = {c["rpm"]: c for c in st["cases"]}
    fe = f"{st['model_label']}, {st['supports']}, {st['load_case']}"
    names = [b.name for b in variant.bearings]
    for rpm in (10_000.0, 7_000.0):
        c = cases.get(rpm)
        if c is None:
            continue
        reac = {b["name"]: b["F_radial_N"] for b in c["bearings"]}
        for side in names:
            key = f"reaction_{side}_{rpm:.0f}_N"
            if key in S:
                speed = f"{rpm:,.0f}".replace(",", " ")
                add(Comparison(grp, f"reaction {side.replace('_', ' ')}, {speed} rpm",
                               "N", S[key], reac.get(side), fe,
                               "statically determinate: springs or rigid give the same"))
    c10 = cases.get(10_000.0)
    eb = {r["rpm"]: r for r in beam_check["euler_bernoulli"]}.get(10_000.0)
    ti = {r["rpm"]: r for r in beam_check["timoshenko"]}.get(10_000.0)
    if c10 is not None:
        rel = c10["relative_deflection_mm"]
        if "gear" in rel:
            add(Comparison(grp, "deflection under the gear, 10 000 rpm", "mm",
                           S["deflection_gear_10000_mm"], rel["gear"], fe,
                           "relative to the line through the bearing centres (the shaft's own "
                           "bending, = rigid supports)"))
        if eb is not None and "gear" in eb["stations"]:
            add(Comparison(grp, "deflection under the gear, 10 000 rpm", "mm",
                           S["deflection_gear_10000_mm"], eb["stations"]["gear"],
                           "beam, Euler-Bernoulli, rigid supports (as Inventor)"))
        if "clearance" in rel:
            add(Comparison(grp, "deflection at the closest clearance, 10 000 rpm", "mm",
                           S["deflection_clearance_10000_mm"], rel["clearance"], fe,
                           "relative to the bearing line"))
        add(Comparison(grp, "max reduced (von Mises) stress, 10 000 rpm", "MPa",
                       S["max_reduced_stress_10000_MPa"], c10["peak_von_mises_MPa"], fe,
                       f"peak with the notch effect ({c10['peak_region']}); singular points "
                       "excluded"))
        if ti is not None:
            add(Comparison(grp, "max reduced (von Mises) stress, 10 000 rpm", "MPa",
                           S["max_reduced_stress_10000_MPa"], ti["max_sigma_vm_nominal_MPa"],
                           "beam, nominal (no notch), rigid supports",
                           f"at x = {ti['x_max_sigma_vm_mm']:.1f} mm"))
    c7 = cases.get(7_000.0)
    if c7 is not None:
        worst = max(c7["bearings"], key=lambda b: b["F_radial_N"])
        add(Comparison(grp, f"L10h {worst['name'].replace('_', ' ')} bearing (3203), 7000 rpm",
                       "h", S["L10h_3203_7000_h"], worst["L10h"], fe + ", ISO 281 p = 3",
                       f"C = {worst['C_N']:.0f} N derived from this seed figure"))
    return rows


def _fatigue_rows(fat: dict, F: dict) -> list[Comparison]:
    """Safety factor, life and hot spot (seed 000 §8.3, Ansys Fatigue Tool)."""
    rows: list[Comparison] = []
    add = rows.append
    grp = "fatigue"
    hs = fat["hot_spot"]
    mdl = (f"{fat['settings']['mean_stress']}, {fat['settings']['material']}, "
           f"same static solution, {fat['history']['source']}")
    life = f"{fat['settings']['design_life_blocks']:,.0f}".replace(",", " ")
    add(Comparison(grp, f"safety factor at {life} blocks",
                   "-", F["safety_factor_at_1e7"], hs["safety_factor"], mdl))
    add(Comparison(grp, "life", "blocks", F["life_blocks"], hs["life_blocks"], mdl))
    add(Comparison(grp, "life", "h", F["life_hours"], hs["life_hours"], mdl))
    add(Comparison(grp, f"life at {fat['settings']['speed_kmh']:g} km/h", "km", F["life_km"],
                   hs["life_km"], mdl))
    add(Comparison(grp, "hot spot position x", "mm", F["hot_spot_x_mm"], hs["xyz_mm"][0],
                   f"{hs['region']} (seed: {F['hot_spot']})"))
    return rows


def _campbell_rows(camp: dict, C: dict) -> list[Comparison]:
    """Natural frequencies at rest and the count of critical speeds (seed 000 §8.4)."""
    rows: list[Comparison] = []
    add = rows.append
    grp = "rotor dynamics"
    f0 = [t["f0_hz"] for t in camp["table"]]
    for k, fs in enumerate(C["freq_0rpm_hz"]):
        if k < len(f0):
            add(Comparison(grp, f"mode {k + 1} at 0 rpm (branch: {camp['table'][k]['whirl']})",
                           "Hz", fs, f0[k], camp["description"],
                           "paired by order: the seed's mode shapes are not known"
                           if k == 0 else ""))
    lo, hi = C["rpm_range"]
    n_crit = sum(1 for c in camp["criticals"] if lo <= c["rpm"] <= hi and c["order"] == 1)
    add(Comparison(grp, f"critical speeds (1×) in {lo:g}-{hi:g} rpm", "count",
                   float(C["n_critical"]), float(n_crit), camp["description"],
                   "counted in the seed's range; the sweep goes to the engine's maximum"))
    return rows


def comparisons(bal: dict | None, beam_check: dict, st: dict, fat: dict, camp: dict, variant,
                seedmod, *, seed_engine: bool = True) -> list[Comparison]:
    """Every seed figure next to ours: the balancing on the seed's engine
    (``seed_engine``); the variant's balance table where its file tags it seed; the loads,
    static, fatigue and rotor rows only for the variant the seed's FE studies were of
    (``seedmod.VARIANT``). A shaft that is not the seed's gets none."""
    rows = _balancing_rows(bal, seedmod.BALANCING) if bal and seed_engine else []
    if bal and variant.provenance.source.get("balance.X2_percent") == "seed":
        rows += _variant_rows(bal, variant)
    if variant.name != seedmod.VARIANT:
        return rows
    return (rows + _load_rows(variant, seedmod.STATIC, seedmod.SEED_PARTS)
            + _static_rows(st, beam_check, variant, seedmod.STATIC)
            + _fatigue_rows(fat, seedmod.FATIGUE) + _campbell_rows(camp, seedmod.CAMPBELL))
