"""Pictures (matplotlib, Agg, imported lazily) and JSON export of a blocking contour.

The style follows the printed atlas charts: x1 across, x2 up, the admissible region shaded,
hard lines bold and labelled with their B-codes, quality lines thin and dashed, the tip-to-tip
contact-ratio reference lines dotted, the design point and the recommendation marked.
"""
from __future__ import annotations

import json
import os
import textwrap

import numpy as np

__all__ = ["figure", "save", "contact_sheet"]

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


def _sibling(style, k: int) -> dict:
    """The style of the ``k``-th (from 0) drawn hard line of a B-code several lines share: the code's
    colour, lightened for odd ``k``, and long dashes from ``k = 2`` on (bold, so no quality line's),
    so that no two entries of the legend look alike."""
    if k == 0:
        return style
    from matplotlib.colors import to_hex, to_rgb

    rgb = np.array(to_rgb(style["color"]))
    out = dict(style, color=to_hex(rgb + (1.0 - rgb) * 0.45) if k % 2 else style["color"])
    if k >= 2:
        out["ls"] = (0, (6, 1.5))
    return out


_METADATA = {".png": {"Software": None}, ".svg": {"Date": None}}  #: nothing that changes between runs
LABEL_SPOTS = (0.5, 0.35, 0.65, 0.2, 0.8, 0.1, 0.9, 0.27, 0.43, 0.57, 0.73, 0.05, 0.95)  #: where along a line
#: its label may go (fraction of its longest piece's vertices), in the order tried
LABEL_PAD = 2.0  #: pixels kept between a label's box and another label's or a marker's


def _short(line) -> str:
    """The on-line label: the B-code of a hard line (with its name where two lines share a code),
    a compact name for the others."""
    if line.hard:
        return line.code if line.code not in ("B6", "B") else f"{line.code} {line.name.split('.')[0]}"
    return (line.name.replace("tip_thickness.", "s_a").replace("contact_ratio_tip", "eps_tip")
            .replace("contact_ratio", "eps").replace("center_distance", "a_w"))


def _overlap(a, b) -> float:
    """Area (pixels^2) shared by two display boxes (matplotlib ``Bbox``)."""
    return max(0.0, min(a.x1, b.x1) - max(a.x0, b.x0)) * max(0.0, min(a.y1, b.y1) - max(a.y0, b.y0))


def _place_labels(fig, ax, labelled, markers) -> None:
    """Put each label of ``labelled`` (``[(text, points (n, 2), colour)]``) on its line where its box,
    as drawn, overlaps no label placed before it, no marker (``markers``: artists) and stays inside the
    axes: the first spot of ``LABEL_SPOTS`` along the line's points inside the window that does, else
    the spot overlapping least. Measured on the laid-out figure (its renderer: ``fig`` drawn without
    rendering first), not guessed from the text's length."""
    renderer = fig.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    taken = [m.get_window_extent(renderer).expanded(1.0, 1.0) for m in markers]
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    for text, pts, colour in labelled:
        inner = (pts[:, 0] > x0) & (pts[:, 0] < x1) & (pts[:, 1] > y0) & (pts[:, 1] < y1)
        cand = pts[inner] if inner.any() else pts
        label = ax.annotate(text, cand[0], fontsize=7, color=colour, zorder=3, ha="center", va="center",
                            bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.75))
        best = None
        for f in LABEL_SPOTS:
            p = cand[min(int(f * len(cand)), len(cand) - 1)]
            label.xy = label.xyann = p  # the point and the text on it
            box = label.get_window_extent(renderer).padded(LABEL_PAD)
            outside = box.width * box.height - _overlap(box, frame)
            cost = outside + sum(_overlap(box, t) for t in taken)
            if best is None or cost < best[0]:
                best = (cost, p, box)
            if cost == 0.0:
                break
        label.xy = label.xyann = best[1]
        taken.append(best[2])


