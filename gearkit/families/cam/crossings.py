"""Where the cam follower's envelope crosses itself: the crossing that joins a kept arc's end to the
next kept arc's start, from the samples on either side of a cut.

A cut of the envelope (:mod:`gearkit.families.cam.faces`) runs from the last kept sample ``e`` of one
arc to the first kept sample ``b`` of the next; the arcs meet where the envelope crosses itself, a
point ``curve(wa) = curve(wb)`` with ``wa`` just past ``e`` and ``wb`` just before ``b``. The search
starts from the crossing of the sampled chords (near the samples, or farther out when the crossing is
shallow and samples past it were kept), or from the closest pair of a dense resampling when a chord
across a motion join is not the curve, and ends with Newton on the two curve parameters; a crossing
next to the curve meeting itself (``wa = wb``, a swallowtail a few samples wide) is solved on the
divided difference instead. A kept arc of a roller turning about a velocity jump's corner ends where
the envelope beside it comes out of the roller's circle about the corner (:func:`corner_cut`): one
equation in one parameter, bracketed and bisected. A knife's cam is cut at the crossings of its
scan's polyline, each refined by Newton (:func:`refine_crossing`).
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.errors import GeometryError

__all__ = ["corner_cut", "refine_crossing", "refine_cut", "sides_crossing"]


def refine_crossing(f, wa, wb, lo_a, hi_a, lo_b, hi_b):
    """Newton on ``f(wa) = f(wb)`` (a self-crossing of the exact curve) from a polyline's crossing, inside the
    given windows: a knife's cam, cut at every crossing its scan finds."""
    h = 1e-9
    x = np.array([wa, wb], dtype=float)
    lo, hi = np.array([lo_a, lo_b]), np.array([hi_a, hi_b])
    for _ in range(50):
        p = f(np.array([x[0] - h, x[0] + h, x[1] - h, x[1] + h, x[0], x[1]]))
        g = p[4] - p[5]
        jac = np.column_stack([(p[1] - p[0]) / (2 * h), -(p[3] - p[2]) / (2 * h)])
        try:
            step = np.linalg.solve(jac, g)
        except np.linalg.LinAlgError:
            break
        new = np.clip(x - step, lo, hi)
        if np.abs(new - x).max() < 1e-15:
            x = new
            break
        x = new
    return float(x[0]), float(x[1])


def refine_cut(curve, w, e, b, da: int = 1, db: int = 1, meet: float | None = None):
    """The crossing ``curve(wa) = curve(wb)`` with ``wa`` just past sample ``e`` (going in the direction
    ``da`` of ``w``, +1 or -1) and ``wb`` just before sample ``b`` (coming in the direction ``db``): the
    chords' crossing, then Newton. With ``meet`` (mm), a crossing whose ends lie farther apart is
    sought again from the closest pair of the curve resampled densely between the samples
    (:func:`_dense_start`): a chord across a motion join, where the envelope turns back at a corner,
    is not the curve, and its crossing may lead Newton to another stretch."""
    n = len(w)
    ja = (e + da * np.arange(-2, 3)) % (n - 1)
    jb = (b + db * np.arange(-3, 2)) % (n - 1)
    pa, pb = curve(w[ja]), curve(w[jb])
    best = None
    for i in range(len(ja) - 1):
        for j in range(len(jb) - 1):
            t = _chord_cross(pa[i], pa[i + 1], pb[j], pb[j + 1])
            if t is not None and not {ja[i], ja[i + 1]} & {jb[j], jb[j + 1]}:  # chords sharing a sample touch
                best = (w[ja[i]] + da * t[0] * (w[1] - w[0]), w[jb[j]] + db * t[1] * (w[1] - w[0]))
    if best is None:  # a shallow crossing: samples past it lie within the slack of the cam and were kept
        best = _far_cross(curve, w, e, b, da, db)
    if best is None:  # no chord crossing seen: start from the last kept and first kept samples
        best = (w[e], w[b])
    h = 0.5 * (w[1] - w[0])
    wa, wb = _newton(curve, *best, h=h)
    if meet is not None:
        wa, wb = _settle(curve, w, e, b, da, db, ja, jb, (wa, wb), meet, h)
    if _same(wa, wb, h):  # Newton fell to the curve meeting itself, wa = wb: a swallowtail a few samples wide
        start = best if not _same(*best, h) else (w[e] + da * h, w[b] - db * h)
        wa, wb = _newton(curve, *start, h=h, divided=True)
        if _same(wa, wb, h):
            raise GeometryError(f"the envelope's crossing past w = {w[e]:.6g} was not found apart from the curve itself")
    return wa, wb


