"""Issue 19: the blocking contour's contract -- the region is the map of check_pair, lines within
2 tol of a much finer trace with the same topology, recommendations that check_pair passes --
with the issue's reproducers as regression tests.

Tolerances: ``TOL`` is the tracing tolerance of the contours under test; the contract is that every
point of a traced line lies within ``CONTRACT * tol`` of the exact line (``CONTRACT = 2``). A random
point closer than ``CONTRACT * tol`` to the region's boundary may fall on either side (the polygon is
exact only to that distance), so the property tests skip such points (a handful at most).
"""
import os
from dataclasses import replace

import numpy as np
import pytest

from gearkit.blocking import blocking_contour
from gearkit.blocking.arrays import margins
from gearkit.blocking.field import PairField
from gearkit.checks import check_pair
from gearkit.curves import polyline_self_intersections
from gearkit.distances import distances_to_polyline
from gearkit.errors import SpecError
from gearkit.pair import PairSpec
from gearkit.families.involute import BasicRack, ShaperCutter

TOL = 1e-4
CONTRACT = 2.0
SAMPLES = 30  #: random points per contour in the property tests (each costs one check_pair, ~15 ms)


def _check_passes(spec, x1, x2) -> bool:
    """The verdict of check_pair itself (generated gears) on ``spec`` at shifts (x1, x2)."""
    try:
        return check_pair(replace(spec, shift1=float(x1), shift2=float(x2))).ok
    except SpecError:
        return False


def _boundary_distance(contour, p) -> float:
    return min((distances_to_polyline(np.asarray(p, float)[None], q)[0] for q in contour.region), default=np.inf)


# the issue's pairs: (spec, window) -- external and internal, default and user windows
CASES = {
    "13/16": (PairSpec(13, 16, 1.0), None),
    "57/130 ring": (PairSpec(57, 130, 1.0, kind="internal", tool2=ShaperCutter(28)), None),
    "16/84 window": (PairSpec(16, 84, 1.0), (-1.29, 0.29, -1.05, 1.28)),
    "16/59 ring": (PairSpec(16, 59, 1.0, kind="internal", tool2=ShaperCutter(19)), None),
    "42/65 window": (PairSpec(42, 65, 1.0), (-0.698, 1.364, -1.412, -0.948)),
    "45/55 ring": (PairSpec(45, 55, 1.0, kind="internal", tool2=ShaperCutter(30)), None),
}


@pytest.fixture(scope="module", params=sorted(CASES))
def case(request):
    spec, window = CASES[request.param]
    return request.param, spec, blocking_contour(spec, window=window, tol=TOL, lines=["sliding"])


def test_region_is_the_map_of_check_pair(case):
    """Property test: at random points of the window, the region's polygons (even-odd) hold exactly
    the points check_pair passes; the polygons are simple (no bow-ties)."""
    name, spec, c = case
    assert all(len(polyline_self_intersections(q)[0]) == 0 for q in c.region), name
    rng = np.random.default_rng(sum(map(ord, name)))
    w = c.window
    pts = np.column_stack([rng.uniform(w[0], w[1], SAMPLES), rng.uniform(w[2], w[3], SAMPLES)])
    inside = c.in_region(pts[:, 0], pts[:, 1])
    for p, r in zip(pts, inside):
        ok = _check_passes(spec, *p)
        if ok != r:
            assert _boundary_distance(c, p) <= CONTRACT * TOL, (name, p, ok)
        assert c.contains(*p) == ok  # membership (--mark) is the check's verdict


PROPERTY_PAIRS = int(os.environ.get("GEARKIT_BLOCKING_PAIRS", "3"))  #: random pairs of each kind (a long run:
#: GEARKIT_BLOCKING_PAIRS=40)
PROPERTY_TOL = 1e-3


def _random_pair(rng, internal: bool) -> PairSpec:
    if internal:
        z1 = int(rng.integers(12, 50))
        z2 = z1 + int(rng.integers(6, 60))
        return PairSpec(z1, z2, 1.0, kind="internal", tool2=ShaperCutter(int(rng.integers(12, min(40, z2 - 5)))))
    z1 = int(rng.integers(10, 60))
    return PairSpec(z1, int(rng.integers(z1, 120)), 1.0)


