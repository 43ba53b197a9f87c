"""Loads as data: the typed load model every path reads (3D, axisymmetric, beam, fatigue).

A variant's loads are its attachments' centrifugal forces (``attachment_actions``) and the
``[[loads]]`` tables of its file (``Load``). Each load has a **speed law** (``scales_with``):

* ``"constant"``: the magnitude as written, at every speed;
* ``"rpm2"``: the magnitude is written at ``ref_rpm`` and scales with (rpm / ref_rpm)²;
* ``"<channel>"`` (any other name, e.g. ``"torque_Nm"``): the magnitude is written for the
  channel's value ``channel_ref`` and scales with channel(t) / channel_ref; the channel is a
  column of the load history (``shaftfe fatigue``) or a value of a load case.

Every load reduces to **actions** (``Action``): a force F (N) and a moment M (N·mm) about the
point (x, 0, 0) on the axis, delivered through a band [x0, x1] of the shaft's surface (a seat,
or a band of ``width_mm`` around a station) as a remote load: the nodal forces are the
transpose of the band's RBE3 averaging rows, so F and M are carried exactly and the band stays
free to deform (Ansys' deformable Remote Force). The shaft's own weight is a body action
(``BodyAction``). Loads of one speed law form one **pattern**; a path solves one pattern per
law (one factorisation) and a case superposes them with its factors (``LoadCase.factor``).

Kinds (``KINDS``; the file-level names are fixed so that other tools can write them):

=============  ======================================================================
force          ``F_N`` along ``angle_deg`` (0° = +y, 90° = +z)
moment         ``M_Nmm``, the moment vector along ``angle_deg`` in the y-z plane
torque         ``T_Nmm`` about +x (right-handed)
axial_force    ``F_N`` along +x
gear_mesh      a spur or helical gear (``module_mm``, ``teeth``, ``pressure_angle_deg``,
               ``helix_angle_deg``; or ``pitch_diameter_mm``) transmitting ``T_Nmm`` (the
               torque the mesh puts on THIS shaft, about +x), meshing at ``angle_deg`` (the
               direction from this axis to the contact): tangential F_t = 2 T / d, radial
               F_r = |F_t| tan α_n / cos β towards the axis, axial F_a = F_t tan β along +x
               (ISO 6336-1 §5 / Niemann–Winter vol. II: the nominal forces at the pitch
               circle), and the moment F_a · d/2 of the axial force at the pitch radius
gravity        ``g_mm_s2`` (default 9810) along ``angle_deg``: the shaft's own mass and
               every part's mass at its centroid (a snapshot in the shaft's frame)
=============  ======================================================================

Torques must form a path: per speed law the torques sum to zero, or a bearing declares
``holds_torsion = true``; else the load is refused, naming the free rotation.

**Frame** (``frame``): the solvers work in the frame that turns with the shaft. A load that
turns with the shaft (an unbalance, a part's m e ω²: ``"shaft"``) is static there; a load
fixed in space (a gear mesh's tangential and radial force and the moment of its axial force,
gravity, a belt pull: ``"space"``) turns once per revolution relative to the shaft: a static
solve shows it at the instant its direction is ``angle_deg`` in the shaft's frame, and in
fatigue it is rotating bending (a fully reversed cycle per revolution). Torques and axial
forces are the same in both frames. Defaults: ``force`` and ``moment`` ``"space"`` (the
textbook shaft: gear, belt and weight loads on a turning shaft), the parts' m e ω² ``"shaft"``.

Attachments (``attachment_actions``): each part's m e ω² (law rpm², at ``REF_RPM``) acts at the
part's centroid and enters the shaft through its seat as a force and the moment of that force
about the seat centre (x_c − x_seat) e_x × F. ``seed_placement=True`` keeps the seed's model
(Inventor, seed 000 §8.2.2): the force at the seat centre, no moment, as a pressure on the
half of the seat the part presses on.
"""

from __future__ import annotations

