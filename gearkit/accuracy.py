"""Accuracy as a length: adaptive sampling of exact curves to a chord tolerance.

Nothing in gearkit hard-codes a point count. A curve is known exactly as a function
``w -> points`` on ``[0, 1]``; :func:`adaptive_sample` splits parameter intervals until
every chord lies within ``tol`` (mm) of the curve and reports the deviation it achieved.
A polyline is measured against points of the exact curve taken independently by
:mod:`gearkit.distances`.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.refine import evaluate_curves, first_samples, first_turnings, refine_sample, refine_samples, turn_curves
from gearkit.errors import GeometryError, check_fields, is_real, require
from gearkit.values import frozen



@frozen
class Accuracy:
    """Requested accuracy: the largest distance (mm) of any output point or chord from the exact curve.

    Examples
    --------
    >>> Accuracy(1e-3).tol
    0.001
    """

    tol: float

    def __post_init__(self):
        check_fields(self)
        require(isinstance(self.tol, (int, float)) and math.isfinite(self.tol) and self.tol > 0, "tol",
                f"{self.tol!r} must be a positive length in mm")


#: the finest tolerance a geometry of size ``m`` (its module) is computed to: the exact pieces join
#: and the envelope solver converges to ~1e-12 of the radii, so chords below this are round-off
PRECISION = 1e-9


def check_tol(tol, module: float, field: str = "tol") -> float:
    """``tol`` as a float if it is a length in ``[PRECISION m, m]`` (mm); else ``SpecError`` naming ``field``.

    Below ``PRECISION * module`` a tolerance asks for more than the geometry's own precision (the
    sampler would only add points on round-off); above ``module`` it is no longer a tooth's shape.

    >>> check_tol(1e-3, 1.0)
    0.001
    >>> check_tol(1e-11, 1.0)
    Traceback (most recent call last):
    ...
    gearkit.errors.SpecError: tol: 1e-11 mm is outside [1e-09, 1] mm (the geometry's own precision 1e-9 m up to one module m)
    """
    lo, hi = PRECISION * module, float(module)
    require(is_real(tol) and lo <= tol <= hi, field, f"{tol!r} mm is outside [{lo:.6g}, {hi:.6g}] mm (the "
            "geometry's own precision 1e-9 m up to one module m)")
    return float(tol)


def default_tol(module: float) -> float:
    """Default 2D tolerance: 1e-3 of the module."""
    return 1e-3 * module




#: the pilot sampling that the vertices are placed from runs at this multiple of tol (its points
#: and probes only have to show where the curve bends)
PILOT = 16.0
#: uniform samples the pilot starts from (more than ``n_init``: the pilot then settles in fewer rounds,
#: each an ``evaluate`` call, the cost that dominates short chains)
PILOT_START = 17
#: chords are placed to deviate by about this fraction of tol: inside the acceptance test's margin,
#: so that few of them fail it and are split
PLACE_AT = 0.9


def adaptive_sample(evaluate, tol: float, n_init: int = 5, max_rounds: int = 60, max_split: int = 16,
                    fewest: bool = False):
    """Sample an exact curve so that every chord is within ``tol`` of it (on request with near the fewest vertices).

    **Placement.** A pilot sampling (:func:`refine_sample` at ``PILOT tol`` from ``PILOT_START``
    uniform samples) and its probes show
    where the curve bends: a chord of length L where the curvature is k deviates by about
    k L^2 / 8, so the fewest vertices for a chord deviation t are spaced sqrt(8 t / k) apart. The
    vertices are placed at equal steps of ``N(s) = integral sqrt(k / (8 t)) ds`` (``t =
    PLACE_AT tol``, the curvature estimated from the turning of the pilot polyline),
    ``ceil(N)`` chords in all: within a few percent of the fewest a chord-at-tol polyline needs.

    **Acceptance.** The placed vertices then go through :func:`refine_sample` at ``tol``, which
    probes every chord and splits the ones that fail: the placement only proposes. A curve that
    gives its tangent's turning (``turning(w)``) is accepted on a proven bound of each chord's
    deviation (``bound=True``), any other on the deviation measured at the probes.

    ``fewest=True`` places the vertices so (what a profile's outline, a mesh or an exported curve
    asks for); the default ``False`` keeps the refinement's own vertices (a uniform ``n_init``
    start refined at ``tol``): denser where the curve bends, and what the start tables of the
    contact and crossing solvers are tuned on.

    Parameters
    ----------
    evaluate : callable, (n,) float64 -> (n, 2) float64
        Exact curve on ``w in [0, 1]``.
    tol : float, mm
    n_init : int
        Starting uniform samples (enough to see the curve's shape; refinement does the rest).
    max_split : int
        Most parts one interval is split into in one round (bisection: 2).
    fewest : bool
        Place the vertices by curvature, or keep the refinement's own (default).

    Returns
    -------
    w : (k,) float64
    points : (k, 2) float64, on the curve
    achieved : float, mm
        With ``fewest=True`` on a curve whose ``turning(w)`` gives angle parts (not None: every tooth piece), a
        *proven upper bound* of every chord's deviation (:mod:`gearkit.chords`: it holds if each
        angle part the curve gives is monotone along it and the curve has no cusp inside; round-off
        of the exact points aside); otherwise the largest deviation measured at the probes.

    Examples
    --------
    A quarter circle of radius 1 at tol 1e-3 needs chords of angle 2 acos(1 - 1e-3) (0.0895 rad):
    18 chords, 19 vertices at the least; the placement lands within one of that:

    >>> arc = lambda w: np.stack([np.cos(np.pi / 2 * w), np.sin(np.pi / 2 * w)], -1)
    >>> w, p, achieved = adaptive_sample(arc, 1e-3, fewest=True)
    >>> least = math.ceil((np.pi / 2) / (2 * math.acos(1 - 1e-3))) + 1
    >>> least, len(p) - least, bool(achieved <= 1e-3)
    (19, 1, True)

    A bump of height 0.1 that the parameter crosses within a few thousandths near w = 0.053: the
    probes of the first interval all land on its chord (a sampler that trusts its probes
    reports 2e-9 and is 0.1 off); the uneven walk through them gives it away:

    >>> def f(w):
    ...     t = np.tanh((w - 0.053) / 0.001)
    ...     return np.stack([t + w, 0.1 * (1 - t * t)], -1)
    >>> from gearkit.distances import polyline_deviation
    >>> w, p, achieved = adaptive_sample(f, 1e-3)
    >>> dense = f(np.linspace(0, 1, 100001))
    >>> bool(polyline_deviation(p, dense) <= 1e-3), bool(achieved <= 1e-3)
    (True, True)
    >>> w, p, achieved = adaptive_sample(f, 1e-3, fewest=True)  # placed, and then probed the same way
    >>> bool(polyline_deviation(p, dense) <= 1e-3), bool(achieved <= 1e-3)
    (True, True)
    """
    if not fewest:
        w = np.linspace(0.0, 1.0, n_init)
        return refine_sample(evaluate, w, evaluate(w), tol, max_rounds, max_split)[:3]
    return sample_curves([evaluate], tol, n_init, max_rounds, max_split)[0]


def sample_curves(curves, tol: float, n_init: int = 5, max_rounds: int = 60, max_split: int = 16):
    """:func:`adaptive_sample` with ``fewest=True`` of several curves at once (a tooth's pieces): ``[(w,
    points, achieved)]``, one per curve, each to the last bit what the curve gets alone.

    The pilot samplings and the acceptance run as one refinement of all the curves
    (:func:`~gearkit.refine.refine_samples`: each round's bookkeeping one pass over every curve);
    the curves are evaluated one by one, each on its own parameters.

    Examples
    --------
    A quarter circle and a straight line, together and alone:

    >>> arc = lambda w: np.stack([np.cos(np.pi / 2 * w), np.sin(np.pi / 2 * w)], -1)
    >>> line = lambda w: np.stack([w, 1.0 + 0.0 * w], -1)
    >>> both = sample_curves([arc, line], 1e-3)
    >>> [len(p) for _, p, _ in both], all(np.array_equal(p, adaptive_sample(c, 1e-3, fewest=True)[1])
    ...                                   for c, (_, p, _) in zip([arc, line], both))
    ([20, 2], True)
    """
    w0 = np.linspace(0.0, 1.0, max(n_init, PILOT_START))
    start = first_samples(curves, [w0] * len(curves))  # the starts and their first probes in one evaluation
    pilot = refine_samples(curves, [w0] * len(curves), [s[0] for s in start], PILOT * tol, max_rounds, max_split,
                           probed=[s[1] for s in start])
    placed = []
    for w, pts, _, probes, q in pilot:
        walk_w, walk_p, ordered = _walk_order(w, pts, probes, q)
        placed.append(place_by_curvature(walk_w, walk_p, PLACE_AT * tol, ordered=ordered))
    turned = first_turnings(curves, placed)
    out = [None] * len(curves)
    for proven in (True, False):  # the curves bounded by their turning, then the ones probed
        which = [i for i, t in enumerate(turned) if (t is not None) == proven]
        if not which:
            continue
        group, ws = [curves[i] for i in which], [placed[i] for i in which]
        done = (refine_samples(group, ws, None, tol, max_rounds, max_split, turned=[turned[i] for i in which])
                if proven else refine_samples(group, ws, evaluate_curves(group, ws), tol, max_rounds, max_split))
        for i, res in zip(which, done):
            out[i] = res[:3]
    return out


#: the grid a piece's turn is taken on, to place its vertices (:func:`sample_pieces`)
TURN_GRID = np.linspace(0.0, 1.0, 65)


def sample_pieces(curves, tol: float, max_rounds: int = 60, max_split: int = 16):
    """:func:`sample_curves` of a tooth's pieces, placed from their exact turn: ``[(w, points, achieved)]``.

    Each curve that gives its turning (``turning(w)``: points, tangents, angle parts) is taken on
    ``TURN_GRID``, and its vertices are placed (:func:`place_by_turn`) from the exact turn of its
    tangent between grid points, not from a pilot sampling; they are then accepted on a proven bound
    through each chord's middle (:func:`~gearkit.refine.refine_samples` with ``middle=True``: the quarter
    points probed only where the middle does not prove ``tol``). ``achieved`` is a proven bound. A curve
    without turning is sampled as :func:`sample_curves` samples it. Each curve gets, to the last bit,
    what it gets alone.

    Examples
    --------
    A quarter circle of radius 1 at tol 1e-3 (18 chords at the least, as in :func:`adaptive_sample`)
    and a straight line:

    >>> from gearkit.pieces import CircleArc, TipLine
    >>> (_, arc, bound), (_, line, _) = sample_pieces([CircleArc(1.0, 0.0, np.pi / 2), TipLine(1.0, 0.0, 2.0)], 1e-3)
    >>> len(arc) - 1, len(line), bool(bound <= 1e-3)
    (19, 2, True)
    >>> psi = np.arctan2(arc[:, 0], arc[:, 1])  # the sagitta of the widest chord, measured
    >>> bool(1.0 - np.cos(np.diff(psi).max() / 2) <= bound)
    True
    """
    grids = turn_curves(curves, [TURN_GRID] * len(curves))
    turned = [i for i, g in enumerate(grids) if g is not None]
    out = [None] * len(curves)
    if turned:
        group = [curves[i] for i in turned]
        placed = [place_by_turn(TURN_GRID, grids[i][0], grids[i][2], PLACE_AT * tol) for i in turned]
        done = refine_samples(group, placed, None, tol, max_rounds, max_split,
                              turned=first_turnings(group, placed, middle=True), middle=True)
        for i, res in zip(turned, done):
            out[i] = res[:3]
    if len(turned) < len(curves):
        rest = [i for i, g in enumerate(grids) if g is None]
        for i, res in zip(rest, sample_curves([curves[i] for i in rest], tol, max_rounds=max_rounds,
                                              max_split=max_split)):
            out[i] = res
    return out


def place_by_turn(w, points, parts, tol: float) -> np.ndarray:
    """Parameters of the fewest vertices whose chords deviate by about ``tol`` from a curve, from its
    points and the angle parts of its tangent at the sorted parameters ``w`` (ends 0 and 1).

    Between two grid points the tangent turns by the change of the parts' sum, ``|d theta|``, over about
    the chord ``L``: a curvature ``|d theta| / L``, so ``N(s) = integral sqrt(k / (8 tol)) ds`` grows by
    ``sqrt(|d theta| L / (8 tol))`` there; ``ceil(N)`` chords are placed at equal steps of ``N``
    (parameters interpolated). Ends are kept exactly. A proposal: the caller checks the chords.

    Examples
    --------
    A circle of radius 2 at tol 1e-3: a quarter of it needs 25 chords (as :func:`place_by_curvature`
    finds), evenly spaced:

    >>> w = np.linspace(0.0, 1.0, 65)
    >>> psi = np.pi / 2 * w
    >>> placed = place_by_turn(w, 2.0 * np.stack([np.cos(psi), np.sin(psi)], -1), psi[:, None], 1e-3)
    >>> len(placed) - 1, bool(np.allclose(np.diff(placed), 1 / 25))
    (25, True)
    """
    d = points[1:] - points[:-1]
    length = np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1])
    if not length.max(initial=0.0) > 0.0:
        return np.array([0.0, 1.0])
    angle = np.asarray(parts, dtype=float).reshape(len(points), -1).sum(axis=1)
    n_of_s = np.concatenate([[0.0], np.add.accumulate(np.sqrt(np.abs(angle[1:] - angle[:-1]) * length))])
    if not np.isfinite(n_of_s[-1]):
        raise GeometryError("a tooth piece's points or tangent angles are not finite: its vertices cannot be placed")
    return _equal_steps(w, n_of_s / math.sqrt(8.0 * tol))


def _equal_steps(w, n_of_s):
    """``ceil(N)`` chords at equal steps of ``N(s)`` (given at the sorted parameters ``w``, ends 0 and 1):
    their ends' parameters, interpolated, the ends kept exactly."""
    chords = max(1, math.ceil(n_of_s[-1] - 1e-9))
    placed = np.interp(np.linspace(0.0, n_of_s[-1], chords + 1), n_of_s, w)
    placed[0], placed[-1] = 0.0, 1.0
    return placed[np.concatenate([[True], (placed[1:] - placed[:-1]) > 0.0])]  # sorted already (np.unique imports numpy.ma)


