"""A cut across a flat strip of the region carried down the strip to its end.

Inside an internal pair's region the tip sweep finds no penetration and its margin is its resolution
(:data:`~gearkit.pair.internal.SWEEP_RESOLUTION`): the region's function is flat there, at that level, but for
a band about ``level / slope`` wide inside its edge. A strip of the region narrower than a grid cell is seen by
the grid as a chain of diamonds, one about each node inside it, whose cuts across the strip are re-joined
(:func:`~gearkit.blocking.region.reconnect`). The strip's last cut pairs with none, and
:func:`~gearkit.blocking.refinement.densify` walks it on towards the strip's end only by splitting it where its
normal meets the strip's edges or its end: within twice the chord, about the strip's width. The grid's last
node in the strip may lie a cell from its end, many strip widths: 25/59 z0 35 internal at tol 1e-5, the last
cut 0.0055 long with the strip's end (exit jamming and trimming.plunge) 2.01 of its lengths beyond, the outline
closed across the strip 0.01 short of its end (273 tol off).

:func:`carry_down` reads such a cut's way on along the strip, on its curve's side (right of the chord where
``F > 0`` at its middle: the region lies on its loop's left), while ``F`` keeps the middle's level (within
:data:`~gearkit.blocking.corners.FLAT`) and the strip's edges stay within a chord to either side: the first
zero there is the strip's end. The way starts along the cut's normal and is aimed again (``AIM_ROUNDS`` times)
from the cut's middle at the strip's middle farther down, between its edges across the way at the last sample
before that zero: the grid's cut runs from a row to a column, at a slant to the strip, and its normal leaves the
strip through an edge (43/100 z0 18 internal at tol 1e-3: the strip running down to the window's lower edge, its
last cut's normal 14 degrees off it reached its left edge 0.015 above the frame, taken for the strip's end; the
outline closed across the strip short of the frame, 6.2 tol off, 631 at tol 1e-5). The cut is moved to half its
length short of the end, square to the way, its new ends the zeros across the way from there, on the strip's
edges; the outline runs from each old end to its new one along an edge, and the moved cut's normal meets the end
within half the chord, where it is split as any chord (the window's edge too: the strip's end on the frame).
densify does this only for the loops :func:`~gearkit.blocking.region.reconnect` refines once more, those still
holding a cut that paired with none (``down``), only where no other line of the region crosses the way
(densify's check of a far zero: a link's cut stays to be re-joined), and once for each cut: a wedge narrowing
to its tip is left to :mod:`~gearkit.blocking.tips` (23/89 z0 19 internal at tol 1e-5: its cut, moved down the
wedge round after round, left the loop passing along the wedge twice, 2388 tol off; carried to the tip, 0.50).
"""
from __future__ import annotations

import numpy as np

from gearkit.blocking.brackets import segment_roots
from gearkit.blocking.corners import FLAT

__all__ = ["carry_down", "FLAT_REACH", "FLAT_STEP", "EDGE_REACH", "AIM_ROUNDS"]

FLAT_REACH = 8.0  #: a cut's normal is read along a flat strip this many chord lengths from its middle
FLAT_STEP = 0.5  #: ... at steps of this many chord lengths
EDGE_REACH = (0.25, 0.5, 0.625, 0.75, 1.0, 1.5)  #: the moved cut's ends: samples along the chord (x chord length)
AIM_ROUNDS = 3  #: the way re-aimed at the strip's middle this many times (the cut lies across the strip at a slant)
AIM_COS = 0.5  #: ... each time by less than 60 degrees
SIDE = 0.1  #: the way's first zero within this fraction of the strip's width of an edge's line is on that edge
STRIP_COS = 0.94  #: ... where the strip's edges (from the cut's ends to across the way) run within 20 degrees


