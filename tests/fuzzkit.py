"""The fuzzing harness shared by tests/test_fuzz.py (families) and tests/test_fuzz_products.py.

Every drawn spec is one *case* with one of three outcomes, counted per property:

- ``valid``: it built and passed every check of its property;
- ``spec_error``: it was refused with a :class:`~gearkit.errors.SpecError` that names a field and says why;
- ``defect``: anything else (another exception, a failed check, a terse SpecError; numpy's
  overflow, division and invalid-value warnings are raised as errors, an underflow to zero is not).

In the fast CI run a defect fails the test at once (hypothesis then shrinks it). In the long run
(``GEARKIT_FUZZ_EXAMPLES=N``, N specs per property) a defect is recorded with its reproducer (the
drawn spec) and the run goes on, so one run counts every defect; each property's test then fails
if it recorded any. ``GEARKIT_FUZZ_REPORT=FILE`` appends, per property, one JSON line
``{"property", "tried", "valid", "spec_error", "defect", "defects": [{"spec", "error"}, ...]}``
(the counts are what happened, defects included); while it runs, every 500 cases one line of
counts to ``FILE.progress`` and every defect at once to ``FILE.defects``.

:func:`true_deviation` is the properties' independent measure of a sampled curve's deviation (and
the oracle of the regression tests of what they found).
"""
import functools
import json
import math
import os
import sys
import time
import traceback
from collections import Counter

import numpy as np
from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

from gearkit.errors import SpecError

#: specs per property (the long run: GEARKIT_FUZZ_EXAMPLES=10000)
EXAMPLES = int(os.environ.get("GEARKIT_FUZZ_EXAMPLES", "0")) or None
LONG = EXAMPLES is not None
REPORT = os.environ.get("GEARKIT_FUZZ_REPORT")
#: defects listed in full per property in the report (the count is always exact)
LISTED = 50

#: dense re-evaluation points per exact piece (:func:`true_deviation`, the independent deviation measure)
DENSE = 4001

COUNTS: dict = {}
DEFECTS: dict = {}


def fuzz_settings(fast: int):
    """``fast`` specs per property in CI; ``GEARKIT_FUZZ_EXAMPLES`` of them in the long run."""
    n = fast if not LONG else max(fast, EXAMPLES)
    return settings(max_examples=n, deadline=None, derandomize=not LONG, database=None,
                    suppress_health_check=list(HealthCheck))


def _progress(name, c):
    if REPORT and c["tried"] % 500 == 0:
        with open(REPORT + ".progress", "a") as fh:
            fh.write(json.dumps({"property": name, "time": time.strftime("%H:%M:%S"), **c}) + "\n")


def forget_caches():
    """Empty every ``functools.lru_cache`` of the loaded gearkit modules (the long run keeps nothing
    per case: cached profiles hold their sampled outlines, and a few hundred of them held gigabytes)."""
    for mod in [m for n, m in list(sys.modules.items()) if n == "gearkit" or n.startswith("gearkit.")]:
        for obj in list(vars(mod).values()):
            if isinstance(obj, functools._lru_cache_wrapper):
                obj.cache_clear()


def run(name, spec, build, check):
    """One case: ``build()`` under raised numpy errors, then ``check(result)``; count the outcome.

    ``spec`` is the reproducer (the drawn values, as a repr-able object) recorded with a defect.
    """
    c = COUNTS.setdefault(name, Counter(tried=0, valid=0, spec_error=0, defect=0))
    c["tried"] += 1
    _progress(name, c)
    old = np.seterr(all="raise", under="ignore")  # an underflow to zero is no error
    try:
        try:
            obj = build()
        except SpecError as exc:
            assert exc.field and len(str(exc)) > len(exc.field) + 8, f"terse SpecError: {exc}"
            c["spec_error"] += 1
            return
        check(obj)
        c["valid"] += 1
    except Exception as exc:  # noqa: BLE001 - every other outcome is a defect: counted, and raised in CI
        c["defect"] += 1
        if not LONG:
            raise
        line = traceback.format_exception_only(type(exc), exc)[-1].strip()
        found = {"spec": repr(spec), "error": line[:500]}
        kept = DEFECTS.setdefault(name, [])
        if len(kept) < LISTED:  # the count is exact (COUNTS); the full list goes to FILE.defects
            kept.append(found)
        if REPORT:  # at once, so a long run's defects can be studied while it goes on
            with open(REPORT + ".defects", "a") as fh:
                fh.write(json.dumps({"property": name, **found}) + "\n")
    finally:
        np.seterr(**old)
        if LONG:
            forget_caches()


