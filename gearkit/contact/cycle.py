"""One mesh cycle evaluated: bounds reduced per driver angle, pairs in contact, their time average.

:class:`Cycle` solves the bounds (:func:`gearkit.contact.solver.solve`) at driver angles, over the
transverse slices of a helical pair, and reduces them: the mate's working and reverse positions, the
driver halves (pairs) within the contact tolerance of the working position, and each pair's margin
to contact. :func:`contact_ratio` time-averages the pairs in contact, finding the instants a pair
enters or leaves contact between steps.
"""
from __future__ import annotations

import numpy as np

from gearkit.contact.solver import solve

__all__ = ["Cycle", "contact_ratio"]

#: iterations for the instants a pair enters or leaves contact
_EXTRAPOLATE = 8


class Cycle:
    """Bounds at driver angles ``phi`` (n,) over the slice shifts (S,), reduced per angle (the working
    bound only with ``working_only``: the reverse one then keeps its search values)."""

    def __init__(self, mesh, phi, shifts, contact_tol, working_only=False):
        self.phi = np.asarray(phi, dtype=float)
        n, s = len(self.phi), len(shifts)
        # ``working_only``: the reverse bound keeps its search values (enough for :meth:`margin`)
        bounds = ((0,) if mesh.working == 1 else (1,)) if working_only else (0, 1)
        b = solve(mesh, (self.phi[:, None] + shifts[None, :]).ravel(), contact_tol, bounds)
        kk = b.teeth.shape[1]

        def grid(a):
            return a.reshape((n, s, kk) + a.shape[2:])
        self.teeth = grid(b.teeth)
        self.value, self.exact, self.arm = grid(b.value), grid(b.exact), grid(b.arm)
        self.point, self.normal = grid(b.point), grid(b.normal)
        self.piece1, self.piece2, self.rho2 = grid(b.piece1), grid(b.piece2), grid(b.rho2)
        self.corner1, self.corner2 = grid(b.corner1), grid(b.corner2)
        self.upper = self.value[..., 0].min(axis=(1, 2, 3))
        self.lower = -self.value[..., 1].min(axis=(1, 2, 3))
        wb = 0 if mesh.working == 1 else 1
        self.wb = wb
        self.work = self.upper if wb == 0 else self.lower
        v = self.value[..., wb]
        flat = v.reshape(n, -1).argmin(axis=1)
        best = v.reshape(n, -1)[np.arange(n), flat]
        arm_best = self.arm[..., wb].reshape(n, -1)[np.arange(n), flat]
        gap = (v - best[:, None, None, None]) * self.arm[..., wb]
        # a bound is known to about noise / arm (rad): a contact whose normal nearly passes through the
        # mate's centre (a crest) sets a position that is uncertain by much more than a firm one
        noise = mesh.noise * self.arm[..., wb] / np.maximum(arm_best, 1e-9 * mesh.arm_scale)[:, None, None, None]
        # unrefined halves are farther than the search margin: their search value, at the arm scale
        rough = (v - best[:, None, None, None]) * mesh.arm_scale
        self.excess = np.where(self.exact[..., wb], gap - noise, rough)  # (n, S, K, 2), mm
        self.touch = self.excess <= contact_tol
        self.pid = 2 * self.teeth[..., None] + np.arange(2)
        self.ids = np.where(self.touch, self.pid, np.iinfo(np.int64).min)
        self.contact_tol = contact_tol
        self.working, self.arm_scale = mesh.working, mesh.arm_scale

    def margin(self, pid):
        """``sqrt(clearance beyond round-off) - sqrt(contact_tol)`` of pair ``pid[i]`` at angle ``i`` (its
        best slice): <= 0 in contact; linear in the driver angle where flanks part (clearance grows with
        the square of the angle). Large where the pair is out of reach."""
        n = len(self.phi)
        mine = self.pid.reshape(n, -1) == np.asarray(pid)[:, None]
        excess = np.where(mine, self.excess.reshape(n, -1), np.inf).min(axis=1)
        return np.sqrt(np.clip(np.nan_to_num(excess, posinf=1e6), 0.0, None)) - np.sqrt(self.contact_tol)

    def depth(self, ref, bound):
        """Overlap (mm along the normal; negative: clearance) of every entry ``(n, S, K, 2)`` on ``bound``:
        on the working bound beyond the ideal position ``ref``, on the reverse bound beyond the
        working position (no position at all: jamming). Unrefined entries at the arm scale."""
        pos = self.value[..., bound] if bound == 0 else -self.value[..., bound]
        arm = np.where(self.exact[..., bound], self.arm[..., bound], self.arm_scale)
        if bound == self.wb:
            return self.working * (ref - pos) * arm
        return self.working * (pos - self.work[:, None, None, None]) * arm

    def pair_depth(self, ref, bound, pid):
        """:meth:`depth` of pair ``pid[i]`` at angle ``i`` (its deepest slice; -inf out of reach)."""
        n = len(self.phi)
        mine = self.pid.reshape(n, -1) == np.asarray(pid)[:, None]
        return np.where(mine, self.depth(ref, bound).reshape(n, -1), -np.inf).max(axis=1)

    def pair_sets(self):
        """The set of pair ids (2 tooth + half) in contact at each angle."""
        return [set(r[r != np.iinfo(np.int64).min].tolist()) for r in self.ids.reshape(len(self.phi), -1)]

    def extreme(self, bound):
        """Index tuples ``(n, s, k, h)`` of the extreme contact of ``bound`` at every angle."""
        v = self.value[..., bound].reshape(len(self.phi), -1)
        flat = np.argmin(v, axis=1)
        return (np.arange(len(self.phi)),) + np.unravel_index(flat, self.value.shape[1:4])