def carry_down(F, A, B, which, tol: float):
    """For the region's chords ``A -> B`` (``(c, 2)``, curves ``which``, ``F`` positive on their left; no zero
    found across them) along whose way down the strip, on the right, ``F`` keeps its middle's positive level (within
    ``FLAT``), with ``F <= 0`` a chord to either side, from the middle out to the last sample before its first
    sign change (at steps of ``FLAT_STEP`` chord lengths, up to ``FLAT_REACH``; the last may lie in the band
    inside the strip's end): the cut moved down the strip (see the module's notes), the way aimed again at the
    strip's middle farther down (``AIM_ROUNDS``, each turn within ``acos(AIM_COS)``). Returns
    ``(ok (c,) bool, end (c, 2), A2 (c, 2), B2 (c, 2))``: where ``ok``, the strip's end on the way and the
    moved cut's ends (square to the way, on the edges of ``A`` and ``B``), each solved to ``tol / 4``.

    >>> F = lambda p, k: np.minimum(np.minimum(1e-4, 1.0 - np.abs(p[:, 0])), 10.0 - p[:, 1])  # |x| < 1, y < 10
    >>> ok, end, a2, b2 = carry_down(F, np.array([[-1.0, 0.0]]), np.array([[1.0, 0.0]]), np.array([0]), 1e-6)
    >>> bool(ok[0]), end.round(6).tolist(), a2.round(6).tolist(), b2.round(6).tolist()
    (False, [[nan, nan]], [[nan, nan]], [[nan, nan]])
    >>> ok, end, a2, b2 = carry_down(F, np.array([[1.0, 0.0]]), np.array([[-1.0, 0.0]]), np.array([0]), 1e-6)
    >>> bool(ok[0]), end.round(6).tolist(), a2.round(6).tolist(), b2.round(6).tolist()
    (True, [[0.0, 10.0]], [[1.0, 9.0]], [[-1.0, 9.0]])

    A cut at a slant to the strip: its normal would leave the strip through its side at (-1, 4); the way is aimed
    down the strip's middle, and the moved cut lies square to it:

    >>> ok, end, a2, b2 = carry_down(F, np.array([[1.0, 0.25]]), np.array([[-1.0, -0.25]]), np.array([0]), 1e-6)
    >>> bool(ok[0]), end.round(6).tolist(), a2.round(6).tolist(), b2.round(6).tolist()
    (True, [[0.0, 10.0]], [[1.0, 8.969224]], [[-1.0, 8.969224]])
    """
    A, B, which = np.asarray(A, float), np.asarray(B, float), np.asarray(which)
    c = len(A)
    ok = np.zeros(c, bool)
    end, A2, B2 = (np.full((c, 2), np.nan) for _ in range(3))
    if not c:
        return ok, end, A2, B2
    vtol = 0.25 * tol
    d = B - A
    L = np.hypot(d[:, 0], d[:, 1])
    t = d / np.maximum(L, 1e-300)[:, None]
    u = np.column_stack([t[:, 1], -t[:, 0]])  # right of the chord
    m = 0.5 * (A + B)
    f0 = F(m, which)
    P, V, j, go = _walk(F, m, u, L, which, f0)
    if not go.size:
        return ok, end, A2, B2
    lo = P[go, j[go] - 1]
    end[go] = _first_zero(F, P, V, j, go, which, vtol)
    # a way that would move the cut to one of the strip's edges (its first zero on the line of one, more than a
    # chord off): aimed again from the cut's middle at the strip's middle farther down
    ea, eb = _edges(F, lo, u[go], L[go], which[go], vtol)
    e, width = end[go], np.hypot(*(eb - ea).T)
    with np.errstate(invalid="ignore", divide="ignore"):
        sided = np.fmin(_off_line(A[go], ea, e), _off_line(B[go], eb, e)) <= SIDE * width
    aim = go[sided & (np.einsum("ij,ij->i", e - m[go], u[go]) > L[go])]
    for _ in range(AIM_ROUNDS):
        if not aim.size:
            break
        ea, eb = _edges(F, P[aim, j[aim] - 1], u[aim], L[aim], which[aim], vtol)
        to, da, db = 0.5 * (ea + eb) - m[aim], ea - A[aim], eb - B[aim]
        with np.errstate(invalid="ignore", divide="ignore"):
            to, da, db = (v / np.hypot(v[:, 0], v[:, 1])[:, None] for v in (to, da, db))
            cos = np.einsum("ij,ij->i", to, u[aim])
            # a strip: its edges from the cut's ends run side by side (a wedge's or a corner's converge)
            turn = np.all(np.isfinite(to), axis=1) & (cos > AIM_COS) & (cos < 1.0 - 1e-12) \
                & (np.einsum("ij,ij->i", da, db) > STRIP_COS)
        u[aim[turn]], aim = to[turn], aim[turn]
        if not aim.size:
            break
        P, V, j, go = _walk(F, m, u, L, which, f0)
        if not go.size:
            return ok, end, A2, B2
        aim = aim[np.isin(aim, go)]
        end[:] = np.nan
        end[go] = _first_zero(F, P, V, j, go, which, vtol)
    D = np.einsum("ij,ij->i", end[go] - m[go], u[go])
    mid = m[go] + (D - 0.5 * L[go])[:, None] * u[go]  # the moved cut's middle, half a chord short of the end
    fm = F(mid, which[go])
    a2, b2 = _edges(F, mid, u[go], L[go], which[go], vtol, fm)
    good = (fm > 0) & (D > L[go]) & np.isfinite(a2[:, 0]) & np.isfinite(b2[:, 0])
    ok[go[good]] = True
    A2[go[good]], B2[go[good]] = a2[good], b2[good]
    end[go[~good]] = np.nan
    return ok, end, A2, B2


