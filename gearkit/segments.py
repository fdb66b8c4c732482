"""Tool edges: the curves a cutter's edge follows, as chains of exact segments.

A tool is described by the half of one of its teeth that faces the tooth being cut,
as a chain of :class:`Segment` (line, circular arc, involute, roulette), each in an affine frame
so that the same primitives serve normal and transverse sections (the transverse
section of a circular arc on a helical rack is an ellipse arc: an arc under a
non-orthogonal affine map). Chains are walked with the tool material on the right;
the outward normal (out of the tool, into the blank) is the left normal.

Each segment carries the ``label`` of the gear feature it generates ("root", "fillet",
"flank", "tip", ...), so labels on a generated profile come from the tool itself. Every
family builds its cutters from these primitives (the involute family's basic rack and shaper
cutter: :mod:`gearkit.families.involute.tools`).
"""
from __future__ import annotations

import math
from dataclasses import replace
from functools import cached_property

import numpy as np

from gearkit.values import frozen

_IDENTITY = (1.0, 0.0, 0.0, 1.0, 0.0, 0.0)
#: below this linear angle (rad) its round-off is far below an eighth of a turn: a segment's fixed quarter
#: turns (:attr:`Segment._quarter`) are what rounding the tangent's own angle gives
_QUARTER_SURE = 1e6


