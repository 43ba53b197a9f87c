"""Mass properties of a variant (pure functions, stdlib only): volumes of the stepped shaft,
keyways and hex socket, the balancer's mass, eccentricity and inertias, the centrifugal seat
loads and the rigid two-support reactions of the seed's Inventor shaft module."""

from __future__ import annotations

import math

import numpy as np

from shaftfe.model.variant import Keyway, MassProperties, Variant


def keyway_volume_mm3(d_mm: float, kw: Keyway) -> float:
    """Material removed by a round-ended keyway of width b, depth t1 (measured at the slot's
    centre line from the cylinder surface) and length l in a shaft of diameter d: the
    transverse section b·t1 minus the sliver outside the circle, times the straight part
    (l − b), plus the two half-round ends as a cylinder of diameter b and mean depth."""
    r, b, t1 = 0.5 * d_mm, kw.width_mm, kw.depth_mm
    s = r - math.sqrt(r * r - 0.25 * b * b)                       # sagitta over the slot width
    segment = r * r * math.acos((r - s) / r) - (r - s) * math.sqrt(2 * r * s - s * s)
    a_t = b * t1 - (b * s - segment)
    return a_t * (kw.length_mm - b) + 0.25 * math.pi * b * b * (t1 - 0.5 * s)


def keyway_centroid_radius_mm(d_mm: float, kw: Keyway) -> float:
    r, b = 0.5 * d_mm, kw.width_mm
    s = r - math.sqrt(r * r - 0.25 * b * b)
    return r - 0.5 * s - 0.5 * kw.depth_mm


def hexagon_area_mm2(across_flats_mm: float) -> float:
    return math.sqrt(3.0) / 2.0 * across_flats_mm**2


def hexagon_polar_moment_mm4(across_flats_mm: float) -> float:
    """Polar second moment of area of a regular hexagon about its centre, (5√3/8) a⁴."""
    a = across_flats_mm / math.sqrt(3.0)
    return 5.0 * math.sqrt(3.0) / 8.0 * a**4


def _frustum(s, rho: float) -> tuple[float, float, float, float]:
    """(m, m x̄, J_polar, Σ(m x² + I_d)) of a conical segment of density ``rho`` (kg/mm³), the
    sums over its thin discs: ∫ ρ π r² {1, x, r²/2, r²/4 + x²} dx, r linear in x. The
    integrands are polynomials of degree ≤ 4 in x: 4-point Gauss-Legendre is exact (to
    degree 7)."""
    t, w = np.polynomial.legendre.leggauss(4)
    x = s.x_start_mm + 0.5 * s.length_mm * (t + 1.0)
    r = 0.5 * s.diameter_at(x)
    disc = rho * math.pi * r * r * 0.5 * s.length_mm * w
    return (float(disc.sum()), float(disc @ x), float(disc @ (0.5 * r * r)),
            float(disc @ (0.25 * r * r + x * x)))


def shaft_body_properties(v: Variant) -> tuple[float, float, float, float, float, float]:
    """(mass kg, x·mass kg·mm, m·e_y, m·e_z kg·mm, polar J kg·mm², Σ(m x² + Id) kg·mm² about
    x = 0) of the shaft body: cylinders minus keyways minus the hex socket."""
    rho = v.material.density_t_mm3 * 1e3                         # kg/mm³
    m = mx = qy = qz = jp = jd = 0.0
    for s in v.segments:
        if s.conical:            # a frustum: the integrals of its discs, exactly (below)
            dm, dmx, djp, djd = _frustum(s, rho)
            m, mx, jp, jd = m + dm, mx + dmx, jp + djp, jd + djd
            continue
        r = 0.5 * s.diameter_mm
        mi = rho * math.pi * r * r * s.length_mm
        xc = s.x_start_mm + 0.5 * s.length_mm
        m += mi
        mx += mi * xc
        jp += 0.5 * mi * r * r
        jd += mi * (0.25 * r * r + s.length_mm**2 / 12.0 + xc * xc)
        for kw in s.keyways:
            mk = rho * keyway_volume_mm3(s.diameter_mm, kw)
            rc = keyway_centroid_radius_mm(s.diameter_mm, kw)
            ang = math.radians(kw.angle_deg)
            m -= mk
            mx -= mk * kw.x_center_mm
            qy -= mk * rc * math.cos(ang)
            qz -= mk * rc * math.sin(ang)
            jp -= mk * rc * rc
            jd -= mk * (kw.x_center_mm**2 + 0.5 * rc * rc)
    hs = v.hex_socket
    if hs is not None:
        mh = rho * hexagon_area_mm2(hs.across_flats_mm) * hs.depth_mm
        x_end = v.segments[-1].x_end_mm if hs.end == "right" else v.segments[0].x_start_mm
        xc = x_end - 0.5 * hs.depth_mm if hs.end == "right" else x_end + 0.5 * hs.depth_mm
        m -= mh
        mx -= mh * xc
        jh = rho * hs.depth_mm * hexagon_polar_moment_mm4(hs.across_flats_mm)
        jp -= jh
        jd -= 0.5 * jh + mh * (hs.depth_mm**2 / 12.0 + xc * xc)
    return m, mx, qy, qz, jp, jd


