"""The shaft solid: validated geometry, exact volume / face areas, and the Gmsh OCC model.

Pure-Python part (no gmsh): ``prepare(variant)`` checks a ``Variant`` and turns it into a
``Solid`` plan (profile, fillets, cylindrical parts, face-group intervals), so a bad variant
fails with ``InputError`` before Gmsh is ever imported. ``analytic_volume`` and
``expected_areas`` are exact closed forms (Pappus for the fillet rings, one-dimensional
quadrature for the round ends of a keyway seat).

Gmsh part: ``build_occ(gmsh, solid)`` builds the solid of revolution (profile with fillet arcs
revolved about x), cuts keyway seats and the hex socket, and imprints the two generator
lines of every attachment's load plane on its seat cylinder (an OCC fragment with line
segments), so the pressed / free halves are exact faces and no cut runs through the interior.

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
from shaftfe.model.validate import source_of, validate_variant

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
    """A keyway seat (stadium planform, flat bottom at depth ``depth`` below the surface)."""
    segment: str
    index: int
    r: float
    width: float
    depth: float
    length: float
    x_center: float
    angle: float        # rad

    @property
    def x0(self) -> float:
        return self.x_center - 0.5 * self.length

    @property
    def x1(self) -> float:
        return self.x_center + 0.5 * self.length


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

    @property
    def r_max(self) -> float:
        return max(self.radii)

    @property
    def r_min(self) -> float:
        return min(self.radii)

    def groups(self) -> tuple[str, ...]:
        names: list[str] = []
        for s in self.seats:
            if s.angle is None:
                names.append(s.name)
            else:
                names += [f"{s.name}:pressed", f"{s.name}:free"]
        names += [f"fillet:{f.segment}" for f in self.fillets]
        names += [f"shoulder:{s.segment}" for s in self.shoulders]
        names += [f"keyway:{k.segment}:{k.index}" for k in self.slots]
        names += ["end:left", "end:right"]
        if self.hex is not None:
            names.append("hex_socket")
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


def _fillets(segs, radii, xs, src: str):
    """Fillets, shoulder annuli and the straight (fillet-free) part of every segment."""
    n = len(segs)
    fillets: list[Fillet] = []
    shoulders: list[Shoulder] = []
    eat_left = [0.0] * n
    eat_right = [0.0] * n
    for i in range(n - 1):
        s = segs[i]
        r0, r1 = radii[i], radii[i + 1]
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
        if r0 < r1:
            side, small, large = -1, r0, r1
            eat_right[i] = rho
        else:
            side, small, large = +1, r1, r0
            eat_left[i + 1] = rho
        if rho > 0:
            fillets.append(Fillet(s.name, xe, small, large, rho, side))
        if large - (small + rho) > TOL:          # else a full-height fillet: no flat annulus
            shoulders.append(Shoulder(s.name, xe, small + rho, large))
    parts: list[CylPart] = []
    for i, s in enumerate(segs):
        a, b = xs[i][0] + eat_left[i], xs[i][1] - eat_right[i]
        if b - a <= TOL:
            raise InputError(src, f"segments[{i}].length_mm",
                             f"> the fillets it carries ({eat_left[i] + eat_right[i]:g} mm)",
                             got=s.length_mm)
        parts.append(CylPart(s.name, i, a, b, radii[i]))
    return fillets, shoulders, parts


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
                              xc, math.radians(float(k.angle_deg))))
    return slots


def _seat(src: str, field: str, name: str, a: float, b: float, angle: float | None,
          xs, parts, slots, inset: float = 0.0, loaded: bool = True) -> Seat:
    """The face-group interval of a bearing ring or an attachment on one straight part."""
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


def _seats(variant, xs, parts, slots, src: str) -> list[Seat]:
    seats = []
    for i, b in enumerate(variant.bearings):
        xc, w, c = float(b.x_center_mm), float(b.width_mm), float(b.chamfer_mm)
        if not w > 0:
            raise InputError(src, f"bearings[{i}].width_mm", "> 0", got=b.width_mm)
        if not 0 <= c < 0.25 * w:
            raise InputError(src, f"bearings[{i}].chamfer_mm", f">= 0 and < width / 4 "
                             f"({0.25 * w:g})", got=b.chamfer_mm)
        seats.append(_seat(src, f"bearings[{i}].seat", f"bearing:{b.name}", xc - 0.5 * w,
                           xc + 0.5 * w, None, xs, parts, slots, c))
    for i, at in enumerate(variant.attachments):
        me = abs(float(at.mass_kg) * float(at.eccentricity_mm))
        seats.append(_seat(src, f"attachments[{i}].seat_x", f"load:{at.name}",
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
    validate_variant(variant, springs=False)   # the solid never reads a stiffness
    src = source_of(variant)
    segs = tuple(variant.segments)
    names = [s.name for s in segs]
    radii, xs = _stations(segs)
    fillets, shoulders, parts = _fillets(segs, radii, xs, src)
    slots = _slots(segs, radii, parts, src)
    seats = _seats(variant, xs, parts, slots, src)
    hx = _hex(variant, radii, xs, names, slots, src)
    prof = sorted({round(x, 9) for st in seats for x in (st.x0, st.x1)})
    return Solid(variant.name, xs[-1][1] - xs[0][0], xs[0][0], xs[-1][1], tuple(radii),
                 tuple(names), tuple(xs), tuple(fillets), tuple(shoulders), tuple(parts),
                 tuple(slots), tuple(seats), hx, tuple(prof))


# --------------------------------------------------------------------------------------
# exact volume and areas


def _quad(f, a: float, b: float) -> float:
    if b <= a:
        return 0.0
    from scipy.integrate import quad
    val, _ = quad(f, a, b, epsabs=1e-13, epsrel=1e-12, limit=200)
    return float(val)


SPANDREL_AREA = 1.0 - math.pi / 4.0                        # × rho²
SPANDREL_CENTROID = (10.0 - 3.0 * math.pi) / (12.0 - 3.0 * math.pi)   # × rho, from the corner


def fillet_volume(f: Fillet) -> float:
    """Material a concave fillet adds to the corner: Pappus, 2π r̄ A, with the spandrel
    A = ρ²(1 − π/4) whose centroid lies ρ(10 − 3π)/(12 − 3π) above the smaller cylinder."""
    return 2.0 * math.pi * (f.r_small + f.rho * SPANDREL_CENTROID) * f.rho ** 2 * SPANDREL_AREA


def fillet_area(f: Fillet) -> float:
    """Toroidal fillet face: Pappus, arc length πρ/2 × 2π × arc centroid radius
    r_small + ρ(1 − 2/π)."""
    return 2.0 * math.pi * (0.5 * math.pi * f.rho) * (f.r_small + f.rho * (1.0 - 2.0 / math.pi))


def slot_volume(k: Slot) -> float:
    """Volume a keyway removes: ∫∫ over the stadium planform of the height of the cylinder
    above the flat bottom, h(s) = sqrt(R² − s²) − (R − t), s = lateral offset."""
    R, a, t = k.r, 0.5 * k.width, k.depth

    def h(s: float) -> float:
        return math.sqrt(R * R - s * s) - (R - t)

    straight = (k.length - k.width) * _quad(h, -a, a)
    ends = _quad(lambda s: h(s) * 2.0 * math.sqrt(max(a * a - s * s, 0.0)), -a, a)
    return straight + ends


def slot_area(k: Slot) -> float:
    """Faces of a keyway: flat bottom (stadium area), two straight walls of height
    h(±w/2), and the two half-cylindrical end walls ∫ a·h(a sin φ) dφ over 0…2π."""
    R, a, t = k.r, 0.5 * k.width, k.depth

    def h(s: float) -> float:
        return math.sqrt(R * R - s * s) - (R - t)

    bottom = (k.length - k.width) * k.width + math.pi * a * a
    walls = 2.0 * (k.length - k.width) * h(a)
    ends = _quad(lambda p: a * h(a * math.sin(p)), 0.0, 2.0 * math.pi)
    return bottom + walls + ends


def _interval_overlap(lo: float, hi: float, a: float, b: float) -> list[tuple[float, float]]:
    """Intersections of [lo, hi] with the angular window [a, b] repeated every 2π."""
    out = []
    for k in (-2, -1, 0, 1, 2):
        u, v = max(lo, a + 2 * math.pi * k), min(hi, b + 2 * math.pi * k)
        if v > u:
            out.append((u, v))
    return out


def slot_hole_area(k: Slot, window: tuple[float, float] | None = None) -> float:
    """Area of the keyway's opening in the cylinder r = R (within the angular window of
    absolute angles [a, b], or all of it): dA = R dψ dx, with the planform's axial extent
    L − w on the straight part and 2 sqrt(a² − R² sin²ψ) over the round ends."""
    R, a = k.r, 0.5 * k.width
    beta = math.asin(a / R)
    if window is None:
        spans = [(-beta, beta)]
    else:
        spans = _interval_overlap(-beta, beta, window[0] - k.angle, window[1] - k.angle)
    tot = 0.0
    for u, v in spans:
        tot += (k.length - k.width) * R * (v - u)
        tot += _quad(lambda p: 2.0 * R * math.sqrt(max(a * a - (R * math.sin(p)) ** 2, 0.0)),
                     u, v)
    return tot


def analytic_volume_of(sol: Solid) -> float:
    vol = sum(math.pi * r * r * (x1 - x0) for r, (x0, x1) in zip(sol.radii, sol.segment_x,
                                                                strict=True))
    vol += sum(fillet_volume(f) for f in sol.fillets)
    vol -= sum(slot_volume(k) for k in sol.slots)
    if sol.hex is not None:
        vol -= sol.hex.area * sol.hex.depth
    return vol


def expected_areas_of(sol: Solid) -> dict[str, float]:
    out: dict[str, float] = {}
    for st in sol.seats:
        slots = [k for k in sol.slots if k.segment == st.part.segment
                 and k.x0 >= st.x0 - TOL and k.x1 <= st.x1 + TOL]
        full = 2.0 * math.pi * st.part.r * (st.x1 - st.x0)
        if st.angle is None:
            out[st.name] = full - sum(slot_hole_area(k) for k in slots)
            continue
        win_p = (st.angle + 0.5 * math.pi, st.angle + 1.5 * math.pi)
        win_f = (st.angle - 0.5 * math.pi, st.angle + 0.5 * math.pi)
        out[f"{st.name}:pressed"] = 0.5 * full - sum(slot_hole_area(k, win_p) for k in slots)
        out[f"{st.name}:free"] = 0.5 * full - sum(slot_hole_area(k, win_f) for k in slots)
    for f in sol.fillets:
        out[f"fillet:{f.segment}"] = fillet_area(f)
    for s in sol.shoulders:
        out[f"shoulder:{s.segment}"] = math.pi * (s.r_out ** 2 - s.r_in ** 2)
    for k in sol.slots:
        out[f"keyway:{k.segment}:{k.index}"] = slot_area(k)
    hx = sol.hex
    left = math.pi * sol.radii[0] ** 2
    right = math.pi * sol.radii[-1] ** 2
    if hx is not None:
        if hx.end == "left":
            left -= hx.area
        else:
            right -= hx.area
        out["hex_socket"] = hx.area + 6.0 * hx.circumradius * hx.depth
    out["end:left"] = left
    out["end:right"] = right
    return out


def analytic_volume(variant) -> float:
    """Exact volume (mm³): cylinders + fillet spandrel rings (Pappus) − keyways − hex socket."""
    return analytic_volume_of(prepare(variant))


def expected_areas(variant) -> dict[str, float]:
    """Exact area (mm²) of each named face group."""
    return expected_areas_of(prepare(variant))


# --------------------------------------------------------------------------------------
# Gmsh OCC model


def _profile(sol: Solid) -> list[tuple[str, tuple]]:
    """Outer profile in the (x, r) half plane from the left end (r = 0 excluded): a list of
    ("line", (x, r)) points and ("arc", (x_end, r_end, xc, rc)) pieces."""
    pts: list[tuple[str, tuple]] = [("line", (sol.x_left, sol.radii[0]))]
    fil = {round(f.x_shoulder, 9): f for f in sol.fillets}
    n = len(sol.radii)
    for i in range(n):
        r = sol.radii[i]
        part = sol.parts[i]
        for x in sol.profile_x:
            if part.x0 + TOL < x < part.x1 - TOL:
                pts.append(("line", (x, r)))
        if i == n - 1:
            pts.append(("line", (sol.x_right, r)))
            break
        xe = sol.segment_x[i][1]
        r1 = sol.radii[i + 1]
        if abs(r1 - r) <= TOL:
            pts.append(("line", (xe, r)))     # keep a face edge between equal segments
            continue
        f = fil.get(round(xe, 9))
        if f is None:
            pts += [("line", (xe, r)), ("line", (xe, r1))]
        elif f.side < 0:      # step up: arc on the left of the shoulder
            pts.append(("line", (xe - f.rho, r)))
            pts.append(("arc", (xe, r + f.rho, xe - f.rho, r + f.rho)))
            if r1 - (r + f.rho) > TOL:
                pts.append(("line", (xe, r1)))
        else:                 # step down: arc on the right of the shoulder
            pts.append(("line", (xe, r)))
            if r - (r1 + f.rho) > TOL:
                pts.append(("line", (xe, r1 + f.rho)))
            pts.append(("arc", (xe + f.rho, r1, xe + f.rho, r1 + f.rho)))
    return pts


def build_occ(gmsh, sol: Solid) -> dict:
    """Build the partitioned solid in the current Gmsh model and synchronise.

    Returns {"volumes": [...], "faces": {group: [surface tags]}, "fillet_faces": [...],
    "sharp_curves": [...]} (sharp_curves: keyway edges and sharp concave shoulder circles)."""
    occ = gmsh.model.occ
    prof = _profile(sol)
    tags = [occ.addPoint(sol.x_left, 0.0, 0.0)]
    curves = []
    for kind, data in prof:
        if kind == "line":
            p = occ.addPoint(data[0], data[1], 0.0)
            curves.append(occ.addLine(tags[-1], p))
            tags.append(p)
        else:
            c = occ.addPoint(data[2], data[3], 0.0)
            p = occ.addPoint(data[0], data[1], 0.0)
            curves.append(occ.addCircleArc(tags[-1], c, p))
            tags.append(p)
    p_end = occ.addPoint(sol.x_right, 0.0, 0.0)
    curves.append(occ.addLine(tags[-1], p_end))
    curves.append(occ.addLine(p_end, tags[0]))
    loop = occ.addCurveLoop(curves)
    face = occ.addPlaneSurface([loop])
    rev = occ.revolve([(2, face)], 0, 0, 0, 1, 0, 0, 2 * math.pi)
    vols = [dt for dt in rev if dt[0] == 3]
    occ.remove([(2, face)], recursive=True)
    splits = _split_lines(sol)
    # put the revolution seam where no split line runs (coincident edges are fragile)
    occ.rotate(vols, 0, 0, 0, 1, 0, 0, _seam_angle([ang for _, _, _, ang in splits]))

    tools = []
    for k in sol.slots:
        tools.append(_slot_tool(occ, k))
    if sol.hex is not None:
        tools.append(_hex_tool(occ, sol))
    if tools:
        vols, _ = occ.cut(vols, [(3, t) for t in tools])
    if splits:
        # imprint the generator lines of each load plane on the seat cylinder: the seat face
        # splits into two exact halves without any cut through the interior (whose internal
        # faces would force tiny elements across the whole section)
        lines = []
        for x0, x1, r, ang in splits:
            y, z = r * math.cos(ang), r * math.sin(ang)
            lines.append((1, occ.addLine(occ.addPoint(x0, y, z), occ.addPoint(x1, y, z))))
        vols_out, _ = occ.fragment(vols, lines)
        vols = [dt for dt in vols_out if dt[0] == 3]
    occ.synchronize()
    loose = [(1, c) for _, c in gmsh.model.getEntities(1)
             if len(gmsh.model.getAdjacencies(1, c)[0]) == 0]
    if loose:                       # parts of split lines that ran over a keyway opening
        occ.remove(loose, recursive=True)
        occ.synchronize()
    return {"volumes": [t for _, t in vols]}


def _split_lines(sol: Solid) -> list[tuple[float, float, float, float]]:
    """(x0, x1, R, angle) of each generator line bounding a load half, deduplicated."""
    out, seen = [], set()
    for st in sol.seats:
        if st.angle is None:
            continue
        for ang in (st.angle + 0.5 * math.pi, st.angle - 0.5 * math.pi):
            a = math.remainder(ang, 2 * math.pi)
            key = (round(st.x0, 9), round(st.x1, 9), round(math.degrees(a) % 360.0, 6))
            if key not in seen:
                seen.add(key)
                out.append((st.x0, st.x1, st.part.r, a))
    return out


def _seam_angle(angles: list[float]) -> float:
    """The whole degree farthest from every split angle (0 when there is none)."""
    if not angles:
        return 0.0

    def gap(deg: int) -> float:
        t = math.radians(deg)
        return min(abs(math.remainder(t - a, 2 * math.pi)) for a in angles)

    return math.radians(max(range(360), key=lambda d: (round(gap(d), 9), -d)))


def _slot_tool(occ, k: Slot) -> int:
    """Stadium prism from the slot bottom to beyond the surface, opening towards +y, then
    rotated to the slot's angle."""
    a = 0.5 * k.width
    y0 = k.r - k.depth
    hgt = k.depth + 2.0
    box = occ.addBox(k.x0 + a, y0, -a, k.length - k.width, hgt, k.width)
    c1 = occ.addCylinder(k.x0 + a, y0, 0.0, 0.0, hgt, 0.0, a)
    c2 = occ.addCylinder(k.x1 - a, y0, 0.0, 0.0, hgt, 0.0, a)
    out, _ = occ.fuse([(3, box)], [(3, c1), (3, c2)])
    tag = out[0][1]
    occ.rotate([(3, tag)], 0, 0, 0, 1, 0, 0, k.angle)
    return tag


