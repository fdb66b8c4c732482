"""Roots of array functions on segments, the nearest bracket of a zero among several rays, and chords
whose ends lie on two lines.

``F(points (n, 2), which (n,) int) -> (n,)`` evaluates function ``which[i]`` at ``points[i]`` (NaN
where undefined), as in :mod:`gearkit.blocking.level`.

>>> import numpy as np
>>> F = lambda p, w: p[:, 0] ** 2 - 2.0
>>> r = segment_roots(F, [[0.0, 0.0]], [[2.0, 0.0]], [-2.0], [2.0], 1e-12, [0])
>>> bool(abs(r[0, 0] - 2 ** 0.5) < 1e-12)
True
"""
from __future__ import annotations

import numpy as np

__all__ = ["segment_roots", "round_off_roots", "NearestBracket", "two_lines"]

ROOT_ITERATIONS = 100
ROUND_OFF = 1e-12  #: :func:`round_off_roots` solves to this fraction of the shortest bracket
GUARD_FRACTION = 0.5  #: a round's guard stands this fraction of tol beyond its estimate ...
GUARD_SETTLED = 0.5  #: ... where the estimate moved less than this fraction of its bracket since the round
#: before (it is settling on a root; not beside a jump of F or while the bracket is still wide)
LADDER_RATIO = 0.5  #: successive distances of :meth:`NearestBracket.ladder`'s samples
LADDER_EVEN = 64  #: most samples to each side :meth:`NearestBracket.ladder` adds at an even spacing
SLOPE_WIDTH = 1.0 / 16  #: the slope at a root is read off a bracket at least this fraction of tol wide