import dataclasses
import math
import re
from dataclasses import dataclass

from shaftfe.errors import InputError
from shaftfe.model.fields import PROV_KEYS, check_keys, is_num, num, provenance, table, text
from shaftfe.util.limits import RPM_CEILING
from shaftfe.util.units import REF_RPM, rpm2_scale

KINDS = ("force", "moment", "torque", "axial_force", "gear_mesh", "gravity")
FIXED_LAWS = ("constant", "rpm2")
CHANNEL_RE = re.compile(r"[A-Za-z][A-Za-z0-9_]*")
G_MM_S2 = 9810.0                      # standard gravity, mm/s²
DEFAULT_BAND_MM = 2.0                 # the width of the band a station load is spread over

# plausibility of magnitudes (a value in the wrong unit: kN typed as N, N·m as N·mm / 1000)
F_MAX_N = 1e6
M_MAX_NMM = 1e9


@dataclass(frozen=True)
class GearGeometry:
    """The gear of a ``gear_mesh``: normal module, teeth, normal pressure angle, helix angle
    (signed: its sign sets the axial force's direction) and the pitch diameter used for the
    forces (m_n z / cos β unless given)."""
    module_mm: float
    teeth: int
    pressure_angle_deg: float
    helix_angle_deg: float
    pitch_diameter_mm: float

    def forces(self, T_Nmm: float) -> tuple[float, float, float]:
        """(F_t, F_r, F_a) in N for the torque ``T_Nmm`` on this gear: F_t = 2T/d (signed as
        T), F_r = |F_t| tan α_n / cos β (towards the axis), F_a = F_t tan β (along +x)."""
        beta = math.radians(self.helix_angle_deg)
        ft = 2.0 * T_Nmm / self.pitch_diameter_mm
        fr = abs(ft) * math.tan(math.radians(self.pressure_angle_deg)) / math.cos(beta)
        return ft, fr, ft * math.tan(beta)


@dataclass(frozen=True)
class Load:
    """One ``[[loads]]`` table, resolved: the position (``x_mm`` on the axis; ``band_mm`` the
    surface band it is delivered through), the magnitude of its kind (``value``: F_N, M_Nmm or
    T_Nmm; for gravity the acceleration in mm/s²), the direction ``angle_deg``, its speed law,
    and for a gear mesh its geometry."""
    name: str
    kind: str
    x_mm: float
    band_mm: tuple[float, float]
    value: float
    angle_deg: float = 0.0
    scales_with: str = "constant"
    ref_rpm: float = REF_RPM           # the speed ``value`` is given at (law rpm2)
    channel_ref: float = 1.0           # the channel value ``value`` is given for (a channel law)
    seat: str = ""                     # the segment named by ``seat`` ("" = by x_mm)
    gear: GearGeometry | None = None
    frame: str = "space"               # "space" (fixed in space) | "shaft" (turns with it)


@dataclass(frozen=True)
class LoadCase:
    """A named case: a speed, a factor per load (default 1) and the value of each channel
    (default: the loads' ``channel_ref``, i.e. factor 1). ``check`` names the assessment the
    case is for: "static" (FKM static / DIN 743 S_F) or "" (a case to look at)."""
    name: str
    rpm: float
    factors: tuple[tuple[str, float], ...] = ()
    channels: tuple[tuple[str, float], ...] = ()
    check: str = ""

    def factor(self, load: Load | Action) -> float:
        """The factor on a load's (or action's) written magnitude in this case."""
        own = dict(self.factors).get(getattr(load, "factor_name", load.name), 1.0)
        return own * law_factor(load.scales_with, self.rpm, dict(self.channels),
                                ref_rpm=load.ref_rpm, channel_ref=load.channel_ref)


