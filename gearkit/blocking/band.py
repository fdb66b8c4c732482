"""The band beside the no-pair area: the lines the grid cannot see there, traced on a graded lattice.

Marching squares (:mod:`gearkit.blocking.level`) mask every grid cell with a corner where ``F`` is
undefined, so nothing within about a cell of the no-pair area's edge is traced from the grid. Lines
that cross the edge are carried on to it (:mod:`gearkit.blocking.ends`); lines that meet it
tangentially (in (x1, x2): the margins reading the working pressure angle vary as the cube root of
the distance to the edge where inv alpha_w reaches 1e-9, those reading a tip at its base circle as
the square root) run along it inside that band (12/30: B1 and the tip-to-tip contact-ratio lines
stopped 0.04 to 0.16 short of the edge; an internal pair's band, where inv alpha_w reaches 1e-9
and where no shaper setting cuts the ring's tooth, was not traced at all: 46/49 B3 1.41 short).
Here the band is traced on its own lattice:

* **columns** x1 = const, ``BAND_COLUMNS`` per grid cell, where the edge crosses the column once
  between two grid rows (the edge is found there by multisection to round-off,
  :func:`~gearkit.blocking.edges.edge_point`);
* **rows** at distances from the edge along the column falling geometrically by ``BAND_RATIO``
  from beyond the masked cells down to round-off, and the edge itself: in these coordinates the
  lines meet the edge transversally, and two zeros of a column a few times apart in their distance
  from the edge lie in different lattice cells.

Where the edge is steep (from one grid row to the next within one grid column, steeper than about 45
degrees in grid units: 54/82's edge near x1 = -2.6 runs nearly parallel to x2, and columns x1 = const
did not cross the line along it, 485 tol short at tol 1e-3), the band is traced on the transposed
lattice instead: **rows** x2 = const, ``BAND_COLUMNS`` per grid cell, with the same distances from
the edge along each row. The rows' pieces are traced first; the columns' pieces are cut where they
enter the rows' band and joined to the rows' pieces there like to the grid's lines, and a column runs
through each end of the rows' band on the edge (a line along the edge across that end which meets
the edge before the next column is seen by the columns).

Every margin is evaluated at the lattice's nodes (one evaluation of the pair formulas for all);
marching squares in lattice coordinates give each line's topology there, and every vertex is
solved on its lattice edge (a segment in (x1, x2)) like the grid's. A sign change through a pole
of ``F`` is none: ``|F|`` does not fall there. The band's pieces are cut where they enter a cell the
grid traced (all corners defined) and joined to the grid line ending on that cell's edge, so each
zero is traced once; a piece lying wholly within ``SAME tol`` of a line traced already is that line
at this tol (two zero lines of one margin may run closer than that beside the edge).

>>> import numpy as np
>>> from gearkit.blocking.region import padded_grid
>>> e = 0.0137  # the edge: F = cbrt(y - e) - 0.1 (x + 1), undefined below it
>>> F = lambda p, k: np.where(p[:, 1] >= e, np.cbrt(p[:, 1] - e) - 0.1 * (p[:, 0] + 1.0), np.nan)
>>> xs, ys = padded_grid(np.linspace(-1.0, 1.0, 9), np.linspace(0.0, 1.0, 9))
>>> gx, gy = np.meshgrid(xs, ys)
>>> v = F(np.column_stack([gx.ravel(), gy.ravel()]), None).reshape(gx.shape)
>>> v[[0, -1], :] = v[:, [0, -1]] = np.nan  # the pad ring
>>> (k, q, g), = band_lines(F, [], [(xs, ys, v)], 1e-6)  # the grid saw nothing: all in the band
>>> bool(np.all(np.abs(q[:, 1] - e - (0.1 * (q[:, 0] + 1.0)) ** 3) < 1e-6)), round(float(q[:, 0].min()), 3)
(True, -1.0)
"""
from __future__ import annotations

import numpy as np

from gearkit.blocking.brackets import segment_roots
from gearkit.blocking.edges import edge_point
from gearkit.blocking.grid import edge_nodes
from gearkit.distances import distances_to_polyline

__all__ = ["band_lines", "once"]