@frozen
class Segment:
    """One exact piece of a tool edge, parametrised by ``u`` in ``[0, 1]``.

    kind ``"line"``: data ``(x0, y0, x1, y1)``.
    kind ``"arc"``: data ``(cx, cy, r, a0, a1)``; point ``c + r (cos a, sin a)``, ``a`` linear in ``u``
    (``r = 0`` is a corner: a fixed point whose normal turns from one side to the other).
    kind ``"involute"``: data ``(cx, cy, rb, gamma, hand, t0, t1)``; involute of the circle of radius
    ``rb`` unwound from polar angle ``gamma`` (``hand`` +1 counter-clockwise, -1 clockwise), roll
    parameter ``t = tan(profile angle)`` linear in ``u``.
    kind ``"roulette"``: data ``(kb, a, ratio, s0, s1)``; cycloid (base curvature ``kb = 0``),
    epicycloid (``a > 0``) or hypocycloid (``a < 0``) traced by a circle of radius ``|a|`` rolling on
    a base of curvature ``kb`` through the origin, rolled length ``s`` linear in ``u``
    (:func:`gearkit.curves.roulette`; a cusp may only be an end, ``s0 = 0`` or ``s1 = 0``).

    ``affine = (a11, a12, a21, a22, b1, b2)`` maps the primitive into the tool frame;
    ``reverse`` walks it from ``u = 1`` to ``u = 0``.
    """

    kind: str
    data: tuple
    label: str
    affine: tuple = _IDENTITY
    reverse: bool = False

    @cached_property
    def _shifted(self) -> bool:
        """The affine map only shifts (its linear part the identity, its offset no -0)."""
        a11, a12, a21, a22, b1, b2 = self.affine
        return (a11, a12, a21, a22) == (1.0, 0.0, 0.0, 1.0) and math.copysign(1.0, b1) + math.copysign(1.0, b2) == 2.0

    def _primitive(self, u):
        """Points and (unnormalised) tangents of the primitive at ``u``: ``(x, y)`` pairs of arrays
        (a line's tangent is the same at every ``u``: scalars)."""
        d = self.data
        if self.kind == "line":
            x0, y0, x1, y1 = d
            return (x0 + u * (x1 - x0), y0 + u * (y1 - y0)), (x1 - x0, y1 - y0)
        if self.kind == "arc":
            cx, cy, r, a0, a1 = d
            a = a0 + u * (a1 - a0)
            c, s = np.cos(a), np.sin(a)
            sign = 1.0 if a1 >= a0 else -1.0
            return (cx + r * c, cy + r * s), (sign * -s, sign * c)
        if self.kind == "involute":
            cx, cy, rb, gamma, hand, t0, t1 = d
            tt = t0 + u * (t1 - t0)
            ang = gamma + hand * tt
            c, s = np.cos(ang), np.sin(ang)
            sign = 1.0 if t1 >= t0 else -1.0
            return (cx + rb * (c + hand * tt * s), cy + rb * (s - hand * tt * c)), (sign * c, sign * s)
        elif self.kind == "roulette":
            from gearkit.curves import roulette

            kb, a, ratio, s0, s1 = d
            p, t = roulette(s0 + u * (s1 - s0), kb, a, ratio, side=1.0 if s0 + s1 >= 0 else -1.0)
            if s1 < s0:
                t = -t
            return (p[..., 0], p[..., 1]), (t[..., 0], t[..., 1])
        raise ValueError(f"unknown segment kind {self.kind!r}")  # pragma: no cover - constructor guards this

    def evaluate(self, u):
        """Points, unit tangents (walking direction) and unit outward normals at ``u``.

        Parameters
        ----------
        u : (n,) float64 in [0, 1]

        Returns
        -------
        points, tangents, normals : (n, 2) float64
        """
        return self._evaluate(u)[:3]

    @cached_property
    def _line_frame(self):
        """A line's unit tangent and normal, ``(tx, ty, nx, ny)``: the same numbers :meth:`_evaluate` divides
        out at every point (one tangent for the whole line), divided once."""
        x0, y0, x1, y1 = self.data
        a11, a12, a21, a22 = self.affine[:4]
        t0x, t0y = x1 - x0, y1 - y0
        tx, ty = a11 * t0x + a12 * t0y, a21 * t0x + a22 * t0y
        norm = np.hypot(tx, ty)
        if self.reverse:
            norm = -norm
        ux, uy = np.divide(tx, norm), np.divide(ty, norm)
        return float(ux), float(uy), float(np.negative(uy)), float(ux)

    @cached_property
    def _line_vectors(self):
        """:attr:`_line_frame` as two read-only ``(2,)`` arrays, the tangent and the normal (filled in at every point)."""
        tx, ty, nx, ny = self._line_frame
        tangent, normal = np.array([tx, ty]), np.array([nx, ny])
        tangent.flags.writeable = normal.flags.writeable = False
        return tangent, normal

    def _evaluate(self, u, normals: bool = True):
        """:meth:`evaluate`, and the primitive's parameter and (unnormalised) tangent it came from (``normals=False``:
        the normals None, for :meth:`turning`)."""
        u = np.asarray(u, dtype=float)
        if self.reverse:
            u = 1.0 - u
        (px, py), (t0x, t0y) = self._primitive(u)
        a11, a12, a21, a22, b1, b2 = self.affine
        shape = u.shape + (2,)
        p = np.empty(shape)
        if self._shifted:  # x + b is (1 x + 0 y) + b to the bit (b is not -0: the sum's zero keeps its sign)
            np.add(px, b1, out=p[..., 0])
            np.add(py, b2, out=p[..., 1])
        else:
            p[..., 0] = a11 * px + a12 * py + b1
            p[..., 1] = a21 * px + a22 * py + b2
        if self.kind == "line":  # one tangent and normal, filled in
            tangent, normal = self._line_vectors
            t = np.empty(shape)
            t[...] = tangent
            if not normals:
                return p, t, None, u, (t0x, t0y)
            n = np.empty(shape)
            n[...] = normal
            return p, t, n, u, (t0x, t0y)
        tx = a11 * t0x + a12 * t0y
        ty = a21 * t0x + a22 * t0y
        norm = np.hypot(tx, ty)
        if self.reverse:
            norm = -norm
        t = np.empty(shape)
        np.divide(tx, norm, out=t[..., 0])
        np.divide(ty, norm, out=t[..., 1])
        if not normals:
            return p, t, None, u, (t0x, t0y)
        n = np.empty(shape)
        np.negative(t[..., 1], out=n[..., 0])
        n[..., 1] = t[..., 0]
        return p, t, n, u, (t0x, t0y)

    def __call__(self, u):
        """Points at ``u`` (a segment is an exact curve too: the basic rack's pieces)."""
        return self.evaluate(u)[0]

    def endpoints(self):
        p, t, _ = self.evaluate(np.array([0.0, 1.0]))
        return p, t

    def turning(self, u):
        """Points, unit tangents (as :meth:`evaluate`) and the tangent's angle (rad), continuous along the segment
        (None for a trochoid, ``ratio != 1``).

        The angle is the walking tangent's direction up to a constant, monotone in ``u`` on every kind: a
        line's is constant; an arc's, an involute's and a cycloid's (``ratio = 1``) primitive angle is linear
        in ``u`` (a, the unwinding angle, minus the rolling circle's mean angle), and the affine map carries
        a monotone angle to a monotone one (a linear map keeps the cyclic order of directions). Used by
        :meth:`gearkit.envelope.Branch.turning` to bound how far a piece of an envelope turns.

        >>> seg = arc((0.0, 0.0), 1.0, 0.0, math.pi, "tip")
        >>> _, _, ang = seg.turning(np.array([0.0, 0.5, 1.0]))
        >>> bool(np.allclose(np.diff(ang), np.pi / 2, rtol=0, atol=1e-12))
        True
        """
        p, t, _, ue, (t0x, t0y) = self._evaluate(u, normals=False)
        if self.kind == "line" and ue.size > 1:  # one tangent: its angle taken once, and filled in
            return p, t, np.full(ue.shape, self._angle(ue.ravel()[:1], t0x, t0y)[0])
        angle = self._angle(ue, t0x, t0y)
        return None if angle is None else (p, t, angle)

    @cached_property
    def _quarter(self):
        """The quarter turns from the linear angle to the tangent's, where the kind fixes them (else None): an
        arc's tangent ``sign (-sin a, cos a)`` is ``a`` plus a quarter turn (``sign`` 1) or three (-1), an
        involute's ``sign (cos a, sin a)`` is ``a`` plus none or two; the tangent's own angle, which
        :meth:`_angle` rounds to the nearest quarter turn from ``a``, lies within round-off of that (while
        ``|a| < _QUARTER_SURE``), so the rounding gives these numbers."""
        d = self.data
        if self.kind == "arc":
            return 1.0 if d[4] >= d[3] else 3.0
        if self.kind == "involute":
            return 0.0 if d[6] >= d[5] else 2.0
        return None

    def _angle(self, ue, t0x, t0y):
        """:meth:`turning`'s angle at the primitive's parameters ``ue`` and (unnormalised) tangents, or None."""
        d = self.data
        if self.kind == "arc":
            lin = d[3] + ue * (d[4] - d[3])
        elif self.kind == "involute":
            lin = d[3] + d[4] * (d[5] + ue * (d[6] - d[5]))
        elif self.kind == "roulette":
            kb, a, ratio, s0, s1 = d
            if ratio != 1.0:  # a trochoid may turn both ways: no monotone angle
                return None
            lin = -(s0 + ue * (s1 - s0)) * (kb + 0.5 / a)
        else:
            lin = np.zeros_like(ue)
        quarter = self._quarter
        if quarter is None or not np.abs(lin).max(initial=0.0) < _QUARTER_SURE:
            # a line's tangent is one vector: its angle is taken once
            turn = np.arctan2(t0y, t0x) if np.ndim(t0x) else np.full(ue.shape, np.arctan2(t0y, t0x))
            quarter = np.mod(np.round((turn - lin) / (0.5 * math.pi)), 4.0)
        psi = lin + 0.5 * math.pi * quarter  # the primitive's tangent angle, continuous
        a11, a12, a21, a22 = self.affine[:4]
        if a11 * a22 - a12 * a21 < 0:  # a reflection: A e(psi) = (A diag(1, -1)) e(-psi)
            a12, a22, psi = -a12, -a22, -psi
        rho = math.atan2(a21 - a12, a11 + a22)  # the rotation of A's polar decomposition
        c, s = math.cos(rho), math.sin(rho)
        b11, b12, b21, b22 = c * a11 + s * a21, c * a12 + s * a22, -s * a11 + c * a21, -s * a12 + c * a22
        if (b11, b12, b21, b22) == (1.0, 0.0, 0.0, 1.0):  # A a rotation: f = e, their angle exactly 0
            return rho + psi + 0.0
        ex, ey = np.cos(psi), np.sin(psi)
        fx, fy = b11 * ex + b12 * ey, b21 * ex + b22 * ey  # symmetric positive definite: within 90 deg of e
        return rho + psi + np.arctan2(ex * fy - ey * fx, ex * fx + ey * fy)


