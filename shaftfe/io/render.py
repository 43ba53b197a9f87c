"""Draw a result file with PyVista: the chosen field on the curved boundary surface, scalar bar
with the unit, the hot spot marked with its value and coordinates; an interactive window or an
off-screen screenshot.

``render`` is what ``shaftfe view`` runs. The file is read and the field and hot spot chosen by
``shaftfe.io.view``; the surface comes from ``shaftfe.io.surface``. PyVista / VTK are imported
inside the functions, so importing this module costs nothing.
"""

from __future__ import annotations

import math
import os
import sys
import time
from dataclasses import dataclass
from pathlib import Path

from shaftfe.errors import InputError
from shaftfe.io.surface import boundary, element_edges, subdivision_level, surface
from shaftfe.io.view import (
    MODE_PREFIX,
    FieldChoice,
    HotSpot,
    choose_field,
    fitted_peak,
    group_names,
    hot_spot,
    load,
    values,
)
from shaftfe.util.atomic import atomic_path, check_output_file

SF_CLIP = 3.0                  # safety factor colour scale: 1.0 marked, clipped above this
CAMERAS = ("iso", "xy", "xz", "yz")
SCREENSHOT_SUFFIXES = (".png", ".jpg", ".jpeg")


@dataclass
class ViewResult:
    path: str
    field: FieldChoice
    vmin: float
    vmax: float
    n_nonfinite: int
    hot: HotSpot | None
    warp: float               # factor applied (0: none)
    warp_note: str | None
    screenshot: str | None
    window_size: tuple[int, int]
    seconds: float
    off_screen: bool
    fitted_peak: float | None = None   # the run's printed (surface-fit) peak, von Mises only

    def summary(self) -> str:
        f = self.field
        unit = f" {f.unit}" if f.unit not in ("-", "id") else ""
        parts = [f"view {self.path}", f"field {f.label} [{f.unit}] ({f.association} data)",
                 f"range {_g(self.vmin)} .. {_g(self.vmax)}{unit}"]
        if self.n_nonfinite:
            parts.append(f"{self.n_nonfinite} non-finite values not shown")
        if self.hot is None:
            parts.append("hot spot n/a")
        else:
            h = self.hot
            what = {"max": "max", "min": "min", "max_abs": "max |value|"}[h.rule]
            kind = "node" if f.association == "point" else "cell"
            parts.append(f"hot spot ({what}) {_g(h.value)}{unit} at x={h.xyz[0]:.2f} "
                         f"y={h.xyz[1]:.2f} z={h.xyz[2]:.2f} mm ({kind} {h.index})")
            if self.fitted_peak is not None:
                parts.append(f"summary.json's peak {_g(self.fitted_peak)}{unit} is the surface "
                             "fit between the nodes; the file holds nodal values")
        if self.warp:
            parts.append(f"warp x{_g(self.warp)}")
        if self.screenshot:
            w, hgt = self.window_size
            parts.append(f"screenshot {self.screenshot} ({w}x{hgt}, {self.seconds:.2f} s)")
        elif not self.off_screen:
            parts.append("interactive window")
        return "; ".join(parts)


def _g(v: float) -> str:
    return f"{v:.4g}"


def headless() -> bool:
    """True on a Linux/BSD machine without an X or Wayland display."""
    if sys.platform.startswith(("win", "darwin")):
        return False
    return not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def use_offscreen_egl() -> None:
    """Make VTK pick its EGL render window (no X server) unless the user chose one."""
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")


def parse_window_size(text: str) -> tuple[int, int]:

    allowed = "WIDTHxHEIGHT in pixels, each 64..8192 (e.g. 1600x900)"
    try:
        w, h = (int(t) for t in text.lower().split("x"))
    except ValueError:
        raise InputError("command line", "--window-size", allowed, got=text) from None
    if not (64 <= w <= 8192 and 64 <= h <= 8192):
        raise InputError("command line", "--window-size", allowed, got=text)
    return w, h


