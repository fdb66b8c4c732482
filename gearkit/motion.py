"""Generating motions: a tool centrode rolling without slip on the blank's centrode, or any planar motion.

Gear cutting has constant ratio, so its centrodes are circles or straight lines: rack on
gear (hobbing), gear on gear (shaper cutter, external or internal), pin ring on disc
(cycloidal drive). :class:`RollingMotion` covers them all with signed centrode curvatures.
A cam's follower moves relative to the cam by a motion law, not by rolling:
:class:`PlanarMotion` is the general planar motion given by its pose and the pose's
derivatives as functions of the motion parameter (the cam angle). Both give the envelope
solver (:mod:`gearkit.envelope`) what it needs: the pose and the instant centre.

Frames. The *tool frame* and the *fixed frame* coincide at ``s = 0``: origin at the pole
(the centrodes' contact point), x along the common tangent, the blank centre at
``(0, blank_centre)`` (negative: below the tangent), the tool centrode's centre at
``(0, tool_centre)`` (positive: a tool on the far side, external mesh; negative: the tool
centre on the blank's side, internal mesh). ``None`` means a straight centrode (rack).
The *blank frame* has its origin at the blank centre (for a rack blank: at the pole at
``s = 0``) and turns with the blank. ``s`` is the rolled arc length (mm).
"""
from __future__ import annotations

import math
from functools import cached_property

import numpy as np

from gearkit.curves import cross2, rotate, turn_by
from gearkit.errors import require
from gearkit.values import frozen


def _centrode(c, s):
    """Point and tangent angle at arc length ``s`` of a centrode through the origin,
    tangent to +x there, centre ``(0, c)`` (``c = None``: the x axis)."""
    out = np.empty(np.shape(s) + (2,))
    if c is None:
        out[..., 0] = s
        out[..., 1] = 0.0
        return out, np.zeros_like(s)
    a = s / c
    out[..., 0] = c * np.sin(a)
    out[..., 1] = c * (1.0 - np.cos(a))
    return out, a


