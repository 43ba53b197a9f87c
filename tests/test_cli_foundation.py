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


def test_balancing_commands_do_not_import_fe_stack():
    """Issue 8 / design card: `shaftfe balance ...` computes only what it reports and never
    imports the FE stack (gmsh, scikit-fem, meshio, pyvista/vtk, scipy.sparse solvers)."""
    code = (
        "import sys, contextlib, io\nfrom shaftfe.cli import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    for argv in (['balance', 'forces', '--engine', 'vm450'],\n"
        "                 ['balance', 'sweep', '--engine', 'vm450', '--x', '31:33:1',"
        " '--x2', '0:100:5'],\n"
        "                 ['balance', 'ratios', '--engine', 'fe570'],\n"
        "                 ['balance', 'twin', '--engine', 'vm450', '--delta', '90']):\n"
        "        assert main(argv) == 0, argv\n"
        "heavy = [m for m in ('gmsh', 'skfem', 'meshio', 'pyvista', 'vtk', 'scipy.sparse') "
        "if m in sys.modules]\n"
        "print('HEAVY', heavy)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "HEAVY []" in out.stdout, out.stdout
