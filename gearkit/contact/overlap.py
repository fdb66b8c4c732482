"""Area of overlap between the driver's teeth and the mate at one position (mm^2).

The driver's teeth near the mesh are closed polygons (the tooth outline at the mesh's ``tol``,
closed through the driver's centre, or outwards for a ring). In the mate's radial and periodic
coordinates ``(rho, psi)`` each polygon is cut by lines of constant ``rho``: the crossings,
sorted, pair into the polygon's extent along ``psi``; the mate's material there is what lies
outside its spaces ``|u| <= w(rho)``. The area is the integral over ``rho`` of that length (times
``rho`` for a gear), by the midpoint rule on ``samples`` radii: a reporting value, accurate to a
few parts in a thousand, not an input of any decision.
"""
from __future__ import annotations

import numpy as np

from gearkit.curves import polar_from_y

__all__ = ["overlap_area"]


def _tooth_polygon(mesh):
    tooth = mesh.gear1.tooth_points(mesh.tol)
    r_end = np.hypot(*tooth[0])
    if mesh.gear1.internal:
        far = 2.0 * r_end
        close = np.array([tooth[-1] * far / r_end, tooth[0] * far / r_end])
    else:
        close = np.zeros((1, 2))
    return np.concatenate([tooth, close])


def _space_measure(x, w, pitch):
    """Measure of the mate's spaces (|u| <= w, u from the centre at pitch/2) within [0, x]."""
    w = np.clip(w, 0.0, pitch / 2)
    return np.floor(x / pitch) * 2 * w + np.clip(np.mod(x, pitch) - (pitch / 2 - w), 0.0, 2 * w)


def overlap_area(mesh, phi: float, delta: float, samples: int = 2000) -> float:
    """Area (mm^2) where the driver's teeth at angle ``phi`` overlap the mate at position ``delta``."""
    poly = _tooth_polygon(mesh)
    teeth, theta = mesh.teeth(np.array([phi]))
    mate = mesh.mate
    total = 0.0
    for th in theta[0]:
        c, s = np.cos(th), np.sin(th)
        q = np.stack([c * poly[:, 0] - s * poly[:, 1], s * poly[:, 0] + c * poly[:, 1]], -1)
        rho, u = mesh.to_mate(q, phi)
        if mesh.kind == "rack":
            psi = mesh.beta0 + mesh.ratio * phi - q[:, 0]
        else:
            beta = mesh.beta0 + mesh.ratio * phi
            cb, sb = np.cos(beta), np.sin(beta)
            x, y = q[:, 0] - mesh.centre2[0], q[:, 1] - mesh.centre2[1]
            psi = polar_from_y(np.stack([cb * x + sb * y, -sb * x + cb * y], -1))[1]
            mid = psi[len(psi) // 2]
            psi = mid + np.mod(psi - mid + np.pi, 2 * np.pi) - np.pi
        psi = psi + delta
        lo, hi = rho.min(), rho.max()
        if mate.outward > 0:
            hi = min(hi, mate.rho_tip)
        else:
            lo = max(lo, mate.rho_tip)
        if hi <= lo:
            continue
        dr = (hi - lo) / samples
        grid = lo + dr * (np.arange(samples) + 0.5)
        r0, r1 = rho, np.roll(rho, -1)
        p0, p1 = psi, np.roll(psi, -1)
        e_lo, e_hi = np.minimum(r0, r1), np.maximum(r0, r1)
        i_lo = np.searchsorted(grid, e_lo, side="left")
        i_hi = np.searchsorted(grid, e_hi, side="left")
        counts = i_hi - i_lo
        edge = np.repeat(np.arange(len(r0)), counts)
        gi = np.repeat(i_lo, counts) + (np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts))
        f = (grid[gi] - r0[edge]) / (r1[edge] - r0[edge])
        x = p0[edge] + f * (p1[edge] - p0[edge])
        order = np.lexsort((x, gi))
        gi, x = gi[order], x[order]
        if len(gi) % 2:
            continue  # a degenerate polygon: no area reported rather than a wrong one
        a, b, g = x[0::2], x[1::2], gi[0::2]
        if not np.array_equal(g, gi[1::2]):
            continue
        w = mate.coarse(grid[g])
        off = np.floor(min(a.min(), 0.0) / mesh.pitch2) * mesh.pitch2
        space = _space_measure(b - off, w, mesh.pitch2) - _space_measure(a - off, w, mesh.pitch2)
        material = np.clip((b - a) - space, 0.0, None)
        weight = 1.0 if mesh.kind == "rack" else grid[g]
        total += float(np.sum(material * weight) * dr)
    return total
