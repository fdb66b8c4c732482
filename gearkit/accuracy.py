"""Accuracy as a length: adaptive sampling of exact curves to a chord tolerance.

Nothing in gearkit hard-codes a point count. A curve is known exactly as a function
``w -> points`` on ``[0, 1]``; :func:`adaptive_sample` splits parameter intervals until
every chord lies within ``tol`` (mm) of the curve and reports the deviation it achieved.
A polyline is measured against points of the exact curve taken independently by
:mod:`gearkit.distances`.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.chords import chord_distance as _chord_deviation
from gearkit.chords import angle_parts, interval_bounds, round_off
from gearkit.errors import check_fields, is_real, require
from gearkit.values import frozen

#: probe fractions of every interval: quarter points, and eighths at both ends (where a square-root
#: end, x ~ sqrt(w), puts the chord's largest deviation)
_PROBES = np.array([0.125, 0.25, 0.5, 0.75, 0.875])
_MID = 2
_WIDTHS = np.diff(np.concatenate([[0.0], _PROBES, [1.0]]))


@frozen
class Accuracy:
    """Requested accuracy: the largest distance (mm) of any output point or chord from the exact curve.

    Examples
    --------
    >>> Accuracy(1e-3).tol
    0.001
    """

    tol: float

    def __post_init__(self):
        check_fields(self)
        require(isinstance(self.tol, (int, float)) and math.isfinite(self.tol) and self.tol > 0, "tol",
                f"{self.tol!r} must be a positive length in mm")


#: the finest tolerance a geometry of size ``m`` (its module) is computed to: the exact pieces join
#: and the envelope solver converges to ~1e-12 of the radii, so chords below this are round-off
PRECISION = 1e-9


def check_tol(tol, module: float, field: str = "tol") -> float:
    """``tol`` as a float if it is a length in ``[PRECISION m, m]`` (mm); else ``SpecError`` naming ``field``.

    Below ``PRECISION * module`` a tolerance asks for more than the geometry's own precision (the
    sampler would only add points on round-off); above ``module`` it is no longer a tooth's shape.

    >>> check_tol(1e-3, 1.0)
    0.001
    >>> check_tol(1e-11, 1.0)
    Traceback (most recent call last):
    ...
    gearkit.errors.SpecError: tol: 1e-11 mm is outside [1e-09, 1] mm (the geometry's own precision 1e-9 m up to one module m)
    """
    lo, hi = PRECISION * module, float(module)
    require(is_real(tol) and lo <= tol <= hi, field, f"{tol!r} mm is outside [{lo:.6g}, {hi:.6g}] mm (the "
            "geometry's own precision 1e-9 m up to one module m)")
    return float(tol)


def default_tol(module: float) -> float:
    """Default 2D tolerance: 1e-3 of the module."""
    return 1e-3 * module


#: an interval is accepted when its probed deviation is within this fraction of tol: between the
#: probes a chord's deviation can run above the largest probed one (by ~5 % where the curvature
#: grows from 0 to its largest across the interval), so the accepted chords keep that margin
PROBE_MARGIN = 0.9
#: an interval whose fastest leg between probes (chord / parameter width) exceeds this multiple of its
#: mean speed moves unevenly in its parameter: a narrow feature (a fast, bent stretch) may sit between probes
UNEVEN = 2.5


def _probe(evaluate, w, pts, tol, rows=None):
    """Quarter-point probes of the intervals ``rows`` (vertex ``i`` to ``i + 1``; default all): (probes,
    probe points, chord deviation, uneven), each interval measured on its own."""
    rows = np.arange(len(w) - 1) if rows is None else rows
    lo, hi, a, b = w[rows], w[rows + 1], pts[rows, None, :], pts[rows + 1, None, :]
    probes = lo[:, None] + (hi - lo)[:, None] * _PROBES
    q = evaluate(probes.ravel()).reshape(len(lo), len(_PROBES), 2)
    dev = _chord_deviation(a, b, q).max(axis=1)
    walk = np.concatenate([a, q, b], axis=1)
    legs = np.linalg.norm(np.diff(walk, axis=1), axis=-1)
    length = legs.sum(axis=1)
    speed = legs / _WIDTHS  # mean speed of each leg, against the interval's mean speed (its length)
    uneven = (speed.max(axis=1) > UNEVEN * length) & (length > tol)
    return probes, q, dev, uneven


#: the pilot sampling that the vertices are placed from runs at this multiple of tol (its points
#: and probes only have to show where the curve bends)
PILOT = 16.0
#: uniform samples the pilot starts from (more than ``n_init``: the pilot then settles in fewer rounds,
#: each an ``evaluate`` call, the cost that dominates short chains)
PILOT_START = 17
#: chords are placed to deviate by about this fraction of tol: inside the acceptance test's margin,
#: so that few of them fail it and are split
PLACE_AT = 0.9


def adaptive_sample(evaluate, tol: float, n_init: int = 5, max_rounds: int = 60, max_split: int = 16,
                    fewest: bool = False):
    """Sample an exact curve so that every chord is within ``tol`` of it (on request with near the fewest vertices).

    **Placement.** A pilot sampling (:func:`refine_sample` at ``PILOT tol`` from ``PILOT_START``
    uniform samples) and its probes show
    where the curve bends: a chord of length L where the curvature is k deviates by about
    k L^2 / 8, so the fewest vertices for a chord deviation t are spaced sqrt(8 t / k) apart. The
    vertices are placed at equal steps of ``N(s) = integral sqrt(k / (8 t)) ds`` (``t =
    PLACE_AT tol``, the curvature estimated from the turning of the pilot polyline),
    ``ceil(N)`` chords in all: within a few percent of the fewest a chord-at-tol polyline needs.

    **Acceptance.** The placed vertices then go through :func:`refine_sample` at ``tol``, which
    probes every chord and splits the ones that fail: the placement only proposes. A curve that
    gives its tangent's turning (``turning(w)``) is accepted on a proven bound of each chord's
    deviation (``bound=True``), any other on the deviation measured at the probes.

    ``fewest=True`` places the vertices so (what a profile's outline, a mesh or an exported curve
    asks for); the default ``False`` keeps the refinement's own vertices (a uniform ``n_init``
    start refined at ``tol``): denser where the curve bends, and what the start tables of the
    contact and crossing solvers are tuned on.

    Parameters
    ----------
    evaluate : callable, (n,) float64 -> (n, 2) float64
        Exact curve on ``w in [0, 1]``.
    tol : float, mm
    n_init : int
        Starting uniform samples (enough to see the curve's shape; refinement does the rest).
    max_split : int
        Most parts one interval is split into in one round (bisection: 2).
    fewest : bool
        Place the vertices by curvature, or keep the refinement's own (default).

    Returns
    -------
    w : (k,) float64
    points : (k, 2) float64, on the curve
    achieved : float, mm
        With ``fewest=True`` on a curve whose ``turning(w)`` gives angle parts (not None: every tooth piece), a
        *proven upper bound* of every chord's deviation (:mod:`gearkit.chords`: it holds if each
        angle part the curve gives is monotone along it and the curve has no cusp inside; round-off
        of the exact points aside); otherwise the largest deviation measured at the probes.

    Examples
    --------
    A quarter circle of radius 1 at tol 1e-3 needs chords of angle 2 acos(1 - 1e-3) (0.0895 rad):
    18 chords, 19 vertices at the least; the placement lands within one of that:

    >>> arc = lambda w: np.stack([np.cos(np.pi / 2 * w), np.sin(np.pi / 2 * w)], -1)
    >>> w, p, achieved = adaptive_sample(arc, 1e-3, fewest=True)
    >>> least = math.ceil((np.pi / 2) / (2 * math.acos(1 - 1e-3))) + 1
    >>> least, len(p) - least, bool(achieved <= 1e-3)
    (19, 1, True)

    A bump of height 0.1 that the parameter crosses within a few thousandths near w = 0.053: the
    probes of the first interval all land on its chord (a sampler that trusts its probes
    reports 2e-9 and is 0.1 off); the uneven walk through them gives it away:

    >>> def f(w):
    ...     t = np.tanh((w - 0.053) / 0.001)
    ...     return np.stack([t + w, 0.1 * (1 - t * t)], -1)
    >>> from gearkit.distances import polyline_deviation
    >>> w, p, achieved = adaptive_sample(f, 1e-3)
    >>> dense = f(np.linspace(0, 1, 100001))
    >>> bool(polyline_deviation(p, dense) <= 1e-3), bool(achieved <= 1e-3)
    (True, True)
    >>> w, p, achieved = adaptive_sample(f, 1e-3, fewest=True)  # placed, and then probed the same way
    >>> bool(polyline_deviation(p, dense) <= 1e-3), bool(achieved <= 1e-3)
    (True, True)
    """
    w = np.linspace(0.0, 1.0, n_init)
    if not fewest:
        return refine_sample(evaluate, w, evaluate(w), tol, max_rounds, max_split)[:3]
    w = np.linspace(0.0, 1.0, max(n_init, PILOT_START))
    w, pts, _, probes, q = refine_sample(evaluate, w, evaluate(w), PILOT * tol, max_rounds, max_split)
    w = place_by_curvature(np.concatenate([w, probes.ravel()]), np.concatenate([pts, q.reshape(-1, 2)]),
                           PLACE_AT * tol)
    bound = getattr(evaluate, "turning", None) is not None
    return refine_sample(evaluate, w, None if bound else evaluate(w), tol, max_rounds, max_split, bound)[:3]


def place_by_curvature(w, points, tol: float) -> np.ndarray:
    """Parameters of the fewest vertices whose chords deviate by about ``tol`` from a curve, from a
    dense polyline of it.

    ``w`` (k,) and ``points`` (k, 2) are parameters and points of the curve (any order; ends at
    w = 0 and 1 included). The curvature is estimated from the turning of the sorted polyline
    (turn angle over the mean of the two edges at each vertex), ``N(s) = integral sqrt(k / (8
    tol)) ds`` is accumulated along it, and ``ceil(N)`` chords are placed at equal steps of N
    (parameters interpolated). Ends are kept exactly. A proposal: the caller checks the chords.

    Examples
    --------
    A circle of radius 2 bends evenly: a quarter of it at tol 1e-3 needs chords of angle
    ``sqrt(8 tol / 2) / 1`` (in radians, ``k L^2 / 8 = tol``) -- 25 chords, evenly spaced:

    >>> w = np.linspace(0.0, 1.0, 401)
    >>> arc = 2.0 * np.stack([np.cos(np.pi / 2 * w), np.sin(np.pi / 2 * w)], -1)
    >>> placed = place_by_curvature(w, arc, 1e-3)
    >>> len(placed) - 1, math.ceil((np.pi / 2) / math.sqrt(8 * 1e-3 / 2.0))
    (25, 25)
    >>> bool(np.allclose(np.diff(placed), 1 / 25))
    True
    """
    order = np.argsort(w, kind="stable")
    w, p = np.asarray(w, dtype=float)[order], np.asarray(points, dtype=float)[order]
    d = np.diff(p, axis=0)
    length = np.hypot(d[:, 0], d[:, 1])
    if len(length) < 2 or not length.max(initial=0.0) > 0.0:
        return np.array([0.0, 1.0])
    a, b = d[:-1], d[1:]
    turn = np.arctan2(np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]), (a * b).sum(axis=1))
    mean = 0.5 * (length[:-1] + length[1:])
    with np.errstate(divide="ignore", invalid="ignore"):
        k = np.where((length[:-1] > 0) & (length[1:] > 0), turn / mean, 0.0)  # at the inner vertices
    root = np.sqrt(np.concatenate([k[:1], k, k[-1:]]))
    n_of_s = np.concatenate([[0.0], np.cumsum(length * 0.5 * (root[:-1] + root[1:]))]) / math.sqrt(8.0 * tol)
    chords = max(1, math.ceil(n_of_s[-1] - 1e-9))
    placed = np.interp(np.linspace(0.0, n_of_s[-1], chords + 1), n_of_s, w)
    placed[0], placed[-1] = 0.0, 1.0
    return placed[np.concatenate([[True], np.diff(placed) > 0.0])]  # sorted already (np.unique imports numpy.ma)


def _carry(n, rows, fresh, at, old):
    """The measurements of ``n`` intervals: ``fresh`` ones of the intervals ``rows``, the ``old`` ones
    of the intervals ``at`` (unchanged since they were measured)."""
    out = []
    for f, o in zip(fresh, old):
        both = np.empty((n,) + f.shape[1:], dtype=f.dtype)
        both[rows], both[at] = f, o
        out.append(both)
    return tuple(out)


#: a parameter interval this short (relative) holds no curve points but its ends and probes
ATOM = 1e-13


def refine_sample(evaluate, w, pts, tol: float, max_rounds: int = 60, max_split: int = 16, bound: bool = False):
    """Split the intervals of a sampling ``(w, pts)`` of an exact curve until every chord is within ``tol``.

    Each round probes every interval at its quarter points and eighths at both ends (an interval no
    point was added to keeps the probes and measures of the round before: they depend on its ends
    alone). An interval whose chord deviates by ``dev > PROBE_MARGIN tol`` is split into
    ``k = ceil(1.1 sqrt(dev / (PROBE_MARGIN tol)))`` equal parameter parts (at most
    ``max_split``): a chord's deviation shrinks as the square of its length, so one round usually
    settles an interval and the rounds (each a call of ``evaluate``, the cost that dominates for
    short chains) stay few. An interval that moves *unevenly* in its parameter (the walk through
    its probes is ``UNEVEN`` times faster on one leg than on average, and longer than ``tol``) is
    split at its probes however small its probed deviation: that is where a narrow
    feature (a short, sharply bent stretch the parameter runs through fast) hides between
    probes, and the quadratic model behind the probes only holds once the speed is even.
    Intervals still too coarse split again.

    ``bound=True`` (the curve has ``turning(w)``, see :mod:`gearkit.chords`): ``dev`` is instead each
    interval's *proven bound* over the legs between its probes (no margin: ``dev <= tol`` accepts), an
    interval whose bound is not established is split at its probes, and ``achieved`` is a bound. The
    vertices and the first round's probes are evaluated in one call of ``turning``; where it gives no
    angle parts (None) the sampling is probed as with ``bound=False`` (``pts`` may be None: evaluated).

    Returns
    -------
    w, points, achieved (as :func:`adaptive_sample`), and the final probes' parameters
    ``(k - 1, 5)`` and points ``(k - 1, 5, 2)``.
    """
    turned = probed = None
    if bound:  # the vertices and the probes of the first round
        first = w[:-1, None] + np.diff(w)[:, None] * _PROBES
        turned = evaluate.turning(np.concatenate([w, first.ravel()]))
    if turned is not None:
        turning = angle_parts(evaluate.turning)
        every = angle_parts(lambda _: turned)(None)
        pts, tan, parts = (v[:len(w)] for v in every)
        probed = tuple(v[len(w):] for v in every)  # handed to the first round's bounds
        margin, bound = 1.0, True
    else:
        pts = evaluate(w) if pts is None else pts
        margin, bound = PROBE_MARGIN, False
    todo, kept = np.arange(len(w) - 1), None  # the intervals to probe: all, then the ones a round made
    for _ in range(max_rounds):
        lo, hi = w[:-1], w[1:]
        if not len(todo):
            measured = kept[1]
        else:
            measured = (interval_bounds(turning, w, pts, tan, parts, tol, _PROBES, todo, probed) if bound
                        else _probe(evaluate, w, pts, tol, todo))
            probed = None
            measured = measured if kept is None else _carry(len(lo), todo, measured, *kept)
        if bound:
            probes, q, tq, pq, dev = measured
            dev = dev + round_off(pts)
            uneven = ~np.isfinite(dev)
            # an interval below the parameter's resolution has no points but its ends and probes: a curve
            # that jumps there (an exact solution switching roots at the very end of its range) is
            # measured at them
            atom = uneven & (hi - lo <= ATOM * np.maximum(np.abs(lo), np.abs(hi)).clip(1.0))
            if atom.any():
                dev[atom] = _chord_deviation(pts[:-1][atom, None], pts[1:][atom, None], q[atom]).max(axis=1)
                uneven &= ~atom
        else:
            probes, q, dev, uneven = measured
        bad = (dev > margin * tol) & ~uneven
        if not (bad.any() or uneven.any()):
            return w, pts, float(dev.max(initial=0.0)), probes, q
        k = np.clip(np.ceil(1.1 * np.sqrt(dev[bad] / (margin * tol))), 2, max(2, max_split)).astype(int)
        quarters = uneven & ~bad  # split at the probes already evaluated
        new_w = [probes[bad, _MID], probes[quarters].ravel()]
        new_p = [q[bad, _MID], q[quarters].reshape(-1, 2)]
        if bound:
            new_t = [tq[bad, _MID], tq[quarters].reshape(-1, 2)]
            new_a = [pq[bad, _MID], pq[quarters].reshape(-1, parts.shape[-1])]
        if (k > 2).any():  # the midpoint is already evaluated; other split points are new
            many = k > 2
            kk = k[many]
            rows = np.repeat(np.arange(len(kk)), kk - 1)
            j = np.arange(len(rows)) - np.repeat(np.cumsum(kk - 1) - (kk - 1), kk - 1) + 1
            frac = j / kk[rows]
            keep = np.abs(frac - 0.5) > 1e-12
            a, h = lo[bad][many][rows][keep], (hi - lo)[bad][many][rows][keep]
            extra = a + h * frac[keep]
            new_w.append(extra)
            if bound:
                pe, te, ae = turning(extra)
                new_p.append(pe)
                new_t.append(te)
                new_a.append(ae)
            else:
                new_p.append(evaluate(extra))
        old = w
        w = np.concatenate([w] + new_w)
        pts = np.concatenate([pts] + new_p)
        w, first = np.unique(w, return_index=True)  # sorted; an interval too short to split stays whole
        pts = pts[first]  # an old vertex keeps its point (the first of equal parameters)
        if bound:
            tan, parts = np.concatenate([tan] + new_t)[first], np.concatenate([parts] + new_a)[first]
        # an interval with the same two ends is measured the same: only the new ones are probed again
        at = np.searchsorted(w, old)
        same = np.diff(at) == 1
        kept = at[:-1][same], tuple(m[same] for m in measured)
        fresh = np.ones(len(w) - 1, dtype=bool)
        fresh[kept[0]] = False
        todo = np.flatnonzero(fresh)
    if bound:
        probes, q, _, _, dev = interval_bounds(turning, w, pts, tan, parts, tol, _PROBES)
        dev = dev + round_off(pts)
        atom = ~np.isfinite(dev) & (np.diff(w) <= ATOM * np.maximum(np.abs(w[:-1]), np.abs(w[1:])).clip(1.0))
        dev[atom] = _chord_deviation(pts[:-1][atom, None], pts[1:][atom, None], q[atom]).max(axis=1)
    else:
        probes, q, dev, _ = _probe(evaluate, w, pts, tol)
    return w, pts, float(dev.max(initial=0.0)), probes, q
