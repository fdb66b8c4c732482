"""One mesh cycle evaluated: bounds reduced per driver angle, pairs in contact, their time average.

:class:`Cycle` solves the bounds (:func:`gearkit.contact.solver.solve`) at driver angles, over the
transverse slices of a helical pair, and reduces them: the mate's working and reverse positions, the
driver halves (pairs) within the contact tolerance of the working position, and each pair's margin
to contact. :func:`contact_ratio` time-averages the pairs in contact, finding the instants a pair
enters or leaves contact between steps.
"""
from __future__ import annotations

import numpy as np

from gearkit.contact.continuation import close
from gearkit.contact.solver import solve

__all__ = ["Cycle", "INSTANT_TOL", "contact_ratio"]

#: most iterations for the instants a pair enters or leaves contact, and their tolerance (of a cycle)
_EXTRAPOLATE = 8
INSTANT_TOL = 1e-8


class Cycle:
    """Bounds at driver angles ``phi`` (n,) over the slice shifts (S,), reduced per angle (the working
    bound only with ``working_only``: the reverse one then keeps its search values; ``near``: ``(cycle,
    position)``, the minimisers start from another cycle's, ``phi`` at ``position`` on its grid)."""

    def __init__(self, mesh, phi, shifts, contact_tol, working_only=False, near=None):
        self.phi = np.asarray(phi, dtype=float)
        n, s = len(self.phi), len(shifts)
        # ``working_only``: the reverse bound keeps its search values (enough for :meth:`margin`)
        bounds = ((0,) if mesh.working == 1 else (1,)) if working_only else (0, 1)
        seeds = None if near is None else near[0].seeds() + (near[1],)
        b = solve(mesh, (self.phi[:, None] + shifts[None, :]).ravel(), contact_tol, bounds, lanes=s, seeds=seeds)
        self._rows = (b.row_code, b.row_t)
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
        self.contact_tol = contact_tol
        self.working, self.arm_scale = mesh.working, mesh.arm_scale

    def seeds(self):
        """The refined rows' codes, sorted, and their minimisers: starts for a cycle at angles between these
        (``near`` of the constructor: this cycle and the angles' positions on its grid, float ``(n,)``)."""
        if not hasattr(self, "_seeds"):
            order = np.argsort(self._rows[0], kind="stable")
            self._seeds = (self._rows[0][order], self._rows[1][order])
        return self._seeds

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

    def pair_counts(self):
        """The number of pairs (driver halves, over all slices) in contact at each angle."""
        return np.bincount(_entries(self)[0], minlength=len(self.phi))

    def extreme(self, bound):
        """Index tuples ``(n, s, k, h)`` of the extreme contact of ``bound`` at every angle."""
        v = self.value[..., bound].reshape(len(self.phi), -1)
        flat = np.argmin(v, axis=1)
        return (np.arange(len(self.phi)),) + np.unravel_index(flat, self.value.shape[1:4])


def contact_ratio(mesh, phi, ev, shifts, contact_tol):
    """Time average of the pairs in contact over ``phi[0] .. phi[-1]`` (one cycle).

    Between two steps where a pair enters or leaves contact, the instant is the zero of
    :meth:`Cycle.margin`: ``sqrt(clearance) - sqrt(contact_tol)``, flat at ``-sqrt(contact_tol)``
    while the flanks touch, then linear in the angle as they part. It is bracketed by a point in
    contact and one out of it; each iteration interpolates between them once the point in contact
    lies on the linear part (Illinois: the end kept twice has its value halved), extrapolates the
    last two points out of contact while it does not, and bisects when neither lands inside the
    bracket. Each iteration is one evaluation of every pending instant, until every bracket (or the
    next correction) is below ``INSTANT_TOL`` of a pitch.
    """
    steps, pid, key, span = _entries(ev)
    last = len(phi) - 1
    nxt = np.isin(key + span, key)  # in contact at the next step too
    prv = np.isin(key - span, key)
    total = float(np.sum(np.diff(phi)[steps[nxt]]))
    leave, enter = ~nxt & (steps < last), ~prv & (steps > 0)
    j = np.concatenate([steps[leave], steps[enter] - 1])
    pid = np.concatenate([pid[leave], pid[enter]])
    start_in = np.concatenate([np.ones(leave.sum(), bool), np.zeros(enter.sum(), bool)])
    if j.size:
        total += float(np.sum(_instants(mesh, phi, ev, shifts, contact_tol, j, pid, start_in)))
    return total / (phi[-1] - phi[0])


