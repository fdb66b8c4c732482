"""Distances of points to a sampled curve: the measure every deviation in gearkit is checked by.

:func:`adaptive_sample` (:mod:`gearkit.accuracy`) places the vertices of a curve and reports
the deviation of its chords at its own probes; the functions here measure a polyline against
points of the exact curve taken independently (a dense sampling, an oracle's points), which is
how the tests, the bench and the checks read an outline's accuracy:

* :func:`nearest`: the nearest of a set of points to each query, by a blocked direct search (no
  tree to build and no scipy import for the few thousand points of a tooth);
* :func:`distances_to_polyline`: each point's distance to a polyline, through the edges at its
  nearest vertices (a k-d tree finds them above ``_DIRECT`` point pairs), and through every edge
  where a long edge might pass nearer;
* :func:`polyline_deviation`: the largest of those distances;
* :func:`edge_distances`: each point's distance to the nearest of all the edges of a long polyline,
  for points far from it compared with its own size (where a k-d tree visits most of it per point).

Examples
--------
The unit square as a closed polyline: a point 0.5 outside an edge and one at the centre.

>>> square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
>>> distances_to_polyline([[0.5, -0.5], [0.5, 0.5]], square, closed=True).tolist()
[0.5, 0.5]
>>> polyline_deviation(square, [[2.0, 0.5]], closed=True)
1.0
"""
from __future__ import annotations

import numpy as np

from gearkit.chords import chord_distance as _chord_deviation

__all__ = ["nearest", "distances_to_polyline", "polyline_deviation", "edge_distances"]


#: point pairs up to which :func:`distances_to_polyline` searches directly instead of through a k-d tree
_DIRECT = 4_000_000


