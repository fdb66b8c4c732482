"""gearkit: gear geometry and tooth-contact kernel.

Every public name is importable from here; modules load on first use, so ``import gearkit``
(and every ``gearkit`` command) pays only for what it touches.

Examples
--------
>>> import gearkit
>>> prof = gearkit.tooth_profile(gearkit.GearSpec(teeth=13, module=1.0))
>>> prof.undercut, round(prof.tip_thickness, 6)
(True, 0.634245)
"""
from gearkit.errors import GearkitError, GeometryError, SpecError

_PUBLIC = {
    # the generating kernel and the involute family
    "gearkit.accuracy": ("Accuracy",),
    "gearkit.profile": ("ToothProfile",),
    "gearkit.families.involute": ("BasicRack", "GearSpec", "InvoluteProfile", "Modification", "RackProfile",
                                  "RackSpec", "ShaperCutter", "rack_profile", "tooth_profile"),
    "gearkit.oracles.involute": ("swept_gear",),
    # gear pairs and design checks
    "gearkit.checks": ("CheckLimits", "CheckReport", "Finding", "PairCheck", "check_pair", "load_design"),
    "gearkit.pair": ("PairGeometry", "PairSpec", "pair_geometry", "shifts_for_center_distance"),
    # solids, meshes and export
    "gearkit.solids": ("Assembly", "Solid", "SolidSpec", "gear_solid", "pair_assembly", "rack_solid", "write_mesh"),
    # blocking contours
    "gearkit.blocking": ("BlockingAtlas", "BlockingContour", "blocking_atlas", "blocking_contour"),
    # tooth contact analysis
    "gearkit.contact": ("ContactAnalysis", "Deviations", "LoadedAnalysis", "Material", "analyse_loaded",
                        "analyse_pair", "harris_map", "pin_ring"),
    # the cycloidal family
    "gearkit.checks.cycloidal": ("check_cycloid_pair", "check_drive", "check_pin_gearing"),
    "gearkit.families.cycloidal": ("CycloidalDisc", "CycloidGear", "CycloidPairSpec", "DriveSpec", "PinGearSpec",
                                   "PinGearWheel", "cycloid_gear", "disc_profile", "pin_gear_wheel", "simulate_mesh"),
    # Novikov (circular-arc) gears
    "gearkit.checks.novikov": ("NovikovCheck", "NovikovLimits", "check_novikov"),
    "gearkit.families.novikov": ("ArcRack", "ArcSpec", "NovikovGearSpec", "NovikovPairGeometry", "NovikovPairSpec",
                                 "NovikovProfile", "RackSystem", "load_rack_system", "mesh_contact", "meshed_outlines",
                                 "novikov_pair_geometry", "rack_presets", "rack_system"),
    # scenes: placed gears, kinematics, planetary synthesis
    "gearkit.scene": ("Scene", "SceneModel", "load_scene", "scene_layout", "scene_speeds"),
    # cams
    "gearkit.families.cam": ("CamProfile", "CamSpec", "MotionProgram", "MotionSegment", "cam_profile"),
    "gearkit.checks.cam": ("CamCheck", "check_cam"),
    "gearkit.oracles.cam": ("swept_cam",),
    # the speed-accuracy bench
    "gearkit.bench": ("run_bench",),
}
_ALIASES = {"novikov_tooth_profile": ("gearkit.families.novikov", "tooth_profile"),
            "synthesize_planetary": ("gearkit.scene", "synthesize")}
__all__ = ["GearkitError", "GeometryError", "SpecError",
           *sorted([*(n for names in _PUBLIC.values() for n in names), *_ALIASES])]


def lazy_exports(package: str, modules: dict, aliases: dict | None = None):
    """``(__getattr__, __dir__)`` of a package whose public names load on first use.

    ``modules`` maps a module to the names it exports (``{"gearkit.pair.spec": ("PairSpec",)}``);
    ``aliases`` maps a name to ``(module, attribute)``. A loaded value is cached in the package, so
    the look-up runs once per name; an unknown name raises AttributeError as usual (and ``from
    package import submodule`` still imports the submodule).

    Examples
    --------
    >>> import gearkit.pair
    >>> gearkit.pair.PairSpec.__module__
    'gearkit.pair.spec'
    """
    import sys

    where = {name: (module, name) for module, names in modules.items() for name in names}
    where.update(aliases or {})
    namespace = sys.modules[package].__dict__

    def __getattr__(name):
        if name in where:
            import importlib

            module, attr = where[name]
            value = getattr(importlib.import_module(module), attr)
            namespace[name] = value
            return value
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__():
        return sorted(set(namespace) | set(where))

    return __getattr__, __dir__


__getattr__, __dir__ = lazy_exports(__name__, _PUBLIC, _ALIASES)
