"""The zoned static solve (issue #32): the axisymmetric harmonic model of the whole shaft as the
global model (every load, the supports and the spin softening: reactions, deflections and every
rotationally symmetric notch), and a 3D submodel for each zone of features that are not bodies
of revolution (``zones``), driven by the global field at its cuts (``submodel``).

Each zone's cut is checked as submodeling practice asks (``submodel.CutCheck``: the submodel's
stresses on its cut faces against the global ones). A zone whose check exceeds ``CUT_TOL``
grows (``zones.grow``: its cut moves outward to the next admissible gap) until it passes or
reaches the shaft's ends. With ``sensitivity`` the peaks' change when the cut moves outward one
gap is measured too (one more submodel per zone).

Peaks: a region inside a zone (its faces are in the submodel) takes the submodel's peak; every
other region the global model's. Reactions, deflections and L10h are the global model's.
"""

from __future__ import annotations

import contextlib
import contextvars
import itertools
import math
import time
from dataclasses import asdict, dataclass, field

from shaftfe.axisymmetric.model import AxiOptions
from shaftfe.axisymmetric.solve import resolve_case, solve_axisymmetric
from shaftfe.beam.planes import mesh_hot_axes
from shaftfe.fe import reuse as fe_reuse
from shaftfe.model.loads import actions
from shaftfe.solid.features import by_region, features, keyway_region, kind_of
from shaftfe.solid.levels import LEVELS, level_name, mesh_level
from shaftfe.solid.mesh import mesh_plan
from shaftfe.solid.plan import plan_payload
from shaftfe.static.measured_errors import zone_bars, zone_feature_bars
from shaftfe.static.model import StaticOptions
from shaftfe.static.solve import _check_rpms
from shaftfe.util import paths
from shaftfe.util.atomic import write_atomic
from shaftfe.util.fmt import json_clean
from shaftfe.util.notices import warn
from shaftfe.util.units import REF_RPM
from shaftfe.zoned import submodel as sm
from shaftfe.zoned.zones import diameter_at, grow, plan_zones

# the cut check's bound: the largest difference of von Mises or σ_xx on a cut face, relative
# to the face's largest global von Mises. Measured on x2_57 (both zones, default level): 5.6 %
# with the submodel's default elements on the cut face (the difference is the two meshes'
# discretisation there: it does not fall when the cut moves a gap outward, 5.9 %), so the bound
# is set above that discretisation floor; a cut inside a feature's field exceeds it
CUT_TOL = 0.10
MAX_GROW = 3
CUT_CLEAR_D = 0.5      # × the local diameter: a round feature this near a cut is the global's


@dataclass(frozen=True)
class ZonedPeak:
    region: str
    kind: str                         # the feature's kind (``solid.features``), "" if none
    von_mises_MPa: float
    xyz_mm: tuple[float, float, float]
    max_principal_MPa: float
    max_principal_xyz_mm: tuple[float, float, float]
    model: str                        # "axisymmetric" or the zone's name


@dataclass(frozen=True)
class ZoneInfo:
    name: str
    features: tuple[str, ...]         # the regions of its cut features
    x_mm: tuple[float, float]
    cuts_mm: tuple[float, ...]
    nominal_mm: tuple[float, float]
    grown: int                        # how many times the cut check grew it
    n_dofs: int
    n_elements: int
    cut_checks: tuple                 # submodel.CutCheck (first speed)
    seconds: dict
    sensitivity: dict | None = None   # region -> relative change of its peak, cut moved out


@dataclass(frozen=True)
class ZonedCase:
    rpm: float
    scale: float
    bearings: tuple
    stations: tuple
    max_axis_deflection_mm: float
    peaks: tuple[ZonedPeak, ...]
    equilibrium_residual: float
    case: str = ""
    load_sum_N: tuple = ()              # the global model's (``AxiCase.load_sum_N``)


