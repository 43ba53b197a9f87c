"""One entry to both rotor models: ``analyse(variant, rpms, options)``.

The beam rotor (``beam_rotor``: Timoshenko beam + rigid disks) and the 3D solid rotor
(``solid_rotor``: P2 tets + rigid attachment bodies) answer the same small protocol,
``RotorKind``: build the model, sweep the speeds, verify the reduced sweep against the full-size
quadratic eigenproblem, and split a mode's strain energy between shaft and bearings. The
Campbell command, the modal command and the report all go through ``analyse``; none of them
knows which model it holds.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from shaftfe.errors import InputError

ROTOR_MODELS = ("beam", "solid")


@dataclass(frozen=True)
class RotorOptions:
    model: str = "beam"                   # "beam" | "solid"
    rigid_supports: bool = False
    bearing_damping: float = 0.0          # N·s/mm, isotropic, on every bearing (0: undamped)
    max_element_mm: float = 5.0           # beam elements
    level: object = "coarse"              # solid: mesh level (name or MeshLevel)
    coupling: str = "rigid"               # solid: attachments "rigid" | "distributing"
    stress_stiffening: bool = False       # solid: centrifugal prestress
    cache_dir: object = None


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


KINDS: dict[str, RotorKind] = {"beam": _Beam(), "solid": _Solid()}


def rotor_kind(model: str, option: str = "--model") -> RotorKind:
    if model not in KINDS:
        raise InputError(option, "model", " | ".join(ROTOR_MODELS), got=model)
    return KINDS[model]


def build_rotor(variant, options: RotorOptions = RotorOptions()):
    """The rotor model of ``variant`` (beam or solid, as ``options.model`` says)."""
    return rotor_kind(options.model).build(variant, options)


def analyse(variant, rpms, n_modes: int = 12, *, orders=(1.0,),
            options: RotorOptions = RotorOptions(), keep_vectors: bool = False,
            verify: bool = True, model=None) -> RotorAnalysis:
    """Build (or take ``model``), sweep ``rpms``, and verify the reduced sweep at the top speed.
    InputError if ``n_modes`` exceeds half the model's dofs."""
    kind = rotor_kind(options.model)
    if model is None:
        model = kind.build(variant, options)
    n_max = model.n_dof // 2
    if n_modes > n_max:
        raise InputError("command line", "--modes", f"1..{n_max} for this model", got=n_modes)
    res, prov = kind.sweep(model, rpms, n_modes, orders, keep_vectors)
    ver = kind.verify(model, res, prov) if verify else None
    return RotorAnalysis(model, res, ver, prov, kind)
