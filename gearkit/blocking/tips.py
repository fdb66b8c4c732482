"""Corners of the admissible region that its chords cut: thin wedges traced to their tips.

The region's edge is the zero set of the smallest of its parts (the hard margins and the distances to the window's
edges: :func:`~gearkit.blocking.parts.part_evaluator`); where the part binding at one vertex of its outline differs
from the next one's, the edge turns a corner between them, where the two parts cross. A
chord's middle near the edge says nothing of such a corner: where the parts cross at a small angle
the region ends in a wedge narrower than a grid cell, which marching squares closes across short of
its tip (33/78 at tol 1e-5: the wedge between interference.1 and interference.2 cut 0.1 short of
its tip, the chord's middle 5.5e-3 from the edge, kept as no zero was found across it; 14/62,
14/118, 13/45: interference.1 and pointing.1; 14/118 at tol 1e-3: the chord across the wedge within
tol of the edge, the tip 4 tol beyond it). :func:`carry_to_tips` solves each corner ``T`` where the
binding part changes from ``a`` to ``b`` along a chord ``A -> B``: the crossing of ``a = 0`` and
``b = 0`` by Newton's method in the plane from ``A``; a corner farther than ``tol`` from its chord
replaces the chord by the line ``a = 0`` from ``A`` to ``T`` and ``b = 0`` from ``T`` to ``B``, each
traced to ``tol`` as a smooth curve of its own. A chord kept with no zero found across it whose ends
bind the same part (along a strip of the region narrower than itself, its middle beside the strip)
is replaced by that part's line; where that line from end to end is cut (across a wedge of the part
whose sides are two branches of its zero set, meeting at its saddle: interference.1's wedges at (1, 1)
of 58/109 and 55/102 internal, cut 7.5 and 2.4 tol short at tol 1e-3), the sides are traced from one
end through where they meet (:func:`meetings`) to the other, the tip a corner of that line; where they meet at no
corner the outline can take (the region goes on through the saddle's neck between them into a part beyond it that
no grid node sees: 29/37 at tol 1e-5, 6.6 tol off), the edge from one end of the chord to the other is walked
(:mod:`~gearkit.blocking.walk`). Which part binds at a vertex (:func:`~gearkit.blocking.parts.binding`): an end beside
the tip sweep's kink, where its margin is flat at the sweep's resolution and smallest, binds the part whose
zero lies there (exit jamming, where the tip sweep starts to penetrate: 25/54 z0 20's wedge); so does an end where the smallest part is flat, farther than
``tol`` from its zero by its slope, and another lies within ``tol`` of its own (beside a saddle: the nearest by value
over slope). Where the crossing nearest a chord's start is not its corner, the one nearest its end is taken (a strip
of the region between two parts ends where they cross at each of its ends; the outline from the start runs the
other way along it: 56/63 z0 25's strip under interference.1's wedge at (1, 1)). A new outline is
taken only where it is the region's edge: every chord's middle within ``tol`` of its part's zero, every part at
every new vertex on its right side or within ``tol`` of its zero (by its own slope), and no chord crossing the
rest of the region's outline or another of its own (two sides crossing where they meet, carried on past it: 39/91
z0 19 internal at tol 5e-3, a cut of a diamond inside a thin wedge carried through the wedge's tip to the frame
beyond it, where the two lines, 0.005 apart, lie within tol of each other; a triangle of the outside 0.045 long was
held as region, 13.8 tol off).

Where the two parts' lines meet past the zero of a third hard margin (a strip ending across its line before its
sides meet: 19/72 z0 33 internal, the flat strip between interference.1 and exit jamming ended by trimming.plunge's
line 0.044 above their crossing), the corner is that strip's end, the chord replaced by three sides
(:func:`~gearkit.blocking.apex.across`); where they meet nowhere within reach and the strip runs out through the
window's frame, its end is there, the window's edge the third side (34/81's strip between interference.1 and .2,
closed by the grid 0.125 short of the top frame: :func:`~gearkit.blocking.apex.frame_corners`), unless a third
margin's line ends it short of the frame (30/33's strip ended by pointing.2's line). A loop lying wholly
in the part a carry takes (a link of the grid's chain of diamonds farther down the wedge than a cut pairs,
:func:`_covered`; dropped afterwards as covered) and a chord crossing the carried path within ``2 tol`` of it (the
outline folded along the wedge's side, :func:`_grazing`) do not stop the carry (40/64 z0 22 internal at tol 1e-5).

The tips themselves are solved by :mod:`~gearkit.blocking.apex` (:func:`crossings`, :func:`meetings`:
also this module's names).
"""
from __future__ import annotations

