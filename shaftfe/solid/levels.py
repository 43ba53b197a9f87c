"""Mesh levels: the size settings of the mesher as one frozen value, ``MeshLevel``.

The named levels (``coarse``, ``default``, ``fine``) live here and nowhere else; a study or a
test that wants other settings makes its own ``MeshLevel`` and passes it to
``shaftfe.solid.mesh.build_mesh`` (or ``StaticOptions(level=...)``): nothing global changes.

Settings (ours): k_global × D is the size on a segment of diameter D; k_sharp × ρ_min the size at
keyway edges and sharp concave shoulders; grad the growth of the size per mm of distance from a
fillet / sharp edge. Fillets: k_fillet × ρ in the hot sectors (half-angle sector_deg, plateau
d_hot × ρ deep, growth grad_hot), k_ring × ρ on the rest of a span fillet's ring, k_fillet_end × ρ
on end fillets. A level without k_ring meshes every fillet ring at k_fillet × ρ (no hot-spot
field). Chosen from the run-time/error study in reports/benchmarks/static.md; ``fine`` has the
hot-spot settings of the reference family there (k_fillet 0.3 / 0.2 / 0.133, everything else
fixed) at k_fillet 0.2, and a finer far field (so that it also refines a shaft without fillets).
Keep k_ring and k_fillet_end ≤ 0.9: coarser fillet rings leave curved tets near minSICN 0
(repaired only to Q_CURVED), and one of them gave a spurious 699 MPa peak on the x2_57
bearing-seat-gear ring (true ~420 MPa there) with k_ring 1.2; end fillets at 1.5 ρ missed the
fillet's area by 0.7 % (tests/validation/test_mesh_geometry.py allows 0.5 %).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from types import MappingProxyType

from shaftfe.errors import InputError


@dataclass(frozen=True)
class MeshLevel:
    name: str
    k_global: float
    k_fillet: float
    k_sharp: float
    grad: float
    k_ring: float | None = None
    k_fillet_end: float | None = None
    grad_hot: float | None = None
    d_hot: float | None = None
    sector_deg: float | None = None
    k_plain: float | None = None

    def settings(self, has_fillets: bool = True) -> dict[str, float]:
        """The size settings that are set and apply (the mesh cache key hashes them):
        ``k_plain`` only on a shaft without fillets."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)
                if f.name != "name" and getattr(self, f.name) is not None
                and (f.name != "k_plain" or not has_fillets)}

    def global_size(self, has_fillets: bool) -> float:
        """k_global, or min(k_global, k_plain) on a shaft without fillets."""
        if has_fillets or self.k_plain is None:
            return self.k_global
        return min(self.k_global, self.k_plain)

    @property
    def hot_spot(self) -> bool:
        """A local hot-spot field on span fillets (k_ring set)."""
        return self.k_ring is not None

    def scaled(self, s: float, name: str) -> MeshLevel:
        """Every size (k_global, k_fillet, k_sharp, k_ring, k_fillet_end) × ``s``."""
        sizes = ("k_global", "k_fillet", "k_sharp", "k_ring", "k_fillet_end")
        return dataclasses.replace(self, name=name, **{
            k: getattr(self, k) * s for k in sizes if getattr(self, k) is not None})


_HOT = {"k_ring": 0.9, "k_fillet_end": 0.9}
# k_plain (× D) on shafts without fillets: there k_global is the only size, and at 0.6-0.7 D
# (1.5 elements across) Gmsh's element count is erratic: "default" gave FEWER tets than
# "coarse" on the Ø20 × 120 test cylinder (307 vs 432 P2 tets). With k_plain the far field
# refines in the levels' order; shafts with fillets (every variant file) are unaffected.
LEVELS = MappingProxyType({
    "coarse": MeshLevel("coarse", k_global=0.70, k_fillet=0.45, k_sharp=5.0, grad=1.3,
                        grad_hot=1.0, d_hot=0.25, sector_deg=10.0, k_plain=0.5, **_HOT),
    "default": MeshLevel("default", k_global=0.60, k_fillet=0.3, k_sharp=4.0, grad=1.0,
                         grad_hot=0.5, d_hot=0.4, sector_deg=10.0, k_plain=0.35, **_HOT),
    "fine": MeshLevel("fine", k_global=0.35, k_fillet=0.2, k_sharp=2.0, grad=1.0,
                      grad_hot=0.5, d_hot=0.4, sector_deg=20.0, k_plain=0.25, **_HOT),
})
LEVEL_NAMES: tuple[str, ...] = tuple(LEVELS)
DEFAULT_LEVEL = "default"
ALLOWED = " | ".join(LEVEL_NAMES)

# The second level of a two-level (Richardson) error estimate: the finer one, "fine" (or
# "default" when the first is "fine"); or, where the estimate must cost less than the run
# itself (the report's --estimate-error), the neighbour level, the coarser one where there is one.
ESTIMATE_PAIR = MappingProxyType({"coarse": "fine", "default": "fine", "fine": "default"})
ESTIMATE_PAIR_CHEAP = MappingProxyType({"coarse": "default", "default": "coarse",
                                        "fine": "default"})


def mesh_level(level: str | MeshLevel, option: str = "--level") -> MeshLevel:
    """The ``MeshLevel`` of a name (InputError naming ``option`` if unknown) or the value."""
    if isinstance(level, MeshLevel):
        return level
    if level not in LEVELS:
        raise InputError(option, "level", ALLOWED, got=level)
    return LEVELS[level]


def level_name(level: str | MeshLevel) -> str:
    return level.name if isinstance(level, MeshLevel) else level
