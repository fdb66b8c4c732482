"""The tip of a wedge of the admissible region, solved in the plane (for :mod:`~gearkit.blocking.tips`).

Where the region ends in a wedge, its tip is where two zero lines meet: the crossing of two parts'
zero lines (:func:`crossings`: Newton's method in the plane, gradients by forward differences), or,
where the wedge's sides are two branches of one part's zero set meeting at its saddle, where those
branches meet (:func:`meetings`: their tangents crossed, the ends moved halfway to that estimate and
back onto their lines, round after round). Each function ``G(points (n, 2), which (n,) int) -> (n,)``
is a part of the region's function (:func:`~gearkit.blocking.parts.part_evaluator`); every step is
bounded by ``reach``, and a solve that does not converge says so. :func:`corners`: which crossings are the
corners an outline's chords cut (far enough from them, on the side the region's part beyond lies:
:func:`outward`).

>>> import numpy as np
>>> P = lambda p, k: np.where(k == 0, p[:, 1] - 0.1 * p[:, 0], 0.2 * p[:, 0] - p[:, 1])  # a wedge, tip (0, 0)
>>> T, ok = crossings(P, np.array([[1.0, 0.1]]), np.array([0]), np.array([1]), 1e-9, 10.0)
>>> bool(ok[0]), bool(np.hypot(*T[0]) < 1e-9)
(True, True)
"""
from __future__ import annotations

import numpy as np

__all__ = ["across", "corners", "frame_corners", "crossings", "meetings", "outward", "segment_distance", "value_grad",
           "NEWTON_ITERATIONS", "STEP_H", "CROSSING_SIN", "REACH"]

NEWTON_ITERATIONS = 40  #: most Newton steps to a tip
STEP_H = 1e-7  #: forward difference of the parts' gradients (shift units; their round-off is ~1e-15)
REACH = 0.25  #: a tip lies within this fraction of the window's diagonal of the chord's end
BACKTRACK = 30  #: most halvings of a Newton step that ends where a part is undefined (the no-pair area)
CROSSING_SIN = 1e-5  #: two zero lines at a smaller angle (its sine) are parallel to the gradients' accuracy
#: (forward differences, STEP_H: about 1e-7 on lines that coincide)


def crossings(G, x0, ia, ib, vtol: float, reach: float):
    """The crossings of ``G_ia = 0`` and ``G_ib = 0`` nearest ``x0`` (``(n, 2)``; ``ia``, ``ib`` ``(n,)``
    part indices) by Newton's method in the plane (gradients by forward differences), each step at most
    ``reach`` long: ``(points (n, 2), converged (n,) bool)``; converged where the last step was below
    ``vtol / 4`` and both parts lie within ``vtol`` (their value over their slope) of zero; failed where a step
    starts from two lines parallel to the gradients' accuracy (the sine of their angle below ``CROSSING_SIN``):
    there no crossing is near, and the step runs along them to wherever (21/65 z0 21 internal: tip_clearance.1
    and interference.2 both vanish on x1 = 0 above x2 = 1.566; from a chord 0.68 up the line, whose ends bound
    one and the other, the steps ran down it to the region's corner, and the outline was carried there and
    back, then cut the corner 5.9 tol off)."""
    x = np.array(x0, dtype=float).reshape(-1, 2)
    n = len(x)
    ok = np.ones(n, bool)
    done = np.zeros(n, bool)
    for _ in range(NEWTON_ITERATIONS):
        act = np.flatnonzero(ok & ~done)
        if not act.size:
            break
        xa = x[act]
        P = np.concatenate([xa, xa + [STEP_H, 0.0], xa + [0.0, STEP_H]] * 2)
        W = np.concatenate([np.tile(ia[act], 3), np.tile(ib[act], 3)])
        fa0, fax, fay, fb0, fbx, fby = G(P, W).reshape(6, act.size)
        j00, j01, j10, j11 = (fax - fa0) / STEP_H, (fay - fa0) / STEP_H, (fbx - fb0) / STEP_H, (fby - fb0) / STEP_H
        ga, gb = np.hypot(j00, j01), np.hypot(j10, j11)
        with np.errstate(invalid="ignore", divide="ignore"):
            det = j00 * j11 - j01 * j10
            dx = -(j11 * fa0 - j01 * fb0) / det
            dy = -(j00 * fb0 - j10 * fa0) / det
            s = np.hypot(dx, dy)
            scale = np.minimum(1.0, reach / s)
            parallel = ~(np.abs(det) >= CROSSING_SIN * ga * gb)  # a step along two parallel lines goes nowhere
        bad = ~(np.isfinite(s) & np.isfinite(fa0) & np.isfinite(fb0)) | parallel
        ok[act[bad]] = False
        good = ~bad
        step = np.column_stack([dx, dy])[good] * scale[good, None]
        _defined(G, xa[good], step, ia[act[good]], ib[act[good]])
        x[act[good]] = xa[good] + step
        with np.errstate(invalid="ignore", divide="ignore"):
            near = (s[good] <= 0.25 * vtol) & (np.abs(fa0[good]) <= vtol * ga[good]) \
                & (np.abs(fb0[good]) <= vtol * gb[good])
        done[act[good][near]] = True
    return x, ok & done


