"""The admissible region beside a wedge of its outside, internal pairs at tol 1e-3, against the check's own
scalar margins (``PairField.margin``: the zeros of the smallest hard margin solved by brentq) and
``check_pair``: every crossing of the region's polygons on a row lies within 2 tol of a zero, every zero
has a crossing within 2 tol, and points on either side are in the region exactly where the check passes.
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

