"""The band's pieces joined to the grid's lines (see :mod:`~gearkit.blocking.band`): each piece cut where
it enters a cell the grid traced (:func:`traced_cell`: all corners defined, not all of one sign) and joined
to the grid line ending on that cell's edge (:func:`join_pieces`, the polylines put together by
:func:`assemble`), so each zero is traced once; a run lying wholly within ``SAME tol`` of a line traced
already is that line at this tol, and so is an open line of the finished set (:func:`once`): two zero
lines of one margin may run closer than that beside the no-pair edge.

>>> import numpy as np
>>> lines = [(0, np.array([[0.0, 0.0], [1.0, 0.0]])), (0, np.array([[0.2, 1e-7], [0.8, 1e-7]])),
...          (1, np.array([[0.2, 1e-7], [0.8, 1e-7]]))]
>>> [(k, len(q)) for k, q in once(lines, 1e-6)]  # function 0's short piece is its long one at this tol
[(0, 2), (1, 2)]
"""
from __future__ import annotations

import numpy as np

from gearkit.blocking.grid import beside_chords, sign_cells, true_runs
from gearkit.distances import distances_to_polyline

__all__ = ["assemble", "join_pieces", "once", "traced_cell", "SAME"]

JOIN_REACH = 0.5  #: a band piece entering a traced cell joins a grid line's end within this many of its chord
SAME = 2.0  #: a band run within this many tol of a line of the same function traced already is dropped
ENTRY_SAMPLES = 64  #: samples of that chord locating where it enters the traced cell


