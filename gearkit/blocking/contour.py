"""The blocking contour of a pair: traced lines, the admissible region, point queries.

:func:`blocking_contour` traces every line of a :class:`~gearkit.blocking.field.PairField` in a
window of the (x1, x2) plane, and the boundary of the admissible region (all hard margins >= 0:
the shifts at which :func:`~gearkit.checks.check_pair` does not fail), and returns a
:class:`BlockingContour`.

Speed: the margins are evaluated as arrays (:mod:`gearkit.blocking.arrays`), many points per
call: one grid for the topology of every line and of the region, then every vertex solved and
every chord refined to ``tol`` (:mod:`gearkit.blocking.level`). The number of vertices follows
the tolerance (a chord's deviation from its curve is at most ``tol``), so coarser is cheaper.
:func:`~gearkit.blocking.blocking_atlas` spreads many contours over processes.
"""
from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass

import numpy as np

from gearkit.blocking.field import PairField
from gearkit.blocking.region import inside_polygons, polygon_area
from gearkit.blocking.tracing import trace
from gearkit.checks.limits import CheckLimits
from gearkit.curves import bracketed_root
from gearkit.errors import SpecError, require
from gearkit.families.involute import tool_label
from gearkit.pair.spec import PairSpec
from gearkit.pair.tooling import half_angle, section, thickness_coeff

__all__ = ["BlockingContour", "Line", "blocking_contour", "check_options", "default_window"]

DEFAULT_TOL = 1e-4  #: shift units (1e-4 m_n): far below what a picture or a cutter shows
TOL_RANGE = (1e-12, 1e-2)  #: allowed tracing tolerances (shift units)


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
        Closed polygons (first vertex repeated last) of the admissible region: outer boundaries
        counter-clockwise, holes clockwise (even-odd rule: :meth:`in_region`).
    empty_reason : str or None
        Why the region is empty (the binding lines at the best point), None when it is not.
    tol : float
        Accuracy (shift units) of every traced line: each of its points lies within ``1.25 tol``.
    seconds : float
        Wall time of the computation.
    evaluations : int
        Points at which the margins were evaluated.
    """

    def __init__(self, field, window, lines, region, empty_reason, tol, seconds, evaluations):
        self.field, self.window, self.lines, self.region = field, window, lines, region
        self.empty_reason, self.tol, self.seconds, self.evaluations = empty_reason, tol, seconds, evaluations

    @property
    def xtol(self) -> float:
        """The tracing tolerance under its old name (deprecated: use ``tol``)."""
        return self.tol

    @property
    def empty(self) -> bool:
        return not self.region

    @property
    def area(self) -> float:
        """Area of the admissible region (shift units squared; holes subtracted)."""
        return float(sum(polygon_area(p) for p in self.region))

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
        """True when :func:`~gearkit.checks.check_pair` passes the pair at (x1, x2): the check's own
        verdict, at the contour's limits (see :meth:`~gearkit.blocking.field.PairField.check`)."""
        return self.field.check(x1, x2)[0]

    def in_region(self, x1, x2):
        """Membership of points in the traced region polygons (even-odd), vectorised."""
        pts = np.column_stack([np.ravel(x1), np.ravel(x2)])
        out = inside_polygons(self.region, pts)
        return bool(out[0]) if np.ndim(x1) == 0 else out

    def binding(self, x1: float, x2: float) -> list:
        """Names of the lines (hard and quality) that (x1, x2) violates, hard ones first, then the
        failing findings of the check that no line maps (e.g. ``tip_interference``)."""
        ok, failing, why = self.field.check(x1, x2)
        if why:
            return ["no_pair"]
        m = self.margins(x1, x2)
        out = [n for n, v in m.items() if not (v >= 0)]
        mapped = {self.field.by_name[n].finding for n in out if n in self.field.by_name}
        out += [f for f in failing if f not in mapped and f not in out]
        hard = set(self.field.hard)
        return sorted(out, key=lambda n: (n not in hard, n))

    def mark(self, x1: float, x2: float) -> dict:
        """The ``marked`` object of the CLI: {x1, x2, inside, binding}."""
        return {"x1": float(x1), "x2": float(x2), "inside": self.contains(x1, x2), "binding": self.binding(x1, x2)}

    def recommend(self, criterion: str = "balanced", center_distance: float | None = None):
        """The recommended shifts by a named criterion (see :mod:`gearkit.blocking.recommend`)."""
        from gearkit.blocking.recommend import recommend
        return recommend(self, criterion, center_distance)

    # -- export ---------------------------------------------------------------------------------
    def to_dict(self, recommendation=None, marked=None, timing: bool = True) -> dict:
        """JSON-ready: pair, window, lines (name, points), region, recommendation, marked (and the
        wall time unless ``timing=False``: the rest is the same on every run)."""
        t = self.field.template
        tools = [tool_label(tt) for tt in t.tools]
        out = {
            "pair": {"z1": t.teeth1, "z2": t.teeth2, "kind": t.kind, "pressure_angle_deg": t.alpha_n_deg,
                     "helix_angle_deg": t.helix_angle_deg, "addendum": t.addendum, "tip_rule": t.tip_rule,
                     "tools": tools,
                     "cutter_teeth": getattr(t.tools[1], "teeth", None) if t.kind == "internal" else None},
            "window": list(self.window), "tol": self.tol,
            "lines": [{"name": ln.name, "code": ln.code, "label": ln.label, "hard": ln.hard, "finding": ln.finding,
                       "points": [c.tolist() for c in ln.components]} for ln in self.lines],
            "region": {"empty": self.empty, "reason": self.empty_reason, "area": self.area,
                       "polygons": [p.tolist() for p in self.region]},
        }
        if timing:
            out["seconds"] = self.seconds
        if recommendation is not None:
            out["recommendation"] = recommendation.to_dict()
        if marked is not None:
            out["marked"] = marked
        return out

    def save(self, path, recommendation=None, marked=None) -> None:
        """Write ``.png``, ``.svg`` (picture) or ``.json`` atomically (temp file + rename)."""
        from gearkit.blocking.plot import save
        save(self, path, recommendation, marked)


