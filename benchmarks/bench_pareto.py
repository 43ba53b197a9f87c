"""Run time against error, one Pareto front per quantity (issue 8, "Run time against error").

Quantities (variant x2_57, bearing springs):
* ``stress``      peak von Mises of the collar fillet and of the bearing-seat-gear fillet at
                  10 000 rpm (all parts loaded, ``shaftfe static`` defaults); error = the worse
                  of the two;
* ``deflection``  radial deflection of the axis at the gear seat (station ``seat:gear``);
* ``reactions``   radial force of both bearings; error = the worse of the two;
* ``fatigue``     life in blocks at the filtered hot spot on ``loadspectra/rpm.dat`` with the
                  settings of ``shaftfe fatigue`` (its argparse defaults are read, not copied),
                  plus the safety factor at the design life;
* ``frequencies`` first 12 natural frequencies at rest and at ``TOP_RPM``; error = the largest
                  relative error of the 24.

Configurations: every mesh level of ``shaftfe.solid.levels.LEVELS`` × P1/P2 × every linear
solver that ``shaftfe.fe.solvers.available()`` reports (SuperLU is not run above
``SUPERLU_MAX_DOFS``, as in bench_static), the beam model (``shaftfe.beam.solve``: stresses = Kt
× nominal at the shoulder, ``shaftfe.beam.scf``) at several element sizes, and for the
frequencies the beam rotor (``shaftfe.rotordynamics.beam_rotor``) at several element sizes and
basis tolerances of the reduced-basis eigensolver (plus ``shaftfe.rotordynamics.solid_rotor``
when it exists: see ``_solid_freq_plan``).

Every run is a FRESH subprocess: ``cold`` = an empty mesh cache (Gmsh runs), ``warm`` = the same
configuration again on the cache the cold run left (no Gmsh). Measured per run: wall time and
CPU time (``time.process_time``: user + sys of every thread) of the computation inside the
child, the child's whole CPU time (``resource.getrusage(RUSAGE_CHILDREN)`` in the parent:
interpreter start and imports included), its peak RSS (``ru_maxrss`` of RUSAGE_SELF in the
child) and the 1-minute load average (``os.getloadavg``, what ``uptime`` prints) before and
after: the machine is shared, wall time is inflated by other work, CPU time much less.

Reference: for the fillet stresses the truth, the axisymmetric path converged by Richardson
(``reports/benchmarks/truth.json``, written by bench_truth: ``_truth_reference``; issue #12);
otherwise the entry that ``reports/benchmarks/static_reference.json`` carries when it has one
(``_static_json_reference``), else the extrapolated value (Richardson) of the two finest P2
levels; the report says which. Pareto fronts: (cold wall time, |error|) — the primary one — and, as
flags in the tables, (CPU time, |error|), (warm wall time, |error|) and (cold wall time, peak
RSS, |error|).

Run: ``python -m benchmarks bench_pareto [--quick] [--parts static,fatigue,freq]
[--levels coarse,default] [--resume] [--report-only]`` or the same through the environment:
``SHAFTFE_PARETO="--quick --parts freq"``. ``--quick``: levels coarse and default only, one
solver (the default one), no warm runs, a few beam sizes (a smoke run, ~2 min; its reference is
NOT converged). ``--resume`` reuses the runs in pareto.json whose configuration key (level
settings, mesh format, code fingerprint) still matches. Writes reports/benchmarks/pareto.md,
pareto.json and pareto_<quantity>.png.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import hashlib
import json
import math
import os
import resource
import shlex
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "reports" / "benchmarks"
STATIC_JSON = OUT / "static_reference.json"   # written by bench_static
SPECTRUM = ROOT / "loadspectra" / "rpm.dat"
VARIANT = "x2_57"
RPM = 10_000.0              # the static load case of shaftfe static (REF_RPM)
TOP_RPM = 8_000.0           # top of the seed's Campbell sweep (SPEC §4: 0-8000 rpm)
N_MODES = 12
SUPERLU_MAX_DOFS = 200_000  # as bench_static: SuperLU takes minutes and GB beyond
WARM_MAX_DOFS = 300_000     # warm re-runs above this are skipped (they only drop Gmsh)
TOL = 0.01                  # the accuracy target the report measures against (1 %)
FLOOR = 1e-7                # errors below this are plotted at it
BEAM_STATIC_SIZES = (5.0, 2.0, 1.0)          # mm; 5 = shaftfe beam's default
BEAM_FREQ_SIZES = (20.0, 10.0, 5.0, 2.5, 1.25, 0.625, 0.3125)
BEAM_FREQ_TOLS = (1e-3, 1e-6, 1e-9)          # choose_basis tolerance; 1e-6 = default
QUICK_FREQ_SIZES = (10.0, 5.0, 2.5, 0.625)
QUANTITIES = ("stress", "deflection", "reactions", "fatigue", "frequencies")
SURFACE_KINDS = ("zoned_static", "axi_static", "zoned_fatigue")   # the shaft as a revolution
FE_KINDS = ("static", "fatigue", *SURFACE_KINDS)                   # with a mesh cache: warm runs


# =========================================================================== child side

def _child(spec_json: str) -> None:
    """Entry point of a fresh subprocess: run one configuration, print RESULT<json>."""
    spec = json.loads(spec_json)
    fn = {"static": _c_static, "fatigue": _c_fatigue, "beam_static": _c_beam_static,
          "beam_fatigue": _c_beam_fatigue, "freq_beam": _c_freq_beam,
          "freq_solid": _c_freq_solid, "zoned_static": _c_surface_static,
          "axi_static": _c_surface_static, "zoned_fatigue": _c_zoned_fatigue}[spec["kind"]]
    src = {m: hashlib.sha256((ROOT / "shaftfe" / f"{m}.py").read_bytes()).hexdigest()[:12]
           for m in ("solid/mesh", "static/solve", "beam/elements", "beam/model", "beam/solve",
                     "rotordynamics/beam_rotor")}
    out = fn(spec)
    out["rss_MB"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    out["source_sha"] = src
    if "level" in spec and spec["kind"] != "axi_static":      # a 3D mesh level's settings
        from shaftfe.solid.levels import LEVELS
        out["level_settings"] = LEVELS[spec["level"]].settings() if spec["level"] in LEVELS else {}
    print("RESULT" + json.dumps(out))


class _Clock:
    def __enter__(self):
        self.w, self.c = time.perf_counter(), time.process_time()
        return self

    def __exit__(self, *exc):
        self.wall = time.perf_counter() - self.w
        self.cpu = time.process_time() - self.c


def _best_of(fn, repeat: int = 5, budget_s: float = 3.0) -> dict:
    """In-process repeats of a cheap computation (the beam paths, no cache): the best wall
    time and the CPU time of that repeat = the "warm" numbers of a configuration without a
    cache (imports done, code paths hot). At most ``repeat`` repeats, fewer once they have
    taken ``budget_s`` (at least one)."""
    best, c0, w0, n = None, time.process_time(), time.perf_counter(), 0
    while n < repeat and (n == 0 or time.perf_counter() - w0 < budget_s):
        with _Clock() as ck:
            fn()
        n += 1
        if best is None or ck.wall < best[0]:
            best = (ck.wall, ck.cpu)
    return {"warm_wall_s": best[0], "warm_cpu_s": best[1], "warm_repeats": n,
            "repeat_cpu_s": time.process_time() - c0}


def _fatigue_defaults():
    """The argparse defaults of ``shaftfe fatigue`` (so the benchmark follows the command)."""
    from shaftfe.commands import fatigue as fcmd
    from shaftfe.fatigue.method_options import with_defaults
    from shaftfe.fatigue.run import DEFAULT_DESIGN_LIFE_BLOCKS
    p = argparse.ArgumentParser()
    fcmd.register(p.add_subparsers())
    a = p.parse_args(["fatigue", str(SPECTRUM), "--method", "seed"])
    with_defaults(a)                   # the method options are filled in after parsing
    a.design_life = DEFAULT_DESIGN_LIFE_BLOCKS     # neither --design-life nor -h given
    return a


def _material(a):
    """The seed method's S-N card as ``shaftfe fatigue`` resolves it: ``--material``, else the
    variant's (``fatigue.run.sn_material``)."""
    from shaftfe.fatigue.run import sn_material
    from shaftfe.model.loader import load_variant
    return sn_material(a, load_variant(VARIANT))


def _c_static(spec: dict) -> dict:
    from shaftfe.model.loader import load_variant
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import solve_static
    v = load_variant(VARIANT)
    opts = StaticOptions(level=spec["level"], order=spec["order"], solver=spec["solver"])
    with _Clock() as ck:
        r = solve_static(v, [RPM], opts, cache_dir=spec["cache"], beam=False)
        c = r.case(RPM)
    pk = {p.region: p for p in c.peaks}
    st = {s.name: s for s in c.stations}
    d = {**r.diagnostics, **r.run}
    return {"wall_s": ck.wall, "cpu_s": ck.cpu, "dofs": r.n_dofs, "n_elements": r.n_elements,
            "mesh_s": d["mesh_seconds"], "mesh_from_cache": d["mesh_from_cache"],
            "assembly_s": d["assembly_seconds"], "factor_s": d["factor_seconds"],
            "solve_s": d["solve_seconds"], "recovery_s": d["recovery_seconds"],
            "solver_used": d["solver"], "relres": d["relative_residual"],
            "collar": pk["fillet:collar"].von_mises_MPa,
            "collar_x": pk["fillet:collar"].xyz_mm[0],
            "bsg": pk["fillet:bearing_seat_gear"].von_mises_MPa,
            "bsg_x": pk["fillet:bearing_seat_gear"].xyz_mm[0],
            "gear_defl": st["seat:gear"].u_mm, "max_defl": c.max_deflection_mm,
            "reactions": {b.name: b.F_radial_N for b in c.bearings}}


