"""Blocking contours of internal pairs beside the shift where gear 1 is cut with no tooth.

Below that shift (and above the one where gear 1's tip reaches its base circle) the pair formulas
still give a pair, but :func:`~gearkit.checks.check_pair` generates gear 1 with the pair's tip, finds
no involute flank left and raises a SpecError: no pair exists there. The traced contour is the map of
the check, so no line runs in that strip and the region does not reach into it. The scalar margins
(``PairField.margin``, ``BlockingContour.margins``) read numbers there for the lines that need no
form circle of gear 1 (46/49, shaper z0 20: the tip-to-tip eps_alpha = 1 line ran 0.22 into it;
57/130, z0 28: s_a1 = 0.25 m_n), so the traced lines looked short of them.

Oracles: check_pair itself (raises, or reports) at random points across the strip; the exact zeros of
the scalar margins on rows x2 = const from the no-pair edge (bisected), solved by brentq.
"""
import math
from dataclasses import replace

import numpy as np
import pytest

from gearkit.blocking import blocking_contour
from gearkit.blocking.contour import default_window
from gearkit.blocking.field import PairField
from gearkit.checks import check_pair
from gearkit.distances import distances_to_polyline
from gearkit.errors import SpecError
from gearkit.families.involute import ShaperCutter
from gearkit.pair import PairSpec, pair_geometry

from edgezeros import zeros_from_edge

CONTRACT = 2.0  #: achieved / tol
SAMPLES = 24  #: random points per pair across the strip
ROWS = 16  #: rows x2 = const across the window
EDGE_BISECTIONS = 60  #: bisections locating the no-pair edge on a row (to round-off)
DISTANCES = np.geomspace(1e-12, 0.6, 160)  #: samples right of the edge (shift units)
CHECK_BISECTIONS = 30  #: bisections of the check's first pair on a row (to 1e-11)
STEP = 0.01  #: steps along a row from a zero in the strip to the check's first pair
FORM_ACCURACY = 1e-9  #: (m_n) the form-circle interpolant's accuracy (PairField.form_interpolant)
RINGS = {"46/49": (46, 49, 20), "57/130": (57, 130, 28)}


def _ring(key):
    z1, z2, z0 = RINGS[key]
    return PairSpec(z1, z2, 1.0, kind="internal", tool2=ShaperCutter(z0))


def _check_raises(spec) -> bool:
    try:
        check_pair(spec)
    except SpecError:
        return True
    return False


def _formula_raises(spec) -> bool:
    """True where the pair formulas give no pair (check_pair's formula geometry raises)."""
    try:
        pair_geometry(spec)
    except SpecError:
        return True
    return False


@pytest.mark.parametrize("key", sorted(RINGS))
def test_the_margins_are_undefined_exactly_where_the_check_finds_no_pair(key):
    """Random points from the window's left side to 0.1 past gear 1's no-tooth shift: every margin of
    the field is NaN where check_pair raises and a number where it reports; contains() is check_pair's
    verdict. (On the old code the margins that need no form circle of gear 1 were numbers in the strip.)"""
    spec = _ring(key)
    field = PairField(spec)
    window = default_window(field)
    rng = np.random.default_rng(19)
    no_pair = pair = 0
    for _ in range(SAMPLES):
        # the strip starts where the pair formulas give a pair (gear 1's tip above its base circle: the
        # check's formula geometry does not raise), bisected on this row
        x2 = rng.uniform(0.0, window[3])
        a, b = -3.0, window[0] + 0.6
        assert _formula_raises(field.spec(a, x2)) and not _formula_raises(field.spec(b, x2))
        for _ in range(EDGE_BISECTIONS):
            m = 0.5 * (a + b)
            a, b = (m, b) if _formula_raises(field.spec(m, x2)) else (a, m)
        x1 = b + 0.15 * rng.uniform() ** 2  # (denser near the edge: the strip is 0.02 .. 0.06 wide)
        raises = _check_raises(field.spec(x1, x2))
        # (the undercut onset's margin is the shift itself, x1 - x1,min: defined with or without a pair)
        lines = [d for d in field.lines if not d.name.startswith("undercut.")]
        values = [field.margin(d.name, x1, x2) for d in lines]
        if raises:
            no_pair += 1
            assert all(math.isnan(v) for v in values), (x1, x2, [d.name for d, v in zip(lines, values)
                                                                 if not math.isnan(v)])
            assert not field.point(x1, x2).valid
        else:
            pair += 1
            assert all(not math.isnan(v) for d, v in zip(lines, values) if d.name != "sliding"), (x1, x2)
    assert no_pair >= 3 and pair >= 3  # the samples cover both sides of the no-tooth shift


