"""What the figure modules share (matplotlib is imported inside the functions)."""

from __future__ import annotations

import math

_SUPERSCRIPT = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")


def power_label(x: float) -> str:
    """A log axis's tick label in plain text: 10³, 2×10⁻⁴, 1.001×10² (the mantissa by
    ``%g``, as matplotlib's default label, which sets the same text as TeX math)."""
    if x == 0 or not math.isfinite(x):
        return f"{x:g}"
    e = math.floor(math.log10(abs(x)) + 1e-9)
    m = x / 10.0 ** e
    power = f"10{str(e).translate(_SUPERSCRIPT)}"
    return power if math.isclose(m, 1.0, rel_tol=1e-9) else f"{m:g}×{power}"


def log_ticks(*axes) -> None:
    """Plain-text tick labels on each log-scaled axis of ``axes`` (``ax.xaxis``,
    ``ax.yaxis``), the ticks matplotlib would label: its default labels are TeX math, whose
    parser (pyparsing) costs ~0.15 s to build in a process and ~10 ms per new label, the
    largest part of drawing a log-scaled figure."""
    from matplotlib import ticker

    class PowerFormatter(ticker.LogFormatter):
        def __call__(self, x, pos=None):
            return power_label(x) if super().__call__(x, pos) else ""

    for axis in axes:
        axis.set_major_formatter(PowerFormatter())
        axis.set_minor_formatter(PowerFormatter(labelOnlyBase=False))