def law_factor(law: str, rpm: float, channels: dict, *, ref_rpm: float = REF_RPM,
               channel_ref: float = 1.0) -> float:
    """The factor of a speed law at ``rpm`` with channel values ``channels`` (a channel not
    given is at its reference value: factor 1); ``rpm`` and the channel values may be arrays
    (a history: ``fatigue.channels.channel_factors``)."""
    if law == "constant":
        return 1.0
    if law == "rpm2":
        return rpm2_scale(rpm, ref_rpm)
    return channels.get(law, channel_ref) / channel_ref


@dataclass(frozen=True)
class Action:
    """A load's resultant: force ``F_N`` and moment ``M_Nmm`` (about (x_mm, 0, 0)), delivered
    through the surface band ``band_mm``; ``pressed_half`` = the seed's placement (a pressure
    on the half of the seat the force presses on, ``M_Nmm`` zero). ``name`` is the load's (or
    the part's) name; the law and references are the load's."""
    name: str
    x_mm: float
    band_mm: tuple[float, float]
    F_N: tuple[float, float, float]
    M_Nmm: tuple[float, float, float]
    scales_with: str = "constant"
    ref_rpm: float = REF_RPM
    channel_ref: float = 1.0
    pressed_half: bool = False
    seat: str = ""                     # the seat's segment or part name, for mesh groups
    load: str = ""                     # the name a load case's factor uses ("" = ``name``)
    frame: str = "shaft"               # "space": turns relative to the shaft (module docstring)

    @property
    def factor_name(self) -> str:
        return self.load or self.name

    @property
    def torque_Nmm(self) -> float:
        return self.M_Nmm[0]


@dataclass(frozen=True)
class BodyAction:
    """A uniform acceleration field on the shaft's own mass (gravity): ``accel_mm_s2``."""
    name: str
    accel_mm_s2: tuple[float, float, float]
    scales_with: str = "constant"
    ref_rpm: float = REF_RPM
    channel_ref: float = 1.0


# --------------------------------------------------------------------------- resolution

def _dir(angle_deg: float) -> tuple[float, float]:
    a = math.radians(angle_deg)
    return math.cos(a), math.sin(a)


def _offset_moment(dx: float, F: tuple[float, float, float]) -> tuple[float, float, float]:
    """The moment about a point of a force F acting dx further along +x: (dx e_x) × F."""
    return 0.0, -dx * F[2], dx * F[1]


def load_actions(load: Load, variant) -> tuple[list[Action], list[BodyAction]]:
    """The actions of one load (gravity: one per part and one body action)."""
    kw = dict(scales_with=load.scales_with, ref_rpm=load.ref_rpm,
              channel_ref=load.channel_ref, seat=load.seat, frame=load.frame)
    c, s = _dir(load.angle_deg)
    zero = (0.0, 0.0, 0.0)
    if load.kind == "force":
        return [Action(load.name, load.x_mm, load.band_mm, (0.0, load.value * c,
                                                              load.value * s), zero, **kw)], []
    if load.kind == "moment":
        return [Action(load.name, load.x_mm, load.band_mm, zero,
                       (0.0, load.value * c, load.value * s), **kw)], []
    if load.kind == "torque":
        return [Action(load.name, load.x_mm, load.band_mm, zero, (load.value, 0.0, 0.0),
                       **{**kw, "frame": "shaft"})], []
    if load.kind == "axial_force":
        return [Action(load.name, load.x_mm, load.band_mm, (load.value, 0.0, 0.0), zero,
                       **{**kw, "frame": "shaft"})], []
    if load.kind == "gear_mesh":
        g = load.gear
        ft, fr, fa = g.forces(load.value)
        r = 0.5 * g.pitch_diameter_mm
        # contact at r e_r, e_r = (0, c, s); tangential e_t = (0, -s, c) so r e_r × F_t e_t
        # = r F_t e_x = T; radial towards the axis; axial along +x at the pitch radius
        # the torque and the axial force are the same in both frames; the transverse forces
        # and the axial force's moment are fixed in space (rotating bending)
        Fq = (0.0, -ft * s - fr * c, ft * c - fr * s)
        Mq = (0.0, fa * r * s, -fa * r * c)
        return [Action(load.name, load.x_mm, load.band_mm, (fa, 0.0, 0.0),
                       (load.value, 0.0, 0.0), **{**kw, "frame": "shaft"}),
                Action(load.name, load.x_mm, load.band_mm, Fq, Mq,
                       **{**kw, "frame": "space"})], []
    if load.kind == "gravity":
        a = (0.0, load.value * c, load.value * s)
        acts = []
        for part in variant.attachments:
            m_t = part.mass_kg * 1e-3
            F = (0.0, m_t * a[1], m_t * a[2])
            xs = part.seat_center_mm
            acts.append(Action(f"{load.name}:{part.name}", xs,
                               (part.seat_x_start_mm, part.seat_x_end_mm), F,
                               _offset_moment(part.x_centroid_mm - xs, F),
                               **{**kw, "seat": part.name, "frame": "space"}, load=load.name))
        return acts, [BodyAction(load.name, a, load.scales_with, load.ref_rpm,
                                 load.channel_ref)]
    raise InputError("loads", f"{load.name}.kind", " | ".join(KINDS), got=load.kind)


