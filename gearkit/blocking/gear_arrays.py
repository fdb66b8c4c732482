"""Per-gear closed forms of the machine mesh on arrays of shifts, for :mod:`gearkit.blocking.arrays`.

The array forms of :func:`~gearkit.pair.tooling.thickness_coeff`, :func:`~gearkit.pair.tooling.root_radius`,
:func:`~gearkit.pair.tooling.form_roll` and :func:`~gearkit.families.involute.ring_cutter_setting`
(the tests hold them equal to the scalar ones through the blocking margins), and the roll length of
each gear's form circle as the check reads it (:func:`form_roll_lengths`: generated where undercut).

>>> import numpy as np
>>> from gearkit.curves import inv
>>> a = inv_inverse(np.array([inv(0.3), inv(0.5)]))
>>> np.allclose(a, [0.3, 0.5], rtol=0, atol=1e-14)
True
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.curves import SERIES_LIMIT, inv, inv_series
from gearkit.families.involute.tools import BasicRack
from gearkit.pair.tooling import cutter_radii

__all__ = ["inv_inverse", "gear_forms", "ring_settings", "form_roll_lengths", "PairScalars", "half_angles",
           "rack_forms"]

NEWTON = 12  #: most Newton steps of the inverse involute (quadratic from the start: 4 to 6 suffice)
SERIES_BELOW = 0.1  #: no iterate falls below this angle (rad) unless v < inv of it: only then are the angles
#: below ``SERIES_LIMIT`` (0.05) given :func:`~gearkit.curves.inv`'s series (elsewhere ``inv a`` is ``tan a - a``,
#: read off the tangent the Newton step has anyway)
_INV_SERIES_BELOW = inv(SERIES_BELOW)
NEWTON_DONE = 1e-13  #: a Newton step of inv_inverse below this fraction of the angle ends it
_ZERO = np.asarray(0.0)  #: (0-d: see :class:`PairScalars`)
HEIGHTS_KEPT = 64  #: racks whose straight-flank height is remembered (each kept alive: its id stays its own)
_HEIGHTS: dict = {}


def inv_inverse(v):
    """The angle ``a`` with ``inv a = v`` (v > 0), arrays: Newton from the right of the root, where
    ``inv`` is convex (the iterates fall monotonically), stopping at round-off: where the step is
    below ``NEWTON_DONE`` a (Newton converges quadratically: the next step would be below 1e-25 a;
    near a = 0.1 rad tan a - a cancels and the steps stall at 1e-14 a), or no longer halves. Where
    ``v`` is not positive (no pair) the result is garbage the caller masks; it does not hold the
    iteration up. Each angle stops on its own: the result does not depend on the others in the array.

    >>> from gearkit.curves import inv
    >>> v = np.geomspace(1e-12, 0.5, 400)
    >>> bool(np.max(np.abs(inv(inv_inverse(v)) - v) / v) < 1e-12)
    True
    """
    v = np.asarray(v, dtype=float)
    if not v.ndim:
        return inv_inverse(v.reshape(1)).reshape(())
    with np.errstate(invalid="ignore"):
        a = np.minimum(np.cbrt(3.0 * v), np.arctan(v + np.pi / 2.0))
        # the iterates fall to the root from the right: none falls below SERIES_BELOW where every value is above its inv
        series = bool(np.count_nonzero(v < _INV_SERIES_BELOW))  # (count_nonzero: one C call; .any() wraps one)
        going = v > 0
        half = np.inf  # half the last step's size (none yet)
        for _ in range(NEWTON):  # (in place where an array is new: each step the same roundings, fewer numpy calls)
            t = np.tan(a)
            f = t - a
            if series:  # inv's series at the small angles alone (f is tan a - a elsewhere), those still going
                small = ((np.abs(a) < SERIES_LIMIT) & going).nonzero()[0]  # (a stopped angle's f is not read)
                if small.size:
                    f[small] = inv_series(a[small])
            f -= v
            t *= t
            step = np.divide(f, t, out=f)
            np.subtract(a, step, out=a, where=going)  # an angle that has stopped stays: each its own iterates, however
            size = np.abs(step, out=step)  # many share the array (the same angle alone or among others, to the bit)
            going &= (size > NEWTON_DONE * a) & (size < half)
            if not np.count_nonzero(going):
                break
            half = np.multiply(size, 0.5, out=size)
    return a


def _straight_height(tool) -> float:
    """The rack's straight-flank height (module units; a property worked out afresh on every read),
    remembered by the rack object itself (an equal rack made anew is compared field by field)."""
    hit = _HEIGHTS.get(id(tool))
    if hit is None or hit[0] is not tool:
        if len(_HEIGHTS) >= HEIGHTS_KEPT:
            _HEIGHTS.clear()
        hit = _HEIGHTS[id(tool)] = (tool, tool.straight_height)
    return hit[1]


class PairScalars:
    """The scalars of a field's pair formulas (:class:`~gearkit.blocking.pair_arrays.PairArrays`), worked out once:
    those the formulas combine with arrays are kept as 0-d arrays (``np.asarray(v)``): numpy combines an
    array with a 0-d float64 array in about half the time it takes with a Python float, which it converts
    on every call; each operation is the same IEEE one either way, to the bit. ``rack1``, ``rack2``: a rack
    tool's closed forms (:func:`gear_forms`), None for a shaper."""

    def __init__(self, field):
        t, sec = field.template, field._sec
        mn, mt, at = sec.mn, sec.mt, sec.alpha_t
        c = np.asarray
        self.z1, self.z2 = z1, z2 = t.teeth1, t.teeth2
        self.r1, self.r2 = r1, r2 = z1 * mt / 2, z2 * mt / 2
        self.rb1, self.rb2 = rb1, rb2 = r1 * math.cos(at), r2 * math.cos(at)
        k_e = 2 * mn * math.tan(sec.alpha_n)
        self.thin1, self.thin2 = c(t.thinning1 / k_e), c(t.thinning2 / k_e)  # (read where the thinning is not +0)
        self.inv_at = inv(at)
        if field.internal:
            self.base, self.a_ref, self.z_sum = rb2 - rb1, r2 - r1, c(float(z2 - z1))
        else:
            self.base, self.a_ref, self.z_sum = rb1 + rb2, r1 + r2, c(float(z1 + z2))
        self.base_min = c(self.base * (1 + 1e-12))
        self.c_base, self.c_a_ref, self.c_inv_at = c(self.base), c(self.a_ref), c(self.inv_at)
        self.mn, self.c_r1, self.c_r2, self.ha = c(mn), c(r1), c(r2), c(t.addendum)
        self.rb1_sq, self.rb2_sq = c(rb1 ** 2), c(rb2 ** 2)
        self.p_bt = p_bt = math.pi * mt * math.cos(at)
        self.c_p_bt = c(p_bt)
        self.tiny, self.one, self.zero, self.nan = c(1e-9), c(1.0), c(0.0), c(np.nan)
        self.minus_one, self.inf = c(-1.0), c(np.inf)
        # a gear without thinning (+0): x and d as they are (x - 0.0 is x to the bit; - -0.0 turns -0.0 to +0.0)
        self.plain1, self.plain2 = (th == 0 and math.copysign(1.0, th) > 0 for th in (t.thinning1, t.thinning2))
        # half_angle's scalars: pi / 2, each gear's base radius as it works it out, and its teeth
        self.half_pi, self.half_rb = c(math.pi / 2), (c(z1 * mt * math.cos(at) / 2), c(z2 * mt * math.cos(at) / 2))
        self.c_z = (c(float(z1)), c(float(z2)))
        self.rack1, self.rack2 = (self._rack(sec, z, tool) if isinstance(tool, BasicRack) else None
                                  for z, tool in ((z1, field._tools[0]), (z2, field._tools[1])))

    @staticmethod
    def _rack(sec, z, tool):
        """(tan a_n, r, dedendum, r sin a_t, straight-flank height, sin a_t, the tip the rack leaves at x = 0)."""
        r, s, mn = z * sec.mt / 2, math.sin(sec.alpha_t), sec.mn
        return tuple(np.asarray(v) for v in (math.tan(sec.alpha_n), r, tool.dedendum, r * s, _straight_height(tool),
                                              s, z * sec.mt / 2))


