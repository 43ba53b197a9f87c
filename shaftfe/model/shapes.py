"""Mass properties of a part from its drawn shape: what a design study varies.

The variant files state each counterweight's mass, eccentricity and inertias (seed values or
fitted ones, ``geometry/RECONSTRUCTION.md``) and its ``[attachments.shape]`` beside them. A study
that changes the plate thickness, outer radius or half angle wants the mass properties to follow
from the geometry, so ``derived_overrides`` turns shape overrides into the attachment's
``mass_kg``, ``eccentricity_mm`` and inertias, and the variant's ``[balance]`` statement into
what the parts then give (mass, γ2, x_T, X2). Closed forms of a plate of thickness t (x along
the shaft axis), density ρ:

* annular sector, radii r_i..R, half angle α (rad), symmetric about its eccentricity direction:
  m = ρ t α (R² − r_i²); e = 2 sin α (R³ − r_i³) / (3 α (R² − r_i²));
  J_axis = ρ t α (R⁴ − r_i⁴) / 2
* hub ring r_b..r_h (r_b = the seat radius it is keyed on) plus an annular sector: the ring adds
  m = ρ t π (r_h² − r_b²), J_axis = m (r_h² + r_b²) / 2 and nothing to m e.

polar (about the part's own centroid, parallel to x) = J_axis − m e²; diametral (a transverse
axis through the centroid) = polar / 2 + m t² / 12 (thin-plate rule, as the files' notes say).
The files' x2_57 values reproduce to 5 digits (tests/validation/test_shapes.py).
"""

from __future__ import annotations

import math

from shaftfe.errors import InputError

SHAPE_KINDS = ("annular_sector", "hub_ring_plus_annular_sector")


def _sector(rho: float, t: float, ri: float, R: float, alpha_deg: float):
    a = math.radians(alpha_deg)
    m = rho * t * a * (R * R - ri * ri)
    me = rho * t * 2.0 * math.sin(a) * (R ** 3 - ri ** 3) / 3.0
    J = rho * t * a * (R ** 4 - ri ** 4) / 2.0
    return m, me, J


def shape_mass_properties(shape: dict, density_t_mm3: float, seat_radius_mm: float,
                          where: str = "shape") -> dict[str, float]:
    """{mass_kg, eccentricity_mm, polar_inertia_kg_mm2, diametral_inertia_kg_mm2} of a plate
    shape (mm; density in t/mm³ as the material cards)."""
    kind = shape.get("kind")
    if kind not in SHAPE_KINDS:
        raise InputError(where, "kind", " | ".join(SHAPE_KINDS) + " (a shape whose mass "
                         "properties shaftfe derives)", got=kind)
    need = ["thickness_mm", "inner_radius_mm", "outer_radius_mm", "half_angle_deg"]
    if kind == "hub_ring_plus_annular_sector":
        need.append("hub_outer_radius_mm")
    for k in need:
        if not isinstance(shape.get(k), int | float) or isinstance(shape.get(k), bool):
            raise InputError(where, k, f"a number (a {kind} needs " + ", ".join(need) + ")",
                             got=shape.get(k), reason="is missing" if k not in shape else None)
    rho = density_t_mm3 * 1e3                     # kg/mm³
    t = float(shape["thickness_mm"])
    ri, R = float(shape["inner_radius_mm"]), float(shape["outer_radius_mm"])
    alpha = float(shape["half_angle_deg"])
    if not (t > 0 and 0 <= ri < R and 0 < alpha <= 180):
        raise InputError(where, "shape", "thickness > 0, inner_radius < outer_radius, "
                         "0 < half_angle <= 180 deg", got=f"t={t:g}, r={ri:g}..{R:g}, "
                         f"α={alpha:g}")
    m, me, J = _sector(rho, t, ri, R, alpha)
    if kind == "hub_ring_plus_annular_sector":
        rh, rb = float(shape["hub_outer_radius_mm"]), seat_radius_mm
        if not rb < rh <= ri:
            raise InputError(where, "hub_outer_radius_mm", f"in ({rb:g}, {ri:g}] mm (between "
                             "the seat and the sector)", got=rh)
        mh = rho * t * math.pi * (rh * rh - rb * rb)
        m, J = m + mh, J + mh * (rh * rh + rb * rb) / 2.0
    e = me / m
    polar = J - m * e * e
    return {"mass_kg": m, "eccentricity_mm": e, "polar_inertia_kg_mm2": polar,
            "diametral_inertia_kg_mm2": polar / 2.0 + m * t * t / 12.0}
