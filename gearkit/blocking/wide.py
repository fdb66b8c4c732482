"""A chord's zero searched for beyond its normal's ends, for :func:`~gearkit.blocking.refinement.densify`.

:func:`search_wide`: a chord with no zero at the samples of its normal within half a chord of its middle is
sampled again on rays of up to twice its length along the normal (``RAY_FRACTIONS`` of ``WIDE_REACH`` chord
lengths; a strip, a saddle's thin wedge or a region's edge narrower than the normal's half chord), a measured
curve's (the region's) at the reach, or twice it, only, with no zero where both sides change sign there (a thin
part of the region, not the chord's edge); a measured curve's zero so found is read as far as its root lies and
offered the ladder within the normal's ends, which wins where nearer (a strip narrower than the normal's half
chord beside the middle hid the nearer zero: 59/68 z0 25 internal at tol 1e-3, a chord along the region's strip
split at the far side of a wedge of its outside 1.7 chords off zigzagged across the wedge, 35 tol off; the secant
from the middle to a steep far side read it next to the middle: 56/63 z0 25 at tol 1e-5, the region's outline
folded back along exit jamming 0.8 chords off).

:func:`past_lines`: a measured curve's zero so found past another of the region's chords is none (a link of the
grid's chain of diamonds along a flat strip, refined down the strip past the next link's cut, took its part
twice).
"""
from __future__ import annotations

import numpy as np

from gearkit.blocking.brackets import segment_roots

__all__ = ["search_wide", "past_lines"]

WIDE_REACH = 1.0  #: a chord's second search for its curve reaches this many chord lengths to each side
RAY_FRACTIONS = (0.125, 0.25, 0.375, 0.5, 0.75, 1.0, 2.0)  #: where the second search samples (x reach)
NRAYS = 1  #: directions searched: the normal only (a diagonal ray's zero may lie on the other branch of a
#: saddle: a chord joining two branches was kept 3.8e-5 off its line at every tol below 1e-4)
PLAIN = (5, 6)  #: the samples a measured curve's search reads: the reach, then twice it (an acute corner)
PAST = 2.0  #: a measured curve's zero farther than this many tol (and half that chord) past another of its chords
#: is not the searching chord's (:func:`past_lines`)


def search_wide(F, best, wide, m, f0, n, L, which, trusted, vtol: float) -> None:
    """Offer ``best`` (a :class:`~gearkit.blocking.brackets.NearestBracket` over the chords measured) the zeros
    beyond the normal's ends of the chords ``wide`` (indices into the chords' middles ``m``, values there ``f0``,
    unit normals ``n``, lengths ``L``, curves ``which``; ``trusted``: not a measured curve's), roots to ``vtol``."""
    tg = np.column_stack([n[wide, 1], -n[wide, 0]])
    dirs = [sg * dv for dv in (n[wide], (n[wide] + tg) / np.sqrt(2), (n[wide] - tg) / np.sqrt(2))[:NRAYS]
            for sg in (1.0, -1.0)]
    fr = WIDE_REACH * np.asarray(RAY_FRACTIONS)
    P = np.stack([m[wide][:, None, :] + (fr[None, :, None] * L[wide][:, None, None]) * dv[:, None, :]
                  for dv in dirs], axis=1)  # (w, rays, samples, 2)
    V = F(P.reshape(-1, 2), np.repeat(which[wide], len(dirs) * fr.size)).reshape(P.shape[:3])
    tw = trusted[wide]
    # a measured curve (the region) keeps the plain search: the normal at full reach (twice it
    # where there is none), and no zero when both sides change sign (a thin part of the region,
    # not this chord's edge)
    sides = np.isfinite(V[:, :2]) & ((V[:, :2] > 0) != (f0[wide] > 0)[:, None, None])  # (w, 2, samples)
    far = ~np.any(sides[:, :, PLAIN[0]], axis=1)  # no zero at the reach: read twice the reach
    jp = np.where(far, PLAIN[1], PLAIN[0])
    rw = np.arange(wide.size)
    both = sides[rw, 0, jp] & sides[rw, 1, jp]
    for r in range(len(dirs)):  # rays 0, 1: the normal; the others diagonal
        vs, ps = V[:, r], P[:, r]
        change = np.isfinite(vs) & ((vs > 0) != (f0[wide] > 0)[:, None])
        j = np.argmax(change, axis=1)
        ok = change[rw, j] & np.all(np.isfinite(vs) | (np.arange(fr.size)[None] >= j[:, None]), axis=1)
        plain = ~tw & (r < 2)
        j = np.where(plain, jp, j)
        ok = np.where(plain, change[rw, j] & ~both, ok & tw)
        prev = np.maximum(j - 1, 0)
        start = (j > 0) & ~plain
        lo = np.where(start[:, None], ps[rw, prev], m[wide])
        flo = np.where(start, vs[rw, prev], f0[wide])
        best.consider(wide[ok], lo[ok], flo[ok], ps[rw, j][ok], vs[rw, j][ok], diagonal=r >= 2)
    # a measured curve's zero found only at the reach or twice it may lie across a wedge of the other sign
    # while a strip narrower than the normal's half chord hides the nearer one beside the middle (a chord
    # along the strip's edge): the ladder within the normal's ends offers the nearer (NearestBracket), read
    # against the far zero's root (the secant from the middle to a steep far side reads it next to the middle)
    beyond = wide[best.have[wide] & ~tw]
    if beyond.size:
        far_root = segment_roots(F, best.lo[beyond], best.end[beyond], best.flo[beyond], best.fe[beyond],
                                 vtol, which[beyond])
        best.dist[beyond] = np.hypot(*(far_root - m[beyond]).T)
        best.ladder(F, beyond, n[beyond], 0.5 * L[beyond], which[beyond], vtol, np.ones(beyond.size, bool))


