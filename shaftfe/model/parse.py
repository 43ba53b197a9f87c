"""TOML → ``Variant``: read ``geometry/<name>.toml`` with its includes, parse every field (types,
known keys, references to the shared tables of materials, bearing types and parts, the
standards' tables of DIN 471 and DIN 509, provenance), then apply the variant's rules
(``shaftfe.model.validate.validate_variant``: one set, for a Variant however it was made, and
the solid's construction rules, ``shaftfe.solid.plan.prepare``) with their errors named in the
file and under the key the value was written (``shaftfe.model.origins``), each bearing's
stiffness against its own catalogue data, and the variant's [balance] statement.
``shaftfe.model.loader.load_variant`` adds what follows from a run's overrides first."""

from __future__ import annotations

import dataclasses
import math
import tomllib
from pathlib import Path
from types import MappingProxyType

from shaftfe.errors import InputError
from shaftfe.model import bearing_stiffness as bs
from shaftfe.model import grooves
from shaftfe.model import overrides as ov
from shaftfe.model.fields import (
    PROV_KEYS,
    Ctx,
    check_keys,
    is_num,
    need,
    num,
    provenance,
    table,
    text,
)
from shaftfe.model.loads import read_load_cases, read_loads
from shaftfe.model.mass import balance_ratio, mass_properties
from shaftfe.model.origins import Origins
from shaftfe.model.validate import (
    check_material,
    check_segments,
    first_source,
    validate_variant,
)
from shaftfe.model.variant import (
    Attachment,
    BalanceTarget,
    Bearing,
    CrossHole,
    Duty,
    Groove,
    HexSocket,
    Keyway,
    Material,
    Provenance,
    Segment,
    Variant,
    content_hash,
)
from shaftfe.util.paths import COMMON_DIR, GEOMETRY_DIR  # the variant files (geometry/)

_TABLE_KINDS = {"materials", "bearing_types", "parts"}       # merged across files by sub-key
# the file named on the command line may include a whole variant and add to it (its loads):
# it then names itself; every other key is still defined in one file only
_TOP_MAY_RENAME = {"name", "description"}
def list_variants(directory: str | Path | None = None) -> list[str]:
    """Names of the variant files in ``geometry/`` (``<name>.toml``; ``common/`` excluded)."""
    d = Path(directory) if directory is not None else GEOMETRY_DIR
    return sorted(p.stem for p in d.glob("*.toml") if p.is_file())


def one_of(names, table: str) -> str:
    """The allowed values of a field naming an entry of ``[table.*]``: never an empty list
    (an empty or missing included file defines none: say so)."""
    if names:
        return "one of " + ", ".join(sorted(names))
    return f"a name defined in [{table}.*] (none is: is an included file empty or missing?)"


def check_new_name(name: str) -> None:
    """A new variant's name. Rules (issue #30): letters, digits, _ and -, starting with a
    letter or digit (``-rf`` would be read as an option by every command that takes it); and
    not the name of a variant already in geometry/ (two files of one name: ``--variant NAME``
    would pick one of them silently), wherever --out writes it."""
    import re

    if not re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9_-]*", name):
        raise InputError("command line", "NAME", "letters, digits, _ and -, starting with a "
                         "letter or digit", got=name)
    # case-insensitive: X2_31 beside x2_31 is one file on a case-insensitive file system
    # (macOS, Windows) and two look-alike names elsewhere
    same = next((v for v in list_variants() if v.casefold() == name.casefold()), None)
    if same is not None:
        raise InputError("command line", "NAME", "a name no variant in geometry/ has yet, "
                         f"in any letter case (geometry/{same}.toml exists)", got=name)


def resolve_path(name_or_path: str | Path) -> Path:
    text = str(name_or_path)
    p = Path(text)
    if text.endswith(".toml") or "/" in text or p.exists():
        if not p.is_file():
            raise InputError(text, "path", "an existing .toml variant file", got=text)
        return p
    cand = GEOMETRY_DIR / f"{text}.toml"
    if not cand.is_file():
        raise InputError("variant", "name", f"one of {list_variants()} or a path to a .toml",
                         got=text)
    return cand


def _read_toml(path: Path, shown: str) -> dict:
    try:
        raw = path.read_bytes()
        text = raw.decode("utf-8-sig")       # a BOM from a Windows editor is tolerated
        return tomllib.loads(text)
    except UnicodeDecodeError as exc:
        raise InputError(shown, "file", "a UTF-8 text file (TOML)",
                         reason=f"is not UTF-8 text (byte 0x{raw[exc.start]:02x} at offset "
                         f"{exc.start}: a binary file, or saved as Latin-1/CP1250?)") from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError(shown, "file", "valid TOML", reason=f"is not valid TOML ({exc})") \
            from None
    except OSError as exc:
        raise InputError(shown, "file", "a readable file", reason=f"cannot be read ({exc})") \
            from None


def _show(path: Path) -> str:
    try:
        return str(path.resolve().relative_to(Path.cwd().resolve()))
    except ValueError:
        return str(path)


