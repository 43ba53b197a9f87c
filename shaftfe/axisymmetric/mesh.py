"""The meridian-plane mesh: a closed (x, r) outline of named curves, meshed by Gmsh 2D into P2
triangles whose edges on arcs are curved (Gmsh places the mid-side nodes on the arc).

``shaft_geometry(plan)`` turns a solid plan into its outline with the SAME group names as the 3D
solid's faces (``end:left``, ``end:right``, ``fillet:<seg>``, ``shoulder:<seg>``,
``bearing:<name>``, ``load:<name>``; a pressed/free half of the 3D model is a θ-range of the
``load:`` line here), plus ``axis`` (r = 0) and ``surface`` (the plain cylinder). Keyway seats
and the hex socket are 3D cuts and are not in the outline (``shaftfe.solid.features.cuts``).

``mesh_geometry(geometry, level, refine=0)`` meshes it: sizes k_fillet × ρ on every fillet arc
(and at sharp concave corners, k_fillet × the smaller radius / 10), growing by ``grad`` per mm
to k_far × the smallest diameter; ``refine`` uniform refinements (every triangle into four,
boundary nodes put back on the curves), which is what a Richardson extrapolation needs. The
result is cached by the content hash of the outline, the level, ``refine`` and the Gmsh version
(``util.paths.cache_dir``).
"""

from __future__ import annotations

import dataclasses
import hashlib
import itertools
import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType

import numpy as np

from shaftfe.errors import InputError
from shaftfe.solid.features import (
    END_LEFT,
    END_RIGHT,
    chamfer_region,
    fillet_region,
    groove_region,
    shoulder_region,
    taper_region,
)
from shaftfe.solid.mesh import GMSH_LOCK, gmsh_version
from shaftfe.solid.plan import TOL, profile
from shaftfe.util import cachefile, paths

CACHE_FORMAT = 1


@dataclass(frozen=True)
class Curve:
    """One piece of the outline: a line, or an arc about ``center`` (the shorter one)."""
    start: tuple[float, float]
    end: tuple[float, float]
    groups: tuple[str, ...] = ()
    center: tuple[float, float] | None = None
    size: float | None = None           # element size on this curve (a hot spot), mm


@dataclass(frozen=True)
class MeridianGeometry:
    """A closed outline in the (x, r) half plane (r ≥ 0), curves end to start."""
    name: str
    curves: tuple[Curve, ...]
    d_ref: float                        # the length the far-field size refers to (mm)
    points: tuple[tuple[float, float, float], ...] = ()   # (x, r, size) extra hot points
    bands: tuple[tuple[float, float, float], ...] = ()    # (x0, x1, d): far size × d there


@dataclass(frozen=True)
class AxiLevel:
    name: str
    k_far: float        # far-field size × d_ref
    k_fillet: float     # size × ρ on a fillet arc (or × the curve's own size factor)
    grad: float         # size growth per mm of distance from a hot curve


# "default" is picked by measurement (reports/benchmarks/axisymmetric.md, "mesh parameters"):
# on the x2_57 fillets (the four variants share them) the peak's error against the converged
# value scatters by ±0.2 % with the mesh parameters, not monotonically; these met ≤ 0.05 % on
# both span fillets in ≈ 0.3 s, as well as a mesh 1.6× larger (0.10, 0.15, 0.25)
AXI_LEVELS = MappingProxyType({
    "coarse": AxiLevel("coarse", k_far=0.16, k_fillet=0.30, grad=0.35),
    "default": AxiLevel("default", k_far=0.20, k_fillet=0.12, grad=0.40),
    "fine": AxiLevel("fine", k_far=0.05, k_fillet=0.075, grad=0.15),
})


def axi_level(level: str | AxiLevel) -> AxiLevel:
    if isinstance(level, AxiLevel):
        return level
    if level not in AXI_LEVELS:
        raise InputError("--level", "level", " | ".join(AXI_LEVELS), got=level)
    return AXI_LEVELS[level]