def _settle(curve, w, e, b, da, db, ja, jb, found, meet: float, h: float):
    """The crossing of :func:`refine_cut` once Newton from the chords' crossing has settled at ``found``: when
    its ends lie apart (beyond a thousandth of ``meet``: a crossing solves to round-off) or on the curve
    meeting itself, Newton again from the resampled polylines' crossing about the cut's samples
    (:func:`_dense_start`), then from the chords' crossing up to 64 samples past them (:func:`_far_cross`) and
    the resampled crossing there: the ends that meet best.

    Samples inside a loop shallower than the keep test's slack are kept, and the loop's crossing lies past
    them: a roller just larger than the pitch curve's radius of curvature after an acceleration jump runs back
    along its envelope at a few thousandths of its speed, and its kept samples lay seven steps short of the
    crossing. Newton on two stretches that run side by side within the meet may also stop short of their
    crossing within it (1.8e-5 mm apart, 0.7 of the meet), taken for a crossing into the wrong run."""
    def gap(x):
        return np.inf if _same(*x, h) else float(np.hypot(*np.subtract(*curve(np.array(x)))))

    def better(best, start):
        return min([best, _newton(curve, *start(), h=h)], key=gap) if gap(best) > 1e-3 * meet else best
    best = better(found, lambda: _dense_start(curve, w, ja, jb))
    far = _far_cross(curve, w, e, b, da, db) if gap(best) > 1e-3 * meet else None
    if far is not None:
        n = len(w) - 1
        ka, kb = int(np.floor(far[0] * n)), int(np.floor(far[1] * n))
        best = better(best, lambda: far)
        best = better(best, lambda: _dense_start(curve, w, (ka + da * np.arange(-1, 3)) % n,
                                                 (kb + db * np.arange(-1, 3)) % n))
    return best


def _same(wa: float, wb: float, h: float) -> bool:  # within a sixteenth of a sample step 2 h (cyclic): one point
    return abs((wa - wb + 0.5) % 1.0 - 0.5) < h / 8


