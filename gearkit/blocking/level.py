"""Zero sets of several functions ``F_k(x1, x2) = 0`` in a window, to a stated accuracy, in batches.

``F(points (n, 2), which (n,) int) -> (n,)`` evaluates function ``which[i]`` at ``points[i]`` (NaN
where undefined); every step below evaluates all the points it needs, of all the curves, at once.

1. **Topology** from a grid: marching squares (contourpy) on the values at the nodes of a grid
   gives each component once, open ones ending on the window's edge or where ``F`` is undefined,
   closed ones closed (no duplicate traces, no spurious loops: the polylines are the level set
   of one interpolant).
2. **Vertices on the curve**: each marching-squares vertex lies on a grid edge with a sign change;
   it is moved to the root of ``F`` on that edge (:func:`segment_roots`: regula falsi with the
   Illinois modification and bisection safeguards) to ``tol / 4`` in x.
3. **Chords on the curve** (:func:`densify`): a chord's deviation from its curve is estimated at
   its middle ``m`` from ``|F(m)| / |grad F|`` (the slope known from the roots that made its ends);
   a chord estimated within ``tol / 2`` is kept, any other is measured by a root of ``F`` along
   its normal through ``m`` and, if that root is more than ``tol`` away, split into as many
   pieces as its curvature needs (``sqrt(deviation / (tol / 2))``, the new vertices roots of ``F``
   near the parabola through the three known points), round after round. So every point of a
   polyline lies within about ``tol + tol / 4`` of its curve, and the number of vertices is what
   the curvature needs at that tolerance: coarser tolerances cost less.

``F`` may have kinks (e.g. the smallest of several margins); a corner of a zero set is approached
by splitting the chords beside it until they pass within ``tol``.
"""
from __future__ import annotations

import numpy as np

__all__ = ["segment_roots", "zero_lines", "densify", "grid_values", "sign_cells", "refine_grid"]

VERTEX_FRACTION = 0.25  #: vertices are solved to this fraction of tol
ESTIMATE_FRACTION = 0.5  #: a chord whose estimated deviation is below this fraction of tol is kept
MAX_ROUNDS = 60  #: rounds of chord splitting
MAX_PIECES = 64  #: most pieces one chord is split into in one round
ROOT_ITERATIONS = 100
WIDE_REACH = 1.0  #: a chord's second search for its curve reaches this many chord lengths to each side
WIDE_REGION = True  #: the wider search for measured curves too
JUMP_FACTOR = 100.0  #: a solved vertex with |F| above this times slope x tol sits on a jump, not a zero


def grid_values(F, xs, ys, which: int = 0) -> np.ndarray:
    """``F`` (function ``which``) at the nodes of the grid ``xs`` x ``ys``: ``values[j, i]``."""
    gx, gy = np.meshgrid(xs, ys)
    return F(np.column_stack([gx.ravel(), gy.ravel()]), np.full(gx.size, which)).reshape(gx.shape)