def _defined(G, x, step, ia, ib) -> None:
    """Each Newton ``step`` from ``x`` halved (in place) until both parts ``ia``, ``ib`` are defined where it ends,
    at most ``BACKTRACK`` times: a step from a wedge beside the no-pair area into that area, where neither part is
    defined, is none (internal 21/80 z0 27 at tol 1e-3: interference.1 and contact ratio 1 bound a wedge along the
    area's edge; the first step from the chord across it, 0.1 short of its tip, ended in the area and the solve
    failed, the chord left 6.6 tol off)."""
    todo = np.arange(len(x))
    for _ in range(BACKTRACK):
        if not todo.size:
            return
        end = x[todo] + step[todo]
        f = G(np.concatenate([end, end]), np.concatenate([ia[todo], ib[todo]])).reshape(2, -1)
        todo = todo[~np.all(np.isfinite(f), axis=0)]
        step[todo] *= 0.5


def value_grad(G, p, k):
    """Part ``k[i]`` of ``G`` at ``p[i]`` (``(n, 2)``) and its gradient by central differences (exact for a quadratic,
    as a part is beside its saddle): ``(values (n,), gradients (n, 2))``."""
    f0, fx, fy, bx, by = G(np.concatenate([p, p + [STEP_H, 0.0], p + [0.0, STEP_H], p - [STEP_H, 0.0],
                                           p - [0.0, STEP_H]]), np.tile(k, 5)).reshape(5, -1)
    return f0, np.column_stack([fx - bx, fy - by]) / (2 * STEP_H)


