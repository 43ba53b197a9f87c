"""`shaftfe variant`: list, show and check the balancer-shaft variant files (geometry/*.toml).

Stdlib only at module level; ``shaftfe.model.variant`` is imported inside the handlers.
"""

from __future__ import annotations


def register(sub) -> None:
    from shaftfe.commands._common import add_set_option
    p = sub.add_parser("variant", help="list, show or check balancer-shaft variant files",
                       description="Variant files (geometry/<name>.toml with includes): list "
                       "them, show one (segments, bearings, attachments with provenance, mass "
                       "properties, attachment forces), or validate a file.")
    vs = p.add_subparsers(dest="variant_command", metavar="SUBCOMMAND",
                          parser_class=type(p))
    pl = vs.add_parser("list", help="list the variants in geometry/")
    pl.add_argument("--json", action="store_true", help="print JSON")
    pl.set_defaults(handler=run_list)
    ps = vs.add_parser("show", help="show one variant",
                       description="Segments, bearings and attachments with their provenance, "
                       "the whole-balancer mass properties against the seed's table, and the "
                       "attachment forces m e ω² with rigid-support reactions.")
    ps.add_argument("variant", help="variant name (e.g. x2_57) or path to a .toml file")
    ps.add_argument("--rpm", default=None,
                    help="speeds for the forces, comma-separated (default: the variant's "
                    "[duty] design speeds, ascending: 7000,10000 for the x2_* shafts; none "
                    "stated: no force table)")
    ps.add_argument("--json", action="store_true", help="print JSON instead of tables")
    add_set_option(ps)
    ps.set_defaults(handler=run_show)
    pc = vs.add_parser("check", help="validate a variant file (exit 2 with one line if bad)")
    pc.add_argument("path", help="path to a variant .toml (or a variant name)")
    pc.add_argument("--json", action="store_true", help="print JSON")
    add_set_option(pc)
    pc.set_defaults(handler=run_check)
    pn = vs.add_parser("new", help="write a self-contained, editable copy of a variant",
                       description="Write geometry/NAME.toml (or --out): the --from variant "
                       "with its includes resolved into one file (materials, bearing types, "
                       "parts, shaft), renamed, with any --set applied. Checked like any "
                       "variant before it is written; an existing file is not overwritten.")
    pn.add_argument("name", help="name of the new variant (letters, digits, _ and -)")
    pn.add_argument("--from", dest="source", default="x2_57",
                    help="variant to start from: a name or a path (default x2_57)")
    pn.add_argument("--out", default=None, help="file to write (default geometry/NAME.toml)")
    add_set_option(pn)
    pn.set_defaults(handler=run_new)
    p.set_defaults(handler=lambda args: p.print_help() or 0)


def _retag(merged: dict, orig: dict, o, ov) -> None:
    """A value written with --set is no longer what its provenance list said: move its key to
    ``reconstructed`` and say in the table's note what it was."""
    from shaftfe.model.fields import is_numeric_value
    from shaftfe.model.variant import SOURCES
    table, key, _ = ov.locate(merged, o)
    was = ov.locate(orig, o)
    old = was[0][was[1]]
    if not is_numeric_value(table[key]):
        return
    for tag in SOURCES:
        if key in table.get(tag, []):
            table[tag] = [k for k in table[tag] if k != key]
    table.setdefault("reconstructed", []).append(key)
    line = f"{key} = {table[key]!r}: set by `shaftfe variant new --set` (was {old!r})."
    table["note"] = (table.get("note", "").rstrip() + "\n" + line).lstrip("\n")


