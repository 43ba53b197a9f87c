"""Benchmark inputs written as files: x2_57 with extra tables in its segments, for the whole-process
runs of ``shaftfe static`` (a variant file cannot add to an included file's segments)."""

from __future__ import annotations

import shutil
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
COLLAR_END = 'spot (§8.3)."""\n'        # the last line of the collar's segment table


def x2_57_with(where: Path, *, collar: str = "", boss: str = "") -> Path:
    """A copy of geometry/ in ``where`` whose x2_57 has ``collar`` appended to the collar's
    segment table and ``boss`` to the gear hub boss's (sub-tables such as
    ``[[shaft.segments.grooves]]``); the variant file's path."""
    g = where / "geometry"
    shutil.copytree(ROOT / "geometry", g)
    p = g / "common" / "shaft_c.toml"
    s = p.read_text(encoding="utf-8")
    assert s.count(COLLAR_END) == 1
    s = s.replace(COLLAR_END, COLLAR_END + collar)
    i = s.index('name = "gear_hub_boss"')
    j = s.index("[[shaft.segments]]", i)
    p.write_text(s[:j] + boss + s[j:], encoding="utf-8")
    return g / "x2_57.toml"


def write_report(out: Path, lines: list[str], data=None) -> None:
    """``out``.md from ``lines`` (printed too) and, with ``data``, ``out``.json."""
    import json
    if data is not None:
        out.with_suffix(".json").write_text(json.dumps(data, indent=1) + "\n",
                                            encoding="utf-8")
    out.with_suffix(".md").write_text("\n".join(lines) + "\n", encoding="utf-8")
    print("\n".join(lines))


def write_kt_table(path: Path, rows: list[dict], fields: tuple[str, ...], source: str,
                   name: str) -> None:
    """A converged Kt table (``beam.scf.converged_kt`` reads it) at ``path``: one entry per
    geometry (the values of ``fields``) with its loads' {"kt", "bar"}, under ``name``."""
    import json
    table: dict = {}
    for r in rows:
        key = tuple(r[k] for k in fields)
        table.setdefault(key, {k: r[k] for k in fields})
        table[key][r["load"]] = {"kt": r["kt"], "bar": r["bar"]}
    path.write_text(json.dumps({"source": source, name: list(table.values())}, indent=1)
                    + "\n", encoding="utf-8")
