"""Mode shapes of the 3D solid rotor as VTU point fields (docs/FIELDS.md "Mode shapes"), on
the rotor's own volume mesh. PyVista inside ``write_modes_vtu``.
"""

from __future__ import annotations

import numpy as np

from shaftfe.rotordynamics.campbell import CampbellResult
from shaftfe.rotordynamics.solid_rotor import SolidRotor


def mode_field_name(k: int, f_hz: float) -> str:
    """docs/FIELDS.md: ``mode_<k>_<freq>Hz`` (k from 1, two decimals)."""
    return f"mode_{k}_{f_hz:.2f}Hz"


def write_modes_vtu(rotor: SolidRotor, res: CampbellResult, path, speed_index: int = 0):
    """Mode shapes of ``res`` (kept vectors) at ``speed_index`` as VTU point fields
    ``mode_<k>_<f>Hz`` (docs/FIELDS.md: the real part after the phase rotation that makes the
    largest component real, normalised to a largest nodal displacement of 1); field data
    ``frequencies_hz`` and ``rpm``. Cells: the volume's tetra10 (P2) or tetra (P1). Written
    with PyVista/VTK (meshio's VTU writer drops field data)."""
    import pyvista as pv

    from shaftfe.fe import assembly as fem
    from shaftfe.util.atomic import atomic_path

    if res.vectors is None:
        raise ValueError("write_modes_vtu needs a result with keep_vectors=True")
    m = rotor.shaft_mesh.mesh
    conn = fem.element_nodes(m).T.astype(np.int64)
    ctype = pv.CellType.QUADRATIC_TETRA if fem.is_quadratic(m) else pv.CellType.TETRA
    cells = np.hstack([np.full((conn.shape[0], 1), conn.shape[1]), conn]).ravel()
    grid = pv.UnstructuredGrid(cells, np.full(conn.shape[0], ctype, dtype=np.uint8),
                               np.ascontiguousarray(m.doflocs.T))
    X = res.vectors[speed_index]
    for j in range(X.shape[1]):
        u = rotor.mesh_vector(X[:, j])
        k = int(np.argmax(np.abs(u)))
        u = (u * np.exp(-1j * np.angle(u[k]))).real.reshape(-1, 3)
        u = u / max(float(np.linalg.norm(u, axis=1).max()), 1e-300)
        grid.point_data[mode_field_name(j + 1, float(res.freq_hz[speed_index, j]))] = u
    grid.field_data["frequencies_hz"] = np.asarray(res.freq_hz[speed_index], dtype=float)
    grid.field_data["rpm"] = np.array([float(res.rpm[speed_index])])
    from pathlib import Path
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_path(path) as tmp:
        grid.save(str(tmp))
    return path
