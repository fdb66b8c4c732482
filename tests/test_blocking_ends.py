"""Issue 19: lines carried to the saddle where the grid cut them (gearkit.blocking.ends).

Oracles: a synthetic function whose zero set is known in closed form (a hyperbola through the
neighbourhood of a saddle inside one grid cell), and for the 12/30 pair the saddle of the
interference.1 margin located independently (a root finder on the gradient of the scalar margin,
the check's own pair geometry) with the exact zeros around it found on circles by a bracketing root
finder. ``CONTRACT = 2``: every exact point within 2 tol of the traced line (issue 19). A front at a
corner of a kinked zero set: a synthetic one in closed form (two rays), and internal 17/76's tip
sweep, its zeros by brentq on the scalar margin where check_pair's finding changes.
"""
import math

import numpy as np
import pytest
from scipy.optimize import brentq, root

from gearkit.blocking import blocking_contour
from gearkit.blocking.field import PairField
from gearkit.blocking.level import zero_lines
from gearkit.blocking.region import pad, padded_grid
from gearkit.distances import distances_to_polyline
from gearkit.families.involute import ShaperCutter
from gearkit.pair import PairSpec

from edgezeros import move_solved_edges

CONTRACT = 2.0  #: achieved / tol (issue 19)
FD_STEP = 1e-4  #: central-difference step of the saddle's gradient (shift units; the margin is
#: quadratic there, so the difference is exact to round-off / FD_STEP ~ 1e-12)
RADII = (3e-3, 1e-3, 3e-4)  #: circles around the saddle on which its exact zeros are found: inside
#: the 6e-3 the arms stopped short of it, outside the 4.5e-5 where its two branches turn away


def _nearest(points, polylines):
    return np.min([distances_to_polyline(points, q) for q in polylines], axis=0)


@pytest.mark.parametrize("c0", [1e-4, -1e-4, 0.0])
def test_a_saddle_inside_one_cell_is_joined_as_its_function_connects(c0):
    """F = x^2 - y^2 + c0 on a 9 x 9 grid one of whose cells holds the saddle: for c0 > 0 the zero set
    is the two branches y = +-sqrt(x^2 + c0) (each in one half plane y > 0, y < 0), for c0 < 0 the
    branches x = +-sqrt(y^2 - c0); traced, each is one component from the frame to the frame, every
    vertex and chord middle within tol of it (closed form). For c0 = 0 the two lines cross."""
    tol = 1e-6
    F = lambda p, k: p[:, 0] ** 2 - p[:, 1] ** 2 + c0  # noqa: E731
    xs = np.linspace(-1.0, 1.0, 9) + 0.037  # the saddle inside a cell, no node on a zero line
    ys = np.linspace(-1.0, 1.0, 9) + 0.061
    gx, gy = np.meshgrid(xs, ys)
    values = F(np.column_stack([gx.ravel(), gy.ravel()]), None).reshape(gx.shape)
    px, py = padded_grid(xs, ys)
    lines = zero_lines(F, [(px, py, pad(values, np.nan))], tol)[0]
    on_frame = lambda p: min(abs(p[0] - xs[0]), abs(p[0] - xs[-1]), abs(p[1] - ys[0]),  # noqa: E731
                             abs(p[1] - ys[-1])) <= 1e-12
    for q in lines:
        assert on_frame(q[0]) and on_frame(q[-1])  # no end short of the saddle
        mid = 0.5 * (q[:-1] + q[1:])
        for p in (q, mid):  # distance to the conic, first order: |F| / |grad F|
            assert np.all(np.abs(F(p, None)) / (2 * np.hypot(*p.T)) <= CONTRACT * tol)
    if c0 > 0:
        assert len(lines) == 2 and sorted(bool(np.all(q[:, 1] > 0)) for q in lines) == [False, True]
        assert all(np.all(q[:, 1] > 0) or np.all(q[:, 1] < 0) for q in lines)
    elif c0 < 0:
        assert len(lines) == 2 and all(np.all(q[:, 0] > 0) or np.all(q[:, 0] < 0) for q in lines)
    else:  # the exact crossing: every exact zero near it within 2 tol of the traced lines
        t = np.linspace(-0.2, 0.2, 41)
        exact = np.concatenate([np.column_stack([t, t]), np.column_stack([t, -t])])
        assert _nearest(exact, lines).max() <= CONTRACT * tol


