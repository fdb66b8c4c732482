"""A roller cam's loop shallower than the swept region's sampling error is cut all the same.

The keep test measures an envelope point's depth in the swept region against the chords of a sampled
pitch curve, which read a point on the boundary up to their sagitta deep; a loop (swallowtail) less deep
than that slack was kept whole, and the outline ran inside the roller while its reported deviation,
a bound against the kept pieces, was met. Oracle: the roller's discs about the pitch curve written out
in closed form (:func:`test_cam_bounds.pitch_curve`, no envelope and no sampler), 2^20 of them over a
turn; every outline vertex must lie outside each disc to within the reported deviation, plus the
sagitta of the centres' polyline (its chords lie within that of the exact path, so a vertex's distance
to them reads at most that much low).
"""
import math

import numpy as np
import pytest
from fuzzkit import true_deviation
from test_cam_bounds import BOUND_SLACK, pitch_curve

from gearkit.distances import edge_distances
from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

#: exact roller centres over a turn for the discs' check
CENTRES = 1 << 20


def _assert_outside_every_roller(spec, tol):
    prof = cam_profile(spec)
    out, achieved = prof.outline(tol), prof.achieved(tol)
    centres = pitch_curve(spec, np.linspace(0.0, 2 * math.pi, CENTRES, endpoint=False))
    # a chord's sagitta is h^2 |c''| / 8 with h |c''| the change of its step: a quarter of the largest
    # second difference bounds it twice over
    second = np.roll(centres, -1, axis=0) - 2 * centres + np.roll(centres, 1, axis=0)
    sagitta = float(np.hypot(*second.T).max()) / 4
    depth = spec.roller_radius - edge_distances(out, centres, closed=True)
    assert depth.max() <= achieved + sagitta, (depth.max(), achieved, sagitta)
    real = true_deviation(prof.pieces, np.concatenate([out[::-1], out[-1:]]))
    assert real <= achieved * (1 + BOUND_SLACK) and achieved <= tol
    return prof


#: the fuzz search's rocker (r0 5, pivot 6, arm 8, a harmonic rise of 2.5 mm over 20 degrees): the roller
#: 1.001 times the pitch curve's least convex radius of curvature (0.25201611 mm) left a swallowtail
#: 3.8e-7 mm deep, under the old slack of 1e-7 (r0 + stroke) = 7.5e-7 mm; outline 3.8e-7 mm inside the
#: roller at tol 1.5e-8, reported 1.43e-8. Also a third and three times as far past it
ROCKER_ROLLERS = [1.001, 1.0003, 1.003]


@pytest.mark.parametrize("factor", ROCKER_ROLLERS)
def test_rocker_loop_shallower_than_the_slack_is_cut(factor):
    spec = CamSpec(5.0, MotionProgram.rise_dwell_return(2.5, 20.0, 20.0, 20.0, "harmonic"), follower="rocker",
                   contact="roller", roller_radius=0.25201611 * factor, pivot_distance=6.0, arm_length=8.0)
    assert len(_assert_outside_every_roller(spec, 1.5e-8).loops) == 1


#: a translating cycloidal cam (r0 40, rise 20 over 60 degrees, return over 90): the roller 3 um past the
#: pitch curve's least convex radius of curvature (21.2103675176 mm) left a loop 6e-7 mm deep under the old
#: slack of 6e-6 mm; outline 6e-7 mm inside the roller at tol 1.2e-7. Also 1 um and 10 um past it
TRANSLATING_EXCESS = [3e-3, 1e-3, 1e-2]


@pytest.mark.parametrize("excess", TRANSLATING_EXCESS)
def test_translating_loop_shallower_than_the_slack_is_cut(excess):
    spec = CamSpec(40.0, MotionProgram.rise_dwell_return(20.0, 60.0, 30.0, 90.0, "cycloidal"),
                   roller_radius=21.2103675176 + excess)
    prof = _assert_outside_every_roller(spec, 1.2e-7)
    assert prof.undercut
