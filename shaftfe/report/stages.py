"""The report's stages: each computes one analysis of the variant through the package's API and
returns its summary (a JSON-ready dict) with the objects the later stages need."""

from __future__ import annotations

import math

from shaftfe.balance import single, sweep
from shaftfe.balance.engines import load_engine
from shaftfe.beam.elements import NDOF, RX, RY, RZ, UX, UY, UZ
from shaftfe.beam.model import build_model
from shaftfe.beam.solve import solve
from shaftfe.errors import InputError
from shaftfe.fatigue.methods import AssessmentInputs, get_method
from shaftfe.fatigue.run import FatigueJob, check_history, read_spectrum
from shaftfe.fatigue.sn import load_material
from shaftfe.io.vtu import bearing_line
from shaftfe.model.mass import mass_properties, variant_x2
from shaftfe.report.options import ReportOptions
from shaftfe.rotordynamics.analyse import analyse
from shaftfe.rotordynamics.options import RotorOptions
from shaftfe.solid.features import kind_of
from shaftfe.solid.plan import refuse_sharp_corners
from shaftfe.util.paths import repo_relative
from shaftfe.util.units import omega
from shaftfe.zoned.submodel import cut_error


def read_inputs(o: ReportOptions, variant) -> tuple:
    """The engine (None: the variant states none and --engine is not given: no balancing),
    the rpm history (bounded by the engine's max_rpm, else the variant's [duty] speed range)
    and the seed method's S-N card of the options ``o`` (``options.with_duty``)."""
    refuse_sharp_corners(variant, "the report's fatigue check")     # before any solve
    engine = load_engine(o.engine) if o.engine else None
    history = read_spectrum(o.spectrum, None, None)
    # at rest, or above the engine's max_rpm (the variant's highest speed without an engine)
    check_history(history, o.engine or variant.duty, o.allow_overspeed)
    material = load_material(o.material)
    return engine, history, material


def file_comments(path, limit: int = 20) -> list[str]:
    """The leading '#' comment lines of a text file that are not ``key = value`` header keys:
    what an rpm history says about its own provenance."""
    out = []
    try:
        with open(path, encoding="utf-8", errors="replace") as fh:
            for line in fh:
                t = line.strip()
                if not t.startswith("#"):
                    break
                t = t.lstrip("#").strip()
                if t and not (" = " in t and t.split(" = ", 1)[0].isidentifier()):
                    out.append(t)
                if len(out) >= limit:
                    break
    except OSError:
        return []
    return out


def provenance_summary(variant) -> dict:
    """Counts of the provenance tags and the list of reconstructed values."""
    counts: dict[str, int] = {}
    recon = []
    for path, tag in sorted(variant.provenance.source.items()):
        counts[tag] = counts.get(tag, 0) + 1
        if tag == "reconstructed":
            recon.append(path)
    # the seed's shaft: its geometry tagged seed (the drawings' dimensions, RECONSTRUCTION.md)
    seed_geometry = any(tag == "seed" and path.startswith("segments.")
                        for path, tag in variant.provenance.source.items())
    return {"counts": counts, "reconstructed": recon, "seed_geometry": seed_geometry,
            "document": "geometry/RECONSTRUCTION.md",
            "files": list(variant.source_files)}


def is_seed_engine(engine, seedmod) -> bool:
    """The engine the seed's balancing figures are of (seed 000 ch. 5 and 8: the VM 450)."""
    return engine is not None and engine.name == seedmod.ENGINE


