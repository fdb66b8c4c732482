"""Pictures (matplotlib, Agg, imported lazily) and JSON export of a blocking contour.

The style follows the printed atlas charts: x1 across, x2 up, the admissible region shaded,
hard lines bold and labelled with their B-codes, quality lines thin and dashed, the tip-to-tip
contact-ratio reference lines dotted, the design point and the recommendation marked.
"""
from __future__ import annotations

import json
import os
import tempfile

__all__ = ["figure", "save"]

_COLOURS = {"B1": "#b2182b", "B2": "#d6604d", "B3": "#2166ac", "B4": "#1b7837", "B5": "#5aae61",
            "B6": "#762a83", "B": "#444444"}


def _style(line):
    if line.hard:
        return dict(color=_COLOURS.get(line.code, "#000000"), lw=1.8, ls="-")
    if line.code == "R":
        return dict(color="#2166ac", lw=0.8, ls=":")
    if line.code == "C":
        return dict(color="#8c510a", lw=1.0, ls="-.")
    if line.name.startswith("undercut"):
        return dict(color="#7f7f7f", lw=1.0, ls="--")
    if line.name == "sliding":
        return dict(color="#e08214", lw=1.2, ls="-")
    return dict(color="#555555", lw=0.8, ls="--")


def figure(contour, recommendation=None, marked=None):
    """A matplotlib Figure of ``contour`` (Agg backend; nothing is shown)."""
    import matplotlib
    matplotlib.use("Agg")
    from matplotlib.figure import Figure
    from matplotlib.patches import Polygon

    fig = Figure(figsize=(7.5, 7.0), dpi=120)
    ax = fig.add_subplot(1, 1, 1)
    x0, x1, y0, y1 = contour.window
    for poly in contour.region:
        ax.add_patch(Polygon(poly, closed=True, facecolor="#fde0b2", edgecolor="none", alpha=0.8, zorder=0))
    for ln in contour.lines:
        st = _style(ln)
        for k, comp in enumerate(ln.components):
            ax.plot(comp[:, 0], comp[:, 1], zorder=2 if ln.hard else 1,
                    label=(f"{ln.code} {ln.name}" if ln.hard else ln.name) if k == 0 else None, **st)
            if len(comp) >= 2 and (ln.hard or ln.code == "Q"):
                p = comp[len(comp) // 2]
                ax.annotate(ln.code if ln.hard else ln.name.replace("tip_thickness.", "s_a").replace(
                    "contact_ratio", "eps"), p, fontsize=7, color=st["color"], zorder=3,
                    xytext=(3, 3), textcoords="offset points")
    if recommendation is not None:
        ax.plot([recommendation.x1], [recommendation.x2], marker="*", ms=14, color="#d01c8b", ls="none",
                label=f"recommended ({recommendation.criterion})", zorder=4)
    if marked is not None:
        ax.plot([marked["x1"]], [marked["x2"]], marker="o", ms=8, mfc="none", mec="k", mew=1.5, ls="none",
                label="design point (%s)" % ("inside" if marked["inside"] else "outside"), zorder=4)
    t = contour.field.template
    kind = "internal" if contour.field.internal else "external"
    ax.set_title(f"Blocking contour: {kind} pair z1 = {t.teeth1}, z2 = {t.teeth2}, alpha_n = {t.alpha_n_deg:g} deg, "
                 f"beta = {t.helix_angle_deg:g} deg" + ("\n(region empty)" if contour.empty else ""), fontsize=9)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_xlabel("x1 (pinion shift, normal coefficient)")
    ax.set_ylabel("x2 (%s shift)" % ("ring" if contour.field.internal else "wheel"))
    ax.grid(True, lw=0.3, color="#cccccc")
    ax.set_aspect("equal", adjustable="box")
    ax.legend(fontsize=6, loc="upper right", framealpha=0.9)
    fig.tight_layout()
    return fig


def save(contour, path, recommendation=None, marked=None) -> None:
    """Write ``path`` (.png, .svg or .json) atomically: a temporary file in the same folder, renamed."""
    from gearkit.errors import SpecError

    path = os.fspath(path)
    ext = os.path.splitext(path)[1].lower()
    if ext not in (".png", ".svg", ".json"):
        raise SpecError("output", f"{path!r}: the file name must end in .png, .svg or .json")
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(suffix=ext, prefix=".gearkit-", dir=folder)
    try:
        with os.fdopen(fd, "wb") as fh:
            if ext == ".json":
                fh.write(json.dumps(contour.to_dict(recommendation, marked), indent=1, allow_nan=False).encode())
            else:
                figure(contour, recommendation, marked).savefig(fh, format=ext[1:])
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
