"""What the follower leaves of the blank: the envelope's points that bound the cam, and its corners.

**Roller.** The roller sweeps every point within ``R_p`` of the pitch curve: an envelope point is
on the cam when no other roller position covers it, i.e. when its distance to the whole pitch
curve is ``R_p``. Where the roller is larger than the pitch curve's convex radius of curvature, or
at a concave corner of the pitch curve (a velocity jump), the envelope loops inside the swept
region and is cut there.

**Flat face.**
Relative to the cam, the face is a line at every cam angle ``phi`` and the cam lies on the side of
the cam axis: the cam is the intersection of the half-planes ``n(phi) . x <= h(phi)`` (``n`` the unit
normal into the follower, ``h > 0`` the line's distance from the axis) — a convex region whatever
the motion asks for. Where the motion asks for a convex cam (``r0 + s + s'' > 0`` for a translating
face, textbook 3.45) every line touches it at the envelope point and the envelope is the cam.
Where it does not, the envelope loops (a swallowtail) or, for a rocker whose face turns back
relative to the cam (``|psi'| > 1``), runs off along the face; the cam keeps only the envelope's
points on the boundary of the intersection, and its corners are where the kept arcs cross.

Which lines touch the cam is read off the dual curve ``d = n / h``: the intersection of the
half-planes is the polar of the convex hull of the ``d``, so a line bounds the cam exactly when
its dual point is a hull vertex (a line that turns back has its dual point moving towards the
origin, inside the hull). The envelope's samples are then kept where they lie on the boundary of
the polygon those lines bound, and each change from kept to cut is refined to the exact crossing
of the envelope with itself.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.errors import GeometryError

__all__ = ["face_lines", "face_depth", "roller_depth", "kept_runs", "FaceEdge", "corner_lines", "bridge_cuts"]


def face_lines(motion, tool, phi):
    """The face at cam angles ``phi`` in the cam frame: unit normals ``n`` (away from the cam axis)
    and distances ``h > 0`` of the lines ``n . x = h``."""
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    ends = tool.evaluate(np.array([0.0, 1.0]))[0]
    a = motion.to_blank(np.broadcast_to(ends[0], phi.shape + (2,)), phi)
    b = motion.to_blank(np.broadcast_to(ends[1], phi.shape + (2,)), phi)
    d = b - a
    n = np.stack([d[:, 1], -d[:, 0]], -1) / np.hypot(d[:, 0], d[:, 1])[:, None]
    h = np.einsum("ij,ij->i", n, a)
    flip = np.where(h < 0, -1.0, 1.0)
    return n * flip[:, None], h * flip


def _bounding_polygon(n, h):
    """The lines that bound the intersection of the half-planes (hull vertices of the dual points),
    in counter-clockwise order, and the polygon's vertex angles: ``(n_active, h_active, angles)``;
    the edge ending at vertex ``k`` lies on active line ``k``."""
    from scipy.spatial import ConvexHull

    dual = n / h[:, None]
    idx = ConvexHull(dual).vertices  # counter-clockwise in 2-D
    na, ha = n[idx], h[idx]
    nb, hb = np.roll(na, -1, axis=0), np.roll(ha, -1)
    det = na[:, 0] * nb[:, 1] - na[:, 1] * nb[:, 0]
    vx = (ha * nb[:, 1] - hb * na[:, 1]) / det  # vertex of lines k and k + 1
    vy = (na[:, 0] * hb - nb[:, 0] * ha) / det
    return na, ha, np.arctan2(vy, vx)


def _outside(points, na, ha, ang):
    """Signed distance of each point outside the polygon (negative inside): against the active line
    whose edge the ray from the axis through the point crosses."""
    alpha = np.arctan2(points[:, 1], points[:, 0])
    order = np.argsort(ang)
    k = np.searchsorted(ang[order], alpha) % len(ang)  # the edge ends at the next vertex by angle
    line = order[k]
    return np.einsum("ij,ij->i", points, na[line]) - ha[line]


def face_depth(motion, tool, start: float, samples: int = 65536):
    """How deep (mm) points lie inside the region the flat face sweeps (negative: on the cam's side
    of every line), from ``samples`` face positions over one turn from cam angle ``start``."""
    phi = start + np.linspace(0.0, 2.0 * math.pi, samples, endpoint=False)
    na, ha, ang = _bounding_polygon(*face_lines(motion, tool, phi))
    return lambda points: _outside(points, na, ha, ang)


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


def kept_runs(curve, depth, slack: float, samples: int = 16385, meet: float | None = None):
    """Where the envelope ``curve`` (of ``w`` in [0, 1], one turn) bounds the cam: ``[(wa, wb), ...]``,
    the cuts from a kept arc's end ``wa`` to the next kept arc's start ``wb`` (cyclic, ``wb`` may be
    below ``wa``: the cut runs through ``w = 1``), each refined to the envelope's self-crossing.
    A sample is kept where ``depth`` (:func:`face_depth`, :func:`roller_depth`) is at most ``slack``
    (mm: the swept region's own sampling error). Empty when the whole envelope bounds the cam.

    With ``meet`` (mm; a roller) every cut must be a crossing, its ends within ``meet``: the cuts are
    then the cycle of :func:`_cam_cycle`, in the order the cam's boundary runs."""
    w = np.linspace(0.0, 1.0, samples)
    keep = depth(curve(w)) <= slack
    keep[-1] = keep[0]  # w = 1 is w = 0
    if keep.all():
        return []
    if not keep.any():
        raise GeometryError("the flat face leaves no envelope point on the cam (no line touches it)")
    k = np.flatnonzero(keep[:-1])
    starts = [int(j) for j in k if not keep[j - 1 if j else samples - 2]]  # runs beginning at j
    ends = [int(j) for j in k if not keep[j + 1]]  # runs ending at j
    if meet is not None:
        return _cam_cycle(curve, w, keep, starts, ends, meet)
    cuts = []
    for e in ends:
        b = min((s for s in starts if s > e), default=starts[0])  # the next run, cyclically
        cuts.append(_refine_cut(curve, w, e, b))
    return cuts


def _cam_cycle(curve, w, keep, starts, ends, meet: float):
    """The cuts of the kept runs that bound the cam, followed from run to run around it.

    A sample no roller covers lies on the boundary of the swept region, but not every such boundary
    bounds the cam: a roller far larger than the rise is steep (a lift of several prime radii over a
    short rise) sweeps a finger whose outer side the envelope also traces, uncovered and outside the
    cam. Each run's end meets exactly one run's start (the swept region's boundary has two arcs at a
    corner), so the runs fall into cycles, and the cam's is the one through the kept sample nearest
    the axis (the first point of the swept region any ray from the axis meets there lies on the cam).

    Raises
    ------
    GeometryError
        When a run's end meets no run's start, or the runs do not close into a cycle.
    """
    kept = np.flatnonzero(keep[:-1])
    radius = np.hypot(*curve(w[kept]).T)
    j0 = int(kept[np.argmin(radius)])
    starts, ends = sorted(starts), sorted(ends)
    first = max((s for s in starts if s <= j0), default=starts[-1])
    cuts, s = [], first
    for _ in range(len(starts)):
        e = next((j for j in ends if j >= s), ends[0])
        for b in [j for j in starts if j > e] + [j for j in starts if j <= e]:
            wa, wb = _refine_cut(curve, w, e, b)
            pa, pb = curve(np.array([wa, wb]))
            if np.hypot(*(pa - pb)) <= meet:
                break
        else:
            raise GeometryError(f"the roller's envelope leaves the cam at w = {w[e]:.6g} where it meets no other kept arc")
        cuts.append((wa, wb))
        s = b
        if s == first:
            return cuts
    raise GeometryError("the arcs of the roller's envelope that no roller covers do not close around the cam axis")


def _refine_cut(curve, w, e, b):
    """The crossing ``curve(wa) = curve(wb)`` with ``wa`` just after sample ``e`` and ``wb`` just
    before sample ``b``: the chords' crossing, then Newton."""
    n = len(w)
    ja = np.arange(e - 2, e + 3) % (n - 1)
    jb = np.arange(b - 3, b + 2) % (n - 1)
    pa, pb = curve(w[ja]), curve(w[jb])
    best = None
    for i in range(len(ja) - 1):
        for j in range(len(jb) - 1):
            t = _chord_cross(pa[i], pa[i + 1], pb[j], pb[j + 1])
            if t is not None:
                best = (w[ja[i]] + t[0] * (w[1] - w[0]), w[jb[j]] + t[1] * (w[1] - w[0]))
    if best is None:  # no chord crossing seen: start from the last kept and first kept samples
        best = (w[e], w[b])
    return _newton(curve, *best, h=0.5 * (w[1] - w[0]))


def _chord_cross(p0, p1, q0, q1):
    d1, d2, r = p1 - p0, q1 - q0, q0 - p0
    den = d1[0] * d2[1] - d1[1] * d2[0]
    if den == 0.0:
        return None
    t = (r[0] * d2[1] - r[1] * d2[0]) / den
    u = (r[0] * d1[1] - r[1] * d1[0]) / den
    return (t, u) if 0.0 <= t <= 1.0 and 0.0 <= u <= 1.0 else None


def _newton(curve, wa, wb, h):
    """Newton on ``curve(wa) = curve(wb)`` within ``h`` of the start (central differences)."""
    x = np.array([wa, wb])
    lo, hi = x - 4 * h, x + 4 * h
    step_h = 1e-9
    for _ in range(50):
        p = curve(np.mod(np.array([x[0] - step_h, x[0] + step_h, x[1] - step_h, x[1] + step_h, x[0], x[1]]), 1.0))
        jac = np.column_stack([(p[1] - p[0]) / (2 * step_h), -(p[3] - p[2]) / (2 * step_h)])
        try:
            step = np.linalg.solve(jac, p[4] - p[5])
        except np.linalg.LinAlgError:
            break
        new = np.clip(x - step, lo, hi)
        done = np.abs(new - x).max() < 1e-15
        x = new
        if done:
            break
    return float(np.mod(x[0], 1.0)), float(np.mod(x[1], 1.0))


class FaceEdge:
    """A straight stretch of the cam along one face line, from ``p0`` to ``p1``: an exact curve of
    ``w`` in [0, 1]."""

    def __init__(self, p0, p1):
        self.p0 = np.asarray(p0, dtype=float)
        self.p1 = np.asarray(p1, dtype=float)

    def __call__(self, w):
        w = np.atleast_1d(np.asarray(w, dtype=float))
        return self.p0[None, :] + w[:, None] * (self.p1 - self.p0)[None, :]

    def turning(self, w):
        """Points, the unit tangent (one direction: a straight edge turns by nothing) and one constant part."""
        pts, d = self(w), self.p1 - self.p0
        length = float(np.hypot(*d))
        tangent = d / length if length > 0 else np.array([1.0, 0.0])
        return pts, np.broadcast_to(tangent, pts.shape).copy(), np.zeros((len(pts), 1))


def _on_line(curve, n, h, w, step):
    """The ``w`` within ``8 step`` of ``w`` nearest to it where the curve crosses the line
    ``n . x = h`` (bisection on a bracketing pair of 65 samples), or None."""
    ws = np.mod(w + np.linspace(-8.0, 8.0, 65) * step, 1.0)
    g = curve(ws) @ n - h
    flips = np.flatnonzero(np.sign(g[:-1]) != np.sign(g[1:]))
    if len(flips) == 0:
        return None
    k = int(flips[np.argmin(np.abs(flips - 31.5))])
    lo, hi, glo = w + (k - 32) * step / 4.0, w + (k - 31) * step / 4.0, g[k]
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        gm = float(curve(np.array([mid % 1.0]))[0] @ n - h)
        lo, hi, glo = (mid, hi, gm) if np.sign(gm) == np.sign(glo) else (lo, mid, glo)
    return float((0.5 * (lo + hi)) % 1.0)


def corner_lines(curve, motion, tool):
    """``(n, h, e0, e1)`` of each corner section of the envelope ``curve`` (a velocity jump): the face
    line at its cam angle and the section's ``w`` range."""
    out = []
    for k, sec in enumerate(curve.sections):
        if sec[0] == "corner":
            n, h = face_lines(motion, tool, sec[1])
            out.append((n[0], float(h[0]), float(curve.edges[k]), float(curve.edges[k + 1])))
    return out


def bridge_cuts(curve, cuts, corners, scale: float, step: float = 1.0 / 16384):
    """Every cut through :func:`_bridge`: the cuts ``[(wa, wb), ...]`` and the straight stretches
    ``{wa: FaceEdge}`` that run from a cut's ``wa`` to its ``wb``."""
    out, straight = [], {}
    for cut in cuts:
        wa, wb, edge = _bridge(curve, cut, corners, scale, step)
        out.append((wa, wb))
        if edge is not None:
            straight[wa] = edge
    return out, straight


def _bridge(curve, cut, corners, scale: float, step: float):
    """A cut ``(wa, wb)`` of :func:`kept_runs` whose ends do not meet (no self-crossing of the
    envelope there): the straight stretch of the cam between them along a corner's face line.

    ``corners`` are ``(n, h, e0, e1)``: the face line at each velocity jump and the ``w`` range of
    its corner section. An end within the section's reach snaps to the section's nearer end (the
    face's slide at the jump runs along the same line), any other end to the envelope's crossing
    with the line. Returns ``(wa, wb, edge)``; ``edge`` is None when the cut's ends meet (within
    ``1e-6 scale``); the step is :func:`kept_runs` sampling step.

    Raises
    ------
    GeometryError
        When the ends meet no corner's line (the half-plane model has no other straight stretch).
    """
    wa, wb = cut
    pa, pb = curve(np.array([wa, wb]))
    if np.hypot(*(pa - pb)) <= 1e-6 * scale:
        return wa, wb, None
    off = [abs(pa @ n - h) + abs(pb @ n - h) for n, h, _, _ in corners]
    if not off or min(off) > 1e-2 * scale:
        raise GeometryError("a cut of the flat face's envelope meets neither a crossing nor a corner's face line")
    n, h, e0, e1 = corners[int(np.argmin(off))]
    ends = []
    for w in (wa, wb):
        if e0 - 8 * step <= w <= e1 + 8 * step:
            ends.append(float(e0 if abs(w - e0) <= abs(w - e1) else e1))
            continue
        on = _on_line(curve, n, h, w, step)
        if on is None:
            raise GeometryError("the flat face's envelope does not reach a corner's face line at a cut")
        ends.append(on)
    pa, pb = curve(np.array(ends))
    return ends[0], ends[1], FaceEdge(pa, pb)
