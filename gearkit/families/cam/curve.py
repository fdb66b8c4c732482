"""The cam's envelope over one turn and its pitch curve, as exact curves whose tangent's turn is bounded.

:class:`CamCurve` joins the kernel's envelope branch (solved along the cam angle) with the sections
where the follower's velocity jumps; :class:`PitchCurve` is the reference point's path over one phase.
Both give the sampler (:func:`gearkit.accuracy.adaptive_sample`) their points, tangents and the parts
``(phi, A)`` (cam angle, tangent angle), and a ``span``: the proven range of a leg's turn
(:class:`~gearkit.families.cam.turns.CamTurns`), so a cam's reported deviation is a proven bound as a
tooth's is.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.curves import rotate
from gearkit.envelope import touching
from gearkit.families.cam.turns import CamTurns

__all__ = ["AngleBranch", "CamCurve", "PitchCurve"]

_TWO_PI = 2.0 * math.pi


class AngleBranch:
    """A branch evaluated at cam angles directly (its parameter runs over ``[0, 1]`` = one radian)."""

    def __init__(self, branch):
        self.segment, self.motion, self.root = branch.segment, branch.motion, branch.root
        self._branch = branch

    def __call__(self, phi):
        return self._branch(np.asarray(phi, dtype=float))


class CamCurve:
    """The whole envelope over one turn as one exact curve of ``w`` in [0, 1].

    Between the joins where the follower's velocity jumps (a constant-velocity law) it is the
    kernel's branch solved along the cam angle. At such a join the relative motion's instant
    centre jumps while the cam angle stands still; the follower's contact sweeps from the old
    pole's contact to the new one's (a roller turns about the pitch curve's corner: an arc of the
    roller; a flat face slides: a piece of the face) — inserted here as a section of its own with
    the pole moving on the straight line between the two. ``corners`` are ``(phi, pole before, pole
    after, weight)``, ``phi`` in ``[start, start + 2 pi)`` the first cam angle the law reads after the
    jump: the motion before it is solved at the angles below it, the motion after it from it on.
    """

    def __init__(self, branch: AngleBranch, start: float, corners, turns: CamTurns):
        self.branch = branch
        self.start = start
        self.span = turns.span
        # sections: ("motion", phi0, phi1) and ("corner", phi, pole0, pole1), each with a weight in w
        sections, phi = [], start
        for phi_c, p0, p1, weight in sorted(corners, key=lambda corner: corner[0]):
            if phi_c > phi:
                sections.append(("motion", phi, phi_c, phi_c - phi))
            sections.append(("corner", phi_c, p0, p1, weight))
            phi = phi_c
        sections.append(("motion", phi, start + _TWO_PI, start + _TWO_PI - phi))
        total = sum(sec[-1] for sec in sections)
        self.sections = sections
        self._before_corner = np.array([sec[0] == "motion" and k + 1 < len(sections) and sections[k + 1][0] == "corner"
                                        for k, sec in enumerate(sections)])
        self.edges = np.concatenate([[0.0], np.cumsum([sec[-1] for sec in sections]) / total])
        self.edges[-1] = 1.0

    def locate(self, w):
        """Section index and local parameter in [0, 1] of each ``w``."""
        w = np.atleast_1d(np.asarray(w, dtype=float))
        k = np.clip(np.searchsorted(self.edges, w, side="right") - 1, 0, len(self.sections) - 1)
        lo, hi = self.edges[k], self.edges[k + 1]
        return k, np.clip((w - lo) / (hi - lo), 0.0, 1.0)

    def breaks(self, program):
        """Sorted ``w`` of every section end and every join of the motion program inside a motion
        section: where the curve may turn at once (a velocity jump's corner) or its curvature jumps,
        so that each piece between them is smooth for the sampler."""
        out = list(self.edges)
        corners = [sec[1] for sec in self.sections if sec[0] == "corner"]  # edges already (an ulp past the join)
        joins = [phi % _TWO_PI for phi, _, _ in program.joins()
                 if not any(abs((c - phi + math.pi) % _TWO_PI - math.pi) < 1e-9 for c in corners)]
        for k, sec in enumerate(self.sections):
            if sec[0] != "motion":
                continue
            for phi in joins:
                for p in (phi + _TWO_PI * j for j in (-1, 0, 1, 2)):
                    if sec[1] < p < sec[2]:
                        out.append(self.edges[k] + (p - sec[1]) / (sec[2] - sec[1]) * (self.edges[k + 1] - self.edges[k]))
        return np.unique(np.asarray(out, dtype=float))

    def phi(self, w):
        """Cam angle (rad, from ``start``) at ``w``."""
        k, t = self.locate(w)
        out = np.empty(len(k))
        for i, sec in enumerate(self.sections):
            m = k == i
            out[m] = sec[1] + t[m] * (sec[2] - sec[1]) if sec[0] == "motion" else sec[1]
        return out

    def __call__(self, w):
        return self.solve(w)[0]

    def turning(self, w):
        """Points, unit tangents and the parts ``(phi, A)``: the cam angle and the tangent's angle, whose
        range over a leg :meth:`span` (:class:`~gearkit.families.cam.turns.CamTurns`) bounds."""
        pts, tangents, phi = self.solve(w)
        return pts, tangents, np.stack([phi, np.arctan2(tangents[:, 1], tangents[:, 0])], -1)

    def solve(self, w):
        """Points, unit tangents (the follower's at the contact, carried to the cam) and cam angles at ``w``."""
        k, t = self.locate(w)
        # a motion section's end at a corner is the left limit, the corner's start (the law itself
        # gives the velocity after the jump there)
        ends = (t >= 1.0) & self._before_corner[k]
        k, t = np.where(ends, k + 1, k), np.where(ends, 0.0, t)
        out, tangents, phi = np.empty((len(k), 2)), np.empty((len(k), 2)), np.empty(len(k))
        br = self.branch
        seg, motion = br.segment, br.motion
        for i, sec in enumerate(self.sections):
            m = k == i
            if not m.any():
                continue
            if sec[0] == "motion":
                ph = sec[1] + t[m] * (sec[2] - sec[1])
                if self._before_corner[i]:  # below the corner's angle: the law before the jump
                    ph = np.minimum(ph, np.nextafter(sec[2], -np.inf))
                u, _ = touching(seg, motion.tool_pole(ph), br.root)
            elif seg.kind == "arc":  # a roller turns about the corner: its contact angle, the short way
                ph = np.full(int(m.sum()), sec[1])
                ua, ub = touching(seg, np.stack([sec[2], sec[3]]), br.root)[0]
                du = (ub - ua) - np.round(ub - ua)  # the whole circle is u in [0, 1]
                u = np.mod(ua + t[m] * du, 1.0)
            else:  # a face slides: its foot point moves with the pole
                ph = np.full(int(m.sum()), sec[1])
                poles = sec[2][None, :] * (1.0 - t[m, None]) + sec[3][None, :] * t[m, None]
                u, _ = touching(seg, poles, br.root)
            p, tool_tangent, _ = seg.evaluate(u)
            _, theta, offset = motion.pose(ph)
            out[m], tangents[m], phi[m] = rotate(p, theta) + offset, rotate(tool_tangent, theta), ph
        return out, tangents, phi


class PitchCurve:
    """The pitch curve (the path of the reference point, :func:`~gearkit.families.cam.follower.reference_point`)
    over one phase of the motion program, ``phi0`` to ``phi1``: an exact curve of ``w`` in [0, 1] with its
    tangent's turn bounded as the cam's (:class:`~gearkit.families.cam.turns.CamTurns` with ``pitch=True``)."""

    def __init__(self, motion, reference, turns: CamTurns, phi0: float, phi1: float):
        self.motion, self.reference, self.span = motion, np.asarray(reference, dtype=float), turns.span
        self.phi0, self.phi1 = float(phi0), float(phi1)

    def _phi(self, w):
        return self.phi0 + np.atleast_1d(np.asarray(w, dtype=float)) * (self.phi1 - self.phi0)

    def __call__(self, w):
        phi = self._phi(w)
        return self.motion.to_blank(np.broadcast_to(self.reference, phi.shape + (2,)), phi)

    def turning(self, w):
        """Points, unit tangents (the reference point's velocity) and the parts ``(phi, A)``."""
        phi = self._phi(w)
        q, dq, _ = self.motion.path(np.broadcast_to(self.reference, phi.shape + (2,)), phi)
        tangents = dq / np.hypot(dq[:, 0], dq[:, 1])[:, None]
        return q, tangents, np.stack([phi, np.arctan2(dq[:, 1], dq[:, 0])], -1)
