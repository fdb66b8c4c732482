"""The contact minimiser's continuation over driver angles gives the fresh minimiser's answers to round-off.

:mod:`gearkit.contact.continuation` starts Newton's method at most driver angles from the minima of the
neighbouring angles (and the contact ratio's instants from the grid's) instead of probing every interval
afresh. Oracles: the fresh path itself (``newton_from`` refused for every row: each row is minimised
exactly as before continuation), and for conjugate pairs zero transmission error and the formula contact
ratio.

Named tolerances (absolute: a conjugate pair's TE is itself round-off, so nothing is relative):

* ``mesh.noise / mesh.arm_scale`` (rad; mm for a rack): the mesh's own statement of how well a contact's
  position is known (round-off along the normal over the smallest arm). Both paths evaluate each final
  contact on the same exact pieces at minimisers that agree to Newton's tolerance, whose values differ by
  its square: TE, backlash and bounds agree within it.
* ``LOCATE = 1e-5 m``: where a contact lies. It is the argument of a minimum, known to about the square
  root of round-off over the flanks' relative curvature: where they nearly conform (the reverse flanks of the
  internal 46/49 pair, a helical slice entering contact) two starts settle up to a few 1e-6 m apart on bounds
  whose values agree within the position's round-off, so bounds are compared by value; most working
  contacts agree within 1e-12 m, Newton's own tolerance.
* ``TURN = 1e-4``: a contact normal (unit vector): that shift over the flank's smallest radius of curvature
  (the cutter's tip rounding, 0.38 m, taken as 0.1 m).
* ``RATIO = 1e-6``: the simulated contact ratio's own resolution (as the table tests): the instants a pair
  parts solve ``sqrt(clearance) = sqrt(contact_tol)`` with the clearance at round-off.
* ``FORMULA = 1e-3``: simulated against the formula contact ratio (as the contact tests).
"""
import numpy as np
import pytest

from gearkit.contact import continuation, pair_mesh, simulate
from gearkit.contact.solver import solve
from gearkit.families.involute import Modification, ShaperCutter
from gearkit.pair import PairSpec, pair_geometry

LOCATE = 1e-5
TURN = 1e-4
RATIO = 1e-6
FORMULA = 1e-3
STEPS = 400  # node angles 8 / 400 of a pitch apart: close (continuation.REACH)
SHAPER = ShaperCutter(20, addendum=1.3)
HELICAL = {"face_width": 20.0, "helix_angle_deg": 15.0, "slices": 4}

#: (spec, pair_mesh keywords, simulate keywords, conjugate: TE zero and the formula contact ratio)
PAIRS = {
    "20/40 m=2": (PairSpec(20, 40, 2.0), {}, {}, True),
    "shifted 18/41": (PairSpec(18, 41, 1.0, 0.3, -0.1), {}, {}, True),
    "shifted 13/29": (PairSpec(13, 29, 1.0, 0.4, 0.1), {}, {}, True),
    "undercut 12/24": (PairSpec(12, 24, 1.0), {}, {}, False),
    "backlash 20/40": (PairSpec(20, 40, 1.0, center_distance=30.05), {}, {}, True),
    "centre distance +0.03": (PairSpec(20, 40, 2.0), {"center_distance_deviation": 0.03}, {}, False),
    "25/25 m=3": (PairSpec(25, 25, 3.0), {}, {}, True),
    "40/20 speed-up": (PairSpec(40, 20, 1.0), {}, {}, True),
    "17/1000": (PairSpec(17, 1000, 1.0), {}, {}, True),
    "rack, x = 0.2": (PairSpec(20, None, 1.0, 0.2, kind="rack"), {}, {}, True),
    "rack 13 m=1.5": (PairSpec(13, None, 1.5, kind="rack"), {}, {}, False),
    "internal 46/49": (PairSpec(46, 49, 1.0, 0.0, 0.52, kind="internal", shift_convention="cutter", tool1=SHAPER,
                                tool2=SHAPER), {}, {}, False),
    "internal 20/60, interfering": (PairSpec(20, 60, 1.0, kind="internal", tool1=SHAPER, tool2=SHAPER), {}, {}, False),
    "helical 20/40": (PairSpec(20, 40, 2.0, helix_angle_deg=15.0, face_width=20.0), {}, HELICAL, False),
    "tip relief": (PairSpec(20, 40, 2.0), {"modifications": (Modification(tip_relief=0.01, tip_relief_diameter=42.0),
                                                             None)}, {}, False),
    "profile crowning": (PairSpec(20, 40, 2.0), {"modifications": (Modification(profile_crowning=0.005),) * 2}, {},
                         False),
}


def _fresh(monkeypatch):
    """Every row minimised afresh: continuation's Newton confirms none."""
    def refuse(task, a, b, x, iterations):
        return np.full(len(a), np.inf), x, np.zeros(len(a), bool)
    monkeypatch.setattr(continuation, "newton_from", refuse)


