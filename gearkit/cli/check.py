"""``gearkit check``: will this gear pair work? Findings with numbers, limits and reasons.

Usage::

    gearkit check --z1 18 --z2 41 -m 2 [--x1 0.3 --x2 -0.1 | --center-distance 60 [--split balanced]]
                  [--pressure-angle-deg 20] [--helix-angle-deg 15 --width 20]
                  [--internal --cutter-teeth 20] [--rack iso53a] [--json]
    gearkit check design.toml [--json]

Exit status: 0 when no finding fails, 1 when one fails, 2 for bad input.
"""
from __future__ import annotations

import math
import sys

from gearkit.cli.common import SIGN_NOTE, add_json_flag, add_pair_arguments, pair_spec_from_args, print_json


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "check", help="check a gear pair: undercut, pointing, contact ratio, interference, jamming",
        description="Check an involute gear pair (lengths in mm, angles in degrees). " + SIGN_NOTE,
        epilog="Exit status: 0 no finding fails, 1 a finding fails, 2 bad input.")
    add_pair_arguments(p)
    out = p.add_argument_group("output")
    out.add_argument("--geometry", choices=("generated", "formula"), default="generated",
                     help="read form circles and undercut off the generated gears (default) or the formulas")
    add_json_flag(out)
    p.set_defaults(run=run)


def run(args) -> int:
    from gearkit.checks import check_pair

    spec, limits = pair_spec_from_args(args)
    result = check_pair(spec, limits, geometry=args.geometry)
    if args.json:
        print_json(result.to_dict())
    else:
        print(format_report(result))
    return 0 if result.ok else 1


def _num(v, width=10, digits=4) -> str:
    if v is None:
        return "-".rjust(width)
    if isinstance(v, float) and math.isinf(v):
        return ("inf" if v > 0 else "-inf").rjust(width)
    v = 0.0 if abs(v) < 0.5 * 10.0 ** -digits else v  # no "-0.0000"
    return f"{v:{width}.{digits}f}"


def format_report(result) -> str:
    """The compact human table of ``gearkit check``: pair summary, gears, findings (failures marked)."""
    g = result.geometry
    s = g.spec
    z2 = "rack" if g.kind == "rack" else f"z2 = {s.teeth2}"
    lines = [
        f"gearkit check: {g.kind} pair, z1 = {s.teeth1}, {z2}, m_n = {g.module:g} mm, "
        f"alpha_n = {math.degrees(g.pressure_angle):g} deg, beta = {math.degrees(g.helix_angle):g} deg "
        f"({'generated' if result.profiles else 'formula'} geometry)",
        f"  a_w {g.center_distance:.4f} mm (a {g.reference_center_distance:.4f})   alpha_wt "
        f"{math.degrees(g.working_pressure_angle):.4f} deg   y {g.center_distance_modification_coeff:.4f}   "
        f"dy {g.tip_shortening_coeff:.4f}   x_sum {g.sum_shift_coeff:.4f}",
        f"  eps_alpha {g.contact_ratio:.4f} (tip-to-tip {g.contact_ratio_nominal:.4f})   eps_beta "
        f"{g.overlap_ratio:.4f}   eps_gamma {g.total_contact_ratio:.4f}   backlash {_num(g.backlash, 0)} mm",
        "",
        "  gear      z         x       d_a       d_f       d_F      s_an  undercut",
    ]
    for i, gear in enumerate(g.gears):
        prof = result.profiles[i] if result.profiles else None
        under = prof.undercut if prof else gear.undercut
        d_f = prof.root_diameter if prof else gear.root_diameter
        lines.append(f"  {i + 1:<4}{gear.teeth:>5}{_num(gear.shift_coeff)}{_num(gear.tip_diameter)}{_num(d_f)}"
                     f"{_num(gear.form_diameter)}{_num(gear.tip_thickness_normal)}  {'yes' if under else 'no'}")
    if g.kind == "internal":
        ring = g.gears[1]
        lines.append(f"  ring shift x2 read as {'ISO 21771 (by the tooth thickness)' if ring.shift_convention == 'iso' else 'the shaper setting'}"
                     f"; shaper setting {ring.cutter_setting:.6f}")
    from gearkit.checks.report import format_findings

    lines += [""] + format_findings(result.report, 22)
    return "\n".join(lines)


if __name__ == "__main__":  # pragma: no cover
    from gearkit.cli import main
    sys.exit(main(["check", *sys.argv[1:]]))
