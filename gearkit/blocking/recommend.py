"""Recommended shifts inside a blocking contour, by a named criterion, with the reason.

Criteria
--------
``balanced`` (default)
    On the line of equal specific sliding (|zeta1| at the start of the path = |zeta2| at its end),
    the point with the least sliding that meets the quality limits: no undercut, s_a >= the
    check's ``min_tip_thickness`` m_n on both gears, eps_alpha >= ``min_contact_ratio`` (and, for
    internal pairs, no trimming of the ring beyond O2N_u). Sliding falls as the shifts grow, so
    the point is where the first quality limit stops it.
``strength``
    The largest x1 + x2 (strongest teeth) meeting the same quality limits.
``center_distance``
    On the line of the given centre distance, the point nearest to equal sliding that meets the
    quality limits.

Every candidate is also inside the admissible region (the check does not fail there).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearkit.blocking.trace import axis_root
from gearkit.errors import SpecError, require

__all__ = ["CRITERIA", "Recommendation", "recommend"]

CRITERIA = ("balanced", "strength", "center_distance")


@dataclass(frozen=True)
class Recommendation:
    """Recommended shifts: the point, the criterion, the binding limit, the reason in words."""

    x1: float
    x2: float
    criterion: str
    binding: str | None
    reason: str
    sliding: float | None = None
    contact_ratio: float | None = None

    def to_dict(self) -> dict:
        return {"x1": self.x1, "x2": self.x2, "criterion": self.criterion, "binding": self.binding,
                "reason": self.reason, "sliding": self.sliding, "contact_ratio": self.contact_ratio}


def _quality_names(field) -> list:
    lim = field.limits
    names = [d.name for d in field.lines if d.hard and d.name != "tip_clearance.1" and d.name != "tip_clearance.2"]
    names += [n for n in ("undercut.1", "undercut.2", "trimming.nu") if n in field.by_name]
    for i in (1, 2):
        names.append(f"tip_thickness.{i}={lim.min_tip_thickness:g}")
    names.append(f"contact_ratio={lim.min_contact_ratio:g}")
    return names


def _worst(field, names, p):
    """(smallest margin, its name) over ``names`` at p; margins of levels not traced are computed."""
    pt = field.point(*p)
    if not pt.valid:
        return -math.inf, "no_pair"
    best = (math.inf, None)
    for n in names:
        if n not in field.by_name:  # a level not among the lines: evaluate it all the same
            pass
        v = pt.margin(n) if n in field.by_name else _level_margin(pt, n)
        if not (v >= best[0]):
            best = (v if math.isfinite(v) else -math.inf, n)
    return best


def _level_margin(pt, name):
    base, _, level = name.partition("=")
    g = pt.geometry((True, True))
    if base == "contact_ratio":
        return g.contact_ratio - float(level)
    i = int(base[-1])
    return g.gears[i - 1].tip_thickness_normal / pt.field.module - float(level)


def _refine(field, names, good, bad, line_f, xtol):
    """Bisect along the chord good -> bad for the last point meeting all ``names``, snapped to the line."""
    for _ in range(60):
        if np.hypot(*(bad - good)) <= xtol:
            break
        mid = 0.5 * (good + bad)
        if line_f is not None:
            t = bad - good
            k = 0 if abs(t[1]) >= abs(t[0]) else 1
            res = axis_root(line_f, mid, k, math.nan, 0.1 * xtol, float(np.hypot(*t)))
            if res is not None:
                mid = res[0]
        if _worst(field, names, mid)[0] >= 0:
            good = mid
        else:
            bad = mid
    return good


def _describe(contour, p, names) -> str:
    d = contour.field.by_name.get(names) if isinstance(names, str) else None
    return d.label if d is not None else str(names)


def recommend(contour, criterion: str = "balanced", center_distance: float | None = None) -> Recommendation:
    """The recommended point of ``contour`` by ``criterion`` (see the module notes)."""
    require(criterion in CRITERIA, "criterion", f"{criterion!r} is not one of {', '.join(CRITERIA)}")
    field = contour.field
    names = _quality_names(field)
    if contour.empty:
        raise SpecError("criterion", f"the admissible region is empty: {contour.empty_reason}")
    if criterion == "strength":
        return _strength(contour, names)
    if criterion == "center_distance":
        require(center_distance is not None and math.isfinite(center_distance) and center_distance > 0,
                "center_distance", "the criterion 'center_distance' needs a centre distance in mm")
        line = contour.center_distance_line(center_distance)
        return _along(contour, names, line, criterion, f"a_w = {center_distance:g} mm")
    return _along(contour, names, contour.line("sliding"), criterion, None)


def _sliding_value(field, p):
    g = field.point(*p).geometry((True, True))
    return abs(g.specific_sliding["start"][0]), abs(g.specific_sliding["end"][1]), g.contact_ratio


def _along(contour, names, line, criterion, fixed):
    field = contour.field
    best = None
    for comp in line.components:
        ok = np.array([_worst(field, names, p)[0] >= 0 for p in comp])
        for j in np.flatnonzero(ok):
            p = comp[j]
            s1, s2, eps = _sliding_value(field, p)
            key = (abs(s1 - s2), max(s1, s2)) if criterion == "center_distance" else (max(s1, s2),)
            if best is None or key < best[0]:
                best = (key, comp, j, ok)
    if best is None:
        where = "the equal-sliding line" if fixed is None else f"the line {fixed}"
        # fall back: the point of the line with the least violation
        cand = [(_worst(field, names, p), p) for comp in line.components for p in comp]
        if not cand:
            raise SpecError("criterion", f"{where} does not cross the window")
        (v, n), p = max(cand, key=lambda c: c[0][0])
        return Recommendation(float(p[0]), float(p[1]), criterion, n,
                              f"no point of {where} meets the quality limits; the least violation is at "
                              f"x1 = {p[0]:.4f}, x2 = {p[1]:.4f}, where {n} is short by {-v:.4g}")
    _, comp, j, ok = best
    p = comp[j]
    binding = None
    f_line = None
    if line.name == "sliding" or line.name.startswith("center_distance"):
        def f_line(x1, x2, _n=line.name):
            return field.margin(_n, x1, x2) if _n in field.by_name else _sliding_margin(field, x1, x2, _n)
    for nb in (j + 1, j - 1):  # the limit that stops the walk along the line
        if 0 <= nb < len(comp) and not ok[nb]:
            s_here = _sliding_value(field, p)
            s_there = _sliding_value(field, comp[nb])
            if criterion != "balanced" or max(s_there[:2]) < max(s_here[:2]):
                p = _refine(field, names, p.copy(), comp[nb].copy(), f_line, contour.xtol)
                binding = _worst(field, names, comp[nb])[1]
                break
    s1, s2, eps = _sliding_value(field, p)
    what = ("equal specific sliding |zeta1| = |zeta2| = %.4g at the ends of the path" % max(s1, s2)
            if criterion == "balanced" else f"on {fixed}, sliding |zeta1| = {s1:.4g}, |zeta2| = {s2:.4g}")
    lim = field.limits
    limit_words = (f"no undercut, s_a >= {lim.min_tip_thickness:g} m_n, eps_alpha >= {lim.min_contact_ratio:g}"
                   + (", ring not trimmed" if field.internal else ""))
    stop = (f"; the sliding falls as the shifts grow, and {binding} ({_describe(contour, p, binding)}) "
            "stops it here" if binding else "; no quality limit binds along the line")
    reason = f"criterion '{criterion}': {what}, with {limit_words}{stop}; eps_alpha = {eps:.4f}"
    return Recommendation(float(p[0]), float(p[1]), criterion, binding, reason, max(s1, s2), eps)


def _sliding_margin(field, x1, x2, name):
    base, _, level = name.partition("=")
    g = field.point(x1, x2).geometry()
    return (g.center_distance - float(level)) / field.module


def _strength(contour, names):
    field = contour.field
    best = None
    for ln in contour.lines:
        if ln.name not in names and not ln.name.startswith(("tip_thickness", "contact_ratio=")):
            continue
        for comp in ln.components:
            for p in comp:
                if best is not None and p[0] + p[1] <= best[0]:
                    continue
                v, _ = _worst(field, names, p)
                if v >= -10 * contour.xtol:
                    best = (p[0] + p[1], p, ln.name)
    if best is None:
        raise SpecError("criterion", "no point of the window meets the quality limits")
    _, p, name = best
    pt = field.point(*p)
    g = pt.geometry((True, True))
    reason = (f"criterion 'strength': the largest x1 + x2 = {p[0] + p[1]:.4f} (strongest teeth, largest centre "
              f"distance a_w = {g.center_distance:.4f} mm) with no undercut, s_a >= "
              f"{field.limits.min_tip_thickness:g} m_n and eps_alpha >= {field.limits.min_contact_ratio:g}; "
              f"it lies on {name} ({field.by_name[name].label})")
    return Recommendation(float(p[0]), float(p[1]), "strength", name, reason, None, g.contact_ratio)
