"""Pair geometry against the textbook's worked examples (reference digest 3.1, 3.2) and
closed-form identities (digest 1.9-1.13, 5.7-5.12).

Tolerances: a printed value with d decimals is matched to half a unit of its last digit,
``printed(d) = 0.5 * 10**-d``; identities between two exact formulas to ``EXACT = 1e-12`` (relative).
"""
import math

import numpy as np
import pytest

from gearkit.curves import inv
from gearkit.errors import SpecError
from gearkit.pair import PairSpec, pair_geometry
from gearkit.families.involute import BasicRack, ShaperCutter

EXACT = 1e-12


def printed(decimals):
    return 0.5 * 10.0 ** -decimals


BETA = 20.5  # 20 deg 30'
COS_B = math.cos(math.radians(BETA))
# the textbook's transverse shifts xi = x_n cos(beta)
HELICAL = PairSpec(8, 14, 6.0, 0.45 / COS_B, 0.03 / COS_B, helix_angle_deg=BETA, face_width=9 * 6.0)
SHAPER = ShaperCutter(20, addendum=1.3)  # medium-worn shaper, x_u + x_c = 1.3
INTERNAL = PairSpec(46, 49, 8.0, 0.0, 0.52, kind="internal", shift_convention="cutter", tool1=SHAPER, tool2=SHAPER)


def dms(deg, minutes, seconds):
    return deg + minutes / 60 + seconds / 3600


# ----------------------------------------------------------------------------- textbook 3.1
def test_helical_example_mesh():
    g = pair_geometry(HELICAL)
    assert math.degrees(g.working_pressure_angle) == pytest.approx(dms(26, 13, 49), abs=0.5 / 3600)
    assert inv(g.working_pressure_angle) == pytest.approx(0.0349129, abs=printed(7))
    assert math.tan(g.transverse_pressure_angle) == pytest.approx(0.388578, abs=printed(6))
    assert g.transverse_module == pytest.approx(6.40566, abs=printed(5))
    # y and dy in the textbook's transverse-module units
    assert g.center_distance_modification_coeff * COS_B == pytest.approx(0.430149, abs=printed(6))
    assert g.tip_shortening_coeff * COS_B == pytest.approx(0.0498505, abs=printed(7))
    assert g.center_distance == pytest.approx(73.2176, abs=printed(4))
    assert [x.tip_diameter / 2 for x in g.gears] == pytest.approx([34.1858, 50.7124], abs=printed(4))


def test_helical_example_contact_and_thickness():
    g = pair_geometry(HELICAL)
    assert g.contact_ratio == pytest.approx(1.10997, abs=printed(5))
    assert g.contact_ratio_nominal == pytest.approx(1.10997, abs=printed(5))  # no undercut: real = nominal
    assert g.overlap_ratio == pytest.approx(1.00327, abs=printed(5))
    assert g.total_contact_ratio == pytest.approx(2.11324, abs=printed(5))
    assert [x.tip_thickness for x in g.gears] == pytest.approx([2.13312, 4.73721], abs=printed(5))


def test_helical_example_sliding_and_pressure():
    g = pair_geometry(HELICAL)
    u = 14 / 8
    z1_a, z2_a = g.sliding_at(g.path["A"])
    z1_e, z2_e = g.sliding_at(g.path["E"])
    assert z1_a == pytest.approx(-3.50974, abs=printed(5))  # lambda1(B1)
    assert abs(z2_a) / u == pytest.approx(0.444719, abs=printed(6))  # lambda2(B1)
    assert abs(z1_e) == pytest.approx(0.815417, abs=printed(6))  # lambda1(B2)
    assert z2_e == pytest.approx(-4.41761, abs=printed(5))
    assert abs(z2_e) / u == pytest.approx(2.52435, abs=printed(5))  # lambda2(B2)
    assert g.pressure_coeff == pytest.approx(0.855407, abs=printed(6))
    assert g.specific_sliding["start"] == pytest.approx((z1_a, z2_a), rel=EXACT)


