"""Novikov pairs: the digest's worked helical pair and formula vectors, the checks on both sides of
their limits, and the simulated transverse mesh (contact at the design point, no interference,
centre-distance sensitivity against the rack formula)."""
import math

import numpy as np
import pytest

from gearkit.checks.novikov import NovikovLimits, check_novikov
from gearkit.errors import GeometryError, SpecError
from gearkit.families.novikov import NovikovPairSpec, novikov_pair_geometry
from gearkit.families.novikov.mesh import contact_trace, mesh_contact, signed_clearance
from gearkit.families.novikov.presets import RackSystem, rack_system
from gearkit.families.novikov.racks import ArcRack, ArcSpec

D = math.radians
PRINTED = 0.6e-4  # the digest prints 4 decimals for mm and degrees here


def worked(**kw):
    args = dict(teeth1=20, teeth2=60, module=4.0, helix_angle_deg=15.0, face_width=60.0, racks="dca24")
    args.update(kw)
    return NovikovPairSpec(**args)


def test_worked_helical_pair_of_the_digest():
    g = novikov_pair_geometry(worked())
    assert g.reference_center_distance == pytest.approx(165.6442, abs=PRINTED)
    assert g.overlap_ratio == pytest.approx(1.23577, abs=0.6e-5)
    assert g.transverse_module == pytest.approx(4.14110, abs=0.6e-5)
    assert [2 * r for r in g.pitch_radii] == pytest.approx([82.8221, 248.4663], abs=PRINTED)
    assert list(g.tip_diameters) == pytest.approx([90.0221, 255.6663], abs=PRINTED)
    assert list(g.root_diameters) == pytest.approx([74.0221, 239.6663], abs=PRINTED)
    assert g.axial_pitch == pytest.approx(48.5527, abs=PRINTED)
    assert math.degrees(g.contact_angle_transverse) == pytest.approx(24.7466, abs=PRINTED)
    c0, c1 = g.contacts
    assert c0.pole_offset == pytest.approx(4.7300, abs=PRINTED)
    assert c0.height == pytest.approx(2.1802, abs=PRINTED)
    assert list(c0.radii) == pytest.approx([43.8472, 122.1445], abs=PRINTED)  # gear 1 addendum, gear 2 dedendum
    assert list(c1.radii) == pytest.approx([39.5149, 126.5018], abs=2 * PRINTED)  # 126.50185 rounds either way
    assert c0.leads[0] == pytest.approx(math.pi * 4 * 20 / math.sin(D(15)))
    # the digest's q_TA = Delta m_n / sin(beta): where the two contacts' normals cross the instantaneous axis
    assert g.pole_axial_distance == pytest.approx(44.3848, abs=PRINTED)
    assert g.pole_axial_distance / g.axial_pitch == pytest.approx(0.91416, abs=0.6e-5)
    # the contact points themselves are 2 h_k m cot(a_k) sin(beta) closer (checked by simulation below)
    assert g.pole_axial_distance - g.contact_axial_distance == pytest.approx(
        2 * c0.height / math.tan(D(24)) * math.sin(D(15)), rel=1e-4)
    assert g.transverse_contact_ratio == 0.0


def test_textbook_formula_vectors():
    beta = 15.0
    m = 2 * 150.0 * math.cos(D(beta)) / 80  # a = 150 with z = 20/60 (i = 3)
    g = novikov_pair_geometry(worked(module=m))
    assert g.reference_center_distance == pytest.approx(150.0, rel=1e-14)
    assert list(g.pitch_radii) == pytest.approx([37.5, 112.5], rel=1e-14)
    assert novikov_pair_geometry(worked(face_width=40.0)).overlap_ratio == pytest.approx(0.8238, abs=0.6e-4)
    assert novikov_pair_geometry(worked(face_width=58.26)).overlap_ratio == pytest.approx(1.2, abs=1e-4)


