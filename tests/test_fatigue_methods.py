"""The fatigue methods behind one protocol and one registry (issue #31 §5, first bullet).

* every registered method answers ``fatigue.methods.protocol.FatigueMethod``;
* a fourth method registered by a test (one class, one registry entry) is taken by
  ``shaftfe fatigue --method`` by name, its options are refused or accepted by the registry's
  table, and it runs through the command's one path (files, summary, text);
* through the protocol the three methods give EXACTLY what the functions they wrap give on the
  same inputs (the same arithmetic on the same floats: equality, no tolerance): the seed method
  (``fatigue.run.run_fatigue`` / ``fatigue.field.evaluate``), FKM (``strength.run_fkm``,
  ``fkm_field.assess_field``), DIN 743 (``strength.run_din743``); the report's seed stage goes
  through the registry.

One coarse static solution of x2_57 (this module's cache), no other solve.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from types import MappingProxyType

import numpy as np
import pytest

from shaftfe.cli import main
from shaftfe.errors import InputError
from shaftfe.fatigue import method_options as mo
from shaftfe.fatigue.methods import (
    METHODS,
    AssessmentInputs,
    FatigueAssessment,
    LoadChannel,
    Location,
    get_method,
)
from shaftfe.fatigue.methods.protocol import FatigueMethod

RPM_DAT = Path(__file__).resolve().parents[1] / "loadspectra" / "rpm.dat"
MEMBERS = ("check", "assess", "write", "lines")


def test_every_registered_method_answers_the_protocol():
    attrs = {k for k in FatigueMethod.__annotations__}
    assert attrs == {"name", "title", "options", "narrowed", "out_dir", "files",
                     "optional_files", "files_help", "stages"}
    assert list(METHODS) == ["seed", "fkm", "din743"]
    outs = set()
    for name, m in METHODS.items():
        assert get_method(name) is m and m.name == name
        assert all(hasattr(m, a) for a in attrs) and all(callable(getattr(m, f))
                                                          for f in MEMBERS)
        assert set(m.options) <= set(mo.OPTIONS), name           # rows of the one table
        assert set(m.narrowed) <= set(m.options), name
        assert "summary.json" in m.files and all(f in m.files_help for f in m.files)
        assert all(f in m.files_help and f not in m.files for f in m.optional_files), name
        outs.add(m.out_dir)
    assert len(outs) == len(METHODS)                   # no two methods write one folder


def test_an_unknown_name_is_refused_naming_the_registered_ones():
    with pytest.raises(InputError, match=r"--method = 'x'.*seed \| fkm \| din743"):
        get_method("x")


def test_several_channels_are_refused_until_a_method_combines_them():
    two = AssessmentInputs(None, (LoadChannel("rpm2", None), LoadChannel("torque", None)))
    for m in METHODS.values():
        with pytest.raises(InputError, match="channels"):
            m.assess(two, None)


class Toy:
    """A fourth method in one class: the history's largest load factor × --kf."""
    name = "toy"
    title = "the largest load factor (a test's method)"
    options = ("--kf",)
    narrowed = MappingProxyType({})
    out_dir = "fatigue-toy"
    files = ("summary.json",)
    optional_files = ()
    files_help = "summary.json"
    stages = ("toy",)

    def check(self, options) -> None:
        pass

    def assess(self, inputs, options, progress=None) -> FatigueAssessment:
        u = float(inputs.single(self.name).history.load_factor.max()) * options.kf
        loc = Location("shaft", 0.0, u, 1.0 / u, math.nan, math.nan, math.nan, math.nan)
        return FatigueAssessment(self.name, (loc,), loc, (), (), u)

    def write(self, result, inputs, options, out):
        summary = {"method": self.name, "utilisation": result.governing.utilisation}
        (out / "summary.json").write_text(json.dumps(summary))
        return summary, ["summary.json"]

    def lines(self, result, inputs, options, summary, out, files):
        return [f"toy utilisation {result.governing.utilisation!r}"]