@dataclass(frozen=True, eq=False)
class ZonedResult:
    variant: str
    variant_hash: str
    options: StaticOptions
    axi_level: str
    zones: tuple[ZoneInfo, ...]
    cases: tuple[ZonedCase, ...]
    notes: tuple[str, ...]
    run: dict
    global_result: object = field(default=None, repr=False)     # axisymmetric AxiResult
    plan: object = field(default=None, repr=False)         # the mesh plan the zones are cut from
    fields: tuple = field(default=(), repr=False)               # (SubModel, SubField) per zone
    # the measured error bars of the span-fillet and groove peaks the global model gives
    # outside every 3D zone (``AxiResult.truth_error_bar_pct``) and of the rounded keyways'
    # and cross holes' peaks the zones give (``static.measured_errors.zone_bars``), and why such a
    # notch has none
    truth_error_bar_pct: dict = field(default_factory=dict)
    truth_bar_notes: dict = field(default_factory=dict)

    def case(self, rpm: float) -> ZonedCase:
        return next(c for c in self.cases if math.isclose(c.rpm, rpm))

    def to_dict(self) -> dict:
        g = self.global_result
        opts = {**asdict(self.options), "level": getattr(self.options.level, "name",
                                                         self.options.level)}
        return json_clean({
            "model": "zoned", "variant": self.variant, "variant_hash": self.variant_hash,
            "options": opts, "load_case": self.options.load_case,
            "global": {"model": "axisymmetric", "level": self.axi_level,
                       "nodes": g.n_nodes, "elements": g.n_elements,
                       "harmonics": list(g.harmonics)},
            "cut_tolerance": CUT_TOL,
            "zones": [asdict(z) for z in self.zones],
            "cases": [asdict(c) for c in self.cases],
            "truth_error_bar_pct": self.truth_error_bar_pct,
            "truth_bar_notes": self.truth_bar_notes,
            "notes": list(self.notes), "run": self.run,
        })


def _axi_options(o: StaticOptions, axi_level: str) -> AxiOptions:
    return AxiOptions(level=axi_level, rigid_supports=o.rigid_supports,
                      load_distribution=o.load_distribution, seed_load_case=o.seed_load_case,
                      exclude_mm=o.exclude_mm, spin_softening=o.spin_softening)


def _bands(variant, options) -> tuple:
    """The load bands that are not a part's seat (the seats are features already)."""
    acts, _ = actions(variant.with_seed_load_case() if options.seed_load_case else variant,
                      seed_placement=options.seed_load_case)
    return tuple(a.band_mm for a in acts if not a.seat)


def _grown(zone, plan, bands, times: int):
    """(``zone`` grown up to ``times`` gaps outward, how many it grew)."""
    n = 0
    while n < times:
        bigger = grow(zone, plan, bands)
        if bigger is None:
            break
        zone, n = bigger, n + 1
    return zone, n


def _solve_zone(variant, plan, zone, options, gsol, rpm, case, cache_dir):
    sub = sm.build_submodel(variant, plan, zone, options, cache_dir=cache_dir)
    return sub, sm.solve_speed(sub, gsol, rpm, case)


def _prebuild(v, plan, zones, bands, grown_before, options, cache_dir):
    """Start building each zone's submodel (mesh, stiffness, factorisation: nothing of the
    global field) in a worker thread while the global model solves: (pool, {zone name:
    (zone, grown, future)}), the zones at the size an earlier run's cut check grew them to."""
    if not zones:
        return None, {}
    from concurrent.futures import ThreadPoolExecutor
    # one worker: two (each factorisation on MKL's two threads) were slower on 2 cores
    # (x2_57 warm: 2.18 s with one, 2.51 s with two; 2.13 s with none). The largest zone goes
    # first; once the global model is done the solve builds every zone the worker has not
    # started yet itself (``_take``), so the smaller ones are built beside the largest
    pool = ThreadPoolExecutor(1)
    pre = {}
    grown = {z0.name: _grown(z0, plan, bands, grown_before.get(z0.name, 0)) for z0 in zones}
    for z0 in sorted(zones, key=lambda z0: -_volume(plan, grown[z0.name][0])):
        z, n = grown[z0.name]
        # in this run's context: a notice the build raises reaches its summary (util.notices)
        pre[z0.name] = (z, n, pool.submit(contextvars.copy_context().run,
                                          sm.build_submodel, v, plan, z, options,
                                          cache_dir=cache_dir))
    return pool, pre


