"""``gearkit contact``: mesh the generated teeth of a pair over one cycle (tooth contact analysis).

Usage::

    gearkit contact --z1 20 --z2 40 -m 2 [pair options as in gearkit check] [--steps 2000]
                    [--slices 20] [--tol 0.002] [--json] [-o te.png] [-o path.svg]
    gearkit contact ... --width 20 --torque 100 [--tip-relief 0.008[@43.2]] [--crowning 0.01]
                    [--misalignment 0.02] [--runout1 0.01 --cycles 20] [--json] [-o te.png] [-o load.png]
                    [-o pattern.png] [-o harris.png]
    gearkit contact design.toml [--json]

Prints the simulated contact ratio beside the formula value, the transmission error, the
backlash and any interference, with the simulation's findings. ``-o`` writes a plot (PNG or SVG
by the suffix): the path of contact when the file name contains "path", else the transmission
error. With ``--torque`` the pair is also analysed under load (the JSON gains ``loaded``) and ``-o``
writes the loaded TE, the load sharing (``load`` in the name), the contact pattern (``pattern``) or
the Harris map around the torque (``harris``: p-p TE over torque for long tip reliefs).
Exit status: 0 when no simulated finding fails, 1 when one does, 2 for bad input.
"""
from __future__ import annotations

import math
import sys

from gearkit.cli.common import (SIGN_NOTE, add_json_flag, add_output_flag, add_pair_arguments, add_tol_flag,
                                pair_spec_from_args, print_json)
from gearkit.errors import SpecError


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "contact",
        help="mesh the generated teeth over a cycle: transmission error, contact ratio, backlash, interference",
        description="Tooth contact analysis of an involute pair (lengths in mm, angles in degrees): the "
                    "generated teeth meshed rigidly over one mesh cycle. " + SIGN_NOTE,
        epilog="Exit status: 0 no simulated finding fails, 1 one fails, 2 bad input.")
    add_pair_arguments(p)
    add_json_flag(p)
    sim = p.add_argument_group("simulation")
    sim.add_argument("--steps", type=int, default=2000, help="driver angles per mesh cycle (default 2000)")
    sim.add_argument("--slices", type=int, help="transverse slices of a helical pair (default 20 with --width)")
    add_tol_flag(sim, "chord tolerance (mm) that locates contacts before they are refined on the exact teeth "
                      "(default 0.001 m_n)")
    sim.add_argument("--contact-tol", type=float, help="normal clearance (mm) counted as contact (default: "
                     "round-off, the geometric contact)")
    add_output_flag(sim, "write a plot (.png or .svg): the path of contact if FILE's name contains 'path', else the "
                    "transmission error; repeatable", action="append", default=[], metavar="FILE")
    ld = p.add_argument_group("loaded contact (external pairs; needs --width)")
    ld.add_argument("--torque", type=float, help="pinion torque, N m: analyse the pair under load")
    ld.add_argument("--tip-relief", metavar="AMOUNT[@DIAMETER]", help="linear tip relief on both gears, mm; "
                    "from the pinion's DIAMETER (mm; the wheel's over the same roll length), else from each "
                    "gear's highest point of single tooth contact (long relief)")
    ld.add_argument("--crowning", type=float, default=0.0, help="lead crowning C_beta of the pinion, mm")
    ld.add_argument("--misalignment", type=float, default=0.0,
                    help="axis misalignment out of plane f_Sigma_beta over the face width, mm")
    ld.add_argument("--misalignment-in-plane", type=float, default=0.0,
                    help="axis misalignment in plane f_Sigma_delta over the face width, mm")
    ld.add_argument("--center-distance-deviation", type=float, default=0.0,
                    help="centre-distance deviation from the operating centre distance, mm")
    ld.add_argument("--runout1", type=float, default=0.0, help="pinion run-out (eccentricity), mm")
    ld.add_argument("--runout2", type=float, default=0.0, help="wheel run-out (eccentricity), mm")
    ld.add_argument("--cycles", type=int, default=1,
                    help="mesh cycles analysed under load (default 1; z1 for a whole pinion turn)")
    p.set_defaults(run=run)


def _spec(args):
    return pair_spec_from_args(args)


#: default limit of the positions simulated (--steps per cycle times --cycles): about 15 s
MAX_POSITIONS = 100_000


