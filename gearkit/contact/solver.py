"""Where the mate must stop, for a batch of driver angles: a search on polylines, then exact.

For every driver angle, driver tooth ``i`` (of those that can touch) and half ``s`` (right,
left), the bounds that its boundary puts on the mate's position (see :mod:`gearkit.contact.mesh`):

* upper: ``min over the half of (w(rho) - u)``,
* lower: ``max over the half of (-w(rho) - u)``, kept as ``min (w(rho) + u)``.

1. **Search.** The bound functions are evaluated at the polyline samples (exact points; the
   mate's ``w`` interpolated). Between two samples the exact function can dip below them by at
   most the chord's deviation plus the mate's bending over the chord, as a normal distance over
   the local arm of the mate's normal (``dip``; unbounded next to a rounded crest, where the
   bound falls like a square root). Every interval whose ends come within ``dip`` of the half's
   best value is refined, for every half that may come within the contact tolerance of the best
   bound overall.
2. **Refinement**, one polyline interval at a time: the crossing of the tip circle by root finding
   (Illinois), the minimum after a few probes (:func:`~gearkit.contact.minimise.minimise`: Newton on
   the tables' derivatives, Brent's method on the exact pieces; at most driver angles Newton alone, from
   the neighbouring angles' minima: :mod:`gearkit.contact.continuation`), then each half's best evaluated on
   the exact pieces, ``w`` by :meth:`HalfWidth.exact`. A smooth contact ends at a stationary point (the flanks touch
   tangentially); a corner contact at an interval end (the driver's corner) or at the tip
   crossing (the mate's corner).

Work per angle depends on the window of teeth that can touch, not on the tooth counts.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gearkit.contact.continuation import NODE_EVERY, close, continued, driver_derivatives, row_key
from gearkit.contact.minimise import minimise
from gearkit.contact.search import search
from gearkit.progress import Progress

__all__ = ["Bounds", "solve"]

#: Illinois iterations of a crossing (it converges long before)
_CROSS_ITER = 40
#: search-array size per chunk of driver angles (memory ~ 40 bytes each)
_CHUNK = 1_500_000
#: table evaluations of one block of :meth:`_Task.grid_values` (64 KiB a float64 array)
_PROBE_BLOCK = 1 << 13


@dataclass
class Bounds:
    """Bounds on the mate's position from each driver half, for ``n`` driver angles.

    Axes: ``(n, K, half, bound)`` with ``half`` 0 = right, 1 = left and ``bound`` 0 = upper,
    1 = lower. ``value`` holds ``min (w - u)`` (bound 0) and ``min (w + u)`` (bound 1): the upper
    bound is ``value[..., 0]``, the lower one ``-value[..., 1]``. Only halves that may come within
    the contact tolerance of the best are refined (``exact``); the others keep their search value.
    """

    phi: np.ndarray
    teeth: np.ndarray
    value: np.ndarray
    exact: np.ndarray
    point: np.ndarray
    normal: np.ndarray
    arm: np.ndarray
    piece1: np.ndarray
    piece2: np.ndarray
    rho2: np.ndarray
    corner1: np.ndarray
    corner2: np.ndarray
    #: every refined row's ``code`` (its driver angle and what it minimises: :func:`~gearkit.contact.continuation.code`)
    #: and minimiser, unordered: starts for a later solve between these angles (``seeds`` of :func:`solve`)
    row_code: np.ndarray = None
    row_t: np.ndarray = None

    @property
    def upper(self):
        return self.value[..., 0].min(axis=(1, 2))

    @property
    def lower(self):
        return -self.value[..., 1].min(axis=(1, 2))


def _driver_xy(mesh, k, t, sigma, theta, exact=False):
    """Fixed-frame coordinates ``x``, ``y`` of driver pieces ``k`` at ``t`` (half ``sigma``, turned by ``theta``)."""
    p = mesh.driver.evaluate(k, t, exact)
    x, y = sigma * p[..., 0], p[..., 1]
    c, s = np.cos(theta), np.sin(theta)
    return c * x - s * y, s * x + c * y


class _Task:
    """Exact bound function along one polyline interval per row."""

    def __init__(self, mesh, phi, theta, sigma, sb, piece, interval=None, frame=None):
        self.mesh, self.phi, self.theta, self.sigma, self.sb, self.piece = mesh, phi, theta, sigma, sb, piece
        self.interval = interval  # the polyline interval of each row (for :meth:`grid_values`)
        self.k2 = np.full(len(phi), -1)  # the mate's last solution per row: the secant's first point
        self.t2 = np.zeros(len(phi))
        self.r2 = np.zeros(len(phi))
        self.exact = False  # True: on the exact pieces even where the mesh has tables
        # the driver half's own coordinates -> the mate's (``frame``: these rows' frames, made already)
        self.frame = mesh.frames(theta, sigma, phi) if frame is None else frame

    def subset(self, rows):
        """The same task over ``rows`` (int array) alone."""
        interval = None if self.interval is None else self.interval[rows]
        return _Task(self.mesh, self.phi[rows], self.theta[rows], self.sigma[rows], self.sb[rows], self.piece[rows],
                     interval, self.frame[:, rows])

    @property
    def noise(self):
        """A bound of the error of :meth:`value` where it is read off tables without derivatives (not
        :attr:`smooth`; mate units): the tables' deviation as a normal distance over the arm scale, ten
        times over (its effect on ``w`` and ``u`` both). 0 on the exact pieces and on smooth tables,
        whose minima :func:`minimise` finds by Newton."""
        if self.exact or self.mesh.driver.table is None or self.smooth:
            return 0.0
        return 10.0 * self.mesh.table_deviation / self.mesh.arm_scale

    @property
    def roundoff(self):
        """The round-off of three values' one-sided difference (mate units): ``w`` and ``u`` a pitch each."""
        return 16.0 * np.finfo(float).eps * abs(self.mesh.pitch2)

    @property
    def smooth(self):
        """The bound function's derivatives are at hand (:meth:`slope`): on tables within their tolerance."""
        drv, mate = self.mesh.driver.table, self.mesh.mate.table
        return not self.exact and drv is not None and mate is not None and drv.smooth and mate.smooth

    def slope(self, t, rows):
        """The bound function on the tables and its first and second derivatives in ``t`` (only where
        :attr:`smooth`): the driver's and the mate's polynomials, differentiated through the frames."""
        mesh = self.mesh
        p, d1, d2 = driver_derivatives(mesh.driver, self.piece, self.interval, t, rows)
        rho, r1, r2, u, u1, u2 = mesh.mate_derivatives(p, d1, d2, self.frame[:, rows])
        w, w1, w2 = mesh.mate.table.derivatives(rho)
        sb = self.sb[rows]
        return w - sb * u, w1 * r1 - sb * u1, w2 * r1 * r1 + w1 * r2 - sb * u2

    def _fast(self, exact):
        return not (exact or self.exact) and self.mesh.driver.table is not None

    def rho(self, t, rows=slice(None)):
        """The mate's radial coordinate of the rows' points at ``t`` (the offset ``u``, and its arctangent,
        left unformed)."""
        if self._fast(False):  # the table, through the row's frame
            p = self.mesh.driver.table.evaluate_xy(self.piece[rows], t)
            return self.mesh.mate_radius(p[0], p[1], self.frame[:, rows])[0]
        x, y = _driver_xy(self.mesh, self.piece[rows], t, self.sigma[rows], self.theta[rows], self.exact)
        return self.mesh.to_mate_radius(x, y, self.phi[rows])

    def grid_values(self, grid):
        """:meth:`value` at ``grid`` ``(P, n)`` (row ``i``'s parameters in column ``i``), on the tables: a row
        probed over its whole polyline interval (``interval``) reads the driver's points off
        :meth:`Boundary.probes`; in blocks of rows, so the arrays stay in the processor's caches."""
        count, n = grid.shape
        drv, mate = self.mesh.driver, self.mesh.mate
        t_all, x_all, y_all = drv.probes(count)
        out = np.empty(grid.shape)
        step = max(1, _PROBE_BLOCK // count)
        for s in range(0, n, step):
            cols = slice(s, s + step)
            g, m = grid[:, cols], self.interval[cols]
            px, py = x_all[:, m], y_all[:, m]
            own = np.flatnonzero(~(t_all[:, m] == g).all(axis=0))  # a row cut at the tip circle: its own
            if own.size:
                p = drv.table.evaluate_xy(np.broadcast_to(self.piece[cols][own], (count, own.size)).ravel(),
                                          g[:, own].ravel())
                px[:, own], py[:, own] = p[0].reshape(count, -1), p[1].reshape(count, -1)
            rho, u = self.mesh.mate_coords(px, py, self.frame[:, None, cols])
            out[:, cols] = mate.table.values(rho.ravel()).reshape(rho.shape) - self.sb[cols] * u
        return out

    def value(self, t, rows=slice(None), tangent=False, exact=False):
        """The bound function at ``t`` and the point's mate coordinate ``rho``; with ``tangent`` (True, or a mask of
        the rows, exact only) also the fixed-frame points ``q`` and the mate's unit tangent there (zero elsewhere)."""
        exact = exact or self.exact
        if self._fast(exact) and tangent is False:
            p = self.mesh.driver.table.evaluate_xy(self.piece[rows], t)
            rho, u = self.mesh.mate_coords(p[0], p[1], self.frame[:, rows])
            return self.mesh.mate.table.values(rho) - self.sb[rows] * u, None, rho, None, None
        x, y = _driver_xy(self.mesh, self.piece[rows], t, self.sigma[rows], self.theta[rows], exact)
        rho, u = self.mesh.to_mate_xy(x, y, self.phi[rows])
        q = None if tangent is False else np.stack([x, y], -1)
        w, k2, t2, tan2 = self.mesh.mate.width(rho, (self.k2[rows], self.t2[rows], self.r2[rows]), tangent, exact)
        if t2 is not None:
            self.k2[rows], self.t2[rows], self.r2[rows] = k2, t2, rho
        return w - self.sb[rows] * u, q, rho, k2, tan2


def _crossing(task, a, b):
    """Parameter where the interval meets the mate's tip circle, on its finite side (Illinois).

    Returns the bracket end on the finite side (``g <= 0``), converged to round-off: the iteration
    stops once that end is within the mate's radial round-off of the tip circle or the bracket has
    closed. (An exact zero at the new point ends the bracket there: it is on the finite side.)
    """
    mate = task.mesh.mate
    ga = mate.outward * (task.rho(a) - mate.rho_tip)
    gb = mate.outward * (task.rho(b) - mate.rho_tip)
    wa, wb = np.ones_like(ga), np.ones_like(gb)  # Illinois weights of the retained ends
    side = 0
    for _ in range(_CROSS_ITER):
        with np.errstate(divide="ignore", invalid="ignore"):
            c = np.where(gb != ga, b - wb * gb * (b - a) / (wb * gb - wa * ga), 0.5 * (a + b))
        c = np.where(np.isfinite(c) & ((c - a) * (c - b) <= 0), c, 0.5 * (a + b))
        gc = mate.outward * (task.rho(c) - mate.rho_tip)
        left = (np.sign(gc) == np.sign(ga)) & (gc != 0)
        a, ga, b, gb = (np.where(left, c, a), np.where(left, gc, ga),
                        np.where(left, b, c), np.where(left, gb, gc))
        wa = np.where(left, 1.0, np.where(side == -1, wa / 2, wa))
        wb = np.where(~left, 1.0, np.where(side == 1, wb / 2, wb))
        side = np.where(left, 1, -1)
        fin_a, fin_b = ga <= 0, gb <= 0
        near = (fin_a & (-ga <= mate.noise)) | (fin_b & (-gb <= mate.noise))
        if np.all(near | (np.abs(b - a) <= 1e-15 * np.maximum(1.0, np.abs(a)))):
            break
    # the end on the finite side (g <= 0); both (a zero): the nearer the tip circle
    return np.where(gb <= 0, np.where((ga <= 0) & (ga > gb), a, b), a)


def _refine(mesh, phi, theta, sigma, sb, m, fa, fb, half, frame, along):
    """Minima of the bound function over polyline intervals ``m`` (one row each), the smallest kept
    per ``half`` (row indices ``sel``): on the tables, then the winners evaluated on the exact pieces.
    ``frame``: the rows' :meth:`Mesh.frames`, made by the search; ``along``: the rows' driver angles and what
    they minimise, for :func:`~gearkit.contact.continuation.continued`. Also returns every row's minimiser."""
    drv = mesh.driver
    piece, a, b = drv.piece[m], drv.ta[m].copy(), drv.tb[m].copy()
    task = _Task(mesh, phi, theta, sigma, sb, piece, m, frame)
    cross = fa != fb
    at_tip = np.zeros(len(m), bool)
    if cross.any():
        rows = np.flatnonzero(cross)
        sub = _Task(mesh, phi[rows], theta[rows], sigma[rows], sb[rows], piece[rows], frame=frame[:, rows])
        tc = inner = _crossing(sub, a[rows], b[rows])
        if mesh.tables:  # the crossing on the exact pieces, in a narrow bracket about the tables' one
            sub.exact = True
            span = 1e-6 * (b[rows] - a[rows])
            tx = _crossing(sub, np.maximum(tc - span, a[rows]), np.minimum(tc + span, b[rows]))
            tx = np.where(mesh.mate.outward * (sub.rho(tx) - mesh.mate.rho_tip) <= 0, tx, tc)
            # the minimum is searched up to the nearer of the two crossings, finite on the tables and the
            # exact pieces alike (beyond the tables' own, a corner contact would be approached by halving)
            inner, tc = np.where(fa[rows], np.minimum(tx, tc), np.maximum(tx, tc)), tx
        a[rows] = np.where(fa[rows], a[rows], tc)
        b[rows] = np.where(fa[rows], tc, b[rows])
        at_tip[rows] = True
    lo, hi = a.copy(), b.copy()
    if cross.any():
        lo[rows] = np.where(fa[rows], a[rows], inner)
        hi[rows] = np.where(fa[rows], inner, b[rows])
    value, t = continued(task, lo, hi, *along)
    sel = _winners(value, half)
    if mesh.tables:
        # a winner the tables place on the mate's tip circle (within 1e-9 of its radius) may lie a last bit
        # beyond it on the exact pieces, where the bound is infinite and the tables' value is not one: its
        # half is minimised again on the exact pieces (a tip crossing's own end aside)
        mate = mesh.mate
        ts, ls, hs = t[sel], lo[sel], hi[sel]
        g = mate.outward * (task.rho(ts, sel) - mate.rho_tip)
        rim = 1e-9 * max(abs(mate.rho_tip), abs(mate.rho_root))
        flag = (g > -rim) & ~(at_tip[sel] & ((ts == ls) | (ts == hs)))
        if flag.any():
            r = np.flatnonzero(np.isin(half, half[sel[flag]]))
            sub = _Task(mesh, phi[r], theta[r], sigma[r], sb[r], piece[r], frame=frame[:, r])
            sub.exact = True
            value[r], t[r] = minimise(sub, a[r], b[r])
            sel = _winners(value, half)
    t_all = t
    phi, theta, sigma, sb, m, fa, fb = phi[sel], theta[sel], sigma[sel], sb[sel], m[sel], fa[sel], fb[sel]
    piece, a, b, t, at_tip = piece[sel], a[sel], b[sel], t[sel], at_tip[sel]
    task = _Task(mesh, phi, theta, sigma, sb, piece, frame=task.frame[:, sel])
    corner2 = at_tip & (((t == b) & fa) | ((t == a) & fb))
    # contact value (exact), point, normal and arm; the mate's tangent only where a driver piece ends (a corner)
    at_end = ((t <= drv.ta[m]) | (t >= drv.tb[m])) & ~corner2
    piece_end = at_end & ((t <= 0.0) | (t >= 1.0))
    exact, q, rho, k2, tan2 = task.value(t, tangent=piece_end, exact=True)
    value = np.where(np.isfinite(exact), exact, value[sel])  # a tip crossing a last bit beyond the tip
    if drv.table is not None:  # the tangent from the table's derivative (closer than differences)
        d = drv.table.evaluate(piece, t, derivative=True)[1]
        x, y, c, s = sigma * d[:, 0], d[:, 1], np.cos(theta), np.sin(theta)
        normal = np.stack([-(s * x + c * y), c * x - s * y], -1)
    else:
        h = 1e-7
        ts = np.clip(t, h, 1 - h)
        (x1, y1), (x0, y0) = _driver_xy(mesh, piece, ts + h, sigma, theta), _driver_xy(mesh, piece, ts - h, sigma, theta)
        normal = np.stack([y0 - y1, x1 - x0], -1)
    corner1 = at_end & np.where(t <= drv.ta[m], drv.corner_end[m], drv.corner_end[m + 1])
    use_mate = piece_end & (k2 >= 0) & (np.linalg.norm(tan2, axis=-1) > 0)
    if use_mate.any():
        at = np.flatnonzero(use_mate)
        delta = sb[at] * value[at]  # the mate's position at this contact (upper bound w - u; lower -(w + u))
        n2 = _mate_direction(mesh, tan2[at], phi[at], delta)
        normal[at] = np.stack([-n2[:, 1], n2[:, 0]], -1)
    norm = np.linalg.norm(normal, axis=-1, keepdims=True)
    normal = np.divide(normal, norm, out=np.zeros_like(normal), where=norm > 0)
    vel = mesh.mate_velocity(q)
    dot = np.einsum("ij,ij->i", normal, vel)
    normal = np.where((sb * dot > 0)[:, None], -normal, normal)
    return sel, (value, q, normal, np.abs(dot), piece, k2, rho, corner1, corner2), t_all


def _winners(value, half):
    """Row of the least ``value`` of each ``half`` (group; the first of equal ones, a group of nans its first row).
    The search hands the rows over sorted by half: each group's least by one reduction, not a sort."""
    if half.size == 0 or np.any(half[1:] < half[:-1]):
        order = np.lexsort((value, half))
        first = np.ones(order.size, bool)
        first[1:] = half[order][1:] != half[order][:-1]
        return order[first]
    start = np.flatnonzero(np.concatenate([[True], half[1:] != half[:-1]]))
    group = np.cumsum(np.concatenate([[False], half[1:] != half[:-1]]))
    hit = np.flatnonzero(value == np.fmin.reduceat(value, start)[group])
    lead = np.ones(hit.size, bool)
    lead[1:] = group[hit][1:] != group[hit][:-1]
    out = start.copy()
    out[group[hit[lead]]] = hit[lead]
    return out


def _mate_direction(mesh, tangent, phi, delta):
    if mesh.kind == "rack":
        return -tangent
    beta = mesh.beta0 + mesh.ratio * phi + delta
    c, s = np.cos(beta), np.sin(beta)
    return np.stack([c * tangent[:, 0] - s * tangent[:, 1], s * tangent[:, 0] + c * tangent[:, 1]], -1)


def solve(mesh, phi, contact_tol: float, bounds=(0, 1), lanes: int = 1, seeds=None) -> Bounds:
    """Bounds on the mate's position from every driver half at driver angles ``phi`` ``(n,)``.

    Parameters
    ----------
    mesh : Mesh
    phi : (n,) float64, rad
    contact_tol : float, mm
        Every half that may come within this of the extreme bound is refined.
    bounds : tuple of int
        The bounds refined (0 upper, 1 lower); the others keep their search values.
    lanes : int
        ``phi`` is a grid of driver angles by ``lanes`` (e.g. the slices of a helical pair) flattened: the
        minimiser continues along the angles within each lane (:mod:`gearkit.contact.continuation`).
    seeds : (codes, t, position) or None
        Starts from an earlier solve: its rows (:attr:`Bounds.row_code`, :attr:`Bounds.row_t`, sorted by code) and
        the position of each of these driver angles (``(n / lanes,)`` float) on its grid of angles.
    """
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    per_angle = len(mesh.offsets) * 4 * len(mesh.driver.points) // 2  # about half the halves are near
    step = max(1, _CHUNK // per_angle)
    angles = phi[::lanes]
    fine = angles.size > 1 and close(NODE_EVERY * np.abs(np.diff(angles)).max(), mesh.pitch1)
    parts = []
    with Progress("contact", len(phi), unit="positions") as bar:
        for i in range(0, len(phi), step):
            parts.append(_solve_chunk(mesh, phi[i:i + step], contact_tol, bounds, i, lanes, seeds, fine))
            bar.update(min(i + step, len(phi)))
    if len(parts) == 1:
        return parts[0]
    return Bounds(*(np.concatenate([getattr(p, f) for p in parts]) for f in Bounds.__dataclass_fields__))


def _solve_chunk(mesh, phi, contact_tol, bounds, first=0, lanes=1, seeds=None, fine=False) -> Bounds:
    teeth, theta = mesh.teeth(phi)
    n, kk = teeth.shape
    # only the driver halves with a sample inside the mate's tip circle are searched: the others
    # are free at every sample (their bounds infinite, as the search would find them)
    mid, reach = mesh.half_reach[:2]
    near = np.abs(np.mod(theta[..., None] - mid + np.pi, 2 * np.pi) - np.pi) <= reach  # (n, K, 2)
    r_n, r_k, r_h = np.unravel_index(np.flatnonzero(near), near.shape)
    frame = mesh.frames(theta[r_n, r_k], np.where(r_h == 0, 1.0, -1.0), phi[r_n])
    best, i_a, i_b, i_m, fa, fb = search(mesh, frame, r_n, n, contact_tol, bounds)
    i_n, i_k, i_h = r_n[i_a], r_k[i_a], r_h[i_a]
    shape = (n, kk, 2, 2)
    value = np.full(shape, np.inf)
    value[r_n, r_k, r_h] = best
    exact = np.zeros(shape, bool)
    point = np.full(shape + (2,), np.nan)
    normal = np.full(shape + (2,), np.nan)
    arm = np.full(shape, np.nan)
    piece1 = np.full(shape, -1)
    piece2 = np.full(shape, -1)
    rho2 = np.full(shape, np.nan)
    corner1 = np.zeros(shape, bool)
    corner2 = np.zeros(shape, bool)
    row_code, row_t = np.zeros(0, np.int64), np.zeros(0)
    if i_n.size:
        sigma = np.where(i_h == 0, 1.0, -1.0)
        angle = (first + i_n) // lanes
        key, span = row_key(mesh, teeth[i_n, i_k], i_h, i_b, i_m, (first + i_n) % lanes, lanes)
        given = None if seeds is None else (seeds[0], seeds[1], seeds[2][angle])
        sel, res, t = _refine(mesh, phi[i_n], theta[i_n, i_k], sigma, np.array([1.0, -1.0])[i_b], i_m, fa, fb,
                              i_a * 2 + i_b, frame[:, i_a], (angle, key, span, given, fine))
        row_code, row_t = angle.astype(np.int64) * span + key, t
        at = (i_n[sel], i_k[sel], i_h[sel], i_b[sel])
        exact[at] = True
        value[at], point[at], normal[at], arm[at], piece1[at], piece2[at], rho2[at], corner1[at], corner2[at] = res
    return Bounds(phi, teeth, value, exact, point, normal, arm, piece1, piece2, rho2, corner1, corner2, row_code, row_t)
