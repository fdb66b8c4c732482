"""Cams on the envelope kernel: laws, profiles, pressure angles, undercut, oracles.

Oracles: the laws' published peak-acceleration coefficients and numerical differentiation; the
pitch curve in the textbook's polar form (3.28-3.29) written out here; the pressure-angle closed
forms (textbook 3.19, the friction digest's eq. 6 and corrected eq. 18 with its test vectors);
the digest's r0,min table (§3.1) and pitch-curve radii (§3.2); the eccentric circle cam; the
flat-face closed forms (3.45-3.49); the swept-follower oracle.
"""
import math

import numpy as np
import pytest

from gearkit.distances import distances_to_polyline
from gearkit.errors import SpecError
from gearkit.families.cam import (LAWS, CamSpec, MotionProgram, MotionSegment, cam_profile, law_shape,
                                  rocker_pressure_angle, smallest_prime_radius)

#: the pressure angle closed forms hold to this (rad): the issue's bound
ANGLE_TOL = 1e-9
#: the digest prints r0,min to 4 decimals
DIGEST_R0_TOL = 0.6e-4
CLOSED_FORM_LAWS = [law for law in LAWS if law != "table"]


def digest_program(law="cycloidal"):
    """The digest's test law: rise 20 mm over 60 deg, dwell to 120, return to 180, dwell."""
    return MotionProgram((MotionSegment("rise", 60.0, 20.0, law), MotionSegment("dwell", 60.0),
                          MotionSegment("return", 60.0, 20.0, law)))


def polar_pitch(spec, phi):
    """Textbook (3.28-3.29): pitch curve of a translating follower in polar form, written out again.
    The cam turns counter-clockwise, so the follower point sits at cam-frame angle
    ``atan2(H0 + s, e) - phi``."""
    s = spec.motion.evaluate(phi)[0]
    h0 = math.sqrt(spec.prime_radius ** 2 - spec.offset ** 2)
    r = np.hypot(spec.offset, s + h0)
    delta = np.arctan2(s + h0, spec.offset) - phi
    return np.stack([r * np.cos(delta), r * np.sin(delta)], -1)


# ----------------------------------------------------------------------------- laws

@pytest.mark.parametrize("law, peak", [("harmonic", math.pi ** 2 / 2), ("cycloidal", 2 * math.pi),
                                       ("polynomial_345", 10 / math.sqrt(3)), ("polynomial_4567", 7.5132),
                                       ("modified_trapezoid", 4.8881), ("modified_sine", 5.5280)])
def test_law_peak_acceleration_matches_published_coefficient(law, peak):
    x = np.linspace(0.0, 1.0, 200001)
    a = law_shape(law, x)[2]
    assert abs(np.abs(a).max() - peak) < 1e-4  # coefficients published to 4 decimals


@pytest.mark.parametrize("law", CLOSED_FORM_LAWS + ["table"])
def test_law_endpoints_and_derivatives_by_numerical_differentiation(law):
    table = ((0.0, 0.0), (0.3, 0.2), (0.7, 0.8), (1.0, 1.0)) if law == "table" else None
    x = np.linspace(0.0, 1.0, 40001)
    f, v, a, j = law_shape(law, x, table)
    assert f[0] == 0.0 and abs(f[-1] - 1.0) < 1e-12
    h = x[1] - x[0]
    # central differences: error h^2/6 times the next derivative, ~1e-7 of the derivatives' scale
    # (4 pi)^k; the piecewise laws join their pieces at multiples of 1/8 (the table's spline at its
    # knots), where a higher derivative jumps: skipped by 2 h
    knots = np.concatenate([np.arange(9) / 8, np.asarray(table or [(0, 0)])[:, 0]])
    away = np.abs(x[1:-1, None] - knots[None, :]).min(axis=1) > 2 * h
    for lower, upper, scale in ((f, v, 1.0), (v, a, 4 * math.pi), (a, j, (4 * math.pi) ** 2)):
        diff = (lower[2:] - lower[:-2]) / (2 * h)
        assert np.abs(diff - upper[1:-1])[away].max() < 1e-6 * scale
    if law != "constant_velocity":
        assert abs(v[0]) < 1e-12 and abs(v[-1]) < 1e-12