def meetings(G, A, B, which, vtol: float, reach: float):
    """Where the zero lines of part ``which[i]`` through ``A[i]`` and through ``B[i]`` meet (``(n, 2)``
    each): the tip of a wedge whose two sides are branches of one part's zero set, crossing at its saddle
    (interference.1's wedges meeting at (1, 1)), where :func:`crossings` has no second part to solve
    against. Each round the two lines' tangents (``G`` linearised at ``A`` and ``B``) cross at the tip's
    estimate ``T``; ``A`` and ``B`` move halfway to it and back onto their lines (Newton steps along the
    gradient), so the estimate is made ever nearer the tip. ``(points (n, 2), converged (n,) bool)``:
    converged where both ends came within ``vtol`` of ``T``, every step at most ``reach`` from the start.

    >>> P = lambda p, k: (p[:, 1] - 0.1 * p[:, 0]) * (p[:, 1] - 0.3 * p[:, 0])  # a wedge, its sides meeting at (0, 0)
    >>> T, ok = meetings(P, np.array([[1.0, 0.1]]), np.array([[1.0, 0.3]]), np.array([0]), 1e-9, 10.0)
    >>> bool(ok[0]), bool(np.hypot(*T[0]) < 1e-9)
    (True, True)
    """
    a = np.array(A, dtype=float).reshape(-1, 2)
    b = np.array(B, dtype=float).reshape(-1, 2)
    start = 0.5 * (a + b)
    n = len(a)
    T = np.full((n, 2), np.nan)
    ok = np.ones(n, bool)
    done = np.zeros(n, bool)

    def onto(p, k):  # Newton steps along the gradient back onto the zero line
        for _ in range(4):
            f, g = value_grad(G, p, k)
            with np.errstate(invalid="ignore", divide="ignore"):
                p = p - (f / np.einsum("ij,ij->i", g, g))[:, None] * g
        return p

    for _ in range(NEWTON_ITERATIONS):
        act = np.flatnonzero(ok & ~done)
        if not act.size:
            break
        k = which[act]
        fa, ga = value_grad(G, a[act], k)
        fb, gb = value_grad(G, b[act], k)
        ra = np.einsum("ij,ij->i", ga, a[act]) - fa
        rb = np.einsum("ij,ij->i", gb, b[act]) - fb
        with np.errstate(invalid="ignore", divide="ignore"):
            det = ga[:, 0] * gb[:, 1] - ga[:, 1] * gb[:, 0]
            t = np.column_stack([(ra * gb[:, 1] - rb * ga[:, 1]) / det, (ga[:, 0] * rb - gb[:, 0] * ra) / det])
        good = np.all(np.isfinite(t), axis=1) & (np.hypot(*(t - start[act]).T) <= reach)
        ok[act[~good]] = False
        act, t = act[good], t[good]
        T[act] = t
        near = (np.hypot(*(a[act] - t).T) <= vtol) & (np.hypot(*(b[act] - t).T) <= vtol)
        done[act[near]] = True
        act, t = act[~near], t[~near]
        if act.size:
            a[act] = onto(0.5 * (a[act] + t), which[act])
            b[act] = onto(0.5 * (b[act] + t), which[act])
            ok[act[~(np.all(np.isfinite(a[act]), axis=1) & np.all(np.isfinite(b[act]), axis=1))]] = False
    return T, ok & done


def segment_distance(A, B, P) -> np.ndarray:
    """Distance of each ``P[i]`` from the segment ``A[i] -> B[i]``."""
    d = B - A
    t = np.clip(np.einsum("ij,ij->i", P - A, d) / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300), 0.0, 1.0)
    return np.hypot(*(A + t[:, None] * d - P).T)


def corners(F, G, region: int, A, B, ia, ib, before, after, x0, tol: float, span: float):
    """The corners of the chords ``A -> B`` (ends binding parts ``ia``, ``ib``; ``before``, ``after`` the outline's
    vertices beside them): the crossing of the two parts' zero lines nearest ``x0`` (:func:`crossings`), within
    ``REACH`` of the window's diagonal ``span`` of ``A``, farther than ``tol`` from the chord and the chords beside it,
    on the side of it where the region's part beyond it lies (:func:`outward`): ``(points, corner (n,) bool, seen
    (n,) bool, ends (n, 2, 2), cut (n,) int)``, ``seen`` where the crossing lies within ``tol`` of those chords (the
    outline has it). Where a third hard margin lies below zero at the crossing (:func:`across`: ``cut``, -1 where
    none), the strip between the two parts ends across its line: ``ends`` are the crossings of each side with it
    (NaN elsewhere), the point their middle."""
    T, conv = crossings(G, x0, ia, ib, 0.25 * tol, REACH * span)
    conv &= np.hypot(*(T - A).T) <= REACH * span
    ends = np.full((len(A), 2, 2), np.nan)
    cut = np.full(len(A), -1)
    _framed(G, A, B, ia, ib, T, conv, ends, cut, tol, span)  # the sides meet beyond the window's frame
    _third(G, A, B, ia, ib, T, conv, ends, cut, tol, span)  # the sides meet past a third margin's zero
    return (T, *_beyond(F, region, A, B, before, after, T, conv, ends, tol), ends, cut)