# ----------------------------------------------------------------------------- textbook 3.2
def test_internal_example():
    g = pair_geometry(INTERNAL)
    assert g.center_distance == pytest.approx(14.9869, abs=printed(4))
    assert math.degrees(g.working_pressure_angle) == pytest.approx(dms(41, 12, 1.8), abs=0.05 / 3600)
    assert inv(g.working_pressure_angle) == pytest.approx(0.156365, abs=printed(6))
    assert g.center_distance_modification_coeff == pytest.approx(0.373368, abs=printed(6))
    assert g.tip_shortening_coeff == pytest.approx(-0.146632, abs=printed(6))
    assert g.contact_ratio_nominal == pytest.approx(1.92561, abs=printed(5))
    assert [x.tip_diameter / 2 for x in g.gears] == pytest.approx([193.173, 190.987], abs=printed(3))
    assert g.gears[1].thickness_coeff == pytest.approx(-0.424382, abs=printed(6))
    s2 = 8.0 * (math.pi / 2 + g.gears[1].thickness_coeff)
    assert s2 == pytest.approx(9.17132, abs=printed(5))
    assert g.tip_clearance == pytest.approx((2.4, 2.4), abs=1e-9)
    assert g.gears[1].root_diameter / 2 == pytest.approx(210.560, abs=printed(3))
    # tip-fillet conditions 3.127 / 3.128: rho_l1 <= rho_p1 and rho_p2 <= rho_l2
    assert g.gears[0].form_roll == pytest.approx(40.0856, abs=printed(4))
    assert g.path["A"] == pytest.approx(40.6636, abs=printed(4))
    assert g.gears[1].form_roll == pytest.approx(100.769, abs=printed(3))
    assert g.path["E"] + g.line_of_action == pytest.approx(96.0126, abs=printed(4))


def test_internal_example_real_path_is_trimmed_beyond_nu():
    """At x2 = 0.52 the ring's tip lies 0.007 mm inside O2N_u (digest 3.2): the real path starts
    there, so the real contact ratio is slightly below the textbook's tip-to-tip 1.92561."""
    g = pair_geometry(INTERNAL)
    rb2 = g.gears[1].base_diameter / 2
    o2nu = 190.994  # digest: O2N_u, printed to 3 decimals
    start = -g.line_of_action + math.sqrt(o2nu ** 2 - rb2 ** 2)
    assert g.path["T2"] == pytest.approx(start, abs=2 * printed(3))
    assert g.path_real[0] == g.path["T2"]
    assert g.contact_ratio == pytest.approx((g.path["E"] - g.path["T2"]) / g.base_pitch, rel=EXACT)
    assert g.contact_ratio < g.contact_ratio_nominal


# ----------------------------------------------------------------------------- closed forms
@pytest.mark.parametrize("z1,z2,x1,x2,beta", [(20, 40, 0.0, 0.0, 0.0), (13, 16, 0.3, 0.2, 0.0),
                                              (17, 53, 0.4, -0.3, 15.0), (9, 31, 0.6, 0.1, 30.0)])
