"""Where each part of a ``Variant`` was written: the file, and the name the value has there.

The rules of a variant (``model.validate.validate_variant``, the solid's ``solid.plan.prepare``)
take a ``Variant`` however it was made, so they name a field as the Variant holds it
(``segments[4].grooves[0].depth_mm``, ``bearings[1].chamfer_mm``, ``attachments[3].mass_kg``,
``material.E_MPa``) and its source as ``model.validate.source_of`` (the variant's first file, or
``variant <name>`` for one made in Python). The loader, which alone knows which file defined
what, records it here while it parses (``Origins.add``) and re-words such an error to the file
and the name the value was written under (``Origins.locate``): a groove of
``common/shaft_c.toml`` is named in that file, a bearing's chamfer in its type's table
(``bearing_types.<type>``) of ``common/bearings.toml``, a part's mass under ``parts.<name>``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from shaftfe.errors import InputError

# a field's head (``segments[4]``, ``hex_socket``, ``material``) and the rest (``.grooves[0].
# depth_mm (bearing 'x')``)
_HEAD = re.compile(r"([A-Za-z_]+(?:\[\d+\])?)(.*)", re.DOTALL)
_KEY = re.compile(r"\.([A-Za-z0-9_]+)")


@dataclass
class Origins:
    """What the loader records of one variant: for each head of a field as the Variant names
    it, the file and the head in that file; for some heads (a bearing: its position is in the
    shaft's file, its data in its type's record) a second place for a set of keys."""
    source: str                       # the source the rules name (``validate.source_of``)
    heads: dict[str, tuple[str, str]] = field(default_factory=dict)
    keyed: dict[str, tuple[frozenset[str], str, str]] = field(default_factory=dict)

    def add(self, head: str, file: str, shown: str) -> None:
        """Fields under ``head`` are in ``file``, under ``shown``; a head without an index
        (``segments``) also stands for each of its entries (``segments[4]``), the index kept
        (where the file lists them in the same order)."""
        self.heads[head] = (file, shown)

    def add_keys(self, head: str, keys, file: str, shown: str) -> None:
        """Fields ``head.<key>`` for a ``key`` in ``keys`` are in ``file`` under ``shown``."""
        self.keyed[head] = (frozenset(keys), file, shown)

    def locate(self, exc: InputError) -> InputError:
        """``exc`` re-worded to the file and name of its field, where it names the variant's
        generic source and a field recorded here; else ``exc`` as it is."""
        if exc.source != self.source:
            return exc
        m = _HEAD.fullmatch(str(exc.field))
        if m is None:
            return exc
        head, rest = m.groups()
        key = _KEY.match(rest)
        place = None
        if head in self.keyed and key is not None and key.group(1) in self.keyed[head][0]:
            place = self.keyed[head][1:]
        elif head in self.heads:
            place = self.heads[head]
        elif "[" in head and head.split("[")[0] in self.heads:     # an index kept as it is
            base = head.split("[")[0]
            file, shown = self.heads[base]
            place = (file, shown + head[len(base):])
        if place is None:
            return exc
        return type(exc)(place[0], place[1] + rest, exc.allowed, got=exc.got,
                         reason=exc.reason)


__all__ = ["Origins"]