def _instants(mesh, phi, ev, shifts, contact_tol, j, pid, start_in):
    """The time each pending pair spends in contact between steps ``j`` and ``j + 1`` (rad)."""
    flat = np.sqrt(contact_tol)
    g0, g1 = _margin_at(ev, j, pid), _margin_at(ev, j + 1, pid)
    # the grid step beyond the one out of contact, where it is out of contact too: the second point
    # of the first extrapolation
    far = np.clip(np.where(start_in, j + 2, j - 1), 0, len(phi) - 1)
    g_far = _margin_at(ev, far, pid)
    far_ok = (np.abs(far - j) == np.where(start_in, 2, 1)) & (g_far > 0)
    b = {"in": np.where(start_in, phi[j], phi[j + 1]), "g_in": np.where(start_in, g0, g1),
         "out": np.where(start_in, phi[j + 1], phi[j]), "g_out": np.maximum(np.where(start_in, g1, g0), 1e-300),
         "out2": np.where(far_ok, phi[far], np.nan), "g_out2": np.where(far_ok, g_far, np.nan),
         "out3": np.full(len(j), np.nan), "g_out3": np.full(len(j), np.nan),
         "w_in": np.ones(len(j)), "w_out": np.ones(len(j)), "side": np.zeros(len(j))}
    xtol = INSTANT_TOL * (phi[-1] - phi[0])
    fine = close(np.abs(np.diff(phi)).max(), mesh.pitch1)
    todo = np.arange(len(j))
    for _ in range(_EXTRAPOLATE):
        c = {k: v[todo] for k, v in b.items()}
        x = _estimate(c, flat)
        at = j[todo]
        near = (ev, at + (x - phi[at]) / (phi[at + 1] - phi[at])) if fine else None  # starts from the steps about
        g = Cycle(mesh, x, shifts, contact_tol, working_only=True, near=near).margin(pid[todo])
        hit = g <= 0
        # Illinois: an end kept a second time in a row has its value halved
        c["w_out"] = np.where(hit, np.where(c["side"] > 0, 0.5 * c["w_out"], c["w_out"]), 1.0)
        c["w_in"] = np.where(hit, 1.0, np.where(c["side"] < 0, 0.5 * c["w_in"], c["w_in"]))
        c["side"] = np.where(hit, 1.0, -1.0)
        c["out3"], c["g_out3"] = np.where(hit, c["out3"], c["out2"]), np.where(hit, c["g_out3"], c["g_out2"])
        c["out2"], c["g_out2"] = np.where(hit, c["out2"], c["out"]), np.where(hit, c["g_out2"], c["g_out"])
        c["in"], c["g_in"] = np.where(hit, x, c["in"]), np.where(hit, g, c["g_in"])
        c["out"], c["g_out"] = np.where(hit, c["out"], x), np.where(hit, c["g_out"], np.maximum(g, 1e-300))
        for k, v in c.items():
            b[k][todo] = v
        width = np.abs(c["out"] - c["in"])
        with np.errstate(invalid="ignore", divide="ignore"):  # the next correction, on the linear part
            step = np.abs(g) * width / (c["g_out"] - c["g_in"])
        done = (width <= xtol) | ((c["g_in"] > -0.5 * flat) & (step <= xtol))
        todo = todo[~done]
        if todo.size == 0:
            break
    b["w_in"][:], b["w_out"][:] = 1.0, 1.0
    cut = _estimate(b, flat, final=True)
    return np.where(start_in, cut - phi[j], phi[j + 1] - cut)


def _estimate(b, flat, final=False):
    """Next point of each bracket ``b``: interpolated (Illinois weights) once its end in contact is on
    the margin's linear part, else extrapolated from its last two (three) points out of contact, linearly
    (inverse quadratic); bisection
    when neither lies strictly inside the bracket. ``final``: the last estimate, which stops at the
    bracket's end it passes (the margin bends where the clearance meets round-off)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        gi, go = b["w_in"] * b["g_in"], b["w_out"] * b["g_out"]
        x_int = b["out"] - go * (b["out"] - b["in"]) / (go - gi)
        x_ext = b["out"] - b["g_out"] * (b["out"] - b["out2"]) / (b["g_out"] - b["g_out2"])
        # three points out of contact: inverse quadratic (the margin bends on its way to zero)
        g1, g2, g3 = b["g_out"], b["g_out2"], b["g_out3"]
        x_quad = (b["out"] * g2 * g3 / ((g1 - g2) * (g1 - g3)) + b["out2"] * g1 * g3 / ((g2 - g1) * (g2 - g3))
                  + b["out3"] * g1 * g2 / ((g3 - g1) * (g3 - g2)))
        x_ext = np.where(np.isfinite(x_quad), x_quad, x_ext)
        x = np.where(b["g_in"] > -0.5 * flat, x_int, x_ext)
    lo, hi = np.minimum(b["in"], b["out"]), np.maximum(b["in"], b["out"])
    if final:
        return np.where(np.isfinite(x), np.clip(x, lo, hi), 0.5 * (lo + hi))
    return np.where(np.isfinite(x) & (x > lo) & (x < hi), x, 0.5 * (lo + hi))


def _entries(ev):
    """The pairs in contact at every step, each once: ``(step, pid, key, span)`` sorted by ``key = step *
    span + pid - base`` (``key + span``: the same pair at the next step)."""
    n = len(ev.phi)
    s, c = np.nonzero(ev.touch.reshape(n, -1))
    pid = ev.pid.reshape(n, -1)[s, c]
    if pid.size == 0:
        return s, pid, s, 1
    base = int(pid.min())
    span = int(pid.max()) - base + 1
    key = np.unique(s * span + (pid - base))
    return key // span, key % span + base, key, span


def _margin_at(ev, steps, pid):
    """:meth:`Cycle.margin` of pair ``pid[i]`` at grid step ``steps[i]``."""
    n = len(ev.phi)
    flat = ev.pid.reshape(n, -1)[steps] == pid[:, None]
    excess = np.where(flat, ev.excess.reshape(n, -1)[steps], np.inf).min(axis=1)
    return np.sqrt(np.clip(np.nan_to_num(excess, posinf=1e6), 0.0, None)) - np.sqrt(ev.contact_tol)
