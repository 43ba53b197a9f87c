"""Stage 3: the 3D static solve on spring-supported bearings.

``model`` (options, assembly, bearing couplings, loads at REF_RPM), ``solve`` (one supported
solve at REF_RPM, every rpm by scaling, stress recovery), ``result`` (frozen results), ``error``
(a two-level error estimate), ``benchmark`` (each level's measured error), ``cache`` (the
reduced solution on disk, for fatigue). The names below load their module on first use, so
importing this package costs nothing.
"""

from __future__ import annotations

import importlib

# The static models every command that takes a static solution accepts as --model: 3D P2
# tets, or the body of revolution in Fourier harmonics (shaftfe.axisymmetric).
MODELS = ("solid", "axisymmetric")
# ``shaftfe static`` also takes the zoned solve (shaftfe.zoned: the axisymmetric global model
# with 3D submodels where the shaft is not round), its default
STATIC_MODELS = ("zoned", *MODELS)

_HOME = {
    "StaticOptions": "model", "StaticModel": "model",
    "build_model": "model", "load_case_label": "model", "region_nodes": "model",
    "StaticResult": "result", "StaticCase": "result",
    "RESIDUAL_TOL": "solve", "solve_model": "solve", "solve_static": "solve",
    "axis_deflection": "solve",
    "estimate_error": "error",
}
__all__ = sorted(_HOME)


def __getattr__(name: str):
    if name in _HOME:
        return getattr(importlib.import_module(f"{__name__}.{_HOME[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