import numpy as np

from gearkit.blocking.apex import REACH, STEP_H, corners, crossings, frame_corners, meetings, segment_distance
from gearkit.blocking.parts import binding
from gearkit.blocking.walk import walk_sides
from gearkit.curves import polyline_self_intersections

__all__ = ["crossings", "meetings", "carry_to_tips"]

GRAZE_SAMPLES = 17  #: points along a chord crossing a carried path read for how far they lie inside its part


def _crosses(P, Q, A, B) -> np.ndarray:
    """For each segment ``P[i] -> Q[i]``: True where it properly crosses any segment ``A[j] -> B[j]``."""
    if not len(P) or not len(A):
        return np.zeros(len(P), bool)

    def orient(o, u, v):  # sign of (u - o) x (v - o), broadcast (i, j)
        return np.sign((u[..., 0] - o[..., 0]) * (v[..., 1] - o[..., 1]) - (u[..., 1] - o[..., 1]) * (v[..., 0] - o[..., 0]))
    p, q, a, b = P[:, None], Q[:, None], A[None], B[None]
    hit = (orient(p, q, a) * orient(p, q, b) < 0) & (orient(a, b, p) * orient(a, b, q) < 0)
    return np.any(hit, axis=1)


def _along(path, P, reach) -> np.ndarray:
    """True for each point of ``P`` within ``reach`` of the polyline ``path``."""
    d = np.full(len(P), np.inf)
    for u, v in zip(path[:-1], path[1:]):
        d = np.minimum(d, segment_distance(np.broadcast_to(u, P.shape), np.broadcast_to(v, P.shape), P))
    return d <= reach


