"""The bad-input catalogue: every command, every class of malformed or hostile input that a
robustness audit found (output locations, undecodable files, unit mistakes, operating values,
supports, spectra). Each case must give

* exit code 2,
* exactly one line on stderr, naming the file or option and the field (``expect``),
* no traceback,
* and leave the work space as it was: no output file, no staging directory, no --out change.

The commands run in-process through ``shaftfe.cli.main`` (what the ``shaftfe`` script calls),
in a work space with a copy of the geometry whose files each case edits; nothing is solved.
"""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import numpy as np
import pytest

from shaftfe.cli import main
from shaftfe.util.paths import GEOMETRY_DIR

RPM_DAT = str(GEOMETRY_DIR.parent / "loadspectra" / "rpm.dat")
SHAFT, BEAR, MATS = "common/shaft_c.toml", "common/bearings.toml", "common/materials.toml"
COLLAR = 'name = "collar"\nkind = "plain"\nlength_mm = 17.5\ndiameter_mm = 22.0'
BOSS = 'name = "gear_hub_boss"\nkind = "plain"\nlength_mm = 13.5\ndiameter_mm = 17.0'
SEAT_G = 'name = "bearing_seat_gear"\nkind = "seat"\nlength_mm = 17.5'
FREE_X = 'name = "free_side"\ntype = "zkl_3203"\nx_center_mm = 73.25'
CW2 = "mass_kg = 0.24\neccentricity_mm = 20.23"
K = "K_N_per_mm = [[35030.0, 8756.0], [8756.0, 35030.0]]"

# a groove table appended to the collar's segment (Ø22, straight on [47, 64.5]) or to the
# free bearing's seat (Ø17, the ring on [64.5, 82])
COLLAR_END = 'spot (§8.3)."""\n'
FREE_END = 'axially free."\n'


def _groove(at: str, body: str, table: str = "grooves") -> tuple[str, str, str]:
    """One or more groove (or ``table``) tables after ``at``, each with its numbers'
    provenance."""
    head = f"[[shaft.segments.{table}]]\n"
    tables = []
    for t in body.split(head):
        keys = [ln.split(" = ")[0] for ln in t.strip().splitlines() if ln.split(" = ")[0]
                not in ("kind", "side")]
        tables.append(t.strip() + "\nreconstructed = [" + ", ".join(f'"{k}"' for k in keys)
                      + "]")
    return (SHAFT, at, at + "".join(f"{head}{t}\n" for t in tables))


COLLAR_CHAMFER = ('diameter_mm = 22.0\nfillet_mm = 0.6\n'
                  'reconstructed = ["length_mm", "diameter_mm", "fillet_mm"]')
SEAT_G_CHAMFER = ('diameter_mm = 17.0\nfillet_mm = 0.6\nseed = ["length_mm", "diameter_mm"]\n'
                  'reconstructed = ["fillet_mm"]')


