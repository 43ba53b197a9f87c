"""Foundation: the CLI is a thin, lazy layer."""

import subprocess
import sys


def test_help_does_not_import_fe_stack():
    """`shaftfe --help` must not import gmsh, scikit-fem, pyvista or matplotlib (issue 2)."""
    code = (
        "import sys; from shaftfe.cli import main\n"
        "try:\n    main(['--help'])\nexcept SystemExit:\n    pass\n"
        "heavy = [m for m in ('gmsh', 'skfem', 'pyvista', 'matplotlib', 'meshio', 'vtk') "
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
