"""The contact solver's search: which polyline intervals of which driver halves may hold a bound.

Every driver half that reaches the mate's tip circle (:attr:`Mesh.half_reach`) is placed in the
mate's frame at its polyline samples, and the bound functions (``w(rho) - u`` for the upper bound,
``w(rho) + u`` for the lower one; see :mod:`gearkit.contact.solver`) are read there, the mate's
``w`` interpolated in its table. Between two samples the exact function can dip below them by at
most ``dip`` (the chord's deviation plus the mate's bending over the chord, as a normal distance
over the local arm of the mate's normal). An interval is picked when its ends come within ``dip``
of its half's best value, in every half that may come within the contact tolerance of the best
bound at its driver angle.

The halves are searched in blocks of driver angles, each block's arrays laid out samples by halves
(the halves along the long, contiguous axis) and small enough to stay in the processor's caches
and in memory the allocator hands back at once (arrays of megabytes are mapped afresh on every
allocation, and touching their new pages costs more than the arithmetic on them). Each value is
computed by the same operations on the same numbers as over the whole batch at once: the picks
and the bounds do not depend on the blocks.
"""
from __future__ import annotations

import numpy as np

__all__ = ["search"]

#: elements (samples x halves) of one block's arrays: 16384 float64 are 128 KiB
_BLOCK = 1 << 14
_SB = np.array([1.0, -1.0])  # the sign of u in the bound: upper w - u, lower w + u


