"""``gearkit cam``: generate a disc cam as the envelope of its follower, check it, export it.

Usage::

    gearkit cam --prime-radius R0 --roller-radius RR [--offset E] --law cycloidal --rise H --rise-deg B1
                [--dwell-deg D1] --return-deg B2 [--return-law LAW] [--friction MU | --efficiency ETA]
                [--contact roller|knife|flat] [--rocker --pivot-distance L0 --arm-length L] [--groove]
                [--limit-deg A] [--tol T] [--json] [-o cam.svg|cam.dxf|cam.csv|cam.json|cam.stl|cam.obj|cam.glb]
                [--width B --bore D [--keyway WxD]] [--plot cam.png]
    gearkit cam cam.toml [flags that override the file] [--json] [-o FILE] [--plot FILE]

Exit status: 0 when no finding fails, 1 when one fails, 2 for bad input (one line naming the flag).
"""
from __future__ import annotations

import sys

from gearkit.cli.common import (QUANTITIES, add_json_flag, add_keyway_flag, add_output_flag, add_renamed_flag, add_tol_flag,
                                keyway_from_arg, output_kind, print_json, tol_from)
from gearkit.cli.design import add_design_argument, given
from gearkit.errors import SpecError

#: spec fields as the flags that set them, for error lines a user can act on
_FLAGS = {"prime_radius": "--prime-radius", "roller_radius": "--roller-radius", "offset": "--offset",
          "pivot_distance": "--pivot-distance", "arm_length": "--arm-length", "efficiency": "--efficiency",
          "friction": "--friction", "pressure_angle_limit_deg": "--limit-deg", "rise": "--rise",
          "return": "--rise", "rise_deg": "--rise-deg", "return_deg": "--return-deg", "dwell_deg": "--dwell-deg",
          "motion": "--rise-deg", "law": "--law", "contact": "--contact", "width": "--width", "bore": "--bore",
          "keyway": "--keyway", "tol": "--tol"}
#: flag destination -> the CamSpec field it overrides in a design file
_SPEC_FIELDS = {"prime_radius": "prime_radius", "contact": "contact", "roller_radius": "roller_radius",
                "offset": "offset", "pivot_distance": "pivot_distance", "arm_length": "arm_length",
                "efficiency": "efficiency", "friction": "friction", "limit_deg": "pressure_angle_limit_deg",
                "groove": "groove"}
#: the flags of the motion program: any of them typed replaces a design file's [[motion]] program
_MOTION_FLAGS = ("law", "return_law", "rise", "rise_deg", "dwell_deg", "return_deg")


def register(subparsers) -> None:
    from gearkit.families.cam.laws import LAWS

    p = subparsers.add_parser(
        "cam", help="disc cam: generate the profile as the envelope of the follower, check it, export it",
        description="Generate a disc cam as the envelope of its follower (translating or rocker; roller, knife "
                    "or flat face) moving by the motion law, on the same kernel as the gears; report pressure "
                    "angles with and without friction, the smallest prime radius, undercut and curvature; export "
                    "the profile (2D), the solid or a picture. Lengths in mm, angles in degrees; the cam turns "
                    "counter-clockwise.",
        epilog="Exit status: 0 no finding fails, 1 a finding fails, 2 bad input.")
    add_design_argument(p, "cam")
    # the old spelling; a destination of its own (the empty first argument would overwrite it)
    add_renamed_flag(p, "--design", "the design file as the first argument (gearkit cam FILE)", "design_option",
                     metavar="FILE")
    p.add_argument("--prime-radius", type=float, default=None, help="r0: smallest radius of the pitch curve (the "
                   "roller centre's path; base circle of a flat face), mm")
    p.add_argument("--contact", choices=("roller", "knife", "flat"), default="roller", help="follower end "
                   "(default roller)")
    p.add_argument("--roller-radius", type=float, default=None, help="R_p, roller radius, mm")
    p.add_argument("--offset", type=float, default=0.0, help="e: offset of a translating follower's line, mm "
                   "(positive lowers the rise's pressure angle)")
    p.add_argument("--rocker", action="store_true", help="oscillating follower (needs --pivot-distance and "
                   "--arm-length; the lift is the roller centre's arc)")
    p.add_argument("--pivot-distance", type=float, default=None, help="l0: cam axis to rocker pivot, mm")
    p.add_argument("--arm-length", type=float, default=None, help="l: rocker arm, pivot to roller centre, mm")
    p.add_argument("--law", choices=LAWS[:-1], default="cycloidal", help="motion law of the rise (and the "
                   "return unless --return-law; default cycloidal)")
    p.add_argument("--return-law", choices=LAWS[:-1], default=None, help="motion law of the return")
    p.add_argument("--rise", type=float, default=None, help="H: stroke, mm")
    p.add_argument("--rise-deg", type=float, default=None, help="cam angle of the rise, degrees")
    p.add_argument("--dwell-deg", type=float, default=0.0, help="far dwell, degrees (the near dwell closes the "
                   "turn)")
    p.add_argument("--return-deg", type=float, default=None, help="cam angle of the return, degrees")
    fr = p.add_mutually_exclusive_group()
    fr.add_argument("--friction", type=float, default=None, metavar="MU", help="friction coefficient in the "
                    "roller joint: the friction angle atan(MU) adds to the pressure angle (textbook model)")
    fr.add_argument("--efficiency", type=float, default=None, metavar="ETA", help="efficiency of the "
                    "roller-cam couple: tg theta uses s'/ETA (power-balance model)")
    p.add_argument("--limit-deg", type=float, default=None, help="allowed pressure angle, degrees (default 30 "
                   "translating, 45 rocker)")
    p.add_argument("--groove", action="store_true", help="grooved (form-closed) cam: the return is driven too")
    add_tol_flag(p, "max deviation of the output from the exact profile, mm (default 1e-4 of r0 + stroke)")
    add_json_flag(p)
    add_output_flag(p, "write the profile (.svg .dxf .csv .json), the solid (.stl .obj .glb .3mf, exact .step; needs "
                    "--width) or a page (.html: the cam turning, its follower, solids and check)")
    p.add_argument("--plot", default=None, metavar="FILE", help="picture: s-v-a-j, pressure angle with and "
                   "without friction, the cam (.png or .svg)")
    g = p.add_argument_group("solid (mesh output)")
    g.add_argument("--width", type=QUANTITIES["width"], default=None, help="cam width, mm")
    g.add_argument("--bore", type=float, default=None, help="bore diameter, mm")
    add_keyway_flag(g)
    g.add_argument("--ascii", action="store_true", help="ASCII STL instead of binary")
    p.set_defaults(run=run)


