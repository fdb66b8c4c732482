"""Independent oracles for the cycloidal family: swept pins and rolled circles.

Nothing here shares code with the envelope path. The kinematics are written out again from
the textbook's and the reference digest's frames (crank-fixed inversion for the pin-wheel
drive: the pin wheel turns phi, the disc turns ``Z_b/Z_g phi`` about its centre at ``(0, e)``;
external rolling for pin gearing), the pins are placed at discrete steps, and the uncut
boundary is found by casting rays from the blank's centre against every pin circle (exact
circle-ray intersections, no meshing equation): a disc inside the pins ends where a ray first
enters a pin, a ring outside them where it last leaves one. The result is scalloped between
pin positions; the scallop height is about ``step**2 / (8 r)`` for a pin of radius ``r`` whose
centre moves ``step`` between positions. Rolled-circle constructions (for clock gearing) roll
a circle by the equal-arc rule with rotation matrices.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["swept_pin_disc", "swept_pin_disc_centres", "swept_pin_disc_clearance", "swept_pin_wheel", "swept_pin_centres", "swept_pin_clearance", "clock_addendum_by_rolling", "ray_cast"]


def ray_cast(centres, radius: float, psi, outside: bool = False):
    """Boundary radius along rays from the origin at polar angles ``psi`` (from +y towards +x).

    ``outside=False``: where each ray first enters any circle (the material is inside all of
    them); ``outside=True``: where it last leaves one (the material is outside). ``inf`` / 0 where
    a ray meets no circle. ``centres`` ``(k, 2)`` mm, ``psi`` ``(n,)`` rad; returns ``(n,)`` mm.
    """
    u = np.stack([np.sin(psi), np.cos(psi)], -1)
    c = np.asarray(centres, dtype=float)
    b = u @ c.T
    disc = b * b - (np.einsum("ij,ij->i", c, c) - radius * radius)[None, :]
    hit = disc >= 0
    sq = np.sqrt(np.where(hit, disc, 0.0))
    if outside:
        t = np.where(hit, b + sq, -np.inf)
        return np.maximum(t.max(axis=1), 0.0)
    t = np.where(hit & (b - sq > 0), b - sq, np.inf)
    return t.min(axis=1)


def _fold(points, teeth: int, margin: float):
    """Turn points into tooth 0's sector by multiples of the pitch; keep those near it."""
    pitch = 2.0 * math.pi / teeth
    ang = np.arctan2(points[:, 0], points[:, 1])
    k = np.round(ang / pitch)
    a = ang - k * pitch
    rad = np.hypot(points[:, 0], points[:, 1])
    out = [np.stack([rad * np.sin(a + j * pitch), rad * np.cos(a + j * pitch)], -1) for j in (-1, 0, 1)]
    out = np.concatenate(out)
    keep = np.abs(np.arctan2(out[:, 0], out[:, 1])) <= math.pi / teeth + margin
    return out[keep]


def swept_pin_disc_centres(pins: int, lobes: int, pin_circle_radius: float, pin_radius: float, eccentricity: float,
                           step: float):
    """Pin centres relative to the disc (disc frame, lobe 0 on +y, folded into tooth 0's sector and
    its neighbours), ``(k, 2)`` mm; ``step`` (mm) bounds the pin centre's move between consecutive
    positions relative to the disc."""
    zb, zg, big_r, e = pins, lobes, pin_circle_radius, eccentricity
    dz = zb - zg
    # one pin pitch of the pin wheel covers every relative position up to the disc's symmetry
    speed = big_r * abs(zb / zg - 1.0) + e * abs(zb / zg)  # bound on |d(pin centre)/d phi| in the disc
    n = max(2, int(math.ceil(2.0 * math.pi / zb * speed / step)) + 1)
    phi = np.linspace(0.0, 2.0 * math.pi / zb, n)
    a = phi[:, None] + 2.0 * math.pi * np.arange(zb)[None, :] / zb  # pin-wheel angle of pin k
    pa = np.broadcast_to(zb / zg * phi[:, None], a.shape)           # disc angle
    x, y = -big_r * np.sin(a), big_r * np.cos(a) - e                # pin centre relative to the disc centre
    cx = np.cos(pa) * x + np.sin(pa) * y                            # ... in the disc's own frame
    cy = -np.sin(pa) * x + np.cos(pa) * y
    if dz > 0:  # the reference frame has a tooth space on +y: turn it by half a pitch
        h = math.pi / zg
        cx, cy = cx * math.cos(h) + cy * math.sin(h), -cx * math.sin(h) + cy * math.cos(h)
    return _fold(np.stack([cx.ravel(), cy.ravel()], -1), zg, 2.0 * pin_radius / (big_r - e) + 0.1)


def swept_pin_disc(pins: int, lobes: int, pin_circle_radius: float, pin_radius: float, eccentricity: float,
                   psi, step: float):
    """Radii of the disc (dz > 0) or ring (dz < 0) the swept pins leave, at polar angles ``psi``
    about the disc centre, lobe 0 on +y. ``step`` (mm) bounds the pin centre's move between
    consecutive positions relative to the disc. One radius per ray: where the disc is not
    star-shaped about its centre compare with :func:`swept_pin_disc_clearance` instead."""
    centres = swept_pin_disc_centres(pins, lobes, pin_circle_radius, pin_radius, eccentricity, step)
    return ray_cast(centres, pin_radius, np.asarray(psi, dtype=float), outside=pins < lobes)


