"""Internal pairs: exit jamming, tip sweep, tip-fillet interference, trimming by the shaper,
minimum tooth differences -- each on both sides of its limit (digest 1.8, 1.10, 2.3, 3.2, 3.3).

``SIDE = 1e-3`` (in x2) is far above the root solvers' accuracy and above the sweep's resolution
(1e-4 m_n of penetration ~ 1e-4 in x2 here), and far from the other limits.
"""
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from gearkit.checks import check_pair, min_cutter_difference, min_tooth_difference
from gearkit.pair.internal import exit_jamming_margin, nu_radius, plunge_trimming, tip_sweep
from gearkit.pair import PairSpec, pair_geometry
from gearkit.families.involute import ShaperCutter

from sweeporacle import brute_maximum, brute_sweep

SIDE = 1e-3
SHAPER = ShaperCutter(20, addendum=1.3)  # medium-worn shaper, x_c = 0.3


def example(x2, z1=46, z2=49, m=8.0, **kw):
    """The textbook's internal example (digest 3.2) with another ring shift."""
    return PairSpec(z1, z2, m, 0.0, x2, kind="internal", shift_convention="cutter", tool1=SHAPER, tool2=SHAPER, **kw)


def root(f, lo, hi):
    return brentq(f, lo, hi, xtol=1e-13)


def test_exit_jamming_threshold_and_both_sides():
    """Digest 3.3: x2min = 0.407106 for z1 = 46, z2 = 49, x1 = 0, z0 = 20. This implementation finds
    0.4070967 (the same closed form recomputed); the digest's value is matched to 1e-5."""
    x_star = root(lambda x: exit_jamming_margin(pair_geometry(example(x))), 0.3, 0.5)
    assert x_star == pytest.approx(0.407106, abs=1e-5)
    below = check_pair(example(x_star - SIDE)).report
    above = check_pair(example(x_star + SIDE)).report
    assert (below["exit_jamming"].status, above["exit_jamming"].status) == ("fail", "ok")
    # the rigid-body sweep of the tip corners sees the same interference (a second method)
    assert (below["tip_interference"].status, above["tip_interference"].status) == ("fail", "ok")


@pytest.mark.parametrize("x2", [0.30, 0.38, 0.40, 0.4140, 0.45, 0.60])
def test_tip_sweep_agrees_with_the_closed_form(x2):
    g = pair_geometry(example(x2))
    depth, _ = tip_sweep(g)
    assert (depth > 0) == (exit_jamming_margin(g) < 0)


def test_tip_sweep_contact_is_not_interference():
    """Along the path of contact the tip corners touch the flanks (depth 0): a sound pair is clean,
    with zero backlash and with backlash."""
    for spec in (example(0.52), example(0.52, center_distance=14.95),  # an internal pair opens inwards
                 PairSpec(20, 61, 2.0, 0.1, 0.3, kind="internal", shift_convention="cutter", tool2=ShaperCutter(25), helix_angle_deg=15.0)):
        assert tip_sweep(pair_geometry(spec))[0] == 0.0


@pytest.mark.parametrize("z2,want", [(34, 9), (50, 9), (77, 9), (78, 8), (100, 8)])
def test_minimum_tooth_difference(z2, want):
    """Digest 3.3/5.14: zero wheels, h_a* = 1: (z_p)min = 9 for 34 <= z2 <= 77 and 8 for z2 >= 78."""
    spec = PairSpec(z2 - 20, z2, 1.0, kind="internal", shift_convention="cutter", tool2=ShaperCutter(min(20, z2 - 4)))
    assert min_tooth_difference(spec) == want
    ok = check_pair(PairSpec(z2 - want, z2, 1.0, kind="internal", shift_convention="cutter", tool2=spec.tool2), geometry="formula").report
    bad = check_pair(PairSpec(z2 - want + 1, z2, 1.0, kind="internal", shift_convention="cutter", tool2=spec.tool2), geometry="formula").report
    assert (ok["min_teeth.difference"].status, bad["min_teeth.difference"].status) == ("ok", "fail")
    assert (ok["exit_jamming"].status, bad["exit_jamming"].status) == ("ok", "fail")


