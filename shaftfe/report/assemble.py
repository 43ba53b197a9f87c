"""Run the whole assessment of one variant once and collect it into a frozen ``Report``.

``run_report(options, out, progress)`` does, in this order, on ONE mesh and ONE static model:

1. inputs: the variant (files, content hash, provenance tags), the engine, the rpm history
   (all validated before anything is computed or written);
2. balancing at the engine's speed (``shaftfe.balance``): forces of crank C with the variant's
   X2 and the sweep over X2; the seed's mode-2 row X = 31 % (cylinder frame) for the comparison;
3. beam check (milliseconds): the Inventor-style rigid-support beam (Euler-Bernoulli and
   Timoshenko) for the seed comparison of deflection and nominal stress;
4. static (``options.model``): the zoned solve at the design speeds (the default; the
   axisymmetric one alike) with its surface reference, or ONE full 3D ``shaftfe.static.solve.
   solve_static`` at its reference speed, reported at every design speed (loads ∝ ω²) and
   stored in the static cache;
5. fatigue on the rpm history and FKM: that same solution (no second solve of the softened
   field; with spin softening the surface models solve the unsoftened one once more), rainflow
   counted once (``shaftfe.fatigue.field.evaluate``);
6. Campbell 0 … the engine's maximum speed (beam rotor model; ``rotor_model="solid"`` when the
   3D rotor builder exists), with the reduced-vs-full check at the top speed;
7. the VTU of the run (static fields at the first design speed + the fatigue fields), the
   PyVista pictures rendered from it (in a second process, ``report.pictures``, while this one
   computes the strength section by standard and draws the plots), and the seed comparison.

Every number in the report comes from these computations; the seed figures come from
``shaftfe.report.seed`` (and the variant file's ``balance`` table). numpy / scikit-fem /
matplotlib / pyvista are imported inside the functions.
"""

from __future__ import annotations

import math
from pathlib import Path

from shaftfe.axisymmetric import reference as axi
from shaftfe.axisymmetric.recovery import principal_max_local
from shaftfe.axisymmetric.reference import surface_envelope, write_surface_vtu
from shaftfe.beam.solve import beam_at_ref
from shaftfe.errors import InputError
from shaftfe.fatigue import strength as sd
from shaftfe.fatigue import strength_outputs as so
from shaftfe.fatigue import surface_cache
from shaftfe.fatigue.field import hot_spot_with_factor
from shaftfe.fatigue.methods import DEFAULT_METHOD, AssessmentInputs, get_method
from shaftfe.fatigue.run import (
    DEFAULT_MODEL,
    FatigueJob,
    level_corrected_life,
    resolve_design_life,
    surface_model,
    surface_reference,
)
from shaftfe.io import vtu as export
from shaftfe.machine_elements.bearings import EC_DEFAULT, KAPPA_DEFAULT
from shaftfe.model.loader import load_variant
from shaftfe.report import pictures
from shaftfe.report import seed as seedmod
from shaftfe.report.comparisons import comparisons, error_estimates
from shaftfe.report.drawings import FatigueFigures, draw_balance, draw_fatigue
from shaftfe.report.html import PEAK_FIT_LABEL, num
from shaftfe.report.options import (
    ERROR_STAGE,
    OTHER_LEVEL,
    ReportOptions,
    check_options,
    stages,
    with_duty,
)
from shaftfe.report.results import Figure, Report
from shaftfe.report.stages import (
    balancing,
    beam_check,
    beam_mode_fields,
    campbell,
    fatigue,
    fatigue_job,
    file_comments,
    is_seed_engine,
    provenance_summary,
    read_inputs,
    static_summary,
    static_summary_axisymmetric,
    static_summary_zoned,
)
from shaftfe.rotordynamics.modes_vtu import write_modes_vtu
from shaftfe.rotordynamics.plots import plot_campbell
from shaftfe.static import cache as static_cache
from shaftfe.static.cache import kept_nodes
from shaftfe.static.error import estimate_error
from shaftfe.static.measured_errors import benchmark_errors
from shaftfe.static.model import StaticOptions
from shaftfe.static.outputs import clearance_of
from shaftfe.static.solve import solve_static
from shaftfe.util.atomic import write_atomic
from shaftfe.util.notices import collected, warn
from shaftfe.util.paths import repo_relative
from shaftfe.util.progress import Progress
from shaftfe.util.units import REF_RPM, rpm2_scale
from shaftfe.zoned import reference as zoned_ref

