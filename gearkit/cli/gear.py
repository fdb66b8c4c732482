"""``gearkit gear``: generate one involute gear, print its key values, export its profile or solid.

``-o`` with a 2D extension (.svg .dxf .csv .json) writes the transverse profile; with a mesh
extension (.stl .obj .glb .3mf .step) it writes the solid (``--width`` required): spur or helical,
``--herringbone [--gap G]``, ``--bore D [--keyway WxD]``, a ring's ``--outer-diameter`` or
``--rim``. The mesh path imports only numpy and manifold3d (every mesh format is written with numpy).
"""
from __future__ import annotations

from gearkit.cli.common import (QUANTITIES, TIP_RULES, add_gear_flags, add_json_flag, add_keyway_flag, add_output_flag, add_tol_flag,
                                add_tool_flags, keyway_from_arg, print_json, tol_from, tool_from_args)
from gearkit.cli.design import add_design_argument, given, require_flags
from gearkit.errors import SpecError

def register(subparsers) -> None:
    p = subparsers.add_parser(
        "gear", help="generate an involute gear by simulating its cutter",
        description="Generate an involute gear (external, internal, spur or helical) as the envelope of its "
                    "cutter; print key values (mm, transverse section) and export the profile. For an internal "
                    "gear positive -x moves the ring's teeth outward (thinner teeth, larger tip diameter).")
    add_design_argument(p, "pair")
    p.add_argument("--gear", type=int, choices=(1, 2), default=None,
                   help="with a design file: which gear of the pair (1 pinion, the default; 2 wheel or ring)")
    add_gear_flags(p, required=False)
    p.add_argument("--helix-angle-deg", type=QUANTITIES["helix_angle_deg"], default=0.0, help="helix angle, degrees (+ right hand)")
    p.add_argument("--internal", action="store_true", help="internal (ring) gear, cut by a shaper cutter")
    p.add_argument("--ring-shift", choices=("iso", "cutter"), default="iso",
                   help="how a ring's -x is read: 'iso' (ISO 21771, by the tooth thickness as if rack-cut; the "
                        "shaper setting is derived; default) or 'cutter' (the shaper's radial setting)")
    add_tool_flags(p)
    p.add_argument("--tip-diameter", type=float, default=None, help="tip diameter d_a, mm (default by --tip-rule)")
    p.add_argument("--tip-rule", choices=TIP_RULES, default="standard",
                   help="'standard' d_a = d +- 2m(h_a* +- x) (default), or 'shortened' as in the pair with "
                        "--mate-teeth/--mate-shift (the tip the pair check uses)")
    p.add_argument("--mate-teeth", type=QUANTITIES["teeth"], default=None, help="the mating gear's teeth (for --tip-rule shortened)")
    p.add_argument("--mate-shift", type=QUANTITIES["shift"], default=0.0, help="the mating gear's shift (default 0)")
    p.add_argument("--thinning", type=float, default=0.0, help="tooth thinning for backlash, mm (normal, reference)")
    add_tol_flag(p, "accuracy: max deviation of any output point, chord or facet from the exact profile or tooth "
                 "surface, mm (default 0.001*m for 2D, 0.005*m for meshes)")
    add_output_flag(p, "write the profile (.svg .dxf .csv .json) or the solid (.stl .obj .glb .3mf, or exact B-rep "
                    ".step; needs --width)")
    add_json_flag(p, "print one JSON object instead of the table")
    add_inspection_flags(p)
    add_solid_flags(p)
    p.set_defaults(run=run)


def add_inspection_flags(p) -> None:
    """Flags of the inspection dimensions (span, over pins/balls, chordal thickness)."""
    g = p.add_argument_group("inspection dimensions")
    g.add_argument("--span-teeth", type=int, default=None, help="span over k teeth (default: the standard k, "
                   "anvils nearest d + 2 x m_n)")
    g.add_argument("--pin-diameter", type=float, default=None, help="pin/ball diameter d_p, mm (default: touching "
                   "the flanks on d + 2 x m_n)")
    g.add_argument("--chordal-diameter", type=float, default=None, help="circle of the chordal thickness, mm "
                   "(default: the reference circle)")


