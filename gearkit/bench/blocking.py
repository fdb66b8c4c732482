"""Bench of the blocking contours: the tolerance ladder, the in-process targets, atlas throughput.

* **Ladder** (12/30 pair, every line and the region) at tol 1e-2 ... 1e-9 shift units: the achieved
  deviation is the largest distance of the traced polylines from the exact lines, measured at
  every vertex and every chord's middle as the nearest zero of the margin on eight rays (the
  chord's normal, the chord, the diagonals) solved to 1e-14 (the limit of an ever finer trace); the contract is achieved / tol <= 2 at every row and
  time falling as tol grows.
* **Targets** (issue 15): the 13/16 and 20/40 contours in-process, at the default tolerance, each
  under 0.3 s; shown beside the measurement with pass/fail and the load average.
* **Atlas throughput** in cells per second for 1 and 2 local workers and the distributed path (a
  Dask cluster of two worker processes on this machine).
"""
from __future__ import annotations

import os
import time

import numpy as np

__all__ = ["ladder_rows", "target_rows", "atlas_rows", "deviation", "format_section"]

LADDER = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9)
QUICK_LADDER = (1e-3, 1e-6)
CONTOUR_TARGET = 0.3  #: s, in-process contour of 13/16 and 20/40 (issue 15)
RATIO_TARGET = 2.0  #: achieved / tol (issue 19)
ROUND_OFF = 1e-12  #: |margin| taken as zero
MEASURE_TOL = 1e-14  #: accuracy of the exact points the deviation is measured against
ATLAS_GRID = (10, 20, 30, 40)


def _median_time(fn, repeats):
    times, out = [], None
    for _ in range(repeats):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return float(np.median(times)), out


def deviation(contour) -> float:
    """Largest distance of the contour's traced lines and region boundary from the exact zero sets
    (at each vertex and each chord's middle: the nearest zero on eight rays, to ``MEASURE_TOL``).

    Examples
    --------
    >>> from gearkit.blocking import blocking_contour
    >>> from gearkit.pair import PairSpec
    >>> c = blocking_contour(PairSpec(13, 16, 1.0), tol=1e-4, lines=["undercut.1"])
    >>> deviation(c) <= 1e-4
    True
    """
    from gearkit.blocking.arrays import evaluator
    from gearkit.blocking.level import segment_roots

    names = [ln.name for ln in contour.lines] + ["region"]
    F = evaluator(contour.field, names, contour.window)
    pts, nrm, ids = [], [], []
    polys = [(k, c) for k, ln in enumerate(contour.lines) for c in ln.components]
    polys += [(len(names) - 1, p) for p in contour.region]
    for k, c in polys:
        if len(c) < 2:
            continue
        d = np.diff(c, axis=0)
        n = np.column_stack([-d[:, 1], d[:, 0]]) / np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-300)[:, None]
        pts += [c[:-1], 0.5 * (c[:-1] + c[1:])]
        nrm += [n, n]
        ids.append(np.full(2 * len(d), k))
    if not pts:
        return 0.0
    P, N, K = np.concatenate(pts), np.concatenate(nrm), np.concatenate(ids)
    f0 = F(P, K)
    worst = 0.0
    # |F| at round-off: on the zero set (also where F only touches zero, with no sign change near)
    todo = np.flatnonzero(np.isfinite(f0) & (np.abs(f0) > ROUND_OFF))
    r = 4 * contour.tol
    T = np.column_stack([N[:, 1], -N[:, 0]])
    rays = [s * D for D in (N, T, (N + T) / np.sqrt(2), (N - T) / np.sqrt(2)) for s in (1.0, -1.0)]
    for _ in range(6):  # the nearest zero on 8 rays of growing length (the normal, the chord, diagonals)
        if not todo.size:
            break
        best = np.full(todo.size, np.inf)
        for D in rays:
            end = P[todo] + r * D[todo]
            fe = F(end, K[todo])
            hit = np.isfinite(fe) & ((fe > 0) != (f0[todo] > 0))
            if hit.any():
                i = todo[hit]
                root = segment_roots(F, P[i], end[hit], f0[i], fe[hit], MEASURE_TOL, K[i])
                best[hit] = np.minimum(best[hit], np.hypot(*(root - P[i]).T))
        found = np.isfinite(best)
        if found.any():
            worst = max(worst, float(best[found].max()))
        todo = todo[~found]
        r *= 8
    if todo.size:  # no zero along the normal (F only nears zero there): |F| / |grad F|, first order
        e = 1e-7
        g = np.hypot(F(P[todo] + [e, 0.0], K[todo]) - f0[todo], F(P[todo] + [0.0, e], K[todo]) - f0[todo]) / e
        with np.errstate(divide="ignore", invalid="ignore"):
            est = np.abs(f0[todo]) / g
        worst = max(worst, float(np.nanmax(np.where(np.isfinite(est), est, r / 8))))
    return worst


