"""ONE set of rules for a variant, whoever made it (a TOML file, a notebook, a test).

``validate_variant(v)`` checks what every analysis assumes: contiguous segments of positive
length and diameter, a material with E > 0 and −1 < ν < 0.5, unique non-empty names, bearings
inside the shaft (a width of 0 is a point support: the beam's idealisation) with a symmetric
positive-definite 2×2 radial stiffness (a bearing that gives no stiffness in some direction
leaves the shaft free there: refused as input, in the beam and in 3D alike), attachments inside
the shaft with mass and eccentricity ≥ 0, keyways of positive size, grooves inside their
segment with a depth below a quarter of its diameter and a corner radius the groove holds, DIN
509 undercuts of the standard's size at a step up whose fillet is 0, and a hex socket at one
end, shorter than the shaft. The loader
(``shaftfe.model.loader.load_variant``) calls it after parsing; the beam, the solid plan and
the static model call it on the variant they are given.
The rules that need the solid's plan (a ring of positive width with a chamfer below a quarter
of it, a keyway inside the straight part of its segment, a contact band clear of the fillets,
the hex socket's corners) are the solid's construction rules: ``shaftfe.solid.plan.prepare``.

Each failure is one ``InputError(source, field, allowed, got)`` with the variant's first
source file as the source.
"""

from __future__ import annotations

import math

import numpy as np

from shaftfe.errors import InputError
from shaftfe.model import grooves
from shaftfe.model.fields import FILLET_MIN_MM
from shaftfe.model.loads import check_torque_path

TOL_X_MM = 1e-6       # mm: segment ends closer than this are the same station


def source_of(variant) -> str:
    """The file a variant came from (its first source), else ``variant <name>``."""
    return variant.source_files[0] if variant.source_files else f"variant {variant.name}"


def _finite(x) -> bool:
    try:
        return math.isfinite(float(x))
    except (TypeError, ValueError):
        return False


def _positive(src: str, fld: str, x) -> None:
    if not (_finite(x) and float(x) > 0):
        raise InputError(src, fld, "> 0", got=x)


def _nonneg(src: str, fld: str, x) -> None:
    if not (_finite(x) and float(x) >= 0):
        raise InputError(src, fld, ">= 0", got=x)


def _unique(src: str, what: str, names) -> None:
    seen: set[str] = set()
    for i, n in enumerate(names):
        if not n or n in seen or ":" in n:
            raise InputError(src, f"{what}[{i}].name", "unique, non-empty, without ':'", got=n)
        seen.add(n)