def transform_chain(chain, matrix, offset=(0.0, 0.0)):
    """Apply ``x -> matrix @ x + offset`` to a chain of segments.

    A reflection (negative determinant) would put the material on the left, so the
    chain and each segment are reversed to keep the material on the right.
    """
    m = np.asarray(matrix, dtype=float)
    out = []
    flip = np.linalg.det(m) < 0
    for seg in chain:
        a11, a12, a21, a22, b1, b2 = seg.affine
        old = np.array([[a11, a12], [a21, a22]])
        new = m @ old
        nb = m @ np.array([b1, b2]) + np.asarray(offset, dtype=float)
        out.append(replace(seg, affine=(new[0, 0], new[0, 1], new[1, 0], new[1, 1], nb[0], nb[1]),
                           reverse=seg.reverse ^ bool(flip)))
    return tuple(reversed(out)) if flip else tuple(out)


def rotation_matrix(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


def line(p0, p1, label):
    return Segment("line", (float(p0[0]), float(p0[1]), float(p1[0]), float(p1[1])), label)


def arc(centre, radius, a0, a1, label):
    return Segment("arc", (float(centre[0]), float(centre[1]), float(radius), float(a0), float(a1)), label)


def corner(point, t_in, t_out, label):
    """Zero-radius arc at ``point`` turning the walking direction from ``t_in`` to ``t_out``.

    Its normals sweep the angle between the adjacent segments' normals, so the envelope of
    a chain stays continuous across the corner (a convex corner generates a trochoid).
    """
    n_in = np.array([-t_in[1], t_in[0]])
    n_out = np.array([-t_out[1], t_out[0]])
    turn = t_in[0] * t_out[1] - t_in[1] * t_out[0]
    if turn <= 0:  # right turn: convex corner, walked clockwise, normal = (cos a, sin a)
        a0 = math.atan2(n_in[1], n_in[0])
        a1 = math.atan2(n_out[1], n_out[0])
        while a1 > a0:
            a1 -= 2 * math.pi
    else:  # left turn: concave corner, walked counter-clockwise, normal = -(cos a, sin a)
        a0 = math.atan2(-n_in[1], -n_in[0])
        a1 = math.atan2(-n_out[1], -n_out[0])
        while a1 < a0:
            a1 += 2 * math.pi
    return arc(point, 0.0, a0, a1, label)