def test_joins_flag_velocity_acceleration_and_jerk_jumps():
    def jumps(law):
        return MotionProgram.rise_dwell_return(10.0, 90.0, 90.0, 90.0, law=law).jumps()
    beta = math.pi / 2
    cv = jumps("constant_velocity")
    assert abs(cv[0][1] + 10.0 / beta) < 1e-12  # the rise's velocity H/beta stops dead
    shm = jumps("harmonic")
    assert abs(shm[0][2] - 10.0 * math.pi ** 2 / 2 / beta ** 2) < 1e-9 and abs(shm[0][1]) < 1e-12
    cyc = jumps("cycloidal")
    assert all(abs(dv) < 1e-12 and abs(da) < 1e-9 for _, dv, da, _ in cyc)
    assert abs(abs(cyc[0][3]) - 10.0 * (2 * math.pi) ** 2 / beta ** 3) < 1e-9
    assert all(abs(dj) < 1e-9 for _, _, _, dj in jumps("polynomial_4567"))


def test_program_rejects_a_rise_that_does_not_fit_and_a_follower_that_does_not_return():
    with pytest.raises(SpecError, match="rise_deg"):
        MotionProgram.rise_dwell_return(10.0, 200.0, 100.0, 100.0)
    with pytest.raises(SpecError, match="return"):
        MotionProgram((MotionSegment("rise", 90.0, 10.0), MotionSegment("return", 90.0, 8.0)))
    with pytest.raises(SpecError, match="rise"):
        MotionSegment("rise", 90.0, -1.0)


# ----------------------------------------------------------------------------- profiles

# constant velocity included: its pitch curve has corners (velocity jumps), where the profile is the
# roller's arc about the corner (convex) or the crossing of the two flanks (concave)
@pytest.mark.parametrize("law", CLOSED_FORM_LAWS)
@pytest.mark.parametrize("offset", [0.0, 6.0, -6.0])
def test_roller_profile_is_the_offset_of_the_exact_pitch_curve(law, offset):
    tol, rr = 1e-3, 8.0
    spec = CamSpec(60.0, digest_program(law), roller_radius=rr, offset=offset)
    prof = cam_profile(spec)
    assert not prof.undercut
    assert len(prof.corner_loops) == (2 if law == "constant_velocity" else 0)  # the two concave corners
    out = prof.outline(tol)
    phi = np.linspace(0.0, 2 * math.pi, 400001)
    pitch = polar_pitch(spec, phi)  # 4e5 chords: their own sag is below 1e-8 mm
    # every output point (vertices and chord midpoints) lies at the roller radius from the pitch curve
    mids = 0.5 * (out + np.roll(out, -1, axis=0))
    for pts, slack in ((out, 1e-7), (mids, tol + 1e-7)):
        d = distances_to_polyline(pts, pitch, closed=True)
        assert np.abs(d - rr).max() <= slack
    assert prof.achieved(tol) <= tol


@pytest.mark.parametrize("offset", [0.0, 5.0, -5.0])
@pytest.mark.parametrize("follower", ["roller", "knife"])
def test_pressure_angle_from_the_generated_contact_equals_the_closed_form(offset, follower):
    rr = 10.0 if follower == "roller" else 0.0
    for law in ("cycloidal", "modified_sine", "harmonic"):
        spec = CamSpec(56.7702, digest_program(law), contact=follower, roller_radius=rr, offset=offset)
        phi = np.linspace(0.0, 2 * math.pi, 3001)
        s, v, _, _ = spec.motion.evaluate(phi)
        closed = np.arctan((v - offset) / (s + math.sqrt(56.7702 ** 2 - offset ** 2)))  # textbook 3.19
        assert np.abs(cam_profile(spec).pressure_angle(phi) - closed).max() < ANGLE_TOL