def _dense_start(curve, w, ja, jb, per: int = 128):
    """The crossing ``(wa, wb)`` of the curve's polylines resampled ``per`` times a sample step along the
    samples ``ja`` and ``jb`` (each walked in its own direction, consecutive samples), the one nearest the
    middle of both where they cross more than once, or their closest pair of points where they do not.

    The closest pair alone misses a crossing of two stretches that run at speeds far apart and at a small
    angle: at an acceleration jump where the roller turns from smaller to larger than the pitch curve's
    radius of curvature, the envelope runs back at a few thousandths of its speed before the jump (a
    swallowtail 1e-4 mm long), and points of the slow stretch as far as twenty sample steps from the
    crossing lay within the fast stretch's resampled spacing of it, past the reach of Newton."""
    f = np.arange(per) / per

    def dense(j):
        a, b = w[j[:-1]], w[j[1:]]
        b = np.where(np.abs(b - a) > 0.5, b + np.sign(a - b), b)  # a step across w = 1
        return np.mod(np.append((a[:, None] + f[None, :] * (b - a)[:, None]).ravel(), b[-1]), 1.0)
    xa, xb = dense(ja), dense(jb)
    pa, pb = curve(xa), curve(xb)
    t, u, hit = _chords_crossing(pa, pb)
    near = 2.0 * (w[1] - w[0]) / per  # chords a resampled step or two apart, or shared: the curve meeting itself
    same = np.abs((xa[:, None] - xb[None, :] + 0.5) % 1.0 - 0.5) <= near
    hit &= ~same[:-1, :-1]
    if hit.any():
        i, k = np.nonzero(hit)
        c = int(np.argmin(np.abs(i - len(xa) // 2) + np.abs(k - len(xb) // 2)))
        i, k = int(i[c]), int(k[c])
        return (float(xa[i] + t[i, k] * ((xa[i + 1] - xa[i] + 0.5) % 1.0 - 0.5)),
                float(xb[k] + u[i, k] * ((xb[k + 1] - xb[k] + 0.5) % 1.0 - 0.5)))
    gap = np.where(same, np.inf, np.hypot(pa[:, None, 0] - pb[None, :, 0], pa[:, None, 1] - pb[None, :, 1]))
    i, k = np.unravel_index(int(np.argmin(gap)), gap.shape)
    return float(xa[i]), float(xb[k])


def _far_cross(curve, w, e, b, da: int, db: int, reach: int = 64):
    """The chords' crossing nearest the samples ``e`` and ``b`` within ``reach`` samples either side of
    each (the two runs walked as in :func:`_refine_cut`; chords sharing a sample are no crossing), as
    ``(wa, wb)``, or None."""
    n = len(w) - 1
    k = np.arange(-reach, reach + 1)
    ja, jb = (e + da * k) % n, (b + db * k) % n
    pa, pb = curve(w[ja]), curve(w[jb])
    t, u, hit = _chords_crossing(pa, pb)
    hit &= np.abs((ja[:-1, None] - jb[None, :-1] + n // 2) % n - n // 2) > 1  # not one chord, nor two that touch
    if not hit.any():
        return None
    i, j = np.nonzero(hit)
    c = int(np.argmin(np.abs(i - reach) + np.abs(j - reach)))
    step = w[1] - w[0]
    return w[ja[i[c]]] + da * t[i[c], j[c]] * step, w[jb[j[c]]] + db * u[i[c], j[c]] * step


def _chords_crossing(pa, pb):
    """Where each chord of the polyline ``pa`` crosses each of ``pb``: ``(t, u, hit)``, arrays of shape
    ``(len(pa) - 1, len(pb) - 1)``, the crossing at ``t`` along the first chord and ``u`` along the second
    (fractions), ``hit`` where both lie in [0, 1] (parallel chords never cross)."""
    d1, d2 = (pa[1:] - pa[:-1])[:, None, :], (pb[1:] - pb[:-1])[None, :, :]
    r = pb[None, :-1, :] - pa[:-1, None, :]
    den = d1[..., 0] * d2[..., 1] - d1[..., 1] * d2[..., 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (r[..., 0] * d2[..., 1] - r[..., 1] * d2[..., 0]) / den
        u = (r[..., 0] * d1[..., 1] - r[..., 1] * d1[..., 0]) / den
    return t, u, (den != 0.0) & (t >= 0.0) & (t <= 1.0) & (u >= 0.0) & (u <= 1.0)


def _chord_cross(p0, p1, q0, q1):
    d1, d2, r = p1 - p0, q1 - q0, q0 - p0
    den = d1[0] * d2[1] - d1[1] * d2[0]
    if den == 0.0:
        return None
    t = (r[0] * d2[1] - r[1] * d2[0]) / den
    u = (r[0] * d1[1] - r[1] * d1[0]) / den
    return (t, u) if 0.0 <= t <= 1.0 and 0.0 <= u <= 1.0 else None


def _newton(curve, wa, wb, h, divided: bool = False):
    """Newton on ``curve(wa) = curve(wb)`` within ``4 h`` of the start (central differences); ``divided``: on
    ``(curve(wa) - curve(wb)) / (wa - wb)``, the curve's slope (not zero) as ``wb`` comes to ``wa``, keeping their
    order: a swallowtail a few samples wide crosses so near the curve meeting itself (every ``wa = wb`` a root of
    the plain difference) that Newton falls to that."""
    x = np.array([wa, wb])
    lo, hi = x - 4 * h, x + 4 * h
    step_h = 1e-9
    for _ in range(50):
        a = np.array([x[0] - step_h, x[0] + step_h, x[0], x[0], x[0]])
        b = np.array([x[1], x[1], x[1] - step_h, x[1] + step_h, x[1]])
        p = curve(np.mod(np.concatenate([a[[0, 1, 4]], b[[2, 3, 4]]]), 1.0))
        g = p[[0, 1, 2, 2, 2]] - p[[5, 5, 3, 4, 5]]  # curve(a) - curve(b) at the five pairs
        if divided:
            g = g / (a - b)[:, None]
        jac = np.column_stack([(g[1] - g[0]) / (2 * step_h), (g[3] - g[2]) / (2 * step_h)])
        try:
            step = np.linalg.solve(jac, g[4])
        except np.linalg.LinAlgError:
            break
        new = np.clip(x - step, lo, hi)
        if divided and (new[1] - new[0]) * np.sign(wb - wa) < h / 8:  # the pair would pass through the curve meeting itself
            break
        done = np.abs(new - x).max() < 1e-15
        x = new
        if done:
            break
    return float(np.mod(x[0], 1.0)), float(np.mod(x[1], 1.0))


def corner_cut(curve, w, e, b, circles, meet: float, reach: int = 64, per: int = 8):
    """The crossing that ends a kept arc of a roller's corner (the roller turning about a velocity
    jump's corner ``C`` of the pitch curve, on the circle ``|x - C| = R``) where the motion's envelope
    beside it first runs inside that circle and then out across it (a swallowtail a few micrometres
    deep), or None when neither the last kept sample ``e`` nor the first kept sample ``b`` of the cut
    lies on a corner's arc. An arc cut whole (a concave corner, the arc running back) but for a sample at
    an end has no such exit: the envelopes either side of it cross, solved on their own stretches
    (:func:`sides_crossing`); arcs whose motion section between them is shorter than a sample step (two
    velocity jumps a dwell of a few ulps apart) are one gap, its sides those of the run (:func:`_runs`).

    The envelope beside the corner starts on the circle (the arc's end), so its signed distance from
    the circle ``|curve(w) - C| - R`` is a function of one parameter whose first rise through zero
    after it has dipped below is the crossing: bracketed on ``per`` points a sample step over the
    neighbouring motion section, up to ``reach`` samples past the cut's far end (samples of a shallow
    swallowtail lie within the keep test's slack and may have been kept), and bisected. The arc is
    linear in the roller's contact angle, so its own parameter at the crossing follows from the
    angle of ``x - C`` (a point of the circle off the arc, farther than ``meet`` from it, is no
    crossing). ``circles`` are ``(k, C, R)``: the index of each corner section of ``curve``
    (a :class:`~gearkit.families.cam.curve.CamCurve`), its centre and radius.
    """
    step, edges = w[1] - w[0], curve.edges
    span = (w[b] - w[e]) % 1.0

    def off(x):  # signed offset of x from the last kept sample along the cut (cyclic)
        return (x - w[e] + 0.5) % 1.0 - 0.5
    for run in _runs(circles, edges, step):
        # the arcs cut but for a sample at an end (whose central difference straddles the break): their sides cross
        k0, k1 = run[0][0], run[-1][0]
        w0, w1 = edges[k0], edges[k1 + 1]
        if -step < off(w0) <= reach * step and -step < span - off(w1) <= reach * step:
            lo = max(edges[k0 - 1], w0 - off(w0) - reach * step)
            hi = min(edges[k1 + 2] if k1 + 2 < len(edges) else 1.0, w1 + span - off(w1) + reach * step)
            wa, wb = sides_crossing(curve, lo, w0, w1, hi)
            if off(wa) <= step and span - off(wb) <= step and np.hypot(*np.subtract(*curve(np.array([wa, wb])))) <= meet:
                return wa, wb
        for k, centre, radius in run:
            hit = _arc_exit(curve, w, e, span, step, off, k, centre, radius, meet, reach, per)
            if hit is not None:
                return hit
    return None


def _runs(circles, edges, step):
    """The corners ``circles`` grouped into runs of adjacent arcs: two corners whose motion section between
    them is shorter than a sample step (a dwell of a few ulps of the cam angle between two velocity jumps)
    are one gap in the envelope, whose sides are the sections before the first arc and after the last."""
    runs = []
    for c in circles:
        if runs and c[0] == runs[-1][-1][0] + 2 and edges[c[0]] - edges[c[0] - 1] < step:
            runs[-1].append(c)
        else:
            runs.append([c])
    return runs


def _arc_exit(curve, w, e, span, step, off, k, centre, radius, meet, reach, per):
    """The crossing where the envelope beside corner ``k``'s arc comes out of its circle after the cut's
    last kept sample ``e`` lies on the arc (the section after it) or its first kept one does (the section
    before it), or None (:func:`corner_cut`)."""
    edges = curve.edges
    w0, w1 = edges[k], edges[k + 1]
    if off(w0) <= step and off(w1) >= -step and off(w1) <= span + step:  # e on the arc: the section after
        far = min(edges[k + 2] if k + 2 < len(edges) else 1.0, w1 + span - off(w1) + reach * step)
        x, after = _circle_exit(curve, w1, far, centre, radius, per * int(math.ceil((far - w1) / step))), True
    elif off(w1) >= span - step and off(w0) <= span + step and off(w0) >= -step:  # b on the arc: before it
        near = max(edges[k - 1] if k > 0 else 0.0, w0 - off(w0) - reach * step)
        x, after = _circle_exit(curve, w0, near, centre, radius, per * int(math.ceil((w0 - near) / step))), False
    else:
        return None
    if x is None:
        return None
    t = _arc_fraction(curve, w0, w1, centre, curve(np.array([x]))[0])
    on_arc = w0 + t * (w1 - w0)
    if np.hypot(*np.subtract(*curve(np.array([on_arc, x])))) <= meet:  # on the arc itself, not its circle
        return (on_arc, x) if after else (x, on_arc)
    return None


def sides_crossing(curve, lo, w0, w1, hi, start=None):
    """The crossing ``curve(wa) = curve(wb)`` of the envelope's stretches either side of a corner's arc,
    ``wa`` in ``[lo, w0]`` (before the arc, which starts at ``w0``) and ``wb`` in ``[w1, hi]`` (after it):
    Newton with each side's differences taken within its own stretch, so it never reads the arc, whose
    parameter runs the roller's contact angle over a sample step's length of ``w`` a few micrometres long
    (a tangent the motion's thousands of times shorter). From ``start`` ``(wa, wb)`` if given, else half
    the arc's width of ``w`` out from its ends."""
    x = np.array([w0 - 0.5 * min(w0 - lo, w1 - w0), w1 + 0.5 * min(hi - w1, w1 - w0)] if start is None else start,
                 dtype=float)
    lo_x, hi_x = np.array([lo, w1]), np.array([w0, hi])
    d = np.array([-1.0, 1.0]) * min(1e-9, 0.25 * (w0 - lo), 0.25 * (hi - w1))  # inward: back from w0, on from w1
    for _ in range(50):
        p = curve(np.array([x[0], x[0] + d[0], x[1], x[1] + d[1]]))
        jac = np.column_stack([(p[1] - p[0]) / d[0], -(p[3] - p[2]) / d[1]])
        try:
            step = np.linalg.solve(jac, p[0] - p[2])
        except np.linalg.LinAlgError:
            break
        new = np.clip(x - step, lo_x, hi_x)
        done = np.abs(new - x).max() < 1e-15
        x = new
        if done:
            break
    return float(x[0]), float(x[1])


def _circle_exit(curve, w0, w1, centre, radius, n):
    """The first ``w`` from ``w0`` towards ``w1`` (either way) where ``curve`` comes out of the circle
    about ``centre`` after it has run inside it (``n`` points bracket, bisection refines), or None."""
    xs = np.linspace(w0, w1, max(n, 2) + 1)
    h = np.hypot(*(curve(xs) - centre).T) - radius
    noise = 64 * np.finfo(float).eps * (radius + float(np.hypot(*centre)))
    inside = np.flatnonzero(h < -noise)
    if len(inside) == 0:
        return None
    out = np.flatnonzero(h[inside[0]:] >= 0.0)
    if len(out) == 0:
        return None
    j = inside[0] + int(out[0])
    lo, hi = float(xs[j - 1]), float(xs[j])
    for _ in range(64):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        if float(np.hypot(*(curve(np.array([mid]))[0] - centre))) - radius < 0.0:
            lo = mid
        else:
            hi = mid
    return hi


def _arc_fraction(curve, w0, w1, centre, x):
    """Where on the arc from ``curve(w0)`` to ``curve(w1)`` about ``centre`` (turning the short way,
    linearly in its parameter) the point ``x`` lies, as a fraction in [0, 1]."""
    a0, a1 = (np.arctan2(*(p - centre)[::-1]) for p in curve(np.array([w0, w1])))
    ax = math.atan2(x[1] - centre[1], x[0] - centre[0])
    sweep = (a1 - a0 + math.pi) % (2 * math.pi) - math.pi
    if sweep == 0.0:
        return 0.0
    return float(np.clip(((ax - a0 + math.pi) % (2 * math.pi) - math.pi) / sweep, 0.0, 1.0))