def frame_corners(F, G, region, A, B, ia, ib, before, after, tol: float, span: float):
    """For chords whose parts' lines meet nowhere within reach (:func:`corners` found no crossing): where the strip
    between them runs out through the window's frame, its end there, as :func:`corners` returns it (``cut`` the
    window's edge, ``ends`` its crossings with each side, each within ``REACH`` of the window's diagonal ``span`` of
    the chord's end, on the window's frame and farther than ``tol`` apart; of the four edges the one nearest the
    chord: internal 17/76 z0 17's interference.2 and tip_clearance.1 both vanish along x1 = 0, and a chord there
    whose ends bind one and the other was carried up to the frame and back). 34/81 at tol 1e-3:
    interference.1 and interference.2 bound a strip 0.006 wide running out through the top frame, whose last
    row of nodes lies outside it; the grid closed the outline across it 0.125 short of the frame (3 tol off, 300
    at 1e-5), and the sides, crossing far down, were carried nowhere. Where a third hard margin lies below zero
    halfway between the two crossings with the frame (:func:`across`), its line ends the strip short of the frame, as
    in :func:`corners` (30/33: the strip between interference.1 and .2 ends where pointing.2's line crosses it, 0.035
    past the grid's cut and 0.53 short of the frame; carried to the frame, its sides were no edge and the cut was
    kept, 5.8 tol off at 1e-3, 578 at 1e-5)."""
    n = len(A)
    T, ends, cut = np.full((n, 2), np.nan), np.full((n, 2, 2), np.nan), np.full(n, -1)
    # (two parts vanishing on one line meet the frame at one point: crossings farther than tol apart)
    conv, cut[:], ends[:, 0], ends[:, 1] = _through_frame(G, A, B, ia, ib, tol, span, tol)
    T[conv] = 0.5 * (ends[conv, 0] + ends[conv, 1])
    _third(G, A, B, ia, ib, T, conv, ends, cut, tol, span)  # a third margin's line ends the strip short of the frame
    return (T, *_beyond(F, region, A, B, before, after, T, conv, ends, tol), ends, cut)


def _through_frame(G, A, B, ia, ib, tol: float, span: float, apart: float = -1.0):
    """Where the lines of ``ia`` (from ``A``) and ``ib`` (from ``B``) cross one edge of the window's frame, both
    crossings on the frame, within ``REACH`` of the window's diagonal ``span`` of their chord's end and farther than
    ``apart`` from each other: ``(found (n,), edge (n,), U (n, 2), V (n, 2))`` (-1 and NaN where none), of the four
    edges the one nearest the chord (the sum of the two distances)."""
    n = len(A)
    lo, hi = np.array(G.window[::2]), np.array(G.window[1::2])
    best, cut = np.full(n, np.inf), np.full(n, -1)
    U0, V0 = np.full((n, 2), np.nan), np.full((n, 2), np.nan)
    for e in range(G.size - 4, G.size):
        edge = np.full(n, e)
        U, ok_u = crossings(G, A, ia, edge, 0.25 * tol, REACH * span)
        V, ok_v = crossings(G, B, edge, ib, 0.25 * tol, REACH * span)
        d = np.hypot(*(U - A).T) + np.hypot(*(V - B).T)
        on = np.all((np.minimum(U, V) >= lo - tol) & (np.maximum(U, V) <= hi + tol), axis=1)
        take = ok_u & ok_v & on & (np.hypot(*(U - A).T) <= REACH * span) & (np.hypot(*(V - B).T) <= REACH * span) \
            & (np.hypot(*(U - V).T) > apart) & (d < best)
        best[take], cut[take], U0[take], V0[take] = d[take], e, U[take], V[take]
    return np.isfinite(best), cut, U0, V0


