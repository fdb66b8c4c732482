"""Straight extrusions: a triangulated plane section swept from ``z0`` to ``z1``, meshed, checked and
measured by its structure rather than by sorting every edge of the mesh.

The section: points ``(p, 2)`` whose first ones run round its boundary loops (the *walls*, one after
the other), the rest inner points; triangles ``(t, 3)`` covering it, counter-clockwise seen from +z.
The mesh (:func:`extruded`):

* **vertices**: each wall's loop at ``z0`` then at ``z1``, wall by wall, then the inner points at
  ``z0`` then at ``z1``;
* **faces**: each wall's quads, every quad's first triangle then every quad's second (split along
  its :attr:`Wall.diagonals`), then the bottom face (the triangles turned over, at ``z0``), then
  the top face (at ``z1``).

**Why the structure is enough.** :func:`~gearkit.solids.measures.mesh_measures` asks that every edge
of the mesh be met by exactly one edge running the other way. Here it is checked on the section
alone: its triangles' edges and each loop's edges run backwards must pair up so
(:func:`~gearkit.solids.measures.edges_paired`, a sort of a quarter of the mesh's edges), that is,
the triangles are closed and oriented inside, and their boundary is exactly the loops, once each
way round as the walls say. Then the mesh's edges pair: an inner edge of the section pairs in the
top face and, turned, in the bottom one; a loop edge of the top face pairs with its quad's top edge,
and of the bottom face with its bottom edge; a quad's diagonal pairs inside it, and its upright
edges with the neighbouring quads' (the loop is closed and its vertices are its own). The facets
are then measured with the products :func:`mesh_measures` uses, from the single-precision corners
(so the same normals to the bit and the same zero-area test); the volume is the height times the
section's area, the area the two faces' and the loops' lengths times the height (the same sums in
another order: to about 1e-15 relative). A section that fails any of this (or any facet of no area)
is handed to :meth:`~gearkit.solids.Solid.from_arrays` whole, which decides as for any mesh.
"""
from __future__ import annotations

import math

import numpy as np

import gearkit.solids.measures as meshcheck
from gearkit.errors import GeometryError
from gearkit.progress import Progress
from gearkit.solids.measures import cross, edges_paired
from gearkit.solids.solid import Recipe, Solid
from gearkit.values import frozen


@frozen
class Wall:
    """One boundary loop of a section: ``size`` consecutive section points, a closed polygon.

    Parameters
    ----------
    size : int, the loop's vertices (at least 3)
    outside : bool
        The solid lies outside the loop (a bore; a ring gear's teeth): its quads face inwards, and
        the section's triangles run round the loop clockwise (seen from +z).
    diagonals : (size,) bool or None
        Quad ``j`` (from vertex ``j`` to ``j + 1``) split from bottom-right to top-left where True
        (else, and for None, bottom-left to top-right).
    """

    size: int
    outside: bool = False
    diagonals: np.ndarray | None = None


