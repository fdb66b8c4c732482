"""``gearkit planetary``: ranked planetary tooth-number sets for a ratio.

Usage::

    gearkit planetary --ratio R --planets K -m M [--ratio-tol T] [--max-teeth Z]
                      [--scheme simple|compound|external|internal] [--min-teeth N] [--sets N]
                      [--textbook] [--json]

``R`` is i_1B: the sun's speed over the carrier's with gear 4 (the ring) fixed. Every set within
the tolerance and the limits is ranked by size; the best are kept if they are coaxial (profile
shift closes tooth sums that differ by up to 2), assemble (equally spaced planets, else the
unequal angles that do), clear their neighbours and pass gearkit's pair checks on every mesh.
Exit status: 0 sets found, 1 none passes, 2 bad input.
"""
from __future__ import annotations

from gearkit.cli.common import add_json_flag, add_module_flag, add_renamed_flag, print_json
from gearkit.errors import SpecError


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "planetary", help="planetary tooth numbers for a ratio: coaxial, assemblable, clear, checked",
        description="Rank planetary tooth-number sets for a target ratio i_1B (sun in, carrier out, ring fixed) "
                    "with K planets: coaxiality (profile shift when tooth sums differ), assembly (equal spacing, "
                    "else unequal angles that assemble), neighbour clearance and gearkit's pair checks per mesh; "
                    "each set with its planet angles, mesh phases and phasing class. Lengths in mm.",
        epilog="Exit status: 0 sets found, 1 none passes, 2 bad input.")
    p.add_argument("--ratio", type=float, required=True, help="target i_1B = w_sun / w_carrier (ring fixed)")
    p.add_argument("--planets", type=int, required=True, metavar="K", help="number of planets")
    add_module_flag(p, "normal module, mm", required=True)
    p.add_argument("--ratio-tol", type=float, default=0.0, help="relative ratio tolerance (default 0: exact)")
    p.add_argument("--max-teeth", type=int, default=200, help="largest tooth number of any gear (default 200)")
    p.add_argument("--min-teeth", type=int, default=17, help="smallest external gear (default 17)")
    p.add_argument("--scheme", choices=("simple", "compound", "external", "internal"), default="simple",
                   help="simple: sun-planet-ring; compound: sun-2|3-ring; external: sun-2|3-gear 4; "
                        "internal: ring-2|3-ring (default simple)")
    sets = p.add_mutually_exclusive_group()
    sets.add_argument("--sets", type=int, default=5, metavar="N", help="how many sets to list (default 5)")
    add_renamed_flag(sets, "--count", "--sets", "sets", type=int)
    p.add_argument("--textbook", action="store_true", help="the textbook's limits instead (zero gears: ring >= 85, "
                   "planet in a ring >= 20, difference >= 8, exact coaxiality, equal spacing, no pair checks)")
    add_json_flag(p)
    p.set_defaults(run=run)


def run(args) -> int:
    from dataclasses import replace

    from gearkit.scene.synthesis import TEXTBOOK_LIMITS, SynthesisLimits, synthesize

    if not 1 <= args.sets <= 1000:
        raise SpecError("--sets", f"{args.sets} is outside [1, 1000] (sets listed)")
    if args.textbook:
        limits = replace(TEXTBOOK_LIMITS, max_teeth=args.max_teeth)
    else:
        limits = SynthesisLimits(min_teeth=args.min_teeth, max_teeth=args.max_teeth)
    sets = synthesize(args.ratio, args.planets, args.module, scheme=args.scheme, ratio_tol=args.ratio_tol,
                      limits=limits, count=args.sets)
    out = {"ratio": args.ratio, "planets": args.planets, "module": args.module, "scheme": args.scheme,
           "ratio_tol": args.ratio_tol, "candidates": [s.to_dict() for s in sets]}
    if args.json:
        print_json(out)
    else:
        print(_table(out))
    return 0 if sets else 1


def _table(out) -> str:
    rows = [f"planetary {out['scheme']}: i_1B = {out['ratio']:g} (tol {out['ratio_tol']:g}), "
            f"{out['planets']} planets, m = {out['module']:g} mm"]
    if not out["candidates"]:
        rows.append("  no set passes (widen --ratio-tol, raise --max-teeth, or try another scheme)")
    for i, c in enumerate(out["candidates"], 1):
        planet = c["planet"] if isinstance(c["planet"], int) else "/".join(str(z) for z in c["planet"])
        shifts = ", ".join(f"{k} {v:+.4f}" for k, v in c["shifts"].items() if v)
        rows.append(f"  {i}. sun {c['sun']}  planet {planet}  ring {c['ring']}  ratio {c['ratio']:.8g} "
                    f"({c['ratio_exact']})  a_w {c['center_distance']:.4f} mm" + (f"  shifts {shifts}" if shifts else ""))
        rows.append(f"     planets at " + ", ".join(f"{a:.4g}" for a in c["planet_angles_deg"]) + " deg; "
                    f"phasing {c['phasing']}; ring phases " + ", ".join(f"{a:.4g}" for a in c["ring_phase_deg"])
                    + f" deg; neighbour clearance {c['neighbour_clearance']:.4f} mm; checks {c['checks']}")
    return "\n".join(rows)