EMPTY_CHARS = 90  #: characters per line of an empty region's reason under the title (the axes' width at 9 pt)
NO_PAIR_GRID = 121  #: nodes per side of the grid the no-pair area is first found on


def _no_pair(contour):
    """The window's no-pair area as ``(vertices, codes)`` of a matplotlib path, or None where a pair
    exists everywhere: the cells of a node grid filled where no pair exists, each vertex of that
    area's boundary moved from the middle of its grid edge onto the area's edge (found along that
    grid edge by :func:`~gearkit.blocking.edges.edge_point`), so the drawn edge is the area's own and
    not the grid's staircase.

    >>> from gearkit.blocking import blocking_contour
    >>> from gearkit.pair import PairSpec
    >>> verts, codes = _no_pair(blocking_contour(PairSpec(12, 30, 1.0), tol=1e-3))
    >>> verts.shape[1], int(codes[0])  # a path of points, starting with a move
    (2, 1)
    """
    import contourpy
    from gearkit.blocking.arrays import evaluator
    from gearkit.blocking.edges import edge_point

    x0, x1, y0, y1 = contour.window
    n = NO_PAIR_GRID
    xs, ys = np.linspace(x0, x1, n), np.linspace(y0, y1, n)
    F = evaluator(contour.field, [contour.field.hard[0]], None)  # NaN where no pair exists
    gx, gy = np.meshgrid(xs, ys)
    bad = np.isnan(F(np.column_stack([gx.ravel(), gy.ravel()]), np.zeros(gx.size, dtype=int))).reshape(gx.shape)
    if not bad.any():
        return None
    points, codes = contourpy.contour_generator(xs, ys, bad.astype(float), fill_type="OuterCode").filled(0.5, 2.0)
    if not points:
        return None
    verts, codes = np.concatenate(points), np.concatenate(codes)
    # a vertex between a node where a pair exists and one where none does lies in its grid edge's middle
    fx, fy = (verts[:, 0] - x0) / (x1 - x0) * (n - 1), (verts[:, 1] - y0) / (y1 - y0) * (n - 1)
    ix, iy = np.floor(fx).astype(int), np.floor(fy).astype(int)
    mid_x = (np.abs(fx - ix - 0.5) < 1e-6) & (np.abs(fy - np.rint(fy)) < 1e-6)  # on a grid edge along x
    mid_y = (np.abs(fy - iy - 0.5) < 1e-6) & (np.abs(fx - np.rint(fx)) < 1e-6)  # on a grid edge along y
    ja, ia = np.where(mid_x, np.rint(fy), iy).astype(int), np.where(mid_y, np.rint(fx), ix).astype(int)
    jb, ib = ja + mid_y, ia + mid_x
    sel = np.flatnonzero(mid_x | mid_y)
    ja, ia, jb, ib = ja[sel], ia[sel], jb[sel], ib[sel]
    cross = bad[ja, ia] != bad[jb, ib]
    sel, ja, ia, jb, ib = sel[cross], ja[cross], ia[cross], jb[cross], ib[cross]
    a_first = ~bad[ja, ia]  # order each edge from its node with a pair (a) to its node without (b)
    a = np.where(a_first[:, None], np.c_[xs[ia], ys[ja]], np.c_[xs[ib], ys[jb]])
    b = np.where(a_first[:, None], np.c_[xs[ib], ys[jb]], np.c_[xs[ia], ys[ja]])
    verts[sel] = edge_point(F, a, b, np.zeros(len(a), dtype=int), float(np.hypot(x1 - x0, y1 - y0)))
    return verts, codes


