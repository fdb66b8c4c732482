"""Continuation over driver angles: the minimiser starts where the neighbouring angles' minima lie.

The contact solver refines the same polyline intervals of the same driver halves at consecutive driver
angles, and a minimum moves little from one angle to the next (where the angles lie :func:`close`: node
angles at most ``REACH`` of a driver pitch apart; coarser grids are minimised afresh). So the rows of every
``NODE_EVERY``-th angle (and of the last) are minimised afresh (:func:`~gearkit.contact.minimise.minimise`: probes, then
Newton), and every other row that is minimised at a node angle too (the same driver tooth, half, bound
and interval: its ``key``) starts Newton's method from there: the parameter interpolated linearly between
the nodes before and after it, or the one node's parameter where only one has the row. A start is within
a few units of ``(NODE_EVERY dphi)^2`` of the minimum, so Newton converges in one to three steps where the
probes cost seven evaluations and Newton four or five more from the best probe; an end minimum (the
function rising from the interval's end: the neighbour interval of a contact, a corner contact) is
confirmed by one evaluation on the end. The instants a pair enters or leaves contact, between two steps
of a cycle, start every row from those two steps' minima (``given``).

The fallback is the fresh minimisation: a row without a start, a row whose interval ends on a corner of the
driver (a join of its pieces that is not smooth, where the bound can have a second minimum on the corner
itself), and any row :func:`~gearkit.contact.minimise.newton_from` does not confirm (an evaluation not finite,
no convergence in ``ITERATIONS`` steps, a minimum more than a quarter of the interval from its start: no
continuation of it; on the cycloid pair 8/64 at 64 steps such a start would settle on a node beside a second,
shallow minimum; an end where the function's second-order model does not rise over a quarter of the interval:
a cycloid flank's end on the pitch circle has a nil slope, its parametrisation stationary at the cusp). On the exact pieces, or on tables without derivatives, every row is minimised afresh.

The minima are those of the fresh path to round-off: the same stationary point found from another start
(their parameters agree within Newton's tolerance, their values to the last bits), the same end where the
function rises from it. What continuation assumes is what the probes assume: the bound function has one
minimum on a polyline interval (chords within the mesh tolerance are far shorter than the flanks'
curvature radii).

Examples
--------
Rows of one key (5, of 10) at angles 0 and 8, nodes, and at angle 4 between them, whose start is the mean of
the nodes' minimisers:

>>> step = np.array([0, 8, 4])
>>> nodes(step).tolist()
[True, True, False]
>>> code, t = step[:2] * 10 + 5, np.array([0.25, 0.75])
>>> starts(code, t, 10, np.array([0]), np.array([8]), np.array([0.5]), np.array([5])).tolist()
[0.5]
"""
from __future__ import annotations

import numpy as np

from gearkit.contact.minimise import minimise, newton_from

__all__ = ["ITERATIONS", "NODE_EVERY", "REACH", "close", "continued", "driver_derivatives", "nodes", "row_key",
           "starts"]

#: driver angles between two minimised afresh
NODE_EVERY = 8
#: most Newton steps of a continued row before it is minimised afresh
ITERATIONS = 6
#: starts at most this fraction of a driver pitch apart: a contact then moves along its flank by less than a
#: polyline interval between them (a cycle of 24 steps, nodes a third of a pitch apart, settled a cycloid
#: row on a second minimum its start lay next to)
REACH = 1.0 / 32.0


def close(spacing, pitch):
    """Whether starts ``spacing`` (rad) apart are close enough for continuation (:data:`REACH` of ``pitch``)."""
    return bool(spacing <= REACH * pitch)


def row_key(mesh, tooth, half, bound, interval, lane, lanes):
    """What a row minimises, the same at every driver angle: ``(key, span)``, ``key`` (int64) in ``[0, span)`` from
    the driver tooth (absolute index), its half (0, 1), the bound (0, 1), the polyline interval and the lane."""
    m = len(mesh.driver.chord)
    key = (((np.asarray(tooth, np.int64) % mesh.z1) * 4 + half * 2 + bound) * m + interval) * lanes + lane
    return key, mesh.z1 * 4 * m * lanes


def nodes(step):
    """Rows ``(n,)`` at a node angle: every :data:`NODE_EVERY`-th driver angle of ``step`` (int) and the last."""
    return (step % NODE_EVERY == 0) | (step == step.max(initial=0))


