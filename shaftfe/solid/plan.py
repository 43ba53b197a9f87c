"""The shaft solid's plan: validated geometry, no Gmsh involved.

``prepare(variant)`` checks a ``Variant`` and turns it into a ``Solid`` plan (profile, fillets,
cylindrical parts, face-group intervals), so a bad variant fails with ``InputError`` before Gmsh
is ever imported. ``shaftfe.solid.exact`` gives the plan's exact volume and face areas;
``shaftfe.solid.occ`` builds it in Gmsh: ``build_occ(gmsh, solid)`` builds the solid of
revolution (profile with fillet arcs revolved about x), cuts keyway seats and the hex socket, and
imprints the two generator lines of every attachment's load plane on its seat cylinder (an OCC
fragment with line segments), so the pressed / free halves are exact faces and no cut runs
through the interior.

Conventions: x = shaft axis (mm); angles in the y–z plane, 0° = +y, 90° = +z. A keyway's
``angle_deg`` is the direction of its open side. The seat of an attachment is the cylindrical
part of one segment inside [start, end] (fillet arcs excluded). The seat of a bearing is the
inner ring's contact band [x_start + c, x_end − c], c = ``Bearing.chamfer_mm`` (the chamfered
ring corners do not bear); with c > 0 the band must lie on straight seat (InputError if it reaches
into a fillet), so the coupling edge never sits in a fillet.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from shaftfe.errors import InputError
from shaftfe.model.grooves import (
    DIN471_RECONSTRUCTED_FROM,
    DIN509_FACE_DEG,
    DIN509_RAMP_DEG,
    UNDERCUTS,
    undercut_at,
)
from shaftfe.model.validate import source_of, validate_variant
from shaftfe.solid.features import (
    END_LEFT,
    END_RIGHT,
    HEX_SOCKET,
    SEAT_HALVES,
    bearing_group,
    chamfer_region,
    fillet_region,
    groove_region,
    half_group,
    hole_region,
    keyway_region,
    seat_group,
    shoulder_region,
    taper_region,
)
from shaftfe.util.notices import warn

TOL = 1e-6          # mm, geometric tolerance for coincident x-stations
SQRT3 = math.sqrt(3.0)


@dataclass(frozen=True)
class Fillet:
    segment: str        # the segment whose right shoulder carries it
    x_shoulder: float   # x of the shoulder plane
    r_small: float      # radius of the smaller segment
    r_large: float
    rho: float
    side: int           # -1: smaller segment on the left (step up), +1: on the right


@dataclass(frozen=True)
class Shoulder:
    segment: str
    x: float
    r_in: float         # inner radius of the annulus (r_small + rho)
    r_out: float


@dataclass(frozen=True)
class CylPart:
    """The cylindrical (fillet-free) part of a segment's surface."""
    segment: str
    index: int
    x0: float
    x1: float
    r: float


@dataclass(frozen=True)
class Slot:
    """A keyway seat (stadium planform, flat bottom at depth ``depth`` below the surface),
    its bottom edges rounded with radius ``rho`` (DIN 6885-1's r1; 0: sharp)."""
    segment: str
    index: int
    r: float
    width: float
    depth: float
    length: float
    x_center: float
    angle: float        # rad
    rho: float = 0.0

    @property
    def x0(self) -> float:
        return self.x_center - 0.5 * self.length

    @property
    def perimeter(self) -> float:
        """The stadium's perimeter: the two straight sides and the two half circles."""
        return 2.0 * (self.length - self.width) + math.pi * self.width

    @property
    def x1(self) -> float:
        return self.x_center + 0.5 * self.length


@dataclass(frozen=True)
class Groove:
    """A circumferential groove (``model.variant.Groove``) on the straight part of segment
    ``segment`` of radius ``r``: flanks at x0 and x1, a flat bottom at r − depth, bottom
    corners of radius ``rho`` (ρ = width/2: one arc, a U groove).

    A DIN 509 undercut (``side`` "left" | "right": the segment's end at the shoulder) spans
    [x0, x1] = its opening f on the cylinder and, form F, its recess ``t2`` into the face
    (``_undercut_profile``)."""
    segment: str
    index: int
    kind: str
    r: float
    x0: float
    x1: float
    depth: float
    rho: float
    side: str = ""
    t2: float = 0.0

    @property
    def width(self) -> float:
        return self.x1 - self.x0

    @property
    def r_bottom(self) -> float:
        return self.r - self.depth

    @property
    def undercut(self) -> bool:
        return self.kind in UNDERCUTS

    @property
    def x_face(self) -> float:
        """An undercut's shoulder plane (the larger segment's face)."""
        return self.x1 - self.t2 if self.side == "right" else self.x0 + self.t2

    @property
    def r_top(self) -> float:
        """The outline's highest point: a groove's surface; an undercut's top on the face,
        where the shoulder's flat annulus begins (form E: the corner arc's end, form F: the
        8° wall's)."""
        if not self.undercut:
            return self.r
        return self.r_bottom + self.rho + self.t2 / math.tan(math.radians(DIN509_FACE_DEG))


@dataclass(frozen=True)
class Hole:
    """A transverse hole (``model.variant.CrossHole``) through segment ``segment`` of radius
    ``r``: radius ``a``, its axis through (x_center, 0, 0) along (0, cos angle, sin angle)."""
    segment: str
    index: int
    r: float
    a: float
    x_center: float
    angle: float        # rad

    @property
    def x0(self) -> float:
        return self.x_center - self.a

    @property
    def x1(self) -> float:
        return self.x_center + self.a


@dataclass(frozen=True)
class Chamfer:
    """A 45° chamfer ``c`` on the outer edge of segment ``segment`` (radius ``r``) at its
    ``side`` end: the cone from (x_edge, r − c) to (x_edge ∓ c, r)."""
    segment: str
    side: str           # "left" | "right"
    r: float
    c: float
    x_edge: float       # the segment's end the chamfer breaks

    @property
    def x0(self) -> float:
        return self.x_edge if self.side == "left" else self.x_edge - self.c

    @property
    def x1(self) -> float:
        return self.x_edge + self.c if self.side == "left" else self.x_edge


