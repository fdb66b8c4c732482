"""The admissible region of a blocking contour: polygons of the shifts at which the check passes.

The region is the set where every hard margin of :class:`~gearkit.blocking.field.PairField` (and
the backlash) is >= 0, inside the window. Its boundary is the zero set of

    ``R(x1, x2) = min(hard margins, backlash, distances to the window's edges)``

(-1 where no pair exists; :func:`~gearkit.blocking.arrays.evaluator`'s ``"region"``), traced by
:func:`~gearkit.blocking.level.zero_lines` on a grid padded by one ring of nodes outside the window
(so every component closes). Each loop is a polygon;
loops inside an odd number of others are holes. Outer boundaries are counter-clockwise, holes
clockwise, so a matplotlib path (non-zero winding) and the even-odd rule agree.
"""
from __future__ import annotations

import numpy as np

from gearkit.blocking.between import clear, neck
from gearkit.blocking.grid import grid_values
from gearkit.distances import edge_distances

__all__ = ["padded_grid", "pad", "orient_loops", "inside_polygons", "polygon_area", "best_point", "reconnect",
           "locate_chord", "drop_covered"]

SPLIT_DEPTH = 20  #: most self-crossings split out of one loop
FINE = 41  #: nodes per side of the local grid that looks for the best point of an empty region
SLIVER = 0.5  #: a loop split off narrower than this fraction of tol on average is a fold (_simple_loops)
RECONNECT_ROUNDS = 3  #: rounds of re-joining loops cut across a thin part (:func:`reconnect`)
PAIR_REACH = 4.0  #: two cuts pair when their middles lie within this many times the longer one apart
CHAIN_REACH = 32.0  #: ... or within this many, where F keeps the sign of their other side all the way between
CHAIN_SAMPLES = 4  #: ... read at least this many times per length of the shorter cut on that way


def polygon_area(p) -> float:
    """Signed area (shoelace) of the closed polygon ``p`` (n, 2); positive when counter-clockwise."""
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def inside_polygons(polygons, points) -> np.ndarray:
    """Even-odd membership of ``points`` (n, 2) in the closed ``polygons``."""
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    out = np.zeros(len(pts), dtype=bool)
    for poly in polygons:
        a, b = poly[:-1], poly[1:]
        x, y = pts[:, 0:1], pts[:, 1:2]
        cond = (a[None, :, 1] > y) != (b[None, :, 1] > y)
        with np.errstate(divide="ignore", invalid="ignore"):
            xc = a[None, :, 0] + (y - a[None, :, 1]) * (b[None, :, 0] - a[None, :, 0]) / (b[None, :, 1] - a[None, :, 1])
        out ^= (np.count_nonzero(cond & (x < xc), axis=1) % 2).astype(bool)
    return out


def padded_grid(xs, ys):
    """The grid ``xs`` x ``ys`` with one more node on every side (outside the window)."""
    dx, dy = xs[1] - xs[0], ys[1] - ys[0]
    return (np.concatenate([[xs[0] - dx], xs, [xs[-1] + dx]]), np.concatenate([[ys[0] - dy], ys, [ys[-1] + dy]]))


def pad(values, fill: float):
    """``values`` (m, n) inside a ring of ``fill``: the node values of :func:`padded_grid`."""
    out = np.full((values.shape[0] + 2, values.shape[1] + 2), fill)
    out[1:-1, 1:-1] = values
    return out


def _simple_loops(p, tol: float, depth: int = 0) -> list:
    """A closed loop split at its self-crossings into simple loops (a crossing of two of its edges
    within the tolerance band, e.g. where two parts of the region nearly touch); a loop split off whose
    mean width (4 area / perimeter) is below ``SLIVER tol`` is dropped: a fold of the loop's path, back
    along the line it came (beside a corner, a saddle's neck or a cut), not a part of the region."""
    from gearkit.curves import polyline_self_intersections

    ei, ej, ti, _ = polyline_self_intersections(p)
    if not ei.size or depth > SPLIT_DEPTH:
        return [p]
    i, j = int(ei[0]), int(ej[0])
    x = p[i] + ti[0] * (p[i + 1] - p[i])
    a = np.vstack([p[:i + 1], x[None], p[j + 1:]])
    b = np.vstack([x[None], p[i + 1:j + 1], x[None]])
    wide = [q for q in (a, b) if len(q) >= 4 and 4 * abs(polygon_area(q)) >= SLIVER * tol * _perimeter(q)]
    return [q for part in wide for q in _simple_loops(part, tol, depth + 1)]


