"""The edge of the area where a margin is defined (the no-pair area), seen from the lines beside it.

A margin ``F`` is undefined (NaN) where no pair exists. A zero of ``F`` beside that area may lie
closer to its edge than any grid node or ray sample: here the edge point between a defined and an
undefined point is solved for to round-off (:func:`edge_point`), and ``F`` is sampled
at distances from it shrinking geometrically to round-off (:func:`ladder`): a zero between a
sample and the edge is seen however close to the edge it lies. :func:`across` looks for the
nearest oriented zero along normals (for the continuation of :mod:`gearkit.blocking.ends`),
:func:`toward_edge` the nearest zero towards the edge (for the accuracy measure of the bench),
:func:`crossing_ends` which ends of lines beside the edge run into it (carried on to it there).

>>> import numpy as np
>>> F = lambda p, k: np.where(p[:, 0] < 1.0, p[:, 0] - (1.0 - 1e-9), np.nan)  # a zero 1e-9 before the edge
>>> lo, flo, hi, fhi = toward_edge(F, np.array([[0.0, 0.0]]), np.array([-1.0]), np.array([[2.0, 0.0]]), np.array([0]))
>>> bool(flo[0] < 0 < fhi[0]) and bool(1.0 - 1e-8 < lo[0, 0] <= hi[0, 0] < 1.0)
True
"""
from __future__ import annotations

import math

import numpy as np


__all__ = ["edge_point", "by_slack", "toward_edge", "touchdowns", "step_ends", "ladder", "nearest_change",
           "across", "crossing_ends", "EDGE_REACH"]

LADDER = 0.5  #: ratio of the geometric sample distances
FLOOR = 1e-13  #: the smallest sample distance, relative to the window's size
EDGE_ULPS = 8.0  #: :func:`across` samples from the edge down to this many units of round-off of its coordinates
SPLITS = 15  #: points per round of the multisection for the edge of the defined area
EDGE_REACH = 3.0  #: an end beside the no-pair area is carried on when its tangent meets the area's edge
#: within this many grid cell diagonals ...
EDGE_DEG = 20.0  #: ... at more than this angle to the edge (a line running along the edge is left as the
#: grid has it, at every tol alike)
EDGE_PROBE = 1e-4  #: ... and where ``F`` is regular at the edge (at the edge points of the rays either side of
#: the tangent, up from the edge from this fraction of the reach)
EDGE_GROWTH = 3.0  #: ... its differences over D, 4 D, 16 D from the edge grow by more than this (4 where
#: F is smooth; 4 ** (1/3) and 2 where it varies as the cube or square root of the distance to the edge,
#: as the margins that read the working pressure angle or a tip at its base circle do: their lines
#: meet the edge tangentially)
EDGE_FLAT = 1e-12  #: ... (differences at round-off: F does not vary up from the edge, regular)
EDGE_BUDGET = 2.0  #: ... and carried no farther than this times its distance to the edge along the tangent
EDGE_FAN_DEG = 10.0  #: the edge's direction there: from its points on rays this far either side of the tangent
GUARDS = np.array([0.1, 1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12])  #: fractions of the bracket about the false
#: position that :func:`by_slack` samples (2 * 7 + 1 = SPLITS points): the next bracket is about the first
#: guard beyond the false position's error
_EVEN = np.arange(1, SPLITS + 1) / (SPLITS + 1)  #: :func:`by_slack`'s even splits of a bracket ...
_GUARDS = np.concatenate([-GUARDS, [0.0], GUARDS[::-1]])  #: ... and its samples about a false position
_ZERO, _ONE = np.asarray(0.0), np.asarray(1.0)


def edge_point(F, a, b, which, span, within=None):
    """The last defined point from ``a`` (defined) towards ``b`` (undefined), to ``span * FLOOR``
    (or to ``within``, a length, where that is enough). With a measure of the undefined area
    (``F.slack``, see :func:`by_slack`) the edge is solved for; without, found by multisection."""
    close = FLOOR * span if within is None else max(float(within), FLOOR * span)
    if getattr(F, "slack", None) is not None and len(a):
        return by_slack(F.slack, a, b, which, close)
    return _multisection(F, a.copy(), b.copy(), which, close)


