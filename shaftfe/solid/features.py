"""One typed description of every geometric feature of the shaft (issue #32).

``features(plan)`` turns the solid plan (``solid.plan.Solid``) into a tuple of ``Feature``: what
it is (``kind``), where (its axial extent ``x_mm`` and the segment), its size, whether it is a
body of revolution (``round``: the axisymmetric model holds it exactly) and its zone of
influence (``zone_mm``). The feature's ``region`` is the name of its faces in both meshes (the
3D mesh groups of ``solid.occ`` and the meridian groups of ``axisymmetric.mesh``) and the key
of its peak in every result; consumers choose features by ``kind`` and the flags below, never
by parsing that name. This module is the one place that spells a region or a seat's mesh group
(``fillet_region``, ``seat_group``, ...) and reads one back (``kind_of``, ``region_of``).

Zone of influence (Saint-Venant: a self-equilibrated disturbance of a bar decays over about one
diameter): a cut (keyway, hex socket) or a notch widens its axial extent by the local diameter
on each side; a seat or an end has no zone of its own (its loads are the global model's).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:       # the plan builds its group names from the scheme below
    from shaftfe.solid.plan import Solid

# the kinds, in the order they are listed; NOTCH: the kinds a fatigue check assesses (a stress
# raiser of the outline), CUT: the kinds that are not bodies of revolution, SEAT: the seats
# (a part's, a bearing's), OUTLINE: the faces of the outline that no load band covers
KINDS = ("fillet", "shoulder", "groove", "keyway", "cross_hole", "hex_socket", "seat",
         "bearing_seat", "chamfer", "taper", "end")
NOTCH_KINDS = frozenset({"fillet", "groove", "keyway", "cross_hole"})
CUT_KINDS = frozenset({"keyway", "cross_hole", "hex_socket"})
ROUND_NOTCH_KINDS = NOTCH_KINDS - CUT_KINDS          # the notches a body of revolution holds
SEAT_KINDS = frozenset({"seat", "bearing_seat"})
OUTLINE_KINDS = frozenset(KINDS) - SEAT_KINDS


# --------------------------------------------------------------------------------------
# the naming scheme: the one place that spells a feature's region (its faces' group name in
# both meshes and its peak's key) and a seat's mesh groups, and reads a name back to its kind

HEX_SOCKET = "hex_socket"
END_LEFT, END_RIGHT = "end:left", "end:right"
SEAT_HALVES = ("pressed", "free")      # a split seat's two halves (a load line's side, the other)


def fillet_region(segment: str) -> str:
    return f"fillet:{segment}"


def shoulder_region(segment: str) -> str:
    return f"shoulder:{segment}"


def groove_region(segment: str, index: int) -> str:
    return f"groove:{segment}:{index}"


def chamfer_region(segment: str, side: str) -> str:
    return f"chamfer:{segment}:{side}"


def taper_region(segment: str) -> str:
    """A conical segment's surface."""
    return f"taper:{segment}"


def hole_region(segment: str, index: int) -> str:
    return f"cross_hole:{segment}:{index}"


def keyway_region(segment: str, index: int) -> str:
    return f"keyway:{segment}:{index}"


def part_seat_region(part: str) -> str:
    """The region (peak key, station name) of a part's seat."""
    return f"seat:{part}"


def half_group(seat: str, half: str) -> str:
    """The mesh group of one half (``SEAT_HALVES``) of the split seat whose group is ``seat``."""
    assert half in SEAT_HALVES, half
    return f"{seat}:{half}"


def seat_group(part: str, half: str | None = None) -> str:
    """The mesh group of a part's seat (``half``: one of ``SEAT_HALVES`` of a split seat)."""
    return f"load:{part}" if half is None else half_group(f"load:{part}", half)


def seat_halves(part: str) -> tuple[str, ...]:
    """The mesh groups of the two halves of a part's split seat."""
    return tuple(seat_group(part, h) for h in SEAT_HALVES)


