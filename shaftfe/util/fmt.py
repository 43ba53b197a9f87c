"""Number formats of the printed results (the CLI and the generated docs share them)."""

from __future__ import annotations

import math


def big(v: float) -> str:
    """Thousands with a space (25 000), small values with 3 significant digits."""
    return f"{v:,.0f}".replace(",", " ") if abs(v) >= 1000 else f"{v:.3g}"


def life(v: float | None) -> str:
    """A life in blocks: 4 significant digits, ``inf`` for none or infinite."""
    return "inf" if v is None or not math.isfinite(v) else f"{v:.4g}"