def mass_properties(v: Variant) -> MassProperties:
    """Mass, γ2, x_T and inertias of the whole balancer (shaft body + every attachment)."""
    ms, mx, qy, qz, jp, jd0 = shaft_body_properties(v)
    m_tot, mx_tot, jp_tot = ms, mx, jp
    jd_x0 = jd0                                    # Σ (Id + m x²) about a transverse axis at x=0
    for a in v.attachments:
        ang = math.radians(a.angle_deg)
        m_tot += a.mass_kg
        mx_tot += a.mass_kg * a.x_centroid_mm
        qy += a.mass_kg * a.eccentricity_mm * math.cos(ang)
        qz += a.mass_kg * a.eccentricity_mm * math.sin(ang)
        jp_tot += a.polar_inertia_kg_mm2 + a.mass_kg * a.eccentricity_mm**2
        jd_x0 += (a.diametral_inertia_kg_mm2
                  + a.mass_kg * (a.x_centroid_mm**2 + 0.5 * a.eccentricity_mm**2))
    xc = mx_tot / m_tot
    return MassProperties(
        mass_kg=m_tot, shaft_mass_kg=ms, x_centroid_mm=xc, me_y_kg_mm=qy, me_z_kg_mm=qz,
        gamma2_mm=math.hypot(qy, qz) / m_tot, x_T_mm=xc - v.parting_plane_x_mm,
        polar_inertia_kg_mm2=jp_tot, diametral_inertia_kg_mm2=jd_x0 - m_tot * xc * xc,
        shaft_polar_inertia_kg_mm2=jp)


def seat_loads(v: Variant, rpm: float, seed_case: bool = True) -> list[tuple[float, float, float]]:
    """Centrifugal forces lumped per seat: [(x of the seat centre, Fy N, Fz N), ...] in seat
    order (the gear and counterweight 1 share the gear seat: F1 of the seed)."""
    out: dict[tuple[float, float], list[float]] = {}
    for a in v.attachments:
        if seed_case and not a.seed_load_case:
            continue
        f = a.force_N(rpm)
        ang = math.radians(a.angle_deg)
        key = (round(a.seat_x_start_mm, 9), round(a.seat_x_end_mm, 9))
        acc = out.setdefault(key, [0.0, 0.0])
        acc[0] += f * math.cos(ang)
        acc[1] += f * math.sin(ang)
    return [(0.5 * (k[0] + k[1]), fy, fz) for k, (fy, fz) in sorted(out.items())]


def rigid_support_reactions(v: Variant, rpm: float, seed_case: bool = True
                            ) -> tuple[tuple[str, float], ...]:
    """Radial reaction magnitudes (N) of two simple supports at the bearing centres under the
    seat-lumped centrifugal forces (the seed's Inventor shaft-module idealisation). Needs
    exactly two bearings; returns ((bearing name, |R|), ...) in x order."""
    if len(v.bearings) != 2:
        raise ValueError("rigid_support_reactions needs exactly two bearings")
    a, b = v.bearings
    span = b.x_center_mm - a.x_center_mm
    loads = seat_loads(v, rpm, seed_case)
    out = []
    for comp in (1, 2):
        f_tot = sum(ld[comp] for ld in loads)
        rb = sum(ld[comp] * (ld[0] - a.x_center_mm) for ld in loads) / span
        out.append((f_tot - rb, rb))
    ra = math.hypot(out[0][0], out[1][0])
    rb_ = math.hypot(out[0][1], out[1][1])
    return ((a.name, ra), (b.name, rb_))


def variant_x2(v: Variant, mp: MassProperties | None = None,
               default: float = 0.0) -> float:
    """The balancer's X2 (a fraction) of a variant: from its parts and the crank's m_pos R in
    its [balance] table, else the X2 that table states, else ``default`` (no table: e.g. the
    engine's own balancer)."""
    tgt = v.balance_target
    x2 = balance_ratio(mp if mp is not None else mass_properties(v), tgt)
    if x2 is None:
        x2 = tgt.X2_percent / 100.0 if tgt is not None else default
    return x2


def balance_ratio(mp: MassProperties, target) -> float | None:
    """The balancer's ratio X2 = Σ m e / (m_pos R) (a fraction) from its mass properties and
    the engine figures of the variant's [balance] table; None without them."""
    if target is None or not (target.m_pos_kg > 0 and target.crank_radius_mm > 0):
        return None
    return mp.mass_kg * mp.gamma2_mm / (target.m_pos_kg * target.crank_radius_mm)