def _perimeter(p) -> float:
    return float(np.sum(np.hypot(*np.diff(p, axis=0).T)))


def orient_loops(loops, window, tol: float) -> tuple:
    """The region's polygons from the traced loops of ``R = 0``: closed, clipped to the window,
    slivers below the tolerance dropped, outer boundaries counter-clockwise and holes clockwise."""
    lo = np.array([window[0], window[2]])
    hi = np.array([window[1], window[3]])
    closed = []
    for p in loops:
        if len(p) < 3:
            continue
        if not np.array_equal(p[0], p[-1]):
            p = np.vstack([p, p[:1]])
        p = np.clip(p, lo, hi)
        if abs(polygon_area(p)) > (10 * tol) ** 2 or len(p) > 6:
            closed.append(p)
    closed = [q for p in closed for q in _simple_loops(p, tol)]
    out = []
    for i, p in enumerate(closed):
        others = [q for j, q in enumerate(closed) if j != i]
        hole = bool(inside_polygons(others, p[:1])[0]) if others else False
        if (polygon_area(p) > 0) == hole:
            p = p[::-1].copy()
        out.append(p)
    return tuple(out)


def best_point(R, which, window, xs, ys, values):
    """The point of the window where ``R`` (function ``which`` of an array function, see
    :mod:`gearkit.blocking.level`) is largest: the best grid node, then finer local grids."""
    v = np.where(np.isfinite(values), values, -np.inf)
    j, i = np.unravel_index(np.argmax(v), v.shape)
    x, y = float(xs[i]), float(ys[j])
    hx, hy = xs[1] - xs[0], ys[1] - ys[0]
    for _ in range(3):
        fx = np.clip(np.linspace(x - hx, x + hx, FINE), window[0], window[1])
        fy = np.clip(np.linspace(y - hy, y + hy, FINE), window[2], window[3])
        fv = grid_values(R, fx, fy, which)
        jj, ii = np.unravel_index(np.argmax(np.where(np.isfinite(fv), fv, -np.inf)), fv.shape)
        x, y = float(fx[ii]), float(fy[jj])
        hx, hy = 2 * hx / (FINE - 1), 2 * hy / (FINE - 1)
    return x, y


def reconnect(F, lines, kept, tol: float, refine) -> list:
    """Closed polylines of measured curves (``[(k, points, slopes)]``, ``F_k`` positive on their left)
    re-joined where the grid took the wrong side of a saddle: a part of the region (or of its outside)
    narrower than a grid cell, a strip or a neck between two corners, that marching squares cut across
    (33/78 at tol 1e-5: a strip of interference.2 0.02 wide cut 0.01 off its edges; 21/52: the neck of
    the interference.1 saddle at (1, -1), where the check forgives 1e-9, cut 5e-5 off). Each cut is a
    chord of ``kept`` (no zero across it, see :func:`~gearkit.blocking.refinement.densify`) longer than
    ``tol``. Two of them, ``P1 -> Q1`` and ``P2 -> Q2``, running opposite ways with each on the same
    side of the other, where ``F`` halfway between their middles has the sign of the other side (the
    polylines leave out, or take in, the part between them), become ``P1 -> Q2`` and ``P2 -> Q1`` (two
    loops become one, or one loop two); so do two such chords farther apart (up to ``CHAIN_REACH`` times the
    longer), where ``F`` has the sign of the other side all the way from one middle to the other: the links of the
    grid's chain of diamonds along a strip narrower than a grid cell (:func:`~gearkit.blocking.between.clear`). Where ``F`` there has their
    side's sign and the chords lie in two loops, each chord's middle inside the other loop, both loops take the part
    between them (32/77 at tol 1e-3: a strip of the region cut across twice, the part between the cuts left out by
    the even-odd rule, 10 tol off): the two loops become one along their lines, their vertices between the chords
    dropped. The lines changed are refined again by ``refine(lines, kept)``
    (:func:`~gearkit.blocking.refinement.densify`, which adds the chords it finds no zero across to the new
    ``kept``), round after round (``RECONNECT_ROUNDS``); ``kept`` is extended by their chords kept. The
    joined lines still holding a cut that paired with none are refined once more by ``refine(lines, None, rest)``
    (``rest``: the other lines, ``[(k, points)]``): no cut is then left alone as across a flat strip
    (:func:`~gearkit.blocking.corners.corner_splits`; a strip's last cut short of its end: 25/59 internal at tol
    1e-3, 5.6 tol off), and one across a flat strip is carried down it to its end where neither these lines nor
    ``rest`` cross the way (:func:`~gearkit.blocking.flats.carry_down`). A loop holding a cut that lies
    inside another loop of the same sense is dropped (:func:`drop_covered`): its part is held already."""
    todo, joined = list(kept), set()
    for _ in range(RECONNECT_ROUNDS):
        lines, changed = _rejoin(F, lines, todo, tol)
        if not changed:
            break
        todo = []
        new = refine([lines[n] for n in changed], todo)
        lines = [lines[n] for n in range(len(lines)) if n not in changed] + new
        joined = {id(q) for _, q, _ in lines} & joined | {id(q) for _, q, _ in new}
        kept += todo
    left = {w[0] for w in (locate_chord(lines, k, a, b) for k, a, b in kept) if w is not None} \
        & {n for n, (_, q, _) in enumerate(lines) if id(q) in joined}
    if left:  # a joined loop's cuts not re-joined: refined with none left alone (no flat strip across them)
        rest = [lines[n] for n in range(len(lines)) if n not in left]
        lines = rest + refine([lines[n] for n in sorted(left)], None, [(k, q) for k, q, _ in rest])
    return drop_covered(lines, kept, tol)


