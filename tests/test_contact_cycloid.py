"""Contact analysis of the cycloidal family's generated profiles: the cycloid–pin-wheel drive (pins
carrying load against the disc), cycloid gear pairs and pin gearing.

Oracles: the reference digest "cycloid" §1.10/§4 items 6–8 (contact ratios of the four worked
drives: 6.0000, 6.4199, 5.7125, 7.5; every pin of an unmodified dz = 1 drive touches), and for
cycloid pairs the arcs of approach and recess on the generating circles (the family's closed
form) and the law of gearing (contacts on the generating circles through the pitch point).

``EPS_TOL = 1e-3`` is the issue's and the digest's tolerance for a time-averaged pin count.
``TOL = 1e-3 m`` is the simulation's search tolerance (m = 2e for a drive).
"""
import math

import numpy as np
import pytest

from gearkit.contact import Mesh, pin_ring, simulate, table
from gearkit.families.cycloidal import (CycloidPairSpec, DriveSpec, PinGearSpec, contact_ratio, cycloid_gear,
                                        disc_profile, pair_contact_ratio, pin_gear_wheel)

EPS_TOL = 1e-3
STEPS = 48

DRIVES = {  # digest §1.10: (Z_b, Z_g, R_Z, r_Z, e) and the contact ratio eps
    "+1": ((12, 11, 90.0, 7.0, 4.0), 6.0000),
    "+2": ((24, 22, 90.0, 7.0, 4.0), 6.4199),
    "+3": ((36, 33, 90.0, 7.0, 4.0), 5.7125),
    "-1": ((15, 16, 120.0, 10.0, 5.0), 7.5),
}


def _drive(args):
    spec = DriveSpec(*args)
    disc = disc_profile(spec)
    pins = pin_ring(spec.pins, spec.pin_circle_radius, spec.pin_radius, internal=spec.tooth_difference > 0)
    return spec, Mesh(disc, pins, spec.eccentricity)


@pytest.mark.parametrize("case", sorted(DRIVES))
def test_load_carrying_pins_average_the_contact_ratio(case):
    """Issue item 5 (digest §4 item 7): the time-averaged count of pins in contact on the loaded side,
    disc driving, equals the drive's analytic eps to 1e-3."""
    args, eps = DRIVES[case]
    spec, mesh = _drive(args)
    assert contact_ratio(spec) == pytest.approx(eps, abs=1e-4)
    res = simulate(mesh, STEPS)
    assert res.contact_ratio == pytest.approx(eps, abs=EPS_TOL)
    assert not res.interference.found
    assert abs(res.backlash) <= 1e-6 * spec.eccentricity  # unmodified: the pins leave no play


@pytest.mark.parametrize("case", ["+2", "-1"])
def test_drive_results_do_not_hang_on_the_tables_last_bits(case, monkeypatch):
    """The tables' interpolation matrix is LAPACK's inverse, whose last bits follow the CPU's kernel (so
    machines differed): tables fitted through an inverse a few units in the last place off must give
    the same count and no play. Round-off may move the count by at most a quarter of the digest's
    tolerance. (Before the minimiser's noise-aware end test and the exact crest values: 6.41861,
    6.41934 or 6.41993 for +2, an interval end settled on the tables' fitting error; up to -1.3e-5 mm of
    play for -1, a crest contact valued on the tables.)"""
    args, eps = DRIVES[case]
    spec = DriveSpec(*args)
    base = table._VANDER_INV
    i, j = np.indices(base.shape)
    results = []
    for ulps in (0, 2, -2):
        monkeypatch.setattr(table, "_VANDER_INV", base + ulps * np.spacing(base) * (-1.0) ** (i + j))
        results.append(simulate(_drive(args)[1], STEPS))
    for res in results:
        assert res.contact_ratio == pytest.approx(results[0].contact_ratio, abs=EPS_TOL / 4)
        assert res.contact_ratio == pytest.approx(eps, abs=EPS_TOL)
        assert abs(res.backlash) <= 1e-6 * spec.eccentricity


def test_every_pin_of_an_unmodified_single_difference_drive_touches():
    """Digest §4 item 8: dz = +1, all 12 pins touch at every crank angle, half on each side."""
    spec, mesh = _drive(DRIVES["+1"][0])
    res = simulate(mesh, 16)
    assert res.pairs_in_contact.min() >= 6
    assert np.mean(res.pairs_in_contact) == pytest.approx(6.0, abs=0.25)


def test_equidistant_modification_opens_backlash():
    """A disc ground with larger pins (dr = 0.02 mm) leaves play on both sides; no pin then jams."""
    args = DRIVES["+1"][0]
    spec = DriveSpec(*args, equidistant_mod=0.02)
    pins = pin_ring(spec.pins, spec.pin_circle_radius, spec.pin_radius)
    res = simulate(Mesh(disc_profile(spec), pins, spec.eccentricity), 16)
    assert res.backlash > 0
    assert not res.interference.found
    # normal play: the gap 2 dr between the modified flank pair, along the contact normal (first order)
    assert res.backlash_normal == pytest.approx(2 * 0.02, rel=0.05)


