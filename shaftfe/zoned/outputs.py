"""Files of a zoned run (``shaftfe static``, the default model): ``summary.json``,
``result.vtu`` (the global axisymmetric solution's outline revolved to 3D: the surface, with
the surface-recovered stress its peaks come from) and one ``zone_<k>.vtu`` per 3D submodel (its
P2 tets with ``displacement``, ``von_mises``, ``max_principal`` and ``stress``, cell data
``region``), all at the first speed;
each written atomically into ``out`` (the command stages the whole directory)."""

from __future__ import annotations

from dataclasses import asdict

from shaftfe.axisymmetric.outputs import SECTORS, write_surface_vtu
from shaftfe.fe import recovery
from shaftfe.io.vtu import write_fields_vtu
from shaftfe.static.outputs import write_summary


def zone_file(k: int) -> str:
    return f"zone_{k + 1}.vtu"


def write_outputs(variant_arg: str, variant, opts, res, rpms, out) -> dict:
    rpm_vtu = rpms[0]
    scale = res.case(rpm_vtu).scale
    path = write_surface_vtu(res.global_result.solution, scale, out / "result.vtu")
    zones = []
    for k, (sub, sf) in enumerate(res.fields):
        stress = sf.stress * scale
        _, regions = write_fields_vtu(sub.shaft_mesh.mesh, out / zone_file(k), {
            "displacement": sf.u.reshape(-1, 3) * scale,
            "von_mises": recovery.von_mises(stress),
            "max_principal": recovery.principal(stress)[0],
            "stress": stress.T.copy()})
        zones.append({"zone": sub.zone.name, "file": zone_file(k), "regions": regions})
    return write_summary(out, variant_arg, variant, rpms,
                         {**asdict(opts), "level": getattr(opts.level, "name", opts.level)}, {
                             "file": path.name, "rpm": rpm_vtu, "sectors": SECTORS,
                             "zones": zones,
                             "note": "result.vtu: the global axisymmetric solution's outline "
                             "revolved to 3D (quads; the surface-recovered von Mises of its "
                             "peaks); zone_<k>.vtu: each 3D submodel's field; all at vtu.rpm"},
                         res.to_dict(), model="zoned", versions=("pypardiso",))
