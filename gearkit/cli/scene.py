"""``gearkit scene``: a scene file's kinematics, layout and mesh checks at a fidelity; export.

Usage::

    gearkit scene FILE.toml [--json] [--fidelity formula|generated|simulated|solid] [--state S]
                  [--angle DEG] [--tol T] [--width W] [-o scene.glb|scene.obj|scene.stl|scene.png|scene.svg]

Prints the degrees of freedom, the ratio input/output (exact), every member's speed with the
input at 1, planet speeds relative to their carriers, mesh frequencies, each state's ratio, the
per-gear tips, the planets' radii, angles and neighbour clearance, each mesh's checks at the
fidelity, and what was built. ``-o`` writes every placed part as a named node (planets turned
with the carrier by ``--angle``): solids for .glb/.obj/.stl, the placed outlines for .png/.svg.
Exit status: 0 no mesh fails, 1 one fails, 2 bad input or I/O.
"""
from __future__ import annotations

from pathlib import Path

from gearkit.cli.common import QUANTITIES, add_json_flag, add_output_flag, add_tol_flag, print_json


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "scene", help="several placed gears from a TOML file: ratios, speeds, mesh checks, export",
        description="Model a scene file (gears with identity, shafts, carriers, meshes, motion, states) lazily: "
                    "the kinematics need no geometry; the mesh checks build only what --fidelity needs "
                    "(formula: no tooth; generated: one profile per distinct gear; simulated: one meshing "
                    "simulation per mesh; solid: one solid per distinct gear and the 3D interference of every "
                    "mesh). Lengths in mm, angles in degrees.",
        epilog="Exit status: 0 no mesh fails, 1 one fails, 2 bad input or I/O.")
    p.add_argument("file", help="scene file (TOML; see the README's scene section)")
    p.add_argument("--fidelity", choices=("formula", "generated", "simulated", "solid"), default="formula",
                   help="what the mesh checks build (default formula: no tooth)")
    p.add_argument("--state", default=None, help="report the motion of this state (a [states.NAME] table)")
    p.add_argument("--angle", type=float, default=0.0, metavar="DEG",
                   help="input angle for the export and the 3D interference, degrees (default 0)")
    add_tol_flag(p, "max deviation of outlines and solids from the exact teeth, mm (default 0.005 m for solids, "
                 "0.001 m for outlines)")
    p.add_argument("--width", type=QUANTITIES["width"], default=None, help="face width of the solids, mm (default: the scene's "
                   "face_width, else 8 m)")
    add_output_flag(p, "write the placed scene: .glb, .obj, .stl, .3mf, .step (solids, named parts), .png, .svg "
                    "(outlines) or .html (a page: the scene turning, its solids and checks)")
    add_json_flag(p)
    p.set_defaults(run=run)


def run(args) -> int:
    from gearkit.scene import load_scene
    from gearkit.scene.query import SceneModel
    from gearkit.scene.report import format_report, scene_report

    page = args.output is not None and str(args.output).lower().endswith((".html", ".htm"))
    scene = load_scene(args.file)
    model = SceneModel(scene, tol=args.tol, width=args.width, state=args.state)
    if args.output is not None and not page:
        from gearkit.cli.shell import bound_step

        bound_step(args.output, model.parts(args.angle) if args.output.lower().endswith((".step", ".stp")) else [])
    rep = scene_report(model, args.fidelity, args.angle, args.state, None if page else args.output)
    if page:  # the page: every gear turning with the input, the solids, the meshes' checks
        from gearkit.view import write_page
        from gearkit.view.scene import scene_view

        rep["file"] = str(write_page(args.output, scene_view(model, title=f"gearkit: {Path(args.file).name}")))
    if args.json:
        print_json(rep)
    else:
        print(format_report(rep, Path(args.file).name))
    return 0 if rep["ok"] else 1