def parse_warp(text: str | float | None) -> float | str:
    """``auto`` or a finite factor >= 0."""

    if text is None:
        return 0.0
    if isinstance(text, str) and text.strip().lower() == "auto":
        return "auto"
    try:
        v = float(text)
    except ValueError:
        v = float("nan")
    if not (0 <= v < float("inf")):
        raise InputError("command line", "--warp", "auto or a factor >= 0", got=text)
    return v


def render(path, field: str | None = None, component: str | None = None,
           warp: float | str = 0.0, edges: bool = False, screenshot=None,
           window_size: tuple[int, int] = (1600, 900), camera: str = "iso",
           off_screen: bool | None = None, hot_exclude=None,
           zoom: float | str | None = None, grid=None, title: str | None = None) -> ViewResult:
    """Load ``path``, render ``field`` and either save ``screenshot`` (written atomically) or
    open an interactive window. Input errors are raised before anything is drawn.
    ``hot_exclude``: point/cell ids the hot spot is not searched in (drawn all the same).
    ``zoom``: camera zoom after fitting the model (default 1.35; the yz end view fits the
    cross-section instead); ``"fit"``: a parallel projection whose shaft fills the width of the
    picture between the title and the colour bar. ``title``: the text at the top (default
    ``<file name>: <field>``). ``grid``: ``path`` already read by ``view.load`` (several
    pictures of one file read it once; each render sets its ``_view`` array on it)."""
    import numpy as np


    t0 = time.perf_counter()
    shot = _screenshot_option(camera, screenshot)
    if off_screen is None:
        off_screen = shot is not None or headless()
    if off_screen:
        use_offscreen_egl()
    grid = load(path) if grid is None else grid
    choice = choose_field(grid, field, component, source=str(path))
    vals = values(grid, choice)
    finite = np.isfinite(vals)
    if not finite.any():
        raise InputError(str(path), choice.name, "at least one finite value",
                         reason="has no finite values")
    vmin, vmax = float(vals[finite].min()), float(vals[finite].max())
    hot = hot_spot(grid, choice, vals, exclude=hot_exclude)
    shape_field = _shape_field(grid, choice)
    factor, warp_note = _warp_factor(grid, shape_field, warp, path)

    if shot is None and off_screen:
        shot = Path(path).with_name(f"{Path(path).stem}_{choice.name}.png")
    if shot is not None:
        check_output_file(shot, "--screenshot")

    surf, edge_lines = _scene(grid, choice, np.where(finite, vals, np.nan), factor,
                              shape_field, edges)
    names = group_names(grid, path) if choice.rule == "none" else {}
    plotter = _plot(path, surf, edge_lines, choice, vmin, vmax, hot, factor,
                    shape_field, grid, window_size, camera, off_screen, names, zoom, title)
    n_nonfinite = int((~finite).sum())
    fit = fitted_peak(path, choice) if hot is not None else None
    try:
        if shot is not None:
            _screenshot(plotter, shot)
            return ViewResult(str(path), choice, vmin, vmax, n_nonfinite, hot, factor,
                              warp_note, str(shot), window_size, time.perf_counter() - t0,
                              bool(off_screen), fit)
        res = ViewResult(str(path), choice, vmin, vmax, n_nonfinite, hot, factor,
                         warp_note, None, window_size, time.perf_counter() - t0, False, fit)
        print(res.summary(), flush=True)
        plotter.show()
        return res
    finally:
        plotter.close()


def _screenshot_option(camera: str, screenshot) -> Path | None:
    """Check ``--camera`` and the ``--screenshot`` suffix; the screenshot path or None."""

    if camera not in CAMERAS:
        raise InputError("command line", "--camera", " | ".join(CAMERAS), got=camera)
    return check_output_file(screenshot, "--screenshot", SCREENSHOT_SUFFIXES)


def _shape_field(grid, choice: FieldChoice) -> str | None:
    """The point field the shape is warped by: a mode by its own shape, anything else by
    ``displacement`` (3 components); None when the file has neither."""
    import numpy as np

    disp = grid.point_data["displacement"] if "displacement" in grid.point_data.keys() else None
    if choice.name.startswith(MODE_PREFIX) and choice.n_components == 3:
        return choice.name
    if disp is not None and np.ndim(disp) == 2 and np.shape(disp)[1] == 3:
        return "displacement"
    return None