def bearing_group(bearing: str) -> str:
    """The mesh group of a bearing's seat."""
    return f"bearing:{bearing}"


# (prefix, kind): the regions' (the longer prefix first), and the seats' mesh groups'
_REGION_KIND = (("fillet:", "fillet"), ("shoulder:", "shoulder"), ("keyway:", "keyway"),
                ("groove:", "groove"), ("cross_hole:", "cross_hole"), ("chamfer:", "chamfer"),
                ("taper:", "taper"), ("end:", "end"), ("seat:bearing:", "bearing_seat"),
                ("seat:", "seat"))
_GROUP_KIND = (("bearing:", "bearing_seat"), ("load:", "seat"))


def _group_kind(name: str) -> str | None:
    return next((k for p, k in _GROUP_KIND if name.startswith(p)), None)


def kind_of(name: str) -> str | None:
    """The kind (one of ``KINDS``) of a region or a mesh group (a seat's ``load:<part>[:half]``
    or ``bearing:<name>``); None for a name that is no feature's (``axis``, a load band)."""
    if name == HEX_SOCKET:
        return "hex_socket"
    return next((k for p, k in _REGION_KIND if name.startswith(p)), None) or _group_kind(name)


def is_notch(name: str) -> bool:
    """Is the region ``name`` a stress raiser the fatigue methods assess (``NOTCH_KINDS``)?"""
    return kind_of(name) in NOTCH_KINDS


def _owner(name: str) -> str:
    """What a fillet, shoulder, seat group or end is named after: its segment, part, bearing
    or side."""
    return name.split(":")[1]


def seat_region(group: str) -> str:
    """The region (peak key) of a seat's mesh group: a part's seat (either half of a split one)
    ``seat:<part>``, a bearing's ``seat:bearing:<name>``."""
    kind = _group_kind(group)
    if kind == "seat":
        return part_seat_region(_owner(group))
    if kind == "bearing_seat":
        return f"seat:{group}"
    raise ValueError(f"{group!r} is not a seat's mesh group")


def region_of(group: str) -> str:
    """The region a mesh group belongs to: a seat's groups their seat's, every other its own."""
    return seat_region(group) if _group_kind(group) else group


def is_patch(group: str) -> bool:
    """A seat's contact patch: a bearing's seat or the pressed half of a split part seat."""
    kind = _group_kind(group)
    pressed = kind == "seat" and group.endswith(f":{SEAT_HALVES[0]}")
    return kind == "bearing_seat" or pressed


def segment_of(region: str) -> str:
    """The segment of a fillet's or a shoulder's region."""
    assert kind_of(region) in ("fillet", "shoulder"), region
    return _owner(region)


def omitted_entry(f: Feature) -> dict:
    """A cut as ``summary.json`` lists it under ``omitted_features``."""
    return {"feature": f.region, "x_mm": list(f.x_mm), "zone_mm": list(f.zone_mm)}


@dataclass(frozen=True)
class Feature:
    kind: str                          # one of KINDS
    region: str                        # its faces' group name and its peak's key
    segment: str                       # the segment it belongs to ("" for an end)
    x_mm: tuple[float, float]          # axial extent
    zone_mm: tuple[float, float]       # zone of influence (= x_mm where it has none)
    size: tuple[tuple[str, float], ...] = ()   # (name, mm) e.g. ("rho", 0.6), ("width", 5)
    round: bool = True                 # a body of revolution (the axisymmetric model holds it)
    angle_deg: float | None = None     # a cut's direction (0 = +y); a split seat's load line

    @property
    def notch(self) -> bool:
        """A stress raiser that the fatigue methods assess (fillets, grooves, keyways, cross
        holes)."""
        return self.kind in NOTCH_KINDS

    @property
    def cut(self) -> bool:
        """Not a body of revolution: the zoned solve meshes it in a 3D submodel."""
        return not self.round


def _segment_radius(sol: Solid, name: str) -> float:
    return sol.radii[sol.segment_names.index(name)]