def _segments(v, src: str) -> tuple[float, float]:
    segs = v.segments
    if not segs:
        raise InputError(src, "segments", "at least one segment", got=0)
    _unique(src, "segments", [s.name for s in segs])
    for i, s in enumerate(segs):
        f = f"segments[{i}]"
        if not _finite(s.x_start_mm):
            raise InputError(src, f"{f}.x_start_mm", "a finite number", got=s.x_start_mm)
        _positive(src, f"{f}.length_mm", s.length_mm)
        _positive(src, f"{f}.diameter_mm", s.diameter_mm)
        _nonneg(src, f"{f}.fillet_mm", s.fillet_mm)
        if i and abs(s.x_start_mm - segs[i - 1].x_end_mm) > TOL_X_MM:
            raise InputError(src, f"{f}.x_start_mm", f"= x_end of segments[{i - 1}] "
                             f"({segs[i - 1].x_end_mm:g}): segments are contiguous",
                             got=s.x_start_mm)
        for j, k in enumerate(s.keyways):
            kf, r = f"{f}.keyways[{j}]", 0.5 * s.diameter_mm
            for name in ("width_mm", "depth_mm", "length_mm"):
                _positive(src, f"{kf}.{name}", getattr(k, name))
            if k.width_mm >= 1.6 * r:
                raise InputError(src, f"{kf}.width_mm", f"< 0.8 × diameter ({1.6 * r:g})",
                                 got=k.width_mm)
            if k.depth_mm >= 0.5 * r:
                raise InputError(src, f"{kf}.depth_mm", f"< radius / 2 ({0.5 * r:g})",
                                 got=k.depth_mm)
            if k.length_mm < k.width_mm + TOL_X_MM:
                raise InputError(src, f"{kf}.length_mm", f">= width ({k.width_mm:g})",
                                 got=k.length_mm)
            # the side walls' height: the depth less the sagitta of the surface over the width
            wall = k.depth_mm - (r - math.sqrt(max(r * r - 0.25 * k.width_mm ** 2, 0.0)))
            rb, rb_max = k.bottom_radius_mm, min(0.4 * k.width_mm, 0.5 * wall)
            if not (_finite(rb) and (rb == 0 or FILLET_MIN_MM <= rb <= rb_max)):
                # a flat bottom of at least a fifth of the width and a straight side wall of
                # at least half its height remain (beyond that it is no parallel-key seat)
                raise InputError(src, f"{kf}.bottom_radius_mm", f"0 (sharp) or "
                                 f"{FILLET_MIN_MM:g} … {rb_max:.3g} mm (≤ 0.4 × width and ≤ "
                                 "half the side wall's height)", got=rb)
        for side, c in (("left", s.chamfer_left_mm), ("right", s.chamfer_right_mm)):
            if not (_finite(c) and c >= 0):
                raise InputError(src, f"{f}.chamfer_{side}_mm", ">= 0", got=c)
            nb = (segs[i - 1] if i else None) if side == "left" else \
                (segs[i + 1] if i + 1 < len(segs) else None)
            if c > 0 and nb is not None and (nb.d_right_mm if side == "left" else
                                             nb.diameter_mm) >= s.diameter_mm - TOL_X_MM:
                raise InputError(src, f"{f}.chamfer_{side}_mm", "0 where the neighbouring "
                                 "segment is not smaller (a chamfer breaks an outer edge: the "
                                 "shaft's end or a step down)", got=c)
        _conical(src, f, segs, i)
        for j, g in enumerate(s.grooves):
            if g.kind in grooves.UNDERCUTS:
                _undercut(src, f"{f}.grooves[{j}]", segs, i, g)
            else:
                _groove(src, f"{f}.grooves[{j}]", s, g)
        for j, h in enumerate(s.cross_holes):
            _cross_hole(src, f"{f}.cross_holes[{j}]", s, h)
    return segs[0].x_start_mm, segs[-1].x_end_mm


def _groove(src: str, gf: str, s, g) -> None:
    """A groove's own rules (``model.grooves``); its place among the other features is the
    solid plan's (``solid.plan``)."""
    if g.kind not in grooves.BUILT:
        raise InputError(src, f"{gf}.kind", " | ".join(grooves.BUILT), got=g.kind)
    for name in ("width_mm", "depth_mm", "radius_mm", "x_center_mm"):
        if not _finite(getattr(g, name)):
            raise InputError(src, f"{gf}.{name}", "a finite number", got=getattr(g, name))
    _positive(src, f"{gf}.width_mm", g.width_mm)
    d = s.diameter_mm
    if not 0 < g.depth_mm < 0.25 * d:
        raise InputError(src, f"{gf}.depth_mm", f"0 < depth < radius / 2 ({0.25 * d:g}): a "
                         "deeper groove leaves a neck the shaft's models are not made for",
                         got=g.depth_mm)
    top = grooves.full_round(g.width_mm, g.depth_mm)
    if not FILLET_MIN_MM <= g.radius_mm <= top + TOL_X_MM:
        raise InputError(src, f"{gf}.radius_mm", f">= {FILLET_MIN_MM:g} and <= min(width / 2, "
                         f"depth) ({top:g})", got=g.radius_mm)
    lo, hi = g.x_center_mm - 0.5 * g.width_mm, g.x_center_mm + 0.5 * g.width_mm
    if lo < s.x_start_mm - TOL_X_MM or hi > s.x_end_mm + TOL_X_MM:
        raise InputError(src, f"{gf}.x_center_mm", f"groove [{lo:g}, {hi:g}] inside its "
                         f"segment [{s.x_start_mm:g}, {s.x_end_mm:g}]", got=g.x_center_mm)


