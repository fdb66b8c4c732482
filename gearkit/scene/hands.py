"""Helix hands of a scene: every gear's signed helix angle, spread along its meshes.

A given helix angle is kept; the others follow from the meshes (an external mesh reverses the hand,
an internal one keeps it, a rack takes its pinion's); gears on one shaft do not constrain each
other (stepped gears may differ). Two meshing gears that break the rule raise
:class:`~gearkit.errors.SpecError` naming them.
"""
from __future__ import annotations

import math

from gearkit.errors import require

__all__ = ["helix_angles"]


def helix_angles(scene) -> dict:
    """Signed helix angle of every gear of ``scene`` (a :class:`~gearkit.scene.model.Scene`), degrees:
    given ones kept, the others from their meshes (an external mesh reverses the hand, an internal one
    keeps it; a rack takes its pinion's).

    Raises SpecError naming the gears when two meshing gears break that rule.
    """
    given = {g.name: float(g.helix_angle_deg) for g in scene.gears if g.helix_angle_deg is not None}
    out = dict(given)
    links = {g.name: [] for g in scene.gears}
    for m in scene.meshes:
        sign = 1.0 if scene.mesh_kind(m) in ("internal", "rack") else -1.0
        links[m.first].append((m.second, sign))
        links[m.second].append((m.first, sign))
    seeds = [g.name for g in scene.gears if g.name in given] + [g.name for g in scene.gears]
    for seed in seeds:  # given hands spread first; a set with none takes the scene's angle
        if seed in out and seed not in given:
            continue
        out.setdefault(seed, float(scene.helix_angle_deg))
        stack = [seed]
        while stack:  # shafts do not constrain hands (stepped gears may differ)
            name = stack.pop()
            for other, sign in links[name]:
                if other not in out:
                    out[other] = sign * out[name]
                    stack.append(other)
    for m in scene.meshes:
        sign = 1.0 if scene.mesh_kind(m) in ("internal", "rack") else -1.0
        a, b = out[m.first], out[m.second]
        if scene.mesh_kind(m) == "rack":
            continue
        require(math.isclose(b, sign * a, abs_tol=1e-9), "meshes",
                f"{m.first} (beta = {a:g} deg) and {m.second} (beta = {b:g} deg) mesh but break the helix "
                f"rule: an {scene.mesh_kind(m)} mesh needs {'the same' if sign > 0 else 'opposite'} hands "
                "and equal helix angles")
    return out