def _warp_factor(grid, shape_field: str | None, warp: float | str,
                 path) -> tuple[float, str | None]:
    """(factor, note): ``auto`` makes the largest displacement 5 % of the model size; a
    requested warp without a shape field gives factor 0 and a note saying so."""
    import numpy as np

    if not (warp == "auto" or (isinstance(warp, float) and warp > 0)):
        return 0.0, None
    if shape_field is None:
        return 0.0, f"no 'displacement' field in {path}: not warped"
    u = np.asarray(grid.point_data[shape_field], float)
    umax = float(np.nanmax(np.linalg.norm(u, axis=1)))
    if warp == "auto":
        return (0.05 * grid.length / umax if umax > 0 else 0.0), None
    return float(warp), None


def _scene(grid, choice: FieldChoice, shown, factor: float, shape_field: str | None,
           edges: bool):
    """(curved boundary surface, element edge lines or None) with ``shown`` as ``_view``,
    warped by ``shape_field`` × ``factor``."""
    bnd = boundary(grid, choice, shown)
    if factor:
        bnd = bnd.warp_by_vector(shape_field, factor=factor)
    level = subdivision_level(bnd)
    surf = surface(bnd, level)
    edge_lines = element_edges(bnd, level) if edges else None
    return surf, edge_lines


def _plot(path, surf, edge_src, choice, vmin, vmax, hot, factor, shape_field, grid,
          window_size, camera, off_screen, names, zoom=None, title_text=None):
    import pyvista as pv

    p = pv.Plotter(off_screen=off_screen, window_size=list(window_size))
    p.set_background("white")
    title = f"{choice.label} [{choice.unit}]"
    if factor:
        title += f"  (deformed x{factor:.3g})"
    clim, sbar, kw = _colour_scale(surf, choice, vmin, vmax, title, names)
    actor = p.add_mesh(surf, scalars="_view", clim=clim, scalar_bar_args=sbar,
                       smooth_shading=True, split_sharp_edges=True, nan_color="lightgrey",
                       show_scalar_bar=True, **kw)
    if edge_src is not None:
        # push the faces back a little so that the edge lines on them are not z-fighting
        actor.mapper.SetResolveCoincidentTopologyToPolygonOffset()
        actor.mapper.SetRelativeCoincidentTopologyPolygonOffsetParameters(2.0, 4.0)
        p.add_mesh(edge_src, color="black", line_width=1, opacity=0.6)
    _set_camera(p, surf, hot, camera, zoom, window_size)
    if hot is not None:
        _mark_hot_spot(p, surf, hot, choice, grid, factor, shape_field, camera)
    p.add_axes(color="black", xlabel="x", ylabel="y", zlabel="z")
    p.add_text(title_text or f"{Path(path).name}: {choice.label}", position="upper_left",
               font_size=14 if title_text else 12, color="black")
    return p


