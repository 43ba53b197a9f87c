"""Balancer-shaft variants: frozen dataclasses (the contract every later stage reads).

Coordinates: x along the shaft axis in mm, from the shaft's left end face (x = 0, the gear
side) to the right end (x = total length); y, z transverse. An eccentricity angle of 0° points
along +y, 90° along +z (right-handed about +x). The loader ``load_variant`` (below) reads
``geometry/<name>.toml`` (with its includes), validates it and returns a ``Variant``.

Units: mm, N, MPa, kg (masses in files and reports), kg·mm² (inertias), t/mm³ (densities).
Every numeric value in the files carries its provenance: "seed" or "reconstructed" (see
``Provenance``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Literal

Source = Literal["seed", "reconstructed", "derived"]


@dataclass(frozen=True)
class Material:
    name: str                 # e.g. "14220" (16MnCr5), "12050" (C45), "structural_steel"
    E_MPa: float
    nu: float
    density_t_mm3: float      # t/mm³ (7.85e-9 for steel)
    yield_MPa: float
    ultimate_MPa: float


@dataclass(frozen=True)
class Keyway:
    """A parallel-key seat milled into a segment (flat-ended slot, DIN 6885 / ČSN 02 2562)."""
    width_mm: float
    depth_mm: float           # depth into the shaft from the surface (t1)
    length_mm: float          # overall slot length including the round ends
    x_center_mm: float        # axial centre of the slot (absolute x)
    angle_deg: float = 0.0    # angular position of the slot centre line


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

    @property
    def x_end_mm(self) -> float:
        return self.x_start_mm + self.length_mm


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

    @property
    def x_start_mm(self) -> float:
        return self.x_center_mm - 0.5 * self.width_mm

    @property
    def x_end_mm(self) -> float:
        return self.x_center_mm + 0.5 * self.width_mm


@dataclass(frozen=True)
class Attachment:
    """A part carried by the shaft: gear, counterweight, nut.

    The seat is the axial interval of the shaft surface the part bears on; its centrifugal force
    m e ω² acts in the direction ``angle_deg`` and is applied to the half of that seat it presses
    on. Parts bolted to another part (counterweight 1 on the gear) name the same seat.
    Inertias are about the part's own centroid: polar (about the part's axis parallel to x)
    and diametral (about a transverse axis)."""
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

    def force_N(self, rpm: float) -> float:
        """Centrifugal force m e ω² in N at ``rpm``."""
        import math
        omega = rpm * 2.0 * math.pi / 60.0
        return self.mass_kg * self.eccentricity_mm * 1e-3 * omega**2


@dataclass(frozen=True)
class Provenance:
    """Where each value came from: maps a dotted field path (e.g. "segments.seat_gear.length_mm")
    to "seed", "reconstructed" or "derived", plus a free-text note per path."""
    source: MappingProxyType = field(default_factory=lambda: MappingProxyType({}))
    note: MappingProxyType = field(default_factory=lambda: MappingProxyType({}))


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

    @property
    def length_mm(self) -> float:
        return self.segments[-1].x_end_mm - self.segments[0].x_start_mm

    def segment_at(self, x_mm: float) -> Segment:
        for s in self.segments:
            if s.x_start_mm - 1e-9 <= x_mm <= s.x_end_mm + 1e-9:
                return s
        raise ValueError(f"x = {x_mm} mm is outside the shaft")

    def bearing(self, name: str) -> Bearing:
        return next(b for b in self.bearings if b.name == name)

    def attachment(self, name: str) -> Attachment:
        return next(a for a in self.attachments if a.name == name)