def extruded(points, triangles, walls, z0: float, z1: float, name: str, info: dict,
             recipe: Recipe | None = None) -> Solid:
    """The solid of a triangulated section (mm) from ``z0`` to ``z1`` (mm, ``z0 < z1``): mesh laid out as
    the module says, checked and measured by its structure (else as any mesh, by
    :meth:`Solid.from_arrays <gearkit.solids.Solid.from_arrays>`).

    Examples
    --------
    >>> square = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]])
    >>> s = extruded(square, [[0, 1, 2], [0, 2, 3]], [Wall(4)], 0.0, 3.0, "block", {})
    >>> s.faces, s.volume, s.area
    (12, 6.0, 22.0)
    """
    p = np.ascontiguousarray(points, dtype=np.float64)
    tri = np.ascontiguousarray(triangles, dtype=np.int64)
    sizes = [int(w.size) for w in walls]
    starts = [int(a) for a in np.cumsum([0] + sizes)]
    rim = starts[-1]
    if (p.ndim != 2 or p.shape[1] != 2 or tri.ndim != 2 or tri.shape[1] != 3 or not len(tri) or not sizes
            or min(sizes) < 3 or rim > len(p) or tri.min() < 0 or tri.max() >= len(p)):
        raise GeometryError(f"{name}: a section needs (p, 2) points, (t, 3) triangles naming them and walls "
                            "of 3 or more of them")
    blocks = list(zip(starts, sizes + [len(p) - rim]))  # the walls' loops, then the inner points
    v = np.empty((2 * len(p), 3))
    at_z0 = np.empty(len(p), dtype=np.int64)  # each section point's vertex at z0; at z1: + its block's size
    for start, size in blocks:
        for row, z in ((2 * start, z0), (2 * start + size, z1)):
            v[row:row + size, :2], v[row:row + size, 2] = p[start:start + size], float(z)
        np.add(np.arange(start, start + size), start, out=at_z0[start:start + size])
    at_z1 = at_z0 + np.repeat([size for _, size in blocks], [size for _, size in blocks])
    f = np.empty((2 * rim + 2 * len(tri), 3), dtype=np.int64)
    for wall, start in zip(walls, starts):
        _quads(f[2 * start:2 * (start + wall.size)], wall, 2 * start)
    # (the triangles name section points: checked above, so no bounds check, and numpy takes straight into f)
    np.take(at_z0, tri[:, ::-1], out=f[2 * rim:2 * rim + len(tri)], mode="clip")
    np.take(at_z1, tri, out=f[2 * rim + len(tri):], mode="clip")
    z0, z1 = float(z0), float(z1)
    bounded = np.isfinite(p).all() and math.isfinite(z0) and math.isfinite(z1) and z0 < z1
    measures = _measures(p, tri, walls, starts, z0, z1) if bounded and _closed(tri, walls, sizes, len(p)) else None
    if measures is None:
        return Solid.from_arrays(v, f, name, info, recipe)
    return Solid.from_checked(v, f, measures, name, info, recipe)


def _quads(out, wall: Wall, base: int):
    """A wall's quads into ``out`` (``(2 size, 3)``): corners a, b (vertex j, j + 1 at z0, from
    ``base``) and c, d (at z1); (a, b, d) and (a, d, c), or (a, b, c) and (b, d, c) where split the
    other way; turned round for a wall the solid lies outside."""
    n = wall.size
    j = np.arange(n)
    jn = np.where(j + 1 < n, j + 1, 0)
    lo, hi = base, base + n
    k0, k1, k2 = (2, 1, 0) if wall.outside else (0, 1, 2)
    first, second = out[:n], out[n:]
    np.add(j, lo, out=first[:, k0])
    np.add(jn, lo, out=first[:, k1])
    np.add(jn, hi, out=first[:, k2])
    np.add(j, lo, out=second[:, k0])
    np.add(jn, hi, out=second[:, k1])
    np.add(j, hi, out=second[:, k2])
    diag = _diagonals(wall)
    if diag is not None:
        np.add(j, hi, out=first[:, k2], where=diag)
        np.add(jn, lo, out=second[:, k0], where=diag)


def _diagonals(wall: Wall):
    """The wall's diagonals as a bool array, or None where no quad is split the other way."""
    if wall.diagonals is None:
        return None
    diag = np.asarray(wall.diagonals, dtype=bool)
    return diag if diag.any() else None


def _closed(tri, walls, sizes, points: int) -> bool:
    """The section's triangles are closed and oriented inside and bounded exactly by its loops, each
    way round as its wall says (module docstring)."""
    corners = tuple(tri[:, k] for k in range(3))
    here = np.arange(sum(sizes))
    ahead = here + 1
    ahead[np.cumsum(sizes) - 1] = np.cumsum([0] + sizes[:-1])  # each loop's last vertex back to its first
    outside = np.repeat([bool(w.outside) for w in walls], sizes)
    # each loop edge run the way the section's triangles must not run it: backwards, or forwards outside
    tails, heads = np.where(outside, here, ahead), np.where(outside, ahead, here)
    return edges_paired(corners + (tails,), corners[1:] + corners[:1] + (heads,), points)