def test_double_arc_pole_offset_is_a_fixed_fraction_of_the_axial_pitch():
    for beta in (10.0, 15.0, 30.0):
        g = novikov_pair_geometry(worked(helix_angle_deg=beta))
        assert g.pole_axial_distance / g.axial_pitch == pytest.approx(2.87191 / math.pi, abs=0.6e-5)
    single = novikov_pair_geometry(worked(racks="single-arc"))
    assert single.contact_axial_distance is None and single.pole_axial_distance is None


def consistent_dca():
    """The dca24 rack with x_f recomputed so that both arcs reach exactly the same contact height."""
    r = rack_system("dca24").rack1
    a = r.alpha
    x_f = r.concave.radius * math.sin(a) - r.contact_height("convex")
    rack = ArcRack(24.0, 0.9, 1.1, r.convex, ArcSpec(r.concave.radius, x_f, r.concave.centre_offset), "relief-arc",
                   r.transition_radius, r.transition_angle_deg, name="dca24-exact")
    return RackSystem(rack, rack, name="dca24-exact")


def test_slices_across_the_face_touch_at_the_designed_height():
    """The helical pair set up at a contact: every transverse section is the mesh at another phase. The
    sections through the contact points touch (to the sampling tolerance) at the designed contact radius,
    one axial pitch apart for each zone and the double-arc zones contact_axial_distance apart; the
    sections between them do not touch."""
    from gearkit.families.novikov.mesh import section_clearance

    spec = worked(racks=consistent_dca())
    g = novikov_pair_geometry(spec)
    c0, c1 = mesh_contact(spec, 0, interference=False), mesh_contact(spec, 1, interference=False)
    dz = (c1.rotations[0] - c0.rotations[0]) * g.pitch_radii[0] / math.tan(g.helix_angle)
    assert dz == pytest.approx(g.contact_axial_distance, abs=1e-9 * spec.module)
    tol = 1e-5 * spec.module
    d_kappa = (1 / spec.racks.rack1.convex.radius - 1 / spec.racks.rack1.concave.radius) / spec.module
    reach = 2 * math.sqrt(2 * 2 * tol / d_kappa)  # sampled points within 2 tol of touching lie this close
    for contact, z_shift, design in ((c0, 0.0, g.contacts[0]), (c0, dz, g.contacts[1])):
        zs = contact_trace(spec, contact) + z_shift
        for z in zs[(zs >= 0) & (zs <= spec.face_width)]:
            d, p = section_clearance(spec, contact, z, tol)
            assert abs(d) <= 2 * tol
            assert abs(np.hypot(*p) - design.radii[0]) <= reach
        for z in (0.25 * g.axial_pitch, 0.5 * g.axial_pitch):
            assert section_clearance(spec, contact, z + z_shift, tol)[0] > 100 * tol


@pytest.mark.parametrize("da,expected", [(-0.02, 34.99), (-0.01, 29.35), (-0.005, 26.64), (0.005, 21.41),
                                         (0.01, 18.87), (0.02, 13.89)])
def test_centre_distance_sensitivity_table(da, expected):
    g = novikov_pair_geometry(worked(center_distance=worked().reference_center_distance + da * 4.0))
    assert math.degrees(g.operating_contact_angle) == pytest.approx(expected, abs=0.006)


def test_centre_distance_window_of_the_racks():
    lo, hi = novikov_pair_geometry(worked()).center_distance_window
    assert lo / 4.0 == pytest.approx(-0.0328, abs=0.6e-4) and hi / 4.0 == pytest.approx(0.0286, abs=0.6e-4)
    lo, hi = novikov_pair_geometry(worked(racks="single-arc")).center_distance_window
    assert hi / 4.0 > 0.06  # the digest's illustration: [-0.044, +0.068] with a vertical flank line
    outside = worked(center_distance=worked().reference_center_distance + 0.04 * 4.0)
    assert novikov_pair_geometry(outside).operating_contact_angle is None


