"""Issue 19: lines inside the band beside the no-pair area, where the grid masks every cell
(gearkit.blocking.band).

Lines that meet the no-pair edge tangentially in (x1, x2) (the margins reading alpha_w vary as the
cube root of the distance to the edge, those reading gear 2's tip at its base circle as the square
root) ran inside the band of masked cells and were cut short there by up to 0.54 shift units.
Oracle: the exact zeros of the scalar margins (the check's own pair geometry, ``PairField.margin``)
on columns x1 = const, each sampled from the no-pair edge upwards (the edge found by bisection on
where the scalar margin is defined, then distances from it growing geometrically from 1e-12), every
sign change solved by brentq; each zero must lie within 2 tol of the traced line. A sign change
where |F| does not fall (a pole of the sliding margin) is none. Where the edge is steep (nearly
parallel to x2), the same on rows x2 = const running from the edge to the right.

An internal pair's no-pair edge has three parts: where inv alpha_w reaches 1e-9 (x1 - x2 large),
where no shaper setting cuts the ring's tooth (x2 low) and where gear 1's tip reaches its base
circle (x1 low). Its band was not traced at all: 46/49 (shaper z0 = 20) B3 stopped 1.41 short of
the edge, tip_clearance.1 2.75; 16/59 (z0 = 19) exit_jamming had no trace at all.
"""
import numpy as np
import pytest

from gearkit.blocking import blocking_contour
from gearkit.distances import distances_to_polyline
from gearkit.families.involute import ShaperCutter
from gearkit.pair import PairSpec

from edgezeros import row_crossings, zeros_from_edge

CONTRACT = 2.0  #: achieved / tol (issue 19)
COLUMNS = 80  #: columns x1 = const across the window
DISTANCES = np.geomspace(1e-12, 0.4, 160)  #: samples above the edge (shift units)


def _edge_zeros(field, name, window, rows=False, x1s=None):
    """Exact zeros of ``name`` on columns rising from the no-pair edge (see the module notes), at ``x1s``
    (default: ``COLUMNS`` across the window); ``rows``: on rows x2 = const running right from the edge
    instead."""
    if rows:
        zeros = _edge_zeros(lambda n, a, b: field.margin(n, b, a), name, window[2:] + window[:2])
        return zeros[:, ::-1]
    margin = field if callable(field) else field.margin
    if x1s is None:
        x1s = np.linspace(window[0], window[1], COLUMNS + 2)[1:-1]
    zeros = [[x1, y] for x1 in x1s
             for y in _zeros_from_edge(lambda x2: margin(name, x1, x2), window[2], window[3], window[3])]
    return np.array(zeros).reshape(-1, 2)


def _zeros_from_edge(f, lo, hi, top):
    """:func:`edgezeros.zeros_from_edge` with the samples of this file (above the edge, up to 0.4)."""
    return zeros_from_edge(f, lo, hi, top, DISTANCES)


_ZEROS = {}  #: the oracle's zeros by (oracle, spec, line, window): one pair's line traced at several tolerances


def _shared_zeros(oracle, spec, contour, name):
    """``oracle(contour.field, name, contour.window)``, worked out once for the cases that trace the same
    pair's line in the same window at other tolerances (the scalar margins do not depend on tol)."""
    key = (oracle.__name__, spec, name, tuple(contour.window))
    if key not in _ZEROS:
        _ZEROS[key] = oracle(contour.field, name, contour.window)
    return _ZEROS[key]


def _farthest(zeros, components):
    return float(np.min([distances_to_polyline(zeros, q) for q in components], axis=0).max())


CASES = [  # (z1, z2, line, tol): cut short in the band by 0.04 .. 0.38 before
    (12, 30, "interference.1", 1e-3),
    (12, 30, "contact_ratio_tip=1", 1e-3),
    (12, 30, "contact_ratio_tip=1.2", 1e-6),
    (20, 40, "contact_ratio_tip=1", 1e-4),
    (20, 40, "contact_ratio=1", 1e-4),
    # the sliding line (its margin |zeta1| - |zeta2| traced as the zeros of its two factors): 0.54 short on
    # 12/30 and 0.69 on 20/40 before
    (12, 30, "sliding", 1e-3),
    # its leg zeta1 = -zeta2 dips to the edge between two lattice columns (x1 0.2963 .. 0.2989), closer than
    # 1.4e-6 for 0.008 around: carried to where it meets it (7.6 tol short at 1e-4, 763 at 1e-6 before)
    (12, 30, "sliding", 1e-4),
    (12, 30, "sliding", 1e-6),
    (13, 16, "sliding", 1e-4),
    (20, 40, "sliding", 1e-4),
]


