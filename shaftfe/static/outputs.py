"""The files of a static run: ``result.vtu`` (displacement, stresses, von Mises and the face
groups at the first speed), ``deflection.png`` and ``summary.json`` (every case, the inputs and
the package versions). Each file is written atomically into ``out`` (the command stages the
whole directory)."""

from __future__ import annotations

import json
from dataclasses import asdict

from shaftfe.io import vtu as export
from shaftfe.util.atomic import write_atomic
from shaftfe.util.notices import collected
from shaftfe.util.versions import package_versions


def clearance_of(variant) -> tuple[float, float] | None:
    """(station x, clearance) in mm from the variant's shaft file, or None without both."""
    x, c = (getattr(variant, k, None) for k in ("clearance_station_x_mm", "clearance_mm"))
    return (float(x), float(c)) if x is not None and c is not None else None


def write_outputs(variant_arg: str, variant, opts, res, rpms: list[float], out) -> dict:
    """result.vtu, deflection.png and summary.json into the directory ``out``; the summary.
    ``variant_arg``: the variant as the user named it (a name or a path)."""
    rpm_vtu = rpms[0]
    vtu, regions = export.write_vtu(res, out / "result.vtu", rpm_vtu)
    export.plot_png(res, out / "deflection.png", rpm_vtu, clearance=clearance_of(variant))
    return write_summary(out, variant_arg, variant, rpms, asdict(opts), {
        "file": vtu.name, "rpm": rpm_vtu, "regions": regions,
        "stress_components": ["xx", "yy", "zz", "xy", "yz", "xz"],
        "note": ("fields at vtu.rpm; scale by (rpm / vtu.rpm)^2 for another speed"
                 if all(p["scales_with"] == "rpm2" for p in res.patterns) else
                 "fields of the case at vtu.rpm (loads not all ∝ rpm²: superpose "
                 "the patterns with their factors for another case)")},
        res.to_dict(), versions=("pypardiso",))


def write_summary(out, variant_arg: str, variant, rpms, options: dict, vtu: dict, body: dict,
                  *, model: str | None = None, versions: tuple[str, ...] = ()) -> dict:
    """``summary.json`` of a static run (every model): the inputs (the variant as the user
    named it, the speeds, ``model`` when given, the options, the source files, the --set
    values), the package versions, the files' ``vtu`` entry, the result's ``body`` and the
    warnings; written atomically into ``out``. Returns the summary."""
    inputs = {"variant": variant_arg, "rpm": rpms, **({"model": model} if model else {}),
              "options": options, "source_files": list(getattr(variant, "source_files", ())),
              "overrides": variant.overrides_map}
    summary = {"inputs": inputs, "versions": package_versions(*versions), "vtu": vtu, **body,
               "warnings": collected()}
    write_atomic(out / "summary.json", json.dumps(summary, indent=2, allow_nan=False) + "\n")
    return summary
