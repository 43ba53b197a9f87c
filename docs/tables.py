"""The result tables README.md quotes, computed by the project's own API so they cannot go stale.

    python docs/tables.py            # rewrite the tables in README.md (make tables)
    python docs/tables.py --check    # exit 1 if README.md's tables differ from a fresh run

Each table sits between ``<!-- table:NAME -->`` and ``<!-- /table -->`` in README.md. The
static solutions come from the cache (``shaftfe.static.cache``) when the model is unchanged, so a
second run takes seconds; a cold run solves x2_57 twice at the default level (≈ 30 s).
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"


def fatigue_x2_57() -> str:
    """x2_57, the seed's fatigue settings on loadspectra/rpm.dat, default mesh, both load cases,
    3D and axisymmetric, next to the seed's Ansys result (seed 000 §8.3)."""
    from shaftfe.fatigue.field import evaluate
    from shaftfe.fatigue.run import SEED, read_spectrum
    from shaftfe.fatigue.sn import load_material
    from shaftfe.model.loader import load_variant
    from shaftfe.static import cache as static_cache
    from shaftfe.static.model import StaticOptions, load_case_label
    from shaftfe.util.fmt import big as _big
    from shaftfe.util.paths import DEFAULT_SPECTRUM

    v = load_variant("x2_57")
    history = read_spectrum(str(DEFAULT_SPECTRUM), None, None)
    material = load_material("structural_steel")
    rows = [f"| seed (Ansys) | {SEED['hot_spot']} | {SEED['safety_factor_at_1e7']} | "
            f"{_big(SEED['life_blocks'])} blocks, {_big(SEED['life_hours'])} h, "
            f"{_big(SEED['life_km'])} km |"]
    for seed_case in (True, False):
        ref = static_cache.load_or_solve(v, StaticOptions(level="default",
                                                          seed_load_case=seed_case))
        hs = evaluate(ref, history, material).hot_spot
        rows.append(
            f"| shaftfe, {load_case_label(seed_case)} | {hs.region}, x = {hs.xyz_mm[0]:.1f} mm "
            f"({hs.sigma_eq_ref_MPa:.1f} MPa at {_big(ref.ref_rpm)} rpm) | "
            f"{hs.safety_factor:.3f} | {_big(hs.life_blocks)} blocks, {_big(hs.life_hours)} h, "
            f"{_big(hs.life_km)} km |")
    from shaftfe.axisymmetric.model import AxiOptions
    from shaftfe.axisymmetric.reference import static_reference
    from shaftfe.axisymmetric.solve import solve_axisymmetric
    for seed_case in (True, False):
        ref = static_reference(solve_axisymmetric(
            v, options=AxiOptions(level="default", seed_load_case=seed_case)))
        hs = evaluate(ref, history, material).hot_spot
        rows.append(
            f"| shaftfe `--model axisymmetric`, {load_case_label(seed_case)} | {hs.region}, "
            f"x = {hs.xyz_mm[0]:.1f} mm ({hs.sigma_eq_ref_MPa:.1f} MPa at "
            f"{_big(ref.ref_rpm)} rpm) | {hs.safety_factor:.3f} | {_big(hs.life_blocks)} "
            f"blocks, {_big(hs.life_hours)} h, {_big(hs.life_km)} km |")
    head = ("| | hot spot | safety factor at 10⁷ blocks | life |\n"
            "|---|---|---|---|")
    return head + "\n" + "\n".join(rows)


TABLES = {"fatigue-x2_57": fatigue_x2_57}


def render(text: str) -> str:
    for name, make in TABLES.items():
        pat = re.compile(rf"(<!-- table:{re.escape(name)} -->\n)(?:.*?\n)?(<!-- /table -->)",
                         re.S)
        if not pat.search(text):
            raise SystemExit(f"README.md: marker <!-- table:{name} --> not found")
        body = make()
        text = pat.sub(lambda m, b=body: m.group(1) + b + "\n" + m.group(2), text)
    return text


def main(argv: list[str]) -> int:
    old = README.read_text(encoding="utf-8")
    new = render(old)
    if "--check" in argv:
        if new != old:
            print("README.md: the result tables are stale; run `make tables`", file=sys.stderr)
            return 1
        print("README.md: result tables are current")
        return 0
    if new != old:
        from shaftfe.util.atomic import write_atomic
        write_atomic(README, new)
        print("README.md: tables rewritten")
    else:
        print("README.md: tables already current")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
