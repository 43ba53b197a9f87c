"""The fatigue command's inputs (issue #30 §1-3, nothing solved): the engine's speed limit,
bounds on sample rate and design life, the method-option table and its help, an engine at rest,
capped reading of a history, and lives printed as "no finite life at this load" past 1e9.
The refusals on the command line are in the catalogue (tests/test_bad_input.py, slice a1)."""

from __future__ import annotations

import math

import pytest

from shaftfe.balance import engines
from shaftfe.cli import build_parser
from shaftfe.errors import InputError
from shaftfe.fatigue import history as hist
from shaftfe.fatigue import method_options as mo
from shaftfe.fatigue.run import FatigueJob, check_history, resolve_design_life
from shaftfe.model import bearing_life as bl
from shaftfe.util import fmt, limits


def test_the_speed_limit_is_the_engine_files_max_rpm():
    assert engines.engine_speed_limit("vm450") == (
        9500.0, "max_rpm of VM 450 in geometry/engines/vm450.toml")
    top, where = engines.engine_speed_limit("fe570")          # no max_rpm in that file
    assert top == limits.RPM_CEILING and "RPM_CEILING" in where


def test_a_history_at_the_limit_passes_above_it_is_refused_or_warned():
    at = hist.from_rpm([3000.0, 9500.0, 3000.0], source="at.dat")
    check_history(at, "vm450", False)                           # exactly max_rpm: allowed
    above = hist.from_rpm([3000.0, 9500.5, 3000.0], source="above.dat")
    with pytest.raises(InputError, match=r"above.dat: highest rpm = 9500.5 .*9500 rpm"):
        check_history(above, "vm450", False)
    with pytest.warns(UserWarning, match="9500.5 rpm is above 9500 rpm"):
        check_history(above, "vm450", True)


def test_a_proof_check_may_go_to_1_2_times_max_rpm():
    engines.check_operating_speed(11_400.0, "vm450", False, "command line", "--rpm",
                                 factor=limits.PROOF_FACTOR)   # 1.2 × 9500, exact
    with pytest.raises(InputError, match=r"11400 rpm = 1\.2 × the max_rpm"):
        engines.check_operating_speed(11_401.0, "vm450", False, "command line", "--rpm",
                                     factor=limits.PROOF_FACTOR)


def test_an_engine_at_rest_is_no_load_and_its_bearings_do_not_wear():
    with pytest.raises(InputError, match="no load in this history: no damage, no bearing wear"):
        check_history(hist.from_rpm([0.0, 0.0, 0.0]), "vm450", False)
    # the ISO 281 duty cycle itself (it divided by Σ n = 0): no revolutions, no wear
    assert bl.duty_cycle([0.0, 0.0], [0.0, 0.0]) == (0.0, 0.0)
    assert bl.l10h(14_418.0, 0.0, 0.0) == math.inf
    assert bl.modified_life_spectrum(14_418.0, 500.0, [0.0, 0.0], [0.0, 0.0], 1.0, 0.3) \
        == math.inf


@pytest.mark.parametrize("rate", [1e300, 1e-300, 1.1e5, 9e-4])
def test_sample_rates_outside_the_physical_range_are_refused(rate):
    with pytest.raises(InputError, match="sample_rate_hz"):
        hist.from_rpm([3000.0, 4000.0], sample_rate_hz=rate)


def test_sample_rates_at_the_bounds_pass():
    for rate in hist.SAMPLE_RATE_HZ:
        h = hist.from_rpm([3000.0, 4000.0], sample_rate_hz=rate)
        assert h.duration_s == 2.0 / rate


def test_a_history_is_read_up_to_the_caps_and_refused_beyond(tmp_path, monkeypatch):
    f = tmp_path / "long.dat"
    f.write_text("# format = rpm\n# sample_rate_hz = 1\n" + "3000\n" * 40)   # 42 lines, 236 B
    monkeypatch.setattr(hist, "MAX_LINES", 42)
    assert hist.read_history(f).n_samples == 40
    monkeypatch.setattr(hist, "MAX_LINES", 41)
    with pytest.raises(InputError, match="more than 41 lines"):
        hist.read_history(f)
    monkeypatch.setattr(hist, "MAX_LINES", 10_000_000)
    monkeypatch.setattr(hist, "MAX_BYTES", 235)
    with pytest.raises(InputError, match="larger than"):
        hist.read_history(f)
    b = tmp_path / "nul.dat"
    b.write_bytes(b"3000\n\x004000\n")
    with pytest.raises(InputError, match="binary"):
        hist.read_history(b)