def _multisection(F, a, b, which, close):
    """:func:`edge_point` by multisection: ``SPLITS`` samples a round, the first undefined one kept."""
    n = len(a)
    t = np.arange(1, SPLITS + 1) / (SPLITS + 1)
    for _ in range(40):
        if not n or np.max(np.hypot(*(b - a).T)) <= close:
            break
        P = a[:, None, :] + t[None, :, None] * (b - a)[:, None, :]
        v = F(P.reshape(-1, 2), np.repeat(which, SPLITS)).reshape(n, SPLITS)
        bad = ~np.isfinite(v)
        j = np.where(bad.any(axis=1), np.argmax(bad, axis=1), SPLITS)  # first undefined sample
        r = np.arange(n)
        na = np.where((j > 0)[:, None], P[r, np.maximum(j - 1, 0)], a)
        nb = np.where((j < SPLITS)[:, None], P[r, np.minimum(j, SPLITS - 1)], b)
        a, b = na, nb
    return a


def by_slack(S, a, b, which, close):
    """:func:`edge_point` for a function ``F`` whose ``S = F.slack`` gives the conditions for ``F``
    to be defined, ``(n, K)``: all positive exactly where it is, each smooth and zero where it starts
    to fail (NaN where it has no measure). Each round samples ``SPLITS`` points between the last
    defined and the first undefined point found: where a condition is measured at both ends and
    fails at the far one, about the false position of the first such (guards at fractions ``GUARDS``
    of the bracket: a straight edge is met to round-off in one round, a curved one quadratically);
    elsewhere ``SPLITS`` even splits. The first undefined sample ends the bracket, as in the
    multisection.

    >>> S = lambda p, k: np.where(p[:, :1] < 1 / 3, 1 / 3 - p[:, :1], np.nan)  # no measure past x = 1/3
    >>> bool(abs(by_slack(S, np.array([[0.0, 0.0]]), np.array([[1.0, 0.0]]), np.array([0]), 1e-13)[0, 0] - 1 / 3) < 1e-13)
    True
    """
    n = len(a)
    d = b - a
    length = np.maximum(np.hypot(*d.T), 1e-300)
    lo, hi = np.zeros(n), np.ones(n)
    s_lo = s_hi = None
    even, guards = _EVEN, _GUARDS
    live = np.arange(n)
    for _ in range(40):
        live = live[(hi[live] - lo[live]) * length[live] > close]
        if not live.size:
            break
        w = hi[live] - lo[live]
        t = lo[live, None] + even[None, :] * w[:, None]
        if s_lo is not None:
            a_s, b_s = s_lo[live], s_hi[live]
            with np.errstate(invalid="ignore", divide="ignore"):
                fails = np.isfinite(a_s) & np.isfinite(b_s) & (a_s > 0) & (b_s <= 0)
                f = np.where(fails, a_s / (a_s - b_s), np.inf).min(axis=1)  # the first condition's false position
            m = np.isfinite(f).nonzero()[0]  # (f + guards is finite there: clipped by its bounds, as np.clip does)
            t[m] = lo[live[m], None] + np.minimum(np.maximum(f[m, None] + guards[None, :], _ZERO), _ONE) * w[m, None]
        P = a[live, None, :] + t[:, :, None] * d[live, None, :]
        if s_lo is None:  # the start's own measure, with the first samples
            v = S(np.concatenate([a, P.reshape(-1, 2)]), np.concatenate([which, np.repeat(which[live], SPLITS)]))
            s_lo, s_hi = v[:n].copy(), np.full((n, v.shape[1]), np.nan)
            v = v[n:].reshape(live.size, SPLITS, -1)  # (a segment already shorter than close takes none)
            hi[~(s_lo > 0).all(axis=1)] = 0.0  # a start that is not defined is its own edge (as in the multisection)
        else:
            v = S(P.reshape(-1, 2), np.repeat(which[live], SPLITS)).reshape(live.size, SPLITS, -1)
        within = (t > lo[live, None]) & (t < hi[live, None])
        ok = (v > 0).all(axis=2)
        inside, out = ok & within, ~ok & within
        j = np.where(out.any(axis=1), np.argmax(out, axis=1), SPLITS)  # the first undefined sample
        r = np.arange(live.size)
        before = inside & (np.arange(SPLITS)[None, :] < j[:, None])  # the defined samples before it
        k = np.where(before.any(axis=1), SPLITS - 1 - np.argmax(before[:, ::-1], axis=1), -1)
        got, cut = k >= 0, j < SPLITS
        lo[live[got]], s_lo[live[got]] = t[r[got], k[got]], v[r[got], k[got]]
        hi[live[cut]], s_hi[live[cut]] = t[r[cut], j[cut]], v[r[cut], j[cut]]
        s_lo[live[~got]] *= 0.5  # an end kept twice weighs half in the next false position: the
        s_hi[live[~cut]] *= 0.5  # other comes to the edge where the condition bends
        live = live[got | cut]  # (neither: every sample fell on an end of its bracket, at round-off)
    return a + lo[:, None] * d


