"""What the follower leaves of the blank: the envelope's points that bound the cam, and its corners.

**Roller.** The roller sweeps every point within ``R_p`` of the pitch curve: an envelope point is
on the cam when no other roller position covers it, i.e. when its distance to the whole pitch
curve is ``R_p``. Where the roller is larger than the pitch curve's convex radius of curvature, or
at a concave corner of the pitch curve (a velocity jump), the envelope loops inside the swept
region and is cut there.

**Flat face.**
The cam is the intersection of the face's half-planes (:mod:`gearkit.families.cam.halfplanes`), a
convex region whatever the motion asks for. Where the motion asks for a convex cam (``r0 + s + s''
> 0`` for a translating face, textbook 3.45) every line touches it at the envelope point and the
envelope is the cam. Where it does not, the envelope loops (a swallowtail) or, for a rocker whose
face turns back relative to the cam (``1 + psi' < 0``), folds and runs off along the face; the cam
keeps only the envelope's points on the boundary of the intersection. Its boundary is convex and
holds the axis, so the kept arcs follow each other around it in the order of their polar angles
(not of the cam angle: an arc of the face turning back relative to the cam lies between arcs of
other phases, and may run the other way); each meets the next where the envelope crosses itself,
or, at a velocity jump, along the face line of that cam angle (the face slides along it). A slide that runs
back along the line, the way against the boundary, is a fold even where every sample beside it is kept: the
arcs either side of it overlap along the line and meet at their crossing.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.errors import GeometryError
from gearkit.families.cam.crossings import corner_cut, refine_cut
from gearkit.families.cam.faceline import bridge, slides_back
from gearkit.families.cam.halfplanes import face_lines

__all__ = ["roller_depth", "kept_runs", "corner_lines", "face_boundary", "FINEST"]

#: the densest sampling of a flat face's envelope (samples over one turn) that resolves a narrow kept arc
FINEST = (1 << 20) + 1


def roller_depth(pitch_points, radius: float, start: float, samples: int = 65536):
    """How deep (mm) points lie inside the region the roller sweeps: ``R_p`` less their distance to
    the pitch curve (``pitch_points(phi)``, sampled at ``samples`` cam angles over one turn). The
    envelope's points lie a roller radius from the pitch curve, hugging that circle about them for a
    long stretch of it: the distances are measured by spans of edges
    (:func:`~gearkit.distances.edge_distances`), not through a k-d tree's nearest vertices (which
    visited most of the pitch curve for each point: 18 s for one cam)."""
    from gearkit.distances import edge_distances

    pitch = pitch_points(start + np.linspace(0.0, 2.0 * math.pi, samples, endpoint=False))
    return lambda points: radius - edge_distances(points, pitch, closed=True)


def kept_runs(curve, depth, slack: float, meet: float, circles=(), samples: int = 16385):
    """Where the roller's envelope ``curve`` (of ``w`` in [0, 1], one turn) bounds the cam: ``[(wa, wb),
    ...]``, the cuts from a kept arc's end ``wa`` to the next kept arc's start ``wb`` (cyclic, ``wb`` may
    be below ``wa``: the cut runs through ``w = 1``), each refined to the envelope's self-crossing, in
    the order the cam's boundary runs (:func:`_cam_cycle`; a crossing's ends within ``meet``, mm). A
    sample is kept where ``depth`` (:func:`roller_depth`) is at most ``slack`` (mm: the swept region's
    own sampling error). A cut from or to a roller's arc about a velocity jump's corner (``circles``,
    :func:`~gearkit.families.cam.crossings.corner_cut`) is sought where the envelope beside it comes out
    of that circle. Empty when the whole envelope bounds the cam."""
    w = np.linspace(0.0, 1.0, samples)
    keep = depth(curve(w)) <= slack
    keep[-1] = keep[0]  # w = 1 is w = 0
    if keep.all():
        return []
    if not keep.any():
        raise GeometryError("the roller leaves no envelope point on the cam")
    k = np.flatnonzero(keep[:-1])
    starts = [int(j) for j in k if not keep[j - 1 if j else samples - 2]]  # runs beginning at j
    ends = [int(j) for j in k if not keep[j + 1]]  # runs ending at j
    return _cam_cycle(curve, w, keep, starts, ends, meet, circles)


def _cam_cycle(curve, w, keep, starts, ends, meet: float, circles=()):
    """The cuts of the kept runs that bound the cam, followed from run to run around it.

    A sample no roller covers lies on the boundary of the swept region, but not every such boundary
    bounds the cam: a roller far larger than the rise is steep (a lift of several prime radii over a
    short rise) sweeps a finger whose outer side the envelope also traces, uncovered and outside the
    cam, and a large roller on a short steep rise may pinch the cam's nose off, leaving an island of
    uncovered envelope beyond the neck that no shaft holds. Each run's end meets exactly one run's start
    (the swept region's boundary has two arcs at a corner), so the runs fall into cycles, and the cam's
    is the one through the kept sample nearest the axis (the first point of the swept region any ray
    from the axis meets there lies on the cam).

    The crossing that ends a run lies by it: the envelope between the crossings that start and end a run
    bounds the swept region, so no covered sample lies between them, and past the run's end the envelope
    runs inside the region until it comes out at a later run's start (samples within the slack inside a
    shallow loop are kept, and may lie either side of the loop's crossing: :func:`refine_cut` seeks it past
    them). Newton started from a chords' crossing far out (a
    shallow crossing), or a corner's circle left far from the run, may settle on another crossing that
    meets as well: a large roller on a short steep rise pinched the cam's nose off at a neck, and the
    crossing of the island's tip beyond it, or of two of the island's arcs, was taken for the neck's; a
    constant-velocity rocker's one run was joined to itself where the envelope left a corner's circle
    far past the run's start. So a crossing counts only where its ends lie by the run it leaves and by the
    run it enters (:func:`_by_run`), every run's start is tried, and of the crossings that count the first
    past the run's start is taken (one within a sample of the run's last kept sample ends the search).

    Raises
    ------
    GeometryError
        When a run's end meets no run's start, or the runs do not close into a cycle.
    """
    kept = np.flatnonzero(keep[:-1])
    radius = np.hypot(*curve(w[kept]).T)
    j0 = int(kept[np.argmin(radius)])
    starts, ends = sorted(starts), sorted(ends)
    runs = {s: next((j for j in ends if j >= s), ends[0]) for s in starts}  # start -> end
    first = max((s for s in starts if s <= j0), default=starts[-1])
    cuts, s = [], first
    for _ in range(len(starts)):
        e = runs[s]
        since = cuts[-1][1] if cuts else w[(s - 1) % (len(w) - 1)]  # where the run began
        found = []
        for b in [j for j in starts if j > e] + [j for j in starts if j <= e]:
            for wa, wb in _candidates(curve, w, e, b, circles, meet):
                pa, pb = curve(np.array([wa, wb]))
                if np.hypot(*(pa - pb)) > meet or not _by_run(w, keep, s, e, wa):
                    continue
                entered = [r for r in starts if _by_run(w, keep, r, runs[r], wb)]
                if entered:  # by two runs a sample apart: the one whose start is nearer
                    nearest = min(entered, key=lambda r: abs((w[r] - wb + 0.5) % 1.0 - 0.5))
                    found.append(((wa - since) % 1.0, wa, wb, nearest))
                    break
            if found and found[-1][0] <= (w[e + 1] - since) % 1.0:
                break
        if not found:
            raise GeometryError(f"the roller's envelope leaves the cam at w = {w[e]:.6g} where it meets no other "
                                "kept arc")
        _, wa, wb, s = min(found)
        cuts.append((wa, wb))  # the run the crossing enters: a run of a kept sample inside a loop is passed by
        if s == first:
            return cuts
    raise GeometryError("the arcs of the roller's envelope that no roller covers do not close around the cam axis")


def _candidates(curve, w, e, b, circles, meet):
    """The crossings from the last kept sample ``e`` to the first kept sample ``b``: where the envelope beside
    a corner's arc comes out of its circle, if it does, then the envelope's own crossing."""
    hit = corner_cut(curve, w, e, b, circles, meet)
    if hit is not None:
        yield hit
    yield refine_cut(curve, w, e, b, meet=meet)


def _by_run(w, keep, s, e, x, reach: int = 64) -> bool:
    """``x`` lies by the kept run from sample ``s`` to ``e`` (cyclic): between the covered samples either side
    of it, or up to ``reach`` samples beyond one of them with no kept sample between. The crossing of a
    stretch covered by less than the slack's few times over (a roller's arc about a slight concave corner)
    is solved to within ``meet`` of the envelope meeting itself, which may lie a few samples into it."""
    n, step = len(w) - 1, w[1] - w[0]
    lo, hi = (s - 1) % n, (e + 1) % n
    span = (w[hi] - w[lo]) % 1.0 or 1.0  # a run of all samples but one: the whole turn
    if (x - w[lo]) % 1.0 <= span:
        return True
    after, ahead = (x - w[hi]) % 1.0 / step, (w[lo] - x) % 1.0 / step  # samples beyond the run's either side
    if after <= reach:
        return not keep[(hi + np.arange(1, int(after) + 1)) % n].any()
    return ahead <= reach and not keep[(lo - np.arange(1, int(ahead) + 1)) % n].any()


def corner_lines(curve, motion, tool):
    """``(n, h, e0, e1)`` of each corner section of the envelope ``curve`` (a velocity jump): the face
    line at its cam angle and the section's ``w`` range."""
    out = []
    for k, sec in enumerate(curve.sections):
        if sec[0] == "corner":
            n, h = face_lines(motion, tool, sec[1])
            out.append((n[0], float(h[0]), float(curve.edges[k]), float(curve.edges[k + 1])))
    return out


