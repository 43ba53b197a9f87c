"""Bending planes for the 3D mesher: where around each fillet's ring the stress peaks.

The nominal bending stress of a round section under the moment vector (0, M_y, M_z) is
σ_x(θ) = (M_y sin θ − M_z cos θ) r / I at angle θ from +y (right-handed: a load along +y at
angle φ gives M_y = −s sin φ, M_z = s cos φ), so it peaks on the line θ* = atan2(M_y, −M_z)
(both senses: tension on one side, compression on the other). ``hot_axes`` takes M_y, M_z at
each fillet from one beam solve of the same variant (loads, bearing 2×2 springs, tilt
stiffness): the 3D mesher refines a sector about θ* instead of a fixed angle.

What moves the plane: several load directions (each fillet sees its own resultant moment);
bearing tilt stiffness or more than two bearings (the reactions then depend on the
stiffnesses, K12 included). With two tilt-free bearings the reactions follow from statics
alone, so K12 cannot rotate the plane (measured on x2_57 with the loads turned by 0/30/45/90°:
θ* = the load angle to 1e-12°). The beam solve carries every load of the variant
(``shaftfe.model.loads``: the parts' forces at their centroids, the ``[[loads]]``) at
``REF_RPM`` with every other load at its written magnitude: when loads of different speed laws
act in different planes the plane depends on the case, and this is the one the mesher
refines (spin softening, off here, would turn it by the deflection's share of the load, ~1 %).
A plane within ``SNAP_RAD`` of π is reported as 0 (the same line; the sign of a round-off
moment must not change the mesh).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shaftfe.beam.solve import analyse
from shaftfe.errors import InputError, SolverError
from shaftfe.model.variant import content_hash
from shaftfe.solid.features import groove_region
from shaftfe.solid.plan import prepare
from shaftfe.util import paths
from shaftfe.util.atomic import write_atomic
from shaftfe.util.cachefile import code_fingerprint
from shaftfe.util.notices import raised, warn
from shaftfe.util.units import REF_RPM

MIN_SHARE = 1e-3              # |M| below this share of the largest: no plane (whole ring hot)
SNAP_RAD = 1e-9               # a line at π − 1e-9 rad is the line at 0 (round-off of M_y)
# the cached axes' key holds the source of these modules (``util.cachefile.code_fingerprint``):
# a change of the beam, the loads or the plan gives new axes, never stale ones; bump
# AXES_FORMAT when the stored JSON changes meaning
AXES_MODULES = ("shaftfe.beam.planes", "shaftfe.beam.solve", "shaftfe.beam.model",
                "shaftfe.beam.elements", "shaftfe.model.loads", "shaftfe.solid.plan",
                "shaftfe.util.units")
AXES_FORMAT = 2


def hot_axes(variant, fillets) -> dict[str, float | None]:
    """{segment: θ* in rad (a line: [0, π)) or None} for ``fillets`` (objects with
    ``segment`` and ``x_shoulder``, e.g. ``shaftfe.solid.plan.Fillet``), from one beam solve of
    ``variant`` at its own options (bearing springs). None where the moment there is below
    ``MIN_SHARE`` of the shaft's largest (no bending to follow)."""
    x, My, Mz, top = section_moments(variant)
    out: dict[str, float | None] = {}
    for fl in fillets:
        my = float(np.interp(fl.x_shoulder, x, My))
        mz = float(np.interp(fl.x_shoulder, x, Mz))
        if not top > 0 or math.hypot(my, mz) < MIN_SHARE * top:
            out[fl.segment] = None
        else:
            th = tension_side(my, mz) % math.pi
            out[fl.segment] = 0.0 if math.pi - th < SNAP_RAD else th
    return out


def section_moments(variant) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """(x, M_y, M_z, max |M|) along the shaft from one beam solve of ``variant`` at
    ``REF_RPM`` on its bearing springs (rigid bearings where it has no valid springs: a
    rigid-support study), every other load at its written magnitude."""
    try:
        res = analyse(variant, REF_RPM)[0]
    except InputError:              # no valid springs (a rigid-support study): rigid bearings
        res = analyse(variant, REF_RPM, rigid_supports=True)[0]
    x, My, Mz = np.asarray(res.x_sec), np.asarray(res.My), np.asarray(res.Mz)
    return x, My, Mz, float(np.max(np.hypot(My, Mz))) if My.size else 0.0


def tension_side(my: float, mz: float) -> float:
    """The angle θ (rad, from +y towards +z) of a round section's tension side under the
    moment (0, M_y, M_z): where σ_x(θ) = (M_y sin θ − M_z cos θ) r / I peaks."""
    return math.atan2(my, -mz)


@dataclass(frozen=True)
class _Spot:
    """A groove's hot spot for ``hot_axes``: keyed by its region, at its middle."""
    segment: str
    x_shoulder: float


def mesh_hot_axes(variant, *, cache_dir=None, use_cache: bool = False
                  ) -> dict[str, float | None]:
    """``hot_axes`` of every fillet of ``variant``'s solid plan (keyed by segment) and every
    groove's (keyed by its region, at its middle): what the pipeline passes to ``build_mesh``
    (static, rotor, ``shaftfe mesh``, the static cache's key). A variant the beam cannot solve
    (no axial bearing: a geometry-only study) gets {} and so the mesher's geometric rule;
    every caller gets the same answer, hence one mesh per variant and level.

    ``use_cache``: read the axes from, or write them to, ``axes-<key>.json`` in the cache
    directory (``util.paths.cache_dir(cache_dir)``), keyed by the variant's content
    (``model.variant.content_hash``: its loads and bearings included), the source of
    ``AXES_MODULES`` and ``AXES_FORMAT``: a warm zoned solve then needs no beam solve (and no
    scipy.linalg import: 0.1 s). The values are the same floats either way (JSON keeps a
    float's every bit), and so are the warnings: the beam solve's (its deflection beyond the
    small-deflection range, the clearance, the torques: in the zoned default the only
    deflection check) are stored with the axes and raised again on a hit."""
    if not use_cache:
        return _mesh_hot_axes(variant)
    import hashlib
    import json

    key = hashlib.sha256(f"{AXES_FORMAT}|{content_hash(variant)}|"
                         f"{code_fingerprint(AXES_MODULES)}".encode()).hexdigest()[:24]
    path = paths.cache_dir(cache_dir) / f"axes-{key}.json"
    try:
        data = json.loads(path.read_text())
        axes, said = data["axes"], data["warnings"]
        if all(v is None or isinstance(v, float) for v in axes.values()):
            for w in said:
                warn(w["code"], w["where"], w["text"])
            return axes
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        pass
    with raised() as said:
        axes = _mesh_hot_axes(variant)
    try:
        write_atomic(path, json.dumps({"axes": axes, "warnings": said}, sort_keys=True))
    except OSError:
        pass                                   # a read-only cache only costs the time
    return axes


def _mesh_hot_axes(variant) -> dict[str, float | None]:
    try:
        plan = prepare(variant)
        return hot_axes(variant, [*plan.fillets, *(
            _Spot(groove_region(g.segment, g.index), 0.5 * (g.x0 + g.x1))
            for g in plan.grooves)])
    except (InputError, SolverError):
        return {}
