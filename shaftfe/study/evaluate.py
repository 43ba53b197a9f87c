"""One design of a study → one result row (a flat dict of numbers and strings).

Every number comes from the package's own analyses, the ones the commands use:

* balance: the design's mass properties (``model.mass``) and X2 = Σ m e / (m_pos R); the
  engine's shaking force max|F| and RMS|F| over one revolution at the engine's speed
  (``balance.single.forces``, crank balance X of the seed's crank C unless given);
* beam: the Euler-Bernoulli shaft on its bearing springs at ``bearing_rpm``: bearing loads and
  ISO 281 L10h, the largest Kt × nominal stress;
* static: the 3D solid (``static.solve.solve_static``), or the zoned model with
  ``analyses.static.model = "zoned"`` (``zoned.solve.solve_zoned``), at 10 000 rpm (the fatigue
  reference) and ``bearing_rpm`` (the zoned model: its global model there, the reactions):
  the filtered von Mises peak of every fillet and keyway, L10h from the static reactions
  (replacing the beam's);
* fatigue: the study's method (the seed's by default, ``fatigue.field.evaluate``) on that
  field: the governing place's safety factor and life in blocks, hours and km;
* campbell: the beam rotor's first forward 1× critical speed and its margin over the engine's
  max_rpm.

A design the loader refuses (an impossible combination of values) has status ``refused``; one
whose analysis fails (a mesh that cannot be built, a solver failure) ``failed``; both with the
one-line reason in ``error``. Everything the row holds is the same on every run (the wall time
is in ``seconds``, not part of the cache key).
"""

from __future__ import annotations

import functools
import math
import time
from typing import Any

from shaftfe.errors import InputError, ShaftfeError
from shaftfe.fe import reuse
from shaftfe.solid.features import is_notch, kind_of
from shaftfe.study.spec import Analyses, refusal

# The Campbell sweep's default top: a stiff balancer shaft's first bending critical lies far
# above the engine's speeds (x2_57 beam rotor: 39 700 rpm, 4.2 × the VM 450's 9500 rpm), and a
# beam sweep to 60 000 rpm costs ~0.3 s. A critical above the top is reported as None.
CAMPBELL_TOP_RPM = 60_000.0


def _fin(v) -> float | None:
    """A number for the table: ±inf kept (an infinite life is a result), NaN → None."""
    v = float(v)
    return None if math.isnan(v) else v


@functools.lru_cache(maxsize=4)
def _engine(name: str):
    from shaftfe.balance.engines import load_engine
    return load_engine(name)


@functools.lru_cache(maxsize=2)
def _fatigue_inputs(spectrum: str, material: str):
    """The history and S-N card, read once per worker process (every design shares them)."""
    from shaftfe.fatigue.run import read_spectrum
    from shaftfe.fatigue.sn import load_material
    return read_spectrum(spectrum, None, None), load_material(material)


def load_design(base: str, overrides, fatigue: bool = False) -> tuple[Any, dict]:
    """(Variant, every override incl. the derived ones) of a design; InputError if refused.
    ``fatigue``: the study assesses fatigue, so a loaded sharp corner (a zero fillet) refuses
    the design, as it refuses ``shaftfe fatigue`` (``solid.plan.refuse_sharp_corners``)."""
    from shaftfe.model.derive import design_overrides
    from shaftfe.model.loader import load_variant
    from shaftfe.solid.plan import refuse_sharp_corners
    full = design_overrides(base, dict(overrides))
    v = load_variant(base, full)
    if fatigue:
        refuse_sharp_corners(v, "the study's fatigue check")
    return v, full


def balance_row(v, an: Analyses) -> dict:
    from shaftfe.balance.single import forces
    from shaftfe.model.mass import mass_properties, variant_x2
    from shaftfe.report.seed import CRANK_C_X
    mp = mass_properties(v)
    eng = _engine(an.engine)
    x2 = variant_x2(v, mp, default=eng.X2 if eng.X2 is not None else 0.0)
    rpm = an.engine_rpm or eng.rpm
    X = an.X_percent / 100 if an.X_percent is not None else CRANK_C_X
    res = forces(eng, X=X, X2=x2, rpm=rpm)
    return {"mass_kg": mp.mass_kg, "gamma2_mm": mp.gamma2_mm, "x_T_mm": mp.x_T_mm,
            "X2_percent": 100 * x2, "engine_rpm": rpm, "engine_max_F_N": res.metrics.max_f,
            "engine_rms_F_N": res.metrics.rms_f}


