"""Refinement of samplings of exact curves until every chord is within a tolerance, several curves at once.

A curve is known exactly as a function ``w -> points`` on ``[0, 1]``. :func:`refine_samples` takes a
sampling of each of several curves and splits their intervals, round by round, until every chord is
within ``tol`` of its curve; every interval is measured on its own (its probes, its deviation and its
splits depend on its two ends alone), so refining the curves together gives each the vertices, probes
and achieved deviation it gets alone (:func:`refine_sample`), to the last bit, while each round's
bookkeeping is one pass over all of them (a tooth's pieces: a handful of short chains whose cost is the
number of calls, not their length). Only the curves are called one by one, each on its own parameters.
"""
from __future__ import annotations

import numpy as np

from gearkit.chords import angle_parts, fractions_of, interval_bounds, monotone_range, put_rows, round_offs
from gearkit.chords import chord_distance as _chord_deviation
from gearkit.chords import point_distance as _chord_points
from gearkit.errors import GeometryError

__all__ = ["ATOM", "PROBE_MARGIN", "UNEVEN", "evaluate_curves", "first_samples", "first_turning", "first_turnings",
           "refine_sample", "refine_samples", "turn_curves"]

#: probe fractions of every interval: quarter points, and eighths at both ends (where a square-root
#: end, x ~ sqrt(w), puts the chord's largest deviation)
_PROBES = np.array([0.125, 0.25, 0.5, 0.75, 0.875])
_MID = 2
_WIDTHS = np.diff(np.concatenate([[0.0], _PROBES, [1.0]]))
#: the probes of ``middle=True`` (:func:`refine_samples`): each interval's middle, its quarters where needed
_MIDDLE, _QUARTERS = np.array([0.5]), np.array([0.25, 0.75])

#: an interval is accepted when its probed deviation is within this fraction of tol: between the
#: probes a chord's deviation can run above the largest probed one (by ~5 % where the curvature
#: grows from 0 to its largest across the interval), so the accepted chords keep that margin
PROBE_MARGIN = 0.9
#: an interval whose fastest leg between probes (chord / parameter width) exceeds this multiple of its
#: mean speed moves unevenly in its parameter: a narrow feature (a fast, bent stretch) may sit between probes
UNEVEN = 2.5
#: a parameter interval this short (relative) holds no curve points but its ends and probes
ATOM = 1e-13
#: unproven intervals a round may hold: each splits at its probes, so ones that stay unproven would multiply for ever
UNPROVEN_LIMIT = 1 << 16


def _probe(evaluate, w, pts, tol, rows=None, probed=None):
    """Quarter-point probes of the intervals ``rows`` (vertex ``i`` to ``i + 1``; default all): (probes,
    probe points, chord deviation, uneven), each interval measured on its own. ``evaluate(x, rows)``
    gives the points at parameters ``x`` ``(m, j)`` of the intervals ``rows``; ``probed``: the points at
    the probes (flat), where the caller evaluated them already."""
    rows = np.arange(len(w) - 1) if rows is None else rows
    # rows taken whole (``take``): indexing the first axis of a 2-d array copies it point by point
    lo, hi, a, b = w[rows], w[rows + 1], pts.take(rows, axis=0)[:, None], pts.take(rows + 1, axis=0)[:, None]
    probes = fractions_of(lo, hi - lo, _PROBES)
    q = (evaluate(probes, rows) if probed is None else probed).reshape(len(lo), len(_PROBES), 2)
    # the walk from a through the probes to b as (x or y, point, interval): every operation runs along the intervals
    walk = np.concatenate([a, q, b], axis=1).transpose(2, 1, 0).copy()
    (ax, bx), (ay, by) = walk[0, ::len(_PROBES) + 1], walk[1, ::len(_PROBES) + 1]
    dev = _chord_points(ax, ay, bx - ax, by - ay, walk[0, 1:-1], walk[1, 1:-1]).max(axis=0)
    step = walk[:, 1:] - walk[:, :-1]
    legs = np.sqrt(step[0] * step[0] + step[1] * step[1])  # np.linalg.norm's sum of the two squares
    length = np.ascontiguousarray(legs.T).sum(axis=1)  # each interval's legs added as a row, in their order
    speed = legs / _WIDTHS[:, None]  # mean speed of each leg, against the interval's mean speed (its length)
    uneven = (speed.max(axis=0) > UNEVEN * length) & (length > tol)
    return probes, q, dev, uneven


