"""Kernels of shaftfe.rotordynamics.kernels (model-independent) and the `campbell` / `modal`
commands."""

from __future__ import annotations

import csv
import io
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from shaftfe.cli import main
from shaftfe.rotordynamics import campbell, kernels, plots

ROOT = Path(__file__).resolve().parents[1]


# ----------------------------------------------------------------------------- kernels

def test_whirl_ratio_sign_convention():
    """Circular orbit y = cos ωt, z = sin ωt (from +y towards +z, the spin sense about +x) is
    Y = 1, Z = −i for the e^{iωt} eigenvector: ratio +1 (forward); the mirror orbit −1; a
    straight line 0; an ellipse with axes 1 and 0.5 gives 2·0.5/(1 + 0.25) = 0.8."""
    V = np.array([[1.0, 1.0, 1.0, 1.0], [-1j, 1j, 0.5, -0.5j]])
    r = kernels.whirl_ratio(V, np.array([0]), np.array([1]))
    # exact arithmetic (round-off only, O(1) values): approx's defaults rel 1e-6 / abs 1e-12
    assert r == pytest.approx([1.0, -1.0, 0.0, 0.8])


def test_mac_identity_and_orthogonal_whirls():
    """MAC(a, a) = 1, MAC(a, c·a) = 1 for complex c, forward vs backward circular modes of the
    same shape are MAC-orthogonal (0)."""
    a = np.array([[1.0], [-1j]])
    b = np.array([[1.0], [1j]])
    # exact arithmetic (round-off only: measured ≤ 2.2e-16): approx's default rel 1e-6
    assert kernels.mac(a, a)[0, 0] == pytest.approx(1.0)
    assert kernels.mac(a, (2 - 3j) * a)[0, 0] == pytest.approx(1.0)
    assert kernels.mac(a, b)[0, 0] == pytest.approx(0.0, abs=1e-15)   # exact 0 (measured 0)


def test_critical_speed_interpolation_exact_for_linear_branches():
    """A branch f = 50 + 0.01 n (Hz) crosses the 1× line n/60 where 50 + 0.01 n = n/60, i.e.
    n = 50/(1/60 − 0.01) = 7500 rpm, and the 2× line at 50/(2/60 − 0.01) = 2142.857 rpm; linear
    interpolation is exact for linear data; a flat 1000 Hz branch never crosses."""
    rpm = np.arange(0.0, 10_001.0, 1000.0)
    f = np.column_stack([50 + 0.01 * rpm, np.full_like(rpm, 1000.0)])
    whirl = [("forward", "backward")] * rpm.size
    cs = campbell.critical_speeds(rpm, f, (1.0, 2.0), whirl)
    assert [(c.order, c.branch) for c in cs] == [(2.0, 0), (1.0, 0)]
    # exact arithmetic (round-off only): linear interpolation of linear data
    assert cs[0].rpm == pytest.approx(50 / (2 / 60 - 0.01), rel=1e-12)
    assert cs[1].rpm == pytest.approx(7500.0, rel=1e-12)
    assert cs[1].freq_hz == pytest.approx(125.0, rel=1e-12)
    assert cs[1].whirl == "forward"


