"""Solids, meshes and export: watertight gears, racks, pairs and 3D interference.

Any generated profile (every family, through :class:`~gearkit.profile.ToothProfile`) becomes
a solid: spur, helical, herringbone / double-helical, ring gears (:func:`gear_solid`), rack bars
(:func:`rack_solid`); bores with keyways. Pairs are placed at their centre distance, phased,
and tested for 3D interference (:func:`pair_assembly`). A solid built from a triangle mesh is
checked with numpy (closed, oriented, no facet of zero area in single precision, positive volume;
a straight gear by the structure of its swept section, :mod:`gearkit.solids.extrusion`)
and handed to manifold3d only when a boolean asks for it; STL, OBJ (named parts), GLB (named nodes) and
3MF are written with numpy a chunk at a time behind a progress bar (:func:`write_mesh`, atomic). The same ``tol`` (mm) bounds the deviation of every vertex and
facet from the exact tooth surface, twist included, and every solid reports the deviation it
achieved (``Solid.achieved``). STEP rebuilds each part from its :class:`Recipe` as an exact B-rep
(:mod:`gearkit.solids.step`, B-spline flanks, planar ends, cylindrical bores) with the optional
``gearkit[step]`` kernel, imported only then. Any other closed outline of exact curves (a cam,
a plate) becomes a solid, with its recipe, through :func:`prism_solid`.

This package (with :mod:`gearkit.oracles.involute`) is the only place that imports manifold3d and OCP; trimesh
is imported only by :meth:`Solid.to_trimesh`.
"""
from gearkit import lazy_exports

#: module -> the names it exports (loaded on first use: importing the package costs nothing)
_EXPORTS = {
    "gearkit.solids.export": ("MESH_FORMATS", "mesh_format", "write_mesh"),
    "gearkit.solids.gear": ("gear_solid",),
    "gearkit.solids.pair": ("Assembly", "pair_assembly"),
    "gearkit.solids.prism": ("prism_solid",),
    "gearkit.solids.rack": ("rack_solid",),
    "gearkit.solids.solid": ("Recipe", "Solid", "SolidSpec", "default_mesh_tol"),
}
__all__ = ["Assembly", "MESH_FORMATS", "Recipe", "Solid", "SolidSpec", "default_mesh_tol", "gear_solid", "mesh_format",
           "pair_assembly", "prism_solid", "rack_solid", "write_mesh"]

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
