"""The design check of a pair as functions of the shifts: margins at any point (x1, x2).

A :class:`PairField` holds a pair without shifts (a :class:`~gearkit.pair.PairSpec` whose shifts
are ignored) and evaluates, at any (x1, x2), the margins the blocking lines are level sets of.
Every margin is read off the same :func:`~gearkit.pair.pair_geometry` and the same check functions
as :func:`~gearkit.checks.check_pair` (:func:`~gearkit.checks.involute.fail_margins`,
:func:`~gearkit.pair.internal.exit_jamming_margin`, :func:`~gearkit.pair.internal.plunge_trimming`,
:func:`~gearkit.pair.internal.tip_sweep_depth`,
:func:`~gearkit.checks.min_shift_undercut`): there is one implementation of each check.

Form circles. The check reads each gear's form circle off the generated gear. A rack- or
shaper-cut gear that is not undercut (``rho_l >= 0``) has its form circle where the closed form
puts it (the generated one agrees to rounding), so the closed form is used there; an undercut
gear's form circle comes from the generated gear, cached per (gear, x): it does not depend on
the tip diameter. Only the margins that depend on a form circle (real contact ratio, interference,
sliding at the ends of the real path) read it; where the generated gear has no tooth, no margin exists.

Units: lengths in module units (margin / m_n), angles in radians, ratios as they are.
"""
from __future__ import annotations

import math
from collections import OrderedDict
from dataclasses import dataclass, replace

from gearkit.blocking.point import FieldPoint
from gearkit.checks.involute import min_shift_undercut
from gearkit.checks.limits import CheckLimits
from gearkit.errors import SpecError, require
from gearkit.pair.spec import PairSpec
from gearkit.pair.tooling import form_roll, section

__all__ = ["LineDef", "PairField", "forget_generated", "generated_form_diameter"]

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


@dataclass(frozen=True)
class LineDef:
    """One line of a blocking contour: the level ``margin = 0`` of a named quantity.

    Parameters
    ----------
    name : str
        Stable id, e.g. ``"interference.1"``, ``"tip_thickness.1=0.25"``.
    code : str
        Short tag for pictures: ``B1`` ... ``B6`` for the hard lines (reference digest 2.2), ``Q`` for
        quality lines, ``R`` for reference lines, ``C`` for lines of constant centre distance.
    label : str
        Plain-language meaning, with the admissible side.
    hard : bool
        True when crossing it makes :func:`~gearkit.checks.check_pair` fail.
    finding : str or None
        The id of the check finding this line is the limit of.
    needs : (bool, bool)
        Whether the margin needs the generated form circle of gear 1 / gear 2.
    """

    name: str
    code: str
    label: str
    hard: bool
    finding: str | None
    needs: tuple = (False, False)


