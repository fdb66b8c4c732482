"""The admissible region beside a wedge of its outside and where two margins vanish on one line, internal
pairs at tol 1e-3, against the check's own scalar margins (``PairField.margin``: the zeros of the smallest
hard margin solved by brentq) and ``check_pair``: every crossing of the region's polygons on a row lies
within 2 tol of a zero, every zero has a crossing within 2 tol, and points on either side are in the
region exactly where the check passes.
"""
import dataclasses
import functools

import numpy as np
import pytest

from gearkit.blocking import blocking_contour
from gearkit.blocking.field import PairField
from gearkit.checks import check_pair
from gearkit.families.involute import ShaperCutter
from gearkit.pair import PairSpec
from test_blocking_region import _crossings, _smallest, _zeros

CONTRACT = 2.0
TOL = 1e-3


@functools.lru_cache(maxsize=None)
def _internal(z1, z2, z0):
    spec = PairSpec(z1, z2, 1.0, kind="internal", tool2=ShaperCutter(z0))
    return spec, PairField(spec), blocking_contour(spec, tol=TOL, lines=[])


def _matched(polygons, a, b, exact) -> np.ndarray:
    """The polygons' crossings of the segment ``a -> b`` (as distances from ``a``), each checked within 2 tol
    of a zero in ``exact`` (distances from ``a`` too) and every zero with a crossing within 2 tol."""
    got = _crossings(polygons, a, b) * float(np.hypot(*(b - a)))
    assert got.size, (a, b, exact)
    near = np.abs(got[:, None] - exact[None, :])
    assert near.min(axis=1).max() <= CONTRACT * TOL, (a, b, exact, got)
    assert near.min(axis=0).max() <= CONTRACT * TOL, (a, b, exact, got)
    return got


def _tip_on_outline(c, edge, a: str, b: str, ys, tol: float):
    """The tip of a wedge between the hard margins ``a`` and ``b``, solved apart from the tracing: the row x2 in
    ``ys`` where their zeros along it (``edge(name, x2)``: brentq) meet (brentq on their difference), x1 there that
    of ``a``; the region's outline is asserted to pass within 2 tol of it. Returns ``(x1, x2)``."""
    from scipy.optimize import brentq
    from test_blocking_region import _distance_to_outline

    yt = brentq(lambda y: edge(a, y) - edge(b, y), *ys, xtol=1e-14)
    xt = edge(a, yt)
    assert _distance_to_outline(c.region, np.array([xt, yt])) <= CONTRACT * tol, (xt, yt)
    return xt, yt


def _passes(spec, x1, x2) -> bool:
    return check_pair(dataclasses.replace(spec, shift1=float(x1), shift2=float(x2))).ok


@pytest.mark.parametrize("y", [1.01, 1.03, 1.06, 1.1, 1.13, 1.16, 1.2, 1.25])
def test_a_strip_beside_a_wedge_of_the_outside_keeps_its_edge(y):
    """59/68 (shaper z0 25): interference.1's negative wedge opens from its saddle at (1, 1) up to the right
    at about 20 degrees, and below it a strip of the region (the tip sweep flat there) runs up to a tip at
    (1.46, 1.36) between the wedge's lower side and exit jamming, narrower than a grid cell. A chord along the
    strip's edge (the re-joined strip's) had its middle 3e-5 inside the wedge and the strip's far edge hid
    the near zero between the normal's samples; the search found the wedge's other side 1.7 chords off, the
    chord was split there and the outline zigzagged across the wedge down to the saddle (35 tol off, the
    wedge's middle in the region). On rows across the wedge and the strip the polygons cross only at the
    three zeros (the wedge's two sides, exit jamming); beside the wedge, in its middle and in the strip's
    middle the region agrees with check_pair."""
    spec, field, c = _internal(59, 68, 25)
    xs = np.linspace(0.95, 1.45, 201)
    exact = _zeros(lambda x: _smallest(field, x, y), xs)
    assert len(exact) == 3, (y, exact)
    _matched(c.region, np.array([xs[0], y]), np.array([xs[-1], y]), exact - xs[0])
    for x, inside in ((exact[0] - 0.005, True), (0.5 * (exact[0] + exact[1]), False),
                      (0.5 * (exact[1] + exact[2]), True)):
        assert _passes(spec, x, y) == inside, (x, y)
        assert c.in_region(x, y) == inside, (x, y)


