"""Where the grid cut a traced line short: continuation to a saddle, or to the no-pair edge it crosses.

Marching squares cut a crossing of two branches of a zero set (a saddle of ``F``) inside its grid
cell, and the chords that cross the cell find no zero across them: the four arms stop short of
the saddle (12/30: interference.1 up to 6e-3 short of its saddle at (x1, x2) = (1, -1)). The grid
also masks every cell with a corner in the no-pair area, so a line that runs into that area's
edge ends up to a cell short of it (12/30: pointing.1 and gear 1's tip-thickness lines 0.07 to
0.13 short of the edge where gear 2's tip meets its base circle). Here every open end inside the
window (not on its frame) is carried along its line by predictor-corrector continuation; an end
beside the no-pair area only when its line runs clear of the area (``F`` defined along its tangent for
``EDGE_REACH`` cells) or crosses the edge (:func:`~gearkit.blocking.edges.crossing_ends`:
its tangent meets the edge within ``EDGE_REACH`` cells at more than ``EDGE_DEG`` to it, ``F`` is regular
there, and the front gets no farther than ``EDGE_BUDGET`` times that distance). A margin that varies as the
cube or square root of the distance to the edge (those reading the working pressure angle, or a
tip at its base circle) has lines that meet the edge tangentially, along it for up to the whole
window: those ends are not carried on here (the band beside the edge is traced on its own lattice,
:mod:`~gearkit.blocking.band`), but for those where a band piece left its lattice beside the edge
(through its last row, a chord between two columns' edge points or the frame) and those of a chord
:func:`~gearkit.blocking.refinement.densify` cut (from one side of a strip to the other: 46/49's interference.1,
two thin wedges meeting at a saddle at (1, 1), whose arms ended 0.02 to 0.04 short of it beside the edge,
tangents away from it; such a front's first step is no longer than the cut chord): such a front follows
its line along the edge (a prediction past it moved back onto it along the normal) to where it ends.
How a front steps, where it stops and which fronts join: :mod:`~gearkit.blocking.fronts`. The joined
lines' new chords are then refined to ``tol`` like the others (:func:`~gearkit.blocking.refinement.densify`).
"""
from __future__ import annotations

import numpy as np

from gearkit.blocking.edges import EDGE_REACH, crossing_ends
from gearkit.blocking.fronts import run_fronts, start_fronts

__all__ = ["extend_ends", "join_ends"]

MAX_STEP_CELLS = 2.0  #: longest step, in grid cell diagonals (the chords are refined afterwards)
CLEAR_SAMPLES = 16  #: samples of an end's tangent telling a line clear of the no-pair area
JOIN_REACH = 2.0  #: open ends of one curve this many tol apart, off the frame and clear of the no-pair area, join


