"""Balancer-shaft variants: frozen dataclasses (the contract every later stage reads).

Coordinates: x along the shaft axis in mm, from the shaft's left end face (x = 0, the gear
side) to the right end (x = total length); y, z transverse. An eccentricity angle of 0° points
along +y, 90° along +z (right-handed about +x). The loader ``load_variant`` (below) reads
``geometry/<name>.toml`` (with its includes), validates it and returns a ``Variant``.

For balancer shaft C the gear (with counterweight 1 bolted to it) is at the left end (x = 0,
M10×0.75 thread, KM 0 nut) and counterweight 2 at the right end (M15×1 thread, KM 2 nut, hex
socket for the water-pump drive). See ``geometry/RECONSTRUCTION.md``.

Units: mm, N, MPa, kg (masses in files and reports), kg·mm² (inertias), t/mm³ (densities).
Every numeric value in the files carries its provenance (see ``Provenance``): "seed" (stated
in a seed document), "reconstructed" (chosen or fitted by us; the note says to what),
"derived" (computed from other values by a stated formula) or "standard" (taken from a cited
standard or catalogue, not from the seeds).
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any, Literal

from shaftfe.util.units import omega

Source = Literal["seed", "reconstructed", "derived", "standard"]
SOURCES: tuple[str, ...] = ("seed", "reconstructed", "derived", "standard")


@dataclass(frozen=True)
class Material:
    name: str                 # e.g. "14220" (16MnCr5), "12050" (C45), "structural_steel"
    E_MPa: float
    nu: float
    density_t_mm3: float      # t/mm³ (7.85e-9 for steel)
    yield_MPa: float          # R_p, R_m: at strength_reference_diameter_mm where given
    ultimate_MPa: float
    description: str = ""
    # what the standards' assessments (FKM, DIN 743) read from the same record
    group: str = ""                              # "" = no standard material group
    heat_treatment: str = ""
    strength_reference_diameter_mm: float | None = None
    case_hardness_HRC: float | None = None
    case_depth_mm: float | None = None           # None = not case hardened


@dataclass(frozen=True)
class Keyway:
    """A parallel-key seat milled into a segment (flat-ended slot, DIN 6885 / ČSN 02 2562)."""
    width_mm: float
    depth_mm: float           # depth into the shaft from the surface (t1)
    length_mm: float          # overall slot length including the round ends
    x_center_mm: float        # axial centre of the slot (absolute x)
    angle_deg: float = 0.0    # angular position of the slot centre line
    # the radius r1 of the slot's bottom edges (DIN 6885-1); 0: sharp-edged, where a peak
    # on the keyway is a value of the mesh (``solid.plan.SharpKeywayEdge``)
    bottom_radius_mm: float = dataclasses.field(default=0.0, metadata={"omit_empty": True})


@dataclass(frozen=True)
class Groove:
    """A circumferential groove turned into a segment (``shaftfe.model.grooves``): a flat
    bottom ``depth_mm`` below the surface, ``width_mm`` wide, bottom corners of ``radius_mm``
    (half the width: a full round U groove). The loader resolves a standard groove's
    dimensions from the segment's diameter; ``kind`` says which standard they came from."""
    kind: str                 # one of model.grooves.BUILT
    x_center_mm: float        # axial centre (absolute x); an undercut's: of its opening f
    width_mm: float           # an undercut's: f, on the cylinder from the face plane
    depth_mm: float           # an undercut's: t1
    radius_mm: float
    # a DIN 509 undercut's (``model.grooves.UNDERCUTS``): the segment's end it sits at, next to
    # the larger segment's face ("left" | "right"), and form F's recess t2 into that face;
    # empty for a groove on a straight part (and out of the content hash)
    side: str = dataclasses.field(default="", metadata={"omit_empty": True})
    face_depth_mm: float = dataclasses.field(default=0.0, metadata={"omit_empty": True})


@dataclass(frozen=True)
class CrossHole:
    """A transverse hole drilled through a segment (issue #33): straight through the axis,
    its direction ``angle_deg`` in the y-z plane (0° = +y, as a keyway's)."""
    diameter_mm: float
    x_center_mm: float        # axial position of the hole's axis (absolute x)
    angle_deg: float = 0.0


