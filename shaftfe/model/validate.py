"""ONE set of rules for a variant, whoever made it (a TOML file, a notebook, a test).

``validate_variant(v)`` checks what every analysis assumes of a Variant's fields (the parser,
``model.parse``, keeps only what the Variant does not hold: types, keys, references, the
[duty] table, the [balance] statement, a bearing record's catalogue data and its stiffness
against them, a part's shape, the standards' tables): segments contiguous, of positive and plausible
length and diameter, no wider than the bar stock, of a known kind, each fillet 0 or at least
``FILLET_MIN_MM`` and no larger than its step (0 where there is none); keyways of positive
size inside their segment; grooves inside their segment with a depth below a quarter of its
diameter and a corner radius the groove holds; DIN 509 undercuts of the standard's size at a
step up whose fillet is 0; cross holes within the charts; cones and their neighbours; the
material's record (E, ν, density, strengths, group, its size and case data); each bearing's
own data (a finite, symmetric, positive-definite 2×2 radial stiffness; width, ratings, bore,
life exponent, the ring's chamfer against its ISO 15 corner) and its place (its centre on the
shaft, on a seat of its bore, clear of the other rings, one axial bearing, the shoulder fillet
its ring abuts no larger than that corner: ISO 582); attachments with finite data, a seat on
the shaft, plausible mass and eccentricity, a centroid beside the shaft, inertias ≥ 0; the
loads' positions and torque path; a hex socket at one end, its corners inside the end's
diameter, shorter than the shaft; the parting plane and the clearance station on the shaft.
An r_s min of 0 is not given; in a model made for a solver (untyped, below), so is a
bore, and a width of 0 is a point support (the beam's idealisation).

The plausible ranges (``fields.PLAUSIBLE``: a diameter in metres, a mass in grams, a stiffness
in N/m, a density in kg/mm³) catch a unit slip in typed values, and a typed design states all
of itself (a bore and a width for each bearing, exactly one axial bearing): ``typed=True``,
the loader, ``--set``, a study, a check by hand. The solvers check the variant they are
given with ``typed=False`` and take any value they can solve (a point support, a massless
shaft, a stiffness of 1e12 N/mm, no axial bearing: their own error then).

The rules that need the solid's plan (a ring of positive width, a keyway inside the straight
part of its segment, a contact band clear of the fillets, the hex socket's corners against the
keyways) are the solid's construction rules: ``shaftfe.solid.plan.prepare``, which calls this
first.

Each failure is one ``InputError(source, field, allowed, got)`` naming the field as the
Variant holds it and the variant's first source file (``source_of``); the loader re-words it
to the file and the key the value was written under (``shaftfe.model.origins``).
"""
from __future__ import annotations

import itertools
import math

import numpy as np

from shaftfe.errors import InputError
from shaftfe.model import grooves
from shaftfe.model.bearing_stiffness import radial_eigenvalues
from shaftfe.model.fields import FILLET_MIN_MM, plausible
from shaftfe.model.loads import check_torque_path

TOL_X_MM = 1e-6       # mm: segment ends closer than this are the same station


def source_of(variant) -> str:
    """The file a variant came from (its first source), else ``variant <name>``."""
    return first_source(variant.source_files, variant.name)


def first_source(files, name: str) -> str:
    """``source_of`` a variant of ``files`` (in the order read) and ``name``."""
    return files[0] if files else f"variant {name}"


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


def _plausible(x, kind: str, src: str, fld: str, typed: bool) -> None:
    """A finite number, and with ``typed`` in ``fields.PLAUSIBLE[kind]`` (else a unit slip,
    named as one: ``validate_variant``'s ``typed``)."""
    if not _finite(x):
        raise InputError(src, fld, "a finite number", got=x)
    if typed:
        plausible(float(x), kind, src, fld)


def _unique(src: str, what: str, names) -> None:
    seen: set[str] = set()
    for i, n in enumerate(names):
        if not n or n in seen or ":" in n:
            raise InputError(src, f"{what}[{i}].name", "unique, non-empty, without ':'", got=n)
        seen.add(n)


