"""Smoke test of the fatigue figures (shaftfe.fatigue.plots): each writes a non-empty PNG.
Not a numerical validation; the plotted numbers are validated in test_fatigue_damage.py."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from shaftfe.fatigue import count_cycles, load_material, rainflow_matrix
from shaftfe.fatigue import plots as fp
from shaftfe.fatigue.history import read_history
from shaftfe.fatigue.kernels import damage_matrix


def test_all_figures_are_written(tmp_path):
    h = read_history(Path(__file__).resolve().parents[2] / "loadspectra" / "rpm.dat")
    c = count_cycles(h.load_factor)
    m = load_material("structural_steel")
    out = [fp.plot_load_history(h, tmp_path / "h.png"),
           fp.plot_sn_curve(m, tmp_path / "sn.png", kf=0.8),
           fp.plot_cycle_matrix(rainflow_matrix(c, 150.0, bins=8), tmp_path / "rm.png"),
           fp.plot_cycle_matrix(damage_matrix(150.0, c, m, bins=8), tmp_path / "dm.png"),
           fp.plot_haigh(150.0, c, m, tmp_path / "haigh.png", theory="gerber"),
           fp.plot_haigh(-150.0, c, m, tmp_path / "haigh_neg.png")]
    for p in out:
        assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and p.stat().st_size > 5000
    assert np.isfinite(c.range).all()
