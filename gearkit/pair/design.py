"""Design from a given centre distance: the shift sum, and its split between the gears.

The centre distance fixes the working pressure angle and therefore the sum of the thickness
coefficients (textbook 3.113/3.123): external ``Delta_1 + Delta_2 = (z1 + z2)(inv a_wt - inv a_t)``,
internal ``Delta_1 + Delta_2 = (z2 - z1)(inv a_t - inv a_wt)``. For rack-cut gears this is the
familiar ``x_sum = (z2 +- z1)(inv a_wt - inv a_t)/(2 tan a_n)``; for a shaper-cut gear each
``Delta`` is a monotonic function of its ``x`` and is inverted numerically.

Split rules
-----------
``"x1"``
    keep the pinion's ``shift1`` and give the rest to gear 2;
``"equal"``
    equal thickness change on both gears (``x1 = x2`` for rack-cut external gears);
``"balanced"``
    equal ISO specific sliding at the two roots, ``|zeta1(A)| = |zeta2(E)|``.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.curves import inv
from gearkit.errors import SpecError, require
from gearkit.pair.geometry import pair_geometry
from gearkit.pair.spec import PairSpec
from gearkit.pair.tooling import section, thickness_coeff
from gearkit.families.involute import BasicRack

__all__ = ["SPLITS", "shifts_for_center_distance", "thickness_sum_for_center_distance"]

SPLITS = ("x1", "equal", "balanced")
_X_RANGE = (-3.0, 3.0)  # the shifts PairSpec accepts
_XTOL = 1e-14


def thickness_sum_for_center_distance(spec: PairSpec, center_distance: float) -> float:
    """Delta_1 + Delta_2 (transverse, m_t units) of a tight mesh at ``center_distance`` (mm).

    For a rack pair: the pinion's Delta_1 that puts the rack datum at ``center_distance``.
    """
    require(math.isfinite(center_distance) and center_distance > 0, "center_distance",
            f"{center_distance!r} must be a positive length in mm")
    sec = section(spec.module, spec.alpha_n_deg, spec.helix_angle_deg)
    at = sec.alpha_t
    r1 = spec.teeth1 * sec.mt / 2
    if spec.kind == "rack":
        return 2 * (center_distance - r1) * math.tan(at) / sec.mt
    r2 = spec.teeth2 * sec.mt / 2
    internal = spec.kind == "internal"
    base = (r2 - r1 if internal else r1 + r2) * math.cos(at)
    require(center_distance > base, "center_distance",
            f"a_w = {center_distance:.6g} mm must exceed {base:.6g} mm (the base radii "
            f"{'difference' if internal else 'sum'})")
    alpha_w = math.acos(base / center_distance)
    if internal:
        return (spec.teeth2 - spec.teeth1) * (inv(at) - inv(alpha_w))
    return (spec.teeth1 + spec.teeth2) * (inv(alpha_w) - inv(at))


def _inverse_delta(spec: PairSpec, which: int, target: float, field: str) -> float:
    """The shift x of gear ``which`` (1 or 2) whose thickness coefficient is ``target``."""
    from gearkit.roots import brentq
    sec = section(spec.module, spec.alpha_n_deg, spec.helix_angle_deg)
    tool = spec.tools[which - 1]
    z = spec.teeth1 if which == 1 else spec.teeth2
    internal = which == 2 and spec.kind == "internal"
    iso_ring = internal and spec.shift_convention == "iso"
    if isinstance(tool, BasicRack) or iso_ring:  # the shift is the thickness: x = +-Delta / (2 tan a_n)
        x = (-target if iso_ring else target) / (2 * math.tan(sec.alpha_n))
        require(_X_RANGE[0] <= x <= _X_RANGE[1], field, f"the centre distance needs x = {x:.4g}, outside [-3, 3]")
        return x

    sign = -1.0 if internal else 1.0  # the ring's Delta falls as x grows

    def f(x):
        return sign * (thickness_coeff(sec, z, x, tool, internal) - target)

    # the machine mesh needs a_0 > |r_b +- r_b0|: the lowest admissible setting, plus a hair
    lo = -(z + (-1 if internal else 1) * tool.teeth) * (sec.mt / sec.mn) * (1 - math.cos(sec.alpha_t)) / 2
    lo = max(lo + 1e-9, _X_RANGE[0])
    hi = _X_RANGE[1]
    if not f(lo) <= 0 <= f(hi):
        raise SpecError(field, f"no cutter setting x in [{lo:.3g}, {hi:g}] gives the thickness this centre "
                        "distance needs")
    return brentq(f, lo, hi, xtol=_XTOL, rtol=4 * np.finfo(float).eps, maxiter=200)


def _split_x1(spec: PairSpec, total: float, x1: float) -> tuple[float, float]:
    sec = section(spec.module, spec.alpha_n_deg, spec.helix_angle_deg)
    d1 = thickness_coeff(sec, spec.teeth1, x1, spec.tools[0], False)
    return x1, _inverse_delta(spec, 2, total - d1, "shift2")


def _split_equal(spec: PairSpec, total: float) -> tuple[float, float]:
    return _inverse_delta(spec, 1, total / 2, "shift1"), _inverse_delta(spec, 2, total / 2, "shift2")


def _split_balanced(spec: PairSpec, total: float, center_distance: float) -> tuple[float, float]:
    """Pinion shift with |zeta1(A)| = |zeta2(E)| on the nominal tip-to-tip path."""
    from gearkit.roots import brentq

    def imbalance(x1):
        """|zeta1(A)| - |zeta2(E)|; None when an end of the path lies beyond N1 or N2."""
        x2 = _split_x1(spec, total, x1)[1]
        g = pair_geometry(spec.with_shifts(x1, x2, center_distance))
        a, e = g.path["A"], g.path["E"]
        if a <= 0 or (g.kind == "external" and e >= g.line_of_action):
            return None
        return float(abs(g.sliding_at(a)[0]) - abs(g.sliding_at(e)[1]))

    def root(x1):
        value = imbalance(x1)
        if value is None:  # brentq stays inside a bracket of valid designs
            raise SpecError("split", "the balanced split left the admissible designs")
        return value

    # scan for a bracket over designs that exist (both ends inside N1N2: finite sliding)
    values = []
    for x1 in np.linspace(-1.5, 2.5, 81):
        try:
            value = imbalance(x1)
        except SpecError:  # outside the admissible design space for this centre distance
            continue
        if value is not None:
            values.append((x1, value))
    for (xa, fa), (xb, fb) in zip(values, values[1:]):
        if fa == 0:
            return _split_x1(spec, total, xa)
        if fa > 0 > fb or fa < 0 < fb:
            x1 = brentq(root, xa, xb, xtol=_XTOL, rtol=4 * np.finfo(float).eps, maxiter=200)
            return _split_x1(spec, total, x1)
    raise SpecError("split", "no shift split balances the specific sliding at this centre distance "
                    "(both ends must lie inside N1N2); use split 'equal' or 'x1'")


def shifts_for_center_distance(spec: PairSpec, center_distance: float, split: str = "balanced") -> PairSpec:
    """A copy of ``spec`` whose shifts give a tight mesh at ``center_distance``.

    Parameters
    ----------
    spec : PairSpec
        The pair; its ``shift1`` is used by the ``"x1"`` rule, other shifts are replaced.
    center_distance : float, mm
        Operating centre distance a_w (rack pair: pinion axis to rack datum line).
    split : {"x1", "equal", "balanced"}

    Returns
    -------
    PairSpec
        With ``shift1``, ``shift2`` solved and ``center_distance`` set.

    Examples
    --------
    >>> s = shifts_for_center_distance(PairSpec(18, 41, 2.0), 60.0, split="equal")
    >>> round(s.shift1, 6) == round(s.shift2, 6), round(s.shift1 + s.shift2, 6)
    (True, 0.530249)
    """
    require(split in SPLITS, "split", f"{split!r} is not one of {', '.join(SPLITS)}")
    total = thickness_sum_for_center_distance(spec, center_distance)
    if spec.kind == "rack":
        x1 = _inverse_delta(spec, 1, total, "center_distance")
        return spec.with_shifts(x1, 0.0, float(center_distance))
    if split == "x1":
        x1, x2 = _split_x1(spec, total, float(spec.shift1))
    elif split == "equal":
        x1, x2 = _split_equal(spec, total)
    else:
        x1, x2 = _split_balanced(spec, total, float(center_distance))
    return spec.with_shifts(x1, x2, float(center_distance))
