"""Static strength on a named load case (``fatigue.static_check``): DIN 743 S_F per notch.

The S_F formula is DIN 743-1's, one implementation (``fatigue.din743.assess``), which
tests/validation/test_din743.py checks against the TU Wien exam solution (S_F = 1.4640). Here:
the case's nominal stresses are the beam's (N/A, 32 M/(π d³), 16 T/(π d³), exact arithmetic on
the beam's lines), S_F combines them as DIN 743-1 says (1/√((σ_b/σ_bFK)² + (τ/τ_tFK)²), checked
by hand from the same result's FK values), and a factor on every load divides S_F by it
(S_F is homogeneous of degree −1 in the stresses: exact up to round-off)."""

import dataclasses
import math

import pytest

from shaftfe.errors import InputError
from shaftfe.fatigue import din743
from shaftfe.fatigue.static_check import din743_static
from shaftfe.fatigue.strength import StrengthOptions
from shaftfe.model.loader import load_variant
from shaftfe.util.paths import GEOMETRY_DIR


@pytest.fixture(scope="module")
def driven():
    return load_variant(GEOMETRY_DIR / "examples" / "x2_57_driven.toml")


def test_run_up_case_stresses_and_the_din743_combination(driven):
    chk = din743_static(driven, "run_up", StrengthOptions())
    assert chk.case == "run_up" and chk.rpm == 9500.0 and len(chk.rows) >= 4
    g = chk.governing
    assert g.S_F == min(r.S_F for r in chk.rows) and math.isfinite(g.S_F)
    # the run-up torque 0.376 N·m crosses the collar: τ = 16 T / (π d³) at d = 22 mm would be
    # 0.18 MPa; it is there, and tiny beside the bending
    collar = [r for r in chk.rows if "collar" in r.notch]
    assert collar and all(0 < r.tau_t_MPa < 1.0 for r in collar)
    assert all(r.sigma_b_MPa > 100 * r.tau_t_MPa for r in collar)


def test_a_factor_on_every_load_divides_s_f(driven):
    base = din743_static(driven, "run_up", StrengthOptions())
    names = ["parts", *(ld.name for ld in driven.loads)]
    case = dataclasses.replace(driven.load_cases[0], name="x1.5",
                               factors=tuple((n, 1.5) for n in names))
    v = dataclasses.replace(driven, load_cases=(*driven.load_cases, case))
    up = din743_static(v, "x1.5", StrengthOptions())
    for a, b in zip(base.rows, up.rows, strict=True):
        assert b.S_F == pytest.approx(a.S_F / 1.5, rel=1e-12)


def test_s_f_by_hand_from_the_fk_values():
    n = din743.Notch("shoulder", "shoulder", 17.0, 22.0, 1.0)
    st = din743.Stresses(b_m=300.0, t_m=40.0)
    r = din743.assess(n, st, 1000.0, 695.0, "case_hardening_steel")
    hand = 1.0 / math.hypot(300.0 / r.factors["bending"]["FK"], 40.0 / r.factors["torsion"]["FK"])
    assert r.S_F == pytest.approx(hand, rel=1e-15)


def test_unknown_case_is_named(driven):
    with pytest.raises(InputError, match="run_up"):
        din743_static(driven, "overload", StrengthOptions())
