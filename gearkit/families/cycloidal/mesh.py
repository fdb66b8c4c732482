"""The simulated mesh of a pin-wheel drive: which pins touch the generated disc, which carry load,
and how far the disc turns before the first contact (backlash).

The disc is the generated one (the exact envelope of its generating pin, over the rolls the
kernel kept); the pins are the nominal ones (``R_Z``, ``r_Z``, running eccentricity ``e``),
placed in the disc's frame for a relative angle ``psi0`` (reference digest §1.3): the pin ring's centre sits at
``-e (sin Z_e psi0, cos Z_e psi0)`` and pin k at polar angle ``psi0 - 2 pi k/Z_b`` about it
(in the digest's frame, turned into gearkit's by the same phase as the closed forms). A
pin's clearance is its centre's distance from the exact generated disc minus ``r_Z``; it touches
when the clearance is within ``contact_tol``. It carries load in direction ``+1`` when its contact
force (along the common normal, pushing the disc) turns the disc counter-clockwise.

The mesh repeats, turned by one disc pitch, after ``Delta psi0 = 2 pi |dz| / (Z_b Z_g)``, so time
averages are taken over that period; uniform ``psi0`` is uniform crank angle.
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from gearkit.distances import nearest
from gearkit.families.cycloidal.disc import disc_profile
from gearkit.families.cycloidal.drive import DriveSpec, frame_phase, turn_polar
from gearkit.values import frozen

__all__ = ["CONTACT_TOL", "MeshState", "MeshStats", "pin_centres", "mesh_state", "simulate_mesh", "backlash"]

#: a pin touches when its clearance is below this fraction of the pin-circle radius (clearances
#: are exact to ~1e-13 of it; a pin leaving a pointed tip does so tangentially, its clearance
#: growing with the square of the angle, so the threshold must be far below the sampling)
CONTACT_TOL = 1e-11
#: a foot is certified the nearest when it lies within this fraction of the pin-circle radius of the bound
#: every disc point keeps (round-off of the closed forms: ~1e-15 of the radii)
CERTIFY_TOL = 1e-13
_FLIP_X = np.array([-1.0, 1.0])
#: rolls in the table of the pin centre's polar angle (its cubic interpolation finds the foot of a pin
#: centre on the theoretical curve within the certificate's tolerance; one Newton step any other's)
_ANGLE_TABLE = 2049


def pin_centres(spec: DriveSpec, psi0, turn: float = 0.0):
    """Nominal pin centres in the disc frame at relative angle ``psi0`` (rad), ``(Z_b, 2)`` mm
    (``(n, Z_b, 2)`` for ``n`` angles).

    ``turn`` rotates the disc counter-clockwise by that angle (rad) about its centre with the
    crank held (the pins move clockwise relative to it).
    """
    psi = np.asarray(psi0, dtype=float)[..., None]
    z_e = spec.equivalent_pins
    e, big_r = spec.eccentricity, spec.pin_circle_radius
    beta = psi - 2.0 * math.pi * np.arange(spec.pins) / spec.pins
    c = np.stack([big_r * np.sin(beta) - e * np.sin(z_e * psi), big_r * np.cos(beta) - e * np.cos(z_e * psi)], -1)
    return turn_polar(c, frame_phase(spec) + turn)


class _Outline:
    """Nearest points on the generated disc, exact to machine precision.

    A query point is turned into tooth 0's sector and folded into the half tooth's wedge by the
    disc's symmetry; its nearest disc point is then on the half tooth or on the half tooth's
    mirror image in the tooth's or the space's centre line. The half tooth is the generating
    pin's envelope over the rolls the kernel kept (:meth:`CycloidalDisc.flank_rolls`), plus the
    tip arc of a truncated disc; Newton's method in the roll finds the foot of the perpendicular.

    The foot is first sought at the roll where the generating pin's centre had the query's polar
    angle (a table of ``_ANGLE_TABLE`` rolls, where one roll interval is kept and that angle is
    monotone), then one Newton step from it, and kept where it is certified the nearest point of
    the whole outline (:meth:`_certified`: every pin near the theoretical curve, all of them in an
    unmodified drive).
    Every other query (``fast=False``: all) starts from its nearest of ``samples`` points per roll
    interval, for itself and its mirror images.
    """

    def __init__(self, spec: DriveSpec, samples: int = 128, fast: bool = True):
        disc = disc_profile(spec)
        self.disc = disc
        self.half = math.pi / disc.teeth
        rolls = [np.linspace(a, b, samples) for a, b in disc.flank_rolls()]
        self.rolls = np.concatenate(rolls)
        self.bounds = np.concatenate([np.repeat([[a[0], a[-1]]], len(a), axis=0) for a in rolls])
        pts = disc.at_roll(self.rolls)
        self.points = pts
        self.spacing = float(np.linalg.norm(np.diff(pts, axis=0), axis=1).max())
        # unit normal of the space centre line (polar angle pi/z), towards the tooth; the samples' least
        # signed distances from it and from the tooth centre line bound the mirrored candidates' distances
        self.space_normal = np.array([-math.cos(self.half), math.sin(self.half)])
        self.least_side = (float((pts @ self.space_normal).min()), float(pts[:, 0].min()))
        first = disc.half.pieces[0]
        self.tip = first.curve if not hasattr(first.curve, "solve") else None
        self.by_angle = self._angle_table(rolls) if fast else None
        self.certify_tol = CERTIFY_TOL * spec.pin_circle_radius

    def _angle_table(self, rolls):
        """``(polar angles, rolls, d roll / d angle)`` of the generating pin's centre, sorted by angle,
        when one roll interval is kept and the centre's polar angle is strictly monotone in it (else None)."""
        if len(rolls) != 1:
            return None
        table = np.linspace(rolls[0][0], rolls[0][-1], _ANGLE_TABLE)
        (x, y), (dx, dy) = (v.T for v in self.disc.centre_at_roll(table, derivative=True))
        ang = np.arctan2(x, y)
        turn = (y * dx - x * dy) / (x * x + y * y)  # d angle / d roll
        if not (np.all(turn > 0) or np.all(turn < 0)) or not (np.all(np.diff(ang) * turn[0] > 0)):
            return None
        order = np.argsort(ang)
        return ang[order], table[order], 1.0 / turn[order]

    def _start(self, q):
        """Distance to the sampled flank and the nearest sample's index."""
        return nearest(self.points, q)

    def _by_angle(self, q):
        """Start rolls read off the pin centre's polar angle: the roll at which the generating pin's
        centre had the query's polar angle (a pin centre on the theoretical curve has its foot there),
        by cubic Hermite interpolation in the table (the ends beyond it)."""
        ang, rolls, slope = self.by_angle
        a = np.arctan2(q[:, 0], q[:, 1])
        i = np.clip(np.searchsorted(ang, a) - 1, 0, len(ang) - 2)
        h = ang[i + 1] - ang[i]
        t = np.clip((a - ang[i]) / h, 0.0, 1.0)
        t2, t3 = t * t, t * t * t
        return ((2.0 * t3 - 3.0 * t2 + 1.0) * rolls[i] + (t3 - 2.0 * t2 + t) * h * slope[i]
                + (3.0 * t2 - 2.0 * t3) * rolls[i + 1] + (t3 - t2) * h * slope[i + 1])

    def _refine(self, q, x, lo, hi, steps: int = 40):
        """Newton in the roll from the rolls ``x`` within ``[lo, hi]`` (at most ``steps`` steps): exact
        distance to the flank (or the tip arc), foot point and the foot's roll on the flank."""
        x = np.array(x, dtype=float)
        lo, hi = np.broadcast_to(lo, x.shape), np.broadcast_to(hi, x.shape)
        span = hi - lo
        act = np.arange(len(q))
        for _ in range(steps):
            xa, qa = x[act], q[act]
            p, d1, dd = self.disc.at_roll(xa, derivatives=True)  # exact derivatives in the roll
            r = p - qa
            f = np.einsum("ij,ij->i", r, d1)
            gn = np.einsum("ij,ij->i", d1, d1)
            x_new = np.clip(xa - f / np.maximum(gn + np.einsum("ij,ij->i", r, dd), 0.1 * gn), lo[act], hi[act])
            moved = np.abs(x_new - xa)
            x[act] = x_new
            act = act[moved > 1e-8 * span[act]]
            if not len(act):
                break
        foot = self.disc.at_roll(x)
        best = np.linalg.norm(foot - q, axis=1)
        roll = x
        if self.tip is not None:  # truncated disc: the tip arc about the centre
            psi = np.arctan2(q[:, 0], q[:, 1])
            ang = np.clip(psi, min(self.tip.psi0, self.tip.psi1), max(self.tip.psi0, self.tip.psi1))
            p = self.tip.radius * np.stack([np.sin(ang), np.cos(ang)], -1)
            dist = np.linalg.norm(p - q, axis=1)
            better = dist < best
            best = np.where(better, dist, best)
            foot = np.where(better[:, None], p, foot)
        return best, foot, roll

    def nearest(self, q):
        """Distance to the disc outline and the nearest outline point for each query point."""
        k = np.round(np.arctan2(q[:, 0], q[:, 1]) / (2.0 * self.half))
        local = turn_polar(q, -k * 2.0 * self.half)
        flip = np.where(local[:, :1] < 0, _FLIP_X, 1.0)
        local = local * flip
        dist, foot = np.full(len(q), np.inf), np.zeros((len(q), 2))
        rest = np.arange(len(q))
        if self.by_angle is not None:
            dist, foot, certified = self._certified(local)
            rest = np.flatnonzero(~certified)
        if len(rest):
            d, f = self._nearest_by_samples(local[rest])
            better = d < dist[rest]
            dist[rest] = np.where(better, d, dist[rest])
            foot[rest] = np.where(better[:, None], f, foot[rest])
        return dist, turn_polar(foot * flip, k * 2.0 * self.half)

    def _certified(self, local):
        """Distance, foot and whether the foot is certified the nearest point of the whole outline: at
        the roll :meth:`_by_angle` reads off (a pin centre on the theoretical curve), else after one
        Newton step in the roll from it.

        The disc lies outside every position of the grinding pin (radius ``r``): a query at ``|q - c|``
        from the pin's centre ``c`` at some roll is at least ``r - |q - c|`` from every disc point, so a
        foot at that roll attaining it (within ``certify_tol``: the query on the radius from the
        pin's centre to the foot) is the nearest point, on this flank or any other.
        """
        lo, hi = self.bounds[0]
        x = np.clip(self._by_angle(local), lo, hi)
        dist, foot, ok = self._check(local, x)
        redo = np.flatnonzero(~ok)
        if redo.size:
            q, x = local[redo], x[redo]
            p, d1, dd = self.disc.at_roll(x, derivatives=True)
            r = p - q
            f = np.einsum("ij,ij->i", r, d1)
            gn = np.einsum("ij,ij->i", d1, d1)
            x = np.clip(x - f / np.maximum(gn + np.einsum("ij,ij->i", r, dd), 0.1 * gn), lo, hi)
            dist[redo], foot[redo], ok[redo] = self._check(q, x)
        return dist, foot, ok

    def _check(self, q, x):
        """Distance and foot at the rolls ``x``, and whether the foot is certified (:meth:`_certified`)."""
        dist, foot, _ = self._refine(q, x, *self.bounds[0], steps=0)
        reach = np.linalg.norm(q - self.disc.centre_at_roll(x), axis=1) + dist
        return dist, foot, reach <= self.disc.pin_radius + self.certify_tol

    def _nearest_by_samples(self, local):
        """The nearest of the three candidates (the query and its mirror images in the space and the
        tooth centre lines), each by Newton from its nearest flank sample: ``(dist, foot)``, local frame."""
        def mirror_s(p):  # mirror image in the space centre line (polar pi/z)
            return turn_polar(turn_polar(p, -self.half) * _FLIP_X, self.half)
        cands = (local, mirror_s(local), local * _FLIP_X)
        sides = (local @ self.space_normal + self.least_side[0], local[:, 0] + self.least_side[1])
        coarse = np.full((3, len(local)), np.inf)
        idx = np.zeros(coarse.shape, dtype=np.intp)
        coarse[0], idx[0] = self._start(local)
        # a mirrored candidate lies at least as far from every sample as the query from the mirror
        # line (plus the samples' least distance from it): past coarse[0] + 2 spacing it cannot be
        # kept, so its nearest sample is not searched (the same candidates are kept as with a search)
        bound = coarse[0] + 2.0 * self.spacing
        for c, side in zip((1, 2), sides):
            sel = np.flatnonzero(side <= bound)
            coarse[c, sel], idx[c, sel] = self._start(cands[c][sel])
        keep = coarse <= coarse.min(axis=0) + 2.0 * self.spacing
        dist = np.full(coarse.shape, np.inf)
        feet = np.zeros(coarse.shape + (2,))
        for c, p in enumerate(cands):
            sel = np.flatnonzero(keep[c])
            i = idx[c, sel]
            dist[c, sel], feet[c, sel], _ = self._refine(p[sel], self.rolls[i], self.bounds[i, 0], self.bounds[i, 1])
        feet[1] = mirror_s(feet[1])
        feet[2] = feet[2] * _FLIP_X
        which = np.argmin(dist, axis=0)
        n = np.arange(len(local))
        return dist[which, n], feet[which, n]