def _row_zeros(margin, lo, hi):
    """The zeros of ``margin(x1)`` (NaN where no pair exists) right of its no-pair edge, bisected between
    ``lo`` (undefined) and ``hi`` (defined): empty where the row has no such edge."""
    return zeros_from_edge(margin, lo, hi, math.inf, DISTANCES)


def _formula_margin(spec, name):
    """``name``'s margin read off the pair formulas (check_pair's formula geometry, no generated gear:
    defined in the strip too), NaN where they give no pair."""
    def margin(x1, x2):
        try:
            g = pair_geometry(replace(spec, shift1=x1, shift2=x2))
        except SpecError:
            return math.nan
        if name.startswith("tip_thickness.1="):
            return g.gears[0].tip_thickness_normal / g.module - float(name.split("=")[1])
        assert name.startswith("contact_ratio_tip=")
        return g.contact_ratio_nominal - float(name.split("=")[1])
    return margin


STRIP_LINES = [  # (ring, line, tol, zeros in the strip, zeros with a pair): lines that the old scalar margins
    # showed in the strip (46/49 the tip-to-tip eps_alpha = 1 line, 0.22 from the trace; 57/130 s_a1 = 0.25 m_n,
    # which lies wholly in it: gear 1 is 0.257 m_n thick at the tip where the check first finds a tooth)
    ("46/49", "contact_ratio_tip=1", 1e-4, True, True),
    ("57/130", "tip_thickness.1=0.25", 1e-4, True, False),
]


@pytest.mark.parametrize("key, name, tol, in_strip, with_pair", STRIP_LINES)
def test_a_line_beside_gear_1s_no_tooth_shift_is_the_checks_line(key, name, tol, in_strip, with_pair):
    """The zeros of the line's margin by the check's formula geometry on rows x2 = const from its no-pair
    edge (gear 1's tip at its base circle), solved by brentq: those where check_pair (generated) gives a
    pair lie within 2 tol of the trace; those where it raises (the strip) have no trace near, closer than
    their own distance from the nearest pair the check gives on the row, less 2 tol."""
    spec = _ring(key)
    c = blocking_contour(spec, tol=tol, lines=[name])
    w = c.window
    margin = _formula_margin(spec, name)
    on, off = [], []
    for x2 in np.linspace(w[2], w[3], ROWS + 2)[1:-1]:
        for x in _row_zeros(lambda x1: margin(x1, x2), -3.0, w[0] + 0.6):
            (off if _check_raises(c.field.spec(x, x2)) else on).append((x, x2))
    assert bool(on) == with_pair and bool(off) == in_strip
    components = c.line(name).components
    if on:
        far = np.min([distances_to_polyline(np.array(on), q) for q in components], axis=0)
        assert float(far.max()) <= CONTRACT * tol
    for x, x2 in off:  # the check's pair nearest on the row: stepped to from the zero, then bisected
        b = x
        while _check_raises(c.field.spec(b, x2)):
            b += STEP
        a = b - STEP
        for _ in range(CHECK_BISECTIONS):
            m = 0.5 * (a + b)
            a, b = (m, b) if _check_raises(c.field.spec(m, x2)) else (a, m)
        near = min(float(distances_to_polyline(np.array([[x, x2]]), q)[0]) for q in components) if components \
            else math.inf
        assert near >= (b - x) - CONTRACT * tol