def traced_cell(grid, p, specks=()):
    """True where the points ``p`` lie in a cell of ``grid`` with every corner defined and not all of one
    sign (traced there), but for the cells of the points ``specks`` (the grid's piece there dropped)."""
    xs, ys, values = grid
    fin = np.isfinite(values)
    full = fin[:-1, :-1] & fin[1:, :-1] & fin[:-1, 1:] & fin[1:, 1:] & sign_cells(values)

    def cell(q):
        i = np.clip(((q[:, 0] - xs[0]) // (xs[1] - xs[0])).astype(int), 0, len(xs) - 2)
        j = np.clip(((q[:, 1] - ys[0]) // (ys[1] - ys[0])).astype(int), 0, len(ys) - 2)
        return j, i
    if len(specks):
        full = full.copy()
        full[cell(np.asarray(specks, float))] = False
    return full[cell(p)]


def join_pieces(F, lines, pieces, traced, tol):
    """The grid's ``lines`` and the band's ``pieces``: each piece cut where it enters a traced cell,
    its part in the band joined to the grid line's end where it left: the open end of the same
    function nearest to the point where the chord crossing into the cell meets the cell's side, within
    ``JOIN_REACH`` of that chord's length (pairs matched nearest first, each end once). A run is
    dropped as a line traced already where each of its vertices lies within ``SAME tol`` of that line or
    on the curve one of its chords stands for (:func:`~gearkit.blocking.grid.beside_chords`: the grid's
    chords are not refined yet; 40/105 z0 33's contact ratio 1 at tol 1e-5 ran 6 tol beside a grid chord
    for a stretch in cells with an undefined corner, that run took the grid line's end and the band's
    run beyond it was left unjoined, a gap of 0.11)."""
    ends = {}  # (line, 0 | 1) -> point, of open grid lines
    for n, (k, q, _) in enumerate(lines):
        if len(q) >= 2 and not np.array_equal(q[0], q[-1]):
            ends[(n, 0)], ends[(n, 1)] = q[0], q[-1]
    runs = []  # [k, points, slopes, start link, end link, closed]
    offers = []  # (distance, run, slot, grid end)
    parts = []  # (k, piece's points, run's first and end vertex, closed)
    for k, q, g, closed in pieces:
        cov = traced(k, q)
        if closed and not cov.any():
            parts.append((k, q, g, 0, len(q), True))
        else:
            parts += [(k, q, g, lo, hi, False) for lo, hi in true_runs(~cov)]
    # a run lying within SAME tol of a line traced already is that line (the longer runs first): two
    # zero lines closer than that are one at this tol (each zero within 2 tol of the one traced)
    kept = [(k, q) for k, q, _ in lines]
    keep = set()
    for n in sorted(range(len(parts)), key=lambda n: (parts[n][3] - parts[n][4], n)):
        k, q, _, lo, hi, _ = parts[n]
        near = [distances_to_polyline(q[lo:hi], r) <= SAME * tol for kk, r in kept if kk == k and len(r) >= 2]
        if near and np.all(np.any(near, axis=0)):
            continue
        if near and np.all(np.any([beside_chords(F, k, q[lo:hi], r, SAME * tol) | m for (kk, r), m in
                                   zip([(kk, r) for kk, r in kept if kk == k and len(r) >= 2], near)], axis=0)):
            continue
        kept.append((k, q[lo:hi]))
        keep.add(n)
    for k, q, g, lo, hi, closed in (parts[n] for n in sorted(keep)):
        r = len(runs)
        runs.append([k, q[lo:hi], g[lo:hi], None, None, closed])
        if not closed:
            for slot, inner, outer in ((3, lo, lo - 1), (4, hi - 1, hi)):
                if outer < 0 or outer >= len(q):
                    continue
                u, c = q[inner], q[outer]
                t = np.linspace(0.0, 1.0, ENTRY_SAMPLES + 1)
                on = u[None] + t[:, None] * (c - u)[None]
                x = on[int(np.argmax(traced(k, on)))]  # where the chord enters the traced cells
                reach = JOIN_REACH * float(np.hypot(*(c - u)))
                for key, e in ends.items():
                    if lines[key[0]][0] == k:
                        dist = float(np.hypot(*(e - x)))
                        if dist <= reach:
                            offers.append((dist, r, slot, key))
    used = set()
    for _, r, slot, key in sorted(offers, key=lambda o: o[0]):
        if key in used or runs[r][slot] is not None:
            continue
        runs[r][slot] = key
        used.add(key)
    runs = [run for run in runs if len(run[1]) >= 2 or run[3] is not None or run[4] is not None]
    return assemble(lines, runs)


def assemble(lines, runs):
    """Polylines ``[(k, points, slopes)]`` from the grid's lines and the band's runs and their links."""
    link = {}
    nl = len(lines)
    for r, run in enumerate(runs):
        for s, end in ((3, 0), (4, 1)):
            if run[s] is not None:
                link[(nl + r, end)] = run[s]
                link[run[s]] = (nl + r, end)

    def piece(n):
        if n < nl:
            return lines[n][1], lines[n][2]
        return runs[n - nl][1], runs[n - nl][2]

    out, seen = [], set()
    total = nl + len(runs)
    for first_pass in (True, False):
        for n in range(total):
            if n in seen or (first_pass and (n, 0) in link and (n, 1) in link):
                continue
            start = 0 if (n, 0) not in link or not first_pass else 1
            P, G = [], []
            cur, enter = n, start
            while cur not in seen:
                seen.add(cur)
                p, g = piece(cur)
                if enter == 1:
                    p, g = p[::-1], g[::-1]
                P.append(p), G.append(g)
                nxt = link.get((cur, 1 - enter))
                if nxt is None:
                    break
                cur, enter = nxt
            p, g = np.concatenate(P), np.concatenate(G)
            if not first_pass or (n >= nl and runs[n - nl][5]):
                if not np.array_equal(p[0], p[-1]):
                    p, g = np.vstack([p, p[:1]]), np.append(g, g[0])
            k = lines[n][0] if n < nl else runs[n - nl][0]
            if len(p) >= 2:
                out.append((k, p, g))
    return out


def once(lines, tol: float, measure=()) -> list:
    """``lines`` (``[(k, points)]``) without the open components lying wholly within ``SAME tol`` of
    another of the same function (kept first: the longer): beside the no-pair area two zero lines
    of one margin may run closer than tol to each other and to the edge (12/30 sliding: legs 1e-5
    apart), and pieces of them traced from the grid, the band and the continuation are one line at
    that tol. Closed components and the curves ``measure`` are kept as they are."""
    order = sorted(range(len(lines)), key=lambda n: (-len(lines[n][1]), n))
    kept, drop = [], set()
    for n in order:
        k, q = lines[n][0], lines[n][1]
        if k not in measure and not np.array_equal(q[0], q[-1]):
            near = [distances_to_polyline(q, r) for kk, r in kept if kk == k]
            if near and np.all(np.min(near, axis=0) <= SAME * tol):
                drop.add(n)
                continue
        kept.append((k, q))
    return [(ln[0], ln[1]) for n, ln in enumerate(lines) if n not in drop]
