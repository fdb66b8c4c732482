"""The exact measure of a traced blocking contour (the bench's ladder and contract rows,
:mod:`gearkit.bench.blocking`): the distance of each vertex and chord middle of its lines and region
from the exact zero sets of their functions, solved on rays to round-off."""
from __future__ import annotations

import numpy as np

from gearkit.bench.topology import MEASURE_TOL, ROUND_OFF, leg, line_evaluator

__all__ = ["deviation", "polyline_deviation", "point_distances"]

RAY_ROUNDS = 10  #: ray lengths tol / 16 ... tol 4**8: the nearest zero first
SHORT_RATIO = 8.0  #: below tol / 16, the normal is sampled at distances shrinking by this factor
FLOOR = 1e-13  #: ... down to this fraction of the window's diagonal (round-off)
EDGE_BISECTIONS = 50  #: the ray along the no-pair edge to pi/4 * 2**-50 rad (see _along_edge)
FAN_ANGLES, FAN_STEPS = 64, 16  #: a point whose rays' nearest zero is farther than tol: a fan of samples (_fan)


def deviation(contour) -> float:
    """Largest distance of the contour's traced lines and region boundary from the exact zero sets
    (at each vertex and each chord's middle: the nearest zero on eight rays, and a vertex's on its corner's
    bisector, to ``MEASURE_TOL``). A line
    whose margin is ``|a| - |b|`` (the sliding line) has the zeros of ``a - b`` and of ``a + b``: each
    point is measured to the nearer of the two (the factors' own zero sets, not ``|a| - |b|``'s: where
    they cross at a small angle ``|a| - |b|`` changes sign only across a sliver far narrower than the
    rays' steps beside the crossing, and a chord 0.4 tol from its line read 11.5 tol, 9/21 at tol 1e-5;
    nor one factor per component: a component ending on the other factor's zeros, 13/45 at 1e-5, read
    9.2 tol where it is 0.59).

    Examples
    --------
    >>> from gearkit.blocking import blocking_contour
    >>> from gearkit.pair import PairSpec
    >>> c = blocking_contour(PairSpec(13, 16, 1.0), tol=1e-4, lines=["undercut.1"])
    >>> deviation(c) <= 1e-4
    True
    """
    F, legs = line_evaluator(contour)
    span = _span(contour.window)
    plain = [(k, c) for k, ln in enumerate(contour.lines) if not legs[k] for c in ln.components]
    plain += [(len(contour.lines), p) for p in contour.region]
    worst = polyline_deviation(F, plain, contour.tol, span)
    factored = [(legs[k], c) for k, ln in enumerate(contour.lines) if legs[k] for c in ln.components]
    if factored:  # each point to the nearer of its factors' zero sets: its own first (the component's),
        own = [leg(F, w, c) for w, c in factored]  # the others where that is farther than the worst yet
        d = point_distances(F, [(w[j], c) for (w, c), j in zip(factored, own)], contour.tol, span)
        for i in range(1, len(factored[0][0])):
            far = d > worst
            if far.any():
                d = np.minimum(d, np.where(far, point_distances(
                    F, [(w[(j + i) % len(w)], c) for (w, c), j in zip(factored, own)], contour.tol, span, far), np.inf))
        worst = max(worst, float(d.max()) if d.size else 0.0)
    return worst


def polyline_deviation(F, polys, tol: float, span: float) -> float:
    """Largest distance of the polylines ``polys`` (``[(k, (n, 2))]``: function ``k`` of ``F``) from
    the zero sets of their functions, at each vertex and chord middle: the nearest zero on eight rays
    (the chord's normal, the chord, the diagonals; at a vertex also the two ways of its corner's bisector,
    which alone reaches inside an acute corner of the zero set, 52/75 z0 15's region at tol 1e-3: a vertex
    1e-7 from the tip of a 6-degree corner read 75 tol) of lengths ``tol / 16`` ... ``tol * 4**8``, solved
    to ``MEASURE_TOL`` (beside the no-pair edge, where none of them finds one, also on the ray along the
    edge: :func:`_along_edge`), and, where none lies within ``tol / 16``, along the normal at distances
    shrinking to round-off (``span``: the window's diagonal): a strip narrower than ``tol / 16``
    beside a point (both its zeros crossed by the shortest ray) is seen.

    Examples
    --------
    >>> F = lambda p, k: 1e12 * p[:, 1] * (p[:, 1] - 1e-6) * (p[:, 1] - 0.3)  # zeros y = 0, 1e-6, 0.3
    >>> line = np.array([[0.0, -1e-7], [1.0, -1e-7]])  # 1e-7 below the strip 0 < y < 1e-6
    >>> bool(abs(polyline_deviation(F, [(0, line)], 1e-3, 1.0) - 1e-7) < 1e-12)
    True
    """
    d = point_distances(F, polys, tol, span)
    return float(d.max()) if d.size else 0.0