# id -> (file, old text, new text): one edit of the copied x2_57 files
VARIANT_EDITS = {
    "groove_deeper_than_allowed": _groove(COLLAR_END, 'kind = "u"\nx_center_mm = 55.0\n'
                                          'width_mm = 3.0\ndepth_mm = 6.0'),
    "groove_radius_larger_than_groove": _groove(COLLAR_END, 'kind = "u"\nx_center_mm = 55.0\n'
                                                'width_mm = 2.0\ndepth_mm = 1.0\n'
                                                'radius_mm = 1.5'),
    "groove_under_bearing_seat": _groove(FREE_END, 'kind = "din471"\nx_center_mm = 73.0'),
    "groove_onto_the_shoulder": _groove(COLLAR_END, 'kind = "u"\nx_center_mm = 48.0\n'
                                  'width_mm = 2.0\ndepth_mm = 1.0'),
    "grooves_overlapping": _groove(COLLAR_END, 'kind = "u"\nx_center_mm = 55.0\n'
                                   'width_mm = 2.0\ndepth_mm = 1.0\n'
                                   '[[shaft.segments.grooves]]\nkind = "u"\n'
                                   'x_center_mm = 56.0\nwidth_mm = 2.0\ndepth_mm = 1.0'),
    "din471_on_a_diameter_not_in_its_table": _groove(COLLAR_END,
                                                     'kind = "din471"\nx_center_mm = 55.0\n'
                                                     'depth_mm = 0.4'),
    "din509_given_a_position": _groove(COLLAR_END, 'kind = "din509_e"\nx_center_mm = 55.0'),
    "din509_at_a_step_down": _groove(COLLAR_END, 'kind = "din509_e"\nside = "left"'),
    "din509_beside_a_fillet": _groove(FREE_END, 'kind = "din509_f"\nside = "left"'),
    "din509_radius_not_in_its_table": _groove(FREE_END, 'kind = "din509_e"\nside = "left"\n'
                                              'radius_mm = 0.7'),
    "fillet_beside_a_cone": (SHAFT, 'name = "gear_seat"\nkind = "seat"\nlength_mm = 10.0\n'
                         'diameter_mm = 17.0', 'name = "gear_seat"\nkind = "seat"\n'
                         'length_mm = 10.0\ndiameter_mm = 17.0\ndiameter_right_mm = 16.0\n'
                         'derived = ["diameter_right_mm"]'),
    "chamfer_deeper_than_the_shoulder": (SHAFT, COLLAR_CHAMFER, COLLAR_CHAMFER.replace(
        "fillet_mm = 0.6\n", "fillet_mm = 0.6\nchamfer_left_mm = 2.0\n").replace(
        '"fillet_mm"]', '"fillet_mm", "chamfer_left_mm"]')),
    "chamfer_on_an_inner_edge": (SHAFT, SEAT_G_CHAMFER, SEAT_G_CHAMFER.replace(
        "diameter_mm = 17.0\n", "diameter_mm = 17.0\nchamfer_right_mm = 0.5\n").replace(
        'reconstructed = ["', 'reconstructed = ["chamfer_right_mm", "')),
    "cross_hole_too_large": _groove(COLLAR_END, 'diameter_mm = 12.0\nx_center_mm = 55.0',
                                    "cross_holes"),
    "cross_hole_under_bearing_seat": _groove(FREE_END, 'diameter_mm = 3.0\n'
                                             'x_center_mm = 73.0', "cross_holes"),
    "cross_hole_on_a_groove": (SHAFT, COLLAR_END, _groove(
        COLLAR_END, 'kind = "u"\nx_center_mm = 55.0\nwidth_mm = 2.0\ndepth_mm = 1.0')[2]
        + _groove("", 'diameter_mm = 3.0\nx_center_mm = 56.0', "cross_holes")[2]),
    "diameter_in_metres": (SHAFT, COLLAR, COLLAR.replace("22.0", "0.022")),
    "boss_diameter_in_metres": (SHAFT, BOSS, BOSS.replace("17.0", "0.017")),
    "mass_in_grams": ("x2_57.toml", CW2, CW2.replace("0.24", "240.0")),
    "eccentricity_in_metres": ("x2_57.toml", CW2, CW2.replace("20.23", "0.02023")),
    "E_in_GPa": (MATS, 'blank-hardened"\ngroup = "case_hardening_steel"\nE_MPa = 210000.0',
                 'blank-hardened"\ngroup = "case_hardening_steel"\nE_MPa = 210.0'),
    "C_in_kN": (BEAR, "C_N = 14418.0", "C_N = 14.418"),
    "balance_table_contradicts_parts": ("x2_57.toml", "mass_kg = 0.761", "mass_kg = 7.61"),
    "X2_contradicts_parts": ("x2_57.toml", "X2_percent = 57.0", "X2_percent = 23.0"),
    "bearings_at_the_same_x": (SHAFT, FREE_X, FREE_X.replace("73.25", "38.25")),
    "bearing_stiffness_tiny": (BEAR, K, "K_N_per_mm = [[1e-9, 0.0], [0.0, 1e-9]]"),
    "bearing_stiffness_inf": (BEAR, K, "K_N_per_mm = [[inf, 0.0], [0.0, inf]]"),
    "bearing_stiffness_not_definite": (BEAR, K, "K_N_per_mm = [[1000.0, 2000.0], "
                                       "[2000.0, 1000.0]]"),
    "fillet_above_bearing_corner": (BEAR, "r_s_min_mm = 0.6", "r_s_min_mm = 0.3"),
    "fillet_into_bearing_seat": (SHAFT, 'diameter_mm = 22.0\nfillet_mm = 0.6',
                                 'diameter_mm = 22.0\nfillet_mm = 2.4'),
    "nan_in_shape": ("x2_57.toml", "thickness_mm = 25.0", "thickness_mm = nan"),
    "hex_socket_through_thread": (SHAFT, 'end = "right"', 'end = "left"'),
    "keyway_too_deep": (SHAFT, "depth_mm = 3.0\nlength_mm = 8.0\nx_center_mm = 94.5",
                        "depth_mm = 8.4\nlength_mm = 8.0\nx_center_mm = 94.5"),
    "sliver_segment": (SHAFT, SEAT_G, SEAT_G.replace("17.5", "0.001")),
    "negative_tilt_stiffness": (BEAR, "tilt_stiffness_Nmm_per_rad = 0.0",
                                "tilt_stiffness_Nmm_per_rad = -1e9"),
    "life_exponent_zero": (BEAR, "life_exponent = 3.0", "life_exponent = 0.0"),
    "keyways_not_a_list": (SHAFT, '[[shaft.segments.keyways]]\nwidth_mm = 5.0\ndepth_mm = 3.0\n'
                           'length_mm = 8.0\nx_center_mm = 94.5',
                           'keyways = true\n[[shaft.segments.keyways_x]]\nwidth_mm = 5.0\n'
                           'depth_mm = 3.0\nlength_mm = 8.0\nx_center_mm = 94.5'),
    "centroid_far_off_the_shaft": ("x2_57.toml", "x_centroid_mm = 94.5",
                                   "x_centroid_mm = 94500.0"),
    "fillet_in_metres": (SHAFT, 'diameter_mm = 22.0\nfillet_mm = 0.6',
                         'diameter_mm = 22.0\nfillet_mm = 0.0006'),
    "density_in_kg_per_mm3": (MATS, 'blank-hardened"\ngroup = "case_hardening_steel"\n'
                              'E_MPa = 210000.0\nnu = 0.3\ndensity_t_mm3 = 7.85e-9',
                              'blank-hardened"\ngroup = "case_hardening_steel"\n'
                              'E_MPa = 210000.0\nnu = 0.3\ndensity_t_mm3 = 7.85e-6'),
}
# id -> what the one stderr line must name (file and field): the file the value is written in
# (an include's, e.g. common/shaft_c.toml for the shaft), whichever rule refuses it (the loader
# names the files of the variant's rules' errors: ``model.origins``)
VARIANT_EXPECT = {
    "groove_deeper_than_allowed": ["shaft_c.toml", "segments[4].grooves[0].depth_mm",
                                   "radius / 2"],
    "groove_radius_larger_than_groove": ["shaft_c.toml", "grooves[0].radius_mm"],
    "groove_under_bearing_seat": ["shaft_c.toml", "segments[5].grooves[0].x_center_mm",
                                  "bearing:free_side"],
    "groove_onto_the_shoulder": ["shaft_c.toml", "grooves[0].x_center_mm", "0.5 mm to spare"],
    "grooves_overlapping": ["shaft_c.toml", "grooves[1].x_center_mm", "another notch"],
    "din471_on_a_diameter_not_in_its_table": ["shaft_c.toml", "grooves[0].depth_mm",
                                              "DIN 471 fixes it"],
    "din509_given_a_position": ["shaft_c.toml", "grooves[0].x_center_mm",
                                "DIN 509 places the undercut"],
    "din509_at_a_step_down": ["shaft_c.toml", "segments[4].grooves[0].side", "step up"],
    "din509_beside_a_fillet": ["shaft_c.toml", "segments[4].fillet_mm", "undercut"],
    "din509_radius_not_in_its_table": ["shaft_c.toml", "grooves[0].radius_mm",
                                       "0.4, 0.6"],
    "fillet_beside_a_cone": ["shaft_c.toml", "segments[0].fillet_mm", "conical"],
    "chamfer_deeper_than_the_shoulder": ["shaft_c.toml", "segments[4].chamfer_left_mm",
                                         "flat height"],
    "chamfer_on_an_inner_edge": ["shaft_c.toml", "segments[3].chamfer_right_mm",
                                 "outer edge"],
    "cross_hole_too_large": ["shaft_c.toml", "cross_holes[0].diameter_mm", "0.4"],
    "cross_hole_under_bearing_seat": ["shaft_c.toml", "cross_holes[0].x_center_mm",
                                      "bearing:free_side"],
    "cross_hole_on_a_groove": ["shaft_c.toml", "cross_holes[0].x_center_mm", "another notch"],
    "diameter_in_metres": ["shaft_c.toml", "segments[4].diameter_mm", "metres"],
    "boss_diameter_in_metres": ["shaft_c.toml", "segments[2].diameter_mm", "metres"],
    "mass_in_grams": ["x2_57.toml", "mass_kg", "grams"],
    "eccentricity_in_metres": ["x2_57.toml", "X2_percent", "23.4 %"],
    "E_in_GPa": ["materials.toml", "E_MPa", "GPa"],
    "C_in_kN": ["bearings.toml", "C_N", "kN"],
    "balance_table_contradicts_parts": ["x2_57.toml", "balance.mass_kg", "0.7620 kg"],
    "X2_contradicts_parts": ["x2_57.toml", "balance.X2_percent", "57.3 %"],
    "bearings_at_the_same_x": ["shaft_c.toml", "free_side", "x_center_mm"],
    "bearing_stiffness_tiny": ["bearings.toml", "K_N_per_mm", "N/mm"],
    "bearing_stiffness_inf": ["bearings.toml", "K_N_per_mm", "finite"],
    "bearing_stiffness_not_definite": ["bearings.toml", "K_N_per_mm", "positive definite"],
    "fillet_above_bearing_corner": ["shaft_c.toml", "fillet_mm", "ISO 582"],
    "fillet_into_bearing_seat": ["shaft_c.toml", "fillet_mm"],
    "nan_in_shape": ["x2_57.toml", "shape.thickness_mm"],
    "hex_socket_through_thread": ["hex_socket"],
    "keyway_too_deep": ["shaft_c.toml", "keyways[0].depth_mm"],
    "sliver_segment": ["shaft_c.toml", "segments[3].length_mm"],
    "negative_tilt_stiffness": ["bearings.toml", "tilt_stiffness_Nmm_per_rad"],
    "life_exponent_zero": ["bearings.toml", "life_exponent"],
    "keyways_not_a_list": ["shaft_c.toml", "keyways"],
    "centroid_far_off_the_shaft": ["x2_57.toml", "x_centroid_mm"],
    "density_in_kg_per_mm3": ["materials.toml", "density_t_mm3"],
    "fillet_in_metres": ["shaft_c.toml", "segments[4].fillet_mm", "metres"],
}