@dataclass(frozen=True)
class Segment:
    """A cylindrical step of the shaft. Segments are contiguous: x_start of segment i+1 equals
    x_end of segment i. ``fillet_mm`` is the radius of the fillet at this segment's RIGHT end
    (the shoulder to the next segment; 0 = sharp edge, ignored on the last segment)."""
    name: str
    x_start_mm: float
    length_mm: float
    diameter_mm: float
    fillet_mm: float = 0.0
    keyways: tuple[Keyway, ...] = ()
    kind: str = "plain"       # "plain" | "seat" | "thread" (threads modelled at minor diameter)
    # added later: left out of the content hash while empty, so a shaft without grooves
    # keeps its hash (and its cached meshes and solutions)
    grooves: tuple[Groove, ...] = dataclasses.field(default=(), metadata={"omit_empty": True})
    cross_holes: tuple[CrossHole, ...] = dataclasses.field(default=(),
                                                           metadata={"omit_empty": True})
    # 45° chamfers on the segment's outer edge at its left / right end (mm along the axis and
    # radially): only where that edge is convex, the shaft's end or a step down to the next
    chamfer_left_mm: float = dataclasses.field(default=0.0, metadata={"omit_empty": True})
    chamfer_right_mm: float = dataclasses.field(default=0.0, metadata={"omit_empty": True})
    # a conical (tapered) segment: its diameter at the right end, ``diameter_mm`` being the
    # left end's; 0: a cylinder (issue #33)
    diameter_right_mm: float = dataclasses.field(default=0.0, metadata={"omit_empty": True})

    @property
    def x_end_mm(self) -> float:
        return self.x_start_mm + self.length_mm

    @property
    def conical(self) -> bool:
        return bool(self.diameter_right_mm) and abs(self.diameter_right_mm
                                                    - self.diameter_mm) > 1e-9

    @property
    def d_right_mm(self) -> float:
        """The diameter at the right end (``diameter_mm`` for a cylinder)."""
        return self.diameter_right_mm if self.conical else self.diameter_mm

    def diameter_at(self, x_mm):
        """The diameter at ``x_mm`` (a number or an array; linear along a conical segment)."""
        if not self.conical:
            return self.diameter_mm + 0.0 * x_mm
        t = (x_mm - self.x_start_mm) / self.length_mm
        return self.diameter_mm + t * (self.diameter_right_mm - self.diameter_mm)


@dataclass(frozen=True)
class HexSocket:
    """Hexagon socket in an end face (water-pump drive, seed 000 §8.2: s = 8, 10 mm deep)."""
    end: Literal["left", "right"]
    across_flats_mm: float
    depth_mm: float


@dataclass(frozen=True)
class Bearing:
    """A bearing seat with its radial spring support.

    K_N_per_mm is the 2×2 radial stiffness [[K11, K12], [K21, K22]] in the (y, z) plane
    (seed 000 §8.3: K11 = K22 = 35 030, K12 = K21 = 8756 N/mm). ``axial`` marks the bearing
    that holds the axial load (the gear-side one in the seed)."""
    name: str                 # e.g. "gear_side", "free_side"
    designation: str          # e.g. "ZKL 3203"
    x_center_mm: float
    width_mm: float
    C_N: float                # basic dynamic load rating
    C0_N: float               # basic static load rating
    K_N_per_mm: tuple[tuple[float, float], tuple[float, float]]
    axial: bool = False
    tilt_stiffness_Nmm_per_rad: float = 0.0   # 0 = tilt free (seed)
    life_exponent: float = 3.0                # ISO 281: 3 for ball bearings
    bore_mm: float = 0.0
    outer_diameter_mm: float = 0.0
    chamfer_mm: float = 0.0   # axial length of the inner ring's bore chamfer (0 = sharp)
    r_s_min_mm: float = 0.0   # ISO 15 smallest corner chamfer r_s min (0 = not given)
    holds_torsion: bool = False   # reacts torque about the axis (a coupling, a locked drive)

    @property
    def x_start_mm(self) -> float:
        return self.x_center_mm - 0.5 * self.width_mm

    @property
    def x_end_mm(self) -> float:
        return self.x_center_mm + 0.5 * self.width_mm

    @property
    def contact_x_start_mm(self) -> float:
        """Start of the band where the inner ring's bore touches the seat: the ring's face plus
        its corner chamfer (the chamfered corner does not bear on the shaft)."""
        return self.x_start_mm + self.chamfer_mm

    @property
    def contact_x_end_mm(self) -> float:
        return self.x_end_mm - self.chamfer_mm