INTERNAL = [  # (z1, z2, shaper teeth, line, tol): the band was not traced (1.0e4 .. 2.8e6 tol short, or no trace)
    (46, 49, 20, "contact_ratio=1", 1e-4),
    (46, 49, 20, "tip_clearance.1", 1e-6),
    (46, 49, 20, "interference.2", 1e-3),
    (57, 130, 28, "contact_ratio=1", 1e-4),
    (57, 130, 28, "contact_ratio_tip=1.2", 1e-6),
    (16, 59, 19, "exit_jamming", 1e-4),
    (16, 59, 19, "interference.1", 1e-3),
    (16, 59, 19, "contact_ratio_tip=1", 1e-6),
]


@pytest.mark.parametrize("z1, z2, name, tol", CASES)
def test_a_line_running_along_the_no_pair_edge_is_traced_to_tol(z1, z2, name, tol):
    spec = PairSpec(z1, z2, 1.0)
    c = blocking_contour(spec, tol=tol, lines=[name])
    zeros = _shared_zeros(_edge_zeros, spec, c, name)
    assert len(zeros) >= 3, name  # the oracle sees the line beside the edge
    assert _farthest(zeros, c.line(name).components) <= CONTRACT * tol


def test_the_band_adds_no_duplicate_trace():
    """12/30 at tol 1e-4: no two components of one line run along each other (each zero traced once:
    the band's pieces are cut where they enter the grid's cells and joined to the grid's lines)."""
    from gearkit.bench.topology import duplicates
    from gearkit.blocking.arrays import evaluator

    c = blocking_contour(PairSpec(12, 30, 1.0), tol=1e-4)
    F = evaluator(c.field, [ln.name for ln in c.lines], c.window)
    for k, ln in enumerate(c.lines):
        assert duplicates(list(ln.components), c.tol, F, k) == 0, ln.name


STEEP = [  # (z1, z2, line, tol, on rows): the no-pair edge near x1 = -2.6 runs nearly parallel to x2; columns
    # x1 = const did not cross it and the line along it was cut short (485, 371, 215 tol at tol 1e-3 before)
    (54, 82, "interference.1", 1e-3, True),
    (53, 104, "interference.1", 1e-3, True),
    (52, 89, "interference.1", 1e-4, True),
    # edges at 100 to 110 degrees with the line 1e-8 .. 1e-5 from them: cut where the rows' band ends, or where
    # a lattice vertex's |F| did not fall at tol / 4, or where the line left the lattice under a chord between
    # two fibers' edge points (36, 30, 20 tol at 1e-3 and 2766 tol at 1e-5 before)
    (33, 78, "contact_ratio_tip=1.2", 1e-3, True),
    (48, 117, "contact_ratio_tip=1", 1e-3, True),
    (22, 103, "interference.2", 1e-3, True),
    (42, 85, "contact_ratio_tip=1.2", 1e-5, False),
]


@pytest.mark.parametrize("z1, z2, name, tol, rows", STEEP)
def test_a_line_along_a_steep_no_pair_edge_is_traced_to_tol(z1, z2, name, tol, rows):
    """The band is traced on rows x2 = const where the edge is steeper than 45 degrees in grid units (all
    lines traced: the lattice follows the edge of the first line's grid)."""
    c = blocking_contour(PairSpec(z1, z2, 1.0), tol=tol)
    zeros = _edge_zeros(c.field, name, c.window, rows=rows)
    assert len(zeros) >= 3, name
    assert _farthest(zeros, c.line(name).components) <= CONTRACT * tol


ALONG_CASES = [  # (z1, z2, line, tol, columns): where a band piece left the lattice beside the edge, short of
    # the line's end: 12/15's sliding leg zeta1 = -zeta2, 9e-5 .. 2.5e-4 above the edge, left the lattice
    # through its last row (a chord from the edge to the window's frame) at x1 = 0.3156 and runs on to the
    # frame at 0.3248 (6e-3 short); 12/30's tip-to-tip line reaches the edge at x1 = 0.7215, the band left
    # it at 0.7236 (2e-3 short)
    (12, 15, "sliding", 1e-3, (0.317, 0.319, 0.321, 0.323)),
    (12, 15, "sliding", 1e-5, (0.317, 0.319, 0.321, 0.323)),
    (12, 30, "contact_ratio_tip=1", 1e-4, (0.7218, 0.7222, 0.7226, 0.7230)),
    (12, 30, "contact_ratio_tip=1", 1e-6, (0.7218, 0.7222, 0.7226, 0.7230)),
    # 43/47's interference.1 runs 6e-5 .. 0 above the edge from x1 = -0.0795 to its touchdown at -0.0915: the
    # band's piece left the lattice through the edge's row at index 80 + 1.4e-14, not seen on that row, and was
    # not carried on (0.0146 short: 14.6 tol at 1e-3, 1463 at 1e-5 before)
    (43, 47, "interference.1", 1e-3, (-0.081, -0.084, -0.087, -0.090)),
    (43, 47, "interference.1", 1e-5, (-0.081, -0.084, -0.087, -0.090)),
]


