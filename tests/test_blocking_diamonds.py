"""A flat strip of the admissible region narrower than a grid cell, traced through the grid's chain of diamonds
(one loop about each node inside it): each link's cut across the strip must stay a cut, to be re-joined with the
next link's, and the strip's last cut must be carried on to its end. Oracle: the check's own scalar margins
(``PairField.margin``, their zeros along rows solved by brentq) and ``check_pair`` (the row helpers of
``test_blocking_region``).
"""
import functools

import numpy as np
import pytest

from gearkit.blocking import blocking_contour
from gearkit.blocking.field import PairField
from gearkit.families.involute import ShaperCutter
from gearkit.pair import PairSpec
from test_blocking_region import _row_crosses_the_strip

TOL = 1e-5
SIDE = 4e-3  #: each row is sampled this far beyond the strip's edges (short of every other zero)


@functools.lru_cache(maxsize=None)
def _internal(z1, z2, z0):
    spec = PairSpec(z1, z2, 1.0, kind="internal", tool2=ShaperCutter(z0))
    return spec, PairField(spec), blocking_contour(spec, tol=TOL, lines=[])


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
    spec, field, c = _internal(*key)
    (xl, sl, yl), (xr, sr, yr), rows = STRIPS[key]
    for y in rows:
        xs = np.linspace(xl + sl * (y - yl) - SIDE, xr + sr * (y - yr) + SIDE, 61)
        _row_crosses_the_strip(spec, field, c, y, xs, TOL)
