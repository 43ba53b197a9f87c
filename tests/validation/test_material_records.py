"""One record per material and heat treatment (issue #30 §5: strength.toml's 14220 said R_m 1000 /
R_p 695 MPa while materials.toml and sn_curves.toml said 740 / 490).

Source of the values: geometry/common/materials.toml's notes (DIN 743-3:2012 material table,
16MnCr5 blank-hardened at d_B = 16 mm: σ_B 1000, σ_S 695 MPa; EN 10083-2 C45 +QT, d ≤ 16 mm:
R_m 700, R_e 490 MPa). The checks are identities between the consumers (exact: the same float
read once), not numerical results.
"""

from __future__ import annotations

import dataclasses
import tomllib

import pytest

from shaftfe.errors import InputError
from shaftfe.fatigue import fkm
from shaftfe.fatigue.cards import CARDS_FILE, load_card
from shaftfe.fatigue.sn import load_material
from shaftfe.fatigue.strength import StrengthOptions, strength_card
from shaftfe.model.loader import load_variant
from shaftfe.model.parse import material_record


def test_every_consumer_reads_the_one_record_of_14220():
    v = load_variant("x2_57")
    rec = v.material                                  # the drawing's (shaft.material)
    card = strength_card(v, StrengthOptions())        # FKM and DIN 743
    sn = load_material("14220")                       # the seed method's S-N card
    assert rec.name == card.name == "14220"
    assert (rec.ultimate_MPa, rec.yield_MPa) == (card.rm_n_MPa, card.rp_n_MPa) \
        == (sn.ultimate_MPa, sn.yield_MPa) == (1000.0, 695.0)
    assert rec.strength_reference_diameter_mm == 16.0          # DIN 743-3's d_B
    assert (card.case_hardness_HRC, card.case_depth_mm) == (58.0, 0.4)
    # the S-N knee is FKM's material fatigue strength of the same R_m: f_W,σ R_m
    f_w = fkm.GROUPS["case_hardening_steel"].f_w_sigma
    assert sn.sn.amplitude_at(1e6) == pytest.approx(f_w * 1000.0, rel=1e-12)  # round-off
    # no second copy of a strength: strength.toml keeps the surfaces only
    assert "cards" not in tomllib.loads(CARDS_FILE.read_text(encoding="utf-8"))


def test_the_drawings_material_decides_and_card_overrides():
    v = load_variant("x2_57")
    c45 = dataclasses.replace(v, material=material_record("12050"))
    card = strength_card(c45, StrengthOptions())
    assert (card.name, card.group, card.rm_n_MPa, card.rp_n_MPa) == ("12050", "qt_steel",
                                                                     700.0, 490.0)
    assert not card.case_hardened
    # --card names a record explicitly, whatever the shaft is made of
    assert strength_card(c45, StrengthOptions(card="14220")) == load_card("14220")


def test_a_record_without_a_standard_group_is_refused():
    v = dataclasses.replace(load_variant("x2_57"), material=material_record("11600"))
    with pytest.raises(InputError, match=r"materials\.11600\.group"):
        strength_card(v, StrengthOptions())


def test_an_sn_card_naming_a_record_may_not_repeat_its_strengths(tmp_path):
    p = tmp_path / "sn.toml"
    p.write_text('[sn_curves.x]\nmaterial = "14220"\nultimate_MPa = 740.0\n'
                 'knee_cycles = 1e6\nslope_k = 5.0\n', encoding="utf-8")
    with pytest.raises(InputError, match=r"sn_curves\.x\.ultimate_MPa"):
        load_material("x", p)


def test_the_report_leaves_the_standards_out_with_a_warning_for_such_a_shaft():
    """A shaft of a record the standards cannot assess (no group): the report's "strength by
    standard" is left out with a visible warning (before: judged as 14220 whatever the shaft)."""
    from shaftfe.report.assemble import _strength
    from shaftfe.report.options import ReportOptions
    from shaftfe.util.notices import ShaftfeWarning
    v = dataclasses.replace(load_variant("x2_57"), material=material_record("11600"))
    with pytest.warns(ShaftfeWarning, match=r"strength by standard left out.*materials\.11600"):
        assert _strength(ReportOptions(), v, None, None) == {}
