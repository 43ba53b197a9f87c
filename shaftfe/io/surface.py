"""Geometry for rendering a result: the boundary faces of the volume cells, their curved
subdivided surface and the element edges drawn on it.

The volume cells (tetra / tetra10) are reduced to their boundary faces (quadratic triangles for
tetra10) and those faces are subdivided (VTK nonlinear subdivision) so that curved fillets and
seats look curved. Cell fields that live on the face cells of the file (``region`` / ``group``:
0 on the volume, k ≥ 1 on the triangles of face group k) are mapped onto the boundary faces by
their corner nodes, so a mesh file shows its named face groups. The shown scalar travels as the
``_view`` array. PyVista / VTK are imported inside the functions.
"""

from __future__ import annotations

from shaftfe.io.view import FieldChoice

# VTK cell types with a 3D volume (linear, quadratic, Lagrange, Bezier solids).
_VOLUME_TYPES = frozenset({10, 11, 12, 13, 14, 24, 25, 26, 27, 29, 31, 32, 33, 71, 72, 73,
                           74, 78, 79, 80, 81})
# Corner-node triples of the four faces of a VTK tetra (outward normals) and the mid-side
# nodes of tetra10 on the edges (a, b), (b, c), (c, a) of each face.
_TET_FACES = ((0, 1, 3), (1, 2, 3), (2, 0, 3), (0, 2, 1))
_TET10_EDGE = {(0, 1): 4, (1, 2): 5, (0, 2): 6, (0, 3): 7, (1, 3): 8, (2, 3): 9}


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