def toward_edge(F, m, f0, out, which):
    """For points ``m`` (n, 2) where ``F`` is ``f0`` (defined) and ``out`` where it is not: the
    bracket ``(lo, f(lo), hi, f(hi))`` of the sign change nearest to ``m`` among samples from the
    edge of the defined area towards ``m`` (distances shrinking geometrically to round-off; the
    bracket is ``m``, ``m`` where there is none)."""
    span = float(np.max(np.hypot(*(out - m).T)))
    E = edge_point(F, m, out, which, span)
    toward = m - E
    d = np.concatenate([ladder(1.0, FLOOR / 8), [0.0]])
    P = E[:, None, :] + d[None, :, None] * toward[:, None, :]
    V = F(P.reshape(-1, 2), np.repeat(which, d.size)).reshape(len(m), d.size)
    V[:, 0] = f0
    fin = np.isfinite(V)
    ch = fin[:, :-1] & fin[:, 1:] & ((V[:, :-1] > 0) != (V[:, 1:] > 0))
    j = np.argmax(ch, axis=1)  # the first from m
    r = np.arange(len(m))
    ok = ch[r, j]
    lo = np.where(ok[:, None], P[r, j], m)
    hi = np.where(ok[:, None], P[r, j + 1], m)
    return lo, np.where(ok, V[r, j], f0), hi, np.where(ok, V[r, j + 1], f0)