def segment_roots(F, a, b, fa, fb, tol: float, which) -> np.ndarray:
    """Roots of ``F`` (function ``which[k]``) on the segments ``a[k] -> b[k]`` (``(k, 2)``), given end
    values of opposite signs; each within ``tol`` (in x) of a sign change of ``F``.

    Regula falsi with the Illinois modification; a step that fails to halve the bracket over two
    iterations is followed by a bisection. Where ``F`` is undefined (NaN) inside a bracket the
    half towards the end with the larger ``|F|`` is kept.
    """
    a = np.asarray(a, dtype=float).reshape(-1, 2)
    b = np.asarray(b, dtype=float).reshape(-1, 2)
    which = np.asarray(which)
    d = b - a
    span = np.maximum(np.abs(d).max(axis=1), 1e-300)
    k = len(a)
    lo, hi = np.zeros(k), np.ones(k)
    flo, fhi = np.array(fa, dtype=float), np.array(fb, dtype=float)
    t = np.where(flo == 0, 0.0, np.where(fhi == 0, 1.0, np.nan))
    done = (flo == 0) | (fhi == 0) | ~((flo > 0) != (fhi > 0)) | (span <= tol)
    side = np.zeros(k, dtype=int)
    stall = np.zeros(k, dtype=int)
    for _ in range(ROOT_ITERATIONS):
        act = np.flatnonzero(~done)
        if not act.size:
            break
        l, h, fl, fh = lo[act], hi[act], flo[act], fhi[act]
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            c = (l * fh - h * fl) / (fh - fl)
        bis = ~((c > l) & (c < h)) | (stall[act] >= 3)
        c = np.where(bis, 0.5 * (l + h), c)
        fc = F(a[act] + c[:, None] * d[act], which[act])
        nan = np.isnan(fc)
        zero = fc == 0
        same_hi = ~nan & ~zero & ((fc > 0) == (fh > 0))
        same_lo = ~nan & ~zero & ~same_hi
        nh = nan & (np.abs(fh) >= np.abs(fl))
        nl = nan & ~nh
        s = side[act]
        # Anderson-Bjorck: when the same end moves twice, scale the value kept at the other end
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            m_hi = 1.0 - fc / fh
            m_lo = 1.0 - fc / fl
        m_hi = np.where(m_hi > 0, m_hi, 0.5)
        m_lo = np.where(m_lo > 0, m_lo, 0.5)
        fl2 = np.where(same_lo, fc, np.where(same_hi & (s == -1) & ~bis, fl * m_hi, fl))
        fh2 = np.where(same_hi, fc, np.where(same_lo & (s == 1) & ~bis, fh * m_lo, fh))
        side[act] = np.where(bis | nan, 0, np.where(same_hi, -1, np.where(same_lo, 1, s)))
        new_h = np.where(same_hi | nh, c, h)
        new_l = np.where(same_lo | nl, c, l)
        shrunk = (new_h - new_l) <= 0.5 * (h - l)
        stall[act] = np.where(shrunk | bis, 0, stall[act] + 1)
        lo[act], hi[act], flo[act], fhi[act] = new_l, new_h, fl2, fh2
        t[act] = np.where(zero, c, t[act])
        done[act] = zero | ((new_h - new_l) * span[act] <= tol)
    with np.errstate(invalid="ignore"):
        best = np.where(np.abs(flo) <= np.abs(fhi), lo, hi)
    t = np.where(np.isnan(t), best, t)
    return a + t[:, None] * d


def _edge_of(v, xs, ys):
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