def run(args) -> int:
    from gearkit.checks import check_pair
    from gearkit.checks.simulated import simulated_findings
    from gearkit.contact import analyse_pair, save_plot

    spec, limits = _spec(args)
    for name in ("steps", "slices"):
        v = getattr(args, name)
        if v is not None and v < 1:
            raise SpecError(f"--{name}", f"{v} must be a positive integer")
    from gearkit.cli.shell import bound

    bound("--steps", args.steps * max(args.cycles or 1, 1), MAX_POSITIONS, "mesh positions (--steps x --cycles)")
    check = check_pair(spec, limits)
    analysis = analyse_pair(spec, args.steps, tol=args.tol, slices=args.slices, contact_tol=args.contact_tol)
    findings = simulated_findings(spec, check.geometry, check.report.findings, limits, analysis)
    loaded = _loaded(spec, args)
    if loaded is not None:
        from gearkit.contact.plot_loaded import save_loaded_plot

        written = [save_plot(analysis, path) if "path" in path.lower() else
                   _harris(spec, args, path) if "harris" in path.lower() else save_loaded_plot(loaded, path)
                   for path in args.output]
    else:
        written = [save_plot(analysis, path) for path in args.output]
    if args.json:
        out = analysis.to_dict()
        g = check.geometry
        out["contact_ratio_formula"] = g.contact_ratio
        if analysis.slices > 1:
            out["total_contact_ratio_formula"] = g.total_contact_ratio
        out["backlash_formula"] = g.backlash
        out["findings"] = [f.to_dict() for f in findings]
        out["formula_findings"] = [f.to_dict() for f in check.report.findings if f.status != "ok"]
        out["files"] = written
        if loaded is not None:
            out["loaded"] = loaded.to_dict()
        print_json(out)
    else:
        print(format_summary(spec, check, analysis, findings, written, loaded))
    return 1 if any(f.status == "fail" for f in findings) else 0


def _tip_relief(spec, text):
    """``AMOUNT[@DIAMETER]`` -> (Modification, Modification) or (None, None)."""
    from gearkit.contact.harris import long_tip_relief
    from gearkit.families.involute.modification import Modification
    from gearkit.pair import pair_geometry

    if not text:
        return None, None
    amount, _, diameter = text.partition("@")
    try:
        c = float(amount)
        d = float(diameter) if diameter else None
    except ValueError:
        raise SpecError("--tip-relief", f"{text!r} must be AMOUNT or AMOUNT@DIAMETER (mm)") from None
    if d is None:
        return long_tip_relief(spec, c)
    if not (math.isfinite(c) and 0 <= c <= 1):
        raise SpecError("--tip-relief", f"{c!r} must be an amount in [0, 1] mm")
    g = pair_geometry(spec)
    rb1, ra1 = g.gears[0].base_diameter / 2, g.gears[0].tip_diameter / 2
    if not (math.isfinite(d) and 2 * rb1 < d < 2 * ra1):
        raise SpecError("--tip-relief", f"start diameter {d!r} must lie on the pinion's flank "
                        f"({2 * rb1:.4f} .. {2 * ra1:.4f} mm)")
    roll = math.sqrt(ra1 ** 2 - rb1 ** 2) - math.sqrt((d / 2) ** 2 - rb1 ** 2)
    return (Modification(tip_relief=c, tip_relief_diameter=d), Modification(tip_relief=c, tip_relief_roll=roll))


def _loaded(spec, args):
    """The loaded analysis asked for by ``--torque`` (None without it)."""
    from gearkit.contact.loaded import Deviations
    from gearkit.contact.pair import analyse_loaded
    from gearkit.families.involute.modification import Modification

    extras = ("tip_relief", "crowning", "misalignment", "misalignment_in_plane", "center_distance_deviation",
              "runout1", "runout2")
    if args.torque is None:
        if any(getattr(args, k) for k in extras):
            raise SpecError("--torque", "micro-geometry and mounting deviations act in the loaded analysis: "
                            "give --torque")
        return None
    m1, m2 = _tip_relief(spec, args.tip_relief)
    if args.crowning:
        import dataclasses

        m1 = dataclasses.replace(m1, lead_crowning=args.crowning) if m1 else Modification(lead_crowning=args.crowning)
    dev = Deviations(args.center_distance_deviation, args.misalignment_in_plane, args.misalignment,
                     args.runout1, args.runout2)
    return analyse_loaded(spec, args.torque, modifications=(m1, m2), deviations=dev, steps=args.steps,
                          slices=args.slices, tol=args.tol, cycles=args.cycles)


