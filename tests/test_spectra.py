"""rpm-history readers (shaftfe.fatigue.history) and the rebuilt seed block loadspectra/rpm.dat."""

from __future__ import annotations

import dataclasses
import importlib.util
import re
from pathlib import Path

import numpy as np
import pytest

from shaftfe.errors import InputError
from shaftfe.fatigue.history import RPM_CEILING, LoadHistory, from_rpm, read_history

ROOT = Path(__file__).resolve().parents[1]
RPM_DAT = ROOT / "loadspectra" / "rpm.dat"


def _write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


# --- the seed block --------------------------------------------------------------------------

def test_rpm_dat_has_the_seed_described_pieces():
    """Seed 000 appendix 5: 300 samples at 1 Hz stored as rpm²/7000²; first 50 s at 3100 rpm,
    overtaking up to 7500 rpm, 10 s at 3100, 50 s at 4600; bounds idle 1200 / max 9500 rpm."""
    h = read_history(RPM_DAT)
    assert (h.format, h.rpm_ref, h.n_samples, h.duration_s) == ("normalised", 7000.0, 300, 300.0)
    rpm = np.round(h.rpm, 6)
    assert np.all(rpm[:50] == 3100) and rpm[50] != 3100
    assert rpm[50:85].max() == 7500
    assert np.all(rpm[85:95] == 3100)
    assert np.all(rpm[96:146] == 4600)
    assert rpm.min() >= 1200 and rpm.max() <= 9500
    # exact arithmetic: rpm = 7000 √lf and back, ≤ 4 correctly rounded IEEE operations
    assert h.load_factor == pytest.approx((h.rpm / 7000.0) ** 2, rel=1e-15)


