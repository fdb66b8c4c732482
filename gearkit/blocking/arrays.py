"""The pair formulas as arrays: every margin of a blocking contour at many shift pairs at once.

:func:`~gearkit.pair.pair_geometry` derives one pair per call (about 100 µs of Python); a contour
asks for tens of thousands of points. :func:`margins` evaluates the same closed forms (tight mesh,
tips by the template's ``tip_rule``) with numpy over arrays ``x1``, ``x2`` in one pass, and returns
the margins :class:`~gearkit.blocking.field.PairField` defines (the same names, units and signs).
Where no pair exists (the scalar formulas raise a :class:`~gearkit.errors.SpecError`) the margins
are NaN. The scalar path stays the reference: the tests hold the two equal at random points. The
pair geometry the margins read is :class:`~gearkit.blocking.pair_arrays.PairArrays`; here are the
margins by name and their evaluators (:func:`evaluator`: one evaluation for many functions).

The form circles are those the check reads off the generated gears: the closed form where a gear
is not undercut, and for an undercut gear the field's interpolant of the generated ones
(:meth:`~gearkit.blocking.field.PairField.form_interpolant`).

>>> import numpy as np
>>> from gearkit.blocking.field import PairField
>>> from gearkit.pair import PairSpec
>>> f = PairField(PairSpec(20, 40, 1.0))
>>> m = margins(f, np.array([0.0, 0.5]), np.array([0.0, 0.2]), ["contact_ratio=1"])
>>> np.round(m["contact_ratio=1"], 4)
array([0.6352, 0.4277])
"""
from __future__ import annotations

import numpy as np

from gearkit.blocking.gear_arrays import PairScalars
from gearkit.blocking.pair_arrays import PairArrays
from gearkit.blocking.ring_arrays import exit_jamming, plunge_gap, tip_clearance_margin

__all__ = ["margins", "evaluator", "sliding_ends", "SLIDING_LEGS"]

#: the factors of the sliding margin (:meth:`~gearkit.blocking.pair_arrays.PairArrays.sliding_factors`)
SLIDING_LEGS = ("sliding.same", "sliding.opposite")
_AT_POINTS = ("tip_interference", "trimming.plunge")  #: margins swept at the points asked for alone (costly)


class _Pair(PairArrays):
    """The pair geometry at arrays of shifts (:class:`~gearkit.blocking.pair_arrays.PairArrays`) and its
    margins by name, each worked out once."""

    def __init__(self, field, x1, x2, k=None):
        super().__init__(field, x1, x2, k)
        self._margins = {}

    def margin(self, name, sel=None):
        """Margin ``name`` (see :func:`margins`) at the points ``sel`` (indices; None: all). Each is worked
        out once at all the points and read at ``sel`` (an evaluation of several functions reads the hard
        margins for the region and for their own lines), but for the sweeps read at the points alone."""
        if name.startswith("undercut."):
            i = int(name[-1])
            v = (self.x1, self.x2)[i - 1] - self.field.x_min[i - 1]
            return v if sel is None else v[sel]
        if name in _AT_POINTS:
            return np.where(self.bad if sel is None else self.bad[sel], self.k.nan, self._value(name, sel))
        m = self._margins.get(name)
        if m is None:
            m = self._margins[name] = np.where(self.bad, self.k.nan, self._value(name, None))
        return m if sel is None else m[sel]

    def smallest(self, names, sel):
        """The smallest of the margins ``names`` at the points ``sel``: NaN where no pair exists (a new array)."""
        if any(n in _AT_POINTS for n in names):
            m = np.minimum.reduce([self.margin(n, sel) for n in names])
        else:  # (each margin at all the points: see margin)
            m = np.minimum.reduce([self.margin(n) for n in names])
            m = m if sel is None else m[sel]
        return np.where(self.bad if sel is None else self.bad[sel], self.k.nan, m)

    def _value(self, name, sel):
        """Margin ``name`` at the points ``sel`` (None: all), read where a pair exists."""
        field = self.field
        mn = field.module
        tol = 1e-9 * mn
        base, _, level = name.partition("=")
        at = (lambda a: a) if sel is None else (lambda a: np.asarray(a)[sel])
        if base.startswith("undercut."):
            i = int(base[-1])
            return at((self.x1, self.x2)[i - 1]) - field.x_min[i - 1]
        if base == "interference.1":
            return (at(self.u_a) - at(self.rhoF1) + tol) / mn
        if base == "interference.2":
            return (at(self.u_hi) - at(self.u_e) + tol) / mn
        if base in ("pointing.1", "pointing.2"):
            s = at(self.tip_thickness(int(base[-1])))
            return np.where(s == 0, -5e-324, s) / mn
        if base in ("tip_clearance.1", "tip_clearance.2"):
            return at(self.clearance(int(base[-1]))) / mn
        if name == "contact_ratio=1":
            return at(self.eps) - 1.0
        if base == "contact_ratio":
            return at(self.eps) - float(level)
        if base == "contact_ratio_tip":
            return at(self.eps_nominal) - float(level)
        if base.startswith("tip_thickness."):
            return at(self.tip_thickness(int(base[-1]))) / mn - float(level)
        if base == "sliding":
            return at(self.sliding())
        if base in SLIDING_LEGS:
            return at(self.sliding_factors()[SLIDING_LEGS.index(base)])
        if base == "exit_jamming":
            return at(exit_jamming(self))
        if base == "trimming.plunge":
            gap = plunge_gap(self, sel) / mn
            return np.where(gap > 0, gap, np.minimum(gap, -5e-324))
        if base == "tip_interference":
            return tip_clearance_margin(self, sel)
        if base == "trimming.nu":
            return (at(self.ra2) - at(self.nu)) / mn
        if base == "center_distance":
            return (at(self.a_w) - float(level)) / mn
        if base == "backlash":
            return (at(self.backlash) + tol) / mn
        raise KeyError(name)


