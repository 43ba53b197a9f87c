"""S-N curves and fatigue material cards (``geometry/common/sn_curves.toml``).

An S-N curve is a table of (cycles to failure N, alternating stress S_a) at zero mean stress,
interpolated linearly in log N - log S_a between its points. Outside the table:

* above the first point (S_a > S_a[0], N < N[0]): the first segment's power law continues;
* below the last point (S_a < S_a[-1], N > N[-1]) — ``beyond_last``:
  - ``"cutoff"`` (default): the last point is an endurance limit; smaller amplitudes have the
    life ``infinite_life_cycles`` (default ∞, i.e. no damage). This is what the Ansys Fatigue
    Tool does with a tabular S-N curve: below the lowest alternating stress the life is its
    "Infinite Life" setting (default 1e9 cycles; give ``infinite_life_cycles = 1e9`` to copy
    that exactly);
  - ``"extrapolate"``: the last segment's power law continues (Miner "elementary", no
    endurance limit; conservative for variable amplitudes).

A ``FatigueMaterial`` is an S-N curve plus the static strengths the mean-stress theories need
(yield for Soderberg, ultimate for Goodman and Gerber).

Card keys: ``description``, ``source``, ``yield_MPa``, ``ultimate_MPa``, ``mean_stress_MPa``
(must be 0: the mean-stress theories correct to a zero-mean curve), ``beyond_last``,
``infinite_life_cycles`` (optional), and either a table ``cycles`` + ``alternating_MPa`` or a
Basquin line ``knee_cycles`` + ``knee_alternating_MPa`` + ``slope_k`` (S_a^k N = const; stored as
the two-point table (N_D/1000, S_D·1000^(1/k)), (N_D, S_D), which is the same power law).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from shaftfe.errors import InputError
from shaftfe.fatigue.cards import card_of
from shaftfe.fatigue.fkm import GROUPS
from shaftfe.model.parse import material_record
from shaftfe.model.sn_file import card_names as known_materials
from shaftfe.model.sn_file import read_cards
from shaftfe.util.paths import SN_FILE

BEYOND_LAST = ("cutoff", "extrapolate")


@dataclass(frozen=True)
class SNCurve:
    """Zero-mean S-N table; see the module docstring for the behaviour outside it."""

    cycles: tuple[float, ...]            # N, strictly increasing, > 0
    alternating_MPa: tuple[float, ...]   # S_a, strictly decreasing, > 0
    beyond_last: str = "cutoff"
    infinite_life_cycles: float = math.inf

    def __post_init__(self) -> None:
        n = np.asarray(self.cycles, dtype=float)
        s = np.asarray(self.alternating_MPa, dtype=float)
        src = "S-N curve"
        if n.ndim != 1 or n.size < 2 or n.size != s.size:
            raise InputError(src, "cycles/alternating_MPa", "two equally long lists, >= 2 points",
                             got=(n.size, s.size))
        if not (np.all(np.isfinite(n)) and np.all(n > 0) and np.all(np.diff(n) > 0)):
            raise InputError(src, "cycles", "finite, > 0, strictly increasing",
                             got=list(self.cycles))
        if not (np.all(np.isfinite(s)) and np.all(s > 0) and np.all(np.diff(s) < 0)):
            raise InputError(src, "alternating_MPa", "finite, > 0, strictly decreasing",
                             got=list(self.alternating_MPa))
        if self.beyond_last not in BEYOND_LAST:
            raise InputError(src, "beyond_last", " | ".join(BEYOND_LAST), got=self.beyond_last)
        if not (self.infinite_life_cycles >= n[-1]):
            raise InputError(src, "infinite_life_cycles", f">= the last point ({n[-1]:g})",
                             got=self.infinite_life_cycles)

    @property
    def endurance_MPa(self) -> float:
        """The last point's amplitude: no damage below it with ``beyond_last = "cutoff"``."""
        return float(self.alternating_MPa[-1])

    def log_tables(self) -> tuple[np.ndarray, np.ndarray]:
        """(log10 S_a ascending, log10 N matching) for ``np.interp``."""
        ls = np.log10(np.asarray(self.alternating_MPa, dtype=float))[::-1].copy()
        ln = np.log10(np.asarray(self.cycles, dtype=float))[::-1].copy()
        return ls, ln

    def cycles_to_failure(self, sa) -> np.ndarray:
        """N(S_a) for any array of equivalent zero-mean amplitudes (MPa); ∞ → 0 cycles."""
        return 10.0 ** (-self.log_inverse_life(np.asarray(sa, dtype=float)))

    def log_inverse_life(self, sa: np.ndarray) -> np.ndarray:
        """log10(1/N(S_a)) (= −log10 N). S_a = ∞ gives +∞ (N = 0); S_a below the cutoff gives
        −log10(infinite_life_cycles) (−∞ by default: no damage)."""
        ls_tab, ln_tab = self.log_tables()
        with np.errstate(divide="ignore", invalid="ignore"):
            ls = np.log10(sa)
        out = np.interp(ls, ls_tab, ln_tab)
        hi = ls > ls_tab[-1]
        if hi.any():
            slope = (ln_tab[-1] - ln_tab[-2]) / (ls_tab[-1] - ls_tab[-2])
            out = np.where(hi, ln_tab[-1] + slope * (ls - ls_tab[-1]), out)
        lo = ls < ls_tab[0]
        if lo.any():
            if self.beyond_last == "cutoff":
                out = np.where(lo, math.log10(self.infinite_life_cycles), out)
            else:
                slope = (ln_tab[1] - ln_tab[0]) / (ls_tab[1] - ls_tab[0])
                out = np.where(lo, ln_tab[0] + slope * (ls - ls_tab[0]), out)
        out = np.where(np.isposinf(ls), -np.inf, out)   # infinite amplitude: N = 0
        return -out

    def amplitude_at(self, cycles) -> np.ndarray:
        """Inverse: S_a at N cycles (log-log, same extrapolation); NaN beyond a cutoff."""
        n = np.asarray(cycles, dtype=float)
        ls_tab, ln_tab = self.log_tables()
        x, y = ln_tab[::-1], ls_tab[::-1]     # log N ascending, log S descending
        ln = np.log10(n)
        out = np.interp(ln, x, y)
        s0 = (y[1] - y[0]) / (x[1] - x[0])
        out = np.where(ln < x[0], y[0] + s0 * (ln - x[0]), out)
        if self.beyond_last == "extrapolate":
            s1 = (y[-1] - y[-2]) / (x[-1] - x[-2])
            out = np.where(ln > x[-1], y[-1] + s1 * (ln - x[-1]), out)
        else:
            out = np.where(ln > x[-1], np.nan, out)
        return 10.0 ** out