def attachment_actions(variant, *, seed_placement: bool = False) -> list[Action]:
    """Each part's m e ω² at ``REF_RPM`` (law rpm²): at its centroid, entering through its
    seat as a force and a moment (default), or the seed's placement (``seed_placement``)."""
    out = []
    for a in variant.attachments:
        F0 = a.force_N(REF_RPM)
        if F0 == 0:
            continue
        c, s = _dir(a.angle_deg)
        F = (0.0, F0 * c, F0 * s)
        xs = a.seat_center_mm
        M = (0.0, 0.0, 0.0) if seed_placement else _offset_moment(a.x_centroid_mm - xs, F)
        out.append(Action(a.name, xs, (a.seat_x_start_mm, a.seat_x_end_mm), F, M, "rpm2",
                          REF_RPM, 1.0, pressed_half=seed_placement, seat=a.name,
                          load="parts", frame="shaft"))
    return out


def actions(variant, *, seed_placement: bool = False
            ) -> tuple[tuple[Action, ...], tuple[BodyAction, ...]]:
    """Every action of the variant: its parts' m e ω² and its ``[[loads]]``."""
    acts = attachment_actions(variant, seed_placement=seed_placement)
    body: list[BodyAction] = []
    for ld in getattr(variant, "loads", ()):
        a, b = load_actions(ld, variant)
        acts += a
        body += b
    return tuple(acts), tuple(body)


def pattern_key(item: Action | BodyAction | Load) -> tuple:
    """The pattern an action belongs to: actions of one key scale together (one solve each).
    (A load fixed in space is a static pattern like any other; fatigue, which needs it at
    every phase of a revolution, asks for its ``quadrature`` as well.)"""
    if item.scales_with == "constant":
        return ("constant",)
    if item.scales_with == "rpm2":
        return ("rpm2", float(item.ref_rpm))
    return (item.scales_with, float(item.channel_ref))


def factored_loads(variant) -> frozenset:
    """The loads a load case factors on its own (each then a pattern of its own)."""
    return frozenset(k for c in getattr(variant, "load_cases", ()) for k, _ in c.factors)


def solve_pattern(pattern: tuple, own: str, factored) -> tuple:
    """The key of one right-hand side of a static solve: the law's ``pattern_key``, split by
    the load's name ``own`` where a case factors it alone (``factored_loads``)."""
    return (*pattern, "load", own) if own in factored else tuple(pattern)


def pattern_label(key: tuple) -> str:
    """A readable, unique name of a pattern key (summary.json, the caches, fatigue's
    per-pattern fields: the full 3D, axisymmetric and zoned models name them alike)."""
    return ":".join(f"{k:g}" if isinstance(k, float) else str(k) for k in key)


