"""Gear solids from any generated profile: spur, helical, herringbone, double-helical, ring.

The mesh is built directly (numpy) and checked with numpy (:class:`~gearkit.solids.Solid`):

* **Side:** the tooth polyline of :mod:`gearkit.solids.surface`, repeated over the teeth, at
  every layer height turned by ``theta(z)``; each quad split along its planned diagonal.
* **Caps:** the end faces of :mod:`gearkit.solids.section` (cells, one per tooth, and a core), so
  the cost stays linear in the teeth. A ring's end face (outer circle, teeth as a hole) is
  triangulated whole.
* **Walls:** the bore (with keyway) and a ring's outer circle are straight prisms.

A straight (spur) gear is one section swept (:mod:`gearkit.solids.extrusion`): the same mesh,
checked and measured by its structure; a twisted one is checked as any mesh.

Frame: axis z, from 0 to the face width; tooth 0 centred on +y at z = 0.
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.accuracy import check_tol
from gearkit.errors import SpecError, check_length
from gearkit.progress import Progress
from gearkit.solids.extrusion import Wall, extruded
from gearkit.solids.section import Section, rotate
from gearkit.solids.solid import Recipe, Solid, SolidSpec, default_mesh_tol
from gearkit.solids.surface import LayerPlan, helix_angle, plan_layers, reference_radius, tooth_polyline


def circle_points(radius: float, tol: float) -> np.ndarray:
    """Counter-clockwise polygon on a circle with every chord within ``tol`` of it."""
    step = 2.0 * math.acos(max(1.0 - tol / radius, -1.0))
    n = max(8, math.ceil(2.0 * math.pi / step))
    a = 2.0 * math.pi * np.arange(n) / n
    return radius * np.stack([np.cos(a), np.sin(a)], -1)


def _sag(polygon, radius: float) -> float:
    """Largest sag (mm) of the polygon's chords between vertices on the circle of ``radius`` (the
    other edges, such as a keyway's, are exact)."""
    on = np.isclose(np.hypot(polygon[:, 0], polygon[:, 1]), radius, rtol=1e-12)
    chord = on & np.roll(on, -1)
    mid = 0.5 * (polygon + np.roll(polygon, -1, axis=0))
    return float((radius - np.hypot(mid[:, 0], mid[:, 1]))[chord].max(initial=0.0))


def bore_points(diameter: float, keyway, tol: float) -> np.ndarray:
    """Counter-clockwise bore outline (mm), a keyway (width, depth) centred on +y."""
    r = diameter / 2.0
    if keyway is None:
        return circle_points(r, tol)
    w, depth = keyway
    half = w / 2.0
    a0 = math.atan2(math.sqrt(r * r - half * half), half)  # the keyway's right edge on the circle
    sweep = 2.0 * math.pi - 2.0 * (math.pi / 2 - a0)
    n = max(8, math.ceil(sweep / (2.0 * math.acos(max(1.0 - tol / r, -1.0)))))
    a = math.pi - a0 + sweep * np.arange(n + 1) / n  # from the left edge, round the bottom
    arc = r * np.stack([np.cos(a), np.sin(a)], -1)
    top = r + depth
    return np.concatenate([[[half, top], [-half, top]], arc])