# Cases on the command line and on files of the work space (W = the work space):
# id -> (argv with {W}, {V} = an edited variant, {RPM} = the seed history; expected names)
CASES: dict[str, tuple[list[str], list[str]]] = {
    # output locations: checked before any work
    "forces_plot_under_a_file": (["balance", "forces", "--plot", "{W}/afile/p.png"],
                                 ["--plot", "afile"]),
    "forces_plot_is_a_directory": (["balance", "forces", "--plot", "{W}/adir.png"],
                                   ["--plot", "directory"]),
    "forces_csv_under_a_file": (["balance", "forces", "--csv", "{W}/afile/f.csv"], ["--csv"]),
    "sweep_csv_is_a_directory": (["balance", "sweep", "--x", "31:33", "--csv",
                                  "{W}/adir.csv"], ["--csv", "directory"]),
    "sweep_plot_unwritable": (["balance", "sweep", "--x", "31:33", "--plot",
                               "/proc/shaftfe_sweep.png"], ["--plot", "cannot be written"]),
    "twin_plot_under_a_file": (["balance", "twin", "--delta", "90", "--plot",
                                "{W}/afile/t.png"], ["--plot"]),
    "inline_plot_is_a_directory": (["balance", "inline", "--pins", "0,180", "--spacing-mm",
                                    "80", "--plot", "{W}/adir.png"], ["--plot", "directory"]),
    "beam_plot_under_a_file": (["beam", "--variant", "x2_57", "--plot", "{W}/afile/b.png"],
                               ["--plot"]),
    "beam_plot_is_a_directory": (["beam", "--variant", "x2_57", "--plot", "{W}/adir.png"],
                                 ["--plot", "directory"]),
    "mesh_out_under_a_file": (["mesh", "--variant", "x2_57", "--level", "coarse", "--out",
                               "{W}/afile/m.vtu"], ["--out"]),
    "mesh_out_is_a_directory": (["mesh", "--variant", "x2_57", "--out", "{W}/adir.vtu"],
                                ["--out", "directory"]),
    "static_out_is_a_file": (["static", "--variant", "x2_57", "--out", "{W}/afile"],
                             ["--out", "is a file"]),
    "static_out_under_a_file": (["static", "--variant", "x2_57", "--out", "{W}/afile/sub"],
                                ["--out"]),
    "static_out_unwritable": (["static", "--variant", "x2_57", "--out", "/proc/shaftfe_st"],
                              ["--out", "cannot be written"]),
    "fatigue_out_is_a_file": (["fatigue", "{RPM}", "--out", "{W}/afile"], ["--out"]),
    "fatigue_out_unwritable": (["fatigue", "{RPM}", "--out", "/proc/shaftfe_fat"], ["--out"]),
    "campbell_out_is_a_file": (["campbell", "0:8000", "--out", "{W}/afile"], ["--out"]),
    "modal_out_under_a_file": (["modal", "--out", "{W}/afile/sub"], ["--out"]),
    "report_out_is_a_file": (["report", "--no-pictures", "--out", "{W}/afile"], ["--out"]),
    "demo_out_under_a_file": (["demo", "--out", "{W}/afile/sub"], ["--out"]),
    "view_screenshot_under_a_file": (["view", "{W}/result.vtu", "--screenshot",
                                      "{W}/afile/v.png"], ["--screenshot"]),
    "view_screenshot_is_a_directory": (["view", "{W}/result.vtu", "--screenshot",
                                        "{W}/adir.png"], ["--screenshot", "directory"]),
    "view_a_directory": (["view", "{W}/adir"], ["adir", "is a directory"]),
    # undecodable input files name the file
    "variant_binary": (["variant", "check", "{W}/bin.toml"], ["bin.toml", "UTF-8"]),
    "variant_latin1": (["variant", "check", "{W}/latin1.toml"], ["latin1.toml", "UTF-8"]),
    "variant_binary_include": (["variant", "check", "{W}/inc_bin.toml"], ["blob.toml", "UTF-8"]),
    "beam_binary_variant": (["beam", "--variant", "{W}/bin.toml"], ["bin.toml", "UTF-8"]),
    "static_latin1_variant": (["static", "--variant", "{W}/latin1.toml", "--out", "{W}/o"],
                              ["latin1.toml", "UTF-8"]),
    "spectrum_binary": (["fatigue", "{W}/bin.dat", "--out", "{W}/o"], ["bin.dat"]),
    "spectrum_latin1": (["fatigue", "{W}/latin1.dat", "--out", "{W}/o"], ["latin1.dat"]),
    "spectrum_utf16": (["fatigue", "{W}/utf16.dat", "--out", "{W}/o"], ["utf16.dat"]),
    "spectrum_empty": (["fatigue", "{W}/empty.dat", "--out", "{W}/o"], ["empty.dat"]),
    "spectrum_is_a_directory": (["fatigue", "{W}/adir", "--out", "{W}/o"], ["adir"]),
    "view_garbage_vtu": (["view", "{W}/garbage.vtu"], ["garbage.vtu"]),
    # a variant no command may choke on: refused by the loader of every command
    "mesh_metre_diameter": (["mesh", "--variant", "{V:diameter_in_metres}", "--level",
                             "coarse"], ["segments[4].diameter_mm"]),
    "static_gram_mass": (["static", "--variant", "{V:mass_in_grams}", "--out", "{W}/o"],
                         ["mass_kg"]),
    "beam_same_x_bearings": (["beam", "--variant", "{V:bearings_at_the_same_x}"],
                             ["free_side"]),
    "static_tiny_stiffness": (["static", "--variant", "{V:bearing_stiffness_tiny}", "--out",
                               "{W}/o"], ["K_N_per_mm"]),
    # operating values: one rpm ceiling, no empty items, bounded resources
    "beam_rpm_1e9": (["beam", "--variant", "x2_57", "--rpm", "1e9"], ["--rpm", "20000"]),
    "beam_rpm_empty_item": (["beam", "--variant", "x2_57", "--rpm", "10000,,7000"],
                            ["--rpm"]),
    "static_rpm_1e9": (["static", "--variant", "x2_57", "--rpm", "1e9", "--out", "{W}/o"],
                       ["--rpm", "20000"]),
    "modal_rpm_1e9": (["modal", "--rpm", "1e9"], ["--rpm", "20000"]),
    "forces_rpm_1e9": (["balance", "forces", "--rpm", "1e9"], ["--rpm", "20000"]),
    "campbell_range_1e9": (["campbell", "0:1e9"], ["RANGE", "20000"]),
    "campbell_step_tiny": (["campbell", "0:20000:1e-308"], ["RANGE/--step", "speeds"]),
    "campbell_max_element_tiny": (["campbell", "0:8000", "--max-element", "1e-6"],
                                  ["--max-element"]),
    "beam_max_element_tiny": (["beam", "--variant", "x2_57", "--max-element", "1e-6"],
                              ["--max-element"]),
    "report_campbell_step_tiny": (["report", "--campbell-step", "0.01", "--out", "{W}/o"],
                                  ["--campbell-step"]),
    "campbell_negative_range": (["campbell", "-50:500"], ["-50:500", "--"]),
    "sweep_negative_range": (["balance", "sweep", "--x", "-50:500:10"],
                             ["--x=-50:500:10"]),
    "inline_negative_spacing": (["balance", "inline", "--pins", "0,180", "--spacing-mm",
                                 "-80"], ["--spacing-mm", "-80", "mm"]),
    "static_exclude_huge": (["static", "--variant", "x2_57", "--exclude-mm", "1e9", "--out",
                             "{W}/o"], ["--exclude-mm"]),
    "fatigue_exclude_huge": (["fatigue", "{RPM}", "--exclude-mm", "1e9", "--out", "{W}/o"],
                             ["--exclude-mm"]),
    "static_level_bogus": (["static", "--variant", "x2_57", "--level", "bogus", "--out",
                            "{W}/o"], ["--level"]),
    "static_zoned_estimate_error": (["static", "--variant", "x2_57", "--estimate-error",
                                     "--out", "{W}/o"], ["--estimate-error", "--model solid"]),
    "report_default_zoned_estimate_error": (["report", "--estimate-error", "--out", "{W}/o"],
                                             ["--estimate-error", "--model solid", "zoned"]),
    "static_zoned_body_force": (["static", "--variant", "x2_57", "--body-force", "--out",
                                 "{W}/o"], ["--body-force", "--model solid"]),
    "static_model_bogus": (["static", "--variant", "x2_57", "--model", "shell", "--out",
                            "{W}/o"], ["--model"]),
    "fatigue_design_life_negative": (["fatigue", "{RPM}", "--design-life", "-1", "--out",
                                      "{W}/o"], ["--design-life"]),
    "campbell_modes_zero": (["campbell", "0:8000", "--modes", "0"], ["--modes"]),
    "fatigue_kf_zero": (["fatigue", "{RPM}", "--kf", "0", "--out", "{W}/o"], ["--kf"]),
    # spectra
    "spectrum_unicode_digits": (["fatigue", "{W}/arabic.dat", "--out", "{W}/o"],
                                ["arabic.dat", "line 4"]),
    "spectrum_nan": (["fatigue", "{W}/nan.dat", "--out", "{W}/o"], ["nan.dat", "line 3"]),
    "spectrum_negative_rpm": (["fatigue", "{W}/neg.dat", "--out", "{W}/o"],
                              ["neg.dat", "line 4"]),
    "spectrum_time_not_increasing": (["fatigue", "{W}/time.csv", "--out", "{W}/o"],
                                     ["time.csv", "time_s"]),
    "spectrum_rpm_above_ceiling": (["fatigue", "{W}/fast.dat", "--out", "{W}/o"],
                                   ["fast.dat", "20000"]),
}
for _k in VARIANT_EDITS:
    CASES[f"variant_check_{_k}"] = (["variant", "check", f"{{V:{_k}}}"], VARIANT_EXPECT[_k])


def _workspace(root: Path) -> Path:
    """Files the cases point at (the same for every case; each case also gets its variant)."""
    w = root / "w"
    w.mkdir()
    (w / "afile").write_text("a regular file where a directory is expected\n")
    for d in ("adir", "adir.png", "adir.csv", "adir.vtu"):
        (w / d).mkdir()
    rng = np.random.default_rng(0)
    blob = bytes([0xD5, 0xFF, 0x00]) + rng.integers(0, 256, 2000, dtype=np.uint8).tobytes()
    (w / "bin.toml").write_bytes(blob)
    (w / "bin.dat").write_bytes(blob)
    (w / "blob.toml").write_bytes(blob)
    (w / "inc_bin.toml").write_text('name = "x"\ninclude = ["blob.toml"]\n')
    (w / "latin1.toml").write_bytes('name = "x"\ndescription = "§ Ø 17"\n'.encode("latin-1"))
    (w / "latin1.dat").write_bytes("# sample_rate_hz = 1 §\n0.5\n".encode("latin-1"))
    (w / "utf16.dat").write_bytes("0.5\n0.6\n".encode("utf-16"))
    (w / "empty.dat").write_text("")
    (w / "garbage.vtu").write_bytes(blob)
    hdr = "# format = normalised\n# reference_rpm = 7000\n"
    (w / "arabic.dat").write_text(hdr + "0.5\n\u0660.\u0663\n")
    (w / "nan.dat").write_text(hdr + "nan\n0.5\n")
    (w / "neg.dat").write_text("# format = rpm\n# sample_rate_hz = 1\n3000\n-5\n")
    (w / "time.csv").write_text("time_s,rpm\n0,3000\n1,4000\n1,5000\n")
    (w / "fast.dat").write_text("# format = rpm\n# sample_rate_hz = 1\n3000\n90000\n")
    import meshio
    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    meshio.write(w / "result.vtu", meshio.Mesh(pts, [("tetra", np.array([[0, 1, 2, 3]]))],
                                               point_data={"von_mises": np.arange(4.0)}))
    return w


