"""Balance ratios from weighed parts and CAD centroids (seed 003 ch. 4-6, SPEC.md §1).

    rod split (eq. 7-8):  m_or = m_oj (l − l1) / l,   m_op = m_oj − m_or
    crank (eq. 9-11):     m_r = m_kh + m_č + m_or,    r_r = (m_kh r_kh − (m_č + m_or) r) / m_r
    balance (eq. 12-13):  P  = (m_r r_r + m_v r_v) / ((m_p + m_op) r)
    balancer/crank (15):  Pv = m_v r_v / (m_r r_r)

l is the rod's eye-to-eye distance and l1 the distance of its centroid from the big eye; the
crank centroid r_kh lies opposite the pin. In seed 000 terms P = X + X2 and Pv = X2 / X.
Any consistent units work; ``Engine`` values are kg and mm.
"""

from __future__ import annotations

from dataclasses import dataclass

from shaftfe.balance.engines import Engine
from shaftfe.errors import InputError


@dataclass(frozen=True)
class PartsRatios:
    """Seed 003 quantities (kg, mm) and the ratios P, Pv; X, X2 in seed 000 terms."""

    engine: str
    m_rod_rot_kg: float        # m_or (plus the big-end bearing if the file gives one)
    m_rod_pos_kg: float        # m_op
    m_pos_kg: float            # m_p + m_op
    m_r_kg: float | None       # crank rotating mass m_kh + m_č + m_or (parts description only)
    r_r_mm: float | None       # its centroid, counterweight side positive
    crank_moment_kg_mm: float  # m_r r_r (= m_C γ − m_rot R for a lumped description)
    balancer_moment_kg_mm: float
    X: float                   # crank share of the 1st-order reciprocating force
    X2: float                  # balancer share
    P: float                   # = X + X2
    Pv: float | None           # = X2 / X (None when the crank moment is zero)

    def summary(self, source: str) -> dict:
        """What ``shaftfe balance ratios`` reports (its ``--json``): every field, X, X2, P and
        Pv in percent (as the table and every command), and the engine file ``source``."""
        d = {k: getattr(self, k) for k in self.__dataclass_fields__}
        for k in ("X", "X2", "P", "Pv"):
            v = d.pop(k)
            d[f"{k}_percent"] = None if v is None else 100.0 * v
        d["source"] = source
        return d


def ratios(engine: Engine) -> PartsRatios:
    """P and Pv of an engine (seed 003 §5.3-5.5), from parts or from a lumped description."""
    crank = engine.crank_static_moment_kg_mm
    if crank is None:
        raise InputError(engine.source, "compensation_mass_kg",
                         "compensation_mass_kg + compensation_radius_mm, or crank_pin_mass_kg + "
                         "crank_without_pin_mass_kg + crank_without_pin_centroid_mm",
                         reason="is missing (the crank's static moment is needed)")
    if engine.balancer_mass_kg is not None and engine.balancer_radius_mm is not None:
        bal = engine.balancer_mass_kg * engine.balancer_radius_mm
    else:
        bal = 0.0
    R = engine.crank_radius_mm
    m_pos = engine.m_pos_kg
    if engine.has_parts and engine.compensation_mass_kg is None:
        m_r = engine.crank_without_pin_mass_kg + engine.crank_pin_mass_kg + engine.m_rot_kg
        r_r = crank / m_r
    else:
        m_r = r_r = None
    X = crank / (m_pos * R)
    X2 = bal / (m_pos * R)
    return PartsRatios(
        engine=engine.name, m_rod_rot_kg=engine.m_rot_kg, m_rod_pos_kg=engine.rod_pos_mass_kg,
        m_pos_kg=m_pos, m_r_kg=m_r, r_r_mm=r_r, crank_moment_kg_mm=crank,
        balancer_moment_kg_mm=bal, X=X, X2=X2, P=X + X2,
        Pv=None if crank == 0 else bal / crank,
    )
