"""``gearkit demo``: the main job on a built-in design, end to end.

Generates a 13/40 spur pair (m = 2 mm, x1 = 0.3) by simulating its rack cutter, writes the
two profiles (SVG and DXF) into an output folder, and prints the gear values and the pair's
design check.
"""
from __future__ import annotations

from pathlib import Path

DEFAULT = {"z1": 13, "z2": 40, "module": 2.0, "x1": 0.3, "x2": 0.0, "width": 20.0}


def register(subparsers) -> None:
    p = subparsers.add_parser("demo", help="run the main job on a built-in 13/40 spur pair",
                              description=run_demo.__doc__)
    p.add_argument("--out-dir", default="gearkit-demo", help="folder for the files written (default ./gearkit-demo)")
    p.set_defaults(run=run_demo)


def run_demo(args) -> int:
    """Generate a 13/40 spur pair (m = 2 mm, x1 = 0.3, x2 = 0) by simulating the rack cutter, write the
    profiles (SVG, DXF) and the solids (STL, face width 20 mm), and print gear values and the design
    check (lengths in mm)."""
    from gearkit.checks import check_pair
    from gearkit.cli.check import format_report
    from gearkit.cli.gear import format_summary
    from gearkit.export import write_profile
    from gearkit.pair import PairSpec
    from gearkit.solids import SolidSpec, default_mesh_tol, gear_solid

    out = Path(args.out_dir)
    out.mkdir(parents=True, exist_ok=True)
    d = DEFAULT
    tol = 1e-3 * d["module"]
    written = []
    # the geometry checked is the geometry exported: the pair's own gears (tips shortened as the check has them)
    result = check_pair(PairSpec(d["z1"], d["z2"], d["module"], d["x1"], d["x2"], face_width=d["width"]))
    for name, prof in zip(("pinion", "wheel"), result.profiles):
        info = prof.summary(tol)
        print(format_summary(info))
        print()
        for ext in ("svg", "dxf"):
            written.append(write_profile(out / f"{name}.{ext}", [prof.outline(tol)], info))
        solid = gear_solid(prof, SolidSpec(width=d["width"]), default_mesh_tol(d["module"]), name=name)
        written.append(solid.export(out / f"{name}.stl"))
    print(format_report(result))
    print()
    print("wrote " + ", ".join(str(p) for p in written))
    return 0 if result.ok else 1
