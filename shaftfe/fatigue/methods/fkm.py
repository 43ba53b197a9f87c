"""FKM guideline (``fatigue.fkm``, ``fatigue.fkm_field``): local stresses on the static field (3D,
axisymmetric or zoned; the stress gradient from each field's own ``DepthProbe``), the
shaft's own strength card, the stress gradient's support factor, three Miner rules; the
bearings' ISO 281 life and the seed's key and gear checks beside it (``fatigue.strength``,
``fatigue.strength_outputs``)."""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType

from shaftfe.fatigue.methods.protocol import AssessmentInputs, FatigueAssessment, life_location


@dataclass(frozen=True, eq=False)
class FkmDetail:
    result: object                   # fatigue.fkm_field.FkmResult
    ref: object                      # the static reference it assessed
    speed_kmh: float
    along: object = None             # fatigue.fkm_field.FkmAlong (``--plot``), or None


class Fkm:
    name = "fkm"
    title = ("FKM guideline, local stresses on the static field, the shaft's real material "
             "and surface")
    options = ("--card", "--miner", "--consequences", "--inspection", "--damage-sum",
               "--kappa", "--ec", "--model", "--level", "--exclude-mm", "--seed-load-case",
               "--spin-softening", "--design-life", "--design-life-h", "--plot")
    narrowed = MappingProxyType({})
    out_dir = "fatigue-fkm"
    files = ("fatigue.vtu", "haigh.png", "rainflow_matrix.png", "damage_matrix.png",
             "summary.json")
    optional_files = ("fkm_along.png",)
    files_help = ("fatigue.vtu (fkm_utilisation, fkm_safety at the assessed surface nodes), "
                  "haigh.png (F2, the governing spot's cycles), rainflow_matrix.png, "
                  "damage_matrix.png, fkm_along.png (with --plot: the utilisation along the "
                  "shaft), summary.json")
    stages = ("static", "FKM")

    def check(self, options) -> None:
        from shaftfe.fatigue import strength as sd
        sd.check_options(sd.strength_options(options))
        sd.bearing_options(options)

    def assess(self, inputs: AssessmentInputs, options, progress=None) -> FatigueAssessment:
        from contextlib import nullcontext

        from shaftfe.fatigue import strength as sd
        from shaftfe.fatigue.cards import load_surfaces
        from shaftfe.fatigue.channel_run import warn_rpm2_only
        from shaftfe.fatigue.fkm_field import assess_field
        from shaftfe.fatigue.run import FatigueInputs, resolve_design_life
        from shaftfe.util.notices import raised
        ch = inputs.single(self.name)
        warn_rpm2_only(inputs.variant, f"--method {self.name}")
        opts = sd.strength_options(options)

        def stage(name):
            return progress.stage(name) if progress is not None else nullcontext()
        with raised() as warned:
            if ch.field is None:
                res, _, ref = sd.run_fkm(options, opts,
                                         FatigueInputs(ch.history, None, inputs.variant),
                                         progress=progress)
            else:                   # the caller's field and count (the report: no second one)
                ref = ch.field
                job = options if options.design_life is not None else \
                    resolve_design_life(options, ch.history, inputs.variant.duty)
                with stage("FKM"):
                    res = assess_field(ref, ch.history, sd.strength_card(inputs.variant, opts),
                                       load_surfaces(),
                                       ground_fillets=sd.ground_fillets(inputs.variant),
                                       rule=opts.rule,
                                       j_D=sd.fkm.J_D[(opts.consequences, opts.inspection)],
                                       damage_sum=opts.damage_sum,
                                       design_life_blocks=job.design_life, cycles=ch.cycles)
            along = None
            if getattr(options, "plot", False):
                from shaftfe.fatigue.fkm_field import assess_along
                with stage("FKM"):
                    along = assess_along(ref, load_surfaces(), res,
                                         ground_fillets=sd.ground_fillets(inputs.variant))
        rule, bs, v = res.rule, res.block_seconds, options.speed_kmh

        def loc(r, c):
            return life_location(r.region, r.xyz_mm[0], c.utilisation[rule], c.safety[rule],
                                 c.life_blocks[rule], bs, v)
        worst = [max((c for c in (r.surface, r.core) if c is not None),
                     key=lambda c: c.utilisation[rule]) for r in res.regions]
        return FatigueAssessment(self.name, tuple(loc(r, c) for r, c in zip(res.regions, worst,
                                                                             strict=True)),
                                 loc(*res.governing), tuple(warned), tuple(res.notes),
                                 FkmDetail(res, ref, v, along))

    def write(self, result, inputs, options, out) -> tuple[dict, list[str]]:
        from shaftfe.fatigue import strength_outputs as so
        res, ref = result.detail.result, result.detail.ref
        along = result.detail.along
        summary = standard_summary(inputs, options, so.fkm_summary(res, along))
        summary["static"] = {"model": options.model, "level": options.level,
                             "ref_rpm": ref.ref_rpm, "points": ref.n_nodes,
                             "from_cache": bool(ref.from_cache)}
        vtu, plots = so.write_fkm_files(res, ref, out)
        if along is not None:
            so.plot_fkm_along(summary, inputs.variant, out / "fkm_along.png")
            plots["fkm_along"] = "fkm_along.png"
        return so.write_outputs({**summary, "vtu": vtu, "plots": plots}, out)

    def lines(self, result, inputs, options, summary, out, files) -> list[str]:
        from shaftfe.fatigue import strength_outputs as so
        from shaftfe.fatigue.assess import life_hours, life_km
        from shaftfe.util.fmt import design_life, lives, table_lines
        res, ref, job = result.detail.result, result.detail.ref, options
        p = head_line(inputs, "FKM", res.card.name, job)
        p.append(f"static ({job.model} model): {'from cache' if ref.from_cache else 'solved'} "
                 f"({ref.ref_rpm:g} rpm, {ref.n_nodes} points, P2 {job.level}); design life "
                 f"{design_life(res.design_life_blocks, res.block_seconds, job.speed_kmh)}; "
                 f"j_D {res.j_D:g}; D_M {res.damage_sum:g}; governing rule: {res.rule}")
        sharp = so.sharp_keyways(inputs.variant)
        p += table_lines(so.FKM_HEAD, so.fkm_rows(res, sharp), title="FKM, local stresses, per "
                         "region (surface layer and core at the case depth)")
        p += so.fkm_notes(res, sharp)
        g, c = res.governing
        b = c.life_blocks[res.rule]
        h = float(life_hours(b, res.block_seconds))
        if so.no_load_cycles(res):
            p.append(f"governing: none: {so.NO_LOAD_CYCLES}")
        else:
            p.append(f"governing: {g.region} ({c.layer}), safety {so._f(c.safety[res.rule])} "
                     f"against j_D {res.j_D:g}, degree of utilisation "
                     f"{so._f(c.utilisation[res.rule])} "
                     f"({'passes' if c.utilisation[res.rule] <= 1 else 'FAILS'}); life: "
                     f"{lives(b, h, float(life_km(h, job.speed_kmh)), job.speed_kmh)}")
            p.append(f"size factor: K_d,m at d_eff {c.d_eff_mm:.2f} mm, the round section "
                     "through the hot spot (FKM; DIN 743 takes its K1 at a shoulder's larger "
                     "diameter)")
        return p + tail_lines(summary, out, files, job)