@pytest.mark.parametrize("internal", [False, True])
def test_region_is_the_map_of_check_pair_for_random_pairs(internal):
    """Property test over random pairs (external and internal, the ring with its shaper; check_pair also
    sweeps the tip corners of an internal pair through the mate's teeth): at random points of the window
    and beside the region's boundary, membership in the region is check_pair's verdict (points within
    2 tol of the boundary excepted), and ``contains`` (``--mark``) is that verdict exactly."""
    rng = np.random.default_rng(1919 + internal)
    for _ in range(PROPERTY_PAIRS):
        spec = _random_pair(rng, internal)
        c = blocking_contour(spec, tol=PROPERTY_TOL, lines=[])
        w = c.window
        pts = [np.column_stack([rng.uniform(w[0], w[1], 6), rng.uniform(w[2], w[3], 6)])]
        if c.region:
            edge = np.concatenate(c.region)
            pts.append(edge[rng.integers(0, len(edge), 6)] + rng.normal(0.0, 0.03, (6, 2)))
        pts = np.clip(np.concatenate(pts), [w[0], w[2]], [w[1], w[3]])
        inside = c.in_region(pts[:, 0], pts[:, 1])
        for p, r in zip(pts, inside):
            ok = _check_passes(spec, *p)
            assert c.contains(*p) == ok
            if ok != r:
                assert _boundary_distance(c, p) <= CONTRACT * PROPERTY_TOL, (spec, p, ok)


def test_issue_points_of_the_region():
    """(0.45, -0.80) of the 57/130 ring pair passes the check and lies in the region (it was left out);
    the 16/59 ring pair's region visits no vertex twice (it was a bow-tie at (1.3825, 1.0421))."""
    spec, _ = CASES["57/130 ring"]
    c = blocking_contour(spec, tol=TOL, lines=[])
    assert _check_passes(spec, 0.45, -0.80) and c.in_region(0.45, -0.80) and c.contains(0.45, -0.80)
    spec, _ = CASES["16/59 ring"]
    c = blocking_contour(spec, tol=TOL, lines=[])
    for q in c.region:
        assert len(np.unique(q[:-1], axis=0)) == len(q) - 1


def test_a_user_window_cuts_the_region_without_moving_it():
    """16/84 with a user window: the region is the default window's region cut by the window (the
    interference.1 crossing kept, no edge moved): the two agree at random points."""
    spec, window = CASES["16/84 window"]
    cut = blocking_contour(spec, window=window, tol=TOL, lines=[])
    whole = blocking_contour(spec, tol=TOL, lines=[])
    rng = np.random.default_rng(84)
    pts = np.column_stack([rng.uniform(window[0], window[1], 400), rng.uniform(window[2], window[3], 400)])
    a, b = cut.in_region(pts[:, 0], pts[:, 1]), whole.in_region(pts[:, 0], pts[:, 1])
    for p in pts[a != b]:
        assert min(_boundary_distance(cut, p), _boundary_distance(whole, p)) <= CONTRACT * TOL


README_PAIRS = {
    "13/16 with a centre distance line": (PairSpec(13, 16, 1.0), (14.8,)),
    "20/40 rack B": (PairSpec(20, 40, 1.0, tool1=BasicRack.iso53("B"), tool2=BasicRack.iso53("B")), ()),
    "46/49 ring": (PairSpec(46, 49, 1.0, kind="internal", tool2=ShaperCutter(20)), ()),
}
REFERENCE_TOL = 1e-6  #: the much finer trace: 1000 x finer than the coarsest tolerance tested


@pytest.fixture(scope="module", params=sorted(README_PAIRS))
def readme_reference(request):
    spec, cds = README_PAIRS[request.param]
    return spec, cds, blocking_contour(spec, tol=REFERENCE_TOL, center_distances=cds)


@pytest.mark.parametrize("tol", [1e-2, 1e-3])
def test_topology_at_coarse_tolerances(readme_reference, tol):
    """The README's pairs, every line and the region at a coarse ``tol`` against a trace at 1e-6: every
    traced point within 2 tol of the exact lines (the bench's measure) and every point of the finer
    trace within 2 tol of the traced lines (no gap), the same closed loops (no spurious loop), no
    component traced twice; coarser costs less."""
    from gearkit.bench.blocking import deviation, topology

    spec, cds, fine = readme_reference
    c = blocking_contour(spec, tol=tol, center_distances=cds)
    t = topology(c, fine)
    assert deviation(c) <= CONTRACT * tol
    assert t["gap"] <= CONTRACT * tol and t["extra"] <= CONTRACT * tol + CONTRACT * REFERENCE_TOL
    assert t["loops"][0] == t["loops"][1] and t["duplicates"] == 0
    assert c.evaluations < fine.evaluations


