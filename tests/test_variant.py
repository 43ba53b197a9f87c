"""Variant files: loader, includes, provenance, validation errors, content hash, CLI (issue 3)."""

import dataclasses
import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from shaftfe.errors import InputError
from shaftfe.model.loader import load_variant
from shaftfe.model.mass import mass_properties
from shaftfe.model.parse import list_variants
from shaftfe.model.variant import SOURCES
from shaftfe.util.paths import GEOMETRY_DIR

VARIANTS = ("x2_31", "x2_42", "x2_50", "x2_57")


def _copy_geometry(tmp_path: Path) -> Path:
    dst = tmp_path / "geometry"
    shutil.copytree(GEOMETRY_DIR, dst, ignore=shutil.ignore_patterns("*.md", "engines"))
    return dst


def _edit(path: Path, old: str, new: str) -> None:
    text = path.read_text(encoding="utf-8")
    assert text.count(old) == 1, f"{old!r} must occur once in {path.name}"
    path.write_text(text.replace(old, new), encoding="utf-8")


def test_list_variants_has_the_four_counterweight_pairs():
    assert list_variants() == list(VARIANTS)


@pytest.mark.parametrize("name", VARIANTS)
def test_variant_loads_with_contiguous_segments_and_files(name):
    v = load_variant(name)
    assert v.name == name
    assert v.source_files[0].endswith(f"{name}.toml")
    assert len(v.source_files) == 6                      # the variant + 5 common includes
    for a, b in zip(v.segments, v.segments[1:], strict=False):
        assert b.x_start_mm == pytest.approx(a.x_end_mm)   # exact sums of mm: default rel 1e-6
    assert v.segments[0].x_start_mm == 0.0
    assert [b.name for b in v.bearings] == ["gear_side", "free_side"]
    assert [b.axial for b in v.bearings] == [True, False]


def test_load_by_path_equals_load_by_name():
    a = load_variant("x2_57")
    b = load_variant(GEOMETRY_DIR / "x2_57.toml")
    assert a.content_hash == b.content_hash
    assert a == b


@pytest.mark.parametrize("name", VARIANTS)
def test_every_numeric_value_has_exactly_one_known_source(name):
    """Provenance: the loader rejects a numeric key without a source, so every numeric value in
    the resolved files appears in Variant.provenance with one of the four sources."""
    v = load_variant(name)
    assert set(v.provenance.source.values()) <= set(SOURCES)
    for s in v.segments:
        for f in ("length_mm", "diameter_mm", "fillet_mm"):
            assert f"segments.{s.name}.{f}" in v.provenance.source
    for a in v.attachments:
        for f in ("mass_kg", "eccentricity_mm", "x_centroid_mm"):
            assert f"attachments.{a.name}.{f}" in v.provenance.source
    assert v.provenance.source["bearing_types.zkl_3203.K_N_per_mm"] == "seed"
    assert v.provenance.source["bearing_types.zkl_3203.C_N"] == "derived"
    assert "segments.collar" in v.provenance.note


def test_seed_and_reconstructed_counterweights_are_marked():
    """x2_57's counterweight masses are seed (§8.2.2 forces); the other variants' are fitted."""
    v57, v31 = load_variant("x2_57"), load_variant("x2_31")
    assert v57.provenance.source["attachments.counterweight_2.mass_kg"] == "seed"
    assert v31.provenance.source["attachments.counterweight_2.mass_kg"] == "reconstructed"
    assert v31.provenance.source["attachments.counterweight_1.eccentricity_mm"] == \
        "reconstructed"


def test_seed_load_case_keeps_gear_and_counterweights_only():
    v = load_variant("x2_57").with_seed_load_case()
    assert sorted(a.name for a in v.attachments) == ["counterweight_1", "counterweight_2", "gear"]


# --- content hash -----------------------------------------------------------------------------

def test_hash_ignores_comments_whitespace_and_notes(tmp_path):
    g = _copy_geometry(tmp_path)
    ref = load_variant(g / "x2_57.toml").content_hash
    shaft = g / "common" / "shaft_c.toml"
    shaft.write_text("# a new comment\n\n" + shaft.read_text(encoding="utf-8")
                     .replace("length_mm = 17.5\ndiameter_mm = 22.0",
                              "length_mm   =   17.5\ndiameter_mm = 22.000"), encoding="utf-8")
    _edit(g / "x2_57.toml", 'note = "The web joining', 'note = "Edited note. The web joining')
    assert load_variant(g / "x2_57.toml").content_hash == ref


def test_hash_changes_with_geometry(tmp_path):
    g = _copy_geometry(tmp_path)
    ref = load_variant(g / "x2_57.toml").content_hash
    _edit(g / "common" / "shaft_c.toml", "diameter_mm = 22.0", "diameter_mm = 21.0")
    assert load_variant(g / "x2_57.toml").content_hash != ref


def test_hash_differs_between_variants():
    hashes = {load_variant(n).content_hash for n in VARIANTS}
    assert len(hashes) == len(VARIANTS)
    assert all(len(h) == 64 for h in hashes)


# --- impossible files: one InputError naming the file and the field ---------------------------

SHAFT = "common/shaft_c.toml"
BEAR = "common/bearings.toml"
COLLAR = 'name = "collar"\nkind = "plain"\nlength_mm = 17.5\ndiameter_mm = 22.0\nfillet_mm = 0.6'

