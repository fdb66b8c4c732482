"""The admissible region of a blocking contour: polygons of the shifts at which the check passes.

The region is the set where every hard margin of :class:`~gearkit.blocking.field.PairField` (and
the backlash) is >= 0, inside the window. Its boundary is the zero set of

    ``R(x1, x2) = min(hard margins, backlash, distances to the window's edges)``

(-1 where no pair exists; :func:`~gearkit.blocking.arrays.evaluator`'s ``"region"``), traced by
:func:`~gearkit.blocking.level.zero_lines` on a grid padded by one ring of nodes outside the window
(so every component closes). Each loop is a polygon;
loops inside an odd number of others are holes. Outer boundaries are counter-clockwise, holes
clockwise, so a matplotlib path (non-zero winding) and the even-odd rule agree.
"""
from __future__ import annotations

import numpy as np

from gearkit.blocking.grid import grid_values

__all__ = ["padded_grid", "pad", "orient_loops", "inside_polygons", "polygon_area", "best_point"]

SPLIT_DEPTH = 20  #: most self-crossings split out of one loop
FINE = 41  #: nodes per side of the local grid that looks for the best point of an empty region


def polygon_area(p) -> float:
    """Signed area (shoelace) of the closed polygon ``p`` (n, 2); positive when counter-clockwise."""
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def inside_polygons(polygons, points) -> np.ndarray:
    """Even-odd membership of ``points`` (n, 2) in the closed ``polygons``."""
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    out = np.zeros(len(pts), dtype=bool)
    for poly in polygons:
        a, b = poly[:-1], poly[1:]
        x, y = pts[:, 0:1], pts[:, 1:2]
        cond = (a[None, :, 1] > y) != (b[None, :, 1] > y)
        with np.errstate(divide="ignore", invalid="ignore"):
            xc = a[None, :, 0] + (y - a[None, :, 1]) * (b[None, :, 0] - a[None, :, 0]) / (b[None, :, 1] - a[None, :, 1])
        out ^= (np.count_nonzero(cond & (x < xc), axis=1) % 2).astype(bool)
    return out


def padded_grid(xs, ys):
    """The grid ``xs`` x ``ys`` with one more node on every side (outside the window)."""
    dx, dy = xs[1] - xs[0], ys[1] - ys[0]
    return (np.concatenate([[xs[0] - dx], xs, [xs[-1] + dx]]), np.concatenate([[ys[0] - dy], ys, [ys[-1] + dy]]))


def pad(values, fill: float):
    """``values`` (m, n) inside a ring of ``fill``: the node values of :func:`padded_grid`."""
    out = np.full((values.shape[0] + 2, values.shape[1] + 2), fill)
    out[1:-1, 1:-1] = values
    return out


def _simple_loops(p, depth: int = 0) -> list:
    """A closed loop split at its self-crossings into simple loops (a crossing of two of its edges
    within the tolerance band, e.g. where two parts of the region nearly touch)."""
    from gearkit.curves import polyline_self_intersections

    ei, ej, ti, _ = polyline_self_intersections(p)
    if not ei.size or depth > SPLIT_DEPTH:
        return [p]
    i, j = int(ei[0]), int(ej[0])
    x = p[i] + ti[0] * (p[i + 1] - p[i])
    a = np.vstack([p[:i + 1], x[None], p[j + 1:]])
    b = np.vstack([x[None], p[i + 1:j + 1], x[None]])
    return [q for part in (a, b) if len(part) >= 4 for q in _simple_loops(part, depth + 1)]


def orient_loops(loops, window, tol: float) -> tuple:
    """The region's polygons from the traced loops of ``R = 0``: closed, clipped to the window,
    slivers below the tolerance dropped, outer boundaries counter-clockwise and holes clockwise."""
    lo = np.array([window[0], window[2]])
    hi = np.array([window[1], window[3]])
    closed = []
    for p in loops:
        if len(p) < 3:
            continue
        if not np.array_equal(p[0], p[-1]):
            p = np.vstack([p, p[:1]])
        p = np.clip(p, lo, hi)
        if abs(polygon_area(p)) > (10 * tol) ** 2 or len(p) > 6:
            closed.append(p)
    closed = [q for p in closed for q in _simple_loops(p)]
    out = []
    for i, p in enumerate(closed):
        others = [q for j, q in enumerate(closed) if j != i]
        hole = bool(inside_polygons(others, p[:1])[0]) if others else False
        if (polygon_area(p) > 0) == hole:
            p = p[::-1].copy()
        out.append(p)
    return tuple(out)


def best_point(R, which, window, xs, ys, values):
    """The point of the window where ``R`` (function ``which`` of an array function, see
    :mod:`gearkit.blocking.level`) is largest: the best grid node, then finer local grids."""
    v = np.where(np.isfinite(values), values, -np.inf)
    j, i = np.unravel_index(np.argmax(v), v.shape)
    x, y = float(xs[i]), float(ys[j])
    hx, hy = xs[1] - xs[0], ys[1] - ys[0]
    for _ in range(3):
        fx = np.clip(np.linspace(x - hx, x + hx, FINE), window[0], window[1])
        fy = np.clip(np.linspace(y - hy, y + hy, FINE), window[2], window[3])
        fv = grid_values(R, fx, fy, which)
        jj, ii = np.unravel_index(np.argmax(np.where(np.isfinite(fv), fv, -np.inf)), fv.shape)
        x, y = float(fx[ii]), float(fy[jj])
        hx, hy = 2 * hx / (FINE - 1), 2 * hy / (FINE - 1)
    return x, y
