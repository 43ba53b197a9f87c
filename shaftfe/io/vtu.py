"""Result files of the static analysis: VTU (meshio), summary JSON, deflection/bending plot.

``result.vtu`` (open with ParaView or PyVista):

* points: the mesh nodes (P2: corners and mid-side nodes), mm;
* cells: ``tetra10`` (P2) or ``tetra`` (P1) for the shaft volume, then ``triangle6`` /
  ``triangle`` for every named face group;
* point data ``displacement`` (n, 3) mm, ``von_mises`` MPa, ``max_principal`` MPa and
  ``stress`` (n, 6) MPa with the components in the order xx, yy, zz, xy, yz, xz
  (``recovery.STRESS_COMPONENTS``), all at the rpm given (fields scale with (rpm/ref)²);
* cell data ``region``: 0 for the volume, k ≥ 1 for the face group ``regions[k − 1]`` as listed
  in ``summary.json`` (``vtu.regions``);
* optionally further point fields on the same nodes (``extra_point_data``): the assessment report
  adds the fatigue fields ``safety_factor``, ``life_blocks`` and ``damage_per_block`` of the same
  static solution, so one file holds the whole run (docs/FIELDS.md).

Files are written to a temporary name and renamed (never half-written).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from shaftfe.fe import assembly as fem
from shaftfe.fe import recovery
from shaftfe.fe.assembly import element_nodes
from shaftfe.util.atomic import atomic_path, check_suffix, write_atomic
from shaftfe.util.units import rpm2_scale

MESH_SUFFIXES = (".vtu", ".msh")       # the mesh files ``write_mesh`` writes (meshio)


def mesh_cells(m) -> tuple[list, list, list[str]]:
    """meshio cells of a scikit-fem mesh: the volume (tetra10 / tetra), then the triangles of
    every named face group; the cell data ``region`` (0 volume, k = names[k − 1]) and the
    names."""
    quad = fem.is_quadratic(m)
    vol = ("tetra10" if quad else "tetra", fem.element_nodes(m).T.astype(np.int64))
    cells = [vol]
    region = [np.zeros(vol[1].shape[0], dtype=np.int32)]
    names = sorted(m.boundaries)
    tri = []
    for i, g in enumerate(names):
        f = np.asarray(m.boundaries[g])
        if quad:
            tri.append(triangle6_connectivity(m, f))
        else:
            tri.append(m.facets[:, f].T.astype(np.int64))
        region.append(np.full(f.size, i + 1, dtype=np.int32))
    if tri:
        cells.append(("triangle6" if quad else "triangle", np.concatenate(tri)))
        region = [region[0], np.concatenate(region[1:])]
    return cells, region, names


def write_fields_vtu(m, path, point_data: dict) -> tuple[Path, list[str]]:
    """The mesh ``m`` (scikit-fem) with the given point fields and the cell data ``region``;
    written atomically (``write_point_fields``). Returns the path and the region names."""
    cells, region, names = mesh_cells(m)
    return write_point_fields(m.doflocs.T, cells, region, path, point_data), names


def write_point_fields(points, cells: list, region: list, path, point_data: dict) -> Path:
    """Points (n, 3), meshio cell blocks with their ``region`` cell data, and point fields (one
    row per point; float32 kept, anything else as float64), written atomically as VTU."""
    import meshio

    n = np.asarray(points).shape[0]
    data = {}
    for name, arr in point_data.items():
        a = np.asarray(arr)
        a = a if a.dtype == np.float32 else a.astype(float)     # float32 stays (mode shapes)
        if a.shape[:1] != (n,):
            raise ValueError(f"point field {name!r}: shape {a.shape}, needs ({n}, ...)")
        data[name] = a
    out = meshio.Mesh(np.ascontiguousarray(points), cells, point_data=data,
                      cell_data={"region": region})
    path = Path(path)
    with atomic_path(path) as tmp:
        # raw binary, not zlib: meshio compresses at zlib's default level, 90 % of the write
        # (x2_57's larger zone: 0.061 s → 0.006 s, 1.7 → 2.7 MB); ParaView reads both
        meshio.write(tmp, out, file_format="vtu", compression=None)
    return path


def write_vtu(result, path, rpm: float, *,
              extra_point_data: dict | None = None) -> tuple[Path, list[str]]:
    """Write the fields of ``result`` (a ``StaticResult``) scaled to ``rpm``, plus
    ``extra_point_data`` (name -> one value per node, or (n, k)), written unscaled. Returns the
    path and the region names (cell data ``region`` = index + 1)."""
    m = result.mesh.mesh
    s = 1.0 if rpm == result.ref_rpm else rpm2_scale(rpm, result.ref_rpm)
    stress = result.stress_ref * s
    point_data = {"displacement": result.u_ref.reshape(-1, 3) * s,
                  "von_mises": result.von_mises_ref * s,
                  "max_principal": recovery.principal(stress)[0],
                  "stress": np.ascontiguousarray(stress.T)}
    for name in extra_point_data or {}:
        if name in point_data:
            raise ValueError(f"extra point field {name!r} would replace a static field")
    return write_fields_vtu(m, path, {**point_data, **(extra_point_data or {})})


def stress_envelope(mesh, vm: np.ndarray, n_slices: int = 120) -> tuple[np.ndarray, np.ndarray]:
    """The largest nodal von Mises of the elements that reach into each of ``n_slices`` equal
    slices along x (``span_envelope`` over the elements of ``mesh``)."""
    x = np.asarray(mesh.doflocs[0])
    en = element_nodes(mesh)
    return span_envelope(x[en].min(axis=0), x[en].max(axis=0), np.asarray(vm)[en].max(axis=0),
                         (float(x.min()), float(x.max())), n_slices)


def span_envelope(lo, hi, v, x_range: tuple[float, float],
                  n_slices: int = 120) -> tuple[np.ndarray, np.ndarray]:
    """Slice bins over ``x_range`` and, in each slice, the largest ``v`` of the pieces
    (elements, outline segments) spanning [lo, hi] in x: a piece long in x counts in every slice
    it spans, so a slice without a node of its own (a coarse uniform segment) still shows the
    stress there, not 0."""
    lo, hi, v = (np.asarray(a, dtype=float) for a in (lo, hi, v))
    bins = np.linspace(x_range[0], x_range[1], n_slices + 1)
    i0 = np.clip(np.searchsorted(bins, lo, side="right") - 1, 0, n_slices - 1)
    i1 = np.clip(np.searchsorted(bins, hi, side="left") - 1, 0, n_slices - 1)
    i1 = np.maximum(i1, i0)
    count = i1 - i0 + 1
    rep = np.repeat(np.arange(lo.size), count)
    first = np.repeat(np.cumsum(count) - count, count)
    slices = i0[rep] + (np.arange(rep.size) - first)
    env = np.zeros(n_slices)
    np.maximum.at(env, slices, v[rep])
    return bins, env


def load_plane(uy, uz) -> np.ndarray:
    """Unit vector (n_y, n_z) of the plane the axis bends in: the direction that carries the
    most of Σ u² over the axis points (the leading principal direction of the (u_y, u_z)
    pairs, uncentred); its sign makes the largest deflection positive."""
    a = np.column_stack([np.asarray(uy, float), np.asarray(uz, float)])
    w, v = np.linalg.eigh(a.T @ a)
    n = v[:, int(np.argmax(w))]
    proj = a @ n
    if proj.size and proj[int(np.argmax(np.abs(proj)))] < 0:
        n = -n
    return n


def bearing_line(case, x):
    """(u_y, u_z) at ``x`` of the straight line through the two bearings' remote points (the
    shaft's rigid-body motion on its springs), or None unless there are exactly two."""
    b = sorted(case.bearings, key=lambda b: b.x_mm)
    if len(b) != 2 or b[1].x_mm == b[0].x_mm:
        return None
    t = (np.asarray(x, float) - b[0].x_mm) / (b[1].x_mm - b[0].x_mm)
    return (b[0].uy_mm + t * (b[1].uy_mm - b[0].uy_mm),
            b[0].uz_mm + t * (b[1].uz_mm - b[0].uz_mm))