def zero_lines(F, grids, tol: float, max_step: float | None = None, measure=()) -> list:
    """Every component of ``F_k = 0`` seen by the grids ``grids[k] = (xs, ys, values)`` (``values[j, i]``
    at ``(xs[i], ys[j])``, NaN where undefined): a list (one entry per ``k``) of ``(n, 2)`` polylines
    within about ``1.25 tol`` of the zero set; a closed one repeats its first vertex last."""
    import contourpy

    raw, owner, edges = [], [], []
    for k, (xs, ys, values) in enumerate(grids):
        if not np.any(np.isfinite(values)):
            continue
        gen = contourpy.contour_generator(xs, ys, np.ma.masked_invalid(values), name="serial",
                                          line_type="Separate")
        for p in gen.lines(0.0):
            if len(p) >= 2:
                p = np.array(p, dtype=float)
                raw.append(p)
                owner.append(k)
                i0, j0, i1, j1 = _edge_of(p, xs, ys)
                edges.append((np.column_stack([xs[i0], ys[j0]]), np.column_stack([xs[i1], ys[j1]]),
                              values[j0, i0], values[j1, i1]))
    out = [[] for _ in grids]
    if not raw:
        return out
    allv = np.concatenate(raw)
    ids = np.concatenate([np.full(len(p), k) for p, k in zip(raw, owner)])
    a = np.concatenate([e[0] for e in edges])
    b = np.concatenate([e[1] for e in edges])
    fa = np.concatenate([e[2] for e in edges])
    fb = np.concatenate([e[3] for e in edges])
    ok = np.isfinite(fa) & np.isfinite(fb) & ((fa > 0) != (fb > 0))
    moved = allv.copy()
    grad = np.full(len(allv), np.nan)
    if ok.any():
        moved[ok] = segment_roots(F, a[ok], b[ok], fa[ok], fb[ok], VERTEX_FRACTION * tol, ids[ok])
        grad[ok] = np.abs(fb[ok] - fa[ok]) / np.hypot(*(b[ok] - a[ok]).T)
    # a sign change through a pole or a jump of F is no zero: |F| stays large at the "root"; a
    # vertex on no edge with a sign change (beside undefined nodes) is kept only where F = 0
    fv = np.abs(F(moved, ids))
    jump = np.where(ok, fv > JUMP_FACTOR * grad * tol, ~(fv == 0))
    jump[np.isin(ids, list(measure))] = False  # the region: where no pair exists is its edge too
    lines, k0 = [], 0
    for p, k in zip(raw, owner):
        q, g, jmp = moved[k0:k0 + len(p)], grad[k0:k0 + len(p)], jump[k0:k0 + len(p)]
        k0 += len(p)
        closed = np.array_equal(p[0], p[-1])
        keep = np.concatenate([[True], np.any(q[1:] != q[:-1], axis=1)])
        q, g, jmp = q[keep], g[keep], jmp[keep]
        if closed and not np.array_equal(q[0], q[-1]):
            q, g, jmp = np.vstack([q, q[:1]]), np.append(g, g[0]), np.append(jmp, jmp[0])
        for lo, hi in _runs(~jmp):
            if hi - lo >= 2:
                lines.append((k, q[lo:hi], g[lo:hi]))
    for k, q in densify(F, lines, tol, max_step, measure):
        out[k].append(q)
    return out


def _runs(mask):
    """(start, stop) of the runs of True in ``mask``."""
    d = np.diff(np.concatenate([[False], mask, [False]]).astype(int))
    return list(zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1)))