def carry_to_tips(F, G, lines, kept, region: int, tol: float, trace) -> list:
    """``lines`` (``[(k, points, slopes)]``) with the region's chords (curve ``region`` of ``F``) that cut
    a corner farther than ``tol`` from them carried to it, and the chords listed in ``kept``
    (``(k, start, end)``: no zero found across them) whose ends bind the same part replaced by its line,
    or by its two sides to where they meet, or by the region's edge walked from end to end (see the module's notes).
    ``G``: the region's parts (:func:`~gearkit.blocking.parts.part_evaluator`); ``trace(G, [(part, points (2, 2),
    slopes)])`` traces lines of single parts to ``tol`` (returns
    ``[(part, points)]``, a line cut where no zero is found)."""
    from gearkit.blocking.region import locate_chord

    vtol = 0.25 * tol
    own = [(m, q) for m, (k, q, _) in enumerate(lines) if k == region and len(q) >= 2]
    if not own:
        return lines
    P = np.concatenate([q for _, q in own])
    bind = binding(G, P, tol)
    first = np.cumsum([0] + [len(q) for _, q in own])
    A, B, ia, ib, before, after = [], [], [], [], [], []  # the chords, their parts, the chords beside them
    for (m, q), s in zip(own, first):
        b = bind[s:s + len(q)]
        j = np.flatnonzero((b[:-1] != b[1:]) & (b[:-1] >= 0) & (b[1:] >= 0))
        A.append(q[j]), B.append(q[j + 1]), ia.append(b[j]), ib.append(b[j + 1])
        before.append(q[np.maximum(j - 1, 0)]), after.append(q[np.minimum(j + 2, len(q) - 1)])
    A, B, ia, ib, before, after = (np.concatenate(v) for v in (A, B, ia, ib, before, after))
    smooth = ~np.isin(ia, G.costly) & ~np.isin(ib, G.costly)
    A, B, ia, ib, before, after = (v[smooth] for v in (A, B, ia, ib, before, after))
    tips = np.full(A.shape, np.nan)
    ends, cut = np.full((len(A), 2, 2), np.nan), np.full(len(A), -1)  # a strip's end: its corners (apex.corners)
    span = float(np.hypot(G.window[1] - G.window[0], G.window[3] - G.window[2]))
    if len(A):
        T, conv, seen, ends, cut = corners(F, G, region, A, B, ia, ib, before, after, A, tol, span)
        # the crossing nearest the chord's start may be the other end of a strip between the two parts (the
        # outline from that start runs the other way along the strip): where it is not the chord's corner (nor
        # within tol of the outline), the crossing nearest the chord's end
        again = np.flatnonzero(~conv & ~seen)
        if again.size:
            T2, conv2, seen2, ends2, cut2 = corners(F, G, region, A[again], B[again], ia[again], ib[again],
                                                    before[again], after[again], B[again], tol, span)
            T[again[conv2]], conv[again[conv2]] = T2[conv2], True
            ends[again[conv2]], cut[again[conv2]] = ends2[conv2], cut2[conv2]
            # nor that: the strip between the two parts may run out through the window's frame (frame_corners)
            out = again[~conv2 & ~seen2]
            if out.size:
                T3, conv3, _, ends3, cut3 = frame_corners(F, G, region, A[out], B[out], ia[out], ib[out],
                                                          before[out], after[out], tol, span)
                T[out[conv3]], conv[out[conv3]] = T3[conv3], True
                ends[out[conv3]], cut[out[conv3]] = ends3[conv3], cut3[conv3]
        tips[conv] = T[conv]
    corner = np.isfinite(tips[:, 0])
    sides = {}  # chord (start, end) -> its sides (part, start, end)
    for i in np.flatnonzero(corner):
        if np.isfinite(ends[i, 0, 0]):  # a strip's end across a third margin's line: three sides
            sides[(tuple(A[i]), tuple(B[i]))] = [(int(ia[i]), A[i], ends[i, 0]), (int(cut[i]), ends[i, 0], ends[i, 1]),
                                                 (int(ib[i]), ends[i, 1], B[i])]
        else:
            sides[(tuple(A[i]), tuple(B[i]))] = [(int(ia[i]), A[i], tips[i]), (int(ib[i]), tips[i], B[i])]
    along = [(a, b) for k, a, b in kept if k == region and locate_chord(lines, k, a, b) is not None]
    if along:
        a, b = np.array([c[0] for c in along]), np.array([c[1] for c in along])
        ba, bb = binding(G, a, tol), binding(G, b, tol)
        for i in np.flatnonzero((ba == bb) & (ba >= 0) & ~np.isin(ba, G.costly)):
            sides.setdefault((tuple(a[i]), tuple(b[i])), [(int(ba[i]), a[i], b[i])])
    todo = [s for ss in sides.values() for s in ss]
    if not todo:
        return lines
    traced = trace(G, [(k, np.array([a, b]), np.full(2, np.nan)) for k, a, b in todo])
    by_end = {(k, tuple(p[0]), tuple(p[-1])): p for k, p in traced}  # a side cut in two is none
    # a kept chord whose part's line from end to end was cut: across a wedge of that part, its sides two
    # branches of its zero set meeting at a saddle (meetings): traced from each end to the tip
    lone = [(ab, ss[0][0]) for ab, ss in sides.items() if len(ss) == 1 and (ss[0][0], *ab) not in by_end]
    if lone:
        a, b = np.array([ab[0] for ab, _ in lone]), np.array([ab[1] for ab, _ in lone])
        T, conv = meetings(G, a, b, np.array([k for _, k in lone]), vtol, REACH * span)
        more = {}  # each wedge's two sides traced as one line of its part through the tip, a corner of it (the
        # chord beside the tip measured a quarter from it: corner_splits; a side traced alone from its end kept one
        # chord along a branch that bends towards the saddle near its end, its middle 0.48 tol off and its last
        # hundredth 2.1 tol, 42/67 z0 40 internal at tol 1e-5)
        for i in np.flatnonzero(conv & (segment_distance(a, b, T) > tol)):
            (ab, k) = lone[i]
            sides[ab] = [(k, a[i], T[i]), (k, T[i], b[i])]
            more[(k, ab[0], ab[1])] = T[i]
        through = [(k, np.array([s, t, e]), np.full(3, np.nan)) for (k, s, e), t in more.items()]
        for k, p in trace(G, through) if through else ():
            t = more.get((k, tuple(p[0]), tuple(p[-1])))
            at = np.flatnonzero(np.all(p == t, axis=1)) if t is not None else ()
            if len(at):  # (a line cut in two is none)
                by_end[(k, tuple(p[0]), tuple(t))], by_end[(k, tuple(t), tuple(p[-1]))] = p[:at[0] + 1], p[at[0]:]
    lines, left = _carry(G, lines, sides, by_end, region, tol)
    # a lone chord whose part's sides met at no corner the outline takes (the region goes on through the saddle's
    # neck between them, 29/37 at tol 1e-5): the region's edge walked from its start to its end (walk)
    walked, traced = walk_sides(G, [(ab, k) for ab, k in lone if ab in left], tol, REACH * span, trace)
    if walked:
        by_end.update(traced)
        lines = _carry(G, lines, walked, by_end, region, tol)[0]
    return lines


