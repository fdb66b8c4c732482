"""Page data of a blocking contour: the map of admissible shifts beside the recommended design in mesh.

The map draws the contour's region (shaded), its hard lines (bold, one colour per B-code) and
quality lines (dashed), the recommendation and a marked design point. The animation, the
solids and the findings are those of :func:`~gearkit.view.mesh.pair_view` for the pair at the
recommended shifts (or at the marked point when there is no recommendation).
"""
from __future__ import annotations

from dataclasses import replace

from gearkit.view.page import flat

#: colours of the hard lines by code (quality lines are grey and dashed)
LINE_COLORS = {"B1": "#b2182b", "B2": "#d6604d", "B3": "#2166ac", "B4": "#1b7837", "B5": "#5aae61",
               "B6": "#762a83", "B": "#444444"}


def contour_map(contour, recommendation=None, marked=None) -> dict:
    """The ``map`` object of a page from a :class:`~gearkit.blocking.BlockingContour`."""
    lines = []
    for ln in contour.lines:
        parts = [flat(c) for c in ln.components if len(c) > 1]
        if not parts:
            continue
        lines.append({"code": ln.code, "name": ln.name, "parts": parts, "dashed": not ln.hard,
                      "color": LINE_COLORS.get(ln.code, "#444444") if ln.hard else "#8a8a8a"})
    points = []
    if recommendation is not None:
        points.append({"x1": recommendation.x1, "x2": recommendation.x2, "label": "recommended", "color": "#d01c8b"})
    if marked is not None:
        points.append({"x1": marked["x1"], "x2": marked["x2"], "label": "marked", "color": "#111111"})
    return {"window": [float(v) for v in contour.window], "region": [flat(p) for p in contour.region],
            "lines": lines, "points": points}


def blocking_view(spec, contour, recommendation=None, marked=None, width: float | None = None,
                  cycles: int | None = None) -> dict:
    """Page data: the contour's map, and the pair ``spec`` at the recommended (or marked) shifts.

    Examples
    --------
    >>> from gearkit.blocking import blocking_contour
    >>> from gearkit.pair import PairSpec
    >>> spec = PairSpec(13, 16, 1.0)
    >>> contour = blocking_contour(spec, points=40)
    >>> data = blocking_view(spec, contour, contour.recommend("balanced"), cycles=1)
    >>> sorted(data["map"]), data["anim"]["frames"]
    (['lines', 'points', 'region', 'window'], 48)
    """
    from gearkit.view.mesh import pair_view

    point = recommendation or (None if marked is None else type("P", (), marked))
    data = {}
    if point is not None:
        data = pair_view(replace(spec, shift1=float(point.x1), shift2=float(point.x2)), width=width, cycles=cycles)
        data["subtitle"] = (f"beside the map: the pair at the {'recommended' if recommendation else 'marked'} "
                            f"shifts x1 = {point.x1:.4f}, x2 = {point.x2:.4f}, its generated teeth meshed by the "
                            "contact simulation")
    t = contour.field.template
    data["title"] = (f"gearkit: blocking contour of the {t.kind} pair z1 = {t.teeth1}, z2 = {t.teeth2}, "
                     f"alpha_n = {t.alpha_n_deg:g} deg")
    data.setdefault("findings", [])
    data.setdefault("parts3d", [])
    summary = [["region", "EMPTY: " + str(contour.empty_reason) if contour.empty else
                f"{len(contour.region)} polygon(s)"]]
    if recommendation is not None:
        summary.append(["recommendation", f"x1 = {recommendation.x1:.4f}, x2 = {recommendation.x2:.4f}: "
                        f"{recommendation.reason}"])
    if marked is not None:
        summary.append(["marked point", f"x1 = {marked['x1']:g}, x2 = {marked['x2']:g}: "
                        + ("inside" if marked["inside"] else "OUTSIDE (" + ", ".join(marked["binding"]) + ")")])
    data["summary"] = summary + data.get("summary", [])
    data["map"] = contour_map(contour, recommendation, marked)
    return data
