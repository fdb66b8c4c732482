"""An atlas of blocking contours: one contour per (z1, z2) cell, computed in parallel processes.

Printed atlases cover a grid of tooth numbers for one tool; :func:`blocking_atlas` computes the
same grid for any pair template (tool, pressure angle, helix angle, external or internal) with
:class:`concurrent.futures.ProcessPoolExecutor`. Each cell is the contour
:func:`~gearkit.blocking.blocking_contour` returns for the template with ``teeth1 = z1``,
``teeth2 = z2``; a worker sends it back without its evaluation caches (they are rebuilt on demand).

>>> atlas = blocking_atlas([13], [16], workers=1, lines=["undercut.1"])
>>> sorted(atlas.cells), atlas.errors
([(13, 16)], {})
"""
from __future__ import annotations

import os
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, replace

from gearkit.errors import GearkitError, SpecError, require
from gearkit.pair.spec import PairSpec

__all__ = ["BlockingAtlas", "blocking_atlas"]


@dataclass(frozen=True)
class BlockingAtlas:
    """Result of :func:`blocking_atlas`.

    Attributes
    ----------
    cells : dict
        ``(z1, z2) -> BlockingContour`` for every cell whose pair exists.
    errors : dict
        ``(z1, z2) -> str``: why a cell has no contour (e.g. an internal pair with z2 <= z1).
    seconds : float
        Wall time of the whole atlas.
    workers : int
        Processes used (1: computed in this process).
    """

    cells: dict
    errors: dict
    seconds: float
    workers: int

    def __getitem__(self, key):
        return self.cells[key]

    def to_dict(self) -> dict:
        """JSON-ready: one entry per cell (its :meth:`~gearkit.blocking.BlockingContour.to_dict`) or error."""
        return {"seconds": self.seconds, "workers": self.workers,
                "cells": [{"z1": z1, "z2": z2, "contour": c.to_dict()} for (z1, z2), c in sorted(self.cells.items())],
                "errors": [{"z1": z1, "z2": z2, "error": e} for (z1, z2), e in sorted(self.errors.items())]}


def _cell(template: PairSpec, z1: int, z2: int, options: dict):
    """One cell (runs in a worker): ``(z1, z2, contour or None, error or None)``."""
    from gearkit.blocking.contour import blocking_contour

    try:
        spec = replace(template, teeth1=int(z1), teeth2=int(z2))
        return z1, z2, blocking_contour(spec, **options), None
    except GearkitError as exc:
        return z1, z2, None, str(exc)


def blocking_atlas(z1s, z2s, template: PairSpec | None = None, *, workers: int | None = 2,
                   **options) -> BlockingAtlas:
    """Blocking contours of every pair ``(z1, z2)`` of ``z1s`` x ``z2s``, computed in ``workers`` processes.

    Parameters
    ----------
    z1s, z2s : iterable of int
        Pinion and wheel (ring) tooth numbers.
    template : PairSpec or None
        Everything but the tooth numbers (tools, module, pressure and helix angle, kind); its teeth
        and shifts are ignored. None: external spur pair, module 1, the 20 degree basic rack.
    workers : int or None
        Worker processes (default 2; None: one per CPU; 1: no pool, computed in this process).
    **options
        Keyword arguments of :func:`~gearkit.blocking.blocking_contour` (``window``, ``xtol``,
        ``points``, ``lines``, ``tip_levels`` ...), the same for every cell.

    Returns
    -------
    BlockingAtlas
        A cell whose pair does not exist (e.g. a ring with too few teeth) is listed in ``errors``
        with the reason, not left out silently.
    """
    t0 = time.perf_counter()
    z1s = [int(z) for z in z1s]
    z2s = [int(z) for z in z2s]
    require(z1s and z2s, "z1s", "give at least one tooth number for each gear")
    template = PairSpec(20, 40, 1.0) if template is None else template
    require(isinstance(template, PairSpec), "template", "must be a PairSpec")
    n = (os.cpu_count() or 1) if workers is None else workers
    require(isinstance(n, int) and n >= 1, "workers", f"{workers!r} must be a positive integer or None")
    jobs = [(z1, z2) for z1 in z1s for z2 in z2s]
    results = []
    if n == 1 or len(jobs) == 1:
        results = [_cell(template, z1, z2, options) for z1, z2 in jobs]
    else:
        with ProcessPoolExecutor(max_workers=min(n, len(jobs))) as pool:
            futures = [pool.submit(_cell, template, z1, z2, options) for z1, z2 in jobs]
            results = [f.result() for f in futures]
    cells, errors = {}, {}
    for z1, z2, contour, err in results:
        if contour is None:
            errors[(z1, z2)] = err
        else:
            cells[(z1, z2)] = contour
    if not cells and errors:
        raise SpecError("z1s", "no cell of the atlas is a valid pair: " + next(iter(errors.values())))
    return BlockingAtlas(cells, errors, time.perf_counter() - t0, n)
