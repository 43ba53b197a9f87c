"""`shaftfe view`: look at a result file (.vtu) — interactive window or off-screen screenshot.

Stdlib only at module level; PyVista/VTK are imported by ``shaftfe.io.render`` inside the handler.
"""

from __future__ import annotations

CAMERAS = ("iso", "xy", "xz", "yz")


def register(sub) -> None:
    p = sub.add_parser(
        "view", help="show a result .vtu (field, hot spot, warp) or save a screenshot",
        description="Render a field of a result file written by shaftfe (result.vtu, "
        "fatigue.vtu, a mesh .vtu) with PyVista: scalar bar with the unit, the hot spot "
        "(max; min for safety_factor and life_blocks) marked with its value and coordinates. "
        "Opens an interactive window when a display exists; renders off-screen (no X server "
        "needed) with --screenshot or on a machine without DISPLAY, where the image goes to "
        "RESULT_<field>.png unless --screenshot says otherwise. Field names and units: "
        "docs/FIELDS.md.")
    p.add_argument("result", metavar="RESULT.vtu", help="VTK XML unstructured grid (.vtu)")
    p.add_argument("--field", default=None,
                   help="field to show (default: the first of von_mises, safety_factor, "
                   "displacement, group, region present)")
    p.add_argument("--component", default=None,
                   help="vector: magnitude | x | y | z | 0..2 (default magnitude); stress: "
                   "xx | yy | zz | xy | yz | xz | 0..5 (default xx, the axial stress)")
    p.add_argument("--warp", default=None, metavar="FACTOR",
                   help="draw the shape deformed by displacement × FACTOR, or 'auto' (largest "
                   "displacement = 5 %% of the model size); default: undeformed")
    p.add_argument("--edges", action="store_true", help="draw the element edges")
    p.add_argument("--screenshot", default=None, metavar="PNG",
                   help="render off-screen and save the image here (.png, .jpg)")
    p.add_argument("--window-size", default="1600x900", metavar="WxH",
                   help="window / image size in pixels (default %(default)s)")
    p.add_argument("--camera", default="iso", choices=CAMERAS,
                   help="iso (oblique, facing the hot spot), xy, xz or yz (end view) "
                   "(default %(default)s)")
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    p.set_defaults(handler=run)


def run(args) -> int:
    import sys

    from shaftfe.commands._common import print_json
    from shaftfe.io.render import parse_warp, parse_window_size, render

    size = parse_window_size(args.window_size)
    warp = parse_warp(args.warp)
    res = render(args.result, field=args.field, component=args.component, warp=warp,
                 edges=args.edges, screenshot=args.screenshot, window_size=size,
                 camera=args.camera)
    if res.warp_note:
        print(f"shaftfe view: note: {res.warp_note}", file=sys.stderr)
    if args.json:
        h = res.hot
        print_json({
            "file": res.path, "field": res.field.name, "component": res.field.component,
            "label": res.field.label, "unit": res.field.unit,
            "association": res.field.association, "min": res.vmin, "max": res.vmax,
            "non_finite": res.n_nonfinite,
            "hot_spot": None if h is None else {
                "rule": h.rule, "value": h.value, "xyz_mm": list(h.xyz),
                ("node" if res.field.association == "point" else "cell"): h.index},
            "warp": res.warp, "screenshot": res.screenshot,
            "window_size": list(res.window_size), "seconds": round(res.seconds, 3)})
    elif res.screenshot is not None:          # interactive mode printed it before the window
        print(res.summary())
    return 0
