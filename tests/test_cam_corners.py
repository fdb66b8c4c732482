"""A large roller turning about a velocity jump's corner: the cam against the swept roller disc.

Where a constant-velocity law's velocity jumps, the roller's centre path (the pitch curve) has a corner
and the roller turns about it; with a roller nearly as large as the pitch curve's radius of curvature
past the corner, the envelope there first runs inside the corner's roller circle (a swallowtail a few
micrometres deep, inside the keep test's slack in part) and then out across it, some twenty samples of
the keep test past the corner. Oracle, none of it the product's envelope: the roller centre written
out on its arm about the pivot from the spec alone (a rocker's centre ``O2 + l (-cos Psi, sin Psi)``,
``Psi = Psi0 + s / l``, the cam turned counter-clockwise by ``phi``), densely, with every phase end
among the angles (the corners exact). The cam is what the roller disc swept along it leaves: every
outline vertex (an exact point of the cam) a roller radius from the centre path — on every roller's
circle or outside it, and touching one — and every chord of the outline outside the swept discs by
at most the tolerance.
"""
import math

import numpy as np
import pytest

from gearkit.distances import distances_to_polyline
from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

#: the reproducers' rocker: prime radius, roller radius, pivot distance, arm length (mm); lift (mm), rise (deg)
R0, ROLLER, PIVOT, ARM = 60.0, 39.4795408849898, 150.0, 114.00944307538478
LIFT, RISE = 90.0, 99.940485620097
#: roller centres over a turn (plus the phase ends): chords of at most 2 pi (PIVOT + ARM) / 2^18 = 6.3e-3 mm
CENTRES = 1 << 18
#: how far the dense centre path's chords may stand off the exact path near a kept cam point: the
#: nearest centre of a point the swept disc leaves uncovered is where the path's radius of curvature is
#: at least the roller's (else the neighbouring discs cover it), so the sag is at most L^2 / (8 R) with L
#: the longest chord (1.3e-7 mm), doubled for the round-off of lengths up to the pivot (1e-13 mm)
SAG = 2 * (2 * math.pi * (PIVOT + ARM) / CENTRES) ** 2 / (8 * ROLLER)


def _spec(dwell, ret, arm=ARM, roller=ROLLER):
    motion = MotionProgram.rise_dwell_return(LIFT, RISE, dwell, ret, "constant_velocity")
    return CamSpec(R0, motion, follower="rocker", contact="roller", roller_radius=roller, pivot_distance=PIVOT,
                   arm_length=arm)


def _centre_path(spec):
    """The roller centre in the cam frame over one turn, from the spec's frames alone."""
    ends = np.array([ph[2] for ph in spec.motion.phases()])
    phi = np.unique(np.concatenate([np.linspace(0.0, 2 * np.pi, CENTRES), ends % (2 * np.pi)]))
    s = spec.motion.evaluate(phi)[0]
    l0, arm = spec.pivot_distance, spec.arm_length
    psi = math.acos((l0 * l0 + arm * arm - spec.prime_radius ** 2) / (2 * l0 * arm)) + s / arm
    x, y = l0 - arm * np.cos(psi), arm * np.sin(psi)
    c, sn = np.cos(-phi), np.sin(-phi)
    return np.stack([c * x - sn * y, sn * x + c * y], -1)


def _check_against_swept_discs(spec, tol):
    prof = cam_profile(spec)
    out, achieved = prof.outline(tol), prof.achieved(tol)
    assert achieved <= tol
    path = _centre_path(spec)
    r = spec.roller_radius
    vertex = distances_to_polyline(out, path, closed=True)
    # every vertex on the cam: on a roller's circle (touching the envelope) and inside none
    assert np.abs(vertex - r).max() <= SAG
    closed = np.concatenate([out, out[:1]])
    mids = distances_to_polyline(0.5 * (closed[1:] + closed[:-1]), path, closed=True)
    assert mids.min() >= r - achieved * (1 + 1e-9) - SAG
    return prof


@pytest.mark.parametrize("dwell", [3.7e-20, 0.0, 1e-10, 1.0])
@pytest.mark.parametrize("ret", [31.5, 60.0])
def test_large_roller_at_a_velocity_jump_leaves_the_cam_where_the_envelope_crosses_its_arc(dwell, ret):
    # the long fuzz run's reproducers (GeometryError: the envelope leaves the cam where it meets no
    # other kept arc), and the 0 deg dwell with a 31.5 deg return, which built with a cut 1.3e-4 mm
    # short of a crossing (its far end a point 4e-5 mm inside the swept discs)
    _check_against_swept_discs(_spec(dwell, ret), 1e-5 * (R0 + LIFT))


@pytest.mark.parametrize("arm, roller", [(ARM + 1e-6, ROLLER), (ARM - 1e-6, ROLLER), (ARM, ROLLER + 1e-6),
                                         (ARM, ROLLER - 1e-6)])
@pytest.mark.parametrize("dwell, ret", [(3.7e-20, 31.5), (0.0, 60.0), (1.0, 45.0), (1e-10, 90.0)])
def test_neighbours_of_the_reproducers_build_the_swept_cam(arm, roller, dwell, ret):
    _check_against_swept_discs(_spec(dwell, ret, arm, roller), 1e-4 * R0)


def test_a_vanishing_dwell_is_one_jump():
    # a dwell of 3.7e-20 deg moves the cam angle by nothing: the rise's velocity jumps straight to the
    # return's, one corner the roller turns about, as with no dwell at all
    prof = cam_profile(_spec(3.7e-20, 60.0))
    none = cam_profile(_spec(0.0, 60.0))
    corners = [sec[1] for sec in prof.branch.sections if sec[0] == "corner"]
    assert len(corners) == len(set(corners)) == 3
    out, ref = prof.outline(1e-3), none.outline(1e-3)
    assert distances_to_polyline(out, ref, closed=True).max() <= 2e-3


@pytest.mark.parametrize("dwell", [1e-10, 1e-7, 3.7e-20, 1.0])
def test_the_envelope_is_continuous_across_every_corner(dwell):
    # a dwell shorter than the 1e-9 rad the pole before a jump was read at: the second corner's arc
    # started from the rise's pole, not the dwell's, and the envelope jumped 11 mm back at its start.
    # The roller's contact is continuous in the cam angle and along each corner's arc, so both sides of
    # every section's end are one point (to the round-off of lengths up to the pivot)
    prof = cam_profile(_spec(dwell, 60.0))
    edges = prof.branch.edges[1:-1]
    left = prof.branch(np.nextafter(edges, -np.inf))
    right = prof.branch(edges)
    assert np.hypot(*(left - right).T).max() <= 1e-12 * (PIVOT + ARM)