def _draw(ax, contour, nopair):
    """Draw ``contour``'s region, its no-pair area ``nopair`` (from :func:`_no_pair`) and its lines onto
    ``ax``; return the legend's handles and the lines to label (``[(text, points, colour)]``)."""
    from matplotlib.patches import Patch, PathPatch
    from matplotlib.path import Path

    handles = []
    if contour.region:
        verts = np.concatenate(contour.region)
        codes = np.concatenate([[Path.MOVETO] + [Path.LINETO] * (len(p) - 2) + [Path.CLOSEPOLY]
                                for p in contour.region])
        ax.add_patch(PathPatch(Path(verts, codes), facecolor="#fde0b2", edgecolor="none", alpha=0.8, zorder=0))
        handles.append(Patch(facecolor="#fde0b2", edgecolor="none", label="admissible (check passes)"))
    if nopair is not None:  # where no pair exists the lines end: say why
        ax.add_patch(PathPatch(Path(*nopair), facecolor="#d9d9d9", edgecolor="none", zorder=0))
        handles.append(Patch(facecolor="#d9d9d9", edgecolor="none", label="no pair (no tight mesh or no tooth)"))
    labelled = []
    sharing = {}  # hard lines drawn so far per B-code
    for ln in contour.lines:
        if not ln.components:
            continue
        st = _style(ln)
        if ln.hard:  # lines sharing a B-code (B6: jamming, trimming, tip sweep) drawn apart
            sharing[ln.code] = sharing.get(ln.code, -1) + 1
            st = _sibling(st, sharing[ln.code])
        for k, comp in enumerate(ln.components):
            h, = ax.plot(comp[:, 0], comp[:, 1], zorder=2 if ln.hard else 1, **st,
                         label=(f"{ln.code} {ln.name}" if ln.hard else ln.name) if k == 0 else None)
            if k == 0:
                handles.append(h)
        if ln.hard or ln.code in ("Q", "C"):
            labelled.append((_short(ln), max(ln.components, key=len), st["color"]))
    return handles, labelled


def figure(contour, recommendation=None, marked=None):
    """A matplotlib Figure of ``contour`` (Agg backend; nothing is shown): the window fitted, the
    legend beside the axes, one label per line placed apart, the markers on top."""
    import matplotlib
    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    x0, x1, y0, y1 = contour.window
    aspect = (y1 - y0) / (x1 - x0)
    width = 6.2
    height = min(max(width * aspect, 3.5), 9.0)
    fig = Figure(figsize=(width + 2.6, height + 0.9), dpi=120, layout="constrained")
    ax = fig.add_subplot(1, 1, 1)
    nopair = _no_pair(contour)
    handles, labelled = _draw(ax, contour, nopair)
    markers, star = [], None
    if recommendation is not None and recommendation.x1 is not None:
        # the star is only ever a point check_pair passes; a failing best point is a cross, said so
        ok = recommendation.passes
        h, = ax.plot([recommendation.x1], [recommendation.x2], marker="*" if ok else "X", ms=16 if ok else 11,
                     color="#d01c8b", mec="white", mew=0.8, ls="none", zorder=10,
                     label=(f"recommended ({recommendation.criterion})" if ok else
                            f"no recommendation ({recommendation.criterion}): the best point found fails the check"))
        handles.append(h)
        markers.append(h)
        star = h if ok else None
    if marked is not None:
        h, = ax.plot([marked["x1"]], [marked["x2"]], marker="o", ms=9, mfc="none", mec="k", mew=1.8, ls="none",
                     zorder=11, label="design point (%s)" % ("inside" if marked["inside"] else "outside"))
        handles.append(h)
        markers.append(h)
    t = contour.field.template
    kind = "internal" if contour.field.internal else "external"
    ax.set_title(f"Blocking contour: {kind} pair z1 = {t.teeth1}, z2 = {t.teeth2}, alpha_n = {t.alpha_n_deg:g} deg, "
                 f"beta = {t.helix_angle_deg:g} deg" + ("\n" + textwrap.fill(f"region empty: {contour.empty_reason}",
                                                                         EMPTY_CHARS) if contour.empty else ""),
                 fontsize=9)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_xlabel("x1 (pinion shift, normal coefficient)")
    ax.set_ylabel("x2 (%s shift)" % ("ring" if contour.field.internal else "wheel"))
    ax.grid(True, lw=0.3, color="#cccccc")
    ax.set_aspect("equal", adjustable="box")
    fig.legend(handles=handles, loc="outside right upper", fontsize=7, frameon=False)
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    FigureCanvasAgg(fig)
    fig.draw_without_rendering()  # the constrained layout and the equal aspect fix the axes' box
    if star is not None and contour.region:  # where the region about the star is thinner than the star: a zoom
        from gearkit.blocking.inset import add_inset

        def draw(a):  # the inset: the same picture without labels, the design point where it is
            _draw(a, contour, nopair)
            if marked is not None:
                a.plot([marked["x1"]], [marked["x2"]], marker="o", ms=7, mfc="none", mec="k", mew=1.4, ls="none",
                       zorder=11)
        card = add_inset(fig, ax, contour.region, star, draw)
        if card is not None:
            markers.append(card)
    _place_labels(fig, ax, labelled, markers)
    return fig


