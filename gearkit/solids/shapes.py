"""The exact B-rep (OpenCascade solid) of every part gearkit makes, from its recipe.

Each :class:`~gearkit.solids.Solid` made by gearkit carries a :class:`~gearkit.solids.solid.Recipe`
(what it was built from and where it was placed); :func:`shape` rebuilds it as one valid
OpenCascade solid through :mod:`gearkit.solids.brep`: gears (spur, helical, herringbone,
double-helical, ring; bore and keyway), rack bars (helical racks sheared), cylinders, tubes,
and differences/unions of those (a cycloid disc's output holes). A gear of many teeth has its
end caps cut into sectors (:func:`cap_sectors`, :mod:`gearkit.solids.faces`). :mod:`gearkit.solids.step`
writes and reads the STEP files.

A new family plugs in with :func:`section_shape`: a closed loop of exact plane curves swept
along z (straight, twisted or sheared), or a :class:`~gearkit.solids.solid.Recipe` of kind
``"section"``.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.errors import GeometryError, SpecError
from gearkit.solids import brep

#: axial overshoot of a cutting tool beyond the part, as a fraction of its width (no coplanar faces)
_OVER = 0.05


def _rot(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s], [s, c]])


def tooth_curves(profile, tol: float, rack: bool = False):
    """Fitted curves of one tooth of ``profile`` (its ``half.pieces``), counter-clockwise for a gear
    (right space centre -> tip -> left space centre), left to right for a rack."""
    half = [brep.fit_curve(pc, brep.CURVE_SHARE * tol) for pc in profile.half.pieces]
    mirror = np.diag([-1.0, 1.0])
    if rack:
        return [c.transformed(mirror, mirror=True) for c in half[::-1]] + half
    return [c.transformed(np.eye(2), mirror=True) for c in half[::-1]] + [c.transformed(mirror) for c in half]


def _teeth(tooth, teeth: int):
    return [c.transformed(_rot(2.0 * math.pi * k / teeth)) for k in range(teeth) for c in tooth]


def section_shape(curves, runs, tol: float, measure=None, outer=None, sectors=None):
    """(solid, achieved deviation mm) of a closed loop of exact curves swept through runs.

    Parameters
    ----------
    curves : list of callables ``w -> (n, 2)`` mm, or of :class:`~gearkit.solids.brep.FittedCurve`
        A closed loop, counter-clockwise round the material.
    runs : list of :class:`~gearkit.solids.brep.Run` (z ranges with their turn and shift)
    tol : float, mm
    measure : indices of the curves whose surfaces are measured (default all)
    outer : float or None, mm: the loop is a hole in a cylinder of this radius (a ring)
    sectors : (curves per sector, radius) or None: end caps cut into sectors (a gear of many teeth,
        :func:`~gearkit.solids.brep.to_shape`)
    """
    fitted = [c if isinstance(c, brep.FittedCurve) else brep.fit_curve(c, brep.CURVE_SHARE * tol) for c in curves]
    sw = brep.sweep(fitted, runs, tol, measure)
    return brep.to_shape(sw, outer, sectors, BAR[0]), sw.achieved


#: the progress bar of the STEP file being written (advanced per face made)
BAR: list = [None]
#: a gear's end caps are cut into sectors above this many edges per cap (:mod:`gearkit.solids.faces`)
SECTOR_ABOVE = 256


def cap_sectors(teeth: int, per_tooth: int, r_min: float, r_max: float, module: float, internal: bool,
                outer: float | None = None, inner: float = 0.0):
    """(curves per sector, dividing radius) for a gear's end caps, or None for a cap of one face.

    About sqrt(edges) edges per sector, whole teeth each; the dividing circle half a module below the
    root (above it for a ring, half way to the rim), above ``inner`` (a bore and keyway's reach, mm).

    Examples
    --------
    >>> cap_sectors(2000, 8, 997.5, 1001.0, 1.0, False)
    (128, 997.0)
    >>> cap_sectors(20, 8, 8.75, 11.0, 1.0, False) is None
    True
    """
    if teeth * per_tooth <= SECTOR_ABOVE:
        return None
    group = max(1, round(math.sqrt(teeth / per_tooth)))
    if internal:
        core = r_max + min(0.5 * module, 0.5 * (outer - r_max))
    else:
        core = r_min - min(0.5 * module, 0.5 * (r_min - inner))
    return group * per_tooth, core


def _helix_runs(k, z0, z1, herringbone, over=0.0):
    """Runs of a helical (or herringbone) gear from z0 to z1 (``theta = k z``; a herringbone turns
    back from the middle), extended by ``over`` at both ends."""
    mid = (z0 + z1) / 2.0

    def th(z):
        return k * ((z1 - z0) / 2.0 - abs(z - mid)) if herringbone else k * z
    if not herringbone:
        return [brep.Run(z0 - over, z1 + over, th(z0 - over), th(z1 + over))]
    return [brep.Run(z0 - over, mid, th(z0 - over), th(mid)), brep.Run(mid, z1 + over, th(mid), th(z1 + over))]


def cylinder(radius, z0, z1, centre=(0.0, 0.0)):
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt

    ax = gp_Ax2(gp_Pnt(float(centre[0]), float(centre[1]), float(z0)), gp_Dir(0.0, 0.0, 1.0))
    return BRepPrimAPI_MakeCylinder(ax, float(radius), float(z1 - z0)).Shape()


def _box(x0, y0, z0, x1, y1, z1):
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
    from OCP.gp import gp_Pnt

    return BRepPrimAPI_MakeBox(gp_Pnt(x0, y0, z0), gp_Pnt(x1, y1, z1)).Shape()


def _boolean(kind, a, b):
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Common, BRepAlgoAPI_Cut, BRepAlgoAPI_Fuse

    op = {"cut": BRepAlgoAPI_Cut, "fuse": BRepAlgoAPI_Fuse, "common": BRepAlgoAPI_Common}[kind](a, b)
    if not op.IsDone():
        raise GeometryError(f"B-rep boolean ({kind}) failed")
    shape = op.Shape()
    if kind == "fuse":
        from OCP.ShapeUpgrade import ShapeUpgrade_UnifySameDomain

        unify = ShapeUpgrade_UnifySameDomain(shape, True, True, False)
        unify.Build()
        shape = unify.Shape()
    return shape


def _radii(curves):
    u = [c(c.grid()) for c in curves]
    r = np.concatenate([np.hypot(p[:, 0], p[:, 1]) for p in u])
    return float(r.min()), float(r.max())


def gear_shape(profile, spec, tol: float):
    """(solid, achieved) of :func:`~gearkit.solids.gear_solid`'s gear as an exact B-rep."""
    from gearkit.solids.surface import helix_angle, reference_radius

    beta = math.radians(helix_angle(profile, spec))
    k = math.tan(beta) / reference_radius(profile, abs(beta))
    tooth = tooth_curves(profile, tol)
    curves = _teeth(tooth, profile.teeth)
    measure = range(len(tooth))
    b, gap = spec.width, spec.gap
    run = (b - gap) / 2.0 if spec.herringbone else b
    r_min, r_max = _radii(tooth)
    r_out = None
    if profile.internal:
        r_out = spec.outer_diameter / 2.0 if spec.outer_diameter else r_max + (spec.rim or 2.0 * profile.module)
    inner = 0.0 if spec.bore is None else math.hypot(spec.bore / 2.0 + (spec.keyway or (0, 0))[1],
                                                     (spec.keyway or (0, 0))[0] / 2.0)
    sectors = cap_sectors(profile.teeth, len(tooth), r_min, r_max, profile.module, profile.internal, r_out, inner)
    if spec.herringbone and gap > 0.0:
        lo, a1 = section_shape(curves, [brep.Run(0.0, run, 0.0, k * run)], tol, measure, r_out, sectors)
        hi, a2 = section_shape(curves, [brep.Run(b - run, b, k * run, 0.0)], tol, measure, r_out, sectors)
        if profile.internal:  # the groove: a tube between the halves, glued to their end faces
            middle = _boolean("cut", cylinder(r_out, run, b - run),
                              cylinder(r_max + profile.module, run - 1.0, b - run + 1.0))
        else:  # a core reaching into both halves
            middle = cylinder(r_min - profile.module, run / 2.0, b - run / 2.0)
        body = _boolean("fuse", _boolean("fuse", lo, middle), hi)
        achieved = max(a1, a2)
    else:
        body, achieved = section_shape(curves, _helix_runs(k, 0.0, b, spec.herringbone), tol, measure, r_out,
                                       sectors)
    if profile.internal:
        return body, achieved
    return _bored(body, spec), achieved


def _bored(body, spec):
    """``body`` with the spec's bore (and keyway, centred on +y) cut through it."""
    if spec.bore is None:
        return body
    b, r = spec.width, spec.bore / 2.0
    tool = cylinder(r, -_OVER * b, b * (1 + _OVER))
    if spec.keyway is not None:
        w, depth = spec.keyway
        tool = _boolean("fuse", tool, _box(-w / 2.0, 0.0, -_OVER * b, w / 2.0, r + depth, b * (1 + _OVER)))
    return _boolean("cut", body, tool)


def prism_shape(curves, spec, tol: float):
    """(solid, achieved) of :func:`~gearkit.solids.prism_solid`'s prism: the loop of exact ``curves``
    extruded over ``spec.width``, with the spec's bore and keyway."""
    body, achieved = section_shape(list(curves), [brep.Run(0.0, float(spec.width))], tol)
    return _bored(body, spec), achieved


def rack_shape(profile, length, height, width, start, tol: float):
    """(solid, achieved) of :func:`~gearkit.solids.rack_solid`'s bar as an exact B-rep."""
    tooth = tooth_curves(profile, tol, rack=True)
    tips = np.concatenate([c(c.grid())[:, 1] for c in tooth])
    tip = float(tips.max())
    shear = math.tan(math.radians(float(getattr(getattr(profile, "spec", None), "helix_angle_deg", 0.0) or 0.0)))
    p = profile.pitch
    reach = abs(shear) * width + p
    k0, k1 = math.floor((start - reach) / p), math.ceil((start + length + reach) / p)
    row = [c.transformed(np.eye(2)) for c in tooth]
    curves = []
    for j in range(k0, k1 + 1):
        curves += [_shifted(c, j * p) for c in row]
    back = tip - height
    a, z = curves[-1](np.array([curves[-1].knots[-1]]))[0], curves[0](np.array([curves[0].knots[0]]))[0]
    corners = [a, (a[0], back), (z[0], back), z]
    lines = [_line(corners[i], corners[i + 1]) for i in range(3)]
    loop = curves + lines
    measure = range(len(tooth))
    bar, achieved = section_shape(loop, [brep.Run(0.0, width, 0.0, 0.0, 0.0, width * shear)], tol, measure)
    box = _box(start, back - height, -0.5 * width, start + length, back + 3.0 * height, 1.5 * width)
    return _boolean("common", bar, box), achieved


def _shifted(c, dx):
    exact = c.exact
    return brep.FittedCurve(c.knots, c.poles + (dx, 0.0), c.degree,
                            lambda w, exact=exact, dx=dx: exact(w) + (dx, 0.0), c.deviation)


def _line(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    return brep.FittedCurve(np.array([0.0, 0.0, 1.0, 1.0]), np.stack([a, b]), 1,
                            lambda w, a=a, b=b: a + np.asarray(w, float)[:, None] * (b - a), 0.0)


def _compound(shapes):
    """Disjoint bodies as one shape (no boolean needed)."""
    from OCP.BRep import BRep_Builder
    from OCP.TopoDS import TopoDS_Compound

    builder, out = BRep_Builder(), TopoDS_Compound()
    builder.MakeCompound(out)
    for sh in shapes:
        builder.Add(out, sh)
    return out


def _placed(shape, angle, offset):
    if not angle and not any(offset):
        return shape
    from OCP.BRepBuilderAPI import BRepBuilderAPI_Transform
    from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt, gp_Trsf, gp_Vec

    rot, move = gp_Trsf(), gp_Trsf()
    rot.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), float(angle))
    move.SetTranslation(gp_Vec(*map(float, offset)))
    return BRepBuilderAPI_Transform(shape, move.Multiplied(rot), True).Shape()


def shape(recipe):
    """(solid, achieved deviation mm) of a :class:`~gearkit.solids.solid.Recipe`, placed."""
    brep.require_kernel()
    kind, args = recipe.kind, recipe.args
    achieved = 0.0
    if kind == "gear":
        out, achieved = gear_shape(*args)
    elif kind == "rack":
        out, achieved = rack_shape(*args)
    elif kind == "section":
        out, achieved = section_shape(*args)
    elif kind == "prism":
        out, achieved = prism_shape(*args)
    elif kind == "cylinders":
        centres, radius, z0, z1 = args
        out = _compound([cylinder(radius, z0, z1, c) for c in centres])
    elif kind == "tube":
        inner, outer, z0, z1 = args
        out = _boolean("cut", cylinder(outer, z0, z1), cylinder(inner, z0 - 1.0, z1 + 1.0))
    elif kind in ("difference", "union"):
        (out, achieved), (other, a2) = shape(args[0]), shape(args[1])
        out = _boolean("cut" if kind == "difference" else "fuse", out, other)
        achieved = max(achieved, a2)
    else:
        raise SpecError("output", f"no exact B-rep for a part of kind {kind!r}")
    return _placed(out, recipe.angle, recipe.offset), achieved
