"""Cam solids: the generated cam profile extruded to its width, with a bore (and keyway).

The outline is :meth:`~gearkit.families.cam.CamProfile.outline` at ``tol``; the bore comes from
:func:`~gearkit.solids.gear.bore_points` (the same bore and keyway as a gear's). manifold3d
extrudes the cross section and checks the solid. The side wall is exact in z, so the solid's
deviation from the exact cam is the larger of the outline's and the bore's chord deviations.
"""
from __future__ import annotations

import math

import manifold3d as m3
import numpy as np

from gearkit.errors import SpecError
from gearkit.solids.gear import bore_points
from gearkit.solids.solid import Recipe, Solid, SolidSpec, checked

__all__ = ["cam_solid"]


def cam_solid(profile, spec: SolidSpec, tol: float | None = None, name: str = "cam") -> Solid:
    """The cam as a watertight solid: axis z from 0 to ``spec.width``, cam frame at z = 0.

    Parameters
    ----------
    profile : CamProfile
    spec : SolidSpec
        ``width`` and optionally ``bore`` and ``keyway`` (the other fields are for gears and must be
        left at their defaults).
    tol : float, mm (default 1e-4 of prime radius + stroke)

    Examples
    --------
    >>> from gearkit.families.cam import CamSpec, MotionProgram, cam_profile
    >>> prof = cam_profile(CamSpec(40.0, MotionProgram.rise_dwell_return(10.0, 90.0, 30.0, 90.0), roller_radius=8.0))
    >>> solid = cam_solid(prof, SolidSpec(width=10.0, bore=12.0), tol=0.01)
    >>> round(solid.volume / 10.0 / (solid.info["area"]), 6)
    1.0
    """
    cam = profile.spec
    if tol is None:
        tol = 1e-4 * (cam.prime_radius + cam.stroke)
    if not (isinstance(tol, (int, float)) and math.isfinite(tol) and tol > 0):
        raise SpecError("tol", f"{tol!r} must be a positive length in mm")
    if spec.helix_angle_deg not in (None, 0.0) or spec.herringbone or spec.outer_diameter or spec.rim:
        raise SpecError("solid", "a cam solid takes a width, a bore and a keyway only")
    outline = profile.outline(tol)
    loops = [outline]
    base = profile.radii()[0]
    if spec.bore is not None:
        reach = spec.bore / 2.0 + (spec.keyway[1] if spec.keyway else 0.0)
        if reach >= base - tol:
            raise SpecError("bore", f"the bore (reaching {reach:.6g} mm from the axis) must stay inside the cam's "
                            f"smallest radius {base:.6g} mm")
        loops.append(bore_points(spec.bore, spec.keyway, tol)[::-1])
    section = m3.CrossSection([np.ascontiguousarray(lp) for lp in loops], m3.FillRule.Positive)
    area = float(section.area())
    man = checked(m3.Manifold.extrude(section, float(spec.width)), name)
    info = {"kind": "cam", "tol": tol, "achieved": profile.achieved(tol), "area": area, "width": float(spec.width),
            "bore": spec.bore, "points": int(len(outline))}
    # the exact pieces rebuild it as B-spline faces for STEP (gearkit.solids.shapes.prism_shape)
    return Solid(man, name, info, Recipe("prism", (tuple(profile.pieces), spec, float(tol))))