def _harris(spec, args, path):
    """``-o harris.png``: the Harris map around ``--torque`` for long tip reliefs up to about twice the
    deflection of one pair at that torque (ISO 6336-1 single stiffness)."""
    import numpy as np

    from gearkit.contact import harris_map, iso_mesh_stiffness
    from gearkit.contact.plot_loaded import plot_harris_map
    from gearkit.pair import pair_geometry

    g = pair_geometry(spec)
    c1 = iso_mesh_stiffness(spec.teeth1, spec.teeth2, spec.shift1, spec.shift2, contact_ratio=g.contact_ratio,
                            helix_angle_deg=spec.helix_angle_deg).single
    load = args.torque * 1e3 / (g.gears[0].base_diameter / 2) / spec.face_width  # N/mm, one pair
    deflection = load / c1 * 1e-3  # mm
    reliefs = np.linspace(0.0, 2.0 * deflection, 9)
    torques = args.torque * np.array([0.25, 0.5, 0.75, 1.0, 1.25, 1.5])
    hmap = harris_map(spec, torques, reliefs, design_torque=args.torque, steps=min(args.steps, 200), tol=args.tol)
    return plot_harris_map(hmap, path)


def _mm(v) -> str:
    return f"{0.0 if abs(v) < 5e-6 else v:.5f}"  # no "-0.00000"


def format_summary(spec, check, analysis, findings, written=(), loaded=None) -> str:
    """The human summary of ``gearkit contact``."""
    g = check.geometry
    z2 = "rack" if g.kind == "rack" else f"z2 = {spec.teeth2}"
    unit = "mm" if analysis.units == "mm" else "rad"
    counts = analysis.pairs_in_contact
    inter = analysis.interference
    lines = [
        f"gearkit contact: {g.kind} pair, z1 = {spec.teeth1}, {z2}, m_n = {g.module:g} mm, a_w = "
        f"{g.center_distance:.4f} mm; {len(analysis.driver_angle)} steps per cycle"
        + (f", {analysis.slices} slices" if analysis.slices > 1 else ""),
        f"  contact ratio   simulated {analysis.contact_ratio:.5f}   formula {g.contact_ratio:.5f}"
        + (f"   total {analysis.total_contact_ratio:.5f} (formula {g.total_contact_ratio:.5f})"
           if analysis.slices > 1 else ""),
        f"  pairs in contact {int(counts.min())}..{int(counts.max())}",
        f"  transmission error  max |TE| {analysis.transmission_error_max:.3e} {unit}, "
        f"peak-to-peak {analysis.transmission_error_pp:.3e} {unit}",
        f"  backlash  {_mm(analysis.backlash)} mm circular, {_mm(analysis.backlash_normal)} mm normal "
        f"(formula {_mm(g.backlash)} mm)",
        "  interference  " + (f"{inter.max_depth:.4g} mm deep, area {inter.area:.3g} mm^2, at "
                              f"{math.degrees(inter.driver_angle):.3f} deg ({', '.join(inter.where)})"
                              if inter.found else "none"),
        "",
    ]
    if loaded is not None:
        lines[-1:-1] = [
            f"  loaded ({loaded.torque:g} N m; {loaded.steps} steps, {loaded.slices} slices): p-p TE "
            f"{loaded.transmission_error_pp * 1e6:.3f} µrad, contact ratio {loaded.contact_ratio_loaded:.3f}, "
            f"max Hertzian pressure {loaded.max_contact_pressure:.0f} MPa, mean mesh stiffness "
            f"{loaded.mesh_stiffness_mean:.2f} N/mm/µm"]
    for f in findings:
        mark = {"fail": "!! FAIL  ", "warn": " ! warn  ", "ok": "   ok    "}[f.status]
        lines.append(f"  {mark}{f.id:<29}{f.message}")
    for path in written:
        lines.append(f"wrote {path}")
    return "\n".join(lines)


if __name__ == "__main__":  # pragma: no cover
    from gearkit.cli import main
    sys.exit(main(["contact", *sys.argv[1:]]))
