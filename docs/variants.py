"""docs/VARIANTS.md, the variant file format, generated from the loader's own constants.

    python docs/variants.py            # rewrite docs/VARIANTS.md
    python docs/variants.py --check    # exit 1 if docs/VARIANTS.md differs from a fresh run

The plausibility bounds, the smallest fillet and the balance tolerances are the loader's
constants (``shaftfe.model.fields``, ``shaftfe.model.parse``); the other ranges (ν, ρ, the life
exponent, chamfers, keyways) are written here from the variant's rules (``shaftfe.model.
validate``) and are not generated:
change them together. tests/test_variant.py checks that this file renders docs/VARIANTS.md,
that every key of every shipped variant has a row, and that the example loads.
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
OUT = ROOT / "docs" / "VARIANTS.md"


def _p(kind: str) -> str:
    from shaftfe.model.fields import PLAUSIBLE
    lo, hi, unit, _ = PLAUSIBLE[kind]
    return f"[{lo:g}, {hi:g}] {unit}"


def keys() -> list[tuple[str, str, str, str]]:
    from shaftfe.util.limits import PROOF_FACTOR, RPM_CEILING
    """(``--set`` path, unit, allowed, meaning); ``<seg>``, ``<part>`` … stand for names."""
    from shaftfe.model import bearing_stiffness as bs
    from shaftfe.model import loads as ld
    from shaftfe.model.fields import FILLET_MIN_MM
    from shaftfe.model.parse import BALANCE_MASS_RTOL, BALANCE_X2_TOL_POINTS
    from shaftfe.model.validate import CENTROID_REACH_MM, SEGMENT_KINDS, TAPER_MAX_DEG
    from shaftfe.util.units import REF_RPM
    return [
        # top level
        ("name", "—", "non-empty string", "the variant's name (reports, output folders)"),
        ("description", "—", "string", "one line shown in reports"),
        ("use_parts", "—", "list of names in [parts.*]",
         "shared parts (from an include's [parts.*]) mounted on this shaft"),
        # shaft
        ("shaft.name", "—", "string", "drawing name of the shaft"),
        ("shaft.material", "—", "a name in [materials.*]", "shaft material"),
        ("shaft.stock_diameter_mm", "mm", "≥ every segment diameter (optional)",
         "bar stock; checked against the diameters"),
        ("shaft.x_start_mm", "mm", "number (optional, default 0)", "x of the left end face"),
        ("shaft.parting_plane_x_mm", "mm", "on the shaft",
         "crankcase parting plane: origin of the balance table's x_T"),
        ("shaft.clearance_station_x_mm", "mm", "on the shaft (optional)",
         "station where the deflection is checked against the crankshaft clearance"),
        ("shaft.clearance_to_crankshaft_mm", "mm", "number (optional)",
         "smallest clearance to the crankshaft (reported beside that deflection)"),
        ("segments.<seg>.name", "—", "unique string",
         "the segment's name: stress regions, attachment seats, --set paths"),
        ("segments.<seg>.kind", "—", " | ".join(SEGMENT_KINDS),
         "seat: a part or bearing sits on it; thread: modelled at the minor diameter"),
        ("segments.<seg>.length_mm", "mm", _p("length_mm"),
         "segments follow each other from x_start_mm in file order"),
        ("segments.<seg>.diameter_mm", "mm", _p("diameter_mm") + ", ≤ stock",
         "outer diameter (a conical segment's at its left end)"),
        ("segments.<seg>.diameter_right_mm", "mm", _p("diameter_mm") + ", ≤ stock; a half-angle "
         f"≤ {TAPER_MAX_DEG:g}° over the segment's length; absent: a cylinder",
         "a conical (tapered) segment's diameter at its right end: a plain "
         "transition (no keyway, groove, hole, chamfer, seat or load band on it; fillet 0 at "
         "a step beside it); in every model (the beam cuts it into elements 2 % apart in "
         "diameter)"),
        ("segments.<seg>.fillet_mm", "mm",
         f"0 (sharp) or ≥ {FILLET_MIN_MM:g}; ≤ the step height and the smaller segment's "
         "length; ≤ r_s_min_mm of a bearing abutting the shoulder (ISO 582); 0 at a step "
         "beside a conical segment or a DIN 509 undercut",
         "fillet radius at the segment's RIGHT end (the step to the next segment)"),
        ("segments.<seg>.thread", "—", "string (kind = thread)",
         "thread designation, e.g. M10x0.75"),
        ("segments.<seg>.keyways.<i>.width_mm", "mm", "> 0, < diameter", "keyway width"),
        ("segments.<seg>.keyways.<i>.depth_mm", "mm", "0 < depth < radius",
         "shaft keyway depth t1"),
        ("segments.<seg>.keyways.<i>.length_mm", "mm", "≥ width", "keyway length"),
        ("segments.<seg>.keyways.<i>.x_center_mm", "mm", "slot inside its segment",
         "axial centre of the keyway"),
        ("segments.<seg>.keyways.<i>.angle_deg", "deg", "number (default 0)",
         "angular position; 0 = in line with the loads at 0°"),
        ("segments.<seg>.keyways.<i>.bottom_radius_mm", "mm",
         f"0 (sharp, the default) or {FILLET_MIN_MM:g} … min(0.4 × width, half the side "
         "wall's height: depth less the surface's sagitta over the width)",
         "radius r1 of the slot's bottom edges (DIN 6885-1: the drawing's value); meshed in "
         "the 3D models, where the keyway's peak is then a converged stress "
         "(reports/benchmarks/keyway_radius.md), at a cost that grows as 1/r1: refused in "
         "one line where the level's mesh of the fillets would pass 1.5 million dofs; 0: a "
         "sharp edge, whose peak is a value of the mesh and is marked"),
        ("segments.<seg>.chamfer_left_mm", "mm", "0 (none), or > 0 on an outer edge (the "
         "shaft's end, < radius / 2, or a step down to a smaller segment, < the shoulder's "
         "flat height); leaves a straight part", "45° chamfer of the segment's left edge "
         "(axial = radial size); in the solid and the axisymmetric model, not in the beam "
         "or the mass properties"),
        ("segments.<seg>.chamfer_right_mm", "mm", "as chamfer_left_mm", "45° chamfer of the "
         "segment's right edge"),
        ("segments.<seg>.grooves.<i>.kind", "—", "u | din471 | din509_e | din509_f",
         "a circumferential groove: a U groove, a DIN 471 retaining-ring groove whose width "
         "and depth the standard fixes from the segment's diameter, or a DIN 509 undercut "
         "(form E, or F with its recess into the face) at a shoulder, sized by the standard "
         "from the segment's diameter (model/grooves.py: the table, and the outline's "
         "interpretation)"),
        ("segments.<seg>.grooves.<i>.side", "—", "left | right (din509 only): the segment's "
         "end at a step up to a larger segment, whose shoulder has fillet_mm 0",
         "where the undercut sits: in this segment's cylinder beside the larger one's face "
         "(a bearing ring may reach over it to the face)"),
        ("segments.<seg>.grooves.<i>.x_center_mm", "mm", "on the segment's straight part with "
         "0.5 mm to spare; clear of seats, keyways, the hex socket and other grooves by 0.5 mm;"
         " not given for din509 (side places it)", "axial centre of the groove"),
        ("segments.<seg>.grooves.<i>.width_mm", "mm", "> 0 (u); not given for din471 and "
         "din509", "groove width at the surface (DIN 471: m; DIN 509: f)"),
        ("segments.<seg>.grooves.<i>.depth_mm", "mm", "0 < depth < diameter / 4 (u); not given "
         "for din471 and din509", "groove depth below the surface (DIN 471: (d1 − d2)/2; "
         "DIN 509: t1)"),
        ("segments.<seg>.grooves.<i>.radius_mm", "mm", f"≥ {FILLET_MIN_MM:g}, ≤ min(width / 2, "
         "depth); default the full round (u), 0.1 (din471, an assumption: the standard bounds "
         "it); din509: a radius of the standard's rows for the diameter (default the row for "
         "usual loading)", "the bottom corners' radius"),
        ("segments.<seg>.cross_holes.<i>.diameter_mm", "mm", "0 < diameter ≤ 0.4 × the "
         "segment's diameter (the charts' range)", "a transverse hole straight through the "
         "axis (an oil hole); meshed in a 3D zone of the zoned solve"),
        ("segments.<seg>.cross_holes.<i>.x_center_mm", "mm", "on the segment's straight part "
         "with 0.5 mm to spare; clear of seats, keyways, grooves, the hex socket and other "
         "holes by 0.5 mm", "axial position of the hole's axis"),
        ("segments.<seg>.cross_holes.<i>.angle_deg", "deg", "number (default 0)",
         "the hole's direction in the y-z plane; 0 = in line with the loads at 0°"),
        ("shaft.hex_socket.end", "—", "left | right", "end face with the hexagon socket"),
        ("shaft.hex_socket.across_flats_mm", "mm", "> 0, corners inside the end segment",
         "socket size"),
        ("shaft.hex_socket.depth_mm", "mm", "0 < depth < shaft length", "socket depth"),
        ("bearings.<brg>.name", "—", "unique string", "the bearing's name (reports, --set)"),
        ("bearings.<brg>.type", "—", "a name in [bearing_types.*]", "bearing type"),
        ("bearings.<brg>.x_center_mm", "mm", "ring on the shaft, bearings not overlapping",
         "axial centre of the bearing"),
        ("bearings.<brg>.axial", "—", "true | false; exactly one bearing true",
         "the bearing that takes the axial load"),
        # shared tables
        ("materials.<mat>.E_MPa", "MPa", _p("E_MPa"), "Young's modulus"),
        ("materials.<mat>.nu", "—", "0 < ν < 0.5", "Poisson's ratio"),
        ("materials.<mat>.density_t_mm3", "t/mm³", "0 < ρ < 1e-7", "density (steel 7.85e-9)"),
        ("materials.<mat>.yield_MPa", "MPa", _p("strength_MPa"),
         "yield strength R_p (at strength_reference_diameter_mm if given)"),
        ("materials.<mat>.ultimate_MPa", "MPa", "≥ yield_MPa",
         "ultimate strength R_m (likewise); FKM, DIN 743 and the S-N cards read these"),
        ("materials.<mat>.description", "—", "string", "what the material is"),
        ("materials.<mat>.heat_treatment", "—", "string", "the heat treatment of this record"),
        ("materials.<mat>.group", "—", "case_hardening_steel | qt_steel | structural_steel",
         "the FKM / DIN 743 material group (absent: not assessable by the standards)"),
        ("materials.<mat>.strength_reference_diameter_mm", "mm", "[1, 1000] mm",
         "the diameter the strengths hold at (DIN 743-3 d_B = 16 mm)"),
        ("materials.<mat>.case_hardness_HRC", "HRC", "[20, 70]", "case hardness"),
        ("materials.<mat>.case_depth_mm", "mm", "[0.05, 5] mm",
         "case depth (absent: not case hardened)"),
        ("bearing_types.<type>.designation", "—", "string", "catalogue designation"),
        ("bearing_types.<type>.bore_mm", "mm", _p("diameter_mm"), "bore d"),
        ("bearing_types.<type>.outer_diameter_mm", "mm", "number", "outer diameter D"),
        ("bearing_types.<type>.width_mm", "mm", _p("length_mm"), "width B (the seat patch)"),
        ("bearing_types.<type>.C_N", "N", _p("C_N"), "basic dynamic load rating (ISO 281)"),
        ("bearing_types.<type>.C0_N", "N", _p("C_N"), "basic static load rating"),
        ("bearing_types.<type>.K_N_per_mm", "N/mm", "[[K11, K12], [K21, K22]], symmetric, "
         "positive definite, eigenvalues in " + _p("K_N_per_mm") + f"; a ball bearing's in "
         f"1/{bs.BELOW:g} … {bs.ABOVE:g} × the estimate from its d, D, C, rows and contact angle "
         "(Palmgren / ISO 281, shaftfe.model.bearing_stiffness)",
         "2×2 radial stiffness (y, z) of the bearing's remote point"),
        ("bearing_types.<type>.rolling_element", "—", " | ".join(bs.KINDS) + " (default ball)",
         "rolling elements (a roller type has no stiffness estimate)"),
        ("bearing_types.<type>.rows", "—", "1 … 4 (default 1)", "rows of rolling elements"),
        ("bearing_types.<type>.contact_angle_deg", "deg", "[0, 45] (default 0)",
         "nominal contact angle α"),
        ("bearing_types.<type>.tilt_stiffness_Nmm_per_rad", "N·mm/rad", "≥ 0 (default 0)",
         "tilting stiffness"),
        ("bearing_types.<type>.life_exponent", "—", "[1, 10] (default 3)",
         "ISO 281 exponent p: 3 ball, 10/3 roller"),
        ("bearing_types.<type>.chamfer_mm", "mm", "≥ r_s_min_mm, < width/4 (default 0)",
         "ring chamfer (the seat patch is shortened by it)"),
        ("bearing_types.<type>.r_s_min_mm", "mm", "≥ 0 (default 0)",
         "smallest ring corner radius (ISO 15): the largest shoulder fillet it seats against"),
        # parts and attachments (the same keys)
        ("attachments.<part>.name", "—", "unique string (a part: its [parts.*] key)",
         "the part's name"),
        ("attachments.<part>.seat", "—", "a segment name (or seat_x_mm = [a, b])",
         "the seat the part's force acts on (pressure on its pressed half)"),
        ("attachments.<part>.seat_x_mm", "mm", "[x_start, x_end] on the shaft",
         "a seat interval instead of a segment"),
        ("attachments.<part>.mass_kg", "kg", _p("mass_kg"), "mass m of the part"),
        ("attachments.<part>.eccentricity_mm", "mm", _p("eccentricity_mm"),
         "centroid offset e from the axis: force m e ω²"),
        ("attachments.<part>.angle_deg", "deg", "number (default 0)",
         "angular position of the centroid (0 = the counterweights' direction)"),
        ("attachments.<part>.x_centroid_mm", "mm", f"within {CENTROID_REACH_MM:g} mm of the shaft",
         "axial position of the centroid (mass properties, rotor)"),
        ("attachments.<part>.polar_inertia_kg_mm2", "kg·mm²", "≥ 0 (default 0)",
         "polar moment of inertia about its own centroid"),
        ("attachments.<part>.diametral_inertia_kg_mm2", "kg·mm²", "≥ 0 (default 0)",
         "diametral moment of inertia about its own centroid"),
        ("attachments.<part>.material", "—", "a name in [materials.*]", "part material"),
        ("attachments.<part>.seed_load_case", "—", "true | false (default false)",
         "loaded in the seed's own load case (--seed-load-case)"),
        ("attachments.<part>.description", "—", "string", "what the part is"),
        ("attachments.<part>.part", "—", "string (accepted, not read)",
         "older files' reference to the part; ignored"),
        ("attachments.<part>.shape.<key>", "mm, deg, —", "numbers ≥ 0; kind a string",
         "the shape the mass properties were derived from (documentation: the analyses "
         "read mass_kg, eccentricity_mm and the inertias, not the shape)"),
        # loads
        ("loads.<load>.name", "—", "unique string (not a part's name)",
         "the load's name: load-case factors, tables, --set paths"),
        ("loads.<load>.kind", "—", " | ".join(ld.KINDS), "what the load is (see Loads)"),
        ("loads.<load>.x_mm", "mm", "on the shaft (on the seat with seat)",
         "axial position of the resultant"),
        ("loads.<load>.seat", "—", "a segment name (instead of x_mm)",
         "the load is spread over this segment as a remote load (x_mm: default its centre)"),
        ("loads.<load>.width_mm", "mm", f"(0, shaft length] (default {ld.DEFAULT_BAND_MM:g}; "
         "not with seat)", "the band of surface a load at x_mm is spread over in 3D"),
        ("loads.<load>.F_N", "N", f"|F| ≤ {ld.F_MAX_N:.0e}",
         "force (kind force: radial along angle_deg; axial_force: along +x)"),
        ("loads.<load>.M_Nmm", "N·mm", f"|M| ≤ {ld.M_MAX_NMM:.0e}",
         "bending moment; its vector along angle_deg in the y-z plane"),
        ("loads.<load>.T_Nmm", "N·mm", f"|T| ≤ {ld.M_MAX_NMM:.0e}",
         "torque about +x (torque), or the torque the mesh puts on this shaft (gear_mesh)"),
        ("loads.<load>.angle_deg", "deg", "number (default 0; not for torque, axial_force)",
         "direction in the y-z plane: 0 = +y, 90 = +z; gear_mesh: towards the contact"),
        ("loads.<load>.frame", "—", "space | shaft (default space; force and moment only)",
         "fixed in space (rotating bending in fatigue) or turning with the shaft"),
        ("loads.<load>.scales_with", "—", "constant | rpm2 | a channel name (default constant)",
         "speed law: as written; × (rpm/ref_rpm)²; × channel/channel_ref"),
        ("loads.<load>.ref_rpm", "rpm", f"(0, 1e5] (default {REF_RPM:g}; only rpm2)",
         "the speed the magnitude is written at"),
        ("loads.<load>.channel_ref", "channel unit", "≠ 0 (default 1; only a channel law)",
         "the channel value the magnitude is written for"),
        ("loads.<load>.module_mm", "mm", f"{ld.GEAR_MODULE_MM[0]:g} … "
         f"{ld.GEAR_MODULE_MM[1]:g} (gear_mesh)", "normal module m_n"),
        ("loads.<load>.teeth", "—", f"whole number ≥ {ld.GEAR_MIN_TEETH} (gear_mesh)",
         "number of teeth z"),
        ("loads.<load>.pressure_angle_deg", "deg", f"{ld.GEAR_PRESSURE_DEG[0]:g} … "
         f"{ld.GEAR_PRESSURE_DEG[1]:g} (default 20)", "normal pressure angle α_n"),
        ("loads.<load>.helix_angle_deg", "deg", f"|β| < {ld.GEAR_HELIX_MAX_DEG:g} (default 0)",
         "helix angle; its sign sets the axial force's direction (F_a = F_t tan β along +x)"),
        ("loads.<load>.pitch_diameter_mm", "mm", "within 2 m_n of m_n z / cos β; root "
         "d − 2.5 m_n above the seat (default m_n z / cos β)", "the diameter the forces act at"),
        ("loads.<load>.g_mm_s2", "mm/s²", "|g| ≤ 1e6 (default 9810; gravity)",
         "acceleration on the shaft's and every part's mass"),
        ("bearings.<brg>.holds_torsion", "—", "true | false (default false)",
         "the support reacts torque about the axis (else the torques must sum to zero)"),
        ("load_cases.<case>.name", "—", "unique string", "the case's name"),
        ("load_cases.<case>.rpm", "rpm", "[0, 20000]", "the speed of the case"),
        ("load_cases.<case>.factors", "—", "{load = factor 0 … 100}; \"parts\" = every part",
         "a factor per load (default 1)"),
        ("load_cases.<case>.channels", "channel unit", "{channel = value}",
         "the value of each channel in the case (default: the loads' channel_ref)"),
        ("load_cases.<case>.check", "—", "\"static\" or absent",
         "the case of the static-strength check (FKM static, DIN 743 S_F)"),
        # balance statement
        ("balance.X2_percent", "%", f"within {BALANCE_X2_TOL_POINTS:g} points of "
         "Σ m e / (m_pos R) of the parts", "stated balance ratio"),
        ("balance.mass_kg", "kg", f"within {100 * BALANCE_MASS_RTOL:g} % of the parts' and "
         "shaft's mass", "stated mass of the whole balancer"),
        ("balance.gamma2_mm", "mm", "number", "stated eccentricity of the whole balancer"),
        ("balance.x_T_mm", "mm", "number", "stated axial centroid from the parting plane"),
        ("balance.m_pos_kg", "kg", "number (default 0: X2 not checked)",
         "the crank mechanism's reciprocating mass"),
        ("balance.crank_radius_mm", "mm", "number (default 0: X2 not checked)",
         "crank radius R"),
        # duty
        ("duty.speed_range_rpm", "rpm", f"[low, high], 0 ≤ low < high ≤ {RPM_CEILING:g}; high "
         "≤ the engine's max_rpm", "lowest running (idle) and highest speed: high bounds every "
         "rpm history (fatigue, report) unless --allow-overspeed"),
        ("duty.design_speeds_rpm", "rpm", f"each in (0, {PROOF_FACTOR:g} × high]",
         "the report's static speeds; the first is static's and beam's default --rpm"),
        ("duty.campbell_range_rpm", "rpm", f"[low, high], 0 ≤ low < high ≤ {RPM_CEILING:g}",
         "the report's Campbell sweep"),
        ("duty.spectrum", "—", "a file: relative to the file stating [duty], else in "
         "loadspectra/", "the rpm history of the report"),
        ("duty.design_life_h", "h", "in (0, 1e7]; or design_life_blocks, not both",
         "design life in hours of the history"),
        ("duty.design_life_blocks", "—", "in [1, 1e12]; or design_life_h",
         "design life in passes of the history's block (the seed's 1e7)"),
        ("duty.engine", "—", "a .toml file: relative, else geometry/engines/NAME.toml",
         "the engine the shaft balances: the report's balancing section (none: no section)"),
        ("duty.sn_curve", "—", "a card of geometry/common/sn_curves.toml", "the seed method's "
         "S-N card (default: the card whose material is the shaft's)"),
        ("duty.elements", "—", "a file like common/elements.toml: relative, else "
         "geometry/common/", "the drive, key and gear-pair data of the element checks (none: "
         "no key or gear-pair check)"),
    ]


EXAMPLE = (ROOT / "docs" / "examples" / "minimal.toml")
LOADS_EXAMPLE = (ROOT / "geometry" / "examples" / "drive_shaft_c.toml")


def render() -> str:
    from shaftfe.model.parse import BALANCE_MASS_RTOL, BALANCE_X2_TOL_POINTS
    rows = "\n".join(f"| `{p}` | {u} | {a} | {m} |" for p, u, a, m in keys())
    example = EXAMPLE.read_text(encoding="utf-8").rstrip()
    loads_example = LOADS_EXAMPLE.read_text(encoding="utf-8").rstrip()
    return f"""# Variant files