def test_two_margins_vanishing_on_one_line_have_no_corner_along_it():
    """21/65 (shaper z0 21): tip_clearance.1 and interference.2 both vanish on the line x1 = 0 above
    x2 = 1.566 (the region's edge there, its side x1 < 0), where tip_clearance.1's zero turns along
    x2 = 1.566; the outline's vertices along the line bind one or the other by which side of it they lie on.
    A corner between them was solved from a chord 0.68 up the line (Newton's steps along two parallel lines
    ran down it to the region's corner), the outline carried down there and back, and what was left cut the
    corner from (0.0059, 1.566) to (0, 2.347) (2.9 tol off, points beside the line on its wrong side in the
    region). On rows across the line and columns across x2 = 1.566 beside the corner the polygons cross
    only at the zeros; beside the line the region agrees with check_pair."""
    spec, field, c = _internal(21, 65, 21)
    xs = np.linspace(-0.02, 0.02, 41)
    for y in (1.58, 1.7, 1.9, 2.1, 2.3):
        exact = _zeros(lambda x: _smallest(field, x, y), xs)
        assert len(exact) == 1, (y, exact)
        _matched(c.region, np.array([xs[0], y]), np.array([xs[-1], y]), exact - xs[0])
        for x, inside in ((exact[0] - 2 * TOL, True), (exact[0] + 2 * TOL, False)):
            assert _passes(spec, x, y) == inside, (x, y)
            assert c.in_region(x, y) == inside, (x, y)
    ys = np.linspace(1.5, 1.65, 31)
    for x in (0.001, 0.003, 0.005, 0.01):
        exact = _zeros(lambda y: _smallest(field, x, y), ys)
        assert len(exact) == 1, (x, exact)
        _matched(c.region, np.array([x, ys[0]]), np.array([x, ys[-1]]), exact - ys[0])


def test_a_cut_whose_tip_lies_behind_it_is_not_carried_there():
    """23/89 internal (shaper z0 19) at tol 1e-5: the flat strip between interference.1 and exit jamming ends in a
    wedge with its tip at (0.4724, -0.7947), narrower than a grid cell; one grid node inside it, at x2 = -0.7917,
    gave a diamond alone in the wedge with a cut across it on each side. Both cuts bind the wedge's two sides,
    and Newton's steps from either run down to the tip: the lower cut rightly, the upper one back through its
    own diamond, so the diamond's loop passed the tip twice and, with the outline beyond the diamond carried
    there too, the even-odd rule left the wedge's end out (18.6 tol off). On rows through the diamond and below
    it every crossing of the polygons lies within 2 tol of a zero of the check's smallest hard margin (brentq)
    and every zero has a crossing within 2 tol; the wedge's middle passes check_pair and is in the region."""
    from test_blocking_region import _crosses_the_strip

    tol = 1e-5
    spec = PairSpec(23, 89, 1.0, kind="internal", tool2=ShaperCutter(19))
    field = PairField(spec)
    c = blocking_contour(spec, tol=tol, lines=[])
    for y in (-0.7944, -0.794, -0.793, -0.792, -0.7915, -0.791):
        xc = 0.4724 + 0.72 * (y + 0.7947)
        _crosses_the_strip(spec, field, c, y, np.linspace(xc - 0.002, xc + 0.002, 401), tol)


