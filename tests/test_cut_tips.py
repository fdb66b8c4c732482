"""Issue 20, class 2 for internal pairs: the tip a pair check grades is never larger than the tip its
cutter can cut -- and the blocking map grades the same tip (issue 19: the region is the map of the check).

An internal pair's tip shortening ``dy`` is negative where the centre distance exceeds ``a + (x2 - x1) m``:
the blank tips grow by ``-dy m``. Beyond ``h_fP* - h_a*`` (0.25 with the default tools) they would reach past
what the tools leave: a rack cuts a pinion's blank down to its root line ``r + (x + h_fP*) m``, a shaper
an external gear to ``a_0 - r_f0`` and a ring (its inner tip) up to ``a_0 + r_f0``. The long fuzz run found 19
such internal pairs (checked pinion tips up to 0.25 m beyond the cut one).

Oracle: the tip measured on the generated tooth (the largest radius of its points, for a ring the
smallest), and for the issue's pair the closed forms by hand.
"""
from dataclasses import replace

import numpy as np
import pytest

from gearkit.blocking.arrays import margins
from gearkit.blocking.field import PairField
from gearkit.checks import check_pair
from gearkit.errors import SpecError
from gearkit.families.involute import GearSpec, ShaperCutter, tooth_profile
from gearkit.pair import PairSpec, pair_geometry
from gearkit.pair.geometry import gear_specs

MEASURE = 1e-6  #: (m_n) the tooth's points lie within this of the generated tooth (its tol), so the
#: measured tip is within it of the exact one

REPRODUCERS = [
    # the issue's pair: pinion blank 3184.834 mm, cut 3184.014 mm; ring blank 5763.698 mm, cut 5764.518 mm
    PairSpec(56, 112, 52.644, kind="internal", shift1=0.991, tool2=ShaperCutter(31)),
    # helical, an 8-tooth shaper, dy = -0.340
    PairSpec(67, 104, 1.0, 0.425, -0.401, kind="internal", helix_angle_deg=15.0, tool2=ShaperCutter(8)),
    # helical, opened centre distance, dy = -0.328
    PairSpec(71, 131, 1.0, -0.48, 0.909, kind="internal", helix_angle_deg=15.0, tool2=ShaperCutter(11),
             center_distance=32.1188),
    # a shaper-cut pinion (its tip cut down to a_0 - r_f0), dy = -0.287 at x2 = 0.9
    PairSpec(46, 49, 1.0, 0.0, 0.9, kind="internal", shift_convention="cutter",
             tool1=ShaperCutter(20, addendum=1.3), tool2=ShaperCutter(20, addendum=1.3)),
]


def _measured_tip(gspec) -> float:
    """The tip diameter of the generated tooth, read off its points (largest radius; a ring's smallest)."""
    prof = tooth_profile(gspec)
    r = np.hypot(*prof.tooth_points(MEASURE * gspec.module).T)
    return 2 * float(r.min() if gspec.internal else r.max())


@pytest.mark.parametrize("spec", REPRODUCERS)
def test_checked_tip_is_the_cut_tip(spec):
    """Each gear's graded tip is the generated gear's own (measured): never beyond it, for the ring never
    inside it; the pinion's blank by the pair's rule would have been larger (the cap is what acts)."""
    res = check_pair(spec)
    g = res.geometry
    assert g.tip_shortening_coeff < -0.25
    blank1 = g.gears[0].reference_diameter + 2 * spec.module * (spec.addendum + spec.shift1
                                                                - g.tip_shortening_coeff)
    assert blank1 > g.gears[0].tip_diameter + 1e-3 * spec.module
    for gear, gspec in zip(g.gears, gear_specs(spec)):
        assert gear.tip_diameter == pytest.approx(_measured_tip(gspec), abs=2 * MEASURE * spec.module)


def test_the_issue_pair_by_hand():
    """56/112, m = 52.644, x1 = 0.991, z0 = 31: pinion r + (x1 + h_fP*) m = 1474.032 + 2.241 m; ring
    a_0 + r_f0 = 81 m / 2 + (31 / 2 - 1.25) m; both pass the check (it failed nothing before either, but
    graded 3184.834 / 5763.698)."""
    spec = REPRODUCERS[0]
    m = 52.644
    res = check_pair(spec)
    d1, d2 = (gear.tip_diameter for gear in res.geometry.gears)
    assert d1 == pytest.approx(2 * (28 * m + 2.241 * m), abs=1e-9)
    assert d2 == pytest.approx(2 * (40.5 * m + 14.25 * m), abs=1e-9)
    assert [p.tip_diameter for p in res.profiles] == pytest.approx([d1, d2], abs=1e-9)


def test_a_given_tip_beyond_the_tool_is_cut_down():
    """A tip diameter given beyond the rack's root line is graded where the rack leaves it."""
    spec = PairSpec(20, 40, 2.0, tip_diameter1=46.0)  # the rack leaves r + 1.25 m = 22.5 mm
    g = pair_geometry(spec)
    assert g.gears[0].tip_diameter == pytest.approx(45.0, abs=1e-12)
    assert _measured_tip(GearSpec(20, 2.0, tip_diameter=46.0)) == pytest.approx(45.0, abs=2 * MEASURE * 2.0)


def test_the_blocking_arrays_grade_the_same_tip():
    """The blocking map's margins (arrays) equal the check's formulas (scalar) where the cap acts: the
    56/112 ring pair along x1 - x2 = 1 (dy < -0.25 near the edge of the pairs that mesh)."""
    spec = PairSpec(56, 112, 1.0, kind="internal", tool2=ShaperCutter(31))
    f = PairField(spec)
    rng = np.random.default_rng(20)
    x1 = rng.uniform(0.3, 1.8, 40)
    x2 = x1 - rng.uniform(0.95, 1.05, 40)
    capped = 0
    for a, b in zip(x1, x2):
        try:
            g = pair_geometry(replace(f.template, shift1=float(a), shift2=float(b)))
        except SpecError:  # no mesh at these shifts: NaN in both (compared below)
            continue
        capped += g.gears[0].tip_diameter < g.gears[0].reference_diameter + 2 * (1 + a - g.tip_shortening_coeff) - 1e-9
    assert capped >= 10
    names = [d.name for d in f.lines]
    vec = margins(f, x1, x2, names)
    for n in names:
        sc = np.array([f.margin(n, a, b) for a, b in zip(x1, x2)])
        both = np.isfinite(sc) & np.isfinite(vec[n])
        assert both.sum() >= 20, n
        assert np.allclose(vec[n][both], sc[both], rtol=1e-9, atol=1e-11), n