@pytest.fixture(scope="module")
def saddle_1230():
    """The saddle of interference.1 of 12/30 near (1, -1), from the scalar margin: grad = 0."""
    return _saddle(PairSpec(12, 30, 1.0), "interference.1", [1.01, -0.99])


def _saddle(spec, name, guess):
    """``(spec, margin(x1, x2), saddle)``: the saddle of the scalar margin ``name`` near ``guess`` (grad = 0,
    central differences), checked to be one (the Hessian's determinant negative)."""
    c = blocking_contour(spec, tol=1e-3, lines=[name])
    m = lambda x1, x2: c.field.margin(name, x1, x2)  # noqa: E731
    h = FD_STEP

    def grad(p):
        x1, x2 = p
        return [(m(x1 + h, x2) - m(x1 - h, x2)) / (2 * h), (m(x1, x2 + h) - m(x1, x2 - h)) / (2 * h)]

    sol = root(grad, guess, tol=1e-13)
    assert sol.success
    x1, x2 = sol.x
    hxx = (m(x1 + h, x2) - 2 * m(x1, x2) + m(x1 - h, x2)) / h ** 2
    hyy = (m(x1, x2 + h) - 2 * m(x1, x2) + m(x1, x2 - h)) / h ** 2
    hxy = (m(x1 + h, x2 + h) - m(x1 + h, x2 - h) - m(x1 - h, x2 + h) + m(x1 - h, x2 - h)) / (4 * h * h)
    assert hxx * hyy - hxy ** 2 < 0  # a saddle: two branches of the zero set meet near it
    return spec, m, np.array([x1, x2])


def test_the_saddle_is_where_the_closed_form_puts_it(saddle_1230):
    """At x1 = 1, x2 = -1 (x1 + x2 = 0: a_w = a, no tip shortening) gear 2's tip circle is its
    reference circle, the start of gear 1's involute (rack-cut, rho_l1 = r1 sin(alpha) - m (1 - x1) /
    sin(alpha)) lies on the pitch point, and both derivatives of u_a - rho_F1 along x1 + x2 = 0 and
    across it vanish: the margin there is the check's forgiveness, 1e-9."""
    _, m, s = saddle_1230
    assert s == pytest.approx([1.0, -1.0], abs=1e-6)
    assert m(1.0, -1.0) == pytest.approx(1e-9, abs=1e-12)


@pytest.mark.parametrize("tol", [1e-3, 1e-5])
def test_interference_line_reaches_its_saddle(saddle_1230, tol):
    """12/30 interference.1 (B1): every exact zero on circles of radius RADII around the saddle
    (brentq on the scalar margin along the circle) lies within 2 tol of the traced line (the arms
    stopped up to 6e-3 short of it), and no traced component ends near the saddle."""
    _arms_reach_the_saddle(*saddle_1230, "interference.1", tol)


@pytest.mark.parametrize("tol", [1e-3, 1e-5])
def test_the_arms_of_a_saddle_are_joined_past_the_other_branch(tol):
    """25/58 interference.2 (B2) at its saddle near (-1, 1), where the margin is the check's 1e-9: the
    arms of the branch above it stopped 0.02 apart at tol 1e-5 (the continuation's step past the saddle
    found the branch below, traced already, and stopped there). Oracle as for 12/30."""
    _arms_reach_the_saddle(*_saddle(PairSpec(25, 58, 1.0), "interference.2", [-1.01, 1.01]), "interference.2", tol)


def test_the_arms_a_cut_across_a_saddle_left_open_are_carried_to_it():
    """35/61 interference.2 (B2) at its saddle near (-1, 1), tol 3e-4: two thin wedges of the other sign meet
    there; the continuation joined the grid's two left arms by a chord 0.03 beside the saddle, which the
    refinement after it cut as across a strip, and its ends were left open 1.2e-3 (4 tol) short of the saddle
    (seen by the gap measure's sections on from the right arms' corner: 2.39 tol). Oracle as for 12/30."""
    _arms_reach_the_saddle(*_saddle(PairSpec(35, 61, 1.0), "interference.2", [-1.01, 1.01]), "interference.2", 3e-4)


