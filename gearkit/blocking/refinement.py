"""Chords made to keep the tolerance: the vertices added to traced lines until every chord lies within ``tol``.

Step 3 of :func:`~gearkit.blocking.level.zero_lines` (see there for the others), on the lines of every curve at
once, with ``F(points (n, 2), which (n,) int) -> (n,)`` (NaN where undefined) as there.

:func:`densify`: a chord's deviation from its curve is estimated at its middle ``m`` from
``|F(m)| / |grad F|`` (the slope known from the roots that made its ends), and where that is within ``tol / 2``
at its quarters too (a curve bent one way then the other crosses its chord at the middle: 25/54 z0 20's sliding
line at tol 1e-5, a grid chord 7.3 tol off at three quarters, is split at its middle's root); a chord
estimated within ``tol / 2`` is kept, any other is measured by a root of ``F`` along its normal through ``m`` and, if that
root (where the normal meets a zero to each side, the nearer by its root, on a line's chord and on a region's:
across a kink of ``F`` the secant misjudges which, :meth:`~gearkit.blocking.brackets.NearestBracket.nearer`) is
more than ``tol`` away, split into
as many pieces as its curvature needs
(``sqrt(deviation / (tol / 2))``, new vertices solved near the parabola through the three known points),
round after round. A chord with no zero at those samples is searched again at distances from its middle
falling geometrically to ``tol / 4`` (a strip, a saddle's thin wedge, or beside a region's edge a strip of
it, narrower than their spacing; a line's chord also at samples no farther apart than ``tol``: a strip of the
other sign between two of those distances, the chord's line beside it, was missed and the chord cut, 45/82 z0 13's
interference.1 beside a neck of its negative part), and beyond the normal's ends (:mod:`~gearkit.blocking.wide`;
a region's zero found only there is read as far as its root lies against the ladder's within the normal's ends,
and is none past another of the region's chords: :func:`~gearkit.blocking.wide.past_lines`). One from one side
of a strip to the other (brackets.two_lines) is cut, not split (a zigzag across the strip lost an arm: 46/49's
interference.1 beside (1, 1)), its ends carried on (ends). So every point of a polyline lies within about
``1.25 tol`` of its curve; coarser tols cost less.

``F`` may have kinks (e.g. the smallest of several margins); a corner of a zero set is approached
by splitting the chords beside it until they pass within ``tol``.
"""
from __future__ import annotations

import numpy as np

from gearkit.blocking.brackets import NearestBracket, round_off_roots, segment_roots, two_lines
from gearkit.blocking.corners import corner_splits, uncut
from gearkit.blocking.edges import touchdowns, toward_edge
from gearkit.blocking.flats import carry_down
from gearkit.blocking.grid import cut_positions
from gearkit.blocking.wide import past_lines, search_wide

__all__ = ["densify"]

VERTEX_FRACTION = 0.25  #: vertices are solved to this fraction of tol
ESTIMATE_FRACTION = 0.5  #: a chord whose estimated deviation is below this fraction of tol is kept
SPLIT_FRACTION = 0.75  #: a chord measured farther than this fraction of tol from its curve is split (a
#: kink of the curve beside the chord's middle lies at most twice as far as the middle: 1.5 tol)
SLOPE_RATIO = 2.0  #: a chord is estimated only where the slopes at its ends agree within this factor
STEEP = 1e5  #: ... and below this (beside the no-pair edge F goes as a cube root: an extrapolated zero may be none)
SPLIT_MEASURED = 0.5  #: the same for measured curves (a region's corners: its zero may be found on a diagonal)
MAX_ROUNDS = 60  #: rounds of chord splitting
MAX_PIECES = 64  #: most pieces one chord is split into in one round
WIDE_REGION = True  #: the wider search for measured curves too
SHORT_KEEP = 2.5  #: a line's chord this short (tol) with no zero beside it (a saddle's neck) stays: within 1.25 tol
MEASURED_LADDER = 0.125  #: a measured curve's chord's ladder starts this many chord lengths from its middle
STRIP_PROBE = 0.5  #: a chord whose middle lies between two zeros is read this many tol beside its ends (two_lines)
JUMP_FACTOR = 100.0  #: a solved vertex with |F| above this times slope x tol sits on a jump, not a zero
JUMP_FALL = 0.5  #: ... and |F| there above this fraction of the smaller |F| at the bracket's ends (the
#: solver keeps the better end: a real zero is far below it at any tol, a pole or a jump is not)