def quadrature(a: Action) -> Action:
    """The action turned by +90° about the axis: with ``a`` it spans every phase of a load
    fixed in space (σ(φ) = cos φ σ(a) + sin φ σ(quadrature(a)), linear elasticity)."""
    F, M = a.F_N, a.M_Nmm
    return dataclasses.replace(a, F_N=(F[0], -F[2], F[1]), M_Nmm=(M[0], -M[2], M[1]))


def laws(variant) -> tuple[str, ...]:
    """The speed laws the variant's loads use (``"rpm2"`` whenever a part spins)."""
    acts, body = actions(variant)
    return tuple(dict.fromkeys(a.scales_with for a in (*acts, *body)))


def channels(variant) -> tuple[str, ...]:
    """The history channels the variant's loads scale with."""
    return tuple(law for law in laws(variant) if law not in FIXED_LAWS)


# --------------------------------------------------------------------------- rules

TORQUE_TOL = 1e-9            # relative: Σ T per law must vanish to round-off of the inputs


def check_torque_path(variant, src: str = "loads") -> None:
    """Torques must form a path (issue #31): per speed law the torques about the axis sum to
    zero, or a bearing holds torsion (``Bearing.holds_torsion``). Else the shaft is free to
    rotate about its axis under the load: refused, naming the free rotation."""
    if any(getattr(b, "holds_torsion", False) for b in variant.bearings):
        return
    acts, _ = actions(variant)
    sums: dict[str, float] = {}
    scale: dict[str, float] = {}
    for a in acts:
        # loads of one channel with different references still scale together: per unit
        k = a.scales_with
        w = 1.0 / a.channel_ref if k not in FIXED_LAWS else (
            1.0 / a.ref_rpm ** 2 if k == "rpm2" else 1.0)
        sums[k] = sums.get(k, 0.0) + a.torque_Nmm * w
        scale[k] = scale.get(k, 0.0) + abs(a.torque_Nmm * w)
    for k, t in sums.items():
        if scale[k] > 0 and abs(t) > TORQUE_TOL * scale[k]:
            names = ", ".join(a.name for a in acts if a.scales_with == k and a.torque_Nmm)
            raise InputError(src, "loads", "torques that sum to zero per speed law, or a bearing "
                             "with holds_torsion = true", reason=(
                                 f"leave the rotation about the shaft axis free: the torques "
                                 f"scaling with {k!r} ({names}) sum to a net torque and no "
                                 "support holds torsion"))


# --------------------------------------------------------------------------- reading

_COMMON_KEYS = {"name", "kind", "x_mm", "seat", "width_mm", "angle_deg", "scales_with",
                "ref_rpm", "channel_ref", "frame"}
FRAMES = ("space", "shaft")
_KIND_KEYS = {
    "force": {"F_N"}, "moment": {"M_Nmm"}, "torque": {"T_Nmm"}, "axial_force": {"F_N"},
    "gear_mesh": {"T_Nmm", "module_mm", "teeth", "pressure_angle_deg", "helix_angle_deg",
                  "pitch_diameter_mm"},
    "gravity": {"g_mm_s2"},
}
_VALUE_KEY = {"force": "F_N", "moment": "M_Nmm", "torque": "T_Nmm", "axial_force": "F_N",
              "gear_mesh": "T_Nmm", "gravity": "g_mm_s2"}
_VALUE_MAX = {"F_N": F_MAX_N, "M_Nmm": M_MAX_NMM, "T_Nmm": M_MAX_NMM, "g_mm_s2": 1e6}
_UNIT_HINT = {"F_N": "N (not kN)", "M_Nmm": "N·mm (not N·m)", "T_Nmm": "N·mm (not N·m)",
              "g_mm_s2": "mm/s² (9810 = 1 g)"}