def plot_png(result, path, rpm: float, *, envelope=None, model: str = "3D FE",
             clearance: tuple[float, float] | None = None) -> Path:
    """Deflection line and the von Mises envelope along x. Top: the axis's signed deflection
    in its load plane (``load_plane``), in total (bearing springs' rigid-body motion
    included) and its bending part (relative to the line through the two bearings), the beam
    model's line in the same plane, the stations as labelled vertical lines and, with
    ``clearance`` = (x, c) in mm, the clearance ± c at x. Bottom: the von Mises envelope of
    the elements of ``result.mesh`` unless ``envelope`` = (bins, values at
    ``result.ref_rpm``) is given (the axisymmetric model's surface); ``model`` labels the
    curves."""
    import io

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    s = 1.0 if rpm == result.ref_rpm else rpm2_scale(rpm, result.ref_rpm)
    case = result.case(rpm)
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 7.6), sharex=True,
                                 gridspec_kw={"height_ratios": [1.25, 1]})
    x = np.asarray(result.axis_x, float)
    u = np.asarray(result.axis_u_ref, float) * s
    n = load_plane(u[:, 1], u[:, 2])
    um = 1e3                                                        # mm -> µm
    a1.axhline(0.0, color="0.6", lw=0.8)
    a1.plot(x, (u[:, 1:3] @ n) * um, color="tab:blue",
            label=f"{model}, total (incl. rigid-body motion on the bearing springs)")
    line = bearing_line(case, x)
    if line is not None:
        bend = (u[:, 1] - line[0]) * n[0] + (u[:, 2] - line[1]) * n[1]
        a1.plot(x, bend * um, color="tab:green",
                label=f"{model}, bending only (relative to the bearing line)")
    beam = getattr(case, "beam", None)
    if beam and "uy_line_mm" in beam:
        bu = np.asarray(beam["uy_line_mm"]) * n[0] + np.asarray(beam["uz_line_mm"]) * n[1]
        a1.plot(beam["x_line_mm"], bu * um, "--", color="tab:orange",
                label="beam model, total")
    off = np.abs(u[:, 1] * -n[1] + u[:, 2] * n[0]).max() * um
    merged: dict[float, list] = {}                 # one label per position (gear + CW1)
    for st in case.stations:
        name = st.name.split(":", 1)[-1]
        merged.setdefault(round(st.x_mm, 6), []).append(name)
    for xs, names in merged.items():
        a1.axvline(xs, color="0.55", lw=0.7, ls=":")
        a1.text(xs, 0.98, "\n".join(names), transform=a1.get_xaxis_transform(), fontsize=6.5,
                rotation=90, ha="center", va="top", color="0.25",
                bbox=dict(facecolor="white", edgecolor="none", alpha=0.8, pad=0.5))
    lo, hi = a1.get_ylim()
    if clearance is not None and clearance[1]:
        # the deflection turns with the shaft, so the clearance counts on every side: drawn
        # once, on the side of the largest deflection (positive)
        cx, cc = clearance
        a1.plot([cx - 4.0, cx + 4.0], [cc * um] * 2, color="tab:red", lw=2)
        a1.annotate(f"clearance {cc:g} mm (any side)", (cx - 4.0, cc * um), xytext=(-4, 0),
                    textcoords="offset points", ha="right", va="center", fontsize=7,
                    color="tab:red")
        hi = max(hi, 1.08 * cc * um)
    a1.set_ylim(lo, hi + 0.43 * (hi - lo))           # the top 30 % for the station labels
    a1.set_ylabel(f"deflection in the load plane [µm]\n(n_y, n_z) = ({n[0]:.2f}, {n[1]:.2f})")
    a1.grid(alpha=0.3)
    if envelope is None:
        bins, env = stress_envelope(result.mesh.mesh, result.von_mises_ref * s)
        what = "the elements"
    else:
        bins, env = envelope[0], np.asarray(envelope[1]) * s
        what = "the surface"
    a2.step(0.5 * (bins[1:] + bins[:-1]), env, where="mid", color="tab:purple",
            label=f"{model}, max von Mises of {what} in each slice")
    a2.set_xlabel("x along the shaft [mm]")
    a2.set_ylabel("von Mises [MPa]")
    a2.grid(alpha=0.3)
    # one legend under both panels, outside the axes: it never covers a curve or a label
    handles = [h for a in (a1, a2) for h in a.get_legend_handles_labels()[0]]
    fig.legend(handles=handles, loc="lower center", ncol=2, fontsize=7, frameon=False,
               title=f"deflection: its component out of the load plane is ≤ {off:.2g} µm",
               title_fontsize=7)
    fig.suptitle(f"{result.variant} at {rpm:,.0f} rpm: deflection and stress along the shaft"
                 .replace(",", " "))
    fig.tight_layout(rect=(0.0, 0.1, 1.0, 1.0))
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    plt.close(fig)
    return write_atomic(path, buf.getvalue())


