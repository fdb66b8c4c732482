"""The transverse contact solve of a Novikov pair (:func:`gearkit.families.novikov.mesh.mesh_contact`)
held against oracles that share none of its code: the design point at the reference centre distance,
an independent scalar reduction of the spur single-arc mesh (the pinion's tooth is a circle, the
wheel's the parallel curve of its rack centre's trochoid), and the sampled outlines touching without
interpenetrating. Out of its working arcs' reach the contact does not exist and the solve says so."""
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings, strategies as st
from scipy.optimize import brentq

from gearkit.distances import distances_to_polyline
from gearkit.families.novikov import NovikovPairSpec, novikov_pair_geometry, tooth_profile
from gearkit.families.novikov.mesh import NoContact, mesh_contact
from gearkit.families.novikov.presets import rack_system

PINION, WHEEL = rack_system("single-arc").racks
SOLVED = 1e-9  # the solve's acceptance on the contact equations, x m (lengths) and rad
#: the contact angle moves by da / ((rho_f - rho_a) cos a) for a centre-distance change da: an acceptance of
#: SOLVED m on the equations is SOLVED / 0.15 / cos(30 deg) ~ 8 SOLVED in angle (single-arc); twice that
ANGLE = 16 * SOLVED
#: the rack angle of the contact must clear the ends of the working arcs by this (rad) for the test to
#: say on which side of them it is (far above the solve's and the oracle's round-off)
MARGIN = 1e-6


def _rot(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s], [s, c]])


def _wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def _path(centre, r):
    """Textbook rolling (rack shifted by ``roll`` along the pitch line, blank turned by roll / r): the
    rack point ``centre`` (mm, v away from the gear centre) in the blank frame, and the pitch point."""
    u, v = centre
    return (lambda s: _rot(s / r) @ np.array([u + s, r + v]),
            lambda s: _rot(s / r) @ np.array([0.0, r]))


def _spur_single_arc_oracle(spec, a_w):
    """The contact of the spur single-arc pair at ``a_w`` by a scalar reduction, or None.

    The pinion's convex arc has its centre on the pitch line, so its tooth is the circle of radius
    rho_a about C_1 (the centre's image on the pitch circle). The wheel's concave tooth is the parallel
    curve, at rho_f, of the trochoid T(s) its rack centre describes; that curve's normal at T(s) passes
    through the generating pitch point Q(s). Internally tangent, the two teeth touch where C_1 lies on
    that normal at rho_f - rho_a from T; the pair condition puts the pole P on it too. So for each roll s
    the wheel's turn is the one that brings the line T Q through P, C_1 is where that line meets the
    pinion's pitch circle, and |C_1 - T| = rho_f - rho_a is one equation in s.
    Returns the contact point, gear 1's outward normal there, both rotations, and the rack angles of
    the contact on the convex arc (theta) and the concave arc (psi).
    """
    m, z1, z2 = spec.module, spec.teeth1, spec.teeth2
    r1, r2 = m * z1 / 2, m * z2 / 2
    rho_a, rho_f = PINION.convex.radius * m, WHEEL.concave.radius * m
    u1 = PINION.centre("convex")[0] * m
    c1_blank = _rot(-u1 / r1) @ np.array([0.0, r1])
    trochoid, pitch = _path(WHEEL.centre("concave") * m, r2)
    r_p = a_w * z2 / (z1 + z2)
    pole, o2 = np.array([0.0, a_w - r_p]), np.array([0.0, a_w])

    def place(s):
        t, q = trochoid(s), pitch(s)
        e = (t - q) / np.hypot(*(t - q))
        b = q @ e
        disc = b * b - q @ q + r_p * r_p
        if disc < 0:  # the normal misses the pole's circle
            return None
        p_b = q + min(-b + math.sqrt(disc), -b - math.sqrt(disc), key=abs) * e
        turn = math.atan2(-r_p, 0.0) - math.atan2(p_b[1], p_b[0])
        t2, e2 = _rot(turn) @ t + o2, _rot(turn) @ e  # placed about the wheel's centre
        b = t2 @ e2
        disc = b * b - t2 @ t2 + r1 * r1
        if disc < 0:  # the normal misses the pinion's pitch circle
            return None
        k = min((-b + sgn * math.sqrt(disc) for sgn in (1, -1)), key=lambda k: np.hypot(*(t2 + k * e2 - pole)))
        return t2, k, e2, turn

    def gap(s):  # C_1 = T - (rho_f - rho_a) e: gear 1's outward normal -e points from T through C_1
        placed = place(s)
        return math.nan if placed is None else -placed[1] - (rho_f - rho_a)

    rolls = np.linspace(-1.5 * math.pi * m, 1.5 * math.pi * m, 301)
    g = np.array([gap(s) for s in rolls])
    found = []
    for i in np.flatnonzero(g[:-1] * g[1:] < 0):
        s = brentq(gap, rolls[i], rolls[i + 1], xtol=1e-15 * m, rtol=1e-15)
        t2, k, e2, turn = place(s)
        c1, u = t2 + k * e2, -e2
        phi1 = math.atan2(c1[1], c1[0]) - math.atan2(c1_blank[1], c1_blank[0])
        theta = math.atan2(*(_rot(-phi1) @ u)[::-1]) + u1 / r1  # rack angles: K_a = O_a + rho_a (cos, sin)
        psi = math.atan2(*(-(_rot(-turn - s / r2) @ u))[::-1])  # K_f = O_f - rho_f (cos, sin)
        found.append((c1 + rho_a * u, u, (phi1, turn), (theta, psi)))
    # the contact nearest the design point: rack angles nearest alpha_k (the other roots are the circles'
    # far sides, or the mirrored flank)
    alpha = PINION.alpha
    return min(found, key=lambda r: abs(_wrap(r[3][0] - alpha)) + abs(_wrap(r[3][1] - alpha)), default=None)


