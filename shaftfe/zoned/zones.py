"""Where the 3D submodels go: one zone per group of features that are not bodies of revolution
(``solid.features.cuts``: keyways, the hex socket), cut where the global field may be imposed.

A zone starts as the union of its features' zones of influence (``Feature.zone_mm``: the
feature's extent ± the local diameter, Saint-Venant), zones that overlap merged. Its two cuts
are planes x = const that must lie

* on a straight part of the outline (not in a fillet, not on a shoulder step): the submodel's
  cut face is then a full disc whose field is the global's;
* clear of every load band and seat (the parts' seats, the bearings' contact bands, the
  ``[[loads]]`` bands): a load is applied whole inside a zone or not at all; a part's seat by
  ``SEAT_CLEAR_D`` × the local diameter;
* at least ``CUT_MARGIN_MM`` from each of these edges, and at least ``MIN_DISTANCE_D`` × the
  local diameter from the feature (a cut nearer than that sits in the feature's own field).

The nominal cut is the zone's end; when it is not admissible, the middle of the admissible gap
nearest to it is taken (inward or outward), on a 0.1 mm grid (``_snap``). A zone that
reaches a shaft end has no cut there. ``grow`` moves a cut outward to the next admissible gap:
the zoned solve does so while its cut check fails (``zoned.solve``).
"""

from __future__ import annotations

from dataclasses import dataclass

from shaftfe.solid.features import Feature, features

CUT_MARGIN_MM = 0.5        # from a fillet, a step or a load band's edge
MIN_DISTANCE_D = 0.5       # × the local diameter, from the zone's cut features
# × the local diameter, from a part's seat (its load enters through the seat: an RBE3 patch in
# 3D, a band in the global model, whose local fields differ within about a diameter). Measured
# on x2_57 (default level): a cut 1.5 mm from counterweight_2's seat failed the cut check
# (σ_xx 12.9 %, 13.8 % at 1 mm, 25.6 % at 0.5 mm) and the zone grew by one gap, solving the
# submodel twice; a cut 0.5 mm from a bearing's band passes (5.7 %). The cut check still
# decides: this only starts the zone where it would have grown to
SEAT_CLEAR_D = 0.5
# a cut in a gap's middle is rounded to this grid (``_snap``): half of it is the most it moves
CUT_GRID_MM = 0.1
TOL = 1e-9


@dataclass(frozen=True)
class Zone:
    """One 3D submodel: its cut features, its extent [x0, x1] and which ends are cuts."""
    name: str                              # "zone:<first feature's region>"
    features: tuple[Feature, ...]          # the cuts it holds (not bodies of revolution)
    x0: float
    x1: float
    cut_left: bool                          # x0 is a cut (False: the shaft's left end)
    cut_right: bool
    nominal_mm: tuple[float, float]        # the features' zones of influence, merged

    @property
    def cuts_mm(self) -> tuple[float, ...]:
        return tuple(x for x, c in ((self.x0, self.cut_left), (self.x1, self.cut_right)) if c)


def _forbidden(plan, feats, bands) -> list[tuple[float, float]]:
    """Intervals no cut may fall in: fillets, shoulder steps, seats, load bands, and every
    segment boundary where the diameter changes (with ``CUT_MARGIN_MM`` around each)."""
    out = []
    for f in feats:
        if f.kind == "seat":                # a part's seat: its load's own field around it
            gap = SEAT_CLEAR_D * max(diameter_at(plan, f.x_mm[0]), diameter_at(plan, f.x_mm[1]))
            out.append((f.x_mm[0] - gap, f.x_mm[1] + gap))
        elif f.kind != "end":
            out.append(f.x_mm)
    out += [tuple(b) for b in bands]
    for i in range(len(plan.radii) - 1):
        if abs(plan.r_right(i) - plan.radii[i + 1]) > 1e-9:
            x = plan.segment_x[i][1]
            out.append((x, x))
    return sorted((a - CUT_MARGIN_MM, b + CUT_MARGIN_MM) for a, b in out)


def admissible_gaps(plan, feats, bands) -> list[tuple[float, float]]:
    """The stations where a cut may go, as closed intervals inside the shaft."""
    gaps, x = [], plan.x_left
    for a, b in _forbidden(plan, feats, bands):
        if a > x + TOL:
            gaps.append((x, a))
        x = max(x, b)
    if plan.x_right > x + TOL:
        gaps.append((x, plan.x_right))
    return [(a, b) for a, b in gaps if b - a > TOL]


def diameter_at(plan, x: float) -> float:
    for i, ((a, b), r) in enumerate(zip(plan.segment_x, plan.radii, strict=True)):
        if a - TOL <= x <= b + TOL:
            return 2.0 * (r + (x - a) / (b - a) * (plan.r_right(i) - r))
    return 2.0 * plan.r_max