BAD_CASES = {
    "negative_length": (SHAFT, COLLAR, COLLAR.replace("length_mm = 17.5", "length_mm = -3.0"),
                        SHAFT, "segments[4].length_mm"),
    "zero_diameter": (SHAFT, COLLAR, COLLAR.replace("diameter_mm = 22.0", "diameter_mm = 0.0"),
                      SHAFT, "segments[4].diameter_mm"),
    "fillet_larger_than_step": (SHAFT, COLLAR, COLLAR.replace("fillet_mm = 0.6",
                                                              "fillet_mm = 3.0"),
                                SHAFT, "segments[4].fillet_mm"),
    "fillet_without_step": (SHAFT, 'name = "gear_seat"\nkind = "seat"\nlength_mm = 10.0\n'
                            'diameter_mm = 17.0\nfillet_mm = 0.0',
                            'name = "gear_seat"\nkind = "seat"\nlength_mm = 10.0\n'
                            'diameter_mm = 17.0\nfillet_mm = 0.5', SHAFT, "segments[1].fillet_mm"),
    "fillet_longer_than_segment": (SHAFT, "length_mm = 7.0\ndiameter_mm = 13.773",
                                   "length_mm = 0.3\ndiameter_mm = 13.773",
                                   SHAFT, "segments[6].fillet_mm"),
    "above_stock": (SHAFT, COLLAR, COLLAR.replace("diameter_mm = 22.0", "diameter_mm = 26.0"),
                    SHAFT, "segments[4].diameter_mm"),
    "keyway_outside_segment": (SHAFT, "x_center_mm = 11.0", "x_center_mm = 3.0",
                               SHAFT, "segments[1].keyways[0].x_center_mm"),
    "keyway_too_deep": (SHAFT, "depth_mm = 3.0\nlength_mm = 8.0\nx_center_mm = 11.0",
                        "depth_mm = 9.0\nlength_mm = 8.0\nx_center_mm = 11.0",
                        SHAFT, "segments[1].keyways[0].depth_mm"),
    "bearing_outside_shaft": (SHAFT, "x_center_mm = 38.25", "x_center_mm = 5.0",
                              SHAFT, "bearings[0].x_center_mm"),
    "bearing_on_collar": (SHAFT, "x_center_mm = 73.25", "x_center_mm = 56.0",
                          SHAFT, "bearings[1].x_center_mm"),
    "bearing_without_stiffness": (BEAR, "K_N_per_mm = [[35030.0, 8756.0], [8756.0, 35030.0]]\n",
                                  "", BEAR, "bearing_types.zkl_3203.K_N_per_mm"),
    "K_not_symmetric": (BEAR, "[[35030.0, 8756.0], [8756.0, 35030.0]]",
                        "[[35030.0, 8756.0], [8000.0, 35030.0]]",
                        BEAR, "bearing_types.zkl_3203.K_N_per_mm (bearing 'gear_side')"),
    "K_not_positive_definite": (BEAR, "[[35030.0, 8756.0], [8756.0, 35030.0]]",
                                "[[5000.0, 8756.0], [8756.0, 5000.0]]",
                                BEAR, "bearing_types.zkl_3203.K_N_per_mm (bearing 'gear_side')"),
    "K_wrong_shape": (BEAR, "[[35030.0, 8756.0], [8756.0, 35030.0]]", "[35030.0, 8756.0]",
                      BEAR, "bearing_types.zkl_3203.K_N_per_mm"),
    "chamfer_below_iso15_minimum": (BEAR, "chamfer_mm = 2.0", "chamfer_mm = 0.4",
                                    BEAR, "bearing_types.zkl_3203.chamfer_mm"),
    "chamfer_eats_the_ring": (BEAR, "chamfer_mm = 2.0", "chamfer_mm = 5.0",
                              BEAR, "bearing_types.zkl_3203.chamfer_mm"),
    "two_axial_bearings": (SHAFT, "axial = false", "axial = true", SHAFT, "bearings[*].axial"),
    "unknown_shaft_material": (SHAFT, 'material = "14220"', 'material = "99999"',
                               SHAFT, "shaft.material"),
    "unknown_attachment_material": ("x2_57.toml", 'material = "12050"\nseed_load_case = true\n'
                                    'seed = ["mass_kg", "eccentricity_mm"]\nreconstructed = '
                                    '["angle_deg", "x_centroid_mm"]\nderived = ["polar_inertia_'
                                    'kg_mm2", "diametral_inertia_kg_mm2"]\nnote = """m and e: '
                                    'seed §8.2.2 (F_v1',
                                    'material = "unobtainium"\nseed_load_case = true\n'
                                    'seed = ["mass_kg", "eccentricity_mm"]\nreconstructed = '
                                    '["angle_deg", "x_centroid_mm"]\nderived = ["polar_inertia_'
                                    'kg_mm2", "diametral_inertia_kg_mm2"]\nnote = """m and e: '
                                    'seed §8.2.2 (F_v1', "x2_57.toml", "attachments[0].material"),
    "unknown_include": ("x2_57.toml", '"common/duty_vm450.toml"]', '"common/duty_vm450.toml", '
                        '"common/nope.toml"]', "x2_57.toml", "include[5]"),
    "seat_not_a_segment": ("x2_57.toml", 'seat = "cw2_seat"', 'seat = "nowhere"',
                           "x2_57.toml", "attachments[1].seat"),
    "negative_mass": ("x2_57.toml", "mass_kg = 0.24\n", "mass_kg = -0.24\n",
                      "x2_57.toml", "attachments[1].mass_kg"),
    "missing_provenance": (SHAFT, 'reconstructed = ["length_mm", "diameter_mm", "fillet_mm"]\n'
                           'note = """Collar', 'reconstructed = ["diameter_mm", "fillet_mm"]\n'
                           'note = """Collar', SHAFT, "segments[4].length_mm"),
    "double_provenance": (BEAR, 'derived = ["C_N"]', 'derived = ["C_N", "bore_mm"]',
                          BEAR, "bearing_types.zkl_3203.bore_mm"),
    "unknown_field": (SHAFT, COLLAR, COLLAR + "\ndiametre_mm = 3.0", SHAFT,
                      "segments[4].diametre_mm"),
    "hex_too_big_for_end": (SHAFT, "across_flats_mm = 8.0", "across_flats_mm = 12.5",
                            SHAFT, "hex_socket.across_flats_mm"),
    "parting_plane_off_shaft": (SHAFT, "parting_plane_x_mm = 54.107", "parting_plane_x_mm = 200.0",
                                SHAFT, "shaft.parting_plane_x_mm"),
}


