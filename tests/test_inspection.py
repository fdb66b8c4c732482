"""Inspection dimensions: standard formulas against independent closed forms and published values,
and against measurement on the generated tooth (the second method)."""
import math

import pytest

from gearkit.checks.inspection import inspection_findings
from gearkit.errors import SpecError
from gearkit.families.involute import GearSpec, tooth_profile
from gearkit.pair.dimensions import chordal, over_pins, span, suggested_pin
from gearkit.pair.gauging import measure_chordal, measure_over_pins, measure_span
from gearkit.pair.inspection import inspect_gear
from gearkit.pair.tooling import section
from gearkit.families.involute import ShaperCutter

AGREE = 1e-6  # mm: formula and measurement on a sound involute flank (the requirement)
EXACT = 1e-9  # mm: two closed forms of the same quantity (round-off of a few ulp of ~100 mm, with margin)
A20 = math.radians(20.0)


def inv(a):
    return math.tan(a) - a


def inv_inverse(v):
    a = 0.5
    for _ in range(100):
        a -= (math.tan(a) - a - v) / math.tan(a) ** 2
    return a


def textbook_span(m, z, x, k, beta_deg=0.0):
    """W = m_n cos a_n [pi (k - 0.5) + z inv a_t] + 2 x m_n sin a_n (the classical span formula)."""
    b = math.radians(beta_deg)
    at = math.atan(math.tan(A20) / math.cos(b))
    return m * math.cos(A20) * (math.pi * (k - 0.5) + z * inv(at)) + 2 * x * m * math.sin(A20)


def textbook_pins(m, z, x, d_p, beta_deg=0.0, internal=False):
    """inv a_M = inv a_t +- (d_p/(z m_n cos a_n) - pi/(2z)) + 2 x tan a_n / z, M = d_b/cos a_M (cos 90/z) +- d_p."""
    b = math.radians(beta_deg)
    at = math.atan(math.tan(A20) / math.cos(b))
    sign = -1.0 if internal else 1.0
    v = inv(at) + sign * (d_p / (z * m * math.cos(A20)) - math.pi / (2 * z)) + 2 * x * math.tan(A20) / z
    am = inv_inverse(v)
    db = z * m / math.cos(b) * math.cos(at)
    c = math.cos(math.pi / (2 * z)) if z % 2 else 1.0
    return db / math.cos(am) * c + sign * d_p


def test_span_published_example():
    # m = 2, z = 20, x = 0, alpha 20: k = 3, W = 15.321 mm, anvils on d = 40.59 mm (published, 3 and 2 decimals)
    s = span(section(2.0, 20.0, 0.0), 20, 0.0)
    assert s.k == 3
    assert round(s.W, 3) == 15.321
    assert round(s.d_M, 2) == 40.59


@pytest.mark.parametrize("z, x, beta", [(20, 0.0, 0.0), (31, 0.3, 0.0), (17, -0.1, 0.0), (24, 0.5, 15.0),
                                        (41, 0.0, 30.0), (13, 0.4, 0.0)])
def test_span_formula_and_measurement(z, x, beta):
    m = 2.5
    sec = section(m, 20.0, beta)
    s = span(sec, z, 2 * x * math.tan(A20))
    assert s.W == pytest.approx(textbook_span(m, z, x, s.k, beta), abs=EXACT)
    # the standard span number puts the anvils' contact nearest d + 2 x m_n (in roll length along the
    # base tangent, W_t / 2 against r_b tan a_M): k +- 1 are farther
    rb = z * sec.mt * math.cos(sec.alpha_t) / 2
    target = math.sqrt((z * sec.mt / 2 + x * m) ** 2 - rb ** 2)
    for k in (s.k - 1, s.k + 1):
        if 1 <= k <= (z + 1) // 2:
            assert abs(span(sec, z, 2 * x * math.tan(A20), k).W_t / 2 - target) >= abs(s.W_t / 2 - target)
    measured, touch = measure_span(tooth_profile(GearSpec(z, m, x, beta)), s.k, sec.beta_b)
    assert touch == "flank"
    assert measured.W == pytest.approx(s.W, abs=AGREE)
    assert s.b_min == pytest.approx(s.W * math.sin(sec.beta_b), abs=EXACT)


