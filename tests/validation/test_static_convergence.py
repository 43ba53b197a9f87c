"""Mesh convergence of the peak fillet stress next to a chamfered bearing ring (issue 4).

Small stepped shaft Ø8 / Ø14 / Ø8 with r = 2 mm shoulder fillets, symmetric about x = 23;
each Ø8 end carries a bearing whose ring (12 mm wide) abuts the shoulder. The ring has a
2.9 mm bore chamfer, so its contact band — the ``bearing:<name>`` coupling face — stops 0.9 mm
short of the fillet's tangent line: the coupling edge (a traction jump, singular by
construction) is separated from the fillet by straight seat. One part on the Ø14 middle is
spun at 10 000 rpm.

Reference: Richardson extrapolation (the module's own ``static.estimate_error``). The test
asserts what issue 4 asks of it: a mesh refinement does not move the peak fillet stress by more
than the estimate said. Three test levels differ only in the fillet element size
(k_fillet 0.45, 0.32, 0.225 × ρ: ratio √2 each; 24k / 48k / 112k dofs, ~1 min). The estimate
is made from conv0 and conv1 (assumed order 2); the check is the third, finer mesh conv2,
whose peak must move from conv1 by no more than the estimated error of conv1. For order-2
convergence the move is 1/2 of the estimate; an order below 1 or a non-monotone peak fails.

Measured (this test): fillet a 166.14 / 169.93 / 174.23 MPa, fillet b 165.65 / 171.74 /
171.71 MPa (conv0 / conv1 / conv2); mirror mean 165.90 / 170.84 / 172.97, estimated error of
conv1 4.94 MPa, move 2.14 MPa. With coarser levels (k_fillet 0.9 / 0.64 / 0.45, the coarse and
default levels' fillet size) the peak was NOT in the asymptotic range (increments 5.9 then
9.7 MPa on a 1 mm fillet): the estimate is only trustworthy from k_fillet ≈ 0.45 down.
"""

from __future__ import annotations

import dataclasses

import pytest

from shaftfe.model.examples import STEEL
from shaftfe.model.variant import Attachment, Bearing, Segment, Variant
from shaftfe.solid.levels import MeshLevel

K = ((35_030.0, 0.0), (0.0, 35_030.0))
RPM = 10_000.0
# three test levels that differ only in the fillet element size (ratio √2 each)
TEST_LEVELS = [MeshLevel(f"conv{i}", k_global=0.7, k_fillet=kf, k_sharp=5.0, grad=3.0)
               for i, kf in enumerate((0.45, 0.45 / 2 ** 0.5, 0.225))]


def shaft() -> Variant:
    segs = (Segment("a", 0.0, 16.0, 8.0, 2.0), Segment("b", 16.0, 14.0, 14.0, 2.0),
            Segment("c", 30.0, 16.0, 8.0, 0.0))
    brg = (Bearing("L", "x", 10.0, 12.0, 14_400.0, 10_000.0, K, axial=True, chamfer_mm=2.9,
                   r_s_min_mm=0.6),
           Bearing("R", "x", 36.0, 12.0, 14_400.0, 10_000.0, K, chamfer_mm=2.9, r_s_min_mm=0.6))
    att = (Attachment("w", 19.0, 27.0, 0.12, 20.0, 23.0, angle_deg=0.0),)
    return Variant("stepped_small", "stepped shaft, chamfered rings", segs, brg, att, STEEL, 0.0)


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from shaftfe import static
    cache = tmp_path_factory.mktemp("conv")
    v = shaft()
    opts = static.StaticOptions(level=TEST_LEVELS[1])
    mid = static.solve_static(v, [RPM], opts, cache_dir=cache, beam=False)
    est = static.estimate_error(mid, v, opts, cache, other_level=TEST_LEVELS[0])
    fine = static.solve_static(v, [RPM], dataclasses.replace(opts, level=TEST_LEVELS[2]),
                               cache_dir=cache, beam=False)
    return mid, est, fine


def _peak(res, region):
    return next(p for p in res.case(RPM).peaks if p.region == region)


def test_coupling_face_is_the_contact_band(runs):
    """The coupling face is the ring minus its chamfers: area 2π·4·(12 − 2·2.9) = 155.82 mm²
    (P2 facet quadrature, 0.5 %), and no node of a fillet is excluded by the singular-point
    rule (the coupling edges are 0.9 mm of straight seat away from the fillets)."""
    import math

    from skfem import ElementTetP2, FacetBasis, Functional
    fine = runs[2]
    m = fine.mesh.mesh
    one = Functional(lambda w: 1.0 + 0.0 * w.x[0])
    for g in ("bearing:L", "bearing:R"):
        a = float(one.assemble(FacetBasis(m, ElementTetP2(), facets=m.boundaries[g])))
        # mesh: P2 facets on a curved band (0.5 %, as tests/test_mesh.py's group areas)
        assert a == pytest.approx(2 * math.pi * 4.0 * (12.0 - 2 * 2.9), rel=5e-3), g
    for r in ("fillet:a", "fillet:b"):
        assert _peak(fine, r).n_excluded == 0, r


def test_refinement_stays_within_the_error_estimate(runs):
    """|σ(conv2) − σ(conv1)| ≤ the Richardson error estimate of σ(conv1) made from conv0 and
    conv1, and the three values are monotone (the peak converges, it does not drift).

    σ is the mean of the two mirror-image fillet peaks (the shaft and its load are symmetric
    about x = 23): an unstructured mesh is not symmetric, and each fillet's own peak carries a
    random mesh part of ~1-2 % at these sizes (measured 174.2 vs 171.7 MPa at conv2), which the
    mean halves; that asymmetry is asserted below 2.5 % at conv2."""
    mid, est, fine = runs
    e = [est["cases"][0]["region_peaks"][r] for r in ("fillet:a", "fillet:b")]
    q_c = 0.5 * (e[0]["coarse"] + e[1]["coarse"])
    q_m = 0.5 * (e[0]["fine"] + e[1]["fine"])
    q_f = 0.5 * sum(_peak(fine, r).von_mises_MPa for r in ("fillet:a", "fillet:b"))
    # exact: the same solution reported twice (approx's default rel 1e-6)
    assert q_m == pytest.approx(0.5 * sum(_peak(mid, r).von_mises_MPa
                                          for r in ("fillet:a", "fillet:b")))
    assert est["levels"] == ["conv1", "conv0"]
    err = abs(q_m - q_c) / (est["ratio_stress"] ** est["order_stress"] - 1.0)
    msg = (f"mirror-mean fillet peak: conv0 {q_c:.2f}, conv1 {q_m:.2f}, conv2 {q_f:.2f} MPa; "
           f"estimated error of conv1 {err:.3f} MPa, move {abs(q_f - q_m):.3f}")
    assert abs(q_f - q_m) <= err, msg     # the derived bound: Richardson estimate of conv1
    assert (q_f - q_m) * (q_m - q_c) > 0, msg
    a, b = (_peak(fine, r).von_mises_MPa for r in ("fillet:a", "fillet:b"))
    # mesh asymmetry of an unstructured mesh: ~1-2 % (measured 1.4 %), bound 2.5 % (docstring)
    assert abs(a - b) <= 0.025 * q_f, (a, b)
