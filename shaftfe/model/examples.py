"""Small synthetic shafts for tests, benchmarks and notebooks (not the seed's balancer shaft).

``four_step_shaft``: Ø15 | Ø17 (fillet, 5×3×14 keyway) | Ø22 (fillet, bearing) | Ø17 (seat,
hex socket in the right end), 100 mm long, steel; a counterweight 'cw' on the keyed Ø17 and a
'hub' on the last Ø17; optionally a U groove in the Ø22. With it, it has every feature the
mesher names (fillets, shoulders, a groove, keyway, hex socket, split load seats, a bearing
seat) at a size that meshes in seconds.
"""

from __future__ import annotations

from shaftfe.model.grooves import din509_groove
from shaftfe.model.loads import Load
from shaftfe.model.variant import (
    Attachment,
    Bearing,
    CrossHole,
    Groove,
    HexSocket,
    Keyway,
    Material,
    Segment,
    Variant,
)

STEEL = Material("steel", 210_000.0, 0.3, 7.85e-9, 540.0, 800.0)
K_SEED = ((35_030.0, 8_756.0), (8_756.0, 35_030.0))     # seed 000 §8.3 bearing stiffness, N/mm


def four_step_shaft(*, name: str = "four_step", description: str = "synthetic four-step shaft",
                    fillet_b: float = 1.0, fillet_c: float = 1.0, keyway: bool = True,
                    keyway_x: float = 35.0, keyway_angle: float = 0.0, hex_socket: bool = True,
                    hex_end: str = "right", cw_angle: float = 30.0, hub_angle: float = 0.0,
                    washer: bool = False, thread_end: bool = False, groove: bool = False,
                    cross_hole: bool = False, chamfers: bool = False, undercut: str = "",
                    taper: bool = False, keyway_radius: float = 0.0,
                    bearing: tuple[float, float] = (60.0, 8.0),
                    cw_seat: tuple[float, float] = (25.0, 45.0),
                    hub_seat: tuple[float, float] = (75.0, 85.0)) -> Variant:
    """The four-step test shaft; ``washer`` adds a part sharing the hub's seat, ``thread_end``
    marks the Ø15 end as a thread (informational), ``groove`` turns a U groove (2 wide,
    0.8 deep, corner radius 0.8, a 0.4 mm flat bottom) into the Ø22 at x = 53 mm, beside the
    bearing, ``cross_hole``
    drills a Ø2 hole through the last Ø17 at x = 72.5 mm (at 90°), ``chamfers`` breaks the
    left end's edge (0.5 mm) and the Ø22's edge at its step down (0.5 mm), ``undercut``
    ("din509_e" | "din509_f") puts a DIN 509 undercut at the Ø17's right end, beside the
    Ø22's face, in place of the fillet there, ``taper`` makes the Ø15 a cone from Ø15 to
    Ø17 (no step at x = 20; its end chamfer off), ``keyway_radius`` rounds the keyway's
    bottom edges (r1)."""
    kw = (Keyway(5.0, 3.0, 14.0, keyway_x, keyway_angle, keyway_radius),) if keyway else ()
    segs = (
        Segment("a", 0.0, 20.0, 15.0, 0.0, kind="thread" if thread_end else "plain",
                chamfer_left_mm=0.5 if chamfers and not taper else 0.0,
                diameter_right_mm=17.0 if taper else 0.0),
        Segment("b", 20.0, 30.0, 17.0, 0.0 if undercut else fillet_b, keyways=kw,
                grooves=(din509_groove(undercut, 17.0, "right", (20.0, 50.0)),)
                if undercut else ()),
        Segment("c", 50.0, 20.0, 22.0, fillet_c,
                grooves=(Groove("u", 53.0, 2.0, 0.8, 0.8),) if groove else (),
                chamfer_right_mm=0.5 if chamfers else 0.0),
        Segment("d", 70.0, 30.0, 17.0, 0.0,
                cross_holes=(CrossHole(2.0, 72.5, 90.0),) if cross_hole else ()),
    )
    brg = (Bearing("mid", "ZKL 3203", bearing[0], bearing[1], 14_400.0, 10_000.0, K_SEED),)
    att = [
        Attachment("cw", cw_seat[0], cw_seat[1], 0.24, 20.23, 35.0, angle_deg=cw_angle),
        Attachment("hub", hub_seat[0], hub_seat[1], 0.15, 1.36, 80.0, angle_deg=hub_angle),
    ]
    if washer:
        att.append(Attachment("washer", hub_seat[0], hub_seat[1], 0.01, 0.5, 80.0,
                              angle_deg=hub_angle))
    hx = HexSocket(hex_end, 8.0, 10.0) if hex_socket else None
    return Variant(name, description, segs, brg, tuple(att), STEEL, 0.0, hex_socket=hx)