def swept_pin_disc_clearance(points, pins: int, lobes: int, pin_circle_radius: float, pin_radius: float,
                             eccentricity: float, step: float, chunk: int = 512):
    """Signed clearance (mm) of disc-frame points (tooth 0's sector) from the swept pins: distance
    to the nearest pin position minus the pin radius, negative inside a pin. On the true disc
    boundary it lies in ``[0, step**2 / (8 r)]`` (the scallop between discrete positions)."""
    c = swept_pin_disc_centres(pins, lobes, pin_circle_radius, pin_radius, eccentricity, step)
    return _clearance(points, c, pin_radius, chunk)


def _clearance(points, centres, radius, chunk):
    p = np.asarray(points, dtype=float)
    out = np.empty(len(p))
    for k in range(0, len(p), chunk):
        d = p[k:k + chunk, None, :] - centres[None, :, :]
        out[k:k + chunk] = np.sqrt(np.einsum("ijk,ijk->ij", d, d).min(axis=1))
    return out - radius


def swept_pin_centres(module: float, pins: int, wheel_teeth: int, pin_radius: float, tip_radius: float,
                      step: float):
    """Pin-centre positions in the wheel's frame (pin gearing), ``(k, 2)`` mm, tooth 0 on +y, folded
    into tooth 0's sector. The pin wheel (pitch radius ``m z1/2``) rolls on the wheel's pitch circle
    (``m z2/2``) externally; consecutive positions are at most ``step`` (mm) apart."""
    r1, r2 = module * pins / 2.0, module * wheel_teeth / 2.0
    reach = math.acos(max(-1.0, ((r1 + r2) ** 2 + r1 * r1 - (tip_radius + pin_radius) ** 2) / (2 * r1 * (r1 + r2))))
    span = reach + 2.0 * math.pi / pins
    n = max(2, int(math.ceil(2 * span * (r1 + r2) / step)) + 1)
    phi1 = np.linspace(-span, span, n)  # pin wheel's turn from the line of centres
    phi2 = -phi1 * r1 / r2              # the wheel turns the other way
    # pin at the pole at phi1 = 0 would sit in a space centred on +y; half a wheel pitch turns
    # the space to polar angle pi/z2
    cx = r1 * np.sin(phi1)
    cy = (r1 + r2) - r1 * np.cos(phi1)
    ang = phi2 + math.pi / wheel_teeth
    px = cx * np.cos(ang) + cy * np.sin(ang)
    py = -cx * np.sin(ang) + cy * np.cos(ang)
    return _fold(np.stack([px, py], -1), wheel_teeth, 2.0 * pin_radius / r2 + 0.1)


def swept_pin_wheel(module: float, pins: int, wheel_teeth: int, pin_radius: float, tip_radius: float, psi,
                    step: float):
    """Radii of the wheel the pins of a pin wheel leave (pin gearing), at polar angles ``psi``,
    tooth 0 on +y, inside the tip circle; ``step`` bounds the pin centre's move (mm).

    A ray gives one radius per angle, the first entry into a pin: where the boundary is not
    star-shaped about the centre the ray misses the outer crossings. The space bottom (the pin at
    the pole) does that next to the pitch circle whenever the flank is trimmed above the radius
    ``sqrt(r2^2 - rho^2)`` at which rays touch that pin: compare there with
    :func:`swept_pin_clearance`, which has no such limit.
    """
    centres = swept_pin_centres(module, pins, wheel_teeth, pin_radius, tip_radius, step)
    return np.minimum(ray_cast(centres, pin_radius, np.asarray(psi, dtype=float)), tip_radius)


def swept_pin_clearance(points, module: float, pins: int, wheel_teeth: int, pin_radius: float,
                        tip_radius: float, step: float, chunk: int = 512):
    """Signed clearance (mm) of points (wheel frame, tooth 0's sector) from the swept pins: the
    distance to the nearest pin position minus the pin radius, negative inside a pin (material a
    pin removes). On the true envelope it lies in ``[0, step**2 / (8 rho)]`` (the pins sit at
    discrete positions ``step`` apart, the scallop between them)."""
    c = swept_pin_centres(module, pins, wheel_teeth, pin_radius, tip_radius, step)
    return _clearance(points, c, pin_radius, chunk)


def clock_addendum_by_rolling(pinion_teeth: int, wheel_teeth: int, module: float = 1.0) -> float:
    """Theoretical clock-wheel addendum A (module units) by rolling a circle.

    A circle of diameter equal to the pinion's pitch radius rolls without slip on the outside of
    the wheel's pitch circle. The traced point starts on the pitch circle a quarter pitch from the
    tooth's centre line; at each roll ``s`` the contact point is ``s`` along the pitch circle and
    the traced point ``s`` back along the rolling circle (equal arcs). A is the height above the
    pitch circle where the traced point crosses the centre line.
    """
    from gearkit.roots import brentq

    r2 = module * wheel_teeth / 2.0
    a = module * pinion_teeth / 4.0
    g0 = math.pi / (2.0 * wheel_teeth)

    def rot(v, ang):
        c, s = math.cos(ang), math.sin(ang)
        return np.array([[c, -s], [s, c]]) @ v

    def traced(s):
        g = g0 - s / r2                                  # polar angle of the contact (towards the centre line)
        k = r2 * np.array([math.sin(g), math.cos(g)])   # contact point
        c = (r2 + a) * np.array([math.sin(g), math.cos(g)])
        return c + rot(k - c, s / a)                    # equal arc on the rolling circle, behind the contact

    def polar(s):
        p = traced(s)
        return math.atan2(p[0], p[1])
    s_hi = math.pi * a  # half a turn of the rolling circle: the traced point's farthest
    s = brentq(polar, 1e-12 * r2, s_hi, xtol=1e-15, rtol=1e-15)
    return (float(np.hypot(*traced(s))) - r2) / module