def contact_ratio(mesh, phi, ev, shifts, contact_tol):
    """Time average of the pairs in contact over ``phi[0] .. phi[-1]`` (one cycle).

    Between two steps where a pair enters or leaves contact, the instant is found on
    :meth:`Cycle.margin` (linear in the angle where the flanks part) by extrapolating its last two
    values out of contact, bisecting while there are not two; each iteration is one evaluation of
    every pending instant.
    """
    sets = ev.pair_sets()
    period = phi[-1] - phi[0]
    total = 0.0
    todo = []  # (step, pair id, in at the step)
    for j in range(len(phi) - 1):
        a, b = sets[j], sets[j + 1]
        total += len(a & b) * (phi[j + 1] - phi[j])
        todo += [(j, pid, pid in a) for pid in a ^ b]
    if todo:
        j = np.array([t[0] for t in todo])
        pid = np.array([t[1] for t in todo])
        start_in = np.array([t[2] for t in todo])
        # bracket: a point in contact (g <= 0) and one out of it (g > 0); out of contact g is linear in
        # the angle, so the last two outside points extrapolate to the instant (bisection otherwise)
        g0, g1 = _margin_at(ev, j, pid), _margin_at(ev, j + 1, pid)
        inside = np.where(start_in, phi[j], phi[j + 1])
        out1, gout1 = np.where(start_in, phi[j + 1], phi[j]), np.maximum(np.where(start_in, g1, g0), 1e-300)
        out2, gout2 = np.full(len(todo), np.nan), np.full(len(todo), np.nan)
        for _ in range(_EXTRAPOLATE):
            with np.errstate(invalid="ignore", divide="ignore"):
                x = out1 - gout1 * (out1 - out2) / (gout1 - gout2)
            ok = np.isfinite(x) & ((x - inside) * (x - out1) < 0)
            x = np.where(ok, x, 0.5 * (inside + out1))
            g = Cycle(mesh, x, shifts, contact_tol, working_only=True).margin(pid)
            hit = g <= 0
            inside = np.where(hit, x, inside)
            out2, gout2 = np.where(hit, out2, out1), np.where(hit, gout2, gout1)
            out1, gout1 = np.where(hit, out1, x), np.where(hit, gout1, g)
        with np.errstate(invalid="ignore", divide="ignore"):
            cut = out1 - gout1 * (out1 - out2) / (gout1 - gout2)
        # the last bracket holds the instant: an extrapolation a last bit beyond its inside end (the
        # margin bends where the clearance meets round-off) stops there
        cut = np.where(np.isfinite(cut), np.clip(cut, np.minimum(inside, out1), np.maximum(inside, out1)),
                       0.5 * (inside + out1))
        total += float(np.sum(np.where(start_in, cut - phi[j], phi[j + 1] - cut)))
    return total / period


def _margin_at(ev, steps, pid):
    """:meth:`Cycle.margin` of pair ``pid[i]`` at grid step ``steps[i]``."""
    n = len(ev.phi)
    flat = ev.pid.reshape(n, -1)[steps] == pid[:, None]
    excess = np.where(flat, ev.excess.reshape(n, -1)[steps], np.inf).min(axis=1)
    return np.sqrt(np.clip(np.nan_to_num(excess, posinf=1e6), 0.0, None)) - np.sqrt(ev.contact_tol)
