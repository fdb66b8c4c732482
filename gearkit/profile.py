"""Generated profiles: what every family returns, read off its exact half tooth.

:class:`ToothProfile` is a generated gear (one exact half tooth from
:func:`gearkit.boundary.trim_half_tooth`, repeated ``teeth`` times); its key values (tip,
root and form diameters, thicknesses, undercut, trimming, pointing) are read off the
generated geometry, and ``outline(tol)`` samples it to a chord tolerance.
"""
from __future__ import annotations


import numpy as np

from gearkit.accuracy import check_tol
from gearkit.boundary import CircleArc, HalfTooth, TipLine
from gearkit.pieces import crossings
from gearkit.curves import polar_from_y


class HalfToothProfile:
    """What every generated profile shares: its exact half tooth, sampled on request.

    Subclasses set ``half`` (a :class:`HalfTooth`), ``module`` and ``_cache`` (a dict).
    """

    def _end(self, which):
        """The tip (the first piece's start) or the space centre (the last piece's end), ``(2,)`` mm,
        read-only: evaluated once (the key values and the gauges read it many times)."""
        key = ("end", which)
        if key not in self._cache:
            piece = self.half.pieces[0] if which == "tip" else self.half.pieces[-1]
            point = piece(np.array([0.0 if which == "tip" else 1.0]))[0]
            point.flags.writeable = False
            self._cache[key] = point
        return self._cache[key]

    @property
    def pointed(self) -> bool:
        return self.half.pointed

    def half_points(self, tol: float):
        """Half tooth from tip to space centre sampled to ``tol``; returns (points, achieved).

        ``tol`` (mm) must lie in ``[1e-9 m, m]`` (:func:`gearkit.accuracy.check_tol`).
        """
        key = ("half", check_tol(tol, self.module))
        if key not in self._cache:
            self._cache[key] = self.half.sample(tol)
        return self._cache[key]

    def achieved(self, tol: float) -> float:
        """Largest chord deviation (mm) of the half tooth sampled at ``tol``."""
        return self.half_points(tol)[1]


class ToothProfile(HalfToothProfile):
    """A generated gear: one exact half tooth, repeated ``teeth`` times.

    Lengths in mm, transverse section. Everything is read off the generated geometry.
    ``outline(tol)`` is the closed outline of all teeth as an ``(n, 2)`` array,
    counter-clockwise, tooth 0 centred on +y.
    """

    def __init__(self, half: HalfTooth, teeth: int, internal: bool, module: float, *,
                 family: str, spec=None, reference_diameter: float | None = None,
                 base_diameter: float | None = None, blank_tip_diameter: float | None = None):
        self.half = half
        self.teeth = int(teeth)
        self.internal = bool(internal)
        self.module = float(module)
        self.family = family
        self.spec = spec
        self.reference_diameter = reference_diameter
        self.base_diameter = base_diameter
        self.blank_tip_diameter = blank_tip_diameter
        self._cache = {}

    # -- key values read off the geometry ---------------------------------------------
    @property
    def tip_diameter(self) -> float:
        """Diameter of the generated tip (the blank's tip circle, or the point of a pointed tooth)."""
        return 2.0 * float(np.hypot(*self._end("tip")))

    @property
    def root_diameter(self) -> float:
        """Diameter at the centre of the tooth space (the root circle of a generated gear)."""
        return 2.0 * float(np.hypot(*self._end("root")))

    @property
    def form_diameter(self) -> float:
        """d_Nf: diameter where the flank ends and the fillet (or undercut) begins."""
        pieces = self.half.pieces
        k = 0
        while k < len(pieces) and pieces[k].label != "flank":
            k += 1
        while k + 1 < len(pieces) and pieces[k + 1].label == "flank":
            k += 1
        k = min(k, len(pieces) - 1)
        return 2.0 * float(np.hypot(*pieces[k](np.array([1.0]))[0]))

    def _flank_joins(self):
        labels = [p.label for p in self.half.pieces]
        return [(labels[i], labels[i + 1], j) for i, j in enumerate(self.half.joins)]

    @property
    def undercut(self) -> bool:
        """True when the fillet cuts into the flank (a loop of the envelope was removed there)."""
        return any(j == "trim" and a == "flank" and b != "flank" for a, b, j in self._flank_joins())

    @property
    def trimmed(self) -> bool:
        """True when the cutter removed part of the flank on the tip side (trimming): the tooth
        between the tip circle and the flank was formed by a non-flank part of the cutter, or a
        loop of the envelope was cut away there."""
        pieces = self.half.pieces
        k_f = next((i for i, p in enumerate(pieces) if p.label == "flank"), len(pieces))
        cut_by_other = any(not isinstance(p.curve, (CircleArc, TipLine)) for p in pieces[:k_f])
        return cut_by_other or any(j == "trim" for j in self.half.joins[:k_f])

    def thickness_at(self, radius: float) -> float | None:
        """Arc tooth thickness (mm) on the circle of ``radius``; 0 above a pointed tip.

        ``None`` when the circle does not reach the tooth (it lies outside the tooth's radial
        range, e.g. the reference circle of a gear whose shift puts it below the root): a value to
        report, not an error.

        Examples
        --------
        >>> from gearkit import GearSpec, tooth_profile
        >>> prof = tooth_profile(GearSpec(40, 1.0, shift=1.3))
        >>> prof.thickness_at(20.0) is None, round(prof.thickness_at(21.0), 6) > 0
        (True, True)
        """
        r = float(radius)
        rs = [float(np.hypot(*self._end("tip"))), float(np.hypot(*self._end("root")))]
        if not min(rs) - 1e-12 * max(rs) <= r <= max(rs) + 1e-12 * max(rs):
            return None
        hits = crossings(self.half.pieces, lambda p: polar_from_y(p)[0], r)
        if not hits:
            end = self._end("tip") if abs(np.hypot(*self._end("tip")) - r) < abs(np.hypot(*self._end("root")) - r) \
                else self._end("root")
            return max(0.0, 2.0 * r * float(polar_from_y(end[None])[1][0]))
        k, w = hits[0]
        psi = polar_from_y(self.half.pieces[k].curve(np.array([w])))[1][0]
        return max(0.0, 2.0 * r * float(psi))

    @property
    def tip_thickness(self) -> float:
        """s_a: arc thickness on the tip circle (0 for a pointed tooth)."""
        if self.pointed:
            return 0.0
        tip = self._end("tip")
        first = self.half.pieces[0]
        end = first(np.array([1.0]))[0] if first.label == "tip" else tip
        # a tip pointed to round-off (psi ~ -1e-16) is pointed: never a negative thickness
        return max(0.0, 2.0 * float(np.hypot(*end)) * float(polar_from_y(end[None])[1][0]))

    # -- sampled geometry ---------------------------------------------------------------
    def tooth_points(self, tol: float):
        """One whole tooth, counter-clockwise from the right space centre to the left one."""
        half, _ = self.half_points(tol)
        mirror = half * np.array([-1.0, 1.0])
        return np.concatenate([half[::-1], mirror[1:]])

    def outline(self, tol: float | None = None):
        """Closed outline of all teeth, ``(n, 2)`` float64, counter-clockwise (no repeated end point)."""
        tol = 1e-3 * self.module if tol is None else tol
        return turn_copies(self.tooth_points(tol)[:-1], self.teeth)


