"""The package's shape: the public ``gearkit`` names, and which module may import which.

``PUBLIC`` is the table of ``gearkit/__init__.py`` as it stood before the layout change
(issue 12): a name may be added, none may disappear or move out of ``import gearkit``.
"""
import gearkit

#: every public name of ``import gearkit`` (the lazy table plus the three errors)
PUBLIC = (
    "Accuracy", "ArcRack", "ArcSpec", "Assembly", "BasicRack", "BlockingAtlas", "BlockingContour", "CheckLimits",
    "CheckReport", "ContactAnalysis", "CycloidGear", "CycloidPairSpec", "CycloidalDisc", "DriveSpec", "Finding",
    "GearSpec", "GearkitError", "GeometryError", "InvoluteProfile", "NovikovCheck", "NovikovGearSpec",
    "NovikovLimits", "NovikovPairGeometry", "NovikovPairSpec", "NovikovProfile", "PairCheck", "PairGeometry",
    "PairSpec", "PinGearSpec", "PinGearWheel", "RackProfile", "RackSpec", "RackSystem", "ShaperCutter", "Solid",
    "SolidSpec", "SpecError", "ToothProfile", "analyse_pair", "blocking_atlas", "blocking_contour",
    "check_cycloid_pair", "check_drive", "check_novikov", "check_pair", "check_pin_gearing", "cycloid_gear",
    "disc_profile", "gear_solid", "load_design", "load_rack_system", "mesh_contact", "meshed_outlines",
    "novikov_pair_geometry", "novikov_tooth_profile", "pair_assembly", "pair_geometry", "pin_gear_wheel", "pin_ring",
    "rack_presets", "rack_profile", "rack_solid", "rack_system", "run_bench", "shifts_for_center_distance",
    "simulate_mesh", "swept_gear", "tooth_profile", "write_mesh",
)


def test_every_public_name_is_still_exported_and_resolves():
    missing = [n for n in PUBLIC if n not in gearkit.__all__]
    assert missing == []
    unresolved = [n for n in PUBLIC if getattr(gearkit, n, None) is None]
    assert unresolved == []


def test_public_names_are_the_families_own_objects():
    from gearkit.families.involute.gear import tooth_profile
    from gearkit.families.novikov.gear import tooth_profile as novikov_tooth_profile

    assert gearkit.tooth_profile is tooth_profile
    assert gearkit.novikov_tooth_profile is novikov_tooth_profile
    assert gearkit.RackSpec.__module__ == "gearkit.families.involute.rack"
