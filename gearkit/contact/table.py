"""Tables of the exact tooth pieces: every flank evaluated once, then cheap anywhere.

The meshing simulation evaluates both teeth at every driver angle, but the teeth never change:
every tooth is a turned copy of one half tooth. So each piece is evaluated once, densely, and
represented by piecewise polynomials, and every step of the simulation evaluates those
(a handful of multiply-adds per point, all pieces in one vectorised call) instead of the exact
pieces (an envelope solve, one call per piece).

* :class:`CurveTable` — a profile's pieces ``t -> (x, y)``: on each sub-interval the polynomial
  interpolating the exact piece at ``DEGREE + 1`` Chebyshev nodes.
* :class:`WidthTable` — the mate's half space width ``w(rho)`` (:class:`~gearkit.contact.tooth.HalfWidth`)
  on the same kind of sub-intervals, in ``rho`` or, next to a stationary end where ``w`` has a
  square-root behaviour, in ``sqrt(|rho - end|)``, where it is smooth.

**Accuracy.** A sub-interval is accepted when its polynomial agrees with the exact piece (the
exact inversion for ``w``) within ``tol`` at ``DEGREE + 2`` check points between its nodes and at
both ends; otherwise it is halved. ``tol`` defaults to :data:`TABLE_TOL` of the outer radius
(1e-12: a few hundred units in the last place, three orders below the simulation's ``EXACT``
accuracy); the deviation achieved is measured and kept (``achieved``, mm). An interval that cannot
reach ``tol`` (halving no longer halves the error: the exact piece's own round-off, or a singular
end such as a square-root one; or ``MAX_HALVINGS`` are spent) is left to the exact piece: points
there are evaluated exactly. The simulation evaluates its final contacts on the exact pieces
(``exact=True``), so what it reports does not depend on the tables.

Examples
--------
>>> from gearkit.families.involute import GearSpec, tooth_profile
>>> prof = tooth_profile(GearSpec(20, 1.0))
>>> table = CurveTable(prof.half.pieces, 1e-12 * 11.0)
>>> k, t = np.array([1, 1]), np.array([0.25, 0.75])
>>> bool(np.abs(table.evaluate(k, t) - prof.half.pieces[1](t)).max() <= table.achieved <= 1.1e-11)
True
"""
from __future__ import annotations

import numpy as np

__all__ = ["CurveTable", "DEGREE", "TABLE_TOL", "WidthTable"]

#: degree of the interpolating polynomials
DEGREE = 9
#: default accuracy of a table, relative to the outer radius (mm per mm)
TABLE_TOL = 1e-12
#: most halvings of a starting sub-interval before a table accepts what it measured
MAX_HALVINGS = 16

_NODES = np.cos(np.pi * (np.arange(DEGREE + 1) + 0.5) / (DEGREE + 1))[::-1]  # Chebyshev nodes in [-1, 1]
_CHECK = np.cos(np.pi * np.arange(DEGREE + 2) / (DEGREE + 1))[::-1]  # extrema of T_{D+1}: ends included
_VANDER_INV = np.linalg.inv(np.vander(_NODES, DEGREE + 1, increasing=True))


def _fit(values):
    """Monomial coefficients in ``s in [-1, 1]`` of the interpolants of ``values`` ``(n, D+1, c)``."""
    return np.einsum("ij,njc->nic", _VANDER_INV, values)


def _horner(coef, s):
    """``sum_i coef[:, i] s^i`` for rows of ``coef`` ``(n, D+1, c)`` at ``s`` ``(n,)``: ``(n, c)``."""
    acc = coef[:, -1].copy()
    s = s[:, None]
    for i in range(coef.shape[1] - 2, -1, -1):
        acc *= s
        acc += coef[:, i]
    return acc


def _gathered(coef, j, s):
    """:func:`_horner` of sub-intervals ``j`` from coefficients stored ``(c, D+1, J)``: a list of ``c``
    flat arrays (one component each), every component in the same few array operations."""
    a = np.take(coef, j, axis=2, mode="clip")  # (c, D+1, n); j is within the table
    acc = a[:, -1].copy()
    for i in range(a.shape[1] - 2, -1, -1):
        acc *= s
        acc += a[:, i]
    return list(acc)


