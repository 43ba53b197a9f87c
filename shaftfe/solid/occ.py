"""The Gmsh OCC model of the solid plan: the profile revolved about x with its fillet arcs,
keyway seats and the hex socket cut, the load-plane lines of every attachment imprinted on its
seat, and every face classified into its named group (Gmsh is passed in: imported by the
caller)."""

from __future__ import annotations

import math

from shaftfe.solid.features import (
    END_LEFT,
    END_RIGHT,
    HEX_SOCKET,
    SEAT_HALVES,
    chamfer_region,
    fillet_region,
    groove_region,
    half_group,
    hole_region,
    keyway_region,
    shoulder_region,
    taper_region,
)
from shaftfe.solid.plan import Hole, Slot, Solid, profile


def build_occ(gmsh, sol: Solid) -> dict:
    """Build the partitioned solid in the current Gmsh model and synchronise.

    Returns {"volumes": [...], "faces": {group: [surface tags]}, "fillet_faces": [...],
    "sharp_curves": [...], "slot_fillets": {...}} (sharp_curves: keyway edges and sharp concave
    shoulder circles; slot_fillets: each rounded keyway's bottom fillet faces)."""
    occ = gmsh.model.occ
    prof = profile(sol)
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
    # (and where no cross hole opens: its two openings at its angle and opposite)
    holes = [a for h in sol.holes for a in (h.angle, h.angle + math.pi)]
    occ.rotate(vols, 0, 0, 0, 1, 0, 0,
               _seam_angle([ang for _, _, _, ang in splits] + holes))

    tools = []
    for k in sol.slots:
        tools.append(_slot_tool(occ, k))
    for h in sol.holes:
        tools.append(_hole_tool(occ, h))
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
    rotated to the slot's angle; with a bottom radius, its bottom edges rounded (a rolling
    ball of radius ρ: in the shaft, a concave fillet between the bottom and the walls)."""
    a = 0.5 * k.width
    y0 = k.r - k.depth
    hgt = k.depth + 2.0
    if k.rho > 0:
        tag = _rounded_stadium(occ, k.x0 + a, k.x1 - a, y0, a, hgt, k.rho)
    else:                        # (the sharp slot's construction, whose mesh the cache holds)
        box = occ.addBox(k.x0 + a, y0, -a, k.length - k.width, hgt, k.width)
        c1 = occ.addCylinder(k.x0 + a, y0, 0.0, 0.0, hgt, 0.0, a)
        c2 = occ.addCylinder(k.x1 - a, y0, 0.0, 0.0, hgt, 0.0, a)
        out, _ = occ.fuse([(3, box)], [(3, c1), (3, c2)])
        tag = out[0][1]
    occ.rotate([(3, tag)], 0, 0, 0, 1, 0, 0, k.angle)
    return tag


def _rounded_stadium(occ, xa: float, xb: float, y0: float, a: float, hgt: float,
                     rho: float) -> int:
    """The stadium of end centres xa, xb and radius a in the plane y = y0, extruded by hgt
    along +y, its bottom edges filleted with radius ρ. Each end is one half circle, so that
    no edge of the fillet runs through the apex of its end, the hot spot in bending."""
    up, ax = [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]     # the circles' plane y = y0; angle 0 = +x
    p = [occ.addPoint(xa, y0, -a), occ.addPoint(xb, y0, -a), occ.addPoint(xb, y0, a),
         occ.addPoint(xa, y0, a)]
    loop = [occ.addLine(p[0], p[1]),
            occ.addCircle(xb, y0, 0.0, a, angle1=-0.5 * math.pi, angle2=0.5 * math.pi,
                          zAxis=up, xAxis=ax),
            occ.addLine(p[2], p[3]),
            occ.addCircle(xa, y0, 0.0, a, angle1=0.5 * math.pi, angle2=1.5 * math.pi,
                          zAxis=up, xAxis=ax)]
    s = occ.addPlaneSurface([occ.addCurveLoop(loop)])
    ext = occ.extrude([(2, s)], 0.0, hgt, 0.0)
    vol = next(t for d, t in ext if d == 3)
    out = occ.fillet([vol], loop, [rho], removeVolume=True)
    return out[0][1]


def _hole_tool(occ, h: Hole) -> int:
    """A cylinder of the hole's radius through the shaft along (0, cos angle, sin angle)."""
    L = h.r + 1.0
    c, s = math.cos(h.angle), math.sin(h.angle)
    return occ.addCylinder(h.x_center, -L * c, -L * s, 0.0, 2 * L * c, 2 * L * s, h.a)


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


def _hex_range(sol: Solid) -> tuple[float, float] | None:
    hx = sol.hex
    if hx is None:
        return None
    return (sol.x_left, sol.x_left + hx.depth) if hx.end == "left" else \
        (sol.x_right - hx.depth, sol.x_right)


