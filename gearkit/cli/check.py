"""``gearkit check``: will this gear pair work? Findings with numbers, limits and reasons.

Usage::

    gearkit check --z1 18 --z2 41 -m 2 [--x1 0.3 --x2 -0.1 | --center-distance 60 [--split balanced]]
                  [--pressure-angle-deg 20] [--helix-angle-deg 15 --width 20]
                  [--internal --cutter-teeth 20] [--rack iso53a] [--json]
    gearkit check design.toml [--json]

Exit status: 0 when no finding fails, 1 when one fails, 2 for bad input.
"""
from __future__ import annotations

import json
import math
import sys

from gearkit.errors import SpecError

#: flags that describe the pair (not allowed together with a design file)
_MODEL_FLAGS = ("z1", "z2", "module", "x1", "x2", "center_distance", "split", "pressure_angle_deg",
                "helix_angle_deg", "width", "internal", "rack_pair", "cutter_teeth", "cutter_shift",
                "cutter_addendum", "pinion_cutter_teeth", "rack", "addendum", "tip", "da1", "da2",
                "thinning1", "thinning2", "min_tip_thickness", "min_contact_ratio", "min_tip_clearance",
                "ring_shift")

SIGN_NOTE = ("Shifts are normal coefficients x_n. A ring's --x2 is read as ISO 21771 says (--ring-shift iso, the "
             "default: by its tooth thickness, as if rack-cut; the shaper setting that cuts it is derived) or as "
             "the shaper's radial setting (--ring-shift cutter); positive --x2 makes the ring's teeth thinner and "
             "its tip (inner) diameter larger. An external shaper-cut gear's shift is the cutter's radial setting.")


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "check", help="check a gear pair: undercut, pointing, contact ratio, interference, jamming",
        description="Check an involute gear pair (lengths in mm, angles in degrees). " + SIGN_NOTE,
        epilog="Exit status: 0 no finding fails, 1 a finding fails, 2 bad input.")
    add_pair_arguments(p)
    out = p.add_argument_group("output")
    out.add_argument("--geometry", choices=("generated", "formula"), default="generated",
                     help="read form circles and undercut off the generated gears (default) or the formulas")
    out.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=run)


def add_pair_arguments(p, limits: bool = True) -> None:
    """The design-file argument and the pair, tool (and limit) flags every pair command shares."""
    p.add_argument("design", nargs="?", help="TOML design file (instead of the pair flags)")
    g = p.add_argument_group("pair")
    g.add_argument("--z1", type=int, help="pinion teeth")
    g.add_argument("--z2", type=int, help="wheel (or ring) teeth")
    g.add_argument("-m", "--module", type=float, help="normal module m_n, mm")
    g.add_argument("--x1", type=float, help="pinion normal shift coefficient x_n1 (default 0)")
    g.add_argument("--x2", type=float, help="wheel/ring normal shift coefficient x_n2 (default 0; ring: see above)")
    g.add_argument("--center-distance", type=float, help="operating centre distance a_w, mm (rack pair: pinion "
                   "axis to rack datum). Alone: the shifts are solved and split by --split; with --x1: x2 "
                   "follows; with --x1 and --x2: the pair runs at a_w (backlash)")
    g.add_argument("--split", choices=("x1", "equal", "balanced"), help="shift split for --center-distance "
                   "(default balanced: equal specific sliding at the roots)")
    g.add_argument("--pressure-angle-deg", type=float, help="normal pressure angle alpha_n, degrees (default 20)")
    g.add_argument("--helix-angle-deg", type=float, default=0.0, help="helix angle beta, degrees")
    g.add_argument("--width", type=float, help="face width b, mm (for the overlap ratio)")
    kind = g.add_mutually_exclusive_group()
    kind.add_argument("--internal", action="store_true", help="pinion inside a ring (needs --cutter-teeth)")
    kind.add_argument("--rack-pair", action="store_true", help="pinion and rack (no --z2)")
    g.add_argument("--addendum", type=float, default=1.0, help="addendum coefficient h_a* (default 1)")
    g.add_argument("--tip", choices=("shortened", "standard"), default="shortened",
                   help="tip diameters: keep the standard clearance (default) or d_a = d + 2 m_n (h_a* + x)")
    g.add_argument("--da1", type=float, help="given pinion tip diameter, mm")
    g.add_argument("--da2", type=float, help="given wheel/ring tip diameter, mm")
    g.add_argument("--thinning1", type=float, default=0.0, help="pinion normal tooth thinning for backlash, mm")
    g.add_argument("--thinning2", type=float, default=0.0, help="wheel normal tooth thinning for backlash, mm")
    t = p.add_argument_group("tools")
    t.add_argument("--rack", choices=("iso53a", "iso53b", "iso53c", "iso53d"),
                   help="ISO 53 basic rack of the rack-cut gears (default: h_aP* 1, h_fP* 1.25, largest fillet)")
    t.add_argument("--cutter-teeth", type=int, help="teeth z0 of the shaper cutter that cuts the ring")
    t.add_argument("--ring-shift", choices=("iso", "cutter"), default="iso",
                   help="how the ring's --x2 is read: 'iso' (ISO 21771, by the tooth thickness; default) or "
                        "'cutter' (the shaper's radial setting)")
    t.add_argument("--cutter-shift", type=float, default=0.0, help="the shaper's own shift x0")
    t.add_argument("--cutter-addendum", type=float, default=1.25, help="the shaper's addendum h_a0* (default 1.25)")
    t.add_argument("--pinion-cutter-teeth", type=int, help="cut the pinion with a shaper of this many teeth")
    if not limits:
        p.set_defaults(min_tip_thickness=None, min_contact_ratio=None, min_tip_clearance=None)
        return
    lim = p.add_argument_group("limits")
    lim.add_argument("--min-tip-thickness", type=float, help="warn below this s_an / m_n (default 0.25)")
    lim.add_argument("--min-contact-ratio", type=float, help="warn below this eps_alpha (default 1.2)")
    lim.add_argument("--min-tip-clearance", type=float, help="warn below this c / m_n (default 0.1)")