def _bearing_cols(rows, prefix: str) -> dict:
    out = {f"L10h_{b.name}_h": _fin(b.L10h) if b.L10h is not None else None for b in rows}
    out.update({f"{prefix}F_{b.name}_N": float(getattr(b, "F_N", None) or b.F_radial_N)
                for b in rows})
    lives = [x for x in (out[f"L10h_{b.name}_h"] for b in rows) if x is not None]
    out["L10h_min_h"] = min(lives) if lives else None
    return out


def beam_row(v, an: Analyses) -> dict:
    from shaftfe.beam.solve import analyse
    vv = v.with_seed_load_case() if an.seed_load_case else v      # as the static row's
    br = analyse(vv, an.bearing_rpm, seed_placement=an.seed_load_case)[0]
    out = {"beam_max_peak_MPa": br.max_peak_MPa, "beam_max_deflection_mm": br.max_deflection_mm}
    out.update(_bearing_cols(br.bearings, "beam_"))
    return out


def static_rows(v, an: Analyses, shaft_mesh=None, cache_dir=None) -> tuple[dict, Any]:
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import solve_static
    from shaftfe.util.units import REF_RPM
    opts = StaticOptions(level=an.level, spin_softening=an.spin_softening,
                         seed_load_case=an.seed_load_case)
    rpms = [REF_RPM] if an.bearing_rpm == REF_RPM else [REF_RPM, an.bearing_rpm]
    if an.static_model == "zoned":
        return _zoned_rows(v, an, opts, rpms, cache_dir)
    res = solve_static(v, rpms, opts, shaft_mesh=shaft_mesh, cache_dir=cache_dir, beam=False,
                       linear_stress=an.fatigue)
    ref = res.cases[0]
    out: dict[str, Any] = {"n_dofs": res.n_dofs, "mesh_key": res.mesh_key}
    for p in ref.peaks:
        if is_notch(p.region):
            out[f"stress_{p.region}_MPa"] = _fin(p.von_mises_MPa)
    out["stress_max_MPa"] = _fin(ref.peak_von_mises_MPa)
    at = next(c for c in res.cases if c.rpm == an.bearing_rpm)
    out.update(_bearing_cols(at.bearings, "static_"))
    out["static_max_deflection_mm"] = res.cases[0].max_deflection_mm
    return out, res


def _zoned_rows(v, an: Analyses, opts, rpms, cache_dir) -> tuple[dict, Any]:
    """``static_rows`` of the zoned model (``shaftfe.zoned``): the same columns; n_dofs is the
    global model's and the zones' together, mesh_key the zones' (the global meridian mesh
    follows from the same drawing). With spin softening (each speed its own global solve) the
    zones are solved at the reference speed only: the bearing speed's columns (the reactions)
    are the global model's, which is all a zoned case takes them from, so that speed is the
    global solve alone (its harmonic factorisations shared by ``evaluate_design``'s
    ``fe.reuse`` scope) and no zone is solved for it. Without it one global solve serves both
    speeds, as ``solve_zoned`` does."""
    from shaftfe.axisymmetric.solve import solve_axisymmetric
    from shaftfe.zoned.solve import solve_zoned
    if not opts.spin_softening:
        # unsoftened, one global solve serves every speed (``solve_zoned``): as it was
        res = solve_zoned(v, rpms, opts, cache_dir=cache_dir)
        at = next(c for c in res.cases if c.rpm == an.bearing_rpm)
    else:
        res = solve_zoned(v, rpms[:1], opts, cache_dir=cache_dir)
        at = res.cases[0] if an.bearing_rpm == rpms[0] else solve_axisymmetric(
            v, an.bearing_rpm, res.global_result.options,
            cache_dir=cache_dir).case(an.bearing_rpm)
    c0 = res.cases[0]
    g = res.global_result
    out: dict[str, Any] = {
        "n_dofs": 3 * g.n_nodes * len(g.harmonics) + sum(z.n_dofs for z in res.zones),
        "mesh_key": "zoned:" + ",".join(f"{z.name}@{z.x_mm[0]:g}-{z.x_mm[1]:g}"
                                        for z in res.zones)}
    for p in c0.peaks:
        if is_notch(p.region):
            out[f"stress_{p.region}_MPa"] = _fin(p.von_mises_MPa)
    out["stress_max_MPa"] = _fin(max((p.von_mises_MPa for p in c0.peaks
                                      if kind_of(p.region) != "end"), default=None))
    out.update(_bearing_cols(at.bearings, "static_"))
    out["static_max_deflection_mm"] = c0.max_axis_deflection_mm
    return out, res