def _c_fatigue(spec: dict) -> dict:
    from shaftfe.fatigue.field import evaluate
    from shaftfe.fatigue.run import read_spectrum
    from shaftfe.model.loader import load_variant
    from shaftfe.static import solve as static_solve
    from shaftfe.static.model import StaticOptions
    a = _fatigue_defaults()
    v = load_variant(VARIANT)
    opts = StaticOptions(level=spec["level"], order=spec["order"], solver=spec["solver"],
                         seed_load_case=a.seed_load_case)
    with _Clock() as ck:
        history = read_spectrum(str(SPECTRUM), a.ref_rpm, a.sample_rate)
        material = _material(a)
        ref = static_solve.load_or_solve(v, opts, spec["cache"], use_cache=False)
        t0 = time.perf_counter()
        ff = evaluate(ref, history, material, equivalent=a.equivalent, theory=a.mean_stress,
                      kf=a.kf, design_life_blocks=a.design_life, speed_kmh=a.speed_kmh)
        t_eval = time.perf_counter() - t0
    h = ff.hot_spot
    return {"wall_s": ck.wall, "cpu_s": ck.cpu, "dofs": 3 * ref.n_nodes,
            "n_elements": ref.n_elements, "static_s": ref.seconds, "eval_s": t_eval,
            "solver_used": spec["solver"],      # a named, installed backend is used as asked
            "life": h.life_blocks, "sf": h.safety_factor, "sigma_eq": h.sigma_eq_ref_MPa,
            "region": h.region, "x": h.xyz_mm[0], "infinite": h.infinite_life,
            "tensor": [float(s) for s in ref.stress_ref[:, h.node]],
            # with spin softening (the default) the unsoftened stress too: the node's
            # S0 (λ + β λ²) needs both (fatigue.field.softening_beta)
            "tensor_linear": (None if ref.stress_linear is None else
                              [float(s) for s in ref.stress_linear[:, h.node]]),
            "cycles_per_block": ff.cycles_per_block}


def _c_surface_static(spec: dict) -> dict:
    """``shaftfe static``'s default, the zoned model (the axisymmetric global model at
    ``default`` and 3D zones at ``spec["level"]``), or the axisymmetric model alone at its
    level. dofs: the meridian mesh's 3 per node per harmonic solved, plus the zones'."""
    from shaftfe.model.loader import load_variant
    v = load_variant(VARIANT)
    with _Clock() as ck:
        if spec["kind"] == "zoned_static":
            from shaftfe.static.model import StaticOptions
            from shaftfe.zoned.solve import solve_zoned
            r = solve_zoned(v, RPM, StaticOptions(level=spec["level"]), cache_dir=spec["cache"])
            g = r.global_result
        else:
            from shaftfe.axisymmetric.model import AxiOptions
            from shaftfe.axisymmetric.solve import solve_axisymmetric
            r = g = solve_axisymmetric(v, RPM, AxiOptions(level=spec["level"]),
                                       cache_dir=spec["cache"])
        c = r.case(RPM)
    pk = {p.region: p for p in c.peaks}
    st = {s.name: s for s in c.stations}
    zones = getattr(r, "zones", ())
    return {"wall_s": ck.wall, "cpu_s": ck.cpu,
            "dofs": 3 * g.n_nodes * len(g.harmonics) + sum(z.n_dofs for z in zones),
            "n_elements": g.n_elements + sum(z.n_elements for z in zones),
            "mesh_from_cache": bool(g.run.get("mesh_from_cache")), "solver_used": _default_solver(),
            "collar": pk["fillet:collar"].von_mises_MPa,
            "collar_x": pk["fillet:collar"].xyz_mm[0],
            "bsg": pk["fillet:bearing_seat_gear"].von_mises_MPa,
            "bsg_x": pk["fillet:bearing_seat_gear"].xyz_mm[0],
            "gear_defl": st["seat:gear"].u_mm, "max_defl": float("nan"),
            "reactions": {b.name: b.F_radial_N for b in c.bearings}}


def _c_zoned_fatigue(spec: dict) -> dict:
    """The seed method's hot spot on the zoned model's surface reference (``shaftfe fatigue
    --method seed``'s default static model), solved softened and unsoftened as there."""
    from shaftfe.fatigue.field import evaluate
    from shaftfe.fatigue.run import FatigueJob, read_spectrum, surface_model, surface_reference
    from shaftfe.model.loader import load_variant
    from shaftfe.util.units import REF_RPM
    a = _fatigue_defaults()
    v = load_variant(VARIANT)
    job = FatigueJob(str(SPECTRUM), model="zoned", level=spec["level"])
    with _Clock() as ck:
        history = read_spectrum(str(SPECTRUM), a.ref_rpm, a.sample_rate)
        material = _material(a)
        opts, solve, reference = surface_model("zoned", level=job.level,
                                               seed_load_case=a.seed_load_case,
                                               spin_softening=job.spin_softening)
        t0 = time.perf_counter()
        solved = []

        def make(o):
            solved.append(solve(v, REF_RPM, o, cache_dir=spec["cache"]))
            return reference(solved[-1])
        ref = surface_reference(make, opts)
        t_static = time.perf_counter() - t0
        t0 = time.perf_counter()
        ff = evaluate(ref, history, material, equivalent=a.equivalent, theory=a.mean_stress,
                      kf=a.kf, design_life_blocks=a.design_life, speed_kmh=a.speed_kmh)
        t_eval = time.perf_counter() - t0
    h = ff.hot_spot
    g = solved[0].global_result              # dofs as the static row counts them
    return {"wall_s": ck.wall, "cpu_s": ck.cpu,
            "dofs": 3 * g.n_nodes * len(g.harmonics) + sum(z.n_dofs for z in solved[0].zones),
            "n_elements": ref.n_elements, "static_s": t_static, "eval_s": t_eval,
            "solver_used": _default_solver(), "life": h.life_blocks, "sf": h.safety_factor,
            "sigma_eq": h.sigma_eq_ref_MPa, "region": h.region, "x": h.xyz_mm[0],
            "infinite": h.infinite_life,
            "tensor": [float(x) for x in ref.stress_ref[:, h.node]],
            "tensor_linear": (None if ref.stress_linear is None else
                              [float(x) for x in ref.stress_linear[:, h.node]]),
            "cycles_per_block": ff.cycles_per_block}


def _beam_fillets(variant) -> dict:
    """FE fillet region name -> shoulder x of that fillet (shaftfe.solid.plan's plan)."""
    from shaftfe.solid.features import fillet_region
    from shaftfe.solid.plan import prepare
    return {fillet_region(f.segment): f.x_shoulder for f in prepare(variant).fillets}


def _notch_at(res, x: float):
    return min(res.notches, key=lambda n: abs(n.x_mm - x))


def _c_beam_static(spec: dict) -> dict:
    from shaftfe.beam.model import build_model
    from shaftfe.beam.solve import solve
    from shaftfe.model.loader import load_variant
    v = load_variant(VARIANT)
    fx = _beam_fillets(v)
    def run():
        m = build_model(v, max_element_mm=spec["h"], spread_loads=spec["spread"])
        return m, solve(m, [RPM])[0]
    with _Clock() as ck:
        m, r = run()
    warm = _best_of(run)
    col, bsg = _notch_at(r, fx["fillet:collar"]), _notch_at(r, fx["fillet:bearing_seat_gear"])
    return {"wall_s": ck.wall, "cpu_s": ck.cpu, **warm, "dofs": 6 * m.n_nodes,
            "collar": col.sigma_peak_MPa, "collar_kt": col.kt, "collar_nom": col.sigma_nom_MPa,
            "bsg": bsg.sigma_peak_MPa, "bsg_kt": bsg.kt, "bsg_nom": bsg.sigma_nom_MPa,
            "gear_defl": r.stations["gear"].u_mm, "max_defl": r.max_deflection_mm,
            "reactions": {b.name: b.F_N for b in r.bearings}}


def _c_beam_fatigue(spec: dict) -> dict:
    """Beam + Kt: the largest shoulder peak Kt·σ_nom (seed load case) as a uniaxial stress."""
    import numpy as np

    from shaftfe.beam.model import build_model
    from shaftfe.beam.solve import solve
    from shaftfe.fatigue.field import evaluate_arrays
    from shaftfe.fatigue.run import read_spectrum
    from shaftfe.model.loader import load_variant
    a = _fatigue_defaults()
    v = load_variant(VARIANT)
    vv = v.with_seed_load_case() if a.seed_load_case else v
    def run():
        history = read_spectrum(str(SPECTRUM), a.ref_rpm, a.sample_rate)
        material = _material(a)
        m = build_model(vv, max_element_mm=spec["h"], spread_loads=spec["spread"])
        r, = solve(m, [RPM])
        n = max(r.notches, key=lambda q: q.sigma_peak_MPa)
        s = np.zeros((6, 1))
        s[0, 0] = n.sigma_peak_MPa
        ff = evaluate_arrays(s, history, material, ref_rpm=RPM, xyz=np.array([[n.x_mm], [0.0],
                             [0.0]]), equivalent=a.equivalent, theory=a.mean_stress, kf=a.kf,
                             design_life_blocks=a.design_life, speed_kmh=a.speed_kmh)
        return m, n, s, ff
    with _Clock() as ck:
        m, n, s, ff = run()
    warm = _best_of(run)
    h = ff.hot_spot
    return {"wall_s": ck.wall, "cpu_s": ck.cpu, **warm, "dofs": 6 * m.n_nodes,
            "life": h.life_blocks,
            "sf": h.safety_factor, "sigma_eq": h.sigma_eq_ref_MPa, "region": "beam notch",
            "x": n.x_mm, "infinite": h.infinite_life, "tensor": s[:, 0].tolist()}


def _branches(res) -> dict:
    """Per tracked branch: frequency at rest and at TOP_RPM, family and whirl label (for the
    mode pairing between models), plus the sorted lists."""
    modes = [{"f0": float(res.freq_hz[0, j]), "f1": float(res.freq_hz[-1, j]),
              "family": str(res.family[0][j]), "whirl": str(res.branch_whirl[j])}
             for j in range(res.freq_hz.shape[1])]
    return {"modes": modes, "f0": sorted(m["f0"] for m in modes),
            "f1": sorted(m["f1"] for m in modes)}


def _c_freq_beam(spec: dict) -> dict:
    from shaftfe.model.loader import load_variant
    from shaftfe.rotordynamics import beam_rotor as rotor
    v = load_variant(VARIANT)
    def run():
        rot = rotor.rotor_from_variant(v, max_element_mm=spec["h"])
        return rot, rotor.campbell(rot, [0.0, TOP_RPM], N_MODES, tol=spec["tol"])
    with _Clock() as ck:
        rot, res = run()
    warm = _best_of(run)
    return {"wall_s": ck.wall, "cpu_s": ck.cpu, **warm, "dofs": int(rot.n_dof),
            "basis": int(res.basis_size), **_branches(res)}