def _merge(path: Path, merged: dict, ctx: Ctx, stack: tuple[Path, ...]) -> None:
    shown = _show(path)
    doc = _read_toml(path, shown)
    ctx.files.append(shown)
    includes = doc.pop("include", [])
    if not isinstance(includes, list) or not all(isinstance(i, str) for i in includes):
        raise InputError(shown, "include", "a list of file names relative to this file",
                         got=includes)
    for i, inc in enumerate(includes):
        ip = (path.parent / inc).resolve()
        if not ip.is_file():
            raise InputError(shown, f"include[{i}]", "an existing file relative to this file",
                             got=inc)
        if ip in stack:
            raise InputError(shown, f"include[{i}]", "no include cycles", got=inc)
        _merge(ip, merged, ctx, (*stack, ip))
    for key, val in doc.items():
        if key in _TABLE_KINDS:
            if not isinstance(val, dict):
                raise InputError(shown, key, "a table of named entries", got=type(val).__name__)
            dest = merged.setdefault(key, {})
            for sub, entry in val.items():
                if sub in dest:
                    raise InputError(shown, f"{key}.{sub}", "defined once (in one file only)",
                                     reason=f"is also defined in {ctx.origin[f'{key}.{sub}']}")
                dest[sub] = entry
                ctx.origin[f"{key}.{sub}"] = shown
        else:
            if key in merged and not (len(stack) == 1 and key in _TOP_MAY_RENAME):
                raise InputError(shown, key, "defined once (in one file only)",
                                 reason=f"is also defined in {ctx.origin[key]}")
            merged[key] = val
            ctx.origin[key] = shown


def _material(name: str, t: dict, src: str, ctx: Ctx) -> Material:
    fld = f"materials.{name}"
    t = table(t, src, fld)
    check_keys(t, {"description", "E_MPa", "nu", "density_t_mm3", "yield_MPa",
                    "ultimate_MPa", "group", "heat_treatment", "strength_reference_diameter_mm",
                    "case_hardness_HRC", "case_depth_mm"}, src, fld)
    provenance(t, src, fld, fld, ctx)
    return Material(name=name, E_MPa=num(t, "E_MPa", src, fld), nu=num(t, "nu", src, fld),
                    density_t_mm3=num(t, "density_t_mm3", src, fld),
                    yield_MPa=num(t, "yield_MPa", src, fld),
                    ultimate_MPa=num(t, "ultimate_MPa", src, fld),
                    description=str(t.get("description", "")),
                    group=text(t, "group", src, fld, default=""),
                    heat_treatment=str(t.get("heat_treatment", "")),
                    strength_reference_diameter_mm=num(t, "strength_reference_diameter_mm", src,
                                                       fld, required=False),
                    case_hardness_HRC=num(t, "case_hardness_HRC", src, fld, required=False),
                    case_depth_mm=num(t, "case_depth_mm", src, fld, required=False))


def material_record(name: str, path=None) -> Material:
    """The record ``[materials.NAME]`` of a materials file (default: geometry/common/
    materials.toml), outside any variant (``--card NAME``, the S-N cards' ``material``)."""
    p = Path(path) if path is not None else COMMON_DIR / "materials.toml"
    mats = _read_toml(p, str(p)).get("materials", {})      # UTF-8, valid TOML, readable
    if name not in mats:
        raise InputError(str(p), "materials", one_of(mats, "materials"), got=name)
    m = _material(name, mats[name], str(p), Ctx())
    check_material(m, str(p), f"materials.{name}")        # the rules of every material record
    return m


def _segments(shaft: dict, src: str, ctx: Ctx) -> tuple[tuple[Segment, ...], list]:
    """The segments without their grooves, and each segment's table (``_with_grooves`` reads
    the grooves once the segments' own rules have passed: a DIN groove's size comes from its
    segment's diameter, which may be a unit slip)."""
    raw = shaft.get("segments")
    if not isinstance(raw, list) or not raw:
        raise InputError(src, "segments", "a non-empty list of [[shaft.segments]] tables",
                         got=raw)
    segs: list[Segment] = []
    tables: list = []
    x = num(shaft, "x_start_mm", src, "shaft", default=0.0) or 0.0
    for i, t in enumerate(raw):
        fld = f"segments[{i}]"
        t = table(t, src, fld)
        check_keys(t, {"name", "length_mm", "diameter_mm", "fillet_mm", "kind", "keyways",
                        "thread", "grooves", "cross_holes", "chamfer_left_mm",
                        "chamfer_right_mm", "diameter_right_mm"}, src, fld)
        name = text(t, "name", src, fld)
        provenance(t, src, fld, f"segments.{name}", ctx)
        length = num(t, "length_mm", src, fld)
        dia = num(t, "diameter_mm", src, fld)
        fil = num(t, "fillet_mm", src, fld, default=0.0)
        kind = text(t, "kind", src, fld, default="plain")
        dia_r = num(t, "diameter_right_mm", src, fld, default=0.0)
        kws: list[Keyway] = []
        need(isinstance(t.get("keyways", []), list), src, f"{fld}.keyways",
              "a list of [[...keyways]] tables", t.get("keyways"))
        for j, k in enumerate(t.get("keyways", [])):
            kf = f"{fld}.keyways[{j}]"
            k = table(k, src, kf)
            check_keys(k, {"width_mm", "depth_mm", "length_mm", "x_center_mm", "angle_deg",
                           "bottom_radius_mm"}, src, kf)
            provenance(k, src, kf, f"segments.{name}.keyways[{j}]", ctx)
            kw = Keyway(width_mm=num(k, "width_mm", src, kf),
                        depth_mm=num(k, "depth_mm", src, kf),
                        length_mm=num(k, "length_mm", src, kf),
                        x_center_mm=num(k, "x_center_mm", src, kf),
                        angle_deg=num(k, "angle_deg", src, kf, default=0.0) or 0.0,
                        bottom_radius_mm=num(k, "bottom_radius_mm", src, kf, default=0.0)
                        or 0.0)
            kws.append(kw)
        holes = _cross_holes(t, src, fld, name, ctx)
        tables.append((t, fld, name))
        segs.append(Segment(name=name, x_start_mm=x, length_mm=length, diameter_mm=dia,
                            fillet_mm=fil, keyways=tuple(kws), kind=kind, cross_holes=holes,
                            chamfer_left_mm=num(t, "chamfer_left_mm", src, fld, default=0.0),
                            chamfer_right_mm=num(t, "chamfer_right_mm", src, fld,
                                                 default=0.0),
                            diameter_right_mm=dia_r))
        x += length
    return tuple(segs), tables


