"""Look at a result file: load a VTU, pick a field, find its hot spot, render it with PyVista.

Pure functions used by ``shaftfe view`` (see ``docs/FIELDS.md`` for the field names and units
every analysis writes). PyVista / VTK are imported inside the functions, so importing this
module costs nothing.

Rendering path: the volume cells (tetra / tetra10) are reduced to their boundary faces (quadratic
triangles for tetra10) and those faces are subdivided (VTK nonlinear subdivision) so that curved
fillets and seats look curved. Cell fields that live on the face cells of the file (``region`` /
``group``: 0 on the volume, k ≥ 1 on the triangles of face group k) are mapped onto the boundary
faces by their corner nodes, so a mesh file shows its named face groups.
"""

from __future__ import annotations

import json
import os
import sys
import time
from dataclasses import dataclass
from pathlib import Path

# ---------------------------------------------------------------------------------------------
# The documented fields (docs/FIELDS.md): name -> (unit, hot-spot rule, what it is).
# Rule "max": the hot spot is the maximum; "min": the minimum (safety factor, life);
# "none": categorical ids, no hot spot.

FIELDS: dict[str, tuple[str, str, str]] = {
    "displacement": ("mm", "max", "nodal displacement, 3 components x, y, z"),
    "von_mises": ("MPa", "max", "von Mises equivalent stress at the nodes"),
    "von_mises_ref": ("MPa", "max", "von Mises stress at the static reference speed"),
    "max_principal": ("MPa", "max", "largest principal stress at the nodes"),
    "stress": ("MPa", "max", "stress tensor, 6 components xx, yy, zz, xy, yz, xz"),
    "safety_factor": ("-", "min", "fatigue safety factor at the design life"),
    "life_blocks": ("blocks", "min", "fatigue life in passes of the load block"),
    "damage_per_block": ("-", "max", "Miner damage of one pass of the load block"),
    "region": ("id", "none", "face group id: 0 volume, k = regions[k - 1]"),
    "group": ("id", "none", "mesh face group id: 0 volume, k = groups[k - 1]"),
}
SF_CLIP = 3.0                  # safety factor colour scale: 1.0 marked, clipped above this
MODE_PREFIX = "mode_"          # mode shapes: mode_<k>_<freq>Hz, 3 components, unitless
DEFAULT_ORDER = ("von_mises", "safety_factor", "displacement", "group", "region")
CAMERAS = ("iso", "xy", "xz", "yz")
VECTOR_COMPONENTS = ("x", "y", "z")
TENSOR_COMPONENTS = ("xx", "yy", "zz", "xy", "yz", "xz")
SCREENSHOT_SUFFIXES = (".png", ".jpg", ".jpeg")
_INTERNAL = ("vtkOriginalPointIds", "vtkOriginalCellIds", "vtkGhostType", "_view")
# VTK cell types with a 3D volume (linear, quadratic, Lagrange, Bezier solids).
_VOLUME_TYPES = frozenset({10, 11, 12, 13, 14, 24, 25, 26, 27, 29, 31, 32, 33, 71, 72, 73,
                           74, 78, 79, 80, 81})
# Corner-node triples of the four faces of a VTK tetra (outward normals) and the mid-side
# nodes of tetra10 on the edges (a, b), (b, c), (c, a) of each face.
_TET_FACES = ((0, 1, 3), (1, 2, 3), (2, 0, 3), (0, 2, 1))
_TET10_EDGE = {(0, 1): 4, (1, 2): 5, (0, 2): 6, (0, 3): 7, (1, 3): 8, (2, 3): 9}


def field_unit(name: str) -> str:
    """Unit of a documented field; ``-`` for mode shapes and unknown fields."""
    if name in FIELDS:
        return FIELDS[name][0]
    return "-"


def is_categorical(name: str) -> bool:
    return name in FIELDS and FIELDS[name][1] == "none"