@pytest.mark.parametrize("case", sorted(BAD_CASES))
def test_impossible_file_gives_one_input_error_naming_file_and_field(tmp_path, case):
    rel, old, new, bad_file, field = BAD_CASES[case]
    g = _copy_geometry(tmp_path)
    _edit(g / rel, old, new)
    with pytest.raises(InputError) as exc:
        load_variant(g / "x2_57.toml")
    err = exc.value
    assert err.field == field
    assert Path(err.source).name == Path(bad_file).name
    assert "\n" not in str(err)


def test_invalid_toml_is_an_input_error(tmp_path):
    p = tmp_path / "broken.toml"
    p.write_text('name = "x"\n[shaft\n', encoding="utf-8")
    with pytest.raises(InputError) as exc:
        load_variant(p)
    assert exc.value.field == "file"


def test_unknown_variant_name():
    with pytest.raises(InputError) as exc:
        load_variant("x2_99")
    assert "x2_57" in exc.value.allowed


def test_include_cycle_is_rejected(tmp_path):
    g = _copy_geometry(tmp_path)
    mats = g / "common" / "materials.toml"
    mats.write_text('include = ["../x2_57.toml"]\n' + mats.read_text(encoding="utf-8"),
                    encoding="utf-8")
    with pytest.raises(InputError) as exc:
        load_variant(g / "x2_57.toml")
    assert exc.value.field == "include[0]"


def test_duplicate_definition_across_files_is_rejected(tmp_path):
    g = _copy_geometry(tmp_path)
    parts = g / "common" / "parts.toml"
    parts.write_text(parts.read_text(encoding="utf-8")
                     + '\n[materials.14220]\nE_MPa = 1.0\nstandard = ["E_MPa"]\n',
                     encoding="utf-8")
    with pytest.raises(InputError) as exc:
        load_variant(g / "x2_57.toml")
    assert exc.value.field == "materials.14220"


# --- CLI ----------------------------------------------------------------------------------------

def _cli(*args):
    return subprocess.run([sys.executable, "-m", "shaftfe", *args], capture_output=True,
                          text=True)


def test_cli_check_bad_file_is_one_line_exit_2(tmp_path):
    g = _copy_geometry(tmp_path)
    _edit(g / SHAFT, COLLAR, COLLAR.replace("length_mm = 17.5", "length_mm = -3.0"))
    out = _cli("variant", "check", str(g / "x2_57.toml"))
    assert out.returncode == 2
    assert "Traceback" not in out.stderr
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1
    assert "shaft_c.toml" in lines[0] and "segments[4].length_mm" in lines[0]
    assert "[0.2, 2000] mm" in lines[0]


def test_cli_check_good_file():
    out = _cli("variant", "check", str(GEOMETRY_DIR / "x2_31.toml"))
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("OK x2_31")


def test_cli_show_json_matches_api():
    out = _cli("variant", "show", "x2_57", "--json", "--rpm", "10000")
    assert out.returncode == 0, out.stderr
    rep = json.loads(out.stdout)
    v = load_variant("x2_57")
    assert rep["content_hash"] == v.content_hash
    assert [s["name"] for s in rep["segments"]] == [s.name for s in v.segments]
    cw2 = next(a for a in rep["attachments"] if a["name"] == "counterweight_2")
    assert cw2["source"]["mass_kg"] == "seed"
    # exact arithmetic: the same computation, JSON floats round-trip (approx's default 1e-6)
    assert cw2["force_N"]["10000"] == pytest.approx(v.attachment("counterweight_2")
                                                    .force_N(10000))
    assert rep["mass_properties"]["mass_kg"] == pytest.approx(mass_properties(v).mass_kg)  # same


def test_cli_show_table_and_list_run():
    out = _cli("variant", "show", "x2_42")
    assert out.returncode == 0, out.stderr
    assert "counterweight_2" in out.stdout and "rigid-support reactions" in out.stdout
    out = _cli("variant", "list")
    assert out.returncode == 0, out.stderr
    assert all(n in out.stdout for n in VARIANTS)


