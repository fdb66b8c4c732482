"""The command line's quantities: one type and one allowed range per quantity, for every command.

A flag that sets a quantity (teeth, module, shift, helix angle, pressure angle, face width) takes
its ``type=`` from :data:`QUANTITIES`, so ``--helix-angle-deg 70`` is refused alike by ``gear``,
``check``, ``novikov`` and ``blocking``, before any work and naming the flag and the range; a spec
may narrow a range further where its family needs it (and says why). A renamed flag keeps its old
spelling working with one deprecation line (:func:`add_renamed_flag`).

Examples
--------
>>> QUANTITIES["teeth"]("20"), QUANTITIES["helix_angle_deg"]("15.5")
(20, 15.5)
>>> QUANTITIES["helix_angle_deg"]("60")
Traceback (most recent call last):
...
argparse.ArgumentTypeError: 60.0 is outside (-60, 60) degrees (helix angle)
"""
from __future__ import annotations

import math

__all__ = ["QUANTITIES", "Quantity", "add_renamed_flag"]


class Quantity:
    """The argparse ``type=`` of one quantity: parses the text and checks the allowed range.

    Parameters
    ----------
    name : str, what the quantity is (in the error line)
    kind : int or float
    lo, hi : the bounds; ``open_lo``/``open_hi`` exclude them
    unit : str, e.g. ``"mm"``, ``"degrees"``
    """

    def __init__(self, name: str, kind, lo: float, hi: float, unit: str = "", open_lo: bool = False,
                 open_hi: bool = False):
        self.name, self.kind, self.lo, self.hi, self.unit = name, kind, lo, hi, unit
        self.open_lo, self.open_hi = open_lo, open_hi
        self.__name__ = "integer" if kind is int else "number"  # argparse's "invalid <name> value"

    @property
    def range_text(self) -> str:
        """``[3, 100000]``, ``(-60, 60) degrees``: the allowed range as every error line says it."""
        text = f"{'(' if self.open_lo else '['}{self.lo:g}, {self.hi:g}{')' if self.open_hi else ']'}"
        return f"{text} {self.unit}".rstrip()

    def __call__(self, text):
        value = self.kind(text)  # ValueError: argparse says "invalid integer/number value"
        if self.kind is float and not math.isfinite(value):
            raise _refused(f"{text!r} is not a finite number ({self.name})")
        below = value <= self.lo if self.open_lo else value < self.lo
        above = value >= self.hi if self.open_hi else value > self.hi
        if below or above:
            raise _refused(f"{value!r} is outside {self.range_text} ({self.name})")
        return value

    def __repr__(self) -> str:
        return f"Quantity({self.name!r}, {self.range_text})"


#: one definition per quantity; every command's flag of that quantity uses it (a test walks them all)
QUANTITIES = {
    "teeth": Quantity("tooth number", int, 3, 100_000),
    "module": Quantity("module", float, 1e-4, 1e4, "mm"),
    "shift": Quantity("profile shift coefficient", float, -3.0, 3.0),
    "helix_angle_deg": Quantity("helix angle", float, -60.0, 60.0, "degrees", open_lo=True, open_hi=True),
    "pressure_angle_deg": Quantity("pressure angle", float, 1.0, 45.0, "degrees", open_hi=True),
    "width": Quantity("face width", float, 0.0, 1e5, "mm", open_lo=True),
    # the teeth of a rack bar laid out (not a gear's tooth number: a bar of one tooth is a bar)
    "bar_teeth": Quantity("teeth of the bar", int, 1, 100_000),
}


def _refused(message: str) -> Exception:
    """The error a ``type=`` raises for argparse to print as it is (argparse is loaded only on a refusal:
    a plain command line is read without it)."""
    import argparse

    return argparse.ArgumentTypeError(message)


def add_renamed_flag(p, old: str, new: str, dest: str, **kwargs) -> None:
    """Declare ``old`` as the deprecated spelling of ``new`` (destination ``dest``; same type): the
    action ``"renamed"`` (:class:`gearkit.cli.parser.RenamedFlag`) stores into ``dest`` and prints one
    deprecation line; it sets nothing unless typed.

    Put both in one mutually exclusive group to refuse them together."""
    p.add_argument(old, dest=dest, action="renamed", new_flag=new, help=f"deprecated: the old name of {new}",
                   **kwargs)
