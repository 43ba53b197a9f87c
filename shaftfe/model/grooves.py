"""Circumferential grooves turned into a segment (issue #33): their kinds and the standard's
dimensions by shaft diameter.

A groove is a body of revolution: a flat bottom at ``depth_mm`` below the segment's surface,
``width_mm`` wide at the surface, the two bottom corners rounded with ``radius_mm``. A
``radius_mm`` of half the width is the full round (U) groove; the flanks are planes normal to
the axis.

Kinds (the file-level names are fixed by issue #33 so other tools can write them):

* ``u``: a U (or flat-bottomed) groove; ``width_mm`` and ``depth_mm`` given, ``radius_mm``
  given or the full round min(width / 2, depth).
* ``din471``: the groove of a DIN 471 retaining ring for the segment's diameter d1 (normal
  type): width m (H13) and groove diameter d2 from ``DIN471`` below, depth (d1 − d2)/2; the
  standard leaves the bottom corners' radius to the drawing (it bounds it), so ``radius_mm``
  may be given and is ``DIN471_CORNER_MM`` otherwise.
* ``din509_e``, ``din509_f`` (DIN 509 relief grooves at a shoulder) are named by the file
  format but not built yet: refused with a clear error.
"""

from __future__ import annotations

from types import MappingProxyType

KINDS = ("u", "din471", "din509_e", "din509_f")
BUILT = ("u", "din471")

# DIN 471:2011-04, table 1, normal type: shaft d1 -> (groove diameter d2, groove width m), mm.
# Rows 10…19 read from the table as reprinted by suppliers (capitalbolts.in/din-471, nutbolt.org
# "DIN 471 - External Circlip", 2026-11-27). Rows 20…40 are RECONSTRUCTED: written from the
# standard's widely reprinted series without a reprint at hand this session; each follows the
# series' rules (m = ring thickness s + 0.1; d2 from the rows above continued); re-read them
# against the standard before relying on a groove of those sizes.
DIN471 = MappingProxyType({
    10.0: (9.6, 1.1), 11.0: (10.5, 1.1), 12.0: (11.5, 1.1), 13.0: (12.4, 1.1),
    14.0: (13.4, 1.1), 15.0: (14.3, 1.1), 16.0: (15.2, 1.1), 17.0: (16.2, 1.1),
    18.0: (17.0, 1.3), 19.0: (18.0, 1.3),
    20.0: (19.0, 1.3), 21.0: (20.0, 1.3), 22.0: (21.0, 1.3), 24.0: (22.9, 1.3),
    25.0: (23.9, 1.3), 26.0: (24.9, 1.3), 28.0: (26.6, 1.6), 29.0: (27.6, 1.6),
    30.0: (28.6, 1.6), 32.0: (30.3, 1.6), 34.0: (32.3, 1.6), 35.0: (33.0, 1.6),
    36.0: (34.0, 1.85), 38.0: (36.0, 1.85), 40.0: (37.5, 1.85),
})
DIN471_RECONSTRUCTED_FROM = 20.0      # rows from this d1 on are reconstructed (see above)
# the groove's bottom corner radius when the file gives none: DIN 471 bounds it (r max) and
# leaves it to the drawing; 0.1 mm is the bound of the small sizes, an ASSUMPTION to be
# replaced by the drawing's value (DIN 743-2's ring-groove β depends on it)
DIN471_CORNER_MM = 0.1


def din471(d1_mm: float) -> tuple[float, float] | None:
    """(width m, depth t) of the DIN 471 groove for shaft diameter ``d1_mm``; None for a
    diameter the table does not hold."""
    key = next((d for d in DIN471 if abs(d - float(d1_mm)) <= 1e-6), None)
    if key is None:
        return None
    d2, m = DIN471[key]
    return m, 0.5 * (key - d2)


def full_round(width_mm: float, depth_mm: float) -> float:
    """The radius of a U groove whose bottom is one arc (or whose corners are as round as
    the depth allows)."""
    return min(0.5 * float(width_mm), float(depth_mm))
