"""Errors that the CLI turns into one clear line and exit code 2."""

from __future__ import annotations


class ShaftfeError(Exception):
    """Base class for errors caused by the user's input, not by a bug."""


class InputError(ShaftfeError, ValueError):
    """Bad input: names the file (or option), the field and the allowed range.

    >>> str(InputError("geometry/x2_57.toml", "segments[2].length_mm", "> 0", got=-3))
    'geometry/x2_57.toml: segments[2].length_mm = -3 is invalid; allowed: > 0'
    """

    def __init__(self, source: str, field: str, allowed: str, got: object = None,
                 reason: str | None = None):
        self.source, self.field, self.allowed, self.got = source, field, allowed, got
        self.reason = reason
        what = f"{field} = {got!r}" if got is not None else field
        detail = reason if reason else "is invalid"
        super().__init__(f"{source}: {what} {detail}; allowed: {allowed}")


class SolverError(ShaftfeError, RuntimeError):
    """A model that cannot be solved as posed (singular system, missing support, ...)."""
