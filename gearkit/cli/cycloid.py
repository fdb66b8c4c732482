"""``gearkit cycloidal-drive`` and ``gearkit cycloid``: the cycloidal family from the command line.

Usage::

    gearkit cycloidal-drive --pins 12 --lobes 11 --pin-circle-radius 90 --pin-radius 7 --eccentricity 4
                            [--equidistant-mod 0.02] [--shift-mod 0] [--tip-radius R] [--json]
                            [-o disc.stl|disc.dxf|disc.svg|drive.obj]
    gearkit cycloid -m 1 --pinion-teeth 8 --wheel-teeth 64 [--clock | --rolling-radius A1 [A2]]
                    [--pin-radius RHO] [--json] [-o pair.svg|pair.obj|wheel.stl]

Exit status: 0 when no finding fails, 1 when one fails, 2 for bad input. One module registers
both commands.
"""
from __future__ import annotations

import math
import sys

from gearkit.cli.common import (QUANTITIES, add_json_flag, add_module_flag, add_output_flag, add_renamed_flag, add_tol_flag,
                                output_kind, print_json, tol_from)
from gearkit.cli.design import add_design_argument, apply_flag_design, require_flags
from gearkit.errors import SpecError

_SCALARS = (int, float, str, bool, type(None))
#: the flags a drive needs (from the command line or a design file)
DRIVE_REQUIRED = (("pins", "--pins"), ("lobes", "--lobes"), ("pin_circle_radius", "--pin-circle-radius"),
                  ("pin_radius", "--pin-radius"), ("eccentricity", "--eccentricity"))


def register(subparsers) -> None:
    d = subparsers.add_parser(
        "cycloidal-drive", help="cycloid-pin-wheel planetary drive: generate the disc, check and export it",
        description="Generate the cycloid disc (or ring, when --lobes > --pins) of a pin-wheel drive as the "
                    "envelope of its pins, simulate its mesh and check it (lengths in mm).",
        epilog="Exit status: 0 no finding fails, 1 a finding fails, 2 bad input.")
    add_design_argument(d, "flags")
    d.add_argument("--pins", type=int, help="Z_b, pins in the pin ring")
    d.add_argument("--lobes", type=int, help="Z_g, disc teeth (lobes); Z_b - Z_g is the tooth "
                   "difference (negative: a cycloid ring outside the pins)")
    d.add_argument("--pin-circle-radius", type=float, help="R_Z, radius of the pin-centre circle, mm")
    d.add_argument("--pin-radius", type=float, help="r_Z, pin radius, mm")
    d.add_argument("--eccentricity", type=float, help="e, crank eccentricity, mm")
    d.add_argument("--equidistant-mod", type=float, default=0.0, help="dr: grind with pins of radius r_Z + dr, mm")
    d.add_argument("--shift-mod", type=float, default=0.0, help="dR: grind on the pin circle R_Z + dR, mm")
    d.add_argument("--disc-eccentricity", type=float, default=None,
                   help="e' the disc was generated with (default e; the correct-meshing condition is e' = e)")
    d.add_argument("--tip-radius", type=float, default=None, help="truncate the disc's teeth at this radius, mm")
    d.add_argument("--samples", type=int, default=2000, help="instants of the simulated mesh (default 2000)")
    _output_flags(d)
    d.add_argument("--output-pins", type=int, default=6, help="output pins / disc holes (default 6; 0: none)")
    d.set_defaults(run=run_drive)

    c = subparsers.add_parser(
        "cycloid", help="cycloid gear pair, clock gearing or pin (lantern) gearing",
        description="Generate a cycloid gear pair with its cycloidal racks (epicycloidal addenda, "
                    "hypocycloidal dedenda), clock gearing (--clock: radial pinion flanks), or pin gearing "
                    "(--pin-radius RHO: the pinion is a pin wheel and the wheel is cut by its pins); check it.",
        epilog="Exit status: 0 no finding fails, 1 a finding fails, 2 bad input.")
    add_design_argument(c, "flags")
    add_module_flag(c, "module, mm (required)")
    c.add_argument("--pinion-teeth", type=QUANTITIES["teeth"], help="z1 (pins of the pin wheel with --pin-radius)")
    c.add_argument("--wheel-teeth", type=QUANTITIES["teeth"], help="z2")
    kind = c.add_mutually_exclusive_group()
    kind.add_argument("--clock", action="store_true", help="clock gearing (BS 978-2 style): generating circles "
                      "r1/2 and r2/2, wheel addendum 0.95 A")
    kind.add_argument("--rolling-radius", type=float, nargs="+", metavar="A",
                      help="generating circle radii a1 [a2], mm (default 0.375 of each pitch radius)")
    kind.add_argument("--pin-radius", type=float, metavar="RHO", help="pin gearing: the pinion is a pin wheel of "
                      "pins of radius RHO mm on its pitch circle (as r_Z of cycloidal-drive)")
    add_renamed_flag(kind, "--pins", "--pin-radius", "pin_radius", type=float, metavar="RHO")
    c.add_argument("--addendum", type=float, nargs="+", metavar="HA",
                   help="addendum coefficients h_a1* [h_a2*] (module units; pin gearing: the wheel's)")
    c.add_argument("--dedendum", type=float, default=None, help="dedendum coefficient h_f* (default 1.25)")
    _output_flags(c)
    c.set_defaults(run=run_cycloid)


