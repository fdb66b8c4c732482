"""Lines beside the no-pair edge that the grid cannot see, and strips narrower than a chord: the
sliding hairpin of 14/46 (smaller than a grid cell, in cells whose corners all have one sign) and
46/49's interference.1, whose two thin wedges meet at a saddle at (x1, x2) = (1, 1) (a chord from
one side of a wedge to the other was cut there, and the arms stopped 0.02 to 0.04 short of it).
Oracle: the exact zeros of the scalar margin (``PairField.margin``) along rows x2 = const through
them, sampled densely and solved by brentq. So too where a chord cut from one side of a thin loop or
wedge to the other had its ends carried on round the turn onto a piece traced there already (14/55's
sliding loop, 56/59's interference.1 wedge); and where a chord along one side of a thin wedge of one
sign (the smallest of two margins, its slope jumping at the wedge's ridge) was split at the other side
(11/22's tip sweep): on rows and columns across it every crossing of the traced line within 2 tol of a
zero along the scan, and every zero with a crossing. A line's chord whose line bulges towards a strip of the
other sign lying between two rungs of the ladder of its normal (closed form; 45/82's interference.1 beside a
neck of its negative part, against the check's zeros on rows through the neck) is split, not cut; so is a
line's chord its line crosses like an S, its middle on the line (42/52's exit_jamming at tol 1e-5, against the
check's zeros on columns across it)."""
import functools

import numpy as np
import pytest
from scipy.optimize import brentq

from gearkit.blocking import blocking_contour
from gearkit.blocking.field import PairField
from gearkit.distances import distances_to_polyline
from gearkit.families.involute import ShaperCutter
from gearkit.pair import PairSpec

from edgezeros import row_crossings

CONTRACT = 2.0  #: every exact zero within this many tol of its traced line
SAMPLES = 4001  #: samples of a row between brentq brackets


def _row_zeros(field, name, x2, lo, hi):
    """The zeros of margin ``name`` on the row x2 = const between x1 = lo and hi (a sign change
    where |F| falls: a zero, not a jump)."""
    def f(x):
        return field.margin(name, x, x2)
    x = np.linspace(lo, hi, SAMPLES)
    v = np.array([f(t) for t in x])
    out = []
    for i in np.flatnonzero(np.isfinite(v[:-1]) & np.isfinite(v[1:]) & ((v[:-1] > 0) != (v[1:] > 0))):
        t = brentq(f, x[i], x[i + 1], xtol=1e-15, rtol=1e-15)
        if abs(f(t)) <= 0.5 * min(abs(v[i]), abs(v[i + 1])):
            out.append(t)
    return np.array(out)


def _farthest(contour, name, rows, lo, hi):
    """Largest distance, in tol, of the exact zeros on ``rows`` from the traced line ``name``; the
    number of zeros seen."""
    comps = contour.line(name).components
    worst, seen = 0.0, 0
    for x2 in rows:
        z = _row_zeros(contour.field, name, x2, lo, hi)
        seen += len(z)
        if len(z):
            pts = np.column_stack([z, np.full(len(z), x2)])
            d = np.min([distances_to_polyline(pts, q) for q in comps], axis=0)
            worst = max(worst, float(d.max()))
    return worst / contour.tol, seen


@pytest.mark.parametrize("tol", [1e-3, 1e-5])
def test_a_sliding_hairpin_smaller_than_a_grid_cell_is_traced(tol):
    """14/46: the sliding line's hairpin beside (0.02, -1.15), in grid cells whose corners all have one
    sign (the grid traced nothing there, and the band's piece was cut at them: 44 tol short at 1e-3,
    4374 at 1e-5)."""
    c = blocking_contour(PairSpec(14, 46, 1.0), tol=tol, lines=["sliding"])
    rows = np.linspace(-1.2, -1.1, 21)
    worst, seen = _farthest(c, "sliding", rows, -0.2, 0.25)
    assert seen > 0
    assert worst <= CONTRACT


