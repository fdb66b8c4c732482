"""Exact B-rep solids (OpenCascade through OCP): B-spline flanks fitted to the generated curves.

A *section* is a closed loop of exact plane curves (each a vectorised callable ``w -> (n, 2)``
points, ``w`` in [0, 1], counter-clockwise round the material). Every curve is fitted by a
cubic B-spline ``C(u)`` interpolating the exact curve at nodes placed by
:func:`~gearkit.accuracy.adaptive_sample` (ends exact). The section is then *swept* along z
through *runs*: in a run the section turns by ``theta(z)`` (linear in z: a helix) and may be
sheared along x by ``s(z)`` (linear: a helical rack). The rotation ``R(theta(z))`` is
interpolated by cubic B-splines in z, ``H(z) = [[a(z), -b(z)], [b(z), a(z)]]`` (a spur run:
degree 1, exact), so each flank becomes the tensor-product B-spline surface
``S(u, z) = H(z) C(u) + (s(z), 0, z)`` with poles ``H_j P_i`` (z is reproduced exactly by its
Greville abscissae). End faces are planes, bores cylinders (boolean cuts through the solid).

**Deviation.** Each surface is compared with the exact surface on a parameter grid (8 points
per knot span in u and in z): ``|S(u, z) - (R(theta(z)) c(w(u)) + (s(z), 0, z))|`` bounds
the distance of the surface point from the exact surface. The fit is refined until the
largest measured value meets ``tol`` (the curve fit takes at most ``CURVE_SHARE`` of it).

This module, :mod:`gearkit.solids.faces` and :mod:`gearkit.solids.step` are the only ones that import OCP; it is imported
only when an exact solid is asked for.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import BSpline, make_interp_spline

from gearkit.accuracy import adaptive_sample
from gearkit.errors import GeometryError, SpecError
from gearkit.solids import faces

#: share of ``tol`` the curve fit may take; the rest is the helix interpolation's
CURVE_SHARE = 0.5
#: sewing tolerance, mm (shared edges are built from the same poles; this absorbs round-off)
SEW_TOL = 1e-6
_SUB = 8  # measured points per knot span

EXTRA = "gearkit[step]"


def require_kernel():
    """Import OCP or raise a SpecError naming the optional extra."""
    try:
        import OCP.BRepBuilderAPI  # noqa: F401
    except ImportError:
        raise SpecError("output", f"STEP needs the optional B-rep kernel: pip install '{EXTRA}'") from None


# -- curves ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class FittedCurve:
    """A plane cubic B-spline fitted to an exact curve.

    knots : (m,) float64, the full knot vector (clamped); poles : (n, 2) float64, mm;
    exact : the exact curve ``w -> (k, 2)`` the spline's parameter follows (None for a
    transformed copy that carries ``map``); deviation : largest measured |C(u) - c(u)|, mm.
    """

    knots: np.ndarray
    poles: np.ndarray
    degree: int
    exact: object
    deviation: float

    def __call__(self, u):
        return BSpline(self.knots, self.poles, self.degree, extrapolate=False)(np.asarray(u, dtype=float))

    def grid(self) -> np.ndarray:
        """Parameters of the measurement grid: ``_SUB`` per knot span."""
        k = np.unique(self.knots)
        sub = np.linspace(0.0, 1.0, _SUB + 1)[:-1]
        return np.append((k[:-1, None] + np.diff(k)[:, None] * sub[None, :]).ravel(), k[-1])

    def transformed(self, matrix, mirror: bool = False) -> "FittedCurve":
        """The curve under a 2x2 linear map (poles mapped exactly); ``mirror`` reverses it."""
        m = np.asarray(matrix, dtype=float)
        exact = self.exact

        def mapped(w, exact=exact, m=m, mirror=mirror):
            w = np.asarray(w, dtype=float)
            return exact(1.0 - w if mirror else w) @ m.T

        poles = self.poles @ m.T
        knots = self.knots
        if mirror:
            poles, knots = poles[::-1], (knots[-1] + knots[0] - knots)[::-1]
        return FittedCurve(knots, poles, self.degree, mapped, self.deviation)


def fit_curve(curve, tol: float) -> FittedCurve:
    """Cubic B-spline through the exact curve ``w -> (n, 2)`` with every measured point within ``tol``.

    Examples
    --------
    >>> import numpy as np
    >>> arc = lambda w: 10.0 * np.stack([np.cos(w), np.sin(w)], -1)
    >>> c = fit_curve(arc, 1e-4)
    >>> c.deviation <= 1e-4, bool(np.allclose(c(np.array([0.0, 1.0])), arc(np.array([0.0, 1.0]))))
    (True, True)
    """
    chord = 50.0 * tol
    for _ in range(12):
        w, _, _ = adaptive_sample(curve, chord)
        if len(w) < 4:
            w = np.linspace(w[0], w[-1], 4)
        spline = make_interp_spline(w, curve(w), k=3)
        fitted = FittedCurve(np.asarray(spline.t, float), np.asarray(spline.c, float), 3, curve, 0.0)
        u = fitted.grid()
        dev = float(np.linalg.norm(fitted(u) - curve(u), axis=1).max())
        if dev <= tol:
            return FittedCurve(fitted.knots, fitted.poles, 3, curve, dev)
        chord /= 4.0
    raise GeometryError(f"cannot fit a B-spline within {tol:g} mm to an exact curve")


# -- runs along z -----------------------------------------------------------------------------
@dataclass(frozen=True)
class Run:
    """A straight piece of the sweep: z from ``z0`` to ``z1``; the section turned by ``theta0`` ->
    ``theta1`` (rad, linear in z) and moved along x by ``shift0`` -> ``shift1`` (mm, linear)."""

    z0: float
    z1: float
    theta0: float = 0.0
    theta1: float = 0.0
    shift0: float = 0.0
    shift1: float = 0.0

    def theta(self, z):
        return self.theta0 + (self.theta1 - self.theta0) * (np.asarray(z) - self.z0) / (self.z1 - self.z0)

    def shift(self, z):
        return self.shift0 + (self.shift1 - self.shift0) * (np.asarray(z) - self.z0) / (self.z1 - self.z0)


def _rotation_spline(run: Run, limit: float, r_max: float):
    """(knots, coefficients (m, 2) of (cos, sin), degree, Greville z) with the interpolation error of
    ``R(theta(z))`` times ``r_max`` within ``limit``; returns also the measured rotation error."""
    if run.theta0 == run.theta1:
        c, s = math.cos(run.theta0), math.sin(run.theta0)
        return np.array([run.z0, run.z0, run.z1, run.z1]), np.array([[c, s], [c, s]]), 1, \
            np.array([run.z0, run.z1]), 0.0
    span = abs(run.theta1 - run.theta0)
    n = max(3, math.ceil(span * (r_max / (limit * 384.0 / 5.0)) ** 0.25) + 1)
    for _ in range(20):
        z = np.linspace(run.z0, run.z1, n + 1)
        th = run.theta(z)
        spl = make_interp_spline(z, np.stack([np.cos(th), np.sin(th)], -1), k=3)
        knots, coef = np.asarray(spl.t, float), np.asarray(spl.c, float)
        zz = np.linspace(run.z0, run.z1, _SUB * n + 1)
        tt = run.theta(zz)
        err = float(np.linalg.norm(spl(zz) - np.stack([np.cos(tt), np.sin(tt)], -1), axis=1).max())
        if err * r_max <= limit:
            greville = np.array([knots[j + 1:j + 4].mean() for j in range(len(coef))])
            return knots, coef, 3, greville, err
        n = math.ceil(1.5 * n)
    raise GeometryError("cannot interpolate the helix within tol")


@dataclass
class Sweep:
    """The B-spline surfaces of a section swept through runs (numpy only; OCP in :func:`to_shape`)."""

    curves: list  # FittedCurve per section edge, counter-clockwise
    runs: list  # Run
    patches: list  # per run: (knots_v, coef_v (m, 2), degree_v, greville (m,), shift poles (m,))
    achieved: float


def sweep(curves, runs, tol: float, measure=None) -> Sweep:
    """Plan the surfaces of ``curves`` (a closed loop) swept through ``runs`` within ``tol``.

    ``measure``: indices of the curves whose surfaces are measured (default all; a gear
    measures one tooth, the others are its exact rotations).
    """
    r_max = max(float(np.hypot(c.poles[:, 0], c.poles[:, 1]).max()) for c in curves)
    curve_dev = max(c.deviation for c in curves)
    limit = max(tol - curve_dev, 0.0) * 0.95
    patches = []
    for run in runs:
        knots, coef, deg, grev, _ = _rotation_spline(run, limit, r_max)
        patches.append((knots, coef, deg, grev, run.shift(grev)))
    out = Sweep(list(curves), list(runs), patches, 0.0)
    idx = range(len(curves)) if measure is None else measure
    out.achieved = max(_surface_deviation(curves[i], run, p) for i in idx for run, p in zip(runs, patches))
    if out.achieved > tol:
        raise GeometryError(f"the surfaces deviate {out.achieved:.3g} mm from the exact ones (tol {tol:g} mm)")
    return out


def _surface_deviation(curve: FittedCurve, run: Run, patch) -> float:
    """Largest |S(u, z) - exact(u, z)| on the measurement grid, mm."""
    knots, coef, deg, grev, _ = patch
    u = curve.grid()
    cf, ce = curve(u), curve.exact(u)
    kz = np.unique(knots)
    sub = np.linspace(0.0, 1.0, _SUB + 1)[:-1]
    z = np.append((kz[:-1, None] + np.diff(kz)[:, None] * sub[None, :]).ravel(), kz[-1])
    ab = BSpline(knots, coef, deg)(z)
    th = run.theta(z)
    ca, sa = np.cos(th)[:, None], np.sin(th)[:, None]
    fx = ab[:, :1] * cf[None, :, 0] - ab[:, 1:] * cf[None, :, 1]
    fy = ab[:, 1:] * cf[None, :, 0] + ab[:, :1] * cf[None, :, 1]
    ex = ca * ce[None, :, 0] - sa * ce[None, :, 1]
    ey = sa * ce[None, :, 0] + ca * ce[None, :, 1]
    # the shift is linear in z and reproduced exactly by its Greville poles: it cancels
    return float(np.hypot(fx - ex, fy - ey).max())


# -- OCP ------------------------------------------------------------------------------------------
def _surface(curve: FittedCurve, patch):
    from OCP.collections import Array2_gp_Pnt
    from OCP.Geom import Geom_BSplineSurface
    from OCP.gp import gp_Pnt

    knots_v, coef, deg_v, grev, shift = patch
    p = curve.poles
    qx = coef[None, :, 0] * p[:, None, 0] - coef[None, :, 1] * p[:, None, 1] + shift[None, :]
    qy = coef[None, :, 1] * p[:, None, 0] + coef[None, :, 0] * p[:, None, 1]
    nu, nv = qx.shape
    poles = Array2_gp_Pnt(1, nu, 1, nv)
    for i in range(nu):
        for j in range(nv):
            poles.SetValue(i + 1, j + 1, gp_Pnt(float(qx[i, j]), float(qy[i, j]), float(grev[j])))
    uk, um = faces.knot_arrays(curve.knots)
    vk, vm = faces.knot_arrays(knots_v)
    surf = Geom_BSplineSurface(poles, uk, vk, um, vm, curve.degree, deg_v)
    ends = [np.column_stack([qx[:, j], qy[:, j], np.full(nu, grev[j])]) for j in (0, -1)]
    return surf, ends


def to_shape(sw: Sweep, outer: float | None = None, sectors=None, bar=None):
    """The closed, valid OCP solid of a planned sweep; with ``outer`` (radius, mm) the section is a
    hole in a cylinder of that radius (a ring gear). ``sectors`` ``(curves per sector, radius of the
    dividing circle)`` cuts each end cap into sectors (:func:`~gearkit.solids.faces.sector_caps`: the
    section's loop must start at a space centre, and every sector too). ``bar``: a
    :class:`~gearkit.progress.Progress` advanced by one step per face made."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeSolid, BRepBuilderAPI_Sewing
    from OCP.TopAbs import TopAbs_SHELL
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    sewing = BRepBuilderAPI_Sewing(SEW_TOL)
    bottom, top, ends_at = [], [], ([], [])
    for r, patch in enumerate(sw.patches):
        for c in sw.curves:
            surf, ends = _surface(c, patch)
            sewing.Add(BRepBuilderAPI_MakeFace(surf, 1e-9).Face())
            if r == 0:
                bottom.append(faces.bspline_edge(ends[0], c.knots, c.degree))
                ends_at[0].append(ends[0][0, :2])
            if r == len(sw.patches) - 1:
                top.append(faces.bspline_edge(ends[1], c.knots, c.degree))
                ends_at[1].append(ends[1][0, :2])
            if bar is not None:
                bar.step()
    z0, z1 = sw.runs[0].z0, sw.runs[-1].z1
    for edges, starts, z in ((bottom, ends_at[0], z0), (top, ends_at[1], z1)):
        if sectors is None:
            sewing.Add(faces.cap(edges, outer, z))
            continue
        first = list(range(0, len(edges), sectors[0]))
        for face in faces.sector_caps(edges, first, [starts[i] for i in first], sectors[1], outer, z):
            sewing.Add(face)
    if outer is not None:
        sewing.Add(faces.cylinder_face(outer, z0, z1))
    if bar is not None:
        bar.note = "sewing the faces"
        bar.update(bar.done)
    sewing.Perform()
    sewed = sewing.SewedShape()
    exp = TopExp_Explorer(sewed, TopAbs_SHELL)
    if not exp.More():
        raise GeometryError("the faces do not sew into a shell")
    shell = TopoDS.Shell(exp.Current())
    exp.Next()
    if exp.More():
        raise GeometryError("the faces sew into more than one shell")
    solid = BRepBuilderAPI_MakeSolid(shell).Solid()
    if bar is not None:
        bar.step(len(sw.curves) * len(sw.patches))
    # the sewn shell's faces agree in orientation (check_solid verifies it): a negative volume means the
    # whole shell faces inwards (a classifier's orientation costs as much as the sewing for thousands of faces)
    if volume(solid, None) < 0.0:
        solid.Reverse()
    return solid


def check_solid(shape, what: str, solids: int = 1):
    """Return ``shape`` if it is ``solids`` valid solids of positive volume; else raise GeometryError."""
    from OCP.BRepCheck import BRepCheck_Analyzer

    if count_solids(shape) != solids:
        raise GeometryError(f"{what}: {count_solids(shape)} solids where {solids} were expected")
    if not BRepCheck_Analyzer(shape).IsValid():
        raise GeometryError(f"{what}: the B-rep is not valid")
    if not volume(shape, None) > 0:
        raise GeometryError(f"{what}: the solid is empty or inside out")
    return shape


def count_solids(shape) -> int:
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer

    exp, n = TopExp_Explorer(shape, TopAbs_SOLID), 0
    while exp.More():
        n += 1
        exp.Next()
    return n


def volume(shape, eps: float | None = 1e-6) -> float:
    """Volume of a shape, mm^3 (adaptive integration to a relative error ``eps``; None: the quick
    fixed rule, good for a sign)."""
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps

    props = GProp_GProps()
    if eps is None:
        BRepGProp.VolumeProperties_s(shape, props)
    else:  # the fixed rule misjudges long B-spline faces by up to a few percent
        BRepGProp.VolumeProperties_s(shape, props, eps, False)
    return float(props.Mass())


def bounds(shape):
    """((x, y, z) min, (x, y, z) max) of a shape's tight bounding box, mm."""
    from OCP.Bnd import Bnd_Box
    from OCP.BRepBndLib import BRepBndLib

    box = Bnd_Box()
    BRepBndLib.AddOptimal_s(shape, box, False, False)
    lo, hi = box.CornerMin(), box.CornerMax()
    return (lo.X(), lo.Y(), lo.Z()), (hi.X(), hi.Y(), hi.Z())
