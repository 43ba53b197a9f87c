"""One typed description of every geometric feature of the shaft (issue #32).

``features(plan)`` turns the solid plan (``solid.plan.Solid``) into a tuple of ``Feature``: what
it is (``kind``), where (its axial extent ``x_mm`` and the segment), its size, whether it is a
body of revolution (``round``: the axisymmetric model holds it exactly) and its zone of
influence (``zone_mm``). The feature's ``region`` is the name of its faces in both meshes (the
3D mesh groups of ``solid.occ`` and the meridian groups of ``axisymmetric.mesh``) and the key
of its peak in every result; consumers choose features by ``kind`` and the flags below, never
by parsing that name.

Zone of influence (Saint-Venant: a self-equilibrated disturbance of a bar decays over about one
diameter): a cut (keyway, hex socket) or a notch widens its axial extent by the local diameter
on each side; a seat or an end has no zone of its own (its loads are the global model's).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from shaftfe.solid.plan import Solid

# the kinds, in the order they are listed; NOTCH: the kinds a fatigue check assesses (a stress
# raiser of the outline), CUT: the kinds that are not bodies of revolution
KINDS = ("fillet", "shoulder", "keyway", "hex_socket", "seat", "bearing_seat", "end")
NOTCH_KINDS = frozenset({"fillet", "keyway"})
CUT_KINDS = frozenset({"keyway", "hex_socket"})


@dataclass(frozen=True)
class Feature:
    kind: str                          # one of KINDS
    region: str                        # its faces' group name and its peak's key
    segment: str                       # the segment it belongs to ("" for an end)
    x_mm: tuple[float, float]          # axial extent
    zone_mm: tuple[float, float]       # zone of influence (= x_mm where it has none)
    size: tuple[tuple[str, float], ...] = ()   # (name, mm) e.g. ("rho", 0.6), ("width", 5)
    round: bool = True                 # a body of revolution (the axisymmetric model holds it)
    angle_deg: float | None = None     # a cut's direction (0 = +y); a split seat's load line

    @property
    def notch(self) -> bool:
        """A stress raiser that the fatigue methods assess (fillets, keyways)."""
        return self.kind in NOTCH_KINDS

    @property
    def cut(self) -> bool:
        """Not a body of revolution: the zoned solve meshes it in a 3D submodel."""
        return not self.round

    def dim(self, name: str) -> float:
        return dict(self.size)[name]

    def holds(self, x: float, tol: float = 1e-9) -> bool:
        """Is the axial station ``x`` inside the feature's extent?"""
        return self.x_mm[0] - tol <= x <= self.x_mm[1] + tol

    def in_zone(self, x: float, tol: float = 1e-9) -> bool:
        return self.zone_mm[0] - tol <= x <= self.zone_mm[1] + tol


def _segment_radius(sol: Solid, name: str) -> float:
    return sol.radii[sol.segment_names.index(name)]


def features(sol: Solid) -> tuple[Feature, ...]:
    """Every feature of the plan ``sol``: fillets, shoulder annuli, keyways, the hex socket,
    the seats (parts' and bearings'), and the two ends."""
    out: list[Feature] = []
    for f in sol.fillets:
        xa, xb = (f.x_shoulder - f.rho, f.x_shoulder) if f.side < 0 else \
            (f.x_shoulder, f.x_shoulder + f.rho)
        out.append(Feature("fillet", f"fillet:{f.segment}", f.segment, (xa, xb), (xa, xb),
                           (("rho", f.rho), ("r_small", f.r_small), ("r_large", f.r_large))))
    for s in sol.shoulders:
        out.append(Feature("shoulder", f"shoulder:{s.segment}", s.segment, (s.x, s.x),
                           (s.x, s.x), (("r_in", s.r_in), ("r_out", s.r_out))))
    for k in sol.slots:
        d = 2.0 * k.r
        out.append(Feature("keyway", f"keyway:{k.segment}:{k.index}", k.segment, (k.x0, k.x1),
                           (k.x0 - d, k.x1 + d),
                           (("width", k.width), ("depth", k.depth), ("length", k.length),
                            ("r", k.r)), round=False, angle_deg=math.degrees(k.angle)))
    if sol.hex is not None:
        h = sol.hex
        seg = sol.segment_names[0 if h.end == "left" else -1]
        d = 2.0 * _segment_radius(sol, seg)
        x0, x1 = ((sol.x_left, sol.x_left + h.depth) if h.end == "left"
                  else (sol.x_right - h.depth, sol.x_right))
        out.append(Feature("hex_socket", "hex_socket", seg, (x0, x1), (x0 - d, x1 + d),
                           (("across_flats", h.across_flats), ("depth", h.depth)),
                           round=False))
    seen: set[str] = set()
    for st in sol.seats:
        bearing = st.name.startswith("bearing:")
        region = "seat:" + (st.name if bearing else st.name.split(":", 1)[1])
        if region in seen:
            continue
        seen.add(region)
        out.append(Feature("bearing_seat" if bearing else "seat", region, st.part.segment,
                           (st.x0, st.x1), (st.x0, st.x1), (("r", st.part.r),),
                           angle_deg=None if st.angle is None else math.degrees(st.angle)))
    out.append(Feature("end", "end:left", sol.segment_names[0], (sol.x_left, sol.x_left),
                       (sol.x_left, sol.x_left)))
    out.append(Feature("end", "end:right", sol.segment_names[-1], (sol.x_right, sol.x_right),
                       (sol.x_right, sol.x_right)))
    return tuple(out)


def cuts(sol: Solid) -> tuple[Feature, ...]:
    """The features that are not bodies of revolution (keyways, the hex socket)."""
    return tuple(f for f in features(sol) if f.cut)


def by_region(feats) -> dict[str, Feature]:
    return {f.region: f for f in feats}
