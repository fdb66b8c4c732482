"""The tight-mesh pair geometry at arrays of shifts: what the margins of :mod:`gearkit.blocking.arrays` read.

:class:`PairArrays` works out, with numpy over arrays ``x1``, ``x2`` in one pass, the closed forms
:func:`~gearkit.pair.pair_geometry` derives for one pair: the generating shifts and form circles of
both gears (:mod:`~gearkit.blocking.gear_arrays`), the tight mesh's centre distance and working
pressure angle, the tips the check grades (:func:`graded_tip`), the real path of contact and its
contact ratio, and, read on demand, the tip clearances, backlash, tip thicknesses and specific
slidings; ``bad`` marks the points where no pair exists and :meth:`PairArrays.conditions` measures how
far each is from one. The margins by name, and their evaluators, are :mod:`~gearkit.blocking.arrays`'s.

>>> import numpy as np
>>> from gearkit.blocking.field import PairField
>>> from gearkit.pair import PairSpec
>>> with np.errstate(invalid="ignore", divide="ignore"):
...     g = PairArrays(PairField(PairSpec(20, 40, 1.0)), np.array([0.0, 0.5]), np.array([0.0, 0.2]))
>>> # unshifted: the reference centre distance (z1 + z2) m / 2 at the tool's 20 degrees
>>> round(float(g.a_w[0]), 9), round(float(np.degrees(g.alpha_w[0])), 9), g.bad.tolist()
(30.0, 20.0, [False, False])
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.curves import inv
from gearkit.blocking.gear_arrays import (PairScalars, form_roll_lengths, gear_forms, half_angles, inv_inverse,
                                          rack_forms, ring_settings)
from gearkit.pair.tooling import graded_tip_radius

__all__ = ["PairArrays", "graded_tip"]


def graded_tip(rack, sec, z, x, tool, internal, blank, mn):
    """:func:`~gearkit.pair.tooling.graded_tip_radius` (``rack``: the rack's scalars of
    :class:`~gearkit.blocking.gear_arrays.PairScalars`, its cut tip ``r + (x + h_fP*) m_n`` worked out here)."""
    if rack is None:
        return graded_tip_radius(sec, z, x, tool, internal, blank)
    return (np.maximum if internal else np.minimum)(blank, rack[6] + (x + rack[2]) * mn)


class PairArrays:
    """The tight-mesh pair geometry at arrays of shifts (transverse section, mm)."""

    def __init__(self, field, x1, x2, k=None):
        k = PairScalars(field) if k is None else k  # (an evaluator works them out once)
        t = field.template
        sec = field._sec
        self.field, self.sec, self.k = field, sec, k
        self.internal = internal = field.internal
        mn = k.mn
        tool1, tool2 = field._tools
        self.x1, self.x2 = x1, x2
        self.z1, self.z2 = z1, z2 = k.z1, k.z2
        self.r1, self.r2, self.rb1, self.rb2 = r1, r2, rb1, rb2 = k.r1, k.r2, k.rb1, k.rb2
        # a ring's shift read by the ISO convention is cut by the shaper setting x2c (closed form);
        # the thickness allowance feeds the tool in (generating shift x_E) for roots and form circles
        x2c = ring_settings(sec, t, x2) if internal and t.shift_convention == "iso" else x2
        # generating shifts (x itself without thinning)
        xe1 = x1 if k.plain1 else x1 - k.thin1
        xe2 = x2c if k.plain2 else x2c - k.thin2
        forms = (lambda x, rack, z, tool, ring: rack_forms(x, k, rack) if rack is not None
                 else gear_forms(sec, z, x, tool, ring))
        d1, rf1, rho_l1, _ = forms(x1, k.rack1, z1, tool1, False)
        if t.thinning1:
            _, rf1, rho_l1, _ = forms(xe1, k.rack1, z1, tool1, False)
        d2, rf2, rho_l2, a02 = forms(x2c, k.rack2, z2, tool2, internal)
        if t.thinning2:
            _, rf2, rho_l2, _ = forms(xe2, k.rack2, z2, tool2, internal)
        self.a02 = a02
        # (the callers hold an errstate that ignores invalid and divide: :func:`_quiet`)
        if internal:
            value = k.c_inv_at - (d1 + d2) / k.z_sum
        else:
            value = k.c_inv_at + (d1 + d2) / k.z_sum
        base = k.base
        bad = ~(value > k.tiny)
        alpha_tight = inv_inverse(np.where(bad, k.one, value))
        a_w = np.where(bad, k.nan, k.c_base / np.cos(alpha_tight))
        self._tight = (value, a_w, base)  # (for :meth:`conditions`)
        bad |= ~(a_w > k.base_min)
        a_w = np.where(bad, k.nan, a_w)
        alpha_w = np.arccos(k.c_base / a_w)
        ha = k.ha
        if t.tip_rule == "shortened":
            y = (a_w - k.c_a_ref) / mn
            cut = y - (x2 - x1) if internal else (x1 + x2) - y
            blank1 = k.c_r1 + mn * (ha + x1 - cut)
            blank2 = k.c_r2 - mn * (ha - x2 - cut) if internal else k.c_r2 + mn * (ha + x2 - cut)
        else:  # (x - 0.0 is x to the bit)
            blank1 = k.c_r1 + mn * (ha + x1)
            blank2 = k.c_r2 - mn * (ha - x2) if internal else k.c_r2 + mn * (ha + x2)
        # the tips the check grades: the blank's, cut down to what the tools leave (one function)
        ra1 = graded_tip(k.rack1, sec, z1, xe1, tool1, False, blank1, mn)
        ra2 = graded_tip(k.rack2, sec, z2, xe2, tool2, internal, blank2, mn)
        bad |= ~(ra1 > rb1)
        bad |= ~(ra2 < rf2) if internal else ~(ra2 > rb2)
        self.bad = bad | np.isnan(d1) | np.isnan(d2)
        rhoF1 = form_roll_lengths(field, 1, x1, rho_l1, rb1)
        rhoF2 = form_roll_lengths(field, 2, x2, rho_l2, rb2)
        self.bad |= np.isnan(rhoF1) | np.isnan(rhoF2)
        g_line = a_w * np.sin(alpha_w)
        u_e = np.sqrt(ra1 ** 2 - k.rb1_sq)
        if internal:
            mt, at = sec.mt, sec.alpha_t
            nu = np.sqrt(a02 ** 2 + 2 * rb2 * (tool2.teeth * mt * math.cos(at) / 2)
                         - (tool2.teeth * mt * math.cos(at) / 2) ** 2)
            inner2 = np.maximum(np.maximum(ra2, rb2), nu)
            u_a = -g_line + np.sqrt(np.maximum(ra2, rb2) ** 2 - rb2 ** 2)
            u_lo2 = -g_line + np.sqrt(inner2 ** 2 - rb2 ** 2)
            u_hi = rhoF2 - g_line
            lo = np.maximum(np.maximum(u_a, rhoF1), u_lo2)
            self.nu = nu
        else:
            u_a = g_line - np.sqrt(ra2 ** 2 - k.rb2_sq)
            u_hi = g_line - rhoF2
            lo = np.maximum(u_a, rhoF1)
        hi = np.minimum(u_e, u_hi)
        self.p_bt = k.p_bt
        self.eps = np.maximum(hi - lo, k.zero) / k.c_p_bt
        self.u_a, self.u_e, self.rhoF1, self.u_hi = u_a, u_e, rhoF1, u_hi
        self.lo, self.hi, self.g_line = lo, hi, g_line
        # a gear without thinning: d - 0.0 is d itself, to the bit
        t1 = d1 if k.plain1 else d1 - t.thinning1 / sec.mn
        t2 = d2 if k.plain2 else d2 - t.thinning2 / sec.mn
        self.a_w, self.alpha_w, self.ra1, self.ra2, self.rf1, self.rf2 = a_w, alpha_w, ra1, ra2, rf1, rf2
        self.t1, self.t2 = t1, t2
        self._tips = self._slide = None

    def conditions(self):
        """The conditions for a pair, ``(n, 4)`` (a tight mesh, its centre distance beyond the base
        circles', each tip beyond its base circle or, for a ring, inside its root circle): every one
        positive exactly where a pair exists (one is NaN where an earlier one fails); where none
        exists for another reason (no tooth, no cutter setting) there is no measure: all NaN."""
        value, a_w, _ = self._tight
        k = self.k
        far = (self.rf2 - self.ra2) if self.internal else (self.ra2 - self.rb2)
        parts = np.empty((len(value), 4))
        parts[:, 0], parts[:, 1] = value - k.tiny, (a_w - k.base_min) / k.mn
        parts[:, 2], parts[:, 3] = (self.ra1 - self.rb1) / k.mn, far / k.mn
        parts[self.bad & (parts > 0).all(axis=1)] = np.nan
        return parts

    @property
    def eps_nominal(self):
        """The contact ratio of the tips alone (no form circles)."""
        return (self.u_e - self.u_a) / self.p_bt

    def clearance(self, which):
        """Tip clearance (mm) of gear ``which``: its tip's distance from the mate's root circle."""
        a_w = self.a_w
        if self.internal:
            return self.rf2 - a_w - self.ra1 if which == 1 else self.ra2 - a_w - self.rf1
        return a_w - self.ra1 - self.rf2 if which == 1 else a_w - self.ra2 - self.rf1

    @property
    def backlash(self):
        """Circumferential backlash on the operating pitch circle of gear 1 (mm; ~0 at the tight mesh)."""
        z1, z2, t1, t2, alpha_w = self.z1, self.z2, self.t1, self.t2, self.alpha_w
        with np.errstate(invalid="ignore", divide="ignore"):
            rw1 = self.rb1 / np.cos(alpha_w)
            k = 2 * (inv(self.sec.alpha_t) - inv(alpha_w))
            psi1 = (math.pi + 2 * t1) / z1 + k
            if self.internal:
                eta2 = (math.pi - 2 * t2) / z2 + k
                return rw1 * (z2 / z1 * eta2 - psi1)
            psi2 = (math.pi + 2 * t2) / z2 + k
            return rw1 * (2 * math.pi / z1 - psi1 - z2 / z1 * psi2)

    def tip_thickness(self, which):
        """Normal tip thickness s_an (mm) of gear ``which`` (computed once per gear: several lines read it)."""
        if self._tips is None:
            self._tips = {}
        if which not in self._tips:
            self._tips[which] = self._tip_thickness(which)
        return self._tips[which]

    def _tip_thickness(self, which):
        sec = self.sec
        z, t, ra, r, rb = ((self.z1, self.t1, self.ra1, self.r1, self.rb1) if which == 1 else
                           (self.z2, self.t2, self.ra2, self.r2, self.rb2))
        internal = self.internal and which == 2
        rr = np.maximum(ra, rb)
        s_at = (rr + rr) * half_angles(self.k, which, t, rr, internal)  # (2 rr: rr + rr to the bit)
        if not sec.beta:  # spur: the normal section is the transverse one
            return s_at
        beta_a = np.arctan(math.tan(sec.beta) * ra / r)
        return s_at * np.cos(beta_a)

    def sliding(self):
        """|zeta1| at the start of the real path minus |zeta2| at its end."""
        z1, z2 = self.sliding_ends()
        return z1 - z2

    def _path_ends(self):
        """(i = z2 / z1, u and rho (the roll lengths of gear 1 and 2) at the start and the end of the
        real path: u0, rho0, u1, rho1)."""
        u0, u1, g = self.lo, self.hi, self.g_line
        rho0, rho1 = (u0 + g, u1 + g) if self.internal else (g - u0, g - u1)
        return self.z2 / self.z1, u0, rho0, u1, rho1

    def sliding_ends(self):
        """(|zeta1| at the start of the real path, |zeta2| at its end)."""
        ratio, u0, rho0, u1, rho1 = self._path_ends()
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.abs(1.0 - rho0 / (ratio * u0)), np.abs(1.0 - ratio * u1 / rho1)

    def sliding_factors(self):
        """The factors of |zeta1| - |zeta2|: zeta1 - zeta2 and zeta1 + zeta2, each times
        ``u0 rho1 / g**2`` (g = N1N2): smooth, pole-free, zero on the sliding line's two legs,
        which cross where both slidings vanish (a saddle of the absolute form)."""
        if self._slide is None:  # (both legs are read off one evaluation)
            ratio, u0, rho0, u1, rho1 = self._path_ends()
            d = ratio * self.g_line ** 2
            self._slide = ((ratio * ratio * u0 * u1 - rho0 * rho1) / d,
                           (2 * ratio * u0 * rho1 - rho0 * rho1 - ratio * ratio * u0 * u1) / d)
        return self._slide
