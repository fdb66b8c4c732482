"""Form circles of the generated gears, as functions of the shift, for :class:`~gearkit.blocking.field.PairField`.

The check reads each gear's form circle off the generated gear. A rack- or shaper-cut gear that is
not undercut (``rho_l >= 0``) has its form circle where the closed form puts it (the generated one
agrees to rounding), so the closed form is used there; an undercut gear's form circle comes from
the generated gear, cached per (gear, x): it does not depend on the tip diameter. Only the margins
that depend on a form circle (real contact ratio, interference, sliding at the ends of the real
path) read it; where the generated gear has no tooth, no margin exists. Over a window, an undercut
gear's form circle is read off a Chebyshev interpolant of the generated ones
(:meth:`FormCircles.form_interpolant`), which the arrays (:mod:`~gearkit.blocking.arrays`) evaluate.

Units: shifts in module units, diameters and roll lengths in mm.
"""
from __future__ import annotations

import math
from collections import OrderedDict

from gearkit.errors import SpecError
from gearkit.pair.tooling import form_roll

__all__ = ["FLOOR_HITS", "FORM_GAP", "FormCircles", "forget_generated", "generated_form_diameter"]

FORM_NODES = 14  #: Chebyshev nodes of the undercut form-circle interpolant (error ~1e-9 m_n)
FORM_GAP = 0.005  #: the interpolant ends this far below the undercut onset
FORM_CHECKS = 2  #: test shifts of the interpolant
FORM_MARGIN = 0.5  #: the interpolant reaches this far below the window (the probes of chords beside the
#: window's edge reach past it: each point left outside would generate a gear of its own)
FORM_TIPS = (0.0, 1.0, -0.5)  #: blank tips tried (m_n above the blank's own) for a gear with a flank
FORM_BISECTIONS = 12  #: bisections for the smallest shift at which the generated gear has a tooth; once
FLOOR_HITS = 4  #: gears are generated between the last two, it is bisected on to neighbouring floats (edge
#: searches close in on it there: each point generated a gear, 9354 on 46/49's contour)
FEW_SHIFTS = 16  #: the form-circle interpolant sums the series on floats for at most this many shifts (numpy's
#: cost per call outweighs the arithmetic)
GENERATED_CACHE = 4096  #: generated form circles kept per process (an atlas meets each gear in many cells)
_GENERATED: OrderedDict = OrderedDict()


def _clenshaw(u, c):
    """The Chebyshev series ``c`` at one ``u`` (or at an array of them, ``c`` then best 0-d arrays): numpy's
    ``chebval`` recurrence, step for step (the same roundings: each step one IEEE operation either way)."""
    c0, c1, x2 = c[-2], c[-1], 2 * u
    for ci in c[-3::-1]:
        c0, c1 = ci - c1, c0 + c1 * x2
    return c0 + c1 * u


def forget_generated() -> None:
    """Forget the remembered generated gears (a cold start, e.g. for a timing)."""
    _GENERATED.clear()


def generated_form_diameter(gspec) -> float | None:
    """The form diameter of the generated gear ``gspec`` (a :class:`~gearkit.families.involute.GearSpec`),
    or None when its cutter leaves it no tooth; the last ``GENERATED_CACHE`` gears are remembered (the
    same gear comes back in every contour of a session and every atlas cell it belongs to).

    >>> from gearkit.families.involute import GearSpec
    >>> d = generated_form_diameter(GearSpec(12, 1.0))
    >>> round(d, 4), generated_form_diameter(GearSpec(12, 1.0)) == d
    (11.3027, True)
    """
    from gearkit.families.involute import tooth_profile

    if gspec in _GENERATED:
        _GENERATED.move_to_end(gspec)
        return _GENERATED[gspec]
    try:
        d = tooth_profile(gspec).form_diameter
    except SpecError:
        d = None
    _GENERATED[gspec] = d
    if len(_GENERATED) > GENERATED_CACHE:
        _GENERATED.popitem(last=False)
    return d


