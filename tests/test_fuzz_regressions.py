"""The reproducers of the fuzzing report (issue 20), one test per numbered defect class.

Each case is the report's own spec; the assertions hold it to an independent oracle (a closed
form, the generated geometry, a dense re-evaluation of the exact curve, strict JSON parsing).
"""
import json
import math

import numpy as np
import pytest
from fuzzkit import check_flat_cam, true_deviation

import gearkit as gk
from gearkit.cli import main
from gearkit.curves import inv
from gearkit.distances import polyline_deviation
from gearkit.errors import SpecError

#: exact geometry against closed forms (mm, relative to a module of 1)
EXACT = 1e-9
#: dense re-evaluation points per exact piece: fine enough that its own chords are far below tol
DENSE = 200_001


def _strict(text):
    """Parse JSON refusing NaN/Infinity (``json.loads`` accepts them by default)."""
    def refuse(token):
        raise ValueError(f"non-standard JSON number {token}")
    return json.loads(text, parse_constant=refuse)


def _true_deviation(profile, tol, dense=None):
    """Largest distance of the exact half tooth (``dense`` points per piece) from its sampled polyline."""
    half, _ = profile.half_points(tol)
    w = np.linspace(0.0, 1.0, dense or DENSE)
    exact = np.concatenate([p(w) for p in profile.half.pieces])
    return polyline_deviation(half, exact)


# -- 1. thickness at a radius the tooth does not reach ----------------------------------------
def test_1_reference_circle_below_the_root_is_reported_not_raised(capsys):
    prof = gk.tooth_profile(gk.GearSpec(40, 1.0, shift=1.3))
    # closed forms: r_f = r - m (h_fP* - x) = 20.05 > r = 20; the involute thickness at r = 21
    assert prof.root_diameter / 2 == pytest.approx(20.0 - (1.25 - 1.3), abs=EXACT)
    info = prof.summary()
    assert info["tooth_thickness"] is None and prof.thickness_at(20.0) is None
    alpha, r, rb = math.radians(20.0), 21.0, 20.0 * math.cos(math.radians(20.0))
    s_ref = math.pi / 2 + 2 * 1.3 * math.tan(alpha)
    closed = 2 * r * (s_ref / 40.0 + inv(alpha) - inv(math.acos(rb / r)))
    assert prof.thickness_at(r) == pytest.approx(closed, abs=EXACT)
    assert main(["gear", "-z", "40", "-m", "1", "-x", "1.3"]) == 0
    assert "not on the tooth" in capsys.readouterr().out
    assert main(["gear", "-z", "40", "-m", "1", "-x", "1.3", "--json"]) == 0
    assert _strict(capsys.readouterr().out)["tooth_thickness"] is None


# -- 2. the pair check grades the tips that are cut --------------------------------------------
@pytest.mark.parametrize("spec, tips", [
    (dict(teeth1=20, teeth2=40, module=1.0, center_distance=30.6), (22.0, 42.0)),
    (dict(teeth1=40, teeth2=None, module=1.0, kind="rack", center_distance=20.6), (42.0,)),
])
def test_2_checked_tip_is_never_larger_than_the_cut_tip(spec, tips):
    res = gk.check_pair(gk.PairSpec(**spec), simulate=True)
    checked = [gear.tip_diameter for gear in res.geometry.gears]
    cut = [p.tip_diameter for p in res.profiles]
    # the standard blank d + 2 m (h_a* + x) with x = 0: a_w > a never lengthens the tips
    assert checked == pytest.approx(tips, abs=EXACT) and all(c <= k * (1 + EXACT) for c, k in zip(checked, cut))
    rep = res.report
    assert rep["contact_ratio.simulated"].value == pytest.approx(rep["contact_ratio"].value, abs=1e-3)
    assert rep["contact_ratio.simulated"].status != "fail"


def test_2_pointed_tooth_is_checked_at_its_point():
    # z = 10, x = 1: the flanks meet below the blank's tip circle d + 2 m (1 + x) = 14
    res = gk.check_pair(gk.PairSpec(10, 30, 1.0, shift1=1.0, tip_rule="standard"))
    pinion = res.profiles[0]
    assert pinion.pointed and pinion.tip_diameter < 14.0 - 0.1
    assert res.geometry.gears[0].tip_diameter == pytest.approx(pinion.tip_diameter, abs=EXACT)
    assert res.report["pointing.1"].status == "fail"


def test_2_formula_simulation_disagreement_fails():
    from gearkit.checks.simulated import EPS_AGREEMENT, simulated_findings
    from gearkit.contact import analyse_pair

    spec = gk.PairSpec(20, 40, 1.0)
    res = gk.check_pair(spec)
    analysis = analyse_pair(spec, 64)
    ok = simulated_findings(spec, res.geometry, res.report.findings, gk.CheckLimits(), analysis)[0]
    assert ok.status == "ok"
    # the same simulation against the formula geometry of another pair (tips 0.1 m longer)
    other = gk.pair_geometry(gk.PairSpec(20, 40, 1.0, tip_diameter1=22.2, tip_diameter2=42.2))
    assert abs(other.contact_ratio - analysis.contact_ratio) > EPS_AGREEMENT
    bad = simulated_findings(spec, other, res.report.findings, gk.CheckLimits(), analysis)[0]
    assert bad.status == "fail" and "disagree" in bad.message