def check_options(tol: float | None = None, points: int | None = None, window=None) -> float:
    """The tracing tolerance ``tol`` (None: ``DEFAULT_TOL``) once ``tol``, ``points`` and a user
    ``window`` are checked against their ranges (``SpecError`` naming the field): what
    :func:`blocking_contour` checks before any work, for callers that check once for many pairs.

    >>> check_options(), check_options(1e-3, 40, (0, 1, 0, 1))
    (0.0001, 0.001)
    """
    tol = DEFAULT_TOL if tol is None else tol
    require(isinstance(tol, float) and TOL_RANGE[0] <= tol <= TOL_RANGE[1], "tol",
            f"{tol!r} must be in [{TOL_RANGE[0]:g}, {TOL_RANGE[1]:g}] (shift units)")
    require(points is None or (isinstance(points, int) and 20 <= points <= 5000), "points",
            f"{points!r} must be in [20, 5000]")
    if window is not None:
        _checked_window(window)
    return tol


def _checked_window(window) -> tuple:
    try:
        win = tuple(float(v) for v in window)
    except (TypeError, ValueError):
        raise SpecError("window", f"{window!r} must be four numbers (x1_lo, x1_hi, x2_lo, x2_hi)") from None
    require(len(win) == 4 and all(math.isfinite(v) and -3.0 <= v <= 3.0 for v in win)
            and win[0] < win[1] and win[2] < win[3], "window",
            f"{win!r} must be (x1_lo, x1_hi, x2_lo, x2_hi) within [-3, 3], lo < hi")
    return win


def blocking_contour(pair: PairSpec, *, window=None, limits: CheckLimits = CheckLimits(), tip_levels=(0.25, 0.4),
                     contact_levels=(1.2,), center_distances=(), tol: float | None = None,
                     points: int | None = None, lines=None, xtol: float | None = None) -> BlockingContour:
    """Compute the blocking contour of ``pair`` (its shifts are ignored).

    Parameters
    ----------
    pair : PairSpec
        External or internal pair (an internal one with its shaper, ``tool2``).
    window : (x1_lo, x1_hi, x2_lo, x2_hi) or None
        The plotted part of the plane; None: :func:`default_window`.
    limits, tip_levels, contact_levels, center_distances
        See :class:`~gearkit.blocking.field.PairField`.
    tol : float
        Accuracy of every traced line in shift units, in [1e-12, 1e-2] (default ``DEFAULT_TOL``,
        1e-4): every vertex within ``tol / 4`` of its line, every chord within ``tol``.
    points : int or None
        Also cap the chords at the window's diagonal / ``points`` (smoother pictures at coarse
        tolerances); None: the tolerance alone sets the vertices.
    lines : iterable of str or None
        Names of the lines to trace (default all); the region is always traced.
    xtol : float
        Deprecated name of ``tol``.

    Returns
    -------
    BlockingContour

    Examples
    --------
    >>> c = blocking_contour(PairSpec(13, 16, 1.0), tol=1e-4, lines=["pointing.1"])
    >>> c.contains(0.5, 0.3), c.in_region(0.5, 0.3), c.in_region(1.5, 0.0)
    (True, True, False)
    """
    t0 = time.perf_counter()
    if xtol is not None:
        warnings.warn("blocking_contour: 'xtol' is deprecated, use 'tol'", DeprecationWarning, stacklevel=2)
        require(tol is None, "tol", "give tol or its deprecated name xtol, not both")
        tol = xtol
    tol = check_options(tol, points, window)
    field = PairField(pair, limits, tip_levels, contact_levels, center_distances)
    win = _checked_window(default_window(field) if window is None else window)
    field.x_ranges = ((win[0], win[1]), (win[2], win[3]))  # undercut form circles: interpolated
    field.exact_forms = False
    max_step = None if points is None else math.hypot(win[1] - win[0], win[3] - win[2]) / points
    wanted = [d for d in field.lines if lines is None or d.name in set(lines)]
    t = trace(field, win, [d.name for d in wanted], tol, max_step, region=True)
    lines_out = tuple(Line(d.name, d.code, d.label, d.hard, d.finding, tuple(t.lines[d.name])) for d in wanted)
    return BlockingContour(field, win, lines_out, t.region, t.reason, tol, time.perf_counter() - t0, t.evaluations)