@dataclass(frozen=True, eq=False)
class MeridianMesh:
    """Nodes ``xr`` (2, n): x and r; triangles ``tri`` (6, ne) (Gmsh order, det J > 0);
    boundary edges ``edges`` (3, m) (end, end, middle), the curve of each edge ``edge_curve``
    (m,), its outward normal side ``edge_sign`` (m,) (+1: the outward normal is (t_r, −t_x)
    for the tangent t from end 0 to end 1) and the groups: name -> curve indices."""
    xr: np.ndarray = field(repr=False)
    tri: np.ndarray = field(repr=False)
    edges: np.ndarray = field(repr=False)
    edge_curve: np.ndarray = field(repr=False)
    edge_sign: np.ndarray = field(repr=False)
    geometry: MeridianGeometry = field(repr=False)
    level: str = ""
    refine: int = 0
    key: str = ""
    from_cache: bool = False
    seconds: float = 0.0

    @property
    def n_nodes(self) -> int:
        return int(self.xr.shape[1])

    @property
    def n_elements(self) -> int:
        return int(self.tri.shape[1])

    def group_edges(self, name: str) -> np.ndarray:
        """Indices of the boundary edges of group ``name`` (empty if none)."""
        ids = [i for i, c in enumerate(self.geometry.curves) if name in c.groups]
        return np.nonzero(np.isin(self.edge_curve, ids))[0]

    def axis_nodes(self) -> np.ndarray:
        return np.nonzero(self.xr[1] <= 1e-9 * max(1.0, float(self.xr[1].max())))[0]


# ------------------------------------------------------------------------------- the shaft


def shaft_geometry(sol, bands=()) -> MeridianGeometry:
    """The outline of a solid plan ``sol`` (``solid.plan.prepare(variant)``): the profile the
    3D solid revolves (``solid.plan.profile``), with the 3D
    face-group names on its curves. Hot curves: every fillet and every groove's corner arcs
    (size factor ρ), every sharp concave shoulder corner (a hot point, size factor
    r_small / 10).

    ``bands``: (group, x0, x1) surface bands a remote load is delivered through (a
    ``[[loads]]`` entry that is not a part's seat): the straight outline is split at their ends
    and every outline piece off the axis and the end faces whose middle lies in [x0, x1] gets
    the group; no bands, the outline of the plan alone (the mesh key unchanged)."""
    prof = profile(sol)
    fil = {round(f.x_shoulder, 9): f for f in sol.fillets}
    undercut = {round(g.x_face, 9) for g in sol.grooves if g.undercut}
    shoulder_at = {round(s.x, 9): s for s in sol.shoulders}
    seats = [(s.name, s.x0, s.x1, s.part.r) for s in sol.seats]
    curves: list[Curve] = []
    prev = (sol.x_left, 0.0)
    points = []
    def groove_of(xm: float, rm: float):
        """The groove whose outline holds the piece with middle (xm, rm), or None."""
        return next((g for g in sol.grooves if g.x0 - TOL <= xm <= g.x1 + TOL
                     and rm < g.r_top - TOL), None)

    for kind, data in prof:
        end = (float(data[0]), float(data[1]))
        g = groove_of(0.5 * (prev[0] + end[0]), min(prev[1], end[1]))
        if g is not None:            # a groove's flank, corner arc or bottom (hot: its arcs)
            name = (groove_region(g.segment, g.index),)
            curves.append(Curve(prev, end, name, (float(data[2]), float(data[3])), g.rho)
                          if kind == "arc" else Curve(prev, end, name))
        elif kind == "arc":
            xc, rc = float(data[2]), float(data[3])
            f = next(f for f in sol.fillets if abs(abs(xc - f.x_shoulder) - f.rho) < 1e-6)
            curves.append(Curve(prev, end, (fillet_region(f.segment),), (xc, rc), f.rho))
        elif abs(end[1] - prev[1]) > TOL and abs(end[0] - prev[0]) > TOL:  # a chamfer, a cone
            xm = 0.5 * (prev[0] + end[0])
            t = next((t for t in sol.tapers if t.x0 - TOL <= xm <= t.x1 + TOL), None)
            c = None if t else next(c for c in sol.chamfers if c.x0 - TOL <= xm <= c.x1 + TOL)
            curves.append(Curve(prev, end, (taper_region(t.segment),) if t else
                                (chamfer_region(c.segment, c.side),)))
        elif abs(end[0] - prev[0]) <= TOL:           # vertical: an end face or a shoulder
            if abs(prev[0] - sol.x_left) <= TOL:
                g = (END_LEFT,)
            else:
                s = shoulder_at.get(round(prev[0], 9))
                g = (shoulder_region(s.segment),) if s else ("shoulder",)
                if round(prev[0], 9) not in fil and round(prev[0], 9) not in undercut:
                    # a sharp concave corner
                    rs = min(prev[1], end[1])
                    points.append((prev[0], rs, 0.1 * rs))
            curves.append(Curve(prev, end, g))
        else:
            xm, r = 0.5 * (prev[0] + end[0]), end[1]
            g = tuple(n for n, a, b, rs in seats if a - TOL <= xm <= b + TOL
                      and abs(rs - r) <= TOL) or ("surface",)
            curves.append(Curve(prev, end, g))
        prev = end
    curves.append(Curve(prev, (sol.x_right, 0.0), (END_RIGHT,)))
    curves = _with_bands(curves, bands, TOL)
    curves.append(Curve((sol.x_right, 0.0), (sol.x_left, 0.0), ("axis",)))
    # seat ends: the traction jumps there (a bearing band's RBE3 traction, a pressure patch)
    # are singular points whose pollution reaches a fillet next to them; size as the smallest
    # fillet (or r / 10 without fillets)
    rho = min((f.rho for f in sol.fillets), default=0.1 * sol.r_min)
    for st in sol.seats:
        points += [(st.x0, st.part.r, rho), (st.x1, st.part.r, rho)]
    for c in curves:               # a load band's ends are traction jumps as well
        if any(g.startswith(BAND_PREFIX) for g in c.groups):
            points += [(*c.start, rho), (*c.end, rho)]
    bands = tuple((a, b, 2 * max(r, sol.r_right(i))) for i, ((a, b), r)
                  in enumerate(zip(sol.segment_x, sol.radii, strict=True)))
    return MeridianGeometry(sol.name, tuple(curves), 2 * sol.r_max, tuple(points), bands)


