"""Vectorised plane-curve primitives: the involute function and its inverse, rotations,
polar angles, and polyline intersection.

Angles are radians; points are ``(n, 2)`` float64 arrays (mm).
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.roots import bracketed_root  # noqa: F401  (its home before the root finders were gathered)

# Taylor coefficients of tan(a) - a = sum c_k a^(2k+1), k >= 1 (odd Bernoulli-type series).
_INV_SERIES = (
    1.0 / 3.0,
    2.0 / 15.0,
    17.0 / 315.0,
    62.0 / 2835.0,
    1382.0 / 155925.0,
    21844.0 / 6081075.0,
    929569.0 / 638512875.0,
    6404582.0 / 10854718875.0,
)
_SERIES_REVERSED = tuple(reversed(_INV_SERIES))
_SERIES_ARRAYS = tuple(np.asarray(c) for c in _SERIES_REVERSED)
SERIES_LIMIT = 0.05  # |a| below which the series beats tan(a) - a (cancellation)
SERIES_FEW = 12  #: :func:`inv_series` sums on floats for at most this many angles (numpy's cost per call
#: outweighs the arithmetic; the same roundings)


def _is_scalar(x) -> bool:
    """True for a finite Python/NumPy real scalar (not bool, not an array)."""
    return isinstance(x, (float, int)) and not isinstance(x, bool) and math.isfinite(x)


def _series_scalar(a: float) -> float:
    """The series of ``inv`` at one float: :func:`inv_series`'s steps, each the same IEEE operation."""
    a2 = a * a
    series = 0.0
    for c in _SERIES_REVERSED:
        series = series * a2 + c
    return series * a2 * a


def _inv_scalar(a: float) -> float:
    """``inv`` of one float, with the same series below ``SERIES_LIMIT``."""
    if abs(a) < SERIES_LIMIT:
        return _series_scalar(a)
    return math.tan(a) - a


def inv(alpha):
    """Involute function ``inv a = tan a - a``.

    Accurate to a few ulp of the result for every ``a`` in ``[0, pi/2)``: below 0.05 rad
    a series replaces the cancelling difference.

    Parameters
    ----------
    alpha : array_like, rad

    Returns
    -------
    ndarray or float, rad

    Examples
    --------
    >>> round(float(inv(np.radians(20.0))), 7)
    0.0149044
    """
    if _is_scalar(alpha):  # plain-float fast path (pair formulas call this per point)
        return _inv_scalar(float(alpha))
    a = np.asarray(alpha, dtype=float)
    if a.ndim == 0:
        return _inv_scalar(float(a))
    with np.errstate(invalid="ignore"):
        out = np.tan(a) - a
        small = np.abs(a) < SERIES_LIMIT
    if np.count_nonzero(small):  # the series only where it is used (most calls have no small angle)
        out[small] = inv_series(a[small])
    return out if out.ndim else float(out)


def inv_series(a):
    """``inv a`` by its Taylor series, for an array of angles below 0.05 rad (what :func:`inv` uses
    there; no checks: for callers that have selected them).

    >>> bool(abs(inv_series(np.array([0.01]))[0] - (np.tan(0.01) - 0.01)) < 1e-18)
    True
    """
    if a.size <= SERIES_FEW:
        return np.array([_series_scalar(v) for v in a.ravel().tolist()], dtype=float).reshape(a.shape)
    a2 = a * a
    series = np.full(a.shape, _SERIES_REVERSED[0])  # (0 a2 + c is c)
    for c in _SERIES_ARRAYS[1:]:  # Horner in place, on 0-d coefficients (numpy converts a float on every call)
        series *= a2
        series += c
    series *= a2
    series *= a
    return series


