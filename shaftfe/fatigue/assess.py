"""The fatigue chain for a whole stress field: history → cycles → damage → life → safety factor.

``assess(sigma_ref, history, material)``: ``sigma_ref`` is the static solution at the history's
reference speed (per node, (N, 6) components xx, yy, zz, xy, yz, xz in MPa, or an (N,) array of
equivalent stresses already computed; ``shaftfe.static.solve`` stores (6, N): pass
``stress_ref.T``); ``history`` a ``shaftfe.fatigue.history.LoadHistory`` whose ``rpm_ref`` is the
speed of the static solution (``history.with_reference(static_rpm)`` otherwise); its load factor is
counted once. Life: blocks = 1 / D, hours = blocks · block duration / 3600, km = hours · average
speed (default 70 km/h, seed 000 §8.3). A history without cycles (constant speed) or a node without
stress has D = 0: life = ∞ and the safety factor is capped; the result says so in ``notes`` instead
of dividing by zero.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from shaftfe.errors import InputError
from shaftfe.fatigue import kernels
from shaftfe.fatigue.counting import Cycles, count_cycles
from shaftfe.fatigue.sn import FatigueMaterial

DEFAULT_SPEED_KMH = 70.0              # seed 000 §8.3
DEFAULT_DESIGN_LIFE_BLOCKS = 1.0e7    # seed 000 §8.3: 10^7 "cycles" = passes of the block


def life_hours(blocks, block_duration_s: float):
    """Life in hours of riding from a life in blocks (∞ stays ∞)."""
    return np.asarray(blocks, dtype=float) * (block_duration_s / 3600.0)


def life_km(hours, speed_kmh: float = DEFAULT_SPEED_KMH):
    """Life in km at an average speed."""
    return np.asarray(hours, dtype=float) * speed_kmh


@dataclass(frozen=True, eq=False)
class FatigueResult:
    """Per-node results (arrays of the field's shape) and the settings that produced them."""

    sigma_eq_MPa: np.ndarray
    damage_per_block: np.ndarray
    life_blocks: np.ndarray
    life_hours: np.ndarray
    life_km: np.ndarray
    safety_factor: np.ndarray
    safety_status: np.ndarray          # kernels.SOLVED / CAPPED / FLOORED
    cycles: Cycles
    block_duration_s: float
    design_life_blocks: float
    speed_kmh: float
    material: str
    theory: str
    equivalent: str
    kf: float
    notes: tuple[str, ...]
    exact_nodes: np.ndarray | None = None   # None: every node exact; else only these (long
                                            # history, the rest of the field on binned classes)
    beta: np.ndarray | None = None          # spin softening per node (None: proportional)

    def linear_stress(self, i: int) -> tuple[float, float]:
        """(S0, β) of node ``i``: the stress history there is S0 (λ + β λ²)."""
        s = float(np.ravel(self.sigma_eq_MPa)[i])
        if self.beta is None:
            return s, 0.0
        b = float(np.ravel(self.beta)[i])
        return s / (1.0 + b), b

    @property
    def infinite_life(self) -> np.ndarray:
        return self.damage_per_block == 0.0

    def hot_spot(self, mask=None) -> int:
        """Index of the node with the largest damage (smallest safety factor on ties), among
        ``mask`` (e.g. to exclude singular nodes under a bearing, as the seed did)."""
        d = np.where(mask, self.damage_per_block, -1.0) if mask is not None \
            else self.damage_per_block
        order = np.lexsort((self.safety_factor.ravel(), -np.ravel(d)))
        return int(order[0])

    def node_summary(self, i: int) -> dict:
        f = {k: float(np.ravel(getattr(self, k))[i]) for k in (
            "sigma_eq_MPa", "damage_per_block", "life_blocks", "life_hours", "life_km",
            "safety_factor")}
        f["safety_status"] = ("solved", "capped", "floored")[int(np.ravel(self.safety_status)[i])]
        return {"node": int(i), **f}


def assess(sigma_ref, history, material: FatigueMaterial, *, equivalent: str = "von_mises",
           theory: str = "soderberg", kf: float = 1.0,
           design_life_blocks: float = DEFAULT_DESIGN_LIFE_BLOCKS,
           speed_kmh: float = DEFAULT_SPEED_KMH, n_max: float = kernels.SAFETY_FACTOR_MAX,
           closure: str = "repeated", safety: bool = True, exact_at=None,
           sigma_eq=None, beta=None) -> FatigueResult:
    """Evaluate every node at once (see the module docstring). ``exact_at``: nodes whose
    damage is evaluated on every cycle class even where a very long history makes the rest of
    the field go to binned classes (``kernels.node_damage``): the hot-spot candidates.
    ``sigma_eq``: the equivalent stress of ``sigma_ref`` if the caller has it already.
    ``beta``: spin softening per node (``shaftfe.fatigue.field.softening_beta``); the stress
    ``sigma_ref`` is then the softened one at the reference speed, S0 (1 + β), and the node's
    history S0 (λ + β λ²) (``kernels`` module docstring)."""
    if not (math.isfinite(speed_kmh) and speed_kmh > 0):
        raise InputError("fatigue options", "average speed", "a finite number > 0 (km/h)",
                         got=speed_kmh)
    s = np.asarray(sigma_ref, dtype=float)
    if sigma_eq is not None and s.ndim == 2 and s.shape[-1] == 6:
        s_eq = np.asarray(sigma_eq, dtype=float)
    elif s.ndim >= 1 and s.shape[-1] == 6 and s.ndim == 2:
        s_eq = kernels.equivalent_stress(s, equivalent)
    elif s.ndim == 1:
        s_eq = s.copy()
        equivalent = "given"
    else:
        raise InputError("stress field", "sigma_ref", "(N, 6) components or (N,) equivalent "
                         "stresses", got=s.shape)
    if not np.all(np.isfinite(s_eq)):
        raise InputError("stress field", "sigma_ref", "finite values", reason="has NaN/inf")
    b = kernels.check_beta(beta, s_eq.shape)
    if b is not None:
        b = b.reshape(s_eq.shape)
    s_lin = s_eq if b is None else s_eq / (1.0 + b)
    cyc = count_cycles(history.load_factor, closure)
    notes = []
    info: dict = {}
    d = kernels.node_damage(s_lin, cyc, material, theory, kf, exact_at=exact_at, info=info,
                            beta=b)
    if cyc.n == 0:
        notes.append("the history has no load cycles (constant speed): no fatigue damage, "
                     "infinite life everywhere")
    if info:
        notes.append(f"long history: {info['binned_nodes']} of {d.size} nodes were evaluated on "
                     f"the {info['exact_classes']} most damaging of {info['classes']} cycle "
                     f"classes plus {info['binned_classes']} binned range × mean classes for "
                     "the rest; the hot-spot candidates on every class")
    if cyc.n and np.any(d == 0):
        notes.append(f"{int(np.sum(d == 0))} node(s) without damage (all cycles below the "
                     "endurance limit or no stress): infinite life")
    with np.errstate(divide="ignore"):
        blocks = np.where(d > 0, 1.0 / np.where(d > 0, d, 1.0), np.inf)
    hours = life_hours(blocks, history.duration_s)
    if safety:
        n, status = kernels.safety_factor(s_lin, cyc, material, design_life_blocks, theory,
                                          kf, n_max=n_max, beta=b)
        if np.any(status == kernels.CAPPED):
            notes.append(f"safety factor capped at {n_max:g} at {int(np.sum(status == 1))} "
                         f"node(s) (life at {n_max:g}x the load >= design life)")
    else:
        n = np.full(s_eq.shape, np.nan)
        status = np.full(s_eq.shape, -1, dtype=np.int8)
    exact_nodes = None
    if info:
        exact_nodes = np.asarray(exact_at if exact_at is not None else [], dtype=np.int64)
    return FatigueResult(s_eq, d, blocks, hours, life_km(hours, speed_kmh), n, status, cyc,
                         float(history.duration_s), float(design_life_blocks), float(speed_kmh),
                         material.name, theory, equivalent, float(kf), tuple(notes),
                         exact_nodes, b)
