"""Grids for the level sets of :mod:`gearkit.blocking.level`: values at the nodes, the cells a zero
set crosses, a locally refined grid, the grid edges marching-squares vertices lie on, the pieces
lying on its frame, and where polylines are cut.

>>> import numpy as np
>>> v = np.array([[-1.0, 1.0], [-1.0, 1.0]])
>>> sign_cells(v).tolist()
[[True]]
"""
from __future__ import annotations

import numpy as np

__all__ = ["grid_values", "sign_cells", "refine_grid", "edge_nodes", "bridge_pieces", "true_runs", "on_frame",
           "cut_positions", "beside_chords"]

BESIDE = 0.25  #: a point farther than this many chord lengths from a chord is not on the curve it stands for
BESIDE_SAMPLES = 16  #: samples on the way from the chord to the point (and as far beyond it)


def grid_values(F, xs, ys, which: int = 0) -> np.ndarray:
    """``F`` (function ``which``) at the nodes of the grid ``xs`` x ``ys``: ``values[j, i]``."""
    gx, gy = np.meshgrid(xs, ys)
    return F(np.column_stack([gx.ravel(), gy.ravel()]), np.full(gx.size, which)).reshape(gx.shape)


def true_runs(mask):
    """(start, stop) of the runs of True in ``mask``.

    >>> true_runs(np.array([True, True, False, True]))
    [(0, 2), (3, 4)]
    """
    d = np.diff(np.concatenate([[False], mask, [False]]).astype(int))
    return [(int(a), int(b)) for a, b in zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1))]


def edge_nodes(v, xs, ys):
    """For marching-squares vertices ``v`` (m, 2): the grid nodes (i0, j0), (i1, j1) of their edges."""
    dx, dy = xs[1] - xs[0], ys[1] - ys[0]
    fi = (v[:, 0] - xs[0]) / dx
    fj = (v[:, 1] - ys[0]) / dy
    on_row = np.abs(fj - np.round(fj)) < 1e-7
    i0 = np.clip(np.where(on_row, np.floor(fi + 1e-9), np.round(fi)).astype(int), 0, len(xs) - 1)
    j0 = np.clip(np.where(on_row, np.round(fj), np.floor(fj + 1e-9)).astype(int), 0, len(ys) - 1)
    i1 = np.clip(np.where(on_row, i0 + 1, i0), 0, len(xs) - 1)
    j1 = np.clip(np.where(on_row, j0, j0 + 1), 0, len(ys) - 1)
    return i0, j0, i1, j1


def sign_cells(values) -> np.ndarray:
    """Cells (m - 1, n - 1) of a grid whose corners change sign or are undefined (NaN)."""
    pos = values > 0
    bad = ~np.isfinite(values)
    c = [pos[:-1, :-1], pos[:-1, 1:], pos[1:, :-1], pos[1:, 1:]]
    n = [bad[:-1, :-1], bad[:-1, 1:], bad[1:, :-1], bad[1:, 1:]]
    return (c[0] != c[1]) | (c[0] != c[2]) | (c[0] != c[3]) | n[0] | n[1] | n[2] | n[3]


def refine_grid(F, which: int, xs, ys, values, cells, factor: int = 4):
    """A grid ``factor`` times finer: ``F`` (function ``which``) evaluated at the fine nodes of the
    marked ``cells`` and of their neighbours, bilinear in the coarse values elsewhere (where the
    coarse grid already has the sign right). Returns ``(fine_xs, fine_ys, fine_values)``."""
    ny, nx = values.shape
    fx = np.linspace(xs[0], xs[-1], (nx - 1) * factor + 1)
    fy = np.linspace(ys[0], ys[-1], (ny - 1) * factor + 1)
    # bilinear interpolation of the coarse values
    ti = np.arange(len(fx)) / factor
    tj = np.arange(len(fy)) / factor
    i0 = np.minimum(np.floor(ti).astype(int), nx - 2)
    j0 = np.minimum(np.floor(tj).astype(int), ny - 2)
    u, v = ti - i0, tj - j0
    V = values
    fine = ((1 - v)[:, None] * ((1 - u)[None] * V[j0][:, i0] + u[None] * V[j0][:, i0 + 1])
            + v[:, None] * ((1 - u)[None] * V[j0 + 1][:, i0] + u[None] * V[j0 + 1][:, i0 + 1]))
    near = cells.copy()
    near[1:] |= cells[:-1]
    near[:-1] |= cells[1:]
    near[:, 1:] |= near[:, :-1].copy()
    near[:, :-1] |= near[:, 1:].copy()
    mask = np.zeros(fine.shape, dtype=bool)
    cj, ci = np.nonzero(near)
    for dj in range(factor + 1):
        for di in range(factor + 1):
            mask[cj * factor + dj, ci * factor + di] = True
    jj, ii = np.nonzero(mask)
    if jj.size:
        pts = np.column_stack([fx[ii], fy[jj]])
        fine[jj, ii] = F(pts, np.full(len(pts), which))
    return fx, fy, fine