#: points a block of :func:`turn_copies` writes at once (its temporaries stay in cache)
_BLOCK = 8192
#: points of a tooth, and of the outline, from which :func:`turn_copies` turns one copy a call (measured: z = 40
#: at tol 1e-6 m, 1342 points a tooth, about 0.4 -> 0.25 ms; z = 12, 22 k points in all, stays in blocks)
_LONG, _LARGE = 512, 32768


def turn_copies(tooth, teeth: int):
    """``teeth`` copies of ``tooth`` ``(n, 2)``, copy ``k`` turned by ``2 pi k / teeth`` about the origin,
    ``(teeth n, 2)`` float64.

    Copy ``k`` is ``cos a_k (x, y) + sin a_k (-y, x)``: the same products and sums as the rotation
    ``(c x - s y, s x + c y)``, written straight into the result a copy at a time (a long tooth) or a block
    of copies at a time (no whole-outline temporaries).

    >>> ring = turn_copies(np.array([[0.0, 1.0], [0.5, 2.0]]), 3)
    >>> c, s = np.cos(2 * np.pi / 3), np.sin(2 * np.pi / 3)
    >>> ring.shape, bool(np.allclose(ring[2:4], [[-s, c], [0.5 * c - 2 * s, 0.5 * s + 2 * c]], rtol=0, atol=1e-15))
    ((6, 2), True)
    """
    tooth = np.ascontiguousarray(tooth, dtype=float)
    ang = 2.0 * np.pi * np.arange(teeth) / teeth
    c, s = np.cos(ang)[:, None, None], np.sin(ang)[:, None, None]
    normal = np.empty_like(tooth)  # (-y, x)
    np.negative(tooth[:, 1], out=normal[:, 0])
    normal[:, 1] = tooth[:, 0]
    n = len(tooth)
    out = np.empty((teeth, n, 2))
    if n >= _LONG and teeth * n >= _LARGE:  # each copy by its own two numbers (a block's factors, broadcast
        # over its points, cost more than the calls on a large outline)
        part = np.empty((n, 2))
        for k, (ck, sk) in enumerate(zip(np.cos(ang).tolist(), np.sin(ang).tolist())):
            np.multiply(ck, tooth, out=out[k])
            np.multiply(sk, normal, out=part)
            out[k] += part
        return out.reshape(-1, 2)
    step = max(1, _BLOCK // max(n, 1))
    part = np.empty((min(step, teeth), n, 2))
    for k in range(0, teeth, step):
        e = min(teeth, k + step)
        o, t = out[k:e], part[:e - k]
        np.multiply(c[k:e], tooth, out=o)
        np.multiply(s[k:e], normal, out=t)
        o += t
    return out.reshape(-1, 2)

