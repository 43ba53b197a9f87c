"""DIN 743 (``fatigue.din743``, ``fatigue.strength.run_din743``): nominal stresses on the beam
model at every shoulder, keyway and press fit, a fatigue-limit check (S_D) of the history's
largest cycle and a static check (S_F) at its highest speed; no mesh, no design life. The
bearings' ISO 281 life and the seed's key and gear checks beside it."""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import MappingProxyType

from shaftfe.fatigue.methods.fkm import head_line, standard_summary, tail_lines
from shaftfe.fatigue.methods.protocol import AssessmentInputs, FatigueAssessment, Location


@dataclass(frozen=True, eq=False)
class DinDetail:
    run: object                      # fatigue.strength.Din743Run
    beam: object                     # the beam solution it took its moments from
    static: object = None            # fatigue.static_check.StaticCheck on --case, or None


class Din743:
    name = "din743"
    title = "DIN 743, nominal stresses on the beam"
    options = ("--card", "--kappa", "--ec", "--case", "--plot")
    narrowed = MappingProxyType({})
    out_dir = "fatigue-din743"
    files = ("din743_safety.png", "summary.json")       # (+ din743_along.png with --plot)
    optional_files = ("din743_along.png",)
    files_help = ("din743_safety.png (S_D, S_F per notch), din743_along.png (with --plot: "
                  "the safety along the shaft), summary.json")
    stages = ("beam + DIN 743",)

    def check(self, options) -> None:
        from shaftfe.fatigue import strength as sd
        sd.check_options(sd.strength_options(options))
        sd.bearing_options(options)

    def assess(self, inputs: AssessmentInputs, options, progress=None) -> FatigueAssessment:
        from contextlib import nullcontext

        from shaftfe.beam.solve import beam_at_ref
        from shaftfe.fatigue import din743
        from shaftfe.fatigue import strength as sd
        from shaftfe.fatigue.run import FatigueInputs
        from shaftfe.fatigue.static_check import case_of, din743_static
        case = getattr(options, "case", None)
        if case is not None:
            case_of(inputs.variant, case)                # a wrong name before any solve
        from shaftfe.fatigue.channel_run import warn_rpm2_only
        from shaftfe.util.notices import raised
        ch = inputs.single(self.name)
        warn_rpm2_only(inputs.variant, f"--method {self.name}")
        with raised() as warned, (progress.stage(self.stages[0]) if progress is not None
                                  else nullcontext()):
            # one beam solve for DIN 743 and the bearings
            beam = ch.beam if ch.beam is not None else beam_at_ref(inputs.variant)
            run = sd.run_din743(options, sd.strength_options(options),
                                FatigueInputs(ch.history, None, inputs.variant), beam)
            static = (din743_static(inputs.variant, case, sd.strength_options(options))
                      if case is not None else None)

        def loc(w):
            s = min(w.result.S_D, w.result.S_F)
            return Location(w.result.notch.name, w.x_mm,
                            din743.S_MIN / s if s > 0 else math.inf, s,
                            math.nan, math.nan, math.nan, math.nan)   # no life: a limit check
        return FatigueAssessment(self.name, tuple(loc(w) for w in run.rows), loc(run.governing),
                                 tuple(warned), tuple(run.notes), DinDetail(run, beam, static))

    def write(self, result, inputs, options, out) -> tuple[dict, list[str]]:
        from shaftfe.fatigue import strength_outputs as so
        run, beam = result.detail.run, result.detail.beam
        summary = standard_summary(inputs, options, so.din_summary(run), beam)
        st = result.detail.static
        if st is not None:
            summary["static_case"] = {
                "case": st.case, "rpm": st.rpm, "card": st.card, "S_min": st.S_min,
                "governing": st.governing.notch, "S_F": st.governing.S_F,
                "rows": [{"notch": r.notch, "x_mm": r.x_mm, "sigma_zd_MPa": r.sigma_zd_MPa,
                          "sigma_b_MPa": r.sigma_b_MPa, "tau_t_MPa": r.tau_t_MPa,
                          "S_F": r.S_F} for r in st.rows]}
        return so.write_outputs({**summary, "plots": so.write_din_files(summary, out)}, out)

    def lines(self, result, inputs, options, summary, out, files) -> list[str]:
        from shaftfe.fatigue import din743
        from shaftfe.fatigue import strength_outputs as so
        from shaftfe.util.fmt import table_lines
        res = result.detail.run
        p = head_line(inputs, "DIN 743", res.card.name, options)
        p.append(f"cycle: the history's largest, {res.rpm_min:.0f}-{res.rpm_max:.0f} rpm (case "
                 f"2); S_F at {res.rpm_max:.0f} rpm; beam at {res.ref_rpm:g} rpm scaled by rpm²")
        p += table_lines(so.DIN_HEAD, so.din_rows(res), title="DIN 743, nominal stresses, "
                         "bending factors per notch")
        g = res.governing
        p.append(f"governing: {g.result.notch.name} at x = {g.x_mm:g} mm: S_D "
                 f"{so._f(g.result.S_D)}, S_F {so._f(g.result.S_F)} (S_min {din743.S_MIN})")
        if res.along is not None:
            i = int(res.along.S_D.argmin())
            j = int(res.along.S_F.argmin())
            p.append(f"along the shaft (unnotched sections every 0.25 mm, din743_along.png): "
                     f"lowest S_D {so._f(float(res.along.S_D[i]))} at x = "
                     f"{res.along.x_mm[i]:.2f} mm, lowest S_F "
                     f"{so._f(float(res.along.S_F[j]))} at x = {res.along.x_mm[j]:.2f} mm")
        p += [f"note: {note}" for note in res.notes]
        st = result.detail.static
        if st is not None:
            p += table_lines(["notch", "x mm", "σ_zd MPa", "σ_b MPa", "τ_t MPa", "S_F"],
                             [[r.notch, f"{r.x_mm:g}", f"{r.sigma_zd_MPa:.2f}",
                               f"{r.sigma_b_MPa:.1f}", f"{r.tau_t_MPa:.2f}", so._f(r.S_F)]
                              for r in st.rows],
                             title=f"DIN 743 static check on load case {st.case!r} "
                                   f"({st.rpm:g} rpm, every load with its factor; beam)")
            g = st.governing
            p.append(f"static: {g.notch}: S_F {so._f(g.S_F)} "
                     f"({'≥' if st.ok else 'BELOW'} S_min {st.S_min})")
        return p + tail_lines(summary, out, files, options)


METHOD = Din743()