def test_cli_bad_rpm_is_one_line_exit_2():
    out = _cli("variant", "show", "x2_57", "--rpm", "fast")
    assert out.returncode == 2
    assert len(out.stderr.strip().splitlines()) == 1


def test_variant_is_frozen():
    v = load_variant("x2_57")
    with pytest.raises(dataclasses.FrozenInstanceError):
        v.name = "other"  # type: ignore[misc]


# --------------------------------------------------------------------------- --set, variant new

def test_set_equals_editing_the_file_and_is_recorded(tmp_path):
    """Reference: the same value edited into a copy of the files by hand. --set changes that one
    key (the same physics, content hash and segment), leaves the files alone and is recorded."""
    g = _copy_geometry(tmp_path)
    _edit(g / SHAFT, COLLAR, COLLAR.replace("fillet_mm = 0.6", "fillet_mm = 0.5"))
    by_hand = load_variant(g / "x2_57.toml")
    by_set = load_variant("x2_57", {"segments.collar.fillet_mm": 0.5})
    assert by_set.content_hash == by_hand.content_hash != load_variant("x2_57").content_hash
    assert by_set.segment("collar").fillet_mm == 0.5
    assert by_set.overrides == (("segments.collar.fillet_mm", 0.5),)
    assert load_variant("x2_57").overrides == ()
    # the CLI form (a TOML value after '='), a keyway by index, a part's table and an integer
    # typed for a float all reach the same keys
    v = load_variant("x2_57", ["segments.collar.fillet_mm=0.5",
                               "segments.gear_seat.keyways.0.depth_mm=2.5",
                               "parts.gear.mass_kg=0.155", "shaft.material=16220"])
    assert v.segment("collar").fillet_mm == 0.5
    assert v.segment("gear_seat").keyways[0].depth_mm == 2.5
    assert next(a for a in v.attachments if a.name == "gear").mass_kg == 0.155
    assert v.material.name == "16220"
    # an overridden value is tagged "set" in the provenance (it no longer is what its list says)
    tags = dict(v.provenance.source)
    changed = {k for k, t in tags.items() if t != load_variant("x2_57").provenance.source[k]}
    assert changed == {"segments.collar.fillet_mm", "segments.gear_seat.keyways[0].depth_mm",
                       "attachments.gear.mass_kg"} and {tags[k] for k in changed} == {"set"}


@pytest.mark.parametrize("path, value, expect", [
    ("segments.colar.fillet_mm", 0.5, "nearest: collar"),
    ("segments.collar.filet_mm", 0.5, "nearest: fillet_mm"),
    ("sgments.collar.fillet_mm", 0.5, "nearest: segments"),
    ("attachments.counterweight_3.mass_kg", 0.2, "nearest: counterweight_2, counterweight_1"),
    ("segments.collar", 0.5, "a path to one value"),
    ("segments.collar.fillet_mm", "wide", "a number (as in the variant file)"),
    ("segments.collar.seed", 1.0, "a key of segments.collar"),       # provenance: not settable
])
def test_set_with_a_wrong_path_or_kind_names_the_set_and_the_nearest_names(path, value, expect):
    with pytest.raises(InputError) as e:
        load_variant("x2_57", {path: value})
    assert str(e.value).startswith(f"--set {path}=") and expect in str(e.value)


@pytest.mark.parametrize("path, value, expect", [
    ("segments.collar.fillet_mm", 9.0, "<= step height 2.5"),
    ("segments.collar.fillet_mm", 1.0, "r_s min of bearing 'free_side'"),     # ISO 582 abutment
    ("attachments.counterweight_2.mass_kg", 240.0, "typed in grams?"),
    ("segments.gear_seat.keyways.0.depth_mm", 12.0, "< radius / 2 (4.25)"),
    # a bottom radius: 0 or from 0.05 mm to 0.4 × width (2.0) and half the side wall (Ø17,
    # 5 wide, 3 deep: 3 − (8.5 − √(8.5² − 2.5²)) = 2.624 mm, half 1.312)
    ("segments.gear_seat.keyways.0.bottom_radius_mm", 1.4, "0 (sharp) or 0.05 … 1.31 mm"),
    ("segments.gear_seat.keyways.0.bottom_radius_mm", 0.02, "0 (sharp) or 0.05 … 1.31 mm"),
])
def test_set_out_of_range_is_checked_as_the_file_would_be_and_names_the_set(path, value, expect):
    """The loader's own range checks apply; the error names the --set, not the include file."""
    with pytest.raises(InputError) as e:
        load_variant("x2_57", {path: value})
    assert str(e.value).startswith(f"--set {path}=") and expect in str(e.value)


def test_cli_set_is_recorded_and_a_bad_set_is_one_line_exit_2():
    out = _cli("beam", "--variant", "x2_57", "--json", "--set", "segments.collar.fillet_mm=0.5")
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout)["overrides"] == {"segments.collar.fillet_mm": 0.5}
    for bad in ("segments.colar.fillet_mm=0.5", "segments.collar.fillet_mm", "a.b=1=2"):
        out = _cli("variant", "check", "x2_57", "--set", bad)
        assert out.returncode == 2 and "Traceback" not in out.stderr
        assert len(out.stderr.strip().splitlines()) == 1 and "--set" in out.stderr