@dataclass(frozen=True)
class Taper:
    """A conical segment: its surface from (x0, r0) to (x1, r1), a plain transition (nothing
    cut into it, no seat on it: ``model.validate``)."""
    segment: str
    x0: float
    x1: float
    r0: float
    r1: float


@dataclass(frozen=True)
class Seat:
    """A named cylindrical face group on [x0, x1] of segment ``part``; ``angle`` is the force
    direction (rad) for a split seat, None for an unsplit one (bearing)."""
    name: str
    part: CylPart
    x0: float
    x1: float
    angle: float | None
    loaded: bool = True     # False: a part without centrifugal force (m e = 0, a nut on a thread)


@dataclass(frozen=True)
class Hex:
    end: str
    across_flats: float
    depth: float

    @property
    def circumradius(self) -> float:
        return self.across_flats / SQRT3

    @property
    def area(self) -> float:
        return 0.5 * SQRT3 * self.across_flats ** 2


@dataclass(frozen=True)
class Solid:
    name: str
    length: float
    x_left: float
    x_right: float
    radii: tuple[float, ...]
    segment_names: tuple[str, ...]
    segment_x: tuple[tuple[float, float], ...]
    fillets: tuple[Fillet, ...]
    shoulders: tuple[Shoulder, ...]
    parts: tuple[CylPart, ...]
    slots: tuple[Slot, ...]
    seats: tuple[Seat, ...]
    hex: Hex | None
    profile_x: tuple[float, ...]   # extra x-stations (seat interval ends) on the profile
    # per span fillet (segment name) and groove (its region): the angle (deg, 0 = +y, in
    # [0, 180), 0.1° steps) of the line along which its bending stress peaks, or None (the
    # whole ring); set by
    # ``shaftfe.solid.mesh.build_mesh`` (part of the mesh key), () in a bare plan
    hot_axes_deg: tuple[tuple[str, float | None], ...] = ()
    grooves: tuple[Groove, ...] = ()
    holes: tuple[Hole, ...] = ()
    # a clipped plan's (a 3D zone's): the x-range of the WHOLE shaft's loaded seats, so a
    # fillet inside the zone is an end fillet only if it is one of the whole shaft
    # (``solid.mesh.end_fillet``); None: the plan's own seats
    seat_span: tuple[float, float] | None = None
    clipped: bool = False        # a 3D zone's plan (``clip``): its grooves are meshed coarsely
    chamfers: tuple[Chamfer, ...] = ()
    tapers: tuple[Taper, ...] = ()

    def r_right(self, i: int) -> float:
        """Segment ``i``'s radius at its right end (``radii`` holds the left ends')."""
        t = next((t for t in self.tapers if t.segment == self.segment_names[i]), None)
        return self.radii[i] if t is None else t.r1

    def chamfer(self, segment: str, side: str) -> float:
        """The chamfer (mm) of ``segment``'s ``side`` edge, 0 without one."""
        return next((c.c for c in self.chamfers if c.segment == segment and c.side == side),
                    0.0)

    @property
    def r_max(self) -> float:
        return max(self.radii + tuple(t.r1 for t in self.tapers))

    @property
    def r_min(self) -> float:
        return min(self.radii + tuple(t.r1 for t in self.tapers))

    def groups(self) -> tuple[str, ...]:
        names: list[str] = []
        for s in self.seats:
            if s.angle is None:
                names.append(s.name)
            else:
                names += [half_group(s.name, half) for half in SEAT_HALVES]
        names += [fillet_region(f.segment) for f in self.fillets]
        names += [shoulder_region(s.segment) for s in self.shoulders]
        names += [keyway_region(k.segment, k.index) for k in self.slots]
        names += [groove_region(g.segment, g.index) for g in self.grooves]
        names += [hole_region(h.segment, h.index) for h in self.holes]
        names += [chamfer_region(c.segment, c.side) for c in self.chamfers]
        names += [taper_region(t.segment) for t in self.tapers]
        names += [END_LEFT, END_RIGHT]
        if self.hex is not None:
            names.append(HEX_SOCKET)
        return tuple(names)


# --------------------------------------------------------------------------------------
# validation


def _stations(segs) -> tuple[list[float], list[tuple[float, float]]]:
    """Radii and [x0, x1] of the (validated, contiguous) segments."""
    xs: list[tuple[float, float]] = []
    for s in segs:
        x0 = xs[-1][1] if xs else float(s.x_start_mm)
        xs.append((x0, x0 + float(s.length_mm)))
    return [0.5 * float(s.diameter_mm) for s in segs], xs


def _undercuts(segs, radii, xs) -> list[Groove]:
    """The DIN 509 undercuts (``model.grooves``; their rules: ``model.validate``)."""
    out = []
    for i, s in enumerate(segs):
        for j, g in enumerate(s.grooves):
            if g.kind not in UNDERCUTS:
                continue
            t2 = float(g.face_depth_mm)
            x0, x1 = ((xs[i][1] - g.width_mm, xs[i][1] + t2) if g.side == "right"
                      else (xs[i][0] - t2, xs[i][0] + g.width_mm))
            out.append(Groove(s.name, j, g.kind, radii[i], x0, x1, float(g.depth_mm),
                              float(g.radius_mm), g.side, t2))
    return out


