"""The tooth surface sampled to a tolerance: a transverse polyline swept in axial layers.

A gear's flank surface is its exact transverse profile swept along the axis, turned by
``theta(z) = z tan(beta) / r`` (``r``: reference radius; right hand turns counter-clockwise
as z grows). It is meshed as a stack of layers: at every layer height the tooth polyline
(vertices on the exact profile) is turned to that height, so every vertex lies on the exact
surface. Between two heights each polyline edge spans a quad, split into two triangles.

**Deviation.** A facet point at height z, turned back by ``-theta(z)``, is compared with the
exact transverse profile: that distance, in the transverse plane, bounds the 3D distance to
the exact surface from above. Three effects add up in a layer: the polyline chord (2D sag),
the chord of each helix edge (``r dtheta^2 / 8``) and the twist of each quad (about
``dtheta h / 4`` at its diagonal, ``h`` the edge length, with the sign set by the diagonal).
All layers of one hand are congruent, and so are all teeth, so one layer of one tooth is
measured (a barycentric grid on every facet, against a dense exact polyline of each edge);
each column takes the diagonal with the smaller deviation, and the layer count and the
polyline tolerance are chosen together to meet ``tol`` with the fewest facets.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.accuracy import sample_pieces
from gearkit.errors import GeometryError, SpecError
from gearkit.refine import evaluate_curves
from gearkit.values import frozen

#: exact sub-points per polyline edge (the reference the deviation is measured against)
FINE = 16
#: measured deviations must stay below ``MARGIN * tol`` (the grid and the dense reference
#: polyline each misjudge the continuous maximum by well under 1 %)
MARGIN = 0.98
#: polyline tolerances tried, as fractions of tol (largest first: fewest points)
FRACTIONS = (0.95, 0.8, 0.65, 0.5, 0.35, 0.25)


@frozen
class ToothPolyline:
    """One tooth's boundary sampled on the exact profile.

    points : (n + 1, 2) float64, mm
        Gear: counter-clockwise from the right space centre to the left one (tooth 0 on +y;
        the last point is the next tooth's first). Rack: left to right, tooth centred on x = 0.
    fine : (n, FINE + 1, 2) float64, mm
        Exact points along each edge (both ends included).
    tol : float, mm, the polyline's chord tolerance
    """

    points: np.ndarray
    fine: np.ndarray
    tol: float

    @property
    def edges(self) -> int:
        return len(self.points) - 1


def _half(half, tol: float):
    """Half tooth (tip -> space centre) with the exact sub-points of every edge."""
    pts, fine = [], []
    sub = np.linspace(0.0, 1.0, FINE + 1)
    sampled = sample_pieces(half.pieces, tol)  # all pieces in one refinement: each as it samples alone
    ws = [(w[:-1, None] + (w[1:] - w[:-1])[:, None] * sub[None, :]).ravel() for w, _, _ in sampled]
    for k, ((w, p, _), exact) in enumerate(zip(sampled, evaluate_curves(half.pieces, ws))):
        fine.append(exact.reshape(len(w) - 1, FINE + 1, 2))
        pts.append(p if k == 0 else p[1:])
    return np.concatenate(pts), np.concatenate(fine)


def _drop_short(points, fine, min_gap):
    """Merge edges shorter than ``min_gap`` into their neighbour (the ends stay)."""
    length = np.linalg.norm(np.diff(points, axis=0), axis=1)
    if length.min(initial=np.inf) >= min_gap or len(points) < 4:
        return points, fine
    keep_p, keep_f = [points[0]], [fine[0]]
    for i in range(1, len(points) - 1):
        if np.linalg.norm(points[i] - keep_p[-1]) < min_gap or np.linalg.norm(points[-1] - points[i]) < min_gap:
            merged = np.concatenate([keep_f[-1], fine[i][1:]])
            keep_f[-1] = merged[np.linspace(0, len(merged) - 1, FINE + 1).round().astype(int)]
            continue
        keep_p.append(points[i])
        keep_f.append(fine[i])
    keep_p.append(points[-1])
    return np.array(keep_p), np.array(keep_f)


def tooth_polyline(profile, tol: float, rack: bool = False) -> ToothPolyline:
    """Sample one whole tooth of ``profile`` (its ``half.pieces``) with chords within ``tol``.

    Edges shorter than ``tol / 100`` (slivers where two exact pieces meet) are merged, so no
    facet degenerates when written in single precision.
    """
    half, fine = _half(profile.half, tol)
    mirror = np.array([-1.0, 1.0])
    if rack:  # left space centre -> tip -> right space centre
        pts = np.concatenate([half[::-1] * mirror, half[1:]])
        fin = np.concatenate([fine[::-1, ::-1] * mirror, fine])
    else:  # right space centre -> tip -> left space centre
        pts = np.concatenate([half[::-1], half[1:] * mirror])
        fin = np.concatenate([fine[::-1, ::-1], fine * mirror])
    pts, fin = _drop_short(pts, fin, 1e-2 * tol)
    if not np.isfinite(pts).all():
        raise GeometryError("the tooth profile has non-finite points")
    return ToothPolyline(pts, fin, float(tol))


def _grid(level: int) -> np.ndarray:
    rows = [(i, j, level - i - j) for i in range(level + 1) for j in range(level + 1 - i)]
    return np.array(rows, dtype=float) / level


_GRID = _grid(6)
_CHORD = np.linspace(0.0, 1.0, 13)[1:-1]
# the two triangles of each diagonal choice: (which end of the edge, bottom 0 / top 1) per vertex
_TRIANGLES = (
    (((0, 0), (1, 0), (1, 1)), ((0, 0), (1, 1), (0, 1))),  # diagonal 0: bottom-left to top-right
    (((0, 0), (1, 0), (0, 1)), ((1, 0), (1, 1), (0, 1))),  # diagonal 1: bottom-right to top-left
)


def _distance_to_fine(qx, qy, fine):
    """Distance of points ``(qx, qy)`` (each (n, g)) to the dense exact polyline of their edge (n, FINE+1, 2).

    Only the segments around each point's position along the edge are searched (the nearest and
    one on either side): a distance to fewer segments can only be larger, never hide a deviation.
    The x and y coordinates are arrays of their own (a dot product of two is ``x x' + y y'``).
    """
    fx, fy = (np.ascontiguousarray(fine[..., i]) for i in range(2))
    cx, cy = fx[:, -1:] - fx[:, :1], fy[:, -1:] - fy[:, :1]  # each edge's chord
    norm = np.maximum(cx * cx + cy * cy, 1e-300)
    t_fine = ((fx - fx[:, :1]) * cx + (fy - fy[:, :1]) * cy) / norm
    t_q = ((qx - fx[:, :1]) * cx + (qy - fy[:, :1]) * cy) / norm
    # the segment holding each point's position (the inner sub-points it has passed, counted a row of
    # them at a time: a sum along a short last axis costs a step per point)
    j = (np.ascontiguousarray(t_fine.T[1:-1, :, None]) <= t_q).sum(axis=0)
    fx, fy, first = fx.ravel(), fy.ravel(), np.arange(len(fine))[:, None] * fine.shape[1]
    best = np.full(qx.shape, np.inf)
    for off in (-1, 0, 1):
        k = np.clip(j + off, 0, FINE - 1) + first
        x0, y0 = fx.take(k), fy.take(k)
        dx, dy = fx.take(k + 1) - x0, fy.take(k + 1) - y0
        dd = np.maximum(dx * dx + dy * dy, 1e-300)
        wx, wy = qx - x0, qy - y0
        t = np.clip((wx * dx + wy * dy) / dd, 0.0, 1.0)
        gx, gy = wx - t * dx, wy - t * dy
        best = np.minimum(best, gx * gx + gy * gy)
    return np.sqrt(best)


def layer_deviation(poly: ToothPolyline, dtheta: float) -> np.ndarray:
    """Deviation (mm) of each column of one layer, for both diagonal choices.

    Parameters
    ----------
    poly : ToothPolyline
    dtheta : float, rad, the turn of the profile from the layer's bottom to its top

    Returns
    -------
    (n, 2) float64, mm: the largest transverse distance of the column's two facets from the
    exact profile, with diagonal 0 (bottom-left to top-right) and diagonal 1.
    """
    x, y = (poly.points[:, i, None] for i in range(2))  # (n + 1, 1) each
    if dtheta == 0.0:  # a straight prism: the facets' transverse sections are the chords
        q = [c[:-1] + _CHORD[None, :] * (c[1:] - c[:-1]) for c in (x, y)]
        dev = _distance_to_fine(*q, poly.fine).max(axis=1)
        return np.stack([dev, dev], 1)
    ends = ((x[:-1], y[:-1]), (x[1:], y[1:]))
    out = np.empty((poly.edges, 2))
    for choice, triangles in enumerate(_TRIANGLES):
        worst = np.zeros(poly.edges)
        for tri in triangles:
            t_v = np.array([top for _, top in tri], dtype=float)
            t_g = _GRID @ t_v  # height fraction of every grid point
            qx, qy = np.zeros((poly.edges, len(_GRID))), np.zeros((poly.edges, len(_GRID)))
            for i, (end, top) in enumerate(tri):  # each corner turned to the grid point's height, weighted
                angle = ((top - t_g) * dtheta)[None, :]
                c, s = np.cos(angle), np.sin(angle)
                (ex, ey), w = ends[end], _GRID[None, :, i]
                qx += w * (c * ex - s * ey)
                qy += w * (s * ex + c * ey)
            worst = np.maximum(worst, _distance_to_fine(qx, qy, poly.fine).max(axis=1))
        out[:, choice] = worst
    return out


@frozen
class LayerPlan:
    """How a tooth surface is meshed: the polyline, the layers of one helical run and the diagonals.

    ``diagonals[+1]`` / ``diagonals[-1]``: (n,) int8 choice per column (0: bottom-left to
    top-right, 1: bottom-right to top-left) for layers turning counter-clockwise / clockwise
    going up; ``achieved``: the largest measured deviation, mm.
    """

    polyline: ToothPolyline
    layers: int
    diagonals: dict
    achieved: float


def plan_layers(sample, tol: float, twist: float, both_hands: bool = False) -> LayerPlan:
    """Choose the polyline tolerance and the layer count of one helical run.

    Parameters
    ----------
    sample : callable, tol -> ToothPolyline
    tol : float, mm
    twist : float, rad, the profile's total turn over the run (0 for a spur gear)
    both_hands : bool, also plan layers turning the other way (a herringbone's second half)
    """
    limit = MARGIN * tol
    best = None
    for frac in FRACTIONS:
        poly = sample(frac * tol)
        r_max = float(np.hypot(poly.points[:, 0], poly.points[:, 1]).max())
        if twist == 0.0:
            n_lo = 1
        else:  # the helix chord at the largest radius alone needs this many layers
            n_lo = max(1, math.ceil(abs(twist) / math.sqrt(8.0 * limit / max(r_max, 1e-300))))
        n = n_lo
        while n <= 4 * n_lo + 8:
            hand = 1 if twist >= 0.0 else -1
            devs = {hand: layer_deviation(poly, twist / n)}
            if both_hands and twist:
                devs[-hand] = layer_deviation(poly, -twist / n)
            worst = max(float(d.min(axis=1).max()) for d in devs.values())
            if worst <= limit:
                break
            if twist == 0.0:
                n = None
                break
            n = max(n + 1, math.ceil(1.2 * n))
        else:
            n = None
        if n is None:
            continue
        cost = poly.edges * (n + 1)
        if best is None or cost < best[0]:
            diag = {s: np.argmin(d, axis=1).astype(np.int8) for s, d in devs.items()}
            diag.setdefault(-hand, diag[hand])
            best = (cost, LayerPlan(poly, n, diag, worst))
        if n == n_lo:
            break
    if best is None:
        raise GeometryError(f"cannot mesh the tooth surface within tol = {tol:g} mm")
    return best[1]


def helix_angle(profile, spec) -> float:
    """The helix angle (degrees) of a gear solid of ``profile`` by ``spec`` (a
    :class:`~gearkit.solids.solid.SolidSpec`): the spec's, else the profile's own; SpecError when they differ."""
    own = getattr(getattr(profile, "spec", None), "helix_angle_deg", None)
    if spec.helix_angle_deg is None:
        return float(own or 0.0)
    if own is not None and not math.isclose(spec.helix_angle_deg, own, abs_tol=1e-12):
        raise SpecError("helix_angle_deg", f"{spec.helix_angle_deg} degrees, but the profile was generated for "
                        f"{own} degrees (its transverse section depends on it)")
    return float(spec.helix_angle_deg)


def reference_radius(profile, beta: float) -> float:
    """Reference radius (mm) of ``profile`` at helix angle ``beta`` (rad): its own, else z m / (2 cos beta)."""
    d = getattr(profile, "reference_diameter", None)
    if d is None:
        d = profile.teeth * profile.module / math.cos(beta)
    return d / 2.0