# -- 3. the reported deviation is a bound ------------------------------------------------------
@pytest.mark.parametrize("make, tol", [
    (lambda: gk.pin_gear_wheel(gk.PinGearSpec(1.0, 50, 60, 0.04)), 3e-5),
    (lambda: gk.disc_profile(gk.DriveSpec(3, 2, 13.0, 8.0, 3.8)), 0.01),
    # found by the property suite: a square-root end where the disc's two pin walks meet
    (lambda: gk.disc_profile(gk.DriveSpec(26, 24, 1.0, 0.06041524333826525, 0.019230769230769232)),
     3.846153846153846e-05),
])
def test_3_sampler_does_not_skip_narrow_features(make, tol):
    prof = make()
    _, achieved = prof.half_points(tol)
    true = _true_deviation(prof, tol, BOUND_DENSE)
    assert achieved <= tol and true <= tol
    # the reported deviation is a proven bound: at least the real one (a dense measure reads at most
    # the real deviation; round-off of the exact points aside)
    assert true <= achieved * (1 + 1e-9), (true, achieved)


#: points per piece of the independent measure of the reproducers of item 3 (as DENSE: steps 5e-6 of a piece)
BOUND_DENSE = DENSE


# -- 4. strict JSON ------------------------------------------------------------------------------
def test_4_drive_without_finite_curvature_limit_is_strict_json(capsys):
    from gearkit.families.cycloidal import min_curvature_radius

    spec = gk.DriveSpec(6, 9, 40.0, 5.0, 4.0)
    value, where = min_curvature_radius(spec)
    assert value == math.inf and where is None
    code = main(["cycloidal-drive", "--pins", "6", "--lobes", "9", "--pin-circle-radius", "40", "--pin-radius", "5",
                 "--eccentricity", "4", "--json"])
    out = _strict(capsys.readouterr().out)
    assert code in (0, 1) and out["min_curvature_radius"] is None
    looping = next(f for f in out["findings"] if f["id"] == "looping")
    assert looping["limit"] is None and "never bends" in looping["message"]


# -- 9. one validation path for every spec field ------------------------------------------------
@pytest.mark.parametrize("build, field", [
    (lambda: gk.GearSpec(20, 2.0, shift="0.3"), "shift"),
    (lambda: gk.GearSpec(20, 2.0, thinning=None), "thinning"),
    (lambda: gk.GearSpec(20, 2.0, internal="yes"), "internal"),
    (lambda: gk.rack_profile(gk.RackSpec(1.0)).outline(1e-3, teeth=True), "teeth"),
    (lambda: gk.RackSpec("1.0"), "module"),
    (lambda: gk.NovikovGearSpec(20, 1.0, gk.rack_system("dca24").rack1, helix_angle_deg=None), "helix_angle_deg"),
    (lambda: gk.NovikovPairSpec(20, 40, 1.0, 15.0, "20"), "face_width"),
    (lambda: gk.PairSpec(20, 40, 1.0, shift1="0.3"), "shift1"),
    (lambda: gk.PairSpec(20, 40, 1.0, thinning1=None), "thinning1"),
    (lambda: gk.PairSpec(True, 40, 1.0), "teeth1"),
    (lambda: gk.BasicRack(pressure_angle_deg="20"), "pressure_angle_deg"),
    (lambda: gk.ShaperCutter(20.0), "cutter.teeth"),
    (lambda: gk.SolidSpec(width=None), "width"),
    (lambda: gk.SolidSpec(5.0, herringbone=1), "herringbone"),
    (lambda: gk.DriveSpec(12, 11, "90", 7.0, 4.0), "pin_circle_radius"),
    (lambda: gk.CycloidPairSpec(1.0, 10, 20, clock="2"), "clock"),
    (lambda: gk.PinGearSpec(1.0, np.float64(10), 20, 0.1), "pins"),
    (lambda: gk.CheckLimits(min_contact_ratio=None), "min_contact_ratio"),
])
def test_9_wrong_types_are_spec_errors_naming_the_field(build, field):
    with pytest.raises(SpecError) as exc:
        build()
    assert exc.value.field == field


def test_9_numpy_scalars_are_numbers():
    gear = gk.GearSpec(np.int64(20), np.int64(2), np.float64(0.3))
    assert gear == gk.GearSpec(20, 2.0, 0.3) and type(gear.teeth) is int
    assert gk.tooth_profile(gear).tip_diameter == pytest.approx(20 * 2 + 2 * 2 * (1 + 0.3), abs=EXACT)
    spec = gk.PairSpec(np.int64(20), np.int32(40), np.int64(2), np.float64(0.1))
    assert (type(spec.teeth1), type(spec.module), type(spec.shift1)) == (int, int, float)
    assert spec == gk.PairSpec(20, 40, 2, 0.1)
    res = gk.check_pair(spec)
    assert res.geometry.center_distance == pytest.approx(gk.check_pair(gk.PairSpec(20, 40, 2.0, 0.1))
                                                         .geometry.center_distance, abs=EXACT)
    assert gk.DriveSpec(np.int64(12), np.int64(11), np.float32(90.0), 7, 4) == gk.DriveSpec(12, 11, 90.0, 7.0, 4.0)


