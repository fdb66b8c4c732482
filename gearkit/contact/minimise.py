"""The minimum of a bound function along polyline intervals, one interval per row, all rows at once.

The contact solver (:mod:`gearkit.contact.solver`) hands over a *task*: the bound function of each
row, ``task.value(t, rows)`` (values only) and, where the teeth are evaluated on their tables,
``task.slope(t, rows)`` (value, first and second derivative in ``t``; ``task.smooth`` says so);
``task.noise`` (optional) bounds the error of its values; ``task.grid_values(grid)`` (optional, with
``task.interval``) gives the values of the probes below at once, ``(P, n)``.

1. **Probes.** The function is sampled at the interval's ends and at ``_PROBES`` interior points.
   The best sample brackets the minimum with its neighbours; an end sample is the minimum when the
   function rises from it (second-order one-sided slope, step 1e-7 of the interval, beyond its values'
   noise and round-off: where a piece's parametrisation is stationary at its end, as on a cycloid's cusp
   on the pitch circle, that slope is nil whichever way the function runs) and, on tables with derivatives,
   when the derivatives on the end agree (an end on a knot of the tables is read off the next polynomial:
   the joint's mismatch over that step can fake a rise).
2. **Newton** on the derivative (tables): from the best sample, steps ``-f'/f''`` kept inside the
   bracket, which every evaluation narrows by the sign of ``f'`` (bisection when a step would leave
   it or ``f''`` is not positive). Quadratic convergence: a handful of evaluations to round-off.
3. **Brent's method** on values, for rows without derivatives (the exact pieces) and for any row
   Newton leaves (a non-finite value in its bracket, e.g. a last bit beyond the mate's tip):
   parabolic steps from the three best points, golden-section steps when a parabola is not trusted.

Examples
--------
A parabola with its minimum at 0.3 in ``[0, 1]``, found by Newton on its derivatives:

>>> class Parabola:
...     smooth = True
...     def value(self, t, rows=slice(None)):
...         return ((t - 0.3) ** 2,)
...     def slope(self, t, rows):
...         return (t - 0.3) ** 2, 2 * (t - 0.3), np.full_like(t, 2.0)
>>> v, t = minimise(Parabola(), np.zeros(1), np.ones(1))
>>> bool(abs(t[0] - 0.3) < 1e-15), bool(v[0] < 1e-30)
(True, True)
"""
from __future__ import annotations

import numpy as np

__all__ = ["minimise", "newton_from"]

#: Brent iterations, Newton iterations (both converge long before)
_MIN_ITER = 60
_NEWTON_ITER = 60
_GOLD = 0.3819660112501051
#: interior samples of an interval before the bracket is narrowed
_PROBES = 5
#: Newton stops when its step (or its bracket) is below this fraction of the interval
_NEWTON_TOL = 1e-12
#: :func:`newton_from` confirms a minimum at most this fraction of the interval from its start
_TRAVEL = 0.25