def test_tip_fillet_threshold_and_both_sides():
    """Digest 3.2/3.3 (3.127): margins 0.578 and 4.756 mm at x2 = 0.52; threshold 0.470483 (this
    implementation: 0.470522, matched to 5e-5), and 0.476094 for z1 = 43."""
    g = pair_geometry(example(0.52))
    assert g.path["A"] - g.path["F1"] == pytest.approx(0.578, abs=5e-4)
    assert g.gears[1].form_roll - (g.path["E"] + g.line_of_action) == pytest.approx(4.756, abs=1e-3)

    def margin(x, z1=46):
        g = pair_geometry(example(x, z1=z1))
        return g.path["A"] - g.path["F1"]

    x_star = root(margin, 0.3, 0.6)
    assert x_star == pytest.approx(0.470483, abs=5e-5)
    assert root(lambda x: margin(x, 43), 0.3, 0.6) == pytest.approx(0.476094, abs=6e-5)
    below = check_pair(example(x_star - SIDE)).report["interference.1"]
    above = check_pair(example(x_star + SIDE)).report["interference.1"]
    assert (below.status, above.status) == ("fail", "ok")


def test_plunge_trimming_example_margin():
    """Digest 3.3: z2 = 49, z0 = 20, zero ring: (X2 - X0)min = 0.1846 m at phi2 = 14.2 deg."""
    g = pair_geometry(PairSpec(46, 49, 1.0, kind="internal", shift_convention="cutter", tool2=SHAPER))
    gap, phi = plunge_trimming(g)
    assert gap == pytest.approx(0.1846, abs=5e-5)
    assert math.degrees(phi) == pytest.approx(14.2, abs=0.05)


@pytest.mark.parametrize("z2,want", [(36, 19), (37, 18), (50, 18), (81, 18), (82, 19), (100, 19)])
def test_minimum_cutter_difference(z2, want):
    """Digest 3.3/5.15: (z_pc)min = 18 for 37 <= z2 <= 81 and 19 for z2 >= 82 (and z2 = 36)."""
    spec = PairSpec(z2 - 12, z2, 1.0, kind="internal", shift_convention="cutter", tool2=SHAPER)
    assert min_cutter_difference(spec) == want

    def plunge(z0):
        s = PairSpec(z2 - 12, z2, 1.0, kind="internal", shift_convention="cutter", tool2=ShaperCutter(z0, addendum=1.3))
        return check_pair(s, geometry="formula").report["trimming.plunge"].status

    assert (plunge(z2 - want), plunge(z2 - want + 1)) == ("ok", "fail")


def test_trimming_beyond_nu():
    """Digest 1.8/3.2: (3.109) z2min = 63.0105 for z0 = 20 (zero ring), and (3.110) x2min = 0.522336
    for the example (with dy = -0.146632): the adopted 0.52 is 0.007 mm inside O2N_u."""
    s2 = math.sin(math.radians(20.0)) ** 2
    z2min = (20 ** 2 * s2 / 4 - 1) / (20 * s2 / 2 - 1)
    assert z2min == pytest.approx(63.0105, abs=5e-5)

    def nu_status(z2):
        spec = PairSpec(z2 - 12, z2, 1.0, kind="internal", shift_convention="cutter", tool2=SHAPER)
        return check_pair(spec, geometry="formula").report["trimming.nu"].status

    assert (nu_status(63), nu_status(64)) == ("warn", "ok")

    def gap(x):  # (3.110) keeps the example's tip shortening dy = -0.146632
        g = pair_geometry(example(x, tip_diameter2=2 * 8.0 * (49 / 2 - 1 + x - 0.146632)))
        return g.gears[1].tip_diameter / 2 - nu_radius(g)

    assert root(gap, 0.4, 0.7) == pytest.approx(0.522336, abs=5e-7)
    g = pair_geometry(example(0.52))
    assert nu_radius(g) - g.gears[1].tip_diameter / 2 == pytest.approx(0.007, abs=5e-4)
    rep = check_pair(example(0.52)).report
    assert rep["trimming.nu"].status == "warn" and rep.status == "warn"  # the textbook's choice passes
    x_ok = 0.522336 + SIDE
    ok = check_pair(example(x_ok, tip_diameter2=2 * 8.0 * (49 / 2 - 1 + x_ok - 0.146632))).report
    assert ok["trimming.nu"].status == "ok"


def test_larger_centre_distance_closes_an_internal_mesh():
    """Moving the pinion outward pushes it into the ring's teeth: negative backlash, and the tip
    sweep sees the overlap that the backlash finding reports."""
    rep = check_pair(example(0.52, center_distance=15.05)).report
    assert rep["backlash"].status == "fail" and rep["backlash"].value < 0
    assert rep["tip_interference"].status == "fail"