def _framed(G, A, B, ia, ib, T, conv, ends, cut, tol: float, span: float) -> None:
    """Where the crossing ``T`` lies more than ``tol`` beyond the window's frame, the wedge between the lines of ``ia``
    and ``ib`` runs out through it short of its tip (internal 42/98 z0 16 at tol 1e-3: interference.1 and contact
    ratio 1 bound a wedge whose tip lies 3.8 tol below the window; the carried path was no edge there, and the grid's
    chord across the wedge was kept 70 tol short of the frame, 2.5 tol off): ``ends`` set to the sides' crossings
    with the edge (:func:`_through_frame`), ``cut`` to the edge, ``T`` to their middle; where the two crossings are
    one point (to a thousandth of ``tol``), ``T`` that point and no ends; where none is found, ``conv`` False (all
    arrays changed in place)."""
    lo, hi = np.array(G.window[::2]), np.array(G.window[1::2])
    c = np.flatnonzero(conv & np.any((T < lo - tol) | (T > hi + tol), axis=1))
    if not c.size:
        return
    found, edge, U, V = _through_frame(G, A[c], B[c], ia[c], ib[c], tol, span)
    conv[c[~found]] = False
    apart = found & (np.hypot(*(U - V).T) > 1e-3 * tol)
    T[c[found]] = 0.5 * (U[found] + V[found])
    cut[c[apart]], ends[c[apart], 0], ends[c[apart], 1] = edge[apart], U[apart], V[apart]


def _third(G, A, B, ia, ib, T, conv, ends, cut, tol: float, span: float) -> None:
    """Where a third hard margin lies below zero at ``T`` (:func:`across`), the strip between the lines of ``ia`` and
    ``ib`` (from ``A`` and ``B``) ends across its line: ``ends`` set to the crossings of each side with it, ``cut`` to
    that margin, ``T`` to their middle; where they are not found within ``REACH`` of ``span``, ``conv`` False if the
    margin lies more than ``tol`` below zero at ``T`` (by its value over its slope), else ``T`` kept (all arrays
    changed in place, for the ``conv`` rows only)."""
    c = np.flatnonzero(conv)
    third, deep = across(G, T[c], ia[c], ib[c], tol)
    c, third, deep = c[third >= 0], third[third >= 0], deep[third >= 0]
    if c.size:
        U, ok_u = crossings(G, A[c], ia[c], third, 0.25 * tol, REACH * span)
        V, ok_v = crossings(G, B[c], third, ib[c], 0.25 * tol, REACH * span)
        ok = ok_u & ok_v & (np.hypot(*(U - A[c]).T) <= REACH * span) & (np.hypot(*(V - B[c]).T) <= REACH * span)
        conv[c[~ok & deep]] = False
        cut[c[ok | deep]] = third[ok | deep]
        ends[c[ok], 0], ends[c[ok], 1] = U[ok], V[ok]
        T[c[ok]] = 0.5 * (U[ok] + V[ok])


def _beyond(F, region, A, B, before, after, T, conv, ends, tol):
    """``(corner, seen)`` of :func:`corners`: the corners ``T`` found (``conv``) farther than ``tol`` from the chords
    ``A -> B`` and the chords beside them (``seen`` where within: the outline has it), on the side of the chord where
    the region's part beyond it lies (:func:`outward`)."""
    conv = conv.copy()
    seen = np.zeros(len(A), bool)
    c = np.flatnonzero(conv)  # a corner farther than tol from the chord and the chords beside it
    conv[c] = np.fmax.reduce([np.minimum.reduce([segment_distance(u[c], v[c], X) for u, v in
                                                 ((before, A), (A, B), (B, after))])
                              for X in (T[c], ends[c, 0], ends[c, 1])]) > tol
    seen[c[~conv[c]]] = True
    c = np.flatnonzero(conv)  # ... on the side of it the region's part beyond it lies (outward)
    conv[c] = outward(F, region, A[c], B[c], T[c], tol)
    return conv, seen


