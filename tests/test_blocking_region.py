"""Issue 19: the admissible region's boundary lies within 2 tol of the check's exact zero set where the
region is thinner than the tracing grid's cells (marching squares' saddle cells: a strip cut across,
the neck of a saddle cut through), against the check's own scalar margins (``PairField.margin``, the
zeros solved by brentq) and ``check_pair``.
"""
import functools

import numpy as np
import pytest
from scipy.optimize import brentq

from gearkit.blocking import blocking_contour
from gearkit.blocking.field import PairField
from gearkit.checks import check_pair
from gearkit.pair import PairSpec

CONTRACT = 2.0


def _smallest(field, x1, x2) -> float:
    """The smallest hard margin of the check at (x1, x2) (scalar, the check's own formulas)."""
    return min(field.margin(n, float(x1), float(x2)) for n in field.hard)


def _zeros(g, t):
    """Every zero of ``g`` between the samples ``t`` where it changes sign, solved by brentq."""
    v = np.array([g(s) for s in t])
    i = np.flatnonzero((v[:-1] >= 0) != (v[1:] >= 0))
    return np.array([brentq(g, t[j], t[j + 1], xtol=1e-13) for j in i])


def _row_sine(field, x, y, h=1e-7) -> float:
    """|sin| of the angle between the row x2 = ``y`` and the zero line of the check's smallest hard margin through
    (``x``, ``y``) (its gradient by central differences): a point ``dx`` along the row off the zero lies
    ``dx`` times this from the line."""
    gx = _smallest(field, x + h, y) - _smallest(field, x - h, y)
    gy = _smallest(field, x, y + h) - _smallest(field, x, y - h)
    return abs(gx) / float(np.hypot(gx, gy))


def _crossings(polygons, a, b) -> np.ndarray:
    """Parameters s in [0, 1] where the segment a -> b crosses the polygons' edges, sorted."""
    out = []
    d = b - a
    for p in polygons:
        e = np.diff(p, axis=0)
        den = d[0] * e[:, 1] - d[1] * e[:, 0]
        w = p[:-1] - a
        with np.errstate(divide="ignore", invalid="ignore"):
            s = (w[:, 0] * e[:, 1] - w[:, 1] * e[:, 0]) / den
            u = (w[:, 0] * d[1] - w[:, 1] * d[0]) / den
        ok = (den != 0) & (s >= 0) & (s <= 1) & (u >= 0) & (u < 1)
        out += s[ok].tolist()
    return np.sort(out)


def test_a_strip_narrower_than_a_grid_cell_is_not_cut_across():
    """33/78: interference.2 and interference.1 leave a strip about 0.02 wide (a region grid cell is
    0.022 x 0.031) running up to x2 = 1.8; the grid's nodes in it sit in diagonal corners of a saddle
    cell, and the region came out as two loops closed across the strip (chords 0.02 long, 10 tol off
    at tol 1e-3). On rows across it, the polygons cross exactly where the check's smallest hard margin
    does (brentq), within 2 tol, and the strip's middle is in the region."""
    tol = 1e-3
    spec = PairSpec(33, 78, 1.0)
    field = PairField(spec)
    c = blocking_contour(spec, tol=tol, lines=[])
    _rows_cross_the_strip(spec, field, c, np.linspace(-1.30, -1.13, 35), np.linspace(1.60, 1.70, 6), tol)


@pytest.mark.parametrize("pair, tol, xr, rows", [((32, 77), 1e-3, (-1.13, -1.04), (1.22, 1.23, 1.24)),
                                                 ((34, 105), 1e-5, (-1.27, -1.20), (1.775, 1.778, 1.78)),
                                                 ((31, 66), 1e-3, (-1.05, -1.00), (1.03, 1.05, 1.07)),
                                                 ((31, 66), 1e-5, (-1.05, -1.00), (1.03, 1.045, 1.06))])
def test_a_strip_cut_across_twice_is_taken_once(pair, tol, xr, rows):
    """The strip between interference.1 and interference.2 below its tip (about 0.02 wide), cut across twice
    by the grid (32/77: at x2 = 1.214 and 1.245; 34/105: two cuts crossing near x2 = 1.778): the loop
    below the upper cut and the loop above the lower cut both took the part between the cuts (each cut's
    middle inside the other loop), so by the even-odd rule it left the region (32/77 at tol 1e-3: the
    chords 10 tol off; 34/105 at 1e-5: 787 tol). 31/66 at tol 1e-3: the strip from interference.2's
    saddle neck at (-1, 1) cut at x2 = 1.02 and 1.077, the part between them, 3 times as long as the
    cuts, left out by both loops, and the tracing never ended (a corner split put the tip of the wedge
    the outline passes elsewhere into a cut, again and again: RecursionError); at tol 1e-5 the loops joined
    along the strip's right edge by one chord 0.05 long, 3.6 tol off its convex edge, whose middle's normal
    ends beyond the strip (0.012 wide) on both sides, kept as a cut. On rows between the cuts,
    the polygons cross exactly where the check's smallest hard margin does (brentq), within 2 tol, and
    the strip's middle is in the region and passes check_pair."""
    spec = PairSpec(*pair, 1.0)
    field = PairField(spec)
    c = blocking_contour(spec, tol=tol, lines=[])
    _rows_cross_the_strip(spec, field, c, np.linspace(*xr, 37), rows, tol)


