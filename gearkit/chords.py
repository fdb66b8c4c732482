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

__all__ = ["angle_parts", "chord_distance", "fractions_of", "interval_bounds", "leg_bound", "monotone_range",
           "point_distance", "put_rows", "round_off", "round_offs"]

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
    a, b, q = np.asarray(a, dtype=float), np.asarray(b, dtype=float), np.asarray(q, dtype=float)
    return _distance(a[..., 0], a[..., 1], b[..., 0] - a[..., 0], b[..., 1] - a[..., 1], q[..., 0], q[..., 1])


def point_distance(ax, ay, dx, dy, qx, qy):
    """:func:`chord_distance` on coordinates: points ``(qx, qy)`` from the segments from ``(ax, ay)`` along
    ``(dx, dy)`` (all broadcast; laid out with the long axis last, every operation runs along it).

    >>> float(point_distance(0.0, 0.0, 2.0, 0.0, np.array(1.0), np.array(-0.5)))
    0.5
    """
    return _distance(ax, ay, dx, dy, qx, qy)


def _distance(ax, ay, dx, dy, qx, qy):
    """:func:`chord_distance` on coordinates: points ``(qx, qy)`` from the segments from ``(ax, ay)``
    along ``(dx, dy)``."""
    dd = dx * dx + dy * dy
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (((qx - ax) * dx + (qy - ay) * dy) / dd).clip(0.0, 1.0)
    positive = dd > 0
    if np.count_nonzero(positive) != np.size(positive):  # (a chord of no length: its points measured from its end)
        t = np.where(positive, t, 0.0)
    fx, fy = qx - (ax + t * dx), qy - (ay + t * dy)
    return np.sqrt(fx * fx + fy * fy)


def _sum_parts(x):
    """The sum over the last axis (the parts), added in order."""
    total = x[..., 0]
    for j in range(1, x.shape[-1]):
        total = total + x[..., j]
    return total


def _cos_sin(angle):
    """Cosine and sine of ``angle``, 1 and +0 where it is 0 (either zero): a range that starts or ends at the
    leg's own tangent, as it does wherever the parts turn one way. Taken everywhere (a masked evaluation of
    half of them costs more): the cosine of 0 is 1, and ``+ 0.0`` turns the sine of -0 to +0 and no other."""
    angle = np.asarray(angle)
    return np.cos(angle), np.sin(angle) + 0.0


def _range_cos_sin(lo, hi):
    """:func:`_cos_sin` of both ends of the ranges ``[lo, hi]`` (``lo <= 0 <= hi``): ``(cos lo, sin lo, cos hi,
    sin hi)``. Where a leg turns one way one end is 0 (either zero) and ``lo + hi`` is the other to the bit, so
    one cosine and one sine serve both ends; only where every leg does so (else each end taken on its own).

    >>> lo, hi = np.array([0.0, -0.5, -0.0]), np.array([0.25, 0.0, 0.0])
    >>> all(np.array_equal(u, v) for u, v in zip(_range_cos_sin(lo, hi), _cos_sin(lo) + _cos_sin(hi)))
    True
    """
    at_lo = lo == 0.0
    if np.count_nonzero(at_lo | (hi == 0.0)) != np.size(at_lo):
        return _cos_sin(lo) + _cos_sin(hi)
    cos, sin = _cos_sin(lo + hi)
    return np.where(at_lo, 1.0, cos), np.where(at_lo, 0.0, sin), np.where(at_lo, cos, 1.0), np.where(at_lo, sin, 0.0)


