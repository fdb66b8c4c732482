"""How far a cam's tangent turns over a stretch of cam angle: a proven range, from the motion law.

A tooth's tangent angle is a sum of monotone parts (:mod:`gearkit.chords`); a cam's is not: the
follower's contact turns both ways along the cam angle ``phi`` with the pressure angle. Its rate is a
known function of the motion law instead, and the law bounds it:

* a flat face: the cam's tangent is the face, turned by the motion's angle ``theta``, so
  ``dA/dphi = theta' = -1`` (translating) or ``-1 - s'/l`` (rocker);
* a roller or a knife: the cam is the offset of the pitch curve ``P`` (the roller centre's path), its
  tangent is ``P'``'s, and ``P' = R(-phi) Y`` with ``Y = (H0 + s, s' - e)`` (translating) or
  ``Y = c u(Psi) - (0, l0)``, ``c = rho (1 + s'/l)``, ``u = (sin Psi, cos Psi)``, ``Psi = Psi0 + s/l``
  (rocker; ``rho`` the reference point's distance from the pivot), so
  ``dA/dphi = -1 + cross(Y, Y') / |Y|^2``.

Over a leg from ``phi_a`` to ``phi_b`` inside one phase of the program (the outline is split at every
join) the law's jerk is at most ``J = lift max|f'''| / span^3`` (:func:`~gearkit.families.cam.laws.jerk_bound`).
The acceleration then lies in the range of a function with known ends whose slope is in ``[-J, J]``
(:func:`extent`), the velocity in the range that acceleration range allows, the lift likewise;
interval arithmetic carries them to a range ``[k_lo, k_hi]`` of ``dA/dphi`` over the leg, and
:func:`extent` once more to the range of the angle itself, from its exact values at the leg's ends.
Every step only widens a range, so it holds; as the legs shrink it narrows to the exact one (a dwell's
is exact at once: ``dA/dphi = -1``).

>>> lo, hi = extent(np.array(0.0), np.array(1.0), np.array(-1.0), np.array(3.0), np.array(1.0))
>>> float(lo), float(hi)  # y(0) = 0, y(1) = 1, -1 <= y' <= 3: between max(-t, 3 t - 2) and min(3 t, 2 - t)
(-0.5, 1.5)
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.families.cam.laws import jerk_bound, law_shape

__all__ = ["CamTurns", "extent", "sin_range"]

#: a leg's end angles must agree with its rate range to this angle (rad): round-off of the angles
CONSISTENT = 1e-9
#: the range given to a leg that is not bounded (wider than the half turn :mod:`gearkit.chords` accepts)
UNBOUNDED = 10.0


def extent(ya, yb, dlo, dhi, h):
    """Range ``(lo, hi)`` of a function on ``[0, h]`` with ``y(0) = ya``, ``y(h) = yb`` and slope in
    ``[dlo, dhi]``: it stays below both ``ya + dhi t`` and ``yb - dlo (h - t)``, so below their
    crossing, and above the other two lines' crossing."""
    gap = dhi - dlo
    with np.errstate(divide="ignore", invalid="ignore"):
        th = np.where(gap > 0, np.clip(np.divide(yb - ya - dlo * h, gap, where=gap > 0, out=np.zeros_like(gap)), 0, h), 0)
        tl = np.where(gap > 0, np.clip(np.divide(ya - yb + dhi * h, gap, where=gap > 0, out=np.zeros_like(gap)), 0, h), 0)
    return np.minimum(np.minimum(ya, yb), ya + dlo * tl), np.maximum(np.maximum(ya, yb), ya + dhi * th)


def sin_range(lo, hi):
    """Range ``(lo, hi)`` of ``sin`` over each interval ``[lo, hi]`` of angles (any place, rad): its values at
    the ends, and 1 or -1 where the interval holds a crest or a trough.

    >>> [tuple(round(float(v), 12) for v in sin_range(np.array(a), np.array(b))) for a, b in
    ...  [(0.0, 0.5), (-0.5, 0.0), (1.0, 2.0), (-2.0, -1.0), (-1.0, 7.0)]]
    [(0.0, 0.479425538604), (-0.479425538604, 0.0), (0.841470984808, 1.0), (-1.0, -0.841470984808), (-1.0, 1.0)]
    """
    a, b = np.sin(lo), np.sin(hi)
    crest = np.floor((hi - 0.5 * math.pi) / (2 * math.pi)) * (2 * math.pi) + 0.5 * math.pi >= lo
    trough = np.floor((hi + 0.5 * math.pi) / (2 * math.pi)) * (2 * math.pi) - 0.5 * math.pi >= lo
    return np.where(trough, -1.0, np.minimum(a, b)), np.where(crest, 1.0, np.maximum(a, b))


