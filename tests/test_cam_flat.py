"""A flat face's cam is the intersection of its half-planes, and where the face cannot follow its law the
check reports how far and where the follower leaves it (never an error).

Oracles, none of them the product's envelope, trimming or departure code: the face's lines written out
from the frames of :class:`CamSpec` (``fuzzkit.face_half_planes``) and scipy's intersection of 65 536 of
their half-planes (``fuzzkit.check_flat_cam``: the outline inside every one, convex, enclosing their
polygon's area); the follower's pose on that polygon by brute force over its vertices (a translating face
rests on the highest vertex, a rocker's line through the pivot on the vertex at the largest line angle).
"""
import math

import numpy as np
import pytest
from fuzzkit import check_flat_cam, face_half_planes, true_deviation

from gearkit.checks.cam import check_cam
from gearkit.families.cam import CamSpec, MotionProgram, MotionSegment, cam_profile

#: the bound is proven: the dense measure may exceed it by round-off only
BOUND_SLACK = 1e-9
#: the oracle's lines over one turn
LINES = 1 << 16
#: points of the exact pieces checked per piece
DENSE = 4001
#: a point of the cam stands outside a half-plane by round-off only: of the lengths up to the pivot (as
#: fuzzkit.check_flat_cam allows its vertices)
INSIDE = 1e-12
#: the product's pose and the oracle's agree to this fraction of r0 + stroke: their polygons of sampled lines
#: (from different start angles) differ by their vertices' excess, below 1e-7 of the cam's size here
AGREE = 1e-6

ROCKER = dict(follower="rocker", contact="flat")
#: flat rockers whose face turns several times as fast as the cam and back on the return (psi' from -6.9 to
#: 6.9; from -2.5 to 2.6): the kept arcs of the envelope lie out of the order of the cam angle, and pairing
#: them by it raised GeometryError ("a cut of the flat face's envelope meets neither a crossing nor a face line")
STEEP = [
    (dict(prime_radius=20.0, pivot_distance=24.0, arm_length=27.13), (35.0, 20.0, 1.75, 20.0, "polynomial_345"), 1e-5),
    (dict(prime_radius=8.0, pivot_distance=20.33, arm_length=10.17), (26.7, 92.2, 0.0, 93.0, "harmonic"), 1e-4),
]

#: a swallowtail whose crossing is so shallow that the envelope past it stays within the kept samples' slack
#: (1e-7 of r0 + stroke) for many samples: the crossing lay beyond the few chords searched, the arcs were
#: joined at their last kept samples, and a vertex stood 3.04e-6 mm outside a half-plane
SHALLOW = [
    (dict(prime_radius=198.87489953108155, pivot_distance=582.6105270306667, arm_length=497.86391716055635),
     (230.5782200006818, 140.824459574811, 4.133697514044821, 123.79116566821037, "harmonic"), 1e-4),
]


#: swallowtails shallower than the kept samples' old slack (1e-7 of r0 + stroke; 1.6e-7 and 5.7e-7 mm deep, 0.5 degrees
#: wide, just before a cycloidal rise ends): every sample was kept and vertices stood that far outside a half-plane;
#: the same swallowtail 4 samples wide (lift 3.9727), where Newton on the crossing fell to the curve meeting itself
SLIVER = [
    (dict(prime_radius=8.0, pivot_distance=10.02147318225105, arm_length=11.738518689816196),
     (3.9667567402513733, 31.5, 59.0, 104.07049232462066, "cycloidal"), 1e-5),
    (dict(prime_radius=31.5, pivot_distance=39.45955065511351, arm_length=46.22041734115127),
     (15.619104664739782, 31.5, 59.0, 104.07049232462066, "cycloidal"), 1e-5),
    (dict(prime_radius=8.0, pivot_distance=10.02147318225105, arm_length=11.738518689816196),
     (3.9727, 31.5, 59.0, 104.07049232462066, "cycloidal"), 1e-5),
    # a polynomial_4567 return: 4.36e-6 mm outside
    (dict(prime_radius=39.06527482107495, pivot_distance=63.229241166192665, arm_length=52.103007412441094),
     (0.781305496421499, 20.0, 0.9, 27.759925869977888, "polynomial_4567"), 1e-3),
]
#: a harmonic rise whose acceleration jump at its end is a cusp of the envelope: the kept arcs' crossing lies
#: past it, where the chord across the join led Newton astray (GeometryError: "meets the next one neither at a
#: crossing nor along a corner's face line")
ACCELERATION_JUMP = [
    (dict(prime_radius=70.9907652857193, pivot_distance=145.50958548524014, arm_length=141.83358984052643),
     (42.59445917143158, 67.20731476814215, 20.377810328596134, 67.20731476814215, "harmonic"), 1e-3),
]