def leg_bound(a, b, ta, tb, dparts, chord_a, chord_b):
    """Bound of the distance from the segment ``chord_a``-``chord_b`` of the curve's leg from ``a`` to ``b``.

    ``ta``, ``tb`` are the curve's unit tangents at the leg's ends (either sense, the same along the
    curve) and ``dparts`` ``(..., k)`` the change of each monotone part of the tangent's angle from
    ``a`` to ``b``. Returns the largest distance of the leg's parallelogram's corners from the segment
    (see the module), or ``inf`` where the leg is not bounded so (to be split). All arrays broadcast.
    """
    a, b, chord_a, chord_b = (np.asarray(v, dtype=float) for v in (a, b, chord_a, chord_b))
    cx, cy = chord_a[..., 0], chord_a[..., 1]
    dx, dy = chord_b[..., 0] - cx, chord_b[..., 1] - cy
    ends = np.maximum(_distance(cx, cy, dx, dy, a[..., 0], a[..., 1]), _distance(cx, cy, dx, dy, b[..., 0], b[..., 1]))
    ta, tb = np.asarray(ta, dtype=float), np.asarray(tb, dtype=float)
    return _legs(a[..., 0], a[..., 1], b[..., 0], b[..., 1], (ta[..., 0], ta[..., 1]), (tb[..., 0], tb[..., 1]),
                 monotone_range(np.asarray(dparts, dtype=float)), (cx, cy, dx, dy), ends)


def monotone_range(dparts):
    """The range ``(lo, hi)`` of a leg's tangent angle (from its angle at the leg's start) and its total
    turn, from the changes ``dparts`` ``(..., k)`` of monotone parts: the sums of their least and largest
    changes, and of the changes."""
    return _sum_parts(np.minimum(dparts, 0.0)), _sum_parts(np.maximum(dparts, 0.0)), _sum_parts(dparts)


def _along(cx, cy, tax, tay, half):
    """The chords ``(cx, cy)`` on the directions of their ranges' middles: the tangents ``(tax, tay)`` turned by
    ``half``."""
    cos, sin = np.cos(half), np.sin(half)
    return cx * (cos * tax - sin * tay) + cy * (sin * tax + cos * tay)


#: the sign of a chord's component along its range's middle is proven where its size is above this multiple of
#: the chord's coordinates: far above the round-off of :func:`_along` (a few ulps of them) and of the proof's sums
SURE_SIGN = 1e-13


def _backwards(cx, cy, tax, tay, half):
    """Where :func:`_along` is negative, proven without its cosines and sines (None where any is not proven so,
    NaN included): it is ``D cos h + X sin h`` with ``D`` the chord along the tangent and ``X`` across it, and
    ``1 >= cos h >= 1 - h^2 / 2``, ``|sin h| <= |h|``, so where ``|D| (1 - h^2 / 2) - |X| |h|`` exceeds
    ``SURE_SIGN`` of the chord's coordinates (their round-off) the computed value has the sign of ``D``.

    >>> cx, cy, t = np.array([1.0, -1.0]), np.array([0.0, -0.05]), np.array([1.0, 0.0])
    >>> _backwards(cx, cy, *t, np.array([0.1, 0.2])).tolist(), _backwards(cx, cy, *t, np.array([0.1, 1.5]))
    ([False, True], None)
    >>> (_along(cx, cy, *t, np.array([0.1, 1.5])) < 0).tolist()  # the second: backwards, but not proven so
    [False, True]
    """
    along, across = cx * tax + cy * tay, cy * tax - cx * tay
    low = np.abs(along) * (1.0 - 0.5 * half * half) - np.abs(across) * np.abs(half)
    sure = low > SURE_SIGN * (np.abs(cx) + np.abs(cy))
    return along < 0.0 if np.count_nonzero(sure) == np.size(sure) else None


