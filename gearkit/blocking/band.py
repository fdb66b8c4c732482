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

* **columns** x1 = const, ``BAND_COLUMNS`` per grid cell (:mod:`~gearkit.blocking.lattice`), where the edge crosses the column once
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
the edge before the next column is seen by the columns). An internal pair's rows cross its edge
twice, where x1 is about constant (gear 1 cut no tooth below) and where inv alpha_w reaches 1e-9:
each way round is taken on its own (57/130's steep left edge: B6 tip interference 0.05 short).

A line may also lie in a sliver along the edge shorter than the columns' spacing, between two columns whose
margins on the edge have one sign (28/80 z0 38's trimming.nu, negative for 0.015 along the edge and at most
6.5e-5 from it): where the margins on the edge, carried on from the columns beside, change sign between two
columns, more columns are tried between them and kept where they show it
(:func:`~gearkit.blocking.lattice.dip_columns`).

Every margin is evaluated at the lattice's nodes (one evaluation of the pair formulas for all);
marching squares in lattice coordinates give each line's topology there, and every vertex is
solved on its lattice edge (a segment in (x1, x2)) like the grid's. A sign change through a pole
of ``F`` is none: ``|F|`` does not fall there. The band's pieces are cut where they enter a cell the
grid traced (all corners defined, not all of one sign: 14/46's sliding line turns back in a hairpin
smaller than a grid cell, in cells whose corners all have one sign, 44 tol short of it at tol 1e-3
when those counted) and joined to the grid line ending on that cell's edge, so each
zero is traced once; a piece lying wholly within ``SAME tol`` of a line traced already is that line
at this tol (two zero lines of one margin may run closer than that beside the edge): the joining is
:mod:`~gearkit.blocking.joins`'s (its :func:`~gearkit.blocking.joins.once` is also this module's).

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

from gearkit.blocking.brackets import round_off_roots, segment_roots
from gearkit.blocking.grid import edge_nodes, true_runs
from gearkit.blocking.joins import join_pieces, once, traced_cell
from gearkit.blocking.lattice import band_lattice, covering, dip_columns, run_ends, steep_cells

__all__ = ["band_lines", "once"]

JUMP_FALL = 0.5  #: a solved vertex whose |F| is above this fraction of its edge's ends' is a pole or a jump
INDEX_ROUND = 1e-9  #: lattice indices closer than this to a whole number are on that row or column
THIN = 0.25  #: successive vertices of a band piece closer than this many tol are one (a line crossing the chord
#: between two columns' edge points, where the edge has a corner: the rows next to the edge all put theirs there)