def _as_flag(exc: SpecError) -> SpecError:
    """The same error naming the flag a user types."""
    return exc.renamed(_FLAGS.get(exc.field, exc.field))


def spec_from_args(args):
    """The :class:`~gearkit.families.cam.CamSpec` the flags (or ``--design``) describe."""
    from gearkit.families.cam import CamSpec, MotionProgram

    if getattr(args, "design_option", None) is not None:
        if args.design is not None:
            raise SpecError("--design", "give the design file once (as the first argument)")
        args.design = args.design_option
    if args.design is not None:
        return _design_with_flags(args)
    for flag, value in (("--prime-radius", args.prime_radius), ("--rise", args.rise), ("--rise-deg", args.rise_deg),
                        ("--return-deg", args.return_deg)):
        if value is None:
            raise SpecError(flag, "required (or give a design file)")
    if args.contact == "roller" and args.roller_radius is None:
        raise SpecError("--roller-radius", "a roller follower needs its radius (or --contact knife|flat)")
    rocker = args.rocker or args.pivot_distance is not None or args.arm_length is not None
    try:
        motion = MotionProgram.rise_dwell_return(args.rise, args.rise_deg, args.dwell_deg, args.return_deg,
                                                 args.law, args.return_law)
        return CamSpec(args.prime_radius, motion, "rocker" if rocker else "translating", args.contact,
                       args.roller_radius or 0.0, args.offset, args.pivot_distance, args.arm_length,
                       1.0 if args.efficiency is None else args.efficiency,
                       0.0 if args.friction is None else args.friction, args.limit_deg, args.groove)
    except SpecError as exc:
        raise _as_flag(exc) from None


def _design_with_flags(args):
    """The design file's cam with the flags typed applied (a motion flag: the flags' motion program)."""
    from dataclasses import replace

    from gearkit.families.cam import MotionProgram
    from gearkit.families.cam.design import load_cam_design

    spec = load_cam_design(args.design)
    changes = {field: getattr(args, dest) for dest, field in _SPEC_FIELDS.items() if given(args, dest)}
    if given(args, "rocker") or given(args, "pivot_distance") or given(args, "arm_length"):
        changes["follower"] = "rocker"
    try:
        if any(given(args, dest) for dest in _MOTION_FLAGS):
            for flag, value in (("--rise", args.rise), ("--rise-deg", args.rise_deg), ("--return-deg", args.return_deg)):
                if value is None:
                    raise SpecError(flag, "required with the other motion flags (they replace the file's motion)")
            changes["motion"] = MotionProgram.rise_dwell_return(args.rise, args.rise_deg, args.dwell_deg,
                                                                args.return_deg, args.law, args.return_law)
        if given(args, "efficiency"):
            changes["friction"] = 0.0  # --friction and --efficiency exclude each other, as on the command line
        elif given(args, "friction"):
            changes["efficiency"] = 1.0
        return replace(spec, **changes) if changes else spec
    except SpecError as exc:
        raise _as_flag(exc) from None