def _arms_reach_the_saddle(spec, m, s, name, tol):
    c = blocking_contour(spec, tol=tol, lines=[name])
    comps = c.line(name).components
    zeros = []
    for rho in RADII:
        f = lambda a: m(s[0] + rho * math.cos(a), s[1] + rho * math.sin(a))  # noqa: E731
        th = np.linspace(0.0, 2 * math.pi, 361)
        v = [f(a) for a in th]
        for a, b, fa, fb in zip(th[:-1], th[1:], v[:-1], v[1:]):
            if (fa > 0) != (fb > 0):
                a0 = brentq(f, a, b, xtol=1e-14)
                zeros.append([s[0] + rho * math.cos(a0), s[1] + rho * math.sin(a0)])
    assert len(zeros) == 4 * len(RADII)  # four arms cross every circle
    assert _nearest(np.array(zeros), comps).max() <= CONTRACT * tol
    ends = np.array([q[i] for q in comps for i in (0, -1)])
    assert np.hypot(*(ends - s).T).min() > 10 * max(RADII)


@pytest.mark.parametrize("delta", [1e-6, 1e-9, 1e-12])
def test_across_sees_a_zero_closer_to_the_edge_than_its_floor(delta):
    """The continuation's search along a normal that runs into the no-pair area samples from the edge
    towards the point down to round-off, whatever the floor of its samples about the point (tol / 16
    in the continuation: a line meeting the edge at a small angle runs closer to it than that). F =
    cbrt(1 - y) - cbrt(delta) for y < 1 (undefined beyond): the cube-root growth of the margins beside
    the no-pair edge, and a zero at y = 1 - delta in closed form."""
    from gearkit.blocking.edges import across

    F = lambda p, k: np.where(p[:, 1] < 1.0, np.cbrt(1.0 - p[:, 1]) - np.cbrt(delta), np.nan)  # noqa: E731
    floor = 1e-4  # tol / 16 at tol 1.6e-3: far above delta
    Q, N = np.array([[0.0, 0.5]]), np.array([[0.0, 1.0]])
    (s, v, c), = across(F, Q, N, np.array([1.0]), np.array([-1.0]), np.array([0]), 1.0, floor)
    assert c >= 0
    zero = 0.5 - delta  # along the normal from Q
    assert s[c] <= zero <= s[c + 1] and s[c + 1] - s[c] <= max(delta, 1e-12)


@pytest.mark.parametrize("slope", [0.0, 0.6, -1.5])
def test_a_line_meeting_the_no_pair_edge_reaches_it(slope):
    """F = x - 0.3 - slope y, undefined below y = 0.0137 (the edge inside a row of cells, as the
    no-pair edge lies): the grid masks every cell with an undefined corner, so marching squares end
    the line a cell short of the edge; it is carried on to the edge, where it ends within 2 tol of
    the closed-form point (0.3 + slope y_e, y_e), every vertex on the line (|F| / |grad F|)."""
    tol, y_e = 1e-6, 0.0137
    F = lambda p, k: np.where(p[:, 1] >= y_e, p[:, 0] - 0.3 - slope * p[:, 1], np.nan)  # noqa: E731
    xs = np.linspace(-1.0, 1.0, 9) + 0.011
    ys = np.linspace(0.0, 1.0, 9)
    gx, gy = np.meshgrid(xs, ys)
    values = F(np.column_stack([gx.ravel(), gy.ravel()]), None).reshape(gx.shape)
    px, py = padded_grid(xs, ys)
    lines = zero_lines(F, [(px, py, pad(values, np.nan))], tol)[0]
    assert len(lines) == 1
    q = lines[0]
    assert np.all(np.abs(F(q, None)) / math.hypot(1.0, slope) <= CONTRACT * tol)
    end = np.array([0.3 + slope * y_e, y_e])
    assert np.hypot(*(q[np.argmin(q[:, 1])] - end)) <= CONTRACT * tol