def test_a_wedge_beside_a_strips_cut_is_not_cut_off():
    """31/66 at tol 1e-3: the wedge of the region above the crossing of interference.1 and interference.2 near
    (-1.0195, 0.985), which goes on up into the strip towards interference.2's saddle neck at (-1, 1). The grid cut
    the strip across just above the wedge; its cut, measured again once a corner split changed its loop, read the
    wedge's far side (0.029 below its middle, through the wedge's own chords) as its zero, the loop folded down
    into the wedge and back, and the region came out with a separate triangle closed across the wedge by a chord
    3.95 tol off any zero. On rows through the wedge between the crossing and the neck, every crossing of the
    polygons lies within 2 tol of a zero of the check's smallest hard margin (brentq) and every zero has one; the
    wedge's middle passes check_pair and is in the region."""
    tol = 1e-3
    spec = PairSpec(31, 66, 1.0)
    field = PairField(spec)
    c = blocking_contour(spec, tol=tol)
    xs = np.linspace(-1.03, -1.003, 55)
    for y in (0.987, 0.989, 0.991, 0.993, 0.995):
        _crosses_the_strip(spec, field, c, y, xs, tol)


def _rows_cross_the_strip(spec, field, c, xs, rows, tol):
    """On each row x2 = y of ``rows`` (x1 sampled at ``xs``) of the pair ``spec``, the region's polygons cross where the
    check's smallest hard margin does (brentq: the strip's two edges), within 2 tol, and the strip's
    middle passes check_pair and is in the region."""
    import dataclasses

    for y in rows:
        exact = _zeros(lambda x: _smallest(field, x, y), xs)
        assert len(exact) == 2, (y, exact)  # the strip's two edges
        a, b = np.array([xs[0], y]), np.array([xs[-1], y])
        got = xs[0] + _crossings(c.region, a, b) * (xs[-1] - xs[0])
        assert len(got) == 2 and np.max(np.abs(got - exact)) <= CONTRACT * tol, (y, exact, got)
        mid = 0.5 * (exact[0] + exact[1])
        assert check_pair(dataclasses.replace(spec, shift1=float(mid), shift2=float(y))).ok, (y, mid)
        assert c.in_region(mid, y), (y, mid)


def test_the_neck_of_a_saddle_is_not_cut_through():
    """21/52 at tol 1e-5: interference.1 has a saddle at (x1, x2) = (1, -1) where its margin is +1e-9
    (the check forgives 1e-9 m_n), so the region goes on through a neck about 9e-5 wide between the two
    branches of the zero set; the grid saw the branches' other pairing and both loops cut through the
    neck (chords 1e-4 long, 5 tol off). Across the neck (the diagonal through the saddle), the polygons
    cross only at the two branches, each within 2 tol of the check's zero (brentq), and the saddle
    itself, which check_pair passes, is in the region."""
    tol = 1e-5
    spec = PairSpec(21, 52, 1.0)
    field = PairField(spec)
    c = blocking_contour(spec, tol=tol, lines=[])
    d = np.array([1.0, 1.0]) / np.sqrt(2.0)
    o = np.array([1.0, -1.0])
    g = lambda t: _smallest(field, *(o + t * d))  # noqa: E731
    reach = 2e-4
    exact = _zeros(g, np.linspace(-reach, reach, 81))
    assert len(exact) == 2 and exact[0] < 0 < exact[1], exact
    got = -reach + _crossings(c.region, o - reach * d, o + reach * d) * (2 * reach)
    assert len(got) == 2 and np.max(np.abs(got - exact)) <= CONTRACT * tol, (exact, got)
    assert check_pair(PairSpec(21, 52, 1.0, 1.0, -1.0)).ok and c.in_region(1.0, -1.0)