@pytest.fixture(scope="module")
def space(tmp_path_factory):
    root = tmp_path_factory.mktemp("bad-input")
    return root, _workspace(root)


def _variant(root: Path, key: str) -> str:
    """The x2_57 files copied with one edit (VARIANT_EDITS[key]); path of the variant."""
    g = root / f"v_{key}"
    if not g.exists():
        shutil.copytree(GEOMETRY_DIR, g, ignore=shutil.ignore_patterns("*.md", "engines"))
        rel, old, new = VARIANT_EDITS[key]
        text = (g / rel).read_text(encoding="utf-8")
        assert text.count(old) == 1, f"{key}: {old!r} must occur once in {rel}"
        (g / rel).write_text(text.replace(old, new), encoding="utf-8")
    return str(g / "x2_57.toml")


def _snapshot(root: Path) -> dict[str, tuple[int, int]]:
    out = {}
    for dirpath, dirnames, filenames in os.walk(root):
        for n in dirnames + filenames:
            p = Path(dirpath) / n
            st = p.lstat()
            out[str(p.relative_to(root))] = (st.st_size if p.is_file() else -1, st.st_mtime_ns)
    return out


@pytest.mark.parametrize("case", sorted(CASES))
def test_bad_input_is_one_clear_line_exit_2_and_writes_nothing(case, space, capsys,
                                                               monkeypatch):
    root, w = space
    argv, expect = CASES[case]
    args = []
    for a in argv:
        if a.startswith("{V:"):
            a = _variant(root, a[3:-1])
        args.append(a.replace("{W}", str(w)).replace("{RPM}", RPM_DAT))
    monkeypatch.chdir(w)
    monkeypatch.setenv("SHAFTFE_CACHE_DIR", str(root / "cache"))
    monkeypatch.setenv("MPLBACKEND", "Agg")
    before = _snapshot(w)
    capsys.readouterr()
    try:
        rc = main(args)
    except SystemExit as exc:                       # argparse usage errors
        rc = exc.code
    out = capsys.readouterr()
    lines = out.err.strip().splitlines()
    assert rc == 2, f"exit {rc}; stderr: {out.err!r}"
    assert len(lines) == 1, f"expected one line on stderr, got {lines!r}"
    assert "Traceback" not in out.err
    for word in expect:
        assert word in lines[0], f"{word!r} not named in: {lines[0]}"
    assert _snapshot(w) == before, "the work space (--out) changed"


def test_the_catalogue_covers_every_command_and_at_least_60_cases():
    commands = {CASES[c][0][0] for c in CASES}
    assert len(CASES) >= 60
    assert commands >= {"balance", "variant", "beam", "mesh", "static", "fatigue", "campbell",
                        "modal", "report", "demo", "view"}


# --------------------------------------------------------------------------- issue 30, slice
# c-study: `shaftfe study` (every input checked before the first design; the scheduler's
# address; damaged study folders). Same contract as the catalogue above; no design is solved
# (each case is refused before the cluster starts) and only loopback addresses are used.

STUDY_HEAD = ('[study]\nname = "t"\nbase = "x2_57"\n[[parameters]]\n'
              'path = "segments.collar.fillet_mm"\nvalues = [0.4, 0.5]\n')
STUDY_FILES = {
    "beam.toml": STUDY_HEAD + "[analyses]\nbeam = true\n",
    "badspec.toml": STUDY_HEAD + '[analyses]\nstatic = { level = "coarse" }\n'
                    'fatigue = { spectrum = "bad.dat" }\n',
    "ecc_metres.toml": ('[study]\nname = "e"\nbase = "x2_57"\n[[parameters]]\n'
                        'path = "attachments.counterweight_2.eccentricity_mm"\n'
                        'values = [20.23, 0.02023]\n[analyses]\nbeam = true\n'),
    "radius_huge.toml": ('[study]\nname = "r"\nbase = "x2_57"\n[[parameters]]\n'
                         'name = "cw2 radius"\n'
                         'path = "attachments.counterweight_2.shape.outer_radius_mm"\n'
                         'values = [39.0, 400.0]\n[analyses]\nbeam = true\n'),
    "all_refused.toml": STUDY_HEAD.replace("[0.4, 0.5]", "[0.8, 1.0]")
                        + "[analyses]\nbeam = true\n",
    "overspeed.toml": STUDY_HEAD + "[analyses]\nbearings = { rpm = 19000 }\n",
    "overspeed_spectrum.toml": STUDY_HEAD + '[analyses]\nstatic = { level = "coarse" }\n'
                               'fatigue = { spectrum = "over.dat" }\n',
}
STUDY_CASES: dict[str, tuple[list[str], list[str]]] = {
    "study_spectrum_malformed": (["study", "run", "{W}/badspec.toml", "--out", "{W}/o"],
                                 ["bad.dat", "line 3"]),
    "study_eccentricity_in_metres": (["study", "run", "{W}/ecc_metres.toml", "--out",
                                      "{W}/o"], ["ecc_metres.toml", "eccentricity_mm",
                                                 "0.02023", "20.23"]),
    "study_derived_mass_names_the_parameter": (
        ["study", "run", "{W}/radius_huge.toml", "--out", "{W}/o"],
        ["radius_huge.toml", "design 1", "'cw2 radius'", "= 400", "mass_kg", "[1e-05, 20] kg"]),
    "study_every_design_refused": (["study", "run", "{W}/all_refused.toml", "--out", "{W}/o"],
                                   ["all_refused.toml", "all 2 refused", "ISO 582"]),
    "study_bearing_speed_above_max_rpm": (["study", "run", "{W}/overspeed.toml", "--out",
                                           "{W}/o"], ["overspeed.toml", "bearings.rpm",
                                                      "max_rpm"]),
    "study_spectrum_above_max_rpm": (["study", "run", "{W}/overspeed_spectrum.toml", "--out",
                                      "{W}/o"], ["over.dat", "highest rpm", "9500", "max_rpm"]),
    "study_scheduler_not_a_url": (["study", "run", "{W}/beam.toml", "--out", "{W}/o",
                                   "--scheduler", "not a url"], ["--scheduler", "not a URL"]),
    "study_scheduler_http": (["study", "run", "{W}/beam.toml", "--out", "{W}/o",
                              "--scheduler", "http://127.0.0.1:8787"],
                             ["--scheduler", "web address", "tcp://"]),
    "study_scheduler_refused": (["study", "run", "{W}/beam.toml", "--out", "{W}/o",
                                 "--scheduler", "tcp://127.0.0.1:{PORT}"],
                                ["--scheduler", "refused the connection"]),
    "study_out_with_damaged_study_json": (["study", "run", "{W}/beam.toml", "--out",
                                           "{W}/damaged_meta"], ["study.json", "damaged"]),
    "study_report_missing_folder": (["study", "report", "{W}/nothing_here"],
                                    ["nothing_here", "does not exist"]),
    "study_report_damaged_study_json": (["study", "report", "{W}/damaged_meta"],
                                        ["study.json", "damaged"]),
    "study_report_damaged_parquet": (["study", "report", "{W}/damaged_table"],
                                     ["results.parquet", "cannot be read"]),
}


@pytest.fixture(scope="module")
def study_space(tmp_path_factory):
    import socket
    w = tmp_path_factory.mktemp("bad-study")
    for name, text in STUDY_FILES.items():
        (w / name).write_text(text)
    (w / "bad.dat").write_text("# format = rpm\n# sample_rate_hz = 1\nabc\n3000\n")
    (w / "over.dat").write_text("# format = rpm\n# sample_rate_hz = 1\n3000\n19999\n3000\n")
    (w / "damaged_meta").mkdir()
    (w / "damaged_meta" / "study.json").write_bytes(b"\x00{not json")
    (w / "damaged_table").mkdir()
    (w / "damaged_table" / "study.json").write_text(json.dumps(S2_META))  # a whole record
    (w / "damaged_table" / "results.parquet").write_bytes(b"PAR1 not a table")
    with socket.socket() as s:                 # a loopback port nobody listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    return w, port