def _with_grooves(segs: tuple[Segment, ...], tables: list, src: str, ctx: Ctx
                  ) -> tuple[Segment, ...]:
    """``segs`` with the grooves of their tables (``_segments``)."""
    return tuple(dataclasses.replace(s, grooves=_grooves(t, src, fld, name, s.diameter_mm, ctx,
                                                         (s.x_start_mm, s.x_end_mm)))
                 for s, (t, fld, name) in zip(segs, tables, strict=True))


def _grooves(t: dict, src: str, fld: str, name: str, dia: float,
             ctx: Ctx, ends: tuple[float, float]) -> tuple[Groove, ...]:
    """A segment's ``[[shaft.segments.grooves]]``: the kind, the centre and the dimensions the
    kind's standard does not fix (``shaftfe.model.grooves``); ``ends``: the segment's x."""
    raw = t.get("grooves", [])
    need(isinstance(raw, list), src, f"{fld}.grooves", "a list of [[...grooves]] tables", raw)
    out: list[Groove] = []
    for j, g in enumerate(raw):
        gf = f"{fld}.grooves[{j}]"
        g = table(g, src, gf)
        check_keys(g, {"kind", "x_center_mm", "width_mm", "depth_mm", "radius_mm", "side"},
                   src, gf)
        provenance(g, src, gf, f"segments.{name}.grooves[{j}]", ctx)
        kind = text(g, "kind", src, gf)
        need(kind in grooves.KINDS, src, f"{gf}.kind", " | ".join(grooves.KINDS), kind)
        need(kind in grooves.UNDERCUTS or "side" not in g, src, f"{gf}.side", "not given: "
             "only a DIN 509 undercut sits at a segment's end", g.get("side"))
        if kind in grooves.UNDERCUTS:
            out.append(_undercut(g, src, gf, kind, dia, ends))
            continue
        xc = num(g, "x_center_mm", src, gf)
        if kind == "din471":
            for key in ("width_mm", "depth_mm"):
                need(key not in g, src, f"{gf}.{key}", "not given: DIN 471 fixes it from the "
                     f"segment's diameter {dia:g} mm", g.get(key))
            std = grooves.din471(dia)
            need(std is not None, src, f"{gf}.kind", "din471 on a segment whose diameter is "
                 "in DIN 471's table (" + ", ".join(f"{d:g}" for d in grooves.DIN471) +
                 " mm)", f"din471 on diameter {dia:g}")
            w, dep = std
            rad = num(g, "radius_mm", src, gf, default=grooves.DIN471_CORNER_MM)
        else:
            w, dep = num(g, "width_mm", src, gf), num(g, "depth_mm", src, gf)
            rad = num(g, "radius_mm", src, gf, default=grooves.full_round(w, dep))
        # the ranges (depth, radius, inside the segment): model.validate, for every Variant
        out.append(Groove(kind, xc, w, dep, rad))
    return tuple(out)


def _undercut(g: dict, src: str, gf: str, kind: str, dia: float,
              ends: tuple[float, float]) -> Groove:
    """A DIN 509 undercut: ``side`` (the segment's end at the shoulder) and optionally
    ``radius_mm`` (another row of the table); the rest is the standard's."""
    for key in ("x_center_mm", "width_mm", "depth_mm"):
        need(key not in g, src, f"{gf}.{key}", "not given: DIN 509 places the undercut at the "
             "shoulder (side) and fixes its size from the segment's diameter", g.get(key))
    side = text(g, "side", src, gf)
    need(side in ("left", "right"), src, f"{gf}.side", "left | right (the segment's end at "
         "the step up to the larger segment)", side)
    rows = grooves.din509_rows(dia)
    need(bool(rows), src, f"{gf}.kind", "a DIN 509 undercut on a diameter DIN 509 assigns one "
         "(over 1.6 mm)", f"{kind} on diameter {dia:g}")
    rad = num(g, "radius_mm", src, gf, default=None) if "radius_mm" in g else None
    out = grooves.din509_groove(kind, dia, side, ends, rad)
    need(out is not None, src, f"{gf}.radius_mm", "a radius DIN 509 gives for diameter "
         f"{dia:g}: " + ", ".join(f"{r.r:g}" for r in rows), rad)
    return out


def _cross_holes(t: dict, src: str, fld: str, name: str, ctx: Ctx) -> tuple[CrossHole, ...]:
    """A segment's ``[[shaft.segments.cross_holes]]`` (their ranges: ``model.validate``)."""
    raw = t.get("cross_holes", [])
    need(isinstance(raw, list), src, f"{fld}.cross_holes", "a list of [[...cross_holes]] "
         "tables", raw)
    out: list[CrossHole] = []
    for j, h in enumerate(raw):
        hf = f"{fld}.cross_holes[{j}]"
        h = table(h, src, hf)
        check_keys(h, {"diameter_mm", "x_center_mm", "angle_deg"}, src, hf)
        provenance(h, src, hf, f"segments.{name}.cross_holes[{j}]", ctx)
        out.append(CrossHole(num(h, "diameter_mm", src, hf), num(h, "x_center_mm", src, hf),
                             num(h, "angle_deg", src, hf, default=0.0) or 0.0))
    return tuple(out)


