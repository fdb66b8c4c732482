"""Solids: what to build around a profile (:class:`SolidSpec`) and what was built (:class:`Solid`).

A :class:`Solid` wraps a manifold3d ``Manifold`` that passed its checks (valid status,
non-empty, positive volume, no degenerate facet) with the record of how it was made:
requested and achieved deviation, layer count, polyline points per tooth.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import manifold3d as m3
import numpy as np

from gearkit.errors import GeometryError, SpecError, check_fields, require


def default_mesh_tol(module: float) -> float:
    """Default mesh tolerance: 5e-3 of the module (10 um at m = 2 mm)."""
    return 5e-3 * module


def _positive(value, field, allow_none=True):
    if value is None and allow_none:
        return
    require(isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value) and value > 0,
            field, f"{value!r} must be a positive length in mm")


@dataclass(frozen=True)
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
        if self.helix_angle_deg is not None:
            b = self.helix_angle_deg
            require(isinstance(b, (int, float)) and math.isfinite(b) and -80.0 < b < 80.0, "helix_angle_deg",
                    f"{b!r} must be in (-80, 80) degrees")
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


@dataclass(frozen=True)
class Recipe:
    """How to rebuild a solid as an exact B-rep (:func:`gearkit.solids.step.shape`), and where it is placed.

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

    Attributes
    ----------
    manifold : manifold3d.Manifold
    name : str
    info : dict
        ``kind``, ``tol`` (requested, mm), ``achieved`` (largest measured deviation of any vertex
        or facet from the exact surface, mm), ``layers``, ``points_per_tooth``, ...
    recipe : Recipe or None
        How to rebuild it exactly (STEP); None for a mesh-only solid.
    """

    def __init__(self, manifold, name: str, info: dict, recipe: Recipe | None = None):
        self.manifold = manifold
        self.name = name
        self.info = dict(info)
        self.recipe = recipe
        self._arrays = None

    @classmethod
    def from_arrays(cls, vertices, faces, name: str, info: dict, recipe: Recipe | None = None) -> "Solid":
        """Build from a triangle mesh; raise :class:`GeometryError` unless it is a valid solid."""
        return cls(checked(manifold_from_arrays(vertices, faces), name), name, info, recipe)

    # -- invariants ---------------------------------------------------------------------
    @property
    def volume(self) -> float:
        """mm^3"""
        return float(self.manifold.volume())

    @property
    def area(self) -> float:
        """Surface area, mm^2."""
        return float(self.manifold.surface_area())

    @property
    def faces(self) -> int:
        return int(self.manifold.num_tri())

    @property
    def bounds(self):
        """((x, y, z) min, (x, y, z) max), mm."""
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
        man = self.manifold
        if angle:
            man = man.rotate((0.0, 0.0, math.degrees(angle)))
        if any(offset):
            man = man.translate(tuple(float(c) for c in offset))
        recipe = None if self.recipe is None else self.recipe.placed(angle, offset)
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
