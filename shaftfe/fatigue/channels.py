"""Fatigue under several load channels (issue #31): σ(t) = Σ_k σ_k L_k(t) at each candidate node.

Each load pattern k (``shaftfe.model.loads.pattern_key``: the rpm² loads, the constant loads,
each history channel) has its own static stress field σ_k (6, n) at unit factor, and its own
factor history L_k(t) (``channel_factors``): (rpm(t)/ref)² for the rpm² pattern, 1 for the
constant one, channel(t)/channel_ref for a channel. The stress tensor at a node is the sum; the
loading is no longer proportional (a torque channel and the speed vary independently), so the
cycles are counted per node, not once for the whole field.

Measure (``MULTI_CHANNEL_EQUIVALENT``): rainflow cycles of the **signed von Mises** stress
(σ_vM with the sign of the largest-magnitude principal stress, as the Ansys Fatigue Tool's
"Signed von Mises"), per node, then the same mean-stress correction, S-N curve and Miner sum as
the single-channel path (``kernels``: one implementation). Why: a reversing torque must count
as one full cycle of ±τ, which the unsigned σ_vM folds into two cycles of 0…τ (a life several
times too long); the signed measure keeps the reversal, costs one equivalent history per node,
and reduces exactly to the single-channel result when one pattern acts (σ(t) = σ_1 λ(t), λ ≥ 0:
the signed σ_vM is s_1 λ(t) and its cycles are λ's cycles scaled by s_1). A critical-plane
measure (Findley, Fatemi–Socie) would resolve the shear planes of combined bending-torsion
better, at one history per plane and node; it is not implemented. Known limit of the signed
measure: where the dominant principal stress changes between σ1 and σ3 in a shear-dominated
state (|σ1| ≈ |σ3|) the sign jumps and a range of up to 2 σ_vM is counted that the tensor does
not have (conservative).

Time compression (``reversal_union``): only the samples where some factor history L_k turns
(its reversals, ``counting.reversals``) are kept — exact for one channel (the rainflow cycles
of σ_1 λ(t) are those of λ's reversals), and for several the multichannel peak-valley editing
that durability codes use (a combination Σ a_k L_k can turn between two channels' reversals
only where one channel's slope overtakes another's; the error is a range lost inside a
monotone stretch of every channel).

Candidates (``candidate_nodes``): the nodes whose bound on the equivalent stress can matter.
σ_vM is a norm of the stress tensor, so |σ_vM(Σ_k σ_k L_k)| ≤ Σ_k σ_vM(σ_k) max|L_k| =: U (the
triangle inequality). The exact peak |σ_eq| is computed at the extremes of U per region
(``field.candidates``); the candidates are the ``MAX_CANDIDATES`` nodes of largest U among
those whose U reaches ``CANDIDATE_FRACTION`` (0.9) of the largest of these peaks
(the node of that peak always among them). A node with a bound below that fraction has a
stress history below 0.9 × a candidate's peak (damage ≤ 0.9^k ≈ 0.59 of it for an S-N slope
k ≥ 5): it is not the hot spot unless its cycles differ much from the candidate's. A node
above it but beyond the ``MAX_CANDIDATES`` largest bounds is not assessed (``candidate_nodes``
returns how many; the run says so). Each candidate costs one rainflow
count of its own history (the single-channel path counts one for the whole field), which is
what bounds their number.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from shaftfe.fatigue import counting, kernels
from shaftfe.fatigue.field import candidates
from shaftfe.model.loads import FIXED_LAWS, law_factor
from shaftfe.util.units import REF_RPM, von_mises

MULTI_CHANNEL_EQUIVALENT = "signed_von_mises"
CANDIDATE_FRACTION = 0.9
MAX_CANDIDATES = 16
_CHUNK = 2_000_000                   # samples × nodes per equivalent-stress chunk


def channel_factors(history, keys) -> np.ndarray:
    """The factor histories L_k(t) (K, T) of the pattern keys (``model.loads.pattern_key``)
    on ``history``, by the speed laws' own rule (``model.loads.law_factor``): ("rpm2", ref) →
    (rpm/ref)², ("constant",) → 1, (channel, ref) → channel(t)/ref (an absent channel:
    InputError naming the history's columns)."""
    rows = []
    for key in keys:
        law, ref = key[0], (float(key[1]) if len(key) > 1 else 1.0)
        chans = {} if law in FIXED_LAWS else {law: history.channel(law)}
        v = law_factor(law, history.rpm, chans, ref_rpm=ref if law == "rpm2" else REF_RPM,
                       channel_ref=ref if law not in FIXED_LAWS else 1.0)
        rows.append(np.broadcast_to(np.asarray(v, dtype=float), (history.n_samples,)))
    return np.vstack(rows) if rows else np.zeros((0, history.n_samples))


def equivalent_histories(stress_k: np.ndarray, L: np.ndarray, nodes,
                         kind: str = MULTI_CHANNEL_EQUIVALENT) -> np.ndarray:
    """σ_eq(t) (len(nodes), T) at ``nodes`` from the pattern fields ``stress_k`` (K, 6, n) and
    the factor histories ``L`` (K, T)."""
    nodes = np.asarray(nodes, dtype=np.int64)
    out = np.empty((nodes.size, L.shape[1]))
    step = max(1, _CHUNK // max(L.shape[1], 1))
    for a in range(0, nodes.size, step):
        idx = nodes[a:a + step]
        sig = np.einsum("kcn,kt->ntc", stress_k[:, :, idx], L)        # (n, T, 6)
        out[a:a + step] = kernels.equivalent_stress(sig, kind)
    return out


def reversal_union(L: np.ndarray) -> np.ndarray:
    """The sample indices where some factor history turns (first and last kept)."""
    keep = np.zeros(L.shape[1], dtype=bool)
    keep[[0, -1]] = True
    for row in L:
        d = np.diff(row)
        nz = np.flatnonzero(d)
        if nz.size < 2:
            continue
        # a turn between consecutive changes of opposite sign (plateaus: their last sample)
        turn = nz[1:][np.sign(d[nz[1:]]) != np.sign(d[nz[:-1]])]
        keep[turn] = True
    return np.flatnonzero(keep)


def candidate_nodes(stress_k: np.ndarray, L: np.ndarray, excluded: np.ndarray,
                    regions: dict, kind: str = MULTI_CHANNEL_EQUIVALENT
                    ) -> tuple[np.ndarray, int]:
    """(the nodes that can be the hot spot, how many more passed the bound but were beyond
    ``MAX_CANDIDATES``) (module docstring)."""
    bound = np.asarray(sum(von_mises(stress_k[k]) * float(np.abs(L[k]).max(initial=0.0))
                           for k in range(stress_k.shape[0])), dtype=float)
    first = candidates(bound, excluded, regions)
    # |σ_eq| is σ_vM for every kind (the sign aside): the unsigned measure, no principal
    # stresses; on the samples where some channel turns (``reversal_union``)
    peaks = np.abs(equivalent_histories(stress_k, L[:, reversal_union(L)], first,
                                         "von_mises")).max(axis=1, initial=0.0)
    peak = float(peaks.max(initial=0.0))
    best = first[int(np.argmax(peaks))] if first.size else None
    ok = np.flatnonzero((bound >= CANDIDATE_FRACTION * peak) & ~excluded) if peak > 0 \
        else first[:0]
    ok = ok[np.argsort(-bound[ok], kind="stable")]
    chosen = ok[:MAX_CANDIDATES]
    if best is not None:
        chosen = np.concatenate([[best], chosen])
    return np.unique(chosen).astype(np.int64), int(max(0, ok.size - MAX_CANDIDATES))


@dataclass(frozen=True, eq=False)
class NodeLives:
    """Per candidate node: damage per block, safety factor at the design life (and its
    status), the peak |σ_eq| (MPa) and the number of cycle classes."""
    nodes: np.ndarray
    damage: np.ndarray
    safety: np.ndarray
    status: np.ndarray
    peak_MPa: np.ndarray
    n_classes: np.ndarray


def assess_nodes(stress_k: np.ndarray, L: np.ndarray, nodes, material, *,
                 design_life_blocks: float, theory: str = "soderberg", kf: float = 1.0,
                 kind: str = MULTI_CHANNEL_EQUIVALENT, closure: str = "repeated") -> NodeLives:
    """Rainflow per node on its equivalent-stress history, then the single-channel kernels with
    a unit reference stress (the history is already in MPa): the same mean-stress correction,
    S-N curve and Miner sum, one implementation."""
    nodes = np.asarray(nodes, dtype=np.int64)
    L = L[:, reversal_union(L)]
    dmg, sf, st, pk, ncl = (np.zeros(nodes.size) for _ in range(5))
    one = np.ones(1)
    for i in range(nodes.size):
        s_t = equivalent_histories(stress_k, L, nodes[i:i + 1], kind)[0]
        cyc = counting.count_cycles(s_t, closure)
        dmg[i] = kernels.node_damage(one, cyc, material, theory, kf)[0]
        n_i, st_i = kernels.safety_factor(one, cyc, material, design_life_blocks, theory, kf)
        sf[i], st[i] = n_i[0], st_i[0]
        pk[i] = float(np.abs(s_t).max(initial=0.0))
        ncl[i] = cyc.n
    return NodeLives(nodes, dmg, sf, st.astype(int), pk, ncl.astype(int))