def test_external_rack_cut_formulas(z1, z2, x1, x2, beta):
    """Digest 5.7 with ISO 21771 normal-system conversions; tip shortening keeps c = c* m_n."""
    m = 2.5
    g = pair_geometry(PairSpec(z1, z2, m, x1, x2, helix_angle_deg=beta))
    an = math.radians(20.0)
    at = math.atan(math.tan(an) / math.cos(math.radians(beta)))
    mt = m / math.cos(math.radians(beta))
    aw = g.working_pressure_angle
    assert inv(aw) == pytest.approx(inv(at) + 2 * math.tan(an) * (x1 + x2) / (z1 + z2), rel=EXACT)
    a = (z1 + z2) * mt / 2
    assert g.center_distance == pytest.approx(a * math.cos(at) / math.cos(aw), rel=EXACT)
    y = (g.center_distance - a) / m
    assert g.tip_shortening_coeff == pytest.approx(x1 + x2 - y, abs=EXACT)
    assert g.tip_shortening_coeff >= -EXACT  # rack-cut: never negative
    assert g.tip_clearance == pytest.approx((0.25 * m, 0.25 * m), rel=1e-10)
    # contact ratio, textbook 3.131 in the transverse section
    z = np.array([z1, z2])
    ra = np.array([x.tip_diameter for x in g.gears]) / 2
    rb = z * mt * math.cos(at) / 2
    eps = np.sum(z / (2 * math.pi) * (np.sqrt(ra ** 2 / rb ** 2 - 1) - math.tan(aw)))
    assert g.contact_ratio_nominal == pytest.approx(eps, rel=EXACT)
    p = g.path
    assert p["D"] - p["A"] == pytest.approx(g.base_pitch, rel=EXACT)
    assert p["E"] - p["B"] == pytest.approx(g.base_pitch, rel=EXACT)
    assert p["C"] == pytest.approx(rb[0] * math.tan(aw), rel=EXACT)
    assert g.base_pitch_normal == pytest.approx(math.pi * m * math.cos(an), rel=EXACT)
    assert math.tan(g.base_helix_angle) == pytest.approx(math.tan(math.radians(beta)) * math.cos(at), abs=EXACT)


def test_standard_tip_rule_and_given_tips():
    spec = PairSpec(13, 16, 1.0, 0.5, 0.5, tip_rule="standard")
    g = pair_geometry(spec)
    assert [x.tip_diameter for x in g.gears] == pytest.approx([13 + 2 * 1.5, 16 + 2 * 1.5], rel=EXACT)
    g = pair_geometry(PairSpec(13, 16, 1.0, 0.5, 0.5, tip_diameter1=15.5, tip_diameter2=18.9))
    assert (g.gears[0].tip_diameter, g.gears[1].tip_diameter) == (15.5, 18.9)


def test_blocking_contour_sample_points():
    """Digest 2.2 sample points for z1 = 13, z2 = 16 (rack-cut, tips with dy): all columns."""
    rows = [  # xi1, xi2, alpha_w, a_w, y, dy, r_a1, r_a2, s_a1, s_a2, eps, rho_p1-rho_l1, rho_p2-rho_l2, zeta1(A), zeta2(E)
        (0.3, 0.2, 24.3148, 14.9518, 0.451817, 0.0481828, 7.75182, 9.15182, 0.533439, 0.636400, 1.29945,
         0.760526, 0.986143, 3.52594, 3.24696),
        (0.5, 0.5, 27.3734, 15.3436, 0.843575, 0.156425, 7.84357, 9.34357, 0.568946, 0.627232, 1.15671,
         0.744767, 0.859747, 1.99362, 1.83801),
        (0.8, 0.3, 27.8980, 15.4173, 0.917308, 0.182692, 8.11731, 9.11731, 0.393414, 0.764512, 1.11487,
         0.416694, 1.17793, 1.03956, 2.52360),
    ]
    for row in rows:
        g = pair_geometry(PairSpec(13, 16, 1.0, row[0], row[1]))
        got = (math.degrees(g.working_pressure_angle), g.center_distance, g.center_distance_modification_coeff,
               g.tip_shortening_coeff, g.gears[0].tip_diameter / 2, g.gears[1].tip_diameter / 2,
               g.gears[0].tip_thickness, g.gears[1].tip_thickness, g.contact_ratio,
               g.path["A"] - g.path["F1"], g.path["F2"] - g.path["E"],
               abs(g.sliding_at(g.path["A"])[0]), abs(g.sliding_at(g.path["E"])[1]))
        for value, want in zip(got, row[2:]):
            digits = len(f"{want:.6g}".split(".")[1])
            assert value == pytest.approx(want, abs=printed(digits))


