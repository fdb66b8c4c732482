"""Envelope kernel vs the swept-tool oracle (independent code: tool outlines, kinematics and
polygon booleans of its own). The oracle's error must shrink as its roll step shrinks, at the
order its tool shape implies: second order for a rounded cutter tip (smooth scallops), first
order for a sharp cutter corner (a corner's discrete positions)."""
import math

import numpy as np
import pytest

from gearkit.distances import distances_to_polyline
from gearkit.families.involute import GearSpec, tooth_profile
from gearkit.oracles.involute import swept_rack_gear, swept_shaper_gear, tooth_zone_points
from gearkit.families.involute import ShaperCutter


def _oracle_error(spec, step):
    prof = tooth_profile(spec)
    exact = prof.outline(1e-7 * spec.module)
    ra = spec.blank_tip_diameter / 2
    if spec.internal:
        rim = ra + 5 * spec.module
        contours = swept_shaper_gear(spec.teeth, spec.module, spec.cutter_setting, spec.tool, ra, step, internal=True,
                                     rim_radius=rim)
        pts = tooth_zone_points(contours, spec.teeth, ra)
        pts = pts[np.hypot(*pts.T) < rim - 0.1 * spec.module]
    else:
        contours = swept_rack_gear(spec.teeth, spec.module, spec.shift, spec.tool, ra, step,
                                   helix_angle_deg=spec.helix_angle_deg)
        pts = tooth_zone_points(contours, spec.teeth, ra)
    assert len(pts) > 500  # the comparison really covers the flanks, fillets and root
    return float(distances_to_polyline(pts, exact, closed=True).max()) / spec.module


@pytest.mark.parametrize("spec", [GearSpec(13, 1.0, 0.0), GearSpec(13, 1.0, -0.5),
                                  GearSpec(20, 1.0, 0.3, helix_angle_deg=20.0)])
def test_rack_oracle_converges_to_the_envelope_at_second_order(spec):
    coarse, fine = _oracle_error(spec, 0.04), _oracle_error(spec, 0.02)
    order = math.log2(coarse / fine)
    assert order > 1.6  # scallop height ~ step^2
    assert fine < 1e-4  # and the envelope is what it converges to


def test_shaper_oracle_converges_to_the_envelope_at_first_order_for_a_sharp_cutter():
    spec = GearSpec(49, 8.0, 0.52, internal=True, shift_convention="cutter", tool=ShaperCutter(20, addendum=1.3))
    coarse, fine = _oracle_error(spec, 0.32), _oracle_error(spec, 0.16)
    order = math.log2(coarse / fine)
    assert 0.8 < order < 1.3
    assert fine < 1e-3  # a corner's scallops: ~ step/60 at a step of 0.02 m