def run_new(args) -> int:
    from pathlib import Path

    from shaftfe.errors import InputError
    from shaftfe.model import overrides as ov
    from shaftfe.model.loader import load_variant
    from shaftfe.model.parse import check_new_name, resolve_path, resolved_dict
    from shaftfe.model.tomlwrite import dumps
    from shaftfe.util.atomic import check_output_file, write_atomic
    from shaftfe.util.paths import GEOMETRY_DIR, repo_relative
    check_new_name(args.name)
    out = Path(args.out) if args.out else GEOMETRY_DIR / f"{args.name}.toml"
    # the option that chose the file is the one blamed: --out if given, else NAME
    opt = ("--out", "out") if args.out else ("command line", "NAME")
    if out.suffix != ".toml":
        raise InputError(*opt, "a path ending in .toml", got=str(out))
    if out.exists():
        raise InputError(*opt, "a file that does not exist yet (not overwritten)"
                         + ("" if args.out else ": another NAME, or --out"), got=str(out))
    check_output_file(out, opt[0])
    src = resolve_path(args.source)
    sets = ov.normalise(tuple(args.set or ()))
    base = load_variant(src, sets)                  # the source itself must be valid
    merged = resolved_dict(src)
    import copy
    orig = copy.deepcopy(merged)
    for o in ov.apply(merged, sets):
        _retag(merged, orig, o, ov)
    merged["name"] = args.name
    order = ["name", "description", "use_parts", "balance", "shaft", "materials",
             "bearing_types", "parts", "attachments"]
    doc = {k: merged[k] for k in order if k in merged}
    doc.update({k: v for k, v in merged.items() if k not in doc})
    changed = "".join(f"\n  --set {o.path}={o.text}" for o in sets)
    header = (f"Variant {args.name}: written by `shaftfe variant new {args.name} --from "
              f"{args.source}`\nfrom {', '.join(base.source_files)}{changed}\n"
              "Self-contained (no includes): edit any value. Units are in the key names; "
              "every numeric key\nis listed in one provenance list (seed / reconstructed / "
              "derived / standard). Keys, units,\nranges and paths: docs/VARIANTS.md. Check "
              f"it with: shaftfe variant check {repo_relative(out)}")
    text = dumps(doc, header)
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:       # check the very text before writing it
        probe = Path(tmp) / out.name
        probe.write_text(text, encoding="utf-8")
        v = load_variant(probe)
    write_atomic(out, text)
    print(f"wrote {repo_relative(out)}: {v.name}, {len(v.segments)} segments, "
          f"{len(v.attachments)} attachments, hash {v.content_hash[:16]} "
          f"({'same physics as' if v.content_hash == base.content_hash else 'differs from'} "
          f"{base.name}{' with the --set values' if sets else ''})")
    return 0



def run_list(args) -> int:
    from shaftfe.commands._common import print_json, print_table
    from shaftfe.model.loader import load_variant
    from shaftfe.model.mass import mass_properties
    from shaftfe.model.parse import list_variants

    rows = []
    for name in list_variants():
        v = load_variant(name)
        mp = mass_properties(v)
        rows.append({"name": v.name, "description": v.description,
                     "mass_kg": round(mp.mass_kg, 4), "gamma2_mm": round(mp.gamma2_mm, 3),
                     "x_T_mm": round(mp.x_T_mm, 3), "content_hash": v.content_hash})
    if args.json:
        print_json(rows)
    else:
        print_table(["name", "mass kg", "γ2 mm", "x_T mm", "description"],
                    [[r["name"], f"{r['mass_kg']:.4f}", f"{r['gamma2_mm']:.3f}",
                      f"{r['x_T_mm']:.3f}", r["description"]] for r in rows])
    return 0


def _src(v, path: str) -> str:
    return v.provenance.source.get(path, "?")


