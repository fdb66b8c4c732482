"""Solids, meshes and export: watertight gears, racks, pairs and 3D interference.

Any generated profile (every family, through :class:`~gearkit.boundary.ToothProfile`) becomes
a solid: spur, helical, herringbone / double-helical, ring gears, racks; bores with keyways.
manifold3d builds and checks the solids; the mesh writers are numpy (STL) or trimesh (OBJ
with named parts, GLB). The same ``tol`` (mm) bounds the deviation of every vertex and facet
from the exact tooth surface, twist included, and every solid reports the deviation it
achieved (``Solid.info["achieved"]``).

This package (with :mod:`gearkit.oracle`) is the only place that imports manifold3d; trimesh
is imported only where a format or a check needs it.
"""
from gearkit.solids.gear import gear_solid
from gearkit.solids.solid import Solid, SolidSpec, default_mesh_tol

__all__ = ["Solid", "SolidSpec", "default_mesh_tol", "gear_solid"]
