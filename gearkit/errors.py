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


def is_int(v) -> bool:
    """An integer input (Python or numpy), not a bool."""
    import numpy as np

    return isinstance(v, (int, np.integer)) and not isinstance(v, bool)


def is_real(v) -> bool:
    """A finite real input (Python or numpy), not a bool."""
    import math

    import numpy as np

    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool) and math.isfinite(v)


def require_cut_inputs(module, helix_angle_deg, thinning) -> None:
    """Validate the inputs every generated gear shares: normal module (mm), helix angle (degrees)
    and tooth thinning (mm); raise ``SpecError`` naming the first one out of range."""
    import math

    ok_m = isinstance(module, (int, float)) and not isinstance(module, bool) and math.isfinite(module)
    require(ok_m and 1e-4 <= module <= 1e4, "module", f"{module!r} must be a length in [0.0001, 10000] mm")
    b = helix_angle_deg
    require(math.isfinite(b) and -80.0 < b < 80.0, "helix_angle_deg", f"{b!r} must be in (-80, 80) degrees")
    require(math.isfinite(thinning) and 0.0 <= thinning < 0.5 * math.pi * module, "thinning",
            f"{thinning!r} must be in [0, pi*m/2) mm")