def point_distances(F, polys, tol: float, span: float, keep=None) -> np.ndarray:
    """What :func:`polyline_deviation` takes the largest of: the distance of each vertex but the last
    and each chord's middle of the polylines ``polys`` from their function's zero set, in that order
    (0 where the function is at round-off or undefined, or where the mask ``keep`` is False).

    >>> F = lambda p, k: p[:, 1] - 0.5
    >>> point_distances(F, [(0, np.array([[0.0, 0.4], [1.0, 0.4]]))], 1e-3, 1.0).round(12).tolist()
    [0.1, 0.1]
    """
    from gearkit.blocking.brackets import segment_roots
    from gearkit.blocking.edges import toward_edge

    pts, nrm, bis, ids = [], [], [], []
    for k, c in polys:
        if len(c) < 2:
            continue
        d = np.diff(c, axis=0)
        n = np.column_stack([-d[:, 1], d[:, 0]]) / np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-300)[:, None]
        pts += [c[:-1], 0.5 * (c[:-1] + c[1:])]
        nrm += [n, n]
        bis += [_corner_rays(c, d), np.full(d.shape, np.nan)]
        ids.append(np.full(2 * len(d), k))
    if not pts:
        return np.zeros(0)
    P, N, K = np.concatenate(pts), np.concatenate(nrm), np.concatenate(ids)
    C = np.concatenate(bis)
    f0 = F(P, K)
    dist = np.zeros(len(P))
    # |F| at round-off: on the zero set (also where F only touches zero, with no sign change near)
    todo = np.flatnonzero(np.isfinite(f0) & (np.abs(f0) > ROUND_OFF) & (True if keep is None else keep))
    # rays start short (a ray across a strip narrower than itself sees no sign change) and grow
    r = tol / 16
    T = np.column_stack([N[:, 1], -N[:, 0]])
    rays = [s * D for D in (N, T, (N + T) / np.sqrt(2), (N - T) / np.sqrt(2), C) for s in (1.0, -1.0)]
    angles = np.pi / 4 * np.array([2, 6, 0, 4, 1, 5, 3, 7])  # of the first 8 rays from T towards N (for _along_edge)
    for rnd in range(RAY_ROUNDS):  # the nearest zero on the rays, growing (the normal, the chord, diagonals, bisector)
        if not todo.size:
            break
        if rnd == 1:  # none within tol / 16: a strip narrower than that beside the point, along the normal
            near = _short_zero(F, P[todo], N[todo], f0[todo], K[todo], tol / 16, span, dist, todo)
            todo = todo[~near]
            if not todo.size:
                break
        best = np.full(todo.size, np.inf)
        ends_out = np.zeros((len(rays), todo.size), dtype=bool)
        for D, out in zip(rays, ends_out):
            end = P[todo] + r * D[todo]
            fe = np.full(todo.size, np.nan)
            own = np.isfinite(end[:, 0])  # a corner's bisector: at the vertices only
            fe[own] = F(end[own], K[todo[own]])
            edge = np.isnan(fe) & own
            out[:] = edge
            if edge.any():  # a ray into the no-pair area ends at its edge: the sign change nearest before it
                i = todo[edge]
                lo, flo, hi, fhi = toward_edge(F, P[i], f0[i], end[edge], K[i])
                found = np.any(lo != hi, axis=1)
                end[edge] = np.where(found[:, None], hi, end[edge])
                fe[edge] = np.where(found, fhi, fe[edge])
            hit = np.isfinite(fe) & ((fe > 0) != (f0[todo] > 0))
            if hit.any():
                i = todo[hit]
                root = segment_roots(F, P[i], end[hit], f0[i], fe[hit], MEASURE_TOL, K[i])
                best[hit] = np.minimum(best[hit], np.hypot(*(root - P[i]).T))
        fixed = ends_out[:len(angles)]  # the eight fixed rays' (the bisector's is no neighbour of theirs)
        none = np.isinf(best) & fixed.any(axis=0)  # beside the no-pair edge, no zero on the rays: along it
        if none.any():
            i = todo[none]
            best[none] = _along_edge(F, P[i], T[i], N[i], f0[i], K[i], r, angles, fixed[:, none])
        found = np.isfinite(best)
        dist[todo[found]] = best[found]
        todo = todo[~found]
        r *= 4
    if todo.size:  # no zero along the normal (F only nears zero there): |F| / |grad F|, first order
        e = 1e-7
        g = np.hypot(F(P[todo] + [e, 0.0], K[todo]) - f0[todo], F(P[todo] + [0.0, e], K[todo]) - f0[todo]) / e
        with np.errstate(divide="ignore", invalid="ignore"):
            est = np.abs(f0[todo]) / g
        dist[todo] = np.where(np.isfinite(est), est, r / 4)
    far = np.flatnonzero(dist > tol)
    if far.size:
        dist[far] = _fan(F, P[far], f0[far], K[far], dist[far])
    return dist


