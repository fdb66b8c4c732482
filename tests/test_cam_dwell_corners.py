"""A roller rocker with a dwell of a few ulps between the rise's end and the return's start.

Two velocity jumps a dwell of 1e-10 degrees apart (not one cam angle, so not merged into one corner) leave
two concave corner arcs of the roller separated by a motion section some 1e-8 of a keep-test sample long.
The cut runs across both arcs and both are cut whole: the crossing that closes it is that of the envelopes
on the far sides of the run of arcs, not of either arc's own sides (the fuzz run's GeometryError: the
envelope leaves the cam where it meets no other kept arc). Neighbouring dwells (1e-12 to 1e-6 degrees) and
rollers (+-1e-6 mm) are checked too.

Oracle, none of it the product's envelope: the roller's discs swept along its centre path written out from
the spec's frames, every phase end among the angles (:func:`test_cam_concave_corner.check_against_swept_discs`).
"""
import pytest
from test_cam_concave_corner import check_against_swept_discs

from gearkit.families.cam import CamSpec, MotionProgram

#: the fuzz run's rocker: prime radius, roller radius, pivot distance, arm length (mm)
R0, ROLLER, PIVOT, ARM = 136.97462601101927, 0.5689211377504696, 315.86970571909904, 390.32835760861724
#: lift (mm), rise and return (degrees)
LIFT, RISE, RETURN = 1.0329866489673276, 46.5572100442338, 59.10249839541623


def _spec(dwell, roller=ROLLER):
    motion = MotionProgram.rise_dwell_return(LIFT, RISE, dwell, RETURN, "constant_velocity")
    return CamSpec(R0, motion, follower="rocker", contact="roller", roller_radius=roller, pivot_distance=PIVOT,
                   arm_length=ARM)


@pytest.mark.parametrize("tol", [1e-3 * R0, 1e-4 * R0])  # the fuzz run's tolerance and a tenth of it
def test_the_fuzz_runs_rocker_cuts_across_both_arcs(tol):
    check_against_swept_discs(_spec(1e-10), tol)


NEIGHBOURS = [(d, r) for d in (1e-12, 1e-10, 1e-8, 1e-6) for r in (ROLLER - 1e-6, ROLLER, ROLLER + 1e-6)
              if (d, r) != (1e-10, ROLLER)]


@pytest.mark.parametrize("tol", [1e-3 * R0, 1e-4 * R0])
@pytest.mark.parametrize("dwell, roller", NEIGHBOURS)
def test_neighbouring_dwells_and_rollers(dwell, roller, tol):
    check_against_swept_discs(_spec(dwell, roller), tol)
