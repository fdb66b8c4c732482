"""Vertex placement: near the fewest vertices, never less accurate; and the mesh check behind every solid.

The sampler places vertices by curvature (:func:`gearkit.accuracy.place_by_curvature`) and then
probes every chord (:func:`gearkit.refine.refine_sample`). Its deviation is measured here
independently -- the exact pieces evaluated densely and uniformly in their parameters
(:func:`gearkit.bench.vertices.dense_exact`), their distance to the sampled polyline -- for every
family at several tolerances; its vertex count is held against the fewest a chord-at-tol polyline
needs on that dense evaluation (:func:`gearkit.bench.vertices.fewest_vertices`), which is itself
held against an exhaustive shortest-path count.
"""
import math

import numpy as np
import pytest

from gearkit.accuracy import PLACE_AT, adaptive_sample, place_by_curvature
from gearkit.bench.vertices import VERTEX_TARGET, dense_exact, fewest_vertices
from gearkit.distances import distances_to_polyline
from gearkit.errors import GeometryError

#: tolerances, in modules (or eccentricities), the families are sampled at
TOLS = (1e-2, 1e-3, 1e-4)


def _families():
    import gearkit as gk
    from gearkit.families import cycloidal as cyc
    from gearkit.families import novikov
    from gearkit.families.involute import GearSpec, ShaperCutter, tooth_profile
    from gearkit.families.novikov.presets import rack_system

    return {
        "involute z40": (lambda: tooth_profile(GearSpec(40, 1.0)), 1.0, True),
        "involute undercut z8": (lambda: tooth_profile(GearSpec(8, 1.0)), 1.0, True),
        "involute internal z60": (lambda: tooth_profile(GearSpec(60, 1.0, internal=True, tool=ShaperCutter(20))),
                                  1.0, True),
        "involute helical z20 x0.5": (lambda: tooth_profile(GearSpec(20, 2.0, 0.5, 20.0)), 2.0, True),
        "novikov z20": (lambda: novikov.tooth_profile(novikov.NovikovGearSpec(20, 4.0, rack_system("dca24").rack1,
                                                                              15.0)), 4.0, True),
        "pin gear wheel": (lambda: gk.pin_gear_wheel(gk.PinGearSpec(1.0, 50, 60, 0.04)), 1.0, True),
        "cycloid gear": (lambda: gk.cycloid_gear(gk.CycloidPairSpec(1.0, 10, 20), 1), 1.0, True),
        # the disc's pin walks end in a square root (the parameter races there): its refinement splits
        # those ends however straight they are, so its count is not held to the target (accuracy is)
        "cycloid disc": (lambda: cyc.disc_profile(cyc.DriveSpec(12, 11, 40.0, 3.0, 1.5)), 1.5, False),
    }


FAMILIES = _families()


@pytest.fixture(scope="module")
def profiles():
    return {name: make() for name, (make, _, _) in FAMILIES.items()}


#: the dense evaluation measuring the deviation: its own steps sag by this fraction of tol
MEASURE = 1e-2
#: the dense evaluation the fewest count is found on: steps ~1/30 of a chord (the count ~3 % high at most)
COUNT = 1e-3


@pytest.mark.parametrize("name", sorted(FAMILIES))
def test_every_family_is_sampled_within_tol_measured_densely_with_near_the_fewest_vertices(profiles, name):
    prof = profiles[name]
    _, scale, held = FAMILIES[name]
    for tol_m in TOLS:
        tol = tol_m * scale
        half, achieved = prof.half_points(tol)
        exact = dense_exact(prof.half.pieces, tol, fraction=MEASURE)
        assert distances_to_polyline(exact, half).max() <= tol, (name, tol)
        assert achieved <= tol
    if held:  # the sampler keeps the joins of the pieces (flank, fillet, ...): so does the count it is held to
        tol = 1e-3 * scale
        least = sum(fewest_vertices(dense_exact([p], tol, fraction=COUNT), tol) for p in prof.half.pieces)
        least -= len(prof.half.pieces) - 1
        assert len(prof.half_points(tol)[0]) <= VERTEX_TARGET * least, (name, least)