def save(contour, path, recommendation=None, marked=None) -> None:
    """Write ``path`` (.png, .svg or .json) atomically: a temporary file in the same folder, renamed."""
    from gearkit.errors import SpecError
    from gearkit.export import atomic_write

    path = os.fspath(path)
    ext = os.path.splitext(path)[1].lower()
    if ext not in (".png", ".svg", ".json"):
        raise SpecError("output", f"{path!r}: the file name must end in .png, .svg or .json")

    def write(tmp):
        with open(tmp, "wb") as fh:
            if ext == ".json":
                fh.write(json.dumps(contour.to_dict(recommendation, marked), indent=1, allow_nan=False).encode())
            else:
                figure(contour, recommendation, marked).savefig(fh, format=ext[1:], bbox_inches="tight",
                                                                metadata=_METADATA[ext])
    atomic_write(path, write)


SHEET_CELL = 0.62  #: inches per cell of the contact sheet
SHEET_MIN_WIDTH = 4.0  #: inches: a small sheet still has room for its axis labels and title
SHEET_MIN_HEIGHT = 3.2  #: inches, the same for the height (the wrapped title takes about one inch)
SHEET_PAD = 0.08  #: inches of white kept about the sheet's drawing
SHEET_TITLE_CHARS_PER_INCH = 16  #: characters of the 8 pt title per inch (its average glyph is ~4.5 pt wide)