@pytest.mark.parametrize("name", VARIANTS)
def test_toml_writer_round_trips_every_resolved_variant(name):
    """tomllib (the standard library's reader) is the reference: reading the written text gives
    back the same dictionary, exactly (floats are written by repr, which round-trips)."""
    import tomllib

    from shaftfe.model.parse import resolve_path, resolved_dict
    from shaftfe.model.tomlwrite import dumps
    d = resolved_dict(resolve_path(name))
    assert tomllib.loads(dumps(d, "a header\nof two lines")) == d


def test_variant_new_writes_a_self_contained_equal_variant(tmp_path):
    """The new file has no includes, the same physics (content hash) and the same provenance
    tags as its source; --set values go into it; an existing file is never overwritten."""
    out = tmp_path / "mine.toml"
    r = _cli("variant", "new", "mine", "--out", str(out))
    assert r.returncode == 0, r.stderr
    assert "include" not in out.read_text(encoding="utf-8").split("\n\n", 1)[1]
    v, ref = load_variant(out), load_variant("x2_57")
    assert v.name == "mine" and len(v.source_files) == 1          # no include was read
    assert v.content_hash == ref.content_hash
    assert dict(v.provenance.source) == dict(ref.provenance.source)
    r = _cli("variant", "new", "mine", "--out", str(out))
    assert r.returncode == 2 and "not overwritten" in r.stderr
    out2 = tmp_path / "mine2.toml"
    r = _cli("variant", "new", "mine2", "--out", str(out2), "--set",
             "segments.collar.fillet_mm=0.5")
    assert r.returncode == 0, r.stderr
    assert load_variant(out2).content_hash == load_variant(
        "x2_57", {"segments.collar.fillet_mm": 0.5}).content_hash


