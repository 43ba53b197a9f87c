"""One entry to the rotor models: ``analyse(variant, rpms, options)``.

The beam rotor (``beam_rotor``: Timoshenko beam + rigid disks), the 3D solid rotor
(``solid_rotor``: P2 tets + rigid attachment bodies) and the harmonic rotor
(``harmonic_rotor``: the round shaft's n = 0, 1 fields on the meridian mesh + the same bodies)
answer the same small protocol, ``RotorKind``: build the model, sweep the speeds, verify the
reduced sweep against the full-size quadratic eigenproblem, and split a mode's strain energy
between shaft and bearings. The Campbell command, the modal command and the report all go
through ``analyse``; none of them knows which model it holds.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol

from shaftfe.errors import InputError
from shaftfe.rotordynamics.options import (
    DEFAULT_ORDERS,
    ROTOR_MODELS,
    RotorOptions,
    check_modes,
    check_options,
)

if TYPE_CHECKING:
    import numpy as np


@dataclass(frozen=True, eq=False)
class RotorAnalysis:
    """A sweep with the model it ran on (the model is not changed by the sweep)."""
    model: object
    result: object                        # rotordynamics.campbell.CampbellResult
    verification: object | None           # beam_rotor.Verification, or None if not asked
    provider: object | None               # the solid rotor's basis (its factorisation), reused
    kind: RotorKind

    def support_energy_share(self, speed_index: int = 0) -> np.ndarray:
        """Share of each mode's strain energy in the bearing springs at one speed."""
        return self.kind.support_energy_share(self.model, self.result.vectors[speed_index])


class RotorKind(Protocol):
    def build(self, variant, o: RotorOptions): ...
    def sweep(self, model, rpms, n_modes: int, orders, keep_vectors: bool): ...
    def verify(self, model, res, provider): ...
    def support_energy_share(self, model, vecs: np.ndarray) -> np.ndarray: ...


class _Beam:
    def build(self, variant, o: RotorOptions):
        from shaftfe.rotordynamics import beam_rotor
        return beam_rotor.rotor_from_variant(
            variant, max_element_mm=o.max_element_mm, rigid_supports=o.rigid_supports,
            bearing_damping=o.bearing_damping if o.bearing_damping > 0 else None)

    def sweep(self, model, rpms, n_modes, orders, keep_vectors):
        from shaftfe.rotordynamics import beam_rotor
        return beam_rotor.campbell(model, rpms, n_modes, orders=orders,
                                   keep_vectors=keep_vectors), None

    def verify(self, model, res, provider):
        from shaftfe.rotordynamics import beam_rotor
        return beam_rotor.verify(model, res)

    def support_energy_share(self, model, vecs):
        from shaftfe.rotordynamics import beam_rotor
        return beam_rotor.support_energy_share(model, vecs)


class _Solid:
    def build(self, variant, o: RotorOptions):
        from shaftfe.rotordynamics import solid_rotor
        opts = solid_rotor.SolidOptions(level=o.level, coupling=o.coupling,
                                        rigid_supports=o.rigid_supports,
                                        bearing_damping=o.bearing_damping,
                                        stress_stiffening=o.stress_stiffening)
        return solid_rotor.build_solid_rotor(variant, opts, cache_dir=o.cache_dir)

    def sweep(self, model, rpms, n_modes, orders, keep_vectors):
        from shaftfe.rotordynamics import solid_modal
        prov = solid_modal.BasisProvider(model)
        return solid_modal.campbell(model, rpms, n_modes, orders=orders,
                                    keep_vectors=keep_vectors, provider=prov), prov

    def verify(self, model, res, provider):
        from shaftfe.rotordynamics import solid_modal
        return solid_modal.verify(model, res, provider=provider)

    def support_energy_share(self, model, vecs):
        from shaftfe.rotordynamics import solid_modal
        return solid_modal.support_energy_share(model, vecs)


class _Harmonic(_Beam):
    """The harmonic rotor: its own model and sweep; its check against the full eigenproblem
    and its bearings' energy share are the beam rotor's (the same K, M, G, K_support
    attributes, the same rule)."""

    def build(self, variant, o: RotorOptions):
        from shaftfe.rotordynamics import harmonic_rotor
        opts = harmonic_rotor.HarmonicOptions(level=o.level, coupling=o.coupling,
                                              rigid_supports=o.rigid_supports,
                                              bearing_damping=o.bearing_damping)
        return harmonic_rotor.build_harmonic_rotor(variant, opts, cache_dir=o.cache_dir)

    def sweep(self, model, rpms, n_modes, orders, keep_vectors):
        from shaftfe.rotordynamics import harmonic_rotor
        return harmonic_rotor.campbell(model, rpms, n_modes, orders=orders,
                                       keep_vectors=keep_vectors), None


KINDS: dict[str, RotorKind] = {"beam": _Beam(), "solid": _Solid(), "harmonic": _Harmonic()}
assert tuple(KINDS) == ROTOR_MODELS


def rotor_kind(model: str, option: str = "--model") -> RotorKind:
    if model not in KINDS:
        raise InputError(option, "model", " | ".join(ROTOR_MODELS), got=model)
    return KINDS[model]


def build_rotor(variant, options: RotorOptions = RotorOptions()):
    """The rotor model of ``variant`` (beam or solid, as ``options.model`` says)."""
    return rotor_kind(options.model).build(variant, options)