@pytest.mark.parametrize("z1, z2, z0", [(55, 102, 34), (51, 90, 26), (42, 67, 40)])
def test_a_neck_the_point_halfway_between_its_cuts_misses_is_not_cut_through(z1, z2, z0):
    """Internal pairs at tol 1e-5 whose interference.1 has a saddle at (1, 1), +1e-9 there (the check forgives
    1e-9 m_n), leaving a neck about 1.4e-4 wide between the tips of its two negative wedges, each 1e-4 from it.
    55/102 (shaper z0 34): the cuts across the neck and those across the wedges were told apart by the margin
    halfway between their middles, which lay 2.3e-4 off the saddle, in a wedge: the region was left in two
    loops closed across the neck (810 tol off). 51/90 z0 26 and 42/67 z0 40: the cuts' middles 0.033 apart, the
    quadratic fitted to the region's function on a stencil that wide read the tip sweep's flat level (1e-4)
    beside the saddle and stepped out of reach; the same two loops, 504 and 536 tol off (and once joined, 42/67's
    lower wedge's side traced alone to its tip kept one chord 0.022 long, 2.07 tol off on the row 5e-4 below the
    saddle where the branch bends towards it, its middle 0.48 tol off). On rows through both
    wedges every crossing of the polygons lies within 2 tol of a zero of the check's smallest hard margin
    (brentq) and every zero has one; each wedge's middle fails check_pair and is outside the region, and the
    saddle passes it and is inside."""
    import dataclasses

    from gearkit.families.involute import ShaperCutter

    tol = 1e-5
    spec = PairSpec(z1, z2, 1.0, kind="internal", tool2=ShaperCutter(z0))
    field = PairField(spec)
    c = blocking_contour(spec, tol=tol, lines=[])
    xs = np.linspace(0.99, 1.01, 201)
    for y in 1.0 + np.array([-2e-3, -5e-4, -2e-4, 0.0, 2e-4, 5e-4, 2e-3]):
        exact = _zeros(lambda x: _smallest(field, x, y), xs)
        assert len(exact) == (0 if y == 1.0 else 2), (y, exact)
        got = xs[0] + _crossings(c.region, np.array([xs[0], y]), np.array([xs[-1], y])) * (xs[-1] - xs[0])
        assert len(got) == len(exact), (y, exact, got)
        if len(exact):
            # off the zero line by the offset along the row times the sine of the line's angle with the row
            sine = np.array([_row_sine(field, x, y) for x in exact])
            near = np.abs(got[:, None] - exact[None, :]) * sine[None, :]
            assert near.min(axis=1).max() <= CONTRACT * tol and near.min(axis=0).max() <= CONTRACT * tol, (y, exact, got)
            mid = 0.5 * (exact[0] + exact[1])
            assert not check_pair(dataclasses.replace(spec, shift1=float(mid), shift2=float(y))).ok, (mid, y)
            assert not c.in_region(mid, y), (mid, y)
    assert check_pair(dataclasses.replace(spec, shift1=1.0, shift2=1.0)).ok and c.in_region(1.0, 1.0)


def _edge(field, name, y, lo, hi) -> float:
    """The zero of the check's margin ``name`` on the row x2 = ``y`` between x1 = ``lo`` and ``hi`` (brentq)."""
    return brentq(lambda x: field.margin(name, x, y), lo, hi, xtol=1e-14)


def _distance_to_outline(polygons, p) -> float:
    """Distance of the point ``p`` from the polygons' edges."""
    best = np.inf
    for q in polygons:
        a, d = q[:-1], np.diff(q, axis=0)
        t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300), 0.0, 1.0)
        best = min(best, float(np.min(np.hypot(*(a + t[:, None] * d - p).T))))
    return best


# pair, the two hard margins whose zeros bound the wedge, x1 bracketing both on the rows, x2 bracketing the tip
WEDGES = [((33, 78), "interference.1", "interference.2", (-1.30, -1.15), (1.75, 1.85)),
          ((14, 62), "interference.1", "pointing.1", (0.93, 0.99), (-1.36, -1.30)),
          ((14, 118), "interference.1", "pointing.1", (0.95, 0.99), (-1.53, -1.49)),
          ((13, 45), "interference.1", "pointing.1", (0.92, 0.96), (-1.40, -1.37))]