def _gathered_derivatives(coef, j, s):
    """:func:`_gathered` of the coefficients stored ``(c, D+1, J)`` and of their first and second derivatives in
    ``s``: three lists of ``c`` flat arrays. Each coefficient is gathered once; the derivatives' coefficients
    ``a_k k`` and ``(a_k k) (k - 1)`` are formed from it as :func:`_derived` forms its stored ones (the same
    products of the same numbers), and every sum runs in the same order: the same values to the bit. The three
    sums run side by side, the derivatives' shorter ones led by zeros (``0 s + b = b``)."""
    c, d = coef.shape[:2]
    k = np.arange(d, dtype=float)[:, None]
    e = np.empty((3, c, d, len(j)))  # the value's, the first and the second derivative's coefficients
    np.take(coef, j, axis=2, out=e[0], mode="clip")
    np.multiply(e[0, :, 1:], k[1:], out=e[1, :, :-1])
    np.multiply(e[1, :, 1:-1], k[1:-1], out=e[2, :, :-2])
    e[1, :, -1] = 0.0
    e[2, :, -2:] = 0.0
    acc = e[:, :, -1].copy()
    for i in range(d - 2, -1, -1):
        acc *= s
        acc += e[:, :, i]
    return list(acc[0]), list(acc[1]), list(acc[2])


def _derived(coef):
    """Coefficients ``(n, D+1, c)`` and those of their first derivative in ``s``, each stored ``(c, D+1-i, n)`` (for
    :func:`_gathered`)."""
    powers = np.arange(DEGREE + 1)[None, :, None]
    d1 = coef[:, 1:] * powers[:, 1:]
    return tuple(np.ascontiguousarray(c.transpose(2, 1, 0)) for c in (coef, d1))


def _build(evaluate, rows, a, b, tol, scale=None):
    """Fit ``evaluate(rows, x) -> (n, c)`` on intervals ``[a, b]`` (``rows``: the caller's index of each).

    The intervals are halved until every one's polynomial agrees with ``evaluate`` within ``tol``
    (``scale``: per-check-point weights turning the difference into a length). Returns the accepted
    ``(rows, a, b, coef, error)``, sorted by row and start.
    """
    done = []
    parent = np.full(rows.size, np.inf)
    for depth in range(MAX_HALVINGS + 1):
        if rows.size == 0:
            break
        mid, half = 0.5 * (a + b), 0.5 * (b - a)
        x_nodes = mid[:, None] + half[:, None] * _NODES[None, :]
        x_check = mid[:, None] + half[:, None] * _CHECK[None, :]
        x_check[:, 0], x_check[:, -1] = a, b
        nn, nc = x_nodes.shape[1], x_check.shape[1]
        r_all = np.concatenate([np.repeat(rows, nn), np.repeat(rows, nc)])
        vals = evaluate(r_all, np.concatenate([x_nodes.ravel(), x_check.ravel()]))
        c = vals.shape[-1]
        coef = _fit(vals[:rows.size * nn].reshape(rows.size, nn, c))
        exact = vals[rows.size * nn:].reshape(rows.size, nc, c)
        approx = np.stack([_horner(coef, np.full(rows.size, s)) for s in _CHECK], 1)
        diff = np.abs(approx - exact)
        if scale is not None:
            diff = diff * scale(r_all[rows.size * nn:], x_check.ravel()).reshape(rows.size, nc, 1)
        err = np.nan_to_num(diff.max(axis=(1, 2)), nan=np.inf)
        # accepted: within tol; or halving no longer pays (the exact piece's round-off, a singular
        # end): then the sub-interval is left to the exact piece (error inf)
        stall = (err > 0.5 * parent) | (depth == MAX_HALVINGS)
        ok = (err <= tol) | stall
        kept = np.where(err <= tol, err, np.inf)
        done.append((rows[ok], a[ok], b[ok], coef[ok], kept[ok]))
        rows, a, b = np.repeat(rows[~ok], 2), np.ravel(np.column_stack([a[~ok], mid[~ok]])), \
            np.ravel(np.column_stack([mid[~ok], b[~ok]]))
        parent = np.repeat(err[~ok], 2)
    r, a, b, coef, err = (np.concatenate([d[i] for d in done]) for i in range(5))
    order = np.lexsort((a, r))
    return r[order], a[order], b[order], coef[order], err[order]


