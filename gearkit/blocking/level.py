"""Zero sets of several functions ``F_k(x1, x2) = 0`` in a window, to a stated accuracy, in batches.

``F(points (n, 2), which (n,) int) -> (n,)`` evaluates function ``which[i]`` at ``points[i]`` (NaN
where undefined); every step below evaluates all the points it needs, of all the curves, at once.

1. **Topology** from a grid: marching squares (contourpy) on the values at the nodes of a grid
   gives each component once, open ones ending on the window's edge or where ``F`` is undefined,
   closed ones closed (no duplicate traces, no spurious loops: the polylines are the level set
   of one interpolant).
2. **Vertices on the curve**: each marching-squares vertex lies on a grid edge with a sign change;
   it is moved to the root of ``F`` on that edge
   (:func:`~gearkit.blocking.brackets.segment_roots`: regula falsi with the Illinois modification,
   a guard beside a settling estimate and bisection safeguards) to ``tol / 4`` in x.
3. **Chords on the curve** (:func:`~gearkit.blocking.refinement.densify`): chords split, round after
   round, until each lies within ``tol`` of its curve (so every point of a polyline lies within about
   ``1.25 tol`` of it; coarser tols cost less); one from one side of a strip to the other is cut, its
   ends carried on (:mod:`~gearkit.blocking.ends`).

4. **Saddles the grid got wrong**: the ends of a chord the refinement after the continuation cut carried on too,
   and joined where they stop on either side of a saddle's neck (:func:`~gearkit.blocking.ends.join_ends`);
   loops cut across a thin part re-joined (:func:`~gearkit.blocking.region.reconnect`), wedges cut short of
   their tips carried to them (:func:`~gearkit.blocking.tips.carry_to_tips`; a kinked curve's own:
   :func:`~gearkit.blocking.corners.carry_corners`).

The band beside the area where ``F`` is undefined, whose cells the grid masks, is traced on a
lattice of its own and joined to the grid's lines (:mod:`~gearkit.blocking.band`); at the end, an
open component lying wholly within ``2 tol`` of another of the same curve is dropped (one line at
that tol).
"""
from __future__ import annotations

import numpy as np

from gearkit.blocking.band import band_lines, once
from gearkit.blocking.brackets import segment_roots
from gearkit.blocking.corners import carry_corners
from gearkit.blocking.ends import extend_ends, join_ends
from gearkit.blocking.grid import bridge_pieces, edge_nodes, on_frame, true_runs
from gearkit.blocking.onsets import onset_vertices
from gearkit.blocking.refinement import JUMP_FACTOR, JUMP_FALL, VERTEX_FRACTION, densify
from gearkit.blocking.region import drop_covered, reconnect
from gearkit.blocking.tips import carry_to_tips

__all__ = ["zero_lines", "densify"]

BRIDGE_CELLS = 3.0  #: open pieces of one curve whose ends face each other this many cell diagonals apart join
BRIDGE_COS = 0.5  #: ... when the gap runs within 60 degrees of both ends' directions
NODE_ZERO = 1e-12  #: a vertex on a node whose |F| is below this fraction of the larger at its edge's ends is a zero