def densify(F, lines, tol: float, max_step: float | None = None, measure=()) -> list:
    """``lines`` (a list of ``(k, points (n, 2), slope (n,))``: curve index, vertices on the curve, and
    estimates of ``|grad F_k|`` there, NaN if unknown) with vertices added until every chord lies
    within ``tol`` of its curve and is at most ``max_step`` long; returns ``[(k, points)]``. Curves whose
    index is in ``measure`` (e.g. the smallest of several functions, whose slope jumps at the kinks)
    have every chord measured, never estimated."""
    vtol = VERTEX_FRACTION * tol
    step = np.inf if not max_step else float(max_step)
    state = [(k, np.asarray(p, float), np.asarray(g, float), np.ones(len(p) - 1, bool)) for k, p, g in lines]
    state_before = list(state)
    n_curves = 1 + max((k for k, _, _ in lines), default=0)
    trust = np.ones(n_curves, dtype=bool)
    trust[[k for k in measure if k < n_curves]] = False
    for _ in range(MAX_ROUNDS):
        parts = [(n, np.flatnonzero(todo)) for n, (_, _, _, todo) in enumerate(state) if todo.any()]
        if not parts:
            break
        A = np.concatenate([state[n][1][i] for n, i in parts])
        B = np.concatenate([state[n][1][i + 1] for n, i in parts])
        gA = np.concatenate([state[n][2][i] for n, i in parts])
        gB = np.concatenate([state[n][2][i + 1] for n, i in parts])
        which = np.concatenate([np.full(i.size, state[n][0]) for n, i in parts])
        d = B - A
        L = np.hypot(d[:, 0], d[:, 1])
        nrm = np.column_stack([-d[:, 1], d[:, 0]]) / np.maximum(L, 1e-300)[:, None]
        m = 0.5 * (A + B)
        fm = F(m, which)
        with np.errstate(invalid="ignore"):
            slope = np.fmin(gA, gB)
            est = np.abs(fm) / slope
        live = L > vtol
        long = L > step
        keep = ~live | (~long & trust[which] & np.isfinite(est) & (est <= ESTIMATE_FRACTION * tol)) | (fm == 0) & ~long
        # measure the others: the root of F along the normal through the middle
        meas = np.flatnonzero(~keep & np.isfinite(fm))
        f0 = fm[meas]
        span = np.full(meas.size, 0.5)
        up_end, dn_end = m[meas] + 0.5 * L[meas, None] * nrm[meas], m[meas] - 0.5 * L[meas, None] * nrm[meas]
        fu = F(up_end, which[meas])
        fd = F(dn_end, which[meas])
        up = np.isfinite(fu) & ((fu > 0) != (f0 > 0))
        dn = np.isfinite(fd) & ((fd > 0) != (f0 > 0))
        wide = np.flatnonzero(~(up | dn) & (trust[which[meas]] | WIDE_REGION))  # past a sharp corner: wider
        if wide.size:
            r = WIDE_REACH * L[meas][wide, None] * nrm[meas][wide]
            up_end[wide], dn_end[wide] = m[meas][wide] + r, m[meas][wide] - r
            fu[wide], fd[wide] = F(up_end[wide], which[meas][wide]), F(dn_end[wide], which[meas][wide])
            span[wide] = WIDE_REACH
            up = np.isfinite(fu) & ((fu > 0) != (f0 > 0))
            dn = np.isfinite(fd) & ((fd > 0) != (f0 > 0))
            amb = np.zeros(meas.size, dtype=bool)
            amb[wide] = up[wide] & dn[wide]  # both sides: another part of the curve, not this chord's
            up &= ~amb
            dn &= ~amb
        pick_up = up & ~(dn & (np.abs(fu - f0) > np.abs(fd - f0)))
        pick_dn = dn & ~pick_up
        root = m[meas].copy()
        for sel, end, fe in ((pick_up, up_end, fu), (pick_dn, dn_end, fd)):
            if sel.any():
                root[sel] = segment_roots(F, m[meas][sel], end[sel], f0[sel], fe[sel], vtol, which[meas][sel])
        # a "root" through a pole or a jump of F is none: |F| stays large there
        solved = np.flatnonzero(pick_up | pick_dn)
        if solved.size:
            slope_end = np.abs(np.where(pick_up, fu, fd)[solved] - f0[solved]) / (span[solved] * L[meas][solved])
            bad = np.abs(F(root[solved], which[meas][solved])) > JUMP_FACTOR * slope_end * tol
            bad &= trust[which[meas][solved]]
            pick_up[solved[bad]] = False
            pick_dn[solved[bad]] = False
        off = np.einsum("ij,ij->i", root - m[meas], nrm[meas])
        dev = np.abs(off)
        found = pick_up | pick_dn
        with np.errstate(invalid="ignore", divide="ignore"):
            g_root = np.where(dev > 0, np.abs(f0) / dev, np.nan)
        split_m = found & ((dev > tol) | long[meas])
        # no zero across a line's chord: two components (a region's loop stays closed)
        cut = set(meas[~found & live[meas] & trust[which[meas]]].tolist())
        # chords measured and within tol are kept; chords with no root found are kept as they are
        inserts = {}  # chord row -> (points (j, 2) ordered along the chord, slopes)
        rows = meas[split_m]
        if rows.size:
            offs, devs = off[split_m], dev[split_m]
            pieces = np.clip(np.ceil(np.sqrt(devs / (ESTIMATE_FRACTION * tol))), 2, MAX_PIECES).astype(int)
            pieces = np.maximum(pieces, np.ceil(L[rows] / step).astype(int) if np.isfinite(step) else 2)
            pieces = np.minimum(pieces, MAX_PIECES)
            # a measured curve (kinks of a smallest-of) is split at its middle only: the parabola
            # does not predict the points beside a corner
            pieces = np.where(trust[which[rows]], pieces, 2)
            # interior points at t = j / pieces, solved along the normal near the parabola's offset
            r_idx = np.repeat(np.arange(rows.size), pieces - 1)
            j = np.concatenate([np.arange(1, p) for p in pieces])
            tt = j / pieces[r_idx]
            keep_mid = np.abs(tt - 0.5) > 1e-12
            r_idx, tt = r_idx[keep_mid], tt[keep_mid]
            row = rows[r_idx]
            base = A[row] + tt[:, None] * d[row]
            pred = 4.0 * offs[r_idx] * tt * (1 - tt)
            nn = nrm[row]
            lo_p, hi_p = base - 0.5 * pred[:, None] * nn, base + 2.0 * pred[:, None] * nn
            if len(row):
                flo = F(lo_p, which[row])
                fhi = F(hi_p, which[row])
                okb = np.isfinite(flo) & np.isfinite(fhi) & ((flo > 0) != (fhi > 0))
                pts = np.full(lo_p.shape, np.nan)
                if okb.any():
                    pts[okb] = segment_roots(F, lo_p[okb], hi_p[okb], flo[okb], fhi[okb], vtol, which[row][okb])
                with np.errstate(invalid="ignore", divide="ignore"):
                    gs = np.abs(fhi - flo) / np.abs(2.5 * pred)
            else:
                okb = np.zeros(0, bool)
                pts, gs = np.zeros((0, 2)), np.zeros(0)
            mid_rows = np.flatnonzero(split_m)
            for q, rr in enumerate(rows):
                mine = np.flatnonzero((r_idx == q) & okb)
                ts = np.append(tt[mine], 0.5)
                ps = np.vstack([pts[mine], root[mid_rows[q]][None]])
                gg = np.append(gs[mine], g_root[mid_rows[q]])
                order = np.argsort(ts)
                inserts[rr] = (ps[order], gg[order])
        # write back: per polyline, insert new vertices after their chord's start
        base_row = 0
        cuts = {}
        for n, idx in parts:
            k, p, g, todo = state[n]
            todo = todo.copy()
            chord_rows = np.arange(base_row, base_row + idx.size)
            base_row += idx.size
            new_p, new_g, new_t = [], [], []
            last = 0
            for c, r in zip(idx, chord_rows):
                if r in cut:
                    todo[c] = False
                    cuts.setdefault(n, []).append(c)
                    continue
                if r in inserts:
                    ps, gg = inserts[r]
                    new_p.append(p[last:c + 1])
                    new_g.append(g[last:c + 1])
                    new_t.append(todo[last:c])
                    new_t.append(np.ones(len(ps) + 1, bool))
                    new_p.append(ps)
                    new_g.append(gg)
                    last = c + 1
                else:
                    todo[c] = False
            if last:
                new_p.append(p[last:])
                new_g.append(g[last:])
                new_t.append(todo[last:])
                p, g, todo = np.concatenate(new_p), np.concatenate(new_g), np.concatenate(new_t)
            state[n] = (k, p, g, todo)
        for n, chords in cuts.items():  # positions of cut chords after this round's insertions
            k, p, g, todo = state[n]
            at = _cut_positions(p, [state_before[n][1][c] for c in chords])
            pieces = np.split(np.arange(len(p)), [i + 1 for i in at])
            first = True
            for piece in pieces:
                if len(piece) < 2:
                    continue
                entry = (k, p[piece], g[piece], todo[piece[:-1]])
                if first:
                    state[n], first = entry, False
                else:
                    state.append(entry)
            if first:
                state[n] = (k, p[:1], g[:1], np.zeros(0, bool))
        state_before = list(state)
    return [(k, p) for k, p, _, _ in state if len(p) >= 2]


def _cut_positions(p, starts):
    """Indices in ``p`` of the given chord start points (each found once, in order)."""
    out = []
    for a in starts:
        hits = np.flatnonzero(np.all(p == a, axis=1))
        if hits.size:
            out.append(int(hits[0]))
    return sorted(set(out))


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
