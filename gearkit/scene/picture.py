"""A picture of a placed scene: every gear copy's generated outline where the scene puts it (PNG or
SVG, matplotlib with the Agg backend, written atomically).

A ring is drawn as its tooth outline inside a rim band; carriers as a line from their axis to
each planet; each axis is labelled with its gears' names and tooth numbers.
"""
from __future__ import annotations

import math

__all__ = ["scene_figure", "write_picture"]

_COLOURS = ("#4c78a8", "#f58518", "#54a24b", "#b279a2", "#e45756", "#72b7b2", "#eeca3b", "#9d755d")


def scene_figure(model, angle_deg: float = 0.0, title: str | None = None):
    """A matplotlib Figure of ``model``'s placed outlines (a :class:`~gearkit.scene.SceneModel`)."""
    import matplotlib
    matplotlib.use("Agg")
    import numpy as np
    from matplotlib.figure import Figure
    from matplotlib.patches import Circle, PathPatch, Polygon
    from matplotlib.path import Path

    scene = model.scene
    colour = {g.name: _COLOURS[i % len(_COLOURS)] for i, g in enumerate(scene.gears)}
    fig = Figure(figsize=(7.0, 7.0), dpi=120)
    ax = fig.add_subplot(1, 1, 1)
    extent = 0.0
    labels = {}
    poses = {p.name: p for p in model.poses(angle_deg)}
    for name, pts in model.outlines(angle_deg):
        pose = poses[name]
        gear = scene.gear(pose.gear)
        extent = max(extent, float(np.abs(pts).max()))
        if gear.internal:
            r_out = float(np.hypot(pts[:, 0] - pose.x, pts[:, 1] - pose.y).max()) + 2.0 * scene.module_of(gear)
            t = np.linspace(0, 2 * math.pi, 361)[:-1]
            rim = np.column_stack([pose.x + r_out * np.cos(t), pose.y + r_out * np.sin(t)])
            verts = np.vstack([rim, rim[:1], pts[::-1], pts[-1:]])
            codes = ([Path.MOVETO] + [Path.LINETO] * (len(rim) - 1) + [Path.CLOSEPOLY]
                     + [Path.MOVETO] + [Path.LINETO] * (len(pts) - 1) + [Path.CLOSEPOLY])
            ax.add_patch(PathPatch(Path(verts, codes), facecolor=colour[pose.gear], edgecolor="k", lw=0.4, alpha=0.55))
            extent = max(extent, r_out + math.hypot(pose.x, pose.y))
            ax.annotate(f"{pose.gear} (z = {gear.teeth})", (pose.x, pose.y - r_out), fontsize=8, ha="center",
                        va="top")
        else:
            ax.add_patch(Polygon(pts, closed=True, facecolor=colour[pose.gear], edgecolor="k", lw=0.4, alpha=0.85))
            ax.add_patch(Circle((pose.x, pose.y), 0.6 * scene.module_of(gear), color="k"))
            labels.setdefault((round(pose.x, 6), round(pose.y, 6)), []).append(f"{name} z{gear.teeth}")
    for (x, y), names in labels.items():  # gears sharing an axis (stepped, stacked) share one label
        ax.annotate("\n".join(names), (x, y), fontsize=7, ha="center", va="bottom", xytext=(0, 4),
                    textcoords="offset points", bbox=dict(boxstyle="round,pad=0.2", fc="white", alpha=0.7, lw=0))
    layout = model.layout()
    for carrier in scene.carriers:
        cx, cy = layout.positions[carrier]
        for pose in poses.values():
            if scene.gear(pose.gear).carrier == carrier:
                ax.plot([cx, pose.x], [cy, pose.y], color="#333333", lw=2.0, alpha=0.6)
        ax.annotate(carrier, (cx, cy), fontsize=8, xytext=(6, -14), textcoords="offset points")
    pad = 1.05 * extent
    ax.set_xlim(-pad, pad)
    ax.set_ylim(-pad, pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.grid(True, lw=0.3, color="#dddddd")
    ax.set_title(title or f"Scene: {len(poses)} placed gears, input at {angle_deg:g} deg", fontsize=9)
    fig.tight_layout()
    return fig


def write_picture(path, model, angle_deg: float = 0.0, title: str | None = None):
    """Write the placed outlines to ``path`` (.png or .svg) atomically; returns the path."""
    from pathlib import Path

    from gearkit.errors import SpecError
    from gearkit.export import atomic_write

    fmt = Path(path).suffix.lower().lstrip(".")
    if fmt not in ("png", "svg"):
        raise SpecError("output", f"a scene picture is .png or .svg, not {Path(path).suffix!r}")
    fig = scene_figure(model, angle_deg, title)
    return atomic_write(path, lambda tmp: fig.savefig(tmp, format=fmt))