def _report(v, rpms: list[float]) -> dict:
    from shaftfe.model.mass import (
        balance_ratio,
        mass_properties,
        rigid_support_reactions,
        seat_loads,
    )

    mp = mass_properties(v)
    tgt = v.balance_target
    segs = [{"name": s.name, "kind": s.kind, "x_start_mm": s.x_start_mm, "x_end_mm": s.x_end_mm,
             "length_mm": s.length_mm, "diameter_mm": s.diameter_mm,
             **({"diameter_right_mm": s.d_right_mm} if s.conical else {}),
             "fillet_mm": s.fillet_mm,
             "keyways": [{"width_mm": k.width_mm, "depth_mm": k.depth_mm,
                          "length_mm": k.length_mm, "x_center_mm": k.x_center_mm,
                          "angle_deg": k.angle_deg,
                          **({"bottom_radius_mm": k.bottom_radius_mm}
                             if k.bottom_radius_mm else {})} for k in s.keyways],
             "source": {f: _src(v, f"segments.{s.name}.{f}")
                        for f in ("length_mm", "diameter_mm", "fillet_mm")}}
            for s in v.segments]
    brgs = []
    for b in v.bearings:
        brgs.append({"name": b.name, "designation": b.designation, "x_center_mm": b.x_center_mm,
                     "width_mm": b.width_mm, "C_N": b.C_N, "C0_N": b.C0_N,
                     "K_N_per_mm": [list(r) for r in b.K_N_per_mm], "axial": b.axial,
                     "source": {"x_center_mm": _src(v, f"bearings.{b.name}.x_center_mm")}})
    atts = []
    for a in v.attachments:
        atts.append({"name": a.name, "seat": a.seat_segment,
                     "seat_x_mm": [a.seat_x_start_mm, a.seat_x_end_mm], "mass_kg": a.mass_kg,
                     "eccentricity_mm": a.eccentricity_mm, "angle_deg": a.angle_deg,
                     "x_centroid_mm": a.x_centroid_mm,
                     "polar_inertia_kg_mm2": a.polar_inertia_kg_mm2,
                     "diametral_inertia_kg_mm2": a.diametral_inertia_kg_mm2,
                     "material": a.material, "seed_load_case": a.seed_load_case,
                     "source": {f: _src(v, f"attachments.{a.name}.{f}")
                                for f in ("mass_kg", "eccentricity_mm", "x_centroid_mm")},
                     "force_N": {f"{r:g}": a.force_N(r) for r in rpms}})
    ratio = balance_ratio(mp, tgt)
    x2 = None if ratio is None else 100.0 * ratio
    mass = {"mass_kg": mp.mass_kg, "shaft_mass_kg": mp.shaft_mass_kg,
            "gamma2_mm": mp.gamma2_mm, "sum_me_kg_mm": mp.mass_kg * mp.gamma2_mm,
            "x_centroid_mm": mp.x_centroid_mm, "x_T_mm": mp.x_T_mm, "X2_percent": x2,
            "polar_inertia_kg_mm2": mp.polar_inertia_kg_mm2,
            "diametral_inertia_kg_mm2": mp.diametral_inertia_kg_mm2,
            "seed": None if tgt is None else {
                "X2_percent": tgt.X2_percent, "mass_kg": tgt.mass_kg,
                "gamma2_mm": tgt.gamma2_mm, "x_T_mm": tgt.x_T_mm}}
    loads = []
    for r in rpms:
        for case in ("seed", "full"):
            lumped = seat_loads(v, r, seed_case=(case == "seed"))
            reac = rigid_support_reactions(v, r, seed_case=(case == "seed")) \
                if len(v.bearings) == 2 else ()
            loads.append({"rpm": r, "case": case,
                          "seat_forces": [{"x_mm": x, "Fy_N": fy, "Fz_N": fz}
                                          for x, fy, fz in lumped],
                          "rigid_reactions_N": {n: val for n, val in reac}})
    return {"name": v.name, "description": v.description, "content_hash": v.content_hash,
            "overrides": v.overrides_map,
            "source_files": list(v.source_files), "length_mm": v.length_mm,
            "material": v.material.name, "parting_plane_x_mm": v.parting_plane_x_mm,
            "clearance_station_x_mm": v.clearance_station_x_mm,
            "hex_socket": None if v.hex_socket is None else {
                "end": v.hex_socket.end, "across_flats_mm": v.hex_socket.across_flats_mm,
                "depth_mm": v.hex_socket.depth_mm},
            "segments": segs, "bearings": brgs, "attachments": atts,
            "mass_properties": mass, "loads": loads}