def test_a_cam_outline_is_placed_within_tol_measured_densely():
    from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

    prof = cam_profile(CamSpec(56.7702, MotionProgram.rise_dwell_return(20.0, 60.0, 60.0, 60.0), roller_radius=10.0))
    for tol in (1e-2, 1e-3, 1e-4):
        out = prof.outline(tol)
        exact = dense_exact(prof.pieces, tol, fraction=MEASURE)
        assert distances_to_polyline(exact, out, closed=True).max() <= tol
        assert prof.achieved(tol) <= tol


def test_placement_on_a_circle_is_even_and_the_fewest_at_its_chord_deviation():
    # radius 5: a chord of angle h sags 5 (1 - cos(h / 2)); the whole circle needs ceil(2 pi / h) chords.
    # Chords are placed to sag by PLACE_AT tol (inside the acceptance test's margin)
    tol, r = 1e-4, 5.0
    circle = lambda w: r * np.stack([np.cos(2 * np.pi * w), np.sin(2 * np.pi * w)], -1)
    w, p, achieved = adaptive_sample(circle, tol, fewest=True)
    least = math.ceil(2 * math.pi / (2 * math.acos(1 - PLACE_AT * tol / r)))
    assert least <= len(p) - 1 <= least + 1
    assert np.diff(w).max() / np.diff(w).min() < 1 + 1e-4  # equal steps where the curvature is even
    dense = circle(np.linspace(0, 1, 200001))
    assert distances_to_polyline(dense, p).max() <= tol and achieved <= tol


