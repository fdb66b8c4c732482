"""The bench's measuring tools and JSON structure (no timing is asserted: speed lives in the bench).

The ladder's "achieved" must be an independent measurement: it must track the requested tol
(within 2x, monotone over the ladder) and it must see a polyline that is too coarse.
"""
import copy
import math
import os
import subprocess
import sys

import numpy as np
import pytest

from gearkit.bench.meshes import distances_to_segments, plane_section
from gearkit.bench.profiles import measured_deviation, profile_row
from gearkit.families.involute import GearSpec, tooth_profile

#: the ladder's promise: achieved within this factor of the requested tol
FACTOR = 2.0


def test_ladder_rows_track_the_requested_tol_and_grow_monotonically():
    spec = GearSpec(40, 1.0)
    rows = [profile_row("involute", "spur z=40", spec, t, repeats=1) for t in (1e-2, 1e-4, 1e-6)]
    for r in rows:
        assert set(r) >= {"family", "product", "tol", "achieved", "vertices", "seconds"}
        assert 0 < r["achieved"] <= FACTOR * r["tol"]
        assert r["seconds"] > 0
    assert [r["vertices"] for r in rows] == sorted(r["vertices"] for r in rows)
    assert rows[0]["achieved"] > rows[1]["achieved"] > rows[2]["achieved"]


def test_the_independent_measure_sees_a_polyline_that_is_too_coarse():
    spec = GearSpec(20, 1.0)
    tol = 1e-4
    prof = tooth_profile(spec)
    outline = prof.outline(tol)
    n_half = len(prof.half_points(tol)[0])
    good = measured_deviation(prof, outline, n_half)
    assert good <= FACTOR * tol
    # keep every 4th vertex of the whole outline (teeth stay aligned: one tooth has len/z vertices)
    n_t = len(outline) // spec.teeth
    coarse = outline.reshape(spec.teeth, n_t, 2)[:, ::4].reshape(-1, 2)
    assert measured_deviation(prof, coarse, n_half) > 4 * tol  # chords 4x longer sag ~16x more


def test_plane_section_of_a_prism_and_distances_to_its_segments():
    # a square prism 2 x 2 x 1 as a triangle mesh: its section at z = 0.5 is the square
    sq = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]], dtype=float)
    v = np.concatenate([np.c_[sq, np.zeros(4)], np.c_[sq, np.ones(4)]])
    faces = []
    for i in range(4):
        j = (i + 1) % 4
        faces += [[i, j, 4 + j], [i, 4 + j, 4 + i]]
    faces += [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7]]
    a, b = plane_section(v, np.array(faces), 0.5)
    assert len(a) == 8
    assert np.allclose(np.abs(np.concatenate([a, b])).max(axis=1), 1.0)
    pts = np.array([[0.0, 0.0], [1.5, 0.0], [0.3, 1.0]])
    assert np.allclose(distances_to_segments(pts, a, b), [1.0, 0.5, 0.0], atol=1e-15)