def _docs_variants():
    import importlib.util
    spec = importlib.util.spec_from_file_location(
        "docs_variants", GEOMETRY_DIR.parent / "docs" / "variants.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_docs_variants_md_is_the_generated_one_and_its_example_checks():
    """docs/VARIANTS.md is what docs/variants.py renders now (its ranges come from the loader's
    bounds), and its minimal example is a complete variant the loader accepts."""
    doc = _docs_variants()
    assert doc.OUT.read_text(encoding="utf-8") == doc.render()
    v = load_variant(doc.EXAMPLE)
    assert (len(v.segments), len(v.bearings), len(v.attachments)) == (3, 2, 1)


@pytest.mark.parametrize("name", VARIANTS)
def test_every_key_of_every_shipped_variant_is_documented(name):
    """Each key the files define, as a documented path pattern (names → <…>), has a row in
    docs/VARIANTS.md's key table."""
    import re

    from shaftfe.model.fields import PROV_KEYS
    from shaftfe.model.parse import resolve_path, resolved_dict
    documented = {p for p, *_ in _docs_variants().keys()}
    generic = {re.sub(r"<[a-z]+>", "<>", p) for p in documented}
    found = set()

    def walk(d, path):
        for k, val in d.items():
            if k in PROV_KEYS:
                continue
            if isinstance(val, dict):
                walk(val, (*path, k))
            elif isinstance(val, list) and val and all(isinstance(e, dict) for e in val):
                for e in val:
                    walk(e, (*path, k, "<>"))
            else:
                found.add(".".join((*path, k)))
    d = resolved_dict(resolve_path(name))
    for table_name in ("materials", "bearing_types", "parts"):
        for entry in d.pop(table_name, {}).values():
            walk(entry, ("attachments" if table_name == "parts" else table_name, "<>"))
    walk(d, ())
    missing = []
    for p in sorted(found):
        q = re.sub(r"^shaft\.(segments|bearings)\.", r"\1.", p)
        q = re.sub(r"^attachments\.<>\.shape\..*", "attachments.<>.shape.<>", q)
        if q not in generic:
            missing.append(p)
    assert not missing, missing


@pytest.mark.parametrize("text", [
    'back\\slash', 'quote " inside', 'three """ quotes', 'ends with a quote"', "tab\there",
    "line\nbreak", "line\nbreak ending in a quote\"", "cr\r\nlf", "bell\x07", "del\x7f",
    "\nleading newline", "backslash at end of line\\\nnext", "unicode Ø ω² ≤",
])
def test_toml_writer_round_trips_awkward_strings_and_keys(text):
    """tomllib is the reference: strings with quotes, backslashes and control characters, as
    values and as keys (which must then be quoted), read back exactly."""
    import tomllib

    from shaftfe.model.tomlwrite import dumps
    d = {"note": text, "t": {text: 1.5, "list": [text, 2]}, "rows": [{"name": text}]}
    assert tomllib.loads(dumps(d)) == d


def test_set_paths_are_canonical_tagged_recorded_as_applied_and_set_once():
    """Index paths and the shaft. prefix reach the same key as the names, are recorded by
    name, tag the provenance; a name typed as a number is recorded as the name it became; one
    key set twice (two spellings) is an error."""
    v = load_variant("x2_57", ["shaft.segments.4.fillet_mm=0.5", "shaft.material=16220",
                               "shaft.hex_socket.depth_mm=9.0"])
    assert v.overrides == (("segments.collar.fillet_mm", 0.5), ("shaft.material", "16220"),
                           ("shaft.hex_socket.depth_mm", 9.0))
    assert v.provenance.source["segments.collar.fillet_mm"] == "set"
    assert v.provenance.source["hex_socket.depth_mm"] == "set"
    with pytest.raises(InputError, match=r"fillet_mm=0\.4.*also set by --set segments\.collar"):
        load_variant("x2_57", ["segments.collar.fillet_mm=0.5", "segments.4.fillet_mm=0.4"])


@pytest.mark.parametrize("item, expect", [
    ("segments.collar.fillet_mm=0.5\njunk = 1", "one TOML value"),
    ('description="unclosed', "one TOML value"),
    ('name="../../tmp/evil"', "a file name"),             # it names output folders
])
def test_set_malformed_values_and_unsafe_names_are_refused(item, expect):
    with pytest.raises(InputError, match=expect) as e:
        load_variant("x2_57", [item])
    assert str(e.value).startswith("--set")


def test_an_error_that_follows_from_a_set_names_the_file_with_the_set():
    """A check of ANOTHER key that the --set value breaks (the hex socket moved to the other
    end no longer fits there) is reported as the file WITH the --set, not the file alone."""
    with pytest.raises(InputError) as e:
        load_variant("x2_57", ["shaft.hex_socket.end=left"])
    assert " with --set shaft.hex_socket.end=left" in str(e.value)


def test_default_output_folder_of_a_set_run_is_its_own():
    from shaftfe.commands._common import out_name
    assert out_name("x2_57") == "x2_57"
    a = out_name("x2_57", [("segments.collar.fillet_mm", 0.5)])
    assert a.startswith("x2_57_set_") and a != out_name("x2_57", [("segments.collar.fillet_mm",
                                                                     0.4)])


# ---------------------------------------------------------------- issue #30, b-static-variant

def test_ball_bearing_stiffness_estimate_against_a_catalogue_bearing():
    """The estimate's geometry steps against a bearing whose internals are published: the SKF
    6203 (17 × 40 mm, C = 9.95 kN, SKF catalogue) has 8 balls of 6.747 mm (17/64 in). Bounds:
    D_w = 0.3 (D − d) is a proportion of the series (3 %); Z follows from ISO 281 with a
    tabulated f_c read at a typical D_w/D_pw (±5 % on f_c is ±7.5 % on Z)."""
    from shaftfe.model.bearing_stiffness import estimate_ball
    e = estimate_ball(17.0, 40.0, 9950.0)
    assert e.ball_diameter_mm == pytest.approx(6.747, rel=0.03)
    assert e.balls_per_row == pytest.approx(8.0, rel=0.075)
    # the closed forms recomputed by hand for the ZKL 3203 (2 rows, 30°): exact arithmetic
    import math
    z = (14418.0 / (1.3 * 60.0 * (2 * math.cos(math.radians(30))) ** 0.7 * 6.9 ** 1.8)) ** 1.5
    q = 4.37 * 1441.8 / (2 * z * math.cos(math.radians(30)))
    d_r = 4.36e-4 * q ** (2 / 3) / 6.9 ** (1 / 3) / math.cos(math.radians(30))
    e2 = estimate_ball(17.0, 40.0, 14418.0, 2, 30.0)
    assert e2.K_N_per_mm == pytest.approx(1.5 * 1441.8 / d_r, rel=1e-12)


def test_every_bearing_type_in_geometry_is_inside_its_stiffness_band():
    """Each stated matrix of geometry/ within 1/20 … 3 × the estimate (the seed's bushing is
    3.1–5.1 × softer than the ZKL 3203's contacts); 1000 × either way is refused with the
    estimate named (the audit's 35.03 N/mm gave a 254.6 mm deflection)."""
    import math
    import tomllib

    from shaftfe.model.bearing_stiffness import estimate_ball
    types = tomllib.loads((GEOMETRY_DIR / "common" / "bearings.toml").read_text())
    for bt in types["bearing_types"].values():
        e = estimate_ball(bt["bore_mm"], bt["outer_diameter_mm"], bt["C_N"], bt["rows"],
                          bt["contact_angle_deg"])
        (k11, k12), (_, k22) = bt["K_N_per_mm"]
        h = math.hypot(0.5 * (k11 - k22), k12)
        lo, hi = e.band
        assert lo <= 0.5 * (k11 + k22) - h and 0.5 * (k11 + k22) + h <= hi
    path = "bearing_types.zkl_3203.K_N_per_mm"
    for f in (1e-3, 1e3):
        with pytest.raises(InputError, match=r"estimate 1\.34e"):
            load_variant("x2_57", {path: [[35030.0 * f, 8756.0 * f], [8756.0 * f, 35030.0 * f]]})


def test_a_shape_override_rederives_the_part_in_every_command():
    """`--set attachments.<part>.shape.*` re-derives mass, eccentricity, inertias and the
    balance statement (shaftfe.model.derive, the study's implementation) in load_variant, so
    every command sees the new part and the content hash changes; a study design's full set
    (already derived) loads to the same variant."""
    from shaftfe.beam.solve import analyse
    from shaftfe.model.derive import design_overrides
    from shaftfe.model.shapes import shape_mass_properties
    path = "attachments.counterweight_2.shape.outer_radius_mm"
    base, v = load_variant("x2_57"), load_variant("x2_57", {path: 42.0})
    cw = next(a for a in v.attachments if a.name == "counterweight_2")
    shape = {"kind": "hub_ring_plus_annular_sector", "thickness_mm": 25.0,
             "hub_outer_radius_mm": 12.0, "inner_radius_mm": 29.542, "outer_radius_mm": 42.0,
             "half_angle_deg": 79.4409}
    ref = shape_mass_properties(shape, v.material.density_t_mm3, 8.5)
    assert cw.mass_kg == pytest.approx(ref["mass_kg"], rel=1e-8)     # 9 digits kept
    assert cw.eccentricity_mm == pytest.approx(ref["eccentricity_mm"], rel=1e-8)
    assert cw.mass_kg > 0.24 and v.content_hash != base.content_hash
    assert v.balance_target.X2_percent > 60.0                        # restated from the parts
    study = load_variant("x2_57", design_overrides("x2_57", {path: 42.0}))
    assert study.content_hash == v.content_hash
    f = [b.F_N for b in analyse(v, 10000.0)[0].bearings]
    f0 = [b.F_N for b in analyse(base, 10000.0)[0].bearings]
    assert f[1] > f0[1] * 1.2                                        # the heavier part loads it
    with pytest.raises(InputError, match="follows from the shape"):
        load_variant("x2_57", {path: 42.0, "attachments.counterweight_2.mass_kg": 0.3})


def test_an_empty_included_file_is_named_not_an_empty_list(tmp_path):
    g = _copy_geometry(tmp_path)
    (g / "common" / "bearings.toml").write_text("", encoding="utf-8")
    with pytest.raises(InputError) as ei:
        load_variant(g / "x2_57.toml")
    assert "one of ;" not in str(ei.value) and "none is" in str(ei.value)


# ---------------------------------------------------------------- one set of rules (issue 34)

def _seg(v, i, **kw):
    segs = list(v.segments)
    segs[i] = dataclasses.replace(segs[i], **kw)
    return dataclasses.replace(v, segments=tuple(segs))


def _brg(v, i, **kw):
    brgs = list(v.bearings)
    brgs[i] = dataclasses.replace(brgs[i], **kw)
    return dataclasses.replace(v, bearings=tuple(brgs))


def _att(v, i, **kw):
    atts = list(v.attachments)
    atts[i] = dataclasses.replace(atts[i], **kw)
    return dataclasses.replace(v, attachments=tuple(atts))


def _key(v, i, **kw):
    s = v.segments[i]
    return _seg(v, i, keyways=(dataclasses.replace(s.keyways[0], **kw),))


# Each rule the loader applied to a file before issue 34, broken in a Variant made in Python
# (x2_57 with one field replaced): validate_variant refuses it as the file was refused, naming
# the Variant's field. id -> (the change, the field named, a word of the allowed range)
PYTHON_CASES = {
    "length_in_metres": (lambda v: _seg(v, 3, length_mm=0.0175), "segments[3].length_mm",
                         "metres"),
    "diameter_above_the_stock": (lambda v: _seg(v, 4, diameter_mm=26.0),
                                 "segments[4].diameter_mm", "stock diameter 25"),
    "fillet_in_metres": (lambda v: _seg(v, 4, fillet_mm=0.0006), "segments[4].fillet_mm",
                         "metres"),
    "unknown_segment_kind": (lambda v: _seg(v, 4, kind="spline"), "segments[4].kind",
                             "plain | seat | thread"),
    "fillet_taller_than_its_step": (lambda v: _seg(v, 3, fillet_mm=2.6),
                                    "segments[3].fillet_mm", "step height 2.5"),
    "fillet_without_a_step": (lambda v: _seg(v, 1, fillet_mm=0.4), "segments[1].fillet_mm",
                              "no step"),
    "keyway_off_its_segment": (lambda v: _key(v, 1, x_center_mm=14.0),
                               "segments[1].keyways[0].x_center_mm", "inside the segment"),
    "bearing_stiffness_in_N_per_m": (
        lambda v: _brg(v, 0, K_N_per_mm=((3.5e10, 0.0), (0.0, 3.5e10))),
        "bearings[0].K_N_per_mm (bearing 'gear_side') (eigenvalue)", "N/m"),
    "bearing_stiffness_not_symmetric": (
        lambda v: _brg(v, 0, K_N_per_mm=((35030.0, 8756.0), (0.0, 35030.0))),
        "bearings[0].K_N_per_mm", "symmetric"),
    "C_in_kN": (lambda v: _brg(v, 1, C_N=14.4), "bearings[1].C_N", "kN"),
    "life_exponent_zero": (lambda v: _brg(v, 1, life_exponent=0.0), "bearings[1].life_exponent",
                           "ISO 281"),
    "chamfer_below_the_iso15_corner": (lambda v: _brg(v, 1, chamfer_mm=0.3),
                                       "bearings[1].chamfer_mm", "r_s_min_mm"),
    "bearing_off_its_bore": (lambda v: _brg(v, 1, x_center_mm=56.0), "bearings[1].x_center_mm",
                             "= bore 17"),
    "two_axial_bearings": (lambda v: _brg(v, 1, axial=True), "bearings[*].axial",
                           "exactly one"),
    "rings_sharing_a_seat": (lambda v: _brg(v, 1, x_center_mm=38.25),
                             "bearings[1].x_center_mm", "clear of bearing 'gear_side'"),
    "fillet_above_the_ring_corner": (lambda v: _brg(v, 0, r_s_min_mm=0.3, chamfer_mm=0.3),
                                     "segments[3].fillet_mm", "ISO 582"),
    "mass_in_grams": (lambda v: _att(v, 9, mass_kg=240.0), "attachments[9].mass_kg", "grams"),
    "centroid_far_off_the_shaft": (lambda v: _att(v, 9, x_centroid_mm=94500.0),
                                   "attachments[9].x_centroid_mm", "within 100 mm"),
    "negative_inertia": (lambda v: _att(v, 0, polar_inertia_kg_mm2=-1.0),
                         "attachments[0].polar_inertia_kg_mm2", ">= 0"),
    "seat_given_backwards": (lambda v: _att(v, 0, seat_x_start_mm=16.0, seat_x_end_mm=6.0),
                             "attachments[0].seat_x_mm", "x_start < x_end"),
    "hex_corners_through_the_end": (
        lambda v: dataclasses.replace(v, hex_socket=dataclasses.replace(
            v.hex_socket, across_flats_mm=13.0)), "hex_socket.across_flats_mm", "across-corners"),
    "parting_plane_off_the_shaft": (lambda v: dataclasses.replace(v, parting_plane_x_mm=500.0),
                                    "parting_plane_x_mm", "on the shaft"),
    "E_in_GPa": (lambda v: dataclasses.replace(v, material=dataclasses.replace(
        v.material, E_MPa=210.0)), "material.E_MPa", "GPa"),
    "ultimate_below_yield": (lambda v: dataclasses.replace(v, material=dataclasses.replace(
        v.material, ultimate_MPa=100.0)), "material.ultimate_MPa", ">= yield_MPa"),
}


@pytest.mark.parametrize("case", sorted(PYTHON_CASES))
def test_a_variant_made_in_python_meets_the_rules_a_file_meets(case):
    """One set of rules (issue 34): what the loader refused in a file before, validate_variant
    refuses in a Variant however it was made, naming the Variant's field and the variant."""
    from shaftfe.model.validate import validate_variant
    change, field, word = PYTHON_CASES[case]
    x2 = load_variant("x2_57")
    validate_variant(x2)                                  # as loaded: every rule holds
    with pytest.raises(InputError) as e:
        validate_variant(change(x2))
    assert e.value.field.startswith(field) and word in str(e.value)
    assert e.value.source == "geometry/x2_57.toml"        # source_of: the variant's first file


def test_the_plausible_ranges_are_for_typed_values_not_for_the_solvers():
    """A stiffness of 1e12 N/mm is a unit slip where a person typed it (the loader, ``--set``,
    validate_variant by hand) and a value the solvers take (their stability sweeps)."""
    from shaftfe.model.validate import validate_variant
    stiff = _brg(load_variant("x2_57"), 0, K_N_per_mm=((1e12, 0.0), (0.0, 1e12)))
    with pytest.raises(InputError, match="plausible"):
        validate_variant(stiff)
    validate_variant(stiff, typed=False)
    with pytest.raises(InputError, match="positive definite"):     # a rule, typed or not
        validate_variant(_brg(stiff, 0, K_N_per_mm=((1.0, 2.0), (2.0, 1.0))), typed=False)
    # a model made for a solver may leave the axial bearing to it (the first coupling, or its
    # SolverError); a typed design states exactly one
    x2 = load_variant("x2_57")
    free = dataclasses.replace(x2, bearings=tuple(dataclasses.replace(b, axial=False)
                                                  for b in x2.bearings))
    validate_variant(free, typed=False)
    with pytest.raises(InputError, match="exactly one bearing with axial"):
        validate_variant(free)


def test_a_typed_design_states_each_bearing_s_bore_and_a_slip_is_named_before_the_standards():
    """A bearing record's bore of 0 is refused where it is typed (a Variant made for a solver
    may leave it out); a segment's diameter in metres is named as such, not as the DIN 471
    groove its size would be looked up for."""
    with pytest.raises(InputError, match=r"bore_mm.*plausible"):
        load_variant("x2_57", {"bearing_types.zkl_3203.bore_mm": 0.0})


def test_a_unit_slip_under_a_din_groove_is_named_as_a_unit_slip(tmp_path):
    from shaftfe.model.fields import ImplausibleValue
    geo = _copy_geometry(tmp_path)
    shaft = geo / "common" / "shaft_c.toml"
    _edit(shaft, 'spot (§8.3)."""\n', 'spot (§8.3)."""\n[[shaft.segments.grooves]]\n'
          'kind = "din471"\nx_center_mm = 55.0\nreconstructed = ["x_center_mm"]\n')
    load_variant(geo / "x2_57.toml")                      # the groove as written is valid
    _edit(shaft, "length_mm = 17.5\ndiameter_mm = 22.0", "length_mm = 17.5\ndiameter_mm = 0.022")
    with pytest.raises(ImplausibleValue) as e:
        load_variant(geo / "x2_57.toml")
    assert e.value.field == "segments[4].diameter_mm" and "metres" in str(e.value)