def touchdowns(F, A, B, D, which, res):
    """For chords ``A`` -> ``B`` (n, 2) whose ends are zeros of ``F`` with none across the middle, the
    undefined area lying along ``D`` (unit, (n, 2)) from the middle: the points ``(TA, TB)`` where the
    line through each end meets the edge of the defined area on its way to the middle (NaN where it
    does not). Below a chord point ``C`` the edge is the last defined point along ``D`` within a
    chord's length; ``F`` there has the sign of the line's side towards the edge while the line runs
    between ``C`` and the edge, the other sign once it has met the edge: where it meets it is bisected
    along the chord to ``res`` (a line dipping to the edge between two lattice columns, beside it
    closer than any sample, is carried to where it meets it; NaN where that is the end itself). Each point
    returned is defined.

    >>> F = lambda p, k: np.where(p[:, 1] >= 0.0, p[:, 1] - 1e-3 * (16.0 * p[:, 0] ** 2 - 1.0), np.nan)
    >>> A, B = np.array([[-0.5, 3e-3]]), np.array([[0.5, 3e-3]])  # zeros; the line dips below y = 0 for |x| < 1/4
    >>> TA, TB = touchdowns(F, A, B, np.array([[0.0, -1.0]]), np.array([0]), 1e-9)
    >>> np.round(TA, 8).tolist(), np.round(TB, 8).tolist()
    ([[-0.25, 0.0]], [[0.25, 0.0]])
    """
    n = len(A)
    L = np.hypot(*(B - A).T)
    span = float(max(1.0, np.max(np.abs(np.concatenate([A, B]))))) if n else 1.0

    def below(t, rows):
        C = A[rows] + t[:, None] * (B[rows] - A[rows])
        far = C + L[rows, None] * D[rows]
        v = F(far, which[rows])
        out = np.isnan(v)
        E = far.copy()
        if out.any():
            E[out] = edge_point(F, C[out], far[out], which[rows][out], span)
            v[out] = F(E[out], which[rows][out])
        return E, v

    rows = np.concatenate([np.arange(n), np.arange(n)])
    lo = np.concatenate([np.zeros(n), np.ones(n)])  # from each end ...
    hi = np.full(2 * n, 0.5)  # ... to the middle
    _, v_lo = below(lo, rows)
    _, v_hi = below(hi, rows)
    live = np.isfinite(v_lo) & np.isfinite(v_hi) & ((v_lo > 0) != (v_hi > 0))
    s_lo = v_lo > 0
    u = np.arange(1, SPLITS + 1) / (SPLITS + 1)
    while True:  # multisection: the first of SPLITS samples from the end's side with the middle's sign
        go = np.flatnonzero(live & (np.abs(hi - lo) * L[rows] > res))
        if not go.size:
            break
        t = lo[go, None] + u[None, :] * (hi - lo)[go, None]
        _, v = below(t.ravel(), np.repeat(rows[go], SPLITS))
        v = v.reshape(go.size, SPLITS)
        other = ~(np.isfinite(v) & ((v > 0) == s_lo[go, None]))
        j = np.where(other.any(axis=1), np.argmax(other, axis=1), SPLITS)
        r = np.arange(go.size)
        lo[go] = np.where(j > 0, t[r, np.maximum(j - 1, 0)], lo[go])
        hi[go] = np.where(j < SPLITS, t[r, np.minimum(j, SPLITS - 1)], hi[go])
    T = np.full((2 * n, 2), np.nan)
    if live.any():
        T[live] = below(lo[live], rows[live])[0]
    ends = np.concatenate([A, B])
    T[np.hypot(*(T - ends).T) <= res] = np.nan  # the line meets the edge at its end already
    return T[:n], T[n:]


def step_ends(F, P, T, h, which, span, res):
    """The predictions ``Q = P + h T`` of steps from points ``P`` (n, 2) along ``T`` and, for those that
    leave the defined area (indices ``out``), the last defined point towards each (:func:`edge_point`, to
    ``res``) and, for a line running along the edge closer to it than its tangent's meeting with it, the
    edge's point a whole step ahead, reached from the defined side of the normal there (``h`` to the left
    where defined, else to the right; NaN where neither is): ``(Q, out, E, ahead)``, from one evaluation of
    ``F`` (the predictions and the points beside them) and one edge search.

    >>> F = lambda p, k: np.where(p[:, 1] >= p[:, 0] ** 2, 0.0, np.nan)  # defined above y = x^2
    >>> Q, out, E, q = step_ends(F, np.array([[0.0, 1e-9]]), np.array([[1.0, 0.0]]), np.array([0.5]), np.array([0]),
    ...                          1.0, 1e-12)
    >>> out.tolist(), bool(E[0, 0] < 1e-4), bool(abs(q[0, 0] - 0.5) < 1e-12 and abs(q[0, 1] - 0.25) < 1e-11)
    ([0], True, True)
    """
    Q = P + h[:, None] * T
    N = np.column_stack([-T[:, 1], T[:, 0]])
    left, right = Q + h[:, None] * N, Q + -1.0 * h[:, None] * N
    V = F(np.concatenate([Q, left, right]), np.concatenate([which, which, which])).reshape(3, -1)
    out = np.flatnonzero(np.isnan(V[0]))
    ok_l = np.isfinite(V[1, out])
    ok_r = ~ok_l & np.isfinite(V[2, out])
    E, ahead = np.zeros((0, 2)), np.full((out.size, 2), np.nan)
    if out.size:
        k = which[out]
        R = edge_point(F, np.concatenate([P[out], left[out][ok_l], right[out][ok_r]]),
                       np.concatenate([Q[out], Q[out][ok_l], Q[out][ok_r]]), np.concatenate([k, k[ok_l], k[ok_r]]),
                       span, res)
        n_l = out.size + np.count_nonzero(ok_l)
        E, ahead[ok_l], ahead[ok_r] = R[:out.size], R[out.size:n_l], R[n_l:]
    return Q, out, E, ahead