def _conical(src: str, f: str, segs, i: int) -> None:
    """A conical segment (``diameter_right_mm``) is a plain transition: nothing cut into it
    (keyways, grooves, holes, chamfers) and no fillet where it meets a step (a fillet against a
    cone is not built); its seats and loads are refused by ``_off_cones``."""
    s = segs[i]
    if s.diameter_right_mm and not (_finite(s.diameter_right_mm) and s.diameter_right_mm > 0):
        raise InputError(src, f"{f}.diameter_right_mm", "> 0 (or absent: a cylinder)",
                         got=s.diameter_right_mm)
    if s.conical:
        half = math.degrees(math.atan(0.5 * abs(s.d_right_mm - s.diameter_mm) / s.length_mm))
        if half > TAPER_MAX_DEG:
            raise InputError(src, f"{f}.diameter_right_mm", f"a cone of half-angle <= "
                             f"{TAPER_MAX_DEG:g}° over its length {s.length_mm:g} mm (a steeper "
                             "one is a step: give a step with its fillet)",
                             got=s.diameter_right_mm, reason=f"makes a {half:.1f}° cone")
        for name, what in (("keyways", "keyways"), ("grooves", "grooves"),
                           ("cross_holes", "cross holes")):
            if getattr(s, name):
                raise InputError(src, f"{f}.{name}", f"no {what} on a conical segment (only "
                                 "on a cylinder)", got=len(getattr(s, name)))
        for side in ("left", "right"):
            if getattr(s, f"chamfer_{side}_mm"):
                raise InputError(src, f"{f}.chamfer_{side}_mm", "0 on a conical segment",
                                 got=getattr(s, f"chamfer_{side}_mm"))
    for k in (i - 1, i):                  # the steps at this segment's ends
        if 0 <= k < len(segs) - 1 and (segs[k].conical or segs[k + 1].conical) \
                and abs(segs[k].d_right_mm - segs[k + 1].diameter_mm) > TOL_X_MM \
                and segs[k].fillet_mm > 0:
            raise InputError(src, f"segments[{k}].fillet_mm", "0 at a step beside a conical "
                             "segment (a fillet against a cone is not built)",
                             got=segs[k].fillet_mm)


# a cone steeper than this is a step whose concave kink (180° + the half-angle) is as strong a
# singularity as a sharp shoulder's is not far from: give it as a step with its fillet
TAPER_MAX_DEG = 30.0


def _off_cones(v, src: str) -> None:
    """No bearing, part seat, ``[[loads]]`` band or hex socket on a conical segment: a seat
    is a cylinder here (a tapered fit is not built)."""
    cones = [(s.x_start_mm, s.x_end_mm, s.name) for s in v.segments if s.conical]
    if not cones:
        return
    spans = [(f"bearings[{i}].x_center_mm", b.x_center_mm - 0.5 * b.width_mm,
              b.x_center_mm + 0.5 * b.width_mm) for i, b in enumerate(v.bearings)]
    spans += [(f"attachments[{i}].seat_x", *sorted((a.seat_x_start_mm, a.seat_x_end_mm)))
              for i, a in enumerate(v.attachments)]
    spans += [(f"loads[{i}].band_mm", *ld.band_mm) for i, ld in enumerate(v.loads)
              if ld.kind != "gravity"]
    h = v.hex_socket
    if h is not None:
        x0, x1 = v.segments[0].x_start_mm, v.segments[-1].x_end_mm
        spans.append(("hex_socket.depth_mm", *((x0, x0 + h.depth_mm) if h.end == "left"
                                               else (x1 - h.depth_mm, x1))))
    for fld, a, b in spans:
        for c0, c1, name in cones:
            if a < c1 - TOL_X_MM and c0 < b - TOL_X_MM:
                raise InputError(src, fld, f"clear of the conical segment {name!r} [{c0:g}, "
                                 f"{c1:g}] (a seat is a cylinder)", got=(a, b))