(generated by `python docs/variants.py`; do not edit by hand)

A variant is one balancer shaft with its bearings and the parts mounted on it:
`geometry/<name>.toml`, read by `shaftfe.load_variant(name)` and by every command's
`--variant NAME` (or `--variant path/to/file.toml`). `shaftfe variant check FILE` validates a
file: one line naming the file, the key and the allowed range if anything is wrong.

## Writing your own

* **Start from a copy**: `shaftfe variant new my_shaft --from x2_57` writes
  `geometry/my_shaft.toml`, the variant with its includes resolved into one self-contained file
  (nothing else to re-point), which you then edit. Add `--set PATH=VALUE` to write the copy with
  changes, `--out FILE` to write it elsewhere. It never overwrites a file.
* **Change one key for one run**: every analysis command (`static`, `fatigue`, `report`,
  `campbell`, `modal`, `beam`, `mesh`, `variant show|check`) takes `--set PATH=VALUE`,
  repeatable, e.g. `shaftfe static --variant x2_57 --set segments.collar.fillet_mm=0.5`; the
  API takes `load_variant("x2_57", {{"segments.collar.fillet_mm": 0.5}})`. The value is checked
  as if the file said it, the error names the `--set` (or, for a check of another key that
  the value breaks, the file *with* the `--set`), a wrong path lists the nearest names,
  and the overrides are recorded in summary.json (`inputs.overrides`) and the report's inputs;
  an overridden value's provenance tag becomes `set`. A change of a part's mass or eccentricity
  must keep the file's `[balance]` statement true (within {100 * BALANCE_MASS_RTOL:g} % of mass,
  {BALANCE_X2_TOL_POINTS:g} points of X2), or
  be accompanied by `--set balance.mass_kg=…` / `balance.X2_percent=…`.
