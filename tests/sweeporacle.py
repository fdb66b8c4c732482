"""The oracle of the tip-sweep tests: the tip sweep of an internal pair by brute force, written apart
from :mod:`gearkit.pair.sweep`. Every tip corner of both gears (both sides of the tooth) is rotated as
a point to sampled pinion angles; its depth in the mate's teeth is as defined by the check's
``tip_interference`` (radial bounds, flank distance along the base tangent)."""
import math

import numpy as np

from gearkit.curves import inv

CHUNK = 250_000  #: angles per chunk of the brute-force sweep
GRADIENT = 2.0  #: bound on a tooth's depth gradient in the plane (radially 1, along the base tangent 1)


def corner_speed(g) -> float:
    """Bound on a tip corner's speed relative to the mate (mm per radian of the pinion): its distance
    from the pitch point at most the pinion's tip radius plus the ring's working radius, the mate's
    frame turning about it at ``1 - z1/z2``."""
    p, ring = g.gears
    return (1 - p.teeth / ring.teeth) * (p.tip_diameter / 2 + ring.working_diameter)


def depths(g, phi):
    """The deepest of the four tip corners in the mate's teeth at the pinion angles ``phi``: (n,) mm."""
    p, ring = g.gears
    sec_t = g.transverse_pressure_angle
    z1, z2, a = p.teeth, ring.teeth, g.center_distance
    ra1, ra2 = p.tip_diameter / 2, max(ring.tip_diameter, ring.base_diameter) / 2
    rb1, rb2 = p.base_diameter / 2, ring.base_diameter / 2
    rl1, rf2 = max(rb1, p.form_diameter / 2), ring.root_diameter / 2

    def half(z, t, r, internal):
        ay = np.arccos(np.clip((rb2 if internal else rb1) / r, -1, 1))
        return (math.pi / 2 + t) / z + (-1 if internal else 1) * (inv(sec_t) - inv(ay))

    def depth(q, z, centre, t, internal, r_in, r_out, rb):
        rho = np.hypot(q[..., 0], q[..., 1])
        theta = np.arctan2(-q[..., 0], q[..., 1])
        d = np.abs((theta - centre + math.pi / z) % (2 * math.pi / z) - math.pi / z)
        flank = (half(z, t, np.maximum(rho, rb), internal) - d) * rb
        return np.minimum(np.minimum(rho - r_in, r_out - rho), flank)

    def rot(v, ang):
        return np.stack([np.cos(ang) * v[0] - np.sin(ang) * v[1], np.sin(ang) * v[0] + np.cos(ang) * v[1]], -1)

    k = z1 / z2
    phi = np.asarray(phi, dtype=float)
    best = np.full(phi.shape, -np.inf)
    h1 = max(float(half(z1, p.thickness_coeff, ra1, False)), 0.0)
    h2 = max(float(half(z2, ring.thickness_coeff, ra2, True)), 0.0)
    for s in (h1, -h1):
        c = ra1 * np.array([-math.sin(s), math.cos(s)])
        q = rot((np.array([0.0, a])[:, None] + rot(c, phi).T), -k * phi)
        best = np.maximum(best, depth(q, z2, math.pi / z2, ring.thickness_coeff, True, ra2, rf2, rb2))
    for s in (h2, -h2):
        c = ra2 * np.array([-math.sin(math.pi / z2 + s), math.cos(math.pi / z2 + s)])
        q = rot((rot(c, k * phi) - np.array([0.0, a])).T, -phi)
        best = np.maximum(best, depth(q, z1, 0.0, p.thickness_coeff, False, rl1, ra1, rb1))
    return best


def brute_sweep(g, samples: int, offset: float = 0.0) -> float:
    """The deepest corner over ``samples`` pinion angles spread evenly over a turn (shifted by
    ``offset``): a lower bound of the sweep's maximum, below it by at most ``GRADIENT``
    :func:`corner_speed` times half a step."""
    if samples > CHUNK:  # in chunks of angles (memory)
        return max(brute_sweep(g, CHUNK, offset) for offset in np.arange(samples // CHUNK) * (2 * math.pi / samples))
    return float(depths(g, np.linspace(-math.pi, math.pi, samples, endpoint=False) + offset).max())


def brute_maximum(g, samples: int = 200_000, zoom: int = 10, rounds: int = 10) -> tuple:
    """The sweep's maximum by sampling, refined: ``samples`` angles over a turn, then, ``rounds`` times,
    angles ``zoom`` times closer across the step on each side of every sample that may lie beside the
    maximum (not below the deepest sample by more than what a step can hide, ``GRADIENT``
    :func:`corner_speed` times a step). Returns (the deepest sample, mm; the most it can lie below the
    maximum, mm)."""
    phi = np.linspace(-math.pi, math.pi, samples, endpoint=False)
    step = 2 * math.pi / samples
    slack = GRADIENT * corner_speed(g)
    for _ in range(rounds):
        d = depths(g, phi)
        keep = np.sort(phi[d >= d.max() - slack * step])
        cut = np.flatnonzero(np.diff(keep) > 2 * step) + 1  # runs of samples whose neighbourhoods overlap
        fine = step / zoom
        phi = np.concatenate([np.arange(run[0] - step, run[-1] + step + fine / 2, fine) for run in np.split(keep, cut)])
        step = fine
    return float(depths(g, phi).max()), slack * step / 2