# -- 10. hostile magnitudes ----------------------------------------------------------------------
@pytest.mark.parametrize("build, field", [
    (lambda: gk.rack_solid(gk.rack_profile(gk.RackSpec(1.0)), 10.0, 5.0, 3.0, start=math.inf), "start"),
    (lambda: gk.PairSpec(20, 40, 1.0, center_distance=1e300), "center_distance"),
    (lambda: gk.PairSpec(20, 40, 1e-300), "module"),
    (lambda: gk.gear_solid(gk.tooth_profile(gk.GearSpec(20, 1.0)), gk.SolidSpec(5.0, bore=1e300)), "bore"),
    (lambda: gk.gear_solid(gk.tooth_profile(gk.GearSpec(20, 1.0)), gk.SolidSpec(1e300)), "width"),
    (lambda: gk.BasicRack(pressure_angle_deg=1e-12), "pressure_angle_deg"),
    (lambda: gk.ShaperCutter(20, pressure_angle_deg=1e-12), "cutter.pressure_angle_deg"),
    (lambda: gk.DriveSpec(12, 11, 90.0, 7.0, 1e-300), "eccentricity"),
    (lambda: gk.DriveSpec(12, 11, 1e300, 7.0, 4.0), "pin_circle_radius"),
    # the cam property's knife on a base circle of 1e-300 mm (0/0 in the pitch curve's curvature), and a
    # prime radius in range but below 1e-4 of the stroke
    (lambda: gk.CamSpec(1e-300, gk.MotionProgram.rise_dwell_return(0.8042838121527993, 20.0, 0.16085676243055985, 20.0,
                                                                   "polynomial_345"), contact="knife"), "prime_radius"),
    (lambda: gk.CamSpec(0.01, gk.MotionProgram.rise_dwell_return(1000.0, 90.0, 0.0, 90.0), contact="knife"),
     "prime_radius"),
    (lambda: gk.tooth_profile(gk.GearSpec(20, 1.0)).half_points(1e-11), "tol"),
    (lambda: gk.tooth_profile(gk.GearSpec(20, 1.0)).outline(math.inf), "tol"),
    (lambda: gk.gear_solid(gk.tooth_profile(gk.GearSpec(20, 1.0)), gk.SolidSpec(5.0), tol=1e-300), "tol"),
])
def test_10_hostile_magnitudes_are_spec_errors(build, field):
    with pytest.raises(SpecError) as exc:
        build()
    assert exc.value.field == field


def test_10_tol_floor_names_the_allowed_range():
    with pytest.raises(SpecError, match=r"outside \[1e-09, 1\] mm"):
        gk.tooth_profile(gk.GearSpec(20, 1.0)).half_points(1e-11)
    # the floor itself is accepted and achieved
    prof = gk.tooth_profile(gk.GearSpec(20, 1.0))
    assert prof.half_points(1e-9)[1] <= 1e-9


# -- 11. small ones ------------------------------------------------------------------------------
def test_11_pointed_tip_thickness_is_zero():
    disc = gk.disc_profile(gk.DriveSpec(12, 11, 90.0, 7.0, 4.0))
    assert disc.tip_thickness == 0.0 and math.copysign(1.0, disc.tip_thickness) == 1.0


def test_11_clock_gearing_with_many_pinion_teeth_names_the_field():
    with pytest.raises(SpecError) as exc:
        gk.CycloidPairSpec(1.0, 98, 104, clock=True)
    assert exc.value.field == "pinion_teeth"
    # with the wheel addendum given, the pair is valid and generates
    spec = gk.CycloidPairSpec(1.0, 98, 104, clock=True, addendum2=2.5)
    assert spec.addendum(2) == pytest.approx(2.5)


# -- 5. end faces that survive single precision ---------------------------------------------------
@pytest.mark.parametrize("z, m, bore", [(225, 0.02, None), (1050, 1.0, None), (1050, 1.0, 300.0)])
def test_5_large_and_small_gears_build_valid_solids(z, m, bore):
    prof = gk.tooth_profile(gk.GearSpec(z, m))
    width, tol = 5.0 * m, 5e-3 * m
    solid = gk.gear_solid(prof, gk.SolidSpec(width, bore=bore), tol=tol)
    out = prof.outline(tol / 4)
    x, y = out[:, 0], out[:, 1]
    area = 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)) - (0 if bore is None else math.pi * bore ** 2 / 4)
    # the solid's volume is its section times the width; section and polyline differ by ~tol per length
    perimeter = float(np.sum(np.hypot(np.diff(x, append=x[0]), np.diff(y, append=y[0]))))
    assert solid.volume == pytest.approx(area * width, abs=2 * tol * perimeter * width)


def test_5_cli_5000_teeth_stl_is_watertight(tmp_path, capsys):
    trimesh = pytest.importorskip("trimesh")
    out = tmp_path / "g.stl"
    assert main(["gear", "-z", "5000", "-m", "1", "--width", "5", "-o", str(out)]) == 0
    mesh = trimesh.load(out)
    assert mesh.is_watertight and mesh.volume == pytest.approx(math.pi * 2500.0 ** 2 * 5.0, rel=1e-3)