def _mul(x, y):
    p = (x[0] * y[0], x[0] * y[1], x[1] * y[0], x[1] * y[1])
    return np.minimum(np.minimum(p[0], p[1]), np.minimum(p[2], p[3])), np.maximum(np.maximum(p[0], p[1]),
                                                                                 np.maximum(p[2], p[3]))


def _scale(c, x):
    return (c * x[0], c * x[1]) if c >= 0 else (c * x[1], c * x[0])


def _add(x, y):
    return x[0] + y[0], x[1] + y[1]


def _sq(x):
    a, b = x[0] * x[0], x[1] * x[1]
    return np.where((x[0] < 0) & (x[1] > 0), 0.0, np.minimum(a, b)), np.maximum(a, b)


def _quad(x, alpha, beta):
    """Range of ``alpha v^2 + beta v`` over ``v`` in ``x`` (its ends and its vertex)."""
    f = (alpha * x[0] * x[0] + beta * x[0], alpha * x[1] * x[1] + beta * x[1])
    lo, hi = np.minimum(*f), np.maximum(*f)
    if alpha == 0:
        return lo, hi
    top = -beta / (2 * alpha)
    inside = (x[0] < top) & (top < x[1])
    vertex = -beta * beta / (4 * alpha)
    return np.where(inside, np.minimum(lo, vertex), lo), np.where(inside, np.maximum(hi, vertex), hi)


def _div(x, y):
    """``x / y`` for ``y`` positive."""
    return _mul(x, (1.0 / y[1], 1.0 / y[0]))