class CurveTable:
    """Piecewise polynomial copies of ``pieces`` (callables ``t in [0, 1] -> (n, 2)``) within ``tol`` (mm).

    Attributes
    ----------
    achieved : float, mm, the largest deviation measured at the check points
    intervals : int, sub-intervals over all pieces
    """

    def __init__(self, pieces, tol: float, start: int = 4):
        self.pieces = tuple(pieces)
        n = len(self.pieces)

        def exact(rows, t):
            out = np.empty(t.shape + (2,))
            for k in range(n):
                sel = rows == k
                if sel.any():
                    out[sel] = self.pieces[k](t[sel])
            return out

        k0 = np.repeat(np.arange(n), start)
        frac = np.tile(np.arange(start + 1) / start, n).reshape(n, start + 1)
        lo, hi = frac[:, :-1].ravel(), frac[:, 1:].ravel()
        k, a, b, self._coef, err = _build(exact, k0, lo, hi, tol)
        self._exact_piece = exact
        self._fallback = ~np.isfinite(err)
        self.achieved = float(err[~self._fallback].max(initial=0.0))
        self.intervals = len(k)
        self._key = 2.0 * k + a  # pieces two apart: t in [0, 1] never reaches the next piece's key
        self._a, self._inv = a, 2.0 / (b - a)
        self._coef, self._dcoef = _derived(self._coef)
        #: every sub-interval within ``tol``: :meth:`derivatives` applies everywhere
        self.smooth = not self._fallback.any()

    def _locate(self, k, t):
        j = np.searchsorted(self._key, 2.0 * k + t, side="right") - 1
        j = np.minimum(np.maximum(j, 0), len(self._key) - 1)  # (np.clip's wrapper costs more)
        return j, (t - self._a[j]) * self._inv[j] - 1.0

    def evaluate(self, k, t, derivative: bool = False, exact: bool = False):
        """Points ``(..., 2)`` of pieces ``k`` at ``t`` (and ``dp/dt`` with ``derivative``); ``exact``: on
        the exact pieces (so are points in a sub-interval left to them)."""
        k = np.asarray(k)
        t = np.asarray(t, dtype=float)
        shape = t.shape
        kf, tf = np.broadcast_to(k, shape).ravel(), t.ravel()
        if exact:
            return self._exact_piece(kf, tf).reshape(shape + (2,))
        j, s = self._locate(kf, tf)
        p = np.stack(_gathered(self._coef, j, s), -1)
        slow = np.flatnonzero(self._fallback[j]) if not self.smooth else j[:0]  # (smooth: none left to the pieces)
        if slow.size:
            p[slow] = self._exact_piece(kf[slow], tf[slow])
        p = p.reshape(shape + (2,))
        if not derivative:
            return p
        inv = self._inv[j]
        d = np.stack([c * inv for c in _gathered(self._dcoef, j, s)], -1)
        if slow.size:  # central differences on the exact piece (a step of 1e-7, inside the piece)
            h = 1e-7
            ts = np.clip(tf[slow], h, 1 - h)
            d[slow] = (self._exact_piece(kf[slow], ts + h) - self._exact_piece(kf[slow], ts - h)) / (2 * h)
        return p, d.reshape(shape + (2,))

    def evaluate_xy(self, k, t):
        """:meth:`evaluate` of flat ``k``, ``t`` as two flat arrays ``[x, y]``."""
        j, s = self._locate(k, t)
        p = _gathered(self._coef, j, s)
        slow = np.flatnonzero(self._fallback[j]) if not self.smooth else j[:0]  # (smooth: none left to the pieces)
        if slow.size:
            exact = self._exact_piece(k[slow], t[slow])
            p[0][slow], p[1][slow] = exact[:, 0], exact[:, 1]
        return p

    def derivatives(self, k, t):
        """Points of pieces ``k`` at ``t`` (flat arrays) and their first and second derivatives in ``t``:
        three lists ``[x, y]`` of flat arrays, on the table only (for a table that is :attr:`smooth`)."""
        j, s = self._locate(k, t)
        inv = self._inv[j]
        p, d1, d2 = _gathered_derivatives(self._coef, j, s)
        inv2 = inv * inv
        return p, [c * inv for c in d1], [c * inv2 for c in d2]


