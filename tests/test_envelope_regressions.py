"""Envelopes the fuzzing found wrong, each against an oracle that shares no code with the kernel.

* A flat face on a motion that asks for a non-convex cam: the cam is what the swept face leaves
  (the intersection of its half-planes, convex), flagged as undercut; the envelope beyond it is
  cut away. Oracle: the swept follower (:func:`gearkit.oracles.cam.swept_cam`, polygon booleans)
  and the face's half-planes written out again from the spec's frames.
* A constant-velocity cam: the outline is split where the velocity jumps (the pitch curve's
  corner), so the sampler cannot skip the corner. Oracle: the exact pieces re-evaluated densely,
  and the swept follower.
* A cycloid disc whose pin is large enough for its two contacts' distances to cross over inside
  the pin's arc: the contacts are told apart by side (continuous), not by distance (which jumped
  0.17 mm at a piece end). Oracle: the swept pins' clearance (:mod:`gearkit.oracles.cycloid`).
"""
import math

import numpy as np
import pytest

import gearkit as gk
from gearkit.distances import distances_to_polyline
from gearkit.families.cam import CamSpec, MotionProgram, cam_profile
from gearkit.oracles.cam import oracle_error_bound, swept_cam
from gearkit.oracles.cycloid import swept_pin_disc_clearance

#: follower positions of the swept oracle (its scallop falls as the square of the step)
STEPS = 2880
#: dense points per exact piece for the independent deviation measure
DENSE = 20001
#: a dense polyline of the exact curve reads at most its own chord error low: a relative margin
MEASURE_SLACK = 1e-3


def _dense_deviation(prof, out):
    """Largest distance of the exact pieces from the closed outline (dense re-evaluation)."""
    w = np.linspace(0.0, 1.0, DENSE)
    exact = np.concatenate([pc(w) for pc in prof.pieces])
    return float(distances_to_polyline(exact, out, closed=True).max())


def _against_swept(spec, out, tol):
    """The outline and the swept follower's cam within the oracle's error bound plus tol, both ways."""
    swept = swept_cam(spec, steps=STEPS)
    bound = oracle_error_bound(spec, steps=STEPS) + tol
    assert distances_to_polyline(swept, out, closed=True).max() <= bound
    assert distances_to_polyline(out, swept, closed=True).max() <= bound


def _face_half_planes(spec, phi):
    """The face's lines in the cam frame, written out from the frames of CamSpec: unit normals away
    from the cam axis and distances ``h`` of ``n . x = h``."""
    s = spec.motion.evaluate(phi)[0]
    if spec.follower == "translating":  # the line y = r0 + s, turned back by -phi
        n = np.stack([np.sin(phi), np.cos(phi)], -1)
        return n, spec.prime_radius + s
    psi = math.asin(spec.prime_radius / spec.pivot_distance) + s / spec.arm_length
    d = np.stack([-np.cos(psi), np.sin(psi)], -1)  # along the arm from the pivot (l0, 0)
    normal = np.stack([d[:, 1], -d[:, 0]], -1)
    h = normal[:, 0] * spec.pivot_distance
    n = np.where((h < 0)[:, None], -normal, normal)
    c, sn = np.cos(-phi), np.sin(-phi)
    n = np.stack([c * n[:, 0] - sn * n[:, 1], sn * n[:, 0] + c * n[:, 1]], -1)
    return n, np.abs(h)


FLAT = {
    # the issue's reproducer: a rocker whose face turns back relative to the cam (psi' up to 1.43)
    "rocker": CamSpec(5.0, MotionProgram.rise_dwell_return(2.5, 20.0, 0.0, 20.0), "rocker", "flat",
                      pivot_distance=10.0, arm_length=10.0),
    # a translating face with r0 + s + s'' < 0 after the rise (textbook 3.45): two swallowtails
    "translating": CamSpec(20.0, MotionProgram.rise_dwell_return(10.0, 60.0, 30.0, 60.0, "harmonic"), contact="flat"),
}