# gear geometry: the ranges of ISO 53 / ISO 54 gearing (module 0.3 … 50 mm, α_n 14.5 … 30°,
# |β| < 45°) and the fewest teeth a cut involute gear has without undercut at α_n = 14.5°
GEAR_MODULE_MM = (0.3, 50.0)
GEAR_PRESSURE_DEG = (14.5, 30.0)
GEAR_HELIX_MAX_DEG = 45.0
GEAR_MIN_TEETH = 6


def _num(t: dict, key: str, src: str, fld: str, default=None) -> float | None:
    return num(t, key, src, fld, default=default, required=default is None)


def _position(t: dict, src: str, fld: str, segs) -> tuple[float, tuple[float, float], str]:
    """(x of the resultant, the band it is delivered through, the seat's segment name)."""
    x0, x1 = segs[0].x_start_mm, segs[-1].x_end_mm
    seat = ""
    if "seat" in t:
        seat = t["seat"]
        seg = next((s for s in segs if s.name == seat), None)
        if seg is None:
            raise InputError(src, f"{fld}.seat", "the name of a shaft segment: "
                             + ", ".join(s.name for s in segs), got=seat)
        band = (seg.x_start_mm, seg.x_end_mm)
        x = _num(t, "x_mm", src, fld, default=0.5 * (band[0] + band[1]))
        if not band[0] - 1e-9 <= x <= band[1] + 1e-9:
            raise InputError(src, f"{fld}.x_mm", f"on its seat {seat!r} [{band[0]:g}, "
                             f"{band[1]:g}] mm", got=x)
        if "width_mm" in t:
            raise InputError(src, f"{fld}.width_mm", "absent with seat (the seat is the band)",
                             got=t["width_mm"])
        return x, band, seat
    if "x_mm" not in t:
        raise InputError(src, f"{fld}.x_mm", "a position on the shaft in mm (or seat = "
                         "\"<segment>\")", reason="is missing")
    x = _num(t, "x_mm", src, fld)
    w = _num(t, "width_mm", src, fld, default=DEFAULT_BAND_MM)
    if not (x0 <= x <= x1):
        raise InputError(src, f"{fld}.x_mm", f"on the shaft [{x0:g}, {x1:g}] mm", got=x)
    if not (0 < w <= x1 - x0):
        raise InputError(src, f"{fld}.width_mm", f"0 < width <= the shaft length {x1 - x0:g} "
                         "mm", got=w)
    band = (max(x0, x - 0.5 * w), min(x1, x + 0.5 * w))
    return x, band, seat


def _gear(t: dict, src: str, fld: str, seat_d: float) -> GearGeometry:
    beta = _num(t, "helix_angle_deg", src, fld, default=0.0)
    alpha = _num(t, "pressure_angle_deg", src, fld, default=20.0)
    if not abs(beta) < GEAR_HELIX_MAX_DEG:
        raise InputError(src, f"{fld}.helix_angle_deg", f"|β| < {GEAR_HELIX_MAX_DEG:g}°",
                         got=beta)
    if not GEAR_PRESSURE_DEG[0] <= alpha <= GEAR_PRESSURE_DEG[1]:
        raise InputError(src, f"{fld}.pressure_angle_deg",
                         f"{GEAR_PRESSURE_DEG[0]:g} … {GEAR_PRESSURE_DEG[1]:g}°", got=alpha)
    m = _num(t, "module_mm", src, fld)
    if not GEAR_MODULE_MM[0] <= m <= GEAR_MODULE_MM[1]:
        raise InputError(src, f"{fld}.module_mm",
                         f"{GEAR_MODULE_MM[0]:g} … {GEAR_MODULE_MM[1]:g} mm", got=m)
    z = t.get("teeth")
    if not (isinstance(z, int) and not isinstance(z, bool) and z >= GEAR_MIN_TEETH):
        raise InputError(src, f"{fld}.teeth", f"a whole number >= {GEAR_MIN_TEETH}", got=z)
    d_ref = m * z / math.cos(math.radians(beta))
    d = _num(t, "pitch_diameter_mm", src, fld, default=d_ref)
    # a working pitch diameter differs from m z / cos β only by the profile shift (a few
    # modules at most); a root circle d − 2.5 m inside the seat is a gear that cannot exist
    if not abs(d - d_ref) <= 2.0 * m:
        raise InputError(src, f"{fld}.pitch_diameter_mm", f"within 2 modules of m z / cos β = "
                         f"{d_ref:.4g} mm", got=d)
    if not d - 2.5 * m > seat_d:
        raise InputError(src, f"{fld}", f"a root diameter d − 2.5 m above the seat's Ø "
                         f"{seat_d:g} mm", reason=f"has a root diameter {d - 2.5 * m:.4g} mm "
                         "(the gear would be inside the shaft)")
    return GearGeometry(m, z, alpha, beta, d)


