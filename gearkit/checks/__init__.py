"""Design checks: findings with numbers, limits and plain-language reasons."""
from gearkit.checks.report import STATUSES, CheckReport, Finding

__all__ = ["STATUSES", "CheckReport", "Finding"]