class CamTurns:
    """Proven ranges of the turn of a cam's tangent (``pitch=False``) or of its pitch curve's
    (``pitch=True``: the path of the reference point, :func:`~gearkit.families.cam.follower.reference_point`)
    over legs of cam angle. :meth:`span` is a curve's ``span`` for :func:`gearkit.chords.interval_bounds`;
    the curve's angle parts are ``(phi, A)``: the cam angle and the tangent's angle (any branch)."""

    def __init__(self, spec, pitch: bool = False):
        self.spec = spec
        self.face = spec.contact == "flat" and not pitch
        self.rho = 0.0 if spec.contact == "flat" else spec.arm_length or 0.0  # the reference point from the pivot
        self.phases = spec.motion.phases()
        self.starts = np.array([p[1] for p in self.phases])
        self.jerks = []
        for kind, p0, p1, _, g in self.phases:
            span = p1 - p0
            with np.errstate(all="ignore"):
                jerk = 0.0 if kind == "dwell" else g.lift * jerk_bound(g.law, g.table) / np.float64(span) ** 3
            self.jerks.append(float(jerk) if np.isfinite(jerk) else math.inf)

    def _law(self, phase, phi):
        """Lift, velocity and acceleration at ``phi`` in phase ``phase``, one-sided (its own law at its ends)."""
        kind, p0, p1, s0, g = self.phases[phase]
        if kind == "dwell":
            return np.full_like(phi, s0), np.zeros_like(phi), np.zeros_like(phi)
        span = p1 - p0
        lift = g.lift if kind == "rise" else -g.lift
        f, d1, d2, _ = law_shape(g.law, np.clip((phi - p0) / span, 0.0, 1.0), g.table)
        return s0 + lift * f, lift * d1 / span, lift * d2 / span ** 2

    def rates(self, phi_a, phi_b):
        """Range ``(k_lo, k_hi)`` of ``dA/dphi`` over each leg ``phi_a < phi_b`` (inside one phase), and
        whether it is bounded."""
        h = phi_b - phi_a
        mid = 0.5 * (phi_a + phi_b)
        lap = np.floor(mid / (2 * math.pi)) * (2 * math.pi)  # the whole turns before the leg
        phase = np.clip(np.searchsorted(self.starts, mid - lap, side="right") - 1, 0, len(self.phases) - 1)
        s, v, a = (np.empty((2,) + h.shape) for _ in range(3))
        jerk = np.empty(h.shape)
        for i in np.unique(phase):
            m = phase == i
            both = np.stack([phi_a[m] - lap[m], phi_b[m] - lap[m]])
            s[:, m], v[:, m], a[:, m] = self._law(int(i), both)
            jerk[m] = self.jerks[int(i)]
        ok = np.isfinite(jerk)
        jerk = np.where(ok, jerk, 0.0)
        acc = extent(a[0], a[1], -jerk, jerk, h)
        vel = extent(v[0], v[1], acc[0], acc[1], h)
        lift = extent(s[0], s[1], vel[0], vel[1], h)
        spec = self.spec
        if self.face:
            if spec.follower == "translating":
                return -np.ones_like(h), -np.ones_like(h), ok
            arm = spec.arm_length
            return -1.0 - vel[1] / arm, -1.0 - vel[0] / arm, ok
        if spec.follower == "translating":
            e, h0 = spec.offset, spec.start_height
            height = (h0 + lift[0], h0 + lift[1])
            ok &= height[0] > 0
            cross = _add(_mul(height, acc), _scale(-1.0, _quad(vel, 1.0, -e)))  # (H0 + s) s'' - s' (s' - e)
            norm = _add(_sq(height), _sq((vel[0] - e, vel[1] - e)))
        else:
            arm, l0, rho = spec.arm_length, spec.pivot_distance, self.rho
            psi = (spec.psi0 + lift[0] / arm, spec.psi0 + lift[1] / arm)
            # the formula holds at any arm angle: at rest the arm may point straight through the cam's
            # axis (Psi0 = 0, l - l0 = r0) and a leg's lift range dip below it
            psi = (np.where(ok, psi[0], 1.0), np.where(ok, psi[1], 1.0))
            sin, cos = sin_range(psi[0], psi[1]), sin_range(psi[0] + 0.5 * math.pi, psi[1] + 0.5 * math.pi)
            c = (rho + rho * vel[0] / arm, rho + rho * vel[1] / arm)
            # cross(Y, Y') = -c^2 s'/l + l0 rho s'' sin(Psi)/l + l0 (c s') cos(Psi)/l, with c s' = rho (s' + s'^2/l)
            cross = _add(_add(_scale(-1.0 / arm, _mul(_sq(c), vel)), _scale(l0 * rho / arm, _mul(acc, sin))),
                         _scale(l0 / arm, _mul(_quad(vel, rho / arm, rho), cos)))
            norm = _add(_sq((c[0] - l0 * cos[1], c[1] - l0 * cos[0])), _scale(l0 * l0, _sq(sin)))
        ok &= norm[0] > 0
        turn = _div(cross, (np.where(ok, norm[0], 1.0), np.where(ok, norm[1], 1.0)))
        return -1.0 + turn[0], -1.0 + turn[1], ok

    def span(self, pa, pb):
        """Range ``(lo, hi)`` of the tangent's angle over each leg from its angle at ``pa``, and the leg's
        turn, from the parts ``(phi, A)`` at the legs' ends (``(..., 2)``). A leg at one cam angle (a
        corner of the pitch curve: the roller's arc, the face's slide) turns one way; a leg whose end
        angles do not fit its rate range is not bounded."""
        phi_a, phi_b = pa[..., 0], pb[..., 0]
        total = np.remainder(pb[..., 1] - pa[..., 1] + math.pi, 2 * math.pi) - math.pi
        lo, hi = np.minimum(total, 0.0), np.maximum(total, 0.0)
        moving = phi_a != phi_b
        if not moving.any():
            return lo, hi, total
        back = phi_b[moving] < phi_a[moving]
        start, end = np.where(back, phi_b[moving], phi_a[moving]), np.where(back, phi_a[moving], phi_b[moving])
        turn = np.where(back, -total[moving], total[moving])
        k_lo, k_hi, ok = self.rates(start, end)
        h = end - start
        ok &= (k_lo * h - CONSISTENT <= turn) & (turn <= k_hi * h + CONSISTENT)
        f_lo, f_hi = extent(np.zeros_like(h), turn, k_lo, k_hi, h)
        shift = np.where(back, total[moving], 0.0)  # a leg walked backwards: from its far end
        lo[moving] = np.where(ok, f_lo + shift, 0.0)
        hi[moving] = np.where(ok, f_hi + shift, UNBOUNDED)
        return lo, hi, total
