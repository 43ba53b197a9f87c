"""The surface references of the axisymmetric and zoned models
(``fatigue.run.surface_reference``) kept on disk for the next fatigue run, as the static cache
keeps the full 3D model's (``static.cache``): a warm ``shaftfe fatigue`` reads its field
instead of solving twice (softened and unsoftened).

An entry is one ``.npz`` (``util.cachefile``: checksummed, written atomically): the
``StaticReference`` in the static cache's format (``static.cache._save``, ``_load_entry``) with
the arrays of its ``DepthProbe`` beside it (FKM's stress profiles need the field below the
surface: the meridian mesh and the harmonics' nodal stresses; each zone's volume field). The key
is the static cache's (``static.cache.static_key``: the variant's content, the options, the
reference speed) with the model and a fingerprint of the code of both models
(``KEY_MODULES``): any change of these solves again.
"""

from __future__ import annotations

import dataclasses
import time
from pathlib import Path

from shaftfe.axisymmetric.reference import SurfaceProbe
from shaftfe.solid.mesh import gmsh_version
from shaftfe.static import cache as static_cache
from shaftfe.zoned.reference import ZonedProbe

SURFACE_CACHE_FORMAT = 2       # 2: one file per entry (the probe's arrays inside)
KEY_MODULES = (*static_cache.FINGERPRINT_MODULES,
               "shaftfe.axisymmetric.mesh", "shaftfe.axisymmetric.kernels",
               "shaftfe.axisymmetric.harmonic", "shaftfe.axisymmetric.model",
               "shaftfe.axisymmetric.solve", "shaftfe.axisymmetric.recovery",
               "shaftfe.axisymmetric.reference", "shaftfe.axisymmetric.pointeval",
               "shaftfe.zoned.zones", "shaftfe.zoned.submodel", "shaftfe.zoned.solve",
               "shaftfe.zoned.reference", "shaftfe.fe.pointeval", "shaftfe.solid.plan",
               "shaftfe.solid.mesh", "shaftfe.fatigue.run", "shaftfe.fatigue.surface_cache",
               # the patterns' split and labels, the parts' softening, the entry's format
               "shaftfe.model.loads", "shaftfe.model.spin", "shaftfe.static.cache")


def key(model: str, variant, options, ref_rpm: float) -> str:
    """The static cache's key (``static.cache.static_key``) with this entry's model, format
    and code (``KEY_MODULES``)."""
    return static_cache.static_key(variant, options, "", ref_rpm, modules=KEY_MODULES,
                                   extra={"surface_format": SURFACE_CACHE_FORMAT,
                                          "model": model, "gmsh": gmsh_version()})


def entry_path(k: str, cache_dir=None) -> Path:
    return static_cache.cache_path(k, cache_dir, kind="surface")


def load(model: str, variant, options, ref_rpm: float, cache_dir=None):
    """The cached reference with its probe, or None (no entry, another key, damage)."""
    t0 = time.perf_counter()
    k = key(model, variant, options, ref_rpm)
    path = entry_path(k, cache_dir)
    if not path.exists():
        return None
    got = static_cache._load_entry(path, k, variant.name, t0, "surface")
    if got is None:
        return None
    ref, arrays, meta = got
    kind = _probe_class(meta.get("probe"))
    if kind is None:
        return None
    probe = kind.from_arrays(arrays)
    return dataclasses.replace(ref, depth_probe=probe, seconds=time.perf_counter() - t0)


def store(ref, model: str, variant, options, cache_dir=None):
    """Write ``ref`` (a surface reference with its probe) for the next run, one file; ``ref``
    with a note when the directory cannot be written."""
    k = key(model, variant, options, ref.ref_rpm)
    ref = dataclasses.replace(ref, key=k)
    try:
        static_cache._save(entry_path(k, cache_dir), ref, ref.depth_probe.arrays(),
                           {"probe": type(ref.depth_probe).__name__})
    except OSError as exc:
        return dataclasses.replace(ref, notes=(*ref.notes, "surface cache: not written "
                                               f"({exc.__class__.__name__})"))
    return ref


def _probe_class(name):
    return {"SurfaceProbe": SurfaceProbe, "ZonedProbe": ZonedProbe}.get(name)