# --------------------------------------------------------------------------- mesh files

def triangle6_connectivity(m, facets):
    """(n, 6) triangle6 node ids of the given facets of a P2 skfem mesh: the three corners, then
    the mid-side nodes of edges 01, 12, 20 (VTK / meshio order)."""
    import numpy as np

    nv = m.p.shape[1]
    a, b, c = m.facets[:, facets].astype(np.int64)
    ekey = m.edges[0].astype(np.int64) * nv + m.edges[1]
    order = np.argsort(ekey)
    ks = ekey[order]
    edofs = m.dofs.edge_dofs[0]

    def mid(i, j):
        return edofs[order[np.searchsorted(ks, np.minimum(i, j) * nv + np.maximum(i, j))]]
    return np.vstack([a, b, c, mid(a, b), mid(b, c), mid(c, a)]).T


GROUP_NAMES_FIELD = "group_names_utf8"     # field data of mesh.vtu: the group names, UTF-8


def write_mesh(sm, path) -> Path:
    """Write the ``ShaftMesh`` ``sm`` as .vtu (VTK) or .msh (Gmsh 2.2): volume cells (group
    id 0) plus each face group's triangles with cell data ``group`` = 1-based index into
    ``sm.groups``."""
    import meshio
    import numpy as np
    path = check_suffix(path, "--out", MESH_SUFFIXES)
    m = sm.mesh
    if sm.order == 2:
        vol = ("tetra10", m.dofs.element_dofs.T.astype(np.int64))
        tri_cells = "triangle6"
    else:
        vol = ("tetra", m.t.T.astype(np.int64))
        tri_cells = "triangle"
    tris, ids = [], []
    for i, g in enumerate(sm.groups):
        if g not in m.boundaries:
            continue
        f = np.asarray(m.boundaries[g])
        if sm.order == 2:
            tris.append(triangle6_connectivity(m, f))
        else:
            tris.append(m.facets[:, f].T)
        ids.append(np.full(f.size, i + 1, dtype=np.int32))
    cells = [vol]
    data = [np.zeros(vol[1].shape[0], dtype=np.int32)]
    if tris:
        cells.append((tri_cells, np.concatenate(tris).astype(np.int64)))
        data.append(np.concatenate(ids))
    out = meshio.Mesh(m.doflocs.T if sm.order == 2 else m.p.T, cells,
                      cell_data={"group": data})
    with atomic_path(path) as tmp:
        if path.suffix.lower() == ".msh":
            out.cell_data = {"gmsh:physical": data, "gmsh:geometrical": data}
            meshio.write(tmp, out, file_format="gmsh22", binary=False)
        else:
            # VTK's own writer, for the group names as field data (meshio's writer drops field
            # data, and its reader refuses VTK string arrays): UTF-8 bytes, one name a line, so
            # `shaftfe view mesh.vtu` names the groups and meshio still reads the file
            import pyvista as pv
            grid = pv.from_meshio(out)
            grid.field_data[GROUP_NAMES_FIELD] = np.frombuffer(
                "\n".join(sm.groups).encode("utf-8"), dtype=np.uint8)
            grid.save(str(tmp))
    return path