def _measures(p, tri, walls, starts, z0: float, z1: float):
    """``{volume, area, normals}`` as :func:`~gearkit.solids.measures.mesh_measures` gives them (the
    normals to the bit), or None where a facet has no area in single precision. The loops' edges of
    an ``outside`` wall run backwards in the section (:func:`_closed` held them to it). The facets
    go a chunk at a time behind a progress bar."""
    rim, faces = int(starts[-1]), 2 * int(starts[-1]) + 2 * len(tri)
    single = p.astype(np.float32).astype(np.float64)
    xs, ys = single[:, 0].copy(), single[:, 1].copy()
    s0, s1 = float(np.float32(z0)), float(np.float32(z1))
    normals = np.empty((faces, 3), dtype=np.float32)
    height, area, twice = z1 - z0, 0.0, 0.0
    with Progress("mesh check", faces, unit="facets") as bar:
        for wall, start in zip(walls, starts):
            n, at = wall.size, 2 * int(start)
            xa, ya, xe, ye = xs[start:start + n], ys[start:start + n], p[start:start + n, 0], p[start:start + n, 1]
            xb, yb = np.roll(xa, -1), np.roll(ya, -1)
            dx, dy = np.roll(xe, -1) - xe, np.roll(ye, -1) - ye
            area += height * float(np.sqrt(dx * dx + dy * dy).sum())
            diag = _diagonals(wall)
            for s in range(0, n, meshcheck.CHUNK):
                c = slice(s, s + meshcheck.CHUNK)
                a0, b0, a1, b1 = (xa[c], ya[c], s0), (xb[c], yb[c], s0), (xa[c], ya[c], s1), (xb[c], yb[c], s1)
                first, second = (a0, b0, b1), (a0, b1, a1)
                if diag is not None:
                    d = diag[c]
                    first = (a0, b0, (np.where(d, xa[c], xb[c]), np.where(d, ya[c], yb[c]), s1))
                    second = ((np.where(d, xb[c], xa[c]), np.where(d, yb[c], ya[c]), s0), b1, a1)
                for corners, row in ((first, at + s), (second, at + n + s)):
                    if not _unit(normals[row:row + len(xa[c])], cross(corners[::-1] if wall.outside else corners)):
                        return None
                bar.step(2 * len(xa[c]))
        columns = np.ascontiguousarray(tri.T)
        xe, ye = p[:, 0].copy(), p[:, 1].copy()
        for s in range(0, len(tri), meshcheck.CHUNK):
            corners = tuple(c[s:s + meshcheck.CHUNK] for c in columns)
            up = tuple((xs.take(c), ys.take(c)) for c in corners)
            rows = len(corners[0])
            for flat, z, row in ((up[::-1], s0, 2 * rim + s), (up, s1, 2 * rim + len(tri) + s)):
                if not _unit(normals[row:row + rows], cross(tuple((x, y, z) for x, y in flat))):
                    return None
            (x0, y0), (x1, y1), (x2, y2) = ((xe.take(c), ye.take(c)) for c in corners)
            cz = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0)
            twice += float(cz.sum())
            area += float(np.abs(cz).sum())  # both faces: half of twice the area, twice
            bar.step(2 * rows)
    volume = height * 0.5 * twice
    if not volume > 0.0:
        return None
    return {"volume": volume, "area": area, "normals": normals}


def _unit(out, n) -> bool:
    """``out`` (float32 rows) = the cross products ``n`` (columns) made unit; False if one has no length."""
    length = np.sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2])
    if not (length > 0.0).all():
        return False
    for k in range(3):
        out[:, k] = n[k] / length
    return True