#: a dwell between a steep rise and return whose arc on the cam is 9e-5 rad wide, under a quarter of the kept samples'
#: step: no sample of it was kept and the rise's and the return's arcs were joined at their crossing, 8.75 um outside
#: the dwell's lines; with its neighbours (lift and arm 1e-6 apart, tol 1e-3 and 1e-5 r0)
_NARROW_KW = dict(prime_radius=90.924628409045, pivot_distance=216.09747403229971, arm_length=304.88450930124304)
_NARROW_MOTION = (216.09747403229971, 20.0, 34.33031085368909, 90.924628409045, "modified_trapezoid")
NARROW_ARC = [(_NARROW_KW, _NARROW_MOTION, t) for t in (1e-4, 1e-3, 1e-5)] + [
    (_NARROW_KW, (_NARROW_MOTION[0] * f,) + _NARROW_MOTION[1:], 1e-4) for f in (1 - 1e-6, 1 + 1e-6)] + [
    (dict(_NARROW_KW, arm_length=_NARROW_KW["arm_length"] * f), _NARROW_MOTION, 1e-4) for f in (1 - 1e-6, 1 + 1e-6)]
#: cam angles of the dwell's lines in the narrow arc's oracle (spaced 3e-5 rad: three across the arc)
DWELL_LINES = 20001


@pytest.mark.parametrize("kw, motion, tol_r0", NARROW_ARC)
def test_a_dwell_arc_narrower_than_a_sample_is_kept(kw, motion, tol_r0):
    spec = CamSpec(motion=MotionProgram.rise_dwell_return(*motion), **ROCKER, **kw)
    out = cam_profile(spec).outline(tol_r0 * spec.prime_radius)
    # the dwell's face is one line turning with the cam: every vertex lies inside all of its lines
    _, a, b, _, _ = spec.motion.phases()[1]
    n, h = face_half_planes(spec, np.linspace(a, b, DWELL_LINES))
    reach = spec.prime_radius + spec.stroke + spec.pivot_distance + spec.arm_length
    assert max(float((out[k:k + 1024] @ n.T - h).max()) for k in range(0, len(out), 1024)) <= INSIDE * reach