# --------------------------------------------------------------------------- validation


# --------------------------------------------------------------------------- stages


# --------------------------------------------------------------------------- errors


# --------------------------------------------------------------------------- comparisons


# --------------------------------------------------------------------------- the run

def _machine() -> dict:
    import os
    import platform
    try:
        load = os.getloadavg()
    except OSError:                           # pragma: no cover
        load = None
    return {"cpus": os.cpu_count(), "load_average_1_5_15": load,
            "platform": platform.platform(), "python": platform.python_version()}


def _life_in_blocks(o: ReportOptions, history) -> ReportOptions:
    """The design life in passes of the history's block (a life in hours over its length),
    within the fatigue command's range (``fatigue.run.resolve_design_life``)."""
    import dataclasses

    job = resolve_design_life(FatigueJob(str(o.spectrum), design_life=o.design_life_blocks,
                                         design_life_h=o.design_life_h), history)
    return dataclasses.replace(o, design_life_blocks=job.design_life)


def _static(o: ReportOptions, variant, prog):
    """ONE static solve at the design speeds, stored in the static cache for fatigue, and with
    --estimate-error a second solve on the neighbour level."""
    import dataclasses

    if o.model in ("axisymmetric", "zoned"):
        return _surface_static(o, variant, prog)
    with prog.stage("static (mesh + one solve)"):
        sopts = StaticOptions(level=o.level, seed_load_case=o.seed_load_case,
                              spin_softening=o.spin_softening)
        res = solve_static(variant, list(o.design_rpm), sopts, cache_dir=o.cache_dir,
                           linear_stress=True)
        ref = static_cache.store(variant, sopts, res, o.cache_dir)   # the fatigue input
    if o.estimate_error:
        with prog.stage(ERROR_STAGE):
            ee = estimate_error(res, variant, sopts, o.cache_dir,
                                other_level=OTHER_LEVEL[o.level])
            res = dataclasses.replace(res, error_estimate=ee)
    return res, ref


def _surface_static(o: ReportOptions, variant, prog):
    """The axisymmetric or zoned solve at the design speeds and its surface reference, the
    fatigue input (with spin softening also the unsoftened stress, ``fatigue.run.
    surface_reference``: one more solve at the first design speed), stored in the surface
    cache when it is at the speed ``shaftfe fatigue`` reads (as ``_static`` stores the full 3D
    model's)."""
    opts, solve, reference = surface_model(o.model, level=o.level,
                                           seed_load_case=o.seed_load_case,
                                           spin_softening=o.spin_softening)
    solved = {}

    def make(op):             # the design speeds' solve; the unsoftened one at the first
        rpm = list(o.design_rpm) if op.spin_softening == o.spin_softening \
            else float(o.design_rpm[0])
        solved[op.spin_softening] = solve(variant, rpm, op, cache_dir=o.cache_dir)
        return reference(solved[op.spin_softening])
    with prog.stage("static (mesh + one solve)"):
        ref = surface_reference(make, opts)
        if math.isclose(ref.ref_rpm, REF_RPM):  # what ``shaftfe fatigue`` reads next
            ref = surface_cache.store(ref, o.model, variant, opts, o.cache_dir)
    return solved[o.spin_softening], ref


def _nodal_peak(st: dict, ref) -> None:
    """Add ``peak_von_mises_node_MPa`` to the static case at the reference speed: the largest
    nodal von Mises stress outside the singular points, the value the 3D picture and
    ``shaftfe view`` show beside the surface-fitted ``peak_von_mises_MPa``."""
    import numpy as np

    vm = np.asarray(ref.von_mises_ref, dtype=float)
    if vm.size == 0:
        return
    keep = kept_nodes(ref)
    for c in st["cases"]:
        if abs(c["rpm"] - ref.ref_rpm) <= 1e-9 * ref.ref_rpm and keep.any():
            c["peak_von_mises_node_MPa"] = float(vm[keep & np.isfinite(vm)].max())


