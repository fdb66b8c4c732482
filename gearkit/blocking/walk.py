"""The region's edge walked from one end of a cut of its outline to the other (for :mod:`~gearkit.blocking.tips`).

Where a chord of the region's outline cuts across a part of the region that no grid node sees, and its two ends bind
one part whose zero line from end to end is no wedge's two sides (their meeting is no corner the outline can take:
the region goes on through the saddle's neck between them), the edge between the chord's ends is found by walking it:
from the chord's start along the zero line of the part it binds, the region on the left, each step predicted along
the line's tangent and corrected back onto it by Newton's steps along the gradient; where another part falls below
zero over a step the edge turns a corner, solved as the crossing of the two lines
(:func:`~gearkit.blocking.apex.crossings`), and the walk goes on along the other part's line, until it passes the
chord's end. Steps shorten where the line turns (at most ``TURN`` a step) and lengthen along it; the walk gives up
where a part is undefined (no pair) or costly, where it is longer than ``reach`` or takes more than ``STEPS`` steps.

29/37 at tol 1e-5: interference.2's saddle at (-1, 1) leaves a neck 1e-4 wide between its two negative wedges,
through which the region goes on into a pocket 6e-4 wide and 5e-3 long, bounded by the wedges' far sides and
interference.1's line. The grid closed the outline across the neck (the chord's middle 6.6 tol from both tips) and
left the pocket out; walked, the outline goes round the upper wedge's tip, up its far side to interference.1's line,
down that to the lower wedge's far side and round its tip to the chord's end.

>>> import numpy as np
>>> def G(p, k):  # a disc of radius 1 (part 0) cut by the half-plane x2 <= 0.5 (part 1)
...     return np.where(np.asarray(k) == 0, 1.0 - np.hypot(p[:, 0], p[:, 1]), 0.5 - p[:, 1])
>>> G.size, G.costly = 2, []
>>> G.many = lambda p: np.vstack([G(p, np.zeros(len(p), int)), G(p, np.ones(len(p), int))])
>>> a, b = np.array([0.0, -1.0]), np.array([-1.0, 0.0])  # from a round to b, the region on the left
>>> path, parts = walk(G, a, b, 0, 1e-6, 10.0)
>>> corner = np.sqrt(0.75)
>>> bool(np.allclose(path[[0, -1]], [a, b])), sorted(set(parts.tolist()))
(True, [0, 1])
>>> bool(np.min(np.hypot(*(path - [corner, 0.5]).T)) < 1e-6), bool(np.min(np.hypot(*(path - [-corner, 0.5]).T)) < 1e-6)
(True, True)
"""
from __future__ import annotations

import numpy as np

from gearkit.blocking.apex import STEP_H, crossings, segment_distance, value_grad

__all__ = ["walk", "walk_sides"]

STEPS = 4000  #: most steps of a walk
TURN = 0.2  #: most turn of the line's tangent over one step (radians); a step turning more is halved
GROW = 1.5  #: a step taken with less than half that turn is followed by one this much longer
ONTO = 6  #: most Newton steps back onto the line after a predicted step
SHRINK = 1e-3  #: the walk gives up where its step falls below this fraction of tol


def _value_grad(G, p, k: int):
    """``G_k`` and its gradient at the point ``p`` (:func:`~gearkit.blocking.apex.value_grad`)."""
    f, g = value_grad(G, p[None], np.array([k]))
    return f[0], g[0]


def _onto(G, p, k: int, vtol: float):
    """``p`` moved onto ``G_k = 0`` by Newton's steps along the gradient (None where they do not reach it)."""
    for _ in range(ONTO):
        f, g = _value_grad(G, p, k)
        gg = float(g @ g)
        if not (np.isfinite(f) and gg > 0):
            return None
        p = p - f / gg * g
        if abs(f) <= vtol * np.sqrt(gg):
            return p
    return None


def _tangent(G, p, k: int):
    """The unit tangent of ``G_k = 0`` at ``p`` with ``G_k`` positive on its left (None where flat)."""
    _, g = _value_grad(G, p, k)
    n = float(np.hypot(*g))
    return np.array([g[1], -g[0]]) / n if np.isfinite(n) and n > 0 else None


def _distances(G, p):
    """Every part's value over its slope at ``p`` (its signed distance from its zero, infinite where it is flat; NaN
    where it is undefined)."""
    P = np.array([p, p + [STEP_H, 0.0], p + [0.0, STEP_H]])
    V = G.many(P)
    s = np.hypot(V[:, 1] - V[:, 0], V[:, 2] - V[:, 0]) / STEP_H
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(s > 0, V[:, 0] / s, np.sign(V[:, 0]) * np.inf)


