"""The cam profile: the envelope of the follower moving relative to the cam.

:func:`cam_profile` hands the follower (the tool: roller circle, knife point, flat face) and its
motion relative to the cam (:func:`~gearkit.families.cam.follower.follower_motion`) to the
kernel's envelope solver, solved along the cam angle (:class:`gearkit.envelope.Branch` with
``along="motion"``). The branch is an exact curve of the cam angle; where a roller is larger than
the pitch curve's convex radius of curvature (or a flat face meets a non-convex motion) the
envelope loops, and the loop is cut away at the refined crossing (undercut: the cam no longer
gives the prescribed motion there). ``outline(tol)`` samples what is left to a chord tolerance
and reports the deviation it achieved.
"""
from __future__ import annotations

import functools
import math

import numpy as np

from gearkit.accuracy import PRECISION, sample_curves
from gearkit.chords import ROUND_OFF
from gearkit.boundary import Piece, next_crossing
from gearkit.curves import cross2, polyline_self_intersections
from gearkit.envelope import Branch, touching
from gearkit.errors import GeometryError, is_real, require
from gearkit.families.cam.crossings import refine_crossing
from gearkit.families.cam.curve import AngleBranch, CamCurve, PitchCurve
from gearkit.families.cam.faces import corner_lines, face_boundary, kept_runs, roller_depth
from gearkit.families.cam.halfplanes import face_depth
from gearkit.families.cam.follower import follower_motion, follower_tool, lift_direction, reference_point
from gearkit.families.cam.turns import CamTurns

__all__ = ["CamProfile", "cam_profile"]

_TWO_PI = 2.0 * math.pi
#: cam angles sampled to find the curve's shape, loops and extremes
_SCAN = 4096
#: a roller's keep test (:func:`~gearkit.families.cam.faces.kept_runs`) keeps envelope points up to this
#: deep in the swept region, in (r0 + stroke): the sampling error of the region it measures them against.
#: A loop (swallowtail) shallower than that stays in the outline, so its reported deviation adds it
KEEP_SLACK = 1e-7
#: the finest tol of a roller cam's outline, in (r0 + stroke): the keep slack and as much again for the
#: chords (a tol below it could not be told from the loops the keep test leaves in)
ROLLER_FLOOR = 2 * KEEP_SLACK