def _undercut(src: str, gf: str, segs, i: int, g) -> None:
    """A DIN 509 undercut's own rules: at the segment's ``side`` end, next to a larger
    segment, that shoulder without a fillet (the undercut is its transition), its size a row
    of the standard's table for the segment's diameter, its centre where that places it."""
    s = segs[i]
    if g.side not in ("left", "right"):
        raise InputError(src, f"{gf}.side", "left | right", got=g.side)
    if sum(h.kind in grooves.UNDERCUTS and h.side == g.side for h in s.grooves) > 1:
        raise InputError(src, f"{gf}.side", f"one undercut at the segment's {g.side} end",
                         got=g.side, reason="repeats another undercut there")
    k = i - 1 if g.side == "left" else i + 1
    if not 0 <= k < len(segs) or (segs[k].d_right_mm if k < i else segs[k].diameter_mm) \
            <= s.diameter_mm + TOL_X_MM:
        raise InputError(src, f"{gf}.side", "the segment's end at a step up to a larger "
                         "segment (DIN 509 undercuts the smaller cylinder at the larger one's "
                         "face)", got=g.side)
    owner = min(i, k)                       # the segment whose fillet_mm is that shoulder's
    if segs[owner].fillet_mm > 0:
        raise InputError(src, f"segments[{owner}].fillet_mm", "0 where a DIN 509 undercut is "
                         "the shoulder's transition (its radius is the undercut's)",
                         got=segs[owner].fillet_mm)
    want = grooves.din509_groove(g.kind, s.diameter_mm, g.side, (s.x_start_mm, s.x_end_mm),
                                 g.radius_mm)
    if want is None or any(abs(getattr(g, k) - getattr(want, k)) > 1e-9
                           for k in ("width_mm", "depth_mm", "face_depth_mm")):
        rows = ", ".join(f"R{r.r:g}×{r.t1:g} f {r.f:g}" for r in grooves.din509_rows(
            s.diameter_mm)) or "none"
        raise InputError(src, f"{gf}.radius_mm", f"a row of DIN 509 for diameter "
                         f"{s.diameter_mm:g} ({rows}), with its t1, f and t2",
                         got=(g.radius_mm, g.depth_mm, g.width_mm, g.face_depth_mm))
    if abs(g.x_center_mm - want.x_center_mm) > TOL_X_MM:
        raise InputError(src, f"{gf}.x_center_mm", f"{want.x_center_mm:g}: the middle of the "
                         f"undercut's opening f at the {g.side} end", got=g.x_center_mm)


# a cross hole wider than this × the shaft's diameter leaves the charts (Peterson's and
# DIN 743-2's α of a transverse hole are given to d_h/d ≈ 0.3-0.4) and a shaft no one designs
CROSS_HOLE_MAX = 0.4


def _cross_hole(src: str, hf: str, s, h) -> None:
    for name in ("diameter_mm", "x_center_mm", "angle_deg"):
        if not _finite(getattr(h, name)):
            raise InputError(src, f"{hf}.{name}", "a finite number", got=getattr(h, name))
    d = s.diameter_mm
    if not 0 < h.diameter_mm <= CROSS_HOLE_MAX * d:
        raise InputError(src, f"{hf}.diameter_mm", f"0 < diameter <= {CROSS_HOLE_MAX:g} × the "
                         f"segment's diameter ({CROSS_HOLE_MAX * d:g}: the charts' range)",
                         got=h.diameter_mm)
    a = 0.5 * h.diameter_mm
    if h.x_center_mm - a < s.x_start_mm - TOL_X_MM or h.x_center_mm + a > s.x_end_mm + TOL_X_MM:
        raise InputError(src, f"{hf}.x_center_mm", f"hole [{h.x_center_mm - a:g}, "
                         f"{h.x_center_mm + a:g}] inside its segment [{s.x_start_mm:g}, "
                         f"{s.x_end_mm:g}]", got=h.x_center_mm)


def _material(v, src: str) -> None:
    m = v.material
    _positive(src, "material.E_MPa", m.E_MPa)
    if not (_finite(m.nu) and -1.0 < m.nu < 0.5):
        raise InputError(src, "material.nu", "-1 < nu < 0.5", got=m.nu)


def check_bearing_stiffness(K, src: str, fld: str) -> None:
    """A symmetric positive-definite 2×2 radial stiffness (N/mm)."""
    try:
        A = np.asarray(K, dtype=float)
    except (TypeError, ValueError):
        A = np.full(1, np.nan)
    if A.shape != (2, 2) or not np.all(np.isfinite(A)) or not np.allclose(A, A.T, rtol=1e-12) \
            or np.linalg.eigvalsh(0.5 * (A + A.T)).min() <= 0:
        raise InputError(src, fld, "a symmetric positive-definite 2×2 matrix",
                         got=A.tolist() if A.ndim == 2 else K)