def check_segments(segs, src: str, stock: float | None = None, *, typed: bool = True
                   ) -> tuple[float, float]:
    """The segments' rules (with their keyways, grooves, cross holes, chamfers and cones), on
    their own: the loader applies them before it places anything on the segments, so that a
    length typed in metres is named as such and not as the bearing it moved off the shaft.
    ``stock``: the bar's diameter (no segment wider); ``typed``: as ``validate_variant``.
    Returns the shaft's ends (x0, x1)."""
    if not segs:
        raise InputError(src, "segments", "at least one segment", got=0)
    if stock is not None and not (_finite(stock) and stock > 0):
        raise InputError(src, "stock_diameter_mm", "> 0 mm (or absent)", got=stock)
    _unique(src, "segments", [s.name for s in segs])
    for i, s in enumerate(segs):
        f = f"segments[{i}]"
        if not _finite(s.x_start_mm):
            raise InputError(src, f"{f}.x_start_mm", "a finite number", got=s.x_start_mm)
        _plausible(s.length_mm, "length_mm", src, f"{f}.length_mm", typed)
        _plausible(s.diameter_mm, "diameter_mm", src, f"{f}.diameter_mm", typed)
        _positive(src, f"{f}.length_mm", s.length_mm)
        _positive(src, f"{f}.diameter_mm", s.diameter_mm)
        _nonneg(src, f"{f}.fillet_mm", s.fillet_mm)
        if s.diameter_right_mm and _finite(s.diameter_right_mm):
            _plausible(s.diameter_right_mm, "diameter_mm", src, f"{f}.diameter_right_mm",
                       typed)
        for key in ("diameter_mm", "diameter_right_mm"):
            d = getattr(s, key)
            if stock is not None and d and d > stock + 1e-9:
                raise InputError(src, f"{f}.{key}", f"<= stock diameter {stock:g} mm", got=d)
        # a fillet is meshed at a fraction of its radius: a 1 µm "fillet" (a radius typed in
        # metres) would ask for millions of elements; below FILLET_MIN_MM it is a sharp corner
        if not (s.fillet_mm == 0 or s.fillet_mm >= FILLET_MIN_MM):
            raise InputError(src, f"{f}.fillet_mm", f"0 (sharp) or >= {FILLET_MIN_MM:g} mm "
                             "(typed in metres?)", got=s.fillet_mm)
        if s.kind not in SEGMENT_KINDS:
            raise InputError(src, f"{f}.kind", " | ".join(SEGMENT_KINDS), got=s.kind)
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
            if not _finite(k.x_center_mm):
                raise InputError(src, f"{kf}.x_center_mm", "a finite number", got=k.x_center_mm)
            lo, hi = k.x_center_mm - 0.5 * k.length_mm, k.x_center_mm + 0.5 * k.length_mm
            if not (s.x_start_mm - 1e-9 <= lo and hi <= s.x_end_mm + 1e-9):
                raise InputError(src, f"{kf}.x_center_mm", f"slot [{lo:g}, {hi:g}] inside the "
                                 f"segment [{s.x_start_mm:g}, {s.x_end_mm:g}]", got=k.x_center_mm)
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
    _step_fillets(segs, src)
    return segs[0].x_start_mm, segs[-1].x_end_mm


SEGMENT_KINDS = ("plain", "seat", "thread")


def _step_fillets(segs, src: str) -> None:
    """A shoulder fillet fits its step: no larger than the step's height nor than the
    smaller segment's length, and 0 where there is no step."""
    for i, (a, b) in enumerate(itertools.pairwise(segs)):
        fld = f"segments[{i}].fillet_mm"
        step = 0.5 * abs(a.d_right_mm - b.diameter_mm)
        if step < 1e-9:
            if a.fillet_mm != 0:
                raise InputError(src, fld, "0 (no step to the next segment)", got=a.fillet_mm)
            continue
        small = a if a.d_right_mm < b.diameter_mm else b
        if a.fillet_mm > min(step, small.length_mm) + 1e-12:
            raise InputError(src, fld, f"<= step height {step:g} and <= length of the smaller "
                             f"segment {small.length_mm:g}", got=a.fillet_mm)


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