class CamProfile:
    """A generated disc cam. Lengths in mm, cam frame (the cam at angle 0).

    ``branch`` is the exact envelope over one turn (its parameter ``w`` in [0, 1] runs the cam
    angle from ``start`` through a full turn); ``pieces`` are the parts that remain after the loops
    are cut. Everything else is read off them.
    """

    def __init__(self, spec):
        self.spec = spec
        self.motion = follower_motion(spec)
        self.tool = follower_tool(spec)
        self.reference = reference_point(spec)
        self._cache = {}
        start = self._start_angle()
        self.start = start
        # the branch's own parameter is the cam angle itself: the curve maps w onto it and the corners
        self.envelope = Branch(self.tool, self.motion, 0.0, 1.0, "near", along="motion")
        scale = spec.prime_radius + spec.stroke
        corners = self._corners(scale)
        self.corner_angles = tuple(phi for phi, dv, _, _ in spec.motion.jumps() if abs(dv) > 1e-12 * scale)
        self.branch = CamCurve(AngleBranch(self.envelope), start, corners, CamTurns(spec))
        self.planes = None  # a flat face's half-planes (gearkit.families.cam.halfplanes.HalfPlanes)
        self.pieces, self.loops = self._trim()

    # -- construction ---------------------------------------------------------------------
    def _start_angle(self) -> float:
        """A cam angle where the envelope is regular and outermost (no loop can cover it): where
        the pitch curve is least convex relative to the roller."""
        phi = np.linspace(0.0, _TWO_PI, _SCAN, endpoint=False)
        jumps = [c for c, dv, _, _ in self.spec.motion.jumps() if dv != 0.0]
        if jumps:  # not at a velocity jump: the curve's start and end would be its two sides
            gap = np.abs((phi[:, None] - np.array(jumps)[None, :] + math.pi) % _TWO_PI - math.pi).min(axis=1)
            phi = phi[gap > 1e-9]
        if self.spec.contact == "flat":
            s, _, a, _ = self.spec.motion.evaluate(phi)
            return float(phi[np.argmax(s + a)])
        k = 1.0 / self.pitch_curvature_radius(phi)
        return float(phi[np.argmin(k)])

    def _corners(self, scale):
        """Joins where the velocity jumps: ``(phi, pole before, pole after, weight)`` (tool frame), ``phi``
        in ``[start, start + 2 pi)``: the first cam angle the law reads after the jump (:func:`_after_jump`).
        Jumps read at one angle (a dwell between them shorter than an ulp of it) are one jump, from the
        velocity before the first to the velocity after the last: the cam angle does not move between them."""
        out, phases = [], self.spec.motion.phases()
        for phi, dv, _, _ in self.spec.motion.jumps():
            if abs(dv) <= 1e-12 * scale:
                continue
            # within the phase ending at the jump (a dwell before it may be shorter than 1e-9 rad)
            span = min((p[2] - p[1] for p in phases if abs((p[2] - phi + math.pi) % _TWO_PI - math.pi) < 1e-12),
                       default=1e-9)
            h = max(min(1e-9, 0.25 * span), 8 * np.spacing(_TWO_PI))
            before = self.motion.tool_pole(np.array([phi - h]))[0]  # the law is linear there (constant velocity)
            after = self.motion.tool_pole(np.array([phi]))[0]
            before = before + (before - self.motion.tool_pole(np.array([phi - 2 * h]))[0])  # extrapolated to phi
            at = _after_jump(self.spec.motion, phi + (_TWO_PI if phi < self.start else 0.0), phi)
            same = [k for k, c in enumerate(out) if c[0] == at]
            if same:  # the same corner: its pole before stays, its pole after is this jump's
                before = out.pop(same[0])[1]
            out.append((at, before, after, float(np.linalg.norm(after - before)) / scale))
        return [c for c in out if c[3] > 1e-12]  # two jumps that cancel leave no corner

    def _trim(self):
        """The kept pieces in the order the cam's boundary runs (split where the curve has a break: a
        section's end, a motion join) and the loops cut away, ``(phi_a, phi_b)``."""
        if self.spec.contact == "knife":
            pieces, loops = self._trim_loops()
            return self._split([((pc.w0, pc.w1), None) for pc in pieces]), loops
        scale = self.spec.prime_radius + self.spec.stroke
        if self.spec.contact == "flat":  # the arcs in the order of the boundary, joined along a corner's line
            self.planes = face_depth(self.motion, self.tool, self.start, self.corner_angles)
            arcs, cuts = face_boundary(self.branch, self.planes.depth, 1e-13 * self._reach(),
                                       corner_lines(self.branch, self.motion, self.tool), scale)
            chain = [(span, edge if k + 1 == len(spans) else None) for spans, edge in arcs
                     for k, span in enumerate(spans)]
        else:  # every cut a crossing, in the order the cam's boundary runs
            depth = roller_depth(self.pitch_points, self.spec.roller_radius, self.start)
            circles = [(k, self.pitch_points([sec[1]])[0], self.spec.roller_radius)
                       for k, sec in enumerate(self.branch.sections) if sec[0] == "corner"]
            cuts = kept_runs(self.branch, depth, KEEP_SLACK * scale, meet=1e-6 * scale, circles=circles)
            chain = []
            for (_, wb), (wa, _) in zip(cuts, cuts[1:] + cuts[:1]):
                chain += [((wb, wa), None)] if wb < wa else [((wb, 1.0), None), ((0.0, wa), None)]
            chain = sorted(c for c in chain if c[0][1] > c[0][0]) if cuts else [((0.0, 1.0), None)]
        loops = tuple((self._phi(wa), self._phi(wb)) for wa, wb in cuts)
        pieces = self._split(chain)
        first = next((k for k, pc in enumerate(pieces) if pc.curve is self.branch and pc.w0 == 0.0), 0)
        return pieces[first:] + pieces[:first], loops  # from w = 0, the start angle, where it is kept

    def _split(self, chain):
        """Pieces of the chain ``[((w0, w1), edge)]`` (a stretch of the branch walked from ``w0`` to ``w1``,
        then the straight ``edge`` or None), split at the curve's breaks in the order they are walked."""
        breaks = self.branch.breaks(self.spec.motion)
        out = []
        for (w0, w1), edge in chain:
            lo, hi = min(w0, w1), max(w0, w1)
            inner = breaks[(breaks > lo + 1e-12) & (breaks < hi - 1e-12)]
            edges = [w0, *(inner if w1 > w0 else inner[::-1]).tolist(), w1]
            out += [Piece(self.spec.contact, self.branch, a, b) for a, b in zip(edges[:-1], edges[1:])]
            out += [Piece(self.spec.contact, edge, 0.0, 1.0)] if edge is not None else []
        return tuple(out)

    def _trim_loops(self):
        w = np.linspace(0.0, 1.0, 4 * _SCAN + 1)
        pts = self.branch(w)
        ii, jj, ti, tj = polyline_self_intersections(pts)
        # the scan is closed: its first and last edges meet at the start (an ulp or so apart, the angle
        # a turn later), and read as crossing there would cut the whole cam away as one loop
        joint = (ii == 0) & (jj == len(w) - 2)
        ii, jj, ti, tj = ii[~joint], jj[~joint], ti[~joint], tj[~joint]
        pieces, loops = [], []
        pos_e, pos_f, start = -1, 0.0, 0.0
        step = w[1] - w[0]
        while True:
            pick = next_crossing(ii, jj, ti, tj, pos_e, pos_f)
            if pick is None:
                break
            ea, eb = int(ii[pick]), int(jj[pick])
            wa = w[ea] + ti[pick] * step
            wb = w[eb] + tj[pick] * step
            wa, wb = refine_crossing(self.branch, wa, wb, w[max(ea - 2, 0)], w[min(ea + 3, len(w) - 1)],
                             w[max(eb - 2, 0)], w[min(eb + 3, len(w) - 1)])
            pieces.append(Piece(self.spec.contact, self.branch, start, wa))
            loops.append((self._phi(wa), self._phi(wb)))
            start = wb
            pos_e, pos_f = eb, float(tj[pick])
        pieces.append(Piece(self.spec.contact, self.branch, start, 1.0))
        return tuple(pieces), tuple(loops)

    def _phi(self, w):
        return float(np.mod(self.branch.phi([w])[0], _TWO_PI))

    # -- exact curves ---------------------------------------------------------------------
    def contact(self, phi):
        """Contact at cam angles ``phi``: points and unit outward normals of the cam (cam frame), and
        the contact point and tool normal in the follower frame. Returns ``(q, n, c, m)``, each ``(n, 2)``."""
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        u, _ = touching(self.tool, self.motion.tool_pole(phi), "near")
        c, _, m = self.tool.evaluate(u)
        q = self.motion.to_blank(c, phi)
        n = -self.motion.rotate_to_blank(m, phi)
        return q, n, c, m

    def profile_points(self, phi):
        """Points of the (untrimmed) envelope at cam angles ``phi``, ``(n, 2)``."""
        return self.contact(phi)[0]

    def pitch_points(self, phi):
        """The pitch curve (path of the roller centre or knife tip) at cam angles ``phi``, ``(n, 2)``."""
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        return self.motion.to_blank(np.broadcast_to(self.reference, phi.shape + (2,)), phi)

    def pitch_curvature_radius(self, phi):
        """Signed radius of curvature of the pitch curve (exact, from the pose derivatives), mm:
        positive where it is convex (its centre of curvature on the cam's side), ``inf`` where straight."""
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        _, dq, ddq = self.motion.path(np.broadcast_to(self.reference, phi.shape + (2,)), phi)
        speed = np.hypot(dq[:, 0], dq[:, 1])
        with np.errstate(divide="ignore"):
            return -speed ** 3 / cross2(dq, ddq)  # the pitch curve runs clockwise in the cam frame

    def curvature_radius(self, phi, h: float = 2e-4):
        """Signed radius of curvature of the generated envelope, mm (positive convex), by central
        differences of the exact branch over the cam angle (step ``h`` rad)."""
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        p = self.profile_points(np.concatenate([phi - h, phi, phi + h])).reshape(3, len(phi), 2)
        d1 = (p[2] - p[0]) / (2 * h)
        d2 = (p[2] - 2 * p[1] + p[0]) / (h * h)
        speed = np.hypot(d1[:, 0], d1[:, 1])
        with np.errstate(divide="ignore", invalid="ignore"):
            return -speed ** 3 * np.sign(self._forward(phi)) / cross2(d1, d2)

    def _forward(self, phi):
        """+1 where the envelope runs the same way as the pitch curve (or the cam angle), -1 in a loop."""
        q, _, _, _ = self.contact(phi)
        _, dq, _ = self.motion.path(np.broadcast_to(self.reference, q.shape), phi)
        h = 1e-6
        d = (self.profile_points(phi + h) - self.profile_points(phi - h)) / (2 * h)
        return np.where(np.einsum("ij,ij->i", d, dq) >= 0, 1.0, -1.0)

    # -- values read off the geometry ----------------------------------------------------
    def pressure_angle(self, phi):
        """Pressure angle without friction at cam angles ``phi``, rad, signed: the angle from the driven
        point's velocity (as the lift grows) to the force the cam puts on the follower (along the
        generated contact normal)."""
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        _, _, c, m = self.contact(phi)
        driven = np.broadcast_to(self.reference, c.shape) if self.spec.contact == "roller" else c
        v = lift_direction(self.spec, driven)
        f = -m
        return np.arctan2(cross2(v, f), np.einsum("ij,ij->i", v, f))

    def face_contact(self, phi):
        """Where a flat face touches, as the signed distance along the face from its foot point, mm."""
        _, _, c, _ = self.contact(phi)
        return c[:, 0] - self.reference[0] if self.spec.follower == "translating" else c[:, 0]

    @property
    def corner_loops(self) -> tuple:
        """Loops cut at a concave corner of the pitch curve (a velocity jump): the follower switches
        flanks there at once, which the motion law already asks for (flagged as a hard impact)."""
        return tuple(lp for lp in self.loops if any(_within(c, lp) for c in self.corner_angles))

    @property
    def undercut(self) -> bool:
        """True when a loop of the envelope was cut away where the motion is smooth (the roller is
        larger than the pitch curve's convex radius of curvature, or a flat-faced cam is not convex):
        the cam cannot give the motion there."""
        return len(self.loops) > len(self.corner_loops)

    # -- sampled geometry ----------------------------------------------------------------
    def _tol(self, tol, pitch: bool = False) -> tuple:
        """``tol`` checked against the cam's size ``r0 + stroke`` (``SpecError`` below its floor or above the size),
        the round-off allowance of the cam's exact points (they are computed through the follower's pose, whose
        lengths reach the pivot: ``ROUND_OFF`` of those) and how deep in the swept region the kept pieces may
        lie (a roller's ``KEEP_SLACK``, else 0). The floor is ``PRECISION`` of the size, the geometry's own
        precision, or for a roller's outline (not its ``pitch`` curve) ``ROLLER_FLOOR`` of it."""
        spec = self.spec
        size = spec.prime_radius + spec.stroke
        roller = spec.contact == "roller" and not pitch
        floor, why = (ROLLER_FLOOR, "a roller cam's 2e-7 (r0 + stroke), twice how deep in a roller its outline may "
                      "keep a loop,") if roller else (PRECISION, "the cam's own precision 1e-9 (r0 + stroke)")
        require(is_real(tol) and floor * size <= tol <= size, "tol", f"{tol!r} mm is outside [{floor * size:.6g}, "
                f"{size:.6g}] mm ({why} up to r0 + stroke)")
        return float(tol), ROUND_OFF * self._reach(), KEEP_SLACK * size if roller else 0.0

    def _reach(self) -> float:
        """The lengths the follower's pose spans, mm: the cam's size ``r0 + stroke``, the offset, the pivot
        distance and the arm (the scale of the round-off in the cam's exact points)."""
        spec = self.spec
        return spec.prime_radius + spec.stroke + abs(spec.offset) + (spec.pivot_distance or 0.0) + (spec.arm_length or 0.0)

    def _gap(self) -> float:
        """The widest gap between a kept piece's end and the next one's start (the last's end and the first's
        start), mm. The outline drops each piece's start for the previous end: its first chord moves by the
        gap, and so may its deviation."""
        ends = np.array([pc(np.array([0.0, 1.0])) for pc in self.pieces])
        return float(np.hypot(*(np.roll(ends[:, 1], 1, axis=0) - ends[:, 0]).T).max())

    def _sample(self, tol: float):
        tol, slack, keep = self._tol(tol)
        key = ("outline", tol)
        if key not in self._cache:
            gap = self._gap()
            if gap >= tol - 2 * slack - keep:
                raise GeometryError(f"the cam's kept pieces meet only within {gap:.3g} mm, not within tol {tol:.3g} mm")
            done = sample_curves(list(self.pieces), tol - 2 * slack - gap - keep, n_init=33)
            pts = np.concatenate([pts if k == 0 else pts[1:] for k, (_, pts, _) in enumerate(done)])
            pts = pts[:-1][::-1]  # closed: drop the repeated start; counter-clockwise
            # a vertex within round-off of the one before it is the same point: a knife's corner (the tip stands
            # while the velocity jumps), or the ends of a piece a few ulps long (a dwell of 1e-14 degrees). Each
            # one dropped moves a chord by at most its step, so the bound adds the steps dropped
            step = np.hypot(*(pts - np.roll(pts, 1, axis=0)).T)
            same = step <= slack
            pts = pts[~same]
            self._cache[key] = (np.ascontiguousarray(pts), max(dev for _, _, dev in done) + gap + slack
                                + float(step[same].sum()) + keep)
        return self._cache[key]

    def outline(self, tol: float = 1e-3):
        """Closed profile, ``(n, 2)`` float64, counter-clockwise, no vertex within round-off of the one before it
        (nor the last of the first); every chord within ``tol`` (mm, in ``[1e-9, 1] (r0 + stroke)``, a roller's in
        ``[2e-7, 1] (r0 + stroke)``) of the exact envelope and of the region the follower leaves uncovered."""
        return self._sample(tol)[0]

    def achieved(self, tol: float = 1e-3) -> float:
        """A proven bound (mm) of the largest chord deviation of :meth:`outline` at ``tol`` from the exact
        pieces (:mod:`gearkit.families.cam.turns`: the tangent's turn over every leg, bounded by the law),
        plus the widest gap where one kept piece hands over to the next, the steps to the vertices merged with
        the one before them and, for a roller, the keep slack (``KEEP_SLACK (r0 + stroke)``: how deep in another
        roller a loop the keep test leaves in may lie), so it bounds the outline's distance from the cam."""
        return self._sample(tol)[1]

    def pitch_outline(self, tol: float = 1e-3):
        """Closed pitch curve, counter-clockwise, and a proven bound of its chords' deviation (each phase
        of the program sampled as its own piece: the curve has a corner where the velocity jumps)."""
        tol, slack, _ = self._tol(tol, pitch=True)
        turns = CamTurns(self.spec, pitch=True)
        done = sample_curves([PitchCurve(self.motion, self.reference, turns, p0, p1)
                              for _, p0, p1, _, _ in self.spec.motion.phases()], tol - slack, n_init=33)
        pts = np.concatenate([pts if k == 0 else pts[1:] for k, (_, pts, _) in enumerate(done)])
        return np.ascontiguousarray(pts[:-1][::-1]), max(dev for _, _, dev in done) + slack

    def radii(self):
        """(smallest, largest) radius of the generated (trimmed) profile, mm: a dense scan of every
        kept piece refined by a bounded search."""
        from gearkit.families.cam.follower import phase_extreme

        lo, hi = math.inf, 0.0
        for pc in self.pieces:
            def rad(w, _pc=pc):
                return np.hypot(*_pc(np.asarray(w)).T)
            hi = max(hi, phase_extreme(rad, 0.0, 1.0, 1025))
            lo = min(lo, -phase_extreme(lambda w: -rad(w), 0.0, 1.0, 1025))
        return lo, hi


