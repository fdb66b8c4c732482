"""A roller cam's turned-back envelope is judged sample by sample against the roller centre's own motion.

The keep test cuts an envelope sample that runs back along the roller's tangent. Read against the first
sample's direction, it cut everything where the start angle's own sample was turned back (a roller 0.71
times the prime radius on a constant-velocity rise: no envelope point was left); judged against the
pitch curve's step at the same cam angle, each sample stands alone. A concave corner (a velocity jump
that turns the roller by 1.4e-3 rad) is cut whole, its arc 3e-6 mm inside the rollers either side, and
the envelopes before and after it meet beside the arc's ends, a fraction of a sample step away.

Oracle: the roller's discs about the exact pitch curve (closed form, no envelope and no sampler), as in
:mod:`test_cam_shallow_loops`: every outline vertex outside each disc to within the reported deviation
plus the centres' chord sagitta, the deviation measured independently within its bound, the bound
within the tolerance.
"""
import pytest
from test_cam_shallow_loops import _assert_outside_every_roller

from gearkit.families.cam import CamSpec, MotionProgram

#: the fuzz search's translating cam: a roller 0.71 r0 about a corner at the start angle
TRANSLATING = dict(prime_radius=84.11975542276507, roller_radius=60.13534410330576, offset=-1.992655965884543e-12)
TRANSLATING_MOTION = (1.6823951084553013, 23.106310833796368, 0.0, 96.65579693902146, "constant_velocity")
#: the fuzz search's rocker: a swing of 182 degrees over 29; the rise's end a concave corner cut whole
ROCKER = dict(prime_radius=72.27068359804167, follower="rocker", roller_radius=9.350448421424751,
              pivot_distance=86.72482031765, arm_length=80.96078708209076)
ROCKER_MOTION = (182.32162140121568, 29.253329781035745, 17.840159764479537, 29.253329781035745, "constant_velocity")
#: the roller a millionth larger and smaller
NEAR = [1.0, 1.0 - 1e-6, 1.0 + 1e-6]


def _check(kw, motion):
    spec = CamSpec(motion=MotionProgram.rise_dwell_return(*motion), contact="roller", **kw)
    return _assert_outside_every_roller(spec, 1e-4 * kw["prime_radius"])


@pytest.mark.parametrize("factor", NEAR)
def test_translating_start_sample_turned_back(factor):
    _check(dict(TRANSLATING, roller_radius=TRANSLATING["roller_radius"] * factor), TRANSLATING_MOTION)


@pytest.mark.parametrize("offset", [0.0, 1e-12, -1e-12])
def test_translating_start_sample_turned_back_offsets(offset):
    _check(dict(TRANSLATING, offset=offset), TRANSLATING_MOTION)


@pytest.mark.parametrize("factor", NEAR)
def test_rocker_concave_corner_cut_whole(factor):
    prof = _check(dict(ROCKER, roller_radius=ROCKER["roller_radius"] * factor), ROCKER_MOTION)
    assert prof.loops
