"""Look at a result file: load a VTU, pick a field, find its hot spot.

Pure functions used by ``shaftfe view`` (see ``docs/FIELDS.md`` for the field names and units
every analysis writes); the picture itself is drawn by ``shaftfe.io.render`` on the boundary
faces made by ``shaftfe.io.surface``. PyVista / VTK are imported inside the functions, so
importing this module costs nothing.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

from shaftfe.errors import InputError

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
    "fkm_utilisation": ("-", "max", "FKM degree of utilisation at the assessed surface nodes"),
    "fkm_safety": ("-", "min", "FKM achieved safety factor at the assessed surface nodes"),
    "region": ("id", "none", "face group id: 0 volume, k = regions[k - 1]"),
    "group": ("id", "none", "mesh face group id: 0 volume, k = groups[k - 1]"),
}
MODE_PREFIX = "mode_"          # mode shapes: mode_<k>_<freq>Hz, 3 components, unitless
DEFAULT_ORDER = ("von_mises", "safety_factor", "displacement", "group", "region")
VECTOR_COMPONENTS = ("x", "y", "z")
TENSOR_COMPONENTS = ("xx", "yy", "zz", "xy", "yz", "xz")
_INTERNAL = ("vtkOriginalPointIds", "vtkOriginalCellIds", "vtkGhostType", "_view")


def field_unit(name: str) -> str:
    """Unit of a documented field; ``-`` for mode shapes and unknown fields."""
    if name in FIELDS:
        return FIELDS[name][0]
    return "-"


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


# ---------------------------------------------------------------------------------------------
# Loading and picking


def load(path) -> object:
    """Read a VTK XML unstructured grid (.vtu). Missing, empty or non-VTU files raise
    InputError naming the file."""

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
        from vtkmodules.vtkCommonCore import vtkObject  # not `import vtk`: all of VTK, 0.6 s
        self._obj = vtkObject
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


def fitted_peak(path, choice: FieldChoice) -> float | None:
    """The whole shaft's von Mises peak that the run which wrote ``path`` printed (``static``
    or ``report``: the sidecar ``summary.json``'s case at the file's speed), when ``choice`` is
    ``von_mises``. That peak is the surface fit between the nodes; the file holds nodal
    values, so ``view``'s hot spot can be a little lower: ``render`` names both."""
    if choice.name != "von_mises" or choice.n_components != 1:
        return None
    side = Path(path).with_name("summary.json")
    try:
        d = json.loads(side.read_text())
        vtu = d["vtu"]
        if vtu.get("file", Path(path).name) != Path(path).name:
            return None
        cases = d["static"]["cases"] if "static" in d else d["cases"]
        c = next(c for c in cases if abs(float(c["rpm"]) - float(vtu["rpm"])) < 1e-9)
        v = c["peak_von_mises_MPa"]
        return float(v) if v is not None else None
    except (OSError, ValueError, KeyError, TypeError, AttributeError, StopIteration):
        return None