def test_the_arms_of_two_thin_wedges_are_traced_to_their_saddle():
    """46/49 at tol 1e-3: interference.1's two thin negative wedges meeting at (1, 1); every zero on
    rows from 0.01 below to 0.05 above the saddle within 2 tol of the traced line (the upper wedge's
    arms stopped 0.017 and 0.04 short of it: a chord from one side of the wedge to the other was cut,
    and nothing carried the ends beside the no-pair edge)."""
    spec = PairSpec(46, 49, 1.0, kind="internal", tool2=ShaperCutter(20))
    c = blocking_contour(spec, tol=1e-3, lines=["interference.1"])
    rows = np.linspace(0.99, 1.05, 25)
    worst, seen = _farthest(c, "interference.1", rows, 0.95, 1.1)
    assert seen >= 2 * len(rows) - 2
    assert worst <= CONTRACT


@pytest.mark.parametrize("width", [1.2, 1.8, 3.0])
def test_a_chord_from_one_side_of_a_strip_to_the_other_is_cut_not_split(width):
    """densify on a hairpin across a strip ``width`` tol wide (F = y (y - w), negative between the lines
    y = 0 and y = w): the chord from one side to the other is cut, so each piece lies on one line (the
    closed form) and every vertex within tol / 4 of it; split instead, it zigzagged across the strip."""
    from gearkit.blocking.level import densify

    tol = 1e-3
    w = width * tol
    F = lambda p, k: p[:, 1] * (p[:, 1] - w)  # noqa: E731
    hairpin = np.array([[0.0, 0.0], [0.5, 0.0], [1.0, 0.0], [0.6, w], [0.1, w]])
    out = densify(F, [(0, hairpin, np.full(len(hairpin), np.nan))], tol)
    assert len(out) == 2
    for _, q in out:
        side = np.abs(q[:, 1]) <= tol / 4
        assert side.all() or (np.abs(q[:, 1] - w) <= tol / 4).all()
    covered = sorted((float(q[:, 0].min()), float(q[:, 0].max())) for _, q in out)
    assert covered == [(0.0, 1.0), (0.1, 0.6)]


@pytest.mark.parametrize("tol", [1e-3, 1e-5])
def test_a_thin_loop_cut_across_is_carried_round_its_turn(tol):
    """14/55: sliding's leg ``sliding.same`` is a thin loop 0.07 wide beside (-0.3, -0.8) that the grid
    saw as two loops; the chord from one side to the other of the upper one was cut, and its ends'
    fronts ran at their first step onto the lower one (closed, no end to join) and stopped where they
    stood: 0.09 of its right side and 0.017 of its left side untraced (42 tol at 1e-3, 4197 at 1e-5).
    Every zero on rows across the loop within 2 tol of the traced line."""
    c = blocking_contour(PairSpec(14, 55, 1.0), tol=tol, lines=["sliding"])
    rows = np.linspace(-0.92, -0.65, 28)
    worst, seen = _farthest(c, "sliding", rows, -0.45, -0.2)
    assert seen >= 2 * len(rows)
    assert worst <= CONTRACT


@pytest.mark.parametrize("z1, z2, z0, top, n, right", [(56, 59, 26, 1.15, 15, 1.2), (58, 63, 16, 1.25, 13, 1.35)],
                         ids=["arm-beside-the-edge", "past-the-saddle"])
def test_a_wedge_arm_cut_across_is_carried_to_the_piece_traced_there(z1, z2, z0, top, n, right):
    """interference.1's negative wedge opening from the saddle at (1, 1) beside the no-pair edge, tol 1e-3.
    56/59 with a 26-tooth shaper: the chord across it from (1.074, 1.061) to (1.091, 1.122) was cut, and
    the upper arm's front ran onto the piece the grid traced from (1.0625, 1.0825), whose end beside the
    edge is not carried on: 0.048 of the arm untraced (21.7 tol). 58/63 with a 16-tooth shaper: the two
    branches cross at a small angle at the saddle; a front carried down the upper arm that ran onto the
    other branch's piece beyond the saddle with a step of two cells, taken whole, joined the arm to that
    branch and left the arm above (1.1, 1.15) untraced (38 tol on 19a2229): a long step onto a piece with
    no end to join is halved. Every zero on rows from the saddle up the wedge within 2 tol of the traced
    line."""
    spec = PairSpec(z1, z2, 1.0, kind="internal", tool2=ShaperCutter(z0))
    c = blocking_contour(spec, tol=1e-3, lines=["interference.1"])
    rows = np.linspace(1.01, top, n)
    worst, seen = _farthest(c, "interference.1", rows, 0.95, right)
    assert seen >= 2 * len(rows)
    assert worst <= CONTRACT


