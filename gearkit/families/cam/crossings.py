"""Where the cam follower's envelope crosses itself: the crossing that joins a kept arc's end to the
next kept arc's start, from the samples on either side of a cut.

A cut of the envelope (:mod:`gearkit.families.cam.faces`) runs from the last kept sample ``e`` of one
arc to the first kept sample ``b`` of the next; the arcs meet where the envelope crosses itself, a
point ``curve(wa) = curve(wb)`` with ``wa`` just past ``e`` and ``wb`` just before ``b``. The search
starts from the crossing of the sampled chords (near the samples, or farther out when the crossing is
shallow and samples past it were kept), or from the closest pair of a dense resampling when a chord
across a motion join is not the curve, and ends with Newton on the two curve parameters; a crossing
next to the curve meeting itself (``wa = wb``, a swallowtail a few samples wide) is solved on the
divided difference instead.
"""
from __future__ import annotations

import numpy as np

from gearkit.errors import GeometryError

__all__ = ["refine_cut"]


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
    if meet is not None and np.hypot(*np.subtract(*curve(np.array([wa, wb])))) > meet:
        wa, wb = _newton(curve, *_dense_start(curve, w, ja, jb), h=h)
    if _same(wa, wb, h):  # Newton fell to the curve meeting itself, wa = wb: a swallowtail a few samples wide
        start = best if not _same(*best, h) else (w[e] + da * h, w[b] - db * h)
        wa, wb = _newton(curve, *start, h=h, divided=True)
        if _same(wa, wb, h):
            raise GeometryError(f"the envelope's crossing past w = {w[e]:.6g} was not found apart from the curve itself")
    return wa, wb


def _same(wa: float, wb: float, h: float) -> bool:  # within a sixteenth of a sample step 2 h (cyclic): one point
    return abs((wa - wb + 0.5) % 1.0 - 0.5) < h / 8


def _dense_start(curve, w, ja, jb, per: int = 128):
    """The closest pair ``(wa, wb)`` of the curve resampled ``per`` times a sample step along the
    samples ``ja`` and ``jb`` (each walked in its own direction, consecutive samples)."""
    f = np.arange(per) / per

    def dense(j):
        a, b = w[j[:-1]], w[j[1:]]
        b = np.where(np.abs(b - a) > 0.5, b + np.sign(a - b), b)  # a step across w = 1
        return np.mod((a[:, None] + f[None, :] * (b - a)[:, None]).ravel(), 1.0)
    xa, xb = dense(ja), dense(jb)
    pa, pb = curve(xa), curve(xb)
    gap = np.hypot(pa[:, None, 0] - pb[None, :, 0], pa[:, None, 1] - pb[None, :, 1])
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
    d1, d2 = (pa[1:] - pa[:-1])[:, None, :], (pb[1:] - pb[:-1])[None, :, :]
    r = pb[None, :-1, :] - pa[:-1, None, :]
    den = d1[..., 0] * d2[..., 1] - d1[..., 1] * d2[..., 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (r[..., 0] * d2[..., 1] - r[..., 1] * d2[..., 0]) / den
        u = (r[..., 0] * d1[..., 1] - r[..., 1] * d1[..., 0]) / den
    apart = np.abs((ja[:-1, None] - jb[None, :-1] + n // 2) % n - n // 2) > 1  # not one chord, nor two that touch
    hit = apart & (den != 0.0) & (t >= 0.0) & (t <= 1.0) & (u >= 0.0) & (u <= 1.0)
    if not hit.any():
        return None
    i, j = np.nonzero(hit)
    c = int(np.argmin(np.abs(i - reach) + np.abs(j - reach)))
    step = w[1] - w[0]
    return w[ja[i[c]]] + da * t[i[c], j[c]] * step, w[jb[j[c]]] + db * u[i[c], j[c]] * step


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
