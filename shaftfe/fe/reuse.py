"""Share an assembled matrix and its factorisation between solves of one solid (a study group).

A design study evaluates many designs whose solid is the same: only part masses, eccentricities,
bearing stiffnesses or the load differ. The stiffness K of the mesh and the factorisation of
B = K + pins depend on the mesh and the shaft's E, ν only (the bearings and the parts' spin
softening are the low-rank terms of ``shaftfe.fe.lowrank``), so inside ``with shared():`` they
are made once per key and reused:

    with reuse.shared() as stats:
        for design in group:
            solve_static(design, ...)          # K and the factor made once
    stats == {"made": {"K": 1, "factor": 1}, "reused": {"K": 15, "factor": 15}}

Outside the context nothing is kept (every solve makes its own, as before), unless the process
called ``keep()`` (a study's worker process). Inside a ``shared()`` (or after ``keep()``) a
nested ``shared()`` shares the same store: a solve that opens its own scope (several speeds of
one shaft, fatigue's softened and unsoftened references) reuses what its caller kept. The
axisymmetric model's n = 0 and n = 1 factorisations are kinds of their own
(``axisymmetric.harmonic.solve``). One entry per kind
is held (a factorisation at the default level is ~600 MB), so a group must be evaluated in
order, one solid after the other.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

_store: dict | None = None


def _new() -> dict:
    return {"entries": {}, "made": {}, "reused": {}}


def keep() -> dict:
    """Turn sharing on for the rest of this process (a study's worker: consecutive designs of
    one solid reuse K and the factor across tasks); returns the running counts."""
    global _store
    if _store is None:
        _store = _new()
    return _store


@contextmanager
def shared() -> Iterator[dict]:
    """Reuse K and factorisations by key inside the block; yields the counts made / reused
    (the enclosing scope's store, and its counts, when one is open)."""
    global _store
    if _store is not None:
        yield _store
        return
    prev = _store
    _store = _new()
    try:
        yield _store
    finally:
        _store = prev


def mesh_digest(mesh) -> str:
    """The mesh itself (nodes, elements, element type), not how it was made: a mesh rebuilt
    elsewhere with another numbering is another key. ~1 ms at the default level."""
    import hashlib

    import numpy as np
    h = hashlib.sha256(type(mesh).__name__.encode())
    h.update(np.ascontiguousarray(mesh.p).tobytes())
    h.update(np.ascontiguousarray(mesh.t).tobytes())
    return h.hexdigest()


def active() -> bool:
    """Whether a scope keeps what ``memo`` makes (so a key is worth computing)."""
    return _store is not None


def memo(kind: str, key: tuple, make: Callable[[], Any]) -> Any:
    """``make()`` once per (kind, key) inside ``shared()``; a plain call outside it."""
    if _store is None:
        return make()
    held = _store["entries"].get(kind)
    if held is not None and held[0] == key:
        _store["reused"][kind] = _store["reused"].get(kind, 0) + 1
        return held[1]
    _store["entries"].pop(kind, None)          # free the old one before making the next
    value = make()
    _store["entries"][kind] = (key, value)
    _store["made"][kind] = _store["made"].get(kind, 0) + 1
    return value