def _legs(ax, ay, bx, by, ta, tb, turn, chord, ends):
    """:func:`leg_bound` on coordinates (the unit tangents ``ta``, ``tb`` too, as ``(x, y)`` pairs), given the
    range ``turn = (lo, hi, total)`` of each leg's tangent angle and its total turn, and the larger distance
    ``ends`` of each leg's two ends from its chord ``(x, y, dx, dy)`` (a walk shares them between its legs)."""
    lo, hi, total = turn
    width = hi - lo
    tax, tay = ta
    cx, cy = bx - ax, by - ay
    cos_lo, sin_lo, cos_hi, sin_hi = _range_cos_sin(lo, hi)
    lox, loy = cos_lo * tax - sin_lo * tay, sin_lo * tax + cos_lo * tay
    hix, hiy = cos_hi * tax - sin_hi * tay, sin_hi * tax + cos_hi * tay
    half = 0.5 * (lo + hi)
    backwards, along_mid = _backwards(cx, cy, tax, tay, half), None  # (no chord is then 0 along it)
    if backwards is None:
        along_mid = _along(cx, cy, tax, tay, half)
        backwards = along_mid < 0.0
    if np.count_nonzero(backwards):  # (elsewhere the sense is 1: a product by it changes no bit)
        sense = np.where(backwards, -1.0, 1.0)
        lox, loy, hix, hiy = sense * lox, sense * loy, sense * hix, sense * hiy
    # cross(d_lo, d_hi): sin(width), which is sin(hi) where the range starts at the leg's tangent
    turned = lo != 0.0
    swing = np.sin(width, out=np.array(sin_hi), where=turned) if np.count_nonzero(turned) else sin_hi
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        along_lo, along_hi = (cx * hiy - cy * hix) / swing, (lox * cy - loy * cx) / swing
    spread = swing > 0
    if np.count_nonzero(spread) != spread.size:  # a cone of no width: no corner beyond the ends
        along_lo, along_hi = np.where(spread, along_lo, 0.0), np.where(spread, along_hi, 0.0)
    length = np.sqrt(cx * cx + cy * cy)
    slack = 1e-12 * length
    corners = np.maximum(_distance(*chord, ax + along_lo * lox, ay + along_lo * loy),
                         _distance(*chord, ax + along_hi * hix, ay + along_hi * hiy))
    narrow = width < NARROW
    bound = np.maximum(ends, corners)
    if np.count_nonzero(narrow):
        bound = np.where(narrow, ends + 0.5 * length * np.tan(0.5 * np.minimum(width, 3.0)), bound)
    # the parts must reproduce the end tangent, the range stay below a half turn, the chord lie in the cone
    total = np.asarray(total)
    at_hi = total == hi  # parts turning one way: the total turn is an end of the range
    cos, sin = np.where(at_hi, cos_hi, cos_lo), np.where(at_hi, sin_hi, sin_lo)
    mixed = ~at_hi & (total != lo)
    if np.count_nonzero(mixed):
        np.cos(total, out=cos, where=mixed)
        np.sin(total, out=sin, where=mixed)
    ex, ey = cos * tax - sin * tay, sin * tax + cos * tay
    tbx, tby = tb
    ok = (np.abs(ex * tby - ey * tbx) <= CONSISTENT) & (ex * tbx + ey * tby > 0.0) & (width < 0.5 * np.pi)
    ok &= narrow | ((along_lo >= -slack) & (along_hi >= -slack))
    if along_mid is not None:  # (else no chord is 0 along its range's middle: its sign is proven)
        ok &= narrow | ~(length > 0) | (along_mid != 0.0)
    ok &= np.isfinite(bound)
    return bound if np.count_nonzero(ok) == ok.size else np.where(ok, bound, np.inf)


#: an interval whose bound is below RETRY tol is bounded again on FINE legs before it is split
RETRY = 2.0
FINE = 32
#: the bound's allowance for the round-off of exact points (a multiple of the largest coordinate)
ROUND_OFF = 1e-14


def angle_parts(turning):
    """``turning`` with its angle parts as ``(n, k)`` (a single part may come as ``(n,)``), called as
    :func:`interval_bounds` calls it: on parameters of any shape (flattened) and the intervals they
    belong to (one curve: not read)."""
    def call(w, rows=None):
        p, t, a = turning(np.ravel(w))
        return p, t, np.asarray(a, dtype=float).reshape(len(p), -1)
    return call