def face_boundary(curve, depth, slack: float, corners, scale: float, samples: int = 16385):
    """The flat face's cam from its envelope ``curve`` (of ``w`` in [0, 1], one turn): the kept arcs in
    the order the cam's boundary runs (clockwise, as the envelope of a face turning with the cam), each
    joined to the next, and the stretches of ``w`` cut away.

    A sample is kept where ``depth`` (:meth:`~gearkit.families.cam.halfplanes.HalfPlanes.depth`) is at
    most ``slack`` (mm: round-off; the polygon of sampled lines, dense about the velocity jumps, holds the
    whole cam, so a swallowtail's sliver is cut however shallow). The runs of kept samples are ordered by
    their polar angles; each run's end meets the next run's start at the envelope's crossing (sought again
    from a dense resampling when Newton's ends stay apart: a cusp at an acceleration jump), or along a
    corner's face line (:func:`~gearkit.families.cam.faceline.bridge`; ``corners`` of
    :func:`corner_lines`). Returns ``(arcs, cuts)``: ``arcs`` ``[(spans,
    edge)]``, the stretches ``(w0, w1)`` of one kept arc in the order they are walked (``w1 < w0`` where it
    runs against ``w``; split at ``w = 1``) and the :class:`~gearkit.families.cam.faceline.FaceEdge` to the
    next arc or None; ``cuts`` ``[(wa, wb)]``, from a kept arc's end to the next one's start along ``w``
    (cyclic: ``wb`` may be below ``wa``). One arc
    ``[((0, 1),), None]`` and no cut when the whole envelope bounds the cam.

    A kept arc narrower than a sample step has no kept sample: its neighbours' crossing, joined past it,
    lies off the cam (outside the lines of that arc's cam angles, beyond ``slack``). A section narrower than
    a sample step has no sample either: a fold in it goes uncut (the slides along the face line at the
    velocity jumps at cam angle 0 of a constant-velocity rocker with a lift of 3e-4 mm, a sixth of a step
    wide, ran 4e-8 mm outside the cam and back with every sample kept). Every join, and the middle of every
    section on a kept arc, is checked against ``depth``, and the envelope is sampled again four times as
    densely until each lies on the cam (a dwell's arc a quarter of a sample step wide, between a rise and a
    return whose arcs cross 9 um outside it, was cut away whole). A velocity jump's slide back along the face
    on a kept arc, too shallow a fold for ``depth``, is cut at the crossing of the arcs either side of it
    (:func:`~gearkit.families.cam.faceline.slides_back`).

    Raises
    ------
    GeometryError
        When no sample is kept, or a run's end meets the next run's start neither at a crossing nor
        along a corner's face line, or a join still lies off the cam, or the arcs either side of a slide
        back do not meet, at ``FINEST`` samples.
    """
    edges = np.asarray(getattr(curve, "edges", (0.0, 1.0)), dtype=float)  # a curve of one section: no narrow one
    middles = 0.5 * (edges[:-1] + edges[1:]) % 1.0  # a section narrower than a sample step has none
    while True:
        found = _sampled_boundary(curve, depth, slack, corners, scale, samples)
        # the joins on the cam, then the slides back cut out (the middle of one lies off the cam by its fold's depth)
        why = "a kept arc of the flat face's envelope narrower than 1/{} of a turn was not resolved: its neighbours' " \
            "crossing lies off the cam"
        if found is not None and (not found[1] or depth(curve(np.reshape(found[1], -1))).max() <= slack):
            folded = slides_back(curve, *found, corners, scale)
            if folded is None:
                why = "the arcs of the flat face's envelope either side of a slide back along the face at a velocity " \
                    "jump do not meet at 1/{} of a turn"
            else:
                arcs, cuts = folded
                probe = np.concatenate([np.reshape(cuts, -1), middles[_on_arcs(arcs, middles)]])
                if not len(probe) or depth(curve(probe)).max() <= slack:
                    return arcs, cuts
        if samples > FINEST:
            raise GeometryError(why.format(FINEST - 1))
        samples = 4 * (samples - 1) + 1


