"""Fuzzing every family (hypothesis): valid geometry measured independently, or a clear SpecError.

Each property draws a spec over a wide physical range; about 15 % of the specs get one hostile
field (inf, nan, 1e300, 1e-300, 0, a negative, a string, None, a bool, a numpy scalar). Every spec
must give either

- a valid result: finite; the profile sampled to ``tol`` reports an achieved deviation within
  ``tol`` and at least the real one (a proven bound, every family), and the real one is within
  ``tol``, measured independently by dense re-evaluation of the exact pieces (``fuzzkit.true_deviation``); the outline closes without
  crossing itself (racks); a cam's outline bounds what its follower leaves of the blank, to within
  the reported deviation (a flat face's half-planes; a roller's discs along its centre path, written
  from the spec alone in tests/camoracle.py) at tols down to the cam's floor; a pointed tip has
  thickness 0, never a negative one; the summary is strict JSON; or
- a ``SpecError`` that names a field and says why.

Anything else is a defect (tests/fuzzkit.py counts the outcomes). Numpy floating-point warnings are
errors. The products (pair, Novikov and drive checks, solids) are fuzzed in tests/test_fuzz_products.py.

Fast by default (a few dozen specs per property). The long run, N specs per property, every
outcome counted and every defect listed with its reproducer (see tests/fuzzkit.py)::

    GEARKIT_FUZZ_EXAMPLES=10000 GEARKIT_FUZZ_REPORT=fuzz.jsonl nice python -m pytest tests/test_fuzz.py -p no:randomly
"""
import math

import numpy as np
import pytest
from fuzzkit import (assert_clean, check_flat_cam, fuzz_settings, maybe_hostile, modules, run, strict_json,
                     true_deviation, write_report)
from hypothesis import given
from hypothesis import strategies as st

import gearkit as gk
from gearkit.curves import polyline_self_intersections

#: the dense measure is itself a polyline of the exact curve: it may read up to its own chord
#: error below the true deviation, never above; allow that much plus round-off
MEASURE_SLACK = 1e-3
#: the reported deviation is a proven bound: the measure may exceed it by round-off only
BOUND_SLACK = 1e-9


@pytest.fixture(autouse=True, scope="module")
def _report():
    yield
    write_report()


tols = st.sampled_from([1e-2, 1e-3, 1e-4, 1e-5])


def _tool(desc):
    """A tool from its description ("shaper", args...) / ("rack", args...), built inside the property."""
    if not isinstance(desc, tuple):
        return desc
    kind, *args = desc
    return gk.ShaperCutter(*args) if kind == "shaper" else gk.BasicRack(*args)


def _check_bound(polyline, achieved, true, tol):
    """The sampling contract: the reported deviation and the real one are within tol, and the reported
    one bounds the real one (a proven bound in every family: the dense measure reads at most the real
    deviation, so it may not exceed the bound beyond round-off)."""
    assert np.isfinite(polyline).all() and achieved <= tol, f"reported {achieved:.3g} above tol {tol:.3g}"
    assert true <= tol * (1 + MEASURE_SLACK), f"sampled curve is {true:.3g} off at tol {tol:.3g}"
    assert true <= achieved * (1 + BOUND_SLACK), f"reported {achieved:.3g} below the real {true:.3g}"


def _check_half(prof, tol):
    half, achieved = prof.half_points(tol)
    _check_bound(half, achieved, true_deviation(prof.half.pieces, half), tol)
    return half


def _check_gear(prof, tol):
    _check_half(prof, tol)
    assert prof.tip_thickness >= 0.0 and math.copysign(1.0, prof.tip_thickness) > 0
    assert prof.tip_thickness == 0.0 or not prof.pointed  # a smooth crest (dz = 1 disc) has 0 too
    if hasattr(prof, "summary"):
        strict_json(prof.summary(tol))


# -- families -------------------------------------------------------------------------------------
#: the least tip land (module units) of a drawn shaper cutter's tooth
CUTTER_LAND = 0.02