def test_span_teeth_settable_and_checked():
    sec = section(1.0, 20.0, 0.0)
    assert span(sec, 30, 0.0, 5).W - span(sec, 30, 0.0, 4).W == pytest.approx(math.pi * math.cos(A20), abs=EXACT)
    with pytest.raises(SpecError, match="span_teeth"):
        span(sec, 30, 0.0, 16)
    with pytest.raises(SpecError, match="span_teeth"):
        inspect_gear(GearSpec(30, 1.0), span_teeth=2.5)


@pytest.mark.parametrize("z, x, beta", [(20, 0.0, 0.0), (21, 0.2, 0.0), (19, -0.2, 20.0), (30, 0.6, 25.0)])
def test_over_pins_external(z, x, beta):
    m = 2.0
    sec = section(m, 20.0, beta)
    delta = 2 * x * math.tan(A20)
    d_p = 3.5
    p = over_pins(sec, z, delta, d_p)
    assert p.M == pytest.approx(textbook_pins(m, z, x, d_p, beta), abs=EXACT)
    measured, touch = measure_over_pins(tooth_profile(GearSpec(z, m, x, beta)), d_p, sec.beta_b)
    assert touch == "flank"
    assert measured.M == pytest.approx(p.M, abs=AGREE)


@pytest.mark.parametrize("z2, z0", [(24, 16), (25, 16), (60, 20)])
def test_between_pins_internal(z2, z0):
    m = 3.0
    spec = GearSpec(z2, m, 0.2, internal=True, tool=ShaperCutter(z0))
    sec = section(m, 20.0, 0.0)
    from gearkit.pair.inspection import gear_thickness_coeff
    delta = gear_thickness_coeff(spec)
    x_iso = -delta / (2 * math.tan(A20))  # the ring's shift by its thickness
    d_p = 5.0
    p = over_pins(sec, z2, delta, d_p, internal=True)
    assert p.M == pytest.approx(textbook_pins(m, z2, x_iso, d_p, internal=True), abs=EXACT)
    measured, touch = measure_over_pins(tooth_profile(spec), d_p)
    assert touch == "flank"
    assert measured.M == pytest.approx(p.M, abs=AGREE)


@pytest.mark.parametrize("internal", [False, True])
def test_suggested_pin_touches_the_reference_circle(internal):
    sec = section(2.0, 20.0, 0.0)
    z, delta = 24, 0.1
    d_p = suggested_pin(sec, z, delta, internal)
    p = over_pins(sec, z, delta, d_p, internal)
    assert p.d_contact == pytest.approx(z * 2.0, abs=EXACT)
    # the contact normal is tangent to the base circle: contact, pin centre and the base tangent line
    rb = z * 2.0 * math.cos(A20) / 2
    roll_c = math.sqrt((p.d_contact / 2) ** 2 - rb ** 2)
    roll_m = math.sqrt((p.d_M / 2) ** 2 - rb ** 2)
    assert abs(roll_m - roll_c) == pytest.approx(d_p / 2, abs=EXACT)


def test_chordal_spur_textbook():
    # x = 0 at the reference circle: s = z m sin(90/z), h = m + z m/2 (1 - cos(90/z))
    m, z = 2.0, 20
    c = chordal(section(m, 20.0, 0.0), z, 0.0, z * m + 2 * m)
    assert c.s == pytest.approx(z * m * math.sin(math.pi / (2 * z)), abs=EXACT)
    assert c.h == pytest.approx(m + z * m / 2 * (1 - math.cos(math.pi / (2 * z))), abs=EXACT)
    measured = measure_chordal(tooth_profile(GearSpec(z, m)))
    assert (measured.s, measured.h) == pytest.approx((c.s, c.h), abs=AGREE)


