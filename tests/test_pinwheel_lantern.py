"""Pin (lantern) gearing: the wheel a pin wheel's pins cut, its trimmed loop and its checks.

Oracles: the equidistant of the epicycloid traced by a pin centre (textbook §53; reference digest
"other gears" §1.7, written out here in the standard form), the swept pins of
``gearkit.oracles.cycloid`` (ray cast, no meshing equation), the digest's first usable roll
(r1 = 25, r2 = 100, rho = 3.927 -> 0.0943 rad).

``CLOSED = 1e-9 m``; the oracle's scallop bound ``step^2/(8 rho)`` with ``SCALLOP = 1.1``.
"""
import math

import numpy as np
import pytest

from gearkit.accuracy import adaptive_sample
from gearkit.checks.cycloidal import check_pin_gearing
from gearkit.errors import SpecError
from gearkit.families.cycloidal import PinGearSpec, first_usable_roll, pin_gear_wheel
from gearkit.oracles.cycloid import swept_pin_centres, swept_pin_clearance, swept_pin_wheel

CLOSED = 1e-9
SCALLOP = 1.1

SPECS = {"8/40": PinGearSpec(1.0, 8, 40, 0.8), "10/30 m2": PinGearSpec(2.0, 10, 30, 1.2, 1.6),
         "6/10": PinGearSpec(1.0, 6, 10, 1.45, 0.3)}


def _pin_centre_path(spec, t):
    """Epicycloid of the pin centre: circle r1 rolled outside r2 from the space centre (polar pi/z2)
    towards tooth 0; x-y written from the standard equations, then turned into the wheel frame."""
    r1, r2 = spec.r1, spec.r2
    x = (r2 + r1) * np.cos(t) - r1 * np.cos((r2 + r1) / r1 * t)
    y = (r2 + r1) * np.sin(t) - r1 * np.sin((r2 + r1) / r1 * t)
    g0 = math.pi / spec.wheel_teeth
    rad, ang = np.hypot(x, y), np.arctan2(y, x)  # standard angle grows towards the tooth
    return np.stack([rad * np.sin(g0 - ang), rad * np.cos(g0 - ang)], -1)


@pytest.mark.parametrize("name", sorted(SPECS))
def test_flank_is_the_equidistant_of_the_pin_centre_epicycloid(name):
    """The working flank lies at the pin radius from the pin centre's epicycloid (to 1e-9 m); the space
    bottom is the pin itself, sitting at the pole."""
    from scipy.spatial import cKDTree

    spec = SPECS[name]
    w = pin_gear_wheel(spec)
    labels = [p.label for p in w.half.pieces]
    assert "flank" in labels and labels[-1] == "root" and w.looped
    flank = np.concatenate([adaptive_sample(p, 1e-4 * spec.module)[1] for p in w.half.pieces if p.label == "flank"])
    t = np.linspace(0.0, 1.0, 200001)
    path = _pin_centre_path(spec, t)
    _, idx = cKDTree(path).query(flank)
    x = t[idx]
    for _ in range(8):  # Newton on the foot of the perpendicular
        h = 1e-7
        p0, pp, pm = _pin_centre_path(spec, x), _pin_centre_path(spec, x + h), _pin_centre_path(spec, x - h)
        d1, d2 = (pp - pm) / (2 * h), (pp - 2 * p0 + pm) / h ** 2
        x = x - np.einsum("ij,ij->i", p0 - flank, d1) / (np.einsum("ij,ij->i", d1, d1)
                                                        + np.einsum("ij,ij->i", p0 - flank, d2))
    dist = np.linalg.norm(_pin_centre_path(spec, x) - flank, axis=1)
    assert np.abs(dist - spec.pin_radius).max() <= CLOSED * spec.module
    bottom = np.concatenate([adaptive_sample(p, 1e-4)[1] for p in w.half.pieces if p.label == "root"])
    g0 = math.pi / spec.wheel_teeth
    pin = spec.r2 * np.array([math.sin(g0), math.cos(g0)])
    assert np.linalg.norm(bottom - pin, axis=1) == pytest.approx(spec.pin_radius, abs=CLOSED * spec.module)
    assert w.root_diameter / 2 == pytest.approx(spec.r2 - spec.pin_radius, abs=CLOSED)


