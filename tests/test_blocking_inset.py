"""The zoomed inset of a blocking picture: drawn exactly where the admissible region about the
recommended star is thinner than the star (59/68, shaper 25: the star on the corner of a wedge between
interference.1 and interference.2, seen on white at the picture's scale), and nowhere else (the
external 20/40, the star well inside). The condition is recomputed here from the region's polygons by
a second method: disc centres on a polar grid under the marker, their depth the distance to the
nearest of the boundary's points resampled finely (a k-d tree), membership by matplotlib's path."""
import numpy as np
import pytest

from gearkit import ShaperCutter
from gearkit.blocking import blocking_contour
from gearkit.pair import PairSpec

TOL = 1e-3


@pytest.fixture(scope="module")
def internal():
    c = blocking_contour(PairSpec(59, 68, 1.0, kind="internal", tool2=ShaperCutter(25)), tol=TOL)
    return c, c.recommend()


@pytest.fixture(scope="module")
def external():
    c = blocking_contour(PairSpec(20, 40, 1.0), tol=TOL)
    return c, c.recommend()


def _star(ax):
    stars = [ln for ln in ax.lines if ln.get_marker() == "*"]
    assert len(stars) == 1
    return stars[0]


def _marker_in_units(fig, ax, line):
    """The marker's size (points) in shift units: the axes' pixel width over its x range."""
    x0, x1 = ax.get_xlim()
    return line.get_markersize() * fig.dpi / 72.0 / (ax.get_window_extent().width / (x1 - x0))


def _thickness(polygons, point, radius):
    """Diameter of the widest disc inside the region whose centre lies within ``radius`` of ``point``."""
    from matplotlib.path import Path
    from scipy.spatial import cKDTree

    step = radius / 400
    boundary = []
    for p in polygons:
        for a, b in zip(p[:-1], p[1:]):
            n = max(1, int(np.ceil(np.hypot(*(b - a)) / step)))
            boundary.append(a + np.linspace(0.0, 1.0, n, endpoint=False)[:, None] * (b - a))
    tree = cKDTree(np.concatenate(boundary))
    r, phi = np.meshgrid(np.linspace(0.0, radius, 80), np.linspace(0.0, 2 * np.pi, 240, endpoint=False))
    centres = np.column_stack([point[0] + (r * np.cos(phi)).ravel(), point[1] + (r * np.sin(phi)).ravel()])
    verts = np.concatenate(polygons)
    codes = np.concatenate([[Path.MOVETO] + [Path.LINETO] * (len(p) - 2) + [Path.CLOSEPOLY] for p in polygons])
    inside = Path(verts, codes).contains_points(centres)  # non-zero winding: holes run clockwise
    if not inside.any():
        return 0.0
    return 2.0 * float(tree.query(centres[inside])[0].max())


def _thin(fig, ax, contour, rec):
    from gearkit.blocking.inset import THIN

    size = _marker_in_units(fig, ax, _star(ax))
    return _thickness(contour.region, (rec.x1, rec.x2), size / 2) < THIN * size, size


@pytest.mark.parametrize("case, expected", [("internal", True), ("external", False)])
def test_inset_drawn_exactly_where_the_region_is_thinner_than_the_star(case, expected, request):
    from gearkit.blocking.plot import figure

    contour, rec = request.getfixturevalue(case)
    assert rec.passes
    fig = figure(contour, rec)
    ax = fig.axes[0]
    thin, size = _thin(fig, ax, contour, rec)
    assert thin == expected  # the two cases are what they are said to be
    assert len(ax.child_axes) == int(thin)
    if not thin:
        return
    inset = ax.child_axes[0]
    (a0, a1), (b0, b1) = inset.get_xlim(), inset.get_ylim()
    assert a0 < rec.x1 < a1 and b0 < rec.x2 < b1
    # at the inset's scale the region about the star (as measured under the main star) is several of
    # the inset's stars wide
    inset_size = _marker_in_units(fig, inset, _star(inset))
    assert _thickness(contour.region, (rec.x1, rec.x2), size / 2) >= 3.0 * inset_size
    # the zoomed box is marked on the main axes, the inset keeps clear of the star, inside the axes
    from matplotlib.inset import InsetIndicator

    assert any(isinstance(a, InsetIndicator) for a in ax.get_children())
    fig.draw_without_rendering()
    frame = ax.get_window_extent()
    box = inset.get_tightbbox()
    star_box = _star(ax).get_window_extent()
    assert frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 and box.y1 <= frame.y1
    assert not box.overlaps(star_box)
    legend = fig.legends[0].get_window_extent()
    assert legend.x0 >= frame.x1  # the legend stays outside
