"""The topology of a traced blocking contour against a much finer trace: gaps, spurious pieces,
loops and duplicate traces (the ladder of :mod:`gearkit.bench.blocking`)."""
from __future__ import annotations

import numpy as np

from gearkit.blocking.tracing import LEGS

__all__ = ["topology", "duplicates", "scan_gap", "far_zero", "corner_gap", "leg", "line_evaluator"]

SCANS = 80  #: scan lines per axis of the independent gap measure (:func:`scan_gap`)
SCAN_SAMPLES = 800  #: samples per scan line
SCAN_FALL = 0.5  #: a solved sign change is a zero when |F| fell below this fraction of its ends' (a jump
#: of F keeps |F| up)
EDGE_SAMPLES = 96  #: samples between a scan line's last sample before the no-pair area and its edge ...
EDGE_FLOOR = 1e-13  #: ... at distances from the edge down to this fraction of the spacing (round-off)
CORNER_STEPS, CORNER_HALF, CORNER_SAMPLES = 320, 2.0, 65  #: sections on from a sharp corner of a trace: how
#: many (a quarter tol apart: 80 tol on), their least half length in tol, their samples (_beyond_corners)
CORNER_WIDEST = 32.0  #: ... widened (doubled) up to this half length in tol across a wedge wider than they are
CORNER_COS = -0.5  #: ... from each corner whose chords are less than 120 degrees apart
MEASURE_TOL = 1e-14  #: accuracy of the exact points the bench's measures solve for
ROUND_OFF = 1e-12  #: |margin| taken as zero


def _far(points, polylines) -> float:
    """Largest distance from ``points`` (n, 2) to the nearest of ``polylines`` (inf when there are none)."""
    from gearkit.distances import distances_to_polyline

    if not len(points):
        return 0.0
    best = np.full(len(points), np.inf)
    for q in polylines:
        best = np.minimum(best, distances_to_polyline(points, q))
    return float(best.max())


def _probe_points(polylines):
    """Vertices and chord middles of ``polylines``."""
    pts = [p for q in polylines for p in (q, 0.5 * (q[:-1] + q[1:]))]
    return np.concatenate(pts) if pts else np.zeros((0, 2))


def _nearest_points(points, polyline):
    """The nearest point of ``polyline`` (m, 2) to each of ``points`` (n, 2) (in blocks of points)."""
    a, b = polyline[:-1], polyline[1:]
    d = b - a
    out = np.empty_like(points)
    for lo in range(0, len(points), 256):
        p = points[lo:lo + 256]
        with np.errstate(invalid="ignore", divide="ignore"):
            t = np.clip(np.nan_to_num(np.einsum("nmk,mk->nm", p[:, None, :] - a[None], d) / np.einsum("mk,mk->m", d, d)),
                        0.0, 1.0)
        c = a[None] + t[:, :, None] * d[None]
        k = np.argmin(np.hypot(*(c - p[:, None, :]).transpose(2, 0, 1)), axis=1)
        out[lo:lo + 256] = c[np.arange(len(p)), k]
    return out


def _sides_of_a_sliver(F, k, v, w, tol):
    """True where the zeros ``v`` and their nearest points ``w`` on another polyline bound a sliver
    (``F`` of one sign between them and of the other just beyond both, or beyond one where the other
    borders the no-pair area: two lines, not one traced twice); points closer than ``tol / 4`` (the
    vertices' accuracy) are one zero."""
    out = v + (v - w)
    beyond = w + (w - v)
    vals = F(np.concatenate([0.5 * (v + w), out, beyond]), np.full(3 * len(v), k)).reshape(3, -1)
    with np.errstate(invalid="ignore"):
        apart = np.hypot(*(v - w).T) > 0.25 * tol
        flips = [np.isnan(vals[i]) | ((vals[0] > 0) != (vals[i] > 0)) for i in (1, 2)]
        return apart & np.isfinite(vals[0]) & (np.isfinite(vals[1]) | np.isfinite(vals[2])) & flips[0] & flips[1]


def line_evaluator(contour):
    """``(F, legs)``: an evaluator of the contour's lines (function ``k`` the ``k``-th line), its region
    (the next) and, after them, the factors of the lines traced as factors (``legs[k]``: the factors'
    functions of line ``k``, empty for the others)."""
    from gearkit.blocking.arrays import evaluator

    names = [ln.name for ln in contour.lines] + ["region"]
    legs = [[] for _ in names]
    for k, ln in enumerate(contour.lines):
        for f in LEGS.get(ln.name, ()):
            legs[k].append(len(names))
            names.append(f)
    F = evaluator(contour.field, names, contour.window)
    return F, legs


