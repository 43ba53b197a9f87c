"""Disk cache of the static reference solution that the fatigue study post-processes.

The fatigue evaluation needs only the nodal stresses at the static reference speed, the node
coordinates, the named face regions, the singular-point exclusion and (for ``fatigue.vtu``) the
cells. ``static.solve.load_or_solve(variant, options, cache_dir)`` returns them as a
``StaticReference``, from ``<dir>/static-<key[:24]>.npz`` when the model is unchanged,
otherwise by one ``shaftfe.static.solve.solve_static`` at its ``REF_RPM`` (the file is then
written).

Key (sha256 of a canonical JSON): ``STATIC_CACHE_FORMAT``; the variant's content hash
(``Variant.content_hash``: geometry, bearings, attachments, materials); the static options
(``StaticOptions`` without ``solver``: every solver meets the same residual limit, 1e-8, so the
choice does not change the stresses beyond that); the mesh key of ``shaftfe.solid.mesh`` (geometry
plan, level, order, Gmsh version and options, mesh ``CACHE_FORMAT``); the static reference
speed; and a fingerprint (sha256) of the source of the modules that compute the stresses
(``FINGERPRINT_MODULES``: static model, solve and result, fe assembly, facet integrals,
supports, recovery, surface recovery, the low-rank solve and the regions' naming scheme
``solid.features``), so a change of the solver code is never served a stale result. Bump
``STATIC_CACHE_FORMAT`` when the stored arrays change meaning.

Stored arrays: ``stress_ref`` (6, n) MPa in the order xx yy zz xy yz xz, ``von_mises_ref`` (n,),
``xyz`` (3, n) mm, ``excluded`` (node ids of the singular-point rule of
``recovery.excluded_nodes`` on the bearing and pressed-load patches with the options'
``exclude_mm`` band, the same rule as ``shaftfe static``), one node-id array per stress region
(the static command's regions: each face group, the two halves of a load seat merged into
``seat:<part>``, bearing seats as ``seat:bearing:<side>``), the volume cells and the face-group
triangles for the VTU.

The metadata also keep the static solve's relative residual (``StaticReference.
relative_residual``, None for files written before it), which ``shaftfe fatigue`` summaries
report.

Directory: ``cache_dir``, else ``$SHAFTFE_CACHE_DIR``, else ``~/.cache/shaftfe`` (as the mesh
cache). Writes are atomic (a temporary file renamed into place); an unreadable, truncated or
foreign file is recomputed and overwritten, never a crash; a read-only cache directory only
costs the write.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from shaftfe.beam.planes import mesh_hot_axes
from shaftfe.fe import assembly as fem
from shaftfe.fe import recovery
from shaftfe.model.variant import content_hash
from shaftfe.solid import mesh as mesh_mod
from shaftfe.solid.features import is_patch
from shaftfe.static.model import region_nodes
from shaftfe.util import cachefile, paths
from shaftfe.util.cachefile import code_fingerprint
from shaftfe.util.units import REF_RPM

STATIC_CACHE_FORMAT = 3          # 2: spin softening's unsoftened stress (stress_linear)
#                                  3: the per-pattern stresses (pattern_stress, patterns)
FINGERPRINT_MODULES = ("shaftfe.static.model", "shaftfe.static.solve", "shaftfe.static.result",
                       "shaftfe.fe.recovery", "shaftfe.fe.assembly", "shaftfe.fe.lowrank",
                       "shaftfe.fe.supports", "shaftfe.fe.facets", "shaftfe.fe.surface",
                       "shaftfe.solid.features")     # the regions' names and kinds
_KEY_SKIP_OPTIONS = ("solver",)


@dataclass(frozen=True, eq=False)
class StaticReference:
    """The static solution at ``ref_rpm`` reduced to what fatigue needs (arrays read-only)."""

    variant: str
    variant_hash: str
    options: dict
    ref_rpm: float
    mesh_key: str
    key: str
    stress_ref: np.ndarray = field(repr=False)       # (6, n) MPa, xx yy zz xy yz xz
    von_mises_ref: np.ndarray = field(repr=False)    # (n,) MPa
    xyz: np.ndarray = field(repr=False)              # (3, n) mm
    excluded: np.ndarray = field(repr=False)         # node ids (singular-point rule)
    regions: dict = field(repr=False)                # region name -> node ids
    cells: np.ndarray = field(repr=False)            # (ne, 10 | 4) volume connectivity
    face_cells: np.ndarray = field(repr=False)       # (nf, 6 | 3) triangles of the groups
    face_group: np.ndarray = field(repr=False)       # (nf,) index into ``face_groups``
    face_groups: tuple[str, ...]
    n_elements: int
    solve_seconds: float                             # wall time of the original solve
    from_cache: bool
    seconds: float                                   # wall time of this call
    notes: tuple[str, ...] = ()
    relative_residual: float | None = None           # of the static solve (≤ 1e-8 checked)
    # with spin softening: the unsoftened stress at ref_rpm (6, n); ``stress_ref`` is the
    # softened one, and fatigue models each node as S(λ) = S0 (λ + β λ²) from the two
    stress_linear: np.ndarray | None = field(default=None, repr=False)
    # the load patterns (``StaticResult.patterns``: label, law, references, loads) and, per
    # label, the unsoftened stress (6, n) at the pattern's written magnitudes: a case or a
    # history is Σ_k factor_k(t) × pattern_stress[k] (empty when the solve did not recover them)
    patterns: tuple = ()
    pattern_stress: dict = field(default_factory=dict, repr=False)
    # where FKM's stress profile below a surface point comes from (``fatigue.fkm_field.
    # DepthProbe``) when the reference has no volume cells (the axisymmetric and zoned surface
    # references); None: the 3D field's own cells. Not stored in the cache.
    depth_probe: object = field(default=None, repr=False, compare=False)

    def __post_init__(self) -> None:
        for name in ("stress_ref", "von_mises_ref", "xyz", "excluded", "cells", "face_cells",
                     "face_group", "stress_linear"):
            if getattr(self, name) is None:
                continue
            object.__setattr__(self, name, _readonly(getattr(self, name)))
        from types import MappingProxyType
        object.__setattr__(self, "pattern_stress", MappingProxyType(
            {k: _readonly(v) for k, v in dict(self.pattern_stress).items()}))

    @property
    def n_nodes(self) -> int:
        return int(self.xyz.shape[1])


def _readonly(a) -> np.ndarray:
    a = np.asarray(a)
    if a.flags.writeable:
        a = a.copy()
        a.flags.writeable = False
    return a


# --------------------------------------------------------------------------- key

def predicted_mesh_key(variant, options) -> str:
    """The key ``shaftfe.solid.mesh.build_mesh`` gives the mesh the static solve will use (the seed
    load case meshes the variant reduced to the seed's parts, as ``static.build_model``)."""
    v = variant.with_seed_load_case() if options.seed_load_case else variant
    plan = mesh_mod.mesh_plan(v, options.level, mesh_hot_axes(v))
    return mesh_mod.mesh_key(plan, options.level, options.order, mesh_mod.gmsh_version())


def static_key(variant, options, mesh_key: str, ref_rpm: float, *,
               modules: tuple[str, ...] = FINGERPRINT_MODULES, extra: dict | None = None) -> str:
    """The key of a cache entry: the variant's content, the options, the mesh, the reference
    speed and the code of ``modules``; ``extra`` adds what tells another kind of entry apart
    (``fatigue.surface_cache``: its model and format)."""
    opts = {k: v for k, v in dataclasses.asdict(options).items() if k not in _KEY_SKIP_OPTIONS}
    payload = {"format": STATIC_CACHE_FORMAT, "variant_hash": variant_hash(variant),
               "options": opts, "mesh_key": mesh_key, "ref_rpm": float(ref_rpm),
               "code": code_fingerprint(modules), **(extra or {})}
    text = json.dumps(payload, sort_keys=True, separators=(",", ":"), default=repr)
    return hashlib.sha256(text.encode()).hexdigest()


def variant_hash(variant) -> str:
    """The variant's content hash, always computed from its content: a variant changed in code
    (``dataclasses.replace(v, loads=...)``) keeps the loaded file's ``content_hash`` field, and
    trusting that field would return the unchanged variant's cached solution."""
    return content_hash(variant)


def cache_path(key: str, cache_dir=None, kind: str = "static") -> Path:
    return paths.cache_dir(cache_dir) / f"{kind}-{key[:24]}.npz"


def singular_patches(mesh) -> list[np.ndarray]:
    """The patches whose edges are singular by construction: bearing seats (RBE3 coupling) and
    the pressed half of every load seat (pressure edge) — the static command's choice."""
    return [np.asarray(f) for g, f in mesh.boundaries.items()
            if is_patch(g)]


def facet_cells(mesh) -> tuple[np.ndarray, np.ndarray, tuple[str, ...]]:
    """Triangles (triangle6 for P2: corners, then the mid-side nodes of edges 01, 12, 20) of
    every named face group, the group index of each, and the group names (sorted)."""
    names = tuple(sorted(mesh.boundaries))
    if not names:
        return np.zeros((0, 6 if fem.is_quadratic(mesh) else 3), np.int64), \
            np.zeros(0, np.int32), names
    facets = np.concatenate([np.asarray(mesh.boundaries[g]) for g in names])
    gid = np.concatenate([np.full(np.asarray(mesh.boundaries[g]).size, i, np.int32)
                          for i, g in enumerate(names)])
    a, b, c = mesh.facets[:, facets].astype(np.int64)
    if not fem.is_quadratic(mesh):
        return np.stack([a, b, c], 1), gid, names
    nv = int(mesh.p.shape[1])
    ekey = np.minimum(mesh.edges[0], mesh.edges[1]).astype(np.int64) * nv \
        + np.maximum(mesh.edges[0], mesh.edges[1])
    order = np.argsort(ekey)
    ks = ekey[order]
    edofs = np.asarray(mesh.dofs.edge_dofs[0])

    def mid(i, j):
        k = np.minimum(i, j) * nv + np.maximum(i, j)
        pos = order[np.searchsorted(ks, k)]
        return edofs[pos].astype(np.int64)
    return np.stack([a, b, c, mid(a, b), mid(b, c), mid(c, a)], 1), gid, names


# --------------------------------------------------------------------------- load / solve

def kept_nodes(ref) -> np.ndarray:
    """The mask of the reference's nodes outside the singular-point exclusion (``excluded``)."""
    keep = np.ones(np.asarray(ref.von_mises_ref).size, dtype=bool)
    keep[np.asarray(ref.excluded, dtype=np.int64)] = False
    return keep


def region_peaks(ref: StaticReference) -> dict[str, float]:
    """Each region's largest nodal von Mises of the reference, the singular-point rule applied
    (``kept_nodes``)."""
    keep = kept_nodes(ref)
    out = {}
    for name, ids in ref.regions.items():
        ids = np.asarray(ids, dtype=np.int64)
        ids = ids[keep[ids]]
        if ids.size:
            out[name] = float(ref.von_mises_ref[ids].max())
    return out


def store(variant, options, res, cache_dir=None) -> StaticReference:
    """Put a ``StaticResult`` solved elsewhere (``shaftfe static``) into the cache, so that a
    later ``shaftfe fatigue`` on the same model reuses it instead of solving again."""
    mkey = predicted_mesh_key(variant, options)
    key = static_key(variant, options, mkey, REF_RPM)
    ref = from_result(res, key)
    notes: list[str] = []
    # a softened result serves fatigue only with its unsoftened stress at REF_RPM as well
    softened = any(c.spin_softening_N for c in res.cases)
    if res.mesh_key != mkey:        # the prediction missed: do not store under a wrong key
        notes.append("static cache: the mesh key could not be predicted; result not cached")
    elif getattr(res, "case_name", "") or not math.isclose(float(res.ref_rpm), REF_RPM):
        # the cache holds the plain case at REF_RPM (what load_or_solve solves), nothing else
        notes.append(f"static cache: a result at {float(res.ref_rpm):g} rpm"
                     + (f" of case {res.case_name!r}" if getattr(res, "case_name", "") else "")
                     + f", not the plain case at {REF_RPM:g} rpm; not cached")
    elif softened and (res.stress_linear_ref is None
                       or not math.isclose(float(res.ref_rpm), REF_RPM)):
        notes.append("static cache: a softened result without its unsoftened stress at "
                     f"{REF_RPM:g} rpm; not cached")
    else:
        try:
            _save(cache_path(key, cache_dir), ref)
        except OSError as exc:
            notes.append(f"static cache: not written ({exc.__class__.__name__})")
    return dataclasses.replace(ref, notes=tuple(notes))


def from_result(res, key: str = "", seconds: float = 0.0) -> StaticReference:
    """A ``StaticReference`` from a ``shaftfe.static.result.StaticResult`` (not cached)."""
    m = res.mesh.mesh
    band = float(getattr(res.options, "exclude_mm", 0.0))
    excl = (recovery.excluded_nodes(m, singular_patches(m), band) if band > 0
            else recovery.excluded_nodes(m, singular_patches(m))).astype(np.int64)
    fc, gid, names = facet_cells(m)
    return StaticReference(
        variant=res.variant, variant_hash=res.variant_hash,
        options=dataclasses.asdict(res.options), ref_rpm=float(res.ref_rpm),
        mesh_key=res.mesh_key, key=key, stress_ref=np.asarray(res.stress_ref, dtype=float),
        von_mises_ref=np.asarray(res.von_mises_ref, dtype=float),
        xyz=np.asarray(m.doflocs, dtype=float), excluded=excl, regions=region_nodes(m),
        cells=fem.element_nodes(m).T.astype(np.int64), face_cells=fc, face_group=gid,
        face_groups=names, n_elements=int(res.n_elements),
        solve_seconds=float(getattr(res, "run", {}).get("total_seconds", seconds)),
        from_cache=False, seconds=seconds, relative_residual=_float_or_none(
            res.diagnostics.get("relative_residual")),
        stress_linear=(None if getattr(res, "stress_linear_ref", None) is None
                       else np.asarray(res.stress_linear_ref, dtype=float)),
        patterns=tuple(getattr(res, "patterns", ())),
        pattern_stress=_pattern_stress(res))


def _pattern_stress(res) -> dict:
    """{pattern label: stress} of a ``StaticResult`` (its mapping is keyed by pattern key)."""
    ps = getattr(res, "pattern_stress", {})
    keys = list(getattr(res, "pattern_u", {}))
    return {p["key"]: np.asarray(ps[k], dtype=float)
            for p, k in zip(res.patterns, keys, strict=True) if k in ps}


def _float_or_none(v) -> float | None:
    return float(v) if isinstance(v, int | float) and math.isfinite(v) else None


EXTRA_PREFIX = "x_"        # arrays another kind of entry stores beside the reference's own


def _save(path: Path, ref: StaticReference, extra: dict | None = None,
          extra_meta: dict | None = None) -> None:
    """Write ``ref`` as one checksummed file; ``extra``: more arrays in the same file (read
    back by ``_load_entry``), ``extra_meta`` their description."""
    names = sorted(ref.regions)
    meta = {"format": STATIC_CACHE_FORMAT, "key": ref.key, "variant": ref.variant,
            "variant_hash": ref.variant_hash, "options": ref.options, "ref_rpm": ref.ref_rpm,
            "mesh_key": ref.mesh_key, "regions": names, "face_groups": list(ref.face_groups),
            "n_elements": ref.n_elements, "solve_seconds": ref.solve_seconds,
            "relative_residual": ref.relative_residual, "patterns": list(ref.patterns),
            "pattern_stress": list(ref.pattern_stress)}
    arrays = {"stress_ref": ref.stress_ref, "von_mises_ref": ref.von_mises_ref, "xyz": ref.xyz,
              "excluded": ref.excluded, "cells": ref.cells, "face_cells": ref.face_cells,
              "face_group": ref.face_group}
    if ref.stress_linear is not None:
        arrays["stress_linear"] = ref.stress_linear
    for i, n in enumerate(names):
        arrays[f"r{i}"] = ref.regions[n]
    for i, k in enumerate(ref.pattern_stress):
        arrays[f"p{i}"] = ref.pattern_stress[k]
    arrays.update({EXTRA_PREFIX + k: v for k, v in (extra or {}).items()})
    cachefile.save(path, arrays, {**meta, "extra": extra_meta or {}})


def _load(path: Path, key: str, name: str, t0: float) -> StaticReference | None:
    """Read a cache file; None (→ recompute) if it is unreadable, truncated, foreign or
    inconsistent."""
    got = _load_entry(path, key, name, t0)
    return None if got is None else got[0]


def _load_entry(path: Path, key: str, name: str, t0: float, what: str = "static"):
    """(reference, extra arrays, extra meta) of a cache file (``_save``), or None."""
    got = cachefile.load(path, key, what)
    if got is None:
        return None
    z, meta = got
    ref = _reference(z, meta, key, name, t0)
    if ref is None:
        return None
    extra = {k[len(EXTRA_PREFIX):]: z[k] for k in z if k.startswith(EXTRA_PREFIX)}
    return ref, extra, dict(meta.get("extra") or {})


def _reference(z, meta: dict, key: str, name: str, t0: float) -> StaticReference | None:
    """The reference of a cache file's arrays and meta; None where they are inconsistent."""
    try:
        if meta.get("format") != STATIC_CACHE_FORMAT:
            return None
        arr = {k: z[k] for k in ("stress_ref", "von_mises_ref", "xyz", "excluded", "cells",
                                 "face_cells", "face_group")}
        regions = {n: z[f"r{i}"] for i, n in enumerate(meta["regions"])}
        lin = z["stress_linear"] if "stress_linear" in z else None
        pst = {k: z[f"p{i}"] for i, k in enumerate(meta["pattern_stress"])}
        n = arr["xyz"].shape[1] if arr["xyz"].ndim == 2 else -1
        ok = (arr["xyz"].shape == (3, n) and n > 0 and arr["stress_ref"].shape == (6, n)
              and arr["von_mises_ref"].shape == (n,)
              and (lin is None or (lin.shape == (6, n) and bool(np.all(np.isfinite(lin)))))
              and all(a.shape == (6, n) and bool(np.all(np.isfinite(a))) for a in pst.values())
              and all(np.all(np.isfinite(arr[k])) for k in ("stress_ref", "von_mises_ref",
                                                              "xyz"))
              and arr["cells"].ndim == 2 and arr["cells"].shape[1] in (4, 10)
              and arr["face_cells"].ndim == 2
              and arr["face_group"].shape == (arr["face_cells"].shape[0],)
              and len(meta["face_groups"]) > int(arr["face_group"].max(initial=-1)))
        for a in [arr["excluded"], arr["cells"], arr["face_cells"], *regions.values()]:
            ok = ok and a.dtype.kind in "iu" and (a.size == 0 or (a.min() >= 0 and a.max() < n))
        if not ok:
            return None
        ref = StaticReference(
            variant=name, variant_hash=str(meta["variant_hash"]), options=dict(meta["options"]),
            ref_rpm=float(meta["ref_rpm"]), mesh_key=str(meta["mesh_key"]), key=key,
            regions=regions, face_groups=tuple(meta["face_groups"]),
            n_elements=int(meta["n_elements"]), solve_seconds=float(meta["solve_seconds"]),
            from_cache=True, seconds=time.perf_counter() - t0,
            relative_residual=_float_or_none(meta.get("relative_residual")),
            stress_linear=lin, patterns=tuple(meta["patterns"]), pattern_stress=pst, **arr)
        if not math.isfinite(ref.ref_rpm) or ref.ref_rpm <= 0:
            return None
        return ref
    except (KeyError, TypeError, ValueError):      # meta of another shape: recompute
        return None