def _volume(plan, zone) -> float:
    """The volume of the plain shaft between the zone's ends (mm³): which zone is the largest
    (the order they are built in; no result depends on it)."""
    xs = sorted({zone.x0, zone.x1, *(x for ab in plan.segment_x for x in ab
                                     if zone.x0 < x < zone.x1)})
    return sum(math.pi / 4 * (b - a) * diameter_at(plan, 0.5 * (a + b)) ** 2
               for a, b in itertools.pairwise(xs))


def _take(name, pre, v, plan, options, cache_dir):
    """The submodel of zone ``name`` from ``pre`` (``_prebuild``): built here where the worker
    has not started it yet; where the worker is on it, the zones it has not started are built
    here meanwhile (kept in ``pre`` as done). The same function on the same inputs: the same
    submodels, whichever thread builds them."""
    from concurrent.futures import Future
    z, grown, job = pre.pop(name)
    if job.cancel():
        return z, grown, sm.build_submodel(v, plan, z, options, cache_dir=cache_dir)
    for other, (zo, go, jo) in list(pre.items()):
        if not job.done() and jo.cancel():
            done = Future()
            done.set_result(sm.build_submodel(v, plan, zo, options, cache_dir=cache_dir))
            pre[other] = (zo, go, done)
    return z, grown, job.result()


def _reusable(reuse, variant, options) -> dict:
    """{zone name: (SubModel, times grown)} of ``reuse`` that a solve of ``variant`` (as the
    submodels see it: with the seed's load case applied where ``options`` asks) with
    ``options`` can take as they are: the same variant and options but spin softening (a
    submodel's stiffness has none: its softening enters as loads from the global motion,
    ``submodel.load_vector``), and a submodel built with softening (its seats' softening rows)
    serves both ways."""
    from dataclasses import replace
    if reuse is None:
        return {}
    out = {}
    for (sub, _), info in zip(reuse.fields, reuse.zones, strict=True):
        o = sub.options
        # the variant itself compared (a Variant made in Python has no content hash)
        if sub.variant == variant \
                and replace(o, spin_softening=options.spin_softening) == options \
                and (o.spin_softening or not options.spin_softening):
            out[sub.zone.name] = (sub, info.grown)
    return out


def _zone_peaks(sf: sm.SubField) -> dict:
    return {p.region: p for p in sf.peaks}