def _place(plan, gaps, nominal: float, limit: float, side: int) -> float | None:
    """The cut on side ``side`` (−1: left cut, at most ``limit``; +1: right cut, at least
    ``limit``) in the admissible gap nearest to ``nominal``: ``nominal`` itself when it lies in
    the gap, else the gap's middle, at most ``MIN_DISTANCE_D`` local diameters from the gap's
    station nearest to ``nominal`` (a long gap does not carry the cut far); None if the zone
    reaches the shaft end."""
    if (side < 0 and nominal <= plan.x_left + TOL) or (side > 0 and nominal >= plan.x_right - TOL):
        return None
    best, dist = None, None
    for a, b in gaps:
        if side < 0:
            b = min(b, limit)
        else:
            a = max(a, limit)
        if b - a < TOL:
            continue
        near = min(max(nominal, a), b)          # the gap's station nearest to the nominal
        if dist is None or abs(near - nominal) < dist - TOL:
            # inside the gap: the nominal cut; else the gap's middle, as far from the
            # fillet, step or band at either edge as the gap allows (x2_57's gear-seat zone:
            # its cut 3 mm inward at the middle, cut check 5.7 → 4.6 %)
            if a <= nominal <= b:
                best = near
            else:
                step = MIN_DISTANCE_D * diameter_at(plan, near)
                best = _snap(near + max(-step, min(step, 0.5 * (a + b) - near)), a, b)
            dist = abs(near - nominal)
    return best


def _snap(x: float, a: float, b: float) -> float:
    """``x`` rounded to ``CUT_GRID_MM`` when that stays in the admissible gap [a, b] (which
    holds every margin already), else ``x``: a cut placed in the middle of a gap follows the
    gap's edges, and an edge is often a fillet outside the zone (x2_57's keyway zone at
    counterweight 2: the gap starts where the collar fillet ends), so without the grid every
    change of that fillet would move the cut by half the change and mesh and factorise the
    zone anew; on the grid a study of the collar fillet (0.41 … 0.49 mm) keeps one zone."""
    q = round(x / CUT_GRID_MM) * CUT_GRID_MM
    q = round(q, 6)                         # the grid's decimal value, not its binary remainder
    return q if a - TOL <= q <= b + TOL else x


def plan_zones(plan, bands=()) -> tuple[Zone, ...]:
    """The zones of the solid plan ``plan``; ``bands``: the load bands (x0, x1) of the
    variant's actions that are not seats (``model.loads.actions``)."""
    feats = features(plan)
    cuts = sorted((f for f in feats if f.cut), key=lambda f: f.zone_mm[0])
    groups: list[list[Feature]] = []
    for f in cuts:
        if groups and f.zone_mm[0] <= max(g.zone_mm[1] for g in groups[-1]) + TOL:
            groups[-1].append(f)
        else:
            groups.append([f])
    gaps = admissible_gaps(plan, feats, bands)
    zones = []
    for g in groups:
        lo = min(f.zone_mm[0] for f in g)
        hi = max(f.zone_mm[1] for f in g)
        ext0 = min(f.x_mm[0] for f in g)
        ext1 = max(f.x_mm[1] for f in g)
        d0, d1 = diameter_at(plan, ext0), diameter_at(plan, ext1)
        x0 = _place(plan, gaps, lo, ext0 - MIN_DISTANCE_D * d0, -1)
        x1 = _place(plan, gaps, hi, ext1 + MIN_DISTANCE_D * d1, +1)
        if (x0 is None and lo > plan.x_left + TOL) or (x1 is None and hi < plan.x_right - TOL):
            x0 = plan.x_left if x0 is None else x0      # no admissible cut: to the shaft end
            x1 = plan.x_right if x1 is None else x1
        zones.append(Zone(f"zone:{g[0].region}", tuple(g),
                          plan.x_left if x0 is None else x0, plan.x_right if x1 is None else x1,
                          x0 is not None and x0 > plan.x_left + TOL,
                          x1 is not None and x1 < plan.x_right - TOL, (lo, hi)))
    return _merge(zones, plan)


def _merge(zones, plan) -> tuple[Zone, ...]:
    """Zones whose placed cuts overlap become one."""
    out: list[Zone] = []
    for z in zones:
        if out and z.x0 < out[-1].x1 - TOL:
            p = out[-1]
            out[-1] = Zone(p.name, p.features + z.features, p.x0, max(p.x1, z.x1), p.cut_left,
                           z.cut_right if z.x1 >= p.x1 else p.cut_right,
                           (p.nominal_mm[0], max(p.nominal_mm[1], z.nominal_mm[1])))
        else:
            out.append(z)
    return tuple(out)


def grow(zone: Zone, plan, bands=(), side: int = 0) -> Zone | None:
    """``zone`` with its cut(s) moved outward to the next admissible gap (``side`` −1 the left
    one, +1 the right one, 0 both), or None when there is no room left."""
    gaps = admissible_gaps(plan, features(plan), bands)
    x0, x1, c0, c1 = zone.x0, zone.x1, zone.cut_left, zone.cut_right
    moved = False
    if side <= 0 and c0:
        left = [g for g in gaps if g[1] < x0 - CUT_MARGIN_MM]
        x0, c0 = ((_snap(0.5 * (left[-1][0] + left[-1][1]), *left[-1]), True) if left
                  else (plan.x_left, False))
        moved = True
    if side >= 0 and c1:
        right = [g for g in gaps if g[0] > x1 + CUT_MARGIN_MM]
        x1, c1 = ((_snap(0.5 * (right[0][0] + right[0][1]), *right[0]), True) if right
                  else (plan.x_right, False))
        moved = True
    if not moved:
        return None
    return Zone(zone.name, zone.features, x0, x1, c0, c1, zone.nominal_mm)
