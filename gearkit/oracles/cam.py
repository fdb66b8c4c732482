"""Swept-follower oracle for cams: the cam is what the follower leaves of a blank disc.

Nothing here shares code with the envelope path. The follower's positions relative to the cam
are written out again from the frames of :class:`~gearkit.families.cam.CamSpec` (the cam turning
counter-clockwise by ``phi``; a translating follower's reference point at ``(e, H0 + s)``, a
rocker's roller centre at ``O2 + l (-cos Psi, sin Psi)``, a flat face on the line ``y = r0 + s``),
rotated back by ``-phi`` into the cam frame at ``steps`` equal cam angles. Each position becomes a
polygon (the roller as a regular ``sides``-gon on its circle, the knife as a wedge of half-angle
45 degrees opening along the follower, the face as a long slab) and all of them are subtracted
from a disc with 2D polygon booleans (manifold3d's
cross sections). What remains is scalloped between positions and faceted by the polygons: the
oracle boundary lies outside the exact cam by at most the polygon's sag ``r (1 - cos(pi/sides))``
plus the scallop between positions (about ``d^2/(8 r)`` for roller centres ``d`` apart; the
corner between two face lines ``dphi`` apart stands ``rho dphi^2/8`` out; the notch between two
wedge tips ``d`` apart is ``d/2`` deep).
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["swept_cam", "oracle_error_bound"]


def _positions(spec, phi):
    """Reference point (roller centre, knife tip; a face's foot point) in the fixed frame, and
    for a rocker the arm angle, at cam angles ``phi``."""
    s = spec.motion.evaluate(phi)[0]
    if spec.follower == "translating":
        h0 = spec.prime_radius if spec.contact == "flat" else math.sqrt(spec.prime_radius ** 2 - spec.offset ** 2)
        return np.stack([np.full_like(s, spec.offset), h0 + s], -1), None
    l0, arm, r0 = spec.pivot_distance, spec.arm_length, spec.prime_radius
    if spec.contact == "flat":
        psi = math.asin(r0 / l0) + s / arm
    else:
        psi = math.acos((l0 * l0 + arm * arm - r0 * r0) / (2 * l0 * arm)) + s / arm
    centre = np.stack([l0 - arm * np.cos(psi), arm * np.sin(psi)], -1)
    return centre, psi


def _to_cam(points, phi):
    c, s = math.cos(-phi), math.sin(-phi)
    return np.stack([c * points[:, 0] - s * points[:, 1], s * points[:, 0] + c * points[:, 1]], -1)


def swept_cam(spec, steps: int = 720, sides: int = 64):
    """The cam the swept follower leaves: its outer boundary, ``(n, 2)`` mm, cam frame.

    Parameters
    ----------
    spec : CamSpec
    steps : int, follower positions over one turn
    sides : int, sides of each roller polygon (a knife tip is a disc of 1e-6 of the prime radius)
    """
    import manifold3d as m3

    phi = 2.0 * math.pi * np.arange(steps) / steps
    ref, psi = _positions(spec, phi)
    big = 4.0 * (spec.prime_radius + spec.motion.stroke + (spec.pivot_distance or 0.0) + abs(spec.offset))
    a = 2.0 * math.pi * np.arange(sides) / sides
    unit = np.stack([np.cos(a), np.sin(a)], -1)
    cutters = []
    for k in range(steps):
        if spec.contact == "flat":
            if spec.follower == "translating":
                y0 = ref[k, 1]
                slab = np.array([[-big, y0], [big, y0], [big, y0 + big], [-big, y0 + big]])
            else:  # the face along the arm, through the pivot; the cam on its left
                o2 = np.array([spec.pivot_distance, 0.0])
                d = np.array([-math.cos(psi[k]), math.sin(psi[k])])
                left = np.array([-d[1], d[0]])
                slab = np.array([o2 - big * d, o2 + big * d, o2 + big * d - big * left, o2 - big * d - big * left])
            cutters.append(_to_cam(slab, phi[k]))
        elif spec.contact == "knife":
            tip = ref[k]
            if spec.follower == "translating":
                up = np.array([0.0, 1.0])
            else:  # along the arm, away from the pivot
                up = (tip - np.array([spec.pivot_distance, 0.0])) / spec.arm_length
            side = np.array([-up[1], up[0]])
            wedge = np.array([tip, tip + big * (up + side), tip + big * (up - side)])
            cutters.append(_to_cam(wedge[::-1] if _area(wedge) < 0 else wedge, phi[k]))
        else:
            cutters.append(_to_cam(ref[k] + spec.roller_radius * unit, phi[k]))
    blank = m3.CrossSection([0.5 * big * unit])
    left = blank - m3.CrossSection(cutters, m3.FillRule.NonZero)
    loops = [np.asarray(lp, dtype=float) for lp in left.to_polygons()]
    inside = [lp for lp in loops if _winds(lp)]
    if not inside:
        raise ValueError("the swept follower leaves nothing of the blank around the cam axis")
    return min(inside, key=lambda p: abs(_area(p)))  # the cam: the smallest loop around the axis


def _winds(p) -> bool:
    """True when the closed polygon ``p`` goes round the origin (even-odd ray test along +x)."""
    x0, y0 = p[:, 0], p[:, 1]
    x1, y1 = np.roll(x0, -1), np.roll(y0, -1)
    cross = (y0 > 0) != (y1 > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        xs = x0 + (0.0 - y0) * (x1 - x0) / (y1 - y0)
    return bool(np.count_nonzero(cross & (xs > 0)) % 2)


def _area(p):
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def oracle_error_bound(spec, steps: int = 720, sides: int = 64) -> float:
    """How far (mm) the oracle's boundary may stand outside the exact cam: polygon sag plus the
    scallop between consecutive roller positions (largest centre step over the turn)."""
    phi = 2.0 * math.pi * np.arange(steps + 1) / steps
    ref, _ = _positions(spec, phi)
    cam = np.stack([_to_cam(ref[k:k + 1], phi[k])[0] for k in range(len(phi))])
    step = float(np.linalg.norm(np.diff(cam, axis=0), axis=1).max())
    if spec.contact == "knife":
        return step / 2.0
    if spec.contact == "flat":
        _, _, acc, _ = spec.motion.evaluate(phi)
        rho = spec.prime_radius + spec.motion.stroke + float(np.abs(acc).max())
        return rho * (2.0 * math.pi / steps) ** 2 / 8.0
    r = spec.roller_radius
    return r * (1.0 - math.cos(math.pi / sides)) + step * step / (8.0 * r)
