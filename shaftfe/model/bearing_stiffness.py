"""A ball bearing's radial stiffness estimated from its own data, to check the stiffness matrix
a variant states (``bearing_types.*.K_N_per_mm``) against (issue #30: a matrix off by 1000×
passed every check and gave a 254.6 mm deflection).

The estimate uses only what a bearing type in ``geometry/common/bearings.toml`` states: bore d,
outside diameter D, basic dynamic load rating C, rows i and nominal contact angle α.

1. Ball diameter from the cross-section: D_w = 0.3 (D − d) (the proportion of the standard
   radial ball bearing series; a 6203, 17 × 40, has D_w = 6.747 mm against 0.3 · 23 = 6.9).
2. Balls per row from the load rating, ISO 281:2007 eq. (2) (D_w <= 25.4 mm):
   C = b_m f_c (i cos α)^0.7 Z^(2/3) D_w^1.8, with b_m = 1.3 and f_c = 60 (ISO 281 Table 2,
   radial ball bearings, D_w cos α / D_pw ≈ 0.2). A 6203 (C = 9.95 kN) gives Z = 7.9: it has 8.
3. The most loaded ball under a radial load F_r, zero clearance (Stribeck; Harris & Kotzalas,
   Rolling Bearing Analysis, 5th ed., Vol. 1 §7.2): Q_max = 4.37 F_r / (i Z cos α).
4. Its elastic approach for a steel ball on steel raceways (Palmgren, Ball and Roller Bearing
   Engineering, 3rd ed. 1959, point contact): δ = 4.36e-4 Q^(2/3) D_w^(-1/3) mm (Q in N, D_w in
   mm); the rings' radial approach is δ_r = δ / cos α.
5. F_r ∝ δ_r^(3/2), so the tangent stiffness is K = dF_r/dδ_r = 1.5 F_r / δ_r, evaluated at
   F_r = 0.1 C (the upper end of SKF's "normal load" range, 0.05 C < P <= 0.1 C).

The stated matrix passes when both its eigenvalues lie in [K_est / 20, 3 K_est]. Why 20 below:
a real support is softer than the bearing's own contacts: the housing seat (an aluminium
crankcase) and ring fits add a compliance of the same order (× 2–3), a radial clearance shrinks
the load zone (× up to 2), and K ∝ F_r^(1/3) over the loads the shaft sees (0.01 C … 0.1 C:
× 2.2); their product is ~13, rounded up to 20. Why 3 above: nothing makes a support stiffer
than its contacts but a preload (at most × 2 at a light-to-medium preload) and a load above 0.1 C
(0.3 C: × 1.4); 2 × 1.4 = 2.8, rounded to 3. The seed's bushing (35 030 N/mm, eigenvalues
26 274 and 43 786) is 3.1–5.1 × below the estimate of the ZKL 3203 (134 500 N/mm): inside; a
factor 1000 either way is far outside. Only ball bearings are estimated (a roller type: no
check; no roller bearing is used in geometry/).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from shaftfe.errors import InputError

BALL_FRACTION = 0.3          # D_w / (D − d)
B_M, F_C = 1.3, 60.0         # ISO 281 rating factors of a radial ball bearing
STRIBECK = 4.37              # Q_max = 4.37 F_r / (i Z cos α), zero clearance
PALMGREN_BALL = 4.36e-4      # mm N^(-2/3) mm^(1/3): δ = c Q^(2/3) D_w^(-1/3)
LOAD_FRACTION = 0.1          # F_r = 0.1 C
BELOW, ABOVE = 20.0, 3.0     # the accepted band [K_est / BELOW, ABOVE K_est]
KINDS = ("ball", "roller")


@dataclass(frozen=True)
class StiffnessEstimate:
    K_N_per_mm: float        # tangent radial stiffness at F_r
    F_r_N: float
    ball_diameter_mm: float
    balls_per_row: float     # from ISO 281 (not rounded)

    @property
    def band(self) -> tuple[float, float]:
        return self.K_N_per_mm / BELOW, self.K_N_per_mm * ABOVE


def estimate_ball(bore_mm: float, outer_diameter_mm: float, C_N: float, rows: int = 1,
                  contact_angle_deg: float = 0.0) -> StiffnessEstimate:
    """The radial stiffness estimate of a ball bearing (module docstring, steps 1–5)."""
    cos_a = math.cos(math.radians(contact_angle_deg))
    dw = BALL_FRACTION * (outer_diameter_mm - bore_mm)
    z = (C_N / (B_M * F_C * (rows * cos_a) ** 0.7 * dw ** 1.8)) ** 1.5
    fr = LOAD_FRACTION * C_N
    q = STRIBECK * fr / (rows * z * cos_a)
    delta_r = PALMGREN_BALL * q ** (2.0 / 3.0) * dw ** (-1.0 / 3.0) / cos_a
    return StiffnessEstimate(1.5 * fr / delta_r, fr, dw, z)


def radial_eigenvalues(K) -> tuple[float, float]:
    """(smaller, larger) eigenvalue of a symmetric 2×2 radial stiffness [[K11, K12], [K12, K22]]
    (N/mm), in closed form: the one expression the variant's rules and this estimate's check
    read."""
    (k11, k12), (_, k22) = K
    half = math.hypot(0.5 * (k11 - k22), k12)
    return 0.5 * (k11 + k22) - half, 0.5 * (k11 + k22) + half


def check_stiffness(eigenvalues: tuple[float, float], est: StiffnessEstimate, src: str,
                    field: str, got) -> None:
    """InputError unless both eigenvalues of the stated matrix lie in ``est.band``."""
    lo, hi = est.band
    if all(lo <= k <= hi for k in eigenvalues):
        return
    raise InputError(src, field, f"eigenvalues in [{lo:.3g}, {hi:.3g}] N/mm: 1/{BELOW:g} … "
                     f"{ABOVE:g} × the estimate {est.K_N_per_mm:.3g} N/mm from the bearing's "
                     f"own d, D, C (Palmgren/ISO 281, shaftfe.model.bearing_stiffness)",
                     got=f"{got} (eigenvalues {eigenvalues[0]:.4g}, {eigenvalues[1]:.4g})")
