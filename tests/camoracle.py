"""The roller cam's oracle, written from the spec alone: the roller centre's path and the discs it sweeps.

None of it is the product's envelope or sampler. The roller centre (the follower's reference point) is
written out from the frames of :class:`~gearkit.families.cam.CamSpec` and turned back by the cam angle
(:func:`pitch_curve`); the cam is what the roller's disc swept along that path leaves of the blank. So
an outline vertex (an exact point of the envelope) lies a roller radius from its own centre and inside
no other disc by more than the reported deviation, and every chord of the outline lies outside the
discs to within that deviation (:func:`check_swept_discs`).
"""
import math

import numpy as np

from gearkit.distances import edge_distances

#: roller centres over a turn, plus the phase ends (the corners exact)
CENTRES = 1 << 18
#: the round-off of a point computed through the follower's pose, in the lengths it spans (r0 + stroke, the
#: offset, the pivot distance and the arm)
ROUND_OFF = 1e-12


def pitch_curve(spec, phi):
    """The reference point's path in the cam frame, written out from the frames of :class:`CamSpec`:
    the follower's point at cam angle ``phi``, turned back by ``-phi``."""
    s = spec.motion.evaluate(phi)[0]
    if spec.follower == "translating":
        x, y = np.full_like(s, spec.offset), spec.start_height + s
    else:
        big_psi = spec.psi0 + s / spec.arm_length
        x, y = spec.pivot_distance - spec.arm_length * np.cos(big_psi), spec.arm_length * np.sin(big_psi)
    c, n = np.cos(phi), np.sin(phi)
    return np.stack([c * x + n * y, -n * x + c * y], -1)


def centres_for(spec, tol: float, share: float = 0.1) -> int:
    """Enough roller centres (a power of two, 2^12 to 2^20) that the sag of their polyline, ``2 L^2 / (8 R)``
    for its longest chord ``L``, stays within ``share`` of ``tol`` (the path's length read off 4096 of them,
    the longest chord taken as twice the mean)."""
    path = pitch_curve(spec, np.linspace(0.0, 2 * math.pi, 4097))
    length = float(np.hypot(*np.diff(path, axis=0).T).sum())
    chord = math.sqrt(4 * spec.roller_radius * share * tol) / 2
    return 1 << min(max(math.ceil(math.log2(max(length / chord, 1.0))), 12), 20)


def check_swept_discs(spec, out, achieved, centres: int = CENTRES):
    """Assert that the closed outline ``out`` of a roller cam is the boundary the swept discs leave, to
    within ``achieved`` (mm): every vertex at most a roller radius from the centre path and inside no disc
    by more than ``achieved``, every chord's middle inside none by more than ``achieved``, both read
    against a polyline of ``centres`` exact centres within its chords' sag."""
    ends = np.array([ph[2] for ph in spec.motion.phases()]) % (2 * math.pi)
    path = pitch_curve(spec, np.unique(np.concatenate([np.linspace(0.0, 2 * math.pi, centres), ends])))
    r = spec.roller_radius
    # the nearest centre of a point the swept discs leave uncovered is where the path's radius of curvature
    # is at least the roller's (else the neighbouring discs cover it), so a chord of length L stands off the
    # path there by at most L^2 / (8 R); doubled for the round-off of lengths up to the pivot
    chord = float(np.hypot(*np.diff(path, axis=0).T).max())
    sag = 2 * chord ** 2 / (8 * r) + ROUND_OFF * (spec.prime_radius + spec.stroke + abs(spec.offset)
                                                  + (spec.pivot_distance or 0.0) + (spec.arm_length or 0.0))
    # a vertex's own centre may lie where the path turns tighter than the roller (the vertex on its outer
    # side): its chords there stand off by h^2 |c''| / 8, which a quarter of the largest second difference
    # of the centres bounds twice over
    bend = float(np.hypot(*np.diff(path, 2, axis=0).T).max()) / 4 + sag
    vertex = edge_distances(out, path, closed=True)
    assert vertex.max() <= r + bend, f"a vertex lies {vertex.max() - r:.3g} mm off every roller (sag {bend:.3g})"
    closed = np.concatenate([out, out[:1]])
    mids = edge_distances(0.5 * (closed[1:] + closed[:-1]), path, closed=True)
    inside = r - min(vertex.min(), mids.min())
    assert inside <= achieved * (1 + 1e-9) + sag, f"the outline lies {inside:.3g} mm inside a roller, reported " \
        f"{achieved:.3g} (sag {sag:.3g})"
