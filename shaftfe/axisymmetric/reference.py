"""The axisymmetric solution as the fatigue stage's input: a
``shaftfe.static.cache.StaticReference`` on the revolved free surface.

Points: every outline node off the axis (``recovery.Surface``) at θ = 0°, 1°, …, 359° (the
peaks' grid, ``recovery.theta_grid``: a peak between two samples is missed by at most
1 − cos(0.5° · n) of a harmonic-n variation, 4e-5 for the n = 1 bending that carries the fillets).
Stresses: the surface recovery of ``recovery.Surface`` synthesised over θ and rotated from the
surface frame (t, θ, n) to Cartesian xx yy zz xy yz xz, at the solution's reference speed. Regions
and the singular-point rule are those of the axisymmetric peaks (``solve.regions``,
``solve.excluded_nodes`` and, on a loaded seat, the ± ``SEAT_EDGE_BAND_DEG`` band around the
pressure's θ-edges), so ``shaftfe fatigue --model axisymmetric`` finds its hot spot where
``shaftfe static --model axisymmetric`` reports its peaks. Cells: the revolved outline as
linear triangles (each P2 outline edge split at its mid node, two per sector), grouped by region
for the VTU; the volume is not stored (fatigue starts at the surface), and the points on the
axis (the centres of the end faces) are left out, so the end faces show a pinhole.
"""

from __future__ import annotations

import time
from functools import cached_property

import numpy as np

from shaftfe.axisymmetric import recovery as rc
from shaftfe.axisymmetric.model import superpose
from shaftfe.axisymmetric.pointeval import StressField
from shaftfe.axisymmetric.solve import (
    excluded_nodes,
    loaded_seat_angles,
    regions,
    seat_edge_band,
    surface_sigma,
)
from shaftfe.fe.recovery import von_mises
from shaftfe.io.vtu import span_envelope, write_point_fields
from shaftfe.model.loads import factored_loads, pattern_label, solve_pattern
from shaftfe.static.cache import StaticReference


def local_to_cartesian(s: np.ndarray, tangent: np.ndarray, sign: np.ndarray,
                       theta: np.ndarray) -> np.ndarray:
    """(6, k, q) surface-local stresses (tt, θθ, nn, tθ, θn, nt) at nodes with meridian tangent
    (2, k) = (t_x, t_r) and outward normal sign (k,) → Cartesian (6, k, q) in the order xx yy zz
    xy yz xz. Basis at angle θ: t = (t_x, t_r cos θ, t_r sin θ), e_θ = (0, −sin θ, cos θ),
    n = (n_x, n_r cos θ, n_r sin θ) with (n_x, n_r) = sign · (t_r, −t_x) (``recovery.
    cyl_to_local``); σ_ij = Σ_ab σ_ab a_i b_j."""
    tx, tr = tangent[0][:, None], tangent[1][:, None]
    nx, nr = sign[:, None] * tr, -sign[:, None] * tx
    c, sn = np.cos(theta)[None], np.sin(theta)[None]
    one = np.ones_like(tx * c)
    B = np.stack([np.stack([tx * one, tr * c, tr * sn], -1),          # t
                  np.stack([0 * one, -sn * one, c * one], -1),         # e_θ
                  np.stack([nx * one, nr * c, nr * sn], -1)], -2)      # n   (k, q, 3, 3)
    tt, qq, nn, tq, qn, nt = s
    L = np.stack([np.stack([tt, tq, nt], -1), np.stack([tq, qq, qn], -1),
                  np.stack([nt, qn, nn], -1)], -2)                     # (k, q, 3, 3)
    C = np.swapaxes(B, -1, -2) @ L @ B        # Bᵀ L B (three times the 3-operand einsum's speed)
    return np.stack([C[..., 0, 0], C[..., 1, 1], C[..., 2, 2], C[..., 0, 1], C[..., 1, 2],
                     C[..., 0, 2]])


