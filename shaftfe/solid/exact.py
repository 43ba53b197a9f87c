"""Exact volume and face areas of the solid plan (closed forms: Pappus for the fillet rings,
one-dimensional quadrature for the round ends of a keyway seat): the independent check of every
mesh's volume and face groups."""

from __future__ import annotations

import math

from shaftfe.solid.features import (
    END_LEFT,
    END_RIGHT,
    HEX_SOCKET,
    SEAT_HALVES,
    fillet_region,
    half_group,
    keyway_region,
    shoulder_region,
)
from shaftfe.solid.plan import TOL, Fillet, Slot, Solid, prepare


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
        for half, win in zip(SEAT_HALVES, (win_p, win_f), strict=True):
            out[half_group(st.name, half)] = 0.5 * full - sum(slot_hole_area(k, win)
                                                              for k in slots)
    for f in sol.fillets:
        out[fillet_region(f.segment)] = fillet_area(f)
    for s in sol.shoulders:
        out[shoulder_region(s.segment)] = math.pi * (s.r_out ** 2 - s.r_in ** 2)
    for k in sol.slots:
        out[keyway_region(k.segment, k.index)] = slot_area(k)
    hx = sol.hex
    left = math.pi * sol.radii[0] ** 2
    right = math.pi * sol.radii[-1] ** 2
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
    """Exact volume (mm³): cylinders + fillet spandrel rings (Pappus) − keyways − hex socket."""
    return analytic_volume_of(prepare(variant))


def expected_areas(variant) -> dict[str, float]:
    """Exact area (mm²) of each named face group."""
    return expected_areas_of(prepare(variant))