def _hex_tool(occ, sol: Solid) -> int:
    """Hexagonal prism (across flats s, flat bottom) from the end face inwards; one flat is
    normal to +y."""
    hx = sol.hex
    rc = hx.circumradius
    if hx.end == "left":
        x0, dx = sol.x_left - 1.0, hx.depth + 1.0
    else:
        x0, dx = sol.x_right - hx.depth, hx.depth + 1.0
    pts = [occ.addPoint(x0, rc * math.sin(math.pi / 3 * i), rc * math.cos(math.pi / 3 * i))
           for i in range(6)]
    lines = [occ.addLine(pts[i], pts[(i + 1) % 6]) for i in range(6)]
    s = occ.addPlaneSurface([occ.addCurveLoop(lines)])
    ext = occ.extrude([(2, s)], dx, 0, 0)
    return next(t for d, t in ext if d == 3)


def _surface_samples(gmsh, s: int):
    """Points of the (untrimmed) underlying surface on a 3×3 parameter grid."""
    lo, hi = gmsh.model.getParametrizationBounds(2, s)
    uv = []
    for fu in (0.1, 0.5, 0.9):
        for fv in (0.1, 0.5, 0.9):
            uv += [lo[0] + fu * (hi[0] - lo[0]), lo[1] + fv * (hi[1] - lo[1])]
    xyz = gmsh.model.getValue(2, s, uv)
    return [xyz[3 * i:3 * i + 3] for i in range(len(uv) // 2)]


def classify(gmsh, sol: Solid) -> dict:
    """Assign every boundary surface of the synchronised model to its face group(s).

    CAD faces are exact entities, so each test below is exact up to the tolerance of the
    kernel: a shaft cylinder has every point of its underlying surface at r = R; a fillet is a
    torus inside the fillet's axial range; end / shoulder / hex-bottom faces are planes normal
    to x at their station; whatever else lies in a keyway's or the hex socket's box belongs to
    it. Raises RuntimeError for a face that fits nothing (a bug, not a user error).

    Returns {"faces": {group: [surface tags]}, "fillet_faces": [...], "sharp_curves": [...]}.
    """
    faces: dict[str, list[int]] = {g: [] for g in sol.groups()}
    fillet_faces: list[int] = []
    keyway_faces: list[int] = []
    sharp_curves: set[int] = set()
    eps = 1e-5 * max(sol.length, 1.0)
    hx = sol.hex
    hex_x = None
    if hx is not None:
        hex_x = (sol.x_left, sol.x_left + hx.depth) if hx.end == "left" else \
            (sol.x_right - hx.depth, sol.x_right)
    for _, s in gmsh.model.getEntities(2):
        up, _ = gmsh.model.getAdjacencies(2, s)
        if len(up) != 1:
            continue                          # internal partition face
        kind = gmsh.model.getType(2, s)
        bx0, by0, bz0, bx1, by1, bz1 = gmsh.model.getBoundingBox(2, s)
        com = gmsh.model.occ.getCenterOfMass(2, s)
        groups: list[str] = []
        if kind == "Plane":
            lo, hi = gmsh.model.getParametrizationBounds(2, s)
            nrm = gmsh.model.getNormal(s, [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])])
            rmax = max(abs(by0), abs(by1), abs(bz0), abs(bz1))
            if abs(abs(nrm[0]) - 1.0) < 1e-9 and bx1 - bx0 < eps:
                x = 0.5 * (bx0 + bx1)
                if hex_x is not None and abs(x - (hex_x[1] if hx.end == "left" else hex_x[0])) \
                        < eps and rmax <= hx.circumradius + eps:
                    groups.append("hex_socket")
                elif abs(x - sol.x_left) < eps:
                    groups.append("end:left")
                elif abs(x - sol.x_right) < eps:
                    groups.append("end:right")
                else:
                    groups += [f"shoulder:{sh.segment}" for sh in sol.shoulders
                               if abs(x - sh.x) < eps and rmax <= sh.r_out + eps]
            elif hex_x is not None and abs(nrm[0]) < 1e-9 and bx0 > hex_x[0] - eps \
                    and bx1 < hex_x[1] + eps and rmax <= hx.circumradius + eps:
                groups.append("hex_socket")
        if not groups and kind == "Cylinder":
            rs = [math.hypot(p[1], p[2]) for p in _surface_samples(gmsh, s)]
            part = next((p for p in sol.parts if all(abs(r - p.r) < eps for r in rs)
                         and bx0 > p.x0 - eps and bx1 < p.x1 + eps), None)
            if part is not None:
                groups.append("")             # plain shaft surface (maybe in a seat)
                for st in sol.seats:
                    if st.part != part or bx0 < st.x0 - eps or bx1 > st.x1 + eps:
                        continue
                    if st.angle is None:
                        groups.append(st.name)
                    else:
                        side = com[1] * math.cos(st.angle) + com[2] * math.sin(st.angle)
                        groups.append(f"{st.name}:{'pressed' if side < 0 else 'free'}")
        if not groups and kind == "Torus":
            for f in sol.fillets:
                xa, xb = (f.x_shoulder - f.rho, f.x_shoulder) if f.side < 0 else \
                    (f.x_shoulder, f.x_shoulder + f.rho)
                if xa - eps < com[0] < xb + eps:    # (OCC's torus bounding box is loose)
                    groups.append(f"fillet:{f.segment}")
                    fillet_faces.append(s)
                    break
        if not groups:
            best, score = None, -2.0
            for k in sol.slots:
                if bx0 > k.x0 - eps and bx1 < k.x1 + eps:
                    rr = math.hypot(com[1], com[2]) or 1.0
                    sc = (com[1] * math.cos(k.angle) + com[2] * math.sin(k.angle)) / rr
                    if sc > score:
                        best, score = k, sc
            if best is not None and score > 0.5:
                groups.append(f"keyway:{best.segment}:{best.index}")
                keyway_faces.append(s)
        if not groups:
            raise RuntimeError(f"shaft solid: surface {s} ({kind}, bbox x {bx0:g}..{bx1:g}) "
                               "matches no face group")
        for g in groups:
            if g:
                faces[g].append(s)
    empty = [g for g, v in faces.items() if not v]
    if empty:
        raise RuntimeError(f"shaft solid: no faces found for groups {empty}")
    # sharp re-entrant edges: keyway edges, the inner circle of a sharp concave shoulder
    for s in keyway_faces:
        for _, c in gmsh.model.getBoundary([(2, s)], oriented=False):
            sharp_curves.add(abs(c))
    for sh in sol.shoulders:
        if any(abs(f.x_shoulder - sh.x) < eps for f in sol.fillets):
            continue
        for s in faces[f"shoulder:{sh.segment}"]:
            for _, c in gmsh.model.getBoundary([(2, s)], oriented=False):
                b = gmsh.model.getBoundingBox(1, abs(c))
                if max(abs(b[1]), abs(b[4]), abs(b[2]), abs(b[5])) < sh.r_in + eps:
                    sharp_curves.add(abs(c))
    return {"faces": faces, "fillet_faces": sorted(fillet_faces),
            "sharp_curves": sorted(sharp_curves)}