def ladder_rows(quick: bool):
    """The tolerance ladder of the 12/30 contour (rows of the bench's accuracy ladder)."""
    from gearkit.blocking.contour import blocking_contour
    from gearkit.pair import PairSpec

    pair = PairSpec(12, 30, 1.0)
    rows = []
    for tol in (QUICK_LADDER if quick else LADDER):
        seconds, contour = _median_time(lambda: blocking_contour(pair, tol=tol), 3 if tol >= 1e-6 else 1)
        rows.append({"family": "involute", "product": "blocking contour", "case": "12/30 m=1, all lines",
                     "tol": tol, "achieved": deviation(contour),
                     "vertices": int(sum(len(ln.points) for ln in contour.lines)
                                     + sum(len(p) for p in contour.region)),
                     "evaluations": int(contour.evaluations), "seconds": seconds})
    return rows


def target_rows(ladder):
    """Issue 15's contour targets measured here, and issue 19's ladder contract read off ``ladder``."""
    from gearkit.blocking.contour import DEFAULT_TOL, blocking_contour
    from gearkit.pair import PairSpec

    rows = []
    for z1, z2 in ((13, 16), (20, 40)):
        seconds, _ = _median_time(lambda: blocking_contour(PairSpec(z1, z2, 1.0)), 5)
        rows.append({"target": f"blocking contour {z1}/{z2} in-process, tol {DEFAULT_TOL:g}", "measured": seconds,
                     "limit": CONTOUR_TARGET, "unit": "s", "pass": seconds < CONTOUR_TARGET})
    mine = [r for r in ladder if r["product"] == "blocking contour"]
    if mine:
        worst = max(r["achieved"] / r["tol"] for r in mine)
        rows.append({"target": "blocking ladder: achieved / tol at every row", "measured": worst,
                     "limit": RATIO_TARGET, "unit": "", "pass": worst <= RATIO_TARGET})
        times = [r["seconds"] for r in sorted(mine, key=lambda r: -r["tol"])]
        rows.append({"target": "blocking ladder: time grows as tol falls", "measured": None, "limit": None,
                     "unit": "", "pass": all(a <= b for a, b in zip(times, times[1:]))})
    return rows


def atlas_rows(quick: bool):
    """Atlas throughput (cells/s) on the grid ATLAS_GRID x ATLAS_GRID: 1 and 2 local workers and a Dask
    cluster of two worker processes on this machine (when dask.distributed is installed)."""
    import tempfile

    from gearkit.blocking.atlas import write_atlas

    grid = ATLAS_GRID[:2] if quick else ATLAS_GRID
    n = len(grid) ** 2
    rows = []
    runs = [("1 worker", {"workers": 1}), ("2 workers", {"workers": 2})]
    cluster = None
    if not quick:
        try:
            from distributed import LocalCluster
            cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                   dashboard_address=None)
            runs.append(("Dask, 2 worker processes", {"scheduler": cluster.scheduler_address}))
        except ImportError:
            rows.append({"case": "Dask", "note": "dask.distributed not installed (pip install 'gearkit[dask]')"})
    try:
        for name, kw in runs:
            with tempfile.TemporaryDirectory() as d:
                t = time.perf_counter()
                write_atlas(grid, grid, os.path.join(d, "a"), progress=False, **kw)
                s = time.perf_counter() - t
            rows.append({"case": name, "cells": n, "seconds": s, "cells_per_second": n / s})
    finally:
        if cluster is not None:
            cluster.close()
    return rows


def format_section(res: dict) -> list:
    """Lines of the bench report for the blocking targets and the atlas throughput."""
    lines = ["", "blocking contours: targets (load average %s)" % res["meta"].get("load_before")]
    for r in res.get("blocking_targets", []):
        meas = "" if r["measured"] is None else (f"{r['measured']:.3f} {r['unit']}".strip())
        lim = "" if r["limit"] is None else f"< {r['limit']:g} {r['unit']}".strip()
        lines.append(f"  {r['target']:55} {meas:>10} {lim:>10}  {'pass' if r['pass'] else 'FAIL'}")
    rows = res.get("atlas", [])
    if rows:
        lines.append("atlas throughput (external pairs, z1, z2 in %s)" % (ATLAS_GRID,))
        for r in rows:
            if "note" in r:
                lines.append(f"  {r['case']:28} -- {r['note']}")
            else:
                lines.append(f"  {r['case']:28} {r['cells']:4d} cells {r['seconds']:8.2f} s "
                             f"{r['cells_per_second']:7.2f} cells/s")
    return lines