BAND_COLUMNS = 4  #: lattice columns per grid cell
BAND_RATIO = 2 ** -0.5  #: ratio of the distances from the edge of successive lattice rows
BAND_OVER = 0.5  #: the lattice reaches this many grid rows past the masked cells
FLOOR = 1e-13  #: the nearest row (before the edge's own), relative to the window's diagonal
JUMP_FALL = 0.5  #: a solved vertex whose |F| is above this fraction of its edge's ends' is a pole or a jump
JOIN_REACH = 0.5  #: a band piece entering a traced cell joins a grid line's end within this many of its chord
SAME = 2.0  #: a band run within this many tol of a line of the same function traced already is dropped
ENTRY_SAMPLES = 64  #: samples of that chord locating where it enters the traced cell
THIN = 0.25  #: successive vertices of a band piece closer than this many tol are one (a line crossing the chord
#: between two columns' edge points, where the edge has a corner: the rows next to the edge all put theirs there)


def band_lines(F, lines, grids, tol: float, measure=(), many=None, band=None, carry=None) -> list:
    """``lines`` (``[(k, points, slopes)]``, the grid's pieces) with the band's pieces added and joined
    to them (see the module notes). ``many(points, ks) -> (len(ks), n)``: all functions ``ks`` at the
    same points (one evaluation); None: ``F`` once per function. ``band``: the curves traced in the
    band (None: all but ``measure``). ``carry``: a list to which the ends of the band's pieces that
    leave the lattice through its boundary off the no-pair edge are appended (``(k, point)``): the
    lattice's last row is a chord between the edge's points on two columns, or the window's frame
    on one of them, and a line may go on beside the edge below it (see
    :func:`~gearkit.blocking.ends.extend_ends`)."""
    ks = [k for k in range(len(grids)) if k not in measure and (band is None or k in band)
          and np.any(np.isnan(grids[k][2][1:-1, 1:-1])) and np.any(np.isfinite(grids[k][2]))]
    if not ks:
        return lines
    grid = grids[ks[0]]
    xs, ys, values = grid
    # the steep parts of the edge: rows x2 = const (the transposed lattice) where it runs within one
    # grid column from one grid row to the next; columns x1 = const elsewhere
    steep = _steep_cells(np.isfinite(values[1:-1, 1:-1]).T)
    FT = (lambda p, k: F(p[:, ::-1], k))
    rows = _lattice(FT, (ys, xs, values.T), ks[0], steep) if steep.any() else None
    # a column through each end of the rows' band on the edge: a line along the edge across it that meets
    # the edge before the next column is seen by the columns (its tail is no piece of a row)
    cols = _lattice(F, grid, ks[0], extra=_run_ends(rows))

    def traced(k, p):
        return _traced_cell(grids[k], p)

    for lattice, flip in ((rows, True), (cols, False)):
        if lattice is None:
            continue
        P, valid = lattice
        if flip:
            P = P[:, :, ::-1]
        nodes = P[valid]
        if many is None:
            V = np.stack([F(nodes, np.full(len(nodes), k)) for k in ks])
        else:
            V = np.asarray(many(nodes, ks), dtype=float)
        pieces = _pieces(F, P, valid, V, ks, tol, carry)
        lines = _merge(lines, pieces, traced, tol)
        if flip:  # the column lattice's pieces are cut where they enter the rows' band
            traced = _covering(traced, lattice)
    return lines


def _run_ends(lattice):
    """x1 of the edge points at the ends of each run of rows of the transposed ``lattice`` (none: ())."""
    if lattice is None:
        return ()
    P, valid = lattice
    ok = valid[-1]
    y, x = P[-1, ok, 0], P[-1, ok, 1]
    if y.size < 2:
        return ()
    o = np.argsort(y)
    y, x = y[o], x[o]
    step = np.diff(y)
    cut = np.flatnonzero(step > 1.5 * np.median(step))
    return tuple(float(v) for v in np.unique(np.concatenate([x[[0, -1]], x[cut], x[cut + 1]])))


def _crossings(fin):
    """Per column of ``fin`` ``[j, i]`` (defined nodes): ``(row below the one crossing, sense)`` where
    the defined area's edge crosses it once (sense 1: defined above), else None."""
    out = []
    for i in range(fin.shape[1]):
        t = np.flatnonzero(fin[1:, i] != fin[:-1, i])
        out.append((int(t[0]), 1 if fin[t[0] + 1, i] else -1) if t.size == 1 else None)
    return out