def zero_lines(F, grids, tol: float, max_step: float | None = None, measure=(), kinked=(), onsets=((), ()),
               many=None, parts=None) -> list:
    """Every component of ``F_k = 0`` seen by the grids ``grids[k] = (xs, ys, values)`` (``values[j, i]``
    at ``(xs[i], ys[j])``, NaN where undefined): a list (one entry per ``k``) of ``(n, 2)`` polylines
    within about ``1.25 tol`` of the zero set; a closed one repeats its first vertex last. A piece of
    one grid cell that does not cross the grid's inner frame (the window of a grid padded by one ring)
    is dropped: it ends on both sides beside undefined nodes. ``onsets``: ``(((axis, x), ...), curves)``,
    lines ``x_axis = x`` where the curves listed have a kink (:mod:`~gearkit.blocking.onsets`). ``many``:
    see :func:`~gearkit.blocking.band.band_lines`. ``parts``: the region's (:mod:`~gearkit.blocking.tips`)."""
    import contourpy

    raw, owner, edges = [], [], []
    specks = []  # (k, point): the grid cells of the specks dropped, left to the band (no grid line there)
    for k, (xs, ys, values) in enumerate(grids):
        if not np.any(np.isfinite(values)):
            continue
        gen = contourpy.contour_generator(xs, ys, np.ma.masked_invalid(values), name="serial",
                                          line_type="Separate")
        for p in gen.lines(0.0):
            if len(p) == 2 and k not in measure and not on_frame(np.asarray(p, float), xs, ys):
                specks.append((k, np.mean(p, axis=0)))
                continue  # one cell beside undefined ones: a speck the grid barely sees, at any tol alike
            if len(p) >= 2:
                p = np.array(p, dtype=float)
                raw.append(p)
                owner.append(k)
                i0, j0, i1, j1 = edge_nodes(p, xs, ys)
                edges.append((np.column_stack([xs[i0], ys[j0]]), np.column_stack([xs[i1], ys[j1]]),
                              values[j0, i0], values[j1, i1]))
    out = [[] for _ in grids]
    if not raw:
        return out
    allv = np.concatenate(raw)
    ids = np.concatenate([np.full(len(p), k) for p, k in zip(raw, owner)])
    a = np.concatenate([e[0] for e in edges])
    b = np.concatenate([e[1] for e in edges])
    fa = np.concatenate([e[2] for e in edges])
    fb = np.concatenate([e[3] for e in edges])
    ok = np.isfinite(fa) & np.isfinite(fb) & ((fa > 0) != (fb > 0))
    moved = allv.copy()
    grad = np.full(len(allv), np.nan)  # the secant across the grid edge (a jump's |F| is read against it)
    slope = grad.copy()  # |grad F| at the vertex, off its root's last bracket (segment_roots: not the edge's secant)
    if ok.any():
        moved[ok], slope[ok] = segment_roots(F, a[ok], b[ok], fa[ok], fb[ok], VERTEX_FRACTION * tol, ids[ok], True)
        grad[ok] = np.abs(fb[ok] - fa[ok]) / np.hypot(*(b[ok] - a[ok]).T)
    # a sign change through a pole or a jump of F is no zero: |F| stays large at the "root"; a
    # vertex on no edge with a sign change (beside undefined nodes) is kept only where F = 0
    fv = np.abs(F(moved, ids))
    with np.errstate(invalid="ignore"):  # and |F| hardly fell from the edge's ends: a zero falls a lot
        fell = fv <= JUMP_FALL * np.fmin(np.abs(fa), np.abs(fb))
        # a vertex at a node where F is zero to round-off is on no edge with a sign change either, but a zero: 17/17's
        # sliding margin is zero on x1 = x2 (both gears alike), +-1e-17 at the nodes there, and every vertex along
        # that line was read as a jump and dropped (129 tol at 1e-3)
        node_zero = np.isfinite(fa) & np.isfinite(fb) & (fv <= NODE_ZERO * np.fmax(np.abs(fa), np.abs(fb)))
    jump = np.where(ok, (fv > JUMP_FACTOR * grad * tol) & ~fell, ~((fv == 0) | node_zero))
    jump[np.isin(ids, list(measure))] = False  # the region: where no pair exists is its edge too
    lines, k0 = [], 0
    for p, k in zip(raw, owner):
        q, g, jmp = moved[k0:k0 + len(p)], slope[k0:k0 + len(p)], jump[k0:k0 + len(p)]
        k0 += len(p)
        closed = np.array_equal(p[0], p[-1])
        keep = np.concatenate([[True], np.any(q[1:] != q[:-1], axis=1)])
        q, g, jmp = q[keep], g[keep], jmp[keep]
        if closed and not np.array_equal(q[0], q[-1]):
            q, g, jmp = np.vstack([q, q[:1]]), np.append(g, g[0]), np.append(jmp, jmp[0])
        lines += [(k, q[lo:hi], g[lo:hi]) for lo, hi in true_runs(~jmp) if hi - lo >= 2]
    # the band beside the no-pair area, where the grid masks every cell (band)
    carry = []  # band ends that leave its lattice beside the edge: carried on (ends)
    lines = band_lines(F, lines, grids, tol, measure, many, carry, specks)
    lines = bridge_pieces(lines, grids, measure, BRIDGE_CELLS, BRIDGE_COS)
    # a run of one chord off the frame, bridged to none: a speck (see above), but for a band piece that goes on
    # beside the edge (an end carried on): 24/107's interference.1 left the band's lattice 1e-6 from where it
    # meets the edge, in a sliver along the edge 0.013 long to the window's frame, and was dropped with it
    lines = [(k, q, g) for k, q, g in lines if len(q) >= 3 or k in measure or on_frame(q, *grids[k][:2])
             or any(c[0] == k and min(np.hypot(*(c[1] - q[0])), np.hypot(*(c[1] - q[-1]))) <= tol for c in carry)]
    vtol = VERTEX_FRACTION * tol
    kept = []  # the region's chords with no zero across them: loops cut across a thin part, re-joined (reconnect)
    lines = densify(F, onset_vertices(F, lines, *onsets, vtol), tol, max_step, measure, kinked, True, kept,
                    loose=carry)
    # lines the grid cut short of their ends (a saddle): carried on to them (ends)
    lines = extend_ends(F, lines, grids, tol, measure, carry)
    again = []
    lines = densify(F, onset_vertices(F, lines, *onsets, vtol), tol, max_step, measure, kinked, True, kept,
                    loose=again)
    if again:  # the ends of a chord it cut (across a saddle's neck, 35/61 at tol 3e-4): carried on, and joined
        lines = extend_ends(F, lines, grids, tol, measure, again)
        lines = densify(F, lines, tol, max_step, measure, kinked, True, kept)
        xs, ys = grids[0][:2]
        lines = join_ends(F, lines, {k for k, _, _ in again}, (xs[1], xs[-2], ys[1], ys[-2]), tol)
    lines = reconnect(F, lines, kept, tol, lambda ls, kp, rest=None: densify(F, ls, tol, max_step, measure, kinked,
                                                                               True, kp, down=rest))
    if parts is not None and measure:  # the region's chords still across a wedge or a strip: its edge (tips)
        lines = carry_to_tips(F, parts, lines, kept, measure[0], tol,  # (a side is taken whole or not at all)
                              lambda g, ls: densify(g, ls, tol, max_step, (), range(g.size), dips=False))
        lines = drop_covered(lines, kept, tol)  # a link carried to the tip another loop was carried to
    # a kinked curve's wedge, or the region's, closed short of its tip (the region's beyond a saddle's neck too)
    lines = carry_corners(F, lines, set(kinked) | set(measure), tol, vtol, set(measure))
    for k, q in once([(k, q) for k, q, _ in lines], tol, measure):
        # a vertex repeated next to itself goes (which step left it was not pinned down): a chord of no
        # length has no direction (internal 49/64 z0 20's interference.1 at tol 1e-5, at the tip of a thin
        # wedge, where the exact measure, along no normal, read 4.3 tol)
        q = q[np.concatenate([[True], np.any(q[1:] != q[:-1], axis=1)])]
        if len(q) >= 2:
            out[k].append(q)
    return out