def minimise(task, a, b):
    """Minimum of the bound function on ``[a, b]`` (finite there), per row: ``(value, parameter)``."""
    width = b - a
    h = 1e-7 * width
    n = len(a)
    frac = np.linspace(0.0, 1.0, _PROBES + 2)
    grid = a[None, :] + frac[:, None] * width[None, :]  # (P, n)
    if task.smooth:  # the one-sided slopes only where the best sample is an end (values alone on tables)
        if getattr(task, "grid_values", None) is not None and getattr(task, "interval", None) is not None:
            vg = task.grid_values(grid)
        else:
            vg = task.value(grid.ravel(), np.tile(np.arange(n), len(frac)))[0].reshape(grid.shape)
        j = np.argmin(vg, axis=0)
        ea, eb = np.flatnonzero(j == 0), np.flatnonzero(j == len(frac) - 1)
        v = task.value(np.concatenate([a[ea] + h[ea], a[ea] + 2 * h[ea], b[eb] - h[eb], b[eb] - 2 * h[eb]]),
                       np.concatenate([ea, ea, eb, eb]))[0]
        va1, va2, vb1, vb2 = np.full((4, n), np.nan)
        va1[ea], va2[ea], vb1[eb], vb2[eb] = np.split(v, np.cumsum([len(ea), len(ea), len(eb)]))
    else:
        pts = np.concatenate([grid.ravel(), a + h, a + 2 * h, b - h, b - 2 * h])
        rows_all = np.concatenate([np.tile(np.arange(n), len(frac)), np.tile(np.arange(n), 4)])
        v = task.value(pts, rows_all)[0]
        vg = v[:grid.size].reshape(grid.shape)
        va1, va2, vb1, vb2 = v[grid.size:].reshape(4, n)
        j = np.argmin(vg, axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        da = (-3 * vg[0] + 4 * va1 - va2) / (2 * h)
        db = (3 * vg[-1] - 4 * vb1 + vb2) / (2 * h)
    best_v = vg[j, np.arange(n)]
    best_t = grid[j, np.arange(n)]
    at_a, at_b = j == 0, j == len(frac) - 1
    # an end is the minimum where the function rises from it by more than its values' noise over the
    # step can fake (values on tables carry their fitting error: a flat end is searched, not settled)
    # (and by more than the values' round-off: at an end where the piece's parametrisation is stationary, a cycloid's
    # cusp on the pitch circle, the one-sided slope is nil whichever way the function runs, and round-off set its sign)
    rise = (2.0 * getattr(task, "noise", 0.0) + getattr(task, "roundoff", 0.0)) / h
    end_a, end_b = at_a & ~(da < rise), at_b & ~(db > -rise)
    if task.smooth:
        # the one-sided difference reads an end that is a knot of the tables off the next polynomial and the points
        # inside off this one: their joint's mismatch (within the tables' tolerance, a few 1e-14 on the value) over
        # the step can fake a rise; an end is settled only where the derivatives agree (:func:`_rises`, as
        # :func:`newton_from` confirms an end), else searched (the search keeps the end where nothing is lower)
        for end, at, inward in ((end_a, a, 1.0), (end_b, b, -1.0)):
            e = np.flatnonzero(end)
            if e.size:
                end[e] = _rises(task, e, at[e], inward, _TRAVEL * width[e])
    settled = (width <= 0) | end_a | end_b
    rows = np.flatnonzero(~settled)
    if rows.size == 0:
        return best_v, best_t
    jr = j[rows]
    lo = grid[np.maximum(jr - 1, 0), rows]
    hi = grid[np.minimum(jr + 1, len(frac) - 1), rows]
    x = np.where(at_a[rows] | at_b[rows], 0.5 * (lo + hi), grid[jr, rows])
    if task.smooth:
        x, fx, done = _newton(task, rows, width[rows], lo.copy(), hi.copy(), x)
    else:
        fx, done = np.full(rows.size, np.inf), np.zeros(rows.size, bool)
    rest = np.flatnonzero(~done)
    if rest.size:
        r = rows[rest]
        start = np.where(at_a[r] | at_b[r], task.value(x[rest], r)[0], vg[jr[rest], r])
        x[rest], fx[rest] = _brent(task, r, width[r], lo[rest], hi[rest], x[rest], start)
    better = fx < best_v[rows]
    best_v[rows] = np.where(better, fx, best_v[rows])
    best_t[rows] = np.where(better, x, best_t[rows])
    return best_v, best_t


def newton_from(task, a, b, x, iterations):
    """Newton on the derivatives (a :attr:`smooth` task) in ``[a, b]`` from a start ``x`` close to the minimum, at
    most ``iterations`` steps: ``(value, parameter, ok)``.

    A start beyond an end is moved onto it. ``ok`` where the iteration converged to a minimum strictly inside
    (farther than its tolerance from either end), or stayed on an end (``a``, or ``a + (b - a)`` as
    :func:`minimise` spaces its probes) because the function rises from it there; a row that ends near an end
    from inside starts once more from that end. Elsewhere (an evaluation not finite, no convergence, a minimum
    farther than ``_TRAVEL`` of the interval from the start: the start was no continuation of it) the caller
    minimises afresh.
    """
    n = len(a)
    width = b - a
    end = a + width
    x0 = np.minimum(np.maximum(x, a), end)
    x, fx, done = _newton(task, np.arange(n), width, a.copy(), b.copy(), x0, iterations)
    tol = _NEWTON_TOL * width
    on_end = ((x == a) | (x == end)) & done
    if on_end.any():
        at = np.flatnonzero(on_end)
        on_end[at] = _rises(task, at, x[at], np.where(x[at] == a[at], 1.0, -1.0), _TRAVEL * width[at])
    ok = done & (((x > a + tol) & (x < b - tol)) | on_end) & (np.abs(x - x0) <= _TRAVEL * width)
    again = np.flatnonzero(~ok)
    if again.size:  # once more from the nearer end, where the minimum may sit
        e = np.where(x[again] - a[again] < end[again] - x[again], a[again], end[again])
        x2, f2, d2 = _newton(task, again, width[again], a[again].copy(), b[again].copy(), e, 1)
        settled = d2 & (x2 == e) & (np.abs(e - x0[again]) <= _TRAVEL * width[again])
        if settled.any():
            s = np.flatnonzero(settled)
            settled[s] = _rises(task, again[s], e[s], np.where(e[s] == a[again[s]], 1.0, -1.0),
                                _TRAVEL * width[again[s]])
        at = again[settled]
        x[at], fx[at], ok[at] = e[settled], f2[settled], True
    return fx, x, ok


def _rises(task, rows, x, inward, span):
    """Whether the function rises from the ends ``x`` of rows ``rows`` into the interval (``inward`` +1 from the
    start, -1 from the end) over ``span`` by its second-order model: a slope into the interval not negative and not
    undone by the curvature within ``span``. (A slope alone misleads where the piece's parametrisation is stationary
    at its end, a cycloid's cusp on the pitch circle: the slope is nil there whichever way the function runs.)"""
    _, g, g1 = task.slope(x, rows)
    d = inward * g
    return (d >= 0) & (d + 0.5 * g1 * span >= 0)


def _newton(task, rows, width, lo, hi, x, iterations=_NEWTON_ITER):
    """Safeguarded Newton on ``f' = 0`` in ``[lo, hi]`` from ``x``: ``(x, f(x), converged)``; a row whose
    evaluation is not finite is left (not converged) at its start."""
    x0 = x.copy()
    x = x.copy()
    fx = np.full(rows.size, np.inf)
    done = np.zeros(rows.size, bool)
    failed = np.zeros(rows.size, bool)
    todo = np.arange(rows.size)
    for _ in range(iterations):
        xt = x[todo]
        f, g, g1 = task.slope(xt, rows[todo])
        bad = ~(np.isfinite(f) & np.isfinite(g) & np.isfinite(g1))
        fx[todo] = f
        lo_, hi_ = np.where(g < 0, xt, lo[todo]), np.where(g > 0, xt, hi[todo])
        with np.errstate(divide="ignore", invalid="ignore"):
            step = -g / g1
        xn = xt + step
        tol = _NEWTON_TOL * width[todo]
        # converged: the next step is below the tolerance (it may round onto x itself)
        stop = (g == 0) | ((g1 > 0) & (np.abs(step) <= tol)) | (hi_ - lo_ <= tol)
        xn = np.where((g1 > 0) & (xn > lo_) & (xn < hi_), xn, 0.5 * (lo_ + hi_))
        failed[todo[bad]] = True
        done[todo[stop & ~bad]] = True
        lo[todo], hi[todo] = lo_, hi_
        go = ~(stop | bad)
        x[todo[go]] = xn[go]
        todo = todo[go]
        if todo.size == 0:
            break
    x = np.where(failed, x0, x)
    return x, np.where(failed, np.inf, fx), done


def _brent(task, rows, width, lo, hi, x, fx):
    """Brent's minimisation in ``[lo, hi]`` from ``x`` (value ``fx``), comparing values only: ``(x, f(x))``."""
    x, fx, lo, hi = x.copy(), fx.copy(), lo.copy(), hi.copy()
    xw, fw, xv, fv = x.copy(), fx.copy(), x.copy(), fx.copy()
    d = np.zeros(rows.size)
    e = np.zeros(rows.size)
    todo = np.arange(rows.size)
    for _ in range(_MIN_ITER):
        tol1 = 1e-8 * np.abs(x[todo]) + 1e-10 * width[todo]
        todo = todo[np.abs(x[todo] - 0.5 * (lo[todo] + hi[todo])) > 2 * tol1 - 0.5 * (hi[todo] - lo[todo])]
        if todo.size == 0:
            break
        x_, fx_, w_, fw_, v_, fv_ = x[todo], fx[todo], xw[todo], fw[todo], xv[todo], fv[todo]
        lo_, hi_, d_, e_ = lo[todo], hi[todo], d[todo], e[todo]
        mid = 0.5 * (lo_ + hi_)
        tol1 = 1e-8 * np.abs(x_) + 1e-10 * width[todo]
        with np.errstate(invalid="ignore", over="ignore", divide="ignore"):  # inf values: golden steps
            r = (x_ - w_) * (fx_ - fv_)
            q = (x_ - v_) * (fx_ - fw_)
            p = (x_ - v_) * q - (x_ - w_) * r
            q = 2 * (q - r)
            p = np.where(q > 0, -p, p)
            q = np.abs(q)
            e_old = e_
            para = (np.abs(e_old) > tol1) & (np.abs(p) < np.abs(0.5 * q * e_old)) & (p > q * (lo_ - x_)) \
                & (p < q * (hi_ - x_))
            step_p = p / q
        golden_e = np.where(x_ >= mid, lo_ - x_, hi_ - x_)
        e_new = np.where(para, d_, golden_e)
        d_new = np.where(para, step_p, _GOLD * golden_e)
        u = x_ + d_new
        near_end = para & ((u - lo_ < 2 * tol1) | (hi_ - u < 2 * tol1))
        d_new = np.where(near_end, np.copysign(tol1, mid - x_), d_new)
        u = np.where(np.abs(d_new) >= tol1, x_ + d_new, x_ + np.copysign(tol1, d_new))
        fu = task.value(u, rows[todo])[0]
        better = fu <= fx_
        lo_n = np.where(better, np.where(u >= x_, x_, lo_), np.where(u < x_, u, lo_))
        hi_n = np.where(better, np.where(u >= x_, hi_, x_), np.where(u < x_, hi_, u))
        shift_w = ~better & ((fu <= fw_) | (w_ == x_))
        shift_v = ~better & ~shift_w & ((fu <= fv_) | (v_ == x_) | (v_ == w_))
        xv[todo] = np.where(better | shift_w, w_, np.where(shift_v, u, v_))
        fv[todo] = np.where(better | shift_w, fw_, np.where(shift_v, fu, fv_))
        xw[todo] = np.where(better, x_, np.where(shift_w, u, w_))
        fw[todo] = np.where(better, fx_, np.where(shift_w, fu, fw_))
        x[todo] = np.where(better, u, x_)
        fx[todo] = np.where(better, fu, fx_)
        lo[todo], hi[todo], d[todo], e[todo] = lo_n, hi_n, d_new, e_new
    return x, fx