* **Or from scratch**: the minimal complete file at the end of this page.

## Units, provenance, includes

* **Units are in the key names**: `_mm`, `_kg`, `_N`, `_MPa`, `_deg`, `_t_mm3`, `_kg_mm2`,
  `_N_per_mm`, `_Nmm_per_rad`. Inside the solver: mm, N, MPa, t/mm³, s.
* **Provenance**: every numeric key of a table must be listed in exactly one of the lists
  `seed` (a figure of the source documents), `reconstructed` (fitted or assumed: say to what in
  the table's `note`), `derived` (computed from other values) or `standard` (a catalogue or a
  standard). A key without one, or in two, is an error. The report shows the tags.
* **Includes**: `include = ["common/materials.toml", …]` (paths relative to the including
  file) merges other files first. A key may be defined in one file only; the shared tables
  `[materials.*]`, `[bearing_types.*]` and `[parts.*]` are merged entry by entry (each entry in
  one file only). Include cycles are an error.
* **use_parts**: names of `[parts.*]` entries (usually from `common/parts.toml`) mounted on this
  shaft, in addition to the file's own `[[attachments]]`. A part and an attachment have the same
  keys; the parts are shared between variants, the attachments are the variant's own.
* **Order**: segments follow each other along x from the left end face (`shaft.x_start_mm`,
  default 0) in file order; a segment's `fillet_mm` is the fillet at its right end.