def test_a_link_refined_to_the_wedge_tip_the_loop_reached_leaves_no_sliver():
    """59/68 (shaper z0 25): the region narrows between interference.2 (above) and the steep side of
    interference.1's wedge from (1, 1) to a tip at about (1.291, 1.511); the grid closed the big loop across
    the wedge a cell short of the tip and left the tip as a diamond of its own. The loop's cut was refined up
    the wedge to the tip, and so was the diamond's: its chord from the upper side down to the steep side,
    with no zero within its normal's ends, was split at a zero the wide search found at the tip, past the
    loop's line. The diamond, a fold inside the loop, was carried to the tip again and a chord from
    (1.28125, 1.4925) on the steep side to (1.2852, 1.5092) on the upper one was left across the region, the
    sliver between it and the steep side taken twice and left out by the even-odd rule (2.1 tol off; rows
    3.7 tol, columns 4.8 tol). On rows and columns through the tip's neighbourhood the polygons cross only at
    the zeros (the two sides); between and beside them the region agrees with check_pair."""
    spec, field, c = _internal(59, 68, 25)
    rows = [(y, lambda t, y=y: (t, y)) for y in (1.494, 1.497, 1.5, 1.503, 1.506, 1.508)]
    columns = [(x, lambda t, x=x: (x, t)) for x in (1.2825, 1.284, 1.2855, 1.287)]
    for scans, ts in ((rows, np.linspace(1.23, 1.30, 281)), (columns, np.linspace(1.48, 1.53, 201))):
        for at, point in scans:
            exact = _zeros(lambda t: _smallest(field, *point(t)), ts)
            assert len(exact) == 2, (at, exact)
            _matched(c.region, np.array(point(ts[0])), np.array(point(ts[-1])), exact - ts[0])
            for t, inside in ((exact[0] - 0.005, False), (0.5 * (exact[0] + exact[1]), True), (exact[1] + 0.005, False)):
                assert _passes(spec, *point(t)) == inside, point(t)
                assert c.in_region(*point(t)) == inside, point(t)


def test_a_wedge_whose_tip_the_windows_edge_cuts_is_traced_to_the_edge():
    """14/62 at tol 1e-3 in a window whose top edge lies 0.5 tol below the tip of the region's wedge between
    pointing.1 and interference.1 (at (0.961344, -1.327878)): the path carried from the chord across the wedge
    up to the edge was judged at its vertex on the window's edge by the vertex's own part's slope (the window's
    edge: 1) against interference.1 just below zero there (its slope 1.4e-3 of the edge's, so 0.5 tol of
    distance read as 700), rejected, and the chord left cutting the wedge 42 tol below the edge (6.1 tol off
    the region's edge). On rows across the wedge below the edge the polygons cross only at the check's zeros
    (the smallest hard margin's, brentq), on columns through it only at those and at the window's edge, each
    within 2 tol of one and each zero with a crossing; inside the wedge next to the edge the check passes and
    the point is in the region."""
    tol = 1e-3
    spec = PairSpec(14, 62, 1.0)
    field = PairField(spec)
    base = blocking_contour(spec, tol=tol, lines=[]).window
    top = -1.327878 - 0.5 * tol
    c = blocking_contour(spec, tol=tol, window=(base[0], base[1], base[2], top))
    xs = np.linspace(0.95, 0.975, 251)
    for d in (3, 6, 10, 20, 30):
        y = top - d * tol
        exact = _zeros(lambda x: _smallest(field, x, y), xs)
        assert len(exact) == 2, (y, exact)
        got = xs[0] + _crossings(c.region, np.array([xs[0], y]), np.array([xs[-1], y])) * (xs[-1] - xs[0])
        assert len(got) == 2 and np.abs(got - exact).max() <= CONTRACT * tol, (y, exact, got)
    ys = np.linspace(top - 0.03, top + 0.005, 71)
    for x in (0.9605, 0.961, 0.9615, 0.962):
        zeros = _zeros(lambda y: np.nan_to_num(_smallest(field, x, y), nan=-1.0), ys)
        exact = zeros[zeros < top]  # the check's zeros in the window, and its edge where the check passes there
        if _smallest(field, x, top) > 0:
            exact = np.append(exact, top)
        _matched(c.region, np.array([x, ys[0]]), np.array([x, ys[-1]]), exact - ys[0])
    for x, y in ((0.96134, top - 0.25 * tol), (0.96137, top - 2 * tol)):
        assert _passes(spec, x, y) and c.in_region(x, y), (x, y)