def test_a_line_beside_the_edge_whose_margin_has_a_root_there_is_left_as_the_grid_has_it():
    """F = cbrt(y - y_e) - 0.02 (x + 1): a margin that varies as the cube root of the distance to the
    edge (as those reading the working pressure angle do) has a zero set that meets the edge
    tangentially, at x = -1 far from where its grid piece ends; it is not carried along the edge (at
    every tol alike): the traced line is the grid's, every vertex on the line (closed form
    y = y_e + (0.02 (x + 1)) ** 3)."""
    y_e = 0.0137
    F = lambda p, k: np.where(p[:, 1] >= y_e, np.cbrt(p[:, 1] - y_e) - 0.02 * (p[:, 0] + 1.0), np.nan)  # noqa: E731
    xs = np.linspace(-1.0, 1.0, 9) + 0.011
    ys = np.linspace(0.0, 0.05, 9)
    gx, gy = np.meshgrid(xs, ys)
    values = F(np.column_stack([gx.ravel(), gy.ravel()]), None).reshape(gx.shape)
    px, py = padded_grid(xs, ys)
    ends = []
    for tol in (1e-3, 1e-7):
        lines = zero_lines(F, [(px, py, pad(values, np.nan))], tol)[0]
        for q in lines:
            exact_y = y_e + (0.02 * (q[:, 0] + 1.0)) ** 3
            assert np.all(np.abs(q[:, 1] - exact_y) <= CONTRACT * tol)
        ends.append(sorted(float(q[i, 0]) for q in lines for i in (0, -1)))
    assert ends[0] == pytest.approx(ends[1], abs=1e-2)  # the same pieces at both tolerances


TIP_EDGE_LINES = ("pointing.1", "tip_thickness.1=0.25", "tip_thickness.1=0.4")
SCAN_ROWS = 9  #: scan lines x2 = const within SCAN_HEIGHT of the window's bottom
SCAN_HEIGHT = 0.25  #: (shift units) where these lines run down to the no-pair edge
SCAN_STEPS = 200  #: samples per scan line


@pytest.mark.parametrize("tol", [1e-2, 1e-5])
def test_12_30_lines_reach_the_edge_where_the_tip_of_gear_2_meets_its_base_circle(tol):
    """12/30: pointing.1 and the tip-thickness lines of gear 1 run down to the edge of the no-pair
    area where d_a2 = d_b2 (tip shortening), and stopped 0.07 to 0.13 short of it. Oracle: the exact
    zeros of the scalar margins (the check's own functions) on scan lines x2 = const across the
    bottom of the window, every sign change between neighbouring samples solved by brentq; every one
    lies within 2 tol of the traced line."""
    spec = PairSpec(12, 30, 1.0)
    c = blocking_contour(spec, tol=tol, lines=list(TIP_EDGE_LINES))
    x1_lo, x1_hi, x2_lo, _ = c.window
    xs = np.linspace(x1_lo, x1_hi, SCAN_STEPS + 1)
    seen = 0
    for name in TIP_EDGE_LINES:
        zeros = []
        for x2 in x2_lo + SCAN_HEIGHT * (np.arange(SCAN_ROWS) + 0.5) / SCAN_ROWS:
            f = lambda x1: c.field.margin(name, x1, x2)  # noqa: E731
            v = np.array([f(x1) for x1 in xs])
            ok = np.isfinite(v[:-1]) & np.isfinite(v[1:]) & ((v[:-1] > 0) != (v[1:] > 0))
            zeros += [[brentq(f, xs[i], xs[i + 1], xtol=1e-14), x2] for i in np.flatnonzero(ok)]
        assert zeros, name
        seen += len(zeros)
        assert _nearest(np.array(zeros), c.line(name).components).max() <= CONTRACT * tol, name
    assert seen >= 2 * SCAN_ROWS


@pytest.mark.parametrize("ulps", [-4, 0, 4])
@pytest.mark.parametrize("delta", [2e-14, 1e-12])
def test_across_sees_a_zero_within_round_off_of_the_edge_from_any_edge_point(delta, ulps, monkeypatch):
    """Samples from the edge reach down to the round-off of its coordinates, wherever within a few ulps
    of the edge its search puts the edge point (moved ``ulps`` towards the undefined area or back): a
    line meeting the edge at a small angle comes that close to it, and where its zero is seen is
    where the continuation's front stops (from ``FLOOR * span``, 1e-13 here, a zero 2e-14 from the edge
    was not seen). F = cbrt(1 - y) - cbrt(delta) below y = 1, its conditions ``1 - y`` (solved for);
    the zero at y = 1 - delta in closed form."""
    from gearkit.blocking.edges import across

    def F(p, k):
        return np.where(p[:, 1] < 1.0, np.cbrt(1.0 - p[:, 1]) - np.cbrt(delta), np.nan)
    F.slack = lambda p, k: np.repeat((1.0 - p[:, 1])[:, None], 4, axis=1)
    move_solved_edges(monkeypatch, ulps)
    Q, N = np.array([[0.0, 0.5]]), np.array([[0.0, 1.0]])
    (s, v, c), = across(F, Q, N, np.array([1.0]), np.array([-1.0]), np.array([0]), 1.0, 1e-4)
    assert c >= 0
    zero = 0.5 - delta  # along the normal from Q
    assert s[c] <= zero <= s[c + 1] and s[c + 1] - s[c] <= 1.1 * delta


