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
        self.field, self.reason = field, message
        super().__init__(f"{field}: {message}")

    def renamed(self, field: str) -> "SpecError":
        """The same error naming ``field`` (a command-line flag, or a field inside a larger spec).

        >>> SpecError("teeth", "2 must be at least 3").renamed("--z1")
        SpecError('--z1: 2 must be at least 3')
        """
        return SpecError(field, self.reason)


class GeometryError(GearkitError):
    """The spec is valid but the requested geometry does not exist (e.g. no tooth is left)."""


def require(condition: bool, field: str, message: str) -> None:
    """Raise ``SpecError(field, message)`` unless ``condition`` holds."""
    if not condition:
        raise SpecError(field, message)


def is_int(v) -> bool:
    """An integer input (Python or numpy), not a bool."""
    import numpy as np

    return isinstance(v, (int, np.integer)) and not isinstance(v, (bool, np.bool_))


def is_real(v) -> bool:
    """A finite real input (Python or numpy), not a bool."""
    import math

    import numpy as np

    return (isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, (bool, np.bool_))
            and math.isfinite(v))


def _kinds(annotation) -> set:
    """The names in a field's annotation (``"float | None"`` -> ``{"float", "None"}``)."""
    text = annotation if isinstance(annotation, str) else getattr(annotation, "__name__", str(annotation))
    return {k.strip() for k in text.split("|")}


#: spec class -> its fields that :func:`check_fields` checks, with their kinds (read once per class)
_TYPED: dict = {}


def _typed_fields(cls) -> tuple:
    """``(name, kinds)`` of the fields of ``cls`` whose annotation names only int, float, bool, str
    and None (a union with a class, ``RackSystem | str``, is left to the spec's own check)."""
    typed = _TYPED.get(cls)
    if typed is None:
        import dataclasses

        kinds = [(f.name, _kinds(f.type)) for f in dataclasses.fields(cls)]
        typed = _TYPED[cls] = tuple((n, k) for n, k in kinds if not k - {"int", "float", "bool", "str", "None"})
    return typed


def check_fields(spec, prefix: str = "") -> None:
    """The one type gate of every spec: each field's value must match its annotation.

    Read from the dataclass annotations: an ``int`` field takes an integer (Python or numpy, never
    a bool), a ``float`` field a finite real number (an integer or a numpy scalar too, never a bool,
    a string or a non-finite value), a ``bool`` field a boolean, a ``str`` field a string; ``None``
    only where the annotation allows it. Numpy scalars are stored as Python numbers, so what a spec
    holds is plain (hashable, JSON-ready). Other annotations (tools, tuples) are left to the spec's
    own checks, and so are unions that name one. Raises ``SpecError`` naming the first field that does not match.

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class S:
    ...     n: int
    ...     x: float = 0.0
    ...     def __post_init__(self):
    ...         check_fields(self)
    >>> import numpy as np
    >>> S(np.int64(3), np.float64(0.5))
    S(n=3, x=0.5)
    >>> S(3, "0.5")
    Traceback (most recent call last):
    ...
    gearkit.errors.SpecError: x: '0.5' (str) must be a finite real number
    >>> S(True)
    Traceback (most recent call last):
    ...
    gearkit.errors.SpecError: n: True (bool) must be an integer
    """
    import numpy as np

    for field, kinds in _typed_fields(type(spec)):
        v = getattr(spec, field)
        if v is None:
            require("None" in kinds or not kinds & {"int", "float", "bool", "str"}, prefix + field,
                    "is required (None is not allowed)")
            continue
        if "bool" in kinds:
            ok, need = isinstance(v, (bool, np.bool_)), "must be True or False"
            value = bool(v) if ok else v
        elif "int" in kinds and "float" not in kinds:
            ok, need = is_int(v), "must be an integer"
            value = int(v) if ok else v
        elif "float" in kinds:
            ok, need = is_real(v), "must be a finite real number"
            value = (int(v) if is_int(v) else float(v)) if ok else v
        elif "str" in kinds:
            ok, need, value = isinstance(v, str), "must be a string", v
        else:
            continue
        if not ok:  # the message (a repr of the value) is made only for a value refused
            raise SpecError(prefix + field, f"{v!r} ({type(v).__name__}) {need}")
        if value is not v:
            object.__setattr__(spec, field, value)


def check_count(value, field: str, lo: int, hi: int) -> int:
    """An integer argument (not a bool) in ``[lo, hi]``, as ``int``; else ``SpecError`` naming ``field``.

    >>> check_count(3, "teeth", 1, 10)
    3
    """
    require(is_int(value) and lo <= value <= hi, field, f"{value!r} must be an integer in [{lo}, {hi}]")
    return int(value)


def check_length(value, field: str, lo: float, hi: float) -> float:
    """A real argument in ``[lo, hi]`` (mm), as ``float``; else ``SpecError`` naming ``field``.

    >>> check_length(2, "width", 0.0, 10.0)
    2.0
    """
    require(is_real(value) and lo <= value <= hi, field, f"{value!r} must be a length in [{lo:.6g}, {hi:.6g}] mm")
    return float(value)


def require_cut_inputs(module, helix_angle_deg, thinning) -> None:
    """Validate the inputs every generated gear shares: normal module (mm), helix angle (degrees)
    and tooth thinning (mm); raise ``SpecError`` naming the first one out of range."""
    import math

    require(is_real(module) and 1e-4 <= module <= 1e4, "module", f"{module!r} must be a length in [0.0001, 10000] mm")
    b = helix_angle_deg
    require(is_real(b) and -60.0 < b < 60.0, "helix_angle_deg", f"{b!r} must be in (-60, 60) degrees")
    require(is_real(thinning) and 0.0 <= thinning < 0.5 * math.pi * module, "thinning",
            f"{thinning!r} must be in [0, pi*m/2) mm")