def ladder(h, floor):
    """Distances h, h LADDER, ... down to ``floor``."""
    n = max(1, int(math.ceil(math.log(max(h / floor, 1.0)) / -math.log(LADDER))) + 1)
    return h * LADDER ** np.arange(n)


def nearest_change(s, v, sigma):
    """Index i of the sign change between samples i, i + 1 (positions ``s`` sorted, values ``v``)
    nearest to s = 0 whose sign goes from -sigma to sigma along s; -1 when none."""
    fin = np.isfinite(v)
    pos = v > 0
    ok = fin[:-1] & fin[1:] & (pos[:-1] != pos[1:]) & (pos[1:] == (sigma > 0))
    idx = np.flatnonzero(ok)
    if not idx.size:
        return -1
    return int(idx[np.argmin(np.minimum(np.abs(s[idx]), np.abs(s[idx + 1])))])


def across(F, Q, N, reach, sig, which, span, floor=None):
    """Along the normals ``N`` through ``Q`` (within ``reach``): per point ``(s, v, c)``, samples at
    positions ``s`` along the normal with values ``v`` and the index ``c`` of the sign change nearest
    to ``Q`` with ``F`` going from ``-sig`` to ``sig`` (-1: none). The samples lie at distances
    shrinking geometrically from ``Q`` down to ``floor`` (default: round-off) and, where the normal
    runs into the undefined area, from that edge towards ``Q`` from round-off up (a zero closer to
    the edge than ``floor`` is seen)."""
    floor = FLOOR * span if floor is None else floor
    plans = []
    for h in reach:
        d = ladder(h, floor)
        plans.append(np.concatenate([-d, [0.0], d[::-1]]))
    sizes = [s.size for s in plans]
    rows = np.repeat(np.arange(len(plans)), sizes)  # each point's samples in one array (each as q + s n)
    S = np.concatenate(plans) if plans else np.zeros(0)
    V = np.split(F(Q[rows] + S[:, None] * N[rows], np.asarray(which)[rows]), np.cumsum(sizes)[:-1])
    out = [[s, v, nearest_change(s, v, sg)] for s, v, sg in zip(plans, V, sig)]
    edge = []  # (entry, s defined, s undefined)
    for e, (s, v, c) in enumerate(out):
        fin = np.isfinite(v)
        bnd = np.flatnonzero(fin[:-1] != fin[1:])
        if c < 0 and bnd.size:
            b = bnd[np.argmin(np.minimum(np.abs(s[bnd]), np.abs(s[bnd + 1])))]
            edge.append((e, s[b] if fin[b] else s[b + 1], s[b + 1] if fin[b] else s[b]))
    if edge:
        idx = np.array([e for e, _, _ in edge])
        A = Q[idx] + np.array([a for _, a, _ in edge])[:, None] * N[idx]
        B = Q[idx] + np.array([b for _, _, b in edge])[:, None] * N[idx]
        E = edge_point(F, A, B, which[idx], span)
        # from the edge down to the round-off of its coordinates (EDGE_ULPS), whatever ``floor``: a line
        # meeting the edge at a small angle runs closer to it than any sample about Q (the margins vary
        # as the cube root of the distance), and where it comes within the samples' reach of the edge
        # is where its front stops (12/30 at tol 1e-9: from FLOOR * span, 1e-12, the front stopped 1.8e-7
        # or 3.4e-9 short of the reference's as the edge point moved by 1e-13)
        ulp = EDGE_ULPS * np.finfo(float).eps * max(1.0, float(np.max(np.abs(E))))
        d = ladder(1.0, ulp / max(float(np.max(np.hypot(*(A - E).T))), 1e-300))
        P = E[:, None, :] + d[None, :, None] * (A - E)[:, None, :]
        W = F(P.reshape(-1, 2), np.repeat(which[idx], d.size)).reshape(len(idx), d.size)
        for r, e in enumerate(idx):
            s = np.concatenate([out[e][0], (P[r] - Q[e]) @ N[e]])
            v = np.concatenate([out[e][1], W[r]])
            o = np.argsort(s, kind="stable")
            out[e] = [s[o], v[o], nearest_change(s[o], v[o], sig[e])]
    return out


