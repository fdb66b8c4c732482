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

from gearkit.errors import SpecError, check_fields, is_real, require
from gearkit.families.novikov.rack_geometry import RackGeometry, rack_geometry
from gearkit.segments import Segment, arc, corner, line, transform_chain

__all__ = ["ArcSpec", "ArcRack", "HEIGHT_TOL", "TRANSITIONS"]

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
        require(is_real(self.radius) and 0.0 < self.radius <= 10.0, "radius",
                f"{self.radius!r} must be in (0, 10] (module units)")
        require(is_real(self.centre_shift) and abs(self.centre_shift) <= 2.0, "centre_shift",
                f"{self.centre_shift!r} must be in [-2, 2] (module units)")
        require(is_real(self.centre_offset) and -5.0 <= self.centre_offset <= 10.0, "centre_offset",
                f"{self.centre_offset!r} must be in [-5, 10] (module units)")


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
        require(is_real(a) and 5.0 < a < 45.0, "contact_angle_deg", f"{a!r} must be in (5, 45) degrees")
        require(is_real(self.addendum) and 0.0 <= self.addendum <= 3.0, "addendum",
                f"h_a* = {self.addendum!r} must be in [0, 3] (module units)")
        require(is_real(self.dedendum) and 0.0 < self.dedendum <= 3.0, "dedendum",
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
            require(is_real(d) and 0.0 < d < a, "transition_angle_deg",
                    f"delta_1 = {d!r} must be in (0, alpha_k = {a}) degrees: the convex arc must reach below "
                    f"the contact point, and a flank perpendicular to the pitch line (delta_1 = 0) generates no "
                    f"envelope")
        if self.transition == "relief-arc":
            r = self.transition_radius
            require(is_real(r) and 0.0 < r <= 5.0, "transition_radius",
                    f"r_j* = {r!r} must be in (0, 5] (module units)")
        if self.root_radius is not None:
            require(is_real(self.root_radius) and self.root_radius > 0.0, "root_radius",
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

        Same frame and walking direction as :meth:`gearkit.families.involute.BasicRack.half_tooth`: u along the
        pitch line, v away from the gear centre, gear tooth centred at u = 0, cutter tooth centred at
        u = p/2 pointing to -v; the chain runs from the cutter tip (the gear's root, extended ``extend*p``
        past the space axis) to the cutter root (extended past the tooth axis), tool material on the
        right. Above the gear's tip line the flank continues along its tangent (that part never touches
        a blank whose tip circle is at most d + 2 h_a m).
        """
        return transform_chain(_unit_chain(self, extend), np.diag([module, module]))


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
