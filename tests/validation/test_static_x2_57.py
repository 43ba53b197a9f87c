"""Variant x2_57 at 10 000 rpm on rigid supports vs the seed's Inventor shaft-module results.

Reference: seed 000 §8.2.2 (SPEC §2): radial reactions 2689 N (gear side) and 5921 N (other
side) at 10 000 rpm with the seed's load case (gear, counterweights 1 and 2). The geometry is
reconstructed (geometry/RECONSTRUCTION.md), so the reactions are asserted within 3 %.

Measured (coarse level, this test): 2678.1 N / 5969.5 N (−0.4 % / +0.8 %); the beam model
with the same loads gives the same reactions (statics).

For the report (not asserted: the seed gives them from a beam model with an unknown Kt), seed
load case, rigid supports, default level (91k dofs), bearings coupled on their contact bands
(ring minus the 2 mm ISO 582 chamfer at each end): 0.069 mm under the gear (seed 0.063 mm),
0.114 mm at the clearance station (seed 0.1 mm); peak von Mises 449.8 MPa on the collar fillet
(x = 64.9), the same filtered and unfiltered, bearing-seat-gear fillet 408.5 MPa; with the
hot-spot default level of issue 4 (≈ 0.5 % from the converged peak on the spring-supported
case, reports/benchmarks/static.md) the collar fillet gives 489.4 MPa. The nominal
bending stress there is 32 M/(π d³) = 224 MPa (M = 107.9 N·m), so Kt_FE ≈ 2.2; the seed's
263 MPa cannot include a shoulder Kt of that size. Before the chamfer the coupling edge sat on
the fillet's tangent line and the excluded element layer hid the fillet (259.6 MPa filtered,
not converged: 246 → 474 MPa default → fine).
"""

from __future__ import annotations

import pytest

RPM = 10_000.0


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    from shaftfe.model.loader import load_variant
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import solve_static
    v = load_variant("x2_57")           # a loader regression fails here, it is not skipped
    return solve_static(v, [RPM], StaticOptions(level="coarse", rigid_supports=True,
                                                seed_load_case=True),
                        cache_dir=tmp_path_factory.mktemp("vx"), beam=False)


def test_reactions_match_seed(result):
    """Radial reactions within 3 % of 2689 N / 5921 N (seed 000 §8.2.2)."""
    got = {b.name: b.F_radial_N for b in result.case(RPM).bearings}
    # reconstructed geometry (RECONSTRUCTION.md): 3 %; measured −0.4 % / +0.8 %
    assert got["gear_side"] == pytest.approx(2689.0, rel=0.03)
    assert got["free_side"] == pytest.approx(5921.0, rel=0.03)
    # statics: the solver's residual contract (static.RESIDUAL_TOL = 1e-8)
    assert result.case(RPM).equilibrium_residual <= 1e-8
