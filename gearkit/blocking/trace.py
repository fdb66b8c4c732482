"""Level sets ``f(x1, x2) = 0`` in a window, traced by continuation and root finding.

Seeds are the sign changes of ``f`` on the edges of a coarse grid, each refined by a bracketed
root. From a seed the curve is followed in both directions: a predictor steps ``h`` along the
tangent (extrapolated from the last chords, constant curvature), and a corrector solves
``f = 0`` along the coordinate axis most transverse to the curve (secant/Newton, falling back to
a bracketed root). A point is accepted when the last correction is at most ``xtol``, so every
vertex lies within ``xtol`` (in x) of the exact curve. A curve ends on the window's edge (its end
solved on the edge), where ``f`` is undefined (NaN: no pair exists there), or where it closes.

``f`` may have kinks (a margin that switches between two formulas); it must be continuous.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.accuracy import distances_to_polyline
from gearkit.curves import bracketed_root

__all__ = ["Window", "grid_seeds", "trace_curves"]


class Window:
    """Rectangle ``x1 in [a1, b1], x2 in [a2, b2]``."""

    def __init__(self, x1_lo: float, x1_hi: float, x2_lo: float, x2_hi: float):
        self.lo = np.array([x1_lo, x2_lo], dtype=float)
        self.hi = np.array([x1_hi, x2_hi], dtype=float)

    @property
    def size(self) -> float:
        return float(np.hypot(*(self.hi - self.lo)))

    def inside(self, p, slack: float = 0.0) -> bool:
        return bool(np.all(p >= self.lo - slack) and np.all(p <= self.hi + slack))

    def as_tuple(self) -> tuple:
        return (float(self.lo[0]), float(self.hi[0]), float(self.lo[1]), float(self.hi[1]))


def grid_seeds(f, xs, ys, values, xtol: float) -> list:
    """Points of ``f = 0`` on the edges of the grid ``xs`` x ``ys`` with node values ``values[j, i]``."""
    seeds = []
    ny, nx = values.shape
    for j in range(ny):
        for i in range(nx):
            v = values[j, i]
            for dj, di in ((0, 1), (1, 0)):
                jj, ii = j + dj, i + di
                if jj >= ny or ii >= nx:
                    continue
                w = values[jj, ii]
                if not (math.isfinite(v) and math.isfinite(w)) or (v > 0) == (w > 0) or (v == 0 and w == 0):
                    continue
                a = np.array([xs[i], ys[j]])
                b = np.array([xs[ii], ys[jj]])
                t = bracketed_root(lambda s: f(*(a + s * (b - a))), 0.0, 1.0, v, w,
                                   xtol=xtol / max(float(np.abs(b - a).max()), 1e-300))
                seeds.append(a + t * (b - a))
    return seeds


def _axis_root(f, p, k, d, xtol, h):
    """Solve ``f = 0`` moving coordinate ``k`` of ``p``; ``d`` is a derivative estimate. -> (point, d) or None."""
    x = p.copy()
    v = f(*x)
    if not math.isfinite(v):
        return None
    pos = neg = None
    for _ in range(10):
        if v == 0.0:
            return x, d
        if v > 0:
            pos = x[k]
        else:
            neg = x[k]
        if not (math.isfinite(d) and d != 0.0):
            e = 1e-3 * h
            x2 = x.copy()
            x2[k] += e
            v2 = f(*x2)
            if not math.isfinite(v2) or v2 == v:
                return None
            d = (v2 - v) / e
        step = -v / d
        if abs(step) > h:
            step = math.copysign(h, step)
        if abs(step) <= xtol:  # x (evaluated) is within |step| of the root
            return x, d
        x_new = x.copy()
        x_new[k] += step
        v_new = f(*x_new)
        if not math.isfinite(v_new):
            return None
        if v_new != v:
            d = (v_new - v) / step
        x, v = x_new, v_new
    if pos is None or neg is None:
        return None

    def g(s):
        q = x.copy()
        q[k] = s
        return f(*q)

    lo, hi = min(pos, neg), max(pos, neg)
    s = bracketed_root(g, lo, hi, xtol=0.5 * xtol / (1.0 + abs(lo)))
    x = x.copy()
    x[k] = s
    return x, d


def _edge_end(f, window, p, q, d_est, xtol, h):
    """Where the curve leaving the window between p (inside) and q (outside) meets the window edge."""
    span = q - p
    s_hit, k_edge, val = 1.0, None, None
    for k in (0, 1):
        for bound in (window.lo[k], window.hi[k]):
            if span[k] != 0:
                s = (bound - p[k]) / span[k]
                if 0 <= s <= s_hit:
                    s_hit, k_edge, val = s, k, bound
    if k_edge is None:
        return None
    b = p + s_hit * span
    b[k_edge] = val
    other = 1 - k_edge
    res = _axis_root(f, b, other, d_est[other], xtol, h)
    if res is None:
        return None
    e = res[0]
    if not window.inside(e, 1e-12) or np.hypot(*(e - p)) > 2.5 * h:
        return None
    return e


def _trace_one(f, window, seed, direction, grad, h0, xtol, max_points, prefer=None):
    """Follow the curve from ``seed`` along the unit ``direction``; returns (points, closed)."""
    pts = [seed.copy()]
    t = direction / np.hypot(*direction)
    d = np.array(grad, dtype=float)
    h = h0
    closed = False
    while len(pts) < max_points:
        p = pts[-1]
        q = p + h * t
        if not window.inside(q):
            e = _edge_end(f, window, p, q, d, xtol, h)
            if e is not None and np.hypot(*(e - p)) > 1e-12:
                pts.append(e)
            break
        k = 0 if abs(t[1]) >= abs(t[0]) else 1
        if prefer is not None:
            k_pref = prefer(q)
            if k_pref is not None and abs(t[1 - k_pref]) >= 0.35:
                k = k_pref
        res = _axis_root(f, q, k, d[k], xtol, h)
        new = dk = c = None
        dist = turn = 0.0
        if res is not None:
            new, dk = res
            dist = float(np.hypot(*(new - p)))
            if 1e-12 < dist < 2.0 * h:
                c = (new - p) / dist
                turn = math.atan2(t[0] * c[1] - t[1] * c[0], t @ c)
        smooth = c is not None and dist > 0.2 * h and abs(turn) < 0.35
        corner = c is not None and h < 0.02 * h0  # a kink of f's zero set: step through it
        if not (smooth or corner):
            h *= 0.5
            if h < 1e-4 * h0:
                break
            continue
        if not smooth:
            turn = 0.0
        d[k] = dk
        if abs(c[1 - k]) > 1e-3:  # gradient is normal to the chord
            d[1 - k] = -dk * c[k] / c[1 - k]
        # tangent at the new point: the chord turned on by the same angle again (constant curvature)
        ang = math.atan2(c[1], c[0]) + turn
        t = np.array([math.cos(ang), math.sin(ang)])
        pts.append(new)
        if len(pts) > 4 and np.hypot(*(new - seed)) < 0.75 * h and (seed - new) @ t > 0:
            pts.append(seed.copy())
            closed = True
            break
        h = min(h0, 1.5 * h)
    return np.array(pts), closed


def _gradient(f, p, h):
    e = 1e-4 * h
    v = f(*p)
    g = []
    for k in (0, 1):
        q = p.copy()
        q[k] += e
        g.append((f(*q) - v) / e)
    return np.array(g)


def trace_curves(f, window: Window, seeds, h: float, xtol: float, max_points: int = 4000, prefer=None,
                 near: float | None = None) -> list:
    """Every component of ``f = 0`` through ``seeds``: a list of ``(n, 2)`` polylines.

    A seed within ``near`` (default ``0.05 h``) of a traced component is taken as lying on it."""
    near = 0.05 * h + 10 * xtol if near is None else near
    curves = []
    todo = [np.asarray(s, dtype=float) for s in seeds]
    while todo:
        seed = todo.pop(0)
        g = _gradient(f, seed, h)
        if not np.all(np.isfinite(g)) or not g.any():
            continue
        t = np.array([-g[1], g[0]])
        fwd, closed = _trace_one(f, window, seed, t, g, h, xtol, max_points, prefer)
        if closed:
            line = fwd
        else:
            back, _ = _trace_one(f, window, seed, -t, g, h, xtol, max_points, prefer)
            line = np.concatenate([back[::-1], fwd[1:]])
        if len(line) >= 2:
            curves.append(line)
            if todo:
                close = distances_to_polyline(np.array(todo), line, closed=closed) < near
                todo = [s for s, n in zip(todo, close) if not n]
    return curves
