"""A flat rocker whose far dwell lasts 2e-12 degrees: the dwell's arc, 4.4e-13 mm long, is an edge of the outline
a round-off or two long (just past the 1e-14 of the pivot's lengths within which a vertex is merged with the one
before it). The 10 000-spec cam fuzz read "the outline turns back by 5.92e-06 mm" at tol 1e-6 r0: the old
convexity measure took the next vertex's distance from the line of that edge, whose direction is round-off, so
the next edge's far end 0.025 mm on stood 6e-6 mm behind it. The vertex itself lies 1e-16 mm from the chord of
its neighbours and on the outline's convex hull: the outline was convex, the measure was not well conditioned.
The check now measures each vertex against its neighbours' chord (``fuzzkit.convex_dents``) and counts the
tangent's turns round.

Oracles, none of them the product's envelope or trimming code: scipy's intersection of 65 536 of the face's
half-planes written out from the frames of :class:`CamSpec` (``fuzzkit.check_flat_cam``), and scipy's convex
hull of the outline (every vertex on it within round-off). The spec at three tolerances and its neighbours
(far dwell 0, 1e-12 and 1e-6 degrees; lift halved and doubled); the measure itself on polygons built by hand.
"""
import math

import numpy as np
import pytest
from fuzzkit import check_flat_outline, convex_dents

from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

#: the oracle's lines over one turn
LINES = 1 << 16

KW = dict(prime_radius=12.207099220943714, follower="rocker", contact="flat", pivot_distance=18.18268786695413,
          arm_length=9.946368939824433)
#: lift (mm), rise, far dwell, return (degrees)
LIFT, RISE, DWELL, RETURN = 0.2441419844188743, 31.5, 2e-12, 28.944675221912917

CASES = [((LIFT, RISE, DWELL, RETURN), t) for t in (1e-4, 1e-5, 1e-6)] + [
    ((LIFT, RISE, d, RETURN), 1e-6) for d in (0.0, 1e-12, 1e-6)] + [
    ((LIFT * f, RISE, DWELL, RETURN), 1e-6) for f in (0.5, 2.0)]


@pytest.mark.parametrize("motion, tol_r0", CASES)
def test_dwell_of_a_round_off_is_a_convex_outline(motion, tol_r0):
    spec = CamSpec(motion=MotionProgram.rise_dwell_return(*motion, "harmonic"), **KW)
    prof = cam_profile(spec)
    tol = tol_r0 * spec.prime_radius
    check_flat_outline(prof, tol, LINES)


def _circle(n=360, radius=10.0):
    t = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    return radius * np.column_stack([np.cos(t), np.sin(t)])


def test_an_edge_of_a_round_off_is_no_turn_back():
    """A vertex doubled a few ulps off along a circle (its edge points anywhere) leaves every vertex on the
    hull: the measure reads round-off, not the next edge's length times the edge's direction error."""
    ring = _circle()
    twin = ring[10] + np.array([-3e-13, 3e-13])  # beside, not along: the short edge's line is off by 45 degrees
    ring = np.insert(ring, 11, twin, axis=0)
    dent, winding = convex_dents(ring)
    assert winding == 1 and dent.min() >= -1e-12


def test_a_dent_a_spike_and_a_second_turn_are_not_convex():
    """A vertex moved inward by 1e-9 mm past its neighbours' chord reads that depth; a spike out of the circle
    and back leaves its base vertices behind their chords to its tip (by the 0.17 mm of the circle's sides
    they turn from, at least a tenth of a millimetre); a circle walked twice turns every vertex the right way
    but its tangent twice round."""
    ring = _circle()
    chord = 0.5 * (ring[9] + ring[11])
    dented = ring.copy()
    dented[10] = chord * (1 - 1e-9 / np.hypot(*chord))
    dent, winding = convex_dents(dented)
    assert dent.min() == pytest.approx(-1e-9, rel=1e-3) and winding == 1
    spike = np.insert(ring, 11, [ring[10] * 2.0, ring[10] * (1 + 1e-9)], axis=0)
    assert convex_dents(spike)[0].min() < -0.1
    dent, winding = convex_dents(np.concatenate([ring, ring]))
    assert dent.min() > 0.0 and winding == 2


#: constant-velocity rockers with lifts of 1e-4 mm or so (a sweep's siblings): the face's slides along its line at
#: the velocity jumps about cam angle 0 (and at a 1e-6 or 1e-8 degree dwell) are a sixth of a sample step wide and
#: fold, 1e-9 to 4e-8 mm outside the cam and back, with every sample kept: the fold went uncut
FOLDS = [((6.539762333839532, 17.101923666922126, 10.090473573201985),
          (0.0003218040992005135, 133.58248336930353, 1e-08, 118.61727099439513)),
         ((4.606682903032246, 6.92407573594996, 2.3071582688722496),
          (8.836816373038924e-05, 53.45090782943877, 0.0, 141.50038049893953)),
         ((5.740909064592631, 10.246838403621304, 8.955572128872431),
          (0.00013080969039075388, 72.70631367466137, 0.001, 101.28147483177388)),
         ((21.542151308638108, 62.97568469725222, 49.42689327718606),
          (0.0002703735246265625, 75.85242799527698, 1e-06, 16.045263866279704))]


@pytest.mark.parametrize("tol_r0", [1e-4, 1e-6])
@pytest.mark.parametrize("sizes, motion", FOLDS)
def test_a_fold_narrower_than_a_sample_step_is_cut(sizes, motion, tol_r0):
    r0, pivot, arm = sizes
    spec = CamSpec(motion=MotionProgram.rise_dwell_return(*motion, "constant_velocity"), prime_radius=r0,
                   follower="rocker", contact="flat", pivot_distance=pivot, arm_length=arm)
    prof = cam_profile(spec)
    tol = tol_r0 * r0
    check_flat_outline(prof, tol, LINES)