def _output_flags(p) -> None:
    add_tol_flag(p, "accuracy of exported points/facets, mm")
    p.add_argument("--width", type=QUANTITIES["width"], default=None, help="face width of solids, mm")
    add_output_flag(p, "write: .svg .dxf .csv .json (2D outlines) or .stl .obj .glb .3mf .step (solids)")
    add_json_flag(p)


def _num(v, digits=6):
    from gearkit.export import text_number

    if isinstance(v, float) or v is None:
        return text_number(v, f".{digits}g")
    return str(v)


def _format(title: str, values: dict, report) -> str:
    lines = [title]
    for k, v in values.items():
        if isinstance(v, _SCALARS) and k not in ("ok", "status"):
            lines.append(f"  {k:<30}{_num(v)}")
    from gearkit.checks.report import format_findings

    lines += [""] + format_findings(report, 22)
    return "\n".join(lines)


def _tol(args, scale, default_factor):
    return tol_from(args.tol, default_factor * scale)


def run_drive(args) -> int:
    from gearkit.checks.cycloidal import check_drive
    from gearkit.families.cycloidal import DriveSpec

    apply_flag_design(args)
    require_flags(args, *DRIVE_REQUIRED)
    fmt = output_kind(args.output)
    spec = DriveSpec(args.pins, args.lobes, args.pin_circle_radius, args.pin_radius, args.eccentricity,
                     args.equidistant_mod, args.shift_mod, args.disc_eccentricity, args.tip_radius)
    if not 1 <= args.samples <= 100000:
        raise SpecError("--samples", f"{args.samples!r} must be in [1, 100000]")
    result = check_drive(spec, samples=args.samples)
    out = result.to_dict()
    if fmt is not None:
        out["output"] = _write_drive(args, spec, fmt)
    if args.json:
        print_json(out)
    else:
        kind = "disc" if spec.sign > 0 else "ring"
        title = (f"gearkit cycloidal-drive: {kind}, Z_b = {spec.pins} pins, Z_g = {spec.lobes}, dz = "
                 f"{spec.tooth_difference:+d}, R_Z = {spec.pin_circle_radius:g}, r_Z = {spec.pin_radius:g}, "
                 f"e = {spec.eccentricity:g} mm")
        text = _format(title, result.values, result.report)
        if "pins_in_contact" in result.values and result.values.get("backlash_rad", 1.0) == 0.0:
            loaded = result.values["load_carrying_pins"]
            text += (f"\npins in contact: {result.values['pins_in_contact']:.4g} "
                     f"({loaded:.4g} load-carrying per direction)")
        print(text + (f"\nwrote {out['output']['path']}" if "output" in out else ""))
    return 0 if result.report.ok else 1


def _write_drive(args, spec, fmt) -> dict:
    from gearkit.families.cycloidal.assembly import OutputMechanism, drive_loops

    output = OutputMechanism(count=args.output_pins)
    if fmt == "2d":
        from gearkit.export import write_profile

        tol = _tol(args, spec.eccentricity, 1e-4)
        loops = drive_loops(spec, tol, output)
        write_profile(args.output, loops, {"family": "cycloidal disc", "pins": spec.pins, "lobes": spec.lobes})
        return {"path": args.output, "loops": len(loops), "tol": tol}
    from gearkit.solids.drive import disc_solid, drive_parts
    from gearkit.cli.shell import write_solids
    from gearkit.solids.export import mesh_format

    tol = _tol(args, spec.eccentricity, 5e-3)
    width = args.width if args.width is not None else max(2.0 * spec.pin_radius, 0.1 * spec.pin_circle_radius)
    if mesh_format(args.output) == "stl":
        parts = [disc_solid(spec, width, tol, output)]
    else:
        parts = drive_parts(spec, width, tol, output)
    write_solids(args.output, parts)
    return {"path": args.output, "parts": [p.name for p in parts], "tol": tol, "width": width,
            "volumes": {p.name: p.volume for p in parts}}


