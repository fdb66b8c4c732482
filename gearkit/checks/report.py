"""Findings and check reports: a valid but poor design is reported, never raised.

A :class:`Finding` is one verdict with its number and its limit; a :class:`CheckReport` is an
ordered, immutable collection of findings whose ``status`` is the worst of them.

Examples
--------
>>> r = CheckReport((Finding("contact_ratio", "warn", 1.12, 1.2, "eps_alpha below 1.2", "min"),))
>>> r.status, r.ok
('warn', True)
"""
from __future__ import annotations

import math

from gearkit.errors import require
from gearkit.export import json_number, text_number
from gearkit.values import frozen

__all__ = ["STATUSES", "Finding", "CheckReport", "grade"]

#: statuses from best to worst
STATUSES = ("ok", "warn", "fail")
SENSES = ("min", "max")


@frozen
class Finding:
    """One check result.

    Parameters
    ----------
    id : str
        Stable identifier, e.g. ``"pointing.1"`` (``.1``/``.2`` name the gear).
    status : {"ok", "warn", "fail"}
    value : float
        The checked quantity (unit in ``message``; ``inf`` = unbounded).
    limit : float or None
        The limit it is compared with (the warn limit when there is one).
    message : str
        Plain-language explanation a designer can act on.
    sense : {"min", "max"} or None
        Whether ``limit`` is a lower (``value >= limit`` passes) or an upper bound.
    """

    id: str
    status: str
    value: float
    limit: float | None
    message: str
    sense: str | None = None

    def __post_init__(self):
        require(self.status in STATUSES, "status", f"{self.status!r} is not one of {', '.join(STATUSES)}")
        require(self.sense is None or self.sense in SENSES, "sense", f"{self.sense!r} is not 'min' or 'max'")
        require(self.value is not None and not (isinstance(self.value, float) and math.isnan(self.value)),
                "value", f"finding {self.id!r} needs a number (got {self.value!r})")

    def to_dict(self) -> dict:
        """JSON-ready dict with the keys ``id, status, value, limit, message`` (and ``sense``)."""
        return {"id": self.id, "status": self.status, "value": json_number(self.value),
                "limit": json_number(self.limit), "message": self.message, "sense": self.sense}


def grade(value: float, *, fail_below=None, warn_below=None, fail_above=None, warn_above=None) -> str:
    """Status of ``value`` against optional fail/warn bounds (strict comparisons).

    Examples
    --------
    >>> grade(1.1, fail_below=1.0, warn_below=1.2), grade(0.9, fail_below=1.0)
    ('warn', 'fail')
    """
    if (fail_below is not None and value < fail_below) or (fail_above is not None and value > fail_above):
        return "fail"
    if (warn_below is not None and value < warn_below) or (warn_above is not None and value > warn_above):
        return "warn"
    return "ok"


@frozen
class CheckReport:
    """Ordered findings; the report's ``status`` is the worst finding's."""

    findings: tuple

    def __post_init__(self):
        object.__setattr__(self, "findings", tuple(self.findings))
        ids = [f.id for f in self.findings]
        require(len(ids) == len(set(ids)), "findings", f"duplicate finding ids in {ids}")

    @property
    def status(self) -> str:
        """Worst status (``"ok"`` for an empty report)."""
        return max((f.status for f in self.findings), key=STATUSES.index, default="ok")

    @property
    def ok(self) -> bool:
        """True when no finding fails."""
        return self.status != "fail"

    @property
    def failures(self) -> tuple:
        return tuple(f for f in self.findings if f.status == "fail")

    @property
    def warnings(self) -> tuple:
        return tuple(f for f in self.findings if f.status == "warn")

    def __getitem__(self, finding_id: str) -> Finding:
        for f in self.findings:
            if f.id == finding_id:
                return f
        raise KeyError(finding_id)

    def __contains__(self, finding_id: str) -> bool:
        return any(f.id == finding_id for f in self.findings)

    def __iter__(self):
        return iter(self.findings)

    def __len__(self) -> int:
        return len(self.findings)

    def to_dict(self) -> dict:
        return {"ok": self.ok, "status": self.status, "findings": [f.to_dict() for f in self.findings]}


#: magnitudes below this (mm, or a plain ratio) are round-off of a zero and print as 0
ROUND_OFF = 1e-12


def _cell(v, width: int) -> str:
    """A table number: 4 decimals, small magnitudes in exponent form, no "-0.0000", blank for None."""
    if v is None:
        return " " * width
    v = float(v)
    if not math.isfinite(v):
        return text_number(v, f"{width}")
    if abs(v) < ROUND_OFF:  # a zero computed through round-off is a zero
        v = 0.0
    if 0 < abs(v) < 5e-4:
        return f"{v:{width}.2e}"
    return f"{(0.0 if abs(v) < 5e-5 else v):{width}.4f}"


def format_findings(report: "CheckReport", id_width: int = 22) -> list:
    """The findings of a report as the compact table every ``gearkit`` command prints: one line a
    finding with failures marked ``!! FAIL``, then the overall result line."""
    lines = [f"     status  {'check':<{id_width}}    value      limit  note"]
    for f in report:
        mark = {"fail": "!! FAIL  ", "warn": " ! warn  ", "ok": "   ok    "}[f.status]
        bound = {"min": ">=", "max": "<="}.get(f.sense, "  ")
        lines.append(f"  {mark}{f.id:<{id_width}}{_cell(f.value, 10)} {bound}{_cell(f.limit, 9)}  {f.message}")
    lines.append(f"result: {report.status.upper()} ({len(report.failures)} failing, {len(report.warnings)} warning"
                 f"{'' if len(report.warnings) == 1 else 's'})")
    return lines