def test_chordal_at_a_given_circle_and_on_a_ring():
    m, z = 2.0, 27
    spec = GearSpec(z, m, 0.25)
    sec = section(m, 20.0, 0.0)
    d_y = z * m + 1.0
    c = chordal(sec, z, 2 * 0.25 * math.tan(A20), spec.blank_tip_diameter, d_y=d_y)
    ay = math.acos(z * m * math.cos(A20) / d_y)
    psi = (math.pi / 2 + 2 * 0.25 * math.tan(A20)) / z + inv(A20) - inv(ay)
    assert c.s == pytest.approx(d_y * math.sin(psi), abs=EXACT)
    measured = measure_chordal(tooth_profile(spec), d_y)
    assert (measured.s, measured.h) == pytest.approx((c.s, c.h), abs=AGREE)
    ring = GearSpec(40, m, 0.0, internal=True, tool=ShaperCutter(20))
    insp = inspect_gear(ring)
    assert insp.span is None
    assert insp.deviations["chordal.s"] < AGREE and insp.deviations["chordal.h"] < AGREE


def test_chordal_helical_virtual_gear():
    m, z, beta = 2.0, 21, 25.0
    sec = section(m, 20.0, beta)
    spec = GearSpec(z, m, 0.0, beta)
    c = chordal(sec, z, 0.0, spec.blank_tip_diameter)
    # the standard's virtual spur gear: z_n = z/(cos^2 b_b cos b), s_n = pi m/2 at d_n = m z_n
    z_n = z / (math.cos(sec.beta_b) ** 2 * math.cos(sec.beta))
    assert c.s == pytest.approx(m * z_n * math.sin(math.pi / (2 * z_n)), abs=EXACT)
    assert c.h == pytest.approx(m + m * z_n / 2 * (1 - math.cos(math.pi / (2 * z_n))), abs=EXACT)
    # measured in the normal section: the chord's ends lie on the reference cylinder (an exact invariant)
    meas = measure_chordal(tooth_profile(spec), None, sec.beta)
    r, ra = spec.reference_diameter / 2, spec.blank_tip_diameter / 2
    u, v = meas.s / 2, ra - meas.h
    assert (u * math.cos(sec.beta)) ** 2 + v ** 2 == pytest.approx(r ** 2, abs=EXACT * r)
    # the approximation is second order in the tooth's half chord: below (s/2)^2/(2 r) (1 - cos^2 b / cos^2 b_b)
    bound = (c.s / 2) ** 2 / (2 * r) * abs(1 - math.cos(sec.beta) ** 2 / math.cos(sec.beta_b) ** 2) * 1.5
    assert abs(meas.h - c.h) < bound


def test_undercut_gear_parts_formula_and_measurement():
    # z = 8, x = -0.5 is deeply undercut: the anvils rest on the fillet edge, the formula misreads the span
    insp = inspect_gear(GearSpec(8, 2.0, -0.5))
    assert insp.span_contact == "fillet"
    tol = 2e-3
    assert insp.deviations["span.W"] > tol
    span_finding = next(f for f in inspection_findings(insp, tol) if f.id == "inspection.span")
    assert span_finding.status == "warn" and "fillet" in span_finding.message


def test_sound_gear_findings_ok_and_face_width():
    insp = inspect_gear(GearSpec(23, 2.0, 0.2, 20.0))
    assert max(insp.deviations[k] for k in ("span.W", "over_pins.M")) < AGREE
    found = {f.id: f for f in inspection_findings(insp, 2e-3, face_width=3.0)}
    assert found["inspection.span"].status == "ok" and found["inspection.over_pins"].status == "ok"
    assert found["inspection.face_width"].status == "warn"  # b = 3 mm < W sin b_b
    assert found["inspection.face_width"].limit == pytest.approx(insp.span.b_min)
    wide = {f.id: f for f in inspection_findings(insp, 2e-3, face_width=insp.span.b_min + 1)}
    assert wide["inspection.face_width"].status == "ok"