@pytest.mark.parametrize("case", sorted(STUDY_CASES))
def test_bad_study_input_is_one_clear_line_exit_2_and_writes_nothing(case, study_space, capsys,
                                                                     monkeypatch):
    w, port = study_space
    argv, expect = STUDY_CASES[case]
    args = [a.replace("{W}", str(w)).replace("{PORT}", str(port)) for a in argv]
    monkeypatch.chdir(w)
    before = _snapshot(w)
    capsys.readouterr()
    rc = main(args)
    out = capsys.readouterr()
    lines = out.err.strip().splitlines()
    assert rc == 2, f"exit {rc}; stderr: {out.err!r}"
    assert len(lines) == 1, f"expected one line on stderr, got {lines!r}"
    assert "Traceback" not in out.err and "typed in grams" not in out.err
    for word in expect:
        assert word in lines[0], f"{word!r} not named in: {lines[0]}"
    assert _snapshot(w) == before, "the work space (--out) changed"
# ---------------------------------------------------------------- issue #30, b-static-variant
# 0 rpm, a sharp shoulder in a fatigue check, a bearing stiffness off by 1000×, `variant new`
# names, an empty bearings file
B_EDITS = {
    "bearing_stiffness_1000x_soft": (BEAR, K, "K_N_per_mm = [[35.03, 8.756], [8.756, 35.03]]"),
    "bearing_stiffness_1000x_stiff": (BEAR, K, "K_N_per_mm = [[35030000.0, 8756000.0], "
                                      "[8756000.0, 35030000.0]]"),
    "bearings_file_empty": (BEAR, (GEOMETRY_DIR / BEAR).read_text(encoding="utf-8"), ""),
    # a keyway bottom radius taller than half the side wall (Ø17, 5 wide, 3 deep: 1.31 mm)
    "keyway_radius_above_the_wall": (SHAFT, "x_center_mm = 94.5\nangle_deg = 0.0\n"
                                     "bottom_radius_mm = 0.0", "x_center_mm = 94.5\n"
                                     "angle_deg = 0.0\nbottom_radius_mm = 1.4"),
}
B_EXPECT = {
    "bearing_stiffness_1000x_soft": ["bearings.toml", "K_N_per_mm", "estimate 1.34e+05"],
    "bearing_stiffness_1000x_stiff": ["bearings.toml", "K_N_per_mm", "estimate 1.34e+05"],
    "bearings_file_empty": ["shaft_c.toml", "bearings[0].type", "[bearing_types.*] (none"],
    "keyway_radius_above_the_wall": ["shaft_c.toml", "keyways[0].bottom_radius_mm", "1.31 mm"],
}
VARIANT_EDITS.update(B_EDITS)
B_CASES = {f"variant_check_{_k}": (["variant", "check", f"{{V:{_k}}}"], B_EXPECT[_k])
           for _k in B_EDITS}
B_CASES.update({
    "static_rpm_zero": (["static", "--variant", "x2_57", "--rpm", "0", "--out", "{W}/o"],
                        ["--rpm", "at least one > 0", "m·e·ω²"]),
    "static_axisymmetric_rpm_all_zero": (
        ["static", "--variant", "x2_57", "--model", "axisymmetric", "--rpm", "0,0",
         "--out", "{W}/o"], ["--rpm", "at least one > 0"]),
    "beam_stiffness_1000x_soft": (["beam", "--variant", "{V:bearing_stiffness_1000x_soft}"],
                                  ["K_N_per_mm", "estimate"]),
    "fatigue_sharp_shoulder": (["fatigue", "{RPM}", "--set", "segments.collar.fillet_mm=0",
                                "--out", "{W}/o"], ["--set segments.collar.fillet_mm=0",
                                                    "fillet_mm", "sharp corner"]),
    "fatigue_din743_sharp_shoulder": (["fatigue", "{RPM}", "--method", "din743", "--set",
                                       "segments.bearing_seat_gear.fillet_mm=0", "--out",
                                       "{W}/o"], ["bearing_seat_gear", "sharp corner"]),
    "fatigue_seed_sharp_shoulder": (["fatigue", "{RPM}", "--method", "seed", "--set",
                                     "segments.collar.fillet_mm=0", "--out", "{W}/o"],
                                    ["collar", "sharp corner"]),
    "report_sharp_shoulder": (["report", "--no-pictures", "--set",
                               "segments.collar.fillet_mm=0", "--out", "{W}/o"],
                              ["collar", "sharp corner"]),
    # keyway bottom radii the level's 3D mesh cannot hold (about 2.3 million fillet dofs at
    # default): refused at the plan, before gmsh (solid.mesh.KEYWAY_DOFS_MAX)
    "static_keyway_radius_too_small_for_the_mesh": (
        ["static", "--variant", "x2_57", "--set", "segments.gear_seat.keyways.0."
         "bottom_radius_mm=0.08", "--set", "segments.cw2_seat.keyways.0.bottom_radius_mm=0.08",
         "--out", "{W}/o"], ["keyways[0].bottom_radius_mm", "million dofs", "coarser --level"]),
    "variant_new_name_like_an_option": (["variant", "new", "--", "-rf"],
                                        ["NAME", "starting with a letter or digit"]),
    "variant_new_existing_name_elsewhere": (["variant", "new", "x2_31", "--out",
                                             "{W}/other.toml"], ["NAME", "x2_31.toml exists"]),
    "variant_new_existing_name_other_case": (["variant", "new", "X2_31", "--out",
                                              "{W}/other.toml"], ["NAME", "any letter case",
                                                                  "x2_31.toml exists"]),
})
CASES.update(B_CASES)          # counted by the catalogue's coverage test

# --- issue #30 §1-2, slice a1 (the fatigue command's inputs) ---------------------------------
# The engine's speed limit (balance.engines: max_rpm of geometry/engines/vm450.toml, 9500 rpm; a
# static/beam proof check up to 1.2 × = 11 400 rpm), absurd sample rates and design lives
# (history.SAMPLE_RATE_HZ, run.DESIGN_LIFE_*), options the chosen method does not use
# (fatigue.method_options), an engine at rest, and endless or binary streams (history.MAX_*).
A1_FILES = {
    "over.dat": "# format = rpm\n# sample_rate_hz = 1\n3000\n19999\n3000\n8000\n",
    "rate_huge.dat": "# format = rpm\n# sample_rate_hz = 1e300\n3000\n8000\n3000\n",
    "rate_tiny.dat": "# format = rpm\n# sample_rate_hz = 1e-300\n3000\n8000\n3000\n",
    "steps_tiny.csv": "time_s,rpm\n0,3000\n1e-300,8000\n2e-300,3000\n",
    "at_rest.dat": "# format = rpm\n# sample_rate_hz = 1\n0\n0\n0\n0\n",
}
A1_SPEED = ["19999", "9500", "vm450.toml", "--allow-overspeed"]
A1_CASES: dict[str, tuple[list[str], list[str]]] = {
    "fatigue_history_above_max_rpm": (["fatigue", "{W}/over.dat", "--out", "{W}/o"],
                                      ["over.dat", *A1_SPEED]),
    "fatigue_din743_history_above_max_rpm": (["fatigue", "{W}/over.dat", "--method", "din743",
                                              "--out", "{W}/o"], ["over.dat", *A1_SPEED]),
    "fatigue_seed_history_above_max_rpm": (["fatigue", "{W}/over.dat", "--method", "seed",
                                            "--out", "{W}/o"], ["over.dat", *A1_SPEED]),
    "report_spectrum_above_max_rpm": (["report", "--spectrum", "{W}/over.dat", "--no-pictures",
                                       "--out", "{W}/o"], ["over.dat", *A1_SPEED]),
    "static_rpm_above_proof_speed": (["static", "--variant", "x2_57", "--rpm", "7000,12000",
                                      "--out", "{W}/o"],
                                     ["--rpm", "12000", "11400", "vm450.toml", "1.2"]),
    "beam_rpm_above_proof_speed": (["beam", "--variant", "x2_57", "--rpm", "12000"],
                                   ["--rpm", "12000", "11400", "vm450.toml"]),
    "fatigue_sample_rate_1e300": (["fatigue", "{W}/rate_huge.dat", "--out", "{W}/o"],
                                  ["rate_huge.dat", "sample_rate_hz", "100000"]),
    "fatigue_sample_rate_1e-300": (["fatigue", "{W}/rate_tiny.dat", "--out", "{W}/o"],
                                   ["rate_tiny.dat", "sample_rate_hz", "0.001"]),
    "fatigue_sample_rate_option_1e300": (["fatigue", "{RPM}", "--sample-rate", "1e300", "--out",
                                          "{W}/o"], ["--sample-rate", "100000"]),
    "fatigue_csv_steps_1e-300_s": (["fatigue", "{W}/steps_tiny.csv", "--out", "{W}/o"],
                                   ["steps_tiny.csv", "line 3: time_s", "1e-05"]),
    "fatigue_design_life_1e300": (["fatigue", "{RPM}", "--design-life", "1e300", "--out",
                                   "{W}/o"], ["--design-life", "1e+09"]),
    "fatigue_design_life_h_1e300": (["fatigue", "{RPM}", "--design-life-h", "1e300", "--out",
                                     "{W}/o"], ["--design-life-h", "1e+09"]),
    "fatigue_design_life_in_blocks_and_hours": (["fatigue", "{RPM}", "--design-life", "1e7",
                                                 "--design-life-h", "5000", "--out", "{W}/o"],
                                                ["--design-life", "--design-life-h", "not both"]),
    "fatigue_speed_kmh_1e300": (["fatigue", "{RPM}", "--speed-kmh", "1e300", "--out", "{W}/o"],
                                ["--speed-kmh", "400"]),
    "fatigue_card_with_seed": (["fatigue", "{RPM}", "--card", "14220", "--method", "seed",
                                "--out", "{W}/o"], ["--card", "fkm | din743", "seed"]),
    "fatigue_miner_with_seed": (["fatigue", "{RPM}", "--miner", "elementary", "--method", "seed",
                                 "--out", "{W}/o"], ["--miner", "only with --method fkm"]),
    "fatigue_model_with_din743": (["fatigue", "{RPM}", "--model", "axisymmetric", "--method",
                                   "din743", "--out", "{W}/o"], ["--model", "seed | fkm"]),
    "fatigue_material_with_fkm": (["fatigue", "{RPM}", "--material", "14220", "--out", "{W}/o"],
                                  ["--material", "only with --method seed", "fkm"]),
    "fatigue_design_life_with_din743": (["fatigue", "{RPM}", "--design-life-h", "5000",
                                         "--method", "din743", "--out", "{W}/o"],
                                        ["--design-life-h", "din743"]),
    "fatigue_engine_at_rest": (["fatigue", "{W}/at_rest.dat", "--out", "{W}/o"],
                               ["at_rest.dat", "no load", "no damage", "no bearing wear"]),
    "fatigue_din743_engine_at_rest": (["fatigue", "{W}/at_rest.dat", "--method", "din743",
                                       "--out", "{W}/o"], ["at_rest.dat", "no load"]),
    "fatigue_seed_engine_at_rest": (["fatigue", "{W}/at_rest.dat", "--method", "seed", "--out",
                                     "{W}/o"], ["at_rest.dat", "no load"]),
    "report_engine_at_rest": (["report", "--spectrum", "{W}/at_rest.dat", "--no-pictures",
                               "--out", "{W}/o"], ["at_rest.dat", "no load"]),
    "fatigue_dev_zero": (["fatigue", "/dev/zero", "--out", "{W}/o"], ["/dev/zero", "NUL", "MB"]),
    "fatigue_dev_urandom": (["fatigue", "/dev/urandom", "--out", "{W}/o"],
                            ["/dev/urandom", "binary"]),
}
CASES.update(A1_CASES)        # after the catalogue's own parametrisation: run by the test below


