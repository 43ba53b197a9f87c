"""`shaftfe demo` (what `make demo` runs) is the assessment report of the default variant.

The report itself is run and checked in tests/test_report.py (coarse mesh); here only the
wiring: the demo asks for the report of x2_57 on the bundled data, with the level and output
folder given, and `make demo` runs it.
"""

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_demo_runs_the_report_of_the_default_variant(monkeypatch, tmp_path):
    from shaftfe.cli import main
    from shaftfe.commands import report
    from shaftfe.util.paths import DEFAULT_SPECTRUM

    calls = []
    monkeypatch.setattr(report, "make_report",
                        lambda options, out=None, **kw: calls.append((options, out, kw)) or 0)
    assert main(["demo", "--out", str(tmp_path), "--level", "coarse"]) == 0
    (options, out, kw), = calls
    assert options.variant == "x2_57" and options.level == "coarse"
    assert options.seed_load_case is True          # the seed study: compared like with like
    assert Path(options.spectrum) == DEFAULT_SPECTRUM and DEFAULT_SPECTRUM.is_file()
    assert options.design_rpm == (10_000.0, 7_000.0)      # seed §8.2.2 static check, §8.3 ref
    assert Path(out) == tmp_path and kw == {"json_out": False}


def test_demo_defaults_and_make_target():
    from shaftfe.cli import build_parser

    args = build_parser().parse_args(["demo"])
    assert args.out == "reports/x2_57" and args.level == "default"
    make = (ROOT / "Makefile").read_text()
    demo = make.split("\ndemo:", 1)[1].split("\n\n", 1)[0]
    assert "shaftfe demo" in demo and "index.html" in demo