def _stiffness_matrix(bt: dict, tsrc: str, tf: str):
    """A bearing type's 2×2 radial stiffness as numbers (its rules: finite, symmetric, positive
    definite, plausible: ``model.validate.check_bearing_stiffness``)."""
    K = bt.get("K_N_per_mm")
    ok = (isinstance(K, list) and len(K) == 2
          and all(isinstance(r, list) and len(r) == 2 and all(is_num(e) for e in r)
                  for r in K))
    need(ok, tsrc, f"{tf}.K_N_per_mm", "[[K11, K12], [K21, K22]] in N/mm", K)
    return (float(K[0][0]), float(K[0][1])), (float(K[1][0]), float(K[1][1]))


def _stiffness_plausible(bt: dict, tsrc: str, tf: str, bore: float, C: float, K) -> None:
    """The stated stiffness against the estimate from the bearing's own data (rule and its
    sources: ``shaftfe.model.bearing_stiffness``): a ball bearing's eigenvalues within
    1/20 … 3 × the estimate. A roller bearing has no estimate (no check)."""
    kind = text(bt, "rolling_element", tsrc, tf, default="ball")
    need(kind in bs.KINDS, tsrc, f"{tf}.rolling_element", " | ".join(bs.KINDS), kind)
    rows = num(bt, "rows", tsrc, tf, default=1.0)
    need(rows in (1, 2, 3, 4), tsrc, f"{tf}.rows", "1, 2, 3 or 4 rows of rolling elements", rows)
    alpha = num(bt, "contact_angle_deg", tsrc, tf, default=0.0)
    need(0.0 <= alpha <= 45.0, tsrc, f"{tf}.contact_angle_deg",
         "in [0, 45] deg (a radial bearing's nominal contact angle)", alpha)
    od = num(bt, "outer_diameter_mm", tsrc, tf, default=0.0) or 0.0
    need(od > bore, tsrc, f"{tf}.outer_diameter_mm", f"> the bore {bore:g} mm", od)
    if kind != "ball":
        return
    est = bs.estimate_ball(bore, od, C, int(rows), alpha)
    bs.check_stiffness(bs.radial_eigenvalues(K), est, tsrc, f"{tf}.K_N_per_mm",
                       bt.get("K_N_per_mm"))


def _ring(bt: dict, tsrc: str, tf: str):
    """A bearing type's width, bore, C, C0, tilt stiffness, life exponent, chamfer, r_s min
    (their rules: ``model.validate``)."""
    return (num(bt, "width_mm", tsrc, tf), num(bt, "bore_mm", tsrc, tf), num(bt, "C_N", tsrc, tf),
            num(bt, "C0_N", tsrc, tf),
            num(bt, "tilt_stiffness_Nmm_per_rad", tsrc, tf, default=0.0),
            num(bt, "life_exponent", tsrc, tf, default=3.0),
            num(bt, "chamfer_mm", tsrc, tf, default=0.0) or 0.0,
            num(bt, "r_s_min_mm", tsrc, tf, default=0.0) or 0.0)


# the Bearing fields its type's record ([bearing_types.<type>]) gives; the others (name, place,
# axial, holds_torsion) are the [[shaft.bearings]] table's
BEARING_TYPE_KEYS = frozenset({"designation", "width_mm", "C_N", "C0_N", "K_N_per_mm",
                               "tilt_stiffness_Nmm_per_rad", "life_exponent", "bore_mm",
                               "outer_diameter_mm", "chamfer_mm", "r_s_min_mm"})


def _bearings(shaft: dict, types: dict, ctx: Ctx, src: str, origins: Origins
              ) -> tuple[tuple[Bearing, ...], list]:
    """The bearings, sorted along x (where each one's fields were written: ``origins``), and
    the arguments of each one's stiffness check against its own catalogue data
    (``_stiffness_plausible``, run once the variant's rules have passed)."""
    raw = shaft.get("bearings")
    if not isinstance(raw, list) or len(raw) < 2:
        raise InputError(src, "bearings", "a list of at least two [[shaft.bearings]] tables",
                         got=raw if raw is None else len(raw))
    out: list[tuple[Bearing, int, str, str, tuple]] = []
    for i, t in enumerate(raw):
        fld = f"bearings[{i}]"
        t = table(t, src, fld)
        check_keys(t, {"name", "type", "x_center_mm", "axial", "holds_torsion"}, src, fld)
        name = text(t, "name", src, fld)
        provenance(t, src, fld, f"bearings.{name}", ctx)
        typ = text(t, "type", src, fld)
        if typ not in types:
            raise InputError(src, f"{fld}.type", one_of(types, "bearing_types"), got=typ)
        tsrc = ctx.file_of(f"bearing_types.{typ}", src)
        tf = f"bearing_types.{typ}"
        bt = table(types[typ], tsrc, tf)
        check_keys(bt, {"designation", "bore_mm", "outer_diameter_mm", "width_mm", "C_N",
                         "C0_N", "K_N_per_mm", "life_exponent", "tilt_stiffness_Nmm_per_rad",
                         "chamfer_mm", "r_s_min_mm", "rolling_element", "rows",
                         "contact_angle_deg"}, tsrc, tf)
        provenance(bt, tsrc, tf, tf, ctx)
        K = _stiffness_matrix(bt, tsrc, tf)
        width, bore, C, C0, tilt, p_life, chamfer, r_s_min = _ring(bt, tsrc, tf)
        axial = t.get("axial", False)
        need(isinstance(axial, bool), src, f"{fld}.axial", "true | false", axial)
        torsion = t.get("holds_torsion", False)
        need(isinstance(torsion, bool), src, f"{fld}.holds_torsion", "true | false", torsion)
        b = Bearing(
            name=name, designation=text(bt, "designation", tsrc, tf),
            x_center_mm=num(t, "x_center_mm", src, fld), width_mm=width, C_N=C, C0_N=C0,
            K_N_per_mm=K, axial=axial, tilt_stiffness_Nmm_per_rad=tilt, life_exponent=p_life,
            bore_mm=bore, outer_diameter_mm=num(bt, "outer_diameter_mm", tsrc, tf,
                                                 default=0.0) or 0.0, chamfer_mm=chamfer,
            r_s_min_mm=r_s_min, holds_torsion=torsion)
        out.append((b, i, tsrc, tf, (bt, tsrc, tf, bore, C, K)))
    out.sort(key=lambda e: e[0].x_center_mm)
    for k, (_, i, tsrc, tf, _) in enumerate(out):       # as the Variant holds them: sorted
        origins.add(f"bearings[{k}]", src, f"bearings[{i}]")
        origins.add_keys(f"bearings[{k}]", BEARING_TYPE_KEYS, tsrc, tf)
    origins.add("bearings", src, "bearings")
    return tuple(e[0] for e in out), [e[4] for e in out]