def test_crlf_and_cr_line_ends_read_as_before(tmp_path):
    """The capped reader decodes bytes itself: line ends as Python's text mode reads them."""
    a, b = tmp_path / "crlf.dat", tmp_path / "cr.dat"
    a.write_bytes(b"# format = rpm\r\n# sample_rate_hz = 1\r\n3000\r\n4000\r\n")
    b.write_bytes(b"# format = rpm\r# sample_rate_hz = 1\r3000\r4000\r")
    for f in (a, b):
        assert hist.read_history(f).rpm.tolist() == [3000.0, 4000.0]


def _history(seconds: float):
    return hist.from_rpm([3000.0] * 300, sample_rate_hz=300.0 / seconds)


def test_the_design_life_in_hours_becomes_blocks_of_the_history():
    # the seed's 1e7 blocks of its 300 s block are 833 333.3 h; 1000 h of a 4 s block are
    # 900 000 blocks (3.6e6 / 4 exact in binary)
    assert resolve_design_life(FatigueJob("x", design_life_h=1000.0), _history(4.0)) \
        .design_life == 900_000.0
    assert resolve_design_life(FatigueJob("x"), _history(300.0)).design_life == 1e7
    assert resolve_design_life(FatigueJob("x", design_life=5e6), _history(300.0)) \
        .design_life == 5e6
    with pytest.raises(InputError, match="--design-life-h"):      # 1e6 h of a 1 s block
        resolve_design_life(FatigueJob("x", design_life_h=1e6), _history(1.0))


def test_every_method_option_is_in_the_help_with_its_methods(capsys):
    """The help is generated from the one table: each option's line ends with its methods,
    and the closing paragraph lists each method's options."""
    with pytest.raises(SystemExit):
        build_parser().parse_args(["fatigue", "--help"])
    text = "".join(capsys.readouterr().out.split())    # argparse wraps lines, even at '-'
    for option in mo.OPTIONS:
        assert f"{option}" in text and "".join(mo.applies_to(option).split()) in text
    assert "".join(mo.help_epilog().split()) in text
    sub = next(a for a in build_parser()._subparsers._group_actions[0].choices.items()
               if a[0] == "fatigue")[1]
    helps = {o: a.help for a in sub._actions for o in a.option_strings}
    for option in mo.OPTIONS:                    # each option's own line names them
        assert helps[option].endswith(mo.applies_to(option)), option


def test_an_option_is_refused_only_with_a_method_that_does_not_use_it():
    for option, (_, default, methods) in mo.table().items():
        value = "x" if default is None else default        # given, even at its default
        for m in mo.METHODS:
            if m in methods:
                mo.check_method_options(m, {option: value})
            else:
                with pytest.raises(InputError, match=f"{option} = .* is not used by "
                                   f"--method {m}"):
                    mo.check_method_options(m, {option: value})


@pytest.mark.parametrize("blocks, hours, text", [
    (25_000.0, 2083.0, "25 000 blocks = 2 083 h"),
    (1e9, 1e9, "1 000 000 000 blocks = 1 000 000 000 h"),        # the bound itself: a number
    (3.22e10, 2.68e9, "no finite life at this load (more than 1e9 blocks, hours or km)"),
    (4.0e8, 1.2e9, "no finite life at this load (more than 1e9 blocks, hours or km)"),
    (math.inf, math.inf, "no finite life at this load (infinite: no damaging cycle)"),
    (None, None, "no finite life at this load (infinite: no damaging cycle)"),
])
def test_a_life_past_1e9_is_no_finite_life(blocks, hours, text):
    assert fmt.lives(blocks, hours) == text


def _bearing_line(L10h: float, Lnm_h: float, Lnm_km: float) -> str:
    """The printed line of one bearing with these lives (70 km/h)."""
    from shaftfe.fatigue.strength_outputs import elements_lines
    duty = {"name": "gear_side", "designation": "ZKL 3303", "P_eq_N": 1.0, "n_eq_rpm": 3000.0,
            "L10h": L10h, "Lnm_h": Lnm_h, "Lnm_km": Lnm_km}
    el = {"bearings": {"kappa": 1.0, "e_C": 0.3, "duty_cycle": [duty], "seed_points": []},
          "keys": [], "gear": {"torque_Nmm": 1.0, "F_t_N": 1.0, "F_r_N": 1.0, "F_n_N": 1.0,
                               "v_m_s": 1.0, "safety": 1.0}}
    return elements_lines(el, 70.0)[1]


def test_the_bearing_lines_print_no_finite_life_for_a_huge_l10h():
    line = _bearing_line(5.5e11, 1250.0, 87_500.0)
    assert "L10h no finite life at this load; L_nm 1 250 h = 87 500 km at 70 km/h" in line