@pytest.mark.parametrize("tol", [1e-3, 1e-5])
@pytest.mark.parametrize("pair, a, b, xr, yr", WEDGES)
def test_a_thin_wedge_is_traced_to_its_tip(pair, a, b, xr, yr, tol):
    """Where two hard margins cross at a small angle the region ends in a wedge narrower than a grid
    cell below their crossing; the grid closed the loop across it short of the tip (33/78: 0.1 short, the
    chord 549 tol from the region's edge at tol 1e-5; 14/62: 0.04 short, 613 tol). The tip is solved
    here apart from the tracing, as the row x2 where the two margins' zeros along the row (brentq) meet
    (brentq again): the outline passes within 2 tol of it; on rows below it the outline crosses
    exactly where the two margins do, within 2 tol, and the wedge's middle is in the region and passes
    check_pair."""
    z1, z2 = pair
    field = PairField(PairSpec(z1, z2, 1.0))
    c = blocking_contour(PairSpec(z1, z2, 1.0), tol=tol, lines=[])
    yt = brentq(lambda y: _edge(field, a, y, *xr) - _edge(field, b, y, *xr), *yr, xtol=1e-14)
    xt = _edge(field, a, yt, *xr)
    assert _distance_to_outline(c.region, np.array([xt, yt])) <= CONTRACT * tol, (xt, yt)
    for d in (0.03, 0.01, 3e-3, 1e-3, 3e-4):
        if d < 30 * tol:
            continue
        y = yt - d
        exact = np.sort([_edge(field, a, y, *xr), _edge(field, b, y, *xr)])
        mid = 0.5 * (exact[0] + exact[1])
        assert _smallest(field, mid, y) > 0 and check_pair(PairSpec(z1, z2, 1.0, float(mid), float(y))).ok, (d, mid)
        assert c.in_region(mid, y), (d, mid)
        lo, hi = np.array([xr[0], y]), np.array([xr[1], y])
        got = xr[0] + _crossings(c.region, lo, hi) * (xr[1] - xr[0])
        assert len(got) == 2 and np.max(np.abs(got - exact)) <= CONTRACT * tol, (d, exact, got)


def test_the_regions_parts_are_the_margins_and_the_window():
    """The parts of the region's function (parts.part_evaluator) at random points: each hard margin as
    the check's scalar margin gives it, each window part the distance to its edge, and their smallest
    the region's function where a pair exists."""
    from gearkit.blocking.arrays import evaluator
    from gearkit.blocking.parts import part_evaluator

    field = PairField(PairSpec(33, 78, 1.0))
    window = (-1.0, 2.0, -3.0, 0.5)
    G = part_evaluator(field, window)
    P = np.random.default_rng(7).uniform(-1.5, 1.5, (12, 2))
    V = G.many(P)
    hard = list(field.hard)
    for i, (x, y) in enumerate(P):
        want = [field.margin(n, x, y) for n in hard] + [x - window[0], window[1] - x, y - window[2], window[3] - y]
        assert np.allclose(V[:, i], want, rtol=0, atol=1e-12, equal_nan=True), (x, y)
    for k in range(G.size):
        assert np.array_equal(G(P, np.full(len(P), k)), V[k], equal_nan=True)
    R = evaluator(field, ["region"], window)(P, np.zeros(len(P), int))
    ok = np.all(np.isfinite(V), axis=0)
    assert ok.any() and np.array_equal(R[ok], V[:, ok].min(axis=0))


def _deep_point(polygons, q, reach):
    """A point inside the polygon ``q`` farther than ``reach`` from every polygon's edges (chord middles
    of ``q`` moved along their normals by ``reach`` x 1.25 x 2^k), or None."""
    from gearkit.blocking.region import inside_polygons

    d = np.diff(q, axis=0)
    n = np.column_stack([-d[:, 1], d[:, 0]]) / np.maximum(np.hypot(*d.T), 1e-300)[:, None]
    m = 0.5 * (q[:-1] + q[1:])
    steps = 1.25 * reach * 2.0 ** np.arange(13)
    pts = np.concatenate([m + s * sg * n for s in steps for sg in (1.0, -1.0)])
    for p in pts[inside_polygons([q], pts)]:
        if _distance_to_outline(polygons, p) > reach:
            return p
    return None


@pytest.mark.parametrize("pair, tol", [((21, 52), 1e-5), ((42, 85), 1e-5), ((34, 105), 1e-5)])
def test_every_loop_of_the_region_bounds_a_part_the_check_confirms(pair, tol):
    """Every polygon of the region bounds a part of it or a hole: inside it lies a point farther than
    2 tol from every polygon's edges, where the region's verdict is check_pair's. Folds of a loop's
    path, back along the line it came, were split off as loops about 1e-7 wide bounding nothing (the
    interference.1 saddle's neck of 21/52 at (1, -1), a corner of 42/85 near (-1.5009, 0.5127), the
    cuts of 34/105 near (-1.24, 1.77)): the contours had spurious loops."""
    spec = PairSpec(*pair, 1.0)
    c = blocking_contour(spec, tol=tol, lines=[])
    for q in c.region:
        p = _deep_point(c.region, q, CONTRACT * tol)
        assert p is not None, (len(q), q.mean(axis=0))
        assert check_pair(PairSpec(*pair, 1.0, float(p[0]), float(p[1]))).ok == c.in_region(*p), p


