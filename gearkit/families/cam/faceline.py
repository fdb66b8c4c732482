"""The flat face's cam along the face line of a velocity jump, where the face slides along its own line.

At a velocity jump of the follower's law the cam angle stands while the face slides along one line, from where
the envelope's arc before the jump touches that line to where the arc after it does (the corner section of
:class:`~gearkit.families.cam.curve.CamCurve`). A slide the way the cam's boundary runs (clockwise) is a
straight stretch of the cam; so is the stretch of such a line that joins two kept arcs with no crossing between
them (:func:`bridge`, a :class:`FaceEdge`). A slide back against the boundary is a fold: the arcs either side of
it overlap along the line and the cam keeps them only up to their crossing (:func:`slides_back`).
:mod:`gearkit.families.cam.faces` finds the kept arcs and hands their joins here.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.errors import GeometryError
from gearkit.families.cam.crossings import sides_crossing

__all__ = ["FaceEdge", "bridge", "slides_back"]


class FaceEdge:
    """A straight stretch of the cam along one face line, from ``p0`` to ``p1``: an exact curve of
    ``w`` in [0, 1]."""

    def __init__(self, p0, p1):
        self.p0 = np.asarray(p0, dtype=float)
        self.p1 = np.asarray(p1, dtype=float)

    def __call__(self, w):
        w = np.atleast_1d(np.asarray(w, dtype=float))
        return self.p0[None, :] + w[:, None] * (self.p1 - self.p0)[None, :]

    def turning(self, w):
        """Points, the unit tangent (one direction: a straight edge turns by nothing) and one constant part."""
        pts, d = self(w), self.p1 - self.p0
        length = float(np.hypot(*d))
        tangent = d / length if length > 0 else np.array([1.0, 0.0])
        return pts, np.broadcast_to(tangent, pts.shape).copy(), np.zeros((len(pts), 1))


def _on_line(curve, n, h, w, step):
    """The ``w`` within ``8 step`` of ``w`` nearest to it where the curve crosses the line
    ``n . x = h`` (bisection on a bracketing pair of 65 samples), or None."""
    ws = np.mod(w + np.linspace(-8.0, 8.0, 65) * step, 1.0)
    g = curve(ws) @ n - h
    flips = np.flatnonzero(np.sign(g[:-1]) != np.sign(g[1:]))
    if len(flips) == 0:
        return None
    k = int(flips[np.argmin(np.abs(flips - 31.5))])
    lo, hi, glo = w + (k - 32) * step / 4.0, w + (k - 31) * step / 4.0, g[k]
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        gm = float(curve(np.array([mid % 1.0]))[0] @ n - h)
        lo, hi, glo = (mid, hi, gm) if np.sign(gm) == np.sign(glo) else (lo, mid, glo)
    return float((0.5 * (lo + hi)) % 1.0)


def bridge(curve, cut, kept, corners, scale: float, step: float):
    """A join ``(wa, wb)`` of :func:`~gearkit.families.cam.faces.face_boundary` whose ends do not meet (no
    self-crossing of the envelope there): the straight stretch of the cam between them along a corner's
    face line.

    ``corners`` are ``(n, h, e0, e1)``: the face line at each velocity jump and the ``w`` range of
    its corner section. With no crossing to find, Newton's ends ``(wa, wb)`` settle anywhere along
    the envelope past the kept arcs, so the line and the stretch are read off the arcs' own ends,
    ``kept`` (the ``w`` of the last kept sample of one arc and the first of the next): the line leaves
    each within the chord of a sample step either side of it (the envelope crosses the line between
    the kept sample and the cut one beside it, or enters the cam at the corner section's end a step
    away). An end within the section's reach snaps to the section's nearer end (the face's slide at
    the jump runs along the same line), any other end to the envelope's crossing with the line
    beside its kept sample. Returns ``(wa, wb, edge)``; ``edge`` is None when the cut's ends meet
    (within ``1e-6 scale``); the step is :func:`~gearkit.families.cam.faces.face_boundary`'s sampling step.

    Raises
    ------
    GeometryError
        When the ends meet no corner's line (the half-plane model has no other straight stretch).
    """
    wa, wb = cut
    pa, pb = curve(np.array([wa, wb]))
    if np.hypot(*(pa - pb)) <= 1e-6 * scale:
        return wa, wb, None
    ka, kb = np.asarray(kept, dtype=float)
    side = curve(np.mod(np.array([ka - step, ka, ka + step, kb - step, kb, kb + step]), 1.0))
    reach = [max(np.hypot(*(side[i] - side[i + 1])), np.hypot(*(side[i + 1] - side[i + 2]))) for i in (0, 3)]
    off = [max(abs(side[1] @ n - h) / reach[0], abs(side[4] @ n - h) / reach[1]) for n, h, _, _ in corners]
    if not off or min(off) > 1.0 + 1e-9:
        raise GeometryError("a kept arc of the flat face's envelope meets the next one neither at a crossing nor "
                            "along a corner's face line")
    n, h, e0, e1 = corners[int(np.argmin(off))]
    ends = []
    for w in (ka, kb):
        if e0 - 8 * step <= w <= e1 + 8 * step:
            ends.append(float(e0 if abs(w - e0) <= abs(w - e1) else e1))
            continue
        on = _on_line(curve, n, h, w, step)
        if on is None:
            raise GeometryError("the flat face's envelope does not reach a corner's face line at a cut")
        ends.append(on)
    pa, pb = curve(np.array(ends))
    return ends[0], ends[1], FaceEdge(pa, pb)


def slides_back(curve, arcs, cuts, corners, scale: float):
    """:func:`~gearkit.families.cam.faces.face_boundary`'s ``(arcs, cuts)`` with every velocity jump's slide
    that runs back along the face line, on a kept arc, cut out at the crossing of the envelope's arcs either
    side of it.

    At a jump the face slides along its line from where the arc before it touches the line to where the
    arc after it does. Where that slide runs forward (clockwise, the way the boundary runs) it is a
    straight stretch of the cam; where it runs back, the two arcs, each touching the line at its own end
    and bending inside it, overlap along it and cross about the slide's middle, ``slide^2 / (8 r)``
    inside the line (``r`` their radius of curvature): a fold of the envelope too shallow for the keep
    test's half-planes (a constant-velocity rocker lifting 1e-5 r0, a 3.9e-5 mm slide on a 21 mm cam, cut
    by its neighbours' lines by 4e-11 mm), so every sample beside it is kept and the outline walked
    forward to the jump, back along the slide and forward again (a turn-back of 5e-7 mm at tol 1e-4 r0).
    The cam keeps only the forward run: the arc before up to the crossing, the arc after from it
    (:func:`_fold_cut`).

    None when the arcs either side of a slide running back do not meet within ``1e-12 scale``, or the
    crossings of two slides overlap (the arcs kept at a coarse sampling, their fold deeper than the slack
    about a sample too few to see).
    """
    if not corners:
        return arcs, cuts
    edges = np.asarray(curve.edges, dtype=float)
    out, added = [], []
    for spans, edge in arcs:
        split = []
        for x, y in spans:
            lo, hi, way = min(x, y), max(x, y), (1.0 if y > x else -1.0)
            folds = []
            for n, _, e0, e1 in corners:
                if not lo < e0 <= e1 < hi:
                    continue
                p0, p1 = curve(np.array([e0, e1]))
                if way * ((p1 - p0) @ np.array([n[1], -n[0]])) >= 0.0:  # forward along the boundary: a flat
                    continue
                k = int(np.searchsorted(edges, e0, side="right")) - 1  # the corner section
                wa, wb = _fold_cut(curve, n, max(edges[k - 1], lo), e0, e1, min(edges[k + 2], hi))
                if np.hypot(*np.subtract(*curve(np.array([wa, wb])))) > 1e-12 * scale:
                    return None
                folds.append((wa, wb))
            marks = [lo] + [v for f in sorted(folds) for v in f] + [hi]
            if (np.diff(marks) < 0.0).any():  # two slides' crossings overlap: the arc between them folded away
                return None
            parts = list(zip(marks[::2], marks[1::2]))
            split += parts if way > 0 else [(b, a) for a, b in parts[::-1]]
            added += folds
        out.append((tuple(split), edge))
    return out, sorted(cuts + added)


def _fold_cut(curve, n, lo, e0, e1, hi):
    """Where the arcs either side of a slide back along the face line (normal ``n``; the corner section from
    ``e0`` to ``e1``, the arc before it from ``lo``, the one after it up to ``hi``) cross: ``(wa, wb)``.

    Each arc is first cut where it passes the slide's middle along the line (bisection on its own stretch):
    they cross there to within ``slide^2 / (8 r)``, how deep the fold is. Newton from that pair
    (:func:`~gearkit.families.cam.crossings.sides_crossing`) finds the crossing itself where the two arcs'
    angle, ``slide / r``, stands above their points' round-off over their differences' step; below it (a
    slide of 2e-6 mm on a 21 mm cam: the arcs 1e-7 rad apart, their differences' chords 3e-6 rad off their
    tangents) it wanders to its bounds. Newton's pair is taken where its ends meet closer, both within the
    slide's span along the line. An arc too short to reach the slide's middle (a dwell's arc a few ulps
    long between two jumps) leaves Newton alone, from half the slide's width of ``w`` out from its ends.
    """
    t = np.array([n[1], -n[0]])
    p0, p1 = curve(np.array([e0, e1]))
    u0, u1 = float(p0 @ t), float(p1 @ t)
    mid = 0.5 * (u0 + u1)
    wa, wb = (_passing(curve, t, mid, w, stop, e1 - e0) for w, stop in ((e0, lo), (e1, hi)))
    if wa is None or wb is None:  # an arc shorter than half the slide (a dwell of a few ulps): Newton alone
        return sides_crossing(curve, lo, e0, e1, hi)
    na, nb = sides_crossing(curve, lo, e0, e1, hi, start=(wa, wb))
    p = curve(np.array([wa, wb, na, nb]))
    along = p[2:] @ t
    if np.hypot(*(p[2] - p[3])) < np.hypot(*(p[0] - p[1])) and \
            (along >= min(u0, u1)).all() and (along <= max(u0, u1)).all():
        return na, nb
    return wa, wb


def _passing(curve, t, target: float, w: float, stop: float, width: float):
    """The ``w`` from ``w`` towards ``stop`` where ``curve(w) . t`` first passes ``target``: bracketed on steps
    from ``width`` doubling, then bisected; None when it does not before ``stop``."""
    start = float(curve(np.array([w]))[0] @ t) - target
    prev, d = w, math.copysign(max(abs(width), 4 * np.spacing(1.0)), stop - w)
    while True:
        x = stop if abs(d) >= abs(stop - w) else w + d
        if (float(curve(np.array([x]))[0] @ t) - target) * start <= 0.0:
            break
        if x == stop:
            return None
        prev, d = x, 2 * d
    a, b = prev, x
    for _ in range(64):
        m = 0.5 * (a + b)
        if m in (a, b):
            break
        a, b = (m, b) if (float(curve(np.array([m]))[0] @ t) - target) * start > 0.0 else (a, m)
    return b