@dataclass(frozen=True)
class FieldChoice:
    name: str
    association: str          # "point" | "cell"
    n_components: int
    component: str | None     # None (scalar), "magnitude", "x".."z", "xx".."xz", "0".."n-1"
    label: str                # e.g. "von_mises", "displacement magnitude", "stress xx"
    unit: str
    rule: str                 # "max" | "min" | "max_abs" | "none"


@dataclass(frozen=True)
class HotSpot:
    rule: str                 # "max" | "min" | "max_abs"
    index: int                # point id (point field) or cell id (cell field) in the file
    value: float
    xyz: tuple[float, float, float]


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


# ---------------------------------------------------------------------------------------------
# Loading and picking


def headless() -> bool:
    """True on a Linux/BSD machine without an X or Wayland display."""
    if sys.platform.startswith(("win", "darwin")):
        return False
    return not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def use_offscreen_egl() -> None:
    """Make VTK pick its EGL render window (no X server) unless the user chose one."""
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")


def load(path) -> object:
    """Read a VTK XML unstructured grid (.vtu). Missing, empty or non-VTU files raise
    InputError naming the file."""
    from shaftfe.errors import InputError

    p = Path(path)
    allowed = "an existing VTK XML unstructured grid file (.vtu)"
    if p.is_dir():
        raise InputError(str(path), "file", allowed + "; give a file inside it",
                         reason="is a directory")
    if not p.is_file():
        raise InputError(str(path), "file", allowed, reason="does not exist")
    try:
        with open(p, "rb") as fh:
            head = fh.read(4096)
    except OSError as exc:
        raise InputError(str(path), "file", allowed, reason=f"cannot be read ({exc})") from None
    if b"<VTKFile" not in head or b'type="UnstructuredGrid"' not in head:
        raise InputError(str(path), "file", allowed,
                         reason="is not a VTK XML UnstructuredGrid file")
    import pyvista as pv

    with _vtk_quiet():
        try:
            grid = pv.read(str(p), force_ext=".vtu")
        except Exception as exc:  # corrupt XML / binary payload
            raise InputError(str(path), "file", allowed,
                             reason=f"cannot be parsed ({type(exc).__name__})") from None
    if grid is None or grid.n_points == 0 or grid.n_cells == 0:
        raise InputError(str(path), "file", allowed, reason="holds no points or cells")
    return grid


class _vtk_quiet:
    """Silence VTK's own error printing (we report errors ourselves)."""

    def __enter__(self):
        import vtk
        self._obj = vtk.vtkObject
        self._prev = self._obj.GetGlobalWarningDisplay()
        self._obj.GlobalWarningDisplayOff()
        return self

    def __exit__(self, *exc):
        self._obj.SetGlobalWarningDisplay(self._prev)
        return False


def field_names(grid) -> dict[str, tuple[str, int]]:
    """Fields of the grid: name -> (association, number of components). Point data first;
    VTK bookkeeping arrays are left out."""
    out: dict[str, tuple[str, int]] = {}
    for assoc, data in (("point", grid.point_data), ("cell", grid.cell_data)):
        for name in data.keys():
            if name in _INTERNAL or name in out:
                continue
            arr = data[name]
            if arr.dtype.kind not in "biuf":
                continue
            out[name] = (assoc, 1 if arr.ndim == 1 else int(arr.shape[1]))
    return out


def default_field(grid) -> str | None:
    names = field_names(grid)
    for n in DEFAULT_ORDER:
        if n in names:
            return n
    return next(iter(names), None)


def allowed_components(name: str, n: int) -> tuple[str, ...]:
    if n == 1:
        return ()
    if n == 3:
        return ("magnitude", *VECTOR_COMPONENTS, "0", "1", "2")
    if n == 6 and (name == "stress" or name not in FIELDS):
        return (*TENSOR_COMPONENTS, *(str(i) for i in range(6)))
    return ("magnitude", *(str(i) for i in range(n)))


