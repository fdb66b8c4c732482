"""A flat rocker whose constant-velocity return is so steep that the face turns back relative to the cam
(``1 + psi' = -0.03``): the return's, the far dwell's and the rise's last lines all lie outside the cam, and the
cam runs straight from the rise's kept arc to the near dwell's along the face line of the return's end (the
velocity jump there). No self-crossing of the envelope joins the two arcs, and Newton's ends, sought for one,
settled 0.67 mm off that line, past the 1e-2 (r0 + stroke) the line was sought within: the 10 000-spec cam
fuzz's GeometryError ("a kept arc of the flat face's envelope meets the next one neither at a crossing nor along
a corner's face line") on a valid cam. The line is read off the kept arcs' own ends now. That rocker at three
tolerances, and its neighbours (far dwell 0, 1e-6, 0.5 and 3 degrees; lift 1e-6 and 10 % either way), and a sibling.

Oracles, none of them the product's envelope or trimming code: the face's lines written out from the frames of
:class:`CamSpec` (``fuzzkit.face_half_planes``) and scipy's intersection of 65 536 of their half-planes
(``fuzzkit.check_flat_cam``: the outline inside every one, convex, enclosing their polygon's area), every point
of the exact pieces inside them, and the straight stretch on the face line at the return's end.
"""
import math

import numpy as np
import pytest
from fuzzkit import check_flat_cam, face_half_planes, true_deviation

from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

#: the bound is proven: the dense measure may exceed it by round-off only
BOUND_SLACK = 1e-9
#: the oracle's lines over one turn
LINES = 1 << 16
#: points of the exact pieces checked per piece
DENSE = 4001
#: a point of the cam stands outside a half-plane by round-off only, of the lengths up to the pivot
INSIDE = 1e-12

KW = dict(prime_radius=38.907650314666384, follower="rocker", contact="flat", pivot_distance=111.11527478689848,
          arm_length=64.81656876162084)
#: lift (mm), rise, far dwell, return (degrees)
LIFT, RISE, DWELL, RETURN = 23.34459018879983, 109.58766694459987, 1.5, 20.000000000000004

CASES = [(KW, (LIFT, RISE, DWELL, RETURN), t) for t in (1e-3, 1e-4, 1e-5)] + [
    (KW, (LIFT, RISE, d, RETURN), 1e-4) for d in (0.0, 1e-6, 0.5, 3.0)] + [
    (KW, (LIFT * f, RISE, DWELL, RETURN), 1e-4) for f in (1 - 1e-6, 1 + 1e-6, 0.9, 1.1)] + [
    # a sibling from a sweep of 100 flat rockers with 20-40 degree returns: no dwell, return psi' = -1.01
    (dict(KW, prime_radius=165.08155009224944, pivot_distance=348.76621918583555, arm_length=436.9144173166428),
     (168.07913719572693, 126.96351171061875, 0.0, 21.839922630556142), 1e-4)]


@pytest.mark.parametrize("kw, motion, tol_r0", CASES)
def test_steep_return_is_bridged_along_its_end_face_line(kw, motion, tol_r0):
    spec = CamSpec(motion=MotionProgram.rise_dwell_return(*motion, "constant_velocity"), **kw)
    prof = cam_profile(spec)
    tol = tol_r0 * spec.prime_radius
    out, achieved = prof.outline(tol), prof.achieved(tol)
    closed = np.concatenate([out[::-1], out[-1:]])  # the pieces' own order
    assert achieved <= tol and true_deviation(prof.pieces, closed) <= achieved * (1 + BOUND_SLACK)
    check_flat_cam(spec, out, tol, LINES)
    reach = spec.prime_radius + spec.stroke + spec.pivot_distance + spec.arm_length
    n, h = face_half_planes(spec, np.linspace(0.0, 2 * math.pi, LINES // 16, endpoint=False))
    dense = np.concatenate([pc(np.linspace(0.0, 1.0, DENSE)) for pc in prof.pieces])
    assert max(float((dense[k:k + 4096] @ n.T - h).max()) for k in range(0, len(dense), 4096)) <= INSIDE * reach
    # the outline's longest edge (closed: the straight stretch) lies on the face line at the return's end
    end = spec.motion.phases()[-2][2]
    n, h = face_half_planes(spec, np.array([end]))
    ring = np.concatenate([out, out[:1]])
    k = int(np.argmax(np.hypot(*np.diff(ring, axis=0).T)))
    assert np.abs(ring[k:k + 2] @ n[0] - h[0]).max() <= INSIDE * reach
