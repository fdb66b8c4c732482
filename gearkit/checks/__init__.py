"""Design checks: findings with numbers, limits and plain-language reasons.

:func:`check_pair` answers "will this pair work?" for involute external, internal and
rack-pinion pairs; :func:`load_design` reads the TOML design files of ``gearkit check``.
"""
from gearkit import lazy_exports

#: module -> the names it exports (loaded on first use: importing the package costs nothing)
_EXPORTS = {
    "gearkit.checks.design_file": ("design_from_dict", "load_design"),
    "gearkit.checks.involute": ("PairCheck", "check_pair", "min_shift_undercut"),
    "gearkit.checks.limits": ("CheckLimits", "min_cutter_difference", "min_teeth_undercut", "min_tooth_difference"),
    "gearkit.checks.report": ("STATUSES", "CheckReport", "Finding"),
}
__all__ = ["STATUSES", "CheckLimits", "CheckReport", "Finding", "PairCheck", "check_pair", "design_from_dict",
           "load_design", "min_cutter_difference", "min_shift_undercut", "min_teeth_undercut",
           "min_tooth_difference"]

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
