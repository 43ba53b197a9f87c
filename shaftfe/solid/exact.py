"""Exact volume and face areas of the solid plan (closed forms: Pappus for the fillet rings and
the grooves,
one-dimensional quadrature for the round ends of a keyway seat): the independent check of every
mesh's volume and face groups."""

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
from shaftfe.solid.plan import (
    TOL,
    Fillet,
    Groove,
    Hole,
    Slot,
    Solid,
    groove_pieces,
    prepare,
)


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
    return straight + ends - slot_fillet_volume(k)


def slot_fillet_volume(k: Slot) -> float:
    """The material a keyway's bottom radius ρ leaves in its corners: the spandrel
    (``SPANDREL_AREA`` ρ²) along the two straight sides, and revolved about each round end's
    axis by Pappus (its centroid ``SPANDREL_CENTROID`` ρ from the wall, at radius w/2 less
    that)."""
    a = 0.5 * k.width
    return SPANDREL_AREA * k.rho ** 2 * (2.0 * (k.length - k.width)
                                         + 2.0 * math.pi * (a - SPANDREL_CENTROID * k.rho))


def slot_area(k: Slot) -> float:
    """Faces of a keyway: flat bottom (stadium area), two straight walls of height
    h(±w/2), and the two half-cylindrical end walls ∫ a·h(a sin φ) dφ over 0…2π. With a bottom
    radius ρ: the bottom's stadium of radius a − ρ, the walls ρ lower, and the fillet: a
    quarter cylinder πρ/2 along each straight side and a quarter torus of area
    2πρ((a − ρ)π/2 + ρ) (Pappus) round the two ends."""
    R, a, t, rho = k.r, 0.5 * k.width, k.depth, k.rho

    def h(s: float) -> float:
        return math.sqrt(R * R - s * s) - (R - t) - rho

    straight = k.length - k.width
    bottom = straight * (k.width - 2.0 * rho) + math.pi * (a - rho) ** 2
    walls = 2.0 * straight * h(a)
    ends = _quad(lambda p: a * h(a * math.sin(p)), 0.0, 2.0 * math.pi)
    fillet = straight * math.pi * rho + 2.0 * math.pi * rho * ((a - rho) * 0.5 * math.pi + rho)
    return bottom + walls + ends + fillet


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


def _arc_prim(t: float, rc: float, rho: float) -> float:
    """∫ (rc + ρ sin t)² (−ρ sin t) dt: the volume under an arc, per π."""
    return -rho * (-rc * rc * math.cos(t) + 2.0 * rc * rho * (0.5 * t - 0.25 * math.sin(2.0 * t))
                   + rho * rho * (-math.cos(t) + math.cos(t) ** 3 / 3.0))


def outline_integrals(pieces) -> tuple[float, float]:
    """(∫ π r² dx, ∫ 2π r ds) along an outline in the (x, r) half plane (``solid.plan.
    profile``'s pieces; the first piece's end is the start): the volume under it, signed by
    the direction of x (Pappus, exact for lines and arcs), and the area it sweeps."""
    x0, r0 = pieces[0][1][:2]
    vol = area = 0.0
    for kind, data in pieces[1:]:
        x1, r1 = data[0], data[1]
        if kind == "line":
            vol += math.pi * (x1 - x0) * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0
            area += math.pi * (r0 + r1) * math.hypot(x1 - x0, r1 - r0)
        else:       # the minor arc about (xc, rc): x = xc + ρ cos θ, r = rc + ρ sin θ
            xc, rc = data[2], data[3]
            rho = math.hypot(x0 - xc, r0 - rc)
            a0 = math.atan2(r0 - rc, x0 - xc)
            da = math.remainder(math.atan2(r1 - rc, x1 - xc) - a0, 2.0 * math.pi)
            a1 = a0 + da

            vol += math.pi * (_arc_prim(a1, rc, rho) - _arc_prim(a0, rc, rho))
            area += 2.0 * math.pi * rho * abs(rc * da - rho * (math.cos(a1) - math.cos(a0)))
        x0, r0 = x1, r1
    return vol, area


def groove_volume(g: Groove) -> float:
    """The volume a groove removes (Pappus, ``outline_integrals``): the cylinder over its
    opening, π R² × (its width on the cylinder), less the volume under its outline. For a DIN
    509 undercut that is against the sharp step it replaces (negative where its corner arc
    rises above the cylinder into the step's corner)."""
    return math.pi * g.r ** 2 * (g.x1 - g.x0 - g.t2) - outline_integrals(groove_pieces(g))[0]


