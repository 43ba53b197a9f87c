"""Every input of a study checked before the first design runs (``shaftfe study run``).

Two kinds of rule, two outcomes (docs/STUDIES.md, "What is checked before anything runs"):

* **Input rules refuse the whole study** (InputError: one line naming the study file, the
  parameter and its value as the file gives it; exit 2; nothing written). They are the rules
  ``shaftfe variant check`` applies to one key or to a file that cannot be read:

  - the files every design reads: the rpm history (``analyses.fatigue.spectrum``, read and
    checked as ``shaftfe fatigue`` reads it), the S-N card, the engine; the engine speed and
    the bearings' speed at most the engine's ``max_rpm``;
  - every parameter path and value (``spec.check_designs``: the key exists, its kind, the
    key's own range);
  - a part's mass or eccentricity set directly more than ``UNIT_SLIP`` times away from the
    base variant's value (``variant check`` refuses such a value through the [balance]
    statement, which a study re-derives and so cannot use; a unit slip is ×10 or ×1000:
    mm↔cm, mm↔m, kg↔g);
  - a value derived from a parameter (a counterweight's mass from its shape) outside the
    plausible range of its key (``model.fields.plausible``): the message names the parameter
    that gave it.

* **Design rules refuse one design** (a combination of values the loader will not build: a
  fillet larger than the bearing corner at its shoulder, a hub wider than its crescent). The
  design is listed before anything is solved (``Checked.refused``; the command prints them),
  recorded as a row with status ``refused`` and the reason, and the study goes on.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from shaftfe.balance.engines import check_operating_speed
from shaftfe.errors import InputError
from shaftfe.fatigue.run import check_history
from shaftfe.model.fields import ImplausibleValue
from shaftfe.model.parse import resolve_path, resolved_dict
from shaftfe.study.evaluate import _engine, _fatigue_inputs, group_of, load_design
from shaftfe.study.spec import StudySpec, check_designs, parameter_of, refusal

# A part's mass or eccentricity set directly may move by at most this factor from the base
# variant's value: the smallest unit slip (mm typed as cm, ×10) is outside, a real redesign of
# the same part inside (the showcase's counterweights, derived from their shapes: 0.57…1.18×
# in mass, 0.76…1.07× in eccentricity; tests/test_study.py checks it).
UNIT_SLIP = 5.0
_PART_KEYS = ("mass_kg", "eccentricity_mm")


@dataclass(frozen=True)
class Checked:
    """What the check found: refused designs (number → reason) and, for a 3D study, each
    loadable design's mesh group (number → (mesh key, E, ν)), so nothing is loaded twice."""
    refused: dict = field(default_factory=dict)
    groups: dict = field(default_factory=dict)
    rules: dict = field(default_factory=dict)      # number → the rule (reason without values)

    def summary(self, limit: int = 12) -> list[str]:
        """One line per rule: ``<n> designs refused (3, 4, …): <rule>``."""
        by: dict[str, list[int]] = {}
        for n in sorted(self.refused):
            by.setdefault(self.rules.get(n, self.refused[n]), []).append(n)
        out = []
        for why, ns in by.items():
            shown = ", ".join(map(str, ns[:limit])) + (", …" if len(ns) > limit else "")
            out.append(f"{len(ns)} design{'s' if len(ns) > 1 else ''} refused ({shown}): {why}")
        return out


def _unit_slip(spec: StudySpec, designs) -> None:
    base = {a.get("name"): a for a in resolved_dict(resolve_path(spec.base)).get("attachments", [])}
    for d in designs:
        for path, value in d.overrides:
            parts = path.split(".")
            if not (len(parts) == 3 and parts[0] == "attachments" and parts[2] in _PART_KEYS
                    and isinstance(value, int | float)):
                continue
            b = base.get(parts[1], {}).get(parts[2])
            if not isinstance(b, int | float) or b <= 0:
                continue
            if not (b / UNIT_SLIP <= value <= b * UNIT_SLIP):
                unit = "kg" if parts[2] == "mass_kg" else "mm"
                raise InputError(spec.path, parameter_of(spec, path), (
                    f"within {UNIT_SLIP:g}× of the base variant's {b:g} {unit} "
                    f"([{b / UNIT_SLIP:.4g}, {b * UNIT_SLIP:.4g}] {unit}; a unit slip is ×10 or "
                    "×1000; a different part: change its shape or the base file)"), got=value)


def _files(spec: StudySpec) -> None:
    """The files every design reads, read once here (their own one-line errors), and the
    speeds against the engine's own limit by the rule of ``shaftfe fatigue``
    (``balance.engines.check_operating_speed``, ``fatigue.run.check_history``; a study has no
    --allow-overspeed)."""
    an = spec.analyses
    _engine(an.engine)
    hint = " (a study assesses operating speeds only: it has no --allow-overspeed)"
    for fld, rpm in (("analyses.balance.rpm", an.engine_rpm),
                     ("analyses.bearings.rpm", an.bearing_rpm)):
        if rpm is not None:
            check_operating_speed(rpm, an.engine, False, spec.path, fld, hint=hint)
    if an.fatigue:
        history, _ = _fatigue_inputs(an.spectrum, an.material)
        check_history(history, an.engine, False, hint)


def check_study(spec: StudySpec, designs) -> Checked:
    """Check every input of the study (see the module docstring); InputError if the study is
    refused, else the designs the loader refuses and the 3D designs' mesh groups."""
    check_designs(spec, designs)
    _unit_slip(spec, designs)
    _files(spec)
    refused, groups, rules = {}, {}, {}
    seen: dict = {}
    for d in designs:
        key = repr(d.overrides)
        if key in seen:                      # equal designs (a grid with repeated points)
            n0 = seen[key]
            if n0 in refused:
                refused[d.number], rules[d.number] = refused[n0], rules[n0]
            elif n0 in groups:
                groups[d.number] = groups[n0]
            continue
        seen[key] = d.number
        try:
            v, _ = load_design(spec.base, d.overrides,
                               spec.analyses.static and spec.analyses.fatigue)
        except ImplausibleValue as exc:      # an input rule: the whole study is refused
            head, allowed = refusal(spec, d.overrides, exc)[0].split(" is refused; allowed: ",
                                                                  1)
            raise InputError(spec.path, f"design {d.number}: {head}", allowed,
                             reason="is outside its key's plausible range (the study is "
                             "refused)") from None
        except InputError as exc:            # a design rule: this design only
            refused[d.number], rules[d.number] = refusal(spec, d.overrides, exc)
            continue
        if spec.analyses.static:
            groups[d.number] = group_of(v, spec.analyses.level)
    if refused and len(refused) == len(designs):
        # nothing to evaluate: a study whose every design is refused is the input's fault
        first = min(refused)
        raise InputError(spec.path, "parameters", "at least one design the loader accepts",
                         reason=f"give no design to evaluate (all {len(designs)} refused; "
                         f"design {first}: {refused[first]})")
    return Checked(refused, groups, rules)
