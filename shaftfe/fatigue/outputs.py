"""The files of a fatigue run: ``fatigue.vtu`` (life, damage, safety factor and the reference
von Mises stress at every node), three plots of the hot spot (rainflow matrix, damage matrix,
Haigh diagram) and ``summary.json``. Every file is written atomically into ``out`` (the
command stages the whole directory)."""

from __future__ import annotations

import json

from shaftfe.fatigue import kernels
from shaftfe.fatigue import plots as fatigue_plots
from shaftfe.fatigue.counting import rainflow_matrix
from shaftfe.fatigue.field import write_vtu
from shaftfe.fatigue.run import SEED, FatigueRun, finite_or_none, seed_applies
from shaftfe.static.model import load_case_label
from shaftfe.util.atomic import atomic_path, write_atomic
from shaftfe.util.fmt import life_reason
from shaftfe.util.notices import collected
from shaftfe.util.versions import package_versions


def write_plots(run: FatigueRun, out) -> dict[str, str]:
    """The hot spot's rainflow matrix, damage matrix and Haigh diagram (PNG)."""
    job, ff = run.job, run.field
    r, hot = ff.result, ff.hot_spot
    s0, beta = ff.result.linear_stress(hot.node)      # the node's S0 (λ + β λ²)
    lbl = f"{hot.region} x = {hot.xyz_mm[0]:.1f} mm"
    with atomic_path(out / "rainflow_matrix.png") as tmp:
        fatigue_plots.plot_cycle_matrix(
            rainflow_matrix(kernels.node_stress_cycles(s0, beta, r.cycles), units="MPa"), tmp,
            title=f"rainflow matrix per block\nhot spot {lbl}")
    with atomic_path(out / "damage_matrix.png") as tmp:
        fatigue_plots.plot_cycle_matrix(
            kernels.damage_matrix(s0, r.cycles, run.material, job.mean_stress, job.kf,
                                  beta=beta), tmp,
            title=f"damage matrix per block\nhot spot {lbl}")
    with atomic_path(out / "haigh.png") as tmp:
        fatigue_plots.plot_haigh(s0, r.cycles, run.material, tmp, job.mean_stress, job.kf,
                                 beta)
    return {"rainflow_matrix": "rainflow_matrix.png", "damage_matrix": "damage_matrix.png",
            "haigh": "haigh.png"}


def _inputs(job, variant) -> dict:
    return {"spectrum": str(job.spectrum), "variant": job.variant, "ref_rpm": job.ref_rpm,
            "sample_rate_hz": job.sample_rate, "mean_stress": job.mean_stress,
            "equivalent": job.equivalent, "material": job.material,
            "design_life_blocks": job.design_life, "speed_kmh": job.speed_kmh, "kf": job.kf,
            "level": job.level, "model": job.model, "seed_load_case": job.seed_load_case,
            "load_case": load_case_label(job.seed_load_case), "exclude_mm": job.exclude_mm,
            "supports": "bearing springs (2x2 radial stiffness)",
            "overrides": variant.overrides_map,
            "design_life_h": job.design_life_h, "allow_overspeed": job.allow_overspeed}


def _history(run: FatigueRun) -> dict:
    history, ff = run.history, run.field
    lf = ff.history.load_factor
    return {"source": history.source, "format": history.format,
            "samples": history.n_samples, "duration_s": history.duration_s,
            "rpm_min": float(history.rpm.min()), "rpm_max": float(history.rpm.max()),
            "rpm_ref_of_file": history.rpm_ref, "static_ref_rpm": ff.ref_rpm,
            "load_factor_min": float(lf.min()), "load_factor_max": float(lf.max()),
            "note": "load factor = (rpm / static_ref_rpm)^2 multiplies the static "
                    "stresses at static_ref_rpm"}


def _static(run: FatigueRun) -> dict:
    ref = run.ref
    return {"from_cache": ref.from_cache, "seconds": ref.seconds,
            "solve_seconds": ref.solve_seconds, "ref_rpm": ref.ref_rpm, "cache_key": ref.key,
            "relative_residual": ref.relative_residual,
            "mesh_key": ref.mesh_key, "variant_hash": ref.variant_hash, "options": ref.options,
            "n_nodes": ref.n_nodes, "n_elements": ref.n_elements,
            "n_excluded_nodes": run.field.n_excluded, "notes": list(ref.notes)}


def _result(run: FatigueRun) -> dict:
    ff = run.field
    r, hot = ff.result, ff.hot_spot
    filtered = ~ff.excluded_mask
    return {"life_blocks": finite_or_none(hot.life_blocks),
            "life_hours": finite_or_none(hot.life_hours),
            "life_km": finite_or_none(hot.life_km), "infinite_life": hot.infinite_life,
            "life_reason": life_reason(hot.life_blocks, hot.life_hours),   # printed as none
            "damage_per_block": finite_or_none(hot.damage_per_block),
            "safety_factor": hot.safety_factor, "safety_status": hot.safety_status,
            "design_life_blocks": run.job.design_life,
            "safety_factor_cap": kernels.SAFETY_FACTOR_MAX,
            "min_safety_factor_filtered": float(r.safety_factor[filtered].min())
            if filtered.any() else None,
            "min_safety_factor_unfiltered": float(r.safety_factor.min())}


def summary(run: FatigueRun, vtu_name: str, plots: dict[str, str]) -> dict:
    """The summary.json content (every number the command prints, and more)."""
    ff, ref = run.field, run.ref
    r = ff.result
    return {
        "inputs": _inputs(run.job, run.variant),
        "versions": package_versions("matplotlib"),
        "history": _history(run),
        "static": _static(run),
        "cycles": {"per_block": r.cycles.total_count, "classes": r.cycles.n,
                   "closure": r.cycles.closure},
        "result": _result(run),
        "hot_spot": ff.hot_spot.to_dict(),
        "hot_spot_unfiltered": ff.hot_spot_unfiltered.to_dict(),
        "regions": [h.to_dict() for h in ff.region_hot_spots if h is not None],
        "seed": SEED if seed_applies(run.job, ref.variant) else None,
        "notes": list(r.notes) + list(ref.notes),
        "vtu": {"file": vtu_name, "regions": list(ref.face_groups),
                "point_data": ["life_blocks", "damage_per_block", "safety_factor",
                               "von_mises_ref"],
                "von_mises_ref_rpm": ref.ref_rpm,
                "note": "life_blocks = inf where there is no damage; von_mises_ref at "
                        "von_mises_ref_rpm"},
        "plots": plots,
        "timing": {"fatigue_seconds": run.eval_seconds},
        "level_error": run.level_error,
        "warnings": collected(),             # shaftfe.util.notices (e.g. an allowed overspeed)
    }


def write_outputs(run: FatigueRun, out) -> tuple[dict, dict[str, str]]:
    """fatigue.vtu, the plots and summary.json into the directory ``out``."""
    vtu = out / "fatigue.vtu"
    write_vtu(run.ref, run.field, vtu)
    plots = write_plots(run, out)
    data = summary(run, vtu.name, plots)
    write_atomic(out / "summary.json", json.dumps(data, indent=2, allow_nan=False) + "\n")
    return data, plots
