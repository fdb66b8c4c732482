"""Recommended shifts inside a blocking contour, by a named criterion, verified by the check.

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

Where the line does not cross the window, or no point of it meets the limits, the admissible
region itself is searched (a grid of its points) by the same criterion. Every candidate is
verified with :func:`~gearkit.checks.check_pair` at the contour's limits before it is returned;
when no candidate passes, the :class:`Recommendation` says so (``passes=False``) and why.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearkit.blocking.arrays import margins, sliding_ends
from gearkit.blocking.tracing import trace
from gearkit.errors import require

__all__ = ["CRITERIA", "Recommendation", "recommend"]

CRITERIA = ("balanced", "strength", "center_distance")
REGION_SAMPLES = 61  #: grid per side of the region search
CHECKS = 12  #: most candidates verified by the check before giving up
BISECTIONS = 50  #: steps of the walk to a quality limit


@dataclass(frozen=True)
class Recommendation:
    """Recommended shifts: the point, the criterion, the binding limit, the reason in words.

    ``passes`` is True when :func:`~gearkit.checks.check_pair` passes the pair at (x1, x2) (always,
    unless no candidate did: then x1, x2 is the best point found, or None in an empty region)."""

    x1: float | None
    x2: float | None
    criterion: str
    binding: str | None
    reason: str
    sliding: float | None = None
    contact_ratio: float | None = None
    passes: bool = True

    def to_dict(self) -> dict:
        return {"x1": self.x1, "x2": self.x2, "criterion": self.criterion, "binding": self.binding,
                "reason": self.reason, "sliding": self.sliding, "contact_ratio": self.contact_ratio,
                "passes": self.passes}


def quality_names(field) -> list:
    """The margins a recommendation must keep >= 0: the hard lines but the tip clearances, no
    undercut, no ring trimming beyond O2N_u, and the check's tip-thickness and contact-ratio limits."""
    lim = field.limits
    names = [d.name for d in field.lines if d.hard and not d.name.startswith("tip_clearance")]
    names += [n for n in ("undercut.1", "undercut.2", "trimming.nu") if n in field.by_name]
    names += [f"tip_thickness.{i}={lim.min_tip_thickness:g}" for i in (1, 2)]
    names.append(f"contact_ratio={lim.min_contact_ratio:g}")
    return names


def _worst(field, names, pts):
    """(smallest quality margin, index of its name) at each of ``pts`` (n, 2); -inf where no pair."""
    pts = np.asarray(pts, dtype=float).reshape(-1, 2)
    m = margins(field, pts[:, 0], pts[:, 1], names)
    stack = np.stack([np.where(np.isnan(m[n]), -np.inf, m[n]) for n in names])
    return stack.min(axis=0), stack.argmin(axis=0)


def _key(criterion, pts, s1, s2, field, center_distance):
    if criterion == "strength":
        return -(pts[:, 0] + pts[:, 1])
    if criterion == "center_distance":
        a = margins(field, pts[:, 0], pts[:, 1], [f"center_distance={center_distance:g}"])
        dev = np.abs(next(iter(a.values())))
        return dev * 1e3 + np.abs(s1 - s2)  # on the line first, then nearest to equal sliding
    return np.maximum(s1, s2)


def _walk(field, names, good, bad, tol):
    """Bisect the segment good -> bad for the last point meeting every quality limit."""
    for _ in range(BISECTIONS):
        if np.hypot(*(bad - good)) <= tol:
            break
        mid = 0.5 * (good + bad)
        if _worst(field, names, mid)[0][0] >= 0:
            good = mid
        else:
            bad = mid
    return good


def _line_points(contour, criterion, center_distance):
    if criterion == "strength":
        return []
    name = "sliding" if criterion == "balanced" else f"center_distance={center_distance:g}"
    try:
        return list(contour.line(name).components)
    except KeyError:
        return trace(contour.field, contour.window, [name], contour.tol).lines[name]


def _region_points(contour):
    w = contour.window
    gx, gy = np.meshgrid(np.linspace(w[0], w[1], REGION_SAMPLES), np.linspace(w[2], w[3], REGION_SAMPLES))
    pts = np.column_stack([gx.ravel(), gy.ravel()])
    return pts[contour.in_region(pts[:, 0], pts[:, 1])]