def write_report():
    """Append one JSON line per property to ``GEARKIT_FUZZ_REPORT`` (if set); then forget them."""
    if REPORT:
        with open(REPORT, "a") as fh:
            for name, c in sorted(COUNTS.items()):
                found = DEFECTS.get(name, [])
                fh.write(json.dumps({"property": name, **c, "defects": found[:LISTED]}) + "\n")
    COUNTS.clear()
    DEFECTS.clear()


def assert_clean(name):
    """The long run's verdict for one property: no defect recorded (the first few shown)."""
    found = DEFECTS.get(name, [])
    assert not found, f"{COUNTS[name]['defect']} defects in {name}: " + "; ".join(f"{d['spec']} -> {d['error']}"
                                                                     for d in found[:3])


def strict_json(obj):
    """``obj`` through strict JSON: no NaN or Infinity (``json.loads`` would accept them)."""
    text = json.dumps(obj, allow_nan=False)

    def refuse(token):
        raise AssertionError(f"non-standard JSON number {token}")
    return json.loads(text, parse_constant=refuse)


HOSTILE = st.sampled_from([math.inf, -math.inf, math.nan, 1e300, -1e300, 1e-300, 0.0, -1.0, 1e-12, "1", None,
                           True, np.float64(2.5), np.int64(7), np.float32(0.3)])


@st.composite
def maybe_hostile(draw, kwargs):
    """``kwargs`` with, for ~15 % of draws, one value replaced by a hostile one."""
    kwargs = dict(kwargs)
    if draw(st.integers(0, 99)) < 15:
        key = draw(st.sampled_from(sorted(kwargs)))
        kwargs[key] = draw(HOSTILE)
    return kwargs


modules = st.floats(0.01, 100.0).map(lambda m: float(f"{m:.5g}"))


class _Stations:
    """A polyline's edges and their *stations*: points spaced at most ``step`` along each edge (ends
    included), in a k-d tree. An edge within ``r`` of a point has a station within ``r + step / 2`` of it,
    so a ball query lists every edge that can be a point's nearest; each is then measured exactly."""

    def __init__(self, polyline):
        from scipy.spatial import cKDTree

        self.a, self.e = polyline[:-1], np.diff(polyline, axis=0)
        self.length = np.hypot(self.e[:, 0], self.e[:, 1])
        positive = self.length[self.length > 0]
        h = float(np.median(positive)) if len(positive) else 1.0
        count = np.clip(np.ceil(self.length / h).astype(np.int64), 1, 10_000) + 1  # stations per edge, ends included
        self.edge = np.repeat(np.arange(len(self.a)), count)
        frac = (np.arange(len(self.edge)) - np.repeat(np.cumsum(count) - count, count)) / np.repeat(count - 1, count)
        self.tree = cKDTree(self.a[self.edge] + frac[:, None] * self.e[self.edge])
        self.step = float((self.length / (count - 1)).max())  # the widest station spacing

    def distance(self, q, ed):
        """Exact distances of the points ``q`` from the edges ``ed`` (the same shape, ``ed`` without the 2)."""
        a, e, length = self.a[ed], self.e[ed], self.length[ed]
        t = np.clip(np.einsum("...i,...i->...", q - a, e) / np.maximum(length * length, 1e-300), 0.0, 1.0)
        return np.hypot(*np.moveaxis(q - (a + t[..., None] * e), -1, 0))

    def upper(self, points, k: int = 4):
        """An upper bound of each point's distance to the polyline: its exact distance to the edges of its
        ``k`` nearest stations (at most its true distance plus half a station spacing)."""
        k = min(k, len(self.edge))
        _, idx = self.tree.query(points, k=k)
        idx = np.asarray(idx).reshape(len(points), k)
        return self.distance(points[:, None, :], self.edge[idx]).min(axis=1)

    def exact(self, points, upper):
        """Exact distance of each point to the polyline, given an upper bound ``upper`` of it: the least
        distance to the edges of every station within ``upper + step / 2`` (one of them is the nearest)."""
        near = self.tree.query_ball_point(points, upper + 0.5 * self.step + 1e-12)
        counts = np.array([len(n) for n in near])
        pt = np.repeat(np.arange(len(points)), counts)
        d = self.distance(points[pt], self.edge[np.concatenate(near).astype(np.int64)])
        out = np.array(upper, dtype=float)
        has = counts > 0
        out[has] = np.minimum(out[has], np.minimum.reduceat(d, (np.cumsum(counts) - counts)[has]))
        return out


