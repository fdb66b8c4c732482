"""Wall-clock timing for the bench: the median of repeats, and the closed-form baseline
(the kernel-overhead ratio times both in CPU time: :func:`gearkit.bench.profiles.overhead`).

The median (not the mean, not the minimum) of several repeats is what a user sees on a
warm interpreter; the spread is reported beside it so a noisy machine shows as noise.
"""
from __future__ import annotations

import math
import time

import numpy as np


def median_time(fn, repeats: int = 5, budget: float = 2.0):
    """Median wall time (s) of ``fn()`` over ``repeats`` calls (fewer if they exceed ``budget`` s).

    Returns
    -------
    seconds : float, the median
    result : whatever the last call returned
    """
    times, result = [], None
    start = time.perf_counter()
    for i in range(max(1, repeats)):
        t0 = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t0)
        if i >= 2 and time.perf_counter() - start > budget:
            break
    return float(np.median(times)), result


#: seconds a timed batch of calls lasts at least (many ticks of a coarse CPU clock)
BATCH = 0.05


def batch_calls(fn, seconds: float) -> int:
    """How many calls of ``fn`` last about ``seconds`` of wall time (at least 1), from one timed call.

    Examples
    --------
    >>> batch_calls(lambda: None, 1e-3) > 1, batch_calls(lambda: sum(range(10)), 0.0)
    (True, 1)
    """
    t0 = time.perf_counter()
    fn()
    one = time.perf_counter() - t0
    return max(1, min(10_000, math.ceil(seconds / one))) if one > 0 else 10_000


def closed_form_involute(n: int, base_radius: float, roll_max: float):
    """The bare closed form: ``n`` points of an involute of the base circle, ``(n, 2)`` float64, mm.

    x = r_b (cos t + t sin t), y = r_b (sin t - t cos t) for roll angles t in [0, roll_max]:
    the least work any method must do to put ``n`` involute points in an array.
    """
    t = np.linspace(0.0, roll_max, n)
    c, s = np.cos(t), np.sin(t)
    return np.stack([base_radius * (c + t * s), base_radius * (s - t * c)], -1)