def _c_freq_solid(spec: dict) -> dict:
    """3D solid rotor (``shaftfe.rotordynamics.solid_rotor``): P2/P1 mesh of the static model,
    attachments as rigid bodies (its default coupling), reduced-basis Campbell sweep with basis
    tolerance ``tol`` (the eigensolver setting that decides the basis size)."""
    from shaftfe.model.loader import load_variant
    from shaftfe.rotordynamics import solid_modal
    from shaftfe.rotordynamics import solid_rotor as rotor_solid
    v = load_variant(VARIANT)
    opts = rotor_solid.SolidOptions(level=spec["level"], order=spec["order"],
                                    solver=spec["solver"])
    with _Clock() as ck:
        rot = rotor_solid.build_solid_rotor(v, opts, cache_dir=spec["cache"])
        res = solid_modal.campbell(rot, [0.0, TOP_RPM], N_MODES, tol=spec["tol"])
    return {"wall_s": ck.wall, "cpu_s": ck.cpu, "dofs": int(rot.n_dof),
            "basis": int(res.basis_size), **_branches(res)}


# =========================================================================== parent side

def _load1() -> float:
    return os.getloadavg()[0]


def _spawn(spec: dict, timeout: float = 3600) -> dict | None:
    """Run ``spec`` in a fresh interpreter; add the parent-side measurements."""
    code = (f"import sys; sys.path.insert(0, {str(ROOT)!r}); "
            "from benchmarks.bench_pareto import _child; _child(sys.argv[1])")
    ru0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    l0, t0 = _load1(), time.perf_counter()
    env = dict(os.environ)
    try:
        p = subprocess.run([sys.executable, "-c", code, json.dumps(spec)], capture_output=True,
                           text=True, timeout=timeout, env=env, cwd=str(ROOT))
    except subprocess.TimeoutExpired:
        print(f"   {spec['kind']} {_name(spec)}: timed out after {timeout:g} s", flush=True)
        return None
    wall = time.perf_counter() - t0
    ru1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    for line in p.stdout.splitlines():
        if line.startswith("RESULT"):
            out = json.loads(line[6:])
            out.update(spec)
            out.pop("cache", None)
            out.update(child_wall_s=wall,
                       child_cpu_s=(ru1.ru_utime - ru0.ru_utime) + (ru1.ru_stime - ru0.ru_stime),
                       load_before=l0, load_after=_load1(),
                       utc=_dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M:%S"))
            return out
    tail = (p.stderr.strip().splitlines() or ["(no output)"])[-1]
    print(f"   {spec['kind']} {_name(spec)}: failed: {tail}", flush=True)
    return None


def _name(spec: dict) -> str:
    k = spec["kind"]
    if k in ("static", "fatigue"):
        return f"{spec['level']} P{spec['order']} {spec['solver']}"
    if k in ("zoned_static", "zoned_fatigue"):
        return f"zoned, zones {spec['level']}"
    if k == "axi_static":
        return f"axisymmetric {spec['level']}"
    if k in ("beam_static", "beam_fatigue"):
        return f"beam h={spec['h']:g}" + (" spread" if spec["spread"] else " point")
    if k == "freq_beam":
        return f"beam h={spec['h']:g} tol={spec['tol']:g}"
    return f"3D {spec['level']} P{spec['order']} tol={spec['tol']:g}"


def _fingerprints() -> dict:
    """Input fingerprints per family of runs (the --resume key): ``beam`` = the beam, rotor,
    Kt and fatigue code, the variant's content and the spectrum; ``fe:<level>`` = that plus the
    static/mesh code (``util.cachefile.code_fingerprint`` + mesh, solid, static_cache) and the
    level's settings, Gmsh options and mesh cache format."""
    from shaftfe.model.loader import load_variant
    from shaftfe.solid.levels import LEVELS
    from shaftfe.solid.mesh import CACHE_FORMAT, GMSH_OPTIONS
    from shaftfe.static import cache as static_cache
    from shaftfe.util.cachefile import code_fingerprint
    b = hashlib.sha256()
    for pkg in ("beam", "model", "rotordynamics", "solid"):
        for f in sorted((ROOT / "shaftfe" / pkg).glob("*.py")):
            b.update(f.read_bytes())
    for f in sorted((ROOT / "shaftfe" / "fatigue").glob("*.py")):
        b.update(f.read_bytes())
    b.update(SPECTRUM.read_bytes())
    b.update(load_variant(VARIANT).content_hash.encode())
    out = {"beam": b.hexdigest()[:16]}
    fe = b.copy()
    fe.update(code_fingerprint(static_cache.FINGERPRINT_MODULES).encode())
    for mod in ("solid/mesh", "solid/levels", "static/cache", "fe/solvers", "fe/lowrank"):
        fe.update((ROOT / "shaftfe" / f"{mod}.py").read_bytes())
    fe.update(json.dumps([GMSH_OPTIONS, CACHE_FORMAT], sort_keys=True).encode())
    sf = fe.copy()                         # the axisymmetric and zoned models' code too
    for pkg in ("axisymmetric", "zoned"):
        for f in sorted((ROOT / "shaftfe" / pkg).glob("*.py")):
            sf.update(f.read_bytes())
    out["surface"] = sf.hexdigest()[:16]
    rs = ROOT / "shaftfe" / "rotordynamics" / "solid_rotor.py"
    if rs.exists():
        out["solid"] = hashlib.sha256(rs.read_bytes()).hexdigest()[:8]
    for lv, settings in LEVELS.items():
        h = fe.copy()
        h.update(json.dumps(settings.settings(), sort_keys=True).encode())
        out[f"fe:{lv}"] = h.hexdigest()[:16]
    return out


def _fp_of(spec: dict, fps: dict) -> str:
    if spec["kind"] in SURFACE_KINDS:
        return fps.get(f"fe:{spec['level']}", "") + fps.get("surface", "")
    if spec["kind"] in ("static", "fatigue"):
        return fps.get(f"fe:{spec['level']}", "")
    if spec["kind"] == "freq_solid":
        return fps.get(f"fe:{spec['level']}", "") + fps.get("solid", "")
    return fps["beam"]


def _key(spec: dict) -> str:
    s = {k: v for k, v in spec.items() if k != "cache"}
    return json.dumps(s, sort_keys=True)


def _solid_freq_plan(args) -> list[dict]:
    """3D solid modal configurations when ``shaftfe.rotordynamics.solid_rotor`` imports: its default
    (``SolidOptions()``: level, order, solver; ``solid_modal.campbell``'s tolerance) and a looser
    basis tolerance at that level, then the finer levels of ``--solid-levels`` (default: the
    solid default level and ``default``; the ``fine`` level's modal solve is left out by
    default: minutes and GB on this shared machine)."""
    try:
        import inspect

        from shaftfe.rotordynamics import solid_modal
        from shaftfe.rotordynamics import solid_rotor as rotor_solid
    except Exception:
        return []
    from shaftfe.solid.levels import LEVELS
    d = rotor_solid.SolidOptions()
    tol = float(inspect.signature(solid_modal.campbell).parameters["tol"].default)
    levels = args.solid_levels.split(",") if args.solid_levels else [d.level, "default"]
    if args.quick:
        levels = [d.level]
    out = []
    for lv in dict.fromkeys(levels):
        if lv not in LEVELS:
            continue
        tols = (1e-3, tol) if lv == d.level and not args.quick else (tol,)
        out += [{"kind": "freq_solid", "level": lv, "order": d.order, "solver": d.solver,
                 "tol": t} for t in tols]
    return out


def plan(args) -> list[tuple[dict, bool]]:
    """(spec, also run warm) in run order: cheap first, the finest FE levels last."""
    from shaftfe.fe import solvers
    from shaftfe.solid.levels import LEVELS
    from shaftfe.static.model import StaticOptions
    have = [s for s, ok in solvers.available().items() if ok]
    default_solver = _default_solver()
    if args.quick:
        have = [default_solver]
    levels = list(LEVELS)
    if args.levels:
        levels = [lv for lv in args.levels.split(",") if lv in LEVELS]
    elif args.quick:
        levels = [lv for lv in ("coarse", StaticOptions().level) if lv in LEVELS]
    parts = set(args.parts.split(",")) if args.parts else {"static", "fatigue", "freq"}
    out: list[tuple[dict, bool]] = []
    solid = []
    if "freq" in parts:
        sizes = QUICK_FREQ_SIZES if args.quick else BEAM_FREQ_SIZES
        tols = (1e-6,) if args.quick else BEAM_FREQ_TOLS
        out += [({"kind": "freq_beam", "h": h, "tol": t}, False) for h in sizes for t in tols]
        solid = [(s, False) for s in _solid_freq_plan(args)]
    if "static" in parts:
        out += [({"kind": "beam_static", "h": h, "spread": sp}, False)
                for h in BEAM_STATIC_SIZES for sp in (False, True)]
    if "fatigue" in parts:
        out += [({"kind": "beam_fatigue", "h": h, "spread": sp}, False)
                for h in BEAM_STATIC_SIZES for sp in (False, True)]
    # FE: order 1 first (cheap), then order 2; levels in LEVELS order (coarse → fine);
    # SuperLU last within a level so its dofs are known from the first solver
    order_solvers = sorted(have, key=lambda s: s == "superlu")
    kinds = [k for k in ("static", "fatigue") if k in parts]
    for order in (1, 2):
        for lv in levels:
            for s in order_solvers:
                for k in kinds:
                    out.append(({"kind": k, "level": lv, "order": order, "solver": s},
                                not args.quick))
    # the zoned model (the default of static and fatigue) and the axisymmetric model alone
    if "static" in parts:
        out.append(({"kind": "zoned_static", "level": StaticOptions().level}, True))
        out += [({"kind": "axi_static", "level": lv}, not args.quick)
                for lv in ("coarse", "default", "fine")]
    if "fatigue" in parts:
        out.append(({"kind": "zoned_fatigue", "level": StaticOptions().level}, True))
    if "freq" in parts:
        out += solid            # last: the 3D modal runs are the most expensive per run
    return out


def _default_solver() -> str:
    """What ``StaticOptions().solver`` resolves to here (``shaftfe.fe.solvers.factorize``'s
    "auto": PARDISO when it imports, else SuperLU)."""
    from shaftfe.fe import solvers
    from shaftfe.static.model import StaticOptions
    s = StaticOptions().solver
    if s != "auto":
        return s
    return "pardiso" if solvers.available()["pardiso"] else "superlu"


def run_all(args) -> dict:
    prev = {}
    fps = _fingerprints()
    if args.resume and (OUT / "pareto.json").exists():
        old = json.loads((OUT / "pareto.json").read_text())
        prev = {r["key"]: r for r in old.get("runs", [])}
        print(f"resume: {len(prev)} stored runs; those whose inputs changed are redone")
    runs: list[dict] = []
    dofs_seen: dict[tuple, int] = {}
    up0 = _uptime()
    print(f"uptime at start: {up0}", flush=True)
    for spec, warm in plan(args):
        fe = spec["kind"] in FE_KINDS
        if fe and spec.get("solver") == "superlu":
            n = dofs_seen.get((spec["kind"], spec["level"], spec["order"]))
            if n is not None and n > SUPERLU_MAX_DOFS:
                print(f"  {spec['kind']:<12} {_name(spec)}: not run ({n} dofs > "
                      f"{SUPERLU_MAX_DOFS})", flush=True)
                continue
        modes = ["cold", "warm"] if (fe and warm) else ["cold"]
        with tempfile.TemporaryDirectory(prefix="pareto-") as cache:
            for mode in modes:
                s = dict(spec, cache=cache, mode=mode)
                k = _key(s) + _fp_of(spec, fps)
                r = prev.get(k)
                if r is None:
                    fps_now = _fingerprints()          # inputs may change while this runs
                    if fps_now != fps:
                        fps = fps_now
                        k = _key(s) + _fp_of(spec, fps)
                        r = prev.get(k)
                if r is None:
                    if mode == "warm" and runs[-1].get("dofs", 0) > WARM_MAX_DOFS \
                            and spec["kind"] not in SURFACE_KINDS:     # a 3D model's dofs
                        print(f"  {spec['kind']:<12} {_name(spec)} warm: not run "
                              f"(> {WARM_MAX_DOFS} dofs)", flush=True)
                        continue
                    r = _spawn(s)
                    if r is None:
                        break
                    r["key"] = k
                else:
                    r = dict(r, resumed=True)
                runs.append(r)
                _save_partial(prev, runs, fps)
                if fe:
                    dofs_seen[(spec["kind"], spec["level"], spec.get("order"))] = r["dofs"]
                print(f"  {spec['kind']:<12} {_name(spec):<26} {mode:<4} "
                      f"{r.get('dofs', 0):>8} dofs  wall {r['wall_s']:8.3f} s  "
                      f"cpu {r['cpu_s']:8.3f} s  child cpu {r['child_cpu_s']:6.1f} s  "
                      f"RSS {r['rss_MB']:6.0f} MB  load {r['load_before']:.2f}"
                      + (" (resumed)" if r.get("resumed") else ""), flush=True)
    return {"fingerprints": fps, "runs": runs, "uptime_start": up0, "uptime_end": _uptime(),
            "quick": bool(args.quick), "argv": args.argv}


def _save_partial(prev: dict, runs: list[dict], fps: dict) -> None:
    """pareto.json after every run (``partial``: true), so that an interrupted run can be
    resumed (``--resume``) and its stored runs are not lost."""
    have = {r["key"] for r in runs}
    keep = [r for k, r in prev.items() if k not in have]
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "pareto.json").write_text(json.dumps({"partial": True, "fingerprints": fps,
                                                 "runs": runs + keep}, default=str) + "\n")


