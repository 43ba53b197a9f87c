"""The independent reference for the completed spin softening (issue #31 item 3): the
synchronous unbalance response of x2_57's beam rotor computed by ROSS (petrobras/ross,
``pip install ross-rotordynamics``; made with ROSS 2.3.0 in its own virtual environment, as the
project does not depend on it):

    /path/to/ross-venv/bin/python -m benchmarks.ross_unbalance --write

writes tests/validation/ross_unbalance_x2_57.json, which the test reads (CI needs no ROSS).

The ROSS model is built here from the variant file's data only (none of the project's beam
code): Timoshenko shaft elements (ROSS's, Cowper's shear coefficient, rotary inertia and
gyroscopic terms on) on the file's segments, nodes at the segment ends, the bearing and seat
centres, cut into elements no longer than ``MAX_ELEMENT_MM`` (half the project's 5 mm: the
reference is the finer of the two); the hex socket (a hexagonal hole, which ROSS's annular
elements cannot take) as the bore of equal area (equal mass; its stiffness, at the free end
beyond every load, does not enter the reactions); the bearings as ROSS bearing elements with the
file's 2×2 stiffness (its cross term included, undamped); every part as a disk on its seat
centre's node with its mass at its centroid through a rigid link (``OffsetDisk``: ROSS's disk
matrices transformed by the link, as a disk cannot sit off the shaft line: counterweight 1's
centroid lies beyond the shaft's end) and its unbalance m e at the centroid (force and moment at
the node, ROSS's own unbalance convention, F = m e ω² e^{i(ωt + φ)} (1, −i)). Two disk
inertias: the part's own (I_d, I_p) about its centroid ("own_inertia") and the axisymmetrised
(I_p + m e², I_d + m e²/2: "axisymmetrised"), see ``shaftfe.model.spin``.

ROSS solves (K − ω² M + i ω² G) q = F at ω (``Rotor.run_forced_response``: the full harmonic
response in the stationary frame). Compared: at t = 0 (each unbalance along its file angle, as
the static model's load), the bearings' |K_b Re q| and the bending moment at the collar fillet
(x = 64.5 mm) from the end forces of the shaft element left of it, K_e q + M_e q̈ + ω G_e q̇;
the unsoftened values are the same response at ``QUASI_STATIC_RPM`` scaled by (rpm / that)².
"""

from __future__ import annotations

import json
import math
import sys
from itertools import pairwise
from pathlib import Path

import numpy as np

MAX_ELEMENT_MM = 2.5
QUASI_STATIC_RPM = 10.0          # (10 / 7000)² = 2e-6: the inertia's share, far below 1e-4
RPMS = (7000.0, 10000.0)
COLLAR_X_MM = 64.5
OUT = Path(__file__).resolve().parent.parent / "tests/validation/ross_unbalance_x2_57.json"


def _nodes(v) -> np.ndarray:
    segs = v.segments
    x0, x1 = segs[0].x_start_mm, segs[-1].x_end_mm
    key = {round(s.x_start_mm, 9) for s in segs} | {x1}
    key |= {b.x_center_mm for b in v.bearings}
    key |= {0.5 * (a.seat_x_start_mm + a.seat_x_end_mm) for a in v.attachments}
    key.add(x1 - v.hex_socket.depth_mm if v.hex_socket.end == "right"
            else x0 + v.hex_socket.depth_mm)
    key = np.array(sorted(key))
    out = [key[0]]
    for a, b in pairwise(key):
        n = max(1, math.ceil((b - a) / MAX_ELEMENT_MM - 1e-9))
        out += list(np.linspace(a, b, n + 1)[1:])
    return np.array(out)


