"""The edge of the no-pair area solved for from the conditions for a pair (``F.slack``,
:func:`gearkit.blocking.edges.by_slack`), against the margins' own definedness, the multisection
that needs no measure, and the closed form of the tight-mesh edge."""
import math

import numpy as np
import pytest

from gearkit.blocking import edges
from gearkit.blocking.arrays import evaluator
from gearkit.blocking.field import PairField
from gearkit.curves import inv
from gearkit.families.involute.tools import ShaperCutter
from gearkit.pair import PairSpec

from edgezeros import move_solved_edges

PAIRS = {
    "20/40": PairSpec(20, 40, 1.0),
    "13/16": PairSpec(13, 16, 1.0),
    "46/49 internal": PairSpec(46, 49, 1.0, kind="internal", tool2=ShaperCutter(20)),
    "14/30 shaper": PairSpec(14, 30, 1.0, tool1=ShaperCutter(17)),
}
NAMES = ["contact_ratio=1", "interference.1", "interference.2", "pointing.1", "tip_clearance.2", "sliding.same"]


def _field(key):
    f = PairField(PAIRS[key])
    names = NAMES + (["exit_jamming", "undercut.1"] if f.internal else ["undercut.1"])
    return f, names, evaluator(f, names, None)


@pytest.mark.parametrize("key", sorted(PAIRS))
def test_the_conditions_are_positive_exactly_where_the_margin_is_defined(key):
    f, names, F = _field(key)
    rng = np.random.default_rng(3)
    p = rng.uniform(-2.5, 3.0, (1500, 2))
    defined = 0
    for k in range(len(names)):
        which = np.full(len(p), k)
        v, s = F(p, which), F.slack(p, which)
        assert s.shape == (len(p), 4)
        np.testing.assert_array_equal(np.all(s > 0, axis=1), np.isfinite(v), err_msg=names[k])
        defined += int(np.count_nonzero(np.isfinite(v)))
    assert 0.1 * len(p) * len(names) < defined < 0.95 * len(p) * len(names)  # both sides sampled


def _rows(F, k, n=12, seed=5):
    """Segments from a defined point to an undefined one."""
    rng = np.random.default_rng(seed)
    p = rng.uniform(-2.5, 3.0, (20 * n, 2))
    q = p + rng.normal(0.0, 0.6, p.shape)
    which = np.full(len(p), k)
    ok = np.isfinite(F(p, which)) & np.isnan(F(q, which))
    return p[ok][:n], q[ok][:n]


@pytest.mark.parametrize("key", sorted(PAIRS))
def test_the_edge_solved_for_is_where_the_multisection_finds_it(key):
    f, names, F = _field(key)
    close = 1e-12
    for k in (0, 1, 3):
        a, b = _rows(F, k, n=6)
        assert len(a) >= 5
        which = np.full(len(a), k)
        e = edges.by_slack(F.slack, a, b, which, close)
        m = edges._multisection(F, a.copy(), b.copy(), which, close)  # sees only defined or not
        np.testing.assert_array_less(np.hypot(*(e - m).T), 4 * close)
        assert np.all(np.isfinite(F(e, which)))  # the last defined point ...
        u = (b - a) / np.hypot(*(b - a).T)[:, None]
        assert np.all(np.isnan(F(e + 4 * close * u, which)))  # ... with the area a step beyond


def test_the_tight_mesh_edge_is_met_where_its_closed_form_puts_it_in_two_rounds():
    """Rack-cut gears: a tight mesh exists while inv a_t + 2 (x1 + x2) tan a_n / (z1 + z2) > 1e-9
    (the arrays' threshold); that edge is a straight line, met to round-off by the false position."""
    f, names, F = _field("20/40")
    edge = (1e-9 - inv(f._sec.alpha_t)) * 60 / (2 * math.tan(f._sec.alpha_n))
    x1 = np.array([-1.0, -0.5, 0.0, 0.25])
    a, b = np.column_stack([x1, np.full(4, 2.0)]), np.column_stack([x1, np.full(4, -6.0)])
    calls = []

    def S(p, k):
        calls.append(len(p))
        return F.slack(p, k)
    e = edges.by_slack(S, a, b, np.zeros(4, int), 1e-13)
    np.testing.assert_allclose(e.sum(axis=1), edge, rtol=0, atol=1e-13)
    slack_calls = len(calls)

    def G(p, k):
        calls.append(len(p))
        return F(p, k)
    m = edges._multisection(G, a.copy(), b.copy(), np.zeros(4, int), 1e-13)
    np.testing.assert_allclose(m.sum(axis=1), edge, rtol=0, atol=1e-13)
    # even splits, the false position (at round-off), one more round of guards to close the bracket
    assert slack_calls == 3 and len(calls) - slack_calls >= 10


@pytest.mark.parametrize("key", sorted(PAIRS))
def test_a_margin_at_a_point_does_not_depend_on_the_points_beside_it(key):
    """The same point alone or among others, to the bit (each Newton iteration of the working
    pressure angle stops on its own): an edge solved to round-off stays defined when evaluated again."""
    f, names, F = _field(key)
    names = list(dict.fromkeys(names + list(f.hard)))
    F = evaluator(f, names, None)
    p = np.random.default_rng(1).uniform(-2.0, 2.5, (120, 2))
    for k in range(len(names)):
        which = np.full(len(p), k)
        alone = np.array([F(p[i:i + 1], which[:1])[0] for i in range(len(p))])
        np.testing.assert_array_equal(F(p, which), alone, err_msg=names[k])


