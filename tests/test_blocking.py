"""Blocking contours: reference values of the digest (2.2, 2.3, 3.3), agreement with the design check,
internal pairs, the empty region, the CLI.

Tolerances: ``XTOL = 1e-6`` is the tracing tolerance (``tol``); a reference value printed to 6 digits is
matched to ``PRINTED = 1e-5`` (the issue's bound); a traced polyline passes a reference point within
its chord deviation, ``CHORD = 1e-4`` (step ~0.01, curvature < 4: h^2 k / 8 < 5e-5).
"""
import json
import math

import numpy as np
import pytest

from gearkit.blocking import blocking_contour
from gearkit.checks import check_pair
from gearkit.cli import main
from gearkit.curves import bracketed_root
from gearkit.distances import distances_to_polyline
from gearkit.errors import SpecError
from gearkit.pair import PairSpec, pair_geometry
from gearkit.families.involute import ShaperCutter

XTOL = 1e-6
PRINTED = 1e-5
CHORD = 1e-4
NEAR = 3e-3  # a reference point near a line's kink or end: the polyline passes within this (see the report)
X2MIN = 0.0641778


@pytest.fixture(scope="module")
def c1316():
    return blocking_contour(PairSpec(13, 16, 1.0), tol=XTOL)


def _root_x1(contour, name, x2, lo, hi):
    f = contour.field
    return bracketed_root(lambda x: f.margin(name, x, x2), lo, hi, xtol=1e-13)


@pytest.mark.parametrize("name,x1,x2", [
    ("pointing.1", 1.41162, 0.0), ("tip_thickness.1=0.25", 0.832754, 0.0), ("tip_thickness.1=0.4", 0.495900, 0.0),
    ("contact_ratio_tip=1", 1.32908, 0.0), ("contact_ratio=1.2", 0.747509, 0.0),
    ("contact_ratio_tip=1.2", 0.747509, 0.0), ("undercut.1", 0.239644, 0.0),
    ("pointing.1", 1.50806, X2MIN), ("tip_thickness.1=0.25", 0.897423, X2MIN), ("contact_ratio_tip=1", 1.29700, X2MIN),
    ("contact_ratio=1.2", 0.704761, X2MIN), ("sliding", 0.242465, X2MIN), ("sliding", 0.395543, 0.3),
    ("sliding", 0.537054, 0.5), ("interference.2", -0.466913, X2MIN)])
def test_lines_pass_the_digest_reference_points(c1316, name, x1, x2):
    """Digest 2.2 (z1 = 13, z2 = 16): the margin each line is traced from vanishes at the reference
    shift (to 1e-5), and the traced polyline passes the point."""
    assert _root_x1(c1316, name, x2, x1 - 0.05, x1 + 0.05) == pytest.approx(x1, abs=PRINTED)
    line = c1316.line(name)
    w = c1316.window
    if not (w[0] <= x1 <= w[1] and w[2] <= x2 <= w[3]):
        return  # beyond the default window: the margin's root is the line
    assert min(distances_to_polyline(np.array([[x1, x2]]), comp)[0] for comp in line.components) < NEAR


def test_undercut_onset_lines(c1316):
    assert c1316.line("undercut.1").points[:, 0] == pytest.approx(0.239644, abs=PRINTED)
    assert c1316.line("undercut.2").points[:, 1] == pytest.approx(X2MIN, abs=PRINTED)