def solve_zoned(variant, rpm=REF_RPM, options: StaticOptions = StaticOptions(), *,
                axi_level: str = "default", case=None, cache_dir=None,
                sensitivity: bool = False, reuse: ZonedResult | None = None) -> ZonedResult:
    """Every speed in ``rpm`` (or the load case ``case``): the global axisymmetric solve, then
    each zone's submodel (one factorisation per zone, every speed).

    ``reuse``: an earlier zoned result of the same variant whose submodels this solve may take
    as they are (``_reusable``: the same zone, the same options but spin softening, which
    enters a submodel as loads, never in its stiffness): the unsoftened solve that fatigue's
    reference needs beside the softened one then factorises no zone again."""
    t0 = time.perf_counter()
    case = resolve_case(variant, case)
    rpms = _check_rpms(case.rpm if case is not None else rpm,
                       at_rest_loads=any(getattr(ld, "scales_with", "rpm2") != "rpm2"
                                         for ld in getattr(variant, "loads", ())))
    v = variant.with_seed_load_case() if options.seed_load_case else variant
    aopts = _axi_options(options, axi_level)
    plan = mesh_plan(v, options.level, mesh_hot_axes(v, cache_dir=cache_dir, use_cache=True))
    feats = by_region(features(plan))
    bands = _bands(variant, options)
    zones = plan_zones(plan, bands)
    _warn_grooves_in_zones(plan, zones, feats)
    t_plan = time.perf_counter() - t0
    memo = _growth_file(plan, bands, zones, options, cache_dir)
    grown_before = _read_growth(memo)
    grown_now: dict = {}
    cases, infos, fields, notes = [], [], [], []
    t_global = t_zones = 0.0
    subs: dict = {}
    fields_of: dict = {}                  # (zone, global solution, speed) -> SubField
    # the zones' submodels start building now, beside the global solve (``_prebuild``)
    ready = _reusable(reuse, v, options)
    pool, pre = _prebuild(v, plan, [z for z in zones if z.name not in ready], bands,
                          grown_before, options, cache_dir)
    # every speed's global solve shares the harmonic factorisations (spin softening is a
    # low-rank term: ``fe.reuse``), for as long as this solve runs
    scope = contextlib.ExitStack()
    scope.enter_context(fe_reuse.shared())
    try:
        # no softening and every load ∝ rpm² (or one case): one global solve serves each speed
        once = None
        if not options.spin_softening:
            once = solve_axisymmetric(variant, rpms, aopts, cache_dir=cache_dir, case=case)
            if case is None and not all(c.scales_with == "rpm2"
                                        for c in once.solution.columns.components):
                once = None                   # constant or channel loads: each speed its fields
        for r in rpms:
            t1 = time.perf_counter()
            g = once or solve_axisymmetric(variant, r, aopts, cache_dir=cache_dir, case=case)
            gc = g.case(r) if case is None else g.cases[0]
            rpm_f = r if math.isclose(gc.scale, 1.0) else g.ref_rpm
            t_global += time.perf_counter() - t1
            t1 = time.perf_counter()
            peaks: dict[str, ZonedPeak] = {}
            for z0 in zones:
                key = (z0.name, id(g.solution), rpm_f)
                if key in fields_of:
                    sub, sf = subs[z0.name], fields_of[key]
                elif z0.name in subs:
                    sub = subs[z0.name]
                    sf = sm.solve_speed(sub, g.solution, rpm_f, case)
                else:
                    if z0.name in ready:              # an earlier solve's, as it was
                        sub, grown = ready[z0.name]
                        z = sub.zone
                        sf = sm.solve_speed(sub, g.solution, rpm_f, case)
                    elif z0.name in pre:              # built beside the global solve
                        z, grown, sub = _take(z0.name, pre, v, plan, options, cache_dir)
                        sf = sm.solve_speed(sub, g.solution, rpm_f, case)
                    else:
                        z, grown = _grown(z0, plan, bands, grown_before.get(z0.name, 0))
                        sub, sf = _solve_zone(v, plan, z, options, g.solution, rpm_f, case,
                                              cache_dir)
                    while sm.cut_error(sf.cut_check) > CUT_TOL and grown < MAX_GROW:
                        bigger, n = _grown(z, plan, bands, 1)
                        if n == 0:
                            break
                        z, grown = bigger, grown + 1
                        sub, sf = _solve_zone(v, plan, z, options, g.solution, rpm_f, case,
                                              cache_dir)
                    if sm.cut_error(sf.cut_check) > CUT_TOL:
                        warn("cut-check", z.name, f"the cut check reads "
                             f"{100 * sm.cut_error(sf.cut_check):.1f} % (> {100 * CUT_TOL:g} %) "
                             "after growing the zone as far as it goes: its peaks may carry the "
                             "cut's error; compare with --model solid")
                    subs[z0.name] = sub
                    grown_now[z0.name] = grown
                    sens = _sensitivity(v, plan, z, options, g.solution, rpm_f, case, cache_dir,
                                        sf, bands) if sensitivity else None
                    infos.append(ZoneInfo(z.name, tuple(f.region for f in z.features),
                                          (z.x0, z.x1), z.cuts_mm, z.nominal_mm, grown,
                                          sub.n_dofs, sub.shaft_mesh.n_elements, sf.cut_check,
                                          {**({"reused": True} if sub is ready.get(
                                              z0.name, (None,))[0] else sub.seconds),
                                           **sf.seconds}, sens))
                    fields.append((sub, sf))
                fields_of[key] = sf
                for p in sf.peaks:
                    if not _from_zone(feats.get(p.region), sub.zone, plan):
                        continue
                    peaks[p.region] = ZonedPeak(p.region, _kind(feats, p.region),
                                                p.von_mises_MPa * gc.scale, p.xyz_mm,
                                                p.max_principal_MPa * gc.scale,
                                                p.max_principal_xyz_mm, sub.zone.name)
            t_zones += time.perf_counter() - t1
            for p in gc.peaks:
                if p.region not in peaks and not _in_zone(feats.get(p.region), subs.values(), plan):
                    peaks[p.region] = ZonedPeak(p.region, _kind(feats, p.region), p.von_mises_MPa,
                                                p.xyz_mm, p.max_principal_MPa,
                                                p.max_principal_xyz_mm, "axisymmetric")
            cases.append(ZonedCase(r, gc.scale, gc.bearings, gc.stations,
                                   gc.max_axis_deflection_mm,
                                   tuple(peaks[k] for k in sorted(peaks)), gc.equilibrium_residual,
                                   gc.case, gc.load_sum_N))
            if len(cases) == 1:
                first_global = g
    finally:
        scope.close()
        if pool is not None:   # on an error too: no zone built for nothing; gmsh left whole
            pool.shutdown(wait=True, cancel_futures=True)
    if grown_now != grown_before:
        _write_growth(memo, grown_now)
    notes.append("global model: the axisymmetric harmonic model of the whole shaft (reactions, "
                 "deflections, L10h and every rotationally symmetric notch); 3D submodels "
                 "only in the zones of " + ", ".join(
                     r for z in zones for r in (f.region for f in z.features)))
    notes.append("the keyways' and the hex socket's effect on the shaft's stiffness is not in "
                 "the global model (reactions and deflections are the round shaft's)")
    notes.append("shaftfe report, demo and fatigue take this zoned field by default; "
                 "--model solid gives the full 3D model, whose peaks differ from these by what "
                 "reports/benchmarks/zoned.md measures")
    glob = {p.region for p in cases[0].peaks if p.model == "axisymmetric"}
    # a notch the global model gives but whose faces reach into a 3D zone (a zone's cut lies
    # beyond its nominal reach, or the cut check grew it): the cut features' field acts there,
    # which the bars' grids did not hold
    solved = [(sub.zone.name, sub.zone.x0, sub.zone.x1) for sub in subs.values()]
    in_zone = {r: name for r in glob if r in feats for name, x0, x1 in solved
               if feats[r].x_mm[1] > x0 and feats[r].x_mm[0] < x1}
    bars, bar_notes = zone_filtered(first_global.truth_error_bar_pct,
                                    first_global.truth_bar_notes, glob, in_zone)
    zbars, znotes = _zone_peak_bars(v, plan, options, [p for p in cases[0].peaks
                                                       if p.model != "axisymmetric"], infos,
                                    feats)
    notes.append("error bars: a span fillet's or groove's peak from the global model carries "
                  f"the axisymmetric {axi_level} level's error measured over a grid of "
                  "shoulders or of U grooves (its own method refined: a discretisation bar; "
                  "reports/benchmarks/bars_grid.md, groove_bars.md)" if bars else
                  "error bars: none on the global model's span fillets and grooves (other "
                  "options or loads than the measured ones, or no such notch inside the "
                  "measured grids: the reasons are printed)")
    notes.append(("error bars of the zones' peaks: a rounded keyway's or a cross hole's peak "
                  "carries its zone level's error measured over a grid of keyways and one of "
                  "cross holes against the full 3D model at a finer level (keyways: fine; "
                  "cross holes: fine × 0.7; reports/benchmarks/zone_bars.md)" if zbars else
                  "error bars of the zones' peaks: none (no rounded keyway or cross hole "
                  "inside the measured grids, with their loads, level and clear "
                  "surroundings: the reasons are printed)") +
                 "; the zones' other peaks (fillets, seats, the hex socket) have none")
    bars, bar_notes = bars | zbars, bar_notes | znotes
    if any(k.rho == 0 for k in plan.slots):
        notes.append("a keyway without a bottom radius (bottom_radius_mm) is sharp-edged: a "
                     "peak on it is a value of the mesh that grows with refinement, not a "
                     "converged stress (marked where printed; reports/benchmarks/"
                     "keyway_edge.md)")
    rounded = [k for k in plan.slots if k.rho > 0]
    if rounded:
        notes.append("keyways with a bottom radius (" + ", ".join(
            f"{keyway_region(k.segment, k.index)}: r1 {k.rho:g} mm" for k in rounded) +
            ") are meshed with it, sized as a fillet's hot spot: their peaks converge "
            "(reports/benchmarks/keyway_radius.md, zone_bars.md)")
    notes += [n for n in first_global.notes if "is not modelled" not in n]
    run = {"plan_seconds": t_plan, "global_seconds": t_global, "zones_seconds": t_zones,
           "total_seconds": time.perf_counter() - t0}
    return ZonedResult(variant.name, variant.content_hash, options, axi_level, tuple(infos),
                       tuple(cases), tuple(notes), run, first_global, plan, tuple(fields),
                       bars, bar_notes)


