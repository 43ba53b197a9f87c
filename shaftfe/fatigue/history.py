"""Engine-speed histories for the fatigue study → a validated, frozen ``LoadHistory``.

The balancer shaft is loaded by centrifugal forces F = m e ω², so every load is proportional to
rpm². The static FE solution is computed once at a reference speed ``rpm_ref`` (seed 000 §8.3:
7000 rpm) and the time history enters only through the load factor

    load_factor(t) = (rpm(t) / rpm_ref)²

Three file formats are read (SPEC §3):

``normalised`` (the seed's ``rpm.dat``, seed 000 appendix 5)
    one value ``rpm² / rpm_ref²`` per line, equally spaced in time. ``rpm_ref`` comes from a
    header comment ``# reference_rpm = 7000`` or the ``rpm_ref`` argument (if both are given they
    must agree); the sample rate from ``# sample_rate_hz = 1`` or the argument, default 1 Hz (the
    seed's: 300 samples = 5 min).
``rpm``
    one engine speed in rpm per line, equally spaced; the sample rate is required (header
    ``# sample_rate_hz = ...`` or argument).
``csv``
    a data-logger export with the header ``time_s,rpm`` and one ``time, rpm`` row per sample,
    any (even irregular) but strictly increasing times. Further columns are **load channels**
    (issue #31): ``time_s,rpm,torque_Nm`` — each column named by a channel that the variant's
    ``[[loads]]`` scale with (``scales_with = "torque_Nm"``), its unit in the name after the
    first underscore (``CHANNEL_RE``); any finite value (a torque may reverse). The channels
    are ``LoadHistory.channels``; the rpm² loads still follow the ``rpm`` column. The channel
    ``alpha_rad_s2`` (the angular acceleration) is derived from the rpm column when it is not
    logged (``angular_acceleration``).

Lines starting with ``#`` are comments; ``# key = value`` comments before the first data line
are header keys (``format``, ``reference_rpm``, ``sample_rate_hz``); blank lines are skipped.
Automatic format choice: ``.csv`` → csv; otherwise the header's ``format`` key; otherwise
``normalised`` if every value is ≤ 50 (50 rpm is far below any idle speed, and a normalised value
of 50 would mean 7 × rpm_ref), else ``rpm``.

Time and duration. Equally spaced formats: ``time_s[i] = i / f`` and ``duration_s = n / f`` (each
sample holds for one interval: 300 samples at 1 Hz = the seed's 300 s block). CSV: the times as
given, and ``duration_s = t_last − t_first + (t_last − t_prev)`` (the last sample holds for one
more interval, so a regular 1 Hz log gives the same block length as the rpm format). The block
length converts a life in blocks into hours.

Bad input (empty file, non-numeric value, NaN/inf, negative rpm or load factor, speed above
``RPM_CEILING``, non-increasing time, missing header) raises ``InputError`` naming the file, the
line and the allowed range; the CLI prints it as one line and exits with code 2.

Bounds on what a history may be (each refused with one line naming the file):

``MAX_BYTES`` (256 MB) and ``MAX_LINES`` (10 000 000 lines)
    what is read of a file. The longest real log the project has met is the 5-million-sample
    benchmark (100 Hz for 13.9 h, about 40 MB as text); a whole day of riding logged at 100 Hz
    is 8.6 million samples. Reading stops at the cap, so ``/dev/zero`` or ``/dev/urandom``
    (endless streams) are refused at once instead of filling the memory; a NUL byte in the
    first MiB marks a binary file and is refused before more is read.
``SAMPLE_RATE_HZ`` ([1e-3, 1e5] Hz), also the interval of a csv log ([1e-5, 1e3] s)
    a sample every 1000 s (17 min) is already too coarse to follow any change of speed on a
    ride; 100 kHz is ten times the fastest engine-speed loggers (10 kHz), and the speed itself
    cannot change faster than one ignition (79 Hz at 9500 rpm for a four-stroke single). The
    block length n / rate turns a life in blocks into hours, so 1e300 Hz would print a life of
    1e-292 h and 1e-300 Hz an infinite one.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from shaftfe.errors import InputError
from shaftfe.util.limits import RPM_CEILING
from shaftfe.util.units import omega, rpm2_scale

DEFAULT_RPM_REF = 7000.0        # reference speed of the seed's static load case (seed 000 §8.3)
SEED_SAMPLE_RATE_HZ = 1.0       # seed 000 appendix 5: one sample per second
FORMATS = ("normalised", "rpm", "csv")
_AUTO_NORMALISED_MAX = 50.0
MAX_BYTES = 256 * 2 ** 20      # see the module docstring: ~6× the 5-million-sample log
MAX_LINES = 10_000_000         # a day at 100 Hz is 8.6 million samples
SAMPLE_RATE_HZ = (1e-3, 1e5)   # see the module docstring; a csv's intervals: 1/hi .. 1/lo s
_BINARY_PROBE = 2 ** 20        # a NUL byte in the first MiB: a binary file
ALPHA_CHANNEL = "alpha_rad_s2"        # derived from the rpm column when not logged
CHANNEL_RE = re.compile(r"[A-Za-z][A-Za-z0-9]*_[A-Za-z0-9_]+")   # name_unit, e.g. torque_Nm
MAX_CHANNELS = 16
_HEADER_RE = re.compile(r"^#\s*([A-Za-z_][A-Za-z0-9_]*)\s*[=:]\s*(\S.*?)\s*$")


@dataclass(frozen=True, eq=False)
class LoadHistory:
    """An engine-speed history and its load factor (rpm / rpm_ref)². Arrays are read-only.

    ``source`` is the file it was read from (or a description), ``format`` one of FORMATS (or
    "array" for histories built in code)."""

    time_s: np.ndarray
    rpm: np.ndarray
    load_factor: np.ndarray
    rpm_ref: float
    duration_s: float
    source: str
    format: str
    channels: tuple = ()          # ((name, values), ...): the csv's load channels

    def __post_init__(self) -> None:
        for name in ("time_s", "rpm", "load_factor"):
            arr = np.array(getattr(self, name), dtype=float)
            arr.flags.writeable = False
            object.__setattr__(self, name, arr)
        chans = []
        for nm, vals in self.channels:
            arr = np.array(vals, dtype=float)
            arr.flags.writeable = False
            chans.append((str(nm), arr))
        object.__setattr__(self, "channels", tuple(chans))

    @property
    def channel_names(self) -> tuple[str, ...]:
        return tuple(nm for nm, _ in self.channels)

    def channel(self, name: str) -> np.ndarray:
        """The values of channel ``name`` (InputError naming the history if it has none). The
        angular acceleration ``alpha_rad_s2`` is derived from the rpm column when the history
        has no such column (``angular_acceleration``)."""
        for nm, vals in self.channels:
            if nm == name:
                return vals
        if name == ALPHA_CHANNEL:
            return angular_acceleration(self)
        raise InputError(self.source, f"channel {name}", "a column of the load history: "
                         + (", ".join(self.channel_names) or "(it has none besides time_s, rpm; "
                            "write a csv 'time_s,rpm," + name + "')"),
                         reason="is named by a load but absent from the history")

    @property
    def n_samples(self) -> int:
        return int(self.rpm.size)

    def repeated(self, times: int) -> LoadHistory:
        """The block played ``times`` times in a row (a longer block of the same riding)."""
        if int(times) != times or times < 1:
            raise InputError(self.source, "repeat", "an integer >= 1", got=times)
        k = int(times)
        t0 = self.time_s[0]
        offs = np.repeat(np.arange(k) * self.duration_s, self.n_samples)
        return LoadHistory(np.tile(self.time_s - t0, k) + offs + t0, np.tile(self.rpm, k),
                           np.tile(self.load_factor, k), self.rpm_ref, k * self.duration_s,
                           self.source, self.format,
                           tuple((nm, np.tile(v, k)) for nm, v in self.channels))

    def with_reference(self, rpm_ref: float) -> LoadHistory:
        """The same speeds with the load factor taken relative to another reference speed — the
        speed at which the static solution was computed (e.g. a static case at 10 000 rpm and
        the seed's rpm.dat normalised to 7000 rpm: load factor × (7000/10 000)²)."""
        _check_ref(rpm_ref, self.source, "rpm_ref")
        return LoadHistory(self.time_s, self.rpm, rpm2_scale(self.rpm, rpm_ref), float(rpm_ref),
                           self.duration_s, self.source, self.format, self.channels)

    def scaled(self, factor: float) -> LoadHistory:
        """Every speed multiplied by ``factor`` (load factor × factor²), same times."""
        if not (math.isfinite(factor) and factor > 0):
            raise InputError(self.source, "scale", "a finite number > 0", got=factor)
        rpm = self.rpm * factor
        return LoadHistory(self.time_s, rpm, rpm2_scale(rpm, self.rpm_ref), self.rpm_ref,
                           self.duration_s, self.source, self.format, self.channels)


def from_rpm(rpm, *, sample_rate_hz: float = SEED_SAMPLE_RATE_HZ,
             rpm_ref: float = DEFAULT_RPM_REF, source: str = "array") -> LoadHistory:
    """A history from an rpm array sampled at ``sample_rate_hz`` (same checks as the files)."""
    rpm = np.asarray(rpm, dtype=float).ravel()
    check_sample_rate(sample_rate_hz, source, "sample_rate_hz")
    _check_ref(rpm_ref, source, "rpm_ref")
    if rpm.size == 0:
        raise InputError(source, "rpm", "at least one sample", reason="is empty")
    if rpm.size > MAX_LINES:
        raise InputError(source, "rpm", f"at most {MAX_LINES:,} samples".replace(",", " "),
                         got=rpm.size, reason="has too many samples")
    bad = ~(np.isfinite(rpm) & (rpm >= 0) & (rpm <= RPM_CEILING))
    if bad.any():
        i = int(np.argmax(bad))
        raise InputError(source, f"rpm[{i}]", f"finite, in [0, {RPM_CEILING:g}] rpm",
                         got=float(rpm[i]))
    n = rpm.size
    return LoadHistory(np.arange(n) / sample_rate_hz, rpm, rpm2_scale(rpm, rpm_ref), float(rpm_ref),
                       n / sample_rate_hz, source, "array")


def read_history(path: str | Path, *, fmt: str | None = None, rpm_ref: float | None = None,
                 sample_rate_hz: float | None = None) -> LoadHistory:
    """Read an rpm history file (see the module docstring for the formats and checks).

    ``rpm_ref``: normalised files — the speed the values are normalised by (must match the
    header if it has one); rpm/csv files — the reference speed of the load factor (default
    ``DEFAULT_RPM_REF``). To evaluate against a static solution computed at another speed, use
    ``history.with_reference(static_rpm)``."""
    path = Path(path)
    src = str(path)
    if fmt is not None and fmt not in FORMATS:
        raise InputError(src, "format", " | ".join(FORMATS), got=fmt)
    if rpm_ref is not None:
        _check_ref(rpm_ref, "command line", "rpm_ref")
    if sample_rate_hz is not None:
        check_sample_rate(sample_rate_hz, "argument", "sample_rate_hz")
    text = _read_capped(path, src)

    fast = _read_fast(src, text, fmt, rpm_ref, sample_rate_hz)
    return fast if fast is not None else _read_lines(src, text, fmt, rpm_ref, sample_rate_hz)


def _read_capped(path: Path, src: str) -> str:
    """The file's text, at most ``MAX_BYTES`` and ``MAX_LINES`` (see the module docstring):
    an endless or binary stream is refused after at most ``MAX_BYTES`` bytes read."""
    allowed = (f"a UTF-8 text file of at most {MAX_BYTES // 2 ** 20} MB and "
               f"{MAX_LINES:,} lines".replace(",", " "))
    try:
        with open(path, "rb") as fh:
            data = fh.read(_BINARY_PROBE)
            if b"\0" not in data:
                data += fh.read(MAX_BYTES + 1 - len(data))
    except FileNotFoundError:
        raise InputError(src, "file", "an existing, readable file", reason="does not exist")\
            from None
    except OSError as exc:
        raise InputError(src, "file", "a readable UTF-8 text file",
                         reason=f"cannot be read ({exc.__class__.__name__})") from None
    if b"\0" in data:
        raise InputError(src, "file", allowed, reason="is binary (NUL bytes), not text")
    if len(data) > MAX_BYTES:
        raise InputError(src, "file", allowed, reason=f"is larger than "
                         f"{MAX_BYTES // 2 ** 20} MB (far longer than any real rpm log)")
    if data.count(b"\n") > MAX_LINES:
        raise InputError(src, "file", allowed, reason=f"has more than {MAX_LINES:,} lines "
                         "(far longer than any real rpm log)".replace(",", " "))
    try:
        text = data.decode("utf-8-sig")       # tolerate a BOM from spreadsheet exports
    except UnicodeDecodeError as exc:
        raise InputError(src, "file", "a readable UTF-8 text file",
                         reason=f"cannot be read ({exc.__class__.__name__})") from None
    return text.replace("\r\n", "\n").replace("\r", "\n")    # as text mode's newlines


def _read_lines(src: str, text: str, fmt: str | None, rpm_ref, sample_rate_hz) -> LoadHistory:
    """The line-by-line reader: every check, and an error that names the line."""
    path = Path(src)
    header, rows = _split(text)
    if fmt is None:
        fmt = _detect(path, header, rows, src)
    if "format" in header and header["format"][1] != fmt:
        line, value = header["format"]
        raise InputError(src, f"line {line}: format", f"{fmt} (the format being read)",
                         got=value, reason="contradicts the format being read")
    if fmt == "csv":
        return _read_csv(src, header, rows, rpm_ref)
    return _read_sampled(src, fmt, header, rows, rpm_ref, sample_rate_hz)


# --- internals -------------------------------------------------------------------------------

def _read_fast(src: str, text: str, fmt: str | None, rpm_ref, sample_rate_hz):
    """The common case at C speed (a 5-million-sample log in about a second): the header is read
    line by line, the data by ``numpy.loadtxt``. Anything unusual (a value that does not parse,
    is out of range, a comment between data lines, a bad header) returns None, and the
    line-by-line reader below then reads the file again and names the offending line."""
    import io
    if not text.isascii() or any(c in text for c in "\f\v\x1c\x1d\x1e") \
            or text.count("\r") != text.count("\r\n"):
        return None          # line breaks other than \n / \r\n, or non-ASCII: str.splitlines
    head: list[str] = []
    pos = 0
    while pos < len(text):
        end = text.find("\n", pos)
        end = len(text) if end < 0 else end
        line = text[pos:end].strip()
        if line and not line.startswith("#"):
            break
        head.append(line)
        pos = end + 1
    body = text[pos:]
    if "#" in body or not body.strip():
        return None
    header = {}
    for line in head:
        m = _HEADER_RE.match(line)
        if m:
            header[m.group(1).lower()] = (0, m.group(2))
    is_csv = fmt == "csv" or (fmt is None and (Path(src).suffix.lower() == ".csv" or body.lstrip(
        " \t").lower().replace(" ", "").startswith("time_s,")))
    try:
        if is_csv:
            first, _, rest = body.partition("\n")
            names = [c.strip() for c in first.split(",")]
            if [c.lower() for c in names[:2]] != ["time_s", "rpm"] or not _channels_ok(names):
                return None
            data = np.loadtxt(io.StringIO(rest), delimiter=",", ndmin=2, dtype=float)
            if data.shape[1] != len(names) or data.shape[0] < 2:
                return None
        else:
            data = np.loadtxt(io.StringIO(body), ndmin=2, dtype=float)
            if data.shape[1] != 1:                     # several numbers on a line
                return None
            data = data.ravel()
    except ValueError:
        return None
    if fmt is None:
        fmt = "csv" if is_csv else header["format"][1] if "format" in header else (
            "normalised" if data.max() <= _AUTO_NORMALISED_MAX else "rpm")
    if not np.all(np.isfinite(data)) or fmt not in FORMATS or (fmt == "csv") != is_csv or (
            "format" in header and header["format"][1] != fmt):
        return None
    if is_csv:
        t, rpm = data[:, 0], data[:, 1]
        if not (np.all(np.diff(t) > 0) and np.all((rpm >= 0) & (rpm <= RPM_CEILING))):
            return None
        dt = np.diff(t)
        if not np.all((dt >= 1.0 / SAMPLE_RATE_HZ[1]) & (dt <= 1.0 / SAMPLE_RATE_HZ[0])):
            return None                  # the line reader names the line
        ref = DEFAULT_RPM_REF if rpm_ref is None else float(rpm_ref)
        return LoadHistory(t, rpm, rpm2_scale(rpm, ref), ref, float(t[-1] - t[0] + (t[-1] - t[-2])),
                           src, "csv", tuple((nm, data[:, 2 + j])
                                             for j, nm in enumerate(names[2:])))
    try:
        rate = _header_or_option(src, header, "sample_rate_hz", sample_rate_hz, check_sample_rate)
        ref = (_header_or_option(src, header, "reference_rpm", rpm_ref, _check_ref)
               if fmt == "normalised" else rpm_ref)
    except InputError:
        return None
    if (rate is None and fmt == "rpm") or (ref is None and fmt == "normalised"):
        return None
    rate = SEED_SAMPLE_RATE_HZ if rate is None else rate
    if fmt == "normalised":
        if not np.all((data >= 0) & (data <= rpm2_scale(RPM_CEILING, ref))):
            return None
        lf, rpm = data, ref * np.sqrt(data)
    else:
        if not np.all((data >= 0) & (data <= RPM_CEILING)):
            return None
        ref = DEFAULT_RPM_REF if ref is None else float(ref)
        rpm, lf = data, rpm2_scale(data, ref)
    n = data.size
    return LoadHistory(np.arange(n) / rate, rpm, lf, float(ref), n / rate, src, fmt)


def _split(text: str) -> tuple[dict[str, tuple[int, str]], list[tuple[int, str]]]:
    """Header keys (before the first data line) and (line number, text) data rows."""
    header: dict[str, tuple[int, str]] = {}
    rows: list[tuple[int, str]] = []
    for k, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line:
            continue
        if line.startswith("#"):
            m = _HEADER_RE.match(line)
            if m and not rows:
                header[m.group(1).lower()] = (k, m.group(2))
            continue
        rows.append((k, line))
    return header, rows


def _detect(path: Path, header, rows, src: str) -> str:
    if path.suffix.lower() == ".csv":
        return "csv"
    if "format" in header:
        line, value = header["format"]
        if value not in FORMATS:
            raise InputError(src, f"line {line}: format", " | ".join(FORMATS), got=value)
        return value
    if not rows:
        raise InputError(src, "data", "at least one data line", reason="is empty")
    if rows[0][1].lower().replace(" ", "").startswith("time_s,"):
        return "csv"
    vals = []
    for line, s in rows:
        try:
            vals.append(float(s))
        except ValueError:
            raise InputError(src, f"line {line}", "one number per line", got=s,
                             reason="is not a number") from None
    finite = [v for v in vals if math.isfinite(v)]
    return "normalised" if finite and max(finite) <= _AUTO_NORMALISED_MAX else "rpm"


def _header_float(src: str, header, key: str) -> float | None:
    if key not in header:
        return None
    line, value = header[key]
    if not _ASCII_NUMBER.fullmatch(value):            # float() would take '1_000' and '٣'
        raise InputError(src, f"line {line}: {key}", "a number", got=value)
    return float(value)


def _check_ref(v: float, src: str, field: str) -> None:
    if not (math.isfinite(v) and 0 < v <= RPM_CEILING):
        raise InputError(src, field, f"in (0, {RPM_CEILING:g}] rpm", got=v)


def check_sample_rate(v: float, src: str, field: str) -> None:
    """A sample rate within ``SAMPLE_RATE_HZ`` (``field``: the header line or the option)."""
    lo, hi = SAMPLE_RATE_HZ
    if not (math.isfinite(v) and lo <= v <= hi):
        raise InputError(src, field, f"a sample rate in [{lo:g}, {hi:g}] Hz (one sample per "
                         f"{1 / lo:g} s at most; 10× the fastest engine-speed logger at most)",
                         got=v)


def _check_intervals(src: str, t: np.ndarray, lines=None) -> None:
    """A csv log's sample intervals within 1/SAMPLE_RATE_HZ (the same bound as a rate)."""
    lo, hi = 1.0 / SAMPLE_RATE_HZ[1], 1.0 / SAMPLE_RATE_HZ[0]
    dt = np.diff(t)
    bad = (dt < lo) | (dt > hi)
    if bad.any():
        i = int(np.argmax(bad)) + 1
        where = f"line {lines[i]}: time_s" if lines is not None else f"time_s[{i}]"
        raise InputError(src, where, f"a step of [{lo:g}, {hi:g}] s after the previous "
                         f"sample (a sample rate in [{SAMPLE_RATE_HZ[0]:g}, "
                         f"{SAMPLE_RATE_HZ[1]:g}] Hz)", got=float(t[i]))


_ASCII_NUMBER = re.compile(r"[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?|[+-]?(inf|nan)",
                           re.IGNORECASE | re.ASCII)


def _number(src: str, line: int, s: str, what: str, allowed: str) -> float:
    try:
        if not _ASCII_NUMBER.fullmatch(s):       # float() would take '٣' and '1_000'
            raise ValueError(s)
        v = float(s)
    except ValueError:
        raise InputError(src, f"line {line}: {what}", allowed, got=s,
                         reason="is not a number") from None
    if not math.isfinite(v):
        raise InputError(src, f"line {line}: {what}", allowed, got=s)
    return v


def _bounded_values(src: str, rows, what: str, hi: float, allowed: str) -> np.ndarray:
    """The numbers of ``rows`` ((line, text) pairs), each in [0, hi]; else an error naming the
    line."""
    out = np.empty(len(rows))
    for i, (line, text) in enumerate(rows):
        v = _number(src, line, text, what, allowed)
        if not 0 <= v <= hi:
            raise InputError(src, f"line {line}: {what}", allowed, got=v)
        out[i] = v
    return out


def _header_or_option(src: str, header, key: str, option: float | None, check) -> float | None:
    """The header's ``key`` (checked by ``check``) or the option's value; both given must agree."""
    value = _header_float(src, header, key)
    if value is None:
        return option
    field = f"line {header[key][0]}: {key}"
    check(value, src, field)
    if option is not None and not math.isclose(option, value, rel_tol=1e-12):
        raise InputError(src, field, f"{option:g} (the value given on the command line)",
                         got=value, reason="contradicts the option")
    return value


def _read_sampled(src, fmt, header, rows, rpm_ref, sample_rate_hz) -> LoadHistory:
    if not rows:
        raise InputError(src, "data", "at least one data line", reason="is empty")
    rate = _header_or_option(src, header, "sample_rate_hz", sample_rate_hz, check_sample_rate)
    if rate is None:
        if fmt == "rpm":
            raise InputError(src, "sample_rate_hz", "a header '# sample_rate_hz = ...' or the "
                             "--sample-rate option", reason="is missing")
        rate = SEED_SAMPLE_RATE_HZ

    if fmt == "normalised":
        ref = _header_or_option(src, header, "reference_rpm", rpm_ref, _check_ref)
        if ref is None:
            raise InputError(src, "reference_rpm", "a header '# reference_rpm = ...' or the "
                             "--rpm-ref option", reason="is missing")
        cap = rpm2_scale(RPM_CEILING, ref)
        allowed = f"a finite number in [0, {cap:.6g}] (= ({RPM_CEILING:g}/{ref:g})²)"
        lf = _bounded_values(src, rows, "load factor", cap, allowed)
        rpm = ref * np.sqrt(lf)
    else:
        ref = DEFAULT_RPM_REF if rpm_ref is None else float(rpm_ref)
        allowed = f"a finite number in [0, {RPM_CEILING:g}] rpm"
        rpm = _bounded_values(src, rows, "rpm", RPM_CEILING, allowed)
        lf = rpm2_scale(rpm, ref)
    n = len(rows)
    return LoadHistory(np.arange(n) / rate, rpm, lf, float(ref), n / rate, src, fmt)


def _read_csv(src, header, rows, rpm_ref) -> LoadHistory:
    if not rows:
        raise InputError(src, "data", "a header 'time_s,rpm' and at least two rows",
                         reason="is empty")
    line0, first = rows[0]
    names = [c.strip() for c in first.split(",")]
    if [c.lower() for c in names[:2]] != ["time_s", "rpm"]:
        raise InputError(src, f"line {line0}: header", "'time_s,rpm' (then load channels, "
                         "e.g. 'time_s,rpm,torque_Nm')", got=first)
    if not _channels_ok(names):
        raise InputError(src, f"line {line0}: header", f"channel names name_unit (letters, "
                         f"digits, _; e.g. torque_Nm), unique, at most {MAX_CHANNELS}",
                         got=first)
    data = rows[1:]
    if len(data) < 2:
        raise InputError(src, "data", "at least two rows 'time_s,rpm'",
                         got=len(data), reason="has too few rows")
    ref = DEFAULT_RPM_REF if rpm_ref is None else float(rpm_ref)
    t = np.empty(len(data))
    rpm = np.empty(len(data))
    extra = np.empty((len(names) - 2, len(data)))
    allowed_rpm = f"a finite number in [0, {RPM_CEILING:g}] rpm"
    for i, (line, s) in enumerate(data):
        cols = s.split(",")
        if len(cols) != len(names):
            raise InputError(src, f"line {line}", f"{len(names)} columns '{','.join(names)}'",
                             got=s)
        for j, nm in enumerate(names[2:]):
            extra[j, i] = _number(src, line, cols[2 + j].strip(), nm, "a finite number")
        t[i] = _number(src, line, cols[0].strip(), "time_s", "a finite number (s)")
        v = _number(src, line, cols[1].strip(), "rpm", allowed_rpm)
        if not 0 <= v <= RPM_CEILING:
            raise InputError(src, f"line {line}: rpm", allowed_rpm, got=v)
        rpm[i] = v
        if i and not t[i] > t[i - 1]:
            raise InputError(src, f"line {line}: time_s",
                             f"> {t[i - 1]:g} (strictly increasing)", got=float(t[i]))
    _check_intervals(src, t, [line for line, _ in data])
    duration = float(t[-1] - t[0] + (t[-1] - t[-2]))
    return LoadHistory(t, rpm, rpm2_scale(rpm, ref), ref, duration, src, "csv",
                       tuple((nm, extra[j]) for j, nm in enumerate(names[2:])))


def _channels_ok(names: list[str]) -> bool:
    """A csv header's load channels after time_s, rpm: name_unit each, unique, not too many."""
    ch = names[2:]
    return (len(ch) <= MAX_CHANNELS and len(set(ch)) == len(ch)
            and all(CHANNEL_RE.fullmatch(c) for c in ch))


def angular_acceleration(history: LoadHistory) -> np.ndarray:
    """dω/dt in rad/s² at every sample of the rpm column (second-order central differences,
    one-sided at the ends: ``numpy.gradient`` on the sample times; a block that repeats is
    differenced as it stands). The d'Alembert torque of a run-up follows it
    (``scales_with = "alpha_rad_s2"``)."""
    if history.n_samples < 2:
        return np.zeros(history.n_samples)
    return np.gradient(omega(history.rpm), history.time_s)
