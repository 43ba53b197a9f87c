"""What a report run returns: the frozen ``Report`` (every stage's summary, the seed comparison,
the error estimates, the figures) and its rows."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from shaftfe.report.options import ReportOptions
from shaftfe.util.fmt import json_clean


@dataclass(frozen=True)
class Comparison:
    """One seed figure next to ours."""
    group: str
    quantity: str
    unit: str
    seed: float | None
    ours: float | None
    model: str                # how ours was computed
    note: str = ""

    @property
    def diff_percent(self) -> float | None:
        if self.seed in (None, 0) or self.ours is None or not math.isfinite(self.ours):
            return None
        return 100.0 * (self.ours / self.seed - 1.0)


@dataclass(frozen=True)
class ErrorEstimate:
    quantity: str
    value: float | None
    unit: str
    error: str                # e.g. "−7.7 % (low)" or "≤ 1e-12"
    method: str


@dataclass(frozen=True)
class Figure:
    name: str                 # file stem in figures/
    title: str
    caption: str
    png: bytes = field(repr=False)


@dataclass(frozen=True)
class Report:
    options: ReportOptions
    created_utc: str
    inputs: dict
    provenance: dict
    balancing: dict
    beam: dict
    static: dict
    fatigue: dict
    campbell: dict
    comparisons: tuple[Comparison, ...]
    errors: tuple[ErrorEstimate, ...]
    timings: tuple[tuple[str, float], ...]
    sub_timings: dict
    figures: tuple[Figure, ...]
    files: dict
    notes: tuple[str, ...] = ()
    machine: dict = field(default_factory=dict)
    strength: dict = field(default_factory=dict)
    warnings: tuple[dict, ...] = ()       # shaftfe.util.notices.collected() of the run

    def figure(self, name: str) -> Figure | None:
        return next((f for f in self.figures if f.name == name), None)

    def to_dict(self) -> dict:
        from dataclasses import asdict
        return json_clean({
            "options": asdict(self.options), "created_utc": self.created_utc,
            "inputs": self.inputs, "provenance": self.provenance, "balancing": self.balancing,
            "beam": self.beam, "static": self.static, "fatigue": self.fatigue,
            "campbell": self.campbell, "strength": self.strength,
            "comparisons": [dict(asdict(c), diff_percent=c.diff_percent)
                            for c in self.comparisons],
            "error_estimates": [asdict(e) for e in self.errors],
            "timings_s": dict(self.timings), "sub_timings_s": self.sub_timings,
            "figures": [f"figures/{f.name}.png" for f in self.figures], "files": self.files,
            "notes": list(self.notes), "machine": self.machine,
            "warnings": [dict(w) for w in self.warnings]})