def analyse(variant, rpms, n_modes: int = 12, *, orders=DEFAULT_ORDERS,
            options: RotorOptions = RotorOptions(), keep_vectors: bool = False,
            verify: bool = True, model=None) -> RotorAnalysis:
    """Build (or take ``model``), sweep ``rpms``, and verify the reduced sweep at the top speed.
    InputError if ``n_modes`` exceeds half the model's dofs."""
    check_options(options)
    check_modes(n_modes)
    kind = rotor_kind(options.model)
    if model is None:
        model = kind.build(variant, options)
    n_max = model.n_dof // 2
    if n_modes > n_max:
        raise InputError("command line", "--modes", f"1..{n_max} for this model", got=n_modes)
    res, prov = kind.sweep(model, rpms, n_modes, orders, keep_vectors)
    ver = kind.verify(model, res, prov) if verify else None
    return RotorAnalysis(model, res, ver, prov, kind)


def analyse_with_beam(variant, rpms, n_modes: int = 12, *, orders=DEFAULT_ORDERS,
                      options: RotorOptions = RotorOptions(), keep_vectors: bool = False,
                      verify: bool = True):
    """``analyse``, and for the solid model the beam model's sweep of the same speeds beside
    it (its ``CampbellResult``; None for the other models): what ``shaftfe campbell`` and
    ``shaftfe modal`` report. The beam has no centrifugal prestress: beside a solid sweep with
    ``stress_stiffening`` it is the unstiffened beam (it was refused there, after the solid
    sweep)."""
    from dataclasses import replace
    run = analyse(variant, rpms, n_modes, orders=orders, options=options,
                  keep_vectors=keep_vectors, verify=verify)
    beam = None
    if options.model == "solid":
        beam = analyse(variant, rpms, n_modes, orders=orders,
                       options=replace(options, model="beam", stress_stiffening=False),
                       verify=False).result
    return run, beam


def summary(label: str, variant, options: RotorOptions, run: RotorAnalysis,
            beam_res=None) -> dict:
    """The JSON of a rotor run (``campbell.json``, ``modal.json``, ``--json``): the variant as
    named (``label``) with its overrides, the model and its supports, the sweep, and for the
    solid model its mesh, the beam's sweep and the two side by side; the verification where
    it ran."""
    model, res, ver = run.model, run.result, run.verification
    d = {"variant": label, "overrides": variant.overrides_map, "model": options.model,
         "n_dof": model.n_dof,
         "supports": "rigid" if options.rigid_supports else "springs",
         "bearing_damping_Ns_per_mm": options.bearing_damping,
         "stress_stiffening": bool(options.stress_stiffening), "result": res.to_dict()}
    if options.model == "solid":
        sm = model.shaft_mesh
        d["solid"] = {"level": sm.level, "order": sm.order, "nodes": sm.n_nodes,
                      "elements": sm.n_elements, "coupling": options.coupling,
                      "attachment_bodies": [b.name for b in model.bodies]}
    if beam_res is not None:
        d["beam"] = beam_res.to_dict()
        d["side_by_side"] = side_by_side(res, beam_res)
        if options.stress_stiffening:          # the beam has no prestress (analyse_with_beam)
            d["beam_stress_stiffening"] = False
    if ver is not None:
        d["verify"] = {"rpm": ver.rpm, "freq_reduced_hz": list(ver.freq_reduced_hz),
                       "freq_full_hz": list(ver.freq_full_hz),
                       "max_rel_diff": ver.max_rel_diff, "n_missed": ver.n_missed}
    return d


def side_by_side(res, beam_res) -> list[dict]:
    """Per 3D mode, at the first and the last speed: the beam mode of the same family
    (lateral / torsional / axial) and the same rank within it (None if the beam's first
    modes hold no such mode), with frequencies and whirl labels."""
    out = []
    for i in sorted({0, len(res.rpm) - 1}):
        fam_b = list(beam_res.family[i])
        for j in range(res.freq_hz.shape[1]):
            fam = res.family[i][j]
            rank = list(res.family[i][:j]).count(fam)
            hits = [k for k, f in enumerate(fam_b) if f == fam]
            k = hits[rank] if rank < len(hits) else None
            fs = float(res.freq_hz[i, j])
            fb = float(beam_res.freq_hz[i, k]) if k is not None else None
            out.append({"rpm": float(res.rpm[i]), "mode": j + 1, "family": fam,
                        "solid_hz": fs, "solid_whirl": res.whirl[i][j],
                        "beam_mode": None if k is None else k + 1, "beam_hz": fb,
                        "beam_whirl": None if k is None else beam_res.whirl[i][k],
                        "solid_over_beam": None if fb is None else fs / fb})
    return out


def write_rest_modes(run: RotorAnalysis, n_modes: int, path) -> bool:
    """The solid model's mode shapes at rest as a VTU (on the sweep's own factorisation);
    False for the beam model, whose shapes live on the beam's nodes."""
    if run.provider is None:
        return False
    from shaftfe.rotordynamics.modes_vtu import write_modes_vtu
    from shaftfe.rotordynamics.solid_modal import modal
    rest = modal(run.model, 0.0, n_modes, keep_vectors=True, provider=run.provider)
    write_modes_vtu(run.model, rest, path)
    return True
