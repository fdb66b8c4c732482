"""Circular-arc (Novikov, Wildhaber-Novikov) basic racks: parametric, validated, as kernel tools.

A circular-arc basic rack is drawn in its normal section, in module units, in the frame of the
reference digest: x along the pitch line, y towards the tip of the basic-rack tooth (the gear
tooth), tooth axis at x = 0, space axis at x = pi/2, pitch pi, material below the profile. Only the
right flank of tooth 0 (0 <= x <= pi/2) is drawn; the rack is its mirror image and period.

The profile, from the tooth axis to the space axis:

1. tip land ``y = h_a`` (the gear's tip);
2. **convex addendum arc**, radius rho_a, centre ``O_a = (-l_a, x_a)`` (beyond the tooth axis);
3. **transition**: ``"relief-arc"`` (an arc of radius r_j tangent to the convex arc at the angle
   delta_1, meeting the concave arc at a corner; the relief that keeps a double-arc rack out of line
   contact with its mate), ``"common-tangent"`` (the internal common tangent of the two arcs: near
   line contact, reference only), ``"flank-line"`` (a line tangent to the convex arc at delta_1, for a
   rack without a concave arc) or ``"none"`` (a rack without a convex arc);
4. **concave dedendum arc**, radius rho_f, centre ``O_f = (pi/2 + l_f, x_f)`` (beyond the space axis);
5. root: an arc tangent to the flank and to the root line ``y = -h_f`` (``root_radius = None``: the
   full radius, tangent to both flanks of the space), then the root land.

Every working point has the contact angle alpha_k: the convex contact is
``K_a = O_a + rho_a (cos a_k, sin a_k)`` at height ``h_k = rho_a sin a_k + x_a``, the concave one
``K_f = O_f - rho_f (cos a_k, sin a_k)`` at depth ``rho_f sin a_k - x_f``.

A :class:`RackSystem` names the rack of each gear of a pair: one rack for both gears (double-arc,
one hob), or a convex pinion rack and a concave wheel rack (single-arc). Presets are data, in
``gearkit/data/novikov_racks.toml``; a user's rack file has the same format (:func:`load_rack_system`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from gearkit.errors import SpecError, check_fields, require
from gearkit.errors import is_real as _num
from gearkit.tools import Segment, arc, corner, line, transform_chain

__all__ = ["ArcSpec", "ArcRack", "RackGeometry", "TRANSITIONS", "rack_geometry"]

TRANSITIONS = ("relief-arc", "common-tangent", "flank-line", "none")
#: contact heights of mating arcs must agree to this (module units)
HEIGHT_TOL = 1e-4
_HALF = math.pi / 2



@dataclass(frozen=True)
class ArcSpec:
    """One working arc of a circular-arc rack, module units.

    Parameters
    ----------
    radius : float, > 0
        rho_a* (convex) or rho_f* (concave).
    centre_shift : float
        x_a* / x_f*: height of the arc centre above the pitch line (towards the tooth tip).
    centre_offset : float
        l_a* / l_f*: how far the centre lies beyond the tooth axis (convex arc) or beyond the space
        axis (concave arc).
    """

    radius: float
    centre_shift: float = 0.0
    centre_offset: float = 0.0

    def __post_init__(self):
        check_fields(self)
        require(_num(self.radius) and 0.0 < self.radius <= 10.0, "radius",
                f"{self.radius!r} must be in (0, 10] (module units)")
        require(_num(self.centre_shift) and abs(self.centre_shift) <= 2.0, "centre_shift",
                f"{self.centre_shift!r} must be in [-2, 2] (module units)")
        require(_num(self.centre_offset) and -5.0 <= self.centre_offset <= 10.0, "centre_offset",
                f"{self.centre_offset!r} must be in [-5, 10] (module units)")


@dataclass(frozen=True)
class RackGeometry:
    """The constructed profile of an :class:`ArcRack` (module units, digest frame).

    ``drawing`` runs from the tooth axis (x = 0) to the space axis (x = pi/2) as exact
    :class:`~gearkit.tools.Segment` s; ``convex_index`` / ``concave_index`` point at the working arcs
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


