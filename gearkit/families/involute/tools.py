"""The involute family's generating tools: the basic rack (hob) and the shaper cutter.

Tool specs (:class:`BasicRack`, :class:`ShaperCutter`) hold inputs in module units and
build their edges on request for a given module, as chains of exact
:class:`~gearkit.segments.Segment` (:mod:`gearkit.segments`), the tooth-facing half of one tooth
walked with the tool material on the right.
"""
from __future__ import annotations

import math
from dataclasses import field

import numpy as np

from gearkit.errors import SpecError, check_fields, require
from gearkit.segments import Segment, arc, corner, line
from gearkit.values import frozen

# ----------------------------------------------------------------------------- basic rack

_ISO53 = {"A": (1.25, 0.38), "B": (1.25, 0.30), "C": (1.25, 0.25), "D": (1.40, 0.39)}
#: the ISO 53 basic rack profiles (letters)
ISO53_PROFILES = tuple(_ISO53)


#: smallest pressure angle of a cutter, degrees: below it a flank is nearly radial and the undercut
#: limit (2 / sin^2 alpha teeth) runs to millions of teeth (1e-12 degrees exhausted the memory)
MIN_PRESSURE_ANGLE_DEG = 1.0

@frozen
class BasicRack:
    """Generating (basic) rack in module units, normal section.

    Parameters
    ----------
    pressure_angle_deg : float, degrees, in (0, 45)
        Profile angle alpha_P of the straight flank.
    addendum : float
        h_aP*: the rack addendum (the gear's addendum), above the datum line.
    dedendum : float
        h_fP*: the rack dedendum (the gear's dedendum; the cutter's addendum).
    fillet_radius : float or None
        rho_fP*: root fillet of the rack = tip rounding of the cutter. ``None`` gives the
        largest that fits, c*/(1 - sin alpha) (= 0.379951 for c* = 0.25, alpha = 20 deg).
    protuberance : float
        pr*: normal distance by which a protuberance flank stands proud of the main flank at
        the cutter tip (0 = none). It undercuts the gear's root on purpose (grinding stock).
    protuberance_angle_deg : float or None
        Profile angle of the protuberance flank (steeper than the main flank); default
        alpha - 10 degrees.
    name : str
        Label shown in reports.

    Examples
    --------
    >>> BasicRack.iso53("A").dedendum
    1.25
    >>> round(BasicRack().fillet, 6)
    0.379951
    """

    pressure_angle_deg: float = 20.0
    addendum: float = 1.0
    dedendum: float = 1.25
    fillet_radius: float | None = None
    protuberance: float = 0.0
    protuberance_angle_deg: float | None = None
    name: str = field(default="basic rack", compare=False)

    def __post_init__(self):
        check_fields(self)
        a = self.pressure_angle_deg
        require(MIN_PRESSURE_ANGLE_DEG <= a < 45.0, "pressure_angle_deg",
                f"{a!r} is outside the allowed range [{MIN_PRESSURE_ANGLE_DEG:g}, 45) degrees")
        require(math.isfinite(self.addendum) and 0.0 < self.addendum <= 3.0, "addendum",
                f"h_aP* = {self.addendum!r} must be in (0, 3] (module units)")
        require(math.isfinite(self.dedendum) and self.addendum <= self.dedendum <= 4.0, "dedendum",
                f"h_fP* = {self.dedendum!r} must be in [addendum = {self.addendum}, 4] (module units)")
        half_tip = math.pi / 4 - self.dedendum * math.tan(self.alpha)
        require(half_tip > 0, "dedendum",
                f"h_fP* = {self.dedendum} leaves the cutter no tip at {a} degrees "
                f"(needs h_fP* < {math.pi / 4 / math.tan(self.alpha):.4f})")
        if self.fillet_radius is not None:
            r = self.fillet_radius
            require(math.isfinite(r) and 0.0 <= r <= self.max_fillet, "fillet_radius",
                    f"rho_fP* = {r!r} must be in [0, {self.max_fillet:.6f}] (the largest rounding that "
                    f"fits the cutter tip)")
        require(math.isfinite(self.protuberance) and 0.0 <= self.protuberance < 0.2, "protuberance",
                f"pr* = {self.protuberance!r} must be in [0, 0.2) (module units)")
        if self.protuberance > 0:
            ap = self.alpha_protuberance
            require(0.0 <= ap < self.alpha, "protuberance_angle_deg",
                    f"{math.degrees(ap)!r} must be in [0, {a}) degrees (steeper than the flank)")
            require(self._protuberance_top() < self.dedendum + self.addendum, "protuberance",
                    "the protuberance flank does not meet the main flank inside the cutter")
            require(self.fillet * (1 - math.sin(ap)) < self._protuberance_top(), "fillet_radius",
                    f"rho_fP* = {self.fillet:.6f} reaches above the protuberance flank (needs < "
                    f"{self._protuberance_top() / (1 - math.sin(ap)):.6f})")

    @classmethod
    def iso53(cls, profile: str) -> "BasicRack":
        """ISO 53 basic rack profile ``"A"``, ``"B"``, ``"C"`` or ``"D"`` (alpha = 20 deg, h_aP* = 1)."""
        key = str(profile).upper().removeprefix("ISO53").strip()
        if key not in _ISO53:
            raise SpecError("rack", f"unknown ISO 53 profile {profile!r}; allowed: A, B, C, D")
        hf, rho = _ISO53[key]
        return cls(20.0, 1.0, hf, rho, name=f"ISO 53 {key}")

    @property
    def alpha(self) -> float:
        """Pressure angle, rad."""
        return math.radians(self.pressure_angle_deg)

    @property
    def alpha_protuberance(self) -> float:
        ang = self.protuberance_angle_deg
        return math.radians(self.pressure_angle_deg - 10.0 if ang is None else ang)

    @property
    def clearance(self) -> float:
        """c* = h_fP* - h_aP*."""
        return self.dedendum - self.addendum

    @property
    def max_fillet(self) -> float:
        """Largest tip rounding that fits the cutter tip (the two roundings meet at its centre)."""
        a = self.alpha_protuberance if self.protuberance > 0 else self.alpha
        half_tip = math.pi / 4 - self.dedendum * math.tan(self.alpha) + self.protuberance / math.cos(self.alpha)
        return max(half_tip, 0.0) / math.tan(math.pi / 4 - a / 2)

    @property
    def fillet(self) -> float:
        """The tip rounding actually used (rho_fP*, module units)."""
        if self.fillet_radius is not None:
            return self.fillet_radius
        rho = min(self.clearance / (1 - math.sin(self.alpha)), self.max_fillet)
        if self.protuberance > 0:  # and leave the protuberance flank a tenth of its height
            rho = min(rho, 0.9 * self._protuberance_top() / (1 - math.sin(self.alpha_protuberance)))
        return rho

    @property
    def straight_height(self) -> float:
        """Depth below the datum line where the cutter's straight (main) flank ends, module units.

        Equals h_aP* for the default rounding; enters the undercut limit x_min = h - z sin^2(a)/2.
        """
        if self.protuberance > 0:
            return self.dedendum - self._protuberance_top()
        return self.dedendum - self.fillet * (1 - math.sin(self.alpha))

    @property
    def protuberance_height(self) -> float:
        return self._protuberance_top() if self.protuberance > 0 else 0.0

    @property
    def protuberance_top(self) -> float:
        """Height (module units) above the cutter tip line where the protuberance flank meets the main flank."""
        return self._protuberance_top()

    def _protuberance_top(self) -> float:
        """Height above the cutter tip line where the protuberance flank meets the main flank."""
        a, ap = self.alpha, self.alpha_protuberance
        return self.protuberance / (math.cos(a) * (math.tan(a) - math.tan(ap)))

    def half_tooth(self, module: float, shift: float = 0.0, thinning: float = 0.0, extend: float = 0.02):
        """The cutter tooth half facing the gear tooth, in the rack frame, mm.

        Frame: u along the pitch line (the gear's rolling line), v away from the gear centre,
        origin where the gear's tooth centre line meets the pitch line. The datum line is at
        ``v = shift`` (mm); the cutter tooth is centred at ``u = p/2`` and points to -v. The
        chain runs from the tip centre (extended ``extend*p`` past it) up the left flank to the
        root line (extended past the tooth-space centre ``u = 0``).

        Parameters
        ----------
        module : float, mm (normal module)
        shift : float, mm (x*m, positive away from the gear centre)
        thinning : float, mm, the gear tooth's thickness reduction on the reference line
        """
        m = module
        p = math.pi * m
        a = self.alpha
        ta = math.tan(a)
        v_tip = shift - self.dedendum * m
        v_root = shift + self.dedendum * m
        rho = self.fillet * m
        dx = extend * p

        def u_flank(v):  # left flank of the cutter tooth centred at p/2
            return p / 2 - (p / 4 + (v - shift) * ta + thinning / 2)

        segs = []
        if self.protuberance > 0:
            ap = self.alpha_protuberance
            pr = self.protuberance * m
            u_pr_tip = u_flank(v_tip) - pr / math.cos(a)
            v_x = v_tip + self._protuberance_top() * m

            def u_prot(v):
                return u_pr_tip - (v - v_tip) * math.tan(ap)
            side_angle, side_u = ap, u_prot
        else:
            side_angle, side_u = a, u_flank
        # tip rounding tangent to the tip line and the (protuberance) flank
        v_c = v_tip + rho
        u_c = side_u(v_c) + rho / math.cos(side_angle)
        require(u_c <= p / 2 + 1e-12 * p, "fillet_radius",
                f"the tip rounding {self.fillet:.6f} does not fit the cutter tip")
        n_side = (-math.cos(side_angle), -math.sin(side_angle))
        p_side = (u_c + rho * n_side[0], v_c + rho * n_side[1])
        segs.append(line((p / 2 + dx, v_tip), (u_c, v_tip), "root"))
        segs.append(arc((u_c, v_c), rho, -math.pi / 2, side_angle - math.pi, "fillet"))
        up = (-math.sin(a), math.cos(a))
        if self.protuberance > 0:
            upp = (-math.sin(ap), math.cos(ap))
            p_x = (u_flank(v_x), v_x)
            segs.append(line(p_side, p_x, "fillet"))
            segs.append(corner(p_x, upp, up, "fillet"))
            segs.append(line(p_x, (u_flank(v_root), v_root), "flank"))
        else:
            segs.append(line(p_side, (u_flank(v_root), v_root), "flank"))
        top = (u_flank(v_root), v_root)
        segs.append(corner(top, up, (-1.0, 0.0), "tip"))
        segs.append(line(top, (-dx, v_root), "tip"))
        return tuple(segs)