def test_traced_vertices_are_on_their_lines(c1316):
    """Every vertex is within XTOL (in x) of the zero of its margin: |margin| <= XTOL * |gradient|."""
    f = c1316.field
    for name in ("pointing.1", "contact_ratio=1", "interference.1", "interference.2", "sliding"):
        for comp in c1316.line(name).components:
            for p in comp[:: max(1, len(comp) // 15)]:
                v = f.margin(name, *p)
                e = 1e-5
                g = np.hypot(f.margin(name, p[0] + e, p[1]) - v, f.margin(name, p[0], p[1] + e) - v) / e
                assert abs(v) <= 2 * XTOL * g + 1e-12


def test_real_and_tip_to_tip_contact_ratio_lines(c1316):
    """The check's eps_alpha (B3) and the tip-to-tip one agree wherever B1 and B2 hold; at the digest's
    eps = 1 point on x2 = 0 the wheel tip already digs into the pinion's fillet (B1 fails)."""
    f = c1316.field
    for p in c1316.line("contact_ratio_tip=1.2").points[::10]:
        pt = f.point(*p, exact=True)
        if pt.margin("interference.1") >= 0 and pt.margin("interference.2") >= 0:
            assert pt.margin("contact_ratio=1.2") == pytest.approx(0.0, abs=1e-6)  # vertex within XTOL
    assert f.margin("interference.1", 1.32908, 0.0) < 0


def test_region_agrees_with_the_design_check(c1316):
    """Issue item 2: random points of the window; the region's polygons hold the points check_pair
    (generated gears) passes, but for points within 2 tol of the boundary."""
    rng = np.random.default_rng(5)
    x0, x1, y0, y1 = c1316.window
    pts = np.column_stack([rng.uniform(x0, x1, 150), rng.uniform(y0, y1, 150)])
    inside = c1316.in_region(pts[:, 0], pts[:, 1])
    for (a, b), r in zip(pts, inside):
        try:
            ok = check_pair(PairSpec(13, 16, 1.0, float(a), float(b))).ok
        except SpecError:
            ok = False
        if ok != r:
            d = min(distances_to_polyline(np.array([[a, b]]), q)[0] for q in c1316.region)
            assert d <= 2 * XTOL, (a, b)


def test_the_star_is_only_a_point_check_passes(c1316):
    """A recommendation that fails the check (no candidate passed: x1, x2 the best point found) is
    drawn as a cross that says so, never as the star of a recommended point (it was a star)."""
    from gearkit.blocking.plot import figure
    from gearkit.blocking.recommend import Recommendation

    failing = Recommendation(1.5, 0.0, "balanced", "interference.1", "no recommendation: ...", passes=False)
    assert not c1316.contains(1.5, 0.0)
    for rec, marker in ((c1316.recommend(), "*"), (failing, "X")):
        drawn = [ln for ln in figure(c1316, rec).axes[0].lines if ln.get_marker() in ("*", "X")]
        assert [ln.get_marker() for ln in drawn] == [marker]
        assert ("recommended" in drawn[0].get_label()) == rec.passes


def test_region_and_recommendation(c1316):
    assert len(c1316.region) == 1
    poly = c1316.region[0]
    assert all(c1316.contains(*p) for p in (0.5 * (poly[::9] + poly[::9].mean(axis=0)))[:20])
    rec = c1316.recommend()
    assert rec.passes and c1316.contains(rec.x1, rec.x2)
    # on the sliding line: within the polyline's tolerance (1.25 tol in x; |grad| of the margin < 2)
    assert abs(c1316.field.margin("sliding", rec.x1, rec.x2)) < 2 * 1.25 * c1316.tol
    assert rec.binding and rec.binding in rec.reason
    strong = c1316.recommend("strength")
    assert strong.x1 + strong.x2 >= rec.x1 + rec.x2 - 1e-9
    assert c1316.mark(0.5, 0.3)["inside"] and c1316.mark(1.5, 0.0)["binding"][0] in ("contact_ratio=1",
                                                                                     "interference.1")


# ------------------------------------------------------------------------------ internal pair
SHAPER = ShaperCutter(20, addendum=1.3)


def _internal_closed_forms():
    """Digest 1.10/3.3 closed forms recomputed independently (math only): exit jamming and (3.127)."""
    a0 = math.radians(20.0)

    def inv(a):
        return math.tan(a) - a

    def geo(x2):
        ac2 = math.acos(29 * math.cos(a0) / (29 + 2 * x2))
        d2 = 29 * (inv(a0) - inv(ac2))
        aw = bracketed_root(lambda a: inv(a) - (inv(a0) - d2 / 3), 0.1, 1.5, xtol=1e-15)
        a = 1.5 * math.cos(a0) / math.cos(aw)
        dy = a - 1.5 - x2
        return aw, a, 23 + 1 - dy, 24.5 - 1 + x2 + dy

    rb1, rb2, rb0 = 23 * math.cos(a0), 24.5 * math.cos(a0), 10 * math.cos(a0)

    def exit_jam(x2):
        aw, a, r1, r2 = geo(x2)
        d1 = math.acos((r2 ** 2 - r1 ** 2 - a ** 2) / (2 * a * r1))
        d2 = math.acos((r2 ** 2 - r1 ** 2 + a ** 2) / (2 * a * r2))
        return 46 * (inv(math.acos(rb1 / r1)) + d1) + 3 * inv(aw) - 49 * (inv(math.acos(rb2 / r2)) + d2)

    def tip_fillet(x2):
        aw, a, r1, r2 = geo(x2)
        return (math.sqrt(r2 ** 2 - rb2 ** 2) - a * math.sin(aw)) - (33 * math.sin(a0) - math.sqrt(11.3 ** 2 - rb0 ** 2))

    return (bracketed_root(exit_jam, 0.3, 0.5, xtol=1e-14), bracketed_root(tip_fillet, 0.3, 0.6, xtol=1e-14))


def test_internal_limits_at_x1_zero():
    """Issue item 3 (z1 = 46, z2 = 49, shaper z0 = 20, x_c = 0.3). The closed forms recomputed here, and
    (exit jamming) the rigid-body tip sweep, give 0.4070967 and 0.4705220; the digest's 0.407106 and
    0.470483 are 1e-5 and 4e-5 off (its root finding). The lines are tested against the recomputed values
    to 1e-6 and against the digest to 5e-5."""
    c = blocking_contour(PairSpec(46, 49, 1.0, kind="internal", shift_convention="cutter", tool1=SHAPER, tool2=SHAPER),
                         tol=XTOL,
                         lines=["exit_jamming", "interference.1", "trimming.nu"])
    f = c.field
    jam, fillet = _internal_closed_forms()
    assert jam == pytest.approx(0.4070967, abs=1e-7) and fillet == pytest.approx(0.4705220, abs=1e-7)
    for name, want, digest in (("exit_jamming", jam, 0.407106), ("interference.1", fillet, 0.470483)):
        x2 = bracketed_root(lambda x: f.margin(name, 0.0, x), 0.3, 0.6, xtol=1e-13)
        assert x2 == pytest.approx(want, abs=XTOL)
        assert x2 == pytest.approx(digest, abs=5e-5)
        d = min(distances_to_polyline(np.array([[0.0, want]]), comp)[0] for comp in c.line(name).components)
        assert d < CHORD
    # trimming beyond O2N_u: with each point's own tip shortening the ring's tip stays inside O2N_u along
    # x1 = 0 (0.522336 holds only with the example's dy frozen, see test_checks_internal) up to x2 = 0.8;
    # beyond it the shortening (dy < -0.25) would lengthen the ring's teeth inside what the shaper leaves:
    # the graded tip is the cut one there, a_0 + r_f0 = 14.5 + x2 + 8.75, as on the generated ring
    assert max(f.margin("trimming.nu", 0.0, x) for x in np.linspace(0.3, 0.8, 21)) < 0
    spec = PairSpec(46, 49, 1.0, 0.0, 0.9, kind="internal", shift_convention="cutter", tool1=SHAPER, tool2=SHAPER)
    ring = check_pair(spec).profiles[1]
    assert ring.tip_diameter == pytest.approx(2 * (23.25 + 0.9), abs=1e-9)
    assert pair_geometry(spec).gears[1].tip_diameter == pytest.approx(ring.tip_diameter, abs=1e-9)


def test_empty_region_names_the_binding_lines():
    c = blocking_contour(PairSpec(13, 16, 1.0), window=(1.6, 2.0, 1.6, 2.0), lines=["pointing.1"])
    assert c.empty and c.region == ()
    assert "violates B" in c.empty_reason
    rec = c.recommend()  # said, not raised (issue 19)
    assert not rec.passes and rec.x1 is None and "empty" in rec.reason
    # the picture says why too (it said only "(region empty)" over an empty map)
    from gearkit.blocking.plot import figure

    title = " ".join(figure(c, rec).axes[0].get_title().split())
    assert "region empty: " + " ".join(c.empty_reason.split()) in title


# ------------------------------------------------------------------------------ CLI
def test_cli_json_and_export(tmp_path, capsys):
    out = tmp_path / "contour.json"
    code = main(["blocking", "--z1", "13", "--z2", "16", "--mark", "0.5,0.3", "-o", str(out), "--json",
                 "--points", "60"])
    assert code == 0
    data = json.loads(capsys.readouterr().out)
    assert {"region", "lines", "recommendation", "marked"} <= set(data)
    assert data["marked"] == {"x1": 0.5, "x2": 0.3, "inside": True, "binding": []}
    assert {ln["name"] for ln in data["lines"]} >= {"interference.1", "pointing.1", "contact_ratio=1", "sliding"}
    assert json.loads(out.read_text())["region"]["empty"] is False
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".gearkit-")]
    assert main(["blocking", "--z1", "13", "--z2", "16", "--mark", "1.5,0", "--points", "40"]) == 1
    assert main(["blocking", "--z1", "13", "--z2", "16", "-o", str(tmp_path / "x.txt")]) == 2
    assert main(["blocking", "--z1", "46", "--z2", "49", "--internal"]) == 2
    capsys.readouterr()
    # a mark that is no number is bad input (exit 2, one line), not a point outside the region (exit 1)
    assert main(["blocking", "--z1", "13", "--z2", "16", "--mark", "nan,0.3", "--points", "40"]) == 2
    assert capsys.readouterr().err.strip() == "gearkit blocking: error: --mark: 'nan,0.3': every number must be finite"
    # the options' errors name the flags typed, with the range (a zero centre distance read as none given)
    for extra, line in ((["--tol", "5"], "--tol: 5.0 must be in [1e-12, 0.01] (shift units)"),
                        (["--center-distance", "0", "--criterion", "center_distance"],
                         "--center-distance: 0.0 must be a positive length in mm"),
                        (["--window", "1,0,0,1"], "--window: (1.0, 0.0, 0.0, 1.0) must be (x1_lo, x1_hi, x2_lo, "
                                                  "x2_hi) within [-3, 3], lo < hi")):
        assert main(["blocking", "--z1", "13", "--z2", "16", *extra]) == 2
        assert capsys.readouterr().err.strip() == "gearkit blocking: error: " + line
    # a negative first value reads as a flag: the error says how to write it
    assert main(["blocking", "--z1", "13", "--z2", "16", "--mark", "-0.2,0.3"]) == 2
    assert "one starting with '-': write --mark=VALUE" in capsys.readouterr().err