def test_markdown_block_replaces_only_the_marked_region():
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parent.parent / "examples" / "bench_table.py"
    spec = importlib.util.spec_from_file_location("bench_table", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    text = f"# t\n\nbefore\n{mod.START}\nold\n{mod.END}\nafter\n"
    out = mod.replace_block(text, "new table")
    assert out == f"# t\n\nbefore\n{mod.START}\nnew table\n{mod.END}\nafter\n"


@pytest.mark.skipif(not os.path.isdir("/proc/self/task"), reason="counts threads in Linux's /proc")
def test_the_bench_script_times_with_numpys_blas_on_one_thread():
    """``examples/bench_table.py`` runs the bench as ``gearkit bench`` does: its in-process rows run with numpy's
    BLAS on one thread, and the bench says so. Oracle: the process's own threads (Linux's ``/proc``) once
    numpy is loaded: one, where a plain ``import numpy`` in the same environment starts BLAS's pool (a thread
    per core)."""
    from pathlib import Path

    script = Path(__file__).resolve().parent.parent / "examples" / "bench_table.py"
    env = {k: v for k, v in os.environ.items() if k not in ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")}
    count = "import os, numpy; print(len(os.listdir('/proc/self/task')))"
    plain = subprocess.run([sys.executable, "-c", count], capture_output=True, text=True, env=env, timeout=120)
    probe = ("import os, runpy, sys\n"
             f"runpy.run_path({str(script)!r}, run_name='bench_table')\n"
             "from gearkit.bench import process\n"
             "print(len(os.listdir('/proc/self/task')), process.blas_threads(), 'numpy' in sys.modules)")
    proc = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, env=env, timeout=120)
    assert plain.returncode == 0 and proc.returncode == 0, plain.stderr + proc.stderr
    assert proc.stdout.split() == ["1", "1", "True"]
    if (os.cpu_count() or 1) > 1:  # the oracle sees a pool where there is one
        assert int(plain.stdout) > 1


def test_bench_is_a_registered_command():
    from gearkit.cli import COMMANDS, build_parser

    assert "bench" in COMMANDS
    args = build_parser().parse_args(["bench", "--quick", "-o", "x.json"])
    assert args.quick and args.output == "x.json" and args.json is False


def test_closed_form_baseline_is_the_involute():
    from gearkit.bench.timing import closed_form_involute

    pts = closed_form_involute(50, 2.0, 0.8)
    t = np.linspace(0, 0.8, 50)
    # an involute point's distance from the centre is r_b sqrt(1 + t^2)
    assert np.allclose(np.hypot(*pts.T), 2.0 * np.sqrt(1 + t * t), rtol=1e-14)
    assert math.isclose(float(pts[0, 0]), 2.0)


def test_target_rows_pass_reads_measured_against_target_and_every_row_is_printed():
    """Generic target rows: pass is measured <= target; rows from any producer (contact here)
    are printed with their verdict, and the floor and load average head the table."""
    from gearkit.bench.targets import contact_targets, format_target_rows, markdown_target_rows, target_row

    assert target_row("a", 0.1, 0.1, "s")["pass"] is True
    assert target_row("a", 0.1000001, 0.1, "s")["pass"] is False
    assert target_row("a", None, 0.1, "s")["pass"] is None and target_row("a", 1.0, None, "s")["pass"] is None
    contact = [{"case": "rigid cycle 20/40 m=2", "steps": 2000, "slices": 1, "seconds": 0.9, "cpu_seconds": 0.55,
                "target": 0.1},
               {"case": "loaded", "steps": 500, "slices": 10, "seconds": 1.0, "cpu_seconds": 0.8, "target": None}]
    rows = contact_targets(contact)
    assert [(r["name"], r["measured"], r["target"], r["pass"]) for r in rows] == [
        ("rigid cycle 20/40 m=2, 2000 steps", 0.55, 0.1, False)]  # rows without a target are no target rows
    from gearkit.bench.targets import blocking_targets

    blocking = blocking_targets([{"target": "blocking ladder: time grows as tol falls", "measured": None,
                                  "limit": None, "unit": "", "pass": False}])
    assert blocking == [{"name": "blocking ladder: time grows as tol falls", "measured": None, "target": None,
                         "unit": "", "pass": False}]  # a verdict that is not a number comparison is kept
    res = {"targets": rows + [target_row("gear z=12 -> STL", 1.12, 1.15, "x floor")],
           "floor": {"cpu_seconds": 0.125, "wall_seconds": 0.2, "runs": 5, "command": "python -c \"import numpy\""},
           "meta": {"load_before": 3.5, "load_after": 4.0, "cpus": 2}}
    text = "\n".join(format_target_rows(res))
    assert "125 ms CPU" in text and "load average 3.5 before, 4.0 after" in text
    lines = text.splitlines()
    assert "FAIL" in next(x for x in lines if x.strip().startswith("rigid cycle"))
    assert "pass" in next(x for x in lines if x.strip().startswith("gear z=12"))
    md = markdown_target_rows(res)
    assert sum(x.startswith("| rigid cycle") or x.startswith("| gear z=12") for x in md) == 2


def test_overhead_ratio_is_measured_on_a_coarse_cpu_clock(monkeypatch):
    """A CPU clock that ticks every 15.6 ms (Windows; 4 ms while an interval timer runs on some kernels)
    read 0 s for the bare closed form and the ratio divided by zero; batches of calls span many ticks."""
    import time

    from gearkit.bench.profiles import overhead

    real, tick = time.process_time, 15.6e-3
    monkeypatch.setattr(time, "process_time", lambda: math.floor(real() / tick) * tick)
    out = overhead(3)
    assert out["baseline_seconds"] > 0 and math.isfinite(out["overhead_ratio"]) and out["overhead_ratio"] > 0
    # on a loaded machine a batch sized on the wall clock holds few calls (one slow call sized it): the
    # timed batches still span ticks of the CPU clock
    import gearkit.bench.timing as timing

    monkeypatch.setattr(timing, "batch_calls", lambda fn, seconds: 1)
    out = overhead(3)
    assert out["baseline_seconds"] > 0 and math.isfinite(out["overhead_ratio"]) and out["overhead_ratio"] > 0
    assert math.isfinite(out["overhead_ratio_sampling"]) and out["overhead_ratio_sampling"] > 0


def test_the_blocking_measure_finds_the_zero_where_a_line_leaves_the_no_pair_edge_at_a_small_angle():
    """A line ending on the no-pair edge may leave it at a small angle: its function's zeros on one
    side of it fill only the wedge between the line and the edge, and a point on the edge beside the
    line's end is as far from the zero set as from that end. Two cases with that distance known
    independently: a linear function defined on x >= 0 (its zero line leaves the edge x = 0 at 13
    degrees), and 51/127 z0 19 (internal), whose contact-ratio line eps_alpha = 1.2 tip to tip leaves
    the edge x1 = const below which the generated pinion has no tooth left at about the same angle: there the end is found by bisection for
    the edge along a row and scipy's brentq along the edge. The eight fixed rays missed the wedge and
    read the point 4.2 mm off."""
    from scipy.optimize import brentq

    from gearkit.bench.exact import polyline_deviation
    from gearkit.blocking import default_window
    from gearkit.blocking.arrays import evaluator
    from gearkit.blocking.field import PairField
    from gearkit.families.involute import ShaperCutter
    from gearkit.pair import PairSpec

    tol, off = 1e-3, 1e-6  # the point lies `off` above the line's end on the edge
    slope = math.tan(math.radians(13.0))
    lin = lambda p, k: np.where(p[:, 0] >= 0.0, p[:, 0] + slope * p[:, 1], np.nan)
    line = np.array([[0.0, off], [slope * 1e-3, -1e-3]])  # from beside the end along the zero line
    assert polyline_deviation(lin, [(0, line)], tol, 1.0) == pytest.approx(off, rel=1e-6)

    field = PairField(PairSpec(51, 127, 1.0, kind="internal", tool2=ShaperCutter(19)))
    field.x_ranges = ((w := default_window(field))[:2], w[2:])  # as blocking_contour reads the form circles
    field.exact_forms = False
    F = evaluator(field, ["contact_ratio_tip=1.2"], None)
    f = lambda x1, x2: float(F(np.array([[x1, x2]]), np.array([0]))[0])
    a, b = -2.8, -2.7  # the edge (ra1 = rb1, the same on every row): no pair at a, one at b
    for _ in range(60):
        m = 0.5 * (a + b)
        a, b = (m, b) if math.isnan(f(m, -0.92)) else (a, m)
    b += 1e-12  # (inside on every row: the edge moves with round-off from row to row)
    end = brentq(lambda x2: f(b, x2), -0.93, -0.91, xtol=1e-15)  # the line's end on the edge
    rows = [(brentq(lambda x1: f(x1, x2), b, b + 0.01, xtol=1e-15), x2) for x2 in end - 3e-4 * np.arange(1, 5)]
    line = np.array([(b, end + off)] + rows)
    assert polyline_deviation(F, [(0, line)], tol, 8.0) == pytest.approx(off, rel=1e-3)


def test_the_exact_measure_reaches_into_an_acute_corner_of_a_zero_set():
    """A region's function ``min(a, b)`` whose zeros ``a = 0`` and ``b = 0`` cross at 6 degrees (52/75 z0 15
    at tol 1e-3: exit jamming and interference.1 at (0.3276, -0.1119)): a polygon's vertex 1e-6 behind the
    corner, its chords along the two sides just outside them. No ray of the chord (normal, chord, diagonals)
    enters the corner, and one along the chord met the curved side 0.08 beyond: the vertex read 97 tol (52/75:
    75 tol) where it lies 1e-6 from the zero set. Oracle: the nearest zero of a point behind an acute corner
    (outside both sides' normals at the tip) is the tip, at exactly the point's distance from it; a ray's
    zero is no nearer, and the corner's bisector passes the tip within the chords' 1e-5 / 0.06 of its angle
    (the zero it meets within a side's 3 degrees: 1.3e-6)."""
    from gearkit.bench.exact import point_distances

    tol, delta, k = 1e-3, 1e-6, 1.0
    lo, hi = np.radians(44.0), np.radians(50.0)  # the sides' directions at the tip (the origin)

    def F(p, which):  # inside the corner: below the upper side y = x tan(hi) + k x^2, above the lower one
        x, y = p[:, 0], p[:, 1]
        return np.minimum(x * np.tan(hi) + k * x * x - y, y - x * np.tan(lo))

    bis = 0.5 * (lo + hi)
    P0 = -delta * np.array([np.cos(bis), np.sin(bis)])
    up = np.array([0.06, 0.06 * np.tan(hi) + k * 0.06 ** 2]) + 1e-5 * np.array([-np.sin(hi), np.cos(hi)])
    down = 0.06 * np.array([np.cos(lo), np.sin(lo)]) + 1e-5 * np.array([np.sin(lo), -np.cos(lo)])
    assert F(np.array([P0, up, down]), 0).max() < 0  # all three outside the corner
    for poly in (np.array([P0, up, down, P0]), np.array([P0, down, up, P0])):  # either way round
        d = point_distances(F, [(0, poly)], tol, 1.0)
        assert delta * (1 - 1e-9) <= d[0] <= 2 * delta, d[0] / tol


def test_the_exact_measure_sees_the_tip_of_a_thin_wedge_beside_a_chord():
    """Two thin wedges of the other sign meeting at a saddle, a chord passing over the gap between their
    tips (internal 58/63 z0 16's interference.1 at tol 1e-3, a chord 0.54 tol from a tip read 3.69 tol):
    ``F = y^2 - (e x)^2 + (e x0)^2`` is negative in two wedges along the x axis, 2e wide a unit from
    their tips at x = +-x0. None of the nine rays of the chord's middle (0, h) (normal, chord, diagonals)
    enters a wedge before x = h / e (2.7 tol out). Oracle: the nearest point of the hyperbola
    ``y^2 = e^2 (x^2 - x0^2)`` to (0, h), by scipy's minimize_scalar along it; the measure finds a zero on
    a ray, so no nearer, and within a quarter tol of it."""
    from scipy.optimize import minimize_scalar

    from gearkit.bench.exact import point_distances

    tol, e, x0, h = 1e-3, 0.15, 3e-4, 4e-4

    def F(p, which):
        return p[:, 1] ** 2 - (e * p[:, 0]) ** 2 + (e * x0) ** 2

    branch = lambda x: math.hypot(x, e * math.sqrt(max(x * x - x0 * x0, 0.0)) - h)
    near = minimize_scalar(branch, bounds=(x0, 10 * x0), method="bounded", options={"xatol": 1e-12}).fun
    assert 0.45 * tol < near < 0.55 * tol  # the tips' neighbourhood, beside the saddle
    d = point_distances(F, [(0, np.array([[-2e-4, h], [2e-4, h]]))], tol, 1.0)
    assert near * (1 - 1e-9) <= d[1] <= near + tol / 4, (d[1] / tol, near / tol)


def test_the_gap_measure_follows_a_thin_wedge_traced_short_of_its_tip():
    """A thin wedge of a line's zero set closed 3 tol short of its tip by a chord across it (internal 19/42
    z0 19's tip sweep at tol 1e-3: 2.9 tol short where it is half a tol wide, between the scan lines,
    which read 0.85 tol): the corner's bisector is 10 degrees off the wedge's way (the chords do not lie
    along its sides) and the wedge bends, so a march along the bisector leaves it through a side. Oracle:
    the tip, where the two sides ``x2 = c x1^2 +- w (1 - x1)`` meet, at (1, c); the measure's zero is a
    zero of F on the far side of the corner, so no farther from the trace than the tip, and within a
    quarter tol of it."""
    from gearkit.bench.topology import corner_gap

    tol, c, w = 1e-3, 0.2, 0.09

    def F(p, which):
        return np.abs(p[:, 1] - c * p[:, 0] ** 2) - w * (1.0 - p[:, 0])

    x = 1.0 - 3.2e-3  # the corner, off the wedge's middle by a third of its width there
    corner = np.array([x, c * x * x + 0.3 * w * (1.0 - x)])
    way = np.array([1.0, 2 * c])  # the wedge's way at its tip
    turn = np.radians(10.0)  # the bisector 10 degrees off it: the chords' ends placed symmetrically about it
    b = np.array([[np.cos(turn), -np.sin(turn)], [np.sin(turn), np.cos(turn)]]) @ (way / np.hypot(*way))
    side = np.array([-b[1], b[0]])
    trace = np.array([corner - 0.05 * b + 0.004 * side, corner, corner - 0.05 * b - 0.004 * side])
    tip = np.array([1.0, c])
    assert F(tip[None], 0)[0] == pytest.approx(0.0, abs=1e-15) and F(corner[None], 0)[0] < 0  # inside
    from gearkit.distances import distances_to_polyline

    short = float(distances_to_polyline(tip[None], trace)[0])
    d, at = corner_gap(F, 0, [trace], tol)
    assert short - tol / 4 <= d <= short + 1e-12, (d / tol, short / tol)


def test_the_gap_measure_sees_a_wedge_of_the_region_closed_short_of_its_tip():
    """External 33/78 at tol 1e-3: the region ends in a wedge of 6 degrees between interference.1 and .2 (traced
    to its tip). Closed by a chord 3 tol back from that tip (as the grid closes it, the tip left out), the
    outline's corner has the region's sign beyond it: the gap measure's sections follow the wedge and name the
    region, its zero at the tip within a tol of the vertex the trace had there (the chord's ends are on the
    sides, its middle inside the wedge)."""
    from gearkit.bench.topology import scan_gap
    from gearkit.blocking import blocking_contour
    from gearkit.pair import PairSpec

    tol = 1e-3
    c = blocking_contour(PairSpec(33, 78, 1.0), tol=tol)
    assert scan_gap(c)[0] <= 2 * tol
    for n, p in enumerate(c.region):
        a, b = p[:-2] - p[1:-1], p[2:] - p[1:-1]
        cos = np.einsum("ij,ij->i", a, b) / np.hypot(*a.T) / np.hypot(*b.T)
        i = np.flatnonzero(cos > np.cos(np.radians(10.0)))
        if i.size:
            break
    assert i.size == 1, "the region's one wedge of less than 10 degrees"
    tip, before, after = p[i[0] + 1], p[i[0]], p[i[0] + 2]
    back = lambda q: tip + 3 * tol * (q - tip) / np.hypot(*(q - tip))  # noqa: E731
    cut = np.vstack([p[:i[0] + 1], back(before), back(after), p[i[0] + 2:]])  # the tip cut off 3 tol back
    short = copy.copy(c)
    short.region = (*c.region[:n], cut, *c.region[n + 1:])
    d, name, at = scan_gap(short)
    assert name == "region" and 2 * tol < d <= 3 * tol + tol and np.hypot(*(np.array(at) - tip)) <= tol, (d / tol, at)


def test_the_gap_measure_follows_a_wide_wedge_cut_square_far_short_of_its_tip():
    """A wedge 5 tol wide where a chord cuts it square, 70 tol short of its tip (internal 42/98 z0 16's region at
    tol 1e-3, closed so short of the window's frame): sections across either corner's bisector cross a side and
    hold no run, and a section across the wedge 2 tol either side lies all inside it. The measure goes on from the
    cut's middle along the sides, its sections widened to the wedge and narrowed with it. Oracle: the tip, where
    the sides ``x2 = +-w (1 - x1)`` meet, at (1, 0); the measure's zero lies beyond the cut, so no farther from the
    trace than the tip, and within a quarter tol of it."""
    from gearkit.bench.topology import corner_gap
    from gearkit.distances import distances_to_polyline

    tol, w = 1e-3, 2.5e-3 / 0.07  # 5 tol wide at x1 = 0.93

    def F(p, which):
        return np.abs(p[:, 1]) - w * (1.0 - p[:, 0])

    x, y = 0.93, w * 0.07
    trace = np.array([[0.5, w * 0.5], [x, y], [x, -y], [0.5, -w * 0.5]])  # the sides up to the square cut
    tip = np.array([1.0, 0.0])
    short = float(distances_to_polyline(tip[None], trace)[0])
    d, at = corner_gap(F, 0, [trace], tol)
    assert short - tol / 4 <= d <= short + 1e-12, (d / tol, short / tol)