def _output_kind(path):
    """'page' (.html), '2d', 'mesh' or None for ``-o``; an unknown extension is rejected before any work."""
    if path and str(path).lower().endswith((".html", ".htm")):
        return "page"
    return output_kind(path)


def _write(args, prof, tol, kind) -> dict:
    if kind == "page":
        from gearkit.view import write_page
        from gearkit.view.cam import cam_view

        write_page(args.output, cam_view(prof.spec))
        return {"path": args.output}
    if kind == "2d":
        from gearkit.export import write_profile

        write_profile(args.output, [prof.outline(tol)], {"family": "cam", "tol": tol})
        return {"path": args.output, "tol": tol, "points": int(len(prof.outline(tol)))}
    from gearkit.solids import SolidSpec
    from gearkit.solids.cam import cam_solid
    from gearkit.cli.shell import write_solids

    if args.width is None:
        raise SpecError("--width", "a mesh output needs the cam width (--width, mm)")
    try:
        solid = cam_solid(prof, SolidSpec(args.width, bore=args.bore, keyway=keyway_from_arg(args.keyway)), tol)
    except SpecError as exc:
        raise _as_flag(exc) from None
    write_solids(args.output, [solid], ascii=args.ascii)
    return {"path": args.output, "tol": tol, "width": args.width, "volume": solid.volume}


def run(args) -> int:
    from gearkit.checks.cam import check_cam
    from gearkit.families.cam import cam_profile

    kind = _output_kind(args.output)
    if args.plot is not None and not str(args.plot).lower().endswith((".png", ".svg")):
        raise SpecError("--plot", f"{args.plot!r}: the file name must end in .png or .svg")
    if kind != "mesh":
        for flag, value in (("--width", args.width), ("--bore", args.bore), ("--keyway", args.keyway)):
            if value is not None:
                raise SpecError(flag, "applies to a mesh output only (-o .stl .obj .glb)")
    spec = spec_from_args(args)
    try:
        result = check_cam(spec, tol_from(args.tol, None))
    except SpecError as exc:  # a tol below the cam's floor is found by the profile: named as the flag
        raise _as_flag(exc) from None
    tol = result.values["tolerance"]["requested"]
    out = result.to_dict()
    prof = cam_profile(spec)
    if kind is not None:
        out["output"] = _write(args, prof, tol, kind)
    if args.plot is not None:
        from gearkit.families.cam.plot import save

        save(prof, args.plot, tol)
        out["plot"] = args.plot
    if args.json:
        print_json(out)
    else:
        print(format_summary(spec, result, out))
    return 0 if result.report.ok else 1


def format_summary(spec, result, out) -> str:
    """The plain-text report: key values, then the findings table."""
    from gearkit.checks.report import format_findings
    from gearkit.export import text_number

    v = result.values
    follower = f"{spec.follower} {spec.contact}" + (f" R_p = {spec.roller_radius:g} mm" if spec.roller_radius else "")
    lines = [f"gearkit cam: {follower}, r0 = {spec.prime_radius:g} mm, stroke {spec.stroke:g} mm"
             + (f", offset {spec.offset:g} mm" if spec.offset else "")]
    pa = v["pressure_angle_max_deg"]
    lines.append(f"  pressure angle max, deg       rise {pa['rise']:.4f}   return {pa['return']:.4f}"
                 f"   (limit {v['pressure_angle_limit_deg']:g})")
    if "pressure_angle_friction_max_deg" in v:
        pf = v["pressure_angle_friction_max_deg"]
        lines.append(f"  with friction, deg            rise {pf['rise']:.4f}   return {pf['return']:.4f}")
    if v.get("prime_radius_min") is not None:
        lines.append(f"  smallest prime radius, mm     {v['prime_radius_min']:.4f}"
                     + (f"   with friction {v['prime_radius_min_friction']:.4f}"
                        if "prime_radius_min_friction" in v else ""))
    back = v.get("curvature_unbounded_deg")
    rho = "unbounded below (the face turns back at " + ", ".join(f"{x:.6g}" for x in back) + " deg)" if back \
        else text_number(v["min_curvature_radius"], ".6g", "none")
    lines.append(f"  min radius of curvature, mm   {rho}   undercut: {'yes' if v['undercut'] else 'no'}")
    lines.append(f"  profile radii, mm             {v['base_radius']:.6g} .. {v['max_radius']:.6g}")
    t = v["tolerance"]
    lines.append(f"  tolerance, mm                 requested {t['requested']:.3g}, achieved {t['achieved']:.3g} "
                 f"({v['vertices']} points)")
    lines += [""] + format_findings(result.report, 26)
    if "output" in out:
        lines.append(f"wrote {out['output']['path']}")
    if "plot" in out:
        lines.append(f"wrote {out['plot']}")
    return "\n".join(lines)


if __name__ == "__main__":  # pragma: no cover
    from gearkit.cli import main
    sys.exit(main(["cam", *sys.argv[1:]]))