def test_small_shapers_always_trim_beyond_nu():
    """Digest 1.8: (3.109) holds only for z0 > 2 h_a*/sin^2(a) = 17.097; a 17-tooth shaper trims
    every zero ring."""
    for z2 in (40, 80, 200, 1000):
        g = pair_geometry(PairSpec(z2 - 12, z2, 1.0, kind="internal", shift_convention="cutter", tool2=ShaperCutter(17, addendum=1.3)))
        assert g.gears[1].tip_diameter / 2 < nu_radius(g)


def test_ring_tip_inside_its_base_circle():
    """A zero ring with z2 < 2/(1 - cos a) = 33.2 has its tip circle inside its base circle."""
    small = check_pair(PairSpec(20, 33, 1.0, kind="internal", shift_convention="cutter", tool2=ShaperCutter(12)), geometry="formula")
    large = check_pair(PairSpec(21, 34, 1.0, kind="internal", shift_convention="cutter", tool2=ShaperCutter(12)), geometry="formula")
    assert (small.report["ring_tip.base"].status, large.report["ring_tip.base"].status) == ("warn", "ok")


def test_textbook_example_report():
    res = check_pair(example(0.52))
    assert res.ok
    assert [f.id for f in res.report.warnings] == ["trimming.nu"]
    assert res.report["min_teeth.difference"].value == 3.0


@pytest.mark.parametrize("spec", [example(0.30), example(0.4140), example(0.60),
                                  PairSpec(30, 38, 1.0, 0.2, 0.1, kind="internal", tool2=ShaperCutter(20)),
                                  PairSpec(44, 52, 2.0, 0.3, 0.6, kind="internal", tool2=ShaperCutter(20),
                                           helix_angle_deg=15.0)])
def test_tip_sweep_against_brute_force(spec):
    """The branch and bound (one corner of each gear, by the mesh's mirror symmetry) against every corner
    sampled on 1 000 000 angles: deeper than the samples by at most what they can miss (the corners'
    largest relative speed times half a step, twice as the depth's gradient bound); never shallower
    where the depth is above the sweep's floor (half the resolution; below it, e.g. the depth 0 of
    contact, the sweep only proves it below the floor); the same verdict."""
    from gearkit.pair.internal import SWEEP_RESOLUTION, tip_sweep_depth
    from gearkit.pair.sweep import SWEEP_BAND

    g = pair_geometry(spec)
    samples = 1_000_000
    brute = brute_sweep(g, samples)
    depth, _ = tip_sweep_depth(g)
    p, ring = g.gears
    k = p.teeth / ring.teeth
    speed = (1 - k) * (p.tip_diameter / 2 + ring.working_diameter)  # a corner's distance from P at most
    step_error = 2.0 * speed * math.pi / samples
    res = SWEEP_RESOLUTION * spec.module
    assert depth <= brute + step_error
    if brute > SWEEP_BAND * res:
        assert depth >= brute - 1e-12
    else:
        assert depth <= SWEEP_BAND * res + step_error
    assert abs(brute - res) > step_error and (depth > res) == (brute > res)


def test_tip_sweep_finds_the_deeper_of_two_close_maxima():
    """34/76 (shaper 33) at a shift pair on its tip_interference line: the two corners' maxima over the
    pinion turn (at -0.844 and +0.659 rad) lie 2.8e-7 m_n apart, within the branch and bound's stop
    (resolution / 100); only the deepest sample's maximum was refined, the lower one (9.9660e-5 against
    9.9943e-5 mm), which put the map's tip_interference zero 2.3 tol off its line traced at tol 1e-7.
    Against the brute-force sweep refined about every sample that may lie beside the maximum: equal
    within what the refined samples can miss (a few 1e-13 mm), and never shallower."""
    from gearkit.pair.internal import tip_sweep_depth

    g = pair_geometry(PairSpec(34, 76, 1.0, 1.0736059920785432, 0.2142069902277642, kind="internal",
                               tool2=ShaperCutter(33)))
    brute, below = brute_maximum(g)
    depth, _ = tip_sweep_depth(g)
    assert below < 1e-9  # the oracle resolves the two maxima (2.8e-7 apart)
    assert brute - 1e-12 <= depth <= brute + below + 1e-12
