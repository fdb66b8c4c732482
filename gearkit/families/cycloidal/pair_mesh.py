"""The mesh of a generated cycloid pair: conjugate contacts and the contact ratio they give.

For points of the wheel's generated flank, the wheel is turned until the point's normal passes
through the pitch point P (where the point must touch the pinion if the pair is conjugate);
the pinion turns by ``-phi2 z2/z1``. The point is then carried into the pinion's frame and
compared with the pinion's *generated* flank: the distance to it, and the distance of the
pinion's own normal line there from P. Both are zero for a conjugate pair whose common normal
at every contact passes through the pitch point (the law of gearing for a constant ratio).

Frame: wheel centre at the origin, P = (0, r2), pinion centre at (0, r2 + r1); at phi2 = 0 the
wheel's tooth 0 and a pinion space face P.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.accuracy import adaptive_sample
from gearkit.families.cycloidal.pair import CycloidPairSpec, cycloid_gear
from gearkit.values import frozen

__all__ = ["ConjugateCheck", "conjugate_check", "generated_contact_ratio"]


def _rot(p, a):
    c, s = np.cos(a), np.sin(a)
    return np.stack([c * p[..., 0] - s * p[..., 1], s * p[..., 0] + c * p[..., 1]], -1)


def _flank_samples(gear, tol):
    """(points, normals) of the gear's generated flank pieces (exact), sampled to ``tol``."""
    pts, nrm = [], []
    for pc in gear.half.pieces:
        if pc.label != "flank" or not hasattr(pc.curve, "solve"):
            continue
        w, _, _ = adaptive_sample(pc, tol)
        q, n, _, _ = pc.curve.solve(pc.w0 + w * (pc.w1 - pc.w0))
        pts.append(q)
        nrm.append(n)
    return np.concatenate(pts), np.concatenate(nrm)


class _Foot:
    """Feet of perpendiculars on a gear's generated flank pieces (exact, by bisection in the branch
    parameter on the tangency condition), for points folded into the half tooth's wedge."""

    def __init__(self, gear, tol):
        self.gear = gear
        self.pieces = [pc for pc in gear.half.pieces if pc.label == "flank" and hasattr(pc.curve, "solve")]
        self.samples = [(pc, adaptive_sample(pc, tol)) for pc in self.pieces]

    def nearest(self, x):
        best = np.full(len(x), np.inf)
        foot = np.zeros_like(x)
        normal = np.zeros_like(x)
        for pc, (w, pts, _) in self.samples:
            d = np.linalg.norm(x[:, None, :] - pts[None, :, :], axis=-1)
            i = np.argmin(d, axis=1)
            lo = w[np.maximum(i - 1, 0)]
            hi = w[np.minimum(i + 1, len(w) - 1)]

            def g(t):
                q, n, _, _ = pc.curve.solve(pc.w0 + t * (pc.w1 - pc.w0))
                return q, n, (q[:, 0] - x[:, 0]) * n[:, 1] - (q[:, 1] - x[:, 1]) * n[:, 0]
            g_lo, g_hi = g(lo)[2], g(hi)[2]
            for _ in range(80):
                mid = 0.5 * (lo + hi)
                g_mid = g(mid)[2]
                left = np.sign(g_mid) == np.sign(g_lo)
                lo, g_lo = np.where(left, mid, lo), np.where(left, g_mid, g_lo)
                hi = np.where(left, hi, mid)
            q, n, _ = g(0.5 * (lo + hi))
            dist = np.linalg.norm(q - x, axis=1)
            better = dist < best
            best = np.where(better, dist, best)
            foot = np.where(better[:, None], q, foot)
            normal = np.where(better[:, None], n, normal)
        return best, foot, normal


@frozen
class ConjugateCheck:
    """Wheel flank points in contact with the pinion (mm, pair frame) and the checks at each.

    ``gap``: distance from the pinion's generated flank (0 when conjugate); ``normal_offset``:
    distance of the pinion's normal line at the contact from the pitch point; ``wheel_offset``
    the same for the wheel's normal (0 by construction); ``angle``: the wheel's turn phi2 (rad).
    """

    points: np.ndarray
    angle: np.ndarray
    gap: np.ndarray
    normal_offset: np.ndarray
    normal_angle: np.ndarray