METHOD = Fkm()


def standard_summary(inputs: AssessmentInputs, options, method_summary: dict,
                     beam=None) -> dict:
    """summary.json of a standard (FKM, DIN 743): the method's block with the bearings' ISO 281
    life over the duty cycle and the seed's key and gear checks (``beam``: the beam solution
    when the method has one)."""
    from shaftfe.fatigue import strength as sd
    from shaftfe.fatigue import strength_outputs as so
    kappa, ec = sd.bearing_options(options)
    v = inputs.variant
    el = so.compute_elements(v, inputs.history, kappa, ec, options.speed_kmh, beam)
    return {"variant": v.name, "spectrum": str(options.spectrum), **method_summary,
            "elements": el}


def head_line(inputs: AssessmentInputs, label: str, card: str, job) -> list[str]:
    """The first line of a standard's text: shaft, history and strength card."""
    h = inputs.history
    return [f"{inputs.variant.name} strength by {label}: {h.source} ({h.n_samples} samples, "
            f"rpm {h.rpm.min():.0f}-{h.rpm.max():.0f}), material {card} "
            f"({'--card' if job.card else 'the shaft material'}, "
            "geometry/common/materials.toml)"]


def tail_lines(summary: dict, out, files, job) -> list[str]:
    """The bearings, keys and gear lines and the files written."""
    from shaftfe.fatigue import strength_outputs as so
    return ["", *so.elements_lines(summary["elements"], job.speed_kmh),
            "\nwrote " + ", ".join(str(out / f) for f in files)]
