"""The band's lattice beside the no-pair area (see :mod:`~gearkit.blocking.band`): columns x1 = const
where the area's edge crosses them once between two grid rows, ``BAND_COLUMNS`` per grid cell, or
rows x2 = const where the edge is steep (the transposed problem); along each, nodes at distances from
the edge falling geometrically by ``BAND_RATIO`` from beyond the masked cells down to round-off, and
the edge itself (solved for to round-off, :func:`~gearkit.blocking.edges.edge_point`)."""
from __future__ import annotations

import numpy as np

from gearkit.blocking.edges import edge_point
from gearkit.blocking.grid import true_runs

__all__ = ["band_lattice", "dip_columns", "steep_cells", "covering", "run_ends", "crossings", "BAND_COLUMNS",
           "BAND_RATIO"]

BAND_COLUMNS = 4  #: lattice columns per grid cell
BAND_RATIO = 2 ** -0.5  #: ratio of the distances from the edge of successive lattice rows
BAND_OVER = 0.5  #: the lattice reaches this many grid rows past the masked cells
FLOOR = 1e-13  #: the nearest row (before the edge's own), relative to the window's diagonal
DIP_SAMPLES = 8  #: columns tried between two whose values on the edge may dip through zero between them


def run_ends(lattice):
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


def crossings(fin, sense=None):
    """Per column of ``fin`` ``[j, i]`` (defined nodes): ``(row below the one crossing, sense)`` where
    the defined area's edge crosses it once (sense 1: defined above; ``sense``: once that way round,
    crossings the other way aside), else None."""
    out = []
    for i in range(fin.shape[1]):
        t = np.flatnonzero(fin[1:, i] != fin[:-1, i])
        s = np.where(fin[t + 1, i], 1, -1)
        t, s = (t, s) if sense is None else (t[s == sense], s[s == sense])
        out.append((int(t[0]), int(s[0])) if t.size == 1 else None)
    return out


def steep_cells(fin, sense=None):
    """For ``fin`` ``[i, j]`` (the defined grid nodes, transposed: a row of it is a grid column), per
    cell between grid rows j, j + 1: True where the edge crosses both rows once, the same way round,
    within one grid column (steeper than about 45 degrees in grid units); gaps of one cell between
    such runs filled, runs of one cell dropped but at the window's frame (34/105's edge leaves through the
    top frame after one such cell, the frame's column crossing it twice: no column lattice there), and the
    cell at the frame beside a run taken where the edge crosses both its rows once, the same way round."""
    t = crossings(fin, sense)  # (``sense``: see :func:`crossings`)
    n = len(t) - 1
    s = np.array([t[j] is not None and t[j + 1] is not None and t[j][1] == t[j + 1][1] and t[j][0] == t[j + 1][0]
                  for j in range(n)], dtype=bool)
    fill = s.copy()
    fill[1:-1] |= s[:-2] & s[2:]
    ok = np.array([t[j] is not None and t[j + 1] is not None and t[j][1] == t[j + 1][1] for j in range(n)], dtype=bool)
    fill &= ok
    out = fill.copy()
    for lo, hi in true_runs(fill):
        if hi - lo < 2 and 0 < lo and hi < n:
            out[lo:hi] = False
    # the cell at the frame beside a run, the edge crossing both its rows once the same way round, but into the
    # next grid column: the frame's column there crosses the edge twice, or not at all (47/76's steep edge near
    # x1 = -2.40 steps a column over in the top row of cells: pointing.2's line from the edge there to the top frame
    # lay in no lattice, no trace at all)
    for j, beside in ((0, 1), (n - 1, n - 2)):
        if n > 1 and ok[j] and out[beside]:
            out[j] = True
    return out


def covering(traced, lattice):
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


def band_lattice(F, grid, k0, cells=None, extra=(), sense=None):
    """The band's lattice ``(P (rows, cols, 2), valid (rows, cols))``: columns where the edge crosses
    once between grid rows, the same way round in all of them (None where there is none); ``cells``
    (per cell between grid columns i, i + 1): only those (None: all); ``extra``: more columns x1 = these
    (in the cells used); ``sense``: the crossings that way round only (see :func:`crossings`)."""
    xs, ys, values = grid
    X, Y = xs[1:-1], ys[1:-1]
    fin = np.isfinite(values[1:-1, 1:-1])  # [j, i] at (X[i], Y[j])
    nx = len(X)
    trans = crossings(fin, sense)  # per grid column: (row below the edge crossing, sense) or None
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
    past = [t is not None and t[0] in (-1, ny - 1) for t in trans]  # the edge past the window's frame
    # the cells used: the edge crossing both columns, not past the frame on both sides
    taken = [trans[i] is not None and trans[i + 1] is not None and use[i] and not (past[i] and past[i + 1])
             for i in range(nx - 1)]
    cx, lo_row, hi_row = [], [], []
    for i in range(nx - 1):
        if not taken[i]:
            continue
        a, b = trans[i], trans[i + 1]
        j0, j1 = max(min(a[0], b[0]), 0), min(max(a[0], b[0]) + 1, ny - 1)
        here = [X[i] + (X[i + 1] - X[i]) * s / m for s in range(m + 1)]
        # the next cell's first column, where that cell is used (15/106: the edge leaves through the bottom frame
        # in a cell whose right column, past the frame, was left to the next cell, which is past it on both sides
        # and not used: contact_ratio_tip=1.2's line from the frame up to that column had no lattice, 12.8 tol)
        if i + 1 < nx - 1 and taken[i + 1]:
            here.pop()
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


