"""Run the whole assessment of one variant once and collect it into a frozen ``Report``.

``run_report(options, out, progress)`` does, in this order, on ONE mesh and ONE static model:

1. inputs: the variant (files, content hash, provenance tags), the engine, the rpm history
   (all validated before anything is computed or written);
2. balancing at the engine's speed (``shaftfe.balance``): forces of crank C with the variant's
   X2 and the sweep over X2; the seed's mode-2 row X = 31 % (cylinder frame) for the comparison;
3. beam check (milliseconds): the Inventor-style rigid-support beam (Euler-Bernoulli and
   Timoshenko) for the seed comparison of deflection and nominal stress;
4. 3D static: ONE ``shaftfe.static.solve.solve_static`` at its reference speed, reported at every
   design speed (loads ∝ ω²), stored in the static cache;
5. fatigue on the rpm history: that same solution (``static_cache.from_result`` → no second
   solve), rainflow counted once (``shaftfe.fatigue.field.evaluate``);
6. Campbell 0 … the engine's maximum speed (beam rotor model; ``rotor_model="solid"`` when the
   3D rotor builder exists), with the reduced-vs-full check at the top speed;
7. the VTU of the run (static fields at the first design speed + the fatigue fields), the
   PyVista pictures rendered from it, the plots, and the seed comparison.

Every number in the report comes from these computations; the seed figures come from
``shaftfe.report.seed`` (and the variant file's ``balance`` table). numpy / scikit-fem /
matplotlib / pyvista are imported inside the functions.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from shaftfe.errors import InputError
from shaftfe.solid.levels import LEVEL_NAMES
from shaftfe.static.benchmark import bench_matches, benchmark_errors
from shaftfe.util.paths import DEFAULT_SPECTRUM, repo_relative

ROTOR_MODELS = ("beam", "solid")

STAGES = ("inputs", "balancing", "beam check", "static (mesh + one solve)", "fatigue",
          "Campbell", "VTU", "3D pictures", "plots")
ERROR_STAGE = "error estimate (second mesh level)"
# --estimate-error: the second level of the Richardson estimate (the neighbour level; the
# coarser one where there is one, so the estimate costs less than the run itself)
OTHER_LEVEL = {"coarse": "default", "default": "coarse", "fine": "default"}


def stages(o) -> tuple[str, ...]:
    """The progress stages of a run with options ``o``."""
    if not o.estimate_error:
        return STAGES
    i = STAGES.index("static (mesh + one solve)") + 1
    return (*STAGES[:i], ERROR_STAGE, *STAGES[i:])


@dataclass(frozen=True)
class ReportOptions:
    variant: str = "x2_57"
    spectrum: str = str(DEFAULT_SPECTRUM)
    engine: str = "vm450"
    level: str = "default"
    design_rpm: tuple[float, ...] = (10_000.0, 7_000.0)   # seed §8.2.2 static check, §8.3 ref
    campbell_step_rpm: float = 500.0
    modes: int = 12
    orders: tuple[float, ...] = (1.0, 2.0)
    rotor_model: str = "beam"
    estimate_error: bool = False          # solve a second mesh level (OTHER_LEVEL)
    mean_stress: str = "soderberg"
    material: str = "structural_steel"
    design_life_blocks: float = 1e7
    speed_kmh: float = 70.0
    cache_dir: str | None = None
    pictures: bool = True                 # PyVista renders (off: no VTK import)
    seed_load_case: bool = False          # every part (as every command); True: the seed's F1+Fv2


@dataclass(frozen=True)
class Comparison:
    """One seed figure next to ours."""
    group: str
    quantity: str
    unit: str
    seed: float | None
    ours: float | None
    model: str                # how ours was computed
    note: str = ""

    @property
    def diff_percent(self) -> float | None:
        if self.seed in (None, 0) or self.ours is None or not math.isfinite(self.ours):
            return None
        return 100.0 * (self.ours / self.seed - 1.0)


@dataclass(frozen=True)
class ErrorEstimate:
    quantity: str
    value: float | None
    unit: str
    error: str                # e.g. "−7.7 % (low)" or "≤ 1e-12"
    method: str


@dataclass(frozen=True)
class Figure:
    name: str                 # file stem in figures/
    title: str
    caption: str
    png: bytes = field(repr=False)


@dataclass(frozen=True)
class Report:
    options: ReportOptions
    created_utc: str
    inputs: dict
    provenance: dict
    balancing: dict
    beam: dict
    static: dict
    fatigue: dict
    campbell: dict
    comparisons: tuple[Comparison, ...]
    errors: tuple[ErrorEstimate, ...]
    timings: tuple[tuple[str, float], ...]
    sub_timings: dict
    figures: tuple[Figure, ...]
    files: dict
    notes: tuple[str, ...] = ()
    machine: dict = field(default_factory=dict)

    def figure(self, name: str) -> Figure | None:
        return next((f for f in self.figures if f.name == name), None)

    def to_dict(self) -> dict:
        from dataclasses import asdict
        return _clean({
            "options": asdict(self.options), "created_utc": self.created_utc,
            "inputs": self.inputs, "provenance": self.provenance, "balancing": self.balancing,
            "beam": self.beam, "static": self.static, "fatigue": self.fatigue,
            "campbell": self.campbell,
            "comparisons": [dict(asdict(c), diff_percent=c.diff_percent)
                            for c in self.comparisons],
            "error_estimates": [asdict(e) for e in self.errors],
            "timings_s": dict(self.timings), "sub_timings_s": self.sub_timings,
            "figures": [f"figures/{f.name}.png" for f in self.figures], "files": self.files,
            "notes": list(self.notes), "machine": self.machine})


def _clean(o):
    """JSON-safe: non-finite floats → None, tuples → lists, numpy scalars → float."""
    if isinstance(o, dict):
        return {str(k): _clean(v) for k, v in o.items()}
    if isinstance(o, list | tuple):
        return [_clean(v) for v in o]
    if isinstance(o, bool | str) or o is None:
        return o
    if isinstance(o, int):
        return int(o)
    try:
        f = float(o)
    except (TypeError, ValueError):
        return str(o)
    return f if math.isfinite(f) else None


# --------------------------------------------------------------------------- validation

CAMPBELL_STEP_MIN_RPM = 10.0     # ≤ 2000 speeds up to the rpm ceiling: seconds, not GiB


def check_options(o: ReportOptions) -> None:
    """Cheap checks of everything the user typed (before any computation or output)."""
    if o.level not in LEVEL_NAMES:
        raise InputError("command line", "--level", " | ".join(LEVEL_NAMES), got=o.level)
    if o.rotor_model not in ROTOR_MODELS:
        raise InputError("command line", "--rotor-model", " | ".join(ROTOR_MODELS),
                         got=o.rotor_model)
    from shaftfe.util.limits import RPM_CEILING, check_rpm
    if not o.design_rpm:
        raise InputError("command line", "--rpm", "one or more speeds", got="")
    for r in o.design_rpm:
        check_rpm(r, "--rpm", positive=True)
    if not (math.isfinite(o.campbell_step_rpm)
            and CAMPBELL_STEP_MIN_RPM <= o.campbell_step_rpm <= RPM_CEILING):
        raise InputError("command line", "--campbell-step",
                         f"a step in [{CAMPBELL_STEP_MIN_RPM:g}, {RPM_CEILING:g}] rpm (at most "
                         f"{RPM_CEILING / CAMPBELL_STEP_MIN_RPM:.0f} speeds)",
                         got=o.campbell_step_rpm)
    if not (1 <= o.modes <= 50):
        raise InputError("command line", "--modes", "1..50", got=o.modes)
    from shaftfe.fatigue.run import MEAN_STRESS, check_life_settings
    check_life_settings(o.design_life_blocks, o.speed_kmh)
    if o.mean_stress not in MEAN_STRESS:
        raise InputError("command line", "--mean-stress", " | ".join(MEAN_STRESS),
                         got=o.mean_stress)
    if o.rotor_model == "solid" and not solid_rotor_available():
        raise InputError("command line", "--rotor-model",
                         "beam (the 3D solid rotor model is not available yet)", got="solid")


def solid_rotor_available() -> bool:
    """True when the 3D solid rotor model (``shaftfe.rotordynamics.solid_rotor``) is installed."""
    import importlib.util
    return importlib.util.find_spec("shaftfe.rotordynamics.solid_rotor") is not None


# --------------------------------------------------------------------------- stages

def _inputs(o: ReportOptions) -> tuple:
    from shaftfe.balance.engines import load_engine
    from shaftfe.fatigue.run import read_spectrum
    from shaftfe.fatigue.sn import load_material
    from shaftfe.model.loader import load_variant

    variant = load_variant(o.variant)
    engine = load_engine(o.engine)
    if engine.max_rpm is None or not engine.max_rpm > 0:
        raise InputError(engine.source, "max_rpm", "> 0 rpm (the Campbell range ends there)",
                         got=engine.max_rpm, reason="is missing")
    history = read_spectrum(o.spectrum, None, None)
    material = load_material(o.material)
    return variant, engine, history, material


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
    return {"counts": counts, "reconstructed": recon,
            "document": "geometry/RECONSTRUCTION.md",
            "files": list(variant.source_files)}


def _balancing(engine, variant, seedmod) -> tuple[dict, object, object, object]:
    import numpy as np

    from shaftfe.balance import single, sweep

    mp = variant.mass_properties()
    tgt = variant.balance_target
    if tgt is not None and tgt.m_pos_kg > 0 and tgt.crank_radius_mm > 0:
        x2 = mp.mass_kg * mp.gamma2_mm / (tgt.m_pos_kg * tgt.crank_radius_mm)
    elif tgt is not None:
        x2 = tgt.X2_percent / 100.0
    else:                                     # no balance table: the engine's own balancer
        x2 = engine.X2 if engine.X2 is not None else 0.0
    X = seedmod.CRANK_C_X
    res = single.forces(engine, X=X, X2=x2, rpm=engine.rpm)
    sw = sweep.sweep(engine, [X], np.arange(0.0, 1.0001, 0.01), rpm=engine.rpm,
                     tilt_deg=0.0)            # cylinder frame, as the seed's fig. 58
    mins = {k: (float(v[0][0]), 100.0 * float(v[1][0])) for k, v in sw.minima().items()}
    sb = seedmod.BALANCING
    sw2 = sweep.sweep(engine, [sb["X"]], np.arange(0.0, 1.0001, 0.01), rpm=sb["rpm"],
                      tilt_deg=0.0)
    mins2 = {k: (float(v[0][0]), 100.0 * float(v[1][0])) for k, v in sw2.minima().items()}
    omega = 2 * math.pi * sb["rpm"] / 60.0
    bal_force = engine.balancer_mass_kg * engine.balancer_radius_mm * 1e-3 * omega ** 2 \
        if engine.balancer_mass_kg and engine.balancer_radius_mm else None
    out = {
        "engine": engine.name, "engine_file": repo_relative(engine.source), "rpm": engine.rpm,
        "tilt_deg": engine.tilt_deg, "idle_rpm": engine.idle_rpm, "max_rpm": engine.max_rpm,
        "m_pos_kg": engine.m_pos_kg, "m_rot_kg": engine.m_rot_kg,
        "crank_radius_mm": engine.crank_radius_mm, "rod_length_mm": engine.rod_length_mm,
        "X_percent": 100 * X, "X2_percent": 100 * x2,
        "first_order_amplitude_N": res.first_order_amplitude,
        "metrics": res.metrics.as_dict(),
        "sweep_minima": {k: {"value_N": v[0], "at_X2_percent": v[1]} for k, v in mins.items()},
        "seed_row": {"X_percent": 100 * sb["X"], "rpm": sb["rpm"], "tilt_deg": 0.0,
                     "minima": {k: {"value_N": v[0], "at_X2_percent": v[1]}
                                for k, v in mins2.items()}},
        "balancer_force_A1_N": bal_force,
        "mass_properties": {"mass_kg": mp.mass_kg, "gamma2_mm": mp.gamma2_mm,
                            "x_T_mm": mp.x_T_mm,
                            "polar_inertia_kg_mm2": mp.polar_inertia_kg_mm2},
    }
    return out, res, sw, mins2


def _beam_check(variant) -> tuple[dict, object]:
    """Inventor-style beam (rigid supports, seed load case) at 10 000 and 7000 rpm."""
    from shaftfe.beam.model import build_model
    from shaftfe.beam.solve import solve

    v = variant.with_seed_load_case()
    rpms = [10_000.0, 7_000.0]
    timo = solve(build_model(v, rigid_supports=True), rpms)
    eb = solve(build_model(v, rigid_supports=True, shear_deformation=False), rpms)
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
    b = sorted(case.bearings, key=lambda b: b.x_mm)
    st = min(case.stations, key=lambda s: abs(s.x_mm - x_mm))
    if len(b) != 2:
        return st.u_mm
    t = (st.x_mm - b[0].x_mm) / (b[1].x_mm - b[0].x_mm)
    uy = st.uy_mm - (b[0].uy_mm + t * (b[1].uy_mm - b[0].uy_mm))
    uz = st.uz_mm - (b[0].uz_mm + t * (b[1].uz_mm - b[0].uz_mm))
    return math.hypot(uy, uz)


def _static_summary(res, variant) -> dict:
    from dataclasses import asdict
    cases = []
    gear_x = next((a.seat_center_mm for a in variant.attachments if a.name == "gear"), None)
    for c in res.cases:
        rel = {}
        if gear_x is not None:
            rel["gear"] = _relative_deflection(c, gear_x)
        if variant.clearance_station_x_mm is not None:
            rel["clearance"] = _relative_deflection(c, variant.clearance_station_x_mm)
        cases.append({
            "rpm": c.rpm,
            "bearings": [asdict(b) for b in c.bearings],
            "stations": [asdict(s) for s in c.stations],
            "relative_deflection_mm": rel,
            "max_deflection_mm": c.max_deflection_mm,
            "max_deflection_xyz_mm": c.max_deflection_xyz_mm,
            "peaks": [asdict(p) for p in c.peaks],
            "peak_von_mises_MPa": c.peak_von_mises_MPa,
            "peak_von_mises_xyz_mm": c.peak_von_mises_xyz_mm,
            "peak_region": _region_of_peak(c),
            "peak_von_mises_unfiltered_MPa": c.peak_von_mises_unfiltered_MPa,
            "peak_von_mises_unfiltered_xyz_mm": c.peak_von_mises_unfiltered_xyz_mm,
            "equilibrium_residual": c.equilibrium_residual,
            "load_sum_N": c.load_sum_N,
            "beam_springs": {k: v for k, v in (c.beam or {}).items()
                             if k not in ("x_line_mm", "u_line_mm")},
        })
    d = res.diagnostics
    return {"level": res.options.level, "order": res.options.order,
            "supports": "rigid" if res.options.rigid_supports else "bearing springs (2×2)",
            "load_case": res.options.load_case,
            "ref_rpm": res.ref_rpm, "n_nodes": res.n_nodes, "n_elements": res.n_elements,
            "n_dofs": res.n_dofs, "mesh_key": res.mesh_key, "variant_hash": res.variant_hash,
            "solver": d.get("solver"), "relative_residual": d.get("relative_residual"),
            "cond_S": d.get("cond_S"), "min_quality": d.get("min_quality"),
            "mesh_from_cache": getattr(res, "run", {}).get("mesh_from_cache"),
            "n_excluded_nodes": d.get("n_excluded_nodes"),
            "cases": cases, "error_estimate": res.error_estimate, "notes": list(res.notes)}


def _region_of_peak(c) -> str:
    best = max((p for p in c.peaks if math.isfinite(p.von_mises_MPa)),
               key=lambda p: p.von_mises_MPa, default=None)
    return best.region if best is not None and math.isclose(
        best.von_mises_MPa, c.peak_von_mises_MPa, rel_tol=1e-9) else "-"


def _fatigue(ref, history, material, o: ReportOptions) -> tuple[dict, object]:
    from shaftfe.fatigue.field import evaluate

    ff = evaluate(ref, history, material, equivalent="von_mises", theory=o.mean_stress,
                  kf=1.0, design_life_blocks=o.design_life_blocks, speed_kmh=o.speed_kmh)
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
                    if h is not None and not h.region.startswith("end:")],
        "n_excluded_nodes": ff.n_excluded, "evaluation_seconds": ff.seconds,
        "notes": list(r.notes),
    }
    return out, ff


def _campbell(variant, engine, o: ReportOptions) -> tuple[dict, object, object]:
    import numpy as np

    top = float(engine.max_rpm)
    n = math.floor(top / o.campbell_step_rpm + 1e-9)
    rpms = [i * o.campbell_step_rpm for i in range(n + 1)]
    if top - rpms[-1] > 1e-9 * top:
        rpms.append(top)
    from shaftfe.rotordynamics.analyse import RotorOptions, analyse
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

    from shaftfe.beam.elements import NDOF, RX, RY, RZ, UX, UY, UZ

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


# --------------------------------------------------------------------------- errors

def _error_estimates(report_static: dict, res, ff_out: dict, scaled: dict | None,
                     bench: dict | None, camp: dict, beam_check: dict) -> list[ErrorEstimate]:
    import math as _m
    c0 = report_static["cases"][0]
    out = []
    ee = res.error_estimate
    if ee:
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
                  if region.startswith("fillet:")]
        for label, val, unit, e in items:
            if e and val and e["extrapolated"]:
                rel = val / e["extrapolated"] - 1.0
                out.append(ErrorEstimate(
                    label, val, unit,
                    f"{100 * rel:+.2f} % against the extrapolated {e['extrapolated']:.5g} {unit}",
                    how))
    elif bench and not bench_matches(bench, report_static["n_dofs"]):
        out.append(ErrorEstimate(
            "peak von Mises", c0["peak_von_mises_MPa"], "MPa", "not estimated in this run",
            f"the benchmark ({bench['source']}) was run on a {bench['level']} mesh of "
            f"{bench.get('dofs')} dofs, this run has {report_static['n_dofs']}: the mesh levels "
            "changed since (re-run `make bench`); `shaftfe report --estimate-error` adds a "
            "Richardson estimate from a second solve on the "
            f"{OTHER_LEVEL[report_static['level']]} level"))
    elif bench:
        mesh_note = (f"; benchmark mesh {bench.get('dofs')} dofs, this run "
                     f"{report_static['n_dofs']}")
        for key, label in (("collar", "collar fillet peak"),
                           ("bsg", "bearing-seat-gear fillet peak")):
            region = {"collar": "fillet:collar", "bsg": "fillet:bearing_seat_gear"}[key]
            pk = next((p for p in c0["peaks"] if p["region"] == region), None)
            val = pk["von_mises_MPa"] if pk else None
            rel = bench[key]["rel_error"]
            extra = (f"; corrected ≈ {val / (1 + rel):.4g} MPa" if val else "")
            out.append(ErrorEstimate(
                f"{label}, {c0['rpm']:g} rpm", val, "MPa",
                f"{100 * rel:+.1f} % (reads low){extra}",
                f"benchmark ({bench['source']}, level {bench['level']} P2 against the "
                "Richardson extrapolation of default and fine; all-parts load case; no second "
                f"solve in this run{mesh_note})"))
        rel = bench["defl"]["rel_error"]
        out.append(ErrorEstimate(
            f"max deflection, {c0['rpm']:g} rpm", c0["max_deflection_mm"], "mm",
            f"{100 * rel:+.2f} %", f"benchmark ({bench['source']}), same rule"))
    else:
        out.append(ErrorEstimate("peak von Mises", c0["peak_von_mises_MPa"], "MPa",
                                 "not estimated in this run",
                                 "no benchmark data; `shaftfe report --estimate-error` adds a "
                                 "Richardson estimate from a second mesh level"))
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
                             f"{report_static['solver']}; the run fails above 1e-8"))
    hs = ff_out["hot_spot"]
    if scaled is not None and hs["life_blocks"] is not None:
        lb = scaled["life_blocks"]
        out.append(ErrorEstimate(
            "fatigue life at the hot spot", hs["life_blocks"], "blocks",
            f"≈ {f'{lb:,.0f}'.replace(',', ' ')} blocks "
            f"({100 * (lb / hs['life_blocks'] - 1):+.0f} %), safety factor "
            f"{scaled['safety_factor']:.3f}, if the hot-spot stress is corrected by "
            f"×{scaled['factor']:.4f}"
            if _m.isfinite(lb) else "infinite after correction",
            "the same S-N evaluation at the hot spot with the stress corrected by the estimated "
            "error of the peak above (life ∝ σ^-k: a few % of stress is tens of % of life)"))
    out.append(ErrorEstimate(
        "natural frequencies (reduced basis)", camp["table"][0]["f0_hz"], "Hz",
        f"{camp['verify']['max_rel_diff']:.1e} vs the full-size problem at "
        f"{camp['verify']['rpm']:g} rpm; basis change {camp['basis_change']:.1e}",
        f"{camp['description']}; model error vs the seed's 3D Ansys model is not covered "
        "(see the comparison)"))
    return out


# --------------------------------------------------------------------------- comparisons

def comparisons(bal: dict, beam_check: dict, st: dict, fat: dict, camp: dict, variant,
                seedmod) -> list[Comparison]:
    S, B, C, F = seedmod.STATIC, seedmod.BALANCING, seedmod.CAMPBELL, seedmod.FATIGUE
    rows: list[Comparison] = []
    add = rows.append
    # balancing (seed 000 §5.4, appendix 1)
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
    # variant (seed 000 §8.2.2 table, from the variant file's seed-tagged balance table)
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
    if variant.name != seedmod.VARIANT:       # the seed's FE studies are of another variant
        return rows
    # loads
    grp = "loads"
    att = {a.name: a for a in variant.attachments}
    if {"gear", "counterweight_1", "counterweight_2"} <= att.keys():
        g, c1, c2 = att["gear"], att["counterweight_1"], att["counterweight_2"]
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
    # static
    grp = "static"
    cases = {c["rpm"]: c for c in st["cases"]}
    fe = f"3D FE P{st['order']} {st['level']}, {st['supports']}, {st['load_case']}"
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
    # fatigue
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
    # Campbell
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


def run_report(o: ReportOptions, out, progress=None) -> Report:
    """Run every stage once (see the module docstring) and return the ``Report``. Writes the
    VTU, ``summary.json``'s sidecar data and the figures into ``out``; the HTML is rendered
    from the returned object (``shaftfe.report.html.render``) and written by the caller."""
    import datetime

    from shaftfe.report import seed as seedmod
    from shaftfe.util.progress import Progress

    prog = progress if progress is not None else Progress(stages(o), enabled=False)
    out = Path(out)
    check_options(o)
    machine = _machine()
    figs: list[Figure] = []
    fig_dir = out / "figures"

    def add_fig(name: str, title: str, caption: str) -> None:
        figs.append(Figure(name, title, caption, (fig_dir / f"{name}.png").read_bytes()))

    with prog.stage("inputs"):
        variant, engine, history, material = _inputs(o)
        prov = provenance_summary(variant)
    with prog.stage("balancing"):
        bal, fres, sw, _ = _balancing(engine, variant, seedmod)
    with prog.stage("beam check"):
        beam_out, _ = _beam_check(variant)
    with prog.stage("static (mesh + one solve)"):
        from shaftfe.static import cache as static_cache
        from shaftfe.static.model import StaticOptions
        from shaftfe.static.solve import solve_static
        sopts = StaticOptions(level=o.level, seed_load_case=o.seed_load_case)
        res = solve_static(variant, list(o.design_rpm), sopts, cache_dir=o.cache_dir)
        ref = static_cache.store(variant, sopts, res, o.cache_dir)   # the fatigue input
    if o.estimate_error:
        with prog.stage(ERROR_STAGE):
            import dataclasses

            from shaftfe.static.error import estimate_error
            ee = estimate_error(res, variant, sopts, o.cache_dir,
                                 other_level=OTHER_LEVEL[o.level])
            res = dataclasses.replace(res, error_estimate=ee)
    st = _static_summary(res, variant)
    with prog.stage("fatigue"):
        fat, ff = _fatigue(ref, history, material, o)
        from shaftfe.fatigue.field import hot_spot_with_factor
        life = {"theory": o.mean_stress, "design_life_blocks": o.design_life_blocks,
                "speed_kmh": o.speed_kmh}
        bench = benchmark_errors(o.level) if not o.estimate_error else None
        from shaftfe.fatigue.run import level_corrected_life
        corrected = level_corrected_life(ref, ff, history, material, bench, res.n_dofs, **life)
        scaled = corrected[1] if corrected else None
        if scaled is None and res.error_estimate:
            e = res.error_estimate["cases"][0]["peak_von_mises"]
            ours = res.cases[0].peak_von_mises_MPa
            if e and ours and e["extrapolated"]:
                scaled = hot_spot_with_factor(ref, ff, history, material,
                                              e["extrapolated"] / ours, **life)
        fat["life_if_peak_corrected"] = scaled
    with prog.stage("Campbell"):
        camp, cres, rotor_model = _campbell(variant, engine, o)
    with prog.stage("VTU"):
        from shaftfe.io import vtu as export
        rpm_vtu = float(o.design_rpm[0])
        vtu = out / f"{variant.name}.vtu"
        r = ff.result
        _, regions = export.write_vtu(res, vtu, rpm_vtu, extra_point_data={
            "safety_factor": r.safety_factor, "life_blocks": r.life_blocks,
            "damage_per_block": r.damage_per_block})
        modes_vtu = out / "modes.vtu"                  # mode shapes: a file of their own
        modes = beam_mode_fields(rotor_model, cres, res.mesh.mesh.doflocs)
        if o.rotor_model == "solid":                   # 3D modes on the rotor's own mesh
            from shaftfe.rotordynamics.modes_vtu import write_modes_vtu
            write_modes_vtu(rotor_model, cres, modes_vtu)
        else:                                          # beam modes on the static mesh
            export.write_fields_vtu(res.mesh.mesh, modes_vtu, modes)
    with prog.stage("3D pictures"):
        pics = _pictures(o, vtu, fig_dir, ff, rpm_vtu, st) if o.pictures else []
        for name, title, caption in pics:
            add_fig(name, title, caption)
    with prog.stage("plots"):
        _plots(o, out, fig_dir, variant, fres, sw, res, ff, history, material, cres, camp,
               rpm_vtu, add_fig)
    errs = _error_estimates(st, res, fat, scaled, bench, camp, beam_out)
    comps = comparisons(bal, beam_out, st, fat, camp, variant, seedmod)
    d = getattr(res, "run", {})
    sub = {"mesh": d.get("mesh_seconds"), "mesh from cache": bool(d.get("mesh_from_cache")),
           "assembly": d.get("assembly_seconds"), "factorisation": d.get("factor_seconds"),
           "solves": d.get("solve_seconds"), "stress recovery": d.get("recovery_seconds"),
           "static total": d.get("total_seconds"), "fatigue evaluation": ff.seconds}
    inputs = {
        "variant": variant.name, "description": variant.description,
        "files": list(variant.source_files), "content_hash": variant.content_hash,
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
        "engine": engine.name, "engine_file": repo_relative(engine.source),
        "spectrum": fat["history"]["source"], "design_rpm": list(o.design_rpm),
        "spectrum_comments": file_comments(o.spectrum),
        "campbell_range_rpm": [0.0, float(engine.max_rpm)],
    }
    files = {"vtu": vtu.name, "vtu_rpm": rpm_vtu, "regions": regions,
             "figures_dir": "figures", "mode_fields": list(modes),
             "mode_rpm": float(cres.rpm[0]),
             "mode_note": "mode shapes of the beam rotor model at mode_rpm mapped onto the 3D "
                          "mesh (rigid cross-sections), largest displacement 1"
             if modes else "3D mode shapes of the solid rotor model on its own mesh",
             "modes_vtu": modes_vtu.name}
    notes = tuple(dict.fromkeys(list(res.notes) + list(ref.notes)))
    return Report(
        options=o, created_utc=datetime.datetime.now(datetime.UTC).strftime(
            "%Y-%m-%d %H:%M UTC"),
        inputs=inputs, provenance=prov, balancing=bal, beam=beam_out, static=st, fatigue=fat,
        campbell=camp, comparisons=tuple(comps), errors=tuple(errs),
        timings=prog.timings, sub_timings=sub, figures=tuple(figs), files=files,
        notes=notes, machine=machine)


def _pictures(o, vtu: Path, fig_dir: Path, ff, rpm: float, st: dict) -> list[tuple]:
    import numpy as np

    from shaftfe.io.render import render

    excl = np.flatnonzero(ff.excluded_mask)
    size = (1000, 440)
    out = []
    shots = (
        ("von_mises_3d", "von_mises", 0.0, "von Mises stress",
         f"von Mises stress at {rpm:g} rpm [MPa]; hot spot = the largest value outside the "
         f"singular points ({len(excl)} nodes at the bearing-coupling and load-patch edges "
         "excluded, as the static and fatigue analyses)."),
        ("displacement_3d", "displacement", "auto", "deflection",
         f"displacement magnitude at {rpm:g} rpm [mm] on the shape deformed ×(auto) — bearing "
         "springs included, so the shaft also moves as a body on its springs."),
        ("safety_factor_3d", "safety_factor", 0.0, "fatigue safety factor",
         f"fatigue safety factor at {o.design_life_blocks:g} blocks [-]; hot spot = the minimum "
         "outside the singular points."),
    )
    for name, fld, warp, title, caption in shots:
        res = render(vtu, field=fld, warp=warp, screenshot=fig_dir / f"{name}.png",
                     window_size=size, off_screen=True, hot_exclude=excl, zoom=1.9)
        if res.hot is not None:
            unit = f" {res.field.unit}" if res.field.unit not in ("-", "id") else ""
            caption += f" Marked: {res.hot.value:.4g}{unit} at x = {res.hot.xyz[0]:.1f} mm."
        out.append((name, title, caption))
    return out


def _plots(o, out, fig_dir, variant, fres, sw, res, ff, history, material, cres, camp,
           rpm_vtu, add_fig) -> None:
    from shaftfe.balance import plots
    from shaftfe.fatigue import kernels
    from shaftfe.fatigue import plots as fatigue_plots
    from shaftfe.fatigue.counting import rainflow_matrix
    from shaftfe.io import vtu as export
    from shaftfe.rotordynamics.plots import plot_campbell
    from shaftfe.util.atomic import write_atomic

    plots.plot_forces(fres, fig_dir / "balance_forces.png")
    add_fig("balance_forces", "shaking forces over one revolution",
            f"{fres.engine}, crank C X = {100 * fres.X:.1f} %, balancer X2 = "
            f"{100 * fres.X2:.2f} % (this variant), {fres.rpm:g} rpm, engine frame (tilt "
            f"{fres.tilt_deg:g}°): Fx, Fy, |F| [N] against the crank angle [°]; polar plot of "
            "|F| against its direction; hodograph Fy(Fx) [N].")
    plots.plot_sweep(sw, fig_dir / "balance_sweep.png")
    add_fig("balance_sweep", "balancing curves over X2",
            f"max|Fx|, max|Fy|, RMS|F|, max|F| [N] against the balancer ratio X2 [%] for crank "
            f"C (X = {100 * sw.X[0]:.1f} %), {sw.rpm:g} rpm, cylinder frame (as the seed's "
            "fig. 58: x across, y along the cylinder axis).")
    export.plot_png(res, fig_dir / "deflection.png", rpm_vtu)
    add_fig("deflection", "deflection line and stress envelope",
            f"{rpm_vtu:g} rpm: deflection of the axis [µm] (3D FE and beam, bearing springs) "
            "and the largest von Mises stress [MPa] in each 1 mm slice along the shaft x [mm].")
    camp_png = plot_campbell(cres, title=f"{variant.name}: Campbell diagram "
                             f"({o.rotor_model} model)")
    write_atomic(fig_dir / "campbell.png", camp_png)
    add_fig("campbell", "Campbell diagram",
            "damped natural frequencies [Hz] against the speed [rpm], branches by whirl "
            "(forward / backward), engine-order lines k × n/60 and critical speeds (X).")
    hot = ff.hot_spot
    s_hot = hot.sigma_eq_ref_MPa
    lbl = f"{hot.region} x = {hot.xyz_mm[0]:.1f} mm"
    r = ff.result
    fatigue_plots.plot_load_history(history, fig_dir / "load_history.png")
    add_fig("load_history", "rpm history (one block)",
            f"{Path(history.source).name}: engine speed [rpm] and load factor (rpm/ref)² [-] "
            "against time [s].")
    fatigue_plots.plot_cycle_matrix(
        rainflow_matrix(r.cycles, scale=s_hot if s_hot != 0 else 1.0),
        fig_dir / "rainflow_matrix.png",
        title=f"rainflow matrix per block, hot spot {lbl}")
    add_fig("rainflow_matrix", "rainflow matrix",
            "cycles per block at the hot spot by stress range and mean [MPa].")
    fatigue_plots.plot_cycle_matrix(
        kernels.damage_matrix(s_hot, r.cycles, material, o.mean_stress, 1.0),
        fig_dir / "damage_matrix.png", title=f"damage matrix per block, hot spot {lbl}")
    add_fig("damage_matrix", "damage matrix",
            "Miner damage per block at the hot spot by stress range and mean [MPa].")
    fatigue_plots.plot_haigh(s_hot, r.cycles, material, fig_dir / "haigh.png",
                             o.mean_stress, 1.0)
    add_fig("haigh", "Haigh diagram",
            f"the hot spot's cycles (mean, amplitude) [MPa] and the {o.mean_stress} line.")
    fatigue_plots.plot_sn_curve(material, fig_dir / "sn_curve.png")
    add_fig("sn_curve", "S-N curve", f"{material.name}: alternating stress [MPa] against "
            "cycles to failure [-].")
