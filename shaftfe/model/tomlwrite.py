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
    return k if _BARE.match(k) else _string(k)


def _string(s: str) -> str:
    if "\n" in s:
        body = s.replace("\\", "\\\\").replace('"""', '\\"\\"\\"')
        return '"""\n' + body + '"""'
    out = s.replace("\\", "\\\\").replace('"', '\\"').replace("\t", "\\t").replace("\r", "\\r")
    return f'"{out}"'


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
