"""``gearkit blocking``: the blocking contour of a pair -- admissible shifts, lines, recommendation.

Usage::

    gearkit blocking --z1 13 --z2 16 [--rack iso53a] [--helix-angle-deg 0] [--tol 1e-4]
                     [--internal --cutter-teeth 20] [--mark 0.5,0.3] [-o contour.png|.svg|.json|page.html] [--json]

Exit status: 0 (1 when ``--mark`` is outside the region), 2 for bad input.
"""
from __future__ import annotations

import argparse
import math
import sys

from gearkit.cli.common import (QUANTITIES, add_json_flag, add_module_flag, add_output_flag, add_rack_flag, add_tol_flag, print_json,
                                rack_from_args, refuse_unused_cutter_flags, shaper_from_args)
from gearkit.cli.design import add_design_argument, require_flags
from gearkit.errors import SpecError


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "blocking", help="blocking contour: the map of admissible profile shifts (x1, x2) of a pair",
        description="Trace the blocking contour of an involute pair: the lines where the design check starts "
                    "to fail (interference B1/B2, eps_alpha = 1 B3, pointed tips B4/B5, internal jamming and "
                    "trimming B6) and quality lines inside; shade the admissible region; recommend shifts. "
                    "Shifts are normal coefficients x_n. Internal pairs (--internal): x2 > 0 moves the ring's teeth "
                    "outward (thinner ring teeth, larger tip (inner) diameter), and the ring's x2 is read as "
                    "'gearkit check' reads it by default (ISO 21771, by its tooth thickness; the shaper "
                    "setting that cuts it is derived); an external shaper-cut pinion's x1 is the cutter's "
                    "radial setting.",
        epilog="Exit status: 0 ok, 1 the --mark point is outside the region, 2 bad input.")
    g = p.add_argument_group("pair")
    add_design_argument(p, "pair")
    g.add_argument("--z1", type=QUANTITIES["teeth"], help="pinion teeth (required unless a design file gives them)")
    g.add_argument("--z2", type=QUANTITIES["teeth"], help="wheel (or ring) teeth (required unless a design file gives "
                   "them)")
    add_template_arguments(p, g)
    c = p.add_argument_group("contour")
    c.add_argument("--window", help="x1_lo,x1_hi,x2_lo,x2_hi (default: from the undercut and pointing limits)")
    add_tol_flag(c, "accuracy of the traced lines and the region, shift units: every point within tol of the "
                    "exact line (default 1e-4; allowed 1e-12 .. 1e-2)")
    c.add_argument("--xtol", type=float, help="deprecated: the old name of --tol")
    c.add_argument("--points", type=int, help="also cap the chords at window diagonal / points (smoother "
                   "pictures at coarse tolerances)")
    c.add_argument("--criterion", choices=("balanced", "strength", "center_distance"), default="balanced",
                   help="recommendation criterion (default balanced: equal sliding, s_a >= 0.25 m, eps >= 1.2)")
    c.add_argument("--center-distance", type=float, help="mm: draw a_w = const and use it with "
                   "--criterion center_distance")
    c.add_argument("--mark", help="x1,x2: a design point to mark and test")
    o = p.add_argument_group("output")
    add_output_flag(o, "write contour.png, contour.svg, contour.json, or page.html: the map beside the "
                    "recommended pair animated, its solids and its check (atomically)")
    add_json_flag(o)
    p.set_defaults(run=run)


def add_template_arguments(p, g) -> None:
    """The pair options but the tooth numbers (``gearkit blocking`` and ``gearkit atlas``)."""
    add_module_flag(g, "normal module m_n, mm (default 1)", default=1.0)
    g.add_argument("--pressure-angle-deg", type=QUANTITIES["pressure_angle_deg"],
                   help="normal pressure angle, degrees (default 20)")
    g.add_argument("--helix-angle-deg", type=QUANTITIES["helix_angle_deg"], default=0.0,
                   help="helix angle beta, degrees")
    g.add_argument("--internal", action="store_true", help="pinion inside a ring (needs --cutter-teeth)")
    g.add_argument("--addendum", type=float, default=1.0, help="addendum coefficient h_a* (default 1)")
    t = p.add_argument_group("tools")
    add_rack_flag(t)
    t.add_argument("--cutter-teeth", type=int, help="teeth z0 of the shaper cutter that cuts the ring")
    t.add_argument("--cutter-addendum", type=float, default=1.25, help="the shaper's addendum h_a0* (default 1.25)")
    t.add_argument("--pinion-cutter-teeth", type=int, help="cut the pinion with a shaper of this many teeth")


#: blocking_contour's and recommend's option fields -> the flags that set them
FLAGS = {"tol": "--tol", "window": "--window", "points": "--points", "center_distances": "--center-distance",
         "center_distance": "--center-distance", "criterion": "--criterion"}


def tol_from_args(args, command: str = "blocking"):
    """``--tol``, or its deprecated name ``--xtol`` (with a note on stderr); None: the default."""
    tol = args.tol
    if getattr(args, "xtol", None) is not None:
        print(f"gearkit {command}: --xtol is deprecated, use --tol (the same value, in shift units)",
              file=sys.stderr)
        if tol is not None:
            raise SpecError("--tol", "give --tol or its deprecated name --xtol, not both")
        tol = args.xtol
    return tol


def _floats(text, n, flag):
    try:
        vals = [float(v) for v in text.split(",")]
    except ValueError:
        raise SpecError(flag, f"{text!r} is not {n} comma-separated numbers") from None
    if len(vals) != n:
        raise SpecError(flag, f"{text!r} must have {n} comma-separated numbers")
    if not all(math.isfinite(v) for v in vals):
        raise SpecError(flag, f"{text!r}: every number must be finite")
    return vals