def balancing(engine, variant, seedmod) -> tuple[dict, object, object, object]:
    """The engine's shaking forces with the variant's X2 and the sweep over X2; the crank's X
    is the seed's crank C (31.1 %) on the seed's engine, else the engine file's own; the seed's
    §5.4 row only on the seed's engine (``seed_row`` None otherwise)."""
    import numpy as np


    mp = mass_properties(variant)
    x2 = variant_x2(variant, mp, default=engine.X2 if engine.X2 is not None else 0.0)
    seed = is_seed_engine(engine, seedmod)
    X = seedmod.CRANK_C_X if seed else engine.X
    if X is None:
        raise InputError(engine.source, "compensation_mass_kg",
                         "the crank's balance (compensation_mass_kg, compensation_radius_mm or "
                         "X) for the balancing section", reason="is missing")
    res = single.forces(engine, X=X, X2=x2, rpm=engine.rpm)
    sw = sweep.sweep(engine, [X], np.arange(0.0, 1.0001, 0.01), rpm=engine.rpm,
                     tilt_deg=0.0)            # cylinder frame, as the seed's fig. 58
    mins = {k: (float(v[0][0]), 100.0 * float(v[1][0])) for k, v in sw.minima().items()}
    out = {
        "engine": engine.name, "engine_file": repo_relative(engine.source), "rpm": engine.rpm,
        "tilt_deg": engine.tilt_deg, "idle_rpm": engine.idle_rpm, "max_rpm": engine.max_rpm,
        "m_pos_kg": engine.m_pos_kg, "m_rot_kg": engine.m_rot_kg,
        "crank_radius_mm": engine.crank_radius_mm, "rod_length_mm": engine.rod_length_mm,
        "X_percent": 100 * X, "X2_percent": 100 * x2,
        "first_order_amplitude_N": res.first_order_amplitude,
        "metrics": res.metrics.as_dict(),
        "sweep_minima": {k: {"value_N": v[0], "at_X2_percent": v[1]} for k, v in mins.items()},
        "seed_row": None, "balancer_force_A1_N": None,
        "mass_properties": {"mass_kg": mp.mass_kg, "gamma2_mm": mp.gamma2_mm,
                            "x_T_mm": mp.x_T_mm,
                            "polar_inertia_kg_mm2": mp.polar_inertia_kg_mm2},
    }
    if not seed:
        return out, res, sw, None
    sb = seedmod.BALANCING
    sw2 = sweep.sweep(engine, [sb["X"]], np.arange(0.0, 1.0001, 0.01), rpm=sb["rpm"],
                      tilt_deg=0.0)
    mins2 = {k: (float(v[0][0]), 100.0 * float(v[1][0])) for k, v in sw2.minima().items()}
    w = omega(sb["rpm"])
    bal_force = engine.balancer_mass_kg * engine.balancer_radius_mm * 1e-3 * w ** 2 \
        if engine.balancer_mass_kg and engine.balancer_radius_mm else None
    out["seed_row"] = {"X_percent": 100 * sb["X"], "rpm": sb["rpm"], "tilt_deg": 0.0,
                       "minima": {k: {"value_N": v[0], "at_X2_percent": v[1]}
                                  for k, v in mins2.items()}}
    out["balancer_force_A1_N"] = bal_force
    return out, res, sw, mins2


def beam_check(variant, rpms) -> tuple[dict, object]:
    """Inventor-style beam (rigid supports, seed load case) at the design speeds ``rpms``."""

    v = variant.with_seed_load_case()
    rpms = [float(r) for r in rpms]
    timo = solve(build_model(v, rigid_supports=True, seed_placement=True), rpms)
    eb = solve(build_model(v, rigid_supports=True, shear_deformation=False,
                           seed_placement=True), rpms)
    out = {}
    for label, res in (("timoshenko", timo), ("euler_bernoulli", eb)):
        out[label] = [{"rpm": r.rpm,
                       "bearings": {b.name: {"F_N": b.F_N, "L10h": b.L10h} for b in r.bearings},
                       "stations": {k: s.u_mm for k, s in r.stations.items()},
                       "max_sigma_vm_nominal_MPa": r.max_sigma_vm_MPa,
                       "x_max_sigma_vm_mm": r.x_max_sigma_vm_mm,
                       "max_peak_with_kt_MPa": r.max_peak_MPa,
                       "x_max_peak_mm": r.x_max_peak_mm} for r in res]
    return out, timo