def _zone_peak_bars(variant, plan, options: StaticOptions, peaks, infos,
                    feats: dict | None = None) -> tuple[dict, dict]:
    """The bars of the keyway and cross-hole peaks the 3D zones give
    (``static.measured_errors.zone_bars``), for a named level used as named under the measured
    options (P2, every peak node kept), and none in a zone whose cut check reads worse than
    any the grid measured (``infos``: the ``ZoneInfo`` of each zone). Supports, spin softening
    and the loads' placement are not checked: the grid measured rigid supports without spin
    and the loads outside the feature's zone (``zone_bars`` refuses a load inside it); the
    only evidence with bearing springs and spin softening is x2_57's keyways (r1 0.25 mm, at
    default: the zone's peaks within 0.1 % of the full 3D model at the same level,
    reports/benchmarks/keyway_radius.md §2), which the grid's lookup itself refuses (another
    profile, crowded zones)."""
    name = level_name(options.level)
    if name not in LEVELS or mesh_level(options.level) != LEVELS[name] or options.order != 2 \
            or options.exclude_mm != 0.0:
        return {}, {p.region: "no measured bar for these options (measured: a named level, "
                    "P2, every peak node kept)" for p in peaks
                    if kind_of(p.region) in ("keyway", "cross_hole")}
    bars, notes = zone_bars(variant, plan, name, peaks, feats)
    worst = {k: g.get("cut_check_max", 0.0) for k, g in zone_feature_bars().items()
             if isinstance(g, dict)}
    for zi in infos:
        err = sm.cut_error(zi.cut_checks)
        for r in zi.features:
            if r in bars and err > worst.get(kind_of(r), 0.0):
                del bars[r]
                notes[r] = (f"no measured bar: the cut check of {zi.name} reads "
                            f"{100 * err:.1f} %, above the grid's worst "
                            f"{100 * worst.get(kind_of(r), 0.0):.2f} %")
    return bars, notes