@dataclass(frozen=True)
class FatigueMaterial:
    name: str
    yield_MPa: float
    ultimate_MPa: float
    sn: SNCurve
    description: str = ""
    source: str = ""


_CARD_KEYS = {"description", "source", "material", "yield_MPa", "ultimate_MPa", "mean_stress_MPa",
              "beyond_last", "infinite_life_cycles", "cycles", "alternating_MPa", "knee_cycles",
              "knee_alternating_MPa", "slope_k", "note"}


def card_of_material(material: str, path: str | Path = SN_FILE) -> str | None:
    """The name of the S-N card whose ``material`` is the record ``material`` (the first in
    name order), or None."""
    cards = read_cards(path)
    return next((n for n in sorted(cards) if cards[n].get("material") == material), None)


def variant_card(variant) -> str:
    """The seed method's S-N card of a variant: its [duty] ``sn_curve``, else the card whose
    ``material`` is the shaft's own (``card_of_material``); neither: one line naming the
    material and the cards there are."""
    d = variant.duty
    if d is not None and d.sn_curve is not None:
        return d.sn_curve
    name = card_of_material(variant.material.name)
    if name is None:
        src = d.source if d is not None else (variant.source_files or (variant.name,))[0]
        raise InputError(src, "duty.sn_curve", "an S-N card of sn_curves.toml for the seed "
                         f"method (none has material = {variant.material.name!r}, the shaft's): "
                         f"one of {', '.join(known_materials())}, or --material",
                         reason="is not stated")
    return name


