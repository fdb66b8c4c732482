"""Two profiles placed in mesh: frames, ideal motion, pitch point and the teeth that can touch.

Fixed frame: the driver (gear 1) turns about the origin; the mesh is at the top, on +y. At
driver angle ``phi = 0`` the driver's tooth 0 is centred on +y and the mate (gear 2) shows a
tooth space there.

=============  ==============================================  ===========================
kind           mate                                            mate centre / datum
=============  ==============================================  ===========================
external       external gear                                   ``O2 = (0, a)``
internal       ring (internal gear), driver inside it          ``O2 = (0, -a)``
ring-driver    external gear inside the driver (a ring)        ``O2 = (0, a)``
rack           rack (teeth towards the driver)                 datum line ``y = a``
=============  ==============================================  ===========================

The driver turns counter-clockwise by ``phi``. The mate's position ``delta`` is its rotation
(rad, counter-clockwise) or, for a rack, its displacement along +x (mm), measured from the
ideal motion ``k phi`` (``k = -z1/z2`` external, ``+z1/z2`` internal and ring-driver,
``-r1`` rack with ``r1 = z1 p / 2 pi``). A driver point in a mate's space at offset ``u``
from the space centre (mate units, at ``delta = 0``) stays clear while ``|u + delta| <= w``:
each point bounds ``delta`` to ``[-w - u, w - u]``.

The driven mate lags behind its driver: it rests against the *working* bound, the upper one
when it moves towards negative ``delta`` (``k < 0``) and the lower one otherwise.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.contact.table import TABLE_TOL, CurveTable, WidthTable
from gearkit.contact.tooth import Boundary, HalfWidth, linear_from_y
from gearkit.curves import polar_from_y
from gearkit.errors import GeometryError, SpecError, require

__all__ = ["Mesh", "KINDS"]

KINDS = ("external", "internal", "ring-driver", "rack")


def _is_rack(profile) -> bool:
    return getattr(profile, "teeth", None) is None and hasattr(profile, "pitch")


class Mesh:
    """Two generated profiles in mesh at a centre distance.

    Parameters
    ----------
    gear1 : ToothProfile
        The driver (external or internal), any family.
    gear2 : ToothProfile or rack profile
        The mate. A rack profile has ``pitch`` (mm) and no ``teeth``, its half tooth in the
        rack frame (datum line y = 0, teeth towards +y, tooth 0 centred on x = 0).
    center_distance : float, mm
        a; for a rack, from the driver's axis to the rack's datum line.
    tol : float or None, mm
        Chord tolerance of the polylines that locate contacts before they are refined on the
        exact pieces (default 1e-3 module): features smaller than about ``tol`` may be missed,
        values found are exact.
    tables : bool
        Evaluate both teeth on their tables (:mod:`gearkit.contact.table`: every piece fitted once,
        within ``TABLE_TOL`` of the outer radius, measured) instead of on the exact pieces at every
        step: the same results within ``table_deviation`` (mm), several times faster. ``False``
        evaluates the exact pieces throughout (the reference the tables are tested against).

    Examples
    --------
    >>> from gearkit.families.involute import GearSpec, tooth_profile
    >>> m = Mesh(tooth_profile(GearSpec(20, 1.0)), tooth_profile(GearSpec(40, 1.0)), 30.0)
    >>> m.kind, round(m.pitch_radii[0], 12), m.working
    ('external', 10.0, 1)
    """

    def __init__(self, gear1, gear2, center_distance: float, tol: float | None = None, tables: bool = True):
        require(getattr(gear1, "teeth", None) is not None, "gear1", "the driver must be a gear (a rack cannot turn)")
        a = center_distance
        require(isinstance(a, (int, float, np.floating)) and math.isfinite(a) and a > 0, "center_distance",
                f"{a!r} must be a positive length in mm")
        self.gear1, self.gear2 = gear1, gear2
        self.a = float(a)
        self.module = float(gear1.module)
        self.tol = 1e-3 * self.module if tol is None else float(tol)
        require(math.isfinite(self.tol) and 0 < self.tol <= 0.1 * self.module, "tol",
                f"{tol!r} must be in (0, {0.1 * self.module:g}] mm (a tenth of the module)")
        self.z1 = int(gear1.teeth)
        self.pitch1 = 2.0 * math.pi / self.z1
        if _is_rack(gear2):
            require(not gear1.internal, "gear1", "a ring cannot mesh with a rack")
            self.kind = "rack"
            self.z2 = None
            self.pitch2 = float(gear2.pitch)
            self.ratio = -self.z1 * self.pitch2 / (2.0 * math.pi)
            r_w1 = -self.ratio
            self.centre2 = None
            self.beta0 = self.pitch2 / 2.0
            coords = linear_from_y
        else:
            require(not (gear1.internal and gear2.internal), "gear2", "two rings cannot mesh")
            self.z2 = int(gear2.teeth)
            self.pitch2 = 2.0 * math.pi / self.z2
            if gear2.internal:
                require(self.z2 > self.z1, "gear2", f"the ring needs more teeth than the pinion ({self.z2} <= {self.z1})")
                self.kind, d, toward = "internal", -self.a, 0.0
                r_w1 = self.a * self.z1 / (self.z2 - self.z1)
            elif gear1.internal:
                require(self.z1 > self.z2, "gear2", f"the ring needs more teeth than the pinion ({self.z1} <= {self.z2})")
                self.kind, d, toward = "ring-driver", self.a, 0.0
                r_w1 = self.a * self.z1 / (self.z1 - self.z2)
            else:
                self.kind, d, toward = "external", self.a, math.pi
                r_w1 = self.a * self.z1 / (self.z1 + self.z2)
            self.ratio = (-1.0 if self.kind == "external" else 1.0) * self.z1 / self.z2
            self.centre2 = np.array([0.0, d])
            self.beta0 = self.pitch2 / 2.0 - toward  # mate frame turned so a space faces the mesh
            coords = polar_from_y
        self.working = 1 if self.ratio < 0 else -1
        split = 134217729.0 * self.pitch2  # Veltkamp: 2^27 + 1
        self._pitch_hi = split - (split - self.pitch2)
        self._pitch_lo = self.pitch2 - self._pitch_hi
        self.pitch_point = np.array([0.0, r_w1])
        r_w2 = (self.a - r_w1 if self.kind == "rack" else
                float(np.hypot(*(self.pitch_point - self.centre2))))
        self.pitch_radii = (float(r_w1), float(r_w2))
        self.driver = Boundary(gear1, self.tol)
        self.mate = HalfWidth(gear2, self.pitch2, coords, min(self.tol, 1e-4 * self.module))
        self.offsets = self._window()
        self.half_reach = self._half_reach()
        self.tables = bool(tables)
        #: the tables' largest measured deviation from the exact pieces (mm; 0 without tables)
        self.table_deviation = 0.0
        if self.tables:
            scale = TABLE_TOL * max(abs(self.mate.rho_tip), abs(self.mate.rho_root), self.driver.radius_range[1])
            self.driver.table = CurveTable(self.driver.pieces, scale)
            self.mate.table = WidthTable(self.mate, scale)
            self.table_deviation = max(self.driver.table.achieved, self.mate.table.achieved)
        #: a lower bound of the contact normal's arm about the mate's centre (mm; 1 for a rack, whose
        #: unit is mm), turning normal distances into mate units for the search's safety margins
        self.arm_scale = 0.25 * (1.0 if self.kind == "rack" else min(abs(self.mate.rho_tip), abs(self.mate.rho_root)))
        #: round-off of a contact's position along its normal (mm): a few units in the last place of
        #: the largest coordinate involved
        self.noise = 1e-13 * max(abs(self.mate.rho_tip), abs(self.mate.rho_root), self.driver.radius_range[1], self.a)

    # -- frames -----------------------------------------------------------------------------------
    def teeth(self, phi):
        """Absolute indices ``(n, K)`` of the driver teeth that can touch at ``phi`` ``(n,)``, and their
        frame angles ``theta = phi + 2 pi i / z1`` (rad, counter-clockwise)."""
        phi = np.asarray(phi, dtype=float)
        i0 = np.round(-phi / self.pitch1).astype(int)
        idx = i0[:, None] + self.offsets[None, :]
        return idx, phi[:, None] + idx * self.pitch1

    def to_mate(self, points, phi):
        """Fixed-frame points ``(..., 2)`` at driver angle ``phi`` (broadcast over ``...``): the mate's
        radial coordinate ``rho`` and the offset ``u`` from the nearest space centre (mate units,
        at ``delta = 0``)."""
        p = np.asarray(points, dtype=float)
        return self.to_mate_xy(p[..., 0], p[..., 1], phi)

    def to_mate_xy(self, x, y, phi):
        """:meth:`to_mate` of points given by their coordinates ``x``, ``y`` (arrays of one shape)."""
        phi = np.asarray(phi, dtype=float)
        if self.kind == "rack":
            rho = self.a - y
            psi = self.beta0 + self.ratio * phi - x
        else:
            qx, qy = self._turned(x, y, phi)
            rho, psi = np.hypot(qx, qy), np.arctan2(qx, qy)
        return rho, self.space_offset(psi, self.kind != "rack")

    def to_mate_radius(self, x, y, phi):
        """``rho`` of :meth:`to_mate_xy` alone, to the bit (no offset: no arctangent, no remainder)."""
        if self.kind == "rack":
            return self.a - np.asarray(y, dtype=float)
        return np.hypot(*self._turned(x, y, np.asarray(phi, dtype=float)))

    def _turned(self, x, y, phi):
        """Fixed-frame points relative to the mate's centre, turned into the mate's frame at ``phi``."""
        beta = self.beta0 + self.ratio * phi
        c, s = np.cos(beta), np.sin(beta)
        x, y = x - self.centre2[0], y - self.centre2[1]
        return c * x + s * y, c * y - s * x

    def space_offset(self, psi, polar: bool = False):
        """The offset ``u`` of a periodic coordinate ``psi`` (mate units) from the space centre: ``fmod(psi,
        P)``, moved into ``[0, P)`` when negative, ``- P / 2``, to the bit, without fmod (whose exact
        division costs tens of nanoseconds a value).

        The remainder ``psi - q P`` (``q = trunc(psi / P)``) is formed exactly: ``P = P_hi + P_lo``
        (Veltkamp's split, 26 bits each), so ``q P_hi`` and ``q P_lo`` are exact for ``|q| < 2^26``,
        ``psi - q P_hi`` is exact (Sterbenz: the two lie within a factor 2) and so is the last
        difference, whose exact value is fmod's. The rounded quotient may be one too large (never too
        small); the remainder then has the other sign, ``P`` away from fmod's, and moving it into
        ``[0, P)`` adds the same ``P`` to the same value as after fmod. Larger quotients: fmod (``polar``:
        ``psi`` is an angle of ``arctan2``, within ``pi``, so ``|q| <= pi / P + 1``; a nan passes either way)."""
        pitch, hi, lo = self.pitch2, self._pitch_hi, self._pitch_lo
        q = np.trunc(psi / pitch)
        if not (polar and math.pi / pitch + 1.0 < 2.0 ** 26) and not np.abs(q).max(initial=0.0) < 2.0 ** 26:
            r = np.fmod(psi, pitch)
            return np.where(r < 0, r + pitch, r) - pitch / 2.0
        r = psi - q * hi
        r -= q * lo
        r += pitch * (r < 0)
        r -= pitch / 2.0
        return r

    def frames(self, theta, sigma, phi):
        """Maps from a driver half's own coordinates to the mate's, one per row: driver teeth turned by
        ``theta``, halves ``sigma`` (1 right, -1 left), at driver angles ``phi`` (arrays of one shape).

        The two turns (the driver's by ``theta``, the mate frame's by ``-beta``) are one: ``X = a px -
        b py - ox``, ``Y = c px + d py - oy`` are the mate-frame coordinates of a gear's point (the
        fixed-frame ones for a rack, whose ``rho = a - Y``, ``psi = shift - X``). Returns ``(a, b, c,
        d, ox, oy, shift)`` for :meth:`mate_coords` and :meth:`mate_derivatives` (index rows with
        ``[:, rows]``)."""
        theta, sigma, phi = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (theta, sigma, phi)))
        beta = self.beta0 + self.ratio * phi
        if self.kind == "rack":
            gamma, ox, oy = theta, np.zeros_like(theta), np.zeros_like(theta)
        else:
            gamma = theta - beta
            cb, sb = np.cos(beta), np.sin(beta)
            ox = cb * self.centre2[0] + sb * self.centre2[1]
            oy = cb * self.centre2[1] - sb * self.centre2[0]
        c, s = np.cos(gamma), np.sin(gamma)
        return np.stack([sigma * c, s, sigma * s, c, ox, oy, beta])

    def mate_coords(self, px, py, frame):
        """``rho, u`` (as :meth:`to_mate_xy`) of driver points given in their half's own coordinates,
        through :meth:`frames` ``frame`` (each of its rows broadcast against ``px``, ``py``)."""
        rho, x, y = self.mate_radius(px, py, frame)
        return rho, self.mate_offset(x, y, frame[6])

    def mate_radius(self, px, py, frame):
        """``rho`` of :meth:`mate_coords` and the mate-frame coordinates ``x, y`` it comes from (for
        :meth:`mate_offset`, where ``u`` is wanted)."""
        a, b, c, d, ox, oy, _ = frame
        x, y = a * px - b * py - ox, c * px + d * py - oy
        return (self.a - y if self.kind == "rack" else np.sqrt(x * x + y * y)), x, y  # (hypot's scaling not needed)

    def mate_offset(self, x, y, shift):
        """``u`` of :meth:`mate_coords` from :meth:`mate_radius`'s ``x, y`` (``shift``: the frames' last row, read
        for a rack only)."""
        if self.kind == "rack":
            return self.space_offset(shift - x)
        return self.space_offset(np.arctan2(x, y), True)

    def mate_derivatives(self, p, d1, d2, frame):
        """:meth:`mate_coords` along a driver curve, with the first and second derivatives in its
        parameter, from its points ``p = [px, py]`` and their derivatives ``d1``, ``d2`` (flat arrays):
        ``(rho, rho', rho'', u, u', u'')``."""
        a, b, c, d, ox, oy, shift = frame
        x, y = a * p[0] - b * p[1] - ox, c * p[0] + d * p[1] - oy
        dx, dy = a * d1[0] - b * d1[1], c * d1[0] + d * d1[1]  # the map is affine: its derivatives linear
        ex, ey = a * d2[0] - b * d2[1], c * d2[0] + d * d2[1]
        if self.kind == "rack":  # rho = a - y, psi = shift - x
            return self.a - y, -dy, -ey, self.space_offset(shift - x), -dx, -ex
        r2 = x * x + y * y
        rho = np.sqrt(r2)
        rho_1 = (x * dx + y * dy) / rho
        rho_2 = (dx * dx + dy * dy + x * ex + y * ey - rho_1 * rho_1) / rho
        u_1 = (y * dx - x * dy) / r2  # psi = atan2(x, y): psi' = (y x' - x y') / rho^2
        u_2 = (y * ex - x * ey) / r2 - 2.0 * u_1 * rho_1 / rho
        return rho, rho_1, rho_2, self.space_offset(np.arctan2(x, y), True), u_1, u_2

    def mate_velocity(self, points):
        """Velocity of mate points at fixed-frame ``points`` per unit ``delta`` (mm/rad or 1 for a rack)."""
        p = np.asarray(points, dtype=float)
        if self.kind == "rack":
            return np.broadcast_to(np.array([1.0, 0.0]), p.shape).copy()
        r = p - self.centre2
        return np.stack([-r[..., 1], r[..., 0]], -1)

    def mate_to_fixed(self, points, phi, delta=0.0):
        """Mate-frame points at driver angle ``phi`` and mate position ``delta`` in the fixed frame."""
        p = np.asarray(points, dtype=float)
        if self.kind == "rack":
            shift = self.beta0 + self.ratio * phi + delta
            return np.stack([shift - p[..., 0], self.a - p[..., 1]], -1)
        beta = self.beta0 + self.ratio * phi + delta
        c, s = np.cos(beta), np.sin(beta)
        return np.stack([c * p[..., 0] - s * p[..., 1], s * p[..., 0] + c * p[..., 1]], -1) + self.centre2

    # -- the teeth that can touch --------------------------------------------------------------
    def _window(self):
        """Driver teeth that can reach the mate's teeth, as offsets from the tooth nearest +y."""
        r_lo, r_hi = self.driver.radius_range
        c = self._reach_cosine(np.linspace(r_lo, r_hi, 257))
        if not (c <= 1.0).any():
            raise SpecError("center_distance", f"a = {self.a:g} mm: the teeth of the two gears do not reach "
                            "each other")
        reach = float(np.arccos(np.clip(c[c <= 1.0], -1.0, 1.0)).max())
        half = int(math.ceil(reach / self.pitch1 + 1.0))
        if 2 * half + 1 >= self.z1:
            return np.arange(self.z1) - self.z1 // 2
        return np.arange(-half, half + 1)

    def _reach_cosine(self, r):
        """A driver point at radius ``r`` lies inside the mate's tip circle where the cosine of its polar
        angle (from +y) is at least this (the cosine rule; > 1: never)."""
        rt = self.mate.rho_tip
        if self.kind == "rack":
            return (self.a - rt) / r
        if self.kind == "internal":
            return (rt ** 2 - r ** 2 - self.a ** 2) / (2 * self.a * r)
        return (r ** 2 + self.a ** 2 - rt ** 2) / (2 * self.a * r)

    def _half_reach(self):
        """Frame angles ``theta`` (centre ``(2,)`` and half width ``(2,)``, right and left half, rad)
        outside which no sample of a driver half lies inside the mate's tip circle.

        A sample at radius ``r`` and own polar angle ``alpha`` (from +y towards +x) lies at polar angle
        ``alpha - theta`` once turned, and inside the tip circle where the cosine of that angle is at
        least ``c(r)`` (the cosine rule, as in :meth:`_window`): ``theta`` within ``arccos c`` of
        ``alpha``. The hull of these intervals over the samples, widened by a round-off margin. Also
        the number of leading samples (tip first) the search needs: up to the last one that can lie
        inside the tip circle, and its neighbour (the samples beyond are free at every angle, and so
        are the intervals between them).
        """
        p = self.driver.points
        with np.errstate(divide="ignore", invalid="ignore"):
            c = self._reach_cosine(np.hypot(p[:, 0], p[:, 1]))
        mids, halves = [], []
        for sign in (1.0, -1.0):
            alpha = np.arctan2(sign * p[:, 0], p[:, 1])
            ok = ~(c > 1.0 + 1e-9)  # nan (r = 0) counts as reaching
            if not ok.any():
                mids.append(0.0)
                halves.append(-1.0)
                continue
            span = np.where(np.isfinite(c[ok]), np.arccos(np.clip(c[ok], -1.0, 1.0)), np.pi)
            lo, hi = float(np.min(alpha[ok] - span)), float(np.max(alpha[ok] + span))
            mids.append(0.5 * (lo + hi))
            halves.append(np.pi + 1.0 if hi - lo >= 2 * np.pi - 1e-6 else 0.5 * (hi - lo) + 1e-9)
        reach = np.flatnonzero(~(c > 1.0 + 1e-9))
        samples = min(len(p), int(reach[-1]) + 2) if reach.size else 2
        return np.array(mids), np.array(halves), samples

    def root_clearances(self):
        """Radial clearances (mm) of the driver's tip circle to the mate's root circle and of the mate's
        tip circle to the driver's root circle (negative: they overlap)."""
        r_lo, r_hi = self.driver.radius_range
        rt, rr = abs(self.mate.rho_tip), abs(self.mate.rho_root)
        if self.kind == "rack":
            return (self.a - self.mate.rho_root) - r_hi, (self.a - self.mate.rho_tip) - r_lo
        if self.kind == "external":
            return self.a - r_hi - rr, self.a - rt - r_lo
        if self.kind == "internal":  # driver inside the ring
            return rr - self.a - r_hi, rt - self.a - r_lo
        return r_lo - self.a - rr, r_hi - self.a - rt  # ring-driver: driver tips inward

    # -- the ideal position ---------------------------------------------------------------------
    def reference(self) -> float | None:
        """``delta`` at which the working flanks touch at the pitch point (None if a flank misses it).

        The driver's working flank (its left flank, facing the turning direction) is brought to
        the pitch point; the mate's position puts its flank through the same point. For
        conjugate profiles this is the position of every flank contact: transmission error and
        interference are measured from it. Found once per mesh (the teeth do not change).
        """
        if not hasattr(self, "_reference"):
            self._reference = self._find_reference()
        return self._reference

    def _find_reference(self):
        try:
            own = HalfWidth(self.gear1, self.pitch1, polar_from_y, min(self.tol, 1e-4 * self.module))
        except GeometryError:
            return None
        r_w1, r_w2 = self.pitch_radii
        w1 = own.exact(np.array([r_w1]))
        w2 = self.mate.exact(np.array([r_w2]))  # for a rack r_w2 is the pitch point's height
        if w1[1][0] < 0 or w2[1][0] < 0:
            return None
        if own.labels[w1[1][0]] != "flank" or self.mate.labels[w2[1][0]] != "flank":
            return None
        half1 = self.pitch1 / 2.0 - float(w1[0][0])
        phi_p = -half1  # the left flank point at r_w1 turned onto +y
        _, u = self.to_mate(self.pitch_point, phi_p)
        return float(self.working * float(w2[0][0]) - float(u))