class WidthTable:
    """``w(rho)`` of a :class:`~gearkit.contact.tooth.HalfWidth` as piecewise polynomials within ``tol``.

    The sub-intervals start from the half width's own table (one piece each, ordered by ``rho``);
    next to a stationary end they are in ``x = sign(rho - end) sqrt(|rho - end|)``. The deviation
    is measured as a length: ``w`` times the radial scale (``|rho|`` for a gear, 1 for a rack).
    """

    def __init__(self, half, tol: float):
        self.half = half
        anchor = half._anchor
        self._grazing = np.isfinite(anchor)
        self._anchor = np.where(self._grazing, anchor, 0.0)
        polar = half.root_scale != 1.0
        x0, x1 = self._x(np.arange(len(anchor)), half._r0), self._x(np.arange(len(anchor)), half._r1)

        def rho_of(rows, x):
            return np.where(self._grazing[rows], self._anchor[rows] + np.sign(x) * x * x, x)

        def exact(rows, x):
            w, piece, _, _ = half.exact(rho_of(rows, x))
            return w[:, None]

        def scale(rows, x):
            return np.abs(rho_of(rows, x)) if polar else np.ones(len(rows))

        rows, a, b, coef, err = _build(exact, np.arange(len(anchor)), x0, x1, tol, scale)
        self._fallback = ~np.isfinite(err)
        self.achieved = float(err[~self._fallback].max(initial=0.0))
        self.intervals = len(rows)
        self._row, self._a, self._b, self._inv = rows, a, b, 2.0 / (b - a)
        self._coef, self._dcoef = _derived(coef)
        #: every sub-interval within ``tol``: :meth:`derivatives` applies everywhere
        self.smooth = not self._fallback.any()
        self._piece = half._k[rows]
        # sub-interval starts in rho, for the lookup (increasing, like the half width's table)
        self._r_start = np.where(self._grazing[rows], self._anchor[rows] + np.sign(a) * a * a, a)
        self._polar = polar

    def _x(self, rows, rho):
        x = np.array(rho, dtype=float)
        g = np.flatnonzero(self._grazing[rows])  # few: the square root only there
        if g.size:
            d = x[g] - self._anchor[rows[g]]
            x[g] = np.sign(d) * np.sqrt(np.abs(d))
        return x

    def _locate(self, rho):
        """Sub-interval ``j``, its row, the coordinate ``x`` and the local ``s in [-1, 1]`` of flat ``rho``."""
        j = np.minimum(np.maximum(np.searchsorted(self._r_start, rho, side="right") - 1, 0), len(self._r_start) - 1)
        row = self._row[j]
        x = self._x(row, rho)
        return j, row, x, np.minimum(np.maximum((x - self._a[j]) * self._inv[j] - 1.0, -1.0), 1.0)

    def derivatives(self, rho):
        """``w`` and its first and second derivatives in ``rho`` at flat ``rho``, on the table only (for a
        table that is :attr:`smooth`): inf beyond the tip, the root's linear width inside the root circle.
        Next to a stationary end the table is in ``x``, ``rho = end + sign(x) x^2``: the chain rule."""
        half = self.half
        j, row, x, s = self._locate(rho)
        inv = self._inv[j]
        (w,), (w_x,), (w_xx,) = _gathered_derivatives(self._coef, j, s)
        w_x = w_x * inv
        w_xx = w_xx * (inv * inv)
        graz = self._grazing[row]
        r_x = np.where(graz, 2.0 * np.abs(x), 1.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            w_r = w_x / r_x
            w_rr = (w_xx - w_r * np.where(graz, 2.0 * np.sign(x), 0.0)) / (r_x * r_x)
        body, free = half._body(rho), half.free(rho)
        if body.any() or free.any():
            slope = half.outward / half.root_scale
            w = np.where(body, half._body_width(rho), np.where(free, np.inf, w))
            w_r = np.where(body, slope, np.where(free, np.nan, w_r))
            w_rr = np.where(body, 0.0, np.where(free, np.nan, w_rr))
        return w, w_r, w_rr

    def values(self, rho):
        """``w`` alone at flat ``rho`` (as :meth:`width`)."""
        return self._values(rho)[0]

    def _values(self, rho):
        """``w`` at flat ``rho``, with :meth:`_locate`'s ``j, row, x, s`` and the body and free masks."""
        half = self.half
        j, row, x, s = self._locate(rho)
        w = _gathered(self._coef, j, s)[0]
        slow = np.flatnonzero(self._fallback[j]) if not self.smooth else j[:0]  # (smooth: none left to the pieces)
        if slow.size:
            w[slow] = half.exact(rho[slow])[0]
        body, free = half._body(rho), half.free(rho)
        if body.any():
            w = np.where(body, half._body_width(rho), w)
        if free.any():
            w[free] = np.inf
        return w, j, row, x, s, body, free

    def width(self, rho, tangent: bool = False):
        """``w``, the piece (-1 beyond the tip, -2 inside the root circle) and, with ``tangent``, the
        flank's unit tangent in the mate frame (zero off the flank), at ``rho`` (float64 array)."""
        half = self.half
        rho = np.asarray(rho, dtype=float)
        shape = rho.shape
        rho = rho.ravel()
        w, j, row, x, s, body, free = self._values(rho)
        piece = np.where(body, -2, np.where(free, -1, self._piece[j]))
        if not tangent:
            return w.reshape(shape), piece.reshape(shape), None
        dw = _gathered(self._dcoef, j, s)[0] * self._inv[j]  # dw/dx
        drho = np.where(self._grazing[row], 2.0 * np.abs(x), 1.0)  # drho/dx
        if self._polar:  # point = rho (sin psi, cos psi), psi = P/2 - w
            psi = half.pitch / 2 - np.where(np.isfinite(w), w, 0.0)
            e_r = np.stack([np.sin(psi), np.cos(psi)], -1)
            e_p = np.stack([np.cos(psi), -np.sin(psi)], -1)
            tan = drho[:, None] * e_r - (rho * dw)[:, None] * e_p
        else:  # point = (psi, rho)
            tan = np.stack([-dw, drho], -1)
        tan = np.where((body | free)[:, None], 0.0, tan)
        norm = np.linalg.norm(tan, axis=-1, keepdims=True)
        tan = np.divide(tan, norm, out=np.zeros_like(tan), where=norm > 0)
        return w.reshape(shape), piece.reshape(shape), tan.reshape(shape + (2,))
