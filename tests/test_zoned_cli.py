"""`shaftfe static` runs the zoned solve by default (issue #32): its files, its summary and the
--model choices beside it."""

from __future__ import annotations

import json

import pytest


@pytest.fixture(scope="module")
def zoned_run(tmp_path_factory, cache):
    import os

    from shaftfe.cli import main
    out = tmp_path_factory.mktemp("zoned") / "o"
    old = os.environ.get("SHAFTFE_CACHE_DIR")
    os.environ["SHAFTFE_CACHE_DIR"] = str(cache)
    try:
        rc = main(["static", "--variant", "x2_57", "--level", "coarse", "--json",
                   "--out", str(out)])
    finally:
        if old is None:
            os.environ.pop("SHAFTFE_CACHE_DIR")
        else:
            os.environ["SHAFTFE_CACHE_DIR"] = old
    return rc, out


def test_the_default_static_model_is_zoned_and_writes_every_file(zoned_run):
    import meshio
    rc, out = zoned_run
    assert rc == 0
    assert {p.name for p in out.iterdir()} == {"result.vtu", "zone_1.vtu", "zone_2.vtu",
                                               "summary.json"}
    s = json.loads((out / "summary.json").read_text())
    assert s["model"] == "zoned" and s["inputs"]["model"] == "zoned"
    assert [z["features"] for z in s["zones"]] == [["keyway:gear_seat:0"],
                                                   ["keyway:cw2_seat:0", "hex_socket"]]
    assert [z["file"] for z in s["vtu"]["zones"]] == ["zone_1.vtu", "zone_2.vtu"]
    models = {p["region"]: p["model"] for p in s["cases"][0]["peaks"]}
    assert models["keyway:gear_seat:0"] == "zone:keyway:gear_seat:0"
    assert models["fillet:collar"] == "axisymmetric"      # the span fillets: the global model
    z = meshio.read(out / "zone_1.vtu")
    assert z.point_data["stress"].shape == (z.points.shape[0], 6)
    g = meshio.read(out / "result.vtu")
    assert set(g.point_data) == {"displacement_mm", "von_mises_MPa"}