@pytest.mark.parametrize("tol", [1e-3, 1e-5])
def test_a_wedge_beside_a_fold_of_the_outline_is_traced_to_its_tip(tol):
    """32/86: the strip between interference.1 and interference.2 ends in a wedge, tip near (-1.082,
    1.251), cut 0.025 short of it; the outline beside the cut folds back along the wedge's left side
    (at tol 1e-3 up to x2 = 1.232 and down again, at 1e-5 to 1.230 and down 2e-3 past the cut's end),
    and the line to the tip, traced along that side within tol, was refused as crossing the outline
    (the chord 2.01 tol off at 1e-3, 200 at 1e-5); the fold now goes with the cut. The tip is solved
    apart from the tracing (brentq on the two margins' zeros along rows): the outline passes within
    2 tol of it, and crosses the rows below it where the margins do (see the wedge test above)."""
    test_a_thin_wedge_is_traced_to_its_tip((32, 86), "interference.2", "interference.1", (-1.10, -1.06),
                                           (1.24, 1.26), tol)


def test_a_wedge_bounded_beside_the_tip_sweeps_kink_is_traced_to_its_tip():
    """25/54 internal (shaper z0 20) at tol 1e-3: interference.1 and exit jamming leave a wedge about 0.1
    long and 0.02 wide at most, tip near (0.551, -0.026), narrower than the region grid's cells; inside it
    the tip sweep's margin is flat at its resolution (1e-4: no penetration) and smallest, and it kinks down
    where exit jamming crosses zero. The grid saw the wedge as a chain of diamonds, the outline was closed
    across it at x2 = 0.06 (the chord 9 tol off) and its end beside the kink read as bound by the tip sweep,
    whose corners are not carried. The tip is solved apart from the tracing (brentq on the two margins'
    zeros along rows, then on their difference): the outline passes within 2 tol of it; on rows above it
    the outline crosses exactly where the two margins do, within 2 tol, and the wedge's middle is in the
    region and passes check_pair."""
    import dataclasses

    from gearkit.families.involute import ShaperCutter

    tol = 1e-3
    spec = PairSpec(25, 54, 1.0, kind="internal", tool2=ShaperCutter(20))
    field = PairField(spec)
    c = blocking_contour(spec, tol=tol, lines=[])
    span = lambda y: (y + 0.50, y + 0.59)  # noqa: E731 (the rows' x1 short of the no-pair edge, x1 - x2 = 0.594)
    edge = lambda name, y: _edge(field, name, y, *span(y))  # noqa: E731
    yt = brentq(lambda y: edge("interference.1", y) - edge("exit_jamming", y), -0.04, -0.01, xtol=1e-14)
    assert _distance_to_outline(c.region, np.array([edge("interference.1", yt), yt])) <= CONTRACT * tol, yt
    for d in (0.08, 0.04, 0.02, 0.01, 3e-3):
        y = yt + d
        exact = np.array([edge("interference.1", y), edge("exit_jamming", y)])
        mid = 0.5 * (exact[0] + exact[1])
        assert _smallest(field, mid, y) > 0 and check_pair(dataclasses.replace(spec, shift1=float(mid),
                                                                               shift2=float(y))).ok, (d, mid)
        assert c.in_region(mid, y), (d, mid)
        lo, hi = span(y)
        got = lo + _crossings(c.region, np.array([lo, y]), np.array([hi, y])) * (hi - lo)
        assert len(got) == 2 and np.max(np.abs(got - exact)) <= CONTRACT * tol, (d, exact, got)


# internal pairs (shaper teeth) at tol 1e-3; the rows across the strip between interference.1 and exit jamming where the
# tip sweep is flat: x2, and x1 from x2 + lo over a span short of the no-pair edge
FLAT_STRIPS = {(58, 109, 31): ((-0.995, -0.985, -0.975, -0.965), 0.995, 0.047),
               (55, 102, 34): ((-0.89, -0.875, -0.86, -0.845), 0.925, 0.036)}


@functools.lru_cache(maxsize=None)
def _internal(z1, z2, z0):
    from gearkit.families.involute import ShaperCutter

    spec = PairSpec(z1, z2, 1.0, kind="internal", tool2=ShaperCutter(z0))
    return spec, PairField(spec), blocking_contour(spec, tol=1e-3, lines=[])


