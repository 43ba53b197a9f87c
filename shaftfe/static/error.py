"""A Richardson-type error estimate of a static result from a second mesh level."""

from __future__ import annotations

import math
from dataclasses import replace

from shaftfe.solid.features import is_notch
from shaftfe.solid.levels import ESTIMATE_PAIR, level_name, mesh_level
from shaftfe.static.model import StaticOptions
from shaftfe.static.result import StaticResult
from shaftfe.static.solve import solve_static


def with_error_estimate(res: StaticResult, variant, options: StaticOptions, cache_dir=None,
                        other_level=None) -> StaticResult:
    """``res`` with its ``error_estimate`` from a second solve (``estimate_error``)."""
    return replace(res, error_estimate=estimate_error(res, variant, options, cache_dir,
                                                      other_level))


def estimate_error(res: StaticResult, variant, options: StaticOptions, cache_dir,
                    other_level: str | None = None) -> dict:
    """Richardson-type estimate from a second mesh level.

    Second level: ``other_level`` if given, else "fine" (or "default" when the first is
    "fine"); the finer of the two is the one with the smaller fillet size k_fillet. With q_h
    (finer) and q_H,
    the estimated error of q_h is |q_h − q_H| / (r^p − 1) and the extrapolated value
    q_h + (q_h − q_H)/(r^p − 1). Ratios r: element size on the fillets (k_fillet of the levels)
    for stress peaks; (N_fine/N_coarse)^(1/3) from the element counts for deflections. Orders
    assumed: p = 2 for recovered P2 stresses (p = 1 for P1), p = 3 for P2 displacements (2 for
    P1). An estimate, not a bound: on a graded mesh the asymptotic range is not guaranteed."""
    other = other_level or ESTIMATE_PAIR.get(level_name(options.level), "fine")
    k_this, k_other = mesh_level(options.level).k_fillet, mesh_level(other).k_fillet
    case = getattr(res, "case_name", "") or None        # a load case: its own rpm
    res2 = solve_static(variant, None if case else [c.rpm for c in res.cases],
                        replace(options, level=other), case=case, cache_dir=cache_dir,
                        beam=False)
    finer_first = k_this < k_other or (k_this == k_other and other != "fine")
    fine_r, coarse_r = (res, res2) if finer_first else (res2, res)
    p_s, p_u = (2, 3) if options.order == 2 else (1, 2)
    r_s = (k_other / k_this) if finer_first else (k_this / k_other)
    r_u = (fine_r.n_elements / coarse_r.n_elements) ** (1 / 3)

    def est(qf, qc, r, p):
        if not (math.isfinite(qf) and math.isfinite(qc)) or r <= 1:
            return None
        d = (qf - qc) / (r ** p - 1)
        return {"fine": qf, "coarse": qc, "extrapolated": qf + d, "error_fine": abs(d),
                "rel_error_fine": abs(d) / abs(qf) if qf else None}
    out = {"levels": [level_name(fine_r.options.level), level_name(coarse_r.options.level)],
           "dofs": [fine_r.n_dofs, coarse_r.n_dofs], "ratio_stress": r_s, "ratio_deflection": r_u,
           "order_stress": p_s, "order_deflection": p_u, "cases": []}
    for cf, cc in zip(fine_r.cases, coarse_r.cases, strict=True):
        pk_c = {p.region: p for p in cc.peaks}
        peaks = {p.region: est(p.von_mises_MPa, pk_c[p.region].von_mises_MPa, r_s, p_s)
                 for p in cf.peaks if p.region in pk_c
                 and is_notch(p.region)}
        st_c = {s.name: s for s in cc.stations}
        out["cases"].append({
            "rpm": cf.rpm,
            "peak_von_mises": est(cf.peak_von_mises_MPa, cc.peak_von_mises_MPa, r_s, p_s),
            "region_peaks": peaks,
            "max_deflection": est(cf.max_deflection_mm, cc.max_deflection_mm, r_u, p_u),
            "stations": {s.name: est(s.u_mm, st_c[s.name].u_mm, r_u, p_u)
                         for s in cf.stations if s.name in st_c}})
    return out
