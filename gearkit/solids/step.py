"""STEP: the exact B-rep of every part (B-spline flanks, planar ends, cylindrical bores), named.

:func:`write_step` writes the parts' solids (:func:`~gearkit.solids.shapes.shape`, rebuilt from each
:class:`~gearkit.solids.Solid`'s recipe) as one STEP file (AP214, mm): one named product per part, an
assembly when there are several; a progress bar (:class:`~gearkit.progress.Progress`) follows the work.
:func:`estimate_faces` tells the size of that work before any of it (the command line refuses a file
above its limit). :func:`read_step` reads a STEP file back as named shapes. ``shape``, ``gear_shape``
and ``section_shape`` are :mod:`gearkit.solids.shapes`' own, named here too.
"""
from __future__ import annotations

import math

from gearkit.errors import GeometryError, SpecError
from gearkit.export import atomic_write
from gearkit.solids import brep, shapes
from gearkit.solids.shapes import gear_shape, section_shape, shape

__all__ = ["estimate_faces", "gear_shape", "part_shapes", "read_step", "recipe_faces", "section_shape", "shape", "write_step"]


def part_shapes(parts):
    """[(name, solid, achieved)] of gearkit solids; each checked to be one valid solid."""
    out = []
    for part in parts:
        if part.recipe is None:
            raise SpecError("output", f"part {part.name!r} has no exact B-rep (STEP): write a mesh format instead")
        solid, achieved = shape(part.recipe)
        pieces = len(part.manifold.decompose())  # a part may be several bodies (a ring of pins)
        if shapes.BAR[0] is not None:
            shapes.BAR[0].note = "checking the solid"
            shapes.BAR[0].update(shapes.BAR[0].done)
        out.append((part.name, brep.check_solid(solid, part.name, pieces), achieved))
        if shapes.BAR[0] is not None:
            shapes.BAR[0].step(recipe_faces(part.recipe))
    return out


def write_step(path, parts) -> dict:
    """Write the parts' exact B-reps to a STEP file (atomically); returns the achieved deviation.

    Parameters
    ----------
    path : str or Path, ending in .step or .stp
    parts : sequence of Solid (each with a recipe); several parts make a named assembly

    Returns
    -------
    dict: ``achieved`` (mm, the largest over the parts) and ``parts`` (name -> achieved)
    """
    from gearkit.progress import Progress

    brep.require_kernel()
    parts = list(parts)
    faces = estimate_faces(parts)
    # steps: each face made, then sewn, checked, transferred and written (a step per face each)
    with Progress("STEP", 5 * faces, unit="") as bar:
        shapes.BAR[0] = bar
        try:
            bar.note = "making the faces"
            built = part_shapes(parts)
        finally:
            shapes.BAR[0] = None
        bar.note = "writing the file"
        bar.update(3 * faces)
        atomic_write(path, lambda tmp: _quiet(_write, tmp, built, len(built) > 1, bar))
    return {"achieved": max(a for _, _, a in built), "parts": {n: a for n, _, a in built}}


def estimate_faces(parts) -> int:
    """About how many B-rep faces the parts' STEP file holds (from their recipes, before any is built).

    Examples
    --------
    >>> from gearkit.families.involute import GearSpec, tooth_profile
    >>> from gearkit.solids import SolidSpec, gear_solid
    >>> prof = tooth_profile(GearSpec(2000, 1.0))
    >>> estimate_faces([gear_solid(prof, SolidSpec(width=5.0), tol=0.005)]) // 1000
    16
    """
    return sum(recipe_faces(p.recipe) for p in parts if p.recipe is not None)


def recipe_faces(recipe) -> int:
    """About how many B-rep faces a :class:`~gearkit.solids.solid.Recipe` makes (no solid is built)."""
    kind, args = recipe.kind, recipe.args
    if kind == "gear":
        profile, spec = args[0], args[1]
        per_tooth = 2 * len(profile.half.pieces)
        sectors = 1 + profile.teeth * per_tooth // max(int(math.sqrt(profile.teeth * per_tooth)), 1)
        runs = 2 if spec.herringbone else 1
        return runs * (profile.teeth * per_tooth + 2 * sectors) + 4
    if kind == "rack":
        profile, length = args[:2]
        teeth = length / profile.pitch + 2  # the bar cut to its length (a tooth more at each end before)
        return int(teeth * 2 * len(profile.half.pieces)) + 6
    if kind in ("prism", "section"):
        return len(args[0]) * (len(args[1]) if kind == "section" else 1) + 6
    if kind == "cylinders":
        return 3 * len(args[0])
    if kind in ("difference", "union"):
        return recipe_faces(args[0]) + recipe_faces(args[1])
    return 4