@pytest.mark.parametrize("eta, e, expected", [
    (1.00, 0.0, 56.7702), (1.00, 5.0, 48.3690), (1.00, -5.0, 65.6212),
    (0.95, 0.0, 60.2219), (0.95, 5.0, 51.8035), (0.95, -5.0, 69.0634),
    (0.90, 0.0, 64.0605), (0.90, 5.0, 55.6254), (0.90, -5.0, 72.8924),
    (0.80, 0.0, 73.1884), (0.80, 5.0, 64.7216), (0.80, -5.0, 82.0013)])
def test_smallest_prime_radius_reproduces_the_digest_table(eta, e, expected):
    spec = CamSpec(100.0, digest_program(), roller_radius=10.0, offset=e, efficiency=eta)
    r0 = smallest_prime_radius(spec)
    assert abs(r0 - expected) < DIGEST_R0_TOL
    # and the geometry generated at that radius peaks exactly at the limit with friction
    at = CamSpec(r0, digest_program(), roller_radius=10.0, offset=e, efficiency=eta)
    from gearkit.families.cam import law_pressure_angle
    phi = np.linspace(0.0, math.pi / 3, 20001)
    assert abs(np.degrees(np.abs(law_pressure_angle(at, phi))).max() - 30.0) < 1e-5


@pytest.mark.parametrize("psi_deg, dpsi, expected", [(30.0, 0.3, 41.7346), (40.0, -0.2, 4.0972),
                                                     (55.0, 0.5, 18.4680)])
def test_corrected_rocker_formula_reproduces_the_digest_vectors(psi_deg, dpsi, expected):
    got = abs(math.degrees(rocker_pressure_angle(0.6, math.radians(psi_deg), dpsi, sense=-1)))
    assert abs(got - expected) < 0.6e-4


def test_rocker_geometry_equals_the_corrected_formula_and_friction_raises_it():
    spec = CamSpec(45.0, digest_program(), follower="rocker", roller_radius=6.0, pivot_distance=80.0,
                   arm_length=50.0)
    prof = cam_profile(spec)
    phi = np.linspace(0.0, 2 * math.pi, 3001)
    s, v, _, _ = spec.motion.evaluate(phi)
    psi = spec.psi0 + s / 50.0
    closed = rocker_pressure_angle(50.0 / 80.0, psi, v / 50.0, sense=1)
    assert np.abs(prof.pressure_angle(phi) - closed).max() < ANGLE_TOL
    # every profile point at the roller radius from the roller centre's path (the rocker's pitch curve)
    q, c = prof.profile_points(phi), prof.pitch_points(phi)
    assert np.abs(np.hypot(*(q - c).T) - 6.0).max() < 1e-9
    rise = phi <= math.pi / 3
    with_friction = rocker_pressure_angle(50.0 / 80.0, psi, v / 50.0, efficiency=0.9, sense=1)
    assert np.abs(with_friction[rise]).max() > np.abs(closed[rise]).max() + 1e-3


@pytest.mark.parametrize("kw", [dict(efficiency=0.9), dict(friction=0.1)])
def test_friction_raises_the_pressure_angle_and_the_smallest_prime_radius(kw):
    from gearkit.checks.cam import check_cam

    plain = CamSpec(60.0, digest_program(), roller_radius=10.0, offset=3.0)
    rough = CamSpec(60.0, digest_program(), roller_radius=10.0, offset=3.0, **kw)
    res = check_cam(rough).values
    for kind in ("rise", "return"):
        assert res["pressure_angle_friction_max_deg"][kind] > res["pressure_angle_max_deg"][kind] + 0.5
    assert res["prime_radius_min_friction"] > smallest_prime_radius(plain) + 1.0
    # a rocker's smallest r0 is often set at rest (psi' = 0), where the power model adds nothing;
    # the friction-angle model raises it wherever it is set
    rocker = dict(follower="rocker", roller_radius=6.0, pivot_distance=100.0, arm_length=60.0,
                  pressure_angle_limit_deg=30.0)
    assert smallest_prime_radius(CamSpec(60.0, digest_program(), friction=0.1, **rocker)) > \
        smallest_prime_radius(CamSpec(60.0, digest_program(), **rocker)) + 0.5