def zone_filtered(bars: dict, notes: dict, glob: set, in_zone: dict) -> tuple[dict, dict]:
    """The global model's bars and their notes kept for the notches it reports (``glob``),
    but a notch whose faces reach into a solved 3D zone (``in_zone``: region → zone name),
    which gets, in place of its bar or of its note, why it has none."""
    kept = {r: b for r, b in bars.items() if r in glob and r not in in_zone}
    why = {r: n for r, n in notes.items() if r in glob and r not in in_zone}
    why |= {r: f"no measured bar: it lies in the 3D zone {name}, whose cut features' field "
               "the measured grids did not hold"
            for r, name in in_zone.items() if r in bars or r in notes}
    return kept, why


def _growth_file(plan, bands, zones, options, cache_dir):
    """Where the zones' growth of an earlier run of the same plan, load bands, placed zones,
    level and order is kept (``zones-<key>.json``): a run starts from the zones that passed the
    cut check before (and checks them again: a zone still grows if its check fails), instead
    of solving each smaller zone again. Starting larger only costs time; the cut check and the
    peaks are those of the zone actually solved."""
    import hashlib
    import json

    payload = json.dumps([plan_payload(plan), list(bands), [(z.x0, z.x1) for z in zones],
                          str(options.level), options.order],
                         sort_keys=True, default=repr)
    key = hashlib.sha256(payload.encode()).hexdigest()[:24]
    return paths.cache_dir(cache_dir) / f"zones-{key}.json"