def _fatigue(o: ReportOptions, res, ref, history, material, variant=None):
    """Fatigue on the static solution, and the hot spot's life with its stress corrected by
    the level's measured error (benchmark) or by the run's own two-level estimate."""
    fat, ff = fatigue(ref, history, material, o, variant)
    life = {"theory": o.mean_stress, "design_life_blocks": o.design_life_blocks,
            "speed_kmh": o.speed_kmh}
    # the 3D level's measured error (the axisymmetric levels' errors are in
    # reports/benchmarks/axisymmetric.md; none corrects the life here)
    # measured on x2_57 as shipped: none for another shaft or a --set geometry
    bench = benchmark_errors(o.level, variant_hash=ref.variant_hash) \
        if not o.estimate_error and o.model == "solid" else None
    corrected = level_corrected_life(ref, ff, history, material, bench,
                                     getattr(res, "n_dofs", 0), **life)
    scaled = corrected[1] if corrected else None
    if scaled is None and getattr(res, "error_estimate", None):
        e = res.error_estimate["cases"][0]["peak_von_mises"]
        ours = res.cases[0].peak_von_mises_MPa
        if e and ours and e["extrapolated"]:
            scaled = hot_spot_with_factor(ref, ff, history, material,
                                          e["extrapolated"] / ours, **life)
    fat["life_if_peak_corrected"] = scaled
    return fat, ff, scaled, bench


def _axi_vtu(res, ref, ff, vtu: Path, rpm: float, zoned: bool = False) -> list[str]:
    """The axisymmetric or zoned run's VTU: the surface field's points (the revolved surface;
    the zones' free surfaces) with the static fields at ``rpm`` and the fatigue fields."""
    import numpy as np

    surface_displacement = (zoned_ref if zoned else axi).surface_displacement
    write_surface_vtu = axi.write_surface_vtu
    s = rpm2_scale(rpm, ref.ref_rpm)
    stress = np.asarray(ref.stress_ref) * s
    r = ff.result
    write_surface_vtu(ref, vtu, {
        "displacement": surface_displacement(res, ref) * s, "von_mises": ref.von_mises_ref * s,
        "max_principal": principal_max_local(stress), "stress": np.ascontiguousarray(stress.T),
        "safety_factor": r.safety_factor, "life_blocks": r.life_blocks,
        "damage_per_block": r.damage_per_block})
    return list(ref.face_groups)


def _vtu(o: ReportOptions, out: Path, variant, res, ref, ff, rotor_model, cres) -> dict:
    """The run's VTU (static + fatigue fields at the first design speed) and the mode shapes
    (a file of their own); returns the ``files`` block of the report."""
    rpm_vtu = float(o.design_rpm[0])
    vtu = out / f"{variant.name}.vtu"
    r = ff.result
    axi = o.model in ("axisymmetric", "zoned")          # a surface field
    if axi:
        regions = _axi_vtu(res, ref, ff, vtu, rpm_vtu, zoned=o.model == "zoned")
    else:
        _, regions = export.write_vtu(res, vtu, rpm_vtu, extra_point_data={
            "safety_factor": r.safety_factor, "life_blocks": r.life_blocks,
            "damage_per_block": r.damage_per_block})
    modes_vtu = out / "modes.vtu"
    modes = beam_mode_fields(rotor_model, cres, ref.xyz if axi else res.mesh.mesh.doflocs)
    if o.rotor_model == "solid":                   # 3D modes on the rotor's own mesh
        write_modes_vtu(rotor_model, cres, modes_vtu)
    elif axi:                                      # beam modes on the revolved surface
        write_surface_vtu(ref, modes_vtu, modes)
    else:                                          # beam modes on the static mesh
        export.write_fields_vtu(res.mesh.mesh, modes_vtu, modes)
    return {"vtu": vtu.name, "vtu_rpm": rpm_vtu, "regions": regions,
            "figures_dir": "figures", "mode_fields": list(modes),
            "mode_rpm": float(cres.rpm[0]),
            "mode_note": ("mode shapes of the beam rotor model at mode_rpm mapped onto the "
                          + ({"axisymmetric": "revolved surface", "zoned": "zoned surface"}
                             .get(o.model, "3D mesh"))
                          + " (rigid cross-sections), largest displacement 1")
            if modes else "3D mode shapes of the solid rotor model on its own mesh",
            "modes_vtu": modes_vtu.name}