def _cutter_tip_land(z0, alpha_deg, x0, addendum=1.25):
    """Half the tooth thickness (module units) of a shaper cutter at its tip circle (textbook: the
    arc thickness ``s_a = d_a (s / d + inv a - inv a_a)`` with ``s = m (pi/2 + 2 x0 tan a)``)."""
    a = math.radians(alpha_deg)
    ra = z0 / 2 + x0 + addendum
    a_tip = math.acos(min(1.0, z0 * math.cos(a) / (2 * ra)))
    return ra * ((math.pi / 2 + 2 * x0 * math.tan(a)) / z0 + math.tan(a) - a - math.tan(a_tip) + a_tip)


def _cutter_top_shift(z0, alpha_deg):
    """The largest cutter shift in [-1, 0.5] that leaves the tooth ``CUTTER_LAND`` at its tip (bisection:
    the land narrows as the shift grows), or -1."""
    lo, hi = -1.0, 0.5
    if _cutter_tip_land(z0, alpha_deg, hi) >= CUTTER_LAND or _cutter_tip_land(z0, alpha_deg, lo) < CUTTER_LAND:
        return hi if _cutter_tip_land(z0, alpha_deg, hi) >= CUTTER_LAND else lo
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _cutter_tip_land(z0, alpha_deg, mid) >= CUTTER_LAND else (lo, mid)
    return lo


@st.composite
def shaper_for_internal(draw, alpha):
    """A shaper cutter (description) that cuts internal gears: its tooth not pointed (a 30 degree
    cutter needs a negative shift), one draw in ten over the whole range (the refusals)."""
    z0 = draw(st.integers(8, 40))
    if 45 <= draw(st.integers(0, 99)) < 55:  # a band inside the range: hypothesis favours its ends
        return ("shaper", z0, alpha, draw(st.floats(-0.3, 0.5)))
    top = _cutter_top_shift(z0, alpha)
    return ("shaper", z0, alpha, draw(st.floats(max(-1.0, min(-0.3, top - 0.3)), top)))


@st.composite
def involute_kwargs(draw, kind):
    alpha = draw(st.sampled_from([14.5, 20.0, 25.0, 30.0]))
    m = draw(modules)
    thinning = draw(st.sampled_from([0.0, 0.0, 0.05])) * m  # mm: a share of the tooth, whatever the module
    if kind == "internal":
        tool = draw(shaper_for_internal(alpha))
        z = tool[1] + draw(st.integers(4, 400))
        beta, thinning = 0.0, 0.0  # a shaper-cut gear is thinned by the cutter's setting, not by a thinning
    else:
        tool = ("rack", alpha, 1.0, draw(st.sampled_from([1.1, 1.25, 1.4])), None,
                draw(st.sampled_from([0.0, 0.0, 0.0, 0.05, 0.1])))
        z = draw(st.one_of(st.integers(3, 80), st.integers(80, 5000)))
        beta = draw(st.floats(-40.0, 40.0)) if kind == "helical" else 0.0
    return draw(maybe_hostile(dict(teeth=z, module=m, shift=draw(st.floats(-1.5, 2.5)),
                                   helix_angle_deg=beta, internal=kind == "internal", tool=tool,
                                   thinning=thinning)))


def _involute(kind):
    @fuzz_settings(14)
    @given(kw=involute_kwargs(kind), tol_m=tols)
    def prop(kw, tol_m):
        def build():
            return gk.tooth_profile(gk.GearSpec(**{**kw, "tool": _tool(kw["tool"])}))
        run(f"involute_{kind}", (kw, tol_m), build, lambda prof: _check_gear(prof, tol_m * prof.module))
    prop()
    assert_clean(f"involute_{kind}")


@pytest.mark.parametrize("kind", ["external", "internal", "helical"])
def test_involute(kind):
    _involute(kind)


@st.composite
def rack_kwargs(draw):
    if draw(st.booleans()):
        tool = ("shaper", draw(st.integers(8, 60)))
    else:
        tool = ("rack", draw(st.sampled_from([15.0, 20.0, 25.0])), 1.0, draw(st.sampled_from([1.25, 1.3, 1.4])),
                None, draw(st.sampled_from([0.0, 0.0, 0.05, 0.1, 0.15])))
    return draw(maybe_hostile(dict(module=draw(modules), tool=tool,
                                   helix_angle_deg=draw(st.sampled_from([0.0, 15.0, 30.0])))))