def choose_field(grid, field: str | None, component: str | None,
                 source: str = "result") -> FieldChoice:
    """Validate ``field`` / ``component`` against the grid. Unknown names raise InputError
    listing the fields (or components) present."""
    from shaftfe.errors import InputError

    names = field_names(grid)
    if not names:
        raise InputError(source, "field", "a file with point or cell data", got=None,
                         reason="no data arrays in the file")
    if field is None:
        field = default_field(grid)
    if field not in names:
        raise InputError(source, "--field", " | ".join(names), got=field,
                         reason="is not in the file")
    assoc, n = names[field]
    comps = allowed_components(field, n)
    unit = field_unit(field)
    rule = FIELDS[field][1] if field in FIELDS else "max"
    if n == 1:
        if component not in (None, "magnitude", "0"):
            raise InputError(source, "--component", f"none ({field} is a scalar)",
                             got=component)
        return FieldChoice(field, assoc, 1, None, field, unit, rule)
    if component is None:
        component = "xx" if comps[0] == "xx" else "magnitude"
    if component not in comps:
        raise InputError(source, "--component", " | ".join(comps), got=component,
                         reason=f"is not a component of {field} ({n} components)")
    if component == "magnitude":
        return FieldChoice(field, assoc, n, component, f"{field} magnitude", unit,
                           "max" if rule != "none" else "none")
    idx = _component_index(component)
    label = f"{field} {component}" if not component.isdigit() else f"{field}[{idx}]"
    if n == 6 and comps[0] == "xx":
        label = f"{field} {TENSOR_COMPONENTS[idx]}"
    elif n == 3:
        label = f"{field} {VECTOR_COMPONENTS[idx]}"
    return FieldChoice(field, assoc, n, component, label, unit,
                       "max_abs" if rule != "none" else "none")


def _component_index(component: str) -> int:
    if component.isdigit():
        return int(component)
    if component in TENSOR_COMPONENTS:
        return TENSOR_COMPONENTS.index(component)
    return VECTOR_COMPONENTS.index(component)


def values(grid, choice: FieldChoice):
    """The scalar shown for ``choice``: one float per point (or cell) of the file."""
    import numpy as np

    data = grid.point_data if choice.association == "point" else grid.cell_data
    arr = np.asarray(data[choice.name], dtype=float)
    if choice.n_components == 1:
        return arr.reshape(-1)
    if choice.component == "magnitude":
        return np.linalg.norm(arr, axis=1)
    return arr[:, _component_index(choice.component)]


def hot_spot(grid, choice: FieldChoice, vals=None, exclude=None) -> HotSpot | None:
    """Max of the field (min for safety factor and life; max |value| for a signed component)
    over all finite values; coordinates of the node (point field) or cell centre. ``exclude``:
    ids (points or cells) left out of the search, e.g. the singular points of the analysis;
    ignored if it would leave nothing."""
    import numpy as np

    if choice.rule == "none":
        return None
    v = values(grid, choice) if vals is None else vals
    finite = np.isfinite(v)
    if exclude is not None and np.size(exclude):
        keep = finite.copy()
        keep[np.asarray(exclude, dtype=np.int64)] = False
        if keep.any():
            finite = keep
    if not finite.any():
        return None
    if choice.rule == "min":
        i = int(np.argmin(np.where(finite, v, np.inf)))
    elif choice.rule == "max_abs":
        i = int(np.argmax(np.where(finite, np.abs(v), -np.inf)))
    else:
        i = int(np.argmax(np.where(finite, v, -np.inf)))
    if choice.association == "point":
        xyz = grid.points[i]
    else:
        xyz = grid.extract_cells([i]).center
    return HotSpot(choice.rule, i, float(v[i]), tuple(float(c) for c in xyz))


def group_names(grid, path) -> dict[int, str]:
    """Id -> name of the face groups: field data ``region_names`` / ``group_names`` (entry
    k - 1 names id k), ``group_names_utf8`` (``shaftfe mesh``: UTF-8 bytes, one name a line)
    or, for ``result.vtu``, the sidecar ``summary.json`` (``vtu.regions``)."""
    out: dict[int, str] = {}
    for key in ("region_names", "group_names"):
        if key in grid.field_data.keys():
            out = {k + 1: str(s) for k, s in enumerate(grid.field_data[key])}
            return out
    if "group_names_utf8" in grid.field_data.keys():          # shaftfe mesh --out x.vtu
        import numpy as np
        raw = bytes(np.asarray(grid.field_data["group_names_utf8"], dtype=np.uint8))
        names = raw.decode("utf-8", errors="replace").split("\n")
        return {k + 1: s for k, s in enumerate(names)}
    side = Path(path).with_name("summary.json")
    try:
        vtu = json.loads(side.read_text())["vtu"]
        if vtu.get("file", Path(path).name) == Path(path).name:
            out = {k + 1: str(s) for k, s in enumerate(vtu["regions"])}
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        pass
    return out


