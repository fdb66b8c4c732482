"""A proven bound of how far an exact curve strays from a chord, from its tangents' turning.

**The bound.** Take a stretch of a smooth curve from ``a`` to ``b`` (a *leg*) whose tangent's angle
stays in a range ``[lo, hi]`` narrower than a half turn, and whose velocity never vanishes (no cusp
inside). Every velocity then lies in the cone of directions ``[lo, hi]`` (one sense all along), so the
curve lies in ``a + cone`` and in ``b - cone``: in the parallelogram with corners ``a``, ``b`` and the
two crossings of the cone's edges from ``a`` and from ``b`` (the chord ``b - a``, a sum of velocities,
lies in the cone, so the crossings exist). The distance to a segment is convex, so the largest
distance of those four corners from any chord bounds the curve's distance from it. Where the
tangent turns one way between ``a`` and ``b`` the range is the end tangents' own, the parallelogram
is the tangent triangle and its mirror image, and the bound is the triangle's height: on a short leg
barely above the curve's own deviation.

**The range.** A curve gives its tangent's angle as a sum of *parts*, each monotone in the
parameter (``turning(w)`` on the exact curves: an envelope branch's tool angle and motion angle,
an arc's polar angle). Over a leg each part lies between its end values, so the range is ``the
angle at a`` plus the sum of each part's least and largest change: no inflection needs to be found,
and one that falls inside a leg only widens its range. A leg whose parts are not consistent with its
exact end tangents, whose range reaches a half turn, or whose chord falls outside its cone (a cusp)
is not bounded (``inf``): the sampler splits it.

>>> import numpy as np
>>> h = 0.3  # an arc of the unit circle of half-angle h, against its own chord: sagitta 1 - cos h
>>> a, b = np.array([-np.sin(h), np.cos(h)]), np.array([np.sin(h), np.cos(h)])
>>> ta, tb = np.array([np.cos(h), np.sin(h)]), np.array([np.cos(h), -np.sin(h)])
>>> bound = leg_bound(a, b, ta, tb, np.array([-2 * h]), a, b)
>>> round(float(bound), 9), round(float(np.tan(h) * np.sin(h)), 9)  # the tangent triangle's height
(0.091415112, 0.091415112)
"""
from __future__ import annotations

import numpy as np

__all__ = ["angle_parts", "chord_distance", "interval_bounds", "leg_bound", "round_off"]

#: a leg's parts must reproduce its exact end tangent to this angle (rad): round-off of the parts
CONSISTENT = 1e-9
#: below this width (rad) of its range a leg is bounded by its ends plus the parallelogram's
#: largest height over its chord, ``|b - a| tan(W / 2) / 2`` (the corners' solve loses digits there)
NARROW = 1e-6


def chord_distance(a, b, q):
    """Distance of points ``q`` from the segments ``a``-``b`` (broadcast over the last axis).

    >>> float(chord_distance(np.zeros(2), np.array([2.0, 0.0]), np.array([1.0, 0.5])))
    0.5
    """
    d = b - a
    dd = np.einsum("...i,...i->...", d, d)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.clip(np.einsum("...i,...i->...", q - a, d) / dd, 0.0, 1.0)
    t = np.where(dd > 0, t, 0.0)
    foot = a + t[..., None] * d
    return np.linalg.norm(q - foot, axis=-1)


def _turn(v, angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], -1)


