"""A small progress display of named stages on stderr (stdlib only, no dependencies).

    prog = Progress(["balancing", "static", "fatigue"], enabled=None)
    with prog.stage("static"):
        ...
    prog.timings            # (("balancing", 0.03), ("static", 9.1), ...) always recorded

On a terminal each stage shows one line, ``[2/3] static ...`` while it runs, rewritten to
``[2/3] static  9.1 s`` when it ends (``failed`` if it raised). ``enabled=None`` means: show it
only when the stream is a terminal; ``--json`` passes ``enabled=False``. The wall times are
recorded whether or not anything is shown, so a report can print them.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Iterator, Sequence
from contextlib import contextmanager


class Progress:
    def __init__(self, stages: Sequence[str] = (), *, stream=None,
                 enabled: bool | None = None) -> None:
        self.stream = stream if stream is not None else sys.stderr
        if enabled is None:
            isatty = getattr(self.stream, "isatty", None)
            enabled = bool(isatty and isatty())
        self.enabled = enabled
        self._names = list(stages)
        self._times: list[tuple[str, float]] = []
        self._t0 = time.perf_counter()

    @property
    def timings(self) -> tuple[tuple[str, float], ...]:
        return tuple(self._times)

    @property
    def elapsed(self) -> float:
        return time.perf_counter() - self._t0

    def _label(self, name: str) -> str:
        n = len(self._names)
        k = self._names.index(name) + 1 if name in self._names else len(self._times) + 1
        width = len(str(max(n, k)))
        return f"[{k:>{width}}/{max(n, k)}] {name}"

    def _write(self, text: str) -> None:
        try:
            self.stream.write(text)
            self.stream.flush()
        except (OSError, ValueError):        # closed or broken stream: stop showing
            self.enabled = False

    @contextmanager
    def stage(self, name: str) -> Iterator[None]:
        label = self._label(name)
        if self.enabled:
            self._write(f"\r\x1b[K{label} ...")
        t0 = time.perf_counter()
        ok = False
        try:
            yield
            ok = True
        finally:
            dt = time.perf_counter() - t0
            self._times.append((name, dt))
            if self.enabled:
                self._write(f"\r\x1b[K{label}  {dt:.1f} s{'' if ok else '  failed'}\n")

    def done(self, message: str) -> None:
        if self.enabled:
            self._write(f"{message} ({self.elapsed:.1f} s)\n")