def band_lines(F, lines, grids, tol: float, measure=(), many=None, carry=None, specks=()) -> list:
    """``lines`` (``[(k, points, slopes)]``, the grid's pieces) with the band's pieces added and joined
    to them (see the module notes). ``many(points, ks) -> (len(ks), n)``: all functions ``ks`` at the
    same points (one evaluation); None: ``F`` once per function; every curve but ``measure`` is
    traced in the band. ``carry``: a list to which the ends of the band's pieces that
    leave the lattice through its boundary off the no-pair edge are appended (``(k, point, inf)``: no
    limit on the first step of their continuation): the
    lattice's last row is a chord between the edge's points on two columns, or the window's frame
    on one of them, or a column's rows from the edge end under the frame, and a line may go on beside
    the edge below it or to the frame (see
    :func:`~gearkit.blocking.ends.extend_ends`). ``specks`` (``(k, point)``): grid cells whose piece
    of function k the grid dropped (one chord beside undefined nodes): the band's pieces go on through
    them (44/112's tip thickness line from the edge to the window's top frame crosses one such cell
    on its way: cut there, it stopped 0.08 short of the frame)."""
    ks = [k for k in range(len(grids)) if k not in measure
          and np.any(np.isnan(grids[k][2][1:-1, 1:-1])) and np.any(np.isfinite(grids[k][2]))]
    if not ks:
        return lines
    grid = grids[ks[0]]
    xs, ys, values = grid
    # the steep parts of the edge: rows x2 = const (the transposed lattice) where it runs within one
    # grid column from one grid row to the next; columns x1 = const elsewhere
    # (each way round on its own: an internal pair's rows cross the edge twice, at x1 about constant where
    # gear 1 is cut no tooth and where inv alpha_w reaches 1e-9)
    def FT(p, k):
        return F(p[:, ::-1], k)
    if getattr(F, "slack", None) is not None:  # the measure of the no-pair area, transposed alike
        FT.slack = lambda p, k: F.slack(p[:, ::-1], k)
    manyT = None if many is None else (lambda p, k: many(p[:, ::-1], k))
    rows = []
    for sense in (1, -1):
        steep = steep_cells(np.isfinite(values[1:-1, 1:-1]).T, sense)
        if steep.any():
            def build_rows(extra=(), steep=steep, sense=sense):
                return band_lattice(FT, (ys, xs, values.T), ks[0], steep, extra=tuple(extra), sense=sense)
            lattice = dip_columns(FT, build_rows, build_rows(), ks, manyT)
            rows += [] if lattice is None else [lattice]
    # a column through each end of the rows' band on the edge: a line along the edge across it that meets
    # the edge before the next column is seen by the columns (its tail is no piece of a row)
    ends = tuple(x for r in rows for x in run_ends(r))

    def build_cols(extra=()):
        return band_lattice(F, grid, ks[0], extra=ends + tuple(extra))
    cols = dip_columns(F, build_cols, build_cols(), ks, many)

    def traced(k, p):
        return traced_cell(grids[k], p, [q for kk, q in specks if kk == k])

    for lattice, flip in [(r, True) for r in rows] + [(cols, False)]:
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
        far = []
        pieces = _pieces(F, P, valid, V, ks, tol, carry, far)
        if carry is not None:  # leaving through the far end into a cell the grid traced nothing in: carried on
            carry += [(k, q, np.inf) for k, q in far if not traced(k, q[None])[0]]
        lines = join_pieces(F, lines, pieces, traced, tol)
        if flip:  # the column lattice's pieces are cut where they enter the rows' band
            traced = covering(traced, lattice)
    return lines


def _pieces(F, P, valid, V, ks, tol, carry=None, far=None):
    """Each function's zero lines on the lattice: ``[(k, points, slopes)]`` (vertices solved on their
    lattice edges to ``tol / 4``, split where a sign change is a pole or a jump); the ends leaving the
    lattice through its boundary where a pair exists beyond (not on the edge), or where its rows end
    under the window's frame, appended to ``carry``; those leaving through its far end (``(k, point)``) to
    ``far`` (34/105's tip thickness line, from the steep edge's corner cell to the frame through a cell
    whose grid piece was dropped, left the lattice 5.5e-4 under the frame: nothing went on from there)."""
    import contourpy

    rows, cols = valid.shape
    framed = ~valid & valid.any(axis=0)[None, :]  # nodes of a column with an edge beyond the window's frame
    ci, ri = np.arange(cols, dtype=float), np.arange(rows, dtype=float)
    raw = []  # (k, index-space vertices)
    for n, k in enumerate(ks):
        grid = np.full(valid.shape, np.nan)
        grid[valid] = V[n]
        if not (np.any(grid > 0) and np.any(grid < 0)):
            continue
        # a cell with a node past the frame is left out whole (the corner's triangle is not traced): a vertex on
        # its diagonal lies on no lattice edge and is dropped, and the line's end before it was then no end of
        # the piece (23/44 z0 35's tip thickness line under the frame, not carried on: 7.6 tol at 1e-3)
        gen = contourpy.contour_generator(ci, ri, np.ma.masked_invalid(grid), name="serial", line_type="Separate",
                                          corner_mask=False)
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
    # |grad F| at each vertex, off its root's last bracket (not the lattice edge's secant: beside the edge, where
    # F goes as a root of the distance, the secant across an edge reaching towards it is many times the slope at
    # the root, and densify kept a chord on its middle read against it: 58/63 z0 16's sliding line at tol 1e-7,
    # slopes 8029 and 10484 read at a chord's ends for 620, the chord 4.57 tol off kept as 0.35)
    slope = np.full(len(A), np.nan)
    # an edge shorter than the vertices' accuracy is solved to round-off all the same: whether |F| falls
    # there (a zero) or not (a pole) is read off the root
    # (to a thousandth of its length, edges grouped by the decade of their length)
    length = np.hypot(*(B - A).T)
    decade = np.where(length > tol, np.inf, np.floor(np.log10(np.maximum(length, 1e-300))))
    for e in np.unique(decade[ok]):
        sel = ok & (decade == e)
        t = 0.25 * tol if np.isinf(e) else 1e-3 * 10.0 ** e
        R[sel], slope[sel] = segment_roots(F, A[sel], B[sel], FA[sel], FB[sel], t, W[sel], True)
    fr = np.full(len(A), np.nan)
    fr[ok] = np.abs(F(R[ok], W[ok]))
    with np.errstate(invalid="ignore"):
        good = ok & (fr <= JUMP_FALL * np.fmin(np.abs(FA), np.abs(FB)))
    again = np.flatnonzero(ok & ~good)  # |F| did not fall at a root solved to tol / 4: solved to round-off,
    if again.size:  # a zero beside the edge, where F varies as a root of the distance, falls there; a pole not
        R[again], slope[again], good[again] = round_off_roots(F, A[again], B[again], FA[again], FB[again], W[again],
                                                              JUMP_FALL)
    out, at = [], 0
    for k, _, p, _ in raw:
        q, g, use = R[at:at + len(p)], slope[at:at + len(p)], good[at:at + len(p)]
        at += len(p)
        closed = np.array_equal(p[0], p[-1]) and use.all()
        for lo, hi in true_runs(use):
            keep = _thin(q[lo:hi], THIN * tol)
            if keep.size >= 2:
                out.append((k, q[lo:hi][keep], g[lo:hi][keep], closed))
                if carry is not None and not closed:
                    carry += [(k, q[j], np.inf) for j, at_end in ((lo, lo == 0), (hi - 1, hi == len(p)))
                              if at_end and (_off_lattice(p[j], rows, cols) or _at_frame(p[j], framed))]
                if far is not None and not closed:
                    far += [(k, q[j]) for j, at_end in ((lo, lo == 0), (hi - 1, hi == len(p)))
                            if at_end and abs(p[j][1]) <= INDEX_ROUND and abs(p[j][0] - round(p[j][0])) > INDEX_ROUND]
    if carry:  # a vertex on the edge itself (undefined to round-off) ends its line there
        keep = np.isfinite(F(np.array([c[1] for c in carry]), np.array([c[0] for c in carry])))
        carry[:] = [c for c, kp in zip(carry, keep) if kp]
    return out


