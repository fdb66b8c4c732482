"""The tip sweep of internal pairs, vectorised over many pairs: one function for the check and the map.

:func:`sweep_depth` sweeps a tip corner of each gear of an internal pair along its relative
(trochoidal) path through the mate's teeth over a whole pinion turn and returns the largest depth
it reaches inside a mate's tooth. :func:`~gearkit.pair.internal.tip_sweep` (the check's
``tip_interference``) calls it for one pair, the blocking arrays for thousands of shift pairs at
once: the map and the check cannot disagree.

Geometry: the ring at O2 = 0, the pinion at O1 = (0, a), both turning counter-clockwise, the ring by
``phi z1/z2``; pinion tooth 0 and ring space 0 centred on +y at ``phi = 0``. A tooth is the region
between two radii and its two involute flanks; a point's depth in it is the smallest of its
distances to those boundaries (the flank distance along the base-circle tangent,
``r_b (half(r) - |angle|)``), negative outside.

>>> from gearkit.pair import PairSpec, pair_geometry
>>> from gearkit.pair.internal import tip_sweep_depth
>>> from gearkit.families.involute import ShaperCutter
>>> g = pair_geometry(PairSpec(46, 49, 1.0, kind="internal", tool2=ShaperCutter(20)))
>>> round(tip_sweep_depth(g)[0], 4)   # zero shifts, z2 - z1 = 3: the tips jam
0.3919
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.pair.tooling import half_angle

__all__ = ["sweep_depth", "SWEEP_START", "SWEEP_BAND", "SWEEP_ENOUGH", "SWEEP_GRADIENT"]

SWEEP_START = 64  #: intervals over a pinion turn the branch and bound starts from
SWEEP_BAND = 0.5  #: maxima above this fraction of the resolution are refined (the margin is exact near 0)
SWEEP_SPLIT = 4  #: an interval of the branch and bound that may hold the maximum is cut into this many
SWEEP_ZOOM = 17  #: samples across the bracket of the deepest sample, per refining step (it shrinks 8 times)
SWEEP_REFINE = 10  #: refining steps (the bracket, 4 final half widths of the branch and bound, ~1e-5 rad,
#: shrinks below 1e-14 rad)
SWEEP_SLIDES = 16  #: moves of the zoom's bracket, as wide, where its deepest sample is one of its ends
SWEEP_ENOUGH = 0.01  #: (m_n) the blocking map's sweep stops beyond this depth past the resolution
SWEEP_BLOCK = 4096  #: samples of phi evaluated at once (each of the corners' ~100 array operations then
#: works in the processor's cache: 1.5x faster than all of a round's samples at once, the same values)
SWEEP_GRADIENT = 2.0  #: bound on the gradient of a tooth's depth function in the plane (it is at most
#: sqrt(2): radially sin(a_y) <= 1, tangentially r_b / r <= 1 above the base circle)


def _wrap(angle, period):
    return (angle + period / 2) % period - period / 2


def _corners(phi, w, c):
    """Depths of the two tip corners in the mate's teeth at ``phi`` ((2, m): the pinion's in the ring's
    teeth, the ring's in the pinion's) and, with a half width ``w``, how much more each can reach over
    ``[phi - w, phi + w]`` (the bound's slack). ``c``: the corners' parameters, (2, m) or (2, 1).

    A corner lies at radius ``r`` from its own centre, ``a`` from the mate's, at angle ``chi`` from the
    line of centres (``rate`` per radian of ``phi``); in the mate's frame its polar angle is
    ``Theta(chi) - omega phi`` (``sign = -1`` flips it by pi: the ring's corner, seen from the pinion
    past the ring's centre).

    Slack: the smaller of a first-order bound (the mate's frame turns about the pitch point at
    ``1 - k`` per radian: the corner moves at most ``(1 - k) D`` with ``D`` its largest distance from
    the pitch point, its depth at most ``SWEEP_GRADIENT`` times that) and a second-order one (the
    active piece of the depth -- a radius, or one flank -- has slope ``g'`` at ``phi`` and curvature at
    most ``K`` over the interval, from bounds on the corner's radius and angle derivatives; the depth
    is the smallest of the pieces, so it stays below the active piece's parabola ``g'w + K w^2/2``).
    Across the base circle or the middle of a space (kinks of the wrong sense) ``K`` is infinite.
    """
    r, a, rate, sign, rb = c["r"], c["a"], c["rate"], c["sign"], c["rb"]
    chi = c["chi0"] + rate * phi
    cs, sn = np.cos(chi), np.sin(chi)
    ar = a * r
    rho = np.sqrt(np.maximum(a * a + r * r + 2 * ar * cs, 0.0))
    theta = np.arctan2(sign * r * sn, sign * (a + r * cs)) - c["omega"] * phi
    delta = _wrap(theta - c["centre"], c["pitch"])
    rr = np.maximum(rho, rb)
    ay = np.arccos(np.minimum(rb / rr, 1.0))
    half = c["h0"] + c["sh"] * (c["inv_t"] - (np.tan(ay) - ay))
    pieces = (rho - c["r_in"], c["r_out"] - rho, (half - np.abs(delta)) * rb)
    depth = np.minimum(np.minimum(pieces[0], pieces[1]), pieces[2])
    if w is None:
        return depth
    far = np.minimum(np.abs(_wrap(chi, 2 * math.pi)) + rate * w, math.pi)
    # first order: the corner's largest distance from the pitch point of its own gear
    cf = np.cos(np.minimum(np.abs(_wrap(chi + c["turn"], 2 * math.pi)) + rate * w, math.pi))
    rw = c["r_w"]
    first = c["speed"] * np.sqrt(np.maximum(r * r + rw * rw - 2 * r * rw * cf, 0.0)) * w
    # second order: derivatives of rho and Theta in chi at chi, and their bounds over the interval
    rho_min = np.sqrt(np.maximum(a * a + r * r + 2 * ar * np.cos(far), 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        d_rho = -ar * sn / rho * rate
        d_theta = r * (r + a * cs) / rho ** 2 * rate - c["omega"]
        dr_max = np.minimum(ar / rho_min, c["short"])
        d2r = (ar / rho_min + dr_max ** 2 / rho_min) * rate ** 2
        d2t = (ar / rho_min ** 2 + 2 * r * (r + a) * dr_max / rho_min ** 3) * rate ** 2
        dt_max = r * (r + a) / rho_min ** 2 * rate + c["omega"]
        h2 = np.where(rho_min > rb, rb / (rho_min ** 2 * np.sqrt(rho_min ** 2 - rb ** 2)), np.inf)
        flank_slope = -c["sh"] * np.sin(ay) * d_rho - np.sign(delta) * rb * d_theta
        flank_k = rb * h2 * (dr_max * rate) ** 2 + d2r + rb * d2t
        flank_k = np.where(np.abs(delta) + dt_max * w >= c["pitch"] / 2, np.inf, flank_k)  # a space's middle
        radial = pieces[0] <= pieces[1]
        flank = pieces[2] < np.minimum(pieces[0], pieces[1])
        slope = np.where(flank, flank_slope, np.where(radial, d_rho, -d_rho))
        curv = np.where(flank, flank_k, d2r)
        second = np.abs(slope) * w + 0.5 * curv * w * w
    slack = np.fmin(first, np.where(np.isnan(second), np.inf, second))
    return depth, slack


def sweep_depth(sec, z1: int, z2: int, a, ra1, ra2, rl1, rf2, t1, t2, rw2, resolution: float,
                enough: float = math.inf):
    """The largest depth (mm) of a tip corner inside a mate's tooth over a pinion turn, and the pinion
    angle, of many internal pairs at once: arrays (n,) -> ((n,), (n,)).

    Per pair: the centre distance ``a``, the pinion's tip ``ra1``, the ring's tip ``ra2`` (not inside
    its base circle), the radius ``rl1`` above which a pinion tooth counts (its form circle, not inside
    its base circle), the ring's root ``rf2``, the thickness coefficients ``t1``, ``t2`` and the ring's
    working radius ``rw2``; ``sec``, ``z1``, ``z2`` are shared. NaN parameters give depth -inf.

    ``enough`` (mm): a pair whose depth is found beyond it is done (its depth is then a lower bound,
    above ``enough``: the blocking map needs the margin exact near its zero only); the check leaves it
    infinite and gets every depth exact.

    One corner of each gear suffices: the mirror image of the mesh (x -> -x) is the mesh at ``-phi``
    with the other corner, and the sweep's range (a whole pinion turn) is symmetric.

    The maximum is found by a branch and bound on ``phi``, vectorised over (pair, interval): an
    interval whose mid-point depth plus its slack (see :func:`_corner`) stays below
    ``max(best, SWEEP_BAND resolution)`` cannot hold the maximum (nor an interference) and is
    dropped; the rest are cut in ``SWEEP_SPLIT`` until the slack is below ``resolution / 100``; then
    zooming samples refine, above ``SWEEP_BAND resolution``, the deepest sample and every interval left
    whose bound passes it (two maxima closer than the slack, e.g. of the two corners: either may be the
    deeper) to round-off (climbing beyond the branch and bound's bracket where the depth keeps rising
    there). A maximum above ``SWEEP_BAND resolution`` is thus found to round-off; below it, a lower
    bound is returned (contact along the path of contact, depth 0, is not refined).
    """
    a, ra1, ra2, rl1, rf2, t1, t2, rw2 = (np.atleast_1d(np.asarray(v, dtype=float))
                                          for v in (a, ra1, ra2, rl1, rf2, t1, t2, rw2))
    n = a.size
    rb1 = z1 * sec.mt * math.cos(sec.alpha_t) / 2
    rb2 = z2 * sec.mt * math.cos(sec.alpha_t) / 2
    k = z1 / z2
    c2 = math.pi / z2
    with np.errstate(invalid="ignore", divide="ignore"):
        s1 = np.maximum(half_angle(sec, z1, t1, ra1, False), 0.0)
        s2 = np.maximum(half_angle(sec, z2, t2, ra2, True), 0.0)

    def pick(u, v):  # row 0: the pinion's corner in the ring's teeth; row 1: the ring's in the pinion's
        return np.stack([u, v])

    const = {"rate": pick(1.0, k), "omega": pick(k, 1.0), "sign": pick(1.0, -1.0), "rb": pick(rb2, rb1),
             "centre": pick(c2, 0.0), "pitch": pick(2 * math.pi / z2, 2 * math.pi / z1),
             "sh": pick(-1.0, 1.0), "inv_t": math.tan(sec.alpha_t) - sec.alpha_t,
             "turn": pick(0.0, math.pi), "speed": SWEEP_GRADIENT * (1.0 - k)}
    const = {key: (v[:, None] if np.ndim(v) == 1 else v) for key, v in const.items()}
    per = {"r": pick(ra1, ra2), "a": pick(a, a), "chi0": pick(s1, c2 + s2 + math.pi),
           "h0": pick((math.pi / 2 + t2) / z2, (math.pi / 2 + t1) / z1), "r_in": pick(ra2, rl1),
           "r_out": pick(rf2, ra1), "r_w": pick(rw2 - a, rw2), "short": pick(np.minimum(a, ra1), np.minimum(a, ra2))}
    keys = list(per)
    table = np.stack([per[key] for key in keys])  # (keys, 2, n): one gather per evaluation

    def depth(i, phi, w=None):
        """max of the two corners' depths at ``phi`` (pairs ``i``); with a half width ``w``, also
        their bound over ``[phi - w, phi + w]`` and its slack (in blocks of ``SWEEP_BLOCK`` samples)."""
        if i.size > SWEEP_BLOCK:
            parts = [depth(i[k:k + SWEEP_BLOCK], phi[k:k + SWEEP_BLOCK], w) for k in range(0, i.size, SWEEP_BLOCK)]
            return np.concatenate(parts) if w is None else tuple(np.concatenate(p) for p in zip(*parts))
        c = dict(const)
        c.update(zip(keys, table[:, :, i]))
        out = _corners(phi[None], w, c)
        if w is None:
            return out.max(axis=0)
        d, sl = out
        b = d + sl
        top = np.argmax(np.where(np.isnan(b), -np.inf, b), axis=0)
        cols = np.arange(d.shape[1])
        return d.max(axis=0), b[top, cols], np.maximum(sl[top, cols], 0.0)

    floor = SWEEP_BAND * resolution
    stop = resolution / 100
    best, at, width = np.full(n, -np.inf), np.zeros(n), np.full(n, math.pi / SWEEP_START)
    w = math.pi / SWEEP_START
    owner = np.repeat(np.arange(n), SWEEP_START)
    mid = np.tile(-math.pi + w * (2 * np.arange(SWEEP_START) + 1), n)
    ends = []  # (owner, mid, half width, bound): intervals cut no further that may yet hold the maximum
    with np.errstate(invalid="ignore", divide="ignore"):
        while owner.size:
            d, bound, slack = depth(owner, mid, w)
            d = np.where(np.isnan(d), -np.inf, d)
            starts = np.flatnonzero(np.r_[True, owner[1:] != owner[:-1]])
            top = np.maximum.reduceat(d, starts)
            o = owner[starts]
            hit = np.flatnonzero(d == np.repeat(top, np.diff(np.r_[starts, owner.size])))
            first = hit[np.unique(owner[hit], return_index=True)[1]]
            up = top > best[o]
            best[o[up]], at[o[up]], width[o[up]] = top[up], mid[first[up]], w
            open_ = (bound > np.maximum(best, floor)[owner]) & (best < enough)[owner]
            keep = open_ & (slack >= stop)
            done = np.flatnonzero(open_ & ~keep)
            ends.append((owner[done], mid[done], np.full(done.size, w), bound[done]))
            owner, m = owner[keep], mid[keep]
            owner = np.repeat(owner, SWEEP_SPLIT)
            w /= SWEEP_SPLIT
            mid = (m[:, None] + w * (2 * np.arange(SWEEP_SPLIT) + 1 - SWEEP_SPLIT)).ravel()
        # zoom, where it matters (above the floor), on the deepest sample's neighbourhood and on every interval
        # left whose bound passes it (a second maximum within the stop of the first, e.g. of the other corner:
        # 34/76 shaper 33, two maxima 2.8e-7 m_n apart, the lower one refined): SWEEP_ZOOM samples across
        # each bracket, then the bracket around the best of them (the maximum is the only one there).
        # A bracket whose deepest sample is one of its ends does not hold the maximum (an interval the
        # branch and bound left for its small slack may hold it, beyond the bracket): the bracket moves
        # to be centred there, as wide, up to SWEEP_SLIDES times
        live = np.flatnonzero(np.isfinite(best) & (best > floor) & (best < enough))
        if not live.size:
            return best, at
        e_owner, e_mid, e_w, e_bound = (np.concatenate(v) for v in zip(*ends))
        more = (e_bound > best[e_owner]) & (best[e_owner] > floor) & (best[e_owner] < enough)
        more &= (e_mid != at[e_owner]) | (e_w != width[e_owner])  # the deepest sample's bracket is zoomed anyway
        pair = np.concatenate([live, e_owner[more]])  # the pair of each bracket
        half = np.concatenate([width[live], e_w[more]])
        h = 2 * half / (SWEEP_ZOOM - 1)  # the bracket [centre - 2 half, centre + 2 half]: its sample step
        x0 = np.concatenate([at[live], e_mid[more]]) - 2 * half
        grid = np.arange(SWEEP_ZOOM)
        shrunk, slid = np.zeros(pair.size, int), np.zeros(pair.size, int)
        while pair.size:
            xs = x0[:, None] + h[:, None] * 2 * grid
            f = depth(np.repeat(pair, SWEEP_ZOOM), xs.ravel()).reshape(xs.shape)
            j = np.argmax(np.where(np.isnan(f), -np.inf, f), axis=1)
            rows = np.arange(pair.size)
            fj, xj = f[rows, j], xs[rows, j]
            lead = np.lexsort((-fj, pair))  # per pair, its deepest bracket's sample first
            lead = lead[np.r_[True, pair[lead][1:] != pair[lead][:-1]]]
            up = fj[lead] > best[pair[lead]]
            best[pair[lead][up]], at[pair[lead][up]] = fj[lead][up], xj[lead][up]
            slide = ((j == 0) | (j == SWEEP_ZOOM - 1)) & (slid < SWEEP_SLIDES)
            x0 = np.where(slide, xj - (SWEEP_ZOOM - 1) * h, xj - 2 * h)
            h = np.where(slide, h, 4 * h / (2 * (SWEEP_ZOOM - 1)))
            slid, shrunk = slid + slide, shrunk + ~slide
            more = shrunk < SWEEP_REFINE
            pair, x0, h, shrunk, slid = pair[more], x0[more], h[more], shrunk[more], slid[more]
    return best, at
