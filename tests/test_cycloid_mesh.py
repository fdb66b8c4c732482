"""The simulated pin mesh of generated cycloid discs: pins in contact, load-carrying pins, backlash.

Oracles: the digest (cycloid §1.9, §1.11 modifications table, §2 simulation rows, §4 items 7, 8,
9, 13): eps from eq. 27, the first-order and continuous backlash formulas, the normal clearance
Delta_0(phi) = dr - dR (1 - K1 cos phi)/sqrt(S).

``EPS_TOL = 1e-3`` (the issue's); ``REL = 0.01`` (the issue's 1% on the backlash angle);
``NUMERIC = 2e-4`` relative for the digest's own contact-search values; ``CLEAR = 1e-5`` mm
(digest item 13).
"""
import math

import numpy as np
import pytest

from gearkit.families.cycloidal import DriveSpec, backlash, contact_ratio, disc_profile, mesh_state, simulate_mesh

EPS_TOL = 1e-3
REL = 0.01
NUMERIC = 2e-4
CLEAR = 1e-5

CASES = {"+1": (12, 11, 90.0, 7.0, 4.0), "+2": (24, 22, 90.0, 7.0, 4.0), "+3": (36, 33, 90.0, 7.0, 4.0),
         "-1": (15, 16, 120.0, 10.0, 5.0)}


@pytest.mark.parametrize("case,eps", [("+1", 6.0), ("+2", 6.4199), ("+3", 5.7125), ("-1", 7.5)])
def test_time_averaged_load_carrying_pins_equal_the_contact_ratio(case, eps):
    """Issue item 2: the count of pins on the loaded flank, averaged over the mesh period on the
    generated disc, equals eps to 1e-3 (both load directions)."""
    spec = DriveSpec(*CASES[case])
    stats = simulate_mesh(spec)
    assert contact_ratio(spec) == pytest.approx(eps, abs=1e-4)
    assert stats.loaded[0] == pytest.approx(contact_ratio(spec), abs=EPS_TOL)
    assert stats.loaded_reverse[0] == pytest.approx(contact_ratio(spec), abs=EPS_TOL)
    assert stats.loaded[1] == math.floor(contact_ratio(spec)) and stats.loaded[2] == math.ceil(contact_ratio(spec))


def test_unmodified_single_difference_every_pin_touches():
    """Issue item 4 (digest §4 item 8): dz = +1, all Z_b pins touch at every crank angle and
    exactly Z_b/2 carry load in each direction."""
    stats = simulate_mesh(DriveSpec(*CASES["+1"]), samples=500)
    assert stats.touching == (12.0, 12, 12)
    assert stats.loaded == (6.0, 6, 6) and stats.loaded_reverse == (6.0, 6, 6)
    state = mesh_state(DriveSpec(*CASES["+1"]), 0.0123)
    assert np.abs(state.clearance).max() < 1e-9


@pytest.mark.parametrize("case,phi0_deg,touch,loaded", [("+2", 4.5, 13, 7), ("+3", 3.0, 12, 6)])
def test_multi_tooth_snapshots(case, phi0_deg, touch, loaded):
    """Digest §4 item 9: pins touching and loaded at the pin-wheel angle phi0 (crank-fixed frame)."""
    spec = DriveSpec(*CASES[case])
    state = mesh_state(spec, math.radians(phi0_deg) / spec.equivalent_lobes)
    assert int(state.touching.sum()) == touch
    assert max(int(state.load_carrying(1).sum()), int(state.load_carrying(-1).sum())) == loaded


def test_equidistant_modification_backlash_and_one_pin():
    """Issue item 4 (digest §4 item 13): dr = 0.02 mm: the backlash angle is within 1% of
    (dr - dR sqrt(1 - K1^2))/r_g' = 0.45455 mrad; one pin touches at zero load, the one at 60 deg
    from the line of centres (nearest arccos K1 = 57.77 deg), on either side by the direction."""
    spec = DriveSpec(*CASES["+1"], equidistant_mod=0.02)
    assert mesh_state(spec).touching.sum() == 0  # clearance all round before the disc turns
    continuous = (0.02 - 0.0) / spec.disc_pitch_radius
    assert continuous == pytest.approx(0.45455e-3, rel=1e-4)
    for direction, side in ((1, -1), (-1, 1)):
        angle, state = backlash(spec, 0.0, direction)
        assert angle == pytest.approx(continuous, rel=REL)
        assert angle == pytest.approx(0.45493e-3, rel=NUMERIC)  # the digest's contact search
        k = np.flatnonzero(state.touching)
        assert len(k) == 1
        centre = state.centres[k[0]] - state.centres.mean(axis=0)  # about the pin ring's centre
        line = -state.centres.mean(axis=0)  # towards the disc centre
        ang = math.degrees(math.atan2(centre[0] * line[1] - centre[1] * line[0], centre @ line))
        assert ang == pytest.approx(side * 60.0, abs=1e-9)


