"""Static strength on a named load case (issue #31 item 4): DIN 743 S_F at every notch of the
beam model, from the case's maxima of the nominal stresses.

A load case (``model.loads.LoadCase``: a speed, a factor per load, the channels' values) is the
extreme the shaft must carry once without yielding: an overload of 1.5 × torque, a run-up, the
top speed. The beam solves it (``beam.solve.solve_cases``: every load, torsion and axial force,
one factorisation); at each notch of ``fatigue.strength.din743_notches`` the nominal stresses
are those the fatigue check takes (``fatigue.strength.section_stresses``: σ_zd = N/A,
σ_b = 32 M/(π d³), τ_t = 16 T/(π d³) at the notch's judged span), entered as maxima
(static: amplitude 0), and DIN 743-1 gives
S_F = 1/√((σ_zd,max/σ_zdFK + σ_b,max/σ_bFK)² + (τ_t,max/τ_tFK)²) (``fatigue.din743.assess``:
one implementation of the standard), required ≥ S_min = 1.2.
"""

from __future__ import annotations

from dataclasses import dataclass

from shaftfe.beam.model import build_model
from shaftfe.beam.scf import converged_kt
from shaftfe.beam.solve import solve_cases
from shaftfe.errors import InputError
from shaftfe.fatigue import din743
from shaftfe.fatigue.cards import load_surfaces
from shaftfe.fatigue.strength import din743_card, din743_notches, notch_stresses


@dataclass(frozen=True)
class StaticRow:
    x_mm: float
    notch: str
    sigma_zd_MPa: float
    sigma_b_MPa: float
    tau_t_MPa: float
    S_F: float


@dataclass(frozen=True)
class StaticCheck:
    """DIN 743 S_F per notch for one load case, the governing notch and the requirement."""
    case: str
    rpm: float
    card: str
    rows: tuple[StaticRow, ...]
    S_min: float = din743.S_MIN

    @property
    def governing(self) -> StaticRow:
        return min(self.rows, key=lambda r: r.S_F)

    @property
    def ok(self) -> bool:
        return self.governing.S_F >= self.S_min


def case_of(variant, name: str, option: str = "--case"):
    """The variant's load case ``name`` (InputError listing its cases)."""
    for c in variant.load_cases:
        if c.name == name:
            return c
    raise InputError(option, "case", "a [[load_cases]] name of the variant: " + (
        ", ".join(c.name for c in variant.load_cases) or "(it defines none)"), got=name)


def din743_static(variant, case_name: str, opts) -> StaticCheck:
    """S_F per notch of ``variant`` in its load case ``case_name`` (``opts``: the strength
    options that choose the material card, ``fatigue.strength.StrengthOptions``)."""
    case = case_of(variant, case_name)
    card = din743_card(variant, opts)
    beam = solve_cases(build_model(variant), [case])[0]
    rows = []
    for x, notch, d, span in din743_notches(variant, beam, card, load_surfaces(),
                                            converged_kt()):
        zd, sb, tt = notch_stresses(beam, x, notch, d, span)
        res = din743.assess(notch, din743.Stresses(zd_m=zd, b_m=sb, t_m=tt), card.rm_n_MPa,
                            card.rp_n_MPa, card.group, hard_layer=card.case_hardened)
        rows.append(StaticRow(x, notch.name, zd, sb, tt, res.S_F))
    return StaticCheck(case.name, case.rpm, card.name, tuple(rows))