@pytest.mark.parametrize("case", sorted(FLAT))
def test_flat_face_on_a_non_convex_motion_gives_the_cam_the_swept_face_leaves(case):
    spec, tol = FLAT[case], 0.005
    prof = cam_profile(spec)
    out = prof.outline(tol)
    assert prof.achieved(tol) <= tol and _dense_deviation(prof, out) <= tol * (1 + MEASURE_SLACK)
    _against_swept(spec, out, tol)
    # every outline vertex lies in every half-plane of the face, and on the line of one of them
    phi = np.linspace(0.0, 2.0 * math.pi, 20001)
    n, h = _face_half_planes(spec, phi)
    gap = out @ n.T - h[None, :]
    sag = oracle_error_bound(spec, steps=20000)
    assert gap.max() <= 1e-9 and gap.max(axis=1).min() >= -sag
    assert prof.undercut  # the cam cannot give the motion: a finding, not an error
    report = gk.check_cam(spec).report
    assert report["convexity"].status == "fail" and report.status == "fail"


def test_convex_flat_cam_keeps_the_whole_envelope():
    """r0 + s + s'' > 0 everywhere (textbook 3.45): nothing is cut, the cam is the envelope."""
    spec = CamSpec(40.0, MotionProgram.rise_dwell_return(10.0, 90.0, 30.0, 90.0), contact="flat")
    prof = cam_profile(spec)
    s, _, a, _ = spec.motion.evaluate(np.linspace(0.0, 2.0 * math.pi, 7201))
    assert (spec.prime_radius + s + a).min() > 0
    assert prof.loops == () and not prof.undercut
    _against_swept(spec, prof.outline(1e-4), 1e-4)


def test_constant_velocity_corner_is_not_skipped_by_the_sampler():
    """Reported 0.0042 at tol 0.005 and was 0.0054 off: the pitch curve's corner at the velocity
    jump sat inside one sampled piece. Pieces now end at every section end and motion join."""
    spec = CamSpec(5.0, MotionProgram.rise_dwell_return(1.25, 20.0, 1e-6, 20.0, "constant_velocity"), "rocker",
                   "roller", roller_radius=1.0, pivot_distance=10.0, arm_length=10.0)
    tol = 0.005
    prof = cam_profile(spec)
    out = prof.outline(tol)
    real = _dense_deviation(prof, out)
    assert prof.achieved(tol) <= tol and real <= tol * (1 + MEASURE_SLACK)
    assert real <= prof.achieved(tol) * (1 + MEASURE_SLACK)
    corners = [phi for phi, dv, _, _ in spec.motion.jumps() if abs(dv) > 0]
    assert len(corners) == 4
    ends = {round(float(prof.branch.phi([pc.w0])[0]) % (2 * math.pi), 9) for pc in prof.pieces}
    ends |= {round(float(prof.branch.phi([pc.w1])[0]) % (2 * math.pi), 9) for pc in prof.pieces}
    kept = [c for c in corners if not any(_inside(c % (2 * math.pi), lp) for lp in prof.loops)]
    assert kept and all(round(c % (2 * math.pi), 9) in ends for c in kept)
    _against_swept(spec, prof.outline(1e-4), 1e-4)


def _inside(phi, loop):
    a, b = loop
    return 0.0 < (phi - a) % (2 * math.pi) < (b - a) % (2 * math.pi)


def test_disc_contacts_stay_continuous_where_a_large_pin_distances_cross():
    """DriveSpec(3, 2, 13, 8, 3.8): the near/far rule swapped the pin's two contacts inside its arc;
    a piece began at the swap with the other contact's point, 0.17 mm from its own curve."""
    args = (3, 2, 13.0, 8.0, 3.8)
    spec = gk.DriveSpec(*args)
    disc = gk.disc_profile(spec)
    pieces = disc.half.pieces
    for a, b in zip(pieces[:-1], pieces[1:]):  # consecutive pieces meet
        assert np.linalg.norm(a(np.array([1.0]))[0] - b(np.array([0.0]))[0]) <= 1e-9
    for pc in pieces:  # an end is the limit of the curve inside (a square-root end at worst)
        for t, dt in ((0.0, 1e-10), (1.0, -1e-10)):
            gap = np.linalg.norm(pc(np.array([t]))[0] - pc(np.array([t + dt]))[0])
            assert gap <= 1e-3
    pts, _ = disc.half_points(1e-6)
    step = 0.01
    clearance = swept_pin_disc_clearance(pts, *args, step)
    assert clearance.min() >= -1e-9 and clearance.max() <= step ** 2 / (8 * spec.pin_radius)
    _, achieved = disc.half_points(0.01)
    assert achieved <= 0.01