def _uptime() -> str:
    try:
        return subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    except OSError:
        la = os.getloadavg()
        return f"load average: {la[0]:.2f}, {la[1]:.2f}, {la[2]:.2f}"


# =========================================================================== analysis

def _static_json_reference() -> dict | None:
    """A reference entry in reports/benchmarks/static_reference.json, if the static benchmark wrote
    one: a top-level object with a ``reference`` mapping (keys ``collar``, ``bsg``, optional
    ``defl``, ``gear_defl``, ``reactions``; values numbers or {"value": ...} /
    {"extrapolated": ...})."""
    if not STATIC_JSON.exists():
        return None
    try:
        data = json.loads(STATIC_JSON.read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict):
        return None
    ref = data.get("reference")
    if not isinstance(ref, dict):
        return None

    def num(v):
        if isinstance(v, dict):
            for k in ("extrapolated", "value", "q_star", "reference"):
                if isinstance(v.get(k), int | float):
                    return float(v[k])
            return None
        return float(v) if isinstance(v, int | float) else None
    out = {k: num(ref.get(k)) for k in ("collar", "bsg", "gear_defl", "defl")}
    out = {k: v for k, v in out.items() if v is not None}
    if "collar" not in out or "bsg" not in out:
        return None
    out["_note"] = str(ref.get("note", ref.get("description", ""))) or (
        "bench_static's graded family: only the hot fillet sectors refined, k_fillet "
        f"{' / '.join(f'{k:g}' for k in data.get('ref_k', ()))}; "
        "converged to the mesh noise, see static.md")
    out["_mtime"] = _dt.datetime.fromtimestamp(STATIC_JSON.stat().st_mtime, _dt.UTC) \
        .strftime("%Y-%m-%d %H:%M UTC")
    return out


TRUTH_JSON = OUT / "truth.json"   # written by bench_truth


def _truth_reference() -> dict | None:
    """x2_57's collar and bearing-seat-gear fillet peaks (von Mises, 10 000 rpm, springs) from
    the axisymmetric path converged by Richardson (reports/benchmarks/truth.json, written by
    bench_truth): an independent truth for the stresses (another element, mesh and recovery;
    issue #12), preferred to any reference extrapolated from the 3D path itself."""
    if not TRUTH_JSON.exists():
        return None
    try:
        recs = json.loads(TRUTH_JSON.read_text())["records"]
    except (OSError, ValueError, KeyError, TypeError):
        return None
    out = {}
    for key, region in (("collar", "fillet:collar"), ("bsg", "fillet:bearing_seat_gear")):
        hit = [r for r in recs if r.get("case") == f"x2_57 {region}"
               and r.get("quantity") == "von_mises"]
        if not hit:
            return None
        out[key] = float(hit[0]["truth_MPa"])
        out[f"{key}_bar"] = float(hit[0]["truth_bar_MPa"])
    out["_mtime"] = _dt.datetime.fromtimestamp(TRUTH_JSON.stat().st_mtime, _dt.UTC) \
        .strftime("%Y-%m-%d %H:%M UTC")
    return out


def _merge(runs: list[dict]) -> list[dict]:
    """One row per configuration: cold and warm runs side by side."""
    rows: dict[str, dict] = {}
    for r in runs:
        spec = {k: v for k, v in r.items() if k in ("kind", "level", "order", "solver", "h",
                                                    "spread", "tol", "label", "kwargs")}
        k = json.dumps(spec, sort_keys=True)
        row = rows.setdefault(k, dict(spec, name=_name(spec)))
        if r["mode"] == "cold":
            row.update({kk: vv for kk, vv in r.items() if kk not in ("mode", "key")})
            row["cold_wall_s"], row["cold_cpu_s"] = r["wall_s"], r["cpu_s"]
            if "warm_wall_s" in r:
                row["warm_how"] = f"best of {r.get('warm_repeats', 5)} in-process repeats"
                # the child's CPU without those repeats: one cold computation + start-up
                row["child_cpu_s"] = r["child_cpu_s"] - r.get("repeat_cpu_s", 0.0)
            else:
                row.pop("warm_wall_s", None)
        else:
            row["warm_wall_s"], row["warm_cpu_s"] = r["wall_s"], r["cpu_s"]
            row["warm_child_cpu_s"], row["warm_rss_MB"] = r["child_cpu_s"], r["rss_MB"]
            row["warm_load"] = r["load_before"]
            row["warm_mesh_from_cache"] = r.get("mesh_from_cache")
    return [r for r in rows.values() if "cold_wall_s" in r]


def _levels_info() -> dict:
    from shaftfe.solid.levels import LEVELS
    return {k: v.settings() for k, v in LEVELS.items()}


def _fe_pair(rows: list[dict], kind: str, levels: dict):
    """The two finest P2 levels (by dofs) of ``kind`` with distinct settings: (fine, coarse,
    r_stress, r_volume). r_stress = k_fillet ratio (the fillet element size decides the peak),
    falling back to the element-count ratio^(1/3) when both levels share k_fillet."""
    p2 = {}
    for r in rows:
        if r["kind"] == kind and r["order"] == 2 and r["level"] not in p2:
            p2[r["level"]] = r
    lv = sorted(p2, key=lambda k: p2[k]["dofs"])
    if len(lv) < 2:
        return None
    f, c = p2[lv[-1]], p2[lv[-2]]
    r_vol = (f["n_elements"] / c["n_elements"]) ** (1 / 3)
    kf = levels.get(c["level"], {}).get("k_fillet"), levels.get(f["level"], {}).get("k_fillet")
    r_s = kf[0] / kf[1] if None not in kf and kf[0] / kf[1] > 1.05 else r_vol
    return f, c, r_s, r_vol


def _ref_static(rows: list[dict], levels: dict) -> dict:
    from benchmarks._pareto import richardson
    pair = _fe_pair(rows, "static", levels)
    if pair is None:
        return {}
    f, c, r_s, r_u = pair
    ref = {"fine_level": f["level"], "coarse_level": c["level"], "fine_dofs": f["dofs"],
           "r_stress": r_s, "r_volume": r_u, "p_stress": 2, "p_displacement": 3}
    for k in ("collar", "bsg"):
        ref[k] = {"fine": f[k], "coarse": c[k], "extrapolated": richardson(f[k], c[k], r_s, 2)}
    for k in ("gear_defl", "max_defl"):
        ref[k] = {"fine": f[k], "coarse": c[k], "extrapolated": richardson(f[k], c[k], r_u, 3)}
    for b in f["reactions"]:
        qf, qc = f["reactions"][b], c["reactions"][b]
        ref[f"R:{b}"] = {"fine": qf, "coarse": qc, "extrapolated": richardson(qf, qc, r_u, 3)}
    return ref