def _steep_cells(fin):
    """For ``fin`` ``[i, j]`` (the defined grid nodes, transposed: a row of it is a grid column), per
    cell between grid rows j, j + 1: True where the edge crosses both rows once, the same way round,
    within one grid column (steeper than about 45 degrees in grid units); gaps of one cell between
    such runs filled, runs of one cell dropped."""
    t = _crossings(fin)
    n = len(t) - 1
    s = np.array([t[j] is not None and t[j + 1] is not None and t[j][1] == t[j + 1][1] and t[j][0] == t[j + 1][0]
                  for j in range(n)], dtype=bool)
    fill = s.copy()
    fill[1:-1] |= s[:-2] & s[2:]
    ok = np.array([t[j] is not None and t[j + 1] is not None and t[j][1] == t[j + 1][1] for j in range(n)], dtype=bool)
    fill &= ok
    out = fill.copy()
    for lo, hi in _runs(fill):
        if hi - lo < 2:
            out[lo:hi] = False
    return out


def _covering(traced, lattice):
    """``traced`` widened by the transposed lattice ``(P, valid)`` (its coordinates swapped): a point
    is covered where it lies between two valid rows x2 = const of it, no farther from the edge along
    the row than the lattice's far end."""
    P, valid = lattice  # transposed: P[..., 0] is x2, rows of P run from the far end (0) to the edge (-1)
    ok = valid[0] & valid[-1]
    y = P[0, ok, 0]
    edge = P[-1, ok, 1]
    far = P[0, ok, 1]
    o = np.argsort(y)
    y, edge, far = y[o], edge[o], far[o]
    if y.size < 2:
        return traced
    step = np.diff(y)
    gap = step > 1.5 * np.median(step)  # two runs of rows: no band between them

    def covered(k, p):
        out = traced(k, p)
        j = np.searchsorted(y, p[:, 1]) - 1
        inside = (j >= 0) & (j < y.size - 1)
        j = np.clip(j, 0, y.size - 2)
        w = (p[:, 1] - y[j]) / (y[j + 1] - y[j])
        e = edge[j] + w * (edge[j + 1] - edge[j])
        f = far[j] + w * (far[j + 1] - far[j])
        t = (p[:, 0] - e) / (f - e)  # 0 at the edge, 1 at the far end
        return out | (inside & ~gap[j] & (t <= 1.0) & (t >= -1.0))
    return covered


def _lattice(F, grid, k0, cells=None, extra=()):
    """The band's lattice ``(P (rows, cols, 2), valid (rows, cols))``: columns where the edge crosses
    once between grid rows, the same way round in all of them (None where there is none); ``cells``
    (per cell between grid columns i, i + 1): only those (None: all); ``extra``: more columns x1 = these
    (in the cells used)."""
    xs, ys, values = grid
    X, Y = xs[1:-1], ys[1:-1]
    fin = np.isfinite(values[1:-1, 1:-1])  # [j, i] at (X[i], Y[j])
    nx = len(X)
    trans = _crossings(fin)  # per grid column: (row below the edge crossing, sense) or None
    use = np.ones(nx - 1, dtype=bool) if cells is None else np.asarray(cells, dtype=bool)
    near = np.zeros(nx, dtype=bool)
    near[:-1] |= use
    near[1:] |= use
    senses = {t[1] for t, u in zip(trans, near) if t is not None and u}
    if len(senses) != 1:
        return None
    sense = senses.pop()
    ny = len(Y)
    for i in range(nx):  # a column defined throughout: the edge lies past the window's frame there
        if trans[i] is None and fin[:, i].all():
            trans[i] = (-1 if sense > 0 else ny - 1, sense)
    m = BAND_COLUMNS
    cx, lo_row, hi_row = [], [], []
    for i in range(nx - 1):
        a, b = trans[i], trans[i + 1]
        if a is None or b is None or not use[i]:
            continue
        if a[0] in (-1, ny - 1) and b[0] in (-1, ny - 1):
            continue  # the edge past the frame on both sides
        j0, j1 = max(min(a[0], b[0]), 0), min(max(a[0], b[0]) + 1, ny - 1)
        here = [X[i] + (X[i + 1] - X[i]) * s / m for s in range(m + 1)]
        if i + 1 < nx - 1 and trans[i + 2] is not None and use[i + 1]:
            here.pop()  # the next cell's first column
        here += [x for x in extra if X[i] < x < X[i + 1] and min(abs(x - h) for h in here) > 1e-9 * (X[i + 1] - X[i])]
        for x in sorted(here):
            cx.append(x)
            lo_row.append(j0)
            hi_row.append(j1)
    if len(cx) < 2:
        return None
    cx, lo_row, hi_row = np.array(cx), np.array(lo_row), np.array(hi_row)
    inside = np.where(sense > 0, Y[hi_row], Y[lo_row])  # defined end of each column's bracket
    outside = np.where(sense > 0, Y[lo_row], Y[hi_row])
    A = np.column_stack([cx, inside])
    B = np.column_stack([cx, outside])
    fa = F(A, np.full(len(A), k0))
    fb = F(B, np.full(len(B), k0))
    ok = np.isfinite(fa) & np.isnan(fb)
    frame = np.isfinite(fa) & np.isfinite(fb) & (outside == (Y[0] if sense > 0 else Y[-1]))
    if np.count_nonzero(ok | frame) < 2:
        return None
    span = float(np.hypot(X[-1] - X[0], Y[-1] - Y[0]))
    E = np.full(A.shape, np.nan)
    if ok.any():
        E[ok] = edge_point(F, A[ok], B[ok], np.full(np.count_nonzero(ok), k0), span)
    E[frame] = B[frame]  # the edge past the frame: the band ends on it
    ok |= frame
    dy = Y[1] - Y[0]
    reach = float(np.max(np.abs(inside[ok] - E[ok, 1]))) + BAND_OVER * dy
    n = int(np.ceil(np.log(FLOOR * span / reach) / np.log(BAND_RATIO)))
    d = np.concatenate([reach * BAND_RATIO ** np.arange(n + 1), [0.0]])  # from the far row to the edge
    P = np.empty((d.size, cx.size, 2))
    P[:, :, 0] = cx[None, :]
    P[:, :, 1] = E[None, :, 1] + sense * d[:, None]
    valid = ok[None, :] & (P[:, :, 1] >= Y[0]) & (P[:, :, 1] <= Y[-1])
    valid[:, ~ok] = False
    P[~valid] = 0.0
    return P, valid


