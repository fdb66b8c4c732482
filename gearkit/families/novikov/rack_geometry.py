"""The constructed profile of a circular-arc basic rack: its drawing, working arcs and their windows.

:func:`rack_geometry` builds the right flank of tooth 0 of an
:class:`~gearkit.families.novikov.racks.ArcRack` (normal section, module units, the digest's frame:
x along the pitch line, y towards the tooth tip, tooth axis at x = 0, space axis at x = pi/2) from the
tip land, the convex arc, the transition, the concave arc and the root fillet, and so validates it:
a rack whose pieces cannot be joined raises :class:`~gearkit.errors.SpecError` naming the input that
breaks the construction.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from gearkit.errors import require
from gearkit.segments import arc, line

__all__ = ["RackGeometry", "rack_geometry"]

_HALF = math.pi / 2


@dataclass(frozen=True)
class RackGeometry:
    """The constructed profile of an :class:`ArcRack` (module units, digest frame).

    ``drawing`` runs from the tooth axis (x = 0) to the space axis (x = pi/2) as exact
    :class:`~gearkit.segments.Segment` s; ``convex_index`` / ``concave_index`` point at the working arcs
    (None when absent). Windows are the angle ranges (rad) of the working arcs: the contact angle
    can move inside them.
    """

    drawing: tuple
    convex_index: int | None
    concave_index: int | None
    tip_land: float
    root_radius: float
    convex_window: tuple | None
    concave_window: tuple | None

    def points(self):
        """Junction points of the drawing, ``(n+1, 2)``."""
        p = [self.drawing[0].endpoints()[0][0]]
        p += [s.endpoints()[0][1] for s in self.drawing]
        return np.array(p)


def _circle_intersections(c0, r0, c1, r1):
    d = np.asarray(c1, float) - np.asarray(c0, float)
    dist = math.hypot(*d)
    if dist == 0.0 or dist > r0 + r1 or dist < abs(r0 - r1):
        return []
    a = (dist * dist + r0 * r0 - r1 * r1) / (2 * dist)
    h = math.sqrt(max(r0 * r0 - a * a, 0.0))
    base = np.asarray(c0, float) + a * d / dist
    perp = np.array([-d[1], d[0]]) / dist
    return [base + h * perp, base - h * perp]


def _ang(v) -> float:
    return math.atan2(v[1], v[0])


def _tip(rack):
    """Tip land end and the angle where the adjacent arc starts."""
    ha = rack.addendum
    if rack.convex is not None:
        c, r = rack.centre("convex"), rack.convex.radius
        s = (ha - c[1]) / r
        require(-1.0 < s < 1.0, "addendum",
                f"the convex arc (top at y = {c[1] + r:.5f}) does not reach the tip line y = h_a = {ha}")
        th = math.asin(s)
        x = c[0] + r * math.cos(th)
        require(x > 0.0, "convex.centre_offset",
                f"the convex arc meets the tip line at x = {x:.5f}, past the tooth axis: the rack tooth is "
                f"pointed (reduce l_a or h_a)")
        require(th > rack.alpha, "addendum",
                f"the contact point (height {rack.contact_height('convex'):.5f}) is above the tip line h_a = {ha}")
        return x, th
    c, r = rack.centre("concave"), rack.concave.radius
    s = (c[1] - ha) / r
    require(0.0 < s < 1.0, "addendum",
            f"the concave arc must meet the tip line y = h_a = {ha} below its centre (y = {c[1]:.5f}) while "
            "still rising towards the tip")
    ps = math.asin(s)
    x = c[0] - r * math.cos(ps)
    require(0.0 < x < _HALF, "concave.centre_offset",
            f"the concave arc meets the tip line at x = {x:.5f}, outside the half pitch (0, pi/2)")
    require(ps < rack.alpha, "addendum", "the concave contact point is above the tip line")
    return x, ps


def _root_on_circle(rack, oc, rc):
    """Root arc tangent to the concave circle (oc, rc) and the root line; returns (centre, radius, psi_t)."""
    hf = rack.dedendum
    k = -hf - oc[1]
    l_f = oc[0] - _HALF
    y_axis = oc[1] - math.sqrt(max(rc * rc - l_f * l_f, 0.0)) if rc > abs(l_f) else math.inf
    require(y_axis < -hf, "dedendum",
            f"the concave arcs meet at y = {y_axis:.5f} on the space axis, above the root line y = -h_f = {-hf}: "
            "reduce h_f or enlarge the concave arc")
    r_full = (rc * rc - l_f * l_f - k * k) / (2 * k + 2 * rc)
    r = r_full if rack.root_radius is None else rack.root_radius
    require(r <= r_full * (1 + 1e-12), "root_radius",
            f"r_g* = {r} is larger than the full root radius {r_full:.6f} that fits the space")
    cy = -hf + r
    arg = (rc - r) ** 2 - (cy - oc[1]) ** 2
    require(arg >= 0.0, "root_radius", f"a root fillet of r_g* = {r} cannot touch the concave arc")
    cx = min(oc[0] - math.sqrt(arg), _HALF) if rack.root_radius is not None else _HALF
    cg = np.array([cx, cy])
    u = (cg - oc) / math.hypot(*(cg - oc))
    t = oc + rc * u
    psi_t = _ang(oc - t)
    return cg, r, t, psi_t


def _root_on_line(rack, p0, d):
    """Root arc tangent to the flank line (point p0, unit direction d) and the root line."""
    hf = rack.dedendum
    nn = np.array([-d[1], d[0]])  # left of the downward walk: the space side
    if rack.root_radius is None:
        r = ((_HALF - p0[0]) * nn[0] + (-hf - p0[1]) * nn[1]) / (1.0 - nn[1])
        require(r > 0.0, "root_radius", "the flank line leaves no room for a root fillet")
    else:
        r = rack.root_radius
    cy = -hf + r
    t = (p0[1] + r * nn[1] - cy) / -d[1]
    require(t >= -1e-12, "root_radius",
            f"the root fillet r_g* = {r} reaches above the end of the convex arc: reduce it or delta_1")
    foot = p0 + max(t, 0.0) * d
    cg = foot + r * nn
    require(cg[0] <= _HALF + 1e-12, "root_radius",
            f"the root fillet r_g* = {r} does not fit the space (its centre is past the space axis)")
    return np.array([min(cg[0], _HALF), cy]), r, foot


def _transition(rack, x_tip, th_tip, segs):
    """Append convex arc + transition; return (concave start angle psi or None, flank-line data or None)."""
    oa, ra = rack.centre("convex"), rack.convex.radius
    kind = rack.transition
    if kind == "common-tangent":
        of, rf = rack.centre("concave"), rack.concave.radius
        d = math.hypot(*(of - oa))
        require(d > ra + rf, "transition",
                f"the arcs are too close for a common tangent (|O_a O_f| = {d:.5f} <= rho_a + rho_f = {ra + rf})")
        th = _ang(of - oa) + math.acos((ra + rf) / d)
        require(0.0 < th < rack.alpha, "transition",
                f"the common tangent touches the arcs at {math.degrees(th):.4f} deg, not below the contact angle")
        t1 = oa + ra * np.array([math.cos(th), math.sin(th)])
        t2 = of - rf * np.array([math.cos(th), math.sin(th)])
        segs.append(arc(oa, ra, th_tip, th, "flank"))
        segs.append(line(t1, t2, "relief"))
        return th, (th, th_tip), None
    d1 = math.radians(rack.transition_angle_deg)
    e1 = oa + ra * np.array([math.cos(d1), math.sin(d1)])
    segs.append(arc(oa, ra, th_tip, d1, "flank"))
    if kind == "flank-line":
        return None, (d1, th_tip), (e1, np.array([math.sin(d1), -math.cos(d1)]))
    of, rf = rack.centre("concave"), rack.concave.radius
    rj = rack.transition_radius
    cj = e1 + rj * np.array([math.cos(d1), math.sin(d1)])
    hits = _circle_intersections(cj, rj, of, rf)
    require(bool(hits), "transition_radius",
            f"the relief arc r_j* = {rj} tangent at delta_1 = {rack.transition_angle_deg} deg does not reach the "
            "concave arc")
    e2 = min(hits, key=lambda q: q[1])
    psi2 = _ang(of - e2)
    require(0.0 < psi2 < rack.alpha, "transition_radius",
            f"the relief arc meets the concave arc at psi = {math.degrees(psi2):.4f} deg, outside (0, alpha_k): "
            "the concave contact point would be relieved away")
    a0, a1 = _ang(e1 - cj), _ang(e2 - cj)
    require(a0 < a1 < -_HALF and e2[1] < e1[1], "transition_radius",
            "the relief arc does not descend from the convex arc to the concave arc")
    segs.append(arc(cj, rj, a0, a1, "relief"))
    return psi2, (d1, th_tip), None


@lru_cache(maxsize=128)
def rack_geometry(rack) -> RackGeometry:
    """Construct (and so validate) the profile of ``rack``; raises SpecError with the reason.

    ``rack`` is an :class:`~gearkit.families.novikov.racks.ArcRack` (its validated inputs); the
    result is cached per rack.
    """
    x_tip, a_tip = _tip(rack)
    segs = [line((0.0, rack.addendum), (x_tip, rack.addendum), "tip")]
    convex_i = concave_i = None
    cwin = fwin = None
    psi0, flank_line = None, None
    if rack.convex is not None:
        convex_i = 1
        psi0, cwin, flank_line = _transition(rack, x_tip, a_tip, segs)
    else:
        psi0 = a_tip
    if rack.concave is not None:
        of, rf = rack.centre("concave"), rack.concave.radius
        cg, rg, t, psi_t = _root_on_circle(rack, of, rf)
        require(rack.alpha < psi_t < _HALF, "root_radius",
                f"the root fillet reaches the concave arc at psi = {math.degrees(psi_t):.4f} deg, above the "
                "contact point")
        require(psi0 < psi_t, "dedendum", "the concave arc has no length between the transition and the root")
        concave_i = len(segs)
        segs.append(arc(of, rf, psi0 + math.pi, psi_t + math.pi, "flank"))
        fwin = (psi0, psi_t)
        a_start = _ang(t - cg)
    else:
        e1, d = flank_line
        cg, rg, foot = _root_on_line(rack, e1, d)
        if math.hypot(*(foot - e1)) > 1e-12:
            segs.append(line(e1, foot, "relief"))
        a_start = _ang(foot - cg)
    segs.append(arc(cg, rg, a_start, -_HALF, "fillet"))
    if cg[0] < _HALF - 1e-12:
        segs.append(line((cg[0], -rack.dedendum), (_HALF, -rack.dedendum), "root"))
    return RackGeometry(tuple(segs), convex_i, concave_i, x_tip, rg, cwin, fwin)