@dataclass(frozen=True)
class ArcRack:
    """A circular-arc basic rack (normal section, module units). See the module docstring.

    Parameters
    ----------
    contact_angle_deg : float, degrees, in (5, 45)
        alpha_k: the profile angle at the contact points.
    addendum : float, in [0, 3]
        h_a*: height of the tip land above the pitch line.
    dedendum : float, in (0, 3]
        h_f*: depth of the root line below the pitch line.
    convex, concave : ArcSpec or None
        The addendum (convex) and dedendum (concave) working arcs; at least one.
    transition : {"relief-arc", "common-tangent", "flank-line", "none"}
        How the convex arc continues towards the root (see the module docstring).
    transition_radius : float or None
        r_j* of a ``"relief-arc"``.
    transition_angle_deg : float or None, degrees
        delta_1: where the convex arc ends (``"relief-arc"``, ``"flank-line"``).
    root_radius : float or None
        Root fillet radius r_g*; None = the full radius.
    name, title, provenance : str
        Labels shown in reports. They are inputs like the rest (two racks that differ only in their
        labels are different specs), so a cached result never carries another rack's labels.
    verified : bool
        False for parameters not checked against the standard text.
    """

    contact_angle_deg: float
    addendum: float
    dedendum: float
    convex: ArcSpec | None = None
    concave: ArcSpec | None = None
    transition: str = "relief-arc"
    transition_radius: float | None = None
    transition_angle_deg: float | None = None
    root_radius: float | None = None
    name: str = "custom"
    title: str = ""
    provenance: str = "user"
    verified: bool = False

    def __post_init__(self):
        check_fields(self)
        a = self.contact_angle_deg
        require(_num(a) and 5.0 < a < 45.0, "contact_angle_deg", f"{a!r} must be in (5, 45) degrees")
        require(_num(self.addendum) and 0.0 <= self.addendum <= 3.0, "addendum",
                f"h_a* = {self.addendum!r} must be in [0, 3] (module units)")
        require(_num(self.dedendum) and 0.0 < self.dedendum <= 3.0, "dedendum",
                f"h_f* = {self.dedendum!r} must be in (0, 3] (module units)")
        for name in ("convex", "concave"):
            v = getattr(self, name)
            require(v is None or isinstance(v, ArcSpec), name, "must be an ArcSpec or None")
        require(self.convex is not None or self.concave is not None, "convex",
                "a circular-arc rack needs a convex arc, a concave arc or both")
        require(self.transition in TRANSITIONS, "transition",
                f"{self.transition!r} is not one of {', '.join(TRANSITIONS)}")
        both = self.convex is not None and self.concave is not None
        if both:
            require(self.transition in ("relief-arc", "common-tangent"), "transition",
                    f"a rack with both arcs joins them by 'relief-arc' or 'common-tangent', not {self.transition!r}")
        elif self.convex is not None:
            require(self.transition == "flank-line", "transition",
                    "a convex-only rack continues below its arc with a 'flank-line'")
        else:
            require(self.transition == "none", "transition", "a concave-only rack has no transition ('none')")
        if self.transition in ("relief-arc", "flank-line"):
            d = self.transition_angle_deg
            require(_num(d) and 0.0 < d < a, "transition_angle_deg",
                    f"delta_1 = {d!r} must be in (0, alpha_k = {a}) degrees: the convex arc must reach below "
                    f"the contact point, and a flank perpendicular to the pitch line (delta_1 = 0) generates no "
                    f"envelope")
        if self.transition == "relief-arc":
            r = self.transition_radius
            require(_num(r) and 0.0 < r <= 5.0, "transition_radius",
                    f"r_j* = {r!r} must be in (0, 5] (module units)")
        if self.root_radius is not None:
            require(_num(self.root_radius) and self.root_radius > 0.0, "root_radius",
                    f"r_g* = {self.root_radius!r} must be positive (or None for the full radius)")
        if both:
            require(self.concave.radius > self.convex.radius, "concave.radius",
                    f"rho_f = {self.concave.radius} must exceed rho_a = {self.convex.radius}: the concave arc "
                    f"must be larger than the convex one it mates with (equal radii run in line contact)")
            ha, hf = self.contact_height("convex"), self.contact_height("concave")
            require(abs(ha - hf) <= HEIGHT_TOL, "concave.centre_shift",
                    f"the contact heights disagree: convex {ha:.6f}, concave {hf:.6f} (module units); they must "
                    f"agree within {HEIGHT_TOL:g} (x_f = rho_f sin a_k - h_k = "
                    f"{self.concave.radius * math.sin(self.alpha) - ha:.6f} matches the convex arc)")
            j = self.backlash
            require(j > 0.0, "concave.centre_offset",
                    f"the built-in backlash j* = {j:.6f} must be positive (j = 2 (rho_f - rho_a) cos a_k - "
                    f"2 (l_f - l_a); reduce l_f)")
        rack_geometry(self)  # raises SpecError with the reason when the profile cannot be built

    # -- derived values (module units) ---------------------------------------------------
    @property
    def alpha(self) -> float:
        """alpha_k, rad."""
        return math.radians(self.contact_angle_deg)

    @property
    def kind(self) -> str:
        """``"double-arc"``, ``"convex"`` or ``"concave"``."""
        if self.convex is not None and self.concave is not None:
            return "double-arc"
        return "convex" if self.convex is not None else "concave"

    def centre(self, which: str) -> np.ndarray:
        """Centre ``O_a`` (``"convex"``) or ``O_f`` (``"concave"``), module units."""
        s = self._arc(which)
        if which == "convex":
            return np.array([-s.centre_offset, s.centre_shift])
        return np.array([_HALF + s.centre_offset, s.centre_shift])

    def _arc(self, which):
        s = getattr(self, which)
        if s is None:
            raise SpecError(which, f"the {self.name} rack has no {which} arc")
        return s

    def contact_point(self, which: str) -> np.ndarray:
        """K_a (convex, above the pitch line) or K_f (concave, below it), module units."""
        s = self._arc(which)
        d = np.array([math.cos(self.alpha), math.sin(self.alpha)])
        return self.centre(which) + (d if which == "convex" else -d) * s.radius

    def contact_height(self, which: str) -> float:
        """h_k*: distance of the contact point from the pitch line (positive), module units."""
        return abs(float(self.contact_point(which)[1]))

    def contact_thickness(self) -> float:
        """s_a*: chordal tooth thickness at the convex contact height (2 x of K_a)."""
        return 2.0 * float(self.contact_point("convex")[0])

    def contact_space(self) -> float:
        """e_f*: space width at the concave contact depth (2 (pi/2 - x of K_f))."""
        return 2.0 * (_HALF - float(self.contact_point("concave")[0]))

    @property
    def backlash(self) -> float:
        """j*: built-in backlash of a double-arc rack run with itself (e_f* - s_a*)."""
        return self.contact_space() - self.contact_thickness()

    @property
    def geometry(self) -> "RackGeometry":
        return rack_geometry(self)

    def half_tooth(self, module: float, extend: float = 0.02):
        """The cutter tooth half facing the gear tooth, in the kernel's rack frame, mm.

        Same frame and walking direction as :meth:`gearkit.tools.BasicRack.half_tooth`: u along the
        pitch line, v away from the gear centre, gear tooth centred at u = 0, cutter tooth centred at
        u = p/2 pointing to -v; the chain runs from the cutter tip (the gear's root, extended ``extend*p``
        past the space axis) to the cutter root (extended past the tooth axis), tool material on the
        right. Above the gear's tip line the flank continues along its tangent (that part never touches
        a blank whose tip circle is at most d + 2 h_a m).
        """
        return transform_chain(_unit_chain(self, extend), np.diag([module, module]))