## Duty: what the shaft is asked to do

The optional `[duty]` table states the shaft's speeds, its rpm history and design life, the
engine it balances and the data of its element checks (every key below). The shipped x2_*
variants include `common/duty_vm450.toml`, the seed's duty (VM 450, 1200-9500 rpm, design speeds
10 000 and 7000 rpm, `rpm.dat`, 1e7 blocks), tagged `seed`. Nothing falls back to the seed's
values: a variant without `[duty]` gets none of them, and a command that needs one asks for it
on its command line (one line naming the field, the file and the option). The checks run only
where their element is: balancing with an engine, the key check where a segment has a keyway,
the gear-pair check where the variant has a part named `gear` (both with `elements`); the
seed's comparison figures appear only for the seed's engine and variant. The shaft's material
(`shaft.material`) selects the strength card of FKM and DIN 743 and, without `sn_curve`, the
seed method's S-N card (`sn_curves.toml` entry with that `material`).

## Every key

`--set` paths name list entries by their `name` (`segments.collar`, `bearings.free_side`,
`attachments.counterweight_2`) and keyways by their index in their segment (`keyways.0`). The
parts of `use_parts` are set through `parts.<part>.<key>` (they live in that table); the
`attachments.<part>.<key>` rows hold for both. `<seg>`, `<brg>`, `<mat>`, `<type>`, `<part>`
stand for the names in your files. Every table may also carry `note` (a string) and the
provenance lists; they cannot be `--set`.

