"""One self-contained HTML page: the template, the viewer script and the data, inlined.

The page (``assets/page.html``) holds four panels: the 2D mesh animated with the transmission
error trace under it, a 3D view of the solids (WebGL, orbit controls), a map (blocking
contours) and the design check's findings with a table of values. ``assets/viewer.js`` draws
them from one JSON object; nothing is fetched at view time.

The data (all lengths mm, angles rad):

* ``title``, ``subtitle``; ``summary``: [[label, text]]; ``findings``: [{status, id, message}]
* ``anim`` (optional): ``frames``, ``fps``, ``caption``; ``bodies``: [{name, color, fill,
  loops: [flat x, y list], poses: [[angle, x, y]] per frame (the body's own frame turned by
  angle, then moved to (x, y)), mark: [x, y] a radial line}]; ``contacts``: per frame a flat
  x, y list; ``path``: flat x, y list; ``trace``: {label, xlabel, x, y} over one cycle
  (frame ``f`` marks ``f mod len(x)``); ``bounds`` / ``focus`` (optional): the view and the
  double-click zoom [x, y, span]
* ``parts3d``: [{name, color, positions (base64 float32 xyz), indices (base64 uint32),
  body (optional): the index of the animated body whose pose moves it}]
* ``map`` (optional): {window: [x1 lo, x1 hi, x2 lo, x2 hi], region: [flat polygons],
  lines: [{code, name, color, dashed, parts: [flat polylines]}], points: [{x1, x2, label, color}]}

Any producer (a pair, a drive, a scene, a cam) that fills this object gets the page.
"""
from __future__ import annotations

import base64
import json
import math
from importlib import resources

import numpy as np

from gearkit.errors import SpecError
from gearkit.export import atomic_write

#: part colours, in order
COLORS = ("#5b7fb8", "#c08a3e", "#6a9a5b", "#9a5b8f", "#5b9a9a", "#a05050")


def _asset(name: str) -> str:
    return resources.files("gearkit.view").joinpath("assets", name).read_text(encoding="utf-8")


def flat(points, digits: int = 5) -> list:
    """``(n, 2)`` points as a flat rounded list (JSON size)."""
    p = np.asarray(points, dtype=float).reshape(-1)
    return [round(float(v), digits) for v in p]


def mesh_part(solid, color: str, body: int | None = None) -> dict:
    """A solid's triangles for the 3D view (single precision, base64)."""
    v, f = solid.arrays()
    part = {"name": solid.name, "color": color,
            "positions": base64.b64encode(np.ascontiguousarray(v, dtype="<f4").tobytes()).decode("ascii"),
            "indices": base64.b64encode(np.ascontiguousarray(f, dtype="<u4").tobytes()).decode("ascii")}
    if body is not None:
        part["body"] = int(body)
    return part


def findings_rows(findings) -> list:
    """[{status, id, message}] of :class:`~gearkit.checks.report.Finding` objects."""
    return [{"status": f.status, "id": f.id, "message": f.message} for f in findings]


def _clean(obj):
    """Replace non-finite floats (JSON has none) by None, recursively."""
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {k: _clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_clean(v) for v in obj]
    return obj


def render(data: dict) -> str:
    """The page's HTML text for ``data`` (see the module notes).

    Examples
    --------
    >>> html = render({"title": "demo", "findings": [], "parts3d": []})
    >>> html.startswith("<!DOCTYPE html>"), "http" in html.split("<script>")[-1][:200]
    (True, False)
    """
    if not isinstance(data, dict) or "title" not in data:
        raise SpecError("page", "the page data needs at least a title")
    text = json.dumps(_clean(data), separators=(",", ":"), allow_nan=False).replace("</", "<\\/")
    page = _asset("page.html")
    title = str(data["title"]).replace("&", "&amp;").replace("<", "&lt;")
    for key, value in (("$CSS", _asset("viewer.css")), ("$TITLE", title), ("$SCRIPT", _asset("viewer.js")),
                       ("$DATA", text)):
        page = page.replace(key, value, 1)
    return page


def write_page(path, data: dict):
    """Write the page to ``path`` (.html), atomically; returns the path."""
    if not str(path).lower().endswith((".html", ".htm")):
        raise SpecError("output", f"{str(path)!r}: a page is written as .html")
    text = render(data)
    return atomic_write(path, lambda tmp: open(tmp, "w", encoding="utf-8").write(text))
