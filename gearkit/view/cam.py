"""Page data of a disc cam: the cam turning, its follower riding on it, the contact point, the lift.

Ground frame: the cam turns counter-clockwise about the origin by its angle ``phi``; the
follower's pose in the ground is the cam's generating motion (:attr:`CamProfile.motion`, the
follower frame carried into the cam frame) turned back by ``phi``. The contact point comes from
the exact envelope (:meth:`CamProfile.contact`); the trace is the follower's lift over one turn
with the pressure angle beside it. The solids: the cam (:func:`~gearkit.solids.cam.cam_solid`)
and the follower's roller, turning and moving with the same poses.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.view.page import COLORS, findings_rows, flat, mesh_part

#: frames per cam turn
TURN_FRAMES = 240


def _follower_loops(prof) -> list:
    """The follower in its own frame as closed loops: the roller (a circle at the reference point),
    the knife (a tip at it) or the flat face (along y = 0; a rocker's from its pivot outward),
    with a stem for a translating follower."""
    spec = prof.spec
    ref = np.asarray(prof.reference, dtype=float)
    thin = 0.02 * spec.prime_radius
    if spec.contact == "roller":
        t = np.linspace(0.0, 2.0 * math.pi, 97)[:-1]
        loops = [ref + spec.roller_radius * np.stack([np.cos(t), np.sin(t)], -1)]
        top = ref + (0.0, spec.roller_radius)
    elif spec.contact == "flat":  # the tool's own line, centred where it touches at cam angle 0
        half = 0.6 * (spec.prime_radius + spec.stroke)
        seg = prof.tool.evaluate(np.array([0.0, 1.0]))[0]
        d = (seg[1] - seg[0]) / np.linalg.norm(seg[1] - seg[0])
        n = np.array([-d[1], d[0]])
        mid = prof.contact(np.array([0.0]))[2][0]
        loops = [mid + np.array([-half * d - thin * n, half * d - thin * n, half * d + thin * n,
                                 -half * d + thin * n])]
        top = mid + thin * n
    else:
        w = 3.0 * thin
        loops = [ref + np.array([[0.0, 0.0], [w, 2.0 * w], [-w, 2.0 * w]])]
        top = ref + (0.0, 2.0 * w)
    if spec.follower == "translating":
        w, h = 2.5 * thin, 0.3 * spec.prime_radius
        loops.append(top + np.array([[-w, 0.0], [w, 0.0], [w, h], [-w, h]]))
    return loops


def cam_view(spec, width: float | None = None, frames: int = TURN_FRAMES, tol: float | None = None) -> dict:
    """Page data of a cam (:class:`~gearkit.families.cam.CamSpec`): the mechanism turning, its solids
    and the cam's check.

    Examples
    --------
    >>> from gearkit.families.cam import CamSpec, MotionProgram
    >>> cam = CamSpec(40.0, MotionProgram.rise_dwell_return(10.0, 90.0, 30.0, 90.0), roller_radius=8.0)
    >>> data = cam_view(cam, frames=24)
    >>> data["anim"]["frames"], [b["name"] for b in data["anim"]["bodies"]]
    (24, ['cam', 'follower'])
    """
    from gearkit.checks.cam import check_cam
    from gearkit.families.cam import cam_profile
    from gearkit.solids import SolidSpec, prism_solid
    from gearkit.solids.cam import cam_solid

    prof = cam_profile(spec)
    check = check_cam(spec)
    scale = spec.prime_radius + spec.stroke
    tol = 1e-3 * scale if tol is None else tol
    phi = 2.0 * math.pi * np.arange(frames) / frames
    origin = prof.motion.to_blank(np.zeros((frames, 2)), phi)
    axis = prof.motion.to_blank(np.tile([1.0, 0.0], (frames, 1)), phi) - origin
    c, s = np.cos(phi), np.sin(phi)
    ground = np.stack([c * origin[:, 0] - s * origin[:, 1], s * origin[:, 0] + c * origin[:, 1]], -1)
    turn = np.mod(phi + np.arctan2(axis[:, 1], axis[:, 0]) + math.pi, 2.0 * math.pi) - math.pi
    follower = np.column_stack([turn, ground])
    q = prof.contact(phi)[0]
    touch = np.stack([c * q[:, 0] - s * q[:, 1], s * q[:, 0] + c * q[:, 1]], -1)
    lift = spec.motion.evaluate(phi)[0]
    from gearkit.families.cam.follower import law_pressure_angle

    alpha = np.degrees(law_pressure_angle(spec, phi))
    bodies = [{"name": "cam", "color": "#1d2b44", "fill": COLORS[0] + "88",
               "loops": [flat(prof.outline(tol))], "poses": np.column_stack([phi, 0 * phi, 0 * phi]).round(7).tolist(),
               "mark": [0.0, round(0.5 * prof.radii()[0], 5)]},
              {"name": "follower", "color": "#1d2b44", "fill": COLORS[1] + "88",
               "loops": [flat(lp) for lp in _follower_loops(prof)], "poses": np.round(follower, 7).tolist()}]
    anim = {"frames": int(frames), "fps": 30, "bodies": bodies, "contacts": [flat(p[None]) for p in touch],
            "path": flat(touch), "tol": tol,
            "trace": {"label": "follower motion s (the motion law)",
                      "xlabel": "cam angle, deg", "x": flat(np.degrees(phi), 4), "y": flat(lift, 6),
                      "label2": "pressure angle, deg", "y2": [round(float(v), 2) for v in alpha]},
            "caption": f"cam turning, {spec.follower} {spec.contact} follower"}
    b = width or 0.3 * spec.prime_radius
    parts = [mesh_part(cam_solid(prof, SolidSpec(b), tol), COLORS[0], body=0)]
    if spec.contact == "roller":
        ref, r = np.asarray(prof.reference, float), spec.roller_radius

        def half(a0, ref=ref, r=r):
            return lambda w: ref + r * np.stack([np.cos(a0 + np.pi * np.asarray(w)), np.sin(a0 + np.pi * np.asarray(w))],
                                               -1)
        roller = prism_solid([half(0.0), half(np.pi)], SolidSpec(b), tol, name="roller")
        parts.append(mesh_part(roller, COLORS[1], body=1))
    summary = [[k.replace("_", " "), f"{v:.6g}" if isinstance(v, float) else str(v)]
               for k, v in check.values.items() if isinstance(v, (int, float)) and not isinstance(v, bool)]
    return {"title": f"gearkit: disc cam, prime radius {spec.prime_radius:g} mm, stroke {spec.stroke:g}",
            "subtitle": f"{spec.follower} follower with a {spec.contact} contact; the cam turns counter-clockwise",
            "summary": summary, "findings": findings_rows(check.report.findings), "anim": anim, "parts3d": parts}