def run_show(args) -> int:
    from shaftfe.commands._common import parse_rpm_list, print_json, print_table
    from shaftfe.model.loader import load_variant

    rpms = parse_rpm_list(args.rpm) if args.rpm is not None else None
    v = load_variant(args.variant, tuple(args.set or ()))
    if rpms is None:
        rpms = sorted(v.duty.design_speeds_rpm) if v.duty is not None else []
    rep = _report(v, rpms)
    if args.json:
        print_json(rep)
        return 0
    print(f"{v.name}: {v.description}")
    print(f"files: {', '.join(v.source_files)}")
    print(f"content hash: {v.content_hash}")
    print(f"length {v.length_mm:g} mm, material {v.material.name}, x = 0 at the gear end; "
          f"parting plane x = {v.parting_plane_x_mm:g}, clearance station x = "
          f"{v.clearance_station_x_mm}")
    print()
    print_table(["segment", "kind", "x0", "x1", "Ø mm", "fillet", "keyway", "source L/Ø/r"],
                [[s["name"], s["kind"], s["x_start_mm"], s["x_end_mm"],
                  f"{s['diameter_mm']:.2f}→{s['diameter_right_mm']:.2f}"
                  if "diameter_right_mm" in s else s["diameter_mm"], s["fillet_mm"],
                  ", ".join(f"{k['width_mm']:g}×{k['depth_mm']:g}×{k['length_mm']:g}"
                            f"@{k['x_center_mm']:g}" + (f" r1 {k['bottom_radius_mm']:g}"
                                                        if "bottom_radius_mm" in k else "")
                            for k in s["keyways"]) or "-",
                  "/".join(s["source"][f] for f in ("length_mm", "diameter_mm", "fillet_mm"))]
                 for s in rep["segments"]])
    print()
    print_table(["bearing", "type", "x mm", "width", "C N", "C0 N", "K11/K12 N/mm", "axial",
                 "source x"],
                [[b["name"], b["designation"], b["x_center_mm"], b["width_mm"], b["C_N"],
                  b["C0_N"], f"{b['K_N_per_mm'][0][0]:g}/{b['K_N_per_mm'][0][1]:g}",
                  "yes" if b["axial"] else "no", b["source"]["x_center_mm"]]
                 for b in rep["bearings"]])
    print()
    hdr = ["attachment", "seat", "m kg", "e mm", "x mm", "Ip", "Id", "seed case",
           "source m/e"] + [f"F@{r:g} N" for r in rpms]
    print_table(hdr, [[a["name"], a["seat"], f"{a['mass_kg']:.5f}", f"{a['eccentricity_mm']:.3f}",
                       a["x_centroid_mm"], a["polar_inertia_kg_mm2"],
                       a["diametral_inertia_kg_mm2"], "yes" if a["seed_load_case"] else "no",
                       f"{a['source']['mass_kg']}/{a['source']['eccentricity_mm']}"]
                      + [f"{a['force_N'][f'{r:g}']:.0f}" for r in rpms]
                      for a in rep["attachments"]])
    print()
    m = rep["mass_properties"]
    s = {k: f"{val:g}" for k, val in (m["seed"] or {}).items()}
    rows = [["mass kg", f"{m['mass_kg']:.4f}", s.get("mass_kg", "-")],
            ["γ2 mm", f"{m['gamma2_mm']:.3f}", s.get("gamma2_mm", "-")],
            ["x_T mm", f"{m['x_T_mm']:.3f}", s.get("x_T_mm", "-")],
            ["X2 %", "-" if m["X2_percent"] is None else f"{m['X2_percent']:.2f}",
             s.get("X2_percent", "-")],
            ["Σ m e kg·mm", f"{m['sum_me_kg_mm']:.4f}", "-"],
            ["shaft mass kg", f"{m['shaft_mass_kg']:.4f}", "-"],
            ["polar J kg·mm²", f"{m['polar_inertia_kg_mm2']:.2f}", "-"],
            ["diametral J kg·mm²", f"{m['diametral_inertia_kg_mm2']:.2f}", "-"]]
    print_table(["whole balancer", "files", "seed table"], rows)
    print()
    lrows = []
    for ld in rep["loads"]:
        forces = "  ".join(f"{f['Fy_N']:.0f}@{f['x_mm']:g}" for f in ld["seat_forces"])
        reac = "  ".join(f"{n} {val:.0f}" for n, val in ld["rigid_reactions_N"].items())
        lrows.append([f"{ld['rpm']:g}", ld["case"], forces, reac])
    print_table(["rpm", "case", "seat forces N @ x mm", "rigid-support reactions N"], lrows)
    if 0.0 in rpms:
        from shaftfe.beam.solve import AT_REST_NOTE
        print(f"note: {AT_REST_NOTE}")
    return 0


def run_check(args) -> int:
    from shaftfe.commands._common import print_json
    from shaftfe.model.loader import load_variant
    from shaftfe.model.mass import mass_properties

    v = load_variant(args.path, tuple(args.set or ()))
    mp = mass_properties(v)
    info = {"ok": True, "name": v.name, "files": list(v.source_files),
            "overrides": v.overrides_map,
            "content_hash": v.content_hash, "segments": len(v.segments),
            "bearings": len(v.bearings), "attachments": len(v.attachments),
            "mass_kg": mp.mass_kg, "values_with_provenance": len(v.provenance.source)}
    if args.json:
        print_json(info)
    else:
        print(f"OK {v.name}: {len(v.segments)} segments, {len(v.bearings)} bearings, "
              f"{len(v.attachments)} attachments, {len(v.provenance.source)} values with "
              f"provenance, mass {mp.mass_kg:.4f} kg, hash {v.content_hash[:16]}")
    return 0
