"""The OCP edges and faces of gearkit's exact B-reps: B-spline edges, wires, planar end caps and cylinders.

A swept section (:mod:`gearkit.solids.brep`) is closed at each end by a planar face bounded by the
section's loop of edges. A gear of many teeth has a loop of thousands of edges, and the kernel's
validity check of a face compares every edge of a wire with every other (work growing as the square
of the edges): a 2000-tooth gear's two caps took minutes. :func:`sector_caps` cuts such a cap into
*sectors* of a few teeth each by radial lines from the loop down (out, for a ring) to a dividing
circle, and a core disc (a ring's outer annulus) inside that circle: the same plane, the same
boundary, wires of about sqrt(edges) edges each, so the check grows about linearly.

Imported only when an exact solid is asked for (it imports OCP).

Examples
--------
>>> import numpy as np
>>> square = [bspline_edge(np.array([a, b]), np.array([0.0, 0, 1, 1]), 1)
...           for a, b in [((0, 0, 0), (1, 0, 0)), ((1, 0, 0), (1, 1, 0)), ((1, 1, 0), (0, 1, 0)), ((0, 1, 0), (0, 0, 0))]]
>>> from OCP.BRepCheck import BRepCheck_Analyzer
>>> BRepCheck_Analyzer(cap(square)).IsValid()
True
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.errors import GeometryError


def knot_arrays(knots):
    """(values, multiplicities) OCP arrays of a full knot vector."""
    from OCP.collections import Array1_double, Array1_int

    vals, mults = [], []
    for k in knots:
        if vals and abs(k - vals[-1]) <= 1e-14 * max(1.0, abs(k)):
            mults[-1] += 1
        else:
            vals.append(float(k))
            mults.append(1)
    a, m = Array1_double(1, len(vals)), Array1_int(1, len(vals))
    for i, (v, c) in enumerate(zip(vals, mults), start=1):
        a.SetValue(i, v)
        m.SetValue(i, c)
    return a, m


def bspline_edge(poles3, knots, degree):
    """The edge of the B-spline curve with (n, 3) poles ``poles3`` (mm) and the full ``knots``."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
    from OCP.collections import Array1_gp_Pnt
    from OCP.Geom import Geom_BSplineCurve
    from OCP.gp import gp_Pnt

    arr = Array1_gp_Pnt(1, len(poles3))
    for i, q in enumerate(poles3, start=1):
        arr.SetValue(i, gp_Pnt(*map(float, q)))
    k, m = knot_arrays(knots)
    return BRepBuilderAPI_MakeEdge(Geom_BSplineCurve(arr, k, m, degree)).Edge()


def wire(edges):
    """One wire of edges given in order round the loop (coincident ends are joined)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeWire

    out = BRepBuilderAPI_MakeWire()
    for e in edges:
        out.Add(e)
    if not out.IsDone():
        raise GeometryError("an end face's edges do not close")
    return out.Wire()


def circle_edge(radius: float, z: float, a0: float | None = None, a1: float | None = None):
    """The circle of ``radius`` round the z axis at height ``z``; with ``a0 < a1`` (rad) its arc between them."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
    from OCP.gp import gp_Ax2, gp_Circ, gp_Dir, gp_Pnt

    circ = gp_Circ(gp_Ax2(gp_Pnt(0.0, 0.0, z), gp_Dir(0.0, 0.0, 1.0)), radius)
    made = BRepBuilderAPI_MakeEdge(circ) if a0 is None else BRepBuilderAPI_MakeEdge(circ, float(a0), float(a1))
    return made.Edge()


def _line(p, q):
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
    from OCP.gp import gp_Pnt

    return BRepBuilderAPI_MakeEdge(gp_Pnt(*map(float, p)), gp_Pnt(*map(float, q))).Edge()


def _plane_face(loop, holes=()):
    """Planar face bounded by the wire ``loop`` with ``holes`` (wires) cut out of it."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.ShapeFix import ShapeFix_Face

    face = BRepBuilderAPI_MakeFace(loop, True)
    for hole in holes:
        face.Add(hole)
    if not face.IsDone():
        raise GeometryError("an end face is not planar")
    if not holes:
        return face.Face()
    fix = ShapeFix_Face(face.Face())
    fix.FixOrientation()
    return fix.Face()


def cap(edges, outer=None, z=0.0):
    """Planar end face bounded by ``edges``; with ``outer`` (radius), an annulus from that circle in
    to the loop of edges (a ring's end face)."""
    loop = wire(edges)
    if outer is None:
        return _plane_face(loop)
    return _plane_face(wire([circle_edge(outer, z)]), [loop])


def sector_caps(edges, starts, points, core: float, outer=None, z=0.0) -> list:
    """The faces of one planar end cap cut into sectors (see the module's text).

    Parameters
    ----------
    edges : the loop's edges, in order round it
    starts : increasing indices into ``edges``, the first edge of each sector (``starts[0] == 0``)
    points : (len(starts), 2) float64, mm: the loop's point where each sector starts (the start of
        ``edges[starts[i]]``); the radial line from there to the dividing circle must cross no other edge
        (a gear's space centre, whose radius is the loop's least, or a ring's greatest)
    core : radius of the dividing circle, mm (inside the loop; outside it, between it and ``outer``, for a ring)
    outer : radius of a ring's outer circle, mm (None for a gear)
    z : height of the cap, mm

    Returns
    -------
    list of faces: the sectors, then the core disc (or the ring's outer annulus)
    """
    pts = np.asarray(points, dtype=float)
    angles = np.arctan2(pts[:, 1], pts[:, 0])
    n = len(starts)
    on_circle = [(core * math.cos(a), core * math.sin(a), z) for a in angles]
    radial = [_line((p[0], p[1], z), q) for p, q in zip(pts, on_circle)]
    arcs = []
    for g in range(n):
        a0 = angles[g]
        a1 = a0 + (angles[(g + 1) % n] - a0) % (2.0 * math.pi)
        arcs.append(circle_edge(core, z, a0, a1))
    faces = []
    for g in range(n):
        lo, hi = starts[g], starts[g + 1] if g + 1 < n else len(edges)
        faces.append(_plane_face(wire(list(edges[lo:hi]) + [radial[(g + 1) % n], arcs[g], radial[g]])))
    ring = wire(arcs)
    faces.append(_plane_face(ring) if outer is None else _plane_face(wire([circle_edge(outer, z)]), [ring]))
    return faces


def cylinder_face(radius: float, z0: float, z1: float):
    """The whole cylindrical face of ``radius`` round the z axis from ``z0`` to ``z1``."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.gp import gp_Ax3, gp_Cylinder, gp_Dir, gp_Pnt

    cyl = gp_Cylinder(gp_Ax3(gp_Pnt(0.0, 0.0, 0.0), gp_Dir(0.0, 0.0, 1.0)), radius)
    return BRepBuilderAPI_MakeFace(cyl, 0.0, 2.0 * math.pi, z0, z1).Face()
