"""A study's result table: one row per design, Parquet and CSV; the non-dominated designs, the
requirements and the sensitivities the report shows.

Columns: ``design`` (number), ``key`` (its cache key), ``status`` (ok | refused | failed), one
column per parameter path (the value set), then the analyses' columns
(``shaftfe.study.evaluate``), ``error`` and ``seconds``.

* Non-dominated (Pareto) designs: among the ``ok`` rows with every objective finite, those no
  other row is at least as good as in every objective and better in one.
* Requirements (``[outputs] require = ["life_h >= 2083", ...]``): a design meets them or not.
* Recommended: the non-dominated design that meets every requirement and is best in the FIRST
  objective (ties: the next objectives in order).
* Sensitivity of an output to a parameter: Spearman's rank correlation over the ok designs
  (monotone effects of any shape count; −1 … +1, 0 for no monotone effect) — a screening
  measure, as a tornado chart shows it, not a derivative.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from shaftfe.errors import InputError
from shaftfe.study.spec import FIXED, OPS, PREFIXES, StudySpec
from shaftfe.util.atomic import atomic_path

LAST = ("error", "seconds")


def default_objectives(spec: StudySpec) -> tuple[tuple[str, str], ...]:
    if spec.objectives:
        return spec.objectives
    life = ("life_h", "max") if spec.analyses.fatigue else (
        ("stress_max_MPa", "min") if spec.analyses.static else ("beam_max_peak_MPa", "min"))
    return (("engine_max_F_N", "min"), life, ("mass_kg", "min"))


def row_with_inputs(design, key: str, row: dict) -> dict:
    out: dict[str, Any] = {"design": design.number, "key": key, "status": row["status"]}
    for path, value in design.overrides:
        out[path] = value
    out.update({k: v for k, v in row.items() if k not in ("status", "cluster_failure", *LAST)})
    out.update({k: row.get(k) for k in LAST})
    return out


def frame(rows):
    import pandas as pd
    df = pd.DataFrame(list(rows))
    lead = [c for c in ("design", "key", "status") if c in df.columns]
    tail = [c for c in LAST if c in df.columns]
    return df[lead + [c for c in df.columns if c not in (*lead, *tail)] + tail]


def write_tables(out: Path, spec: StudySpec, rows) -> None:
    """results.parquet and results.csv (every design, all columns or those asked)."""
    df = frame(rows)
    if spec.columns:
        inputs = [c for c in df.columns if c not in FIXED and not c.startswith(PREFIXES)
                  and c not in LAST]
        wanted = [*spec.columns, *(c for c, _ in default_objectives(spec)),
                  *(c for c, _, _ in spec.requirements)]
        keep = inputs + [c for c in wanted if c in df.columns] + list(LAST)
        df = df[list(dict.fromkeys(keep))]
    # a column that mixes numbers and None (a failed design) is a float column with NaN
    for c in df.columns:
        if df[c].dtype == object and df[c].map(lambda x: x is None or (isinstance(
                x, int | float) and not isinstance(x, bool))).all():
            df[c] = df[c].astype(float)
    with atomic_path(out / "results.parquet") as tmp:
        df.to_parquet(tmp, index=False)
    with atomic_path(out / "results.csv") as tmp:
        df.to_csv(tmp, index=False)


def read_table(out_dir):
    import pandas as pd
    p = Path(out_dir) / "results.parquet"
    if not p.is_file():
        raise InputError(str(out_dir), "results.parquet", "a directory written by shaftfe "
                         "study run", reason="is missing")
    try:
        df = pd.read_parquet(p)
    except Exception as exc:                # pyarrow's ArrowInvalid, OSError, …: damaged
        raise InputError(str(out_dir), "results.parquet", "the table shaftfe study run writes "
                         "(run the same study again: it rewrites the table from designs/)",
                         reason=f"cannot be read ({type(exc).__name__}: damaged?)") from None
    if not {"design", "status", "error"} <= set(df.columns):
        raise InputError(str(out_dir), "results.parquet", "the table shaftfe study run writes "
                         "(columns design, status, error)", reason="has other columns")
    return df


def _finite(v) -> bool:
    """A number that ranks (±inf does: an infinite life is the best life); not None / NaN."""
    return v is not None and isinstance(v, int | float) and not math.isnan(v)


def non_dominated(df, objectives) -> list[bool]:
    """Mask of the non-dominated ok rows (objectives: [(column, "min"|"max")])."""
    cols = [c for c, _ in objectives]
    if any(c not in df.columns for c in cols):
        return [False] * len(df)
    sign = [1.0 if s == "min" else -1.0 for _, s in objectives]
    pts = []
    for _, r in df.iterrows():
        vals = [r[c] for c in cols]
        ok = r["status"] == "ok" and all(_finite(v) for v in vals)
        pts.append([s * float(v) for s, v in zip(sign, vals, strict=True)] if ok else None)
    mask = []
    for i, p in enumerate(pts):
        if p is None:
            mask.append(False)
            continue
        dom = any(q is not None and j != i and all(a <= b for a, b in zip(q, p, strict=True))
                  and any(a < b for a, b in zip(q, p, strict=True)) for j, q in enumerate(pts))
        mask.append(not dom)
    return mask


def meets(df, requirements) -> list[bool]:
    out = []
    for _, r in df.iterrows():
        ok = r["status"] == "ok"
        for col, op, val in requirements:
            v = r.get(col)
            ok = ok and _finite(v) and OPS[op](float(v), val)
        out.append(bool(ok))
    return out


def recommend(df, objectives, requirements) -> int | None:
    """Row index of the recommended design (see the module docstring), or None."""
    nd = non_dominated(df, objectives)
    ok = meets(df, requirements)
    cand = [i for i in range(len(df)) if nd[i] and ok[i]]
    if not cand:
        return None

    def score(i):
        return tuple((1 if s == "min" else -1) * float(df.iloc[i][c]) for c, s in objectives)
    return min(cand, key=score)


def sensitivities(df, parameters, outputs) -> dict[str, dict[str, float | None]]:
    """{output: {parameter: Spearman ρ}} over the ok designs."""
    ok = df[df["status"] == "ok"]
    res: dict[str, dict[str, float | None]] = {}
    for o in outputs:
        if o not in ok.columns:
            continue
        res[o] = {}
        for p in parameters:
            if p not in ok.columns or ok[p].dtype.kind not in "iuf":   # numbers only
                continue
            xy = ok[[p, o]].astype(float).dropna()          # pairs first, then ranks
            x, y = xy[p].rank(), xy[o].rank()
            if len(xy) < 3 or x.std() == 0 or y.std() == 0:
                res[o][p] = None
            else:
                res[o][p] = float(x.corr(y))
    return res