def _plane_groups(gmsh, s: int, sol: Solid, bbox, eps: float) -> list[str]:
    """End faces, shoulder annuli, the hex socket's bottom and flats."""
    bx0, by0, bz0, bx1, by1, bz1 = bbox
    hx, hex_x = sol.hex, _hex_range(sol)
    lo, hi = gmsh.model.getParametrizationBounds(2, s)
    nrm = gmsh.model.getNormal(s, [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])])
    rmax = max(abs(by0), abs(by1), abs(bz0), abs(bz1))
    if abs(abs(nrm[0]) - 1.0) < 1e-9 and bx1 - bx0 < eps:
        x = 0.5 * (bx0 + bx1)
        if hex_x is not None and abs(x - (hex_x[1] if hx.end == "left" else hex_x[0])) \
                < eps and rmax <= hx.circumradius + eps:
            return [HEX_SOCKET]
        if abs(x - sol.x_left) < eps:
            return [END_LEFT]
        if abs(x - sol.x_right) < eps:
            return [END_RIGHT]
        return [shoulder_region(sh.segment) for sh in sol.shoulders
                if abs(x - sh.x) < eps and rmax <= sh.r_out + eps]
    if hex_x is not None and abs(nrm[0]) < 1e-9 and bx0 > hex_x[0] - eps \
            and bx1 < hex_x[1] + eps and rmax <= hx.circumradius + eps:
        return [HEX_SOCKET]
    return []


def _cylinder_groups(gmsh, s: int, sol: Solid, bbox, com, eps: float) -> list[str]:
    """A straight part's surface ("") and the seats it lies in (loads split pressed / free)."""
    bx0, bx1 = bbox[0], bbox[3]
    rs = [math.hypot(p[1], p[2]) for p in _surface_samples(gmsh, s)]
    part = next((p for p in sol.parts if all(abs(r - p.r) < eps for r in rs)
                 and bx0 > p.x0 - eps and bx1 < p.x1 + eps), None)
    if part is None:
        return []
    groups = [""]                             # plain shaft surface (maybe in a seat)
    for st in sol.seats:
        if st.part != part or bx0 < st.x0 - eps or bx1 > st.x1 + eps:
            continue
        if st.angle is None:
            groups.append(st.name)
        else:
            side = com[1] * math.cos(st.angle) + com[2] * math.sin(st.angle)
            groups.append(half_group(st.name, SEAT_HALVES[0] if side < 0 else SEAT_HALVES[1]))
    return groups


def _fillet_group(sol: Solid, com, eps: float) -> str | None:
    for f in sol.fillets:
        xa, xb = (f.x_shoulder - f.rho, f.x_shoulder) if f.side < 0 else \
            (f.x_shoulder, f.x_shoulder + f.rho)
        if xa - eps < com[0] < xb + eps:        # (OCC's torus bounding box is loose)
            return fillet_region(f.segment)
    return None


def _groove_group(sol: Solid, bbox, com, eps: float) -> str | None:
    """The groove whose axial range holds the face (its flanks, corner tori and bottom
    cylinder; the straight parts' cylinders and the keyways are never in that range). OCC's
    torus bounding box is loose: the centre of mass decides, the box only within ρ."""
    for g in sol.grooves:
        if g.x0 - eps < com[0] < g.x1 + eps and bbox[0] > g.x0 - g.rho - eps \
                and bbox[3] < g.x1 + g.rho + eps:
            return groove_region(g.segment, g.index)
    return None


def _chamfer_group(sol: Solid, bbox, com, eps: float) -> str | None:
    """The chamfer (a cone) whose axial range holds the face's centre of mass and whose
    outer radius is the face's (a DIN 509 form F undercut's wall is a cone in the same axial
    range, below the shoulder's flat)."""
    r_out = max(abs(v) for v in (bbox[1], bbox[2], bbox[4], bbox[5]))
    for c in sol.chamfers:
        if c.x0 - eps < com[0] < c.x1 + eps and abs(r_out - c.r) < 1e-3 * c.r:
            return chamfer_region(c.segment, c.side)
    return None


def _taper_group(sol: Solid, com, eps: float) -> str | None:
    """The conical segment whose axial range holds the face's centre of mass (a cone: nothing
    else is cut into a taper)."""
    for t in sol.tapers:
        if t.x0 - eps < com[0] < t.x1 + eps:
            return taper_region(t.segment)
    return None


def _hole_group(sol: Solid, bbox, eps: float) -> str | None:
    """The cross hole whose axial range holds the face (its wall: the shaft's own cylinders
    were classified before)."""
    for h in sol.holes:
        if bbox[0] > h.x0 - eps and bbox[3] < h.x1 + eps:
            return hole_region(h.segment, h.index)
    return None


def _keyway_group(sol: Solid, bbox, com, eps: float) -> str | None:
    """The keyway whose box holds the face and whose open side faces it best. (OCC's box of
    a bottom fillet's torus is loose: there the centre of mass decides, the box only within
    the slot's end radius.)"""
    best, score = None, -2.0
    for k in sol.slots:
        loose = 0.5 * k.width if k.rho > 0 else 0.0
        if bbox[0] > k.x0 - loose - eps and bbox[3] < k.x1 + loose + eps \
                and k.x0 - eps < com[0] < k.x1 + eps:
            rr = math.hypot(com[1], com[2]) or 1.0
            sc = (com[1] * math.cos(k.angle) + com[2] * math.sin(k.angle)) / rr
            if sc > score:
                best, score = k, sc
    return keyway_region(best.segment, best.index) if best is not None and score > 0.5 else None


