"""Exceptions raised by gearkit.

``SpecError`` is raised for input a user must change (it names the field and the
allowed range); ``GeometryError`` for a valid spec whose geometry cannot be built.
A valid but poor design never raises: it is reported by the checks.
"""


class GearkitError(Exception):
    """Base class of every error gearkit raises on purpose."""


class SpecError(GearkitError, ValueError):
    """Invalid input: the message names the field, its value and the allowed range."""

    def __init__(self, field: str, message: str):
        self.field = field
        super().__init__(f"{field}: {message}")


class GeometryError(GearkitError):
    """The spec is valid but the requested geometry does not exist (e.g. no tooth is left)."""


def require(condition: bool, field: str, message: str) -> None:
    """Raise ``SpecError(field, message)`` unless ``condition`` holds."""
    if not condition:
        raise SpecError(field, message)
