"""The mesher's refined sectors follow each fillet's computed bending plane (issue #12 item 2).

Reference: beam theory. For a round section under the moment vector (0, M_y, M_z) the bending
stress σ_x = (M_y sin θ − M_z cos θ) r / I peaks on the line θ* = atan2(M_y, −M_z) (e.g.
Timoshenko & Gere, Mechanics of Materials, unsymmetric bending of a circular section, where
every centroidal axis is principal). The moments come from the beam model of the same variant
(``shaftfe.beam``, verified against ROSS and closed forms elsewhere); the 3D solid's own peak
locations are compared with them.
"""

from __future__ import annotations

import dataclasses
import math

import pytest

from shaftfe.beam.planes import hot_axes, mesh_hot_axes
from shaftfe.model.loader import load_variant
from shaftfe.solid.levels import LEVELS
from shaftfe.solid.mesh import hot_axis
from shaftfe.solid.plan import prepare


def turned(variant, names, angle_deg):
    """``variant`` with the attachments ``names`` pushing at ``angle_deg``."""
    return dataclasses.replace(variant, attachments=tuple(
        dataclasses.replace(a, angle_deg=angle_deg) if a.name in names else a
        for a in variant.attachments))


def line_diff_deg(a: float, b: float) -> float:
    """Smallest angle between two lines (either sense), degrees."""
    d = (a - b) % 180.0
    return min(d, 180.0 - d)


@pytest.mark.parametrize("phi", [0.0, 30.0, 45.0, 90.0])
def test_one_load_line_gives_its_plane_whatever_k12(phi):
    """Every load along one line at φ: the plane at both span fillets is φ, although the
    bearings' 2×2 springs couple y and z (K12 = 8756 N/mm): with two tilt-free bearings the
    reactions follow from statics alone. Exact arithmetic up to the beam solve's rounding
    (relative residual ~1e-15 → 1e-9°)."""
    v = load_variant("x2_57")
    w = turned(v, {a.name for a in v.attachments}, phi)
    ax = mesh_hot_axes(w)
    for seg in ("bearing_seat_gear", "collar"):
        assert line_diff_deg(math.degrees(ax[seg]), phi) < 1e-9


def test_no_moment_no_plane():
    """A fillet outboard of every load and bearing carries no bending moment: no plane (None);
    the mesher treats such end fillets apart anyway (``end_fillet``)."""
    v = load_variant("x2_57")
    ax = hot_axes(v, prepare(v).fillets)
    assert ax["thread_m10"] is None and ax["cw2_seat"] is None


@pytest.mark.xfail(strict=True, reason="issue #31: with each part's force at its centroid the "
                   "collar's 3D peak lies 7.1° (von Mises) / 4.6° (max principal) off the beam's "
                   "moment plane (measured with and without spin softening alike), beyond the "
                   "5° this test holds; still inside the coarse level's refined ±10° sector. "
                   "Open: the plane rule should follow the remote loads' distribution")
def test_two_load_planes_the_3d_peak_lies_in_each_fillets_refined_sector(cache):
    """Counterweight 2 (and its key) turned to 60°, the rest at 0°: the loads act in two
    planes, so the old geometric rule (``hot_axis``) has no single line and refines the whole
    ring (coarse: 182 868 dofs against 92 727; default 615 471 against 171 069). The beam pass
    gives each span fillet its own plane (bearing-seat-gear 15.4°, collar 47.5°). The 3D peak
    (von Mises and max principal, each located by the surface fit) lies within 5° of it
    (measured 1.4 / 2.5° and 0.9 / 0.7°): the beam plane ignores the transverse shear and the
    seat pressure, which move the peak a little; 5° is half the coarse level's refined sector
    (±10°), so the peak sits well inside the refined zone, where σ differs from its value on
    the plane by 1 − cos 5° = 0.4 % at most."""
    from shaftfe.solid.mesh import gmsh_version, mesh_key, mesh_plan
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import solve_static

    v = turned(load_variant("x2_57"), {"counterweight_2", "key_cw2"}, 60.0)
    assert hot_axis(prepare(v)) is None
    ax = mesh_hot_axes(v)
    res = solve_static(v, 10_000.0, StaticOptions(level="coarse"), beam=False, cache_dir=cache)
    # the mesh the static path used is the one refined about these planes (its key is that of
    # the plan carrying them), not the whole-ring one of the geometric rule
    plan = mesh_plan(v, "coarse", ax)
    assert dict(plan.hot_axes_deg) == {s: round(math.degrees(a), 1)
                                       for s, a in ax.items() if a is not None}
    assert res.mesh_key == mesh_key(plan, "coarse", 2, gmsh_version())
    assert res.mesh_key != mesh_key(mesh_plan(v, "coarse"), "coarse", 2, gmsh_version())
    peaks = {p.region: p for p in res.cases[0].peaks}
    sector = LEVELS["coarse"].sector_deg
    for seg in ("bearing_seat_gear", "collar"):
        plane = math.degrees(ax[seg])
        p = peaks[f"fillet:{seg}"]
        for xyz in (p.xyz_mm, p.max_principal_xyz_mm):
            theta = math.degrees(math.atan2(xyz[2], xyz[1]))
            assert line_diff_deg(theta, plane) < 0.5 * sector
