"""Flat followers whose face, at a velocity jump of a constant-velocity law, slides back along its own line.

At a jump the face slides along its line from where the arc before the jump touches it to where the arc after it
does. A slide forward (the way the boundary runs) is a straight stretch of the cam; a slide back leaves the two
arcs overlapping along the line, each bending inside it from its own end, and they cross about the slide's
middle, ``slide^2 / (8 r)`` inside the line. For a rocker lifting 1e-5 r0 over a 20-degree rise with a
1.36-degree dwell (the 10 000-spec cam fuzz's spec) the slide is 3.9e-5 mm on a 21 mm cam: its neighbours' lines
cut it by some 4e-11 mm, below the keep test's slack, so every sample there was kept and the outline walked
forward to the jump, back along the slide and forward again ("the outline turns back by 5.18e-07 mm: not a
convex cam" at tol 1e-4 r0, its tangent's winding 0). Such a slide is now cut out at the crossing of the arcs
either side of it: each arc cut where it passes the slide's middle along the line, then Newton from there where
the arcs' angle stands above their round-off. A fold just deeper than the slack is cut the same way before the
middles of the sections on kept arcs are checked (the corner's middle read as off the cam at every sampling). The spec from 1e-3 r0 down to the floor 1e-9 (r0 + stroke), and siblings from a sweep about
it (lift 1e-6 to 1e-3 r0, dwell 0 to 10 degrees, rise 20 and 60 degrees, two pivots, rocker and translating
faces): each failed before.

Oracles, none of them the product's envelope or trimming code: the face's lines written out from the frames of
:class:`CamSpec` (``fuzzkit.face_half_planes``), every 16th of 65 536 over the turn and 100 per step within six
steps of each velocity jump, and scipy's intersection of all 65 536 (``fuzzkit.check_flat_cam``: the outline
inside every one, turning one way once round, enclosing their polygon's area), the reported deviation within
tol, and scipy's convex hull of the outline (every vertex on it within round-off; ``fuzzkit.check_flat_outline``).
"""
import pytest
from fuzzkit import check_flat_outline

from gearkit.accuracy import PRECISION
from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

#: the oracle's lines over one turn
LINES = 1 << 16

R0, PIVOT, ARM = 21.428075269039287, 25.713690322847143, 34.985282362769
ROCKER = dict(prime_radius=R0, follower="rocker", contact="flat", pivot_distance=PIVOT, arm_length=ARM)
#: lift (mm), rise, far dwell, return (degrees): the fuzz's spec
FUZZ = (0.00021428075269039288, 20.0, 1.3605702613476625, 127.95687556946545)
#: the other pivot of the sweep
OTHER = dict(ROCKER, pivot_distance=1.5 * PIVOT, arm_length=0.7 * ARM)
TRANSLATING = dict(prime_radius=R0, follower="translating", contact="flat")

CASES = [(ROCKER, FUZZ, t) for t in (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, None)] + [
    # siblings: (follower, (lift, rise, dwell, return), tol in r0; None: the floor)
    (ROCKER, (1e-6 * R0, 20.0, 0.0, FUZZ[3]), 1e-4),
    (ROCKER, (1e-6 * R0, 60.0, 0.0, FUZZ[3]), None),
    (OTHER, (1e-6 * R0, 60.0, 0.0, FUZZ[3]), 1e-6),
    (OTHER, (1e-6 * R0, 20.0, 1e-3, FUZZ[3]), 1e-4),
    (ROCKER, (1e-6 * R0, 60.0, 10.0, FUZZ[3]), 1e-6),
    (TRANSLATING, (1e-6 * R0, 60.0, 0.0, FUZZ[3]), 1e-4),
    (TRANSLATING, (1e-6 * R0, 20.0, 10.0, FUZZ[3]), 1e-6),
    # the fold's depth just over the keep slack: the dwell's corner's middle read as off the cam at every sampling
    # (GeometryError: a kept arc narrower than 1/1048576 of a turn not resolved)
    (TRANSLATING, (1e-6 * R0, 60.0, 1e-3, FUZZ[3]), 1e-4),
    (TRANSLATING, (1e-6 * R0, 60.0, 1e-3, FUZZ[3]), None),
    # a slide of 2e-6 mm: Newton alone on the arcs 1e-7 rad apart wandered to its bounds (GeometryError)
    (ROCKER, (5e-7 * R0, 60.0, 1e-3, FUZZ[3]), 1e-4),
    (ROCKER, (5e-7 * R0, 60.0, 1e-3, FUZZ[3]), 1e-6),
]


@pytest.mark.parametrize("kw, motion, tol_r0", CASES)
def test_a_slide_back_along_the_face_at_a_jump_is_cut(kw, motion, tol_r0):
    spec = CamSpec(motion=MotionProgram.rise_dwell_return(*motion, "constant_velocity"), **kw)
    prof = cam_profile(spec)
    tol = tol_r0 * spec.prime_radius if tol_r0 is not None else PRECISION * (spec.prime_radius + spec.stroke)
    check_flat_outline(prof, tol, LINES)
