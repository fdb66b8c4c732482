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

:func:`carry_down` reads such a cut's normal on along the strip, on its curve's side (right of the chord where
``F > 0`` at its middle: the region lies on its loop's left), while ``F`` keeps the middle's level (within
:data:`~gearkit.blocking.corners.FLAT`) and the strip's edges stay within a chord to either side: the first
zero there is the strip's end. The cut is moved to half its length short of it, its new ends the zeros along
the chord's direction from there, on the strip's edges; the outline runs from each old end to its new one along
an edge, and the moved cut's normal meets the end within half the chord, where it is split as any chord.
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

__all__ = ["carry_down", "FLAT_REACH", "FLAT_STEP", "EDGE_REACH"]

FLAT_REACH = 8.0  #: a cut's normal is read along a flat strip this many chord lengths from its middle
FLAT_STEP = 0.5  #: ... at steps of this many chord lengths
EDGE_REACH = (0.25, 0.5, 0.625, 0.75, 1.0, 1.5)  #: the moved cut's ends: samples along the chord (x chord length)


def carry_down(F, A, B, which, tol: float):
    """For the region's chords ``A -> B`` (``(c, 2)``, curves ``which``, ``F`` positive on their left; no zero
    found across them) along whose normal, on the right, ``F`` keeps its middle's positive level (within
    ``FLAT``), with ``F <= 0`` a chord to either side, from the middle out to the last sample before its first
    sign change (at steps of ``FLAT_STEP`` chord lengths, up to ``FLAT_REACH``; the last may lie in the band
    inside the strip's end): the cut moved down the strip (see the module's notes). Returns
    ``(ok (c,) bool, end (c, 2), A2 (c, 2), B2 (c, 2))``: where ``ok``, the strip's end on the normal and the
    moved cut's ends (on the edges of ``A`` and ``B``), each solved to ``tol / 4``.

    >>> F = lambda p, k: np.minimum(np.minimum(1e-4, 1.0 - np.abs(p[:, 0])), 10.0 - p[:, 1])  # |x| < 1, y < 10
    >>> ok, end, a2, b2 = carry_down(F, np.array([[-1.0, 0.0]]), np.array([[1.0, 0.0]]), np.array([0]), 1e-6)
    >>> bool(ok[0]), end.round(6).tolist(), a2.round(6).tolist(), b2.round(6).tolist()
    (False, [[nan, nan]], [[nan, nan]], [[nan, nan]])
    >>> ok, end, a2, b2 = carry_down(F, np.array([[1.0, 0.0]]), np.array([[-1.0, 0.0]]), np.array([0]), 1e-6)
    >>> bool(ok[0]), end.round(6).tolist(), a2.round(6).tolist(), b2.round(6).tolist()
    (True, [[0.0, 10.0]], [[1.0, 9.0]], [[-1.0, 9.0]])
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
    s = FLAT_STEP * np.arange(1, int(round(FLAT_REACH / FLAT_STEP)) + 1)  # (samples,) in chord lengths
    P = m[:, None] + (s[None, :, None] * L[:, None, None]) * u[:, None]
    V = F(P.reshape(-1, 2), np.repeat(which, s.size)).reshape(c, s.size)
    with np.errstate(invalid="ignore"):
        level = np.isfinite(V) & (np.abs(V - f0[:, None]) <= FLAT * np.abs(f0)[:, None])
        change = ~(V > 0)  # a sign change, or undefined: no pair
    # a strip about as wide as the cut: its edges within a chord to either side of the way
    side = P[:, :, None] + (np.array([-1.0, 1.0])[None, None, :, None] * L[:, None, None, None]) * t[:, None, None]
    S = F(side.reshape(-1, 2), np.repeat(which, 2 * s.size)).reshape(c, s.size, 2)
    with np.errstate(invalid="ignore"):
        level &= np.all(~(S > 0), axis=2)
    j = np.argmax(change, axis=1)
    r = np.arange(c)
    # the way flat and narrow up to the sample before the last before the change (that one may lie in the band
    # inside the end, where the end's part is below the level)
    flat_way = np.array([bool(np.all(level[i, :max(j[i] - 1, 0)])) for i in range(c)])
    go = np.flatnonzero((f0 > 0) & change[r, j] & np.isfinite(V[r, j]) & (j > 0) & flat_way)
    if not go.size:
        return ok, end, A2, B2
    lo, hi = P[go, j[go] - 1], P[go, j[go]]
    end[go] = segment_roots(F, lo, hi, V[go, j[go] - 1], V[go, j[go]], vtol, which[go])
    D = np.einsum("ij,ij->i", end[go] - m[go], u[go])
    mid = m[go] + (D - 0.5 * L[go])[:, None] * u[go]  # the moved cut's middle, half a chord short of the end
    fm = F(mid, which[go])
    ends = []
    for sgn in (-1.0, 1.0):  # towards A's edge, then B's
        e = np.asarray(EDGE_REACH)
        Q = mid[:, None] + sgn * (e[None, :, None] * L[go][:, None, None]) * t[go][:, None]
        W = F(Q.reshape(-1, 2), np.repeat(which[go], e.size)).reshape(go.size, e.size)
        with np.errstate(invalid="ignore"):
            ch = np.isfinite(W) & (W <= 0)
        k = np.argmax(ch, axis=1)
        g = np.arange(go.size)
        have = ch[g, k] & np.all(np.isfinite(W) | (np.arange(e.size)[None] >= k[:, None]), axis=1)
        lo = np.where((k > 0)[:, None], Q[g, np.maximum(k - 1, 0)], mid)
        flo = np.where(k > 0, W[g, np.maximum(k - 1, 0)], fm)
        p = np.full((go.size, 2), np.nan)
        if have.any():
            p[have] = segment_roots(F, lo[have], Q[g, k][have], flo[have], W[g, k][have], vtol, which[go][have])
        ends.append(p)
    good = (fm > 0) & (D > L[go]) & np.isfinite(ends[0][:, 0]) & np.isfinite(ends[1][:, 0])
    ok[go[good]] = True
    A2[go[good]], B2[go[good]] = ends[0][good], ends[1][good]
    end[go[~good]] = np.nan
    return ok, end, A2, B2