def design_template(args):
    """The pair of the design file (``args.design``) with the template flags typed applied, its shifts
    zeroed (the contour varies them); None without a design file."""
    if getattr(args, "design", None) is None:
        return None
    from dataclasses import replace

    from gearkit.checks import load_design
    from gearkit.cli.common import override_pair_spec

    spec = replace(load_design(args.design)[0], shift1=0.0, shift2=0.0, center_distance=None)
    view = argparse.Namespace(**{**vars(args), "given_flags": args.given_flags - {"center_distance", "z1", "z2"}})
    return override_pair_spec(spec, view)  # --center-distance draws a line (no shifts solved); teeth come after


def template_spec(args, z1: int, z2: int):
    """The PairSpec of the template options (or of the design file, flags applied) with tooth numbers z1, z2."""
    from dataclasses import replace

    template = design_template(args)
    if template is not None:
        return replace(template, teeth1=z1, teeth2=z2)
    from gearkit.pair import PairSpec

    alpha = args.pressure_angle_deg
    rack = rack_from_args(args)
    tool1 = rack
    if args.pinion_cutter_teeth is not None:
        tool1 = shaper_from_args(args.pinion_cutter_teeth, rack.pressure_angle_deg, 0.0, args.cutter_addendum,
                                 "--pinion-cutter-teeth")
    tool2 = rack
    if args.internal:
        if args.cutter_teeth is None:
            raise SpecError("--cutter-teeth", "an internal gear is cut by a shaper: give its tooth number z0")
        tool2 = shaper_from_args(args.cutter_teeth, rack.pressure_angle_deg, 0.0, args.cutter_addendum)
    elif args.cutter_teeth is not None:
        raise SpecError("--cutter-teeth", "applies to internal pairs (use --pinion-cutter-teeth)")
    if tool1 is rack and tool2 is rack:
        refuse_unused_cutter_flags(args)
    return PairSpec(z1, z2, args.module, kind="internal" if args.internal else "external",
                    pressure_angle_deg=alpha, helix_angle_deg=args.helix_angle_deg, tool1=tool1, tool2=tool2,
                    addendum=args.addendum)


def run(args) -> int:
    from gearkit.blocking import blocking_contour

    template = design_template(args)
    z1 = args.z1 if args.z1 is not None else getattr(template, "teeth1", None)
    z2 = args.z2 if args.z2 is not None else getattr(template, "teeth2", None)
    require_flags(argparse.Namespace(z1=z1, z2=z2), ("z1", "--z1"), ("z2", "--z2"))
    spec = template_spec(args, z1, z2)
    window = _floats(args.window, 4, "--window") if args.window else None
    cds = () if args.center_distance is None else (args.center_distance,)
    tol = tol_from_args(args)
    mark = _floats(args.mark, 2, "--mark") if args.mark else None  # bad input before any work
    try:
        contour = blocking_contour(spec, window=window, tol=tol, points=args.points, center_distances=cds)
        rec = contour.recommend(args.criterion, args.center_distance)
    except SpecError as exc:  # the options' errors name the flags typed
        flag = FLAGS.get(exc.field)
        if flag == "--tol" and args.xtol is not None:
            flag = "--xtol"
        raise (exc if flag is None else exc.renamed(flag)) from None
    marked = None if mark is None else contour.mark(*mark)
    if args.output and str(args.output).lower().endswith((".html", ".htm")):
        from gearkit.view import blocking_view, write_page

        write_page(args.output, blocking_view(spec, contour, rec if rec.passes else None, marked))
    elif args.output:
        contour.save(args.output, rec, marked)
    if args.json:
        print_json(contour.to_dict(rec, marked), indent=None)
    else:
        print(format_summary(contour, rec, marked, args.output))
    return 1 if marked is not None and not marked["inside"] else 0


def format_summary(contour, rec, marked, output=None) -> str:
    t = contour.field.template
    w = contour.window
    out = [f"gearkit blocking: {t.kind} pair z1 = {t.teeth1}, z2 = {t.teeth2}, alpha_n = {t.alpha_n_deg:g} deg, "
           f"beta = {t.helix_angle_deg:g} deg; window x1 [{w[0]:.3f}, {w[1]:.3f}], x2 [{w[2]:.3f}, {w[3]:.3f}]; "
           f"lines to tol {contour.tol:g}; {contour.seconds:.2f} s", "", "  code  line                        vertices"]
    for ln in contour.lines:
        n = sum(len(c) for c in ln.components)
        out.append(f"  {ln.code:<5} {ln.name:<27} {n:>6}" + ("" if n else "   (not in the window)"))
    out.append("")
    if contour.empty:
        out.append(f"region: EMPTY -- {contour.empty_reason}")
    else:
        out.append(f"region: {len(contour.region)} polygon(s), area {contour.area:.4f}")
    if rec is not None and rec.passes:
        out.append(f"recommended: x1 = {rec.x1:.4f}, x2 = {rec.x2:.4f} -- {rec.reason}")
    elif rec is not None:
        out.append(rec.reason)
    if marked is not None:
        verdict = "inside" if marked["inside"] else "OUTSIDE"
        why = ", ".join(marked["binding"]) or "none"
        out.append(f"marked x1 = {marked['x1']:g}, x2 = {marked['x2']:g}: {verdict}; violates: {why}")
    if output:
        out.append(f"wrote {output}")
    return "\n".join(out)


if __name__ == "__main__":  # pragma: no cover
    from gearkit.cli import main
    sys.exit(main(["blocking", *sys.argv[1:]]))