# the standards' material groups a record may name (shaftfe.fatigue.fkm.GROUPS, without the
# guideline example's grey cast iron)
MATERIAL_GROUPS = ("case_hardening_steel", "qt_steel", "structural_steel")


def check_material(m, src: str, fld: str, *, typed: bool = True) -> None:
    """A material record's own rules (the variant's shaft material, every record of a
    materials file, an S-N card's ``material``): plausible E and strengths (a unit slip),
    0 < ν < 0.5, a density in t/mm³, ultimate >= yield, a known group, and the optional size
    and case data in their ranges."""
    for name in ("E_MPa", "nu", "density_t_mm3", "yield_MPa", "ultimate_MPa"):
        if not _finite(getattr(m, name)):
            raise InputError(src, f"{fld}.{name}", "a finite number", got=getattr(m, name))
    _plausible(m.E_MPa, "E_MPa", src, f"{fld}.E_MPa", typed)
    _positive(src, f"{fld}.E_MPa", m.E_MPa)
    if not 0.0 < m.nu < 0.5:
        raise InputError(src, f"{fld}.nu", "0 < nu < 0.5", got=m.nu)
    if typed and not 0 < m.density_t_mm3 < 1e-7:        # kg/mm³ is the usual slip
        raise InputError(src, f"{fld}.density_t_mm3", "0 < value < 1e-7 t/mm³",
                         got=m.density_t_mm3)
    _nonneg(src, f"{fld}.density_t_mm3", m.density_t_mm3)     # a massless model: 0
    _plausible(m.yield_MPa, "strength_MPa", src, f"{fld}.yield_MPa", typed)
    if not m.ultimate_MPa >= m.yield_MPa:
        raise InputError(src, f"{fld}.ultimate_MPa", f">= yield_MPa ({m.yield_MPa})",
                         got=m.ultimate_MPa)
    if m.group not in MATERIAL_GROUPS and m.group != "":
        raise InputError(src, f"{fld}.group", " | ".join(MATERIAL_GROUPS), got=m.group)
    for name, lo, hi, allowed in (
            ("strength_reference_diameter_mm", 1.0, 1000.0, "a diameter in [1, 1000] mm"),
            ("case_hardness_HRC", 20.0, 70.0, "in [20, 70]"),
            ("case_depth_mm", 0.05, 5.0, "a depth in [0.05, 5] mm")):
        x = getattr(m, name)
        if x is not None and not (_finite(x) and lo <= x <= hi):
            raise InputError(src, f"{fld}.{name}", allowed, got=x)


def _material(v, src: str, typed: bool) -> None:
    check_material(v.material, src, "material", typed=typed)
    for i, m in enumerate(v.materials):
        if m is not v.material:
            check_material(m, src, f"materials[{i}]", typed=typed)


