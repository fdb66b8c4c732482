"""A flat strip of the admissible region running to the window's frame: the grid's last cut across it, at a slant
to the strip, carried down the strip's middle to the frame (gearkit.blocking.flats.carry_down). Oracle: the check's
own scalar margins (``PairField.margin``, their zeros solved by brentq: the helpers of ``test_blocking_region``),
``check_pair`` and the window's edge.
"""
import dataclasses

import numpy as np
from scipy.optimize import brentq

from gearkit.blocking.arrays import evaluator
from gearkit.blocking.contour import default_window
from gearkit.blocking.field import PairField
from gearkit.blocking.flats import carry_down
from gearkit.blocking.tracing import GRID, REGION_REFINE
from gearkit.checks import check_pair
from gearkit.families.involute import ShaperCutter
from gearkit.pair import PairSpec
from test_blocking_region import CONTRACT, _smallest, _zeros

TOL = 1e-3


def test_a_flat_strips_cut_at_a_slant_is_carried_down_the_strip_to_the_frame():
    """43/100 internal (shaper z0 18): the strip where the tip sweep's margin is flat (about 0.012 across) runs down
    to the default window's lower edge x2 = -1 at a slant, and the grid's last cut across it runs from the strip's
    left edge on a row to its right edge on a column, about 14 degrees off square to the strip. Read along that
    cut's normal, the way left the strip through its left edge 0.015 above the frame, that zero was taken for the
    strip's end and the cut moved there: the outline closed across the strip short of the frame (6.2 tol off at
    tol 1e-3, 631 at 1e-5). Here that cut (its ends solved by brentq on the row and the column through the region
    grid's node in the strip) is carried down: the end found is on the frame, inside the strip (the check passes just above it),
    and the moved cut lies within a chord of the frame with its ends on the strip's edges, within 2 tol of the
    check's zeros (brentq) along its line, its middle passing check_pair."""
    spec = PairSpec(43, 100, 1.0, kind="internal", tool2=ShaperCutter(18))
    field = PairField(spec)
    win = default_window(field)
    assert win[2] == -1.0
    # the region's grid: the node in the strip on its third row (x2 = -0.9583), column 100 (x1 = 0.1756)
    hx, hy = ((win[1] - win[0]) / ((GRID - 1) * REGION_REFINE), (win[3] - win[2]) / ((GRID - 1) * REGION_REFINE))
    x0, y0 = win[0] + 100 * hx, win[2] + 2 * hy
    assert _smallest(field, x0, y0) > 0
    a = np.array([brentq(lambda x: _smallest(field, x, y0), x0 - hx, x0, xtol=1e-13), y0])
    b = np.array([x0, brentq(lambda y: _smallest(field, x0, y), y0 - hy, y0, xtol=1e-13)])
    assert _smallest(field, *(0.5 * (a + b))) > 0  # across the strip, the region on the cut's left
    F = evaluator(field, ["region"], win)
    ok, end, a2, b2 = carry_down(F, a[None], b[None], np.array([0]), TOL)
    assert ok[0]
    end, a2, b2 = end[0], a2[0], b2[0]
    assert abs(end[1] - win[2]) <= TOL, end  # the frame ends the strip, not one of its edges
    assert _smallest(field, end[0], win[2] + 2 * TOL) > 0, end
    cut = float(np.hypot(*(b2 - a2)))
    mid = 0.5 * (a2 + b2)
    assert 0 < mid[1] - win[2] <= cut, (a2, b2)
    # the moved cut's ends: the check's two zeros on its line, half a cut beyond each end
    p, q = a2 - 0.5 * (b2 - a2), b2 + 0.5 * (b2 - a2)
    exact = _zeros(lambda s: _smallest(field, *(p + s * (q - p))), np.linspace(0.0, 1.0, 25)) * 2 * cut
    assert len(exact) == 2, exact
    got = np.array([0.5 * cut, 1.5 * cut])
    assert np.abs(got - exact).max() <= CONTRACT * TOL, (exact, got)
    assert check_pair(dataclasses.replace(spec, shift1=float(mid[0]), shift2=float(mid[1]))).ok, mid