@pytest.mark.parametrize("z1, z2, name, tol, x1s", ALONG_CASES)
def test_a_line_the_lattice_left_beside_the_edge_is_carried_to_its_end(z1, z2, name, tol, x1s):
    c = blocking_contour(PairSpec(z1, z2, 1.0), tol=tol, lines=[name])
    zeros = _edge_zeros(c.field, name, c.window, x1s=np.array(x1s))
    assert len(zeros) >= len(x1s)  # the oracle sees the line on every column
    assert _farthest(zeros, c.line(name).components) <= CONTRACT * tol


def _left_edge_zeros(field, name, window):
    """Exact zeros of ``name`` on rows x2 = const running right from the no-pair edge at the window's left
    side (an internal pair's rows end on its edge at the right too: each row's edge is bracketed from
    the left side to ``LEFT_REACH`` in, then sampled as on the columns)."""
    x2s = LEFT_ROWS_OF.get(name, np.linspace(window[2], window[3], LEFT_ROWS + 2)[1:-1])
    zeros = [[x, x2] for x2 in x2s
             for x in _zeros_from_edge(lambda x1: field.margin(name, x1, x2), window[0], window[0] + LEFT_REACH,
                                       np.inf)]
    return np.array(zeros).reshape(-1, 2)


LEFT_REACH = 0.5  #: the rows' brackets of the left edge: from the window's left side this far in
LEFT_ROWS = 30  #: rows x2 = const across the window from its left side
LEFT_ROWS_OF = {  # 57/130's tip interference (each zero about 200 tip sweeps) meets the left edge only in a loop
    # between x2 = -0.72 and -0.645, crossed twice by each of these rows (by one at -0.72)
    "tip_interference": np.linspace(-0.72, -0.65, 8),
}
LEFT = [  # (z1, z2, shaper teeth, line, tol): an internal pair's edge where x1 is about constant (57/130: gear 1
    # is cut no tooth below x1 = -2.948), which the columns never cross (411 .. 4.1e5 tol short before)
    (57, 130, 28, "contact_ratio_tip=1.2", 1e-3),
    (57, 130, 28, "contact_ratio_tip=1.2", 1e-6),
    (57, 130, 28, "tip_interference", 1e-4),
]


@pytest.mark.parametrize("z1, z2, z0, name, tol, left", [c + (False,) for c in INTERNAL] + [c + (True,) for c in LEFT])
def test_an_internal_pair_line_beside_the_no_pair_edge_is_traced_to_tol(z1, z2, z0, name, tol, left):
    """The exact zeros on columns rising from the edge below (INTERNAL), or on rows from the left side of
    the edge, where x1 is about constant (LEFT), within 2 tol of the traced line."""
    spec = PairSpec(z1, z2, 1.0, kind="internal", tool2=ShaperCutter(z0))
    c = blocking_contour(spec, tol=tol, lines=[name])
    zeros = _shared_zeros(_left_edge_zeros if left else _edge_zeros, spec, c, name)
    assert len(zeros) >= 3, name
    assert c.line(name).components, name
    assert _farthest(zeros, c.line(name).components) <= CONTRACT * tol


def _row_zeros(field, name, x2s, lo, hi):
    """Exact zeros of ``name`` on rows x2 = ``x2s`` running right from the no-pair edge between ``lo``
    (undefined) and ``hi`` (defined), up to ``hi``."""
    zeros = [[x, x2] for x2 in x2s for x in _zeros_from_edge(lambda x1: field.margin(name, x1, x2), lo, hi, hi)]
    return np.array(zeros).reshape(-1, 2)