def check_bearing_stiffness(K, src: str, fld: str, *, typed: bool = True) -> None:
    """A 2×2 radial stiffness (N/mm): finite, symmetric, positive definite, and with ``typed``
    both eigenvalues plausible (a typed spring softer than the bound leaves the shaft floating
    on a support the solver cannot tell from none: 1e-9 N/mm gave a residual of 5.6 instead of
    1e-8; one stiffer than it is a unit slip. The solvers themselves take 1e-1 … 1e12 N/mm:
    tests/test_stability.py)."""
    try:
        A = np.asarray(K, dtype=float)
    except (TypeError, ValueError):
        A = np.full(1, np.nan)
    if A.shape != (2, 2):
        raise InputError(src, fld, "[[K11, K12], [K21, K22]] in N/mm", got=K)
    if not np.all(np.isfinite(A)):
        raise InputError(src, fld, "finite stiffnesses in N/mm (a rigid support: "
                         "--rigid-supports)", got=A.tolist())
    (k11, k12), (k21, k22) = A.tolist()
    if abs(k12 - k21) > 1e-9 * max(abs(k11), abs(k22), 1.0) \
            or not np.allclose(A, A.T, rtol=1e-12):
        raise InputError(src, fld, "symmetric (K12 = K21)", got=A.tolist())
    if not (k11 > 0 and k22 > 0 and k11 * k22 - k12 * k21 > 0):
        raise InputError(src, fld, "positive definite (K11 > 0, K22 > 0, K11 K22 - K12² > 0)",
                          got=A.tolist())
    for kk in radial_eigenvalues(A.tolist()):
        _plausible(kk, "K_N_per_mm", src, f"{fld} (eigenvalue)", typed)


def _bearing_type(b, src: str, f: str, springs: bool, typed: bool) -> None:
    """A bearing's own data (its type's record: ring, ratings, stiffness, life exponent).
    Untyped (a model made for a solver), a width of 0 is a point support (the beam's
    idealisation) and a bore of 0 is not given."""
    if springs:
        check_bearing_stiffness(b.K_N_per_mm, src, f"{f}.K_N_per_mm (bearing {b.name!r})",
                                typed=typed)
    _nonneg(src, f"{f}.width_mm", b.width_mm)
    for name, kind in (("width_mm", "length_mm"), ("C_N", "C_N"), ("C0_N", "C_N"),
                       ("bore_mm", "diameter_mm")):
        # a typed design states them all; in a model made for a solver a width of 0 is a
        # point support and a bore of 0 is not given
        if typed or getattr(b, name) or name in ("C_N", "C0_N"):
            _plausible(getattr(b, name), kind, src, f"{f}.{name}", typed)
    _positive(src, f"{f}.C_N", b.C_N)
    _positive(src, f"{f}.C0_N", b.C0_N)
    _nonneg(src, f"{f}.tilt_stiffness_Nmm_per_rad", b.tilt_stiffness_Nmm_per_rad)
    if not (_finite(b.life_exponent) and 1.0 <= b.life_exponent <= 10.0):
        raise InputError(src, f"{f}.life_exponent", "in [1, 10] (ISO 281: 3 for ball, 10/3 "
                         "for roller bearings)", got=b.life_exponent)
    if not (_finite(b.chamfer_mm) and (b.chamfer_mm == 0 or 0.0 < b.chamfer_mm
                                       < 0.25 * b.width_mm)):
        raise InputError(src, f"{f}.chamfer_mm", f">= 0 and < width / 4 "
                         f"({0.25 * b.width_mm:g})", got=b.chamfer_mm)
    _nonneg(src, f"{f}.r_s_min_mm", b.r_s_min_mm)
    if not (b.r_s_min_mm <= b.chamfer_mm or b.chamfer_mm == 0):
        raise InputError(src, f"{f}.chamfer_mm", f">= r_s_min_mm ({b.r_s_min_mm:g}): an "
                         "actual chamfer is at least the ISO 15 minimum (or 0 = no chamfer "
                         "modelled)", got=b.chamfer_mm)


