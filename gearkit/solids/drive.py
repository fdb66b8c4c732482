"""A cycloidal drive's parts as solids: the disc (or ring) with its bore and output holes, pins, housing.

The 2D parts are :mod:`gearkit.families.cycloidal.assembly` (same drive frame: the pin ring's centre at
the origin, the disc's centre at ``e`` along the crank): the disc is a :func:`~gearkit.solids.gear_solid`
of the generated disc with its bore, minus the output holes; pins, output pins and the housing are
prisms (:func:`prism`, :func:`cylinders`).
"""
from __future__ import annotations

import math

import numpy as np

from gearkit.errors import SpecError
from gearkit.families.cycloidal.assembly import (OutputMechanism, circle, disc_offset, output_pin_centres,
                                                 pin_centres)
from gearkit.families.cycloidal.disc import disc_profile
from gearkit.families.cycloidal.drive import DriveSpec
from gearkit.solids.gear import gear_solid
from gearkit.solids.solid import Recipe, Solid, SolidSpec

__all__ = ["cylinders", "disc_solid", "drive_parts", "prism"]


def prism(loops, z0: float, z1: float, name: str):
    """A solid prism of closed, convex-or-annular polygon loops: one loop (a convex polygon, fan
    caps) or two loops with the same vertex count (an annulus: outer counter-clockwise first)."""
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


def cylinders(centres, radius: float, z0: float, z1: float, tol: float, name: str):
    """Pins: one solid of circular prisms of ``radius`` about each of ``centres`` from ``z0`` to ``z1``, mm."""
    parts = [prism([circle(c, radius, tol)], z0, z1, name) for c in centres]
    man = parts[0].manifold
    for p in parts[1:]:
        man = man + p.manifold
    recipe = Recipe("cylinders", ([tuple(map(float, c)) for c in centres], float(radius), float(z0), float(z1)))
    return Solid(man, name, {"kind": "pins", "count": len(parts)}, recipe)


def disc_solid(spec: DriveSpec, width: float, tol: float, output: OutputMechanism = OutputMechanism()):
    """The generated disc (or ring) as a solid: bore and output holes cut through it (disc frame)."""
    disc = disc_profile(spec)
    if spec.sign < 0:
        return gear_solid(disc, SolidSpec(width=width), tol=tol, name="ring")
    count, rw_c, _, hole, bore = output.resolve(spec)
    body = gear_solid(disc, SolidSpec(width=width, bore=2.0 * bore), tol=tol, name="disc")
    if not count:
        return body
    holes = cylinders(output_pin_centres(count, rw_c), hole, -width, 2.0 * width, tol, "holes")
    info = dict(body.info)
    info.update({"output_holes": count, "hole_radius": hole})
    return Solid(body.manifold - holes.manifold, "disc", info, Recipe("difference", (body.recipe, holes.recipe)))


def drive_parts(spec: DriveSpec, width: float, tol: float, output: OutputMechanism = OutputMechanism()):
    """The drive's parts as solids in the drive frame: disc (or ring), pins, housing, output pins."""
    if not (math.isfinite(width) and width > 0):
        raise SpecError("width", f"{width!r} must be a positive length in mm")
    off = disc_offset(spec)
    disc = disc_solid(spec, width, tol, output).placed(0.0, (float(off[0]), float(off[1]), 0.0))
    big_r, r = spec.pin_circle_radius, spec.pin_radius
    pins = cylinders(pin_centres(spec), r, -0.1 * width, 1.1 * width, tol, "pins")
    parts = [disc, pins]
    if spec.sign > 0:
        inner = big_r + r
        outer = inner + max(2.0 * r, 0.1 * big_r)
        n = max(len(circle((0, 0), outer, tol)), len(circle((0, 0), inner, tol)))
        t = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
        ring = [outer * np.stack([np.cos(t), np.sin(t)], -1), inner * np.stack([np.cos(t), np.sin(t)], -1)]
        housing = prism(ring, -0.1 * width, 1.1 * width, "housing")
        housing.recipe = Recipe("tube", (inner, outer, -0.1 * width, 1.1 * width))
        parts.append(housing)
        count, rw_c, rw, _, _ = output.resolve(spec)
        if count:
            parts.append(cylinders(output_pin_centres(count, rw_c), rw, -0.2 * width, 1.2 * width, tol, "output_pins"))
    return parts
