"""Issue 19: the line of equal specific sliding, |zeta1| = |zeta2| at the ends of the path.

Its margin |zeta1| - |zeta2| is zero where either factor zeta1 - zeta2 or zeta1 + zeta2 is: two legs,
which cross where both slidings vanish (a saddle of the absolute form, no sign change along either
leg there) and which both run along the no-pair edge. It is traced as the zeros of the two factors,
each a smooth function (gearkit.blocking.pair_arrays: ``PairArrays.sliding_factors``). Oracles: the specific
slidings of the scalar pair geometry (``PairField.point``, the check's own, with the generated form
circles), the sign of
|zeta1| - |zeta2| against the product of the factors, and the exact zeros of the scalar margin on
circles around the 12/30 crossing (solved by brentq along the circle).
"""
import numpy as np
import pytest
from scipy.optimize import brentq

from gearkit.blocking import blocking_contour
from gearkit.blocking.arrays import evaluator
from gearkit.blocking.field import PairField
from gearkit.distances import distances_to_polyline
from gearkit.errors import SpecError
from gearkit.pair import PairSpec

from edgezeros import row_crossings

CONTRACT = 2.0  #: achieved / tol (issue 19)
CROSSING_12_30 = (0.38812051, -1.2461073)  #: where the legs cross, 1.95e-3 (in x1 + x2) above the no-pair edge
ANGLES = 1440  #: samples on a circle around it


@pytest.mark.parametrize("z1, z2", [(12, 30), (13, 16), (20, 40), (17, 60)])
def test_the_factors_have_the_sign_of_the_sliding_margin(z1, z2):
    """sign(|zeta1| - |zeta2|) = sign((zeta1 - zeta2)(zeta1 + zeta2)), and the factors are that product
    times a square: their product has the margin's sign at every point where a pair exists."""
    field = PairField(PairSpec(z1, z2, 1.0))
    rng = np.random.default_rng(z1 * 100 + z2)
    w = blocking_contour(PairSpec(z1, z2, 1.0), tol=1e-2, lines=["sliding"]).window
    pts = np.column_stack([rng.uniform(w[0], w[1], 300), rng.uniform(w[2], w[3], 300)])
    F = evaluator(field, ["sliding.same", "sliding.opposite"], w)
    same, opposite = F(pts, np.zeros(len(pts), int)), F(pts, np.ones(len(pts), int))
    checked = 0
    for p, a, b in zip(pts, same, opposite):
        pt = field.point(*p)
        if not pt.valid:  # no pair at this point: the arrays say so too
            assert np.isnan(a) and np.isnan(b)
            continue
        s = pt.geometry((True, True)).specific_sliding  # the generated form circles, as the check reads them
        margin = abs(s["start"][0]) - abs(s["end"][1])
        if abs(margin) < 1e-9:
            continue
        assert np.sign(a * b) == np.sign(margin), (p, a, b, margin)
        checked += 1
    assert checked >= 150


def _circle_zeros(field, centre, radius):
    """Exact zeros of the scalar sliding margin on the circle of ``radius`` around ``centre``."""
    def f(t):
        return field.margin("sliding", centre[0] + radius * np.cos(t), centre[1] + radius * np.sin(t))
    t = np.linspace(0.0, 2 * np.pi, ANGLES + 1)
    v = np.array([f(a) for a in t])
    out = []
    for i in np.flatnonzero(np.isfinite(v[:-1]) & np.isfinite(v[1:]) & ((v[:-1] > 0) != (v[1:] > 0))):
        a = brentq(f, t[i], t[i + 1], xtol=1e-15, rtol=1e-15)
        if abs(f(a)) <= 0.5 * min(abs(v[i]), abs(v[i + 1])):  # a zero, not a pole
            out.append([centre[0] + radius * np.cos(a), centre[1] + radius * np.sin(a)])
    return np.array(out).reshape(-1, 2)


_CROSSING_ZEROS = {}  #: the exact zeros by radius, shared by the tolerances (the scalar margin has none)


def _crossing_zeros(field, radius):
    """:func:`_circle_zeros` around the 12/30 crossing, worked out once per radius."""
    if radius not in _CROSSING_ZEROS:
        _CROSSING_ZEROS[radius] = _circle_zeros(field, CROSSING_12_30, radius)
    return _CROSSING_ZEROS[radius]