def _bearings(v, src: str, x0: float, x1: float, springs: bool, typed: bool) -> None:
    """Each bearing's own data, then its place: its ring on the shaft, on a seat of its bore
    (where the bore is given), clear of the other rings, one bearing holding the axial load, and
    the shoulder fillets its ring abuts no larger than the ring's corner (ISO 582)."""
    _unique(src, "bearings", [b.name for b in v.bearings])
    for i, b in enumerate(v.bearings):
        f = f"bearings[{i}]"
        _bearing_type(b, src, f, springs, typed)
        # its centre on the shaft (a support at an end is the beam's idealisation); the ring's
        # contact band on a seat is the solid's rule (``solid.plan``)
        if not (_finite(b.x_center_mm) and x0 - 1e-9 <= b.x_center_mm <= x1 + 1e-9):
            raise InputError(src, f"{f}.x_center_mm", f"on the shaft [{x0:g}, {x1:g}]",
                             got=b.x_center_mm)
        lo, hi = b.x_start_mm, b.x_end_mm
        if b.bore_mm:
            bad = [s.name for s in v.segments if s.x_end_mm > lo + 1e-9
                   and s.x_start_mm < hi - 1e-9 and abs(s.diameter_mm - b.bore_mm) > 1e-6]
            if bad:
                raise InputError(src, f"{f}.x_center_mm", f"a bearing seat of diameter = bore "
                                 f"{b.bore_mm:g} mm over [{lo:g}, {hi:g}]",
                                 got=f"{b.x_center_mm:g} (over {', '.join(bad)})")
    # a design states which bearing holds the axial load; a model made for a solver may leave
    # it to the solver (the first coupling, or a SolverError naming it)
    n_axial = sum(b.axial is True for b in v.bearings)
    if typed and v.bearings and n_axial != 1:
        raise InputError(src, "bearings[*].axial", "exactly one bearing with axial = true",
                         got=n_axial)
    order = sorted(range(len(v.bearings)), key=lambda i: v.bearings[i].x_center_mm)
    for i, j in itertools.pairwise(order):      # two rings cannot share a seat
        a, b = v.bearings[i], v.bearings[j]
        if a.x_end_mm > b.x_start_mm + 1e-9:
            raise InputError(src, f"bearings[{j}].x_center_mm ({b.name!r})", f"clear of "
                             f"bearing {a.name!r} (its ring ends at {a.x_end_mm:g} mm)",
                             got=b.x_center_mm)
    _abutment_fillets(v, src)


def _abutment_fillets(v, src: str) -> None:
    """The bearing's own abutment rule (ISO 582): the shaft fillet at the shoulder a ring
    abuts may not exceed the ring's corner r_s min (r_as max = r_s min), or the ring rides on
    the fillet instead of seating against the shoulder."""
    segs = v.segments
    for b in v.bearings:
        if b.r_s_min_mm <= 0:
            continue
        for i, (a, c) in enumerate(itertools.pairwise(segs)):
            if a.fillet_mm <= 0 or abs(a.diameter_mm - c.diameter_mm) < 1e-9:
                continue
            small, big = (a, c) if a.diameter_mm < c.diameter_mm else (c, a)
            at_ring = abs(a.x_end_mm - b.x_start_mm) <= a.fillet_mm + 1e-6 \
                or abs(a.x_end_mm - b.x_end_mm) <= a.fillet_mm + 1e-6
            if at_ring and abs(small.diameter_mm - b.bore_mm) < 1e-6 \
                    and big.diameter_mm > b.bore_mm and a.fillet_mm > b.r_s_min_mm + 1e-12:
                raise InputError(src, f"segments[{i}].fillet_mm", f"<= {b.r_s_min_mm:g} mm, "
                                 f"the corner radius r_s min of bearing {b.name!r} "
                                 f"({b.designation}) that abuts this shoulder (ISO 582)",
                                 got=a.fillet_mm)


# an attachment's centroid may lie beside its seat (a counterweight overhanging the shaft's
# end), but not further than this from the shaft: a position typed in the wrong unit
CENTROID_REACH_MM = 100.0