def past_lines(lines, which, A, B, m, F0, root, tol: float) -> np.ndarray:
    """True where the way from a chord's middle ``m`` to a zero found along its normal, ``root`` (``(c, 2)``,
    chords ``A -> B`` of curves ``which``), crosses a chord of the lines of its curve in ``lines``
    (``[(k, points)]``; none of its own or beside it) farther from the zero than ``PAST`` tol and half that
    chord: the zero lies past another line of the curve, across the part that line bounds, so it is not this
    chord's (the arc a chord stands for bounds, with it, a part no other line enters). A chord across a strip
    of a region narrower than a grid cell, where its margin is flat (a link of the grid's chain of diamonds),
    reads along the strip its edge beyond the next link's cut: that zero taken, the loop is refined down the
    strip past the cut,
    which then pairs with none (:func:`~gearkit.blocking.region.reconnect`), and the part taken twice is
    left out by the even-odd rule (55/102 z0 34 and 25/59 z0 35 internal at tol 1e-5, 810 and 565 tol off).
    Kept as it is, the chord is a cut (re-joined with the next link's). So too where the zero lies on the side
    of the chord its curve does not (``F0 = F(m)``; ``F > 0`` on a loop's left), through its own loop's part, within
    ``PAST`` tol of a chord of its own line not beside it: taken, the line would fold back along itself (25/59
    z0 35 at tol 1e-3: a chord across the strip, its normal down the strip, read its own loop's edge there)."""
    out = np.zeros(len(m), bool)
    for k in np.unique(which):
        own = [q for kk, q in lines if kk == k and len(q) >= 2]
        segs = [(q[:-1], q[1:]) for q in own]
        C, D = np.concatenate([s[0] for s in segs]), np.concatenate([s[1] for s in segs])
        line = np.repeat(np.arange(len(own)), [len(q) - 1 for q in own])
        E = D - C
        ell = np.hypot(E[:, 0], E[:, 1])
        for i in np.flatnonzero(which == k):
            other = ~(np.all(C == A[i], axis=1) | np.all(C == B[i], axis=1) | np.all(D == A[i], axis=1)
                      | np.all(D == B[i], axis=1))
            mine = np.isin(line, line[np.all(C == A[i], axis=1) & np.all(D == B[i], axis=1)])
            t = np.clip(np.einsum("ij,ij->i", root[i] - C, E) / np.maximum(ell ** 2, 1e-300), 0.0, 1.0)
            r = root[i] - m[i]
            inward = (float(r[0] * (A[i][1] - B[i][1]) + r[1] * (B[i][0] - A[i][0])) > 0) == (F0[i] > 0)
            if inward and np.any(other & mine & (np.hypot(*(C + t[:, None] * E - root[i]).T) <= PAST * tol)):
                out[i] = True  # on its own line elsewhere, through its own part: the line would fold back
                continue
            den = r[0] * E[:, 1] - r[1] * E[:, 0]
            w = C - m[i]
            with np.errstate(divide="ignore", invalid="ignore"):
                s = (w[:, 0] * E[:, 1] - w[:, 1] * E[:, 0]) / den  # along the way, 0 at m, 1 at the root
                u = (w[:, 0] * r[1] - w[:, 1] * r[0]) / den  # along the chord crossed
            hit = other & (den != 0) & (s > 0) & (s < 1) & (u >= 0) & (u <= 1)
            gap = (1.0 - s) * np.hypot(*r)
            out[i] = bool(np.any(hit & (gap > np.fmax(PAST * tol, 0.5 * ell))))
    return out