def _inside(angle, window, margin=0.0):
    return window[0] + margin <= angle <= window[1] - margin


def _flank_state(spec, c):
    """Gear 2's point and outward normal at the contact's flank parameter, placed by the contact's
    rotation (rotation matrices here, not the solve's code), and both parameters."""
    zone = spec.racks.zones[c.zone]
    which = ("convex", "concave") if zone.convex_gear == 1 else ("concave", "convex")
    q, n, _, valid = tooth_profile(spec.gear(2)).working_branch(which[1]).solve(np.array([c.flank_params[1]]))
    assert valid[0]
    turn = _rot(c.rotations[1])
    return turn @ q[0] + np.array([0.0, c.center_distance]), turn @ n[0]


def _assert_a_contact(spec, c):
    """What every solved contact is: both points inside their branches' domains, the same point, the
    outward normals opposite (not the same direction: interpenetrating flanks), the common normal
    through the pole, and the phase within half a pitch of the design phase (not whole pitches away)."""
    m = spec.module
    assert all(0.0 <= w <= 1.0 for w in c.flank_params)
    p2, m2 = _flank_state(spec, c)
    assert np.abs(p2 - c.point).max() <= SOLVED * m
    assert float(c.normal @ m2) == pytest.approx(-1.0, abs=SOLVED)
    pole = np.array([0.0, c.center_distance * spec.teeth1 / (spec.teeth1 + spec.teeth2)])
    d = c.point - pole
    assert abs(d[0] * c.normal[1] - d[1] * c.normal[0]) <= SOLVED * m
    design = mesh_contact(spec, c.zone, spec.reference_center_distance, interference=False)  # the design point
    assert abs(c.rotations[0] - design.rotations[0]) < math.pi / spec.teeth1
    assert abs(c.play) < math.pi / spec.teeth2


