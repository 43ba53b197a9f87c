"""One cache-entry format for every disk cache (mesh, static solution): an ``.npz`` of named
arrays plus a JSON ``meta`` block that carries the entry's key and a sha256 checksum of the
arrays.

``save(path, arrays, meta)`` writes atomically (a temporary file renamed into place), so two
processes building the same entry at once both write a complete file and the last rename wins.
``load(path, key, what)`` returns (arrays, meta), or None when the entry must be rebuilt: a
file that cannot be read, is truncated, fails its checksum or belongs to another key. A damaged
entry prints one line on stderr, ``shaftfe: note: <what> cache entry <file> is damaged (...);
rebuilding``; an entry of an older format without a checksum is rebuilt silently.
"""

from __future__ import annotations

import hashlib
import importlib.util
import json
import sys
from pathlib import Path

import numpy as np

from shaftfe.util.atomic import atomic_path


def checksum(arrays: dict[str, np.ndarray]) -> str:
    """sha256 over every array's name, dtype, shape and bytes, in name order."""
    h = hashlib.sha256()
    for name in sorted(arrays):
        a = np.ascontiguousarray(arrays[name])
        h.update(f"{name}|{a.dtype.str}|{a.shape}|".encode())
        h.update(a.tobytes())
    return h.hexdigest()


def save(path: Path, arrays: dict[str, np.ndarray], meta: dict, *,
         compressed: bool = False) -> None:
    meta = dict(meta, sha256=checksum(arrays))
    payload = dict(arrays, meta=np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8))
    with atomic_path(path, suffix=".tmp") as tmp, open(tmp, "wb") as fh:
        (np.savez_compressed if compressed else np.savez)(fh, **payload)


def load(path: Path, key: str, what: str) -> tuple[dict[str, np.ndarray], dict] | None:
    path = Path(path)
    try:
        with np.load(path, allow_pickle=False) as z:
            meta = json.loads(z["meta"].tobytes().decode())
            if meta.get("key") != key:
                return None                      # another entry (a 96-bit prefix collision)
            arrays = {n: np.array(z[n]) for n in z.files if n != "meta"}
    except Exception as exc:                     # any damage (zip, json, truncation): rebuild
        _notice(what, path, exc.__class__.__name__)
        return None
    if "sha256" not in meta:
        return None                              # an older format: rebuilt silently
    if checksum(arrays) != meta["sha256"]:
        _notice(what, path, "checksum mismatch")
        return None
    return arrays, meta


def _notice(what: str, path: Path, why: str) -> None:
    print(f"shaftfe: note: {what} cache entry {path.name} is damaged ({why}); rebuilding",
          file=sys.stderr)


def cached(path: Path, key: str, what: str, make) -> tuple[dict[str, np.ndarray], dict]:
    """(arrays, meta) of ``make()`` cached at ``path`` under ``key`` (``save`` / ``load``:
    checksummed, rebuilt when damaged or another entry's; a read-only cache only costs the
    write). ``make`` returns the arrays and the extra meta to keep beside them."""
    got = load(path, key, what) if Path(path).exists() else None
    if got is not None:
        return got
    arrays, meta = make()
    meta = dict(meta, key=key)
    try:
        save(path, arrays, meta)
    except OSError:
        pass
    return arrays, meta


def cached_csr(path: Path, key: str, what: str, make):
    """The sparse CSR matrix ``make()`` cached at ``path`` under ``key`` (``cached``)."""
    import scipy.sparse as sp

    def arrays():
        A = make().tocsr()
        return {"data": A.data, "indices": A.indices, "indptr": A.indptr}, \
            {"shape": list(A.shape)}
    z, meta = cached(path, key, what, arrays)
    return sp.csr_matrix((z["data"], z["indices"], z["indptr"]), shape=tuple(meta["shape"]),
                         copy=False)


def code_fingerprint(modules: tuple[str, ...]) -> str:
    """sha256 over the source files of ``modules`` (found without importing)."""
    h = hashlib.sha256()
    for name in modules:
        spec = importlib.util.find_spec(name)
        origin = spec.origin if spec is not None else None
        h.update(name.encode())
        if origin and Path(origin).is_file():
            h.update(Path(origin).read_bytes())
    return h.hexdigest()