@pytest.mark.parametrize("case", sorted(A1_CASES))
def test_a1_fatigue_inputs_are_one_clear_line_exit_2(case, space, capsys, monkeypatch):
    _, w = space
    for name, text in A1_FILES.items():
        (w / name).write_text(text)
    test_bad_input_is_one_clear_line_exit_2_and_writes_nothing(case, space, capsys,
                                                               monkeypatch)
# --- slice d-kt-materials (issue #30 §5): the material record the standards read ------------
# --card names a record of geometry/common/materials.toml; one without a standard material
# group (a key steel) or an unknown name is refused before any solve
MATERIAL_CASES = {
    "card_without_standard_group": (["fatigue", "{RPM}", "--method", "din743", "--card",
                                     "11600", "--out", "{W}/o"], ["materials.11600.group"]),
    "card_unknown_record": (["fatigue", "{RPM}", "--method", "fkm", "--card", "nosuch",
                             "--out", "{W}/o"], ["materials.toml", "nosuch"]),
}
CASES.update(MATERIAL_CASES)



# --- issue #30, slice s2-study-fixes: study folders and addresses ---------------------------
# a study.json without its keys (`{}` beside a finished study's table), `study report` on a
# file, an empty --scheduler, a fatigue spectrum of the engine at rest
S2_META = {"study_file": "../t.toml", "digest": "x", "name": "t", "base": "x2_57",
           "parameters": [], "objectives": [], "requirements": [], "analyses": {}}
S2_CASES: dict[str, tuple[list[str], list[str]]] = {
    "study_report_study_json_without_keys": (
        ["study", "report", "{W}/empty_meta"], ["empty_meta", "study.json", "damaged",
                                                "study_file", "analyses"]),
    "study_report_on_a_file": (["study", "report", "{W}/beam.toml"],
                               ["beam.toml", "is a file, not a study folder"]),
    "study_scheduler_empty": (["study", "run", "{W}/beam.toml", "--out", "{W}/o",
                               "--scheduler", ""], ["--scheduler", "''", "not a URL"]),
    "study_spectrum_all_zero": (["study", "run", "{W}/zero_spectrum.toml", "--out", "{W}/o"],
                                ["zero.dat", "0 in every sample", "engine at rest"]),
}
STUDY_CASES.update(S2_CASES)


@pytest.mark.parametrize("case", sorted(S2_CASES))
def test_s2_study_folders_and_addresses(case, study_space, capsys, monkeypatch):
    """As the c-study catalogue; the `{}` study.json sits beside the showcase's real table
    (which `study report` read and overwrote index.html from, exit 0, before the fix)."""
    w, _ = study_space
    (w / "zero.dat").write_text("# format = rpm\n# sample_rate_hz = 1\n0\n0\n0\n")
    (w / "zero_spectrum.toml").write_text(STUDY_HEAD + '[analyses]\nstatic = { level = '
                                          '"coarse" }\nfatigue = { spectrum = "zero.dat" }\n')
    (w / "empty_meta").mkdir(exist_ok=True)
    (w / "empty_meta" / "study.json").write_text("{}")
    shown = Path(__file__).resolve().parents[1] / "reports" / "studies" / "x2_tradeoff"
    for name in ("results.parquet", "base.json"):
        (w / "empty_meta" / name).write_bytes((shown / name).read_bytes())
    test_bad_study_input_is_one_clear_line_exit_2_and_writes_nothing(case, study_space, capsys,
                                                                     monkeypatch)
# --- slice f2-fatigue-fixes (issue #30 review of `shaftfe fatigue`) ---------------------------
# one design-life rule in blocks and hours (one pass .. 1e9 blocks and 1e9 h, named in the unit
# of the option typed); an unknown --model as its help says; the sample rate by its option
F2_CASES = {
    "fatigue_design_life_h_past_1e9_blocks": (["fatigue", "{RPM}", "--design-life-h", "1e8",
                                               "--out", "{W}/o"],
                                              ["--design-life-h", "1.2e+09 blocks",
                                               "300 s history"]),
    "fatigue_design_life_h_under_one_block": (["fatigue", "{RPM}", "--design-life-h", "0.01",
                                               "--out", "{W}/o"],
                                              ["--design-life-h", "0.08333"]),
    "fatigue_design_life_past_1e9": (["fatigue", "{RPM}", "--design-life", "2e9", "--out",
                                      "{W}/o"], ["--design-life", "1e+09"]),
    "fatigue_fkm_model_bogus": (["fatigue", "{RPM}", "--model", "cylinder", "--out", "{W}/o"],
                                ["--model", "zoned | solid | axisymmetric"]),
    "fatigue_seed_sample_rate_option": (["fatigue", "{RPM}", "--method", "seed",
                                         "--sample-rate", "0", "--out", "{W}/o"],
                                        ["command line: --sample-rate", "0.001"]),
}
CASES.update(F2_CASES)

# --- issue #31, loads as data (model.loads): a load outside the shaft, a torque with nothing to
# react it, a magnitude in the wrong unit, a gear that cannot exist, an unknown kind or law
_BAL = "[balance]\nX2_percent = 57.0"


def _with_load(body: str) -> tuple[str, str, str]:
    return ("x2_57.toml", _BAL, "[[loads]]\n" + body + "\n\n" + _BAL)