WEDGE_SAMPLES = 161  #: samples of a scan across the tip sweep's wedge (its zeros 8e-5 apart or more there)


@functools.lru_cache(maxsize=None)
def _tip_sweep_wedge():
    spec = PairSpec(11, 22, 1.0, kind="internal", tool2=ShaperCutter(15))
    return PairField(spec), blocking_contour(spec, tol=1e-5, lines=["tip_interference"])


@pytest.mark.parametrize("axis, at, lo, hi", [(1, -0.03835, 0.1328, 0.134), (1, -0.0382, 0.1328, 0.134),
                                              (1, -0.0381, 0.1328, 0.134), (0, 0.1336, -0.0386, -0.0378),
                                              (0, 0.1337, -0.0386, -0.0378), (0, 0.1338, -0.0386, -0.0378)])
def test_a_chord_along_a_thin_wedge_keeps_to_its_side(axis, at, lo, hi):
    """11/22 internal with a 15-tooth shaper at tol 1e-5: the tip sweep's margin is positive in a thin wedge
    whose sides meet at (0.13392, -0.03795), the smallest of a gentle part (slope 0.012, the upper side) and a
    steep one (0.87, the lower side). A chord along the upper side (its middle 9e-8 from it) read the lower
    side as the nearer zero along its normal (the secant from its middle to the normal's steep end), was split
    there, and the line zigzagged across the wedge: a chord from (0.13355, -0.03836) to (0.13373, -0.03804)
    4.4 tol off. On rows (axis 1: x2 = at) and columns (axis 0: x1 = at) across the wedge beside its tip,
    the traced line crosses within 2 tol of the zeros of the check's scalar margin (brentq) and at each."""
    field, c = _tip_sweep_wedge()
    tol = c.tol

    def f(t):
        p = (t, at) if axis == 1 else (at, t)
        return field.margin("tip_interference", *p)
    ts = np.linspace(lo, hi, WEDGE_SAMPLES)
    v = np.array([f(t) for t in ts])
    exact = np.array([brentq(f, ts[i], ts[i + 1], xtol=1e-15, rtol=1e-15)
                      for i in np.flatnonzero((v[:-1] > 0) != (v[1:] > 0))])
    assert len(exact) == 2, exact  # both sides of the wedge
    comps = [q if axis == 1 else q[:, ::-1] for q in c.line("tip_interference").components]
    got = np.array(row_crossings(comps, at, lo, hi))
    assert got.size, exact
    near = np.abs(got[:, None] - exact[None, :])
    assert near.min(axis=1).max() <= CONTRACT * tol, (got, exact)
    assert near.min(axis=0).max() <= CONTRACT * tol, (got, exact)


def test_a_regions_chord_is_split_at_the_nearer_zero_not_the_far_side_the_secant_favours():
    """densify on a chord of a measured curve (the region's: the smallest of two parts, F = min(1e-3 (y - 0.1)
    (y - 0.45), 10 (y + 0.8))) from (-0.5, 0) to (0.5, 0): its middle lies in a strip of F > 0 beside a thin wedge
    of F < 0 (0.1 < y < 0.45, the gentle part flat) and 0.8 above a steep zero; the normal's ends (y = +-0.5) are of
    the middle's sign. The wide search found the steep zero at the reach, and the secant from the middle (F = 4.5e-5)
    to the reach (F = -2) read it 2e-5 off, nearer than the ladder's zero at y = 0.1 within the normal's ends: the
    chord was split at y = -0.8 (56/63 z0 25 internal at tol 1e-5: a chord from exit jamming to interference.1's
    wedge, its middle in the strip between them, split at exit jamming 0.8 chords off, and the outline folded back
    along it). The zeros are y = 0.1, 0.45 and -0.8 (closed form): the chord is split on the nearest, every new vertex
    within tol / 4 of y = 0.1 and none near -0.8."""
    from gearkit.blocking.level import densify

    tol = 1e-3
    F = lambda p, k: np.minimum(1e-3 * (p[:, 1] - 0.1) * (p[:, 1] - 0.45), 10.0 * (p[:, 1] + 0.8))  # noqa: E731
    out = densify(F, [(0, np.array([[-0.5, 0.0], [0.5, 0.0]]), np.full(2, np.nan))], tol, None, (0,), (), False, [])
    inner = np.concatenate([q[1:-1] for _, q in out])
    assert len(inner) and np.all(np.abs(inner[:, 1] - 0.1) <= tol / 4), inner