def _relative_deflection(case, x_mm: float) -> float:
    """|u| of the axis at ``x_mm`` relative to the straight line through the two bearings'
    remote points (the shaft's own bending; equals the rigid-support deflection for two
    supports with free tilt, where the reactions are statically determinate)."""
    st = min(case.stations, key=lambda s: abs(s.x_mm - x_mm))
    line = bearing_line(case, st.x_mm)
    if line is None:
        return st.u_mm
    return math.hypot(st.uy_mm - float(line[0]), st.uz_mm - float(line[1]))


def _relative_deflections(case, variant) -> dict:
    """Under the gear and at the closest clearance, relative to the bearing line."""
    rel = {}
    gear_x = next((a.seat_center_mm for a in variant.attachments if a.name == "gear"), None)
    if gear_x is not None:
        rel["gear"] = _relative_deflection(case, gear_x)
    if variant.clearance_station_x_mm is not None:
        rel["clearance"] = _relative_deflection(case, variant.clearance_station_x_mm)
    return rel


def _case_common(c, variant) -> dict:
    """The keys of a speed's static summary that every model has."""
    from dataclasses import asdict
    return {"rpm": c.rpm, "bearings": [asdict(b) for b in c.bearings],
            "stations": [asdict(s) for s in c.stations],
            "relative_deflection_mm": _relative_deflections(c, variant),
            "equilibrium_residual": c.equilibrium_residual, "load_sum_N": c.load_sum_N}


def static_summary(res, variant) -> dict:
    from dataclasses import asdict
    cases = []
    for c in res.cases:
        cases.append({
            **_case_common(c, variant),
            "max_deflection_mm": c.max_deflection_mm,
            "max_deflection_xyz_mm": c.max_deflection_xyz_mm,
            "peaks": [asdict(p) for p in c.peaks],
            "peak_von_mises_MPa": c.peak_von_mises_MPa,
            "peak_von_mises_xyz_mm": c.peak_von_mises_xyz_mm,
            "peak_region": _region_of_peak(c),
            "peak_von_mises_unfiltered_MPa": c.peak_von_mises_unfiltered_MPa,
            "peak_von_mises_unfiltered_xyz_mm": c.peak_von_mises_unfiltered_xyz_mm,
            "beam_springs": {k: v for k, v in (c.beam or {}).items()
                             if k not in ("x_line_mm", "u_line_mm", "uy_line_mm",
                                                  "uz_line_mm")},
        })
    d = res.diagnostics
    return {"model": "solid",
            "model_label": f"3D FE P{res.options.order} {res.options.level}",
            "level": res.options.level, "order": res.options.order,
            "supports": "rigid" if res.options.rigid_supports else "bearing springs (2×2)",
            "load_case": res.options.load_case,
            "ref_rpm": res.ref_rpm, "n_nodes": res.n_nodes, "n_elements": res.n_elements,
            "n_dofs": res.n_dofs, "mesh_key": res.mesh_key, "variant_hash": res.variant_hash,
            "solver": d.get("solver"), "relative_residual": d.get("relative_residual"),
            "cond_S": d.get("cond_S"), "min_quality": d.get("min_quality"),
            "mesh_from_cache": getattr(res, "run", {}).get("mesh_from_cache"),
            "n_excluded_nodes": d.get("n_excluded_nodes"),
            "truth_error_bar_pct": res.truth_error_bar_pct,
            "truth_bar_notes": res.truth_bar_notes,
            "cases": cases, "error_estimate": res.error_estimate, "notes": list(res.notes)}