@pytest.mark.parametrize("tol", [1e-3, 1e-4, 1e-6])
def test_the_legs_crossing_beside_the_no_pair_edge_are_traced_through_it(tol):
    """12/30: the four arms of the crossing, 1.95e-3 above the no-pair edge, each reach it: the exact zeros
    on circles of radius 2e-2 down to 5 tol around it all lie within 2 tol of the traced line."""
    c = blocking_contour(PairSpec(12, 30, 1.0), tol=tol, lines=["sliding"])
    comps = c.line("sliding").components
    for radius in (2e-2, 5e-3, 1e-3, 5 * tol):
        if radius < 5 * tol:
            continue
        zeros = _crossing_zeros(c.field, radius)
        assert len(zeros) >= 3, radius  # the arms the circle meets where a pair exists
        far = np.min([distances_to_polyline(zeros, q) for q in comps], axis=0)
        assert far.max() <= CONTRACT * tol, (radius, far.max())


@pytest.mark.parametrize("tol", [1e-4, 1e-5])
def test_a_leg_touching_the_no_pair_edge_twice_is_not_drawn_along_it_between(tol):
    """31/39: the leg zeta1 = -zeta2 touches the no-pair edge near x1 = -0.159 and again near -0.138 and
    runs nowhere near it between (its margin about -30 along the edge there); the band joined the two
    touchdowns by a chord along the edge, 0.015 from any zero (150 tol at 1e-4, 1499 at 1e-5): the slope
    at its ends, steep beside the edge, made its middle look within tol. Oracle: at points along the
    traced line in that stretch, the scalar margin (``PairField.margin``, the check's own geometry) takes
    both signs within 2 tol of the point (on circles of radius 1e-4 .. 2 tol: beside the edge the margin
    varies as the cube root of the distance to it, and the leg runs along it closer than 1e-8)."""
    field = PairField(PairSpec(31, 39, 1.0))
    c = blocking_contour(PairSpec(31, 39, 1.0), tol=tol, lines=["sliding"])
    lo, hi = np.array([-0.156, -1.298]), np.array([-0.141, -1.277])
    pts = []
    for q in c.line("sliding").components:
        d = np.hypot(*np.diff(q, axis=0).T)
        s = np.concatenate([[0.0], np.cumsum(d)])
        t = np.linspace(0.0, s[-1], max(2, int(s[-1] / 1e-3)))
        p = np.column_stack([np.interp(t, s, q[:, 0]), np.interp(t, s, q[:, 1])])
        pts += [v for v in p if np.all(v >= lo) and np.all(v <= hi)]
    a = np.linspace(0.0, 2 * np.pi, 16, endpoint=False)
    ring = np.concatenate([r * tol * np.column_stack([np.cos(a), np.sin(a)]) for r in np.geomspace(1e-4, 2.0, 12)])
    def margin(q):
        return np.array([field.margin("sliding", *q)])

    for p in pts:
        assert _a_factor_takes_both_signs(margin, p, ring), (p, *_ring_range(margin, p, ring))


@pytest.mark.parametrize("z1, z2, near_x1, near_x2", [(9, 21, 0.2189, -0.8268), (13, 45, 0.4738, -1.6613)])
def test_a_chord_through_the_legs_crossing_at_a_small_angle_is_measured_on_its_leg(z1, z2, near_x1, near_x2):
    """9/21 at tol 1e-5: the legs cross near (0.2189, -0.8268) at about 4 degrees, and a chord of the
    leg zeta1 = zeta2 passes the crossing at its middle. There |zeta1| - |zeta2| changes sign only
    across a sliver about 3e-7 wide 4e-6 beside the middle, which the measure's rays stepped over: it
    read the chord 11.5 tol off. 13/45 at tol 1e-5: a component of the leg zeta1 = zeta2 has a vertex
    near (0.4738, -1.6613) on the other leg's zeros, 9.2 tol from its own: measured against one leg per
    component it read 9.2 tol. Oracle: at each vertex and chord middle of the traced line within 1e-2
    of the spot, zeta1 - zeta2 or zeta1 + zeta2 (the scalar pair geometry's specific slidings, with the
    generated form circles) takes both signs within 2 tol (on circles of radius 1e-4 .. 2 tol: beside the
    no-pair edge the legs vary as the cube root of the distance to it);
    and the measure (``deviation``) reads the contour within 2 tol too."""
    from gearkit.bench.blocking import deviation

    tol = 1e-5
    crossing = np.array([near_x1, near_x2])
    field = PairField(PairSpec(z1, z2, 1.0))
    c = blocking_contour(PairSpec(z1, z2, 1.0), tol=tol)

    def factors(p):  # NaN where the shifts give no pair (beside the no-pair edge)
        try:
            s = field.point(*p).geometry((True, True)).specific_sliding
        except SpecError:
            return np.full(2, np.nan)
        return np.array([s["start"][0] - s["end"][1], s["start"][0] + s["end"][1]])

    a = np.linspace(0.0, 2 * np.pi, 16, endpoint=False)
    ring = np.concatenate([r * tol * np.column_stack([np.cos(a), np.sin(a)]) for r in np.geomspace(1e-4, CONTRACT, 12)])
    probed = 0
    for q in c.line("sliding").components:
        for p in np.concatenate([q[:-1], 0.5 * (q[:-1] + q[1:])]):
            if np.hypot(*(p - crossing)) > 1e-2:
                continue
            # beside the no-pair edge the legs vary as the cube root
            assert _a_factor_takes_both_signs(factors, p, ring), (p, *_ring_range(factors, p, ring))
            probed += 1
    assert probed >= 6
    assert deviation(c) <= CONTRACT * tol