def true_deviation(pieces, polyline, dense=None):
    """Largest distance of the exact pieces (``dense`` points each, default ``DENSE``) from a polyline:
    the independent measure of a sampling's deviation. Each point's distance is bounded from above by the
    edges of its nearest stations (:class:`_Stations`), then measured exactly against every edge within
    that bound, largest bound first, until no point left can exceed the largest exact distance found."""
    w = np.linspace(0.0, 1.0, dense or DENSE)
    exact = np.concatenate([p(w) for p in pieces])
    stations = _Stations(np.asarray(polyline, dtype=float))
    d = stations.upper(exact)
    order = np.argsort(d)[::-1]
    best = 0.0
    for lo in range(0, len(order), 4096):
        chunk = order[lo:lo + 4096]
        if d[chunk[0]] <= best:
            break
        best = max(best, float(stations.exact(exact[chunk], d[chunk]).max()))
    return best


def face_half_planes(spec, phi):
    """A flat face's lines at cam angles ``phi`` in the cam frame, written out from the frames of
    :class:`~gearkit.families.cam.CamSpec` alone (no envelope, no pose of the kernel): unit normals ``n``
    away from the cam axis and heights ``h``, the cam being ``n . x <= h`` for every line. A translating
    face is the line ``y = r0 + s``; a rocker's lies along the arm through the pivot ``(l0, 0)`` at
    ``Psi = asin(r0 / l0) + s / l`` from the line to the axis (normal ``(sin Psi, cos Psi)``, height
    ``l0 sin Psi``); the cam turned by ``phi`` counter-clockwise puts them at ``-phi`` in its frame."""
    phi = np.asarray(phi, dtype=float)
    s = spec.motion.evaluate(phi)[0]
    if spec.follower == "translating":
        nf, h = np.stack([np.zeros_like(s), np.ones_like(s)], -1), spec.prime_radius + s
    else:
        psi = math.asin(spec.prime_radius / spec.pivot_distance) + s / spec.arm_length
        nf, h = np.stack([np.sin(psi), np.cos(psi)], -1), spec.pivot_distance * np.sin(psi)
    c, sn = np.cos(phi), np.sin(phi)
    return np.stack([c * nf[:, 0] + sn * nf[:, 1], -sn * nf[:, 0] + c * nf[:, 1]], -1), h


def convex_dents(outline):
    """How far each vertex of a closed polygon (counter-clockwise) lies on the inner side of the chord of its
    two neighbours (mm; negative where it turns back), and how many times round its tangent turns (1 for a
    convex polygon). A vertex's distance from its neighbours' chord is well conditioned whatever its edges'
    lengths (it is at most the shorter edge); the distance of the next vertex from the line of an edge is
    not: the line of an edge a few round-offs long (the ends of a dwell of 2e-12 degrees, 4e-13 mm apart)
    points anywhere, and the next edge's far end 0.025 mm on stood 6e-6 mm behind it."""
    e = np.roll(outline, -1, axis=0) - outline
    en = np.roll(e, -1, axis=0)
    cross = e[:, 0] * en[:, 1] - e[:, 1] * en[:, 0]
    dent = cross / np.maximum(np.hypot(*(e + en).T), 1e-300)
    winding = int(np.round(np.arctan2(cross, (e * en).sum(axis=1)).sum() / (2 * math.pi)))
    return dent, winding


#: :func:`check_flat_cam`'s lines per line step about each velocity jump, and the steps either side they span
JUMP_LINES, JUMP_REACH = 100, 6