def static_summary_axisymmetric(res, variant) -> dict:
    """``static_summary`` of an ``AxiResult`` (``shaftfe.axisymmetric.solve``): the same keys;
    peaks are the located surface peaks (no unfiltered value: the singular points are left out
    by construction), the whole shaft's peak is the largest of them."""
    from dataclasses import asdict

    import numpy as np
    cases = []
    i_max = int(np.nanargmax(np.hypot(res.axis_u_ref[:, 1], res.axis_u_ref[:, 2])))
    for c in res.cases:
        peaks = [{**asdict(p), "von_mises_unfiltered_MPa": None} for p in c.peaks]
        best = max((p for p in c.peaks if kind_of(p.region) != "end"),
                   key=lambda p: p.von_mises_MPa)
        cases.append({
            **_case_common(c, variant),
            "max_deflection_mm": c.max_axis_deflection_mm,
            "max_deflection_xyz_mm": (float(res.axis_x[i_max]), 0.0, 0.0),
            "peaks": peaks,
            "peak_von_mises_MPa": best.von_mises_MPa,
            "peak_von_mises_xyz_mm": best.xyz_mm,
            "peak_region": best.region,
            "peak_von_mises_unfiltered_MPa": None,
            "peak_von_mises_unfiltered_xyz_mm": None,
            "beam_springs": {},
        })
    o = res.options
    level = o.level_name
    return {"model": "axisymmetric",
            "model_label": f"axisymmetric FE (P2, harmonics n ≤ {res.harmonics[-1]}) {level}",
            "level": level, "order": 2,
            "supports": "rigid" if o.rigid_supports else "bearing springs (2×2)",
            "load_case": o.load_case, "ref_rpm": res.ref_rpm, "n_nodes": res.n_nodes,
            "n_elements": res.n_elements, "n_dofs": 3 * res.n_nodes * len(res.harmonics),
            "harmonics": list(res.harmonics), "mesh_key": None,
            "variant_hash": res.variant_hash,
            "solver": f"SuperLU, one factorisation per harmonic ({len(res.harmonics)})",
            "relative_residual": res.run.get("relative_residual"), "cond_S": None,
            "min_quality": None, "mesh_from_cache": res.run.get("mesh_from_cache"),
            "n_excluded_nodes": sum(p.n_excluded for p in res.cases[0].peaks),
            "omitted_features": list(res.omitted),
            "truth_error_bar_pct": res.truth_error_bar_pct,
            "truth_bar_notes": res.truth_bar_notes,
            "cases": cases, "error_estimate": None, "notes": list(res.notes)}


def static_summary_zoned(res, variant) -> dict:
    """``static_summary`` of a ``ZonedResult`` (``shaftfe.zoned.solve``): the same keys; the
    reactions and deflections are the global axisymmetric model's, each peak comes from the
    model named in ``peaks[].model`` (the global model or a 3D zone), the whole shaft's peak is
    the largest of them; ``zones`` lists the 3D submodels with their cut checks."""
    from dataclasses import asdict

    g = res.global_result
    axi = static_summary_axisymmetric(g, variant)
    by_rpm = {c["rpm"]: c for c in axi["cases"]}
    cases = []
    for c in res.cases:
        peaks = [{**asdict(p), "von_mises_unfiltered_MPa": None} for p in c.peaks]
        best = max((p for p in c.peaks if kind_of(p.region) != "end"),
                   key=lambda p: p.von_mises_MPa)
        a = by_rpm.get(c.rpm, axi["cases"][0])     # the global solve of the first speed
        cases.append({
            **_case_common(c, variant),
            "max_deflection_mm": c.max_axis_deflection_mm,
            "max_deflection_xyz_mm": a["max_deflection_xyz_mm"],
            "peaks": peaks,
            "peak_von_mises_MPa": best.von_mises_MPa,
            "peak_von_mises_xyz_mm": best.xyz_mm,
            "peak_region": best.region,
            "peak_model": best.model,
            "peak_von_mises_unfiltered_MPa": None,
            "peak_von_mises_unfiltered_xyz_mm": None,
            "beam_springs": {},
        })
    zones = [{"name": z.name, "features": list(z.features), "x_mm": list(z.x_mm),
              "cuts_mm": list(z.cuts_mm), "grown": z.grown, "n_dofs": z.n_dofs,
              "n_elements": z.n_elements,
              "cut_check_percent": 100 * cut_error(z.cut_checks)}
             for z in res.zones]
    dofs = sum(z["n_dofs"] for z in zones)
    return {**axi, "model": "zoned",
            "model_label": f"zoned: axisymmetric global ({axi['level']}) + "
                           f"{len(zones)} 3D P2 zones ({res.options.level})",
            "level": getattr(res.options.level, "name", res.options.level),
            "global_level": axi["level"], "zones": zones, "zone_dofs": dofs,
            "n_dofs": axi["n_dofs"] + dofs,
            "solver": f"{axi['solver']}; PARDISO per zone",
            "truth_error_bar_pct": res.truth_error_bar_pct,
            "truth_bar_notes": res.truth_bar_notes,
            "mesh_from_cache": None, "cases": cases, "notes": list(res.notes)}