KEYED_BAR_F_N = 1000.0        # four-point bending: a force at x = 40 and x = 120 mm
KEYED_BAR_T_NMM = 50_000.0    # torsion: +T at x = 40, −T at x = 120


def keyed_bar(kind: str, bottom_radius_mm: float = 0.0, diameter_mm: float = 20.0) -> Variant:
    """Ø20 × 160 mm bar, a 6 × 3.5 × 16 keyway at x = 80, supports at 10 and 150 mm, in
    four-point bending (``kind`` "bending": F at 40 and 120 mm, so M = F · 30 mm between them)
    or torsion (+T at 40, −T at 120): the zoned solve's two-cut case (tests/validation/
    test_zoned.py, benchmarks/bench_zoned.py); ``bottom_radius_mm``: the keyway's r1 (0:
    sharp); ``diameter_mm``: the bar's diameter (the keyway stays DIN 6885-1's 6 × 3.5 of
    shafts over 17 up to 22 mm: the grid of benchmarks/bench_zone_bars.py)."""
    kw = (Keyway(6.0, 3.5, 16.0, 80.0, 0.0, bottom_radius_mm),)
    segs = (Segment("bar", 0.0, 160.0, diameter_mm, 0.0, keyways=kw),)
    brg = (Bearing("L", "x", 10.0, 10.0, 14_400.0, 10_000.0, K_SEED, axial=True),
           Bearing("R", "x", 150.0, 10.0, 14_400.0, 10_000.0, K_SEED))
    if kind == "bending":
        loads = (Load("p1", "force", 40.0, (38.0, 42.0), KEYED_BAR_F_N, 0.0),
                 Load("p2", "force", 120.0, (118.0, 122.0), KEYED_BAR_F_N, 0.0))
    else:
        loads = (Load("t1", "torque", 40.0, (38.0, 42.0), KEYED_BAR_T_NMM),
                 Load("t2", "torque", 120.0, (118.0, 122.0), -KEYED_BAR_T_NMM))
    return Variant(f"keyed_{kind}", "keyed bar", segs, brg, (), STEEL, 0.0, loads=loads)


HOLED_BAR_F_N = 1000.0         # four-point bending, as keyed_bar: M = F · 30 mm between the forces
HOLED_BAR_T_NMM = 50_000.0     # torsion between x = 40 and x = 120 mm
HOLED_BAR_P_N = 10_000.0       # tension between x = 40 and x = 120 mm


def holed_bar(kind: str, hole_mm: float = 4.0) -> Variant:
    """Ø20 × 160 mm bar with a transverse hole of ``hole_mm`` at x = 80 (along +y), supports
    at 10 and 150 mm (the left one axial), loaded between x = 40 and x = 120 mm: ``kind``
    "bending" (F at 40 and 120 mm: M = F · 30 mm), "torsion" (+T at 40, −T at 120) or
    "tension" (−P at 40, +P at 120): the cross hole's validation case (issue #33,
    tests/validation/test_cross_hole.py, benchmarks/bench_cross_hole.py)."""
    segs = (Segment("bar", 0.0, 160.0, 20.0, 0.0,
                    cross_holes=(CrossHole(hole_mm, 80.0, 0.0),)),)
    brg = (Bearing("L", "x", 10.0, 10.0, 14_400.0, 10_000.0, K_SEED, axial=True),
           Bearing("R", "x", 150.0, 10.0, 14_400.0, 10_000.0, K_SEED))
    if kind == "bending":
        loads = (Load("p1", "force", 40.0, (38.0, 42.0), HOLED_BAR_F_N, 0.0),
                 Load("p2", "force", 120.0, (118.0, 122.0), HOLED_BAR_F_N, 0.0))
    elif kind == "torsion":
        loads = (Load("t1", "torque", 40.0, (38.0, 42.0), HOLED_BAR_T_NMM),
                 Load("t2", "torque", 120.0, (118.0, 122.0), -HOLED_BAR_T_NMM))
    elif kind == "tension":
        loads = (Load("a1", "axial_force", 40.0, (38.0, 42.0), -HOLED_BAR_P_N),
                 Load("a2", "axial_force", 120.0, (118.0, 122.0), HOLED_BAR_P_N))
    else:
        raise ValueError(f"kind {kind!r}: bending | torsion | tension")
    return Variant(f"holed_{kind}", "holed bar", segs, brg, (), STEEL, 0.0, loads=loads)
