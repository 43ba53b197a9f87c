"""The fatigue command's inputs (issue #30 §1-3, nothing solved): the engine's speed limit,
bounds on sample rate and design life, the method-option table and its help, an engine at rest,
capped reading of a history, and lives printed as "no finite life at this load" past 1e9.
The refusals on the command line are in the catalogue (tests/test_bad_input.py, slice a1)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from shaftfe.cli import build_parser
from shaftfe.errors import InputError
from shaftfe.fatigue import history as hist
from shaftfe.fatigue import method_options as mo
from shaftfe.fatigue.run import FatigueJob, check_history, resolve_design_life
from shaftfe.model import bearing_life as bl
from shaftfe.util import fmt, limits


def test_the_speed_limit_is_the_engine_files_max_rpm():
    assert limits.engine_speed_limit("vm450") == (
        9500.0, "max_rpm of VM 450 in geometry/engines/vm450.toml")
    top, where = limits.engine_speed_limit("fe570")          # no max_rpm in that file
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
    limits.check_operating_speed(11_400.0, "vm450", False, "command line", "--rpm",
                                 factor=limits.PROOF_FACTOR)   # 1.2 × 9500, exact
    with pytest.raises(InputError, match=r"11400 rpm = 1\.2 × the max_rpm"):
        limits.check_operating_speed(11_401.0, "vm450", False, "command line", "--rpm",
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
    for option in mo.METHOD_OPTIONS:
        assert f"{option}" in text and "".join(mo.applies_to(option).split()) in text
    assert "".join(mo.help_epilog().split()) in text
    sub = next(a for a in build_parser()._subparsers._group_actions[0].choices.items()
               if a[0] == "fatigue")[1]
    helps = {o: a.help for a in sub._actions for o in a.option_strings}
    for option in mo.METHOD_OPTIONS:                    # each option's own line names them
        assert helps[option].endswith(mo.applies_to(option)), option


def test_an_option_is_refused_only_with_a_method_that_does_not_use_it():
    for option, (_, default, methods) in mo.METHOD_OPTIONS.items():
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
    (3.22e10, 2.68e9, "no finite life at this load (more than 1e9 blocks or hours)"),
    (4.0e8, 1.2e9, "no finite life at this load (more than 1e9 blocks or hours)"),
    (math.inf, math.inf, "no finite life at this load (infinite: no damaging cycle)"),
    (None, None, "no finite life at this load (infinite: no damaging cycle)"),
])
def test_a_life_past_1e9_is_no_finite_life(blocks, hours, text):
    assert fmt.lives(blocks, hours) == text


def test_the_bearing_lines_print_no_finite_life_for_a_huge_l10h():
    from shaftfe.fatigue.standards_out import elements_lines
    duty = {"name": "gear_side", "designation": "ZKL 3303", "P_eq_N": 1.0, "n_eq_rpm": 3000.0,
            "L10h": 5.5e11, "Lnm_h": 1250.0, "Lnm_km": 87_500.0}
    el = {"bearings": {"kappa": 1.0, "e_C": 0.3, "duty_cycle": [duty], "seed_points": []},
          "keys": [], "gear": {"torque_Nmm": 1.0, "F_t_N": 1.0, "F_r_N": 1.0, "F_n_N": 1.0,
                               "v_m_s": 1.0, "safety": 1.0}}
    line = elements_lines(el, 70.0)[1]
    assert "L10h no finite life at this load; L_nm 1 250 h = 87 500 km at 70 km/h" in line
    assert np.isfinite(duty["Lnm_h"])