def _triangles(S, keep: np.ndarray, q: int) -> tuple[np.ndarray, np.ndarray]:
    """Linear triangles of the revolved outline over the points (k kept nodes × q angles,
    point = j · q + i) and the outline curve of each."""
    pos = -np.ones(S.nodes.size, dtype=np.int64)
    pos[keep] = np.arange(keep.size)
    loc = np.searchsorted(S.nodes, S.e)                     # (3, m): ends 0, 1 and mid 2
    segs = np.concatenate([loc[[0, 2]], loc[[2, 1]]], axis=1)
    curve = np.tile(S.mesh.edge_curve[S.edge_ids], 2)
    a, b = pos[segs[0]], pos[segs[1]]
    ok = (a >= 0) & (b >= 0)
    a, b, curve = a[ok], b[ok], curve[ok]
    i = np.arange(q)
    i2 = (i + 1) % q
    A0, A1 = a[:, None] * q + i, a[:, None] * q + i2
    B0, B1 = b[:, None] * q + i, b[:, None] * q + i2
    tri = np.concatenate([np.stack([A0, B0, B1], -1).reshape(-1, 3),
                          np.stack([A0, B1, A1], -1).reshape(-1, 3)])
    cur = np.concatenate([np.repeat(curve, q), np.repeat(curve, q)])
    return tri, cur


def pattern_groups(variant, components) -> tuple[tuple[tuple, np.ndarray, dict], ...]:
    """(key, factors, info) of each load pattern of a static solve (``model.loads.
    solve_pattern``: the full 3D model's ``static.model.LoadPattern`` keys) made of the
    axisymmetric solve's components (``model.Component``, one column each): ``factors`` picks
    the pattern's components at their written magnitudes (``model.superpose``); ``info`` is the
    pattern as fatigue's per-pattern fields name it (``StaticReference.patterns``)."""
    factored = factored_loads(variant)
    keys: dict[tuple, list] = {}
    for j, c in enumerate(components):
        keys.setdefault(solve_pattern(c.pattern, c.factor_name, factored), []).append(j)
    out = []
    for key, js in keys.items():
        c = components[js[0]]
        f = np.zeros(len(components))
        f[js] = 1.0
        out.append((key, f, {"key": pattern_label(key), "scales_with": c.scales_with,
                             "ref_rpm": c.ref_rpm, "channel_ref": c.channel_ref,
                             "factor_name": c.factor_name if c.factor_name in factored
                             else ""}))
    return tuple(out)