def _field(res, an: Analyses, variant, cache_dir=None):
    """The fatigue input of a design's static result: the 3D one's reference, or the zoned
    one's surface reference with its unsoftened stress (one more zoned solve at 10 000 rpm on
    the same factorised zones, ``fatigue.run.surface_reference``)."""
    from shaftfe.static.cache import from_result
    if an.static_model != "zoned":
        return from_result(res)
    from shaftfe.fatigue.run import surface_reference
    from shaftfe.util.units import REF_RPM
    from shaftfe.zoned.reference import zoned_reference
    from shaftfe.zoned.solve import solve_zoned

    def make(o):
        same = o.spin_softening == res.options.spin_softening
        return zoned_reference(res if same else solve_zoned(variant, REF_RPM, o,
                                                            cache_dir=cache_dir, reuse=res))
    return surface_reference(make, res.options)


def fatigue_row(res, an: Analyses, variant=None, cache_dir=None) -> dict:
    """The fatigue columns: the study's method (``analyses.fatigue.method``, by name from
    ``fatigue.methods``) on the design's static field; its governing location (a limit check
    such as DIN 743 has a safety and no life: the life columns are empty)."""
    from shaftfe.fatigue.methods import AssessmentInputs, get_method
    from shaftfe.fatigue.run import FatigueJob
    history, _ = _fatigue_inputs(an.spectrum, an.material)
    job = FatigueJob(spectrum=an.spectrum, material=an.material, mean_stress=an.mean_stress,
                     equivalent=an.equivalent, design_life=an.design_life,
                     speed_kmh=an.speed_kmh, level=an.level, spin_softening=an.spin_softening,
                     engine=an.engine, seed_load_case=an.seed_load_case,
                     model=an.static_model)
    got = get_method(an.fatigue_method, "study", "analyses.fatigue.method").assess(
        AssessmentInputs.one_channel(variant, history,
                                     field=_field(res, an, variant, cache_dir)), job)
    g = got.governing
    return {"fatigue_hot_spot": g.name, "fatigue_sf": _fin(g.safety),
            "life_blocks": _fin(g.life_blocks), "life_h": _fin(g.life_hours),
            "life_km": _fin(g.life_km)}


def campbell_row(v, an: Analyses) -> dict:
    import numpy as np

    from shaftfe.rotordynamics.analyse import analyse
    from shaftfe.rotordynamics.options import RotorOptions
    eng = _engine(an.engine)
    n_max = float(eng.max_rpm or 0.0)
    top = an.campbell_max_rpm or CAMPBELL_TOP_RPM
    rpms = np.linspace(0.0, top, max(2, round(top / an.campbell_step_rpm) + 1))
    run = analyse(v, rpms, 6, orders=(1.0,), options=RotorOptions(model=an.campbell_model),
                  verify=False)
    crit = [c for c in run.result.criticals if c.whirl != "backward"]
    first = min((c.rpm for c in crit), default=None)
    return {"critical_rpm": first, "critical_margin_percent":
            (100.0 * (first / n_max - 1.0) if first is not None and n_max > 0 else None),
            "campbell_top_rpm": float(rpms[-1])}


def group_of(v, level: str) -> tuple:
    """(mesh key, E, ν) of a loaded design's solid: the designs that share one mesh and one
    factorisation."""
    from shaftfe.static.cache import predicted_mesh_key
    from shaftfe.static.model import StaticOptions
    return (predicted_mesh_key(v, StaticOptions(level=level)), v.material.E_MPa, v.material.nu)


def evaluate_design(base: str, overrides, an: Analyses, *, shaft_mesh=None,
                    cache_dir=None) -> dict:
    """The result row of one design (never raises for the design's own faults)."""
    t0 = time.perf_counter()
    row: dict[str, Any] = {"status": "ok", "error": ""}
    try:
        v, _ = load_design(base, overrides, an.static and an.fatigue)
    except InputError as exc:
        return {"status": "refused", "error": refusal(None, overrides, exc)[0],
                "seconds": time.perf_counter() - t0}
    row["variant_hash"] = v.content_hash
    try:
        row.update(balance_row(v, an))
        if an.beam:
            row.update(beam_row(v, an))
        if an.static:
            # one design is one shaft: its static row (every speed) and fatigue's reference
            # share what ``fe.reuse`` keeps (a study's group or worker scope when one is open)
            with reuse.shared():
                cols, res = static_rows(v, an, shaft_mesh, cache_dir)
                row.update(cols)
                if an.fatigue:
                    row.update(fatigue_row(res, an, v, cache_dir))
                del res
        if an.campbell:
            row.update(campbell_row(v, an))
    except (ShaftfeError, ArithmeticError, RuntimeError, ValueError) as exc:
        msg = " ".join(str(exc).split()) or type(exc).__name__
        row.update(status="failed", error=msg if isinstance(exc, ShaftfeError)
                   else f"{type(exc).__name__}: {msg}")
    row["seconds"] = time.perf_counter() - t0
    return row