def test_topology_sees_a_missing_piece_and_a_duplicate():
    """The measure itself: a line with a piece removed shows the gap; a component given twice counts."""
    from dataclasses import replace as dc_replace

    from gearkit.bench.blocking import topology

    spec = PairSpec(13, 16, 1.0)
    c = blocking_contour(spec, tol=1e-3, lines=["pointing.1"])
    ln = c.line("pointing.1")
    q = ln.components[0]
    cut = dc_replace(ln, components=(q[: len(q) // 2],))
    doubled = dc_replace(ln, components=(q, q.copy()))
    c2 = blocking_contour(spec, tol=1e-3, lines=["pointing.1"])
    c2.lines = (cut,)
    gap = float(np.hypot(*(q[-1] - q[len(q) // 2 - 1])))
    assert topology(c2, c)["gap"] == pytest.approx(gap, rel=0.05)
    c2.lines = (doubled,)
    assert topology(c2, c)["duplicates"] == 2


def test_the_two_sides_of_a_sliver_are_no_duplicate():
    """The bench's duplicate count: the two sides of a sliver narrower than 2 tol (F of one sign between
    them, of the other beyond) are two lines; one line given twice, offset by less than the vertices'
    accuracy, is a duplicate."""
    from gearkit.bench.topology import duplicates

    tol, width = 1e-3, 5e-4  # the sliver 0 < y < width, narrower than 2 tol
    F = lambda p, k: p[:, 1] * (width - p[:, 1])  # noqa: E731  positive inside the sliver
    x = np.linspace(0.0, 1.0, 11)
    low = np.column_stack([x, np.zeros_like(x)])
    high = np.column_stack([x, np.full_like(x, width)])
    assert duplicates([low, high], tol) == 2  # distance alone: both flagged
    assert duplicates([low, high], tol, F, 0) == 0
    twice = low + [0.0, 0.1 * tol]
    assert duplicates([low, twice], tol, F, 0) == 2


def test_vectorised_margins_are_the_pair_formulas():
    """The array margins equal the scalar ones (pair_geometry and the check functions) to round-off
    wherever both exist, for an external, a helical and an internal pair."""
    specs = [PairSpec(13, 16, 1.0), PairSpec(12, 30, 2.0, helix_angle_deg=15.0),
             PairSpec(46, 49, 1.0, kind="internal", tool2=ShaperCutter(20))]
    rng = np.random.default_rng(15)
    for spec in specs:
        c = blocking_contour(spec, tol=1e-2, lines=[])
        f = c.field
        w = c.window
        x1, x2 = rng.uniform(w[0], w[1], 40), rng.uniform(w[2], w[3], 40)
        names = [d.name for d in f.lines]
        vec = margins(f, x1, x2, names)
        compared = 0
        for n in names:
            sc = np.array([f.margin(n, a, b) for a, b in zip(x1, x2)])
            both = np.isfinite(sc) & np.isfinite(vec[n])
            assert np.allclose(vec[n][both], sc[both], rtol=1e-9, atol=1e-11), n
            compared += both.sum()
        assert compared > 0.5 * len(names) * len(x1)


README_EXAMPLES = [
    (PairSpec(13, 16, 1.0), {}),
    (PairSpec(20, 40, 1.0, tool1=BasicRack.iso53("B"), tool2=BasicRack.iso53("B")), {"criterion": "strength"}),
    (PairSpec(13, 16, 1.0), {"criterion": "center_distance", "center_distance": 14.8}),
    (PairSpec(46, 49, 1.0, kind="internal", tool2=ShaperCutter(20)), {}),
]


@pytest.fixture(scope="module", params=range(len(README_EXAMPLES)),
                ids=["13/16", "20/40 iso53b strength", "13/16 a_w 14.8", "46/49 ring"])
def readme_example(request):
    """``(spec, criterion kw, contour, recommendation)`` of a README example, at the default tol."""
    spec, kw = README_EXAMPLES[request.param]
    cds = (kw["center_distance"],) if "center_distance" in kw else ()
    c = blocking_contour(spec, center_distances=cds)
    return spec, kw, c, c.recommend(**kw)


def test_readme_recommendations_pass_check_pair(readme_example):
    """The README's four blocking examples recommend points that check_pair itself passes (the
    internal one recommended x1 = 1.6705, x2 = 1.3878, which failed four checks)."""
    spec, kw, _, rec = readme_example
    assert rec.passes and _check_passes(spec, rec.x1, rec.x2)


def test_readme_pictures_are_readable(readme_example):
    """The README examples' pictures, measured as drawn (the renderer's boxes, not the placement's
    own arithmetic): no two line labels overlap (46/49: 'B tip_clearance' lay on 's_a2=0.25', 'B6
    exit_jamming' on 'sliding'), none covers the star or the mark or leaves the axes; the legend lies
    outside the axes, names each line once, and the hard lines' entries all look different (46/49's
    three B6 lines were one colour and style); the star and the mark are drawn above everything else."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from gearkit.blocking.plot import figure

    _, _, c, rec = readme_example
    w = c.window
    mark = c.mark(0.5, 0.3) if w[0] < 0.5 < w[1] and w[2] < 0.3 < w[3] else None
    fig = figure(c, rec, mark)
    FigureCanvasAgg(fig)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    ax = fig.axes[0]
    frame = ax.get_window_extent(renderer)
    labels = [(t.get_text(), t.get_window_extent(renderer)) for t in ax.texts]
    markers = [ln for ln in ax.lines if ln.get_marker() in ("*", "o")]
    assert len(markers) == 1 + (mark is not None) and len(labels) >= 5
    assert len({name for name, _ in labels}) == len(labels)  # one label per line, none twice
    for k, (name, box) in enumerate(labels):
        assert frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 and box.y1 <= frame.y1, name
        assert not [other for other, b in labels[k + 1:] if box.overlaps(b)], name
        assert not [m for m in markers if box.overlaps(m.get_window_extent(renderer))], name
    legend = fig.legends[0]
    assert not legend.get_window_extent(renderer).overlaps(frame)
    names = [t.get_text() for t in legend.get_texts()]
    assert len(names) == len(set(names))
    hard = [h for h in legend.legend_handles if h.get_label()[:1] == "B"]
    looks = {(h.get_color(), str(h.get_linestyle()), h.get_linewidth()) for h in hard}
    assert len(looks) == len(hard) == sum(1 for ln in c.lines if ln.hard and ln.components)
    top = max(a.get_zorder() for a in ax.get_children() if a not in markers)
    assert all(m.get_zorder() > top for m in markers)


def test_recommendation_in_a_user_window():
    """42/65 in the issue's window recommended (-0.434, -0.948), short on interference.1; 16/84 with a
    user window and the default criterion raised SpecError('criterion'). Both now pass check_pair."""
    for spec, window in (CASES["42/65 window"], CASES["16/84 window"]):
        rec = blocking_contour(spec, window=window, tol=TOL).recommend()
        assert rec.passes and _check_passes(spec, rec.x1, rec.x2)
        assert window[0] <= rec.x1 <= window[1] and window[2] <= rec.x2 <= window[3]


def test_field_form_circles_where_the_blank_tip_leaves_no_flank():
    """57/130 ring, x1 = -2.7255: the pinion's own blank tip lies below its form circle, the pair's
    (raised by the negative tip shortening) does not; the field reads the generated form circle the
    check reads (53.5738 mm, from check_pair's profile) instead of calling the pair invalid."""
    spec = PairSpec(57, 130, 1.0, kind="internal", tool2=ShaperCutter(28))
    f = PairField(spec)
    d = check_pair(replace(spec, shift1=-2.7255, shift2=1.357)).profiles[0].form_diameter
    assert f.form_diameter(1, -2.7255) == pytest.approx(d, abs=1e-9)


def test_the_bench_measure_sees_a_line_off_its_place():
    """The bench's achieved deviation (nearest exact zero of each vertex and chord middle) reads a
    line moved by 0.01 in x1 as about 0.01 off (the undercut onset line is x1 = const: exactly)."""
    from dataclasses import replace as dc_replace

    from gearkit.bench.blocking import deviation

    c = blocking_contour(PairSpec(13, 16, 1.0), tol=TOL, lines=["undercut.1"])
    assert deviation(c) <= CONTRACT * TOL
    ln = c.line("undercut.1")
    c.lines = (dc_replace(ln, components=tuple(q + [0.01, 0.0] for q in ln.components)),)
    assert deviation(c) == pytest.approx(0.01, rel=1e-6)


def test_the_bench_scan_sees_a_missing_piece_without_a_reference():
    """The bench's scan gap (exact zeros on scan lines across the window, no trace involved) reads a
    line cut short as the distance from its cut end to the farthest zero beyond it: for the undercut
    onset line x1 = x_min cut at the window's middle, the top scan line's zero."""
    from dataclasses import replace as dc_replace

    from gearkit.bench.blocking import scan_gap

    scans = 20
    c = blocking_contour(PairSpec(13, 16, 1.0), tol=TOL, lines=["undercut.1"])
    assert scan_gap(c, scans=scans, samples=50)[0] <= CONTRACT * TOL
    w, x_min = c.window, c.field.x_min[0]
    mid = 0.5 * (w[2] + w[3])
    ln = c.line("undercut.1")
    c.lines = (dc_replace(ln, components=(np.array([[x_min, w[2]], [x_min, mid]]),)),)
    d, name, at = scan_gap(c, scans=scans, samples=50)
    top = w[2] + scans / (scans + 1) * (w[3] - w[2])  # the highest scan line x2 = const
    assert name == "undercut.1" and at[1] == pytest.approx(top, abs=1e-12)
    assert d == pytest.approx(top - mid, rel=1e-9)


def test_the_bench_scan_sees_a_line_dipping_to_the_no_pair_edge_between_its_samples():
    """12/30: the sliding line's leg zeta1 = -zeta2 runs within 1.4e-6 of the no-pair edge for x1 in
    (0.293, 0.301) and meets it between 0.2963 and 0.2989, closer to it than any sample of a scan line
    (spacing 5e-3). With that stretch cut out of the trace (from x1 = 0.2925: the band's trace along the
    edge has a vertex at 0.2933, 3.5e-4 from the scan's zero, since its columns are tried between two where
    a margin on the edge may dip through zero), the scan's
    ladder of samples from the edge finds the zero the trace misses: on the scan line x1 = 0.29366, closer
    to the edge than 2e-6 (a pair exists there, none 2e-6 below)."""
    from dataclasses import replace as dc_replace

    from gearkit.bench.blocking import scan_gap

    c = blocking_contour(PairSpec(12, 30, 1.0), tol=1e-4, lines=["sliding"])
    assert scan_gap(c)[0] <= CONTRACT * 1e-4
    ln = c.line("sliding")
    kept = []
    for q in ln.components:
        out = (q[:, 0] > 0.2925) & (q[:, 0] < 0.3005)
        cuts = np.flatnonzero(np.diff(out.astype(int))) + 1
        kept += [p for p, o in zip(np.split(q, cuts), np.split(out, cuts)) if len(p) >= 2 and not o[0]]
    c.lines = (dc_replace(ln, components=tuple(kept)),)
    d, name, at = scan_gap(c)
    assert name == "sliding" and 0.2925 < at[0] < 0.3005 and d > 5 * 1e-4
    assert c.field.point(at[0], at[1]).valid and not c.field.point(at[0], at[1] - 2e-6).valid


def _zero_within(field, name, p, reach) -> bool:
    """True when the check's scalar margin ``name`` takes both signs within ``reach`` of ``p`` (circles of
    radius 1e-3 .. 1 reach around it)."""
    a = np.linspace(0.0, 2 * np.pi, 12, endpoint=False)
    ring = np.concatenate([r * reach * np.column_stack([np.cos(a), np.sin(a)]) for r in np.geomspace(1e-3, 1.0, 6)])
    signs = set()  # read from the widest circle in, and no further once both signs are seen
    return any(signs.add(np.sign(field.margin(name, *(p + o)))) or {1.0, -1.0} <= signs for o in ring[::-1])


@pytest.mark.parametrize("z1, z2, name, tol, saddle", [(55, 68, "interference.2", 1e-5, (-1.0, 1.0)),
                                                        (31, 39, "interference.1", 1e-6, (1.0, -1.0))])
def test_a_line_beside_the_interference_saddle_is_traced_to_tol(z1, z2, name, tol, saddle):
    """The interference margins have a saddle at (x1, x2) = (-1, 1) (interference.2) or (1, -1)
    (interference.1) where their value is the 1e-9 the check forgives: beside it the margin is nearly
    quadratic, and the slope a vertex got from the secant across its root's bracket (a grid edge, or the
    wide bracket of a vertex added by densify) was up to 13 times the slope at the root: a chord was
    estimated within tol that lay 2.1 tol (55/68 at 1e-5) and 2.2 tol (31/39 at 1e-6) from its line.
    Oracle: at the quarter points of every chord within 2e-3 of the saddle, the check's scalar margin
    takes both signs within 2 tol (on circles about the point)."""
    field = PairField(PairSpec(z1, z2, 1.0))
    c = blocking_contour(PairSpec(z1, z2, 1.0), tol=tol, lines=[name])
    checked = 0
    for q in c.line(name).components:
        for t in (0.25, 0.5, 0.75):
            p = q[:-1] + t * np.diff(q, axis=0)
            for v in p[np.max(np.abs(p - saddle), axis=1) < 2e-3]:
                assert _zero_within(field, name, v, CONTRACT * tol), v
                checked += 1
    assert checked >= 6