def across(G, T, ia, ib, tol: float):
    """The hard margin (not ``ia[i]``, ``ib[i]`` nor a costly one) farthest below zero at each crossing ``T[i]`` of
    ``ia`` and ``ib``, by its value over its slope (-1 where none is below zero), and whether that is more than
    ``tol`` below: the region's strip between the two parts' lines ends across that margin's line before they meet
    (19/72 z0 33 internal at tol 1e-3: interference.1 and exit jamming, 0.01 apart, meet 0.044 below the line of
    trimming.plunge, which ends the strip; carried to their crossing the outline was no edge, and the chord across
    the strip was left 4.9 tol off its end). A margin less than ``tol`` below zero there may still end the strip far
    from it: its line crossing a thin wedge at a small angle, within tol of the tip beyond the region (18/74 z0 27
    internal at tol 1e-3: exit jamming 0.73 tol from the crossing of interference.1 and contact ratio 1 by its
    slope, the wedge's tip between them 8.9 tol back from it). The window's edges are none: a crossing beyond one
    is no corner of the region (40/105 z0 33 at tol 1e-3: contact ratio 1 and exit jamming, a few tol apart, cross
    0.012 below the window; carried along its edge, the outline cut a sliver 15 tol wide out of the region)."""
    parts = np.array([k for k in range(G.size - 4) if k not in G.costly])  # (the last four: the window's edges)
    n = len(T)
    if not n or not parts.size:
        return np.full(n, -1), np.zeros(n, bool)
    P = np.repeat(T, parts.size, axis=0)
    W = np.tile(parts, n)
    f = G(P, W)
    g = np.hypot(G(P + [STEP_H, 0.0], W) - f, G(P + [0.0, STEP_H], W) - f) / STEP_H
    with np.errstate(invalid="ignore", divide="ignore"):
        d = (f / g).reshape(n, parts.size)
    d[(parts[None] == ia[:, None]) | (parts[None] == ib[:, None]) | ~np.isfinite(d)] = np.inf
    j = np.argmin(d, axis=1)
    low = d[np.arange(n), j]
    return np.where(low < 0, parts[j], -1), low < -tol


def outward(F, region: int, A, B, T, tol: float = 0.0) -> np.ndarray:
    """True where carrying the chord ``A -> B`` (the region on its left) to the corner ``T`` changes the
    region by a part of the right kind: ``F`` positive halfway from the chord's middle to ``T``, or a quarter of
    the chord's length from its middle towards ``T``, where ``T`` lies right of the chord (a wedge of the region
    taken in), negative where it lies left (a notch of its outside taken out). The point near the chord reads a
    wedge that bends away from the straight way to its tip (internal 21/55 z0 18 at tol 1e-3: interference.1 and
    contact ratio 1 bound a wedge 0.14 long, curved, whose point halfway lay 0.003 outside it; the chord across it
    was kept, 6.5 tol off). A cut across a wedge whose tip lies behind it, inside its loop (the upper cut of
    a grid node's diamond alone in the wedge, which Newton's steps carry down to the tip its lower cut
    is carried to), is no corner: carried there, the loop passed the tip twice. A corner within ``tol`` of
    the chord's line, beyond its end (:func:`corners` asks only of corners farther than ``tol`` from the chord),
    is one: the chord runs along a thin wedge's side towards its tip, the point halfway lies on that side, and
    ``F`` there is round-off (25/54 z0 20 internal at tol 1e-3, the chord's end 2.3 tol short of the tip; the
    carried path is the region's edge or is not taken, :func:`~gearkit.blocking.tips.carry_to_tips`).

    >>> F = lambda p, k: 1e-3 * p[:, 0] - np.abs(p[:, 1])  # a thin wedge along y = 0, tip (0, 0), region x > 0
    >>> A, B = np.array([[2.0, 1.5e-3]]), np.array([[1.0, 0.95e-3]])  # inside it, towards its upper side
    >>> T = np.zeros((1, 2))  # 4e-4 left of the chord's line
    >>> outward(F, 0, A, B, T), outward(F, 0, A, B, T, 5e-4)
    (array([False]), array([ True]))
    """
    d, m = B - A, 0.5 * (A + B)
    side = (d[:, 0] * (T[:, 1] - A[:, 1]) - d[:, 1] * (T[:, 0] - A[:, 0])) / np.maximum(np.hypot(*d.T), 1e-300)
    r = np.hypot(*(T - m).T)
    near = m + (np.minimum(0.25 * np.hypot(*d.T), 0.5 * r) / np.maximum(r, 1e-300))[:, None] * (T - m)
    f = F(np.concatenate([0.5 * (m + T), near]), np.full(2 * len(A), region)).reshape(2, -1)
    return (np.abs(side) <= tol) | np.any(np.where(side > 0, f < 0, f > 0), axis=0)