def read_load(t: dict, src: str, fld: str, segs) -> Load:
    """One ``[[loads]]`` table → ``Load`` (InputError naming the file and field)."""
    kind = text(t, "kind", src, fld)
    if kind not in KINDS:
        raise InputError(src, f"{fld}.kind", " | ".join(KINDS), got=kind)
    check_keys(t, _COMMON_KEYS | _KIND_KEYS[kind], src, fld)
    name = text(t, "name", src, fld)
    vk = _VALUE_KEY[kind]
    if kind == "gravity":
        value = _num(t, vk, src, fld, default=G_MM_S2)
        x, band, seat = 0.5 * (segs[0].x_start_mm + segs[-1].x_end_mm), (
            segs[0].x_start_mm, segs[-1].x_end_mm), ""
        for k in ("x_mm", "seat", "width_mm"):
            if k in t:
                raise InputError(src, f"{fld}.{k}", "absent for gravity (it acts on every "
                                 "mass)", got=t[k])
    else:
        value = _num(t, vk, src, fld)
        x, band, seat = _position(t, src, fld, segs)
    if not abs(value) <= _VALUE_MAX[vk]:
        raise InputError(src, f"{fld}.{vk}", f"|{vk}| <= {_VALUE_MAX[vk]:.0e} in "
                         f"{_UNIT_HINT[vk]}", got=value)
    law = t.get("scales_with", "constant")
    if not (isinstance(law, str) and CHANNEL_RE.fullmatch(law)):
        raise InputError(src, f"{fld}.scales_with", "constant | rpm2 | the name of a load-history"
                         " channel (letters, digits, _)", got=law)
    ref_rpm = _num(t, "ref_rpm", src, fld, default=REF_RPM)
    if "ref_rpm" in t and law != "rpm2":
        raise InputError(src, f"{fld}.ref_rpm", "only with scales_with = \"rpm2\"", got=ref_rpm)
    if not 0 < ref_rpm <= 1e5:
        raise InputError(src, f"{fld}.ref_rpm", "0 < ref_rpm <= 100000 rpm", got=ref_rpm)
    channel_ref = _num(t, "channel_ref", src, fld, default=1.0)
    if "channel_ref" in t and law in FIXED_LAWS:
        raise InputError(src, f"{fld}.channel_ref", "only with scales_with = a channel name",
                         got=channel_ref)
    if not (channel_ref != 0 and math.isfinite(channel_ref)):
        raise InputError(src, f"{fld}.channel_ref", "a finite number other than 0",
                         got=channel_ref)
    angle = _num(t, "angle_deg", src, fld, default=0.0)
    if kind in ("torque", "axial_force") and "angle_deg" in t:
        raise InputError(src, f"{fld}.angle_deg", f"absent for {kind} (it acts along the axis)",
                         got=angle)
    frame = t.get("frame", "space")
    if frame not in FRAMES or (kind not in ("force", "moment") and "frame" in t):
        raise InputError(src, f"{fld}.frame", "space | shaft, only for force and moment (a gear "
                         "mesh and gravity are fixed in space; torque and axial force are the "
                         "same in both frames)", got=frame)
    gear = None
    if kind == "gear_mesh":
        seg = next(s for s in segs if s.x_start_mm - 1e-9 <= x <= s.x_end_mm + 1e-9)
        gear = _gear(t, src, fld, seg.diameter_mm)
    return Load(name, kind, x, band, value, angle, law, ref_rpm, channel_ref, seat, gear, frame)