def inspection_of(args, spec, prof, tol: float):
    """(JSON dict, findings) of the gear's inspection dimensions, by formula and measured."""
    from gearkit.checks.inspection import inspection_findings
    from gearkit.pair.inspection import inspect_gear

    insp = inspect_gear(spec, args.span_teeth, args.pin_diameter, args.chordal_diameter, profile=prof)
    width = getattr(args, "width", None)
    return insp.to_dict(), inspection_findings(insp, tol, width)


def format_inspection(info: dict) -> str:
    """Table rows of the inspection dimensions (formula, and measured on the generated tooth)."""
    rows = []
    if "span" in info:
        s = info["span"]
        rows.append((f"span W (k = {s['k']})", f"{s['W']:12.6f} mm  measured {s['measured']['W']:.6f} mm, "
                     f"anvils on d_M = {s['measured']['d_M']:.4f} mm ({s['measured']['touches']})"))
    p = info["over_pins"]
    rows.append((f"{'between' if p['between'] else 'over'} pins M", f"{p['M']:12.6f} mm  measured "
                 f"{p['measured']['M']:.6f} mm, d_p = {p['d_p']:.4f} mm ({p['measured']['touches']})"))
    c = info["chordal"]
    rows.append(("chordal thickness s", f"{c['s']:12.6f} mm  measured {c['measured']['s']:.6f} mm, "
                 f"on d_y = {c['d_y']:.4f} mm"))
    rows.append(("chordal height h", f"{c['h']:12.6f} mm  measured {c['measured']['h']:.6f} mm"))
    return "\n".join(f"  {label:<25}{value}" for label, value in rows)


def add_solid_flags(p) -> None:
    """Flags of the solid a mesh output builds (face width, herringbone, bore, ring rim)."""
    g = p.add_argument_group("solid (mesh output)")
    g.add_argument("--width", type=QUANTITIES["width"], default=None, help="face width b, mm (a herringbone's total, gap included)")
    g.add_argument("--herringbone", action="store_true", help="two helical halves of opposite hand")
    g.add_argument("--gap", type=float, default=0.0, help="central gap of a double-helical gear, mm (with "
                   "--herringbone; grooved a module below the root)")
    g.add_argument("--bore", type=float, default=None, help="bore diameter, mm")
    add_keyway_flag(g, help="keyway width x depth in the bore, mm (e.g. 3x1.4)")
    rim = g.add_mutually_exclusive_group()
    rim.add_argument("--outer-diameter", type=float, default=None, help="ring gear's outer diameter, mm")
    rim.add_argument("--rim", type=float, default=None, help="ring gear's rim thickness beyond the root, mm "
                     "(default 2 modules)")
    g.add_argument("--ascii", action="store_true", help="ASCII STL instead of binary")


def solid_spec_from_args(args, helix_angle_deg=None):
    """The :class:`~gearkit.solids.SolidSpec` of the solid flags (``--width`` required)."""
    from gearkit.solids import SolidSpec

    if args.width is None:
        raise SpecError("--width", "a mesh output needs the face width (--width, mm)")
    return SolidSpec(args.width, helix_angle_deg, args.herringbone, args.gap, args.bore,
                     keyway_from_arg(args.keyway), args.outer_diameter, args.rim)


def _solid_only_flags(args) -> list:
    flags = [("--width", args.width is not None), ("--herringbone", args.herringbone), ("--gap", bool(args.gap)),
             ("--bore", args.bore is not None), ("--keyway", args.keyway is not None),
             ("--outer-diameter", args.outer_diameter is not None), ("--rim", args.rim is not None),
             ("--ascii", args.ascii)]
    return [name for name, given in flags if given]


#: gear flag destination -> the GearSpec field it sets (a design file's gear, overridden)
_GEAR_FIELDS = {"teeth": "teeth", "module": "module", "shift": "shift", "helix_angle_deg": "helix_angle_deg",
                "tip_diameter": "tip_diameter", "thinning": "thinning", "ring_shift": "shift_convention"}
_TOOL_FLAGS = ("rack", "pressure_angle_deg", "cutter_teeth", "cutter_shift", "cutter_addendum")