@frozen
class RollingMotion:
    """Tool centrode rolling on the blank centrode.

    Parameters
    ----------
    blank_centre : float or None, mm
        y of the blank centre in the fixed frame (``-r_w`` for a gear blank; None: rack blank).
    tool_centre : float or None, mm
        y of the tool centrode's centre (``+r_w0`` external shaper, ``-r_w0`` internal shaper or
        pin ring; None: rack cutter).
    roll_centre : float, mm
        On a circular tool centrode a contact's roll is defined only up to whole turns of the
        tool; :meth:`contact` returns the one within half a turn of ``roll_centre`` (default 0:
        the turn centred on the start position). A tool whose contacts span more than half a
        turn on one side of the start (a pin touching near the root and again near the crest
        of a cycloidal disc) centres the turn on its own pass so its envelope stays continuous.
    """

    blank_centre: float | None
    tool_centre: float | None
    roll_centre: float = 0.0

    def __post_init__(self):
        for name in ("blank_centre", "tool_centre"):
            c = getattr(self, name)
            require(c is None or (math.isfinite(c) and c != 0.0), name, "must be finite and non-zero, or None")
        require(math.isfinite(self.roll_centre), "roll_centre", "must be a finite roll in mm")
        require(not (self.blank_centre is None and self.tool_centre is None), "tool_centre",
                "a rack cannot generate a rack")
        require(self.blank_centre != self.tool_centre, "tool_centre", "the centrodes must differ")

    @cached_property
    def blank_offset(self) -> np.ndarray:
        """Vector from the blank-frame origin to the pole at s = 0 (read-only; built once)."""
        out = np.array([0.0, 0.0 if self.blank_centre is None else -self.blank_centre])
        out.flags.writeable = False
        return out

    def pose(self, s):
        """Tool-to-blank map at roll ``s``: ``q = rotate(p - shift, angle) + offset``.

        Returns
        -------
        shift : (n, 2) float64, the pole in the tool frame
        angle : (n,) float64, rad
        offset : (n, 2) float64, the pole in the blank frame
        """
        s = np.asarray(s, dtype=float)
        c_t, tau_t = _centrode(self.tool_centre, s)
        c_b, tau_b = _centrode(self.blank_centre, s)
        return c_t, tau_b - tau_t, c_b + self.blank_offset

    def carry(self, points, s, *vectors):
        """Tool-frame ``points`` at rolls ``s`` in the blank frame, the turn ``angle`` of the pose and
        ``vectors`` turned by it: ``(q, angle, *vectors)``, each to the bit as ``rotate(points - shift, angle,
        *vectors)`` and ``+ offset`` from :meth:`pose` give them (a rack cutting a gear turns by the blank
        centrode's own angle: its sine and cosine serve the centrode and the turn)."""
        if self.tool_centre is not None or self.blank_centre is None:
            shift, angle, offset = self.pose(s)
            turned = rotate(np.asarray(points) - shift, angle, *vectors)
            return (turned[0] + offset, angle, *turned[1:]) if vectors else (turned + offset, angle)
        c = self.blank_centre
        angle = np.asarray(s, dtype=float) / c  # the blank's turn less the rack's (none)
        cos, sin = np.cos(angle), np.sin(angle)
        p = np.asarray(points, dtype=float)
        dx, dy = p[..., 0] - s, p[..., 1]  # minus the pole (s, 0) in the tool frame
        q = np.empty(p.shape)
        q[..., 0] = cos * dx - sin * dy + (c * sin + 0.0)  # plus the pole in the blank frame
        q[..., 1] = sin * dx + cos * dy + (c * (1.0 - cos) + -c)
        return (q, angle, *(turn_by(v, cos, sin) for v in vectors))

    def to_blank(self, points, s):
        """Tool-frame points at roll ``s`` expressed in the blank frame.

        Parameters
        ----------
        points : (n, 2) float64, mm
        s : (n,) or scalar float64, mm
        """
        s = np.asarray(s, dtype=float)
        c_t, tau_t = _centrode(self.tool_centre, s)
        c_b, tau_b = _centrode(self.blank_centre, s)
        return rotate(np.asarray(points) - c_t, tau_b - tau_t) + c_b + self.blank_offset

    def tool_pole(self, s):
        """The pole (instant centre of the relative motion) in the tool frame at roll ``s``, ``(n, 2)``.

        A tool point's normal passes through it exactly when the point is in contact, so for a
        circular tool this gives the contact point at any roll directly.
        """
        return _centrode(self.tool_centre, np.asarray(s, dtype=float))[0]

    def rotate_to_blank(self, vectors, s):
        """Tool-frame direction vectors at roll ``s`` in the blank frame."""
        s = np.asarray(s, dtype=float)
        _, tau_t = _centrode(self.tool_centre, s)
        _, tau_b = _centrode(self.blank_centre, s)
        return rotate(vectors, tau_b - tau_t)

    def contact(self, points, normals, root="near"):
        """Closed-form solution of the meshing equation n . v_rel = 0 for tool points.

        The relative velocity is a rotation about the pole, so a tool point is in contact
        when its normal line passes through the pole: the roll is where that line meets the
        tool centrode.

        Parameters
        ----------
        points, normals : (n, 2) float64 in the tool frame
        root : "near", "far", "front" or "back"
            On a circular tool centrode the normal line meets it twice: "near" takes the
            intersection closest to the point (the one the cutter actually passes through
            in generation), "far" the other; "front" takes the one farther along the
            outward normal (into the blank), "back" the other. The signed rule is the one to
            use when the point's distances to the two intersections cross over along the
            tool (a pin centred on the tool centrode: one root is always the pin centre).

        Returns
        -------
        s : (n,) float64, mm (NaN where the normal misses the centrode)
        valid : (n,) bool
        """
        p = np.asarray(points, dtype=float)
        n = np.asarray(normals, dtype=float)
        c = self.tool_centre
        if c is None:
            with np.errstate(divide="ignore", invalid="ignore"):
                t = -p[:, 1] / n[:, 1]
            valid = np.abs(n[:, 1]) > 1e-14
            s = np.where(valid, p[:, 0] + t * n[:, 0], np.nan)  # where the normal line meets the x axis
            return s, valid
        rel = p - np.array([0.0, c])
        b = np.einsum("ij,ij->i", n, rel)
        # c^2 - d^2 with d the centre's distance from the normal line: equal to b^2 - (|rel|^2 - c^2)
        # for a unit normal, without its cancellation; a line grazing the centrode within rounding
        # touches it (the two roots meet exactly there, e.g. where a pin's contact turns back)
        d = np.abs(rel[:, 0] * n[:, 1] - rel[:, 1] * n[:, 0])
        disc = (abs(c) - d) * (abs(c) + d)
        valid = disc >= -8.0 * np.finfo(float).eps * abs(c) * (abs(c) + d)
        sq = np.sqrt(np.maximum(disc, 0.0))
        t1, t2 = -b - sq, -b + sq
        if root in ("near", "far"):
            # a tie (the normal is perpendicular to the line of centres through the point, e.g. an
            # involute's base point) goes to the root along the outward normal, the one its
            # neighbours on the involute take
            first = np.abs(t1) < np.abs(t2) - 1e-12 * (np.abs(t1) + np.abs(t2))
            t = np.where(first, t1, t2) if root == "near" else np.where(first, t2, t1)
        elif root in ("front", "back"):
            t = t2 if root == "front" else t1
        else:
            raise ValueError(f"root must be 'near', 'far', 'front' or 'back', not {root!r}")
        hit = p + t[:, None] * n
        sigma = np.arctan2(hit[:, 0] / c, 1.0 - hit[:, 1] / c)
        if self.roll_centre:
            sigma = sigma - 2.0 * np.pi * np.round((sigma - self.roll_centre / c) / (2.0 * np.pi))
        return np.where(valid, c * sigma, np.nan), valid

    def contact_newton(self, points, normals, s0=None, iterations=50):
        """The same meshing equation solved by vectorised Newton iteration.

        Solves ``g(s) = (C(s) - p) x n = 0`` with ``C(s)`` the pole in the tool frame. It is
        the general path for motions without a closed form, and an independent check of
        :meth:`contact`. ``s0`` defaults to where the normal line meets the centrode's
        tangent at the pole.
        """
        p = np.asarray(points, dtype=float)
        n = np.asarray(normals, dtype=float)
        if s0 is None:
            with np.errstate(divide="ignore", invalid="ignore"):
                s0 = p[:, 0] - p[:, 1] * n[:, 0] / n[:, 1]
        s = np.array(s0, dtype=float)
        for _ in range(iterations):
            c_t, tau = _centrode(self.tool_centre, s)
            g = cross2(c_t - p, n)
            dg = cross2(np.stack([np.cos(tau), np.sin(tau)], -1), n)
            with np.errstate(divide="ignore", invalid="ignore"):
                step = g / dg
            s = s - step
            if np.all(np.abs(step) <= 1e-15 * (1.0 + np.abs(s))):
                break
        return s