BAND_PREFIX = "band:"


def _with_bands(curves: list[Curve], bands, tol: float) -> list[Curve]:
    """``curves`` with the straight pieces (r ≠ 0, not vertical) split at the band ends and the
    band groups added (``shaft_geometry``)."""
    if not bands:
        return curves
    cuts = sorted({x for _, a, b in bands for x in (a, b)})
    out: list[Curve] = []
    for c in curves:
        (xa, ra), (xb, rb) = c.start, c.end
        straight = c.center is None and abs(xb - xa) > tol and min(ra, rb) > 0
        pieces = [c]
        if straight:
            inner = [x for x in cuts if min(xa, xb) + tol < x < max(xa, xb) - tol]
            xs = [xa, *(inner if xb > xa else inner[::-1]), xb]
            pieces = [Curve((x0, ra + (rb - ra) * (x0 - xa) / (xb - xa)),
                            (x1, ra + (rb - ra) * (x1 - xa) / (xb - xa)), c.groups)
                      for x0, x1 in itertools.pairwise(xs)]
        for p in pieces:
            xm = 0.5 * (p.start[0] + p.end[0])
            vertical = p.center is None and abs(p.end[0] - p.start[0]) <= tol
            g = tuple(name for name, a, b in bands if a - tol <= xm <= b + tol and not vertical)
            out.append(dataclasses.replace(p, groups=p.groups + g) if g else p)
    return out


def cylinder_geometry(R: float, L: float) -> MeridianGeometry:
    """A plain round bar of radius R and length L (groups end:left, surface, end:right, axis):
    the verification geometry of the closed-form tests."""
    return MeridianGeometry("bar", (Curve((0, 0), (0, R), (END_LEFT,)),
                                    Curve((0, R), (L, R), ("surface",)),
                                    Curve((L, R), (L, 0), (END_RIGHT,)),
                                    Curve((L, 0), (0, 0), ("axis",))), 2 * R)


# ------------------------------------------------------------------------------- meshing