def pair_spec_from_args(args, allowed_with_design=()):
    """``(PairSpec, CheckLimits)`` from a design file or from the pair flags (not both: flags other
    than ``allowed_with_design`` next to a design file are a ``SpecError``)."""
    if args.design is not None:
        extra = [name for name in _MODEL_FLAGS
                 if hasattr(args, name) and name not in allowed_with_design and _given(args, name)]
        if extra:
            raise SpecError("design", "give either a design file or pair flags, not both "
                            f"(also got --{extra[0].replace('_', '-')})")
        from gearkit.checks import load_design
        return load_design(args.design)
    return _spec_from_flags(args)


def _given(args, name) -> bool:
    value = getattr(args, name)
    default = {"helix_angle_deg": 0.0, "addendum": 1.0, "tip": "shortened", "thinning1": 0.0, "thinning2": 0.0,
               "cutter_shift": 0.0, "cutter_addendum": 1.25, "internal": False, "rack_pair": False,
               "ring_shift": "iso"}.get(name)
    return value is not None and value != default


def _spec_from_flags(args):
    from gearkit.checks import CheckLimits
    from gearkit.pair import PairSpec
    from gearkit.families.involute import BasicRack, ShaperCutter

    kind = "internal" if args.internal else "rack" if args.rack_pair else "external"
    for name, flag in (("z1", "--z1"), ("module", "-m/--module")):
        if getattr(args, name) is None:
            raise SpecError(flag, "is required (or give a design file)")
    if kind == "rack":
        if args.z2 is not None:
            raise SpecError("--z2", "a rack pair has no z2")
    elif args.z2 is None:
        raise SpecError("--z2", "is required")
    alpha = args.pressure_angle_deg
    rack = BasicRack.iso53(args.rack[-1]) if args.rack else BasicRack(20.0 if alpha is None else alpha)
    tool1 = rack
    if args.pinion_cutter_teeth is not None:
        tool1 = ShaperCutter(args.pinion_cutter_teeth, rack.pressure_angle_deg, args.cutter_shift, args.cutter_addendum)
    tool2 = rack
    if kind == "internal":
        if args.cutter_teeth is None:
            raise SpecError("--cutter-teeth", "an internal gear is cut by a shaper: give its tooth number z0")
        tool2 = ShaperCutter(args.cutter_teeth, rack.pressure_angle_deg, args.cutter_shift, args.cutter_addendum)
    elif args.cutter_teeth is not None:
        raise SpecError("--cutter-teeth", "applies to internal pairs (use --pinion-cutter-teeth, or a design file)")
    spec = PairSpec(args.z1, args.z2, args.module, args.x1 or 0.0, args.x2 or 0.0, kind, alpha,
                    args.helix_angle_deg, args.width, tool1, tool2, args.addendum, args.tip, args.da1, args.da2,
                    None, args.thinning1, args.thinning2, args.ring_shift)
    spec = _apply_center_distance(spec, args.center_distance, args.x1, args.x2, args.split)
    limits = CheckLimits(**{k: getattr(args, k) for k in ("min_tip_thickness", "min_contact_ratio",
                                                           "min_tip_clearance") if getattr(args, k) is not None})
    return spec, limits


def _apply_center_distance(spec, a_w, x1, x2, split):
    """Resolve the shifts/centre-distance combinations (see ``--center-distance``)."""
    from dataclasses import replace

    from gearkit.pair import shifts_for_center_distance

    if a_w is None:
        if split is not None:
            raise SpecError("split", "applies only with a centre distance")
        return spec
    if x1 is not None and x2 is not None:
        if split is not None:
            raise SpecError("split", "both shifts are given: nothing to split")
        return replace(spec, center_distance=a_w)
    if x2 is not None:
        raise SpecError("x2", "with a centre distance give x1 (x2 follows), both shifts, or neither")
    if x1 is not None and split not in (None, "x1"):
        raise SpecError("split", f"x1 is given, so the split is 'x1', not {split!r}")
    rule = "x1" if x1 is not None else (split or "balanced")
    return shifts_for_center_distance(spec, a_w, rule)


def run(args) -> int:
    from gearkit.checks import check_pair

    spec, limits = pair_spec_from_args(args)
    result = check_pair(spec, limits, geometry=args.geometry)
    if args.json:
        print(json.dumps(result.to_dict(), indent=2, allow_nan=False))
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