# ---------------------------------------------------------------------------------------------
# Geometry for rendering


def boundary(grid, choice: FieldChoice, vals):
    """Boundary faces of the volume cells (quadratic triangles for tetra10) with all point data,
    the shown scalar as ``_view`` and, for cell fields on face cells, the face value."""
    import numpy as np
    import pyvista as pv

    grid.point_data.pop("_view", None)
    grid.cell_data.pop("_view", None)
    ctypes = np.asarray(grid.celltypes)
    is_vol = np.isin(ctypes, list(_VOLUME_TYPES))
    if choice.association == "point":
        grid.point_data["_view"] = vals
    else:
        grid.cell_data["_view"] = vals
    if not is_vol.any():                                  # a surface mesh already
        return grid.extract_cells(np.arange(grid.n_cells))
    cells = grid.cells_dict
    tets = {t: cells[t] for t in (10, 24) if t in cells}
    if not tets or is_vol.sum() != sum(len(c) for c in tets.values()):
        # other solid types: let VTK find the boundary (no face-group mapping)
        sub = grid.extract_cells(np.flatnonzero(is_vol))
        return _geometry_filter(sub)
    faces, tri_type = [], None
    cell_of_face = []
    for t, conn in tets.items():
        ids = np.flatnonzero(ctypes == t)
        for a, b, c in _TET_FACES:
            if t == 24:
                cols = [a, b, c, _edge(a, b), _edge(b, c), _edge(c, a)]
                tri_type = pv.CellType.QUADRATIC_TRIANGLE
            else:
                cols = [a, b, c]
                tri_type = tri_type or pv.CellType.TRIANGLE
            f = conn[:, cols]
            if t == 10 and 24 in tets:                     # mixed orders: degrade to linear
                f = f[:, :3]
            faces.append(f)
            cell_of_face.append(ids)
    if len(tets) == 2:
        faces = [f[:, :3] for f in faces]
        tri_type = pv.CellType.TRIANGLE
    faces = np.concatenate(faces)
    cell_of_face = np.concatenate(cell_of_face)
    key = np.sort(faces[:, :3], axis=1)
    _, inv, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    outer = counts[inv.reshape(-1)] == 1
    faces, cell_of_face, key = faces[outer], cell_of_face[outer], key[outer]
    bnd = pv.UnstructuredGrid({tri_type: faces}, grid.points)
    for name in grid.point_data.keys():
        bnd.point_data[name] = grid.point_data[name]
    if choice.association == "cell":
        face_val = np.asarray(vals, dtype=float)[cell_of_face]
        surf_ids = np.flatnonzero(~is_vol)
        if surf_ids.size:                                  # values on the face cells win
            sconn = _corner_triples(grid, surf_ids)
            if sconn is not None:
                both = np.concatenate([key, np.sort(sconn, axis=1)])
                _, inv2 = np.unique(both, axis=0, return_inverse=True)
                inv2 = inv2.reshape(-1)
                lookup = np.full(inv2.max() + 1, np.nan)
                # several groups on one face: the largest id is shown
                np.fmax.at(lookup, inv2[len(key):], np.asarray(vals, float)[surf_ids])
                hit = lookup[inv2[:len(key)]]
                face_val = np.where(np.isfinite(hit), hit, face_val)
        bnd.cell_data["_view"] = face_val
    return bnd


def _edge(a: int, b: int) -> int:
    return _TET10_EDGE[(min(a, b), max(a, b))]