def test_two_dof_gyroscopic_closed_form():
    """Two tilt dofs of a rigid disk on an isotropic tilt spring k: Id θ̈ + Ω Ip J θ̇ + k θ = 0
    has ω = (±ΩIp + √((ΩIp)² + 4 Id k)) / (2 Id) (forward +, backward −; e.g. Friswell et al.
    2010 §3.6). Sweep kernel: frequencies, forward/backward labels (pairs (θ_z, −θ_y) as the
    lateral pair) and the basis = full space (2 dofs)."""
    Id, Ip, k = 2.0, 3.0, 5.0e4
    M = np.diag([Id, Id])
    K = np.diag([k, k])
    G = np.array([[0.0, Ip], [-Ip, 0.0]])          # dofs (θ_y, θ_z)
    # lateral pair for whirl: y ~ θ_z, z ~ −θ_y; give the kernel the z sign by a flipped dof
    T = np.diag([-1.0, 1.0])                       # q' = (−θ_y, θ_z)
    lab = kernels.Labelling(groups={"lateral": np.array([0, 1])}, pair_y=np.array([1]),
                            pair_z=np.array([0]))
    res = campbell.sweep(T @ K @ T, T @ M @ T, T @ G @ T, [0.0, 3000.0], 1, lab)
    Om = 3000 * math.pi / 30
    wf = (Om * Ip + math.sqrt((Om * Ip) ** 2 + 4 * Id * k)) / (2 * Id)
    wb = (-Om * Ip + math.sqrt((Om * Ip) ** 2 + 4 * Id * k)) / (2 * Id)
    # 2×2 symmetric pencil: round-off only (measured 9e-16)
    assert res.freq_hz[1, 0] == pytest.approx(wb / (2 * math.pi), rel=1e-12)
    assert res.whirl[1][0] == "backward"
    full = kernels.full_qep(K, M, G, Om, 2)
    # linearised 4×4 eigenproblem, well-separated eigenvalues (condition O(1)): round-off
    # only, measured 4e-16 (was 1e-10)
    assert sorted(full.imag) == pytest.approx(sorted([wf, wb]), rel=1e-12)


def test_forward_is_the_stiffened_branch_in_two_dof_model():
    """Same 2-dof disk: with Ip > 0 the branch whose frequency rises with speed must be labelled
    forward (physical check of the sign conventions of G and the whirl ratio together)."""
    Id, Ip, k = 2.0, 3.0, 5.0e4
    lab = kernels.Labelling(groups={"lateral": np.array([0, 1])}, pair_y=np.array([1]),
                            pair_z=np.array([0]))
    T = np.diag([-1.0, 1.0])
    G = np.array([[0.0, Ip], [-Ip, 0.0]])
    res = campbell.sweep(T @ np.diag([k, k]) @ T, np.diag([Id, Id]), T @ G @ T,
                         [0.0, 2000.0, 4000.0], 1, lab)
    assert res.whirl[1][0] == res.whirl[2][0] == "backward"
    assert res.freq_hz[2, 0] < res.freq_hz[1, 0] < res.freq_hz[0, 0]


def test_sweep_rejects_bad_speeds_and_modes():
    """Validation: negative, non-increasing speeds and too many modes are InputErrors."""
    from shaftfe.errors import InputError

    lab = kernels.Labelling(groups={}, pair_y=np.array([0]), pair_z=np.array([1]))
    K, M, G = np.eye(4), np.eye(4), np.zeros((4, 4))
    for rpms, n in (([-1.0], 1), ([0.0, 0.0], 1), ([0.0], 3), ([float("nan")], 1)):
        with pytest.raises(InputError):
            campbell.sweep(K, M, G, rpms, n, lab)


def test_plot_campbell_png():
    """The plot function returns a PNG (signature bytes) for a sweep with a critical speed."""
    rpm = np.arange(0.0, 10_001.0, 1000.0)
    f = np.column_stack([50 + 0.01 * rpm, np.full_like(rpm, 300.0)])
    wl = tuple(("forward", "torsional") for _ in rpm)
    res = campbell.CampbellResult(
        rpm=rpm, freq_hz=f, zeta=np.zeros_like(f), whirl=wl, family=wl,
        whirl_ratio=np.zeros_like(f), mac_min=np.ones(rpm.size),
        branch_whirl=("forward", "torsional"), orders=(1.0,),
        criticals=tuple(campbell.critical_speeds(rpm, f, (1.0,), wl)), basis_size=2,
        basis_change=0.0, n_rigid=0, n_dof=2)
    assert len(res.criticals) == 1
    png = plots.plot_campbell(res, "t")
    assert png[:8] == b"\x89PNG\r\n\x1a\n"



def _two_branch_result(f, whirl, family, orders=(1.0,)):
    rpm = np.arange(0.0, 1000.0 * f.shape[0], 1000.0)
    return campbell.CampbellResult(
        rpm=rpm, freq_hz=f, zeta=np.zeros_like(f), whirl=whirl, family=family,
        whirl_ratio=np.zeros_like(f), mac_min=np.ones(rpm.size), branch_whirl=whirl[-1],
        orders=orders, criticals=(), basis_size=2, basis_change=0.0, n_rigid=0, n_dof=4)


