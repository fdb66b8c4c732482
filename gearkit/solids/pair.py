"""Gear pairs as solids: placed at their centre distance, phased, exported, tested for interference.

Frame (at pinion rotation 0): the pinion on the z axis with a tooth centred on +x; the wheel
centred at (a, 0) and the ring at (-a, 0), each with a tooth space centred on the line of
centres facing the pinion's tooth; a rack with its datum line at x = a, teeth pointing -x,
running along y, a tooth space centred on y = 0. Both flanks then see the same backlash.
Turning the pinion by ``angle`` (counter-clockwise, rad) turns the wheel by
``-angle z1/z2``, the ring by ``+angle z1/z2`` and moves the rack by ``r1 angle`` along +y
(``r1``: the pinion's reference radius, on which the rack's datum line rolls). Helical gears
keep these relations at every height because each gear's twist follows its own helix.

**Interference** is the volume of the intersection of the two placed solids (manifold3d
boolean), mm^3: zero for a pair that runs freely.
"""
from __future__ import annotations

import math
from contextlib import contextmanager
from dataclasses import dataclass, replace

import numpy as np

from gearkit.errors import SpecError
from gearkit.progress import Progress
from gearkit.solids.gear import gear_solid
from gearkit.solids.rack import rack_solid
from gearkit.solids.solid import SolidSpec, default_mesh_tol

PART_NAMES = {"external": ("pinion", "wheel"), "internal": ("pinion", "ring"), "rack": ("pinion", "rack")}


@dataclass(frozen=True)
class Assembly:
    """Two solids that mesh: each in its own frame, with the placement rule of the module notes.

    Attributes
    ----------
    kind : "external", "internal" or "rack"
    parts : (Solid, Solid), pinion first, each in its own frame (a gear on its axis, tooth 0 on +y)
    center_distance : float, mm (rack: pinion axis to the rack's datum line)
    teeth : (int, int or None)
    pinion_radius : float, mm, reference radius r1 (the rack's rolling radius)
    rack_pitch : float or None, mm (transverse)
    """

    kind: str
    parts: tuple
    center_distance: float
    teeth: tuple
    pinion_radius: float
    rack_pitch: float | None = None

    def moved(self, center_distance: float) -> "Assembly":
        """The same solids at another centre distance (same phasing)."""
        if not (math.isfinite(center_distance) and center_distance > 0):
            raise SpecError("center_distance", f"{center_distance!r} must be a positive length in mm")
        return replace(self, center_distance=float(center_distance))

    def placed(self, angle: float = 0.0) -> tuple:
        """Both solids in the pair frame with the pinion turned by ``angle`` (rad)."""
        pinion, other = self.parts
        a = self.center_distance
        first = pinion.placed(-math.pi / 2 + angle)
        if self.kind == "rack":
            second = other.placed(math.pi / 2, (a, self.pinion_radius * angle - self.rack_pitch / 2, 0.0))
        else:
            z1, z2 = self.teeth
            if self.kind == "external":
                second = other.placed(math.pi / 2 + math.pi / z2 - angle * z1 / z2, (a, 0.0, 0.0))
            else:
                second = other.placed(-math.pi / 2 + math.pi / z2 + angle * z1 / z2, (-a, 0.0, 0.0))
        return first, second

    def interference(self, angle: float = 0.0) -> float:
        """Volume (mm^3) of the intersection of the two solids with the pinion turned by ``angle`` (rad)."""
        first, second = self.placed(angle)
        return float((first.manifold ^ second.manifold).volume())

    def sweep(self, angles) -> np.ndarray:
        """Interference volume (mm^3) at each pinion angle (rad)."""
        angles = np.atleast_1d(angles)
        out = np.empty(len(angles))
        with Progress("sweep", len(angles), unit="rotations") as bar:
            for k, t in enumerate(angles):
                out[k] = self.interference(float(t))
                bar.update(k + 1)
        return out

    def summary(self) -> dict:
        return {"kind": self.kind, "center_distance": self.center_distance,
                "tol": max(p.info["tol"] for p in self.parts),
                "achieved": max(p.achieved for p in self.parts),
                "faces": sum(p.faces for p in self.parts),
                "parts": [p.summary() for p in self.parts]}

    def export(self, path, angle: float = 0.0, ascii: bool = False):
        """Write the placed pair (OBJ with named parts, GLB, or STL) atomically."""
        from gearkit.solids.export import write_mesh

        return write_mesh(path, self.placed(angle), ascii=ascii)