def test_a_lines_chord_bulging_towards_a_strip_between_the_ladders_rungs_is_split_not_cut():
    """densify on a chord from (-1, 0) to (1, 0) of the line y = -a(x), a = 0.3 (1 - x^2), beside the strip
    -a - 0.15 < y < -a where F = (y + a) (y + a + 0.15) is negative (closed form): along the normal through the
    chord's middle (F > 0) the line lies 0.3 off, the strip's far side 0.45, and F is positive at the normal's
    ends (+-1), at the wider search's samples (0.25, 0.5, ... chord lengths) and at the ladder's rungs (1, 0.5,
    0.25, ...: the strip lies between two of them). No zero found, the chord was cut and the line lost (45/82
    z0 13 internal at tol 1e-3: a chord of interference.1's line beside a neck of its negative part). Samples
    no farther apart than tol on a line's ladder see the strip: the chord is split down to the line, one
    polyline from end to end, every vertex within tol / 4 of the parabola and every chord's middle within tol."""
    from gearkit.blocking.level import densify

    tol = 1e-3
    a = lambda x: 0.3 * (1.0 - x * x)  # noqa: E731
    F = lambda p, k: (p[:, 1] + a(p[:, 0])) * (p[:, 1] + a(p[:, 0]) + 0.15)  # noqa: E731
    chord = np.array([[-1.0, 0.0], [1.0, 0.0]])
    out = densify(F, [(0, chord, np.full(2, np.nan))], tol)
    assert len(out) == 1, [q[[0, -1]] for _, q in out]
    (_, q), = out
    assert np.array_equal(q[0], chord[0]) and np.array_equal(q[-1], chord[1])
    x = np.linspace(-1.0, 1.0, 200001)
    parabola = np.column_stack([x, -a(x)])
    assert distances_to_polyline(q, parabola).max() <= tol / 4
    assert distances_to_polyline(0.5 * (q[:-1] + q[1:]), parabola).max() <= tol


def _checked_zeros(field, name, at, span, step, column=False):
    """The zeros of the check's scalar margin ``name`` on the row x2 = ``at`` (``column``: x1 = ``at``) sampled
    over ``span`` (linspace's arguments), solved by brentq, each confirmed by check_pair's finding ``name``
    failing ``step`` to its negative side and not to its positive one: ``(n, 2)`` points (x1, x2)."""
    point = (lambda s: (at, s)) if column else (lambda s: (s, at))

    def f(s):
        return field.margin(name, *point(s))
    ts = np.linspace(*span)
    v = np.array([f(t) for t in ts])
    zeros = []
    for i in np.flatnonzero((v[:-1] > 0) != (v[1:] > 0)):
        t = brentq(f, ts[i], ts[i + 1], xtol=1e-15, rtol=1e-15)
        out = step if v[i] > 0 else -step  # towards the negative side
        assert name in field.check(*point(t + out))[1], point(t)
        assert name not in field.check(*point(t - out))[1], point(t)
        zeros.append(point(t))
    return np.array(zeros, float).reshape(-1, 2)


NECK_ROWS = np.linspace(0.992, 1.006, 15)  #: rows x2 = const through the neck of 45/82 z0 13's interference.1 ...
NECK_SPAN = (0.975, 1.02, 451)  #: ... sampled in x1 (its zeros 1.3e-3 apart or more on them)


