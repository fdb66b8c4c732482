"""``gearkit pair``: both gears of a pair as solids, placed and phased; export and 3D interference.

Usage::

    gearkit pair --z1 18 --z2 41 -m 2 [the pair flags of 'gearkit check'] --width 10
                 [--herringbone [--gap G]] [--bore1 8 --keyway1 3x1.4] [--rim R | --outer-diameter D]
                 [--angle-deg A] [--sweep N] [--tol T] [-o assembly.obj|glb|stl] [--json]
    gearkit pair design.toml --width 10 -o assembly.glb

The pair flags (and design files) are those of ``gearkit check``, taken from its parser.
Exit status: 0 the gears run free at every sampled rotation, 1 they interfere, 2 bad input.
"""
from __future__ import annotations

import math

from gearkit.cli.common import (add_json_flag, add_keyway_flag, add_output_flag, add_pair_arguments, add_tol_flag,
                                keyway_from_arg, pair_spec_from_args, print_json)
from gearkit.errors import SpecError

def register(subparsers) -> None:
    p = subparsers.add_parser(
        "pair", help="both gears of a pair as solids: export the assembly, measure 3D interference",
        description="Build both gears of an involute pair as solids at their centre distance, phased so a "
                    "tooth of one sits in the middle of a space of the other; write the assembly (OBJ with "
                    "named parts, GLB, or STL) and measure the interference volume of the two solids.",
        epilog="Exit status: 0 the gears run free at every sampled rotation, 1 they interfere, 2 bad input.")
    add_pair_arguments(p, limits=False)
    s = p.add_argument_group("solids")
    s.add_argument("--herringbone", action="store_true", help="double-helical gears (needs a helix angle)")
    s.add_argument("--gap", type=float, default=0.0, help="central gap of double-helical gears, mm")
    s.add_argument("--bore1", type=float, default=None, help="pinion bore diameter, mm")
    s.add_argument("--bore2", type=float, default=None, help="wheel bore diameter, mm")
    add_keyway_flag(s, "--keyway1", "pinion keyway width x depth, mm")
    add_keyway_flag(s, "--keyway2", "wheel keyway width x depth, mm")
    rim = s.add_mutually_exclusive_group()
    rim.add_argument("--outer-diameter", type=float, default=None, help="ring's outer diameter, mm")
    rim.add_argument("--rim", type=float, default=None, help="ring's rim thickness beyond its root, mm")
    s.add_argument("--rack-length", type=float, default=None, help="rack bar length, mm (default 2 d_a1)")
    s.add_argument("--rack-height", type=float, default=None, help="rack bar height, mm (tooth depth + 2 m)")
    add_tol_flag(s, "max deviation of any vertex or facet from the exact tooth surface, mm (default 0.005*m)")
    o = p.add_argument_group("output")
    o.add_argument("--angle-deg", type=float, default=0.0, help="pinion rotation for the export and the "
                   "interference, degrees")
    o.add_argument("--sweep", type=int, default=0, metavar="N",
                   help="also measure the interference at N rotations over one pinion pitch")
    add_output_flag(o, "write the assembly: .obj .glb .3mf .step (named parts) or .stl")
    o.add_argument("--ascii", action="store_true", help="ASCII STL instead of binary")
    add_json_flag(o)
    p.set_defaults(run=run)


def _pair_spec(args):
    return pair_spec_from_args(args)[0]


#: default limit of --sweep (each position is a boolean intersection of the two solids)
MAX_SWEEP = 1000


def run(args) -> int:
    if args.output:
        from gearkit.solids.export import mesh_format

        if mesh_format(args.output) is None:
            raise SpecError("output", f"{args.output!r}: the assembly is written as .obj, .glb, .3mf, .step or .stl")
    if args.sweep < 0:
        raise SpecError("--sweep", f"{args.sweep} must be >= 0")
    from gearkit.cli.shell import bound

    bound("--sweep", args.sweep, MAX_SWEEP, "rotations (each a 3D intersection)")
    spec = _pair_spec(args)
    from gearkit.solids.pair import pair_assembly

    width = args.width if args.width is not None else spec.face_width
    if width is None:
        raise SpecError("--width", "give the face width (mm) of the gears")
    asm = pair_assembly(spec, width, args.tol, herringbone=args.herringbone, gap=args.gap,
                        bores=(args.bore1, args.bore2), keyways=(keyway_from_arg(args.keyway1),
                                                                 keyway_from_arg(args.keyway2)),
                        outer_diameter=args.outer_diameter, rim=args.rim, rack_length=args.rack_length,
                        rack_height=args.rack_height)
    angle = math.radians(args.angle_deg)
    info = asm.summary()
    info["angle_deg"] = args.angle_deg
    info["interference"] = asm.interference(angle)
    worst = info["interference"]
    if args.sweep:
        pitch = 2.0 * math.pi / spec.teeth1
        angles = angle + pitch * (0.5 + __import__("numpy").arange(args.sweep)) / args.sweep
        vols = asm.sweep(angles)
        info["sweep"] = {"angles_deg": [math.degrees(a) for a in angles], "interference": vols.tolist()}
        worst = max(worst, float(vols.max()))
    if args.output:
        from gearkit.cli.shell import write_solids

        write_solids(args.output, asm.placed(angle), ascii=args.ascii)
        info["output"] = args.output
    if args.json:
        print_json(info)
    else:
        print(format_assembly(info, worst))
    return 0 if worst <= 0.0 else 1


def format_assembly(info: dict, worst: float) -> str:
    rows = [f"gearkit pair: {info['kind']} pair as solids, a = {info['center_distance']:.6f} mm"]
    for part in info["parts"]:
        rows.append(f"  {part['name']:<8} {part['kind']:<16} volume {part['volume']:14.3f} mm^3  faces "
                    f"{part['faces']:8d}  accuracy {part['achieved']:.3g} mm (requested {part['tol']:.3g})")
    rows.append(f"  interference at {info['angle_deg']:g} deg: {info['interference']:.6g} mm^3")
    if "sweep" in info:
        rows.append(f"  sweep over one pinion pitch ({len(info['sweep']['angles_deg'])} rotations): largest "
                    f"{max(info['sweep']['interference']):.6g} mm^3")
    rows.append("result: " + ("runs free" if worst <= 0.0 else "INTERFERES"))
    if "output" in info:
        rows.append(f"wrote {info['output']}")
    return "\n".join(rows)
