"""The parts of the admissible region's function, and which of them binds at a point of its outline (for
:mod:`~gearkit.blocking.tips` and :mod:`~gearkit.blocking.walk`).

The region's function is the smallest of its parts: the hard margins of the pair's check and the distances to the
window's four edges (:func:`part_evaluator`). Where the part binding at one vertex of the outline differs from the
next one's, the edge turns a corner between them (:func:`binding`).
"""
from __future__ import annotations

import numpy as np

from gearkit.blocking.apex import STEP_H

__all__ = ["part_evaluator", "binding"]


def part_evaluator(field, window, count=None):
    """``G(points (n, 2), which (n,) int) -> (n,)``: part ``which[i]`` of the region's function at
    ``points[i]``: the hard margins of ``field`` (NaN where no pair exists), then the distances to the
    window's four edges (x1 - lo, hi - x1, x2 - lo, hi - x2); ``G.size`` parts, ``G.window``, and
    ``G.many(points)``: every part at the points, ``(G.size, n)``; ``G.costly``: the parts whose
    corners are not carried (the tip sweep); ``G.flat``: part -> the level at which it is flat (the tip
    sweep's resolution, where it finds no penetration). The region's function
    (:func:`~gearkit.blocking.arrays.evaluator`'s ``"region"``) is their smallest. ``count``: a list
    whose first item counts the points evaluated (times the parts, for ``G.many``)."""
    from gearkit.blocking.arrays import evaluator
    from gearkit.pair.internal import SWEEP_RESOLUTION

    hard = list(field.hard)
    M = evaluator(field, hard, None)
    edges = np.array([0, 0, 1, 1]), np.array([False, True, False, True])  # axis, upper
    lo = np.array([window[0], window[2]], dtype=float)
    hi = np.array([window[1], window[3]], dtype=float)

    def G(p, which):
        p = np.asarray(p, dtype=float).reshape(-1, 2)
        if count is not None:
            count[0] += len(p)
        which = np.asarray(which)
        out = np.empty(len(p))
        m = which < len(hard)
        if np.count_nonzero(m):
            out[m] = M(p[m], which[m])
        j = which[~m] - len(hard)
        axis, upper = j // 2, j % 2 == 1
        v = p[~m, axis]
        out[~m] = np.where(upper, hi[axis] - v, v - lo[axis])
        return out

    def many(p):
        """Every part at the points ``p``: ``(G.size, n)``."""
        p = np.asarray(p, dtype=float).reshape(-1, 2)
        if count is not None:
            count[0] += len(p) * G.size
        v = p[:, edges[0]].T
        w = np.where(edges[1][:, None], hi[edges[0]][:, None] - v, v - lo[edges[0]][:, None])
        return np.concatenate([M.many(p, range(len(hard))), w]) if len(p) else np.zeros((G.size, 0))
    def slack(p, which):
        """The conditions for part ``which[i]`` to be defined at ``p[i]`` (:func:`~gearkit.blocking.arrays.evaluator`'s
        ``slack``; a window's edge is defined everywhere)."""
        p = np.asarray(p, dtype=float).reshape(-1, 2)
        if count is not None:
            count[0] += len(p)
        which = np.asarray(which)
        out = np.full((len(p), 4), np.inf)
        m = which < len(hard)
        if np.count_nonzero(m):
            out[m] = M.slack(p[m], which[m])
        return out
    G.size, G.window, G.many, G.slack = len(hard) + 4, tuple(window), many, slack
    # the tip sweep (B6 tip interference): a sweep of the tips at every point, exact only down to -SWEEP_ENOUGH
    # and not smooth below: its corners are left as the outline has them (traced as one of its parts, a side
    # took minutes on 20/49 internal at tol 1e-3)
    G.costly = [i for i, n in enumerate(hard) if n == "tip_interference"]
    G.flat = {i: SWEEP_RESOLUTION for i in G.costly}  # its margin where it finds no penetration (its kink's level)
    return G


def binding(G, P, tol: float) -> np.ndarray:
    """The part smallest at each point of ``P`` (``(n,)`` int; -1 where one is undefined: no pair). Where
    that is a costly part at its flat level (``G.flat``: the tip sweep finding no penetration, its margin
    the sweep's resolution, its slope nil) and the smallest of the others lies within ``tol`` of its zero
    (its value over its slope), the other: the edge there is the other's zero, the costly part's kink
    beside it (25/54 z0 20: exit jamming, where the tip sweep starts to penetrate)."""
    V = G.many(P)
    fin = np.all(np.isfinite(V), axis=0)
    V = np.where(np.isfinite(V), V, np.inf)
    b = np.argmin(V, axis=0)
    flat = np.zeros(len(b), bool)
    for k, level in G.flat.items():
        flat |= (b == k) & (V[k] >= level * (1 - 1e-9))
    i = np.flatnonzero(flat & fin)
    if i.size:
        W = V[:, i].copy()
        W[G.costly] = np.inf
        c = np.argmin(W, axis=0)
        v = W[c, np.arange(i.size)]
        p = P[i]
        g = np.hypot(G(p + [STEP_H, 0.0], c) - v, G(p + [0.0, STEP_H], c) - v) / STEP_H
        with np.errstate(invalid="ignore"):
            near = np.abs(v) <= tol * g
        b[i[near]] = c[near]
    _nearest_zero(G, P, V, b, fin, tol)
    return np.where(fin, b, -1)


def _nearest_zero(G, P, V, b, fin, tol: float) -> None:
    """Where the smallest part ``b`` (``V``: every part at ``P``) lies farther than ``tol`` from its zero by its
    own slope (flat beside a saddle, where its value is small far from its zero) and another part lies within
    ``tol`` of its own, ``b`` is set to the part nearest its zero (value over slope): the outline's vertex lies on
    that part's zero. 56/63 z0 25 internal at tol 1e-5: beside interference.1's saddle at (1, 1) it is below
    4e-7 across the whole strip between its wedge and exit jamming, whose zero the vertex lies on (5e-7 off; by
    interference.1's slope 5.7 tol): both ends of the cut across the strip read interference.1 and the cut
    was not carried to the strip's end, where the two cross."""
    i = np.flatnonzero(fin & ~np.isin(b, G.costly))
    if not i.size:
        return
    p, c = P[i], b[i]
    v = V[c, i]
    g = np.hypot(G(p + [STEP_H, 0.0], c) - v, G(p + [0.0, STEP_H], c) - v) / STEP_H
    with np.errstate(invalid="ignore"):
        far = ~(np.abs(v) <= tol * g)
    i = i[far]
    if not i.size:
        return
    p, W = P[i], V[:, i]
    S = np.hypot(G.many(p + [STEP_H, 0.0]) - W, G.many(p + [0.0, STEP_H]) - W) / STEP_H
    with np.errstate(invalid="ignore", divide="ignore"):
        dist = np.where(np.isfinite(S) & (S > 0), np.abs(W) / S, np.inf)
    dist[G.costly] = np.inf
    c = np.argmin(dist, axis=0)
    near = dist[c, np.arange(i.size)] <= tol
    b[i[near]] = c[near]