#: dense, sampler-independent points: each piece at this many uniform parameters
DENSE = 2001
#: pin wheels for the point-wise swept-pin comparison: the loop-trimmed ones above, a thin pin on a big
#: pin wheel (a tiny loop) and a fat pin on few wheel teeth
SWEPT = dict(SPECS, **{"50/60 thin": PinGearSpec(1.0, 50, 60, 0.04), "12/25 m3": PinGearSpec(3.0, 12, 25, 2.5, 1.2)})


def _dense_boundary(spec):
    w = pin_gear_wheel(spec)
    t = np.linspace(0.0, 1.0, DENSE)
    return {p.label: p(t) for p in w.half.pieces}, np.concatenate([p(t) for p in w.half.pieces])


def _polyline_distance(q, poly):
    """Distance of points ``q`` to the polyline ``poly`` (exact per segment, near the nearest vertex)."""
    from scipy.spatial import cKDTree

    _, i = cKDTree(poly).query(q)
    best = np.full(len(q), np.inf)
    for j in (i - 1, i):
        j = np.clip(j, 0, len(poly) - 2)
        a, d = poly[j], poly[j + 1] - poly[j]
        u = np.clip(np.einsum("ij,ij->i", q - a, d) / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300), 0, 1)
        best = np.minimum(best, np.linalg.norm(a + u[:, None] * d - q, axis=1))
    return best


@pytest.mark.parametrize("name", sorted(SWEPT))
def test_swept_pins_and_generated_wheel_agree_pointwise(name):
    """Both ways, at dense points neither side's sampler chose: (1) every point of the generated flank
    and space bottom is touched by a pin and inside none (clearance in [0, scallop]); (2) every point
    of a pin circle no other pin position covers (the swept boundary), in the half-tooth wedge and a
    ``step`` below the tip circle (the tip clips the scallops there: a gap up to about ``step`` wide), lies on the generated boundary to the scallop. A ray cast cannot do this next to
    the pitch circle: the space bottom curls back past the ray's tangent to the pin (10/30 m2: by
    0.029 mm), where the first entry along a ray is the pin's lower side. A thin pin (50/60) leaves
    material in the middle of the space, between its approach and recess paths: the wheel's space is
    the flanks and the pin at the pole, so those swept points lie in the space, never in the tooth."""
    spec = SWEPT[name]
    m, rho, z2 = spec.module, spec.pin_radius, spec.wheel_teeth
    step = 0.01 * m
    scallop = SCALLOP * step ** 2 / (8 * rho)
    args = (m, spec.pins, z2, rho, spec.tip_radius, step)
    pieces, poly = _dense_boundary(spec)
    for label in ("flank", "root"):
        clear = swept_pin_clearance(pieces[label], *args)
        assert clear.min() >= -CLOSED * m, label
        assert clear.max() <= scallop, label
    c = swept_pin_centres(*args)
    a = np.linspace(0.0, 2.0 * math.pi, 361)[:-1]
    q = (c[:, None, :] + rho * np.stack([np.cos(a), np.sin(a)], -1)[None]).reshape(-1, 2)
    r, psi = np.hypot(q[:, 0], q[:, 1]), np.arctan2(q[:, 0], q[:, 1])
    q = q[(r < spec.tip_radius - step) & (psi >= 0.0) & (psi <= math.pi / z2)]
    from scipy.spatial import cKDTree

    from matplotlib.path import Path

    exposed = q[cKDTree(c).query(q)[0] >= rho - CLOSED * m]
    assert len(exposed) >= 50
    off = _polyline_distance(exposed, poly) > scallop + CLOSED * m
    # the half tooth: its boundary closed through the wheel centre
    tooth = Path(np.concatenate([poly, [[0.0, 0.0]], poly[:1]]))
    assert not tooth.contains_points(exposed[off]).any()
    # off the boundary only in the space, between the pin's approach and recess paths (a thin pin)
    assert off.any() == (name == "50/60 thin")


