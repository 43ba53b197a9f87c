"""Rainflow counting of the load-factor history (detection) and its recording into arrays and
range × mean matrices.

Detection is ``three_point`` (ASTM E1049-85 §5.4.4, three-point rule; half cycles kept) on the
history's reversals, found by NumPy first (``reversals``): a 5-million-sample log is counted in
about two seconds. It gives the same cycles in the same order as the ``rainflow`` package, which
the validation tests use as the independent peer. The history is counted ONCE, in load-factor
units; stresses follow per node by scaling (``kernels``). Two closures of the residue:

``"repeated"`` (default) — the block is one period of a repeating history, as the Ansys Fatigue
    Tool treats a load-history block that is applied over and over. The block is rotated to
    start at its absolute maximum and the maximum is appended at the end (the sample that the
    next block would start with). A history that starts and ends at its absolute maximum leaves
    as residue only pairs of equal half cycles (the largest one, max → min → max, among them),
    so after merging equal (range, mean) pairs every count is a whole number, and n repetitions
    of the block give exactly n times the cycles of one block. Same cycles as the other usual
    closure, counting the one-pass residue concatenated with itself (as fatpack documents it);
    the validation tests check the two against each other.
``"half"`` — the history as it stands, residue counted as half cycles (ASTM E1049-85 §5.4.4).

Cycles with equal (range, mean) are merged (their counts added): exact, because both numbers are
computed from the same two reversal values.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shaftfe.errors import InputError

CLOSURES = ("repeated", "half")


@dataclass(frozen=True, eq=False)
class Cycles:
    """Counted cycles of a load-factor history: ``range`` (max − min), ``mean`` ((max + min)/2)
    and ``count`` (1 per full cycle, 0.5 per half cycle) as read-only 1-D arrays."""

    range: np.ndarray
    mean: np.ndarray
    count: np.ndarray
    closure: str

    def __post_init__(self) -> None:
        for name in ("range", "mean", "count"):
            arr = np.array(getattr(self, name), dtype=float).ravel()
            arr.flags.writeable = False
            object.__setattr__(self, name, arr)
        if not (self.range.size == self.mean.size == self.count.size):
            raise ValueError("range, mean and count must have the same length")

    @property
    def n(self) -> int:
        """Number of distinct (range, mean) cycle classes."""
        return int(self.range.size)

    @property
    def total_count(self) -> float:
        return float(self.count.sum())

    @property
    def amplitude(self) -> np.ndarray:
        return self.range / 2.0

    @property
    def maximum(self) -> np.ndarray:
        return self.mean + self.range / 2.0

    @property
    def minimum(self) -> np.ndarray:
        return self.mean - self.range / 2.0


def extract(series, closure: str = "repeated") -> np.ndarray:
    """Raw rainflow cycles (range, mean, count) as an (n, 3) array, not merged (detection)."""
    if closure not in CLOSURES:
        raise InputError("fatigue options", "closure", " | ".join(CLOSURES), got=closure)
    y = np.asarray(series, dtype=float).ravel()
    if y.size and not np.all(np.isfinite(y)):
        raise InputError("load history", "load_factor", "finite values", reason="has NaN/inf")
    if y.size < 2 or y.max() == y.min():
        return np.zeros((0, 3))
    if closure == "repeated":
        i = int(np.argmax(y))
        y = np.concatenate((y[i:], y[:i], y[i:i + 1]))
    lo, hi, count = three_point(reversals(y))
    rng = np.abs(hi - lo)
    keep = rng > 0
    return np.column_stack((rng[keep], 0.5 * (lo + hi)[keep], count[keep]))


def three_point(rev: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """ASTM E1049-85 §5.4.4 rainflow on the reversals ``rev`` (detection only): the two
    reversal values of each counted range and its count (1 full cycle, 0.5 half cycle, the
    residue as half cycles), in the order counted. A range Y (the older of the two newest) is
    counted once the newest range X is at least as large; Y holding the start point is a half
    cycle. The same cycles, in the same order, as ``rainflow.extract_cycles``
    (tests/validation/test_fatigue_counting.py checks it), in a loop over plain floats."""
    stack: list[float] = []
    push, a_out, b_out, c_out = stack.append, [], [], []
    start = 0                                   # stack[start] is the oldest point still held
    for x in rev.tolist():
        push(x)
        while len(stack) - start >= 3:
            x1, x2, x3 = stack[-3], stack[-2], stack[-1]
            if abs(x3 - x2) < abs(x2 - x1):
                break
            if len(stack) - start == 3:         # Y contains the start: half cycle
                a_out.append(stack[start])
                b_out.append(stack[start + 1])
                c_out.append(0.5)
                start += 1
            else:                               # full cycle; drop its two points
                a_out.append(x1)
                b_out.append(x2)
                c_out.append(1.0)
                del stack[-3:-1]
    for i in range(start, len(stack) - 1):      # residue: half cycles
        a_out.append(stack[i])
        b_out.append(stack[i + 1])
        c_out.append(0.5)
    return np.array(a_out, dtype=float), np.array(b_out, dtype=float), np.array(c_out, float)


def reversals(series) -> np.ndarray:
    """The turning points of a history, in NumPy (rainflow counts only these): the first and the
    last sample and every sample where the direction changes, plateaus (equal neighbours) kept
    once. The same values as ``rainflow.reversals`` yields, at C speed: a 5-million-sample log
    shrinks to its reversals before the Python-level counting loop sees it."""
    y = np.asarray(series, dtype=float).ravel()
    if y.size < 3:              # as rainflow.reversals: one sample or two give one point or none
        return y[:1] if y.size == 2 else y[:0]
    first_last = y[[0, -1]]
    y = y[np.concatenate(([True], y[1:] != y[:-1]))]
    if y.size < 3:
        return first_last
    d = np.diff(y)
    turn = np.flatnonzero(d[1:] * d[:-1] < 0) + 1
    return y[np.concatenate(([0], turn, [y.size - 1]))]


def merge(raw: np.ndarray, closure: str) -> Cycles:
    """Record raw (range, mean, count) rows as ``Cycles`` with equal (range, mean) merged."""
    if raw.shape[0] == 0:
        return Cycles(np.zeros(0), np.zeros(0), np.zeros(0), closure)
    # complex numbers sort by (real, imag): one sort of (range, mean) pairs, the order of
    # np.unique(axis=0) at a fraction of its cost on a million cycles
    keys, inv = np.unique(raw[:, 0] + 1j * raw[:, 1], return_inverse=True)
    counts = np.bincount(inv.ravel(), weights=raw[:, 2], minlength=keys.size)
    return Cycles(keys.real, keys.imag, counts, closure)


def count_cycles(series, closure: str = "repeated") -> Cycles:
    """Rainflow-count a load-factor (or any) history; see the module docstring."""
    return merge(extract(series, closure), closure)


@dataclass(frozen=True, eq=False)
class CycleMatrix:
    """A range × mean matrix: ``values[i, j]`` sums a per-cycle quantity (count, damage) over the
    cycles whose range is in [range_edges[i], range_edges[i+1]) and mean in mean bin j."""

    range_edges: np.ndarray
    mean_edges: np.ndarray
    values: np.ndarray
    quantity: str
    units: str = ""           # units of range and mean: "MPa" or "load factor"


def _matrix(ranges, means, weights, bins, quantity, units="") -> CycleMatrix:
    nr, nm = (bins, bins) if np.isscalar(bins) else bins
    if ranges.size == 0:
        return CycleMatrix(np.linspace(0, 1, nr + 1), np.linspace(0, 1, nm + 1),
                           np.zeros((nr, nm)), quantity, units)
    rr = (0.0, float(ranges.max()) or 1.0)
    lo, hi = float(means.min()), float(means.max())
    mr = (lo, hi) if hi > lo else (lo - 0.5 * abs(lo or 1.0), hi + 0.5 * abs(hi or 1.0))
    vals, re, me = np.histogram2d(ranges, means, bins=(nr, nm), range=(rr, mr), weights=weights)
    return CycleMatrix(re, me, vals, quantity, units)


def rainflow_matrix(cycles: Cycles, scale: float = 1.0, bins=10,
                    units: str | None = None) -> CycleMatrix:
    """Counts in range × mean bins, in stress units when ``scale`` is a node's σ_eq at the
    reference speed (MPa), in load-factor units for scale = 1 (``units`` overrides: cycles
    already in MPa, e.g. ``kernels.node_stress_cycles``)."""
    units = units or ("load factor" if scale == 1.0 else "MPa")
    return _matrix(cycles.range * abs(scale), cycles.mean * scale, cycles.count, bins, "count",
                   units)