def drop_covered(lines, kept, tol: float) -> list:
    """``lines`` without the loops holding a cut (a chord of ``kept``) that lie inside another closed
    polyline of their curve of the same sense (``F`` positive inside both, or negative inside both) with
    none of the other sense between: a link of the grid's chain of diamonds along a strip narrower than a
    grid cell whose part another loop's line, refined down the strip (or re-joined along it), already
    holds. Taken twice, the part would be left out by the even-odd rule (52/75 and 41/80 internal at tol
    1e-3: the link was then carried to the wedge's tip beside the other, 12.5 and 11.4 tol off). Again once
    the wedges are carried to their tips (:func:`~gearkit.blocking.tips.carry_to_tips`): a link too far from
    the next one's cut to pair with it, carried to the tip the other loop was carried to (52/75 at tol 1e-5,
    215 tol off). Inside: every vertex and chord middle inside the other or within ``tol`` of its outline,
    the vertices' mean inside it. A loop holding both ends of a cut as vertices holds it too: the cut split beside
    a corner by the last refinement of :func:`reconnect` (given no ``kept``, its pieces are not noted), at the
    strip's edge beside its end (36/82 z0 18 internal at tol 1e-3: a link so split, carried to the wedge's tip
    inside the loop carried there already, its piece across the strip 4.5 tol off)."""
    closed = [n for n, (_, q, _) in enumerate(lines) if len(q) > 3 and np.array_equal(q[0], q[-1])]
    verts = {n: set(map(tuple, lines[n][1].tolist())) for n in closed}
    links = {n for n in closed for k, a, b in kept if lines[n][0] == k and {tuple(a), tuple(b)} <= verts[n]}
    area = {n: polygon_area(lines[n][1]) for n in closed}
    drop = set()
    for n in sorted(links):
        k, q, _ = lines[n]
        pts = np.vstack([q[:-1], 0.5 * (q[:-1] + q[1:])])
        mean = q[:-1].mean(axis=0)[None]
        around = [m for m in closed if m != n and lines[m][0] == k and abs(area[m]) > abs(area[n])
                  and inside_polygons([lines[m][1]], mean)[0]
                  and np.all(inside_polygons([lines[m][1]], pts) | (edge_distances(pts, lines[m][1]) <= tol))]
        if around and area[min(around, key=lambda m: abs(area[m]))] * area[n] > 0:
            drop.add(n)
    return [line for n, line in enumerate(lines) if n not in drop]


