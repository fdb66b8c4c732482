"""``gearkit novikov``: generate and check a Novikov (circular-arc) pair.

Usage::

    gearkit novikov --z1 20 --z2 60 -m 4 --helix-angle-deg 15 --width 60
                    [--rack dca24|single-arc|FILE.toml] [--center-distance A] [--json]
                    [-o profile.svg|profile.dxf|profile.csv|profile.json|pair.obj|gear.stl]

Exit status: 0 when no finding fails, 1 when one fails, 2 for bad input.
"""
from __future__ import annotations

import math
import sys
from pathlib import Path

from gearkit.cli.common import QUANTITIES, add_json_flag, add_module_flag, add_output_flag, add_tol_flag, print_json, tol_from
from gearkit.cli.design import add_design_argument, apply_flag_design
from gearkit.errors import SpecError


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "novikov", help="generate and check a Novikov (circular-arc) pair: overlap, arcs, sensitivity, mesh",
        description="Generate a Novikov (Wildhaber-Novikov) circular-arc gear pair with its racks and check it "
                    "(lengths in mm, angles in degrees). The preset racks are NOT verified against the "
                    "standards: verify against the standard before production.",
        epilog="Exit status: 0 no finding fails, 1 a finding fails, 2 bad input.")
    add_design_argument(p, "flags")
    g = p.add_argument_group("pair")
    g.add_argument("--z1", type=QUANTITIES["teeth"], help="pinion teeth (required)")
    g.add_argument("--z2", type=QUANTITIES["teeth"], help="wheel teeth (required)")
    add_module_flag(g, "normal module m_n, mm (required)")
    g.add_argument("--helix-angle-deg", type=QUANTITIES["helix_angle_deg"], help="helix angle beta, degrees, its sign the pinion's hand "
                   "(negative: left hand; the wheel has the other hand; required; 0 fails the overlap check)")
    g.add_argument("--width", type=QUANTITIES["width"], help="face width b, mm (required)")
    g.add_argument("--rack", default="standard", help="rack system: dca24 (double arc, 24 deg; the default, also "
                   "named 'standard' as every command's default rack), single-arc, or a TOML rack file written as "
                   "a preset is: one [NAME] table with [NAME.rack] (or [NAME.pinion] and [NAME.wheel])")
    g.add_argument("--center-distance", type=float, help="operating centre distance a_w, mm (default: the "
                   "reference a = m_n (z1 + z2) / (2 cos beta))")
    lim = p.add_argument_group("limits")
    lim.add_argument("--min-overlap-ratio", type=float, help="warn below this eps_beta (default 1.1; fail below 1)")
    out = p.add_argument_group("output")
    out.add_argument("--no-mesh", action="store_true", help="skip the simulated mesh (contact and interference)")
    add_tol_flag(out, "tolerance of written outlines/meshes, mm (default 1e-3 m_n in 2D, the solids' default in 3D)")
    add_json_flag(out)
    add_output_flag(out, "write the pair in mesh: 2D .svg .dxf .csv .json, or helical solids .obj .stl .glb .3mf "
                    ".step (one gear when the file is named gear*, or with --gear)")
    out.add_argument("--gear", type=int, choices=(1, 2), help="3D output of this gear only (1 pinion, 2 wheel)")
    p.set_defaults(run=run)


def _spec(args):
    from gearkit.families.novikov import NovikovPairSpec

    for name, flag in (("z1", "--z1"), ("z2", "--z2"), ("module", "-m/--module"),
                       ("helix_angle_deg", "--helix-angle-deg"), ("width", "--width")):
        if getattr(args, name) is None:
            raise SpecError(flag, "is required")
    return NovikovPairSpec(args.z1, args.z2, args.module, args.helix_angle_deg, args.width, args.rack,
                           args.center_distance)


def _write(spec, args, info):
    from gearkit.solids.export import mesh_format

    path = args.output
    if mesh_format(path) is not None:
        return _write_3d(spec, args)
    from gearkit.export import write_profile
    from gearkit.families.novikov.mesh import meshed_outlines

    tol = tol_from(args.tol, 1e-3 * spec.module)
    return write_profile(path, meshed_outlines(spec, tol), info)