def test_rpm_dat_is_what_the_generator_writes():
    """Deterministic: loadspectra/make_rpm.py renders exactly the committed file."""
    spec = importlib.util.spec_from_file_location("make_rpm", ROOT / "loadspectra" / "make_rpm.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    assert mod.render() == RPM_DAT.read_text(encoding="utf-8")


# --- good files ------------------------------------------------------------------------------

def test_seed_format_without_header_needs_reference(tmp_path):
    p = _write(tmp_path, "plain.dat", "0.25\n1\n0.25\n")
    with pytest.raises(InputError, match="reference_rpm"):
        read_history(p)
    h = read_history(p, rpm_ref=7000.0)
    assert h.rpm == pytest.approx([3500.0, 7000.0, 3500.0], rel=1e-15)   # exact: √0.25 = 0.5
    assert h.duration_s == 3.0 and h.time_s.tolist() == [0.0, 1.0, 2.0]


def test_header_and_option_must_agree(tmp_path):
    p = _write(tmp_path, "h.dat", "# reference_rpm = 7000\n0.5\n")
    assert read_history(p, rpm_ref=7000.0).rpm_ref == 7000.0
    with pytest.raises(InputError, match=r"line 1: reference_rpm.*contradicts"):
        read_history(p, rpm_ref=6000.0)


def test_rpm_per_line_with_sample_rate(tmp_path):
    p = _write(tmp_path, "r.txt", "# logged at 2 Hz\n3000\n\n6000\n")
    with pytest.raises(InputError, match="sample_rate_hz"):
        read_history(p)
    h = read_history(p, sample_rate_hz=2.0, rpm_ref=6000.0)
    assert h.format == "rpm" and h.duration_s == 1.0
    assert h.time_s.tolist() == [0.0, 0.5]
    assert h.load_factor.tolist() == [0.25, 1.0]
    q = _write(tmp_path, "r2.txt", "# sample_rate_hz = 4\n3000\n6000\n")
    assert read_history(q).duration_s == 0.5


def test_csv_irregular(tmp_path):
    """Irregular logger times are kept; duration = span + the last interval (1.7 + 0.5)."""
    p = _write(tmp_path, "log.csv", "# ECU export\ntime_s,rpm\n0.0,1200\n0.3,2500\n1.2,4000\n"
               "1.7,3900\n")
    h = read_history(p)
    assert h.format == "csv" and h.time_s.tolist() == [0.0, 0.3, 1.2, 1.7]
    # exact arithmetic (one or two correctly rounded operations each)
    assert h.duration_s == pytest.approx(2.2, rel=1e-15)
    assert h.load_factor[2] == pytest.approx((4000 / 7000) ** 2, rel=1e-15)


def test_regular_csv_equals_rpm_format(tmp_path):
    """A 1 Hz CSV and the same speeds one per line give the same times, load and duration."""
    rpm = [3100, 5000, 7500, 3100]
    a = read_history(_write(tmp_path, "a.csv", "time_s,rpm\n" + "".join(
        f"{i},{r}\n" for i, r in enumerate(rpm))))
    b = read_history(_write(tmp_path, "b.txt", "".join(f"{r}\n" for r in rpm)),
                     sample_rate_hz=1.0)
    assert a.duration_s == b.duration_s == 4.0
    assert np.array_equal(a.load_factor, b.load_factor)


def test_with_reference_rescales_the_load_factor():
    """rpm.dat is normalised to 7000 rpm; against a static case at 10 000 rpm the load factor
    is (rpm/10 000)² = value · 0.49 (hand: (7000/10 000)²), the speeds unchanged."""
    h = read_history(RPM_DAT)
    g = h.with_reference(10_000.0)
    assert g.rpm_ref == 10_000.0 and np.array_equal(g.rpm, h.rpm)
    # exact arithmetic: 0.49 = (7000/10 000)² is itself rounded, plus ≤ 4 roundings
    assert g.load_factor == pytest.approx(0.49 * h.load_factor, rel=1e-14)
    with pytest.raises(InputError, match="rpm_ref"):
        h.with_reference(0.0)


def test_history_is_frozen_and_read_only():
    h = from_rpm([1000.0, 2000.0])
    with pytest.raises(dataclasses.FrozenInstanceError):
        h.rpm_ref = 1.0
    with pytest.raises(ValueError):
        h.rpm[0] = 5.0
    assert isinstance(h.repeated(3), LoadHistory) and h.repeated(3).duration_s == 6.0
    assert h.repeated(2).time_s.tolist() == [0.0, 1.0, 2.0, 3.0]


# --- bad files: one line naming the file and the line -------------------------------------------

BAD = [
    ("empty.dat", "", {"rpm_ref": 7000.0}, r"empty\.dat: data .*is empty"),
    ("comments.dat", "# only comments\n\n", {"rpm_ref": 7000.0}, r"comments\.dat: data"),
    ("nan.dat", "# format = normalised\n0.5\nnan\n", {"rpm_ref": 7000.0},
     r"nan\.dat: line 3: load factor = 'nan'"),
    ("neg.dat", "# format = normalised\n0.5\n-0.1\n", {"rpm_ref": 7000.0},
     r"neg\.dat: line 3: load factor = -0\.1"),
    ("text.dat", "0.5\nabc\n", {"rpm_ref": 7000.0}, r"text\.dat: line 2 = 'abc'"),
    ("big.dat", "# format = normalised\n0.5\n9.0\n", {"rpm_ref": 7000.0},
     r"big\.dat: line 3: load factor = 9\.0 .*allowed: a finite number in \[0, 8\.16"),
    ("negrpm.txt", "# format = rpm\n3000\n-5\n", {"sample_rate_hz": 1.0},
     r"negrpm\.txt: line 3: rpm = -5\.0"),
    ("fast.txt", "3000\n25000\n", {"sample_rate_hz": 1.0},
     r"fast\.txt: line 2: rpm = 25000\.0 .*\[0, 20000\] rpm"),
    ("inf.txt", "# format = rpm\n3000\ninf\n", {"sample_rate_hz": 1.0},
     r"inf\.txt: line 3: rpm = 'inf'"),
    ("time.csv", "time_s,rpm\n0,1000\n1,2000\n1,3000\n", {},
     r"time\.csv: line 4: time_s = 1\.0 .*allowed: > 1 \(strictly increasing\)"),
    ("back.csv", "time_s,rpm\n0,1000\n2,2000\n1.5,3000\n", {},
     r"back\.csv: line 4: time_s = 1\.5"),
    ("head.csv", "t,n\n0,1000\n1,2000\n", {}, r"head\.csv: line 1: header = 't,n'"),
    ("short.csv", "time_s,rpm\n0,1000\n", {}, r"short\.csv: data = 1 has too few rows"),
    ("cols.csv", "time_s,rpm\n0,1000\n1,2000,3\n", {}, r"cols\.csv: line 3 = '1,2000,3'"),
    ("nanrpm.csv", "time_s,rpm\n0,1000\n1,NaN\n", {}, r"nanrpm\.csv: line 3: rpm = 'NaN'"),
    ("ceil.csv", "time_s,rpm\n0,1000\n1,20001\n", {}, r"ceil\.csv: line 3: rpm = 20001\.0"),
    ("emptycsv.csv", "", {}, r"emptycsv\.csv: data .*is empty"),
    ("fmt.dat", "# format = rpmx\n3000\n", {}, r"fmt\.dat: line 1: format = 'rpmx'"),
    ("rate.txt", "# sample_rate_hz = 0\n3000\n", {}, r"rate\.txt: line 1: sample_rate_hz = 0\.0"),
]


@pytest.mark.parametrize("name,text,kw,pattern", BAD, ids=[b[0] for b in BAD])
def test_bad_input_is_one_line_naming_file_and_line(tmp_path, name, text, kw, pattern):
    p = _write(tmp_path, name, text)
    with pytest.raises(InputError) as exc:
        read_history(p, **kw)
    msg = str(exc.value)
    assert "\n" not in msg and str(p) in msg
    assert "allowed:" in msg
    assert re.search(pattern, msg), msg


def test_missing_file_and_bad_options(tmp_path):
    with pytest.raises(InputError, match="does not exist"):
        read_history(tmp_path / "nope.dat")
    p = _write(tmp_path, "ok.dat", "0.5\n")
    with pytest.raises(InputError, match=r"command line: rpm_ref = -1"):
        read_history(p, rpm_ref=-1.0)
    with pytest.raises(InputError, match="format"):
        read_history(p, fmt="xls")
    with pytest.raises(InputError, match=f"in \\[0, {RPM_CEILING:g}\\]"):
        from_rpm([1000.0, -1.0])