# --- slice f2-fatigue-fixes (issue #30 review of `shaftfe fatigue`) ---------------------------

def test_one_design_life_rule_in_blocks_and_in_hours():
    """One rule for --design-life and --design-life-h: one pass of the history up to 1e9 blocks
    and 1e9 h (util.fmt.LIFE_MAX, where a life prints as no finite life). Before, 1e9 blocks
    of a 300 s block (8.3e7 h) passed as blocks while 2e6 h was refused as hours."""
    from shaftfe.fatigue.run import design_life_range
    h300 = _history(300.0)
    # 2e6 h of a 300 s block = 2.4e7 blocks: inside (refused before by a 1e6 h bound);
    # 7.2e9 / 300 is exact in binary
    assert resolve_design_life(FatigueJob("x", design_life_h=2e6), h300).design_life == 2.4e7
    assert resolve_design_life(FatigueJob("x", design_life=1e9), h300).design_life == 1e9
    # the same life typed both ways: 8e7 h = 9.6e8 blocks of 300 s, both inside
    assert resolve_design_life(FatigueJob("x", design_life_h=8e7), h300).design_life == 9.6e8
    with pytest.raises(InputError, match=r"--design-life-h = .* is 1.2e\+09 blocks.*"
                       r"\[1, 1e\+09\] blocks of the 300 s history"):
        resolve_design_life(FatigueJob("x", design_life_h=1e8), h300)
    # a day-long block: 1e9 blocks would be 2.4e10 h, past 1e9 h: the bound is 1e9 h both ways
    day = _history(86_400.0)
    assert design_life_range(86_400.0) == (1.0, 1e9 * 3600.0 / 86_400.0)
    with pytest.raises(InputError, match=r"--design-life = .* is 2.4e\+10 h"):
        resolve_design_life(FatigueJob("x", design_life=1e9), day)
    assert resolve_design_life(FatigueJob("x", design_life_h=1e9), day).design_life == \
        1e9 * 3600.0 / 86_400.0
    # less than one pass of the history, in either form
    with pytest.raises(InputError, match="--design-life-h"):
        resolve_design_life(FatigueJob("x", design_life_h=0.01), h300)


def test_the_sample_rate_error_names_the_option_typed():
    from shaftfe.fatigue.run import check_job
    with pytest.raises(InputError, match=r"^command line: --sample-rate = 1e\+300"):
        check_job(FatigueJob("x", sample_rate=1e300))
    check_job(FatigueJob("x", sample_rate=100.0))


def test_model_applies_to_seed_and_fkm_on_every_model():
    """--model is tagged [seed, fkm]: FKM takes its stress gradient from each field's own
    DepthProbe, so it takes every static model the seed method takes."""
    assert mo.applies_to("--model") == "[seed, fkm]"
    for model in ("solid", "axisymmetric", "zoned"):
        mo.check_method_options("fkm", {"--model": model})
        mo.check_method_options("seed", {"--model": model})


def test_a_narrowed_option_is_refused_with_its_reason(monkeypatch):
    """A method that takes only some values of an option (its ``narrowed``) is tagged so in the
    help, and refuses another value in one line that names the methods taking it."""
    from types import MappingProxyType

    from shaftfe.fatigue.methods import METHODS
    monkeypatch.setattr(METHODS["fkm"], "narrowed", MappingProxyType(
        {"--model": (("solid",), "a reason")}))
    assert mo.applies_to("--model") == "[seed, fkm: solid only]"
    assert "--model (solid only)" in mo.help_epilog().split("din743:")[0]
    mo.check_method_options("fkm", {"--model": "solid"})
    with pytest.raises(InputError, match=r"--model = 'axisymmetric'.*solid with --method fkm"
                       r".*axisymmetric with --method seed"):
        mo.check_method_options("fkm", {"--model": "axisymmetric"})


def test_a_life_in_km_past_1e9_is_no_finite_life_too():
    # 2e7 h at 70 km/h = 1.4e9 km: past the bound in km although the hours are not
    assert fmt.lives(2e5, 2e7, 1.4e9, 70.0) == \
        "no finite life at this load (more than 1e9 blocks, hours or km)"
    assert fmt.lives(25_000.0, 2083.0, 145_810.0, 70.0) == \
        "25 000 blocks = 2 083 h = 145 810 km at 70 km/h"
    assert fmt.life_h_km(1250.0, 87_500.0, 70.0) == "1 250 h = 87 500 km at 70 km/h"
    assert fmt.life_h_km(3.8e8, 2.66e10, 70.0) == fmt.NO_FINITE_LIFE