def check_flat_cam(spec, outline, tol, lines: int = 1 << 16):
    """A flat face's cam is the intersection of its half-planes (:func:`face_half_planes` at ``lines``
    cam angles and at every velocity jump, ``JUMP_LINES`` times as dense within ``JUMP_REACH`` steps of
    each jump): the outline (counter-clockwise) must lie inside every one (round-off of its points,
    computed through lengths up to the pivot), turn one way (a convex cam: no
    vertex behind its neighbours' chord by more than that round-off, :func:`convex_dents`), and
    enclose the area of their polygon within its perimeter times ``tol`` plus the polygon's own excess
    (each vertex between two lines ``delta`` apart stands out by at most ``D (k delta)^2 / 8``: ``D`` the
    polygon's diameter bounding the curvature radius, ``k = 1 + max|psi'|`` how much faster than the cam
    the face turns). Returns ``(area of the outline, area of the polygon, allowed difference)``."""
    from scipy.spatial import ConvexHull, HalfspaceIntersection

    jumps = np.array([p for p, dv, _, _ in spec.motion.jumps() if dv != 0.0])
    phi = np.concatenate([np.linspace(0.0, 2 * math.pi, lines, endpoint=False), jumps])
    n, h = face_half_planes(spec, phi)
    reach = spec.prime_radius + spec.stroke + (spec.pivot_distance or 0.0) + (spec.arm_length or 0.0)
    slack = 1e-12 * reach
    sparse = slice(None, None, max(lines // 4096, 1))
    # about each velocity jump, where a small lift's slide folds within a fraction of a line step of it: lines
    # JUMP_LINES times as dense as the whole turn's over JUMP_REACH of its steps either side
    near = (jumps[:, None] + np.linspace(-JUMP_REACH, JUMP_REACH, 2 * JUMP_REACH * JUMP_LINES + 1)
            * 2 * math.pi / lines).reshape(-1)
    nj, hj = face_half_planes(spec, near) if len(near) else (np.zeros((0, 2)), np.zeros(0))
    nv, hv = np.concatenate([n[sparse], nj]), np.concatenate([h[sparse], hj])
    for lo in range(0, len(outline), 1024):
        worst = float((outline[lo:lo + 1024] @ nv.T - hv).max())
        assert worst <= slack, f"an outline vertex lies {worst:.3g} mm outside a half-plane of the face"
    dent, winding = convex_dents(outline)
    assert dent.min() >= -slack, f"the outline turns back by {-dent.min():.3g} mm: not a convex cam"
    assert winding == 1, f"the outline's tangent turns {winding} times round: not a convex cam"
    polygon = HalfspaceIntersection(np.column_stack([n, -h]), np.zeros(2)).intersections
    hull = ConvexHull(polygon)
    k = 1.0 + (np.abs(spec.motion.evaluate(phi)[1]).max() / spec.arm_length if spec.follower == "rocker" else 0.0)
    diameter = 2.0 * float(np.hypot(*polygon.T).max())
    excess = diameter * (k * 2 * math.pi / lines) ** 2 / 8
    x, y = outline.T
    area = 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    allowed = hull.area * (tol + excess)  # hull.area is the polygon's perimeter in 2-D
    assert abs(area - hull.volume) <= allowed, f"outline area {area:.9g} against the half-planes' {hull.volume:.9g}"
    return area, float(hull.volume), allowed


#: a flat cam's vertex stands off the outline's convex hull by round-off only, of the lengths up to the pivot
ON_HULL = 1e-12


def check_flat_outline(prof, tol, lines: int = 1 << 16):
    """A flat face's cam outline at ``tol``: its reported deviation within ``tol``, inside the face's half-planes
    and convex (:func:`check_flat_cam`), and every vertex on the outline's convex hull (scipy's) within
    ``ON_HULL`` of the lengths up to the pivot. Returns the outline."""
    from scipy.spatial import ConvexHull

    spec = prof.spec
    out = prof.outline(tol)
    assert prof.achieved(tol) <= tol
    check_flat_cam(spec, out, tol, lines)
    reach = spec.prime_radius + spec.stroke + (spec.pivot_distance or 0.0) + (spec.arm_length or 0.0)
    hull = ConvexHull(out).vertices  # counter-clockwise in 2-D, as the outline runs: the same cyclic order
    first = int(np.argmin(hull))
    idx = np.roll(hull, -first)
    assert (np.diff(idx) > 0).all(), "the outline's convex hull visits its vertices out of their order"
    # each vertex against the hull edge spanning it (a floor tol's outline has some 1e5 vertices: not all edges)
    k = np.searchsorted(idx, np.arange(len(out)), side="right") - 1
    a, b = out[idx[k]], out[idx[(k + 1) % len(idx)]]
    d, r = b - a, out - a
    inside = (d[:, 0] * r[:, 1] - d[:, 1] * r[:, 0]) / np.hypot(*d.T)  # left of the edge: inside
    assert inside.max() <= ON_HULL * reach
    return out
