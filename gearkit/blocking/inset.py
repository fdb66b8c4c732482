"""The zoomed inset of a blocking picture about the recommended point.

Where the admissible region about the recommendation is thinner than the star that marks it (a
thin wedge of the region, or a corner the star sits on), the marker hides the region at the
picture's scale and a reader sees the star on white. Then :func:`add_inset` draws a second view about
the star, at a scale where the region's width there spans several (smaller) stars, with its box
marked on the main axes, at the place of the axes where least is drawn. The measure is
:func:`thickness`: the diameter of the widest disc inside the region whose centre the marker covers,
against the marker's size in shift units (:func:`marker_size`).

>>> import numpy as np
>>> square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]])
>>> round(thickness([square], (0.5, 0.5), 0.1), 2)  # a disc of diameter 1 fits about the centre
1.0
>>> round(thickness([square], (1.0, 0.5), 0.1), 2)  # on an edge: centres up to 0.1 inside
0.2
"""
from __future__ import annotations

import numpy as np

__all__ = ["THIN", "thickness", "marker_size", "add_inset"]

THIN = 0.9  #: the region is thin about the star where :func:`thickness` < THIN marker sizes (a star on a
#: straight edge of a wide region measures 1: no inset; on a corner under 128 degrees, or in a strip, it is thin)
DEPTH_NODES = 61  #: nodes per side of the grid of disc centres sampled under the marker
INSET_SIDE = 0.4  #: the inset's side, a fraction of the main axes' shorter side
INSET_MARKER = 10.0  #: points: the star's size in the inset
INSET_SPAN = 6.0  #: the region's thickness about the star spans this many inset stars
MIN_ZOOM = 3.0  #: the inset magnifies at least this much
SPOTS = 15  #: candidate places of the inset per side of the axes
FILL_WEIGHT = 0.05  #: a pixel of the region's shading counts this much of a pixel of a line
INK = 0.6  #: a pixel darker than this (smallest of its RGB, 0..1) is a line's or a label's
SHADE = 0.8  #: ... else darker than this, the region's shading (the no-pair grey, lighter, is free to cover)
MARGIN = 4.0  #: pixels kept between the inset's card and the axes' frame, and about the box it zooms
CARD_LEFT, CARD_BOTTOM, CARD_GAP = 22.0, 11.0, 3.0  #: points of the card beside the inset: its tick labels


def _depths(polygons, points) -> np.ndarray:
    """Distance of each of ``points`` (n, 2) to the nearest edge of ``polygons``."""
    a = np.concatenate([p[:-1] for p in polygons])
    d = np.concatenate([p[1:] for p in polygons]) - a
    length2 = np.einsum("ij,ij->i", d, d)
    best = np.full(len(points), np.inf)
    for k in range(0, len(a), 512):  # edges in blocks: (points x edges) stays small
        ak, dk, lk = a[k:k + 512], d[k:k + 512], length2[k:k + 512]
        rel = points[:, None, :] - ak[None]
        t = np.clip(np.einsum("pej,ej->pe", rel, dk) / np.where(lk > 0, lk, 1.0), 0.0, 1.0)
        gap = rel - t[..., None] * dk[None]
        best = np.minimum(best, np.sqrt(np.einsum("pej,pej->pe", gap, gap)).min(axis=1))
    return best


def thickness(polygons, point, radius: float) -> float:
    """Diameter (shift units) of the widest disc inside ``polygons`` (closed, even-odd) whose centre
    lies within ``radius`` of ``point``: centres sampled on a grid of ``DEPTH_NODES`` per side over
    that disc, each one's depth its distance to the nearest edge. 0 where no centre is inside."""
    from gearkit.blocking.region import inside_polygons

    if not polygons:
        return 0.0
    g = np.linspace(-radius, radius, DEPTH_NODES)
    gx, gy = np.meshgrid(g, g)
    offsets = np.column_stack([gx.ravel(), gy.ravel()])
    centres = offsets[np.einsum("ij,ij->i", offsets, offsets) <= radius * radius] + np.asarray(point, dtype=float)
    centres = centres[inside_polygons(polygons, centres)]
    return 2.0 * float(_depths(polygons, centres).max()) if len(centres) else 0.0


def marker_size(ax, line) -> float:
    """The size of ``line``'s marker (its ``markersize`` in points) in data units of ``ax`` along x, as
    the axes are laid out now (equal aspect: the same along y)."""
    pixels = line.get_markersize() * ax.figure.dpi / 72.0
    (u0, _), (u1, _) = ax.transData.transform([[0.0, 0.0], [1.0, 0.0]])
    return pixels / abs(u1 - u0)


