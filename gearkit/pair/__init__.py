"""Involute gear pairs: specs, geometry and design from a centre distance.

``PairSpec`` holds the inputs; :func:`pair_geometry` derives the mesh (working pressure angle,
centre distance, tip diameters, path of contact, contact ratios, sliding, clearances, backlash);
:func:`shifts_for_center_distance` solves the shifts that give a centre distance; :func:`gear_specs`
gives the family's :class:`~gearkit.families.involute.GearSpec` of each gear. The internal pair's
own geometry (exit jamming, trimming, tip sweep) is :mod:`gearkit.pair.internal`.
"""
from gearkit import lazy_exports

#: module -> the names it exports (loaded on first use: importing the package costs nothing)
_EXPORTS = {
    "gearkit.pair.design": ("SPLITS", "shifts_for_center_distance"),
    "gearkit.pair.geometry": ("GearGeometry", "PairGeometry", "gear_specs", "gear_tip_diameter", "pair_geometry"),
    "gearkit.pair.spec": ("KINDS", "TIP_RULES", "PairSpec"),
}
__all__ = ["KINDS", "SPLITS", "TIP_RULES", "GearGeometry", "PairGeometry", "PairSpec", "gear_specs",
           "gear_tip_diameter", "pair_geometry", "shifts_for_center_distance"]

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
