"""Shoulder-fillet peak stress of a stepped shaft in bending vs the Kt fits of ``shaftfe.beam.scf``.

Shaft Ø17 / Ø22 / Ø17 with r = 1 mm fillets (D/d = 1.294, r/d = 0.059, h/r = 2.5: the
balancer's own bearing-seat shoulders), on two bearings, loaded in the middle: each fillet sits
in a bending field with M/V ≈ 29.5 mm ≈ 1.7 d (shear stress ~ 1/10 of the bending stress).

Reference: Kt for bending of a stepped round shaft, Roark 7th ed. Table 17.1 case 17b and
Pilkey, Peterson's SCF 3rd ed. Chart 3.10 (``shaftfe.beam.scf``), Kt = σ_max / σ_nom with
σ_nom = 32 M / (π d³) at the section of the peak. The fit's stated accuracy (scf.py): the two
fits of the same photoelastic data agree within 2.5 %, and the charts are reported to lie several
percent, in places more than 20 %, BELOW converged FE for shoulder fillets (Tipton et al.,
Machine Design, Jan 2009; FINDINGS pitfall 5). The test therefore asserts the band
[0.975 × min fit, 1.25 × max fit] and records the measured ratio.

Measured (max principal stress, left fillet; the first version of benchmarks/bench_static.py,
before it moved to x2_57): P2 coarse / default /
fine = 25k / 30k / 168k dofs: Kt_FE = 2.090 / 2.101 / 2.168 (custom levels with k_fillet 0.7 and
0.5 gave 2.207 and 2.120: not monotonic, ±2-3 %); the right fillet 2.17-2.18. Against Roark
1.943 and Peterson 1.953 the FE lies 8-14 % above the fits, as pitfall 5 warned (2.13-2.35
there). The recovery itself is verified against Goodier's exact cavity solution to 0.5 %
(test_static_recovery_goodier.py), so the gap is the fits', as Tipton et al. report. P1 tets
are useless here (Kt 1.13-1.62). With the hot-spot levels of issue 4 (refinement of the
fillets' load-plane sectors, shaftfe.solid.mesh): coarse 27k dofs Kt_FE 2.174 / 2.158, default 80k
dofs 2.197 / 2.205 (left / right fillet: the mirror pair now agrees to 0.4 %, was 2.8 %).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from shaftfe.model.examples import STEEL
from shaftfe.model.variant import Attachment, Bearing, Segment, Variant

K = ((35_030.0, 0.0), (0.0, 35_030.0))
RPM = 10_000.0


def stepped() -> Variant:
    segs = (Segment("a", 0.0, 40.0, 17.0, 1.0), Segment("b", 40.0, 40.0, 22.0, 1.0),
            Segment("c", 80.0, 40.0, 17.0, 0.0))
    brg = (Bearing("L", "x", 10.0, 10.0, 14_400.0, 10_000.0, K, axial=True),
           Bearing("R", "x", 110.0, 10.0, 14_400.0, 10_000.0, K))
    att = (Attachment("w", 55.0, 65.0, 0.24, 20.0, 60.0, angle_deg=0.0),)
    return Variant("stepped", "stepped shaft, r = 1 fillets", segs, brg, att, STEEL, 0.0)


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    from shaftfe.static.model import StaticOptions
    from shaftfe.static.solve import solve_static
    return solve_static(stepped(), [RPM], StaticOptions(level="default"),
                        cache_dir=tmp_path_factory.mktemp("vf"), beam=False)


def _kt_fe(result, group: str) -> float:
    from shaftfe.fe import assembly as fem
    from shaftfe.fe.recovery import principal
    m = result.mesh.mesh
    s1 = principal(result.stress_ref)[0]
    nodes = fem.face_nodes(m, m.boundaries[group])
    i = nodes[int(np.argmax(s1[nodes]))]
    x = m.doflocs[0, i]
    F = stepped().attachments[0].force_N(RPM)
    arm = (x - 10.0) if x < 60.0 else (110.0 - x)          # M = (F/2)·distance to the bearing
    sigma_nom = 32.0 * (0.5 * F * arm) / (math.pi * 17.0**3)
    return float(s1[i] / sigma_nom)


@pytest.mark.parametrize("group", ["fillet:a", "fillet:b"])
def test_fillet_peak_within_kt_fit_band(result, group):
    """FE Kt within [0.975 × min(Roark, Peterson), 1.25 × max(...)] (see module docstring)."""
    from shaftfe.beam.scf import kt_shoulder
    fits = [kt_shoulder(22.0, 17.0, 1.0, f).kt for f in ("roark", "peterson")]
    kt = _kt_fe(result, group)
    # fits' own spread 2.5 % below; up to +20 % and more for converged FE above (Tipton et al.;
    # module docstring; measured +8 … +14 %)
    assert 0.975 * min(fits) <= kt <= 1.25 * max(fits), (kt, fits)


def test_mirror_fillets_agree(result):
    """The two fillets are mirror images in the same bending field: equal Kt up to the mesh
    (measured 2.8 % apart with the old default level, 0.4 % with the hot-spot default)."""
    # mesh: measured 0.4 % apart at the hot-spot default level (2.8 % with the old one)
    assert _kt_fe(result, "fillet:a") == pytest.approx(_kt_fe(result, "fillet:b"), rel=0.05)


def test_fillet_is_the_reported_region_peak(result):
    """The region table reports the fillet peaks: each fillet's filtered von Mises peak lies on
    the fillet arc (x within 1 mm of the shoulder) and is not cut by the exclusion rule (the
    load and bearing patches are far from the fillets)."""
    c = result.case(RPM)
    for p in c.peaks:
        if p.region in ("fillet:a", "fillet:b"):
            xs = 40.0 if p.region == "fillet:a" else 80.0
            assert abs(p.xyz_mm[0] - xs) <= 1.0      # geometric: the 1 mm fillet radius
            assert p.von_mises_MPa == p.von_mises_unfiltered_MPa
