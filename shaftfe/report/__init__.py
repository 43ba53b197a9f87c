"""The assessment report (`shaftfe report`): one run of every analysis of a variant on one mesh
and one model, collected into a frozen ``Report`` and rendered as one self-contained HTML page.

``assemble.run_report(ReportOptions(...), out)`` → ``Report``; ``html.render(report)`` → str;
``write(report, out)`` writes ``summary.json`` and ``index.html`` (atomically, last).
Importing this package loads only the standard library.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["write"]


def write(report, out) -> Path:
    """Write ``summary.json`` and then ``index.html`` into ``out`` (each atomically; the page
    last, so it never points at a half-finished run). Returns the page's path."""
    import json

    from shaftfe.report import html
    from shaftfe.util.atomic import write_atomic

    out = Path(out)
    d = report.to_dict()
    f = report.files
    d["vtu"] = {"file": f["vtu"], "rpm": f["vtu_rpm"], "regions": f["regions"],  # the sidecar
                "modes_file": f.get("modes_vtu"), "modes": f.get("mode_fields", []),  # shaftfe
                "mode_rpm": f.get("mode_rpm"), "mode_note": f.get("mode_note")}     # view reads
    write_atomic(out / "summary.json", json.dumps(d, indent=1, allow_nan=False) + "\n")
    return write_atomic(out / "index.html", html.render(report))