def design_gear(args):
    """Gear ``--gear`` (default 1) of the design file's pair, as the pair has it (its tip included), with
    the gear flags typed applied; a changed size or shift drops the pair's tip (the tip rule decides)."""
    from dataclasses import replace

    from gearkit.checks import load_design
    from gearkit.pair import gear_specs

    gears = gear_specs(load_design(args.design)[0])
    n = args.gear or 1
    if n > len(gears):
        raise SpecError("--gear", "a rack pair has one gear (the pinion, --gear 1)")
    gear = gears[n - 1]
    changes = {f: getattr(args, d) for d, f in _GEAR_FIELDS.items() if given(args, d)}
    if given(args, "internal") and args.internal:
        changes["internal"] = True
    if any(given(args, d) for d in _TOOL_FLAGS):
        changes["tool"] = tool_from_args(args, changes.get("internal", gear.internal))
    if "tip_diameter" not in changes and {"teeth", "module", "shift", "helix_angle_deg"} & set(changes):
        changes["tip_diameter"] = None
    return replace(gear, **changes)


def build(args):
    from gearkit.families.involute import GearSpec, tooth_profile

    if args.design is not None:
        spec = design_gear(args)
    else:
        if args.gear is not None:
            raise SpecError("--gear", "picks a gear of a design file: give one")
        require_flags(args, ("teeth", "-z/--teeth"), ("module", "-m/--module"))
        spec = GearSpec(args.teeth, args.module, args.shift, args.helix_angle_deg, args.internal,
                        tool_from_args(args, args.internal), args.tip_diameter, args.thinning,
                        shift_convention=args.ring_shift)
    if args.tip_rule == "shortened":
        from dataclasses import replace

        from gearkit.pair import gear_tip_diameter
        if args.tip_diameter is not None:
            raise SpecError("--tip-rule", "give either --tip-diameter or --tip-rule shortened, not both")
        if args.mate_teeth is None:
            raise SpecError("--mate-teeth", "the shortened tip rule needs the mating gear's teeth")
        mate = GearSpec(args.mate_teeth, args.module, args.mate_shift, -args.helix_angle_deg,
                        tool=tool_from_args(args, False) if not args.internal else None)
        spec = replace(spec, tip_diameter=gear_tip_diameter(spec, "shortened", mate))
    elif args.mate_teeth is not None:
        raise SpecError("--mate-teeth", "applies with --tip-rule shortened")
    return spec, tooth_profile(spec)


def _convention(info: dict) -> str:
    """How the shift is read, for the table: ISO, or the shaper's setting (and the setting an ISO ring needs)."""
    if info.get("shift_convention") == "cutter":
        return "shaper cutter setting"
    if info.get("cutter_setting") is not None:
        return f"ISO 21771; shaper setting {info['cutter_setting']:.6g}"
    return "ISO 21771"


def format_summary(info: dict) -> str:
    from gearkit.export import text_number

    kind = "internal" if info["internal"] else "external"
    rows = [
        f"gearkit gear: {kind} involute gear, z = {info['teeth']}, m_n = {info['module']:g} mm, "
        f"x = {text_number(info['shift_coeff'])} ({_convention(info)}), beta = {text_number(info['helix_angle_deg'])} deg, "
        f"tool {info['tool']}",
        f"  reference diameter d     {info['reference_diameter']:12.6f} mm",
        f"  base diameter d_b        {info['base_diameter']:12.6f} mm",
        f"  tip diameter d_a         {info['tip_diameter']:12.6f} mm",
        f"  root diameter d_f        {info['root_diameter']:12.6f} mm",
        f"  form diameter d_Nf       {info['form_diameter']:12.6f} mm  (read from the generated tooth)",
        f"  tooth thickness s        {info['tooth_thickness']:12.6f} mm  (arc, reference circle)"
        if info["tooth_thickness"] is not None else
        "  tooth thickness s                  -     (the reference circle is not on the tooth)",
        f"  tip thickness s_a        {info['tip_thickness']:12.6f} mm",
        f"  undercut                 {'YES, depth %.6f mm' % info['undercut_depth'] if info['undercut'] else 'no'}",
        f"  pointed                  {'YES' if info['pointed'] else 'no'}",
        f"  accuracy                 requested {info['tolerance']['requested']:.3g} mm, achieved "
        f"{info['tolerance']['achieved']:.3g} mm",
    ]
    return "\n".join(rows)


def format_solid(info: dict) -> str:
    """Table rows of a written solid (``Solid.summary()``)."""
    lo, hi = info["bbox"]
    return "\n".join([
        f"  solid                    {info['kind']}, b = {info['width']:g} mm, {info['layers']} layer"
        f"{'s' if info['layers'] != 1 else ''}, {info['points_per_tooth']} points per tooth",
        f"  volume                   {info['volume']:12.3f} mm^3",
        f"  faces                    {info['faces']:12d}",
        f"  bounding box             " + " x ".join(f"{h - l:.4f}" for l, h in zip(lo, hi)) + " mm",
    ])