def _write(tmp, built, assembly: bool, bar=None):
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.Interface import Interface_Static
    from OCP.STEPCAFControl import STEPCAFControl_Writer
    from OCP.STEPControl import STEPControl_AsIs
    from OCP.TCollection import TCollection_ExtendedString
    from OCP.TDataStd import TDataStd_Name
    from OCP.TDocStd import TDocStd_Document
    from OCP.TopLoc import TopLoc_Location
    from OCP.XCAFDoc import XCAFDoc_DocumentTool

    doc = TDocStd_Document(TCollection_ExtendedString("XmlXCAF"))
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    top = tool.NewShape() if assembly else None
    if assembly:
        TDataStd_Name.Set_s(top, TCollection_ExtendedString("assembly"))
    for name, solid, _ in built:
        label = tool.AddShape(solid, False)
        TDataStd_Name.Set_s(label, TCollection_ExtendedString(name))
        if assembly:
            comp = tool.AddComponent(top, label, TopLoc_Location())
            TDataStd_Name.Set_s(comp, TCollection_ExtendedString(name))
    if assembly:
        tool.UpdateAssemblies()
    Interface_Static.SetCVal_s("write.step.unit", "MM")
    Interface_Static.SetCVal_s("write.step.schema", "AP214IS")
    writer = STEPCAFControl_Writer()
    writer.SetNameMode(True)
    if not writer.Transfer(doc, STEPControl_AsIs):
        raise GeometryError("STEP transfer failed")
    if bar is not None:
        bar.step(bar.total // 5)
    if writer.Write(str(tmp)) != IFSelect_RetDone:
        raise GeometryError(f"could not write {tmp}")


def _quiet(func, *args, **kwargs):
    """Run ``func`` with the process's stdout sent to /dev/null (the kernel prints transfer statistics)."""
    import os
    import sys

    sys.stdout.flush()
    saved = os.dup(1)
    null = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(null, 1)
        return func(*args, **kwargs)
    finally:
        os.dup2(saved, 1)
        os.close(saved)
        os.close(null)


def read_step(path) -> list:
    """The parts of a STEP file: [(name, shape)], assemblies flattened (placements applied).

    Examples
    --------
    >>> import tempfile, os
    >>> from gearkit.families.involute import GearSpec, tooth_profile
    >>> from gearkit.solids import SolidSpec, gear_solid
    >>> g = gear_solid(tooth_profile(GearSpec(10, 2.0)), SolidSpec(width=4.0, bore=6.0), tol=0.01)
    >>> path = os.path.join(tempfile.mkdtemp(), "g.step")
    >>> _ = write_step(path, [g])
    >>> [(name, brep.count_solids(s)) for name, s in read_step(path)]
    [('gear', 1)]
    """
    brep.require_kernel()
    from OCP.collections import Sequence_TDF_Label
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPCAFControl import STEPCAFControl_Reader
    from OCP.TCollection import TCollection_ExtendedString
    from OCP.TDocStd import TDocStd_Document
    from OCP.XCAFDoc import XCAFDoc_DocumentTool, XCAFDoc_ShapeTool

    reader = STEPCAFControl_Reader()
    reader.SetNameMode(True)
    if _quiet(reader.ReadFile, str(path)) != IFSelect_RetDone:
        raise SpecError("input", f"cannot read STEP file {str(path)!r}")
    doc = TDocStd_Document(TCollection_ExtendedString("XmlXCAF"))
    if not _quiet(reader.Transfer, doc):
        raise SpecError("input", f"cannot transfer STEP file {str(path)!r}")
    tool = XCAFDoc_DocumentTool.ShapeTool_s(doc.Main())
    free = Sequence_TDF_Label()
    tool.GetFreeShapes(free)
    out = []
    for i in range(1, free.Length() + 1):
        label = free.Value(i)
        if XCAFDoc_ShapeTool.IsAssembly_s(label):
            comps = Sequence_TDF_Label()
            XCAFDoc_ShapeTool.GetComponents_s(label, comps)
            for j in range(1, comps.Length() + 1):
                comp = comps.Value(j)
                out.append((_name(comp), XCAFDoc_ShapeTool.GetShape_s(comp)))
        else:
            out.append((_name(label), XCAFDoc_ShapeTool.GetShape_s(label)))
    return out


def _name(label) -> str:
    from OCP.TDataStd import TDataStd_Name

    attr = TDataStd_Name()
    if label.FindAttribute(TDataStd_Name.GetID_s(), attr):
        return attr.Get().ToExtString()
    return ""