def segment_roots(F, a, b, fa, fb, tol: float, which, slopes: bool = False):
    """Roots of ``F`` (function ``which[k]``) on the segments ``a[k] -> b[k]`` (``(k, 2)``), given end
    values of opposite signs; each within ``tol`` (in x) of a sign change of ``F``. With ``slopes=True``,
    ``(roots, slopes)``: ``|dF/ds|`` along the segment at each root, read off the last bracket (values
    as evaluated, about ``tol`` wide), not off the segment's ends: beside a saddle, where ``F`` is
    nearly quadratic, the secant across a wide bracket is many times the slope at the root. The bracket
    read is the narrowest at least ``SLOPE_WIDTH tol`` wide with both values defined (the segment itself
    when none is narrower).

    Regula falsi with the Illinois modification; a step that fails to halve the bracket over two
    iterations is followed by a bisection. Regula falsi comes at a root from one side, so where its
    estimate settles a guard ``GUARD_FRACTION tol`` beyond it is evaluated in the same call: a root
    between the two closes the bracket at once (read off the chord between them). Where ``F`` is
    undefined (NaN) inside a bracket the half towards the end with the larger ``|F|`` is kept.
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
    # the open brackets' state, compacted as brackets close (their ends written back then)
    act = np.flatnonzero(~done)
    l, h, fl, fh, aa, dd, ww, sp = (v[act] for v in (lo, hi, flo, fhi, a, d, which, span))
    vl, vh = flo[act], fhi[act]  # the bracket's values as evaluated (fl, fh are scaled by Illinois)
    # the slope's bracket: the narrowest so far at least SLOPE_WIDTH tol wide (a narrower one, where regula
    # falsi met the root to round-off, has values of round-off)
    slo, shi, svlo, svhi = lo.copy(), hi.copy(), flo.copy(), fhi.copy()
    bl, bh, bvl, bvh = (v[act] for v in (slo, shi, svlo, svhi))
    s = np.zeros(act.size, dtype=int)  # the end moved last: 1 low, -1 high, 0 none or a bisection
    stall = np.zeros(act.size, dtype=int)
    cp = np.full(act.size, np.nan)
    for _ in range(ROOT_ITERATIONS):
        if not act.size:
            break
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            c = (l * fh - h * fl) / (fh - fl)
            bis = ~((c > l) & (c < h)) | (stall >= 3)
            c = np.where(bis, 0.5 * (l + h), c)
            # a guard GUARD_FRACTION tol beyond a settling estimate, towards the end regula falsi has not
            # moved (it comes at the root from one side): where the root lies between them the bracket closes
            # now, where the estimate fell short the guard moves the same end a little farther
            g = c + np.where(s == 1, 1.0, -1.0) * (GUARD_FRACTION * tol / sp)
            settled = np.abs(c - cp) <= GUARD_SETTLED * (h - l)
            moving = ~bis
            gi = np.flatnonzero((s != 0) & moving & settled & (g > l) & (g < h))
        if gi.size:
            both = F(np.concatenate([aa + c[:, None] * dd, aa[gi] + g[gi, None] * dd[gi]]),
                     np.concatenate([ww, ww[gi]]))
            fc, fg = both[:act.size], both[act.size:]
        else:
            fc = F(aa + c[:, None] * dd, ww)
        cp = c  # (copied before a guard at a zero writes into c)
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            zero = fc == 0
            pos = (fc > 0) == (fh > 0)
            nan = np.isnan(fc)
            if np.count_nonzero(nan):  # undefined inside: the half towards the end with the larger |F| is kept
                live = ~(nan | zero)
                same_hi = live & pos
                same_lo = live & ~same_hi
                nh = nan & (np.abs(fh) >= np.abs(fl))
                new_h = np.where(same_hi | nh, c, h)
                new_l = np.where(same_lo | (nan & ~nh), c, l)
                s_new = np.where(bis | nan, 0, np.where(same_hi, -1, np.where(same_lo, 1, s)))
                vh2 = np.where(same_hi, fc, np.where(nh, np.nan, vh))
                vl2 = np.where(same_lo, fc, np.where(nan & ~nh, np.nan, vl))
            else:
                live = ~zero
                same_hi = live & pos
                same_lo = live & ~same_hi
                new_h = np.where(same_hi, c, h)
                new_l = np.where(same_lo, c, l)
                s_new = np.where(bis, 0, np.where(same_hi, -1, np.where(same_lo, 1, s)))
                vh2 = np.where(same_hi, fc, vh)
                vl2 = np.where(same_lo, fc, vl)
            # Anderson-Bjorck: when the same end moves twice, scale the value kept at the other end
            scale_l, scale_h = same_hi & (s == -1) & moving, same_lo & (s == 1) & moving
            s = s_new
            m_hi = 1.0 - fc / fh
            m_lo = 1.0 - fc / fl
            fl2 = np.where(same_lo, fc, np.where(scale_l, fl * np.where(m_hi > 0, m_hi, 0.5), fl))
            fh2 = np.where(same_hi, fc, np.where(scale_h, fh * np.where(m_lo > 0, m_lo, 0.5), fh))
            t_in = None
            if gi.size:  # the guard: inside the bracket left by the estimate, it moves the end of its own sign
                gv = g[gi]
                ok = np.isfinite(fg) & (gv > new_l[gi]) & (gv < new_h[gi])
                if np.count_nonzero(ok) < ok.size:
                    gi, gv, fg = gi[ok], gv[ok], fg[ok]
                g_zero = fg == 0
                up = ((fg > 0) == (fh2[gi] > 0)) | g_zero  # the guard moves the high end (or is a zero)
                hi_i, lo_i = gi[up], gi[~up]
                new_h[hi_i], fh2[hi_i], vh2[hi_i] = gv[up], fg[up], fg[up]
                new_l[lo_i], fl2[lo_i], vl2[lo_i] = gv[~up], fg[~up], fg[~up]
                if np.count_nonzero(g_zero):
                    c = c.copy()
                    c[gi[g_zero]] = gv[g_zero]
                    zero[gi[g_zero]] = True
                # a bracket the guard closed has two fresh ends: its root read between them (the chord's zero)
                fcg = fc[gi]
                pair = np.flatnonzero(~up & np.isfinite(fcg) & (fcg != 0) & ((fcg > 0) != (fg > 0)))
                if pair.size:
                    t_in = np.full(act.size, np.nan)
                    ci, cg, fci, fgi = c[gi[pair]], gv[pair], fcg[pair], fg[pair]
                    t_in[gi[pair]] = ci + (cg - ci) * (fci / (fci - fgi))
            width = new_h - new_l
            stall = np.where((width <= 0.5 * (h - l)) | bis, 0, stall + 1)
        l, h, fl, fh, vl, vh = new_l, new_h, fl2, fh2, vl2, vh2
        wide = (width * sp >= SLOPE_WIDTH * tol) & np.isfinite(vl) & np.isfinite(vh)
        bl, bh, bvl, bvh = (np.where(wide, x, y) for x, y in ((l, bl), (h, bh), (vl, bvl), (vh, bvh)))
        closed = zero | (width * sp <= tol)
        if np.count_nonzero(closed):
            if np.count_nonzero(zero):
                t[act[zero]] = c[zero]
            if t_in is not None:
                at = closed & ~zero & np.isfinite(t_in)
                t[act[at]] = t_in[at]
            i = act[closed]
            lo[i], hi[i], flo[i], fhi[i] = l[closed], h[closed], fl[closed], fh[closed]
            slo[i], shi[i], svlo[i], svhi[i] = bl[closed], bh[closed], bvl[closed], bvh[closed]
            keep = ~closed
            act, l, h, fl, fh, aa, dd, ww, sp, s, stall, cp, vl, vh, bl, bh, bvl, bvh = (
                v[keep] for v in (act, l, h, fl, fh, aa, dd, ww, sp, s, stall, cp, vl, vh, bl, bh, bvl, bvh))
    lo[act], hi[act], flo[act], fhi[act] = l, h, fl, fh  # brackets still open after the last iteration
    slo[act], shi[act], svlo[act], svhi[act] = bl, bh, bvl, bvh
    with np.errstate(invalid="ignore"):
        best = np.where(np.abs(flo) <= np.abs(fhi), lo, hi)
    t = np.where(np.isnan(t), best, t)
    roots = a + t[:, None] * d
    if not slopes:
        return roots
    with np.errstate(invalid="ignore", divide="ignore"):
        g = np.abs(svhi - svlo) / ((shi - slo) * np.hypot(*d.T))
    return roots, g



def round_off_roots(F, a, b, fa, fb, which, fall: float):
    """The roots of the brackets ``a``-``b`` solved to round-off (``ROUND_OFF`` of the shortest), for roots whose
    ``|F|`` did not fall when solved to a tolerance, and whether it falls now, to ``fall`` times the smaller
    ``|F|`` at the bracket's ends: a zero beside the no-pair edge, where ``F`` goes as a root of the distance to
    it, falls; a pole or a jump does not. Returns ``(roots (n, 2), slopes (n,), fell (n,) bool)``.

    >>> F = lambda p, w: np.where(w == 0, np.cbrt(p[:, 0] - 1e-9), np.sign(p[:, 0] - 1e-9))  # a zero, a jump
    >>> a, b = np.array([[-1.0, 0.0]] * 2), np.array([[1.0, 0.0]] * 2)
    >>> r, g, fell = round_off_roots(F, a, b, F(a, np.arange(2)), F(b, np.arange(2)), np.arange(2), 0.5)
    >>> fell.tolist(), bool(abs(r[0, 0] - 1e-9) < 1e-11)
    ([True, False], True)
    """
    length = np.hypot(*(np.asarray(b) - np.asarray(a)).T)
    roots, slopes = segment_roots(F, a, b, fa, fb, ROUND_OFF * float(length.min()), which, True)
    with np.errstate(invalid="ignore"):
        fell = np.abs(F(roots, which)) <= fall * np.fmin(np.abs(fa), np.abs(fb))
    return roots, slopes, fell

class NearestBracket:
    """The nearest bracket of a zero found so far for each chord middle (``lo``/``flo`` to ``end``/``fe``)."""

    def __init__(self, m, f0):
        self.m, self.f_mid = m, f0
        self.lo, self.end = m.copy(), m.copy()
        self.flo, self.fe = f0.copy(), f0.copy()
        self.dist = np.full(len(m), np.inf)
        self.have = np.zeros(len(m), bool)
        self.diagonal = np.zeros(len(m), bool)

    def consider(self, idx, lo, flo, end, fe, diagonal: bool = False):
        """Offer brackets for the chords ``idx``: kept where they change sign and predict a nearer zero."""
        with np.errstate(invalid="ignore", divide="ignore"):
            ok = np.isfinite(fe) & ((fe > 0) != (flo > 0))
            d = np.hypot(*(lo - self.m[idx]).T) + np.abs(flo / (flo - fe)) * np.hypot(*(end - lo).T)
        take = ok & (d < self.dist[idx])
        i = idx[take]
        self.lo[i], self.flo[i], self.end[i], self.fe[i] = lo[take], flo[take], end[take], fe[take]
        self.dist[i] = d[take]
        self.have[i] = True
        self.diagonal[i] = diagonal

    def nearer(self, F, sides, which, tol: float):
        """For the chords whose middles have a zero to each side (``sides``: ``[(end (n, 2), value (n,))]``,
        every chord's end and value there; to each side: the end's value defined and of the other sign than
        the middle's): the bracket of the side whose root (solved to ``tol``) lies nearer the middle.
        :meth:`consider` predicts a zero's distance by the secant from the middle to the end, which across
        a kink of ``F`` (the smallest of two margins, a thin wedge of one sign) reads the steep side's far
        zero as the nearer: 11/22 internal with its 15-tooth cutter at tol 1e-5, a chord of the tip sweep's
        line along its wedge's gentle side (slope 0.012, its middle 9e-8 from it) was split at the steep
        side's zero 2.2e-4 off, and the line zigzagged across the wedge (4.4 tol).

        >>> F = lambda p, w: np.minimum(1e-2 * (1e-4 - p[:, 1]), p[:, 1] + 1e-4)  # a wedge, zeros at +-1e-4
        >>> b = NearestBracket(np.zeros((1, 2)), np.array([1e-6]))
        >>> ends = [np.array([[0.0, y]]) for y in (1e-3, -1e-3)]
        >>> for e in ends:
        ...     b.consider(np.array([0]), b.m, b.flo, e, F(e, 0))
        >>> bool(b.end[0, 1] < 0)  # the secant's choice: the steep side's zero
        True
        >>> b.nearer(F, [(e, F(e, 0)) for e in ends], np.array([0]), 1e-9)
        >>> bool(b.end[0, 1] > 0)
        True
        """
        with np.errstate(invalid="ignore"):
            idx = np.flatnonzero(np.all([np.isfinite(fe) & ((fe > 0) != (self.f_mid > 0)) for _, fe in sides], axis=0))
        if not idx.size:
            return
        sides, which = [(e[idx], fe[idx]) for e, fe in sides], which[idx]
        k = len(idx)
        m = self.m[idx]
        ends = np.concatenate([e for e, _ in sides])
        fes = np.concatenate([fe for _, fe in sides])
        ms = np.tile(m, (len(sides), 1))
        f0s = np.tile(self.f_mid[idx], len(sides))
        roots = segment_roots(F, ms, ends, f0s, fes, tol, np.tile(which, len(sides)))
        dist = np.hypot(*(roots - ms).T).reshape(len(sides), k)
        s = np.argmin(dist, axis=0)
        r = np.arange(k)
        self.lo[idx], self.flo[idx] = m, self.f_mid[idx]
        self.end[idx] = ends.reshape(len(sides), k, 2)[s, r]
        self.fe[idx] = fes.reshape(len(sides), k)[s, r]
        self.dist[idx] = dist[s, r]
        self.have[idx] = True
        self.diagonal[idx] = False

    def ladder(self, F, idx, n, reach, which, floor, one_side=None, spacing=None):
        """Offer the chords ``idx`` the sign change nearest to their middles along their normals ``n``,
        sampled at distances falling geometrically by ``LADDER_RATIO`` from ``reach`` down to ``floor`` to
        either side: a zero of a strip (or of a saddle's thin wedge) narrower than a sampled search's
        spacing is seen. ``one_side`` (a mask over ``idx``): those chords are offered a sign change only
        where their normal meets none on the other side (a chord lying inside a thin part, both sides
        near, is not on either). ``spacing`` (per chord, inf: none): samples added no farther apart than
        that (nor than ``reach / LADDER_EVEN``) out to ``reach``; the ladder's spacing is half the distance, and
        a strip of the other sign wider than ``spacing`` lying between two of its rungs is seen.

        >>> F = lambda p, w: np.abs(p[:, 1] - 3e-4) - 1e-4  # a strip 2e-4 wide, 3e-4 from the middle
        >>> b = NearestBracket(np.zeros((1, 2)), np.array([2e-4]))
        >>> bool(F(np.array([[0.0, y] for y in (-1.0, -0.5, 0.5, 1.0)]), 0).min() > 0)  # none at a sampled search
        True
        >>> b.ladder(F, np.array([0]), np.array([[0.0, 1.0]]), np.array([1.0]), np.array([0]), 1e-6)
        >>> bool(b.have[0] and b.lo[0, 1] < 2e-4 < b.end[0, 1])
        True
        >>> G = lambda p, w: (p[:, 1] + 0.3) * (p[:, 1] + 0.45)  # a strip -0.45 < y < -0.3, between two rungs
        >>> b = NearestBracket(np.zeros((1, 2)), np.array([0.135]))
        >>> args = (G, np.array([0]), np.array([[0.0, 1.0]]), np.array([1.0]), np.array([0]), 1e-3)
        >>> b.ladder(*args)
        >>> bool(b.have[0])
        False
        >>> b.ladder(*args, spacing=np.array([1e-3]))
        >>> bool(b.have[0] and b.end[0, 1] < -0.3 < b.lo[0, 1])
        True
        """
        for r, i in enumerate(idx):
            d = reach[r] * LADDER_RATIO ** np.arange(max(1, int(np.ceil(np.log(max(reach[r] / floor, 1.0))
                                                                              / -np.log(LADDER_RATIO))) + 1))
            if spacing is not None and np.isfinite(spacing[r]):
                h = max(float(spacing[r]), reach[r] / LADDER_EVEN)
                d = np.union1d(d, h * np.arange(1, int(reach[r] / h) + 1))[::-1]  # descending, as the ladder's
            s = np.concatenate([-d, [0.0], d[::-1]])
            v = F(self.m[i] + s[:, None] * n[r], np.full(s.size, which[r]))
            seen = []
            for side in (slice(d.size, None), slice(d.size, None, -1)):  # outward from the middle, each way
                ss, vv = s[side], v[side]
                with np.errstate(invalid="ignore"):
                    ch = np.flatnonzero(np.isfinite(vv[1:]) & np.isfinite(vv[:-1]) & ((vv[1:] > 0) != (vv[:-1] > 0)))
                if ch.size:
                    seen.append((ss, vv, ch[0]))
            if one_side is not None and one_side[r] and len(seen) > 1:
                continue
            for ss, vv, j in seen:
                self.consider(np.array([i]), (self.m[i] + ss[j] * n[r])[None], vv[j:j + 1],
                              (self.m[i] + ss[j + 1] * n[r])[None], vv[j + 1:j + 2])


def two_lines(F, A, B, n, which, mask, h):
    """True for the chords ``A``-``B`` (``(k, 2)``, unit normals ``n``) marked in ``mask`` whose ends lie
    on two different zero lines: ``F`` grows towards opposite sides of the chord at its two ends (read
    ``h`` to either side of each along ``n``). A chord of one line has ``F`` growing towards the same side
    at both ends (its line turns by less than a right angle from the chord's direction); a chord from
    one side of a strip to the other (the two lines bounding a thin region of one sign) has not. Nor has
    a chord across a thin loop or a wedge, whose two sides are one line joined round its turn: cut too,
    its ends are carried on round the turn (:func:`~gearkit.blocking.ends.extend_ends`).

    >>> F = lambda p, w: np.abs(p[:, 1]) - 1e-3  # a strip |y| < 1e-3
    >>> A, B = np.array([[0.0, -1e-3]]), np.array([[0.1, 1e-3]])  # from one side to the other
    >>> n = np.array([[-0.02, 1.0]]) / np.hypot(0.02, 1.0)
    >>> two_lines(F, A, B, n, [0], [True], 2e-4).tolist()
    [True]
    >>> two_lines(F, A, A + [0.1, 0.0], n, [0], [True], 2e-4).tolist()  # along one side
    [False]
    """
    A, B, n, which = (np.asarray(v) for v in (A, B, n, which))
    out = np.zeros(len(A), bool)
    i = np.flatnonzero(mask)
    if i.size:
        d = h * n[i]
        V = F(np.concatenate([A[i] + d, A[i] - d, B[i] + d, B[i] - d]), np.tile(which[i], 4)).reshape(4, -1)
        with np.errstate(invalid="ignore"):
            out[i] = np.all(np.isfinite(V), axis=0) & (np.sign(V[0] - V[1]) * np.sign(V[2] - V[3]) < 0)
    return out
