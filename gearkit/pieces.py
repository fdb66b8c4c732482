"""Pieces of a tooth boundary, and where a function of their points crosses a level.

A generated half tooth (:mod:`gearkit.boundary`) is a chain of :class:`Piece`: a labelled stretch
``[w0, w1]`` of an exact curve (an envelope branch, the tip circle :class:`CircleArc`, a rack's tip
:class:`TipLine`). :func:`crossings` finds where a function of their points (a polar angle, a radius,
a height) takes a value: sign changes on a grid, each refined to a root; :func:`crossings_many` runs
several such searches side by side, the pieces of one motion evaluated in one call each round.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.refine import evaluate_curves
from gearkit.roots import bracketed_roots
from gearkit.values import frozen

__all__ = ["CircleArc", "Piece", "TipLine", "crossings", "crossings_many", "linear_coords"]


@frozen
class CircleArc:
    """Arc of radius ``radius`` about the blank centre, polar angle from +y (towards +x)."""

    radius: float
    psi0: float
    psi1: float
    label: str = "tip"

    def __call__(self, w):
        psi = self.psi0 + np.asarray(w, dtype=float) * (self.psi1 - self.psi0)
        return np.stack([self.radius * np.sin(psi), self.radius * np.cos(psi)], -1)

    def turning(self, w):  # points, unit tangents, the tangent's angle -psi (linear): as Piece.turning
        psi = self.psi0 + np.asarray(w, dtype=float) * (self.psi1 - self.psi0)
        sin, cos = np.sin(psi), np.cos(psi)  # the points' own (as __call__ takes them), taken once
        return np.stack([self.radius * sin, self.radius * cos], -1), np.stack([cos, -sin], -1), -psi[..., None]


@frozen
class Piece:
    """A labelled piece of a tooth boundary: ``curve`` (a Branch or CircleArc) on ``[w0, w1]``."""

    label: str
    curve: object
    w0: float
    w1: float

    def __call__(self, t):
        return self.curve(self._curve_parameters(t))

    def turning(self, t):
        """Points, unit tangents and angle parts of the curve (its ``turning``; see ``span``), or None."""
        turning = getattr(self.curve, "turning", None)
        return None if turning is None else turning(self._curve_parameters(t))

    span = property(lambda self: getattr(self.curve, "span", None))  # a leg's turn from its parts (gearkit.chords)

    def _curve_parameters(self, t):
        t = np.asarray(t, dtype=float)
        if self.w1 == 1.0 and self.w0 == 0.0 and math.copysign(1.0, self.w0) == 1.0:
            # +0 + t 1 is t itself to the bit (+ 0.0: a -0 sums to +0 there too)
            return t + 0.0
        return self.w0 + t * (self.w1 - self.w0)

    @property
    def joint(self):
        """Pieces with one key are evaluated in one call (:meth:`together`): their curves' key, or None."""
        return getattr(self.curve, "joint", None)

    def together(self, pieces, ts):
        """Points of several pieces of this one's :attr:`joint` key at their parameters ``ts`` (one call)."""
        return self.curve.together([p.curve for p in pieces], [p._curve_parameters(t) for p, t in zip(pieces, ts)])

    def turning_together(self, pieces, ts):
        """:meth:`turning` of several pieces of this one's :attr:`joint` key (one call)."""
        return self.curve.turning_together([p.curve for p in pieces],
                                           [p._curve_parameters(t) for p, t in zip(pieces, ts)])

    def reversed(self) -> "Piece":
        return Piece(self.label, self.curve, self.w1, self.w0)


def _grids(pieces, n=48):
    """Each piece sampled at ``n`` parameters in its own direction (so junctions line up): [(w, points)]."""
    ws = [np.linspace(pc.w0, pc.w1, n) for pc in pieces]
    some = [k for k, pc in enumerate(pieces) if pc.w0 != pc.w1]
    points = dict(zip(some, evaluate_curves([pieces[k].curve for k in some], [ws[k] for k in some])))
    return [(w, points.get(k)) for k, w in enumerate(ws)]


def crossings(pieces, func, target, n=48, grids=None):
    """Refined parameters where ``func(points) = target`` along the pieces: [(piece index, w)].

    ``func`` maps ``(n, 2)`` points to ``(n,)`` values (a polar angle, a radius, a coordinate); every
    sign change on a grid of ``n`` parameters per piece is refined to a root. ``grids`` (one
    sampling of the pieces, as this module builds it) lets several searches share the sampling.
    """
    return crossings_many(pieces, [(func, target)], n, grids)[0]


def crossings_many(pieces, searches, n=48, grids=None):
    """:func:`crossings` of several searches ``[(func, target)]`` on one grid: a list per search. Every sign
    change of every search is refined to a root side by side (:func:`~gearkit.roots.bracketed_roots`: each
    round's points on all the pieces in one call where the pieces share their motion), so the roots are
    those each search finds alone."""
    grids = _grids(pieces, n) if grids is None else grids
    found, brackets, asked, values_of = [[] for _ in searches], [], [], {}
    for j, (func, target) in enumerate(searches):
        last = 0.0
        for k, (w, pts) in enumerate(grids):
            if pts is None:
                continue
            if (func, k) not in values_of:  # searches of one function (two levels of an angle) share its values
                values_of[func, k] = func(pts)
            g = values_of[func, k] - target
            if last * g[0] < 0:  # the sign flips exactly at the junction with the previous piece
                found[j].append((k, float(w[0]), None))
            last = float(g[-1])
            sgn = np.sign(g)
            for i in (sgn[:-1] * sgn[1:] < 0).nonzero()[0]:  # (flatnonzero's result, without its wrapping)
                found[j].append((k, None, len(brackets)))  # the root's place: filled in below
                brackets.append((float(w[i]), float(w[i + 1]), float(g[i]), float(g[i + 1])))
                asked.append((j, k))
            for i in (g == 0).nonzero()[0]:
                found[j].append((k, float(w[i]), None))

    def values(which, xs):
        points = evaluate_curves([pieces[asked[i][1]].curve for i in which], xs)
        return [searches[asked[i][0]][0](p) - searches[asked[i][0]][1] for i, p in zip(which, points)]

    roots = bracketed_roots(values, brackets) if brackets else []
    return [[(k, roots[b] if w is None else w) for k, w, b in hits] for hits in found]


def linear_coords(points):
    """Rack frame counterpart of :func:`~gearkit.curves.polar_from_y`: "radius" y (height) and "angle" x."""
    p = np.asarray(points, dtype=float)
    return p[..., 1], p[..., 0]


@frozen
class TipLine:
    """Tip of a rack tooth: the line y = ``height`` from x = ``x0`` to ``x1``."""

    height: float
    x0: float
    x1: float
    label: str = "tip"

    def __call__(self, w):
        x = self.x0 + np.asarray(w, dtype=float) * (self.x1 - self.x0)
        return np.stack([x, np.full_like(x, self.height)], -1)

    def turning(self, w):  # a line: a constant tangent
        return self(w), np.broadcast_to(np.array([1.0, 0.0]), np.shape(w) + (2,)), np.zeros(np.shape(w) + (1,))