@frozen
class MeshState:
    """One instant of the mesh (disc frame, mm), or ``n`` instants stacked along a first axis.

    centres, contact : (Z_b, 2) float64, mm (pin centres, nearest disc points); clearance :
    (Z_b,) float64, mm; touching : (Z_b,) bool; arm : (Z_b,) float64, mm, the signed moment arm
    about the disc centre of each pin's push on the disc (positive: counter-clockwise).
    """

    psi0: float | np.ndarray
    centres: np.ndarray
    clearance: np.ndarray
    contact: np.ndarray
    touching: np.ndarray
    arm: np.ndarray

    def load_carrying(self, direction: int = 1) -> np.ndarray:
        """Pins that touch and push the disc in ``direction`` (+1 counter-clockwise, -1 clockwise);
        a pin whose push passes through the disc centre (arm below 1e-9 of the size) carries none."""
        return self.touching & (direction * self.arm > 1e-9 * float(np.abs(self.centres).max()))


def _state(spec, outline, psi0, turn, contact_tol):
    c = pin_centres(spec, psi0, turn)
    shape = c.shape[:-1]
    dist, foot = outline.nearest(c.reshape(-1, 2))
    foot = foot.reshape(c.shape)
    clearance = dist.reshape(shape) - spec.pin_radius
    push = foot - c  # the pin pushes the disc along the common normal, from the pin's centre
    push /= np.linalg.norm(push, axis=-1, keepdims=True)
    arm = foot[..., 0] * push[..., 1] - foot[..., 1] * push[..., 0]
    return MeshState(psi0, c, clearance, foot, clearance <= contact_tol, arm)


