"""ISO 281 basic rating life of a bearing (the one implementation; the beam and the 3D static
model both report it)."""

from __future__ import annotations

import math


def l10h(C_N: float, P_N: float, rpm: float, p: float = 3.0) -> float:
    """Basic rating life in hours, (C/P)^p · 10⁶ / (60 n); infinite without load or speed.
    ``p``: 3 for ball, 10/3 for roller bearings (``Bearing.life_exponent``)."""
    if P_N <= 0 or rpm <= 0:
        return math.inf
    return (C_N / P_N) ** p * 1e6 / (60.0 * rpm)