def _bearings(v, src: str, x0: float, x1: float, springs: bool) -> None:
    _unique(src, "bearings", [b.name for b in v.bearings])
    for i, b in enumerate(v.bearings):
        f = f"bearings[{i}]"
        if not (_finite(b.x_center_mm) and x0 - 1e-9 <= b.x_center_mm <= x1 + 1e-9):
            raise InputError(src, f"{f}.x_center_mm", f"in [{x0:g}, {x1:g}]", got=b.x_center_mm)
        if springs:
            check_bearing_stiffness(b.K_N_per_mm, src, f"{f}.K_N_per_mm (bearing {b.name!r})")
        _nonneg(src, f"{f}.tilt_stiffness_Nmm_per_rad", b.tilt_stiffness_Nmm_per_rad)


def _attachments(v, src: str, x0: float, x1: float) -> None:
    _unique(src, "attachments", [a.name for a in v.attachments])
    for i, a in enumerate(v.attachments):
        f = f"attachments[{i}]"
        for name in ("seat_x_start_mm", "seat_x_end_mm", "angle_deg"):
            if not _finite(getattr(a, name)):
                raise InputError(src, f"{f}.{name}", "a finite number", got=getattr(a, name))
        lo, hi = sorted((a.seat_x_start_mm, a.seat_x_end_mm))
        if lo < x0 - 1e-9 or hi > x1 + 1e-9:
            raise InputError(src, f"{f}.seat", f"inside [{x0:g}, {x1:g}]",
                             got=(a.seat_x_start_mm, a.seat_x_end_mm))
        _nonneg(src, f"{f}.mass_kg", a.mass_kg)
        _nonneg(src, f"{f}.eccentricity_mm", a.eccentricity_mm)


def _loads(v, src: str, x0: float, x1: float) -> None:
    """The loads' positions on the shaft, and the torque path (``model.loads``)."""
    _unique(src, "loads", [ld.name for ld in v.loads] + [a.name for a in v.attachments])
    for i, ld in enumerate(v.loads):
        f = f"loads[{i}]"
        lo, hi = ld.band_mm
        if not (_finite(ld.x_mm) and x0 - 1e-9 <= lo <= ld.x_mm <= hi <= x1 + 1e-9):
            raise InputError(src, f"{f}.x_mm (load {ld.name!r})", f"on the shaft [{x0:g}, "
                             f"{x1:g}] mm, inside its band", got=ld.x_mm)
        if not _finite(ld.value):
            raise InputError(src, f"{f} (load {ld.name!r})", "a finite magnitude", got=ld.value)
    check_torque_path(v, src)


def _hex_socket(v, src: str, x0: float, x1: float) -> None:
    h = v.hex_socket
    if h is None:
        return
    if h.end not in ("left", "right"):
        raise InputError(src, "hex_socket.end", "left | right", got=h.end)
    _positive(src, "hex_socket.across_flats_mm", h.across_flats_mm)
    _positive(src, "hex_socket.depth_mm", h.depth_mm)
    if h.depth_mm >= x1 - x0 - TOL_X_MM:
        raise InputError(src, "hex_socket.depth_mm", "< shaft length", got=h.depth_mm)


def validate_variant(variant, *, springs: bool = True) -> None:
    """Raise ``InputError`` on the first rule ``variant`` breaks (see the module docstring).
    ``springs=False``: a model on rigid supports, which never reads the bearing stiffness."""
    src = source_of(variant)
    x0, x1 = _segments(variant, src)
    _material(variant, src)
    _bearings(variant, src, x0, x1, springs)
    _attachments(variant, src, x0, x1)
    _loads(variant, src, x0, x1)
    _hex_socket(variant, src, x0, x1)
    _off_cones(variant, src)
    cs = variant.clearance_station_x_mm
    if cs is not None and not (x0 - 1e-9 <= cs <= x1 + 1e-9):
        raise InputError(src, "clearance_station_x_mm", f"in [{x0:g}, {x1:g}]", got=cs)