def _pieces(F, P, valid, V, ks, tol, carry=None):
    """Each function's zero lines on the lattice: ``[(k, points, slopes)]`` (vertices solved on their
    lattice edges to ``tol / 4``, split where a sign change is a pole or a jump); the ends leaving the
    lattice through its boundary where a pair exists beyond (not on the edge) appended to ``carry``."""
    import contourpy

    rows, cols = valid.shape
    ci, ri = np.arange(cols, dtype=float), np.arange(rows, dtype=float)
    raw = []  # (k, index-space vertices)
    for n, k in enumerate(ks):
        grid = np.full(valid.shape, np.nan)
        grid[valid] = V[n]
        if not (np.any(grid > 0) and np.any(grid < 0)):
            continue
        gen = contourpy.contour_generator(ci, ri, np.ma.masked_invalid(grid), name="serial", line_type="Separate")
        raw += [(k, n, np.asarray(p, float), grid) for p in gen.lines(0.0) if len(p) >= 2]
    if not raw:
        return []
    a, b, fa, fb, which = [], [], [], [], []
    for k, n, p, grid in raw:
        i0, j0, i1, j1 = edge_nodes(p, ci, ri)
        a.append(P[j0, i0]), b.append(P[j1, i1]), fa.append(grid[j0, i0]), fb.append(grid[j1, i1])
        which.append(np.full(len(p), k))
    A, B, FA, FB, W = (np.concatenate(v) for v in (a, b, fa, fb, which))
    ok = np.isfinite(FA) & np.isfinite(FB) & ((FA > 0) != (FB > 0))
    R = np.full(A.shape, np.nan)
    # an edge shorter than the vertices' accuracy is solved to round-off all the same: whether |F| falls
    # there (a zero) or not (a pole) is read off the root
    # (to a thousandth of its length, edges grouped by the decade of their length)
    length = np.hypot(*(B - A).T)
    decade = np.where(length > tol, np.inf, np.floor(np.log10(np.maximum(length, 1e-300))))
    for e in np.unique(decade[ok]):
        sel = ok & (decade == e)
        t = 0.25 * tol if np.isinf(e) else 1e-3 * 10.0 ** e
        R[sel] = segment_roots(F, A[sel], B[sel], FA[sel], FB[sel], t, W[sel])
    fr = np.full(len(A), np.nan)
    fr[ok] = np.abs(F(R[ok], W[ok]))
    with np.errstate(invalid="ignore"):
        good = ok & (fr <= JUMP_FALL * np.fmin(np.abs(FA), np.abs(FB)))
    again = np.flatnonzero(ok & ~good)  # |F| did not fall at a root solved to tol / 4: solved to round-off,
    if again.size:  # a zero beside the edge, where F varies as a root of the distance, falls there; a pole not
        R[again] = segment_roots(F, A[again], B[again], FA[again], FB[again], 1e-12 * float(length[again].min()),
                                 W[again])
        fr[again] = np.abs(F(R[again], W[again]))
        with np.errstate(invalid="ignore"):
            good[again] = fr[again] <= JUMP_FALL * np.fmin(np.abs(FA[again]), np.abs(FB[again]))
    slope = np.abs(FB - FA) / length
    out, at = [], 0
    for k, _, p, _ in raw:
        q, g, use = R[at:at + len(p)], slope[at:at + len(p)], good[at:at + len(p)]
        at += len(p)
        closed = np.array_equal(p[0], p[-1]) and use.all()
        for lo, hi in _runs(use):
            keep = _thin(q[lo:hi], THIN * tol)
            if keep.size >= 2:
                out.append((k, q[lo:hi][keep], g[lo:hi][keep], closed))
                if carry is not None and not closed:
                    carry += [(k, q[j]) for j, at_end in ((lo, lo == 0), (hi - 1, hi == len(p)))
                              if at_end and _off_lattice(p[j], rows, cols)]
    if carry:  # a vertex on the edge itself (undefined to round-off) ends its line there
        keep = np.isfinite(F(np.array([c[1] for c in carry]), np.array([c[0] for c in carry])))
        carry[:] = [c for c, kp in zip(carry, keep) if kp]
    return out