LOAD_EDITS = {
    "load_outside_shaft": _with_load('name = "f"\nkind = "force"\nx_mm = 500.0\nF_N = 100.0'),
    "load_torque_unreacted": _with_load('name = "t"\nkind = "torque"\nx_mm = 50.0\n'
                                        'T_Nmm = 376.0'),
    "load_force_in_wrong_unit": _with_load('name = "f"\nkind = "force"\nx_mm = 50.0\n'
                                           'F_N = 5e7'),
    "load_gear_inside_shaft": _with_load('name = "g"\nkind = "gear_mesh"\nseat = "gear_seat"\n'
                                         'module_mm = 2.0\nteeth = 7\nT_Nmm = 376.0\n'
                                         'scales_with = "torque_Nm"\nchannel_ref = 0.376\n'
                                         '[[loads]]\nname = "p"\nkind = "torque"\nx_mm = 110.0\n'
                                         'T_Nmm = -376.0\nscales_with = "torque_Nm"\n'
                                         'channel_ref = 0.376'),
    "load_unknown_kind": _with_load('name = "f"\nkind = "pressure"\nx_mm = 50.0\nF_N = 1.0'),
    "load_bad_law": _with_load('name = "f"\nkind = "force"\nx_mm = 50.0\nF_N = 1.0\n'
                               'scales_with = "rpm 2"'),
}
LOAD_EXPECT = {
    "load_outside_shaft": ["x2_57.toml", "loads[0].x_mm", "on the shaft"],
    "load_torque_unreacted": ["x2_57.toml", "loads", "rotation about the shaft axis free",
                              "holds_torsion"],
    "load_force_in_wrong_unit": ["x2_57.toml", "loads[0].F_N", "N (not kN)"],
    "load_gear_inside_shaft": ["x2_57.toml", "loads[0]", "root diameter", "inside the shaft"],
    "load_unknown_kind": ["x2_57.toml", "loads[0].kind", "gear_mesh"],
    "load_bad_law": ["x2_57.toml", "loads[0].scales_with", "channel"],
}
VARIANT_EDITS.update(LOAD_EDITS)
LOAD_CASES = {f"variant_check_{_k}": (["variant", "check", f"{{V:{_k}}}"], LOAD_EXPECT[_k])
              for _k in LOAD_EDITS}
LOAD_CASES["static_set_load_outside"] = (
    ["variant", "check", "{V:load_force_in_wrong_unit}", "--set", "loads.f.F_N=100.0",
     "--set", "loads.f.x_mm=-3.0"], ["--set loads.f.x_mm=-3.0", "x_mm", "on the shaft"])
CASES.update(LOAD_CASES)



# --- issue #31, slice duty (item 6: the variant owns its duty) -------------------------------
# the [duty] table of common/duty_vm450.toml: speeds out of range or reversed, files that do not
# exist, an unknown S-N card or key; a variant with no [duty] asks for what a command needs
DUTY = "common/duty_vm450.toml"
DUTY_EDITS = {
    "duty_design_speed_above_proof": (DUTY, "design_speeds_rpm = [10000.0, 7000.0]",
                                      "design_speeds_rpm = [12000.0, 7000.0]"),
    "duty_speed_range_reversed": (DUTY, "speed_range_rpm = [1200.0, 9500.0]",
                                  "speed_range_rpm = [9500.0, 1200.0]"),
    "duty_speed_range_above_engine": (DUTY, "speed_range_rpm = [1200.0, 9500.0]",
                                      "speed_range_rpm = [1200.0, 12000.0]"),
    "duty_campbell_range_reversed": (DUTY, "campbell_range_rpm = [0.0, 9500.0]",
                                     "campbell_range_rpm = [9500.0, 0.0]"),
    "duty_unknown_spectrum": (DUTY, 'spectrum = "rpm.dat"', 'spectrum = "nosuch.dat"'),
    "duty_unknown_engine": (DUTY, 'engine = "vm450"', 'engine = "vm999"'),
    "duty_unknown_sn_curve": (DUTY, 'sn_curve = "structural_steel"', 'sn_curve = "steel"'),
    "duty_life_under_one_block": (DUTY, "design_life_blocks = 1.0e7",
                                  "design_life_blocks = 0.5"),
    "duty_unknown_key": (DUTY, 'sn_curve = "', 'max_speed = "9500"\nsn_curve = "'),
    "no_duty": ("x2_57.toml", ', "common/duty_vm450.toml"]', "]"),
}
DUTY_EXPECT = {
    "duty_design_speed_above_proof": ["duty_vm450.toml", "duty.design_speeds_rpm[0]",
                                      "11400", "1.2 ×"],
    "duty_speed_range_reversed": ["duty_vm450.toml", "duty.speed_range_rpm", "low < high"],
    "duty_speed_range_above_engine": ["duty_vm450.toml", "duty.speed_range_rpm",
                                      "max_rpm 9500"],
    "duty_campbell_range_reversed": ["duty_vm450.toml", "duty.campbell_range_rpm",
                                     "low < high"],
    "duty_unknown_spectrum": ["duty_vm450.toml", "duty.spectrum", "nosuch.dat", "rpm.dat"],
    "duty_unknown_engine": ["duty_vm450.toml", "duty.engine", "vm999", "vm450.toml"],
    "duty_unknown_sn_curve": ["duty_vm450.toml", "duty.sn_curve", "structural_steel"],
    "duty_life_under_one_block": ["duty_vm450.toml", "duty.design_life_blocks", "[1, 1e12]"],
    "duty_unknown_key": ["duty_vm450.toml", "duty.max_speed", "not a known field"],
}
VARIANT_EDITS.update(DUTY_EDITS)
DUTY_CASES = {f"variant_check_{_k}": (["variant", "check", f"{{V:{_k}}}"], DUTY_EXPECT[_k])
              for _k in DUTY_EXPECT}
DUTY_CASES.update({
    "report_campbell_range_reversed": (["report", "--campbell-range", "9500:0", "--out",
                                        "{W}/o"], ["--campbell-range", "a <= b"]),
    "report_no_duty": (["report", "--variant", "{V:no_duty}", "--no-pictures", "--out",
                        "{W}/o"], ["x2_57.toml", "duty.design_life_h", "is not stated",
                                   "--design-life-h"]),
    "report_no_duty_no_spectrum": (["report", "--variant", "{V:no_duty}", "--design-life-h",
                                    "1000", "--no-pictures", "--out", "{W}/o"],
                                   ["x2_57.toml", "duty.spectrum", "--spectrum"]),
    "static_no_duty_no_rpm": (["static", "--variant", "{V:no_duty}", "--out", "{W}/o"],
                              ["x2_57.toml", "duty.design_speeds_rpm", "--rpm"]),
    "beam_no_duty_no_rpm": (["beam", "--variant", "{V:no_duty}"],
                            ["x2_57.toml", "duty.design_speeds_rpm", "--rpm"]),
    "campbell_no_duty_no_range": (["campbell", "--variant", "{V:no_duty}"],
                                  ["x2_57.toml", "duty.campbell_range_rpm", "RANGE"]),
})
CASES.update(DUTY_CASES)          # counted by the catalogue's coverage test



# --- issue #31, slice beamloads: `shaftfe beam` meets the loads (one line, exit 2) -----------
BEAM_LOAD_CASES = {
    "beam_torque_unreacted": (["beam", "--variant", "{V:load_torque_unreacted}"],
                              LOAD_EXPECT["load_torque_unreacted"]),
    "beam_unknown_case": (["beam", "--variant", "x2_57", "--case", "overload"],
                          ["--case", "[[load_cases]] name", "overload"]),
    "beam_set_load_outside": (["beam", "--variant", "{V:load_force_in_wrong_unit}", "--set",
                               "loads.f.F_N=100.0", "--set", "loads.f.x_mm=-3.0"],
                              ["--set loads.f.x_mm=-3.0", "x_mm", "on the shaft"]),
}
CASES.update(BEAM_LOAD_CASES)

# --- slice fatproto (issue #31 §5: the fatigue methods behind one registry) --------------------
# an unknown --method is refused by the registry (fatigue.methods.get_method), naming every
# registered method, before any input is read
FP_CASES = {
    "fatigue_unknown_method": (["fatigue", "{RPM}", "--method", "goodman", "--out", "{W}/o"],
                               ["--method", "goodman", "seed | fkm | din743"]),
    # the along-the-shaft plot is the two standards' (FKM on the field, DIN 743 on the beam);
    # the seed method has none, and must not seem to have drawn one
    "fatigue_seed_plot": (["fatigue", "{RPM}", "--method", "seed", "--plot", "--out", "{W}/o"],
                          ["--plot", "fkm | din743"]),
}
CASES.update(FP_CASES)

# a study's fatigue method by name from the same registry; a key of an option the method does
# not use is refused by the command's rule (study.spec.FATIGUE_KEY_OPTIONS)
_FP_FATIGUE = STUDY_HEAD + '[analyses]\nstatic = { level = "coarse" }\nfatigue = { spectrum = ' \
    '"over.dat", '
STUDY_FILES.update({
    "fp_method_unknown.toml": _FP_FATIGUE + 'method = "goodman" }\n',
    "fp_material_with_fkm.toml": _FP_FATIGUE + 'method = "fkm", material = "14220" }\n',
})
FP_STUDY_CASES = {
    "study_fatigue_method_unknown": (["study", "run", "{W}/fp_method_unknown.toml", "--out",
                                      "{W}/o"], ["analyses.fatigue.method", "goodman",
                                                 "seed | fkm | din743"]),
    "study_fatigue_material_with_fkm": (["study", "run", "{W}/fp_material_with_fkm.toml",
                                         "--out", "{W}/o"],
                                        ["analyses.fatigue.material", "only with method = seed",
                                         "not used by method fkm"]),
}
STUDY_CASES.update(FP_STUDY_CASES)