def groove_area(g: Groove) -> float:
    """The groove's faces (an undercut's up to the face's flat): its outline swept,
    ``outline_integrals``."""
    return outline_integrals(groove_pieces(g))[1]


def hole_volume(h: Hole) -> float:
    """The volume a cross hole removes: over the hole's section (a disc of radius a, z across
    it) the shaft's chord 2√(R² − z²): ∫ 2√(a² − z²) · 2√(R² − z²) dz."""
    a, R = h.a, h.r
    return _quad(lambda z: 4.0 * math.sqrt(max(a * a - z * z, 0.0))
                 * math.sqrt(R * R - z * z), -a, a)


def hole_area(h: Hole) -> float:
    """The hole's wall: around the hole (angle φ) its length across the shaft,
    2√(R² − a² sin²φ), times a dφ."""
    a, R = h.a, h.r
    return _quad(lambda p: 2.0 * a * math.sqrt(R * R - (a * math.sin(p)) ** 2),
                 0.0, 2.0 * math.pi)


def analytic_volume_of(sol: Solid) -> float:
    vol = sum(math.pi * r * r * (x1 - x0) for r, (x0, x1) in zip(sol.radii, sol.segment_x,
                                                                strict=True))
    # a cone: the frustum π L (r0² + r0 r1 + r1²)/3 in place of the cylinder π r0² L
    vol += sum(math.pi * (t.x1 - t.x0) * (t.r0 * t.r1 + t.r1 * t.r1 - 2.0 * t.r0 * t.r0) / 3.0
               for t in sol.tapers)
    vol += sum(fillet_volume(f) for f in sol.fillets)
    vol -= sum(slot_volume(k) for k in sol.slots)
    vol -= sum(groove_volume(g) for g in sol.grooves)
    vol -= sum(hole_volume(h) for h in sol.holes)
    # a 45° chamfer removes a triangle c²/2 whose centroid is at r − c/3 (Pappus)
    vol -= sum(math.pi * c.c * c.c * (c.r - c.c / 3.0) for c in sol.chamfers)
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
        for half, win in zip(SEAT_HALVES, (win_p, win_f), strict=True):
            out[half_group(st.name, half)] = 0.5 * full - sum(slot_hole_area(k, win)
                                                              for k in slots)
    for f in sol.fillets:
        out[fillet_region(f.segment)] = fillet_area(f)
    for s in sol.shoulders:
        out[shoulder_region(s.segment)] = math.pi * (s.r_out ** 2 - s.r_in ** 2)
    for k in sol.slots:
        out[keyway_region(k.segment, k.index)] = slot_area(k)
    for g in sol.grooves:
        out[groove_region(g.segment, g.index)] = groove_area(g)
    for h in sol.holes:
        out[hole_region(h.segment, h.index)] = hole_area(h)
    for t in sol.tapers:            # a frustum's side: π (r0 + r1) × its slant
        out[taper_region(t.segment)] = math.pi * (t.r0 + t.r1) * math.hypot(t.x1 - t.x0,
                                                                          t.r1 - t.r0)
    for c in sol.chamfers:          # a cone between r − c and r, slant c √2
        out[chamfer_region(c.segment, c.side)] = math.pi * (2.0 * c.r - c.c) * c.c * math.sqrt(2.0)
    hx = sol.hex
    left = math.pi * (sol.radii[0] - sol.chamfer(sol.segment_names[0], "left")) ** 2
    right = math.pi * (sol.r_right(len(sol.radii) - 1)
                       - sol.chamfer(sol.segment_names[-1], "right")) ** 2
    if hx is not None:
        if hx.end == "left":
            left -= hx.area
        else:
            right -= hx.area
        out[HEX_SOCKET] = hx.area + 6.0 * hx.circumradius * hx.depth
    out[END_LEFT] = left
    out[END_RIGHT] = right
    return out


def analytic_volume(variant) -> float:
    """Exact volume (mm³): cylinders + fillet spandrel rings (Pappus) − keyways − grooves −
    hex socket."""
    return analytic_volume_of(prepare(variant))


def expected_areas(variant) -> dict[str, float]:
    """Exact area (mm²) of each named face group."""
    return expected_areas_of(prepare(variant))


