"""The fatigue job as an API: ``run_fatigue(FatigueJob(...))`` → ``FatigueRun``.

The static reference solution (3D FE at ``shaftfe.static.model.REF_RPM``) comes from the disk
cache of ``shaftfe.static.cache`` when the model is unchanged, else it is solved once. The
history's load factor is re-referenced to the static solution's speed, every node is evaluated
at once (``shaftfe.fatigue.field``), and where the static benchmark measured this mesh level's
peak-stress error (``shaftfe.static.measured_errors``) the hot spot's life is also given with the
stress corrected by it. ``shaftfe.fatigue.outputs`` writes the files; ``shaftfe fatigue`` is a
thin command over both.

Defaults = the seed's settings (SPEC §3): von Mises, Soderberg, Ansys "Structural Steel",
design life 1e7 blocks, 70 km/h, bearing springs; every part of the variant loads the shaft
(``seed_load_case=True``: only the forces the seed applied).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

from shaftfe.errors import InputError, SolverError
from shaftfe.fatigue.assess import DEFAULT_DESIGN_LIFE_BLOCKS
from shaftfe.fatigue.kernels import EQUIVALENT_STRESSES, MEAN_STRESS_THEORIES
from shaftfe.fe import reuse
from shaftfe.solid.levels import LEVEL_NAMES
from shaftfe.static import MODELS, STATIC_MODELS
from shaftfe.util.fmt import LIFE_MAX
from shaftfe.util.limits import OVERSPEED_HINT, check_exclude_mm

MEAN_STRESS = MEAN_STRESS_THEORIES
# the seed's von Mises and its signed variant; the hydrostatic-signed kind is for studies
# through the API (shaftfe.fatigue.kernels.EQUIVALENT_STRESSES)
EQUIVALENT = EQUIVALENT_STRESSES[:2]
SEED_RPM_REF = 7000.0     # a normalised history without a stated reference: the seed's

# The design life. The seed's is 1e7 blocks (passes of the history; 833 333 h of its 300 s
# block); a user states it in blocks (--design-life) or in hours of riding (--design-life-h).
# ONE rule for both forms, checked once the history (its block duration) is known
# (``design_life_range``): at least one pass of the history (less is no design life), and at
# most ``util.fmt.LIFE_MAX`` = 1e9 in blocks AND in hours, the bound past which every life is
# printed as "no finite life at this load": S-N data end by 1e9 cycles and every block holds at
# least one load cycle, so a longer design life is an extrapolation of a curve with no data
# (1e300 printed a utilisation of 1.5e6). Of the seed's 300 s block: [1, 1e9] blocks =
# [0.0833, 8.33e7] h. Before the history is read each form is checked against the part of the
# rule that needs no block duration (``check_life_settings``).
DESIGN_LIFE_BLOCKS = (1.0, LIFE_MAX)
# --speed-kmh, the average riding speed that turns hours into km: (0, 400] km/h (the fastest
# production motorcycles top out near 300 km/h; an average is far below)
SPEED_KMH_MAX = 400.0

# The seed's result (seed 000 §8.3) for the side-by-side comparison.
# the variant the seed's static, fatigue and rotor-dynamics studies are of (X2 = 57 %;
# ``report.seed.VARIANT``): the seed's figures stand beside ours for this variant only
SEED_VARIANT = "x2_57"
SEED = {"safety_factor_at_1e7": 0.7, "life_blocks": 25_000.0, "life_hours": 2083.0,
        "life_km": 145_810.0,
        "hot_spot": "fillet at the heavier counterweight (the collar fillet on the "
                    "counterweight-2 side, x ≈ 64.5 mm)",
        "hot_spot_x_mm": 64.5}
# the seed's Ansys static had no spin softening (forces at the undeformed seats)
SEED_SETTINGS = {"mean_stress": "soderberg", "equivalent": "von_mises",
                 "material": "structural_steel", "design_life": 1e7, "kf": 1.0,
                 "seed_load_case": True, "spin_softening": False}


@dataclass(frozen=True)
class FatigueJob:
    """What to assess (the command's options, with the same names)."""
    spectrum: str                          # rpm history file (shaftfe.fatigue.history)
    variant: str = "x2_57"                 # variant name or path
    ref_rpm: float | None = None           # reference of a normalised history
    sample_rate: float | None = None       # Hz, for a file without a header
    mean_stress: str = "soderberg"
    equivalent: str = "von_mises"
    material: str | None = None            # S-N card in geometry/common/sn_curves.toml; None:
    #                                        the variant's (fatigue.sn.variant_card)
    design_life: float | None = None       # blocks; None: design_life_h, else 1e7 (the seed's)
    speed_kmh: float = 70.0
    kf: float = 1.0                        # fatigue strength factor in (0, 1]
    level: str = "default"                 # mesh level
    exclude_mm: float = 0.0                # extra band around patch edges (filtered hot spot)
    seed_load_case: bool = False
    cache_dir: str | None = None
    model: str | None = None               # static model: zoned | solid | axisymmetric;
    #                                        None: ``resolve_model`` (zoned)
    spin_softening: bool = True            # the parts' m ω² u (static model; README)
    overrides: tuple[str, ...] = ()        # --set PATH=VALUE on the variant (model.overrides)
    design_life_h: float | None = None     # hours of riding; with design_life=None
    engine: str | None = None              # whose max_rpm bounds the history (check_history);
    #                                        None: the variant's [duty] speed range
    allow_overspeed: bool = False          # assess a history above max_rpm (with a warning)
    # the standards' options (FKM, DIN 743: fatigue.strength.strength_options)
    card: str | None = None                # strength card; None: the variant's shaft material
    miner: str = "modified"                # FKM governing Miner rule
    consequences: str = "severe"           # FKM j_D
    inspection: bool = False               # FKM j_D with regular inspections
    damage_sum: float = 0.3                # FKM effective damage sum D_M
    kappa: float | None = None             # ISO 281 κ of the bearings (None: the default)
    ec: float | None = None                # ISO 281 e_C (None: the default)
    case: str | None = None                # a [[load_cases]] name: static S_F on it (DIN 743)
    plot: bool = False                     # DIN 743: the safety at every cross-section


@dataclass(frozen=True, eq=False)
class FatigueRun:
    """A finished assessment: its inputs and every result the outputs are made of."""
    job: FatigueJob
    variant: object                        # shaftfe.model.variant.Variant
    history: object                        # shaftfe.fatigue.history.LoadHistory
    material: object                       # shaftfe.fatigue.sn.FatigueMaterial
    ref: object                            # shaftfe.static.cache.StaticReference
    field: object                          # shaftfe.fatigue.field.FatigueField
    eval_seconds: float
    level_error: dict | None               # the level-corrected hot spot (see module doc)


def design_life_range(block_seconds: float) -> tuple[float, float]:
    """The design life's bounds in blocks of a history whose block lasts ``block_seconds``:
    one pass of the history up to ``LIFE_MAX`` blocks and ``LIFE_MAX`` hours, whichever is less
    (the rule above ``DEFAULT_DESIGN_LIFE_BLOCKS``)."""
    lo, hi = DESIGN_LIFE_BLOCKS
    return lo, min(hi, LIFE_MAX * 3600.0 / block_seconds)


def _refuse_design_life(option: str, got: float, block_seconds: float | None,
                        reason: str | None = None):
    """The one message of the design-life rule, in the unit of the option typed."""
    if block_seconds is None:
        allowed = (f"a number of blocks in [{DESIGN_LIFE_BLOCKS[0]:g}, {LIFE_MAX:g}]"
                   if option == "--design-life" else f"hours of riding in (0, {LIFE_MAX:g}]")
    else:
        lo, hi = design_life_range(block_seconds)
        h = block_seconds / 3600.0
        allowed = (f"[{lo:g}, {hi:.4g}] blocks = [{lo * h:.4g}, {hi * h:.4g}] h"
                   if option == "--design-life" else
                   f"[{lo * h:.4g}, {hi * h:.4g}] h = [{lo:g}, {hi:.4g}] blocks")
        allowed += f" of the {block_seconds:g} s history"
    allowed += (" (one pass of the history up to 1e9 blocks and 1e9 h: S-N data end by 1e9 "
                "cycles; a longer life is printed as no finite life)")
    return InputError("command line", option, allowed, got=got, reason=reason)


def check_life_settings(design_life: float | None, speed_kmh: float,
                        design_life_h: float | None = None) -> None:
    """The design life (blocks, or hours) and the speed that turns hours into km: what of the
    design-life rule needs no history (``resolve_design_life`` applies the rest), and
    ``SPEED_KMH_MAX`` (shared by ``shaftfe fatigue`` and ``shaftfe report``)."""
    if design_life is not None and design_life_h is not None:
        raise InputError("command line", "--design-life", "either --design-life (blocks) or "
                         "--design-life-h (hours), not both", got=design_life)
    lo, hi = DESIGN_LIFE_BLOCKS
    if design_life is not None and not (math.isfinite(design_life) and lo <= design_life <= hi):
        raise _refuse_design_life("--design-life", design_life, None)
    if design_life_h is not None and not (math.isfinite(design_life_h)
                                          and 0 < design_life_h <= LIFE_MAX):
        raise _refuse_design_life("--design-life-h", design_life_h, None)
    if not (math.isfinite(speed_kmh) and 0 < speed_kmh <= SPEED_KMH_MAX):
        raise InputError("command line", "--speed-kmh",
                         f"an average riding speed in (0, {SPEED_KMH_MAX:g}] km/h", got=speed_kmh)


def resolve_design_life(job: FatigueJob, history, duty=None) -> FatigueJob:
    """The job with its design life in blocks: ``design_life`` or ``design_life_h`` over the
    history's block length, each within ``design_life_range`` of this history; when neither is
    given, the variant's ``duty`` design life, else 1e7 blocks (the seed's, said in a
    warning)."""
    if job.design_life is None and job.design_life_h is None:
        if duty is not None and (duty.design_life_blocks or duty.design_life_h):
            job = replace(job, design_life=duty.design_life_blocks,
                          design_life_h=duty.design_life_h)
        else:
            from shaftfe.util.notices import warn
            warn("design-life-default", "fatigue", "the variant states no design life "
                 f"([duty] design_life_h): {DEFAULT_DESIGN_LIFE_BLOCKS:g} blocks of the "
                 "history assumed (the seed's); --design-life-h sets one")
    block = history.duration_s
    lo, hi = design_life_range(block)
    if job.design_life is not None:
        if not lo <= job.design_life <= hi:
            raise _refuse_design_life("--design-life", job.design_life, block,
                                      f"is {job.design_life * block / 3600.0:.3g} h")
        return job
    if job.design_life_h is None:
        return replace(job, design_life=DEFAULT_DESIGN_LIFE_BLOCKS)
    blocks = job.design_life_h * 3600.0 / block
    if not lo <= blocks <= hi:
        raise _refuse_design_life("--design-life-h", job.design_life_h, block,
                                  f"is {blocks:.3g} blocks")
    return replace(job, design_life=blocks)


def check_history(history, engine: str, allow_overspeed: bool, hint: str = OVERSPEED_HINT):
    """The speeds of a history for a stress or life assessment: some above 0 rpm (an engine
    at rest has no load: no damage, no bearing wear: nothing to assess) and none above the
    engine's max_rpm (``balance.engines.engine_speed_limit``) unless ``allow_overspeed``, then with
    a warning. Shared by ``shaftfe fatigue`` (every method) and ``shaftfe report``."""
    from shaftfe.balance.engines import check_operating_speed
    top = float(history.rpm.max())
    if not top > 0:
        raise InputError(history.source, "rpm", "a history with the engine turning (some "
                         "sample above 0 rpm)", reason="is 0 in every sample (the engine at "
                         "rest): no load in this history: no damage, no bearing wear")
    check_operating_speed(top, engine, allow_overspeed, history.source, "highest rpm",
                          hint=hint)


def check_model_level(model: str, level: str, allowed: tuple[str, ...] = MODELS) -> None:
    """--model one of ``allowed`` (``static.MODELS``; ``shaftfe fatigue`` also takes the zoned
    solve, ``static.STATIC_MODELS``) and --level one of that model's levels (shared by
    ``shaftfe fatigue`` and ``shaftfe report``)."""
    if model not in allowed:
        raise InputError("command line", "--model", " | ".join(allowed), got=model)
    if model == "axisymmetric":
        from shaftfe.axisymmetric.mesh import AXI_LEVELS
        names = tuple(AXI_LEVELS)
    else:
        names = LEVEL_NAMES
    if level not in names:
        raise InputError("command line", "--level", " | ".join(names), got=level)


DEFAULT_MODEL = "zoned"


def resolve_model(job: FatigueJob) -> FatigueJob:
    """``job`` with its static model, ``DEFAULT_MODEL`` when --model was not given: the zoned
    model for every variant (a load that does not scale with rpm² too: its reference holds the
    per-pattern fields the seed method assesses, ``fatigue.channel_run``, as the full 3D
    model's does)."""
    return job if job.model is not None else replace(job, model=DEFAULT_MODEL)


def check_job(job: FatigueJob) -> None:
    if job.mean_stress not in MEAN_STRESS:
        raise InputError("command line", "--mean-stress", " | ".join(MEAN_STRESS),
                         got=job.mean_stress)
    if job.equivalent not in EQUIVALENT:
        raise InputError("command line", "--equivalent", " | ".join(EQUIVALENT),
                         got=job.equivalent)
    check_model_level(job.model or DEFAULT_MODEL, job.level, STATIC_MODELS)
    check_life_settings(job.design_life, job.speed_kmh, job.design_life_h)
    if not (math.isfinite(job.kf) and 0 < job.kf <= 1):
        raise InputError("command line", "--kf", "a number in (0, 1]", got=job.kf)
    check_exclude_mm(job.exclude_mm)
    if job.sample_rate is not None:         # named by its option (the file's is "line N")
        from shaftfe.fatigue.history import check_sample_rate
        check_sample_rate(job.sample_rate, "command line", "--sample-rate")
    if job.ref_rpm is not None and not (math.isfinite(job.ref_rpm) and job.ref_rpm > 0):
        raise InputError("command line", "--ref-rpm", "a finite speed > 0 (rpm)",
                         got=job.ref_rpm)


def read_spectrum(path: str, ref_rpm: float | None, sample_rate: float | None):
    """The history; a normalised file without a reference (header or option) is taken as
    normalised to 7000 rpm, the seed's reference."""
    from shaftfe.fatigue.history import read_history
    try:
        return read_history(path, rpm_ref=ref_rpm, sample_rate_hz=sample_rate)
    except InputError as exc:
        if ref_rpm is None and exc.field == "reference_rpm":
            return read_history(path, rpm_ref=SEED_RPM_REF, sample_rate_hz=sample_rate)
        raise


def seed_applies(job, variant_name: str) -> bool:
    """The seed's x2_57 result is comparable only for variant x2_57, the seed's rpm.dat (same
    bytes) and the seed's settings (``SEED_SETTINGS``)."""
    from pathlib import Path

    from shaftfe.util.paths import DEFAULT_SPECTRUM
    try:
        same_file = Path(job.spectrum).read_bytes() == DEFAULT_SPECTRUM.read_bytes()
    except OSError:
        same_file = False
    return (variant_name == "x2_57" and same_file
            and all(getattr(job, k) == v for k, v in SEED_SETTINGS.items()))


def finite_or_none(v: float):
    return float(v) if math.isfinite(v) else None


def level_corrected_life(ref, ff, history, material, bench: dict | None, n_dofs: int,
                         **settings) -> tuple[dict, dict] | None:
    """The level's measured peak-stress error (``bench`` from
    ``shaftfe.static.measured_errors.benchmark_errors``: the collar fillet) and the hot spot's life
    and safety factor with its stress corrected by it (``fatigue.field.hot_spot_with_factor``);
    None where the benchmark does not cover this level's mesh. Shared by the report and
    ``run_fatigue``."""
    from shaftfe.fatigue.field import hot_spot_with_factor
    from shaftfe.static.measured_errors import bench_matches
    if bench is None or not bench_matches(bench, n_dofs):
        return None
    err = float(bench["collar"]["rel_error"])
    return ({"level": bench["level"], "stress_rel_error": err, "source": bench["source"]},
            hot_spot_with_factor(ref, ff, history, material, 1.0 / (1.0 + err), **settings))


def _level_correction(job: FatigueJob, ref, ff, history, material) -> dict | None:
    from shaftfe.static.measured_errors import benchmark_errors
    # measured on x2_57 as shipped: none for another shaft or a --set geometry
    bench = benchmark_errors(job.level, variant_hash=ref.variant_hash)
    got = level_corrected_life(ref, ff, history, material, bench,
                               3 * ref.n_nodes, equivalent=job.equivalent,
                               theory=job.mean_stress, kf=job.kf,
                               design_life_blocks=job.design_life, speed_kmh=job.speed_kmh)
    if got is None:
        return None
    meta, corr = got
    return {**meta, **{k: finite_or_none(v) for k, v in corr.items()}}


@dataclass(frozen=True, eq=False)
class FatigueInputs:
    history: object
    material: object
    variant: object


def load_inputs(job: FatigueJob) -> FatigueInputs:
    """The job's history, S-N material and variant (each InputError names its file)."""
    from shaftfe.model.loader import load_variant
    from shaftfe.solid.plan import refuse_sharp_corners
    check_job(job)
    variant = load_variant(job.variant, job.overrides)
    refuse_sharp_corners(variant, "a fatigue check")     # every method reads these inputs
    history = read_spectrum(job.spectrum, job.ref_rpm, job.sample_rate)
    check_history(history, job.engine or variant.duty, job.allow_overspeed)
    return FatigueInputs(history, sn_material(job, variant), variant)


def sn_material(job: FatigueJob, variant):
    """The seed method's S-N card: ``job.material``, else the variant's
    (``fatigue.sn.variant_card``)."""
    from shaftfe.fatigue.sn import load_material, variant_card
    return load_material(job.material or variant_card(variant))


def static_reference(variant, job: FatigueJob):
    """The static solution at its reference speed that fatigue scales: the 3D one from the
    static cache (solved once when missing), or the axisymmetric or zoned one on its surface
    (``axisymmetric.reference``, ``zoned.reference``) from the surface cache
    (``fatigue.surface_cache``; solved, softened and unsoftened, when missing)."""
    job = resolve_model(job)
    if job.model in ("axisymmetric", "zoned"):
        return _cached_surface_reference(variant, job)
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import load_or_solve
    extra = {"exclude_mm": job.exclude_mm} if job.exclude_mm > 0 else {}
    opts = StaticOptions(level=job.level, seed_load_case=job.seed_load_case,
                         spin_softening=job.spin_softening, **extra)
    return load_or_solve(variant, opts, job.cache_dir)


def _cached_surface_reference(variant, job: FatigueJob):
    """The axisymmetric or zoned surface reference at REF_RPM with its unsoftened stress: from
    the surface cache, else solved (``surface_reference``) and stored."""
    from shaftfe.fatigue import surface_cache
    from shaftfe.util.units import REF_RPM
    opts, solve, reference = surface_model(job.model, level=job.level,
                                           seed_load_case=job.seed_load_case,
                                           spin_softening=job.spin_softening,
                                           exclude_mm=job.exclude_mm)
    ref = surface_cache.load(job.model, variant, opts, REF_RPM, job.cache_dir)
    if ref is not None:
        return ref
    ref = surface_reference(lambda o: reference(solve(variant, REF_RPM, o,
                                                      cache_dir=job.cache_dir)), opts)
    return surface_cache.store(ref, job.model, variant, opts, job.cache_dir)


def surface_model(model: str, *, level: str, seed_load_case: bool, spin_softening: bool,
                  exclude_mm: float = 0.0):
    """(options, solve, reference) of a surface model (``fatigue.run.surface_reference``'s
    ``make`` is ``reference(solve(variant, rpm, options))``): the axisymmetric one or the
    zoned one."""
    if model == "axisymmetric":
        from shaftfe.axisymmetric.model import AxiOptions
        from shaftfe.axisymmetric.reference import static_reference as reference
        from shaftfe.axisymmetric.solve import solve_axisymmetric as solve
        opts = AxiOptions(level=level, seed_load_case=seed_load_case, exclude_mm=exclude_mm,
                          spin_softening=spin_softening)
    else:
        from shaftfe.static.model import StaticOptions
        from shaftfe.zoned.reference import zoned_reference as reference
        opts = StaticOptions(level=level, seed_load_case=seed_load_case,
                             exclude_mm=exclude_mm, spin_softening=spin_softening)
        solve = ZonedSolves()
    return opts, solve, reference


class ZonedSolves:
    """``solve_zoned`` that hands each solve the one before as ``reuse``: the unsoftened solve
    of ``surface_reference`` takes the softened one's submodels (the same zones, factorised
    once)."""

    def __init__(self) -> None:
        self.last = None

    def __call__(self, variant, rpm, options, **kw):
        from shaftfe.zoned.solve import solve_zoned
        self.last = solve_zoned(variant, rpm, options, reuse=self.last, **kw)
        return self.last


def surface_reference(make, opts):
    """``make(opts)`` (a surface reference of the axisymmetric or the zoned model, solved each
    time), with spin softening also the unsoftened stress on the same points (fatigue's
    S0 (λ + β λ²)): a second solve; the zoned one starts from the zones the first grew to, and
    points that differ anyway are refused in one line."""

    import numpy as np

    from shaftfe.util.units import rpm2_scale
    t0 = time.perf_counter()
    with reuse.shared():          # the second solve factorises what the first did not keep
        ref = make(opts)
        lin = make(replace(opts, spin_softening=False)) if opts.spin_softening else None
    if lin is not None:
        if lin.xyz.shape != ref.xyz.shape or not np.array_equal(lin.xyz, ref.xyz):
            raise SolverError("fatigue reference: the unsoftened solve's points differ from "
                              "the softened one's (the zones grew differently); use "
                              "--no-spin-softening or --model solid")
        # the unsoftened field is the linear one (∝ rpm²) at its own reference speed, which
        # need not be the softened one's (a report at its design speed): taken to that speed
        # and each load pattern's stress is the unsoftened solve's (at its written
        # magnitudes, as the full 3D reference holds it: ``fatigue.channel_run``)
        ref = replace(ref, stress_linear=lin.stress_ref * rpm2_scale(ref.ref_rpm,
                                                                     lin.ref_rpm),
                      patterns=lin.patterns, pattern_stress=lin.pattern_stress)
    return replace(ref, seconds=time.perf_counter() - t0)


def run_fatigue(job: FatigueJob, inputs: FatigueInputs | None = None,
                progress=None, ref=None) -> FatigueRun:
    """Read the inputs (unless given), load or solve the static reference (unless given as
    ``ref``: then no level correction either, the caller owns the field and its error),
    evaluate every node. ``progress``: a ``shaftfe.util.progress.Progress`` with the stages
    "history", "static" and "rainflow + life"."""
    from contextlib import nullcontext

    from shaftfe.fatigue.field import evaluate

    def stage(name):
        return progress.stage(name) if progress is not None else nullcontext()
    if inputs is None:
        with stage("history"):
            inputs = load_inputs(job)
    history, material, variant = inputs.history, inputs.material, inputs.variant
    job = replace(resolve_model(job), material=material.name)
    given = ref is not None
    if not (given and job.design_life is not None):
        # a caller with its own field (the report, a study) has checked its design life
        job = resolve_design_life(job, history, variant.duty)
    with stage("static"):
        ref = ref if given else static_reference(variant, job)
    with stage("rainflow + life"):
        t0 = time.perf_counter()
        ff = evaluate(ref, history, material, equivalent=job.equivalent,
                      theory=job.mean_stress, kf=job.kf, design_life_blocks=job.design_life,
                      speed_kmh=job.speed_kmh)
        t_eval = time.perf_counter() - t0
        level_error = _level_correction(job, ref, ff, history, material) \
            if job.model == "solid" and not given else None
    return FatigueRun(job, variant, history, material, ref, ff, t_eval, level_error)
