"""A gear's transverse section: the tooth polyline repeated over the teeth, and its end faces.

An external gear's end face is cut into one cell per tooth (the tooth polyline closed a tenth of a
pitch below its space centres, triangulated once and repeated) and a core (the polygon below the
space centres: a fan from the axis, or a band to the bore), so the cost stays linear in the teeth.
A ring's end face (outer circle, teeth as a hole), or one whose bore reaches into the cells, is
triangulated whole (manifold3d).

An end face is numbered in the section's own way (:meth:`Section.end_face`): the outline's vertices
first, then the wall's (bore or rim), then the points the face adds (core, axis). A solid maps the
numbers onto its vertices: a straight gear once for both ends (:mod:`gearkit.solids.extrusion`), a
twisted one at each end (:meth:`Section.face`).
"""
from __future__ import annotations

import math

import manifold3d as m3
import numpy as np

from gearkit.errors import GeometryError


def rotate(p, angle):
    """Points ``(n, 2)`` turned counter-clockwise by ``angle`` (rad); the same array for no turn."""
    if angle == 0.0:  # a spur gear's slices: no product (a large one may wake numpy's BLAS threads)
        return p
    c, s = math.cos(angle), math.sin(angle)
    return p @ np.array([[c, s], [-s, c]])


def triangulate(polygons) -> np.ndarray:
    """Triangles ``(k, 3)`` int64, counter-clockwise, of the region of CCW polygons (CW holes),
    numbered through the polygons in turn (manifold3d)."""
    tri = np.asarray(m3.triangulate([np.ascontiguousarray(p, dtype=np.float64) for p in polygons]), dtype=np.int64)
    if len(tri) == 0:
        raise GeometryError("an end face could not be triangulated")
    return tri.reshape(-1, 3)


def zipper(outer, inner) -> np.ndarray:
    """Triangles ``(k, 3)`` of the band between two closed CCW polygons around the origin whose
    polar angles increase along them (a z-gon, a circle): indices ``< len(outer)`` are outer
    vertices, the rest inner ones. Each triangle joins an edge of one polygon to the vertex of the
    other whose angle is nearest, so none is a sliver however many vertices there are."""
    def turned(p):
        ang = np.arctan2(p[:, 1], p[:, 0])
        k0 = int(np.argmin(ang))
        ang = np.roll(ang, -k0)
        ang = ang[0] + np.mod(ang - ang[0], 2.0 * math.pi)
        return k0, np.append(ang, ang[0] + 2.0 * math.pi)
    no, ni = len(outer), len(inner)
    ko, ao = turned(outer)
    ki, ai = turned(inner)
    i = j = 0
    tris = []
    while i < no or j < ni:
        if j == ni or (i < no and ao[i + 1] <= ai[j + 1]):
            tris.append(((ko + i) % no, (ko + i + 1) % no, no + (ki + j) % ni))
            i += 1
        else:
            tris.append(((ko + i) % no, no + (ki + j + 1) % ni, no + (ki + j) % ni))
            j += 1
    return np.asarray(tris, dtype=np.int64)