def _write_3d(spec, args) -> dict:
    """Helical solids through :mod:`gearkit.solids`: the pair placed in mesh at zone 0's contact (the
    transverse sections at z = 0 are those of the 2D mesh; the opposite hands keep them in mesh along
    the face), or one gear when the file is named gear*."""
    from gearkit.families.novikov import tooth_profile
    from gearkit.families.novikov.mesh import mesh_contact
    from gearkit.cli.shell import write_solids
    from gearkit.solids import SolidSpec, default_mesh_tol, gear_solid

    tol = tol_from(args.tol, default_mesh_tol(spec.module))
    body = SolidSpec(width=spec.face_width)
    stem = Path(args.output).name.lower()
    which = args.gear if args.gear is not None else (1 if stem.startswith("gear") else None)
    if which is not None:
        solid = gear_solid(tooth_profile(spec.gear(which)), body, tol, name=f"gear{which}")
        write_solids(args.output, [solid])
        return {"parts": [solid.name], "achieved": solid.achieved}
    c = mesh_contact(spec, 0, interference=False)
    parts = [gear_solid(tooth_profile(spec.gear(k)), body, tol, name=f"gear{k}") for k in (1, 2)]
    placed = [parts[0].placed(c.rotations[0]), parts[1].placed(c.rotations[1], (0.0, c.center_distance, 0.0))]
    write_solids(args.output, placed)
    overlap = float((placed[0].manifold ^ placed[1].manifold).volume())
    return {"parts": [p.name for p in placed], "achieved": max(p.achieved for p in placed),
            "interference_volume": overlap}


def run(args) -> int:
    from gearkit.checks.novikov import NovikovLimits, check_novikov

    apply_flag_design(args)
    spec = _spec(args)
    limits = NovikovLimits() if args.min_overlap_ratio is None else NovikovLimits(args.min_overlap_ratio)
    tol_from(args.tol, None)  # a bad --tol fails before the check runs
    from gearkit.families.novikov.mesh import NoContact

    result = check_novikov(spec, limits, simulate=not args.no_mesh)
    info = result.to_dict()
    unmeshed = None
    if args.output:
        try:
            written = _write(spec, args, {k: info[k] for k in ("center_distance", "overlap_ratio", "contact_radii")})
            info["output"] = {"path": args.output, **(written if isinstance(written, dict) else {})}
        except NoContact as exc:  # a pair that does not mesh cannot be placed in mesh: a failing design, not bad input
            unmeshed = (f"{args.output} not written: the gears cannot be placed in mesh at a_w = "
                        f"{spec.reference_center_distance if spec.center_distance is None else spec.center_distance:.6g}"
                        f" mm ({exc})")
            info["output"] = {"path": args.output, "written": False, "reason": unmeshed}
    if args.json:
        print_json(info)
    else:
        print(format_report(result))
    if unmeshed is not None:
        print(f"gearkit novikov: {unmeshed}", file=sys.stderr)
        return 1
    if args.output and not args.json:
        extra = info["output"].get("interference_volume")
        print(f"wrote {args.output}" + ("" if extra is None else
                                        f" (the placed solids overlap by {extra:.3g} mm^3 at a mesh deviation of "
                                        f"{info['output']['achieved']:.3g} mm; faceting alone shrinks with --tol)"))
    return 0 if result.ok else 1


def format_report(result) -> str:
    """The compact human report of ``gearkit novikov``."""
    from gearkit.export import text_number

    g = result.geometry
    s = g.spec
    deg = math.degrees
    lines = [
        f"gearkit novikov: {g.kind} pair, z1 = {s.teeth1}, z2 = {s.teeth2}, m_n = {g.module:g} mm, "
        f"beta = {text_number(s.helix_angle_deg)} deg" + (f" (pinion {s.hand} hand)" if s.helix_angle_deg else "")
        + f", b = {s.face_width:g} mm, racks {s.racks.name}"
        + ("" if s.racks.verified else " (UNVERIFIED)"),
        f"  a {g.reference_center_distance:.4f} mm   a_w {g.center_distance:.4f} mm   m_t {g.transverse_module:.5f}"
        + (f"   p_x {g.axial_pitch:.4f} mm" if math.isfinite(g.axial_pitch) else
           "   p_x: none (spur, no axial pitch)")
        + f"   eps_beta {text_number(g.overlap_ratio, '.5f')}   eps_alpha 0 (by design)",
        f"  alpha_k {deg(g.contact_angle):.4f} deg   alpha_t {deg(g.contact_angle_transverse):.4f} deg   "
        f"+0.01 m_n -> {deg(g.sensitivity):+.3f} deg   backlash {g.backlash:.4f} mm",
        "",
        "  zone  convex   height     R_K1       R_K2       lead1       lead2",
    ]
    for c in g.contacts:
        lead = [text_number(v, "11.3f", "none") for v in c.leads]  # a spur gear's teeth have no lead
        lines.append(f"  {c.zone:<6}gear {c.convex_gear}{c.height:9.4f}{c.radii[0]:11.4f}{c.radii[1]:11.4f}"
                     f"{lead[0]} {lead[1]}")
    lines += ["", "  gear   z      d_a        d_f       s_a", ]
    for k, prof in enumerate(result.profiles, start=1):
        lines.append(f"  {k:<5}{prof.teeth:>3}{prof.tip_diameter:11.4f}{prof.root_diameter:11.4f}"
                     f"{prof.tip_thickness:10.4f}")
    from gearkit.checks.report import format_findings

    lines += [""] + format_findings(result.report, 27)
    return "\n".join(lines)


if __name__ == "__main__":  # pragma: no cover
    from gearkit.cli import main
    sys.exit(main(["novikov", *sys.argv[1:]]))
