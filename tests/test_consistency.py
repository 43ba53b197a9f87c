"""Consistency a new user relies on: one load-case default for every command, the seed's
comparison only where it applies, tables and plots that read right (issue 13 §6-7)."""

from __future__ import annotations

import argparse

import numpy as np
import pytest

from shaftfe.cli import build_parser
from shaftfe.commands._common import print_table


@pytest.mark.parametrize("argv", [["static", "--variant", "x2_57"],
                                  ["beam", "--variant", "x2_57"],
                                  ["fatigue", "rpm.dat"], ["report"]])
def test_every_command_loads_every_part_by_default(argv):
    args = build_parser().parse_args(argv)
    assert args.seed_load_case is False
    args = build_parser().parse_args([*argv, "--seed-load-case"])
    assert args.seed_load_case is True


def test_the_seed_comparison_is_printed_only_where_it_applies(tmp_path):
    from shaftfe.fatigue.run import SEED_SETTINGS, seed_applies
    from shaftfe.util.paths import GEOMETRY_DIR
    rpm = GEOMETRY_DIR.parent / "loadspectra" / "rpm.dat"
    ok = argparse.Namespace(spectrum=str(rpm), **SEED_SETTINGS)
    assert seed_applies(ok, "x2_57")
    assert not seed_applies(ok, "x2_31")                            # another variant
    other = tmp_path / "other.dat"
    other.write_text(rpm.read_text() + "0.5\n")
    assert not seed_applies(argparse.Namespace(**{**vars(ok), "spectrum": str(other)}),
                            "x2_57")                                 # another history
    for key, value in (("mean_stress", "goodman"), ("seed_load_case", False), ("kf", 0.8),
                       ("material", "14220"), ("design_life", 1e6)):
        assert not seed_applies(argparse.Namespace(**{**vars(ok), key: value}), "x2_57")


def test_a_round_off_residue_prints_as_zero_beside_large_numbers(capsys):
    print_table(["quantity", "N"], [["a", 2225.53], ["b", 6.9e-13], ["c", 0.06712]])
    out = capsys.readouterr().out
    assert "6.9e-13" not in out and "2 225.53" in out and "0.06712" in out
    assert out.splitlines()[3].split()[-1] == "0.00"


def test_stress_envelope_has_no_empty_slice():
    """A coarse element spanning a slice without a node of its own still counts there (the
    deflection.png bug: 0 MPa in the 28-29 mm slice where the VTU held 126.8 MPa)."""
    from skfem import MeshTet

    from shaftfe.io.vtu import stress_envelope
    m = MeshTet.init_tensor(np.linspace(0.0, 100.0, 4), np.linspace(0, 1, 2),
                            np.linspace(0, 1, 2))                    # 33 mm long elements
    vm = 1.0 + m.p[0]                                                # > 0 everywhere
    _, env = stress_envelope(m, vm, n_slices=120)
    assert np.all(env > 0)
    # each slice shows the largest nodal value of the elements reaching into it
    assert env[0] == pytest.approx(1.0 + 100.0 / 3, rel=1e-12)       # exact arithmetic
    assert env[-1] == pytest.approx(101.0, rel=1e-12)


def test_campbell_axis_shows_the_excitation_region_and_the_first_pair():
    from types import SimpleNamespace

    from shaftfe.rotordynamics.plots import campbell_top_hz
    rpm = np.linspace(0, 9500, 5)
    freq = np.tile([480.0, 600.0, 1100.0, 11_000.0], (5, 1))
    res = SimpleNamespace(freq_hz=freq, rpm=rpm, orders=(1.0, 2.0))
    top = campbell_top_hz(res)
    assert top == pytest.approx(1.1 * 600.0)        # the whirl pair, not the 11 kHz mode
    assert top > 2 * 9500 / 60                       # and the whole 2x excitation line


def test_a_solver_failure_names_the_bearings():
    from types import SimpleNamespace

    from shaftfe.fe.supports import SupportBlock
    from shaftfe.static.solve import _springs
    blocks = [SupportBlock("gear_side", ("u_y", "u_z"), np.zeros((2, 3)), 1e-9 * np.eye(2)),
              SupportBlock("free_side", ("u_y", "u_z"), np.zeros((2, 3)),
                           np.array([[35030.0, 8756.0], [8756.0, 35030.0]])),
              SupportBlock("free_side", ("θ_y", "θ_z"), np.zeros((2, 3)), 1e12 * np.eye(2)),
              SupportBlock("gear_side", ("u_x",), np.zeros((1, 3)), None)]
    text = _springs(SimpleNamespace(blocks=blocks))
    assert "softest spring: bearing 'gear_side' (1e-09 N/mm)" in text
    assert "stiffest: bearing 'free_side' (2.63e+04 N/mm)" in text   # K11 - K12: eigenvalue