def _fillets(segs, radii, xs, src: str, undercuts=()):
    """Fillets, shoulder annuli, chamfers and the straight (fillet- and chamfer-free) part of
    every segment; a DIN 509 undercut is its shoulder's transition (``undercuts``)."""
    n = len(segs)
    cut_at = {round(u.x_face, 9): u for u in undercuts}
    cham = {(i, side): float(getattr(s, f"chamfer_{side}_mm", 0.0) or 0.0)
            for i, s in enumerate(segs) for side in ("left", "right")}
    fillets: list[Fillet] = []
    shoulders: list[Shoulder] = []
    eat_left = [0.0] * n
    eat_right = [0.0] * n
    for i in range(n - 1):
        s = segs[i]
        r0, r1 = 0.5 * float(s.d_right_mm), radii[i + 1]
        rho = float(s.fillet_mm)
        if abs(r0 - r1) <= TOL:
            if rho > 0:
                raise InputError(src, f"segments[{i}].fillet_mm", "0 where the next segment has "
                                 "the same diameter (no shoulder)", got=s.fillet_mm)
            continue
        step = abs(r0 - r1)
        if rho > step + TOL:
            raise InputError(src, f"segments[{i}].fillet_mm",
                             f"<= the shoulder height {step:g} mm", got=s.fillet_mm,
                             reason="is larger than the step")
        rho = min(rho, step)
        xe = xs[i][1]
        u = cut_at.get(round(xe, 9))
        # what the transition takes of the smaller segment, and where the face's flat begins
        eat, top = (u.x1 - u.x0 - u.t2, u.r_top) if u is not None else (rho, None)
        if r0 < r1:
            side, small, large = -1, r0, r1
            eat_right[i] = eat
        else:
            side, small, large = +1, r1, r0
            eat_left[i + 1] = eat
        if u is not None and top >= large - TOL:
            j = next(k for k in (i, i + 1) if segs[k].name == u.segment)
            raise InputError(src, f"segments[{j}].grooves[{u.index}].kind", "an undercut "
                             f"whose face top (Ø{2 * top:g}, {u.kind}) stays below the step "
                             f"to Ø{2 * large:g} (form E is lower than form F)", got=u.kind)
        top = small + rho if top is None else top
        if rho > 0:
            fillets.append(Fillet(s.name, xe, small, large, rho, side))
        # the larger segment's chamfer on this shoulder's outer edge
        ci, cside = (i + 1, "left") if side < 0 else (i, "right")
        c = cham[(ci, cside)]
        if c > 0 and c >= large - top - TOL:
            raise InputError(src, f"segments[{ci}].chamfer_{cside}_mm", f"< the shoulder's "
                             f"flat height {large - top:g} mm (the step less the "
                             f"{'undercut' if u is not None else 'fillet'})", got=c)
        if large - c - top > TOL:      # else a full-height fillet: no flat annulus
            shoulders.append(Shoulder(s.name, xe, top, large - c))
    for side, i in (("left", 0), ("right", n - 1)):      # the shaft's ends
        c = cham[(i, side)]
        if c >= 0.5 * radii[i]:           # (no chamfer on a cone: its radii[i] is the end's)
            raise InputError(src, f"segments[{i}].chamfer_{side}_mm", f"< half the radius "
                             f"({0.5 * radii[i]:g} mm)", got=c)
    parts: list[CylPart] = []
    chamfers: list[Chamfer] = []
    for i, s in enumerate(segs):
        cl, cr = cham[(i, "left")], cham[(i, "right")]
        a, b = xs[i][0] + eat_left[i] + cl, xs[i][1] - eat_right[i] - cr
        if b - a <= TOL:
            what = "fillets, undercuts and chamfers" if cl or cr else "fillets and undercuts"
            raise InputError(src, f"segments[{i}].length_mm", f"> the {what} it carries "
                             f"({eat_left[i] + eat_right[i] + cl + cr:g} mm)",
                             got=s.length_mm,
                             reason="leaves no straight part (a chamfer longer than the "
                             "segment?)" if cl or cr else "")
        parts.append(CylPart(s.name, i, a, b, radii[i]))
        chamfers += [Chamfer(s.name, "left", radii[i], cl, xs[i][0])] if cl > 0 else []
        chamfers += [Chamfer(s.name, "right", radii[i], cr, xs[i][1])] if cr > 0 else []
    return fillets, shoulders, parts, chamfers


def _slots(segs, radii, parts, src: str) -> list[Slot]:
    """Keyway seats, each inside the straight part of its segment with 0.5 mm to spare."""
    slots: list[Slot] = []
    for i, s in enumerate(segs):
        for j, k in enumerate(s.keyways):
            xc, ln, p = float(k.x_center_mm), float(k.length_mm), parts[i]
            if xc - 0.5 * ln < p.x0 + 0.5 or xc + 0.5 * ln > p.x1 - 0.5:
                raise InputError(src, f"segments[{i}].keyways[{j}].x_center_mm", "slot inside "
                                 "the cylindrical part of its segment with 0.5 mm to spare "
                                 f"([{p.x0:g}, {p.x1:g}])", got=k.x_center_mm)
            slots.append(Slot(s.name, j, radii[i], float(k.width_mm), float(k.depth_mm), ln,
                              xc, math.radians(float(k.angle_deg)),
                              float(k.bottom_radius_mm)))
    return slots


def _place(src: str, fld: str, noun: str, got, x0: float, x1: float, part: CylPart,
           others) -> None:
    """A notch on [x0, x1]: on the straight part ``part`` of its segment with 0.5 mm to spare
    (its flank never meets a fillet, a chamfer or a shoulder), and clear of each of ``others``
    ((label, a, b, gap mm)) by its gap."""
    if x0 < part.x0 + 0.5 or x1 > part.x1 - 0.5:
        raise InputError(src, fld, f"{noun} on the cylindrical part of its segment with 0.5 mm "
                         f"to spare ([{part.x0:g}, {part.x1:g}])", got=got)
    for label, a, b, gap in others:
        if a < x1 + gap and x0 < b + gap:
            by = f" by {gap:g} mm" if gap > TOL else ""
            raise InputError(src, fld, f"clear of {label} [{a:g}, {b:g}]{by}", got=got,
                             reason="overlaps another notch")


def _grooves(segs, radii, parts, slots, src: str) -> list[Groove]:
    """Grooves (``_place``), clear of the keyways and by 0.5 mm of one another."""
    out: list[Groove] = []
    for i, s in enumerate(segs):
        for j, g in enumerate(s.grooves):
            if g.kind in UNDERCUTS:          # at a shoulder: ``_undercuts``
                continue
            x0, x1 = g.x_center_mm - 0.5 * g.width_mm, g.x_center_mm + 0.5 * g.width_mm
            others = [(f"keyway {k.segment}:{k.index}", k.x0, k.x1, TOL) for k in slots
                      if k.segment == s.name]
            others += [(f"groove {o.segment}:{o.index}", o.x0, o.x1, 0.5) for o in out]
            _place(src, f"segments[{i}].grooves[{j}].x_center_mm", "groove", g.x_center_mm,
                   x0, x1, parts[i], others)
            if g.kind == "din471" and s.diameter_mm >= DIN471_RECONSTRUCTED_FROM:
                warn("din471-reconstructed", f"segments[{i}].grooves[{j}]",
                     f"DIN 471's groove for Ø{s.diameter_mm:g} comes from the table rows from "
                     f"{DIN471_RECONSTRUCTED_FROM:g} mm on, which were reconstructed "
                     "(model/grooves.py): give width_mm, depth_mm from the standard as a "
                     "u groove to be sure")
            out.append(Groove(s.name, j, g.kind, radii[i], x0, x1, float(g.depth_mm),
                              float(g.radius_mm)))
    return out


