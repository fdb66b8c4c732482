"""Solids: what to build around a profile (:class:`SolidSpec`) and what was built (:class:`Solid`).

A :class:`Solid` wraps a manifold3d ``Manifold`` that passed its checks (valid status,
non-empty, positive volume, no degenerate facet) with the record of how it was made:
requested and achieved deviation, layer count, polyline points per tooth.
"""
from __future__ import annotations

import math

import manifold3d as m3
import numpy as np

from gearkit.errors import GeometryError, SpecError, check_fields, require
from gearkit.solids.measures import CHUNK, RepairableMesh, columns, cross, gather, mesh_measures
from gearkit.values import frozen


def default_mesh_tol(module: float) -> float:
    """Default mesh tolerance: 5e-3 of the module (10 um at m = 2 mm)."""
    return 5e-3 * module


def _positive(value, field, allow_none=True):
    if value is None and allow_none:
        return
    require(isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value) and value > 0,
            field, f"{value!r} must be a positive length in mm")


@frozen
class SolidSpec:
    """The body around a tooth profile, inputs only (mm, degrees).

    Parameters
    ----------
    width : float, mm
        Face width b (a herringbone's total width, its gap included).
    helix_angle_deg : float or None, degrees
        None takes the profile's own (its spec's ``helix_angle_deg``; 0 for a spur gear).
        Positive is right hand: the transverse section turns counter-clockwise as z grows.
    herringbone : bool
        Two helical halves of opposite hand (the lower one of the given hand), mirror images
        about the mid plane.
    gap : float, mm
        Axial gap between the two halves of a double-helical gear (0: a herringbone whose
        teeth meet at the apex). The gap is a groove turned ``module`` below the root circle.
    bore : float or None, mm
        Bore diameter (external gears).
    keyway : (float, float) or None, mm
        Keyway (width, depth) in the bore, centred on +y; depth from the bore circle.
    outer_diameter, rim : float or None, mm
        A ring gear's outer diameter, or its rim thickness beyond the root circle (one of them;
        neither: a rim of 2 modules).
    """

    width: float
    helix_angle_deg: float | None = None
    herringbone: bool = False
    gap: float = 0.0
    bore: float | None = None
    keyway: tuple | None = None
    outer_diameter: float | None = None
    rim: float | None = None

    def __post_init__(self):
        check_fields(self)
        _positive(self.width, "width", allow_none=False)
        require(self.width <= 1e5, "width", f"{self.width!r} must be a length in (0, 100000] mm")
        if self.helix_angle_deg is not None:
            b = self.helix_angle_deg
            require(isinstance(b, (int, float)) and math.isfinite(b) and -60.0 < b < 60.0, "helix_angle_deg",
                    f"{b!r} must be in (-60, 60) degrees")
        require(isinstance(self.gap, (int, float)) and math.isfinite(self.gap) and self.gap >= 0, "gap",
                f"{self.gap!r} must be a length >= 0 mm")
        if self.gap:
            require(self.herringbone, "gap", "a central gap needs a herringbone (double-helical) gear")
            require(self.gap < self.width, "gap", f"{self.gap} mm must be smaller than the width {self.width} mm")
        _positive(self.bore, "bore")
        if self.keyway is not None:
            require(self.bore is not None, "keyway", "a keyway needs a bore")
            kw = tuple(self.keyway)
            require(len(kw) == 2, "keyway", "give (width, depth) in mm")
            _positive(kw[0], "keyway")
            _positive(kw[1], "keyway")
            require(kw[0] < self.bore, "keyway", f"width {kw[0]} mm must be smaller than the bore {self.bore} mm")
            object.__setattr__(self, "keyway", (float(kw[0]), float(kw[1])))
        _positive(self.outer_diameter, "outer_diameter")
        _positive(self.rim, "rim")
        if self.outer_diameter is not None and self.rim is not None:
            raise SpecError("rim", "give the outer diameter or the rim thickness, not both")


@frozen
class Recipe:
    """How to rebuild a solid as an exact B-rep (:func:`gearkit.solids.shapes.shape`), and where it is placed.

    kind : "gear" (profile, SolidSpec, tol), "rack" (profile, length, height, width, start, tol),
        "prism" (curves, SolidSpec: width, bore, keyway; tol), "section" (curves, runs, tol),
        "cylinders" (centres, radius, z0, z1), "tube" (inner, outer, z0, z1),
        "difference" / "union" (Recipe, Recipe)
    angle : rad, turned about z first; offset : (x, y, z) mm, moved then
    """

    kind: str
    args: tuple
    angle: float = 0.0
    offset: tuple = (0.0, 0.0, 0.0)

    def placed(self, angle: float = 0.0, offset=(0.0, 0.0, 0.0)) -> "Recipe":
        """This recipe turned by ``angle`` about z and then moved by ``offset`` (after its own placement)."""
        c, s = math.cos(angle), math.sin(angle)
        x, y, z = self.offset
        moved = (c * x - s * y + offset[0], s * x + c * y + offset[1], z + offset[2])
        return Recipe(self.kind, self.args, self.angle + angle, tuple(float(v) for v in moved))