class PairField:
    """Margins of the design check of ``template`` at any shifts (x1, x2) (module units).

    Parameters
    ----------
    template : PairSpec
        External or internal pair; its shifts, centre distance and tip diameters are ignored
        (each point gets the tight mesh and the tips of ``template.tip_rule``).
    limits : CheckLimits
        The check's limits (warn levels: tip thickness, contact ratio).
    tip_levels : tuple of float
        Tip-thickness quality levels s_an / m_n (default 0.25 and 0.4).
    contact_levels : tuple of float
        Contact-ratio quality levels (default 1.2).
    center_distances : tuple of float, mm
        Centre distances whose lines (constant a_w) are wanted.
    """

    def __init__(self, template: PairSpec, limits: CheckLimits = CheckLimits(), tip_levels=(0.25, 0.4),
                 contact_levels=(1.2,), center_distances=(), x_ranges=None):
        require(isinstance(template, PairSpec), "pair", "must be a PairSpec")
        require(template.kind in ("external", "internal"), "kind",
                "a blocking contour needs two gears with shifts (external or internal, not a rack pair)")
        tools = template.tools  # explicit: the pair formulas then need not build default tools per point
        self.template = replace(template, shift1=0.0, shift2=0.0, center_distance=None,
                                tip_diameter1=None, tip_diameter2=None, tool1=tools[0], tool2=tools[1])
        self.limits = limits
        self.internal = template.kind == "internal"
        self.module = float(template.module)
        self.tip_levels = tuple(sorted({float(v) for v in tip_levels}))
        self.contact_levels = tuple(sorted({float(v) for v in contact_levels}))
        for v in self.tip_levels:
            require(math.isfinite(v) and 0.0 < v < 2.0, "tip_levels", f"{v!r} must be in (0, 2) (module units)")
        for v in self.contact_levels:
            require(math.isfinite(v) and 1.0 < v < 3.0, "contact_levels", f"{v!r} must be in (1, 3)")
        self.center_distances = tuple(float(a) for a in center_distances)
        for a in self.center_distances:
            require(math.isfinite(a) and a > 0, "center_distances", f"{a!r} must be a positive length in mm")
        self._sec = section(template.module, template.alpha_n_deg, template.helix_angle_deg)
        self._tools = self.template.tools
        self._fields = dict(self.template.__dict__)
        self._forms = {}
        self._under = {}
        self._fits, self._hits = {}, {}
        self._points = {}
        self._checks = {}
        self.exact_forms = x_ranges is None
        self.x_ranges = None if x_ranges is None else ((x_ranges[0], x_ranges[1]), (x_ranges[2], x_ranges[3]))
        # undercut onset of each external gear (x_min of the check's undercut finding)
        self.x_min = tuple(None if (self.internal and i == 2) else min_shift_undercut(self.template, i)
                           for i in (1, 2))
        self.lines = self._line_defs()
        self.by_name = {d.name: d for d in self.lines}
        self.hard = tuple(d.name for d in self.lines if d.hard)

    def __getstate__(self):
        """Pickled (e.g. from an atlas worker) without the evaluation caches: the evaluated points,
        the undercut flags and the form-circle interpolants (closures) are rebuilt on demand."""
        state = dict(self.__dict__)
        state["_points"], state["_under"], state["_fits"], state["_checks"], state["_hits"] = {}, {}, {}, {}, {}
        return state

    # -- lines ------------------------------------------------------------------------------
    def _line_defs(self) -> tuple:
        ring = self.internal
        out = [
            LineDef("interference.1", "B1", "tip of gear 2 in the fillet of gear 1 (interference; admissible: "
                    "the active profile of gear 1 starts on its involute)", True, "interference.1", (True, False)),
            LineDef("interference.2", "B2", "tip of gear 1 in the fillet of gear 2 (interference)", True,
                    "interference.2", (False, True)),
            LineDef("contact_ratio=1", "B3", "eps_alpha = 1 (the check's contact ratio; admissible above)", True,
                    "contact_ratio", (True, True)),
            LineDef("pointing.1", "B4", "s_a1 = 0: gear 1 pointed (admissible: thicker tips)", True, "pointing.1"),
            LineDef("pointing.2", "B5", "s_a2 = 0: gear 2 pointed", True, "pointing.2"),
            LineDef("tip_clearance.1", "B", "tip of gear 1 hits the root of gear 2", True, "tip_clearance.1"),
            LineDef("tip_clearance.2", "B", "tip of gear 2 hits the root of gear 1", True, "tip_clearance.2"),
        ]
        if ring:
            out += [LineDef("exit_jamming", "B6", "exit jamming: tip interference on leaving mesh", True,
                            "exit_jamming"),
                    LineDef("trimming.plunge", "B6", "the shaper trims the ring while plunging", True,
                            "trimming.plunge"),
                    LineDef("tip_interference", "B6", "tip interference: a tip corner swept along its path "
                            "through the mate's teeth reaches into one (admissible: it clears them)", True,
                            "tip_interference", (True, False))]
        for i in (1, 2):
            if self.x_min[i - 1] is not None:
                out.append(LineDef(f"undercut.{i}", "Q", f"undercut onset of gear {i}: x{i} = x{i},min "
                                   "(admissible: no undercut on the larger side)", False, f"undercut.{i}"))
        for i in (1, 2):
            for v in self.tip_levels:
                out.append(LineDef(f"tip_thickness.{i}={v:g}", "Q", f"s_a{i} = {v:g} m_n", False, f"pointing.{i}"))
        for v in self.contact_levels:
            out.append(LineDef(f"contact_ratio={v:g}", "Q", f"eps_alpha = {v:g}", False, "contact_ratio", (True, True)))
        for v in (1.0,) + self.contact_levels:
            out.append(LineDef(f"contact_ratio_tip={v:g}", "R", f"eps_alpha = {v:g} tip to tip (the atlas' "
                               "line; equals the real one wherever B1 and B2 hold" + (" and the ring is not "
                               "trimmed)" if ring else ")"), False, None))
        out.append(LineDef("sliding", "Q", "equal specific sliding at the ends of the path, |zeta1| = |zeta2|",
                           False, None, (True, True)))
        if ring:
            out.append(LineDef("trimming.nu", "Q", "ring tip circle on O2N_u (inside it the shaper trims the "
                               "ring's involute)", False, "trimming.nu"))
        for a in self.center_distances:
            out.append(LineDef(f"center_distance={a:g}", "C", f"a_w = {a:g} mm", False, None))
        return tuple(out)

    # -- evaluation -------------------------------------------------------------------------
    def spec(self, x1: float, x2: float) -> PairSpec:
        """The pair at shifts (x1, x2) (tight mesh).

        The template is validated once; a point only changes the shifts, which the window keeps
        inside the range :class:`~gearkit.pair.PairSpec` accepts, so the copy skips re-validation
        (``dataclasses.replace`` would repeat it at every point). Out-of-range shifts still go
        through ``replace`` and raise.
        """
        x1, x2 = float(x1), float(x2)
        if not (-3.0 <= x1 <= 3.0 and -3.0 <= x2 <= 3.0):
            return replace(self.template, shift1=x1, shift2=x2)
        out = object.__new__(PairSpec)
        d = out.__dict__
        d.update(self._fields)
        d["shift1"], d["shift2"] = x1, x2
        return out

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

    def point(self, x1: float, x2: float, exact: bool | None = None) -> "FieldPoint":
        """The lazily evaluated pair at (x1, x2); ``exact``: generated form circles (default: the
        field's setting; the check's own, exact ones when no ``x_ranges`` were given)."""
        exact = self.exact_forms if exact is None else bool(exact)
        key = (float(x1), float(x2), exact)
        pt = self._points.get(key)
        if pt is None:
            if len(self._points) > 50000:
                self._points.clear()
            pt = self._points[key] = FieldPoint(self, *key)
        return pt

    def check(self, x1: float, x2: float) -> tuple:
        """The verdict of :func:`~gearkit.checks.check_pair` (generated gears, this field's limits) on
        the pair at (x1, x2): ``(passes, ids of the failing findings, why no pair exists or "")``."""
        key = (float(x1), float(x2))
        out = self._checks.get(key)
        if out is None:
            from gearkit.checks import check_pair

            try:
                report = check_pair(self.spec(*key), self.limits).report
                failing = tuple(f.id for f in report.findings if f.status == "fail")
                out = (not failing, failing, "")
            except SpecError as exc:
                out = (False, (), str(exc))
            if len(self._checks) > 10000:
                self._checks.clear()
            self._checks[key] = out
        return out

    def margin(self, name: str, x1: float, x2: float) -> float:
        """Margin of line ``name`` at (x1, x2): >= 0 on the admissible side; NaN where no pair exists."""
        return self.point(x1, x2).margin(name)
