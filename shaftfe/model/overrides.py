"""``--set PATH=VALUE``: change one key of a variant for one run, by its dotted path.

Paths name what a person sees in the files, tables of lists by their ``name``:

* ``segments.<segment>.<key>``                 e.g. ``segments.collar.fillet_mm=1.0``
* ``segments.<segment>.keyways.<i>.<key>``     (i = 0, 1, … in file order)
* ``segments.<segment>.grooves.<i>.<key>``     (likewise; ``cross_holes.<i>``)
* ``bearings.<bearing>.<key>``                 the [[shaft.bearings]] entries
* ``attachments.<part>.<key>`` and ``attachments.<part>.shape.<key>`` (the variant's own parts)
* ``parts.<part>.<key>``, ``materials.<name>.<key>``, ``bearing_types.<type>.<key>``
  (the shared tables of the includes)
* ``shaft.<key>``, ``shaft.hex_socket.<key>``, ``balance.<key>``, ``use_parts``, ``description``

A path must name a key that the variant's files already define (so a typo is an error, not a new
key that nothing reads), and the value must be of the same kind (a number for a number, a
string for a string, a list for a list); the range is then checked by the loader exactly as if
the file said it. Provenance lists and notes are not settable. A wrong name lists the nearest
valid ones. VALUE is read as a TOML value (``1.0``, ``"14220"``, ``[1, 2]``), or as a bare
string when it is not one (``--set shaft.material=14220``).

Pure functions on the merged TOML dictionary (``shaftfe.model.parse``); the parser applies them
before it builds the ``Variant`` and records them in ``Variant.overrides``.
"""

from __future__ import annotations

import difflib
import math
import re
import tomllib
from dataclasses import dataclass
from typing import Any

from shaftfe.errors import InputError
from shaftfe.model.fields import PROV_KEYS, is_num

OPTION = "--set"
_BARE_WORD = re.compile(r"[A-Za-z0-9_.+-]+")
PROVENANCE_TAG = "set"     # Variant.provenance tag of an overridden value (was seed, …)
_LIST_ALIASES = {"segments": ("shaft", "segments"), "bearings": ("shaft", "bearings"),
                 "loads": ("loads",), "load_cases": ("load_cases",)}


@dataclass(frozen=True)
class Override:
    """One ``--set``: the path, the value as typed and the parsed value."""
    path: str
    text: str
    value: Any

    @property
    def shown(self) -> str:
        return f"{OPTION} {self.path}={self.text}"


def parse(item: str) -> Override:
    """``PATH=VALUE`` → ``Override`` (InputError naming --set if malformed)."""
    if "=" not in item:
        raise InputError(OPTION, item, "PATH=VALUE, e.g. segments.collar.fillet_mm=1.0",
                         reason="has no '='")
    path, text = (s.strip() for s in item.split("=", 1))
    if not path or not text or any(not p for p in path.split(".")):
        raise InputError(OPTION, item, "PATH=VALUE, e.g. segments.collar.fillet_mm=1.0",
                         reason="has an empty path or value")
    try:
        doc = tomllib.loads(f"v = {text}")
        if set(doc) != {"v"}:                # "0.5\njunk = 1": one value only
            raise tomllib.TOMLDecodeError("more than one value")
        value = doc["v"]
    except tomllib.TOMLDecodeError:
        if not _BARE_WORD.fullmatch(text):   # an unclosed quote, a stray '[' …
            raise InputError(OPTION, path, "one TOML value (1.0, \"text\", [1, 2]) or a "
                             "bare name of letters, digits, _ . + -", got=text) from None
        value = text                         # a bare word: a name (material, bearing type)
    if isinstance(value, float) and not math.isfinite(value):
        raise InputError(OPTION, path, "a finite number", got=text)
    return Override(path, text, value)


def parse_all(items) -> tuple[Override, ...]:
    """Every ``--set`` of a command line (``apply`` refuses one key set twice, however it is
    spelled)."""
    return tuple(parse(i) for i in (items or ()))


def normalise(overrides) -> tuple[Override, ...]:
    """A mapping {path: value} (the API), or ``--set`` strings / ``Override``s (the CLI)."""
    if not overrides:
        return ()
    if isinstance(overrides, dict):
        out = []
        for path, value in overrides.items():
            text = repr(value) if not isinstance(value, str) else value
            if isinstance(value, float) and not math.isfinite(value):
                raise InputError(OPTION, path, "a finite number", got=value)
            out.append(Override(str(path), text, value))
        return tuple(out)
    items = list(overrides)
    bad = [o for o in items if not isinstance(o, str | Override)]
    if bad:
        raise TypeError(f"overrides: a mapping or PATH=VALUE strings, not {bad[0]!r}")
    return parse_all([o for o in items if isinstance(o, str)]) + tuple(
        o for o in items if isinstance(o, Override))


def _nearest(word: str, names) -> str:
    names = sorted(str(n) for n in names)
    near = difflib.get_close_matches(word, names, n=4, cutoff=0.5)
    shown = near or names[:12]
    more = "" if near or len(names) <= 12 else f", … ({len(names)} in all)"
    return ("nearest: " if near else "one of: ") + ", ".join(shown) + more


def _kind(v: Any) -> str:
    if is_num(v):
        return "a number"
    if isinstance(v, bool):
        return "true | false"
    if isinstance(v, str):
        return "a string"
    if isinstance(v, list):
        return "a list"
    return type(v).__name__