CORNERS = [  # (z1, z2, line, tol, rows x2, right end of the rows): lines from beside the steep no-pair edge to the
    # window's top frame x2 = 3 (15/106: its bottom frame x2 = -3). 47/79's interference.1 ran on the grid up to the
    # row x2 = 2.875 and stopped there, 0.13 short of the frame (the band's end marked to go on was the grid line's
    # end within tol, not the same point: 52 tol at 1e-3, 5184 at 1e-5 before); 44/112's tip thickness line leaves
    # the edge near x1 = -2.31 and meets the frame at x1 = -2.14 through a cell whose grid piece (one chord beside
    # undefined nodes) was dropped: the band's piece was cut there (80 tol at 1e-3, 8025 at 1e-5 before); 34/105's
    # leaves the edge at (-1.983, 2.919), where the edge crosses one grid cell steeply and leaves through the top
    # frame while the frame's column crosses it twice: no lattice covered that cell and the line had no trace at
    # all; 47/76's pointing.2 runs from the edge at (-2.400, 2.956) to the frame at x1 = -2.222 in the top row of
    # cells, where the steep edge steps a grid column over: that cell was in neither lattice, no trace at all
    # either; 15/106's contact_ratio_tip=1.2 runs from the bottom frame at x1 = 0.550 up beside the edge, which
    # leaves through that frame in a cell whose right column was left to the next cell, itself not used (the edge
    # past the frame on both its sides): the line stopped 0.014 above the frame (12.8 tol at 1e-3, 1280 at 1e-5)
    (47, 79, "interference.1", 1e-3, np.linspace(2.88, 3.0, 7), -2.0),
    (47, 79, "interference.1", 1e-5, np.linspace(2.88, 3.0, 7), -2.0),
    (44, 112, "tip_thickness.2=0.25", 1e-3, np.linspace(2.955, 3.0, 7), -2.0),
    (44, 112, "tip_thickness.2=0.25", 1e-5, np.linspace(2.955, 3.0, 7), -2.0),
    (34, 105, "tip_thickness.2=0.25", 1e-3, np.linspace(2.925, 3.0, 7), -1.7),
    (34, 105, "tip_thickness.2=0.25", 1e-5, np.linspace(2.925, 3.0, 7), -1.7),
    (47, 76, "pointing.2", 1e-3, np.linspace(2.958, 3.0, 7), -2.0),
    (47, 76, "pointing.2", 1e-5, np.linspace(2.958, 3.0, 7), -2.0),
    (15, 106, "contact_ratio_tip=1.2", 1e-3, np.linspace(-3.0, -2.988, 7), 0.65),
    (15, 106, "contact_ratio_tip=1.2", 1e-5, np.linspace(-3.0, -2.988, 7), 0.65),
]


@pytest.mark.parametrize("z1, z2, name, tol, x2s, hi", CORNERS)
def test_a_line_beside_the_edge_is_traced_to_the_window_frame(z1, z2, name, tol, x2s, hi):
    c = blocking_contour(PairSpec(z1, z2, 1.0), tol=tol, lines=[name])
    zeros = _row_zeros(c.field, name, x2s, c.window[0], hi)
    assert len(zeros) >= len(x2s)  # the oracle sees the line on every row
    assert _farthest(zeros, c.line(name).components) <= CONTRACT * tol



FRAMED = [  # (z1, z2, shaper teeth, line, tol, rows x2, x1 bracketing the edge: no pair, a pair): an internal
    # pair's lines in a strip about 0.015 wide left of its steep straight no-pair edge up to the window's top frame
    # x2 = 0.1; the lattice's columns there end on their last row under the frame, and the lines stopped on them
    # at x2 = 0.092 and 0.089 (10.3 tol at 1e-3)
    (25, 49, 37, "interference.1", 1e-3, np.linspace(0.092, 0.0999, 6), (0.7, 0.5)),
    (25, 49, 37, "tip_interference", 1e-3, np.linspace(0.090, 0.0999, 6), (0.7, 0.5)),
    # 23/44's tip thickness line, 0.05 left of the edge under the frame, left the columns' lattice across the
    # corner of a cell with a node past the frame: the vertex on that cell's diagonal lies on no lattice edge
    # and was dropped, so the line's end was no end of the lattice's piece and nothing carried it on (0.0803,
    # 7.6 tol at 1e-3 before; the cells with a node past the frame are now left out whole)
    (23, 44, 35, "tip_thickness.1=0.4", 1e-3, np.linspace(0.081, 0.0999, 6), (0.6, 0.4)),
]