def _attachments(v, src: str, x0: float, x1: float, typed: bool) -> None:
    _unique(src, "attachments", [a.name for a in v.attachments])
    for i, a in enumerate(v.attachments):
        f = f"attachments[{i}]"
        for name in ("seat_x_start_mm", "seat_x_end_mm", "angle_deg", "x_centroid_mm",
                     "mass_kg", "eccentricity_mm", "polar_inertia_kg_mm2",
                     "diametral_inertia_kg_mm2"):
            if not _finite(getattr(a, name)):
                raise InputError(src, f"{f}.{name}", "a finite number", got=getattr(a, name))
        lo, hi = a.seat_x_start_mm, a.seat_x_end_mm
        if not hi > lo:
            raise InputError(src, f"{f}.seat_x_mm", "x_start < x_end", got=[lo, hi])
        if lo < x0 - 1e-9 or hi > x1 + 1e-9:
            raise InputError(src, f"{f}.seat_x_mm", f"on the shaft [{x0:g}, {x1:g}]",
                             got=[lo, hi])
        _plausible(a.mass_kg, "mass_kg", src, f"{f}.mass_kg", typed)
        _plausible(a.eccentricity_mm, "eccentricity_mm", src, f"{f}.eccentricity_mm", typed)
        _nonneg(src, f"{f}.mass_kg", a.mass_kg)
        _nonneg(src, f"{f}.eccentricity_mm", a.eccentricity_mm)
        if typed and not x0 - CENTROID_REACH_MM <= a.x_centroid_mm <= x1 + CENTROID_REACH_MM:
            raise InputError(src, f"{f}.x_centroid_mm", f"within {CENTROID_REACH_MM:g} mm of "
                             f"the shaft [{x0:g}, {x1:g}] (a part beside its seat)",
                             got=a.x_centroid_mm)
        _nonneg(src, f"{f}.polar_inertia_kg_mm2", a.polar_inertia_kg_mm2)
        _nonneg(src, f"{f}.diametral_inertia_kg_mm2", a.diametral_inertia_kg_mm2)


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
    end = v.segments[-1] if h.end == "right" else v.segments[0]
    corners = 2.0 * h.across_flats_mm / math.sqrt(3.0) if _finite(h.across_flats_mm) else 0.0
    if not (_finite(h.across_flats_mm) and 0 < h.across_flats_mm
            and corners < end.diameter_mm):
        raise InputError(src, "hex_socket.across_flats_mm", f"> 0 with across-corners "
                         f"{corners:.3f} < end diameter {end.diameter_mm:g}",
                         got=h.across_flats_mm)
    if not (_finite(h.depth_mm) and 0 < h.depth_mm < x1 - x0 - TOL_X_MM):
        raise InputError(src, "hex_socket.depth_mm", f"0 < depth < shaft length {x1 - x0:g}",
                         got=h.depth_mm)


def validate_variant(variant, *, springs: bool = True, typed: bool = True) -> None:
    """Raise ``InputError`` on the first rule ``variant`` breaks (see the module docstring).
    ``springs=False``: a model on rigid supports, which never reads the bearing stiffness.
    ``typed=False``: leave out the plausible ranges (``fields.PLAUSIBLE``: a diameter in
    metres, a mass in grams, a stiffness in N/m), which catch a unit slip in what a person
    typed (the loader, ``--set``, a study, a Variant checked here by hand), but not a value a
    solver can take: the solvers check the variant they are given with ``typed=False`` (their
    stability tests sweep a bearing's stiffness from 0.1 to 1e12 N/mm)."""
    src = source_of(variant)
    x0, x1 = check_segments(variant.segments, src, variant.stock_diameter_mm, typed=typed)
    _material(variant, src, typed)
    _bearings(variant, src, x0, x1, springs, typed)
    _attachments(variant, src, x0, x1, typed)
    _loads(variant, src, x0, x1)
    _hex_socket(variant, src, x0, x1)
    _off_cones(variant, src)
    cs = variant.clearance_station_x_mm
    if cs is not None and not (x0 - 1e-9 <= cs <= x1 + 1e-9):
        raise InputError(src, "clearance_station_x_mm", f"on the shaft [{x0:g}, {x1:g}]",
                         got=cs)
    pp = variant.parting_plane_x_mm
    if not (_finite(pp) and x0 - 1e-9 <= pp <= x1 + 1e-9):
        raise InputError(src, "parting_plane_x_mm", f"on the shaft [{x0:g}, {x1:g}]", got=pp)