def _walk_order(w, pts, probes, q):
    """A sampling's vertices ``w`` and its intervals' probes as one polyline, its parameters and points: in the
    order of the walk through every interval (vertex, its interval's probes, next vertex) where that order is
    sorted, as :func:`place_by_curvature` sorts them (no two parameters equal: a stable sort's order is theirs),
    else vertices then probes (sorted there): ``(w, points, ordered)``."""
    walk_w = np.concatenate([np.concatenate([w[:-1, None], probes], axis=1).ravel(), w[-1:]])
    if np.count_nonzero(walk_w[1:] > walk_w[:-1]) != len(walk_w) - 1:
        return np.concatenate([w, probes.ravel()]), np.concatenate([pts, q.reshape(-1, 2)]), False
    walk_p = np.concatenate([np.concatenate([pts[:-1, None], q], axis=1).reshape(-1, 2), pts[-1:]])
    return walk_w, walk_p, True


def place_by_curvature(w, points, tol: float, ordered: bool = False) -> np.ndarray:
    """Parameters of the fewest vertices whose chords deviate by about ``tol`` from a curve, from a
    dense polyline of it.

    ``w`` (k,) and ``points`` (k, 2) are parameters and points of the curve (any order, or
    ``ordered``: strictly increasing in ``w``, not sorted again; ends at w = 0 and 1 included). The curvature is estimated from the turning of the sorted polyline
    (turn angle over the mean of the two edges at each vertex), ``N(s) = integral sqrt(k / (8
    tol)) ds`` is accumulated along it, and ``ceil(N)`` chords are placed at equal steps of N
    (parameters interpolated). Ends are kept exactly. A proposal: the caller checks the chords.

    Examples
    --------
    A circle of radius 2 bends evenly: a quarter of it at tol 1e-3 needs chords of angle
    ``sqrt(8 tol / 2) / 1`` (in radians, ``k L^2 / 8 = tol``) -- 25 chords, evenly spaced:

    >>> w = np.linspace(0.0, 1.0, 401)
    >>> arc = 2.0 * np.stack([np.cos(np.pi / 2 * w), np.sin(np.pi / 2 * w)], -1)
    >>> placed = place_by_curvature(w, arc, 1e-3)
    >>> len(placed) - 1, math.ceil((np.pi / 2) / math.sqrt(8 * 1e-3 / 2.0))
    (25, 25)
    >>> bool(np.allclose(np.diff(placed), 1 / 25))
    True
    """
    w, p = np.asarray(w, dtype=float), np.asarray(points, dtype=float)
    if not ordered:
        order = w.argsort(kind="stable")
        w, p = w[order], p.take(order, axis=0)
    d = p[1:] - p[:-1]
    length = np.hypot(d[:, 0], d[:, 1])
    if len(length) < 2 or not length.max(initial=0.0) > 0.0:
        return np.array([0.0, 1.0])
    a, b = d[:-1], d[1:]
    turn = np.arctan2(np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]), a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1])  # (a b) summed
    mean = 0.5 * (length[:-1] + length[1:])
    with np.errstate(divide="ignore", invalid="ignore"):
        k = np.where((length[:-1] > 0) & (length[1:] > 0), turn / mean, 0.0)  # at the inner vertices
    root = np.sqrt(np.concatenate([k[:1], k, k[-1:]]))
    n_of_s = np.concatenate([[0.0], np.add.accumulate(length * 0.5 * (root[:-1] + root[1:]))]) / math.sqrt(8.0 * tol)
    return _equal_steps(w, n_of_s)
