"""The numpy mesh check: a triangle mesh is a valid solid (closed, consistently oriented, no facet of
zero area in single precision, positive volume), and its volume, area and single-precision normals.

:func:`mesh_measures` checks any mesh by sorting all its edges; a straight extrusion is checked
by its structure instead (:mod:`gearkit.solids.extrusion`), from the same pieces: the edge pairing
(:func:`edges_paired`) and the facets' cross products (:func:`gather`, :func:`cross`).
"""
from __future__ import annotations

import numpy as np

from gearkit.errors import GeometryError
from gearkit.progress import Progress


class RepairableMesh(GeometryError):
    """A mesh :func:`mesh_measures` refuses that manifold3d may still merge into a valid solid."""


#: facets handled at once by the chunked mesh passes (bounds their temporary arrays)
CHUNK = 1 << 13


def mesh_measures(vertices, faces, what: str = "mesh") -> dict:
    """Check a triangle mesh is a valid solid and measure it: ``{volume, area, normals}`` (mm^3,
    mm^2, the facets' (m, 3) float32 unit normals as the single-precision vertices give them).

    Valid: finite vertices, faces indexing them, every edge met by exactly one edge running the
    other way (closed and consistently oriented: a sort of the edges proves it), no facet of zero
    area once the vertices are rounded to single precision (as STL stores them), positive volume.
    Otherwise :class:`GeometryError` naming ``what``. The facet passes run in chunks of
    :data:`CHUNK` facets, so their temporaries stay small.
    """
    v = np.asarray(vertices, dtype=np.float64)
    f = np.asarray(faces)
    if v.ndim != 2 or v.shape[1] != 3 or f.ndim != 2 or f.shape[1] != 3:
        raise GeometryError("a mesh needs (n, 3) vertices and (m, 3) faces")
    if not len(f) or f.min() < 0 or f.max() >= len(v):
        raise GeometryError(f"{what}: the mesh is not a valid solid (no faces, or faces naming missing vertices)")
    if not np.isfinite(v).all():
        raise GeometryError(f"{what}: the mesh is not a valid solid (non-finite vertices)")
    with Progress("mesh check", 2 * len(f)) as bar:  # the edges' sort, then the facets
        return _measures(v, f, what, bar)


def _measures(v, f, what: str, bar) -> dict:
    corners = tuple(f[:, k] for k in range(3))  # the facets' corner columns (views: no copy)
    if not edges_paired(corners, corners[1:] + corners[:1], len(v)):
        raise RepairableMesh(f"{what}: the mesh is not a valid solid (an edge without exactly one opposite edge)")
    bar.step(len(f))
    exact, normals, volume, area = tuple(v[:, k] for k in range(3)), np.empty((len(f), 3), dtype=np.float32), 0.0, 0.0
    for s in range(0, len(f), CHUNK):
        chunk = tuple(c[s:s + CHUNK] for c in corners)
        n = cross(corner_points := gather(exact, chunk))
        volume += sum(float(np.einsum("i,i->", p, c)) for p, c in zip(corner_points[0], n)) / 6.0
        area += 0.5 * float(np.sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sum())
        del n  # (the rounded pass reuses the exact corners' arrays: fewer fresh pages at the peak)
        for c in (c for p in corner_points for c in p):  # the same corners rounded to single precision, in place
            c[...] = c.astype(np.float32)
        n = cross(corner_points)
        length = np.sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2])
        if not (length > 0.0).all():
            raise RepairableMesh(f"{what}: the mesh has degenerate facets (zero area in single precision)")
        for k in range(3):
            normals[s:s + CHUNK, k] = n[k] / length
        bar.step(len(chunk[0]))
    if not volume > 0.0:
        raise RepairableMesh(f"{what}: the solid is empty or inside out (volume {volume:.6g} mm^3)")
    return {"volume": volume, "area": area, "normals": normals}


def edges_paired(tails, heads, vertices: int) -> bool:
    """Whether the directed edges ``tails[i][j] -> heads[i][j]`` (sequences of int64 columns of
    vertex indices below ``vertices``) pair up: each edge met by exactly one edge running the other
    way, and by no other edge. For the half-edges of a mesh's facets: closed and consistently oriented.

    Each edge is one integer (its two ends and its way), a column at a time into one buffer; the
    sorted keys then come as each edge (an even key) and itself run the other way (key + 1).

    Examples
    --------
    >>> t = np.array([0, 1, 2]); h = np.array([1, 2, 0])
    >>> edges_paired([t, h], [h, t], 3), edges_paired([t, t], [h, h], 3), edges_paired([t], [h], 3)
    (True, False, False)
    """
    sizes = [len(t) for t in tails]
    small = 2 * vertices * (vertices + 1) <= np.iinfo(np.uint32).max  # every key fits in 32 bits
    kind = np.uint32 if small else np.int64
    if small:  # half the memory, and numpy's vectorised sort of 32-bit keys
        tails, heads = [t.astype(kind) for t in tails], [h.astype(kind) for h in heads]
    key, high, at = np.empty(sum(sizes), dtype=kind), np.empty(max(sizes, default=0), dtype=kind), 0
    for ca, cb, size in zip(tails, heads, sizes):
        k = np.minimum(ca, cb, out=key[at:at + size])
        k *= 2 * vertices
        k += np.multiply(np.maximum(ca, cb, out=high[:size]), 2, out=high[:size])
        k += ca > cb
        at += size
    del high
    # 64-bit keys come in long ascending runs (facets in order), which a merge sort takes whole
    key.sort(kind=None if small else "stable")
    pairs = key.reshape(-1, 2) if len(key) % 2 == 0 else np.array([[1, 1]])
    return all((p[:, 0] & 1 == 0).all() and (p[:, 1] == p[:, 0] + 1).all()
               for p in (pairs[s:s + CHUNK] for s in range(0, len(pairs), CHUNK)))


def columns(a):
    """The three columns of an ``(n, 3)`` array as contiguous float64 (int64 for indices) arrays."""
    kind = np.int64 if np.issubdtype(a.dtype, np.integer) else np.float64
    return tuple(np.ascontiguousarray(a[:, k], dtype=kind) for k in range(3))


def gather(points, corners):
    """The facets' corners ``((x, y, z) of the 1st, 2nd, 3rd)`` from point and corner index columns."""
    return tuple(tuple(c[k] for c in points) for k in corners)


def cross(corner_points):
    """The cross products of the facets' edges (twice the area along the normal), as columns, from
    their corners (:func:`gather`; the products as ``np.cross`` forms them). A coordinate may be a
    scalar shared by every facet (a plane's height): the same products, broadcast."""
    p0, p1, p2 = corner_points
    e1 = tuple(c - q for c, q in zip(p1, p0))
    e2 = tuple(c - q for c, q in zip(p2, p0))
    return (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
