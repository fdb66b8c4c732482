"""A part of the admissible region beyond a saddle's neck that no grid node sees: the outline walked round it
(:mod:`gearkit.blocking.walk`). Oracles: the check's own scalar margins (``PairField.margin``, their zeros along rows
and columns solved by brentq) and ``check_pair`` (the row helpers of ``test_blocking_region``); for the walk itself,
an analytic neck and pocket whose corners are known in closed form.
"""
import numpy as np

from gearkit.blocking import blocking_contour
from gearkit.blocking.field import PairField
from gearkit.blocking.walk import walk
from gearkit.pair import PairSpec
from test_blocking_region import _crosses_the_strip

TOL = 1e-5
POCKET_ROWS = (1.0005, 1.001, 1.002, 1.003, 1.004)  #: rows x2 = const through 29/37's pocket ...
POCKET_LEFT = (-1.000837, -0.2453)  #: ... its left edge (interference.1) x1 = a + b (x2 - 1)
POCKET_RIGHT = (-0.999998, -0.3987)  #: ... its right edge (the upper wedge of interference.2)
NECK_SIDE = 2e-4  #: the column x1 = -1 through the neck, this far each side of x2 = 1


def test_a_pocket_beyond_a_saddles_neck_is_in_the_region():
    """29/37 external at tol 1e-5: interference.2's saddle at (-1, 1) leaves a neck 1e-4 wide between its two
    negative wedges, through which the region goes on into a pocket left of it, 6e-4 wide and 5e-3 long, bounded by
    the wedges' far sides and interference.1's line, that no grid node sees. The grid closed the outline across the
    neck (6.6 tol off) and the pocket was left out of the region. On rows through the pocket and the column through
    the neck, every crossing of the polygons lies within 2 tol of a zero of the check's smallest hard margin (brentq)
    and every zero has one; the middle passes check_pair and is in the region."""
    spec = PairSpec(29, 37, 1.0)
    field, c = PairField(spec), blocking_contour(spec, tol=TOL, lines=[])
    for y in POCKET_ROWS:
        left = POCKET_LEFT[0] + POCKET_LEFT[1] * (y - 1.0)
        right = POCKET_RIGHT[0] + POCKET_RIGHT[1] * (y - 1.0)
        _crosses_the_strip(spec, field, c, y, np.linspace(left - 1e-4, right + 1e-4, 61), TOL)
    _crosses_the_strip(spec, field, c, -1.0, np.linspace(1.0 - NECK_SIDE, 1.0 + NECK_SIDE, 61), TOL, column=True)


def _neck_and_pocket(p, k):
    """Part 0: a saddle x2**2 - x1**2 + 0.01 (negative in two wedges, above and below, with a neck 0.2 wide at the
    origin; positive left and right); part 1: x1 + 1 (the region's left side, the line x1 = -1)."""
    k = np.asarray(k)
    return np.where(k == 0, 0.01 + p[:, 0] ** 2 - p[:, 1] ** 2, p[:, 0] + 1.0)


_neck_and_pocket.size, _neck_and_pocket.costly = 2, []
_neck_and_pocket.many = lambda p: np.vstack([_neck_and_pocket(p, np.zeros(len(p), int)),
                                             _neck_and_pocket(p, np.ones(len(p), int))])


def test_the_walk_goes_through_the_neck_round_the_pocket_to_the_chords_end():
    """From the upper wedge's lower side at (0.5, sqrt(0.26)), the region on the left, to the lower wedge's upper
    side at (0.5, -sqrt(0.26)): the walk goes left through the neck, along the upper branch to its corner with
    x1 = -1 at (-1, sqrt(1.01)), down that line to (-1, -sqrt(1.01)), and back along the lower branch; every vertex on
    the region's edge (each part >= 0 to round-off, one of them zero), both corners vertices, and the path never
    crosses the chord between its ends (the pocket is taken in, not cut)."""
    r = np.sqrt(0.26)
    a, b = np.array([0.5, r]), np.array([0.5, -r])
    got = walk(_neck_and_pocket, a, b, 0, 1e-6, 20.0)
    assert got is not None
    path, parts = got
    assert np.array_equal(path[0], a) and np.array_equal(path[-1], b)
    assert parts[0] == 0 and parts[-1] == 0 and np.count_nonzero(np.diff(parts)) == 2  # part 0, then 1, then 0
    corners = path[1:-1][np.diff(parts) != 0]
    assert np.allclose(corners, [[-1.0, np.sqrt(1.01)], [-1.0, -np.sqrt(1.01)]], atol=1e-6)
    v = _neck_and_pocket.many(path)
    assert np.all(v >= -1e-6) and np.all(np.min(np.abs(v), axis=0) <= 1e-6)
    assert np.min(path[:, 0]) >= -1.0 - 1e-6 and np.max(path[1:-1, 0]) < 0.5