_ATT_KEYS = {"name", "part", "seat", "seat_x_mm", "mass_kg", "eccentricity_mm", "angle_deg",
             "x_centroid_mm", "polar_inertia_kg_mm2", "diametral_inertia_kg_mm2", "material",
             "seed_load_case", "shape", "description"}


def _attachment(t: dict, src: str, fld: str, segs: tuple[Segment, ...], mats: dict,
                ctx: Ctx, name: str) -> Attachment:
    check_keys(t, _ATT_KEYS, src, fld)
    provenance(t, src, fld, f"attachments.{name}", ctx)
    shape = t.get("shape")
    if shape is not None:
        shape = table(shape, src, f"{fld}.shape")
        provenance(shape, src, f"{fld}.shape", f"attachments.{name}.shape", ctx)
    seat_name = ""
    if "seat" in t:
        seat_name = text(t, "seat", src, fld)
        seg = next((s for s in segs if s.name == seat_name), None)
        if seg is None:
            raise InputError(src, f"{fld}.seat", "the name of a shaft segment: "
                             + ", ".join(s.name for s in segs), got=seat_name)
        lo, hi = seg.x_start_mm, seg.x_end_mm
    elif "seat_x_mm" in t:
        sx = t["seat_x_mm"]
        need(isinstance(sx, list) and len(sx) == 2 and all(is_num(e) for e in sx), src,
              f"{fld}.seat_x_mm", "[x_start, x_end] in mm", sx)
        lo, hi = float(sx[0]), float(sx[1])
    else:
        raise InputError(src, f"{fld}.seat", "a segment name (or seat_x_mm = [a, b])",
                         reason="is missing")
    if shape is not None:
        for k, val in shape.items():
            if k not in PROV_KEYS and k != "kind" and not (
                    is_num(val) and math.isfinite(float(val)) and float(val) >= 0):
                raise InputError(src, f"{fld}.shape.{k}", "a finite number >= 0", got=val)
    mat = text(t, "material", src, fld)
    if mat not in mats:
        raise InputError(src, f"{fld}.material", one_of(mats, "materials"), got=mat)
    slc = t.get("seed_load_case", False)
    need(isinstance(slc, bool), src, f"{fld}.seed_load_case", "true | false", slc)
    return Attachment(
        name=name, seat_x_start_mm=lo, seat_x_end_mm=hi, mass_kg=num(t, "mass_kg", src, fld),
        eccentricity_mm=num(t, "eccentricity_mm", src, fld),
        x_centroid_mm=num(t, "x_centroid_mm", src, fld),
        angle_deg=num(t, "angle_deg", src, fld, default=0.0) or 0.0,
        polar_inertia_kg_mm2=num(t, "polar_inertia_kg_mm2", src, fld, default=0.0) or 0.0,
        diametral_inertia_kg_mm2=num(t, "diametral_inertia_kg_mm2", src, fld, default=0.0)
        or 0.0, material=mat, seed_load_case=slc, seat_segment=seat_name)


def _hex_socket(shaft: dict, ssrc: str, ctx: Ctx) -> HexSocket | None:
    if "hex_socket" not in shaft:
        return None
    ht = table(shaft["hex_socket"], ssrc, "shaft.hex_socket")
    check_keys(ht, {"end", "across_flats_mm", "depth_mm"}, ssrc, "shaft.hex_socket")
    provenance(ht, ssrc, "shaft.hex_socket", "hex_socket", ctx)
    return HexSocket(end=text(ht, "end", ssrc, "shaft.hex_socket"),
                     across_flats_mm=num(ht, "across_flats_mm", ssrc, "hex_socket"),
                     depth_mm=num(ht, "depth_mm", ssrc, "hex_socket"))


