"""The blocking contour of a pair: traced lines, the admissible region, point queries.

:func:`blocking_contour` traces every line of a :class:`~gearkit.blocking.field.PairField` in a
window of the (x1, x2) plane and the boundary of the admissible region (all hard margins >= 0:
the shifts at which :func:`~gearkit.checks.check_pair` does not fail), and returns a
:class:`BlockingContour`.

Speed: every evaluation is one call of the pair formulas (:func:`~gearkit.pair.pair_geometry`)
at one shift pair; a full contour of z1 = 13, z2 = 16 (about 200 points per line, 17 lines)
takes some 8,000 of them. The seed grid is shared by all lines and the region, seeds are refined
only where needed, and the region's vertices are solved on the seed grid's edges and at its
corners. :func:`~gearkit.blocking.blocking_atlas` spreads many contours over processes.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from gearkit.blocking.field import PairField
from gearkit.blocking.recommend import recommend
from gearkit.blocking.region import GRID, admissible_region, polygon_area
from gearkit.blocking.trace import Window, grid_seeds, trace_curves
from gearkit.checks.limits import CheckLimits
from gearkit.curves import bracketed_root
from gearkit.errors import SpecError, require
from gearkit.pair.spec import PairSpec
from gearkit.pair.tooling import half_angle, section, thickness_coeff

__all__ = ["BlockingContour", "Line", "blocking_contour", "default_window"]



@dataclass(frozen=True)
class Line:
    """A traced line: its definition and its components, each ``(n, 2)`` float64 (x1, x2)."""

    name: str
    code: str
    label: str
    hard: bool
    finding: str | None
    components: tuple

    @property
    def points(self) -> np.ndarray:
        """All vertices, components concatenated, ``(n, 2)``."""
        return np.concatenate(self.components) if self.components else np.zeros((0, 2))


def _pointing_shift(sec, z, tool, internal, addendum) -> float:
    """Shift at which a lone gear (no tip shortening) is pointed: s_a(x) = 0, or 3 when never below 3."""
    def s_a(x):
        try:
            delta = thickness_coeff(sec, z, x, tool, internal)
        except SpecError:
            return math.nan
        r = z * sec.mt / 2
        ra = r - sec.mn * (addendum - x) if internal else r + sec.mn * (addendum + x)
        rb = r * math.cos(sec.alpha_t)
        return float(half_angle(sec, z, delta, max(ra, rb), internal))

    lo, hi = -0.5, 3.0
    if not s_a(hi) < 0:
        return hi
    return bracketed_root(s_a, lo, hi, xtol=1e-6) if s_a(lo) > 0 else lo


def default_window(field: PairField) -> tuple:
    """(x1_lo, x1_hi, x2_lo, x2_hi): from 1 below the undercut onset (ring: -1) to 0.6 past pointing (tip shortening moves it),
    within the shifts a :class:`~gearkit.pair.PairSpec` accepts ([-3, 3])."""
    t = field.template
    sec = section(t.module, t.alpha_n_deg, t.helix_angle_deg)
    out = []
    for i, z in ((1, t.teeth1), (2, t.teeth2)):
        internal = field.internal and i == 2
        x_min = field.x_min[i - 1]
        lo = -1.0 if x_min is None else max(-3.0, min(x_min - 1.0, -0.5))
        hi = min(3.0, _pointing_shift(sec, z, t.tools[i - 1], internal, t.addendum) + 0.6)
        out += [lo, max(hi, lo + 0.5)]
    return tuple(out)


class BlockingContour:
    """Result of :func:`blocking_contour` (shifts are normal coefficients x_n; see the package notes).

    Attributes
    ----------
    field : PairField
    window : (x1_lo, x1_hi, x2_lo, x2_hi)
    lines : tuple of Line
    region : tuple of (n, 2) float64
        Closed polygons (first vertex repeated last, counter-clockwise) of the admissible region.
    empty_reason : str or None
        Why the region is empty (the binding lines at the best point), None when it is not.
    xtol : float
        Accuracy in x of every traced vertex.
    seconds : float
        Wall time of the computation.
    """

    def __init__(self, field, window, lines, region, empty_reason, xtol, seconds, evaluations):
        self.field, self.window, self.lines, self.region = field, window, lines, region
        self.empty_reason, self.xtol, self.seconds, self.evaluations = empty_reason, xtol, seconds, evaluations

    @property
    def empty(self) -> bool:
        return not self.region

    def line(self, name: str) -> Line:
        for ln in self.lines:
            if ln.name == name:
                return ln
        raise KeyError(name)

    # -- point queries ------------------------------------------------------------------------
    def margins(self, x1: float, x2: float) -> dict:
        """Margin of every line with an admissible side at (x1, x2) (NaN where no pair exists)."""
        pt = self.field.point(x1, x2, exact=True)
        return {d.name: pt.margin(d.name) for d in self.field.lines if d.code in ("B1", "B2", "B3", "B4", "B5",
                                                                                  "B6", "B", "Q")
                and d.name != "sliding"}

    def contains(self, x1: float, x2: float) -> bool:
        """True when the design check of the pair at (x1, x2) does not fail (the check's own verdict:
        every hard margin, the backlash and, for internal pairs, the tip sweep)."""
        pt = self.field.point(x1, x2, exact=True)
        if not pt.valid:
            return False
        if any(not (m >= 0) for m in pt.hard_margins().values()):
            return False
        from gearkit.checks.involute import fail_margins

        g = pt.geometry((True, True))
        if fail_margins(g)["backlash"] < 0:
            return False
        if self.field.internal:
            from gearkit.pair.internal import tip_sweep
            return tip_sweep(g)[0] <= 0
        return True

    def binding(self, x1: float, x2: float) -> list:
        """Names of the lines (hard and quality) that (x1, x2) violates, hard ones first."""
        pt = self.field.point(x1, x2, exact=True)
        if not pt.valid:
            return ["no_pair"]
        m = self.margins(x1, x2)
        out = [n for n, v in m.items() if not (v >= 0)]
        if self.field.internal and not out:
            from gearkit.pair.internal import tip_sweep
            if tip_sweep(pt.geometry((True, True)))[0] > 0:
                out.append("tip_interference")
        hard = set(self.field.hard)
        return sorted(out, key=lambda n: (n not in hard, n))

    def mark(self, x1: float, x2: float) -> dict:
        """The ``marked`` object of the CLI: {x1, x2, inside, binding}."""
        return {"x1": float(x1), "x2": float(x2), "inside": self.contains(x1, x2), "binding": self.binding(x1, x2)}

    @property
    def area(self) -> float:
        """Area of the admissible region in the (x1, x2) plane (0 when it is empty)."""
        return sum(abs(polygon_area(p)) for p in self.region)

    def center_distance_line(self, center_distance: float) -> Line:
        """The line of operating centre distance ``center_distance`` (mm) in this contour's window:
        the traced one when the contour holds it, else traced now with the same limits and ``xtol``."""
        name = f"center_distance={float(center_distance):g}"
        if name in self.field.by_name:
            return self.line(name)
        sub = blocking_contour(self.field.template, window=self.window, limits=self.field.limits,
                              center_distances=(float(center_distance),), xtol=self.xtol, lines=[name])
        return sub.line(name)

    def recommend(self, criterion: str = "balanced", center_distance: float | None = None):
        """The recommended shifts by a named criterion (see :mod:`gearkit.blocking.recommend`)."""
        return recommend(self, criterion, center_distance)

    # -- export ---------------------------------------------------------------------------------
    def to_dict(self, recommendation=None, marked=None) -> dict:
        """JSON-ready: pair, window, lines (name, points), region, recommendation, marked."""
        t = self.field.template
        tools = [getattr(tt, "name", None) or type(tt).__name__ for tt in t.tools]
        out = {
            "pair": {"z1": t.teeth1, "z2": t.teeth2, "kind": t.kind, "pressure_angle_deg": t.alpha_n_deg,
                     "helix_angle_deg": t.helix_angle_deg, "addendum": t.addendum, "tip_rule": t.tip_rule,
                     "tools": tools,
                     "cutter_teeth": getattr(t.tools[1], "teeth", None) if t.kind == "internal" else None},
            "window": list(self.window), "xtol": self.xtol,
            "lines": [{"name": ln.name, "code": ln.code, "label": ln.label, "hard": ln.hard, "finding": ln.finding,
                       "points": [c.tolist() for c in ln.components]} for ln in self.lines],
            "region": {"empty": self.empty, "reason": self.empty_reason,
                       "area": self.area,
                       "polygons": [p.tolist() for p in self.region]},
            "seconds": self.seconds,
        }
        if recommendation is not None:
            out["recommendation"] = recommendation.to_dict()
        if marked is not None:
            out["marked"] = marked
        return out

    def save(self, path, recommendation=None, marked=None) -> None:
        """Write ``.png``, ``.svg`` (picture) or ``.json`` atomically (temp file + rename)."""
        from gearkit.blocking.plot import save
        save(self, path, recommendation, marked)


def _prefer(field: PairField, needs):
    """Corrector axis that keeps an undercut gear's shift fixed (one generated gear per point)."""
    if not any(needs):
        return None

    def prefer(q):
        u1 = needs[0] and field.undercut(1, q[0])
        u2 = needs[1] and field.undercut(2, q[1])
        if u1 and not u2:
            return 1
        if u2 and not u1:
            return 0
        return None
    return prefer


