"""Page data of a scene: every placed gear turning with the input, its solids and the meshes' checks.

The frames turn the scene's input through ``turn_deg`` degrees; each frame places every gear copy
where :meth:`~gearkit.scene.SceneModel.poses` puts it (kinematics and phasing: planets ride their
carrier and turn about their own axes). The solids (one per distinct gear, built once) move
with the same poses; the findings are those of every mesh's pair check, named by the mesh.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.errors import SpecError
from gearkit.view.page import COLORS, flat, mesh_part


def scene_view(model, frames: int = 180, turn_deg: float = 360.0, title: str | None = None) -> dict:
    """Page data of a :class:`~gearkit.scene.SceneModel` (its input turned through ``turn_deg``).

    Examples
    --------
    >>> from gearkit.scene import Gear, Mesh, Motion, Scene, SceneModel
    >>> s = Scene((Gear("a", 20), Gear("b", 30)), (Mesh("a", "b"),), motion=Motion(inputs={"a": 1}))
    >>> data = scene_view(SceneModel(s), frames=6)
    >>> data["anim"]["frames"], [b["name"] for b in data["anim"]["bodies"]]
    (6, ['a', 'b'])
    """
    angles = turn_deg * np.arange(frames) / frames
    per_frame = [model.poses(float(a)) for a in angles]
    first = per_frame[0]
    bodies, parts, colour = [], [], {}
    for k, pose in enumerate(first):
        prof = model.profile(pose.gear)
        tol = 2e-3 * prof.module
        loops = [prof.outline(tol)]
        if prof.internal:
            t = np.linspace(0.0, 2.0 * math.pi, 241)[:-1]
            loops.insert(0, (prof.root_diameter / 2.0 + 2.0 * prof.module) * np.stack([np.cos(t), np.sin(t)], -1))
        colour.setdefault(pose.gear, COLORS[len(colour) % len(COLORS)])
        poses = [[f[k].rotation, f[k].x, f[k].y] for f in per_frame]
        body = {"name": pose.name, "color": "#1d2b44", "fill": colour[pose.gear] + "88",
                "loops": [flat(lp) for lp in loops], "poses": np.round(poses, 7).tolist()}
        if not prof.internal:
            body["mark"] = [0.0, round(0.55 * prof.root_diameter / 2.0, 5)]
        bodies.append(body)
        part = mesh_part(model.solid(pose.gear), colour[pose.gear], body=k)
        part["name"] = pose.name
        parts.append(part)
    findings = []
    for mc in model.check("formula"):
        for f in mc.check.report.findings:
            findings.append({"status": f.status, "id": f"{mc.label}: {f.id}", "message": f.message})
    summary = [["gears placed", str(len(first))], ["meshes", str(len(model.scene.meshes))],
               ["input turned", f"{turn_deg:g} deg over {frames} frames"]]
    try:
        summary.insert(0, ["ratio (input / output)", str(model.ratio())])
    except SpecError as exc:  # a scene without one input and an output has no ratio: say why
        summary.insert(0, ["ratio", str(exc)])
    anim = {"frames": int(frames), "fps": 30, "bodies": bodies, "contacts": [], "path": [],
            "caption": "the input turning", "tol": None}
    return {"title": title or f"gearkit: scene of {len(model.scene.gears)} gears",
            "subtitle": "every gear placed and phased by the scene's layout, turning with its kinematics",
            "summary": summary, "findings": findings, "anim": anim, "parts3d": parts}