@pytest.mark.parametrize("key", sorted(FLAT_STRIPS))
def test_a_strip_where_the_tip_sweep_is_flat_is_not_cut_across(key):
    """58/109 (shaper z0 31) and 55/102 (z0 34) internal at tol 1e-3: a strip of the region about 0.02 wide between
    interference.1 and exit jamming, narrower than a grid cell, where the tip sweep's margin is flat at its
    resolution (1e-4). The grid saw a chain of diamonds; the chords across the strip were kept as cuts, then a
    corner split a quarter along each put a vertex on the strip's edge beside its end and the outline ran down the
    strip's edges and back round its loop, so the loops were never re-joined and the outline closed across the
    strip (11.9 and 8.1 tol off). On rows across it the polygons cross where the check's smallest hard margin does (brentq), within 2 tol,
    and the strip's middle is in the region and passes check_pair."""
    spec, field, c = _internal(*key)
    rows, lo, span = FLAT_STRIPS[key]
    for y in rows:
        _rows_cross_the_strip(spec, field, c, np.linspace(y + lo, y + lo + span, 37), [y], 1e-3)


def test_a_flat_strip_whose_cuts_cross_is_taken_along_its_edges_to_its_end():
    """25/59 internal (shaper z0 35) at tol 1e-3: the same flat strip, about 0.015 wide along the row. Two loops of
    the grid's chain of diamonds overlapped along it, their cuts crossing in an X at (0.57, -0.107), and the
    loops were joined across the X (the outline 5.6 tol off); the strip's last cut, at its lower end short of
    trimming.plunge, paired with none. On rows through the X and below the last cut, the polygons cross where the
    check's smallest hard margin does (brentq: the strip's two edges), within 2 tol, and the strip's middle is in
    the region and passes check_pair."""
    spec, field, c = _internal(25, 59, 35)
    for rows, lo, span in (((-0.112, -0.108, -0.104, -0.101), 0.66, 0.04), ((-0.144, -0.14), 0.672, 0.022)):
        for y in rows:
            _rows_cross_the_strip(spec, field, c, np.linspace(y + lo, y + lo + span, 37), [y], 1e-3)


@pytest.mark.parametrize("key, rows, xr", [((23, 89, 19), (-0.648, -0.652, -0.656), (0.54, 0.60)),
                                           ((34, 76, 33), (-0.478, -0.481, -0.485), (0.33, 0.39))])
def test_a_flat_strip_joined_across_its_cuts_has_no_loop_left_inside(key, rows, xr):
    """23/89 (shaper z0 19) and 34/76 (z0 33) internal at tol 1e-3: the same kind of flat strip, its grid loops
    joined across their cuts. Swapping two cuts that cross left a loop of three or four vertices inside the strip
    (8.1 and 4.2 tol off). On rows through the strip every crossing of the polygons lies within 2 tol of a zero of
    the check's smallest hard margin (brentq) and every zero has a crossing within 2 tol; the strip's middle
    passes check_pair and is in the region."""
    _rows_meet_the_strips_edges(key, rows, xr)


@pytest.mark.parametrize("key, rows, xr", [((38, 61, 16), (0.09, 0.097, 0.1, 0.104), (0.50, 0.575)),
                                           ((30, 82, 27), (-0.705, -0.712, -0.716, -0.719), (0.30, 0.37))])
def test_a_piece_of_a_flat_strip_taken_twice_is_no_hole(key, rows, xr):
    """38/61 (shaper z0 16) and 30/82 (z0 27) internal at tol 1e-3: the same kind of flat strip, a chain of grid
    diamonds, one of them taken along the strip's edges past the next one's cut, so that the next one's piece of
    the strip (a loop of six or seven vertices across it near (0.535, 0.095) and (0.33, -0.715)) lay inside it and
    the even-odd rule cut it out as a hole (7.9 and 5.5 tol off). On rows through that piece every crossing of the
    polygons lies within 2 tol of a zero of the check's smallest hard margin (brentq) and every zero has a crossing
    within 2 tol; the strip's middle passes check_pair and is in the region."""
    _rows_meet_the_strips_edges(key, rows, xr)


def _crosses_the_strip(spec, field, c, y, xs, tol, column=False):
    """On the row ``y`` over ``xs`` (``column``: the column x1 = ``y`` over x2 in ``xs``): the check's smallest
    hard margin has two zeros (brentq), every crossing of the region's polygons lies within 2 tol of one and each
    has a crossing within 2 tol; the middle between them passes check_pair and is in the region."""
    import dataclasses

    at = (lambda s: (y, s)) if column else (lambda s: (s, y))
    exact = _zeros(lambda s: _smallest(field, *at(s)), xs)
    assert len(exact) == 2, (y, exact)
    got = xs[0] + _crossings(c.region, np.array(at(xs[0])), np.array(at(xs[-1]))) * (xs[-1] - xs[0])
    near = np.abs(got[:, None] - exact[None, :])
    assert got.size and near.min(axis=1).max() <= CONTRACT * tol, (y, exact, got)
    assert near.min(axis=0).max() <= CONTRACT * tol, (y, exact, got)
    x1, x2 = at(0.5 * (exact[0] + exact[1]))
    assert check_pair(dataclasses.replace(spec, shift1=float(x1), shift2=float(x2))).ok, (x1, x2)
    assert c.in_region(x1, x2), (x1, x2)