def densify(F, lines, tol: float, max_step: float | None = None, measure=(), kinked=(), slopes=False,
            kept=None, dips=True, loose=None, others=(), down=None) -> list:
    """``lines`` (a list of ``(k, points (n, 2), slope (n,))``: curve index, vertices on the curve, and
    estimates of ``|grad F_k|`` there, NaN if unknown) with vertices added until every chord lies
    within ``tol`` of its curve and is at most ``max_step`` long (a fourth entry, a mask of the
    chords still to refine, leaves the others as they are); returns ``[(k, points)]`` (with
    ``slopes=True``: ``[(k, points, slopes)]``). Curves whose
    index is in ``measure`` (e.g. the smallest of several functions, whose slope jumps at the kinks)
    have every chord measured, never estimated; so do the curves in ``kinked`` (a kink between two
    branches of one margin, e.g. the contact ratio where its limiting end changes: an acute wedge's
    middle value says nothing of its tip), which are otherwise traced as the rest. ``kept``: a list to
    which a measured curve's chords with no zero found across them are added as ``(k, start, end)``. ``dips``:
    lines dipping to the no-pair edge carried to it (:func:`~gearkit.blocking.edges.touchdowns`). ``loose``: a
    list to which the ends of a line's chords cut are added as ``(k, end, chord length)``, to carry on (ends); only with
    it is a kinked curve's chord across a strip or a thin loop cut (without it, such a chord is split as before).
    ``others``: ``[(k, points)]``, lines not refined here that a measured curve's zeros are read against
    (:func:`~gearkit.blocking.wide.past_lines`). ``down`` (``[(k, points)]``, the other lines, or None): a
    measured curve's cut across a flat strip moved once towards its end where no line crosses the way
    (:func:`~gearkit.blocking.flats.carry_down`)."""
    vtol, moved_once = VERTEX_FRACTION * tol, set()
    step = np.inf if not max_step else float(max_step)
    state = [(ln[0], np.asarray(ln[1], float), np.asarray(ln[2], float),
              np.asarray(ln[3], bool) if len(ln) > 3 else np.ones(len(ln[1]) - 1, bool)) for ln in lines]
    n_curves = 1 + max((ln[0] for ln in lines), default=0)
    trust = np.ones(n_curves, dtype=bool)
    trust[[k for k in measure if k < n_curves]] = False
    estimate = trust.copy()
    estimate[[k for k in kinked if k < n_curves]] = False
    for _ in range(MAX_ROUNDS):
        parts = [(n, np.flatnonzero(st[3])) for n, st in enumerate(state) if np.count_nonzero(st[3])]
        if not parts:
            break
        A = np.concatenate([state[n][1][i] for n, i in parts])
        B = np.concatenate([state[n][1][i + 1] for n, i in parts])
        gA = np.concatenate([state[n][2][i] for n, i in parts])
        gB = np.concatenate([state[n][2][i + 1] for n, i in parts])
        which = np.concatenate([np.full(i.size, state[n][0]) for n, i in parts])
        d = B - A
        L = np.hypot(d[:, 0], d[:, 1])
        nrm = np.column_stack([-d[:, 1], d[:, 0]]) / np.maximum(L, 1e-300)[:, None]
        m = 0.5 * (A + B)
        fm = F(m, which)
        with np.errstate(invalid="ignore"):
            slope = np.fmin(gA, gB)
            est = np.abs(fm) / slope
        live = L > vtol
        long = L > step
        with np.errstate(invalid="ignore", divide="ignore"):
            even = np.fmax(gA, gB) <= SLOPE_RATIO * slope  # a slope that jumps along the chord: a kink
        keep = ~live | (~long & estimate[which] & even & (slope <= STEEP) & (est <= ESTIMATE_FRACTION * tol)) \
            | (fm == 0) & ~long
        quiet = np.flatnonzero(keep & live)  # kept on its middle: read at its quarters too (an S-bend)
        if quiet.size:
            Q = np.concatenate([A[quiet] + 0.25 * d[quiet], A[quiet] + 0.75 * d[quiet]])
            fq = np.abs(F(Q, np.tile(which[quiet], 2))).reshape(2, -1).max(axis=0)
            with np.errstate(invalid="ignore", divide="ignore"):
                bent = quiet[fq / slope[quiet] > ESTIMATE_FRACTION * tol]
            long[bent], keep[bent] = True, False  # (split at its middle's root, whatever its deviation there)
        # measure the others: the root of F along the normal through the middle
        meas = np.flatnonzero(~keep & np.isfinite(fm))
        f0 = fm[meas]
        mm, nm_, Lm, km = m[meas], nrm[meas], L[meas], which[meas]
        # the nearest zero from the middle: first along the normal (half a chord to each side), then,
        # for the chords with none there, sampled rays of a chord's length along the normal and the
        # diagonals (a ray past a saddle or across a strip narrower than itself crosses two zeros
        # between its ends; at a saddle's corner the normal only touches zero)
        best = NearestBracket(mm, f0)
        out_dir = np.full(mm.shape, np.nan)  # towards the no-pair area, where the normal runs into it
        # the middle between two zeros along the normal: in a strip or a thin loop, the kinked curves' too where the
        # ends of a cut are carried on (``loose``; internal 13/56 z0 23's tip sweep, flat inside an island 0.005 wide:
        # the grid's chord from its upper side to its far end was split at the lower side's zero, the nearer, and
        # walked round the tip, the far end left out, 2.2 tol; a chord the continuation's fronts joined across a
        # thin wedge, cut and not carried again, left both sides open, 19/42 z0 19's tip sweep, 2.07 tol: the
        # densify after the continuation carries its cuts' ends on too, level.zero_lines)
        strip = (trust if loose is not None else estimate)[km]
        sides = []  # each side's end and value: a zero to both sides is told by its root (NearestBracket.nearer)
        for sgn in (1.0, -1.0):
            end = mm + sgn * 0.5 * Lm[:, None] * nm_
            fe = F(end, km)
            best.consider(np.arange(meas.size), mm, f0, end, fe)
            sides.append((end, fe))
            with np.errstate(invalid="ignore"):
                strip &= np.isfinite(fe) & ((fe > 0) != (f0 > 0))
            edge = np.flatnonzero(np.isnan(fe) & trust[km])
            if edge.size:  # into the no-pair area: the zero nearest the middle among samples from its edge up
                out_dir[edge] = sgn * nm_[edge]
                lo_e, flo_e, hi_e, fhi_e = toward_edge(F, mm[edge], f0[edge], end[edge], km[edge])
                best.consider(edge, lo_e, flo_e, hi_e, fhi_e)
        # a chord with a zero to each side: the nearer root, the region's too (18/74 z0 33 internal at tol 1e-5: a
        # chord along the gentle side of a wedge, its middle on it, read the steep side 0.0045 off as the nearer by
        # the secant, was split there and the outline went over the wedge's tip three times)
        best.nearer(F, sides, km, vtol)
        wide = np.flatnonzero(~best.have & (trust[km] | WIDE_REGION))
        if wide.size:  # none within the normal's ends: searched beyond them (wide)
            search_wide(F, best, wide, mm, f0, nm_, Lm, km, trust[km], vtol)
        thin = np.flatnonzero(~best.have & (Lm > vtol))
        if thin.size:  # no zero at the samples: a strip narrower than their spacing, searched on a ladder (a
            meas_t = ~trust[km[thin]]  # measured curve's near its middle, to one side only: a cut meets none or two;
            # a line's with samples no farther apart than tol too: a strip of the other sign between two rungs)
            best.ladder(F, thin, nm_[thin], np.where(meas_t, MEASURED_LADDER, 0.5) * Lm[thin], km[thin], vtol, meas_t,
                        np.where(meas_t, np.inf, tol))
        # a chord from one side of a strip to the other is cut (not split into a zigzag across it), its ends
        # carried on along their lines (loose: ends)
        found = best.have & ~two_lines(F, A[meas], B[meas], nm_, km, strip, STRIP_PROBE * tol)
        root = mm.copy()
        g_root = np.full(len(mm), np.nan)  # |grad F| at the root, off its last bracket (see zero_lines)
        if found.any():
            root[found], g_root[found] = segment_roots(F, best.lo[found], best.end[found], best.flo[found],
                                                       best.fe[found], vtol, km[found], True)
            # a "root" through a pole or a jump of F is none: |F| stays large there
            solved = np.flatnonzero(found)
            slope_end = np.abs(best.fe[solved] - best.flo[solved]) / np.hypot(*(best.end[solved] - best.lo[solved]).T)
            fr = np.abs(F(root[solved], km[solved]))
            bad = (fr > JUMP_FACTOR * slope_end * tol) & (fr > JUMP_FALL * np.fmin(np.abs(best.flo[solved]),
                                                                               np.abs(best.fe[solved])))
            # |F| did not fall at a root solved to vtol: solved again to round-off, where a zero beside the no-pair
            # edge (F going as a root of the distance to it) falls and a jump does not (45/47's sliding leg, 5e-8
            # from the edge for 0.03 along it: F from -7.9 on the edge to 0 there, each chord's root read as a
            # jump at tol 1e-5 and the line cut, 158 tol; the band's vertices are solved so too: round_off_roots)
            again = solved[bad]
            if again.size:
                r2, g2, fell = round_off_roots(F, best.lo[again], best.end[again], best.flo[again], best.fe[again],
                                               km[again], JUMP_FALL)
                root[again[fell]], g_root[again[fell]] = r2[fell], g2[fell]
                bad[np.flatnonzero(bad)[fell]] = False
            found[solved[bad & trust[km[solved]]]] = False
            # a measured curve's zero beyond the normal's ends past another of its chords: none (a cut)
            far = solved[~trust[km[solved]] & (np.hypot(*(root[solved] - mm[solved]).T) > 0.5 * Lm[solved])]
            if far.size:
                seen = [st[:2] for st in state] + list(others)
                found[far[past_lines(seen, km[far], A[meas[far]], B[meas[far]], mm[far], f0[far], root[far],
                                      tol)]] = False
        # down: a cut across a flat strip moved once towards its end (flats; a wedge walked down: 23/89, 2388 tol off)
        dn = np.flatnonzero(~found & ~trust[km] & live[meas]) if down is not None else np.zeros(0, int)
        dn, (A2, B2) = dn[[(tuple(A[r]), tuple(B[r])) not in moved_once for r in meas[dn]]], np.zeros((2, 0, 2))
        if dn.size:
            seen = [st[:2] for st in state] + list(others) + list(down)
            moved, end, A2, B2 = carry_down(F, A[meas[dn]], B[meas[dn]], km[dn], tol)
            g, i = np.flatnonzero(moved), dn[moved]
            moved[g[past_lines(seen, km[i], A[meas[i]], B[meas[i]], mm[i], f0[i], end[g], tol)]] = False
            dn, A2, B2 = meas[dn[moved]], A2[moved], B2[moved]
            moved_once |= {(tuple(a), tuple(b)) for a, b in zip(A2, B2)}
        off = np.einsum("ij,ij->i", root - m[meas], nrm[meas])
        # a zero found on a diagonal ray is as far as it lies from the middle (an acute corner beyond it)
        dev = np.where(best.diagonal, np.hypot(*(root - mm).T), np.abs(off))
        limit = np.where(trust[km] & even[meas], SPLIT_FRACTION, SPLIT_MEASURED) * tol
        split_m = found & ((dev > limit) | long[meas])
        # a line's chord kept on its middle's root is read at its quarters too, as one kept on its estimate is: a
        # line crossing it like an S (42/52 z0 17 internal at tol 1e-5: exit_jamming 5.4 tol beside a quarter,
        # its middle on the line, 48 tol off near the far end), F of opposite signs there, is split at the
        # middle's root (a bulge to one side is the middle's to measure: 42/52's interference.1 at tol 1e-3,
        # a chord across the corner of its saddle, 0.62 tol off, split there, left a chord 1.97 tol off)
        held = np.flatnonzero(found & ~split_m & trust[km] & live[meas] & np.isfinite(g_root))
        if held.size:
            r = meas[held]
            fq = F(np.concatenate([A[r] + 0.25 * d[r], A[r] + 0.75 * d[r]]), np.tile(km[held], 2)).reshape(2, -1)
            with np.errstate(invalid="ignore", divide="ignore"):
                bent = ((fq[0] > 0) != (fq[1] > 0)) & (np.abs(fq).max(axis=0) / g_root[held] > limit[held])
            split_m[held[bent]] = True
        # no zero across a line's chord: two components (a region's loop stays closed), each carried to where
        # it meets the no-pair area's edge when the chord runs beside it (a line dipping to the edge)
        lost = np.flatnonzero(~found & live[meas] & trust[which[meas]] & (best.have | (Lm > SHORT_KEEP * tol)))
        if kept is not None:  # a measured curve's chord with no zero across it: kept as it is, and noted
            kept += [(int(which[r]), A[r].copy(), B[r].copy()) for r in meas[~found & live[meas] & ~trust[km]]]
        cut = set(meas[lost].tolist())
        if loose is not None:  # (k, end, the chord's length: the first step of its continuation)
            loose += [(int(which[r]), P.copy(), float(L[r])) for r in meas[lost] for P in (A[r], B[r])]
        touch = {}  # chord row -> (new vertices, the first of the chord to cut)
        lost = lost[np.isfinite(out_dir[lost, 0])]
        if lost.size and dips:
            rr = meas[lost]
            TA, TB = touchdowns(F, A[rr], B[rr], out_dir[lost], which[rr], vtol)
            for r, ta, tb in zip(rr.tolist(), TA, TB):
                new = np.array([t for t in (ta, tb) if np.isfinite(t[0])]).reshape(-1, 2)
                if len(new):
                    touch[r] = (new, ta if np.isfinite(ta[0]) else A[r])
        # chords measured and within tol are kept; chords with no root found are kept as they are
        inserts = {}  # chord row -> (points (j, 2) ordered along the chord, slopes)
        rows = meas[split_m]
        if rows.size:
            offs, devs = off[split_m], dev[split_m]
            pieces = np.clip(np.ceil(np.sqrt(devs / (ESTIMATE_FRACTION * tol))), 2, MAX_PIECES).astype(int)
            pieces = np.maximum(pieces, np.ceil(L[rows] / step).astype(int) if np.isfinite(step) else 2)
            pieces = np.minimum(pieces, MAX_PIECES)
            # a measured curve (kinks of a smallest-of) is split at its middle only: the parabola
            # does not predict the points beside a corner
            pieces = np.where(trust[which[rows]] & ~best.diagonal[split_m], pieces, 2)
            # interior points at t = j / pieces, solved along the normal near the parabola's offset
            r_idx = np.repeat(np.arange(rows.size), pieces - 1)
            j = np.concatenate([np.arange(1, p) for p in pieces])
            tt = j / pieces[r_idx]
            keep_mid = np.abs(tt - 0.5) > 1e-12
            r_idx, tt = r_idx[keep_mid], tt[keep_mid]
            row = rows[r_idx]
            base = A[row] + tt[:, None] * d[row]
            pred = 4.0 * offs[r_idx] * tt * (1 - tt)
            nn = nrm[row]
            lo_p, hi_p = base - 0.5 * pred[:, None] * nn, base + 2.0 * pred[:, None] * nn
            if len(row):
                flo = F(lo_p, which[row])
                fhi = F(hi_p, which[row])
                okb = np.isfinite(flo) & np.isfinite(fhi) & ((flo > 0) != (fhi > 0))
                pts, gs = np.full(lo_p.shape, np.nan), np.full(len(row), np.nan)
                if okb.any():
                    pts[okb], gs[okb] = segment_roots(F, lo_p[okb], hi_p[okb], flo[okb], fhi[okb], vtol,
                                                      which[row][okb], True)
            else:
                okb = np.zeros(0, bool)
                pts, gs = np.zeros((0, 2)), np.zeros(0)
            mid_rows = np.flatnonzero(split_m)
            # each chord's new vertices (the solved ones and its middle's root) ordered along it, all at once
            own = np.concatenate([r_idx[okb], np.arange(rows.size)])
            order = np.lexsort((np.concatenate([tt[okb], np.full(rows.size, 0.5)]), own))
            ps_all = np.concatenate([pts[okb], root[mid_rows]])[order]
            gg_all = np.concatenate([gs[okb], g_root[mid_rows]])[order]
            ends = np.searchsorted(own[order], np.arange(rows.size + 1))
            for q, rr in enumerate(rows):
                inserts[rr] = (ps_all[ends[q]:ends[q + 1]], gg_all[ends[q]:ends[q + 1]])
        inserts.update({r: (np.array([a2, b2]), np.full(2, np.nan)) for r, a2, b2 in zip(dn.tolist(), A2, B2)})
        # write back: per polyline, insert new vertices after their chord's start
        base_row = 0
        cuts = {}
        for n, idx in parts:
            k, p, g, todo = state[n]
            todo = todo.copy()
            chord_rows = np.arange(base_row, base_row + idx.size)
            base_row += idx.size
            new_p, new_g, new_t = [], [], []
            last = 0
            for c, r in zip(idx, chord_rows):
                if r in touch:  # its new vertices, then cut after the first end's
                    ps, at = touch[r]
                    inserts[r] = (ps, np.full(len(ps), np.nan))
                    cuts.setdefault(n, []).append(at)
                elif r in cut:
                    todo[c] = False
                    cuts.setdefault(n, []).append(p[c])
                    continue
                if r in inserts:
                    ps, gg = inserts[r]
                    new_p.append(p[last:c + 1])
                    new_g.append(g[last:c + 1])
                    new_t.append(todo[last:c])
                    new_t.append(np.ones(len(ps) + 1, bool))
                    new_p.append(ps)
                    new_g.append(gg)
                    last = c + 1
                else:
                    todo[c] = False
            if last:
                new_p.append(p[last:])
                new_g.append(g[last:])
                new_t.append(todo[last:])
                p, g, todo = np.concatenate(new_p), np.concatenate(new_g), np.concatenate(new_t)
            state[n] = (k, p, g, todo)
        for n, chords in cuts.items():  # positions of cut chords after this round's insertions
            k, p, g, todo = state[n]
            at = cut_positions(p, chords)
            pieces = np.split(np.arange(len(p)), [i + 1 for i in at])
            first = True
            for piece in pieces:
                if len(piece) < 2:
                    continue
                entry = (k, p[piece], g[piece], todo[piece[:-1]])
                if first:
                    state[n], first = entry, False
                else:
                    state.append(entry)
            if first:
                state[n] = (k, p[:1], g[:1], np.zeros(0, bool))
    out = [(st[0], st[1], st[2]) for st in state if len(st[1]) >= 2]
    corners = set(kinked) | set(measure)
    again = corner_splits(F, out, tol, corners, SPLIT_FRACTION * tol, VERTEX_FRACTION * tol, kept or ())
    if again:  # the polylines that got a vertex beside a corner: densified again, but for their cuts (uncut)
        done = [out[n] if slopes else out[n][:2] for n in range(len(out)) if n not in again]
        return done + densify(F, uncut([out[n] for n in sorted(again)], kept), tol, max_step, measure, kinked,
                              slopes, kept, down=down,
                              others=list(others) + [out[n][:2] for n in range(len(out)) if n not in again])
    return out if slopes else [(k, p) for k, p, _ in out]