# a study's static model: the full 3D one or the zoned one (the axisymmetric model alone has no
# keyway peaks for the row)
STUDY_FILES["static_model_axi.toml"] = (STUDY_HEAD + '[analyses]\nstatic = { model = '
                                         '"axisymmetric", level = "coarse" }\n')
SM_STUDY_CASES = {"study_static_model_axisymmetric": (
    ["study", "run", "{W}/static_model_axi.toml", "--out", "{W}/o"],
    ["analyses.static.model", "axisymmetric", "solid | zoned"])}
STUDY_CASES.update(SM_STUDY_CASES)      # (the table's own test was parametrized above)


@pytest.mark.parametrize("case", sorted(SM_STUDY_CASES))
def test_study_static_model(case, study_space, capsys, monkeypatch):
    test_bad_study_input_is_one_clear_line_exit_2_and_writes_nothing(case, study_space, capsys,
                                                                     monkeypatch)


@pytest.mark.parametrize("case", sorted(FP_STUDY_CASES))
def test_fp_study_fatigue_method(case, study_space, capsys, monkeypatch):
    test_bad_study_input_is_one_clear_line_exit_2_and_writes_nothing(case, study_space, capsys,
                                                                     monkeypatch)
# --- issue #31, the static check's load case: an unknown case, a case with the seed method
STATIC_CASES = {
    "fatigue_din743_unknown_case": (
        ["fatigue", "{RPM}", "--method", "din743", "--variant",
         str(GEOMETRY_DIR / "examples" / "x2_57_driven.toml"), "--case", "overload", "--out",
         "{W}/o"], ["--case", "overload", "run_up"]),
    "fatigue_seed_case": (["fatigue", "{RPM}", "--case", "run_up", "--out", "{W}/o"],
                          ["--case", "din743"]),
}
CASES.update(STATIC_CASES)

# --- issue #31, the 3D static path's load cases (h/solidloads): --case must name a case of the
# variant, and a case brings its own speed
SOLID_CASES = {
    "static_unknown_case": (["static", "--variant", "x2_57", "--case", "overload", "--out",
                             "{W}/o"], ["--case", "overload", "[[load_cases]] name", "(it has "
                                        "none)"]),
    "static_case_with_rpm": (["static", "--variant", "x2_57", "--case", "overload", "--rpm",
                              "5000", "--out", "{W}/o"], ["--case", "--rpm", "absent with "
                                                          "--case"]),
    "static_case_axisymmetric": (["static", "--variant", "x2_57", "--case", "overload",
                                  "--model", "axisymmetric", "--out", "{W}/o"],
                                 ["--case", "overload", "[[load_cases]] name"]),
}
CASES.update(SOLID_CASES)

# --- issue #32 item 5 (h/modes): the harmonic rotor model is a Campbell/modal model, not yet
# one of the report's (it would otherwise fall back to the beam silently)
MODES_CASES = {
    "report_rotor_model_harmonic": (["report", "--rotor-model", "harmonic", "--out", "{W}/o"],
                                    ["--rotor-model", "beam | solid", "harmonic"]),
    "campbell_harmonic_stress_stiffening": (["campbell", "0:8000", "--model", "harmonic",
                                             "--stress-stiffening", "--out", "{W}/o"],
                                            ["--stress-stiffening", "harmonic", "solid"]),
}
CASES.update(MODES_CASES)


# the tables defined after the catalogue's own parametrisation (each merged into CASES, so the
# coverage test counts it): one test runs them under the same contract
LATER_CASES = {**B_CASES, **MATERIAL_CASES, **F2_CASES, **LOAD_CASES, **DUTY_CASES,
               **BEAM_LOAD_CASES, **FP_CASES, **STATIC_CASES, **SOLID_CASES, **MODES_CASES}


@pytest.mark.parametrize("case", sorted(LATER_CASES))
def test_later_tables_are_one_clear_line_exit_2(case, space, capsys, monkeypatch):
    test_bad_input_is_one_clear_line_exit_2_and_writes_nothing(case, space, capsys, monkeypatch)


# --- issue #34, one rule per limit: every speed under util.limits.RPM_CEILING (an engine file's
# and balance twin's --rpm too), and shaftfe static's options refused by the options class's
# own rules (static.model.check_options)
LIMIT_FILES = {
    "fast_engine.toml": (GEOMETRY_DIR / "engines" / "vm450.toml").read_text(encoding="utf-8")
    .replace("max_rpm = 9500.0", "max_rpm = 50000.0"),
}
LIMIT_CASES = {
    "engine_max_rpm_above_ceiling": (["balance", "forces", "--engine", "{W}/fast_engine.toml"],
                                     ["fast_engine.toml", "max_rpm", "(0, 20000] rpm"]),
    "balance_twin_rpm_above_ceiling": (["balance", "twin", "--delta", "60", "--rpm", "50000"],
                                       ["--rpm", "50000", "(0, 20000] rpm"]),
    "static_order_3": (["static", "--variant", "x2_57", "--order", "3", "--out", "{W}/o"],
                       ["--order", "1 | 2"]),
    "static_solver_unknown": (["static", "--variant", "x2_57", "--solver", "umfpack", "--out",
                               "{W}/o"], ["--solver", "auto | superlu | pardiso | amg"]),
    "static_exclude_band_too_wide": (["static", "--variant", "x2_57", "--exclude-mm", "7",
                                      "--out", "{W}/o"], ["--exclude-mm", "[0, 5] mm"]),
    # one rule of output file names (util.atomic.check_suffix), whichever command
    "forces_plot_as_jpg": (["balance", "forces", "--plot", "{W}/f.jpg"],
                           ["--plot", "file extension", ".png | .pdf | .svg"]),
    "twin_plot_as_txt": (["balance", "twin", "--delta", "60", "--plot", "{W}/t.txt"],
                         ["--plot", "file extension", ".png | .pdf | .svg"]),
    "beam_plot_as_txt": (["beam", "--variant", "x2_57", "--plot", "{W}/b.txt"],
                         ["--plot", "file extension", ".png | .pdf | .svg"]),
    "mesh_out_as_stl": (["mesh", "--variant", "x2_57", "--out", "{W}/m.stl"],
                        ["--out", "file extension", ".vtu | .msh"]),
    "view_screenshot_as_bmp": (["view", "{W}/afile", "--screenshot", "{W}/v.bmp"],
                               ["--screenshot", "file extension", ".png | .jpg | .jpeg"]),
    # the crank mechanism's and the layouts' rules, in balance.multi (the command parses only)
    "twin_offset_negative": (["balance", "twin", "--delta", "60", "--offset-mm", "-5"],
                             ["--offset-mm", "-5", ">= 0 mm"]),
    "inline_gap_negative": (["balance", "inline", "--pins", "0,180", "--spacing-mm", "-80"],
                            ["--spacing-mm", "-80", "gaps >= 0 mm"]),
    "twin_samples_too_few": (["balance", "twin", "--delta", "60", "--samples", "4"],
                             ["--samples", "8 <= samples <= 1000000"]),
    "twin_rod_shorter_than_crank": (["balance", "twin", "--delta", "60", "--rod-mm", "20",
                                     "--radius-mm", "30"], ["rod length", "> crank radius 30"]),
    "inline_samples_past_a_float": (["balance", "inline", "--pins", "0,180", "--spacing-mm",
                                     "80", "--samples", "9" * 400],
                                    ["--samples", "8 <= samples <= 1000000"]),
    "inline_orders_past_a_float": (["balance", "inline", "--pins", "0,180", "--spacing-mm",
                                    "80", "--orders", "9" * 400], ["--orders", "integers in"]),
    "inline_orders_past_nyquist": (["balance", "inline", "--pins", "0,180", "--spacing-mm",
                                    "80", "--samples", "16", "--orders", "9"],
                                   ["--orders", "integers in [1, 7]"]),
    "forces_plot_empty": (["balance", "forces", "--plot", ""], ["--plot", "a file name"]),
    # a sweep's size, in rotordynamics.options (modes: the command and analyse; speeds: the
    # command line's RANGE/--step)
    "campbell_modes_too_many": (["campbell", "0:8000", "--modes", "500"], ["--modes", "1..200"]),
    "campbell_speeds_too_many": (["campbell", "0:8000:1"], ["RANGE/--step", "2001 speeds"]),
}
CASES.update(LIMIT_CASES)


@pytest.mark.parametrize("case", sorted(LIMIT_CASES))
def test_limits_are_one_rule_one_clear_line_exit_2(case, space, capsys, monkeypatch):
    _, w = space
    for name, text in LIMIT_FILES.items():
        (w / name).write_text(text, encoding="utf-8")
    test_bad_input_is_one_clear_line_exit_2_and_writes_nothing(case, space, capsys, monkeypatch)