def run(args) -> int:
    from gearkit.export import profile_format

    mesh = False
    if args.output:
        from gearkit.solids.export import mesh_format

        mesh = mesh_format(args.output) is not None
        if not mesh:
            profile_format(args.output)  # reject unknown extensions before any work
    if not mesh and _solid_only_flags(args):
        raise SpecError(_solid_only_flags(args)[0], "applies to a solid output (-o .stl .obj .glb .3mf .step)")
    spec, prof = build(args)
    if mesh:
        return _run_solid(args, spec, prof)
    tol = tol_from(args.tol, 1e-3 * spec.module)
    if args.output:
        bound_outline(prof, tol, spec.module)
    info = prof.summary(tol)
    dims, findings = inspection_of(args, spec, prof, tol)
    if args.output:
        from gearkit.export import write_profile

        write_profile(args.output, [prof.outline(tol)], info)
        info["output"] = args.output
    info.update(dims)
    info["findings"] = [f.to_dict() for f in findings]
    if args.json:
        print_json(info)
    else:
        from gearkit.checks.report import CheckReport, format_findings

        warned = [f for f in findings if f.status != "ok"]
        print(format_summary(info) + "\n" + format_inspection(info)
              + ("\n" + "\n".join(format_findings(CheckReport(tuple(warned)))) if warned else ""))
    return 0


#: default size limits of an output (``--max-points`` raises them): about 100 MB of SVG or STL
MAX_OUTLINE_POINTS, MAX_FACES = 2_000_000, 2_000_000


def bound_outline(prof, tol: float, module: float) -> None:
    """Refuse an outline of more than ``MAX_OUTLINE_POINTS`` points at ``tol``, estimated first.

    Chords within ``tol`` of a curve need ``tol**-0.5`` points, so the count at ``tol`` is the count
    at a coarse tolerance scaled by ``sqrt(coarse / tol)``.
    """
    import math

    from gearkit.cli.shell import bound

    coarse = max(tol, 1e-3 * module)
    n = len(prof.outline(coarse)) * math.sqrt(coarse / tol)
    bound("--tol", n, MAX_OUTLINE_POINTS, "outline points")


def _run_solid(args, spec, prof) -> int:
    from gearkit.solids import default_mesh_tol, gear_solid
    from gearkit.solids.export import mesh_format, write_mesh

    tol = tol_from(args.tol, default_mesh_tol(spec.module))
    from gearkit.cli.shell import bound
    from gearkit.solids.gear import estimate_faces, gear_plan

    solid_spec = solid_spec_from_args(args)
    step = mesh_format(args.output) in ("step", "stp")
    if step:  # the B-rep's faces, from the recipe, before anything is built
        from gearkit.cli.shell import MAX_STEP_FACES
        from gearkit.solids.solid import Recipe
        from gearkit.solids.step import recipe_faces

        bound("-o", recipe_faces(Recipe("gear", (prof, solid_spec, tol))), MAX_STEP_FACES,
              "B-rep faces in the STEP file")
    plan = gear_plan(prof, solid_spec, tol)  # sampled once: it sizes the solid, then builds it
    bound("--tol", estimate_faces(prof, solid_spec, tol, plan=plan), MAX_FACES, "facets")
    solid = gear_solid(prof, solid_spec, tol, name="gear", plan=plan)
    info = prof.summary(tol, sample=False)  # the accuracy reported is the solid's
    if step:
        from gearkit.solids.step import write_step

        info["tolerance"] = {"requested": tol, "achieved": write_step(args.output, [solid])["achieved"],
                             "of": "every B-spline flank of the B-rep from the exact surface"}
    else:
        write_mesh(args.output, [solid], ascii=args.ascii)
        info["tolerance"] = {"requested": tol, "achieved": solid.achieved,
                             "of": "every vertex and facet of the mesh from the exact surface"}
    info["solid"] = solid.summary()
    info["output"] = args.output
    if args.json:
        print_json(info)
    else:
        print(format_summary(info) + "\n" + format_solid(info["solid"]))
    return 0