def half_angles(k, which, delta, radius, internal):
    """:func:`~gearkit.pair.tooling.half_angle` of gear ``which`` at the radii ``radius`` (an array), with
    the scalars of :class:`PairScalars` (``k``): each operation as there (``inv`` as :func:`~gearkit.curves.inv`
    takes it; the caller holds an errstate that ignores invalid values)."""
    ay = np.arccos(np.minimum(np.maximum(k.half_rb[which - 1] / radius, k.minus_one), k.one))
    inv_ay = np.tan(ay) - ay
    small = (np.abs(ay) < SERIES_LIMIT).nonzero()[0]
    if small.size:
        inv_ay[small] = inv_series(ay[small])
    d = k.c_inv_at - inv_ay
    return (k.half_pi + delta) / k.c_z[which - 1] + (np.negative(d) if internal else d)


def rack_forms(x, k, rack):
    """:func:`gear_forms` of a rack-cut gear at shifts ``x`` (array), with the scalars of :class:`PairScalars`
    (``k``; ``rack``: its ``rack1`` or ``rack2``): each operation as :func:`gear_forms` does it."""
    tan_n, r, ded, rs, height, s, _ = rack
    mn = k.mn
    return (x + x) * tan_n, r + (x - ded) * mn, rs - (height - x) * mn / s, None