@fuzz_settings(30)
@given(kw=rack_kwargs(), tol_m=tols, teeth=st.integers(1, 4))
def _rack(kw, tol_m, teeth):
    def check(prof):
        tol = tol_m * prof.module
        _check_half(prof, tol)
        out = prof.outline(tol, teeth=teeth)
        assert len(polyline_self_intersections(out)[0]) == 0, "the rack outline crosses itself"
        assert np.allclose(out[-1] - out[0], [teeth * prof.pitch, 0.0], atol=1e-9 * prof.module)
    run("rack", (kw, tol_m, teeth), lambda: gk.rack_profile(gk.RackSpec(**{**kw, "tool": _tool(kw["tool"])})),
        check)


def test_rack():
    _rack()
    assert_clean("rack")


@fuzz_settings(15)
@given(data=st.data(), tol_m=tols)
def _novikov(data, tol_m):
    system = data.draw(st.sampled_from(["dca24", "single-arc"]))
    which = data.draw(st.sampled_from(["rack1", "rack2"]))
    kw = data.draw(maybe_hostile(dict(teeth=data.draw(st.integers(3, 400)), module=data.draw(modules),
                                      helix_angle_deg=data.draw(st.floats(5.0, 40.0)))))
    rack = getattr(gk.rack_system(system), which)
    run("novikov", (system, which, kw, tol_m), lambda: gk.novikov_tooth_profile(gk.NovikovGearSpec(rack=rack, **kw)),
        lambda prof: _check_gear(prof, tol_m * prof.module))


def test_novikov():
    _novikov()
    assert_clean("novikov")


@fuzz_settings(30)
@given(data=st.data(), tol_m=tols)
def _cycloid_disc(data, tol_m):
    pins = data.draw(st.integers(3, 80))
    dz = data.draw(st.sampled_from([-3, -2, -1, 1, 2, 3]))
    big_r = data.draw(st.floats(1.0, 500.0))
    kw = data.draw(maybe_hostile(dict(pins=pins, lobes=pins - dz, pin_circle_radius=big_r,
                                      pin_radius=data.draw(st.floats(0.02, 0.7)) * math.pi * big_r / pins,
                                      eccentricity=data.draw(st.floats(0.02, 0.98)) * big_r * abs(dz) / pins)))
    run("cycloid_disc", (kw, tol_m), lambda: gk.disc_profile(gk.DriveSpec(**kw)),
        lambda prof: _check_gear(prof, tol_m * prof.module))


def test_cycloid_disc():
    _cycloid_disc()
    assert_clean("cycloid_disc")


@fuzz_settings(30)
@given(data=st.data(), tol_m=tols)
def _pin_gear(data, tol_m):
    z1 = data.draw(st.integers(3, 80))
    m = data.draw(modules)
    kw = data.draw(maybe_hostile(dict(module=m, pins=z1, wheel_teeth=data.draw(st.integers(3, 300)),
                                      pin_radius=data.draw(st.floats(0.02, 0.98)) * m * z1 / 2 * math.sin(math.pi / z1),
                                      addendum=data.draw(st.floats(0.3, 2.0)))))
    run("pin_gear", (kw, tol_m), lambda: gk.pin_gear_wheel(gk.PinGearSpec(**kw)),
        lambda prof: _check_gear(prof, tol_m * prof.module))


def test_pin_gear():
    _pin_gear()
    assert_clean("pin_gear")


@fuzz_settings(20)
@given(data=st.data(), tol_m=tols)
def _cycloid_pair_gear(data, tol_m):
    z1 = data.draw(st.integers(4, 120))
    kw = data.draw(maybe_hostile(dict(module=data.draw(modules), pinion_teeth=z1,
                                      wheel_teeth=z1 + data.draw(st.integers(0, 300)),
                                      clock=data.draw(st.booleans()))))
    which = data.draw(st.sampled_from([1, 2]))
    run("cycloid_pair_gear", (kw, which, tol_m), lambda: gk.cycloid_gear(gk.CycloidPairSpec(**kw), which),
        lambda prof: _check_gear(prof, tol_m * prof.module))


