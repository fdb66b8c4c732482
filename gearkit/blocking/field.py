"""The design check of a pair as functions of the shifts: margins at any point (x1, x2).

A :class:`PairField` holds a pair without shifts (a :class:`~gearkit.pair.PairSpec` whose shifts
are ignored) and evaluates, at any (x1, x2), the margins the blocking lines are level sets of.
Every margin is read off the same :func:`~gearkit.pair.pair_geometry` and the same check functions
as :func:`~gearkit.checks.check_pair` (:func:`~gearkit.checks.involute.fail_margins`,
:func:`~gearkit.pair.internal.exit_jamming_margin`, :func:`~gearkit.pair.internal.plunge_trimming`,
:func:`~gearkit.pair.internal.tip_sweep_depth`,
:func:`~gearkit.checks.min_shift_undercut`): there is one implementation of each check.

Form circles. The margins that depend on a form circle (real contact ratio, interference, sliding
at the ends of the real path) read the generated gear's, as the check does (:mod:`~gearkit.blocking.forms`).

Units: lengths in module units (margin / m_n), angles in radians, ratios as they are.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

from gearkit.blocking.forms import FormCircles, forget_generated, generated_form_diameter
from gearkit.blocking.point import FieldPoint
from gearkit.checks.involute import min_shift_undercut
from gearkit.checks.limits import CheckLimits
from gearkit.errors import SpecError, require
from gearkit.pair.spec import PairSpec
from gearkit.pair.tooling import section

__all__ = ["LineDef", "PairField", "forget_generated", "generated_form_diameter"]


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


class PairField(FormCircles):
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