def _inputs_block(o: ReportOptions, variant, engine, fat: dict) -> dict:
    d = variant.duty
    return {
        "variant": variant.name, "description": variant.description,
        "files": list(variant.source_files), "content_hash": variant.content_hash,
        "overrides": variant.overrides_map,
        "length_mm": variant.length_mm, "material": variant.material.name,
        "E_MPa": variant.material.E_MPa, "nu": variant.material.nu,
        "bearings": [{"name": b.name, "designation": b.designation, "x_mm": b.x_center_mm,
                      "C_N": b.C_N, "K_N_per_mm": [list(k) for k in b.K_N_per_mm],
                      "axial": b.axial} for b in variant.bearings],
        "attachments": [{"name": a.name, "mass_kg": a.mass_kg,
                         "eccentricity_mm": a.eccentricity_mm, "x_mm": a.seat_center_mm,
                         "seed_load_case": a.seed_load_case,
                         "force_N": {f"{rp:g}": a.force_N(rp) for rp in o.design_rpm}}
                        for a in variant.attachments],
        "engine": engine.name if engine else None,
        "engine_file": repo_relative(engine.source) if engine else None,
        "spectrum": fat["history"]["source"], "design_rpm": list(o.design_rpm),
        "spectrum_comments": file_comments(o.spectrum),
        "campbell_range_rpm": [float(r) for r in o.campbell_range_rpm],
        "duty": {"file": d.source, "speed_range_rpm": list(d.speed_range_rpm)}
        if d is not None else None,
    }


def _sub_timings(res, ff) -> dict:
    d = getattr(res, "run", {})
    if "zones_seconds" in d:            # a zoned solve (``zoned.solve``): its own phases
        return {"plan and zones": d.get("plan_seconds"),
                "global axisymmetric solves": d.get("global_seconds"),
                "3D zones (mesh, factorisation, solves, recovery)": d.get("zones_seconds"),
                "static total": d.get("total_seconds"), "fatigue evaluation": ff.seconds}
    return {"mesh": d.get("mesh_seconds"), "mesh from cache": bool(d.get("mesh_from_cache")),
            "assembly": d.get("assembly_seconds"), "factorisation": d.get("factor_seconds"),
            "solves": d.get("solve_seconds"), "stress recovery": d.get("recovery_seconds"),
            "static total": d.get("total_seconds"), "fatigue evaluation": ff.seconds}