def _cross(u, v):
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def leg_bound(a, b, ta, tb, dparts, chord_a, chord_b):
    """Bound of the distance from the segment ``chord_a``-``chord_b`` of the curve's leg from ``a`` to ``b``.

    ``ta``, ``tb`` are the curve's unit tangents at the leg's ends (either sense, the same along the
    curve) and ``dparts`` ``(..., k)`` the change of each monotone part of the tangent's angle from
    ``a`` to ``b``. Returns the largest distance of the leg's parallelogram's corners from the segment
    (see the module), or ``inf`` where the leg is not bounded so (to be split). All arrays broadcast.
    """
    lo = np.minimum(dparts, 0.0).sum(axis=-1)
    hi = np.maximum(dparts, 0.0).sum(axis=-1)
    width = hi - lo
    c = b - a
    d_lo, d_hi = _turn(ta, lo), _turn(ta, hi)
    mid = _turn(ta, 0.5 * (lo + hi))
    sense = np.where(np.einsum("...i,...i->...", c, mid) < 0.0, -1.0, 1.0)[..., None]
    d_lo, d_hi = sense * d_lo, sense * d_hi
    swing = np.sin(width)  # cross(d_lo, d_hi)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        along_lo = np.where(swing > 0, _cross(c, d_hi) / swing, 0.0)
        along_hi = np.where(swing > 0, _cross(d_lo, c) / swing, 0.0)
    length = np.linalg.norm(c, axis=-1)
    slack = 1e-12 * length
    ends = np.maximum(chord_distance(chord_a, chord_b, a), chord_distance(chord_a, chord_b, b))
    corners = np.maximum(chord_distance(chord_a, chord_b, a + along_lo[..., None] * d_lo),
                         chord_distance(chord_a, chord_b, a + along_hi[..., None] * d_hi))
    narrow = ends + 0.5 * length * np.tan(0.5 * np.minimum(width, 3.0))
    bound = np.where(width < NARROW, narrow, np.maximum(ends, corners))
    # the parts must reproduce the end tangent, the range stay below a half turn, the chord lie in the cone
    drift = np.abs(_cross(_turn(ta, dparts.sum(axis=-1)), tb))
    same = np.einsum("...i,...i->...", _turn(ta, dparts.sum(axis=-1)), tb) > 0.0
    ok = (drift <= CONSISTENT) & same & (width < 0.5 * np.pi)
    ok &= (width < NARROW) | ((along_lo >= -slack) & (along_hi >= -slack))
    ok &= (width < NARROW) | ~(length > 0) | (np.einsum("...i,...i->...", c, mid) != 0.0)
    return np.where(ok & np.isfinite(bound), bound, np.inf)


#: an interval whose bound is below RETRY tol is bounded again on FINE legs before it is split
RETRY = 2.0
FINE = 32
#: the bound's allowance for the round-off of exact points (a multiple of the largest coordinate)
ROUND_OFF = 1e-14


def angle_parts(turning):
    """``turning`` with its angle parts as ``(n, k)`` (a single part may come as ``(n,)``)."""
    def call(w):
        p, t, a = turning(w)
        return p, t, np.asarray(a, dtype=float).reshape(len(p), -1)
    return call


def _walk_bound(rows, pts, tan, parts, q, tq, pq):
    """Bound of the intervals ``rows`` (vertex ``rows`` to ``rows + 1``) over the legs through their
    probes ``q``, ``tq``, ``pq`` (points, tangents, parts; flat, the same number per interval)."""
    n = len(rows)

    def walk(at, inner, width):
        return np.concatenate([at[rows, None], inner.reshape(n, -1, width), at[rows + 1, None]], axis=1)

    p, t, a = walk(pts, q, 2), walk(tan, tq, 2), walk(parts, pq, parts.shape[-1])
    return leg_bound(p[:, :-1], p[:, 1:], t[:, :-1], t[:, 1:], np.diff(a, axis=1),
                     pts[rows, None], pts[rows + 1, None]).max(axis=1)


def interval_bounds(turning, w, pts, tan, parts, tol, fractions, rows=None):
    """Probes of a sampling's intervals (at ``fractions`` of each) with their tangents and angle parts,
    and each interval's proven deviation bound: the largest :func:`leg_bound` of the legs between its ends
    and probes (``inf``: not proven). ``turning`` as :func:`angle_parts` returns it; ``pts``, ``tan``,
    ``parts`` are its values at the vertices ``w``; ``rows`` the intervals to bound (vertex ``i`` to
    ``i + 1``; default all), each bounded on its own. The bound leaves out the round-off of the exact
    points, :func:`round_off` of the sampling (it grows with the sampling's largest coordinate).
    Where the parts turn against each other (an inflection) a leg's range is wider than its turning:
    an interval bounded just above ``tol`` is bounded again on ``FINE`` legs (more proof, not more
    vertices)."""
    rows = np.arange(len(w) - 1) if rows is None else rows
    lo, hi = w[rows], w[rows + 1]
    probes = lo[:, None] + (hi - lo)[:, None] * fractions
    q, tq, pq = turning(probes.ravel())
    bound = _walk_bound(rows, pts, tan, parts, q, tq, pq)
    near = np.flatnonzero((bound > tol) & (bound < RETRY * tol))
    if len(near):
        fine = lo[near, None] + (hi - lo)[near, None] * np.linspace(0.0, 1.0, FINE + 1)[1:-1]
        bound[near] = np.minimum(bound[near], _walk_bound(rows[near], pts, tan, parts, *turning(fine.ravel())))
    m, k = len(lo), parts.shape[-1]
    return (probes, q.reshape(m, -1, 2), tq.reshape(m, -1, 2), pq.reshape(m, -1, k), bound)


def round_off(pts) -> float:
    """The allowance a proven bound adds for the round-off of the exact points ``pts``: ``ROUND_OFF``
    of their largest coordinate."""
    return ROUND_OFF * float(np.abs(pts).max(initial=0.0))