def _colour_scale(surf, choice: FieldChoice, vmin: float, vmax: float, title: str,
                  names: dict) -> tuple[list, dict, dict]:
    """(colour limits, scalar bar arguments, colour map keywords of ``add_mesh``): a colour per
    id (named when ``names`` has the groups) for categorical fields, diverging and centred on 0
    for signed components, red below 1 / green above for the safety factor, jet otherwise
    (reversed for min-rule fields, logarithmic for a life range over 100)."""
    import numpy as np

    sbar = dict(title=title + "\n", title_font_size=20, label_font_size=18, color="black",
                vertical=False, position_x=0.2, position_y=0.03, width=0.6, height=0.1,
                fmt="%.4g", n_labels=5)
    kw: dict = {}
    if choice.rule == "none":
        ids = np.unique(np.asarray(surf.cell_data["_view"] if "_view" in surf.cell_data.keys()
                                   else surf.point_data["_view"]))
        kw["cmap"] = "tab20" if ids.size <= 20 else "nipy_spectral"   # a colour per id
        kw["categories"] = True
        kw["n_colors"] = max(int(ids.size), 2)
        if names and ids.size <= 40:
            kw["annotations"] = {float(i): names.get(int(i), "(no group)" if i == 0 else str(i))
                                 for i in ids}
            sbar.update(n_labels=0, vertical=True, position_x=0.80, position_y=0.05,
                        width=0.06, height=0.9, title=title,
                        label_font_size=18 if ids.size <= 20 else 11)
        else:                                             # ids without names: whole numbers
            sbar.update(fmt="%.0f", n_labels=int(min(ids.size, 10)))
    elif choice.rule == "max_abs":                        # signed: diverging, centred on 0
        kw["cmap"] = "coolwarm"
        a, _, n = nice_range(0.0, max(abs(vmin), abs(vmax)))
        vmin, vmax = -a, a
        sbar.update(n_labels=2 * n - 1, fmt=_tick_format(a / max(n - 1, 1)))
    elif choice.name == "safety_factor":
        # an engineer reads a safety factor around 1: red below 1, yellow at 1, green above,
        # clipped at SF_CLIP (a linear 0.47-15 scale painted everything from 0.5 to 4 the
        # same red); round ticks every 0.5 with 1 among them, values above SF_CLIP drawn in
        # the top colour (VTK clamps to the range) rather than in a separate swatch
        vmin = min(SF_TICK * math.floor(vmin / SF_TICK), 1.0 - SF_TICK)
        vmax = SF_CLIP
        kw["cmap"] = safety_colormap(vmin, vmax)
        sbar.update(title=title.replace("\n", "") + f" (≥ {SF_CLIP:g} shown as {SF_CLIP:g})\n",
                    n_labels=round((vmax - vmin) / SF_TICK) + 1, fmt="%.1f")
    else:
        kw["cmap"] = "jet" if choice.rule != "min" else "jet_r"
        if choice.name == "life_blocks" and vmin > 0 and vmax / vmin > 100:
            kw["log_scale"] = True
        elif vmax > vmin:
            vmin, vmax, n = nice_range(vmin, vmax)
            sbar.update(n_labels=n, fmt=_tick_format((vmax - vmin) / max(n - 1, 1)))
    clim = [vmin, vmax] if vmax > vmin else [vmin - 0.5, vmax + 0.5]
    if choice.rule == "none":
        clim = [float(np.min(ids)), float(np.max(ids))] if ids.size > 1 else clim
    return clim, sbar, kw


SF_TICK = 0.5                  # safety factor colour bar: a tick every 0.5 (1.0 among them)


def nice_range(vmin: float, vmax: float, bins: int = 5) -> tuple[float, float, int]:
    """(lo, hi, number of ticks): the data range widened to round tick values (1, 2, 2.5, 5
    × 10^k steps), so that a colour bar's evenly spaced labels read 0, 100, 200 … rather than
    0.101, 124.4 …"""
    import numpy as np
    from matplotlib.ticker import MaxNLocator

    t = MaxNLocator(nbins=bins, steps=[1, 2, 2.5, 5, 10]).tick_values(vmin, vmax)
    lo = float(t[t <= vmin + 1e-12 * max(abs(vmin), 1.0)].max(initial=t[0]))
    hi = float(t[t >= vmax - 1e-12 * max(abs(vmax), 1.0)].min(initial=t[-1]))
    step = float(np.diff(t).min()) if t.size > 1 else max(hi - lo, 1.0)
    return lo, hi, round((hi - lo) / step) + 1


def _tick_format(step: float) -> str:
    """printf format of ticks ``step`` apart: as many decimals as the step needs."""
    if step <= 0 or not math.isfinite(step):
        return "%.4g"
    dec = max(0, -math.floor(math.log10(step) + 1e-9))
    if abs(step * 10 ** dec - round(step * 10 ** dec)) > 1e-6:      # 2.5 × 10^k
        dec += 1
    return f"%.{dec}f" if dec <= 6 else "%.2e"