@frozen
class PlanarMotion:
    """A general planar motion of the tool relative to the blank, given by its pose over a parameter.

    At parameter ``t`` (for a cam: the cam angle, rad) a tool-frame point ``p`` sits in the blank
    frame at ``q = R(theta(t)) p + d(t)``. ``rates(t)`` returns the pose and its first two
    derivatives, vectorised over ``t``: ``(theta, theta', theta'', d, d', d'')`` with the angles
    ``(n,)`` rad and the translations ``(n, 2)`` mm. Constant-ratio rolling
    (:class:`RollingMotion`) is the special case with circular or straight centrodes; this class
    serves motions without centrodes of a simple shape (a cam turning while its follower moves by
    a motion law).

    Its instant centre in the tool frame (:meth:`tool_pole`) is where the meshing equation
    n . v_rel = 0 is read: a tool point is in contact when its normal passes through it.

    Examples
    --------
    A tool turning at unit rate about the blank's origin (a rotation, no translation): every
    tool point moves on a circle and the pole is the origin.

    >>> def spin(t):
    ...     t = np.asarray(t, dtype=float)
    ...     z = np.zeros(t.shape + (2,))
    ...     return t, np.ones_like(t), np.zeros_like(t), z, z, z
    >>> m = PlanarMotion(spin)
    >>> m.tool_pole([0.3]).round(12).tolist()
    [[0.0, 0.0]]
    >>> q, dq, ddq = m.path(np.array([[2.0, 0.0]]), [0.0])
    >>> dq.tolist(), ddq.tolist()
    ([[0.0, 2.0]], [[-2.0, 0.0]])
    """

    rates: object

    def pose(self, t):
        """Tool-to-blank map at ``t`` in the form of :meth:`RollingMotion.pose`:
        ``q = rotate(p - shift, angle) + offset`` (the shift is zero)."""
        theta, _, _, d, _, _ = self.rates(np.asarray(t, dtype=float))
        return np.zeros_like(d), theta, d

    def carry(self, points, t, *vectors):
        """Tool-frame ``points`` at ``t`` in the blank frame, the turn ``angle`` and ``vectors`` turned by it:
        ``(q, angle, *vectors)``, as :meth:`RollingMotion.carry`."""
        shift, angle, offset = self.pose(t)
        turned = rotate(np.asarray(points) - shift, angle, *vectors)
        return (turned[0] + offset, angle, *turned[1:]) if vectors else (turned + offset, angle)

    def to_blank(self, points, t):
        """Tool-frame points at ``t`` in the blank frame, ``(n, 2)``."""
        theta, _, _, d, _, _ = self.rates(np.asarray(t, dtype=float))
        return rotate(np.asarray(points, dtype=float), theta) + d

    def rotate_to_blank(self, vectors, t):
        """Tool-frame direction vectors at ``t`` in the blank frame."""
        theta = self.rates(np.asarray(t, dtype=float))[0]
        return rotate(np.asarray(vectors, dtype=float), theta)

    def tool_pole(self, t):
        """Instant centre of the relative motion in the tool frame, ``(n, 2)``: the tool point whose
        blank-frame velocity ``theta' J R p + d'`` vanishes (NaN where the motion is a pure translation)."""
        theta, dtheta, _, _, dd, _ = self.rates(np.asarray(t, dtype=float))
        jd = np.stack([-dd[..., 1], dd[..., 0]], -1)
        with np.errstate(divide="ignore", invalid="ignore"):
            return rotate(jd, -theta) / dtheta[..., None]

    def path(self, points, t):
        """Blank-frame position, velocity and acceleration (with respect to ``t``) of tool points.

        ``q' = theta' J R p + d'``, ``q'' = theta'' J R p - theta'^2 R p + d''``.

        Parameters
        ----------
        points : (n, 2) or (2,) float64, tool frame, mm
        t : (n,) float64

        Returns
        -------
        q, dq, ddq : (n, 2) float64
        """
        theta, dth, ddth, d, dd, ddd = self.rates(np.atleast_1d(np.asarray(t, dtype=float)))
        rp = rotate(np.asarray(points, dtype=float), theta)
        jrp = np.stack([-rp[..., 1], rp[..., 0]], -1)
        return (rp + d, dth[..., None] * jrp + dd,
                ddth[..., None] * jrp - (dth * dth)[..., None] * rp + ddd)
