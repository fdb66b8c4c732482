"""The oracle of the blocking tests for lines beside the no-pair edge: exact zeros of a scalar margin
along one row or column, found from the edge (bisected to round-off) by sampling and brentq; and the
solved edge moved by a few ulps (:func:`move_solved_edges`: a result must not hang on which of the
edge points within round-off the search returns)."""
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


def row_crossings(components, y, lo, hi):
    """Where the polylines ``components`` cross the row ``y`` between ``lo`` and ``hi`` (x, in order met)."""
    got = []
    for q in components:
        a, b = q[:-1], q[1:]
        s = (y - a[:, 1]) / np.where(b[:, 1] != a[:, 1], b[:, 1] - a[:, 1], np.nan)
        x = a[:, 0] + s * (b[:, 0] - a[:, 0])
        got += x[(s >= 0) & (s < 1) & (x >= lo) & (x <= hi)].tolist()
    return got


def move_solved_edges(monkeypatch, ulps):
    """Every edge point the edge search solves (``edges.by_slack``) moved ``ulps`` ulps towards the
    defined end of its segment (positive) or the undefined one (negative), for this test."""
    from gearkit.blocking import edges

    solved = edges.by_slack

    def moved(S, a, b, which, close):
        e = solved(S, a, b, which, close)
        for _ in range(abs(ulps)):
            e = np.nextafter(e, b if ulps > 0 else a)
        return e
    monkeypatch.setattr(edges, "by_slack", moved)
