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
    """``o`` made JSON-safe, recursively: non-finite floats → None (JSON has no inf/nan),
    tuples → lists, keys → str, numpy scalars → float or int, anything else not JSON → str."""
    if isinstance(o, dict):
        return {str(k): json_clean(v) for k, v in o.items()}
    if isinstance(o, list | tuple):
        return [json_clean(v) for v in o]
    if isinstance(o, bool | str) or o is None:
        return o
    if isinstance(o, int):
        return int(o)
    try:
        f = float(o)
    except (TypeError, ValueError):
        return str(o)
    return f if math.isfinite(f) else None