def test_overlap_check_fails_below_one_and_says_what_to_do():
    bad = check_novikov(worked(face_width=40.0), simulate=False)
    f = bad.report["overlap_ratio"]
    assert f.status == "fail" and f.value == pytest.approx(0.8238, abs=0.6e-4) and not bad.ok
    assert "increase the helix angle beta or the face width b" in f.message
    assert "b >= 48.55 mm for 1" in f.message  # b = p_x = pi m_n / sin(beta) gives eps_beta = 1
    assert check_novikov(worked(face_width=60.0 * 1.05 / 1.23577), simulate=False).report["overlap_ratio"].status \
        == "warn"
    assert check_novikov(worked(), simulate=False).report["overlap_ratio"].status == "ok"
    spur = check_novikov(worked(helix_angle_deg=0.0), simulate=False).report["overlap_ratio"]
    assert spur.status == "fail" and "helix angle" in spur.message


def test_zero_transverse_ratio_is_reported_never_failed():
    result = check_novikov(worked(), simulate=False)
    f = result.report["transverse_contact_ratio"]
    assert f.value == 0.0 and f.status == "ok"
    assert result.report["racks"].status == "warn" and "verify against the standard" in result.report["racks"].message
    assert result.report.status == "warn" and result.ok


def test_gear_checks_on_both_sides_of_their_limits():
    dca = rack_system("dca24").rack1
    # few teeth: the concave working arc loses its contact point (undercut by the relief's ridge)
    small = check_novikov(worked(teeth1=4), simulate=False).report
    assert small["working_arc.1.concave"].status == "fail" and small["working_arc.1.convex"].status == "ok"
    assert small["center_distance_window"].status == "fail"
    # a rack whose tip line is higher than its mate's root: negative tip clearance
    tall = ArcRack(24.0, 1.15, 1.1, dca.convex, dca.concave, "relief-arc", 0.5196, dca.transition_angle_deg)
    rep = check_novikov(worked(racks=RackSystem(tall, tall, name="tall")), simulate=False).report
    assert rep["tip_clearance.1"].status == "fail" and rep["tip_clearance.1"].value == pytest.approx(-0.05)
    assert check_novikov(worked(), simulate=False).report["tip_clearance.1"].status == "ok"
    # a narrow tip land on a small pinion: the tip thins below the limit, then points
    pin, wheel = rack_system("single-arc").racks
    rep = check_novikov(worked(racks="single-arc"), simulate=False).report
    assert rep["pointing.1"].status == "warn" and rep["pointing.2"].status == "ok"
    assert check_novikov(worked(racks="single-arc"), NovikovLimits(min_tip_thickness=0.1),
                         simulate=False).report["pointing.1"].status == "ok"
    # centre distance beyond the window: the arcs would touch beyond the end of a working arc, so the
    # working flanks do not meet
    off = worked(center_distance=worked().reference_center_distance + 0.04 * 4.0)
    rep = check_novikov(off).report
    assert rep["center_distance_window"].status == "fail"
    assert rep["mesh.contact.0"].status == "fail" and "runs off the end of a working arc" in rep["mesh.contact.0"].message


@pytest.mark.parametrize("racks", ["dca24", "single-arc"])
def test_simulated_mesh_touches_at_one_point_per_zone_without_interference(racks):
    spec = worked(racks=racks)
    g = novikov_pair_geometry(spec)
    assert len(spec.racks.zones) == (2 if racks == "dca24" else 1)
    for zone, design in zip(spec.racks.zones, g.contacts):
        c = mesh_contact(spec, zone.index)
        assert c.touches == 1 and c.on_arcs
        assert c.clearance > -2 * c.tol  # chords of a sampled outline sit within tol of it
        if racks == "single-arc":  # consistent rack data: the designed point exactly
            assert list(c.radii) == pytest.approx(list(design.radii), abs=1e-9 * spec.module)
            assert c.contact_angle == pytest.approx(g.contact_angle, abs=1e-12)
        else:  # the recalled rack's heights differ by 8e-6 m: conformal arcs touch where the normal moves by
            # sin a' - sin a = (h_convex - h_concave) / (rho_f - rho_a)
            cvx, ccv = spec.racks.racks[zone.convex_gear - 1], spec.racks.racks[2 - zone.convex_gear]
            shift = (cvx.contact_height("convex") - ccv.contact_height("concave")) / zone.rho_diff
            assert math.sin(c.contact_angle) - math.sin(g.contact_angle) == pytest.approx(shift, abs=1e-7)
            assert list(c.radii) == pytest.approx(list(design.radii), abs=1e-3)
        assert math.tan(c.contact_angle_transverse) * math.cos(spec.beta) == pytest.approx(math.tan(c.contact_angle))