def test_a_new_method_is_one_module_and_one_registry_line(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(METHODS, "toy", Toy())
    with pytest.raises(SystemExit):
        main(["fatigue", "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    assert "toy (the largest load factor" in help_text and "toy: --kf" in help_text
    assert mo.applies_to("--kf") == "[seed, toy]"
    out = tmp_path / "toy"
    assert main(["fatigue", str(RPM_DAT), "--method", "toy", "--kf", "0.5",
                 "--out", str(out)]) == 0
    text = capsys.readouterr().out
    from shaftfe.fatigue.run import read_spectrum
    # the same float the toy computed from the same file: exact
    expect = float(read_spectrum(str(RPM_DAT), None, None).load_factor.max()) * 0.5
    assert json.loads((out / "summary.json").read_text())["utilisation"] == expect
    assert f"toy utilisation {expect!r}" in text
    assert sorted(p.name for p in out.iterdir()) == ["summary.json"]
    # an option the toy does not name is refused by the same rule as the others'
    rc = main(["fatigue", str(RPM_DAT), "--method", "toy", "--level", "coarse",
               "--out", str(tmp_path / "no")])
    assert rc == 2 and "is not used by --method toy" in capsys.readouterr().err
    assert not (tmp_path / "no").exists()


# --------------------------------------------------------------------------- exact equality

@pytest.fixture(scope="module")
def coarse(cache):
    """x2_57's inputs, the coarse static reference (this module's cache) and the job."""
    from shaftfe.fatigue.run import FatigueJob, load_inputs, static_reference
    job = FatigueJob(str(RPM_DAT), level="coarse", cache_dir=str(cache), model="solid")
    got = load_inputs(job)
    return job, got, static_reference(got.variant, job)


def _same_hot_spot(loc, h):
    assert (loc.name, loc.x_mm, loc.safety, loc.damage_per_block, loc.life_blocks,
            loc.life_hours, loc.life_km) == (h.region, h.xyz_mm[0], h.safety_factor,
                                             h.damage_per_block, h.life_blocks, h.life_hours,
                                             h.life_km)


def test_the_seed_method_is_run_fatigue_exactly(coarse):
    from shaftfe.fatigue.field import evaluate
    from shaftfe.fatigue.run import run_fatigue
    job, got, ref = coarse
    old = run_fatigue(job, got)
    new = get_method("seed").assess(AssessmentInputs.one_channel(got.variant, got.history), job)
    direct = evaluate(ref, got.history, got.material, equivalent=job.equivalent,
                      theory=job.mean_stress, kf=job.kf, design_life_blocks=1e7,
                      speed_kmh=job.speed_kmh)
    given = get_method("seed").assess(AssessmentInputs.one_channel(
        got.variant, got.history, field=ref), job)
    for run in (new.detail, given.detail):
        for k in ("safety_factor", "life_blocks", "damage_per_block"):
            a = getattr(old.field.result, k)
            assert np.array_equal(getattr(run.field.result, k), a)
            assert np.array_equal(getattr(direct.result, k), a)
        assert run.field.hot_spot == old.field.hot_spot
    assert new.detail.level_error == old.level_error and given.detail.level_error is None
    _same_hot_spot(new.governing, old.field.hot_spot)
    regions = [h for h in old.field.region_hot_spots if h is not None]
    assert len(new.locations) == len(regions)
    for loc, h in zip(new.locations, regions, strict=True):
        _same_hot_spot(loc, h)


def test_fkm_through_the_protocol_is_run_fkm_exactly(coarse):
    from shaftfe.fatigue import strength as sd
    from shaftfe.fatigue import strength_outputs as so
    from shaftfe.fatigue.assess import life_hours
    job, got, ref = coarse
    old, _, _ = sd.run_fkm(job, sd.StrengthOptions(), got, ref)
    new = get_method("fkm").assess(AssessmentInputs.one_channel(got.variant, got.history), job)
    given = get_method("fkm").assess(AssessmentInputs.one_channel(
        got.variant, got.history, field=ref), job)
    want = so.fkm_summary(old)
    assert so.fkm_summary(new.detail.result) == want == so.fkm_summary(given.detail.result)
    assert new.detail.result.assessed == old.assessed
    r, c = old.governing
    g = new.governing
    assert (g.name, g.utilisation, g.safety, g.life_blocks) == \
        (r.region, c.utilisation["modified"], c.safety["modified"], c.life_blocks["modified"])
    assert g.life_hours == float(life_hours(g.life_blocks, old.block_seconds))
    assert max(loc.utilisation for loc in new.locations) == g.utilisation


def test_din743_through_the_protocol_is_run_din743_exactly(coarse):
    from shaftfe.beam.solve import beam_at_ref
    from shaftfe.fatigue import din743
    from shaftfe.fatigue import strength as sd
    from shaftfe.fatigue import strength_outputs as so
    job, got, _ = coarse
    beam = beam_at_ref(got.variant)
    old = sd.run_din743(job, sd.StrengthOptions(), got, beam)
    new = get_method("din743").assess(AssessmentInputs.one_channel(
        got.variant, got.history, beam=beam), job)
    alone = get_method("din743").assess(AssessmentInputs.one_channel(got.variant, got.history),
                                        job)
    assert so.din_summary(new.detail.run) == so.din_summary(old) == \
        so.din_summary(alone.detail.run)
    g = old.governing
    s = min(g.result.S_D, g.result.S_F)
    assert (new.governing.name, new.governing.safety, new.governing.utilisation) == \
        (g.result.notch.name, s, din743.S_MIN / s)
    assert math.isnan(new.governing.life_blocks)           # a limit check: no life


def test_the_report_takes_the_seed_method_from_the_registry(coarse, monkeypatch):
    from shaftfe.fatigue.field import evaluate
    from shaftfe.report.options import ReportOptions
    from shaftfe.report.stages import fatigue
    _, got, ref = coarse
    calls = []
    seed = METHODS["seed"]

    class Spy:
        def __getattr__(self, k):
            return getattr(seed, k)

        def assess(self, *a, **kw):
            calls.append(a)
            return seed.assess(*a, **kw)
    monkeypatch.setitem(METHODS, "seed", Spy())
    o = ReportOptions(level="coarse", material="structural_steel", design_life_blocks=1e7)
    _, ff = fatigue(ref, got.history, got.material, o, got.variant)
    assert len(calls) == 1
    old = evaluate(ref, got.history, got.material, equivalent="von_mises",
                   theory=o.mean_stress, kf=1.0, design_life_blocks=o.design_life_blocks,
                   speed_kmh=o.speed_kmh)
    assert np.array_equal(ff.result.safety_factor, old.result.safety_factor)
    assert ff.hot_spot == old.hot_spot


@pytest.mark.parametrize("method", list(METHODS))
def test_a_study_takes_its_method_by_name(coarse, method, monkeypatch):
    """A study's fatigue row is the governing place of the method it names (the design's
    static field stands in by this module's coarse reference: no second solve)."""
    from shaftfe.static import cache as static_cache
    from shaftfe.study import evaluate
    from shaftfe.study.spec import Analyses
    job, got, ref = coarse
    monkeypatch.setattr(static_cache, "from_result", lambda res: ref)
    an = Analyses(static=True, fatigue=True, fatigue_method=method, spectrum=str(RPM_DAT))
    row = evaluate.fatigue_row(None, an, got.variant)
    g = get_method(method).assess(AssessmentInputs.one_channel(got.variant, got.history,
                                                               field=ref), job).governing
    assert row["fatigue_hot_spot"] == g.name and row["fatigue_sf"] == g.safety
    assert row["life_h"] == (None if math.isnan(g.life_hours) else g.life_hours)
    assert ("fatigue_method" in an.options()) == (method != "seed")   # seed studies' keys kept


def test_an_assessment_keeps_the_warnings_raised_while_it_ran():
    """``util.notices.raised``: in a collection (a command) the block's new warnings, still
    collected once; outside one (the API) the block's warnings, passed on as ShaftfeWarning."""
    from shaftfe.util.notices import ShaftfeWarning, collected, collecting, raised, warn
    with collecting(echo=False):
        warn("before", "x", "raised before the block")
        with raised() as got:
            warn("before", "x", "raised before the block")     # not new: not the block's
            warn("inside", "y", "raised in the block")
        assert [w["code"] for w in got] == ["inside"]
        assert [w["code"] for w in collected()] == ["before", "inside"]
    with pytest.warns(ShaftfeWarning, match="y: outside a collection"), raised() as got:
        warn("api", "y", "outside a collection")
    assert [w["code"] for w in got] == ["api"]
