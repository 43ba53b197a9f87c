"""Fatigue of a proportionally loaded shaft (seed 000 §8.3; replaces the Ansys Fatigue Tool).

The balancer shaft's loads are centrifugal, so the stress at every node is the static solution
at the reference speed times one scalar load factor: σ(t) = σ_ref · (rpm(t)/rpm_ref)². The
load-factor history is rainflow-counted ONCE (``counting``), and every node is evaluated at once by
broadcasting (``kernels``): amplitude = σ_eq · range_factor / 2, mean = σ_eq · mean_factor, a
mean-stress correction, an S-N curve (``sn``), Miner's rule, the life in blocks / hours / km and
the safety factor at a design life. ``assess`` is the thin wrapper that chains them.

Modules: ``counting`` (rainflow detection with the ``rainflow`` package, recording into cycle
arrays and matrices), ``kernels`` (pure NumPy: equivalent stress, mean-stress theories, Miner
damage, safety factor), ``sn`` (S-N curves and material cards), ``assess`` (the chain).
Importing this package loads NumPy only.
"""

from shaftfe.fatigue.assess import FatigueResult, assess, life_hours, life_km
from shaftfe.fatigue.counting import Cycles, count_cycles, rainflow_matrix
from shaftfe.fatigue.kernels import (
    MEAN_STRESS_THEORIES,
    SAFETY_FACTOR_MAX,
    damage_matrix,
    equivalent_stress,
    mean_stress_correction,
    miner_damage,
    node_damage,
    safety_factor,
    signed_von_mises,
    von_mises,
)
from shaftfe.fatigue.sn import FatigueMaterial, SNCurve, known_materials, load_material

__all__ = [
    "MEAN_STRESS_THEORIES",
    "SAFETY_FACTOR_MAX",
    "Cycles",
    "FatigueMaterial",
    "FatigueResult",
    "SNCurve",
    "assess",
    "count_cycles",
    "damage_matrix",
    "equivalent_stress",
    "known_materials",
    "life_hours",
    "life_km",
    "load_material",
    "mean_stress_correction",
    "miner_damage",
    "node_damage",
    "rainflow_matrix",
    "safety_factor",
    "signed_von_mises",
    "von_mises",
]