def pair_assembly(spec, width: float | None = None, tol: float | None = None, *, herringbone: bool = False,
                  gap: float = 0.0, bores=(None, None), keyways=(None, None), outer_diameter: float | None = None,
                  rim: float | None = None, rack_length: float | None = None,
                  rack_height: float | None = None) -> Assembly:
    """Build both gears of a :class:`~gearkit.pair.PairSpec` as solids, placed and phased.

    Parameters
    ----------
    spec : PairSpec (its tip diameters, shifts, tools and thinning make the gears)
    width : float, mm, face width (default ``spec.face_width``)
    tol : float, mm, mesh tolerance of both parts
    herringbone, gap : double-helical gears (not for a rack pair)
    bores, keyways : per gear, bore diameter and keyway (width, depth), mm (a ring takes none)
    outer_diameter, rim : the ring's outer diameter or rim thickness, mm
    rack_length, rack_height : mm (default: twice the pinion's tip diameter; tooth depth + 2 modules)

    Returns
    -------
    Assembly
    """
    from gearkit.pair import gear_specs
    from gearkit.families.involute import tooth_profile
    from gearkit.pair import pair_geometry

    b = spec.face_width if width is None else width
    if b is None:
        raise SpecError("width", "give the face width (or the pair's face_width)")
    tol = default_mesh_tol(spec.module) if tol is None else tol
    geo = pair_geometry(spec)
    names = PART_NAMES[spec.kind]
    specs = gear_specs(spec)
    pinion_prof = tooth_profile(specs[0])
    with _naming(1):
        pinion = gear_solid(pinion_prof, SolidSpec(b, None, herringbone, gap, bores[0], keyways[0]), tol, names[0])
    r1 = pinion_prof.reference_diameter / 2.0
    if spec.kind == "rack":
        if herringbone:
            raise SpecError("herringbone", "a herringbone rack is not built; use a helical pair")
        if bores[1] is not None:
            raise SpecError("bores", "a rack has no bore")
        from gearkit.families.involute.rack import RackSpec, rack_profile

        prof = rack_profile(RackSpec(spec.module, spec.tools[1], spec.helix_angle_deg, spec.thinning2))
        length = 2.0 * geo.gears[0].tip_diameter if rack_length is None else rack_length
        height = (prof.tip_height - prof.root_height + 2.0 * spec.module) if rack_height is None else rack_height
        other = rack_solid(prof, length, height, b, tol, start=prof.pitch / 2.0 - length / 2.0, name=names[1])
        return Assembly("rack", (pinion, other), geo.center_distance, (spec.teeth1, None), r1, prof.pitch)
    internal = spec.kind == "internal"
    if internal and bores[1] is not None:
        raise SpecError("bores", "a ring gear has no bore")
    body = SolidSpec(b, None, herringbone, gap, None if internal else bores[1], None if internal else keyways[1],
                     outer_diameter if internal else None, rim if internal else None)
    with _naming(2):
        other = gear_solid(tooth_profile(specs[1]), body, tol, names[1])
    return Assembly(spec.kind, (pinion, other), geo.center_distance, (spec.teeth1, spec.teeth2), r1)


@contextmanager
def _naming(gear: int):
    """Name the gear a SpecError's field belongs to (``gear2.bore``)."""
    try:
        yield
    except SpecError as exc:
        raise SpecError(f"gear{gear}.{exc.field}", str(exc).split(": ", 1)[-1]) from None


def pinion_pitch_angle(assembly: Assembly) -> float:
    """One angular pitch of the pinion, rad (the interference pattern repeats with it)."""
    return 2.0 * math.pi / assembly.teeth[0]


__all__ = ["Assembly", "PART_NAMES", "pair_assembly", "pinion_pitch_angle"]
