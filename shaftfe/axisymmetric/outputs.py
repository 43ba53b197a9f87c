"""Files of an axisymmetric run: ``summary.json`` and ``result.vtu``, the meridian solution
revolved to 3D (the corner nodes of every triangle swept over ``SECTORS`` sectors into wedges;
displacement and the nodally averaged von Mises stress at the first speed; cell data
``region`` 0, the volume), each written
atomically into ``out`` (the command stages the whole directory)."""

from __future__ import annotations

from dataclasses import asdict

import numpy as np

from shaftfe.axisymmetric import recovery as rc
from shaftfe.io.vtu import write_point_fields
from shaftfe.static.outputs import write_summary
from shaftfe.util.units import von_mises

SECTORS = 36          # 10°: a viewing mesh (the peaks come from the 1° analysis); 72 doubles the
                      # zlib-compressed write (measured 0.48 → 0.96 s, 8.6 → 17 MB)


def revolved_fields(sol, scale: float, sectors: int = SECTORS):
    """Points (n·s, 3), wedge cells, displacement (n·s, 3) and von Mises (n·s,) of the
    meridian solution swept over ``sectors`` angles (× ``scale``)."""
    mesh = sol.mesh
    used = np.unique(mesh.tri[:3])
    idx = -np.ones(mesh.n_nodes, dtype=np.int64)
    idx[used] = np.arange(used.size)
    x, r = mesh.xr[:, used]
    th = np.linspace(0.0, 2 * np.pi, sectors, endpoint=False)
    c, s = np.cos(th), np.sin(th)
    pts = np.stack([np.repeat(x[None], sectors, 0), r[None] * c[:, None],
                    r[None] * s[:, None]], axis=-1).reshape(-1, 3)
    m = used.size
    tri = idx[mesh.tri[:3]].T                                   # (ne, 3)
    cells = []
    for k in range(sectors):
        k2 = (k + 1) % sectors
        cells.append(np.hstack([tri + k * m, tri + k2 * m]))
    cells = np.vstack(cells)
    # displacement and stress by harmonic synthesis at the sector angles
    E, nu = float(sol.variant.material.E_MPa), float(sol.variant.material.nu)
    parts = []
    for h in sol.harmonics:
        avg_s = rc.nodal_average(mesh, h.sym, h.n, E, nu)[:, used]
        avg_a = None if h.anti is None else rc.nodal_average(mesh, h.anti, h.n, E, nu)[:, used]
        parts.append((h.n, avg_s, avg_a))
    stress = rc.synthesize(parts, th, rc.CYL_SHEAR)                # (6, m, s)
    vm = von_mises(stress).T.reshape(-1) * scale
    d = rc.displacement(sol.harmonics, used, th)                   # (3, m, s)
    disp = d.transpose(2, 1, 0).reshape(-1, 3) * scale             # point = k · m + j
    return pts, cells, disp, vm


def write_revolved_vtu(sol, scale: float, path):
    """The meridian solution ``sol`` × ``scale`` revolved (``revolved_fields``) into ``path``:
    point data ``displacement_mm`` and ``von_mises_MPa``, cell data ``region`` 0."""
    pts, cells, disp, vm = revolved_fields(sol, scale)
    write_point_fields(pts, [("wedge", cells)], [np.zeros(cells.shape[0], dtype=np.int32)],
                       path, {"displacement_mm": disp, "von_mises_MPa": vm})
    return path


def revolved_surface(sol, scale: float, sectors: int = SECTORS):
    """Points (k·s, 3), quad cells, displacement (k·s, 3) and von Mises (k·s,) of the
    meridian solution's outline (every outline node off the axis, ``recovery.Surface``, each
    P2 edge as two segments) swept over ``sectors`` angles (× ``scale``): the surface-recovered
    stress the peaks come from, at a tenth of the points of ``revolved_fields``."""
    S = sol.surface
    keep = np.nonzero(~S.on_axis)[0]
    pos = -np.ones(S.nodes.size, dtype=np.int64)
    pos[keep] = np.arange(keep.size)
    k = keep.size
    th = np.linspace(0.0, 2 * np.pi, sectors, endpoint=False)
    x, r = sol.mesh.xr[:, S.nodes[keep]]
    pts = np.stack([np.repeat(x[None], sectors, 0), r[None] * np.cos(th)[:, None],
                    r[None] * np.sin(th)[:, None]], axis=-1).reshape(-1, 3)
    loc = S.inv.reshape(-1, 3)                       # the edges' (end, end, middle) entries
    segs = np.vstack([loc[:, [0, 2]], loc[:, [2, 1]]])
    segs = pos[segs]
    segs = segs[(segs >= 0).all(axis=1)]
    cells = np.vstack([np.column_stack([segs[:, 0] + j * k, segs[:, 1] + j * k,
                                        segs[:, 1] + ((j + 1) % sectors) * k,
                                        segs[:, 0] + ((j + 1) % sectors) * k])
                       for j in range(sectors)])
    parts = [(n, a[:, keep], None if b is None else b[:, keep]) for n, a, b in
             sol.surface_stress]
    vm = von_mises(rc.synthesize(parts, th, rc.LOCAL_SHEAR)).T.reshape(-1) * scale
    d = rc.displacement(sol.harmonics, S.nodes[keep], th)                 # (3, k, s)
    return pts, cells, d.transpose(2, 1, 0).reshape(-1, 3) * scale, vm


def write_surface_vtu(sol, scale: float, path):
    """The revolved outline (``revolved_surface``) into ``path``: point data
    ``displacement_mm`` and ``von_mises_MPa``, cell data ``region`` 0."""
    pts, cells, disp, vm = revolved_surface(sol, scale)
    write_point_fields(pts, [("quad", cells)], [np.zeros(cells.shape[0], dtype=np.int32)],
                       path, {"displacement_mm": disp, "von_mises_MPa": vm})
    return path


def write_outputs(variant_arg: str, variant, opts, res, rpms, out) -> dict:
    rpm_vtu = rpms[0]
    path = write_revolved_vtu(res.solution, res.case(rpm_vtu).scale, out / "result.vtu")
    return write_summary(out, variant_arg, variant, rpms,
                         {**asdict(opts), "level": opts.level_name}, {
                             "file": path.name, "rpm": rpm_vtu, "sectors": SECTORS,
                             "note": "the meridian solution revolved to 3D (P1 wedges on the P2 "
                             "corner nodes; nodally averaged von Mises); fields at vtu.rpm, "
                             "scale by (rpm / vtu.rpm)^2 for another speed"},
                         res.to_dict(), model="axisymmetric")