def safety_colormap(lo: float, hi: float, n: int = 256):
    """RdYlGn over [lo, hi] with its yellow middle at a safety factor of 1 (red below, green
    above, each side stretched over its own range)."""
    import numpy as np
    from matplotlib import colormaps
    from matplotlib.colors import ListedColormap

    v = np.linspace(lo, hi, n)
    below = 0.5 * (v - lo) / max(1.0 - lo, 1e-12)
    above = 0.5 + 0.5 * (v - 1.0) / max(hi - 1.0, 1e-12)
    pos = np.clip(np.where(v < 1.0, below, above), 0.0, 1.0)
    return ListedColormap(colormaps["RdYlGn"](pos), name="safety_factor")


def _set_camera(p, surf, hot: HotSpot | None, camera: str, zoom: float | str | None,
                window_size: tuple[int, int] = (1600, 900)) -> None:
    """Point the camera (``iso``: facing the hot spot; ``yz``: the end view fitted to the
    cross-section) and zoom (``"fit"``: see ``_fit``)."""
    import numpy as np

    if camera == "iso":
        _view_iso(p, surf, hot)
        if zoom == "fit":
            _fit(p, surf, hot, window_size)
            return
    else:
        {"xy": p.view_xy, "xz": p.view_xz, "yz": p.view_yz}[camera]()
        p.reset_camera()
    if camera == "yz":                                    # end view: fit the cross-section
        b = np.asarray(surf.bounds, float).reshape(3, 2)
        across = max(b[1, 1] - b[1, 0], b[2, 1] - b[2, 0], 1e-9)
        p.camera.zoom(float(np.clip(0.5 * surf.length / across, 0.9, 8.0)))
    else:
        p.camera.zoom(1.35 if zoom in (None, "fit") else float(zoom))


FIT_BAND = (0.24, 0.84)        # "fit": the shaft and the label between colour bar and title
FIT_WIDTH = 0.94               # … across this share of the width
LABEL_PX = 56                  # height of the two-line hot-spot label at font size 18


def _fit(p, surf, hot: HotSpot | None, window_size: tuple[int, int]) -> None:
    """Parallel projection fitted to the shaft: its projected outline (and the hot-spot
    label's anchor above it) fills ``FIT_WIDTH`` of the width or the ``FIT_BAND`` of the
    height, whichever is tighter, centred in that band."""
    import itertools

    import numpy as np

    w, h = (float(x) for x in window_size)
    cam = p.camera
    d = np.asarray(cam.position, float) - np.asarray(cam.focal_point, float)
    d /= np.linalg.norm(d)
    up = np.asarray(cam.up, float)
    right = np.cross(up, d)
    b = np.asarray(surf.bounds, float).reshape(3, 2)
    pts = [np.array(c) for c in itertools.product(*b)]
    if hot is not None:
        pts.append(np.asarray(hot.xyz, float) + _label_lift(surf) * up)
    pts = np.array(pts)
    xs, ys = pts @ right, pts @ up
    band = FIT_BAND[1] - FIT_BAND[0] - (LABEL_PX / h if hot is not None else 0.0)
    # parallel scale = half the visible height in model units
    scale = max((ys.max() - ys.min()) / (2.0 * band),
                (xs.max() - xs.min()) / (2.0 * FIT_WIDTH) * h / w)
    cx, cy = 0.5 * (xs.max() + xs.min()), 0.5 * (ys.max() + ys.min())
    # the band's centre sits this far above the picture's centre, in model units
    shift = (0.5 * (FIT_BAND[0] + FIT_BAND[1] - (LABEL_PX / h if hot is not None else 0.0))
             - 0.5) * 2.0 * scale
    centre = np.asarray(surf.center, float)
    along = d @ centre
    focal = cx * right + (cy - shift) * up + along * d
    p.enable_parallel_projection()
    cam.focal_point = focal
    cam.position = focal + d * 4.0 * surf.length
    cam.parallel_scale = scale
    p.reset_camera_clipping_range()


def _label_lift(surf) -> float:
    """How far above the hot spot (screen up, model units) its label is anchored."""
    import numpy as np
    b = np.asarray(surf.bounds, float).reshape(3, 2)
    return 0.75 * max(b[1, 1] - b[1, 0], b[2, 1] - b[2, 0], 0.1 * surf.length)