def _scatter(n, rows, fresh, at=None, old=None):
    """The measurements of ``n`` intervals: ``fresh`` ones of the intervals ``rows``, the ``old`` ones
    of the intervals ``at`` (unchanged since they were measured), zero elsewhere (between two curves)."""
    out = []
    for j, f in enumerate(fresh):
        both = np.zeros((n,) + f.shape[1:], dtype=f.dtype)
        put_rows(both, rows, f)
        if at is not None:
            put_rows(both, at, old[j])
        out.append(both)
    return tuple(out)


def _groups(curves):
    """Indices of the curves evaluated in one call: one list per ``joint`` key (a curve without one, alone)."""
    groups, keyed = [], {}
    for i, curve in enumerate(curves):
        key = getattr(curve, "joint", None)
        if key is None:
            groups.append([i])
        elif key in keyed:
            keyed[key].append(i)
        else:
            keyed[key] = [i]
            groups.append(keyed[key])
    return groups


def evaluate_curves(curves, params):
    """Points of each curve at its parameters ``params[i]``: curves of one ``joint`` key in one call of their
    ``together(curves, params)`` (each curve's points as it gives them alone), any other on its own."""
    out = [None] * len(curves)
    for group in _groups(curves):
        if len(group) == 1:
            out[group[0]] = curves[group[0]](params[group[0]])
            continue
        for i, points in zip(group, curves[group[0]].together([curves[i] for i in group], [params[i] for i in group])):
            out[i] = points
    return out


def turn_curves(curves, params):
    """Each curve's ``turning`` at its parameters (points, tangents, angle parts ``(n, k)``), or None where it
    gives none; curves of one ``joint`` key in one call of their ``turning_together``."""
    out = [None] * len(curves)
    for group in _groups(curves):
        if len(group) == 1:
            turning = getattr(curves[group[0]], "turning", None)
            turned = [None if turning is None else turning(params[group[0]])]
        else:
            turned = curves[group[0]].turning_together([curves[i] for i in group], [params[i] for i in group])
        for i, t in zip(group, turned):
            out[i] = None if t is None else (t[0], t[1], np.asarray(t[2], dtype=float).reshape(len(t[0]), -1))
    return out


class _Curves:
    """Several curves called as one on parameters grouped by curve: ``owner[i]`` is the curve of
    interval ``i``; each curve is called once per run of its intervals, on its own parameters."""

    def __init__(self, curves, owner, parts: int = 0):
        self.curves, self.owner, self.parts = curves, owner, parts
        self.spans = [getattr(c, "span", None) for c in curves]
        self.span = self._span if any(s is not None for s in self.spans) else None

    def _runs(self, rows):
        own = self.owner[rows]
        cuts = (own[1:] != own[:-1]).nonzero()[0] + 1
        return zip(np.concatenate([[0], cuts]).tolist(), np.concatenate([cuts, [len(rows)]]).tolist(),
                   own[np.concatenate([[0], cuts])].tolist())

    def points(self, x, rows):
        """Points at ``x`` ``(m, ...)``, parameters of the intervals ``rows`` ``(m,)``: ``(size, 2)``."""
        runs = list(self._runs(rows))
        if len(runs) == 1:
            return self.curves[runs[0][2]](np.ravel(x))
        out = evaluate_curves([self.curves[c] for _, _, c in runs], [np.ravel(x[a:b]) for a, b, _ in runs])
        return np.concatenate(out)

    def evaluate_at(self, x, own, turning: bool = False):
        """Points (or ``turning``, as :meth:`turning`) at flat parameters ``x`` of the curves ``own`` (any order):
        each curve called once, on its parameters in their order."""
        order = np.argsort(own, kind="stable")
        x, own = x[order], own[order]
        cuts = (own[1:] != own[:-1]).nonzero()[0] + 1
        starts, ends = np.concatenate([[0], cuts]).tolist(), np.concatenate([cuts, [len(x)]]).tolist()
        curves, params = [self.curves[c] for c in own[starts].tolist()], [x[a:b] for a, b in zip(starts, ends)]
        back = np.empty_like(order)
        back[order] = np.arange(len(order))
        if not turning:
            return np.concatenate(evaluate_curves(curves, params)).take(back, axis=0)
        out = turn_curves(curves, params)
        joined = out[0] if len(out) == 1 and out[0][2].shape[1] == self.parts else _joined(out, self.parts)
        return tuple(v.take(back, axis=0) for v in joined)

    def _span(self, pa, pb, rows):
        """Each leg's turn range (:func:`~gearkit.chords.interval_bounds`' ``span``): its curve's own ``span``,
        or the range of its monotone parts."""
        turns = []
        for a, b, c in self._runs(rows):
            span = self.spans[c]
            turns.append(monotone_range(pb[a:b] - pa[a:b]) if span is None else span(pa[a:b], pb[a:b]))
        return tuple(np.concatenate([t[j] for t in turns]) for j in range(3))

    def turning(self, x, rows):
        """Points, unit tangents and angle parts (zero parts added up to ``parts``) at ``x``, as ``points``."""
        runs = list(self._runs(rows))
        out = turn_curves([self.curves[c] for _, _, c in runs], [np.ravel(x[a:b]) for a, b, _ in runs])
        if len(out) == 1 and out[0][2].shape[1] == self.parts:
            return out[0]
        return _joined(out, self.parts)