def test_a_line_beside_a_neck_of_its_margins_negative_part_is_traced_through():
    """45/82 internal with a 13-tooth shaper at tol 1e-3: interference.1's negative part narrows to a neck at
    about (1.0, 1.0) between two lines of its margin. The fronts of the left line's two pieces joined across
    the neck by a chord of 0.026; split once, its upper half, from (0.9924, 0.9954) to (1.0016, 1.0049), had its
    middle 1.75 tol beside the line, the negative strip from 1.75 to 3.2 tol off along its normal: between the
    ladder's rungs at 1.65 and 3.3 tol, as every other sample lay, so no zero was found and the chord was cut
    (the scan measure's zero on x2 = 0.9975 lay 3.98 tol from the trace). On rows through the neck every zero
    of the check's scalar margin (brentq; check_pair's interference.1 finding fails 1e-5 to its negative side
    and not to its positive one) lies within 2 tol of the traced line."""
    spec = PairSpec(45, 82, 1.0, kind="internal", tool2=ShaperCutter(13))
    tol = 1e-3
    c = blocking_contour(spec, tol=tol, lines=["interference.1"])
    field = PairField(spec)  # the check's own form circles

    zeros = np.concatenate([_checked_zeros(field, "interference.1", x2, NECK_SPAN, 1e-5) for x2 in NECK_ROWS])
    assert len(zeros) >= 2 * (len(NECK_ROWS) - 1)  # the two lines on every row but the neck's own
    comps = c.line("interference.1").components
    d = np.min([distances_to_polyline(zeros, q) for q in comps], axis=0)
    assert d.max() <= CONTRACT * tol, zeros[d > CONTRACT * tol]


S_COLUMNS = np.linspace(-0.55, -0.475, 16)  #: columns x1 = const across 42/52 z0 17's S-bent chord ...
S_SPAN = (-0.60, -0.47, 401)  #: ... sampled in x2 (one zero of exit_jamming on each)


def test_a_lines_chord_its_line_crosses_like_an_s_is_split():
    """42/52 internal with a 17-tooth shaper at tol 1e-5: exit_jamming's line had a chord from (-0.4708, -0.5)
    to (-0.5526, -0.5703), 0.107 long, that the line crosses near its middle like an S: 5.4 tol beside it at a
    quarter, on it at the middle, 48 tol off near the far end. Its middle's root lay 0.36 tol off, so the chord
    was kept; only a chord kept on its estimate was read at its quarters. On columns across it every zero of
    the check's scalar margin (brentq; check_pair's exit_jamming finding fails 1e-7 to its negative side and
    not to its positive one) lies within 2 tol of the traced line (50.9 tol before)."""
    spec = PairSpec(42, 52, 1.0, kind="internal", tool2=ShaperCutter(17))
    tol = 1e-5
    c = blocking_contour(spec, tol=tol, lines=["exit_jamming"])
    field = PairField(spec)
    zeros = np.concatenate([_checked_zeros(field, "exit_jamming", x1, S_SPAN, 1e-7, column=True) for x1 in S_COLUMNS])
    assert len(zeros) == len(S_COLUMNS)
    comps = c.line("exit_jamming").components
    d = np.min([distances_to_polyline(zeros, q) for q in comps], axis=0)
    assert d.max() <= CONTRACT * tol, zeros[d > CONTRACT * tol]


ARM_ROWS = np.concatenate([np.linspace(0.976, 0.995, 8), np.linspace(1.004, 1.017, 6)])  #: rows x2 = const across
ARM_SPAN = (0.95, 1.05, 2001)  #: ... 43/52 z0 21's two thin wedges beside their saddle near (1, 1), sampled in x1


def test_the_arms_of_two_wedges_beside_the_no_pair_edge_are_carried_to_their_saddle():
    """43/52 internal with a 21-tooth shaper at tol 1e-5: interference.1's two thin negative wedges meet at a
    saddle near (1, 1), 0.12 from the no-pair edge. The grid cut the wedges' right arms a cell short of the
    saddle (at (0.984, 0.973) and (1.026, 1.018)); ends that close to the edge were carried on only where
    their tangent meets it, and these run 10 degrees off it, clear of it (the scan measure's zero on
    x2 = 0.9877 lay 590 tol from the trace). On rows across both wedges every zero of the check's scalar
    margin (brentq; check_pair's interference.1 finding fails 1e-7 to its negative side and not to its
    positive one) lies within 2 tol of the traced line, two zeros a row."""
    spec = PairSpec(43, 52, 1.0, kind="internal", tool2=ShaperCutter(21))
    tol = 1e-5
    c = blocking_contour(spec, tol=tol, lines=["interference.1"])
    field = PairField(spec)
    zeros = np.concatenate([_checked_zeros(field, "interference.1", x2, ARM_SPAN, 1e-7) for x2 in ARM_ROWS])
    assert len(zeros) == 2 * len(ARM_ROWS)
    comps = c.line("interference.1").components
    d = np.min([distances_to_polyline(zeros, q) for q in comps], axis=0)
    assert d.max() <= CONTRACT * tol, zeros[d > CONTRACT * tol]