def leg(F, legs, q) -> int:
    """Which of the functions ``legs`` of ``F`` vanishes on the polyline ``q`` (-1 without legs): the one
    whose median |value| at its vertices is least."""
    if not legs:
        return -1
    return int(np.argmin([np.nanmedian(np.abs(F(q, np.full(len(q), w)))) for w in legs]))


def duplicates(polylines, tol: float, F=None, k: int = 0, legs=()) -> int:
    """Components most of whose vertices lie within ``2 tol`` of another component on the same zeros
    (traced twice); with ``F`` (function ``k`` of an evaluator), vertices that lie on the other side of
    a sliver from their nearest points (:func:`_sides_of_a_sliver`) do not count: a sliver narrower
    than ``2 tol`` has two lines. A line whose function is a product (``legs``: the functions of ``F``
    that are its factors, e.g. the sliding line's ``|a| - |b|``, zero where ``a - b`` or ``a + b`` is)
    has a component on each factor's zeros: two components on different factors are two lines however
    close they run.

    Examples
    --------
    >>> F = lambda p, k: np.where(np.asarray(k) == 1, p[:, 1], p[:, 1] - 1e-9)  # two legs 1e-9 apart
    >>> a, b = np.array([[0.0, 0.0], [0.5, 0.0], [1.0, 0.0]]), np.array([[0.0, 1e-9], [0.5, 1e-9], [1.0, 1e-9]])
    >>> duplicates([a, b], 1e-3), duplicates([a, b], 1e-3, F, 0, legs=(1, 2))
    (2, 0)
    """
    from gearkit.distances import distances_to_polyline

    count = 0
    on = [leg(F, legs, q) for q in polylines] if F is not None else [-1] * len(polylines)
    for i, q in enumerate(polylines):
        inner = q[1:-1] if len(q) > 2 else q
        for j, r in enumerate(polylines):
            if i == j or on[i] != on[j]:
                continue
            close = distances_to_polyline(inner, r) <= 2 * tol
            if F is not None and np.mean(close) > 0.5 and len(r) > 1:
                close[close] &= ~_sides_of_a_sliver(F, k, inner[close], _nearest_points(inner[close], r), tol)
            if np.mean(close) > 0.5:
                count += 1
                break
    return count


def scan_gap(contour, scans: int = SCANS, samples: int = SCAN_SAMPLES):
    """Largest distance of an exact zero of a traced line from that line's trace, with the zeros found
    independently of any trace: every sign change of the line's margin between neighbouring samples on
    ``scans`` lines x1 = const and ``scans`` lines x2 = const across the window, solved to
    ``MEASURE_TOL`` (a sign change through a jump of the margin, where |F| does not fall, is none); where
    a scan line enters the no-pair area, also at distances from its edge falling geometrically from a
    sample's spacing to round-off (a line that dips to the edge between samples, closer to it than any);
    and on sections beyond each sharp corner of a line's trace and of the region's outline (:func:`corner_gap`:
    a thin wedge traced short of its tip, between the scan lines; ``"region"`` names the outline).
    A piece of a line the trace misses (e.g. cut short before a saddle or the no-pair edge) shows as a
    zero far from it, however fine the reference trace is. Returns ``(distance, line name, (x1, x2))``.

    Examples
    --------
    >>> from gearkit.blocking import blocking_contour
    >>> from gearkit.pair import PairSpec
    >>> c = blocking_contour(PairSpec(13, 16, 1.0), tol=1e-4, lines=["undercut.1"])
    >>> d, name, at = scan_gap(c, scans=20, samples=50)
    >>> d <= 1e-4
    True
    """
    from gearkit.blocking.arrays import evaluator
    from gearkit.blocking.edges import edge_point

    w = contour.window
    names = [ln.name for ln in contour.lines]
    F = evaluator(contour.field, names + ["region"], w)
    u = np.linspace(0.0, 1.0, scans + 2)[1:-1]
    t = np.linspace(0.0, 1.0, samples)
    rows = []  # (scans * 2, samples, 2): lines x1 = const, then x2 = const
    for a in u:
        x = w[0] + a * (w[1] - w[0])
        rows.append(np.column_stack([np.full(samples, x), w[2] + t * (w[3] - w[2])]))
    for a in u:
        y = w[2] + a * (w[3] - w[2])
        rows.append(np.column_stack([w[0] + t * (w[1] - w[0]), np.full(samples, y)]))
    P = np.stack(rows)
    worst = (0.0, None, None)
    for k, ln in enumerate(contour.lines):
        V = F(P.reshape(-1, 2), np.full(P.shape[0] * samples, k)).reshape(P.shape[:2])
        changes = map(np.concatenate, zip(_changes(*_beside_edge(F, P, V, k, edge_point)),
                                          _changes(*_beyond_corners(F, k, ln.components, contour.tol))))
        d, at = far_zero(F, k, ln.components, *changes)
        if d > worst[0]:
            worst = (d, ln.name, at)
    if contour.region:  # the region's outline: its wedges (between two parts crossing) on from their corners
        d, at = corner_gap(F, len(names), contour.region, contour.tol)
        if d > worst[0]:
            worst = (d, "region", at)
    return worst