def _joined(turned, width: int):
    """Points, tangents and angle parts of several curves one after another, the parts padded with zero
    parts to ``width`` (a zero part adds nothing to a leg's range)."""
    p, t = (np.concatenate([o[j] for o in turned]) for j in (0, 1))
    parts = np.zeros((len(p), width))
    at = 0
    for o in turned:
        parts[at:at + len(o[2]), :o[2].shape[1]] = o[2]
        at += len(o[2])
    return p, t, parts


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
    w, points, achieved (as :func:`gearkit.accuracy.adaptive_sample`), and the final probes' parameters
    ``(k - 1, 5)`` and points ``(k - 1, 5, 2)``.
    """
    turned = first_turning(evaluate, w) if bound else None
    if turned is None:
        return refine_samples([evaluate], [w], [evaluate(w) if pts is None else pts], tol, max_rounds, max_split)[0]
    return refine_samples([evaluate], [w], None, tol, max_rounds, max_split, turned=[turned])[0]


def first_turning(curve, w):
    """``curve.turning`` at the vertices ``w`` and the first round's probes of their intervals (one call),
    with its angle parts as ``(n, k)``; None where the curve gives none."""
    return first_turnings([curve], [w])[0]


def first_turnings(curves, ws, middle: bool = False):
    """:func:`first_turning` of several curves (those of one ``joint`` key in one call); ``middle``: the
    probes of :func:`refine_samples` with ``middle=True`` (each interval's middle)."""
    fractions = _MIDDLE if middle else _PROBES
    return turn_curves(curves, [np.concatenate([w, _first_probes(w, fractions)]) for w in ws])


def _first_probes(w, fractions=_PROBES):
    """The first round's probes of the intervals of a sampling ``w``, flat (as the rounds place them)."""
    return fractions_of(w[:-1], w[1:] - w[:-1], fractions).ravel()


def first_samples(curves, ws, more=None):
    """Points of each curve at its vertices ``ws[i]``, at the first round's probes of their intervals (what
    :func:`refine_samples` takes as ``probed``) and at the parameters ``more[i]``, all in one evaluation
    (:func:`evaluate_curves`): ``[(at w, at the probes, at more)]``."""
    more = [np.empty(0)] * len(ws) if more is None else more
    out = evaluate_curves(curves, [np.concatenate([w, _first_probes(w), m]) for w, m in zip(ws, more)])
    return [(p[:len(w)], p[len(w):len(w) + 5 * (len(w) - 1)], p[len(w) + 5 * (len(w) - 1):]) for p, w in zip(out, ws)]


def refine_samples(curves, ws, ptss, tol: float, max_rounds: int = 60, max_split: int = 16, turned=None,
                   probed=None, middle: bool = False):
    """:func:`refine_sample` of several curves at once: ``[(w, points, achieved, probes, q)]``, one per curve,
    each to the last bit what the curve gets alone.

    ``ws`` are the curves' starting parameters (sorted, each curve's own); ``ptss`` their points (probed
    sampling; ``probed``: each curve's points at the first round's probes, where the caller evaluated them
    with :func:`first_samples`), or None with ``turned`` given: each curve's :func:`first_turning` at its
    ``w`` (proven bounds; every curve must give angle parts).

    ``middle=True`` (``turned`` by :func:`first_turnings` with ``middle=True``): each interval is bounded over
    the legs through its middle (two turning evaluations a vertex, not six), and through its quarter points
    too only where those do not prove ``tol`` (the lower proven bound kept); the probes: the middles.
    """
    bound = turned is not None
    fractions, mid, more = (_MIDDLE, 0, _QUARTERS) if middle else (_PROBES, _MID, None)
    sizes = [len(w) for w in ws]
    owner = np.repeat(np.arange(len(ws)), sizes)
    w = np.concatenate(ws)
    if bound:
        width = max(t[2].shape[1] for t in turned)
        curves = _Curves(curves, owner[:-1], width)
        if len(turned) == 1:
            (p, t, a), n = turned[0], sizes[0]
            (pts, tan, parts), probed = (p[:n], t[:n], a[:n]), (p[n:], t[n:], a[n:])
        else:  # the vertices of every curve, then the probes of every curve
            pts, tan, parts = _joined([tuple(v[:n] for v in t) for t, n in zip(turned, sizes)], width)
            probed = _joined([tuple(v[n:] for v in t) for t, n in zip(turned, sizes)], width)
        margin = 1.0
    else:
        curves = _Curves(curves, owner[:-1])
        pts, margin = np.concatenate(ptss), PROBE_MARGIN
        probed = None if probed is None else np.concatenate(probed)
    todo, kept = (owner[:-1] == owner[1:]).nonzero()[0], None  # the intervals to probe: within a curve
    for _ in range(max_rounds):
        curves.owner = owner[:-1]
        lo, hi = w[:-1], w[1:]
        starts = np.concatenate([[True], owner[1:] != owner[:-1]]).nonzero()[0]
        inside = owner[:-1] == owner[1:]
        if not len(todo):
            measured = kept[1]
        else:
            measured = (interval_bounds(curves.turning, w, pts, tan, parts, tol, fractions, todo, probed, curves.span,
                                        more) if bound else _probe(curves.points, w, pts, tol, todo, probed))
            probed = None
            measured = _scatter(len(lo), todo, measured, *(kept or (None, None)))
        if bound:
            probes, q, tq, pq, dev = measured
            dev = np.where(inside, dev + round_offs(pts, starts, owner), 0.0)
            uneven = ~np.isfinite(dev)
            # an interval below the parameter's resolution has no points but its ends and probes: a curve
            # that jumps there (an exact solution switching roots at the very end of its range) is
            # measured at them
            atom = uneven & (hi - lo <= ATOM * np.maximum(np.abs(lo), np.abs(hi)).clip(1.0)) \
                if np.count_nonzero(uneven) else None
            if atom is not None and np.count_nonzero(atom):
                dev[atom] = _chord_deviation(pts[:-1][atom, None], pts[1:][atom, None], q[atom]).max(axis=1)
                uneven &= ~atom
        else:
            probes, q, dev, uneven = measured
        bad = (dev > margin * tol) & ~uneven
        if (unproven := np.count_nonzero(uneven)) > UNPROVEN_LIMIT:
            raise GeometryError(f"the curve's turn between samples is not bounded: {unproven} chords (over {UNPROVEN_LIMIT}) unproven after splitting")
        if not (np.count_nonzero(bad) or np.count_nonzero(uneven)):
            return _split_up(w, pts, dev, probes, q, starts)
        k = np.ceil(1.1 * np.sqrt(dev[bad] / (margin * tol))).clip(2, max(2, max_split)).astype(int)
        quarters = uneven & ~bad  # split at the probes already evaluated
        new_w = [probes[bad, mid], probes[quarters].ravel()]
        new_p = [q[bad, mid], q[quarters].reshape(-1, 2)]
        new_o = [owner[:-1][bad], np.repeat(owner[:-1][quarters], len(fractions))]
        if bound:
            new_t = [tq[bad, mid], tq[quarters].reshape(-1, 2)]
            new_a = [pq[bad, mid], pq[quarters].reshape(-1, parts.shape[-1])]
        if np.count_nonzero(k > 2):  # the midpoint is already evaluated; other split points are new
            many = k > 2
            kk = k[many]
            rows = np.repeat(np.arange(len(kk)), kk - 1)
            j = np.arange(len(rows)) - np.repeat(np.cumsum(kk - 1) - (kk - 1), kk - 1) + 1
            frac = j / kk[rows]
            keep = np.abs(frac - 0.5) > 1e-12
            a, h = lo[bad][many][rows][keep], (hi - lo)[bad][many][rows][keep]
            extra = a + h * frac[keep]
            at = bad.nonzero()[0][many][rows][keep]  # the interval each new point splits
            new_w.append(extra)
            new_o.append(owner[:-1][at])
            # evaluated below, with the next round's probes (one call)
            new_p.append(np.full((len(extra), 2), np.nan))
            if bound:
                new_t.append(np.full((len(extra), 2), np.nan))
                new_a.append(np.full((len(extra), parts.shape[-1]), np.nan))
        else:
            extra = None
        n_old = len(w)
        w, owner = np.concatenate([w] + new_w), np.concatenate([owner] + new_o)
        pts = np.concatenate([pts] + new_p)
        # sorted by curve, then parameter; an interval too short to split stays whole, and an old vertex
        # keeps its point (the first of equal parameters: the sort is stable)
        order = np.lexsort((w, owner))
        w, owner = w[order], owner[order]
        first = np.concatenate([[True], (w[1:] != w[:-1]) | (owner[1:] != owner[:-1])])
        order, w, owner = order[first], w[first], owner[first]
        pts = pts.take(order, axis=0)
        if bound:
            tan = np.concatenate([tan] + new_t).take(order, axis=0)
            parts = np.concatenate([parts] + new_a).take(order, axis=0)
        # an interval with the same two ends is measured the same: only the new ones are probed again
        where = np.full(len(first), -1)  # -1: a new point dropped (its parameter a vertex's already)
        where[order] = np.arange(len(order))
        at = where[:n_old]  # the old vertices (all kept) in the new sampling
        same = (at[1:] - at[:-1]) == 1
        kept = at[:-1][same], tuple(m[same] for m in measured)
        fresh = owner[:-1] == owner[1:]
        fresh[kept[0]] = False
        todo = fresh.nonzero()[0]
        if extra is not None:  # the new split points and the next round's probes, in one call
            new = where[n_old + sum(len(v) for v in new_w[:-1]):]  # the new split points in the new sampling
            extra, new = extra[new >= 0], new[new >= 0]
            lo, hi = w[todo], w[todo + 1]
            x = np.concatenate([extra, fractions_of(lo, hi - lo, fractions).ravel()])
            got = curves.evaluate_at(x, np.concatenate([owner[new], np.repeat(owner[todo], len(fractions))]), bound)
            e = len(extra)
            if bound:
                for into, value in zip((pts, tan, parts), got):
                    put_rows(into, new, value[:e])
                probed = tuple(v[e:] for v in got)
            else:
                put_rows(pts, new, got[:e])
                probed = got[e:]
    curves.owner = owner[:-1]
    starts = np.concatenate([[True], owner[1:] != owner[:-1]]).nonzero()[0]
    inside = owner[:-1] == owner[1:]
    rows = inside.nonzero()[0]
    if bound:
        probes, q, _, _, dev = _scatter(len(w) - 1, rows,
                                        interval_bounds(curves.turning, w, pts, tan, parts, tol, fractions, rows,
                                                        span=curves.span, more=more))
        dev = np.where(inside, dev + round_offs(pts, starts, owner), 0.0)
        atom = ~np.isfinite(dev) & ((w[1:] - w[:-1]) <= ATOM * np.maximum(np.abs(w[:-1]), np.abs(w[1:])).clip(1.0))
        dev[atom] = _chord_deviation(pts[:-1][atom, None], pts[1:][atom, None], q[atom]).max(axis=1)
    else:
        probes, q, dev, _ = _scatter(len(w) - 1, rows, _probe(curves.points, w, pts, tol, rows))
    return _split_up(w, pts, dev, probes, q, starts)


def _split_up(w, pts, dev, probes, q, starts):
    """Each curve's ``(w, points, achieved, probes, q)`` out of the joint sampling."""
    out = []
    for a, b in zip(starts.tolist(), starts[1:].tolist() + [len(w)]):
        out.append((w[a:b], pts[a:b], float(dev[a:b - 1].max(initial=0.0)), probes[a:b - 1], q[a:b - 1]))
    return out