def test_ray_cast_sees_the_pins_lower_side_where_the_space_bottom_curls_back():
    """Why the ray-cast comparison reported the oracle 0.029 mm deeper on 10/30 m2: the flank is trimmed
    above the radius sqrt(r2^2 - rho^2) at which rays touch the pin at the pole, so the ray through the
    trim point enters that pin first on its lower side, at r2 cos(d) - sqrt(rho^2 - r2^2 sin^2 d),
    d = pi/z2 - psi (a circle-ray intersection written out here)."""
    spec = SPECS["10/30 m2"]
    w = pin_gear_wheel(spec)
    r_trim = w.usable_flank_radius()
    assert r_trim > math.sqrt(spec.r2 ** 2 - spec.pin_radius ** 2)
    p = next(pc for pc in w.half.pieces if pc.label == "flank")(np.array([1.0]))[0]
    d = math.pi / spec.wheel_teeth - math.atan2(p[0], p[1])
    lower = spec.r2 * math.cos(d) - math.sqrt(spec.pin_radius ** 2 - (spec.r2 * math.sin(d)) ** 2)
    step = 0.01 * spec.module
    ray = swept_pin_wheel(spec.module, spec.pins, spec.wheel_teeth, spec.pin_radius, spec.tip_radius,
                          np.array([math.atan2(p[0], p[1])]), step)[0]
    # the pin positions are discrete: the ray may enter up to a scallop late
    assert lower - CLOSED * spec.module <= ray <= lower + SCALLOP * step ** 2 / (8 * spec.pin_radius)
    assert r_trim - lower == pytest.approx(0.029, abs=1e-3)


def test_loop_is_trimmed_next_to_the_pitch_circle():
    """The equidistant loops where the epicycloid's curvature radius falls below the pin radius: the
    kernel trims it where the flank meets the space bottom, just inside the pitch circle; the first
    usable roll of the digest's example."""
    assert first_usable_roll(PinGearSpec(10.0, 5, 20, 3.927)) == pytest.approx(0.0943, abs=1e-4)
    for spec in SPECS.values():
        w = pin_gear_wheel(spec)
        assert "trim" in w.half.joins
        r_use = w.usable_flank_radius()
        assert spec.r2 - spec.pin_radius < r_use < spec.r2
        report = check_pin_gearing(spec).report
        assert report["flank.loop"].value == pytest.approx(r_use)


def test_checks_contact_ratio_and_pointing():
    """A short addendum gives too little contact (fail); a long one points the wheel's teeth (warn)."""
    short = check_pin_gearing(PinGearSpec(1.0, 8, 40, 0.8, 1.0))
    assert short.report["contact_ratio"].status == "fail" and short.values["contact_ratio"] < 1
    long = check_pin_gearing(PinGearSpec(1.0, 8, 40, 0.8, 2.0))
    assert long.report["contact_ratio"].status == "warn" and long.report["pointed"].status == "warn"
    # the contact ratio grows with the working flank (taller addendum)
    assert long.values["contact_ratio"] > short.values["contact_ratio"]


@pytest.mark.parametrize("kwargs,field", [(dict(pin_radius=2.0), "pin_radius"), (dict(pins=2), "pins"),
                                          (dict(addendum=0.0), "addendum"), (dict(module=-1.0), "module")])
def test_bad_input_names_its_field(kwargs, field):
    base = dict(module=1.0, pins=8, wheel_teeth=40, pin_radius=0.8)
    base.update(kwargs)
    with pytest.raises(SpecError) as err:
        PinGearSpec(**base)
    assert err.value.field == field