def _rows_meet_the_strips_edges(key, rows, xr):
    spec, field, c = _internal(*key)
    xs = np.linspace(*xr, 61)
    for y in rows:
        _crosses_the_strip(spec, field, c, y, xs, 1e-3)


@pytest.mark.parametrize("key", sorted(FLAT_STRIPS))
def test_the_wedges_of_one_margin_meeting_at_its_saddle_are_traced_to_it(key):
    """The same pairs: interference.1's two negative wedges meet at its saddle at (1, 1), each bounded by two
    branches of the one margin's zero set; the outline was closed across each wedge 0.015 to 0.02 short of the
    saddle (the chords 7.5 and 2.4 tol off), taking the part between the cuts, the wedges' tips, into the region.
    On rows through both wedges beside the saddle, the polygons cross only where the check's smallest hard margin
    does (brentq: the wedge's two sides), within 2 tol; the wedge's middle fails check_pair and is outside the
    region, and points 5e-3 beyond its sides pass it and are inside."""
    import dataclasses

    spec, field, c = _internal(*key)
    tol = 1e-3
    xs = np.linspace(0.96, 1.04, 41)
    for d in (-0.012, -0.006, -0.003, 0.003, 0.006, 0.012):
        y = 1.0 + d
        exact = _zeros(lambda x: _smallest(field, x, y), xs)
        assert len(exact) == 2, (y, exact)
        got = xs[0] + _crossings(c.region, np.array([xs[0], y]), np.array([xs[-1], y])) * (xs[-1] - xs[0])
        assert len(got) == 2 and np.max(np.abs(got - exact)) <= CONTRACT * tol, (y, exact, got)
        for x, inside in ((0.5 * (exact[0] + exact[1]), False), (exact[0] - 5e-3, True), (exact[1] + 5e-3, True)):
            assert check_pair(dataclasses.replace(spec, shift1=float(x), shift2=float(y))).ok == inside, (x, y)
            assert c.in_region(x, y) == inside, (x, y)


def test_a_notch_whose_tip_is_a_saddle_is_traced_to_it():
    """34/76 internal (shaper z0 33) at tol 1e-3: interference.1 has a saddle at (x1, x2) = (1, 1), its
    margin +1e-9 there (the check forgives 1e-9 m_n) and negative in two thin wedges along the diagonal;
    the lower one notches the region. The grid closed the outline across the notch 0.02 short of the
    saddle (the chord 8.1 tol off), and with both ends on interference.1 no corner of two parts was
    there to carry it to. On rows below the saddle, the zeros of the check's margin (brentq) lie within
    2 tol of the outline, and the notch's middle, where check_pair fails, is outside the region."""
    from gearkit.families.involute import ShaperCutter

    tol = 1e-3
    spec = PairSpec(34, 76, 1.0, kind="internal", tool2=ShaperCutter(33))
    field = PairField(spec)
    c = blocking_contour(spec, tol=tol, lines=[])
    for y in np.linspace(0.975, 0.999, 7):
        exact = _zeros(lambda x: field.margin("interference.1", x, y), np.linspace(0.93, 1.0, 141))
        assert len(exact) == 2, (y, exact)
        for x in exact:
            assert _distance_to_outline(c.region, np.array([x, y])) <= CONTRACT * tol, (x, y)
        mid = float(np.mean(exact))
        assert not check_pair(PairSpec(34, 76, 1.0, mid, float(y), kind="internal", tool2=ShaperCutter(33))).ok
        assert not c.in_region(mid, y), (mid, y)


def test_a_corner_beyond_the_windows_edge_is_not_the_regions():
    """40/105 internal (shaper z0 33) at tol 1e-3: contact ratio 1 and exit jamming run within a few tol of
    each other up to the bottom edge of the window and cross at 7 degrees 0.012 below it, at (0.318,
    -1.012); the outline there binds one and the other in turn, and the corner between them was carried to
    that crossing, outside the window: the outline zigzagged below the edge and back, split into a loop of 4
    points and a chord 5.9 tol off the region's edge. On rows just above the edge the polygons cross once,
    where the check's smallest hard margin does (brentq; -1 where no pair exists, just beyond), within 2 tol;
    beside it the region's side passes check_pair and is in the region."""
    import dataclasses

    from gearkit.families.involute import ShaperCutter

    tol = 1e-3
    spec = PairSpec(40, 105, 1.0, kind="internal", tool2=ShaperCutter(33))
    field = PairField(spec)
    c = blocking_contour(spec, tol=tol, lines=[])
    xs = np.linspace(0.30, 0.37, 15)
    for y in (-0.9995, -0.998, -0.995, -0.99, -0.98):  # (both lines end within 1e-3 of the no-pair area: -1 there)
        exact = _zeros(lambda x: np.nan_to_num(_smallest(field, x, y), nan=-1.0), xs)
        assert len(exact) == 1, (y, exact)
        got = xs[0] + _crossings(c.region, np.array([xs[0], y]), np.array([xs[-1], y])) * (xs[-1] - xs[0])
        assert len(got) == 1 and abs(got[0] - exact[0]) <= CONTRACT * tol, (y, exact, got)
        x = float(exact[0] - 3 * tol)
        assert check_pair(dataclasses.replace(spec, shift1=x, shift2=y)).ok and c.in_region(x, y), (x, y)