def test_a_strip_under_a_wedge_beside_its_saddle_is_traced_to_both_its_ends():
    """56/63 internal (shaper z0 25) at tol 1e-5: below interference.1's wedge opening up to the right from its saddle
    at (1, 1), and below the wedge opening down to the left, a strip of the region runs between the wedges' lower
    sides and exit jamming, from (0.99936, 0.99904) to (1.00164, 1.00123) where the two cross, joined to the rest
    of the region through the saddle's neck; interference.1 is below 4e-7 all across it. A chord from exit jamming
    to the upper wedge's far side, its middle in the strip, found no zero at its normal's ends; the wide search's
    zero on exit jamming 0.8 chords off read nearer by the secant (5e-8) than the ladder's on the wedge's side 0.1
    chords off, the chord was split there and the outline folded back along exit jamming, and the cuts across the
    strip, both ends read as binding interference.1, were carried to neither end: the strip's ends left out
    (10.5 tol off). On rows through the strip the polygons cross only at the three zeros of the check's smallest
    hard margin (brentq: the wedge's two sides, exit jamming), each within 2 tol of one and each zero with a
    crossing; beside the wedge, in its middle, in the strip's middle and past exit jamming the region agrees with
    check_pair."""
    tol = 1e-5
    spec = PairSpec(56, 63, 1.0, kind="internal", tool2=ShaperCutter(25))
    field = PairField(spec)
    c = blocking_contour(spec, tol=tol, lines=[])
    for y in (0.9992, 0.9995, 1.0002, 1.0004, 1.0008, 1.0011):
        xs = np.linspace(y - 0.0006, y + 0.0008, 211)
        exact = _zeros(lambda x: _smallest(field, x, y), xs)
        assert len(exact) == 3, (y, exact)
        got = xs[0] + _crossings(c.region, np.array([xs[0], y]), np.array([xs[-1], y])) * (xs[-1] - xs[0])
        assert got.size, (y, exact)
        near = np.abs(got[:, None] - exact[None, :])
        assert near.min(axis=1).max() <= CONTRACT * tol and near.min(axis=0).max() <= CONTRACT * tol, (y, exact, got)
        for x, inside in ((exact[0] - 1e-4, True), (0.5 * (exact[0] + exact[1]), False),
                          (0.5 * (exact[1] + exact[2]), True), (exact[2] + 1e-4, False)):
            assert _passes(spec, x, y) == inside, (x, y)
            assert c.in_region(x, y) == inside, (x, y)


def test_a_wedge_between_a_gentle_and_a_steep_margin_is_taken_once_up_to_its_tip():
    """18/74 internal (shaper z0 33) at tol 1e-5: the region ends in a wedge between pointing.1 (the line x1 =
    0.592179, gentle) and interference.1 (steep), its tip at (0.592179, -0.48989), narrower than a grid cell; the
    grid's chord cut it a cell below the tip. Split up the wedge, a chord along pointing.1 with its middle on it
    (F = 4e-9) had a zero to each side along its normal: its own line's 6e-9 off and the steep side's 0.0045 off,
    which the secant from the middle read as the nearer (F = -0.016 there against -0.004); the chord was split
    there, the splits went from one side of the wedge to the other, the outline went over the wedge's top three
    times and the part held twice was left out by the even-odd rule (23.2 tol off: on rows 7e-4 and 8e-4 below the
    tip crossings 8 and 16 tol off, the wedge's middle out of the region up to 7e-4 below it). The tip is solved
    apart from the tracing (brentq on the two margins' zeros along rows, then on their difference): the outline
    passes within 2 tol of it; on rows below it every crossing of the polygons lies within 2 tol of a zero of the
    check's smallest hard margin (brentq) and every zero has one, and the wedge's middle passes check_pair and is
    in the region."""
    from test_blocking_region import _crosses_the_strip, _edge

    tol = 1e-5
    spec = PairSpec(18, 74, 1.0, kind="internal", tool2=ShaperCutter(33))
    field = PairField(spec)
    c = blocking_contour(spec, tol=tol, lines=[])
    edge = lambda name, y: _edge(field, name, y, 0.57, 0.60)  # noqa: E731
    xt, yt = _tip_on_outline(c, edge, "pointing.1", "interference.1", (-0.495, -0.485), tol)
    for d in (2e-4, 5e-4, 7e-4, 8e-4, 1e-3, 2e-3, 5e-3):  # (the wedge is about 0.65 d wide d below its tip)
        _crosses_the_strip(spec, field, c, yt - d, np.linspace(xt - 0.8 * d - 1e-4, xt + 1e-4, 41), tol)