def _fatigue_eval(tensor, scale: float = 1.0, tensor_linear=None) -> tuple[float, float]:
    """(life in blocks, safety factor) of one node with stress ``tensor`` × ``scale`` at RPM,
    through the same API and settings as the children; ``tensor_linear`` (× the same scale):
    the node's unsoftened stress, which a softened run's fatigue uses too (its β)."""
    import numpy as np

    from shaftfe.fatigue.field import evaluate_arrays
    from shaftfe.fatigue.run import read_spectrum
    a = _fatigue_defaults()
    h = read_spectrum(str(SPECTRUM), a.ref_rpm, a.sample_rate)
    s = np.asarray(tensor, dtype=float).reshape(6, 1) * scale
    lin = None if tensor_linear is None else \
        np.asarray(tensor_linear, dtype=float).reshape(6, 1) * scale
    ff = evaluate_arrays(s, h, _material(a), ref_rpm=RPM, xyz=np.zeros((3, 1)),
                         equivalent=a.equivalent, theory=a.mean_stress, kf=a.kf,
                         design_life_blocks=a.design_life, speed_kmh=a.speed_kmh,
                         stress_linear=lin)
    return ff.hot_spot.life_blocks, ff.hot_spot.safety_factor


def _ref_fatigue(rows: list[dict], levels: dict) -> dict:
    from benchmarks._pareto import richardson
    pair = _fe_pair(rows, "fatigue", levels)
    if pair is None:
        return {}
    f, c, r_s, _ = pair
    s_star = richardson(f["sigma_eq"], c["sigma_eq"], r_s, 2)
    truth = _fatigue_truth(f["region"])
    if truth is not None:            # the axisymmetric truth of the hot spot's fillet
        s_star = truth
    lin = f.get("tensor_linear")
    life, sf = _fatigue_eval(f["tensor"], s_star / f["sigma_eq"], lin)
    # amplification: d ln(life) / d ln(sigma) at the reference (central difference, ±1 %)
    lp, _ = _fatigue_eval(f["tensor"], 1.01 * s_star / f["sigma_eq"], lin)
    lm, _ = _fatigue_eval(f["tensor"], 0.99 * s_star / f["sigma_eq"], lin)
    slope = (math.log(lp) - math.log(lm)) / (math.log(1.01) - math.log(0.99)) \
        if all(math.isfinite(v) and v > 0 for v in (lp, lm)) else float("nan")
    return {"fine_level": f["level"], "coarse_level": c["level"], "fine_dofs": f["dofs"],
            "r_stress": r_s, "p_stress": 2, "same_hot_spot": f["region"] == c["region"],
            "region": f["region"], "x": f["x"],
            "sigma_eq": {"fine": f["sigma_eq"], "coarse": c["sigma_eq"], "extrapolated": s_star},
            "life": {"fine": f["life"], "coarse": c["life"], "extrapolated": life},
            "sf": {"fine": f["sf"], "coarse": c["sf"], "extrapolated": sf},
            "dlnL_dlnS": slope, "truth": truth is not None}


def _fatigue_truth(region: str) -> float | None:
    """The von Mises peak of ``region`` (a fillet outside the keyways' zones) at 10 000 rpm
    from the axisymmetric truth (reports/benchmarks/truth.json), for the load case the fatigue
    rows ran (``shaftfe fatigue``'s default: every part; or the seed load case), or None."""
    try:
        data = json.loads(TRUTH_JSON.read_text())
        if _fatigue_defaults().seed_load_case:
            return float(data["x2_57_seed_load_case"][region]["von_mises"])
        hit = [r for r in data["records"] if r["case"] == f"x2_57 {region}"
               and r["quantity"] == "von_mises"]
        return float(hit[0]["truth_MPa"]) if hit else None
    except (OSError, ValueError, KeyError, TypeError, IndexError):
        return None


def _ref_freq(rows: list[dict]) -> dict:
    """Finest 3D solid run if any, else the finest beam at the tightest tolerance, with a
    Richardson correction (observed order from the three finest sizes) when it is in range."""
    solid = [r for r in rows if r["kind"] == "freq_solid"]
    if solid:
        f = min(solid, key=lambda r: (-r["dofs"], r["tol"]))
        return {"source": f"the finest 3D solid run ({f['name']}, {f['dofs']} dofs; not "
                          "extrapolated: one level per order is not enough for it)",
                "f0": f["f0"], "f1": f["f1"], "modes": f.get("modes"), "finest": f["name"],
                "extrapolated": False}
    beams = [r for r in rows if r["kind"] == "freq_beam"]
    if not beams:
        return {}
    tmin = min(r["tol"] for r in beams)
    seq = sorted((r for r in beams if r["tol"] == tmin), key=lambda r: -r["h"])
    f = seq[-1]
    ref = {"source": f"finest beam ({f['name']})", "finest": f["name"], "f0": f["f0"],
           "f1": f["f1"], "modes": f.get("modes"), "extrapolated": False}
    if len(seq) >= 3 and math.isclose(seq[-2]["h"] / seq[-1]["h"], seq[-3]["h"] / seq[-2]["h"]):
        r = seq[-2]["h"] / seq[-1]["h"]
        out = {}
        ok = True
        for key in ("f0", "f1"):
            vals = []
            for a, b, c in zip(seq[-3][key], seq[-2][key], seq[-1][key], strict=True):
                d1, d2 = b - a, c - b
                if d1 == 0 or d2 == 0 or d1 * d2 < 0 or abs(d2) < 1e-12 * abs(c):
                    vals.append(c)
                    continue
                p = math.log(abs(d1 / d2)) / math.log(r)
                if not 0.5 < p < 10:
                    ok = False
                    vals.append(c)
                    continue
                vals.append(c + d2 / (r ** p - 1))
            out[key] = vals
        if ok:
            ref.update(out, extrapolated=True)
    return ref


def analyse(data: dict) -> dict:
    from benchmarks._pareto import fastest_within, pareto_mask
    levels = dict(data.get("levels") or _levels_info())
    seen: dict[str, set] = {}
    for r in data["runs"]:
        if r.get("level_settings"):
            seen.setdefault(r["level"], set()).add(json.dumps(r["level_settings"],
                                                              sort_keys=True))
    mixed = sorted(k for k, v in seen.items() if len(v) > 1)
    for k, v in seen.items():
        if len(v) == 1:
            levels[k] = json.loads(next(iter(v)))    # the settings the runs really used
    rows = _merge(data["runs"])
    sref_own = _ref_static(rows, levels)
    sref_json = _static_json_reference()
    sref_truth = _truth_reference()
    fref = _ref_fatigue(rows, levels)
    qref = _ref_freq(rows)
    dsolver = data.get("default_solver") or _default_solver()
    fdef = data.get("fatigue_default_level", "default")
    sdef = data.get("static_default_level", "default")
    refs = {"static_own": sref_own, "static_json": sref_json, "truth": sref_truth,
            "fatigue": fref, "frequencies": {k: v for k, v in qref.items()}}

    def ref_of(k):
        if sref_truth and k in sref_truth:
            return sref_truth[k], "truth.json (axisymmetric)"
        if sref_json and k in sref_json:
            return sref_json[k], "static_reference.json"
        if k in sref_own:
            return sref_own[k]["extrapolated"], "own"
        return None, None

    tables = {}
    static_rows = [r for r in rows if r["kind"] in ("static", "beam_static", "zoned_static",
                                                    "axi_static")]
    fat_rows = [r for r in rows if r["kind"] in ("fatigue", "beam_fatigue", "zoned_fatigue")]
    freq_rows = [r for r in rows if r["kind"] in ("freq_beam", "freq_solid")]
    for r in static_rows + fat_rows:
        if r["kind"] in ("static", "fatigue"):
            r["family"] = f"3D P{r['order']} {r['solver_used']}"
            r["short"] = f"{r['level'][:4]} P{r['order']}{r['solver_used'][0]}"
        elif r["kind"] in ("zoned_static", "zoned_fatigue"):
            r["family"] = "zoned (axisymmetric + 3D zones)"
            r["short"] = "zoned"
        elif r["kind"] == "axi_static":
            r["family"] = "axisymmetric"
            r["short"] = f"axi {r['level'][:4]}"
        else:
            r["family"] = "beam " + ("spread" if r["spread"] else "point loads")
            r["short"] = f"b{r['h']:g}{'s' if r['spread'] else 'p'}"
    for r in freq_rows:
        if r["kind"] == "freq_beam":
            r["family"] = f"beam tol {r['tol']:g}"
            r["short"] = f"h{r['h']:g}"
        else:
            r["family"] = "3D solid P2" if r["order"] == 2 else "3D solid P1"
            r["short"] = f"3D {r['level'][:4]} t{r['tol']:g}"
    # errors
    for r in static_rows:
        rc, _ = ref_of("collar")
        rb, _ = ref_of("bsg")
        if rc and rb:
            r["e_collar"], r["e_bsg"] = r["collar"] / rc - 1, r["bsg"] / rb - 1
            r["e_stress"] = max(abs(r["e_collar"]), abs(r["e_bsg"]))
        rg, _ = ref_of("gear_defl")
        if rg:
            r["e_deflection"] = r["gear_defl"] / rg - 1
        es = []
        for b, q in r["reactions"].items():
            rr, _ = ref_of(f"R:{b}")
            if rr:
                r[f"e_R:{b}"] = q / rr - 1
                es.append(abs(q / rr - 1))
        if es:
            r["e_reactions"] = max(es)
    if fref:
        L, S, s_star = fref["life"]["extrapolated"], fref["sf"]["extrapolated"], \
            fref["sigma_eq"]["extrapolated"]
        # a life of 0 blocks at the reference (the hot spot's largest cycle beyond the S-N
        # card: it fails in the first block) has no relative error: the front is then drawn
        # on the safety factor at the design life (``fref["judged_on"]``)
        on_life = math.isfinite(L) and L > 0
        fref["judged_on"] = "life" if on_life else "safety factor"
        for r in fat_rows:
            r["e_sf"] = r["sf"] / S - 1
            r["e_sigma"] = r["sigma_eq"] / s_star - 1
            if not on_life:
                r["e_fatigue"], r["e_life"] = r["e_sf"], None
                r["amplification"] = None
                continue
            r["e_fatigue"] = r["life"] / L - 1 if math.isfinite(r["life"]) else float("inf")
            r["e_life"] = r["e_fatigue"]
            r["amplification"] = (math.log(r["life"] / L) / math.log(r["sigma_eq"] / s_star)
                                  if math.isfinite(r["life"]) and r["life"] > 0
                                  and abs(r["e_sigma"]) > 1e-4 else None)
    if qref:
        for r in freq_rows:
            if qref.get("extrapolated") or not (r.get("modes") and qref.get("modes")):
                pairs = [({"f0": a, "f1": c}, {"f0": b, "f1": d}) for a, b, c, d in
                         zip(r["f0"], qref["f0"], r["f1"], qref["f1"], strict=True)]
                r["pairing"] = "sorted"
            else:
                from benchmarks._pareto import pair_modes
                pairs = pair_modes(r["modes"], qref["modes"])
                r["pairing"] = "family+whirl"
            r["n_paired"] = len(pairs)
            if not pairs:
                continue
            e0 = [a["f0"] / b["f0"] - 1 for a, b in pairs]
            e1 = [a["f1"] / b["f1"] - 1 for a, b in pairs]
            r["e_f0"] = max(e0, key=abs)
            r["e_f1"] = max(e1, key=abs)
            r["e_frequencies"] = max(abs(r["e_f0"]), abs(r["e_f1"]))
            fam: dict[str, float] = {}
            for (a, _ref), x0, x1 in zip(pairs, e0, e1, strict=True):
                f = a.get("family", "all")
                fam[f] = max(fam.get(f, 0.0), abs(x0), abs(x1))
            r["e_by_family"] = fam
    # defaults
    # the defaults: the zoned model (issue #32) for `shaftfe static` and `shaftfe fatigue`
    for r in static_rows:
        r["default"] = r["kind"] == "zoned_static" and r["level"] == sdef
    for r in fat_rows:
        r["default"] = r["kind"] == "zoned_fatigue" and r["level"] == fdef
    for r in freq_rows:
        r["default"] = (r["kind"] == "freq_beam" and r["h"] == data.get("freq_default_h", 5.0)
                        and r["tol"] == data.get("freq_default_tol", 1e-6))
    groups = {"stress": static_rows, "deflection": static_rows, "reactions": static_rows,
              "fatigue": fat_rows, "frequencies": freq_rows}
    for q, rs in groups.items():
        ek = f"e_{q}"
        sel = [dict(r) for r in rs if r.get(ek) is not None]
        if not sel:
            continue
        for r in sel:
            r["warm_or_cold_s"] = r.get("warm_wall_s", r["cold_wall_s"])
        E = [abs(r[ek]) if math.isfinite(r[ek]) else float("inf") for r in sel]
        fronts = {
            "front_wall": pareto_mask([(r["cold_wall_s"], e) for r, e in zip(sel, E,
                                                                              strict=True)]),
            "front_cpu": pareto_mask([(r["child_cpu_s"], e) for r, e in zip(sel, E,
                                                                             strict=True)]),
            "front_warm": pareto_mask([(r["warm_or_cold_s"], e) for r, e in zip(sel, E,
                                                                                 strict=True)]),
            "front_mem": pareto_mask([(r["cold_wall_s"], r["rss_MB"], e)
                                      for r, e in zip(sel, E, strict=True)]),
            "front_rss": pareto_mask([(r["rss_MB"], e) for r, e in zip(sel, E, strict=True)]),
        }
        for name, mask in fronts.items():
            for r, m in zip(sel, mask, strict=True):
                r[name] = m
        d = next((r for r in sel if r["default"]), None)
        fast = fastest_within(sel, ek, "cold_wall_s", TOL)
        fast_cpu = fastest_within(sel, ek, "child_cpu_s", TOL)
        best = min(sel, key=lambda r: abs(r[ek]))
        from benchmarks._pareto import dominates
        dom = {}
        for key, tk in (("wall", "cold_wall_s"), ("cpu", "child_cpu_s")):
            dom[f"dominated_by_{key}"] = [] if d is None else [
                r["name"] for r in sel if dominates((r[tk], abs(r[ek])), (d[tk], abs(d[ek])))]
        tables[q] = {"rows": sel, "default": d, "fastest_1pct": fast,
                     "fastest_1pct_cpu": fast_cpu, "best": best, **dom}
    loads = [r["load_before"] for r in data["runs"]] + [r["load_after"] for r in data["runs"]]
    return {"tables": tables, "refs": refs, "default_solver": dsolver, "levels": levels,
            "mixed_levels": mixed,
            "load": {"min": min(loads), "max": max(loads), "mean": sum(loads) / len(loads)}
            if loads else {}}