def _carry(G, lines, sides, by_end, region: int, tol: float):
    """``lines`` with each chord ``(a, b)`` of ``sides`` replaced by its sides' traced lines (``by_end``) where they
    are the region's edge and cross no other part of the outline (see :func:`carry_to_tips`); and the set of chords
    left as they were."""
    from gearkit.blocking.region import locate_chord

    own = [(m, q) for m, (k, q, _) in enumerate(lines) if k == region and len(q) >= 2]
    OA, OB = np.concatenate([q[:-1] for _, q in own]), np.concatenate([q[1:] for _, q in own])
    owner = np.concatenate([np.full(len(q) - 1, m) for m, q in own])
    lines, left = list(lines), set()
    for (a, b), ss in sides.items():
        left.add((a, b))
        got = [by_end.get((k, tuple(s), tuple(e))) for k, s, e in ss]
        if any(p is None for p in got):
            continue
        path = np.vstack([got[0]] + [p[1:] for p in got[1:]])
        part = np.concatenate([np.full(len(p) - 1, k) for p, (k, _, _) in zip(got, ss)])
        if not _on_edge(G, path, part, tol) or _crossed(path, np.array([e for _, _, e in ss[:-1]]), tol):
            continue
        w = locate_chord(lines, region, np.array(a), np.array(b))
        if w is None:
            continue
        m, j = w
        k, q, g = lines[m]
        # the outline's vertices next to the chord's ends that lie along the new path (within 2 tol): a fold
        # of the outline back along the wedge's side beside the cut, dropped with the chord
        near = _along(path, q, 2 * tol)
        lo, hi = j, j + 1
        while lo > 1 and near[lo - 1]:
            lo -= 1
        while hi < len(q) - 2 and near[hi + 1]:
            hi += 1
        fold = np.concatenate([q[lo:j], q[j + 2:hi + 1]])
        touching = np.all(OA == a, axis=1) | np.all(OB == a, axis=1) | np.all(OA == b, axis=1) | np.all(OB == b, axis=1)
        for v in fold:
            touching |= np.all(OA == v, axis=1) | np.all(OB == v, axis=1)
        touching |= _along(path, OA, 2 * tol) & _along(path, OB, 2 * tol)  # a fold of the outline along the path
        touching |= np.isin(owner, _covered(own, m, path, tol))  # a link of a chain of diamonds the carry covers
        hit = np.flatnonzero(~touching)
        hit = hit[_crosses(OA[hit], OB[hit], path[:-1], path[1:])]
        if not np.all(_grazing(path, OA[hit], OB[hit], tol)) or len(q) - len(fold) < 4:
            continue
        inner = np.full(len(path) - 2, np.nan)
        lines[m] = (k, np.vstack([q[:lo], path, q[hi + 1:]]),
                    np.concatenate([g[:lo], g[j:j + 1], inner, g[j + 1:j + 2], g[hi + 1:]]))
        left.discard((a, b))
    return lines, left


def _crossed(path, joints, tol: float) -> bool:
    """True where the carried ``path`` crosses itself farther than ``2 tol`` from the ``joints`` of its sides (two
    sides of a wedge thinner than tol beside its tip may cross there within the tolerance): its sides carried on
    past the tip where they meet (see the module's notes)."""
    i, _, t, _ = polyline_self_intersections(path)
    if not i.size or not len(joints):
        return bool(i.size)
    x = path[i] + t[:, None] * (path[i + 1] - path[i])
    return bool(np.any(np.min(np.hypot(*(x[:, None] - joints[None]).transpose(2, 0, 1)), axis=1) > 2 * tol))


