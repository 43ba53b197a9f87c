"""Visible warnings: a result that is computed but lies outside the model's range.

A plausible-looking wrong answer is worse than an error. Where a run can still give a number but
the physics is out of the model's range (a sharp corner, an overspeed allowed by an explicit
option, an error bar outside what was measured), the code that knows says so with ``warn``:

* on the command line the warning is printed at once on stderr as one line
  ``shaftfe: warning: <where>: <text>`` (``shaftfe.cli.main`` collects every command);
* the writers of ``summary.json`` put ``collected()`` under ``"warnings"``;
* the report shows them in a banner at the top of the page.

Outside a collection (a Python user calling the API) a warning goes through Python's
``warnings`` module as a ``ShaftfeWarning``, so it is shown once and can be filtered.
Each distinct warning (same code and place) is kept and printed once per collection.
"""

from __future__ import annotations

import sys
import warnings
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import asdict, dataclass

__all__ = ["Notice", "ShaftfeWarning", "collected", "collecting", "raised", "warn"]


class ShaftfeWarning(UserWarning):
    """A result outside the model's range (the API's form of a printed warning)."""


@dataclass(frozen=True)
class Notice:
    """One warning: a short stable ``code`` (e.g. ``"sharp-shoulder"``), the place it concerns
    (a feature such as ``"shoulder:collar"``, a file and field, an option) and one line of text
    saying what is out of range and what the number then means."""
    code: str
    where: str
    text: str

    def line(self) -> str:
        return f"{self.where}: {self.text}"

    def as_dict(self) -> dict:
        return asdict(self)


_ACTIVE: ContextVar[list[Notice] | None] = ContextVar("shaftfe_notices", default=None)
_ECHO: ContextVar[bool] = ContextVar("shaftfe_notices_echo", default=True)


def warn(code: str, where: str, text: str) -> Notice:
    """Record (and, on the command line, print) one warning; returns it."""
    notice = Notice(str(code), str(where), " ".join(str(text).split()))
    active = _ACTIVE.get()
    if active is None:
        warnings.warn(notice.line(), ShaftfeWarning, stacklevel=2)
        return notice
    if notice not in active:
        active.append(notice)
        if _ECHO.get():
            print(f"shaftfe: warning: {notice.line()}", file=sys.stderr)
    return notice


def collected() -> list[dict]:
    """The warnings of the current collection, in the order they were raised, as dicts
    (``code``, ``where``, ``text``) for summary.json and the report; [] outside a collection."""
    active = _ACTIVE.get()
    return [n.as_dict() for n in active] if active else []


@contextmanager
def collecting(echo: bool = True):
    """Collect the warnings raised inside the block (a command's run); ``echo`` prints each on
    stderr as it is raised. Yields the list the block's warnings go into."""
    box: list[Notice] = []
    token, token_echo = _ACTIVE.set(box), _ECHO.set(echo)
    try:
        yield box
    finally:
        _ACTIVE.reset(token)
        _ECHO.reset(token_echo)


@contextmanager
def raised():
    """Yield a list that holds, after the block, the warnings (dicts) raised inside it: inside
    a collection the ones new to it (collected and printed there as usual); outside one, the
    block's warnings, then passed on as ``ShaftfeWarning`` as ``warn`` does there."""
    box: list[dict] = []
    active = _ACTIVE.get()
    if active is None:
        with collecting(echo=False) as inner:
            yield box
        box.extend(n.as_dict() for n in inner)
        for n in inner:
            warnings.warn(n.line(), ShaftfeWarning, stacklevel=3)
        return
    n0 = len(active)
    yield box
    box.extend(n.as_dict() for n in active[n0:])