def inv_inverse(value):
    """Inverse of the involute function: the angle ``a`` in ``[0, pi/2)`` with ``inv a = value``.

    Newton's method from a start to the right of the root (``inv`` is convex there, so
    the iteration decreases monotonically and cannot overshoot). Accurate to ~1e-15 rad
    from 1e-6 rad to 85 degrees.

    Examples
    --------
    >>> round(float(np.degrees(inv_inverse(0.0149044))), 4)
    20.0
    """
    if _is_scalar(value):  # plain-float fast path, the same iteration
        v = float(value)
        if v < 0 or not math.isfinite(v):
            raise ValueError("inv_inverse needs finite values >= 0")
        a = min((3.0 * v) ** (1.0 / 3.0), math.atan(v + math.pi / 2.0))
        for _ in range(60):
            t = math.tan(a)
            step = (_inv_scalar(a) - v) / (t * t) if t > 0 else 0.0
            a -= step
            if abs(step) <= 4e-16 * max(a, 1e-300):
                break
        return a
    v = np.asarray(value, dtype=float)
    if np.any(v < 0) or not np.all(np.isfinite(v)):
        raise ValueError("inv_inverse needs finite values >= 0")
    a = np.minimum(np.cbrt(3.0 * v), np.arctan(v + np.pi / 2.0))
    for _ in range(60):
        t = np.tan(a)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(t > 0, (inv(a) - v) / (t * t), 0.0)
        a = a - step
        if np.all(np.abs(step) <= 4e-16 * np.maximum(a, 1e-300)):
            break
    return a if a.ndim else float(a)


def rotation(angle):
    """2x2 rotation matrix (or stack ``(n, 2, 2)``) turning counter-clockwise by ``angle`` rad."""
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)


def rotate(points, angle, *more):
    """Rotate ``(n, 2)`` points counter-clockwise about the origin by ``angle`` (scalar or ``(n,)``).

    Further arrays ``more`` are rotated by the same angle (its sine and cosine taken once) and all
    are returned as a tuple.

    >>> a, b = rotate(np.array([[1.0, 0.0]]), np.pi / 2, np.array([[0.0, 2.0]]))
    >>> np.round(a, 12).tolist(), np.round(b, 12).tolist()
    ([[0.0, 1.0]], [[-2.0, 0.0]])
    """
    c, s = np.cos(angle), np.sin(angle)
    if more:
        return tuple(turn_by(v, c, s) for v in (points,) + more)
    return turn_by(points, c, s)


def turn_by(points, c, s):
    """``(n, 2)`` points turned counter-clockwise by the angle whose cosine and sine are ``c`` and ``s``
    (scalars or ``(n,)``): :func:`rotate` once it has them."""
    p = np.asarray(points, dtype=float)
    x, y = c * p[..., 0] - s * p[..., 1], s * p[..., 0] + c * p[..., 1]
    out = np.empty(np.shape(x) + (2,), dtype=np.result_type(x, y))  # np.stack's result, without its overhead
    out[..., 0] = x
    out[..., 1] = y
    return out


def polar_from_y(points):
    """Radius and angle of points, the angle measured from +y towards +x (a tooth's centre line).

    Returns
    -------
    rho : (n,) float64, mm
    psi : (n,) float64, rad
    """
    p = np.asarray(points, dtype=float)
    return np.hypot(p[..., 0], p[..., 1]), np.arctan2(p[..., 0], p[..., 1])