def _walk_bound(rows, pts, tan, parts, q, tq, pq, span=None):
    """Bound of the intervals ``rows`` (vertex ``rows`` to ``rows + 1``) over the legs through their
    probes ``q``, ``tq``, ``pq`` (points, tangents, parts; flat, the same number per interval); ``span``
    as :func:`interval_bounds`."""
    n = len(rows)

    def walk(at, inner, width):  # (width, probes + 2, n): each coordinate of a walk's point contiguous over the
        # intervals, so that every operation runs along them (not along a walk's few points, interval by interval)
        # (rows taken whole: indexing the first axis of a 2-d array copies it point by point)
        return np.concatenate([at.take(rows, axis=0)[:, None], inner.reshape(n, -1, width),
                               at.take(rows + 1, axis=0)[:, None]],
                              axis=1).transpose(2, 1, 0).copy()

    (px, py), (tx, ty) = walk(pts, q, 2), walk(tan, tq, 2)
    walked = walk(parts, pq, parts.shape[-1])
    if span is None:
        step = walked[:, 1:] - walked[:, :-1]  # (k, legs, n): the parts first, summed in their order
        turn = _sum_first(np.minimum(step, 0.0)), _sum_first(np.maximum(step, 0.0)), _sum_first(step)
    else:
        walked = walked.transpose(2, 1, 0)
        turn = tuple(np.ascontiguousarray(np.broadcast_to(v, (n, walked.shape[1] - 1)).T)
                     for v in span(walked[:, :-1], walked[:, 1:], rows))
    cx, cy = px[0], py[0]  # the walks' first and last points: each interval's ends
    chord = (cx, cy, px[-1] - cx, py[-1] - cy)
    dist = _distance(*chord, px, py)  # each probe's distance, shared by the two legs it ends
    return _legs(px[:-1], py[:-1], px[1:], py[1:], (tx[:-1], ty[:-1]), (tx[1:], ty[1:]), turn, chord,
                 np.maximum(dist[:-1], dist[1:])).max(axis=0)


def _sum_first(x):
    """:func:`_sum_parts` over the first axis: ``x[0] + x[1] + ...``, added in order."""
    total = x[0]
    for j in range(1, len(x)):
        total = total + x[j]
    return total


def fractions_of(lo, width, fractions):
    """``lo + width * f`` for every interval and fraction ``f``, ``(m, j)``: ``lo[:, None] + width[:, None] *
    fractions`` to the bit, computed along the intervals (``(j, m)``, a pass per operation) and turned.

    >>> fractions_of(np.array([0.0, 1.0]), np.array([1.0, 2.0]), np.array([0.25, 0.5])).tolist()
    [[0.25, 0.5], [1.5, 2.0]]
    """
    return np.ascontiguousarray((lo + width * np.asarray(fractions)[:, None]).T)


