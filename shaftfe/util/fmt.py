"""Number formats of the printed results (the CLI and the generated docs share them)."""

from __future__ import annotations

import math


def big(v: float) -> str:
    """Thousands with a space (25 000), small values with 3 significant digits."""
    return f"{v:,.0f}".replace(",", " ") if abs(v) >= 1000 else f"{v:.3g}"


# A life (in blocks of the history, in hours or in km) above LIFE_MAX is not a number anyone
# can use: 1e9 h is 114 000 years, 1e9 blocks are 1e9 or more load cycles, past the end of every
# S-N data set (and a life below a cutoff endurance limit is already infinite), 1e9 km are
# 25 000 times round the earth. It is printed
# as NO_FINITE_LIFE; summary.json keeps the number (or null when infinite) with a reason
# (``life_reason``).
LIFE_MAX = 1e9
NO_FINITE_LIFE = "no finite life at this load"


def life_reason(*lives: float | None) -> str | None:
    """Why the lives (blocks, hours, km) are "no finite life at this load", or None."""
    if any(v is None or not math.isfinite(v) for v in lives):
        return "infinite: no damaging cycle"
    if any(v > LIFE_MAX for v in lives):
        return "more than 1e9 blocks, hours or km"
    return None


def life(v: float | None) -> str:
    """A life in blocks or hours for a table: 4 significant digits; infinite or above
    ``LIFE_MAX``: ``NO_FINITE_LIFE``."""
    return NO_FINITE_LIFE if life_reason(v) else f"{v:.4g}"


def lives(blocks: float | None, hours: float | None, km: float | None = None,
          speed_kmh: float | None = None) -> str:
    """'25 000 blocks = 2083 h = 145 810 km at 70 km/h', or ``NO_FINITE_LIFE`` when the
    blocks, the hours or the km are infinite or above ``LIFE_MAX``."""
    why = life_reason(blocks, hours, *(() if km is None else (km,)))
    if why:
        return f"{NO_FINITE_LIFE} ({why})"
    out = f"{big(blocks)} blocks = {big(hours)} h"
    if km is not None and speed_kmh is not None:
        out += f" = {big(km)} km at {speed_kmh:g} km/h"
    return out


def life_h_km(hours: float | None, km: float | None, speed_kmh: float) -> str:
    """A life in hours and km (a bearing's): '1 251 h = 87 570 km at 70 km/h', or
    ``NO_FINITE_LIFE`` when either is infinite or above ``LIFE_MAX``."""
    if life_reason(hours, km):
        return NO_FINITE_LIFE
    return f"{big(hours)} h = {big(km)} km at {speed_kmh:g} km/h"


def design_life(blocks: float, block_seconds: float, speed_kmh: float) -> str:
    """'1e+07 blocks (= 833 333 h = 58 333 333 km)': a design life in every unit."""
    h = blocks * block_seconds / 3600.0
    return f"{blocks:g} blocks (= {big(h)} h = {big(h * speed_kmh)} km)"


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


def table_lines(headers: list[str], rows: list[list[object]],
                title: str | None = None) -> list[str]:
    """A plain fixed-width table for terminals, as lines (title, header, rule, rows)."""
    # a round-off residue (6.9e-13) beside numbers of order 1e3 reads as 0 in its column
    big = [max((abs(r[i]) for r in rows if isinstance(r[i], float) and math.isfinite(r[i])),
               default=0.0) for i in range(len(headers))]
    cells = [[str(h) for h in headers]] + [
        [_cell(0.0 if isinstance(c, float) and c != 0 and abs(c) < 1e-9 * big[i] else c)
         for i, c in enumerate(r)] for r in rows]
    widths = [max(len(r[i]) for r in cells) for i in range(len(headers))]
    out = [title] if title else []
    for k, row in enumerate(cells):
        out.append("  ".join(c.rjust(w) for c, w in zip(row, widths, strict=True)))
        if k == 0:
            out.append("  ".join("-" * w for w in widths))
    return out


def _cell(v: object) -> str:
    if isinstance(v, float):
        if v != 0 and abs(v) < 1:
            return f"{v:.4g}"       # small values keep 4 significant digits (0.06712 mm)
        return f"{v:,.2f}".replace(",", " ")
    return str(v)