@pytest.mark.parametrize("d_r,d_big_r,numeric", [(0.0, -0.01, 0.19246), (0.02, -0.01, 0.64744),
                                                 (0.03, 0.01, 0.48990)])
def test_modification_table(d_r, d_big_r, numeric):
    """Digest §1.11 table: backlash from the contact search, and the continuous formula within 1%."""
    spec = DriveSpec(*CASES["+1"], equidistant_mod=d_r, shift_mod=d_big_r)
    angle, _ = backlash(spec)
    assert angle * 1e3 == pytest.approx(numeric, rel=NUMERIC)
    k1 = spec.k1
    assert angle == pytest.approx((d_r - d_big_r * math.sqrt(1 - k1 * k1)) / spec.disc_pitch_radius, rel=REL)


def test_normal_clearance_and_radial_clearance():
    """Digest §4 item 13: the clearance of each pin (disc not turned) is
    Delta_0 = dr - dR (1 - K1 cos phi)/sqrt(S) within 1e-5 mm; tip and root clear by dr - dR."""
    d_r, d_big_r = 0.02, -0.01
    spec = DriveSpec(*CASES["+1"], equidistant_mod=d_r, shift_mod=d_big_r)
    state = mesh_state(spec, 0.0)
    k1 = spec.k1
    phi = 2 * math.pi * np.arange(spec.pins) / spec.pins  # pin k's angle from the line of centres
    s = 1 + k1 * k1 - 2 * k1 * np.cos(phi)
    assert state.clearance == pytest.approx(d_r - d_big_r * (1 - k1 * np.cos(phi)) / np.sqrt(s), abs=CLEAR)
    d = disc_profile(spec)
    assert d.tip_diameter / 2 == pytest.approx(87.0 - (d_r - d_big_r), abs=1e-9)
    assert d.root_diameter / 2 == pytest.approx(79.0 - (d_r - d_big_r), abs=1e-9)


#: central differences of step h = 1e-4 of the roll interval: truncation ~h^2 |p'''| / 6, well
#: under 1e-6 of the derivative for these discs, and round-off ~eps |p| / h^2 far below it
DERIVATIVE_REL = 1e-6


@pytest.mark.parametrize("case", ["+1", "+2", "-1"])
def test_disc_point_derivatives_match_central_differences(case):
    """``at_roll(s, derivatives=True)``: the closed-form first and second derivatives in the roll
    against central differences of the point itself (an independent second method)."""
    disc = disc_profile(DriveSpec(*CASES[case]))
    lo, hi = disc.flank_rolls()[0]
    s = np.linspace(lo, hi, 9)[1:-1]
    h = 1e-4 * (hi - lo)
    p, d1, d2 = disc.at_roll(s, derivatives=True)
    assert np.array_equal(p, disc.at_roll(s))
    ahead, behind = disc.at_roll(s + h), disc.at_roll(s - h)
    assert np.abs(d1 - (ahead - behind) / (2 * h)).max() <= DERIVATIVE_REL * np.abs(d1).max()
    assert np.abs(d2 - (ahead - 2 * p + behind) / h ** 2).max() <= 1e3 * DERIVATIVE_REL * np.abs(d2).max()


