"""Number formats of the printed results (the CLI and the generated docs share them)."""

from __future__ import annotations

import math


def big(v: float) -> str:
    """Thousands with a space (25 000), small values with 3 significant digits."""
    return f"{v:,.0f}".replace(",", " ") if abs(v) >= 1000 else f"{v:.3g}"


def life(v: float | None) -> str:
    """A life in blocks: 4 significant digits, ``inf`` for none or infinite."""
    return "inf" if v is None or not math.isfinite(v) else f"{v:.4g}"


def json_clean(o):
    """``o`` with every non-finite float replaced by None (JSON has no inf/nan), recursively
    through dicts, lists and tuples (tuples become lists)."""
    if isinstance(o, float):
        return o if math.isfinite(o) else None
    if isinstance(o, dict):
        return {k: json_clean(v) for k, v in o.items()}
    if isinstance(o, list | tuple):
        return [json_clean(v) for v in o]
    return o