# ----------------------------------------------------------------------------- shaper cutter

@frozen
class ShaperCutter:
    """Pinion-type (shaper) cutter: a gear-shaped tool whose flanks are involutes.

    Lengths in module units (the module is the gear's).

    Parameters
    ----------
    teeth : int, >= 6
        z0.
    pressure_angle_deg : float, degrees, in (0, 45)
    shift : float
        x0, the cutter's own profile shift (its tooth thickness is m(pi/2 + 2 x0 tan a)).
    addendum : float
        h_a0*: cutter tip radius r_a0 = m(z0/2 + x0 + h_a0*) (cuts the gear's root).
    dedendum : float
        h_f0*: cutter root radius r_f0 = m(z0/2 + x0 - h_f0*).
    tip_radius : float
        rho_a0*: rounding of the cutter tip corners (0 = sharp, the textbook's model).
    """

    teeth: int
    pressure_angle_deg: float = 20.0
    shift: float = 0.0
    addendum: float = 1.25
    dedendum: float = 1.25
    tip_radius: float = 0.0

    def __post_init__(self):
        check_fields(self, 'cutter.')
        require(isinstance(self.teeth, (int, np.integer)) and 6 <= self.teeth <= 1000, "cutter.teeth",
                f"{self.teeth!r} must be an integer in [6, 1000]")
        a = self.pressure_angle_deg
        require(MIN_PRESSURE_ANGLE_DEG <= a < 45.0, "cutter.pressure_angle_deg",
                f"{a!r} is outside [{MIN_PRESSURE_ANGLE_DEG:g}, 45) degrees")
        require(math.isfinite(self.shift) and -1.0 <= self.shift <= 1.5, "cutter.shift",
                f"x0 = {self.shift!r} must be in [-1, 1.5]")
        require(math.isfinite(self.addendum) and 0.5 <= self.addendum <= 2.0, "cutter.addendum",
                f"h_a0* = {self.addendum!r} must be in [0.5, 2]")
        require(math.isfinite(self.dedendum) and 0.5 <= self.dedendum <= 2.0, "cutter.dedendum",
                f"h_f0* = {self.dedendum!r} must be in [0.5, 2]")
        require(math.isfinite(self.tip_radius) and 0.0 <= self.tip_radius <= 0.5, "cutter.tip_radius",
                f"rho_a0* = {self.tip_radius!r} must be in [0, 0.5]")
        # the cutter tooth must not be pointed below its tip circle
        from gearkit.curves import inv
        alpha = math.radians(a)
        rb = self.teeth * math.cos(alpha) / 2
        ra = self.teeth / 2 + self.shift + self.addendum
        half = (math.pi / 2 + 2 * self.shift * math.tan(alpha)) / self.teeth + inv(alpha) \
            - inv(math.acos(min(1.0, rb / ra)))
        require(half * ra > self.tip_radius * 1.01, "cutter.addendum",
                f"the cutter tooth is pointed below its tip circle (tip half-thickness {half * ra:.4f} m)")
        require(self.teeth / 2 + self.shift - self.dedendum > 0.5, "cutter.dedendum",
                "the cutter root circle must have a positive radius")

    def half_tooth(self, module: float, alpha: float, extend: float = 0.02, module_radial: float | None = None):
        """The right half of one cutter tooth in the cutter's own frame, mm.

        Frame: cutter centre at the origin, tooth centred on +y. The chain runs from the tip
        centre (extended past it) clockwise over the tip, down the right flank (involute of the
        base circle; below the base circle a radial line) and along the root circle to past the
        centre of the next tooth space.

        ``module`` and ``alpha`` are those of the section being generated (transverse for a
        helical gear); radial sizes (addendum, dedendum, shift, tip radius) are in units of
        ``module_radial`` (the normal module; default ``module``).
        """
        from gearkit.curves import inv

        m = module
        mr = m if module_radial is None else module_radial
        z0 = self.teeth
        rb = m * z0 * math.cos(alpha) / 2
        ra = m * z0 / 2 + mr * (self.shift + self.addendum)
        rf = m * z0 / 2 + mr * (self.shift - self.dedendum)
        rho = self.tip_radius * mr
        big_s = (math.pi / 2 + 2 * self.shift * (mr / m) * math.tan(alpha)) / z0 + inv(alpha)
        gamma = math.pi / 2 - big_s
        t_a = math.sqrt((ra / rb) ** 2 - 1.0)
        d_ext = extend * 2 * math.pi / z0

        def inv_pt(t):
            c, s = math.cos(gamma + t), math.sin(gamma + t)
            return np.array([rb * (c + t * s), rb * (s - t * c)]), np.array([s, -c])

        if rho > 0:
            from gearkit.curves import bracketed_root

            def gap(t):
                p, n = inv_pt(t)
                return math.hypot(*(p - rho * n)) - (ra - rho)
            t_c = bracketed_root(gap, 0.0, t_a)
            p_c, n_c = inv_pt(t_c)
            centre = p_c - rho * n_c
            a_tip = math.atan2(centre[1], centre[0])
        else:
            t_c = t_a
            p_c, n_c = inv_pt(t_a)
            a_tip = math.atan2(p_c[1], p_c[0])
        segs = [arc((0.0, 0.0), ra, math.pi / 2 + d_ext, a_tip, "root")]
        if rho > 0:
            segs.append(arc(centre, rho, a_tip, math.atan2(n_c[1], n_c[0]), "fillet"))
        else:
            t_in = np.array([math.sin(a_tip), -math.cos(a_tip)])
            segs.append(corner(p_c, t_in, np.array([n_c[1], -n_c[0]]), "fillet"))
        t_f = math.sqrt((rf / rb) ** 2 - 1.0) if rf > rb else 0.0
        segs.append(Segment("involute", (0.0, 0.0, rb, gamma, 1.0, t_c, t_f), "flank"))
        if rf < rb:
            p0 = np.array([rb * math.cos(gamma), rb * math.sin(gamma)])
            p1 = p0 * rf / rb
            segs.append(line(p0, p1, "tip"))
            a_root = gamma
            t_in = -p0 / rb
        else:
            p1, _ = inv_pt(t_f)
            a_root = math.atan2(p1[1], p1[0])
            t_in = -np.array([math.cos(gamma + t_f), math.sin(gamma + t_f)])
        t_out = np.array([math.sin(a_root), -math.cos(a_root)])
        segs.append(corner(p1, t_in, t_out, "tip"))
        segs.append(arc((0.0, 0.0), rf, a_root, math.pi / 2 - math.pi / z0 - d_ext, "tip"))
        return tuple(segs)