def _attachments(merged: dict, segs: tuple[Segment, ...], mats: dict, ctx: Ctx, top: str,
                 origins: Origins) -> tuple[Attachment, ...]:
    """Shared parts named in use_parts, then the variant's own [[attachments]] (where each
    one was written: ``origins``)."""
    parts = merged.get("parts", {})
    atts: list[Attachment] = []
    use = merged.get("use_parts", [])
    usrc = ctx.file_of("use_parts", top)
    need(isinstance(use, list) and all(isinstance(u, str) for u in use), usrc, "use_parts",
          "a list of part names", use)
    for i, pn in enumerate(use):
        if pn not in parts:
            raise InputError(usrc, f"use_parts[{i}]", one_of(parts, "parts"), got=pn)
        psrc = ctx.file_of(f"parts.{pn}", top)
        origins.add(f"attachments[{len(atts)}]", psrc, f"parts.{pn}")
        atts.append(_attachment(table(parts[pn], psrc, f"parts.{pn}"), psrc, f"parts.{pn}",
                                segs, mats, ctx, pn))
    asrc = ctx.file_of("attachments", top)
    raw = merged.get("attachments", [])
    need(isinstance(raw, list), asrc, "attachments", "a list of [[attachments]] tables", raw)
    for i, t in enumerate(raw):
        fld = f"attachments[{i}]"
        t = table(t, asrc, fld)
        an = text(t, "name", asrc, fld)
        origins.add(f"attachments[{len(atts)}]", asrc, fld)
        atts.append(_attachment(t, asrc, fld, segs, mats, ctx, an))
    return tuple(atts)


def _balance_target(merged: dict, ctx: Ctx, top: str) -> BalanceTarget | None:
    if "balance" not in merged:
        return None
    bsrc = ctx.file_of("balance", top)
    bt = table(merged["balance"], bsrc, "balance")
    check_keys(bt, {"X2_percent", "mass_kg", "gamma2_mm", "x_T_mm", "m_pos_kg",
                     "crank_radius_mm"}, bsrc, "balance")
    provenance(bt, bsrc, "balance", "balance", ctx)
    target = BalanceTarget(
        X2_percent=num(bt, "X2_percent", bsrc, "balance"),
        mass_kg=num(bt, "mass_kg", bsrc, "balance"),
        gamma2_mm=num(bt, "gamma2_mm", bsrc, "balance"),
        x_T_mm=num(bt, "x_T_mm", bsrc, "balance"),
        m_pos_kg=num(bt, "m_pos_kg", bsrc, "balance", default=0.0) or 0.0,
        crank_radius_mm=num(bt, "crank_radius_mm", bsrc, "balance", default=0.0) or 0.0)
    return target


def parse_variant(name_or_path: str | Path, sets=()) -> Variant:
    """The variant at ``name_or_path`` (a name in ``geometry/`` or a path) with ``sets`` applied:
    the run's overrides as ``model.overrides.normalise`` gives them, with what follows from
    them already added (``model.derive.with_shape_derived``: ``model.loader.load_variant``
    does both). Read, its includes resolved, parsed, checked by the variant's rules; recorded
    in ``Variant.overrides``, an overridden value tagged in its provenance. Anything impossible
    raises ``InputError(file, field, allowed, got)``, naming the ``--set`` where an overridden
    value is out of its range."""
    path = resolve_path(name_or_path)
    ctx = Ctx()
    merged = resolved_dict(path, ctx)
    sets = ov.apply(merged, sets)
    if sets and "name" in {o.path for o in sets}:
        _check_name(merged["name"], sets)
    try:
        v = _build(path, merged, ctx)
    except InputError as exc:
        raise ov.attribute(exc, sets) from None
    if sets:
        # an overridden value is no longer what its file's provenance list says: tag it
        src = dict(v.provenance.source)
        for o in sets:
            key = ov.provenance_path(o.path)
            if key in src:
                src[key] = ov.PROVENANCE_TAG
        v = dataclasses.replace(
            v, overrides=tuple((o.path, o.value) for o in sets),
            provenance=Provenance(source=MappingProxyType(src), note=v.provenance.note))
    return v


def parts_variant(name_or_path: str | Path, overrides=()) -> Variant:
    """The variant with ``overrides`` applied, its [balance] statement NOT checked against the
    parts (``shaftfe.model.derive`` computes that statement from them)."""
    sets = ov.normalise(overrides)
    path = resolve_path(name_or_path)
    ctx = Ctx()
    merged = resolved_dict(path, ctx)
    sets = ov.apply(merged, sets)
    try:
        return _build(path, merged, ctx, check_balance=False)
    except InputError as exc:
        raise ov.attribute(exc, sets) from None


def _check_name(name, sets) -> None:
    """A variant name set on the command line names output folders: a plain file name."""
    import re
    o = next(o for o in sets if o.path == "name")
    if not isinstance(name, str) or not re.fullmatch(r"[A-Za-z0-9_][A-Za-z0-9_.+-]*", name):
        raise InputError(o.shown, "name", "letters, digits, _ . + - (a file name)", got=name)


def resolved_dict(path: Path, ctx: Ctx | None = None) -> dict:
    """The variant file at ``path`` with its includes merged in, as one TOML dictionary (what
    ``shaftfe variant new`` writes out); ``ctx`` collects which file defined what."""
    merged: dict = {}
    _merge(path.resolve(), merged, ctx if ctx is not None else Ctx(), (path.resolve(),))
    return merged