def _rejoin(F, lines, kept, tol: float):
    """One round of :func:`reconnect`: the lines and the indices of those changed."""
    lines = list(lines)
    cuts = []
    for k, a, b in kept:
        if np.hypot(*(b - a)) > tol and locate_chord(lines, k, a, b) is not None:
            cuts.append((k, tuple(a), tuple(b)))
    cuts = sorted(set(cuts))
    if not cuts:
        return lines, []
    K = np.array([c[0] for c in cuts])
    P, Q = np.array([c[1] for c in cuts]), np.array([c[2] for c in cuts])
    D, M = Q - P, 0.5 * (P + Q)
    L = np.hypot(D[:, 0], D[:, 1])
    used, changed = set(), set()
    if len(cuts) >= 2:
        u, v = np.triu_indices(len(cuts), 1)
        gap = 0.5 * (M[u] + M[v])
        side_u = np.sign(D[u, 0] * (gap - P[u])[:, 1] - D[u, 1] * (gap - P[u])[:, 0])
        side_v = np.sign(D[v, 0] * (gap - P[v])[:, 1] - D[v, 1] * (gap - P[v])[:, 0])
        near = np.hypot(*(M[u] - M[v]).T)
        ok = (K[u] == K[v]) & (np.einsum("ij,ij->i", D[u], D[v]) < 0) & (side_u == side_v) & (side_u != 0) \
            & (near <= CHAIN_REACH * np.fmax(L[u], L[v]))
        u, v, gap, side, near = u[ok], v[ok], gap[ok], side_u[ok], near[ok]
        fg = F(gap, K[u]) if u.size else np.zeros(0)
        close = near <= PAIR_REACH * np.fmax(L[u], L[v])
        # where F has a saddle between the chords, its sign there, not halfway between their middles (between.neck)
        sad = np.array([neck(F, K[a], P[a], Q[a], P[b], Q[b], tol) if c else 0.0 for a, b, c in zip(u, v, close)])
        sg = np.where(sad != 0, sad, np.sign(fg))
        wrong = np.isfinite(fg) & (sg == -side)  # F there has the sign of the chords' other side
        held = np.isfinite(fg) & (sg == side) & close  # ... or of their side: taken twice when in two loops
        # farther apart, two links of the grid's chain of diamonds along a strip narrower than a grid cell: paired
        # where F keeps that sign all the way from one middle to the other (33/63 at tol 1e-3: interference.1 and .2
        # bound a strip 0.013 wide, its links 0.07 to 0.1 apart, each cut across it 0.013 long; the links left
        # alone were each carried to the strip's far corner, the triangle it widens into held three times)
        far = np.flatnonzero(wrong & ~close)
        if far.size:
            wrong[far] = clear(F, K[u[far]], M[u[far]], M[v[far]], -side[far],
                                np.fmin(L[u[far]], L[v[far]]) / CHAIN_SAMPLES)
        for t in np.argsort(near):
            if u[t] in used or v[t] in used:
                continue
            chords = K[u[t]], P[u[t]], Q[u[t]], P[v[t]], Q[v[t]]
            if wrong[t]:
                used |= {int(u[t]), int(v[t])}
                lines, changed = _swap(lines, changed, *chords)
            elif held[t] and _overlap(lines, *chords):
                used |= {int(u[t]), int(v[t])}
                lines, changed = _swap(lines, changed, *chords, side=side[t])
    return lines, sorted(changed)


def _overlap(lines, k, p1, q1, p2, q2) -> bool:
    """True when the chords ``p1 -> q1`` and ``p2 -> q2`` lie in two loops, each chord's middle inside
    the other's loop: the part between them is taken by both (see :func:`reconnect`)."""
    w1, w2 = locate_chord(lines, k, p1, q1), locate_chord(lines, k, p2, q2)
    if w1 is None or w2 is None or w1[0] == w2[0]:
        return False
    return bool(inside_polygons([lines[w2[0]][1]], 0.5 * (p1 + q1))[0]
                and inside_polygons([lines[w1[0]][1]], 0.5 * (p2 + q2))[0])


def locate_chord(lines, k, a, b):
    """(line, index) of the chord ``a -> b`` of a closed polyline of curve ``k`` in ``lines``, or None."""
    a, b = np.asarray(a), np.asarray(b)
    for m, (kk, q, _) in enumerate(lines):
        if kk == k and len(q) > 3 and np.array_equal(q[0], q[-1]):
            at = np.flatnonzero(np.all(q[:-1] == a, axis=1) & np.all(q[1:] == b, axis=1))
            if at.size:
                return m, int(at[0])
    return None


def _replace(lines, changed, drop, new):
    """``lines`` without the indices ``drop``, with ``new`` at the end; ``changed`` renumbered and the
    new ones added."""
    keep = [m for m in range(len(lines)) if m not in drop]
    renum = {m: i for i, m in enumerate(keep)}
    changed = {renum[c] for c in changed if c in renum} | set(range(len(keep), len(keep) + len(new)))
    return [lines[m] for m in keep] + new, changed