def load_material(name: str, path: str | Path = SN_FILE, *,
                  beyond_last: str | None = None,
                  infinite_life_cycles: float | None = None) -> FatigueMaterial:
    """Material card ``name`` from ``path`` (default ``geometry/common/sn_curves.toml``); the
    optional arguments override the card's endurance treatment."""
    path = Path(path)
    cards = read_cards(path)
    if name not in cards:
        raise InputError(str(path), "material", f"one of {sorted(cards)}", got=name)
    card = cards[name]
    src = str(path)
    where = f"sn_curves.{name}"
    unknown = sorted(set(card) - _CARD_KEYS)
    if unknown:
        raise InputError(src, f"{where}.{unknown[0]}", f"one of {sorted(_CARD_KEYS)}",
                         reason="is not a known key")

    def num(key: str, allowed: str, ok, default=None) -> float:
        if key not in card:
            if default is not None:
                return default
            raise InputError(src, f"{where}.{key}", allowed, reason="is missing")
        v = card[key]
        if isinstance(v, bool) or not isinstance(v, int | float) or not ok(float(v)):
            raise InputError(src, f"{where}.{key}", allowed, got=v)
        return float(v)

    rec = None
    if "material" in card:
        # the strengths come from the material record (one record per material and heat
        # treatment, geometry/common/materials.toml), not from a second copy here
        for key in ("yield_MPa", "ultimate_MPa", "knee_alternating_MPa"):
            if key in card:
                raise InputError(src, f"{where}.{key}", "absent: the card names a material "
                                 f"record ({card['material']!r}) that gives it")
        rec = material_record(str(card["material"]))
        sy, su = rec.yield_MPa, rec.ultimate_MPa
    else:
        sy = num("yield_MPa", "> 0", lambda v: v > 0)
        su = num("ultimate_MPa", ">= yield_MPa", lambda v: v >= sy)
    num("mean_stress_MPa", "0 (a zero-mean S-N curve)", lambda v: v == 0.0, default=0.0)
    if "cycles" in card or "alternating_MPa" in card:
        lists = []
        for key in ("cycles", "alternating_MPa"):
            v = card.get(key)
            if not isinstance(v, list) or not all(isinstance(x, int | float) and
                                                  not isinstance(x, bool) for x in v):
                raise InputError(src, f"{where}.{key}", "a list of numbers", got=v)
            lists.append(tuple(float(x) for x in v))
        cycles, amps = lists
    else:
        nd = num("knee_cycles", "> 1000", lambda v: v > 1000)
        sd = (material_knee(rec) if rec is not None
              else num("knee_alternating_MPa", "> 0", lambda v: v > 0))
        k = num("slope_k", "in (1, 100]", lambda v: 1 < v <= 100)
        cycles, amps = (nd / 1000.0, nd), (sd * 1000.0 ** (1.0 / k), sd)
    bl = beyond_last if beyond_last is not None else card.get("beyond_last", "cutoff")
    inf_life = (infinite_life_cycles if infinite_life_cycles is not None
                else num("infinite_life_cycles", "> 0", lambda v: v > 0, default=math.inf))
    try:
        sn = SNCurve(cycles, amps, bl, inf_life)
    except InputError as exc:
        raise InputError(src, f"{where}.{exc.field}", exc.allowed, got=exc.got) from None
    return FatigueMaterial(name, sy, su, sn, str(card.get("description", "")),
                           str(card.get("source", "")))


def material_knee(rec) -> float:
    """The S-N knee amplitude of a material record: the FKM material fatigue strength
    σ_W,zd = f_W,σ R_m of its group (``fkm.GROUPS``; the guideline's Table 4.2.1), at the record's
    strength reference diameter (no size, surface or notch factor: the seed method's kf)."""
    card = card_of(rec, "geometry/common/materials.toml")     # the one group rule
    return GROUPS[card.group].f_w_sigma * card.rm_n_MPa