def run_report(o: ReportOptions, out, progress=None) -> Report:
    """Run every stage once (see the module docstring) and return the ``Report``. Writes the
    VTU, ``summary.json``'s sidecar data and the figures into ``out``; the HTML is rendered
    from the returned object (``shaftfe.report.html.render``) and written by the caller."""
    import dataclasses
    import datetime


    prog = progress if progress is not None else Progress(stages(o), enabled=False)
    out = Path(out)
    check_options(o)
    machine = _machine()
    with prog.stage("inputs"):
        variant = load_variant(o.variant, o.overrides)
        o = with_duty(o, variant)           # what the options leave open, from its [duty]
        if o.model is None:                 # the zoned model, as every command
            o = dataclasses.replace(o, model=DEFAULT_MODEL)
        check_options(o)                    # again: what [duty] filled in
        engine, history, material = read_inputs(o, variant)
        o = _life_in_blocks(o, history)
        prov = provenance_summary(variant)
    # the pictures' process starts now: its start-up (VTK's import) runs beside the solve
    renderer = pictures.Renderer() if o.pictures else None
    figs: list[Figure] = []
    fig_dir = out / "figures"

    def add_fig(name: str, title: str, caption: str) -> None:
        figs.append(Figure(name, title, caption, (fig_dir / f"{name}.png").read_bytes()))

    try:
        with prog.stage("balancing"):             # only for a shaft of a named engine
            bal, fres, sw, _ = balancing(engine, variant, seedmod) if engine else (None,) * 4
            fig_dir.mkdir(parents=True, exist_ok=True)        # every figure's folder
            # its figures need nothing of the solve: the second process draws them meanwhile
            drawing = None
            if fres is not None:
                drawing = renderer.draw(draw_balance, fres, sw, fig_dir) if renderer else \
                    pictures.Job(draw_balance, (fres, sw, fig_dir))
        with prog.stage("beam check"):
            beam_out, _ = beam_check(variant, o.design_rpm)
        res, ref = _static(o, variant, prog)
        st = {"axisymmetric": static_summary_axisymmetric, "zoned": static_summary_zoned}.get(
            o.model, static_summary)(res, variant)
        _nodal_peak(st, ref)
        with prog.stage("fatigue"):
            fat, ff, scaled, bench = _fatigue(o, res, ref, history, material, variant)
            # its figures need nothing more: the second process draws them while this one
            # solves the rotor and writes the VTU, before it renders the pictures
            fat_figs = _fatigue_figures(ff, material, o.mean_stress, fig_dir)
            fat_drawing = renderer.draw(draw_fatigue, fat_figs) if renderer else \
                pictures.Job(draw_fatigue, (fat_figs,))
        with prog.stage("Campbell"):
            camp, cres, rotor_model = campbell(variant, o)
        with prog.stage("VTU"):
            files = _vtu(o, out, variant, res, ref, ff, rotor_model, cres)
            # the pictures render in a second process beside the strength section and the plots
            rendering = renderer.start(_picture_job(o, out / files["vtu"], fig_dir, ff,
                                                    files["vtu_rpm"], st)) if renderer else None
        with prog.stage("strength by standard"):
            strength = _strength(o, variant, ref, history, ff.result.cycles)
        with prog.stage("plots"):
            _plots(o, out, fig_dir, variant, drawing, fat_drawing, fres, sw, res, ref, ff,
                   history, material, cres, camp, files["vtu_rpm"], add_fig)
            _din743_along_plot(strength, fig_dir, add_fig)
            _fkm_along_plot(strength, variant, fig_dir, add_fig)
        picture_seconds = None
        with prog.stage("3D pictures"):           # what is left of them once the plots are done
            if rendering is not None:
                pics, picture_seconds = rendering.result()
                n = len(figs)
                for name, title, caption in pics:
                    add_fig(name, title, caption)
                figs[:] = figs[n:] + figs[:n]     # the pictures first, as the report shows them
    except BaseException:
        # nothing more may land in the output folder: the second process's jobs not started are
        # dropped and the one it is on is waited for, before the caller removes the folder
        if renderer is not None:
            renderer.close()
        raise
    errs = error_estimates(st, res, fat, scaled, bench, camp, beam_out,
                           seed=variant.name == seedmod.VARIANT)
    comps = comparisons(bal, beam_out, st, fat, camp, variant, seedmod,
                        seed_engine=is_seed_engine(engine, seedmod))
    notes = tuple(dict.fromkeys(list(res.notes) + list(ref.notes)))
    return Report(
        options=o, created_utc=datetime.datetime.now(datetime.UTC).strftime(
            "%Y-%m-%d %H:%M UTC"),
        inputs=_inputs_block(o, variant, engine, fat), provenance=prov, balancing=bal,
        beam=beam_out, static=st, fatigue=fat, campbell=camp, comparisons=tuple(comps),
        errors=tuple(errs), timings=prog.timings,
        sub_timings={**_sub_timings(res, ff), **({} if picture_seconds is None else {
            "3D pictures (their own process, beside strength and plots)": picture_seconds})},
        figures=tuple(figs), files=files, notes=notes, machine=machine, strength=strength,
        warnings=tuple(collected()))


def _strength(o: ReportOptions, variant, ref, history, cycles=None) -> dict:
    """FKM on the same static reference (no second solve; any model) and the same rainflow count
    ``cycles`` (the fatigue stage's: counted once), DIN 743 on the beam, the bearings over the
    duty cycle and the seed's key and gear checks, with the defaults of
    ``shaftfe fatigue --method fkm | din743``."""
    import dataclasses

    out = {"default_method": DEFAULT_METHOD}
    try:                    # the shaft's own material decides; not every record is assessable
        sd.din743_card(variant, sd.StrengthOptions())
    except InputError as exc:
        warn("strength-material", "report", f"strength by standard left out: {exc}")
        return {}
    job = fatigue_job(o)
    # FKM with its utilisation at every cross-section (the report plots it along the shaft)
    fkm = get_method("fkm").assess(AssessmentInputs.one_channel(
        variant, history, field=ref, cycles=cycles), dataclasses.replace(job, plot=True))
    out["fkm"] = so.fkm_summary(fkm.detail.result, fkm.detail.along)
    beam = beam_at_ref(variant)              # one beam solve for DIN 743 and the bearings
    # DIN 743 with its safety at every cross-section (the report plots it along the shaft)
    din = get_method("din743").assess(AssessmentInputs.one_channel(variant, history, beam=beam),
                                      dataclasses.replace(job, plot=True))
    out["din743"] = so.din_summary(din.detail.run)
    out["elements"] = so.compute_elements(variant, history, KAPPA_DEFAULT, EC_DEFAULT,
                                          o.speed_kmh, beam)
    return out