def _holes(segs, radii, parts, slots, grooves, src: str) -> list[Hole]:
    """Cross holes (``_place``), clear of the keyways, the grooves and one another by 0.5 mm
    (a hole through a keyway, or two notches' fields on top of each other, is outside every
    chart)."""
    out: list[Hole] = []
    for i, s in enumerate(segs):
        for j, h in enumerate(s.cross_holes):
            hl = Hole(s.name, j, radii[i], 0.5 * float(h.diameter_mm), float(h.x_center_mm),
                      math.radians(float(h.angle_deg)))
            others = [(f"keyway {k.segment}:{k.index}", k.x0, k.x1, 0.5) for k in slots
                      if k.segment == s.name]
            others += [(f"groove {g.segment}:{g.index}", g.x0, g.x1, 0.5) for g in grooves]
            others += [(f"cross hole {o.segment}:{o.index}", o.x0, o.x1, 0.5) for o in out]
            _place(src, f"segments[{i}].cross_holes[{j}].x_center_mm", "hole", h.x_center_mm,
                   hl.x0, hl.x1, parts[i], others)
            out.append(hl)
    return out


def _clear_of_seats(variant, seats, notches, hx: Hex | None, xs, src: str) -> None:
    """No groove or cross hole under a seat (a ring or a hub bears on the full diameter), under
    a ``[[loads]]`` band, or over the hex socket."""
    for g in notches:
        i = next(i for i, s in enumerate(variant.segments) if s.name == g.segment)
        what = "grooves" if isinstance(g, Groove) else "cross_holes"
        fld = f"segments[{i}].{what}[{g.index}].x_center_mm"
        for st in seats:
            if st.x0 < g.x1 - TOL and g.x0 < st.x1 - TOL:
                raise InputError(src, fld, f"clear of the seat {st.name} [{st.x0:g}, "
                                 f"{st.x1:g}]", got=0.5 * (g.x0 + g.x1),
                                 reason=f"puts a {what[:-1].replace('_', ' ')} under a seat")
        for ld in getattr(variant, "loads", ()):
            a, b = ld.band_mm
            if ld.kind != "gravity" and a < g.x1 - TOL and g.x0 < b - TOL:
                raise InputError(src, fld, f"clear of the band [{a:g}, {b:g}] of load "
                                 f"{ld.name!r}", got=0.5 * (g.x0 + g.x1),
                                 reason="puts a notch under a load's band (the two models "
                                 "would deliver it differently)")
        if hx is not None:
            lo, hi = ((xs[0][0], xs[0][0] + hx.depth) if hx.end == "left"
                      else (xs[-1][1] - hx.depth, xs[-1][1]))
            if g.x0 < hi and lo < g.x1:
                raise InputError(src, fld, f"clear of the hex socket [{lo:g}, {hi:g}]",
                                 got=0.5 * (g.x0 + g.x1), reason="overlaps another notch")


def _seat(src: str, field: str, name: str, a: float, b: float, angle: float | None,
          xs, parts, slots, inset: float = 0.0, loaded: bool = True, open_ends=()) -> Seat:
    """The face-group interval of a bearing ring or an attachment on one straight part.
    ``open_ends``: the x of straight parts' ends at a DIN 509 undercut's opening; a ring may
    reach over the undercut to the shoulder's face (what the undercut is for), and bears on the
    straight part only."""
    if b - a <= TOL:
        raise InputError(src, field, "start < end", got=(a, b))
    k = next((i for i in range(len(xs)) if xs[i][0] - TOL <= a and b <= xs[i][1] + TOL), None)
    if k is None:
        raise InputError(src, field, "an interval inside one segment", got=(a, b))
    p = parts[k]
    if inset > 0:
        # a chamfered ring bears on [a + c, b − c] only; that band must stay on the straight
        # seat: a shaft fillet no larger than the ring chamfer (ISO 582: the shaft fillet
        # radius r_as max = the ring's r_s min), so the contact edge never falls in a fillet
        a, b = a + inset, b - inset
        near = [round(x, 9) for x in open_ends]
        a = p.x0 if a < p.x0 and round(p.x0, 9) in near else a
        b = p.x1 if b > p.x1 and round(p.x1, 9) in near else b
        if a < p.x0 - TOL or b > p.x1 + TOL:
            raise InputError(src, field, f"a contact band [{a:g}, {b:g}] (ring minus its "
                             f"chamfer {inset:g} mm) on the straight part [{p.x0:g}, "
                             f"{p.x1:g}] of segment {p.segment!r}", got=(a, b),
                             reason="reaches into a shoulder fillet: the fillet must not "
                             "exceed the ring chamfer")
    a2, b2 = max(a, p.x0), min(b, p.x1)
    if b2 - a2 <= TOL:
        raise InputError(src, field, f"overlapping the cylindrical part [{p.x0:g}, "
                         f"{p.x1:g}] of segment {p.segment!r}", got=(a, b))
    for sl in slots:
        inside = sl.x0 >= a2 - TOL and sl.x1 <= b2 + TOL
        apart = sl.x1 <= a2 + TOL or sl.x0 >= b2 - TOL
        if sl.segment == p.segment and not (inside or apart):
            raise InputError(src, field, f"inside or clear of keyway "
                             f"{sl.segment}:{sl.index} [{sl.x0:g}, {sl.x1:g}]", got=(a, b))
    return Seat(name, p, a2, b2, angle, loaded)


