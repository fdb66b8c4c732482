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
from gearkit.errors import SpecError


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
    al = p.add_argument_group("allowances (ISO 21771; report the backlash range and the dimensions at them)")
    for n in (1, 2):
        al.add_argument(f"--allowance{n}", default=None, metavar="UPPER,LOWER",
                        help=f"gear {n}'s tooth thickness allowances A_sne,A_sni, mm (<= 0, e.g. -0.05,-0.11)")
    al.add_argument("--center-distance-tolerance", default=None, metavar="UPPER,LOWER",
                    help="centre-distance allowances A_ae,A_ai, mm (e.g. 0.03,-0.03)")
    p.set_defaults(run=run)


def _pair_of_floats(text, flag):
    """``"-0.05,-0.11"`` -> (-0.05, -0.11); None -> (0, 0)."""
    if text is None:
        return (0.0, 0.0)
    try:
        upper, lower = (float(v) for v in text.split(","))
    except ValueError:
        raise SpecError(flag, f"{text!r} must be UPPER,LOWER in mm, e.g. -0.05,-0.11") from None
    return (upper, lower)


def allowances_of(args):
    """The :class:`~gearkit.pair.allowances.Allowances` of the allowance flags; None when none is given."""
    flags = (args.allowance1, args.allowance2, args.center_distance_tolerance)
    if all(f is None for f in flags):
        return None
    from gearkit.pair.allowances import Allowances
    try:
        return Allowances(_pair_of_floats(args.allowance1, "--allowance1"),
                          _pair_of_floats(args.allowance2, "--allowance2"),
                          _pair_of_floats(args.center_distance_tolerance, "--center-distance-tolerance"))
    except SpecError as exc:
        name = {"gear1": "--allowance1", "gear2": "--allowance2"}.get(exc.field, "--center-distance-tolerance")
        raise SpecError(name, str(exc).split(": ", 1)[-1]) from None


def run(args) -> int:
    from gearkit.checks import check_pair

    spec, limits = pair_spec_from_args(args)
    allowances = allowances_of(args)
    result = check_pair(spec, limits, geometry=args.geometry)
    report = None
    if allowances is not None:
        from gearkit.pair.allowances import allowance_report
        report = allowance_report(spec, allowances)
    if args.json:
        data = result.to_dict()
        if report is not None:
            data["allowances"] = report
        print_json(data)
    else:
        print(format_report(result) + ("" if report is None else "\n" + format_allowances(report)))
    return 0 if result.ok else 1


def format_allowances(report: dict) -> str:
    """Table rows of the allowance report: backlash range, and per gear x_E, d_f, span and over pins."""
    b = report["backlash"]
    lines = [f"allowances: backlash j_wt {b['min']:.5f} .. {b['max']:.5f} mm (normal j_bn {b['normal_min']:.5f} .. "
             f"{b['normal_max']:.5f} mm)", "  gear  allowance       x_E       d_f    span W      pins M"]
    for i, gear in enumerate(report["gears"]):
        for side in ("upper", "lower"):
            g = gear[side]
            w = g.get("span", {}).get("W")
            lines.append(f"  {i + 1:<4}{g['allowance']:>11.4f}{_num(g['x_E'])}{_num(g['root_diameter'])}"
                         f"{_num(w, 10, 5)}{_num(g['over_pins']['M'], 12, 5)}  ({side})")
    return "\n".join(lines)


def _num(v, width=10, digits=4) -> str:
    from gearkit.export import text_number

    return text_number(v, f"{width}.{digits}f" if width else f".{digits}f")


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
        "  gear      z         x       d_a       d_f       d_F      s_an  undercut  tool",
    ]
    for i, gear in enumerate(g.gears):
        prof = result.profiles[i] if result.profiles else None
        under = prof.undercut if prof else gear.undercut
        d_f = prof.root_diameter if prof else gear.root_diameter
        lines.append(f"  {i + 1:<4}{gear.teeth:>5}{_num(gear.shift_coeff)}{_num(gear.tip_diameter)}{_num(d_f)}"
                     f"{_num(gear.form_diameter)}{_num(gear.tip_thickness_normal)}  {'yes' if under else 'no ':<8}  "
                     f"{gear.tool}")
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