def test_a_front_turns_the_corner_of_a_kinked_zero_set():
    """F = max(y, p . n) with n = (sin 60, -cos 60): its zero set is the ray y = 0, x <= 0 turning at the
    origin by 120 degrees into the ray along (cos 240, sin 240) (closed form). A piece ending 0.1 short
    of the corner is carried round it (no step along the tangent passes a corner: each turns too far)
    and down the second ray to the window's frame at y = -0.55, every vertex within tol of the two rays
    (the front stopped at the corner)."""
    from gearkit.blocking.ends import extend_ends

    u = np.array([math.cos(math.radians(240.0)), math.sin(math.radians(240.0))])
    F = lambda p, k: np.maximum(p[:, 1], -u[1] * p[:, 0] + u[0] * p[:, 1])  # noqa: E731
    xs = ys = np.linspace(-1.1, 1.1, 5)  # a padded grid: the window is [-0.55, 0.55]^2
    tol = 1e-4
    piece = [(0, np.array([[-0.55, 0.0], [-0.3, 0.0], [-0.1, 0.0]]), np.full(3, np.nan))]
    (_, q, _, _), = extend_ends(F, piece, [(xs, ys, np.zeros((5, 5)))], tol)
    end = 0.55 / -u[1] * u  # where the second ray meets the frame
    assert np.hypot(*(q[-1] - end)) <= CONTRACT * tol
    on_first = np.where(q[:, 0] <= 0.0, np.abs(q[:, 1]), np.hypot(*q.T))
    on_second = np.hypot(*(q - np.clip(q @ u, 0.0, None)[:, None] * u).T)
    assert np.minimum(on_first, on_second).max() <= tol
    assert np.count_nonzero(on_second <= tol) >= 3  # the second ray traced, not just its ends


CORNER_ROWS = np.linspace(-0.925, -0.898, 7)  #: rows x2 = const below the corner of 17/76's wedge ...
CORNER_SPAN = (0.22, 0.262)  #: ... on which its left side's zero is the one sign change in x1
GAP_ROWS = (-0.9276, -0.9282, -0.9288)  #: rows across the 1.9e-3 where the turned front stopped beside the arm


def test_the_tip_interference_line_goes_on_round_the_corner_of_its_wedge():
    """Internal 17/76, shaper 17, at tol 1e-3: the tip sweep's margin is positive in a wedge beside the
    no-pair area whose left side turns at a corner near (0.2535, -0.8957) by about 120 degrees. Its upper
    arm, cut by the grid across the wedge, was carried to the corner and stopped there; its lower arm,
    ending beside the no-pair area, was not carried: the 0.035 between them was missing (scan 5.67 tol).
    Oracle: on rows x2 = const between the corner and the lower arm's end, the zero of the scalar margin
    (brentq), where check_pair's tip_interference finding changes (fails 2e-4 to its left, not to its
    right); every zero within 2 tol of the traced line (4.7 to 16.6 tol on the old code). The front turned
    round the corner then stopped 1.9e-3 short of the lower arm's end (it ran onto the arm, which no front
    carried): on rows across that gap the line is crossed once, within 2 tol of the zero (not at all before)."""
    from edgezeros import row_crossings

    spec = PairSpec(17, 76, 1.0, kind="internal", tool2=ShaperCutter(17))
    tol = 1e-3
    c = blocking_contour(spec, tol=tol, lines=["tip_interference"])
    f = PairField(spec)  # the check's own form circles (the contour's field interpolates them)
    zeros = []
    for x2 in [*CORNER_ROWS, *GAP_ROWS]:
        x1 = brentq(lambda x: f.margin("tip_interference", x, x2), *CORNER_SPAN, xtol=1e-12)
        assert "tip_interference" in f.check(x1 - 2e-4, x2)[1]
        assert "tip_interference" not in f.check(x1 + 2e-4, x2)[1]
        zeros.append([x1, x2])
    comps = c.line("tip_interference").components
    d = _nearest(np.array(zeros), comps)
    assert d.max() <= CONTRACT * tol, d / tol
    for x1, x2 in zeros[len(CORNER_ROWS):]:
        got = row_crossings(comps, x2, *CORNER_SPAN)
        assert len(got) == 1 and abs(got[0] - x1) <= CONTRACT * tol, (x2, got, x1)