def test_big_pin_rests_on_the_tips():
    # a pin too big for the space touches the tip corners: measurement and formula part, and it is told
    insp = inspect_gear(GearSpec(20, 2.0), pin_diameter=8.0)
    assert insp.pin_contact == "tip corner"
    assert insp.deviations["over_pins.M"] > 1e-3


def _cli_json(capsys, argv):
    import json

    from gearkit.cli import main
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_gear_command_reports_the_dimensions(capsys):
    # m = 2, z = 20: the published span over k = 3; pins and chordal against the closed forms of this file
    info = _cli_json(capsys, ["gear", "-z", "20", "-m", "2", "--pin-diameter", "3.5", "--json"])
    assert info["span"]["k"] == 3 and round(info["span"]["W"], 3) == 15.321
    assert info["over_pins"]["d_p"] == 3.5
    assert info["over_pins"]["M"] == pytest.approx(textbook_pins(2.0, 20, 0.0, 3.5), abs=EXACT)
    assert info["chordal"]["s"] == pytest.approx(40 * math.sin(math.pi / 40), abs=EXACT)
    assert info["span"]["measured"]["W"] == pytest.approx(info["span"]["W"], abs=AGREE)
    assert [f["status"] for f in info["findings"]] == ["ok", "ok", "ok"]
    info = _cli_json(capsys, ["gear", "-z", "30", "-m", "1", "--span-teeth", "5", "--chordal-diameter", "31",
                              "--json"])
    assert info["span"]["k"] == 5
    assert info["span"]["W"] == pytest.approx(textbook_span(1.0, 30, 0.0, 5), abs=EXACT)
    assert info["chordal"]["d_y"] == 31.0


def test_bad_span_teeth_is_one_line(capsys):
    from gearkit.cli import main
    assert main(["gear", "-z", "30", "-m", "1", "--span-teeth", "40"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "span_teeth" in err[0]


def test_pair_check_reports_both_gears(capsys):
    from gearkit.checks import check_pair
    from gearkit.pair import PairSpec
    res = check_pair(PairSpec(18, 41, 2.0, 0.3, -0.1))
    gears = res.to_dict()["gears"]
    for i, (z, x) in enumerate(((18, 0.3), (41, -0.1))):
        k = gears[i]["inspection"]["span"]["k"]
        assert gears[i]["inspection"]["span"]["W"] == pytest.approx(textbook_span(2.0, z, x, k), abs=EXACT)
        assert res.report[f"inspection.span.{i + 1}"].status == "ok"


@pytest.mark.parametrize("z, x", [(20, 0.0), (9, 0.3), (40, -0.2)])
def test_over_pins_evaluates_each_point_of_the_tooth_once(monkeypatch, z, x):
    """The pin's contact search refines one nearest point per trial centre; the centres are close, so the
    refinements start at the same points of the tooth: each point is evaluated once per measurement
    (a repeat would be the same exact evaluation again), and the dimension is still the formula's."""
    from gearkit.boundary import Piece

    prof = tooth_profile(GearSpec(z, 2.0, x))
    seen, repeats = set(), []
    evaluate = Piece.__call__

    def counting(self, t):
        if len(t) == 1:
            key = (id(self), float(t[0]))
            if key in seen:
                repeats.append(key)
            seen.add(key)
        return evaluate(self, t)

    monkeypatch.setattr(Piece, "__call__", counting)
    formula = over_pins(section(2.0, 20.0, 0.0), z, 2 * x * math.tan(A20), 3.5)
    measured, touch = measure_over_pins(prof, 3.5, near=formula.d_M / 2)
    assert len(seen) > 10 and repeats == []
    if touch == "flank":
        assert measured.M == pytest.approx(formula.M, abs=AGREE)