class _Mesh:
    """Vertices and faces accumulated by parts; indices are global."""

    def __init__(self):
        self.vertices, self.faces, self.size = [], [], 0

    def add(self, points2d, z) -> int:
        base = self.size
        v = np.empty((len(points2d), 3))
        v[:, :2], v[:, 2] = points2d, float(z)
        self.vertices.append(v)
        self.size += len(points2d)
        return base

    def band(self, sec: Section, zs, thetas, diagonals) -> tuple:
        """Swept teeth through the slices; returns the first and last slice's base index."""
        j = np.arange(sec.count)
        jn = (j + 1) % sec.count
        with Progress("solid", len(zs), unit="layers") as bar:
            bases = [self.add(rotate(sec.outline, thetas[0]), zs[0])]
            for s in range(len(zs) - 1):
                bases.append(self.add(rotate(sec.outline, thetas[s + 1]), zs[s + 1]))
                diag = np.tile(diagonals[1 if thetas[s + 1] >= thetas[s] else -1], sec.z).astype(bool)
                # each quad's two triangles, column by column into one array: (a, b, c) and (b, d, c) along
                # diagonal 0, (a, b, d) and (a, d, c) along 1; a ring's reversed. Corners a, b (this slice's
                # j, j + 1), c, d (the next one's) added straight into their columns
                tris = np.empty((2 * sec.count, 3), dtype=np.int64)
                k0, k1, k2 = (2, 1, 0) if sec.internal else (0, 1, 2)
                first, second = tris[:sec.count], tris[sec.count:]
                lo, hi = bases[s], bases[s + 1]
                np.add(j, lo, out=first[:, k0])
                np.add(jn, lo, out=first[:, k1])
                np.add(jn, hi, out=first[:, k2])
                np.add(j, hi, out=first[:, k2], where=diag)
                np.add(j, lo, out=second[:, k0])
                np.add(jn, lo, out=second[:, k0], where=diag)
                np.add(jn, hi, out=second[:, k1])
                np.add(j, hi, out=second[:, k2])
                self.faces.append(tris)
                bar.update(s + 2)
        return bases[0], bases[-1]

    def wall(self, poly, z0: float, z1: float, hole: bool) -> tuple:
        """A straight prism wall over a CCW polygon; returns the bottom and top ring's base index."""
        b0, b1 = self.add(poly, z0), self.add(poly, z1)
        j = np.arange(len(poly))
        a, b = b0 + j, b0 + (j + 1) % len(poly)
        c, d = a + (b1 - b0), b + (b1 - b0)
        tris = np.concatenate([np.stack([a, b, d], 1), np.stack([a, d, c], 1)])
        self.faces.append(tris[:, ::-1] if hole else tris)
        return b0, b1

    def cap(self, tris, up: bool):
        self.faces.append(tris if up else tris[:, ::-1])

    def solid(self, name: str, info: dict, recipe: Recipe | None = None) -> Solid:
        return Solid.from_arrays(np.concatenate(self.vertices), np.concatenate(self.faces), name, info, recipe)


def estimate_faces(profile, spec: SolidSpec, tol: float | None = None, plan: LayerPlan | None = None) -> int:
    """About how many facets :func:`gear_solid` would make, found cheaply before building it.

    One tooth's polyline at ``tol`` (its edge count grows as ``tol**-0.5``) times the teeth, times
    the layers the helix chord alone needs (``twist / sqrt(8 tol / r_a)``), two triangles a quad,
    plus the two end caps. Within a few percent of the real count for spur and helical gears
    (a herringbone or a bore adds a little): for refusing work that would hang, not for sizing
    buffers. Given the ``plan`` :func:`gear_plan` made (which the solid is then built from), its
    polyline and layers are counted instead of sampling the tooth again.

    Examples
    --------
    >>> from gearkit.families.involute import GearSpec, tooth_profile
    >>> prof = tooth_profile(GearSpec(12, 2.0))
    >>> n = estimate_faces(prof, SolidSpec(width=5.0), tol=0.01)
    >>> real = gear_solid(prof, SolidSpec(width=5.0), tol=0.01).faces
    >>> abs(real - n) / real < 0.05
    True
    """
    tol = default_mesh_tol(profile.module) if tol is None else check_tol(tol, profile.module)
    if plan is not None:
        ring = plan.polyline.edges * int(profile.teeth)
        twisted = helix_angle(profile, spec) != 0.0
        return int(2 * ring * (plan.layers if twisted else 1) * (2 if spec.herringbone else 1) + 2 * ring)
    beta = math.radians(helix_angle(profile, spec))
    run = (spec.width - spec.gap) / 2.0 if spec.herringbone else spec.width
    twist = abs(math.tan(beta) / reference_radius(profile, abs(beta)) * run)
    poly = tooth_polyline(profile, tol)
    r_max = float(np.hypot(poly.points[:, 0], poly.points[:, 1]).max())
    layers = max(1, math.ceil(twist / math.sqrt(8.0 * tol / r_max))) * (2 if spec.herringbone else 1)
    ring = poly.edges * int(profile.teeth)
    return int(2 * ring * layers + 2 * ring)