modules = st.sampled_from([0.5, 1.0, 3.0, 10.0])


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(z1=st.integers(8, 60), dz=st.integers(0, 100), m=modules, frac=st.floats(-1.5, 1.5))
def test_spur_single_arc_contact_is_the_scalar_reduction(z1, dz, m, frac):
    """Inside the working arcs the solve finds the contact the reduction finds (point, normal and both
    phases); where the reduction's contact lies beyond an arc's end the solve reports no contact."""
    spec = NovikovPairSpec(z1, z1 + dz, m, 0.0, 20.0 * m, racks="single-arc")
    g = novikov_pair_geometry(spec)
    lo, hi = g.center_distance_window
    a_w = g.reference_center_distance + frac * (hi if frac > 0 else -lo)
    want = _spur_single_arc_oracle(spec, a_w)
    inside = want is not None and _inside(want[3][0], PINION.geometry.convex_window, MARGIN) and \
        _inside(want[3][1], WHEEL.geometry.concave_window, MARGIN)
    outside = want is None or not (_inside(want[3][0], PINION.geometry.convex_window, -MARGIN) and
                                   _inside(want[3][1], WHEEL.geometry.concave_window, -MARGIN))
    if outside:
        with pytest.raises(NoContact, match="runs off the end of a working arc|no point near"):
            mesh_contact(spec, 0, a_w, interference=False)
        return
    c = mesh_contact(spec, 0, a_w, interference=False)
    _assert_a_contact(spec, c)
    if not inside:  # within MARGIN of an arc's end: either answer is right
        return
    point, normal, (phi1, turn), _ = want
    assert np.abs(c.point - point).max() <= SOLVED * m / 0.15 * 2  # lengths move da / (rho_f - rho_a) per da
    assert np.abs(c.normal - normal).max() <= ANGLE
    assert c.rotations[0] == pytest.approx(phi1, abs=ANGLE)
    assert _wrap(c.rotations[1] - turn) == pytest.approx(0.0, abs=ANGLE)
    gen = (tooth_profile(spec.gear(1)), tooth_profile(spec.gear(2)))
    theta, psi = want[3]
    if gen[0].on_working_arc("convex", theta, -MARGIN) and gen[1].on_working_arc("concave", psi, -MARGIN):
        assert c.on_arcs
    elif not (gen[0].on_working_arc("convex", theta, MARGIN) and gen[1].on_working_arc("concave", psi, MARGIN)):
        assert not c.on_arcs


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(z1=st.integers(8, 60), dz=st.integers(0, 100), m=modules, beta=st.floats(0.0, 30.0),
       racks=st.sampled_from(["single-arc", "dca24"]), zone=st.integers(0, 1))
def test_at_the_reference_centre_distance_the_contact_is_the_design_point(z1, dz, m, beta, racks, zone):
    """Closed forms of the pair geometry: at a the contact has the rack's contact angle and lies on the
    contact-helix radii R_K = sqrt((r +- h_k m)^2 + X^2). The recalled double-arc rack's two contact
    heights differ (by 8e-6 m): conformal arcs then touch where sin a moves by that difference over
    rho_f - rho_a, and the radii move by the corresponding slide along the arcs."""
    spec = NovikovPairSpec(z1, z1 + dz, m, beta, 20.0 * m, racks=racks)
    zone = zone % len(spec.racks.zones)
    g = novikov_pair_geometry(spec)
    c = mesh_contact(spec, zone, interference=False)
    _assert_a_contact(spec, c)
    zn = spec.racks.zones[zone]
    cvx, ccv = spec.racks.racks[zn.convex_gear - 1], spec.racks.racks[2 - zn.convex_gear]
    shift = (cvx.contact_height("convex") - ccv.contact_height("concave")) / zn.rho_diff
    assert math.sin(c.contact_angle) - math.sin(g.contact_angle) == pytest.approx(shift, abs=ANGLE)
    slide = abs(shift) / math.cos(g.contact_angle) * cvx.convex.radius * m  # arc length the contact moves
    assert list(c.radii) == pytest.approx(list(g.contacts[zone].radii), abs=SOLVED * m + 2 * slide)


#: pairs on which the undamped iteration wandered off the flanks and accepted a root far from the
#: design point (phase thousands of radians away, or normals in the same direction: interpenetration),
#: or a "contact" on the arc's circle beyond its end. (z1, z2, m_n, beta deg, a_w - a in m_n)
WANDERING = [(10, 107, 0.5, 20.277666558374243, 0.38202401084078108),
             (27, 63, 10.0, 23.76581147676268, -0.1835936931738592),
             (31, 95, 0.5, 12.723359978384558, -0.09819341835508866),
             (51, 109, 0.5, 27.789726221274947, 0.4494158208),
             (60, 128, 1.0, 11.34040045378465, 0.44736671841256237),
             (54, 100, 3.0, 9.77183876074978, -0.035904021292571753)]