def cartesian_surface_stress(sol, keep: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """(6, k q) Cartesian surface stress of ``sol`` at outline nodes ``keep`` × angles
    ``theta`` (point = j · q + i)."""
    S = sol.surface
    return local_to_cartesian(surface_sigma(sol, keep, theta), S.tangent[:, keep],
                              S.sign[keep], theta).reshape(6, -1)


def pattern_views(res) -> tuple[tuple, tuple]:
    """(patterns, views) of an ``AxiResult``: every load pattern's info (``pattern_groups``),
    and, where a pattern's law is not rpm² (fatigue's per-pattern path, ``fatigue.
    channel_run``) and the solve is unsoftened, (key, info, the solution of that pattern alone
    at its written magnitudes) for each (``model.superpose``); else no views. A softened
    solve's columns are softened, so fatigue takes these from its unsoftened solve
    (``fatigue.run.surface_reference``), as the full 3D model's reference holds unsoftened
    per-pattern stresses."""
    sol = res.solution
    cols = getattr(sol, "columns", None)
    if cols is None:
        return (), ()
    # the solved variant itself (``res.variant`` is its name): its load cases split patterns
    groups = pattern_groups(sol.variant, cols.components)
    infos = tuple(g[2] for g in groups)
    if res.options.spin_softening or all(i["scales_with"] == "rpm2" for i in infos):
        return infos, ()
    return infos, tuple((key, info, superpose(sol, f)) for key, f, info in groups)


def static_reference(res, seconds: float | None = None, views=None):
    """The ``StaticReference`` (see the module docstring) of an ``AxiResult`` at its
    reference speed, with the per-pattern fields of ``pattern_views`` (``views``: its result,
    when the caller has it already)."""
    t0 = time.perf_counter()
    sol = res.solution
    mesh, S = sol.mesh, sol.surface
    keep = np.nonzero(~S.on_axis)[0]
    theta = rc.theta_grid()
    q = theta.size
    stress = cartesian_surface_stress(sol, keep, theta)
    patterns, views = pattern_views(res) if views is None else views
    pattern_stress = {info["key"]: cartesian_surface_stress(view, keep, theta)
                      for _, info, view in views}
    x, r = mesh.xr[:, S.nodes[keep]]
    xyz = np.stack([np.repeat(x, q), (r[:, None] * np.cos(theta)).ravel(),
                    (r[:, None] * np.sin(theta)).ravel()])
    node_excl = excluded_nodes(sol, sol.options.exclude_mm)[keep]
    excl = np.repeat(node_excl, q)
    seat_angles = loaded_seat_angles(sol)
    reg = {}
    curve_region = {}
    for name, ids in sorted(regions(mesh).items()):
        on = np.nonzero(np.isin(S.curve[keep], ids))[0]
        if on.size == 0:
            continue
        pts = (on[:, None] * q + np.arange(q)).ravel()
        reg[name] = pts
        if name in seat_angles:
            band = seat_edge_band(theta, seat_angles[name])
            excl[(on[:, None] * q + np.nonzero(band)[0]).ravel()] = True
        for c in ids:
            curve_region.setdefault(c, name)
    tri, cur = _triangles(S, keep, q)
    names = tuple(reg)
    lookup = -np.ones(len(mesh.geometry.curves), dtype=np.int64)
    for c, name in curve_region.items():
        lookup[c] = names.index(name)
    gid = lookup[cur]
    ok = gid >= 0
    vm = von_mises(stress)
    o = res.options
    return StaticReference(
        variant=res.variant, variant_hash=res.variant_hash,
        options={"model": "axisymmetric", "level": o.level_name, "refine": o.refine,
                 "seed_load_case": o.seed_load_case, "exclude_mm": o.exclude_mm,
                 "spin_softening": o.spin_softening, "harmonics": list(res.harmonics)},
        ref_rpm=float(res.ref_rpm), mesh_key="", key="", stress_ref=stress,
        von_mises_ref=vm, xyz=xyz, excluded=np.flatnonzero(excl), regions=reg,
        cells=np.zeros((0, 4), dtype=np.int64), face_cells=tri[ok],
        face_group=gid[ok], face_groups=names, n_elements=int(res.n_elements),
        solve_seconds=float(res.run.get("total_seconds", 0.0)), from_cache=False,
        seconds=float(seconds if seconds is not None else 0.0)
        + time.perf_counter() - t0,
        notes=(*res.notes, f"axisymmetric model: fatigue on the revolved surface "
               f"({keep.size} outline nodes × {q} angles), surface-recovered stresses"),
        relative_residual=res.run.get("relative_residual"),
        depth_probe=SurfaceProbe(sol, keep, theta), patterns=patterns,
        pattern_stress=pattern_stress)


class SurfaceProbe:
    """FKM's stress profile below a point of the revolved surface (``fatigue.fkm_field.
    DepthProbe``), from the harmonic field itself: the inward normal is the outline's at the
    point's node (the surface recovery's tangent and side, ``recovery.Surface``) turned to the
    point's angle; the stress at interior points is the harmonics' nodal stresses interpolated
    in the meridian P2 mesh and synthesised at θ (``pointeval.StressField``), the same kind of
    field the 3D profile interpolates. h is the mean length of the outline edges at the node
    (their end-to-end chord), the element size the profile fits over. Point p is outline node
    ``keep[p // q]`` at angle ``theta[p % q]`` (``static_reference``)."""

    def __init__(self, sol, keep: np.ndarray, theta: np.ndarray):
        S = sol.surface
        self.sol = sol
        self.theta = np.asarray(theta, dtype=float)
        tx, tr = S.tangent[0][keep], S.tangent[1][keep]
        self.n_xr = np.stack([S.sign[keep] * tr, -S.sign[keep] * tx])     # outward (x, r)
        X, R = sol.mesh.xr[0][S.e], sol.mesh.xr[1][S.e]                  # (3, m) ends, mid
        chord = np.hypot(X[1] - X[0], R[1] - R[0])
        total = np.zeros(S.nodes.size)
        np.add.at(total, S.inv, np.repeat(chord, 3))
        self.h = (total / S.count)[keep]

    @cached_property
    def field(self):
        """The harmonics' nodal stresses and the element tree, made when FKM first asks (the
        seed method never does)."""
        return StressField.of(self.sol)

    def arrays(self) -> dict[str, np.ndarray]:
        """Everything ``from_arrays`` needs (the surface-reference cache, ``fatigue.
        surface_cache``): the outline's normals and sizes, the meridian mesh, the amplitudes."""
        f = self.field
        out = {"theta": self.theta, "n_xr": self.n_xr, "h": self.h, "xr": f.mesh.xr,
               "tri": f.mesh.tri, "harmonics": np.array([n for n, _, _ in f.amplitudes])}
        for k, (_, sym, anti) in enumerate(f.amplitudes):
            out[f"sym{k}"] = sym
            if anti is not None:
                out[f"anti{k}"] = anti
        return out

    @classmethod
    def from_arrays(cls, a: dict) -> SurfaceProbe:
        from types import SimpleNamespace

        self = cls.__new__(cls)
        self.sol = None
        self.theta, self.n_xr, self.h = a["theta"], a["n_xr"], a["h"]
        mesh = SimpleNamespace(xr=a["xr"], tri=a["tri"], n_elements=int(a["tri"].shape[1]))
        self.field = StressField(mesh, [(int(n), a[f"sym{k}"], a.get(f"anti{k}"))
                                        for k, n in enumerate(a["harmonics"])])
        return self

    def normal(self, node: int) -> tuple[np.ndarray, float]:
        j, i = divmod(int(node), self.theta.size)
        nx, nr = self.n_xr[:, j]
        th = self.theta[i]
        return -np.array([nx, nr * np.cos(th), nr * np.sin(th)]), float(self.h[j])

    def stress_at(self, node: int, pts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        s, ok = self.field.at(pts)
        return s.T, ok


def surface_displacement(res, ref) -> np.ndarray:
    """(n, 3) Cartesian displacement in mm at the points of ``ref`` (= ``static_reference(res)``)
    at the reference speed (``recovery.displacement``)."""
    S = res.solution.surface
    keep = np.nonzero(~S.on_axis)[0]
    q = ref.n_nodes // keep.size
    theta = np.radians(np.arange(q) * (360.0 / q))
    d = rc.displacement(res.solution.harmonics, S.nodes[keep], theta)     # (3, k, q)
    return d.transpose(1, 2, 0).reshape(-1, 3)                          # point = j · q + i


def surface_envelope(ref, n_slices: int = 120) -> tuple[np.ndarray, np.ndarray]:
    """The von Mises envelope along x of the revolved surface at the reference speed: the
    largest value of the triangles spanning each slice (``io.vtu.span_envelope``)."""
    x = ref.xyz[0][ref.face_cells]
    v = ref.von_mises_ref[ref.face_cells].max(axis=1)
    return span_envelope(x.min(axis=1), x.max(axis=1), v,
                         (float(ref.xyz[0].min()), float(ref.xyz[0].max())), n_slices)


def write_surface_vtu(ref, path, point_data: dict):
    """The revolved surface of ``ref`` (triangles, cell data ``region`` = index + 1 into
    ``ref.face_groups``) with the given point fields (``io.vtu.write_point_fields``)."""
    return write_point_fields(ref.xyz.T, [("triangle", ref.face_cells)],
                              [np.asarray(ref.face_group, dtype=np.int32) + 1], path,
                              point_data)