@pytest.mark.parametrize("z1, z2, z0, name, tol, x2s, bracket", FRAMED)
def test_a_line_beside_a_steep_edge_is_traced_to_the_frame_past_the_lattice(z1, z2, z0, name, tol, x2s, bracket):
    """The exact zeros on rows x2 = const running left from the edge (bracketed between the two x1 of
    ``bracket``) within 2 tol of the traced line."""
    c = blocking_contour(PairSpec(z1, z2, 1.0, kind="internal", tool2=ShaperCutter(z0)), tol=tol, lines=[name])
    lo, hi = -bracket[0], -bracket[1]
    zeros = np.array([[-t, x2] for x2 in x2s
                      for t in _zeros_from_edge(lambda t: c.field.margin(name, -t, x2), lo, hi, hi)])
    assert len(zeros) >= len(x2s)  # the oracle sees the line on every row
    assert _farthest(zeros, c.line(name).components) <= CONTRACT * tol


def test_a_line_nearer_the_edge_than_its_chords_root_is_solved_is_not_cut():
    """45/47 at tol 1e-5: the sliding leg zeta1 = zeta2 runs 2e-8 .. 7e-8 from the no-pair edge from x1 = -0.378
    to where it meets the edge at -0.3569, its factor going from -7.9 on the edge to 0 there. Each chord's root
    along its normal, solved to tol / 4, kept |F| high and was read as a jump: the chords were cut and the line
    lost between -0.377 and -0.360 (158 tol at 1e-5 before). The exact zeros on rows running right from the edge
    within 2 tol of the traced line."""
    tol = 1e-5
    c = blocking_contour(PairSpec(45, 47, 1.0), tol=tol, lines=["sliding"])
    x2s = np.linspace(-1.508, -1.524, 9)
    zeros = _row_zeros(c.field, "sliding", x2s, -0.5, -0.3)
    assert len(zeros) >= len(x2s)  # the oracle sees the line on every row
    assert _farthest(zeros, c.line("sliding").components) <= CONTRACT * tol


ISLANDS = [  # (spec, line, tol, columns x1): a line in a sliver along the edge shorter than the lattice's columns'
    # spacing: 28/80 z0 38's trimming.nu is negative from x1 = 0.2557 to 0.2677 and at most 6.5e-5 above the edge,
    # between two columns 0.0197 apart whose margins on the edge have one sign (no trace at all before); 24/107's
    # interference.1 is positive from x1 = 0.3119 along the edge to the window's bottom frame at 0.3211, its piece
    # on the lattice one chord 1e-6 long, carried on but dropped as a speck (275 tol at 1e-3 before)
    (PairSpec(28, 80, 1.0, kind="internal", tool2=ShaperCutter(38)), "trimming.nu", 1e-3, np.linspace(0.257, 0.267, 5)),
    (PairSpec(24, 107, 1.0), "interference.1", 1e-3, np.linspace(0.3125, 0.3205, 5)),
]


@pytest.mark.parametrize("spec, name, tol, x1s", ISLANDS)
def test_a_line_in_a_sliver_along_the_edge_between_two_columns_is_traced(spec, name, tol, x1s):
    """The exact zeros on columns rising from the edge through the sliver within 2 tol of the traced line."""
    c = blocking_contour(spec, tol=tol, lines=[name])
    zeros = _edge_zeros(c.field, name, c.window, x1s=x1s)
    assert len(zeros) >= len(x1s)  # the oracle sees the line on every column
    assert c.line(name).components, name
    assert _farthest(zeros, c.line(name).components) <= CONTRACT * tol


