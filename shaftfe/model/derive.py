"""A design's overrides plus what follows from them (``shaftfe study``; ``--set`` by hand too).

* An attachment whose ``shape.*`` is overridden gets ``mass_kg``, ``eccentricity_mm`` and both
  inertias from that shape (``shaftfe.model.shapes``), with its material's density and, for a
  hub ring, the radius of the seat it is keyed on.
* When anything is overridden, the variant's ``[balance]``
  statement (mass, γ2, x_T, X2) becomes what the parts give: the loader's consistency check
  (2 %, 2.5 points) then holds by construction. The crank's m_pos and R stay as stated.

The result is an ordinary override mapping {path: value}: ``load_variant(base, result)`` loads
the design, and the derived keys are tagged ``set`` in its provenance like the rest.
"""

from __future__ import annotations

from typing import Any

from shaftfe.errors import InputError

BALANCE_KEYS = ("mass_kg", "gamma2_mm", "x_T_mm", "X2_percent")
SHAPE_DERIVED = ("mass_kg", "eccentricity_mm", "polar_inertia_kg_mm2", "diametral_inertia_kg_mm2")


def with_shape_derived(base, overrides):
    """The overrides of a run as every command applies them (``load_variant``): unchanged
    unless a part's ``shape.*`` is set; then ``design_overrides`` (the one implementation,
    shared with ``shaftfe study``) adds the part's mass, eccentricity and inertias from the
    shape and the [balance] statement from the parts, so a changed shape changes the loads,
    the balance and the content hash of every command alike. A set that already carries the
    derived keys of every shaped part (a study design, from ``design_overrides``) is returned
    as it is."""
    from shaftfe.model import overrides as ov
    sets = ov.normalise(overrides)
    shaped = {o.path.split(".")[1] for o in sets
              if o.path.startswith("attachments.") and ".shape." in o.path}
    if not shaped:
        return sets
    given = {o.path for o in sets}
    if all(f"attachments.{n}.{k}" in given for n in shaped for k in SHAPE_DERIVED):
        return sets
    return ov.normalise(design_overrides(base, sets))


def _digits(v: float) -> float:
    return float(f"{v:.9g}")         # what a variant file would state; hash-stable


def design_overrides(base, overrides) -> dict[str, Any]:
    """{path: value}: ``overrides`` (canonical paths, as applied) and the derived keys."""
    from shaftfe.model import overrides as ov
    from shaftfe.model.mass import balance_ratio, mass_properties
    from shaftfe.model.parse import parts_variant, resolve_path, resolved_dict
    from shaftfe.model.shapes import shape_mass_properties

    sets = ov.normalise(overrides)
    merged = resolved_dict(resolve_path(base))
    applied = ov.apply(merged, sets)
    out: dict[str, Any] = {o.path: o.value for o in applied}
    shaped = {o.path.split(".")[1] for o in applied
              if o.path.startswith("attachments.") and ".shape." in o.path}
    atts = {a.get("name"): a for a in merged.get("attachments", [])}
    segs = {s.get("name"): s for s in merged.get("shaft", {}).get("segments", [])}
    for name in sorted(shaped):
        a = atts[name]
        mat = merged.get("materials", {}).get(a.get("material"), {})
        seat = segs.get(a.get("seat"), {})
        where = next(o.shown for o in applied if o.path.startswith(f"attachments.{name}.shape"))
        if "density_t_mm3" not in mat or "diameter_mm" not in seat:
            raise InputError(where, f"attachments.{name}", "a part with a material density "
                             "and a named seat (to derive its mass from its shape)")
        props = shape_mass_properties(a["shape"], float(mat["density_t_mm3"]),
                                      0.5 * float(seat["diameter_mm"]), where)
        for k, val in props.items():
            path = f"attachments.{name}.{k}"
            if path in out:
                raise InputError(where, path, "either the shape or the value",
                                 reason="is set too but follows from the shape")
            out[path] = _digits(val)
    # any change can move the balancer's mass properties (a part's mass, eccentricity or
    # angle, a segment's size, a density): the statement follows unless it is set itself
    bal = merged.get("balance")
    if out and isinstance(bal, dict) and not any(f"balance.{k}" in out for k in BALANCE_KEYS):
        v = parts_variant(base, out)
        mp = mass_properties(v)
        t = v.balance_target
        out["balance.mass_kg"] = _digits(mp.mass_kg)
        out["balance.gamma2_mm"] = _digits(mp.gamma2_mm)
        out["balance.x_T_mm"] = _digits(mp.x_T_mm)
        ratio = balance_ratio(mp, t)
        if ratio is not None:
            out["balance.X2_percent"] = _digits(100.0 * ratio)
    return out