def _after_jump(program, phi: float, join: float) -> float:
    """The first float from ``phi`` (the velocity jump at ``join``, perhaps a turn later) that the law
    evaluates after the jump: ``phi`` shifted by a turn may land an ulp or two before the join, where the
    law still gives the velocity before it (the curve past the corner would start at the old pole).

    >>> from gearkit.families.cam.laws import MotionProgram
    >>> prog = MotionProgram.rise_dwell_return(10.0, 20.0, 20.0, 40.0, "constant_velocity")
    >>> join = prog.jumps()[2][0]
    >>> at = _after_jump(prog, join + _TWO_PI, join)
    >>> v = lambda x: float(prog.evaluate(np.array([x]))[1][0])
    >>> v(at) == v(join), v(np.nextafter(at, -np.inf)) == v(join - 1e-9)
    (True, True)
    """
    # a quarter of the phases either side inward at most (a dwell between two jumps may be 1e-11 rad
    # short), and a few ulps at least (one of 1e-153 rad puts both jumps at one angle: read as one)
    ends = np.array([p[1] for p in program.phases()] + [_TWO_PI])
    spans = np.diff(ends)
    k = int(np.argmin(np.abs((ends[1:] - join + math.pi) % _TWO_PI - math.pi)))  # the phase ending at the join
    reach = max(min(1e-9, 0.25 * spans[k], 0.25 * spans[(k + 1) % len(spans)]), 8 * np.spacing(_TWO_PI))
    v_before, v_after = program.evaluate(np.array([join - reach, join + reach]))[1]

    def after(x):
        v = program.evaluate(np.array([x]))[1][0]
        return abs(v - v_after) < abs(v - v_before)

    x = float(phi)
    for _ in range(64):  # the turn's round-off is a few ulps
        if after(x) and after(np.nextafter(x, -np.inf)):
            x = float(np.nextafter(x, -np.inf))
        elif not after(x):
            x = float(np.nextafter(x, np.inf))
        else:
            return x
    raise GeometryError(f"the velocity jump at {join!r} rad was not found within 64 ulps of {phi!r}")


def _within(phi, loop) -> bool:
    """``phi`` lies in the loop's cam-angle interval (which may wrap through 0)."""
    a, b = loop
    return (phi - a) % _TWO_PI <= (b - a) % _TWO_PI


@functools.lru_cache(maxsize=32)
def cam_profile(spec) -> CamProfile:
    """Generate the cam of ``spec`` (cached by spec).

    Examples
    --------
    >>> from gearkit.families.cam import CamSpec, MotionProgram
    >>> spec = CamSpec(40.0, MotionProgram.rise_dwell_return(10.0, 90.0, 30.0, 90.0), roller_radius=8.0)
    >>> prof = cam_profile(spec)
    >>> prof.undercut, round(prof.achieved(1e-3) / 1e-3, 1) <= 1.0
    (False, True)
    >>> [round(r, 6) for r in prof.radii()]  # base circle 40 - 8, top 40 + 10 - 8
    [32.0, 42.0]
    """
    return CamProfile(spec)
