"""The figures' shared helpers (``shaftfe.util.figures``)."""

from __future__ import annotations

import re

import matplotlib
import pytest

from shaftfe.util.figures import log_ticks, power_label

matplotlib.use("Agg")


@pytest.mark.parametrize(("x", "text"), [
    (1.0, "10⁰"), (1000.0, "10³"), (1e-4, "10⁻⁴"), (2e3, "2×10³"), (5e-2, "5×10⁻²"),
    (999.0, "9.99×10²"), (100.1, "1.001×10²"), (0.0, "0")])
def test_power_label(x, text):
    """Exact strings (the mantissa by ``%g``, the exponent in superscript digits)."""
    assert power_label(x) == text


@pytest.mark.parametrize("limits", [(1.0, 1e8), (30.0, 2e4), (2.0, 15.0), (0.5, 3.0), (1e-5, 1e-2),
                                    (100.0, 100.5), (2.0, 2.008)])
def test_log_ticks_label_what_matplotlib_labels_without_tex(limits, monkeypatch):
    """The same ticks labelled as by matplotlib's default log formatter (its labels are TeX
    math: the reason for ``log_ticks``), the same values, and no TeX parsed at all."""
    import matplotlib.pyplot as plt
    from matplotlib import mathtext

    def default_labels(ax):
        fig = ax.figure
        fig.canvas.draw()
        return [(t.get_position()[1], t.get_text()) for t in
                ax.yaxis.get_majorticklabels() + ax.yaxis.get_minorticklabels()
                if limits[0] <= t.get_position()[1] <= limits[1]]

    fig, ax = plt.subplots()
    ax.set_yscale("log")
    ax.set_ylim(*limits)
    ref = default_labels(ax)
    plt.close(fig)

    def no_tex(*a, **k):
        raise AssertionError("TeX math parsed")
    monkeypatch.setattr(mathtext.MathTextParser, "parse", no_tex)
    fig, ax = plt.subplots()
    ax.set_yscale("log")
    log_ticks(ax.yaxis)
    ax.set_ylim(*limits)
    got = default_labels(ax)
    plt.close(fig)
    assert [y for y, _ in got] == [y for y, _ in ref]
    assert [bool(s) for _, s in got] == [bool(s) for _, s in ref]
    assert any(s for _, s in got)
    for (y, s), (_, r) in zip(got, ref, strict=True):
        if s:           # matplotlib's TeX "$\mathdefault{2\times10^{3}}$" and ours "2×10³"
            m = re.fullmatch(r"\$\\mathdefault\{(?:([\d.]+)\\times)?10\^\{(-?\d+)\}\}\$", r)
            assert m, r
            sup = m[2].translate(str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻"))
            assert s == (f"{m[1]}×" if m[1] else "") + f"10{sup}" == power_label(y)