def _off_lattice(v, rows, cols) -> bool:
    """True when the index-space vertex ``v`` lies on the lattice's boundary between two nodes: its
    last row (the edge's row) or its first or last column (to ``INDEX_ROUND``: the contour generator
    interpolates the index of a row as ``(1 - f) j + f j``, 51/101's interference.1 ended on the
    edge's row at 81.00000000000001 or at 81 as the values at its nodes moved by an ulp, and its
    piece beside the edge below that row was lost, 7 tol at 1e-3, with the one or the other)."""
    i, j = v
    on = [abs(i - c) <= INDEX_ROUND for c in (0, cols - 1)] + [abs(j - (rows - 1)) <= INDEX_ROUND]
    between = [abs(i - round(i)) > INDEX_ROUND, abs(j - round(j)) > INDEX_ROUND]
    return bool((on[2] and between[0]) or ((on[0] or on[1]) and between[1]))


def _at_frame(v, framed) -> bool:
    """True when the index-space vertex ``v`` lies on a lattice edge of a cell with a node ``framed``
    (beyond the window's frame, in a column whose edge was found): the lattice ends there short of the
    frame by up to a row (25/49 z0 37: interference.1 and tip_interference, in a strip 0.015 wide
    beside the steep no-pair edge, stopped at x2 = 0.092 and 0.089 on the lattice, short of the frame
    at 0.1: 10.3 tol at 1e-3)."""
    rows, cols = framed.shape
    i, j = v
    if abs(j - round(j)) <= INDEX_ROUND:  # on a row: the cells below and above its edge
        r, c = int(round(j)), int(np.floor(i))
        nodes = [(rr, cc) for rr in (r - 1, r + 1) for cc in (c, c + 1)]
    else:  # on a column: the cells left and right of its edge
        r, c = int(np.floor(j)), int(round(i))
        nodes = [(rr, cc) for rr in (r, r + 1) for cc in (c - 1, c + 1)]
    return any(0 <= rr < rows and 0 <= cc < cols and framed[rr, cc] for rr, cc in nodes)


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
