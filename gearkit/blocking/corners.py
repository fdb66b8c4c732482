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

__all__ = ["corner_splits", "uncut", "carry_corners"]

CORNER_COS = math.cos(math.radians(20.0))  #: a polyline turning more than this at a vertex has a corner beside it
CORNER_FRACTION = 0.25  #: ... measured this far along its chords from the turning end
FLAT = 1e-2  #: a cut whose F at its quarters and middle agrees within this fraction is across a flat part
WEDGE_STEPS, WEDGE_HALF, WEDGE_SAMPLES = 256, 2.0, 33  #: sections on from an acute corner (carry_corners): how many
#: at most (a quarter tol apart: 64 tol on; internal 12/53 z0 14's tip sweep at 1e-3 was closed 25 tol short, and
#: 64 sections stopped 9 tol short of its tip), their half length in tol, their samples
WEDGE_EVERY = 4  #: ... every fourth section's zeros kept (the sides a tol apart)
OBTUSE_COS = -0.5  #: the region's corners carried up to 120 degrees (carry_corners)
NARROW = 0.5  #: ... when the last run before the tip is at most this part of the widest (a wedge narrowing to it)


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


def carry_corners(F, lines, curves, tol: float, vtol: float, obtuse=()) -> list:
    """``lines`` (``[(k, points, slopes)]``) with each acute corner of the kinked curves ``curves`` (two chords
    less than 90 degrees apart) that closes a thin wedge of the zero set short of its tip carried to it: a
    chord across the wedge, which a grid cell wider than the wedge closed, leaves the tip out, and its
    middle lies within the wedge's width of both sides (internal 19/42 z0 19's tip sweep at tol 1e-3: closed
    2.9 tol short where the wedge is half a tol wide). Sections across the way on from the corner, a
    quarter tol apart (the first across its bisector, the rest across the way from the first section's
    middle), ``WEDGE_SAMPLES`` samples ``WEDGE_HALF`` tol either side: while one holds a run of the other sign
    than its two ends, the wedge goes on, the run's ends bracket its two sides (solved to ``vtol``) and the
    next section lies on from the run's middle; the tip is the zero between the last run's middle and the
    next section's. The corner is replaced by the sides' zeros (a tol apart, the side nearer the chord before it
    first) and the tip. A corner with no run beyond it (the tip itself), or a wedge wider than the sections or
    going on past the last, is left as it is, and so is a run that does not narrow to its tip (the last at most
    ``NARROW`` of the widest: one that widens on went through a saddle's neck into the sector beyond it);
    so are the slopes (NaN at the new vertices). The curves
    ``obtuse`` (the region's outline) have their corners up to 120 degrees carried too: the outline closed
    across a saddle's neck whose part beyond it no grid node sees (external 29/37 at tol 1e-3: a wedge
    of the region 5.5 tol long beyond the neck of interference.2's saddle at (-1, 1), the corner 111
    degrees); of two such corners next to each other (a square cut across a wedge) the first only.

    >>> import numpy as np
    >>> F = lambda p, k: np.abs(p[:, 1]) - 0.1 * (1.0 - p[:, 0])  # a wedge, its tip at (1, 0)
    >>> p = np.array([[0.0, 0.1], [0.996, 0.0], [0.0, -0.1]])  # closed 4 tol short (tol 1e-3)
    >>> q = carry_corners(F, [(0, p, np.ones(3))], {0}, 1e-3, 2.5e-4)[0][1]
    >>> bool(np.hypot(*(q[np.argmax(q[:, 0])] - [1.0, 0.0])) < 2.5e-4), bool(np.abs(F(q, 0)).max() <= 2.5e-4)
    (True, True)
    """
    rows = []  # (line, vertex, way on, whether the chord before it lies to the left of the way)
    for n, (k, p, _) in enumerate(lines):
        if k not in curves or len(p) < 3:
            continue
        a, b = p[:-2] - p[1:-1], p[2:] - p[1:-1]
        a = a / np.maximum(np.hypot(a[:, 0], a[:, 1]), 1e-300)[:, None]
        b = b / np.maximum(np.hypot(b[:, 0], b[:, 1]), 1e-300)[:, None]
        for i in np.flatnonzero(np.einsum("ij,ij->i", a, b) > (OBTUSE_COS if k in obtuse else 0.0)):
            m = -(a[i] + b[i]) / max(float(np.hypot(*(a[i] + b[i]))), 1e-300)
            rows.append((n, i + 1, m, float(np.dot(a[i], [-m[1], m[0]])) > 0.0))
    if not rows:
        return lines
    C = np.array([lines[n][1][i] for n, i, _, _ in rows])
    D = np.array([m for _, _, m, _ in rows])
    which = np.array([lines[n][0] for n, _, _, _ in rows])
    t = WEDGE_HALF * tol * np.linspace(-1.0, 1.0, WEDGE_SAMPLES)
    first = np.full_like(C, np.nan)
    runs = [[] for _ in rows]  # per corner: (left bracket, right bracket) of each section's run
    tip = [None] * len(rows)  # per corner: (inside point, outside point, values) bracketing the tip
    live = np.arange(len(rows))
    for _ in range(WEDGE_STEPS):
        if not live.size:
            break
        S = C[live] + 0.25 * tol * D[live]
        left = np.column_stack([-D[live, 1], D[live, 0]])
        Q = S[:, None, :] + t[None, :, None] * left[:, None, :]
        W = F(Q.reshape(-1, 2), np.repeat(which[live], t.size)).reshape(len(live), t.size)
        out = W[:, 0] > 0
        run = np.isfinite(W) & ((W > 0) != out[:, None])
        on = np.isfinite(W[:, 0]) & np.isfinite(W[:, -1]) & (out == (W[:, -1] > 0)) & run.any(axis=1)
        mid = t.size // 2
        for j in np.flatnonzero(~on):  # the wedge ended between the last run's middle and this section's
            r = live[j]
            if runs[r] and np.isfinite(W[j, mid]) and (W[j, mid] > 0) == out[j]:
                tip[r] = (C[r], Q[j, mid], W[j, mid])
        for j in np.flatnonzero(on):
            r = live[j]
            i = np.flatnonzero(run[j])
            lo, hi = i[0], i[-1]  # a run of several pieces (another branch beside it): its two ends, left alone
            if not run[j, lo:hi + 1].all():
                on[j] = False
                continue
            runs[r].append(((Q[j, lo - 1], Q[j, lo], W[j, lo - 1], W[j, lo]),
                            (Q[j, hi + 1], Q[j, hi], W[j, hi + 1], W[j, hi])))
            C[r] = Q[j, lo:hi + 1].mean(axis=0)
            if np.isnan(first[r, 0]):
                first[r] = C[r]
            way = C[r] - first[r]
            if np.hypot(*way) > 0.5 * tol:
                D[r] = way / np.hypot(*way)
        live = live[on]
    width = [np.array([np.hypot(*(lo[1] - hi[1])) for lo, hi in runs[r]]) for r in range(len(rows))]
    # a wedge narrows to its tip; a run that widens on is none (internal 58/109 z0 31's region at (1, 1): on
    # from a corner beside interference.1's saddle, through its neck into the region's sector beyond it)
    done = [r for r in range(len(rows)) if tip[r] is not None
            and width[r][-1] <= max(NARROW * width[r].max(), 0.25 * tol)]
    pair = {(rows[r][0], rows[r][1]) for r in done}
    done = [r for r in done if (rows[r][0], rows[r][1] - 1) not in pair]  # a square cut's second corner: left
    if not done:
        return lines
    brackets = [b for r in done for pair in runs[r] for b in pair] + [
        (tip[r][1], tip[r][0], tip[r][2], F(tip[r][0][None], which[r:r + 1])[0]) for r in done]
    ks = np.array([which[r] for r in done for _ in range(2 * len(runs[r]))] + [which[r] for r in done])
    zeros = segment_roots(F, np.array([b[0] for b in brackets]), np.array([b[1] for b in brackets]),
                          np.array([b[2] for b in brackets]), np.array([b[3] for b in brackets]), vtol, ks)
    out = [list(ln) for ln in lines]
    at = dict(zip(done, np.cumsum([0] + [2 * len(runs[r]) for r in done])))  # where each corner's zeros start
    ends = zeros[len(brackets) - len(done):]
    for r, end in sorted(zip(done, ends), key=lambda e: -rows[e[0]][1]):  # from the end: indices stay valid
        n, i, _, before_left = rows[r]
        z = zeros[at[r]:at[r] + 2 * len(runs[r])].reshape(-1, 2, 2)
        z = z[np.arange(len(z))[::-WEDGE_EVERY][::-1]]  # a tol apart, the last (next to the tip) kept
        near, far = (z[:, 1], z[:, 0]) if before_left else (z[:, 0], z[:, 1])  # each run: (right, left)
        p, g = out[n][1], out[n][2]
        new = np.vstack([near, end[None], far[::-1]])
        out[n][1] = np.vstack([p[:i], new, p[i + 1:]])
        out[n][2] = np.concatenate([g[:i], np.full(len(new), np.nan), g[i + 1:]])
    return [tuple(ln) for ln in out]
