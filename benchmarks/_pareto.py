"""Pure helpers of ``bench_pareto``: Pareto dominance, the non-dominated filter, Richardson
extrapolation and the Pareto plot. NumPy / matplotlib are imported inside the functions.

Dominance (all objectives minimised): point a dominates point b when a is no worse than b in
every objective and strictly better in at least one (e.g. Deb, *Multi-Objective Optimization
Using Evolutionary Algorithms*, Wiley 2001, Def. 2.5). The Pareto front of a set = the points
that no other point of the set dominates. Two identical points do not dominate each other, so
both stay on the front. A point with a NaN objective is never on the front and dominates
nothing.
"""

from __future__ import annotations

import math
from collections.abc import Sequence


def _ok(p: Sequence[float]) -> bool:
    return all(not math.isnan(float(v)) for v in p)


def dominates(a: Sequence[float], b: Sequence[float]) -> bool:
    """True when ``a`` dominates ``b`` (every objective minimised)."""
    if len(a) != len(b):
        raise ValueError("points of different dimension")
    if not (_ok(a) and _ok(b)):
        return False
    no_worse = all(float(x) <= float(y) for x, y in zip(a, b, strict=True))
    better = any(float(x) < float(y) for x, y in zip(a, b, strict=True))
    return no_worse and better


def pareto_mask(points: Sequence[Sequence[float]]) -> list[bool]:
    """``mask[i]`` is True when no point of ``points`` dominates point i (O(n²), n is small)."""
    pts = [tuple(float(v) for v in p) for p in points]
    return [_ok(p) and not any(dominates(q, p) for j, q in enumerate(pts) if j != i)
            for i, p in enumerate(pts)]


def richardson(q_fine: float, q_coarse: float, r: float, p: float) -> float:
    """Extrapolated value q* = q_f + (q_f − q_c) / (r^p − 1) for a size ratio r > 1, order p."""
    if not r > 1.0:
        raise ValueError(f"refinement ratio must be > 1, got {r}")
    return q_fine + (q_fine - q_coarse) / (r ** p - 1.0)


def fastest_within(rows: Sequence[dict], err_key: str, time_key: str, tol: float):
    """The row with the smallest ``time_key`` among those with |err| <= tol (None if none)."""
    ok = [r for r in rows if r.get(err_key) is not None and r.get(time_key) is not None
          and math.isfinite(r[err_key]) and abs(r[err_key]) <= tol]
    return min(ok, key=lambda r: r[time_key]) if ok else None


def pair_modes(modes: list[dict], ref: list[dict]) -> list[tuple[dict, dict]]:
    """Pairs (mode, reference mode): within each class (family, whirl) the k-th lowest with
    the k-th lowest; modes of a class the other model lacks stay unpaired."""
    out = []
    keys = {(m["family"], m["whirl"]) for m in modes}
    for k in sorted(keys):
        a = sorted((m for m in modes if (m["family"], m["whirl"]) == k), key=lambda m: m["f0"])
        b = sorted((m for m in ref if (m["family"], m["whirl"]) == k), key=lambda m: m["f0"])
        out += list(zip(a, b, strict=False))
    return out


def plot_pareto(path, rows: Sequence[dict], *, err_key: str, title: str, err_label: str,
                axes: Sequence[tuple[str, str, str]], floor: float = 1e-7) -> None:
    """Error against cost, log-log, one panel per ``axes`` entry (key, axis label, front key).

    Each row: ``label``, ``family`` (marker/colour group), ``default`` (bool), the cost keys,
    ``err_key`` (relative error; |.| in % is plotted, values below ``floor`` are drawn at the
    floor and said so) and the boolean front keys. The front is drawn as a staircase, the
    default as a large ring with its label."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fams = sorted({r["family"] for r in rows})
    cmap = plt.get_cmap("tab10")
    marks = "osD^v<>Ph*X"
    style = {f: (cmap(i % 10), marks[i % len(marks)]) for i, f in enumerate(fams)}
    fig, axs = plt.subplots(1, len(axes), figsize=(6.2 * len(axes), 5.0), squeeze=False)
    floored = False
    for ax, (key, xlabel, front_key) in zip(axs[0], axes, strict=True):
        pts = [r for r in rows if r.get(key) is not None and r.get(err_key) is not None
               and math.isfinite(r[err_key]) and r[key] > 0]
        for f in fams:
            sel = [r for r in pts if r["family"] == f]
            if not sel:
                continue
            ys = [max(abs(r[err_key]), floor) * 100 for r in sel]
            floored |= any(abs(r[err_key]) < floor for r in sel)
            c, m = style[f]
            ax.scatter([r[key] for r in sel], ys, color=c, marker=m, s=36, label=f,
                       zorder=3)
        front = sorted((r for r in pts if r.get(front_key)), key=lambda r: r[key])
        if front:
            xs, ys = [], []
            for r in front:
                y = max(abs(r[err_key]), floor) * 100
                if xs:
                    xs.append(r[key])
                    ys.append(ys[-1])
                xs.append(r[key])
                ys.append(y)
            ax.plot(xs, ys, color="0.3", lw=1.0, ls="--", zorder=2, label="Pareto front")
        for r in pts:
            y = max(abs(r[err_key]), floor) * 100
            ax.annotate(r["short"], (r[key], y), fontsize=6.5, xytext=(3, 3),
                        textcoords="offset points", color="0.25")
            if r.get("default"):
                ax.scatter([r[key]], [y], s=260, facecolors="none", edgecolors="red",
                           linewidths=2.0, zorder=4, label="default")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(err_label)
        ax.grid(True, which="both", alpha=0.3)
        h, lab = ax.get_legend_handles_labels()
        uniq = dict(zip(lab, h, strict=True))
        ax.legend(uniq.values(), uniq.keys(), fontsize=7, loc="best")
    t = title + (f"\n(errors below {floor * 100:g} % drawn at {floor * 100:g} %)"
                 if floored else "")
    fig.suptitle(t, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
