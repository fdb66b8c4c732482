"""Scalar root finding and bounded minimisation: the kernel's own, so that the paths of
``gearkit gear``, ``check``, ``cycloidal-drive`` and ``novikov`` need no scipy import
(scipy costs more to import than those commands take to run).

Both are Brent's classic methods: :func:`brentq` (bracketed root, inverse quadratic
interpolation with bisection safeguard) and :func:`fminbound` (golden section with
parabolic steps). They stop at the same tolerances as the scipy functions of the same
names, so results agree to those tolerances.

Examples
--------
>>> import math
>>> round(brentq(lambda x: x * x - 2.0, 0.0, 2.0, xtol=1e-15), 14)
1.41421356237309
>>> x, fx = fminbound(math.cos, 3.0, 4.0, xatol=1e-12)
>>> round(x, 7), round(fx, 12)
(3.1415927, -1.0)
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["bracketed_root", "bracketed_roots", "brentq", "fminbound"]

_EPS = 2.220446049250313e-16
_GOLDEN = 0.5 * (3.0 - math.sqrt(5.0))


def brentq(f, a: float, b: float, xtol: float = 2e-12, rtol: float = 4 * _EPS, maxiter: int = 100) -> float:
    """A root of ``f`` in ``[a, b]`` where ``f(a)`` and ``f(b)`` differ in sign.

    Stops when the bracket is below ``xtol + rtol * |x|``. Raises ``ValueError`` when the
    ends do not bracket a sign change, ``RuntimeError`` after ``maxiter`` steps.
    """
    fa, fb = float(f(a)), float(f(b))
    if fa == 0.0:
        return float(a)
    if fb == 0.0:
        return float(b)
    if (fa > 0) == (fb > 0):
        raise ValueError("f(a) and f(b) must have different signs")
    c, fc = a, fa
    d = e = b - a
    for _ in range(maxiter):
        if (fb > 0) == (fc > 0):  # keep the root between b and c
            c, fc = a, fa
            d = e = b - a
        if abs(fc) < abs(fb):  # b is the best estimate
            a, b, c = b, c, b
            fa, fb, fc = fb, fc, fb
        tol = 0.5 * (xtol + rtol * abs(b))
        m = 0.5 * (c - b)
        if abs(m) <= tol or fb == 0.0:
            return float(b)
        if abs(e) >= tol and abs(fa) > abs(fb):  # try interpolation
            s = fb / fa
            if a == c:  # secant
                p, q = 2.0 * m * s, 1.0 - s
            else:  # inverse quadratic
                q, r = fa / fc, fb / fc
                p = s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0))
                q = (q - 1.0) * (r - 1.0) * (s - 1.0)
            if p > 0:
                q = -q
            else:
                p = -p
            if 2.0 * p < min(3.0 * m * q - abs(tol * q), abs(e * q)):
                e, d = d, p / q
            else:
                d = e = m
        else:
            d = e = m
        a, fa = b, fb
        b = b + (d if abs(d) > tol else math.copysign(tol, m))
        fb = float(f(b))
    raise RuntimeError(f"brentq: no convergence in {maxiter} iterations")


def fminbound(f, lo: float, hi: float, xatol: float = 1e-5, maxiter: int = 500) -> tuple[float, float]:
    """A local minimum ``(x, f(x))`` of ``f`` on ``[lo, hi]`` (Brent's bounded method).

    Stops when x is known to within ``sqrt(eps) |x| + xatol / 3`` either side (the
    tolerance of scipy's bounded scalar minimiser).
    """
    a, b = float(lo), float(hi)
    x = w = v = a + _GOLDEN * (b - a)
    fx = fw = fv = float(f(x))
    d = e = 0.0
    sqrt_eps = math.sqrt(_EPS)
    for _ in range(maxiter):
        m = 0.5 * (a + b)
        tol1 = sqrt_eps * abs(x) + xatol / 3.0
        tol2 = 2.0 * tol1
        if abs(x - m) <= tol2 - 0.5 * (b - a):
            break
        golden = True
        if abs(e) > tol1:  # try a parabola through x, w, v
            r = (x - w) * (fx - fv)
            q = (x - v) * (fx - fw)
            p = (x - v) * q - (x - w) * r
            q = 2.0 * (q - r)
            if q > 0:
                p = -p
            q = abs(q)
            r, e = e, d
            if abs(p) < abs(0.5 * q * r) and q * (a - x) < p < q * (b - x):
                d = p / q
                u = x + d
                if (u - a) < tol2 or (b - u) < tol2:
                    d = math.copysign(tol1, m - x)
                golden = False
        if golden:
            e = (b - x) if x < m else (a - x)
            d = _GOLDEN * e
        u = x + (d if abs(d) >= tol1 else math.copysign(tol1, d))
        fu = float(f(u))
        if fu <= fx:
            if u >= x:
                a = x
            else:
                b = x
            v, fv, w, fw, x, fx = w, fw, x, fx, u, fu
        else:
            if u < x:
                a = u
            else:
                b = u
            if fu <= fw or w == x:
                v, fv, w, fw = w, fw, u, fu
            elif fu <= fv or v == x or v == w:
                v, fv = u, fu
    return x, fx


def bracketed_root(f, a: float, b: float, fa: float | None = None, fb: float | None = None,
                   xtol: float = 1e-15, maxiter: int = 200) -> float:
    """Root of a scalar function with a sign change on ``[a, b]``.

    Regula falsi with the Illinois modification (superlinear), safeguarded by bisection
    whenever a step fails to halve the bracket. Stops when the bracket is within
    ``xtol * (1 + |x|)`` or ``f`` is exactly zero.

    >>> round(bracketed_root(lambda x: x * x - 2.0, 0.0, 2.0), 15)
    1.414213562373095
    """
    steps = _illinois(a, b, f(a) if fa is None else fa, f(b) if fb is None else fb, xtol, maxiter)
    try:
        x = next(steps)
        while True:
            x = steps.send(f(x))
    except StopIteration as done:
        return done.value


def bracketed_roots(evaluate, brackets, xtol: float = 1e-15, maxiter: int = 200) -> list:
    """Roots of several scalar functions, each with a sign change on its bracket ``(a, b, f(a), f(b))``.

    Each root is held in a bracket with a sign change, shrunk until it is within ``xtol * (1 + |x|)``
    (the stopping test of :func:`bracketed_root`) or ``f`` is exactly zero: the bracket is the proof
    that a root lies within that tolerance of the one returned. The roots are found side by side: one
    call ``evaluate(which, points)`` (the indices of the brackets asking, and for each an array of the
    points it asks at; it returns an array of values for each) gives every value a round needs, so
    the calls are as many as the most rounds one root takes. A round asks at many points of each
    bracket at once (:func:`_squeeze`): where the cost of a call is its overhead, not its points, the
    bracket shrinks in a round by what one point a call would take many calls to do.

    >>> import numpy as np
    >>> funcs = [lambda x: x * x - 2.0, lambda x: x ** 3 - 0.5]
    >>> calls = []
    >>> def evaluate(which, points):
    ...     calls.append(len(which))
    ...     return [funcs[i](x) for i, x in zip(which, points)]
    >>> roots = bracketed_roots(evaluate, [(0.0, 2.0, -2.0, 2.0), (0.0, 1.0, -0.5, 0.5)])
    >>> [abs(r - e) <= 2e-15 for r, e in zip(roots, [2.0 ** 0.5, 0.5 ** (1 / 3)])], len(calls)
    ([True, True], 6)
    """
    steps = [_squeeze(a, b, fa, fb, xtol, maxiter) for a, b, fa, fb in brackets]
    roots, asked = [None] * len(steps), {}
    for i, s in enumerate(steps):
        try:
            asked[i] = next(s)
        except StopIteration as done:
            roots[i] = done.value
    while asked:
        which = list(asked)
        values = evaluate(which, [asked[i] for i in which])
        asked = {}
        for i, v in zip(which, values):
            try:
                asked[i] = steps[i].send(v)
            except StopIteration as done:
                roots[i] = done.value
    return roots


#: the guards about a round's estimate stand this factor apart, from the distance to the nearer bracket
#: end down to half the stopping tolerance
_LADDER = 8.0


def _squeeze(a, b, fa, fb, xtol, maxiter):
    """:func:`bracketed_roots`' rounds for one root: yields the points ``(k,)`` a round asks at and is sent
    their values; returns the root.

    A round asks at the regula falsi estimate ``c`` of the bracket, at guards either side of it a
    factor ``_LADDER`` apart, from ``h``, the distance to the nearer end, down to half the stopping
    tolerance, and at the bracket's thirds. The bracket becomes the neighbouring pair of those points
    across a sign change (the one nearest ``c``). Where ``f`` is smooth the estimate's error is far
    below ``h`` (the secant's error is of the order of the product of its ends' errors), so the
    guards around the root close the bracket to within a factor ``_LADDER`` of that error, and the
    next estimate, from the ends of a bracket that narrow, is better still: a few rounds reach the
    tolerance. Whatever ``f`` is (a jump, a flat stretch, several roots) the thirds shrink the
    bracket at least threefold a round."""
    end = _end_root(a, b, fa, fb)
    if end is not None:
        return end
    if b < a:
        a, b, fa, fb = b, a, fb, fa
    for _ in range(maxiter):
        width = b - a
        if width <= xtol * (1.0 + min(abs(a), abs(b))):
            break
        c = (a * fb - b * fa) / (fb - fa)
        if not a < c < b:
            c = 0.5 * (a + b)
        floor = 0.45 * xtol * (1.0 + abs(c))
        h = [min(c - a, b - c)]
        while h[-1] > _LADDER * floor:
            h.append(h[-1] / _LADDER)
        h.append(floor)
        xs = [c - d for d in h] + [a + width / 3.0, c, b - width / 3.0] + [c + d for d in h]
        xs = sorted(x for x in xs if a < x < b)  # a repeated point is asked twice: no harm
        fx = np.asarray((yield np.array(xs)), dtype=float).tolist()
        x, f = [a] + xs + [b], [fa] + fx + [fb]
        zeros = [v for v, g in zip(xs, fx) if g == 0.0]
        if zeros:  # an exact root: the one nearest c
            return min(zeros, key=lambda v: abs(v - c))
        best = None  # the neighbouring pair across a sign change nearest c
        for k in range(len(x) - 1):
            if (f[k] > 0) != (f[k + 1] > 0):
                gap = abs(0.5 * (x[k] + x[k + 1]) - c)
                if best is None or gap < best[0]:
                    best = (gap, k)
        k = best[1]
        a, b, fa, fb = x[k], x[k + 1], f[k], f[k + 1]
    return a if abs(fa) < abs(fb) else b


def _end_root(a, b, fa, fb):
    """``a`` or ``b`` where ``f`` is exactly zero there, else None; raises ``ValueError`` when the
    bracket's ends have one sign."""
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    if (fa > 0) == (fb > 0):
        raise ValueError("bracketed_root: no sign change on the bracket")
    return None


def _illinois(a, b, fa, fb, xtol, maxiter):
    """:func:`bracketed_root`'s steps: yields each point it needs ``f`` at and is sent the value; returns the root."""
    end = _end_root(a, b, fa, fb)
    if end is not None:
        return end
    side = 0
    width = abs(b - a)
    for _ in range(maxiter):
        c = (a * fb - b * fa) / (fb - fa)
        if not (min(a, b) < c < max(a, b)):
            c = 0.5 * (a + b)
        fc = yield c
        if fc == 0.0:
            return c
        if (fc > 0) == (fb > 0):
            b, fb = c, fc
            if side == -1:
                fa *= 0.5
            side = -1
        else:
            a, fa = c, fc
            if side == 1:
                fb *= 0.5
            side = 1
        new_width = abs(b - a)
        if new_width > 0.5 * width:  # slow progress: bisect once
            m = 0.5 * (a + b)
            fm = yield m
            if fm == 0.0:
                return m
            if (fm > 0) == (fa > 0):
                a, fa = m, fm
            else:
                b, fb = m, fm
            side = 0
            new_width = abs(b - a)
        width = new_width
        if width <= xtol * (1.0 + abs(a)):
            break
    return a if abs(fa) < abs(fb) else b