def test_a_band_run_beside_an_unrefined_grid_chord_is_that_line():
    """40/105 internal (shaper z0 33) at tol 1e-5: contact ratio 1 runs beside the no-pair edge, in and out
    of grid cells with an undefined corner. For a stretch the band's run lay 6 tol beside a grid chord (not
    refined yet) of the same line, was taken for another line, and took the grid line's end: the band's run
    beyond was left unjoined, and the line had a gap of 0.11 from (0.696, -0.611) to (0.773, -0.527). On rows
    across the gap, from x1 = 0.62 to the no-pair edge, the traced line crosses each row once, within 2 tol of
    the zero of the check's contact ratio margin (brentq), and check_pair passes 3 tol before it and fails 3 tol
    beyond."""
    import dataclasses

    from scipy.optimize import brentq

    from gearkit.checks import check_pair

    tol = 1e-5
    spec = PairSpec(40, 105, 1.0, kind="internal", tool2=ShaperCutter(33))
    c = blocking_contour(spec, tol=tol, lines=["contact_ratio=1"])
    for y in np.linspace(-0.61, -0.53, 9):
        xs = np.linspace(0.62, 0.84, 45)
        v = np.array([c.field.margin("contact_ratio=1", float(x), float(y)) for x in xs])
        xs, v = xs[np.isfinite(v)], v[np.isfinite(v)]  # up to the no-pair edge
        i = np.flatnonzero((v[:-1] >= 0) != (v[1:] >= 0))
        assert len(i) == 1, (y, v)
        exact = brentq(lambda x: c.field.margin("contact_ratio=1", x, float(y)), xs[i[0]], xs[i[0] + 1], xtol=1e-13)
        got = row_crossings(c.line("contact_ratio=1").components, float(y), xs[0], xs[-1])
        assert len(got) == 1 and abs(got[0] - exact) <= CONTRACT * tol, (y, exact, got)
        for x, ok in ((exact - 3 * tol, True), (exact + 3 * tol, False)):
            assert check_pair(dataclasses.replace(spec, shift1=float(x), shift2=float(y))).ok == ok, (x, y)



def test_a_band_run_past_the_end_of_a_grid_line_is_joined_to_it():
    """14/63 internal (shaper z0 38) at tol 1e-3: tip interference runs down to the no-pair edge near x1 = 0.4158,
    nearly parallel to x2. Its grid line ends at x2 = -0.5 on the side of a masked cell, 0.012 above the edge, its
    first chord (not refined yet) 0.09 long; the band's run on from there to the edge lay on the curve's way on from
    that chord's end, was read as beside the chord (the same line) and dropped: the trace stopped 6.2 tol short.
    On rows across that stretch, from x1 = 0.38 to 0.45 (no other zero of the margin there), the traced line crosses
    each row once, within 2 tol of the zero of the check's scalar tip interference margin (brentq)."""
    from scipy.optimize import brentq

    tol, name = 1e-3, "tip_interference"
    spec = PairSpec(14, 63, 1.0, kind="internal", tool2=ShaperCutter(38))
    c = blocking_contour(spec, tol=tol, lines=[name])
    for y in np.linspace(-0.5015, -0.5115, 5):
        def f(x):
            return c.field.margin(name, x, float(y))
        lo, hi = f(0.38), f(0.45)
        assert lo > 0 > hi, (y, lo, hi)
        exact = brentq(f, 0.38, 0.45, xtol=1e-12)
        got = row_crossings(c.line(name).components, float(y), 0.38, 0.45)
        assert len(got) == 1 and abs(got[0] - exact) <= CONTRACT * tol, (y, exact, got)


BENT = (58, 63, 16, 1e-7)  #: internal pair, shaper, tol: the sliding line bends beside the edge
BENT_ROWS = np.linspace(-0.96088, -0.96096, 5)  #: rows x2 = const across its band chord (the edge at -0.96231)
BENT_SPAN = (-0.8732, -0.8725)  #: where they cross the line (steep there), and no other line
BENT_SAMPLES = 15


def test_a_band_vertex_carries_the_slope_at_its_root():
    """58/63 (shaper z0 = 16) at tol 1e-7: a band vertex's |grad F| was the secant across its lattice edge,
    which reached towards the edge where F steepens (8029 and 10484 for 620 at two vertices of the sliding
    line 1.4e-3 above it); the chord between them, 4.57 tol off, was kept on its middle's estimate (0.35 tol).
    On rows across that chord every crossing of the traced line lies within 2 tol of a brentq zero of
    the scalar sliding margin and every zero has one."""
    from scipy.optimize import brentq

    z1, z2, z0, tol = BENT
    c = blocking_contour(PairSpec(z1, z2, 1.0, kind="internal", tool2=ShaperCutter(z0)), tol=tol, lines=["sliding"])
    comps = c.line("sliding").components
    lo, hi = BENT_SPAN
    xs = np.linspace(lo, hi, BENT_SAMPLES)
    for y in BENT_ROWS:
        def f(x):
            return c.field.margin("sliding", x, y)
        v = np.array([f(x) for x in xs])
        zeros = [brentq(f, xs[i], xs[i + 1], xtol=1e-15, rtol=1e-15) for i in np.flatnonzero((v[:-1] > 0) != (v[1:] > 0))]
        got = row_crossings(comps, y, lo, hi)
        assert len(zeros) == 1, (y, zeros)
        assert len(got) >= 1 and max(abs(x - zeros[0]) for x in got) <= CONTRACT * tol, (y, got, zeros)