def extend_ends(F, lines, grids, tol, measure=(), carry=()):
    """Carry every open end of ``lines`` (``[(k, points, slopes)]``, the curves ``measure`` aside)
    that lies inside the window, off its frame and away from the undefined area, on along its line
    (see the module notes); so too the ends ``carry`` (``(k, point, first step)``: where the band's
    lattice ended a line beside the edge, :func:`~gearkit.blocking.band.band_lines`, step inf; the ends
    of a chord :func:`~gearkit.blocking.refinement.densify` cut, its length), no farther than ``EDGE_REACH``
    grid cells. Returns ``[(k, points, slopes, todo)]``: ``todo`` marks the chords to refine (the new
    ones).

    >>> import numpy as np
    >>> F = lambda p, k: p[:, 0] ** 2 - p[:, 1] ** 2 + 1e-4  # branches y = +-sqrt(x^2 + 1e-4)
    >>> xs = ys = np.linspace(-1.1, 1.1, 5)  # a padded grid: the window is [-0.55, 0.55]^2
    >>> y = lambda x: np.sqrt(x * x + 1e-4)
    >>> arms = [(0, np.array([[a, s * y(a)], [b, s * y(b)]]), np.full(2, np.nan))
    ...         for s in (1, -1) for a, b in ((-0.55, -0.3), (0.3, 0.55))]  # cut 0.3 short of the saddle
    >>> out = extend_ends(F, arms, [(xs, ys, np.zeros((5, 5)))], 1e-6)
    >>> [bool(np.all(p[:, 1] * p[0, 1] > 0)) for _, p, _, _ in out]  # joined: one branch each
    [True, True]
    """
    lined = [k for k in range(len(grids)) if k not in measure]
    if not lined:
        return [(k, p, g, np.zeros(len(p) - 1, bool)) for k, p, g in lines]
    xs, ys = grids[lined[0]][0], grids[lined[0]][1]
    lo = np.array([xs[1], ys[1]])
    hi = np.array([xs[-2], ys[-2]])
    span = float(np.hypot(*(hi - lo)))
    cell = float(np.hypot(xs[2] - xs[1], ys[2] - ys[1]))
    vtol = tol / 4
    eps = max(vtol, 1e-9 * span)
    recs = [[k, np.asarray(p, float), np.asarray(g, float), [], []] for k, p, g in lines]
    starts, edge_ends = [], []
    for r, (k, p, g, _, _) in enumerate(recs):
        if k in measure or len(p) < 2 or np.array_equal(p[0], p[-1]):
            continue
        for end, a, b in ((0, p[0], p[1]), (1, p[-1], p[-2])):
            if np.any(np.abs(a - lo) <= 1e-12) or np.any(np.abs(a - hi) <= 1e-12):
                continue  # on the window's frame
            i = int((a[0] - xs[0]) // (xs[1] - xs[0]))
            j = int((a[1] - ys[0]) // (ys[1] - ys[0]))
            t = (a - b) / np.hypot(*(a - b))
            if not np.all(np.isfinite(grids[k][2][max(j - 1, 0):j + 3, max(i - 1, 0):i + 3])):
                edge_ends.append((r, end, a, t))  # beside the no-pair area: carried on only into its edge
                continue
            starts.append((r, end, a, t))
    into = crossing_ends(F, edge_ends, [recs[e[0]][0] for e in edge_ends], EDGE_REACH * cell, span)
    starts += into
    taken = {(e[0], e[1]) for e in into}
    # a band end marked to carry on: the line's end within tol of it (the band's run there may have been
    # the grid's line already, whose end was solved on the grid's edge: 47/79's interference.1 on the row
    # x2 = 2.875 under the window's top frame, 0.125 short of it)
    starts += [e + (EDGE_REACH * cell,) for e in edge_ends
               if (e[0], e[1]) not in taken and any(c[0] == recs[e[0]][0] and np.hypot(*(c[1] - e[2])) <= tol
                                                    for c in carry)]
    # an end beside the area whose line runs clear of it: F defined along its tangent for EDGE_REACH cells
    # (43/52 z0 21's interference.1: two thin wedges meeting at a saddle 0.12 from the edge, their right arms cut
    # a cell short of it by the grid, tangents 10 degrees off the edge and clear of it: 590 tol at 1e-5)
    done = taken | {(e[0], e[1]) for e in starts}
    rest = [e for e in edge_ends if (e[0], e[1]) not in done]
    if rest:
        t = np.linspace(0.0, 1.0, CLEAR_SAMPLES + 1)[1:]
        Q = np.concatenate([e[2][None] + EDGE_REACH * cell * t[:, None] * e[3][None] for e in rest])
        v = F(Q, np.repeat([recs[e[0]][0] for e in rest], len(t))).reshape(len(rest), len(t))
        starts += [e + (EDGE_REACH * cell,) for e, ok in zip(rest, np.all(np.isfinite(v), axis=1)) if ok]
    # an end of a chord cut across a strip (densify) starts with a step no longer than that chord: a strip
    # narrowing to a saddle, whose other branches run on nearly straight beyond it (46/49's interference.1
    # at (1, 1)): a first step of two cells passed the saddle onto them and stopped there
    first = {}
    for c in carry:
        if np.isfinite(c[2]):
            for n, e in enumerate(starts):
                if c[0] == recs[e[0]][0] and np.hypot(*(c[1] - e[2])) <= tol:
                    first[n] = min(first.get(n, np.inf), c[2])
    front, joins = [], []
    geo = (span, vtol, MAX_STEP_CELLS * cell, lo, hi, tol)
    new = start_fronts(F, starts, recs, eps, geo[2])
    for n, h in first.items():
        new[n][5] = min(new[n][5], max(h, vtol))
    run_fronts(F, front, new, recs, joins, geo)
    return _assemble(recs, joins)


def _assemble(recs, joins):
    """Polylines from the records (points, the points added at each end) and the joins."""
    def full(r):
        k, p, g, head, tail = recs[r]
        pts = [np.array(head[::-1]).reshape(-1, 2), p, np.array(tail).reshape(-1, 2)]
        gs = [np.full(len(head), np.nan), g, np.full(len(tail), np.nan)]
        todo = np.concatenate([np.ones(len(head), bool), np.zeros(max(len(p) - 1, 0), bool),
                               np.ones(len(tail), bool)])
        if len(p) == 1:  # a seed: every chord new
            todo[:] = True
        return np.concatenate(pts), np.concatenate(gs), todo

    link = {}
    for a, b in joins:
        link[a], link[b] = b, a
    seen, out = set(), []
    order = list(range(len(recs)))
    # chains start at an unlinked end; what is left after them are closed loops
    for first_pass in (True, False):
        for r in order:
            if r in seen:
                continue
            if first_pass and (r, 0) in link and (r, 1) in link:
                continue
            start_end = 0 if (r, 0) not in link else 1
            if first_pass is False:
                start_end = 0
            P, G, T = [], [], []
            cur, enter = r, start_end
            while cur not in seen:
                seen.add(cur)
                p, g, t = full(cur)
                if enter == 1:
                    p, g, t = p[::-1], g[::-1], t[::-1]
                if P:
                    T.append(np.ones(1, bool))  # the joining chord
                P.append(p), G.append(g), T.append(t)
                nxt = link.get((cur, 1 - enter))
                if nxt is None:
                    break
                cur, enter = nxt
            p, g, t = np.concatenate(P), np.concatenate(G), np.concatenate(T)
            if not first_pass:  # closed: back to the first vertex
                p, g, t = np.vstack([p, p[:1]]), np.append(g, g[0]), np.append(t, True)
            if len(p) >= 2:
                out.append((recs[r][0], p, g, t))
    return out


def join_ends(F, lines, curves, frame, tol: float) -> list:
    """``lines`` (``[(k, points, slopes)]``) with the open ends of the curves ``curves`` that lie within
    ``JOIN_REACH tol`` of each other joined, nearest first (two lines become one, a line's own two ends close
    it): ends more than ``JOIN_REACH tol`` inside the window ``frame`` (x1 min, x1 max, x2 min, x2 max) with
    ``F`` defined all round them at that distance. Fronts carried from the two ends of a chord cut across a
    saddle's neck stop on each side of it where they meet the line through it (35/61's interference.2 at tol
    3e-4: 0.94 tol apart).

    >>> import numpy as np
    >>> F = lambda p, k: p[:, 1]  # the line x2 = 0, traced in two pieces 1.5 tol apart
    >>> a, b = np.array([[0.0, 0.0], [0.5, 0.0]]), np.array([[0.5015, 0.0], [1.0, 0.0]])
    >>> out = join_ends(F, [(0, a, np.ones(2)), (0, b, np.ones(2))], {0}, (-1.0, 2.0, -1.0, 1.0), 1e-3)
    >>> len(out), len(out[0][1])
    (1, 4)
    """
    ring = JOIN_REACH * tol * np.column_stack([np.cos(np.arange(8) * np.pi / 4), np.sin(np.arange(8) * np.pi / 4)])
    out = [list(ln) for ln in lines]
    while True:  # the nearest two ends first, the ends read again after each join
        ends = []  # (point, line, which end)
        for n, (k, q, _) in enumerate(out):
            if k not in curves or len(q) < 2 or np.array_equal(q[0], q[-1]):
                continue
            for e, p in ((0, q[0]), (1, q[-1])):
                inside = min(p[0] - frame[0], frame[1] - p[0], p[1] - frame[2], frame[3] - p[1]) > JOIN_REACH * tol
                if inside and np.all(np.isfinite(F(p + ring, np.full(len(ring), k)))):
                    ends.append((p, n, e))
        pairs = [(float(np.hypot(*(a[0] - b[0]))), i, j) for i, a in enumerate(ends) for j, b in enumerate(ends)
                 if i < j and out[a[1]][0] == out[b[1]][0]]
        if not pairs or min(pairs)[0] > JOIN_REACH * tol:
            return [tuple(ln) for ln in out]
        _, i, j = min(pairs)
        (_, n1, e1), (_, n2, e2) = ends[i], ends[j]
        if n1 == n2:  # the line's own two ends: closed
            out[n1][1] = np.vstack([out[n1][1], out[n1][1][:1]])
            out[n1][2] = np.append(out[n1][2], out[n1][2][0])
            continue
        q1, g1 = (out[n1][1], out[n1][2]) if e1 == 1 else (out[n1][1][::-1], out[n1][2][::-1])
        q2, g2 = (out[n2][1], out[n2][2]) if e2 == 0 else (out[n2][1][::-1], out[n2][2][::-1])
        out[n1][1], out[n1][2] = np.vstack([q1, q2]), np.concatenate([g1, g2])
        del out[n2]
