"""Exact vertices where a traced line crosses a known kink of its function: the undercut onsets.

A margin that reads a gear's form circle (interference, the contact ratio, the region) has a slope
break where that gear starts to undercut: on one side of ``x_i = x_i,min`` the form circle is the
closed form's, on the other the generated one's. Its zero set has a corner on that line, and a chord
across the corner keeps its middle on the curve while the corner lies off it (12/30 at tol 1e-9:
interference.2 7.8e-9 from its chord at ``x2 = x2,min``). Where a polyline crosses such a line, the
zero of ``F`` on the line itself (``x_i`` held at the onset, the other shift solved) becomes a vertex:
the chords then end at the corner and each lies on one smooth side of it.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.blocking.brackets import NearestBracket, segment_roots
from gearkit.blocking.edges import toward_edge
from gearkit.blocking.forms import FORM_GAP

__all__ = ["onset_vertices", "undercut_onsets"]

REACH = (0.5, 1.0, 2.0)  #: the zero on the onset line is sought this many chord lengths to each side


def undercut_onsets(field) -> tuple:
    """``((axis, x), ...)``: the shifts where a gear of ``field`` starts to undercut (axis 0: x1, 1: x2),
    where its form circle, and every margin that reads it, has a slope break: the onset of the tool's
    generating setting (a thinned gear is cut with the tool fed in), the field's ``x_min``, and, when
    the window (``field.x_ranges``) reaches below it, where the field's interpolant of the generated
    form circles hands over to its last straight piece
    (:meth:`~gearkit.blocking.field.PairField.form_interpolant`).

    >>> from gearkit.blocking.field import PairField
    >>> from gearkit.pair import PairSpec
    >>> [(a, round(x, 5)) for a, x in undercut_onsets(PairField(PairSpec(12, 30, 1.0)))]
    [(0, 0.29813), (1, -0.75467)]
    """
    t = field.template
    k_e = 2 * t.module * math.tan(math.radians(t.alpha_n_deg))
    out = []
    for i, thin in ((1, t.thinning1), (2, t.thinning2)):
        x_min = field.x_min[i - 1]
        if x_min is None:
            continue
        at = {float(x_min), float(x_min + thin / k_e)}
        if field.x_ranges is not None and field.x_ranges[i - 1][0] < x_min - FORM_GAP:
            fit = field.form_interpolant(i)
            if fit is not None:
                at.add(float(fit[1]))
        for x in sorted(at):
            out.append((i - 1, x))
    return tuple(out)


def onset_vertices(F, lines, onsets, curves, vtol: float) -> list:
    """``lines`` (``(k, points (n, 2), slopes (n,)[, chords to refine (n - 1,)])``) with a vertex added
    on every chord of a curve in ``curves`` that crosses an onset ``(axis, x)`` of ``onsets``: the zero
    of ``F_k`` on the line ``x_axis = x`` nearest the chord's crossing (within two chord lengths; where
    that line runs into the no-pair area, samples from its edge towards the crossing see a zero
    closer to the edge than any even sample), solved to ``vtol``; its slope is the one across the
    curve. A chord that got one is refined again.

    >>> import numpy as np
    >>> F = lambda p, k: p[:, 1] - np.abs(p[:, 0])  # a corner at x1 = 0
    >>> out = onset_vertices(F, [(0, np.array([[-1.0, 1.0], [1.0, 1.0]]), np.ones(2))], [(0, 0.0)], {0}, 1e-12)
    >>> np.round(out[0][1], 12).tolist()
    [[-1.0, 1.0], [0.0, 0.0], [1.0, 1.0]]
    """
    rows = []  # (line, chord, axis, crossing point, fraction along the chord)
    for n, ln in enumerate(lines):
        if ln[0] not in curves or len(ln[1]) < 2:
            continue
        p = ln[1]
        for axis, x in onsets:
            s = p[:, axis] - x
            for i in np.flatnonzero(s[:-1] * s[1:] < 0):
                t = s[i] / (s[i] - s[i + 1])
                rows.append((n, int(i), axis, p[i] + t * (p[i + 1] - p[i]), float(t)))
    if not rows:
        return list(lines)
    P = np.array([r[3] for r in rows])
    which = np.array([lines[r[0]][0] for r in rows])
    A = np.array([lines[r[0]][1][r[1]] for r in rows])
    B = np.array([lines[r[0]][1][r[1] + 1] for r in rows])
    L = np.hypot(*(B - A).T)
    along = np.zeros((len(rows), 2))  # the onset line's direction: the other shift
    along[np.arange(len(rows)), 1 - np.array([r[2] for r in rows])] = 1.0
    f0 = F(P, which)
    best = NearestBracket(P, f0)
    for reach in REACH:
        for sgn in (1.0, -1.0):
            i = np.flatnonzero(~best.have)
            end = P[i] + sgn * reach * L[i, None] * along[i]
            fe = F(end, which[i])
            out = np.flatnonzero(np.isnan(fe))
            if out.size:  # into the no-pair area: the sign change nearest before its edge (to round-off)
                lo, flo, hi, fhi = toward_edge(F, P[i[out]], f0[i[out]], end[out], which[i[out]])
                best.consider(i[out], lo, flo, hi, fhi)
            best.consider(i, P[i], f0[i], end, fe)
        if best.have.all():
            break
    found = np.flatnonzero(best.have)
    if not found.size:
        return list(lines)
    root = segment_roots(F, best.lo[found], best.end[found], best.flo[found], best.fe[found], vtol, which[found])
    # the slope across the curve: the one along the onset line over the sine of the angle between them
    d = (B - A)[found] / np.maximum(L[found], 1e-300)[:, None]
    sine = np.abs(np.einsum("ij,ij->i", along[found], np.column_stack([-d[:, 1], d[:, 0]])))
    with np.errstate(invalid="ignore", divide="ignore"):
        g = np.abs(best.fe[found] - best.flo[found]) / np.hypot(*(best.end[found] - best.lo[found]).T) / sine
    inserts = {}
    for r, q, gq in zip(found, root, g):
        n, i = rows[r][:2]
        inserts.setdefault(n, []).append((i, rows[r][4], q, gq))
    out = list(lines)
    for n, at in inserts.items():
        ln = out[n]
        p, s = ln[1], ln[2]
        todo = ln[3] if len(ln) > 3 else None
        for i, _, q, gq in sorted(at, key=lambda a: (-a[0], -a[1])):  # from the end: earlier ones stay valid
            p = np.insert(p, i + 1, q, axis=0)
            s = np.insert(s, i + 1, gq)
            if todo is not None:
                todo = np.insert(todo, i + 1, True)
                todo[i] = True
        out[n] = (ln[0], p, s) if todo is None else (ln[0], p, s, todo)
    return out
