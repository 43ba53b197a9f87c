"""shaftfe — balancer-shaft design and assessment for low-cylinder-count engines.

The pipeline, one subpackage per stage (docs/ARCHITECTURE.md):

    model → balance → solid → fe → beam / static / fatigue / rotordynamics → io → report

The entry points below take frozen inputs and return frozen results; a notebook needs nothing
else (examples/ has two short scripts)::

    import shaftfe
    v = shaftfe.load_variant("x2_57")                       # model: a frozen Variant
    v2 = shaftfe.load_variant("x2_57", {"segments.collar.fillet_mm": 0.5})  # = --set
    res = shaftfe.solve_static(v, [7000, 10000], shaftfe.StaticOptions(level="coarse"))
    run = shaftfe.analyse_rotor(v, range(0, 8001, 100))    # Campbell (beam rotor)
    fat = shaftfe.run_fatigue(shaftfe.FatigueJob("loadspectra/rpm.dat"))   # zoned model
    fkm = shaftfe.get_fatigue_method("fkm")                # any method by name: one protocol
    a = fkm.assess(shaftfe.AssessmentInputs.one_channel(v, fat.history), fat.job)
    a.governing                                            # utilisation, safety, life (h, km)

Every name loads its module on first use: ``import shaftfe`` has no side effects and loads no
FE stack (numpy, scikit-fem, gmsh, pyvista stay unloaded until a name needs them).

Units inside the solvers: mm, N, MPa, t/mm³, s. Input files state their units in key names.
"""

from __future__ import annotations

import importlib

__version__ = "0.1.0"

# public name -> (module, name in that module)
_API = {
    # model: variants
    "Variant": ("shaftfe.model.variant", "Variant"),
    "Segment": ("shaftfe.model.variant", "Segment"),
    "Bearing": ("shaftfe.model.variant", "Bearing"),
    "Attachment": ("shaftfe.model.variant", "Attachment"),
    "Keyway": ("shaftfe.model.variant", "Keyway"),
    "Material": ("shaftfe.model.variant", "Material"),
    "load_variant": ("shaftfe.model.loader", "load_variant"),
    "list_variants": ("shaftfe.model.parse", "list_variants"),
    "validate_variant": ("shaftfe.model.validate", "validate_variant"),
    "mass_properties": ("shaftfe.model.mass", "mass_properties"),
    # balance
    "load_engine": ("shaftfe.balance.engines", "load_engine"),
    "shaking_forces": ("shaftfe.balance.single", "forces"),
    # solid: plan and mesh
    "MeshLevel": ("shaftfe.solid.levels", "MeshLevel"),
    "LEVELS": ("shaftfe.solid.levels", "LEVELS"),
    "build_mesh": ("shaftfe.solid.mesh", "build_mesh"),
    # beam
    "analyse_beam": ("shaftfe.beam.solve", "analyse"),
    # static
    "StaticOptions": ("shaftfe.static.model", "StaticOptions"),
    "solve_static": ("shaftfe.static.solve", "solve_static"),
    # axisymmetric (Fourier harmonics on the meridian plane)
    "AxiOptions": ("shaftfe.axisymmetric.model", "AxiOptions"),
    "solve_axisymmetric": ("shaftfe.axisymmetric.solve", "solve_axisymmetric"),
    "stepped_bar_kt": ("shaftfe.axisymmetric.kt", "converged"),
    # fatigue
    "FatigueJob": ("shaftfe.fatigue.run", "FatigueJob"),
    "run_fatigue": ("shaftfe.fatigue.run", "run_fatigue"),
    "write_fatigue_outputs": ("shaftfe.fatigue.outputs", "write_outputs"),
    # fatigue methods by name: seed, fkm, din743 (one protocol, one result type)
    "FATIGUE_METHODS": ("shaftfe.fatigue.methods", "METHODS"),
    "get_fatigue_method": ("shaftfe.fatigue.methods", "get_method"),
    "FatigueMethod": ("shaftfe.fatigue.methods", "FatigueMethod"),
    "FatigueAssessment": ("shaftfe.fatigue.methods", "FatigueAssessment"),
    "AssessmentInputs": ("shaftfe.fatigue.methods", "AssessmentInputs"),
    "LoadChannel": ("shaftfe.fatigue.methods", "LoadChannel"),
    # rotor dynamics
    "RotorOptions": ("shaftfe.rotordynamics.options", "RotorOptions"),
    "analyse_rotor": ("shaftfe.rotordynamics.analyse", "analyse"),
    # report
    "ReportOptions": ("shaftfe.report.options", "ReportOptions"),
    "run_report": ("shaftfe.report.assemble", "run_report"),
    "write_report": ("shaftfe.report", "write"),
}
__all__ = sorted(_API)


def __getattr__(name: str):
    if name in _API:
        module, attr = _API[name]
        return getattr(importlib.import_module(module), attr)
    raise AttributeError(f"module 'shaftfe' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted([*globals(), *_API])