def far_zero(F, k, components, A, B, fa, fb):
    """The zero of function ``k`` of ``F`` farthest from the polylines ``components`` among those
    between the points ``A`` and ``B`` (values ``fa``, ``fb`` of opposite signs), solved to
    ``MEASURE_TOL`` (a sign change through a jump of ``F``, where ``|F|`` does not fall below
    ``SCAN_FALL`` of its ends', is none): ``(distance, (x1, x2))``, ``(0.0, None)`` where there is none.

    >>> F = lambda p, k: p[:, 1] - 0.25
    >>> far_zero(F, 0, [np.array([[0.0, 0.0], [1.0, 0.0]])], np.array([[0.5, 0.0]]), np.array([[0.5, 1.0]]),
    ...          np.array([-0.25]), np.array([0.75]))
    (0.25, (0.5, 0.25))
    """
    from gearkit.distances import distances_to_polyline
    from gearkit.blocking.brackets import segment_roots

    if not len(A):
        return 0.0, None
    root = segment_roots(F, A, B, fa, fb, MEASURE_TOL, np.full(len(A), k))
    fr = np.abs(F(root, np.full(len(A), k)))
    root = root[(fr <= ROUND_OFF) | (fr <= SCAN_FALL * np.fmin(np.abs(fa), np.abs(fb)))]
    if not len(root):
        return 0.0, None
    best = np.full(len(root), np.inf)
    for q in components:
        best = np.minimum(best, distances_to_polyline(root, q))
    m = int(np.argmax(best))
    return float(best[m]), (float(root[m, 0]), float(root[m, 1]))


def corner_gap(F, k, components, tol):
    """:func:`far_zero` among the zeros on the sections beyond the sharp corners of ``components``
    (:func:`_beyond_corners`): how far short of its tip a thin wedge of the zero set is traced.

    >>> F = lambda p, k: np.abs(p[:, 1]) - 0.1 * (1.0 - p[:, 0])  # a wedge 0.2 wide, its tip at (1, 0)
    >>> d, at = corner_gap(F, 0, [np.array([[0.0, 0.1], [0.997, 0.0], [0.0, -0.1]])], 1e-3)  # 3 tol short
    >>> bool(2.5e-3 < d <= 3e-3)
    True
    """
    return far_zero(F, k, components, *_changes(*_beyond_corners(F, k, components, tol)))


def _changes(Q, W):
    """The neighbouring samples of the rows ``Q`` (values ``W``) whose signs differ: ``(A, B, fa, fb)``."""
    ch = np.isfinite(W[:, :-1]) & np.isfinite(W[:, 1:]) & ((W[:, :-1] > 0) != (W[:, 1:] > 0))
    i, j = np.nonzero(ch)
    return Q[i, j], Q[i, j + 1], W[i, j], W[i, j + 1]


