"""Corners of kinked zero sets beside a chord's end: where :func:`~gearkit.blocking.refinement.densify`'s
measure at a chord's middle does not look.

A zero set with a corner (the smallest of two margins, a tip cut down to what its tool leaves) is
traced by chords whose middles lie on the curve even where the corner, close to a chord's end, lies
farther than ``tol`` from it; the polyline turns sharply at that end. Such chords are measured a
quarter from the turning end as well.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.blocking.brackets import NearestBracket, segment_roots

__all__ = ["corner_splits", "uncut"]

CORNER_COS = math.cos(math.radians(20.0))  #: a polyline turning more than this at a vertex has a corner beside it
CORNER_FRACTION = 0.25  #: ... measured this far along its chords from the turning end
FLAT = 1e-2  #: a cut whose F at its quarters and middle agrees within this fraction is across a flat part


def corner_splits(F, lines, tol: float, curves, split: float, vtol: float, kept=()) -> set:
    """Chords of the kinked curves ``curves`` beside a sharp turn of their polyline (a corner of the
    zero set near the chord's end, which its middle does not see: a contact-ratio line turning where
    a tip reaches what its tool cuts) measured a quarter from the turning end, along the normal; one
    farther than ``split`` from its curve gets the zero found there as a vertex (in place,
    slopes too; the zero solved to ``vtol``; with a zero to each side, the one whose root is the nearer, not the
    secant's guess: 35/56 z0 22 internal at tol 1e-5, F = +3.5e-6 a quarter from a thin wedge's turn, its own
    side's zero beside it and the other side's 0.0029 off, read as the nearer; the outline crossed the wedge and
    back, and the loop it folded off was left out, 13.8 tol). ``lines``: ``[(k, points (n, 2), slopes (n,))]``,
    changed in place. ``kept``: chords ``(k, start, end)`` that densify found no zero across; one along which ``F`` is
    flat (at its quarters and middle, within ``FLAT``: the tip sweep's margin at its resolution, where it
    finds no penetration) crosses a flat strip of the region narrower than itself and is left alone as a cut
    (for :func:`~gearkit.blocking.region.reconnect`): a zero a quarter along it is the strip's edge beside
    its end, and a vertex there led the outline down the strip's edges and back round its loop (58/109 and
    55/102 internal at tol 1e-3: the region closed across the strip, 11.9 and 8.1 tol off). A cut along
    which ``F`` varies (a saddle's neck) is measured as any chord. Returns the indices of the polylines that
    changed.

    >>> import numpy as np
    >>> F = lambda p, k: np.minimum(p[:, 0] - 1.0, p[:, 1] - 0.0)  # zero set: an L with its corner at (1, 0)
    >>> lines = [(0, np.array([[1.0, 2.0], [1.0, 0.6], [2.0, 0.0], [3.0, 0.0]]), np.ones(4))]
    >>> corner_splits(F, lines, 0.01, {0}, 0.0075, 0.0025), len(lines[0][1])
    ({0}, 5)
    """
    rows = []  # (line, chord start index, fraction along the chord)
    cuts = {(tuple(a), tuple(b)) for _, a, b in kept}
    for n, (k, p, _) in enumerate(lines):
        if k not in curves or len(p) < 3:
            continue
        d = np.diff(p, axis=0)
        L = np.hypot(d[:, 0], d[:, 1])
        u = d / np.maximum(L, 1e-300)[:, None]
        turn = np.einsum("ij,ij->i", u[:-1], u[1:]) < CORNER_COS  # at vertex i + 1
        long = L > 4 * tol
        for i in np.flatnonzero(turn):  # chord i ends at the turn, chord i + 1 starts there
            if long[i]:
                rows.append((n, i, 1.0 - CORNER_FRACTION))
            if long[i + 1]:
                rows.append((n, i + 1, CORNER_FRACTION))
    if rows and cuts:  # a cut along which F is flat crosses a flat part of the region: left alone
        cut = [r for r, (n, i, _) in enumerate(rows) if (tuple(lines[n][1][i]), tuple(lines[n][1][i + 1])) in cuts]
        if cut:
            a = np.array([lines[rows[r][0]][1][rows[r][1]] for r in cut])
            b = np.array([lines[rows[r][0]][1][rows[r][1] + 1] for r in cut])
            t = np.array([CORNER_FRACTION, 0.5, 1.0 - CORNER_FRACTION])
            v = F((a[:, None] + t[None, :, None] * (b - a)[:, None]).reshape(-1, 2),
                  np.repeat([lines[rows[r][0]][0] for r in cut], t.size)).reshape(-1, t.size)
            with np.errstate(invalid="ignore"):
                flat = np.ptp(v, axis=1) <= FLAT * np.abs(v).min(axis=1)
            drop = {cut[j] for j in np.flatnonzero(flat)}
            rows = [row for r, row in enumerate(rows) if r not in drop]
    if not rows:
        return set()
    A = np.array([lines[n][1][i] for n, i, _ in rows])
    B = np.array([lines[n][1][i + 1] for n, i, _ in rows])
    t = np.array([f for _, _, f in rows])
    which = np.array([lines[n][0] for n, _, _ in rows])
    d = B - A
    L = np.hypot(d[:, 0], d[:, 1])
    nrm = np.column_stack([-d[:, 1], d[:, 0]]) / L[:, None]
    P = A + t[:, None] * d
    fp = F(P, which)
    best = NearestBracket(P, fp)
    sides = []
    for sgn in (1.0, -1.0):
        end = P + sgn * 0.5 * L[:, None] * nrm
        sides.append((end, F(end, which)))
        best.consider(np.arange(len(rows)), P, fp, *sides[-1])
    best.nearer(F, sides, which, vtol)  # a zero to each side: the nearer root (not the secant's guess)
    found = np.flatnonzero(best.have)
    if not found.size:
        return set()
    root = segment_roots(F, best.lo[found], best.end[found], best.flo[found], best.fe[found],
                         vtol, which[found])
    dev = np.abs(np.einsum("ij,ij->i", root - P[found], nrm[found]))
    far = dev > split
    inserts = {}
    for r, q, dv in zip(found[far], root[far], dev[far]):
        n, i, _ = rows[r]
        if np.min(np.hypot(*(lines[n][1] - q).T)) <= vtol:  # a vertex of the polyline already (31/66's
            continue  # region: the tip of a wedge it passes elsewhere, put again and again, without end)
        inserts.setdefault(n, {})[i] = (q, abs(fp[r]) / dv)
    for n, at in inserts.items():
        k, p, g = lines[n]
        for i in sorted(at, reverse=True):  # from the end: earlier indices stay valid
            q, gq = at[i]
            p = np.insert(p, i + 1, q, axis=0)
            g = np.insert(g, i + 1, gq)
        lines[n] = (k, p, g)
    return set(inserts)


def uncut(lines, kept) -> list:
    """``lines`` (``[(k, points, slopes)]``) with a mask of the chords to densify again after a corner split: all
    but the cuts of ``kept`` (chords ``(k, start, end)`` densify found no zero across), which stay as they are.
    Measured again against their loop's refined chords, a cut's far zero may no longer lie past them (31/66 at
    tol 1e-3: a cut across the strip above a wedge took the wedge's far side 0.029 off as its zero, the loop
    folded into the wedge and back and the region kept a triangle closed by a chord 3.95 tol off).

    >>> import numpy as np
    >>> p = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]])
    >>> uncut([(0, p, np.ones(3))], [(0, p[0], p[1])])[0][3]
    array([False,  True])
    """
    cut = {(k, tuple(a), tuple(b)) for k, a, b in (kept or ())}
    return [(k, p, g, np.array([(k, tuple(a), tuple(b)) not in cut for a, b in zip(p[:-1], p[1:])], bool))
            for k, p, g in lines]
