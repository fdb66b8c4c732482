"""Contact analysis against its speed targets: the rigid and the loaded mesh cycle.

Targets (issues 15 and 16): a 2000-step rigid cycle of the standard 20/40 pair (m = 2) in under
0.1 s in-process, and a 2000-step loaded spur cycle in under 1 s. Each row reports the median
time beside its target and pass/fail; the loaded cycle is also timed against its steps and slices
(the accuracy knobs reported with every loaded result). The first, untimed call builds the teeth.
Wall time and the process's CPU time are both reported, each the median over the same timed calls;
pass/fail reads the CPU time, which other work on a shared machine does not inflate (it counts this
process's threads only). Run as the ``gearkit`` command runs (``gearkit bench``,
``examples/bench_table.py``), numpy's BLAS is on one thread: no idle BLAS thread spins on the CPU
clock beside the cycle, and CPU time stays at or below wall time (the bench's ``meta`` says which way
it ran: ``blas_threads``).
"""
from __future__ import annotations

import time

import numpy as np

__all__ = ["contact_target_rows", "format_contact_rows"]


def contact_target_rows(quick: bool = False) -> list:
    """Rows ``{case, steps, slices, seconds, cpu_seconds, target, pass}`` (target None: a scaling row)."""
    from gearkit.contact import analyse_loaded, pair_mesh, simulate
    from gearkit.pair import PairSpec

    spur = PairSpec(20, 40, 2.0, face_width=20.0)
    mesh = pair_mesh(spur)
    simulate(mesh, 64)
    repeats = 1 if quick else 3
    rows = []
    seconds, cpu = _timed(lambda: simulate(mesh, 2000), repeats)
    rows.append({"case": "rigid cycle 20/40 m=2", "steps": 2000, "slices": 1, "seconds": seconds,
                 "cpu_seconds": cpu, "target": 0.1})
    cases = [(2000, 1, 1.0)] + ([] if quick else [(500, 1, None), (500, 10, None), (500, 40, None)])
    for steps, slices, target in cases:
        seconds, cpu = _timed(lambda: analyse_loaded(spur, 100.0, steps=steps, slices=slices), repeats)
        rows.append({"case": "loaded cycle 20/40 m=2, 100 N m", "steps": steps, "slices": slices,
                     "seconds": seconds, "cpu_seconds": cpu, "target": target})
    for r in rows:
        r["pass"] = None if r["target"] is None else bool(r["cpu_seconds"] <= r["target"])
    return rows


def _timed(fn, repeats):
    """Median wall and CPU times (s) of ``repeats`` calls of ``fn`` (at least three once 10 s have passed), each
    call read on both clocks: a CPU time of one call alone is as noisy as its wall time."""
    walls, cpus = [], []
    start = time.perf_counter()
    for i in range(max(1, repeats)):
        t0, c0 = time.perf_counter(), time.process_time()
        fn()
        cpus.append(time.process_time() - c0)
        walls.append(time.perf_counter() - t0)
        if i >= 2 and time.perf_counter() - start > 10.0:
            break
    return float(np.median(walls)), float(np.median(cpus))


def format_contact_rows(rows) -> list:
    """Plain-text lines of :func:`contact_target_rows`."""
    lines = ["contact analysis against its targets (in-process, median)",
             f"  {'case':34} {'steps':>6} {'slices':>6} {'wall':>10} {'CPU':>10} {'target':>8} {'':>5}"]
    for r in rows:
        target = "" if r["target"] is None else f"{r['target']:.2f} s"
        verdict = "" if r["pass"] is None else ("pass" if r["pass"] else "FAIL")
        lines.append(f"  {r['case']:34} {r['steps']:6d} {r['slices']:6d} {r['seconds']:9.3f}s "
                     f"{r['cpu_seconds']:9.3f}s {target:>8} {verdict:>5}")
    return lines