def bridge_pieces(lines, grids, measure, cells: float, cos: float) -> list:
    """Join open pieces of one curve whose ends face each other across at most ``cells`` grid
    cells (the grid masks every cell with an undefined corner: a line running beside the edge of
    where ``F`` is defined comes out in pieces). The bridging chord is then measured like any other
    (and cut again when no zero lies across it)."""
    lines = list(lines)
    while True:
        ends = []  # (line, at start?, point, outward direction)
        for n, (k, q, _) in enumerate(lines):
            if k in measure or np.array_equal(q[0], q[-1]) or len(q) < 3:  # specks are not bridged
                continue
            for first in (True, False):
                a, b = (q[0], q[1]) if first else (q[-1], q[-2])
                ends.append((n, first, a, (a - b) / max(float(np.hypot(*(a - b))), 1e-300)))
        pairs = []
        for u in range(len(ends)):
            for v in range(u + 1, len(ends)):
                (n1, f1, a1, t1), (n2, f2, a2, t2) = ends[u], ends[v]
                k1, k2 = lines[n1][0], lines[n2][0]
                if n1 == n2 or k1 != k2:
                    continue
                xs, ys = grids[k1][:2]
                gap = a2 - a1
                d = float(np.hypot(*gap))
                if 0 < d <= cells * np.hypot(xs[1] - xs[0], ys[1] - ys[0]) and \
                        np.dot(t1, gap) > cos * d and np.dot(t2, -gap) > cos * d:
                    pairs.append((d, u, v))
        if not pairs:
            return lines
        d, u, v = min(pairs)
        (n1, f1, _, _), (n2, f2, _, _) = ends[u], ends[v]
        k, q1, g1 = lines[n1]
        _, q2, g2 = lines[n2]
        if f1:  # the first piece ends at the bridge, the second starts there
            q1, g1 = q1[::-1], g1[::-1]
        if not f2:
            q2, g2 = q2[::-1], g2[::-1]
        joined = (k, np.vstack([q1, q2]), np.concatenate([g1, g2]))
        lines = [ln for i, ln in enumerate(lines) if i not in (n1, n2)] + [joined]


def on_frame(p, xs, ys) -> bool:
    """True when both vertices of ``p`` lie on the inner frame of the padded grid (the window's edge)."""
    ex = np.isclose(p[:, 0], xs[1], rtol=0, atol=1e-12) | np.isclose(p[:, 0], xs[-2], rtol=0, atol=1e-12)
    ey = np.isclose(p[:, 1], ys[1], rtol=0, atol=1e-12) | np.isclose(p[:, 1], ys[-2], rtol=0, atol=1e-12)
    return bool(np.all(ex | ey))


def cut_positions(p, starts):
    """Indices in ``p`` of the given chord start points (each found once, in order)."""
    out = []
    for a in starts:
        hits = np.flatnonzero(np.all(p == a, axis=1))
        if hits.size:
            out.append(int(hits[0]))
    return sorted(set(out))


def beside_chords(F, k, q, line, close: float) -> np.ndarray:
    """True for each point of ``q`` (zeros of ``F_k``) that lies on the curve a chord of the polyline ``line``
    (vertices on that curve, chords not yet refined) stands for: within ``close`` of it, or, where the
    chord nearest the point is up to ``BESIDE`` of its length from it, no zero of ``F_k`` on the way from
    the chord to the point (short of ``close`` before it) nor as far on the chord's other side: the
    zero nearest the chord there is the point's. A point past an open line's end (the first chord's start, the
    last's end, nearest it) is beside no chord: the line stops short of it.

    >>> F = lambda p, k: (p[:, 1] - 0.2 * p[:, 0] ** 2) * (p[:, 1] + 0.1)  # zeros y = 0.2 x^2 and y = -0.1
    >>> line = np.array([[-1.0, 0.2], [1.0, 0.2]])  # a chord of the parabola
    >>> beside_chords(F, 0, np.array([[0.0, 0.0], [0.5, 0.05], [0.0, -0.1]]), line, 1e-3).tolist()
    [True, True, False]
    """
    a, b = line[:-1], line[1:]
    d = b - a
    L2 = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
    t = np.clip(np.einsum("mij,ij->mi", q[:, None, :] - a[None], d) / L2, 0.0, 1.0)
    foot = a[None] + t[:, :, None] * d[None]
    dist = np.hypot(*(q[:, None, :] - foot).transpose(2, 0, 1))
    j = np.argmin(dist, axis=1)
    m = np.arange(len(q))
    c, gap = foot[m, j], dist[m, j]
    out = gap <= close
    # a point past an open line's end is beside no chord of it: the line stops short of it (14/63 z0 38's tip
    # interference line, its grid line ending on a masked cell's side 0.012 above the edge, and the band's run on
    # from there, on the curve's way on from the first chord's end, read as that chord's and dropped: 6.2 tol)
    past = ~np.array_equal(line[0], line[-1]) & (((j == 0) & (t[m, j] <= 0.0)) | ((j == len(d) - 1) & (t[m, j] >= 1.0)))
    ask = np.flatnonzero(~out & ~past & (gap <= BESIDE * np.sqrt(L2[j])))
    if ask.size:
        u = np.linspace(0.0, 1.0, BESIDE_SAMPLES + 1)[None, :]
        s = np.hstack([np.repeat(-u[:, :0:-1], ask.size, axis=0), u * (1.0 - close / gap[ask])[:, None]])
        P = c[ask][:, None, :] + s[:, :, None] * (q[ask] - c[ask])[:, None, :]
        V = F(P.reshape(-1, 2), np.full(P.shape[0] * P.shape[1], k)).reshape(P.shape[:2])
        out[ask] = np.all(np.isfinite(V), axis=1) & (np.all(V > 0, axis=1) | np.all(V < 0, axis=1))
    return out