def build(v, part_model: str):
    import ross as rs

    class OffsetDisk(rs.DiskElement):
        """A ROSS disk whose centroid sits ``d`` (m) along the axis from its node, rigidly:
        x_c = x + d β, y_c = y − d α (ROSS dofs x, y, z, α, β, θ)."""

        def __init__(self, n, m, Id, Ip, d, tag=None):
            super().__init__(n=n, m=m, Id=Id, Ip=Ip, tag=tag)
            self.d = d

        def _T(self):
            T = np.eye(6)
            T[0, 4] = self.d
            T[1, 3] = -self.d
            return T

        def M(self):
            T = self._T()
            return T.T @ super().M() @ T

        def G(self):
            T = self._T()
            return T.T @ super().G() @ T

    mat = v.material
    steel = rs.Material(name="shaft", rho=mat.density_t_mm3 * 1e12, E=mat.E_MPa * 1e6,
                        Poisson=mat.nu)
    x = _nodes(v)
    hs = v.hex_socket
    hx0 = v.segments[-1].x_end_mm - hs.depth_mm if hs.end == "right" else v.segments[0].x_start_mm
    hx1 = hx0 + hs.depth_mm
    bore = math.sqrt(4.0 * (math.sqrt(3) / 2 * hs.across_flats_mm ** 2) / math.pi)
    shaft = []
    for a, b in pairwise(x):
        xm = 0.5 * (a + b)
        seg = next(s for s in v.segments if s.x_start_mm <= xm <= s.x_start_mm + s.length_mm)
        idl = bore if hx0 <= xm <= hx1 else 0.0
        shaft.append(rs.ShaftElement(L=(b - a) * 1e-3, idl=idl * 1e-3,
                                     odl=seg.diameter_mm * 1e-3, material=steel,
                                     shear_effects=True, rotary_inertia=True, gyroscopic=True,
                                     shear_method_calc="cowper"))

    def node(xq):
        i = int(np.argmin(np.abs(x - xq)))
        assert abs(x[i] - xq) < 1e-9, xq
        return i

    disks, unb = [], []
    for a in v.attachments:
        if a.mass_kg <= 0:
            continue
        xs = 0.5 * (a.seat_x_start_mm + a.seat_x_end_mm)
        m, e = a.mass_kg, a.eccentricity_mm
        ip, id_ = a.polar_inertia_kg_mm2, a.diametral_inertia_kg_mm2
        if part_model == "axisymmetrised":
            ip, id_ = ip + m * e * e, id_ + 0.5 * m * e * e
        d = (a.x_centroid_mm - xs) * 1e-3
        disks.append(OffsetDisk(node(xs), m, id_ * 1e-6, ip * 1e-6, d, tag=a.name))
        unb.append((node(xs), m * e * 1e-3, math.radians(a.angle_deg), d))
    bearings = []
    for b in v.bearings:
        k = np.asarray(b.K_N_per_mm, dtype=float) * 1e3
        bearings.append(rs.BearingElement(n=node(b.x_center_mm), kxx=k[0, 0], kyy=k[1, 1],
                                          kxy=k[0, 1], kyx=k[1, 0], cxx=0.0, kzz=1e9 if b.axial
                                          else 0.0, tag=b.name))
    return rs.Rotor(shaft, disks, bearings), x, unb, node


def response(rotor, x, unb, node, v, rpm: float) -> dict:
    """ROSS's response at ``rpm`` at t = 0: the bearings' |reaction| (N), the collar moment
    (N·mm)."""
    w = rpm * 2.0 * math.pi / 60.0
    nd = rotor.number_dof
    F = np.zeros((rotor.ndof, 1), dtype=complex)
    for n, me, ph, d in unb:
        fc = w * w * me * np.exp(1j * ph) * np.array([1.0, -1j])   # ROSS's unbalance (x, y)
        F[nd * n + 0, 0] += fc[0]
        F[nd * n + 1, 0] += fc[1]
        F[nd * n + 3, 0] += -d * fc[1]                              # Tᵀ: moments of the link
        F[nd * n + 4, 0] += d * fc[0]
    q = rotor.run_forced_response(force=F, speed_range=np.array([w])).forced_resp[:, 0]
    out = {}
    for b in v.bearings:
        i = node(b.x_center_mm)
        k = np.asarray(b.K_N_per_mm, dtype=float) * 1e3
        out[b.name] = float(np.linalg.norm(k @ q[nd * i:nd * i + 2].real))
    e = node(COLLAR_X_MM) - 1
    el = rotor.shaft_elements[e]
    idx = nd * e + np.arange(2 * nd)
    qe = q[idx]
    f = el.K() @ qe.real - w * w * el.M() @ qe.real - w * w * el.G() @ qe.imag
    out["collar_moment_Nmm"] = float(math.hypot(f[nd + 3], f[nd + 4]) * 1e3)
    return out


def run() -> dict:
    import ross

    from shaftfe.model.loader import load_variant
    v = load_variant("x2_57")
    res = {"source": f"ROSS {ross.__version__} (petrobras/ross), benchmarks/ross_unbalance.py",
           "variant": "x2_57", "max_element_mm": MAX_ELEMENT_MM, "collar_x_mm": COLLAR_X_MM,
           "quasi_static_rpm": QUASI_STATIC_RPM, "models": {}}
    for pm in ("own_inertia", "axisymmetrised"):
        rotor, x, unb, node = build(v, pm)
        qs = response(rotor, x, unb, node, v, QUASI_STATIC_RPM)
        res["models"][pm] = {}
        for rpm in RPMS:
            r = response(rotor, x, unb, node, v, rpm)
            s = (rpm / QUASI_STATIC_RPM) ** 2
            res["models"][pm][f"{rpm:g}"] = {
                k: {"response": r[k], "unsoftened": qs[k] * s,
                    "increment_pct": 100.0 * (r[k] / (qs[k] * s) - 1.0)} for k in r}
    return res


if __name__ == "__main__":
    out = run()
    text = json.dumps(out, indent=1, sort_keys=True)
    if "--write" in sys.argv:
        OUT.write_text(text + "\n")
    print(text)