def gear_forms(sec, z, x, tool, internal):
    """Per-gear closed forms at shifts ``x`` (array): (Delta, r_f, rho_l, a_0 or None), NaN where no mesh."""
    mt, mn = sec.mt, sec.mn
    if isinstance(tool, BasicRack):
        r = z * mt / 2
        s = math.sin(sec.alpha_t)
        delta = 2 * x * math.tan(sec.alpha_n)
        rf = r + (x - tool.dedendum) * mn
        rho = r * s - (_straight_height(tool) - x) * mn / s
        return delta, rf, rho, None
    z0 = tool.teeth
    sign = -1 if internal else 1
    a0 = mt * (z + sign * z0) / 2 + x * mn
    rb = z * mt * math.cos(sec.alpha_t) / 2
    rb0, ra0, rc0 = cutter_radii(sec, tool)
    ok = a0 > abs(rb + sign * rb0)
    a0 = np.where(ok, a0, np.nan)
    with np.errstate(invalid="ignore"):
        alpha_c = np.arccos((rb + sign * rb0) / a0)
    d0 = 2 * tool.shift * math.tan(sec.alpha_n)
    if internal:
        delta = (z - z0) * (inv(sec.alpha_t) - inv(alpha_c)) - d0
    else:
        delta = (z + z0) * (inv(alpha_c) - inv(sec.alpha_t)) - d0
    rf = a0 + ra0 if internal else a0 - ra0
    cutter_roll = math.sqrt(max(rc0 ** 2 - rb0 ** 2, 0.0))
    along = a0 * np.sin(alpha_c)
    rho = along + cutter_roll if internal else along - cutter_roll
    return delta, rf, rho, a0


def ring_settings(sec, t, x):
    """:func:`~gearkit.families.involute.ring_cutter_setting` at ISO ring shifts ``x`` (array): the
    shaper's radial setting, NaN where no setting cuts a tooth that thick."""
    cutter = t.tools[1]
    dz = t.teeth2 - cutter.teeth
    an = math.radians(cutter.pressure_angle_deg)
    at = math.atan(math.tan(an) / math.cos(sec.beta))
    value = inv(at) + 2 * (x - cutter.shift) * math.tan(an) / dz
    ok = value > 0
    ac = inv_inverse(np.where(ok, value, 1.0))
    return np.where(ok, dz / (2 * math.cos(sec.beta)) * (math.cos(at) / np.cos(ac) - 1.0), np.nan)


def form_roll_lengths(field, which, x, rho_l, rb):
    """Roll length of the form circle (mm) of gear ``which`` of ``field`` (a
    :class:`~gearkit.blocking.field.PairField`) at shifts ``x``, from the closed-form roll lengths
    ``rho_l``: the closed form where the gear is not undercut, the generated one where it is (the
    field's interpolant inside its range, the generated gear outside it), NaN where no gear exists."""
    rho = np.maximum(rho_l, _ZERO)
    if which == 2 and field.internal:
        return rho
    idx = (rho_l < _ZERO).nonzero()[0]  # (rho_l is 1-d)
    if not idx.size:
        return rho
    fit = field.form_interpolant(which) if field.x_ranges is not None else None
    xs = x[idx]
    r = np.full(xs.shape, np.nan)
    if fit is not None:  # the interpolant's roll length itself (read off d_F it loses 2e-7 mm near zero)
        inside = (xs >= fit[0]) & (xs <= field.x_min[which - 1])
        r[inside] = fit[5](xs[inside])
        if fit[4] > -math.inf:  # below the shifts where the generated gear has a tooth: NaN
            below = xs < fit[4]
            inside |= below
            r[below] = np.nan
    else:
        inside = np.zeros(xs.shape, bool)
    for k in ([] if inside.all() else np.flatnonzero(~inside)):  # outside the interpolant: the generated gear
        d = field.form_diameter(which, float(xs[k]), exact=True)
        r[k] = math.sqrt(max((d / 2) ** 2 - rb ** 2, 0.0)) if d is not None and not math.isnan(d) else math.nan
    rho[idx] = r
    return rho
