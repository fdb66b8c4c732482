"""Parts of a cycloidal drive (and of cycloid and pin gear pairs) as 2D loops and solids.

The drive in its own frame (mm): the pin ring's centre at the origin, the disc's centre at
``e`` along the crank, the disc placed at relative angle 0 (the mesh frame of
:mod:`gearkit.families.cycloidal.mesh` moved to the ring centre). Output mechanism: ``n`` pins
of radius ``r_w`` on the circle ``R_w`` about the ring's axis run in holes of radius
``r_w + e`` on the same circle about the disc's centre (each pin touches its hole). The pin
ring's housing holds the pins from outside (inner radius ``R_Z + r_Z``).

Solids go through :mod:`gearkit.solids` (imported when a solid is asked for): the disc is a
:func:`~gearkit.solids.gear_solid` of the generated disc with its bore, minus the output holes;
pins, output pins and the housing are prisms.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearkit.errors import SpecError, require
from gearkit.families.cycloidal.disc import disc_profile
from gearkit.families.cycloidal.drive import DriveSpec, _phase

__all__ = ["OutputMechanism", "drive_loops", "drive_parts", "disc_solid", "circle", "prism"]


def circle(centre, radius: float, tol: float, clockwise: bool = False):
    """Closed polygon of a circle (every chord within ``tol``), ``(n, 2)`` mm, counter-clockwise."""
    n = max(12, int(math.ceil(math.pi / math.acos(max(-1.0, 1.0 - tol / radius)))))
    t = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
    if clockwise:
        t = -t
    return np.asarray(centre, dtype=float) + radius * np.stack([np.cos(t), np.sin(t)], -1)


@dataclass(frozen=True)
class OutputMechanism:
    """Output pins and the disc's bore, mm (None: derived from the disc's root radius r_f).

    Defaults: ``count`` 6, pin circle ``0.6 r_f``, pin radius ``0.08 r_f``, bore ``0.25 r_f``.
    """

    count: int = 6
    pin_circle_radius: float | None = None
    pin_radius: float | None = None
    bore_radius: float | None = None

    def resolve(self, spec: DriveSpec):
        """(count, R_w, r_w, hole radius r_w + e, bore radius), checked to fit inside the disc."""
        require(isinstance(self.count, int) and 0 <= self.count <= 64, "output_pins",
                f"{self.count!r} must be an integer in [0, 64]")
        rf = spec.pin_circle_radius - spec.eccentricity - spec.pin_radius
        rw_c = 0.6 * rf if self.pin_circle_radius is None else float(self.pin_circle_radius)
        rw = 0.08 * rf if self.pin_radius is None else float(self.pin_radius)
        bore = 0.25 * rf if self.bore_radius is None else float(self.bore_radius)
        hole = rw + spec.eccentricity
        for name, v in (("output_pin_circle_radius", rw_c), ("output_pin_radius", rw), ("bore", bore)):
            require(math.isfinite(v) and v > 0, name, f"{v!r} must be a positive length in mm")
        if spec.sign > 0 and self.count:
            wall = 0.02 * rf
            require(rw_c + hole + wall < rf, "output_pin_circle_radius",
                    f"the output holes (radius {hole:.6g} mm on {rw_c:.6g} mm) must stay inside the disc's root "
                    f"circle r_f = {rf:.6g} mm")
            require(rw_c - hole - wall > bore, "bore", f"the bore (radius {bore:.6g} mm) runs into the output holes")
            if self.count > 1:
                require(2.0 * rw_c * math.sin(math.pi / self.count) > 2.0 * hole + wall, "output_pins",
                        f"{self.count} holes of radius {hole:.6g} mm do not fit on the circle {rw_c:.6g} mm")
        return self.count, rw_c, rw, hole, bore


def _disc_offset(spec: DriveSpec):
    """The disc centre in the drive frame (ring centre at the origin), mm."""
    ph = _phase(spec)
    return spec.eccentricity * np.array([math.sin(ph), math.cos(ph)])


def drive_loops(spec: DriveSpec, tol: float, output: OutputMechanism = OutputMechanism(), placed: bool = False):
    """The disc as closed 2D loops: its outline, then its bore and output holes (disc frame, or the
    drive frame with ``placed``). For a ring (dz < 0): its tooth outline only."""
    disc = disc_profile(spec)
    loops = [disc.outline(tol)]
    if spec.sign > 0:
        count, rw_c, _, hole, bore = output.resolve(spec)
        loops.append(circle((0.0, 0.0), bore, tol, clockwise=True))
        for j in range(count):
            a = 2.0 * math.pi * j / max(count, 1)
            loops.append(circle(rw_c * np.array([math.sin(a), math.cos(a)]), hole, tol, clockwise=True))
    if placed:
        loops = [lp + _disc_offset(spec) for lp in loops]
    return loops


def prism(loops, z0: float, z1: float, name: str):
    """A solid prism of closed, convex-or-annular polygon loops: one loop (a convex polygon, fan
    caps) or two loops with the same vertex count (an annulus: outer counter-clockwise first)."""
    from gearkit.solids import Solid

    loops = [np.asarray(lp, dtype=float) for lp in loops]
    n = len(loops[0])
    verts, faces = [], []
    for lp in loops:
        verts += [np.column_stack([lp, np.full(n, z0)]), np.column_stack([lp, np.full(n, z1)])]
    v = np.concatenate(verts)
    for k, lp in enumerate(loops):
        b0, b1 = 2 * k * n, 2 * k * n + n
        i = np.arange(n)
        j = (i + 1) % n
        side = np.concatenate([np.stack([b0 + i, b0 + j, b1 + j], -1), np.stack([b0 + i, b1 + j, b1 + i], -1)])
        faces.append(side if k == 0 else side[:, ::-1])
    i = np.arange(n)
    j = (i + 1) % n
    if len(loops) == 1:
        c = len(v)
        v = np.concatenate([v, [[*loops[0].mean(axis=0), z0], [*loops[0].mean(axis=0), z1]]])
        faces.append(np.stack([np.full(n, c), j, i], -1))
        faces.append(np.stack([np.full(n, c + 1), n + i, n + j], -1))
    else:
        o0, o1, h0, h1 = 0, n, 2 * n, 3 * n
        faces.append(np.concatenate([np.stack([o0 + i, h0 + j, o0 + j], -1), np.stack([o0 + i, h0 + i, h0 + j], -1)]))
        faces.append(np.concatenate([np.stack([o1 + i, o1 + j, h1 + j], -1), np.stack([o1 + i, h1 + j, h1 + i], -1)]))
    return Solid.from_arrays(v, np.concatenate(faces), name, {"kind": "prism"})


def _cylinders(centres, radius, z0, z1, tol, name):
    parts = [prism([circle(c, radius, tol)], z0, z1, name) for c in centres]
    man = parts[0].manifold
    for p in parts[1:]:
        man = man + p.manifold
    from gearkit.solids import Solid
    from gearkit.solids.solid import Recipe

    recipe = Recipe("cylinders", ([tuple(map(float, c)) for c in centres], float(radius), float(z0), float(z1)))
    return Solid(man, name, {"kind": "pins", "count": len(parts)}, recipe)


def disc_solid(spec: DriveSpec, width: float, tol: float, output: OutputMechanism = OutputMechanism()):
    """The generated disc (or ring) as a solid: bore and output holes cut through it (disc frame)."""
    from gearkit.solids import Solid, SolidSpec, gear_solid

    disc = disc_profile(spec)
    if spec.sign < 0:
        return gear_solid(disc, SolidSpec(width=width), tol=tol, name="ring")
    count, rw_c, _, hole, bore = output.resolve(spec)
    body = gear_solid(disc, SolidSpec(width=width, bore=2.0 * bore), tol=tol, name="disc")
    if not count:
        return body
    centres = [rw_c * np.array([math.sin(2 * math.pi * j / count), math.cos(2 * math.pi * j / count)])
               for j in range(count)]
    holes = _cylinders(centres, hole, -width, 2.0 * width, tol, "holes")
    info = dict(body.info)
    info.update({"output_holes": count, "hole_radius": hole})
    from gearkit.solids.solid import Recipe

    return Solid(body.manifold - holes.manifold, "disc", info, Recipe("difference", (body.recipe, holes.recipe)))


def drive_parts(spec: DriveSpec, width: float, tol: float, output: OutputMechanism = OutputMechanism()):
    """The drive's parts as solids in the drive frame: disc (or ring), pins, housing, output pins."""
    if not (math.isfinite(width) and width > 0):
        raise SpecError("width", f"{width!r} must be a positive length in mm")
    off = _disc_offset(spec)
    disc = disc_solid(spec, width, tol, output).placed(0.0, (float(off[0]), float(off[1]), 0.0))
    ph = _phase(spec)
    big_r, r = spec.pin_circle_radius, spec.pin_radius
    beta = ph - 2.0 * math.pi * np.arange(spec.pins) / spec.pins
    centres = big_r * np.stack([np.sin(beta), np.cos(beta)], -1)
    pins = _cylinders(centres, r, -0.1 * width, 1.1 * width, tol, "pins")
    parts = [disc, pins]
    if spec.sign > 0:
        inner = big_r + r
        outer = inner + max(2.0 * r, 0.1 * big_r)
        n = max(len(circle((0, 0), outer, tol)), len(circle((0, 0), inner, tol)))
        t = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
        ring = [outer * np.stack([np.cos(t), np.sin(t)], -1), inner * np.stack([np.cos(t), np.sin(t)], -1)]
        from gearkit.solids.solid import Recipe

        housing = prism(ring, -0.1 * width, 1.1 * width, "housing")
        housing.recipe = Recipe("tube", (inner, outer, -0.1 * width, 1.1 * width))
        parts.append(housing)
        count, rw_c, rw, _, _ = output.resolve(spec)
        if count:
            oc = [rw_c * np.array([math.sin(2 * math.pi * j / count), math.cos(2 * math.pi * j / count)])
                  for j in range(count)]
            parts.append(_cylinders(oc, rw, -0.2 * width, 1.2 * width, tol, "output_pins"))
    return parts
