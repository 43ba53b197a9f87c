"""Designs of a study: a full grid, an explicit list, or a Latin hypercube with a seed.

Each design is the base variant plus ``overrides`` ((path, value), ...); ``number`` is its
position in the study (0, 1, …, stable for a given study file).

* grid: the Cartesian product of every parameter's points, the first parameter varying
  slowest.
* list: the ``[[designs]]`` tables in file order.
* lhs (McKay, Beckman & Conover 1979): n samples; each parameter's range cut into n equal
  strata, one uniform point in each, the strata of each parameter in an independent random
  order (numpy's PCG64 seeded by ``seed``: the same designs on every machine).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any

import numpy as np

from shaftfe.study.spec import StudySpec


@dataclass(frozen=True)
class Design:
    number: int
    overrides: tuple[tuple[str, Any], ...]       # (path, value) as the study file sets them


def _expand(spec: StudySpec, point) -> tuple[tuple[str, Any], ...]:
    return tuple((path, v) for q, vals in zip(spec.parameters, point, strict=True)
                 for path, v in zip(q.paths, vals, strict=True))


def count(spec: StudySpec) -> int:
    """How many designs the study has (without making them)."""
    if spec.method == "list":
        return len(spec.designs)
    if spec.method == "lhs":
        return spec.samples
    n = 1
    for q in spec.parameters:
        n *= len(q.grid())
    return n


def lhs_unit(n: int, d: int, seed: int) -> np.ndarray:
    """(n, d) points in [0, 1): one per stratum of every coordinate."""
    rng = np.random.default_rng(seed)
    u = np.empty((n, d))
    for j in range(d):
        u[:, j] = (rng.permutation(n) + rng.random(n)) / n
    return u


def designs(spec: StudySpec) -> tuple[Design, ...]:
    if spec.method == "list":
        return tuple(Design(i, d) for i, d in enumerate(spec.designs))
    if spec.method == "lhs":
        u = lhs_unit(spec.samples, len(spec.parameters), spec.seed)
        pts = [tuple(q.point(float(u[i, j])) for j, q in enumerate(spec.parameters))
               for i in range(spec.samples)]
    else:
        pts = itertools.product(*(q.grid() for q in spec.parameters))
    return tuple(Design(i, _expand(spec, p)) for i, p in enumerate(pts))


def paths(spec: StudySpec) -> tuple[str, ...]:
    """Every key path the study sets, in order (the result table's input columns)."""
    if spec.method == "list":
        return tuple(dict.fromkeys(p for d in spec.designs for p, _ in d))
    return tuple(p for q in spec.parameters for p in q.paths)