def _tols(spec, contact_tol):
    contact_tol = CONTACT_TOL * spec.pin_circle_radius if contact_tol is None else float(contact_tol)
    return _outline(spec), contact_tol


@lru_cache(maxsize=16)
def _outline(spec):
    return _Outline(spec)


def mesh_state(spec: DriveSpec, psi0: float = 0.0, contact_tol: float | None = None):
    """The mesh at relative angle ``psi0`` (rad, scalar or ``(n,)``); pins touch within
    ``contact_tol`` (mm, default ``CONTACT_TOL * R_Z``)."""
    outline, contact_tol = _tols(spec, contact_tol)
    return _state(spec, outline, psi0, 0.0, contact_tol)


@frozen
class MeshStats:
    """Counts over one mesh period (``samples`` instants, uniform in crank angle).

    ``touching`` and ``loaded`` are ``(mean, min, max)``; ``loaded`` is for the counter-clockwise
    push (direction +1), ``loaded_reverse`` for the clockwise one.
    """

    samples: int
    touching: tuple
    loaded: tuple
    loaded_reverse: tuple


def simulate_mesh(spec: DriveSpec, samples: int = 4000, contact_tol: float | None = None):
    """Run the disc through one mesh period and count touching and load-carrying pins.

    The mesh repeats, turned by one disc pitch, after ``Delta psi0 = 2 pi |dz| / (Z_b Z_g)``; that
    period is sampled at ``samples`` midpoints.

    The instants ``psi0`` and ``Delta psi0 - psi0`` are mirror images of each other (the pins, and
    the disc, are symmetric about its space centre lines: pin k at ``-psi0`` is pin ``-k`` at
    ``psi0`` mirrored, and one period later the mesh is the same turned by a pitch), so the same
    pins touch at both and a pin pushing counter-clockwise at one pushes clockwise at the other. The
    midpoints pair up that way: the first half of them (the middle one included) is simulated and
    the second half read off it by the mirror.
    """
    outline, contact_tol = _tols(spec, contact_tol)
    period = 2.0 * math.pi * abs(spec.tooth_difference) / (spec.pins * spec.lobes)
    half = (samples + 1) // 2
    psis = (np.arange(half) + 0.5) / samples * period
    st = _state(spec, outline, psis, 0.0, contact_tol)
    touching, ccw, cw = (v.sum(axis=-1) for v in (st.touching, st.load_carrying(1), st.load_carrying(-1)))
    mirrored = slice(samples - half - 1, None, -1) if samples > half else slice(0, 0)  # instant i <- n - 1 - i

    def stats(v, v_mirror):
        v = np.concatenate([v, v_mirror[mirrored]])
        return float(v.mean()), int(v.min()), int(v.max())
    return MeshStats(samples, stats(touching, touching), stats(ccw, cw), stats(cw, ccw))