def cross2(a, b):
    """z-component of the cross product of 2-vectors (broadcasting)."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def polyline_self_intersections(points):
    """All proper crossings between non-adjacent edges of an open polyline.

    Parameters
    ----------
    points : (n, 2) float64

    Returns
    -------
    i, j : (k,) int
        Edge indices with ``i < j - 1`` (edge ``i`` runs from ``points[i]`` to ``points[i+1]``).
    ti, tj : (k,) float64
        Fractions along each edge of the crossing point.
    """
    p = np.asarray(points, dtype=float)
    a, b = p[:-1], p[1:]
    lo = np.minimum(a, b)
    hi = np.maximum(a, b)
    # an edge of no length (a repeated point) crosses nothing, and a run of them at one point would pair
    # each with every other in the sweep: only edges of some length take part
    live = ((a[:, 0] != b[:, 0]) | (a[:, 1] != b[:, 1])).nonzero()[0]
    lox, loy, hix, hiy = lo[:, 0], lo[:, 1], hi[:, 0], hi[:, 1]
    order = live[lox[live].argsort(kind="stable")]
    # candidate pairs: x-ranges overlap (sweep over edges sorted by their left end)
    reach = np.searchsorted(lox[order], hix[order], side="right")
    counts = reach - np.arange(len(order)) - 1
    counts = np.maximum(counts, 0)
    first = np.repeat(np.arange(len(order)), counts)
    offs = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
    second = first + 1 + offs
    ei, ej = order[first], order[second]
    swap = ei > ej
    ei, ej = np.where(swap, ej, ei), np.where(swap, ei, ej)
    keep = (ej - ei > 1) & (loy[ei] <= hiy[ej]) & (loy[ej] <= hiy[ei])
    ei, ej = ei[keep], ej[keep]
    ai, aj = a.take(ei, axis=0), a.take(ej, axis=0)  # rows whole (indexing copies a 2-d array point by point)
    d1 = b.take(ei, axis=0) - ai
    d2 = b.take(ej, axis=0) - aj
    den = cross2(d1, d2)
    r = aj - ai
    with np.errstate(divide="ignore", invalid="ignore"):
        ti = cross2(r, d2) / den
        tj = cross2(r, d1) / den
    ok = (den != 0) & (ti >= 0) & (ti <= 1) & (tj >= 0) & (tj <= 1)
    # edges that only touch end to end (a repeated vertex between them) do not cross
    ok &= ~(((ti == 0) | (ti == 1)) & ((tj == 0) | (tj == 1)))
    idx = np.lexsort((ej[ok], ei[ok]))
    return ei[ok][idx], ej[ok][idx], ti[ok][idx], tj[ok][idx]


def zoom_crossing(fa, fb, wa: float, wb: float, window_a, window_b, n: int = 33, rounds: int = 80):
    """The crossing of two exact curves ``fa``, ``fb`` near parameters ``(wa, wb)``, by zooming polylines.

    Each round samples both curves at ``n`` parameters across their windows and zooms into every
    crossing of the two polylines (narrowing both windows to two spacings either side of it), the
    least exact gap first: coarse chords may cross where the curves do not, and such a zoom ends
    when its polylines no longer cross. It
    needs no derivative, so it holds where a Newton step does not (a crossing at a small angle next
    to a cusp, where the gap is far from linear). Returns ``(wa, wb, gap)``: the pair with the
    smallest gap ``|fa(wa) - fb(wb)|`` seen, the estimate itself included.

    Examples
    --------
    >>> line = lambda w: np.stack([w, 0.0 * w], -1)
    >>> parabola = lambda w: np.stack([w, w * w - 0.25], -1)
    >>> a, b, gap = zoom_crossing(line, parabola, 0.4, 0.4, (0.0, 1.0), (0.0, 1.0))
    >>> round(a, 12), round(b, 12), gap < 1e-15
    (0.5, 0.5, True)
    """
    def gap(x, y):
        return float(np.hypot(*(fa(np.array([x]))[0] - fb(np.array([y]))[0])))

    best = (float(wa), float(wb), gap(wa, wb))
    stack = [(*window_a, *window_b)]  # windows still to zoom into: every crossing of a round is followed
    for _ in range(rounds * 4):
        if not stack:
            break
        la, ha, lb, hb = stack.pop()
        sa, sb = np.linspace(la, ha, n), np.linspace(lb, hb, n)
        pa, pb = fa(sa), fb(sb)
        d1, d2 = np.diff(pa, axis=0)[:, None], np.diff(pb, axis=0)[None]
        r = pb[None, :-1] - pa[:-1, None]
        den = cross2(d1, d2)
        with np.errstate(divide="ignore", invalid="ignore"):
            ti, tj = cross2(r, d2) / den, cross2(r, d1) / den
        i, j = np.nonzero((den != 0) & (ti >= 0) & (ti <= 1) & (tj >= 0) & (tj <= 1))
        step_a, step_b = (ha - la) / (n - 1), (hb - lb) / (n - 1)
        ca, cb = sa[i] + ti[i, j] * step_a, sb[j] + tj[i, j] * step_b
        gaps = np.hypot(*(fa(ca) - fb(cb)).T) if len(i) else np.zeros(0)
        for k in np.argsort(gaps)[::-1][-4:]:  # the least gap last: followed first
            if gaps[k] < best[2]:
                best = (float(ca[k]), float(cb[k]), float(gaps[k]))
            if gaps[k] > 0 and step_a > 1e-16 * max(abs(ca[k]), 1.0) and step_b > 1e-16 * max(abs(cb[k]), 1.0):
                stack.append((max(la, ca[k] - 2 * step_a), min(ha, ca[k] + 2 * step_a),
                              max(lb, cb[k] - 2 * step_b), min(hb, cb[k] + 2 * step_b)))
    return best


def roulette(s, base_curvature: float, a: float, ratio: float = 1.0, side: float = 1.0):
    """Cycloids, epicycloids and hypocycloids (and their curtate/prolate trochoids) in one form.

    A circle of radius ``|a|`` rolls without slip on a base curve through the origin tangent to
    +x: the x axis (``base_curvature = 0``) or the circle of radius ``1/base_curvature`` centred
    at ``(0, -1/base_curvature)``. The rolling circle lies on the +y side of the base for
    ``a > 0`` (outside a base circle: epicycloid) and on the -y side for ``a < 0`` (inside:
    hypocycloid). The traced point is at ``ratio * |a|`` from the rolling circle's centre and
    starts at the origin's side of it (``ratio = 1``: on the circle, a cusp at the origin).
    ``s`` is the rolled arc length on the base (mm, positive towards +x).

    Parameters
    ----------
    s : (n,) float64, mm
    base_curvature : float, 1/mm (0: straight base)
    a : float, mm, non-zero (signed)
    ratio : float, traced-point distance / |a|
    side : +1 or -1
        Which way the tangent points at a cusp (``s = 0``, ``ratio = 1``), where it is the limit
        from ``s * side > 0``.

    Returns
    -------
    points, tangents : (n, 2) float64 (tangents along increasing ``s``, not normalised)

    Examples
    --------
    >>> p, t = roulette(np.array([np.pi]), 0.0, 1.0)   # cycloid: the arch's top at (pi, 2)
    >>> np.round(p, 12).tolist(), np.round(t / np.linalg.norm(t), 12).tolist()
    ([[3.14159265359, 2.0]], [[1.0, 0.0]])
    """
    s = np.asarray(s, dtype=float)
    kb = float(base_curvature)
    phi = kb * s
    theta = phi + s / a
    if kb == 0.0:
        base = np.stack([s, np.zeros_like(s)], -1)
    else:
        base = np.stack([np.sin(phi) / kb, (np.cos(phi) - 1.0) / kb], -1)
    centre = base + a * np.stack([np.sin(phi), np.cos(phi)], -1)
    p = centre - ratio * a * np.stack([np.sin(theta), np.cos(theta)], -1)
    scale = 1.0 + a * kb
    if ratio == 1.0:
        # u(phi) - u(theta) = 2 sin((theta - phi)/2) (sin m, cos m), m = (phi + theta)/2: exact at the cusp
        half = np.sin(0.5 * (theta - phi))
        half = np.where(half == 0.0, side * np.sign(1.0 / a) * 1e-300, half)
        m = 0.5 * (phi + theta)
        t = (scale * np.sign(half))[..., None] * np.stack([np.sin(m), np.cos(m)], -1)
    else:
        t = scale * (np.stack([np.cos(phi), -np.sin(phi)], -1) - ratio * np.stack([np.cos(theta), -np.sin(theta)], -1))
    return p, t