def _region_of_peak(c) -> str:
    best = max((p for p in c.peaks if math.isfinite(p.von_mises_MPa)),
               key=lambda p: p.von_mises_MPa, default=None)
    return best.region if best is not None and math.isclose(
        best.von_mises_MPa, c.peak_von_mises_MPa, rel_tol=1e-9) else "-"


def fatigue_job(o: ReportOptions):
    """The report's fatigue settings as the options of every fatigue method (the seed's von
    Mises, kf 1; the standards' defaults)."""
    return FatigueJob(spectrum=str(o.spectrum), variant=o.variant, mean_stress=o.mean_stress,
                      material=o.material, design_life=o.design_life_blocks,
                      speed_kmh=o.speed_kmh, level=o.level, cache_dir=o.cache_dir,
                      model=o.model, seed_load_case=o.seed_load_case,
                      spin_softening=o.spin_softening, overrides=o.overrides,
                      engine=o.engine, allow_overspeed=o.allow_overspeed)


def fatigue(ref, history, material, o: ReportOptions, variant=None) -> tuple[dict, object]:
    """The seed method (by name from ``fatigue.methods``) on the report's static field."""
    got = get_method("seed").assess(AssessmentInputs.one_channel(variant, history, field=ref),
                                    fatigue_job(o))
    ff = got.detail.field
    r = ff.result
    lf = ff.history.load_factor
    hot, raw = ff.hot_spot, ff.hot_spot_unfiltered
    out = {
        "history": {"source": repo_relative(history.source), "format": history.format,
                    "samples": history.n_samples, "duration_s": history.duration_s,
                    "rpm_min": float(history.rpm.min()), "rpm_max": float(history.rpm.max()),
                    "rpm_ref_of_file": history.rpm_ref, "static_ref_rpm": ff.ref_rpm,
                    "load_factor_min": float(lf.min()), "load_factor_max": float(lf.max())},
        "settings": {"equivalent": "von_mises", "mean_stress": o.mean_stress,
                     "material": material.name, "design_life_blocks": o.design_life_blocks,
                     "speed_kmh": o.speed_kmh, "kf": 1.0,
                     "yield_MPa": material.yield_MPa, "ultimate_MPa": material.ultimate_MPa,
                     "endurance_MPa": material.sn.endurance_MPa},
        "cycles_per_block": r.cycles.total_count, "cycle_classes": r.cycles.n,
        "closure": r.cycles.closure,
        "hot_spot": hot.to_dict(), "hot_spot_unfiltered": raw.to_dict(),
        "regions": [h.to_dict() for h in ff.region_hot_spots
                    if h is not None and kind_of(h.region) != "end"],
        "n_excluded_nodes": ff.n_excluded, "evaluation_seconds": ff.seconds,
        "notes": list(r.notes),
    }
    return out, ff