@pytest.mark.parametrize("name", list(PAIRS))
def test_a_continued_cycle_is_the_fresh_cycle(name, monkeypatch):
    spec, mesh_kw, sim_kw, conjugate = PAIRS[name]
    mesh = pair_mesh(spec, **mesh_kw)
    cont = simulate(mesh, STEPS, **sim_kw)
    _fresh(monkeypatch)
    fresh = simulate(mesh, STEPS, **sim_kw)
    position = mesh.noise / mesh.arm_scale
    r_w2 = 1.0 if mesh.kind == "rack" else mesh.pitch_radii[1]
    assert np.abs(cont.transmission_error - fresh.transmission_error).max() <= position
    assert np.abs(cont.backlash_angle - fresh.backlash_angle).max() <= position
    assert abs(cont.backlash - fresh.backlash) <= position * r_w2
    assert np.array_equal(cont.pairs_in_contact, fresh.pairs_in_contact)
    assert cont.contact_ratio == pytest.approx(fresh.contact_ratio, abs=RATIO)
    assert cont.total_contact_ratio == pytest.approx(fresh.total_contact_ratio, abs=RATIO)
    for field in ("step", "slice", "tooth", "half"):
        assert np.array_equal(cont.contacts[field], fresh.contacts[field]), field
    assert np.abs(cont.contacts["point"] - fresh.contacts["point"]).max() <= LOCATE * spec.module
    assert np.abs(cont.contacts["normal"] - fresh.contacts["normal"]).max() <= TURN
    a, b = cont.interference, fresh.interference
    assert (a.found, a.where) == (b.found, b.where)
    assert abs(a.max_depth - b.max_depth) <= position * r_w2
    if conjugate:  # the oracles: no transmission error, the formula contact ratio
        assert np.abs(cont.transmission_error).max() <= position
        assert cont.contact_ratio == pytest.approx(pair_geometry(spec).contact_ratio, abs=FORMULA)


@pytest.mark.parametrize("name", ["20/40 m=2", "undercut 12/24", "rack, x = 0.2", "internal 46/49"])
def test_continued_bounds_are_the_fresh_bounds(name, monkeypatch):
    """Every refined bound of 801 driver angles over two pitches: the same halves refined, the same pieces and
    corners (a minimum on an interval's end is settled on it exactly), values to round-off. (Not the points: on
    the reverse flanks of the internal pair, which nearly conform, a bound's minimiser is known to 1e-5 m only;
    the working contacts' points are compared in the cycle.)"""
    spec = PAIRS[name][0]
    mesh = pair_mesh(spec)
    phi = np.linspace(-mesh.pitch1, mesh.pitch1, 801)
    cont = solve(mesh, phi, 1e-12 * mesh.module)
    _fresh(monkeypatch)
    fresh = solve(mesh, phi, 1e-12 * mesh.module)
    for field in ("teeth", "exact", "piece1", "piece2", "corner1", "corner2"):
        assert np.array_equal(getattr(cont, field), getattr(fresh, field)), field
    done = fresh.exact
    assert np.abs(cont.value[done] - fresh.value[done]).max() <= mesh.noise / mesh.arm_scale
    assert np.array_equal(cont.value[~done], fresh.value[~done])  # the search's values, untouched


def test_continuation_confirms_most_rows():
    """The point of continuation: of a 400-step cycle's refined rows, most are confirmed by Newton from their
    start (the rest are the node angles, one in ``NODE_EVERY``, and the few a start does not settle)."""
    calls = {"fresh": 0, "continued": 0}
    minimise, newton_from = continuation.minimise, continuation.newton_from

    def count_fresh(task, a, b):
        calls["fresh"] += len(a)
        return minimise(task, a, b)

    def count_continued(task, a, b, x, iterations):
        value, t, ok = newton_from(task, a, b, x, iterations)
        calls["continued"] += int(ok.sum())
        return value, t, ok

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(continuation, "minimise", count_fresh)
        mp.setattr(continuation, "newton_from", count_continued)
        simulate(pair_mesh(PairSpec(20, 40, 2.0)), 400)
    assert calls["continued"] >= 4 * calls["fresh"]


class _Quadratic:
    """``(t - centre)^2`` per row, with its derivatives: a smooth task for the minimiser."""
    smooth = True

    def __init__(self, centre):
        self.centre = centre

    def value(self, t, rows=slice(None)):
        return ((t - self.centre[rows]) ** 2,)

    def slope(self, t, rows):
        d = t - self.centre[rows]
        return d * d, 2 * d, np.full_like(t, 2.0)