@pytest.mark.parametrize("key, tip, slope, rows", [((52, 75, 15), (0.3276, -0.1119), 0.904, (-0.083, -0.03, 0.01, 0.02, 0.03)),
                                                   ((41, 80, 19), (0.2143, -0.5706), 0.919, (-0.5, -0.435, -0.42, -0.405))])
def test_a_link_of_a_strips_chain_another_loop_holds_is_not_taken_twice(key, tip, slope, rows):
    """52/75 (shaper z0 15) and 41/80 (z0 19) internal at tol 1e-3: a wedge of the region between interference.1
    and exit jamming, narrower than a grid cell, where the tip sweep's margin is flat; the grid saw a chain of
    diamonds along it. The loop beyond the chain was refined down the wedge over one diamond, which paired with
    no cut, was carried to the wedge's tip and overlapped the other loop there: the part taken twice was left
    out (12.5 and 11.4 tol off). On rows through the wedge every crossing of the polygons lies within 2 tol of a
    zero of the check's smallest hard margin (brentq) and every zero has a crossing within 2 tol; the wedge's
    middle passes check_pair and is in the region."""
    spec, field, c = _internal(*key)
    for y in rows:
        xc = tip[0] + slope * (y - tip[1])
        _crosses_the_strip(spec, field, c, y, np.linspace(xc - 0.02, xc + 0.02, 41), 1e-3)


def test_a_link_of_a_strips_chain_carried_to_the_tip_beside_another_is_not_taken_twice():
    """52/75 internal (shaper z0 15) at tol 1e-5: the same wedge; its chain's last link near (0.354, -0.083), too far
    from the next one's cut to pair with it, was carried to the wedge's tip, where the other loop was carried too,
    and the part the two took twice was left out (215 tol off). On rows through that link and below it every
    crossing of the polygons lies within 2 tol of a zero of the check's smallest hard margin (brentq) and every
    zero has a crossing within 2 tol; the wedge's middle passes check_pair and is in the region."""
    from gearkit.families.involute import ShaperCutter

    tol = 1e-5
    spec = PairSpec(52, 75, 1.0, kind="internal", tool2=ShaperCutter(15))
    field = PairField(spec)
    c = blocking_contour(spec, tol=tol, lines=[])
    for y in (-0.1, -0.09, -0.085, -0.083, -0.08):
        xc = 0.3276 + 0.904 * (y + 0.1119)
        _crosses_the_strip(spec, field, c, y, np.linspace(xc - 0.01, xc + 0.01, 41), tol)


def test_a_link_whose_cuts_were_split_beside_its_corners_is_not_taken_twice():
    """36/82 internal (shaper z0 18) at tol 1e-3: a wedge of the region between interference.1 (above) and contact
    ratio 1 (below), its tip near (0.186, -0.746), narrower than a grid cell; the grid saw two diamonds along it,
    rows x2 = -0.6458 and -0.6667, joined into one loop that paired with no other cut. The last refinement of the
    joined loops split both its cuts beside their corners at the wedge's edge (a vertex 0.0036 off the cut across
    the wedge at the top), so the loop no longer held a chord noted as a cut; carried to the wedge's tip inside the
    loop carried there already, it was not dropped as covered and the part taken twice was left out (its piece
    across the wedge 4.5 tol off). On rows through the link and below it every crossing of the polygons lies
    within 2 tol of a zero of the check's smallest hard margin (brentq) and every zero has a crossing within
    2 tol; the wedge's middle passes check_pair and is in the region."""
    spec, field, c = _internal(36, 82, 18)
    for y in (-0.72, -0.69, -0.672, -0.665, -0.655, -0.645, -0.6424, -0.638, -0.62):
        xc = 0.2566 + 0.87 * (y + 0.668)  # (about the wedge's middle)
        _crosses_the_strip(spec, field, c, y, np.linspace(xc - 0.02, xc + 0.02, 41), 1e-3)