def _sharp_curves(gmsh, sol: Solid, faces: dict, keyway_faces: list[int], eps: float
                  ) -> list[int]:
    """Keyway edges (sized by ``k_sharp``; a rounded keyway's bottom fillet has a finer field of
    its own, ``_slot_fillets``) and the inner circle of a sharp concave shoulder."""
    sharp: set[int] = set()
    for s in keyway_faces:
        for _, c in gmsh.model.getBoundary([(2, s)], oriented=False):
            sharp.add(abs(c))
    for sh in sol.shoulders:
        if any(abs(f.x_shoulder - sh.x) < eps for f in sol.fillets) or \
                any(abs(g.x_face - sh.x) < eps for g in sol.grooves if g.undercut):
            continue
        for s in faces[shoulder_region(sh.segment)]:
            for _, c in gmsh.model.getBoundary([(2, s)], oriented=False):
                b = gmsh.model.getBoundingBox(1, abs(c))
                if max(abs(b[1]), abs(b[4]), abs(b[2]), abs(b[5])) < sh.r_in + eps:
                    sharp.add(abs(c))
    return sorted(sharp)


def classify(gmsh, sol: Solid) -> dict:
    """Assign every boundary surface of the synchronised model to its face group(s).

    CAD faces are exact entities, so each test below is exact up to the tolerance of the
    kernel: a shaft cylinder has every point of its underlying surface at r = R; a fillet is a
    torus inside the fillet's axial range; end / shoulder / hex-bottom faces are planes normal
    to x at their station; a groove's faces lie in its axial range below its segment's
    radius; whatever else lies in a keyway's or the hex socket's box belongs to it. Raises
    RuntimeError for a face that fits nothing (a bug, not a user error).

    Returns {"faces": {group: [surface tags]}, "fillet_faces": [...], "sharp_curves": [...],
    "slot_fillets": {keyway group: [its bottom fillet's surface tags]}}.
    """
    faces: dict[str, list[int]] = {g: [] for g in sol.groups()}
    fillet_faces: list[int] = []
    keyway_faces: list[int] = []
    eps = 1e-5 * max(sol.length, 1.0)
    for _, s in gmsh.model.getEntities(2):
        up, _ = gmsh.model.getAdjacencies(2, s)
        if len(up) != 1:
            continue                          # internal partition face
        kind = gmsh.model.getType(2, s)
        bbox = gmsh.model.getBoundingBox(2, s)
        com = gmsh.model.occ.getCenterOfMass(2, s)
        groups: list[str] = _plane_groups(gmsh, s, sol, bbox, eps) if kind == "Plane" else []
        if not groups and kind == "Cylinder":
            groups = _cylinder_groups(gmsh, s, sol, bbox, com, eps)
        if not groups and kind == "Torus":
            g = _fillet_group(sol, com, eps)
            if g is not None:
                groups, fillet_faces = [g], [*fillet_faces, s]
        if not groups:            # a chamfer's cone, a groove's or a cross hole's faces
            g = ((kind == "Cone" and (_chamfer_group(sol, bbox, com, eps)
                                      or _taper_group(sol, com, eps)))
                 or _groove_group(sol, bbox, com, eps) or _hole_group(sol, bbox, eps))
            groups = [g] if g else []
        if not groups:
            g = _keyway_group(sol, bbox, com, eps)
            if g is not None:
                groups, keyway_faces = [g], [*keyway_faces, s]
        if not groups:
            raise RuntimeError(f"shaft solid: surface {s} ({kind}, bbox x {bbox[0]:g}.."
                               f"{bbox[3]:g}) matches no face group")
        for g in groups:
            if g:
                faces[g].append(s)
    empty = [g for g, v in faces.items() if not v]
    if empty:
        raise RuntimeError(f"shaft solid: no faces found for groups {empty}")
    return {"faces": faces, "fillet_faces": sorted(fillet_faces),
            "sharp_curves": _sharp_curves(gmsh, sol, faces, keyway_faces, eps),
            "slot_fillets": _slot_fillets(gmsh, sol, faces, eps)}


def _slot_fillets(gmsh, sol: Solid, faces: dict, eps: float) -> dict[str, list[int]]:
    """Each rounded keyway's bottom fillet faces ({region: [surface tags]}): its faces that
    are not planes (the bottom and the straight walls are) and whose centre of mass lies
    within ρ of the bottom plane (the round ends' walls lie above it)."""
    out: dict[str, list[int]] = {}
    for k in sol.slots:
        if k.rho <= 0:
            continue
        reg = keyway_region(k.segment, k.index)
        out[reg] = []
        for s in faces[reg]:
            com = gmsh.model.occ.getCenterOfMass(2, s)
            n = com[1] * math.cos(k.angle) + com[2] * math.sin(k.angle)
            if gmsh.model.getType(2, s) != "Plane" and n < k.r - k.depth + k.rho + eps:
                out[reg].append(s)
    return out