# ----------------------------------------------------------------------------- construction

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
def rack_geometry(rack: ArcRack) -> RackGeometry:
    """Construct (and so validate) the profile of ``rack``; raises SpecError with the reason."""
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


# ----------------------------------------------------------------------------- kernel tool chain

def _reverse(seg: Segment) -> Segment:
    if seg.kind == "line":
        x0, y0, x1, y1 = seg.data
        return line((x1, y1), (x0, y0), seg.label)
    cx, cy, r, a0, a1 = seg.data
    return arc((cx, cy), r, a1, a0, seg.label)


@lru_cache(maxsize=128)
def _unit_chain(rack: ArcRack, extend: float):
    """Tool chain at module 1 (see :meth:`ArcRack.half_tooth`)."""
    g = rack_geometry(rack)
    draw = list(g.drawing)
    body = [_reverse(s) for s in draw[1:]][::-1]  # root .. flank, walking towards the tooth axis
    first = body[0]
    dx = extend * math.pi
    if first.kind == "line":  # root land: extend past the space axis
        _, y0, x1, y1 = first.data
        body[0] = line((_HALF + dx, y0), (x1, y1), first.label)
    else:  # full-radius root centred on the space axis: continue the arc (its mirror image)
        cx, cy, r, a0, a1 = first.data
        body[0] = arc((cx, cy), r, a0 + 0.25 * (a0 - a1), a1, first.label)
    # above the tip line: continue along the flank tangent, then the cutter root line
    tip_pt, tip_t = body[-1].endpoints()
    t_up = tip_t[1]
    rise = 0.25
    length = min(rise / max(t_up[1], 1e-3), 1.0)
    top = tip_pt[1] + length * t_up
    chain = []
    for k, seg in enumerate(body):
        if chain:
            prev_end, prev_t = chain[-1].endpoints()
            start, start_t = seg.endpoints()
            turn = prev_t[1][0] * start_t[0][1] - prev_t[1][1] * start_t[0][0]
            if abs(turn) > 1e-12 or float(np.dot(prev_t[1], start_t[0])) < 0:
                chain.append(corner(start[0], prev_t[1], start_t[0], seg.label if turn < 0 else chain[-1].label))
        chain.append(seg)
    chain.append(line(tip_pt[1], top, "tip"))
    chain.append(corner(top, t_up, (-1.0, 0.0), "tip"))
    chain.append(line(top, (-dx, top[1]), "tip"))
    return tuple(chain)