def _corner_triples(grid, ids):
    """First three point ids of the triangle cells ``ids`` (None when they are not triangles)."""
    import numpy as np

    ct = np.asarray(grid.celltypes)[ids]
    if not np.isin(ct, (5, 22)).all():
        return None
    offs = np.asarray(grid.cell_offsets if hasattr(grid, 'cell_offsets') else grid.offset)
    conn = np.asarray(grid.cell_connectivity)
    start = offs[ids]
    return np.stack([conn[start], conn[start + 1], conn[start + 2]], axis=1)


def _geometry_filter(sub):
    import pyvista as pv
    from vtkmodules.vtkFiltersGeometry import vtkUnstructuredGridGeometryFilter

    f = vtkUnstructuredGridGeometryFilter()
    f.SetInputData(sub)
    f.Update()
    return pv.wrap(f.GetOutput())


def subdivision_level(bnd) -> int:
    """Nonlinear subdivision levels for the quadratic faces: 2 (16 triangles per face), 1 above
    200k faces."""
    return 2 if bnd.n_cells <= 200_000 else 1


def surface(bnd, subdivision: int | None = None):
    """PolyData of the boundary with curved (subdivided) quadratic faces."""
    if subdivision is None:
        subdivision = subdivision_level(bnd)
    try:
        return bnd.extract_surface(nonlinear_subdivision=subdivision,
                                   algorithm="dataset_surface")
    except TypeError:                                       # pyvista < 0.47
        return bnd.extract_surface(nonlinear_subdivision=subdivision)


# ---------------------------------------------------------------------------------------------
# Plotting


def parse_window_size(text: str) -> tuple[int, int]:
    from shaftfe.errors import InputError

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
    from shaftfe.errors import InputError

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
           zoom: float | None = None) -> ViewResult:
    """Load ``path``, render ``field`` and either save ``screenshot`` (written atomically) or
    open an interactive window. Input errors are raised before anything is drawn.
    ``hot_exclude``: point/cell ids the hot spot is not searched in (drawn all the same).
    ``zoom``: camera zoom after fitting the model (default 1.35; the yz end view fits the
    cross-section instead)."""
    import numpy as np

    from shaftfe.errors import InputError

    t0 = time.perf_counter()
    if camera not in CAMERAS:
        raise InputError("command line", "--camera", " | ".join(CAMERAS), got=camera)
    shot = Path(screenshot) if screenshot is not None else None
    if shot is not None and shot.suffix.lower() not in SCREENSHOT_SUFFIXES:
        raise InputError("command line", "--screenshot",
                         "a path ending in " + " | ".join(SCREENSHOT_SUFFIXES), got=str(shot))
    if off_screen is None:
        off_screen = shot is not None or headless()
    if off_screen:
        use_offscreen_egl()
    grid = load(path)
    choice = choose_field(grid, field, component, source=str(path))
    vals = values(grid, choice)
    finite = np.isfinite(vals)
    if not finite.any():
        raise InputError(str(path), choice.name, "at least one finite value",
                         reason="has no finite values")
    vmin, vmax = float(vals[finite].min()), float(vals[finite].max())
    hot = hot_spot(grid, choice, vals, exclude=hot_exclude)

    warp_note = None
    disp = grid.point_data["displacement"] if "displacement" in grid.point_data.keys() else None
    shape_field = None
    if choice.name.startswith(MODE_PREFIX) and choice.n_components == 3:
        shape_field = choice.name                          # a mode warps by its own shape
    elif disp is not None and np.ndim(disp) == 2 and np.shape(disp)[1] == 3:
        shape_field = "displacement"
    factor = 0.0
    if warp == "auto" or (isinstance(warp, float) and warp > 0):
        if shape_field is None:
            warp_note = f"no 'displacement' field in {path}: not warped"
        else:
            u = np.asarray(grid.point_data[shape_field], float)
            umax = float(np.nanmax(np.linalg.norm(u, axis=1)))
            if warp == "auto":
                factor = 0.05 * grid.length / umax if umax > 0 else 0.0
            else:
                factor = float(warp)

    if shot is None and off_screen:
        shot = Path(path).with_name(f"{Path(path).stem}_{choice.name}.png")
    if shot is not None:
        from shaftfe.util.atomic import check_output_file
        check_output_file(shot, "--screenshot")

    bnd = boundary(grid, choice, np.where(finite, vals, np.nan))
    if factor:
        bnd = bnd.warp_by_vector(shape_field, factor=factor)
    level = subdivision_level(bnd)
    surf = surface(bnd, level)
    edge_lines = element_edges(bnd, level) if edges else None
    names = group_names(grid, path) if choice.rule == "none" else {}
    plotter = _plot(path, surf, edge_lines, choice, vmin, vmax, hot, factor,
                    shape_field, grid, window_size, camera, off_screen, names, zoom)
    try:
        if shot is not None:
            _screenshot(plotter, shot)
            res = ViewResult(str(path), choice, vmin, vmax, int((~finite).sum()), hot, factor,
                             warp_note, str(shot), window_size, time.perf_counter() - t0,
                             bool(off_screen))
            return res
        res = ViewResult(str(path), choice, vmin, vmax, int((~finite).sum()), hot, factor,
                         warp_note, None, window_size, time.perf_counter() - t0, False)
        print(res.summary(), flush=True)
        plotter.show()
        return res
    finally:
        plotter.close()


