"""Meshes: the accuracy ladder of gear solids, measured on sections of the mesh.

The achieved deviation is measured independently of the solid's own number: the mesh is cut
by planes across the face width (mid-layer planes, where a helical mesh's chords sag most), and
dense points of the exact transverse tooth, turned by the helix to each plane, are measured
against the section's segments. Faces and the build time (spec to watertight solid) are
reported beside it.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.bench.timing import median_time

MESH_TOLS = (1e-1, 1e-2, 1e-3, 1e-4)


def plane_section(vertices, faces, z0: float):
    """Segments where the plane ``z = z0`` cuts a triangle mesh: ``(a, b)``, each ``(k, 2)`` float64."""
    v = vertices[faces]  # (m, 3, 3)
    s = v[:, :, 2] - z0
    cut = (s.min(axis=1) < 0) & (s.max(axis=1) > 0)
    v, s = v[cut], s[cut]
    ends = []
    for i, j in ((0, 1), (1, 2), (2, 0)):
        crosses = s[:, i] * s[:, j] < 0
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.where(crosses, s[:, i] / (s[:, i] - s[:, j]), 0.0)
        p = v[:, i, :2] + t[:, None] * (v[:, j, :2] - v[:, i, :2])
        ends.append((crosses, p))
    a = np.empty((len(v), 2))
    b = np.empty((len(v), 2))
    have_a = np.zeros(len(v), dtype=bool)
    for crosses, p in ends:
        first = crosses & ~have_a
        a[first] = p[first]
        second = crosses & have_a
        b[second] = p[second]
        have_a |= crosses
    return a, b


def distances_to_segments(points, a, b, neighbours: int = 12):
    """Distance (mm) of each point to the nearest of the segments ``a``-``b``."""
    from scipy.spatial import cKDTree

    mid = 0.5 * (a + b)
    _, idx = cKDTree(mid).query(points, k=min(neighbours, len(mid)))
    sa, sb = a[idx], b[idx]
    d = sb - sa
    q = points[:, None, :]
    dd = np.einsum("...i,...i->...", d, d)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.clip(np.einsum("...i,...i->...", q - sa, d) / dd, 0.0, 1.0)
    t = np.where(dd > 0, t, 0.0)
    return np.linalg.norm(q - (sa + t[..., None] * d), axis=-1).min(axis=1)


def _exact_transverse(prof, n=3000, tooth=1):
    w = np.linspace(0.0, 1.0, n)
    right = np.concatenate([p(w) for p in prof.half.pieces])
    pts = np.concatenate([right, right * np.array([-1.0, 1.0])])
    ang = 2.0 * math.pi * tooth / prof.teeth
    return _turn(pts, ang)


def _turn(pts, ang):
    c, s = math.cos(ang), math.sin(ang)
    return np.stack([c * pts[:, 0] - s * pts[:, 1], s * pts[:, 0] + c * pts[:, 1]], -1)


def mesh_deviation(prof, solid, width: float, beta_deg: float) -> float:
    """Largest distance (mm) from the exact tooth surface to the mesh, on mid-layer sections."""
    vertices, faces = solid.arrays()
    layers = int(solid.info.get("layers", 1) or 1)
    k = math.tan(math.radians(beta_deg)) / (prof.reference_diameter / 2.0)
    exact = _exact_transverse(prof)
    worst = 0.0
    for i in sorted({0, layers // 2, layers - 1}):
        z0 = (i + 0.5) * width / layers
        a, b = plane_section(vertices, faces, z0)
        worst = max(worst, float(distances_to_segments(_turn(exact, k * z0), a, b).max()))
    return worst


def mesh_ladder(quick: bool, repeats: int):
    """Rows {family, product: "mesh", case, tol, achieved, solid_achieved, vertices (= faces), seconds}."""
    from gearkit.families.involute import GearSpec, tooth_profile
    from gearkit.solids import SolidSpec, gear_solid

    cases = [("spur z=40 b=5", GearSpec(40, 1.0), 5.0), ("helical z=20 b=10 beta=20", GearSpec(20, 1.0,
                                                                                            helix_angle_deg=20.0), 10.0)]
    tols = MESH_TOLS[:3] if quick else MESH_TOLS
    rows = []
    for case, spec, width in (cases[1:] if quick else cases):
        for tol_m in tols:
            tol = tol_m * spec.module

            def build():
                prof = tooth_profile.__wrapped__(spec)
                return prof, gear_solid(prof, SolidSpec(width), tol=tol)

            seconds, (prof, solid) = median_time(build, repeats)
            achieved = mesh_deviation(prof, solid, width, spec.helix_angle_deg)
            rows.append({"family": "involute", "product": "mesh", "case": case, "tol": tol, "tol_m": tol_m,
                         "achieved": achieved, "ratio": achieved / tol, "solid_achieved": solid.achieved,
                         "vertices": int(solid.faces), "count": "faces", "seconds": seconds})
    return rows
