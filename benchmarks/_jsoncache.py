"""A benchmark's JSON cache of its solves, so a run resumes where the last one stopped."""

from __future__ import annotations

import json
from pathlib import Path


def load(path: Path) -> dict:
    """The cache at ``path``, or an empty one ({"points": {}}) if it is missing or unreadable."""
    try:
        return json.loads(Path(path).read_text())
    except (OSError, ValueError):
        return {"points": {}}


def save(path: Path, data: dict) -> None:
    """Write ``data`` to ``path`` whole or not at all (a temporary file, then a rename)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(data, indent=1) + "\n")
    tmp.replace(path)