def test_newton_from_settles_an_end_minimum_on_the_end_and_finds_an_inner_one():
    """Oracle: the fresh minimiser on the same quadratics, and their centres."""
    from gearkit.contact.minimise import _TRAVEL, minimise, newton_from

    a, b = np.zeros(5), np.full(5, 0.3)
    centre = np.array([-0.5, 0.1, 0.9, -0.2, 0.25])  # below, inside, above, below, inside
    start = np.array([0.05, 0.11, 0.5, -1.0, 0.01])  # inside, near, beyond b, beyond a, far from its minimum
    task = _Quadratic(centre)
    value, t, ok = newton_from(task, a, b, start, 6)
    assert ok.tolist() == [True, True, True, True, False]  # the last start travels more than _TRAVEL: afresh
    assert abs(centre[4] - start[4]) > _TRAVEL * 0.3
    fresh_value, fresh_t = minimise(task, a, b)
    assert t[0] == 0.0 and t[3] == 0.0 and t[2] == a[2] + (b[2] - a[2])  # on the ends, as the probes place them
    assert np.array_equal(t[[0, 2, 3]], fresh_t[[0, 2, 3]])
    assert abs(t[1] - centre[1]) <= 1e-12 * 0.3
    assert np.abs(value[:4] - fresh_value[:4]).max() <= 1e-24


class _CuspEnd:
    """``(s - s0)^2`` with ``s = (1 - t)^2``: a flank parametrised from a cusp at ``t = 1`` (a cycloid's on the
    pitch circle), whose slope is nil there while the minimum ``t = 1 - sqrt(s0)`` lies inside. The values carry
    round-off of order one (``(1 + f) - 1``), as the bound's ``w - u`` does of its pitch-sized terms."""
    smooth = True
    roundoff = 16.0 * np.finfo(float).eps

    def __init__(self, s0):
        self.s0 = s0

    def value(self, t, rows=slice(None)):
        return ((1.0 + ((1 - t) ** 2 - self.s0[rows]) ** 2) - 1.0,)

    def slope(self, t, rows):
        s, ds = (1 - t) ** 2, -2 * (1 - t)
        e = s - self.s0[rows]
        return (1.0 + e * e) - 1.0, 2 * e * ds, 2 * ds * ds + 4 * e


def test_an_end_with_a_nil_slope_is_no_minimum_where_the_function_falls_into_the_interval():
    """Oracle: the closed-form minimiser ``1 - sqrt(s0)``. The probes' best is the end ``t = 1`` (value ``s0^2``);
    both one-sided slope and Newton's derivative there are nil (round-off), so neither may settle on it."""
    from gearkit.contact.minimise import minimise, newton_from

    s0 = np.linspace(0.002, 0.01, 17)
    a, b = np.zeros(17), np.ones(17)
    task = _CuspEnd(s0)
    value, t = minimise(task, a, b)
    assert np.abs(t - (1 - np.sqrt(s0))).max() <= 1e-6  # the values' round-off, 1e-16, is flat over sqrt(1e-16)
    assert value.max() <= 1e-15
    _, _, ok = newton_from(task, a, b, b.copy(), 6)
    assert not ok.any()  # the end is not confirmed: these rows are minimised afresh



class _KnotEnd:
    """``k (t - centre)^2`` whose value on ``t = 1`` is read off the next table polynomial: a joint mismatch
    ``jump`` (the tables' fitting error, a few 1e-14 on a bound) on the end alone, the derivatives smooth. The
    internal 46/49 pair's flank has such a knot on a polyline interval's end, its bound's minimum 0.8 % of the
    interval inside and 7e-10 below the end (``k`` 1.1e-5 over the interval): a one-sided difference over 1e-7
    of the interval read the jump as the bound falling into the end."""
    smooth = True
    roundoff = 16.0 * np.finfo(float).eps * 0.13  # a mate pitch of 2 pi / 49 rad
    k = 1.1e-5

    def __init__(self, centre, jump):
        self.centre, self.jump = centre, jump

    def slope(self, t, rows):
        d = t - self.centre[rows]
        return self.k * d * d + np.where(t == 1.0, self.jump[rows], 0.0), 2 * self.k * d, np.full_like(t, 2 * self.k)

    def value(self, t, rows=slice(None)):
        rows = np.arange(len(self.centre))[rows] if isinstance(rows, slice) else rows
        return (self.slope(t, rows)[0],)


def test_a_table_knot_on_an_end_is_no_end_minimum():
    """Oracle: the quadratics' centres, inside the interval by 0.2 .. 1 % of it; a 1.6e-14 mismatch on the end
    (as the 46/49 pair's table has on its flank at parameter 0.5) settled the fresh minimiser on the end, up to
    1e-9 above the minimum, while the continued Newton found the centre. Rows whose centre lies beyond the end
    keep it."""
    from gearkit.contact.minimise import minimise, newton_from

    centre = np.concatenate([1.0 - np.geomspace(0.002, 0.01, 7), [1.01, 1.2]])
    jump = np.concatenate([np.full(7, -1.6e-14), [0.0, -1.6e-14]])
    a, b = np.zeros(9), np.ones(9)
    task = _KnotEnd(centre, jump)
    value, t = minimise(task, a, b)
    assert np.abs(t[:7] - centre[:7]).max() <= 1e-12
    assert value[:7].max() <= 1e-28
    assert t[7:].tolist() == [1.0, 1.0]
    _, t_cont, ok = newton_from(task, a, b, np.minimum(centre, 1.0) - 0.001, 6)
    assert ok.all() and np.abs(t_cont - t).max() <= 1e-12