def test_a_thin_wedge_split_beside_its_turn_is_not_folded_off_its_loop():
    """35/56 internal (shaper z0 22) at tol 1e-5: the region has a thin wedge between interference.1 (left) and
    exit jamming (right), its tip at about (0.52416, 0.12449), the tip sweep flat inside it. A chord of the outline
    near its turn, measured a quarter from it (corner_splits), had F = +3.5e-6 there with its own side's zero
    beside it and interference.1's 0.0029 off on the other side; the secant's guess read the far side as the
    nearer, the chord got a vertex on interference.1, and the outline crossed the wedge and back: an 11-vertex
    loop folded off, which the even-odd rule left out (the region 13.8 tol off). The tip is solved apart from the
    tracing (brentq on the two margins' zeros along rows, then on their difference): the outline passes within
    2 tol of it; on rows above it every crossing of the polygons lies within 2 tol of a zero of the check's
    smallest hard margin (brentq) and every zero has one, and the wedge's middle passes check_pair and is in the
    region."""
    from test_blocking_region import _crosses_the_strip, _edge

    tol = 1e-5
    spec = PairSpec(35, 56, 1.0, kind="internal", tool2=ShaperCutter(22))
    field = PairField(spec)
    c = blocking_contour(spec, tol=tol, lines=[])
    edge = lambda name, y: _edge(field, name, y, 0.522, 0.530)  # noqa: E731
    xt, yt = _tip_on_outline(c, edge, "interference.1", "exit_jamming", (0.1240, 0.1250), tol)
    for d in (2e-4, 5e-4, 1e-3, 1.5e-3, 2e-3, 3e-3, 4e-3, 5e-3):  # (the wedge is about 0.25 d wide d above its tip)
        _crosses_the_strip(spec, field, c, yt + d, np.linspace(xt + 0.6 * d - 1e-4, xt + 1.2 * d + 1e-4, 41), tol)


def test_no_chord_of_a_line_beside_a_thin_wedges_tip_is_of_no_length():
    """49/64 internal with a 20-tooth shaper at tol 1e-5: interference.1's line at the tip of a thin wedge near
    (1.048, 1.032) repeated a vertex next to itself (a front carried to where another piece already ended). A
    chord of no length has no direction, and the exact measure, reading the zero set along no normal, put the
    line 4.3 tol off. Every chord of the line has a length, and the exact distance of its vertices and chords'
    middles from the zeros of its margin (solved on rays to 1e-14, ``gearkit.bench.exact``) is within 2 tol."""
    from gearkit.bench.exact import deviation

    tol = 1e-5
    c = blocking_contour(PairSpec(49, 64, 1.0, kind="internal", tool2=ShaperCutter(20)), tol=tol,
                         lines=["interference.1"])
    for q in c.line("interference.1").components:
        assert np.all(np.hypot(*np.diff(q, axis=0).T) > 0)
    assert deviation(c) <= CONTRACT * tol


def test_a_curved_wedge_is_carried_to_its_tip():
    """21/55 internal (shaper z0 18) at tol 1e-3: interference.1 and contact ratio 1 bound a wedge of the region 0.14
    long that bends away from the straight way to its tip; the point halfway from the grid's chord across it (near
    (0.653, -0.015)) to the tip lay 0.003 outside it, the tip was taken for one behind the chord and the chord was
    kept (6.5 tol off). The tip is solved apart from the tracing (brentq on the two margins' zeros along rows, then
    on their difference): the outline passes within 2 tol of it; on rows through the wedge every crossing of the
    polygons lies within 2 tol of a zero of the check's smallest hard margin (brentq) and every zero has one, and
    the wedge's middle passes check_pair and is in the region."""
    from test_blocking_region import _crosses_the_strip, _edge

    spec, field, c = _internal(21, 55, 18)
    edge = lambda name, y: _edge(field, name, y, 0.53, 0.5752 + (y + 0.12))  # noqa: E731 (short of the no-pair area)
    _tip_on_outline(c, edge, "interference.1", "contact_ratio=1", (-0.12, -0.11), TOL)
    for y in (-0.02, -0.04, -0.06, -0.08, -0.10):  # the wedge's sides about x1 = 0.6424 + (0.78, 0.95) (x2 + 0.02)
        xs = np.linspace(0.6424 + 0.78 * (y + 0.02) - 5e-3, 0.6576 + 0.95 * (y + 0.02) + 5e-3, 61)
        _crosses_the_strip(spec, field, c, y, xs, TOL)


