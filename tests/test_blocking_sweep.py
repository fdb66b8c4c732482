"""Issue 19: the tip sweep of internal pairs is part of the blocking map -- the same function as the
check's ``tip_interference`` (:func:`~gearkit.pair.sweep.sweep_depth`), on arrays.

Random internal pairs (the ring with its shaper) and points of their window, random and beside the
traced ``tip_interference`` line: the array margin equals the scalar one (the check's function on one
pair), its sign is the check's ``tip_interference`` verdict (where no tooth is pointed), and the region
holds exactly the points
``check_pair`` passes (points within ``CONTRACT tol`` of the region's boundary excepted: the polygons
are exact to that distance). ``contains`` (``--mark``) is ``check_pair``'s verdict itself.

At the fine tolerance the sweep must be exact near its zero: its maximum (a kink of a corner's depth)
against a brute-force sweep refined to round-off (``sweeporacle``), and the traced line against
brentq's zeros of the margin on columns.
"""
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import brentq

from gearkit.blocking import blocking_contour
from gearkit.blocking.arrays import margins
from gearkit.blocking.field import PairField
from gearkit.checks import check_pair
from gearkit.distances import distances_to_polyline
from gearkit.errors import SpecError
from gearkit.families.involute import ShaperCutter
from gearkit.pair import PairSpec
from gearkit.pair.internal import SWEEP_RESOLUTION

from edgezeros import row_crossings
from sweeporacle import brute_maximum

TOL = 1e-3
CONTRACT = 2.0
BESIDE = (-4e-3, 4e-3, -2e-2, 2e-2)  #: offsets along the tip line's normal (shift units): beyond 2 tol


def _pairs():
    rng = np.random.default_rng(2019)
    out = [PairSpec(46, 49, 1.0, kind="internal", tool2=ShaperCutter(20))]  # the README's internal pair
    while len(out) < 3:
        z1 = int(rng.integers(12, 50))
        z2 = z1 + int(rng.integers(3, 40))
        out.append(PairSpec(z1, z2, 1.0, kind="internal", tool2=ShaperCutter(int(rng.integers(12, min(40, z2 - 5))))))
    return out


def _beside(contour, rng, per_component: int = 3):
    """Points beside the traced tip-interference line: vertices moved along the line's normal."""
    out = []
    for comp in contour.line("tip_interference").components:
        if len(comp) < 2:
            continue
        for i in rng.integers(0, len(comp) - 1, per_component):
            d = comp[i + 1] - comp[i]
            n = np.array([-d[1], d[0]]) / np.hypot(*d)
            out += [comp[i] + s * n for s in BESIDE]
    return np.array(out).reshape(-1, 2)


@pytest.mark.parametrize("spec", _pairs(), ids=lambda s: f"{s.teeth1}/{s.teeth2} z0={s.tools[1].teeth}")
def test_the_region_holds_the_tip_sweep(spec):
    rng = np.random.default_rng(spec.teeth1 * 1000 + spec.teeth2)
    c = blocking_contour(spec, tol=TOL, lines=["tip_interference"])
    assert "tip_interference" in c.field.hard
    w = c.window
    pts = np.vstack([np.column_stack([rng.uniform(w[0], w[1], 6), rng.uniform(w[2], w[3], 6)]), _beside(c, rng)])
    pts = pts[(pts[:, 0] >= w[0]) & (pts[:, 0] <= w[1]) & (pts[:, 1] >= w[2]) & (pts[:, 1] <= w[3])]
    assert len(pts) >= 12
    exact = PairField(spec)  # the check's own (generated) form circles
    vec = margins(exact, pts[:, 0], pts[:, 1], ["tip_interference"])["tip_interference"]
    inside = c.in_region(pts[:, 0], pts[:, 1])
    swept = 0
    for p, v, r in zip(pts, vec, inside):
        try:
            rep = check_pair(replace(spec, shift1=float(p[0]), shift2=float(p[1]))).report
        except SpecError:  # no pair here: the map has no margin either
            assert np.isnan(v) and not c.contains(*p)
            continue
        scalar = exact.margin("tip_interference", *p)
        assert v == pytest.approx(scalar, rel=1e-9, abs=1e-11)  # arrays: the same function
        if "fail" not in (rep["pointing.1"].status, rep["pointing.2"].status):
            # the check's verdict (a pointed tooth, outside the region by its pointing line, is swept
            # by the check at its point, by the map at its blank's tip)
            assert (v < 0) == (rep["tip_interference"].status == "fail")
            swept += 1
        assert c.contains(*p) == rep.ok
        if r != rep.ok:
            d = min(distances_to_polyline(p[None], q)[0] for q in c.region)
            assert d <= CONTRACT * TOL, (p, rep.ok)
    assert swept >= 6