def _along_edge(F, P, T, N, f0, K, r, angles, ends_out) -> np.ndarray:
    """Distance from each point ``P`` to the nearest zero on the ray of length ``r`` that runs along the
    edge of the no-pair area (inf where there is none): between two neighbouring rays (``angles`` from
    ``T`` towards ``N``) of which one ends in that area (``ends_out``, per ray and point) and the other
    does not, the angle is bisected to the last ray whose end is defined. A line ending on the edge
    leaves it at any angle: where that angle is small, its zeros on one side of it fill only the
    wedge between the line and the edge, which the eight fixed rays may all miss at every length (51/127
    z0 19 at tol 1e-3: a contact-ratio line's end on the edge read 4.2 mm off, 2.2e-8 from its zero
    there); the ray along the edge runs inside that wedge at any length."""
    from gearkit.blocking.brackets import segment_roots

    best = np.full(len(P), np.inf)
    order = np.argsort(angles)
    for a, b in zip(order, np.roll(order, -1)):
        i = np.flatnonzero(ends_out[a] != ends_out[b])
        if not i.size:
            continue
        ta, tb = angles[a], angles[b] + (2 * np.pi if b == order[0] else 0.0)
        lo = np.where(ends_out[a][i], tb, ta)  # the angle whose end is defined
        hi = np.where(ends_out[a][i], ta, tb)
        for _ in range(EDGE_BISECTIONS):
            mid = 0.5 * (lo + hi)
            inside = np.isfinite(F(P[i] + r * _direction(T[i], N[i], mid), K[i]))
            lo, hi = np.where(inside, mid, lo), np.where(inside, hi, mid)
        end = P[i] + r * _direction(T[i], N[i], lo)
        fe = F(end, K[i])
        hit = np.isfinite(fe) & ((fe > 0) != (f0[i] > 0))
        if hit.any():
            j = i[hit]
            root = segment_roots(F, P[j], end[hit], f0[j], fe[hit], MEASURE_TOL, K[j])
            best[j] = np.minimum(best[j], np.hypot(*(root - P[j]).T))
    return best