def _first_zero(F, P, V, j, go, which, vtol):
    """The ways ``go``'s first zeros, solved to ``vtol`` between the samples ``j - 1`` and ``j`` of :func:`_walk`."""
    return segment_roots(F, P[go, j[go] - 1], P[go, j[go]], V[go, j[go] - 1], V[go, j[go]], vtol, which[go])


def _off_line(P, Q, X):
    """Distance of ``X`` from the line through ``P`` and ``Q`` (rows)."""
    d = Q - P
    return np.abs(d[:, 0] * (X - P)[:, 1] - d[:, 1] * (X - P)[:, 0]) / np.hypot(d[:, 0], d[:, 1])


def _walk(F, m, u, L, which, f0):
    """The way from the middles ``m`` along ``u`` (at ``FLAT_STEP`` chord lengths up to ``FLAT_REACH``):
    ``(P (c, samples, 2), V (c, samples), j (c,), go)``, ``j`` the first sample where ``F`` changes sign, ``go`` the
    chords whose way keeps the middle's level (within ``FLAT``) with ``F <= 0`` a chord to either side of it up to
    the sample before the last before the change (that one may lie in the band inside the end, where the end's
    part is below the level)."""
    c = len(m)
    s = FLAT_STEP * np.arange(1, int(round(FLAT_REACH / FLAT_STEP)) + 1)  # (samples,) in chord lengths
    P = m[:, None] + (s[None, :, None] * L[:, None, None]) * u[:, None]
    V = F(P.reshape(-1, 2), np.repeat(which, s.size)).reshape(c, s.size)
    with np.errstate(invalid="ignore"):
        level = np.isfinite(V) & (np.abs(V - f0[:, None]) <= FLAT * np.abs(f0)[:, None])
        change = ~(V > 0)  # a sign change, or undefined: no pair
    t = np.column_stack([-u[:, 1], u[:, 0]])  # (the chord's direction, where u is its normal)
    side = P[:, :, None] + (np.array([-1.0, 1.0])[None, None, :, None] * L[:, None, None, None]) * t[:, None, None]
    S = F(side.reshape(-1, 2), np.repeat(which, 2 * s.size)).reshape(c, s.size, 2)
    with np.errstate(invalid="ignore"):
        level &= np.all(~(S > 0), axis=2)
    j = np.argmax(change, axis=1)
    r = np.arange(c)
    flat_way = np.array([bool(np.all(level[i, :max(j[i] - 1, 0)])) for i in range(c)])
    go = np.flatnonzero((f0 > 0) & change[r, j] & np.isfinite(V[r, j]) & (j > 0) & flat_way)
    return P, V, j, go


def _edges(F, Q0, u, L, which, vtol: float, f=None):
    """The strip's edges across the way ``u`` from the points ``Q0`` (``F`` there ``f``, or evaluated): the first
    zeros along ``-t`` and ``t`` (``t`` the way's left, as ``A -> B`` of the cut), sampled at ``EDGE_REACH`` chord
    lengths ``L`` and solved to ``vtol``; NaN where none is found."""
    t = np.column_stack([-u[:, 1], u[:, 0]])
    fm = F(Q0, which) if f is None else f
    ends = []
    for sgn in (-1.0, 1.0):  # towards A's edge, then B's
        e = np.asarray(EDGE_REACH)
        Q = Q0[:, None] + sgn * (e[None, :, None] * L[:, None, None]) * t[:, None]
        W = F(Q.reshape(-1, 2), np.repeat(which, e.size)).reshape(len(Q0), e.size)
        with np.errstate(invalid="ignore"):
            ch = np.isfinite(W) & (W <= 0)
        k = np.argmax(ch, axis=1)
        g = np.arange(len(Q0))
        have = ch[g, k] & np.all(np.isfinite(W) | (np.arange(e.size)[None] >= k[:, None]), axis=1) & (fm > 0)
        lo = np.where((k > 0)[:, None], Q[g, np.maximum(k - 1, 0)], Q0)
        flo = np.where(k > 0, W[g, np.maximum(k - 1, 0)], fm)
        p = np.full((len(Q0), 2), np.nan)
        if have.any():
            p[have] = segment_roots(F, lo[have], Q[g, k][have], flo[have], W[g, k][have], vtol, which[have])
        ends.append(p)
    return ends[0], ends[1]