def read_loads(raw, src: str, segs, part_names=(), ctx=None) -> tuple[Load, ...]:
    """The ``[[loads]]`` list (names unique, and not a part's name). A table that gives
    provenance lists (seed / reconstructed / derived / standard) must tag every number, as
    every other table; one without them is a user's load (no provenance recorded)."""
    if not isinstance(raw, list):
        raise InputError(src, "loads", "a list of [[loads]] tables", got=type(raw).__name__)
    out = []
    for i, t in enumerate(raw):
        t = table(t, src, f"loads[{i}]")
        out.append(read_load(t, src, f"loads[{i}]", segs))
        if ctx is not None and any(k in t for k in PROV_KEYS - {"note"}):
            provenance(t, src, f"loads[{i}]", f"loads.{out[-1].name}", ctx)
    names = [ld.name for ld in out] + list(part_names)
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise InputError(src, "loads[*].name", "unique names (also among the parts)", got=dup)
    return tuple(out)


def read_load_cases(raw, src: str, loads: tuple[Load, ...]) -> tuple[LoadCase, ...]:
    """The ``[[load_cases]]`` list: ``name``, ``rpm``, ``factors = {load = f}``, ``channels =
    {channel = value}``, ``check = "static"`` (optional)."""
    if not isinstance(raw, list):
        raise InputError(src, "load_cases", "a list of [[load_cases]] tables",
                         got=type(raw).__name__)
    names = {ld.name for ld in loads}
    chans = {ld.scales_with for ld in loads if ld.scales_with not in FIXED_LAWS}
    out = []
    for i, t in enumerate(raw):
        fld = f"load_cases[{i}]"
        t = table(t, src, fld)
        check_keys(t, {"name", "rpm", "factors", "channels", "check"}, src, fld)
        nm = text(t, "name", src, fld)
        rpm = _num(t, "rpm", src, fld)
        if not 0 <= rpm <= RPM_CEILING:
            raise InputError(src, f"{fld}.rpm", f"0 … {RPM_CEILING:g} rpm", got=rpm)
        fac = table(t.get("factors", {}), src, f"{fld}.factors")
        for k, f in fac.items():
            if k not in names and k != "parts":
                raise InputError(src, f"{fld}.factors.{k}", "the name of a [[loads]] entry "
                                 "or \"parts\" (every part's m e ω²): " + ", ".join(
                                     sorted(names | {"parts"})), got=k)
            if not (is_num(f) and math.isfinite(f) and 0 <= f <= 100):
                raise InputError(src, f"{fld}.factors.{k}", "a factor 0 … 100", got=f)
        ch = table(t.get("channels", {}), src, f"{fld}.channels")
        for k, c in ch.items():
            if k not in chans:
                raise InputError(src, f"{fld}.channels.{k}", "a channel a load scales with: "
                                 + (", ".join(sorted(chans)) or "(none does)"), got=k)
            if not (is_num(c) and math.isfinite(c)):
                raise InputError(src, f"{fld}.channels.{k}", "a finite number", got=c)
        chk = t.get("check", "")
        if chk not in ("", "static"):
            raise InputError(src, f"{fld}.check", "\"static\" or absent", got=chk)
        out.append(LoadCase(nm, rpm, tuple((k, float(f)) for k, f in fac.items()),
                            tuple((k, float(c)) for k, c in ch.items()), chk))
    nms = [c.name for c in out]
    dup = sorted({n for n in nms if nms.count(n) > 1})
    if dup:
        raise InputError(src, "load_cases[*].name", "unique names", got=dup)
    return tuple(out)
