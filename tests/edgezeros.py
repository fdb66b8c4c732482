"""The oracle of the blocking tests for lines beside the no-pair edge: exact zeros of a scalar margin
along one row or column, found from the edge (bisected to round-off) by sampling and brentq."""
import numpy as np
from scipy.optimize import brentq

EDGE_BISECTIONS = 60  #: bisections locating the no-pair edge on a row or column (to round-off)
FALL = 0.5  #: a solved sign change is a zero when |F| fell below this fraction of its ends'


def zeros_from_edge(f, lo, hi, top, distances):
    """The zeros of ``f`` (NaN where no pair exists) along one line: its edge bisected between ``lo``
    (undefined) and ``hi`` (defined), then ``f`` sampled at ``distances`` from it up to ``top``, every
    sign change solved by brentq (none where ``|f|`` does not fall: a pole). Empty where the line has
    no such edge."""
    if not np.isnan(f(lo)) or np.isnan(f(hi)):
        return []
    for _ in range(EDGE_BISECTIONS):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if np.isnan(f(mid)) else (lo, mid)
    ts = hi + distances
    ts = ts[ts <= top]
    v = np.array([f(t) for t in ts])
    out = []
    for i in np.flatnonzero(np.isfinite(v[:-1]) & np.isfinite(v[1:]) & ((v[:-1] > 0) != (v[1:] > 0))):
        t = brentq(f, ts[i], ts[i + 1], xtol=1e-15, rtol=1e-15)
        if abs(f(t)) <= FALL * min(abs(v[i]), abs(v[i + 1])):
            out.append(t)
    return out
