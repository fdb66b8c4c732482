"""A roller cam's reported deviation covers the loops its keep test leaves in; a finer tol is refused.

The keep test measures an envelope point's depth in the swept region against a sampled pitch curve and
keeps it up to 1e-7 (r0 + stroke) deep (that sampling's error), so a swallowtail shallower than that stays
in the outline whole. Its reported deviation, a bound against the kept pieces, left that depth out: a
harmonic rocker's outline lay 3.8e-7 mm inside a roller at tol 1.5e-8 mm, reported 1.43e-8. The bound now
adds the keep slack, and a tol below twice it (2e-7 (r0 + stroke)) is refused, naming ``tol`` and the
range (the pitch curve, which keeps nothing, still goes down to 1e-9 (r0 + stroke)).

Oracle, none of it the product's envelope or sampler: the roller's discs about its centre path written
out from the spec's frames (:mod:`camoracle`): the loop exists and is kept (the kept pieces, evaluated
densely, dip into the discs by more than the centres' sag), and at every tol from the floor up the
outline lies inside no disc by more than its reported deviation, which is at most the tol; the deviation
from the kept pieces is measured independently too (:func:`fuzzkit.true_deviation`).
"""
import math

import numpy as np
import pytest
from camoracle import check_swept_discs, pitch_curve
from fuzzkit import true_deviation

from gearkit.cli import main
from gearkit.distances import edge_distances
from gearkit.errors import SpecError
from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

#: the keep test's slack and the roller's finest tol, in (r0 + stroke), as the README states them
SLACK, FLOOR = 1e-7, 2e-7
#: the bound is proven: the dense measure may exceed it by round-off only
BOUND_SLACK = 1e-9

#: a rocker (r0 5, pivot 6, arm 8, a harmonic rise of 2.5 mm over 20 degrees) whose roller is 1.001 times
#: the pitch curve's least convex radius of curvature (0.25201611 mm): a swallowtail 3.8e-7 mm deep, under
#: the slack of 7.5e-7 mm; and a translating cycloidal cam (r0 40, rise 20 over 60 degrees, return over 90)
#: whose roller is 3 um past that radius (21.2103675176 mm): a loop 6e-7 mm deep under the slack of 6e-6 mm
SPECS = {
    "rocker": CamSpec(5.0, MotionProgram.rise_dwell_return(2.5, 20.0, 20.0, 20.0, "harmonic"), follower="rocker",
                      contact="roller", roller_radius=0.25201611 * 1.001, pivot_distance=6.0, arm_length=8.0),
    "translating": CamSpec(40.0, MotionProgram.rise_dwell_return(20.0, 60.0, 30.0, 90.0, "cycloidal"),
                           roller_radius=21.2103675176 + 3e-3),
}
#: tols as multiples of the floor (the floor itself a hair above, as the range is closed)
MULTIPLES = [1 + 1e-9, 2.0, 10.0]


def _size(spec):
    return spec.prime_radius + spec.stroke


@pytest.mark.parametrize("name", SPECS)
def test_the_loop_shallower_than_the_slack_is_kept(name):
    spec = SPECS[name]
    prof = cam_profile(spec)
    points = np.concatenate([pc(np.linspace(0.0, 1.0, 4001)) for pc in prof.pieces])
    path = pitch_curve(spec, np.linspace(0.0, 2 * math.pi, 1 << 20, endpoint=False))  # 4x CENTRES: a sag of 9e-9 mm
    depth = spec.roller_radius - edge_distances(points, path, closed=True)
    # the centres' chords stand off the path by at most L^2 / (8 R) where a loop's nearest centre lies (the
    # path's radius of curvature there at least the roller's, else the neighbouring discs cover it), doubled
    sag = 2 * float(np.hypot(*np.diff(path, axis=0).T).max()) ** 2 / (8 * spec.roller_radius)
    assert 0.05 * SLACK * _size(spec) > sag
    assert 0.05 * SLACK * _size(spec) < depth.max() <= SLACK * _size(spec) + sag


@pytest.mark.parametrize("multiple", MULTIPLES)
@pytest.mark.parametrize("name", SPECS)
def test_the_reported_deviation_bounds_the_distance_to_the_cam(name, multiple):
    spec = SPECS[name]
    prof = cam_profile(spec)
    tol = multiple * FLOOR * _size(spec)
    out, achieved = prof.outline(tol), prof.achieved(tol)
    assert achieved <= tol
    check_swept_discs(spec, out, achieved)
    real = true_deviation(prof.pieces, np.concatenate([out[::-1], out[-1:]]))
    assert real <= achieved * (1 + BOUND_SLACK)


@pytest.mark.parametrize("name", SPECS)
def test_a_tol_below_the_floor_is_refused_naming_it(name):
    spec = SPECS[name]
    prof = cam_profile(spec)
    tol = (1 - 1e-9) * FLOOR * _size(spec)
    for call in (prof.outline, prof.achieved):
        with pytest.raises(SpecError) as exc:
            call(tol)
        assert exc.value.field == "tol" and f"{FLOOR * _size(spec):.6g}" in str(exc.value)
    pitch, bound = prof.pitch_outline(tol)  # the pitch curve keeps nothing: its own precision is its floor
    assert len(pitch) and bound <= tol


def test_the_cli_refuses_it_in_one_line_and_writes_nothing(capsys, tmp_path):
    size = 40.0 + 20.0
    path = tmp_path / "cam.svg"
    args = ["cam", "--prime-radius", "40", "--roller-radius", "10", "--law", "cycloidal", "--rise", "20",
            "--rise-deg", "60", "--dwell-deg", "30", "--return-deg", "90", "-o", str(path)]
    code = main(args + ["--tol", repr(0.5 * FLOOR * size)])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "--tol" in err and f"{FLOOR * size:.6g}" in err
    assert "Traceback" not in err and not path.exists()
    assert main(args + ["--tol", repr(FLOOR * size * (1 + 1e-9))]) in (0, 1) and path.exists()  # 1: a check fails