def _beyond_corners(F, k, components, tol):
    """Sections across the way on from each sharp corner of the traced ``components`` of function ``k``
    (its chords less than 120 degrees apart, ``CORNER_COS``: an acute one, or one of the two a square cut
    across a wedge makes): ``(points, values)``, a row per section, ``CORNER_SAMPLES`` samples
    ``CORNER_HALF`` tol either side of its middle. The first lies a quarter tol beyond the corner across its
    bisector; while a section holds a run of the other sign than its two ends (a thin wedge of the zero set
    going on), the next lies a quarter tol on from that run's middle, across the way from the first
    section's middle (at most ``CORNER_STEPS``), twice as long as that run is wide (``CORNER_HALF`` tol either side
    at least); a section all of the sign between the corner's chords lies inside a wedge wider than it, and is
    taken again twice as long (up to ``CORNER_WIDEST`` tol either side: internal 42/98 z0 16's region at tol 1e-3,
    a wedge closed 5 tol wide and 70 tol short of the window's frame). A wedge traced short of its tip (internal
    19/42 z0 19's tip sweep at tol 1e-3, closed 2.9 tol short where it is 0.5 tol wide) lies between the scan
    lines; the last sections cross its sides next to the tip.

    >>> F = lambda p, k: np.abs(p[:, 1] - 0.05 * p[:, 0]) - 0.1 * (1.0 - p[:, 0])  # a wedge, its tip at (1, 0.05)
    >>> Q, W = _beyond_corners(F, 0, [np.array([[0.0, 0.1], [0.99, 0.05], [0.0, -0.1]])], 1e-3)
    >>> A, B, fa, fb = _changes(Q, W)
    >>> last = A[np.argmax(A[:, 0])]  # the sign change farthest on: 0.4 tol from the tip
    >>> bool(np.hypot(*(last - [1.0, 0.05])) < 0.5e-3)
    True
    """
    tips, ways, half = [], [], []
    for q in components:
        if len(q) < 3:
            continue
        mid = np.arange(0 if np.array_equal(q[0], q[-1]) else 1, len(q) - 1)
        a = q[np.where(mid > 0, mid - 1, len(q) - 2)] - q[mid]
        b = q[mid + 1] - q[mid]
        a = a / np.maximum(np.hypot(a[:, 0], a[:, 1]), 1e-300)[:, None]
        b = b / np.maximum(np.hypot(b[:, 0], b[:, 1]), 1e-300)[:, None]
        sharp = np.einsum("ij,ij->i", a, b) > CORNER_COS
        m = a[sharp] + b[sharp]
        tips.append(q[mid[sharp]])
        ways.append(-m / np.maximum(np.hypot(m[:, 0], m[:, 1]), 1e-300)[:, None])
        half.append(np.full(len(m), CORNER_HALF * tol))
        # two sharp corners next to each other whose outer chords run back the same way: a square cut across a
        # wedge; on from its middle along the wedge (a section across either corner's bisector crosses one side)
        j = np.flatnonzero(sharp[:-1] & sharp[1:] & (mid[1:] == mid[:-1] + 1))
        j = j[np.einsum("ij,ij->i", a[j], b[j + 1]) > 0.0]
        m = a[j] + b[j + 1]
        tips.append(0.5 * (q[mid[j]] + q[mid[j] + 1]))
        ways.append(-m / np.maximum(np.hypot(m[:, 0], m[:, 1]), 1e-300)[:, None])
        half.append(np.maximum(CORNER_HALF * tol, np.hypot(*(q[mid[j] + 1] - q[mid[j]]).T)))
    rows, vals = [np.zeros((0, CORNER_SAMPLES, 2))], [np.zeros((0, CORNER_SAMPLES))]
    if not tips:
        return rows[0], vals[0]
    C, D, H = np.concatenate(tips), np.concatenate(ways), np.concatenate(half)
    first = np.full_like(C, np.nan)
    inner = F(C - 0.25 * tol * D, np.full(len(C), k)) > 0  # the sign between the corner's chords
    u = np.linspace(-1.0, 1.0, CORNER_SAMPLES)
    for _ in range(CORNER_STEPS):
        if not len(C):
            break
        S = C + 0.25 * tol * D
        Q = S[:, None, :] + (H[:, None] * u)[:, :, None] * np.column_stack([-D[:, 1], D[:, 0]])[:, None, :]
        W = F(Q.reshape(-1, 2), np.full(Q.shape[0] * CORNER_SAMPLES, k)).reshape(Q.shape[:2])
        rows.append(Q)
        vals.append(W)
        out = W[:, :1] > 0
        run = np.isfinite(W) & ((W > 0) != out)
        on = np.isfinite(W[:, 0]) & np.isfinite(W[:, -1]) & (out[:, 0] == (W[:, -1] > 0)) & run.any(axis=1)
        # a section all of the sign between the chords lies inside a wedge wider than it: widened, taken again
        wide = np.isfinite(W).all(axis=1) & ~run.any(axis=1) & (out[:, 0] == inner) & (H < CORNER_WIDEST * tol)
        for i in np.flatnonzero(on):
            r = Q[i, run[i]]
            C[i] = r.mean(axis=0)
            H[i] = min(CORNER_WIDEST * tol, max(CORNER_HALF * tol, float(np.hypot(*(r[-1] - r[0])))))  # twice its width
        H[wide] *= 2.0
        first[on & np.isnan(first[:, 0])] = C[on & np.isnan(first[:, 0])]
        keep = on | wide
        C, D, first, H, inner = C[keep], D[keep], first[keep], H[keep], inner[keep]
        way = C - first  # the way on: from the first section's centre (on the wedge's middle)
        far = np.hypot(way[:, 0], way[:, 1])
        D = np.where((far > 0.5 * tol)[:, None], way / np.maximum(far, 1e-300)[:, None], D)
    return np.concatenate(rows), np.concatenate(vals)