def search(mesh, frame, r_n, n, contact_tol, bounds):
    """The intervals to refine, over halves ``A`` at ``n`` driver angles.

    Parameters
    ----------
    mesh : Mesh
    frame : (7, A) float64, :meth:`Mesh.frames` of each half
    r_n : (A,) int, the driver angle of each half (sorted)
    n : int, the number of driver angles
    contact_tol : float, mm
    bounds : tuple of int, the bounds searched (0 upper, 1 lower)

    Returns
    -------
    best : (A, 2) float64, each half's least sample value of either bound (the tip crossings' included)
    i_a, i_b, i_m : (I,) int, the picked intervals: half, bound, interval (ordered by half, bound,
        interval)
    fa, fb : (I,) bool, whether the interval's start and end lie inside the mate's tip circle
    """
    size = mesh.half_reach[2]
    per_block = max(1, _BLOCK // size)  # halves per block, cut at driver angles
    cuts = np.searchsorted(r_n, np.arange(0, n, max(1, per_block * n // max(len(r_n), 1))))
    cuts = np.unique(np.concatenate([cuts, [len(r_n)]]))
    best = np.empty((len(r_n), 2))
    searched = np.isin(np.arange(2), bounds)[None, :]
    parts = []
    for lo, hi in zip(cuts[:-1], cuts[1:]):
        first = r_n[lo]
        b, i_a, *rest = _block(mesh, frame[:, lo:hi], r_n[lo:hi] - first, int(r_n[hi - 1] - first) + 1,
                               contact_tol, searched)
        best[lo:hi] = b
        parts.append((i_a + lo, *rest))
    if not parts:
        empty = np.zeros(0, int)
        return best, empty, empty, empty, empty.astype(bool), empty.astype(bool)
    return (best, *(np.concatenate([p[i] for p in parts]) for i in range(5)))


def _block(mesh, frame, r_n, n, contact_tol, searched):
    """:func:`search` of one block: arrays ``(samples, halves)``; ``searched`` (1, 2) bool, the bounds searched."""
    drv, mate = mesh.driver, mesh.mate
    arm_scale, pitch = mesh.arm_scale, mesh.pitch2
    size = mesh.half_reach[2]
    pts, chord = drv.points[:size], drv.chord[:size - 1]
    rho, x, y = mesh.mate_radius(pts[:, :1], pts[:, 1:], frame[:, None, :])  # (M1, A)
    # beyond the mate's tip circle (about a third of the samples) the width is infinite, the arm the radial scale
    # and the bend nothing: the table is read, and u formed, only on the flank side and next to it
    free = mate.free(rho)
    on = np.flatnonzero(~free)
    near = ~free
    near[1:] |= ~free[:-1]
    near[:-1] |= ~free[1:]
    near = np.flatnonzero(near)
    u = np.zeros(rho.shape)  # (w = inf where no u is formed: w - u and w + u are inf either way)
    u.ravel()[near] = mesh.mate_offset(x.ravel()[near], y.ravel()[near],
                                       frame[6][near % rho.shape[1]] if mesh.kind == "rack" else None)
    r_on = rho.ravel()[on]
    at = mate.lookup(r_on)
    w = np.full(rho.shape, np.inf)
    w.ravel()[on] = mate.coarse(r_on, at)
    big_u = np.empty((2,) + rho.shape)  # (2, M1, A): w - u, w + u
    np.subtract(w, u, out=big_u[0])
    np.add(w, u, out=big_u[1])
    finite = np.isfinite(w)
    # the intervals that cross the mate's tip circle (few): the bound at the crossing (in any order: every use
    # below is a minimum or a mask)
    c_m, c_a = np.nonzero(finite[:-1] != finite[1:])
    r0, r1, u0 = rho[c_m, c_a], rho[c_m + 1, c_a], u[c_m, c_a]
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.clip((mate.rho_tip - r0) / (r1 - r0), 0.0, 1.0)
    du = np.mod(u[c_m + 1, c_a] - u0 + pitch / 2, pitch) - pitch / 2  # across a wrap
    u_c = np.mod(u0 + frac * du + pitch / 2, pitch) - pitch / 2
    big_c = mate.w_tip - _SB[None, :] * u_c[:, None]  # (C, 2)
    best = big_u.min(axis=1).T.copy()  # (A, 2)
    np.minimum.at(best, c_a, big_c)  # a half's curve may cross the tip circle more than once
    # how far the exact function can dip below an interval's ends: the driver's chord deviation
    # plus the mate's bending over the chord, as a normal distance over the arm scale
    rho_mid = 0.5 * (rho[:-1] + rho[1:])
    mid = np.flatnonzero(~(free[:-1] & free[1:]))  # (between two free samples the midpoint is free)
    r_mid = rho_mid.ravel()[mid]
    at_mid = mate.lookup(r_mid)
    bend = np.zeros(rho_mid.shape)
    bend.ravel()[mid] = mate.curvature(r_mid, at_mid)
    arm = mate.off_arm(rho)
    arm.ravel()[on] = mate.arm(r_on, at)
    arm_mid = mate.off_arm(rho_mid)
    arm_mid.ravel()[mid] = mate.arm(r_mid, at_mid)
    arm = np.minimum(np.minimum(arm[:-1], arm[1:]), arm_mid)
    dip = (mesh.tol + bend * chord[:, None] ** 2 / 8.0) / np.maximum(arm, 1e-12 * arm_scale)  # (M, A)
    if mate.crest:  # next to a rounded crest the bound falls like a square root: always look
        dip[c_m, c_a] = np.inf
    glob = np.full((n, 2), np.inf)  # the best of each driver angle (its halves are consecutive)
    first = np.flatnonzero(np.concatenate([[True], r_n[1:] != r_n[:-1]]))
    glob[r_n[first]] = np.minimum.reduceat(best, first, axis=0)
    active = best - dip.max(axis=0)[:, None] <= glob[r_n] + contact_tol / arm_scale
    active &= searched
    # the intervals of the active halves (and bounds) that come within their dip of the best
    p_a, p_b = np.nonzero(active)
    ends = big_u[p_b, :, p_a]  # (P, M1)
    ends = np.minimum(ends[:, :-1], ends[:, 1:])
    reach = best[p_a, p_b][:, None] + dip[:, p_a].T
    pick = ends <= reach
    at_pick = np.full(active.shape, -1)
    at_pick[p_a, p_b] = np.arange(len(p_a))
    for b in range(2):  # an interval crossing the tip circle: its bound at the crossing
        k = at_pick[c_a, b]
        ok = np.flatnonzero(k >= 0)
        pick[k[ok], c_m[ok]] |= big_c[ok, b] <= reach[k[ok], c_m[ok]]
    k, i_m = np.nonzero(pick)
    i_a = p_a[k]
    return best, i_a, p_b[k], i_m, finite[i_m, i_a], finite[i_m + 1, i_a]

