"""Flat rockers with constant-velocity laws lifting 1e-5 to 1e-3 of r0, with and without near-zero dwells.

At each velocity jump the face slides back along its line (by 8e-4 mm for a 1e-3 mm lift on a 34 mm cam), and
with a 0.001-degree dwell between rise and return both slides and the dwell's arc lie within a sixth of a
line step (of the product's 65 536 half-planes) of the jumps. They fold up to 7e-9 mm outside the cam: inside
the polygon of those half-planes, which stands up to 1e-8 mm out of the cam between its lines, so every sample
there read as on the cam and the fold was kept (a vertex 4.7e-9 mm outside the cam at every tol, the outline
turning back by 3.9e-7 mm at 1e-6 r0). The product's polygon now holds the lines 64 times as densely within
four steps of each jump. With the lift doubled and no dwell, the rise's end, the slide and the return's start
lie within one sample step about w = 0, and the join's crossing was not found apart from the curve itself
(GeometryError on a valid cam): such a join is now resolved on a denser sampling.

Oracles, none of them the product's envelope or trimming code: the face's lines written out from the frames of
:class:`CamSpec` (``fuzzkit.face_half_planes``), every 16th of 65 536 over the turn and 100 per step within six
steps of each velocity jump (``fuzzkit.check_flat_cam``: the outline inside every one, convex, enclosing the
area of their polygon), and scipy's convex hull of the outline (every vertex on it within round-off).
"""
import pytest
from fuzzkit import check_flat_outline

from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

#: the oracle's lines over one turn
LINES = 1 << 16

KW = dict(prime_radius=33.74364281538762, follower="rocker", contact="flat", pivot_distance=53.92711523503109,
          arm_length=33.69906779285558)
#: lift (mm), rise, far dwell, return (degrees)
LIFT, RISE, DWELL, RETURN = 0.0010490016280162427, 112.41384754121708, 0.001, 128.97084805539316

CASES = [((LIFT, RISE, DWELL, RETURN), t) for t in (1e-3, 1e-4, 1e-5, 1e-6)] + [
    ((LIFT * f, RISE, d, RETURN), 1e-6) for f, d in
    [(0.5, 0.0), (0.5, 1e-6), (0.5, 1e-3), (0.1, 0.0), (0.1, 1e-3)]] + [
    ((LIFT * 2.0, RISE, d, RETURN), t) for d in (0.0, 1e-6) for t in (1e-4, 1e-6)]
#: a sibling from a sweep of tiny-lift flat rockers: lift 2.6e-5 r0 over a 20-degree rise, a 0.001-degree dwell
#: and a 40-degree return, its join about w = 0 a sample wide (the same GeometryError)
SIBLING = (dict(prime_radius=128.68646530871325, follower="rocker", contact="flat",
                pivot_distance=168.84257221755308, arm_length=95.79243080043248),
           (0.0033655747671202615, 20.030326647176363, 0.001, 39.66444119632563))


@pytest.mark.parametrize("kw, motion, tol_r0", [(KW, m, t) for m, t in CASES] + [(*SIBLING, t) for t in (1e-3, 1e-5)])
def test_a_tiny_lifts_folds_at_its_jumps_are_cut(kw, motion, tol_r0):
    spec = CamSpec(motion=MotionProgram.rise_dwell_return(*motion, "constant_velocity"), **kw)
    prof = cam_profile(spec)
    tol = tol_r0 * spec.prime_radius
    check_flat_outline(prof, tol, LINES)