def _plot(path, surf, edge_src, choice, vmin, vmax, hot, factor, shape_field, grid,
          window_size, camera, off_screen, names, zoom=None):
    import numpy as np
    import pyvista as pv

    p = pv.Plotter(off_screen=off_screen, window_size=list(window_size))
    p.set_background("white")
    title = f"{choice.label} [{choice.unit}]"
    if factor:
        title += f"  (deformed x{factor:.3g})"
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
        a = max(abs(vmin), abs(vmax))
        vmin, vmax = -a, a
    elif choice.name == "safety_factor":
        # an engineer reads a safety factor around 1: red below 1, green above, clipped at
        # SF_CLIP (a linear 0.47-15 scale painted everything from 0.5 to 4 the same red)
        kw["cmap"] = "RdYlGn"
        kw["above_color"] = "darkgreen"
        kw["annotations"] = {1.0: "1.0"}
        vmin, vmax = min(vmin, 0.9), SF_CLIP
        sbar.update(title=title.replace("\n", "") + f" (clipped at {SF_CLIP:g})\n")
    else:
        kw["cmap"] = "jet" if choice.rule != "min" else "jet_r"
        if choice.name == "life_blocks" and vmin > 0 and vmax / vmin > 100:
            kw["log_scale"] = True
    clim = [vmin, vmax] if vmax > vmin else [vmin - 0.5, vmax + 0.5]
    if choice.rule == "none":
        clim = [float(np.min(ids)), float(np.max(ids))] if ids.size > 1 else clim
    actor = p.add_mesh(surf, scalars="_view", clim=clim, scalar_bar_args=sbar,
                       smooth_shading=True, split_sharp_edges=True, nan_color="lightgrey",
                       show_scalar_bar=True, **kw)
    if edge_src is not None:
        # push the faces back a little so that the edge lines on them are not z-fighting
        actor.mapper.SetResolveCoincidentTopologyToPolygonOffset()
        actor.mapper.SetRelativeCoincidentTopologyPolygonOffsetParameters(2.0, 4.0)
        p.add_mesh(edge_src, color="black", line_width=1, opacity=0.6)
    if camera == "iso":
        _view_iso(p, surf, hot)
    else:
        {"xy": p.view_xy, "xz": p.view_xz, "yz": p.view_yz}[camera]()
        p.reset_camera()
    if camera == "yz":                                    # end view: fit the cross-section
        b = np.asarray(surf.bounds, float).reshape(3, 2)
        across = max(b[1, 1] - b[1, 0], b[2, 1] - b[2, 0], 1e-9)
        p.camera.zoom(float(np.clip(0.5 * surf.length / across, 0.9, 8.0)))
    else:
        p.camera.zoom(1.35 if zoom is None else float(zoom))
    if hot is not None:
        xyz = np.array(hot.xyz)
        if factor and choice.association == "point":
            xyz = xyz + factor * np.asarray(grid.point_data[shape_field][hot.index], float)
        what = {"max": "max", "min": "min", "max_abs": "max abs"}[hot.rule]  # no "|": VTK
        unit = f" {choice.unit}" if choice.unit != "-" else ""
        text = (f"{what} {hot.value:.4g}{unit}\n"
                f"({hot.xyz[0]:.1f}, {hot.xyz[1]:.1f}, {hot.xyz[2]:.1f}) mm")
        # marker on the surface; the label sits above it (screen up), joined by a leader line
        b = np.asarray(surf.bounds, float).reshape(3, 2)
        lift = 0.75 * max(b[1, 1] - b[1, 0], b[2, 1] - b[2, 0], 0.1 * surf.length)
        anchor = xyz + lift * np.asarray(p.camera.up, float)
        if camera == "iso":
            # the label grows to the right of its anchor: near the right end of the shaft,
            # move the anchor left along the axis so that the text stays in the picture
            t = (xyz[0] - b[0, 0]) / max(b[0, 1] - b[0, 0], 1e-9)
            if t > 0.7:
                anchor = anchor - np.array([0.28 * (b[0, 1] - b[0, 0]), 0.0, 0.0])
        p.add_mesh(pv.Sphere(radius=0.015 * surf.length, center=xyz), color="magenta")
        p.add_mesh(pv.Line(xyz, anchor), color="black", line_width=2)
        p.add_point_labels(anchor.reshape(1, 3), [text], font_size=18, show_points=False,
                           always_visible=True, shape_opacity=0.85, shape_color="white",
                           text_color="black", margin=4)
    p.add_axes(color="black", xlabel="x", ylabel="y", zlabel="z")
    p.add_text(f"{Path(path).name}: {choice.label}", position="upper_left", font_size=12,
               color="black")
    return p