class Solid:
    """A checked watertight solid and the record of how it was made.

    A solid built from a triangle mesh (:meth:`from_arrays`) is checked with numpy (closed and
    consistently oriented, no facet of zero area in single precision, positive volume) and keeps its
    arrays: the manifold3d ``Manifold`` is built only when something asks for it (a boolean, a
    placement of a solid that has one), so writing a mesh never pays for it.

    Attributes
    ----------
    manifold : manifold3d.Manifold (built on first use for a solid made from arrays)
    name : str
    info : dict
        ``kind``, ``tol`` (requested, mm), ``achieved`` (largest measured deviation of any vertex
        or facet from the exact surface, mm), ``layers``, ``points_per_tooth``, ...
    recipe : Recipe or None
        How to rebuild it exactly (STEP); None for a mesh-only solid.
    """

    def __init__(self, manifold, name: str, info: dict, recipe: Recipe | None = None):
        self._manifold = manifold
        self.name = name
        self.info = dict(info)
        self.recipe = recipe
        self._arrays = self._measures = self._normals = None

    @classmethod
    def from_arrays(cls, vertices, faces, name: str, info: dict, recipe: Recipe | None = None) -> "Solid":
        """A solid of a triangle mesh (vertices (n, 3) mm, faces (m, 3), counter-clockwise seen from
        outside); raise :class:`GeometryError` unless it is a valid solid.

        A mesh that passes :func:`mesh_measures` is kept as arrays; one that does not (an open edge,
        a facet of zero area: coincident vertices, say) is handed to manifold3d as before, which
        merges what it can, and kept only if the result passes :func:`checked`.

        Examples
        --------
        >>> v = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
        >>> f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
        >>> round(Solid.from_arrays(v, f, "tetrahedron", {}).volume, 12)
        0.166666666667
        >>> Solid.from_arrays(v, f[:3], "open", {})
        Traceback (most recent call last):
        ...
        gearkit.errors.GeometryError: open: the mesh is not a valid solid (NotManifold)
        """
        v = np.ascontiguousarray(vertices, dtype=np.float64)
        f = np.ascontiguousarray(faces, dtype=np.int64)
        try:
            measures = mesh_measures(v, f, name)
        except RepairableMesh:  # e.g. coincident vertices: manifold3d merges them, then it is checked
            return cls(checked(manifold_from_arrays(v, f), name), name, info, recipe)
        solid = cls(None, name, info, recipe)
        solid._measures = measures
        solid._arrays = (v, f)
        return solid

    @classmethod
    def from_checked(cls, vertices, faces, measures: dict, name: str, info: dict,
                     recipe: Recipe | None = None) -> "Solid":
        """A solid of a triangle mesh its builder has already proved valid and measured as
        :func:`mesh_measures` would (``measures``: its ``{volume, area, normals}``), kept as arrays
        (:func:`gearkit.solids.extrusion.extruded`)."""
        solid = cls(None, name, info, recipe)
        solid._measures = measures
        solid._arrays = (np.ascontiguousarray(vertices, dtype=np.float64), np.ascontiguousarray(faces, dtype=np.int64))
        return solid

    @property
    def manifold(self):
        """The manifold3d ``Manifold`` (built from the arrays, and checked, on first use)."""
        if self._manifold is None:
            self._manifold = checked(manifold_from_arrays(*self._arrays), self.name)
        return self._manifold

    # -- invariants ---------------------------------------------------------------------
    @property
    def volume(self) -> float:
        """mm^3"""
        if self._measures is not None:
            return self._measures["volume"]
        return float(self.manifold.volume())

    @property
    def area(self) -> float:
        """Surface area, mm^2."""
        if self._measures is not None:
            return self._measures["area"]
        return float(self.manifold.surface_area())

    @property
    def faces(self) -> int:
        if self._arrays is not None:
            return len(self._arrays[1])
        return int(self.manifold.num_tri())

    @property
    def bounds(self):
        """((x, y, z) min, (x, y, z) max), mm."""
        if self._arrays is not None:
            columns = [self._arrays[0][:, k] for k in range(3)]  # (numpy reduces rows of 3 ten times slower)
            return tuple(float(c.min()) for c in columns), tuple(float(c.max()) for c in columns)
        b = self.manifold.bounding_box()
        return tuple(float(c) for c in b[:3]), tuple(float(c) for c in b[3:])

    @property
    def achieved(self) -> float:
        return float(self.info.get("achieved", 0.0))

    def arrays(self):
        """(vertices (n, 3) float64 mm, faces (m, 3) int64), outward (counter-clockwise) winding."""
        if self._arrays is None:
            mesh = self.manifold.to_mesh64()
            v = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
            self._arrays = (v, np.asarray(mesh.tri_verts, dtype=np.int64))
        return self._arrays

    def normals(self):
        """(m, 3) float32 unit normals of the facets, from the vertices rounded to single precision
        (as STL stores them)."""
        if self._measures is not None:
            return self._measures["normals"]
        if self._normals is None:  # a solid made by manifold3d: zero for a facet of no area, as written
            v, f = self.arrays()
            single = columns(v.astype(np.float32))
            self._normals = np.zeros((len(f), 3), dtype=np.float32)
            for s in range(0, len(f), CHUNK):
                n = np.stack(cross(gather(single, columns(f[s:s + CHUNK]))), 1)
                length = np.sqrt(np.einsum("ij,ij->i", n, n))[:, None]
                self._normals[s:s + CHUNK] = np.divide(n, length, out=np.zeros_like(n), where=length > 0)
        return self._normals

    def invariants(self) -> dict:
        """JSON-ready invariants: volume, area, bounding box, face count, requested and achieved tol."""
        lo, hi = self.bounds
        return {"volume": self.volume, "area": self.area, "bbox": [list(lo), list(hi)], "faces": self.faces,
                "tol": self.info.get("tol"), "achieved": self.info.get("achieved")}

    def summary(self) -> dict:
        """The record of the build plus the invariants (JSON-ready)."""
        out = {k: v for k, v in self.info.items() if isinstance(v, (int, float, str, bool, type(None)))}
        out.update(self.invariants())
        out["name"] = self.name
        return out

    # -- placement ----------------------------------------------------------------------
    def placed(self, angle: float = 0.0, offset=(0.0, 0.0, 0.0), name: str | None = None) -> "Solid":
        """A copy turned by ``angle`` (rad, about the z axis) and then moved by ``offset`` (mm)."""
        recipe = None if self.recipe is None else self.recipe.placed(angle, offset)
        if self._manifold is None:  # a mesh not yet handed to manifold3d: move its vertices
            v, f = self._arrays
            c, s = math.cos(angle), math.sin(angle)
            moved = v @ np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]) + np.asarray(offset, dtype=float)
            return Solid.from_arrays(moved, f, name or self.name, self.info, recipe)
        man = self.manifold
        if angle:
            man = man.rotate((0.0, 0.0, math.degrees(angle)))
        if any(offset):
            man = man.translate(tuple(float(c) for c in offset))
        return Solid(man, name or self.name, self.info, recipe)

    def to_trimesh(self):
        """The mesh as a ``trimesh.Trimesh`` (imports trimesh)."""
        import trimesh

        v, f = self.arrays()
        return trimesh.Trimesh(v, f, process=False)

    def export(self, path, ascii: bool = False):
        """Write the solid (.stl binary unless ``ascii``, .obj, .glb, .3mf, .step) atomically; returns the path."""
        from gearkit.solids.export import write_mesh

        return write_mesh(path, [self], ascii=ascii)

    def __repr__(self):
        return f"Solid({self.name!r}, faces={self.faces}, volume={self.volume:.6g} mm^3, achieved={self.achieved:.3g} mm)"