# -- 8. DXF in bulk -------------------------------------------------------------------------------
def test_8_dxf_holds_the_outline_vertex_for_vertex(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    from gearkit.export import write_profile

    prof = gk.tooth_profile(gk.GearSpec(2000, 1.0))
    loop = prof.outline(1e-3)
    path = tmp_path / "g.dxf"
    write_profile(path, [loop])
    (pl,) = ezdxf.readfile(path).modelspace().query("LWPOLYLINE")
    assert pl.closed and np.array_equal(np.array(pl.get_points("xy")), loop)


# -- 6. a Novikov pair that does not mesh is a failing finding -------------------------------------
def test_6_novikov_pair_that_does_not_mesh_fails_the_check(capsys):
    res = gk.check_novikov(gk.NovikovPairSpec(20, 60, 1.0, 15.0, 20.0, center_distance=41.7))
    rep = res.report
    assert rep.status == "fail" and rep["mesh.contact.0"].status == "fail"
    assert "do not meet" in rep["mesh.contact.0"].message
    _strict(json.dumps(rep.to_dict(), allow_nan=False))
    argv = ["novikov", "--z1", "20", "--z2", "60", "-m", "1", "--helix-angle-deg", "15", "--width", "20",
            "--center-distance", "41.7"]
    assert main(argv) == 1
    capsys.readouterr()


# -- 7. protuberance racks --------------------------------------------------------------------------
def test_7_protuberance_rack_outline_is_simple_and_carries_the_protuberance():
    from gearkit.curves import polyline_self_intersections

    rack = gk.BasicRack(dedendum=1.3, protuberance=0.1)
    prof = gk.rack_profile(gk.RackSpec(1.0, rack))
    out = prof.outline(1e-3, teeth=2)
    assert len(polyline_self_intersections(out)[0]) == 0
    # the space bottom is the cutter's tip: at the root line the space is wider than the main flank
    # gives by pr / cos(alpha) (closed form of the protuberance flank)
    alpha, ap = rack.alpha, rack.alpha_protuberance
    pieces = prof.half.pieces
    x_top, y_top = pieces[1](np.array([1.0]))[0]
    assert y_top == pytest.approx(-1.3 + rack.protuberance_top, abs=EXACT)
    x_prot_at_root = x_top + (y_top + 1.3) * math.tan(ap)
    x_main_at_root = math.pi / 4 + 1.3 * math.tan(alpha)
    assert x_main_at_root - x_prot_at_root == pytest.approx(0.1 / math.cos(alpha), abs=EXACT)


def test_7_default_fillet_of_a_protuberance_rack_is_accepted():
    rack = gk.BasicRack(protuberance=0.05)
    # it stays below the protuberance flank: rho (1 - sin a_pr) < its top
    assert rack.fillet * (1 - math.sin(rack.alpha_protuberance)) < rack.protuberance_top
    gear = gk.tooth_profile(gk.GearSpec(30, 2.0, tool=rack))
    assert gear.half_points(2e-3)[1] <= 2e-3


# -- found by the cam property of the fuzz suite -----------------------------------------------
def test_cam_two_velocity_jumps_at_one_angle_build_a_profile():
    # a near-zero dwell between two constant-velocity phases puts two corners at (almost) one cam
    # angle; sorting the corners compared their pole arrays and raised ValueError
    from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

    spec = CamSpec(5.0, MotionProgram.rise_dwell_return(2.5, 20.0, 1.2e-151, 20.0, "constant_velocity"),
                   roller_radius=1.0)
    prof = cam_profile(spec)
    assert len(prof.pieces) >= 1 and len(prof.outline(5e-3)) > 3
    # the pitch curve's largest radius is the prime radius plus the lift (a closed form)
    assert np.hypot(*prof.pitch_points(np.linspace(0, 2 * np.pi, 7201)).T).max() == pytest.approx(7.5, rel=1e-6)


def test_flat_rocker_cam_runs_straight_along_the_face_line_at_a_velocity_jump():
    # a flat-faced rocker turning back relative to the cam (|psi'| > 1, constant velocity): the lines
    # of the return are all cut away and the face line at the return's end (a velocity jump) bounds
    # the cam from its touching point on the base circle to the crossing with the rise's envelope.
    # The kept arcs did not cross there; the outline closed with a chord 0.416 mm inside the cam.
    from gearkit.families.cam import CamSpec, MotionProgram, cam_profile
    from gearkit.families.cam.halfplanes import face_lines

    kw = dict(prime_radius=29.920755273305605, follower="rocker", contact="flat", roller_radius=0.0,
              pivot_distance=35.90490632796673, arm_length=17.952453163983364)
    motion = MotionProgram.rise_dwell_return(14.960377636652803, 29.920755273305605, 29.920755273305605, 20.0,
                                             "constant_velocity")
    prof = cam_profile(CamSpec(motion=motion, **kw))
    tol = 1e-4 * prof.spec.prime_radius
    out = prof.outline(tol)
    closed = np.concatenate([out[::-1], out[-1:]])
    # the fuzz property's independent measure: the exact pieces against the sampled outline
    assert true_deviation(prof.pieces, closed) <= tol * (1 + 1e-3)
    # and the cam as the intersection of the face's half-planes n . x <= h (textbook: the flat face's
    # cam is the region it never sweeps), from the face's poses alone: every vertex on its boundary
    # (the most violated line touches it), every chord's midpoint within tol inside it
    lines = 1 << 16
    n, h = face_lines(prof.motion, prof.tool, np.linspace(0.0, 2 * np.pi, lines, endpoint=False))
    mids = 0.5 * (closed[1:] + closed[:-1])
    # a vertex between two sampled lines reads below 0 by rho (k delta)^2 / 8: the line step delta,
    # the face turning relative to the cam at most k = 1 + |psi'| < 4 times as fast as the cam (the
    # arm's |psi'| = stroke / (arm phase) is 1.6 on the rise, 2.4 on the return), rho at most the
    # cam's diameter 2 (r0 + stroke)
    between = 2 * (29.92 + 14.97) * (4 * 2 * np.pi / lines) ** 2 / 8
    assert np.abs((out @ n.T - h).max(axis=1)).max() <= between
    assert (mids @ n.T - h).max(axis=1).min() >= -tol


def test_flat_rocker_cam_with_a_short_rise_and_return_is_bridged_at_the_jump():
    # the long fuzz run's second flat-faced rocker with |psi'| > 1 (20 deg rise and return, constant
    # velocity): its outline closed 3.16 mm inside the cam at tol 0.0806 before the jump's face line
    # was bridged; the fuzz property's independent measure holds it within tol
    from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

    kw = dict(prime_radius=80.57346728673313, follower="rocker", contact="flat", roller_radius=0.0,
              pivot_distance=96.68816074407975, arm_length=48.344080372039876)
    motion = MotionProgram.rise_dwell_return(20.143366821683284, 20.0, 20.0, 20.0, "constant_velocity")
    prof = cam_profile(CamSpec(motion=motion, **kw))
    tol = 1e-3 * prof.spec.prime_radius
    out = prof.outline(tol)
    assert true_deviation(prof.pieces, np.concatenate([out[::-1], out[-1:]])) <= tol * (1 + 1e-3)


def test_cam_roller_corner_past_a_turn_starts_after_the_jump():
    # a constant-velocity return ending at 1.4695929635480176 rad, the curve started 0.362 rad on: the
    # corner shifted by that start and back landed an ulp before the join, where the law still gives the
    # return's velocity, so the curve past the corner started at the old pole's contact and the outline
    # ran back across the roller's arc and out again (its proven bound read 0.979 mm at tol 0.00315 mm)
    from gearkit.families.cam import CamSpec, MotionProgram, cam_profile
    from gearkit.distances import distances_to_polyline

    kw = dict(prime_radius=31.5, follower="translating", contact="roller", roller_radius=17.970193095431824,
              offset=4.9370394017351126e-206)
    motion = MotionProgram.rise_dwell_return(12.111001733293092, 20.0, 20.262197192103496, 43.93927722132095,
                                             "constant_velocity")
    prof = cam_profile(CamSpec(motion=motion, **kw))
    tol = 1e-4 * prof.spec.prime_radius
    out, achieved = prof.outline(tol), prof.achieved(tol)
    closed = np.concatenate([out[::-1], out[-1:]])
    assert achieved <= tol
    # the fuzz property's independent measure: the exact pieces against the sampled outline
    assert true_deviation(prof.pieces, closed) <= achieved * (1 + 1e-6)
    # and the roller never cuts into the cam (textbook: the cam is what the roller circle about the pitch
    # curve leaves): every chord's midpoint at least r - tol from the pitch curve, the roller centre's
    # path from the law alone (a dense polyline of it, off the curve by step^2 / (8 rho) < 3e-6 mm at
    # 2^16 points over a turn of 48 mm radius: within the margin)
    r = kw["roller_radius"]
    pitch = prof.pitch_points(np.linspace(0.0, 2 * np.pi, 1 << 16))
    assert distances_to_polyline(0.5 * (closed[1:] + closed[:-1]), pitch).min() >= r - tol * (1 + 1e-3)


def _knife_pitch_curve(r0, e, lift, rise, dwell, ret, shape, points=1 << 18):
    """A translating knife's cam from the textbook alone: its tip ``(e, sqrt(r0^2 - e^2) + s)`` seen from the
    cam turned counter-clockwise by ``phi`` (spans in degrees, ``shape(x)`` the law's lift fraction), at
    ``points`` cam angles plus the phases' ends (where a constant-velocity law's curve has its corners)."""
    ends = np.radians(np.cumsum([rise, dwell, ret]))
    phi = np.unique(np.concatenate([np.linspace(0.0, 2 * np.pi, points), ends]))
    s = np.where(phi < ends[0], lift * shape(phi / ends[0]),
                 np.where(phi < ends[1], lift,
                          np.where(phi < ends[2], lift * (1 - shape((phi - ends[1]) / (ends[2] - ends[1]))), 0.0)))
    y = math.sqrt(r0 * r0 - e * e) + s
    return np.stack([e * np.cos(phi) + y * np.sin(phi), -e * np.sin(phi) + y * np.cos(phi)], -1)


def _own_chord_error(curve, mids):
    """How far a dense polyline of a curve lies from it: its edges' midpoints (``mids``, points of the
    curve halfway in the parameter) against it."""
    from gearkit.distances import distances_to_polyline

    return float(distances_to_polyline(mids, curve).max())


def test_repeated_points_take_no_part_in_the_crossing_sweep():
    # a knife cam's corners are points (the tip stands while the velocity jumps): thousands of repeated
    # scan points paired each with every other in the sweep (a (23 963 643, 2) array for one cam).
    # A figure eight with a run of 300 000 repeats of one point: the crossing is the one of the plain
    # figure eight (the same edges, their indices shifted past the run), without 4.5e10 candidate pairs
    from gearkit.curves import polyline_self_intersections

    eight = np.array([[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]])
    run = 300_000
    points = np.concatenate([eight[:2], np.repeat(eight[1:2], run, axis=0), eight[2:]])
    i, j, ti, tj = polyline_self_intersections(points)
    assert (i.tolist(), j.tolist(), ti.tolist(), tj.tolist()) == ([0], [run + 2], [0.5], [0.5])


@pytest.mark.parametrize("dwell", [1e-300, 0.0, 1e-12, 1.0])
def test_cam_knife_on_velocity_jumps_across_a_vanishing_dwell_builds(dwell):
    # constant velocity up 19.58 mm in 20 degrees and back in 63.7, a knife (its cam has corners at the
    # jumps): with a dwell of 1e-300 degrees (two jumps at one angle) the loop scan ran out of memory.
    # A dwell that small is no dwell: every one builds, the cam of the textbook's tip path within tol
    from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

    r0, e, lift, rise, ret = 5.0, 1.535935442883325, 19.580223362389933, 20.0, 63.68876519046828
    spec = CamSpec(r0, MotionProgram.rise_dwell_return(lift, rise, dwell, ret, "constant_velocity"),
                   contact="knife", roller_radius=0.0, offset=e)
    prof = cam_profile(spec)
    tol = 5e-5
    out, achieved = prof.outline(tol), prof.achieved(tol)
    assert achieved <= tol
    exact = _knife_pitch_curve(r0, e, lift, rise, dwell, ret, lambda x: x)
    fine = _knife_pitch_curve(r0, e, lift, rise, dwell, ret, lambda x: x, points=(1 << 19) - 1)
    own = _own_chord_error(exact, fine)
    # the formula's curve within the reported bound of the outline, every vertex on that curve
    assert polyline_deviation(out, exact, closed=True) <= achieved * (1 + 1e-9)
    assert _own_chord_error(exact, out) <= own + EXACT


@pytest.mark.parametrize("dwell", [1e-14, 0.0, 1e-9])
def test_flat_rocker_across_a_dwell_of_a_few_ulps_is_convex_with_no_repeated_vertex(dwell):
    # a 0.1 mm polynomial rise and return of 20 degrees each on a flat rocker: a dwell of 1e-14 degrees is a
    # piece a few ulps long, whose two ends came out as two vertices 4e-15 mm apart, an edge of no direction
    # that read as the outline turning back by 0.0058 mm. The cam is the intersection of the face's
    # half-planes written from the spec alone (check_flat_cam), convex, with every edge of some length
    from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

    spec = CamSpec(5.0, MotionProgram.rise_dwell_return(0.1, 20.0, dwell, 20.0, "polynomial_345"),
                   follower="rocker", contact="flat", pivot_distance=6.625248492635871,
                   arm_length=9.788188074451035)
    prof = cam_profile(spec)
    tol = 5e-4
    out = prof.outline(tol)
    assert prof.achieved(tol) <= tol
    reach = spec.prime_radius + spec.stroke + spec.pivot_distance + spec.arm_length
    assert np.hypot(*(out - np.roll(out, 1, axis=0)).T).min() > 1e-14 * reach
    check_flat_cam(spec, out, tol)
    assert true_deviation(prof.pieces, np.concatenate([out[::-1], out[-1:]])) <= prof.achieved(tol)


def test_cam_knife_keeps_the_whole_cam_when_nothing_loops():
    # a knife on a steep 3-4-5 return (pitch curve concave to 0.27 mm at the scan's start): the scan's
    # first and last edges, an ulp apart where the turn closes, read as a crossing, and the whole cam was
    # cut away as one loop; its outline was 2 points, reported 1.4e-13 off while 9.25e-9 off
    from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

    r0, e, lift, rise, dwell, ret = 5.0, -2.078956268207175, 1.9298767865596234, 78.74266669206554, 9.56962657256484, 20.0
    spec = CamSpec(r0, MotionProgram.rise_dwell_return(lift, rise, dwell, ret, "polynomial_345"),
                   contact="knife", roller_radius=0.0, offset=e)
    prof = cam_profile(spec)
    assert prof.loops == () and not prof.undercut
    def shape(x):
        return x ** 3 * (10 - 15 * x + 6 * x * x)
    exact = _knife_pitch_curve(r0, e, lift, rise, dwell, ret, shape)
    fine = _knife_pitch_curve(r0, e, lift, rise, dwell, ret, shape, points=(1 << 19) - 1)
    own = _own_chord_error(exact, fine)
    for tol in (5e-5, 5e-3):
        out, achieved = prof.outline(tol), prof.achieved(tol)
        closed = np.concatenate([out[::-1], out[-1:]])
        assert achieved <= tol
        # the reported deviation bounds the real one: the formula's curve, and the fuzz property's measure
        assert polyline_deviation(out, exact, closed=True) <= achieved * (1 + 1e-9)
        assert true_deviation(prof.pieces, closed) <= achieved * (1 + 1e-9)
        assert _own_chord_error(exact, out) <= own + EXACT
        # the whole cam: the area the tip path encloses (shoelace), within the perimeter times tol
        def area(p):
            return 0.5 * abs(np.dot(p[:, 0], np.roll(p[:, 1], -1)) - np.dot(p[:, 1], np.roll(p[:, 0], -1)))
        perimeter = float(np.hypot(*np.diff(exact, axis=0).T).sum())
        assert abs(area(out) - area(exact)) <= perimeter * (tol + own)


@pytest.mark.parametrize("field, value", [("pivot_distance", 1e300), ("arm_length", 1e300)])
def test_cam_rocker_pivot_beyond_its_reach_is_refused(field, value):
    # a flat rocker's pivot 1e300 mm from a 5 mm cam divided by zero in its pose (numpy errors raised);
    # the cam's points are computed through the pivot, whose round-off (1e-14 of it) must stay below
    # the cam's finest tol 1e-9 (r0 + stroke): the range ends at 1e4 (r0 + stroke)
    from gearkit.families.cam import CamSpec, MotionProgram, cam_profile
    from gearkit.families.cam.spec import REACH

    kw = dict(prime_radius=5.0, follower="rocker", contact="flat", roller_radius=0.0, pivot_distance=20.0,
              arm_length=5.1222497768659)
    motion = MotionProgram.rise_dwell_return(0.1, 20.0, 0.40722810901615936, 26.554173590505993, "polynomial_4567")
    with pytest.raises(SpecError) as exc:
        CamSpec(motion=motion, **{**kw, field: value})
    reach = REACH * (5.0 + motion.stroke)
    assert exc.value.field == field and f"{reach:.6g} mm" in str(exc.value)
    # the pivot and the arm at the range's end give a valid cam, within tol at the finest tol too
    prof = cam_profile(CamSpec(motion=motion, **{**kw, "pivot_distance": reach, field: reach}))
    for tol in (1e-3 * 5.0, 2e-9 * (5.0 + motion.stroke)):
        out = prof.outline(tol)
        assert true_deviation(prof.pieces, np.concatenate([out[::-1], out[-1:]])) <= prof.achieved(tol) <= tol


def test_cam_roller_that_reaches_the_centre_is_refused():
    from gearkit.families.cam import CamSpec, MotionProgram

    with pytest.raises(SpecError) as exc:
        CamSpec(5.0, MotionProgram.rise_dwell_return(1.0, 90.0, 0.0, 90.0), roller_radius=1e300)
    assert exc.value.field == "roller_radius"


# -- found by the long run -------------------------------------------------------------------------
def test_drive_check_at_k1_exactly_one_is_a_failing_finding():
    """|K1| = 1 exactly (6 pins, 7 lobes, R 5, e 5/6: K1 = -1): the curvature radius was 0/0 at the
    ordinary cycloid's cusp phi = pi (numpy's invalid-value error). Its limit there is 0: with
    t = pi - phi, s ~ t^2 and the denominator ~ -(1 + Z) t^2 / 2, so rho ~ -2 R_Z t / (1 + Z)."""
    from gearkit.families.cycloidal import curvature_radius

    spec = gk.DriveSpec(6, 7, 5.0, 1.3943247007045099, 5.0 / 6.0)
    g = spec.grinding()
    assert g.k1 == -1.0
    t = 1e-4
    with np.errstate(all="raise", under="ignore"):
        rho = curvature_radius(spec, np.array([math.pi, math.pi - t]))
        res = gk.check_drive(spec, samples=50)
    assert rho[0] == 0.0
    assert rho[1] == pytest.approx(-2.0 * g.pin_circle_radius * t / (1.0 + g.equivalent_pins), rel=1e-3)
    assert res.report["curtate"].status == "fail"
    _strict(json.dumps(res.to_dict()))


#: the geometry's own precision relative to the module (README, input checking): pieces meeting at a
#: trim share their crossing point to this
JOIN = 1e-9


@pytest.mark.parametrize("kw, tol_m", [
    (dict(module=43.021, pins=19, wheel_teeth=162, pin_radius=6.903455464415682, addendum=0.31690437167428115), 1e-5),
    (dict(module=40.595, pins=73, wheel_teeth=191, pin_radius=7.0, addendum=0.875), 1e-5),
    (dict(module=2.5, pins=27, wheel_teeth=55, pin_radius=0.17945353188047625, addendum=0.4502043415798687), 1e-3),
])
def test_pin_gear_trim_crossing_is_solved_and_the_bound_holds(kw, tol_m):
    """The loop of the pin's equidistant is cut at its self-crossing; the damped Newton crept there
    (a 0.2 degree crossing next to the cusp) and stopped up to 9.6e-6 mm short, so the flank after
    the trim began away from the vertex the polyline shares with the piece before it and the
    reported chord bound missed the gap (0.000377 reported, 0.000381 real). Oracles: the two pieces
    meet (continuity of the cut boundary) and a dense re-evaluation of the exact pieces stays within
    the reported bound."""
    prof = gk.pin_gear_wheel(gk.PinGearSpec(**kw))
    assert "trim" in prof.half.joins
    pieces, m = prof.half.pieces, prof.module
    for a, b, join in zip(pieces, pieces[1:], prof.half.joins):
        if join == "trim":
            gap = np.hypot(*(a(np.array([1.0]))[0] - b(np.array([0.0]))[0]))
            assert gap <= JOIN * m, (gap, m)
    tol = tol_m * m
    _, achieved = prof.half_points(tol)
    true = _true_deviation(prof, tol, BOUND_DENSE)
    assert achieved <= tol and true <= achieved * (1 + 1e-9), (true, achieved)


#: the pins' closed-form position at the pole: the pin at the tooth space's centre (polar angle pi/z2) on
#: the wheel's pitch circle; a flank point may lie inside that pin by round-off only (relative to r2)
INSIDE = 1e-12


@pytest.mark.parametrize("kw, tol_m", [
    # found by the long fuzz run: the bound 2e-4 (relative) below the real deviation; each pair one
    # geometry at two modules
    (dict(module=1.01, pins=66, wheel_teeth=237, pin_radius=0.2177945573786216, addendum=1.6884620611609897), 1e-5),
    (dict(module=1.6885, pins=66, wheel_teeth=237, pin_radius=0.3641050595384184, addendum=1.6884620611609897), 1e-5),
    (dict(module=35.492, pins=50, wheel_teeth=280, pin_radius=7.531626632153823, addendum=0.6904685765491765), 1e-4),
    (dict(module=0.69047, pins=50, wheel_teeth=280, pin_radius=0.14652209626685592, addendum=0.6904685765491765),
     1e-4),
    (dict(module=62.153, pins=58, wheel_teeth=148, pin_radius=9.831896749814392, addendum=0.7241012025790245), 1e-3),
    (dict(module=1.0, pins=77, wheel_teeth=52, pin_radius=0.09355629413932724, addendum=0.3), 1e-4),
    (dict(module=1.1, pins=33, wheel_teeth=33, pin_radius=0.060450664535327124, addendum=0.41414771419347557), 1e-2),
    (dict(module=0.33333, pins=73, wheel_teeth=245, pin_radius=0.09400214729609072, addendum=1 / 3), 1e-3),
    (dict(module=0.75, pins=71, wheel_teeth=256, pin_radius=0.156930157990897, addendum=0.3), 1e-5),
    (dict(module=60.891, pins=37, wheel_teeth=174, pin_radius=11.037122505607112, addendum=1.3597793068145392), 1e-3),
    (dict(module=0.11553, pins=37, wheel_teeth=174, pin_radius=0.020941005453561107, addendum=1.3597793068145392),
     1e-3),
    (dict(module=0.01, pins=48, wheel_teeth=200, pin_radius=0.0015696751015234335, addendum=0.3), 1e-5),
    (dict(module=0.3, pins=48, wheel_teeth=200, pin_radius=0.047090253045703, addendum=0.3), 1e-5),
])
def test_pin_gear_flank_ends_where_it_enters_the_pin_at_the_pole(kw, tol_m):
    """Past the tool point where its two roots meet, the envelope branch leaves the pin at the pole,
    dips inside it (that stretch is cut) and comes out again at the flank: the pole's part of the
    branch and the flank never cross, and the trim took their nearest approach (1e-8 m apart, the
    flank's end 6e-9 m inside the pin) for a crossing, so the reported chord bound missed the gap.
    Oracles: the pin at the pole in closed form (no flank point inside it, the flank's end on it, the
    root piece on it down to the space centre line), the pieces meeting, and the fuzz property's
    independent measure of the deviation within the reported bound."""
    prof = gk.pin_gear_wheel(gk.PinGearSpec(**kw))
    spec, m = prof.spec, prof.module
    centre = spec.r2 * np.array([math.sin(math.pi / spec.wheel_teeth), math.cos(math.pi / spec.wheel_teeth)])
    pieces = prof.half.pieces
    assert [p.label for p in pieces] == ["tip", "flank", "root"] and prof.half.joins[-1] == "trim"
    w = np.linspace(0.0, 1.0, 20001)
    flank, root = pieces[1](w), pieces[2](w)
    slack = INSIDE * spec.r2
    assert (np.hypot(*(flank - centre).T) >= spec.pin_radius - slack).all()
    assert abs(np.hypot(*(flank[-1] - centre)) - spec.pin_radius) <= slack
    assert np.abs(np.hypot(*(root - centre).T) - spec.pin_radius).max() <= slack
    assert np.allclose(root[-1], (spec.r2 - spec.pin_radius) * centre / spec.r2, rtol=0, atol=slack)
    assert np.hypot(*(flank[-1] - root[0])) <= JOIN * m
    tol = tol_m * m
    half, achieved = prof.half_points(tol)
    true = true_deviation(pieces, half)
    assert achieved <= tol and true <= achieved * (1 + 1e-9), (true, achieved)