def test_sliding_end_formulas_equal_curvature():
    """Digest 1.12: the textbook's end-point formulas 3.137-3.140 equal the ISO zeta, to 1e-12."""
    for spec in (HELICAL, INTERNAL):
        g = pair_geometry(spec)
        z1, z2 = (x.teeth for x in g.gears)
        tw = math.tan(g.working_pressure_angle)
        ta1, ta2 = (math.sqrt((x.tip_diameter / x.base_diameter) ** 2 - 1) for x in g.gears)
        u = z2 / z1
        if spec.kind == "external":
            zc = z1 + z2
            lam = [zc * (ta2 - tw) / (zc * tw - z2 * ta2), (1 - tw / ta2) * (1 + z1 / z2),
                   (1 - tw / ta1) * (1 + z1 / z2), z1 * (ta1 - tw) * (1 + z1 / z2) / (zc * tw - z1 * ta1)]
        else:
            zp = z2 - z1
            lam = [zp * (tw - ta2) / (z2 * ta2 - zp * tw), (tw / ta2 - 1) * (1 - z1 / z2),
                   (1 - tw / ta1) * (1 - z1 / z2), z1 * (ta1 - tw) * (1 - z1 / z2) / (zp * tw + z1 * ta1)]
        za, zb = g.sliding_at(np.array([g.path["A"], g.path["E"]]))
        iso = [abs(za[0]), abs(zb[0]) / u, abs(za[1]), abs(zb[1]) / u]
        # the formulas give magnitudes; in the internal example the whole path lies before C
        assert iso == pytest.approx(np.abs(lam), rel=EXACT)


def test_pressure_coefficient_formulas():
    """Digest 1.13, 3.144/3.145 (transverse): theta = 2 (i +- 1)^2 / (z_sum i tan a_w cos a_t)."""
    for spec in (HELICAL, INTERNAL, PairSpec(20, 40, 2.0, 0.2, 0.1)):
        g = pair_geometry(spec)
        z1, z2 = (x.teeth for x in g.gears)
        i = z2 / z1
        at, tw = g.transverse_pressure_angle, math.tan(g.working_pressure_angle)
        if spec.kind == "external":
            want = 2 * (i + 1) ** 2 / ((z1 + z2) * i * tw * math.cos(at))
        else:
            want = 2 * (i - 1) ** 2 / ((z2 - z1) * i * tw * math.cos(at))
        assert g.pressure_coeff == pytest.approx(want, rel=EXACT)


def test_rack_pair_limits():
    """A rack pair: alpha_w = alpha_t, the contact ratio of 3.131 with a rack, and the rack-with-rack
    limit 4 h_a*/(pi sin 2a) = 1.98081 (digest 3.3) as z1 grows."""
    m, x = 1.5, 0.3
    g = pair_geometry(PairSpec(12, None, m, x, kind="rack"))
    al = math.radians(20.0)
    assert g.working_pressure_angle == al
    assert g.center_distance == pytest.approx(12 * m / 2 + x * m, rel=EXACT)
    r, rb = 6 * m, 6 * m * math.cos(al)
    ra = r + m * (1 + x)
    eps = (math.sqrt(ra ** 2 - rb ** 2) - r * math.sin(al) + (1 - x) * m / math.sin(al)) / (math.pi * m * math.cos(al))
    assert g.contact_ratio_nominal == pytest.approx(eps, rel=EXACT)
    big = pair_geometry(PairSpec(100000, None, 1.0, kind="rack"))
    assert big.contact_ratio_nominal == pytest.approx(4 / (math.pi * math.sin(2 * al)), abs=1e-4)
    assert round(4 / (math.pi * math.sin(2 * al)), 5) == 1.98081


