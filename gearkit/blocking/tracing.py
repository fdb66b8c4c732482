"""Trace named lines of a :class:`~gearkit.blocking.field.PairField` and its admissible region in a window.

One grid (``GRID`` x ``GRID`` nodes, padded by a ring outside the window) gives every line its
topology; the region's grid is ``REGION_REFINE`` times finer along the hard lines (thin parts of
the region, lines close together). All lines and the region are then solved and refined together,
in batches, by :func:`~gearkit.blocking.level.zero_lines` (see there for the accuracy: every vertex
within ``tol / 4``, every chord within ``tol`` of its line); the band beside the no-pair area, where
the grid masks every cell, on a lattice of its own (:mod:`~gearkit.blocking.band`).

>>> from gearkit.pair import PairSpec
>>> f = PairField(PairSpec(13, 16, 1.0))
>>> t = trace(f, (0.0, 1.0, 0.0, 1.0), ["undercut.1"], 1e-6)
>>> line = t.lines["undercut.1"][0]
>>> sorted({float(round(x, 6)) for x in line[:, 0]}), float(line[:, 1].min()), float(line[:, 1].max())
([0.239644], 0.0, 1.0)
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gearkit.blocking.arrays import SLIDING_LEGS, evaluator
from gearkit.blocking.arrays import margins as array_margins
from gearkit.blocking.field import PairField
from gearkit.blocking.grid import refine_grid, sign_cells
from gearkit.blocking.level import zero_lines
from gearkit.blocking.onsets import undercut_onsets
from gearkit.blocking.region import best_point, orient_loops, pad, padded_grid
from gearkit.blocking.parts import part_evaluator
from gearkit.progress import Progress

__all__ = ["Traced", "trace", "empty_reason", "GRID", "REGION_REFINE"]

GRID = 49  #: nodes per side of the grid that gives every line and the region its topology
REGION_REFINE = 4  #: the region's grid is this much finer along the hard lines
LEGS = {"sliding": SLIDING_LEGS}  #: lines traced as the zeros of their factors (one smooth function a leg)


@dataclass(frozen=True)
class Traced:
    """What :func:`trace` returns: ``lines`` name -> list of ``(n, 2)`` polylines, the region's
    polygons (None when not asked), why it is empty (or None), and the points evaluated."""

    lines: dict
    region: tuple | None
    reason: str | None
    evaluations: int


def empty_reason(field: PairField, F, which: int, window, xs, ys, values) -> str:
    """Why no point of the window passes: the hard margins violated at the best point."""
    x1, x2 = best_point(F, which, window, xs, ys, values)
    pt = field.point(x1, x2)
    if not pt.valid:
        return f"no pair exists in the window (e.g. at x1 = {x1:.4f}, x2 = {x2:.4f}: {pt.why})"
    names = list(field.hard)
    m = array_margins(field, [x1], [x2], names)
    bad = [(n, float(m[n][0])) for n in names if not (m[n][0] >= 0)]
    words = ", ".join(f"{field.by_name[n].code} {n} (margin {v:.4g})" for n, v in sorted(bad, key=lambda t: t[1]))
    return (f"no shift pair passes the check: even the best point x1 = {x1:.4f}, x2 = {x2:.4f} "
            f"violates {words or 'no hard line (the check fails on the generated gears there)'}")


def trace(field: PairField, window, names, tol: float, max_step: float | None = None,
          region: bool = False) -> Traced:
    """Trace the lines ``names`` of ``field`` (any margin name, see
    :meth:`~gearkit.blocking.field.PairField.margin`) in ``window`` and, with ``region=True``, the
    admissible region; ``max_step`` caps the chords (None: the tolerance alone)."""
    wanted = list(names)
    # a line whose margin is |a| - |b| is traced as the zeros of its two smooth factors a - b and a + b
    names = [f for n in wanted for f in LEGS.get(n, (n,))]
    count = [0]
    ids = names + (["region"] if region else [])
    F0 = evaluator(field, ids, window)

    def F(p, which):
        count[0] += len(p)
        return F0(p, which)

    def many(p, which):
        count[0] += len(p) * len(which)
        return F0.many(p, which)

    def slack(p, which):
        count[0] += len(p)
        return F0.slack(p, which)
    F.slack = slack
    with Progress("blocking", 4, unit="stages") as bar:  # the grid, the region's cells, the lines, the polygons
        xs = np.linspace(window[0], window[1], GRID)
        ys = np.linspace(window[2], window[3], GRID)
        gx, gy = np.meshgrid(xs, ys)
        nodes = np.column_stack([gx.ravel(), gy.ravel()])
        at_nodes = array_margins(field, nodes[:, 0], nodes[:, 1], names + (list(field.hard) if region else []))
        count[0] += len(nodes)
        bar.update(1)
        px, py = padded_grid(xs, ys)
        curves = [(px, py, pad(at_nodes[n].reshape(gx.shape), np.nan)) for n in names]
        reason = None
        if region:
            rvals = F(nodes, np.full(len(nodes), len(ids) - 1)).reshape(gx.shape)
            rv = pad(np.where(np.isfinite(rvals), rvals, -1.0), -1.0)
            if np.any(rv > 0):
                cells = sign_cells(rv)
                for n in field.hard:
                    cells |= sign_cells(pad(at_nodes[n].reshape(gx.shape), -1.0))
                curves.append(refine_grid(F, len(ids) - 1, px, py, rv, cells, REGION_REFINE))
            else:
                curves.append((px, py, np.full_like(rv, -1.0)))
        # a kink between two branches of one margin (the contact ratio's limiting end), and the tip sweep's margin,
        # flat at its resolution on the side it finds no penetration: a chord's middle there says nothing of its zero
        kinked = [k for k, n in enumerate(names) if n.partition("=")[0] in ("contact_ratio", "tip_interference")]
        bar.update(2)
        # the form circles break their slope where a gear starts to undercut: so do the lines reading them
        onsets = (undercut_onsets(field), {k for k, n in enumerate(ids) if not n.startswith("undercut.")})
        G = part_evaluator(field, window, count)  # the region's parts: its corners (tips)
        traced = zero_lines(F, curves, tol, max_step, measure=(len(ids) - 1,) if region else (), kinked=kinked,
                            onsets=onsets, many=many, parts=G if region else None)
        bar.update(3)
        polygons = None
        if region:
            polygons = orient_loops(traced[-1], window, tol)
            if not polygons:
                reason = empty_reason(field, F, len(ids) - 1, window, xs, ys, rvals)
    lines = {n: [q for f in LEGS.get(n, (n,)) for q in traced[names.index(f)]] for n in wanted}
    return Traced(lines, polygons, reason, count[0])