def _points(x1, x2):
    x1 = np.atleast_1d(np.asarray(x1, dtype=float))
    x2 = np.atleast_1d(np.asarray(x2, dtype=float))
    x1, x2 = np.broadcast_arrays(x1, x2)
    return x1.ravel().copy(), x2.ravel().copy()


def margins(field, x1, x2, names) -> dict:
    """Margins ``names`` of ``field`` at the shift pairs ``(x1[i], x2[i])``: name -> (n,) float64, NaN
    where no pair exists (see :meth:`~gearkit.blocking.field.PairField.margin` for names and units)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        g = _Pair(field, *_points(x1, x2))
        return {name: g.margin(name) for name in dict.fromkeys(names)}


def sliding_ends(field, x1, x2):
    """(|zeta1| at the start, |zeta2| at the end of the real path, eps_alpha) at the points, arrays."""
    with np.errstate(invalid="ignore", divide="ignore"):
        g = _Pair(field, *_points(x1, x2))
        z1, z2 = g.sliding_ends()
    bad = g.bad
    return np.where(bad, np.nan, z1), np.where(bad, np.nan, z2), np.where(bad, np.nan, g.eps)


def evaluator(field, names, window):
    """``F(points (n, 2), which (n,) int) -> (n,)``: margin ``names[which[i]]`` at ``points[i]``, all
    from one evaluation of the pair formulas. The name ``"region"`` is the smallest hard margin
    and, with a ``window``, the distances to its edges (-1 where no pair exists:
    the function of :mod:`gearkit.blocking.region`)."""
    hard = list(field.hard)
    k = PairScalars(field)
    frame = None if window is None else [np.asarray(float(v)) for v in window]  # (0-d: see PairScalars)
    sweep = "tip_interference" in hard  # the costly one: see "region" below
    cheap = [n for n in hard if n != "tip_interference"]  # not the backlash: zero at the tight mesh by construction (the check
    # forgives 1e-9 m_n of round-off); a plateau at 1e-9 would hide the region's real edges

    def one(g, p, name, sel):
        """Function ``name`` at the points ``sel`` (indices; None: all of them)."""
        if name != "region":
            return g.margin(name, sel)
        m = g.smallest(cheap, sel)
        if sweep:  # the tip sweep only where the others pass (elsewhere the region fails anyway)
            at = np.flatnonzero(m >= 0)
            m[at] = np.minimum(m[at], g.margin("tip_interference", at if sel is None else sel[at]))
        if window is None:
            return m
        q = p if sel is None else p[sel]
        w = np.minimum(np.minimum(q[:, 0] - frame[0], frame[1] - q[:, 0]),
                       np.minimum(q[:, 1] - frame[2], frame[3] - q[:, 1]))
        v = np.minimum(w, m)
        return np.where(np.isnan(v), np.minimum(w, k.minus_one), v)

    def values(p, which):
        """(the pair geometry, the functions ``names[which[i]]`` at ``p[i]``)."""
        p = np.asarray(p, dtype=float).reshape(-1, 2)
        which = np.asarray(which)
        with np.errstate(invalid="ignore", divide="ignore"):
            g = _Pair(field, p[:, 0].copy(), p[:, 1].copy(), k)
            if len(p) and not np.count_nonzero(which != which[0]):  # one function (most calls): in place
                return g, np.asarray(one(g, p, names[which[0]], None), dtype=float)
            out = np.empty(len(p))
            order = np.argsort(which, kind="stable")  # each function's points, in their order
            ws = which[order]
            ends = (ws[1:] != ws[:-1]).nonzero()[0].tolist() + [len(p) - 1]
            for lo, hi in zip([-1] + ends, ends if len(p) else []):
                sel = order[lo + 1:hi + 1]
                out[sel] = one(g, p, names[which[sel[0]]], sel)
        return g, out

    def F(p, which):
        return values(p, which)[1]

    def slack(p, which):
        """The conditions for a pair, ``(n, 4)``: all positive exactly where ``F(p, which)`` is finite;
        where it is not, each smooth and zero where its condition starts to fail (the parts of the edge
        of the no-pair area), NaN where it has no measure (a function undefined for a reason of its
        own, no tooth): what :func:`~gearkit.blocking.edges.edge_point` solves for the edge."""
        g, v = values(p, which)
        fin = np.isfinite(v)[:, None]
        s = g.conditions()
        ok = (s > 0).all(axis=1)[:, None]
        return np.where(fin, np.where(ok, s, k.inf), np.where(ok, k.nan, s))

    def many(p, which):
        """Functions ``names[w]`` for every ``w`` in ``which`` at all the points ``p``: ``(len(which), n)``,
        from one evaluation of the pair formulas."""
        p = np.asarray(p, dtype=float).reshape(-1, 2)
        with np.errstate(invalid="ignore", divide="ignore"):
            g = _Pair(field, p[:, 0].copy(), p[:, 1].copy(), k)
            return np.array([one(g, p, names[w], None) for w in which], dtype=float).reshape(len(which), len(p))
    F.many, F.slack = many, slack
    return F