ISLAND_ROWS = (-0.4975, -0.5, -0.5062)  #: rows x2 = const across the top of 13/56's island ...
ISLAND_SPAN = np.linspace(0.352, 0.3695, 176)  #: ... sampled in x1 for the sign changes of its margin


def test_a_thin_island_of_the_tip_sweep_is_cut_across_and_carried_round_its_end():
    """Internal 13/56, shaper 23, at tol 1e-3: the tip sweep finds no penetration in an island 0.02 long and
    0.005 wide (its margin flat at the sweep's resolution inside), which the grid closes as a loop of four
    vertices. Its chord from the upper side to the far end was split at its middle's nearer zero, on the lower
    side, and then walked down both sides round the tip (the tip sweep's chords are measured, never taken as
    across a strip): the upper side's last 0.015 and the far end were missing (scan 2.2 tol). Cut as a chord
    across a thin loop, its ends are carried on round the far end. Oracle: on rows x2 = const across the
    island's top, every zero of the check's scalar margin (brentq between sign changes of 0.0001-spaced samples)
    within 2 tol of the traced line (4.5 tol on the old code)."""
    spec = PairSpec(13, 56, 1.0, kind="internal", tool2=ShaperCutter(23))
    tol = 1e-3
    c = blocking_contour(spec, tol=tol, lines=["tip_interference"])
    f = PairField(spec)
    zeros = []
    for x2 in ISLAND_ROWS:
        g = lambda x: f.margin("tip_interference", x, x2)  # noqa: E731
        v = np.array([g(x) for x in ISLAND_SPAN])
        for j in np.flatnonzero((v[:-1] > 0) != (v[1:] > 0)):
            zeros.append([brentq(g, ISLAND_SPAN[j], ISLAND_SPAN[j + 1], xtol=1e-12), x2])
    assert len(zeros) == 2 * len(ISLAND_ROWS)  # each row crosses the island
    d = _nearest(np.array(zeros), c.line("tip_interference").components)
    assert d.max() <= CONTRACT * tol, d / tol


WEDGE_WINDOW = (-0.3, 0.2, -0.5, 0.0)  #: about 19/42's thin wedge of the tip sweep, closed short as in the full window
WEDGE_SPAN = (0.022, 0.032)  #: x1 about the wedge on the rows near its tip


def test_a_thin_wedge_of_the_tip_sweep_is_carried_to_its_tip():
    """Internal 19/42, shaper 19, at tol 1e-3: the tip sweep finds no penetration in a wedge half a tol wide
    3 tol from its tip (the window WEDGE_WINDOW, whose grid closes it as the whole window's does). A grid
    cell wider than the wedge closed it by a chord 3.8 tol short of its tip, its middle within the wedge's
    width of both sides (no measure of the tracing saw it; the bench's scan lines passed beside it). Oracle,
    apart from the tracing: on a row x2 = const the check's scalar margin has its largest value (scipy's
    minimize_scalar, bounded about the wedge) above zero above the tip and below zero below it, bisected in
    x2; the tip within 2 tol of the traced line (3.8 tol on the old code), and the two zeros (brentq) on
    rows across the wedge up to it too."""
    spec = PairSpec(19, 42, 1.0, kind="internal", tool2=ShaperCutter(19))
    tol = 1e-3
    c = blocking_contour(spec, tol=tol, lines=["tip_interference"], window=WEDGE_WINDOW)
    zeros = _tip_and_sides(PairField(spec), lambda x2: WEDGE_SPAN, -0.412, -0.409, tol * np.array([0.5, 1, 2, 3]))
    d = _nearest(zeros, c.line("tip_interference").components)
    assert d.max() <= CONTRACT * tol, d / tol