# =========================================================================== report

def _pct(e, digits=2) -> str:
    if e is None:
        return "–"
    if not math.isfinite(e):
        return "∞"
    return f"{e * 100:+.{digits}f} %"


def _s(v, fmt="{:.2f}") -> str:
    return "–" if v is None else fmt.format(v)


def _flags(r) -> str:
    return " ".join(("W" if r["front_wall"] else "·", "C" if r["front_cpu"] else "·",
                     "w" if r["front_warm"] else "·", "M" if r["front_mem"] else "·"))


_TITLE = {"stress": "Peak fillet von Mises stress (collar and bearing-seat-gear fillets, "
                    "10 000 rpm)",
          "deflection": "Deflection at the gear seat (10 000 rpm)",
          "reactions": "Bearing reactions (10 000 rpm)",
          "fatigue": "Fatigue life at the hot spot (loadspectra/rpm.dat, shaftfe fatigue settings)",
          "frequencies": f"First {N_MODES} natural frequencies at 0 and {TOP_RPM:g} rpm"}


def _values(q: str, r: dict) -> list[str]:
    if q == "stress":
        return [f"{r['collar']:.1f}", _pct(r.get("e_collar"), 1), f"{r['bsg']:.1f}",
                _pct(r.get("e_bsg"), 1)]
    if q == "deflection":
        return [f"{r['gear_defl']:.5f}", _pct(r.get("e_deflection"), 3)]
    if q == "reactions":
        return [" / ".join(f"{v:.1f}" for v in r["reactions"].values()),
                " / ".join(_pct(r.get(f"e_R:{b}"), 3) for b in r["reactions"])]
    if q == "fatigue":
        life = "∞" if not math.isfinite(r["life"]) else f"{r['life']:.4g}"
        amp = "–" if r.get("amplification") is None else f"{r['amplification']:.2f}"
        return [f"{r['sigma_eq']:.1f}", _pct(r.get("e_sigma"), 1), life,
                _pct(r.get("e_life"), 1), f"{r['sf']:.3f}", _pct(r.get("e_sf"), 1), amp,
                f"{r['region']} x={r['x']:.1f}"]
    if q == "frequencies":
        return [f"{r['f0'][0]:.1f}…{r['f0'][-1]:.1f}", _pct(r.get("e_f0"), 4),
                _pct(r.get("e_f1"), 4), f"{r.get('n_paired', '–')} ({r.get('pairing', '')})",
                str(r.get("basis", "–"))]
    return []


_HEAD = {"stress": ["collar MPa", "err", "bsg MPa", "err"],
         "deflection": ["u gear mm", "err"],
         "reactions": ["F gear-side / free-side N", "err"],
         "fatigue": ["σ_eq hot spot MPa @10k", "err σ", "life blocks", "err life", "SF @1e7",
                     "err SF", "dlnL/dlnσ", "hot spot"],
         "frequencies": ["f1…f12 at 0 rpm Hz", "max err 0 rpm", f"max err {TOP_RPM:g} rpm",
                         "modes paired", "basis"]}


_SCOPE = {
    "stress": "`shaftfe static` has ONE default, the zoned model at `default`, for stress, "
              "deflection and reactions together",
    "deflection": "`shaftfe static` has ONE default, the zoned model at `default`, for stress, "
                  "deflection and reactions together",
    "reactions": "`shaftfe static` has ONE default, the zoned model at `default`, for stress, "
                 "deflection and reactions together",
    "fatigue": "`shaftfe fatigue --method seed` on its default static model, the zoned one at "
               "`default`",
    "frequencies": "`shaftfe campbell` / `modal` default: `--max-element` and the basis "
                   "tolerance of `shaftfe.rotordynamics.beam_rotor.campbell`",
}


def _front_sentence(d: dict, t: dict, key: str, what: str) -> str:
    if d[f"front_{key}"]:
        return f"It IS on the Pareto front of {what} against error."
    dom = ", ".join(t[f"dominated_by_{key}"]) or "?"
    return (f"It is **NOT on the Pareto front** of {what} against error: dominated by {dom} "
            "(no slower, no less accurate, better in one).")


def _why(q: str, t: dict, ref_text: str) -> list[str]:
    """The paragraph on the default, generated from the measured numbers."""
    ek = f"e_{q}"
    d, best = t["default"], t["best"]
    rows = t["rows"]
    if d is None:
        return [f"No run of the default configuration for this quantity: nothing to say about "
                f"it. ({ref_text})"]
    e_d = abs(d[ek])
    out = [f"**Default** ({d['name']}; {_SCOPE[q]}): error {_pct(d[ek])} against the "
           f"reference, {d['cold_wall_s']:.3g} s cold wall"
           + (f" / {d['warm_wall_s']:.3g} s warm" if "warm_wall_s" in d else "")
           + f", {d['child_cpu_s']:.3g} s child CPU, {d['rss_MB']:.0f} MB peak RSS.",
           _front_sentence(d, t, "wall", "cold wall time"),
           _front_sentence(d, t, "cpu", "child CPU time")]
    if d["front_mem"] and not (d["front_wall"] and d["front_cpu"]):
        out.append("With peak memory as a third objective it is on the front.")
    es = [abs(r[ek]) for r in rows if math.isfinite(r[ek])]
    out.append(f"Across the {len(rows)} configurations |error| spans {min(es):.2%} to "
               f"{max(es):.2%}.")
    cheaper = [r for r in rows if r["child_cpu_s"] < d["child_cpu_s"]]
    if cheaper:
        c_best = min(cheaper, key=lambda r: abs(r[ek]))
        out.append(f"Of the {len(cheaper)} configurations with less CPU time the most accurate "
                   f"is {c_best['name']} ({_pct(c_best[ek])}, {c_best['child_cpu_s']:.3g} s "
                   "CPU).")
    else:
        out.append("No configuration takes less CPU time.")
    fast_w, fast_c = t["fastest_1pct"], t["fastest_1pct_cpu"]
    if fast_w is None:
        out.append(f"No configuration reaches {TOL:.0%}: the most accurate is {best['name']} "
                   f"({_pct(best[ek])}, {best['cold_wall_s']:.3g} s wall, "
                   f"{best['child_cpu_s']:.3g} s CPU, {best['rss_MB']:.0f} MB).")
    else:
        for f, what, key in ((fast_c, "child CPU", "child_cpu_s"),
                             (fast_w, "cold wall", "cold_wall_s")):
            if f is d:
                out.append(f"It is the fastest configuration within {TOL:.0%} by {what} time.")
            else:
                out.append(f"The fastest configuration within {TOL:.0%} by {what} time is "
                           f"{f['name']} ({_pct(f[ek])}, {f[key]:.3g} s = "
                           f"{f[key] / d[key]:.3g}× the default's, {f['rss_MB']:.0f} MB).")
    fast = fast_c
    if e_d <= TOL and fast is d:
        out.append(f"Why it is the default: it meets the {TOL:.0%} target at the lowest "
                   "measured CPU cost.")
    elif e_d <= TOL:
        dt = d["child_cpu_s"] - fast["child_cpu_s"]
        out.append(f"Why it is the default: it meets the {TOL:.0%} target; for this quantity "
                   f"alone {fast['name']} would too, with {dt:.3g} s ({dt / d['child_cpu_s']:.0%})"
                   " less CPU: the default is set by the output of its command that needs "
                   "the most accuracy, not by this one.")
        if d["kind"] == "zoned_static":
            out.append("The zoned model's extra cost is its 3D zones at the keyways and the hex "
                       "socket, which the axisymmetric model leaves out and the span fillets "
                       "measured here do not show (their peaks: reports/benchmarks/zoned.md).")
    elif fast is not None:
        out.append(f"Why it is the default anyway: it misses {TOL:.0%} for this quantity "
                   f"({_pct(d[ek])}); meeting it costs {fast['child_cpu_s']:.3g} s CPU instead "
                   f"of {d['child_cpu_s']:.3g} s ({fast['rss_MB']:.0f} MB instead of "
                   f"{d['rss_MB']:.0f} MB): the default trades this accuracy for time — use "
                   f"{fast['name']} when this quantity matters.")
    else:
        out.append(f"No setting offered reaches {TOL:.0%}, so the default is a time/accuracy "
                   "compromise, not a converged answer.")
    out.append(ref_text)
    return [" ".join(out)]