class FormCircles:
    """The form circles of a :class:`~gearkit.blocking.field.PairField`'s two gears at any shift (its base).

    Reads the field's ``template``, ``internal``, ``x_min``, ``x_ranges``, section and tools, and keeps its caches
    (``_under``, ``_forms``, ``_fits``, ``_hits``: set up empty by the field, dropped when it is pickled).
    """

    def undercut(self, which: int, x: float) -> bool:
        """True when the closed form says gear ``which`` is undercut at shift ``x`` (rho_l < 0)."""
        if which == 2 and self.internal:
            return False
        key = (which, float(x))
        u = self._under.get(key)
        if u is None:
            if len(self._under) > 50000:
                self._under.clear()
            t = self.template
            z = t.teeth1 if which == 1 else t.teeth2
            u = self._under[key] = form_roll(self._sec, z, float(x), self._tools[which - 1], False) < 0
        return u

    def form_diameter(self, which: int, x: float, exact: bool = True):
        """d_F (mm) of gear ``which`` at shift ``x`` as generated, or None where the closed form is exact.

        ``exact=False`` reads an undercut gear's form circle off a Chebyshev interpolant of the
        generated ones over ``x_ranges`` (see :meth:`form_interpolant`) instead of generating the gear.
        """
        try:
            if not self.undercut(which, x):
                return None
        except SpecError:  # the tool has no machine mesh with this gear: no gear at all
            return math.nan
        if not exact and self.x_ranges is not None:
            fit = self.form_interpolant(which)
            if fit is not None and fit[0] <= x <= self.x_min[which - 1]:
                return fit[3](x)
        key = (which, float(x))
        if key not in self._forms:
            from gearkit.families.involute import GearSpec

            t = self.template
            # the check's gear (gear_specs); its form circle does not depend on its tip, but whether a flank is
            # left below it does: where the blank's own tip leaves none, other tips are tried (pair tips move)
            z, beta, thin = ((t.teeth1, t.helix_angle_deg, t.thinning1) if which == 1 else
                             (t.teeth2, -t.helix_angle_deg, t.thinning2))
            self._forms[key] = math.nan
            for k, up in enumerate(FORM_TIPS):
                tip = None if k == 0 else 2 * (z * self._sec.mt / 2 + t.module * (t.addendum + float(x) + up))
                try:
                    gspec = GearSpec(z, t.module, float(x), beta, False, t.tools[which - 1], tip, thin)
                except SpecError:  # a shift no gear takes: no tooth
                    continue
                d = generated_form_diameter(gspec)
                if d is not None:
                    self._forms[key] = d
                    break
            fit = self._fits.get(which)
            if fit is not None and fit[4] > -math.inf and fit[4] <= x < fit[0]:  # see FLOOR_HITS
                self._hits[which] = self._hits.get(which, 0) + 1
                if self._hits[which] == FLOOR_HITS:
                    a, b = fit[4], fit[0]
                    while a < (m := 0.5 * (a + b)) < b:
                        a, b = (m, b) if math.isnan(self.form_diameter(which, m)) else (a, m)
                    self._fits[which] = (b,) + fit[1:4] + (a,) + fit[5:]  # (the interpolant reaches b)
        return self._forms[key]

    def form_interpolant(self, which: int):
        """(lo, hi, error, d_F(x), floor, rho_F(x)) interpolating the generated form circle of an undercut gear.

        Chebyshev interpolation, ``FORM_NODES`` nodes, of the roll length rho_F(x) over the undercut
        part ``[lo, hi]`` of ``x_ranges[which - 1]`` that ends ``FORM_GAP`` below the undercut onset
        (closer to it the generated form circle is not smooth); ``error`` is the largest deviation
        (mm) from the generated gears at ``FORM_CHECKS`` test shifts; below ``floor`` the generated gear
        has no tooth (``-inf`` when it has one down to ``lo``; see ``FLOOR_HITS``); ``rho_F(x)`` is the roll length itself (mm, arrays:
        read off ``d_F`` it would lose ``sqrt(r_b ulp)``, 2e-7 mm, beside the onset). None without undercut.
        """
        if which in self._fits:
            return self._fits[which]
        fit = None
        x_min = self.x_min[which - 1]
        lo, hi = self.x_ranges[which - 1]
        lo -= FORM_MARGIN
        hi = min(hi, x_min - FORM_GAP) if x_min is not None else lo
        floor = -math.inf
        if x_min is not None and hi > lo:
            import numpy as np

            t = self.template
            z = t.teeth1 if which == 1 else t.teeth2
            rb = z * self._sec.mt * math.cos(self._sec.alpha_t) / 2

            def roll(x):
                d = self.form_diameter(which, float(x))
                return math.sqrt(max((d / 2) ** 2 - rb ** 2, 0.0))

            if math.isnan(self.form_diameter(which, lo)):  # no tooth at the low end: fit where one exists
                a, b = lo, hi
                if math.isnan(self.form_diameter(which, b)):
                    self._fits[which] = None
                    return None
                for _ in range(FORM_BISECTIONS):
                    m = 0.5 * (a + b)
                    a, b = (m, b) if math.isnan(self.form_diameter(which, m)) else (a, m)
                lo, floor = b, a
            n = FORM_NODES
            nodes = np.cos(math.pi * (np.arange(n) + 0.5) / n)
            xs = (lo + hi) / 2 + (hi - lo) / 2 * nodes
            coef = np.polynomial.chebyshev.chebfit(nodes, [roll(x) for x in xs], n - 1).tolist()
            r_hi = float(np.polynomial.chebyshev.chebval(1.0, coef))

            def interp_roll(x, _c=coef, _lo=lo, _hi=hi, _x0=x_min, _r_hi=r_hi,
                            _a=tuple(np.asarray(v) for v in coef + [lo, hi, x_min, r_hi, hi - lo, x_min - hi])):
                # array; the last FORM_GAP: straight to rho_F = 0 at the onset (numpy's cost per call: floats, 0-d)
                xa = np.asarray(x, dtype=float)
                if xa.size <= FEW_SHIFTS:
                    return np.array([_r_hi * (_x0 - v) / (_x0 - _hi) if v > _hi else
                                     _clenshaw((2 * v - _lo - _hi) / (_hi - _lo), _c)
                                     for v in xa.ravel().tolist()]).reshape(xa.shape)
                lo_, hi_, x0_, r_hi_, width, gap = _a[-6:]  # (chebval's recurrence on 0-d arrays: the same roundings)
                return np.where(xa > hi_, r_hi_ * (x0_ - xa) / gap, _clenshaw((2 * xa - lo_ - hi_) / width, _a[:-6]))

            def interp(x, _rb=rb):
                d = 2.0 * np.hypot(_rb, interp_roll(x))
                return float(d) if d.ndim == 0 else d

            tests = lo + (hi - lo) * (np.arange(FORM_CHECKS) + 0.5) / FORM_CHECKS
            err = max(abs(interp(x) - self.form_diameter(which, float(x))) / 2 for x in tests)
            fit = (lo, hi, err, interp, floor, interp_roll)
        self._fits[which] = fit
        return fit
