"""A rocker whose arm points straight through the cam's axis at rest (``l - l0 = r0``, so ``Psi0 = 0``) is sampled
with a bounded number of points, and its outline lies on the knife tip's path.

The sampler's bound of the tangent's turn reads the arm angle's range over each leg; it used to hold a leg as
unbounded unless that range lay strictly inside ``(0, pi)``, so at ``Psi0 = 0`` (the dwell at rest, the ends of the
rise and return) no leg was ever proven and every split multiplied the unproven chords by six (the cam fuzz's spec
ran out of memory at 8 M points).

Oracle: the spec's own frames (:mod:`gearkit.families.cam.spec`). The knife tip is at ``O2 + l (-cos Psi, sin Psi)``
in the fixed frame, ``O2 = (l0, 0)``, ``Psi = Psi0 + s(phi)/l`` with ``cos Psi0 = (l0^2 + l^2 - r0^2) / (2 l0 l)``;
the cam turns counter-clockwise by ``phi``, so in its frame the tip is that point turned by ``-phi``. Every outline
vertex must lie on that path (within round-off), and every exact point of the path within the outline's reported
deviation of it; the number of vertices is held to a few times the fewest chords the path's curvature needs.
"""
import math

import numpy as np
import pytest
from scipy.spatial import cKDTree

from gearkit.families.cam import CamSpec, MotionProgram, cam_profile

R0, L0, ARM = 22.093392107625554, 44.18678421525111, 66.28017632287666  # l - l0 = r0 to the last bit (Psi0 = 0)
MOTION = (66.28017632287666, 107.20641465791904, 10.166458154505587, 84.96169872339121, "modified_trapezoid")
#: a vertex lies on the exact path within this multiple of the cam's size (the round-off of the tip's pose)
ON_PATH = 1e-12
#: the sampler places chords for a proven bound, not the least deviation: at most this many times the fewest
#: (about 1.1 here), plus a vertex at each of the outline's breaks (the program's joins, its pieces' ends)
FEWEST_FACTOR, BREAKS = 4.0, 50

SPECS = {
    "fuzz": dict(prime_radius=R0, pivot_distance=L0, arm_length=ARM, motion=MOTION),
    "just inside": dict(prime_radius=R0 * (1 + 1e-9), pivot_distance=L0, arm_length=ARM, motion=MOTION),
    "a hair off the axis": dict(prime_radius=20.0 * (1 + 1e-15), pivot_distance=40.0, arm_length=60.0,
                          motion=(50.0, 120.0, 30.0, 90.0, "cycloidal")),
}


def spec_of(case, contact="knife"):
    kw = dict(SPECS[case])
    motion = MotionProgram.rise_dwell_return(*kw.pop("motion"))
    return CamSpec(motion=motion, follower="rocker", contact=contact, roller_radius=3.0 if contact == "roller" else 0.0,
                   **kw)


def tip_path(spec, phi):
    """The knife tip (the roller centre) in the cam frame at cam angles ``phi`` and its derivative over ``phi``,
    from the spec's frames alone: ``p = R(-phi) T``, ``p' = R(-phi) (T' - J T)``, ``J`` the quarter turn."""
    r0, l0, arm = spec.prime_radius, spec.pivot_distance, spec.arm_length
    psi0 = math.acos(min(1.0, (l0 * l0 + arm * arm - r0 * r0) / (2.0 * l0 * arm)))
    s, v, _, _ = spec.motion.evaluate(np.asarray(phi, dtype=float))
    psi = psi0 + s / arm
    x, y = l0 - arm * np.cos(psi), arm * np.sin(psi)
    dx, dy = np.sin(psi) * v + y, np.cos(psi) * v - x
    c, n = np.cos(phi), np.sin(phi)
    return np.stack([c * x + n * y, -n * x + c * y], -1), np.stack([c * dx + n * dy, -n * dx + c * dy], -1)