def _angle_error(z1, z2, da):
    spec = worked(teeth1=z1, teeth2=z2, racks="single-arc")
    a = spec.reference_center_distance
    base = mesh_contact(spec, 0, interference=False)
    moved = mesh_contact(spec, 0, a + da * spec.module, interference=False)
    zone = spec.racks.zones[0]
    predicted = math.asin(math.sin(base.contact_angle) - da / zone.rho_diff)
    return moved.contact_angle - predicted, predicted - base.contact_angle, zone


def test_centre_distance_error_moves_the_contact_angle_as_predicted():
    """+0.01 m_n moves alpha_k by -5.2 deg (single-arc preset) as sin a_k' = sin a_k - da/(rho_f - rho_a).
    The formula is the rack limit: its error at gear level is first order in the pitch-circle curvature,
    bounded by the predicted change times h_k m / r_1, and halves when the tooth numbers double."""
    err, change, zone = _angle_error(20, 60, 0.01)
    r1 = 20 * 4.0 / (2 * math.cos(D(15)))
    assert abs(err) <= abs(change) * zone.height * 4.0 / r1
    assert math.degrees(change) == pytest.approx(-4.32, abs=0.01)  # asin(0.5 - 0.01/0.15) = 25.68 deg
    err2, _, _ = _angle_error(40, 120, 0.01)
    assert 0.4 < err2 / err < 0.6
    assert abs(_angle_error(160, 480, 0.01)[0]) < math.radians(0.01)


def test_interference_is_detected():
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float)
    d = signed_clearance(np.array([[0.5, 0.5], [0.5, 1.25], [1.1, 0.5]]), square)
    assert d == pytest.approx([-0.5, 0.25, 0.1])
    from gearkit.families.novikov import tooth_profile
    from gearkit.families.novikov.mesh import _interference

    spec = worked()
    c = mesh_contact(spec, 0, interference=False)
    profiles = (tooth_profile(spec.gear(1)), tooth_profile(spec.gear(2)))
    tol = 1e-5 * spec.module
    window = 3 * math.pi * spec.module
    ok, _ = _interference(profiles, c.rotations, c.center_distance, tol, window)
    assert ok > -2 * tol
    # gear 2 turned a little further into the working flank: the outlines overlap
    pushed = (c.rotations[0], c.rotations[1] - 2e-3)
    bad, _ = _interference(profiles, pushed, c.center_distance, tol, window)
    # the flank point at R_K2 moves 2e-3 R_K2 along the circle; a good part of that is along the normal
    assert bad < -0.25 * 2e-3 * c.radii[1]


