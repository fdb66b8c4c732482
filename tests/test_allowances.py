"""Tooth thickness allowances (ISO 21771): the tool is fed in, the generating shift x_E moves the root and
the form circle; backlash ranges; inspection dimensions at the allowances."""
import math

import pytest

from gearkit.families.involute import GearSpec, tooth_profile
from gearkit.pair import PairSpec, pair_geometry

EXACT = 1e-9  # mm: closed forms of the same quantity
GEN = 1e-7    # mm: a generated circle against its closed form (the envelope is exact to ~1e-9 m)
A20 = math.radians(20.0)


def test_root_moves_with_the_allowance_as_iso_21771_says():
    # z = 30, m = 1, allowance 0.06 mm: x_E = -0.06 / (2 tan 20) = -0.082424, d_f = 30 - 2.5 + 2 x_E = 27.335
    spec = GearSpec(30, 1.0, thinning=0.06)
    x_e = -0.06 / (2 * math.tan(A20))
    assert spec.generating_shift == pytest.approx(x_e, abs=EXACT)
    prof = tooth_profile(spec)
    assert round(prof.root_diameter, 3) == 27.335
    assert prof.root_diameter == pytest.approx(30 - 2 * 1.25 + 2 * x_e, abs=GEN)
    assert prof.tip_diameter == pytest.approx(32.0, abs=GEN)          # the tip stays at the nominal shift
    assert prof.tooth_thickness == pytest.approx(math.pi / 2 - 0.06, abs=GEN)
    # the form circle is that of a gear cut at x_E: the involute starts where the rack's straight flank ends
    rb = 15 * math.cos(A20)
    roll = 15 * math.sin(A20) - (1.25 - 0.379951 * (1 - math.sin(A20)) - x_e) / math.sin(A20)
    assert prof.form_diameter == pytest.approx(2 * math.hypot(rb, roll), abs=1e-5)
    # the pair geometry agrees: the root of a thinned gear is that of x_E
    g = pair_geometry(PairSpec(30, 40, 1.0, thinning1=0.06))
    assert g.gears[0].root_diameter == pytest.approx(prof.root_diameter, abs=GEN)


def test_demo_exports_the_geometry_it_checks(tmp_path, capsys):
    # the 13/40 pair's shortened tips (d_a = d + 2 m (h_a* + x - dy)) are written, not the rule-free 31.2/84.0
    import numpy as np
    import trimesh

    from gearkit.cli import main
    assert main(["demo", "--out-dir", str(tmp_path)]) == 0
    capsys.readouterr()
    from gearkit.curves import inv_inverse
    alpha_w = inv_inverse(math.tan(A20) - A20 + 2 * 0.3 * math.tan(A20) / 53)  # tight mesh, x1 + x2 = 0.3
    y = (53 / 2) * (math.cos(A20) / math.cos(alpha_w) - 1)
    dy = 0.3 - y
    for name, z, x in (("pinion", 13, 0.3), ("wheel", 40, 0.0)):
        d_a = 2 * z + 2 * 2.0 * (1 + x - dy)  # independent of the pair module: the textbook's tip shortening
        mesh = trimesh.load(tmp_path / f"{name}.stl")
        r_max = float(np.max(np.hypot(mesh.vertices[:, 0], mesh.vertices[:, 1])))
        assert r_max == pytest.approx(d_a / 2, abs=0.01)  # mesh tol 0.005 m_n = 0.01 mm
        assert abs(r_max - (2 * z + 4 * (1 + x)) / 2) > 0.02  # and not the unshortened tip