def conjugate_check(spec: CycloidPairSpec, tol: float | None = None) -> ConjugateCheck:
    """Contacts of the generated wheel with the generated pinion, checked on the pinion's side."""
    m = spec.module
    tol = 1e-3 * m if tol is None else tol
    r1, r2 = spec.r1, spec.r2
    wheel, pinion = cycloid_gear(spec, 2), cycloid_gear(spec, 1)
    q, n = _flank_samples(wheel, tol)
    # turn the wheel until the normal line through q meets the pitch point: in the wheel frame the
    # pitch point is where the line meets the pitch circle (the nearer intersection)
    b = np.einsum("ij,ij->i", q, n)
    disc = b * b - (np.einsum("ij,ij->i", q, q) - r2 * r2)
    ok = disc >= 0
    q, n, b, disc = q[ok], n[ok], b[ok], disc[ok]
    lam = np.where(np.abs(-b - np.sqrt(disc)) < np.abs(-b + np.sqrt(disc)), -b - np.sqrt(disc), -b + np.sqrt(disc))
    hit = q + lam[:, None] * n
    phi2 = np.arctan2(hit[:, 0], hit[:, 1])
    pts = _rot(q, phi2)
    nrm = _rot(n, phi2)
    o1 = np.array([0.0, r1 + r2])
    # contacts exist only inside the pinion's tip circle
    inside = np.linalg.norm(pts - o1, axis=1) <= r1 + spec.addendum(1) * (1.0 - 1e-12)
    pts, nrm, phi2 = pts[inside], nrm[inside], phi2[inside]
    phi1 = -phi2 * r2 / r1
    turn = math.pi + math.pi / spec.pinion_teeth + phi1
    x = _rot(pts - o1, -turn)
    nx = _rot(nrm, -turn)
    # fold into the pinion's right half-tooth wedge
    pitch = 2.0 * math.pi / spec.pinion_teeth
    k = np.round(np.arctan2(x[:, 0], x[:, 1]) / pitch)
    x = _rot(x, k * pitch)
    nx = _rot(nx, k * pitch)
    flip = np.where(x[:, :1] < 0, np.array([-1.0, 1.0]), 1.0)
    x, nx = x * flip, nx * flip
    gap, foot, n_pin = _Foot(pinion, tol).nearest(x)
    p_pin = _rot(_rot(np.array([0.0, r2]) - o1, -turn), k * pitch) * flip
    offset = np.abs((p_pin[:, 0] - foot[:, 0]) * n_pin[:, 1] - (p_pin[:, 1] - foot[:, 1]) * n_pin[:, 0])
    angle = np.arccos(np.clip(-np.einsum("ij,ij->i", n_pin, nx), -1.0, 1.0))
    return ConjugateCheck(pts, phi2, gap, offset, angle)


def generated_contact_ratio(spec: CycloidPairSpec) -> float:
    """Contact ratio read off the generated gears: each addendum flank is in action while the
    pitch circles roll through the span of its contact rolls (the roll at which each of its points
    meets its generating rack is the one at which it meets the mating gear); the sum over the
    circular pitch."""
    total = 0.0
    for k in (1, 2):
        gear = cycloid_gear(spec, k)
        r = gear.pitch_radius
        rolls = []
        for pc in gear.half.pieces:
            if pc.label != "flank" or not hasattr(pc.curve, "solve"):
                continue
            q, _, s, _ = pc.curve.solve(np.array([pc.w0, 0.5 * (pc.w0 + pc.w1), pc.w1]))
            if np.hypot(*q[1]) > r:  # an addendum piece: from the pitch circle to the tip
                rolls.extend([float(s[0]), float(s[2])])
        total += max(rolls) - min(rolls)
    return total / (math.pi * spec.module)
