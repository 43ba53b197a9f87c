"""The S-N card file (``geometry/common/sn_curves.toml``) as it is written: its cards by name.

Read here, at the model's layer, so that a variant's ``[duty] sn_curve`` is checked when the
variant is read (``model.parse``); ``fatigue.sn`` turns a card into an S-N curve.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

from shaftfe.errors import InputError
from shaftfe.util.paths import SN_FILE


def read_cards(path: str | Path = SN_FILE) -> dict:
    """{card name: its table} of the S-N card file at ``path``."""
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise InputError(str(path), "file", "an existing S-N card file",
                         reason="does not exist") from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError(str(path), "TOML", "valid TOML", reason=f"does not parse ({exc})")\
            from None
    cards = data.get("sn_curves")
    if not isinstance(cards, dict) or not cards:
        raise InputError(str(path), "sn_curves", "a table [sn_curves.<name>]", reason="is missing")
    return cards


def card_names(path: str | Path = SN_FILE) -> list[str]:
    """The card names of the S-N card file, sorted."""
    return sorted(read_cards(path).keys())