def _ref_text(q: str, res: dict) -> str:
    refs = res["refs"]
    so, sj, fr, qr = refs["static_own"], refs["static_json"], refs["fatigue"], \
        refs["frequencies"]
    if q in ("stress", "deflection", "reactions"):
        if not so:
            return "Reference: none (fewer than two P2 levels ran)."
        base = (f"Reference: Richardson extrapolation of the two finest P2 levels of this run "
                f"({so['fine_level']}, {so['fine_dofs']} dofs, and {so['coarse_level']}; "
                f"fillet size ratio {so['r_stress']:.3g}, p = 2 for stresses; element-count "
                f"ratio^(1/3) = {so['r_volume']:.3g}, p = 3 for displacements and reactions).")
        if q == "stress":
            step_c = so["collar"]["extrapolated"] / so["collar"]["fine"] - 1
            step_b = so["bsg"]["extrapolated"] / so["bsg"]["fine"] - 1
            s = (f" Collar: fine {so['collar']['fine']:.1f}, extrapolated "
                 f"{so['collar']['extrapolated']:.1f} MPa; bearing-seat-gear: fine "
                 f"{so['bsg']['fine']:.1f}, extrapolated {so['bsg']['extrapolated']:.1f} MPa "
                 f"(the fine-to-extrapolated step, {step_c:+.1%} / {step_b:+.1%}, is the "
                 "size of "
                 "the reference's own uncertainty).")
            st = refs.get("truth")
            if st:
                return base + s + (
                    f" Used instead for the stresses: the TRUTH, the axisymmetric path "
                    f"converged by Richardson (reports/benchmarks/truth.json, {st['_mtime']}: "
                    f"collar {st['collar']:.3f} ± {st['collar_bar']:.3f}, bearing-seat-gear "
                    f"{st['bsg']:.3f} ± {st['bsg_bar']:.3f} MPa; issue #12: the 3D path's own "
                    "extrapolation shares its recovery's bias, so it is not a truth). For the "
                    "axisymmetric and zoned rows, whose fillet peaks are the axisymmetric "
                    "model's, that error measures their convergence, not an independent check "
                    "(those are docs/VALIDATION.md's).")
            if sj:
                s += (f" Used instead for the stresses: the reference in static_reference.json "
                      f"({sj['_mtime']}: collar {sj['collar']:.1f}, bsg {sj['bsg']:.1f} MPa; "
                      f"{sj['_note']}).")
            return base + s
        if q == "deflection":
            g = so["gear_defl"]
            return base + (f" Gear seat: fine {g['fine']:.6f}, extrapolated "
                           f"{g['extrapolated']:.6f} mm.")
        rs = [(k[2:], v) for k, v in so.items() if k.startswith("R:")]
        return base + " " + "; ".join(f"{b}: fine {v['fine']:.2f}, extrapolated "
                                      f"{v['extrapolated']:.2f} N" for b, v in rs) + "."
    if q == "fatigue":
        if not fr:
            return "Reference: none."
        s = fr["sigma_eq"]
        on_sf = (" The reference hot spot's life is 0 blocks (its largest cycle lies beyond "
                 "the S-N card: it fails in the first block), so a relative life error has no "
                 "meaning here: the front and the error column are on the safety factor at "
                 "the design life." if fr.get("judged_on") == "safety factor" else "")
        if fr.get("truth"):
            lc = "the seed load case" if _fatigue_defaults().seed_load_case else "every part"
            return (f"Reference: the TRUTH of the hot spot's fillet ({fr['region']}): its von "
                    f"Mises peak ({lc}) at 10 000 rpm from the axisymmetric "
                    f"path converged by Richardson (reports/benchmarks/truth.json), "
                    f"{s['extrapolated']:.2f} MPa; the reference life "
                    f"{fr['life']['extrapolated']:.4g} blocks and safety factor "
                    f"{fr['sf']['extrapolated']:.3f} are the finest level's hot-spot stress "
                    f"tensor ({fr['fine_level']}, {s['fine']:.1f} MPa) scaled to it and "
                    f"evaluated with the same fatigue API (finest run itself: "
                    f"{fr['life']['fine']:.4g} blocks, SF {fr['sf']['fine']:.3f}). The 3D "
                    "levels' own extrapolation is not used: it shares their recovery's bias "
                    "(issue #12)." + on_sf)
        return (f"Reference: the hot-spot equivalent stress of the two finest P2 levels "
                f"({fr['fine_level']} {s['fine']:.1f} MPa, {fr['coarse_level']} "
                f"{s['coarse']:.1f} MPa at 10 000 rpm, seed load case) extrapolated (p = 2, "
                f"r = {fr['r_stress']:.3g}) to {s['extrapolated']:.1f} MPa; the reference life "
                f"{fr['life']['extrapolated']:.4g} blocks and safety factor "
                f"{fr['sf']['extrapolated']:.3f} are the fine level's hot-spot stress tensor "
                f"scaled to that value and evaluated with the same fatigue API (finest run "
                f"itself: {fr['life']['fine']:.4g} blocks, SF {fr['sf']['fine']:.3f})."
                + ("" if fr["same_hot_spot"] else " The hot spot is NOT in the same region on "
                   "the two finest levels: the extrapolation is doubtful.") + on_sf)
    if not qr:
        return "Reference: none."
    return (f"Reference: {qr['source']}"
            + (", Richardson-extrapolated per mode (observed order)" if qr["extrapolated"]
               else "") + ". Modes are paired by class (family lateral / torsional / axial and "
            "whirl forward / backward, from the Campbell labels) and by order within the "
            "class, so models whose mode order differs are compared mode for mode; *modes "
            "paired* says how many of the 12 found a partner (the error is over those)."
            + _family_text(res))


def _family_text(res: dict) -> str:
    """The default beam row's largest error per mode family: the beam-vs-3D difference is the
    model (twist held at one node vs at both bearings; rigid disks vs tied hubs), not the
    discretisation, and is largest for the torsional modes."""
    rows = [r for r in res.get("tables", {}).get("frequencies", {}).get("rows", [])
            if r.get("default") and r.get("e_by_family")]
    if not rows:
        return ""
    fam = rows[0]["e_by_family"]
    parts = ", ".join(f"{k} {100 * v:.1f} %" for k, v in sorted(fam.items()))
    return (f" The default beam row's largest error per family: {parts}. That is the model, "
            "not the mesh (the beam converges to its own answer at h = 20 mm): the beam holds "
            "the twist at one node where the 3D model holds it at both bearings, and its disks "
            "add no seat stiffness where the 3D tie is rigid; the bearing-dominated lateral "
            "modes agree best (docs/VALIDATION.md, Rotor dynamics). The beam is the fast "
            "check; the 3D solid (`--model solid`) is the reference for the torsional and "
            "higher modes.")


