"""``shaftfe fatigue --method fkm | din743``: strength by standard, the bearings' life over the
duty cycle and the seed's key and gear checks. A thin layer over ``shaftfe.fatigue.standards``
and ``shaftfe.fatigue.standards_out``; writes summary.json, its field and plots
(``standards_out.write_outputs``; all or none)."""

from __future__ import annotations

import math


def options_of(args):
    from shaftfe.fatigue.standards import StrengthOptions
    return StrengthOptions(card=args.card, rule=args.miner, consequences=args.consequences,
                           inspection=args.inspection, damage_sum=args.damage_sum)


def check_element_options(args) -> tuple[float, float]:
    from shaftfe.elements.bearings import EC_DEFAULT, KAPPA_DEFAULT
    from shaftfe.errors import InputError
    kappa = KAPPA_DEFAULT if args.kappa is None else args.kappa
    ec = EC_DEFAULT if args.ec is None else args.ec
    if not (math.isfinite(kappa) and 0.1 <= kappa <= 4.0):
        raise InputError("command line", "--kappa", "a number in [0.1, 4] (ISO 281)", got=kappa)
    if not (math.isfinite(ec) and 0.0 <= ec <= 1.0):
        raise InputError("command line", "--ec", "a number in [0, 1] (ISO 281 Table 13)",
                         got=ec)
    return kappa, ec


def run_standard(args, job) -> int:
    from pathlib import Path

    from shaftfe.commands._common import out_name, print_json, print_table
    from shaftfe.fatigue import standards as sd
    from shaftfe.fatigue import standards_out as so
    from shaftfe.fatigue.assess import life_hours, life_km
    from shaftfe.fatigue.run import load_inputs
    from shaftfe.util.atomic import staged_dir
    from shaftfe.util.fmt import design_life, lives

    opts = options_of(args)
    sd.check_options(opts)
    kappa, ec = check_element_options(args)
    inputs = load_inputs(job)
    v = inputs.variant
    out = Path(args.out) if args.out else \
        Path("reports") / out_name(v.name, v.overrides) / f"fatigue-{args.method}"
    with staged_dir(out) as stage:
        if args.method == "fkm":
            res, _, ref = sd.run_fkm(job, opts, inputs)
            summary = so.fkm_summary(res)
            beam = None
        else:
            beam = sd.beam_at_ref(v)              # one beam solve for DIN 743 and the bearings
            res = sd.run_din743(job, opts, inputs, beam)
            summary = so.din_summary(res)
        el = so.compute_elements(v, inputs.history, kappa, ec, job.speed_kmh, beam)
        summary = {"variant": v.name, "spectrum": str(job.spectrum), **summary,
                   "elements": el}
        summary, files = so.write_outputs(args.method, res, ref if beam is None else None,
                                          stage, summary)
    if args.json:
        print_json(summary)
        return 0
    h = inputs.history
    print(f"{v.name} strength by {args.method.upper() if args.method == 'fkm' else 'DIN 743'}:"
          f" {h.source} ({h.n_samples} samples, rpm {h.rpm.min():.0f}-{h.rpm.max():.0f}), "
          f"material {res.card.name} ({'--card' if opts.card else 'the shaft material'}, "
          "geometry/common/materials.toml)")
    if args.method == "fkm":
        print(f"static: {'from cache' if ref.from_cache else 'solved'} ({ref.ref_rpm:g} rpm, "
              f"{ref.n_nodes} nodes, P2 {job.level}); design life "
              f"{design_life(res.design_life_blocks, res.block_seconds, job.speed_kmh)}; "
              f"j_D {res.j_D:g}; D_M {res.damage_sum:g}; governing rule: {res.rule}")
        print_table(so.FKM_HEAD, so.fkm_rows(res), title="FKM, local stresses, per region "
                    "(surface layer and core at the case depth)")
        for note in so.fkm_notes(res):
            print(note)
        g, c = res.governing
        b = c.life_blocks[res.rule]
        h = float(life_hours(b, res.block_seconds))
        if so.no_load_cycles(res):
            print(f"governing: none: {so.NO_LOAD_CYCLES}")
        else:
            print(f"governing: {g.region} ({c.layer}), safety {so._f(c.safety[res.rule])} "
                  f"against j_D {res.j_D:g}, degree of utilisation "
                  f"{so._f(c.utilisation[res.rule])} "
                  f"({'passes' if c.utilisation[res.rule] <= 1 else 'FAILS'}); life: "
                  f"{lives(b, h, float(life_km(h, job.speed_kmh)), job.speed_kmh)}")
            print(f"size factor: K_d,m at d_eff {c.d_eff_mm:.2f} mm, the round section through "
                  "the hot spot (FKM; DIN 743 takes its K1 at a shoulder's larger diameter)")
    else:
        print(f"cycle: the history's largest, {res.rpm_min:.0f}-{res.rpm_max:.0f} rpm (case 2); "
              f"S_F at {res.rpm_max:.0f} rpm; beam at {res.ref_rpm:g} rpm scaled by rpm²")
        print_table(so.DIN_HEAD, so.din_rows(res), title="DIN 743, nominal stresses, bending "
                    "factors per notch")
        g = res.governing
        print(f"governing: {g.result.notch.name} at x = {g.x_mm:g} mm: S_D "
              f"{so._f(g.result.S_D)}, S_F {so._f(g.result.S_F)} (S_min {sd.din743.S_MIN})")
        for note in res.notes:
            print(f"note: {note}")
    print()
    for line in so.elements_lines(el, job.speed_kmh):
        print(line)
    print("\nwrote " + ", ".join(str(out / f) for f in files))
    return 0
