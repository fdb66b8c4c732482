"""Large rollers on short steep rises: the kept arcs of the envelope joined in the right order.

The roller cam's outline follows the runs of envelope samples no roller covers from the end of one to the
start of the next, each joined at the envelope's crossing (:func:`gearkit.families.cam.faces.kept_runs`).
Two fuzz-found rockers had that crossing taken from the wrong pair:

* a roller of half the prime radius on a 20-degree polynomial rise of 0.6 r0 pinches the cam's nose off:
  past a neck where the two flanks' envelopes cross, an island of uncovered envelope that no shaft holds.
  Newton from the chords' crossing far out settled on the island's crossings, past a whole kept run, and the
  runs did not close around the axis (GeometryError on a valid cam);
* constant-velocity rockers whose kept runs were joined at the exit of a corner's roller circle far from
  the run entered: the outline kept the swallowtail beyond, 4.3 mm (and a stretch 51 mm) inside a roller.

Oracle, none of it the product's envelope: the roller centre written out from the spec's frames
(:func:`test_cam_bounds.pitch_curve`) and the rollers' discs about it
(:func:`test_cam_concave_corner.check_against_swept_discs`: every vertex a roller radius from the centre
path, every chord outside the discs by at most the reported deviation), and the uncovered points of the
path's offset by a roller radius, each on the outline or, for the pinched nose, on the island beyond it.
"""
import math

import numpy as np
import pytest
from camoracle import pitch_curve
from test_cam_concave_corner import check_against_swept_discs

from gearkit.distances import distances_to_polyline, edge_distances
from gearkit.families.cam import CamSpec, MotionProgram

#: the fuzz run's pinched rocker: prime radius, roller radius, pivot distance, arm length (mm)
R0, ROLLER, PIVOT, ARM = 79.06439517241856, 39.91753973151403, 118.59659275862784, 59.29829637931392
#: lift (mm of the roller centre's arc), rise, far dwell and return (degrees)
LIFT, RISE, DWELL, RETURN = 47.438637103451136, 20.0, 28.200489191833114, 20.0
#: the sweep's constant-velocity rockers (prime radius, roller, pivot, arm; lift, rise, dwell, return): their
#: outlines kept a swallowtail 4.3 mm and a stretch 51 mm inside a roller
CV = [((15.250848821808606, 7.672217269941743, 33.230195948187635, 20.918578779305637),
       (10.473036322470314, 22.860452306830492, 18.23934762484577, 34.611408221106345)),
      ((86.44246224559137, 51.37354930535577, 197.3331362983138, 274.38722874099716),
       (61.53250555508405, 26.115452373176545, 55.292509829274245, 24.06409391655079))]
#: centres of the offset oracle over a turn
OFFSETS = 40001


def _pinched(roller=ROLLER):
    motion = MotionProgram.rise_dwell_return(LIFT, RISE, DWELL, RETURN, "polynomial_345")
    return CamSpec(R0, motion, follower="rocker", contact="roller", roller_radius=roller, pivot_distance=PIVOT,
                   arm_length=ARM)


def _constant_velocity(which):
    (r0, roller, pivot, arm), motion = CV[which]
    return CamSpec(r0, MotionProgram.rise_dwell_return(*motion, "constant_velocity"), follower="rocker",
                   contact="roller", roller_radius=roller, pivot_distance=pivot, arm_length=arm)


def uncovered_offset(spec, n=OFFSETS, h=1e-7):
    """The centre path's offset a roller radius towards the cam (normals by central differences of the closed
    form, ``h`` rad), kept where no roller along the path covers it: points of the exact cam's boundary."""
    phi = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    p = pitch_curve(spec, phi)
    d = (pitch_curve(spec, phi + h) - pitch_curve(spec, phi - h)) / (2 * h)
    q = p + spec.roller_radius * np.stack([d[:, 1], -d[:, 0]], -1) / np.hypot(d[:, 0], d[:, 1])[:, None]
    r = spec.roller_radius
    return q[edge_distances(q, p, closed=True) >= r * (1 - 1e-7)]


@pytest.mark.parametrize("tol_r0", [1e-3, 1e-4, 1e-5])
def test_the_pinched_nose_builds_without_its_island(tol_r0):
    spec = _pinched()
    tol = tol_r0 * R0
    prof = check_against_swept_discs(spec, tol)
    out = prof.outline(tol)
    exact = uncovered_offset(spec)
    off = distances_to_polyline(exact, out, closed=True) > 2 * tol
    reach = np.hypot(*out.T).max()
    island = exact[off]
    # every uncovered point the outline does not pass lies beyond the cam's nose: the island past the neck
    assert len(island) and np.hypot(*island.T).min() > reach
    # and the neck between the nose and the island is covered by a roller (no cam joins them there)
    tip, near = out[np.argmax(np.hypot(*out.T))], island[np.argmin(np.hypot(*island.T))]
    gap = tip + np.linspace(0.1, 0.9, 9)[:, None] * (near - tip)
    path = pitch_curve(spec, np.linspace(0.0, 2 * math.pi, 1 << 18))
    assert (distances_to_polyline(gap, path, closed=True) < spec.roller_radius).all()
    assert prof.undercut


@pytest.mark.parametrize("roller", [ROLLER + 1e-6, ROLLER - 1e-6, ROLLER + 0.5, ROLLER - 0.5, 0.3 * R0, 0.6 * R0])
@pytest.mark.parametrize("tol_r0", [1e-3, 1e-4])
def test_neighbours_of_the_pinched_nose(roller, tol_r0):
    spec = _pinched(roller)
    tol = tol_r0 * R0
    out = check_against_swept_discs(spec, tol).outline(tol)
    exact = uncovered_offset(spec)
    off = distances_to_polyline(exact, out, closed=True) > 2 * tol
    assert not off.any() or np.hypot(*exact[off].T).min() > np.hypot(*out.T).max()  # only an island beyond


@pytest.mark.parametrize("which", range(len(CV)))
@pytest.mark.parametrize("tol_r0", [1e-3, 1e-4, 1e-5])
def test_constant_velocity_runs_are_joined_at_their_own_ends(tol_r0, which):
    spec = _constant_velocity(which)
    tol = tol_r0 * spec.prime_radius
    # the swallowtail beside the corners' arcs is cut, but for loops shallower than the keep test's slack,
    # which the reported deviation covers
    out = check_against_swept_discs(spec, tol).outline(tol)
    exact = uncovered_offset(spec)
    assert distances_to_polyline(exact, out, closed=True).max() <= 2 * tol