def _picture_job(o, vtu: Path, fig_dir: Path, ff, rpm: float, st: dict) -> pictures.PictureJob:
    """The three pictures' job: their fields, titles and captions (``report.pictures``)."""
    import numpy as np


    excl = np.flatnonzero(ff.excluded_mask)
    case = next((c for c in st["cases"] if c["rpm"] == rpm), st["cases"][0])
    head = f"{vtu.stem}, {num(rpm)} rpm"
    peak = f"peak {num(case['peak_von_mises_MPa'], 4)} MPa ({PEAK_FIT_LABEL})"
    hot = ff.hot_spot
    shots = (
        ("von_mises_3d", "von_mises", 0.0, "von Mises stress",
         f"{head}: von Mises stress [MPa]\n{peak} at {case['peak_region']}",
         f"von Mises stress at {rpm:g} rpm [MPa]; the ring marks the largest nodal value "
         f"outside the singular points ({len(excl)} nodes at the bearing-coupling and "
         "load-patch edges excluded, as the static and fatigue analyses). The static peak "
         f"printed everywhere else, {num(case['peak_von_mises_MPa'], 4)} MPa, is the "
         f"{PEAK_FIT_LABEL} (a local fit of the recovered surface stress), so it can lie a "
         "little above the largest node."),
        ("displacement_3d", "displacement", "auto", "deflection",
         f"{head}: displacement [mm] (shape exaggerated)",
         f"displacement magnitude at {rpm:g} rpm [mm] on the shape deformed ×(auto) — bearing "
         "springs included, so the shaft also moves as a body on its springs."),
        ("safety_factor_3d", "safety_factor", 0.0, "fatigue safety factor (seed method)",
         f"{head}: fatigue safety factor, seed method\nmin {num(hot.safety_factor, 3)} at "
         f"{num(o.design_life_blocks)} blocks ({hot.region})",
         f"fatigue safety factor of the seed method (von Mises, {o.mean_stress}, S-N card "
         f"{o.material}) at {o.design_life_blocks:g} blocks [-]; red below 1, yellow at 1, green "
         "above; hot spot = the minimum outside the singular points. The default method's "
         "(FKM) verdict is in Strength by standard."),
    )
    return pictures.PictureJob(str(vtu), str(fig_dir), excl,
                               tuple(pictures.Shot(*s) for s in shots))


def _plots(o, out, fig_dir, variant, drawing, fat_drawing, fres, sw, res, ref, ff, history,
           material, cres, camp, rpm_vtu, add_fig) -> None:
    if fres is not None:                      # a shaft of a named engine
        drawing.result()                      # drawn by the second process, or here
        _balance_captions(fres, sw, add_fig)
    _other_plots(o, fig_dir, variant, res, ref, cres, rpm_vtu, add_fig)
    fat_drawing.result()                      # drawn by the second process, or here
    _fatigue_captions(ff, history, material, o.mean_stress, add_fig)


def _din743_along_plot(strength: dict, fig_dir, add_fig) -> None:
    """DIN 743's safety along the shaft (``shaftfe fatigue --method din743 --plot``'s)."""
    din = strength.get("din743")
    if not din or "along" not in din:
        return
    so.plot_din_along(din, fig_dir / "din743_along.png")
    add_fig("din743_along", "DIN 743 safety along the shaft",
            "S_D and S_F of the unnotched section at every cross-section (every 0.25 mm, "
            "the beam's nominal stresses over the history's largest cycle) and at each notch "
            "(markers, named), against S_min; the shaft's outline below")


def _fkm_along_plot(strength: dict, variant, fig_dir, add_fig) -> None:
    """FKM's degree of utilisation along the shaft (``shaftfe fatigue --method fkm --plot``'s)."""
    fkm = strength.get("fkm")
    if not fkm or "along" not in fkm:
        return
    so.plot_fkm_along(fkm, variant, fig_dir / "fkm_along.png")
    add_fig("fkm_along", "FKM degree of utilisation along the shaft",
            "FKM on the static field at every 1 mm of the surface (the worse of each slice's "
            "highest tensile and compressive node outside the singular points, its region's "
            "roughness, the governing Miner rule) and each region's hot spot (markers, "
            "named), against the limit 1; the shaft's outline below")


