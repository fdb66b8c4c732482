"""Straight prisms over any closed outline of exact plane curves: the way in for a new family.

A family that knows its outline exactly (a cam, a plate, a lever) as a loop of curves
``w -> (n, 2)`` (``w`` in [0, 1], each curve starting where the previous one ends; a clockwise
loop is turned round) gets a :class:`~gearkit.solids.Solid` from :func:`prism_solid`, with a bore and a
keyway if asked: the mesh is the outline sampled to ``tol``
(:func:`~gearkit.accuracy.adaptive_sample`, achieved deviation measured) and extruded by
manifold3d; its recipe rebuilds the same outline as B-spline faces for STEP
(:func:`gearkit.solids.shapes.prism_shape`). So STL, OBJ, GLB, 3MF and STEP all work.
"""
from __future__ import annotations

import math

import manifold3d as m3
import numpy as np

from gearkit.accuracy import adaptive_sample
from gearkit.errors import SpecError, require
from gearkit.solids.gear import bore_points
from gearkit.solids.solid import Recipe, Solid, SolidSpec, checked


def prism_solid(curves, spec: SolidSpec, tol: float, name: str = "part") -> Solid:
    """The prism of a closed loop of exact curves, from z = 0 to ``spec.width``.

    Parameters
    ----------
    curves : sequence of callables ``w -> (n, 2)`` mm, a closed loop (either way round)
    spec : SolidSpec (``width``, and optionally ``bore`` and ``keyway``; the gear fields stay unset)
    tol : float, mm, largest deviation of the mesh (and of the STEP faces) from the exact outline
    name : str

    Returns
    -------
    Solid (``info["achieved"]``: the measured deviation of the mesh, mm)

    Examples
    --------
    >>> import numpy as np
    >>> half = lambda a0: (lambda w: 10.0 * np.stack([np.cos(a0 + np.pi * w), np.sin(a0 + np.pi * w)], -1))
    >>> disc = prism_solid([half(0.0), half(np.pi)], SolidSpec(width=5.0), tol=1e-3)
    >>> abs(disc.volume - np.pi * 100 * 5) < 2 * np.pi * 10 * 5 * 1e-3, disc.achieved <= 1e-3
    (True, True)
    """
    require(isinstance(tol, (int, float)) and math.isfinite(tol) and tol > 0, "tol",
            f"{tol!r} must be a positive length in mm")
    if spec.helix_angle_deg not in (None, 0.0) or spec.herringbone or spec.outer_diameter or spec.rim:
        raise SpecError("solid", "a prism takes a width, a bore and a keyway only")
    curves = tuple(curves)
    if not curves:
        raise SpecError("curves", "a prism needs a closed loop of at least one curve")
    pieces, achieved = [], 0.0
    for c in curves:
        _, pts, dev = adaptive_sample(c, tol, fewest=True)
        pieces.append(pts[:-1])
        achieved = max(achieved, float(dev))
    loop = np.concatenate(pieces)
    if _signed_area(loop) < 0.0:  # a clockwise loop: the same curves run backwards
        curves = tuple(_reversed(c) for c in curves[::-1])
        loop = loop[::-1]
    gap = float(np.linalg.norm(curves[-1](np.array([1.0]))[0] - curves[0](np.array([0.0]))[0]))
    if gap > tol:
        raise SpecError("curves", f"the loop does not close: its ends are {gap:.3g} mm apart")
    loops = [np.ascontiguousarray(loop, dtype=np.float64)]
    if spec.bore is not None:
        reach = spec.bore / 2.0 + (spec.keyway[1] if spec.keyway else 0.0)
        inner = float(np.hypot(loop[:, 0], loop[:, 1]).min())
        if reach >= inner - tol:
            raise SpecError("bore", f"the bore (reaching {reach:.6g} mm from the axis) must stay inside the "
                            f"outline (nearest {inner:.6g} mm)")
        loops.append(np.ascontiguousarray(bore_points(spec.bore, spec.keyway, tol)[::-1]))
    man = checked(m3.Manifold.extrude(m3.CrossSection(loops, m3.FillRule.Positive), float(spec.width)), name)
    info = {"kind": "prism", "width": float(spec.width), "tol": float(tol), "achieved": achieved}
    return Solid(man, name, info, Recipe("prism", (curves, spec, float(tol))))


def _signed_area(p) -> float:
    return 0.5 * float(np.dot(p[:, 0], np.roll(p[:, 1], -1)) - np.dot(p[:, 1], np.roll(p[:, 0], -1)))


def _reversed(curve):
    """The same curve run from its end to its start."""
    def back(w, curve=curve):
        return curve(1.0 - np.asarray(w, dtype=float))
    return back
