"""The files of a static run: ``result.vtu`` (displacement, stresses, von Mises and the face
groups at the first speed), ``deflection.png`` and ``summary.json`` (every case, the inputs and
the package versions). Each file is written atomically into ``out`` (the command stages the
whole directory)."""

from __future__ import annotations

import json
from dataclasses import asdict


def clearance_of(variant) -> tuple[float, float] | None:
    """(station x, clearance) in mm from the variant's shaft file, or None without both."""
    x, c = (getattr(variant, k, None) for k in ("clearance_station_x_mm", "clearance_mm"))
    return (float(x), float(c)) if x is not None and c is not None else None


def write_outputs(variant_arg: str, variant, opts, res, rpms: list[float], out) -> dict:
    """result.vtu, deflection.png and summary.json into the directory ``out``; the summary.
    ``variant_arg``: the variant as the user named it (a name or a path)."""
    from shaftfe.io import vtu as export
    from shaftfe.util.atomic import write_atomic
    from shaftfe.util.notices import collected
    from shaftfe.util.versions import package_versions
    rpm_vtu = rpms[0]
    vtu, regions = export.write_vtu(res, out / "result.vtu", rpm_vtu)
    export.plot_png(res, out / "deflection.png", rpm_vtu, clearance=clearance_of(variant))
    summary = {
        "inputs": {"variant": variant_arg, "rpm": rpms, "options": asdict(opts),
                   "source_files": list(getattr(variant, "source_files", ())),
                   "overrides": variant.overrides_map},
        "versions": package_versions("pypardiso"),
        "vtu": {"file": vtu.name, "rpm": rpm_vtu, "regions": regions,
                "stress_components": ["xx", "yy", "zz", "xy", "yz", "xz"],
                "note": ("fields at vtu.rpm; scale by (rpm / vtu.rpm)^2 for another speed"
                         if all(p["scales_with"] == "rpm2" for p in res.patterns) else
                         "fields of the case at vtu.rpm (loads not all ∝ rpm²: superpose "
                         "the patterns with their factors for another case)")},
        **res.to_dict(),
        "warnings": collected(),
    }
    text = json.dumps(summary, indent=2, allow_nan=False)
    write_atomic(out / "summary.json", text + "\n")
    return summary