def write_report(data: dict) -> dict:
    from benchmarks._pareto import plot_pareto
    res = analyse(data)
    T = res["tables"]
    lv = res["levels"]
    runs = data["runs"]
    sv = data.get("solvers", {})
    L = ["# Run time against error: one Pareto front per quantity (x2_57)", "",
         f"Generated by `python -m benchmarks bench_pareto` (benchmarks/bench_pareto.py) on "
         f"{data.get('generated', '?')}"
         + (" — **QUICK run (subset; reference not converged)**" if data.get("quick") else "")
         + f". {len(runs)} runs, each a fresh subprocess. Machine: {os.cpu_count()} cores "
         "shared with other work; `uptime` at start: "
         f"`{data.get('uptime_start', '?')}`, at end: `{data.get('uptime_end', '?')}`; "
         f"1-minute load over the runs {res['load'].get('min', 0):.2f}–"
         f"{res['load'].get('max', 0):.2f} (mean {res['load'].get('mean', 0):.2f}): wall "
         "times are inflated by the others' work, CPU times much less.", "",
         "Mesh levels (the settings the FE runs report having used): "
         + "; ".join(f"`{k}` " + ", ".join(f"{a}={b:g}" for a, b in v.items())
                     for k, v in lv.items()) + ". "
         f"Linear solvers offered (shaftfe.fe.solvers.available()): "
         f"{', '.join(k for k, v in sv.items() if v) or '?'}; not "
         f"installed: {', '.join(k for k, v in sv.items() if not v) or 'none'}. "
         f"Default solver (`auto`) here: {res['default_solver']}. SuperLU is not run above "
         f"{SUPERLU_MAX_DOFS} dofs.", "",
         "Columns: *wall* = wall time of the computation inside the child (cold: empty mesh "
         "cache, Gmsh runs; warm: the same again on that cache — for the beam rows, which have "
         "no cache, the best of up to 5 in-process repeats, fewer when they exceed 3 s); "
         "*CPU* = user + sys time of that computation (`time.process_time`, every "
         "thread); *child CPU* = the whole child's user + sys "
         "(`getrusage(RUSAGE_CHILDREN)`: interpreter start and imports included; "
         "beam rows: without those repeats); *RSS* = the child's peak resident memory "
         "(`ru_maxrss`); *load* = 1-minute load average when the cold run started. Front "
         "flags: W = on the Pareto front of (cold wall time, |error|), C = (child CPU time, "
         "|error|), w = (warm wall time, |error|), M = (cold wall time, peak RSS, |error|). "
         "The plots draw W (left), C (middle) and (RSS, |error|) (right). With the machine "
         "this loaded, C is the robust time axis; W is what a user waited. ★ = the default.",
         ""]
    summary = {}
    for q in QUANTITIES:
        if q not in T:
            L += [f"## {_TITLE[q]}", "", "Not run in this invocation.", ""]
            continue
        t = T[q]
        ek = f"e_{q}"
        png = OUT / f"pareto_{q}.png"
        elabel = {"stress": "worse fillet-peak error |e| (%)",
                  "deflection": "gear-seat deflection error |e| (%)",
                  "reactions": "worse bearing-reaction error |e| (%)",
                  "fatigue": "hot-spot life error |L/L* − 1| (%)",
                  "frequencies": f"max frequency error over {N_MODES} modes × 2 speeds |e| (%)"}[q]
        plot_pareto(png, t["rows"], err_key=ek, title=_TITLE[q], err_label=elabel,
                    axes=[("cold_wall_s", "wall time, cold cache (s)", "front_wall"),
                          ("child_cpu_s", "CPU time user+sys of the child process (s)",
                           "front_cpu"),
                          ("rss_MB", "peak memory RSS (MB)", "front_rss")], floor=FLOOR)
        L += [f"## {_TITLE[q]}", "", f"![{q}](pareto_{q}.png)", ""]
        L += _why(q, t, _ref_text(q, res))
        L += [""]
        head = ["", "configuration", "dofs", "wall cold s", "wall warm s", "CPU cold s",
                "child CPU s", "RSS MB", "load"] + _HEAD[q] + ["front W C w M"]
        L += ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
        for r in sorted(t["rows"], key=lambda r: r["cold_wall_s"]):
            L.append("| " + " | ".join(
                ["★" if r["default"] else "", r["name"], str(r.get("dofs", "–")),
                 f"{r['cold_wall_s']:.3g}", _s(r.get("warm_wall_s"), "{:.3g}"),
                 f"{r['cold_cpu_s']:.3g}", f"{r['child_cpu_s']:.3g}", f"{r['rss_MB']:.0f}",
                 f"{r['load_before']:.2f}", *_values(q, r), _flags(r)]) + " |")
        L.append("")
        d, f1 = t["default"], t["fastest_1pct"]
        summary[q] = {
            "default": None if d is None else {
                "name": d["name"], "error": d[ek], "cold_wall_s": d["cold_wall_s"],
                "warm_wall_s": d.get("warm_wall_s"), "cpu_s": d["cold_cpu_s"],
                "child_cpu_s": d["child_cpu_s"],
                "rss_MB": d["rss_MB"], "on_front_wall": d["front_wall"],
                "on_front_cpu": d["front_cpu"], "on_front_mem": d["front_mem"],
                "dominated_by_wall": t["dominated_by_wall"],
                "dominated_by_cpu": t["dominated_by_cpu"]},
            "fastest_within_1pct_wall": None if f1 is None else {
                "name": f1["name"], "error": f1[ek], "cold_wall_s": f1["cold_wall_s"],
                "child_cpu_s": f1["child_cpu_s"], "rss_MB": f1["rss_MB"]},
            "fastest_within_1pct_cpu": None if t["fastest_1pct_cpu"] is None else {
                "name": t["fastest_1pct_cpu"]["name"], "error": t["fastest_1pct_cpu"][ek],
                "cold_wall_s": t["fastest_1pct_cpu"]["cold_wall_s"],
                "child_cpu_s": t["fastest_1pct_cpu"]["child_cpu_s"],
                "rss_MB": t["fastest_1pct_cpu"]["rss_MB"]},
            "most_accurate": {"name": t["best"]["name"], "error": t["best"][ek],
                              "cold_wall_s": t["best"]["cold_wall_s"]}}
    if "fatigue" in T and res["refs"]["fatigue"] \
            and res["refs"]["fatigue"].get("judged_on") != "safety factor":
        fr = res["refs"]["fatigue"]
        amps = [r["amplification"] for r in T["fatigue"]["rows"]
                if r.get("amplification") is not None and r["kind"] == "fatigue"]
        L += ["## Life is very sensitive to the stress", "",
              f"At the reference hot spot, d ln(life) / d ln(σ) = {fr['dlnL_dlnS']:.2f} "
              f"(central difference ±1 % in stress through the fatigue API): a stress error "
              f"e gives a life error ≈ (1 + e)^({fr['dlnL_dlnS']:.2f}) − 1, e.g. "
              f"{_pct((0.99) ** fr['dlnL_dlnS'] - 1, 1)} for −1 % and "
              f"{_pct((0.92) ** fr['dlnL_dlnS'] - 1, 1)} for −8 %. Measured over the FE "
              f"runs, ln(L/L*) / ln(σ/σ*) = "
              + (f"{min(amps):.2f} … {max(amps):.2f}" if amps else "–")
              + " (column dlnL/dlnσ). The safety factor scales exactly as 1/σ "
              "(its error column mirrors the stress error), so it is the robust number to "
              "report; the life inherits the S-N slope (and the mean-stress correction) as an "
              "amplifier of every stress error.", ""]
    L += ["## What is missing / caveats", ""]
    miss = []
    if res["mixed_levels"]:
        miss.append("**The mesh-level settings changed while this benchmark ran** (levels "
                    + ", ".join(res["mixed_levels"]) + "): runs of those levels used different "
                    "meshes, so their rows are not comparable. Re-run.")
    if not any(r["kind"] == "freq_solid" for r in runs):
        miss.append("The 3D solid modal path (`shaftfe/rotordynamics/solid_rotor.py`) was "
                    "not available "
                    "when this ran (absent or without `campbell_from_variant`): the frequency "
                    "front covers the beam rotor only, and its reference is the finest beam, "
                    "which measures the beam's discretisation error, NOT the modelling error "
                    "against a 3D solid.")
    if not data.get("solvers", {}).get("amg", True):
        miss.append("AMG-CG (`amg`) is offered by shaftfe.fe.solvers but `pyamg` is not "
                    "installed: not run.")
    if res["refs"]["static_json"] is None:
        miss.append("reports/benchmarks/static_reference.json carried no reference when this ran: "
                    "the static references are this benchmark's own extrapolation.")
    miss.append("Warm runs differ from cold ones only by the Gmsh build (mesh cache hit); the "
                "static-solution cache of `shaftfe fatigue` is bypassed (`use_cache=False`) so "
                "every fatigue run solves; a real second `shaftfe fatigue` reads the cached "
                "solution and takes well under a second.")
    miss.append("The beam rows have no cache: cold only. Their times are milliseconds, their "
                "RSS is the interpreter's with NumPy/SciPy.")
    L += [f"- {m}" for m in miss] + [""]
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "pareto.md").write_text("\n".join(L) + "\n")
    data = dict(data, summary=summary, references=res["refs"], load=res["load"])
    (OUT / "pareto.json").write_text(json.dumps(data, indent=1, default=str,
                                                allow_nan=True) + "\n")
    print(f"wrote {OUT / 'pareto.md'}, pareto.json, pareto_<quantity>.png")
    return summary


# =========================================================================== main

def _args(argv: list[str]):
    p = argparse.ArgumentParser(prog="bench_pareto")
    p.add_argument("--quick", action="store_true")
    p.add_argument("--parts", default="")
    p.add_argument("--levels", default="")
    p.add_argument("--solid-levels", default="")
    p.add_argument("--resume", action="store_true")
    p.add_argument("--report-only", action="store_true")
    a, _ = p.parse_known_args(argv)
    a.argv = argv
    return a


def main() -> None:
    argv = [x for x in sys.argv[1:] if x != "bench_pareto"]
    argv += shlex.split(os.environ.get("SHAFTFE_PARETO", ""))
    args = _args(argv)
    if args.report_only:
        data = json.loads((OUT / "pareto.json").read_text())
        write_report(data)
        return
    from shaftfe.fe import solvers
    from shaftfe.static.model import StaticOptions
    data = run_all(args)
    data.update(generated=_dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC"),
                levels=_levels_info(), solvers=solvers.available(),
                default_solver=_default_solver(),
                static_default_level=StaticOptions().level,
                fatigue_default_level=_fatigue_defaults().level,
                freq_default_h=_campbell_default("max_element"),
                freq_default_tol=_campbell_tol_default())
    if (args.parts or args.levels) and not args.resume and (OUT / "pareto.json").exists():
        # a partial run keeps the other parts' stored runs (same fingerprint only)
        old = json.loads((OUT / "pareto.json").read_text())
        valid = set(data["fingerprints"].values())
        have = {r["key"] for r in data["runs"]}
        data["runs"] += [r for r in old.get("runs", []) if r["key"] not in have
                         and any(r["key"].endswith(f) for f in valid)]
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "pareto.json").write_text(json.dumps(data, indent=1, default=str) + "\n")
    write_report(data)


def _campbell_tol_default() -> float:
    """The basis tolerance ``shaftfe.rotordynamics.beam_rotor.campbell`` uses when none is given."""
    import inspect

    from shaftfe.rotordynamics import beam_rotor as rotor
    return float(inspect.signature(rotor.campbell).parameters["tol"].default)


def _campbell_default(dest: str):
    """A default of ``shaftfe campbell`` (read from its parser)."""
    from shaftfe.commands import campbell as ccmd
    p = argparse.ArgumentParser()
    ccmd.register(p.add_subparsers())
    return p.parse_args(["campbell", "0:8000"]).__dict__[dest]


if __name__ == "__main__":
    main()
