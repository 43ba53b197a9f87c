"""``load_variant``: a variant file and a run's overrides → ``Variant``, the one entry every
command, study and test loads a variant through.

The overrides (``--set``, a study's design) first get what follows from them
(``shaftfe.model.derive.with_shape_derived``: a part's mass and inertias from its shape, the
[balance] statement from the parts), then the file is parsed and checked
(``shaftfe.model.parse.parse_variant``). Parsing lives apart so that the derivation, which
builds the design's parts to compute that statement, uses it without a circle of imports.
"""

from __future__ import annotations

from pathlib import Path

from shaftfe.model import overrides as ov
from shaftfe.model.derive import with_shape_derived
from shaftfe.model.parse import parse_variant
from shaftfe.model.variant import Variant


def load_variant(name_or_path: str | Path, overrides=()) -> Variant:
    """Read, resolve the includes of, check and return a variant.

    ``name_or_path`` is a variant name (``geometry/<name>.toml``) or a path to a TOML file.
    ``overrides``: keys changed for this run by their dotted paths (``shaftfe.model.overrides``),
    a mapping {path: value} or ``--set`` strings "PATH=VALUE"; recorded in
    ``Variant.overrides``. Anything impossible raises ``InputError(file, field, allowed, got)``
    (naming the ``--set`` when an overridden value is out of its range)."""
    return parse_variant(name_or_path, with_shape_derived(name_or_path, ov.normalise(overrides)))


__all__ = ["load_variant"]