def test_a_cut_is_not_carried_through_a_wedges_tip_to_the_frame():
    """39/91 internal (shaper z0 19) at tol 5e-3: exit jamming and interference.1 bound a thin wedge of the region
    whose tip lies at (0.093, -0.964), 0.036 above the window's bottom edge; a cut of a grid node's diamond inside the
    wedge, its tip behind the cut, was carried along both lines through the tip to where they meet the frame beyond
    it, 0.005 apart (within tol of each other there), and the triangle of the outside between them was held as
    region (13.8 tol off). On rows between the tip and the frame the check's smallest hard margin is below zero
    everywhere it is defined (the oracle): the polygons cross none of them and hold none of their points."""
    from test_blocking_region import _crossings, _smallest

    tol = 5e-3
    spec = PairSpec(39, 91, 1.0, kind="internal", tool2=ShaperCutter(19))
    field, c = PairField(spec), blocking_contour(spec, tol=tol, lines=[])
    assert c.window[2] == -1.0
    xs = np.linspace(0.0, 0.16, 81)
    for y in (-0.97, -0.98, -0.99, -0.998):
        v = np.array([_smallest(field, x, y) for x in xs])
        assert np.nanmax(v) < 0, (y, np.nanmax(v))
        assert _crossings(c.region, np.array([xs[0], y]), np.array([xs[-1], y])).size == 0, y
        assert not np.any([c.in_region(x, y) for x in xs]), y


def test_a_wedge_along_the_no_pair_edge_is_carried_to_its_tip():
    """21/80 internal (shaper z0 27) at tol 1e-3: interference.1 and, beside the no-pair area's edge, contact ratio 1
    then exit jamming bound a wedge of the region 0.1 long whose tip lies near (0.358, -0.846). The grid closed the
    loop across it 0.1 short of the tip; the first Newton step from the cut towards the crossing of its two parts
    ended in the no-pair area, where neither is defined, the solve failed and the cut was kept (6.6 tol off). The tip
    is solved apart from the tracing (brentq on the zeros of interference.1 and exit jamming along rows short of the
    area, then on their difference): the outline passes within 2 tol of it; on rows through the wedge every crossing
    of the polygons lies within 2 tol of a zero of the check's smallest hard margin (brentq) and every zero has one,
    and the wedge's middle passes check_pair and is in the region."""
    from test_blocking_region import _crosses_the_strip, _edge

    spec, field, c = _internal(21, 80, 27)
    short = lambda y: 0.4471 + (y + 0.76)  # noqa: E731 (1e-3 short of the no-pair area, whose edge runs at 45 degrees)
    edge = lambda name, y: _edge(field, name, y, 0.33, short(y))  # noqa: E731
    _tip_on_outline(c, edge, "interference.1", "exit_jamming", (-0.85, -0.843), TOL)
    for y in (-0.77, -0.79, -0.81, -0.83, -0.84):
        xs = np.linspace(edge("interference.1", y) - 5e-3, short(y), 61)
        _crosses_the_strip(spec, field, c, y, xs, TOL)


