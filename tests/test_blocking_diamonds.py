"""A flat strip of the admissible region narrower than a grid cell, traced through the grid's chain of diamonds
(one loop about each node inside it): each link's cut across the strip must stay a cut, to be re-joined with the
next link's, and the strip's last cut must be carried on to its end. Oracle: the check's own scalar margins
(``PairField.margin``, their zeros along rows solved by brentq) and ``check_pair`` (the row helpers of
``test_blocking_region``).
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
from test_blocking_region import CONTRACT, _crossings, _crosses_the_strip, _smallest, _zeros

TOL = 1e-5
SIDE = 4e-3  #: each row is sampled this far beyond the strip's edges (short of every other zero)


@functools.lru_cache(maxsize=None)
def _internal(z1, z2, z0, tol=TOL):
    spec = PairSpec(z1, z2, 1.0, kind="internal", tool2=ShaperCutter(z0))
    return spec, PairField(spec), blocking_contour(spec, tol=tol, lines=[])


# internal pair (shaper z0) -> the strip's two edges as lines x1 = x0 + slope (x2 - y0) (to place each row's
# samples: the edges themselves are the check's zeros, solved on each row), and the rows x2 through it
STRIPS = {(25, 59, 35): ((0.5315, 0.781, -0.1471), (0.5372, 1.035, -0.1471),
                         (-0.136, -0.13, -0.125, -0.12, -0.115, -0.11, -0.106)),
          (55, 102, 34): ((0.025, 0.845, -0.916), (0.030, 0.987, -0.925),
                          (-0.918, -0.912, -0.905, -0.895, -0.88, -0.865, -0.855, -0.85))}


@pytest.mark.parametrize("key", sorted(STRIPS))
def test_a_flat_strips_links_are_not_refined_past_each_others_cuts(key):
    """25/59 (shaper z0 35) and 55/102 (z0 34) internal at tol 1e-5: the strip between interference.1 and exit
    jamming where the tip sweep's margin is flat (0.005 to 0.02 wide, a region grid cell about 0.02), seen by the
    grid as a chain of diamonds. A link's cut, whose normal runs along the strip, was read at the reach or twice
    it, where the ray had left the strip through its far edge on one side, and that zero was taken as the cut's:
    the loop was refined down the strip past the next link's cut, which then paired with none, and the part the
    two loops both held was left out by the even-odd rule (565 and 810 tol off; 25/59's last cut, 0.01 short of
    the strip's end at trimming.plunge, was kept there). On rows through the strip, from its end up, every
    crossing of the polygons lies within 2 tol of a zero of the check's smallest hard margin (brentq) and every
    zero has one; the strip's middle passes check_pair and is in the region."""
    spec, field, c = _internal(*key, TOL)
    (xl, sl, yl), (xr, sr, yr), rows = STRIPS[key]
    for y in rows:
        xs = np.linspace(xl + sl * (y - yl) - SIDE, xr + sr * (y - yr) + SIDE, 61)
        _crosses_the_strip(spec, field, c, y, xs, TOL)


def _segment_meets_the_strip(spec, field, c, a, b, n=61):
    """On the segment ``a -> b`` (sampled at ``n`` points): the check's smallest hard margin has two zeros (brentq),
    every crossing of the region's polygons lies within 2 tol of one and each has a crossing within 2 tol; the
    middle between them passes check_pair and is in the region."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    span = float(np.hypot(*(b - a)))
    exact = _zeros(lambda s: _smallest(field, *(a + s * (b - a))), np.linspace(0.0, 1.0, n)) * span
    assert len(exact) == 2, (a, b, exact)
    got = _crossings(c.region, a, b) * span
    near = np.abs(got[:, None] - exact[None, :])
    assert got.size and near.min(axis=1).max() <= CONTRACT * TOL, (a, b, exact, got)
    assert near.min(axis=0).max() <= CONTRACT * TOL, (a, b, exact, got)
    mid = a + 0.5 * (exact[0] + exact[1]) / span * (b - a)
    assert check_pair(dataclasses.replace(spec, shift1=float(mid[0]), shift2=float(mid[1]))).ok, mid
    assert c.in_region(*mid), mid


def test_a_flat_strips_last_cut_is_carried_to_its_end():
    """25/59 internal (shaper z0 35) at tol 1e-5: the same strip's last cut, across it at (0.543, -0.138) with its
    normal along the strip, 0.0055 long (the strip's width), found no zero at the normal's reach or twice it: the
    strip's end (exit jamming and trimming.plunge at x2 = -0.1471) lay 2.01 of its lengths beyond. The cut was
    kept there and the outline missed the strip's last 0.01 (273 tol off). On rows through that part, and on
    columns across the strip's end, every crossing of the polygons lies within 2 tol of a zero of the check's
    smallest hard margin (brentq) and every zero has one; the middle between them passes check_pair and is in the
    region."""
    spec, field, c = _internal(25, 59, 35)
    (xl, sl, yl), (xr, sr, yr), _ = STRIPS[(25, 59, 35)]
    for y in (-0.1466, -0.145, -0.143, -0.141, -0.139, -0.137):
        _segment_meets_the_strip(spec, field, c, (xl + sl * (y - yl) - SIDE, y), (xr + sr * (y - yr) + SIDE, y))
    for x in (0.5325, 0.534, 0.5355, 0.537):  # up from below the end to past the strip's left edge
        _segment_meets_the_strip(spec, field, c, (x, yl - SIDE), (x, yl + (x - xl) / sl + SIDE))


# internal pair (shaper z0), tol -> the strip's or wedge's two edges as in STRIPS, its rows, and columns x1 = x with
# their x2 span, crossing the strip's end (each with two zeros of the check's smallest hard margin)
ENDS = {(19, 72, 33, 1e-3): ((0.4855, 0.7475, -0.5825), (0.4901, 1.051, -0.5917),
                             (-0.594, -0.592, -0.59, -0.588, -0.586, -0.584), ((0.481, -0.600, -0.585),)),
        (19, 72, 33, 1e-5): ((0.4855, 0.7475, -0.5825), (0.4901, 1.051, -0.5917),
                             (-0.595, -0.594, -0.592, -0.59, -0.588, -0.586, -0.584),
                             ((0.4785, -0.600, -0.590), (0.481, -0.600, -0.585), (0.484, -0.600, -0.583))),
        (25, 59, 35, 1e-5): ((0.5315, 0.781, -0.1471), (0.5372, 1.035, -0.1471), (-0.147, -0.146, -0.144, -0.142),
                             ((0.534, -0.152, -0.140), (0.536, -0.152, -0.138))),
        (40, 64, 22, 1e-5): ((0.4887, 0.778, 0.0417), (0.4978, 1.029, 0.0312),
                             (-0.035, -0.03, -0.02, -0.01, 0.0, 0.01, 0.02, 0.03, 0.04), ())}


@pytest.mark.parametrize("key", sorted(ENDS))
def test_a_flat_strips_cut_is_carried_to_its_end_or_its_tip(key):
    """19/72 (shaper z0 33) internal at tol 1e-3 and 1e-5: the flat strip between interference.1 and exit jamming
    (0.01 wide) ends at trimming.plunge's line (x2 = -0.5953) before its sides meet (0.044 below it); the
    crossing of the sides, carried to, was no edge (trimming.plunge below zero there) and the strip's last cut was
    left 0.01 to 0.013 short of its end, 4.9 and 513 tol off: the end is the two corners with the part across the
    strip (so too 25/59, z0 35, at 1e-5: its strip's last cut 0.01 short of trimming.plunge, 273 tol). 40/64 (z0 22) at tol 1e-5: the flat wedge between the same two, 0.002 to 0.01 wide, the loop's cut
    0.07 above a lone diamond (too far to pair with its cut); the carry of the cut to the wedge's tip crossed the
    diamond and the loop's own folds along exit jamming and was not taken, the wedge between them left out, 691
    tol off. On rows through the strip (and columns through its end), every crossing of the polygons lies within
    2 tol of a zero of the check's smallest hard margin (brentq) and every zero has one; the middle passes
    check_pair and is in the region."""
    *pair, tol = key
    spec, field, c = _internal(*pair, tol)
    (xl, sl, yl), (xr, sr, yr), rows, columns = ENDS[key]
    for y in rows:
        xs = np.linspace(xl + sl * (y - yl) - SIDE, xr + sr * (y - yr) + SIDE, 61)
        _crosses_the_strip(spec, field, c, y, xs, tol)
    for x, lo, hi in columns:
        _crosses_the_strip(spec, field, c, x, np.linspace(lo, hi, 61), tol, column=True)


CHAIN_ROWS = (2.40, 2.45, 2.50, 2.55, 2.60, 2.65, 2.70, 2.75, 2.80)  #: rows x2 = const through 33/63's strip ...
CHAIN_EDGES = (-1.4555, -1.4390, -0.159)  #: ... its left and right edges at x2 = 2.8 and their slope dx1 / dx2


@pytest.mark.parametrize("tol", [1e-3, 1e-5])
def test_the_links_of_a_strip_far_apart_are_one_part_of_the_region(tol):
    """33/63 external at tol 1e-3 and 1e-5: interference.1 and interference.2 bound a strip of the region 0.013
    wide that runs from the triangle it widens into (below x2 = 2.3) to its end near (-1.45, 2.82), seen by the
    grid as a chain of diamonds 0.07 to 0.1 apart, each cut across the strip 0.013 long: too far apart to pair,
    each link was carried down the strip to its far corner, and the triangle and the strip were held by two and
    three polygons, the strip's middle left out by the even-odd rule (6.7 and 718 tol off). On rows through the
    strip, every crossing of the polygons lies within 2 tol of a zero of the check's smallest hard margin (brentq)
    and every zero has one; the middle passes check_pair and is in the region."""
    spec = PairSpec(33, 63, 1.0)
    field, c = PairField(spec), blocking_contour(spec, tol=tol, lines=[])
    left, right, slope = CHAIN_EDGES
    for y in CHAIN_ROWS:
        xs = np.linspace(left + slope * (y - 2.8) - SIDE, right + slope * (y - 2.8) + SIDE, 61)
        _crosses_the_strip(spec, field, c, y, xs, tol)


FRAME_ROWS = (2.88, 2.90, 2.92, 2.94, 2.96, 2.98, 2.995)  #: rows x2 = const through 34/81's strip below the frame ...
FRAME_EDGES = (-1.4675, -1.4585, -0.135)  #: ... its left and right edges at x2 = 3 and their slope dx1 / dx2


@pytest.mark.parametrize("tol", [1e-3, 1e-5])
def test_a_strip_running_out_through_the_frame_is_carried_to_it(tol):
    """34/81 external at tol 1e-3 and 1e-5: interference.1 and interference.2 bound a strip of the region 0.006 wide
    that runs out through the window's top frame (x2 = 3), whose last row of grid nodes lies outside it; the grid
    closed the outline across the strip at x2 = 2.875, and the sides, which cross far down, were carried nowhere
    (3 and 300 tol off). On rows through the strip up to the frame, every crossing of the polygons lies within 2 tol
    of a zero of the check's smallest hard margin (brentq) and every zero has one; the middle passes check_pair and
    is in the region."""
    spec = PairSpec(34, 81, 1.0)
    field, c = PairField(spec), blocking_contour(spec, tol=tol, lines=[])
    assert c.window[3] == 3.0
    left, right, slope = FRAME_EDGES
    for y in FRAME_ROWS:
        xs = np.linspace(left + slope * (y - 3.0) - SIDE, right + slope * (y - 3.0) + SIDE, 61)
        _crosses_the_strip(spec, field, c, y, xs, tol)


END_ROWS = (1.765, 1.77, 1.775, 1.78, 1.785, 1.79, 1.793)  #: rows x2 = const through 30/33's strip below its end ...
END_EDGES = (-1.2688, -1.2570, -0.229, -0.264)  #: ... its edges at x2 = 1.76 and their slopes dx1 / dx2


@pytest.mark.parametrize("tol", [1e-3, 1e-5])
def test_a_strip_ended_by_a_third_margin_short_of_the_frame_is_carried_to_its_end(tol):
    """30/33 external at tol 1e-3 and 1e-5: interference.1 and interference.2 bound a strip of the region 0.012 wide
    whose sides meet far behind the grid's cut across it (near (-1.07, 0.97)) and, carried on, would reach the
    window's top frame; the strip ends 0.035 past the cut where pointing.2's line crosses it (near x2 = 1.795). The
    carry to the frame was no edge (its sides pass where pointing.2 fails), and the cut was kept (5.8 and 578 tol
    off). On rows through the strip up to its end, every crossing of the polygons lies within 2 tol of a zero of the
    check's smallest hard margin (brentq) and every zero has one, the middle passing check_pair and in the region;
    on rows past its end, where that margin is below zero at every sample, the polygons hold no point."""
    from test_blocking_region import _smallest

    spec = PairSpec(30, 33, 1.0)
    field, c = PairField(spec), blocking_contour(spec, tol=tol, lines=[])
    left, right, sl, sr = END_EDGES
    for y in END_ROWS:
        xs = np.linspace(left + sl * (y - 1.76) - 2e-3, right + sr * (y - 1.76) + 2e-3, 61)
        _crosses_the_strip(spec, field, c, y, xs, tol)
    xs = np.linspace(-1.30, -1.22, 41)
    for y in (1.80, 1.81):
        assert max(_smallest(field, x, y) for x in xs) < 0, y
        assert not np.any([c.in_region(x, y) for x in xs]), y