# ------------------------------------------------------------------------------ criteria, CLI help, atlas
def test_center_distance_criterion_lies_on_the_shift_sum(c1316):
    """The recommendation by centre distance lies on x1 + x2 = the shift sum of that centre distance
    (rack-cut gears: the sum does not depend on the split; shifts_for_center_distance solves it)."""
    from gearkit.pair import shifts_for_center_distance

    a_w = 14.8  # mm, a_ref = 14.5 for m = 1
    s = shifts_for_center_distance(PairSpec(13, 16, 1.0), a_w, split="equal")
    rec = c1316.recommend("center_distance", center_distance=a_w)
    assert rec.criterion == "center_distance"
    # the vertex is within XTOL of the a_w line, whose x1 + x2 changes ~1:1 with a_w / m
    assert rec.x1 + rec.x2 == pytest.approx(s.shift1 + s.shift2, abs=4 * XTOL)
    assert c1316.contains(rec.x1, rec.x2)
    with pytest.raises(SpecError):
        c1316.recommend("center_distance")


def test_cli_help_states_the_ring_shift_sign(capsys):
    assert main(["blocking", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "x2 > 0 moves the ring's teeth outward" in text
    # the ring's x2 is read as `gearkit check` reads it by default, by the tooth thickness (it said the
    # shaper's radial setting, which check reads only with --ring-shift cutter)
    assert "read as 'gearkit check' reads it by default (ISO 21771" in text
    assert "(every ring) is the cutter's radial setting" not in text


def test_atlas_cell_equals_the_single_contour():
    """Two cells in two worker processes; a cell is exactly the contour computed alone."""
    from gearkit.blocking import blocking_atlas

    opts = dict(points=40, lines=["pointing.1", "undercut.1"])
    atlas = blocking_atlas([13], [16, 17], workers=2, **opts)
    assert sorted(atlas.cells) == [(13, 16), (13, 17)] and atlas.errors == {}
    alone = blocking_contour(PairSpec(13, 16, 1.0), **opts)
    cell = atlas[(13, 16)]
    assert cell.window == alone.window
    for a, b in zip(cell.lines, alone.lines):
        assert a.name == b.name and len(a.components) == len(b.components)
        assert all(np.array_equal(p, q) for p, q in zip(a.components, b.components))
    assert len(cell.region) == len(alone.region)
    assert all(np.array_equal(p, q) for p, q in zip(cell.region, alone.region))
    assert cell.contains(0.5, 0.3) and not cell.contains(1.5, 0.0)
    ring = PairSpec(46, 49, 1.0, kind="internal", shift_convention="cutter", tool1=SHAPER, tool2=SHAPER)
    with pytest.raises(SpecError, match="ring needs more teeth"):  # no cell is a pair: said, not empty
        blocking_atlas([50], [49], ring, workers=1, **opts)


def test_no_pair_area_is_drawn_to_its_own_edge_not_the_grids():
    """The grey no-pair area of a picture ends where the tight mesh ends: for an external spur pair
    where inv alpha_w = inv alpha + 2 (x1 + x2) tan alpha / (z1 + z2) reaches the field's 1e-9, a
    straight line x1 + x2 = S. In a window only that line crosses, the drawn area is the triangle
    below it (area by formula) and every vertex off the window's border lies on the line."""
    from gearkit.blocking.plot import _no_pair

    z1, z2, alpha = 12, 30, math.radians(20.0)
    inv_a = math.tan(alpha) - alpha
    s = (1e-9 - inv_a) * (z1 + z2) / (2 * math.tan(alpha))  # -0.8599...
    c = blocking_contour(PairSpec(z1, z2, 1.0), tol=1e-3, window=(-1.0, 0.0, -1.0, 0.0), lines=["undercut.1"])
    verts, codes = _no_pair(c)
    ring = verts[:-1] if codes[-1] == 79 else verts  # the closing vertex repeats the first
    assert (codes[1:-1] == 2).all() and codes[0] == 1  # one area, one outline
    x, y = ring[:, 0], ring[:, 1]
    area = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    assert area == pytest.approx(1.0 - s ** 2 / 2, abs=1e-12)  # u + v < 2 + S in the unit square
    border = (np.abs(x + 0.5) > 0.5 - 1e-15) | (np.abs(y + 0.5) > 0.5 - 1e-15)
    inner = ~border
    assert inner.sum() >= 50  # the grid's edge crossings along the line
    assert np.abs(x[inner] + y[inner] - s).max() < 1e-10


@pytest.mark.parametrize("flags", [
    ["--z1", "13", "--z2", "16"], ["--z1", "20", "--z2", "40", "--rack", "iso53b"],
    ["--z1", "18", "--z2", "41", "--helix-angle-deg", "15", "-m", "2"],
    ["--z1", "46", "--z2", "49", "--internal", "--cutter-teeth", "20"],
    ["--z1", "57", "--z2", "130", "--internal", "--cutter-teeth", "28", "--pressure-angle-deg", "25"],
    ["--z1", "17", "--z2", "40", "--pinion-cutter-teeth", "25"], ["--z1", "15", "--z2", "33", "--addendum", "0.9"]])
def test_cli_mark_is_the_pair_gearkit_check_reads(flags):
    """``gearkit blocking --mark x1,x2`` asks check_pair about the pair ``gearkit check`` builds from the
    same flags and ``--x1 x1 --x2 x2`` (external, internal with the ring's x2 read the same way, rack,
    helix, module, shaper-cut pinion, addendum): the two command lines give equal PairSpecs, so the
    mark's verdict and check's exit status agree at every point (84 random points of seven such pairs
    agreed, the no-pair ones check's exit 2)."""
    from dataclasses import replace

    from gearkit.cli.blocking import template_spec
    from gearkit.cli.common import pair_spec_from_args
    from gearkit.cli.parser import build_parser

    b = build_parser("blocking").parse_args(["blocking", *flags])
    c = build_parser("check").parse_args(["check", *flags, *([] if "-m" in flags else ["-m", "1"]),
                                          "--x1", "0.3", "--x2", "-0.2"])
    c.given_flags, c.design = set(), None
    spec, limits = pair_spec_from_args(c)
    assert replace(template_spec(b, b.z1, b.z2), shift1=0.3, shift2=-0.2) == spec
    assert limits == blocking_contour.__kwdefaults__["limits"]