def element_edges(bnd, subdivision: int = 2):
    """Edges of the boundary faces as polylines. A quadratic edge (a, m, b) is sampled at
    2**subdivision segments on its quadratic curve: the same points the subdivided surface
    has on that edge, so the lines lie exactly on the curved faces."""
    import numpy as np
    import pyvista as pv

    cells = bnd.cells_dict
    pts = np.asarray(bnd.points, float)
    if pv.CellType.QUADRATIC_TRIANGLE in cells:
        c = cells[pv.CellType.QUADRATIC_TRIANGLE]
        e = np.concatenate([c[:, [0, 3, 1]], c[:, [1, 4, 2]], c[:, [2, 5, 0]]])
        e[:, [0, 2]] = np.sort(e[:, [0, 2]], axis=1)
        e = np.unique(e, axis=0)
        n = 2 ** max(int(subdivision), 0)
        t = np.linspace(0.0, 1.0, n + 1)
        a, m, b = (pts[e[:, k]] for k in range(3))
        xyz = (a[:, None] * ((1 - t) * (1 - 2 * t))[None, :, None]
               + m[:, None] * (4 * t * (1 - t))[None, :, None]
               + b[:, None] * (t * (2 * t - 1))[None, :, None]).reshape(-1, 3)
        ids = np.arange(len(e) * (n + 1)).reshape(len(e), n + 1)
        lines = np.column_stack([np.full(len(e), n + 1), ids]).ravel()
        return pv.PolyData(xyz, lines=lines)
    if pv.CellType.TRIANGLE in cells:
        c = cells[pv.CellType.TRIANGLE]
        e = np.unique(np.sort(np.concatenate([c[:, [0, 1]], c[:, [1, 2]], c[:, [2, 0]]]),
                              axis=1), axis=0)
        return pv.PolyData(pts, lines=np.column_stack([np.full(len(e), 2), e]).ravel())
    return bnd.extract_all_edges()


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
    from shaftfe.util.atomic import atomic_path

    with atomic_path(shot) as tmp:
        plotter.screenshot(str(tmp))