def _passes(G, x, y, u, b, k: int, tol: float) -> bool:
    """True where the step ``x -> y`` along ``G_k = 0`` (tangent ``u`` at ``y``) passes ``b``: ``b`` within ``tol``
    of the step's chord or of the arc it cuts (its sagitta, at most a ``TURN / 4`` of its length), and the line's
    tangent at ``b`` within 60 degrees of ``u`` (not a branch running the other way beside it: a neck's far side)."""
    sag = tol + 0.25 * TURN * float(np.hypot(*(y - x)))
    if segment_distance(x[None], y[None], b[None])[0] > sag:
        return False
    v = _tangent(G, b, k)
    return v is not None and float(v @ u) > 0.5


def walk(G, a, b, k: int, tol: float, reach: float):
    """The region's edge from ``a`` to ``b`` (both on ``G_k = 0``; the region, where every part of ``G`` is >= 0, on
    the left): ``(path (n, 2), parts (n - 1,))``, the vertices from ``a`` to ``b`` and the part each chord runs along,
    its corners vertices; None where the walk does not reach ``b`` (see the module's notes). ``G``: the region's
    parts (:func:`~gearkit.blocking.parts.part_evaluator`)."""
    vtol = 0.25 * tol
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    x, part, h = a, int(k), max(0.25 * float(np.hypot(*(b - a))), tol)
    path, parts, length = [a], [], 0.0
    d0 = _distances(G, x)
    t = _tangent(G, x, part)
    for _ in range(STEPS):
        if t is None or h < SHRINK * tol or length > reach or np.any(np.isnan(d0)):
            return None
        y = _onto(G, x + h * t, part, vtol)
        u = _tangent(G, y, part) if y is not None else None
        if u is None or float(np.hypot(*(y - x))) > 2 * h or np.arccos(np.clip(t @ u, -1.0, 1.0)) > TURN:
            h *= 0.5
            continue
        d1 = _distances(G, y)
        below = np.flatnonzero(d1 < -vtol)
        below = below[below != part]
        if below.size:  # a corner over the step: the first part to fall below zero, its line crossed
            f = np.clip(d0[below] / np.where(d0[below] - d1[below] > 0, d0[below] - d1[below], np.inf), 0.0, 1.0)
            j = int(below[np.argmin(f)])
            if j in G.costly:
                return None
            T, ok = crossings(G, (x + float(np.min(f)) * (y - x))[None], np.array([part]), np.array([j]), vtol, h)
            if not ok[0] or float(np.hypot(*(T[0] - x))) > 2 * h:
                h *= 0.5
                continue
            y, u = T[0], _tangent(G, T[0], j)
            parts.append(part)
            part = j
            d1 = _distances(G, y)
        elif part == k and len(path) > 1 and _passes(G, x, y, u, b, k, tol):
            parts.append(part)
            path.append(b)
            return np.array(path), np.array(parts)
        else:
            parts.append(part)
        length += float(np.hypot(*(y - x)))
        path.append(y)
        h = h * GROW if t @ u > np.cos(0.5 * TURN) else h
        x, t, d0 = y, u, d1
    return None


def walk_sides(G, chords, tol: float, reach: float, trace):
    """The chords ``[((a, b), part)]`` (``a``, ``b`` tuples) walked (:func:`walk`): ``{(a, b): sides}``, each side
    ``(part, start, end)`` from one corner to the next, and ``{(part, start, end): points}``, each side traced through
    the walk's vertices by ``trace(G, [(part, points, slopes)])`` (see :func:`~gearkit.blocking.tips.carry_to_tips`;
    a side cut in two is none)."""
    walked, through = {}, []
    for ab, k in chords:
        w = walk(G, np.array(ab[0]), np.array(ab[1]), k, tol, reach)
        if w is None:
            continue
        path, part = w
        turn = np.r_[0, np.flatnonzero(np.diff(part)) + 1, len(part)]  # the corners: a side from one to the next
        sides = list(zip(turn[:-1], turn[1:]))
        walked[ab] = [(int(part[i]), path[i], path[j]) for i, j in sides]
        through += [(int(part[i]), path[i:j + 1], np.full(j + 1 - i, np.nan)) for i, j in sides]
    traced = trace(G, through) if through else []
    return walked, {(k, tuple(p[0]), tuple(p[-1])): p for k, p in traced}