def _seats(variant, xs, parts, slots, src: str, undercuts=()) -> list[Seat]:
    ends = [u.x0 if u.side == "right" else u.x1 for u in undercuts]
    seats = []
    for i, b in enumerate(variant.bearings):
        xc, w, c = float(b.x_center_mm), float(b.width_mm), float(b.chamfer_mm)
        if not w > 0:        # a ring (its chamfer's rule: model.validate, for any model)
            raise InputError(src, f"bearings[{i}].width_mm", "> 0 (a ring, not a point "
                             "support)", got=b.width_mm)
        seats.append(_seat(src, f"bearings[{i}].seat", bearing_group(b.name), xc - 0.5 * w,
                           xc + 0.5 * w, None, xs, parts, slots, c, open_ends=ends))
    for i, at in enumerate(variant.attachments):
        me = abs(float(at.mass_kg) * float(at.eccentricity_mm))
        seats.append(_seat(src, f"attachments[{i}].seat_x", seat_group(at.name),
                           float(at.seat_x_start_mm), float(at.seat_x_end_mm),
                           math.radians(float(at.angle_deg)), xs, parts, slots,
                           loaded=not me == 0.0))
    return seats


def _hex(variant, radii, xs, names, slots, src: str) -> Hex | None:
    """The hex socket, its corners inside 0.8 × every segment radius it reaches, clear of the
    keyways."""
    h = variant.hex_socket
    if h is None:
        return None
    s, dep = float(h.across_flats_mm), float(h.depth_mm)
    hx = Hex(h.end, s, dep)
    x_end = xs[0][0] + dep if h.end == "left" else xs[-1][1] - dep
    lo, hi = sorted((x_end, xs[0][0] if h.end == "left" else xs[-1][1]))
    for i in range(len(xs)):
        if xs[i][1] > lo + TOL and xs[i][0] < hi - TOL and hx.circumradius > 0.8 * radii[i]:
            raise InputError(src, "hex_socket.across_flats_mm",
                             f"corner radius < 0.8 × radius of segment {names[i]!r}", got=s)
    for sl in slots:
        if sl.x1 > lo and sl.x0 < hi:
            raise InputError(src, "hex_socket.depth_mm", "clear of the keyways", got=dep)
    return hx


def prepare(variant) -> Solid:
    """Validate ``variant`` (``shaftfe.model.validate.validate_variant``, then the solid's own
    construction rules) and return the solid's plan (no gmsh involved)."""
    validate_variant(variant, springs=False, typed=False)   # no stiffness in the solid
    src = source_of(variant)
    segs = tuple(variant.segments)
    names = [s.name for s in segs]
    radii, xs = _stations(segs)
    undercuts = _undercuts(segs, radii, xs)
    fillets, shoulders, parts, chamfers = _fillets(segs, radii, xs, src, undercuts)
    slots = _slots(segs, radii, parts, src)
    seats = _seats(variant, xs, parts, slots, src, undercuts)
    hx = _hex(variant, radii, xs, names, slots, src)
    if hx is not None:
        i = 0 if hx.end == "left" else len(segs) - 1
        c = next((ch.c for ch in chamfers if ch.segment == names[i] and ch.side == hx.end), 0.0)
        if c > 0 and hx.circumradius > 0.8 * (radii[i] - c):
            raise InputError(src, f"segments[{i}].chamfer_{hx.end}_mm", "a chamfer leaving "
                             "the end face around the hex socket's corners (corner radius < "
                             "0.8 × (radius − chamfer))", got=c)
    grooves = _grooves(segs, radii, parts, slots, src)
    holes = _holes(segs, radii, parts, slots, grooves, src)
    grooves = sorted([*grooves, *undercuts], key=lambda g: (g.x0, g.segment, g.index))
    _clear_of_seats(variant, seats, [*grooves, *holes], hx, xs, src)
    prof = sorted({round(x, 9) for st in seats for x in (st.x0, st.x1)})
    tapers = tuple(Taper(s.name, *xs[i], radii[i], 0.5 * float(s.d_right_mm))
                   for i, s in enumerate(segs) if s.conical)
    _warn_kinks(segs, tapers)
    return Solid(variant.name, xs[-1][1] - xs[0][0], xs[0][0], xs[-1][1], tuple(radii),
                 tuple(names), tuple(xs), tuple(fillets), tuple(shoulders), tuple(parts),
                 tuple(slots), tuple(seats), hx, tuple(prof), grooves=tuple(grooves),
                 holes=tuple(holes), chamfers=tuple(chamfers), tapers=tapers)


def _warn_kinks(segs, tapers) -> None:
    """A cone meets the cylinder at its small end without a step in a concave kink (interior
    angle 180° + its half-angle): a weak stress singularity, whose FE value grows slowly with
    refinement. Said in a warning: the cone's own peak there is not a converged stress."""
    names = [s.name for s in segs]
    for t in tapers:
        i = names.index(t.segment)
        k, x, r = (i - 1, t.x0, t.r0) if t.r0 < t.r1 else (i + 1, t.x1, t.r1)
        if not 0 <= k < len(segs):
            continue
        rk = 0.5 * (segs[k].d_right_mm if k < i else segs[k].diameter_mm)
        if abs(rk - r) <= TOL:
            half = math.degrees(math.atan(abs(t.r1 - t.r0) / (t.x1 - t.x0)))
            warn("taper-kink", taper_region(t.segment),
                 f"the cone meets the cylinder at x = {x:g} mm in a concave kink (180° + "
                 f"{half:.1f}°): a weak stress singularity, so the FE peak of "
                 f"{taper_region(t.segment)} there grows slowly with refinement and is no "
                 "converged stress (a blend radius is not built)")