@pytest.mark.parametrize("z1,z2,m,beta,da", WANDERING)
def test_no_contact_where_the_rack_formula_puts_it_beyond_the_arcs(z1, z2, m, beta, da):
    """The rack formula sin a' = sin a - da / (rho_f - rho_a) puts the contact at least 2 deg beyond the
    working arcs here (or has no solution at all); its error at gear level is far smaller (the centre-
    distance test in test_novikov_pair). So there is no contact, and the check says the pair does not mesh."""
    from gearkit.checks.novikov import check_novikov

    spec = NovikovPairSpec(z1, z2, m, beta, 20.0 * m)
    zone = spec.racks.zones[0]
    s = math.sin(spec.racks.rack1.alpha) - da / zone.rho_diff
    lo = max(spec.racks.rack1.geometry.convex_window[0], spec.racks.rack1.geometry.concave_window[0])
    hi = min(spec.racks.rack1.geometry.convex_window[1], spec.racks.rack1.geometry.concave_window[1])
    assert not -1 < s < 1 or not lo - math.radians(2) < math.asin(s) < hi + math.radians(2)
    a_w = spec.reference_center_distance + da * m
    for nudge in (0.0, 1.0, -1.0):  # the last bit of a_w changes nothing
        with pytest.raises(NoContact):
            mesh_contact(spec, 0, a_w + nudge * math.ulp(a_w), interference=False)
    if abs(da) <= 0.5:
        rep = check_novikov(NovikovPairSpec(z1, z2, m, beta, 20.0 * m, center_distance=a_w)).report
        assert rep["mesh.contact.0"].status == "fail" and "do not meet" in rep["mesh.contact.0"].message


#: the rack formula is the limit of infinite pitch radii: at gear level its sin a' is off by a first-order
#: term in the pitch circles' curvature, |a' - a| h_k m / r_min with a coefficient of order one (1.33 the
#: largest over 200 random pairs); three times that term separates "surely on the arcs" from "surely off"
RACK_FORMULA = 3.0


def _beyond_generated_arcs(spec, c):
    """Per gear: how far (rad) the contact's rack angle lies beyond the pieces of its working arc that
    survive on the generated tooth (negative: inside one, by that much from its nearer end), and the
    arc's radius (x m_n)."""
    zone = spec.racks.zones[c.zone]
    which = ("convex", "concave") if zone.convex_gear == 1 else ("concave", "convex")
    out = []
    for k in (0, 1):
        prof = tooth_profile(spec.gear(k + 1))
        ang = float(prof.rack_angle(which[k], c.flank_params[k]))
        beyond = min((max(lo - ang, ang - hi) for lo, hi in prof.working_windows(which[k])), default=math.inf)
        out.append((beyond, getattr(prof.spec.rack, which[k]).radius))
    return out


#: a contact this far (rad) beyond a surviving arc's end lies rho * angle along the arc's circle past the
#: cut (the tip circle, the relief's ridge or a fold), which crosses the arc steeply: over 400 random pairs
#: the point was 0.5 rho * angle or more from the outline; the test asserts half of that
CUT_CROSSING = 0.25


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(z1=st.integers(8, 60), dz=st.integers(0, 100), m=modules, beta=st.floats(0.0, 30.0),
       racks=st.sampled_from(["single-arc", "dca24"]), zone=st.integers(0, 1), frac=st.floats(-1.5, 1.5))
