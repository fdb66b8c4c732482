"""Fronts: line ends carried along their lines by predictor-corrector continuation (for
:func:`~gearkit.blocking.ends.extend_ends`, which picks the ends and assembles the lines).

A front goes on until

* it meets another end of the same function heading back along it: the two join. The arms of a
  saddle join in the pairs ``F`` connects (a step never flips the side on which ``F`` is positive,
  as going straight through a crossing would): where ``F`` at the saddle is not exactly zero (the
  check forgives 1e-9 m_n there), the two branches of the zero set turn off before the saddle,
  and the joined arms follow them;
* it runs onto a piece of the same line traced already (it joins that piece's end there, or stops; a
  long step onto a line running across it has passed a saddle onto another branch: it is halved);
* its step shrinks below ``tol / 4`` (a line that ends: the edge where ``F`` is undefined; where ``F`` is
  defined all round it, a corner of its line, which it turns: :func:`_turn_corners`), or
* it reaches the window's frame.

Each step predicts along the tangent and looks for the zero along the normal through the
prediction (:func:`~gearkit.blocking.edges.across`: samples shrinking geometrically, the nearest
sign change with ``F`` positive on the same side as before, solved to ``tol / 4``); a step that
turns by more than ``TURN_DEG`` or finds no zero is halved. The new chords are then refined to
``tol`` like the others (:func:`~gearkit.blocking.refinement.densify`).
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.blocking.brackets import segment_roots
from gearkit.blocking.edges import across, step_ends
from gearkit.blocking.refinement import JUMP_FACTOR, JUMP_FALL

__all__ = ["run_fronts", "start_fronts"]

TURN_DEG = 30.0  #: a step turning more than this is halved
ACROSS = "across"  #: a step that ran onto another line of the same function across its path
ONTO = "onto"  #: a step that ran onto a piece of its line traced already, with no end of it to join there
MAX_STEPS = 400  #: steps of one front
CORNER_RADIUS = 4.0  #: a front stuck where F is defined looks for its line's way on round a circle of this many vtol
CORNER_SAMPLES = 64  #: ... at this many points
MAX_TURNS = 4  #: corners one front turns


def start_fronts(F, starts, recs, eps, hmax) -> list:
    """Fronts ``[rec, end, point, tangent, sigma, step, budget, turns]`` for ``starts`` (rec, end, point,
    tangent[, budget]): sigma is the sign of ``F`` to the left of the direction of travel (0:
    unknown); a front that runs farther than its budget (inf: none) is given up."""
    if not starts:
        return []
    P0 = np.array([s[2] for s in starts])
    T0 = np.array([s[3] for s in starts])
    K0 = np.array([recs[s[0]][0] for s in starts])
    N0 = np.column_stack([-T0[:, 1], T0[:, 0]])
    V = F(np.concatenate([P0 + eps * N0, P0 - eps * N0]), np.tile(K0, 2)).reshape(2, -1)
    sig = np.where(np.isfinite(V[0]) & np.isfinite(V[1]), np.sign(V[0] - V[1]),
                   np.where(np.isfinite(V[0]), np.sign(V[0]), -np.sign(V[1])))
    return [[r, end, st[2].copy(), st[3].copy(), float(s) if np.isfinite(s) else 0.0, hmax,
             st[4] if len(st) > 4 else math.inf, 0] for st, s in zip(starts, sig) for r, end in [st[:2]]]


def run_fronts(F, front, new, recs, joins, geo):
    """Carry the fronts ``new`` (appended to ``front``; the earlier ones stay there to be met) until
    each has joined another, stopped or reached the window's frame. ``recs``: the lines, each
    ``[k, points, slopes, head, tail]`` (the points a front adds at its start / end are appended to
    ``head`` / ``tail``); ``joins``: the pairs of ends ``((rec, end), (rec, end))`` joined are appended
    to it; ``geo``: ``(span, vtol, longest step, window lo, window hi, tol)``."""
    span, vtol, hmax, lo, hi, tol = geo
    first = len(front)
    front += new
    active = [False] * first + [f[4] != 0 for f in new]
    turn = math.cos(math.radians(TURN_DEG))
    for _ in range(MAX_STEPS):
        act = [i for i, a in enumerate(active) if a]
        if not act:
            break
        _join(F, front, active, act, recs, joins, span, vtol)
        act = [i for i in act if active[i]]
        if act:  # the frame: no step past it (every front's distance to it along its tangent at once)
            T = np.array([front[i][3] for i in act])
            P = np.array([front[i][2] for i in act])
            with np.errstate(divide="ignore", invalid="ignore"):
                lim = np.where(T > 0, (hi - P) / T, np.where(T < 0, (lo - P) / T, np.inf)).min(axis=1)
            for i, m in zip(act, lim.tolist()):
                f = front[i]
                f[5] = min(f[5], m)
                if f[5] <= vtol:
                    active[i] = False
        act = [i for i in act if active[i]]
        if act:
            _step(F, front, act, active, recs, joins, vtol, span, hmax, turn, lo, hi)


def _join(F, front, active, act, recs, joins, span, close):
    """Join fronts that meet: another end of the same function within both steps, each ahead of
    the other, with ``F`` changing sign within a quarter of their distance from the middle of the
    chord between them, on the side the fronts expect (or within ``close`` of each other). Two
    such fronts not joinable yet halve their steps towards each other, so as not to pass."""
    cand = []
    for i in act:
        fi = front[i]
        for j, fj in enumerate(front):
            if j == i or recs[fj[0]][0] != recs[fi[0]][0] or fj[4] != -fi[4]:
                continue
            if fj[0] == fi[0] and not (recs[fi[0]][3] or recs[fi[0]][4]):
                continue  # the two fronts of one point that has not moved
            d = fj[2] - fi[2]
            L = float(np.hypot(*d))
            if L > fi[5] + fj[5] or np.dot(fi[3], fj[3]) > 0:
                continue
            if L <= close:
                cand.append((-1.0, i, j))  # met: joined as they are
            elif np.dot(d, fi[3]) > 0 and np.dot(d, fj[3]) < 0:
                cand.append((L, i, j))
    if not cand:
        return
    cand.sort()
    met = [c for c in cand if c[0] < 0]
    cand = [c for c in cand if c[0] >= 0]
    used = set()
    for _, i, j in met:
        if i not in used and j not in used:
            joins.append(((front[i][0], front[i][1]), (front[j][0], front[j][1])))
            active[i] = active[j] = False
            front[i][4] = front[j][4] = 0.0
            used |= {i, j}
    cand = [c for c in cand if c[1] not in used and c[2] not in used]
    if not cand:
        return
    Q = np.array([0.5 * (front[i][2] + front[j][2]) for _, i, j in cand])
    D = np.array([front[j][2] - front[i][2] for _, i, j in cand])
    N = np.column_stack([-D[:, 1], D[:, 0]]) / np.hypot(*D.T)[:, None]
    reach = 0.25 * np.array([L for L, _, _ in cand])
    sig = np.array([front[i][4] for _, i, _ in cand])
    which = np.array([recs[front[i][0]][0] for _, i, _ in cand])
    found = [c >= 0 for _, _, c in across(F, Q, N, reach, sig, which, span)]
    for (L, i, j), ok in zip(cand, found):
        if i in used or j in used or not (active[i] or active[j]):
            continue
        if ok:
            joins.append(((front[i][0], front[i][1]), (front[j][0], front[j][1])))
            active[i] = active[j] = False
            front[i][4] = front[j][4] = 0.0  # joined: no longer a candidate
            used |= {i, j}
        else:
            front[i][5] = min(front[i][5], 0.5 * L)


def _step(F, front, act, active, recs, joins, vtol, span, hmax, turn, lo, hi):
    """One predictor-corrector step of the fronts ``act``."""
    T = np.array([front[i][3] for i in act])
    P = np.array([front[i][2] for i in act])
    h = np.array([front[i][5] for i in act])
    Q, out, E, ahead = step_ends(F, P, T, h, np.array([recs[front[i][0]][0] for i in act]), span, vtol / 4)
    if out.size:  # the prediction left the defined area: the step ends just before its edge
        h = h[out]
        for r, q in zip(out, E):
            f = front[act[r]]
            f[5] = float(np.dot(q - P[r], T[r]))
            Q[r] = P[r] + f[5] * T[r]
        # a line running along the edge, closer to it than vtol where its tangent meets it: predicted on
        # the edge a whole step ahead instead (moved back to it along the normal), and corrected from there
        along = np.flatnonzero(np.array([front[act[r]][5] < vtol for r in out]))
        for r, q, hh in zip(out[along], ahead[along], h[along]):
            if np.isfinite(q[0]):
                Q[r], front[act[r]][5] = q, float(hh)
        stop = [act[r] for r in out if front[act[r]][5] < vtol]
        for i in stop:
            active[i] = False
        keep = [r for r in range(len(act)) if act[r] not in stop]
        act, T, P, Q = [act[r] for r in keep], T[keep], P[keep], Q[keep]
        if not act:
            return
    N = np.column_stack([-T[:, 1], T[:, 0]])
    sig = np.array([front[i][4] for i in act])
    which = np.array([recs[front[i][0]][0] for i in act])
    reach = np.array([front[i][5] for i in act])
    lo_p, hi_p, flo, fhi, ks, who = [], [], [], [], [], []
    stuck = []  # fronts whose steps shrank below vtol where F is defined: a corner of their line, maybe
    for r, (i, (s, v, c)) in enumerate(zip(act, across(F, Q, N, reach, sig, which, span, vtol / 4))):
        f = front[i]
        if c < 0:
            f[5] *= 0.5
            if f[5] < vtol:
                active[i] = False
                stuck.append(i)
            continue
        lo_p.append(Q[r] + s[c] * N[r]), hi_p.append(Q[r] + s[c + 1] * N[r])
        flo.append(v[c]), fhi.append(v[c + 1]), ks.append(which[r]), who.append(i)
    if not who:
        _turn_corners(F, front, stuck, active, recs, vtol, lo, hi)
        return
    R = segment_roots(F, np.array(lo_p), np.array(hi_p), np.array(flo), np.array(fhi), vtol, np.array(ks))
    for i, r in zip(who, R):
        f = front[i]
        d = r - f[2]
        L = float(np.hypot(*d))
        if L <= 0 or np.dot(d, f[3]) < turn * L or np.any(r < lo - vtol) or np.any(r > hi + vtol):
            f[5] *= 0.5
            if f[5] < vtol:
                active[i] = False
                stuck.append(i)
            continue
        close = 8 * vtol
        hit = _collides(F, i, r, d / L, L, front, active, recs, joins, close, turn)
        # a long step onto another branch, across the line's path (past a saddle), or onto a piece with no end
        # to join there (it may have passed a saddle onto a branch at a small angle to its own): shorter
        if hit == ACROSS or hit == ONTO and L > close:
            f[5] *= 0.5
            continue
        if hit is True:
            continue
        f[6] -= L
        if f[6] < 0:  # carried towards the edge farther than it lay: not a line that meets it there
            recs[f[0]][3 + f[1]].clear()
            active[i], f[4] = False, 0.0
            continue
        recs[f[0]][3 + f[1]].append(r)
        if hit == ONTO:  # a short step onto a piece traced already with no end to join: it stops there
            active[i] = False
            continue
        f[2], f[3] = r, d / L
        f[5] = min(2 * f[5], hmax)
    _turn_corners(F, front, stuck, active, recs, vtol, lo, hi)


def _turn_corners(F, front, stuck, active, recs, vtol, lo, hi):
    """Turn the fronts ``stuck`` round a corner of their line: a front whose steps shrank below ``vtol``
    where ``F`` is defined all round it (on a circle of ``CORNER_RADIUS vtol`` about its point) stands
    at a corner of a kinked zero set (the smallest of two margins, the tip sweep's at its resolution),
    which no step along its tangent passes (each turns more than ``TURN_DEG``). Its line goes on where
    ``F`` changes sign on that circle with ``F`` of the front's sign to the left of the way out (the way
    back has it to the right), the zero solved and ``|F|`` falling there (not a jump), where the circle
    crosses the zero set just twice (a saddle's four arms, or lines crowding, are left alone). The front
    goes on from that zero (up to ``MAX_TURNS`` times). Internal 17/76 z0 17 at tol 1e-3: tip_interference's
    upper arm, cut by the grid across a wedge, stopped at the wedge's corner (0.2535, -0.8957) and its lower
    arm, beside the no-pair area, was not carried: the line between them, 0.035 long, was missing (scan
    5.67 tol)."""
    stuck = [i for i in stuck if front[i][4] != 0 and front[i][7] < MAX_TURNS]
    if not stuck:
        return
    rho = CORNER_RADIUS * vtol
    a = 2 * np.pi * np.arange(CORNER_SAMPLES) / CORNER_SAMPLES
    ring = rho * np.column_stack([np.cos(a), np.sin(a)])
    P = np.array([front[i][2] for i in stuck])
    K = np.array([recs[front[i][0]][0] for i in stuck])
    C = P[:, None, :] + ring[None]
    V = F(C.reshape(-1, 2), np.repeat(K, CORNER_SAMPLES)).reshape(len(stuck), CORNER_SAMPLES)
    pos, nxt = V > 0, np.roll(V, -1, axis=1) > 0
    sig = np.array([front[i][4] for i in stuck])
    two = np.isfinite(V).all(axis=1) & (np.count_nonzero(pos != nxt, axis=1) == 2)  # the way back and one on
    ch = two[:, None] & (pos != nxt) & (nxt == (sig > 0)[:, None])
    r, j = np.nonzero(ch)
    if not r.size:
        return
    j1 = (j + 1) % CORNER_SAMPLES
    fa, fb = V[r, j], V[r, j1]
    R = segment_roots(F, C[r, j], C[r, j1], fa, fb, vtol, K[r])
    fr, grad = np.abs(F(R, K[r])), np.abs(fb - fa) / np.hypot(*(C[r, j1] - C[r, j]).T)
    with np.errstate(invalid="ignore"):  # a jump of F keeps |F| up (as a vertex's, level)
        jump = (fr > JUMP_FACTOR * grad * vtol) & (fr > JUMP_FALL * np.fmin(np.abs(fa), np.abs(fb)))
    ok = ~jump & np.isfinite(fr) & np.all(R >= lo - vtol, axis=1) & np.all(R <= hi + vtol, axis=1)
    for rr, q in zip(r[ok], R[ok]):
        i = stuck[rr]
        f = front[i]
        L = float(np.hypot(*(q - f[2])))
        if 0 < L <= f[6]:  # (within the front's budget)
            recs[f[0]][3 + f[1]].append(q)
            f[2], f[3], f[5], f[6], f[7] = q, (q - f[2]) / L, rho, f[6] - L, f[7] + 1
            active[i] = True


def _collides(F, i, r, u, L, front, active, recs, joins, close, turn):
    """True when front ``i``'s next point ``r`` (a step of length ``L`` along ``u``) lies within
    ``close`` of a line of the same function traced already (another record): the front has run
    onto it. It joins that line's nearest open end within ``2 L`` (heading back), or an end no front carries
    that it has reached (:func:`_open_end`); with none to join,
    ``ONTO``: a step no longer than ``close`` is taken and the front stops there, a longer one is halved (a
    line cut on both sides of a loop's or a wedge's turn, whose front ran onto the piece the grid traced
    round the turn as a loop of its own or with its end beside the no-pair edge, not carried: 14/55's
    sliding, 56/59's interference.1, stopped where they stood 0.05 to 0.09 short of it; taken whole, a
    step of two cells passed 58/63's saddle at (1, 1) onto the other branch). ``ACROSS``
    when the step is longer than ``close`` and that line runs across it (at more than the angle
    whose cosine is ``turn``): a step past a saddle onto another branch, whose side of ``F`` the
    front's orientation cannot tell from its own there (25/58's interference.2 beside (-1, 1),
    where F is 1e-9: the arms of the upper branch stopped on the lower one, 0.02 apart at tol 1e-5);
    the front is not stopped."""
    from gearkit.chords import chord_distance

    f = front[i]
    k = recs[f[0]][0]
    for rr, (kk, p, _, hd, tl) in enumerate(recs):
        if kk != k or rr == f[0]:
            continue
        q = np.vstack([np.reshape(hd[::-1], (-1, 2)), p, np.reshape(tl, (-1, 2))])
        if len(q) < 2:
            continue
        dist = float(np.min(chord_distance(q[:-1], q[1:], r)))  # (one point: every chord at once, exact)
        if dist > close:
            continue
        if L > close:
            t = np.diff(q, axis=0)  # the line's chord nearest to r: its direction there
            n2 = np.einsum("ij,ij->i", t, t)
            with np.errstate(invalid="ignore", divide="ignore"):
                w = np.clip(np.einsum("ij,ij->i", r - q[:-1], t) / n2, 0.0, 1.0)
            j = int(np.nanargmin(np.hypot(*(q[:-1] + np.nan_to_num(w)[:, None] * t - r).T)))
            if n2[j] > 0 and abs(float(np.dot(t[j], u))) < turn * math.sqrt(n2[j]):
                return ACROSS
        ends = [j for j, g in enumerate(front) if g[0] == rr and g[4] == -f[4] and g[4] != 0
                and float(np.hypot(*(g[2] - f[2]))) <= 2 * L]
        if not ends:
            e = _open_end(F, k, rr, q, r, u, f[4], front, joins, close)
            if e is None:
                return ONTO
            joins.append(((f[0], f[1]), (rr, e)))
            f[4] = 0.0
            active[i] = False
            return True
        j = min(ends, key=lambda j: float(np.hypot(*(front[j][2] - f[2]))))
        joins.append(((f[0], f[1]), (front[j][0], front[j][1])))
        active[j] = False
        front[j][4] = 0.0
        f[4] = 0.0
        active[i] = False
        return True
    return False


def _open_end(F, k, rr, q, r, u, sigma, front, joins, close):
    """The end (0: first, 1: last) of record ``rr``'s line ``q`` (of function ``k``) that a front at ``r``
    heading along ``u`` with ``F`` of sign ``sigma`` on its left goes on into: an open end within ``close`` of
    ``r``, not joined and not carried (no front of its own), that the front meets head on with ``F`` of its
    sign on the same side (the line's way into ``q`` from that end has ``F`` of sign ``sigma`` on its left);
    or None. An end
    left where the grid's line stops beside the no-pair area is not carried: a front turned round a corner
    towards it stopped beside it (internal 17/76 z0 17 at tol 1e-3: tip_interference's turned front 1.9e-3
    from the lower arm's end, the line in two pieces)."""
    if len(q) < 2 or np.array_equal(q[0], q[-1]):
        return None
    taken = {e for pair in joins for e in pair} | {(g[0], g[1]) for g in front}
    for e, a, b in ((0, q[0], q[1]), (1, q[-1], q[-2])):
        t = b - a  # the way into the line from this end
        n = float(np.hypot(*t))
        if (rr, e) in taken or n == 0 or float(np.hypot(*(a - r))) > close or np.dot(t, u) <= 0:
            continue
        mid, side = 0.5 * (a + b), min(close, 0.5 * n) / n * np.array([-t[1], t[0]])  # the first chord's middle
        left, right = F(np.array([mid + side, mid - side]), np.full(2, k))
        if np.isfinite(left) and np.isfinite(right) and np.sign(left - right) == sigma:
            return e
    return None
