"""What the region's function does between two cuts of its outline (for :func:`~gearkit.blocking.region.reconnect`):
its sign at its saddle between them (:func:`neck`), and whether it keeps one sign all the way from one to the other
(:func:`clear`)."""
from __future__ import annotations

import numpy as np

__all__ = ["clear", "neck"]

NECK_STEPS = 12  #: most steps towards the saddle between two cuts (:func:`neck`)
NECK_H = 1e-6  #: ... its smallest stencil (shift units: the margins' round-off is ~1e-15)
NECK_SHRINK = 0.25  #: ... shrunk by this where its quadratic has no saddle within reach (a kink inside it)


def clear(F, k, a, b, sign, h) -> np.ndarray:
    """True where ``F_k`` has the sign ``sign`` all the way from ``a`` to ``b`` (each row; read at both ends and
    at most ``h`` apart between).

    >>> F = lambda p, k: 1e-3 - np.abs(p[:, 1] - 0.01 * p[:, 0] ** 2)  # a strip along a parabola, 2e-3 wide
    >>> a, b = np.array([[0.0, 0.0], [0.0, 0.0]]), np.array([[0.4, 0.0], [0.8, 0.0]])
    >>> clear(F, np.zeros(2, int), a, b, np.ones(2), 1e-3).tolist()  # 1.6e-3 and 6.4e-3 off the strip's middle
    [False, False]
    >>> clear(F, np.zeros(2, int), a, b / 2, np.ones(2), 1e-3).tolist()
    [True, False]
    """
    n = np.maximum(np.ceil(np.hypot(*(b - a).T) / h).astype(int), 1)
    row = np.repeat(np.arange(len(a)), n + 1)
    t = np.concatenate([np.linspace(0.0, 1.0, m + 1) for m in n])
    v = F(a[row] + t[:, None] * (b - a)[row], np.asarray(k)[row])
    with np.errstate(invalid="ignore"):
        good = np.isfinite(v) & (np.sign(v) == np.asarray(sign)[row])
    return np.logical_and.reduceat(good, np.concatenate([[0], np.cumsum(n + 1)[:-1]]))


def neck(F, k, p1, q1, p2, q2, tol: float) -> float:
    """The sign of ``F_k`` at its saddle between the chords ``p1 -> q1`` and ``p2 -> q2`` (0 where none is
    found there, within half the longer chord of the point halfway between their middles): the critical
    point of the quadratic fitted to ``F`` on a 3 x 3 stencil, from that point, the stencil shrinking to
    each step (to ``NECK_H``), solved to ``tol / 4``; where the fitted quadratic has no saddle within reach, the
    stencil shrunk by ``NECK_SHRINK`` and fitted again (a stencil across a kink of ``F``: 51/90 z0 26 and 42/67 z0 40
    internal at tol 1e-5, the cuts' middles 0.033 apart, two of its corners read the tip sweep's flat level, 1e-4,
    beside interference.1's saddle at (1, 1), and the step left; the region was left in two loops closed across the
    neck, 504 and 536 tol off). Where the region
    goes on through a saddle's neck narrower than the chords are far from its middle, the point halfway
    reads one of the saddle's wedges (55/102 z0 34 internal at tol 1e-5: interference.1's neck at (1, 1),
    +1e-9 there and 1.4e-4 wide, its wedges' tips 1e-4 from it; the point halfway between the cuts lay in
    a wedge 2.3e-4 off it and the region was left in two loops closed across the neck, 810 tol off).

    >>> F = lambda p, k: p[:, 0] ** 2 - (p[:, 1] - 0.01) ** 2 + 1e-6  # a neck at (0, 0.01), positive there
    >>> a, b = np.array([-1.0, 0.5]), np.array([1.0, 0.5])
    >>> neck(F, 0, a, b, -a, -b, 1e-5), neck(lambda p, k: F(p, k) - 2e-6, 0, a, b, -a, -b, 1e-5)
    (1.0, -1.0)
    """
    m1, m2 = 0.5 * (p1 + q1), 0.5 * (p2 + q2)
    x0 = x = 0.5 * (m1 + m2)
    h, reach = 0.25 * float(np.hypot(*(m2 - m1))), 0.5 * max(float(np.hypot(*(q1 - p1))), float(np.hypot(*(q2 - p2))))
    e = np.array([[i, j] for j in (-1.0, 0.0, 1.0) for i in (-1.0, 0.0, 1.0)])
    for _ in range(NECK_STEPS):
        f = F(x + h * e, np.full(9, k)).reshape(3, 3)  # f[j, i] at x + h (i, j)
        if not np.all(np.isfinite(f)):
            return 0.0
        g = np.array([f[1, 2] - f[1, 0], f[2, 1] - f[0, 1]]) / (2 * h)
        H = np.array([[f[1, 2] - 2 * f[1, 1] + f[1, 0], (f[2, 2] - f[2, 0] - f[0, 2] + f[0, 0]) / 4],
                      [0.0, f[2, 1] - 2 * f[1, 1] + f[0, 1]]]) / h ** 2
        H[1, 0] = H[0, 1]
        step = -np.linalg.solve(H, g) if np.linalg.det(H) < 0 else np.full(2, np.inf)
        if not np.hypot(*(x + step - x0)) <= reach:  # no saddle of the fitted quadratic within reach:
            if h <= NECK_H:  # none, or the stencil spans a kink of F (a part flat beside it), read closer
                return 0.0
            h = max(NECK_SHRINK * h, NECK_H)
            continue
        x = x + step
        if np.hypot(*step) <= 0.25 * tol:
            between = all(np.sign((q - p)[0] * (x - p)[1] - (q - p)[1] * (x - p)[0]) ==
                          np.sign((q - p)[0] * (x0 - p)[1] - (q - p)[1] * (x0 - p)[0])
                          for p, q in ((p1, q1), (p2, q2)))
            return float(np.sign(F(x[None], np.array([k]))[0])) if between else 0.0
        h = min(h, max(float(np.hypot(*step)), NECK_H))
    return 0.0