def _on_arcs(arcs, w):
    """Which of ``w`` lie on the kept arcs ``arcs`` (:func:`face_boundary`'s), strictly inside a stretch."""
    spans = np.array([sp for spans, _ in arcs for sp in spans], dtype=float).reshape(-1, 2)
    lo, hi = spans.min(axis=1), spans.max(axis=1)
    return ((w[:, None] > lo) & (w[:, None] < hi)).any(axis=1)


def _sampled_boundary(curve, depth, slack: float, corners, scale: float, samples: int):
    """:func:`face_boundary` from ``samples`` samples of ``w``, whatever its joins; None when a join's kept
    samples lie within two steps of each other below ``FINEST`` samples (:func:`_join_runs`)."""
    w = np.linspace(0.0, 1.0, samples)
    m, step = samples - 1, w[1] - w[0]
    keep = depth(curve(w[:-1])) <= slack
    if keep.all():
        return [(((0.0, 1.0),), None)], []
    if not keep.any():
        raise GeometryError("the flat face leaves no envelope point on the cam (no line touches it)")
    first = np.flatnonzero(keep & ~np.roll(keep, 1))
    last = np.flatnonzero(keep & ~np.roll(keep, -1))
    last = np.where(last < first[0], last + m, last) if last[0] < first[0] else last
    runs = sorted(zip(first.tolist(), np.sort(last).tolist()))  # (first, last), last >= first (unwrapped)
    for _ in range(len(runs)):
        joined = _join_runs(curve, w, runs, corners, scale, step, resolved=samples >= FINEST)
        if joined is None:
            return None
        arcs, dropped = joined
        if not dropped:
            break
        runs = [r for k, r in enumerate(runs) if k not in dropped]
        if not runs:
            raise GeometryError("no kept arc of the flat face's envelope is left between its crossings")
    ranges = sorted(((min(e, f, key=sum), max(e, f, key=sum)) for e, f, _ in arcs), key=lambda r: r[0][0])
    cuts = sorted((hi[0], lo[0]) for (_, hi), (lo, _) in zip(ranges, ranges[1:] + ranges[:1]))  # along w
    return [(_spans(entry, leave), edge) for entry, leave, edge in arcs], cuts