def put_rows(out, rows, values):
    """``out[rows] = values`` (``out`` C-contiguous, ``rows`` integers), each row of a multi-dimensional ``out``
    copied whole as one item of a row-sized type (indexing its first axis copies it element by element).

    >>> out = np.zeros((4, 2, 2))
    >>> put_rows(out, np.array([3, 1]), np.arange(8.0).reshape(2, 2, 2))
    >>> out[:, 0].tolist()
    [[0.0, 0.0], [4.0, 5.0], [0.0, 0.0], [0.0, 1.0]]
    """
    size = out.itemsize * (out.size // len(out)) if len(out) else 0  # bytes a row (not strides[0]: a first
    # axis of one row may have any stride in a contiguous array)
    if out.ndim == 1 or not len(rows) or not size or not out.flags.c_contiguous:
        out[rows] = values
        return
    row = np.dtype((np.void, size))
    values = np.ascontiguousarray(values, dtype=out.dtype).reshape(len(rows), -1)
    out.reshape(len(out), -1).view(row)[:, 0][rows] = values.view(row)[:, 0]


def interval_bounds(turning, w, pts, tan, parts, tol, fractions, rows=None, probed=None, span=None, more=None):
    """Probes of a sampling's intervals (at ``fractions`` of each) with their tangents and angle parts,
    and each interval's proven deviation bound: the largest :func:`leg_bound` of the legs between its ends
    and probes (``inf``: not proven). ``turning`` as :func:`angle_parts` returns it (called with the
    parameters ``(m, j)`` of ``m`` intervals and their indices ``(m,)``: a sampling of several curves
    tells its curves apart by them); ``pts``, ``tan``,
    ``parts`` are its values at the vertices ``w``; ``rows`` the intervals to bound (vertex ``i`` to
    ``i + 1``; default all), each bounded on its own. The bound leaves out the round-off of the exact
    points, :func:`round_off` of the sampling (it grows with the sampling's largest coordinate).
    Where the parts turn against each other (an inflection) a leg's range is wider than its turning:
    an interval bounded just above ``tol`` is bounded again on ``FINE`` legs (more proof, not more
    vertices). ``probed``: ``turning`` at the probes (flat), where the caller evaluated them already.
    ``span``: where the parts are not monotone, the curve's own range of each leg's tangent angle,
    ``span(parts_a, parts_b, rows) -> (lo, hi, total)`` from the parts at the legs' ends (``(m, legs, k)``
    each, of the intervals ``rows``; see :func:`monotone_range`), proven by the curve (e.g. from bounds of
    its tangent's rate). ``more``: fractions probed besides, only in the intervals ``fractions`` do not
    bound within ``tol``, each then bounded over the legs through all of its probes and given the lower
    of its two bounds (both proven); the probes returned are those at ``fractions`` alone."""
    rows = np.arange(len(w) - 1) if rows is None else rows
    lo, hi = w[rows], w[rows + 1]
    probes = fractions_of(lo, hi - lo, fractions)
    q, tq, pq = turning(probes, rows) if probed is None else probed
    bound = _walk_bound(rows, pts, tan, parts, q, tq, pq, span)
    if more is not None and len(unproven := (~(bound <= tol)).nonzero()[0]):
        bound[unproven] = np.minimum(bound[unproven], _more_bound(turning, rows[unproven], lo[unproven],
                                                                  hi[unproven], pts, tan, parts, fractions,
                                                                  (q, tq, pq), unproven, more, span))
    near = ((bound > tol) & (bound < RETRY * tol)).nonzero()[0]
    if len(near):
        fine = lo[near, None] + (hi - lo)[near, None] * np.linspace(0.0, 1.0, FINE + 1)[1:-1]
        bound[near] = np.minimum(bound[near], _walk_bound(rows[near], pts, tan, parts, *turning(fine, rows[near]),
                                                          span))
    m, k = len(lo), parts.shape[-1]
    return (probes, q.reshape(m, -1, 2), tq.reshape(m, -1, 2), pq.reshape(m, -1, k), bound)


def _more_bound(turning, rows, lo, hi, pts, tan, parts, fractions, probed, at, more, span):
    """:func:`_walk_bound` of the intervals ``rows`` (``lo`` to ``hi``) over the legs through their probes at
    ``fractions`` (``probed``: every interval's, flat; those of the intervals ``at`` taken) and at ``more``
    (evaluated here), the probes in the order of their fractions."""
    every = np.concatenate([np.asarray(fractions, dtype=float), np.asarray(more, dtype=float)])
    order = np.argsort(every, kind="stable")
    extra = turning(fractions_of(lo, hi - lo, more), rows)
    m, j = len(rows), len(fractions)
    walk = []
    for old, new in zip(probed, extra):
        old = old.reshape(-1, j, old.shape[-1])[at]
        walk.append(np.concatenate([old, new.reshape(m, -1, old.shape[-1])], axis=1)[:, order].reshape(-1, old.shape[-1]))
    return _walk_bound(rows, pts, tan, parts, *walk, span)


def round_off(pts) -> float:
    """The allowance a proven bound adds for the round-off of the exact points ``pts``: ``ROUND_OFF``
    of their largest coordinate."""
    return ROUND_OFF * float(np.abs(pts).max(initial=0.0))


def round_offs(pts, starts, owner):
    """:func:`round_off` of each of several curves' points, one after another (curve ``owner[i]`` the one of
    point ``i``, ``starts`` each curve's first point), at each interval (as its first point's curve)."""
    if len(starts) == 1:
        return round_off(pts)
    ends = np.concatenate([starts[1:], [len(pts)]])
    each = np.array([round_off(pts[a:b]) for a, b in zip(starts, ends)])
    return each[owner[:-1]]