def recommend(contour, criterion: str = "balanced", center_distance: float | None = None) -> Recommendation:
    """The recommended point of ``contour`` by ``criterion`` (see the module notes).

    Examples
    --------
    >>> from gearkit.blocking import blocking_contour
    >>> from gearkit.pair import PairSpec
    >>> rec = recommend(blocking_contour(PairSpec(13, 16, 1.0), tol=1e-4, lines=["sliding"]))
    >>> rec.passes, round(rec.x1, 2), round(rec.x2, 2)
    (True, 0.46, 0.39)
    """
    require(criterion in CRITERIA, "criterion", f"{criterion!r} is not one of {', '.join(CRITERIA)}")
    if criterion == "center_distance":
        require(center_distance is not None and math.isfinite(center_distance) and center_distance > 0,
                "center_distance", "the criterion 'center_distance' needs a centre distance in mm")
        center_distance = float(center_distance)
    field = contour.field
    if contour.empty:
        return Recommendation(None, None, criterion, None, f"no recommendation: the admissible region is empty "
                              f"({contour.empty_reason})", passes=False)
    names = quality_names(field)
    tried = []
    for source in ("line", "region"):
        if source == "line":
            comps = _line_points(contour, criterion, center_distance)
            pts = np.concatenate(comps) if comps else np.zeros((0, 2))
        else:
            pts = _region_points(contour)
        if not len(pts):
            continue
        worst, which = _worst(field, names, pts)
        s1, s2, _ = sliding_ends(field, pts[:, 0], pts[:, 1])
        key = _key(criterion, pts, s1, s2, field, center_distance)
        ok = worst >= 0
        order = np.flatnonzero(ok)[np.argsort(key[ok], kind="stable")]
        if not order.size:
            tried.append((source, pts, worst, which))
            continue
        best = order[0]
        p = pts[best]
        binding = None
        cand = [p]
        if source == "line":
            nbrs = _neighbours(comps, best)
        elif criterion == "strength":  # on to the quality limit along x1 + x2
            w = contour.window
            nbrs = [p + min(w[1] - p[0], w[3] - p[1]) * np.ones(2)]
        else:
            nbrs = []
        for q in nbrs:
            wq, iq = _worst(field, names, q)
            if wq[0] >= 0:
                continue
            s_q = sliding_ends(field, [q[0]], [q[1]])
            if criterion == "balanced" and not max(s_q[0][0], s_q[1][0]) < key[best]:
                continue
            cand.insert(0, _walk(field, names, p.copy(), q.copy(), contour.tol))
            binding = names[iq[0]]
            break
        cand += [pts[i] for i in order[1:CHECKS]]
        for q in cand[:CHECKS]:
            if field.check(*q)[0]:
                return _passing(contour, criterion, q, binding if q is cand[0] else None, source, center_distance)
    return _failing(contour, criterion, names, tried)


def _neighbours(comps, index):
    k = index
    for c in comps:
        if k < len(c):
            return [c[j] for j in (k + 1, k - 1) if 0 <= j < len(c)]
        k -= len(c)
    return []


def _passing(contour, criterion, p, binding, source, center_distance):
    field = contour.field
    s1, s2, eps = (float(v[0]) for v in sliding_ends(field, [p[0]], [p[1]]))
    lim = field.limits
    limits = (f"no undercut, s_a >= {lim.min_tip_thickness:g} m_n, eps_alpha >= {lim.min_contact_ratio:g}"
              + (", ring not trimmed" if field.internal else ""))
    if criterion == "balanced":
        what = (f"equal specific sliding |zeta1| = |zeta2| = {max(s1, s2):.4g} at the ends of the path"
                if source == "line" else
                f"the equal-sliding line meets no admissible point of the window: the least sliding "
                f"max(|zeta1|, |zeta2|) = {max(s1, s2):.4g} in the region")
    elif criterion == "strength":
        what = f"the largest x1 + x2 = {p[0] + p[1]:.4f} (strongest teeth)"
    else:
        what = (f"on a_w = {center_distance:g} mm, sliding |zeta1| = {s1:.4g}, |zeta2| = {s2:.4g}" if source == "line"
                else f"the line a_w = {center_distance:g} mm meets no admissible point: the nearest point of the region")
    label = field.by_name[binding].label if binding in field.by_name else binding
    stop = (f"; {binding} ({label}) stops it here" if binding else "")
    reason = (f"criterion '{criterion}': {what}, with {limits}{stop}; eps_alpha = {eps:.4f}; "
              "check_pair passes it")
    return Recommendation(float(p[0]), float(p[1]), criterion, binding, reason, max(s1, s2), eps)


def _failing(contour, criterion, names, tried):
    """No candidate passes: the least violation of the quality limits, said with its reason."""
    field = contour.field
    best = None
    for source, pts, worst, which in tried:
        i = int(np.argmax(worst))
        if best is None or worst[i] > best[0]:
            best = (worst[i], pts[i], names[which[i]])
    if best is None:
        pts = _region_points(contour)
        if not len(pts):
            return Recommendation(None, None, criterion, None, "no recommendation: no sample of the region passes "
                                  "(the region is thinner than the search grid)", passes=False)
        worst, which = _worst(field, names, pts)
        i = int(np.argmax(worst))
        best = (worst[i], pts[i], names[which[i]])
    v, p, name = best
    ok, failing, why = field.check(*p)
    if ok:
        return Recommendation(float(p[0]), float(p[1]), criterion, name,
                              f"criterion '{criterion}': no admissible point meets the quality limits; the least "
                              f"violation is at x1 = {p[0]:.4f}, x2 = {p[1]:.4f}, where {name} is short by "
                              f"{-v:.4g}; check_pair passes it (with warnings)")
    return Recommendation(float(p[0]), float(p[1]), criterion, name,
                          f"no recommendation: no candidate passes check_pair; the best, x1 = {p[0]:.4f}, "
                          f"x2 = {p[1]:.4f}, fails {', '.join(failing) or why}", passes=False)