def apply(merged: dict, overrides: tuple[Override, ...]) -> tuple[Override, ...]:
    """Set every override in ``merged`` (the variant's files merged, includes resolved), in
    place, and return them as applied: the path canonical (list entries by name, segments and
    bearings without ``shaft.``) and the value as stored (a number typed for a name becomes
    the name, an integer for a float the float). InputError naming ``--set`` and the path for
    a wrong path or kind of value, or one key set twice."""
    done: dict[str, Override] = {}
    for o in overrides:
        parent, key, canon = _locate(merged, o)
        old = parent[key]
        value = o.value
        if isinstance(old, str) and not isinstance(value, str | list | bool | dict):
            value = o.text                        # a name that reads as a number: "16220"
        same = (is_num(old) and is_num(value)) or type(old) is type(value)
        if not same:
            raise InputError(o.shown, o.path, _kind(old) + " (as in the variant file)",
                             got=value)
        if canon in done:
            raise InputError(o.shown, o.path, "each key set once",
                             reason=f"is also set by {done[canon].shown}")
        value = float(value) if is_num(value) and isinstance(old, float) else value
        parent[key] = value
        done[canon] = Override(canon, o.text, value)
    return tuple(done.values())


def locate(merged: dict, o: Override) -> tuple[dict, str, str]:
    """(the table holding the key ``o.path`` names, the key, the canonical path)."""
    return _locate(merged, o)


def _locate(merged: dict, o: Override) -> tuple[dict, str, str]:
    """(the table holding the key, the key, the canonical path)."""
    parts = o.path.split(".")
    if len(parts) > 1 and parts[0] == "shaft" and parts[1] in _LIST_ALIASES:
        parts = parts[1:]                         # shaft.segments.… = segments.…
    head = parts[0]
    if head in _LIST_ALIASES:
        node: Any = merged
        for k in _LIST_ALIASES[head]:
            node = node.get(k, {}) if isinstance(node, dict) else {}
        if not isinstance(node, list):
            node = []
    elif head in merged:
        node = merged[head]
    else:
        valid = sorted({*merged, *_LIST_ALIASES} - {"include"})
        raise InputError(o.shown, o.path, "a path into the variant; first name " +
                         _nearest(head, valid), got=head)
    if len(parts) == 1:
        if isinstance(node, (dict, list)) and not (isinstance(node, list) and node and all(
                not isinstance(e, dict) for e in node)):
            raise InputError(o.shown, o.path, "a path to one value (a table needs a key)")
        return merged, head, head
    done = [head]
    for i, p in enumerate(parts[1:], start=1):
        last = i == len(parts) - 1
        if isinstance(node, list) and node and all(isinstance(e, dict) for e in node):
            names = [e.get("name") for e in node]
            if p in names:
                node = node[names.index(p)]
            elif p.isdigit() and int(p) < len(node):
                node = node[int(p)]
                p = node.get("name") or p             # canonical: by name where there is one
            else:
                labels = [n for n in names if n] or [str(k) for k in range(len(node))]
                raise InputError(o.shown, o.path, f"an entry of {'.'.join(done)}: " +
                                 _nearest(p, labels), got=p)
            if last:
                raise InputError(o.shown, o.path, "a path to one value (a table needs a key)")
        elif isinstance(node, dict):
            keys = [k for k in node if k not in PROV_KEYS]
            if p not in keys:
                raise InputError(o.shown, o.path, f"a key of {'.'.join(done)}: " +
                                 _nearest(p, keys), got=p)
            if last:
                val = node[p]
                if isinstance(val, dict) or (isinstance(val, list) and val and all(
                        isinstance(e, dict) for e in val)):
                    raise InputError(o.shown, o.path,
                                     "a path to one value (a table needs a key)")
                return node, p, ".".join((*done, p))
            node = node[p]
        else:
            raise InputError(o.shown, o.path, f"{'.'.join(done)} is a value; nothing below it",
                             got=p)
        done.append(p)
    raise InputError(o.shown, o.path, "a path to one value")      # pragma: no cover


def provenance_path(path: str) -> str:
    """The key of ``Variant.provenance.source`` that a canonical --set path changes: a used
    part's keys are recorded as ``attachments.<part>.<key>``, keyways, grooves and cross
    holes as ``keyways[i]``, ``grooves[i]``, ``cross_holes[i]``, the hex socket's without
    ``shaft.``."""
    p = re.sub(r"^parts\.", "attachments.", path)
    p = re.sub(r"^shaft\.hex_socket\.", "hex_socket.", p)
    return re.sub(r"\.(keyways|grooves|cross_holes)\.(\d+)\.", r".\1[\2].", p)


def attribute(exc: InputError, overrides: tuple[Override, ...]) -> InputError:
    """The loader's error about a value that an override set, re-worded to name the ``--set``
    that set it (the loader names the file the key was defined in); other errors unchanged."""
    for o in overrides:
        key = o.path.rsplit(".", 1)[-1]
        if str(exc.field).endswith(key) and _equal(exc.got, o.value):
            return type(exc)(o.shown, o.path, exc.allowed, got=o.value,   # (its kind kept)
                             reason=getattr(exc, "reason", None))
    if not overrides:
        return exc
    sets = " ".join(o.shown for o in overrides)
    hint = ("; also --set the [balance] statement (balance.mass_kg, balance.X2_percent) to the "
            "changed balancer" if str(exc.field).startswith("balance.") else "")
    # a consequence of the --set values (another key's check, a cross-check): the file is fine
    # as written, so the error names the file WITH the --set values
    return type(exc)(f"{exc.source} with {sets}", exc.field, exc.allowed + hint, got=exc.got,
                     reason=getattr(exc, "reason", None))


def _equal(a: Any, b: Any) -> bool:
    if is_num(a) and is_num(b):
        return float(a) == float(b)
    return a == b