def _mark_hot_spot(p, surf, hot: HotSpot, choice: FieldChoice, grid, factor: float,
                   shape_field: str | None, camera: str) -> None:
    """A magenta ring around the (deformed) hot spot, facing the camera, so that the colour
    at the spot stays visible; its value and coordinates in a label above it (screen up),
    joined to the ring by a leader line."""
    import numpy as np
    import pyvista as pv

    xyz = np.array(hot.xyz)
    if factor and choice.association == "point":
        xyz = xyz + factor * np.asarray(grid.point_data[shape_field][hot.index], float)
    what = {"max": "max", "min": "min", "max_abs": "max abs"}[hot.rule]  # no "|": VTK
    unit = f" {choice.unit}" if choice.unit != "-" else ""
    kind = "node" if choice.association == "point" else "cell"
    text = (f"{what} {hot.value:.4g}{unit} ({kind})\n"
            f"({hot.xyz[0]:.1f}, {hot.xyz[1]:.1f}, {hot.xyz[2]:.1f}) mm")
    b = np.asarray(surf.bounds, float).reshape(3, 2)
    up = np.asarray(p.camera.up, float)
    anchor = xyz + _label_lift(surf) * up
    if camera == "iso":
        # the label grows to the right of its anchor: near the right end of the shaft,
        # move the anchor left along the axis so that the text stays in the picture
        t = (xyz[0] - b[0, 0]) / max(b[0, 1] - b[0, 0], 1e-9)
        if t > 0.7:
            anchor = anchor - np.array([0.28 * (b[0, 1] - b[0, 0]), 0.0, 0.0])
    d = np.asarray(p.camera.position, float) - np.asarray(p.camera.focal_point, float)
    d /= np.linalg.norm(d)
    right = np.cross(up, d)
    radius = 0.03 * surf.length
    t = np.linspace(0.0, 2.0 * np.pi, 73)
    # in front of the whole shaft (a diameter towards the eye: every point of the shaft is
    # within a radius of the axis; the same place on the screen in a parallel projection,
    # nearly so in perspective), so that a collar cannot hide part of it
    front = max(b[1, 1] - b[1, 0], b[2, 1] - b[2, 0])
    ring = xyz + front * d + radius * (np.outer(np.cos(t), right)
                                                    + np.outer(np.sin(t), up))
    p.add_mesh(pv.lines_from_points(ring), color="magenta", line_width=4)
    lead = anchor - xyz
    start = xyz + radius * lead / max(float(np.linalg.norm(lead)), 1e-12)
    p.add_mesh(pv.Line(start, anchor), color="black", line_width=2)
    p.add_point_labels(anchor.reshape(1, 3), [text], font_size=18, show_points=False,
                       always_visible=True, shape_opacity=0.85, shape_color="white",
                       text_color="black", margin=4)


def _view_iso(p, surf, hot) -> None:
    """Oblique view with the shaft axis (x) across the screen, looking at the side of the
    shaft where the hot spot is (from +y, +z when there is none)."""
    import numpy as np

    r = np.array([0.0, 1.0, 1.0])
    if hot is not None and np.hypot(hot.xyz[1], hot.xyz[2]) > 1e-9:
        r = np.array([0.0, hot.xyz[1], hot.xyz[2]])
    r /= np.linalg.norm(r)
    t = np.cross([1.0, 0.0, 0.0], r)
    d = np.array([0.5, 0.0, 0.0]) + r + 0.4 * t         # from the focal point to the eye
    d /= np.linalg.norm(d)
    up = np.cross(d, [1.0, 0.0, 0.0])
    up /= np.linalg.norm(up)                              # keeps +x pointing right
    c = np.array(surf.center)
    p.camera.focal_point = c
    p.camera.position = c + d * surf.length
    p.camera.up = up
    p.reset_camera()


def _screenshot(plotter, shot: Path) -> None:
    """Render and write the image under a temporary name, then rename (never half-written)."""

    with atomic_path(shot) as tmp:
        plotter.screenshot(str(tmp))
