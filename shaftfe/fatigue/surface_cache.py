"""The surface references of the axisymmetric and zoned models (``fatigue.run.
surface_reference``) kept on disk for the next fatigue run, as the static cache keeps the full 3D
model's (``static.cache``): a warm ``shaftfe fatigue`` reads its field instead of solving twice
(softened and unsoftened).

An entry is the ``StaticReference`` in the static cache's format (``static.cache._save``,
``_load``) beside the arrays of its ``DepthProbe`` (FKM's stress profiles need the field below
the surface: the meridian mesh and the harmonics' nodal stresses; each zone's volume field),
in one ``.npz`` each (``util.cachefile``: checksummed, written atomically). The key is the
variant's content, the model and its options, the reference speed and a fingerprint of the
code of both models (``KEY_MODULES``): any change of these solves again.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import time
from pathlib import Path

from shaftfe.static import cache as static_cache
from shaftfe.util import paths

SURFACE_CACHE_FORMAT = 1
KEY_MODULES = (*static_cache.FINGERPRINT_MODULES,
               "shaftfe.axisymmetric.mesh", "shaftfe.axisymmetric.kernels",
               "shaftfe.axisymmetric.harmonic", "shaftfe.axisymmetric.model",
               "shaftfe.axisymmetric.solve", "shaftfe.axisymmetric.recovery",
               "shaftfe.axisymmetric.reference", "shaftfe.axisymmetric.pointeval",
               "shaftfe.zoned.zones", "shaftfe.zoned.submodel", "shaftfe.zoned.solve",
               "shaftfe.zoned.reference", "shaftfe.fe.pointeval", "shaftfe.solid.plan",
               "shaftfe.solid.mesh", "shaftfe.fatigue.run", "shaftfe.fatigue.surface_cache")


def key(model: str, variant, options, ref_rpm: float) -> str:
    opts = dataclasses.asdict(options)
    payload = {"format": SURFACE_CACHE_FORMAT, "model": model,
               "variant_hash": static_cache.variant_hash(variant), "options": opts,
               "ref_rpm": float(ref_rpm), "code": static_cache.code_fingerprint(KEY_MODULES)}
    text = json.dumps(payload, sort_keys=True, separators=(",", ":"), default=repr)
    return hashlib.sha256(text.encode()).hexdigest()


def entry_paths(k: str, cache_dir=None) -> tuple[Path, Path]:
    base = paths.cache_dir(cache_dir)
    return base / f"surface-{k[:24]}.npz", base / f"surface-{k[:24]}.probe.npz"


def load(model: str, variant, options, ref_rpm: float, cache_dir=None):
    """The cached reference with its probe, or None (no entry, another key, damage)."""
    from shaftfe.util import cachefile
    t0 = time.perf_counter()
    k = key(model, variant, options, ref_rpm)
    ref_path, probe_path = entry_paths(k, cache_dir)
    if not (ref_path.exists() and probe_path.exists()):
        return None
    ref = static_cache._load(ref_path, k, variant.name, t0)
    got = cachefile.load(probe_path, k, "surface probe")
    if ref is None or got is None:
        return None
    arrays, meta = got
    kind = _probe_class(meta.get("probe"))
    if kind is None:
        return None
    probe = kind.from_arrays(arrays)
    return dataclasses.replace(ref, depth_probe=probe, seconds=time.perf_counter() - t0)


def store(ref, model: str, variant, options, cache_dir=None):
    """Write ``ref`` (a surface reference with its probe) for the next run; ``ref`` with a note
    when the directory cannot be written."""
    from shaftfe.util import cachefile
    k = key(model, variant, options, ref.ref_rpm)
    ref_path, probe_path = entry_paths(k, cache_dir)
    ref = dataclasses.replace(ref, key=k)
    try:
        cachefile.save(probe_path, ref.depth_probe.arrays(),
                       {"key": k, "probe": type(ref.depth_probe).__name__})
        static_cache._save(ref_path, ref)
    except OSError as exc:
        return dataclasses.replace(ref, notes=(*ref.notes, "surface cache: not written "
                                               f"({exc.__class__.__name__})"))
    return ref


def _probe_class(name):
    from shaftfe.axisymmetric.reference import SurfaceProbe
    from shaftfe.zoned.reference import ZonedProbe
    return {"SurfaceProbe": SurfaceProbe, "ZonedProbe": ZonedProbe}.get(name)