def dip_columns(F, build, lattice, ks, many=None):
    """``lattice`` (from ``build(extra)``, :func:`band_lattice` with more columns ``extra``) with columns added
    where a function of ``ks`` changes sign along the edge between two of its columns of one sign there: an
    island of a line beside the edge shorter than the columns' spacing (28/80 z0 38's trimming.nu: negative
    in a sliver 0.015 long and 6.5e-5 wide along the edge, between two columns 0.02 apart, not traced at
    all). Tried between two columns where the values on the edge of the two next to them, carried on in a
    straight line, change sign before the other column: ``DIP_SAMPLES`` columns between them, kept where
    their edge values show a sign change the two did not. ``F(points, k)`` (``many(points, ks)``: all at
    once) in the lattice's coordinates.

    >>> # the edge y = 0, F = |x - 0.5| - 0.02 on it (negative for 0.48 < x < 0.52, between columns 0.4, 0.6)
    >>> def build(extra=()):
    ...     cx = np.unique(np.concatenate([np.linspace(0.0, 1.0, 6), extra]))
    ...     P = np.stack([np.broadcast_to(cx, (3, cx.size)), np.array([[0.2], [0.1], [0.0]]) + 0 * cx], axis=-1)
    ...     return P, np.ones(P.shape[:2], dtype=bool)
    >>> F = lambda p, k: np.abs(p[:, 0] - 0.5) + 10 * p[:, 1] - 0.02
    >>> P, valid = dip_columns(F, build, build(), [0])
    >>> cx = P[-1, :, 0]
    >>> bool(np.any((cx > 0.48) & (cx < 0.52))), int(cx.size)
    (True, 14)
    """
    if lattice is None:
        return None
    P, valid = lattice
    x, e = _edge_values(F, P, valid, ks, many)
    if x.size < 3:
        return lattice
    h = np.diff(x)
    near = h <= 1.5 * np.median(h)  # next to each other (not across a gap between two runs of columns)
    sign = np.sign(e)
    same = near[None] & (sign[:, :-1] * sign[:, 1:] > 0)
    with np.errstate(invalid="ignore", divide="ignore"):
        left = np.full(same.shape, False)  # the line through the two columns before, at the next column
        left[:, 1:] = near[None, :-1] & (np.sign(e[:, 1:-1] + (e[:, 1:-1] - e[:, :-2]) * (h[1:] / h[:-1])[None])
                                         == -sign[:, 1:-1])
        right = np.full(same.shape, False)  # the line through the two columns after, at the one before
        right[:, :-1] = near[None, 1:] & (np.sign(e[:, 1:-1] - (e[:, 2:] - e[:, 1:-1]) * (h[:-1] / h[1:])[None])
                                          == -sign[:, 1:-1])
    tried = np.flatnonzero(np.any(same & (left | right), axis=0))
    if not tried.size:
        return lattice
    t = np.arange(1, DIP_SAMPLES + 1) / (DIP_SAMPLES + 1)
    between = x[tried, None] + h[tried, None] * t[None]
    fine = build(np.ravel(between))
    if fine is None:
        return lattice
    xf, ef = _edge_values(F, *fine, ks, many)
    kept = []
    for i, xs in zip(tried, between):
        sel = (xf >= x[i]) & (xf <= x[i + 1])
        flips = np.any(np.sign(ef[:, sel][:, 1:]) * np.sign(ef[:, sel][:, :-1]) < 0)
        if flips:
            kept += list(xs)
    return build(np.array(kept)) if kept else lattice


def _edge_values(F, P, valid, ks, many=None):
    """x of the lattice's columns with an edge point (its last row) and every function ``ks`` there,
    ``(len(ks), n)``."""
    on = valid[-1]
    pts = P[-1, on]
    if many is not None:
        e = np.asarray(many(pts, ks), dtype=float)
    else:
        e = np.stack([F(pts, np.full(len(pts), k)) for k in ks]) if len(pts) else np.zeros((len(ks), 0))
    return pts[:, 0], e.reshape(len(ks), len(pts))