def gear_plan(profile, spec: SolidSpec, tol: float | None = None) -> LayerPlan:
    """How :func:`gear_solid` meshes the tooth surface of ``profile`` by ``spec`` at ``tol``: the tooth
    polyline, the layers of one helical run and the diagonals (:func:`~gearkit.solids.surface.plan_layers`).

    Planned once, it both sizes the solid (:func:`estimate_faces`) and builds it (``gear_solid(...,
    plan=plan)``): the tooth is sampled once.
    """
    tol = default_mesh_tol(profile.module) if tol is None else check_tol(tol, profile.module)
    beta = math.radians(helix_angle(profile, spec))
    k = math.tan(beta) / reference_radius(profile, abs(beta))
    run = (spec.width - spec.gap) / 2.0 if spec.herringbone else spec.width
    return plan_layers(lambda t: tooth_polyline(profile, t), tol, k * run, both_hands=spec.herringbone)


def gear_solid(profile, spec: SolidSpec, tol: float | None = None, name: str = "gear",
               plan: LayerPlan | None = None) -> Solid:
    """The solid of a generated gear.

    Parameters
    ----------
    profile : ToothProfile (any family): ``half.pieces``, ``teeth``, ``internal``, ``module``
    spec : SolidSpec
    tol : float, mm
        Largest deviation of any vertex or facet from the exact tooth surface (default
        :func:`~gearkit.solids.solid.default_mesh_tol`). ``info["achieved"]`` is the measured one.
    name : str
    plan : LayerPlan or None
        :func:`gear_plan` of the same profile, spec and tol, when made already (else planned here).

    Returns
    -------
    Solid

    Examples
    --------
    >>> from gearkit.families.involute import GearSpec, tooth_profile
    >>> s = gear_solid(tooth_profile(GearSpec(12, 2.0)), SolidSpec(width=5.0), tol=0.01)
    >>> s.achieved <= 0.01, s.volume > 0
    (True, True)
    """
    tol = default_mesh_tol(profile.module) if tol is None else check_tol(tol, profile.module)
    beta_deg = helix_angle(profile, spec)
    beta = math.radians(beta_deg)
    if spec.herringbone and beta == 0.0:
        raise SpecError("herringbone", "a herringbone gear needs a helix angle (--helix-angle-deg)")
    k = math.tan(beta) / reference_radius(profile, abs(beta))
    internal = bool(profile.internal)
    if internal and spec.bore is not None:
        raise SpecError("bore", "a ring gear has no bore (give --outer-diameter or --rim)")
    if not internal and (spec.outer_diameter is not None or spec.rim is not None):
        raise SpecError("outer_diameter" if spec.rim is None else "rim", "applies to ring (internal) gears")
    m = profile.module
    check_length(spec.width, "width", 1e-4 * m, 1e5 * m)  # magnitudes a mesh of this gear can carry
    b, gap = spec.width, spec.gap
    run = (b - gap) / 2.0 if spec.herringbone else b
    plan = gear_plan(profile, spec, tol) if plan is None else plan
    poly = plan.polyline
    radii = np.hypot(poly.points[:, 0], poly.points[:, 1])
    bore = outer = None
    if spec.bore is not None:
        if spec.bore / 2.0 >= radii.min():
            raise SpecError("bore", f"{spec.bore!r} mm must stay inside the root circle (d = {2 * radii.min():.6g} mm)")
        bore = bore_points(spec.bore, spec.keyway, tol)
        if np.hypot(bore[:, 0], bore[:, 1]).max() >= radii.min():
            raise SpecError("bore", f"the bore (and keyway) must stay inside the root circle "
                            f"(d = {2 * radii.min():.6g} mm)")
    if internal:
        r_root = float(radii.max())
        r_out = spec.outer_diameter / 2.0 if spec.outer_diameter else r_root + (spec.rim or 2.0 * profile.module)
        field = "outer_diameter" if spec.rim is None else "rim"
        if not r_root < r_out <= r_root + 1e3 * m:
            raise SpecError(field, f"the outer diameter {2 * r_out:.6g} mm must lie in ({2 * r_root:.6g}, "
                            f"{2 * (r_root + 1e3 * m):.6g}] mm (the ring's root diameter, plus a rim up to 1000 modules)")
        outer = circle_points(r_out, tol)
    sec = Section(poly, profile.teeth, internal)
    n = plan.layers if k else 1
    info = {"kind": _kind(spec, beta, internal), "teeth": int(profile.teeth), "module": float(profile.module),
            "width": float(b), "helix_angle_deg": beta_deg, "hand": _hand(beta), "tol": tol,
            "achieved": plan.achieved, "polyline_tol": poly.tol, "layers": n, "points_per_tooth": poly.edges}
    wall = bore if bore is not None else outer
    if wall is not None:
        info["achieved"] = max(info["achieved"], _sag(wall, spec.bore / 2.0 if bore is not None else r_out))
    recipe = Recipe("gear", (profile, spec, tol))
    if k == 0.0:  # a straight gear: its section swept once, the same end face at both ends
        extra, tri = sec.end_face(0.0, wall)
        walls, points = [Wall(sec.count, internal, np.tile(plan.diagonals[1], sec.z).astype(bool))], [sec.outline]
        if wall is not None:
            walls.append(Wall(len(wall), not internal))
            points.append(wall)
        return extruded(np.concatenate(points + [extra]), tri, walls, 0.0, b, name, info, recipe)
    mesh = _Mesh()
    if spec.herringbone and gap > 0.0:
        zs = np.linspace(0.0, run, n + 1)
        lo = mesh.band(sec, zs, k * zs, plan.diagonals)
        hi = mesh.band(sec, b - zs[::-1], k * zs[::-1], plan.diagonals)
        groove = _groove(profile, radii, wall, internal, tol)
        info["achieved"] = max(info["achieved"], _sag(groove, float(np.hypot(*groove[0]))))
        g0, g1 = mesh.wall(groove, run, b - run, hole=internal)
        mesh.cap(sec.face(mesh, k * run, lo[1], run, groove, g0), up=True)
        mesh.cap(sec.face(mesh, k * run, hi[0], b - run, groove, g1), up=False)
        top = 0.0
    else:
        if spec.herringbone:
            zs = np.linspace(0.0, b, 2 * n + 1)
            thetas = k * (b / 2.0 - np.abs(zs - b / 2.0))
        else:
            zs = np.linspace(0.0, b, n + 1)
            thetas = k * zs
        lo = hi = mesh.band(sec, zs, thetas, plan.diagonals)
        top = float(thetas[-1])
    w0 = w1 = 0
    if wall is not None:
        w0, w1 = mesh.wall(wall, 0.0, b, hole=not internal)
    mesh.cap(sec.face(mesh, 0.0, lo[0], 0.0, wall, w0), up=False)
    mesh.cap(sec.face(mesh, top, hi[1], b, wall, w1), up=True)
    return mesh.solid(name, info, recipe)


def _groove(profile, radii, wall, internal: bool, tol: float):
    """The groove between the halves of a double-helical gear: a module below the root circle."""
    if internal:
        r = float(radii.max()) + profile.module
        if r >= np.hypot(*wall[0]):
            raise SpecError("gap", f"the groove of a double-helical ring is cut a module beyond the root (to "
                            f"d = {2 * r:.6g} mm): the outer diameter must exceed it")
    else:
        r = float(radii.min()) - profile.module
        if r <= 0 or (wall is not None and np.hypot(wall[:, 0], wall[:, 1]).max() >= r):
            raise SpecError("gap", f"the groove of a double-helical gear is cut a module below the root (to "
                            f"d = {2 * r:.6g} mm): the bore must stay inside it")
    return circle_points(r, tol)


def _kind(spec: SolidSpec, beta: float, internal: bool) -> str:
    base = "herringbone" if spec.herringbone and not spec.gap else "double-helical" if spec.herringbone \
        else "helical" if beta else "spur"
    return f"{base} ring" if internal else base


def _hand(beta: float) -> str:
    return "right" if beta > 0 else "left" if beta < 0 else "none"