def test_cycloid_pair_gear():
    _cycloid_pair_gear()
    assert_clean("cycloid_pair_gear")


@st.composite
def cam_kwargs(draw):
    follower = draw(st.sampled_from(["translating", "rocker"]))
    contact = draw(st.sampled_from(["roller", "roller", "knife", "flat"]))
    r0 = draw(st.floats(5.0, 200.0))
    kw = dict(prime_radius=r0, follower=follower, contact=contact,
              roller_radius=draw(st.floats(0.05, 0.8)) * r0 if contact == "roller" else 0.0)
    if follower == "translating":
        kw["offset"] = 0.0 if contact == "flat" else draw(st.floats(-0.5, 0.5)) * r0
    else:
        kw["pivot_distance"] = draw(st.floats(1.2, 3.0)) * r0
        kw["arm_length"] = draw(st.floats(0.5, 1.5)) * kw["pivot_distance"]
    law = draw(st.sampled_from(["cycloidal", "harmonic", "polynomial_345", "polynomial_4567",
                                "modified_trapezoid", "modified_sine", "constant_velocity"]))
    # lifts up to a few prime radii over short rises: the steep, deeply undercut cams where the roller's
    # swept finger once left its outer side in the outline, and a flat rocker's face turning back relative
    # to the cam put its kept arcs out of the order of the cam angle
    lift = draw(st.one_of(st.floats(0.02, 0.6), st.floats(0.6, 4.0)))
    dwell = st.floats(0.0, 60.0)
    if contact == "flat" and draw(st.booleans()):
        # tiny lifts (1e-6 to 1e-3 r0; rockers and translating faces), with and without near-zero dwells: a
        # constant-velocity law's slides along the face at its velocity jumps fold within a fraction of a line
        # step of the jump, as shallow as the excess of the half-planes' polygon there, and a dwell of 1e-3
        # degrees lies between two such; a slide back a few micrometres long lies inside a kept arc
        lift = 10.0 ** draw(st.floats(-6.0, -3.0))
        dwell = st.one_of(dwell, st.sampled_from([0.0, 1e-12, 1e-6, 1e-3, 1e-2]))
    motion = (lift * r0, draw(st.floats(20.0, 150.0)), draw(dwell), draw(st.floats(20.0, 150.0)), law)
    return draw(maybe_hostile(kw)), motion


#: the finest tol of a cam's outline, in (r0 + stroke): a roller's (twice the keep test's slack, the depth
#: in a roller of a loop its outline may keep) and a knife's or flat face's (the geometry's own precision)
CAM_FLOOR = {"roller": 2e-7, "knife": 1e-9, "flat": 1e-9}


@fuzz_settings(20)
@given(drawn=cam_kwargs(), tol_m=st.sampled_from([1e-3, 1e-4, 1e-5, 1e-6, 1e-7]))
def _cam(drawn, tol_m):
    from camoracle import centres_for, check_swept_discs

    from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

    kw, motion = drawn

    def build():
        return cam_profile(CamSpec(motion=MotionProgram.rise_dwell_return(*motion), **kw))

    def check(prof):
        spec = prof.spec  # tol_m r0, down to the floor (a hair above it: the range is closed)
        tol = max(tol_m * spec.prime_radius, (1 + 1e-9) * CAM_FLOOR[spec.contact] * (spec.prime_radius + spec.stroke))
        out, achieved = prof.outline(tol), prof.achieved(tol)
        closed = np.concatenate([out[::-1], out[-1:]])  # the pieces' own order, closed
        _check_bound(out, achieved, true_deviation(prof.pieces, closed), tol)
        if spec.contact == "flat":  # the cam is the intersection of the face's half-planes
            check_flat_cam(spec, out, tol)
        elif spec.contact == "roller":  # the cam is what the roller's discs along its centre path leave
            check_swept_discs(spec, out, achieved, centres_for(spec, tol))
    run("cam", (kw, motion, tol_m), build, check)


def test_cam():
    _cam()
    assert_clean("cam")