@dataclass(frozen=True)
class Attachment:
    """A part carried by the shaft: gear, counterweight, nut.

    The seat is the axial interval of the shaft surface the part bears on; its centrifugal force
    m e ω² acts in the direction ``angle_deg`` and is applied to the half of that seat it presses
    on. Parts bolted to another part (counterweight 1 on the gear) name the same seat.
    Inertias are about the part's own centroid: polar (about the part's axis parallel to x)
    and diametral (about a transverse axis).

    ``seed_load_case`` marks the parts whose forces the seed applied (gear, counterweight 1,
    counterweight 2: seed 000 §8.2.2, Inventor's shaft module); the others (screws, keys, nuts,
    washers) complete the mass properties. ``Variant.with_seed_load_case()`` keeps only the
    former."""
    name: str
    seat_x_start_mm: float
    seat_x_end_mm: float
    mass_kg: float
    eccentricity_mm: float
    x_centroid_mm: float
    angle_deg: float = 0.0
    polar_inertia_kg_mm2: float = 0.0
    diametral_inertia_kg_mm2: float = 0.0
    material: str = ""
    seed_load_case: bool = False
    seat_segment: str = ""            # name of the segment the seat was given as ("" if by x)

    @property
    def seat_center_mm(self) -> float:
        return 0.5 * (self.seat_x_start_mm + self.seat_x_end_mm)

    def force_N(self, rpm: float) -> float:
        """Centrifugal force m e ω² in N at ``rpm``."""
        return self.mass_kg * self.eccentricity_mm * 1e-3 * omega(rpm) ** 2


@dataclass(frozen=True)
class Provenance:
    """Where each value came from: maps a dotted field path (e.g. "segments.seat_gear.length_mm")
    to "seed", "reconstructed", "derived" or "standard", plus a free-text note per path (the
    notes are keyed by the table path, e.g. "segments.gear_seat")."""
    source: MappingProxyType = field(default_factory=lambda: MappingProxyType({}))
    note: MappingProxyType = field(default_factory=lambda: MappingProxyType({}))


@dataclass(frozen=True)
class BalanceTarget:
    """The seed's whole-balancer figures for a variant (seed 000 §8.2.2 table) and the crank's
    reciprocating m_pos R used for X2 (seed 000 §8.1)."""
    X2_percent: float
    mass_kg: float
    gamma2_mm: float
    x_T_mm: float
    m_pos_kg: float = 0.0
    crank_radius_mm: float = 0.0


@dataclass(frozen=True)
class MassProperties:
    """Whole balancer (shaft body + attachments), x from the shaft's left end face.

    ``gamma2_mm`` = |Σ m e| / m (the seed's γ2); ``x_T_mm`` = axial centroid minus the crankcase
    parting plane (positive towards the right, counterweight-2 end); inertias in kg·mm²,
    polar about the shaft axis, diametral about a transverse axis through the centroid (mean
    of the y and z axes)."""
    mass_kg: float
    shaft_mass_kg: float
    x_centroid_mm: float
    me_y_kg_mm: float
    me_z_kg_mm: float
    gamma2_mm: float
    x_T_mm: float
    polar_inertia_kg_mm2: float
    diametral_inertia_kg_mm2: float
    shaft_polar_inertia_kg_mm2: float


@dataclass(frozen=True)
class Duty:
    """What the shaft is asked to do (the variant's ``[duty]`` table): its speeds, its rpm
    history and design life, the engine it balances and the data of its element checks.
    Files are resolved paths (``parse._duty``: relative to the file stating [duty], else a bare
    name in its standard directory). ``None`` = not stated: a command needing it asks for it
    on the command line; nothing falls back to the seed's values."""
    source: str                                   # the file that states [duty]
    speed_range_rpm: tuple[float, float]          # lowest running (idle) … highest speed
    design_speeds_rpm: tuple[float, ...] = ()     # static checking speeds (proof speeds)
    campbell_range_rpm: tuple[float, float] | None = None
    spectrum: str | None = None                   # rpm history file
    design_life_h: float | None = None            # design life in hours of the history
    design_life_blocks: float | None = None       # … or in passes of its block (the seed's 1e7)
    engine: str | None = None                     # engine file (balancing); None = no balancing
    sn_curve: str | None = None                   # the seed method's S-N card (sn_curves.toml)
    elements: str | None = None                   # drive, keys and gear pair data (elements.toml)

    @property
    def max_rpm(self) -> float:
        return self.speed_range_rpm[1]

    def speed_limit(self) -> tuple[float, str]:
        """(the highest operating speed, where it comes from): the bound
        ``balance.engines.engine_speed_limit`` gives a variant's duty."""
        return self.max_rpm, f"highest speed of speed_range_rpm in {self.source} [duty]"