def _build(path: Path, merged: dict, ctx: Ctx, *, check_balance: bool = True) -> Variant:
    top = _show(path.resolve())
    allowed_top = {"name", "description", "shaft", "materials", "bearing_types", "parts",
                   "use_parts", "attachments", "balance", "loads", "load_cases", "duty"}
    for k in merged:
        if k not in allowed_top:
            raise InputError(ctx.file_of(k, top), k, "one of " + ", ".join(sorted(allowed_top)),
                             reason="is not a known top-level key")
    name = merged.get("name")
    if not isinstance(name, str) or not name:
        raise InputError(top, "name", "a non-empty string", got=name)
    desc = merged.get("description", "")

    mats_raw = merged.get("materials", {})
    mats = {k: _material(k, v, ctx.file_of(f"materials.{k}", top), ctx)
            for k, v in mats_raw.items()}
    if "shaft" not in merged:
        raise InputError(top, "shaft", "a [shaft] table (usually from an include)",
                         reason="is missing")
    ssrc = ctx.file_of("shaft", top)
    shaft = table(merged["shaft"], ssrc, "shaft")
    check_keys(shaft, {"name", "material", "stock_diameter_mm", "parting_plane_x_mm",
                        "clearance_station_x_mm", "clearance_to_crankshaft_mm", "x_start_mm",
                        "segments", "bearings", "hex_socket"}, ssrc, "shaft")
    provenance(shaft, ssrc, "shaft", "shaft", ctx)
    stock = num(shaft, "stock_diameter_mm", ssrc, "shaft", required=False)
    # where each part of the Variant was written: the rules name Variant fields, the error
    # names the file and the key as written (``model.origins``)
    origins = Origins(source=first_source(ctx.files, name))
    origins.add("segments", ssrc, "segments")
    origins.add("hex_socket", ssrc, "hex_socket")
    for key in ("parting_plane_x_mm", "clearance_station_x_mm"):
        origins.add(key, ssrc, f"shaft.{key}")
    for i, k in enumerate(sorted(mats)):
        origins.add(f"materials[{i}]", ctx.file_of(f"materials.{k}", top), f"materials.{k}")
    origins.add("loads", ctx.file_of("loads", top), "loads")
    segs, tables = _segments(shaft, ssrc, ctx)
    try:        # the segments' rules first: the rest is placed on them (and sized by them)
        check_segments(segs, origins.source, stock)
    except InputError as exc:
        raise origins.locate(exc) from None
    segs = _with_grooves(segs, tables, ssrc, ctx)
    smat = text(shaft, "material", ssrc, "shaft")
    if smat not in mats:
        raise InputError(ssrc, "shaft.material", one_of(mats, "materials"), got=smat)
    origins.add("material", ctx.file_of(f"materials.{smat}", top), f"materials.{smat}")
    bearings, stiffness_checks = _bearings(shaft, merged.get("bearing_types", {}), ctx, ssrc,
                                           origins)
    hs = _hex_socket(shaft, ssrc, ctx)
    pp = num(shaft, "parting_plane_x_mm", ssrc, "shaft")
    cs = num(shaft, "clearance_station_x_mm", ssrc, "shaft", required=False)
    atts = _attachments(merged, segs, mats, ctx, top, origins)
    target = _balance_target(merged, ctx, top)
    lsrc = ctx.file_of("loads", top)
    loads = read_loads(merged.get("loads", []), lsrc, segs, [a.name for a in atts], ctx)
    cases = read_load_cases(merged.get("load_cases", []), ctx.file_of("load_cases", top), loads)
    duty = _duty(merged, ctx, top)

    v = Variant(
        name=name, description=str(desc), segments=segs, bearings=bearings,
        attachments=atts, material=mats[smat], parting_plane_x_mm=pp, hex_socket=hs,
        clearance_station_x_mm=cs,
        provenance=Provenance(source=MappingProxyType(dict(ctx.source)),
                              note=MappingProxyType(dict(ctx.note))),
        source_files=tuple(ctx.files), materials=tuple(mats[k] for k in sorted(mats)),
        balance_target=target,
        clearance_mm=num(shaft, "clearance_to_crankshaft_mm", ssrc, "shaft", required=False),
        stock_diameter_mm=stock, loads=loads, load_cases=cases, duty=duty)
    from shaftfe.solid.plan import prepare
    try:
        validate_variant(v)     # the variant's rules (model.validate): one set, however made
        prepare(v)              # the solid's construction rules (slots, hex socket, bands)
    except InputError as exc:
        raise origins.locate(exc) from None
    for args in stiffness_checks:        # each bearing's stiffness against its own catalogue
        _stiffness_plausible(*args)
    if target is not None and check_balance:
        _check_balance(v, target, ctx.file_of("balance", top))
    return dataclasses.replace(v, content_hash=content_hash(v))


_DUTY_KEYS = {"speed_range_rpm", "design_speeds_rpm", "campbell_range_rpm", "spectrum",
              "design_life_h", "design_life_blocks", "engine", "sn_curve", "elements"}


def _duty_file(val, src: str, fld: str, std_dir: Path, allowed: str) -> str:
    """A file named by [duty]: relative to the file stating it, else a bare name in its
    standard directory (engines: geometry/engines/NAME.toml)."""
    from shaftfe.util.paths import ENGINES_DIR
    need(isinstance(val, str) and val != "", src, fld, allowed, val)
    here = Path(src).resolve().parent
    names = [val] if std_dir != ENGINES_DIR or val.endswith(".toml") else [val, f"{val}.toml"]
    for cand in [here / n for n in names] + [std_dir / n for n in names]:
        if cand.is_file():
            return str(cand.resolve())
    have = ", ".join(sorted(p.name for p in std_dir.iterdir() if p.is_file()
                            and not p.name.startswith((".", "README", "make_"))))
    raise InputError(src, fld, f"{allowed}: a file relative to {Path(src).name} or one of "
                     f"{have} in {_show(std_dir)}/", got=val, reason="is not an existing file")