def test_clearance_sign_off_a_sharp_corner_is_the_outside():
    """A point whose nearest point is a corner that turns by more than a right angle (a tooth's tip
    corner) can lie on the inner side of one edge's line and still be outside. Oracle: the exact
    distance to the corner and ray casting for the side; then the tiny single-arc pair 8/8 (spur, m 0.5),
    whose wheel's tip corners turn by 98 deg: the scan once read its far side as 4.08 mm deep inside."""
    from matplotlib.path import Path

    from gearkit.distances import distances_to_polyline
    from gearkit.families.novikov import tooth_profile
    from gearkit.families.novikov.mesh import _rot

    sliver = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 0.2]])  # counter-clockwise, the corner at (1, 0)
    p = np.array([[2.0, -0.5], [1.5, 0.01], [0.2, 0.05]])
    want = [math.hypot(1.0, 0.5), math.hypot(0.5, 0.01), -0.05]  # the last inside, 0.05 above the base
    assert signed_clearance(p, sliver) == pytest.approx(want, abs=1e-12)

    spec = NovikovPairSpec(8, 8, 0.5, 0.0, 10.0, racks="single-arc")
    c = mesh_contact(spec, 0, interference=False)
    tol = 1e-5 * spec.module
    loops = [tooth_profile(spec.gear(k + 1)).outline(tol) @ _rot(c.rotations[k]).T
             + np.array([0.0, k * c.center_distance]) for k in (0, 1)]
    for k in (0, 1):
        got = signed_clearance(loops[k], loops[1 - k])
        dist = distances_to_polyline(loops[k], loops[1 - k], closed=True)
        inside = Path(loops[1 - k]).contains_points(loops[k])
        assert np.abs(np.abs(got) - dist).max() <= 1e-12 * spec.module
        far = dist > 2 * tol  # at the contact the side is the sampling's to choose
        assert np.array_equal(got[far] < 0, inside[far])
    assert mesh_contact(spec, 0, tol=tol).clearance > -2 * tol  # chords of a sampled outline sit within tol


def test_contact_travels_along_the_face_one_pitch_apart():
    spec = worked()
    c = mesh_contact(spec, 0, interference=False)
    g = novikov_pair_geometry(spec)
    for rot in np.linspace(0, 2 * math.pi / 20, 7):
        z = contact_trace(spec, c, rot)
        assert len(z) in (math.floor(g.overlap_ratio), math.ceil(g.overlap_ratio))
        assert np.allclose(np.diff(z), g.axial_pitch)
    assert len(contact_trace(worked(helix_angle_deg=0.0), c)) == 0
    with pytest.raises(GeometryError, match="contact zone"):
        mesh_contact(worked(racks="single-arc"), 1)


def test_a_negative_helix_is_the_left_hand_mirror_pair():
    """The sign of beta is the pinion's hand (as for an involute pair): the left-hand pair is the mirror
    image of the right-hand one, so every value but the signed angle and the hand is the same."""
    right, left = worked(), worked(helix_angle_deg=-worked().helix_angle_deg)
    assert (right.hand, left.hand) == ("right", "left")
    assert left.gear(1).helix_angle_deg == right.gear(2).helix_angle_deg < 0 < left.gear(2).helix_angle_deg
    a, b = novikov_pair_geometry(right).to_dict(), novikov_pair_geometry(left).to_dict()
    assert b.pop("helix_angle_deg") == -a.pop("helix_angle_deg") and (a.pop("hand"), b.pop("hand")) == ("right", "left")
    assert a == b
    ca, cb = mesh_contact(right, 0, interference=False), mesh_contact(left, 0, interference=False)
    assert ca.rotations == cb.rotations and ca.center_distance == cb.center_distance


def test_invalid_pair_specs():
    with pytest.raises(SpecError, match="face_width"):
        worked(face_width=0.0)
    with pytest.raises(SpecError, match="helix_angle_deg"):
        worked(helix_angle_deg=-60.0)
    with pytest.raises(SpecError, match="center_distance"):
        worked(center_distance=170.0)
    with pytest.raises(SpecError, match="unknown rack"):
        worked(racks="gost")


@pytest.mark.parametrize("racks", ["single-arc", "dca24"])
def test_helical_pair_is_free_of_interference_across_a_whole_axial_pitch(racks):
    """The transverse sections are not conjugate (run at a constant ratio in the plane they would
    overlap at other phases); the helical body's play is set by the section that touches first, the
    one solved at the contact. Every section over an axial pitch then clears, to the sampling tolerance."""
    from gearkit.families.novikov.mesh import section_clearance

    spec = worked(racks=racks)
    g = novikov_pair_geometry(spec)
    c = mesh_contact(spec, 0, interference=False)
    tol = 1e-5 * spec.module
    d = [section_clearance(spec, c, z, tol)[0] for z in np.linspace(-g.axial_pitch / 2, g.axial_pitch / 2, 25)]
    assert min(d) > -2 * tol
