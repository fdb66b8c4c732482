"""Followers as generating tools: their motion relative to the cam, and their pressure angles.

The follower is the tool and the cam the blank: :func:`follower_motion` gives the kernel's
:class:`~gearkit.motion.PlanarMotion` (the follower frame's pose in the cam frame and its
derivatives over the cam angle, from the motion law), :func:`follower_tool` the tool segment
(roller circle, knife point, flat face) in the follower frame. The envelope solver does the rest.

Pressure angles. Without friction the pressure angle is read off the generated contact (the
angle between the contact normal and the velocity of the driven point: the roller centre, or the
contact point of a knife or face). The closed forms are the references and the friction models:

* translating (textbook 3.19; friction digest eq. 6): ``tg theta = (s'/eta - e)/(s + H0)``;
* rocker (the digest's corrected eq. 18): ``tg theta = [lambda (1 + psi'/eta) - cos Psi]/sin Psi`` here
  (the cam and the arm turn in opposite senses; the digest's vectors have ``1 - psi'/eta``),
  ``lambda = l/l0``, ``Psi = Psi0 + psi``, ``psi' = s'/l``;
* friction-angle model (textbook 3.15): ``|theta| = |alpha| + atan(mu)``.

With the cam turning counter-clockwise these signs hold for the frames of
:mod:`gearkit.families.cam.spec`; the eta models replace ``s'`` by ``s'/eta`` (the power balance
``eta (OP) = s'``).
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.curves import rotate
from gearkit.errors import SpecError
from gearkit.motion import PlanarMotion
from gearkit.segments import Segment, arc, line
from gearkit.values import frozen

__all__ = ["RollerMotion", "follower_motion", "follower_tool", "reference_point", "lift_direction", "translating_pressure_angle",
           "rocker_pressure_angle", "friction_angle_model", "smallest_prime_radius"]


def _j(v):
    return np.stack([-v[..., 1], v[..., 0]], -1)


def _rot(v, angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], -1)


@frozen
class RollerMotion(PlanarMotion):
    """The follower's motion for a roller (or knife) of centre ``centre`` (tool frame).

    The roller touches the cam on its line to the pole, on the cam's side. :meth:`tool_pole`
    returns a point on that line on the cam's side of the centre, ``c + theta' c - R(-theta) J d'``
    (``theta' (pole - c)`` turned round): finite where the relative motion is a pure translation
    (``theta' = 0``, the true pole at infinity), and on the cam's side where the relative rotation
    turns back (a rocker whose ``psi'`` passes -1: the true pole crosses to the far side of the
    roller, and the contact facing it would be the roller's far side).
    """

    centre: tuple = (0.0, 0.0)

    def tool_pole(self, t):
        theta, dtheta, _, _, dd, _ = self.rates(np.asarray(t, dtype=float))
        c = np.asarray(self.centre, dtype=float)
        jd = np.stack([-dd[..., 1], dd[..., 0]], -1)
        return c + dtheta[..., None] * c - rotate(jd, -theta)


def follower_motion(spec) -> PlanarMotion:
    """The follower frame's motion in the cam frame over the cam angle (the generating motion): a
    :class:`RollerMotion` for a roller or knife.

    Examples
    --------
    >>> from gearkit.families.cam import CamSpec, MotionProgram
    >>> spec = CamSpec(40.0, MotionProgram.rise_dwell_return(10.0, 90.0, 30.0, 90.0), roller_radius=8.0)
    >>> follower_motion(spec).to_blank(np.zeros((1, 2)), [0.0]).tolist()  # roller centre at phi = 0
    [[0.0, 40.0]]
    """
    prog = spec.motion
    if spec.follower == "translating":
        e, h0 = spec.offset, spec.start_height

        def rates(phi):
            phi = np.asarray(phi, dtype=float)
            s, v, a, _ = prog.evaluate(phi.ravel())
            s, v, a = (x.reshape(phi.shape) for x in (s, v, a))
            x = np.stack([np.full_like(s, e), h0 + s], -1)
            dx = np.stack([np.zeros_like(v), v], -1)
            ddx = np.stack([np.zeros_like(a), a], -1)
            dx_ = _rot(x, -phi)
            d1 = -_j(dx_) + _rot(dx, -phi)
            d2 = -dx_ - 2.0 * _j(_rot(dx, -phi)) + _rot(ddx, -phi)
            return -phi, -np.ones_like(phi), np.zeros_like(phi), dx_, d1, d2
        return _motion(spec, rates)
    arm, l0, psi0 = spec.arm_length, spec.pivot_distance, spec.psi0

    def rates(phi):
        phi = np.asarray(phi, dtype=float)
        s, v, a, _ = prog.evaluate(phi.ravel())
        s, v, a = (x.reshape(phi.shape) for x in (s, v, a))
        o2 = _rot(np.stack([np.full_like(phi, l0), np.zeros_like(phi)], -1), -phi)
        return math.pi - psi0 - s / arm - phi, -v / arm - 1.0, -a / arm, o2, -_j(o2), -o2
    return _motion(spec, rates)


def _motion(spec, rates):
    if spec.contact == "flat":
        return PlanarMotion(rates)
    return RollerMotion(rates, tuple(float(x) for x in reference_point(spec)))


def reference_point(spec) -> np.ndarray:
    """The driven point in the follower frame: roller centre or knife tip (the face's foot point
    for a flat face), ``(2,)`` mm."""
    if spec.follower == "rocker" and spec.contact != "flat":
        return np.array([spec.arm_length, 0.0])
    return np.zeros(2)


def follower_tool(spec) -> Segment:
    """The follower's working edge in its own frame, walked with the follower's material on the right
    (the outward normal points into the cam): a roller circle (clockwise), a knife point (a corner of
    radius 0), or a flat face long enough for any contact."""
    c = reference_point(spec)
    if spec.contact in ("roller", "knife"):
        return arc(c, spec.roller_radius, 1.5 * math.pi, -0.5 * math.pi, spec.contact)
    _, v, _, _ = spec.motion.evaluate(np.linspace(0.0, 2 * math.pi, 721))
    reach = 4.0 * (spec.prime_radius + spec.stroke + float(np.abs(v).max()) + abs(spec.offset)
                   + (spec.pivot_distance or 0.0))
    if spec.follower == "translating":
        return line((reach, 0.0), (-reach, 0.0), "flat")
    return line((-reach, 0.0), (reach, 0.0), "flat")


def lift_direction(spec, points):
    """Unit velocity direction (follower frame) of follower points as the lift grows, ``(n, 2)``."""
    p = np.atleast_2d(np.asarray(points, dtype=float))
    if spec.follower == "translating":
        return np.broadcast_to(np.array([0.0, 1.0]), p.shape).copy()
    v = np.stack([p[:, 1], -p[:, 0]], -1)  # the arm turns clockwise in its own frame as Psi grows
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def translating_pressure_angle(s, ds, start_height: float, offset: float = 0.0, efficiency: float = 1.0):
    """Signed pressure angle of a translating follower, rad: ``atan2(s'/eta - e, H0 + s)``.

    Examples
    --------
    >>> round(math.degrees(translating_pressure_angle(0.0, 20.0, 20.0)), 9)
    45.0
    """
    return np.arctan2(np.asarray(ds, dtype=float) / efficiency - offset, start_height + np.asarray(s, dtype=float))


def rocker_pressure_angle(lam, psi, dpsi, efficiency: float = 1.0, sense: int = 1):
    """Signed pressure angle of a rocker, rad (the digest's corrected eq. 18):
    ``tg theta = [lambda (1 + sense psi'/eta) - cos Psi] / sin Psi``.

    ``sense = +1`` when the rocker turns against the cam as Psi grows (the frame of
    :mod:`gearkit.families.cam.spec`: the cam counter-clockwise, the arm clockwise), ``-1`` when
    both turn the same way (the sense of the digest's test vectors).

    Examples
    --------
    >>> round(abs(math.degrees(rocker_pressure_angle(0.6, math.radians(30.0), 0.3, sense=-1))), 4)
    41.7346
    """
    psi = np.asarray(psi, dtype=float)
    tg = (lam * (1.0 + sense * np.asarray(dpsi, dtype=float) / efficiency) - np.cos(psi)) / np.sin(psi)
    return np.arctan(tg)


def friction_angle_model(alpha, mu: float):
    """Textbook friction-angle model: the friction angle ``atan(mu)`` adds to ``|alpha|`` (sign kept)."""
    a = np.asarray(alpha, dtype=float)
    return np.where(a >= 0, 1.0, -1.0) * (np.abs(a) + math.atan(mu))


def law_pressure_angle(spec, phi, efficiency: float | None = None, mu: float = 0.0):
    """Pressure angle over the cam angle from the closed forms (roller or knife), rad, signed."""
    eta = spec.efficiency if efficiency is None else efficiency
    s, v, _, _ = spec.motion.evaluate(phi)
    if spec.contact == "flat":
        alpha = np.zeros_like(s)
    elif spec.follower == "translating":
        alpha = translating_pressure_angle(s, v, spec.start_height, spec.offset, eta)
    else:
        arm = spec.arm_length
        alpha = rocker_pressure_angle(arm / spec.pivot_distance, spec.psi0 + s / arm, v / arm, eta)
    return friction_angle_model(alpha, mu) if mu else alpha


def _driving(spec):
    """The phases whose pressure angle counts: ``[(phi0, phi1)]`` (rises; returns too for a groove)."""
    return [(p0, p1) for kind, p0, p1, _, _ in spec.motion.phases()
            if kind == "rise" or (kind == "return" and spec.groove)]


def phase_extreme(func, p0: float, p1: float, n: int = 2001) -> float:
    """Largest ``func(phi)`` on ``[p0, p1]``: a dense grid, then a bounded search around its best node."""
    from gearkit.roots import fminbound

    grid = np.linspace(p0, p1, n)
    vals = func(grid)
    k = int(np.argmax(vals))
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, n - 1)]
    if hi <= lo:
        return float(vals[k])
    _, fun = fminbound(lambda x: -float(func(np.array([x]))[0]), lo, hi, xatol=1e-12)
    return max(float(vals[k]), -fun)


def smallest_prime_radius(spec, efficiency: float | None = None, mu: float | None = None) -> float:
    """Smallest prime radius r0 (mm) whose largest pressure angle over the driving phases (the rises;
    the returns too for a groove) equals the limit.

    Translating follower: ``sqrt(r0^2 - e^2) >= max (|s'/eta - e| / tg[theta] - s)`` (friction digest
    §3.1). Rocker: bisection on r0 over the corrected formula. A flat face: the convexity bound
    ``r0 > max(-s - s'')`` (translating) instead.

    Examples
    --------
    >>> from gearkit.families.cam import CamSpec, MotionProgram, MotionSegment
    >>> prog = MotionProgram((MotionSegment("rise", 60.0, 20.0, "cycloidal"), MotionSegment("dwell", 60.0),
    ...                       MotionSegment("return", 60.0, 20.0, "cycloidal")))
    >>> round(smallest_prime_radius(CamSpec(80.0, prog, roller_radius=10.0)), 4)
    56.7702
    """
    eta = spec.efficiency if efficiency is None else efficiency
    mu = spec.friction if mu is None else mu
    lim = math.radians(spec.limit_deg) - math.atan(mu)
    if lim <= 0:
        raise SpecError("friction", f"the friction angle atan({mu:g}) leaves no pressure angle below the limit")
    phases = _driving(spec)
    if spec.contact == "flat":
        if spec.follower != "translating":
            raise SpecError("contact", "the smallest base circle of a flat-faced rocker has no closed form here")

        def concave(phi):
            s, _, a, _ = spec.motion.evaluate(phi)
            return -s - a
        return max(phase_extreme(concave, 0.0, 2 * math.pi, 7201), 0.0)
    if spec.follower == "translating":
        e, tg = spec.offset, math.tan(lim)

        def need(phi):
            s, v, _, _ = spec.motion.evaluate(phi)
            return np.abs(v / eta - e) / tg - s
        h0 = max(phase_extreme(need, p0, p1) for p0, p1 in phases)
        return math.hypot(max(h0, 0.0), e)
    from dataclasses import replace

    l0, arm = spec.pivot_distance, spec.arm_length

    def worst(r0):
        sp = replace(spec, prime_radius=r0)
        return max(phase_extreme(lambda p: np.abs(law_pressure_angle(sp, p, eta)), p0, p1, 721)
                   for p0, p1 in phases) + math.atan(mu)
    lim_full = math.radians(spec.limit_deg)

    def feasible(r0):
        try:
            return worst(r0) <= lim_full
        except SpecError:  # the rocker cannot reach this prime circle, or its swing does not fit
            return False
    # the largest angle is not monotone in r0 for a rocker (near r0 = l0 + l the arm lies along the
    # line of centres): scan for the first feasible r0, then bisect down to its edge
    grid = np.linspace(abs(l0 - arm), l0 + arm, 66)[1:-1]
    ok = [feasible(r) for r in grid]
    if not any(ok):
        return math.inf  # no prime circle this rocker reaches keeps the pressure angle below the limit
    k = ok.index(True)
    lo, hi = (abs(l0 - arm) if k == 0 else grid[k - 1]), grid[k]
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if feasible(mid) else (mid, hi)
        if hi - lo <= 1e-10 * hi:
            break
    return hi

