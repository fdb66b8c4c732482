"""A small roller across a slight concave corner of its centre path: the sides' envelopes cross there.

Where a constant-velocity law's velocity jumps by little (the start of a long return after a dwell, a
rocker's pitch curve turning by 0.31 degrees), the roller's arc about the corner runs back and is cut
whole, and the envelopes either side of it cross a fraction of a keep-test sample from the arc's ends
(0.0068 mm from the corner's contact, a 2.5 mm roller). The keep test's chords there join a side to the
arc, which its parameter runs over twenty samples of ``w`` while it is 0.0135 mm long: the chords'
crossing and the closest pair of a dense resampling both lay on the arc, and Newton stayed on it (the
fuzz run's GeometryError: the envelope leaves the cam where it meets no other kept arc).

Oracle, none of it the product's envelope: the roller centre written out from the spec's frames
(:func:`camoracle.pitch_curve`), densely, with every phase end among the angles (the corners
exact). The cam is what the roller disc swept along it leaves: every outline vertex (an exact point of
the cam) a roller radius from the centre path, within the chords' sag, and every chord of the outline
outside the swept discs by at most the reported deviation, which is at most the tolerance.
"""
import pytest
from camoracle import check_swept_discs

from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

#: the fuzz run's rocker: prime radius, roller radius, pivot distance, arm length (mm)
R0, ROLLER, PIVOT, ARM = 144.07431815201312, 2.5, 432.2229544560393, 526.875653870586
#: lift (mm), rise, far dwell and return (degrees)
LIFT, RISE, DWELL, RETURN = 2.8814863630402625, 20.0, 38.21955652124192, 144.07431815201312
#: roller centres over a turn, plus the phase ends
CENTRES = 1 << 18
#: the fuzz run's tolerance is 1e-3 r0; a tenth of it here
TOL = 1e-4 * R0


def _spec(dwell=DWELL, roller=ROLLER, arm=ARM, follower="rocker"):
    motion = MotionProgram.rise_dwell_return(LIFT, RISE, dwell, RETURN, "constant_velocity")
    if follower == "translating":
        return CamSpec(R0, motion, contact="roller", roller_radius=roller)
    return CamSpec(R0, motion, follower="rocker", contact="roller", roller_radius=roller, pivot_distance=PIVOT,
                   arm_length=arm)


def check_against_swept_discs(spec, tol):
    """The outline at ``tol`` against the roller's discs along its exact centre path; returns the profile."""
    prof = cam_profile(spec)
    out, achieved = prof.outline(tol), prof.achieved(tol)
    assert achieved <= tol
    check_swept_discs(spec, out, achieved, CENTRES)
    return prof


def test_the_fuzz_runs_rocker_cuts_its_slight_concave_corner():
    prof = check_against_swept_discs(_spec(), TOL)
    check_against_swept_discs(_spec(), 1e-3 * R0)  # the fuzz run's own tolerance
    assert len(prof.corner_loops) == 2 and not prof.undercut  # the rise's end and the return's start


@pytest.mark.parametrize("roller, arm", [(ROLLER + 1e-6, ARM), (ROLLER - 1e-6, ARM), (ROLLER, ARM + 1e-6),
                                         (ROLLER, ARM - 1e-6)])
def test_neighbours_of_the_rocker(roller, arm):
    check_against_swept_discs(_spec(roller=roller, arm=arm), TOL)


@pytest.mark.parametrize("dwell", [0.0, 1e-10, 5.0])
@pytest.mark.parametrize("follower", ["rocker", "translating"])
def test_other_dwells_and_the_translating_follower(dwell, follower):
    check_against_swept_discs(_spec(dwell=dwell, follower=follower), TOL)


def test_the_translating_follower_with_the_fuzz_runs_dwell():
    check_against_swept_discs(_spec(follower="translating"), TOL)


#: a scan of small-roller constant-velocity cams near the fuzz run's: a sample of the arc within a step of
#: its start (a rocker) or of both its ends (an offset translating cam) was kept, its central difference
#: straddling the arc's end, and the chords there met the arc as before
SCANNED = [
    ((1.9503973549824476, 10.11455959642256, 57.7909030043841, 80.81375650026591),
     dict(prime_radius=250.5935070670014, follower="rocker", roller_radius=1.905215077776643,
          pivot_distance=618.1706871534232, arm_length=668.2052661048644)),
    ((1.9807903133506837, 50.4579822901517, 56.11654841965259, 182.3499992099439),
     dict(prime_radius=286.5037606617414, roller_radius=7.395847602632539, offset=20.126240872929696)),
]


@pytest.mark.parametrize("motion, kw", SCANNED)
def test_a_kept_sample_at_the_arcs_end(motion, kw):
    spec = CamSpec(motion=MotionProgram.rise_dwell_return(*motion, "constant_velocity"), contact="roller", **kw)
    # a swallowtail beside these arcs is shallower than the keep test's slack, 1e-7 (r0 + stroke), and stays
    # in the outline: its vertices lie up to that much inside a roller, which the reported deviation covers
    check_against_swept_discs(spec, 1e-4 * spec.prime_radius)