def features(sol: Solid) -> tuple[Feature, ...]:
    """Every feature of the plan ``sol``: fillets, shoulder annuli, keyways, the hex socket,
    the seats (parts' and bearings'), and the two ends."""
    out: list[Feature] = []
    for f in sol.fillets:
        xa, xb = (f.x_shoulder - f.rho, f.x_shoulder) if f.side < 0 else \
            (f.x_shoulder, f.x_shoulder + f.rho)
        out.append(Feature("fillet", fillet_region(f.segment), f.segment, (xa, xb), (xa, xb),
                           (("rho", f.rho), ("r_small", f.r_small), ("r_large", f.r_large))))
    for s in sol.shoulders:
        out.append(Feature("shoulder", shoulder_region(s.segment), s.segment, (s.x, s.x),
                           (s.x, s.x), (("r_in", s.r_in), ("r_out", s.r_out))))
    for g in sol.grooves:
        out.append(Feature("groove", groove_region(g.segment, g.index), g.segment,
                           (g.x0, g.x1), (g.x0, g.x1),
                           (("rho", g.rho), ("depth", g.depth), ("width", g.width),
                            ("r", g.r))))
    for t in sol.tapers:
        out.append(Feature("taper", taper_region(t.segment), t.segment, (t.x0, t.x1),
                           (t.x0, t.x1), (("r_left", t.r0), ("r_right", t.r1))))
    for c in sol.chamfers:
        out.append(Feature("chamfer", chamfer_region(c.segment, c.side), c.segment,
                           (c.x0, c.x1), (c.x0, c.x1), (("c", c.c), ("r", c.r))))
    for h in sol.holes:
        d = 2.0 * h.r
        out.append(Feature("cross_hole", hole_region(h.segment, h.index), h.segment,
                           (h.x0, h.x1), (h.x0 - d, h.x1 + d),
                           (("diameter", 2.0 * h.a), ("r", h.r)), round=False,
                           angle_deg=math.degrees(h.angle)))
    for k in sol.slots:
        d = 2.0 * k.r
        out.append(Feature("keyway", keyway_region(k.segment, k.index), k.segment, (k.x0, k.x1),
                           (k.x0 - d, k.x1 + d),
                           (("width", k.width), ("depth", k.depth), ("length", k.length),
                            ("r", k.r)), round=False, angle_deg=math.degrees(k.angle)))
    if sol.hex is not None:
        h = sol.hex
        seg = sol.segment_names[0 if h.end == "left" else -1]
        d = 2.0 * _segment_radius(sol, seg)
        x0, x1 = ((sol.x_left, sol.x_left + h.depth) if h.end == "left"
                  else (sol.x_right - h.depth, sol.x_right))
        out.append(Feature("hex_socket", HEX_SOCKET, seg, (x0, x1), (x0 - d, x1 + d),
                           (("across_flats", h.across_flats), ("depth", h.depth)),
                           round=False))
    seen: set[str] = set()
    for st in sol.seats:
        region = seat_region(st.name)
        if region in seen:
            continue
        seen.add(region)
        out.append(Feature(kind_of(st.name), region, st.part.segment,
                           (st.x0, st.x1), (st.x0, st.x1), (("r", st.part.r),),
                           angle_deg=None if st.angle is None else math.degrees(st.angle)))
    out.append(Feature("end", END_LEFT, sol.segment_names[0], (sol.x_left, sol.x_left),
                       (sol.x_left, sol.x_left)))
    out.append(Feature("end", END_RIGHT, sol.segment_names[-1], (sol.x_right, sol.x_right),
                       (sol.x_right, sol.x_right)))
    return tuple(out)


def cuts(sol: Solid) -> tuple[Feature, ...]:
    """The features that are not bodies of revolution (keyways, the hex socket)."""
    return tuple(f for f in features(sol) if f.cut)


def by_region(feats) -> dict[str, Feature]:
    return {f.region: f for f in feats}
