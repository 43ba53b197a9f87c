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
* ``din509_e``, ``din509_f``: a DIN 509 undercut (relief groove) at a shoulder, in the smaller
  segment's cylinder next to the larger one's face (``side``: the segment's end at the step
  up). Radius r, depth t1, width f and (form F) the face recess t2 come from ``DIN509`` by the
  segment's diameter; ``radius_mm`` picks another row the table holds for that diameter.
  The undercut is the shoulder's transition: that shoulder's ``fillet_mm`` is 0. Its outline
  (``solid.plan``; GEOMETRY AS INTERPRETED, see ``DIN509_RAMP_DEG``): from the face plane, the
  corner arc r down to the flat bottom at depth t1, the bottom, then a 15° run-out ramp up to
  the cylinder at f from the face; form F also cuts t2 into the face, its wall at 8° to it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import MappingProxyType

from shaftfe.model.variant import Groove

KINDS = ("u", "din471", "din509_e", "din509_f")
BUILT = ("u", "din471", "din509_e", "din509_f")
UNDERCUTS = ("din509_e", "din509_f")     # at a shoulder, not on a straight part

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


# DIN 509:1998-06 table "Maße für Freistiche", forms E and F (r, t1, f, t2 and the diameter
# range (over d_lo, up to d_hi] of the cylinder d1 they are assigned to, for usual loading or
# for increased fatigue strength), as read from the table's public excerpt (de.scribd.com
# document 415623829, "DIN 509: Freistiche (Auszug) (Juni 1998)", 2026-11-28; its layout is
# garbled in places: the R0.8 row's f and t2 are taken from the merged cells of the R0.6 × 0.3
# row above it). The default row per diameter (``DIN509_DEFAULT``) is the one the HEIDENHAIN
# CNC PILOT 4290 control's undercut cycle takes (operation manual p. 686, "Undercut DIN 509 E /
# F, parameters": depth I, width K, radius R, 15° angle W; form F: face depth P at 8°), which
# agrees with these rows for d1 over 10 mm. Forms G and H are not built.
DIN509 = (
    # r,   t1,  f,   t2,  d_lo,  d_hi,  duty
    (0.2, 0.1, 1.0, 0.1, 1.6, 3.0, "usual"),
    (0.4, 0.2, 2.0, 0.1, 3.0, 18.0, "usual"),
    (0.6, 0.2, 2.0, 0.1, 10.0, 18.0, "usual"),
    (0.6, 0.3, 2.5, 0.2, 18.0, 80.0, "usual"),
    (0.8, 0.3, 2.5, 0.2, 18.0, 80.0, "usual"),
    (1.0, 0.2, 2.5, 0.1, 18.0, 50.0, "fatigue"),
    (1.0, 0.4, 4.0, 0.3, 80.0, math.inf, "usual"),
    (1.2, 0.2, 2.5, 0.1, 18.0, 50.0, "fatigue"),
    (1.2, 0.4, 4.0, 0.3, 80.0, math.inf, "usual"),
    (1.6, 0.3, 4.0, 0.2, 50.0, 80.0, "fatigue"),
    (2.5, 0.4, 5.0, 0.3, 80.0, 125.0, "fatigue"),
    (4.0, 0.5, 7.0, 0.3, 125.0, math.inf, "fatigue"),
)
# the default radius by diameter range (the CNC cycle's choice, above): (d_lo, d_hi] -> r
DIN509_DEFAULT = ((1.6, 3.0, 0.2), (3.0, 10.0, 0.4), (10.0, 18.0, 0.6), (18.0, 80.0, 0.6),
                  (80.0, math.inf, 1.0))
# The outline's angles. INTERPRETED: the standard's figure is not at hand; the run-out ramp of
# the undercut's bottom to the cylinder is at 15° to the axis and form F's face wall at 8° to
# the face, as the CNC cycle's parameters W and A say. f is measured on the cylinder from the
# face plane to the ramp's end, t1 from the cylinder to the flat bottom, t2 into the face at
# the bottom's level; the corner arc r joins the face (form E) or the wall (form F) to the
# bottom, tangent to both.
DIN509_RAMP_DEG = 15.0
DIN509_FACE_DEG = 8.0


@dataclass(frozen=True)
class Undercut:
    """One DIN 509 row: radius r, depth t1, width f, face recess t2 (form F), mm."""
    r: float
    t1: float
    f: float
    t2: float


def din509_rows(d1_mm: float) -> tuple[Undercut, ...]:
    """The rows DIN 509 assigns to a cylinder of diameter ``d1_mm`` (usual loading and
    increased fatigue strength)."""
    d = float(d1_mm)
    return tuple(Undercut(r, t1, f, t2) for r, t1, f, t2, lo, hi, _ in DIN509
                 if lo < d <= hi)


def din509(d1_mm: float, radius_mm: float | None = None) -> Undercut | None:
    """The DIN 509 undercut of a cylinder of diameter ``d1_mm``: the default row, or the row of
    radius ``radius_mm``; None where the table holds none."""
    d = float(d1_mm)
    if radius_mm is None:
        radius_mm = next((r for lo, hi, r in DIN509_DEFAULT if lo < d <= hi), None)
        if radius_mm is None:
            return None
    return next((u for u in din509_rows(d) if abs(u.r - float(radius_mm)) <= 1e-9), None)


def undercut_at(segments, i: int):
    """The DIN 509 undercut at the shoulder between ``segments[i]`` and ``segments[i + 1]``:
    (index of its segment, index of the groove, the ``model.variant.Groove``), or None."""
    for k, side in ((i, "right"), (i + 1, "left")):
        for j, g in enumerate(segments[k].grooves):
            if g.kind in UNDERCUTS and g.side == side:
                return k, j, g
    return None


def din509_groove(kind: str, d_mm: float, side: str, ends: tuple[float, float],
                  radius_mm: float | None = None):
    """The ``model.variant.Groove`` of the DIN 509 undercut ``kind`` of radius ``radius_mm``
    (None: the default row) on a cylinder of diameter ``d_mm`` spanning ``ends`` (x), at its
    ``side`` end: its centre the middle of its opening f; None where the table holds no such
    row. What the loader builds and ``model.validate`` holds a Variant's undercuts to."""
    u = din509(d_mm, radius_mm)
    if u is None:
        return None
    xc = ends[1] - 0.5 * u.f if side == "right" else ends[0] + 0.5 * u.f
    return Groove(kind, xc, u.f, u.t1, u.r, side=side,
                  face_depth_mm=u.t2 if kind == "din509_f" else 0.0)
