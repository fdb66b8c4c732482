"""gearkit: gear geometry and tooth-contact kernel."""
from gearkit.errors import GearkitError, GeometryError, SpecError

__all__ = ["GearkitError", "GeometryError", "SpecError"]

# -- gear pairs and design checks ---------------------------------------------------------
from gearkit.checks import CheckLimits, CheckReport, Finding, PairCheck, check_pair, load_design  # noqa: E402
from gearkit.pair import PairGeometry, PairSpec, pair_geometry, shifts_for_center_distance  # noqa: E402

__all__ += ["CheckLimits", "CheckReport", "Finding", "PairCheck", "PairGeometry", "PairSpec", "check_pair",
            "load_design", "pair_geometry", "shifts_for_center_distance"]