def nearest(points, queries, k: int = 1, block: int = 1 << 17):
    """The ``k`` nearest of ``points`` to each of ``queries`` by direct search: ``(dist, idx)``.

    Shapes as a k-d tree query gives them: ``(m,)`` for ``k = 1``, else ``(m, k)`` (the k
    columns in no particular order). For the few hundred to few thousand sample points of
    one tooth a blocked direct search is as fast as building a tree and imports nothing;
    :func:`distances_to_polyline` switches to a k-d tree above ``_DIRECT`` point pairs. ``block``
    bounds the distance table worked on at once (1 MB: it stays in the processor's cache, several
    times faster than one large table for a few hundred points).

    Examples
    --------
    >>> d, i = nearest([[0.0, 0.0], [1.0, 0.0], [3.0, 0.0]], [[0.9, 0.0], [2.5, 1.0]])
    >>> i.tolist(), [round(float(x), 6) for x in d]
    ([1, 2], [0.1, 1.118034])
    """
    a = np.asarray(points, dtype=float)
    q = np.asarray(queries, dtype=float).reshape(-1, a.shape[1])
    k = min(int(k), len(a))
    idx = np.empty((len(q), k), dtype=np.intp)
    dist = np.empty((len(q), k))
    step = max(1, block // max(len(a), 1))
    a2 = np.einsum("ij,ij->i", a, a)
    for s in range(0, len(q), step):
        qs = q[s:s + step]
        rank = a2 - 2.0 * (qs @ a.T)  # |q - a|^2 - |q|^2: one matrix product ranks the points
        part = np.argmin(rank, axis=1)[:, None] if k == 1 else np.argpartition(rank, k - 1, axis=1)[:, :k]
        idx[s:s + step] = part
        dist[s:s + step] = np.linalg.norm(a[part] - qs[:, None, :], axis=-1)  # exact, not from the expansion
    return (dist[:, 0], idx[:, 0]) if k == 1 else (dist, idx)


def distances_to_polyline(points, polyline, closed: bool = False, neighbours: int = 6):
    """Distance of each point to a polyline: exact, through the edges at its nearest vertices.

    Each point is measured against the edges at its ``neighbours`` nearest vertices. An edge at none
    of them has both ends at least ``d_k`` away (the farthest of those vertices), so it lies at least
    ``sqrt(d_k^2 - (L/2)^2)`` away, ``L`` its length: where an edge is long enough to pass nearer
    than the distance found (an unevenly sampled polyline), the point is measured against every
    edge that long (or against all, :func:`edge_distances`, when they are many).

    Parameters
    ----------
    points : (k, 2) float64
    polyline : (n, 2) float64
    closed : bool, the last vertex joins the first

    Returns
    -------
    (k,) float64, mm

    Examples
    --------
    A long edge passing by a point whose six nearest vertices lie bunched far off:

    >>> line = [[-100.0, 1.0], [100.0, 1.0]] + [[float(i), -5.0] for i in range(8)]
    >>> distances_to_polyline([[0.0, 0.0]], line).tolist()
    [1.0]
    """
    a = np.asarray(polyline, dtype=float)
    q = np.asarray(points, dtype=float)
    n = len(a)
    k = min(neighbours, n)
    if n * len(q) <= _DIRECT:  # small: a direct search, no tree to build (and no scipy import)
        dist, idx = nearest(a, q, k=k)
    else:
        from scipy.spatial import cKDTree

        dist, idx = cKDTree(a).query(q, k=k)
    idx = np.atleast_2d(idx.T).T if idx.ndim == 1 else idx
    dist = np.atleast_2d(dist.T).T if dist.ndim == 1 else dist
    best = np.full(len(q), np.inf)
    for col in range(idx.shape[1]):
        for off in (0, -1):
            i = idx[:, col] + off
            if closed:
                i = i % n
                j = (i + 1) % n
            else:
                i = np.clip(i, 0, n - 2)
                j = i + 1
            best = np.minimum(best, _chord_deviation(a[i], a[j], q))
    if k < n:  # an edge not looked at has both ends at least d_k away: it lies no nearer than best
        ring = np.concatenate([a, a[:1]]) if closed else a  # unless it is longer than 2 sqrt(d_k^2 - best^2)
        length = np.hypot(*np.diff(ring, axis=0).T)
        d_k = dist.max(axis=1)
        longest = 2.0 * np.sqrt(np.maximum(d_k * d_k - best * best, 0.0))
        todo = np.flatnonzero(longest < length.max())
        if todo.size:  # such an edge within best of a point has an end within sqrt(best^2 + (L/2)^2) of it
            reach = np.sqrt(best[todo] ** 2 + 0.25 * length.max() ** 2)[:, None]
            lo, hi = (q[todo] - reach).min(axis=0), (q[todo] + reach).max(axis=0)
            inside = ((ring >= lo) & (ring <= hi)).all(axis=1)
            e = np.flatnonzero((inside[:-1] | inside[1:]) & (length > longest[todo].min()))  # might lie nearer
            if e.size and e.size * todo.size <= _DIRECT:
                step = max(1, (1 << 18) // e.size)
                for s in range(0, todo.size, step):
                    t = todo[s:s + step]
                    d = _chord_deviation(ring[e][None], ring[e + 1][None], q[t][:, None]).min(axis=1)
                    best[t] = np.minimum(best[t], d)
            elif e.size:  # many: every edge, pruned by spans (none: the distances found stand)
                best[todo] = np.minimum(best[todo], edge_distances(q[todo], a, closed, upper=best[todo]))
    return best


def polyline_deviation(polyline, exact_points, closed: bool = False) -> float:
    """Largest distance from points on the exact curve to a polyline: an independent deviation measure."""
    return float(distances_to_polyline(exact_points, polyline, closed).max(initial=0.0))


#: spans of edges per level of :func:`edge_distances` are powers of this
_FAN = 4


def _segment_distance(ax, ay, bx, by, qx, qy):
    """Distance of the points ``(qx, qy)`` from the segments ``(ax, ay)``-``(bx, by)`` (coordinates as
    separate arrays)."""
    dx, dy = bx - ax, by - ay
    dd = dx * dx + dy * dy
    px, py = qx - ax, qy - ay
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(dd > 0.0, np.clip((px * dx + py * dy) / dd, 0.0, 1.0), 0.0)
    return np.hypot(px - t * dx, py - t * dy)


def _spans(x, y, length, size):
    """Spans of ``size`` edges of the polyline ``(x, y)`` (``length`` along it at each vertex): their
    end vertices' indices, half lengths, and how far their vertices stray from their chords (the
    segments between their ends; 0 for single edges)."""
    edges = len(x) - 1
    ends = np.append(np.arange(0, edges, size), edges)
    dev = np.zeros(len(ends) - 1)
    if size > 1:
        owner = np.minimum(np.arange(len(x)) // size, len(ends) - 2)
        i, j = ends[owner], ends[owner + 1]
        np.maximum.at(dev, owner, _segment_distance(x[i], y[i], x[j], y[j], x, y))
    return ends, 0.5 * np.diff(length[ends]), dev


def edge_distances(points, polyline, closed: bool = False, block: int = 1024, upper=None):
    """Distance of each point to the nearest of all the edges of a polyline, by spans of edges.

    The edges are grouped in spans of ``4^k`` edges, ``4^(k-1)``, ... down to single edges. A
    point is no farther from the polyline than from any vertex (``upper``: the nearest span end seen
    so far), and no nearer to a span than its distance to the span's end vertices less half the
    span's length, nor than its distance to the span's chord (the segment between its ends) less
    how far the span's vertices stray from it (the span lies in that neighbourhood of the chord, a
    convex set). Level by level, a span that either bound puts beyond ``upper`` is dropped and the
    rest are split; the single edges left are measured. The result is the distance to the nearest of
    all the edges (a span dropped holds none nearer; the bounds allow ``1e-12`` of the largest
    coordinate for round-off). For points far from the polyline compared with its size (a roller's envelope
    against its own pitch curve: points inside a ring of vertices that hugs the circle of their
    distance about them), where a k-d tree visits most of the vertices for each point, a few spans
    per level are measured.

    Parameters
    ----------
    points : (k, 2) float64
    polyline : (n, 2) float64
    closed : bool, the last vertex joins the first
    upper : (k,) float64 or None, distances each point is known not to exceed (the length of a path
        to some edge): spans beyond them are dropped from the first level on

    Returns
    -------
    (k,) float64, mm

    Examples
    --------
    A regular 1000-gon of circumradius 1: from its centre, the apothem; from outside, the vertex.

    >>> t = np.linspace(0.0, 2.0 * np.pi, 1000, endpoint=False)
    >>> ring = np.stack([np.cos(t), np.sin(t)], -1)
    >>> d = edge_distances([[0.0, 0.0], [2.0, 0.0]], ring, closed=True)
    >>> bool(np.allclose(d, [np.cos(np.pi / 1000), 1.0], rtol=0, atol=1e-12))
    True
    """
    a = np.asarray(polyline, dtype=float)
    q = np.asarray(points, dtype=float).reshape(-1, 2)
    if closed:
        a = np.concatenate([a, a[:1]])
    edges = len(a) - 1
    if edges < 1:
        return np.hypot(q[:, 0] - a[0, 0], q[:, 1] - a[0, 1])
    x, y = a[:, 0].copy(), a[:, 1].copy()
    length = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
    sizes = [_FAN ** k for k in range(int(np.log(edges) / np.log(_FAN) + 1e-9), -1, -1)]
    levels = [_spans(x, y, length, size) for size in sizes]
    margin = 1e-12 * max(float(np.abs(a).max()), float(np.abs(q).max(initial=0.0)))  # round-off of a distance
    out = np.empty(len(q))
    known = np.full(len(q), np.inf) if upper is None else np.asarray(upper, dtype=float) + margin
    for s in range(0, len(q), block):
        out[s:s + block] = _nearest_edges(q[s:s + block, 0], q[s:s + block, 1], x, y, sizes, levels, margin,
                                          known[s:s + block])
    return out


#: most (point, span) pairs :func:`edge_distances` holds at once: a block of points that keeps more
#: (points at the centre of a circular stretch: every span stays) is split in two
_PAIRS = 1 << 19


def _nearest_edges(qx, qy, x, y, sizes, levels, margin, upper):
    """:func:`edge_distances` of one block of points ``(qx, qy)``, the spans' ``levels`` made, each
    point's distance known to be at most ``upper``."""
    n = len(qx)
    first = len(levels[0][0]) - 1
    pi, k = np.repeat(np.arange(n), first), np.tile(np.arange(first), n)  # every top span, by point
    upper = upper.copy()
    for level, (ends, half, dev) in enumerate(levels):
        if level:  # split the spans left into the next level's (grouped by point still)
            fan = sizes[level - 1] // sizes[level]
            if n > 1 and len(k) * fan > _PAIRS:
                h = n // 2
                return np.concatenate([_nearest_edges(qx[:h], qy[:h], x, y, sizes, levels, margin, upper[:h]),
                                       _nearest_edges(qx[h:], qy[h:], x, y, sizes, levels, margin, upper[h:])])
            k = (k[:, None] * fan + np.arange(fan)).ravel()
            pi = np.repeat(pi, fan)
            inside = k < len(ends) - 1
            pi, k = pi[inside], k[inside]
        px, py, i, j = qx[pi], qy[pi], ends[k], ends[k + 1]
        near = np.minimum(np.hypot(px - x[i], py - y[i]), np.hypot(px - x[j], py - y[j]))
        group = np.flatnonzero(np.diff(pi, prepend=-1))
        upper = np.minimum(upper, np.minimum.reduceat(near, group) + margin)
        chord = _segment_distance(x[i], y[i], x[j], y[j], px, py)
        if level == len(levels) - 1:  # single edges: the chord is the edge
            return np.minimum.reduceat(chord, group)
        keep = (near - half[k] - margin <= upper[pi]) & (chord - dev[k] - margin <= upper[pi])
        pi, k = pi[keep], k[keep]