def _join_runs(curve, w, runs, corners, scale, step, resolved: bool = True):
    """The runs' arcs joined around the cam: ``[(entry, leave, edge)]`` in boundary order (``entry`` and
    ``leave`` the arc's ends as walked, each ``(w, turns)``; ``edge`` the straight stretch to the next
    arc or None) and the indices of runs left with no arc (both joins past each other: a run of a sample
    or two).

    None, unless ``resolved``, when the kept samples a join leaves and arrives at lie within two steps of
    each other: the cut is one sample wide, its crossing lies on the chords either side of that sample,
    which the crossing's search passes over as touching (a constant-velocity rocker lifting 2e-3 mm with
    no dwell: the end of its rise, the slide back at the jump to the return and the return's start within
    one step about w = 0, a crossing not found apart from the curve itself)."""
    m = len(w) - 1

    def polar(j):
        q = curve(np.mod(np.asarray(j, dtype=float), m) / m)
        return np.unwrap(np.arctan2(q[:, 1], q[:, 0]))
    info = []
    for a, b in runs:
        ang = polar(np.arange(a, b + 1)) if b > a else polar([a - 0.25, a + 0.25])
        info.append((1 if ang[-1] < ang[0] else -1, float(np.mod(ang[len(ang) // 2], 2 * math.pi))))
    order = sorted(range(len(runs)), key=lambda k: -info[k][1])  # clockwise from the largest polar angle
    # start the walk at the run holding w = 0 (the start angle, where the envelope is outermost)
    home = next((k for k in order if runs[k][0] == 0 or runs[k][1] >= m), order[0])
    order = order[order.index(home):] + order[:order.index(home)]
    joins = []
    for i, k in enumerate(order):
        nxt = order[(i + 1) % len(order)]
        (a, b), d = runs[k], info[k][0]
        (c, e), dn = runs[nxt], info[nxt][0]
        leave, arrive = (b if d > 0 else a), (c if dn > 0 else e)
        if not resolved and min((arrive - leave) % m, (leave - arrive) % m) <= 2:
            return None
        wa, wb = refine_cut(curve, w, leave % m, arrive % m, d, dn, meet=1e-9 * scale)
        joins.append(bridge(curve, (wa, wb), (leave % m / m, arrive % m / m), corners, scale, step))
    arcs, dropped = [], set()
    for i, k in enumerate(order):
        (a, b), d = runs[k], info[k][0]
        entry = _near(joins[i - 1][1], (a if d > 0 else b) / m)
        leave = _near(joins[i][0], (b if d > 0 else a) / m)
        if (sum(leave) - sum(entry)) * d <= 0.0:
            dropped.add(k)
        arcs.append((entry, leave, joins[i][2]))
    return arcs, dropped


def _near(x: float, ref: float):
    """``x`` (in [0, 1]) and the whole turns of ``w`` that put it nearest ``ref``: ``(x, turns)``."""
    return float(x), int(np.round(ref - x))


def _spans(entry, leave):
    """The walk from ``entry`` to ``leave`` (each ``(w, turns)``) as stretches inside [0, 1], in order."""
    (x, j), (y, k) = entry, leave
    if j == k:
        out = [(x, y)]
    elif k > j:
        out = [(x, 1.0)] + [(0.0, 1.0)] * (k - j - 1) + [(0.0, y)]
    else:
        out = [(x, 0.0)] + [(1.0, 0.0)] * (j - k - 1) + [(1.0, y)]
    return tuple(sp for sp in out if sp[0] != sp[1])