def clip(sol: Solid, x0: float, x1: float) -> Solid:
    """The plan of the part of ``sol`` on [x0, x1]: a 3D submodel's solid (``shaftfe.zoned``).
    Segments are cut at x0 and x1; the fillets, shoulders, keyways, seats and the hex socket
    inside are kept; the new end faces (groups ``end:left`` / ``end:right``) are the cut faces
    where x0 > ``sol.x_left`` or x1 < ``sol.x_right``. The caller places the cuts on straight
    parts clear of every fillet, seat and cut (``zoned.zones``): a ValueError otherwise."""
    import dataclasses
    x0, x1 = max(x0, sol.x_left), min(x1, sol.x_right)
    idx = [i for i, (a, b) in enumerate(sol.segment_x) if b > x0 + TOL and a < x1 - TOL]
    for x in (x0, x1):
        inner = sol.x_left + TOL < x < sol.x_right - TOL
        cone = any(t.x0 - TOL < x < t.x1 + TOL for t in sol.tapers)
        if inner and (cone or not any(p.x0 + TOL < x < p.x1 - TOL for p in sol.parts)):
            raise ValueError(f"cut at x = {x:g} mm not on a straight part")
    parts, new_part = [], {}
    for k, i in enumerate(idx):
        p = sol.parts[i]
        q = dataclasses.replace(p, index=k, x0=max(p.x0, x0), x1=min(p.x1, x1))
        parts.append(q)
        new_part[p] = q

    def inside(a: float, b: float) -> bool:
        return a >= x0 - TOL and b <= x1 + TOL

    def across(a: float, b: float) -> bool:
        return a < x0 - TOL < b or a < x1 - TOL < b - 2 * TOL

    seats = []
    for st in sol.seats:
        if inside(st.x0, st.x1):
            seats.append(dataclasses.replace(st, part=new_part[st.part]))
        elif across(st.x0, st.x1):
            raise ValueError(f"cut through seat {st.name}")
    for g in (*sol.grooves, *sol.holes):
        if across(g.x0, g.x1):
            raise ValueError(f"cut through the {type(g).__name__.lower()} "
                             f"{g.segment}:{g.index}")
    fillets = tuple(f for f in sol.fillets if x0 + TOL < f.x_shoulder < x1 - TOL)
    keep = {f.segment for f in fillets}
    hx = sol.hex
    if hx is not None and not ((hx.end == "left" and x0 <= sol.x_left + TOL)
                               or (hx.end == "right" and x1 >= sol.x_right - TOL)):
        hx = None
    return dataclasses.replace(
        sol, length=x1 - x0, x_left=x0, x_right=x1, seat_span=seat_span(sol), clipped=True,
        radii=tuple(sol.radii[i] for i in idx),
        segment_names=tuple(sol.segment_names[i] for i in idx),
        segment_x=tuple((max(sol.segment_x[i][0], x0), min(sol.segment_x[i][1], x1))
                        for i in idx),
        fillets=fillets,
        shoulders=tuple(s for s in sol.shoulders if x0 + TOL < s.x < x1 - TOL),
        parts=tuple(parts),
        slots=tuple(k for k in sol.slots if inside(k.x0, k.x1)),
        grooves=tuple(g for g in sol.grooves if inside(g.x0, g.x1)),
        holes=tuple(h for h in sol.holes if inside(h.x0, h.x1)),
        chamfers=tuple(c for c in sol.chamfers if inside(c.x0, c.x1)),
        tapers=tuple(t for t in sol.tapers if inside(t.x0, t.x1)),
        seats=tuple(seats), hex=hx,
        profile_x=tuple(x for x in sol.profile_x if x0 + TOL < x < x1 - TOL),
        hot_axes_deg=tuple(h for h in sol.hot_axes_deg if h[0] in keep))


# fields added to the plan after its keys were first used: dropped from a key while they hold
# their defaults, so a plan without them keeps its mesh, zone and cache keys
LATE_FIELDS = ("grooves", "holes", "seat_span", "clipped", "chamfers", "tapers")


def plan_payload(sol: Solid) -> dict:
    """``dataclasses.asdict(sol)`` without the ``LATE_FIELDS`` at their defaults: what a cache
    key hashes of a plan."""
    import dataclasses
    d = dataclasses.asdict(sol)
    for k in LATE_FIELDS:
        if not d[k]:
            d.pop(k)
    for k in d.get("slots", ()):        # a sharp keyway's key as before its radius existed
        if not k["rho"]:
            k.pop("rho")
    for g in d.get("grooves", ()):      # an undercut's fields, out of other grooves' keys
        for k, empty in (("side", ""), ("t2", 0.0)):
            if g[k] == empty:
                g.pop(k)
    return d


def seat_span(sol: Solid, own: bool = False) -> tuple[float, float] | None:
    """The x-range of the loaded seats (a bearing's, a part's with m e ≠ 0) of the whole shaft
    ``sol`` was clipped from (``own``: of ``sol``'s own seats); None without any."""
    if sol.seat_span is not None and not own:
        return sol.seat_span
    seats = [st for st in sol.seats if st.loaded]
    if not seats:
        return None
    return min(st.x0 for st in seats), max(st.x1 for st in seats)