@pytest.mark.parametrize("ulps", [-4, -1, 0, 1, 4])
def test_a_line_along_the_edge_below_the_bands_rows_is_traced_on_from_any_round_off_edge(ulps, monkeypatch):
    """51/101's interference.1 runs along the no-pair edge near the bottom frame and crosses the band's
    edge row on its way there: its piece below that row is carried on whichever of the edge points
    within a few ulps of each other the search returns (every solved edge moved that many ulps towards
    the undefined area or back: the piece was lost, 7 tol at 1e-3, with the solved edge as found and
    4 ulps beyond it). The bench's scan: exact zeros on scan lines, each within 2 tol of a traced line."""
    from gearkit.blocking import blocking_contour
    from gearkit.bench.topology import scan_gap

    move_solved_edges(monkeypatch, ulps)
    c = blocking_contour(PairSpec(51, 101, 1.0), tol=1e-3)
    assert scan_gap(c)[0] <= 2e-3


def test_a_vertex_on_the_lattices_boundary_to_round_off_is_on_it():
    """The contour generator interpolates a row's index as ``(1 - f) j + f j``: a vertex on the edge's
    row of an 82-row lattice between columns 72 and 73 came as 81.00000000000001 for some values at the
    nodes; it is on that row (it was not: its line was not carried on below the row)."""
    from gearkit.blocking.band import _off_lattice

    f = np.linspace(0.0, 1.0, 2001)
    row, col = (1.0 - f) * 81.0 + f * 81.0, (1.0 - f) * 86.0 + f * 86.0  # the interpolation, round-off and all
    assert np.any(row != 81.0) and np.any(col != 86.0)  # (it does miss them)
    for r, c in zip(row, col):
        assert _off_lattice((72.037, r), 82, 87)  # on the last row, between two nodes
        assert _off_lattice((c, 40.5), 82, 87)  # on the last column, between two rows
        assert not _off_lattice((72.0, r), 82, 87) and not _off_lattice((c, 40.0), 82, 87)  # nodes
        assert not _off_lattice((60.5, r - 1.0), 82, 87)  # inside


def test_a_segment_shorter_than_the_resolution_among_others_is_its_own_start():
    """A segment already within ``close`` (zero length) beside segments to solve: it takes no samples and
    returns its start, the others their edges (the first round sampled every segment's start but only
    the live segments: the functions' indices no longer matched the points, an IndexError in an atlas)."""
    f, names, F = _field("20/40")
    edge = (1e-9 - inv(f._sec.alpha_t)) * 60 / (2 * math.tan(f._sec.alpha_n))
    a = np.array([[0.0, 2.0], [0.3, 0.3], [-0.5, 2.0]])
    b = np.array([[0.0, -6.0], [0.3, 0.3], [-0.5, -6.0]])
    e = edges.by_slack(F.slack, a, b, np.array([0, 1, 0]), 1e-13)
    np.testing.assert_array_equal(e[1], a[1])
    np.testing.assert_allclose(e[[0, 2]].sum(axis=1), edge, rtol=0, atol=1e-13)


@pytest.mark.parametrize("key", ["20/40", "46/49 internal"])
def test_functions_read_together_are_each_as_read_alone(key):
    """Several functions at once (each point its own, in any order) and their conditions for a pair
    (``F.slack``) equal each function read at its points alone, to the bit (one evaluation of the pair
    formulas serves them all: the hard margins, worked out once, are read by the region and by their
    own lines)."""
    f, names, _ = _field(key)
    names = list(dict.fromkeys(names + list(f.hard))) + ["region"]
    F = evaluator(f, names, (-1.5, 2.0, -1.5, 2.0))
    rng = np.random.default_rng(7)
    p = rng.uniform(-2.0, 2.5, (300, 2))
    which = rng.integers(0, len(names), len(p))
    both, conditions = F(p, which), F.slack(p, which)
    for k in range(len(names)):
        sel = np.flatnonzero(which == k)
        np.testing.assert_array_equal(both[sel], F(p[sel], np.full(sel.size, k)), err_msg=names[k])
        np.testing.assert_array_equal(conditions[sel], F.slack(p[sel], np.full(sel.size, k)), err_msg=names[k])


def test_a_steps_edge_points_are_those_of_each_search_alone():
    """:func:`edges.step_ends` reads every step's prediction and the points a step to either side of it in
    one evaluation and makes both edge searches in one: each edge point equals the one
    :func:`edges.edge_point` finds for that step alone (before the prediction; a whole step ahead, from the
    left side of the normal where it is defined, else the right), to the bit."""
    f, names, F = _field("20/40")
    rng = np.random.default_rng(5)
    P = rng.uniform(-1.5, 0.5, (150, 2))
    angle = rng.uniform(0.0, 2 * math.pi, len(P))
    T = np.column_stack([np.cos(angle), np.sin(angle)])
    h = rng.uniform(0.05, 0.8, len(P))
    which = rng.integers(0, len(names), len(P))
    P, T, h, which = (v[np.isfinite(F(P, which))] for v in (P, T, h, which))  # steps from defined points
    Q, out, E, ahead = edges.step_ends(F, P, T, h, which, 4.0, 1e-9)
    assert 5 <= out.size < len(P) and np.isfinite(ahead[:, 0]).sum() >= 3
    for r, e, q in zip(out, E, ahead):
        one = slice(r, r + 1)
        np.testing.assert_array_equal(e, edges.edge_point(F, P[one], Q[one], which[one], 4.0, 1e-9)[0])
        N = np.array([[-T[r, 1], T[r, 0]]])
        left, right = Q[one] + h[one, None] * N, Q[one] + -1.0 * h[one, None] * N
        side = left if np.isfinite(F(left, which[one])[0]) else right if np.isfinite(F(right, which[one])[0]) else None
        expected = np.full(2, np.nan) if side is None else edges.edge_point(F, side, Q[one], which[one], 4.0, 1e-9)[0]
        np.testing.assert_array_equal(q, expected)
