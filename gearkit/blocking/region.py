"""The admissible region of a blocking contour: where no hard margin of the pair is violated.

The zero set of ``min(hard margins, window margins)`` (:func:`admissible_region`) is contoured on
the lines' seed grid, its vertices moved onto the exact boundary and the corners between two
binding margins solved and inserted; an empty region comes with the reason (the margins the best
point of the window still violates).
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.blocking.field import PairField
from gearkit.blocking.trace import Window
from gearkit.curves import bracketed_root

__all__ = ["GRID", "admissible_region", "polygon_area"]

GRID = 17  # seed grid nodes per side (the lines' and the region's)


def polygon_area(p) -> float:
    """Signed area of the polygon ``p`` (``(n, 2)``; positive counter-clockwise).

    Examples
    --------
    >>> polygon_area(np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]]))
    2.0
    """
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def _region_function(field: PairField, window: Window):
    lo, hi = window.lo, window.hi

    def f(x1, x2):
        w = min(x1 - lo[0], hi[0] - x1, x2 - lo[1], hi[1] - x2)
        pt = field.point(x1, x2)
        if not pt.valid:
            return min(w, -1.0)
        m = min(pt.hard_margins().values())
        return min(w, m) if math.isfinite(m) else min(w, -1.0)
    return f


def admissible_region(field: PairField, w: Window, xtol: float, n: int = GRID):
    """Polygons of the admissible region (closed, counter-clockwise) and, when empty, the reason.

    The zero set of ``min(hard margins, window margins)`` is contoured on an ``n`` x ``n`` grid
    (its topology; the lines' seed grid, whose margins are already evaluated), every vertex is
    moved onto the exact boundary by a bracketed root along the grid edge it lies on (to
    ``xtol``), and where two neighbouring vertices are bound by different margins the corner
    between them (both margins zero) is solved by Newton's method and inserted: the polygon's
    vertices lie on the boundary, its chords cut no corner.
    """
    import contourpy

    fr = _region_function(field, w)
    xs = np.linspace(w.lo[0], w.hi[0], n)
    ys = np.linspace(w.lo[1], w.hi[1], n)
    vals = np.array([[fr(x, y) for x in xs] for y in ys])
    if np.all(vals[1:-1, 1:-1] > 0):
        box = np.array([[w.lo[0], w.lo[1]], [w.hi[0], w.lo[1]], [w.hi[0], w.hi[1]], [w.lo[0], w.hi[1]]])
        return (_ccw(box),), None
    if not np.any(vals > 0):
        return (), _empty_reason(field, fr, xs, ys, vals)
    dx, dy = xs[1] - xs[0], ys[1] - ys[0]
    px = np.concatenate([[xs[0] - dx], xs, [xs[-1] + dx]])
    py = np.concatenate([[ys[0] - dy], ys, [ys[-1] + dy]])
    pv = np.full((n + 2, n + 2), -1.0)
    pv[1:-1, 1:-1] = np.where(np.isfinite(vals), vals, -1.0)
    loops = contourpy.contour_generator(px, py, pv, name="serial").lines(0.0)
    polys = []
    for loop in loops:
        loop = np.array(loop, dtype=float)
        for v in loop:
            i = (v[0] - xs[0]) / dx
            j = (v[1] - ys[0]) / dy
            if abs(j - round(j)) < 1e-9 and 0 <= math.floor(i) < n - 1:  # on a row: move along x
                a, b = xs[int(math.floor(i))], xs[int(math.floor(i)) + 1]
                y = ys[int(round(j))]
                fa, fb = fr(a, y), fr(b, y)
                if (fa > 0) != (fb > 0):
                    v[0] = bracketed_root(lambda t: fr(t, y), a, b, fa, fb, xtol=0.5 * xtol / (1 + abs(a)))
            elif abs(i - round(i)) < 1e-9 and 0 <= math.floor(j) < n - 1:
                a, b = ys[int(math.floor(j))], ys[int(math.floor(j)) + 1]
                x = xs[int(round(i))]
                fa, fb = fr(x, a), fr(x, b)
                if (fa > 0) != (fb > 0):
                    v[1] = bracketed_root(lambda t: fr(x, t), a, b, fa, fb, xtol=0.5 * xtol / (1 + abs(a)))
        loop = _with_corners(field, w, loop, xtol, max(dx, dy))
        np.clip(loop, w.lo, w.hi, out=loop)
        poly = _ccw(loop)
        if abs(polygon_area(poly)) > (10 * xtol) ** 2:
            polys.append(poly)
    return tuple(polys), None


def _named_margins(field: PairField, w: Window, p) -> dict:
    """Hard margins and the four window margins at ``p`` (empty where no pair exists)."""
    pt = field.point(p[0], p[1])
    if not pt.valid:
        return {}
    out = dict(pt.hard_margins())
    out.update({"window.x1_lo": p[0] - w.lo[0], "window.x1_hi": w.hi[0] - p[0],
                "window.x2_lo": p[1] - w.lo[1], "window.x2_hi": w.hi[1] - p[1]})
    return out


def _binding_name(field, w, p):
    m = _named_margins(field, w, p)
    m = {k: v for k, v in m.items() if math.isfinite(v)}
    return min(m, key=m.get) if m else None


def _corner(field, w, a, b, name_a, name_b, xtol, cell):
    """The point near the chord a-b where margins ``name_a`` and ``name_b`` both vanish, or None."""
    def both(p):
        m = _named_margins(field, w, p)
        return np.array([m.get(name_a, math.nan), m.get(name_b, math.nan)])

    p = 0.5 * (a + b)
    e = 1e-7
    for _ in range(12):
        v = both(p)
        if not np.all(np.isfinite(v)):
            return None
        jac = np.column_stack([(both(p + [e, 0.0]) - v) / e, (both(p + [0.0, e]) - v) / e])
        if not np.all(np.isfinite(jac)) or abs(np.linalg.det(jac)) < 1e-12:
            return None
        step = np.linalg.solve(jac, -v)
        p = p + step
        if np.hypot(*step) <= xtol:
            break
    else:
        return None
    if np.hypot(*(p - 0.5 * (a + b))) > 1.5 * cell or not w.inside(p, 1e-9):
        return None
    m = _named_margins(field, w, p)
    if not m or min(m.values()) < -10 * xtol * max(1.0, np.abs(jac).max()):
        return None  # a third margin is violated there: not a corner of the region
    return p


def _with_corners(field, w, loop, xtol, cell):
    """``loop`` with the corners between differently bound neighbouring vertices inserted."""
    names = [_binding_name(field, w, v) for v in loop]
    out = [loop[0]]
    for i in range(1, len(loop)):
        na, nb = names[i - 1], names[i]
        if na is not None and nb is not None and na != nb:
            c = _corner(field, w, loop[i - 1], loop[i], na, nb, xtol, cell)
            if c is not None:
                out.append(c)
        out.append(loop[i])
    return np.array(out)


def _ccw(poly):
    if not np.allclose(poly[0], poly[-1]):
        poly = np.vstack([poly, poly[:1]])
    return poly if polygon_area(poly) >= 0 else poly[::-1]


def _empty_reason(field, f, xs, ys, values) -> str:
    j, i = np.unravel_index(np.nanargmax(np.where(np.isfinite(values), values, -np.inf)), values.shape)
    x1, x2 = float(xs[i]), float(ys[j])
    try:
        from scipy.optimize import minimize
        res = minimize(lambda p: -f(*p), [x1, x2], method="Nelder-Mead",
                       options={"xatol": 1e-6, "fatol": 1e-9, "maxfev": 400})
        if -res.fun > f(x1, x2):
            x1, x2 = map(float, res.x)
    except Exception:  # pragma: no cover - the grid point is a fine fallback
        pass
    pt = field.point(x1, x2)
    if not pt.valid:
        return f"no pair exists in the window (e.g. at x1 = {x1:.4f}, x2 = {x2:.4f}: {pt._invalid})"
    bad = [(n, v) for n, v in pt.hard_margins().items() if not (v >= 0)]
    names = ", ".join(f"{field.by_name[n].code} {n} (margin {v:.4g})" for n, v in sorted(bad, key=lambda t: t[1]))
    return (f"no shift pair passes the check: even the best point x1 = {x1:.4f}, x2 = {x2:.4f} "
            f"violates {names}")