def _rpm_pair(t: dict, key: str, src: str, lo0: float, hi0: float) -> tuple[float, float]:
    v = t.get(key)
    ok = (isinstance(v, list) and len(v) == 2 and all(is_num(e) for e in v)
          and all(math.isfinite(float(e)) for e in v))
    need(ok, src, f"duty.{key}", "[low, high] in rpm", v)
    lo, hi = float(v[0]), float(v[1])
    need(lo0 <= lo < hi <= hi0, src, f"duty.{key}",
         f"[low, high] with {lo0:g} <= low < high <= {hi0:g} rpm", v)
    return lo, hi


def _duty(merged: dict, ctx: Ctx, top: str) -> Duty | None:
    """The variant's [duty] (``model.variant.Duty``), or None when it states none: a command
    that needs a duty value then asks for it (nothing defaults to the seed's)."""
    if "duty" not in merged:
        return None
    from shaftfe.util.limits import PROOF_FACTOR, RPM_CEILING
    from shaftfe.util.paths import COMMON_DIR, ENGINES_DIR, LOADSPECTRA_DIR
    src = ctx.file_of("duty", top)
    t = table(merged["duty"], src, "duty")
    check_keys(t, _DUTY_KEYS, src, "duty")
    provenance(t, src, "duty", "duty", ctx)
    need("speed_range_rpm" in t, src, "duty.speed_range_rpm",
         "[lowest running, highest] speed in rpm", None)
    lo, hi = _rpm_pair(t, "speed_range_rpm", src, 0.0, RPM_CEILING)
    ds = t.get("design_speeds_rpm", [])
    need(isinstance(ds, list) and all(is_num(e) for e in ds), src, "duty.design_speeds_rpm",
         "a list of speeds in rpm", ds)
    top_ds = min(PROOF_FACTOR * hi, RPM_CEILING)
    for i, r in enumerate(ds):
        need(math.isfinite(r) and 0 < r <= top_ds, src, f"duty.design_speeds_rpm[{i}]",
             f"a speed in (0, {top_ds:g}] rpm ({PROOF_FACTOR:g} × the highest speed "
             f"{hi:g} of speed_range_rpm: a proof check)", r)
    camp = _rpm_pair(t, "campbell_range_rpm", src, 0.0, RPM_CEILING) \
        if "campbell_range_rpm" in t else None
    life_h = num(t, "design_life_h", src, "duty", required=False)
    life_b = num(t, "design_life_blocks", src, "duty", required=False)
    need(life_h is None or life_b is None, src, "duty.design_life_h",
         "design_life_h or design_life_blocks, not both", life_h)
    need(life_h is None or 0 < life_h <= 1e7, src, "duty.design_life_h",
         "a life in (0, 1e7] h", life_h)
    need(life_b is None or 1 <= life_b <= 1e12, src, "duty.design_life_blocks",
         "a number of blocks in [1, 1e12]", life_b)
    engine = _duty_file(t["engine"], src, "duty.engine", ENGINES_DIR,
                        "an engine file (.toml)") if "engine" in t else None
    if engine is not None:
        from shaftfe.balance.engines import load_engine
        e = load_engine(engine)
        need(e.max_rpm is None or hi <= e.max_rpm, src, "duty.speed_range_rpm",
             f"a highest speed <= {e.name}'s max_rpm {e.max_rpm:g} rpm", [lo, hi])
    spectrum = _duty_file(t["spectrum"], src, "duty.spectrum", LOADSPECTRA_DIR,
                          "an rpm history file") if "spectrum" in t else None
    elements = _duty_file(t["elements"], src, "duty.elements", COMMON_DIR,
                          "an element-check file like common/elements.toml") \
        if "elements" in t else None
    sn = t.get("sn_curve")
    if sn is not None:
        from shaftfe.model.sn_file import card_names
        cards = card_names()
        need(sn in cards, src, "duty.sn_curve", one_of(cards, "sn_curves"), sn)
    return Duty(source=src, speed_range_rpm=(lo, hi),
                design_speeds_rpm=tuple(float(r) for r in ds), campbell_range_rpm=camp,
                spectrum=spectrum, design_life_h=life_h, design_life_blocks=life_b,
                engine=engine, sn_curve=sn, elements=elements)


# The variant's [balance] table states the whole balancer's mass and balance ratio; its parts
# must agree. The seed's own tables disagree with themselves by up to 1.4 points of X2 (x2_31:
# 31 % stated, 32.4 % from its m and γ2) and 0.13 % of mass (x2_57), so the bounds are 2.5
# points and 2 %: a unit mistake (an eccentricity in metres, a mass in grams) is far outside.
BALANCE_X2_TOL_POINTS = 2.5
BALANCE_MASS_RTOL = 0.02


def _check_balance(v: Variant, t: BalanceTarget, src: str) -> None:
    mp = mass_properties(v)
    need(abs(mp.mass_kg - t.mass_kg) <= BALANCE_MASS_RTOL * t.mass_kg, src, "balance.mass_kg",
         f"the mass of the parts and shaft, {mp.mass_kg:.4f} kg (within "
         f"{100 * BALANCE_MASS_RTOL:g} %): a part's mass or the stated value is wrong",
         t.mass_kg)
    ratio = balance_ratio(mp, t)
    if ratio is not None:
        x2 = 100.0 * ratio
        need(abs(x2 - t.X2_percent) <= BALANCE_X2_TOL_POINTS, src, "balance.X2_percent",
             f"the parts' X2 = Σ m e / (m_pos R) = {x2:.1f} % (within "
             f"{BALANCE_X2_TOL_POINTS:g} points): a mass or eccentricity is wrong, e.g. "
             "typed in grams or metres", t.X2_percent)
