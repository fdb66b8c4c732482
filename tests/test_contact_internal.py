"""Contact analysis of internal pairs: the textbook example, and secondary tip interference at small
tooth differences on both sides of the pair check's threshold (reference digest 1.10, 3.2, 3.3).

``SIDE = 1e-3`` (in x2), as in the pair check's own tests: far above the threshold's root-solver
accuracy, and the depth it makes (~1e-3 m) is far above the interference threshold (the pair
check's 1e-4 m).
"""
import pytest
from scipy.optimize import brentq

from gearkit.checks import check_pair
from gearkit.pair.internal import exit_jamming_margin
from gearkit.contact import analyse_pair
from gearkit.pair import PairSpec, pair_geometry
from gearkit.families.involute import ShaperCutter

SIDE = 1e-3
EPS_TOL = 1e-3
SHAPER = ShaperCutter(20, addendum=1.3)  # medium-worn shaper, x_c = 0.3 (digest 3.2)
STEPS = 32


def test_textbook_internal_example_meshes_cleanly():
    """Digest 3.2: z = 46/49, m = 8, x2 = 0.52, both gears shaper-cut: eps = 1.9245 (the ring's tip
    trimmed by its shaper, digest 3.110), no interference, zero backlash."""
    spec = PairSpec(46, 49, 8.0, 0.0, 0.52, kind="internal", shift_convention="cutter", tool1=SHAPER, tool2=SHAPER)
    g = pair_geometry(spec)
    res = analyse_pair(spec, STEPS)
    assert not res.interference.found
    assert res.contact_ratio == pytest.approx(g.contact_ratio, abs=EPS_TOL)
    assert abs(res.backlash) <= 1e-9 * 8.0
    assert res.transmission_error_max * g.gears[1].base_diameter / 2 <= 1e-9 * 8.0


def _pair(x2):
    """46/49 with a rack-cut pinion (x1 = 0.3): its tip-fillet limit (x2 ~ 0.51) lies below the exit
    jamming limit (x2 ~ 0.61), so near the latter only the secondary tip interference changes."""
    return PairSpec(46, 49, 1.0, 0.3, x2, kind="internal", shift_convention="cutter", tool2=SHAPER)


def test_secondary_tip_interference_on_both_sides_of_the_pair_check_threshold():
    """Issue item 4: with too small a tooth difference (z2 - z1 = 3 < (z_p)min) the tips collide as the
    teeth leave mesh. Just below the pair check's exit-jamming threshold the simulation finds the
    tip interference the check predicts (exit_jamming and tip_interference fail); just above it,
    nothing deeper than the check's threshold (1e-4 m)."""
    x_star = brentq(lambda x: exit_jamming_margin(pair_geometry(_pair(x))), 0.5, 0.7, xtol=1e-12)
    below, above = _pair(x_star - SIDE), _pair(x_star + SIDE)
    rep_below, rep_above = check_pair(below).report, check_pair(above).report
    assert (rep_below["exit_jamming"].status, rep_above["exit_jamming"].status) == ("fail", "ok")
    assert (rep_below["tip_interference"].status, rep_above["tip_interference"].status) == ("fail", "ok")
    assert rep_below["interference.1"].status == rep_above["interference.1"].status == "ok"

    res = analyse_pair(below, STEPS)
    assert res.interference.found
    assert "tip" in res.interference.where
    tip = next(e for e in res.interference.events if e["kind"] == "tip")
    assert "tip" in (tip["driver_feature"], tip["mate_feature"])
    # far from the path of contact (the mesh is at the top, near +y): the secondary interference
    assert tip["point"][1] < 0.5 * res.mesh.pitch_point[1]
    assert res.interference.max_depth > 10 * res.interference_tol

    clean = analyse_pair(above, STEPS)
    assert not clean.interference.found
    assert clean.contact_ratio == pytest.approx(pair_geometry(above).contact_ratio, abs=EPS_TOL)


def test_ring_driving_its_pinion():
    """The ring as driver (kind ring-driver): the same mesh seen from the other gear."""
    from gearkit.contact import Mesh, simulate, pair_mesh

    spec = _pair(0.65)
    forward = pair_mesh(spec)
    back = simulate(Mesh(forward.gear2, forward.gear1, forward.a), STEPS)
    assert back.mesh.kind == "ring-driver"
    assert back.contact_ratio == pytest.approx(pair_geometry(spec).contact_ratio, abs=EPS_TOL)
    assert not back.interference.found