def profile(sol: Solid) -> list[tuple[str, tuple]]:
    """Outer profile in the (x, r) half plane from the left end (r = 0 excluded): a list of
    ("line", (x, r)) points and ("arc", (x_end, r_end, xc, rc)) pieces, starting from
    (x_left, 0). The 3D solid revolves it (``solid.occ``); the axisymmetric solver meshes it
    (``axisymmetric.mesh``)."""
    names = sol.segment_names
    c0 = sol.chamfer(names[0], "left")
    pts: list[tuple[str, tuple]] = [("line", (sol.x_left, sol.radii[0] - c0))]
    if c0 > 0:
        pts.append(("line", (sol.x_left + c0, sol.radii[0])))
    fil = {round(f.x_shoulder, 9): f for f in sol.fillets}
    cut = {round(g.x_face, 9): g for g in sol.grooves if g.undercut}
    n = len(sol.radii)
    for i in range(n):
        r = sol.r_right(i)  # a cone (no stations on it): its end point at its right radius,
        part = sol.parts[i]  # the sloped line from the left one
        cr = sol.chamfer(names[i], "right")                 # this segment's right edge
        cl = sol.chamfer(names[i + 1], "left") if i + 1 < n else 0.0   # the next one's left
        stations = [(x, None) for x in sol.profile_x if part.x0 + TOL < x < part.x1 - TOL]
        stations += [(g.x0, g) for g in sol.grooves if g.segment == part.segment
                     and not g.undercut]
        for x, g in sorted(stations, key=lambda e: e[0]):
            if g is None:
                if abs(pts[-1][1][0] - x) > TOL:       # (a seat's end on a groove's flank)
                    pts.append(("line", (x, r)))
            else:
                piece = _groove_profile(g)
                if abs(pts[-1][1][0] - g.x0) <= TOL:      # a seat ends on the groove's edge
                    piece = piece[1:]
                pts += piece
        if i == n - 1:
            if cr > 0:
                pts.append(("line", (sol.x_right - cr, r)))
            pts.append(("line", (sol.x_right, r - cr)))
            break
        xe = sol.segment_x[i][1]
        r1 = sol.radii[i + 1]
        if abs(r1 - r) <= TOL:
            pts.append(("line", (xe, r)))     # keep a face edge between equal segments
            continue
        # a step down's outer edge: this segment's right chamfer; a step up's: the next one's
        # left chamfer (a cone from the shoulder's top to the larger diameter)
        down = [("line", (xe - cr, r)), ("line", (xe, r - cr))] if cr > 0 else \
            [("line", (xe, r))]
        up_top = [("line", (xe, r1 - cl)), ("line", (xe + cl, r1))] if cl > 0 else \
            [("line", (xe, r1))]
        f = fil.get(round(xe, 9))
        u = cut.get(round(xe, 9))
        if u is not None and r < r1:     # an undercut in this segment, the face on its right
            pts += [*_undercut_profile(u), *up_top]
        elif u is not None:              # an undercut in the next segment, below this face
            pts += [*down, ("line", (xe, u.r_top)), *_undercut_profile(u)[1:]]
        elif f is None:
            pts += [*down, ("line", (xe, r1))] if r > r1 else [("line", (xe, r)), *up_top]
        elif f.side < 0:      # step up: arc on the left of the shoulder
            pts.append(("line", (xe - f.rho, r)))
            pts.append(("arc", (xe, r + f.rho, xe - f.rho, r + f.rho)))
            if r1 - (r + f.rho) > TOL:
                pts += up_top
        else:                 # step down: arc on the right of the shoulder
            pts += down
            if r - (r1 + f.rho) > TOL:
                pts.append(("line", (xe, r1 + f.rho)))
            pts.append(("arc", (xe + f.rho, r1, xe + f.rho, r1 + f.rho)))
    return pts


def groove_pieces(g: Groove) -> list[tuple[str, tuple]]:
    """A groove's outline pieces, left to right (``_groove_profile``, an undercut's
    ``_undercut_profile``)."""
    return _undercut_profile(g) if g.undercut else _groove_profile(g)


def _groove_profile(g: Groove) -> list[tuple[str, tuple]]:
    """A groove's outline from its left edge (x0, r) to its right edge (x1, r): flank, corner
    arc, bottom, corner arc, flank (the pieces of zero length left out)."""
    r, rb, rho = g.r, g.r_bottom, g.rho
    out: list[tuple[str, tuple]] = [("line", (g.x0, r))]
    if rb + rho < r - TOL:
        out.append(("line", (g.x0, rb + rho)))
    out.append(("arc", (g.x0 + rho, rb, g.x0 + rho, rb + rho)))
    if g.x1 - rho > g.x0 + rho + TOL:
        out.append(("line", (g.x1 - rho, rb)))
    out.append(("arc", (g.x1, rb + rho, g.x1 - rho, rb + rho)))
    if rb + rho < r - TOL:
        out.append(("line", (g.x1, r)))
    return out


def _undercut_profile(g: Groove) -> list[tuple[str, tuple]]:
    """A DIN 509 undercut's outline (``model.grooves``: the interpreted geometry) from left to
    right, from the cylinder's edge at the opening to the top of the face (side "right"), or
    from the face's top (its first point, for the caller to reach) to the opening's edge
    (side "left"): the 15° run-out ramp, the flat bottom at depth t1, the corner arc ρ, which
    ends tangent to the face plane (form E) or to a plane t2 into the face (form F), from where
    the 8° wall rises back to the face plane."""
    r, rb, rho, xf = g.r, g.r_bottom, g.rho, g.x_face
    s = 1.0 if g.side == "right" else -1.0          # from the face into the small segment: −s
    f = g.x1 - g.x0 - g.t2
    ramp = g.depth / math.tan(math.radians(DIN509_RAMP_DEG))
    xd = xf + s * g.t2                               # the arc's deepest x, in the face
    xc, rc = xd - s * rho, rb + rho
    right = [("line", (xf - s * f, r)), ("line", (xf - s * (f - ramp), rb))]
    if abs(xc - (xf - s * (f - ramp))) > TOL:
        right.append(("line", (xc, rb)))
    right.append(("arc", (xd, rc, xc, rc)))
    if g.t2 > 0:
        right.append(("line", (xf, g.r_top)))
    if s > 0:
        return right
    # mirrored: the same points in the reverse order, each arc's centre kept
    pts = [p[1][:2] for p in right]
    out: list[tuple[str, tuple]] = [("line", pts[-1])]
    for k in range(len(right) - 1, 0, -1):
        kind, data = right[k]
        out.append(("arc", (*pts[k - 1], data[2], data[3])) if kind == "arc"
                   else ("line", pts[k - 1]))
    return out


# --------------------------------------------------------------------------------------
# sharp corners (issue #30: a sharp shoulder looked safer than a rounded one)