def test_placement_follows_the_curvature_of_an_ellipse():
    # an ellipse a = 4, b = 1: curvature a / b^2 = 4 at the ends of the major axis, b / a^2 = 1/16 at
    # the ends of the minor one, so chords there are sqrt(64) = 8x longer (spacing ~ k^-1/2)
    ell = lambda w: np.stack([4 * np.cos(np.pi * w), np.sin(np.pi * w)], -1)
    t = np.linspace(0, 1, 4001)
    placed = ell(place_by_curvature(t, ell(t), 1e-4))
    step = np.linalg.norm(np.diff(placed, axis=0), axis=1)
    assert 6.0 < step[len(step) // 2] / step[0] < 10.0


def test_fewest_vertices_matches_an_exhaustive_shortest_path():
    # every chord i -> j that stays within tol of the points it skips is an edge; the fewest vertices
    # is a shortest path from the first point to the last (breadth first over all chords)
    from gearkit.families.involute import GearSpec, tooth_profile

    prof = tooth_profile(GearSpec(12, 1.0))
    pts = np.concatenate([p(np.linspace(0, 1, 61))[(k > 0):] for k, p in enumerate(prof.half.pieces)])
    for tol in (1e-2, 2e-3):
        n = len(pts)
        ok = np.zeros((n, n), dtype=bool)
        for i in range(n):
            for j in range(i + 1, n):
                d = pts[j] - pts[i]
                q = pts[i + 1:j] - pts[i]
                dev = np.abs(q[:, 0] * d[1] - q[:, 1] * d[0]).max(initial=0.0) / np.hypot(*d)
                ok[i, j] = dev <= tol
        hops = np.full(n, n + 1)
        hops[0] = 0
        for i in range(n):
            reach = np.flatnonzero(ok[i])
            hops[reach] = np.minimum(hops[reach], hops[i] + 1)
        assert fewest_vertices(pts, tol) == hops[-1] + 1


def test_dense_exact_resolves_each_piece_to_a_fraction_of_tol():
    bend = [lambda w: np.stack([w, 0.1 * np.sin(40 * w)], -1)]  # short waves: the start grid is too coarse
    pts = dense_exact(bend, 1e-5, start=65)
    mid = bend[0](0.5 * (np.linspace(0, 1, len(pts))[1:] + np.linspace(0, 1, len(pts))[:-1]))
    assert distances_to_polyline(mid, pts).max() <= 1e-4 * 1e-5


# -- the mesh check every solid made from arrays passes -----------------------------------------
_TETRA_V = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
_TETRA_F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


@pytest.mark.parametrize("faces,vertices,message", [
    (_TETRA_F[:3], _TETRA_V, "not a valid solid"),                               # open
    (np.concatenate([_TETRA_F[:3], _TETRA_F[3:, ::-1]]), _TETRA_V, "not a valid solid"),  # one face flipped
    (_TETRA_F[:, ::-1], _TETRA_V, "inside out"),                                 # all flipped
    (_TETRA_F, _TETRA_V * np.array([1e-5, 1.0, 1.0]) + [1e3, 0, 0], "single precision"),  # two corners one in float32
    (np.concatenate([_TETRA_F, [[0, 1, 4]]]), _TETRA_V, "missing vertices"),
    (_TETRA_F, _TETRA_V * np.array([1.0, np.nan, 1.0]), "non-finite"),
])
def test_invalid_meshes_are_refused_as_manifold3d_would(faces, vertices, message):
    from gearkit.solids import Solid

    with pytest.raises(GeometryError, match=message):
        Solid.from_arrays(vertices, faces, "bad", {})


def test_a_mesh_numpy_refuses_goes_to_manifold3d_which_merges_its_coincident_vertices():
    # a pin ring's tooth polyline meets the next one in coincident vertices: facets of zero area,
    # which manifold3d merges away (as it did for every solid before the numpy check)
    import trimesh

    from gearkit.contact.pins import pin_ring
    from gearkit.solids import SolidSpec, gear_solid

    ring = gear_solid(pin_ring(8, 40.0, 3.0, internal=True), SolidSpec(6.0), 0.015)
    v, f = ring.arrays()
    mesh = trimesh.Trimesh(v, f, process=False)
    assert mesh.is_watertight and mesh.volume == pytest.approx(ring.volume, rel=1e-9) and ring.volume > 0


def test_a_gear_checked_with_numpy_measures_as_manifold3d_does():
    from gearkit.families.involute import GearSpec, tooth_profile
    from gearkit.solids import SolidSpec, gear_solid

    solid = gear_solid(tooth_profile(GearSpec(17, 2.0, helix_angle_deg=15.0)), SolidSpec(8.0, bore=10.0), 1e-2)
    volume, area, bounds = solid.volume, solid.area, solid.bounds
    man = solid.manifold  # built on request from the same arrays
    assert volume == pytest.approx(man.volume(), rel=1e-12)
    assert area == pytest.approx(man.surface_area(), rel=1e-12)
    assert np.allclose(np.ravel(bounds), np.asarray(man.bounding_box()), rtol=0, atol=1e-12)
    assert solid.faces == man.num_tri()
    moved = solid.placed(0.3, (1.0, 2.0, 3.0))
    assert moved.volume == pytest.approx(volume, rel=1e-12)
    assert moved.manifold.volume() == pytest.approx(volume, rel=1e-12)


def test_leg_bound_holds_across_an_inflection_and_refuses_inconsistent_parts():
    """A curve built from its tangent's angle theta(t) = c1 t - c2 t^2 (two monotone parts on t >= 0;
    an inflection where c1 = 2 c2 t): the parallelogram bound of random legs against random chords is
    at least the distance of the densely integrated curve from the chord (oracle: the integration,
    to its own step error ``STEP_ERR``), and parts that do not reproduce the end tangent give inf."""
    from gearkit.chords import chord_distance, leg_bound

    rng = np.random.default_rng(7)
    t = np.linspace(0.0, 1.0, 20001)
    step_err = 1e-8  # trapezoid integration of a unit tangent over steps of 5e-5
    for _ in range(200):
        c1, c2 = rng.uniform(-1.5, 1.5), rng.uniform(0.0, 1.5)
        theta = c1 * t - c2 * t * t
        tan = np.stack([np.cos(theta), np.sin(theta)], -1)
        curve = np.concatenate([[[0.0, 0.0]], np.cumsum(0.5 * (tan[1:] + tan[:-1]) * np.diff(t)[:, None], axis=0)])
        i, j = np.sort(rng.choice(len(t), 2, replace=False))
        k, m = np.sort(rng.choice(np.arange(i, j + 1), 2))  # the chord: any chord around the leg
        parts = np.array([c1 * (t[j] - t[i]), -c2 * (t[j] ** 2 - t[i] ** 2)])
        bound = leg_bound(curve[i], curve[j], tan[i], tan[j], parts, curve[k], curve[m])
        real = chord_distance(curve[k], curve[m], curve[i:j + 1]).max()
        if np.isfinite(bound):
            assert real <= bound + step_err, (c1, c2, i, j)
        else:  # only a range of a quarter turn or more is refused
            assert abs(parts).sum() >= 0.5 * np.pi - 1e-12
        wrong = leg_bound(curve[i], curve[j], tan[i], tan[j], parts + np.array([0.1, 0.0]), curve[k], curve[m])
        assert not np.isfinite(wrong) or abs(parts).sum() < 1e-9


def _bump(w):
    """A bump of height 0.1 the parameter crosses within a few thousandths near w = 0.053."""
    t = np.tanh((w - 0.053) / 0.001)
    return np.stack([t + w, 0.1 * (1 - t * t)], -1)


@pytest.mark.parametrize("bound,middle", [(False, False), (True, False), (True, True)],
                         ids=["probed", "proven", "proven through the middle"])
def test_refinement_probes_each_interval_once_and_carries_what_a_fresh_probe_gives(monkeypatch, bound, middle):
    """A round probes only the intervals the round before made (an interval's probes and measures
    depend on its two ends alone): over all rounds no interval is probed twice, and the probes the
    sampling ends with are, to the last bit, those a fresh probe of its final intervals gives. The
    proven paths on a flank of the cycloid disc (its pin walk ends in a square root: many rounds),
    the probed one on a narrow bump."""
    import gearkit.refine as acc
    from gearkit.chords import angle_parts
    from gearkit.families import cycloidal as cyc

    name, at = ("interval_bounds", 7) if bound else ("_probe", 4)  # the measure and its ``rows`` argument
    measure = getattr(acc, name)
    probed = []

    def spy(*args, **kwargs):
        w = args[1]
        rows = args[at] if len(args) > at else kwargs.get("rows")
        rows = np.arange(len(w) - 1) if rows is None else rows
        probed.extend(zip(w[rows].tolist(), w[rows + 1].tolist()))
        return measure(*args, **kwargs)

    monkeypatch.setattr(acc, name, spy)
    curve = cyc.disc_profile(cyc.DriveSpec(12, 11, 40.0, 3.0, 1.5)).half.pieces[0] if bound else _bump
    tol = 1e-3 * (1.5 if bound else 1.0)
    w0 = np.linspace(0.0, 1.0, 5)
    if middle:
        w, pts, achieved, probes, q = acc.refine_samples([curve], [w0], None, tol, middle=True,
                                                         turned=acc.first_turnings([curve], [w0], middle=True))[0]
    else:
        w, pts, achieved, probes, q = acc.refine_sample(curve, w0, None if bound else curve(w0), tol, bound=bound)
    assert bool(achieved <= tol)
    distinct = len(set(probed))
    assert len(probed) == distinct, f"{len(probed) - distinct} intervals probed again"
    assert distinct > len(w) - 1  # several rounds: intervals of earlier rounds were split and left alone
    if middle:
        fresh = measure(angle_parts(curve.turning), w, *angle_parts(curve.turning)(w), tol, acc._MIDDLE,
                        more=acc._QUARTERS)
    elif bound:
        fresh = measure(angle_parts(curve.turning), w, *angle_parts(curve.turning)(w), tol, acc._PROBES)
    else:
        fresh = measure(lambda x, rows: curve(np.ravel(x)), w, pts, tol)
    assert np.array_equal(fresh[0], probes) and np.array_equal(fresh[1], q)


def test_an_interval_bound_is_the_largest_bound_of_its_legs_bounded_one_by_one():
    """The walk through an interval's probes shares each probe's distance between the two legs it ends;
    oracle: :func:`leg_bound` of every leg on its own (points, tangents and parts of the walk, the
    interval's chord), whose largest is the interval's bound to the last bit. On the flank and fillet
    of a z = 12 gear (two angle parts each) and its tip arc (one)."""
    from gearkit.refine import _PROBES
    from gearkit.chords import angle_parts, interval_bounds, leg_bound
    from gearkit.families.involute import GearSpec, tooth_profile

    for piece in tooth_profile(GearSpec(12, 2.0)).half.pieces:
        turning = angle_parts(piece.turning)
        w = np.linspace(0.0, 1.0, 9)
        pts, tan, parts = turning(w)
        probes, q, tq, pq, bound = interval_bounds(turning, w, pts, tan, parts, 1e-9, _PROBES)
        for i in range(len(w) - 1):
            p = np.concatenate([pts[i:i + 1], q[i], pts[i + 1:i + 2]])
            t = np.concatenate([tan[i:i + 1], tq[i], tan[i + 1:i + 2]])
            a = np.concatenate([parts[i:i + 1], pq[i], parts[i + 1:i + 2]])
            legs = [leg_bound(p[j], p[j + 1], t[j], t[j + 1], a[j + 1] - a[j], pts[i], pts[i + 1])
                    for j in range(len(p) - 1)]
            assert np.isfinite(bound[i]) and bound[i] == max(legs), (piece.label, i)


@pytest.mark.parametrize("pairs", [None, 64])
def test_edge_distances_are_the_nearest_of_all_the_edges(monkeypatch, pairs):
    """Oracle: every edge measured (brute force). Points inside rings whose edges hug the circle of
    their distance about them (a roller's envelope against its pitch curve: the pruning by spans is
    at its weakest there), outside them, near them and on vertices; open and closed; a few edges to
    tens of thousands; coordinates from 1e-3 to 1e3. Also with blocks of points split whenever they
    hold more than 64 (point, span) pairs (the bound on the memory a block takes)."""
    from gearkit import distances
    from gearkit.chords import chord_distance
    from gearkit.distances import edge_distances

    if pairs:
        monkeypatch.setattr(distances, "_PAIRS", pairs)

    rng = np.random.default_rng(20)
    for n in (1, 2, 3, 17, 1000, 20000):
        t = np.sort(rng.uniform(0.0, 2.0 * np.pi, n))
        r = 1.0 + 0.3 * np.sin(3.0 * t) * rng.uniform()
        scale = 10.0 ** rng.uniform(-3.0, 3.0)
        ring = scale * np.stack([r * np.cos(t), r * np.sin(t)], -1) + rng.normal(size=2)
        hug = scale * 0.999 * np.stack([np.cos(rng.uniform(0, 7, 200)), np.sin(rng.uniform(0, 7, 200))], -1)
        q = np.concatenate([0.05 * hug, ring[rng.integers(0, n, 50)], 3.0 * hug,
                            ring[rng.integers(0, n, 50)] + 1e-9 * scale * rng.normal(size=(50, 2))])
        for closed in (False, True):
            a = np.concatenate([ring, ring[:1]]) if closed else ring
            if len(a) < 2:
                continue
            brute = chord_distance(a[:-1][None], a[1:][None], q[:, None]).min(axis=1)
            fast = edge_distances(q, ring, closed=closed)
            assert np.allclose(fast, brute, rtol=1e-13, atol=1e-13 * scale), (n, closed)


class _Probed:
    """A curve with a ``turning`` that gives no angle parts (as a trochoid's): sampled on its probes."""

    def __call__(self, w):
        return _bump(np.asarray(w))

    def turning(self, w):
        return None


def test_curves_sampled_together_get_what_each_gets_alone_and_stay_within_tol():
    """:func:`gearkit.accuracy.sample_curves` refines several curves as one (one pass of bookkeeping per
    round); every interval is measured on its own, so each curve keeps the vertices and the achieved
    deviation it gets alone, to the last bit. The mix: a tooth's pieces (a tip arc with one angle part,
    envelope branches with two), a cycloid disc's pin envelope (many rounds), a curve with no
    ``turning`` and one whose ``turning`` gives none (both probed). Each is also measured against its
    exact curve evaluated densely (the independent measure): within tol."""
    from gearkit.accuracy import sample_curves
    from gearkit.families import cycloidal as cyc
    from gearkit.families.involute import GearSpec, tooth_profile

    tol = 1e-4
    curves = list(tooth_profile(GearSpec(8, 1.0)).half.pieces) + [_bump, _Probed()]
    curves += list(cyc.disc_profile(cyc.DriveSpec(12, 11, 40.0, 3.0, 1.5)).half.pieces)
    together = sample_curves(curves, tol)
    for curve, (w, pts, achieved) in zip(curves, together):
        alone = adaptive_sample(curve, tol, fewest=True)
        assert np.array_equal(w, alone[0]) and np.array_equal(pts, alone[1]) and achieved == alone[2]
        dense = curve(np.linspace(0.0, 1.0, 200_001))
        assert distances_to_polyline(dense, pts).max() <= tol and achieved <= tol


def test_pieces_sampled_together_get_what_each_gets_alone_and_stay_within_the_bound_they_report():
    """:func:`gearkit.accuracy.sample_pieces` places each piece's vertices from its exact turn on a grid
    and accepts them through each chord's middle; every interval is still measured on its own, so a
    piece keeps, to the last bit, the vertices and bound it gets alone. Oracle: each piece evaluated
    densely (the independent measure) lies within the reported deviation of its polyline, which is
    within tol (a probed curve's reported deviation is measured at its probes, not a bound: held to tol).
    The mix: a tooth's pieces (a tip arc with one angle part, envelope branches with two),
    a cycloid disc's pin envelope (its walk ends in a square root), a curve with no ``turning`` and
    one whose ``turning`` gives none (both sampled as :func:`~gearkit.accuracy.sample_curves` does)."""
    from gearkit.accuracy import sample_curves, sample_pieces
    from gearkit.families import cycloidal as cyc
    from gearkit.families.involute import GearSpec, tooth_profile

    tol = 1e-4
    turned = list(tooth_profile(GearSpec(8, 1.0)).half.pieces)
    turned += list(cyc.disc_profile(cyc.DriveSpec(12, 11, 40.0, 3.0, 1.5)).half.pieces)
    curves = turned[:3] + [_bump, _Probed()] + turned[3:]
    together = sample_pieces(curves, tol)
    for k, (curve, (w, pts, achieved)) in enumerate(zip(curves, together)):
        alone = sample_pieces([curve], tol)[0]
        assert np.array_equal(w, alone[0]) and np.array_equal(pts, alone[1]) and achieved == alone[2]
        if k in (3, 4):  # no turning: as the pilot-placed sampling places it
            assert np.array_equal(pts, sample_curves([curve], tol)[0][1])
        dense = curve(np.linspace(0.0, 1.0, 200_001))
        measured = distances_to_polyline(dense, pts).max()
        assert measured <= (tol if k in (3, 4) else achieved) and achieved <= tol, (k, measured, achieved)


def test_a_tooth_is_placed_from_its_turn_and_each_chord_proven_through_its_middle(monkeypatch):
    """The pieces' turning is taken on the 65-point grid, then at the vertices and the chords' middles,
    and at quarter points only where a chord's middle does not prove tol: about two evaluations a
    vertex besides the grid (the pilot-placed sampling takes about six, and its pilot more). Counted on
    the z = 40 tooth at 1e-6 m, whose reported deviation still bounds the measured one (dense oracle)."""
    from gearkit import envelope, pieces
    from gearkit.accuracy import TURN_GRID, sample_pieces
    from gearkit.families.involute import GearSpec, tooth_profile

    half = tooth_profile(GearSpec(40, 1.0)).half
    asked = []
    for module, name in ((envelope, "turning_together"), (pieces.CircleArc, "turning")):
        real = getattr(module, name)

        def spy(*args, real=real, name=name):
            asked.append(sum(len(w) for w in args[1]) if name == "turning_together" else len(args[1]))
            return real(*args)
        monkeypatch.setattr(module, name, spy)
    tol = 1e-6
    sampled = sample_pieces(half.pieces, tol)
    vertices = sum(len(w) for w, _, _ in sampled)
    grid = len(TURN_GRID) * len(half.pieces)
    assert asked[0] == grid or sum(asked[:2]) == grid  # the grid first (the tip arc on its own)
    assert sum(asked) - grid <= 2.2 * vertices, (sum(asked) - grid, vertices)
    for piece, (w, pts, achieved) in zip(half.pieces, sampled):
        dense = piece(np.linspace(0.0, 1.0, 100_001))
        assert distances_to_polyline(dense, pts).max() <= achieved <= tol


def test_quarter_points_are_probed_only_where_the_middle_does_not_prove_tol_and_the_lower_bound_is_kept():
    """:func:`gearkit.chords.interval_bounds` with ``more``: the legs through a chord's middle bound it; only
    where that bound exceeds tol are the quarter points evaluated, and the chord keeps the lower of its
    bound through the middle and its bound through the middle and quarters (each found here on its own).
    On the flank and fillet of a z = 12 gear, whose chords' farthest points lie off their middles.
    Oracle: each chord's deviation measured on a dense evaluation of its stretch, below every bound."""
    from gearkit.chords import RETRY, angle_parts, chord_distance, interval_bounds
    from gearkit.families.involute import GearSpec, tooth_profile

    for piece in tooth_profile(GearSpec(12, 2.0)).half.pieces[1:3]:
        calls = []

        def turning(x, rows=None, piece=piece):
            calls.append(np.size(x))
            return angle_parts(piece.turning)(x)
        w = np.array([0.0, 0.02, 0.06, 0.1, 0.2, 0.4, 0.7, 1.0])
        pts, tan, parts = turning(w)
        middle = interval_bounds(turning, w, pts, tan, parts, 0.0, np.array([0.5]))[-1]
        quarters = interval_bounds(turning, w, pts, tan, parts, 0.0, np.array([0.25, 0.5, 0.75]))[-1]
        sag = [chord_distance(pts[i], pts[i + 1], piece(np.linspace(w[i], w[i + 1], 20_001))).max()
               for i in range(len(w) - 1)]
        assert np.all(sag <= quarters) and np.all(quarters < middle), piece.label
        for tol in (0.5 * (middle[3] + middle[4]), 0.5 * (middle[4] + quarters[4]), 1.0):
            calls.clear()
            both = interval_bounds(turning, w, pts, tan, parts, tol, np.array([0.5]), more=np.array([0.25, 0.75]))
            unproven = middle > tol
            assert calls[:2] == [len(w) - 1] + ([2 * np.count_nonzero(unproven)] if unproven.any() else [])
            kept = np.where(unproven, np.minimum(middle, quarters), middle)
            retried = (kept > tol) & (kept < RETRY * tol)  # bounded again on finer legs (more proof): never higher
            assert np.array_equal(both[-1][~retried], kept[~retried])
            assert np.all(both[-1][retried] <= kept[retried]) and np.all(sag <= both[-1])
            assert both[0].shape == (len(w) - 1, 1)  # the probes returned: the middles alone


def test_distances_to_polyline_are_exact_on_unevenly_sampled_polylines():
    """Oracle: every edge measured (brute force). Polylines as uneven as an adaptive sampling leaves
    them (runs of close vertices beside single long chords, a short edge bunch far from a long edge
    passing near a point): the nearest vertices' edges alone would read 1.5 to 100 times too far for
    many points; the exact fallback must give the brute force's distance for all of them."""
    from gearkit.chords import chord_distance
    from gearkit.distances import distances_to_polyline

    rng = np.random.default_rng(7)
    worse = 0
    for trial in range(40):
        n = int(rng.integers(8, 400))
        steps = np.where(rng.uniform(size=n) < 0.05, rng.uniform(5.0, 50.0, n), rng.uniform(0.01, 0.2, n))
        t = np.cumsum(steps) / steps.sum() * 2.0 * np.pi * rng.uniform(0.3, 1.0)
        line = np.stack([np.cos(t) * (1 + 0.2 * np.sin(5 * t)), np.sin(t)], -1) * 10.0 ** rng.uniform(-2, 2)
        q = line[rng.integers(0, n, 300)] + rng.normal(size=(300, 2)) * np.abs(line).max() * 0.05
        for closed in (False, True):
            a = np.concatenate([line, line[:1]]) if closed else line
            each = chord_distance(a[:-1][None], a[1:][None], q[:, None])
            brute = each.min(axis=1)
            got = distances_to_polyline(q, line, closed=closed)
            assert np.allclose(got, brute, rtol=1e-12, atol=1e-13 * np.abs(line).max()), (trial, closed)
            # points whose nearest edge touches none of their six nearest vertices (the case the fallback serves)
            six = np.argsort(np.hypot(*(line[None] - q[:, None]).transpose(2, 0, 1)), axis=1)[:, :6]
            e = np.argmin(each, axis=1)
            worse += int(((six != e[:, None]) & (six != (e[:, None] + 1) % len(line))).all(axis=1).sum())
    assert worse >= 100  # the polylines are uneven enough that the nearest vertices alone mislead