def test_a_third_margin_crossing_a_wedge_at_a_small_angle_ends_it():
    """18/74 internal (shaper z0 27) at tol 1e-3: interference.1 and contact ratio 1 bound a wedge of the region along
    the no-pair area's edge, crossing at (0.4139, -0.7289); exit jamming's line crosses the wedge at a small angle,
    meeting contact ratio 1 near x2 = -0.717 and interference.1 near -0.723, where the region ends. At the two parts'
    crossing exit jamming lies 0.73 tol below zero by its slope, so no third side was sought, and the outline was
    carried to that crossing, 8.9 tol beyond the region. The tip is solved apart from the tracing (brentq on the zeros
    of interference.1 and exit jamming along rows short of the area, then on their difference): the outline passes
    within 2 tol of it; on rows through the wedge every crossing of the polygons lies within 2 tol of a zero of the
    check's smallest hard margin and every zero has one, and the wedge's middle passes check_pair and is in the
    region; on rows more than 2 tol beyond the tip the smallest hard margin is below zero all along (sampled) and
    the polygons cross none of them."""
    from test_blocking_region import _crosses_the_strip, _edge

    spec, field, c = _internal(18, 74, 27)
    short = lambda y: 0.4455 + (y + 0.7)  # noqa: E731 (short of the no-pair area, whose edge runs at 45 degrees)
    edge = lambda name, y: _edge(field, name, y, 0.40, short(y))  # noqa: E731
    _, yt = _tip_on_outline(c, edge, "interference.1", "exit_jamming", (-0.726, -0.72), TOL)
    for y in (-0.70, -0.705, -0.71):
        xs = np.linspace(edge("interference.1", y) - 3e-3, short(y), 61)
        _crosses_the_strip(spec, field, c, y, xs, TOL)
    for y in (yt - 2.5 * TOL, yt - 4 * TOL):
        xs = np.linspace(0.40, short(y), 201)
        assert max(_smallest(field, x, y) for x in xs) < 0, y
        assert _crossings(c.region, np.array([xs[0], y]), np.array([xs[-1], y])).size == 0, y


@pytest.mark.parametrize("y", [1.0015, 1.003, 1.0045])
def test_a_wedge_of_the_region_beyond_a_saddles_neck_is_taken(y):
    """External 29/37 at tol 1e-3: beyond the neck of interference.2's saddle at (-1, 1) the region goes on in a
    wedge 5.5 tol long up to (-1.0021, 1.0051), which no grid node sees; the outline closed across the neck at a
    corner of 111 degrees and left it out. Oracle: on rows x2 = const across the wedge, the zeros of the check's
    smallest hard margin (brentq) and the polygons' crossings within 2 tol of each other (no crossing at all on
    the old code), the wedge's middle passing check_pair and in the region."""
    spec = PairSpec(29, 37, 1.0)
    field, c = PairField(spec), _external(29, 37)
    a, b = np.array([-1.004, y]), np.array([-0.9995, y])
    t = np.linspace(0.0, 1.0, 901)
    exact = _zeros(lambda s: _smallest(field, *(a + s * (b - a))), t) * float(np.hypot(*(b - a)))
    assert len(exact) >= 2
    got = _matched(c.region, a, b, exact)
    mid = a + 0.5 * (got[0] + got[1]) / float(np.hypot(*(b - a))) * (b - a)
    assert _passes(spec, *mid) and c.contains(*mid)


@functools.lru_cache(maxsize=None)
def _external(z1, z2):
    return blocking_contour(PairSpec(z1, z2, 1.0), tol=TOL, lines=[])


@pytest.mark.parametrize("y", [-0.9995, -0.998, -0.995, -0.985, -0.96])
def test_a_wedge_whose_tip_lies_beyond_the_window_is_traced_to_the_frame(y):
    """Internal 42/98 (shaper 16) at tol 1e-3: interference.1 and contact ratio 1 bound a wedge of the region whose
    tip lies 3.8 tol below the window's bottom edge (x2 = -1). Carried to that tip, the path was no edge (a vertex
    outside the window), and the grid's chord across the wedge, 5 tol wide there, was kept 70 tol short of the
    frame (the exact measure 2.5 tol at its middle). On rows across the wedge down to the frame, the zeros of the
    check's smallest hard margin (brentq) and the polygons' crossings within 2 tol of each other (no crossing on
    the old code below the cut at x2 = -0.935), the wedge's middle passing check_pair and in the region."""
    spec, field, c = _internal(42, 98, 16)
    assert c.window[2] == pytest.approx(-1.0)
    x = 0.154 + 0.856 * (y + 0.96)  # about the wedge's middle
    a, b = np.array([x - 0.01, y]), np.array([x + 0.01, y])
    t = np.linspace(0.0, 1.0, 801)
    exact = _zeros(lambda s: _smallest(field, *(a + s * (b - a))), t) * float(np.hypot(*(b - a)))
    assert len(exact) == 2, exact
    got = _matched(c.region, a, b, exact)
    mid = a + 0.5 * (got[0] + got[1]) / float(np.hypot(*(b - a))) * (b - a)
    assert _passes(spec, *mid) and c.contains(*mid)