@example(z1=8, dz=0, m=0.5, beta=0.0, racks="dca24", zone=0, frac=0.5)  # the relief cut the concave arc there
def test_contact_over_random_pairs_and_centre_distances(z1, dz, m, beta, racks, zone, frac):
    """Every pair and centre distance: where the rack formula surely puts the contact on the working arcs
    the solve finds it, a true contact (opposite normals, on both flanks, the design phase), near the
    formula's angle. Where it lies on the arcs that survive on the generated teeth, the placed outlines
    touch there without interpenetrating; where it lies on a stretch of an arc that the generation cut
    away (a few-toothed gear's relief ridge climbs its concave arc, its tip circle trims the convex one),
    it is not on the arcs and the cut gear's sampled outline misses it. Where the formula surely puts it
    beyond an arc's end, the solve reports no contact."""
    spec = NovikovPairSpec(z1, z1 + dz, m, beta, 20.0 * m, racks=racks)
    zone = zone % len(spec.racks.zones)
    zn = spec.racks.zones[zone]
    g = novikov_pair_geometry(spec)
    lo, hi = g.center_distance_window
    da = frac * (hi if frac > 0 else -lo)
    cvx, ccv = spec.racks.racks[zn.convex_gear - 1], spec.racks.racks[2 - zn.convex_gear]
    shift = (cvx.contact_height("convex") - ccv.contact_height("concave")) / zn.rho_diff
    alpha = spec.racks.rack1.alpha
    s = math.sin(alpha) + shift - da / m / zn.rho_diff
    win = (max(cvx.geometry.convex_window[0], ccv.geometry.concave_window[0]),
           min(cvx.geometry.convex_window[1], ccv.geometry.concave_window[1]))
    slack = RACK_FORMULA * abs(da / m / zn.rho_diff) * zn.height * m / min(g.pitch_radii) + MARGIN
    a_w = g.reference_center_distance + da
    if not math.sin(win[0]) - slack < s < math.sin(win[1]) + slack:
        with pytest.raises(NoContact):
            mesh_contact(spec, zone, a_w, interference=False)
        return
    if not math.sin(win[0]) + slack < s < math.sin(win[1]) - slack:
        return  # too near an arc's end for the formula to say
    c = mesh_contact(spec, zone, a_w, interference=False)
    _assert_a_contact(spec, c)
    assert abs(math.sin(c.contact_angle) - s) <= slack
    beyond = _beyond_generated_arcs(spec, c)
    tol = 1e-4 * m
    if all(out < -MARGIN for out, _ in beyond):
        assert c.on_arcs
        _assert_touching(spec, c, tol)
    elif any(out > MARGIN for out, _ in beyond):  # on a stretch of an arc that the generation cut away
        assert not c.on_arcs
        for k, (out, rho) in enumerate(beyond):
            if CUT_CROSSING * rho * m * out > 2 * tol:
                loop = tooth_profile(spec.gear(k + 1)).outline(tol) @ _rot(c.rotations[k]).T \
                    + np.array([0.0, k * c.center_distance])
                assert distances_to_polyline(c.point[None, :], loop, closed=True)[0] > 2 * tol
    nudged = mesh_contact(spec, zone, a_w + math.ulp(a_w), interference=False)  # the last bit picks no other root
    assert np.abs(nudged.point - c.point).max() <= SOLVED * m and abs(nudged.contact_angle - c.contact_angle) <= ANGLE


def _assert_touching(spec, c, tol):
    """The sampled outlines, placed at the contact's rotations, pass through the contact point and do
    not overlap within half a module of it (inside-ness by ray casting, not the kernel's clearance)."""
    from matplotlib.path import Path

    loops = [tooth_profile(spec.gear(k + 1)).outline(tol) @ _rot(c.rotations[k]).T
             + np.array([0.0, k * c.center_distance]) for k in (0, 1)]
    for loop in loops:  # chords of a sampled outline lie within tol of the exact tooth
        assert distances_to_polyline(c.point[None, :], loop, closed=True)[0] <= 2 * tol
    for k in (0, 1):
        near = loops[k][np.hypot(*(loops[k] - c.point).T) < 0.5 * spec.module]
        assert len(near) > 2
        inside = Path(loops[1 - k]).contains_points(near)
        depth = distances_to_polyline(near[inside], loops[1 - k], closed=True)
        assert not len(depth) or depth.max() <= 2 * tol