def test_backlash_from_thinning_and_centre_distance():
    spec = PairSpec(17, 53, 2.0, 0.2, -0.1, helix_angle_deg=12.0)
    g0 = pair_geometry(spec)
    assert abs(g0.backlash) < 1e-12
    thin = pair_geometry(PairSpec(17, 53, 2.0, 0.2, -0.1, helix_angle_deg=12.0, thinning1=0.03, thinning2=0.05))
    # ISO 21771: a thickness change ds_n gives ds_n / cos(b) on the reference circle, scaled to d_w
    want = 0.08 / math.cos(g0.helix_angle) * math.cos(g0.transverse_pressure_angle) / math.cos(g0.working_pressure_angle)
    assert thin.backlash == pytest.approx(want, rel=1e-12)
    assert thin.backlash_normal == pytest.approx(want * math.cos(g0.working_pressure_angle) * math.cos(g0.base_helix_angle),
                                                 rel=1e-12)
    # a small centre distance increase da opens j_t ~ 2 da tan(a_wt) (first order)
    da = 1e-4
    wide = pair_geometry(PairSpec(17, 53, 2.0, 0.2, -0.1, helix_angle_deg=12.0, center_distance=g0.center_distance + da))
    assert wide.backlash == pytest.approx(2 * da * math.tan(g0.working_pressure_angle), rel=1e-3)
    rack = pair_geometry(PairSpec(15, None, 2.0, 0.1, kind="rack", center_distance=15.0 + 0.2 + 0.01))
    assert rack.backlash == pytest.approx(2 * 0.01 * math.tan(math.radians(20.0)), rel=1e-12)


# ----------------------------------------------------------------------------- validation
@pytest.mark.parametrize("kwargs,field", [
    (dict(teeth1=2, teeth2=30, module=1.0), "teeth1"),
    (dict(teeth1=12, teeth2=30, module=0.0), "module"),
    (dict(teeth1=12, teeth2=30, module=1.0, kind="bevel"), "kind"),
    (dict(teeth1=12, teeth2=30, module=1.0, shift1=4.0), "shift1"),
    (dict(teeth1=12, teeth2=30, module=1.0, kind="internal", shift_convention="cutter"), "tool2"),
    (dict(teeth1=30, teeth2=30, module=1.0, kind="internal", shift_convention="cutter", tool2=ShaperCutter(20)), "teeth2"),
    (dict(teeth1=12, teeth2=30, module=1.0, kind="rack"), "teeth2"),
    (dict(teeth1=12, teeth2=30, module=1.0, pressure_angle_deg=25.0, tool1=BasicRack()), "pressure_angle_deg"),
    (dict(teeth1=12, teeth2=40, module=1.0, kind="internal", shift_convention="cutter", tool2=ShaperCutter(20), thinning2=0.01), "thinning2"),
    (dict(teeth1=12, teeth2=30, module=1.0, center_distance=19.0), "center_distance"),
    (dict(teeth1=12, teeth2=30, module=1.0, tip_rule="long"), "tip_rule"),
    (dict(teeth1=12, teeth2=30, module=1.0, helix_angle_deg=61.0), "helix_angle_deg"),
    (dict(teeth1=12, teeth2=30, module=1.0, shift1=-3.0, shift2=-3.0), "shift1"),
])
def test_bad_input_names_the_field(kwargs, field):
    with pytest.raises(SpecError) as err:
        pair_geometry(PairSpec(**kwargs))
    assert err.value.field == field


def test_pair_matches_the_generated_gears():
    """The tool formulas (tips, roots, form circles, tip thickness) agree with the kernel's generated
    teeth, which are computed by an independent envelope method; atol = 1e-8 m."""
    from gearkit.pair import gear_specs
    from gearkit.families.involute import tooth_profile

    for spec in (HELICAL, INTERNAL, PairSpec(19, 37, 3.0, 0.25, -0.1)):
        g = pair_geometry(spec)
        tol = 1e-8 * spec.module
        for gear, gspec in zip(g.gears, gear_specs(spec)):
            prof = tooth_profile(gspec)
            assert prof.root_diameter == pytest.approx(gear.root_diameter, abs=tol)
            assert prof.form_diameter == pytest.approx(gear.form_diameter, abs=tol)
            assert prof.tip_diameter == pytest.approx(gear.tip_diameter, abs=tol)
            s_ref = gear.reference_diameter / 2 * 2 * ((math.pi / 2 + gear.thickness_coeff) / gear.teeth)
            assert prof.tooth_thickness == pytest.approx(s_ref, abs=tol)
            if not (spec is INTERNAL and gear is g.gears[1]):  # that ring tip is trimmed by 0.007 mm
                assert prof.tip_thickness == pytest.approx(gear.tip_thickness, abs=tol)
