"""``gearkit view``: a page to look at -- one self-contained HTML file of a pair or a cycloidal drive.

Usage::

    gearkit view pair --z1 18 --z2 41 -m 2 [the pair flags of 'gearkit check'] [--width B] -o pair.html
    gearkit view drive --pins 12 --lobes 11 --pin-circle-radius 90 --pin-radius 7 --eccentricity 4 -o drive.html

The page animates the 2D mesh (the contact simulation's poses, contact points, path of
contact, transmission error), shows the solids in 3D (rotate, zoom) and lists the design
check's findings; it opens offline in any browser. ``gearkit blocking ... -o page.html`` writes
the same page with the blocking map, ``gearkit cam ... -o cam.html`` the cam turning with its
follower. Exit status: 0 written, 2 bad input.
"""
from __future__ import annotations

import sys

from gearkit.cli.common import QUANTITIES, add_output_flag, add_pair_arguments, pair_spec_from_args
from gearkit.cli.design import add_design_argument, apply_flag_design, require_flags
from gearkit.errors import SpecError


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "view", help="write a page to look at (HTML, offline): the mesh animated, the solids, the check",
        description="Write one self-contained HTML page: the 2D mesh of a pair or cycloidal drive animated "
                    "(gears turning, contact points and path of contact moving, the transmission error "
                    "beside it), a 3D view of the solids (drag to rotate, wheel to zoom) and the design "
                    "check's findings. It needs no network to open.",
        epilog="Exit status: 0 written, 2 bad input.")
    sub = p.add_subparsers(dest="what", metavar="WHAT", required=True)

    pair = sub.add_parser("pair", help="an involute pair (the flags of 'gearkit check')")
    add_pair_arguments(pair)
    _common(pair)
    pair.set_defaults(run=run_pair)
    drive = sub.add_parser("drive", help="a cycloid-pin-wheel drive (the flags of 'gearkit cycloidal-drive')")
    add_design_argument(drive, "flags")
    drive.add_argument("--pins", type=int, help="Z_b, pins in the pin ring")
    drive.add_argument("--lobes", type=int, help="Z_g, disc lobes")
    drive.add_argument("--pin-circle-radius", type=float, help="R_Z, mm")
    drive.add_argument("--pin-radius", type=float, help="r_Z, mm")
    drive.add_argument("--eccentricity", type=float, help="e, mm")
    drive.add_argument("--equidistant-mod", type=float, default=0.0, help="dr, mm")
    drive.add_argument("--shift-mod", type=float, default=0.0, help="dR, mm")
    drive.add_argument("--width", type=QUANTITIES["width"], default=None, help="disc width of the solids, mm")
    _common(drive)
    drive.set_defaults(run=run_drive)


def _common(p) -> None:
    p.add_argument("--cycles", type=int, default=None, help="mesh cycles animated (default: one turn of the "
                   "pinion, or of the drive's crank)")
    add_output_flag(p, "the page, .html", required=True)


def _check_output(args) -> None:
    if not str(args.output).lower().endswith((".html", ".htm")):
        raise SpecError("--output", f"{args.output!r}: a page is written as .html")
    if args.cycles is not None and not 1 <= args.cycles <= 200:
        raise SpecError("--cycles", f"{args.cycles!r} must be in [1, 200]")


def run_pair(args) -> int:
    from gearkit.view import pair_view, write_page

    _check_output(args)
    spec, limits = pair_spec_from_args(args)
    write_page(args.output, pair_view(spec, limits, width=spec.face_width, cycles=args.cycles))
    print(f"wrote {args.output}")
    return 0


def run_drive(args) -> int:
    from gearkit.families.cycloidal import DriveSpec
    from gearkit.view import drive_view, write_page

    _check_output(args)
    from gearkit.cli.cycloid import DRIVE_REQUIRED

    apply_flag_design(args)
    require_flags(args, *DRIVE_REQUIRED)
    spec = DriveSpec(args.pins, args.lobes, args.pin_circle_radius, args.pin_radius, args.eccentricity,
                     args.equidistant_mod, args.shift_mod)
    write_page(args.output, drive_view(spec, width=args.width, cycles=args.cycles))
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    from gearkit.cli import main
    sys.exit(main(["view", *sys.argv[1:]]))
