"""A roller just larger than the pitch curve's radius of curvature after an acceleration jump: the loop cut.

A harmonic return starts with a jump of the follower's acceleration to ``-h pi^2 / (2 beta^2)``, so the pitch
curve's radius of curvature drops there at once, here to just under the roller's (a translating cam, r0 16,
a harmonic rise of 8.6 mm over 30 degrees and return over 20). The envelope runs up to the jump and then back
along itself at a few thousandths of its speed: a swallowtail about 1e-4 mm long, shallower than the keep
test's slack over most of its length, so samples inside it were kept. The crossing that joins the kept arcs
was sought only from the closest pair of points about the cut's own samples: the slow stretch's points lay
within the fast one's spacing of it as far as twenty sample steps from the crossing, Newton ran off, and
the cam fuzz's valid cam raised GeometryError. The crossing is now taken from the resampled polylines'
crossing, from beyond the kept samples where the loop's are kept.

Oracle, none of it the product's envelope or sampler: the pitch curve's radius of curvature at the return's
start from the polar formula and the harmonic law's acceleration there (below the roller: a loop to cut), and
the roller's discs along the centre path written from the spec (:mod:`camoracle`): at tols from 1e-3 r0 down
to the roller's floor the outline lies inside no disc by more than its reported deviation, and the exact
kept pieces lie within it of the outline (:func:`fuzzkit.true_deviation`).
"""
import math

import numpy as np
import pytest
from camoracle import centres_for, check_swept_discs
from fuzzkit import true_deviation

from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

#: the fuzz run's cam: prime radius, roller radius (mm); lift (mm), rise, far dwell, return (degrees)
R0, ROLLER = 16.0, 1.6281985904579392
LIFT, RISE, DWELL, RETURN = 8.592201558232777, 30.0, 18.381623700053588, 20.0
#: the sweep's siblings that raised the same GeometryError: (roller, lift, return) factors of the cam's
SIBLINGS = [(0.999, 1.0, 1.0), (1.0003, 1.0, 1.0), (1.0, 0.997, 1.0), (1.0, 0.9997, 1.0), (1.0, 1.001, 1.0),
            (1.0, 1.0, 0.9997), (1.0, 1.0, 1.0003)]
CASES = [(1.0, 1.0, 1.0)] + SIBLINGS
#: the keep test's slack and the roller's finest tol, in (r0 + stroke), as the README states them
FLOOR = 2e-7
#: the bound is proven: the dense measure may exceed it by round-off only
BOUND_SLACK = 1e-9


def _spec(roller, lift, ret):
    return CamSpec(R0, MotionProgram.rise_dwell_return(LIFT * lift, RISE, DWELL, RETURN * ret, "harmonic"),
                   follower="translating", contact="roller", roller_radius=ROLLER * roller)


@pytest.mark.parametrize("factors", CASES)
def test_the_roller_is_larger_than_the_pitch_curve_after_the_jump(factors):
    roller, lift, ret = factors
    h, beta = LIFT * lift, math.radians(RETURN * ret)
    r, acc = R0 + h, -h * math.pi ** 2 / (2 * beta ** 2)  # s' = 0 at the return's start
    rho = r ** 3 / (r ** 2 - r * acc)  # polar: (r^2 + r'^2)^1.5 / (r^2 + 2 r'^2 - r r'')
    assert rho < ROLLER * roller < 1.01 * rho


@pytest.mark.parametrize("share", [1e-3, None])
@pytest.mark.parametrize("factors", CASES)
def test_the_outline_is_what_the_discs_leave(factors, share):
    spec = _spec(*factors)
    prof = cam_profile(spec)
    assert prof.loops  # the swallowtail is cut
    tol = share * R0 if share else (1 + 1e-9) * FLOOR * (spec.prime_radius + spec.stroke)
    out, achieved = prof.outline(tol), prof.achieved(tol)
    assert achieved <= tol
    check_swept_discs(spec, out, achieved, centres_for(spec, tol))
    real = true_deviation(prof.pieces, np.concatenate([out[::-1], out[-1:]]))
    assert real <= achieved * (1 + BOUND_SLACK)