def test_the_bearing_lines_print_no_finite_life_for_a_huge_lnm_km():
    """One non-zero sample printed 'L_nm … = 26 625 302 415 km'."""
    line = _bearing_line(1.2e5, 3.8e8, 2.66e10)
    assert line.endswith("L10h 120 000 h; L_nm no finite life at this load"), line


def _fkm_stub(n_cycles: int, G: float):
    """An FKM result of one region with one layer (only what the table reads)."""
    from types import SimpleNamespace
    rules = ("elementary", "modified", "consistent")
    c = SimpleNamespace(layer="surface", sigma_ref_MPa=-463.9, G_per_mm=G, n=1.0, K_d=0.921,
                        R_m_MPa=921.0, sigma_W_zd_MPa=369.0, Rz_um=4.0, K_R=0.912, K_V=1.5,
                        K_WK=0.583, sigma_WK_MPa=632.0, M_sigma=0.223, K_AK_largest=math.nan,
                        safety=dict.fromkeys(rules, math.inf),
                        utilisation=dict.fromkeys(rules, 0.0),
                        life_blocks=dict.fromkeys(rules, math.inf))
    r = SimpleNamespace(region="keyway:cw2_seat:0", xyz_mm=(90.81, 0.0, 0.0), surface=c,
                        core=None)
    cyc = SimpleNamespace(n=n_cycles)
    return SimpleNamespace(regions=(r,), rule="modified", cycles=cyc)


def test_the_fkm_table_of_a_constant_speed_has_no_nan_and_says_no_load_cycles():
    from shaftfe.fatigue import strength_outputs as so
    res = _fkm_stub(0, -0.886)
    (row,) = so.fkm_rows(res, frozenset())
    assert "nan" not in " ".join(map(str, row)) and "∞" not in row
    assert row[len(so.FKM_HEAD) - 6:] == [so.NONE] * 6          # K_AK, S ×3, a, life
    assert row[3] == "-463.9" and so.FKM_HEAD[3].startswith("±σ_vM")
    assert row[4] == "-0.886*"                                   # a negative G is marked
    notes = so.fkm_notes(res, frozenset({"keyway:cw2_seat:0"}))
    assert notes[0] == so.FKM_SIGN_NOTE and so.FKM_G_NOTE in notes and "n_σ = 1" in so.FKM_G_NOTE
    assert so.no_load_cycles(res) and "no fatigue damage" in so.NO_LOAD_CYCLES
    # with cycles: the columns are filled, a nan still prints as '—'
    (row,) = so.fkm_rows(_fkm_stub(3, 0.5), frozenset({"keyway:cw2_seat:0"}))
    assert row[15] == so.NONE and row[16] == "∞" and row[4] == "0.500"
    assert so.FKM_G_NOTE not in so.fkm_notes(_fkm_stub(3, 0.5), frozenset())
    # the stub's region is a keyway: sharp-edged, its row marked and the mark explained;
    # with a bottom radius (not in ``sharp``), neither
    assert row[0] == "keyway:cw2_seat:0†" and so.FKM_KEYWAY_NOTE in notes
    (row,) = so.fkm_rows(_fkm_stub(3, 0.5), frozenset())
    assert row[0] == "keyway:cw2_seat:0"
    assert so.FKM_KEYWAY_NOTE not in so.fkm_notes(res, frozenset())


def test_the_seed_method_on_a_given_field_says_it_scales_every_load_with_rpm2(monkeypatch):
    """The report hands the seed method its one static field, which is scaled by (rpm/ref)²
    as a whole: for x2_57_driven (a run-up torque ∝ the angular acceleration) that is said, not
    done silently (``shaftfe fatigue --method seed`` assesses the patterns one by one)."""
    import shaftfe.fatigue.run as fr
    from shaftfe.fatigue.methods import AssessmentInputs, get_method
    from shaftfe.model.loader import load_variant
    from shaftfe.util.notices import collecting
    from shaftfe.util.paths import DEFAULT_SPECTRUM, GEOMETRY_DIR

    class Reached(Exception):
        pass

    def stop(*args, **kwargs):
        raise Reached

    monkeypatch.setattr(fr, "run_fatigue", stop)            # the warning is all this test reads
    driven = load_variant(str(GEOMETRY_DIR / "examples" / "x2_57_driven.toml"))
    history = fr.read_spectrum(str(DEFAULT_SPECTRUM), None, None)
    inputs = AssessmentInputs.one_channel(driven, history, field=object())
    with collecting(echo=False) as box, pytest.raises(Reached):
        get_method("seed").assess(inputs, FatigueJob("x", model="zoned"))
    (n,) = [n for n in box if n.code == "loads-scaled-as-rpm2"]
    assert "mesh_run_up" in n.text and "scaled with rpm²" in n.text
