"""A TOML writer for the subset the variant files use (``shaftfe variant new``).

Tables, arrays of tables, strings (notes with line breaks as multi-line strings), numbers,
booleans and (nested) lists of them. ``tomllib.loads(dumps(d)) == d`` for every dictionary of
that subset (tests/test_variant.py checks it on every shipped variant).
"""

from __future__ import annotations

import math
import re

_BARE = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(k: str) -> str:
    return k if _BARE.match(k) else _basic(k)


_ESCAPES = {"\\": "\\\\", '"': '\\"', "\b": "\\b", "\t": "\\t", "\n": "\\n", "\f": "\\f",
            "\r": "\\r"}


def _basic(s: str) -> str:
    """A one-line basic string: every control character escaped (TOML 1.0 §String)."""
    out = []
    for ch in s:
        if ch in _ESCAPES:
            out.append(_ESCAPES[ch])
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04X}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def _string(s: str) -> str:
    """Notes with line breaks as multi-line strings (readable in an editor), when they hold no
    other control character than a tab; anything else as a one-line escaped string."""
    plain = all(ch in "\n\t" or (ord(ch) >= 0x20 and ord(ch) != 0x7F) for ch in s)
    if "\n" in s and plain:
        body = s.replace("\\", "\\\\").replace('"""', '\\"\\"\\"')
        if body.endswith('"'):
            body = body[:-1] + '\\"'                # a quote right before the closing """
        return '"""\n' + body + '"""'
    return _basic(s)


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError(f"TOML variant files hold finite numbers only, not {v!r}")
        return repr(v)
    if isinstance(v, str):
        return _string(v)
    if isinstance(v, list):
        return "[" + ", ".join(_value(e) for e in v) + "]"
    raise TypeError(f"cannot write {type(v).__name__} to a variant file")


def _is_table_array(v) -> bool:
    return isinstance(v, list) and bool(v) and all(isinstance(e, dict) for e in v)


def _body(d: dict, path: tuple[str, ...], out: list[str]) -> None:
    for k, v in d.items():
        if not isinstance(v, dict) and not _is_table_array(v):
            out.append(f"{_key(k)} = {_value(v)}")
    for k, v in d.items():
        if isinstance(v, dict):
            p = (*path, k)
            out += ["", "[" + ".".join(_key(x) for x in p) + "]"]
            _body(v, p, out)
    for k, v in d.items():
        if _is_table_array(v):
            p = (*path, k)
            for e in v:
                out += ["", "[[" + ".".join(_key(x) for x in p) + "]]"]
                _body(e, p, out)


def dumps(d: dict, header: str = "") -> str:
    """The TOML text of ``d`` (a ``header`` of comment lines first)."""
    out = [f"# {line}".rstrip() for line in header.splitlines()]
    if out:
        out.append("")
    _body(d, (), out)
    return "\n".join(out).lstrip("\n") + "\n"
