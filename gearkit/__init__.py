"""gearkit: gear geometry and tooth-contact kernel."""
from gearkit.errors import GearkitError, GeometryError, SpecError

__all__ = ["GearkitError", "GeometryError", "SpecError"]

# -- the generating kernel and the involute family ------------------------------------------
from gearkit.accuracy import Accuracy  # noqa: E402
from gearkit.boundary import ToothProfile  # noqa: E402
from gearkit.families.involute import GearSpec, InvoluteProfile, tooth_profile  # noqa: E402
from gearkit.families.rack import RackProfile, RackSpec, rack_profile  # noqa: E402
from gearkit.tools import BasicRack, ShaperCutter  # noqa: E402

__all__ += ["Accuracy", "BasicRack", "GearSpec", "InvoluteProfile", "RackProfile", "RackSpec", "ShaperCutter",
            "ToothProfile", "rack_profile", "tooth_profile"]

# -- gear pairs and design checks ---------------------------------------------------------
from gearkit.checks import CheckLimits, CheckReport, Finding, PairCheck, check_pair, load_design  # noqa: E402
from gearkit.pair import PairGeometry, PairSpec, pair_geometry, shifts_for_center_distance  # noqa: E402

__all__ += ["CheckLimits", "CheckReport", "Finding", "PairCheck", "PairGeometry", "PairSpec", "check_pair",
            "load_design", "pair_geometry", "shifts_for_center_distance"]

# -- solids, meshes and export (lazy: `import gearkit` does not load manifold3d) -------------
_SOLIDS = ("Assembly", "Solid", "SolidSpec", "gear_solid", "pair_assembly", "rack_solid", "write_mesh")


def __getattr__(name):
    if name in _SOLIDS:
        import gearkit.solids

        return getattr(gearkit.solids, name)
    raise AttributeError(f"module 'gearkit' has no attribute {name!r}")


__all__ += list(_SOLIDS)

# -- the speed-accuracy bench (`gearkit bench`) ----------------------------------------------
from gearkit.bench import run_bench  # noqa: E402

__all__ += ["run_bench"]

# -- Novikov (circular-arc) gears: racks, gears, pairs, checks, transverse mesh -----------------
from gearkit.checks.novikov import NovikovCheck, NovikovLimits, check_novikov  # noqa: E402
from gearkit.families.novikov import (NovikovGearSpec, NovikovPairGeometry, NovikovPairSpec,  # noqa: E402
                                      NovikovProfile, novikov_pair_geometry)
from gearkit.families.novikov import tooth_profile as novikov_tooth_profile  # noqa: E402
from gearkit.families.novikov_mesh import mesh_contact, meshed_outlines  # noqa: E402
from gearkit.families.novikov_presets import RackSystem, load_rack_system, rack_presets, rack_system  # noqa: E402
from gearkit.families.novikov_racks import ArcRack, ArcSpec  # noqa: E402

__all__ += ["ArcRack", "ArcSpec", "NovikovCheck", "NovikovGearSpec", "NovikovLimits", "NovikovPairGeometry",
            "NovikovPairSpec", "NovikovProfile", "RackSystem", "check_novikov", "load_rack_system", "mesh_contact",
            "meshed_outlines", "novikov_pair_geometry", "novikov_tooth_profile", "rack_presets", "rack_system"]

# -- blocking contours (issue 5): admissible shifts of a pair, atlases of them ------------------
from gearkit.blocking import BlockingAtlas, BlockingContour, blocking_atlas, blocking_contour  # noqa: E402

__all__ += ["BlockingAtlas", "BlockingContour", "blocking_atlas", "blocking_contour"]

# -- the cycloidal family (issue 6): pin-wheel drives, cycloid pairs and clock gearing, pin gearing --
from gearkit.checks.cycloidal import check_cycloid_pair, check_drive, check_pin_gearing  # noqa: E402
from gearkit.families.cycloidal import (CycloidalDisc, CycloidGear, CycloidPairSpec, DriveSpec,  # noqa: E402
                                        PinGearSpec, PinGearWheel, cycloid_gear, disc_profile, pin_gear_wheel,
                                        simulate_mesh)

__all__ += ["CycloidGear", "CycloidPairSpec", "CycloidalDisc", "DriveSpec", "PinGearSpec", "PinGearWheel",
            "check_cycloid_pair", "check_drive", "check_pin_gearing", "cycloid_gear", "disc_profile",
            "pin_gear_wheel", "simulate_mesh"]

# -- tooth contact analysis (issue 8): the meshing simulation of generated profiles ----------------
from gearkit.contact import ContactAnalysis, analyse_pair, pin_ring  # noqa: E402

__all__ += ["ContactAnalysis", "analyse_pair", "pin_ring"]