class Section:
    """The transverse section of one gear: tooth polyline repeated over the teeth, end faces.

    An external gear's end face (when each tooth's space centres see each other inside it) is
    built from cells: one tooth down to a core polygon a tenth of a pitch below its space centres,
    triangulated once and repeated, and the core (a fan from the axis, or a band to the bore).
    Every triangle then spans at least a tenth of a pitch across, so none degenerates when written
    in single precision (a cell closed by the chord between space centres met the root arc in
    triangles thinner than a float32 step from z ~ 1000 on).

    Attributes
    ----------
    outline : (count, 2) float64, mm, the teeth's closed polyline, counter-clockwise, tooth 0 on +y
    count : int, its vertices (teeth x edges per tooth)
    """

    def __init__(self, poly, teeth: int, internal: bool):
        self.tooth = poly.points  # (n + 1, 2)
        self.n = poly.edges
        self.z = teeth
        self.internal = internal
        ang = 2.0 * math.pi * np.arange(teeth) / teeth
        c, s = np.cos(ang)[:, None], np.sin(ang)[:, None]
        t = self.tooth[:-1]
        self.outline = np.stack([c * t[None, :, 0] - s * t[None, :, 1],
                                 s * t[None, :, 0] + c * t[None, :, 1]], -1).reshape(-1, 2)
        self.count = teeth * self.n
        self._cells = None
        t = self.tooth
        if not internal and (t[1:-1, 1] > t[0, 1]).all():  # the chord between space centres is inside
            r_space = float(np.hypot(t[0, 0], t[0, 1]))
            self.core_radius = r_space - 0.1 * 2.0 * r_space * math.sin(math.pi / teeth)
            u0, u1 = t[0] / np.hypot(*t[0]), t[-1] / np.hypot(*t[-1])
            cell = np.concatenate([t, [self.core_radius * u1, self.core_radius * u0]])
            self._cells = triangulate([cell])
            self.inradius = self.core_radius * math.cos(math.pi / teeth)
            # tooth k's cell corners: a tooth vertex c is outline vertex k n + c, a core vertex (c = n + 1,
            # n + 2) core vertex k + 1 or k; the last tooth's far ends wrap round to vertex 0
            cells = self._cells
            self._on_tooth = cells <= self.n
            self._stride = np.where(self._on_tooth, self.n, 1)
            self._wrap = np.where(self._on_tooth, cells == self.n, cells == self.n + 1)

    def end_face(self, theta: float, wall) -> tuple:
        """An end face with the teeth turned by ``theta`` (rad), in the section's numbering.

        ``wall``: the CCW polygon of the bore or groove (external gear: a hole, may be None) or of
        the rim or groove (ring). Returns the points the face adds ``(e, 2)`` (mm) and its triangles
        ``(k, 3)``, counter-clockwise seen from +z, numbering the outline's vertices ``0 ...
        count - 1``, the wall's next, then the added points.
        """
        n, count = self.n, self.count
        nw = 0 if wall is None else len(wall)
        fits = wall is None or np.hypot(wall[:, 0], wall[:, 1]).max() < getattr(self, "inradius", 0.0)
        if self._cells is not None and fits:
            spaces = rotate(self.outline[::n], theta)
            core = spaces * (self.core_radius / np.hypot(spaces[:, 0], spaces[:, 1]))[:, None]
            core_base = count + nw
            cells = np.multiply.outer(np.arange(self.z), self._stride)  # (teeth, cell triangles, 3)
            cells += np.where(self._on_tooth, self._cells, core_base + (self._cells == n + 1))
            cells[-1] -= np.where(self._on_tooth, count, self.z) * self._wrap
            cells = cells.reshape(-1, 3)
            if wall is None:
                j = np.arange(self.z)
                fan = np.stack([core_base + j, core_base + (j + 1) % self.z, np.full(self.z, core_base + self.z)], 1)
                return np.concatenate([core, np.zeros((1, 2))]), np.concatenate([cells, fan])
            tri = zipper(core, wall)
            ring = np.where(tri < self.z, core_base + tri, count + (tri - self.z))
            return core, np.concatenate([cells, ring])
        turned = rotate(self.outline, theta)
        none = np.zeros((0, 2))
        if self.internal:
            tri = triangulate([wall, turned[::-1]])
            return none, np.where(tri < nw, count + tri, count - 1 - (tri - nw))
        if wall is None:
            return none, triangulate([turned])
        tri = triangulate([turned, wall[::-1]])
        return none, np.where(tri < count, tri, count + (nw - 1 - (tri - count)))

    def face(self, mesh, theta: float, base: int, z: float, wall, wall_base: int) -> np.ndarray:
        """Triangles (counter-clockwise seen from +z) of an end face at ``z``, teeth turned by ``theta``,
        numbered as ``mesh``'s vertices (``mesh.add(points, z)`` returns the first added one's number).

        ``base``: the number of the slice's first outline vertex; ``wall`` (:meth:`end_face`), whose
        vertices start at ``wall_base``. The points the face adds are added to ``mesh``.
        """
        extra, tri = self.end_face(theta, wall)
        nw = 0 if wall is None else len(wall)
        extra_base = mesh.add(extra, z) if len(extra) else 0
        number = np.concatenate([np.arange(base, base + self.count), np.arange(wall_base, wall_base + nw),
                                 np.arange(extra_base, extra_base + len(extra))])
        return number[tri]