def _read_growth(path) -> dict:
    import json
    try:
        data = json.loads(path.read_text())
        return {str(k): int(v) for k, v in data.items()} if isinstance(data, dict) else {}
    except (OSError, ValueError, TypeError):
        return {}


def _write_growth(path, grown: dict) -> None:
    import json

    try:
        write_atomic(path, json.dumps(grown, sort_keys=True))
    except OSError:
        pass                                   # a read-only cache only costs the time


def _kind(feats: dict, region: str) -> str:
    f = feats.get(region)
    return f.kind if f is not None else ""


def _warn_grooves_in_zones(plan, zones, feats) -> None:
    """A groove inside a 3D zone is the global model's (its peak and its fatigue field: the
    axisymmetric model meshes its radius, ``_from_zone``); the zone meshes it only for its
    geometry, at a size it does not resolve (meshing a 0.1 mm ring-groove radius in the zone
    instead took 372 000 dofs and 15 s warm and still read 19 % low: issue #33's note). What
    that leaves out, the cut features' own field at the groove, is not measured: a warning."""
    for z in zones:
        for f in feats.values():
            if f.kind == "groove" and z.x0 - 1e-9 <= f.x_mm[0] and f.x_mm[1] <= z.x1 + 1e-9:
                cuts = ", ".join(c.region for c in z.features)
                warn("groove-in-zone", f.region,
                     f"lies in the 3D zone {z.name} (of {cuts}): its peak and fatigue field are "
                     "the axisymmetric model's, without those features' own stress field at "
                     "the groove (not measured)")


def _from_zone(feat, zone, plan) -> bool:
    """Does a region's peak come from the zone's submodel? Its cut features always; any other
    feature only if it lies at least ``CUT_CLEAR_D`` local diameters from the zone's cuts (a
    region cut short by a cut, or next to it, is the global model's: its peak there is the
    cut's, not the feature's)."""
    if feat is None or feat.cut:
        return True
    if feat.kind == "groove":
        # a body of revolution the global model holds exactly, meshed in the zone only for
        # its geometry (``solid.mesh``: a zone's groove is not refined to its radius)
        return False
    gap = CUT_CLEAR_D * diameter_at(plan, 0.5 * (feat.x_mm[0] + feat.x_mm[1]))
    return all(feat.x_mm[0] - x >= gap or x - feat.x_mm[1] >= gap for x in zone.cuts_mm)


def _in_zone(feat, subs, plan) -> bool:
    """Does the feature's peak come from a solved zone's submodel (``_from_zone``)?"""
    if feat is None:
        return False
    return any(s.zone.x0 - 1e-9 <= feat.x_mm[0] and feat.x_mm[1] <= s.zone.x1 + 1e-9
               and _from_zone(feat, s.zone, plan) for s in subs)


def _sensitivity(v, plan, z, options, gsol, rpm, case, cache_dir, sf, bands) -> dict | None:
    """The relative change of each cut feature's peak when the zone's cuts move outward one
    admissible gap (None when there is no room)."""
    bigger = grow(z, plan, bands)
    if bigger is None:
        return None
    _, sf2 = _solve_zone(v, plan, bigger, options, gsol, rpm, case, cache_dir)
    a, b = _zone_peaks(sf), _zone_peaks(sf2)
    out = {"cuts_mm": list(bigger.cuts_mm)}
    for f in z.features:
        p, q = a.get(f.region), b.get(f.region)
        if p is not None and q is not None and q.von_mises_MPa > 0:
            out[f.region] = p.von_mises_MPa / q.von_mises_MPa - 1.0
    return out


__all__ = ["CUT_TOL", "ZoneInfo", "ZonedCase", "ZonedPeak", "ZonedResult", "solve_zoned"]
