"""The typed feature description (``shaftfe.solid.features``, issue #32): x2_57's features
against the numbers of its geometry files (read here with ``tomllib``, not through the loader),
and every face group of its solid named by the one naming scheme. Pure: no mesh, no solve
(the 3D mesh's groups are the plan's ``groups()``: tests/test_mesh.py checks that, and checks
the scheme on a meshed shaft with every kind of feature)."""

from __future__ import annotations

import itertools
import tomllib

import pytest

from shaftfe.model.loader import load_variant
from shaftfe.solid import features as F
from shaftfe.solid.plan import prepare
from shaftfe.util.paths import COMMON_DIR, GEOMETRY_DIR

# the positions are sums of lengths written with at most 3 decimals: exact to rounding
TOL = 1e-9


@pytest.fixture(scope="module")
def x2_57():
    sol = prepare(load_variant("x2_57"))
    return sol, F.features(sol)


def _expected():
    """x2_57's features from geometry/common/shaft_c.toml and geometry/x2_57.toml: region ->
    (kind, extent, zone, round)."""
    shaft = tomllib.loads((COMMON_DIR / "shaft_c.toml").read_text())["shaft"]
    top = tomllib.loads((GEOMETRY_DIR / "x2_57.toml").read_text())
    segs, x, out = shaft["segments"], 0.0, {}
    ends = []
    for s in segs:                       # the shaft starts at x = 0 (its left end face)
        ends.append((x, x + s["length_mm"]))
        x += s["length_mm"]
    for i, (s, nxt) in enumerate(itertools.pairwise(segs)):
        xe, d, d1 = ends[i][1], s["diameter_mm"], nxt["diameter_mm"]
        rho = s["fillet_mm"]
        if rho > 0:                       # the arc lies on the smaller segment's side
            ext = (xe - rho, xe) if d1 > d else (xe, xe + rho)
            out[f"fillet:{s['name']}"] = ("fillet", ext, ext, True)
        if d1 != d:
            out[f"shoulder:{s['name']}"] = ("shoulder", (xe, xe), (xe, xe), True)
    for s in segs:
        for j, k in enumerate(s.get("keyways", ())):
            xc, half = k["x_center_mm"], 0.5 * k["length_mm"]
            ext = (xc - half, xc + half)
            d = s["diameter_mm"]                    # zone: the extent ± one local diameter
            out[f"keyway:{s['name']}:{j}"] = ("keyway", ext, (ext[0] - d, ext[1] + d), False)
    h = shaft["hex_socket"]
    assert h["end"] == "right"
    ext, d = (x - h["depth_mm"], x), segs[-1]["diameter_mm"]
    out["hex_socket"] = ("hex_socket", ext, (ext[0] - d, ext[1] + d), False)
    out["end:left"] = ("end", (0.0, 0.0), (0.0, 0.0), True)
    out["end:right"] = ("end", (x, x), (x, x), True)
    seats = {f"seat:bearing:{b['name']}": "bearing_seat" for b in shaft["bearings"]}
    seats |= {f"seat:{p}": "seat" for p in top["use_parts"]}
    seats |= {f"seat:{a['name']}": "seat" for a in top["attachments"]}
    return out, seats


def test_x2_57_features_against_its_files(x2_57):
    _, feats = x2_57
    exp, seats = _expected()
    got = F.by_region(feats)
    assert len(got) == len(feats)                      # one feature per region
    assert set(got) == set(exp) | set(seats)
    for region, (kind, ext, zone, rnd) in exp.items():
        f = got[region]
        assert (f.kind, f.round) == (kind, rnd), region
        assert f.x_mm == pytest.approx(ext, abs=TOL), region
        assert f.zone_mm == pytest.approx(zone, abs=TOL), region
    for region, kind in seats.items():
        assert got[region].kind == kind
    assert {f.region for f in F.cuts(x2_57[0])} == {
        r for r, e in exp.items() if e[0] in ("keyway", "hex_socket")}
    assert {f.region for f in feats if f.notch} == {
        r for r, e in exp.items() if e[0] in ("fillet", "keyway")}


def test_every_group_of_the_solid_names_one_feature(x2_57):
    """Each face group of x2_57's solid (the 3D mesh's boundaries) reads back, through the one
    naming table, to the kind of exactly the feature whose region it belongs to; and every
    feature has faces."""
    sol, feats = x2_57
    by = F.by_region(feats)
    regions = set()
    for g in sol.groups():
        f = by[F.region_of(g)]
        assert F.kind_of(g) == f.kind, g
        assert F.kind_of(f.region) == f.kind, f.region
        regions.add(f.region)
    assert regions == set(by)
    assert F.kind_of("axis") is None and F.kind_of("band:1:2") is None