def test_allowance_report_spans_pins_and_backlash():
    from gearkit.pair.allowances import Allowances, allowance_report
    from gearkit.pair.gauging import measure_over_pins

    spec = PairSpec(30, 41, 2.0, 0.2, -0.1)
    allow = Allowances((-0.05, -0.11), (-0.06, -0.13), (0.03, -0.01))
    r = allowance_report(spec, allow)
    g1 = r["gears"][0]
    # ISO 21771: the span falls by |A_sn| cos a_n, the generating shift by |A_sn| / (2 tan a_n)
    assert g1["upper"]["span"]["W"] - g1["lower"]["span"]["W"] == pytest.approx(0.06 * math.cos(A20), abs=EXACT)
    assert g1["lower"]["x_E"] == pytest.approx(0.2 - 0.11 / (2 * 2.0 * math.tan(A20)), abs=EXACT)
    assert g1["lower"]["root_diameter"] == pytest.approx(60 + 2 * 2.0 * (g1["lower"]["x_E"] - 1.25), abs=EXACT)
    # the over-pins dimension at the lower allowance, measured on the gear generated with it (second method)
    gear = GearSpec(30, 2.0, 0.2, thinning=0.11)
    measured, touch = measure_over_pins(tooth_profile(gear), g1["lower"]["over_pins"]["d_p"])
    assert touch == "flank" and measured.M == pytest.approx(g1["lower"]["over_pins"]["M"], abs=1e-6)

    # backlash on the working circle, from the thicknesses there (textbook 3.83), independently
    def j_wt(thin1, thin2, a):
        z1, z2, m = 30, 41, 2.0
        aw = math.acos((z1 + z2) * m / 2 * math.cos(A20) / a)
        inv = lambda t: math.tan(t) - t  # noqa: E731
        s = [d * ((math.pi / 2 * m + 2 * x * m * math.tan(A20) - t) / d + inv(A20) - inv(aw)) * math.cos(A20)
             / math.cos(aw) for d, x, t in ((z1 * m, 0.2, thin1), (z2 * m, -0.1, thin2))]
        return math.pi * z1 * m * math.cos(A20) / math.cos(aw) / z1 - s[0] - s[1]

    a = pair_geometry(spec).center_distance
    assert r["backlash"]["min"] == pytest.approx(j_wt(0.05, 0.06, a - 0.01), abs=EXACT)
    assert r["backlash"]["max"] == pytest.approx(j_wt(0.11, 0.13, a + 0.03), abs=EXACT)


def test_check_command_reports_the_allowances(capsys):
    import json

    from gearkit.cli import main
    argv = ["check", "--z1", "30", "--z2", "41", "-m", "2", "--x1", "0.2", "--x2", "-0.1", "--allowance1=-0.05,-0.11",
            "--allowance2=-0.06,-0.13", "--center-distance-tolerance=0.03,-0.01", "--json"]
    assert main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    gear2 = data["allowances"]["gears"][1]
    assert gear2["upper"]["span"]["W"] - gear2["lower"]["span"]["W"] == pytest.approx(0.07 * math.cos(A20), abs=EXACT)
    assert data["allowances"]["backlash"]["min"] < data["allowances"]["backlash"]["max"]
    assert main(["check", "--z1", "30", "--z2", "41", "-m", "2", "--allowance1=0.05,-0.11"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--allowance1" in err[0]


def test_single_gear_tip_rule_is_the_pair_checks_tip(capsys):
    import json

    from gearkit.checks import check_pair
    from gearkit.cli import main
    from gearkit.pair import gear_tip_diameter
    # the textbook's tip shortening: d_a = d + 2 m (h_a* + x - dy), dy = x1 + x2 - y at the tight mesh
    from gearkit.curves import inv_inverse
    alpha_w = inv_inverse(math.tan(A20) - A20 + 2 * 0.3 * math.tan(A20) / 53)
    dy = 0.3 - 53 / 2 * (math.cos(A20) / math.cos(alpha_w) - 1)
    d_a = 26 + 2 * 2.0 * (1 + 0.3 - dy)
    assert gear_tip_diameter(GearSpec(13, 2.0, 0.3), "shortened", GearSpec(40, 2.0)) == pytest.approx(d_a, abs=EXACT)
    assert gear_tip_diameter(GearSpec(13, 2.0, 0.3)) == pytest.approx(26 + 4 * 1.3, abs=EXACT)
    checked = check_pair(PairSpec(13, 40, 2.0, 0.3, 0.0)).profiles[0].tip_diameter
    assert main(["gear", "-z", "13", "-m", "2", "-x", "0.3", "--tip-rule", "shortened", "--mate-teeth", "40",
                 "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["tip_diameter"] == pytest.approx(checked, abs=GEN)
    assert main(["gear", "-z", "13", "-m", "2", "--tip-rule", "shortened"]) == 2
    assert "--mate-teeth" in capsys.readouterr().err