def _pair_spec(args):
    from gearkit.families.cycloidal import CycloidPairSpec

    a = args.rolling_radius or []
    ha = args.addendum or []
    if len(a) > 2 or len(ha) > 2:
        raise SpecError("--rolling-radius" if len(a) > 2 else "--addendum", "takes one or two values")
    a1 = a[0] if a else None
    a2 = a[1] if len(a) > 1 else (a1 if a else None)
    h1 = ha[0] if ha else None
    h2 = ha[1] if len(ha) > 1 else h1
    return CycloidPairSpec(args.module, args.pinion_teeth, args.wheel_teeth, a1, a2, h1, h2, args.dedendum,
                           clock=args.clock)


def run_cycloid(args) -> int:
    apply_flag_design(args)
    require_flags(args, ("module", "-m/--module"), ("pinion_teeth", "--pinion-teeth"), ("wheel_teeth", "--wheel-teeth"))
    fmt = output_kind(args.output)
    if args.pin_radius is not None:
        from gearkit.checks.cycloidal import check_pin_gearing
        from gearkit.families.cycloidal import PinGearSpec

        if args.dedendum is not None:
            raise SpecError("--dedendum", "pin gearing: the space bottom is the pin itself")
        ha = args.addendum or [1.0]
        if len(ha) != 1:
            raise SpecError("--addendum", "pin gearing takes one value (the wheel's)")
        spec = PinGearSpec(args.module, args.pinion_teeth, args.wheel_teeth, args.pin_radius, ha[0])
        result = check_pin_gearing(spec)
        title = (f"gearkit cycloid: pin gearing, {spec.pins} pins of radius {spec.pin_radius:g} mm, wheel "
                 f"z2 = {spec.wheel_teeth}, m = {spec.module:g} mm")
    else:
        from gearkit.checks.cycloidal import check_cycloid_pair

        spec = _pair_spec(args)
        result = check_cycloid_pair(spec)
        kind = "clock gearing" if spec.clock else "cycloid pair"
        title = (f"gearkit cycloid: {kind}, z1 = {spec.pinion_teeth}, z2 = {spec.wheel_teeth}, m = {spec.module:g} mm, "
                 f"a1 = {spec.rolling(1):g}, a2 = {spec.rolling(2):g} mm")
    out = result.to_dict()
    if fmt is not None:
        out["output"] = _write_pair(args, spec, fmt)
    if args.json:
        print_json(out)
    else:
        print(_format(title, result.values, result.report) + (f"\nwrote {out['output']['path']}" if "output" in out
                                                            else ""))
    return 0 if result.report.ok else 1


def _write_pair(args, spec, fmt) -> dict:
    """Both members in mesh: the wheel at the origin, the pinion (or pin wheel) above it."""
    import numpy as np

    from gearkit.families.cycloidal import PinGearSpec, cycloid_gear, pin_gear_wheel
    from gearkit.families.cycloidal.lantern import pin_wheel_outline

    pins = isinstance(spec, PinGearSpec)
    a = spec.center_distance
    wheel = pin_gear_wheel(spec) if pins else cycloid_gear(spec, 2)
    pinion = None if pins else cycloid_gear(spec, 1)
    z1 = spec.pins if pins else spec.pinion_teeth
    turn = math.pi + math.pi / z1  # the pinion presents a space to the wheel's tooth 0
    if fmt == "2d":
        from gearkit.export import write_profile

        tol = _tol(args, spec.module, 1e-3)
        loops = [wheel.outline(tol)]
        if pins:
            loops += [p + np.array([0.0, a]) for p in pin_wheel_outline(spec, tol, angle=math.pi + math.pi / z1)]
        else:
            c, s = math.cos(turn), math.sin(turn)
            loops.append(pinion.outline(tol) @ np.array([[c, s], [-s, c]]) + np.array([0.0, a]))
        write_profile(args.output, loops, {"family": wheel.family, "center_distance": a})
        return {"path": args.output, "loops": len(loops), "tol": tol}
    from gearkit.solids.drive import cylinders
    from gearkit.cli.shell import write_solids
    from gearkit.solids import SolidSpec, gear_solid

    tol = _tol(args, spec.module, 1e-2)
    width = args.width if args.width is not None else 5.0 * spec.module
    parts = [gear_solid(wheel, SolidSpec(width=width), tol, name="wheel")]
    if pins:
        centres = [a * np.array([0.0, 1.0]) + spec.r1 * np.array([math.sin(b), -math.cos(b)])
                   for b in (-math.pi / z1 + 2 * math.pi * np.arange(z1) / z1)]
        parts.append(cylinders(centres, spec.pin_radius, 0.0, width, tol, "pins"))
    else:
        parts.append(gear_solid(pinion, SolidSpec(width=width), tol, name="pinion").placed(turn, (0.0, a, 0.0)))
    write_solids(args.output, parts)
    return {"path": args.output, "parts": [p.name for p in parts], "tol": tol, "width": width}


if __name__ == "__main__":  # pragma: no cover
    from gearkit.cli import main
    sys.exit(main(["cycloidal-drive", *sys.argv[1:]]))