FINE = 1e-7  #: the fine tolerance
ROUNDOFF = 1e-12  #: (mm) two computations of one corner's depth: a few hundred ulps of the radii (~50 mm)
KINKED = PairSpec(25, 94, 1.0, kind="internal", tool2=ShaperCutter(24))
KINKED_ROW = (np.linspace(-1.2969823, -1.2969819, 5), 0.00641)  #: 1e-7 apart, ~1 FINE below the line
KINKED_WINDOW = (-1.2971, -1.2968, 0.0062, 0.0066)  #: the line (slope ~0.3) crosses it left to right
ROW_SAMPLES = 41


def test_the_sweep_climbs_to_a_kinked_maximum_beyond_its_bracket():
    """25/94 z0 24 near (-1.29698, 0.00641): the deepest corner's depth over the pinion angle is a kink
    (slopes +5.4 and -1.3 mm/rad), the branch and bound's deepest sample 3.3 of its half widths from it;
    the zoom, kept to the bracket around that sample, stopped at the bracket's end and read the margin
    up to 2.6e-7 (2.6 FINE) above its value, on thin spikes 3e-7 wide in x1 which the contour's line
    ran through (58 FINE off). The margin of the map equals the brute-force sweep's to round-off."""
    field = PairField(KINKED)
    x1, x2 = KINKED_ROW
    got = margins(field, x1, np.full(x1.shape, x2), ["tip_interference"])["tip_interference"]
    for x, m in zip(x1, got):
        depth, below = brute_maximum(field.point(x, x2).geometry((True, False)))
        assert abs(m - (SWEEP_RESOLUTION - depth / KINKED.module)) <= below + ROUNDOFF, x


def test_the_fine_tip_line_follows_the_kinked_sweep():
    """The same place at tol 1e-7 in a window: on rows across the line (sampled evenly and 1e-7 apart
    across the spike) every crossing of the traced line within 2 FINE of a brentq zero of the field's
    scalar margin and every zero with one (on the old sweep the spike's zeros were not traced)."""
    field = PairField(KINKED)
    c = blocking_contour(KINKED, tol=FINE, window=KINKED_WINDOW, lines=["tip_interference"])
    comps = c.line("tip_interference").components
    lo, hi = KINKED_WINDOW[:2]
    xs = np.union1d(np.linspace(lo, hi, ROW_SAMPLES), KINKED_ROW[0])
    for y in np.union1d(np.linspace(0.0064, 0.00647, 5), KINKED_ROW[1]):
        def f(x):
            return field.margin("tip_interference", x, y)
        v = np.array([f(x) for x in xs])
        zeros = [brentq(f, xs[i], xs[i + 1], xtol=1e-15, rtol=1e-15)
                 for i in np.flatnonzero((v[:-1] > 0) != (v[1:] > 0))]
        got = row_crossings(comps, y, lo, hi)
        assert len(zeros) >= 1, y
        for x in got:
            assert min(abs(x - z) for z in zeros) <= CONTRACT * FINE, (y, x, zeros)
        for z in zeros:
            assert got and min(abs(x - z) for x in got) <= CONTRACT * FINE, (y, z, got)