@pytest.mark.parametrize("spec", [CycloidPairSpec(1.0, 8, 64), CycloidPairSpec(1.0, 12, 30),
                                  CycloidPairSpec(1.0, 8, 64, clock=True)], ids=["8/64", "12/30", "clock 8/64"])
def test_cycloid_pairs_are_conjugate(spec):
    """Issue item 1 (cycloid): TE on the pitch circle <= 10 tol, the contact on the generating circles
    through the pitch point within tol; the contact ratio is the arcs' (family closed form)."""
    tol = 1e-3 * spec.module
    res = simulate(Mesh(cycloid_gear(spec, 1), cycloid_gear(spec, 2), spec.center_distance), STEPS)
    assert res.transmission_error_max * spec.r2 <= 10 * tol
    p = res.contacts["point"]
    a1, a2 = spec.rolling(1), spec.rolling(2)
    d1 = np.abs(np.hypot(p[:, 0], p[:, 1] - (spec.r1 - a1)) - a1)  # circle a1 inside the pinion
    d2 = np.abs(np.hypot(p[:, 0], p[:, 1] - (spec.r1 + a2)) - a2)  # circle a2 inside the wheel
    assert np.minimum(d1, d2).max() <= tol
    assert res.contact_ratio == pytest.approx(pair_contact_ratio(spec), abs=EPS_TOL)
    assert not res.interference.found


#: TE of a conjugate pair on its exact envelopes: the bound values' round-off (w and u about a pitch, 1e-16 rad)
#: with a factor 1e4 of headroom, far below the glitches of an end taken for a minimum (1e-8 to 1.4e-7 rad)
TE_ROUND = 1e-12
#: contact off the generating circles: a minimum's argument is fixed only within sqrt(2 delta R) by values
#: round-off flat (delta ~ 1e-15 mm, R a few mm: 1e-7 mm), tenfold
PATH_ROUND = 1e-6


@pytest.mark.parametrize("spec", [CycloidPairSpec(1.0, 12, 30), CycloidPairSpec(1.0, 8, 64),
                                  CycloidPairSpec(1.0, 8, 64, clock=True)], ids=["12/30", "8/64", "clock 8/64"])
def test_cycloid_pairs_have_no_te_at_the_pitch_point(spec):
    """A conjugate pair has no TE at any of 1000 steps (continuation applies), and its contacts lie on the
    generating circles. Both flanks of a cycloid tooth leave the pitch circle from a cusp, where their
    parametrisation is stationary: there the one-sided slope of the bound function is nil whichever way it runs.
    (Before, the end of an interval on the pitch circle was taken for the minimum over about 30 steps in 1000
    at the pitch point: TE up to 1.4e-7 rad for 12/30, the contact 1e-3 mm off the circles.)"""
    res = simulate(Mesh(cycloid_gear(spec, 1), cycloid_gear(spec, 2), spec.center_distance), 1000)
    assert np.abs(res.transmission_error).max() <= TE_ROUND
    p = res.contacts["point"]
    a1, a2 = spec.rolling(1), spec.rolling(2)
    d1 = np.abs(np.hypot(p[:, 0], p[:, 1] - (spec.r1 - a1)) - a1)
    d2 = np.abs(np.hypot(p[:, 0], p[:, 1] - (spec.r1 + a2)) - a2)
    assert np.minimum(d1, d2).max() <= PATH_ROUND


def test_pin_gearing_meshes_without_interference():
    """Lantern gearing: the pin wheel drives the wheel its pins generated (the pins' carrier below
    the wheel's tips); the generated flanks are conjugate to the pins."""
    ps = PinGearSpec(1.0, 8, 40, 0.8)
    pins = pin_ring(8, ps.r1, ps.pin_radius, internal=False, carrier_radius=ps.r1 - 1.5 * ps.module)
    res = simulate(Mesh(pins, pin_gear_wheel(ps), ps.center_distance), STEPS)
    assert not res.interference.found
    assert res.transmission_error_max * ps.r2 <= 10 * 1e-3 * ps.module
    assert res.pairs_in_contact.min() >= 1


def test_pin_ring_profile():
    ring = pin_ring(12, 90.0, 7.0)
    assert (ring.tip_diameter / 2, ring.root_diameter / 2) == pytest.approx((83.0, 97.0), abs=1e-12)
    wheel = pin_ring(8, 4.0, 0.8, internal=False, carrier_radius=2.5)
    assert (wheel.tip_diameter / 2, wheel.root_diameter / 2) == pytest.approx((4.8, 2.5), abs=1e-12)
    assert wheel.half.half_pitch_angle == pytest.approx(math.pi / 8)
    from gearkit.errors import SpecError

    with pytest.raises(SpecError, match="pin_radius"):
        pin_ring(12, 90.0, 30.0)  # neighbouring pins overlap
    with pytest.raises(SpecError, match="carrier_radius"):
        pin_ring(12, 90.0, 7.0, carrier_radius=95.0)  # inside the pins of a ring
