"""Fatigue of a proportionally loaded shaft (seed 000 §8.3; replaces the Ansys Fatigue Tool).

The balancer shaft's loads are centrifugal, so the stress at every node is the static solution
at the reference speed times one scalar load factor: σ(t) = σ_ref · (rpm(t)/rpm_ref)². The
load-factor history (``history``) is rainflow-counted ONCE (``counting``: our own three-point
detector on NumPy reversals, split from the recorder of cycle arrays and matrices; the
``rainflow`` package is its validation peer), and every node is evaluated at once by
broadcasting (``kernels``: equivalent stress, mean-stress theories, Miner damage, safety factor;
pure NumPy), with S-N curves and material cards from ``sn``. ``assess`` chains them for one
stress field, ``field`` for the whole static solution (hot spots per region), ``run`` is the
job as an API (``FatigueJob`` → ``FatigueRun``), ``outputs`` writes its files, ``plots`` its
figures, ``reference`` an independent recomputation for the validation tests. The methods
(the seed's, FKM, DIN 743) answer one protocol and are chosen by name from one registry,
``methods.METHODS`` (``methods.get_method``; a new method is one module there).

The names below load their module on first use: importing this package costs nothing. The
function ``assess`` is imported from its module (``shaftfe.fatigue.assess.assess``): the
package attribute ``assess`` is that module.
"""

from __future__ import annotations

import importlib

_HOME = {
    "FatigueResult": "assess", "life_hours": "assess", "life_km": "assess",
    "Cycles": "counting", "count_cycles": "counting", "rainflow_matrix": "counting",
    "MEAN_STRESS_THEORIES": "kernels", "SAFETY_FACTOR_MAX": "kernels",
    "damage_matrix": "kernels", "equivalent_stress": "kernels",
    "mean_stress_correction": "kernels", "miner_damage": "kernels", "node_damage": "kernels",
    "safety_factor": "kernels", "signed_von_mises": "kernels", "von_mises": "kernels",
    "FatigueMaterial": "sn", "SNCurve": "sn", "known_materials": "sn", "load_material": "sn",
}
__all__ = sorted(_HOME)


def __getattr__(name: str):
    if name in _HOME:
        return getattr(importlib.import_module(f"{__name__}.{_HOME[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