def test_lowest_frequency_named_at_rest_and_where_it_is_lowest():
    """Issue 30 §3 ("481.1 Hz" on the card vs "477 Hz" in the statement): the statement gives
    the lowest frequency at the first speed and, when a backward branch falls below it, the
    lowest over the sweep with its speed, whirl and mode, both at 4 significant digits."""
    f = np.array([[481.1, 600.0], [479.0, 602.0], [477.0, 604.0]])
    lab = (("lateral", "lateral"),) * 3
    wl = (("undetermined", "undetermined"), ("backward", "forward"), ("backward", "forward"))
    text = _two_branch_result(f, wl, lab).statement()
    assert "lowest natural frequency 481.1 Hz at 0 rpm, 477 Hz at 2000 rpm (backward " \
           "whirl, mode 1)" in text
    flat = _two_branch_result(np.array([[500.0, 600.0], [500.0, 601.0]]), wl[:2], lab[:2])
    assert "lowest natural frequency 500 Hz at 0 rpm;" in flat.statement()


def test_whirl_ratio_only_for_bending_modes():
    """Issue 30 §3: a whirl ratio is shown for lateral (bending) modes only; torsional and
    axial modes show "—" with their kind."""
    assert campbell.whirl_ratio_text(0.98765, "lateral") == "+0.988"
    assert campbell.whirl_ratio_text(0.0, "torsional") == "— (torsional)"
    assert campbell.whirl_ratio_text(-0.3, "axial") == "— (axial)"


def test_one_default_of_the_excitation_orders():
    """Issue 30 §3: the campbell command, the report and the API share one default."""
    import inspect

    from shaftfe.cli import build_parser
    from shaftfe.report.options import ReportOptions
    from shaftfe.rotordynamics import analyse
    from shaftfe.rotordynamics.options import DEFAULT_ORDERS

    args = build_parser().parse_args(["campbell", "0:8000"])
    from shaftfe.commands.campbell import parse_orders
    assert tuple(parse_orders(args.orders)) == DEFAULT_ORDERS
    assert ReportOptions().orders == DEFAULT_ORDERS
    for fn in (analyse.analyse, campbell.sweep):
        assert inspect.signature(fn).parameters["orders"].default == DEFAULT_ORDERS


# ----------------------------------------------------------------------------- CLI

