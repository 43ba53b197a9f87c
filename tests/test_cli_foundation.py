"""Foundation: the CLI is a thin, lazy layer."""

import subprocess
import sys
from pathlib import Path


def test_help_does_not_import_fe_stack():
    """`shaftfe --help` must not import numpy, scipy, gmsh, scikit-fem, pyvista, matplotlib,
    meshio or vtk (issue 2; issue 14: the lazy public API keeps it so)."""
    code = (
        "import sys; from shaftfe.cli import main\n"
        "try:\n    main(['--help'])\nexcept SystemExit:\n    pass\n"
        "heavy = [m for m in ('numpy', 'scipy', 'gmsh', 'skfem', 'pyvista', 'matplotlib', "
        "'meshio', 'vtk') "
        "if m in sys.modules]\n"
        "print('HEAVY', heavy)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert "HEAVY []" in out.stdout, out.stdout


def test_unknown_command_is_one_line_exit_2():
    out = subprocess.run([sys.executable, "-m", "shaftfe", "nosuchcommand"],
                         capture_output=True, text=True)
    assert out.returncode == 2
    assert "Traceback" not in out.stderr
    assert len(out.stderr.strip().splitlines()) == 1


#: one invocation of every `balance` and `variant` subcommand (no --plot: a plot may import
#: matplotlib, that is the point of asking for it)
LIGHT_COMMANDS = (
    ["balance", "forces", "--engine", "vm450"],
    ["balance", "sweep", "--engine", "vm450", "--x", "31:33:1", "--x2", "0:100:5"],
    ["balance", "ratios", "--engine", "fe570"],
    ["balance", "twin", "--engine", "vm450", "--delta", "90"],
    ["balance", "inline", "--engine", "vm450", "--pins", "0,120,240", "--spacing-mm", "80"],
    ["variant", "list"],
    ["variant", "show", "x2_57"],
    ["variant", "check", "geometry/x2_57.toml"],
    ["variant", "new", "light_probe", "--out", "{tmp}/light_probe.toml"],   # {tmp}: tmp_path
)


def _subcommands(group: str) -> set[str]:
    import argparse

    from shaftfe.cli import build_parser
    top = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    sub = next(a for a in top.choices[group]._actions
               if isinstance(a, argparse._SubParsersAction))
    return set(sub.choices)


def test_light_commands_cover_every_balance_and_variant_subcommand():
    """The import check below runs every subcommand of `balance` and `variant` (a new one must
    be added to LIGHT_COMMANDS)."""
    for group in ("balance", "variant"):
        assert {c[1] for c in LIGHT_COMMANDS if c[0] == group} == _subcommands(group)


def test_balancing_commands_do_not_import_fe_stack(tmp_path):
    """Issue 8 / design card: `shaftfe balance ...` and `shaftfe variant ...` compute only what
    they report and never import the FE stack (gmsh, scikit-fem, meshio, pyvista/vtk,
    scipy.sparse solvers) nor matplotlib."""
    code = (
        "import sys, contextlib, io\nfrom shaftfe.cli import main\n"
        f"cmds = {[[a.replace('{tmp}', str(tmp_path)) for a in c] for c in LIGHT_COMMANDS]!r}\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    for argv in cmds:\n"
        "        assert main(argv) == 0, argv\n"
        "heavy = [m for m in ('gmsh', 'skfem', 'meshio', 'pyvista', 'vtk', 'scipy.sparse', "
        "'matplotlib') if m in sys.modules]\n"
        "print('HEAVY', heavy)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=str(Path(__file__).resolve().parents[1]))
    assert out.returncode == 0, out.stderr
    assert "HEAVY []" in out.stdout, out.stdout