def test_pitch_curvature_radius_matches_the_digest_and_the_polar_formula():
    for r0, expected in ((56.7702, 30.9691), (80.0, 46.2835)):
        spec = CamSpec(r0, digest_program(), roller_radius=5.0)
        phi = np.linspace(0.0, 2 * math.pi, 72001)
        rho = cam_profile(spec).pitch_curvature_radius(phi)
        assert abs(rho[rho > 0].min() - expected) < 1e-3  # 4 decimals, minimum on a 0.005 deg grid
        # polar formula rho = (r^2 + r'^2)^1.5 / (r^2 + 2 r'^2 - r r'') for a central follower
        s, v, a, _ = spec.motion.evaluate(phi)
        r = r0 + s
        polar = (r * r + v * v) ** 1.5 / (r * r + 2 * v * v - r * a)
        assert np.abs(1.0 / rho - 1.0 / polar).max() < 1e-12 / r0  # curvature: no blow-up at inflections


def test_undercut_appears_exactly_where_the_pitch_curvature_radius_falls_below_the_roller():
    base = CamSpec(56.7702, digest_program(), roller_radius=5.0)
    phi = np.linspace(0.0, 2 * math.pi, 36001)
    rho = cam_profile(base).pitch_curvature_radius(phi)
    rr = 1.2 * rho[rho > 0].min()
    prof = cam_profile(CamSpec(56.7702, digest_program(), roller_radius=rr))
    assert prof.undercut
    # the envelope runs backwards (a loop) exactly where 0 < rho < R_p
    backwards = prof._forward(phi) < 0
    inside = (rho > 0) & (rho < rr)
    margin = np.abs(rho - rr) > 1e-6 * rr  # the two sets share their edges; compare away from them
    assert np.array_equal(backwards[margin], inside[margin])
    # each cut loop spans the region where the roller is too large
    for a, b in prof.loops:
        mid = np.linspace(a, b, 50)
        assert (prof._forward(mid) < 0).any()
    # below the limit no loop: R_p just under rho_min
    assert not cam_profile(CamSpec(56.7702, digest_program(), roller_radius=0.99 * rr / 1.2)).undercut


def test_eccentric_circle_cam_with_a_flat_follower_is_harmonic_motion():
    """A flat face on an eccentric circle (radius R, eccentricity eps) moves s = eps (1 - cos phi):
    so the cam generated from that harmonic law must be that circle."""
    big_r, eps = 30.0, 6.0
    prog = MotionProgram((MotionSegment("rise", 180.0, 2 * eps, "harmonic"),
                          MotionSegment("return", 180.0, 2 * eps, "harmonic")))
    prof = cam_profile(CamSpec(big_r - eps, prog, contact="flat"))
    out = prof.outline(1e-4)
    assert not prof.undercut
    assert np.abs(np.hypot(out[:, 0], out[:, 1] + eps) - big_r).max() < 1e-9


def test_flat_face_closed_forms_curvature_polar_profile_and_contact_travel():
    r0 = 100.0
    spec = CamSpec(r0, digest_program("polynomial_345"), contact="flat")
    prof = cam_profile(spec)
    phi = np.linspace(0.0, 2 * math.pi, 2001)
    s, v, a, _ = spec.motion.evaluate(phi)
    q = prof.profile_points(phi)
    assert np.abs(np.hypot(*q.T) - np.hypot(r0 + s, v)).max() < 1e-9  # r_K = sqrt((R0+s)^2 + s'^2)
    assert np.abs(prof.face_contact(phi) - v).max() < 1e-9  # contact at l = s' from the axis
    # rho = R0 + s + s'' (3.45), against central differences of the exact envelope (h = 2e-4 rad)
    joins = np.radians([0.0, 60.0, 120.0, 180.0, 360.0])  # s''' jumps there: the differences see it
    away = np.abs(phi[:, None] - joins[None, :]).min(axis=1) > 4e-4
    # second differences err by about h^2/12 times the curve's fourth derivative (~1e4 mm here)
    assert np.abs(prof.curvature_radius(phi) - (r0 + s + a))[away].max() < 1e-3
    s, _, a, _ = spec.motion.evaluate(np.linspace(0.0, 2 * math.pi, 2_000_001))  # grid error < 1e-7 mm
    assert smallest_prime_radius(spec) == pytest.approx(float(np.max(-s - a)), abs=1e-6)