def _fan(F, P, f0, K, reach) -> np.ndarray:
    """The distance from each point ``P`` to the nearest zero of ``F`` on ``FAN_ANGLES`` rays all round
    it, sampled at ``FAN_STEPS`` steps out to ``reach`` (the nearest zero found on the nine rays), the
    first sign change on each solved to ``MEASURE_TOL``; ``reach`` where it is nearer. Where the nearest
    zero is the tip of a thin wedge of the other sign (two of them meeting at a saddle, internal 58/63
    z0 16's interference.1 at tol 1e-3) the nine rays pass beside it and meet a zero farther on: a point
    0.54 tol from the tip read 3.69 tol.

    >>> F = lambda p, k: p[:, 1] - 0.3  # the line x2 = 0.3, seen from the origin with reach 1
    >>> d = _fan(F, np.zeros((1, 2)), np.array([-0.3]), np.zeros(1), np.ones(1))[0]
    >>> bool(0.3 <= d < 0.3 / np.cos(np.pi / FAN_ANGLES) + 1e-12)  # on the ray nearest the normal
    True
    """
    from gearkit.blocking.brackets import segment_roots

    a = 2 * np.pi * (np.arange(FAN_ANGLES) + 0.5) / FAN_ANGLES
    U = np.column_stack([np.cos(a), np.sin(a)])
    s = np.arange(1, FAN_STEPS + 1) / FAN_STEPS
    Q = P[:, None, None, :] + (reach[:, None] * s)[:, :, None, None] * U  # (points, steps, angles, 2)
    n = len(P)
    V = F(Q.reshape(-1, 2), np.repeat(K, FAN_STEPS * FAN_ANGLES)).reshape(n, FAN_STEPS, FAN_ANGLES)
    W = np.concatenate([np.broadcast_to(f0[:, None, None], (n, 1, FAN_ANGLES)), V], axis=1)
    ch = np.isfinite(W[:, :-1]) & np.isfinite(W[:, 1:]) & ((W[:, :-1] > 0) != (W[:, 1:] > 0))
    j = np.argmax(ch, axis=1)  # (points, angles): the first sign change out along each ray
    i, k = np.nonzero(np.take_along_axis(ch, j[:, None, :], axis=1)[:, 0])
    best = reach.copy()
    if not i.size:
        return best
    j = j[i, k]
    lo = np.where((j > 0)[:, None], Q[i, np.maximum(j - 1, 0), k], P[i])
    root = segment_roots(F, lo, Q[i, j, k], W[i, j, k], W[i, j + 1, k], MEASURE_TOL, K[i])
    np.minimum.at(best, i, np.hypot(*(root - P[i]).T))
    return best


def _direction(T, N, angle):
    """Unit vectors at ``angle`` (radians) from ``T`` towards ``N``."""
    return np.cos(angle)[:, None] * T + np.sin(angle)[:, None] * N


def _corner_rays(c, d) -> np.ndarray:
    """The unit bisectors of the polyline ``c``'s corners at its vertices but the last (``d``: its
    chords; a closed one's first vertex between its last chord and its first, an open one's first
    vertex NaN): where the line follows an acute corner of its zero set (the region's, where two
    margins' zeros cross at a few degrees) the corner's inside is narrower than the rays' 45 degrees,
    and only its bisector reaches it."""
    u = d / np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-300)[:, None]
    back = np.vstack([u[-1:] if np.array_equal(c[0], c[-1]) else np.full((1, 2), np.nan), u[:-1]])
    b = u - back
    with np.errstate(invalid="ignore", divide="ignore"):
        return b / np.hypot(b[:, 0], b[:, 1])[:, None]


def _span(window) -> float:
    """The window's diagonal."""
    return float(np.hypot(window[1] - window[0], window[3] - window[2]))


def _short_zero(F, P, N, f0, K, reach, span, dist, at):
    """True where a zero lies on the normal through ``P`` closer than ``reach``: samples at distances
    shrinking by ``SHORT_RATIO`` from ``reach`` down to round-off on both sides (beside the no-pair edge
    the margins vary as the cube root of the distance to it: a strip there may be 1e-6 wide at any
    tol), the sign change nearest to ``P`` solved to ``MEASURE_TOL``; its distance written to ``dist`` at
    ``at``."""
    from gearkit.blocking.brackets import segment_roots

    n = max(1, int(np.ceil(np.log(reach / (FLOOR * span)) / np.log(SHORT_RATIO))))
    d = reach * SHORT_RATIO ** -np.arange(n + 1)[::-1]  # ascending, up to reach
    best = np.full(len(P), np.inf)
    for s in (1.0, -1.0):
        Q = P[:, None, :] + s * d[None, :, None] * N[:, None, :]
        V = np.column_stack([f0, F(Q.reshape(-1, 2), np.repeat(K, d.size)).reshape(len(P), d.size)])
        ch = np.isfinite(V[:, :-1]) & np.isfinite(V[:, 1:]) & ((V[:, :-1] > 0) != (V[:, 1:] > 0))
        j = np.argmax(ch, axis=1)
        r = np.flatnonzero(ch[np.arange(len(P)), j])
        if not r.size:
            continue
        j = j[r]
        lo = np.where((j > 0)[:, None], Q[r, np.maximum(j - 1, 0)], P[r])
        root = segment_roots(F, lo, Q[r, j], V[r, j], V[r, j + 1], MEASURE_TOL, K[r])
        best[r] = np.minimum(best[r], np.hypot(*(root - P[r]).T))
    ok = np.isfinite(best)
    dist[at[ok]] = best[ok]
    return ok
