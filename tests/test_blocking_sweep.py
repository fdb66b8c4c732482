"""Issue 19: the tip sweep of internal pairs is part of the blocking map -- the same function as the
check's ``tip_interference`` (:func:`~gearkit.pair.sweep.sweep_depth`), on arrays.

Random internal pairs (the ring with its shaper) and points of their window, random and beside the
traced ``tip_interference`` line: the array margin equals the scalar one (the check's function on one
pair), its sign is the check's ``tip_interference`` verdict (where no tooth is pointed), and the region
holds exactly the points
``check_pair`` passes (points within ``CONTRACT tol`` of the region's boundary excepted: the polygons
are exact to that distance). ``contains`` (``--mark``) is ``check_pair``'s verdict itself.
"""
from dataclasses import replace

import numpy as np
import pytest

from gearkit.blocking import blocking_contour
from gearkit.blocking.arrays import margins
from gearkit.blocking.field import PairField
from gearkit.checks import check_pair
from gearkit.distances import distances_to_polyline
from gearkit.errors import SpecError
from gearkit.families.involute import ShaperCutter
from gearkit.pair import PairSpec

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
