"""From envelope branches to the uncut tooth.

The branches of a tool's half tooth join into one continuous curve in the blank frame. What the cutter leaves is
found in two steps, the same for every family:

1. **Loops are cut away.** Where the curve crosses itself (the tip rounding's trochoid cutting into the flank:
   undercut; a cutter flank passing its limit point: trimming), the loop between the crossing points lies inside
   the swept tool and is removed. The crossing is refined to machine precision on the exact branches.
2. **Clip to the half-tooth wedge.** For a tooth centred on +y, its right half lies between the centre line
   (psi = 0) and the space centre line (psi = pi/z), inside the tip circle (outside it for an internal gear). The
   part of the curve joining the space centre line to the tip circle or the centre line is the flank of the half
   tooth; reaching the centre line below the tip circle at an angle means a pointed tooth.

Undercut, trimming and pointing are not special cases: they are read off these steps.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.accuracy import sample_pieces
from gearkit.curves import polar_from_y, polyline_self_intersections, zoom_crossing
from gearkit.errors import GeometryError
from gearkit.pieces import CircleArc, Piece, TipLine, crossings_many, linear_coords
from gearkit.refine import evaluate_curves, first_samples, refine_samples
from gearkit.values import frozen


def _refine_crossing(fa, fb, wa, wb, bounds_a, bounds_b):
    """Damped Newton on ``fa(wa) = fb(wb)`` (exact curves) within the given windows; where it crept (a gap far
    from linear: a small crossing angle next to a cusp), zooming polylines (:func:`~gearkit.curves.zoom_crossing`).
    Central differences over a fixed step (one scaled to a tiny window drowns the derivative in rounding near a
    cusp); a step that does not reduce the gap is halved, so it cannot jump to the branch past a cusp."""
    h = 1e-8
    x = np.array([wa, wb], dtype=float)
    lo = np.array([bounds_a[0], bounds_b[0]])
    hi = np.array([bounds_a[1], bounds_b[1]])

    def gap(v):  # the gap, the point on curve a (the convergence test's scale), and both curves at v -+ h
        pa, pb = evaluate_curves([fa, fb], [np.array([v[0], v[0] - h, v[0] + h]), np.array([v[1], v[1] - h, v[1] + h])])
        return pa[0] - pb[0], pa[0], (pa[1:], pb[1:])  # the differences a step from v will need

    f, at_x, (pa, pb) = gap(x)  # at_x: curve a at x (the last convergence test's scale)
    for _ in range(60):
        jac = np.column_stack([(pa[1] - pa[0]) / (2 * h), -(pb[1] - pb[0]) / (2 * h)])
        try:
            step = np.linalg.solve(jac, f)
        except np.linalg.LinAlgError:
            break
        if not np.all(np.isfinite(step)):
            break
        norm = math.sqrt(f.dot(f))  # np.linalg.norm of a vector, without its dispatch
        for _ in range(40):
            trial = (x - step).clip(lo, hi)
            f_trial, on_a, near = gap(trial)
            if math.sqrt(f_trial.dot(f_trial)) < norm or not step.any():
                break
            step = 0.5 * step
        else:
            break
        moved = np.abs(trial - x).max()
        x, f, (pa, pb), at_x = trial, f_trial, near, on_a
        scale = 1.0 + float(np.abs(at_x).max())
        if moved < 1e-16 or math.sqrt(f.dot(f)) <= 2e-16 * scale:
            break
    if np.linalg.norm(f) > 1e-13 * (1.0 + float(np.abs(at_x).max())):
        x = np.array(zoom_crossing(fa, fb, x[0], x[1], bounds_a, bounds_b)[:2])
    return float(x[0]), float(x[1])


@frozen
class HalfTooth:
    """The right half of one tooth, from the tip (psi = 0) to the space centre (psi = pi/z).

    ``joins[i]`` says how ``pieces[i]`` meets ``pieces[i+1]``: ``"smooth"`` (the cutter's own
    edge continues) or ``"trim"`` (a crossing where a loop of the envelope was cut away).
    """

    pieces: tuple
    joins: tuple
    pointed: bool
    half_pitch_angle: float

    def sample(self, tol: float):
        """Points from tip to space centre with every chord within ``tol``; and the achieved deviation."""
        chunks, worst = [], 0.0
        for k, (_, pts, dev) in enumerate(sample_pieces(self.pieces, tol)):
            chunks.append(pts if k == 0 else pts[1:])
            worst = max(worst, dev)
        return _drop_coincident(np.concatenate(chunks)), worst


def _drop_coincident(pts, rel=1e-13):
    """Drop vertices within ``rel`` (relative to the largest coordinate) of the previous one.

    Pieces of zero length (a sharp cutter corner's envelope, the dust of a tiny loop next to a cusp) sample
    to repeated points: zero-length edges, crossing at round-off scale. Tip and space centre are kept.
    """
    if len(pts) < 3:
        return pts
    eps = rel * float(np.abs(pts).max())
    keep = np.ones(len(pts), dtype=bool)
    step = pts[1:] - pts[:-1]
    keep[1:] = np.sqrt(np.add.reduce(step * step, axis=1)) > eps  # np.linalg.norm's sum, without its checks
    keep[-1] = True
    kept = keep.nonzero()[0]
    if len(kept) > 2 and np.linalg.norm(pts[kept[-1]] - pts[kept[-2]]) <= eps:
        keep[kept[-2]] = False
    return pts[keep]


# Parameters graded geometrically towards both ends of every branch: a loop much smaller than the sampling
# tolerance sits next to a branch junction, so grading the ends resolves loops down to ~1e-13 of the range;
# evaluated with the 49 uniform samples each branch's detection polyline is refined from (enough that one round
# of refinement at the detection tolerance settles a tooth's branches, where 17 took two or three).
_GRADED = np.geomspace(1e-13, 0.05, 90)
_START, _ENDS = np.linspace(0.0, 1.0, 49), np.concatenate([_GRADED, 1.0 - _GRADED])


def _sample_chain(branches, tol):
    # each branch's uniform start, its first probes and its graded ends in one evaluation
    start = first_samples(branches, [_START] * len(branches), [_ENDS] * len(branches))
    refined = refine_samples(branches, [_START] * len(branches), [s[0] for s in start], tol,
                             probed=[s[1] for s in start])
    pts, owner, ws = [], [], []
    for k, ((w, p, *_), s) in enumerate(zip(refined, start)):
        w, p = np.concatenate([w, _ENDS]), np.concatenate([p, s[2]])
        order = np.argsort(w, kind="stable")
        w, p = w[order], p.take(order, axis=0)
        pts.append(p)
        owner.append(np.full(len(w), k))
        ws.append(w)
    return np.concatenate(pts), np.concatenate(owner), np.concatenate(ws)


def _edge_window(owner, ws, edge, reach=3):
    """Parameter window for refining a crossing found on polyline edge ``edge``: that edge and ``reach``
    edges either side on the same branch (the exact crossing may lie on a neighbouring edge)."""
    k = owner[edge]
    lo = edge
    while lo > 0 and lo > edge - reach and owner[lo - 1] == k:
        lo -= 1
    hi = edge + 1
    while hi + 1 < len(ws) and hi < edge + 1 + reach and owner[hi + 1] == k:
        hi += 1
    return float(ws[lo]), float(ws[hi])


def next_crossing(ii, jj, ti, tj, pos_e: int, pos_f: float):
    """The crossing a walk along a self-crossing polyline meets next, taking the outermost loop.

    ``ii, jj, ti, tj`` are the crossings of :func:`~gearkit.curves.polyline_self_intersections`
    (first edge, second edge, fractions along them); the walk stands on edge ``pos_e`` at fraction
    ``pos_f``. Of the crossings on the first edge ahead, the one whose second end lies farthest along
    the polyline is taken, so the whole loop is cut at once. Returns its index, or None when none is ahead.

    Examples
    --------
    >>> import numpy as np
    >>> ii, jj = np.array([2, 2, 5]), np.array([4, 7, 6])
    >>> ti = tj = np.array([0.5, 0.25, 0.5])
    >>> [next_crossing(ii, jj, ti, tj, e, f) for e, f in ((-1, 0.0), (2, 0.5), (6, 0.0))]
    [1, 2, None]
    """
    mask = (ii > pos_e) | ((ii == pos_e) & (ti > pos_f))
    if not mask.any():
        return None
    cand = (mask & (ii == ii[mask].min())).nonzero()[0]
    return int(cand[np.lexsort((tj[cand], jj[cand]))[-1]])


def _remove_loops(branches, pts, owner, ws, significant):
    """Cut the loops out of the chained envelope; returns sections [(k_a, w_a), (k_b, w_b)]."""
    ii, jj, ti, tj = polyline_self_intersections(pts)
    same = (owner[ii] == owner[ii + 1]) & (owner[jj] == owner[jj + 1])
    ii, jj, ti, tj = ii[same], jj[same], ti[same], tj[same]
    sections = []
    start = (int(owner[0]), float(ws[0]))
    pos_e, pos_f = -1, 0.0
    while True:
        pick = next_crossing(ii, jj, ti, tj, pos_e, pos_f)
        if pick is None:
            break
        e_a, e_b = int(ii[pick]), int(jj[pick])
        ka, kb = int(owner[e_a]), int(owner[e_b])
        wa = ws[e_a] + ti[pick] * (ws[e_a + 1] - ws[e_a])
        wb = ws[e_b] + tj[pick] * (ws[e_b + 1] - ws[e_b])
        wa, wb = _refine_crossing(branches[ka], branches[kb], wa, wb,
                                  _edge_window(owner, ws, e_a), _edge_window(owner, ws, e_b))
        # a loop smaller than `significant` is numerical dust at a junction: cut it, but it is no trim
        extent = np.linalg.norm(pts[e_a + 1:e_b + 1] - pts[e_a], axis=1).max(initial=0.0)
        sections.append((start, (ka, wa), extent > significant))
        start = (kb, wb)
        pos_e, pos_f = e_b, float(tj[pick])
    sections.append((start, (int(owner[-1]), float(ws[-1])), False))
    return sections


def _pieces_of(branches, sections):
    """Forward pieces for the kept sections, and the join kinds between consecutive pieces."""
    pieces, joins = [], []
    trimmed_before = False
    for n_sec, ((ka, wa), (kb, wb), trim_after) in enumerate(sections):
        for k in range(ka, kb + 1):
            a = wa if k == ka else 0.0
            b = wb if k == kb else 1.0
            if b <= a and not (k == ka == kb):
                continue
            if pieces:
                joins.append("trim" if (k == ka and n_sec > 0 and trimmed_before) else "smooth")
            pieces.append(Piece(branches[k].label, branches[k], a, b))
        trimmed_before = trim_after
    return pieces, joins


def trim_half_tooth(branches, teeth_or_angle, tip_radius: float, internal: bool, detect_tol: float,
                    pitch: float | None = None) -> HalfTooth:
    """Uncut right half-tooth from the envelope branches of the cutter's facing half tooth.

    Parameters
    ----------
    branches : sequence of Branch, in the tool chain's order
    teeth_or_angle : int (z: the wedge is pi/z wide) or float (the half pitch angle, rad)
    tip_radius : float, mm (the blank's tip circle; for a rack the tip line's height)
    internal : bool (tip circle inside the teeth)
    detect_tol : float, mm
        Chord tolerance of the polyline used to find loops and crossings (refined exactly).
    pitch : float or None, mm
        Given for a rack blank (straight centrode): the wedge is then the strip
        0 <= x <= pitch/2 below the tip line, and ``teeth_or_angle`` is ignored.
    """
    if pitch is not None:
        coords, half = linear_coords, pitch / 2.0
    else:
        coords = polar_from_y
        half = math.pi / teeth_or_angle if isinstance(teeth_or_angle, (int, np.integer)) else float(teeth_or_angle)
    pts, owner, ws = _sample_chain(branches, detect_tol)
    sections = _remove_loops(branches, pts, owner, ws, significant=1e-6 * detect_tol)
    pieces, joins = _pieces_of(branches, sections)

    def psi(p):  # the angle alone (polar_from_y's or linear_coords' second value, to the bit)
        p = np.asarray(p, dtype=float)
        return p[..., 0] if pitch is not None else np.arctan2(p[..., 0], p[..., 1])

    def rho(p):  # the radius alone (their first value)
        p = np.asarray(p, dtype=float)
        return p[..., 1] if pitch is not None else np.hypot(p[..., 0], p[..., 1])

    found = crossings_many(pieces, [(psi, half), (psi, 0.0), (rho, tip_radius)])
    marks = [(k, w, kind) for kind, hits in zip("SCR", found) for k, w in hits]
    marks.sort(key=lambda m: (m[0], m[1]))

    def inside(k, w):
        r, a = coords(pieces[k].curve(np.array([w])))
        in_tip = r[0] >= tip_radius if internal else r[0] <= tip_radius
        return 0.0 < a[0] < half and in_tip

    chosen = None
    for m0, m1 in zip(marks[:-1], marks[1:]):
        kinds = {m0[2], m1[2]}
        if "S" not in kinds or kinds == {"S"}:
            continue
        if m0[0] == m1[0]:
            probe = (m0[0], 0.5 * (m0[1] + m1[1]))
        elif m1[0] > m0[0] + 1:  # a whole piece lies between the marks
            mid = pieces[m0[0] + 1]
            probe = (m0[0] + 1, 0.5 * (mid.w0 + mid.w1))
        else:  # probe the larger remaining share of the two pieces
            a, b = pieces[m0[0]], pieces[m1[0]]
            share_a = (a.w1 - m0[1]) / (a.w1 - a.w0) if a.w1 > a.w0 else 0.0
            share_b = (m1[1] - b.w0) / (b.w1 - b.w0) if b.w1 > b.w0 else 0.0
            probe = (m0[0], 0.5 * (m0[1] + a.w1)) if share_a >= share_b else (m1[0], 0.5 * (b.w0 + m1[1]))
        if inside(*probe):
            chosen = (m0, m1)
            break
    if chosen is None:
        raise GeometryError("no tooth is left between the tooth centre line and the space centre line")
    (ka, wa, kind_a), (kb, wb, kind_b) = chosen
    sel, sel_joins = [], []
    for k in range(ka, kb + 1):
        a = wa if k == ka else pieces[k].w0
        b = wb if k == kb else pieces[k].w1
        if sel:
            sel_joins.append(joins[k - 1])
        sel.append(Piece(pieces[k].label, pieces[k].curve, a, b))
    if kind_a == "S":  # orient from the tip to the space centre
        sel = [p.reversed() for p in reversed(sel)]
        sel_joins = sel_joins[::-1]
        tip_kind, tip_piece = kind_b, sel[0]
    else:
        tip_kind, tip_piece = kind_a, sel[0]
    pointed = False
    if tip_kind == "R":
        r_t, psi_t = coords(tip_piece(np.array([0.0])))
        tip = TipLine(float(tip_radius), 0.0, float(psi_t[0])) if pitch is not None \
            else CircleArc(float(tip_radius), 0.0, float(psi_t[0]))
        sel.insert(0, Piece("tip", tip, 0.0, 1.0))
        sel_joins.insert(0, "corner")
    else:  # reached the centre line: a smooth crest or a pointed tip
        p = tip_piece(np.array([0.0, 1e-6]))
        d = p[1] - p[0]
        pointed = abs(d[1]) > 1e-4 * np.linalg.norm(d)
    return HalfTooth(tuple(sel), tuple(sel_joins), bool(pointed), half)