def blocking_contour(pair: PairSpec, *, window=None, limits: CheckLimits = CheckLimits(), tip_levels=(0.25, 0.4),
                     contact_levels=(1.2,), center_distances=(), xtol: float = 1e-6,
                     points: int = 200, lines=None) -> BlockingContour:
    """Compute the blocking contour of ``pair`` (its shifts are ignored).

    Parameters
    ----------
    pair : PairSpec
        External or internal pair (an internal one with its shaper, ``tool2``).
    window : (x1_lo, x1_hi, x2_lo, x2_hi) or None
        The plotted part of the plane; None: :func:`default_window`.
    limits, tip_levels, contact_levels, center_distances
        See :class:`~gearkit.blocking.field.PairField`.
    xtol : float
        Accuracy in x of every traced vertex (default 1e-6).
    points : int
        Step of the tracing: the window's diagonal / ``points`` (about ``points`` vertices per line
        that crosses the window).
    lines : iterable of str or None
        Names of the lines to trace (default all); the region is always traced.

    Returns
    -------
    BlockingContour
    """
    t0 = time.perf_counter()
    require(isinstance(xtol, float) and 1e-12 <= xtol <= 1e-2, "xtol", f"{xtol!r} must be in [1e-12, 1e-2]")
    require(isinstance(points, int) and 20 <= points <= 5000, "points", f"{points!r} must be in [20, 5000]")
    field = PairField(pair, limits, tip_levels, contact_levels, center_distances)
    win = default_window(field) if window is None else tuple(float(v) for v in window)
    require(len(win) == 4 and all(math.isfinite(v) and -3.0 <= v <= 3.0 for v in win)
            and win[0] < win[1] and win[2] < win[3], "window",
            f"{win!r} must be (x1_lo, x1_hi, x2_lo, x2_hi) within [-3, 3], lo < hi")
    field.x_ranges = ((win[0], win[1]), (win[2], win[3]))  # undercut form circles: interpolated
    field.exact_forms = False
    w = Window(*win)
    h = w.size / points
    xs = np.linspace(w.lo[0], w.hi[0], GRID)
    ys = np.linspace(w.lo[1], w.hi[1], GRID)
    wanted = None if lines is None else set(lines)
    traced = []
    for d in field.lines:
        if wanted is not None and d.name not in wanted:
            continue

        def f(x1, x2, _n=d.name):
            return field.margin(_n, x1, x2)
        vals = np.array([[f(x, y) for x in xs] for y in ys])
        seeds = grid_seeds(f, xs, ys, vals, xtol, refine=False)
        comps = trace_curves(f, w, seeds, h, xtol, prefer=_prefer(field, d.needs)) if seeds else []
        traced.append(Line(d.name, d.code, d.label, d.hard, d.finding, tuple(comps)))
    region, reason = admissible_region(field, w, xtol)
    n_eval = len(field._points)
    return BlockingContour(field, win, tuple(traced), region, reason, xtol, time.perf_counter() - t0, n_eval)