@dataclass(frozen=True)
class SharpCorner:
    """A shoulder without a fillet (``fillet_mm = 0``) that carries bending: a re-entrant 90°
    corner, where linear elasticity has no finite stress (Williams 1952: σ ∝ ρ^-0.46 at the
    corner). The FE value there grows without bound as the mesh is refined: it is not a
    stress, no peak of the shaft is bounded by it, and no fatigue check can use it."""
    segment: str        # the segment whose right end is the shoulder
    x: float            # the shoulder plane
    r_small: float      # the corner's radius (the re-entrant edge)
    r_large: float

    @property
    def region(self) -> str:
        return shoulder_region(self.segment)

    @property
    def zone_mm(self) -> float:
        """How near the corner an FE value is the corner's, not the shaft's: the step height,
        the corner's only length (the singular field dominates at distances small against it;
        beyond a few step heights the nominal field of the smaller section is recovered)."""
        return self.r_large - self.r_small

    @property
    def mark(self) -> str:
        return f"sharp corner {self.region}: not a stress"

    def near(self, xyz) -> bool:
        """Is the point (x, y, z) within ``zone_mm`` of the corner's edge (x, r_small)?"""
        x, y, z = (float(c) for c in xyz)
        return math.hypot(x - self.x, math.hypot(y, z) - self.r_small) <= self.zone_mm + TOL

    def describe(self) -> str:
        return (f"fillet 0 at a loaded shoulder (x = {self.x:g} mm, Ø{2 * self.r_small:g}/"
                f"Ø{2 * self.r_large:g}): a sharp corner is a stress singularity; the FE values "
                f"within {self.zone_mm:g} mm of it are not stresses (they grow without bound as "
                "the mesh is refined), so no peak, hot spot or safety factor of this shaft is "
                "bounded by them; give the drawing's fillet radius")


def sharp_corners(variant) -> tuple[SharpCorner, ...]:
    """The loaded sharp corners of a variant: every diameter step with ``fillet_mm = 0`` (and
    no DIN 509 undercut, whose corner arc is its transition) that
    has a force on both sides (a bearing or a part with m e > 0; a step with nothing beyond it
    carries no moment and is harmless). The one rule static, fatigue (every method) and the
    report read."""
    radii, xs = _stations(tuple(variant.segments))
    forces = [float(b.x_center_mm) for b in variant.bearings]
    forces += [float(a.seat_center_mm) for a in variant.attachments
               if float(a.mass_kg) * float(a.eccentricity_mm) != 0.0]
    out = []
    segs = tuple(variant.segments)
    for i, s in enumerate(segs[:-1]):
        r0, r1 = 0.5 * s.d_right_mm, radii[i + 1]
        if abs(r0 - r1) <= TOL or float(s.fillet_mm) > 0 or undercut_at(segs, i):
            continue
        x = xs[i][1]
        if any(f < x for f in forces) and any(f > x for f in forces):
            out.append(SharpCorner(s.name, x, min(r0, r1), max(r0, r1)))
    return tuple(out)


def warn_sharp_corners(variant) -> tuple[SharpCorner, ...]:
    """``sharp_corners`` with a visible warning for each (``shaftfe.util.notices``)."""
    corners = sharp_corners(variant)
    for c in corners:
        warn("sharp-corner", c.region, c.describe())
    return corners


@dataclass(frozen=True)
class SharpKeywayEdge:
    """A keyway modelled with sharp edges: the variant gives no bottom radius (DIN 6885-1's
    r1, ``bottom_radius_mm``). Its bottom edge is re-entrant, where linear elasticity has no finite
    stress; a peak on the keyway is a value of the mesh. Measured on x2_57's gear-seat keyway
    (benchmarks/bench_keyway_edge.py → reports/benchmarks/keyway_edge.md): as the keyway
    edges' element size goes from the default level's down to 1/16 of it, the zoned von Mises
    peak goes from the top edge of the slot's end to its bottom edge and keeps growing. It is
    not refused (a keyway is assessed by its notch factor, DIN 743), but a peak on the keyway
    is marked in ``shaftfe static``'s tables, and FKM's keyway rows are
    (``fatigue.strength_outputs``)."""
    slot: Slot
    tol_mm: float            # how near the slot a peak is the slot's

    @property
    def region(self) -> str:
        return keyway_region(self.slot.segment, self.slot.index)

    @property
    def mark(self) -> str:
        return "on a sharp-edged keyway: grows with refinement (not a converged stress)"

    def near(self, xyz) -> bool:
        """Is the point (x, y, z) on the slot: within ``tol_mm`` of its stadium planform, and
        no deeper than its bottom plane less ``tol_mm`` (``Slot``)?"""
        k = self.slot
        x, y, z = (float(c) for c in xyz)
        n = y * math.cos(k.angle) + z * math.sin(k.angle)          # along the slot's depth
        t = -y * math.sin(k.angle) + z * math.cos(k.angle)         # across it
        if n < k.r - k.depth - self.tol_mm:
            return False
        half = 0.5 * k.width
        ends = (k.x0 + half, k.x1 - half)                          # the round ends' centres
        xe = min(max(x, ends[0]), ends[1])
        return math.hypot(x - xe, t) <= half + self.tol_mm


def sharp_keyway_edges(variant) -> tuple[SharpKeywayEdge, ...]:
    """Every sharp-edged keyway (``SharpKeywayEdge``): one without a bottom radius."""
    # the tolerance below the 0.5 mm a slot keeps from its segment's ends (``_slots``): a
    # fillet's peak next to a slot end is the fillet's
    return tuple(SharpKeywayEdge(k, min(0.2 * k.width, 0.45)) for k in prepare(variant).slots
                 if k.rho == 0)


def sharp_mark(corners, xyz) -> str:
    """The mark of a printed peak at ``xyz``: "" or why it is not a stress (``corners``: the
    ``SharpCorner``s and ``SharpKeywayEdge``s of the variant)."""
    hit = next((c for c in corners if c.near(xyz)), None)
    return "" if hit is None else hit.mark


def refuse_sharp_corners(variant, what: str) -> None:
    """A fatigue check (any method) of a shaft with a loaded sharp corner is refused: its
    utilisation there is not defined, and elsewhere it would pass a shaft whose worst place
    was never assessed (InputError naming the segment's fillet)."""
    corners = sharp_corners(variant)
    if not corners:
        return
    c = corners[0]
    i = [s.name for s in variant.segments].index(c.segment)
    path = f"segments.{c.segment}.fillet_mm"
    src = next((f"--set {p}={v}" for p, v in getattr(variant, "overrides", ()) if p == path),
               source_of(variant))
    raise InputError(src, f"segments[{i}].fillet_mm ({c.segment!r})",
                     f"> 0 at a loaded shoulder for {what}: a sharp corner (x = {c.x:g} mm) "
                     "is a stress singularity, not assessable; give the drawing's fillet "
                     "radius", got=0.0)
