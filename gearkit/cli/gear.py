"""``gearkit gear``: generate one involute gear, print its key values, export its profile."""
from __future__ import annotations

import json

from gearkit.errors import SpecError

RACKS = ("standard", "iso53a", "iso53b", "iso53c", "iso53d")


def add_tool_flags(p) -> None:
    """Tool flags shared by commands that build one involute gear."""
    p.add_argument("--pressure-angle-deg", type=float, default=None,
                   help="normal pressure angle of the rack/cutter, degrees (default 20)")
    p.add_argument("--rack", choices=RACKS, default="standard",
                   help="generating rack: 'standard' (h_a*=1, c*=0.25, largest tip rounding 0.38 m) or an ISO 53 "
                        "profile (default standard)")
    p.add_argument("--cutter-teeth", type=int, default=None,
                   help="cut with a shaper cutter of this many teeth (required with --internal; default 20 then)")
    p.add_argument("--cutter-shift", type=float, default=0.0, help="shaper cutter's own shift coefficient x0")
    p.add_argument("--cutter-addendum", type=float, default=1.25, help="shaper cutter addendum h_a0* (module units)")


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "gear", help="generate an involute gear by simulating its cutter",
        description="Generate an involute gear (external, internal, spur or helical) as the envelope of its "
                    "cutter; print key values (mm, transverse section) and export the profile. For an internal "
                    "gear positive -x moves the ring's teeth outward (thinner teeth, larger tip diameter).")
    p.add_argument("-z", "--teeth", type=int, required=True, help="number of teeth")
    p.add_argument("-m", "--module", type=float, required=True, help="normal module, mm")
    p.add_argument("-x", "--shift", type=float, default=0.0, help="normal profile shift coefficient x_n")
    p.add_argument("--helix-angle-deg", type=float, default=0.0, help="helix angle, degrees (+ right hand)")
    p.add_argument("--internal", action="store_true", help="internal (ring) gear, cut by a shaper cutter")
    add_tool_flags(p)
    p.add_argument("--tip-diameter", type=float, default=None, help="tip diameter d_a, mm (default d +- 2m(h_a* +- x))")
    p.add_argument("--thinning", type=float, default=0.0, help="tooth thinning for backlash, mm (normal, reference)")
    p.add_argument("--tol", type=float, default=None, help="accuracy: max deviation of any output point or chord "
                                                          "from the exact profile, mm (default 0.001*m)")
    p.add_argument("-o", "--output", default=None, help="write the profile: .svg .dxf .csv .json")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of the table")
    p.set_defaults(run=run)


def tool_from_args(args, internal: bool):
    from gearkit.tools import BasicRack, ShaperCutter

    alpha = 20.0 if args.pressure_angle_deg is None else args.pressure_angle_deg
    if args.cutter_teeth is not None or internal:
        return ShaperCutter(args.cutter_teeth or 20, alpha, args.cutter_shift, args.cutter_addendum)
    if args.rack == "standard":
        return BasicRack(alpha, name="standard")
    if args.pressure_angle_deg not in (None, 20.0):
        raise SpecError("--pressure-angle-deg", f"ISO 53 profiles have 20 degrees; use --rack standard for {alpha}")
    return BasicRack.iso53(args.rack[-1])


def build(args):
    from gearkit.families.involute import GearSpec, tooth_profile

    spec = GearSpec(args.teeth, args.module, args.shift, args.helix_angle_deg, args.internal,
                    tool_from_args(args, args.internal), args.tip_diameter, args.thinning)
    return spec, tooth_profile(spec)


def format_summary(info: dict) -> str:
    kind = "internal" if info["internal"] else "external"
    rows = [
        f"gearkit gear: {kind} involute gear, z = {info['teeth']}, m_n = {info['module']:g} mm, "
        f"x = {info['shift_coeff']:g}, beta = {info['helix_angle_deg']:g} deg, tool {info['tool']}",
        f"  reference diameter d     {info['reference_diameter']:12.6f} mm",
        f"  base diameter d_b        {info['base_diameter']:12.6f} mm",
        f"  tip diameter d_a         {info['tip_diameter']:12.6f} mm",
        f"  root diameter d_f        {info['root_diameter']:12.6f} mm",
        f"  form diameter d_Nf       {info['form_diameter']:12.6f} mm  (read from the generated tooth)",
        f"  tooth thickness s        {info['tooth_thickness']:12.6f} mm  (arc, reference circle)",
        f"  tip thickness s_a        {info['tip_thickness']:12.6f} mm",
        f"  undercut                 {'YES, depth %.6f mm' % info['undercut_depth'] if info['undercut'] else 'no'}",
        f"  pointed                  {'YES' if info['pointed'] else 'no'}",
        f"  accuracy                 requested {info['tolerance']['requested']:.3g} mm, achieved "
        f"{info['tolerance']['achieved']:.3g} mm",
    ]
    return "\n".join(rows)


def run(args) -> int:
    spec, prof = build(args)
    tol = args.tol if args.tol is not None else 1e-3 * spec.module
    if not tol > 0:
        raise SpecError("--tol", f"{tol!r} must be a positive length in mm")
    info = prof.summary(tol)
    if args.output:
        from gearkit.export import write_profile

        write_profile(args.output, [prof.outline(tol)], info)
        info["output"] = args.output
    print(json.dumps(info, indent=2) if args.json else format_summary(info))
    return 0
