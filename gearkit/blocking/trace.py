"""Level sets ``f(x1, x2) = 0`` in a window, traced by continuation and root finding.

Seeds are the sign changes of ``f`` on the edges of a coarse grid; a seed is refined (a
bracketed root along its edge) only when no curve traced so far crosses that edge, so each
component costs one root, not one per grid edge. From a seed the curve is followed in both
directions: a predictor steps ``h`` along an arc that turns like the last chord did (constant
curvature), and a corrector solves ``f = 0`` along the coordinate axis most transverse to the
curve (secant/Newton with the derivative carried from the last point, falling back to a
bracketed root). A point is accepted when the last correction is at most ``xtol``, so every
vertex lies within ``xtol`` (in x) of the exact curve. Where the step has to shrink below
``h / 50`` (a sharp corner of the zero set, e.g. where a margin switches formulas) the curve is
continued from the zero of ``f`` on a circle of radius ``h / 50`` about the last point, the one
nearest ahead. A curve ends on the window's edge (its end solved on the edge), where ``f`` is
undefined (NaN: no pair exists there), or where it closes.

``f`` may have kinks (a margin that switches between two formulas); it must be continuous.

Cost (z1 = 13, z2 = 16, 200 points per line): about 2 to 3.5 evaluations of ``f`` per vertex.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.curves import bracketed_root

__all__ = ["EdgeSeed", "Window", "axis_root", "grid_seeds", "trace_curves"]


def _distances(points, line, closed=False):
    """Distance of each of ``points`` (k, 2) to the polyline ``line`` (n, 2), brute force in numpy
    (a traced line has a few hundred vertices; no spatial index, no scipy import on this path)."""
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    if closed:
        line = np.vstack([line, line[:1]])
    if len(line) == 1:
        return np.hypot(*(pts - line[0]).T)
    a, b = line[:-1], line[1:]
    ab = b - a
    L2 = np.maximum((ab ** 2).sum(1), 1e-300)
    ap = pts[:, None, :] - a[None, :, :]
    t = np.clip((ap * ab[None]).sum(2) / L2[None], 0.0, 1.0)
    d = ap - t[..., None] * ab[None]
    return np.sqrt((d ** 2).sum(2).min(1))


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


class EdgeSeed:
    """A sign change of ``f`` on the grid edge ``a -> b`` (node values ``va``, ``vb``), refined on demand.

    :func:`trace_curves` refines a seed (a bracketed root along the edge) only when no curve traced
    so far crosses its edge: one root per component instead of one per grid edge it crosses.
    """

    __slots__ = ("a", "b", "va", "vb")

    def __init__(self, a, b, va, vb):
        self.a, self.b, self.va, self.vb = a, b, va, vb

    def point(self, f, xtol: float):
        a, b = self.a, self.b
        t = bracketed_root(lambda s: f(*(a + s * (b - a))), 0.0, 1.0, self.va, self.vb,
                           xtol=xtol / max(float(np.abs(b - a).max()), 1e-300))
        return a + t * (b - a)


def grid_seeds(f, xs, ys, values, xtol: float, refine: bool = True) -> list:
    """Points of ``f = 0`` on the edges of the grid ``xs`` x ``ys`` with node values ``values[j, i]``.

    ``refine=False`` returns :class:`EdgeSeed` s (refined later, and only when needed, by
    :func:`trace_curves`)."""
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
                seed = EdgeSeed(np.array([xs[i], ys[j]]), np.array([xs[ii], ys[jj]]), v, w)
                seeds.append(seed.point(f, xtol) if refine else seed)
    return seeds


def _crosses(line, a, b) -> bool:
    """True when the polyline ``line`` (n, 2) meets the segment ``a -> b`` (touching counts)."""
    p, q = line[:-1], line[1:]
    d = b - a
    e = q - p

    def side(o, u, pts):
        return u[..., 0] * (pts[..., 1] - o[..., 1]) - u[..., 1] * (pts[..., 0] - o[..., 0])

    s1 = side(a, d, p)
    s2 = side(a, d, q)
    s3 = side(p, e, a)
    s4 = side(p, e, b)
    return bool(np.any((s1 * s2 <= 0) & (s3 * s4 <= 0)))


def axis_root(f, p, k, d, xtol, h):
    """Solve ``f(x1, x2) = 0`` moving coordinate ``k`` of the point ``p`` only: (point, derivative) or None.

    ``d`` is an estimate of ``df/dx_k`` (NaN: estimated here with a step ``1e-3 h``), ``xtol`` the
    accuracy in x, ``h`` the length scale of the search (a trace step).
    """
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
    res = axis_root(f, b, other, d_est[other], xtol, h)
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
    turned = False
    bend = 0.0  # turn of the last chord per unit length (half the curvature): the predictor follows it
    while len(pts) < max_points:
        p = pts[-1]
        b = bend * h
        q = p + h * np.array([t[0] * math.cos(b) - t[1] * math.sin(b), t[0] * math.sin(b) + t[1] * math.cos(b)])
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
        res = axis_root(f, q, k, d[k], xtol, h)
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
            if h < 0.02 * h0 and not turned:  # a sharp corner the axis corrector cannot turn
                e = _circle_step(f, p, t, 0.02 * h0, xtol)
                turned = True
                if e is not None and window.inside(e):
                    pts.append(e)
                    c = (e - p) / np.hypot(*(e - p))
                    bend = 0.0
                    h = 0.02 * h0
                    d = _gradient(f, e, h)
                    if not (np.all(np.isfinite(d)) and d.any()):
                        break
                    t = np.array([-d[1], d[0]]) / np.hypot(*d)  # the new branch's tangent, onwards
                    if t @ c < 0:
                        t = -t
                    continue
            if h < 1e-4 * h0:
                break
            continue
        turned = False
        if not smooth:
            turn = 0.0
        bend = turn / dist
        d[k] = dk
        if abs(c[1 - k]) > 1e-3:  # gradient is normal to the chord
            d[1 - k] = -dk * c[k] / c[1 - k]
        # tangent at the new point: the chord turned on by the same angle again (constant curvature)
        ang = math.atan2(c[1], c[0]) + turn
        t = np.array([math.cos(ang), math.sin(ang)])
        if len(pts) > 4 and _distances(seed, np.array([p, new]))[0] < 0.05 * h0 + 10 * xtol:
            pts.append(seed.copy())  # the step passed the seed: the curve is closed
            closed = True
            break
        pts.append(new)
        if len(pts) > 4 and np.hypot(*(new - seed)) < 0.75 * h and (seed - new) @ t > 0:
            pts.append(seed.copy())
            closed = True
            break
        h = min(h0, 1.5 * h)
    return np.array(pts), closed


CIRCLE_SAMPLES = 36  #: samples of f on the circle around a corner


def _circle_step(f, p, t, r, xtol):
    """Across a sharp corner: the zero of ``f`` on the circle of radius ``r`` about ``p`` nearest
    ahead of the unit tangent ``t`` (within +-0.9 pi of it), solved in angle to ``xtol``; None if none."""
    a0 = math.atan2(t[1], t[0])
    offs = np.linspace(-0.9 * math.pi, 0.9 * math.pi, CIRCLE_SAMPLES + 1)
    order = np.argsort(np.abs(offs), kind="stable")

    def g(off):
        return f(p[0] + r * math.cos(a0 + off), p[1] + r * math.sin(a0 + off))

    vals = {}
    best = None
    ahead = order[0]
    vals[ahead] = g(offs[ahead])
    if not math.isfinite(vals[ahead]):  # the curve runs into the undefined part (no pair): its end
        return None
    for i in order:  # ahead first: stop at the first sign change found
        for j in (i - 1, i + 1):
            if not 0 <= j < len(offs):
                continue
            for k in (i, j):
                if k not in vals:
                    vals[k] = g(offs[k])
            vi, vj = vals[i], vals[j]
            if math.isfinite(vi) and math.isfinite(vj) and (vi > 0) != (vj > 0):
                lo, hi = (i, j) if i < j else (j, i)
                best = (lo, hi)
                break
        if best is not None:
            break
    if best is None:
        return None
    lo, hi = best
    off = bracketed_root(g, offs[lo], offs[hi], vals[lo], vals[hi], xtol=0.5 * xtol / r)
    return p + r * np.array([math.cos(a0 + off), math.sin(a0 + off)])


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
    todo = list(seeds)
    while todo:
        seed = todo.pop(0)
        if isinstance(seed, EdgeSeed):
            seed = seed.point(f, xtol)
            if any(_distances(seed[None], c)[0] < near for c in curves):
                continue
        seed = np.asarray(seed, dtype=float)
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
            rest = []
            pts = [s for s in todo if not isinstance(s, EdgeSeed)]
            close = (_distances(np.array(pts, dtype=float), line, closed=closed) < near
                     if pts else [])
            k = 0
            for s in todo:
                if isinstance(s, EdgeSeed):
                    if not _crosses(line, s.a, s.b):
                        rest.append(s)
                else:
                    if not close[k]:
                        rest.append(s)
                    k += 1
            todo = rest
    return curves
