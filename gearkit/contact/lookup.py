"""The interval of a sorted table that holds each of many values, in a few array passes.

The contact solver looks up every point it evaluates in a table of sorted interval starts (the
mate's half-width table, the driver's and the mate's polynomial tables): ``j = clip(searchsorted(
starts, x, "right") - 1, 0, n - 1)``, the last start at or below ``x``. A binary search per value
costs a few tens of nanoseconds (its branches do not predict); :class:`SortedIndex` answers the
same question with a handful of passes over the values. A uniform grid of buckets spans the starts;
each bucket keeps how many starts lie safely below its lower edge and the next few starts after
those (every start that may lie between there and the value); the value's index is that count plus
its comparisons with those starts, which are exact. So the index is the binary search's to the
last value, wherever the grid's arithmetic rounds (a value beyond either end, ``inf`` and ``nan``
included: ``nan`` sorts last, as in numpy).

Examples
--------
>>> starts = np.array([0.0, 0.5, 0.75, 2.0])
>>> x = np.array([-1.0, 0.0, 0.6, 0.75, 1.9, 2.0, 7.0, np.inf, np.nan])
>>> SortedIndex(starts)(x).tolist()
[0, 0, 1, 2, 2, 3, 3, 3, 3]
>>> np.array_equal(SortedIndex(starts)(x), np.clip(np.searchsorted(starts, x, "right") - 1, 0, 3))
True
"""
from __future__ import annotations

import numpy as np

__all__ = ["SortedIndex"]

#: most comparisons per value: the grid is refined (up to ``_MAX_BUCKETS``) until a bucket's window
#: of possible starts holds no more
_MAX_CANDIDATES = 3
_MAX_BUCKETS = 1 << 16
#: fewer values than this: the binary search (fewer array passes to set up)
_FEW = 64


class SortedIndex:
    """``clip(searchsorted(starts, x, "right") - 1, 0, n - 1)`` for arrays ``x`` of any shape.

    Parameters
    ----------
    starts : (n,) float64, non-decreasing and finite (otherwise every lookup is numpy's binary search)
    """

    def __init__(self, starts):
        self._starts = a = np.asarray(starts, dtype=float)
        self.n = n = len(a)
        lo, hi = (float(a[0]), float(a[-1])) if n else (0.0, 0.0)
        # starts spanning too little beside their size for the grid's arithmetic: the binary search
        # (or not sorted, where the binary search's answer is its own)
        self._binary = (n < 2 or not np.all(np.diff(a) >= 0) or not np.isfinite(hi - lo)
                        or hi - lo < 1e-9 * max(abs(lo), abs(hi)) * _MAX_BUCKETS)
        if self._binary:
            return
        buckets = 8 * n
        while True:
            h = (hi - lo) / buckets if hi > lo else 1.0
            # a value in bucket b (as the grid's rounding places it) lies within one bucket of b: the
            # starts at or below edge b - 2 are below it, those above edge b + 3 above it
            edges = lo + h * (np.arange(buckets + 2)[:, None] + np.array([-2, 3]))
            below, above = np.searchsorted(a, edges, side="right").T
            width = int((above - below).max())
            if width <= _MAX_CANDIDATES or buckets >= _MAX_BUCKETS:
                break
            buckets *= 2
        self._origin, self._inv, self._top = lo, 1.0 / h, float(buckets + 1)
        # the index if every candidate start is at or below the value, and the candidates (the last
        # start repeated past the end: a value at or beyond it ends at n - 1 whatever it counts)
        self._base = below + width - 1
        self._candidates = [a[np.minimum(below + c, n - 1)] for c in range(width)]

    def __call__(self, x):
        """The index ``j`` (intp, the shape of ``x``) of the last start at or below each ``x``."""
        x = np.asarray(x, dtype=float)
        if self._binary or x.size < _FEW:
            return np.clip(np.searchsorted(self._starts, x, side="right") - 1, 0, max(self.n - 1, 0))
        q = (x - self._origin) * self._inv
        # clamped into the grid; nan to the top (fmin passes the number over a nan)
        b = np.fmax(np.fmin(q, self._top, out=q), 0.0, out=q).astype(np.intp)
        j = self._base[b]
        for cand in self._candidates:
            j -= x < cand[b]  # a start above the value: one fewer
        return np.clip(j, 0, self.n - 1, out=j)