def mesh_key(geometry: MeridianGeometry, level: AxiLevel, refine: int, gmsh_version: str) -> str:
    payload = {"geometry": dataclasses.asdict(geometry), "level": dataclasses.asdict(level),
               "refine": refine, "gmsh": gmsh_version, "format": CACHE_FORMAT}
    payload["geometry"].pop("name")
    text = json.dumps(payload, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()


def mesh_geometry(geometry: MeridianGeometry, level: str | AxiLevel = "default",
                  refine: int = 0, *, cache_dir=None, use_cache: bool = True) -> MeridianMesh:
    """Mesh the outline (cached, see the module docstring)."""
    t0 = time.perf_counter()
    lv = axi_level(level)
    if not (isinstance(refine, int) and 0 <= refine <= 6):
        raise InputError("options", "refine", "0 ... 6", got=refine)
    key = mesh_key(geometry, lv, refine, gmsh_version())
    path = Path(paths.cache_dir(cache_dir)) / f"axi-{key[:24]}.npz"
    if use_cache and path.exists():
        got = cachefile.load(path, key, "meridian mesh")
        if got is not None:
            z, _ = got
            return _mesh(z, geometry, lv, refine, key, True, t0)
    with GMSH_LOCK:
        arrays = _generate(geometry, lv, refine)
    if use_cache:
        try:
            cachefile.save(path, arrays, {"key": key, "format": CACHE_FORMAT})
        except OSError:
            pass
    return _mesh(arrays, geometry, lv, refine, key, False, t0)


def _mesh(z, geometry, lv, refine, key, from_cache, t0) -> MeridianMesh:
    return MeridianMesh(np.asarray(z["xr"], dtype=float), np.asarray(z["tri"], dtype=np.int64),
                        np.asarray(z["edges"], dtype=np.int64),
                        np.asarray(z["edge_curve"], dtype=np.int64),
                        np.asarray(z["edge_sign"], dtype=float), geometry, lv.name, refine,
                        key, from_cache, time.perf_counter() - t0)


def _generate(geo: MeridianGeometry, lv: AxiLevel, refine: int) -> dict:
    import gmsh
    gmsh.initialize(["-noenv"], readConfigFiles=False, interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add("meridian")
        occ = gmsh.model.occ
        pts: dict[tuple, int] = {}

        def point(p):
            k = (round(p[0], 9), round(p[1], 9))
            if k not in pts:
                pts[k] = occ.addPoint(p[0], p[1], 0.0)
            return pts[k]

        tags = []
        for c in geo.curves:
            a, b = point(c.start), point(c.end)
            if c.center is None:
                tags.append(occ.addLine(a, b))
            else:
                tags.append(occ.addCircleArc(a, point(c.center), b))
        loop = occ.addCurveLoop(tags)
        occ.addPlaneSurface([loop])
        occ.synchronize()
        h_far = lv.k_far * geo.d_ref
        # one hot-spot field per size: the curves and points of one size share a Distance
        # field (its distance is the least of theirs, so the size it gives is the same float
        # as the least of one field each), and the background mesh evaluates a few fields
        # instead of one per point (x2_57: 3 instead of 28, generate 1.17 → 0.2 s)
        hot: dict[float, tuple[list, list]] = {}
        for c, t in zip(geo.curves, tags, strict=True):
            if c.size:
                hot.setdefault(lv.k_fillet * c.size, ([], []))[0].append(t)
        for x, r, sz in geo.points:
            hot.setdefault(lv.k_fillet * sz, ([], []))[1].append(point((x, r)))
        fields = [_hot(gmsh, cs, ps, size, lv.grad, h_far) for size, (cs, ps) in hot.items()]
        for x0, x1, d in geo.bands:             # the far-field size of each segment
            b = gmsh.model.mesh.field.add("Box")
            for k, val in (("VIn", lv.k_far * d), ("VOut", h_far), ("XMin", x0 - 1e-9),
                           ("XMax", x1 + 1e-9), ("YMin", -1.0), ("YMax", 1e6),
                           ("ZMin", -1.0), ("ZMax", 1.0)):
                gmsh.model.mesh.field.setNumber(b, k, val)
            fields.append(b)
        if fields:
            fmin = gmsh.model.mesh.field.add("Min")
            gmsh.model.mesh.field.setNumbers(fmin, "FieldsList", fields)
            gmsh.model.mesh.field.setAsBackgroundMesh(fmin)
        gmsh.option.setNumber("Mesh.MeshSizeMax", h_far)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.model.mesh.generate(2)
        for _ in range(refine):
            gmsh.model.mesh.refine()
        gmsh.model.mesh.setOrder(2)
        tag_n, xyz, _ = gmsh.model.mesh.getNodes()
        index = np.zeros(int(tag_n.max()) + 1, dtype=np.int64)
        index[tag_n.astype(np.int64)] = np.arange(tag_n.size)
        xr = xyz.reshape(-1, 3)[:, :2].T.copy()
        _, _, enodes = gmsh.model.mesh.getElements(2)
        tri = index[np.asarray(enodes[0], dtype=np.int64)].reshape(-1, 6).T.copy()
        edges, curve = [], []
        for i, t in enumerate(tags):
            _, _, en = gmsh.model.mesh.getElements(1, t)
            e = index[np.asarray(en[0], dtype=np.int64)].reshape(-1, 3).T
            edges.append(e)
            curve.append(np.full(e.shape[1], i))
        for i, c in enumerate(geo.curves):          # the named groups in the Gmsh model too
            for g in c.groups:
                gmsh.model.addPhysicalGroup(1, [tags[i]], name=g)
    finally:
        gmsh.finalize()
    edges = np.hstack(edges)
    used = np.unique(tri)                  # drop nodes of no triangle (the arcs' centres)
    new = -np.ones(xr.shape[1], dtype=np.int64)
    new[used] = np.arange(used.size)
    xr, tri, edges = xr[:, used], new[tri], new[edges]
    tri = _orient(xr, tri)
    return {"xr": xr, "tri": tri, "edges": edges, "edge_curve": np.concatenate(curve),
            "edge_sign": _edge_sign(xr, tri, edges)}


def _hot(gmsh, curves, points, size, grad, h_far) -> int:
    f = gmsh.model.mesh.field
    d = f.add("Distance")
    if curves:
        f.setNumbers(d, "CurvesList", curves)
        f.setNumber(d, "Sampling", 400)
    if points:
        f.setNumbers(d, "PointsList", points)
    m = f.add("MathEval")
    f.setString(m, "F", f"min({h_far!r}, {size!r} + {grad!r} * F{d})")
    return m


def _orient(xr: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """Corners counter-clockwise in (x, r): swap corners 1, 2 and mid-sides 01, 20 where not."""
    p = xr[:, tri[:3]]
    det = ((p[0, 1] - p[0, 0]) * (p[1, 2] - p[1, 0])
           - (p[0, 2] - p[0, 0]) * (p[1, 1] - p[1, 0]))
    bad = det < 0
    tri = tri.copy()
    tri[[1, 2]] = np.where(bad, tri[[2, 1]], tri[[1, 2]])
    tri[[3, 5]] = np.where(bad, tri[[5, 3]], tri[[3, 5]])
    return tri


def _edge_sign(xr, tri, edges) -> np.ndarray:
    """+1 where (t_r, −t_x) points out of the domain (away from the edge's triangle)."""
    pairs = np.sort(np.vstack([tri[[0, 1]].T, tri[[1, 2]].T, tri[[2, 0]].T]), axis=1)
    owner = np.tile(np.arange(tri.shape[1]), 3)
    lookup = {(int(a), int(b)): int(o) for (a, b), o in zip(pairs, owner, strict=True)}
    sign = np.empty(edges.shape[1])
    cen = xr[:, tri[:3]].mean(axis=1)
    for k in range(edges.shape[1]):
        a, b = sorted((int(edges[0, k]), int(edges[1, k])))
        o = lookup[(a, b)]
        t = xr[:, edges[1, k]] - xr[:, edges[0, k]]
        nrm = np.array([t[1], -t[0]])
        sign[k] = 1.0 if nrm @ (xr[:, edges[2, k]] - cen[:, o]) > 0 else -1.0
    return sign


def arc_length_angle(c: Curve, x: np.ndarray, r: np.ndarray) -> np.ndarray:
    """Angle (deg) of points on arc ``c`` from its start, along the arc."""
    xc, rc = c.center
    a0 = math.atan2(c.start[1] - rc, c.start[0] - xc)
    a = np.arctan2(r - rc, x - xc)
    return np.degrees(np.abs(np.remainder(a - a0 + np.pi, 2 * np.pi) - np.pi))