def test_a_long_thin_wedge_of_the_tip_sweep_is_carried_to_its_tip():
    """Internal 12/53, shaper 14, at tol 1e-3: the tip sweep finds no penetration in a thin wedge along the
    diagonal beside the no-pair area, its tip at about (0.092, -0.740); the grid closed it 25 tol short, and the
    sections carrying a kinked curve's corner on stopped after 16 tol (the bench's gap measure: 16 tol at
    (0.085, -0.746)). Oracle as for 19/42: the tip bisected in x2 off the margin's largest value on a row, the
    wedge's two zeros on rows up to 20 tol below it, all within 2 tol of the traced line."""
    spec = PairSpec(12, 53, 1.0, kind="internal", tool2=ShaperCutter(14))
    tol = 1e-3
    c = blocking_contour(spec, tol=tol, lines=["tip_interference"])
    about = lambda x2: (0.0885 + 1.05 * (x2 + 0.74), 0.0935 + 1.05 * (x2 + 0.74))  # noqa: E731 (the wedge's row)
    zeros = _tip_and_sides(PairField(spec), about, -0.7401, -0.738, -tol * np.array([0.5, 1, 2, 5, 10, 15, 20]))
    d = _nearest(zeros, c.line("tip_interference").components)
    assert d.max() <= CONTRACT * tol, d / tol


def _tip_and_sides(f, span, lo: float, hi: float, rows) -> np.ndarray:
    """The tip of a thin wedge where the tip sweep finds no penetration, and its sides: on a row x2 = const the
    check's scalar margin has its largest value (scipy's minimize_scalar, bounded to ``span(x2)``) above zero
    on the wedge's side of the tip and below it beyond, bisected in x2 between ``lo`` and ``hi``; then the two
    zeros (brentq) on the rows ``tip + rows`` (each inside the wedge)."""
    from scipy.optimize import minimize_scalar

    def top(x2):  # the margin's largest value on the row about the wedge, and where
        r = minimize_scalar(lambda x: -f.margin("tip_interference", x, x2), bounds=span(x2), method="bounded",
                            options={"xatol": 1e-10})
        return -r.fun, r.x

    inside = top(lo)[0] > 0
    assert inside == (top(hi)[0] < 0)
    for _ in range(24):
        m = 0.5 * (lo + hi)
        lo, hi = (m, hi) if (top(m)[0] > 0) == inside else (lo, m)
    tip = lo if inside else hi
    zeros = [[top(tip)[1], tip]]
    for x2 in tip + np.asarray(rows):
        v, x = top(x2)
        assert v > 0, x2
        g = lambda x1: f.margin("tip_interference", x1, x2)  # noqa: E731
        zeros += [[brentq(g, span(x2)[0], x, xtol=1e-12), x2], [brentq(g, x, span(x2)[1], xtol=1e-12), x2]]
    return np.array(zeros)


def test_corners_of_two_lines_carried_at_once_take_their_own_wedges():
    """Two kinked curves, each a wedge closed 4 tol short of its tip by a corner (at the second vertex of one
    line, the third of the other: carried from the later vertex first, each must take the zeros solved on its
    own wedge). Oracle, closed form: F_0 = |y| - 0.1 (1 - x), tip (1, 0); F_1 = |y - 5| - 0.2 (1 - x), tip
    (1, 5); every vertex of each line on its own zero set (to the vertex tolerance, |grad F| about 1) and its
    farthest one within a quarter tol of its own tip."""
    from gearkit.blocking.corners import carry_corners

    tol = 1e-3
    F = lambda p, k: np.where(np.asarray(k) == 0, np.abs(p[:, 1]) - 0.1 * (1.0 - p[:, 0]),  # noqa: E731
                              np.abs(p[:, 1] - 5.0) - 0.2 * (1.0 - p[:, 0]))
    a = np.array([[0.0, 0.1], [0.996, 0.0], [0.0, -0.1]])
    b = np.array([[-1.0, 5.4], [0.0, 5.2], [0.996, 5.0], [0.0, 4.8]])
    out = carry_corners(F, [(0, a, np.ones(3)), (1, b, np.ones(4))], {0, 1}, tol, tol / 4)
    for (k, q, _), tip in zip(out, ([1.0, 0.0], [1.0, 5.0])):
        assert len(q) > 5  # carried
        assert np.abs(F(q, np.full(len(q), k))).max() <= tol / 4, k
        assert np.hypot(*(q[np.argmax(q[:, 0])] - tip)) <= tol / 4, k
