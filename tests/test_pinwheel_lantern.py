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
from gearkit.curves import polar_from_y
from gearkit.errors import SpecError
from gearkit.families.cycloidal import PinGearSpec, first_usable_roll, pin_gear_wheel
from gearkit.oracles.cycloid import swept_pin_wheel

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


@pytest.mark.parametrize("name", ["8/40", "10/30 m2"])
def test_swept_pins_agree_within_their_step_error(name):
    """The ray cast gives the boundary's radius per polar angle, so it needs flanks that rays from the
    centre cross once (the 6/10 wheel's flank curls back: undercut by its big pins)."""
    spec = SPECS[name]
    # the refinement's own vertices (not the fewest placement): the points this comparison was set up on
    pts = np.concatenate([adaptive_sample(p, 1e-7 * spec.module, fewest=False)[1][(k > 0):]
                          for k, p in enumerate(pin_gear_wheel(spec).half.pieces)])
    rho, psi = polar_from_y(pts[np.linspace(0, len(pts) - 1, 41).astype(int)])
    worst = []
    for step in (0.02 * spec.module, 0.01 * spec.module):
        err = swept_pin_wheel(spec.module, spec.pins, spec.wheel_teeth, spec.pin_radius, spec.tip_radius, psi,
                              step) - rho
        assert err.min() >= -CLOSED
        assert err.max() <= SCALLOP * step ** 2 / (8 * spec.pin_radius)
        worst.append(err.max())
    assert worst[1] <= 0.5 * worst[0] + CLOSED


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