def _grazing(path, A, B, tol: float) -> np.ndarray:
    """True for each chord ``A[i] -> B[i]`` crossing ``path`` whose points inside the part a carry along
    ``path`` adds or takes away (the path closed by its chord) all lie within ``2 tol`` of the path, sampled
    at ``GRAZE_SAMPLES`` points: the same edge within the tolerance, not another part of the outline (the
    loop's outline folded back and forth along the wedge's side beyond the cut, each fold a chord along
    that side, crossing the carried side at a grazing angle: 40/64 z0 22 internal at tol 1e-5)."""
    from gearkit.blocking.region import inside_polygons

    if not len(A):
        return np.zeros(0, bool)
    t = np.linspace(0.0, 1.0, GRAZE_SAMPLES)[:, None, None]
    pts = (A[None] + t * (B - A)[None]).reshape(-1, 2)
    ok = ~inside_polygons([np.vstack([path, path[:1]])], pts) | _along(path, pts, 2 * tol)
    return np.all(ok.reshape(GRAZE_SAMPLES, len(A)), axis=0)


def _covered(own, m, path, tol: float) -> list:
    """The loops of ``own`` (``[(line, points)]``) but line ``m`` lying wholly in the part a carry along
    ``path`` adds or takes away (the path closed by its chord), their vertices inside it or within ``2 tol``
    of the path: a link of the grid's chain of diamonds along a wedge narrower than a grid cell, farther
    from the cut the wedge is carried from than a cut pairs (40/64 z0 22 internal at tol 1e-5: the carry of
    the loop's cut 0.07 above a diamond to the wedge's tip crossed the diamond's sides and was not taken,
    the wedge between them left out, 691 tol). The carry takes its part; the link, carried to the same tip,
    then lies inside the carried loop and is dropped (:func:`~gearkit.blocking.region.drop_covered`)."""
    from gearkit.blocking.region import inside_polygons

    area = np.vstack([path, path[:1]])
    return [n for n, q in own if n != m and np.all(inside_polygons([area], q) | _along(path, q, 2 * tol))]


def _on_edge(G, path, part, tol: float) -> bool:
    """True when the traced ``path`` (its chords on the parts ``part``) is the region's edge: every
    chord's middle within ``tol`` of its part's zero, at every inner vertex every part below zero within
    ``tol`` of its own zero (its value over its own slope: a distance; the vertex's own part's slope
    judged another part shallower or steeper than itself, 14/62 at tol 1e-3 in a window whose top edge
    is 0.5 tol below the tip of the wedge between pointing.1 and interference.1: the carried path
    rejected, the chord left cutting the wedge 42 tol deep), and every inner vertex within ``tol`` of the
    window (the distances to its edges are parts of slope 1: two lines crossing at a few degrees just
    beyond the window's edge, the region's corner is on the edge, 40/105 z0 33 at tol 1e-3: contact
    ratio 1 and exit jamming crossing 0.012 below it)."""
    mid = 0.5 * (path[:-1] + path[1:])
    inner = path[1:-1]
    lo, hi = np.array(G.window[0::2]), np.array(G.window[1::2])
    if np.any((inner < lo - tol) | (inner > hi + tol)):
        return False
    f = G(mid, part)
    g = np.hypot(G(mid + [STEP_H, 0.0], part) - f, G(mid + [0.0, STEP_H], part) - f) / STEP_H
    with np.errstate(invalid="ignore"):
        if not np.all(np.abs(f) <= tol * g):
            return False
    V = G.many(inner)  # (G.size, len(inner)): every part at every inner vertex
    if not np.all(np.isfinite(V)):
        return False  # a part undefined there: no pair
    c, i = np.nonzero(V < 0)  # the parts below zero and their vertices
    if not c.size:
        return True
    v, p = V[c, i], inner[i]
    s = np.hypot(G(p + [STEP_H, 0.0], c) - v, G(p + [0.0, STEP_H], c) - v) / STEP_H
    with np.errstate(invalid="ignore"):
        return bool(np.all(-v <= tol * s))