@dataclass(frozen=True)
class Variant:
    name: str                          # "x2_57"
    description: str
    segments: tuple[Segment, ...]
    bearings: tuple[Bearing, ...]
    attachments: tuple[Attachment, ...]
    material: Material                 # shaft material
    parting_plane_x_mm: float          # crankcase parting plane (origin of the seed's x_T)
    hex_socket: HexSocket | None = None
    clearance_station_x_mm: float | None = None   # smallest clearance to the crankshaft (1.4 mm)
    provenance: Provenance = field(default_factory=Provenance)
    source_files: tuple[str, ...] = ()
    content_hash: str = ""             # sha256 of the canonical geometry+physics content
    materials: tuple[Material, ...] = ()          # every material the files define
    balance_target: BalanceTarget | None = None
    clearance_mm: float | None = None             # the seed's smallest clearance (1.4 mm)
    stock_diameter_mm: float | None = None        # bar stock of the shaft (Ø25)
    overrides: tuple[tuple[str, object], ...] = ()  # (path, value) set for this run (--set)
    loads: tuple = ()                  # shaftfe.model.loads.Load: the [[loads]] tables
    load_cases: tuple = ()             # shaftfe.model.loads.LoadCase: the [[load_cases]]
    duty: Duty | None = None                      # [duty]: None = the variant states none

    @property
    def overrides_map(self) -> dict:
        """{path: value} of the ``--set`` overrides this variant was loaded with."""
        return dict(self.overrides)

    @property
    def length_mm(self) -> float:
        return self.segments[-1].x_end_mm - self.segments[0].x_start_mm

    def segment_at(self, x_mm: float) -> Segment:
        for s in self.segments:
            if s.x_start_mm - 1e-9 <= x_mm <= s.x_end_mm + 1e-9:
                return s
        raise ValueError(f"x = {x_mm} mm is outside the shaft")

    def segment(self, name: str) -> Segment:
        return next(s for s in self.segments if s.name == name)

    def bearing(self, name: str) -> Bearing:
        return next(b for b in self.bearings if b.name == name)

    def attachment(self, name: str) -> Attachment:
        return next(a for a in self.attachments if a.name == name)

    def load_case(self, name: str):
        return next(c for c in self.load_cases if c.name == name)

    def with_seed_load_case(self) -> Variant:
        """The same variant carrying only the attachments the seed loaded the shaft with
        (gear, counterweight 1, counterweight 2), as Inventor's shaft module did, and none of
        the file's [[loads]] (the seed neglected the gear mesh and the pump drive)."""
        return dataclasses.replace(
            self, attachments=tuple(a for a in self.attachments if a.seed_load_case), loads=(),
            load_cases=())


def _canonical(obj: Any) -> Any:
    if dataclasses.is_dataclass(obj):
        return {f.name: _canonical(getattr(obj, f.name)) for f in dataclasses.fields(obj)
                if getattr(obj, f.name) or not f.metadata.get("omit_empty")}
    if isinstance(obj, tuple | list):
        return [_canonical(e) for e in obj]
    if isinstance(obj, bool) or obj is None or isinstance(obj, str):
        return obj
    if isinstance(obj, int | float):
        return float(obj)
    raise TypeError(f"cannot canonicalise {type(obj).__name__}")


def content_hash(v: Variant) -> str:
    """sha256 of a canonical JSON of the resolved physical content: segments, bearings,
    attachments, materials, hex socket, parting plane and clearance station (not the duty: the
    solid and its solution do not depend on it). Names of the
    variant, descriptions, provenance and file names are left out, so comments, whitespace,
    notes and the include layout do not change it."""
    skip = {"name", "description", "provenance", "source_files", "content_hash",
            "balance_target", "overrides", "duty"}
    body = {f.name: _canonical(getattr(v, f.name)) for f in dataclasses.fields(v)
            if f.name not in skip}
    text = json.dumps(body, sort_keys=True, separators=(",", ":"), ensure_ascii=True)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()