def backlash(spec: DriveSpec, psi0: float = 0.0, direction: int = 1, contact_tol: float | None = None):
    """Angle (rad) the disc turns, crank held, before a pin touches: the backlash of the mesh.

    Returns ``(angle, state)`` with the mesh state at first contact. ``direction`` +1 turns the disc
    counter-clockwise. 0 when a pin already touches (or interferes) at ``psi0``; ``inf`` when no pin
    is met within one disc pitch.
    """
    from gearkit.roots import brentq

    outline, contact_tol = _tols(spec, contact_tol)

    def gap(turn):
        return float(_state(spec, outline, psi0, direction * turn, contact_tol).clearance.min())

    g0 = gap(0.0)
    if g0 <= contact_tol:
        return 0.0, _state(spec, outline, psi0, 0.0, contact_tol)
    lo, hi = 0.0, g0 / abs(spec.disc_pitch_radius)
    while gap(hi) > 0.0:
        lo, hi = hi, 2.0 * hi
        if lo > 2.0 * math.pi / spec.lobes:
            return math.inf, _state(spec, outline, psi0, 0.0, contact_tol)
    angle = brentq(gap, lo, hi, xtol=1e-16, rtol=1e-15)
    return angle, _state(spec, outline, psi0, direction * angle, contact_tol)