| path | unit | allowed | meaning |
|---|---|---|---|
{rows}

## Loads

Every part's centrifugal force m e ω² is a load of the `rpm2` law: it acts at the part's
centroid (`x_centroid_mm`) and enters the shaft through its seat as a force and the moment of
that force about the seat centre (`--seed-load-case` keeps the seed's placement: the force at
the seat centre as a pressure on the half seat the part presses on). Other loads are
`[[loads]]` tables. geometry/examples/x2_57_driven.toml is x2_57 with its drive loads
(`shaftfe static --variant geometry/examples/x2_57_driven.toml`); its loads file
(tests/test_loads.py reads both):

```toml
{loads_example}
```

Kinds: `force` (`F_N` along `angle_deg`), `moment` (`M_Nmm`, its vector along `angle_deg`),
`torque` (`T_Nmm` about +x), `axial_force` (`F_N` along +x), `gear_mesh` (the nominal forces
of ISO 6336-1 at the pitch circle: F_t = 2T/d, F_r = |F_t| tan α_n / cos β towards the axis,
F_a = F_t tan β, and the moment F_a d/2 of the axial force), `gravity` (`g_mm_s2` along
`angle_deg` on the shaft's and every part's mass). The solvers work in the frame that turns
with the shaft: a gear mesh's transverse forces, gravity and a `force` or `moment` with
`frame = "space"` (the default) are fixed in space, so a static run shows them at the instant
their direction is `angle_deg` in the shaft's frame, and in fatigue they are rotating bending;
`frame = "shaft"` turns with the shaft (an unbalance). Torques must form a path: per speed law
they sum to zero, or a bearing says `holds_torsion = true`; a torque with nothing to react it
is refused. A load case sets the speed, a factor per load (`parts` for every part's m e ω²)
and the value of each channel.

## A minimal complete file

`shaftfe variant check docs/examples/minimal.toml` accepts it (tests/test_variant.py runs it):

```toml
{example}
```
"""


def main() -> int:
    text = render()
    if "--check" in sys.argv[1:]:
        same = OUT.exists() and OUT.read_text(encoding="utf-8") == text
        print("docs/VARIANTS.md is up to date" if same else
              "docs/VARIANTS.md differs: run python docs/variants.py")
        return 0 if same else 1
    OUT.write_text(text, encoding="utf-8")
    print(f"wrote {OUT.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
