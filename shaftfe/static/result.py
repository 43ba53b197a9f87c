"""What a static solve returns: per-rpm cases (bearing reactions and L10h, stations, peak
stresses) and the reference solution at REF_RPM (frozen; arrays read-only by convention)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field

import numpy as np

from shaftfe.solid.features import fillet_region, kind_of, segment_of
from shaftfe.static.model import StaticOptions
from shaftfe.util.fmt import json_clean
from shaftfe.util.notices import warn

# A peak stress of the 3D path is the maximum of the fitted surface stress (fe.surface), which
# can lie between the nodes and above the largest nodal value that a VTU, `shaftfe view` and the
# pictures show: every place that prints a peak names it so.
PEAK_FIT_LABEL = "surface fit between the nodes"

# A resolved fillet carries the peak of its step: the flat shoulder face beside it is loaded less
# by the step itself (its largest value sits at the tangent edge, below the fillet's maximum).
# The face can still read a little more than a lightly loaded fillet where a neighbouring seat or
# keyway loads it (x2_57's end fillet cw2_seat at the coarse level: face 27.6 MPa, fillet
# 25.4 MPa, 1.08 ×), while a fillet the mesh does not resolve reads orders of magnitude off (a
# 0.05 mm collar fillet at the coarse level: face 350 281 MPa, fillet 1 312 MPa, 267 ×). A face
# above twice its own fillet separates the two: neither value is then a stress.
UNRESOLVED_FACE_OVER_FILLET = 2.0


def unresolved_fillets(peak_of: dict[str, float],
                       basis: str = PEAK_FIT_LABEL) -> dict[str, str]:
    """{fillet region: why it is not resolved} from each region's filtered peak von Mises
    (``peak_of``: region -> MPa; ``basis`` names which peak: the fitted one of a fresh solve, or
    the largest nodal value of a cached reference): a ``shoulder:<seg>`` face reading more than
    ``UNRESOLVED_FACE_OVER_FILLET`` × its ``fillet:<seg>``."""
    out = {}
    for region, face in peak_of.items():
        if kind_of(region) != "shoulder":
            continue
        fillet = fillet_region(segment_of(region))
        f = peak_of.get(fillet)
        if f is not None and f > 0 and face > UNRESOLVED_FACE_OVER_FILLET * f:
            out[fillet] = (f"the mesh does not resolve this fillet: the shoulder face beside "
                           f"it reads {face:.4g} MPa, {face / f:.3g} × the fillet's {f:.4g} MPa "
                           f"({basis}), "
                           "which a resolved fillet does not allow; neither is a stress to "
                           "assess (a finer level, or the axisymmetric model --model "
                           "axisymmetric)")
    return out


def warn_unresolved_fillets(peak_of: dict[str, float],
                            basis: str = PEAK_FIT_LABEL) -> dict[str, str]:
    """``unresolved_fillets`` with a visible warning for each (``shaftfe.util.notices``)."""
    out = unresolved_fillets(peak_of, basis)
    for region, why in out.items():
        warn("unresolved-fillet", region, why)
    return out


@dataclass(frozen=True)
class BearingReaction:
    """Force the support exerts ON the shaft at the remote point (bearing load = −this)."""
    name: str
    x_mm: float
    Fx_N: float
    Fy_N: float
    Fz_N: float
    F_radial_N: float
    uy_mm: float                 # remote-point radial translation
    uz_mm: float
    L10h: float | None           # ISO 281 basic, hours (None: unloaded or rpm 0)
    C_N: float
    life_exponent: float
    Mx_Nmm: float | None = None  # torque reaction about +x (a bearing that holds torsion)


@dataclass(frozen=True)
class Station:
    name: str
    x_mm: float
    uy_mm: float
    uz_mm: float
    u_mm: float


@dataclass(frozen=True)
class StaticCase:
    rpm: float
    scale: float                               # (rpm / ref_rpm)²: the loads' ratio
    bearings: tuple[BearingReaction, ...]
    stations: tuple[Station, ...]
    max_deflection_mm: float                   # max nodal |(u_y, u_z)|
    max_deflection_xyz_mm: tuple[float, float, float]
    max_axis_deflection_mm: float              # max over the axis line
    peaks: tuple                               # recovery.RegionPeak per region
    peak_von_mises_MPa: float                  # filtered, whole shaft
    peak_von_mises_xyz_mm: tuple[float, float, float]
    peak_von_mises_unfiltered_MPa: float
    peak_von_mises_unfiltered_xyz_mm: tuple[float, float, float]
    load_sum_N: tuple[float, float, float]
    reaction_sum_N: tuple[float, float, float]
    equilibrium_residual: float                # |Σ reactions + Σ loads| / |Σ loads|
    beam: dict | None = None                   # shaftfe.beam.model numbers side by side
    spin_softening_N: dict | None = None       # part -> (F_y, F_z) of m ω² ū_c at its
                                               # centroid, "shaft" -> its resultant (None: off)
    case: str = ""                             # the load case's name ("" = the plain speed)
    factors: dict = field(default_factory=dict)  # pattern label -> its factor in this case


@dataclass(frozen=True, eq=False)
class StaticResult:
    variant: str
    variant_hash: str
    options: StaticOptions
    ref_rpm: float
    n_nodes: int
    n_elements: int
    n_dofs: int
    mesh_key: str
    u_ref: np.ndarray = field(repr=False)          # (ndof,) at REF_RPM
    stress_ref: np.ndarray = field(repr=False)     # (6, n_nodes) at REF_RPM, xx yy zz xy yz xz
    von_mises_ref: np.ndarray = field(repr=False)
    axis_x: np.ndarray = field(repr=False)         # deflection line (FE, on the axis)
    axis_u_ref: np.ndarray = field(repr=False)     # (n, 3) at REF_RPM
    cases: tuple[StaticCase, ...] = ()
    diagnostics: dict = field(default_factory=dict)    # results only: identical run to run
    error_estimate: dict | None = None
    # fillet region -> (low, high) %: this level's error against the axisymmetric truth
    # (static.measured_errors.shoulder_bars), for the fillets outside every keyway's / the
    # hex's zone whose D/d, r/d lie in the measured grid's hull; the span fillets outside
    # it: region -> why
    truth_error_bar_pct: dict = field(default_factory=dict)
    truth_bar_notes: dict = field(default_factory=dict)
    # fillet region -> why the mesh does not resolve it (``unresolved_fillets``; the same at
    # every speed, the cases being the reference × a factor)
    unresolved_fillets: dict = field(default_factory=dict)
    notes: tuple[str, ...] = ()
    mesh: object = field(default=None, repr=False)
    run: dict = field(default_factory=dict)            # wall-clock seconds, mesh_from_cache
    # with spin softening and ``solve_static(..., linear_stress=True)``: the unsoftened stress
    # at ref_rpm (6, n_nodes); the softened one is ``stress_ref`` (fatigue's β per node)
    stress_linear_ref: np.ndarray | None = field(default=None, repr=False)
    case_name: str = ""                                # the load case named (--case), or ""
    patterns: tuple = ()                               # per load pattern: summary dicts
    # per pattern key: u (ndof,) and the unsoftened stress (6, n_nodes) at the pattern's
    # written magnitudes (factor 1): a case is Σ factor × these (fatigue's Σ_k σ_k L_k(t));
    # read-only mappings (stress absent with spin softening unless linear_stress)
    pattern_u: Mapping = field(default_factory=dict, repr=False)
    pattern_stress: Mapping = field(default_factory=dict, repr=False)

    def case(self, rpm: float) -> StaticCase:
        return next(c for c in self.cases if math.isclose(c.rpm, rpm))

    def to_dict(self) -> dict:
        return json_clean({
            "variant": self.variant, "variant_hash": self.variant_hash,
            "options": asdict(self.options), "load_case": self.options.load_case,
            "case": self.case_name or None, "patterns": list(self.patterns),
            "ref_rpm": self.ref_rpm,
            "mesh": {"key": self.mesh_key, "nodes": self.n_nodes, "elements": self.n_elements,
                     "dofs": self.n_dofs},
            "cases": [asdict(c) for c in self.cases],
            "diagnostics": self.diagnostics, "error_estimate": self.error_estimate,
            "truth_error_bar_pct": self.truth_error_bar_pct,
            "truth_bar_notes": self.truth_bar_notes,
            "unresolved_fillets": self.unresolved_fillets,
            "notes": list(self.notes), "run": self.run,
        })


