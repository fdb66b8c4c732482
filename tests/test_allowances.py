"""Tooth thickness allowances (ISO 21771): the tool is fed in, the generating shift x_E moves the root and
the form circle; backlash ranges; inspection dimensions at the allowances."""
import math

import pytest

from gearkit.families.involute import GearSpec, tooth_profile
from gearkit.pair import PairSpec, pair_geometry

EXACT = 1e-9  # mm: closed forms of the same quantity
GEN = 1e-7    # mm: a generated circle against its closed form (the envelope is exact to ~1e-9 m)
A20 = math.radians(20.0)


def test_root_moves_with_the_allowance_as_iso_21771_says():
    # z = 30, m = 1, allowance 0.06 mm: x_E = -0.06 / (2 tan 20) = -0.082424, d_f = 30 - 2.5 + 2 x_E = 27.335
    spec = GearSpec(30, 1.0, thinning=0.06)
    x_e = -0.06 / (2 * math.tan(A20))
    assert spec.generating_shift == pytest.approx(x_e, abs=EXACT)
    prof = tooth_profile(spec)
    assert round(prof.root_diameter, 3) == 27.335
    assert prof.root_diameter == pytest.approx(30 - 2 * 1.25 + 2 * x_e, abs=GEN)
    assert prof.tip_diameter == pytest.approx(32.0, abs=GEN)          # the tip stays at the nominal shift
    assert prof.tooth_thickness == pytest.approx(math.pi / 2 - 0.06, abs=GEN)
    # the form circle is that of a gear cut at x_E: the involute starts where the rack's straight flank ends
    rb = 15 * math.cos(A20)
    roll = 15 * math.sin(A20) - (1.25 - 0.379951 * (1 - math.sin(A20)) - x_e) / math.sin(A20)
    assert prof.form_diameter == pytest.approx(2 * math.hypot(rb, roll), abs=1e-5)
    # the pair geometry agrees: the root of a thinned gear is that of x_E
    g = pair_geometry(PairSpec(30, 40, 1.0, thinning1=0.06))
    assert g.gears[0].root_diameter == pytest.approx(prof.root_diameter, abs=GEN)