def contact_sheet(records, z1s, z2s, path, template) -> None:
    """The atlas' contact sheet (PNG, atomically): one square per (z1, z2), its admissible region and
    the recommended point, every cell on one common scale (the union of the cells' windows, stated in
    the title, with dotted lines at x1 = 0 and x2 = 0 in each cell); a cross where no pair exists."""
    import matplotlib
    matplotlib.use("Agg")
    from matplotlib.figure import Figure
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path

    from gearkit.export import atomic_write

    col = {z: i for i, z in enumerate(z1s)}
    row = {z: j for j, z in enumerate(z2s)}
    verts, codes, stars, crosses, empties = [], [], [], [], []
    pad = 0.06
    wins = np.array([rec["contour"]["window"] for rec in records if "error" not in rec]).reshape(-1, 4)
    if len(wins):
        x0, x1, y0, y1 = wins[:, 0].min(), wins[:, 1].max(), wins[:, 2].min(), wins[:, 3].max()
    else:
        x0, x1, y0, y1 = -1.0, 1.0, -1.0, 1.0
    for rec in records:
        i, j = col[rec["z1"]], row[rec["z2"]]
        if "error" in rec:
            crosses.append((i + 0.5, j + 0.5))
            continue
        c = rec["contour"]

        def to_cell(p, i=i, j=j):
            p = np.asarray(p, dtype=float)
            return np.column_stack([i + pad + (1 - 2 * pad) * (p[:, 0] - x0) / (x1 - x0),
                                    j + pad + (1 - 2 * pad) * (p[:, 1] - y0) / (y1 - y0)])
        polys = c["region"]["polygons"]
        if not polys:
            empties.append((i + 0.5, j + 0.5))
        for poly in polys:
            q = to_cell(poly)
            verts.append(q)
            codes.append([Path.MOVETO] + [Path.LINETO] * (len(q) - 2) + [Path.CLOSEPOLY])
        r = c.get("recommendation") or {}
        if r.get("x1") is not None and r.get("passes"):
            stars.append(to_cell([[r["x1"], r["x2"]]])[0])
    n1, n2 = len(z1s), len(z2s)
    axes = []  # x1 = 0 and x2 = 0 in every cell (when inside the common window)
    for i in range(n1):
        for j in range(n2):
            if x0 < 0 < x1:
                u = i + pad + (1 - 2 * pad) * (0 - x0) / (x1 - x0)
                axes.append(([u, u], [j + pad, j + 1 - pad]))
            if y0 < 0 < y1:
                v = j + pad + (1 - 2 * pad) * (0 - y0) / (y1 - y0)
                axes.append(([i + pad, i + 1 - pad], [v, v]))
    width = max(SHEET_MIN_WIDTH, 1.2 + SHEET_CELL * n1)
    fig = Figure(figsize=(width, max(SHEET_MIN_HEIGHT, 1.0 + SHEET_CELL * n2)), dpi=100, layout="constrained")
    ax = fig.add_subplot(1, 1, 1)
    for i in range(n1 + 1):
        ax.axvline(i, color="#bbbbbb", lw=0.5)
    for j in range(n2 + 1):
        ax.axhline(j, color="#bbbbbb", lw=0.5)
    for u, v in axes:
        ax.plot(u, v, ":", color="#999999", lw=0.4)
    if verts:
        ax.add_patch(PathPatch(Path(np.concatenate(verts), np.concatenate(codes)), facecolor="#f4a582",
                               edgecolor="#b2182b", lw=0.4))
    if stars:
        s = np.array(stars)
        ax.plot(s[:, 0], s[:, 1], "*", color="#d01c8b", ms=4, zorder=5)
    for x, y in crosses:
        ax.plot([x], [y], "x", color="#999999", ms=5)
    for x, y in empties:
        ax.text(x, y, "empty", ha="center", va="center", fontsize=5, color="#b2182b")
    ax.set_xlim(0, n1)
    ax.set_ylim(0, n2)
    ax.set_xticks(np.arange(n1) + 0.5, [str(z) for z in z1s], fontsize=7)
    ax.set_yticks(np.arange(n2) + 0.5, [str(z) for z in z2s], fontsize=7)
    ax.tick_params(length=0)
    ax.set_aspect("equal")
    ax.set_xlabel("z1 (pinion teeth)")
    ax.set_ylabel("z2 (%s teeth)" % ("ring" if template.kind == "internal" else "wheel"))
    title = [f"Blocking atlas ({template.kind}, alpha_n = {template.alpha_n_deg:g} deg): admissible region "
             "of each pair, star = recommended, x = no pair",
             f"every cell on one scale: x1 from {x0:.2f} to {x1:.2f} (right), x2 from {y0:.2f} to {y1:.2f} (up); "
             "dotted: x1 = 0, x2 = 0"]
    columns = int(width * SHEET_TITLE_CHARS_PER_INCH)  # the title is wrapped to the figure, never cut off
    ax.set_title("\n".join(textwrap.fill(t, columns) for t in title), fontsize=8)
    # cropped to what is drawn: a sheet of one row or column leaves no empty bands about it
    atomic_write(path, lambda tmp: fig.savefig(tmp, format="png", metadata=_METADATA[".png"], bbox_inches="tight",
                                               pad_inches=SHEET_PAD))