def _off_lattice(v, rows, cols) -> bool:
    """True when the index-space vertex ``v`` lies on the lattice's boundary between two nodes: its
    last row (the edge's row) or its first or last column."""
    i, j = v
    on_row = j == rows - 1 and i != round(i)
    on_side = (i == 0 or i == cols - 1) and j != round(j)
    return bool(on_row or on_side)


def _thin(q, close):
    """Indices of the vertices ``q`` kept: each farther than ``close`` from the one kept before it, the
    first and the last always (the last replacing the one before it where those two are close)."""
    keep = [0]
    for i in range(1, len(q)):
        if np.hypot(*(q[i] - q[keep[-1]])) > close:
            keep.append(i)
        elif i == len(q) - 1:
            if len(keep) > 1:
                keep[-1] = i
            else:
                keep.append(i)
    return np.array(keep)


def _runs(mask):
    """(start, stop) of the runs of True in ``mask``."""
    d = np.diff(np.concatenate([[False], mask, [False]]).astype(int))
    return list(zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1)))


def _traced_cell(grid, p):
    """True where the points ``p`` lie in a cell of ``grid`` with every corner defined (traced there)."""
    xs, ys, values = grid
    fin = np.isfinite(values)
    full = fin[:-1, :-1] & fin[1:, :-1] & fin[:-1, 1:] & fin[1:, 1:]
    i = np.clip(((p[:, 0] - xs[0]) // (xs[1] - xs[0])).astype(int), 0, len(xs) - 2)
    j = np.clip(((p[:, 1] - ys[0]) // (ys[1] - ys[0])).astype(int), 0, len(ys) - 2)
    return full[j, i]


def _merge(lines, pieces, traced, tol):
    """The grid's ``lines`` and the band's ``pieces``: each piece cut where it enters a traced cell,
    its part in the band joined to the grid line's end where it left: the open end of the same
    function nearest to the point where the chord crossing into the cell meets the cell's side, within
    ``JOIN_REACH`` of that chord's length (pairs matched nearest first, each end once)."""
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
            parts += [(k, q, g, lo, hi, False) for lo, hi in _runs(~cov)]
    # a run lying within SAME tol of a line traced already is that line (the longer runs first): two
    # zero lines closer than that are one at this tol (each zero within 2 tol of the one traced)
    kept = [(k, q) for k, q, _ in lines]
    keep = set()
    for n in sorted(range(len(parts)), key=lambda n: (parts[n][3] - parts[n][4], n)):
        k, q, _, lo, hi, _ = parts[n]
        near = [distances_to_polyline(q[lo:hi], r) for kk, r in kept if kk == k and len(r) >= 2]
        if near and np.all(np.min(near, axis=0) <= SAME * tol):
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
    return _assemble(lines, runs)


def _assemble(lines, runs):
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
