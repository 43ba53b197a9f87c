"""`shaftfe mesh`: build (or load from the cache) the 3D tetrahedral mesh of a variant."""

from __future__ import annotations

from shaftfe.solid.levels import LEVEL_NAMES as LEVELS


def register(sub) -> None:
    p = sub.add_parser(
        "mesh", help="mesh a variant's shaft with Gmsh (quadratic tets, cached)",
        description="Build the shaft solid of a variant with Gmsh (fillets, keyways, hex "
        "socket, faces split on every load plane), mesh it with quadratic tetrahedra and "
        "cache the result. Prints nodes, elements, min quality (Gmsh minSICN), time and "
        "whether the mesh came from the cache.")
    p.add_argument("--variant", required=True, help="variant name (geometry/<name>.toml)")
    p.add_argument("--level", default="default", choices=LEVELS,
                   help="mesh size level (default: %(default)s)")
    p.add_argument("--order", type=int, default=2, choices=(1, 2),
                   help="element order (default: %(default)s)")
    p.add_argument("--out", default=None, metavar="PATH",
                   help="write the mesh to PATH (.vtu or .msh)")
    p.add_argument("--no-cache", action="store_true", help="neither read nor write the cache")
    p.add_argument("--cache-dir", default=None, metavar="DIR",
                   help="cache directory (default: $SHAFTFE_CACHE_DIR or ~/.cache/shaftfe)")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    from shaftfe.commands._common import add_set_option
    add_set_option(p)
    p.set_defaults(handler=run)


def run(args) -> int:

    from shaftfe.commands._common import print_json
    from shaftfe.io.vtu import MESH_SUFFIXES
    from shaftfe.util.atomic import check_output_file
    out = check_output_file(args.out, "--out", MESH_SUFFIXES)
    from shaftfe.commands._common import load_variant_from

    variant = load_variant_from(args)

    from shaftfe.io.vtu import write_mesh
    from shaftfe.solid.mesh import build_mesh
    from shaftfe.util.progress import Progress
    prog = Progress(["mesh"], enabled=False if args.json else None)
    with prog.stage("mesh"):
        from shaftfe.beam.planes import mesh_hot_axes
        sm = build_mesh(variant, level=args.level, order=args.order, cache_dir=args.cache_dir,
                        use_cache=not args.no_cache, hot_axes=mesh_hot_axes(variant))
    if out is not None:
        write_mesh(sm, out)
    summary = {
        "variant": sm.variant_name, "overrides": variant.overrides_map, "level": sm.level,
        "order": sm.order,
        "nodes": sm.n_nodes, "elements": sm.n_elements, "dofs": sm.n_dofs,
        "min_quality_minSICN": round(sm.min_quality, 4),
        "seconds": round(sm.build_seconds, 3), "mesh_seconds": round(sm.mesh_seconds, 3),
        "from_cache": sm.from_cache, "key": sm.key[:16],
        "groups": list(sm.groups), "out": str(out) if out else None,
    }
    if args.json:
        print_json(summary)
        return 0
    src = "cache" if sm.from_cache else "gmsh"
    print(f"mesh {sm.variant_name} level={sm.level} P{sm.order}: {sm.n_nodes} nodes, "
          f"{sm.n_elements} tets, {sm.n_dofs} dofs, min quality (minSICN) "
          f"{sm.min_quality:.3f}, {sm.build_seconds:.2f} s from {src}")
    print("groups: " + ", ".join(sm.groups))
    if out is not None:
        print(f"wrote {out} (cell data 'group': 0 = volume, i = groups[i-1])")
    return 0