def manifold_from_arrays(vertices, faces):
    """manifold3d ``Manifold`` of a triangle mesh (vertices (n, 3) mm, faces (m, 3)); not yet checked."""
    v = np.require(vertices, dtype=np.float64, requirements=("C", "W"))
    f = np.require(faces, dtype=np.uint64, requirements=("C", "W"))
    if v.ndim != 2 or v.shape[1] != 3 or f.ndim != 2 or f.shape[1] != 3:
        raise GeometryError("a mesh needs (n, 3) vertices and (m, 3) faces")
    return m3.Manifold(m3.Mesh64(vert_properties=v, tri_verts=f))


def checked(manifold, what: str):
    """Return ``manifold`` if it is a valid, non-empty solid of positive volume; else raise GeometryError."""
    status = manifold.status()
    if status != m3.Error.NoError:
        raise GeometryError(f"{what}: the mesh is not a valid solid ({status.name})")
    if manifold.is_empty() or not manifold.volume() > 0.0:
        raise GeometryError(f"{what}: the solid is empty or inside out (volume {manifold.volume():.6g} mm^3)")
    mesh = manifold.to_mesh64()
    v = np.asarray(mesh.vert_properties)[:, :3].astype(np.float32).astype(np.float64)
    f = np.asarray(mesh.tri_verts)
    twice_area = np.linalg.norm(np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]), axis=1)
    if not (twice_area > 0.0).all():
        raise GeometryError(f"{what}: the mesh has degenerate facets (zero area in single precision)")
    return manifold