def starts(code, t, span, before, after, frac, key):
    """Start parameters interpolated between the rows of ``key`` at angles ``before`` and ``after`` (weight ``frac``
    on the later): ``code`` (sorted: ``angle * span + key``) and ``t`` are the rows solved; the one found where
    only one is, nan where neither is."""
    found, at = [], []
    for c in (before, after):
        want = np.asarray(c, np.int64) * span + key
        i = np.minimum(np.searchsorted(code, want), max(len(code) - 1, 0))
        hit = code[i] == want if len(code) else np.zeros(len(want), bool)
        found.append(hit)
        at.append(np.where(hit, t[i] if len(code) else 0.0, np.nan))
    both = at[0] + frac * (at[1] - at[0])
    return np.where(found[0] & found[1], both, np.where(found[0], at[0], at[1]))


def continued(task, lo, hi, step, key, span, given=None, fine=True):
    """:func:`~gearkit.contact.minimise.minimise` of ``task`` on ``[lo, hi]`` with continuation over the driver
    angles: ``(value, parameter)``.

    Parameters
    ----------
    task : the solver's bound functions (with ``subset``), one row each
    lo, hi : (n,) float64, the rows' intervals
    step : (n,) int, each row's driver angle (an index on an even grid)
    key, span : (n,) int64 and int, what a row minimises (:func:`row_key`)
    given : (code, t, position) or None
        Rows solved before (``code`` sorted) and each row's position (float) on their grid of angles: every row
        starts there, none is a node.
    fine : bool
        The node angles lie :func:`close` (without ``given``; otherwise every row is minimised afresh).
    """
    if not task.smooth or (given is None and not fine):
        return minimise(task, lo, hi)
    value, t = np.empty(len(lo)), np.empty(len(lo))
    # next to a corner of the driver (a join of its pieces that is not smooth) the bound can have a second
    # minimum, on the corner: those intervals are probed afresh
    drv, m = task.mesh.driver, task.interval
    corner = drv.corner_end[m] | drv.corner_end[m + 1]
    if given is None:
        step = step - step.min(initial=0)  # the first angle is a node
        node = nodes(step) | corner
        at = np.flatnonzero(node)
        if at.size:
            value[at], t[at] = minimise(task.subset(at), lo[at], hi[at])
        off = np.flatnonzero(~node)
        if off.size == 0:
            return value, t
        code = step[at].astype(np.int64) * span + key[at]
        order = np.argsort(code, kind="stable")
        s = step[off]
        before = s // NODE_EVERY * NODE_EVERY
        after = np.minimum(before + NODE_EVERY, step.max())
        x = starts(code[order], t[at][order], span, before, after, (s - before) / (after - before), key[off])
    else:
        code, t_given, position = given
        off = np.arange(len(lo))
        before = np.floor(position)
        x = starts(code, t_given, span, before, before + 1, position - before, key)
        x[corner] = np.nan
    go = np.isfinite(x)
    ok = np.zeros(len(off), bool)
    if go.any():
        r = off[go]
        v, tx, ok[go] = newton_from(task.subset(r), lo[r], hi[r], x[go], ITERATIONS)
        value[r], t[r] = v, tx
    again = off[~ok]
    if again.size:
        value[again], t[again] = minimise(task.subset(again), lo[again], hi[again])
    return value, t


def driver_derivatives(driver, piece, interval, t, rows):
    """The driver table's points and first and second derivatives (:meth:`CurveTable.derivatives`) of rows
    ``rows`` at ``t``, read off a per-table cache where ``t`` is an end of the row's polyline interval (``interval``;
    as :func:`~gearkit.contact.minimise.minimise` places the ends): most continued rows start on one, the same
    few dozen parameters at every driver angle. The same values to the bit (the same function of the same numbers)."""
    table = driver.table
    if interval is None:
        return table.derivatives(piece[rows], t)
    cache = driver.__dict__.setdefault("_node_derivatives", {})
    if cache.get("table") is not table:  # (kept with the table it was read off)
        ends = np.concatenate([driver.ta, driver.ta + (driver.tb - driver.ta)])
        p, d1, d2 = table.derivatives(np.concatenate([driver.piece, driver.piece]), ends)
        cache.update(table=table, ends=ends.reshape(2, -1), values=np.stack(p + d1 + d2).reshape(6, 2, -1))
    m = interval[rows]
    ends, values = cache["ends"], cache["values"]
    at_a, at_b = t == ends[0, m], t == ends[1, m]
    rest = np.flatnonzero(~(at_a | at_b))
    if 2 * rest.size > t.size:  # mostly inside: no gathering
        return table.derivatives(piece[rows], t)
    out = values[:, 1, m]
    out[:, at_a] = values[:, 0, m[at_a]]
    if rest.size:
        p, d1, d2 = table.derivatives(piece[rows][rest], t[rest])
        out[:, rest] = np.stack(p + d1 + d2)
    return [out[0], out[1]], [out[2], out[3]], [out[4], out[5]]
