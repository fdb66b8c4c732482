"""Distances of points to a sampled curve: the measure every deviation in gearkit is checked by.

:func:`adaptive_sample` (:mod:`gearkit.accuracy`) places the vertices of a curve and reports
the deviation of its chords at its own probes; the functions here measure a polyline against
points of the exact curve taken independently (a dense sampling, an oracle's points), which is
how the tests, the bench and the checks read an outline's accuracy:

* :func:`nearest`: the nearest of a set of points to each query, by a blocked direct search (no
  tree to build and no scipy import for the few thousand points of a tooth);
* :func:`distances_to_polyline`: each point's distance to a polyline, through the edges at its
  nearest vertices (a k-d tree finds them above ``_DIRECT`` point pairs);
* :func:`polyline_deviation`: the largest of those distances.

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

__all__ = ["nearest", "distances_to_polyline", "polyline_deviation"]


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
    """Distance of each point to a (dense) polyline, via its nearest vertices' edges.

    Parameters
    ----------
    points : (k, 2) float64
    polyline : (n, 2) float64
    closed : bool, the last vertex joins the first

    Returns
    -------
    (k,) float64, mm
    """
    a = np.asarray(polyline, dtype=float)
    q = np.asarray(points, dtype=float)
    n = len(a)
    if n * len(q) <= _DIRECT:  # small: a direct search, no tree to build (and no scipy import)
        _, idx = nearest(a, q, k=min(neighbours, n))
    else:
        from scipy.spatial import cKDTree

        _, idx = cKDTree(a).query(q, k=min(neighbours, n))
    idx = np.atleast_2d(idx.T).T if idx.ndim == 1 else idx
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
    return best


def polyline_deviation(polyline, exact_points, closed: bool = False) -> float:
    """Largest distance from points on the exact curve to a polyline: an independent deviation measure."""
    return float(distances_to_polyline(exact_points, polyline, closed).max(initial=0.0))