def campbell(variant, o: ReportOptions) -> tuple[dict, object, object]:
    import numpy as np

    bottom, top = (float(r) for r in o.campbell_range_rpm)
    n = math.floor((top - bottom) / o.campbell_step_rpm + 1e-9)
    rpms = [bottom + i * o.campbell_step_rpm for i in range(n + 1)]
    if top - rpms[-1] > 1e-9 * top:
        rpms.append(top)
    if o.rotor_model == "solid":
        # the 3D solid rotor: its own mesh of the full variant (every part's seat is a face
        # group), the same level as the static mesh
        run = analyse(variant, rpms, o.modes, orders=o.orders, keep_vectors=True,
                      options=RotorOptions(model="solid", level=o.level, cache_dir=o.cache_dir))
        description = (f"3D solid rotor (P2 tets, level {o.level}, {run.model.n_dof} dofs), "
                       "rigid attachments, bearing springs, undamped")
    else:
        run = analyse(variant, rpms, o.modes, orders=o.orders, keep_vectors=True)
        description = (f"Timoshenko beam ({run.model.beam.n_nodes} nodes) + "
                       f"{len(run.model.disks)} rigid disks, bearing springs, undamped")
    model, res, ver = run.model, run.result, run.verification
    share = run.support_energy_share(0)
    i0 = 0
    table = []
    for j in range(res.freq_hz.shape[1]):
        table.append({"mode": j + 1, "f0_hz": float(res.freq_hz[i0, j]),
                      "f_top_hz": float(res.freq_hz[-1, j]),
                      "whirl": res.branch_whirl[j], "family": res.family[-1][j],
                      "whirl_ratio_top": float(res.whirl_ratio[-1, j]),
                      "bearing_energy_share": float(share[j])})
    out = {"model": o.rotor_model, "description": description, "n_dof": res.n_dof,
           "rpm": [float(r) for r in res.rpm], "orders": list(res.orders),
           "freq_hz": res.freq_hz.tolist(), "branch_whirl": list(res.branch_whirl),
           "table": table,
           "criticals": [{"order": c.order, "mode": c.branch + 1, "rpm": c.rpm,
                          "freq_hz": c.freq_hz, "whirl": c.whirl} for c in res.criticals],
           "statement": res.statement(), "basis_size": res.basis_size,
           "basis_change": res.basis_change,
           "verify": {"rpm": ver.rpm, "max_rel_diff": ver.max_rel_diff,
                      "n_missed": ver.n_missed},
           "tracking_mac_min": float(np.min(res.mac_min)), "notes": list(res.notes)}
    return out, res, model


def beam_mode_fields(model, res, xyz, speed_index: int = 0) -> dict:
    """Mode shapes of a beam rotor model at ``res.rpm[speed_index]`` as 3D point fields on the
    nodes ``xyz`` (3, n): the beam's node values interpolated linearly along x and carried over
    each cross-section as a rigid section, u = u0 + θ × (0, y, z), i.e.
    u_x = u0_x + θ_y z − θ_z y, u_y = u0_y − θ_x z, u_z = u0_z + θ_x y. Each complex mode is
    turned real by the phase of its largest entry and scaled to a largest nodal displacement
    of 1; stored as float32 (a shape needs no more, and it halves the file). Names
    ``mode_<k>_<f>Hz`` (docs/FIELDS.md). Empty for a model without a beam."""
    import numpy as np


    beam = getattr(model, "beam", None)
    if beam is None or res.vectors is None:
        return {}
    xb = np.asarray(beam.x, dtype=float)
    x, y, z = (np.asarray(c, dtype=float) for c in xyz)
    full = model.full_vector(res.vectors[speed_index])            # (6 n_nodes, nb)
    out = {}
    for j in range(full.shape[1]):
        q = full[:, j]
        q = (q * np.exp(-1j * np.angle(q[np.argmax(np.abs(q))]))).real

        def at(d, q=q):
            return np.interp(x, xb, q[d::NDOF])
        ux, uy, uz, tx, ty, tz = (at(d) for d in (UX, UY, UZ, RX, RY, RZ))
        u = np.column_stack([ux + ty * z - tz * y, uy - tx * z, uz + tx * y])
        umax = float(np.linalg.norm(u, axis=1).max())
        if umax > 0:
            u /= umax
        out[f"mode_{j + 1}_{res.freq_hz[speed_index, j]:.2f}Hz"] = u.astype(np.float32)
    return out