def segment_distance(points, a, b):
    """Distance of each point from the segment ``a``-``b`` (one per point)."""
    d = b - a
    t = np.clip(((points - a) * d).sum(-1) / (d * d).sum(-1), 0.0, 1.0)
    return np.hypot(*(points - a - t[:, None] * d).T)


def check_on_path(spec, out, achieved):
    size = spec.prime_radius + spec.motion.stroke
    phi = np.linspace(0.0, 2 * math.pi, 200_001)
    dense, d1 = tip_path(spec, phi)
    # every vertex on the path: from its nearest dense point, Gauss-Newton steps to the foot of the perpendicular
    t = phi[cKDTree(dense).query(out)[1]]
    for _ in range(8):
        p, dp = tip_path(spec, t)
        t = t - ((p - out) * dp).sum(-1) / (dp * dp).sum(-1)
    assert np.hypot(*(tip_path(spec, t)[0] - out).T).max() <= ON_PATH * size
    # every exact point of the path within the reported deviation of its own chord: the one between the vertices
    # whose cam angles hold its angle (the path has no loop: the outline walks it in order)
    at = np.mod(t, 2 * math.pi)
    order = np.argsort(at)
    k = np.searchsorted(at[order], phi, side="right") - 1
    a, b = out[order][k % len(out)], out[order][(k + 1) % len(out)]
    assert segment_distance(dense, a, b).max() <= achieved
    # a bounded count: the fewest chords a curve needs is about the integral of sqrt(kappa / (8 tol)) ds
    d2 = np.gradient(d1, phi, axis=0)
    speed = np.hypot(d1[:, 0], d1[:, 1])
    kappa = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / speed ** 3
    fewest = float(np.sum(np.sqrt(kappa / (8 * achieved)) * speed) * (phi[1] - phi[0]))
    assert len(out) <= FEWEST_FACTOR * fewest + BREAKS


@pytest.mark.parametrize("case", list(SPECS))
@pytest.mark.parametrize("rel", [1e-2, 1e-4, 1e-6])
def test_knife_rocker_through_the_axis_is_sampled_and_on_the_tip_path(case, rel):
    spec = spec_of(case)
    prof = cam_profile(spec)
    tol = rel * spec.prime_radius
    out, achieved = prof.outline(tol), prof.achieved(tol)
    assert achieved <= tol
    check_on_path(spec, out, achieved)


@pytest.mark.parametrize("rel", [1e-2, 1e-5])
def test_roller_rocker_pitch_curve_through_the_axis(rel):
    spec = spec_of("fuzz", contact="roller")
    tol = rel * spec.prime_radius
    out, achieved = cam_profile(spec).pitch_outline(tol)
    assert achieved <= tol
    check_on_path(spec, out, achieved)


class NeverBounded:
    """A unit circle whose ``span`` proves no leg's turn (a curve the bound cannot hold anywhere)."""

    def __call__(self, w):
        return np.stack([np.cos(w), np.sin(w)], -1)

    def turning(self, w):
        return self(w), np.stack([-np.sin(w), np.cos(w)], -1), np.asarray(w, dtype=float)[:, None]

    def span(self, pa, pb):
        total = pb[..., 0] - pa[..., 0]
        return np.minimum(total, 0.0), np.full(total.shape, 10.0), total  # wider than any leg may turn


def test_unproven_splitting_is_bounded_by_a_clean_error():
    from gearkit.errors import GeometryError
    from gearkit.refine import UNPROVEN_LIMIT, refine_sample

    # each round splits every unproven chord in six: the limit is passed within a few rounds, never run out of memory
    with pytest.raises(GeometryError, match="not bounded") as err:
        refine_sample(NeverBounded(), np.linspace(0.0, 1.0, 5), None, 1e-3, bound=True)
    assert int(str(err.value).split(": ")[1].split()[0]) <= 6 * UNPROVEN_LIMIT
