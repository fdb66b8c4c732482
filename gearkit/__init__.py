"""gearkit: gear geometry and tooth-contact kernel."""
from gearkit.errors import GearkitError, GeometryError, SpecError

__all__ = ["GearkitError", "GeometryError", "SpecError"]
