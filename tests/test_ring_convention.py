"""A ring's shift in the ISO 21771 sense (the default) and as the shaper's setting (explicit option)."""
import json
import math

import pytest

from gearkit.cli import main
from gearkit.families.involute import GearSpec, ring_cutter_setting, tooth_profile
from gearkit.pair import PairSpec, pair_geometry, shifts_for_center_distance
from gearkit.families.involute import ShaperCutter

EXACT = 1e-9  # mm / rad: two closed forms of the same quantity
GEN = 1e-7    # mm: the generated tooth against its closed form
A20 = math.radians(20.0)


def inv(a):
    return math.tan(a) - a


def test_published_internal_spur_example():
    # z1 16, z2 24, m 3, x1 0, x2 0.5 (ISO): alpha_w = 31.0937 deg, a = 13.1683 mm, y = 0.38943, d_a1 54, d_a2 69.
    # The table works from inv alpha_w printed to 6 decimals (0.060401): that rounding moves alpha_w by up to
    # 0.5e-6 / tan^2(alpha_w) rad = 7.9e-5 deg, on top of half a unit of the printed 4th decimal.
    spec = PairSpec(16, 24, 3.0, 0.0, 0.5, kind="internal", tool2=ShaperCutter(16), tip_rule="standard")
    g = pair_geometry(spec)
    aw = g.working_pressure_angle
    assert math.degrees(aw) == pytest.approx(31.0937, abs=0.5e-4 + math.degrees(0.5e-6 / math.tan(aw) ** 2))
    assert round(inv(aw), 6) == 0.060401
    # the table's chain from its rounded involute reproduces its printed digits
    from gearkit.curves import inv_inverse
    aw_table = inv_inverse(0.060401)
    y_table = (24 - 16) / 2 * (math.cos(A20) / math.cos(aw_table) - 1)
    assert round(math.degrees(aw_table), 4) == 31.0937 and round(y_table, 5) == 0.38943
    assert round(12 + 3 * y_table, 4) == 13.1683
    # and gearkit's unrounded values agree with them within that rounding's effect
    assert round(g.center_distance, 4) == 13.1683
    assert g.center_distance_modification_coeff == pytest.approx(0.38943, abs=0.5e-5 + 4e-6)
    assert [gear.tip_diameter for gear in g.gears] == pytest.approx([54.0, 69.0], abs=EXACT)
    assert g.gears[1].shift_convention == "iso" and g.gears[1].shift_coeff == 0.5


@pytest.mark.parametrize("z, x, beta, cutter", [(24, 0.5, 0.0, ShaperCutter(16)), (49, 0.3, 15.0, ShaperCutter(20)),
                                                (60, -0.2, 0.0, ShaperCutter(25, shift=0.1))])
def test_iso_ring_has_the_rack_thickness_and_the_derived_shaper_cuts_it(z, x, beta, cutter):
    m = 2.0
    iso = GearSpec(z, m, x, beta, internal=True, tool=cutter)
    prof = tooth_profile(iso)
    mt = m / math.cos(math.radians(beta))
    # ISO 21771: s_t = m_t (pi/2 - 2 x tan a_n) for a ring (the rack-cut thickness of its space)
    assert prof.tooth_thickness == pytest.approx(mt * (math.pi / 2 - 2 * x * math.tan(A20)), abs=GEN)
    # the tip circle of the ISO shift, and the root the derived shaper setting cuts
    assert prof.tip_diameter == pytest.approx(z * mt - 2 * m * (1 - x), abs=GEN)
    setting = ring_cutter_setting(z, x, cutter, beta)
    a0 = mt * (z - cutter.teeth) / 2 + setting * m
    ra0 = cutter.teeth * mt / 2 + (cutter.shift + cutter.addendum) * m
    assert prof.root_diameter == pytest.approx(2 * (a0 + ra0), abs=GEN)
    # the same gear in the cutter convention, entered with the derived setting
    cut = tooth_profile(GearSpec(z, m, setting, beta, internal=True, tool=cutter, tip_diameter=prof.tip_diameter,
                                 shift_convention="cutter"))
    assert cut.tooth_thickness == pytest.approx(prof.tooth_thickness, abs=GEN)


def test_conventions_agree_through_the_setting_and_the_design_solves_iso_shifts():
    cutter = ShaperCutter(20, addendum=1.3)
    iso = PairSpec(46, 49, 8.0, 0.0, 0.52, kind="internal", tool2=cutter)
    setting = iso.ring_cutter_setting
    cut = PairSpec(46, 49, 8.0, 0.0, setting, kind="internal", tool2=cutter, shift_convention="cutter",
                   tip_diameter2=pair_geometry(iso).gears[1].tip_diameter)
    a, b = pair_geometry(iso), pair_geometry(cut)
    assert a.working_pressure_angle == pytest.approx(b.working_pressure_angle, abs=EXACT)
    assert a.gears[1].root_diameter == pytest.approx(b.gears[1].root_diameter, abs=EXACT)
    assert a.gears[1].cutter_setting == pytest.approx(setting, abs=EXACT)
    # ISO: inv a_wt = inv a_t + 2 (x2 - x1) tan a_n / (z2 - z1)
    assert inv(a.working_pressure_angle) == pytest.approx(inv(A20) + 2 * 0.52 * math.tan(A20) / 3, abs=EXACT)
    solved = shifts_for_center_distance(iso, a.center_distance, split="x1")
    assert solved.shift2 == pytest.approx(0.52, abs=1e-9)


def test_outputs_say_the_convention(capsys):
    assert main(["gear", "-z", "24", "-m", "3", "-x", "0.5", "--internal", "--cutter-teeth", "16", "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["shift_convention"] == "iso"
    assert info["cutter_setting"] == pytest.approx(ring_cutter_setting(24, 0.5, ShaperCutter(16)), abs=EXACT)
    assert main(["check", "--z1", "16", "--z2", "24", "-m", "3", "--x2", "0.5", "--internal", "--cutter-teeth", "16",
                 "--ring-shift", "cutter", "--json"]) in (0, 1)
    data = json.loads(capsys.readouterr().out)
    assert data["gears"][1]["shift_convention"] == "cutter" and data["gears"][1]["cutter_setting"] == 0.5
    assert main(["check", "--z1", "16", "--z2", "24", "-m", "3", "--x2", "0.5", "--internal",
                 "--cutter-teeth", "16"]) in (0, 1)
    assert "ring shift x2 read as ISO 21771" in capsys.readouterr().out


@pytest.mark.parametrize("x2, da1", [(1.5, 49.6), (1.5, None), (0.5, None), (1.0, 49.8)])
def test_min_tooth_difference_agrees_with_exit_jamming_on_the_pair_as_checked(x2, da1):
    # the 49/50 ring with a given pinion tip: the tooth-difference check must judge the pair's own
    # difference with the pair's own tips (it used to rebuild them by the tip rule and contradict exit_jamming)
    from gearkit.checks import check_pair
    spec = PairSpec(49, 50, 1.0, 0.0, x2, kind="internal", tool2=ShaperCutter(20), tip_diameter1=da1)
    report = check_pair(spec, geometry="formula").report
    jam, diff = report["exit_jamming"], report["min_teeth.difference"]
    assert (jam.status == "ok") == (diff.status == "ok")
    if jam.status == "ok":
        assert diff.limit <= 1.0