def test_nearest_disc_point_is_the_foot_of_the_perpendicular():
    """The mesh's nearest point on the disc is exact: ``q - foot`` is normal to the disc there (its
    tangential part within 1e-12 of the pin circle radius) for every pin over a mesh period. The
    foot's roll is found anew (the foot projected back onto the disc by Gauss-Newton from the
    nearest of 4001 sampled rolls: a zero-residual projection, exact in a few steps)."""
    spec = DriveSpec(*CASES["+1"])
    state = mesh_state(spec, np.linspace(0.0, 2 * math.pi / (spec.pins * spec.lobes), 50))
    disc = disc_profile(spec)
    q, foot = state.centres.reshape(-1, 2), state.contact.reshape(-1, 2)
    # the polar angle from +y grows clockwise: turning counter-clockwise by it brings a foot to tooth 0
    turn = np.round(np.arctan2(foot[:, 0], foot[:, 1]) / (2 * math.pi / disc.teeth)) * 2 * math.pi / disc.teeth
    c, s_ = np.cos(turn), np.sin(turn)

    def fold(v):  # into tooth 0's right half (the disc's symmetry), as the mesh does
        out = np.stack([c * v[:, 0] - s_ * v[:, 1], s_ * v[:, 0] + c * v[:, 1]], -1)
        out[flip, 0] *= -1
        return out

    flip = (c * foot[:, 0] - s_ * foot[:, 1]) < 0
    lf, lq = fold(foot), fold(q)
    (lo, hi), = disc.flank_rolls()
    rolls = np.linspace(lo, hi, 4001)
    roll = rolls[np.argmin(np.linalg.norm(disc.at_roll(rolls)[None] - lf[:, None], axis=-1), axis=1)]
    for _ in range(6):
        p, d1, _ = disc.at_roll(roll, derivatives=True)
        roll = np.clip(roll - np.einsum("ij,ij->i", p - lf, d1) / np.einsum("ij,ij->i", d1, d1), lo, hi)
    p, d1, _ = disc.at_roll(roll, derivatives=True)
    assert np.abs(p - lf).max() <= 1e-12 * spec.pin_circle_radius  # the foot is on the disc
    inner = (roll > lo + 1e-9 * (hi - lo)) & (roll < hi - 1e-9 * (hi - lo))  # not an end of the flank
    assert inner.sum() > len(q) // 2
    offset = np.einsum("ij,ij->i", (lq - lf)[inner], d1[inner]) / np.linalg.norm(d1[inner], axis=1)
    assert np.abs(offset).max() <= 1e-12 * spec.pin_circle_radius


@pytest.mark.parametrize("case,samples", [("+2", 1), ("+2", 40), ("+3", 41), ("-1", 57),
                                          ("tip", 40), ("short", 33)])
def test_mirror_halved_simulation_matches_every_instant(case, samples):
    """simulate_mesh simulates half the instants and reads the rest off the mirror image (instant
    psi0 and period - psi0); the direct simulation of every instant (mesh_state) gives the same
    counts, odd and even sample counts, discs and rings, truncated and multi-difference."""
    extra = {"tip": (14, 12, 60.0, 4.0, 2.0, 0.0, 0.0, None, 57.0), "short": (12, 10, 40.0, 3.0, 1.5)}
    spec = DriveSpec(*(CASES.get(case) or extra[case]))
    period = 2.0 * math.pi * abs(spec.tooth_difference) / (spec.pins * spec.lobes)
    every = mesh_state(spec, (np.arange(samples) + 0.5) / samples * period)

    def stats(v):
        v = v.sum(axis=-1)
        return float(v.mean()), int(v.min()), int(v.max())
    got = simulate_mesh(spec, samples=samples)
    assert got.touching == stats(every.touching)
    assert got.loaded == stats(every.load_carrying(1))
    assert got.loaded_reverse == stats(every.load_carrying(-1))
    if case in ("tip", "short"):  # cases where the count varies over the period
        assert got.touching[1] < got.touching[2]


#: the outline polyline is within OUTLINE_TOL of the disc (its chords' proven bound), so a point's
#: distance to it is within OUTLINE_TOL of its distance to the disc
OUTLINE_TOL = 1e-7


@pytest.mark.parametrize("args", [CASES["+1"], CASES["+2"], CASES["-1"], (12, 11, 40.0, 3.0, 1.5),
                                  (12, 11, 90.0, 7.0, 4.0, 0.02, 0.01), (12, 11, 90.0, 7.0, 4.0, 0.0, 0.0, 4.05),
                                  (14, 12, 60.0, 4.0, 2.0, 0.0, 0.0, None, 57.0), (40, 39, 100.0, 5.3, 2.25),
                                  (6, 9, 40.0, 5.0, 4.0)])
def test_pin_clearances_equal_the_distance_to_the_outline_polyline(args):
    """The mesh's clearances (a pin centre's nearest disc point: by the roll at the pin centre's polar
    angle, kept where the foot attains the bound every grinding pin position sets, else from the
    nearest sample of every mirror image) against a second method: the distance of the pin centres,
    at instants over a whole lobe, to the disc's whole outline sampled to OUTLINE_TOL. Pins off the
    generating pin's path: modifications, a disc generated with another eccentricity, far pins of
    multi-difference drives."""
    from gearkit.distances import distances_to_polyline

    spec = DriveSpec(*args)
    outline = disc_profile(spec).outline(OUTLINE_TOL)
    state = mesh_state(spec, np.linspace(0.0, 2.0 * math.pi / spec.lobes, 41))
    oracle = distances_to_polyline(state.centres.reshape(-1, 2), outline, closed=True) - spec.pin_radius
    assert np.abs(state.clearance.ravel() - oracle).max() <= OUTLINE_TOL + 1e-12 * spec.pin_circle_radius