def test_knife_edge_profile_is_the_pitch_curve():
    spec = CamSpec(50.0, digest_program(), contact="knife", offset=4.0)
    phi = np.linspace(0.0, 2 * math.pi, 1001)
    assert np.abs(cam_profile(spec).profile_points(phi) - polar_pitch(spec, phi)).max() < 1e-12


@pytest.mark.parametrize("kw", [dict(roller_radius=10.0), dict(roller_radius=37.0), dict(contact="knife"),
                                dict(roller_radius=8.0, follower="rocker", pivot_distance=80.0, arm_length=50.0),
                                dict(roller_radius=10.0, law="constant_velocity")])
def test_swept_follower_oracle_agrees_with_the_envelope(kw):
    from gearkit.oracles.cam import oracle_error_bound, swept_cam

    kw = dict(kw)
    spec = CamSpec(56.7702, digest_program(kw.pop("law", "cycloidal")), **kw)
    swept = swept_cam(spec)
    out = cam_profile(spec).outline(1e-4)
    bound = oracle_error_bound(spec) + 1e-4
    assert distances_to_polyline(swept, out, closed=True).max() <= bound
    assert distances_to_polyline(out, swept, closed=True).max() <= bound


@pytest.mark.parametrize("kw, field", [
    (dict(prime_radius=-5.0), "prime_radius"), (dict(roller_radius=-1.0), "roller_radius"),
    (dict(offset=70.0), "offset"), (dict(follower="rocker", pivot_distance=200.0, arm_length=50.0), "arm_length"),
    (dict(efficiency=1.5), "efficiency")])
def test_bad_specs_raise_naming_the_field(kw, field):
    args = dict(prime_radius=60.0, motion=digest_program(), roller_radius=10.0)
    args.update(kw)
    with pytest.raises(SpecError) as err:
        CamSpec(**args)
    assert err.value.field == field


def test_bench_cam_rows_track_the_requested_tol():
    from gearkit.bench.profiles import LADDER_TOLS, cam_ladder

    rows = cam_ladder(quick=True, repeats=1)
    assert [r["family"] for r in rows] == ["cam"] * len(rows)
    # every quick tol from a roller's floor, 2e-7 (r0 + stroke) = 1.5e-5 mm, up: the finer ones are refused
    assert [r["tol"] for r in rows] == [t for t in LADDER_TOLS[::2] if t >= 2e-7 * (56.7702 + 20.0)] == [0.1, 0.001]
    for r in rows:
        assert 0 < r["achieved"] <= 2.0 * r["tol"]  # the bench's promise: within 2x of the requested tol
    assert [r["vertices"] for r in rows] == sorted(r["vertices"] for r in rows)


def test_along_motion_and_along_tool_give_the_same_envelope_of_a_rolling_pin():
    """The kernel's one meshing equation solved for either unknown: a pin (arc) rolling with a disc
    generates the same curve whether solved per pin point (for the roll) or per roll (for the point)."""
    from gearkit.envelope import Branch
    from gearkit.motion import RollingMotion
    from gearkit.segments import arc

    motion = RollingMotion(blank_centre=-40.0, tool_centre=None)  # a rack's pin on a disc of radius 40
    pin = arc((0.0, 3.0), 2.0, 2.0 * math.pi, math.pi, "pin")  # the half facing the blank, clockwise
    by_tool = Branch(pin, motion, 0.0, 1.0, "near")
    pts, _, s, valid = by_tool.solve(np.linspace(0.02, 0.98, 97))
    by_motion = Branch(pin, motion, float(s[valid].min()), float(s[valid].max()), "near", along="motion")
    dense = by_motion(np.linspace(0.0, 1.0, 20001))
    assert distances_to_polyline(pts[valid], dense).max() < 1e-6  # 2e4 chords over ~10 mm: sag < 1e-7