def _a_factor_takes_both_signs(factors, p, ring) -> bool:
    """Whether one of the factors (an array of them at a point) takes both signs at the points ``p + ring`` (NaN: no sign), the ring's
    widest circles read first and the reading stopped once one has (the verdict of reading them all)."""
    seen = False  # per factor, (positive, negative)
    for o in ring[::-1]:
        w = factors(p + o)
        seen = seen | np.column_stack([w > 0, w < 0])
        if seen.all(axis=1).any():
            return True
    return False


def _ring_range(factors, p, ring):
    """Each factor's least and greatest value on the ring (the failure's message)."""
    v = np.array([factors(p + o) for o in ring])
    return np.nanmin(v, axis=0), np.nanmax(v, axis=0)


def test_a_chord_its_line_crosses_at_the_middle_is_refined():
    """25/54 internal (shaper z0 20) at tol 1e-5: between the grid rows x2 = -0.583 and -0.667 the sliding line
    bends one way and then the other, crossing the grid's chord there (0.098 long) at its middle, so the chord
    was estimated on its line at its middle and kept, 4 tol off its line at a quarter and 7.3 tol at three
    quarters. On rows across it, the traced line crosses each row once, within 2 tol of the zero of the check's
    sliding margin (brentq)."""
    from gearkit.families.involute import ShaperCutter

    tol = 1e-5
    spec = PairSpec(25, 54, 1.0, kind="internal", tool2=ShaperCutter(20))
    field = PairField(spec)
    c = blocking_contour(spec, tol=tol, lines=["sliding"])
    xs = np.linspace(-0.2, -0.03, 18)
    for y in np.linspace(-0.665, -0.59, 16):
        v = np.array([field.margin("sliding", float(x), float(y)) for x in xs])
        i = np.flatnonzero((v[:-1] >= 0) != (v[1:] >= 0))
        assert len(i) == 1, (y, v)
        exact = brentq(lambda x: field.margin("sliding", x, float(y)), xs[i[0]], xs[i[0] + 1], xtol=1e-13)
        got = row_crossings(c.line("sliding").components, float(y), xs[0], xs[-1])
        assert len(got) == 1 and abs(got[0] - exact) <= 2.0 * tol, (y, exact, got)


@pytest.mark.parametrize("tol", [1e-3, 1e-5])
def test_the_leg_of_two_alike_gears_along_equal_shifts_is_traced(tol):
    """17/17: two alike gears with equal shifts make a symmetric pair, the same specific sliding at both ends of
    the path, so the leg zeta1 = zeta2 runs along x1 = x2 where the margin changes sign across it. The grid's nodes
    lie on that line (the window is square), the margin there +-1e-17, and every vertex along it, on a grid edge
    with no sign change, was read as a jump and dropped: no trace from (-0.32, -0.32) to (-0.10, -0.10), 129 tol at
    1e-3. Oracle: at points of x1 = x2 where the check's scalar margin takes opposite signs 2e-4 to either side
    (across the line), the margin there is zero to round-off (the pair's symmetry) and the traced line passes
    within 2 tol."""
    field = PairField(PairSpec(17, 17, 1.0))
    c = blocking_contour(PairSpec(17, 17, 1.0), tol=tol, lines=["sliding"])
    h = 2e-4
    on = []
    for t in np.linspace(-0.31, -0.12, 8):
        above, below = field.margin("sliding", t - h, t + h), field.margin("sliding", t + h, t - h)
        if above * below < 0:
            assert abs(field.margin("sliding", t, t)) <= 1e-12, t
            on.append([t, t])
    assert len(on) >= 6  # the oracle sees the line across most of the stretch
    d = np.min([distances_to_polyline(np.array(on), q) for q in c.line("sliding").components], axis=0)
    assert d.max() <= CONTRACT * tol, np.array(on)[d > CONTRACT * tol]
