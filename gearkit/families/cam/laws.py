"""Motion laws of a cam follower: displacement s(phi) and its derivatives, segment by segment.

A follower's motion over one cam turn is a :class:`MotionProgram`: a sequence of
:class:`MotionSegment` (``rise``, ``dwell``, ``return``) whose spans add up to at most 360
degrees (the rest is a closing dwell). Each rise or return follows a normalised law
``f(x)``, ``x`` in [0, 1], ``f(0) = 0``, ``f(1) = 1``:

``constant_velocity``  f = x (infinite acceleration at both ends: flagged by the checks)
``harmonic``           f = (1 - cos pi x)/2
``cycloidal``          f = x - sin(2 pi x)/(2 pi)
``polynomial_345``     f = 10x^3 - 15x^4 + 6x^5
``polynomial_4567``    f = 35x^4 - 84x^5 + 70x^6 - 20x^7
``modified_trapezoid`` acceleration: sine ramps over the first and last eighth, constant between
``modified_sine``      acceleration: a short sine quarter, then a long sine half
``table``              a quintic spline through user points (x, f) with zero velocity and
                       acceleration at both ends

Velocity, acceleration and jerk are exact for every closed-form law (the two sine-acceleration
laws are integrated piecewise in closed form). Derivatives are with respect to the cam angle
(mm/rad, mm/rad^2, mm/rad^3): multiply by omega, omega^2, omega^3 for time.

Examples
--------
>>> prog = MotionProgram.rise_dwell_return(20.0, 60.0, 60.0, 60.0, law="cycloidal")
>>> s, v, a, j = prog.evaluate([0.0, math.radians(30.0), math.radians(90.0)])
>>> [round(float(x), 9) for x in s]
[0.0, 10.0, 20.0]
>>> round(float(v[1]), 6)  # peak velocity 2 H / beta
38.197186
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from gearkit.errors import SpecError, check_fields, is_real, require

__all__ = ["LAWS", "MotionSegment", "MotionProgram", "jerk_bound", "law_shape"]

#: names of the rise/return laws
LAWS = ("constant_velocity", "harmonic", "cycloidal", "polynomial_345", "polynomial_4567",
        "modified_trapezoid", "modified_sine", "table")

_POLY = {"polynomial_345": (0, 0, 0, 10, -15, 6), "polynomial_4567": (0, 0, 0, 0, 35, -84, 70, -20)}

# acceleration shapes of the sine-acceleration laws: pieces (x0, x1, c, amp, omega, phase) meaning
# g(x) = c + amp sin(omega x + phase) on [x0, x1]
_Q = 4.0 * math.pi
_SINE_PIECES = {
    "modified_trapezoid": ((0.0, 0.125, 0.0, 1.0, _Q, 0.0), (0.125, 0.375, 1.0, 0.0, 0.0, 0.0),
                           (0.375, 0.625, 0.0, 1.0, _Q, -_Q * 0.375 + math.pi / 2),
                           (0.625, 0.875, -1.0, 0.0, 0.0, 0.0), (0.875, 1.0, 0.0, 1.0, _Q, -_Q)),
    "modified_sine": ((0.0, 0.125, 0.0, 1.0, _Q, 0.0),
                      (0.125, 0.875, 0.0, 1.0, _Q / 3.0, -_Q / 3.0 * 0.125 + math.pi / 2),
                      (0.875, 1.0, 0.0, 1.0, _Q, -_Q)),
}


def _sine_law(pieces):
    """Closed-form integration of a piecewise ``c + amp sin(omega x + phase)`` acceleration shape:
    returns ``(pieces, v0s, s0s, scale)`` with velocity and displacement continuous and
    ``f(1) = 1``."""
    v0s, s0s = [], []
    v, s = 0.0, 0.0
    for x0, x1, c, amp, om, ph in pieces:
        v0s.append(v)
        s0s.append(s)
        h = x1 - x0
        if om:  # velocity and displacement at x1 from the closed-form antiderivatives
            dv = c * h - amp / om * (math.cos(om * x1 + ph) - math.cos(om * x0 + ph))
            ds = v * h + c * h * h / 2 + amp / om * math.cos(om * x0 + ph) * h \
                - amp / om ** 2 * (math.sin(om * x1 + ph) - math.sin(om * x0 + ph))
        else:
            dv, ds = c * h, v * h + c * h * h / 2
        v, s = v + dv, s + ds
    return v0s, s0s, 1.0 / s


_SINE_CONST = {name: _sine_law(p) for name, p in _SINE_PIECES.items()}


def _sine_eval(name, x):
    pieces = _SINE_PIECES[name]
    v0s, s0s, k = _SINE_CONST[name]
    f = np.zeros_like(x)
    d = [np.zeros_like(x) for _ in range(3)]
    for i, (x0, x1, c, amp, om, ph) in enumerate(pieces):
        m = (x >= x0) & (x <= x1) if i == len(pieces) - 1 else (x >= x0) & (x < x1)
        t = x[m]
        h = t - x0
        if om:
            vel = v0s[i] + c * h - amp / om * (np.cos(om * t + ph) - math.cos(om * x0 + ph))
            dis = s0s[i] + v0s[i] * h + c * h * h / 2 + amp / om * math.cos(om * x0 + ph) * h \
                - amp / om ** 2 * (np.sin(om * t + ph) - math.sin(om * x0 + ph))
            acc = c + amp * np.sin(om * t + ph)
            jerk = amp * om * np.cos(om * t + ph)
        else:
            vel, dis = v0s[i] + c * h, s0s[i] + v0s[i] * h + c * h * h / 2
            acc, jerk = np.full_like(t, c), np.zeros_like(t)
        f[m], d[0][m], d[1][m], d[2][m] = k * dis, k * vel, k * acc, k * jerk
    return f, d[0], d[1], d[2]


def law_shape(law: str, x, table=None):
    """Normalised law and its derivatives at ``x`` in [0, 1]: ``(f, f', f'', f''')``.

    Examples
    --------
    >>> f, v, a, j = law_shape("modified_sine", np.array([0.0, 0.0625, 0.125, 1.0]))
    >>> [round(float(y), 12) for y in (f[0], f[-1])], round(float(a[2]), 3)  # peak acceleration 5.528 H/beta^2
    ([0.0, 1.0], 5.528)
    """
    x = np.asarray(x, dtype=float)
    if law == "constant_velocity":
        return x.copy(), np.ones_like(x), np.zeros_like(x), np.zeros_like(x)
    if law == "harmonic":
        p = math.pi
        return ((1 - np.cos(p * x)) / 2, p / 2 * np.sin(p * x), p * p / 2 * np.cos(p * x),
                -p ** 3 / 2 * np.sin(p * x))
    if law == "cycloidal":
        w = 2 * math.pi
        return (x - np.sin(w * x) / w, 1 - np.cos(w * x), w * np.sin(w * x), w * w * np.cos(w * x))
    if law in _POLY:
        c = np.polynomial.Polynomial(_POLY[law])
        return c(x), c.deriv(1)(x), c.deriv(2)(x), c.deriv(3)(x)
    if law in _SINE_PIECES:
        return _sine_eval(law, x)
    if law == "table":
        spl = _table_spline(table)
        return spl(x), spl(x, 1), spl(x, 2), spl(x, 3)
    raise SpecError("law", f"{law!r} is not one of {', '.join(LAWS)}")


@functools.lru_cache(maxsize=64)
def jerk_bound(law: str, table=None) -> float:
    """An upper bound of the normalised law's jerk ``|f3(x)|`` on [0, 1]: its largest value, at the ends
    or where its derivative vanishes (a polynomial's or a spline piece's roots, found exactly), or the
    amplitude of each sine piece.

    Examples
    --------
    >>> jerk_bound("cycloidal") == 4 * math.pi ** 2, round(jerk_bound("polynomial_345"), 9)
    (True, 60.0)
    """
    if law == "constant_velocity":
        return 0.0
    if law == "harmonic":
        return math.pi ** 3 / 2
    if law == "cycloidal":
        return 4 * math.pi ** 2
    if law in _SINE_PIECES:
        return _SINE_CONST[law][2] * max(abs(amp * om) for _, _, _, amp, om, _ in _SINE_PIECES[law])
    if law in _POLY:
        jerk = np.polynomial.Polynomial(_POLY[law]).deriv(3)
        roots = jerk.deriv().roots()
        x = np.concatenate([[0.0, 1.0], roots[(roots.imag == 0) & (roots.real > 0) & (roots.real < 1)].real])
        return float(np.abs(jerk(x)).max()) * (1 + 1e-12)
    if law == "table":
        from scipy.interpolate import PPoly

        jerk = PPoly.from_spline(_table_spline(table).derivative(3))  # a quadratic on each knot span
        x = np.concatenate([jerk.x, jerk.derivative().roots(extrapolate=False)])
        x = x[np.isfinite(x) & (x >= 0.0) & (x <= 1.0)]
        return float(np.abs(jerk(x)).max()) * (1 + 1e-12)
    raise SpecError("law", f"{law!r} is not one of {', '.join(LAWS)}")


def _table_spline(table):
    from scipy.interpolate import make_interp_spline

    t = np.asarray(table, dtype=float)
    ends = [(1, 0.0), (2, 0.0)]
    return make_interp_spline(t[:, 0], t[:, 1], k=5, bc_type=(ends, ends))


@dataclass(frozen=True)
class MotionSegment:
    """One phase of the follower's motion.

    Parameters
    ----------
    kind : {"rise", "dwell", "return"}
    span_deg : float, degrees, in (0, 360]
        Cam angle the phase takes.
    lift : float, mm
        Stroke of a rise or return (> 0; 0 for a dwell). For a rocker it is the arc the roller
        centre travels (the swing angle is ``lift / arm_length``).
    law : str
        One of :data:`LAWS` (ignored for a dwell).
    table : tuple of (x, f) pairs or None
        The points of a ``table`` law: x strictly increasing from 0 to 1, f from 0 to 1.
    """

    kind: str
    span_deg: float
    lift: float = 0.0
    law: str = "cycloidal"
    table: tuple | None = None

    def __post_init__(self):
        check_fields(self)
        require(self.kind in ("rise", "dwell", "return"), "kind", f"{self.kind!r} is not rise, dwell or return")
        require(is_real(self.span_deg) and 0.0 < self.span_deg <= 360.0, f"{self.kind}_deg",
                f"{self.span_deg!r} must be in (0, 360] degrees")
        require(self.table is None or (self.law == "table" and self.kind != "dwell"), "table",
                f"a {self.law} law or a dwell takes no table (law='table' does)")
        if self.kind == "dwell":
            require(self.lift == 0.0, "lift", "a dwell has no lift")
            return
        require(is_real(self.lift) and self.lift > 0.0, "rise" if self.kind == "rise" else "return",
                f"the lift {self.lift!r} must be a positive length in mm")
        require(self.law in LAWS, "law", f"{self.law!r} is not one of {', '.join(LAWS)}")
        if self.law == "table":
            t = self.table
            ok = t is not None and len(t) >= 3 and all(len(p) == 2 and all(is_real(v) for v in p) for p in t)
            require(ok, "table", "a table law needs at least 3 (x, f) pairs of finite numbers")
            arr = np.asarray(t, dtype=float)
            require(arr[0, 0] == 0.0 and arr[-1, 0] == 1.0 and bool(np.all(np.diff(arr[:, 0]) > 0)), "table",
                    "x must increase strictly from 0 to 1")
            require(arr[0, 1] == 0.0 and arr[-1, 1] == 1.0, "table", "f must run from 0 at x = 0 to 1 at x = 1")
            object.__setattr__(self, "table", tuple((float(a), float(b)) for a, b in arr))

    @property
    def span(self) -> float:
        """Span in radians."""
        return math.radians(self.span_deg)


@dataclass(frozen=True)
class MotionProgram:
    """The follower's displacement over one cam turn: segments from phi = 0, closed by a dwell.

    The rises and returns must add up to zero (the follower comes back), and the spans must fit
    in 360 degrees; what is left is a dwell at the start position.
    """

    segments: tuple

    def __post_init__(self):
        require(isinstance(self.segments, (tuple, list)), "motion", f"{self.segments!r} must be a list of MotionSegment")
        segs = tuple(self.segments)
        object.__setattr__(self, "segments", segs)
        require(len(segs) > 0 and all(isinstance(g, MotionSegment) for g in segs), "motion",
                "give at least one MotionSegment")
        total = sum(g.span_deg for g in segs)
        require(total <= 360.0 + 1e-9, "motion",
                f"the phases take {total:g} degrees: they must fit in 360 degrees "
                f"({', '.join(f'{g.kind} {g.span_deg:g}' for g in segs)})")
        level = 0.0
        for g in segs:
            level += g.lift if g.kind == "rise" else -g.lift if g.kind == "return" else 0.0
            require(level >= -1e-9 * max(1.0, g.lift), "return",
                    "a return takes the follower below its start position")
        require(abs(level) <= 1e-9 * max(1.0, self.stroke), "return",
                f"the follower does not come back: rises minus returns = {level:g} mm")
        require(self.stroke > 0.0, "rise", "the motion needs a rise")

    @classmethod
    def rise_dwell_return(cls, lift: float, rise_deg: float, dwell_deg: float, return_deg: float,
                          law: str = "cycloidal", return_law: str | None = None) -> "MotionProgram":
        """Rise, far dwell, return, and the near dwell that closes the turn."""
        require(is_real(rise_deg) and is_real(dwell_deg) and is_real(return_deg), "rise_deg",
                "the phase angles must be finite numbers of degrees")
        require(dwell_deg >= 0.0, "dwell_deg", f"{dwell_deg!r} must be >= 0 degrees")
        total = rise_deg + dwell_deg + return_deg
        require(total <= 360.0 + 1e-9, "rise_deg",
                f"rise {rise_deg:g} + dwell {dwell_deg:g} + return {return_deg:g} = {total:g} degrees does not fit "
                "in 360 degrees")
        segs = [MotionSegment("rise", rise_deg, lift, law)]
        if dwell_deg > 0:
            segs.append(MotionSegment("dwell", dwell_deg))
        segs.append(MotionSegment("return", return_deg, lift, return_law or law))
        return cls(tuple(segs))

    @property
    def stroke(self) -> float:
        """Largest displacement reached, mm."""
        level, top = 0.0, 0.0
        for g in self.segments:
            level += g.lift if g.kind == "rise" else -g.lift if g.kind == "return" else 0.0
            top = max(top, level)
        return top

    def phases(self):
        """``(kind, phi0, phi1, s0, law_segment)`` for every segment and the closing dwell, rad and mm."""
        out, phi, level = [], 0.0, 0.0
        for g in self.segments:
            out.append((g.kind, phi, phi + g.span, level, g))
            phi += g.span
            level += g.lift if g.kind == "rise" else -g.lift if g.kind == "return" else 0.0
        if phi < 2 * math.pi - 1e-12:
            out.append(("dwell", phi, 2 * math.pi, level, None))
        return out

    def evaluate(self, phi):
        """Displacement and its cam-angle derivatives at ``phi`` (rad, any real; taken mod 2 pi).

        Returns
        -------
        s, v, a, j : (n,) float64, mm, mm/rad, mm/rad^2, mm/rad^3
        """
        phi = np.mod(np.atleast_1d(np.asarray(phi, dtype=float)), 2 * math.pi)
        out = [np.zeros_like(phi) for _ in range(4)]
        phases = self.phases()
        for i, (kind, p0, p1, s0, g) in enumerate(phases):
            m = (phi >= p0) & ((phi < p1) if i < len(phases) - 1 else (phi <= p1 + 1e-15))
            if not m.any():
                continue
            if kind == "dwell":
                out[0][m] = s0
                continue
            span = p1 - p0
            sign = 1.0 if kind == "rise" else -1.0
            f, d1, d2, d3 = law_shape(g.law, (phi[m] - p0) / span, g.table)
            out[0][m] = s0 + sign * g.lift * f
            out[1][m] = sign * g.lift * d1 / span
            out[2][m] = sign * g.lift * d2 / span ** 2
            out[3][m] = sign * g.lift * d3 / span ** 3
        return tuple(out)

    def joins(self):
        """Cam angles (rad) where two phases meet, with the phases' kinds: ``[(phi, kind_before, kind_after)]``."""
        ph = self.phases()
        return [(ph[i][2], ph[i][0], ph[(i + 1) % len(ph)][0]) for i in range(len(ph))]

    def _ends(self, phase, x):
        """(v, a, j) of one phase at its start (x = 0) or end (x = 1), exactly."""
        kind, p0, p1, _, g = phase
        if kind == "dwell":
            return np.zeros(3)
        span = p1 - p0
        sign = 1.0 if kind == "rise" else -1.0
        _, d1, d2, d3 = law_shape(g.law, np.array([float(x)]), g.table)
        return sign * g.lift * np.array([d1[0] / span, d2[0] / span ** 2, d3[0] / span ** 3])

    def jumps(self):
        """Jumps of velocity, acceleration and jerk at every join: ``[(phi, dv, da, dj)]`` (after minus
        before), exact from the laws' end values.

        Constant velocity gives a velocity jump (an infinite acceleration: a hard impact).

        Examples
        --------
        >>> prog = MotionProgram.rise_dwell_return(10.0, 90.0, 90.0, 90.0, law="harmonic")
        >>> [round(da, 4) for _, _, da, _ in prog.jumps()]
        [20.0, -20.0, -20.0, 20.0]
        """
        ph = self.phases()
        out = []
        for i, phase in enumerate(ph):
            after = ph[(i + 1) % len(ph)]
            d = self._ends(after, 0.0) - self._ends(phase, 1.0)
            out.append((phase[2] % (2 * math.pi), float(d[0]), float(d[1]), float(d[2])))
        return out