def _fatigue_figures(ff, material, mean_stress: str, fig_dir) -> FatigueFigures:
    hot = ff.hot_spot
    s0, beta = ff.result.linear_stress(hot.node)      # the node's S0 (λ + β λ²)
    return FatigueFigures(ff.history, s0, beta, f"{hot.region} x = {hot.xyz_mm[0]:.1f} mm",
                          ff.result.cycles, material, mean_stress, Path(fig_dir))


def _fatigue_captions(ff, history, material, mean_stress: str, add_fig) -> None:
    add_fig("load_history", "rpm history (one block)",
            f"{Path(history.source).name}: engine speed [rpm] and load factor (n / "
            f"{ff.ref_rpm:g})² [-] against time [s]: the factor on the static stresses at "
            f"{ff.ref_rpm:g} rpm, the same reference as the fatigue text.")
    add_fig("rainflow_matrix", "rainflow matrix",
            "cycles per block at the hot spot by stress range and mean [MPa].")
    add_fig("damage_matrix", "damage matrix",
            "Miner damage per block at the hot spot by stress range and mean [MPa].")
    add_fig("haigh", "Haigh diagram",
            f"the hot spot's cycles (mean, amplitude) [MPa] and the {mean_stress} line.")
    add_fig("sn_curve", "S-N curve", f"{material.name}: alternating stress [MPa] against "
            "cycles to failure [-].")


def _balance_captions(fres, sw, add_fig) -> None:
    add_fig("balance_forces", "shaking forces over one revolution",
            f"{fres.engine}, crank C X = {100 * fres.X:.1f} %, balancer X2 = "
            f"{100 * fres.X2:.2f} % (this variant), {fres.rpm:g} rpm, engine frame (tilt "
            f"{fres.tilt_deg:g}°): Fx, Fy, |F| [N] against the crank angle [°]; polar plot of "
            "|F| against its direction; hodograph Fy(Fx) [N].")
    add_fig("balance_sweep", "balancing curves over X2",
            f"max|Fx|, max|Fy|, RMS|F|, max|F| [N] against the balancer ratio X2 [%] for crank "
            f"C (X = {100 * sw.X[0]:.1f} %), {sw.rpm:g} rpm, cylinder frame (as the seed's "
            "fig. 58: x across, y along the cylinder axis).")


def _other_plots(o, fig_dir, variant, res, ref, cres, rpm_vtu, add_fig) -> None:
    clear = clearance_of(variant)
    if o.model in ("axisymmetric", "zoned"):
        zoned = o.model == "zoned"
        export.plot_png(res.global_result if zoned else res, fig_dir / "deflection.png",
                        rpm_vtu, envelope=surface_envelope(ref),
                        model="zoned FE" if zoned else "axisymmetric FE", clearance=clear)
        what = ("zoned FE: the axisymmetric global model's axis, the stresses of the global "
                "model and the 3D zones" if zoned else "axisymmetric FE") + ", bearing springs"
    else:
        export.plot_png(res, fig_dir / "deflection.png", rpm_vtu, clearance=clear)
        what = "3D FE and beam, bearing springs"
    add_fig("deflection", "deflection line and stress envelope",
            f"{rpm_vtu:g} rpm: signed deflection of the axis in its load plane [µm] ({what}): "
            "in total, i.e. with the shaft's rigid-body motion on the bearing springs, and its "
            "bending part relative to the straight line through the two bearings"
            + (f"; the clearance ±{clear[1]:g} mm to the crankshaft at x = {clear[0]:g} mm"
               if clear else "")
            + "; below, the largest von Mises stress [MPa] in each 1 mm slice along x [mm].")
    camp_png = plot_campbell(cres, title=f"{variant.name}: Campbell diagram "
                             f"({o.rotor_model} model)")
    write_atomic(fig_dir / "campbell.png", camp_png)
    add_fig("campbell", "Campbell diagram",
            "damped natural frequencies [Hz] against the speed [rpm], branches by whirl "
            "(forward / backward), engine-order lines k × n/60 and critical speeds (X).")