def _swap(lines, changed, k, p1, q1, p2, q2, side=0):
    """The chords ``p1 -> q1`` and ``p2 -> q2`` of closed polylines replaced by ``p1 -> q2`` and
    ``p2 -> q1`` (see :func:`reconnect`). ``side`` (+-1: the part between the chords on their left or
    right, taken by both loops): the loops joined along their lines instead, each loop's vertices
    between the chords dropped, ``q1 ... p1`` becoming ``p2 ... q2`` and ``q2 ... p2`` becoming
    ``p1 ... q1``."""
    w1, w2 = locate_chord(lines, k, p1, q1), locate_chord(lines, k, p2, q2)
    if w1 is None or w2 is None:
        return lines, changed
    (m1, j1), (m2, j2) = w1, w2
    if m1 != m2 and side:  # p2, (q1 ... p1 outside the part between), q2, then p1, (q2 ... p2 outside), q1
        a, ga = _from(lines[m1], j1)
        b, gb = _from(lines[m2], j2)
        ia, ib = _outside(a, side, p1, q1, p2, q2), _outside(b, side, p1, q1, p2, q2)
        if ia is None or ib is None:
            return lines, changed
        ring = np.vstack([b[-1:], a[ia], b[:1], a[-1:], b[ib], a[:1], b[-1:]])
        new = [(k, ring, np.concatenate([gb[-1:], ga[ia], gb[:1], ga[-1:], gb[ib], ga[:1], gb[-1:]]))]
    elif m1 != m2:  # q1 ... p1 then q2 ... p2, closed at q1
        a, ga = _from(lines[m1], j1)
        b, gb = _from(lines[m2], j2)
        new = [(k, np.vstack([a, b, a[:1]]), np.concatenate([ga, gb, ga[:1]]))]
    else:  # one loop in two: q1 ... p2 closed at q1, q2 ... p1 closed at q2
        a, ga = _from(lines[m1], j1)
        s = (j2 - j1) % (len(lines[m1][1]) - 1)  # q2's place from q1
        new = [(k, np.vstack([a[:s], a[:1]]), np.concatenate([ga[:s], ga[:1]])),
               (k, np.vstack([a[s:], a[s:s + 1]]), np.concatenate([ga[s:], ga[s:s + 1]]))]
    return _replace(lines, changed, {m1, m2}, new)


def _outside(a, side, p1, q1, p2, q2):
    """Indices of the inner vertices of the open path ``a`` (a loop from a chord's end round to its start)
    outside the part between the chords ``p1 -> q1`` and ``p2 -> q2`` (on the ``side`` of both): from
    each end up to the vertex farthest from the chords, the stretch of vertices near them is dropped up
    to its last vertex between them (a fold of the path beside a cut, past the other chord and back,
    goes with it). None where nothing is left or the farthest vertex lies between them, near them."""
    between = np.ones(len(a), dtype=bool)
    for p, q in ((p1, q1), (p2, q2)):
        d = q - p
        between &= side * (d[0] * (a[:, 1] - p[1]) - d[1] * (a[:, 0] - p[0])) > 0
    m1, m2 = 0.5 * (p1 + q1), 0.5 * (p2 + q2)
    reach = np.hypot(*(m2 - m1)) + max(np.hypot(*(q1 - p1)), np.hypot(*(q2 - p2)))
    dist = np.hypot(*(a - 0.5 * (m1 + m2)).T)
    dist[[0, -1]] = -np.inf
    top = int(np.argmax(dist))
    if len(a) < 3 or (between[top] and dist[top] <= reach):  # (far off, the two sides' wedge is no strip)
        return None
    go = np.flatnonzero(dist[1:top] > reach)  # the stretches near the chords: to the first far vertex
    lead = np.flatnonzero(between[1:1 + go[0] if go.size else top]) + 1
    back = np.flatnonzero(dist[top + 1:-1] > reach) + top + 1
    start = back[-1] + 1 if back.size else top + 1
    trail = np.flatnonzero(between[start:-1]) + start
    keep = np.arange(lead[-1] + 1 if lead.size else 1, trail[0] if trail.size else len(a) - 1)
    return keep if keep.size else None


def _from(line, j):
    """The closed polyline ``line`` (k, points, slopes) opened at its chord ``j``: its vertices from
    the chord's end round to its start (each once), and their slopes."""
    _, q, g = line
    n = len(q) - 1
    idx = (np.arange(n) + j + 1) % n
    return q[:-1][idx], g[:-1][idx]