def test_cli_campbell_x2_57_table_files_and_verify(tmp_path, capsys):
    """`shaftfe campbell 0:8000 --orders 1,2 --verify --out DIR`: 9 speeds × 12 modes in the CSV,
    JSON with the no-critical statement, a PNG, and a verify difference < 1e-6."""
    out = tmp_path / "cb"
    assert main(["campbell", "0:8000", "--orders", "1,2", "--verify", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "no critical speed in 0-8000 rpm" in text
    rows = list(csv.DictReader(io.StringIO((out / "campbell.csv").read_text())))
    assert len(rows) == 9 * 12
    assert {r["whirl"] for r in rows} <= set(kernels.WHIRL_LABELS)
    js = json.loads((out / "campbell.json").read_text())
    assert js["result"]["critical_speeds"] == []
    # truncated basis (24 vectors) against the full QEP: measured 7.4e-8, matching the sweep's
    # own basis-×1.5 change (6.1e-8); 1e-6 leaves 13× (was 1e-4)
    assert js["verify"]["max_rel_diff"] < 1e-6
    assert (out / "campbell.png").read_bytes()[:4] == b"\x89PNG"


def test_cli_campbell_step_in_range_and_json(capsys):
    """A step inside RANGE wins over --step; the end point is included even off-grid."""
    assert main(["campbell", "0:2500:1000", "--modes", "4", "--json"]) == 0
    js = json.loads(capsys.readouterr().out)
    assert js["result"]["rpm"] == [0.0, 1000.0, 2000.0, 2500.0]
    assert len(js["result"]["freq_hz"][0]) == 4


def test_cli_modal_harmonic_model_against_the_beam(capsys):
    """`shaftfe modal --model harmonic --coupling distributing --modes 4 --json` (the harmonic
    rotor through the RotorKind protocol): x2_57's four bending modes within 1 % of the beam
    rotor's (Timoshenko + rigid disks, validated against ROSS in test_rotor_beam.py), both
    without seat stiffening; lateral families, 0 rpm."""
    from shaftfe.model.loader import load_variant
    from shaftfe.rotordynamics.analyse import analyse

    assert main(["modal", "--model", "harmonic", "--coupling", "distributing", "--modes", "4",
                 "--json"]) == 0
    js = json.loads(capsys.readouterr().out)
    assert js["model"] == "harmonic" and js["result"]["family"][0] == ["lateral"] * 4
    beam = analyse(load_variant("x2_57"), [0.0], 8, verify=False).result
    lat = [f for f, fam in zip(beam.freq_hz[0], beam.family[0], strict=True)
           if fam == "lateral"][:4]
    # 2D continuum with seat bands against the beam's point disks and 5 mm elements on this
    # stepped shaft: measured +0.25 / +0.40 / −0.52 / −0.79 %; bound 1 %, the solid rotor's
    # bound against the beam (test_rotor_solid.py, two-disk rotor)
    assert np.array(js["result"]["freq_hz"][0]) == pytest.approx(lat, rel=1e-2)


def test_cli_modal_at_rest(capsys):
    """`shaftfe modal --variant x2_57`: 12 modes, families include torsional and axial."""
    assert main(["modal", "--variant", "x2_57", "--json"]) == 0
    js = json.loads(capsys.readouterr().out)
    fam = js["result"]["family"][0]
    assert len(fam) == 12 and "torsional" in fam and "axial" in fam
    assert js["result"]["freq_hz"][0] == sorted(js["result"]["freq_hz"][0])


@pytest.mark.parametrize("argv", [
    ["campbell", "8000:0"],
    ["campbell", "0:8000", "--step", "0"],
    ["campbell", "0:8000", "--orders", "1,-2"],
    ["campbell", "0:8000", "--modes", "0"],
    ["campbell", "0:8000", "--model", "solid", "--level", "bogus"],
    ["modal", "--model", "solid", "--coupling", "glue"],
    ["campbell", "0:1e9", "--step", "1"],
    ["campbell", "0:8000", "--variant", "no_such_variant"],
    ["modal", "--rpm", "-5"],
    ["modal", "--bearing-damping", "-1"],
])
def test_cli_bad_input_one_line_exit_2_no_files(argv, tmp_path):
    """Bad input: exit 2, one line on stderr, no traceback, nothing written."""
    out = tmp_path / "o"
    p = subprocess.run([sys.executable, "-m", "shaftfe", *argv, "--out", str(out)],
                       capture_output=True, text=True, cwd=ROOT)
    assert p.returncode == 2, p.stderr
    assert len(p.stderr.strip().splitlines()) == 1 and "Traceback" not in p.stderr
    assert not out.exists()


def test_command_module_imports_only_stdlib():
    """The command module must not import numpy/scipy/matplotlib at import time."""
    code = ("import sys, shaftfe.commands.campbell; "
            "print(any(m in sys.modules for m in ('numpy', 'scipy', 'matplotlib')))")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert p.stdout.strip() == "False", p.stderr


def test_bearing_damping_forms_and_validation():
    """Bearing damping: one value, one 2×2, or one entry per bearing give the same matrix when
    equivalent; a negative or non-symmetric matrix and a wrong count are InputErrors."""
    from shaftfe.beam.model import build_model
    from shaftfe.errors import InputError
    from shaftfe.model.loader import load_variant
    from shaftfe.rotordynamics import beam_rotor as rotor

    m = build_model(load_variant("x2_57"))
    c1 = rotor.build_rotor(m, bearing_damping=0.5).C
    c2 = rotor.build_rotor(m, bearing_damping=[[0.5, 0.0], [0.0, 0.5]]).C
    c3 = rotor.build_rotor(m, bearing_damping=[0.5, 0.5]).C
    assert np.array_equal(c1, c2) and np.array_equal(c1, c3)
    assert c1.sum() == pytest.approx(4 * 0.5)     # exact (four entries 0.5): default rel 1e-6
    for bad in (-1.0, [[0.5, 0.1], [0.0, 0.5]], [0.5, 0.5, 0.5]):
        with pytest.raises(InputError):
            rotor.build_rotor(m, bearing_damping=bad)