@pytest.mark.parametrize("kw, motion, tol_r0", STEEP + SHALLOW + SLIVER + ACCELERATION_JUMP + NARROW_ARC)
def test_steep_flat_rocker_cam_is_the_intersection_of_its_half_planes(kw, motion, tol_r0):
    spec = CamSpec(motion=MotionProgram.rise_dwell_return(*motion), **ROCKER, **kw)
    prof = cam_profile(spec)
    tol = tol_r0 * spec.prime_radius
    out, achieved = prof.outline(tol), prof.achieved(tol)
    closed = np.concatenate([out[::-1], out[-1:]])  # the pieces' own order
    assert true_deviation(prof.pieces, closed) <= achieved * (1 + BOUND_SLACK) and achieved <= tol
    check_flat_cam(spec, out, tol, LINES)
    # not only the outline's vertices: every point of the exact pieces lies inside every half-plane (a sliver a few
    # samples wide holds no vertex at this tol)
    n, h = face_half_planes(spec, np.linspace(0.0, 2 * math.pi, LINES // 16, endpoint=False))
    dense = np.concatenate([pc(np.linspace(0.0, 1.0, DENSE)) for pc in prof.pieces])
    reach = spec.prime_radius + spec.stroke + spec.pivot_distance + spec.arm_length
    assert max(float((dense[k:k + 4096] @ n.T - h).max()) for k in range(0, len(dense), 4096)) <= INSIDE * reach
    # the pieces follow each other around the cam: each starts where the one before it ends
    ends = np.array([[pc(np.array([0.0]))[0], pc(np.array([1.0]))[0]] for pc in prof.pieces])
    gaps = np.hypot(*(ends[:, 0] - np.roll(ends[:, 1], 1, axis=0)).T)
    assert gaps.max() <= 1e-6 * (spec.prime_radius + spec.stroke)


def brute_departure(spec, phi):
    """How far the follower falls short of its law at cam angles ``phi``, on the polygon of the face's
    half-planes, and where along the face it touches: its pose found over every vertex (a translating face
    rests on the highest; a rocker's turns down about the pivot until a vertex stops it, the one at the
    largest angle seen from the pivot: every vertex lies within a half turn below the prescribed angle, on
    the axis's side of the face). Returns ``(gap, contact, the polygon's longest edge)``."""
    from scipy.spatial import HalfspaceIntersection

    lines = np.concatenate([np.linspace(0.0, 2 * math.pi, LINES, endpoint=False),
                            [p for p, dv, _, _ in spec.motion.jumps() if dv != 0.0]])
    n, h = face_half_planes(spec, lines)
    poly = HalfspaceIntersection(np.column_stack([n, -h]), np.zeros(2)).intersections
    gap, contact = [], []
    for p, s in zip(phi, spec.motion.evaluate(phi)[0]):
        c, sn = math.cos(p), math.sin(p)
        x, y = c * poly[:, 0] - sn * poly[:, 1], sn * poly[:, 0] + c * poly[:, 1]  # the cam turned by phi
        if spec.follower == "translating":
            k = int(np.argmax(y))
            gap.append(spec.prime_radius + s - y[k])
            contact.append(x[k] - spec.offset)
            continue
        psi = math.asin(spec.prime_radius / spec.pivot_distance) + s / spec.arm_length
        seen = np.arctan2(y, spec.pivot_distance - x)
        k = int(np.argmax(seen))
        gap.append(spec.arm_length * (psi - seen[k]))
        contact.append(math.hypot(spec.pivot_distance - x[k], y[k]))
    around = poly[np.argsort(np.arctan2(poly[:, 1], poly[:, 0]))]
    return np.array(gap), np.array(contact), float(np.hypot(*(np.roll(around, 1, axis=0) - around).T).max())


DEPARTING = STEEP + [
    # a rocker turning back on a constant-velocity return: every line of the return is cut away (the cut
    # holds the return's velocity jump, so the profile's undercut flag did not count it)
    (dict(prime_radius=29.920755273305605, pivot_distance=35.90490632796673, arm_length=17.952453163983364),
     (14.960377636652803, 29.920755273305605, 29.920755273305605, 20.0, "constant_velocity"), 1e-4),
    # translating: r0 + s + s'' < 0 (textbook 3.45) on a cycloidal rise, and a velocity drop at a
    # constant-velocity rise's end (s'' = -inf there: no face can follow it)
    (dict(prime_radius=40.0, follower="translating"), (20.0, 60.0, 60.0, 60.0, "cycloidal"), 1e-4),
    (dict(prime_radius=10.0, follower="translating"), (8.0, 60.0, 20.0, 60.0, "constant_velocity"), 1e-4),
]
#: cams a flat face follows exactly: r0 above max(-s - s'') (translating), a slow rocker
FOLLOWING = [
    (dict(prime_radius=60.0, follower="translating"), (10.0, 90.0, 20.0, 90.0, "cycloidal"), 1e-4),
    (dict(prime_radius=30.0, pivot_distance=80.0, arm_length=60.0), (5.0, 90.0, 20.0, 90.0, "cycloidal"), 1e-4),
]


@pytest.mark.parametrize("kw, motion, tol_r0", DEPARTING + FOLLOWING)
def test_flat_face_departure_from_its_law_is_reported_where_and_how_far(kw, motion, tol_r0):
    spec = CamSpec(motion=MotionProgram.rise_dwell_return(*motion), **dict(ROCKER, **kw))
    tol = tol_r0 * spec.prime_radius
    res = check_cam(spec, tol)
    finding = next(f for f in res.report.findings if f.id == "undercut")
    grid = np.linspace(0.0, 2 * math.pi, 7201)  # the angles the check reads
    brute, contact, spacing = brute_departure(spec, grid)
    agree = AGREE * (spec.prime_radius + spec.stroke)
    worst, at = res.values["departure_max"], res.values["departure_at_deg"]
    assert abs(brute_departure(spec, np.array([math.radians(at)]))[0][0] - worst) <= agree
    assert abs(worst - brute.max()) <= agree and finding.value == worst and finding.limit == tol
    # where the face touches the cam (its law's contact, or where it rests), to the polygon's longest edge
    assert np.allclose(res.values["face_contact_range"], [contact.min(), contact.max()], rtol=0.0, atol=spacing)
    inside = np.zeros(len(grid), dtype=bool)
    for a, b in res.values["departure_deg"]:
        inside |= (np.degrees(grid) >= a - 1e-9) & (np.degrees(grid) <= b + 1e-9)
    assert not inside[brute < tol - agree].any() and inside[brute > tol + agree].all()
    if (kw, motion, tol_r0) in FOLLOWING:
        assert worst <= agree and finding.status == "ok" and res.values["undercut"] is False
    else:
        assert worst > 100 * tol and finding.status == "fail" and res.report.status == "fail"
        assert res.values["undercut"] is True and f"{worst:.6g}" in finding.message


def test_flat_face_on_an_eccentric_circle_keeps_its_law():
    # an eccentric circle (radius R, eccentricity eps) moves a flat face by s = eps (1 - cos phi) exactly:
    # the harmonic law over half turns is followed, nothing is cut
    big_r, eps = 30.0, 6.0
    prog = MotionProgram((MotionSegment("rise", 180.0, 2 * eps, "harmonic"),
                          MotionSegment("return", 180.0, 2 * eps, "harmonic")))
    res = check_cam(CamSpec(big_r - eps, prog, contact="flat"), 1e-3)
    assert res.values["departure_max"] <= 1e-9 * (big_r + eps) and res.values["departure_deg"] == []


def test_kept_arcs_are_joined_in_the_order_of_the_boundary_whatever_way_they_run():
    # the intersection of three disks (radius R, centres D from the axis at 90, 210 and 330 degrees): its
    # boundary is one arc of each circle, the disk centred opposite. An "envelope" walks the three circles
    # past both vertices of their arcs, in the order 0, 2, 1 of w and the second one counter-clockwise: the
    # kept arcs follow each other around the region clockwise (1, 0, 2 from the top), the second walked
    # against w, each meeting the next at a vertex, sqrt(4 R^2 - 3 D^2)/2 - D/2 from the axis by symmetry
    from gearkit.families.cam.faces import face_boundary

    big_r, d = 1.2, 0.5
    centres = d * np.stack([np.cos(np.radians([90.0, 210.0, 330.0])), np.sin(np.radians([90.0, 210.0, 330.0]))], -1)
    walks = [(0, 350.0, 190.0), (2, 70.0, 230.0), (1, 110.0, -50.0)]  # circle, from, to (degrees about its centre)

    def curve(w):
        w = np.atleast_1d(np.asarray(w, dtype=float))
        k = np.minimum((3 * w).astype(int), 2)
        out = np.empty((len(w), 2))
        for i, (c, a0, a1) in enumerate(walks):
            a = np.radians(a0 + (3 * w[k == i] - i) * (a1 - a0))
            out[k == i] = centres[c] + big_r * np.stack([np.cos(a), np.sin(a)], -1)
        return out

    def depth(points):
        return np.max([np.hypot(*(points - c).T) - big_r for c in centres], axis=0)

    arcs, cuts = face_boundary(curve, depth, 1e-12, [], 1.0)
    rho = 0.5 * (math.sqrt(4 * big_r ** 2 - 3 * d ** 2) - d)
    vertex = {a: rho * np.array([math.cos(math.radians(a)), math.sin(math.radians(a))]) for a in (-30, 90, 210)}
    assert len(arcs) == 3 and all(edge is None and len(spans) == 1 for spans, edge in arcs)
    spans = [spans[0] for spans, _ in arcs]
    ends = np.array([curve(np.array(s)) for s in spans])  # (arc, its start and end, xy)
    polar = np.degrees(np.arctan2(ends[:, :, 1], ends[:, :, 0])).ravel()
    order = [min(vertex, key=lambda a: abs((p - a + 180) % 360 - 180)) for p in polar]
    # clockwise, each arc from one vertex to the next, and the next arc starting where it ends
    assert order in ([90, -30, -30, 210, 210, 90], [-30, 210, 210, 90, 90, -30], [210, 90, 90, -30, -30, 210])
    assert max(np.hypot(*(e - vertex[a])) for e, a in zip(ends.reshape(-1, 2), order)) <= 1e-12
    assert [b < a for a, b in spans].count(True) == 1  # the one arc walked against w
    # the cuts are the rest of w: from each kept arc's end along w to the next one's start
    kept = sum(abs(b - a) for a, b in spans)
    assert len(cuts) == 3 and abs(kept + sum((b - a) % 1.0 for a, b in cuts) - 1.0) <= 1e-12