def crossing_ends(F, ends, which, reach, span) -> list:
    """The ``ends`` (``(..., point, tangent)``, of the functions ``which``) of lines beside the no-pair
    area, for the continuation of :mod:`~gearkit.blocking.ends`, whose line crosses the area's
    edge: the tangent meets the edge within ``reach`` at more than ``EDGE_DEG`` to it (the edge's
    points on the tangent and on rays ``EDGE_FAN_DEG`` either side of it), and ``F`` is regular
    there (see ``EDGE_GROWTH``). Each is returned with the length its front may run
    (``EDGE_BUDGET`` times its distance to the edge). Nothing here depends on tol: the same ends
    are carried on at every tol."""
    if not ends:
        return []
    P = np.array([e[2] for e in ends])
    T = np.array([e[3] for e in ends])
    K = np.asarray(which)
    fan = math.radians(EDGE_FAN_DEG)
    rays = []
    for ang in (0.0, fan, -fan):
        c, s = math.cos(ang), math.sin(ang)
        rays.append(np.column_stack([c * T[:, 0] - s * T[:, 1], s * T[:, 0] + c * T[:, 1]]))
    A, D, KK = np.tile(P, (3, 1)), np.concatenate(rays), np.tile(K, 3)
    B = A + reach * D
    out = np.isnan(F(B, KK))
    E = np.full(A.shape, np.nan)
    if out.any():  # the three rays' edge points in one multisection
        E[out] = edge_point(F, A[out], B[out], KK[out], span, EDGE_PROBE ** 2 * reach)
    hits = np.split(E, 3)
    along = hits[1] - hits[2]
    with np.errstate(invalid="ignore", divide="ignore"):
        sin = np.abs(T[:, 0] * along[:, 1] - T[:, 1] * along[:, 0]) / np.hypot(*along.T)
    ok = np.isfinite(hits[0][:, 0]) & np.isfinite(sin) & (sin > math.sin(math.radians(EDGE_DEG)))
    if ok.any():  # F regular at the edge beside the line: differences over D, 4 D, 16 D up from it
        i = np.flatnonzero(ok)
        n_e = np.column_stack([-along[i, 1], along[i, 0]]) / np.hypot(*along[i].T)[:, None]
        n_e *= np.where(np.einsum("ij,ij->i", n_e, P[i] - hits[0][i]) > 0, 1.0, -1.0)[:, None]
        d = EDGE_PROBE * reach * 4.0 ** np.arange(3)
        Q = np.concatenate([h[i][:, None, :] + d[None, :, None] * n_e[:, None, :] for h in hits[1:]])
        V = F(Q.reshape(-1, 2), np.repeat(np.tile(K[i], 2), d.size)).reshape(2 * len(i), d.size)
        step = np.abs(np.diff(V, axis=1))
        regular = step[:, 1] + EDGE_FLAT * (1.0 + np.abs(V[:, 0])) >= EDGE_GROWTH * step[:, 0]
        ok[i] = np.all(np.isfinite(V), axis=1).reshape(2, -1).all(axis=0) & regular.reshape(2, -1).all(axis=0)
    run = EDGE_BUDGET * np.hypot(*(hits[0] - P).T)
    return [e + (float(b),) for e, o, b in zip(ends, ok, run) if o]
