"""Limits of the pair checks, and the textbook's minimum-teeth rules.

Examples
--------
>>> CheckLimits().min_tip_thickness
0.25
>>> round(min_teeth_undercut(BasicRack(), 0.0), 4)
17.0973
"""
from __future__ import annotations

import math
from dataclasses import replace

from gearkit.errors import SpecError, check_fields, require
from gearkit.pair.geometry import pair_geometry
from gearkit.pair.spec import PairSpec
from gearkit.pair.tooling import form_roll, section
from gearkit.families.involute import BasicRack
from gearkit.values import frozen

__all__ = ["CheckLimits", "min_teeth_undercut", "min_tooth_difference", "min_cutter_difference"]


@frozen
class CheckLimits:
    """Thresholds of :func:`~gearkit.checks.check_pair` (module units are normal-module units).

    Parameters
    ----------
    min_tip_thickness : float
        Warn when the normal tip thickness s_an < this * m_n (fail at s_an <= 0). The textbook asks
        0.2; 0.25 and 0.4 (hardened teeth) are common.
    min_contact_ratio : float
        Warn when eps_alpha < this (fail below 1).
    min_tip_clearance : float
        Warn when a tip clearance c < this * m_n (fail below 0).
    """

    min_tip_thickness: float = 0.25
    min_contact_ratio: float = 1.2
    min_tip_clearance: float = 0.1

    def __post_init__(self):
        check_fields(self)
        require(math.isfinite(self.min_tip_thickness) and 0.0 <= self.min_tip_thickness <= 2.0,
                "min_tip_thickness", f"{self.min_tip_thickness!r} must be in [0, 2] (module units)")
        require(math.isfinite(self.min_contact_ratio) and 1.0 <= self.min_contact_ratio <= 3.0,
                "min_contact_ratio", f"{self.min_contact_ratio!r} must be in [1, 3]")
        require(math.isfinite(self.min_tip_clearance) and 0.0 <= self.min_tip_clearance <= 1.0,
                "min_tip_clearance", f"{self.min_tip_clearance!r} must be in [0, 1] (module units)")


def min_teeth_undercut(tool, shift: float, module: float = 1.0, pressure_angle_deg: float | None = None,
                       helix_angle_deg: float = 0.0) -> float:
    """Smallest tooth number (real) that the tool cuts without undercut at normal shift ``shift``.

    Rack (textbook 3.104/3.105 with shift): ``z_min = 2 (h_s - x) cos(beta) / sin^2(alpha_t)``, ``h_s``
    the rack's straight-flank height. Shaper: the root of ``rho_l(z) = 0`` (the involute reaches
    the base circle), found numerically; 3 when every tooth number from 3 is free of undercut.
    """
    from gearkit.roots import brentq
    alpha = tool.pressure_angle_deg if pressure_angle_deg is None else pressure_angle_deg
    sec = section(module, alpha, helix_angle_deg)
    if isinstance(tool, BasicRack):
        return 2 * (tool.straight_height - shift) * math.cos(sec.beta) / math.sin(sec.alpha_t) ** 2

    def rho(z):
        return form_roll(sec, z, shift, tool, False)

    if rho(3.0) >= 0:
        return 3.0
    hi = 3.0
    while rho(hi) < 0:
        hi *= 2
        if hi > 1e6:
            raise SpecError("shift1", f"x = {shift}: the shaper undercuts every tooth number")
    return brentq(rho, hi / 2 if hi > 3.0 else 3.0, hi, xtol=1e-12)


def _jams(spec: PairSpec) -> bool:
    from gearkit.pair.internal import exit_jamming_margin  # internal pairs only: loaded when one asks

    return exit_jamming_margin(pair_geometry(spec)) < 0


def min_tooth_difference(spec: PairSpec) -> int | None:
    """(z_p)min: the smallest ``z2 - z1`` free of exit jamming, with z2, the shifts and tools of ``spec``.

    The pair's own tooth difference is tried as the pair is (its tips and centre distance: the
    geometry that is checked and exported); other differences with the tips of the tip rule at the
    tight mesh. So the pair's own difference passes exactly when its exit-jamming check passes.
    None when no pinion of 3 or more teeth avoids it.
    """
    for k in range(1, spec.teeth2 - 2):
        try:
            trial = spec if k == spec.teeth2 - spec.teeth1 else replace(
                spec, teeth1=spec.teeth2 - k, tip_diameter1=None, tip_diameter2=None, center_distance=None)
            if not _jams(trial):
                return k
        except SpecError:  # no mesh exists for this tooth difference: try a larger one
            continue
    return None


def min_cutter_difference(spec: PairSpec) -> int | None:
    """(z_pc)min: the smallest ``z2 - z0`` at which the shaper plunges without trimming the ring.

    The ring (z2, its shift and tip) is kept and the shaper's tooth number varied (textbook
    3.108). None when even the smallest admissible shaper (6 teeth) trims.
    """
    from gearkit.pair.internal import plunge_trimming  # internal pairs only: loaded when one asks

    cutter = spec.tools[1]
    g = pair_geometry(spec)
    tip2 = g.gears[1].tip_diameter
    for z0 in range(spec.teeth2 - 4, 5, -1):  # a shaper needs z0 <= z2 - 4
        try:
            trial = replace(spec, tool2=replace(cutter, teeth=z0), tip_diameter2=tip2)
            trial_g = pair_geometry(trial)
        except SpecError:  # this shaper cannot cut the ring at all: a smaller one may
            continue
        if plunge_trimming(trial_g)[0] > 0:
            return spec.teeth2 - z0
    return None