def _beside_edge(F, P, V, k, edge_point):
    """The scan lines' samples ``P`` (lines, samples, 2) with values ``V`` of function ``k`` and, for
    each sample beside the no-pair area (its neighbour undefined), ``EDGE_SAMPLES`` more between it and
    the area's edge (found to round-off) at distances falling geometrically to ``EDGE_FLOOR`` times
    the spacing: ``(Q, W)``, one row per scan line and one per such ladder (ordered from the edge)."""
    fin = np.isfinite(V)
    i, j = np.nonzero(fin[:, :-1] != fin[:, 1:])
    if not i.size:
        return P, V
    inner = np.where(fin[i, j], j, j + 1)
    outer = np.where(fin[i, j], j + 1, j)
    A, B = P[i, inner], P[i, outer]
    span = float(np.max(np.abs(P)))
    E = edge_point(F, A, B, np.full(i.size, k), max(span, 1.0))
    d = np.concatenate([[0.0], np.geomspace(EDGE_FLOOR, 1.0, EDGE_SAMPLES)])
    Q = E[:, None, :] + d[None, :, None] * (A - E)[:, None, :]
    W = F(Q.reshape(-1, 2), np.full(Q.shape[0] * Q.shape[1], k)).reshape(Q.shape[:2])
    pad = P.shape[1] - Q.shape[1]
    if pad < 0:
        return P, V
    Q = np.concatenate([Q, np.full((len(Q), pad, 2), np.nan)], axis=1)
    W = np.concatenate([W, np.full((len(W), pad), np.nan)], axis=1)
    return np.concatenate([P, Q]), np.concatenate([V, W])


def topology(contour, reference) -> dict:
    """The traced lines and region of ``contour`` against a much finer trace ``reference`` (the same
    pair and window): ``gap`` (largest distance of a reference point from the traced lines: a piece
    missing), ``extra`` (largest distance of a traced vertex or chord middle from the reference: a
    spurious piece), ``loops`` (closed components: traced, reference), ``duplicates`` (components traced
    twice: the two sides of a sliver narrower than ``2 tol`` are two lines, see :func:`duplicates`).
    The contract: gap and extra within ``2 tol``, the same number of loops, no duplicate.

    Examples
    --------
    >>> from gearkit.blocking import blocking_contour
    >>> from gearkit.pair import PairSpec
    >>> ref = blocking_contour(PairSpec(13, 16, 1.0), tol=1e-7, lines=["pointing.1"])
    >>> t = topology(blocking_contour(PairSpec(13, 16, 1.0), tol=1e-3, lines=["pointing.1"]), ref)
    >>> t["gap"] <= 2e-3 and t["extra"] <= 2e-3, t["loops"], t["duplicates"]
    (True, (1, 1), 0)
    """
    pairs = [(ln.components, reference.line(ln.name).components) for ln in contour.lines]
    pairs.append((contour.region, reference.region))
    F, legs = line_evaluator(contour)
    gap = extra = 0.0
    loops, loops_ref, dup = 0, 0, 0
    for k, (mine, ref) in enumerate(pairs):
        mine, ref = list(mine), list(ref)
        gap = max(gap, _far(_probe_points(ref), mine))
        extra = max(extra, _far(_probe_points(mine), ref))
        loops += sum(1 for q in mine if len(q) > 2 and np.array_equal(q[0], q[-1]))
        loops_ref += sum(1 for q in ref if len(q) > 2 and np.array_equal(q[0], q[-1]))
        dup += duplicates(mine, contour.tol, F, k, legs[k])
    return {"gap": gap, "extra": extra, "loops": (loops, loops_ref), "duplicates": dup}
