"""Design checks: findings with numbers, limits and plain-language reasons.

:func:`check_pair` answers "will this pair work?" for involute external, internal and
rack-pinion pairs; :func:`load_design` reads the TOML design files of ``gearkit check``.
"""
from gearkit.checks.design_file import design_from_dict, load_design
from gearkit.checks.involute import PairCheck, check_pair, min_shift_undercut
from gearkit.checks.limits import CheckLimits, min_cutter_difference, min_teeth_undercut, min_tooth_difference
from gearkit.checks.report import STATUSES, CheckReport, Finding

__all__ = ["STATUSES", "CheckLimits", "CheckReport", "Finding", "PairCheck", "check_pair", "design_from_dict",
           "load_design", "min_cutter_difference", "min_shift_undercut", "min_teeth_undercut",
           "min_tooth_difference"]
