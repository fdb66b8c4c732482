"""Vertex counts against the fewest a chord-at-tol polyline needs: the exact count, found independently.

The fewest is counted on a dense exact evaluation of the curve (:func:`dense_exact`: each piece
evaluated uniformly in its parameter, densely enough that its own steps sag by 1e-4 tol, so no
sampler is involved) by a shortest path over every chord that passes within tol of the points
it skips (:func:`fewest_vertices`). :func:`vertex_target_rows` sets the sampler's counts beside it.

Examples
--------
>>> import math
>>> t = np.linspace(0.0, np.pi / 2, 2001)
>>> fewest_vertices(np.stack([np.cos(t), np.sin(t)], -1), 1e-3) == math.ceil((np.pi / 2) / (2 * math.acos(1 - 1e-3))) + 1
True
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.bench.targets import target_row

__all__ = ["VERTEX_TARGET", "bound_target_row", "dense_exact", "fewest_vertices", "vertex_target_rows"]

VERTEX_TARGET = 1.2  # x the fewest vertices a chord-at-tol polyline needs
#: the dense exact evaluation behind the fewest count: its own steps sag by at most this fraction of
#: tol, so they are ~1/100 of a chord at tol and the count is quantised by about 1 %
DENSE_FRACTION = 1e-4


def _reach(pts, i: int, tol: float, span: int = 64) -> np.ndarray:
    """Indices ``j > i`` whose chord ``pts[i] -> pts[j]`` passes within ``tol`` of every point between.

    The chord's line runs through ``pts[i]`` at angle theta; it passes within ``tol`` of a point at
    distance r and angle phi iff ``|theta - phi| <= asin(tol / r)``, so the chords that qualify
    are those whose own angle lies in the intersection of these wedges over the points they
    skip (running maxima and minima), found for a whole window of ends at once. Where the curve
    has turned more than 90 degrees from the first step (a cusp) the window stops: a chord could
    not reach past there within tol unless the turn is within tol of ``pts[i]``.
    """
    n = len(pts)
    while True:
        end = min(n, i + 1 + span)
        q = pts[i + 1:end] - pts[i]
        r = np.hypot(q[:, 0], q[:, 1])
        far = np.flatnonzero(r > 0.0)
        if not len(far):
            if end == n:
                return np.arange(i + 1, n)
            span *= 4
            continue
        ref = math.atan2(q[far[0], 1], q[far[0], 0])
        phi = np.mod(np.arctan2(q[:, 1], q[:, 0]) - ref + np.pi, 2.0 * np.pi) - np.pi
        behind = np.flatnonzero((np.abs(phi) > 0.5 * np.pi) & (r > tol))
        stop = behind[0] if len(behind) else len(q)
        with np.errstate(divide="ignore"):
            half = np.where(r > tol, np.arcsin(np.minimum(1.0, tol / np.where(r > 0, r, 1.0))), np.inf)
        lo = np.maximum.accumulate(phi - half)
        hi = np.minimum.accumulate(phi + half)
        ok = np.ones(len(q), dtype=bool)
        ok[1:] = (lo[:-1] <= phi[1:]) & (phi[1:] <= hi[:-1])
        closed = np.flatnonzero(lo > hi)  # the wedge is empty past here: no farther chord qualifies
        limit = min(stop, closed[0] + 1 if len(closed) else len(q))
        if limit < len(q) or end == n:
            return i + 1 + np.flatnonzero(ok[:limit])
        span *= 4


def fewest_vertices(points, tol: float) -> int:
    """The fewest vertices of a polyline through a subset of the dense ``points`` (in order, ends
    kept) whose chords pass within ``tol`` of every point they skip: a shortest path over every
    qualifying chord (:func:`_reach`), exact for the given points (a test holds it to an
    exhaustive search). On a dense exact evaluation (:func:`dense_exact`) it is the count a
    chord-at-tol polyline of the curve needs, to about one dense step per chord.

    Examples
    --------
    >>> import math
    >>> t = np.linspace(0.0, np.pi / 2, 2001)
    >>> n = fewest_vertices(np.stack([np.cos(t), np.sin(t)], -1), 1e-3)
    >>> n == math.ceil((np.pi / 2) / (2 * math.acos(1 - 1e-3))) + 1  # chord angle h: sagitta 1 - cos(h/2) = tol
    True
    """
    pts = np.asarray(points, dtype=float)
    n = len(pts)
    hops = np.full(n, n + 1)
    hops[0] = 0
    span = 64
    for i in range(n - 1):  # chords run forward: hops[i] is final when i is reached
        j = _reach(pts, i, tol, span)
        hops[j] = np.minimum(hops[j], hops[i] + 1)
        span = max(64, 2 * int(j[-1] - i))  # the next start reaches about as far: one window
    return int(hops[-1]) + 1


def dense_exact(pieces, tol: float, start: int = 2049, most: int = 1 << 21, fraction: float = DENSE_FRACTION):
    """The exact pieces (``w -> (n, 2)`` on [0, 1], each starting where the previous ends)
    evaluated densely and uniformly in their parameters, independently of any sampler: each
    piece's grid is doubled until the midpoints of its steps lie within ``fraction * tol`` of
    its chords (at most ``most`` points a piece). Returns the joined ``(n, 2)`` points."""
    chunks = []
    for k, piece in enumerate(pieces):
        n = start
        while True:
            w = np.linspace(0.0, 1.0, n)
            p = piece(w)
            mid = piece(0.5 * (w[:-1] + w[1:]))
            d = p[1:] - p[:-1]
            length = np.hypot(d[:, 0], d[:, 1])
            q = mid - p[:-1]
            off = np.abs(q[:, 0] * d[:, 1] - q[:, 1] * d[:, 0]) / np.where(length > 0, length, 1.0)
            off = np.where(length > 0, off, np.hypot(q[:, 0], q[:, 1]))
            if off.max(initial=0.0) <= fraction * tol or n >= most:
                break
            n = 2 * n - 1
        chunks.append(p if k == 0 else p[1:])
    return np.concatenate(chunks)


#: (name, profile maker, module, mesh too) of the vertex-count rows
VERTEX_CASES = (
    ("spur z=40 m=1", lambda: _involute(40, 1.0), True),
    ("undercut z=8 m=1", lambda: _involute(8, 1.0), False),
)


def _involute(z, m, **kw):
    from gearkit.families.involute import GearSpec, tooth_profile

    return tooth_profile(GearSpec(z, m, **kw))


def vertex_target_rows() -> list:
    """Vertex counts at tol against :func:`fewest_vertices` on a dense exact evaluation of the same
    curve (:func:`dense_exact`, independent of the sampler): the half tooth in 2D at three
    tolerances, and the tooth polyline a spur mesh is built from (its vertices per tooth over the
    fewest for one whole tooth, space centre to space centre)."""
    from gearkit.solids import SolidSpec, gear_solid

    rows = []
    for case, make, mesh in VERTEX_CASES:
        prof = make()
        for tol_m in (1e-3, 1e-4, 1e-5):
            tol = tol_m * prof.module
            have = len(prof.half_points(tol)[0])
            least = fewest_vertices(dense_exact(prof.half.pieces, tol), tol)
            rows.append(target_row(f"2D half tooth {case} tol {tol:g} mm, vertices", have / least, VERTEX_TARGET,
                                   "x fewest", f"{have} vertices, fewest chord-at-tol {least}"))
        if mesh:
            tol = 1e-3 * prof.module
            solid = gear_solid(prof, SolidSpec(5.0), tol)
            half = dense_exact(prof.half.pieces, tol)
            tooth = np.concatenate([half[::-1], half[1:] * np.array([-1.0, 1.0])])
            least = fewest_vertices(tooth, tol) - 1  # a tooth's last vertex is the next one's first
            per_tooth = solid.info["points_per_tooth"]
            rows.append(target_row(f"mesh {case} b=5 tol {tol:g} mm, vertices per tooth", per_tooth / least,
                                   VERTEX_TARGET, "x fewest", f"{per_tooth} per tooth, fewest chord-at-tol {least}"))
    return rows


def bound_target_row(ladder) -> dict:
    """The reported deviation is a proven bound: over the 2D profile rows of the ladder (cams aside, whose
    deviation is measured at probes), the largest ratio of the deviation measured independently (dense
    re-evaluation) to the one the sampler reports; at most 1.

    >>> rows = [{"product": "profile", "family": "involute", "achieved": 0.8, "sampler_achieved": 0.9, "case": "a",
    ...          "tol": 1.0}, {"product": "profile", "family": "cam", "achieved": 0.9, "sampler_achieved": 0.8}]
    >>> round(bound_target_row(rows)["measured"], 4), bound_target_row(rows)["pass"]
    (0.8889, True)
    """
    rows = [r for r in ladder if r.get("product") == "profile" and r.get("family") != "cam"
            and r.get("sampler_achieved", 0.0) > 0.0]
    if not rows:
        return target_row("2D profiles: measured / reported deviation, worst row", None, 1.0, "x reported")
    worst = max(rows, key=lambda r: r["achieved"] / r["sampler_achieved"])
    return target_row("2D profiles: measured / reported deviation, worst row",
                      worst["achieved"] / worst["sampler_achieved"], 1.0, "x reported",
                      f"{worst['case']} tol {worst['tol']:g} mm (the reported deviation is a proven bound)")
