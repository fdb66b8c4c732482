"""The flat face's cam as the intersection of its half-planes, and how far the follower riding it
leaves its law.

Relative to the cam, the face is a line at every cam angle ``phi`` and the cam lies on the side of
the cam axis: the cam a flat face leaves is the intersection of the half-planes ``n(phi) . x <=
h(phi)`` (``n`` the unit normal into the follower, ``h > 0`` the line's distance from the axis), a
convex region whatever the motion asks for. :class:`HalfPlanes` holds that region from the lines
of many cam angles: the lines that bound it are the vertices of the convex hull of the dual points
``d = n / h`` (the intersection is the polar of their hull), in the order of their normals.

Where the motion asks for more than a convex cam gives (``r0 + s + s'' < 0`` for a translating
face, textbook 3.45; a rocker whose face turns back relative to the cam, ``1 + psi' < 0``), the
face at its prescribed pose stands off the cam: the follower, held against the cam, leaves its law.
:func:`follower_departure` measures by how much: a translating face rests at the cam's support
``H(n)`` in its own direction; a rocker's face turns about the pivot until it touches the cam (the
largest arm angle at which its line still meets the cam, found by bisection on the support).
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["HalfPlanes", "face_lines", "face_depth", "follower_departure", "LINES", "ROUND_OFF"]

#: face positions over one turn that stand for the whole family of half-planes
LINES = 65536
#: a face whose line misses the cam by less than this fraction of r0 + stroke touches it (round-off of
#: the support, computed through points up to a few r0 + stroke from the axis)
ROUND_OFF = 1e-9
#: lines per line step about each velocity jump, and the steps either side they span (:func:`face_depth`)
CORNER_LINES, CORNER_REACH = 64, 4


def face_lines(motion, tool, phi):
    """The face at cam angles ``phi`` in the cam frame: unit normals ``n`` (away from the cam axis)
    and distances ``h > 0`` of the lines ``n . x = h``."""
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    ends = tool.evaluate(np.array([0.0, 1.0]))[0]
    a = motion.to_blank(np.broadcast_to(ends[0], phi.shape + (2,)), phi)
    b = motion.to_blank(np.broadcast_to(ends[1], phi.shape + (2,)), phi)
    d = b - a
    n = np.stack([d[:, 1], -d[:, 0]], -1) / np.hypot(d[:, 0], d[:, 1])[:, None]
    h = np.einsum("ij,ij->i", n, a)
    flip = np.where(h < 0, -1.0, 1.0)
    return n * flip[:, None], h * flip


class HalfPlanes:
    """The convex polygon the half-planes ``n . x <= h`` bound (``n`` unit, ``h > 0``: the origin inside).

    ``normals``, ``heights``: the lines that bound it, counter-clockwise; ``vertices[k]`` is where
    line ``k`` meets line ``k + 1``, ``angles`` their polar angles.

    Examples
    --------
    The unit square from its four sides and a line that cuts off nothing:

    >>> n = np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0], [0.6, 0.8]])
    >>> square = HalfPlanes(n, np.array([1.0, 1.0, 1.0, 1.0, 5.0]))
    >>> len(square.heights), square.depth(np.array([[0.5, 0.0], [2.0, 1.0]])).tolist()
    (4, [-0.5, 1.0])
    >>> square.support(np.array([[0.6, 0.8]])).tolist()  # at the corner (1, 1)
    [1.4]
    """

    def __init__(self, n, h):
        from scipy.spatial import ConvexHull

        idx = ConvexHull(n / h[:, None]).vertices  # counter-clockwise in 2-D
        na, ha = n[idx], h[idx]
        nb, hb = np.roll(na, -1, axis=0), np.roll(ha, -1)
        det = na[:, 0] * nb[:, 1] - na[:, 1] * nb[:, 0]
        self.normals, self.heights = na, ha
        self.vertices = np.stack([(ha * nb[:, 1] - hb * na[:, 1]) / det, (na[:, 0] * hb - nb[:, 0] * ha) / det], -1)
        self.angles = np.arctan2(self.vertices[:, 1], self.vertices[:, 0])
        self._by_angle = np.argsort(self.angles)
        normal_angles = np.arctan2(na[:, 1], na[:, 0])
        self._by_normal = np.argsort(normal_angles)
        self._normal_angles = normal_angles[self._by_normal]

    def depth(self, points):
        """Signed distance (mm) of each point outside the polygon (negative inside): against the line
        whose edge the ray from the origin through the point crosses."""
        alpha = np.arctan2(points[:, 1], points[:, 0])
        k = np.searchsorted(self.angles[self._by_angle], alpha) % len(self.angles)  # the edge ends at the next vertex
        line = self._by_angle[k]
        return np.einsum("ij,ij->i", points, self.normals[line]) - self.heights[line]

    def support(self, u):
        """``max u . x`` over the polygon for unit directions ``u`` ``(n, 2)``: at the vertex between the
        two lines whose normals bracket ``u``."""
        return np.einsum("ij,ij->i", u, self.support_points(u))

    def support_points(self, u):
        """The vertex where ``u . x`` is largest for each direction ``u`` ``(n, 2)``."""
        beta = np.arctan2(u[:, 1], u[:, 0])
        return self.vertices[self._by_normal[(np.searchsorted(self._normal_angles, beta) - 1) % len(self._normal_angles)]]


def face_depth(motion, tool, start: float, corners=(), samples: int = LINES):
    """:class:`HalfPlanes` of ``samples`` face positions over one turn from cam angle ``start``, and of the
    face at each of ``corners`` (cam angles of the velocity jumps, where the face slides along one line)
    and ``CORNER_LINES`` times as densely within ``CORNER_REACH`` of their steps either side of each.

    Between two of its lines ``delta`` apart the polygon stands out of the cam by up to ``D (k delta)^2 / 8``
    (``D`` its diameter, ``k`` how much faster than the cam the face turns): 1e-8 mm on a 30 mm cam at
    65 536 lines, which a point there reads as inside. A smooth arc's envelope lies on the cam whatever that
    excess, but the fold of a slide at a velocity jump of a small lift is as shallow: a constant-velocity
    rocker lifting 1e-3 mm, with a 0.001-degree dwell between its rise and return, slides back along the
    face by 8e-4 mm at each jump and its dwell's arc, both within a sixth of a line step of the jumps, ran up
    to 7e-9 mm outside the cam, inside that polygon, and were kept. A fold reaches past the jump by about
    its slide over the cam's radius; where that is less than ``CORNER_REACH`` steps, the lines there are
    ``CORNER_LINES`` times as dense (the excess ``CORNER_LINES^2`` times smaller: 1e-12 of the cam's size);
    where it is more, the fold is ``CORNER_REACH^2`` times deeper than the excess."""
    step = 2.0 * math.pi / samples
    dense = np.linspace(-CORNER_REACH, CORNER_REACH, 2 * CORNER_REACH * CORNER_LINES + 1) * step
    near = [c + dense for c in np.asarray(corners, float)]
    phi = np.concatenate([start + np.linspace(0.0, 2.0 * math.pi, samples, endpoint=False), np.asarray(corners, float),
                          *near])
    return HalfPlanes(*face_lines(motion, tool, phi))


def follower_departure(spec, planes: HalfPlanes, phi):
    """How far the follower held against the cam ``planes`` falls short of its law at cam angles ``phi``,
    and where its face touches the cam: ``(gap, contact)``, ``gap = s(phi) - s_actual(phi) >= 0`` in mm of
    lift (a rocker's as the arc at its arm; 0 where the face touches the cam at its prescribed pose) and
    ``contact`` the contact's place along the face, mm (from the foot of the follower's axis; a rocker's
    from the pivot, along the arm).

    A translating face rests at ``r0 + s_actual = H(n)``, the cam's support in the face's direction
    (the face's normal in the cam frame is ``(sin phi, cos phi)``). A rocker's face lies along the arm
    through the pivot ``(l0, 0)``: at arm angle ``Psi`` its line has the normal ``(sin Psi, cos Psi)``
    and the height ``l0 sin Psi`` (fixed frame). The closing force turns it down (``Psi`` falling) until
    the cam stops it, which only a contact in front of the pivot does (the cam pushing on the face behind
    the pivot turns it further down): it keeps its law where its line touches the cam (within
    ``ROUND_OFF`` of the cam's size) in front of the pivot, and rests otherwise at the largest ``Psi``
    below the prescribed one whose line meets the cam (the lines from ``Psi = 0``, through the axis
    inside the cam, up to that one all cut it; none below the prescribed one meets it behind the
    pivot), found by bisection.
    """
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    s = spec.motion.evaluate(phi)[0]
    c, n = np.cos(phi), np.sin(phi)

    def to_cam(u):  # fixed-frame vectors turned by -phi into the cam frame
        return np.stack([c * u[:, 0] + n * u[:, 1], -n * u[:, 0] + c * u[:, 1]], -1)

    if spec.follower == "translating":
        up = to_cam(np.stack([np.zeros_like(phi), np.ones_like(phi)], -1))
        touch = planes.support_points(up)
        gap = np.maximum(spec.prime_radius + s - np.einsum("ij,ij->i", up, touch), 0.0)
        return gap, np.einsum("ij,ij->i", touch, to_cam(np.stack([np.ones_like(phi), np.zeros_like(phi)], -1))) - spec.offset
    l0, arm = spec.pivot_distance, spec.arm_length
    pivot = to_cam(np.stack([np.full_like(phi, l0), np.zeros_like(phi)], -1))

    def face(psi):  # the face's normal and its direction along the arm, cam frame
        return to_cam(np.stack([np.sin(psi), np.cos(psi)], -1)), to_cam(np.stack([-np.cos(psi), np.sin(psi)], -1))

    def gap(psi):  # how far the cam reaches beyond the face's line at arm angle psi
        return planes.support(face(psi)[0]) - l0 * np.sin(psi)
    prescribed = spec.psi0 + s / arm
    normal, along = face(prescribed)
    front = planes.support_points(normal + 1e-9 * along)  # of the points the line touches, the farthest along the arm
    held = (gap(prescribed) >= -ROUND_OFF * (spec.prime_radius + spec.stroke)) & \
        (np.einsum("ij,ij->i", front - pivot, along) > 0.0)
    lo, hi = np.zeros_like(prescribed), prescribed.copy()
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        meets = gap(mid) >= 0.0
        lo, hi = np.where(~held & meets, mid, lo), np.where(~held & ~meets, mid, hi)
    normal, along = face(hi)
    touch = np.where(held[:, None], front, planes.support_points(normal + 1e-9 * along))
    return np.where(held, 0.0, arm * (prescribed - hi)), np.einsum("ij,ij->i", touch - pivot, along)