def _place(fig, ax, width: float, height: float, keep) -> tuple:
    """The display box ``(x0, y0)`` of a ``width`` x ``height`` pixel box inside ``ax`` covering the
    least drawn (pixels of lines and labels, and a little for the region's shading, read off the
    figure rendered as it stands) and overlapping no box of ``keep`` (display ``Bbox``)."""
    fig.canvas.draw()
    img = np.asarray(fig.canvas.buffer_rgba(), dtype=float)[..., :3] / 255.0
    rows = img.shape[0]
    darkest = img.min(axis=2)
    cost = (darkest < INK) + FILL_WEIGHT * ((darkest < SHADE) & (darkest >= INK))
    table = np.zeros((cost.shape[0] + 1, cost.shape[1] + 1))
    table[1:, 1:] = cost.cumsum(axis=0).cumsum(axis=1)  # summed-area table: a box's sum in four reads
    frame = ax.get_window_extent()
    best = None
    for fy in np.linspace(0.0, 1.0, SPOTS):
        for fx in np.linspace(0.0, 1.0, SPOTS):
            x0 = frame.x0 + MARGIN + fx * (frame.width - width - 2 * MARGIN)
            y0 = frame.y0 + MARGIN + fy * (frame.height - height - 2 * MARGIN)
            if any(x0 < b.x1 and b.x0 < x0 + width and y0 < b.y1 and b.y0 < y0 + height for b in keep):
                continue
            c0, c1 = int(round(x0)), int(round(x0 + width))
            r0, r1 = rows - int(round(y0 + height)), rows - int(round(y0))  # image rows run downwards
            s = table[r1, c1] - table[r0, c1] - table[r1, c0] + table[r0, c0]
            if best is None or s < best[0]:
                best = (s, x0, y0)
    return None if best is None else best[1:]


def add_inset(fig, ax, polygons, star, draw):
    """Draw the zoomed inset about the recommendation's marker ``star`` (a ``Line2D`` of ``ax``) when
    the region ``polygons`` is thin about it (:data:`THIN`): the inset axes on a white card (with its
    tick labels), its box about the star marked on ``ax`` and joined to it. Return the card (a patch
    of ``ax``: what the line labels must keep clear of), or None where the region is not thin.
    ``draw(axes)`` draws the picture's region, shading and lines onto an axes. The figure must be laid
    out (``fig.draw_without_rendering()``)."""
    from matplotlib.patches import Rectangle
    from matplotlib.transforms import Bbox

    p = np.array([star.get_xdata()[0], star.get_ydata()[0]], dtype=float)
    size = marker_size(ax, star)
    t = thickness(polygons, p, size / 2)
    if not polygons or t >= THIN * size:
        return None
    frame = ax.get_window_extent()
    side = INSET_SIDE * min(frame.width, frame.height)
    pt = fig.dpi / 72.0  # pixels per point
    ppu = star.get_markersize() * pt / size  # the main axes' pixels per shift unit
    half = side / (2 * MIN_ZOOM * ppu)
    if t > 0:  # the region's width about the star spans INSET_SPAN stars of the inset
        half = min(half, t * side / (2 * INSET_SPAN * INSET_MARKER * pt))
    indicator = Bbox(ax.transData.transform([p - min(half, size / 2), p + max(half, size / 2)]))
    left, bottom, gap = CARD_LEFT * pt, CARD_BOTTOM * pt, CARD_GAP * pt
    spot = _place(fig, ax, side + left + 2 * gap, side + bottom + 2 * gap, [indicator.padded(MARGIN)])
    if spot is None:
        return None
    to_axes = ax.transAxes.inverted()
    (c0, c1), (c2, c3) = to_axes.transform([spot, (spot[0] + side + left + 2 * gap, spot[1] + side + bottom + 2 * gap)])
    # above the lines (zorder 1, 2) and their labels (3), below the star and the mark (10, 11), which it never covers
    card = Rectangle((c0, c1), c2 - c0, c3 - c1, transform=ax.transAxes, facecolor="white", edgecolor="#999999",
                     lw=0.6, zorder=4.5)
    ax.add_patch(card)
    (b0, b1), (b2, b3) = to_axes.transform([(spot[0] + gap + left, spot[1] + gap + bottom),
                                            (spot[0] + gap + left + side, spot[1] + gap + bottom + side)])
    inset = ax.inset_axes([b0, b1, b2 - b0, b3 - b1], zorder=5)
    draw(inset)
    inset.plot([p[0]], [p[1]], marker=star.get_marker(), ms=INSET_MARKER, color=star.get_color(), mec="white",
               mew=0.6, ls="none", zorder=10)
    inset.set_xlim(p[0] - half, p[0] + half)
    inset.set_ylim(p[1] - half, p[1] + half)
    inset.set_aspect("equal", adjustable="box")
    inset.tick_params(labelsize=6, length=2, pad=1)
    inset.locator_params(nbins=4)
    inset.set_facecolor("white")
    ax.indicate_inset_zoom(inset, edgecolor="#333333", alpha=0.9)
    return card