@pytest.mark.parametrize("key", sorted(RINGS))
def test_gear_1s_no_tooth_shift_is_the_checks_to_round_off(key):
    """The no-pair edge where gear 1 is cut no tooth, as the contour's field reads it (its form-circle
    interpolant's floor, below which the arrays find no pair), is bisected 12 times; once the trace
    generates gears between those bisections (as its edge searches closing in on the edge do) it is
    check_pair's to neighbouring floats: the check raises at the floor and gives a pair one float above
    it, and the interpolant, reaching down to there, gives the generated gear's form circle within its
    own accuracy. (Each point the trace put inside the 3.6e-4 wide bracket on 46/49 generated a gear.)"""
    from gearkit.blocking.arrays import margins
    from gearkit.blocking.forms import FLOOR_HITS

    spec = _ring(key)
    field = PairField(spec, x_ranges=default_window(PairField(spec)))
    floor, lo = field.form_interpolant(1)[4], field.form_interpolant(1)[0]
    assert lo - floor > 1e-6  # coarse until the trace probes it
    for k in range(FLOOR_HITS):
        field.form_diameter(1, floor + (lo - floor) * (k + 1) / (FLOOR_HITS + 1))
    fit = field.form_interpolant(1)
    floor, lo = fit[4], fit[0]
    assert lo == np.nextafter(floor, np.inf)
    assert abs(fit[3](lo) - field.form_diameter(1, lo, exact=True)) <= FORM_ACCURACY * spec.module
    for x2 in (0.5, 2.0):
        assert _check_raises(field.spec(floor, x2)) and not _check_raises(field.spec(lo, x2))
        m = margins(field, np.array([floor, lo]), np.array([x2, x2]), ["pointing.1"])["pointing.1"]
        assert np.isnan(m[0]) and np.isfinite(m[1])


def test_the_tip_sweep_in_blocks_is_the_sweep_at_once(monkeypatch):
    """The tip sweep evaluates its samples of the pinion angle in blocks (speed): at 400 random shift pairs
    of 46/49 the map's tip-interference margin and the sweep's angles are bit for bit those of the whole
    round at once (blocks of 64 samples against one block), deep and clear pairs alike."""
    import gearkit.pair.sweep as sweep
    from gearkit.blocking.arrays import evaluator

    spec = _ring("46/49")
    field = PairField(spec, x_ranges=default_window(PairField(spec)))
    w = field.x_ranges
    rng = np.random.default_rng(7)
    x1, x2 = rng.uniform(w[0][0], w[0][1], 400), rng.uniform(w[1][0], w[1][1], 400)
    runs = []
    for block in (64, 10 ** 9):
        monkeypatch.setattr(sweep, "SWEEP_BLOCK", block)
        calls = []
        monkeypatch.setattr(sweep, "_corners", lambda *a, _c=sweep._corners: calls.append(a[0].size) or _c(*a))
        F = evaluator(field, ["tip_interference"], None)
        runs.append(F(np.column_stack([x1, x2]), np.zeros(len(x1), int)))
        assert (max(calls) <= 64) == (block == 64)
        monkeypatch.undo()
    finite = np.isfinite(runs[0])
    assert np.array_equal(runs[0][finite], runs[1][finite]) and np.array_equal(finite, np.isfinite(runs[1]))
    assert np.count_nonzero(runs[0][finite] < 0) >= 20 and np.count_nonzero(runs[0][finite] > 0) >= 20


def test_the_tip_interference_line_is_measured_where_its_margin_is_flat():
    """The tip sweep's margin is its resolution (flat) wherever the sweep finds no penetration, so a chord's
    middle on that side reads the flat level whatever its distance from the line, and an estimate from it
    kept chords far off (29/39, shaper 19, at tol 1e-3: a grid chord's middle 2.6 tol from the zero, kept as
    0.3). Every chord's middle of the traced line has a sign change of the tip sweep's margin within the
    contract to either side along the chord's normal (where both ends have a pair)."""
    from gearkit.blocking.arrays import evaluator

    tol = 1e-3
    c = blocking_contour(PairSpec(29, 39, 1.0, kind="internal", tool2=ShaperCutter(19)), tol=tol,
                         lines=["tip_interference"])
    P = np.concatenate([np.concatenate([q[:-1], q[1:]], axis=1) for q in c.lines[0].components])
    a, b = P[:, :2], P[:, 2:]
    d = b - a
    n = np.column_stack([-d[:, 1], d[:, 0]]) / np.hypot(d[:, 0], d[:, 1])[:, None]
    m = 0.5 * (a + b)
    F = evaluator(c.field, ["tip_interference"], None)
    k = np.zeros(len(m), int)
    lo, hi = F(m - CONTRACT * tol * n, k), F(m + CONTRACT * tol * n, k)
    both = np.isfinite(lo) & np.isfinite(hi)
    assert np.count_nonzero(both) >= 60
    off = both & ((lo > 0) == (hi > 0))
    assert not off.any(), f"no zero within {CONTRACT} tol of the chords' middles {m[off]}"
