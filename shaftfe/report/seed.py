"""The seed figures the assessment report compares against, in one place (SPEC.md §1-§4).

Fatigue figures live in ``shaftfe.fatigue.run.SEED`` (the fatigue command prints them too)
and the whole-balancer figures of each variant in its file (``Variant.balance_target``, tagged
``seed``); this module re-exports the former and holds the rest. Every entry names its source.
"""

from __future__ import annotations

from shaftfe.fatigue.run import SEED as FATIGUE
from shaftfe.fatigue.run import SEED_VARIANT as VARIANT

__all__ = ["BALANCING", "CAMPBELL", "CRANK_C_X", "ENGINE", "FATIGUE", "SEED_PARTS", "SOURCES",
           "STATIC", "VARIANT"]

# VARIANT: the variant the seed's static, fatigue and rotor-dynamics studies are of (X2 =
# 57 %; ``fatigue.run.SEED_VARIANT``); for another variant only the balancing and its own
# balance-table rows are compared.
# The parts whose forces the seed states (seed 000 §8.2.2): the gear, counterweight 1 (bolted
# to the gear, F1 = both) and counterweight 2 (Fv2), by their names in the variant files.
SEED_PARTS = ("gear", "counterweight_1", "counterweight_2")

# The engine of the seed's balancing study (geometry/engines/vm450.toml's name): its figures
# (the §5.4 row, crank C) are compared only on this engine.
ENGINE = "VM 450"

# Crank C of the VM 450 (m_C 3.580 kg, γ 2.85 mm): X = 31.1 % (seed 000 §8.2.1). The balancing
# stage of the report uses it with the variant's X2, as the seed's §8.2.2 study did.
CRANK_C_X = 0.311

# Seed 000 §5.4 mode-2 table, parameters A, 6000 rpm, cylinder frame: the row X = 31 %.
BALANCING = {
    "X": 0.31,
    "rpm": 6000.0,
    "min_max_f_N": 2219.6, "min_max_f_at_X2_percent": 57.0,
    "min_rms_f_N": 1548.0, "min_rms_f_at_X2_percent": 50.0,
    "min_max_fy_N": 1605.1,
    "balancer_force_A1_N": 3073.0,      # appendix 1: 0.947 · 0.00822 · 628.3² at 6000 rpm
}

# Seed 000 §8.2.2: Inventor shaft module (beam), variant X2 = 57 %, rigid supports.
STATIC = {
    "force_gear_10000_N": 227.0, "force_cw2_10000_N": 5324.0, "force_cw1_10000_N": 3097.0,
    "force_F1_10000_N": 3324.0, "force_F1_7000_N": 1628.0, "force_cw2_7000_N": 2609.0,
    "reaction_gear_side_10000_N": 2689.0, "reaction_free_side_10000_N": 5921.0,
    "reaction_gear_side_7000_N": 1308.0, "reaction_free_side_7000_N": 2931.0,
    "deflection_gear_10000_mm": 0.063, "deflection_clearance_10000_mm": 0.1,
    "max_reduced_stress_10000_MPa": 263.157, "yield_16420_MPa": 540.0,
    "L10h_3203_7000_h": 283.4,
}

# Seed 000 §8.4: Ansys Rotordynamics, 0 rpm, first 12 damped natural frequencies, and no
# critical speed in 0-8000 rpm.
CAMPBELL = {
    "freq_0rpm_hz": (766.29, 825.79, 884.34, 1014.4, 1609.0, 1932.7, 2225.7, 2362.4, 2798.3,
                     3250.3, 3419.8, 4489.8),
    "rpm_range": (0.0, 8000.0),
    "n_critical": 0,
}

SOURCES = {
    "balancing": "seed 000 §5.4 (mode-2 table, parameters A, 6000 rpm), appendix 1",
    "variant": "seed 000 §8.2.2 table (whole balancer, X2 = 57 %)",
    "static": "seed 000 §8.2.2 (Inventor shaft module, rigid supports) and §8.2.3 (L10h)",
    "fatigue": "seed 000 §8.3 (Ansys Fatigue Tool)",
    "campbell": "seed 000 §8.4 (Ansys Rotordynamics)",
}
